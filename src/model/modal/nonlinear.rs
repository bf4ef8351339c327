//! The geometrically nonlinear rule both modal bodies share (planar [`super::ModalBody`] and
//! spatial [`super::ModalBody3`]): the foreshortening and curvature terms' composite 5-point
//! Gauss–Legendre rule on [0, 1], the shapes at its points, one point's modal fields and the
//! foreshortening's axial force along the body (the kinematics in `body.rs`'s module doc).

use super::basis::ModalBasis;
use crate::model::ancf::GAUSS5;
use crate::model::vector::Real;

/// Tables of the nonlinear (foreshortening and curvature) terms: a composite 5-point
/// Gauss–Legendre rule on [0, 1] and the shapes at its points.
#[derive(Debug, Clone)]
pub(super) struct Nonlinear {
    /// Points ξ_p, panel by panel.
    pub(super) xi: Vec<f64>,
    /// Weights W_p (Σ W_p = 1).
    pub(super) w: Vec<f64>,
    /// (φ_k, φ_k′/L, φ_k″/L²)(ξ_p) at `[p * n + k]` (x-derivatives, once the body scales them).
    pub(super) phi: Vec<[f64; 3]>,
    /// The same values for pairs of points: for the pair (2b, 2b + 1) and shape k, the six
    /// values (φ_k, φ_k′/L, φ_k″/L²) at both points (d-th at both, then the next) at
    /// `[(b * n + k) * 6..]`, an odd count's last pair padded with zeros; for
    /// `ModalBody::fields_f64`'s two-lane sums.
    pub(super) phi_pairs: Vec<f64>,
    /// ∫ from the start of a panel to its i-th point of the degree-4 interpolant through its
    /// five points, weight of the j-th: `s[i][j]` (× the panel half-width): with the full
    /// panels before, the cumulative integral ∫₀^ξ_q f dξ ≈ Σ_p V_qp f_p.
    pub(super) s: [[f64; 5]; 5],
}

/// One point's modal fields of one plane from its shape values `phi` (φ_k, φ_k′, φ_k″) and the
/// amplitudes `q`, their rates `v` and accelerations `a`: (w, ẇ, ẅ, w′, ẇ′, ẅ′, w″, ẇ″).
#[inline]
pub(super) fn point_fields<T: Real>(phi: &[[f64; 3]], q: &[T], v: &[T], a: &[T]) -> [T; 8] {
    let mut acc = [T::zero(); 8];
    for (((ph, &x), &y), &z) in phi.iter().zip(q).zip(v).zip(a) {
        acc[0] += x * ph[0];
        acc[1] += y * ph[0];
        acc[2] += z * ph[0];
        acc[3] += x * ph[1];
        acc[4] += y * ph[1];
        acc[5] += z * ph[1];
        acc[6] += x * ph[2];
        acc[7] += y * ph[2];
    }
    acc
}

/// ∫ from −1 to `x` of the Lagrange polynomial ℓ_j through the 5 Gauss points (degree 4: the
/// 5-point rule on [−1, x] is exact).
fn lagrange_integral(x: f64, j: usize) -> f64 {
    let xj = GAUSS5[j].0;
    let mut acc = 0.0;
    for (t, wt) in GAUSS5 {
        let tt = -1.0 + 0.5 * (x + 1.0) * (t + 1.0);
        let mut l = 1.0;
        for (m, &(xm, _)) in GAUSS5.iter().enumerate() {
            if m != j {
                l *= (tt - xm) / (xj - xm);
            }
        }
        acc += 0.5 * (x + 1.0) * wt * l;
    }
    acc
}

impl Nonlinear {
    /// The foreshortening's axial force at every point, N_p = Σ_q m_q V_qp (V the cumulative
    /// rule: the panels after p whole, p's own panel by `s`), m_q the point's axial inertia
    /// force in slot `slot` of its `stride` fields in `buf`. Calls `visit(p, p's fields, N_p)`
    /// panel by panel from the tip, after the panel's m_q are read (so `visit` may overwrite
    /// that slot).
    pub(super) fn for_each_axial_force<T: Real>(
        &self,
        buf: &mut [T],
        stride: usize,
        slot: usize,
        mut visit: impl FnMut(usize, &mut [T], T),
    ) {
        let mut later = T::zero();
        for p0 in (0..self.w.len()).step_by(5).rev() {
            let mut mf = [T::zero(); 5];
            for (i, m) in mf.iter_mut().enumerate() {
                *m = buf[stride * (p0 + i) + slot];
            }
            for j in 0..5 {
                let p = p0 + j;
                let mut axial = later * self.w[p];
                for (i, m) in mf.iter().enumerate() {
                    axial += *m * self.s[i][j];
                }
                visit(p, &mut buf[stride * p..stride * (p + 1)], axial);
            }
            for m in mf {
                later += m;
            }
        }
    }

    pub(super) fn new(basis: &ModalBasis, panels: usize) -> Self {
        let quad = super::basis::quadrature(panels);
        let mut phi = Vec::with_capacity(quad.len() * basis.len());
        let mut buf = Vec::new();
        for &(x, _) in &quad {
            basis.eval_all(x, &mut buf);
            phi.extend_from_slice(&buf);
        }
        // s[i][j] = h/2 ∫_{−1}^{x_i} ℓ_j(t) dt (ℓ_j the Lagrange polynomials of the Gauss
        // points, degree 4: the 5-point rule on [−1, x_i] is exact)
        let half = 0.5 / panels as f64;
        let mut s = [[0.0; 5]; 5];
        for (i, &(xi, _)) in GAUSS5.iter().enumerate() {
            for (j, sij) in s[i].iter_mut().enumerate() {
                *sij = half * lagrange_integral(xi, j);
            }
        }
        Self {
            xi: quad.iter().map(|p| p.0).collect(),
            w: quad.iter().map(|p| p.1).collect(),
            phi,
            phi_pairs: Vec::new(),
            s,
        }
    }

    /// The tables with x-derivatives for a body of length `l` and n shapes (and the pairs).
    pub(super) fn scaled(mut self, l: f64, n: usize) -> Self {
        for f in &mut self.phi {
            f[1] /= l;
            f[2] /= l * l;
        }
        self.pair_up(n);
        self
    }

    /// Fills [`Nonlinear::phi_pairs`] from `phi` (after its scaling) for n shapes.
    fn pair_up(&mut self, n: usize) {
        let np = self.w.len();
        self.phi_pairs = vec![0.0; np.div_ceil(2) * n * 6];
        for (p, row) in self.phi.chunks_exact(n).enumerate() {
            let (b, lane) = (p / 2, p % 2);
            for (k, f) in row.iter().enumerate() {
                for (d, &x) in f.iter().enumerate() {
                    self.phi_pairs[(b * n + k) * 6 + 2 * d + lane] = x;
                }
            }
        }
    }
}

/// Panels of the body's quadrature for n shapes: one per four shapes, at least two. The
/// nonlinear terms are a small part of the forces, dominated by the lowest modes: on Case 1
/// (12 modes + 2 interface shapes) 2 and 14 panels give the same tip history to 1e-8 m, and
/// on the γ = 2 elastica (8 modes) to 5e-7 m of 0.096 m.
pub(super) fn panels(n: usize) -> usize {
    n.div_ceil(4).max(2)
}

impl Nonlinear {
    /// Weights V_p of the cumulative rule at ξ ∈ [0, 1]: ∫₀^ξ f dξ ≈ Σ_p V_p f_p, the panels
    /// before ξ's whole, ξ's own by the degree-4 interpolant through its five points (the rule of
    /// [`Nonlinear::s`] at any ξ; at ξ = 1 the weights W_p, at a point of the rule its row of
    /// `s`).
    pub(super) fn cumulative_weights(&self, xi: f64) -> Vec<f64> {
        let panels = self.w.len() / 5;
        let h = 1.0 / panels as f64;
        let b = ((xi / h).floor().max(0.0) as usize).min(panels - 1);
        let t = (2.0 * (xi - b as f64 * h) / h - 1.0).clamp(-1.0, 1.0);
        let mut v = vec![0.0; self.w.len()];
        v[..5 * b].copy_from_slice(&self.w[..5 * b]);
        for j in 0..GAUSS5.len() {
            v[5 * b + j] = 0.5 * h * lagrange_integral(t, j);
        }
        v
    }
}

/// A point mass on a modal body (docs/references.md §10): a point of the body's kinematics with
/// its own mass, r = R + A ū(x), ū = (x + c, w(, v)), c = −½ aᵀ G_m a (per bending plane), so
/// that its inertia and weight enter the reduced matrices and the nonlinear terms exactly on
/// the body's shapes (Ritz).
#[derive(Debug, Clone)]
pub(super) struct BodyPoint {
    /// Mass [kg].
    pub(super) mass: f64,
    /// Distance from the body's root x [m].
    pub(super) x: f64,
    /// φ_k(x/L) [-].
    pub(super) phi: Vec<f64>,
    /// G_m = ∫₀ˣ φ′φ′ᵀ dx (row-major n × n, x-derivatives) [1/m] on the body's cumulative
    /// rule (the tip's ½aᵀGa/L at x = L); zero on a linear body (ū = (x, w)).
    pub(super) gram: Vec<f64>,
    /// A rigid body on the section (planar): rotary inertia J about its centre [kg m²], its
    /// centre's offset o (along the tangent, along the normal) [m] and φ_k′(x) [1/m]; `None`
    /// for a point.
    pub(super) body: Option<(f64, [f64; 2], Vec<f64>)>,
}

impl BodyPoint {
    /// The point of mass `mass` at x [m] of a body of length `l` with shapes `basis` and
    /// tables `nl` (scaled to x-derivatives); `nonlinear` false: no foreshortening.
    pub(super) fn new(
        basis: &ModalBasis,
        nl: &Nonlinear,
        l: f64,
        nonlinear: bool,
        (x, mass): (f64, f64),
    ) -> Self {
        let n = basis.len();
        let xi = (x / l).clamp(0.0, 1.0);
        let mut buf = Vec::new();
        basis.eval_all(xi, &mut buf);
        let phi = buf.iter().map(|f| f[0]).collect();
        let mut gram = vec![0.0; n * n];
        if nonlinear {
            for (p, v) in nl.cumulative_weights(xi).iter().enumerate() {
                let ph = &nl.phi[p * n..(p + 1) * n];
                for i in 0..n {
                    for j in 0..n {
                        gram[i * n + j] += l * v * ph[i][1] * ph[j][1];
                    }
                }
            }
        }
        Self {
            mass,
            x,
            phi,
            gram,
            body: None,
        }
    }

    /// The same point as a rigid body on the section of rotary inertia `inertia` [kg m²] and
    /// offset `offset` [m] (planar), `dphi` = φ′(x) [1/m].
    pub(super) fn with_body(mut self, inertia: f64, offset: [f64; 2], dphi: Vec<f64>) -> Self {
        self.body = Some((inertia, offset, dphi));
        self
    }

    /// (G_m a)_k.
    #[inline]
    pub(super) fn ga<T: Real>(&self, a: &[T], k: usize) -> T {
        let n = self.phi.len();
        let mut s = T::zero();
        for (g, &x) in self.gram[k * n..(k + 1) * n].iter().zip(a) {
            s += x * *g;
        }
        s
    }

    /// (ū, u̇, ü) of one bending plane's amplitudes (a, ȧ, ä): (c, ċ, c̈) of the
    /// foreshortening and (w, ẇ, ẅ).
    #[inline]
    pub(super) fn plane<T: Real>(&self, a: &[T], v: &[T], acc: &[T]) -> ([T; 3], [T; 3]) {
        let mut c = [T::zero(); 3];
        let mut w = [T::zero(); 3];
        for k in 0..self.phi.len() {
            let (ga, gv) = (self.ga(a, k), self.ga(v, k));
            c[0] += a[k] * ga * -0.5;
            c[1] -= v[k] * ga;
            c[2] -= v[k] * gv + acc[k] * ga;
            w[0] += a[k] * self.phi[k];
            w[1] += v[k] * self.phi[k];
            w[2] += acc[k] * self.phi[k];
        }
        (c, w)
    }
}
