//! Transverse shape functions of a modal segment, on ξ = x/L ∈ [0, 1].
//!
//! The raw basis is the first `n` clamped–free Euler–Bernoulli modes
//! φ_n(ξ) = cosh λξ − cos λξ − σ_n(sinh λξ − sin λξ) (∫φ² dξ = 1, φ(1) = ±2), optionally followed
//! by the two static interface (Craig–Bampton constraint) shapes of the free end,
//! ψ_d = 3ξ² − 2ξ³ (unit tip deflection, zero tip slope) and ψ_r = ξ³ − ξ² (unit tip slope).
//! The raw basis is then made mass-orthonormal and stiffness-diagonal by the reduced generalized
//! eigenproblem, so that the final shapes satisfy ∫φ_iφ_j dξ = δ_ij and ∫φ_i″φ_j″ dξ = Λ_i δ_ij
//! (Λ_i = λ_i⁴ for the pure clamped–free basis). All invariants are computed once here.

use crate::math;
use crate::model::ancf::GAUSS5;
use nalgebra::{DMatrix, DVector};
use std::borrow::Cow;
use std::sync::OnceLock;

/// Roots of 1 + cos λ cosh λ = 0 are refined from these guesses by Newton's method.
fn clamped_free_root(n: usize) -> f64 {
    let mut x = if n == 1 {
        1.875
    } else {
        (n as f64 - 0.5) * std::f64::consts::PI
    };
    for _ in 0..50 {
        let f = 1.0 + math::cos(x) * math::cosh(x);
        let df = -math::sin(x) * math::cosh(x) + math::cos(x) * math::sinh(x);
        let dx = f / df;
        x -= dx;
        if dx.abs() < 1e-15 * x {
            break;
        }
    }
    x
}

/// A raw shape function: value, first and second ξ-derivatives.
#[derive(Debug, Clone, Copy)]
enum Raw {
    /// Clamped–free mode with λ and σ.
    Mode { lambda: f64, sigma: f64 },
    /// 3ξ² − 2ξ³.
    TipDeflection,
    /// ξ³ − ξ².
    TipSlope,
}

impl Raw {
    /// (φ, φ′, φ″) at ξ, derivatives with respect to ξ.
    fn eval(&self, xi: f64) -> [f64; 3] {
        match *self {
            Raw::Mode {
                lambda: l,
                sigma: s,
            } => {
                let x = l * xi;
                // cosh − σ sinh written as e^{−x} + (1 − σ) sinh x to avoid cancellation.
                let em = math::exp(-x);
                let (sh, ch) = (math::sinh(x), math::cosh(x));
                let (sn, cs) = math::sin_cos(x);
                let v = em + (1.0 - s) * sh - cs + s * sn;
                let d1 = l * (-em + (1.0 - s) * ch + sn + s * cs);
                let d2 = l * l * (em + (1.0 - s) * sh + cs - s * sn);
                [v, d1, d2]
            }
            Raw::TipDeflection => [
                3.0 * xi * xi - 2.0 * xi * xi * xi,
                6.0 * xi - 6.0 * xi * xi,
                6.0 - 12.0 * xi,
            ],
            Raw::TipSlope => [
                xi * xi * xi - xi * xi,
                3.0 * xi * xi - 2.0 * xi,
                6.0 * xi - 2.0,
            ],
        }
    }
}

/// Dimensionless shape basis with its precomputed invariants.
#[derive(Debug, Clone)]
pub struct ModalBasis {
    raw: Vec<Raw>,
    /// Final shapes as columns of coefficients on the raw basis: φ_j = Σ_i c[(i, j)] raw_i.
    coef: DMatrix<f64>,
    /// Λ_j = ∫φ_j″² dξ (ω_j = √Λ_j · √(EI/(ρA L⁴))).
    pub lambda4: Vec<f64>,
    /// ∫φ_j dξ.
    pub i1: Vec<f64>,
    /// ∫ξ φ_j dξ.
    pub ix: Vec<f64>,
    /// φ_j(1).
    pub tip: Vec<f64>,
    /// φ_j′(1) (per ξ).
    pub tip_slope: Vec<f64>,
    /// ∫₀¹ φ_i′φ_j′ dξ (row-major n × n): the tip foreshortening is ½ aᵀ G a / L.
    pub slope_gram: Vec<f64>,
    /// The shapes at the first [`SAMPLE_SETS`] sets of sample points asked for (a viewer's
    /// points, a station's cut, the stress points) and at the Gauss points between them
    /// ([`ModalBasis::sample_fields`]): state-independent values,
    /// computed once per set (the shapes cost exponentials and trigonometry).
    samples: [OnceLock<Samples>; SAMPLE_SETS],
}

/// How many sets of sample points a basis keeps ([`ModalBasis::sample_fields`]); a further set is
/// evaluated at each call.
pub const SAMPLE_SETS: usize = 6;

/// (φ, φ′, φ″) of every shape at sample points `xi` and, per interval up to each, the Gauss
/// weights (× half the interval) and the shapes at the Gauss points.
#[derive(Debug, Clone)]
struct Samples {
    xi: Vec<f64>,
    at: Vec<Vec<[f64; 3]>>,
    gauss: Vec<Vec<(f64, Vec<[f64; 3]>)>>,
}

impl Samples {
    fn new(basis: &ModalBasis, xi: &[f64]) -> Self {
        let mut from = 0.0;
        let mut gauss = Vec::with_capacity(xi.len());
        let mut at = Vec::with_capacity(xi.len());
        for &to in xi {
            let h = to - from;
            let mut g = Vec::new();
            if h != 0.0 {
                for (x, w) in GAUSS5 {
                    let mut phi = Vec::new();
                    basis.eval_all(from + 0.5 * h * (x + 1.0), &mut phi);
                    g.push((0.5 * h * w, phi));
                }
            }
            gauss.push(g);
            let mut phi = Vec::new();
            basis.eval_all(to, &mut phi);
            at.push(phi);
            from = to;
        }
        Self {
            xi: xi.to_vec(),
            at,
            gauss,
        }
    }
}

/// Composite 5-point Gauss–Legendre rule on [0, 1] with `panels` panels: (points, weights).
pub fn quadrature(panels: usize) -> Vec<(f64, f64)> {
    const G: [(f64, f64); 5] = [
        (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
        (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (0.0, 0.568_888_888_888_888_9),
        (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (0.906_179_845_938_664, 0.236_926_885_056_189_1),
    ];
    let h = 1.0 / panels as f64;
    let mut out = Vec::with_capacity(panels * 5);
    for p in 0..panels {
        let a = p as f64 * h;
        for (x, w) in G {
            out.push((a + 0.5 * h * (x + 1.0), 0.5 * h * w));
        }
    }
    out
}

impl ModalBasis {
    /// `modes` clamped–free modes, plus the two interface shapes if `interface`.
    pub fn new(modes: usize, interface: bool) -> Self {
        let mut raw: Vec<Raw> = (1..=modes)
            .map(|n| {
                let l = clamped_free_root(n);
                let sigma = (math::sinh(l) - math::sin(l)) / (math::cosh(l) + math::cos(l));
                Raw::Mode { lambda: l, sigma }
            })
            .collect();
        if interface {
            raw.push(Raw::TipDeflection);
            raw.push(Raw::TipSlope);
        }
        let n = raw.len();
        let quad = quadrature(64);
        let mut m = DMatrix::<f64>::zeros(n, n);
        let mut k = DMatrix::<f64>::zeros(n, n);
        for &(xi, w) in &quad {
            let v: Vec<[f64; 3]> = raw.iter().map(|r| r.eval(xi)).collect();
            for i in 0..n {
                for j in 0..n {
                    m[(i, j)] += w * v[i][0] * v[j][0];
                    k[(i, j)] += w * v[i][2] * v[j][2];
                }
            }
        }
        // Reduced generalized eigenproblem K c = Λ M c via Cholesky M = L Lᵀ.
        let chol = m
            .clone()
            .cholesky()
            .expect("raw modal basis is linearly independent");
        let linv = chol
            .l()
            .try_inverse()
            .expect("Cholesky factor of a positive definite matrix is invertible");
        let kt = &linv * &k * linv.transpose();
        let kt = 0.5 * (&kt + kt.transpose());
        let eig = kt.symmetric_eigen();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let mut coef = DMatrix::<f64>::zeros(n, n);
        let mut lambda4 = Vec::with_capacity(n);
        for (j, &o) in order.iter().enumerate() {
            let c: DVector<f64> = linv.transpose() * eig.eigenvectors.column(o);
            coef.set_column(j, &c);
            lambda4.push(eig.eigenvalues[o]);
        }
        let mut basis = Self {
            raw,
            coef,
            lambda4,
            i1: vec![0.0; n],
            ix: vec![0.0; n],
            tip: vec![0.0; n],
            tip_slope: vec![0.0; n],
            slope_gram: vec![0.0; n * n],
            samples: Default::default(),
        };
        // Deterministic sign: φ_j(1) > 0 (or φ_j′(1) > 0 if the tip value vanishes).
        for j in 0..n {
            let [t, ts, _] = basis.eval_one(j, 1.0);
            let flip = if t.abs() > 1e-9 { t < 0.0 } else { ts < 0.0 };
            if flip {
                let c = -basis.coef.column(j);
                basis.coef.set_column(j, &c);
            }
        }
        for &(xi, w) in &quad {
            let vals: Vec<[f64; 3]> = (0..n).map(|j| basis.eval_one(j, xi)).collect();
            for j in 0..n {
                basis.i1[j] += w * vals[j][0];
                basis.ix[j] += w * xi * vals[j][0];
                for i in 0..n {
                    basis.slope_gram[i * n + j] += w * vals[i][1] * vals[j][1];
                }
            }
        }
        for j in 0..n {
            let [t, ts, _] = basis.eval_one(j, 1.0);
            basis.tip[j] = t;
            basis.tip_slope[j] = ts;
        }
        basis
    }

    /// Number of shapes.
    pub fn len(&self) -> usize {
        self.raw.len()
    }

    /// Always false: a basis has at least one shape.
    pub fn is_empty(&self) -> bool {
        self.raw.is_empty()
    }

    /// G1 = ∫(1 − ξ)φ_i′φ_j′ dξ and G2 = ∫½(1 − ξ²)φ_i′φ_j′ dξ (row-major), by the composite
    /// Gauss–Legendre rule: the geometric stiffness of an axial force that falls linearly (axial
    /// inertia) or parabolically (centrifugal) to zero at the free end.
    pub fn stiffening_grams(&self) -> (Vec<f64>, Vec<f64>) {
        let n = self.len();
        let (mut g1, mut g2) = (vec![0.0; n * n], vec![0.0; n * n]);
        for (xi, w) in quadrature(64) {
            let d: Vec<f64> = (0..n).map(|j| self.eval_one(j, xi)[1]).collect();
            for i in 0..n {
                for j in 0..n {
                    let pp = w * d[i] * d[j];
                    g1[i * n + j] += (1.0 - xi) * pp;
                    g2[i * n + j] += 0.5 * (1.0 - xi * xi) * pp;
                }
            }
        }
        (g1, g2)
    }

    /// (φ_j, φ_j′, φ_j″) of every shape at ξ into `out` (each raw function evaluated once).
    pub fn eval_all(&self, xi: f64, out: &mut Vec<[f64; 3]>) {
        let raw: Vec<[f64; 3]> = self.raw.iter().map(|r| r.eval(xi)).collect();
        out.clear();
        out.extend((0..self.len()).map(|j| {
            let mut f = [0.0; 3];
            for (i, v) in raw.iter().enumerate() {
                let c = self.coef[(i, j)];
                for d in 0..3 {
                    f[d] += c * v[d];
                }
            }
            f
        }));
    }

    /// The shapes at the sample points `xi` (kept for the first [`SAMPLE_SETS`] sets asked
    /// for; a slot another thread fills meanwhile with another set is passed over).
    fn samples(&self, xi: &[f64]) -> Cow<'_, Samples> {
        for slot in &self.samples {
            let s = slot.get_or_init(|| Samples::new(self, xi));
            if s.xi == xi {
                return Cow::Borrowed(s);
            }
        }
        Cow::Owned(Samples::new(self, xi))
    }

    /// At each ξ of the ascending `xi` (index k): the fields of each amplitude vector am of `a`,
    /// (Σφ_j am_j, Σφ_j′ am_j, Σφ_j″ am_j) (ξ-derivatives), and ∫₀^ξ (φ′ᵀx)(φ′ᵀy) dξ for each
    /// pair (x, y) of `pairs` by the 5-point Gauss rule on every interval between consecutive
    /// ξ (the foreshortening ½∫₀^ξ w′²dξ / L of the points inside a segment and its rate),
    /// handed to `each(k, fields, integrals)` (no allocation once the points' shapes are kept).
    pub fn sample_fields<const A: usize, const P: usize>(
        &self,
        a: [&[f64]; A],
        pairs: [(&[f64], &[f64]); P],
        xi: &[f64],
        mut each: impl FnMut(usize, [[f64; 3]; A], [f64; P]),
    ) {
        let s = self.samples(xi);
        let field = |phi: &[[f64; 3]], am: &[f64]| {
            let mut f = [0.0; 3];
            for (p, aj) in phi.iter().zip(am.iter()) {
                for d in 0..3 {
                    f[d] += p[d] * aj;
                }
            }
            f
        };
        let mut acc = [0.0; P];
        for (k, (g, at)) in s.gauss.iter().zip(&s.at).enumerate() {
            for (w, phi) in g {
                let slope = |v: &[f64]| -> f64 { phi.iter().zip(v).map(|(p, x)| p[1] * x).sum() };
                for (s, (x, y)) in acc.iter_mut().zip(&pairs) {
                    *s += w * slope(x) * slope(y);
                }
            }
            each(k, a.map(|am| field(at, am)), acc);
        }
    }

    /// (φ_j, φ_j′, φ_j″) at ξ.
    pub fn eval_one(&self, j: usize, xi: f64) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (i, r) in self.raw.iter().enumerate() {
            let c = self.coef[(i, j)];
            let v = r.eval(xi);
            for d in 0..3 {
                out[d] += c * v[d];
            }
        }
        out
    }
}

/// Number of torsion shapes of a spatial modal body (ξ and √2 sin πξ).
pub const TORSION_SHAPES: usize = 2;

/// The torsion shapes χ_m(ξ) and their slopes χ_m′(ξ) (per ξ) of a spatial modal body.
pub fn torsion_shapes(xi: f64) -> ([f64; 2], [f64; 2]) {
    use std::f64::consts::{PI, SQRT_2};
    let (s, c) = crate::math::sin_cos(PI * xi);
    ([xi, SQRT_2 * s], [1.0, SQRT_2 * PI * c])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Table of docs/references.md §3 (independent SciPy computation).
    const TABLE: [(f64, f64, f64, f64, f64); 4] = [
        (1.875104, 0.782992, 0.568826, 2.0, 2.753011),
        (4.694091, 0.433936, 0.090767, 2.0, 9.561557),
        (7.854757, 0.254425, 0.032416, 2.0, 15.697332),
        (10.995541, 0.181898, 0.016542, 2.0, 21.991819),
    ];

    #[test]
    fn clamped_free_modes_match_reference_table() {
        let b = ModalBasis::new(4, false);
        for (j, &(lam, i1, ix, tip, slope)) in TABLE.iter().enumerate() {
            // signs: the table has φ(1) = (−1)^{n+1}·2; ours are normalised to φ(1) > 0.
            let s = if j % 2 == 0 { 1.0 } else { -1.0 };
            assert!((b.lambda4[j].powf(0.25) - lam).abs() < 2e-6, "lambda {j}");
            assert!((b.i1[j] * s - i1).abs() < 2e-6, "i1 {j}");
            assert!((b.ix[j] * s - ix).abs() < 2e-6, "ix {j}");
            assert!((b.tip[j] - tip).abs() < 1e-6, "tip {j}");
            assert!(
                (b.tip_slope[j] - slope).abs() < 2e-6,
                "slope {j}: {}",
                b.tip_slope[j]
            );
        }
    }

    #[test]
    fn slope_gram_matches_the_table() {
        // docs/references.md §3: ∫φ′² dξ = 4.647778, 32.417399, 77.298891 for modes 1–3
        let b = ModalBasis::new(3, false);
        for (j, want) in [4.647778, 32.417399, 77.298891].iter().enumerate() {
            assert!((b.slope_gram[j * 3 + j] - want).abs() < 2e-5, "{j}");
        }
    }

    #[test]
    fn interface_modes_lower_nothing_below_the_exact_spectrum() {
        // Rayleigh–Ritz: enriched basis gives eigenvalues ≥ exact and ≤ the unenriched ones.
        let plain = ModalBasis::new(2, false);
        let rich = ModalBasis::new(2, true);
        for j in 0..2 {
            assert!(rich.lambda4[j] <= plain.lambda4[j] * (1.0 + 1e-9));
            assert!(rich.lambda4[j] >= plain.lambda4[j] * (1.0 - 1e-6));
        }
        // the third eigenvalue of the enriched basis approximates λ₃⁴ from above
        let l3 = TABLE[2].0.powi(4);
        assert!(rich.lambda4[2] >= l3 * (1.0 - 1e-9) && rich.lambda4[2] < 1.5 * l3);
        // orthonormality
        let q = quadrature(64);
        let n = rich.len();
        for i in 0..n {
            for j in 0..n {
                let mut mij = 0.0;
                for &(x, w) in &q {
                    mij += w * rich.eval_one(i, x)[0] * rich.eval_one(j, x)[0];
                }
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((mij - want).abs() < 1e-8, "M[{i},{j}] = {mij}");
            }
        }
    }
}
