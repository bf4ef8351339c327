//! The planar rigid joint between the tip of one segment and the root of the next: 3 rows
//! Φ = [p_up − p_down ; orientation] [m, m, -] with orientation
//! n(ψ)·s = −sin ψ s_x + cos ψ s_y (angle against slope: the DOT1 condition in the plane) or
//! ψ_down − ψ_up (angle against angle). Two ANCF segments share their node instead (no rows).

use super::ends::{EndKin, Orientation};
use super::Planar;
use crate::math;
use crate::model::component::{Constraint, ConstraintOut, Port};
use nalgebra::Vector2;
use std::sync::{Mutex, PoisonError};

/// A rigid joint over the local coordinates [up ; down] of its two ends.
#[derive(Debug)]
pub struct RigidJoint {
    /// Upstream end (tip of segment i).
    pub up: Box<dyn Port<Planar>>,
    /// Downstream end (root of segment i + 1).
    pub down: Box<dyn Port<Planar>>,
    /// Number of local coordinates of the upstream end.
    pub up_len: usize,
    /// The ends' first-order kinematics of the residual path, refilled in place
    /// ([`Port::kinematics_first_into`]): no allocation per evaluation.
    scratch: Mutex<[EndKin; 2]>,
}

impl RigidJoint {
    /// The joint between `up` (its `up_len` local coordinates first) and `down`.
    pub fn new(up: Box<dyn Port<Planar>>, down: Box<dyn Port<Planar>>, up_len: usize) -> Self {
        Self {
            up,
            down,
            up_len,
            scratch: Mutex::default(),
        }
    }
}

impl Constraint for RigidJoint {
    fn rows(&self) -> usize {
        3
    }

    fn eval(&self, q: &[f64], lambda: Option<&[f64]>, out: &mut ConstraintOut) {
        // the second derivatives only for the λ-Hessian
        let (qu, qd) = q.split_at(self.up_len);
        if let Some(l) = lambda {
            let (up, down) = (self.up.kinematics(qu), self.down.kinematics(qd));
            joint_eval(&up, &down, Some([l[0], l[1], l[2]]), out);
        } else {
            let mut kin = self.scratch.lock().unwrap_or_else(PoisonError::into_inner);
            let [up, down] = &mut *kin;
            self.up.kinematics_first_into(qu, up);
            self.down.kinematics_first_into(qd, down);
            joint_eval(up, down, None, out);
        }
    }
}

/// Φ, Φ_q and, with λ, the λ-weighted Hessian of the joint between `up` and `down`.
fn joint_eval(up: &EndKin, down: &EndKin, lambda: Option<[f64; 3]>, out: &mut ConstraintOut) {
    let ku = up.dp.len();
    let k = ku + down.dp.len();
    let d = up.p - down.p;
    let (jp, jo) = out.jac.split_at_mut(2 * k);
    let (jx, jy) = jp.split_at_mut(k);
    for (i, v) in up.dp.iter().enumerate() {
        jx[i] = v[0];
        jy[i] = v[1];
    }
    for (i, v) in down.dp.iter().enumerate() {
        jx[ku + i] = -v[0];
        jy[ku + i] = -v[1];
    }
    let hess = &mut out.hess;
    if let Some(l) = lambda {
        let mu = Vector2::new(l[0], l[1]);
        up.add_point_hessian(mu, |i, j, v| hess.push((i, j, v)));
        down.add_point_hessian(-mu, |i, j, v| hess.push((ku + i, ku + j, v)));
    }
    let lo = lambda.map(|l| l[2]);
    let phi_o = match (&up.orient, &down.orient) {
        (Orientation::Angle(pu, dpu), Orientation::Angle(pd, dpd)) => {
            for (i, v) in dpu.iter().enumerate() {
                jo[i] = -v;
            }
            for (i, v) in dpd.iter().enumerate() {
                jo[ku + i] = *v;
            }
            if let Some(l) = lo {
                down.add_angle_hessian(l, |i, j, v| hess.push((ku + i, ku + j, v)));
                up.add_angle_hessian(-l, |i, j, v| hess.push((i, j, v)));
            }
            pd - pu
        }
        (Orientation::Angle(psi, dpsi), Orientation::Slope(s, ds)) => {
            let angle = AngleAt {
                psi: *psi,
                dpsi,
                at: 0,
            };
            if let Some(l) = lo {
                let w = l * angle.dphi_dpsi(s);
                up.add_angle_hessian(w, |i, j, v| hess.push((i, j, v)));
            }
            angle_slope(&angle, (s, ds, ku), jo, lo, hess)
        }
        (Orientation::Slope(s, ds), Orientation::Angle(psi, dpsi)) => {
            let angle = AngleAt {
                psi: *psi,
                dpsi,
                at: ku,
            };
            if let Some(l) = lo {
                let w = l * angle.dphi_dpsi(s);
                down.add_angle_hessian(w, |i, j, v| hess.push((ku + i, ku + j, v)));
            }
            angle_slope(&angle, (s, ds, 0), jo, lo, hess)
        }
        (Orientation::Slope(..), Orientation::Slope(..)) => {
            unreachable!("consecutive ANCF segments share a node and need no joint")
        }
    };
    out.phi.copy_from_slice(&[d[0], d[1], phi_o]);
}

/// An angle ψ with ∂ψ/∂q over local coordinates starting at `at`.
struct AngleAt<'a> {
    psi: f64,
    dpsi: &'a [f64],
    at: usize,
}

impl AngleAt<'_> {
    /// ∂Φ/∂ψ = −t(ψ)·s of Φ = n(ψ)·s (the weight of ∂²ψ/∂q∂q in ∂²Φ/∂q∂q).
    fn dphi_dpsi(&self, s: &Vector2<f64>) -> f64 {
        let (sn, cs) = math::sin_cos(self.psi);
        -(cs * s[0] + sn * s[1])
    }
}

/// Φ = n(ψ)·s with the slope s, ∂s/∂q over local coordinates at the given offset; adds
/// ∂Φ/∂q to `jac` and, with λ, λ ∂²Φ to `hess`.
fn angle_slope(
    a: &AngleAt<'_>,
    (s, ds, os): (&Vector2<f64>, &[Vector2<f64>], usize),
    jac: &mut [f64],
    lambda: Option<f64>,
    hess: &mut Vec<(usize, usize, f64)>,
) -> f64 {
    let (dpsi, oa) = (a.dpsi, a.at);
    let (sn, cs) = math::sin_cos(a.psi);
    let n = Vector2::new(-sn, cs);
    let t = Vector2::new(cs, sn);
    let phi = n.dot(s);
    let dphi_dpsi = -t.dot(s);
    for (i, v) in dpsi.iter().enumerate() {
        jac[oa + i] += dphi_dpsi * v;
    }
    for (i, v) in ds.iter().enumerate() {
        jac[os + i] += n.dot(v);
    }
    if let Some(l) = lambda {
        // ∂²Φ/∂ψ² = −n·s ; ∂²Φ/∂ψ∂s = −t
        for (i, vi) in dpsi.iter().enumerate() {
            if *vi == 0.0 {
                continue;
            }
            for (j, vj) in dpsi.iter().enumerate() {
                if *vj != 0.0 {
                    hess.push((oa + i, oa + j, -l * phi * vi * vj));
                }
            }
            for (j, dsj) in ds.iter().enumerate() {
                let h = -l * vi * t.dot(dsj);
                if h != 0.0 {
                    hess.push((oa + i, os + j, h));
                    hess.push((os + j, oa + i, h));
                }
            }
        }
    }
    phi
}
