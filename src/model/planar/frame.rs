//! Rigid motion in the plane: how points, directions and frame angles are carried by a frame
//! at angle θ_b turning at ω, α (about z, counter-clockwise), and the path of a mount.

use super::Planar;
use crate::math;
use crate::model::dofs::Rigid;
use crate::model::space::{Motion, MotionRates};
use crate::model::vector::{add2, cross_z, sub2};

/// R(θ) v.
fn rot(th: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = math::sin_cos(th);
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

fn two(x: &[f64]) -> [f64; 2] {
    [x[0], x[1]]
}

pub(super) fn carry(kind: Rigid, m: &Motion<Planar>, rel: [&[f64]; 3], out: [&mut [f64]; 3]) {
    let (w, al) = (m.angular_velocity, m.angular_acceleration);
    let [q, v, a] = out;
    match kind {
        Rigid::Angle => {
            q[0] = m.attitude + rel[0][0];
            v[0] = w + rel[1][0];
            a[0] = al + rel[2][0];
        }
        Rigid::Point | Rigid::Direction => {
            let rho = rot(m.attitude, two(rel[0]));
            let rd = rot(m.attitude, two(rel[1]));
            let rdd = rot(m.attitude, two(rel[2]));
            // v = v_b + ω×ρ + ρ̇, a = a_b + α×ρ + ω×(ω×ρ) + 2ω×ρ̇ + ρ̈
            let mut qo = rho;
            let mut vo = add2(cross_z(w, rho), rd);
            let mut ao = add2(
                add2(cross_z(al, rho), [-w * w * rho[0], -w * w * rho[1]]),
                add2(cross_z(2.0 * w, rd), rdd),
            );
            if kind == Rigid::Point {
                qo = add2(m.position, qo);
                vo = add2(m.velocity, vo);
                ao = add2(m.acceleration, ao);
            }
            q[..2].copy_from_slice(&qo);
            v[..2].copy_from_slice(&vo);
            a[..2].copy_from_slice(&ao);
        }
        Rigid::Euler => unreachable!("no Euler parameters in the plane"),
    }
}

pub(super) fn uncarry(kind: Rigid, m: &Motion<Planar>, abs: [&[f64]; 3], out: [&mut [f64]; 3]) {
    let (w, al) = (m.angular_velocity, m.angular_acceleration);
    let [q, v, a] = out;
    match kind {
        Rigid::Angle => {
            q[0] = abs[0][0] - m.attitude;
            v[0] = abs[1][0] - w;
            a[0] = abs[2][0] - al;
        }
        Rigid::Point | Rigid::Direction => {
            let (mut rho, mut vv, mut aa) = (two(abs[0]), two(abs[1]), two(abs[2]));
            if kind == Rigid::Point {
                rho = sub2(rho, m.position);
                vv = sub2(vv, m.velocity);
                aa = sub2(aa, m.acceleration);
            }
            let rd = sub2(vv, cross_z(w, rho));
            let rdd = sub2(
                sub2(aa, cross_z(al, rho)),
                add2([-w * w * rho[0], -w * w * rho[1]], cross_z(2.0 * w, rd)),
            );
            q[..2].copy_from_slice(&rot(-m.attitude, rho));
            v[..2].copy_from_slice(&rot(-m.attitude, rd));
            a[..2].copy_from_slice(&rot(-m.attitude, rdd));
        }
        Rigid::Euler => unreachable!("no Euler parameters in the plane"),
    }
}

/// x + ẋτ + ẍτ²/2 + jτ³/6 + sτ⁴/24 and its first two derivatives.
pub(crate) fn poly(x: f64, v: f64, a: f64, j: f64, s: f64, t: f64) -> (f64, f64, f64) {
    let t2 = t * t;
    (
        x + v * t + a * t2 / 2.0 + j * t2 * t / 6.0 + s * t2 * t2 / 24.0,
        v + a * t + j * t2 / 2.0 + s * t2 * t / 6.0,
        a + j * t + s * t2 / 2.0,
    )
}

pub(super) fn advance(m: &Motion<Planar>, r: &MotionRates<Planar>, tau: f64) -> Motion<Planar> {
    let mut out = *m;
    for k in 0..2 {
        (out.position[k], out.velocity[k], out.acceleration[k]) = poly(
            m.position[k],
            m.velocity[k],
            m.acceleration[k],
            r.jerk[k],
            r.snap[k],
            tau,
        );
    }
    (out.attitude, out.angular_velocity, out.angular_acceleration) = poly(
        m.attitude,
        m.angular_velocity,
        m.angular_acceleration,
        r.angular_jerk,
        r.angular_snap,
        tau,
    );
    out
}

pub(super) fn to_frame(th: f64, v: &[f64; 2]) -> [f64; 2] {
    rot(-th, *v)
}
