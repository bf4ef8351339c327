//! Planar floating-frame body with transverse modal coordinates (docs/references.md §3): the
//! kernel of [`crate::model::planar::ModalElement`].
//!
//! Local coordinates `q = [Rx, Ry, θ, a_1 … a_n]`: frame origin R [m] (the segment root),
//! frame angle θ [rad] (counter-clockwise from global x), modal amplitudes a [m]. The shapes
//! are mass-orthonormal (∫ρA φ_iφ_j dx = ρAL δ_ij) and stiffness-diagonal, so the linear
//! parts are M_ff = ρAL·I and K_ff = diag(EIΛ_k/L³).
//!
//! Geometrically nonlinear inside the segment (an inextensible beam with foreshortening,
//! Kane, Ryan & Banerjee, "Dynamics of a cantilever beam attached to a moving base",
//! J. Guidance 10(2):139–151, 1987): a material point at x ∈ [0, L] is at
//! r = R + A(θ)[x − ½∫₀ˣ w′² dξ; w(x)], w = Σ φ_k(x/L) a_k, so ∂r/∂a_k =
//! A[−∫₀ˣ w′φ_k′ dξ; φ_k]; the kinetic energy ½∫ρA|ṙ|²dx and the gravity potential are those
//! of this kinematics, and the strain energy is ½EI∫κ²dx with the inextensible curvature to
//! third order, κ = w″(1 + ½w′²) (Crespo da Silva & Glynn, J. Struct. Mech. 6(4):437–448,
//! 1978). The linear floating frame (ū = [x; w], exact invariants, the damping D ȧ) is kept
//! and the rest — every term of the foreshortening c(x) = −½∫₀ˣ w′²dx and the quartic strain
//! energy ½EI∫w″²(w′² + ¼w′⁴)dx, and the Kelvin–Voigt damping of that curvature beyond τKȧ,
//! τEI∫(κ̇ ∂κ/∂a − ẇ″φ″)dx — is added on a composite 5-point Gauss rule
//! (`ModalBody::add_nonlinear_fields`), c at each point being the cumulative integral of w′² on the
//! rule's own points. The tip (joints, tip loads) is the x = L case: [L − ½aᵀGa/L; w(L)] with
//! G the rule's ∫φ′φ′ᵀdξ ([`ModalBody::tip_local`]), its angle the tangent's, θ +
//! atan2(w′, 1 − ½w′²) ([`crate::model::planar::ModalTipPort`]). This carries the axial force
//! of the inertia, centrifugal and gravity fields into the bending of held and free frames
//! alike (its leading term is the geometric stiffness ρAL θ̇² G2 − ρA ā_x G1 of
//! docs/references.md §7.4), the nonlinear inertia of the foreshortening and the curvature's
//! hardening. Measured (docs/engine-findings.md): the converged hybrid Case 1 is 4.1e-8 m from
//! the converged all-ANCF beam (the linear frame's floor was 3.75e-5 m), the all-modal twin
//! 9.1e-8 m (was 4.5e-5 m).
//!
//! [`ModalBody::eval`] returns the residual of the equations of motion
//! `F = M(q) q̈ − Q_v(q, q̇) − Q_g(q) + ∂U/∂a + D ȧ` and its exact partial derivatives
//! ∂F/∂q̈ (mass matrix), ∂F/∂q̇ and ∂F/∂q: by hand for the linear part, by forward-mode
//! automatic differentiation ([`Dual64`]) of the nonlinear part, whose residual is plain f64.

use super::basis::ModalBasis;
use super::nonlinear::{panels, point_fields, BodyPoint, Nonlinear};
use super::taper::{modal_damping, row_times, Taper};
use super::BodyGravity;
use crate::math;
use crate::model::component::LocalVec;
use crate::model::sample::ShapePoint;
use crate::model::vector::Real;
use nalgebra::{DMatrix, DVector, Matrix2, Vector2};
use num_dual::Dual64;

/// Rotation matrix A(θ).
pub fn rot(theta: f64) -> Matrix2<f64> {
    let (s, c) = math::sin_cos(theta);
    Matrix2::new(c, -s, s, c)
}

/// J = A(π/2): Jv rotates v by +90°.
fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v[1], v[0])
}

/// Constant properties and invariants of a modal segment.
#[derive(Debug, Clone)]
pub struct ModalBody {
    /// Shape basis.
    pub basis: ModalBasis,
    /// The nonlinear fields' buffer of the energies (through `&self`; no allocation in a step).
    fields_buf: crate::model::scratch::Scratch<Vec<f64>>,
    /// Length L [m].
    pub length: f64,
    /// Mass per length ρA [kg/m].
    pub rho_a: f64,
    /// Bending stiffness EI [N m²].
    pub ei: f64,
    /// Modal stiffness K_k = EIΛ_k/L³ [N/m].
    pub k: Vec<f64>,
    /// Modal damping D_k = 2ζω_k·ρAL + τK_k [N s/m]; empty if undamped.
    pub d: Vec<f64>,
    /// Kelvin–Voigt retardation time τ [s] of the curvature (0 = none): τK_k is in `d`, the
    /// nonlinear body adds the rest of τEI∫κ̇ ∂κ/∂a dx.
    pub damping_time: f64,
    /// ρA L ∫φ_k dξ [kg].
    pub s_f: Vec<f64>,
    /// ρA L² ∫ξφ_k dξ [kg m].
    pub s_x: Vec<f64>,
    /// G = Σ_p W_p φ′(ξ_p)φ′(ξ_p)ᵀ (row-major n × n) on the body's quadrature (composite
    /// 5-point Gauss, max(4, n) panels): the tip foreshortening is ½ aᵀ G a / L, the ξ = 1 case
    /// of the foreshortening of the points inside.
    pub gram: Vec<f64>,
    /// The geometrically nonlinear body (true unless built [`ModalBody::linear`]).
    pub nonlinear: bool,
    nl: Nonlinear,
    /// Point masses on the body ([`ModalBody::with_points`]).
    points: Vec<BodyPoint>,
    /// The segment's line load over ρA, q/(ρA) [m/s²] ([`ModalBody::with_line_load`]); `None`
    /// without one (a tapered body: over its ρA at the start, `rho_a`).
    pub(crate) line: Option<[f64; 2]>,
    /// The section integrals of a tapered segment ([`ModalBody::tapered`]); `None`: uniform
    /// (the closed forms of the fields above).
    taper: Option<Box<Taper>>,
    /// The shapes at the quadrature points of the stations' cuts ([`ModalBody::partial_load`]).
    cuts: CutCache,
}

/// The shapes at the quadrature points of a station's cut at ξ ([`CutTable`]), one per cut,
/// each computed at the cut's first use (the shapes cost exponentials and trigonometry; no
/// allocation after it): at most [`crate::scene::MAX_STATIONS`] cuts per body.
pub(super) type CutCache = Box<[std::sync::OnceLock<CutTable>; crate::scene::MAX_STATIONS]>;

/// A new, empty [`CutCache`].
pub(super) fn cut_cache() -> CutCache {
    Box::new(std::array::from_fn(|_| std::sync::OnceLock::new()))
}

/// The composite 5-point Gauss–Legendre rule on [0, ξ] of a station's cut inside a modal body,
/// [`cut_panels`] panels, with the shapes and the section's ρA and ρI_p at its points, and for
/// the foreshortening at each point ξ_p (∫₀^ξ_p of the slopes' products) the 5-point rule on
/// [panel start, ξ_p] with the slopes at its points (the panels before ξ_p on the main rule).
#[derive(Debug, Clone)]
pub(super) struct CutTable {
    /// The cut ξ.
    xi: f64,
    /// Per point: (ξ_p, W_p (Σ W_p = ξ), ρA(ξ_p) [kg/m], ρI_p(ξ_p) [kg m]).
    pub(super) points: Vec<[f64; 4]>,
    /// (φ_k, φ_k′, φ_k″)(ξ_p) (ξ-derivatives) at `[p * n + k]`.
    pub(super) phi: Vec<[f64; 3]>,
    /// φ_k′(ξ_p) at `[p * n + k]`.
    slope: Vec<f64>,
    /// φ_k′ at the j-th point of the rule on [panel start, i-th point] of each panel, at
    /// `[((panel * 5 + i) * 5 + j) * n + k]`.
    sub_slope: Vec<f64>,
    /// Their weights (the same in every panel): `sub_w[i][j]` (Σ_j = ξ_i − panel start).
    sub_w: [[f64; 5]; 5],
}

/// Panels of a cut's rule for n shapes: two per shape, at least 8. The k-th mode's wavenumber
/// is λ ≈ (k − ½)π, the foreshortening's products of slopes twice that: over a panel of width
/// ξ/P ≤ 1/2n they turn by at most about π radians, where the 5-point rule (exact to degree 9)
/// errs by about 1e-9 of the load. Measured against an independent 100-panel rule with a nested
/// foreshortening (`tests/stations.rs`, a strongly deflected, accelerated body of 8 modes and
/// the interface shapes): 8.8e-10 with 2 panels per shape, 8.9e-13 with 4 — far below the
/// model's own errors, and half the cost per output of 4 (`benches/stations_cost.sh`).
pub(super) fn cut_panels(n: usize) -> usize {
    (2 * n).max(8)
}

impl CutTable {
    /// The table of the cut at `xi` of a body with `basis`, whose section at ξ has
    /// (ρA, ρI_p) = `props(ξ)`.
    pub(super) fn new(basis: &ModalBasis, xi: f64, props: impl Fn(f64) -> (f64, f64)) -> Self {
        let (n, panels) = (basis.len(), cut_panels(basis.len()));
        let quad = super::basis::quadrature(panels);
        let mut phi = Vec::with_capacity(quad.len() * n);
        let mut buf = Vec::new();
        let points: Vec<[f64; 4]> = quad
            .iter()
            .map(|&(x, w)| {
                let x = x * xi;
                basis.eval_all(x, &mut buf);
                phi.extend_from_slice(&buf);
                let (ra, rip) = props(x);
                [x, w * xi, ra, rip]
            })
            .collect();
        let slope = phi.iter().map(|f| f[1]).collect();
        let width = xi / panels as f64;
        let mut sub_w = [[0.0; 5]; 5];
        let mut sub_slope = Vec::with_capacity(quad.len() * 5 * n);
        for (p, pts) in points.chunks_exact(5).enumerate() {
            let start = p as f64 * width;
            for (i, pt) in pts.iter().enumerate() {
                let h = pt[0] - start;
                for (j, (t, w)) in crate::model::ancf::GAUSS5.iter().enumerate() {
                    sub_w[i][j] = 0.5 * h * w;
                    basis.eval_all(start + 0.5 * h * (t + 1.0), &mut buf);
                    sub_slope.extend(buf.iter().map(|f| f[1]));
                }
            }
        }
        Self {
            xi,
            points,
            phi,
            slope,
            sub_slope,
            sub_w,
        }
    }

    /// Visits every point p of the rule with its shapes and the integrals ∫₀^ξ_p f of the
    /// integrands f = `integrands(φ′ at a point)` (cumulative: the panels before on the main
    /// rule, p's own panel up to ξ_p on its own rule): `visit(point, shapes, integrals)`.
    pub(super) fn for_each<const K: usize>(
        &self,
        n: usize,
        mut integrands: impl FnMut(&[f64]) -> [f64; K],
        mut visit: impl FnMut(&[f64; 4], &[[f64; 3]], [f64; K]),
    ) {
        let mut before = [0.0; K];
        for (panel, pts) in self.points.chunks_exact(5).enumerate() {
            for (i, pt) in pts.iter().enumerate() {
                let p = panel * 5 + i;
                let mut acc = before;
                for (j, w) in self.sub_w[i].iter().enumerate() {
                    let at = (p * 5 + j) * n;
                    let f = integrands(&self.sub_slope[at..at + n]);
                    for (a, x) in acc.iter_mut().zip(f) {
                        *a += w * x;
                    }
                }
                visit(pt, &self.phi[p * n..(p + 1) * n], acc);
            }
            for (i, pt) in pts.iter().enumerate() {
                let p = panel * 5 + i;
                let f = integrands(&self.slope[p * n..(p + 1) * n]);
                for (b, x) in before.iter_mut().zip(f) {
                    *b += pt[1] * x;
                }
            }
        }
    }
}

/// The slope fields (w′, ẇ′, ẅ′) (ξ-derivatives) of the amplitudes (a, ȧ, ä) at shape slopes
/// `slope`.
#[inline]
pub(super) fn slope_fields(slope: &[f64], (a, v, acc): (&[f64], &[f64], &[f64])) -> [f64; 3] {
    let mut f = [0.0; 3];
    for (((s, x), y), z) in slope.iter().zip(a).zip(v).zip(acc) {
        f[0] += s * x;
        f[1] += s * y;
        f[2] += s * z;
    }
    f
}

/// The table of the cut at `xi` from `cache` (computed at its first use), or `None` when every
/// slot holds another cut.
pub(super) fn cut_table(
    cache: &CutCache,
    xi: f64,
    make: impl Fn() -> CutTable,
) -> Option<&CutTable> {
    for slot in cache.iter() {
        let t = slot.get_or_init(&make);
        if t.xi == xi {
            return Some(t);
        }
    }
    None
}

/// Slots per quadrature point of [`ModalBody::fields`].
const FIELDS: usize = 11;

/// Quantities of one state shared by [`ModalBody::eval`]'s linear residual and its matrices:
/// modes n, mass μ = ρAL [kg], s0 = ½ρAL² [kg m], j0 = ρAL³/3 [kg m²], θ̇, θ̈, A(θ), sᵀa,
/// sᵀȧ, sᵀä (s = `s_f`), aᵀa, aᵀȧ, z = R̈ − g and Aᵀz.
#[derive(Debug, Clone, Copy)]
struct LinearTerms {
    n: usize,
    mu: f64,
    s0: f64,
    j0: f64,
    thd: f64,
    thdd: f64,
    rot_a: Matrix2<f64>,
    sfa: f64,
    sfv: f64,
    sfacc: f64,
    a2: f64,
    av: f64,
    z: Vector2<f64>,
    zl: Vector2<f64>,
}

/// Residual and derivatives of one body at one state (local coordinates).
#[derive(Debug, Clone)]
pub struct BodyOut {
    /// F (3 + n) [N, N m, N].
    pub res: DVector<f64>,
    /// ∂F/∂q̈ = M(q).
    pub m: DMatrix<f64>,
    /// ∂F/∂q̇.
    pub c: DMatrix<f64>,
    /// ∂F/∂q.
    pub k: DMatrix<f64>,
    /// Scratch of the nonlinear terms.
    buf: Vec<f64>,
    /// Scratch of [`ModalBody::add_nonlinear_matrices`].
    ad: AdScratch,
}

/// The dual-number buffers of [`ModalBody::add_nonlinear_matrices`] and
/// `add_point_matrices`, kept between calls.
#[derive(Debug, Clone, Default)]
struct AdScratch {
    /// q, q̇, q̈ lifted.
    x: [Vec<Dual64>; 3],
    /// The nonlinear residual.
    r: Vec<Dual64>,
    /// The per-point fields.
    buf: Vec<Dual64>,
    /// The fields' values.
    base: Vec<f64>,
}

impl AdScratch {
    /// q, q̇, q̈ lifted to duals (no derivative seeded) and a zero residual of `d` entries.
    fn lift(&mut self, (q, v, a): (&[f64], &[f64], &[f64]), d: usize) {
        for (x, y) in self.x.iter_mut().zip([q, v, a]) {
            x.clear();
            x.extend(y.iter().map(|&y| Dual64::from_re(y)));
        }
        self.r.clear();
        self.r.resize(d, Dual64::from_re(0.0));
    }
}

impl BodyOut {
    /// Zeroed output for `dim` local coordinates.
    pub fn new(dim: usize) -> Self {
        Self {
            res: DVector::zeros(dim),
            m: DMatrix::zeros(dim, dim),
            c: DMatrix::zeros(dim, dim),
            k: DMatrix::zeros(dim, dim),
            buf: Vec::new(),
            ad: AdScratch::default(),
        }
    }
}

impl ModalBody {
    /// Builds the body from geometry, material and damping.
    pub fn new(
        basis: ModalBasis,
        length: f64,
        rho_a: f64,
        ei: f64,
        damping_ratio: f64,
        damping_time: f64,
    ) -> Self {
        let mu = rho_a * length;
        let k: Vec<f64> = basis
            .lambda4
            .iter()
            .map(|l4| ei * l4 / length.powi(3))
            .collect();
        let d = if damping_ratio > 0.0 || damping_time > 0.0 {
            k.iter()
                .map(|kk| 2.0 * damping_ratio * (kk / mu).sqrt() * mu + damping_time * kk)
                .collect()
        } else {
            Vec::new()
        };
        let s_f = basis.i1.iter().map(|v| mu * v).collect();
        let s_x = basis.ix.iter().map(|v| mu * length * v).collect();
        let n = basis.len();
        let nl = Nonlinear::new(&basis, panels(n));
        let mut gram = vec![0.0; n * n];
        for (p, w) in nl.w.iter().enumerate() {
            let phi = &nl.phi[p * n..(p + 1) * n];
            for i in 0..n {
                for j in 0..n {
                    gram[i * n + j] += w * phi[i][1] * phi[j][1];
                }
            }
        }
        let nl = nl.scaled(length, n);
        Self {
            fields_buf: Default::default(),
            basis,
            length,
            rho_a,
            ei,
            k,
            d,
            damping_time,
            s_f,
            s_x,
            gram,
            nonlinear: true,
            nl,
            points: Vec::new(),
            line: None,
            taper: None,
            cuts: cut_cache(),
        }
    }

    /// The body of the tapered segment `seg` ([`crate::scene::Segment::is_tapered`]; built
    /// [`ModalBody::new`] with its properties at the start, before [`ModalBody::linear`] and
    /// the points): the shapes stay the uniform beam's, and every integral with ρA or EI takes
    /// the property at its point — the mass terms ∫ρA(1, x, x², φ_k, xφ_k, φ_iφ_j)dx, the
    /// stiffness ∫EIφ_i″φ_j″dx (full matrices), the nonlinear rule's point masses and EI, the
    /// stiffening grams; the line load is q per unit length (∫φ_k dx, not ∫ρAφ_k dx); the
    /// modal damping gives every mode of (M, K) the ratio ζ ([`ModalBody::omegas`]), plus τK.
    /// `k` and `d` then hold the diagonals of K and D (the matrices are used). Err if the
    /// modal mass is not positive definite.
    pub fn tapered(mut self, seg: &crate::scene::Segment) -> Result<Self, String> {
        let mut t = Taper::new(seg, &self.basis, &self.nl);
        let n = self.modes();
        let (om, d) = modal_damping(&t.mass, &t.k_z, seg.damping_ratio, self.damping_time)
            .ok_or_else(|| {
                format!(
                    "{}: the tapered modal mass is not positive definite",
                    seg.name
                )
            })?;
        self.k = (0..n).map(|i| t.k_z[i * n + i]).collect();
        self.d = if seg.damping_ratio > 0.0 || self.damping_time > 0.0 {
            (0..n).map(|i| d[i * n + i]).collect()
        } else {
            Vec::new()
        };
        t.damp_z = if self.d.is_empty() { Vec::new() } else { d };
        t.omega_z = om;
        self.s_f.clone_from(&t.s_f);
        self.s_x.clone_from(&t.s_x);
        self.taper = Some(Box::new(t));
        Ok(self)
    }

    /// Whether the body is tapered ([`ModalBody::tapered`]).
    pub fn is_tapered(&self) -> bool {
        self.taper.is_some()
    }

    /// (G1, G2) of a held linear frame's geometric stiffness K_G = ρAL θ̇² G2 − ρA ā_x G1
    /// (ρA, L the body's `rho_a`, `length`): the basis's for a uniform body, the
    /// ρA-weighted ones of a tapered body ([`ModalBody::tapered`]).
    pub fn stiffening_grams(&self) -> (Vec<f64>, Vec<f64>) {
        match &self.taper {
            None => self.basis.stiffening_grams(),
            Some(t) => (t.g1.clone(), t.g2.clone()),
        }
    }

    /// A tapered body's line load q [N/m] (world axes) in the fields `g`, and the unweighted
    /// G1 of its axial part (a held linear frame's K_G += (Aᵀq)_x G1); `None` on a uniform
    /// body (its line load is in `g.distributed`) or without one.
    pub fn taper_line(&self, g: &BodyGravity<2>) -> Option<([f64; 2], &[f64])> {
        let t = self.taper.as_ref()?;
        if g.line == [0.0; 2] {
            return None;
        }
        Some((g.line.map(|c| c * t.rho_ref), &t.g1_line))
    }

    /// The body under the uniform dead line load `q` [N/m] (world axes; `None`: none): a load
    /// of density q beside the weight ρA g, so its distributed mass feels g + q/(ρA) where it
    /// feels gravity (forces, matrices, potential −∫qᵀr dx), its point masses g alone.
    pub fn with_line_load(mut self, q: Option<[f64; 2]>) -> Self {
        self.line = q.map(|q| q.map(|c| c / self.rho_a));
        self
    }

    /// The gravity fields at load factor `load` of gravity `g` [m/s²] with the line load.
    pub fn gravity(&self, g: [f64; 2], load: f64) -> BodyGravity<2> {
        BodyGravity::of(g, load, self.line)
    }

    /// The body carrying point masses `points`: (x from the root [m], mass [kg]), each a point
    /// of the body's kinematics r = R + A[x + c(x); w(x)] with its own mass (c = 0 on a linear
    /// body): its inertia and weight enter every term on the body's shapes (Ritz). Call after
    /// [`ModalBody::linear`].
    pub fn with_points(mut self, points: &[(f64, f64)]) -> Self {
        self.points = points
            .iter()
            .map(|&p| BodyPoint::new(&self.basis, &self.nl, self.length, self.nonlinear, p))
            .collect();
        self
    }

    /// The body carrying rigid bodies on its section (offset or rotary inertia, `xi` = x/L):
    /// each a point of the kinematics as [`ModalBody::with_points`] whose centre is
    /// s = ū + R(β)o, β = atan2 of the centreline's tangent d = dū/dx = (1 + c′, w′) (c′ = 0 on a
    /// linear body), and whose angle θ + β carries its rotary inertia.
    pub fn with_bodies(mut self, bodies: &[crate::model::ancf::SectionMass]) -> Self {
        let n = self.modes();
        let mut buf = Vec::new();
        for b in bodies {
            let x = b.xi * self.length;
            self.basis.eval_all(b.xi.clamp(0.0, 1.0), &mut buf);
            let dphi = buf.iter().take(n).map(|f| f[1] / self.length).collect();
            let pt = BodyPoint::new(
                &self.basis,
                &self.nl,
                self.length,
                self.nonlinear,
                (x, b.mass),
            );
            self.points.push(pt.with_body(b.inertia, b.offset, dphi));
        }
        self
    }

    /// The section kinematics of a rigid body on the section: the slope sums (w′, ẇ′, ẅ′) give
    /// the tangent d and β̇, β̈; returns (β̇, β̈, R(β)o, R(β)Jo, κ) with ∂β/∂a_k = κ φ′_k.
    fn section<T: Real>(&self, o: [f64; 2], sl: [T; 3]) -> (T, T, [T; 2], [T; 2], T) {
        let [w1, w1d, w1dd] = sl;
        let one = T::from(1.0);
        let (d, dd, ddd) = if self.nonlinear {
            (
                [one - w1 * w1 * 0.5, w1],
                [-(w1 * w1d), w1d],
                [-(w1d * w1d) - w1 * w1dd, w1dd],
            )
        } else {
            ([one, w1], [T::zero(), w1d], [T::zero(), w1dd])
        };
        let n2 = d[0] * d[0] + d[1] * d[1];
        let cr = d[0] * dd[1] - d[1] * dd[0];
        let dot = d[0] * dd[0] + d[1] * dd[1];
        let bd = cr / n2;
        let bdd = (d[0] * ddd[1] - d[1] * ddd[0]) / n2 - cr * dot * 2.0 / (n2 * n2);
        let nrm = n2.sqrt();
        let t = [d[0] / nrm, d[1] / nrm];
        let nn = [-t[1], t[0]];
        let ro = [t[0] * o[0] + nn[0] * o[1], t[1] * o[0] + nn[1] * o[1]];
        let rjo = [nn[0] * o[0] - t[0] * o[1], nn[1] * o[0] - t[1] * o[1]];
        let kap = if self.nonlinear {
            (d[0] + d[1] * w1) / n2
        } else {
            d[0] / n2
        };
        (bd, bdd, ro, rjo, kap)
    }

    /// Mass of the point masses [kg].
    pub fn point_mass(&self) -> f64 {
        self.points.iter().map(|p| p.mass).sum()
    }

    /// Adds the point masses' inertia and weight, Σ m (∂r/∂q)ᵀ(r̈ − g), to `out`; `(sn, cs)`
    /// = (sin θ, cos θ). With the local acceleration α = Aᵀ(r̈ − g) = Z + θ̈Jū − θ̇²ū + 2θ̇J ū̇ + ü
    /// (Z = Aᵀ(R̈ − g)): F_R = m Aα, F_θ = m (Jū)·α, F_a = m(φ α_y − G_m a α_x).
    fn add_point_forces<T: Real>(
        &self,
        (q, v, a): (&[T], &[T], &[T]),
        g: [f64; 2],
        (sn, cs): (T, T),
        out: &mut [T],
    ) {
        let n = self.modes();
        let (thd, thdd) = (v[2], a[2]);
        let thd2 = thd * thd;
        let (gx, gy) = (a[0] - g[0], a[1] - g[1]);
        let (zx, zy) = (cs * gx + sn * gy, cs * gy - sn * gx);
        let (am, vm, acc) = (&q[3..3 + n], &v[3..3 + n], &a[3..3 + n]);
        for pt in &self.points {
            let ([ux, uy], [vx, vy], [ax, ay], section) = self.point_local(pt, (am, vm, acc));
            let rot_terms =
                section.map(|(bdd, j, rjo, kap, dphi)| ((thdd + bdd) * j, rjo, kap, dphi));
            let alx = zx - thdd * uy - thd2 * ux - thd * vy * 2.0 + ax;
            let aly = zy + thdd * ux - thd2 * uy + thd * vx * 2.0 + ay;
            let (fx, fy) = (alx * pt.mass, aly * pt.mass);
            out[0] += cs * fx - sn * fy;
            out[1] += sn * fx + cs * fy;
            out[2] += ux * fy - uy * fx;
            for k in 0..n {
                out[3 + k] += fy * pt.phi[k] - fx * pt.ga(am, k);
            }
            if let Some((mom, rjo, kap, dphi)) = rot_terms {
                // ∂s/∂a_k gains R(β)Jo κφ′_k; the rotary inertia J ψ̈ (ψ = θ + β)
                out[2] += mom;
                let along = (rjo[0] * fx + rjo[1] * fy + mom) * kap;
                for k in 0..n {
                    out[3 + k] += along * dphi[k];
                }
            }
        }
    }

    /// A point's local kinematics s = ū (+ R(β)o), ṡ, s̈ at the amplitudes (a, ȧ, ä) and, for a
    /// section body, (β̈, J, R(β)Jo, κ, φ′) ([`ModalBody::section`]).
    #[allow(clippy::type_complexity)]
    fn point_local<'p, T: Real>(
        &self,
        pt: &'p BodyPoint,
        (am, vm, acc): (&[T], &[T], &[T]),
    ) -> (
        [T; 2],
        [T; 2],
        [T; 2],
        Option<(T, f64, [T; 2], T, &'p Vec<f64>)>,
    ) {
        let n = self.modes();
        let (c, w) = pt.plane(am, vm, acc);
        let (mut ux, mut uy) = (c[0] + pt.x, w[0]);
        let (mut vx, mut vy) = (c[1], w[1]);
        let (mut ax, mut ay) = (c[2], w[2]);
        let mut section = None;
        if let Some((j, o, dphi)) = &pt.body {
            let mut sl = [T::zero(); 3];
            for k in 0..n {
                sl[0] += am[k] * dphi[k];
                sl[1] += vm[k] * dphi[k];
                sl[2] += acc[k] * dphi[k];
            }
            let (bd, bdd, ro, rjo, kap) = self.section(*o, sl);
            ux += ro[0];
            uy += ro[1];
            vx += rjo[0] * bd;
            vy += rjo[1] * bd;
            ax += rjo[0] * bdd - ro[0] * bd * bd;
            ay += rjo[1] * bdd - ro[1] * bd * bd;
            section = Some((bdd, *j, rjo, kap, dphi));
        }
        ([ux, uy], [vx, vy], [ax, ay], section)
    }

    /// The d'Alembert load of the part [0, ξ] of the body at (q, q̇, q̈) under the fields `g`
    /// ([`crate::model::component::Element::partial_load`]): ∫ρA(g − r̈) + q and its moment
    /// about `about` on the cut's composite rule ([`CutTable`]), r̈ = R̈ + A(θ̈Jū − θ̇²ū +
    /// 2θ̇Ju̇̄ + ǖ) with the foreshortening of a nonlinear body, ū = (x − ½∫₀ˣw′²dx, w); with
    /// the point masses and section bodies at x < ξL (their own kinematics, as in the
    /// residual, and a section body's rotary inertia J(θ̈ + β̈)). `None` when the body's cut
    /// tables are full.
    pub fn partial_load(
        &self,
        (q, v, a): (&[f64], &[f64], &[f64]),
        g: BodyGravity<2>,
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let n = self.modes();
        let l = self.length;
        let tab = cut_table(&self.cuts, xi, || {
            CutTable::new(&self.basis, xi, |x| match &self.taper {
                Some(t) => (super::taper::line_props(&t.segment, x).rho_a, 0.0),
                None => (self.rho_a, 0.0),
            })
        })?;
        let (am, vm, acc) = (&q[3..3 + n], &v[3..3 + n], &a[3..3 + n]);
        let (sn, cs) = math::sin_cos(q[2]);
        let (thd, thdd) = (v[2], a[2]);
        let to_local = |x: [f64; 2]| [cs * x[0] + sn * x[1], cs * x[1] - sn * x[0]];
        let z = to_local([a[0], a[1]]);
        // the distributed fields, local: a uniform body's g + q/ρA on ρA; a tapered body's g
        // on ρA(x) and q apart
        let (field, line) = match &self.taper {
            None => (to_local(g.distributed), [0.0; 2]),
            Some(t) => (to_local(g.points), to_local(g.line.map(|c| c * t.rho_ref))),
        };
        // local acceleration α = Aᵀr̈ of the point s with rates ṡ, s̈
        let alpha = |u: [f64; 2], ud: [f64; 2], ua: [f64; 2]| {
            [
                z[0] - thdd * u[1] - thd * thd * u[0] - thd * ud[1] * 2.0 + ua[0],
                z[1] + thdd * u[0] - thd * thd * u[1] + thd * ud[0] * 2.0 + ua[1],
            ]
        };
        let (mut fl, mut mz) = ([0.0; 2], 0.0);
        let nonlinear = self.nonlinear;
        tab.for_each(
            n,
            |slope| {
                let f = slope_fields(slope, (am, vm, acc));
                [f[0] * f[0], f[0] * f[1], f[1] * f[1] + f[0] * f[2]]
            },
            |&[x, w, ra, _], phi, c| {
                let f = point_fields(phi, am, vm, acc);
                let c = if nonlinear { c } else { [0.0; 3] };
                let u = [x * l - 0.5 * c[0] / l, f[0]];
                let al = alpha(u, [-c[1] / l, f[1]], [-c[2] / l, f[2]]);
                let load = [
                    w * l * (ra * (field[0] - al[0]) + line[0]),
                    w * l * (ra * (field[1] - al[1]) + line[1]),
                ];
                fl[0] += load[0];
                fl[1] += load[1];
                mz += u[0] * load[1] - u[1] * load[0];
            },
        );
        let gp = to_local(g.points);
        for pt in self.points.iter().filter(|pt| pt.x < xi * l) {
            let (u, ud, ua, section) = self.point_local(pt, (am, vm, acc));
            let al = alpha(u, ud, ua);
            let load = [pt.mass * (gp[0] - al[0]), pt.mass * (gp[1] - al[1])];
            fl[0] += load[0];
            fl[1] += load[1];
            mz += u[0] * load[1] - u[1] * load[0];
            if let Some((bdd, j, ..)) = section {
                mz -= (thdd + bdd) * j;
            }
        }
        // world axes: F = A f_l, M = (R − p) × F + Σ ū × load (the turn keeps the cross product)
        let f = [cs * fl[0] - sn * fl[1], sn * fl[0] + cs * fl[1]];
        let (rx, ry) = (q[0] - about[0], q[1] - about[1]);
        mz += rx * f[1] - ry * f[0];
        Some(([f[0], f[1], 0.0], [0.0, 0.0, mz]))
    }

    /// The exact partial derivatives of [`ModalBody::add_point_forces`] into `out.m`, `out.c`,
    /// `out.k`, column by column by forward-mode automatic differentiation, in the scratch of
    /// `out`.
    fn add_point_matrices(&self, q: &[f64], v: &[f64], a: &[f64], g: [f64; 2], out: &mut BodyOut) {
        let d = self.dim();
        let zero = Dual64::from_re(0.0);
        let ad = &mut out.ad;
        ad.lift((q, v, a), d);
        for j in 0..d {
            for which in 0..3 {
                if which < 2 && j < 2 {
                    continue;
                }
                ad.x[which][j].eps = 1.0;
                ad.r.fill(zero);
                let [xq, xv, xa] = &ad.x;
                let sc = math::sin_cos_dual(xq[2]);
                self.add_point_forces((xq, xv, xa), g, sc, &mut ad.r);
                let mat = match which {
                    0 => &mut out.k,
                    1 => &mut out.c,
                    _ => &mut out.m,
                };
                for (i, ri) in ad.r.iter().enumerate() {
                    mat[(i, j)] += ri.eps;
                }
                ad.x[which][j].eps = 0.0;
            }
        }
    }

    /// The point masses' kinetic energy Σ ½m|ṙ|² and gravity potential −Σ m gᵀr [J].
    fn point_energies(&self, q: &[f64], v: &[f64], g: [f64; 2]) -> (f64, f64) {
        let n = self.modes();
        let rot_a = rot(q[2]);
        let (am, vm) = (&q[3..3 + n], &v[3..3 + n]);
        let z = LocalVec::from_elem(0.0, n);
        let rd = Vector2::new(v[0], v[1]);
        let (mut t, mut u) = (0.0, 0.0);
        for pt in &self.points {
            let (c, w) = pt.plane(am, vm, &z);
            let mut ul = Vector2::new(c[0] + pt.x, w[0]);
            let mut ud = Vector2::new(c[1], w[1]);
            if let Some((j, o, dphi)) = &pt.body {
                let sl = [
                    am.iter().zip(dphi).map(|(a, p)| a * p).sum::<f64>(),
                    vm.iter().zip(dphi).map(|(a, p)| a * p).sum::<f64>(),
                    0.0,
                ];
                let (bd, _, ro, rjo, _) = self.section(*o, sl);
                ul += Vector2::new(ro[0], ro[1]);
                ud += Vector2::new(rjo[0], rjo[1]) * bd;
                let spin = v[2] + bd;
                t += 0.5 * j * spin * spin;
            }
            let vl = Vector2::new(-v[2] * ul[1] + ud[0], v[2] * ul[0] + ud[1]);
            let vel = rd + rot_a * vl;
            let r = Vector2::new(q[0], q[1]) + rot_a * ul;
            t += 0.5 * pt.mass * vel.norm_squared();
            u -= pt.mass * (g[0] * r[0] + g[1] * r[1]);
        }
        (t, u)
    }

    /// The linear floating frame instead: ū = [x; w] inside the segment, strain energy
    /// ½aᵀKa, the tip's foreshortening ½aᵀGa/L with the basis's G
    /// ([`ModalBasis::slope_gram`]) and its angle θ + w′(L) (the body before the nonlinear
    /// terms; for comparisons with linear theory and with the spatial modal body).
    pub fn linear(mut self) -> Self {
        self.nonlinear = false;
        self.gram.clone_from(&self.basis.slope_gram);
        self
    }

    /// Number of modal coordinates.
    pub fn modes(&self) -> usize {
        self.k.len()
    }

    /// Local coordinate count 3 + n.
    pub fn dim(&self) -> usize {
        3 + self.modes()
    }

    /// Mass ρAL [kg].
    pub fn mass(&self) -> f64 {
        match &self.taper {
            None => self.rho_a * self.length,
            Some(t) => t.mu,
        }
    }

    /// Natural frequencies of the clamped segment ω_k [rad/s].
    pub fn omegas(&self) -> Vec<f64> {
        match &self.taper {
            None => self.k.iter().map(|k| (k / self.mass()).sqrt()).collect(),
            Some(t) => t.omega_z.clone(),
        }
    }

    /// (∫ρA x dx, ∫ρA x² dx) [kg m, kg m²]: ½ρAL² and ρAL³/3 on a uniform body.
    fn moments(&self) -> (f64, f64) {
        match &self.taper {
            None => (
                0.5 * self.rho_a * self.length * self.length,
                self.rho_a * self.length.powi(3) / 3.0,
            ),
            Some(t) => (t.s0, t.j0),
        }
    }

    /// The state's quantities shared by the linear residual and its matrices.
    fn linear_terms(&self, q: &[f64], v: &[f64], a: &[f64], g: [f64; 2]) -> LinearTerms {
        let n = self.modes();
        let mu = self.mass();
        let (s0, j0) = self.moments();
        let (th, thd, thdd) = (q[2], v[2], a[2]);
        let am = &q[3..];
        let vm = &v[3..];
        let acc = &a[3..];
        let rot_a = rot(th);
        let sfa = self.dot_sf(am);
        let sfv = self.dot_sf(vm);
        let sfacc = self.dot_sf(acc);
        // a tapered body: aᵀMa/m and aᵀMȧ/m (the uniform body's M = mI)
        let (a2, av) = match &self.taper {
            None => (
                am.iter().map(|x| x * x).sum(),
                am.iter().zip(vm).map(|(x, y)| x * y).sum(),
            ),
            Some(t) => {
                let (mut a2, mut av) = (0.0, 0.0);
                for k in 0..n {
                    let ma = t.mass_times(am, k);
                    a2 += ma * am[k];
                    av += ma * vm[k];
                }
                (a2 / mu, av / mu)
            }
        };
        let z = Vector2::new(a[0] - g[0], a[1] - g[1]);
        let zl = rot_a.transpose() * z;
        LinearTerms {
            n,
            mu,
            s0,
            j0,
            thd,
            thdd,
            rot_a,
            sfa,
            sfv,
            sfacc,
            a2,
            av,
            z,
            zl,
        }
    }

    fn dot_sf(&self, x: &[f64]) -> f64 {
        self.s_f.iter().zip(x).map(|(a, b)| a * b).sum()
    }

    /// Residual and its derivatives at (q, q̇, q̈) for gravity g. With `matrices` false only
    /// `res` is filled.
    pub fn eval(
        &self,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        g: impl Into<BodyGravity<2>>,
        matrices: bool,
        out: &mut BodyOut,
    ) {
        let grav = g.into();
        let BodyGravity {
            points: gp,
            distributed: g,
            ..
        } = grav;
        // a tapered body: its mass feels gravity alone, the line load apart (q per length)
        let line = self.taper_line(&grav).map(|x| x.0);
        let g = if self.taper.is_some() { gp } else { g };
        let lt = self.linear_terms(q, v, a, g);
        let LinearTerms {
            n,
            mu,
            s0,
            j0,
            thd,
            thdd,
            rot_a,
            sfa,
            sfv,
            sfacc,
            a2,
            av,
            z,
            zl,
            ..
        } = lt;
        let (am, vm, acc) = (&q[3..], &v[3..], &a[3..]);
        // local part w of F_R = m(R̈ − g) + A w
        let w = Vector2::new(
            -thdd * sfa - 2.0 * thd * sfv - thd * thd * s0,
            thdd * s0 + sfacc - thd * thd * sfa,
        );
        let fr = mu * z + rot_a * w;
        out.res[0] = fr[0];
        out.res[1] = fr[1];
        out.res[2] = thdd * (j0 + mu * a2)
            + (s0 * zl[1] - sfa * zl[0])
            + self.s_x.iter().zip(acc).map(|(s, x)| s * x).sum::<f64>()
            + 2.0 * mu * thd * av;
        if let Some(t) = &self.taper {
            for kk in 0..n {
                let mut f = self.s_f[kk] * zl[1]
                    + self.s_x[kk] * thdd
                    + (t.mass_times(acc, kk) - thd * thd * t.mass_times(am, kk))
                    + row_times(&t.k_z, am, kk);
                if !t.damp_z.is_empty() {
                    f += row_times(&t.damp_z, vm, kk);
                }
                out.res[3 + kk] = f;
            }
            if let Some(ql) = line {
                self.add_line_forces(q, ql, out.res.as_mut_slice());
            }
        } else {
            for kk in 0..n {
                let mut f = self.s_f[kk] * zl[1]
                    + self.s_x[kk] * thdd
                    + mu * (acc[kk] - thd * thd * am[kk])
                    + self.k[kk] * am[kk];
                if !self.d.is_empty() {
                    f += self.d[kk] * vm[kk];
                }
                out.res[3 + kk] = f;
            }
        }
        let ql = line.unwrap_or([0.0; 2]);
        if self.nonlinear {
            let sc = (rot_a[(1, 0)], rot_a[(0, 0)]);
            self.fields_f64(q, v, a, &mut out.buf);
            let r = out.res.as_mut_slice();
            self.add_nonlinear_fields(v, a, (g, ql), sc, r, &mut out.buf);
        }
        if !self.points.is_empty() {
            let sc = (rot_a[(1, 0)], rot_a[(0, 0)]);
            self.add_point_forces((q, v, a), gp, sc, out.res.as_mut_slice());
        }
        if !matrices {
            return;
        }
        self.linear_matrices(q, v, &lt, out);
        if let Some(ql) = line {
            self.add_line_matrices(q, ql, out);
        }
        if self.nonlinear {
            self.add_nonlinear_matrices(q, v, a, (g, ql), out);
        }
        if !self.points.is_empty() {
            self.add_point_matrices(q, v, a, gp, out);
        }
    }

    /// The partial derivatives of the linear part of the residual into `out.m`, `out.c`, `out.k`.
    fn linear_matrices(&self, q: &[f64], v: &[f64], lt: &LinearTerms, out: &mut BodyOut) {
        let LinearTerms {
            n,
            mu,
            s0,
            j0,
            thd,
            thdd,
            rot_a,
            sfa,
            sfv,
            sfacc,
            a2,
            av,
            zl,
            ..
        } = *lt;
        let (am, vm) = (&q[3..], &v[3..]);
        let w = Vector2::new(
            -thdd * sfa - 2.0 * thd * sfv - thd * thd * s0,
            thdd * s0 + sfacc - thd * thd * sfa,
        );
        out.m.fill(0.0);
        out.c.fill(0.0);
        out.k.fill(0.0);
        let ey = rot_a.column(1).into_owned(); // A e_y
        let ajsv = rot_a * Vector2::new(-sfa, s0); // A J Sv
                                                   // mass matrix
        out.m[(0, 0)] = mu;
        out.m[(1, 1)] = mu;
        for i in 0..2 {
            out.m[(i, 2)] = ajsv[i];
            out.m[(2, i)] = ajsv[i];
        }
        out.m[(2, 2)] = j0 + mu * a2;
        for kk in 0..n {
            for i in 0..2 {
                out.m[(i, 3 + kk)] = ey[i] * self.s_f[kk];
                out.m[(3 + kk, i)] = ey[i] * self.s_f[kk];
            }
            out.m[(2, 3 + kk)] = self.s_x[kk];
            out.m[(3 + kk, 2)] = self.s_x[kk];
            out.m[(3 + kk, 3 + kk)] = mu;
        }
        if let Some(t) = &self.taper {
            for i in 0..n {
                for j in 0..n {
                    out.m[(3 + i, 3 + j)] = t.mass[i * n + j];
                }
            }
        }
        // ∂F/∂q̇
        let dw_dthd = Vector2::new(-2.0 * sfv - 2.0 * thd * s0, -2.0 * thd * sfa);
        let c_r = rot_a * dw_dthd;
        out.c[(0, 2)] = c_r[0];
        out.c[(1, 2)] = c_r[1];
        out.c[(2, 2)] = 2.0 * mu * av;
        for kk in 0..n {
            let c_rk = rot_a * Vector2::new(-2.0 * thd * self.s_f[kk], 0.0);
            out.c[(0, 3 + kk)] = c_rk[0];
            out.c[(1, 3 + kk)] = c_rk[1];
            out.c[(2, 3 + kk)] = 2.0 * mu * thd * am[kk];
            out.c[(3 + kk, 2)] = -2.0 * thd * mu * am[kk];
            out.c[(3 + kk, 3 + kk)] = if self.d.is_empty() { 0.0 } else { self.d[kk] };
        }
        // ∂F/∂q (R does not appear)
        let dfr_dth = rot_a * perp(w);
        out.k[(0, 2)] = dfr_dth[0];
        out.k[(1, 2)] = dfr_dth[1];
        out.k[(2, 2)] = -s0 * zl[0] - sfa * zl[1];
        for kk in 0..n {
            let sk = self.s_f[kk];
            let dfr_da = rot_a * Vector2::new(-thdd * sk, -thd * thd * sk);
            out.k[(0, 3 + kk)] = dfr_da[0];
            out.k[(1, 3 + kk)] = dfr_da[1];
            out.k[(2, 3 + kk)] = 2.0 * thdd * mu * am[kk] - sk * zl[0] + 2.0 * mu * thd * vm[kk];
            out.k[(3 + kk, 2)] = -sk * zl[0];
            out.k[(3 + kk, 3 + kk)] = -thd * thd * mu + self.k[kk];
        }
        if let Some(t) = &self.taper {
            // M a, M ȧ in place of m a, m ȧ; the full M, K, D blocks
            for kk in 0..n {
                let (ma, mv) = (t.mass_times(am, kk), t.mass_times(vm, kk));
                let sk = self.s_f[kk];
                out.c[(2, 3 + kk)] = 2.0 * thd * ma;
                out.c[(3 + kk, 2)] = -2.0 * thd * ma;
                out.k[(2, 3 + kk)] = 2.0 * thdd * ma - sk * zl[0] + 2.0 * thd * mv;
                for j in 0..n {
                    let ij = kk * n + j;
                    out.c[(3 + kk, 3 + j)] = if t.damp_z.is_empty() {
                        0.0
                    } else {
                        t.damp_z[ij]
                    };
                    out.k[(3 + kk, 3 + j)] = -thd * thd * t.mass[ij] + t.k_z[ij];
                }
            }
        }
    }

    /// A tapered body's line load `qw` [N/m] (world axes; ql = Aᵀq) on the linear frame's
    /// kinematics ū = (x, w), added to `res`: its generalized force −∫(∂r/∂q)ᵀq dx, F_R = −Lq,
    /// F_θ = −∫(Jū)·ql dx = −(½L² ql_y − (Σ_k L∫φ_k dξ a_k) ql_x), F_a = −L∫φ_k dξ ql_y (the
    /// foreshortening's part in [`ModalBody::add_nonlinear_fields`]).
    fn add_line_forces(&self, q: &[f64], qw: [f64; 2], res: &mut [f64]) {
        let Some(t) = self.taper.as_deref() else {
            return;
        };
        let n = self.modes();
        let l = self.length;
        let ql = rot(q[2]).transpose() * Vector2::new(qw[0], qw[1]);
        res[0] -= l * qw[0];
        res[1] -= l * qw[1];
        let fa: f64 = t.line_f.iter().zip(&q[3..3 + n]).map(|(f, a)| f * a).sum();
        res[2] -= 0.5 * l * l * ql[1] - fa * ql[0];
        for k in 0..n {
            res[3 + k] -= t.line_f[k] * ql[1];
        }
    }

    /// The partial derivatives of [`ModalBody::add_line_forces`] into `out.k` (q is dead in
    /// world axes: ∂(Aᵀq)/∂θ = (ql_y, −ql_x)).
    fn add_line_matrices(&self, q: &[f64], qw: [f64; 2], out: &mut BodyOut) {
        let Some(t) = self.taper.as_deref() else {
            return;
        };
        let n = self.modes();
        let l = self.length;
        let ql = rot(q[2]).transpose() * Vector2::new(qw[0], qw[1]);
        let dq = (ql[1], -ql[0]);
        let fa: f64 = t.line_f.iter().zip(&q[3..3 + n]).map(|(f, a)| f * a).sum();
        out.k[(2, 2)] -= 0.5 * l * l * dq.1 - fa * dq.0;
        for k in 0..n {
            out.k[(2, 3 + k)] += t.line_f[k] * ql[0];
            out.k[(3 + k, 2)] -= t.line_f[k] * dq.1;
        }
    }

    /// The per-point fields of the nonlinear terms into `buf` (`FIELDS` slots per point of the
    /// body's quadrature): w, ẇ, ẅ, w′, ẇ′, ẅ′, w″ (x-derivatives), the foreshortening
    /// c = −½∫₀ˣ w′² dx with its rates ċ, c̈ (the cumulative integral on the quadrature's own
    /// points, [`Nonlinear::s`]) and ẇ″.
    fn fields<T: Real>(&self, q: &[T], v: &[T], a: &[T], buf: &mut Vec<T>) {
        let n = self.modes();
        let nl = &self.nl;
        let np = nl.w.len();
        buf.clear();
        buf.resize(FIELDS * np, T::zero());
        let (qa, va, aa) = (&q[3..3 + n], &v[3..3 + n], &a[3..3 + n]);
        for (f, phi) in buf.chunks_exact_mut(FIELDS).zip(nl.phi.chunks_exact(n)) {
            let pf = point_fields(phi, qa, va, aa);
            f[..7].copy_from_slice(&pf[..7]);
            f[10] = pf[7];
        }
        self.foreshortening_fields(buf);
    }

    /// [`ModalBody::fields`] on f64: the same values (the same operations in the same order
    /// for each point), two points at a time from [`Nonlinear::phi_pairs`] (the pair's
    /// fourteen sums held in registers).
    fn fields_f64(&self, q: &[f64], v: &[f64], a: &[f64], buf: &mut Vec<f64>) {
        let n = self.modes();
        let nl = &self.nl;
        let np = nl.w.len();
        buf.clear();
        buf.resize(FIELDS * np, 0.0);
        let (qa, va, aa) = (&q[3..3 + n], &v[3..3 + n], &a[3..3 + n]);
        for (b, tab) in nl.phi_pairs.chunks_exact(6 * n).enumerate() {
            let mut acc = [[0.0f64; 2]; 8];
            for (((t, &x), &y), &z) in tab.chunks_exact(6).zip(qa).zip(va).zip(aa) {
                for i in 0..2 {
                    acc[0][i] += x * t[i];
                    acc[1][i] += y * t[i];
                    acc[2][i] += z * t[i];
                    acc[3][i] += x * t[2 + i];
                    acc[4][i] += y * t[2 + i];
                    acc[5][i] += z * t[2 + i];
                    acc[6][i] += x * t[4 + i];
                    acc[7][i] += y * t[4 + i];
                }
            }
            for i in 0..2.min(np - 2 * b) {
                let f = &mut buf[FIELDS * (2 * b + i)..FIELDS * (2 * b + i) + 7];
                for (slot, sum) in f.iter_mut().zip(&acc) {
                    *slot = sum[i];
                }
                buf[FIELDS * (2 * b + i) + 10] = acc[7][i];
            }
        }
        self.foreshortening_fields(buf);
    }

    /// The foreshortening slots 7–9 of [`ModalBody::fields`] from the slopes in slots 3–5.
    fn foreshortening_fields<T: Real>(&self, buf: &mut [T]) {
        let nl = &self.nl;
        let l = self.length;
        // ∫₀^ξ (w′², w′ẇ′, ẇ′² + w′ẅ′) dξ over the panels before
        let mut done = [T::zero(); 3];
        for (panel, pts) in buf.chunks_exact_mut(5 * FIELDS).enumerate() {
            let mut sq = [[T::zero(); 3]; 5];
            for (j, f) in pts.chunks_exact(FIELDS).enumerate() {
                sq[j] = [f[3] * f[3], f[3] * f[4], f[4] * f[4] + f[3] * f[5]];
            }
            for (i, f) in pts.chunks_exact_mut(FIELDS).enumerate() {
                let mut cum = done;
                for j in 0..5 {
                    for r in 0..3 {
                        cum[r] += sq[j][r] * nl.s[i][j];
                    }
                }
                f[7] = cum[0] * (-0.5 * l);
                f[8] = cum[1] * -l;
                f[9] = cum[2] * -l;
            }
            for j in 0..5 {
                for r in 0..3 {
                    done[r] += sq[j][r] * nl.w[5 * panel + j];
                }
            }
        }
    }

    /// Adds to `out` the part of the residual that the linear floating frame leaves out: the
    /// foreshortening c(x) = −½∫₀ˣ w′² dx of every point (ū = [x + c; w], so ∂ū/∂a_k =
    /// [−∫₀ˣ w′φ_k′ dξ; φ_k]) in the inertia and gravity forces, and the elastic force of the
    /// inextensible curvature κ = w″(1 + ½w′²) beyond ½aᵀKa, all on the body's quadrature.
    /// With ρ̈ = Aᵀ(r̈ − g) = Z + α⁰ + αᶜ (Z = Aᵀ(R̈ − g); α⁰ the linear frame's point
    /// acceleration, αᶜ = [c̈ − θ̇²c; θ̈c + 2θ̇ċ]) and m_p = ρA L W_p:
    /// ΔF_R = A Σ m αᶜ, ΔF_θ = Σ m [c(Z + α⁰ + αᶜ)_y − w αᶜ_x + x αᶜ_y],
    /// ΔF_a = Σ m [φ αᶜ_y − s (Z + α⁰ + αᶜ)_x] + ∂U_nl/∂a, s = ∂(−c)/∂a, summed as
    /// Σ_p φ′_p w′_p N_p with the axial force N_p = Σ_q m_q (Z + α⁰ + αᶜ)_x,q V_qp.
    /// Generic over the scalar (f64 residuals, [`Dual64`] for the exact Jacobians); `(sn, cs)`
    /// = (sin θ, cos θ); the state's [`ModalBody::fields`] in `buf` (which it overwrites).
    /// `(g, qw)`: gravity and a tapered body's line load [N/m] (world; zero on a uniform body,
    /// whose `g` carries it): on a tapered body m_p = ρA(x_p)L W_p, EI = EI(x_p), and the line
    /// load is the field q/ρA(x_p) beside g.
    fn add_nonlinear_fields<T: Real>(
        &self,
        v: &[T],
        a: &[T],
        (g, qw): ([f64; 2], [f64; 2]),
        (sn, cs): (T, T),
        out: &mut [T],
        buf: &mut [T],
    ) {
        let n = self.modes();
        let nl = &self.nl;
        let l = self.length;
        let (thd, thdd) = (v[2], a[2]);
        let thd2 = thd * thd;
        let (gx, gy) = (a[0] - g[0], a[1] - g[1]);
        let (zx, zy) = (cs * gx + sn * gy, cs * gy - sn * gx);
        let (mut frx, mut fry, mut fth) = (T::zero(), T::zero(), T::zero());
        let ml = self.rho_a * l;
        let taper = self.taper.as_deref();
        let line = qw != [0.0; 2];
        let (qx, qy) = (cs * qw[0] + sn * qw[1], cs * qw[1] - sn * qw[0]);
        for (p, f) in buf.chunks_exact_mut(FIELDS).enumerate() {
            let (w, wd, wdd) = (f[0], f[1], f[2]);
            let (c, cd, cdd) = (f[7], f[8], f[9]);
            let x = nl.xi[p] * l;
            let (m, zx, zy) = match taper {
                None => (ml * nl.w[p], zx, zy),
                Some(t) if line => (t.m_p[p], zx - qx * t.inv_rho_p[p], zy - qy * t.inv_rho_p[p]),
                Some(t) => (t.m_p[p], zx, zy),
            };
            let acx = cdd - thd2 * c;
            let acy = thdd * c + thd * cd * 2.0;
            let a0x = -(thdd * w) - thd2 * x - thd * wd * 2.0;
            let a0y = thdd * x - thd2 * w + wdd;
            frx += acx * m;
            fry += acy * m;
            fth += (c * (zy + a0y + acy) - w * acx + acy * x) * m;
            // slot 8: m (Z + α)_x; slot 9: the coefficient of φ_p
            f[8] = (zx + a0x + acx) * m;
            f[9] = acy * m;
        }
        out[0] += cs * frx - sn * fry;
        out[1] += sn * frx + cs * fry;
        out[2] += fth;
        // N_p from the panels after and the own panel; coefficients of φ′_p/L, φ″_p/L²
        let tau = self.damping_time;
        nl.for_each_axial_force(buf, FIELDS, 8, |p, f, axial| {
            let (sg, kap) = (f[3], f[6]);
            let e = match taper {
                None => self.ei * l * nl.w[p],
                Some(t) => t.ei_z_p[p] * l * nl.w[p],
            };
            let s2 = sg * sg;
            // U_nl = ½EI∫w″²(w′² + ¼w′⁴)dx
            // ∂c_q/∂a = −L Σ_p V_qp w′_p φ′_p/L
            f[7] = kap * kap * (sg + s2 * sg * 0.5) * e - sg * axial * l;
            f[8] = kap * (s2 + s2 * s2 * 0.25) * e;
            if tau > 0.0 {
                // τEI∫(κ̇ ∂κ/∂a − ẇ″φ″)dx, κ = w″h, h = 1 + ½w′², ∂κ/∂a = φ″h + w″w′φ′
                let (sd, kd) = (f[4], f[10]);
                let h1 = s2 * 0.5;
                let kap_dot = kd * (h1 + 1.0) + kap * sg * sd;
                let et = e * tau;
                f[7] += kap_dot * kap * sg * et;
                f[8] += (kap_dot * (h1 + 1.0) - kd) * et;
            }
        });
        let fa = &mut out[3..3 + n];
        for (f, phi) in buf.chunks_exact(FIELDS).zip(nl.phi.chunks_exact(n)) {
            let (c0, c1, c2) = (f[9], f[7], f[8]);
            for (o, ph) in fa.iter_mut().zip(phi) {
                *o += c0 * ph[0] + c1 * ph[1] + c2 * ph[2];
            }
        }
    }

    /// Adds the exact partial derivatives of [`ModalBody::add_nonlinear_fields`] to `out.m`,
    /// `out.c`, `out.k`, column by column by forward-mode automatic differentiation (R and Ṙ do
    /// not appear), in the scratch of `out`. The per-point fields' first seven slots are linear
    /// in the modal coordinates: their values are computed once and a modal column's
    /// derivatives are the shapes' values (what the dual sums of [`ModalBody::fields`] give,
    /// bit for bit); only the foreshortening and the forces run on dual numbers.
    #[inline(never)]
    fn add_nonlinear_matrices(
        &self,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        g: ([f64; 2], [f64; 2]),
        out: &mut BodyOut,
    ) {
        let d = self.dim();
        let n = self.modes();
        let zero = Dual64::from_re(0.0);
        let ad = &mut out.ad;
        ad.lift((q, v, a), d);
        self.fields_f64(q, v, a, &mut ad.base);
        for j in 0..d {
            for which in 0..3 {
                if which < 2 && j < 2 {
                    continue;
                }
                ad.x[which][j].eps = 1.0;
                ad.r.fill(zero);
                ad.buf.clear();
                ad.buf.extend(ad.base.iter().map(|&f| Dual64::from_re(f)));
                if j >= 3 {
                    // ∂/∂ of the modal coordinate k: its shape in the slots it enters
                    // (ẅ″ is not a field)
                    let slots = [[0, 3, 6], [1, 4, 10], [2, 5, 8]][which];
                    let phis = self.nl.phi[j - 3..].iter().step_by(n);
                    for (f, ph) in ad.buf.chunks_exact_mut(FIELDS).zip(phis) {
                        for (&s, &p) in slots.iter().zip(ph).take(3 - usize::from(which == 2)) {
                            f[s].eps = p;
                        }
                    }
                }
                self.foreshortening_fields(&mut ad.buf);
                let [xq, xv, xa] = &ad.x;
                let sc = math::sin_cos_dual(xq[2]);
                self.add_nonlinear_fields(xv, xa, g, sc, &mut ad.r, &mut ad.buf);
                let mat = match which {
                    0 => &mut out.k,
                    1 => &mut out.c,
                    _ => &mut out.m,
                };
                for (i, ri) in ad.r.iter().enumerate() {
                    mat[(i, j)] += ri.eps;
                }
                ad.x[which][j].eps = 0.0;
            }
        }
    }

    /// Kinetic energy ½ q̇ᵀ M(q) q̇ [J].
    pub fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let n = self.modes();
        let mu = self.mass();
        let (s0, j0) = self.moments();
        let rot_a = rot(q[2]);
        let am = &q[3..];
        let vm = &v[3..];
        let sfa = self.dot_sf(am);
        let a2: f64 = match &self.taper {
            None => am.iter().map(|x| x * x).sum(),
            Some(t) => (0..n).map(|k| t.mass_times(am, k) * am[k]).sum::<f64>() / mu,
        };
        let rd = Vector2::new(v[0], v[1]);
        let ajsv = rot_a * Vector2::new(-sfa, s0);
        let ey = rot_a.column(1).into_owned();
        let mut t =
            mu * rd.norm_squared() + v[2] * v[2] * (j0 + mu * a2) + 2.0 * v[2] * ajsv.dot(&rd);
        for kk in 0..n {
            t += 2.0 * vm[kk] * (self.s_f[kk] * ey.dot(&rd) + self.s_x[kk] * v[2]);
            t += match &self.taper {
                None => mu * vm[kk] * vm[kk],
                Some(tp) => tp.mass_times(vm, kk) * vm[kk],
            };
        }
        // the foreshortening's part: |V⁰ + (ċ, θ̇c)|² − |V⁰|² at the quadrature points, V⁰ the
        // linear frame's local point velocity
        let tp = |t: f64| {
            if self.points.is_empty() {
                t
            } else {
                t + self.point_energies(q, v, [0.0; 2]).0
            }
        };
        if !self.nonlinear {
            return tp(0.5 * t);
        }
        let mut buf = self.fields_buf.take();
        self.fields(q, v, &LocalVec::from_elem(0.0, q.len()), &mut buf);
        let rl = rot_a.transpose() * rd;
        let ml = self.rho_a * self.length;
        for (p, f) in buf.chunks_exact(FIELDS).enumerate() {
            let (w, wd, c, cd) = (f[0], f[1], f[7], f[8]);
            let x = self.nl.xi[p] * self.length;
            let (v0x, v0y) = (rl[0] - v[2] * w, rl[1] + v[2] * x + wd);
            let dv = (cd, v[2] * c);
            let m = match &self.taper {
                None => ml * self.nl.w[p],
                Some(tp) => tp.m_p[p],
            };
            t += m * (2.0 * (v0x * dv.0 + v0y * dv.1) + dv.0 * dv.0 + dv.1 * dv.1);
        }
        self.fields_buf.put(buf);
        tp(0.5 * t)
    }

    /// Strain energy ½EI∫κ²dx with κ = w″(1 + ½w′²): ½ aᵀ K a plus ½EI∫w″²(w′² + ¼w′⁴)dx on
    /// the body's quadrature [J].
    pub fn strain_energy(&self, q: &[f64]) -> f64 {
        let am = &q[3..3 + self.modes()];
        let lin = match &self.taper {
            None => 0.5 * self.k.iter().zip(am).map(|(k, a)| k * a * a).sum::<f64>(),
            Some(t) => {
                0.5 * (0..am.len())
                    .map(|k| row_times(&t.k_z, am, k) * am[k])
                    .sum::<f64>()
            }
        };
        if !self.nonlinear {
            return lin;
        }
        let mut buf = self.fields_buf.take();
        let z = LocalVec::from_elem(0.0, q.len());
        self.fields(q, &z, &z, &mut buf);
        if let Some(t) = &self.taper {
            let nl: f64 = buf
                .chunks_exact(FIELDS)
                .zip(self.nl.w.iter().zip(&t.ei_z_p))
                .map(|(f, (w, ei))| {
                    let s2 = f[3] * f[3];
                    w * ei * f[6] * f[6] * (s2 + 0.25 * s2 * s2)
                })
                .sum();
            self.fields_buf.put(buf);
            return lin + 0.5 * self.length * nl;
        }
        let nl: f64 = buf
            .chunks_exact(FIELDS)
            .zip(&self.nl.w)
            .map(|(f, w)| {
                let s2 = f[3] * f[3];
                w * f[6] * f[6] * (s2 + 0.25 * s2 * s2)
            })
            .sum();
        self.fields_buf.put(buf);
        lin + 0.5 * self.ei * self.length * nl
    }

    /// Gravity potential −gᵀ∫ρA r dx [J] (the foreshortening on the body's quadrature), with a
    /// line load's −∫qᵀr dx when `g` carries one ([`ModalBody::gravity`]).
    pub fn potential_energy(&self, q: &[f64], g: impl Into<BodyGravity<2>>) -> f64 {
        let grav = g.into();
        let BodyGravity {
            points: gp,
            distributed: g,
            ..
        } = grav;
        let (s0, _) = self.moments();
        let mut buf = self.fields_buf.take();
        let z = LocalVec::from_elem(0.0, q.len());
        if self.nonlinear {
            self.fields(q, &z, &z, &mut buf);
        } else {
            buf.clear();
        }
        let short: f64 = match &self.taper {
            None => {
                buf.chunks_exact(FIELDS)
                    .zip(&self.nl.w)
                    .map(|(f, w)| w * f[7])
                    .sum::<f64>()
                    * self.rho_a
                    * self.length
            }
            Some(t) => buf
                .chunks_exact(FIELDS)
                .zip(&t.m_p)
                .map(|(f, m)| m * f[7])
                .sum(),
        };
        let first = self.mass() * Vector2::new(q[0], q[1])
            + rot(q[2]) * Vector2::new(s0 + short, self.dot_sf(&q[3..]));
        let mut u = if self.taper.is_some() {
            -(gp[0] * first[0] + gp[1] * first[1])
        } else {
            -(g[0] * first[0] + g[1] * first[1])
        };
        if let (Some((qw, _)), Some(t)) = (self.taper_line(&grav), &self.taper) {
            // −qᵀ∫r dx, ∫r dx = L R + A(½L² + ∫c dx, Σ L∫φ_k dξ a_k)
            let l = self.length;
            let c: f64 = buf
                .chunks_exact(FIELDS)
                .zip(&self.nl.w)
                .map(|(f, w)| w * f[7])
                .sum::<f64>()
                * l;
            let fa: f64 = t.line_f.iter().zip(&q[3..]).map(|(f, a)| f * a).sum();
            let r = l * Vector2::new(q[0], q[1]) + rot(q[2]) * Vector2::new(0.5 * l * l + c, fa);
            u -= qw[0] * r[0] + qw[1] * r[1];
        }
        self.fields_buf.put(buf);
        if self.points.is_empty() {
            u
        } else {
            u + self
                .point_energies(q, &LocalVec::from_elem(0.0, q.len()), gp)
                .1
        }
    }

    /// (G a)_k / L: gradient of the tip foreshortening ½ aᵀ G a / L with respect to a_k [-].
    pub fn foreshortening_gradient(&self, q: &[f64]) -> Vec<f64> {
        let mut g = vec![0.0; self.modes()];
        self.foreshortening_gradient_into(q, &mut g);
        g
    }

    /// [`ModalBody::foreshortening_gradient`] into `g` (n values; no allocation).
    pub fn foreshortening_gradient_into(&self, q: &[f64], g: &mut [f64]) {
        let n = self.modes();
        let a = &q[3..3 + n];
        for (gk, row) in g.iter_mut().zip(self.gram.chunks_exact(n)) {
            *gk = row.iter().zip(a).map(|(x, y)| x * y).sum::<f64>() / self.length;
        }
    }

    /// Local position of the tip in the body frame: [L − ½ aᵀ G a / L; Σ φ_k(1) a_k], with
    /// the foreshortening of the deflected segment (G = ∫φ′φ′ dξ on the body's quadrature,
    /// [`ModalBody::gram`]: the ξ = 1 case of the points inside), so that the tip moves inward
    /// as the segment bends and an axial tip load stiffens the modes.
    pub fn tip_local(&self, q: &[f64]) -> Vector2<f64> {
        self.tip_local_into(q, &mut LocalVec::from_elem(0.0, self.modes()))
    }

    /// [`ModalBody::tip_local`], with the [`ModalBody::foreshortening_gradient`] into `g`
    /// (n values; no allocation).
    pub fn tip_local_into(&self, q: &[f64], g: &mut [f64]) -> Vector2<f64> {
        let w: f64 = self.basis.tip.iter().zip(&q[3..]).map(|(p, a)| p * a).sum();
        self.foreshortening_gradient_into(q, g);
        let short: f64 = 0.5 * g.iter().zip(&q[3..]).map(|(g, a)| g * a).sum::<f64>();
        Vector2::new(self.length - short, w)
    }

    /// Elastic slope angle at the tip θ_J = Σ φ_k′(1) a_k / L [rad].
    pub fn tip_slope(&self, q: &[f64]) -> f64 {
        self.basis
            .tip_slope
            .iter()
            .zip(&q[3..])
            .map(|(p, a)| p * a)
            .sum::<f64>()
            / self.length
    }

    /// The centreline at each ξ ∈ [0, 1] of the ascending `xi` at (q, q̇) onto `out`: r = R +
    /// A(θ)ū, ū = (ξL − ½∫₀^ξ w′²dξ/L, w) (the tip's [`ModalBody::tip_local`] at ξ = 1, so the
    /// last sample is the tip port's point), ṙ = Ṙ + θ̇ J A ū + A u̇̄, the section frame of the
    /// tangent, curvature κ = w″(1 + ½w′²) (x-derivatives; the body's strain energy is
    /// ½EI∫κ²dx); no axial strain, no twist.
    pub fn sample(&self, q: &[f64], v: &[f64], xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (a, ad) = (&q[3..], &v[3..]);
        let l = self.length;
        let r = rot(q[2]);
        let mut g = crate::model::component::LocalVec::from_elem(0.0, self.modes());
        self.basis
            .sample_fields([a, ad], [(a, a), (a, ad)], xi, |k, f, [s_aa, s_ad]| {
                let ([w, w1, w2], [wd, _, _]) = (f[0], f[1]);
                let x = xi[k];
                let (u, short_rate) = if x == 1.0 {
                    let u = self.tip_local_into(q, &mut g);
                    (u, g.iter().zip(ad).map(|(g, v)| g * v).sum::<f64>())
                } else {
                    let u = Vector2::new(x * l - 0.5 * s_aa / l, w);
                    (u, s_ad / l)
                };
                let ud = Vector2::new(-short_rate, wd);
                let p = Vector2::new(q[0], q[1]) + r * u;
                let vel = Vector2::new(v[0], v[1]) + v[2] * perp(r * u) + r * ud;
                let t = r * Vector2::new(1.0, w1 / l).normalize();
                out.push(ShapePoint {
                    position: [p.x, p.y, 0.0],
                    velocity: [vel.x, vel.y, 0.0],
                    frame: [[t.x, t.y, 0.0], [-t.y, t.x, 0.0], [0.0, 0.0, 1.0]],
                    curvature: [
                        0.0,
                        w2 / (l * l)
                            * if self.nonlinear {
                                1.0 + 0.5 * (w1 / l) * (w1 / l)
                            } else {
                                1.0
                            },
                    ],
                    ..ShapePoint::default()
                });
            });
    }

    /// Global position of the material point at x = ξL, with its foreshortening
    /// −½∫₀ˣ w′²dx (composite 5-point Gauss, 16 panels on [0, ξ]).
    pub fn point(&self, q: &[f64], xi: f64) -> Vector2<f64> {
        let a = &q[3..];
        let mut phi = Vec::new();
        let slope = |phi: &[[f64; 3]]| -> f64 { phi.iter().zip(a).map(|(p, x)| p[1] * x).sum() };
        let mut short = 0.0;
        for (x, w) in super::basis::quadrature(16) {
            self.basis.eval_all(x * xi, &mut phi);
            short += w * xi * slope(&phi).powi(2);
        }
        self.basis.eval_all(xi, &mut phi);
        let w: f64 = phi.iter().zip(a).map(|(p, x)| p[0] * x).sum();
        Vector2::new(q[0], q[1])
            + rot(q[2]) * Vector2::new(xi * self.length - 0.5 * short / self.length, w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ancf::GAUSS5;

    fn body() -> ModalBody {
        ModalBody::new(ModalBasis::new(3, true), 0.2, 0.0247, 0.165, 0.02, 1e-4)
    }

    #[test]
    fn derivatives_match_central_differences() {
        for b in [body(), body().linear()] {
            derivatives_of(b);
        }
    }

    fn derivatives_of(b: ModalBody) {
        let d = b.dim();
        let q: Vec<f64> = (0..d).map(|i| 0.1 + 0.37 * (i as f64).sin()).collect();
        let v: Vec<f64> = (0..d).map(|i| 0.5 * (1.3 * i as f64).cos()).collect();
        let a: Vec<f64> = (0..d).map(|i| 2.0 * (0.7 * i as f64 + 0.2).sin()).collect();
        let g = [0.3, -9.81];
        let mut o = BodyOut::new(d);
        b.eval(&q, &v, &a, g, true, &mut o);
        let h = 1e-6;
        let mut tmp = BodyOut::new(d);
        let mut col = |which: usize, j: usize| {
            let (mut qp, mut vp, mut ap) = (q.clone(), v.clone(), a.clone());
            let (mut qm, mut vm, mut am) = (q.clone(), v.clone(), a.clone());
            match which {
                0 => {
                    qp[j] += h;
                    qm[j] -= h
                }
                1 => {
                    vp[j] += h;
                    vm[j] -= h
                }
                _ => {
                    ap[j] += h;
                    am[j] -= h
                }
            }
            b.eval(&qp, &vp, &ap, g, false, &mut tmp);
            let fp = tmp.res.clone();
            b.eval(&qm, &vm, &am, g, false, &mut tmp);
            (fp - &tmp.res) / (2.0 * h)
        };
        for j in 0..d {
            for (which, mat) in [(0, &o.k), (1, &o.c), (2, &o.m)] {
                let fd = col(which, j);
                for i in 0..d {
                    // FD round-off is ~ 1e-16·|F|/h
                    let err = (fd[i] - mat[(i, j)]).abs();
                    assert!(
                        err < 1e-7 * (1.0 + mat[(i, j)].abs()) + 1e-9 * o.res.amax(),
                        "{which} [{i},{j}] {} vs {}",
                        fd[i],
                        mat[(i, j)]
                    );
                }
            }
        }
    }

    /// The damping force of a body with retardation time τ (and no damping ratio) is the
    /// Kelvin–Voigt force of its curvature κ = w″(1 + ½w′²): F_k = τEI∫κ̇ ∂κ/∂a_k dx, with κ̇
    /// and ∂κ/∂a_k by central differences of κ computed from the basis here; both on a
    /// 50-panel 5-point Gauss rule (the body's own 2 panels under-integrate the stiff
    /// interface shapes of this state by up to ~20 % of the nonlinear part).
    #[test]
    fn damping_is_kelvin_voigt_on_the_nonlinear_curvature() {
        let tau = 1e-3;
        let basis = ModalBasis::new(3, true);
        let (l, ei) = (0.4, 0.165);
        let fine = |tau| {
            let mut b = ModalBody::new(basis.clone(), l, 0.0247, ei, 0.0, tau);
            b.nl = Nonlinear::new(&basis, 50).scaled(l, basis.len());
            b
        };
        let (damped, undamped) = (fine(tau), fine(0.0));
        let d = damped.dim();
        let n = d - 3;
        let q: Vec<f64> = (0..d)
            .map(|i| if i < 3 { 0.2 } else { 0.01 / (i * i) as f64 })
            .collect();
        let v: Vec<f64> = (0..d).map(|i| 0.7 * (1.3 * i as f64).cos()).collect();
        let a: Vec<f64> = (0..d).map(|i| 2.0 * (0.7 * i as f64 + 0.2).sin()).collect();
        let g = [0.3, -9.81];
        let (mut o1, mut o0) = (BodyOut::new(d), BodyOut::new(d));
        damped.eval(&q, &v, &a, g, false, &mut o1);
        undamped.eval(&q, &v, &a, g, false, &mut o0);
        let force: Vec<f64> = (3..d).map(|i| o1.res[i] - o0.res[i]).collect();
        let kappa = |am: &[f64], xi: f64| {
            let mut phi = Vec::new();
            basis.eval_all(xi, &mut phi);
            let (mut s, mut k) = (0.0, 0.0);
            for (p, x) in phi.iter().zip(am) {
                s += x * p[1] / l;
                k += x * p[2] / (l * l);
            }
            k * (1.0 + 0.5 * s * s)
        };
        let h = 1e-6;
        let shifted = |dir: &[f64], xi: f64| {
            let plus: Vec<f64> = (0..n).map(|k| q[3 + k] + h * dir[k]).collect();
            let minus: Vec<f64> = (0..n).map(|k| q[3 + k] - h * dir[k]).collect();
            (kappa(&plus, xi) - kappa(&minus, xi)) / (2.0 * h)
        };
        let mut want = vec![0.0; n];
        let panels = 50;
        for panel in 0..panels {
            for (t, wt) in GAUSS5 {
                let xi = (panel as f64 + 0.5 * (t + 1.0)) / panels as f64;
                let kd = shifted(&v[3..], xi);
                for (k, f) in want.iter_mut().enumerate() {
                    let mut e = vec![0.0; n];
                    e[k] = 1.0;
                    *f += tau * ei * kd * shifted(&e, xi) * 0.5 * wt / panels as f64 * l;
                }
            }
        }
        let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // the linear part τK ȧ alone misses the nonlinear part by > 1 % of the force
        let nl = (0..n)
            .map(|k| (want[k] - tau * damped.k[k] * v[3 + k]).abs())
            .fold(0.0, f64::max);
        assert!(
            nl > 1e-2 * scale,
            "the state should exercise the nonlinear part: {nl:e}"
        );
        for k in 0..n {
            assert!(
                (force[k] - want[k]).abs() < 1e-7 * scale,
                "mode {k}: {} vs {}",
                force[k],
                want[k]
            );
        }
    }

    #[test]
    fn kinetic_energy_is_half_vmv() {
        let b = body();
        let d = b.dim();
        let q: Vec<f64> = (0..d).map(|i| 0.05 * (i as f64 + 1.0)).collect();
        let v: Vec<f64> = (0..d).map(|i| 0.3 - 0.1 * i as f64).collect();
        let mut o = BodyOut::new(d);
        b.eval(&q, &v, &vec![0.0; d], [0.0, 0.0], true, &mut o);
        let vv = DVector::from_column_slice(&v);
        let t = 0.5 * vv.dot(&(&o.m * &vv));
        let te = b.kinetic_energy(&q, &v);
        assert!((t - te).abs() < 1e-14 * (1.0 + t.abs()), "{t} vs {te}");
    }

    /// Power balance of the undamped free body: with q̈ solving F(q, q̇, q̈) = 0, the total
    /// energy T + U + V_g is stationary, d/dt E = ∇_qE·q̇ + ∇_q̇T·q̈ = 0 (by central
    /// differences of the energy functions along the motion). Checks that the residual is the
    /// Lagrangian of the energies at large deflection (w′ up to ~0.5), velocity terms included.
    #[test]
    fn undamped_body_conserves_energy_along_its_motion() {
        let b = ModalBody::new(ModalBasis::new(3, true), 0.2, 0.0247, 0.165, 0.0, 0.0);
        let d = b.dim();
        let g = [0.3, -9.81];
        let energy = |q: &[f64], v: &[f64]| {
            b.kinetic_energy(q, v) + b.strain_energy(q) + b.potential_energy(q, g)
        };
        for (amp, seed) in [(0.002, 0.3), (0.02, 1.1), (0.04, 2.0)] {
            // amplitudes falling as 1/Λ_k^{1/2} (a smooth deflection: w′ up to ~amp·14/L)
            let fall = |i: usize| {
                if i < 3 {
                    1.0
                } else {
                    (b.k[0] / b.k[i - 3]).sqrt()
                }
            };
            let mut q: Vec<f64> = (0..d)
                .map(|i| amp * fall(i) * (seed + 1.7 * i as f64).sin())
                .collect();
            q[2] = 0.4 + seed;
            let v: Vec<f64> = (0..d)
                .map(|i| 3.0 * amp * fall(i) * (seed + 0.9 * i as f64).cos())
                .collect();
            let mut o = BodyOut::new(d);
            b.eval(&q, &v, &vec![0.0; d], g, true, &mut o);
            let acc = o.m.clone().lu().solve(&(-&o.res)).unwrap();
            b.eval(&q, &v, acc.as_slice(), g, false, &mut o);
            assert!(o.res.amax() < 1e-10 * acc.amax());
            // h ω_max ≈ 1e-4 for the stiffest shape: the O(h²) error of the difference is small
            let h = 1e-8;
            let step = |s: f64| -> f64 {
                let qs: Vec<f64> = (0..d).map(|i| q[i] + s * v[i]).collect();
                let vs: Vec<f64> = (0..d).map(|i| v[i] + s * acc[i]).collect();
                energy(&qs, &vs)
            };
            let rate = (step(h) - step(-h)) / (2.0 * h);
            // the scale: the power of the largest force, |∇E|·|q̇| ~ |M q̈|·|q̇|
            let scale = (&o.m * &acc).amax() * v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            // the nonlinear terms' share of the power, to show the check can see them
            let nl = b.strain_energy(&q)
                - 0.5 * b.k.iter().zip(&q[3..]).map(|(k, a)| k * a * a).sum::<f64>();
            eprintln!(
                "amplitude {amp}: dE/dt = {rate:.2e} W, scale {scale:.2e} W, U_nl {nl:.2e} J"
            );
            assert!(
                rate.abs() < 1e-7 * scale,
                "amplitude {amp}: dE/dt = {rate:e} W vs scale {scale:e} W"
            );
        }
    }

    #[test]
    fn frequencies_of_the_clamped_segment_match_euler_bernoulli() {
        // docs/references.md §4c: d = 2 mm steel, L = 0.4 m: f1..f3 = 9.045, 56.68, 158.71 Hz.
        let d: f64 = 0.002;
        let area = std::f64::consts::PI * d * d / 4.0;
        let ei = 2.1e11 * area * d * d / 16.0;
        let b = ModalBody::new(ModalBasis::new(3, false), 0.4, 7850.0 * area, ei, 0.0, 0.0);
        let f: Vec<f64> = b
            .omegas()
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect();
        for (fi, want) in f.iter().zip([9.045, 56.68, 158.71]) {
            assert!((fi / want - 1.0).abs() < 5e-4, "{fi} vs {want}");
        }
    }
}
