//! Spatial floating-frame body with bending modes in both planes and two torsion shapes
//! (docs/references.md §7.3): the kernel of [`crate::model::spatial::ModalElement3`].
//!
//! Local coordinates `q = [R(3), p(4), a_y(nb), a_z(nb), a_t(2)]`: frame origin R [m] (the
//! segment root, world axes), Euler parameters p = (e0, e1, e2, e3) of the body frame → world
//! (scalar first; A(p) = (e0² − eᵀe)I + 2eeᵀ + 2e0ẽ), bending amplitudes a_y (x–y plane, E·i_z)
//! and a_z (x–z plane, E·i_y) [m] on the shapes of a [`ModalBasis`] (∫φ_iφ_j dξ = δ_ij), and
//! torsion amplitudes a_t [rad] on χ₁ = ξ (static twist shape) and χ₂ = √2 sin πξ.
//!
//! A centerline point at x = ξL is at r = R + A ū, ū = (x − ½∫₀ˣ(v′² + w′²)dx, v, w), v = φᵀa_y,
//! w = φᵀa_z; the section turns about the body x axis by θ(ξ) = χᵀa_t and is treated as a
//! spinning rigid disk (kinetic energy ½∫ρI_p(ω̄_x + θ̇)²dx). Geometrically nonlinear as the
//! planar body ([`super::ModalBody`]; docs/references.md §7.6): the foreshortening of every
//! point in the inertia and gravity forces, the inextensible curvatures κ_z = v″(1 + ½v′²) +
//! v′w′w″ and κ_y = w″(1 + ½w′²) (Crespo da Silva & Glynn 1978) in the strain energy, both on
//! the planar body's composite 5-point Gauss rule, added to the linear floating frame's exact
//! terms (`ModalBody3::add_nonlinear`); torsion as before. [`ModalBody3::linear`] is the linear
//! FFRF instead (the foreshortening in the tip port only, [`ModalBody3::tip_local`]; the
//! geometric stiffness K_G of a held frame by [`ModalBody3::with_stiffening`]).
//! Body angular velocity ω̄ = 2Ēṗ (Ē̇ṗ = 0).
//!
//! The residual is `r = M q̈ − Q_v(q, q̇) − Q_g(q) + K a + D ȧ` in Exudyn's form (the p rows are
//! Ḡᵀ = 2Ēᵀ times the body-frame moment balance about the frame origin; they are defined up to a
//! multiple of p, which the normalization row's multiplier absorbs). [`ModalBody3::residual`] is
//! generic over the scalar: plain f64 for the Newton iterations, [`Dual64`] for the exact
//! Newton block ([`ModalBody3::newton_block`]).

use super::basis::ModalBasis;
use super::body::{cut_cache, cut_table, slope_fields, CutCache, CutTable};
use super::nonlinear::{panels, point_fields, BodyPoint, Nonlinear};
use super::taper::{modal_damping, row_times, Taper};
use super::BodyGravity;
use crate::math;
use crate::model::component::{LocalVec, LOCAL_INLINE};
use crate::model::sample::{minimal_frame, ShapePoint};
use crate::model::section3::{self, SectionBody3, SectionPose};
use crate::model::vector::{add, cross, dot, scale, Real, V3};
use crate::scene::Segment;
use crate::scene::MAX_MODES;
use nalgebra::{Matrix2, Vector2};
use num_dual::{Derivative, DualSVec64};
use smallvec::SmallVec;
use std::f64::consts::{PI, SQRT_2};
use std::sync::Arc;

/// A(p) = (e0² − eᵀe)I + 2eeᵀ + 2e0ẽ, rows (body → world; a rotation for |p| = 1).
#[inline]
pub fn euler_rotation<T: Real>(p: [T; 4]) -> [V3<T>; 3] {
    let [e0, e1, e2, e3] = p;
    let s = e0 * e0 - e1 * e1 - e2 * e2 - e3 * e3;
    let two = T::from(2.0);
    [
        [
            s + two * e1 * e1,
            two * (e1 * e2 - e0 * e3),
            two * (e1 * e3 + e0 * e2),
        ],
        [
            two * (e2 * e1 + e0 * e3),
            s + two * e2 * e2,
            two * (e2 * e3 - e0 * e1),
        ],
        [
            two * (e3 * e1 - e0 * e2),
            two * (e3 * e2 + e0 * e1),
            s + two * e3 * e3,
        ],
    ]
}

/// A v̄.
#[inline]
pub fn mul<T: Real>(a: &[V3<T>; 3], v: V3<T>) -> V3<T> {
    [dot(a[0], v), dot(a[1], v), dot(a[2], v)]
}

/// Aᵀ v.
#[inline]
pub fn mul_t<T: Real>(a: &[V3<T>; 3], v: V3<T>) -> V3<T> {
    let mut o = [T::zero(); 3];
    for i in 0..3 {
        for j in 0..3 {
            o[j] += a[i][j] * v[i];
        }
    }
    o
}

/// Ē(p) (3 × 4, rows): ω̄ = 2Ēṗ is the angular velocity in body axes.
#[inline]
pub fn e_bar<T: Real>(p: [T; 4]) -> [[T; 4]; 3] {
    let [e0, e1, e2, e3] = p;
    [[-e1, e0, e3, -e2], [-e2, -e3, e0, e1], [-e3, e2, -e1, e0]]
}

/// E(p) (3 × 4, rows): ω = 2Eṗ is the angular velocity in world axes.
#[inline]
pub fn e_world<T: Real>(p: [T; 4]) -> [[T; 4]; 3] {
    let [e0, e1, e2, e3] = p;
    [[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]]
}

/// 2 B x for a 3 × 4 matrix B (rows) and a 4-vector x.
#[inline]
fn g_mul<T: Real>(b: &[[T; 4]; 3], x: &[T]) -> V3<T> {
    let mut o = [T::zero(); 3];
    for i in 0..3 {
        for k in 0..4 {
            o[i] += b[i][k] * x[k];
        }
        o[i] *= 2.0;
    }
    o
}

/// Geometry, material and damping of a spatial modal segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalProps3 {
    /// Length L [m].
    pub length: f64,
    /// Mass per length ρA [kg/m].
    pub rho_a: f64,
    /// Torsional rotary inertia per length ρI_p [kg m].
    pub rho_ip: f64,
    /// Bending stiffness in the x–y plane E·i_z [N m²] (the a_y modes).
    pub ei_z: f64,
    /// Bending stiffness in the x–z plane E·i_y [N m²] (the a_z modes).
    pub ei_y: f64,
    /// Torsional stiffness G·J [N m²].
    pub gj: f64,
    /// Modal damping ratio ζ of every mode [-].
    pub damping_ratio: f64,
    /// Kelvin–Voigt retardation time τ [s] of the curvatures: D += τK, and the nonlinear body
    /// adds the rest of τ∫(EI_z κ̇_z ∂κ_z/∂a + EI_y κ̇_y ∂κ_y/∂a)dx.
    pub damping_time: f64,
}

impl ModalProps3 {
    /// The properties of a scene segment.
    pub fn of_segment(seg: &Segment) -> Self {
        let s = seg.section_props();
        Self {
            length: seg.length,
            rho_a: seg.density * s.area,
            rho_ip: seg.density * s.polar,
            ei_z: seg.youngs_modulus * s.i_z,
            ei_y: seg.youngs_modulus * s.i_y,
            gj: seg.shear_modulus() * s.torsion,
            damping_ratio: seg.damping_ratio,
            damping_time: seg.damping_time,
        }
    }
}

pub use super::basis::{torsion_shapes, TORSION_SHAPES};

/// Constant properties and invariants of a spatial modal segment.
#[derive(Debug, Clone)]
pub struct ModalBody3 {
    /// Bending shape basis (both planes).
    pub basis: ModalBasis,
    /// Geometry and material.
    pub props: ModalProps3,
    /// Modal stiffness of the a_y modes E·i_z Λ_k/L³ [N/m].
    pub k_y: Vec<f64>,
    /// Modal stiffness of the a_z modes E·i_y Λ_k/L³ [N/m].
    pub k_z: Vec<f64>,
    /// Modal damping of the a_y modes 2ζω_kρAL + τK_k [N s/m] (zero if undamped).
    pub d_y: Vec<f64>,
    /// Modal damping of the a_z modes [N s/m].
    pub d_z: Vec<f64>,
    /// Torsion mass ρI_p L ∫χ_iχ_j dξ [kg m²].
    pub m_t: [[f64; 2]; 2],
    /// Torsion stiffness GJ/L ∫χ_i′χ_j′ dξ [N m].
    pub k_t: [[f64; 2]; 2],
    /// Torsion damping: ζ per torsion mode of (M_t, K_t) plus τK_t [N m s].
    pub d_t: [[f64; 2]; 2],
    /// ρI_p L ∫χ_m dξ [kg m²]: coupling of a_t with the frame's spin ω̄_x.
    pub c_t: [f64; 2],
    /// χ_m(1): tip twist θ_T = χ(1)ᵀa_t.
    pub chi_tip: [f64; 2],
    /// ρA L ∫φ_k dξ [kg].
    pub s_f: Vec<f64>,
    /// ρA L² ∫ξφ_k dξ [kg m].
    pub s_x: Vec<f64>,
    /// G1 = ∫(1 − ξ)φ_i′φ_j′ dξ and G2 = ∫½(1 − ξ²)φ_i′φ_j′ dξ (row-major nb × nb): the
    /// geometric stiffness of the axial inertia and centrifugal forces (docs/references.md §7.4).
    pub g1: Vec<f64>,
    /// See [`ModalBody3::g1`].
    pub g2: Vec<f64>,
    /// Whether the bending rows carry the geometric stiffness K_G = ρAL(ω̄_y² + ω̄_z²)G2 −
    /// ρA ā_x G1 (ā = Aᵀ(R̈ − g)): on for a frame held by a support (a clamped or mounted root
    /// segment), where ω̄ and ā are the support's.
    pub stiffening: bool,
    /// G = Σ_p W_p φ′(ξ_p)φ′(ξ_p)ᵀ (row-major nb × nb): the tip foreshortening of each plane
    /// is ½aᵀGa/L. The nonlinear body's quadrature (the ξ = 1 case of the foreshortening of the
    /// points inside); the basis's [`ModalBasis::slope_gram`] for the linear body.
    pub gram: Arc<[f64]>,
    /// The geometrically nonlinear body (true unless built [`ModalBody3::linear`]).
    pub nonlinear: bool,
    nl: Nonlinear,
    damped: bool,
    /// Point masses on the body ([`ModalBody3::with_points`]).
    points: Vec<BodyPoint>,
    /// Rigid bodies on the body's sections ([`ModalBody3::with_bodies`]).
    bodies: Vec<(SectionBody3, ModalPose)>,
    /// The segment's line load over ρA, q/(ρA) [m/s²] ([`ModalBody3::with_line_load`]);
    /// `None` without one (a tapered body: over its ρA at the start, `props.rho_a`).
    pub(crate) line: Option<[f64; 3]>,
    /// The section integrals of a tapered segment ([`ModalBody3::tapered`]); `None`: uniform.
    taper: Option<Box<Taper>>,
    /// The shapes at the quadrature points of the stations' cuts
    /// ([`ModalBody3::partial_load`]).
    cuts: CutCache,
}

/// Slots per quadrature point of [`ModalBody3::fields`]: v, v̇, v̈, v′, v̇′, v̈′, v″ (0..7), the
/// same of w (7..14), the foreshortening c, ċ, c̈ (14..17), scratch of
/// [`ModalBody3::add_nonlinear`] (17..24), v̇″ and ẇ″ (24, 25).
const FIELDS3: usize = 26;

/// Quadrature points of the default nonlinear rule at most: 5 per panel, max(2, ⌈nb/4⌉) panels
/// of at most [`MAX_MODES`] + 2 bending amplitudes.
const MAX_POINTS: usize = 5 * (MAX_MODES + 2).div_ceil(4);

/// The per-point fields of the nonlinear terms ([`FIELDS3`] per point; on the stack for the
/// default rule: no allocation in a step).
type FieldBuf<T> = SmallVec<[T; FIELDS3 * MAX_POINTS]>;

/// One value per bending amplitude of a plane (on the stack).
pub type Amplitudes = SmallVec<[f64; MAX_MODES + 2]>;

/// Columns of [`ModalBody3::newton_block`] per evaluation of the residual.
const LANES: usize = 8;

/// A dual number carrying [`LANES`] directional derivatives.
type Lanes = DualSVec64<LANES>;

/// Dual local coordinates (on the stack up to [`LOCAL_INLINE`]).
type LaneVec = SmallVec<[Lanes; LOCAL_INLINE]>;

impl ModalBody3 {
    /// Builds the body from its bending basis and properties.
    pub fn new(basis: ModalBasis, props: ModalProps3) -> Self {
        let l = props.length;
        let mu = props.rho_a * l;
        let damped = props.damping_ratio > 0.0 || props.damping_time > 0.0;
        let stiff =
            |ei: f64| -> Vec<f64> { basis.lambda4.iter().map(|x| ei * x / l.powi(3)).collect() };
        let (k_y, k_z) = (stiff(props.ei_z), stiff(props.ei_y));
        let damp = |k: &[f64]| -> Vec<f64> {
            k.iter()
                .map(|kk| {
                    if damped {
                        2.0 * props.damping_ratio * (kk / mu).sqrt() * mu + props.damping_time * kk
                    } else {
                        0.0
                    }
                })
                .collect()
        };
        let (d_y, d_z) = (damp(&k_y), damp(&k_z));
        // ∫χχ = [[1/3, √2/π], [√2/π, 1]], ∫χ′χ′ = diag(1, π²), ∫χ = (1/2, 2√2/π)
        let jt = props.rho_ip * l;
        let m_t = [[jt / 3.0, jt * SQRT_2 / PI], [jt * SQRT_2 / PI, jt]];
        let kt = props.gj / l;
        let k_t = [[kt, 0.0], [0.0, kt * PI * PI]];
        let d_t = torsion_damping(&props, damped, jt, m_t, k_t);
        let c_t = [jt * 0.5, jt * 2.0 * SQRT_2 / PI];
        let s_f = basis.i1.iter().map(|v| mu * v).collect();
        let s_x = basis.ix.iter().map(|v| mu * l * v).collect();
        let (g1, g2) = basis.stiffening_grams();
        let (nl, gram) = Self::rule(&basis, l, panels(basis.len()));
        Self {
            basis,
            props,
            k_y,
            k_z,
            d_y,
            d_z,
            m_t,
            k_t,
            d_t,
            c_t,
            chi_tip: torsion_shapes(1.0).0,
            s_f,
            s_x,
            g1,
            g2,
            stiffening: false,
            gram: gram.into(),
            nonlinear: true,
            nl,
            damped,
            points: Vec::new(),
            bodies: Vec::new(),
            line: None,
            taper: None,
            cuts: cut_cache(),
        }
    }

    /// The body of the tapered segment `seg` ([`Segment::is_tapered`]; built
    /// [`ModalBody3::new`] with [`ModalProps3::of_segment`], its properties at the start, before
    /// [`ModalBody3::linear`], the panels and the points): the shapes stay the uniform beam's
    /// (bending modes, torsion shapes), and every integral with ρA, EI (both planes), GJ or
    /// ρI_p takes the property at its point — the mass terms (∫ρA(1, x, x², φ_k, xφ_k,
    /// φ_iφ_j)dx, ∫ρI_p(1, χ_m, χ_iχ_j)dx), the stiffness (∫EIφ_i″φ_j″dx per plane, ∫GJχ_i′χ_j′dx,
    /// full matrices), the nonlinear rule's point masses and EI, the stiffening grams; the line
    /// load is q per unit length; the modal damping gives every mode of (M, K) of each plane the
    /// ratio ζ, plus τK. `k_y`, `k_z`, `d_y`, `d_z` then hold the diagonals (the matrices are
    /// used). Err if the modal mass is not positive definite.
    pub fn tapered(mut self, seg: &Segment) -> Result<Self, String> {
        let t = Taper::new(seg, &self.basis, &self.nl);
        let n = self.modes();
        let p = self.props;
        let bad = || {
            format!(
                "{}: the tapered modal mass is not positive definite",
                seg.name
            )
        };
        let (_, dz) =
            modal_damping(&t.mass, &t.k_z, p.damping_ratio, p.damping_time).ok_or_else(bad)?;
        let (_, dy) =
            modal_damping(&t.mass, &t.k_y, p.damping_ratio, p.damping_time).ok_or_else(bad)?;
        let diag = |x: &[f64]| -> Vec<f64> { (0..n).map(|i| x[i * n + i]).collect() };
        self.k_y = diag(&t.k_z);
        self.k_z = diag(&t.k_y);
        let mut t = t;
        if self.damped {
            self.d_y = diag(&dz);
            self.d_z = diag(&dy);
            t.damp_z = dz;
            t.damp_y = dy;
        }
        let (m_t, k_t, c_t) = t.torsion();
        self.m_t = m_t;
        self.k_t = k_t;
        self.c_t = c_t;
        self.d_t = torsion_damping(&p, self.damped, t.jp, m_t, k_t);
        self.s_f.clone_from(&t.s_f);
        self.s_x.clone_from(&t.s_x);
        self.g1.clone_from(&t.g1);
        self.g2.clone_from(&t.g2);
        self.taper = Some(Box::new(t));
        Ok(self)
    }

    /// Whether the body is tapered ([`ModalBody3::tapered`]).
    pub fn is_tapered(&self) -> bool {
        self.taper.is_some()
    }
}

/// The torsion damping of the coupled pair (M_t, K_t): D = 2ζ L √(L⁻¹KL⁻ᵀ) Lᵀ with M = LLᵀ
/// (every torsion mode the ratio ζ), + τK; zero unless `damped` and the rotary inertia `jt`
/// [kg m²] > 0.
fn torsion_damping(
    props: &ModalProps3,
    damped: bool,
    jt: f64,
    m_t: [[f64; 2]; 2],
    k_t: [[f64; 2]; 2],
) -> [[f64; 2]; 2] {
    let mut d_t = [[0.0; 2]; 2];
    if damped && jt > 0.0 {
        let mm = Matrix2::new(m_t[0][0], m_t[0][1], m_t[1][0], m_t[1][1]);
        let km = Matrix2::new(k_t[0][0], k_t[0][1], k_t[1][0], k_t[1][1]);
        let lo = mm
            .cholesky()
            .expect("torsion mass is positive definite")
            .l();
        let li = lo.try_inverse().expect("Cholesky factor is invertible");
        let c = li * km * li.transpose();
        let eig = (0.5 * (c + c.transpose())).symmetric_eigen();
        let sq = eig.eigenvectors
            * Matrix2::from_diagonal(&eig.eigenvalues.map(|x| x.max(0.0).sqrt()))
            * eig.eigenvectors.transpose();
        let dz = 2.0 * props.damping_ratio * lo * sq * lo.transpose();
        for i in 0..2 {
            for j in 0..2 {
                d_t[i][j] = dz[(i, j)] + props.damping_time * k_t[i][j];
            }
        }
    }
    d_t
}

impl ModalBody3 {
    /// The body under the uniform dead line load `q` [N/m] (world axes; `None`: none): a load
    /// of density q beside the weight ρA g, so its distributed mass feels g + q/(ρA) where it
    /// feels gravity (forces, Newton block, potential −∫qᵀr dx), its point masses g alone.
    pub fn with_line_load(mut self, q: Option<[f64; 3]>) -> Self {
        self.line = q.map(|q| q.map(|c| c / self.props.rho_a));
        self
    }

    /// The gravity fields at load factor `load` of gravity `g` [m/s²] with the line load.
    pub fn gravity(&self, g: [f64; 3], load: f64) -> BodyGravity<3> {
        BodyGravity::of(g, load, self.line)
    }

    /// The body carrying point masses `points`: (x from the root [m], mass [kg]), each a point
    /// of the body's kinematics r = R + A ū(x), ū = (x + c, v, w) (c = 0 on a linear body) with
    /// its own mass: its inertia and weight enter every term on the body's shapes (Ritz). Call
    /// after [`ModalBody3::linear`] and [`ModalBody3::with_panels`].
    pub fn with_points(mut self, points: &[(f64, f64)]) -> Self {
        let l = self.props.length;
        self.points = points
            .iter()
            .map(|&p| BodyPoint::new(&self.basis, &self.nl, l, self.nonlinear, p))
            .collect();
        self
    }

    /// The body carrying rigid bodies `bodies` on its sections ([`SectionBody3`], `xi` = x/L:
    /// an offset or a rotary inertia) on the section frame of [`ModalPose`]. Call after
    /// [`ModalBody3::linear`] and [`ModalBody3::with_panels`].
    pub fn with_bodies(mut self, bodies: &[SectionBody3]) -> Self {
        let (l, nb) = (self.props.length, self.modes());
        let mut buf = Vec::new();
        for b in bodies {
            let xi = b.xi.clamp(0.0, 1.0);
            let pt = BodyPoint::new(&self.basis, &self.nl, l, self.nonlinear, (xi * l, b.mass));
            self.basis.eval_all(xi, &mut buf);
            let pose = ModalPose {
                nb,
                x: xi * l,
                nonlinear: self.nonlinear,
                phi: pt.phi,
                dphi: buf.iter().take(nb).map(|f| f[1] / l).collect(),
                gram: pt.gram,
                chi: torsion_shapes(xi).0,
            };
            self.bodies.push((*b, pose));
        }
        self
    }

    /// The point masses' inertia and weight Σ m (∂r/∂q)ᵀ(r̈ − g) added to `out`, the p rows as
    /// the body's (Ḡᵀ times the body-frame moment about the frame origin): with the local
    /// acceleration α = Z + ω̄̇ × ū + ω̄ × (ω̄ × ū) + 2ω̄ × u̇ + ü (Z = Aᵀ(R̈ − g)), F_R = m Aα,
    /// F_p = 2Ēᵀ(ū × mα), F_a = m(φ α_{y,z} − G_m a α_x). `frame` = (A, Ē, ω̄, ω̄̇, Z).
    #[allow(clippy::type_complexity)]
    fn add_point_forces<T: Real>(
        &self,
        (q, v, a): (&[T], &[T], &[T]),
        frame: (&[V3<T>; 3], &[[T; 4]; 3], V3<T>, V3<T>, V3<T>),
        out: &mut [T],
    ) {
        let nb = self.modes();
        let (rot, eb, w, wd, z) = frame;
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        let (vy, vz) = (&v[7..7 + nb], &v[7 + nb..7 + 2 * nb]);
        let (ky, kz) = (&a[7..7 + nb], &a[7 + nb..7 + 2 * nb]);
        for pt in &self.points {
            let (cy, py) = pt.plane(ay, vy, ky);
            let (cz, pz) = pt.plane(az, vz, kz);
            let u = [cy[0] + cz[0] + pt.x, py[0], pz[0]];
            let ud = [cy[1] + cz[1], py[1], pz[1]];
            let udd = [cy[2] + cz[2], py[2], pz[2]];
            let al = add(
                add(z, cross(wd, u)),
                add(
                    add(cross(w, cross(w, u)), scale(cross(w, ud), T::from(2.0))),
                    udd,
                ),
            );
            let f = scale(al, T::from(pt.mass));
            let fw = mul(rot, f);
            for i in 0..3 {
                out[i] += fw[i];
            }
            let mo = cross(u, f);
            for k in 0..4 {
                out[3 + k] += (eb[0][k] * mo[0] + eb[1][k] * mo[1] + eb[2][k] * mo[2]) * 2.0;
            }
            for k in 0..nb {
                out[7 + k] += f[1] * pt.phi[k] - f[0] * pt.ga(ay, k);
                out[7 + nb + k] += f[2] * pt.phi[k] - f[0] * pt.ga(az, k);
            }
        }
    }

    /// The d'Alembert load of the part [0, ξ] of the body at (q, q̇, q̈) under the fields `g`
    /// ([`crate::model::component::Element::partial_load`]), world axes: ∫ρA(g − r̈) + q and its
    /// moment about `about` on the cut's composite rule ([`CutTable`]), r̈ = R̈ + A(ω̄̇ × ū +
    /// ω̄ × (ω̄ × ū) + 2ω̄ × u̇̄ + ǖ), ū = (x − ½∫₀ˣ(v′² + w′²)dx, v, w) (no foreshortening on a
    /// linear body); the sections' spin, the rate of the angular momentum ρI_p(ω̄_x + θ̇) A e_x:
    /// −∫ρI_p A[(ω̄̇_x + θ̈)e_x + (ω̄_x + θ̇) ω̄ × e_x]dx; the point masses at x < ξL and the
    /// section bodies at ξ_b < ξ ([`SectionBody3::load`]). `None` when the body's cut tables
    /// are full.
    pub fn partial_load(
        &self,
        (q, v, a): (&[f64], &[f64], &[f64]),
        g: BodyGravity<3>,
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let nb = self.modes();
        let l = self.props.length;
        let tab = cut_table(&self.cuts, xi, || {
            CutTable::new(&self.basis, xi, |x| match &self.taper {
                Some(t) => {
                    let p = super::taper::line_props(&t.segment, x);
                    (p.rho_a, p.rho_ip)
                }
                None => (self.props.rho_a, self.props.rho_ip),
            })
        })?;
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        let (vy, vz) = (&v[7..7 + nb], &v[7 + nb..7 + 2 * nb]);
        let (ky, kz) = (&a[7..7 + nb], &a[7 + nb..7 + 2 * nb]);
        let t0 = 7 + 2 * nb;
        let p = [q[3], q[4], q[5], q[6]];
        let rot = euler_rotation(p);
        let eb = e_bar(p);
        let (w, wd) = (g_mul(&eb, &v[3..7]), g_mul(&eb, &a[3..7]));
        let z = mul_t(&rot, [a[0], a[1], a[2]]);
        let (field, line) = match &self.taper {
            None => (mul_t(&rot, g.distributed), [0.0; 3]),
            Some(t) => (
                mul_t(&rot, g.points),
                mul_t(&rot, g.line.map(|c| c * t.rho_ref)),
            ),
        };
        let alpha = |u: V3<f64>, ud: V3<f64>, ua: V3<f64>| {
            add(
                add(z, cross(wd, u)),
                add(add(cross(w, cross(w, u)), scale(cross(w, ud), 2.0)), ua),
            )
        };
        let (mut fl, mut ml) = ([0.0; 3], [0.0; 3]);
        let nonlinear = self.nonlinear;
        let ex = [1.0, 0.0, 0.0];
        let wxe = cross(w, ex);
        tab.for_each(
            nb,
            |slope| {
                let fy = slope_fields(slope, (ay, vy, ky));
                let fz = slope_fields(slope, (az, vz, kz));
                [
                    fy[0] * fy[0] + fz[0] * fz[0],
                    fy[0] * fy[1] + fz[0] * fz[1],
                    fy[1] * fy[1] + fy[0] * fy[2] + fz[1] * fz[1] + fz[0] * fz[2],
                ]
            },
            |&[x, wt, ra, rip], phi, c| {
                let (fy, fz) = (point_fields(phi, ay, vy, ky), point_fields(phi, az, vz, kz));
                let c = if nonlinear { c } else { [0.0; 3] };
                let u = [x * l - 0.5 * c[0] / l, fy[0], fz[0]];
                let al = alpha(u, [-c[1] / l, fy[1], fz[1]], [-c[2] / l, fy[2], fz[2]]);
                let load: V3<f64> =
                    std::array::from_fn(|i| wt * l * (ra * (field[i] - al[i]) + line[i]));
                let (chi, _) = torsion_shapes(x);
                let spin = w[0] + chi[0] * v[t0] + chi[1] * v[t0 + 1];
                let spin_d = wd[0] + chi[0] * a[t0] + chi[1] * a[t0 + 1];
                let m = cross(u, load);
                for i in 0..3 {
                    fl[i] += load[i];
                    ml[i] += m[i] - wt * l * rip * (spin_d * ex[i] + spin * wxe[i]);
                }
            },
        );
        let gp = mul_t(&rot, g.points);
        for pt in self.points.iter().filter(|pt| pt.x < xi * l) {
            let (cy, py) = pt.plane(ay, vy, ky);
            let (cz, pz) = pt.plane(az, vz, kz);
            let u = [cy[0] + cz[0] + pt.x, py[0], pz[0]];
            let al = alpha(
                u,
                [cy[1] + cz[1], py[1], pz[1]],
                [cy[2] + cz[2], py[2], pz[2]],
            );
            let load: V3<f64> = std::array::from_fn(|i| pt.mass * (gp[i] - al[i]));
            let m = cross(u, load);
            for i in 0..3 {
                fl[i] += load[i];
                ml[i] += m[i];
            }
        }
        // world axes: F = A f_l, M = (R − p) × F + A Σ ū × load
        let f = mul(&rot, fl);
        let arm = [q[0] - about[0], q[1] - about[1], q[2] - about[2]];
        let mut m = add(cross(arm, f), mul(&rot, ml));
        let mut f = f;
        for (b, pose) in self.bodies.iter().filter(|(b, _)| b.xi < xi) {
            let (bf, bm) = b.load(pose, (q, v, a), g.points, about);
            f = add(f, bf);
            m = add(m, bm);
        }
        Some((f, m))
    }

    /// The point masses' kinetic energy Σ ½m|ṙ|² and gravity potential −Σ m gᵀr [J].
    fn point_energies(&self, q: &[f64], v: &[f64], g: [f64; 3]) -> (f64, f64) {
        let nb = self.modes();
        let p = [q[3], q[4], q[5], q[6]];
        let rot = euler_rotation(p);
        let w = g_mul(&e_bar(p), &v[3..7]);
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        let (vy, vz) = (&v[7..7 + nb], &v[7 + nb..7 + 2 * nb]);
        let z = Amplitudes::from_elem(0.0, nb);
        let (mut t, mut e) = (0.0, 0.0);
        for pt in &self.points {
            let (cy, py) = pt.plane(ay, vy, &z);
            let (cz, pz) = pt.plane(az, vz, &z);
            let u = [cy[0] + cz[0] + pt.x, py[0], pz[0]];
            let ud = [cy[1] + cz[1], py[1], pz[1]];
            let vel = add([v[0], v[1], v[2]], mul(&rot, add(cross(w, u), ud)));
            let r = add([q[0], q[1], q[2]], mul(&rot, u));
            t += 0.5 * pt.mass * dot(vel, vel);
            e -= pt.mass * dot(g, r);
        }
        (t, e)
    }

    /// The nonlinear terms' quadrature (composite 5-point Gauss on `panels` panels, shapes
    /// scaled to x-derivatives) and its G = Σ_p W_p φ′φ′ᵀ (ξ-derivatives).
    fn rule(basis: &ModalBasis, l: f64, panels: usize) -> (Nonlinear, Vec<f64>) {
        let nb = basis.len();
        let mut nl = Nonlinear::new(basis, panels);
        let mut gram = vec![0.0; nb * nb];
        for (p, w) in nl.w.iter().enumerate() {
            let phi = &nl.phi[p * nb..(p + 1) * nb];
            for i in 0..nb {
                for j in 0..nb {
                    gram[i * nb + j] += w * phi[i][1] * phi[j][1];
                }
            }
        }
        for f in &mut nl.phi {
            f[1] /= l;
            f[2] /= l * l;
        }
        (nl, gram)
    }

    /// The same body with the nonlinear terms on `panels` (≥ 1) panels of its composite rule
    /// instead of the default max(2, ⌈nb/4⌉) (for convergence checks; no effect on a linear
    /// body).
    pub fn with_panels(mut self, panels: usize) -> Self {
        let (nl, gram) = Self::rule(&self.basis, self.props.length, panels.max(1));
        if let Some(t) = &mut self.taper {
            t.points(&nl, self.props.length);
        }
        self.nl = nl;
        if self.nonlinear {
            self.gram = gram.into();
        }
        self
    }

    /// The linear floating frame instead (the body before the nonlinear terms): ū = (x, v, w)
    /// inside the segment, strain energy ½aᵀKa, the tip's foreshortening with the basis's G
    /// ([`ModalBasis::slope_gram`]) and its directors turned by the rotation vector
    /// (0, −w′, v′) (scene key `linear = true`).
    pub fn linear(mut self) -> Self {
        self.nonlinear = false;
        self.gram = self.basis.slope_gram.as_slice().into();
        self
    }

    /// The same body with the geometric stiffness of a held frame (see
    /// [`ModalBody3::stiffening`]).
    pub fn with_stiffening(mut self) -> Self {
        self.stiffening = true;
        self
    }

    /// Number of bending shapes per plane nb.
    pub fn modes(&self) -> usize {
        self.k_y.len()
    }

    /// Local coordinate count 3 + 4 + 2nb + 2.
    pub fn dim(&self) -> usize {
        7 + 2 * self.modes() + TORSION_SHAPES
    }

    /// Local index of a_y,k.
    pub fn iy(&self, k: usize) -> usize {
        7 + k
    }

    /// Local index of a_z,k.
    pub fn iz(&self, k: usize) -> usize {
        7 + self.modes() + k
    }

    /// Local index of a_t,m.
    pub fn it(&self, m: usize) -> usize {
        7 + 2 * self.modes() + m
    }

    /// Mass ρAL [kg].
    pub fn mass(&self) -> f64 {
        match &self.taper {
            None => self.props.rho_a * self.props.length,
            Some(t) => t.mu,
        }
    }

    /// (∫ρA x dx, ∫ρA x² dx, ∫ρI_p dx) [kg m, kg m², kg m²]: ½mL, mL²/3, ρI_pL uniform.
    fn moments(&self) -> (f64, f64, f64) {
        let l = self.props.length;
        match &self.taper {
            None => {
                let mu = self.mass();
                (0.5 * mu * l, mu * l * l / 3.0, self.props.rho_ip * l)
            }
            Some(t) => (t.s0, t.j0, t.jp),
        }
    }

    /// A tapered body's line load q [N/m] (world axes) in the fields `g`; `None` on a uniform
    /// body (its line load is in `g.distributed`) or without one.
    fn taper_line(&self, g: &BodyGravity<3>) -> Option<[f64; 3]> {
        let t = self.taper.as_ref()?;
        (g.line != [0.0; 3]).then(|| g.line.map(|c| c * t.rho_ref))
    }

    /// Whether the body carries damping.
    pub fn is_damped(&self) -> bool {
        self.damped
    }

    /// Torsion frequencies of the clamped segment [rad/s], ascending (K_t x = ω² M_t x).
    pub fn torsion_omegas(&self) -> [f64; 2] {
        let (m, k) = (self.m_t, self.k_t);
        // det(K − λM) = 0: a λ² + b λ + c = 0
        let a = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let b = -(k[0][0] * m[1][1] + k[1][1] * m[0][0] - k[0][1] * m[1][0] - k[1][0] * m[0][1]);
        let c = k[0][0] * k[1][1] - k[0][1] * k[1][0];
        let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
        let (l1, l2) = ((-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a));
        [l1.sqrt(), l2.sqrt()]
    }

    /// Residual `r = M q̈ − Q_v − Q_g + K a + D ȧ` at (q, q̇, q̈) for gravity g [m/s²] (world)
    /// into `out` (length [`ModalBody3::dim`]). Generic over the scalar; a nonlinear body
    /// keeps its per-point fields ([`FIELDS3`] per quadrature point) on the stack.
    pub fn residual<T: Real>(
        &self,
        q: &[T],
        v: &[T],
        a: &[T],
        g: impl Into<BodyGravity<3>>,
        out: &mut [T],
    ) {
        let grav = g.into();
        let BodyGravity {
            points: gp,
            distributed: g,
            ..
        } = grav;
        // a tapered body: its mass feels gravity alone, the line load apart (q per length)
        let line = self.taper_line(&grav);
        let g = if self.taper.is_some() { gp } else { g };
        let nb = self.modes();
        let l = self.props.length;
        let mu = self.mass();
        let ra = self.props.rho_a;
        let (m_x, m_xx, m_ip) = self.moments();
        let zero = T::zero();
        let p = [q[3], q[4], q[5], q[6]];
        let rot = euler_rotation(p);
        let eb = e_bar(p);
        let w = g_mul(&eb, &v[3..7]); // ω̄
        let wd = g_mul(&eb, &a[3..7]); // ω̄̇ (Ē̇ṗ = 0)
        let z = mul_t(&rot, [a[0] - g[0], a[1] - g[1], a[2] - g[2]]); // Aᵀ(R̈ − g)
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        let (vy, vz) = (&v[7..7 + nb], &v[7 + nb..7 + 2 * nb]);
        let (ky, kz) = (&a[7..7 + nb], &a[7 + nb..7 + 2 * nb]);
        let (at, vt, kt) = (&q[7 + 2 * nb..], &v[7 + 2 * nb..], &a[7 + 2 * nb..]);
        // every reduction over the modes in one pass: s_f·x and s_x·x for x = a, ȧ, ä of both
        // planes, and the products of amplitudes with amplitudes, rates and accelerations
        let (mut sf, mut sx) = ([zero; 6], [zero; 6]);
        let mut pr = [zero; 9];
        for n in 0..nb {
            let (cf, cx) = (self.s_f[n], self.s_x[n]);
            let x = [ay[n], az[n], vy[n], vz[n], ky[n], kz[n]];
            for k in 0..6 {
                sf[k] += x[k] * cf;
                sx[k] += x[k] * cx;
            }
            let (y, z) = (ay[n], az[n]);
            pr[0] += y * y;
            pr[1] += z * z;
            pr[2] += y * z;
            pr[3] += y * kz[n];
            pr[4] += z * ky[n];
            pr[5] += y * vy[n];
            pr[6] += z * vz[n];
            pr[7] += z * vy[n];
            pr[8] += y * vz[n];
        }
        let pr = match &self.taper {
            None => pr.map(|x| x * (ra * l)),
            Some(t) => {
                // the products on the modal mass M: xᵀM y
                let mut pr = [zero; 9];
                for n in 0..nb {
                    let (may, maz) = (t.mass_times(ay, n), t.mass_times(az, n));
                    pr[0] += may * ay[n];
                    pr[1] += maz * az[n];
                    pr[2] += may * az[n];
                    pr[3] += may * kz[n];
                    pr[4] += maz * ky[n];
                    pr[5] += may * vy[n];
                    pr[6] += maz * vz[n];
                    pr[7] += maz * vy[n];
                    pr[8] += may * vz[n];
                }
                pr
            }
        };
        // first moments ∫ρu, ∫ρS ȧ, ∫ρS ä
        let cbar = [T::from(m_x), sf[0], sf[1]];
        let sv = [zero, sf[2], sf[3]];
        let sa = [zero, sf[4], sf[5]];
        // J = ∫ρuuᵀ and Ī = tr(J)I − J + ρI_pL e_x e_xᵀ
        let jxx = m_xx;
        let (jxy, jxz) = (sx[0], sx[1]);
        let (jyy, jzz, jyz) = (pr[0], pr[1], pr[2]);
        let ibar = [
            [jyy + jzz + m_ip, -jxy, -jxz],
            [-jxy, jzz + jxx, -jyz],
            [-jxz, -jyz, jyy + jxx],
        ];
        let iw = mul(&ibar, w);
        let iwd = mul(&ibar, wd);
        // torsion angular momentum about x̄ (rates and accelerations)
        let ht_v = vt[0] * self.c_t[0] + vt[1] * self.c_t[1];
        let ht_a = kt[0] * self.c_t[0] + kt[1] * self.c_t[1];
        // ∫ρ u × s̈ with s̈ = (0, φᵀä_y, φᵀä_z)
        let usa = [pr[3] - pr[4], -sx[5], sx[4]];
        // ∫ρ u × (ω̄ × s) = ω̄ ∫ρ u·s − (∫ρ s uᵀ) ω̄, s = (0, φᵀȧ_y, φᵀȧ_z)
        let us = pr[5] + pr[6];
        let ky_row = [sx[2], pr[5], pr[7]];
        let kz_row = [sx[3], pr[8], pr[6]];
        let uws = [
            w[0] * us,
            w[1] * us - dot(ky_row, w),
            w[2] * us - dot(kz_row, w),
        ];
        // body-frame moment balance about the frame origin
        let hv = [iw[0] + ht_v, iw[1], iw[2]];
        let wxh = cross(w, hv);
        let cz = cross(cbar, z);
        let mut mbar = [
            cz[0] + iwd[0] + usa[0] + ht_a + wxh[0] + uws[0] * 2.0,
            cz[1] + iwd[1] + usa[1] + wxh[1] + uws[1] * 2.0,
            cz[2] + iwd[2] + usa[2] + wxh[2] + uws[2] * 2.0,
        ];
        // translation: m(R̈ − g) + A[ω̄̇ × c̄ + S̄ä + ω̄ × (ω̄ × c̄) + 2 ω̄ × S̄ȧ]
        let wc = cross(w, cbar);
        let mut fl = add(
            add(cross(wd, cbar), sa),
            add(cross(w, wc), scale(cross(w, sv), T::from(2.0))),
        );
        // a tapered body's line load in body axes, ql = Aᵀq, with its first moment about the
        // frame origin ∫ū dx = (½L², Σ L∫φ dξ a_y, Σ L∫φ dξ a_z) (the foreshortening's part in
        // the nonlinear terms): F −= Lq, M̄ −= ∫ū dx × ql, the bending rows −L∫φ dξ ql_(y,z)
        let ql = line.map(|qw| mul_t(&rot, qw.map(T::from)));
        if let (Some(ql), Some(t)) = (ql, &self.taper) {
            let (mut fy, mut fz) = (zero, zero);
            for n in 0..nb {
                fy += ay[n] * t.line_f[n];
                fz += az[n] * t.line_f[n];
            }
            let mo = cross([T::from(0.5 * l * l), fy, fz], ql);
            for k in 0..3 {
                mbar[k] -= mo[k];
            }
        }
        let mut buf = FieldBuf::new();
        if self.nonlinear {
            let zq = (z, ql.unwrap_or([zero; 3]));
            let (dfl, dm) = self.add_nonlinear(q, v, a, (w, wd, zq), out, &mut buf);
            fl = add(fl, dfl);
            mbar = add(mbar, dm);
        }
        let fw = mul(&rot, fl);
        for i in 0..3 {
            out[i] = (a[i] - g[i]) * mu + fw[i];
        }
        if let Some(qw) = line {
            for i in 0..3 {
                out[i] -= T::from(l * qw[i]);
            }
        }
        for k in 0..4 {
            out[3 + k] = (eb[0][k] * mbar[0] + eb[1][k] * mbar[1] + eb[2][k] * mbar[2]) * 2.0;
        }
        let w2 = dot(w, w);
        let ml = ra * l;
        // geometric stiffness: axial force of the centrifugal and axial inertia fields
        let (kg_w, kg_a) = if self.stiffening {
            ((w[1] * w[1] + w[2] * w[2]) * ml, z[0] * ra)
        } else {
            (zero, zero)
        };
        if let Some(t) = &self.taper {
            for n in 0..nb {
                let (sf, sx) = (self.s_f[n], self.s_x[n]);
                let (may, maz) = (t.mass_times(ay, n), t.mass_times(az, n));
                let mut fy = z[1] * sf
                    + (wd[2] * sx - wd[0] * maz)
                    + t.mass_times(ky, n)
                    + w[1] * w[0] * sx
                    + (w[1] * w[1] - w2) * may
                    + w[1] * w[2] * maz
                    - w[0] * t.mass_times(vz, n) * 2.0
                    + row_times(&t.k_z, ay, n);
                let mut fz = z[2] * sf
                    + (wd[0] * may - wd[1] * sx)
                    + t.mass_times(kz, n)
                    + w[2] * w[0] * sx
                    + w[2] * w[1] * may
                    + (w[2] * w[2] - w2) * maz
                    + w[0] * t.mass_times(vy, n) * 2.0
                    + row_times(&t.k_y, az, n);
                if self.damped {
                    fy += row_times(&t.damp_z, vy, n);
                    fz += row_times(&t.damp_y, vz, n);
                }
                if let Some(ql) = ql {
                    fy -= ql[1] * t.line_f[n];
                    fz -= ql[2] * t.line_f[n];
                }
                if self.stiffening {
                    let qx = ql.map_or(zero, |ql| ql[0]);
                    for m in 0..nb {
                        let i = n * nb + m;
                        let k = kg_w * self.g2[i] - kg_a * self.g1[i] + qx * t.g1_line[i];
                        fy += k * ay[m];
                        fz += k * az[m];
                    }
                }
                if self.nonlinear {
                    out[7 + n] += fy;
                    out[7 + nb + n] += fz;
                } else {
                    out[7 + n] = fy;
                    out[7 + nb + n] = fz;
                }
            }
        }
        for n in (0..nb).filter(|_| self.taper.is_none()) {
            let (sf, sx) = (self.s_f[n], self.s_x[n]);
            let mut fy = z[1] * sf
                + (wd[2] * sx - wd[0] * az[n] * ml)
                + ky[n] * ml
                + w[1] * w[0] * sx
                + (w[1] * w[1] - w2) * ay[n] * ml
                + w[1] * w[2] * az[n] * ml
                - w[0] * vz[n] * (2.0 * ml)
                + ay[n] * self.k_y[n];
            let mut fz = z[2] * sf
                + (wd[0] * ay[n] * ml - wd[1] * sx)
                + kz[n] * ml
                + w[2] * w[0] * sx
                + w[2] * w[1] * ay[n] * ml
                + (w[2] * w[2] - w2) * az[n] * ml
                + w[0] * vy[n] * (2.0 * ml)
                + az[n] * self.k_z[n];
            if self.damped {
                fy += vy[n] * self.d_y[n];
                fz += vz[n] * self.d_z[n];
            }
            if self.stiffening {
                for m in 0..nb {
                    let k = kg_w * self.g2[n * nb + m] - kg_a * self.g1[n * nb + m];
                    fy += k * ay[m];
                    fz += k * az[m];
                }
            }
            if self.nonlinear {
                out[7 + n] += fy;
                out[7 + nb + n] += fz;
            } else {
                out[7 + n] = fy;
                out[7 + nb + n] = fz;
            }
        }
        for m in 0..2 {
            let mut f = wd[0] * self.c_t[m]
                + kt[0] * self.m_t[m][0]
                + kt[1] * self.m_t[m][1]
                + at[0] * self.k_t[m][0]
                + at[1] * self.k_t[m][1];
            if self.damped {
                f += vt[0] * self.d_t[m][0] + vt[1] * self.d_t[m][1];
            }
            out[7 + 2 * nb + m] = f;
        }
        if !self.points.is_empty() {
            // the point masses feel gravity alone (the line load is on the distributed mass)
            let zp = if gp == g {
                z
            } else {
                mul_t(&rot, [a[0] - gp[0], a[1] - gp[1], a[2] - gp[2]])
            };
            self.add_point_forces((q, v, a), (&rot, &eb, w, wd, zp), out);
        }
        let d = self.dim();
        for (b, pose) in &self.bodies {
            // the section bodies feel gravity alone, as the point masses
            b.add_forces(pose, d, (q, v, a), gp, out);
        }
    }

    /// The per-point fields of the nonlinear terms into `buf` ([`FIELDS3`] slots per point of
    /// the body's quadrature): v, v̇, v̈, v′, v̇′, v̈′, v″ and the same of w (x-derivatives), and
    /// the foreshortening c = −½∫₀ˣ(v′² + w′²)dx with its rates ċ, c̈ (the cumulative integral
    /// on the quadrature's own points, as the planar body), then v̇″, ẇ″ in slots 24, 25.
    fn fields<T: Real>(&self, q: &[T], v: &[T], a: &[T], buf: &mut FieldBuf<T>) {
        let nb = self.modes();
        let nl = &self.nl;
        let np = nl.w.len();
        let l = self.props.length;
        buf.clear();
        buf.resize(FIELDS3 * np, T::zero());
        for (f, phi) in buf.chunks_exact_mut(FIELDS3).zip(nl.phi.chunks_exact(nb)) {
            for (plane, off) in [(0, 7), (1, 7 + nb)] {
                let (qa, va, aa) = (&q[off..off + nb], &v[off..off + nb], &a[off..off + nb]);
                let pf = point_fields(phi, qa, va, aa);
                f[7 * plane..7 * plane + 7].copy_from_slice(&pf[..7]);
                f[24 + plane] = pf[7];
            }
        }
        let mut done = [T::zero(); 3];
        for (panel, pts) in buf.chunks_exact_mut(5 * FIELDS3).enumerate() {
            let mut sq = [[T::zero(); 3]; 5];
            for (j, f) in pts.chunks_exact(FIELDS3).enumerate() {
                sq[j] = [
                    f[3] * f[3] + f[10] * f[10],
                    f[3] * f[4] + f[10] * f[11],
                    f[4] * f[4] + f[3] * f[5] + f[11] * f[11] + f[10] * f[12],
                ];
            }
            for (i, f) in pts.chunks_exact_mut(FIELDS3).enumerate() {
                let mut cum = done;
                for (j, sqj) in sq.iter().enumerate() {
                    for r in 0..3 {
                        cum[r] += sqj[r] * nl.s[i][j];
                    }
                }
                f[14] = cum[0] * (-0.5 * l);
                f[15] = cum[1] * -l;
                f[16] = cum[2] * -l;
            }
            for (j, sqj) in sq.iter().enumerate() {
                for r in 0..3 {
                    done[r] += sqj[r] * nl.w[5 * panel + j];
                }
            }
        }
    }

    /// The nonlinear part of the strain energy density at one point (x-derivatives s = v′,
    /// t = w′, V = v″, W = w″): with the inextensible curvatures to third order (Crespo da
    /// Silva & Glynn 1978, the Euler angles ψ = atan(v′/(1 + u′)), θ = asin w′ of the tangent,
    /// no twist), κ_z = ψ′cos θ = V(1 + ½s²) + stW and κ_y = θ′ = W(1 + ½t²), the density
    /// ½EI_z(κ_z² − V²) + ½EI_y(κ_y² − W²) and its partial derivatives by (s, V, t, W), for
    /// (EI_z, EI_y) [N m²] at the point.
    #[inline]
    fn strain_density<T: Real>((ez, ey): (f64, f64), s: T, vv: T, t: T, ww: T) -> (T, [T; 4]) {
        let kz = vv * (T::one() + s * s * 0.5) + s * t * ww;
        let ky = ww * (T::one() + t * t * 0.5);
        let e = (kz * kz - vv * vv) * (0.5 * ez) + (ky * ky - ww * ww) * (0.5 * ey);
        let d = [
            kz * (vv * s + t * ww) * ez,
            (kz * (T::one() + s * s * 0.5) - vv) * ez,
            kz * s * ww * ez + ky * ww * t * ey,
            kz * s * t * ez + (ky * (T::one() + t * t * 0.5) - ww) * ey,
        ];
        (e, d)
    }

    /// The nonlinear part of the Kelvin–Voigt damping density's partial derivatives by
    /// (s, V, t, W) at the rates (ṡ, V̇, ṫ, Ẇ) = `r`, per unit retardation time:
    /// EI_z κ̇_z ∂κ_z + EI_y κ̇_y ∂κ_y less the linear EI_z V̇ ∂V + EI_y Ẇ ∂W (which the modal
    /// damping τK carries), κ as in [`ModalBody3::strain_density`].
    #[inline]
    fn damping_density<T: Real>(
        (ez, ey): (f64, f64),
        s: T,
        vv: T,
        t: T,
        ww: T,
        r: [T; 4],
    ) -> [T; 4] {
        let hz = T::one() + s * s * 0.5;
        let hy = T::one() + t * t * 0.5;
        let gz = [vv * s + t * ww, hz, s * ww, s * t];
        let gy = [T::zero(), T::zero(), ww * t, hy];
        let kz_dot = gz[0] * r[0] + gz[1] * r[1] + gz[2] * r[2] + gz[3] * r[3];
        let ky_dot = gy[2] * r[2] + gy[3] * r[3];
        let (kz, ky) = (kz_dot * ez, ky_dot * ey);
        [
            kz * gz[0],
            kz * gz[1] - r[1] * ez,
            kz * gz[2] + ky * gy[2],
            kz * gz[3] + ky * gy[3] - r[3] * ey,
        ]
    }

    /// Adds to the elastic rows of `out` (zeroing them first) the part of the residual that the
    /// linear floating frame leaves out, and returns its additions to the body-frame force and
    /// moment about the frame origin: the foreshortening c(x) = −½∫₀ˣ(v′² + w′²)dx of every
    /// point (ū = ū⁰ + c x̄, ū⁰ = (x, v, w)) in the inertia and gravity forces, and the elastic
    /// force of the inextensible curvatures ([`ModalBody3::strain_density`]), on the body's
    /// quadrature (m_p = ρAL W_p). With α⁰ = Z + ω̄̇×ū⁰ + ω̄×(ω̄×ū⁰) + 2ω̄×u̇̄⁰ + ǖ⁰ (Z =
    /// Aᵀ(R̈ − g)), αᶜ = ω̄̇×cx̄ + ω̄×(ω̄×cx̄) + 2ω̄×ċx̄ + c̈x̄ and α = α⁰ + αᶜ (the body-frame
    /// acceleration of the point less gravity): ΔF = Σ m αᶜ, ΔM = Σ m (ū⁰×αᶜ + cx̄×α),
    /// ΔF_a = Σ m φ αᶜ_(y,z) − Σ_p φ′_p (v′, w′)_p N_p L + ∂U_nl/∂a with the axial force
    /// N_p = Σ_q m_q α_x,q V_qp (V the cumulative rule). Generic over the scalar. `(z, ql)`:
    /// Z and a tapered body's line load in body axes Aᵀq [N/m] (zero on a uniform body, whose
    /// Z carries it): on a tapered body m_p = ρA(x_p)L W_p, EI = EI(x_p), and the line load is
    /// the field q/ρA(x_p) beside g.
    #[allow(clippy::type_complexity)]
    fn add_nonlinear<T: Real>(
        &self,
        q: &[T],
        v: &[T],
        a: &[T],
        (w, wd, (z, ql)): (V3<T>, V3<T>, (V3<T>, V3<T>)),
        out: &mut [T],
        buf: &mut FieldBuf<T>,
    ) -> (V3<T>, V3<T>) {
        let nb = self.modes();
        let nl = &self.nl;
        let l = self.props.length;
        let ml = self.props.rho_a * l;
        let zero = T::zero();
        let taper = self.taper.as_deref();
        let (ez, ey) = (self.props.ei_z, self.props.ei_y);
        self.fields(q, v, a, buf);
        let (mut df, mut dm) = ([zero; 3], [zero; 3]);
        for (p, f) in buf.chunks_exact_mut(FIELDS3).enumerate() {
            let (m, z) = match taper {
                None => (ml * nl.w[p], z),
                Some(t) => (t.m_p[p], add(z, scale(ql, T::from(-t.inv_rho_p[p])))),
            };
            let u0 = [T::from(nl.xi[p] * l), f[0], f[7]];
            let ud0 = [zero, f[1], f[8]];
            let ce = [f[14], zero, zero];
            let a0 = add(
                add(add(z, cross(wd, u0)), cross(w, cross(w, u0))),
                add(scale(cross(w, ud0), T::from(2.0)), [zero, f[2], f[9]]),
            );
            let ac = add(
                add(cross(wd, ce), cross(w, cross(w, ce))),
                add(
                    scale(cross(w, [f[15], zero, zero]), T::from(2.0)),
                    [f[16], zero, zero],
                ),
            );
            let al = add(a0, ac);
            df = add(df, scale(ac, T::from(m)));
            dm = add(dm, scale(add(cross(u0, ac), cross(ce, al)), T::from(m)));
            f[17] = al[0] * m;
            f[18] = ac[1] * m;
            f[19] = ac[2] * m;
        }
        // N_p from the panels after and the own panel; coefficients of φ′_p/L, φ″_p/L² of
        // both planes into slots 20..24
        let tau = self.props.damping_time;
        nl.for_each_axial_force(buf, FIELDS3, 17, |p, f, axial| {
            let ei = match taper {
                None => (ez, ey),
                Some(t) => (t.ei_z_p[p], t.ei_y_p[p]),
            };
            let (_, mut d) = Self::strain_density(ei, f[3], f[6], f[10], f[13]);
            if tau > 0.0 {
                let r = [f[4], f[24], f[11], f[25]];
                let dd = Self::damping_density(ei, f[3], f[6], f[10], f[13], r);
                for (x, y) in d.iter_mut().zip(dd) {
                    *x += y * tau;
                }
            }
            let e = l * nl.w[p];
            f[20] = d[0] * e - f[3] * axial * l;
            f[21] = d[1] * e;
            f[22] = d[2] * e - f[10] * axial * l;
            f[23] = d[3] * e;
        });
        for o in out[7..7 + 2 * nb].iter_mut() {
            *o = zero;
        }
        for (f, phi) in buf.chunks_exact(FIELDS3).zip(nl.phi.chunks_exact(nb)) {
            for (k, ph) in phi.iter().enumerate() {
                out[7 + k] += f[18] * ph[0] + f[20] * ph[1] + f[21] * ph[2];
                out[7 + nb + k] += f[19] * ph[0] + f[22] * ph[1] + f[23] * ph[2];
            }
        }
        (df, dm)
    }

    /// The nonlinear parts of the energies on the body's quadrature at (q, q̇) for gravity g:
    /// kinetic ½Σm(2V⁰·Vᶜ + |Vᶜ|²) (V⁰ = AᵀṘ + ω̄×ū⁰ + u̇̄⁰ the linear frame's point velocity,
    /// Vᶜ = ω̄×cx̄ + ċx̄), strain Σ L W_p (density of [`ModalBody3::strain_density`]) and
    /// gravity −gᵀA Σ m c x̄; zero for the linear body.
    /// A tapered body's line load `qw` [N/m] (world; zero otherwise) adds −(Aᵀq)_x ∫c dx to the
    /// potential.
    fn nonlinear_energies(&self, q: &[f64], v: &[f64], g: [f64; 3], qw: [f64; 3]) -> [f64; 3] {
        if !self.nonlinear {
            return [0.0; 3];
        }
        let l = self.props.length;
        let ml = self.props.rho_a * l;
        let taper = self.taper.as_deref();
        let ei = (self.props.ei_z, self.props.ei_y);
        let mut buf = FieldBuf::new();
        self.fields(q, v, &LocalVec::from_elem(0.0, q.len()), &mut buf);
        let p = [q[3], q[4], q[5], q[6]];
        let rot = euler_rotation(p);
        let w = g_mul(&e_bar(p), &v[3..7]);
        let rl = mul_t(&rot, [v[0], v[1], v[2]]);
        let gl = mul_t(&rot, g);
        let (mut t, mut u, mut c, mut cl) = (0.0, 0.0, 0.0, 0.0);
        for (pi, f) in buf.chunks_exact(FIELDS3).enumerate() {
            let (m, ei) = match taper {
                None => (ml * self.nl.w[pi], ei),
                Some(tp) => (tp.m_p[pi], (tp.ei_z_p[pi], tp.ei_y_p[pi])),
            };
            let u0 = [self.nl.xi[pi] * l, f[0], f[7]];
            let v0 = add(add(rl, cross(w, u0)), [0.0, f[1], f[8]]);
            let vc = add(cross(w, [f[14], 0.0, 0.0]), [f[15], 0.0, 0.0]);
            t += 0.5 * m * (2.0 * dot(v0, vc) + dot(vc, vc));
            u += l * self.nl.w[pi] * Self::strain_density(ei, f[3], f[6], f[10], f[13]).0;
            c += m * f[14];
            cl += l * self.nl.w[pi] * f[14];
        }
        if qw == [0.0; 3] {
            [t, u, -gl[0] * c]
        } else {
            [t, u, -gl[0] * c - mul_t(&rot, qw)[0] * cl]
        }
    }

    /// The Newton block `c_a ∂r/∂q̈ + c_v ∂r/∂q̇ + c_x ∂r/∂q` (row-major d × d) by forward-mode
    /// automatic differentiation of [`ModalBody3::residual`]: column j is the directional
    /// derivative along (δq, δq̇, δq̈) = (c_x, c_v, c_a)·e_j, [`LANES`] columns per evaluation
    /// (vector duals: the residual's values computed once per group of columns instead of once
    /// per column; each column's arithmetic is the scalar dual's). Exact; no allocation (up to
    /// [`LOCAL_INLINE`] coordinates).
    pub fn newton_block(
        &self,
        (q, v, a): (&[f64], &[f64], &[f64]),
        g: impl Into<BodyGravity<3>>,
        (ca, cv, cx): (f64, f64, f64),
        block: &mut [f64],
    ) {
        let g = g.into();
        let d = self.dim();
        let lift = |x: &[f64]| -> LaneVec { x.iter().map(|&x| Lanes::from_re(x)).collect() };
        let (mut qd, mut vd, mut ad) = (lift(q), lift(v), lift(a));
        let mut out = LaneVec::from_elem(Lanes::from_re(0.0), d);
        // c along lane w; none for c = 0, so that what depends only on coordinates that are
        // not differentiated carries no derivative (the mass block alone, c_v = c_x = 0,
        // differentiates along q̈ only)
        let seed = |w: usize, c: f64| {
            if c == 0.0 {
                return Derivative::none();
            }
            let mut e = nalgebra::SVector::<f64, LANES>::zeros();
            e[w] = c;
            Derivative::some(e)
        };
        for j0 in (0..d).step_by(LANES) {
            let lanes = LANES.min(d - j0);
            for w in 0..lanes {
                qd[j0 + w].eps = seed(w, cx);
                vd[j0 + w].eps = seed(w, cv);
                ad[j0 + w].eps = seed(w, ca);
            }
            self.residual(&qd, &vd, &ad, g, &mut out);
            for (i, o) in out.iter().enumerate() {
                let row = &mut block[i * d + j0..i * d + j0 + lanes];
                match &o.eps.0 {
                    Some(e) => row.copy_from_slice(&e.as_slice()[..lanes]),
                    None => row.fill(0.0),
                }
            }
            for x in [&mut qd, &mut vd, &mut ad] {
                for y in &mut x[j0..j0 + lanes] {
                    y.eps = Derivative::none();
                }
            }
        }
    }

    /// Kinetic energy ½ q̇ᵀ M(q) q̇ [J], in closed form: ½m|Ṙ|² + Ṙ·A(ω̄×c̄ + S̄ȧ) + ½ω̄ᵀĪω̄ +
    /// ω̄·∫ρu×s + ½ρAL|ȧ_b|² + ω̄_x c_tᵀȧ_t + ½ȧ_tᵀM_tȧ_t.
    pub fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let nb = self.modes();
        let l = self.props.length;
        let mu = self.mass();
        let ml = self.props.rho_a * l;
        let p = [q[3], q[4], q[5], q[6]];
        let rot = euler_rotation(p);
        let w = g_mul(&e_bar(p), &v[3..7]);
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        let (vy, vz) = (&v[7..7 + nb], &v[7 + nb..7 + 2 * nb]);
        let vt = &v[7 + 2 * nb..];
        let sum = |c: &[f64], x: &[f64]| c.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
        let (m_x, m_xx, m_ip) = self.moments();
        let cbar = [m_x, sum(&self.s_f, ay), sum(&self.s_f, az)];
        let sv = [0.0, sum(&self.s_f, vy), sum(&self.s_f, vz)];
        let rd = [v[0], v[1], v[2]];
        let jxx = m_xx;
        let (jxy, jxz) = (sum(&self.s_x, ay), sum(&self.s_x, az));
        // xᵀM y: ρAL xᵀy on a uniform body
        let mp = |x: &[f64], y: &[f64]| match &self.taper {
            None => ml * sum(x, y),
            Some(t) => (0..nb).map(|k| t.mass_times(x, k) * y[k]).sum::<f64>(),
        };
        let (jyy, jzz, jyz) = (mp(ay, ay), mp(az, az), mp(ay, az));
        let ibar = [
            [jyy + jzz + m_ip, -jxy, -jxz],
            [-jxy, jzz + jxx, -jyz],
            [-jxz, -jyz, jyy + jxx],
        ];
        // ∫ρ u × s = (a_yᵀMȧ_z − a_zᵀMȧ_y, −s_x·ȧ_z, s_x·ȧ_y)
        let us = match &self.taper {
            None => ml * (sum(ay, vz) - sum(az, vy)),
            Some(_) => mp(ay, vz) - mp(az, vy),
        };
        let us = [us, -sum(&self.s_x, vz), sum(&self.s_x, vy)];
        let mt = &self.m_t;
        let tors = vt[0] * (mt[0][0] * vt[0] + mt[0][1] * vt[1])
            + vt[1] * (mt[1][0] * vt[0] + mt[1][1] * vt[1]);
        let modal = match &self.taper {
            None => 0.5 * ml * (sum(vy, vy) + sum(vz, vz)),
            Some(_) => 0.5 * (mp(vy, vy) + mp(vz, vz)),
        };
        let t = self.nonlinear_energies(q, v, [0.0; 3], [0.0; 3])[0]
            + 0.5 * mu * dot(rd, rd)
            + dot(rd, mul(&rot, add(cross(w, cbar), sv)))
            + 0.5 * dot(w, mul(&ibar, w))
            + dot(w, us)
            + modal
            + w[0] * (self.c_t[0] * vt[0] + self.c_t[1] * vt[1])
            + 0.5 * tors;
        let t = if self.points.is_empty() {
            t
        } else {
            t + self.point_energies(q, v, [0.0; 3]).0
        };
        (self.bodies.iter()).fold(t, |t, (b, pose)| t + b.energies(pose, q, v, [0.0; 3]).0)
    }

    /// Strain energy ½ aᵀ K a [J].
    pub fn strain_energy(&self, q: &[f64]) -> f64 {
        let nb = self.modes();
        let mut u = 0.0;
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        for n in 0..nb {
            u += match &self.taper {
                None => {
                    self.k_y[n] * q[7 + n] * q[7 + n] + self.k_z[n] * q[7 + nb + n] * q[7 + nb + n]
                }
                Some(t) => row_times(&t.k_z, ay, n) * ay[n] + row_times(&t.k_y, az, n) * az[n],
            };
        }
        let at = &q[7 + 2 * nb..];
        for i in 0..2 {
            for j in 0..2 {
                u += at[i] * self.k_t[i][j] * at[j];
            }
        }
        0.5 * u
            + self.nonlinear_energies(q, &LocalVec::from_elem(0.0, q.len()), [0.0; 3], [0.0; 3])[1]
    }

    /// Gravity potential −gᵀ∫ρA r dx = −gᵀ(m R + A c̄) [J], with a line load's −∫qᵀr dx when
    /// `g` carries one ([`ModalBody3::gravity`]).
    pub fn potential_energy(&self, q: &[f64], g: impl Into<BodyGravity<3>>) -> f64 {
        let grav = g.into();
        let BodyGravity {
            points: gp,
            distributed: g,
            ..
        } = grav;
        let line = self.taper_line(&grav);
        let g = if self.taper.is_some() { gp } else { g };
        let nb = self.modes();
        let l = self.props.length;
        let sum = |c: &[f64], x: &[f64]| c.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
        let cbar = [
            self.moments().0,
            sum(&self.s_f, &q[7..7 + nb]),
            sum(&self.s_f, &q[7 + nb..7 + 2 * nb]),
        ];
        let rot = euler_rotation([q[3], q[4], q[5], q[6]]);
        let first = add(scale([q[0], q[1], q[2]], self.mass()), mul(&rot, cbar));
        let qw = line.unwrap_or([0.0; 3]);
        let mut u = -dot(g, first)
            + self.nonlinear_energies(q, &LocalVec::from_elem(0.0, q.len()), g, qw)[2];
        if let (Some(qw), Some(t)) = (line, &self.taper) {
            // −qᵀ(L R + A(½L², Σ L∫φ dξ a_y, Σ L∫φ dξ a_z)) (the foreshortening's part above)
            let lf = [
                0.5 * l * l,
                sum(&t.line_f, &q[7..7 + nb]),
                sum(&t.line_f, &q[7 + nb..7 + 2 * nb]),
            ];
            u -= dot(qw, add(scale([q[0], q[1], q[2]], l), mul(&rot, lf)));
        }
        let u = if self.points.is_empty() {
            u
        } else {
            u + self
                .point_energies(q, &LocalVec::from_elem(0.0, q.len()), gp)
                .1
        };
        let v = LocalVec::from_elem(0.0, q.len());
        (self.bodies.iter()).fold(u, |u, (b, pose)| u + b.energies(pose, q, &v, gp).1)
    }

    /// Tip deflections (φ(1)ᵀa_y, φ(1)ᵀa_z) [m], tip slopes (v′, w′) = φ′(1)ᵀ(a_y, a_z)/L [-]
    /// and tip twist θ_T = χ(1)ᵀa_t [rad], body axes.
    pub fn tip_elastic(&self, q: &[f64]) -> (Vector2<f64>, Vector2<f64>, f64) {
        let nb = self.modes();
        let l = self.props.length;
        let (mut v, mut w, mut vs, mut ws) = (0.0, 0.0, 0.0, 0.0);
        for n in 0..nb {
            let (ay, az) = (q[7 + n], q[7 + nb + n]);
            v += ay * self.basis.tip[n];
            w += az * self.basis.tip[n];
            vs += ay * (self.basis.tip_slope[n] / l);
            ws += az * (self.basis.tip_slope[n] / l);
        }
        let th = q[7 + 2 * nb] * self.chi_tip[0] + q[8 + 2 * nb] * self.chi_tip[1];
        (Vector2::new(v, w), Vector2::new(vs, ws), th)
    }

    /// (G a)_k / L for one plane's amplitudes: gradient of the foreshortening ½aᵀGa/L.
    pub fn foreshortening_gradient(&self, a: &[f64]) -> Amplitudes {
        let nb = self.modes();
        (0..nb)
            .map(|k| (0..nb).map(|j| self.gram[k * nb + j] * a[j]).sum::<f64>() / self.props.length)
            .collect()
    }

    /// Tip position in the body frame ū_T = (L − ½(a_yᵀGa_y + a_zᵀGa_z)/L, φ(1)ᵀa_y,
    /// φ(1)ᵀa_z) [m]: the second-order foreshortening in both planes (G = ∫φ′φ′ dξ).
    pub fn tip_local(&self, q: &[f64]) -> [f64; 3] {
        self.tip_local_and_gradients(q).0
    }

    /// [`ModalBody3::tip_local`] and the foreshortening gradients of both planes
    /// ([`ModalBody3::foreshortening_gradient`] of a_y and of a_z) in one pass.
    pub fn tip_local_and_gradients(&self, q: &[f64]) -> ([f64; 3], Amplitudes, Amplitudes) {
        let nb = self.modes();
        let (ay, az) = (&q[7..7 + nb], &q[7 + nb..7 + 2 * nb]);
        let gy = self.foreshortening_gradient(ay);
        let gz = self.foreshortening_gradient(az);
        let short = 0.5
            * (gy.iter().zip(ay).map(|(g, a)| g * a).sum::<f64>()
                + gz.iter().zip(az).map(|(g, a)| g * a).sum::<f64>());
        let (d, _, _) = self.tip_elastic(q);
        ([self.props.length - short, d[0], d[1]], gy, gz)
    }

    /// The centreline at each ξ ∈ [0, 1] of the ascending `xi` at (q, q̇) onto `out`: r = R +
    /// A ū, ū = (ξL − ½∫₀^ξ(v′² + w′²)dξ/L, v, w) (the tip's [`ModalBody3::tip_local`] at ξ =
    /// 1), ṙ = Ṙ + ω × Aū + A u̇̄ (ω = 2Eṗ); the section frame: the tangent's, turned about it
    /// by the twist θ(ξ) = χᵀa_t; curvature (−w″, v″)/L² about the body's section axes (the
    /// linear field's, whose strain energy is ½∫(EI_y w″² + EI_z v″²)dx/L⁴: the twist does not
    /// turn them); twist rate χ′ᵀa_t/L. No axial strain (the linear field does not stretch).
    pub fn sample(&self, q: &[f64], qd: &[f64], xi: &[f64], out: &mut Vec<ShapePoint>) {
        let nb = self.modes();
        let l = self.props.length;
        let (ay, az, at) = (
            &q[7..7 + nb],
            &q[7 + nb..7 + 2 * nb],
            &q[7 + 2 * nb..9 + 2 * nb],
        );
        let (vy, vz) = (&qd[7..7 + nb], &qd[7 + nb..7 + 2 * nb]);
        let b = &self.basis;
        let p = [q[3], q[4], q[5], q[6]];
        let a = euler_rotation(p);
        let e = e_world(p);
        let omega: [f64; 3] =
            std::array::from_fn(|i| 2.0 * (0..4).map(|k| e[i][k] * qd[3 + k]).sum::<f64>());
        let dot = |g: Amplitudes, v: &[f64]| g.iter().zip(v).map(|(g, v)| g * v).sum::<f64>();
        let pairs = [(ay, ay), (az, az), (ay, vy), (az, vz)];
        b.sample_fields([ay, az, vy, vz], pairs, xi, |k, f, s| {
            let x = xi[k];
            let ([v, v1, v2], [w, w1, w2]) = (f[0], f[1]);
            let (u, short_rate) = if x == 1.0 {
                let (u, gy, gz) = self.tip_local_and_gradients(q);
                (u, dot(gy, vy) + dot(gz, vz))
            } else {
                let u = [x * l - 0.5 * (s[0] + s[1]) / l, v, w];
                (u, (s[2] + s[3]) / l)
            };
            let ud = [-short_rate, f[2][0], f[3][0]];
            let (chi, dchi) = torsion_shapes(x);
            let th = chi[0] * at[0] + chi[1] * at[1];
            let au = mul(&a, u);
            let wxu = cross(omega, au);
            let aud = mul(&a, ud);
            let (sv, sw) = (v1 / l, w1 / l);
            // the field's tangent (1 − ½(v′² + w′²), v′, w′) for the nonlinear body
            let tx = if self.nonlinear {
                1.0 - 0.5 * (sv * sv + sw * sw)
            } else {
                1.0
            };
            let [t, d2, d3] = minimal_frame([tx, sv, sw]);
            let (kz, ky) = if self.nonlinear {
                let (vv, ww) = (v2 / (l * l), w2 / (l * l));
                (
                    vv * (1.0 + 0.5 * sv * sv) + sv * sw * ww,
                    ww * (1.0 + 0.5 * sw * sw),
                )
            } else {
                (v2 / (l * l), w2 / (l * l))
            };
            let (sn, cs) = math::sin_cos(th);
            let d2t: [f64; 3] = std::array::from_fn(|i| cs * d2[i] + sn * d3[i]);
            let d3t: [f64; 3] = std::array::from_fn(|i| -sn * d2[i] + cs * d3[i]);
            out.push(ShapePoint {
                position: std::array::from_fn(|i| q[i] + au[i]),
                velocity: std::array::from_fn(|i| qd[i] + wxu[i] + aud[i]),
                frame: [mul(&a, t), mul(&a, d2t), mul(&a, d3t)],
                curvature: [-ky, kz],
                twist: (dchi[0] * at[0] + dchi[1] * at[1]) / l,
                ..ShapePoint::default()
            });
        });
    }

    /// Modal deflection measure max(|(v_T, w_T)|/L, |(v′, w′)|, |θ_T|): tip deflection over the
    /// length, tip slope [rad] and tip twist [rad] (the planar body's measure, plus the twist,
    /// which the first-order section director of the tip also assumes small).
    pub fn deflection(&self, q: &[f64]) -> f64 {
        let (d, s, th) = self.tip_elastic(q);
        (d.norm() / self.props.length).max(s.norm()).max(th.abs())
    }
}

/// The centreline point and section frame of a spatial modal body at x = ξL, as functions of
/// its coordinates `[R, p, a_y, a_z, a_t]`: r = R + A ū, ū = (x + c, v, w) (c = −½Σ aᵀG_m a
/// the foreshortening of both planes, zero on a linear body; the point masses' kinematics), and
/// the frame A[t, d2, d3] of [`ModalBody3::sample`]: the smallest rotation of the body's
/// section axes onto the field's tangent (1 + c′, v′, w′) (1 on a linear body), turned about
/// it by the twist θ = χ(ξ)ᵀa_t.
#[derive(Debug, Clone)]
pub struct ModalPose {
    nb: usize,
    x: f64,
    nonlinear: bool,
    /// φ_k(ξ) [-].
    phi: Vec<f64>,
    /// φ_k′(x) [1/m].
    dphi: Vec<f64>,
    /// G_m (row-major nb × nb) [1/m], zero on a linear body.
    gram: Vec<f64>,
    /// χ_m(ξ) [-].
    chi: [f64; 2],
}

impl SectionPose for ModalPose {
    fn pose<S: Real>(&self, q: impl Fn(usize) -> S) -> (V3<S>, [V3<S>; 3]) {
        let nb = self.nb;
        let zero = S::zero();
        let (mut v, mut w, mut sv, mut sw, mut c) = (zero, zero, zero, zero, zero);
        for k in 0..nb {
            let (ay, az) = (q(7 + k), q(7 + nb + k));
            v += ay * self.phi[k];
            w += az * self.phi[k];
            sv += ay * self.dphi[k];
            sw += az * self.dphi[k];
            if self.nonlinear {
                let (mut gy, mut gz) = (zero, zero);
                for j in 0..nb {
                    let g = self.gram[k * nb + j];
                    gy += q(7 + j) * g;
                    gz += q(7 + nb + j) * g;
                }
                c -= (ay * gy + az * gz) * 0.5;
            }
        }
        let a = euler_rotation([q(3), q(4), q(5), q(6)]);
        let u = [c + self.x, v, w];
        let au = mul(&a, u);
        let r = [q(0) + au[0], q(1) + au[1], q(2) + au[2]];
        let tx = if self.nonlinear {
            S::one() - (sv * sv + sw * sw) * 0.5
        } else {
            S::one()
        };
        let [t, d2, d3] = section3::minimal_frame([tx, sv, sw]);
        let th = q(7 + 2 * nb) * self.chi[0] + q(8 + 2 * nb) * self.chi[1];
        let (sn, cs) = math::sin_cos_dual(th);
        let d2t: V3<S> = std::array::from_fn(|i| d2[i] * cs + d3[i] * sn);
        let d3t: V3<S> = std::array::from_fn(|i| d3[i] * cs - d2[i] * sn);
        (r, [mul(&a, t), mul(&a, d2t), mul(&a, d3t)])
    }
}
