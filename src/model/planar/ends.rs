//! Ends of planar segments (ports) and the root support.
//!
//! An end has a position p(q) and an orientation: either an angle ψ(q) (modal side: frame
//! angle, plus the elastic tip slope at a modal tip) or a slope vector s(q) (ANCF node: s = r′,
//! its length is the axial stretch).

use super::Planar;
use crate::math;
use crate::model::ancf::cross;
use crate::model::component::{Port, Support};
use crate::model::modal::{rot, ModalBody};
use crate::model::space::PortKin;
use nalgebra::Vector2;
use std::sync::Arc;

/// Derivatives over an end's local coordinates (inline up to 24: a planar modal body has at
/// most 3 + 12 + 2; no allocation in a step).
pub type Grads = smallvec::SmallVec<[f64; 24]>;

/// 2-vector derivatives over an end's local coordinates (inline as [`Grads`]).
pub type Grads2 = smallvec::SmallVec<[Vector2<f64>; 24]>;

/// Orientation of an end.
#[derive(Debug, Clone)]
pub enum Orientation {
    /// Angle ψ [rad], with ∂ψ/∂q_local.
    Angle(f64, Grads),
    /// Slope vector s [-], with ∂s/∂q_local (one 2-vector per local coordinate).
    Slope(Vector2<f64>, Grads2),
}

impl Default for Orientation {
    fn default() -> Self {
        Orientation::Angle(0.0, Grads::new())
    }
}

/// Kinematics of an end at one state, over its local coordinates.
#[derive(Debug, Clone, Default)]
pub struct EndKin {
    /// Position [m].
    pub p: Vector2<f64>,
    /// ∂p/∂q_local.
    pub dp: Grads2,
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
    pub j_dp_da: Grads2,
    /// A e_x / L.
    pub ax_over_l: Vector2<f64>,
    /// The body, whose `gram` is G (row-major n × n).
    pub body: Arc<ModalBody>,
    /// The tip angle ψ = θ + f(t), t = uᵀa the elastic tip slope w′(L): (f″(t), u), so that
    /// ∂²ψ/∂a_j∂a_k = f″ u_j u_k.
    pub angle: (f64, Grads),
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
                        let g = c.body.gram[j * n + k];
                        if g != 0.0 {
                            add(it + 1 + j, it + 1 + k, m * g);
                        }
                    }
                }
            }
        }
    }

    /// Adds w·∂²ψ/∂q∂q of an angle end (local × local) through `add(i, j, value)`: nonzero
    /// only at a modal tip ([`TipCurvature::angle`]).
    pub fn add_angle_hessian(&self, w: f64, mut add: impl FnMut(usize, usize, f64)) {
        if let Some(c) = &self.curv {
            let (f2, u) = &c.angle;
            let h = w * f2;
            if h != 0.0 {
                let a0 = c.theta + 1;
                for (j, uj) in u.iter().enumerate() {
                    for (k, uk) in u.iter().enumerate() {
                        add(a0 + j, a0 + k, h * uj * uk);
                    }
                }
            }
        }
    }

    /// Angle of the end [rad]: ψ, or atan2 of the slope.
    pub fn angle(&self) -> f64 {
        match &self.orient {
            Orientation::Angle(psi, _) => *psi,
            Orientation::Slope(s, _) => math::atan2(s[1], s[0]),
        }
    }
}

impl PortKin<Planar> for EndKin {
    fn position(&self) -> [f64; 2] {
        self.p.into()
    }

    fn jacobian(&self, k: usize) -> [f64; 2] {
        self.dp[k].into()
    }

    fn add_point_hessian(&self, mu: &[f64; 2], add: impl FnMut(usize, usize, f64)) {
        EndKin::add_point_hessian(self, Vector2::from(*mu), add)
    }

    fn attitude(&self) -> f64 {
        self.angle()
    }

    /// ∂ψ/∂q_k; for a slope s, ∂ψ/∂s = (−s_y, s_x)/|s|².
    fn rotation_jacobian(&self, k: usize) -> f64 {
        match &self.orient {
            Orientation::Angle(_, dpsi) => dpsi[k],
            Orientation::Slope(s, ds) => cross(s, &ds[k]) / s.norm_squared(),
        }
    }
}

/// An ANCF node, local coordinates `[r_x, r_y, s_x, s_y]` (position [m], slope r′ [-]).
#[derive(Debug, Clone, Copy, Default)]
pub struct NodePort;

impl Port<Planar> for NodePort {
    fn kinematics(&self, q: &[f64]) -> EndKin {
        let mut out = EndKin::default();
        self.kinematics_first_into(q, &mut out);
        out
    }

    fn kinematics_first_into(&self, q: &[f64], out: &mut EndKin) {
        let z = Vector2::zeros();
        out.p = Vector2::new(q[0], q[1]);
        out.dp.clear();
        out.dp.extend([Vector2::x(), Vector2::y(), z, z]);
        let mut ds = match std::mem::take(&mut out.orient) {
            Orientation::Slope(_, v) => v,
            Orientation::Angle(..) => Grads2::new(),
        };
        ds.clear();
        ds.extend([z, z, Vector2::x(), Vector2::y()]);
        out.orient = Orientation::Slope(Vector2::new(q[2], q[3]), ds);
        out.curv = None;
    }

    /// ψ = atan2(s_y, s_x): ∂²ψ/∂s∂s = [[2 s_x s_y, s_y² − s_x²], [s_y² − s_x², −2 s_x s_y]]/|s|⁴.
    fn add_moment_stiffness(&self, q: &[f64], m: &f64, add: &mut dyn FnMut(usize, usize, f64)) {
        let (sx, sy) = (q[2], q[3]);
        let n4 = (sx * sx + sy * sy).powi(2);
        let (a, b) = (2.0 * sx * sy / n4, (sy * sy - sx * sx) / n4);
        add(2, 2, -m * a);
        add(2, 3, -m * b);
        add(3, 2, -m * b);
        add(3, 3, m * a);
    }
}

/// The tip (x = L) of a modal body, on the body's local coordinates `[R_x, R_y, θ, a…]`:
/// position with the foreshortening ([`ModalBody::tip_local`]), angle ψ = θ + f(w′(L)), the
/// direction of the tangent [1 − ½w′²; w′] of the body's foreshortened kinematics,
/// f(t) = atan2(t, 1 − ½t²) = t + t³/6 + …, the elastic tip slope t = w′(L) = φ′(1)ᵀa/L.
#[derive(Debug, Clone)]
pub struct ModalTipPort(pub Arc<ModalBody>);

/// f(t) = atan2(t, 1 − ½t²) and its first two derivatives: f′ = (1 + ½t²)/(1 + ¼t⁴),
/// f″ = t(1 − t² − ¼t⁴)/(1 + ¼t⁴)².
fn tip_angle(t: f64) -> [f64; 3] {
    let (t2, d) = (t * t, 1.0 + 0.25 * t * t * t * t);
    [
        math::atan2(t, 1.0 - 0.5 * t2),
        (1.0 + 0.5 * t2) / d,
        t * (1.0 - t2 - 0.25 * t2 * t2) / (d * d),
    ]
}

impl ModalTipPort {
    /// ∂t/∂a_k = φ_k′(1)/L.
    fn slope_gradient(&self) -> Grads {
        let b = &*self.0;
        b.basis.tip_slope.iter().map(|s| s / b.length).collect()
    }
}

impl ModalTipPort {
    /// The kinematics into `out` (its vectors refilled in place), with the second derivatives
    /// if `curvature`.
    fn kinematics_with(&self, ql: &[f64], curvature: bool, out: &mut EndKin) {
        let b = &*self.0;
        let n = b.modes();
        let t = b.tip_slope(ql);
        let [f, f1, f2] = if b.nonlinear {
            tip_angle(t)
        } else {
            [t, 1.0, 0.0]
        };
        let mut dpsi = angle_storage(&mut out.orient);
        dpsi.clear();
        dpsi.resize(3 + n, 0.0);
        dpsi[2] = 1.0;
        let a = rot(ql[2]);
        // the foreshortening gradient g_k in dpsi[3 + k] until ∂ψ/∂a_k replaces it
        let tip = b.tip_local_into(ql, &mut dpsi[3..]);
        let au = a * tip;
        let dp = &mut out.dp;
        dp.clear();
        dp.extend([Vector2::x(), Vector2::y(), Vector2::new(-au[1], au[0])]);
        for k in 0..n {
            dp.push(a * Vector2::new(-dpsi[3 + k], b.basis.tip[k]));
            dpsi[3 + k] = f1 * b.basis.tip_slope[k] / b.length;
        }
        out.curv = curvature.then(|| TipCurvature {
            theta: 2,
            au,
            j_dp_da: dp[3..].iter().map(|c| Vector2::new(-c[1], c[0])).collect(),
            ax_over_l: a.column(0).into_owned() / b.length,
            body: self.0.clone(),
            angle: (f2, self.slope_gradient()),
        });
        out.p = Vector2::new(ql[0], ql[1]) + au;
        out.orient = Orientation::Angle(ql[2] + f, dpsi);
    }
}

/// The ∂ψ/∂q storage of an angle orientation, taken for reuse (empty for a slope).
fn angle_storage(o: &mut Orientation) -> Grads {
    match std::mem::take(o) {
        Orientation::Angle(_, v) => v,
        Orientation::Slope(..) => Grads::new(),
    }
}

impl Port<Planar> for ModalTipPort {
    fn kinematics(&self, ql: &[f64]) -> EndKin {
        let mut out = EndKin::default();
        self.kinematics_with(ql, true, &mut out);
        out
    }

    /// Without [`EndKin::curv`] (the residual paths).
    fn kinematics_first(&self, ql: &[f64]) -> EndKin {
        let mut out = EndKin::default();
        self.kinematics_with(ql, false, &mut out);
        out
    }

    fn kinematics_first_into(&self, ql: &[f64], out: &mut EndKin) {
        self.kinematics_with(ql, false, out);
    }

    /// −m·∂²ψ/∂a_j∂a_k = −m f″(t) u_j u_k (ψ is linear in θ; in a for a linear body).
    fn add_moment_stiffness(&self, ql: &[f64], m: &f64, add: &mut dyn FnMut(usize, usize, f64)) {
        if !self.0.nonlinear {
            return;
        }
        let u = self.slope_gradient();
        let h = -m * tip_angle(self.0.tip_slope(ql))[2];
        if h != 0.0 {
            for (j, uj) in u.iter().enumerate() {
                for (k, uk) in u.iter().enumerate() {
                    add(3 + j, 3 + k, h * uj * uk);
                }
            }
        }
    }
}

/// The root (frame origin) of a modal body, on the body's local coordinates: position R,
/// angle θ.
#[derive(Debug, Clone)]
pub struct ModalRootPort(pub Arc<ModalBody>);

impl Port<Planar> for ModalRootPort {
    fn kinematics(&self, ql: &[f64]) -> EndKin {
        let mut out = EndKin::default();
        self.kinematics_first_into(ql, &mut out);
        out
    }

    fn kinematics_first_into(&self, ql: &[f64], out: &mut EndKin) {
        let d = self.0.dim();
        out.dp.clear();
        out.dp.resize(d, Vector2::zeros());
        out.dp[0] = Vector2::x();
        out.dp[1] = Vector2::y();
        let mut dpsi = angle_storage(&mut out.orient);
        dpsi.clear();
        dpsi.resize(d, 0.0);
        dpsi[2] = 1.0;
        out.p = Vector2::new(ql[0], ql[1]);
        out.orient = Orientation::Angle(ql[2], dpsi);
        out.curv = None;
    }

    /// The angle θ is a coordinate: no stiffness.
    fn add_moment_stiffness(&self, _: &[f64], _: &f64, _: &mut dyn FnMut(usize, usize, f64)) {}
}

/// The root support of a planar beam: which held coordinates carry its force and moment.
/// Indices are into the held values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RootSupport {
    /// ANCF root node: the force is the residual of the held position; a clamped root also
    /// holds the slope s, and the moment about the root is s × r_s.
    Node {
        /// Held x, y of the position.
        position: [usize; 2],
        /// Held x, y of the slope (clamped).
        slope: Option<[usize; 2]>,
    },
    /// Modal root frame: the force is the residual of R; a clamped root also holds θ, and the
    /// moment is its residual.
    Frame {
        /// Held x, y of R.
        position: [usize; 2],
        /// Held θ (clamped).
        angle: Option<usize>,
    },
}

impl Support<Planar> for RootSupport {
    fn reaction(&self, r: &[f64], held: &[f64]) -> ([f64; 2], f64) {
        match *self {
            RootSupport::Node { position: p, slope } => {
                let moment = slope.map_or(0.0, |[x, y]| held[x] * r[y] - held[y] * r[x]);
                ([r[p[0]], r[p[1]]], moment)
            }
            RootSupport::Frame { position: p, angle } => {
                ([r[p[0]], r[p[1]]], angle.map_or(0.0, |a| r[a]))
            }
        }
    }
}
