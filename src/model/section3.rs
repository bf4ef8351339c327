//! Rigid bodies riding on a spatial section (an attached mass with an offset or a rotary
//! inertia, `[[masses]]`, docs/references.md §10), for every spatial element that has a section
//! frame: the director and angle ANCF elements and the spatial modal body.
//!
//! A body sits on the section at a point of an element: the element gives its centreline point
//! r(q) and its section frame R(q) = [t, d2, d3] (columns, world axes) as functions of its local
//! coordinates q ([`SectionPose`]). The body's centre is p = r + R o (o the offset in section
//! axes [m]); it turns with the section, body angular velocity ω = vee(RᵀṘ) (section axes);
//! kinetic energy ½m|ṗ|² + ½ωᵀIω (I = diag(I_xx, I_yy, I_zz) about its centre, section
//! axes), weight m g. Its generalized inertia and weight forces are Kane's (equal to
//! Lagrange's for any parametrization of R):
//!
//! Q = (∂p/∂q)ᵀ m(p̈ − g) + (∂ω/∂q̇)ᵀ(I ω̇ + ω × I ω),
//!
//! with p̈, ω̇ from one evaluation of the pose along the time Taylor series q + q̇t + ½q̈t²
//! (second-order dual numbers: ω̇ = vee(skew(RᵀR̈))) and ∂p/∂q, ∂ω/∂q̇ = vee(Rᵀ∂R/∂q_k) from one
//! first-order dual evaluation per coordinate. Generic over the scalar, so the Newton block is
//! the exact forward-mode derivative of the same code ([`SectionBody3::add_block`]).

use super::vector::{cross, dot, Real, V3};
use num_dual::{Dual, Dual2, Dual64};

/// A rigid body on a spatial section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionBody3 {
    /// Where it sits: ξ ∈ [0, 1] along an ANCF element; x/L along a modal body.
    pub xi: f64,
    /// Mass m [kg].
    pub mass: f64,
    /// Principal rotary inertia about its centre, section axes [I_xx, I_yy, I_zz] [kg m²].
    pub inertia: [f64; 3],
    /// Its centre from the centreline point, section axes [m].
    pub offset: [f64; 3],
}

/// An element's centreline point and section frame at a body, as functions of the element's
/// local coordinates (`q(j)`: coordinate j), generic over the scalar.
pub trait SectionPose {
    /// (r [m], [t, d2, d3]) in world axes; the frame orthonormal.
    fn pose<S: Real>(&self, q: impl Fn(usize) -> S) -> (V3<S>, [V3<S>; 3]);
}

/// The section-axes components of the rotation rate of the frame `f` moving at `d` (= ḟ or
/// ∂f/∂q_k): ½(f₂·d₁ − f₁·d₂, f₀·d₂ − f₂·d₀, f₁·d₀ − f₀·d₁) (the skew part of fᵀd).
#[inline]
fn spin<S: Real>(f: &[V3<S>; 3], d: &[V3<S>; 3]) -> V3<S> {
    [
        (dot(f[2], d[1]) - dot(f[1], d[2])) * 0.5,
        (dot(f[0], d[2]) - dot(f[2], d[0])) * 0.5,
        (dot(f[1], d[0]) - dot(f[0], d[1])) * 0.5,
    ]
}

impl SectionBody3 {
    /// Whether the body differs from a point (an offset or a rotary inertia).
    pub fn is_body(&self) -> bool {
        self.inertia.iter().chain(&self.offset).any(|x| *x != 0.0)
    }

    /// p = r + R o.
    #[inline]
    fn centre<S: Real>(&self, r: &V3<S>, f: &[V3<S>; 3]) -> V3<S> {
        let o = self.offset;
        std::array::from_fn(|i| r[i] + f[0][i] * o[0] + f[1][i] * o[1] + f[2][i] * o[2])
    }

    /// The body's centre p, m(p̈ − g), the section frame R and Iω̇ + ω × Iω (section axes) at
    /// (q, q̇, q̈) under gravity `g`: one evaluation of the pose along the time Taylor series.
    #[allow(clippy::type_complexity)]
    fn dynamics<T: Real, P: SectionPose>(
        &self,
        pose: &P,
        (q, v, a): (&[T], &[T], &[T]),
        g: [f64; 3],
    ) -> (V3<T>, V3<T>, [V3<T>; 3], V3<T>) {
        let (r, f) = pose.pose(|j| Dual2::new(q[j], v[j], a[j]));
        let p = self.centre(&r, &f);
        let acc: V3<T> = std::array::from_fn(|i| (p[i].v2 - g[i]) * self.mass);
        let part = |k: u8| f.map(|c| c.map(|x| [x.re, x.v1, x.v2][k as usize]));
        let fr = part(0);
        let w = spin(&fr, &part(1));
        let wd = spin(&fr, &part(2));
        let i = self.inertia;
        let iw: V3<T> = std::array::from_fn(|k| w[k] * i[k]);
        let gyro = cross(w, iw);
        let h: V3<T> = std::array::from_fn(|k| wd[k] * i[k] + gyro[k]);
        (p.map(|x| x.re), acc, fr, h)
    }

    /// Adds the body's inertia and weight forces Q (module doc) over the `n` coordinates of the
    /// pose at (q, q̇, q̈) under gravity `g` [m/s²] to `out`.
    pub fn add_forces<T: Real, P: SectionPose>(
        &self,
        pose: &P,
        n: usize,
        (q, v, a): (&[T], &[T], &[T]),
        g: [f64; 3],
        out: &mut [T],
    ) {
        let (_, acc, _, h) = self.dynamics(pose, (q, v, a), g);
        let i = self.inertia;
        let rotary = i.iter().any(|x| *x != 0.0) || self.offset.iter().any(|x| *x != 0.0);
        for (k, o) in out.iter_mut().enumerate().take(n) {
            let (rk, fk) = pose.pose(|j| {
                if j == k {
                    Dual::new(q[j], T::one())
                } else {
                    Dual::from_re(q[j])
                }
            });
            let pk = self.centre(&rk, &fk);
            let mut s = dot(pk.map(|x| x.eps), acc);
            if rotary {
                let fre = fk.map(|c| c.map(|x| x.re));
                let feps = fk.map(|c| c.map(|x| x.eps));
                s += dot(spin(&fre, &feps), h);
            }
            *o += s;
        }
    }

    /// The body's d'Alembert force −m(p̈ − g) [N] and its moment about `about` [N m], world
    /// axes, at (q, q̇, q̈): −(p − about) × m(p̈ − g) − R(Iω̇ + ω × Iω) — the virtual work of Q
    /// ([`SectionBody3::add_forces`]) under a rigid virtual motion (δp = δu + δθ × (p − about),
    /// the section turning by δθ), negated: what a station inside an element takes from it.
    pub fn load<P: SectionPose>(
        &self,
        pose: &P,
        (q, v, a): (&[f64], &[f64], &[f64]),
        g: [f64; 3],
        about: [f64; 3],
    ) -> ([f64; 3], [f64; 3]) {
        let (p, acc, fr, h) = self.dynamics(pose, (q, v, a), g);
        let arm: V3<f64> = std::array::from_fn(|c| p[c] - about[c]);
        let m = cross(arm, acc);
        (
            acc.map(|x| -x),
            std::array::from_fn(|c| -m[c] - (fr[0][c] * h[0] + fr[1][c] * h[1] + fr[2][c] * h[2])),
        )
    }

    /// Adds `c_a ∂Q/∂q̈ + c_v ∂Q/∂q̇ + c_x ∂Q/∂q` of [`SectionBody3::add_forces`] (D coordinates)
    /// to `blk` (row-major D × D): forward-mode AD, column j along (c_x, c_v, c_a)·e_j.
    pub fn add_block<P: SectionPose, const D: usize>(
        &self,
        pose: &P,
        (q, v, a): (&[f64; D], &[f64; D], &[f64; D]),
        g: [f64; 3],
        (ca, cv, cx): (f64, f64, f64),
        blk: &mut [[f64; D]; D],
    ) {
        let (mut qd, mut vd, mut ad) = (
            q.map(Dual64::from_re),
            v.map(Dual64::from_re),
            a.map(Dual64::from_re),
        );
        for j in 0..D {
            (qd[j].eps, vd[j].eps, ad[j].eps) = (cx, cv, ca);
            let mut out = [Dual64::from_re(0.0); D];
            self.add_forces(pose, D, (&qd, &vd, &ad), g, &mut out);
            for (row, o) in blk.iter_mut().zip(&out) {
                row[j] += o.eps;
            }
            (qd[j].eps, vd[j].eps, ad[j].eps) = (0.0, 0.0, 0.0);
        }
    }

    /// (kinetic energy ½m|ṗ|² + ½ωᵀIω, gravity potential −m gᵀp) [J] at (q, q̇).
    pub fn energies<P: SectionPose>(
        &self,
        pose: &P,
        q: &[f64],
        v: &[f64],
        g: [f64; 3],
    ) -> (f64, f64) {
        let (r, f) = pose.pose(|j| Dual64::new(q[j], v[j]));
        let p = self.centre(&r, &f);
        let (fr, fv) = (f.map(|c| c.map(|x| x.re)), f.map(|c| c.map(|x| x.eps)));
        let w = spin(&fr, &fv);
        let vel = p.map(|x| x.eps);
        let kin = 0.5 * self.mass * dot(vel, vel)
            + 0.5 * (0..3).map(|k| self.inertia[k] * w[k] * w[k]).sum::<f64>();
        (kin, -self.mass * dot(g, p.map(|x| x.re)))
    }
}

/// Adds the forces of the bodies `bodies` (each with its pose) at the element's (q, q̇, q̈) of
/// `D` coordinates under gravity `g` [m/s²] to `res` and, with the Newton coefficients
/// `matrix` = (c_a, c_v, c_x), their block to `blk` ([`SectionBody3::add_forces`],
/// [`SectionBody3::add_block`]).
pub fn add_bodies<P: SectionPose, const D: usize>(
    bodies: &[(SectionBody3, P)],
    (q, v, a): (&[f64; D], &[f64; D], &[f64; D]),
    g: [f64; 3],
    matrix: Option<(f64, f64, f64)>,
    res: &mut [f64],
    blk: &mut [[f64; D]; D],
) {
    for (b, pose) in bodies {
        b.add_forces(pose, D, (&q[..], &v[..], &a[..]), g, res);
        if let Some(c) = matrix {
            b.add_block(pose, (q, v, a), g, c, blk);
        }
    }
}

/// Adds the kinetic and gravity energies of the bodies `bodies` at (q, q̇) under gravity `g`
/// [m/s²] to `out` ([`SectionBody3::energies`]).
pub fn add_body_energies<P: SectionPose>(
    bodies: &[(SectionBody3, P)],
    (q, v): (&[f64], &[f64]),
    g: [f64; 3],
    out: &mut super::component::Energies,
) {
    for (b, pose) in bodies {
        let (t, u) = b.energies(pose, q, v, g);
        out.kinetic += t;
        out.potential += u;
    }
}

/// The frame [t, d2, d3] of the tangent `a` and a section director `d` (Gram–Schmidt, as
/// [`crate::model::sample::director_frame`]), generic over the scalar.
#[inline]
pub fn gram_schmidt<S: Real>(a: V3<S>, d: V3<S>) -> [V3<S>; 3] {
    let t = unit(a);
    let s = dot(t, d);
    let d2 = unit(std::array::from_fn(|i| d[i] - t[i] * s));
    [t, d2, cross(t, d2)]
}

/// The smallest rotation of (e_y, e_z) onto the unit tangent of `a` ([`crate::model::sample`]'s
/// minimal frame without its t = −e_x branch), generic over the scalar.
#[inline]
pub fn minimal_frame<S: Real>(a: V3<S>) -> [V3<S>; 3] {
    let t = unit(a);
    let c = t[0];
    let w = [S::zero(), -t[2], t[1]];
    let f = (c + 1.0).recip();
    let col = |e: V3<S>| -> V3<S> {
        let we = cross(w, e);
        let d = dot(w, e) * f;
        std::array::from_fn(|i| e[i] * c + we[i] + w[i] * d)
    };
    let (z, o) = (S::zero(), S::one());
    [t, col([z, o, z]), col([z, z, o])]
}

#[inline]
fn unit<S: Real>(a: V3<S>) -> V3<S> {
    let inv = dot(a, a).sqrt().recip();
    a.map(|x| x * inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A free rigid body: q = (r, rotation vector φ), R = exp([φ]×) (Rodrigues).
    struct Free;
    impl SectionPose for Free {
        fn pose<S: Real>(&self, q: impl Fn(usize) -> S) -> (V3<S>, [V3<S>; 3]) {
            let r = [q(0), q(1), q(2)];
            let phi = [q(3), q(4), q(5)];
            let th2 = dot(phi, phi) + 1e-300;
            let th = th2.sqrt();
            let (s, c) = (th.sin() / th, (S::one() - th.cos()) / th2);
            let col = |e: V3<S>| -> V3<S> {
                let pe = cross(phi, e);
                let ppe = cross(phi, pe);
                std::array::from_fn(|i| e[i] + pe[i] * s + ppe[i] * c)
            };
            let (z, o) = (S::zero(), S::one());
            (r, [col([o, z, z]), col([z, o, z]), col([z, z, o])])
        }
    }

    #[test]
    fn forces_are_lagrange_of_the_kinetic_energy() {
        // Q(q, q̇, q̈) against d/dt ∂T/∂q̇ − ∂T/∂q − ∂(−m gᵀp)/∂q by central differences of the
        // energies (an independent path: energies only)
        let b = SectionBody3 {
            xi: 0.0,
            mass: 0.7,
            inertia: [0.02, 0.05, 0.03],
            offset: [0.1, -0.2, 0.3],
        };
        let q = [0.1, -0.2, 0.3, 0.4, -0.3, 0.2];
        let v = [0.5, 0.1, -0.4, 1.1, -0.7, 0.9];
        let a = [0.3, -0.6, 0.2, -0.5, 0.8, 0.4];
        let g = [0.0, -9.81, 1.0];
        let mut f = [0.0; 6];
        b.add_forces(&Free, 6, (&q, &v, &a), g, &mut f);
        let lag = |q: &[f64; 6], v: &[f64; 6]| {
            let (t, u) = b.energies(&Free, q, v, g);
            t - u
        };
        let h = 1e-5;
        let dl_dv = |q: &[f64; 6], v: &[f64; 6], k: usize| {
            let (mut vp, mut vm) = (*v, *v);
            vp[k] += h;
            vm[k] -= h;
            (lag(q, &vp) - lag(q, &vm)) / (2.0 * h)
        };
        for k in 0..6 {
            // d/dt ∂L/∂q̇ along q + q̇t + ½q̈t², q̇ + q̈t
            let at = |t: f64| {
                let qt: [f64; 6] = std::array::from_fn(|i| q[i] + v[i] * t + 0.5 * a[i] * t * t);
                let vt: [f64; 6] = std::array::from_fn(|i| v[i] + a[i] * t);
                dl_dv(&qt, &vt, k)
            };
            let ddt = (at(h) - at(-h)) / (2.0 * h);
            let (mut qp, mut qm) = (q, q);
            qp[k] += h;
            qm[k] -= h;
            let dl_dq = (lag(&qp, &v) - lag(&qm, &v)) / (2.0 * h);
            let want = ddt - dl_dq;
            assert!(
                (f[k] - want).abs() < 1e-5 * (1.0 + want.abs()),
                "{k}: {} vs {want}",
                f[k]
            );
        }
    }

    #[test]
    fn newton_block_matches_central_differences() {
        let b = SectionBody3 {
            xi: 0.0,
            mass: 0.7,
            inertia: [0.02, 0.05, 0.03],
            offset: [0.1, -0.2, 0.3],
        };
        let x = [
            [0.1, -0.2, 0.3, 0.4, -0.3, 0.2],
            [0.5, 0.1, -0.4, 1.1, -0.7, 0.9],
            [0.3, -0.6, 0.2, -0.5, 0.8, 0.4],
        ];
        let g = [0.0, -9.81, 1.0];
        let c = (2.0, 0.7, 1.3);
        let mut blk = [[0.0; 6]; 6];
        b.add_block(&Free, (&x[0], &x[1], &x[2]), g, c, &mut blk);
        let h = 1e-6;
        for j in 0..6 {
            let res = |s: f64| {
                let mut y = x;
                y[0][j] += s * c.2;
                y[1][j] += s * c.1;
                y[2][j] += s * c.0;
                let mut f = [0.0; 6];
                b.add_forces(&Free, 6, (&y[0], &y[1], &y[2]), g, &mut f);
                f
            };
            let (p, m) = (res(h), res(-h));
            for i in 0..6 {
                let want = (p[i] - m[i]) / (2.0 * h);
                assert!(
                    (blk[i][j] - want).abs() < 1e-6 * (1.0 + want.abs()),
                    "{i},{j}"
                );
            }
        }
    }
}
