//! The spatial floating-frame modal body as components: [`ModalElement3`] (the element),
//! [`ModalTipPort3`] and [`ModalRootPort3`] (its ends), [`EulerNormalization`] (the row that
//! keeps the Euler parameters of a free frame on the unit sphere) and [`FrameSupport3`] (the
//! reaction of a clamped or ball root). Local coordinates are the kernel's,
//! `[R(3), p(4), a_y(nb), a_z(nb), a_t(2)]` ([`ModalBody3`]).
//!
//! Port fields are A(p)·v̄(a) (+ R) with v̄ at most quadratic in a, so their first and second
//! derivatives are closed-form: ∂(Av̄)/∂p = 2[e0v̄ + e×v̄, (eᵀv̄)I + ev̄ᵀ − v̄eᵀ − e0ṽ̄] and the
//! constant ∂²(Av̄)/∂p² (docs/references.md §7.2), valid for any p.

use super::kin::{BarSecond, Coef, FrameSecond, Grad3, Second3, Sparse3};
use super::{EndKin3, EndValues3, Field3, Spatial};
use crate::math;
use crate::model::assembly::Model;
use crate::model::component::{
    Constraint, ConstraintOut, Element, ElementOut, Energies, Env, LocalState, Port, Support,
    Validity, LOCAL_INLINE,
};
use crate::model::modal::body3d::{self, euler_rotation};
use crate::model::modal::{BodyGravity, ModalBody3};
use crate::model::sample::ShapePoint;
use crate::model::vector::{self, cross, Real, V3};
use nalgebra::{Matrix3, Vector3};
use num_dual::HyperDual64;
use std::any::Any;
use std::sync::Arc;

/// Index of the first Euler parameter among the body's local coordinates.
const P0: usize = 3;

/// ∂(A v̄)/∂p_k, k = 0..4 (any p).
fn d_av(p: &[f64; 4], v: &Vector3<f64>) -> [Vector3<f64>; 4] {
    let e0 = p[0];
    let e = Vector3::new(p[1], p[2], p[3]);
    let ev = e.dot(v);
    let mut out = [2.0 * (e0 * v + e.cross(v)); 4];
    for j in 0..3 {
        let mut u = Vector3::zeros();
        u[j] = 1.0;
        out[1 + j] = 2.0 * (ev * u + e * v[j] - v * e[j] - e0 * v.cross(&u));
    }
    out
}

/// ∂²(A v̄)/∂p_i∂p_j (constant in p).
fn dd_av(v: &Vector3<f64>, i: usize, j: usize) -> Vector3<f64> {
    let unit = |k: usize| {
        let mut u = Vector3::zeros();
        u[k] = 1.0;
        u
    };
    match (i, j) {
        (0, 0) => 2.0 * v,
        (0, k) | (k, 0) => 2.0 * unit(k - 1).cross(v),
        (j, k) => {
            let (j, k) = (j - 1, k - 1);
            let mut h = 2.0 * (v[k] * unit(j) + v[j] * unit(k));
            if j == k {
                h -= 2.0 * v;
            }
            h
        }
    }
}

/// A(p) and its derivatives ∂A/∂p_k at one p (A is quadratic in p: these give every
/// ∂(Av̄)/∂p = ∂A/∂p v̄ by one product).
struct Attitude {
    a: Matrix3<f64>,
    da: [Matrix3<f64>; 4],
}

impl Attitude {
    fn new(q: &[f64]) -> Self {
        let p = [q[P0], q[P0 + 1], q[P0 + 2], q[P0 + 3]];
        let a = euler_rotation(p);
        let cols = [Vector3::x(), Vector3::y(), Vector3::z()].map(|e| d_av(&p, &e));
        Self {
            a: Matrix3::from_fn(|i, j| a[i][j]),
            da: [0, 1, 2, 3].map(|k| Matrix3::from_columns(&[cols[0][k], cols[1][k], cols[2][k]])),
        }
    }
}

/// The field A(p)·v̄(a) (+ R if `with_r`) over `dim` local coordinates, from v̄ at the current
/// a, its derivatives `dv` (local index, ∂v̄/∂q_k) and second derivatives `ddv`; the second
/// derivatives of the field only if `second` (else `dd` stays empty and `ddv` unused): those of
/// A(p) listed, the others kept as their factors ([`FrameSecond`]).
#[allow(clippy::too_many_arguments)]
fn frame_field(
    q: &[f64],
    att: &Attitude,
    dim: usize,
    with_r: bool,
    v: Vector3<f64>,
    dv: &[(usize, Vector3<f64>)],
    ddv: BarSecond,
    second: bool,
) -> Field3 {
    let a = &att.a;
    let mut f = Field3 {
        v: a * v,
        d: Grad3::from_elem(Vector3::zeros(), dim),
        dd: Second3::default(),
    };
    if with_r {
        for c in 0..3 {
            f.v[c] += q[c];
            f.d[c][c] = 1.0;
        }
    }
    for (k, da) in att.da.iter().enumerate() {
        f.d[P0 + k] = da * v;
    }
    for &(k, b) in dv {
        f.d[k] += a * b;
    }
    if !second {
        return f;
    }
    if v != Vector3::zeros() {
        for i in 0..4 {
            for j in i..4 {
                let h = dd_av(&v, i, j);
                if h != Vector3::zeros() {
                    f.dd.list.push((P0 + i, P0 + j, h));
                }
            }
        }
    }
    if !dv.is_empty() || ddv != BarSecond::Zero {
        f.dd.frame = Some(FrameSecond {
            p0: P0,
            a: att.a,
            da: att.da,
            dv: Sparse3::from_slice(dv),
            ddv,
        });
    }
    f
}

/// Orthonormal frame [t, d2, d3] of a tangent and a section director: t = T/|T|, d2 the
/// normalized part of S ⟂ t, d3 = t × d2.
fn frame_of<T: Real>(t: V3<T>, s: V3<T>) -> [V3<T>; 3] {
    let t = vector::scale(t, vector::dot(t, t).sqrt().recip());
    let u = vector::add(s, vector::scale(t, -vector::dot(t, s)));
    let d2 = vector::scale(u, vector::dot(u, u).sqrt().recip());
    let d3 = cross(t, d2);
    [t, d2, d3]
}

/// The end kinematics from position, directors and normals: frame [t, d2, d3] of the tangent
/// T and the section director S ([`frame_of`]) and its rotation ω_k = ½Σ d_i × ∂d_i/∂q_k, in
/// closed form on the frame: with |T|, u = S − (t·S)t,
/// ω_k = ((∂S·d3 − (t·S)(∂T·d3)/|T|)/|u|) t − (∂T·d3/|T|) d2 + (∂T·d2/|T|) d3.
fn end_kin(p: Field3, tangent: Field3, section: Field3, normals: [Field3; 3]) -> EndKin3 {
    let [t, d2, d3] = frame_of(tangent.v.into(), section.v.into()).map(Vector3::from);
    let frame = Matrix3::from_columns(&[t, d2, d3]);
    let tn = tangent.v.norm();
    let ts = t.dot(&section.v);
    let un = (section.v - ts * t).norm();
    let rotation = tangent
        .d
        .iter()
        .zip(&section.d)
        .map(|(dt, ds)| {
            let (t2, t3) = (dt.dot(&d2) / tn, dt.dot(&d3) / tn);
            (ds.dot(&d3) - ts * t3) / un * t - t3 * d2 + t2 * d3
        })
        .collect();
    EndKin3 {
        p,
        frame,
        rotation,
        tangent,
        section: Some(section),
        normals: Some(normals),
    }
}

/// Hyper-dual local coordinates (inline up to [`LOCAL_INLINE`]).
type Duals = smallvec::SmallVec<[HyperDual64; LOCAL_INLINE]>;

/// Adds −m·∂²θ/∂q_i∂q_j of the frame of directors (T(q), S(q)) given as a generic function
/// of q, by hyper-dual numbers (exact), over the coordinates `active` (the others do not move
/// the frame).
fn frame_moment_stiffness(
    q: &[f64],
    m: &[f64; 3],
    active: impl Iterator<Item = usize> + Clone,
    directors: impl Fn(&[HyperDual64]) -> (V3<HyperDual64>, V3<HyperDual64>),
    add: &mut dyn FnMut(usize, usize, f64),
) {
    let mut x: Duals = q.iter().map(|&v| HyperDual64::from_re(v)).collect();
    for i in active.clone() {
        for j in active.clone() {
            x[i].eps1 = 1.0;
            x[j].eps2 = 1.0;
            let (t, s) = directors(&x);
            let fr = frame_of(t, s);
            // ∂_j(½Σ d × ∂_i d) = ½Σ (∂_j d × ∂_i d + d × ∂_ij d)
            let mut h = Vector3::zeros();
            for d in fr {
                let re = Vector3::new(d[0].re, d[1].re, d[2].re);
                let di = Vector3::new(d[0].eps1, d[1].eps1, d[2].eps1);
                let dj = Vector3::new(d[0].eps2, d[1].eps2, d[2].eps2);
                let dij = Vector3::new(d[0].eps1eps2, d[1].eps1eps2, d[2].eps1eps2);
                h += 0.5 * (dj.cross(&di) + re.cross(&dij));
            }
            add(i, j, -Vector3::from(*m).dot(&h));
            x[i].eps1 = 0.0;
            x[j].eps2 = 0.0;
        }
    }
}

/// [`frame_moment_stiffness`]'s second derivative along one direction: ∂²θ[dir, dir] =
/// ½Σ_d d × ∂²d[dir, dir] (the cross term ∂d × ∂d vanishes), one hyper-dual evaluation with both
/// parts seeded by `dir` on the `active` coordinates.
fn frame_rotation_second_derivative(
    q: &[f64],
    dir: &[f64],
    active: impl Iterator<Item = usize>,
    directors: impl Fn(&[HyperDual64]) -> (V3<HyperDual64>, V3<HyperDual64>),
) -> [f64; 3] {
    let mut x: Duals = q.iter().map(|&v| HyperDual64::from_re(v)).collect();
    for i in active {
        x[i].eps1 = dir[i];
        x[i].eps2 = dir[i];
    }
    let (t, s) = directors(&x);
    let mut h = Vector3::zeros();
    for d in frame_of(t, s) {
        let re = Vector3::new(d[0].re, d[1].re, d[2].re);
        let dd = Vector3::new(d[0].eps1eps2, d[1].eps1eps2, d[2].eps1eps2);
        h += 0.5 * re.cross(&dd);
    }
    h.into()
}

/// A spatial floating-frame modal body, local coordinates `[R, p, a_y, a_z, a_t]`.
#[derive(Debug, Clone)]
pub struct ModalElement3 {
    /// The body (shared with its ports).
    pub body: Arc<ModalBody3>,
    /// Local (q, q̇, q̈, r) of the last evaluation (reused: no allocation per iteration).
    x: [Vec<f64>; 4],
    /// The Newton block of the last evaluation, row-major d × d (reused likewise).
    block: Vec<f64>,
    /// The segment's line load over ρA, q/(ρA) [m/s²] (the body's at build, then
    /// [`Element::set_line_load`]'s); `None` without one.
    line: Option<[f64; 3]>,
}

impl ModalElement3 {
    /// Component of `body`.
    pub fn new(body: Arc<ModalBody3>) -> Self {
        let d = body.dim();
        Self {
            line: body.line,
            body,
            x: [vec![0.0; d], vec![0.0; d], vec![0.0; d], vec![0.0; d]],
            block: vec![0.0; d * d],
        }
    }
}

impl Element<Spatial> for ModalElement3 {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Spatial>, mut out: ElementOut<'_>) {
        let g = BodyGravity::of(env.gravity, env.load, self.line);
        let [q, v, a, r] = &mut self.x;
        x.gather(q, v, a);
        self.body.residual(q, v, a, g, r);
        out.add_residual(r);
        if let Some(c) = out.matrix {
            let d = self.body.dim();
            let block = &mut self.block;
            self.body.newton_block((q, v, a), g, c, block);
            out.add_block(|i, j| block[i * d + j]);
        }
    }

    fn residual(&self, x: &LocalState<'_>, env: &Env<Spatial>, res: &mut [f64]) {
        let (q, v, a) = x.vectors();
        self.body.residual(
            &q,
            &v,
            &a,
            BodyGravity::of(env.gravity, 1.0, self.line),
            res,
        );
    }

    fn energies(&self, x: &LocalState<'_>, gravity: &[f64; 3]) -> Energies {
        let (q, v, _) = x.vectors();
        Energies {
            kinetic: self.body.kinetic_energy(&q, &v),
            strain: self.body.strain_energy(&q),
            potential: self
                .body
                .potential_energy(&q, BodyGravity::of(*gravity, 1.0, self.line)),
        }
    }

    /// [`ModalBody3::partial_load`] with the element's line load.
    fn partial_load(
        &self,
        x: &LocalState<'_>,
        gravity: &[f64; 3],
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let (q, v, a) = x.vectors();
        let g = BodyGravity::of(*gravity, 1.0, self.line);
        self.body.partial_load((&q, &v, &a), g, xi, about)
    }

    fn set_line_load(&mut self, q: &[f64; 3]) {
        self.line = Some(q.map(|c| c / self.body.props.rho_a));
    }

    fn length(&self) -> f64 {
        self.body.props.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (q, v, _) = x.vectors();
        self.body.sample(&q, &v, xi, out);
    }

    fn is_damped(&self) -> bool {
        self.body.is_damped()
    }

    /// [`ModalBody3::deflection`]: max of tip deflection / L, tip slope and tip twist.
    fn validity(&self, q: &[f64]) -> Validity {
        Validity {
            axial_strain: 0.0,
            modal_deflection: Some(self.body.deflection(q)),
            section: None,
            chart_margin: None,
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// sin σ/σ and (1 − cos σ)/σ² as functions of x = σ² (smooth at 0: power series below
/// x = 1/4, to rounding; closed form above).
fn rotation_coefficients<T: Real>(x: T) -> (T, T) {
    if x.re() < 0.25 {
        // Σ (−x)^k/(2k+1)!, Σ (−x)^k/(2k+2)!, k = 0..8 (next term < 1e-18)
        let (mut a, mut b) = (T::zero(), T::zero());
        let mut fact = [1.0; 20];
        for k in 1..20 {
            fact[k] = fact[k - 1] * k as f64;
        }
        for k in (0..9).rev() {
            a = a * (-x) + T::from(1.0 / fact[2 * k + 1]);
            b = b * (-x) + T::from(1.0 / fact[2 * k + 2]);
        }
        (a, b)
    } else {
        let s = x.sqrt();
        let (sn, cs) = math::sin_cos_dual(s);
        (sn / s, (T::one() - cs) / x)
    }
}

/// The tip directors in the body frame as functions of the tip slopes v′, w′ and the tip twist
/// θ: `[t̂, s̄, n̄1, n̄2, n̄3]`, the columns of R(ψ)·R_x(θ) with R(ψ) the rotation by the vector
/// ψ = (0, −w′, v′) (angle σ = |(v′, w′)|, about the normal of the bending plane): t̂ = R x̄,
/// n̄1 = R ȳ, n̄2 = R z̄, s̄ = cos θ n̄1 + sin θ n̄2, n̄3 = cos θ n̄2 − sin θ n̄1. In the x–y plane
/// (w′ = 0) n̄1 = (−sin v′, cos v′, 0), n̄2 = z̄: the frame is turned by exactly v′ about z̄, as
/// the planar joint places the next segment (θ + v′, the linearized slope used as an angle); in
/// the x–z plane likewise n̄2 = (−sin w′, 0, cos w′). Isotropic (a bending plane turned about x̄
/// turns the directors with it); to first order t̂ = x̄ + v′ȳ + w′z̄, n̄1 = ȳ − v′x̄,
/// n̄2 = z̄ − w′x̄, s̄ = ȳ + θz̄ − v′x̄, n̄3 = z̄ − θȳ − w′x̄.
///
/// With `nonlinear` (the geometrically nonlinear body, whose centreline is ū = (x − ½∫(v′² +
/// w′²), v, w)) the angle is that of the field's tangent (1 − ½σ², v′, w′) instead, σ̃ =
/// atan2(σ, 1 − ½σ²) = σ + σ³/6 + …, about the same axis: with D = √(1 + σ⁴/4), sin σ̃ = σ/D and
/// cos σ̃ = (1 − ½σ²)/D, so the coefficients of ψ, sin σ̃/σ = 1/D and (1 − cos σ̃)/σ² =
/// (½ + σ²/(4(D + 1)))/D, are smooth in σ² (t̂ is the unit tangent of the field, as the planar
/// port's θ + atan2(w′, 1 − ½w′²)).
fn tip_directors<T: Real>(vs: T, ws: T, th: T, nonlinear: bool) -> [V3<T>; 5] {
    let x = vs * vs + ws * ws;
    let (a, b) = if nonlinear {
        let d = (T::one() + x * x * 0.25).sqrt();
        (d.recip(), (x / ((d + 1.0) * 4.0) + 0.5) / d)
    } else {
        rotation_coefficients(x)
    };
    let one = T::one();
    let t = [one - b * (vs * vs + ws * ws), a * vs, a * ws];
    let n1 = [-(a * vs), one - b * vs * vs, -(b * vs * ws)];
    let n2 = [-(a * ws), -(b * vs * ws), one - b * ws * ws];
    let (st, ct) = math::sin_cos_dual(th);
    let s = vector::add(vector::scale(n1, ct), vector::scale(n2, st));
    let n3 = vector::add(vector::scale(n2, ct), vector::scale(n1, -st));
    [t, s, n1, n2, n3]
}

/// Pairs (i, j) of the variables (v′, w′, θ) of [`tip_directors`]: the diagonal first (enough
/// for the first derivatives), then the mixed ones.
const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// [`tip_directors`] with its first and (if asked) second derivatives by (v′, w′, θ), exact
/// (hyper-dual numbers: 3 evaluations for the first derivatives, 6 with the second).
struct TipDirectors {
    /// Values.
    v: [Vector3<f64>; 5],
    /// ∂/∂(v′, w′, θ).
    g: [[Vector3<f64>; 3]; 5],
    /// ∂²/∂x_i∂x_j in the order of [`PAIRS`] (zero if not asked).
    h: [[Vector3<f64>; 6]; 5],
}

impl TipDirectors {
    fn new(x: [f64; 3], second: bool, nonlinear: bool) -> Self {
        let mut out = Self {
            v: [Vector3::zeros(); 5],
            g: [[Vector3::zeros(); 3]; 5],
            h: [[Vector3::zeros(); 6]; 5],
        };
        for (pi, &(i, j)) in PAIRS.iter().take(if second { 6 } else { 3 }).enumerate() {
            let mut y = x.map(HyperDual64::from_re);
            y[i].eps1 = 1.0;
            y[j].eps2 = 1.0;
            for (n, r) in tip_directors(y[0], y[1], y[2], nonlinear)
                .iter()
                .enumerate()
            {
                out.v[n] = Vector3::new(r[0].re, r[1].re, r[2].re);
                out.g[n][i] = Vector3::new(r[0].eps1, r[1].eps1, r[2].eps1);
                out.h[n][pi] = Vector3::new(r[0].eps1eps2, r[1].eps1eps2, r[2].eps1eps2);
            }
        }
        out
    }
}

/// The tip (ξ = 1) of a spatial modal body, on the body's local coordinates:
/// p = R + Aū_T(a) (foreshortening in both planes) and the directors A·[`tip_directors`] of the
/// tip slopes v′ = φ′(1)ᵀa_y/L, w′ = φ′(1)ᵀa_z/L and twist θ = χ(1)ᵀa_t: tangent A t̂, section
/// A s̄, normals A n̄1, A n̄2, A n̄3; frame A[t̂, s̄, n̄3] (orthonormal by construction), rotation
/// its exact derivative.
#[derive(Debug, Clone)]
pub struct ModalTipPort3(pub Arc<ModalBody3>);

impl ModalTipPort3 {
    /// Tangent and section directors as generic functions of q (for the moment stiffness).
    fn directors<T: Real>(&self, q: &[T]) -> (V3<T>, V3<T>) {
        let b = &*self.0;
        let nb = b.modes();
        let l = b.props.length;
        let (mut vs, mut ws) = (T::zero(), T::zero());
        for n in 0..nb {
            vs += q[b.iy(n)] * (b.basis.tip_slope[n] / l);
            ws += q[b.iz(n)] * (b.basis.tip_slope[n] / l);
        }
        let th = q[b.it(0)] * b.chi_tip[0] + q[b.it(1)] * b.chi_tip[1];
        let a = euler_rotation([q[P0], q[P0 + 1], q[P0 + 2], q[P0 + 3]]);
        let [t, s, ..] = tip_directors(vs, ws, th, b.nonlinear);
        (body3d::mul(&a, t), body3d::mul(&a, s))
    }

    /// The kinematics, with the fields' second derivatives only if `second`.
    fn end(&self, q: &[f64], second: bool) -> EndKin3 {
        let b = &*self.0;
        let nb = b.modes();
        let d = b.dim();
        let l = b.props.length;
        let att = Attitude::new(q);
        // position: ū_T and its derivatives
        let u = Vector3::from(b.tip_local(q));
        let gy = b.foreshortening_gradient(&q[b.iy(0)..b.iy(0) + nb]);
        let gz = b.foreshortening_gradient(&q[b.iz(0)..b.iz(0) + nb]);
        let mut dv = Sparse3::new();
        for n in 0..nb {
            dv.push((b.iy(n), Vector3::new(-gy[n], b.basis.tip[n], 0.0)));
            dv.push((b.iz(n), Vector3::new(-gz[n], 0.0, b.basis.tip[n])));
        }
        // ∂²ū_T: the foreshortening's −G/L in both planes
        let ddv = BarSecond::Gram {
            gram: b.gram.clone(),
            nb,
            first: [b.iy(0), b.iz(0)],
            length: l,
        };
        let pos = frame_field(q, &att, d, true, u, &dv, ddv, second);
        // directors: functions of (v′, w′, θ), each linear in its amplitudes with the
        // coefficients (local index, ∂x/∂q_k) of `coef`
        let (_, slope, th) = b.tip_elastic(q);
        let dirs = TipDirectors::new([slope[0], slope[1], th], second, b.nonlinear);
        let coef = |i: usize| -> Coef {
            match i {
                0 => (0..nb)
                    .map(|n| (b.iy(n), b.basis.tip_slope[n] / l))
                    .collect(),
                1 => (0..nb)
                    .map(|n| (b.iz(n), b.basis.tip_slope[n] / l))
                    .collect(),
                _ => (0..2).map(|m| (b.it(m), b.chi_tip[m])).collect(),
            }
        };
        let coef = [coef(0), coef(1), coef(2)];
        let mut field = |n: usize| {
            dv.clear();
            for (i, c) in coef.iter().enumerate() {
                let g = dirs.g[n][i];
                if g != Vector3::zeros() {
                    dv.extend(c.iter().map(|&(k, x)| (k, g * x)));
                }
            }
            let ddv = if second {
                BarSecond::Chain {
                    coef: coef.clone(),
                    pairs: std::array::from_fn(|pi| (PAIRS[pi], dirs.h[n][pi])),
                }
            } else {
                BarSecond::Zero
            };
            frame_field(q, &att, d, false, dirs.v[n], &dv, ddv, second)
        };
        // one by one (not an array map: each field is a large value, moved as little as possible)
        let (tangent, section) = (field(0), field(1));
        let (n1, n2, n3) = (field(2), field(3), field(4));
        end_kin(pos, tangent, section, [n1, n2, n3])
    }
}

impl Port<Spatial> for ModalTipPort3 {
    fn kinematics(&self, q: &[f64]) -> EndKin3 {
        self.end(q, true)
    }

    /// The values of [`ModalTipPort3::end`]'s fields, bit for bit, without their derivatives:
    /// p = R + A ū_T, the directors A·[`tip_directors`] (evaluated on hyper-duals as `end` does,
    /// whose real parts do not depend on the dual parts).
    fn values(&self, q: &[f64]) -> EndValues3 {
        let b = &*self.0;
        let pe = [q[P0], q[P0 + 1], q[P0 + 2], q[P0 + 3]];
        let e = euler_rotation(pe);
        let a = Matrix3::from_fn(|i, j| e[i][j]);
        let mut p = a * Vector3::from(b.tip_local(q));
        for c in 0..3 {
            p[c] += q[c];
        }
        let (_, slope, th) = b.tip_elastic(q);
        let y = [slope[0], slope[1], th].map(HyperDual64::from_re);
        let dirs = tip_directors(y[0], y[1], y[2], b.nonlinear)
            .map(|r| a * Vector3::new(r[0].re, r[1].re, r[2].re));
        EndValues3 {
            p,
            tangent: dirs[0],
            section: Some(dirs[1]),
            normals: Some([dirs[2], dirs[3], dirs[4]]),
        }
    }

    fn kinematics_first(&self, q: &[f64]) -> EndKin3 {
        self.end(q, false)
    }

    /// Exact −m·∂²θ/∂q∂q of the tip frame (hyper-dual numbers over p and the amplitudes).
    fn add_moment_stiffness(
        &self,
        q: &[f64],
        m: &[f64; 3],
        add: &mut dyn FnMut(usize, usize, f64),
    ) {
        frame_moment_stiffness(q, m, P0..q.len(), |x| self.directors(x), add);
    }

    fn rotation_second_derivative_along(&self, q: &[f64], dir: &[f64]) -> [f64; 3] {
        frame_rotation_second_derivative(q, dir, P0..q.len(), |x| self.directors(x))
    }
}

/// The root (frame origin) of a spatial modal body, on the body's local coordinates: p = R,
/// tangent A x̄, section A ȳ, normals [A ȳ, A z̄, A z̄]; frame A (orthonormalized), rotation
/// its exact derivative (2E for unit p).
#[derive(Debug, Clone)]
pub struct ModalRootPort3(pub Arc<ModalBody3>);

impl ModalRootPort3 {
    /// The kinematics, with the fields' second derivatives only if `second`.
    fn end(&self, q: &[f64], second: bool) -> EndKin3 {
        let d = self.0.dim();
        let att = Attitude::new(q);
        let f = |v: Vector3<f64>| frame_field(q, &att, d, false, v, &[], BarSecond::Zero, second);
        let pos = frame_field(
            q,
            &att,
            d,
            true,
            Vector3::zeros(),
            &[],
            BarSecond::Zero,
            second,
        );
        let (fy, fz) = (f(Vector3::y()), f(Vector3::z()));
        end_kin(pos, f(Vector3::x()), fy.clone(), [fy, fz.clone(), fz])
    }
}

impl Port<Spatial> for ModalRootPort3 {
    fn kinematics(&self, q: &[f64]) -> EndKin3 {
        self.end(q, true)
    }

    fn kinematics_first(&self, q: &[f64]) -> EndKin3 {
        self.end(q, false)
    }

    /// Exact −m·∂²θ/∂p∂p of the frame A(p) (hyper-dual numbers).
    fn add_moment_stiffness(
        &self,
        q: &[f64],
        m: &[f64; 3],
        add: &mut dyn FnMut(usize, usize, f64),
    ) {
        frame_moment_stiffness(
            q,
            m,
            P0..P0 + 4,
            |x| {
                let a = euler_rotation([x[P0], x[P0 + 1], x[P0 + 2], x[P0 + 3]]);
                let (o, z) = (HyperDual64::from_re(1.0), HyperDual64::from_re(0.0));
                (body3d::mul(&a, [o, z, z]), body3d::mul(&a, [z, o, z]))
            },
            add,
        );
    }
}

/// The normalization of a free frame's Euler parameters, one row on the 4 local coordinates
/// p: Φ = ½(pᵀp − 1) (dimensionless; the ½ makes Φ_q = pᵀ of unit length, so the multiplier
/// is the generalized force along p [N m]), Hessian λI.
#[derive(Debug, Clone, Copy, Default)]
pub struct EulerNormalization;

impl Constraint for EulerNormalization {
    fn rows(&self) -> usize {
        1
    }

    fn eval(&self, q: &[f64], lambda: Option<&[f64]>, out: &mut ConstraintOut) {
        out.phi[0] = 0.5 * (q.iter().map(|x| x * x).sum::<f64>() - 1.0);
        out.jac.copy_from_slice(&q[..4]);
        if let Some(l) = lambda {
            out.hess.extend((0..4).map(|k| (k, k, l[0])));
        }
    }
}

/// The root support of a spatial modal body: indices into the held values of R and, for a
/// clamped root, of p. Force on the beam F = r_R; moment about the root M = ½E(p)r_p (world;
/// E p = 0 filters the normalization direction), zero for a ball root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameSupport3 {
    /// Held R (x, y, z).
    pub position: [usize; 3],
    /// Held p (e0..e3) of a clamped root; `None` for a ball root.
    pub attitude: Option<[usize; 4]>,
}

impl Support<Spatial> for FrameSupport3 {
    fn reaction(&self, r: &[f64], held: &[f64]) -> ([f64; 3], [f64; 3]) {
        let f = self.position.map(|i| r[i]);
        let m = self.attitude.map_or([0.0; 3], |ix| {
            let e = body3d::e_world(ix.map(|i| held[i]));
            let rp = ix.map(|i| r[i]);
            [0, 1, 2].map(|c| 0.5 * (0..4).map(|k| e[c][k] * rp[k]).sum::<f64>())
        });
        (f, m)
    }
}

impl Model<Spatial> {
    /// The `i`-th spatial modal body in summation order (for tests and analyses).
    pub fn modal_body(&self, i: usize) -> &ModalBody3 {
        &self
            .elements_of::<ModalElement3>()
            .nth(i)
            .expect("modal body index in range")
            .body
    }
}
