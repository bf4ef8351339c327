//! Planar ANCF cable element (gradient-deficient, 8 coordinates, cubic Hermite).
//!
//! Coordinates `e = [r0, r0′, r1, r1′]` (global x, y of the end positions [m] and of the slopes
//! ∂r/∂x [-], x the arc length of the straight reference configuration). `r(x) = S(x) e` with
//! the Hermite functions of the paper (eq. 6). Everything here is a pure function of `e`, `ė`.
//!
//! Elastic energy U = ½∫EA ε² dx + ½∫EI K² dx with, for [`StrainModel::Exact`],
//! ε = |r′| − 1 and the signed material curvature K = e₃·(r′×r″)/|r′|² (Gerstmayr & Irschik 2008),
//! 5 Gauss points for the axial part and 3 for bending (as Exudyn `ObjectANCFCable2D`).
//! [`StrainModel::Paper`] uses ε = ½(r′ᵀr′ − 1) and κ ≈ |r″| (constant bending stiffness).
//! Kelvin–Voigt damping (retardation time τ) adds EAτ ε̇ δε + EIτ K̇ δK.
//!
//! An initially curved element ([`AncfProps::reference`], a segment's `initial_curvature`)
//! counts its strains from its unstressed arc: U = ½∫EA (ε − ε₀)² dx + ½∫EI (K − K₀)² dx, with
//! ε₀, K₀ the arc's own measures at each quadrature point ([`AncfReference`]); x is then the
//! arc length of the curved reference. Without a reference the code path is the straight one.

use crate::math;
use crate::model::sample::ShapePoint;
use crate::model::vector::Real;
use crate::scene::StrainModel;
use nalgebra::{SMatrix, SVector, Vector2};

/// 8-vector of element coordinates.
pub type Vec8 = SVector<f64, 8>;
/// 8×8 element matrix.
pub type Mat8 = SMatrix<f64, 8, 8>;

/// 3-point Gauss rule on [−1, 1]: (abscissa, weight).
pub(crate) const GAUSS3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];
/// 5-point Gauss rule on [−1, 1]: (abscissa, weight).
pub(crate) const GAUSS5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// The polynomial of degree 4 through `values` at the [`GAUSS5`] points, at ξ ∈ [0, 1] of the
/// element (Lagrange form): a tapered element's ρA(x) between its quadrature points, exact for
/// the at most quadratic ρA of a linear taper ([`SectionTable`]).
pub(crate) fn gauss5_interpolate(values: &[f64; 5], xi: f64) -> f64 {
    let t = 2.0 * xi - 1.0;
    let mut out = 0.0;
    for (i, (ti, _)) in GAUSS5.iter().enumerate() {
        let mut w = 1.0;
        for (j, (tj, _)) in GAUSS5.iter().enumerate() {
            if j != i {
                w *= (t - tj) / (ti - tj);
            }
        }
        out += w * values[i];
    }
    out
}

/// Hermite shape functions and their first and second x-derivatives at ξ = x/l.
#[derive(Debug, Clone, Copy)]
pub struct Shape {
    /// s1..s4 [-, m, -, m].
    pub s: [f64; 4],
    /// ds/dx.
    pub ds: [f64; 4],
    /// d²s/dx².
    pub dds: [f64; 4],
}

impl Shape {
    /// Shape functions at ξ ∈ [0, 1] of an element of length `l`.
    pub fn at(xi: f64, l: f64) -> Self {
        let (x2, x3) = (xi * xi, xi * xi * xi);
        Self {
            s: [
                1.0 - 3.0 * x2 + 2.0 * x3,
                l * (xi - 2.0 * x2 + x3),
                3.0 * x2 - 2.0 * x3,
                l * (x3 - x2),
            ],
            ds: [
                (-6.0 * xi + 6.0 * x2) / l,
                1.0 - 4.0 * xi + 3.0 * x2,
                (6.0 * xi - 6.0 * x2) / l,
                3.0 * x2 - 2.0 * xi,
            ],
            dds: [
                (-6.0 + 12.0 * xi) / (l * l),
                (-4.0 + 6.0 * xi) / l,
                (6.0 - 12.0 * xi) / (l * l),
                (6.0 * xi - 2.0) / l,
            ],
        }
    }

    fn combine(w: &[f64; 4], e: &Vec8) -> Vector2<f64> {
        let mut r = Vector2::zeros();
        for k in 0..4 {
            r += w[k] * Vector2::new(e[2 * k], e[2 * k + 1]);
        }
        r
    }

    /// Position r(x) = S e.
    pub fn r(&self, e: &Vec8) -> Vector2<f64> {
        Self::combine(&self.s, e)
    }
    /// Slope r′(x).
    pub fn r1(&self, e: &Vec8) -> Vector2<f64> {
        Self::combine(&self.ds, e)
    }
    /// r″(x).
    pub fn r2(&self, e: &Vec8) -> Vector2<f64> {
        Self::combine(&self.dds, e)
    }
}

/// A rigid body attached to a planar ANCF element's section at ξ (an attached mass with an
/// offset or a rotary inertia, docs/references.md §10): its centre is at p = r + R(φ)o, r = S(ξ)e
/// the centreline point, φ = atan2 of the slope d = S′(ξ)e (the section's angle), o the offset
/// in section axes (along the tangent, along the normal); kinetic energy ½m|ṗ|² + ½Jφ̇².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionMass {
    /// ξ ∈ [0, 1] along the element.
    pub xi: f64,
    /// Mass m [kg].
    pub mass: f64,
    /// Rotary inertia J about its centre [kg m²].
    pub inertia: f64,
    /// Offset o (along the tangent, along the normal) [m].
    pub offset: [f64; 2],
}

impl SectionMass {
    /// (φ̇, φ̈, R(φ)o, R(φ)Jo) of the section with slope d, ḋ, d̈ (J the quarter turn).
    #[inline]
    fn kinematics<T: Real>(&self, d: [T; 2], dd: [T; 2], ddd: [T; 2]) -> (T, T, [T; 2], [T; 2]) {
        let n2 = d[0] * d[0] + d[1] * d[1];
        let cr = d[0] * dd[1] - d[1] * dd[0];
        let dot = d[0] * dd[0] + d[1] * dd[1];
        let phid = cr / n2;
        let phidd = (d[0] * ddd[1] - d[1] * ddd[0]) / n2 - cr * dot * 2.0 / (n2 * n2);
        let nrm = n2.sqrt();
        let t = [d[0] / nrm, d[1] / nrm];
        let nn = [-t[1], t[0]];
        let [o0, o1] = self.offset;
        let ro = [t[0] * o0 + nn[0] * o1, t[1] * o0 + nn[1] * o1];
        let rjo = [nn[0] * o0 - t[0] * o1, nn[1] * o0 - t[1] * o1];
        (phid, phidd, ro, rjo)
    }

    /// The body's inertia and weight as generalized forces on (r, d): F_r = m(p̈ − g),
    /// F_d = (m (R J o)·(p̈ − g) + J φ̈) ∂φ/∂d, ∂φ/∂d = (−d_y, d_x)/|d|², with
    /// p̈ = r̈ + R J o φ̈ − R o φ̇²; at centreline acceleration r̈ and slope d, ḋ, d̈.
    #[inline]
    pub fn forces<T: Real>(
        &self,
        rdd: [T; 2],
        d: [T; 2],
        dd: [T; 2],
        ddd: [T; 2],
        g: [f64; 2],
    ) -> [T; 4] {
        let (phid, phidd, ro, rjo) = self.kinematics(d, dd, ddd);
        let acc = [
            rdd[0] - g[0] + rjo[0] * phidd - ro[0] * phid * phid,
            rdd[1] - g[1] + rjo[1] * phidd - ro[1] * phid * phid,
        ];
        let n2 = d[0] * d[0] + d[1] * d[1];
        let coef = (rjo[0] * acc[0] + rjo[1] * acc[1]) * self.mass + phidd * self.inertia;
        [
            acc[0] * self.mass,
            acc[1] * self.mass,
            -(d[1] * coef) / n2,
            d[0] * coef / n2,
        ]
    }

    /// (kinetic energy ½m|ṗ|² + ½Jφ̇², gravity potential −m gᵀp) [J] at centreline position r,
    /// velocity ṙ and slope d, ḋ.
    pub fn energies(
        &self,
        r: [f64; 2],
        rd: [f64; 2],
        d: [f64; 2],
        dd: [f64; 2],
        g: [f64; 2],
    ) -> (f64, f64) {
        let (phid, _, ro, rjo) = self.kinematics(d, dd, [0.0; 2]);
        let v = [rd[0] + rjo[0] * phid, rd[1] + rjo[1] * phid];
        let p = [r[0] + ro[0], r[1] + ro[1]];
        (
            0.5 * self.mass * (v[0] * v[0] + v[1] * v[1]) + 0.5 * self.inertia * phid * phid,
            -self.mass * (g[0] * p[0] + g[1] * p[1]),
        )
    }
}

/// The section properties of a tapered element at its quadrature points (a segment whose
/// dimensions vary, [`crate::scene::Dim`]): the stiffness integrals use them point by point on
/// the element's own rules (EA on the 5 axial Gauss points, EI on the 3 bending points), the
/// mass matrix and gravity ρA on the 5 points (exact: ρA(x) is at most quadratic in x, the mass
/// integrand of degree 8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionTable {
    /// EA [N] at the [`GAUSS5`] points.
    pub ea: [f64; 5],
    /// EI [N m²] at the [`GAUSS3`] points.
    pub ei: [f64; 3],
    /// ρA [kg/m] at the [`GAUSS5`] points.
    pub rho_a: [f64; 5],
}

impl SectionTable {
    /// The table of an element from arc length `x0` to `x0 + l` [m] of a segment whose EA, EI and
    /// ρA at arc length x [m] from its start are `props(x)` = (EA [N], EI [N m²], ρA [kg/m]).
    pub fn of(x0: f64, l: f64, props: impl Fn(f64) -> (f64, f64, f64)) -> Self {
        let at = |xg: f64| props(x0 + 0.5 * (xg + 1.0) * l);
        Self {
            ea: GAUSS5.map(|(xg, _)| at(xg).0),
            ei: GAUSS3.map(|(xg, _)| at(xg).1),
            rho_a: GAUSS5.map(|(xg, _)| at(xg).2),
        }
    }
}

/// Element properties (constant).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AncfProps {
    /// Element length [m].
    pub length: f64,
    /// Mass per length ρA [kg/m].
    pub rho_a: f64,
    /// Axial stiffness EA [N].
    pub ea: f64,
    /// Bending stiffness EI [N m²].
    pub ei: f64,
    /// Kelvin–Voigt retardation time τ [s] (0 = no damping).
    pub damping_time: f64,
    /// Strain measures.
    pub strain: StrainModel,
    /// The measures of a curved unstressed configuration, subtracted at each quadrature point
    /// (`None`: straight, ε and K count from zero).
    pub reference: Option<AncfReference>,
    /// A tapered element's section properties at its quadrature points (they then replace
    /// `rho_a`, `ea`, `ei`, which hold the values at mid-element); `None`: uniform.
    pub taper: Option<SectionTable>,
}

/// The strain measures of an element's unstressed (curved) configuration at its quadrature
/// points: ε₀ at the 5 axial points and K₀ [1/m] at the 3 bending points, computed from the
/// reference nodal coordinates through the element's own interpolation, so that the
/// reference configuration is exactly stress-free ([`StrainModel::Exact`] only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AncfReference {
    /// ε₀ at the [`GAUSS5`] points [-].
    pub axial: [f64; 5],
    /// K₀ = e₃·(r′×r″)/|r′|² at the [`GAUSS3`] points [1/m].
    pub bending: [f64; 3],
    /// The arc's curvature κ [1/m] (the samples' reference between the points).
    pub kappa: f64,
}

impl AncfReference {
    /// The measures of an element of length `l` [m] whose nodes lie on an arc of curvature
    /// `kappa` [1/m] (positive: counter-clockwise) with unit tangent slopes ([`arc`]); they
    /// are invariant under rigid motions, so one table serves every element of a segment.
    pub fn arc(l: f64, kappa: f64) -> Self {
        let e = arc([0.0, 0.0], 0.0, l, kappa);
        let mut r = Self {
            axial: [0.0; 5],
            bending: [0.0; 3],
            kappa,
        };
        for (k, (xg, _)) in GAUSS5.iter().enumerate() {
            r.axial[k] = Shape::at(0.5 * (xg + 1.0), l).r1(&e).norm() - 1.0;
        }
        for (k, (xg, _)) in GAUSS3.iter().enumerate() {
            let sh = Shape::at(0.5 * (xg + 1.0), l);
            let (r1, r2) = (sh.r1(&e), sh.r2(&e));
            r.bending[k] = cross(&r1, &r2) / r1.norm_squared();
        }
        r
    }
}

/// Quadrature weights (times EA or EI and the Jacobian l/2) and shape derivatives of an
/// element, for the residual path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadTables {
    /// Axial points: (w·EA, ds/dx).
    pub axial: [(f64, Lanes); 5],
    /// Bending points: (w·EI, ds/dx, d²s/dx²).
    pub bending: [(f64, Lanes, Lanes); 3],
}

/// Four shape-function values, each twice: the x and y lanes of the coordinate pairs they
/// weight (pairs of f64 the compiler keeps in one SIMD register, no broadcast per use).
pub type Lanes = [[f64; 2]; 4];

/// The values of `s` in both lanes.
fn lanes(s: [f64; 4]) -> Lanes {
    s.map(|v| [v, v])
}

/// The values of `l` (its first lane).
#[inline(always)]
fn first(l: &Lanes) -> [f64; 4] {
    l.map(|p| p[0])
}

/// Forces and matrices of one element at one state.
#[derive(Debug, Clone)]
pub struct ElasticOut {
    /// Internal (elastic + damping) generalized force, positive = resisting [N].
    pub force: Vec8,
    /// ∂force/∂e.
    pub stiffness: Mat8,
    /// ∂force/∂ė (zero without damping).
    pub damping: Mat8,
}

/// Row-major 8×8 element block.
pub type Block8 = [[f64; 8]; 8];

/// 2×2 block, row-major.
type Block2 = [[f64; 2]; 2];

const I2: Block2 = [[1.0, 0.0], [0.0, 1.0]];

/// Kronecker expansion of a 4×4 scalar pattern with a 2×2 block:
/// `out[2k + i][2l + j] += (scale·pattern[k][l])·block[i][j]` (a zero coefficient adds ±0).
#[inline(always)]
fn expand(pattern: &[[f64; 4]; 4], block: &Block2, out: &mut Block8, scale: f64) {
    for k in 0..4 {
        for i in 0..2 {
            let row = &mut out[2 * k + i];
            for l in 0..4 {
                let c = scale * pattern[k][l];
                for j in 0..2 {
                    row[2 * l + j] += c * block[i][j];
                }
            }
        }
    }
}

/// `out[i][j] += (s·u_i)·v_j`.
#[inline(always)]
fn add_outer(out: &mut Block8, s: f64, u: &[f64; 8], v: &[f64; 8]) {
    for i in 0..8 {
        let su = s * u[i];
        for j in 0..8 {
            out[i][j] += su * v[j];
        }
    }
}

/// `h·x`, summed left to right over the columns.
#[inline(always)]
fn mat_vec(h: &Block8, x: &[f64; 8]) -> [f64; 8] {
    h.map(|row| {
        let mut s = row[0] * x[0];
        for j in 1..8 {
            s += row[j] * x[j];
        }
        s
    })
}

/// `Σ_k w_k x_{2k + c}` for c = 0, 1 (from zero, left to right).
#[inline(always)]
fn comb(w: &[f64; 4], x: &[f64; 8]) -> [f64; 2] {
    let mut r = [0.0; 2];
    for k in 0..4 {
        r[0] += w[k] * x[2 * k];
        r[1] += w[k] * x[2 * k + 1];
    }
    r
}

/// [`comb`] with the weights in lanes.
#[inline(always)]
fn comb_lanes(w: &Lanes, x: &[f64; 8]) -> [f64; 2] {
    let mut r = [0.0; 2];
    for k in 0..4 {
        for c in 0..2 {
            r[c] += w[k][c] * x[2 * k + c];
        }
    }
    r
}

/// The 8-vector `[ds_k v_c]` (k = 0..4, c = 0, 1).
#[inline(always)]
fn spread(ds: &[f64; 4], v: [f64; 2]) -> [f64; 8] {
    let mut o = [0.0; 8];
    for k in 0..4 {
        o[2 * k] = ds[k] * v[0];
        o[2 * k + 1] = ds[k] * v[1];
    }
    o
}

/// `a·b` in nalgebra's order for an 8-vector (the full kernel's ε̇ and K̇).
#[inline(always)]
fn dot8(a: &[f64; 8], b: &[f64; 8]) -> f64 {
    Vec8::from(*a).dot(&Vec8::from(*b))
}

/// The 4×4 pattern a bᵀ.
#[inline(always)]
fn outer4(a: &[f64; 4], b: &[f64; 4]) -> [[f64; 4]; 4] {
    a.map(|ak| b.map(|bl| ak * bl))
}

/// A row-major block as a matrix.
fn to_mat8(b: &Block8) -> Mat8 {
    Mat8::from_fn(|r, c| b[r][c])
}

impl AncfProps {
    /// Consistent mass matrix (paper eq. 7), constant [kg, kg m, kg m²].
    pub fn mass_matrix(&self) -> Mat8 {
        let l = self.length;
        if let Some(t) = &self.taper {
            // ∫ρA(x) S_j S_k dx on 5 Gauss points (exact for ρA quadratic in x)
            let mut p = [[0.0; 4]; 4];
            for ((xg, wg), ra) in GAUSS5.iter().zip(t.rho_a) {
                let sh = Shape::at(0.5 * (xg + 1.0), l);
                for j in 0..4 {
                    for k in 0..4 {
                        p[j][k] += wg * 0.5 * l * ra * sh.s[j] * sh.s[k];
                    }
                }
            }
            let mut m = [[0.0; 8]; 8];
            expand(&p, &I2, &mut m, 1.0);
            return to_mat8(&m);
        }
        let c = self.rho_a * l / 420.0;
        let p = [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ];
        let mut m = [[0.0; 8]; 8];
        expand(&p, &I2, &mut m, c);
        to_mat8(&m)
    }

    /// Generalized gravity force ∫ρA Sᵀ g dx (paper eq. 8) [N, N m].
    pub fn gravity_force(&self, g: [f64; 2]) -> Vec8 {
        let l = self.length;
        let mut f = Vec8::zeros();
        if let Some(t) = &self.taper {
            for ((xg, wg), ra) in GAUSS5.iter().zip(t.rho_a) {
                let sh = Shape::at(0.5 * (xg + 1.0), l);
                for k in 0..4 {
                    let c = wg * 0.5 * l * ra * sh.s[k];
                    f[2 * k] += c * g[0];
                    f[2 * k + 1] += c * g[1];
                }
            }
            return f;
        }
        let w = [0.5, l / 12.0, 0.5, -l / 12.0];
        for k in 0..4 {
            f[2 * k] = self.rho_a * l * w[k] * g[0];
            f[2 * k + 1] = self.rho_a * l * w[k] * g[1];
        }
        f
    }

    /// Generalized force ∫Sᵀ q dx of a uniform load `q` per unit length [N/m] (independent of
    /// the section) [N, N m].
    pub fn line_force(&self, q: [f64; 2]) -> Vec8 {
        let l = self.length;
        let w = [0.5, l / 12.0, 0.5, -l / 12.0];
        let mut f = Vec8::zeros();
        for k in 0..4 {
            f[2 * k] = l * w[k] * q[0];
            f[2 * k + 1] = l * w[k] * q[1];
        }
        f
    }

    /// EA [N] at axial Gauss point `k`.
    #[inline]
    fn ea_at(&self, k: usize) -> f64 {
        self.taper.as_ref().map_or(self.ea, |t| t.ea[k])
    }

    /// EI [N m²] at bending Gauss point `k`.
    #[inline]
    fn ei_at(&self, k: usize) -> f64 {
        self.taper.as_ref().map_or(self.ei, |t| t.ei[k])
    }

    /// Strain energy [J].
    pub fn strain_energy(&self, e: &Vec8) -> f64 {
        let l = self.length;
        let mut u = 0.0;
        for (q, (xg, wg)) in GAUSS5.into_iter().enumerate() {
            let sh = Shape::at(0.5 * (xg + 1.0), l);
            let r1 = sh.r1(e);
            let mut eps = match self.strain {
                StrainModel::Exact => r1.norm() - 1.0,
                StrainModel::Paper => 0.5 * (r1.norm_squared() - 1.0),
            };
            if let Some(r) = &self.reference {
                eps -= r.axial[q];
            }
            u += 0.5 * wg * 0.5 * l * self.ea_at(q) * eps * eps;
        }
        for (q, (xg, wg)) in GAUSS3.into_iter().enumerate() {
            let sh = Shape::at(0.5 * (xg + 1.0), l);
            let (r1, r2) = (sh.r1(e), sh.r2(e));
            let k2 = match self.strain {
                StrainModel::Exact => {
                    let mut k = cross(&r1, &r2) / r1.norm_squared();
                    if let Some(r) = &self.reference {
                        k -= r.bending[q];
                    }
                    k * k
                }
                StrainModel::Paper => r2.norm_squared(),
            };
            u += 0.5 * wg * 0.5 * l * self.ei_at(q) * k2;
        }
        u
    }

    /// The centreline at ξ ∈ [0, 1] of the element at `e`, `ed`: r = S e, ṙ = S ė, the section
    /// frame of the tangent and the element's own strain measures (the module doc: exact ε =
    /// |r′| − 1, K = e₃·(r′×r″)/|r′|²; paper ε = ½(r′ᵀr′ − 1), K = ±|r″| signed as r′×r″).
    pub fn sample(&self, e: &Vec8, ed: &Vec8, xi: f64) -> ShapePoint {
        let sh = Shape::at(xi, self.length);
        let (r, r1, r2, v) = (sh.r(e), sh.r1(e), sh.r2(e), sh.r(ed));
        let (eps, k) = match self.strain {
            StrainModel::Exact => match &self.reference {
                None => (r1.norm() - 1.0, cross(&r1, &r2) / r1.norm_squared()),
                Some(_) => {
                    // the arc's own measures at ξ through the same interpolation
                    let e0 = arc(
                        [0.0, 0.0],
                        0.0,
                        self.length,
                        self.reference.map_or(0.0, |r| r.kappa),
                    );
                    let (a0, b0) = (sh.r1(&e0), sh.r2(&e0));
                    (
                        r1.norm() - a0.norm(),
                        cross(&r1, &r2) / r1.norm_squared() - cross(&a0, &b0) / a0.norm_squared(),
                    )
                }
            },
            StrainModel::Paper => (
                0.5 * (r1.norm_squared() - 1.0),
                r2.norm().copysign(cross(&r1, &r2)),
            ),
        };
        let t = r1.normalize();
        ShapePoint {
            position: [r.x, r.y, 0.0],
            velocity: [v.x, v.y, 0.0],
            frame: [[t.x, t.y, 0.0], [-t.y, t.x, 0.0], [0.0, 0.0, 1.0]],
            axial_strain: eps,
            curvature: [0.0, k],
            ..ShapePoint::default()
        }
    }

    /// Weighted shape-function derivatives at the quadrature points, computed once per
    /// element length (the residual path then does no division by l).
    pub fn tables(&self) -> QuadTables {
        let l = self.length;
        let mut t = QuadTables {
            axial: [(0.0, [[0.0; 2]; 4]); 5],
            bending: [(0.0, [[0.0; 2]; 4], [[0.0; 2]; 4]); 3],
        };
        for (k, (xg, wg)) in GAUSS5.iter().enumerate() {
            let sh = Shape::at(0.5 * (xg + 1.0), l);
            t.axial[k] = (wg * 0.5 * l * self.ea_at(k), lanes(sh.ds));
        }
        for (k, (xg, wg)) in GAUSS3.iter().enumerate() {
            let sh = Shape::at(0.5 * (xg + 1.0), l);
            t.bending[k] = (wg * 0.5 * l * self.ei_at(k), lanes(sh.ds), lanes(sh.dds));
        }
        t
    }

    /// Internal (elastic + damping) force only: the residual path, without matrices. Same
    /// quadrature and strain measures as [`AncfProps::elastic`].
    pub fn internal_force(&self, e: &[f64; 8], ed: &[f64; 8]) -> [f64; 8] {
        self.internal_force_with(&self.tables(), e, ed)
    }

    /// [`AncfProps::internal_force`] with precomputed tables.
    pub fn internal_force_with(&self, tab: &QuadTables, e: &[f64; 8], ed: &[f64; 8]) -> [f64; 8] {
        match (self.strain, self.damping_time > 0.0) {
            (StrainModel::Exact, false) => self.force_kernel::<true, false>(tab, e, ed),
            (StrainModel::Exact, true) => self.force_kernel::<true, true>(tab, e, ed),
            (StrainModel::Paper, false) => self.force_kernel::<false, false>(tab, e, ed),
            (StrainModel::Paper, true) => self.force_kernel::<false, true>(tab, e, ed),
        }
    }

    /// [`AncfProps::internal_force_with`] for exact (`EXACT`) or paper strains, with or
    /// without damping: the branches resolved outside the quadrature loops. r′ at the middle
    /// bending point is that of the middle axial point (both at ξ = ½).
    #[inline(always)]
    fn force_kernel<const EXACT: bool, const DAMPED: bool>(
        &self,
        tab: &QuadTables,
        e: &[f64; 8],
        ed: &[f64; 8],
    ) -> [f64; 8] {
        debug_assert_eq!(tab.axial[2].1, tab.bending[1].1);
        let tau = self.damping_time;
        let (ref_a, ref_b) = self.reference_measures();
        // r′ at the 5 axial and 3 bending points (the middle one shared), r″ at the bending
        // points; then every square root and reciprocal at once (independent, in pairs)
        let mut r1 = [[0.0; 2]; 8];
        for (q, (_, ds)) in tab.axial.iter().enumerate() {
            r1[q] = comb_lanes(ds, e);
        }
        r1[5] = comb_lanes(&tab.bending[0].1, e);
        r1[6] = r1[2];
        r1[7] = comb_lanes(&tab.bending[2].1, e);
        let sq = r1.map(|r| r[0] * r[0] + r[1] * r[1]);
        let mut den = sq;
        if EXACT {
            for d in &mut den[..5] {
                *d = d.sqrt();
            }
        }
        let inv = den.map(|d| 1.0 / d);
        let mut f = [0.0; 8];
        for (q, (w, ds)) in tab.axial.iter().enumerate() {
            let r1 = r1[q];
            // stress (per EA) and dε/dr′
            let (eps, g) = if EXACT {
                (den[q] - 1.0, [r1[0] * inv[q], r1[1] * inv[q]])
            } else {
                (0.5 * (sq[q] - 1.0), r1)
            };
            let mut stress = eps - ref_a[q];
            if DAMPED {
                let r1d = comb_lanes(ds, ed);
                stress += tau * (g[0] * r1d[0] + g[1] * r1d[1]);
            }
            let c = w * stress;
            for k in 0..4 {
                for j in 0..2 {
                    f[2 * k + j] += c * ds[k][j] * g[j];
                }
            }
        }
        for (q, (w, ds, dds)) in tab.bending.iter().enumerate() {
            let r2 = comb_lanes(dds, e);
            if !EXACT {
                let mut m = r2;
                if DAMPED {
                    let r2d = comb_lanes(dds, ed);
                    m[0] += tau * r2d[0];
                    m[1] += tau * r2d[1];
                }
                for k in 0..4 {
                    for j in 0..2 {
                        f[2 * k + j] += w * dds[k][j] * m[j];
                    }
                }
                continue;
            }
            let (r1, inv) = (r1[5 + q], inv[5 + q]);
            let kappa = (r1[0] * r2[1] - r1[1] * r2[0]) * inv;
            let dk1 = [
                (r2[1] - 2.0 * kappa * r1[0]) * inv,
                (-r2[0] - 2.0 * kappa * r1[1]) * inv,
            ];
            let dk2 = [-r1[1] * inv, r1[0] * inv];
            let mut moment = kappa - ref_b[q];
            if DAMPED {
                let r1d = comb_lanes(ds, ed);
                let r2d = comb_lanes(dds, ed);
                moment +=
                    tau * (dk1[0] * r1d[0] + dk1[1] * r1d[1] + dk2[0] * r2d[0] + dk2[1] * r2d[1]);
            }
            let c = w * moment;
            for k in 0..4 {
                for j in 0..2 {
                    f[2 * k + j] += c * (ds[k][j] * dk1[j] + dds[k][j] * dk2[j]);
                }
            }
        }
        f
    }

    /// (ε₀, K₀) at the axial and bending points: the reference's, zero when straight
    /// (subtracting zero is exact).
    #[inline(always)]
    fn reference_measures(&self) -> ([f64; 5], [f64; 3]) {
        self.reference
            .map_or(([0.0; 5], [0.0; 3]), |r| (r.axial, r.bending))
    }

    /// Internal force, tangent stiffness and damping matrix at (e, ė).
    pub fn elastic(&self, e: &Vec8, ed: &Vec8, with_matrices: bool) -> ElasticOut {
        let (mut f, mut k, mut d) = ([0.0; 8], [[0.0; 8]; 8], [[0.0; 8]; 8]);
        let matrices = with_matrices.then_some((&mut k, &mut d));
        self.elastic_into(
            &self.tables(),
            &(*e).into(),
            &(*ed).into(),
            &mut f,
            matrices,
        );
        ElasticOut {
            force: Vec8::from(f),
            stiffness: to_mat8(&k),
            damping: to_mat8(&d),
        }
    }

    /// [`AncfProps::elastic`] with precomputed tables on arrays: the force added to `force`
    /// and, with `matrices`, ∂f/∂e and ∂f/∂ė added to the two row-major blocks.
    pub fn elastic_into(
        &self,
        tab: &QuadTables,
        e: &[f64; 8],
        ed: &[f64; 8],
        force: &mut [f64; 8],
        mut matrices: Option<(&mut Block8, &mut Block8)>,
    ) {
        let tau = self.damping_time;
        let damped = tau > 0.0;
        let (ref_a, ref_b) = self.reference_measures();
        // Axial part.
        for (q, (w, ds)) in tab.axial.iter().enumerate() {
            let (w, ds) = (*w, &first(ds));
            let r1 = comb(ds, e);
            let nn = r1[0] * r1[0] + r1[1] * r1[1];
            // ε, dε/dr′ (2-vector), d²ε/dr′² (2×2)
            let (eps, g, h) = match self.strain {
                StrainModel::Exact => {
                    let n = nn.sqrt();
                    let t = [r1[0] / n, r1[1] / n];
                    let h = [0, 1].map(|i| [0, 1].map(|j| (I2[i][j] - t[i] * t[j]) / n));
                    (n - 1.0, t, h)
                }
                StrainModel::Paper => (0.5 * (nn - 1.0), r1, I2),
            };
            let de = spread(ds, g); // dε/de
            let eps_dot = if damped { dot8(&de, ed) } else { 0.0 };
            let stress = eps + tau * eps_dot - ref_a[q];
            let ws = w * stress;
            for (f, d) in force.iter_mut().zip(de) {
                *f += ws * d;
            }
            if let Some((k, d)) = matrices.as_mut() {
                let pat = outer4(ds, ds);
                // w dε/de dε/deᵀ, then σ d²ε/de² (pattern ⊗ h), added in that order
                for a in 0..4 {
                    for i in 0..2 {
                        let (row, wde) = (&mut k[2 * a + i], w * de[2 * a + i]);
                        for b in 0..4 {
                            let cp = ws * pat[a][b];
                            for j in 0..2 {
                                let c = 2 * b + j;
                                row[c] = row[c] + wde * de[c] + cp * h[i][j];
                            }
                        }
                    }
                }
                if damped {
                    add_outer(d, w * tau, &de, &de);
                    // ∂ε̇/∂e = d²ε/de² ė
                    let mut hed = [[0.0; 8]; 8];
                    expand(&pat, &h, &mut hed, 1.0);
                    add_outer(k, w * tau, &de, &mat_vec(&hed, ed));
                }
            }
        }
        // Bending part.
        for (q, (w, ds, dds)) in tab.bending.iter().enumerate() {
            let (w, ds, dds) = (*w, &first(ds), &first(dds));
            match self.strain {
                StrainModel::Paper => {
                    let (r2, r2d) = (comb(dds, e), comb(dds, ed));
                    let m = [r2[0] + tau * r2d[0], r2[1] + tau * r2d[1]];
                    for k in 0..4 {
                        force[2 * k] += w * dds[k] * m[0];
                        force[2 * k + 1] += w * dds[k] * m[1];
                    }
                    if let Some((k, d)) = matrices.as_mut() {
                        let pat = outer4(dds, dds);
                        expand(&pat, &I2, k, w);
                        if damped {
                            expand(&pat, &I2, d, w * tau);
                        }
                    }
                }
                StrainModel::Exact => {
                    let (r1, r2) = (comb(ds, e), comb(dds, e));
                    let gg = r1[0] * r1[0] + r1[1] * r1[1];
                    let c = r1[0] * r2[1] - r1[1] * r2[0];
                    let kappa = c / gg;
                    // ∂c/∂r′ = (r2y, −r2x), ∂c/∂r″ = (−r1y, r1x)
                    let c1 = [r2[1], -r2[0]];
                    let c2 = [-r1[1], r1[0]];
                    let s = 2.0 * kappa / gg;
                    let dk1 = [c1[0] / gg - s * r1[0], c1[1] / gg - s * r1[1]]; // ∂K/∂r′
                    let dk2 = [c2[0] / gg, c2[1] / gg]; // ∂K/∂r″
                    let mut dk = [0.0; 8];
                    for k in 0..4 {
                        dk[2 * k] = ds[k] * dk1[0] + dds[k] * dk2[0];
                        dk[2 * k + 1] = ds[k] * dk1[1] + dds[k] * dk2[1];
                    }
                    let k_dot = if damped { dot8(&dk, ed) } else { 0.0 };
                    let moment = kappa + tau * k_dot - ref_b[q];
                    let wm = w * moment;
                    for (f, d) in force.iter_mut().zip(dk) {
                        *f += wm * d;
                    }
                    if let Some((k, d)) = matrices.as_mut() {
                        // Hessian of K in (r′, r″): blocks H11, H12, H21 (H22 = 0).
                        let dg = [2.0 * r1[0], 2.0 * r1[1]];
                        let g2 = gg * gg;
                        let (s1, s2) = (2.0 * c / g2, 2.0 * c / (g2 * gg));
                        let jt = [[0.0, 1.0], [-1.0, 0.0]]; // ∂c1/∂r″
                        let h11 = [0, 1].map(|i| {
                            [0, 1].map(|j| {
                                -(c1[i] * dg[j] + dg[i] * c1[j]) / g2 - s1 * I2[i][j]
                                    + s2 * dg[i] * dg[j]
                            })
                        });
                        let h12 =
                            [0, 1].map(|i| [0, 1].map(|j| jt[i][j] / gg - dg[i] * c2[j] / g2));
                        let h21 = [0, 1].map(|i| [0, 1].map(|j| h12[j][i]));
                        // d²K/de² = ds⊗ds ⊗ H11 + ds⊗dds ⊗ H12 + dds⊗ds ⊗ H21; K += w dK dKᵀ + wM d²K
                        let mut hk = [[0.0; 8]; 8];
                        for a in 0..4 {
                            for i in 0..2 {
                                let r = 2 * a + i;
                                let wdk = w * dk[r];
                                for b in 0..4 {
                                    let c11 = ds[a] * ds[b];
                                    let (c12, c21) = (ds[a] * dds[b], dds[a] * ds[b]);
                                    for j in 0..2 {
                                        let c = 2 * b + j;
                                        let hv =
                                            c11 * h11[i][j] + c12 * h12[i][j] + c21 * h21[i][j];
                                        hk[r][c] = hv;
                                        k[r][c] += wdk * dk[c] + wm * hv;
                                    }
                                }
                            }
                        }
                        if damped {
                            add_outer(d, w * tau, &dk, &dk);
                            add_outer(k, w * tau, &dk, &mat_vec(&hk, ed));
                        }
                    }
                }
            }
        }
    }
}

/// z-component of the planar cross product a × b.
pub fn cross(a: &Vector2<f64>, b: &Vector2<f64>) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Coordinates of an element of arc length `l` [m] on the arc from `p0` [m] with start tangent
/// angle `angle` [rad] and curvature `kappa` [1/m] (positive: counter-clockwise): nodal
/// positions on the arc, slopes its unit tangents; [`straight`] for κ = 0.
pub fn arc(p0: [f64; 2], angle: f64, l: f64, kappa: f64) -> Vec8 {
    if kappa == 0.0 {
        return straight(p0, angle, l);
    }
    let (p1, a1) = arc_end(p0, angle, l, kappa);
    let (s0, c0) = math::sin_cos(angle);
    let (s1, c1) = math::sin_cos(a1);
    Vec8::from_column_slice(&[p0[0], p0[1], c0, s0, p1[0], p1[1], c1, s1])
}

/// The end (position [m], tangent angle [rad]) of an arc of length `s` [m] from `p0` at
/// tangent angle `angle` with curvature `kappa` [1/m] (positive: counter-clockwise):
/// p = p0 + (sin φ₁ − sin φ₀, cos φ₀ − cos φ₁)/κ, φ₁ = φ₀ + κs, written as the chord
/// s·sin(h)/h along the mid angle φ₀ + h, h = κs/2, so that a small κ loses no digits (a
/// straight line for κ = 0).
pub fn arc_end(p0: [f64; 2], angle: f64, s: f64, kappa: f64) -> ([f64; 2], f64) {
    if kappa == 0.0 {
        let (s0, c0) = math::sin_cos(angle);
        return ([p0[0] + s * c0, p0[1] + s * s0], angle);
    }
    let h = 0.5 * kappa * s;
    let chord = if h == 0.0 { s } else { s * math::sin(h) / h };
    let (sm, cm) = math::sin_cos(angle + h);
    ([p0[0] + chord * cm, p0[1] + chord * sm], angle + kappa * s)
}

/// Coordinates of a straight, unstretched element from `p0` along `angle`.
pub fn straight(p0: [f64; 2], angle: f64, l: f64) -> Vec8 {
    let (s, c) = math::sin_cos(angle);
    Vec8::from_column_slice(&[p0[0], p0[1], c, s, p0[0] + l * c, p0[1] + l * s, c, s])
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A short stiff element (the element tests' and those of the higher degrees).
    pub(crate) fn props(strain: StrainModel, tau: f64) -> AncfProps {
        AncfProps {
            length: 0.05,
            rho_a: 0.0247,
            ea: 6.6e5,
            ei: 0.165,
            damping_time: tau,
            strain,
            reference: None,
            taper: None,
        }
    }

    fn state() -> (Vec8, Vec8) {
        let e = Vec8::from_column_slice(&[0.01, -0.02, 0.9, 0.3, 0.055, 0.01, 0.7, 0.75]);
        let ed = Vec8::from_column_slice(&[0.1, -0.3, 0.5, 0.2, -0.4, 0.6, 0.3, -0.2]);
        (e, ed)
    }

    #[test]
    fn tangent_matches_central_differences() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            for tau in [0.0, 1e-3] {
                let p = props(strain, tau);
                let (e, ed) = state();
                let o = p.elastic(&e, &ed, true);
                let h = 1e-7;
                let scale = o.stiffness.abs().max();
                for j in 0..8 {
                    let (mut ep, mut em) = (e, e);
                    ep[j] += h;
                    em[j] -= h;
                    let fd = (p.elastic(&ep, &ed, false).force - p.elastic(&em, &ed, false).force)
                        / (2.0 * h);
                    for i in 0..8 {
                        let err = (fd[i] - o.stiffness[(i, j)]).abs();
                        assert!(
                            err <= 1e-6 * scale,
                            "{strain:?} tau {tau} K[{i},{j}]: {err:e}"
                        );
                    }
                    let (mut vp, mut vm) = (ed, ed);
                    vp[j] += h;
                    vm[j] -= h;
                    let fd = (p.elastic(&e, &vp, false).force - p.elastic(&e, &vm, false).force)
                        / (2.0 * h);
                    for i in 0..8 {
                        let err = (fd[i] - o.damping[(i, j)]).abs();
                        assert!(
                            err <= 1e-6 * scale.max(1.0) * tau.max(1e-12) + 1e-12,
                            "C[{i},{j}]"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn residual_path_equals_the_full_kernel() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            for tau in [0.0, 1e-3] {
                let p = props(strain, tau);
                let (e, ed) = state();
                let full = p.elastic(&e, &ed, false).force;
                let fast = p.internal_force(&e.into(), &ed.into());
                for k in 0..8 {
                    assert!(
                        (full[k] - fast[k]).abs() <= 1e-12 * full.amax(),
                        "{strain:?} {tau} {k}"
                    );
                }
            }
        }
    }

    /// The viewer's samples carry the element's own measures: the energy density integrated by
    /// the element's own quadrature is its strain energy.
    #[test]
    fn samples_integrate_to_the_strain_energy() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            let p = props(strain, 0.0);
            let (e, ed) = state();
            let mut u = 0.0;
            for (xg, wg) in GAUSS5 {
                let s = p.sample(&e, &ed, 0.5 * (xg + 1.0));
                u += 0.5 * wg * 0.5 * p.length * p.ea * s.axial_strain * s.axial_strain;
            }
            for (xg, wg) in GAUSS3 {
                let s = p.sample(&e, &ed, 0.5 * (xg + 1.0));
                u += 0.5 * wg * 0.5 * p.length * p.ei * s.curvature[1] * s.curvature[1];
            }
            let want = p.strain_energy(&e);
            assert!((u - want).abs() < 1e-12 * want, "{strain:?}: {u} vs {want}");
        }
    }

    #[test]
    fn force_is_gradient_of_energy() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            let p = props(strain, 0.0);
            let (e, _) = state();
            let f = p.elastic(&e, &Vec8::zeros(), false).force;
            let h = 1e-7;
            for j in 0..8 {
                let (mut ep, mut em) = (e, e);
                ep[j] += h;
                em[j] -= h;
                let fd = (p.strain_energy(&ep) - p.strain_energy(&em)) / (2.0 * h);
                assert!((fd - f[j]).abs() <= 1e-6 * f.abs().max(), "{strain:?} {j}");
            }
        }
    }

    #[test]
    fn mass_and_gravity_match_closed_form() {
        // Independent check: integrate ρA SᵀS and ρA Sᵀ by 5-point Gauss (exact for degree 6).
        let p = props(StrainModel::Exact, 0.0);
        let l = p.length;
        let m = p.mass_matrix();
        let q = p.gravity_force([0.3, -9.81]);
        let mut mi = [[0.0; 4]; 4];
        let mut qi = [0.0; 4];
        for (xg, wg) in GAUSS5 {
            let s = Shape::at(0.5 * (xg + 1.0), l).s;
            for k in 0..4 {
                qi[k] += wg * 0.5 * l * p.rho_a * s[k];
                for j in 0..4 {
                    mi[k][j] += wg * 0.5 * l * p.rho_a * s[k] * s[j];
                }
            }
        }
        for k in 0..4 {
            assert!((q[2 * k] - qi[k] * 0.3).abs() < 1e-15);
            assert!((q[2 * k + 1] + qi[k] * 9.81).abs() < 1e-14);
            for j in 0..4 {
                assert!((m[(2 * k, 2 * j)] - mi[k][j]).abs() < 1e-15);
                assert!((m[(2 * k + 1, 2 * j + 1)] - mi[k][j]).abs() < 1e-15);
                assert_eq!(m[(2 * k, 2 * j + 1)], 0.0);
            }
        }
        // total mass: 1ᵀ M 1 over translation = ρA l
        let mut tot = 0.0;
        for k in [0, 2] {
            for j in [0, 2] {
                tot += mi[k][j];
            }
        }
        assert!((tot - p.rho_a * l).abs() < 1e-15);
    }

    #[test]
    fn rigid_motion_gives_zero_force() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            let p = props(strain, 1e-3);
            for angle in [0.0, 0.7, -2.5, 3.0] {
                let e = straight([0.3, -0.1], angle, p.length);
                // rigid rotation rate ω about the first node
                let w = 2.0;
                let (s, c) = (angle.sin(), angle.cos());
                let l = p.length;
                let ed = Vec8::from_column_slice(&[
                    0.0,
                    0.0,
                    -w * s,
                    w * c,
                    -w * l * s,
                    w * l * c,
                    -w * s,
                    w * c,
                ]);
                let o = p.elastic(&e, &ed, false);
                // relative to the axial stiffness: round-off of ε is ~1e-16
                assert!(
                    o.force.abs().max() < 1e-14 * p.ea,
                    "{strain:?} {angle} {}",
                    o.force
                );
                assert!(p.strain_energy(&e) < 1e-20);
            }
        }
    }
}
