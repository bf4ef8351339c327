//! The ANCF cable elements of degree p > 3 (a segment's `degree`, docs/elements.md): the cubic
//! Hermite interpolation of the nodes [r, r′] plus hierarchic C¹ bubbles, each with one vector
//! amplitude that is an element-internal coordinate. Dimension-free: the shape functions, the
//! Gauss rules, an element's quadrature tables, its mass pattern and load weights, the scatter
//! of a quadrature point's local forces and Jacobians onto the element coordinates, and what a
//! kernel answers ([`PKernel`]); the planar ([`super::ancf_p`]) and spatial
//! ([`super::ancf3d::cable_p`]) kernels supply the strain measures, [`super::element_p`] the
//! component.
//!
//! Coordinates of an element of `n = p + 1` shapes in DIM dimensions: `e = [r0, r0′, r1, r1′,
//! a_4, …, a_p]`, shape j at `e[DIM·j..DIM·j + DIM]`, and `r(x) = Σ_j S_j(ξ) e_j`, ξ = x/l: the
//! Hermite functions of [`super::ancf::Shape`] for j < 4 and the bubble b_k for the amplitude
//! a_k (k = j). The nodes are those of the cubic element, so supports, joints, ports and
//! outputs see no difference.
//!
//! Bubbles (docs/references.md §14): b_k(ξ) = ψ_{k−1}(t)/(2(2k − 3)), t = 2ξ − 1, with the
//! twice-integrated Legendre polynomials ψ_j(t) = ∫_{−1}^t (P_j − P_{j−2}) ds (Szabó & Babuška,
//! *Finite Element Analysis*, 1991: the hierarchic C¹ shape functions of the p-version beam),
//! so that b_k and b_k′ vanish at both ends and b_k″(ξ) = 2 P_{k−2}(t): the bubbles' second
//! derivatives are orthogonal to each other and to the cubic's (of degree 1), which keeps the
//! bending stiffness of the straight beam diagonal in the bubbles (conditioning). b_4 = ξ²(1 − ξ)².
//!
//! Quadrature (Gauss–Legendre, [`rule`]): p + 1 points for the axial part and p for bending,
//! one more each than the rules exact for the straight beam's (linearized) energies, whose
//! integrands are of degree 2p − 2 (ε ≈ t·r′) and 2p − 4 (r″) — the cubic element
//! ([`super::ancf`]) takes 5 and 3. Measured (tests/element_degree.rs, docs/elements.md): the
//! extra bending point halves to quarters the elastica's error at fine meshes, a second extra
//! axial point changes nothing. The mass matrix, the load weights and a partial element's loads
//! on p + 1 points (exact for the products of two shapes, of degree 2p).

use super::sample::ShapePoint;
use crate::math;

/// The highest element degree (the scene's limit).
pub const MAX_DEGREE: usize = crate::scene::MAX_DEGREE;
/// The most shape functions of an element (p + 1).
pub const MAX_SHAPES: usize = MAX_DEGREE + 1;
/// The most Gauss points of a rule (the axial rule of the highest degree, with room for one
/// more).
pub const MAX_POINTS: usize = MAX_DEGREE + 2;
/// The most coordinates of an element (3 dimensions, [`MAX_SHAPES`] vectors).
pub const MAX_DOFS: usize = 3 * MAX_SHAPES;
/// An element's coordinates, forces (the first DIM·(p + 1) used).
pub type PVec = [f64; MAX_DOFS];
/// An element matrix (the leading DIM·(p + 1) square used).
pub type PMat = [[f64; MAX_DOFS]; MAX_DOFS];

/// P_0(t) … P_m(t) (Legendre polynomials by Bonnet's recurrence), m ≤ [`MAX_DEGREE`].
pub fn legendre(t: f64, m: usize) -> [f64; MAX_DEGREE + 1] {
    let mut p = [0.0; MAX_DEGREE + 1];
    p[0] = 1.0;
    if m >= 1 {
        p[1] = t;
    }
    for k in 1..m {
        let kf = k as f64;
        p[k + 1] = ((2.0 * kf + 1.0) * t * p[k] - kf * p[k - 1]) / (kf + 1.0);
    }
    p
}

/// A Gauss–Legendre rule on [−1, 1]: `n` points (abscissa, weight).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rule {
    /// Number of points.
    pub n: usize,
    /// (abscissa, weight), the first `n` used.
    pub points: [(f64, f64); MAX_POINTS],
}

impl Rule {
    /// The points in use.
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points[..self.n]
    }
}

/// The `n`-point Gauss–Legendre rule (1 ≤ n ≤ [`MAX_POINTS`]): the roots of P_n by Newton's
/// method from the usual cosine guesses, weights 2/((1 − t²) P_n′(t)²), the two halves mirrored
/// (so the rule is exactly symmetric).
pub fn rule(n: usize) -> Rule {
    assert!((1..=MAX_POINTS).contains(&n), "Gauss rule of {n} points");
    let mut points = [(0.0, 0.0); MAX_POINTS];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut t = math::cos(std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5));
        let slope = |t: f64| {
            let (p, pm) = legendre_with(t, n);
            (p, nf * (t * p - pm) / (t * t - 1.0))
        };
        for _ in 0..100 {
            let (p, dp) = slope(t);
            let dt = p / dp;
            t -= dt;
            if dt.abs() <= 1e-16 {
                break;
            }
        }
        let dp = slope(t).1;
        let w = 2.0 / ((1.0 - t * t) * dp * dp);
        // roots from the largest down: point i and its mirror n − 1 − i
        points[n - 1 - i] = (t, w);
        points[i] = (-t, w);
    }
    if n % 2 == 1 {
        points[n / 2].0 = 0.0;
    }
    Rule { n, points }
}

/// (P_n(t), P_{n−1}(t)) for any n ≥ 1.
fn legendre_with(t: f64, n: usize) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, t);
    for k in 1..n {
        let kf = k as f64;
        let p2 = ((2.0 * kf + 1.0) * t * p1 - kf * p0) / (kf + 1.0);
        p0 = p1;
        p1 = p2;
    }
    (p1, p0)
}

/// The shape functions of an element of degree p and their first and second x-derivatives at
/// one ξ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PShape {
    /// Number of shapes p + 1.
    pub n: usize,
    /// S_j [-, m for the nodal slopes].
    pub s: [f64; MAX_SHAPES],
    /// dS_j/dx.
    pub ds: [f64; MAX_SHAPES],
    /// d²S_j/dx².
    pub dds: [f64; MAX_SHAPES],
}

impl PShape {
    /// The shapes of an element of degree `degree` (3 ≤ p ≤ [`MAX_DEGREE`]) and length `l` at
    /// ξ ∈ [0, 1].
    pub fn at(degree: usize, xi: f64, l: f64) -> Self {
        let h = super::ancf::Shape::at(xi, l);
        let n = degree + 1;
        let mut out = Self {
            n,
            s: [0.0; MAX_SHAPES],
            ds: [0.0; MAX_SHAPES],
            dds: [0.0; MAX_SHAPES],
        };
        out.s[..4].copy_from_slice(&h.s);
        out.ds[..4].copy_from_slice(&h.ds);
        out.dds[..4].copy_from_slice(&h.dds);
        if degree > 3 {
            let p = legendre(2.0 * xi - 1.0, degree);
            for k in 4..=degree {
                let kf = k as f64;
                let a = (p[k] - p[k - 2]) / (2.0 * kf - 1.0);
                let b = (p[k - 2] - p[k - 4]) / (2.0 * kf - 5.0);
                out.s[k] = (a - b) / (2.0 * (2.0 * kf - 3.0));
                out.ds[k] = (p[k - 1] - p[k - 3]) / ((2.0 * kf - 3.0) * l);
                out.dds[k] = 2.0 * p[k - 2] / (l * l);
            }
        }
        out
    }

    /// Σ_j w_j e_j (DIM-vector) over the element's shapes, `w` one of `s`, `ds`, `dds`.
    #[inline]
    pub fn combine<const DIM: usize>(&self, w: &[f64; MAX_SHAPES], e: &[f64]) -> [f64; DIM] {
        combine::<DIM>(self.n, w, e)
    }
}

/// Σ_{j < n} w_j e[DIM·j..DIM·j + DIM].
#[inline(always)]
pub fn combine<const DIM: usize>(n: usize, w: &[f64; MAX_SHAPES], e: &[f64]) -> [f64; DIM] {
    let mut r = [0.0; DIM];
    for (j, wj) in w.iter().enumerate().take(n) {
        for c in 0..DIM {
            r[c] += wj * e[DIM * j + c];
        }
    }
    r
}

/// `f[DIM·j + c] += s·w_j·v_c` for j < n.
#[inline(always)]
pub fn scatter<const DIM: usize>(
    n: usize,
    w: &[f64; MAX_SHAPES],
    s: f64,
    v: &[f64; DIM],
    f: &mut [f64],
) {
    for (j, wj) in w.iter().enumerate().take(n) {
        let c = s * wj;
        for k in 0..DIM {
            f[DIM * j + k] += c * v[k];
        }
    }
}

/// What a kernel of degree p supplies: its tables and section, and the internal forces,
/// energies and samples at element coordinates (DIM·(p + 1) entries used).
pub trait PKernel: std::fmt::Debug + Clone + Send + Sync + 'static {
    /// Number of components of a vector of the element's space (2 planar, 3 spatial).
    const DIM: usize;
    /// Shapes at the quadrature points, mass pattern, load weights.
    fn tables(&self) -> &PTables;
    /// Number of element coordinates DIM·(p + 1).
    fn dofs(&self) -> usize {
        Self::DIM * self.tables().n
    }
    /// Mass per length ρA [kg/m].
    fn rho_a(&self) -> f64;
    /// Kelvin–Voigt retardation time τ [s] (0: undamped).
    fn damping_time(&self) -> f64;
    /// [`PKernel::forces`] of an element of `N` = p + 1 shapes (the loops over them unrolled).
    fn forces_of<const N: usize>(
        &self,
        e: &PVec,
        ed: &PVec,
        mats: Option<(&mut PMat, &mut PMat)>,
    ) -> PVec;
    /// Internal (elastic + damping) force at (e, ė) and, with `mats`, its stiffness ∂f/∂e and
    /// damping ∂f/∂ė added to the two matrices: [`PKernel::forces_of`] of the element's number
    /// of shapes.
    fn forces(&self, e: &PVec, ed: &PVec, mats: Option<(&mut PMat, &mut PMat)>) -> PVec {
        match self.tables().n {
            4 => self.forces_of::<4>(e, ed, mats),
            5 => self.forces_of::<5>(e, ed, mats),
            6 => self.forces_of::<6>(e, ed, mats),
            7 => self.forces_of::<7>(e, ed, mats),
            8 => self.forces_of::<8>(e, ed, mats),
            n => unreachable!("{n} shapes: an element degree beyond {MAX_SHAPES} − 1"),
        }
    }
    /// Strain energy [J].
    fn strain_energy(&self, e: &[f64]) -> f64;
    /// Largest |ε| = ||r′| − 1| over the axial points at `e`.
    fn max_axial_strain(&self, e: &[f64]) -> f64 {
        let (t, dim) = (self.tables(), Self::DIM);
        (t.axial.iter())
            .map(|q| {
                let mut r1 = [0.0; 3];
                for (j, w) in q.ds.iter().enumerate().take(t.n) {
                    for c in 0..dim {
                        r1[c] += w * e[dim * j + c];
                    }
                }
                (r1.iter().map(|x| x * x).sum::<f64>().sqrt() - 1.0).abs()
            })
            .fold(0.0, f64::max)
    }
    /// The centreline at ξ ∈ [0, 1].
    fn sample(&self, e: &[f64], ed: &[f64], xi: f64) -> ShapePoint;
}

// [`PKernel::forces`] has an instance for each number of shapes up to 8
const _: () = assert!(MAX_SHAPES <= 8);

/// A quadrature point of an element: weight × l/2 [m] and the shapes' x-derivatives there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QPoint {
    /// Gauss weight × l/2 [m].
    pub w: f64,
    /// ξ of the point.
    pub xi: f64,
    /// dS_j/dx.
    pub ds: [f64; MAX_SHAPES],
    /// d²S_j/dx².
    pub dds: [f64; MAX_SHAPES],
}

/// An element's tables, computed once: its quadrature points, the mass pattern ∫S_j S_k dx and
/// the load weights ∫S_j dx.
#[derive(Debug, Clone, PartialEq)]
pub struct PTables {
    /// Degree p.
    pub degree: usize,
    /// Number of shapes p + 1.
    pub n: usize,
    /// Element length l [m].
    pub length: f64,
    /// The axial points (p + 1).
    pub axial: Vec<QPoint>,
    /// The bending points (p).
    pub bending: Vec<QPoint>,
    /// ∫S_j S_k dx [m, m², m³].
    pub mass: [[f64; MAX_SHAPES]; MAX_SHAPES],
    /// ∫S_j dx [m, m²].
    pub load: [f64; MAX_SHAPES],
    /// The (p + 1)-point rule of the mass and of a partial element's loads.
    pub rule: Rule,
}

impl PTables {
    /// The tables of an element of degree `degree` and length `l` [m].
    pub fn new(degree: usize, l: f64) -> Self {
        assert!(
            (3..=MAX_DEGREE).contains(&degree),
            "element degree {degree}"
        );
        let points = |n: usize| -> Vec<QPoint> {
            rule(n)
                .points()
                .iter()
                .map(|&(xg, wg)| {
                    let xi = 0.5 * (xg + 1.0);
                    let sh = PShape::at(degree, xi, l);
                    QPoint {
                        w: wg * 0.5 * l,
                        xi,
                        ds: sh.ds,
                        dds: sh.dds,
                    }
                })
                .collect()
        };
        let n = degree + 1;
        let rule = rule(degree + 1);
        let mut mass = [[0.0; MAX_SHAPES]; MAX_SHAPES];
        let mut load = [0.0; MAX_SHAPES];
        for &(xg, wg) in rule.points() {
            let sh = PShape::at(degree, 0.5 * (xg + 1.0), l);
            let w = wg * 0.5 * l;
            for j in 0..n {
                load[j] += w * sh.s[j];
                for k in 0..n {
                    mass[j][k] += w * sh.s[j] * sh.s[k];
                }
            }
        }
        Self {
            degree,
            n,
            length: l,
            axial: points(degree + 1),
            bending: points(degree),
            mass,
            load,
            rule,
        }
    }

    /// Number of element coordinates in DIM dimensions.
    pub fn dofs(&self, dim: usize) -> usize {
        dim * self.n
    }
}

/// Adds the Jacobian of one quadrature point to an element matrix `k` (D ≥ DIM·n): with the
/// point's local vectors u_a = Σ_j W_a[j] e_j (a < K, e.g. r′ and r″) and `jac[a][b]` the DIM×DIM
/// block ∂F_a/∂u_b of its local forces, `k[DIM·j + i][DIM·m + c] += Σ_ab W_a[j] W_b[m]
/// jac[a][b][i][c]`.
pub fn add_point_jacobian<const DIM: usize, const K: usize, const D: usize>(
    n: usize,
    maps: [&[f64; MAX_SHAPES]; K],
    jac: &[[[[f64; DIM]; DIM]; K]; K],
    k: &mut [[f64; D]; D],
) {
    for j in 0..n {
        for m in 0..n {
            let mut blk = [[0.0; DIM]; DIM];
            for a in 0..K {
                let wa = maps[a][j];
                if wa == 0.0 {
                    continue;
                }
                for b in 0..K {
                    let c = wa * maps[b][m];
                    if c == 0.0 {
                        continue;
                    }
                    for (row, src) in blk.iter_mut().zip(&jac[a][b]) {
                        for (x, y) in row.iter_mut().zip(src) {
                            *x += c * y;
                        }
                    }
                }
            }
            for (i, row) in blk.iter().enumerate() {
                let out = &mut k[DIM * j + i][DIM * m..DIM * m + DIM];
                for (x, y) in out.iter_mut().zip(row) {
                    *x += y;
                }
            }
        }
    }
}

/// The d'Alembert load of the part ξ′ ∈ [0, ξ] of an element in `dim` dimensions (Gauss on
/// p + 1 points of [0, ξ]: exact for ρA(g + q/ρA − r̈) and its moment, of degree 2p) and the
/// point masses (ξ_m, m) with ξ_m < ξ: the force ∫(f_ext − ρA r̈) dx and its moment about
/// `about` (world axes, 3-vectors), at coordinates `e` and accelerations `ea`, ρA `rho_a`, field
/// `field` = g + q/(ρA) on the distributed mass and `gravity` on the point masses (3-vectors,
/// zero beyond `dim`).
#[allow(clippy::too_many_arguments)]
pub fn partial_load(
    t: &PTables,
    dim: usize,
    (e, ea): (&[f64], &[f64]),
    rho_a: f64,
    field: [f64; 3],
    gravity: [f64; 3],
    points: &[(f64, f64)],
    xi: f64,
    about: [f64; 3],
) -> ([f64; 3], [f64; 3]) {
    let (mut f, mut m) = ([0.0; 3], [0.0; 3]);
    let mut add = |s: f64, mass: f64, g: [f64; 3]| {
        let sh = PShape::at(t.degree, s, t.length);
        let (mut r, mut a) = ([0.0; 3], [0.0; 3]);
        for j in 0..t.n {
            for c in 0..dim {
                r[c] += sh.s[j] * e[dim * j + c];
                a[c] += sh.s[j] * ea[dim * j + c];
            }
        }
        let load: [f64; 3] = std::array::from_fn(|c| mass * (g[c] - a[c]));
        let arm: [f64; 3] = std::array::from_fn(|c| r[c] - about[c]);
        let mo = crate::model::vector::cross(arm, load);
        for c in 0..3 {
            f[c] += load[c];
            m[c] += mo[c];
        }
    };
    for &(xg, wg) in t.rule.points() {
        add(
            0.5 * xi * (xg + 1.0),
            0.5 * xi * t.length * wg * rho_a,
            field,
        );
    }
    for &(xm, mass) in points.iter().filter(|(xm, _)| *xm < xi) {
        add(xm, mass, gravity);
    }
    (f, m)
}

/// Checks of a kernel shared by the planar and spatial tests.
#[cfg(test)]
pub(crate) mod checks {
    use super::*;

    /// The kernel's stiffness and damping matrices against central differences of its forces
    /// at (e, ė), its residual path equal to its matrix path, and (undamped) its force the
    /// gradient of its strain energy; `label` names the case in a failure.
    pub(crate) fn jacobians<K: PKernel>(el: &K, e: &PVec, ed: &PVec, tau: f64, label: &str) {
        let d = el.dofs();
        let (mut k, mut c) = ([[0.0; MAX_DOFS]; MAX_DOFS], [[0.0; MAX_DOFS]; MAX_DOFS]);
        let f0 = el.forces(e, ed, Some((&mut k, &mut c)));
        assert_eq!(f0, el.forces(e, ed, None), "{label}");
        let scale = k.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let fs = f0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let h = 1e-7;
        let diff = |j: usize, rates: bool| {
            let (mut p, mut m) = if rates { (*ed, *ed) } else { (*e, *e) };
            p[j] += h;
            m[j] -= h;
            let (fp, fm) = if rates {
                (el.forces(e, &p, None), el.forces(e, &m, None))
            } else {
                (el.forces(&p, ed, None), el.forces(&m, ed, None))
            };
            let du = (el.strain_energy(&p) - el.strain_energy(&m)) / (2.0 * h);
            (
                std::array::from_fn::<f64, MAX_DOFS, _>(|i| (fp[i] - fm[i]) / (2.0 * h)),
                du,
            )
        };
        for j in 0..d {
            let ((fd, du), (gd, _)) = (diff(j, false), diff(j, true));
            for i in 0..d {
                let err = (fd[i] - k[i][j]).abs();
                assert!(
                    err <= 1e-6 * scale,
                    "{label} K[{i},{j}]: {} vs {}",
                    fd[i],
                    k[i][j]
                );
                let err = (gd[i] - c[i][j]).abs();
                assert!(
                    err <= 1e-6 * scale * tau.max(1e-12) + 1e-12,
                    "{label} C[{i},{j}]"
                );
            }
            if tau == 0.0 {
                assert!((du - f0[j]).abs() <= 1e-6 * fs, "{label} dU/de[{j}]");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_rules_integrate_polynomials_exactly() {
        for n in 1..=MAX_POINTS {
            let r = rule(n);
            for deg in 0..2 * n {
                let got: f64 = r.points().iter().map(|(x, w)| w * x.powi(deg as i32)).sum();
                let want = if deg % 2 == 1 {
                    0.0
                } else {
                    2.0 / (deg as f64 + 1.0)
                };
                assert!(
                    (got - want).abs() < 2e-15,
                    "n {n} degree {deg}: {got} vs {want}"
                );
            }
        }
        // the cubic element's tables
        for (a, b) in rule(5).points().iter().zip(crate::model::ancf::GAUSS5) {
            assert!((a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15);
        }
        for (a, b) in rule(3).points().iter().zip(crate::model::ancf::GAUSS3) {
            assert!((a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15);
        }
    }

    /// The bubbles vanish with their slope at both ends, their derivatives are those of their
    /// values (central differences), b_4 = ξ²(1 − ξ)², and b_k″ = 2P_{k−2}: the bending
    /// integrals ∫b_j″b_k″ dξ are diagonal and orthogonal to the cubic's S″.
    #[test]
    fn bubbles_are_c1_hierarchic_and_orthogonal_in_bending() {
        let p = MAX_DEGREE;
        let l = 0.3;
        for xi in [0.0, 1.0] {
            let s = PShape::at(p, xi, l);
            for k in 4..=p {
                assert!(s.s[k].abs() < 1e-15 && s.ds[k].abs() < 1e-14, "{k} at {xi}");
            }
        }
        for xi in [0.1, 0.37, 0.5, 0.83] {
            let s = PShape::at(p, xi, l);
            assert!((s.s[4] - xi * xi * (1.0 - xi) * (1.0 - xi)).abs() < 1e-15);
            let h = 1e-6;
            let (a, b) = (PShape::at(p, xi + h, l), PShape::at(p, xi - h, l));
            for k in 0..=p {
                let d1 = (a.s[k] - b.s[k]) / (2.0 * h * l);
                let d2 = (a.ds[k] - b.ds[k]) / (2.0 * h * l);
                assert!((d1 - s.ds[k]).abs() < 1e-8, "ds {k}");
                assert!(
                    (d2 - s.dds[k]).abs() < 1e-6 * (1.0 + s.dds[k].abs()),
                    "dds {k}"
                );
            }
        }
        let r = rule(MAX_POINTS);
        let mut g = [[0.0; MAX_SHAPES]; MAX_SHAPES];
        for &(x, w) in r.points() {
            let s = PShape::at(p, 0.5 * (x + 1.0), 1.0);
            for j in 0..=p {
                for k in 0..=p {
                    g[j][k] += 0.5 * w * s.dds[j] * s.dds[k];
                }
            }
        }
        for j in 0..=p {
            for k in 4..=p {
                if j != k {
                    assert!(g[j][k].abs() < 1e-12, "({j}, {k}): {}", g[j][k]);
                }
            }
        }
        // ∫(2P_m)² dξ = 4/(2m + 1)
        for k in 4..=p {
            let want = 4.0 / (2.0 * (k - 2) as f64 + 1.0);
            assert!((g[k][k] - want).abs() < 1e-12);
        }
    }

    /// The mass pattern and the load weights of the cubic part are the closed forms of the
    /// cubic element (ρA l/420 [156, 22l, …] and l[½, l/12, ½, −l/12]).
    #[test]
    fn tables_extend_the_cubic_element() {
        let l = 0.7;
        let t = PTables::new(6, l);
        let c = l / 420.0;
        let m4 = [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ];
        let w = [0.5 * l, l * l / 12.0, 0.5 * l, -l * l / 12.0];
        for j in 0..4 {
            assert!((t.load[j] - w[j]).abs() < 1e-15);
            for k in 0..4 {
                assert!((t.mass[j][k] - c * m4[j][k]).abs() < 1e-15);
            }
        }
        // ∫b_4 dξ = 1/30
        assert!((t.load[4] - l / 30.0).abs() < 1e-15);
        assert_eq!((t.axial.len(), t.bending.len()), (7, 6));
    }
}
