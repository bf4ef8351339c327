//! The spatial floating-frame modal body as components: [`ModalElement3`] (the element),
//! [`ModalTipPort3`] and [`ModalRootPort3`] (its ends), [`EulerNormalization`] (the row that
//! keeps the Euler parameters of a free frame on the unit sphere) and [`FrameSupport3`] (the
//! reaction of a clamped or ball root). Local coordinates are the kernel's,
//! `[R(3), p(4), a_y(nb), a_z(nb), a_t(2)]` ([`ModalBody3`]).
//!
//! Port fields are A(p)·v̄(a) (+ R) with v̄ at most quadratic in a, so their first and second
//! derivatives are closed-form: ∂(Av̄)/∂p = 2[e0v̄ + e×v̄, (eᵀv̄)I + ev̄ᵀ − v̄eᵀ − e0ṽ̄] and the
//! constant ∂²(Av̄)/∂p² (shared spatial brief §2.1), valid for any p.

use super::{EndKin3, Field3, Spatial};
use crate::model::assembly::Model;
use crate::model::component::{
    Constraint, ConstraintOut, Element, ElementOut, Energies, Env, LocalState, Port, Support,
    Validity,
};
use crate::model::modal::body3d::{self, cross, euler_rotation, Real, V3};
use crate::model::modal::ModalBody3;
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
/// a, its derivatives `dv` (local index, ∂v̄/∂q_k) and second derivatives `ddv` (k ≤ l).
fn frame_field(
    q: &[f64],
    att: &Attitude,
    dim: usize,
    with_r: bool,
    v: Vector3<f64>,
    dv: &[(usize, Vector3<f64>)],
    ddv: &[(usize, usize, Vector3<f64>)],
) -> Field3 {
    let a = &att.a;
    let mut f = Field3 {
        v: a * v,
        d: vec![Vector3::zeros(); dim],
        dd: Vec::with_capacity(10 + 4 * dv.len() + ddv.len()),
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
    let mut push = |i: usize, j: usize, h: Vector3<f64>| {
        if h != Vector3::zeros() {
            f.dd.push((i, j, h));
        }
    };
    if v != Vector3::zeros() {
        for i in 0..4 {
            for j in i..4 {
                push(P0 + i, P0 + j, dd_av(&v, i, j));
            }
        }
    }
    for &(k, b) in dv {
        for (i, da) in att.da.iter().enumerate() {
            push(P0 + i, k, da * b);
        }
    }
    for &(k, l, c) in ddv {
        push(k, l, a * c);
    }
    for &(k, b) in dv {
        f.d[k] += a * b;
    }
    f
}

/// Orthonormal frame [t, d2, d3] of a tangent and a section director: t = T/|T|, d2 the
/// normalized part of S ⟂ t, d3 = t × d2.
fn frame_of<T: Real>(t: V3<T>, s: V3<T>) -> [V3<T>; 3] {
    let t = body3d::scale(t, body3d::dot(t, t).sqrt().recip());
    let u = body3d::add(s, body3d::scale(t, -body3d::dot(t, s)));
    let d2 = body3d::scale(u, body3d::dot(u, u).sqrt().recip());
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
    let mut x: Vec<HyperDual64> = q.iter().map(|&v| HyperDual64::from_re(v)).collect();
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

/// A spatial floating-frame modal body, local coordinates `[R, p, a_y, a_z, a_t]`.
#[derive(Debug, Clone)]
pub struct ModalElement3 {
    /// The body (shared with its ports).
    pub body: Arc<ModalBody3>,
    /// Local (q, q̇, q̈, r) of the last evaluation (reused: no allocation per iteration).
    x: [Vec<f64>; 4],
}

impl ModalElement3 {
    /// Component of `body`.
    pub fn new(body: Arc<ModalBody3>) -> Self {
        let d = body.dim();
        Self {
            body,
            x: [vec![0.0; d], vec![0.0; d], vec![0.0; d], vec![0.0; d]],
        }
    }
}

impl Element<Spatial> for ModalElement3 {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Spatial>, mut out: ElementOut<'_>) {
        let g = env.gravity.map(|c| env.load * c);
        let [q, v, a, r] = &mut self.x;
        x.gather(q, v, a);
        self.body.residual(q, v, a, g, r);
        out.add_residual(r);
        if let Some(c) = out.matrix {
            let d = self.body.dim();
            let mut block = vec![0.0; d * d];
            self.body.newton_block((q, v, a), g, c, &mut block);
            out.add_block(|i, j| block[i * d + j]);
        }
    }

    fn residual(&self, x: &LocalState<'_>, env: &Env<Spatial>, res: &mut [f64]) {
        let (q, v, a) = x.vectors();
        self.body.residual(&q, &v, &a, env.gravity, res);
    }

    fn energies(&self, x: &LocalState<'_>, gravity: &[f64; 3]) -> Energies {
        let (q, v, _) = x.vectors();
        Energies {
            kinetic: self.body.kinetic_energy(&q, &v),
            strain: self.body.strain_energy(&q),
            potential: self.body.potential_energy(&q, *gravity),
        }
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
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// The tip (ξ = 1) of a spatial modal body, on the body's local coordinates:
/// p = R + Aū_T(a) (foreshortening in both planes), tangent A(x̄ + v′ȳ + w′z̄), section
/// A(ȳ + θz̄ − v′x̄), normals A n̄1 = A(ȳ − v′x̄), A n̄2 = A(z̄ − w′x̄), A n̄3 = A(z̄ − θȳ − w′x̄);
/// frame = orthonormalized (tangent, section), rotation its exact derivative.
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
        let one = T::one();
        (
            body3d::mul(&a, [one, vs, ws]),
            body3d::mul(&a, [-vs, one, th]),
        )
    }
}

impl Port<Spatial> for ModalTipPort3 {
    fn kinematics(&self, q: &[f64]) -> EndKin3 {
        let b = &*self.0;
        let nb = b.modes();
        let d = b.dim();
        let l = b.props.length;
        let att = Attitude::new(q);
        let (_, slope, th) = b.tip_elastic(q);
        let (vs, ws) = (slope[0], slope[1]);
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        // position: ū_T and its derivatives
        let u = Vector3::from(b.tip_local(q));
        let gy = b.foreshortening_gradient(&q[b.iy(0)..b.iy(0) + nb]);
        let gz = b.foreshortening_gradient(&q[b.iz(0)..b.iz(0) + nb]);
        let mut du = Vec::with_capacity(2 * nb);
        let mut ddu = Vec::new();
        for n in 0..nb {
            du.push((b.iy(n), Vector3::new(-gy[n], b.basis.tip[n], 0.0)));
            du.push((b.iz(n), Vector3::new(-gz[n], 0.0, b.basis.tip[n])));
            for m in n..nb {
                let g = b.basis.slope_gram[n * nb + m];
                if g != 0.0 {
                    let h = Vector3::new(-g / l, 0.0, 0.0);
                    ddu.push((b.iy(n), b.iy(m), h));
                    ddu.push((b.iz(n), b.iz(m), h));
                }
            }
        }
        let pos = frame_field(q, &att, d, true, u, &du, &ddu);
        // director derivatives: v′ by a_y, w′ by a_z, θ by a_t
        let sy = |dir: Vector3<f64>| -> Vec<(usize, Vector3<f64>)> {
            (0..nb)
                .map(|n| (b.iy(n), dir * (b.basis.tip_slope[n] / l)))
                .collect()
        };
        let sz = |dir: Vector3<f64>| -> Vec<(usize, Vector3<f64>)> {
            (0..nb)
                .map(|n| (b.iz(n), dir * (b.basis.tip_slope[n] / l)))
                .collect()
        };
        let st = |dir: Vector3<f64>| -> Vec<(usize, Vector3<f64>)> {
            (0..2).map(|m| (b.it(m), dir * b.chi_tip[m])).collect()
        };
        let tangent = {
            let mut dv = sy(y);
            dv.extend(sz(z));
            frame_field(q, &att, d, false, x + vs * y + ws * z, &dv, &[])
        };
        let section = {
            let mut dv = sy(-x);
            dv.extend(st(z));
            frame_field(q, &att, d, false, y + th * z - vs * x, &dv, &[])
        };
        let n1 = frame_field(q, &att, d, false, y - vs * x, &sy(-x), &[]);
        let n2 = frame_field(q, &att, d, false, z - ws * x, &sz(-x), &[]);
        let n3 = {
            let mut dv = st(-y);
            dv.extend(sz(-x));
            frame_field(q, &att, d, false, z - th * y - ws * x, &dv, &[])
        };
        end_kin(pos, tangent, section, [n1, n2, n3])
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
}

/// The root (frame origin) of a spatial modal body, on the body's local coordinates: p = R,
/// tangent A x̄, section A ȳ, normals [A ȳ, A z̄, A z̄]; frame A (orthonormalized), rotation
/// its exact derivative (2E for unit p).
#[derive(Debug, Clone)]
pub struct ModalRootPort3(pub Arc<ModalBody3>);

impl Port<Spatial> for ModalRootPort3 {
    fn kinematics(&self, q: &[f64]) -> EndKin3 {
        let d = self.0.dim();
        let att = Attitude::new(q);
        let f = |v: Vector3<f64>| frame_field(q, &att, d, false, v, &[], &[]);
        let pos = frame_field(q, &att, d, true, Vector3::zeros(), &[], &[]);
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        end_kin(pos, f(x), f(y), [f(y), f(z), f(z)])
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
