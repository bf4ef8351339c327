//! The spatial ANCF element as a component ([`AncfElement3`]), its node as a port
//! ([`NodePort3`]) and the root support of an ANCF chain ([`NodeSupport3`]). Kernel:
//! [`crate::model::ancf3d`].

use super::kin::{EndKin3, EndValues3, Field3, Grad3};
use super::Spatial;
use crate::model::ancf3d::{Ancf3Props, MassPatterns, Tables3, DIRECTOR_DOFS};
use crate::model::component::{
    Element, ElementOut, Energies, Env, LocalState, Port, Support, Validity,
};
use crate::model::sample::ShapePoint;
use crate::model::section3::{
    add_bodies, add_body_energies, gram_schmidt, SectionBody3, SectionPose,
};
use crate::model::vector::{Real, V3};
use nalgebra::{Matrix3, Vector3};
use num_dual::{Dual2Vec, DualSVec64, HyperDual64};
use std::any::Any;

/// A spatial ANCF element, local coordinates node 0 then node 1, each `[r, r_x, r_y]` (18) with
/// torsion or `[r, r_x]` (12) without (global axes; positions [m], gradients [-]).
#[derive(Debug, Clone)]
pub struct AncfElement3 {
    /// Element properties.
    pub props: Ancf3Props,
    /// Dense mass matrix, row-major d × d (for the Newton block).
    mass: Vec<f64>,
    patterns: MassPatterns,
    tables: Tables3,
    /// ∫ρA S_rᵀ g dx at the current gravity (first d entries), and the point masses' weight.
    gravity_force: [f64; DIRECTOR_DOFS],
    /// Σ m S(ξ_m) over the point masses on the element ([`add_points`]); `None` without.
    points: Option<[f64; 4]>,
    /// The segment's line load q [N/m] ([`Ancf3Props::load_force`]); `None` without one.
    line: Option<[f64; 3]>,
    /// Rigid bodies on the section (offset or rotary inertia, the director element only) with
    /// their poses ([`DirectorPose`]).
    bodies: Vec<(SectionBody3, DirectorPose)>,
    /// The current gravity [m/s²] (the bodies' weight).
    g: [f64; 3],
    /// The point masses (ξ, m [kg]) on the element, for [`Element::partial_load`].
    point_list: Vec<(f64, f64)>,
}

/// The centreline point r = S(ξ)e and the section frame of the director element at ξ:
/// Gram–Schmidt of r_x = S′(ξ)e and the interpolated director r_y = (1 − ξ)r_y0 + ξ r_y1, the
/// frame of the element's samples ([`Ancf3Props::sample`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectorPose {
    sh: [f64; 4],
    ds: [f64; 4],
    xi: f64,
    rs: [usize; 4],
    ys: [usize; 2],
}

impl SectionPose for DirectorPose {
    fn pose<S: Real>(&self, q: impl Fn(usize) -> S) -> (V3<S>, [V3<S>; 3]) {
        let comb = |w: &[f64; 4]| -> V3<S> {
            std::array::from_fn(|c| (0..4).fold(S::zero(), |s, j| s + q(self.rs[j] + c) * w[j]))
        };
        let (r, a) = (comb(&self.sh), comb(&self.ds));
        let d: V3<S> = std::array::from_fn(|c| {
            q(self.ys[0] + c) * (1.0 - self.xi) + q(self.ys[1] + c) * self.xi
        });
        (r, gram_schmidt(a, d))
    }
}

/// Adds point masses `points` (ξ ∈ [0, 1], mass [kg]) on an element of length `l` to its
/// constant mass: a point at ξ is at r = S(ξ)e, so m S(ξ)ᵀS(ξ) on the Hermite pattern `pat`
/// and on the r-blocks of the dense row-major d × d matrix `dense` starting at `slots`. Returns
/// Σ m S(ξ) (the weight is Σ m S(ξ)ᵀ g, [`add_point_weight`]), `None` without points.
pub(super) fn add_points(
    points: &[(f64, f64)],
    l: f64,
    pat: &mut MassPatterns,
    dense: &mut [f64],
    d: usize,
    slots: [usize; 4],
) -> Option<[f64; 4]> {
    if points.is_empty() {
        return None;
    }
    let mut w = [0.0; 4];
    for &(xi, m) in points {
        let s = crate::model::ancf::Shape::at(xi, l).s;
        for j in 0..4 {
            w[j] += m * s[j];
            for k in 0..4 {
                let mjk = m * s[j] * s[k];
                pat.hermite[j][k] += mjk;
                for c in 0..3 {
                    dense[(slots[j] + c) * d + slots[k] + c] += mjk;
                }
            }
        }
    }
    Some(w)
}

/// Adds the point masses' weight Σ m S(ξ)ᵀ g (`w` from [`add_points`]) to the r-blocks at
/// `slots` of a gravity force.
pub(super) fn add_point_weight(
    w: &Option<[f64; 4]>,
    g: &[f64; 3],
    slots: [usize; 4],
    f: &mut [f64],
) {
    if let Some(w) = w {
        for j in 0..4 {
            for c in 0..3 {
                f[slots[j] + c] += w[j] * g[c];
            }
        }
    }
}

impl AncfElement3 {
    /// Element of the given properties (gravity zero until set). A cable (no torsion) with
    /// E·I_y ≠ E·I_z uses their mean: builds refuse it first with [`Ancf3Props::check`].
    pub fn new(props: Ancf3Props) -> Self {
        Self {
            props,
            mass: props.mass_matrix(),
            patterns: props.mass_patterns(),
            tables: props.tables(),
            gravity_force: [0.0; DIRECTOR_DOFS],
            points: None,
            line: None,
            bodies: Vec::new(),
            g: [0.0; 3],
            point_list: Vec::new(),
        }
    }

    /// The element carrying rigid bodies `bodies` on its section ([`SectionBody3`], ξ along
    /// the element; the director element: a build refuses them on the 3D cable).
    pub fn with_bodies(mut self, bodies: &[SectionBody3]) -> Self {
        let (rs, ys) = (self.patterns.r_slots, self.patterns.y_slots);
        let l = self.props.length;
        self.bodies = bodies
            .iter()
            .map(|b| {
                let sh = crate::model::ancf::Shape::at(b.xi, l);
                let pose = DirectorPose {
                    sh: sh.s,
                    ds: sh.ds,
                    xi: b.xi,
                    rs,
                    ys,
                };
                (*b, pose)
            })
            .collect();
        self
    }

    /// The element under the uniform dead line load `q` [N/m] (world axes; `None`: none):
    /// ∫S_rᵀ(ρA g + q) dx is the distributed force and −∫qᵀr dx joins the potential; the point
    /// masses keep g.
    pub fn with_line_load(mut self, q: Option<[f64; 3]>) -> Self {
        self.line = q;
        self
    }

    /// The element carrying point masses `points` (ξ ∈ [0, 1], mass [kg], [`add_points`]).
    pub fn with_points(mut self, points: &[(f64, f64)]) -> Self {
        let (d, slots) = (self.props.dofs(), self.patterns.r_slots);
        let l = self.props.length;
        self.points = add_points(points, l, &mut self.patterns, &mut self.mass, d, slots);
        self.point_list = points.to_vec();
        self
    }

    fn eval_d<const D: usize>(
        &self,
        x: &LocalState<'_>,
        env: &Env<Spatial>,
        mut out: ElementOut<'_>,
    ) {
        let (e, ed, ea) = x.arrays::<D>();
        let p = &self.props;
        let (force, matrices) = if let Some((_, cv, cx)) = out.matrix {
            // the stiffness and damping only where the request weighs them (a request for the
            // mass matrix alone, c_v = c_x = 0, as for consistent accelerations, skips the
            // tangent's differentiation; the force is the same function either way)
            let (mut f, mut k, mut c) = if cv != 0.0 || cx != 0.0 {
                p.tangent(&self.tables, &e, &ed)
            } else {
                (
                    p.internal_force(&self.tables, &e, &ed),
                    [[0.0; D]; D],
                    [[0.0; D]; D],
                )
            };
            let active = [cx != 0.0, cv != 0.0, true];
            let (fi, mi) = p.director_tangent(&self.tables, (&e, &ed, &ea), &mut k, &mut c, active);
            for (f, fi) in f.iter_mut().zip(&fi) {
                *f += fi;
            }
            (f, Some((k, c, mi)))
        } else {
            let mut f = p.internal_force(&self.tables, &e, &ed);
            if p.director {
                let fi = p.director_inertia(&self.tables, &e, &ed, &ea);
                for (f, fi) in f.iter_mut().zip(&fi) {
                    *f += fi;
                }
            }
            (f, None)
        };
        // r = M(e) ë + (director velocity terms) + f_int − load·f_g
        let mut res = force;
        for (r, g) in res.iter_mut().zip(&self.gravity_force) {
            *r -= env.load * g;
        }
        self.patterns.add_product(&ea, &mut res);
        // the section bodies' block (none without bodies: no zeroed matrix per call)
        let blk = (!self.bodies.is_empty()).then(|| {
            let mut blk = [[0.0; D]; D];
            let g = self.g.map(|x| env.load * x);
            add_bodies(
                &self.bodies,
                (&e, &ed, &ea),
                g,
                out.matrix,
                &mut res,
                &mut blk,
            );
            blk
        });
        out.add_residual(&res);
        if let (Some((ca, cv, cx)), Some((k, c, mi))) = (out.matrix, matrices) {
            // the director inertia has velocity terms whether damped or not
            let rated = cv != 0.0 && (p.damping_time > 0.0 || p.director);
            let m = &self.mass;
            out.add_block(|r, col| {
                let mut v = ca * (m[r * D + col] + mi[r][col]) + cx * k[r][col];
                if rated {
                    v += cv * c[r][col];
                }
                if let Some(blk) = &blk {
                    v += blk[r][col];
                }
                v
            });
        }
    }

    /// [`Element::partial_load`] on `D` coordinates: Gauss 5 on [0, ξ] of ρA(x)(g − r̈) + q and
    /// (r − p) × that (exact: degree 6 uniform, 8 tapered with ρA(x) from its 5 quadrature
    /// values), the point masses and section bodies at ξ_m < ξ, and the director's twist
    /// inertia, lumped at the nodes (moments m₀, m₁ of weight l/2 each,
    /// [`Ancf3Props::director_node_moments`]): its density interpolated linearly between
    /// them, the part [0, ξ] takes ξ((2 − ξ)m₀ + ξ m₁) (the trapezoid on [0, ξ]; m₀ + m₁ at
    /// ξ = 1, the whole element's).
    fn partial_d<const D: usize>(
        &self,
        x: &LocalState<'_>,
        gravity: &[f64; 3],
        xi: f64,
        about: [f64; 3],
    ) -> ([f64; 3], [f64; 3]) {
        let (e, ed, ea) = x.arrays::<D>();
        let p = &self.props;
        let (l, rs) = (p.length, self.patterns.r_slots);
        let line = self.line.unwrap_or([0.0; 3]);
        let (mut f, mut m) = ([0.0; 3], [0.0; 3]);
        let mut add = |s: f64, w: f64, mass: f64, q: [f64; 3]| {
            let sh = crate::model::ancf::Shape::at(s, l).s;
            let comb = |x: &[f64; D]| -> [f64; 3] {
                std::array::from_fn(|c| (0..4).map(|j| sh[j] * x[rs[j] + c]).sum())
            };
            let (r, a) = (comb(&e), comb(&ea));
            let load: [f64; 3] = std::array::from_fn(|c| w * (mass * (gravity[c] - a[c]) + q[c]));
            let arm: [f64; 3] = std::array::from_fn(|c| r[c] - about[c]);
            let t = crate::model::vector::cross(arm, load);
            for c in 0..3 {
                f[c] += load[c];
                m[c] += t[c];
            }
        };
        for (xg, wg) in crate::model::ancf::GAUSS5 {
            let s = 0.5 * xi * (xg + 1.0);
            let ra = p.taper.as_ref().map_or(p.rho_a, |t| {
                crate::model::ancf::gauss5_interpolate(&t.rho_a, s)
            });
            add(s, 0.5 * xi * l * wg, ra, line);
        }
        for &(xm, mass) in self.point_list.iter().filter(|(xm, _)| *xm < xi) {
            add(xm, 1.0, mass, [0.0; 3]);
        }
        for (b, pose) in self.bodies.iter().filter(|(b, _)| b.xi < xi) {
            let (bf, bm) = b.load(pose, (&e[..], &ed[..], &ea[..]), *gravity, about);
            for c in 0..3 {
                f[c] += bf[c];
                m[c] += bm[c];
            }
        }
        if p.director {
            let [m0, m1] = p.director_node_moments(&self.tables, &e, &ed, &ea);
            for c in 0..3 {
                m[c] -= xi * ((2.0 - xi) * m0[c] + xi * m1[c]);
            }
        }
        (f, m)
    }

    fn residual_d<const D: usize>(&self, x: &LocalState<'_>, res: &mut [f64]) {
        let (e, ed, ea) = x.arrays::<D>();
        let mut r = self.props.internal_force(&self.tables, &e, &ed);
        let fi = self.props.director_inertia(&self.tables, &e, &ed, &ea);
        for ((r, g), fi) in r.iter_mut().zip(&self.gravity_force).zip(&fi) {
            *r += fi - g;
        }
        self.patterns.add_product(&ea, &mut r);
        for (b, pose) in &self.bodies {
            b.add_forces(pose, D, (&e[..], &ed[..], &ea[..]), self.g, &mut r);
        }
        res.copy_from_slice(&r);
    }
}

impl AncfElement3 {
    /// [`Element::inertia_times`] on `D` coordinates: M ë with the director's inertia and the
    /// section bodies' (at ė = 0, without gravity).
    fn inertia_d<const D: usize>(&self, x: &LocalState<'_>, out: &mut [f64]) {
        let (e, ed, ea) = x.arrays::<D>();
        let mut r = self.props.director_inertia(&self.tables, &e, &ed, &ea);
        self.patterns.add_product(&ea, &mut r);
        for (b, pose) in &self.bodies {
            b.add_forces(pose, D, (&e[..], &ed[..], &ea[..]), [0.0; 3], &mut r);
        }
        out.copy_from_slice(&r);
    }
}

impl Element<Spatial> for AncfElement3 {
    fn inertia_times(&self, x: &LocalState<'_>, out: &mut [f64]) -> bool {
        if self.props.director {
            self.inertia_d::<18>(x, out)
        } else {
            self.inertia_d::<12>(x, out)
        }
        true
    }

    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Spatial>, out: ElementOut<'_>) {
        if self.props.director {
            self.eval_d::<18>(x, env, out)
        } else {
            self.eval_d::<12>(x, env, out)
        }
    }

    fn residual(&self, x: &LocalState<'_>, _env: &Env<Spatial>, res: &mut [f64]) {
        if self.props.director {
            self.residual_d::<18>(x, res)
        } else {
            self.residual_d::<12>(x, res)
        }
    }

    fn partial_load(
        &self,
        x: &LocalState<'_>,
        gravity: &[f64; 3],
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        Some(if self.props.director {
            self.partial_d::<18>(x, gravity, xi, about)
        } else {
            self.partial_d::<12>(x, gravity, xi, about)
        })
    }

    fn length(&self) -> f64 {
        self.props.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (e, ed, _) = x.vectors();
        out.extend(xi.iter().map(|&s| self.props.sample(&e, &ed, s)));
    }

    fn energies(&self, x: &LocalState<'_>, _gravity: &[f64; 3]) -> Energies {
        let (e, ed, _) = x.vectors();
        let mut out = Energies {
            kinetic: self.props.kinetic_energy(&self.mass, &self.tables, &e, &ed),
            strain: self.props.strain_energy(&self.tables, &e),
            potential: gravity_potential(&e, &self.gravity_force),
        };
        add_body_energies(&self.bodies, (&e[..], &ed[..]), self.g, &mut out);
        out
    }

    fn set_line_load(&mut self, q: &[f64; 3]) {
        self.line = Some(*q);
    }

    fn set_gravity(&mut self, g: &[f64; 3]) {
        self.gravity_force = self.props.load_force(*g, self.line);
        add_point_weight(
            &self.points,
            g,
            self.patterns.r_slots,
            &mut self.gravity_force,
        );
        self.g = *g;
    }

    fn is_damped(&self) -> bool {
        self.props.damping_time > 0.0
    }

    fn validity(&self, q: &[f64]) -> Validity {
        Validity {
            axial_strain: self.props.max_axial_strain(&self.tables, q),
            modal_deflection: None,
            section: self.props.director.then(|| self.props.section_measures(q)),
            chart_margin: None,
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// The potential of the dead gravity force −eᵀf_g [J] of an element at `e`.
pub(super) fn gravity_potential(e: &[f64], f_g: &[f64]) -> f64 {
    -e.iter().zip(f_g).map(|(a, b)| a * b).sum::<f64>()
}

/// An ANCF node as a port, local coordinates `[r, r_x, r_y]` (the director element) or
/// `[r, r_x]` (the 3D cable).
///
/// Frame [t d2 d3]: with torsion Gram–Schmidt of (r_x, r_y) (t = r_x/|r_x|, d2 = normalized
/// r_y ⟂ t, d3 = t × d2); for the cable the minimal rotation of `reference` that takes its
/// axis x̄ to t (defined except for t = −x̄: a cable node turned by 180° has no frame).
/// Rotation per local coordinate: ½ Σ_i d_i × ∂d_i/∂q_k (exact, forward-mode AD).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodePort3 {
    /// Whether the node carries r_y (9 local coordinates: the director element) or not (6:
    /// the 3D cable).
    pub director: bool,
    /// Section frame → world of the node's straight initial configuration (columns x̄, ȳ, z̄ in
    /// global axes); only the cable's frame uses it.
    pub reference: Matrix3<f64>,
}

impl NodePort3 {
    /// Port of a node with (`director`) or without r_y, initial section frame `reference`.
    pub fn new(director: bool, reference: Matrix3<f64>) -> Self {
        Self {
            director,
            reference,
        }
    }
}

/// A node port's section frame [t, d2, d3] as a function of its N director coordinates (local
/// coordinates 3..3 + N: the slope r_x, then r_y or the twist angle θ), generic over the
/// scalar: the ports' rotations and moment stiffness are its exact derivatives.
pub(super) trait NodeFrame {
    fn frame<T: Real, const N: usize>(&self, x: &[T; N]) -> [[T; 3]; 3];
}

impl NodeFrame for NodePort3 {
    /// Frame columns [t, d2, d3] from r_x (`x[0..3]`) and, with torsion, r_y (`x[3..6]`).
    fn frame<T: Real, const N: usize>(&self, x: &[T; N]) -> [[T; 3]; 3] {
        let a = [x[0], x[1], x[2]];
        let dot = |u: &[T; 3], v: &[T; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let cross = |u: &[T; 3], v: &[T; 3]| {
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
        };
        let inv = dot(&a, &a).sqrt().recip();
        let t = a.map(|v| v * inv);
        if self.director {
            let c = [x[3], x[4], x[5]];
            let tc = dot(&t, &c);
            let u = [0, 1, 2].map(|i| c[i] - t[i] * tc);
            let iu = dot(&u, &u).sqrt().recip();
            let d2 = u.map(|v| v * iu);
            let d3 = cross(&t, &d2);
            [t, d2, d3]
        } else {
            // R = cos θ I + [s]× + s sᵀ/(1 + cos θ), s = x̄ × t, cos θ = x̄·t
            let col = |k: usize| [0, 1, 2].map(|i| T::from(self.reference[(i, k)]));
            let x0 = col(0);
            let s = cross(&x0, &t);
            let ct = dot(&x0, &t);
            let f = (ct + 1.0).recip();
            let rot = |v: [T; 3]| {
                let sv = cross(&s, &v);
                let ss = dot(&s, &v) * f;
                [0, 1, 2].map(|i| v[i] * ct + sv[i] + s[i] * ss)
            };
            [t, rot(col(1)), rot(col(2))]
        }
    }
}

/// The frame's directors as dual numbers over the N director coordinates (offset 3).
pub(super) fn frame_duals<F: NodeFrame, const N: usize>(
    port: &F,
    q: &[f64],
) -> [[DualSVec64<N>; 3]; 3] {
    let x: [DualSVec64<N>; N] =
        std::array::from_fn(|k| DualSVec64::<N>::from_re(q[3 + k]).derivative(k));
    port.frame(&x)
}

/// Frame and rotation per director coordinate, ½ Σ_i d_i × ∂d_i/∂q_k, from the dual directors
/// `d` ([`frame_duals`]).
pub(super) fn rotation_of<const N: usize>(
    d: &[[DualSVec64<N>; 3]; 3],
) -> (Matrix3<f64>, [Vector3<f64>; N]) {
    let mut frame = Matrix3::zeros();
    let mut rot = [Vector3::zeros(); N];
    for (i, di) in d.iter().enumerate() {
        let v = Vector3::from_fn(|c, _| di[c].re);
        frame.set_column(i, &v);
        for (k, rk) in rot.iter_mut().enumerate() {
            let dv = Vector3::from_fn(|c, _| di[c].eps.0.map_or(0.0, |e| e[k]));
            *rk += 0.5 * v.cross(&dv);
        }
    }
    (frame, rot)
}

/// Frame and rotation per director coordinate (forward-mode AD).
pub(super) fn frame_rotation<F: NodeFrame, const N: usize>(
    port: &F,
    q: &[f64],
) -> (Matrix3<f64>, [Vector3<f64>; N]) {
    rotation_of(&frame_duals::<F, N>(port, q))
}

/// Adds −m·∂(∂θ/∂q_i)/∂q_j over the N director coordinates (offset 3).
pub(super) fn moment_stiffness<F: NodeFrame, const N: usize>(
    port: &F,
    q: &[f64],
    m: &[f64; 3],
    add: &mut dyn FnMut(usize, usize, f64),
) {
    let x: [Dual2Vec<f64, nalgebra::Const<N>>; N] = std::array::from_fn(|k| {
        Dual2Vec::<f64, nalgebra::Const<N>>::from_re(q[3 + k]).derivative(k)
    });
    let d = port.frame(&x);
    let m = Vector3::from(*m);
    // ∂_j θ_k = ½ Σ_i (∂_j d_i × ∂_k d_i + d_i × ∂_j∂_k d_i)
    let mut h = [[0.0; N]; N];
    for di in &d {
        let v = Vector3::from_fn(|c, _| di[c].re);
        let g = |c: usize, k: usize| di[c].v1.0.map_or(0.0, |e| e[k]);
        let hh = |c: usize, j: usize, k: usize| di[c].v2.0.map_or(0.0, |e| e[(j, k)]);
        for k in 0..N {
            let dk = Vector3::from_fn(|c, _| g(c, k));
            for j in 0..N {
                let dj = Vector3::from_fn(|c, _| g(c, j));
                let djk = Vector3::from_fn(|c, _| hh(c, j, k));
                h[k][j] += 0.5 * m.dot(&(dj.cross(&dk) + v.cross(&djk)));
            }
        }
    }
    for (k, row) in h.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            if *x != 0.0 {
                add(3 + k, 3 + j, -x);
            }
        }
    }
}

/// Σ ∂²θ/∂q_i∂q_j dir_i dir_j over the N director coordinates: one directional evaluation
/// (hyper-dual numbers along `dir`).
pub(super) fn rotation_second_along<F: NodeFrame, const N: usize>(
    port: &F,
    q: &[f64],
    dir: &[f64],
) -> [f64; 3] {
    let x: [HyperDual64; N] = std::array::from_fn(|k| {
        let mut v = HyperDual64::from_re(q[3 + k]);
        v.eps1 = dir[3 + k];
        v.eps2 = dir[3 + k];
        v
    });
    let mut h = Vector3::zeros();
    for d in port.frame(&x) {
        let re = Vector3::new(d[0].re, d[1].re, d[2].re);
        let dd = Vector3::new(d[0].eps1eps2, d[1].eps1eps2, d[2].eps1eps2);
        h += 0.5 * re.cross(&dd);
    }
    h.into()
}

impl Port<Spatial> for NodePort3 {
    fn kinematics(&self, q: &[f64]) -> EndKin3 {
        let d = q.len();
        let mut rotation = Grad3::from_elem(Vector3::zeros(), d);
        let frame = if self.director {
            let (f, r) = frame_rotation::<_, 6>(self, q);
            rotation[3..9].copy_from_slice(&r);
            f
        } else {
            let (f, r) = frame_rotation::<_, 3>(self, q);
            rotation[3..6].copy_from_slice(&r);
            f
        };
        EndKin3 {
            p: Field3::coordinates(q, 0, d),
            frame,
            rotation,
            tangent: Field3::coordinates(q, 3, d),
            section: self.director.then(|| Field3::coordinates(q, 6, d)),
            normals: None,
        }
    }

    /// p = r, the node's first three coordinates.
    fn point_force_residual(&self, _q: &[f64], force: &[f64; 3], r: &mut [f64]) {
        Field3::selection_force_residual(force, r)
    }

    /// The node's coordinates r, r_x (and r_y with a director).
    fn values(&self, q: &[f64]) -> EndValues3 {
        let v = |k: usize| Vector3::new(q[k], q[k + 1], q[k + 2]);
        EndValues3 {
            p: v(0),
            tangent: v(3),
            section: self.director.then(|| v(6)),
            normals: None,
        }
    }

    fn add_moment_stiffness(
        &self,
        q: &[f64],
        m: &[f64; 3],
        add: &mut dyn FnMut(usize, usize, f64),
    ) {
        if self.director {
            moment_stiffness::<_, 6>(self, q, m, add)
        } else {
            moment_stiffness::<_, 3>(self, q, m, add)
        }
    }

    /// One directional evaluation (hyper-dual numbers along `dir` on the director
    /// coordinates) instead of the default's three Hessians.
    fn rotation_second_derivative_along(&self, q: &[f64], dir: &[f64]) -> [f64; 3] {
        if self.director {
            rotation_second_along::<_, 6>(self, q, dir)
        } else {
            rotation_second_along::<_, 3>(self, q, dir)
        }
    }
}

/// The root support of an ANCF chain: which held coordinates (indices into the held values)
/// carry its force and moment. Clamped: r0, r0_x (and r0_y with torsion) held; ball: r0 only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeSupport3 {
    /// Held x, y, z of the root position r0.
    pub position: [usize; 3],
    /// Held first normal of the clamped slope direction (clamped; its residual is λ r0_x).
    pub slope: Option<[usize; 3]>,
    /// Held second normal of the clamped slope direction (clamped).
    pub normal: Option<[usize; 3]>,
    /// Held r0_y (clamped, with torsion).
    pub section: Option<[usize; 3]>,
    /// Held twist angle θ0 and the clamped axis t⁰ (clamped, with twist angles): its residual
    /// is the moment about t⁰.
    pub twist: Option<(usize, [f64; 3])>,
}

impl Support<Spatial> for NodeSupport3 {
    /// F = r_{r0}, M = Σ d × r_d about r0 over the held directions d (the normals n_1, n_2 of
    /// the clamped slope direction, the section director r0_y): the work of a rotation δθ of
    /// the held directions δd = δθ × d; plus r_θ t⁰ of a held twist angle.
    fn reaction(&self, r: &[f64], held: &[f64]) -> ([f64; 3], [f64; 3]) {
        let vec = |v: &[f64], i: [usize; 3]| Vector3::new(v[i[0]], v[i[1]], v[i[2]]);
        let mut m = Vector3::zeros();
        for idx in [self.slope, self.normal, self.section]
            .into_iter()
            .flatten()
        {
            m += vec(held, idx).cross(&vec(r, idx));
        }
        if let Some((i, axis)) = self.twist {
            m += r[i] * Vector3::from(axis);
        }
        (vec(r, self.position).into(), m.into())
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::model::dofs::{LocalDofs, Numbering};
    use crate::model::PortKin;
    use nalgebra::{Rotation3, Unit};

    fn reference() -> Matrix3<f64> {
        let axis = Unit::new_normalize(Vector3::new(0.3, -0.5, 0.8));
        Rotation3::from_axis_angle(&axis, 0.9).into_inner()
    }

    /// A node: position, then r_x and r_y moved away from the reference frame (stretched,
    /// sheared, turned by tens of degrees).
    fn node(torsion: bool) -> Vec<f64> {
        let f = reference();
        let mut q = vec![0.1, 0.2, -0.3];
        let rx = 1.05 * f.column(0) + 0.3 * f.column(1) - 0.4 * f.column(2);
        q.extend(rx.iter());
        if torsion {
            let ry = 0.2 * f.column(0) + 0.9 * f.column(1) + 0.5 * f.column(2);
            q.extend(ry.iter());
        }
        q
    }

    #[test]
    fn values_are_the_kinematics_values() {
        use crate::model::space::Space;
        for torsion in [false, true] {
            let port = NodePort3::new(torsion, reference());
            let q = node(torsion);
            let k = port.kinematics_first(&q);
            assert_eq!(port.values(&q), Spatial::port_values(&k));
        }
    }

    /// Asserts that `port`'s point-force residual at `q` is the default's (on its
    /// `kinematics_first`) bit for bit, zeros' signs included, for forces with a negative zero,
    /// a subnormal part and all zeros.
    pub(in crate::model::spatial) fn assert_point_force_residual_is_the_default(
        port: &dyn Port<Spatial>,
        q: &[f64],
    ) {
        for f in [[0.7, -1.3, 0.4], [-0.0, 2.5e-310, -3.0], [0.0, 0.0, 0.0]] {
            let mut want = vec![1.0; q.len()];
            crate::model::load::point_force_residual::<Spatial>(
                &port.kinematics_first(q),
                &f,
                &mut want,
            );
            let mut got = vec![1.0; q.len()];
            port.point_force_residual(q, &f, &mut got);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(&want), "{f:?}");
        }
    }

    #[test]
    fn point_force_residual_is_the_kinematics_one_bit_for_bit() {
        for torsion in [false, true] {
            let port = NodePort3::new(torsion, reference());
            assert_point_force_residual_is_the_default(&port, &node(torsion));
        }
    }

    /// Axial vector of the skew part of (∂D/∂q_k) Dᵀ by central differences: the rotation of
    /// the frame per unit q_k, independent of the ½Σ d × ∂d formula.
    pub(in crate::model::spatial) fn fd_rotation(
        port: &dyn Port<Spatial>,
        q: &[f64],
        k: usize,
    ) -> Vector3<f64> {
        let h = 1e-6;
        let (mut qp, mut qm) = (q.to_vec(), q.to_vec());
        qp[k] += h;
        qm[k] -= h;
        let dd = (port.kinematics(&qp).frame - port.kinematics(&qm).frame) / (2.0 * h);
        let w = dd * port.kinematics(q).frame.transpose();
        Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)])
    }

    #[test]
    fn frame_is_orthonormal_and_the_reference_at_the_initial_node() {
        for torsion in [true, false] {
            let port = NodePort3::new(torsion, reference());
            let f = reference();
            let mut q = vec![0.0; 3];
            q.extend(f.column(0).iter());
            if torsion {
                q.extend(f.column(1).iter());
            }
            let k = port.kinematics(&q);
            assert!((k.frame - f).amax() < 1e-15, "{torsion}");
            let k = port.kinematics(&node(torsion));
            assert!((k.frame.transpose() * k.frame - Matrix3::identity()).amax() < 1e-15);
            assert!((k.frame.determinant() - 1.0).abs() < 1e-15);
            let t = Vector3::from_column_slice(&node(torsion)[3..6]).normalize();
            assert!((k.frame.column(0) - t).amax() < 1e-15);
        }
    }

    #[test]
    fn rotation_and_moment_stiffness_match_central_differences() {
        for torsion in [true, false] {
            let port = NodePort3::new(torsion, reference());
            let q = node(torsion);
            let d = q.len();
            let kin = port.kinematics(&q);
            for k in 0..d {
                let fd = fd_rotation(&port, &q, k);
                let got = Vector3::from(kin.rotation_jacobian(k));
                assert!((fd - got).amax() < 1e-9, "{torsion} {k}: {fd} vs {got}");
            }
            let m = [0.7, -1.3, 0.4];
            let mut h = vec![0.0; d * d];
            port.add_moment_stiffness(&q, &m, &mut |i, j, v| h[i * d + j] += v);
            let hmax = h.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            assert!(hmax > 0.1, "{torsion}: {hmax}");
            for j in 0..d {
                let e = 1e-6;
                let (mut qp, mut qm) = (q.clone(), q.clone());
                qp[j] += e;
                qm[j] -= e;
                let (kp, km) = (port.kinematics(&qp), port.kinematics(&qm));
                for i in 0..d {
                    // residual r_i = −m·∂θ/∂q_i; stiffness ∂r_i/∂q_j
                    let rp = -Vector3::from(m).dot(&Vector3::from(kp.rotation_jacobian(i)));
                    let rm = -Vector3::from(m).dot(&Vector3::from(km.rotation_jacobian(i)));
                    let fd = (rp - rm) / (2.0 * e);
                    assert!(
                        (fd - h[i * d + j]).abs() < 1e-8,
                        "{torsion} ({i},{j}): {fd} vs {}",
                        h[i * d + j]
                    );
                }
            }
        }
    }

    #[test]
    fn support_reaction_balances_the_loads_on_an_element() {
        // A free element in a deformed state with accelerations, no gravity: its residual is
        // M ë + f_int, and the internal force is self-equilibrated, so the reaction computed from
        // the node-0 residual by NodeSupport3 must equal minus the force and moment (about r0)
        // of the node-1 residual plus the inertia resultant. With ë = 0 that resultant is the
        // moment dJ/dt of the director inertia's velocity terms (no force).
        for torsion in [true, false] {
            // the cable's damping is not frame-indifferent for spin about its tangent (see
            // ancf3d), so its damping force may carry a net moment: undamped here
            let tau = if torsion { 7e-4 } else { 0.0 };
            let mut p =
                crate::model::ancf3d::tests::props(torsion, tau, if torsion { 0.5 } else { 1.0 });
            // a director inertia 1e4 × the thin rod's, so that its moment dJ/dt (~ρI_p l |ė|²,
            // at the nodes only) stands well above the balance's tolerance
            p.rho_ip *= 1e4;
            let f = reference();
            let cols = [0, 1, 2].map(|c| [f[(0, c)], f[(1, c)], f[(2, c)]]);
            let mut e = crate::model::ancf3d::straight([0.1, 0.0, 0.2], cols, p.length, torsion);
            let d = e.len();
            for (k, x) in e.iter_mut().enumerate() {
                *x += 0.01 * ((k as f64) * 1.7).sin() * if k % (d / 2) < 3 { 0.1 } else { 1.0 };
            }
            let ed: Vec<f64> = (0..d).map(|k| (k as f64 * 0.9).cos()).collect();
            let mut num = Numbering::default();
            let dofs = LocalDofs::new(e.iter().map(|v| num.free(*v, 1.0)).collect());
            let acc = vec![0.0; d];
            let el = AncfElement3::new(p);
            let x = LocalState::new(&dofs, &[], (&e, &ed, &acc));
            let env = Env {
                gravity: [0.0; 3],
                load: 1.0,
            };
            let mut r = vec![0.0; d];
            el.residual(&x, &env, &mut r);
            let st = d / 2;
            let blocks = |b: usize| {
                if torsion {
                    vec![b + 3, b + 6]
                } else {
                    vec![b + 3]
                }
            };
            let sup = NodeSupport3 {
                position: [0, 1, 2],
                slope: Some([3, 4, 5]),
                normal: None,
                section: torsion.then_some([6, 7, 8]),
                twist: None,
            };
            let (fr, mr) = sup.reaction(&r, &e);
            let v = |a: &[f64], i: usize| Vector3::new(a[i], a[i + 1], a[i + 2]);
            let f1 = v(&r, st);
            let mut m1 = (v(&e, st) - v(&e, 0)).cross(&f1);
            for b in blocks(st) {
                m1 += v(&e, b).cross(&v(&r, b));
            }
            let scale = r.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            assert!(
                (Vector3::from(fr) + f1).amax() < 1e-12 * scale,
                "{torsion} force"
            );
            // the director inertia's velocity terms at ë = 0 have the moment dJ/dt, J = Σ_b x_b ×
            // ∂T_y/∂ẋ_b (its angular momentum; T_y quadratic in ė: central differences exact)
            let tab = p.tables();
            let ang = |e: &[f64]| {
                let mut j = Vector3::zeros();
                for b in (0..d).step_by(3) {
                    let pb = Vector3::from_fn(|c, _| {
                        let (mut vp, mut vm) = (ed.clone(), ed.clone());
                        vp[b + c] += 1.0;
                        vm[b + c] -= 1.0;
                        0.5 * (p.director_kinetic(&tab, e, &vp) - p.director_kinetic(&tab, e, &vm))
                    });
                    j += v(e, b).cross(&pb);
                }
                j
            };
            let h = 1e-6;
            let ep: Vec<f64> = e.iter().zip(&ed).map(|(x, y)| x + h * y).collect();
            let em: Vec<f64> = e.iter().zip(&ed).map(|(x, y)| x - h * y).collect();
            let jd = (ang(&ep) - ang(&em)) / (2.0 * h);
            if torsion {
                assert!(jd.amax() > 1e-10 * scale, "{jd} vs {scale}");
            }
            assert!(
                (Vector3::from(mr) + m1 - jd).amax() < 1e-12 * scale,
                "{torsion} moment: {} vs {jd}",
                Vector3::from(mr) + m1
            );
            assert!(Vector3::from(mr).amax() > 1e-6 * scale);
        }
    }

    fn state(e: &[f64], ed: &[f64]) -> (LocalDofs, Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut num = Numbering::default();
        let dofs = LocalDofs::new(e.iter().map(|v| num.free(*v, 1.0)).collect());
        (dofs, e.to_vec(), ed.to_vec(), vec![0.0; e.len()])
    }

    #[test]
    fn energies_and_validity_match_closed_forms() {
        // straight element along the reference axis, stretched by 1 %, translating at v and
        // spinning about its axis at ω: kinetic ½ρA l|v|² + ½ρI_p l ω² (r_y turns at ω about the
        // axis, its rate has length ω), strain ½EA l ε², gravity potential −ρA l g·(centre).
        let p = crate::model::ancf3d::tests::props(true, 0.0, 1.0);
        let f = reference();
        let (x, y) = (f.column(0), f.column(1));
        let (l, eps, om) = (p.length, 0.01, 40.0);
        let v = Vector3::new(0.3, -0.2, 0.5);
        let mut e = Vec::new();
        let mut ed = Vec::new();
        for s in [0.0, l] {
            e.extend((x * s * (1.0 + eps)).iter());
            e.extend((x * (1.0 + eps)).iter());
            e.extend(y.iter());
            ed.extend(v.iter());
            ed.extend([0.0; 3]);
            ed.extend((om * x.cross(&y)).iter());
        }
        let (dofs, q, qd, a) = state(&e, &ed);
        let mut el = AncfElement3::new(p);
        let g = [0.0, -9.81, 2.0];
        el.set_gravity(&g);
        let en = el.energies(&LocalState::new(&dofs, &[], (&q, &qd, &a)), &g);
        let kin = 0.5 * p.rho_a * l * v.norm_squared() + 0.5 * p.rho_ip * l * om * om;
        assert!(
            (en.kinetic - kin).abs() < 1e-14 * kin,
            "{} vs {kin}",
            en.kinetic
        );
        let strain = 0.5 * p.ea * l * eps * eps;
        assert!(
            (en.strain - strain).abs() < 1e-10 * strain,
            "{} vs {strain}",
            en.strain
        );
        let centre = x * 0.5 * l * (1.0 + eps);
        let pot = -p.rho_a * l * Vector3::from(g).dot(&centre);
        assert!(
            (en.potential - pot).abs() < 1e-15,
            "{} vs {pot}",
            en.potential
        );
        let val = el.validity(&e);
        assert!((val.axial_strain - eps).abs() < 1e-14 && val.modal_deflection.is_none());
    }
}
