//! Rigid motion in space: how points, directions (gradients, directors) and Euler parameters
//! are carried by a frame with unit Euler parameters p_b turning at ω, α (world axes), and the
//! path of a mount. Quaternion products are Hamilton's, scalar first: A(p_b ⊗ p) = A(p_b) A(p),
//! and a frame turning at world ω has ṗ = ½ (0, ω) ⊗ p.

use super::Spatial;
use crate::math;
use crate::model::dofs::Rigid;
use crate::model::planar::poly;
use crate::model::space::{Motion, MotionRates};
use crate::model::vector::{add, cross, dot, scale, sub};

type V = [f64; 3];
type Q = [f64; 4];

fn three(x: &[f64]) -> V {
    [x[0], x[1], x[2]]
}

fn four(x: &[f64]) -> Q {
    [x[0], x[1], x[2], x[3]]
}

/// Hamilton product a ⊗ b.
fn qmul(a: Q, b: Q) -> Q {
    let (a0, av, b0, bv) = (a[0], [a[1], a[2], a[3]], b[0], [b[1], b[2], b[3]]);
    let v = add(add(scale(bv, a0), scale(av, b0)), cross(av, bv));
    [a0 * b0 - dot(av, bv), v[0], v[1], v[2]]
}

fn qconj(a: Q) -> Q {
    [a[0], -a[1], -a[2], -a[3]]
}

fn qadd(a: Q, b: Q, s: f64) -> Q {
    [
        a[0] + s * b[0],
        a[1] + s * b[1],
        a[2] + s * b[2],
        a[3] + s * b[3],
    ]
}

/// (0, v).
fn pure(v: V) -> Q {
    [0.0, v[0], v[1], v[2]]
}

/// A(p) v = (e0² − eᵀe) v + 2(eᵀv) e + 2 e0 (e × v).
pub(crate) fn rotate(p: &Q, v: V) -> V {
    let e = [p[1], p[2], p[3]];
    add(
        add(scale(v, p[0] * p[0] - dot(e, e)), scale(e, 2.0 * dot(e, v))),
        scale(cross(e, v), 2.0 * p[0]),
    )
}

/// A(p)ᵀ v.
pub(crate) fn rotate_back(p: &Q, v: V) -> V {
    rotate(&qconj(*p), v)
}

/// ṗ_b and p̈_b of the frame.
fn frame_rates(m: &Motion<Spatial>) -> (Q, Q) {
    let (w, al, p) = (m.angular_velocity, m.angular_acceleration, m.attitude);
    let pd = qmul(pure(scale(w, 0.5)), p);
    let pdd = qadd(qmul(pure(scale(al, 0.5)), p), p, -0.25 * dot(w, w));
    (pd, pdd)
}

pub(super) fn carry(kind: Rigid, m: &Motion<Spatial>, rel: [&[f64]; 3], out: [&mut [f64]; 3]) {
    let [q, v, a] = out;
    match kind {
        Rigid::Euler => {
            let (pb, (pd, pdd)) = (m.attitude, frame_rates(m));
            let (r0, r1, r2) = (four(rel[0]), four(rel[1]), four(rel[2]));
            let p = qmul(pb, r0);
            let p1 = qadd(qmul(pd, r0), qmul(pb, r1), 1.0);
            let p2 = qadd(qadd(qmul(pdd, r0), qmul(pd, r1), 2.0), qmul(pb, r2), 1.0);
            q[..4].copy_from_slice(&p);
            v[..4].copy_from_slice(&p1);
            a[..4].copy_from_slice(&p2);
        }
        Rigid::Point | Rigid::Direction => {
            let (w, al) = (m.angular_velocity, m.angular_acceleration);
            let rho = rotate(&m.attitude, three(rel[0]));
            let rd = rotate(&m.attitude, three(rel[1]));
            let rdd = rotate(&m.attitude, three(rel[2]));
            let mut qo = rho;
            let mut vo = add(cross(w, rho), rd);
            let mut ao = add(
                add(cross(al, rho), cross(w, cross(w, rho))),
                add(cross(scale(w, 2.0), rd), rdd),
            );
            if kind == Rigid::Point {
                qo = add(m.position, qo);
                vo = add(m.velocity, vo);
                ao = add(m.acceleration, ao);
            }
            q[..3].copy_from_slice(&qo);
            v[..3].copy_from_slice(&vo);
            a[..3].copy_from_slice(&ao);
        }
        Rigid::Angle => unreachable!("no plane angles in space"),
    }
}

pub(super) fn uncarry(kind: Rigid, m: &Motion<Spatial>, abs: [&[f64]; 3], out: [&mut [f64]; 3]) {
    let [q, v, a] = out;
    match kind {
        Rigid::Euler => {
            let (pb, (pd, pdd)) = (m.attitude, frame_rates(m));
            let pc = qconj(pb);
            let (p, p1, p2) = (four(abs[0]), four(abs[1]), four(abs[2]));
            let r0 = qmul(pc, p);
            let r1 = qmul(pc, qadd(p1, qmul(pd, r0), -1.0));
            let r2 = qmul(pc, qadd(qadd(p2, qmul(pdd, r0), -1.0), qmul(pd, r1), -2.0));
            q[..4].copy_from_slice(&r0);
            v[..4].copy_from_slice(&r1);
            a[..4].copy_from_slice(&r2);
        }
        Rigid::Point | Rigid::Direction => {
            let (w, al) = (m.angular_velocity, m.angular_acceleration);
            let (mut rho, mut vv, mut aa) = (three(abs[0]), three(abs[1]), three(abs[2]));
            if kind == Rigid::Point {
                rho = sub(rho, m.position);
                vv = sub(vv, m.velocity);
                aa = sub(aa, m.acceleration);
            }
            let rd = sub(vv, cross(w, rho));
            let rdd = sub(
                sub(aa, cross(al, rho)),
                add(cross(w, cross(w, rho)), cross(scale(w, 2.0), rd)),
            );
            q[..3].copy_from_slice(&rotate_back(&m.attitude, rho));
            v[..3].copy_from_slice(&rotate_back(&m.attitude, rd));
            a[..3].copy_from_slice(&rotate_back(&m.attitude, rdd));
        }
        Rigid::Angle => unreachable!("no plane angles in space"),
    }
}

/// exp of the rotation vector φ as unit Euler parameters.
fn exp(phi: V) -> Q {
    let th = dot(phi, phi).sqrt();
    let (s, c) = math::sin_cos(0.5 * th);
    // sin(θ/2)/θ, by its series where θ is tiny
    let k = if th > 1e-4 {
        s / th
    } else {
        0.5 - th * th / 48.0
    };
    [c, k * phi[0], k * phi[1], k * phi[2]]
}

pub(super) fn advance(m: &Motion<Spatial>, r: &MotionRates<Spatial>, tau: f64) -> Motion<Spatial> {
    let mut out = *m;
    for k in 0..3 {
        (out.position[k], out.velocity[k], out.acceleration[k]) = poly(
            m.position[k],
            m.velocity[k],
            m.acceleration[k],
            r.jerk[k],
            r.snap[k],
            tau,
        );
    }
    // Magnus: ∫ω dt plus the commutator term τ³/12 α × ω
    let mut phi = [0.0; 3];
    for k in 0..3 {
        (phi[k], out.angular_velocity[k], out.angular_acceleration[k]) = poly(
            0.0,
            m.angular_velocity[k],
            m.angular_acceleration[k],
            r.angular_jerk[k],
            r.angular_snap[k],
            tau,
        );
    }
    let comm = scale(
        cross(m.angular_acceleration, m.angular_velocity),
        tau * tau * tau / 12.0,
    );
    let rot = exp(add(phi, comm));
    out.attitude = normalize(qmul(rot, m.attitude)).unwrap_or(m.attitude);
    out
}

/// `p` turned further by the world rotation vector `phi` [rad]: exp(φ) ⊗ p, normalized.
pub(super) fn rotated(p: &Q, phi: V) -> Q {
    normalize(qmul(exp(phi), *p)).unwrap_or(*p)
}

pub(crate) fn normalize(p: Q) -> Option<Q> {
    let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]).sqrt();
    (n.is_finite() && n > 1e-12).then(|| p.map(|x| x / n))
}

/// Angle [rad] of the rotation from a to b.
pub(super) fn angle_between(a: &Q, b: &Q) -> f64 {
    let d = qmul(qconj(*a), *b);
    let s = dot([d[1], d[2], d[3]], [d[1], d[2], d[3]]).sqrt();
    2.0 * math::atan2(s, d[0].abs())
}
