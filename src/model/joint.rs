//! Segment ends and the planar rigid joint between consecutive segments.
//!
//! An end of a segment has a position p(q) and an orientation: either an angle ψ(q) (modal
//! side: frame angle, plus the elastic tip slope at a modal tip) or a slope vector s(q) (ANCF
//! node: s = r′, its length is the axial stretch). The rigid joint is
//! Φ = [p_up − p_down ; orientation] with orientation
//! n(ψ)·s = −sin ψ s_x + cos ψ s_y (angle against slope: the DOT1 condition in the plane) or
//! ψ_down − ψ_up (angle against angle). Two ANCF segments share their node instead (no rows).

use super::modal::ModalBody;
use nalgebra::Vector2;

/// Marker of a fixed (eliminated) coordinate in index lists.
pub const FIXED: u32 = u32::MAX;

/// Local values of the global vector `x` at the indices `idx`. An eliminated coordinate takes
/// its value from `fixed` (positions), or 0 when `fixed` is `None` (rates: it does not move).
pub fn gather(idx: &[u32], fixed: Option<&[f64]>, x: &[f64]) -> Vec<f64> {
    idx.iter()
        .enumerate()
        .map(|(k, &i)| match (i, fixed) {
            (FIXED, Some(f)) => f[k],
            (FIXED, None) => 0.0,
            _ => x[i as usize],
        })
        .collect()
}

/// Where an end lives.
#[derive(Debug, Clone, PartialEq)]
pub enum End {
    /// ANCF node: indices of [rx, ry, sx, sy] and the values of the fixed ones.
    Node {
        /// Global free indices or [`FIXED`].
        idx: [u32; 4],
        /// Values used where `idx` is [`FIXED`].
        fixed: [f64; 4],
    },
    /// Tip (x = L) of modal body `body`.
    ModalTip {
        /// Body index in the model.
        body: usize,
    },
    /// Root (frame origin) of modal body `body`.
    ModalRoot {
        /// Body index in the model.
        body: usize,
    },
}

/// Orientation of an end.
#[derive(Debug, Clone)]
pub enum Orientation {
    /// Angle ψ [rad], with ∂ψ/∂q_local.
    Angle(f64, Vec<f64>),
    /// Slope vector s [-], with ∂s/∂q_local (one 2-vector per local coordinate).
    Slope(Vector2<f64>, Vec<Vector2<f64>>),
}

/// Kinematics of an end at one state, over its local coordinates.
#[derive(Debug, Clone)]
pub struct EndKin {
    /// Global indices of the local coordinates ([`FIXED`] where eliminated).
    pub idx: Vec<u32>,
    /// Position [m].
    pub p: Vector2<f64>,
    /// ∂p/∂q_local.
    pub dp: Vec<Vector2<f64>>,
    /// Orientation.
    pub orient: Orientation,
    /// Curvature of p (modal tip only).
    pub curv: Option<TipCurvature>,
}

/// Second derivatives of a modal tip position p = R + A(θ)[L − ½aᵀGa/L; φ(1)ᵀa]:
/// ∂²p/∂θ² = −A u, ∂²p/∂θ∂a_k = J ∂p/∂a_k, ∂²p/∂a_j∂a_k = −A e_x G_jk / L.
#[derive(Debug, Clone)]
pub struct TipCurvature {
    /// Local index of θ (the modal amplitudes follow it).
    pub theta: usize,
    /// A u_tip.
    pub au: Vector2<f64>,
    /// J ∂p/∂a_k.
    pub j_dp_da: Vec<Vector2<f64>>,
    /// A e_x / L.
    pub ax_over_l: Vector2<f64>,
    /// G (row-major n × n).
    pub gram: Vec<f64>,
}

impl EndKin {
    /// Adds μ·∂²p/∂q∂q (local × local) through `add(i, j, value)`.
    pub fn add_point_hessian(&self, mu: Vector2<f64>, mut add: impl FnMut(usize, usize, f64)) {
        if let Some(c) = &self.curv {
            let it = c.theta;
            add(it, it, -mu.dot(&c.au));
            let n = c.j_dp_da.len();
            for (k, v) in c.j_dp_da.iter().enumerate() {
                let h = mu.dot(v);
                add(it, it + 1 + k, h);
                add(it + 1 + k, it, h);
            }
            let m = -mu.dot(&c.ax_over_l);
            if m != 0.0 {
                for j in 0..n {
                    for k in 0..n {
                        let g = c.gram[j * n + k];
                        if g != 0.0 {
                            add(it + 1 + j, it + 1 + k, m * g);
                        }
                    }
                }
            }
        }
    }

    /// Angle of the end [rad]: ψ, or atan2 of the slope.
    pub fn angle(&self) -> f64 {
        match &self.orient {
            Orientation::Angle(psi, _) => *psi,
            Orientation::Slope(s, _) => s[1].atan2(s[0]),
        }
    }
}

/// Evaluates an end.
pub fn end_kin(end: &End, q: &[f64], bodies: &[(ModalBody, Vec<u32>, Vec<f64>)]) -> EndKin {
    match end {
        End::Node { idx, fixed } => {
            let val = |i: usize| {
                if idx[i] == FIXED {
                    fixed[i]
                } else {
                    q[idx[i] as usize]
                }
            };
            let z = Vector2::zeros();
            EndKin {
                idx: idx.to_vec(),
                p: Vector2::new(val(0), val(1)),
                dp: vec![Vector2::x(), Vector2::y(), z, z],
                orient: Orientation::Slope(
                    Vector2::new(val(2), val(3)),
                    vec![z, z, Vector2::x(), Vector2::y()],
                ),
                curv: None,
            }
        }
        End::ModalTip { body } | End::ModalRoot { body } => {
            let (b, idx, fixed) = &bodies[*body];
            let ql = gather(idx, Some(fixed), q);
            let n = b.modes();
            let r = Vector2::new(ql[0], ql[1]);
            let z = Vector2::zeros();
            let mut dpsi = vec![0.0; 3 + n];
            dpsi[2] = 1.0;
            if matches!(end, End::ModalRoot { .. }) {
                let mut dp = vec![z; 3 + n];
                dp[0] = Vector2::x();
                dp[1] = Vector2::y();
                return EndKin {
                    idx: idx.clone(),
                    p: r,
                    dp,
                    orient: Orientation::Angle(ql[2], dpsi),
                    curv: None,
                };
            }
            let a = super::modal::rot(ql[2]);
            let (u, gk) = b.tip_local_and_gradient(&ql);
            let au = a * u;
            let mut dp = vec![Vector2::x(), Vector2::y(), Vector2::new(-au[1], au[0])];
            let mut ajk = Vec::with_capacity(n);
            for k in 0..n {
                let c = a * Vector2::new(-gk[k], b.basis.tip[k]);
                dp.push(c);
                ajk.push(Vector2::new(-c[1], c[0]));
                dpsi[3 + k] = b.basis.tip_slope[k] / b.length;
            }
            EndKin {
                idx: idx.clone(),
                p: r + au,
                dp,
                orient: Orientation::Angle(ql[2] + b.tip_slope(&ql), dpsi),
                curv: Some(TipCurvature {
                    theta: 2,
                    au,
                    j_dp_da: ajk,
                    ax_over_l: a.column(0).into_owned() / b.length,
                    gram: b.basis.slope_gram.clone(),
                }),
            }
        }
    }
}

/// A rigid joint between the tip of one segment and the root of the next.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Upstream end (tip of segment i).
    pub up: End,
    /// Downstream end (root of segment i + 1).
    pub down: End,
    /// First constraint row (0-based among the constraint rows).
    pub row: usize,
}

/// Constraint values, Jacobian and λ-weighted Hessian of one joint over the concatenated local
/// coordinates [up ; down].
#[derive(Debug, Clone)]
pub struct JointEval {
    /// Global indices of the concatenated local coordinates.
    pub idx: Vec<u32>,
    /// Φ (3 rows: x, y, orientation) [m, m, -].
    pub phi: [f64; 3],
    /// ∂Φ_i/∂q_local, row-major 3 × k.
    pub jac: [Vec<f64>; 3],
    /// Σ λ_i ∂²Φ_i/∂q∂q as (local i, local j, value) triplets.
    pub hess: Vec<(usize, usize, f64)>,
}

/// Evaluates a joint; the Hessian is contracted with `lambda` if given.
pub fn joint_eval(up: &EndKin, down: &EndKin, lambda: Option<[f64; 3]>) -> JointEval {
    let ku = up.idx.len();
    let k = ku + down.idx.len();
    let mut idx = up.idx.clone();
    idx.extend_from_slice(&down.idx);
    let d = up.p - down.p;
    let mut jac = [vec![0.0; k], vec![0.0; k], vec![0.0; k]];
    for (i, v) in up.dp.iter().enumerate() {
        jac[0][i] = v[0];
        jac[1][i] = v[1];
    }
    for (i, v) in down.dp.iter().enumerate() {
        jac[0][ku + i] = -v[0];
        jac[1][ku + i] = -v[1];
    }
    let mut hess = Vec::new();
    if let Some(l) = lambda {
        let mu = Vector2::new(l[0], l[1]);
        up.add_point_hessian(mu, |i, j, v| hess.push((i, j, v)));
        down.add_point_hessian(-mu, |i, j, v| hess.push((ku + i, ku + j, v)));
    }
    let phi_o = match (&up.orient, &down.orient) {
        (Orientation::Angle(pu, dpu), Orientation::Angle(pd, dpd)) => {
            for (i, v) in dpu.iter().enumerate() {
                jac[2][i] = -v;
            }
            for (i, v) in dpd.iter().enumerate() {
                jac[2][ku + i] = *v;
            }
            pd - pu
        }
        (Orientation::Angle(psi, dpsi), Orientation::Slope(s, ds)) => angle_slope(
            *psi,
            dpsi,
            0,
            s,
            ds,
            ku,
            &mut jac[2],
            lambda.map(|l| l[2]),
            &mut hess,
        ),
        (Orientation::Slope(s, ds), Orientation::Angle(psi, dpsi)) => angle_slope(
            *psi,
            dpsi,
            ku,
            s,
            ds,
            0,
            &mut jac[2],
            lambda.map(|l| l[2]),
            &mut hess,
        ),
        (Orientation::Slope(..), Orientation::Slope(..)) => {
            unreachable!("consecutive ANCF segments share a node and need no joint")
        }
    };
    JointEval {
        idx,
        phi: [d[0], d[1], phi_o],
        jac,
        hess,
    }
}

/// Φ = n(ψ)·s with ψ over local coordinates at offset `oa`, s at offset `os`.
#[allow(clippy::too_many_arguments)]
fn angle_slope(
    psi: f64,
    dpsi: &[f64],
    oa: usize,
    s: &Vector2<f64>,
    ds: &[Vector2<f64>],
    os: usize,
    jac: &mut [f64],
    lambda: Option<f64>,
    hess: &mut Vec<(usize, usize, f64)>,
) -> f64 {
    let (sn, cs) = psi.sin_cos();
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
