//! The assembled model: components on numbered coordinates, the sparse pattern built once, and
//! [`Integrable::eval`] as loops over components. Dimension-free: a [`Space`] supplies the
//! vector types, the components supply the physics.
//!
//! Unknowns: `q` (n free coordinates, held ones eliminated), `λ` (m constraint multipliers).
//! Equations: `s_d·(M(q) q̈ + f(q, q̇) − f_ext(q)) + Φ_qᵀ λ̃ = 0` and `Φ(q) = 0`, where `s_d` is a
//! row scale chosen by the integrator (βh² for generalized-α, 1 for statics) and λ̃ the
//! correspondingly scaled multiplier. The Newton matrix is
//! `c_a·M + c_v·C + c_x·K + Σλ̃_i ∂²Φ_i` in a pattern fixed at build.
//!
//! Summation order (fixed, so that the same inputs give the same bits): elements in their
//! stored order, then the tip force, then the tip moment, then the constraints in row order.

use super::component::{
    Constraint, ConstraintOut, Element, ElementOut, Env, LocalState, Port, Support,
};
use super::dofs::{LocalDofs, Numbering};
use super::load::{moment_residual, point_force_residual, point_force_stiffness};
use super::space::{is_nonzero, is_nonzero_moment, scaled, Space};
use crate::integrator::{EvalRequest, Integrable, StateRef};
use crate::linalg::{LuMethod, NewtonLu, SingularMatrix, SparsePattern};
use crate::scene::MAX_LINE_LOADS;

/// A component on its local coordinates.
#[derive(Debug)]
pub(crate) struct Placed<C: ?Sized> {
    pub(crate) dofs: LocalDofs,
    pub(crate) part: Box<C>,
}

/// An element with the index of the scene segment it belongs to.
#[derive(Debug)]
pub(crate) struct PlacedElement<S: Space> {
    pub(crate) at: Placed<dyn Element<S>>,
    pub(crate) segment: usize,
}

/// A constraint with its first row (0-based among the constraint rows) and its value slots.
#[derive(Debug)]
pub(crate) struct PlacedConstraint {
    pub(crate) at: Placed<dyn Constraint>,
    pub(crate) rows: usize,
    pub(crate) row: usize,
    /// Slots of (row r, local k) and (local k, row r), row-major rows × d (`None` if held).
    pub(crate) jac_slots: Vec<Option<(usize, usize)>>,
}

/// What a build hands to [`Model::assemble`].
#[derive(Debug)]
pub struct Parts<S: Space> {
    /// Coordinate numbering (free and held).
    pub numbering: Numbering,
    /// Elements in summation order, each with its scene segment index.
    pub elements: Vec<(LocalDofs, Box<dyn Element<S>>, usize)>,
    /// Constraints in row order.
    pub constraints: Vec<(LocalDofs, Box<dyn Constraint>)>,
    /// Where the tip force acts and the tip outputs are read.
    pub tip: (LocalDofs, Box<dyn Port<S>>),
    /// The support at the root.
    pub support: Box<dyn Support<S>>,
    /// Gravity [m/s²].
    pub gravity: S::Vec,
    /// Tip force at build (the scene's) [N], global axes.
    pub tip_force: S::Vec,
    /// Dead tip moment at build (the scene's) [N m], global axes.
    pub tip_moment: S::Moment,
    /// The segments that declare a line load (zero included), in segment order, with the line
    /// load at build [N/m], global axes: slot k of [`Model::set_line_load`] is the k-th.
    pub line_loads: Vec<(usize, S::Vec)>,
    /// Whether the held root coordinates follow a moving mount (`root = "mounted"`); the
    /// numbering's rigid groups say how. Built in the mount frame: the held values at build are
    /// the mount-frame ones.
    pub mounted: bool,
}

/// Reused local work arrays of the assembly's ports and constraints (sized for the largest
/// component).
#[derive(Debug, Clone, Default)]
struct Work {
    q: Vec<f64>,
    r: Vec<f64>,
    con: ConstraintOut,
}

/// The assembled beam model in space `S`.
pub struct Model<S: Space> {
    n: usize,
    m: usize,
    pub(crate) elements: Vec<PlacedElement<S>>,
    pub(crate) constraints: Vec<PlacedConstraint>,
    pub(crate) tip: Placed<dyn Port<S>>,
    pub(crate) support: Box<dyn Support<S>>,
    pub(crate) held: Vec<f64>,
    /// Rates and accelerations of the held coordinates (empty unless mounted: not moving).
    pub(crate) held_v: Vec<f64>,
    pub(crate) held_a: Vec<f64>,
    /// Held values in the mount frame (the build's; empty unless mounted).
    pub(crate) held_ref: Vec<f64>,
    /// How coordinate groups move rigidly (mount, re-anchoring, rigid inertia).
    pub(crate) groups: Vec<crate::model::dofs::RigidGroup>,
    /// The mount motion the held coordinates follow (`None`: the root is fixed).
    pub(crate) mount: Option<Box<crate::model::space::Motion<S>>>,
    /// The mount motion of the last matrix evaluation (what a snapshot needs to rebuild it).
    pub(crate) mount_at_matrix: Option<Box<crate::model::space::Motion<S>>>,
    pub(crate) gravity: S::Vec,
    /// The one total tip force [N], global axes: the scene's at build, then whatever
    /// [`Model::set_tip_force`] sets (no split into scene part and input part).
    pub(crate) tip_force: S::Vec,
    /// The one total dead tip moment [N m], global axes, owned like the tip force.
    pub(crate) tip_moment: S::Moment,
    /// The scene segment of each line-load slot ([`Parts::line_loads`]).
    line_segments: Vec<usize>,
    /// The line load of each slot [N/m], global axes (zero beyond `line_segments`).
    line_loads: [S::Vec; MAX_LINE_LOADS],
    /// The stations' cuts ([`Model::set_stations`]; none until set).
    pub(crate) stations: Vec<super::cut::Cut>,
    /// Each coordinate's rigid group, for the stations.
    pub(crate) group_map: super::cut::GroupMap,
    /// A constraint's rows for the outputs' held residual (through `&self`).
    pub(crate) constraint_out: super::scratch::Scratch<ConstraintOut>,
    /// The stations' and the beam stress's working memory (sized by `set_stations`).
    pub(crate) station_work: super::scratch::Scratch<super::cut::StationWork>,
    scale: Vec<f64>,
    q0: Vec<f64>,
    lu: NewtonLu,
    values: Vec<f64>,
    work: Work,
    /// [`Integrable::constraint_values`]' held values while they are moved.
    held_saved: Vec<f64>,
    /// A mounted model's second matrix storage (LU and values), swapped in while the held
    /// Newton matrix is set aside ([`Model::set_matrix_aside`]).
    aside: Option<Box<(NewtonLu, Vec<f64>)>>,
    /// Whether the held matrix is set aside now.
    matrix_aside: bool,
    /// [`Model::mount_inertia`]'s working memory (sized at build for a mounted model).
    pub(crate) mount_work: super::scratch::Scratch<super::inertia::MountWork>,
}

impl<S: Space> std::fmt::Debug for Model<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Model")
            .field("coordinates", &self.n)
            .field("constraints", &self.m)
            .field("elements", &self.elements.len())
            .field("constraint_blocks", &self.constraints.len())
            .finish()
    }
}

impl<S: Space> Model<S> {
    /// Numbers the constraint rows, builds the sparse pattern and the slot tables, and sets up
    /// the LU (symbolic analysis once).
    pub fn assemble(parts: Parts<S>) -> Self {
        let Parts {
            mut numbering,
            elements,
            constraints,
            tip,
            support,
            gravity,
            tip_force,
            tip_moment,
            line_loads: lines,
            mounted,
        } = parts;
        let mut line_loads = [S::Vec::default(); MAX_LINE_LOADS];
        for (slot, (_, q)) in line_loads.iter_mut().zip(&lines) {
            *slot = *q;
        }
        let line_segments = lines.iter().map(|(seg, _)| *seg).collect();
        let groups = numbering.take_groups();
        let (q0, scale, held) = numbering.finish();
        let (held_ref, held_v, held_a, mount) = if mounted {
            let nh = held.len();
            (
                held.clone(),
                vec![0.0; nh],
                vec![0.0; nh],
                Some(Box::default()),
            )
        } else {
            (Vec::new(), Vec::new(), Vec::new(), None)
        };
        let n = q0.len();
        let mut row = 0;
        let mut constraints: Vec<PlacedConstraint> = constraints
            .into_iter()
            .map(|(dofs, part)| {
                let rows = part.rows();
                row += rows;
                PlacedConstraint {
                    at: Placed { dofs, part },
                    rows,
                    row: row - rows,
                    jac_slots: Vec::new(),
                }
            })
            .collect();
        let m = row;
        let mut elements: Vec<PlacedElement<S>> = elements
            .into_iter()
            .map(|(dofs, part, segment)| PlacedElement {
                at: Placed { dofs, part },
                segment,
            })
            .collect();
        let mut tip = Placed {
            dofs: tip.0,
            part: tip.1,
        };
        let mut entries = Vec::new();
        for e in &elements {
            e.at.dofs.block_entries(&mut entries);
        }
        for c in &constraints {
            c.at.dofs.block_entries(&mut entries);
            for r in 0..c.rows {
                for i in (0..c.at.dofs.len()).filter_map(|k| c.at.dofs.free(k)) {
                    entries.push((n + c.row + r, i));
                    entries.push((i, n + c.row + r));
                }
            }
        }
        tip.dofs.block_entries(&mut entries);
        let pattern = SparsePattern::new(n + m, entries);
        for e in &mut elements {
            e.at.dofs.bind(&pattern);
        }
        for c in &mut constraints {
            c.at.dofs.bind(&pattern);
            let d = c.at.dofs.len();
            c.jac_slots = (0..c.rows * d)
                .map(|rk| {
                    let (r, k) = (rk / d, rk % d);
                    c.at.dofs.free(k).map(|i| {
                        let row = n + c.row + r;
                        (pattern.slot(row, i) as usize, pattern.slot(i, row) as usize)
                    })
                })
                .collect();
        }
        tip.dofs.bind(&pattern);
        let dmax = elements
            .iter()
            .map(|e| e.at.dofs.len())
            .chain(constraints.iter().map(|c| c.at.dofs.len()))
            .chain([tip.dofs.len()])
            .max()
            .unwrap_or(0);
        let work = Work {
            q: vec![0.0; dmax],
            r: vec![0.0; dmax],
            con: ConstraintOut::default(),
        };
        let nnz = pattern.nnz();
        let mut model = Self {
            n,
            m,
            elements,
            constraints,
            tip,
            support,
            held,
            held_v,
            held_a,
            held_ref,
            groups,
            mount,
            mount_at_matrix: None,
            gravity,
            tip_force,
            tip_moment,
            line_segments,
            line_loads,
            stations: Vec::new(),
            group_map: Default::default(),
            constraint_out: Default::default(),
            station_work: Default::default(),
            scale,
            q0,
            lu: NewtonLu::new(pattern),
            values: vec![0.0; nnz],
            work,
            held_saved: Vec::new(),
            aside: None,
            matrix_aside: false,
            mount_work: Default::default(),
        };
        if mounted {
            let (n, nh) = (model.n, model.held.len());
            model.mount_work =
                super::scratch::Scratch::new(super::inertia::MountWork::sized(n, nh, dmax));
            model.aside = Some(Box::new((
                NewtonLu::new(model.lu.pattern().clone()),
                vec![0.0; nnz],
            )));
        }
        model.held_saved.clone_from(&model.held);
        model.set_gravity(gravity);
        model
    }

    /// Coordinates of the initial configuration.
    pub fn initial_coordinates(&self) -> &[f64] {
        &self.q0
    }

    /// Factorizes the Newton matrix by `method` from now on (benchmarks and the tests that
    /// compare the two; results differ by round-off). The held factorization is dropped, so the
    /// caller's integrator must refactorize (`GeneralizedAlpha::invalidate`).
    pub fn set_lu_method(&mut self, method: LuMethod) {
        let pattern = self.lu.pattern().clone();
        if let Some(aside) = &mut self.aside {
            aside.0 = NewtonLu::with_method(pattern.clone(), method);
        }
        self.lu = NewtonLu::with_method(pattern, method);
    }

    /// Sets the held Newton matrix aside (`on`) or takes it back: while it is aside, matrix
    /// evaluations, factorizations and solves use a second storage and leave the held matrix
    /// (its values, its factorization, [`Model::mount_at_matrix`]) as it was, so that solves
    /// beside a step (an apparent mass's, [`crate::integrator::input_jumps`]) need not rebuild
    /// it.
    /// Returns whether it is aside now (a fixed root has no second storage: false).
    pub fn set_matrix_aside(&mut self, on: bool) -> bool {
        let Some(aside) = &mut self.aside else {
            return false;
        };
        if on != self.matrix_aside {
            std::mem::swap(&mut self.lu, &mut aside.0);
            std::mem::swap(&mut self.values, &mut aside.1);
            self.matrix_aside = on;
        }
        on
    }

    /// Whether any damping term is present.
    pub fn is_damped(&self) -> bool {
        self.elements.iter().any(|e| e.at.part.is_damped())
    }

    /// Gravity [m/s²].
    pub fn gravity(&self) -> S::Vec {
        self.gravity
    }

    /// Sets gravity [m/s²].
    pub fn set_gravity(&mut self, g: S::Vec) {
        self.gravity = g;
        for e in &mut self.elements {
            e.at.part.set_gravity(&g);
        }
    }

    /// The total tip force [N], global axes.
    pub fn tip_force(&self) -> S::Vec {
        self.tip_force
    }

    /// Sets the total tip force [N], global axes (replaces the scene's).
    pub fn set_tip_force(&mut self, f: S::Vec) {
        self.tip_force = f;
    }

    /// The line loads of the slots [N/m], global axes ([`Parts::line_loads`]; zero beyond the
    /// scene's).
    pub fn line_loads(&self) -> [S::Vec; MAX_LINE_LOADS] {
        self.line_loads
    }

    /// The number of line-load slots (segments that declare `line_load`).
    pub fn line_load_slots(&self) -> usize {
        self.line_segments.len()
    }

    /// Sets the line load of slot `slot` [N/m], global axes, on every element of its segment
    /// (a slot the scene does not have is ignored).
    pub fn set_line_load(&mut self, slot: usize, q: S::Vec) {
        let Some(&segment) = self.line_segments.get(slot) else {
            return;
        };
        self.line_loads[slot] = q;
        let g = self.gravity;
        for e in self.elements.iter_mut().filter(|e| e.segment == segment) {
            e.at.part.set_line_load(&q);
            e.at.part.set_gravity(&g);
        }
    }

    /// The total dead tip moment [N m], global axes.
    pub fn tip_moment(&self) -> S::Moment {
        self.tip_moment
    }

    /// Sets the total dead tip moment [N m], global axes (replaces the scene's).
    pub fn set_tip_moment(&mut self, m: S::Moment) {
        self.tip_moment = m;
    }

    /// Largest number of local coordinates of a component.
    pub(crate) fn max_local_len(&self) -> usize {
        self.work.q.len()
    }

    /// The matrix assembled by the last [`Integrable::eval`] with a matrix request, as dense
    /// rows (for linearized analyses and tests; O((n + m)²) memory).
    pub fn assembled_dense(&self) -> Vec<Vec<f64>> {
        let p = self.lu.pattern();
        let d = p.dim();
        let mut out = vec![vec![0.0; d]; d];
        for (c, row) in (0..d).flat_map(|c| p.column(c).map(move |r| (c, r))) {
            out[row][c] = self.values[p.slot(row, c) as usize];
        }
        out
    }
}

impl<S: Space> Integrable for Model<S> {
    fn coordinates(&self) -> usize {
        self.n
    }

    fn dense_matrix(&self) -> Option<Vec<Vec<f64>>> {
        Some(self.assembled_dense())
    }

    fn constraints(&self) -> usize {
        self.m
    }

    fn scales(&self) -> &[f64] {
        &self.scale
    }

    fn eval(&mut self, x: StateRef<'_>, req: EvalRequest, res: &mut [f64]) {
        let n = self.n;
        res.fill(0.0);
        let matrix = req.matrix;
        if matrix.is_some() {
            self.values.fill(0.0);
            if self.mount.is_some() && !self.matrix_aside {
                self.mount_at_matrix.clone_from(&self.mount);
            }
        }
        let force = self.tip_force;
        let moment = self.tip_moment;
        let Self {
            elements,
            constraints,
            tip,
            held,
            held_v,
            held_a,
            gravity,
            values,
            work,
            ..
        } = self;
        let env = Env {
            gravity: *gravity,
            load: x.load,
        };
        for e in elements.iter_mut() {
            let local = LocalState::moving(&e.at.dofs, (held, held_v, held_a), (x.q, x.v, x.a));
            let out = ElementOut::new(matrix, &e.at.dofs, req.sd, res, values);
            e.at.part.eval(&local, &env, out);
        }
        if is_nonzero::<S>(&force) {
            let f = scaled::<S>(x.load, &force);
            let dofs = &tip.dofs;
            let d = dofs.len();
            dofs.gather(x.q, held, &mut work.q[..d]);
            if let Some((_, _, cx)) = matrix {
                let kin = tip.part.kinematics(&work.q[..d]);
                point_force_residual::<S>(&kin, &f, &mut work.r[..d]);
                point_force_stiffness::<S>(&kin, &f, |i, j, h| {
                    if let Some(s) = dofs.slot(i, j) {
                        values[s] += cx * h;
                    }
                });
            } else {
                tip.part
                    .point_force_residual(&work.q[..d], &f, &mut work.r[..d]);
            }
            dofs.scatter_add(req.sd, &work.r[..d], res);
        }
        if is_nonzero_moment::<S>(&moment) {
            let mut m = moment;
            for c in S::moment_components_mut(&mut m) {
                *c *= x.load;
            }
            let dofs = &tip.dofs;
            let d = dofs.len();
            dofs.gather(x.q, held, &mut work.q[..d]);
            let kin = tip.part.kinematics_first(&work.q[..d]);
            moment_residual::<S>(&kin, &m, &mut work.r[..d]);
            dofs.scatter_add(req.sd, &work.r[..d], res);
            if let Some((_, _, cx)) = matrix {
                tip.part
                    .add_moment_stiffness(&work.q[..d], &m, &mut |i, j, h| {
                        if let Some(s) = dofs.slot(i, j) {
                            values[s] += cx * h;
                        }
                    });
            }
        }
        let hessian = req.lambda_hessian && matrix.is_some();
        for c in constraints.iter() {
            let dofs = &c.at.dofs;
            let d = dofs.len();
            dofs.gather(x.q, held, &mut work.q[..d]);
            let lam = &x.lambda[c.row..c.row + c.rows];
            let out = &mut work.con;
            out.reset(c.rows, d);
            c.at.part.eval(&work.q[..d], hessian.then_some(lam), out);
            for r in 0..c.rows {
                res[n + c.row + r] = out.phi[r];
                let jac = &out.jac[r * d..(r + 1) * d];
                for (k, j) in jac.iter().enumerate() {
                    if let Some(i) = dofs.free(k) {
                        res[i] += j * lam[r];
                    }
                }
            }
            if matrix.is_some() {
                for (j, s) in out.jac.iter().zip(&c.jac_slots) {
                    if let (Some((a, b)), true) = (s, *j != 0.0) {
                        values[*a] += j;
                        values[*b] += j;
                    }
                }
                for &(i, j, h) in &out.hess {
                    if let Some(s) = dofs.slot(i, j) {
                        values[s] += h;
                    }
                }
            }
        }
    }

    fn constraint_values(&mut self, q: &[f64], dt: f64, out: &mut [f64]) {
        let moved = self.mount.is_some() && dt != 0.0;
        // the held values kept in `held_saved` (copied: no allocation once sized)
        if moved {
            self.held_saved.clone_from(&self.held);
            for ((h, v), a) in self.held.iter_mut().zip(&self.held_v).zip(&self.held_a) {
                *h += dt * v + 0.5 * dt * dt * a;
            }
        }
        // Φ alone: only the constraint components (the elements add nothing to these rows)
        let Self {
            constraints,
            held,
            work,
            ..
        } = self;
        for c in constraints.iter() {
            let dofs = &c.at.dofs;
            let d = dofs.len();
            dofs.gather(q, held, &mut work.q[..d]);
            let o = &mut work.con;
            o.reset(c.rows, d);
            c.at.part.values(&work.q[..d], o);
            out[c.row..c.row + c.rows].copy_from_slice(&o.phi[..c.rows]);
        }
        if moved {
            std::mem::swap(&mut self.held, &mut self.held_saved);
        }
    }

    fn is_driven(&self) -> bool {
        self.mount.is_some()
    }

    fn held_rate(&self) -> f64 {
        let max = |x: &[f64]| x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        max(&self.held_v) + max(&self.held_a).sqrt()
    }

    fn factorize(&mut self) -> Result<(), SingularMatrix> {
        self.lu.factorize(&self.values)
    }

    fn solve(&mut self, rhs: &mut [f64]) -> bool {
        self.lu.solve(rhs)
    }
}

#[cfg(test)]
mod tests {
    //! The assembly with components it has never seen: a point mass on a rigid rod written as
    //! a one-row constraint, the kind of row count (e.g. an Euler-parameter normalization) that
    //! joints of three rows never exercised.
    use super::*;
    use crate::integrator::State;
    use crate::integrator::{GeneralizedAlpha, IntegrationParameters};
    use crate::model::component::Energies;
    use crate::model::dofs::Dof;
    use crate::model::planar::Planar;
    use crate::model::planar::{EndKin, Orientation};
    use crate::model::sample::ShapePoint;
    use nalgebra::Vector2;
    use std::any::Any;

    /// Point mass `m` [kg] on local coordinates [x, y].
    #[derive(Debug)]
    struct PointMass(f64);

    impl Element<Planar> for PointMass {
        fn eval(&mut self, x: &LocalState<'_>, env: &Env<Planar>, mut out: ElementOut<'_>) {
            let m = self.0;
            let (_, _, a) = x.arrays::<2>();
            out.add_residual(&[0, 1].map(|k| m * a[k] - env.load * m * env.gravity[k]));
            if let Some((ca, _, _)) = out.matrix {
                out.add_block(|i, j| if i == j { ca * m } else { 0.0 });
            }
        }
        fn residual(&self, x: &LocalState<'_>, env: &Env<Planar>, res: &mut [f64]) {
            let (_, _, a) = x.arrays::<2>();
            for k in 0..2 {
                res[k] = self.0 * (a[k] - env.gravity[k]);
            }
        }
        fn energies(&self, x: &LocalState<'_>, g: &[f64; 2]) -> Energies {
            let (q, v, _) = x.arrays::<2>();
            Energies {
                kinetic: 0.5 * self.0 * (v[0] * v[0] + v[1] * v[1]),
                strain: 0.0,
                potential: -self.0 * (g[0] * q[0] + g[1] * q[1]),
            }
        }
        fn length(&self) -> f64 {
            0.0
        }
        fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
            let (q, v, _) = x.arrays::<2>();
            out.extend(xi.iter().map(|_| ShapePoint {
                position: [q[0], q[1], 0.0],
                velocity: [v[0], v[1], 0.0],
                ..ShapePoint::default()
            }));
        }
        fn is_damped(&self) -> bool {
            false
        }
        fn as_any(&self) -> &dyn Any {
            self
        }
    }

    /// Φ = ½(x² + y² − L²): one row.
    #[derive(Debug)]
    struct Rod(f64);

    impl Constraint for Rod {
        fn rows(&self) -> usize {
            1
        }
        fn eval(&self, q: &[f64], lambda: Option<&[f64]>, out: &mut ConstraintOut) {
            out.phi[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] - self.0 * self.0);
            out.jac.copy_from_slice(q);
            if let Some(l) = lambda {
                out.hess.extend([(0, 0, l[0]), (1, 1, l[0])]);
            }
        }
    }

    #[derive(Debug)]
    struct Point;

    impl Port<Planar> for Point {
        fn kinematics(&self, q: &[f64]) -> EndKin {
            EndKin {
                p: Vector2::new(q[0], q[1]),
                dp: [Vector2::x(), Vector2::y()].into_iter().collect(),
                orient: Orientation::Angle(0.0, [0.0; 2].into_iter().collect()),
                curv: None,
            }
        }
        fn add_moment_stiffness(&self, _: &[f64], _: &f64, _: &mut dyn FnMut(usize, usize, f64)) {}
    }

    #[derive(Debug)]
    struct NoSupport;

    impl Support<Planar> for NoSupport {
        fn reaction(&self, _: &[f64], _: &[f64]) -> ([f64; 2], f64) {
            ([0.0; 2], 0.0)
        }
    }

    const L: f64 = 0.5;
    const G: f64 = 9.81;

    fn pendulum(theta0: f64) -> Model<Planar> {
        let mut num = Numbering::default();
        let dofs: Vec<Dof> = vec![
            num.free(L * theta0.sin(), L),
            num.free(-L * theta0.cos(), L),
        ];
        let dofs = LocalDofs::new(dofs);
        Model::assemble(Parts {
            numbering: num,
            elements: vec![(dofs.clone(), Box::new(PointMass(0.3)), 0)],
            constraints: vec![(dofs.clone(), Box::new(Rod(L)))],
            tip: (dofs, Box::new(Point)),
            support: Box::new(NoSupport),
            gravity: [0.0, -G],
            tip_force: [0.0, 0.0],
            tip_moment: 0.0,
            line_loads: Vec::new(),
            mounted: false,
        })
    }

    #[test]
    fn one_row_constraint_assembles_with_its_exact_matrix() {
        let mut model = pendulum(0.3);
        model.set_tip_force([0.2, -0.1]);
        assert_eq!((model.coordinates(), model.constraints()), (2, 1));
        let (q, v, a, lam) = ([0.2, -0.4], [0.7, 0.3], [1.0, -2.0], [0.9]);
        let req = EvalRequest {
            sd: 1.0,
            matrix: Some((1.0, 0.0, 1.0)),
            lambda_hessian: true,
        };
        let mut res = [0.0; 3];
        model.eval(StateRef::new(&q, &v, &a, &lam), req, &mut res);
        // M a − m g − F + Φ_qᵀλ, Φ
        let (m, f) = (0.3, [0.2, -0.1]);
        let want = [
            m * a[0] - f[0] + q[0] * lam[0],
            m * a[1] + m * G - f[1] + q[1] * lam[0],
            0.5 * (q[0] * q[0] + q[1] * q[1] - L * L),
        ];
        for (r, w) in res.iter().zip(want) {
            assert!((r - w).abs() < 1e-15, "{res:?} vs {want:?}");
        }
        // c_a M + λ ∂²Φ on the coordinates, Φ_q in the row and column of the constraint
        let dense = model.assembled_dense();
        let want = [
            [m + lam[0], 0.0, q[0]],
            [0.0, m + lam[0], q[1]],
            [q[0], q[1], 0.0],
        ];
        for i in 0..3 {
            for j in 0..3 {
                assert!((dense[i][j] - want[i][j]).abs() < 1e-15, "{dense:?}");
            }
        }
    }

    #[test]
    fn pendulum_period_matches_small_oscillation_theory() {
        // T = 2π √(L/g) (1 + θ₀²/16 + …): at θ₀ = 0.01 the correction is 6e-6
        let theta0: f64 = 0.01;
        let period = 2.0 * std::f64::consts::PI * (L / G).sqrt() * (1.0 + theta0 * theta0 / 16.0);
        let mut model = pendulum(theta0);
        let (n, m) = (model.coordinates(), model.constraints());
        let mut s = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
        let mut integ = GeneralizedAlpha::new(
            &IntegrationParameters {
                tolerance: Some(1e-12),
                max_iterations: 20,
                ..Default::default()
            },
            n,
            m,
        );
        integ.initialize(&mut model, &mut s).unwrap();
        let h = period / 400.0;
        let mut crossings = Vec::new();
        while crossings.len() < 4 {
            let (t0, x0) = (s.t, s.q[0]);
            integ.step(&mut model, &mut s, h).unwrap();
            if x0 > 0.0 && s.q[0] <= 0.0 {
                crossings.push(t0 + h * x0 / (x0 - s.q[0]));
            }
        }
        let measured = (crossings[3] - crossings[0]) / 3.0;
        let err = measured / period - 1.0;
        eprintln!("pendulum period error {err:e}");
        // generalized-α period error is O((ωh)²) ≈ 2e-5 at 400 steps per period
        assert!(err.abs() < 1e-4, "period {measured} vs {period}: {err:e}");
        let o = model.outputs(&s.q, &s.v, &s.acc, &s.lambda);
        let r = (o.tip_position[0].powi(2) + o.tip_position[1].powi(2)).sqrt();
        assert!((r / L - 1.0).abs() < 1e-12, "rod length {r}");
    }
}
