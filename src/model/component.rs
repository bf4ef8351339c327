//! What a component of the model answers, each on its own local coordinates (the assembly maps
//! them to global ones through [`super::LocalDofs`]):
//!
//! * an [`Element`] (ANCF element, modal body): its residual `M q̈ + f − f_ext` and Newton
//!   block `c_a M + c_v C + c_x K`;
//! * a [`Constraint`] (joint rows, a normalization row): Φ, Φ_q and Σλ_i ∂²Φ_i, with its own
//!   row count;
//! * a [`Port`] (ANCF node, modal tip or root): where joints, loads and outputs attach;
//! * a [`Support`]: the reaction from the residual of the held (eliminated) coordinates.

use super::dofs::LocalDofs;
use super::sample::ShapePoint;
use super::space::Space;
use std::any::Any;
use std::fmt::Debug;

/// A component's view of one state: its local coordinates, rates and accelerations, gathered
/// into storage the component chooses (fixed-size arrays for a fixed-size element).
#[derive(Debug, Clone, Copy)]
pub struct LocalState<'a> {
    dofs: &'a LocalDofs,
    held: (&'a [f64], &'a [f64], &'a [f64]),
    q: &'a [f64],
    v: &'a [f64],
    a: &'a [f64],
}

impl<'a> LocalState<'a> {
    /// The view through `dofs` of the global (q, q̇, q̈) and the held values (not moving).
    pub fn new(
        dofs: &'a LocalDofs,
        held: &'a [f64],
        state: (&'a [f64], &'a [f64], &'a [f64]),
    ) -> Self {
        Self::moving(dofs, (held, &[], &[]), state)
    }

    /// The view through `dofs` of the global (q, q̇, q̈) and the held values, rates and
    /// accelerations (the rates and accelerations empty: not moving).
    pub fn moving(
        dofs: &'a LocalDofs,
        held: (&'a [f64], &'a [f64], &'a [f64]),
        (q, v, a): (&'a [f64], &'a [f64], &'a [f64]),
    ) -> Self {
        Self {
            dofs,
            held,
            q,
            v,
            a,
        }
    }

    /// Number of local coordinates d.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    /// (q, q̇, q̈) into slices of length d (held coordinates at their values and rates).
    #[inline]
    pub fn gather(&self, q: &mut [f64], v: &mut [f64], a: &mut [f64]) {
        let global = (self.q, self.v, self.a);
        self.dofs.gather_state(global, self.held, (q, v, a));
    }

    /// (q, q̇, q̈) as arrays of a component with `D` local coordinates.
    #[inline]
    pub fn arrays<const D: usize>(&self) -> ([f64; D], [f64; D], [f64; D]) {
        self.dofs.gather_arrays((self.q, self.v, self.a), self.held)
    }

    /// (q, q̇, q̈) as vectors (on the stack up to [`LOCAL_INLINE`] coordinates: no heap
    /// allocation in a step).
    pub fn vectors(&self) -> (LocalVec, LocalVec, LocalVec) {
        let d = self.len();
        let zero = || LocalVec::from_elem(0.0, d);
        let (mut q, mut v, mut a) = (zero(), zero(), zero());
        self.gather(&mut q, &mut v, &mut a);
        (q, v, a)
    }
}

/// The local coordinates a component holds inline: a spatial modal body with the most modes
/// (7 frame coordinates, 2 × (12 + 2) bending amplitudes, 2 torsion amplitudes) has 37, a
/// joint between two such bodies' ends more.
pub const LOCAL_INLINE: usize = 64;

/// A component's local values, inline up to [`LOCAL_INLINE`].
pub type LocalVec = smallvec::SmallVec<[f64; LOCAL_INLINE]>;

/// The environment of an evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Env<S: Space> {
    /// Gravity [m/s²], global axes (unscaled).
    pub gravity: S::Vec,
    /// Factor on the external loads (1 in dynamics; load stepping in statics).
    pub load: f64,
}

/// Energies of one component [J].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy ½ q̇ᵀ M q̇.
    pub kinetic: f64,
    /// Strain energy.
    pub strain: f64,
    /// Gravity potential −∫ρA gᵀr dx (zero at the origin).
    pub potential: f64,
}

/// Where an element writes its residual and, if requested, its Newton block, on local indices;
/// the assembly's numbering takes them to the free rows and columns.
#[derive(Debug)]
pub struct ElementOut<'a> {
    /// Matrix coefficients (c_a, c_v, c_x), if the block is wanted.
    pub matrix: Option<(f64, f64, f64)>,
    dofs: &'a LocalDofs,
    sd: f64,
    res: &'a mut [f64],
    values: &'a mut [f64],
}

impl<'a> ElementOut<'a> {
    /// Writes into the global residual `res` (rows scaled by `sd`) and matrix `values`.
    pub fn new(
        matrix: Option<(f64, f64, f64)>,
        dofs: &'a LocalDofs,
        sd: f64,
        res: &'a mut [f64],
        values: &'a mut [f64],
    ) -> Self {
        Self {
            matrix,
            dofs,
            sd,
            res,
            values,
        }
    }

    /// Adds the residual `r` (one entry per local coordinate).
    #[inline]
    pub fn add_residual(&mut self, r: &[f64]) {
        self.dofs.scatter_add(self.sd, r, self.res);
    }

    /// Adds the block entries `h(i, j)` of every pair of free local coordinates, row by row.
    #[inline]
    pub fn add_block(&mut self, h: impl FnMut(usize, usize) -> f64) {
        self.dofs.add_block_with(self.values, h);
    }
}

/// Measures of an element's configuration that its model may not be valid for; the simulator
/// refuses a step that exceeds its limits.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Validity {
    /// Largest |axial strain| [-] (0 where not measured).
    pub axial_strain: f64,
    /// Elastic deflection of a small-deformation (modal) element, to be compared with the
    /// validity limit of a linear floating frame; `None` for large-deformation elements.
    pub modal_deflection: Option<f64>,
    /// Section director of the director element: (largest |twist| within one element
    /// [rad], smallest sine of the angle between r_x and r_y at its nodes [-]); `None` for
    /// elements without a director.
    pub section: Option<(f64, f64)>,
    /// Nodal twist angles: the smallest 1 + t⁰·t over the element's nodes (2 straight along
    /// the reference axis t⁰, 0 turned back onto −t⁰, where the angles are undefined);
    /// `None` for other elements.
    pub chart_margin: Option<f64>,
}

/// A body of the model: ANCF element, modal body.
pub trait Element<S: Space>: Debug + Send + Sync + 'static {
    /// Residual `r = M q̈ + f(q, q̇) − env.load·f_ext(q)` on the local coordinates and, with
    /// `out.matrix = Some((c_a, c_v, c_x))`, the block `c_a M + c_v ∂f/∂q̇ +
    /// c_x ∂(M q̈ + f − f_ext)/∂q`, each added once through `out`.
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<S>, out: ElementOut<'_>);

    /// The residual at full load on every local coordinate, by the element's reference path
    /// (used for support reactions, once per output).
    fn residual(&self, x: &LocalState<'_>, env: &Env<S>, res: &mut [f64]);

    /// Kinetic, strain and gravity energies at a state.
    fn energies(&self, x: &LocalState<'_>, gravity: &S::Vec) -> Energies;

    /// The inertia force of the accelerations `x.a` at rest, M(q)·q̈ (the velocities of `x`
    /// zero; no elastic force, no gravity), into `out`; `false` (and `out` untouched) where the
    /// element does not give it directly (the default): the caller then takes it as the
    /// difference of two residuals. The mount inertia reads the rigid fields through it.
    fn inertia_times(&self, _x: &LocalState<'_>, _out: &mut [f64]) -> bool {
        false
    }

    /// Called when gravity changes (elements may cache their gravity force).
    fn set_gravity(&mut self, _gravity: &S::Vec) {}

    /// Sets the line load of the element's segment [N/m], global axes (the model calls
    /// [`Element::set_gravity`] after it, for elements that cache their gravity force).
    fn set_line_load(&mut self, _q: &S::Vec) {}

    /// Whether the element carries damping.
    fn is_damped(&self) -> bool;

    /// Reference length of the element [m].
    fn length(&self) -> f64;

    /// The centreline at each ξ ∈ [0, 1] of `xi` (x = ξ·[`Element::length`] from the element's
    /// root end) pushed onto `out`: position, velocity, section frame and strains
    /// ([`ShapePoint`]; `segment` and `arc` are the caller's to set).
    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>);

    /// The d'Alembert load of the part ξ' ∈ [0, `xi`] of the element at the state `x` under
    /// gravity `gravity` (full load): the force ∫(f_ext − ρA r̈) dx [N] and its moment about
    /// `about` ∫(r − about) × (f_ext − ρA r̈) dx [N m], with the point masses, section bodies
    /// and rotary inertia on that part, world axes as 3-vectors (no heap allocation once the
    /// element has seen the cut: a step asks for it); `None` where the element cannot split
    /// itself (the default; the angle element): scene validation refuses such cuts.
    fn partial_load(
        &self,
        _x: &LocalState<'_>,
        _gravity: &S::Vec,
        _xi: f64,
        _about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        None
    }

    /// Validity measures at `q` (none by default).
    fn validity(&self, _q: &[f64]) -> Validity {
        Validity::default()
    }

    /// The element as [`Any`], for inspection of a concrete kind (tests, analyses).
    fn as_any(&self) -> &dyn Any;
}

/// Φ, Φ_q and Σλ_i ∂²Φ_i of one constraint over its local coordinates.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ConstraintOut {
    /// Φ (rows).
    pub phi: Vec<f64>,
    /// ∂Φ_r/∂q_k, row-major rows × d.
    pub jac: Vec<f64>,
    /// Σλ_r ∂²Φ_r/∂q_i∂q_j as (i, j, value) triplets, in the order they are to be summed
    /// (a pair may repeat).
    pub hess: Vec<(usize, usize, f64)>,
}

impl ConstraintOut {
    /// Zeroes Φ and Φ_q for `rows` × `d` and clears the Hessian.
    pub fn reset(&mut self, rows: usize, d: usize) {
        // the Hessian's triplets reserved once for the most a block can have (rows × d²): a
        // later step never grows it
        let most = rows * d * d;
        if self.hess.capacity() < most {
            self.hess.reserve(most - self.hess.len());
        }
        self.phi.clear();
        self.phi.resize(rows, 0.0);
        self.jac.clear();
        self.jac.resize(rows * d, 0.0);
        self.hess.clear();
    }
}

/// Holonomic constraint rows Φ(q) = 0.
pub trait Constraint: Debug + Send + Sync + 'static {
    /// Number of rows.
    fn rows(&self) -> usize;

    /// Φ and Φ_q at the local coordinates `q` into `out` (after [`ConstraintOut::reset`]);
    /// with `lambda` (one multiplier per row) also Σλ_r ∂²Φ_r.
    fn eval(&self, q: &[f64], lambda: Option<&[f64]>, out: &mut ConstraintOut);

    /// Φ alone into `out.phi` (after [`ConstraintOut::reset`]; `out.jac` may be left as it
    /// is), bit for bit the Φ of [`Constraint::eval`] (its default).
    fn values(&self, q: &[f64], out: &mut ConstraintOut) {
        self.eval(q, None, out);
    }
}

/// An attachment point on a component, evaluated from the component's local coordinates.
pub trait Port<S: Space>: Debug + Send + Sync + 'static {
    /// Kinematics at the local coordinates `q`.
    fn kinematics(&self, q: &[f64]) -> S::PortKin;

    /// Kinematics at `q` for uses that need no second derivatives (residuals, Jacobians,
    /// outputs): positions, directors, first derivatives and rotations as
    /// [`Port::kinematics`], second derivatives possibly absent (a port may skip them to save
    /// work). Default: [`Port::kinematics`].
    fn kinematics_first(&self, q: &[f64]) -> S::PortKin {
        self.kinematics(q)
    }

    /// The residual of a dead point force `force` at the port, r_k = −F·∂p/∂q_k on the
    /// `r.len()` local coordinates at `q` ([`crate::model::load::point_force_residual`] on
    /// [`Port::kinematics_first`], the default). A port whose position is a selection of its
    /// coordinates gives the same bits without building its kinematics (a Newton iteration
    /// with a tip force calls this once).
    fn point_force_residual(&self, q: &[f64], force: &S::Vec, r: &mut [f64]) {
        crate::model::load::point_force_residual::<S>(&self.kinematics_first(q), force, r)
    }

    /// Position and directors alone (no derivatives), for constraint values; bit for bit the
    /// values of [`Port::kinematics_first`] (its default). A port whose kinematics are large
    /// gives them without computing or moving the derivatives.
    fn values(&self, q: &[f64]) -> S::PortValues {
        S::port_values(&self.kinematics_first(q))
    }

    /// [`Port::kinematics_first`] into `out`, which a port whose kinematics hold vectors
    /// refills in place (no allocation once `out` has grown). Default:
    /// `*out = self.kinematics_first(q)`.
    fn kinematics_first_into(&self, q: &[f64], out: &mut S::PortKin) {
        *out = self.kinematics_first(q);
    }

    /// Stiffness of a dead moment `m` [N m] (global axes) at the port: adds
    /// `−m·∂²θ/∂q_i∂q_j` (the derivative of the residual `−m·∂θ/∂q_i` with respect to q_j, see
    /// [`super::PortKin::rotation_jacobian`]) through `add(i, j, value)` (local indices).
    fn add_moment_stiffness(
        &self,
        q: &[f64],
        m: &S::Moment,
        add: &mut dyn FnMut(usize, usize, f64),
    );

    /// The rotation's second derivative along `dir` (local), Σᵢⱼ ∂²θ/∂qᵢ∂qⱼ dirᵢ dirⱼ (global
    /// axes): with dir = q̇ the velocity term of the angular acceleration. Default: from
    /// [`Port::add_moment_stiffness`] with unit moments; a port whose stiffness takes one
    /// evaluation per (i, j) overrides it with one directional evaluation.
    fn rotation_second_derivative_along(&self, q: &[f64], dir: &[f64]) -> S::Moment {
        let mut out = S::Moment::default();
        let n = S::moment_components(&out).len();
        for c in 0..n {
            let mut m = S::Moment::default();
            S::moment_components_mut(&mut m)[c] = 1.0;
            // the stiffness adds −m·∂²θ/∂qᵢ∂qⱼ
            let mut sum = 0.0;
            self.add_moment_stiffness(q, &m, &mut |i, j, h| sum -= h * dir[i] * dir[j]);
            S::moment_components_mut(&mut out)[c] = sum;
        }
        out
    }
}

/// How the support holds the beam: turns the residual of the held coordinates (the generalized
/// force the support exerts) into a force and a moment.
pub trait Support<S: Space>: Debug + Send + Sync + 'static {
    /// Force [N] and moment about the root point [N m] of the support on the beam, global
    /// axes, from the residual `r` and the values of the held coordinates.
    fn reaction(&self, r: &[f64], held: &[f64]) -> (S::Vec, S::Moment);
}
