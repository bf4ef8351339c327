//! Spatial ANCF element: the 3D cable with a twist director ("cable + twist director", 18
//! coordinates) and, without torsion, the plain 3D cable (12 coordinates). Pure functions of the
//! element coordinates; `docs/spatial.md` (element) and `docs/references.md` §7.1.
//!
//! Coordinates (global axes), node 0 then node 1: `[r, r_x, r_y]` per node with torsion, `[r,
//! r_x]` without. x is the arc length of the straight reference configuration, ξ = x/l.
//! `r(x)` is the cubic Hermite interpolation of the planar element ([`super::ancf::Shape`]),
//! `r_y(x) = (1 − ξ) r0_y + ξ r1_y` (linear).
//!
//! Strain measures per unit reference length, on the Gram–Schmidt frame t = r_x/|r_x|,
//! d2 = normalized r_y ⟂ t (section y axis), d3 = t × d2 (section z axis):
//! ε = |r_x| − 1, κ2 = −d3·r_xx/|r_x| (bending about d2: x–z plane, E·I_y),
//! κ3 = d2·r_xx/|r_x| (bending about d3: x–y plane, E·I_z); for E·I_y = E·I_z the bending
//! energy is the cable's, ½EI|r_x × r_xx|²/|r_x|⁴, whatever r_y.
//!
//! Twist (G·J): one rate per element, τ_e = φ/l, from the two nodal frames (t_i, d2_i) by
//! parallel transport, the discrete twist of Bergou, Wardetzky, Robinson, Audoly & Grinspun
//! 2008 ("Discrete elastic rods", ACM TOG 27(3):63; docs/references.md §7.1): φ is the angle
//! about t_1 from P d2_0 to d2_1, P the smallest rotation taking t_0 to t_1 ([`twist_angle`]),
//! taken directly (φ₁) and through the Hermite midpoint tangent (φ₂), φ = (4φ₂ − φ₁)/3: the
//! Richardson extrapolation of the transport's holonomy, which makes φ₁ alone a second-order
//! twist for a non-planar centreline (B2 helix, 16 elements: tip 4.9e-4 m with φ₁, 1.7e-7 m with
//! φ, 4.0e-5 m with the earlier Gauss-point twist; `cargo test --release -j1 -p hybeam --test
//! spatial_ancf -- --nocapture end_moment`). Both are exactly zero for a twist-free rod bent in
//! any plane, so a round rod deflects alike
//! under a transverse load in any direction (static spread 1.5e-14 of the peak, 8 elements,
//! `cargo test --release -j1 -p hybeam --test torsion_isotropy -- --nocapture`; the earlier
//! Gauss-point twist d2′·d3 of the linear r_y was not zero when the rod bent in a plane oblique
//! to the director: 2.5e-7), and gives ½GJΔ²/l exactly for a uniform twist Δ ∈ (−π, π) per
//! element. The angles are atan2s ([`crate::math::atan2_dual`]: libm for the real part, exact
//! derivatives of every order for the dual numbers, no std transcendental); the gradient of φ
//! is written out (kernel `twist_gradient`, checked against nested forward-mode AD), and the
//! tangent differentiates it by the same AD as the bending points (the twist's local vectors:
//! the nodal r_x, r_y and r_x at ξ = ½).
//!
//! Energy ½∫[EA ε² + EI_y κ2² + EI_z κ3²] dx + ½GJ l τ_e² plus the nodal penalty
//! Σ_nodes ½(l/2) k [(½(|r_y|² − 1))² + (t·r_y)²], k = [`PENALTY_FACTOR`]·GJ/l², which only
//! removes the two zero-energy modes of each r_y (its length and its shear angle to r_x).
//! Without torsion: ½∫[EA ε² + EI |r_x × r_xx|²/|r_x|⁴] dx (round or equal-I sections).
//! Kelvin–Voigt damping (retardation time τ_d) on ε, κ2, κ3, τ_e. The cable has no material
//! frame, so the rate of its curvature vector κ = r_x × r_xx/|r_x|² is taken relative to the
//! rotation of the tangent, κ̇ − w × κ with w = t × ṫ (dissipation ½EIτ_d|κ̇ − w × κ|²): exact
//! for rigid rotations about axes ⟂ t, but a rigid spin Ω about an axis with Ω·t ≠ 0 of a
//! *curved* cable is damped by a moment ~EIτ_d(Ω·t)|κ| (no frame can tell it from bending).
//!
//! Inertia: ρA ∫|ṙ|² dx (constant Hermite mass) and, with torsion, the director's twist
//! inertia ½ρI_p ∫|v|² dx with v = ṙ_y − w × r_y, w = (r_x × ṙ_x)/|r_x|² the rotation rate of
//! the tangent: for a rigid rotation Ω of the section v = (Ω·t) t × r_y, so bending in either
//! plane carries no director inertia (as the cable: no rotary inertia) and twist keeps ρI_p.
//! The integral is lumped at the two nodes (2-point Lobatto, weights l/2), where r_x and r_y
//! are both nodal coordinates: between the nodes the linear r_y lags the Hermite tangent's
//! rotation, and at Gauss points that lag gave a bending rotary inertia in one plane only (a
//! round rod's dynamic response then depended on the load direction by 1.07e-5 of the peak;
//! 3.0e-8 lumped, `tests/torsion_isotropy.rs`). Its ṙ_y·ṙ_y part is the constant
//! ρI_p l/2 I₃ per node ([`MassPatterns`]); the rest ([`Ancf3Props::director_inertia`]: the
//! r_x–r_y mass blocks and the velocity-quadratic terms, d/dt ∂T/∂q̇ − ∂T/∂q) its Jacobians
//! (q, q̇, q̈) by the same AD.
//!
//! Quadrature as the planar element: 5 Gauss points axial, 3 bending; the twist from the nodal
//! frames and the midpoint tangent, the penalty at the nodes. The residual path ([`Ancf3Props::internal_force`]) is plain f64 on fixed-size arrays;
//! the tangent and damping matrices ([`Ancf3Props::tangent`]) are the exact Jacobians of the
//! same generic code by forward-mode AD (`num-dual`).

// The kernels pass dual-number 3-vectors (hundreds of bytes each on the tangent path) to the
// `vector` helpers by reference on purpose: by value they would be copied at every call.
#![allow(clippy::needless_borrows_for_generic_args)]

use super::ancf::{GAUSS3, GAUSS5};
use crate::math;
use crate::model::sample::{director_frame, minimal_frame, ShapePoint};
use crate::model::vector::Real;
use crate::model::vector::{cross, dot};
use crate::scene::{Segment, StrainModel};
use num_dual::DualSVec64;

pub mod angle;
mod kernel;
mod mass;

use kernel::*;
pub use kernel::{strains, twist_angle};
pub use mass::{straight, MassPatterns};

/// Coordinates of an element with torsion (2 nodes × [r, r_x, r_y]).
pub const TORSION_DOFS: usize = 18;
/// Coordinates of a cable element (2 nodes × [r, r_x]).
pub const CABLE_DOFS: usize = 12;
/// Starts of the nodal vectors of the element twist in an element with torsion: r_x,0, r_y,0,
/// r_x,1, r_y,1.
const TWIST_SLOTS: [usize; 4] = [3, 6, 12, 15];
/// Penalty factor c of the nodal r_y penalty k = c·GJ/l_e² [-].
///
/// With c = 1 the penalty's stiffness per node, k·l_e/2 = GJ/(2 l_e), is of the order of the
/// element's torsional stiffness GJ/l_e (the Newton matrix keeps its scaling), and the penalty
/// modes sit at ω ≈ √(k/ρI_p) = √(G J/(ρ I_p))/l_e = c_t/l_e for round sections, below the
/// element's highest torsional mode √12·c_t/l_e: no new, faster time scale. Linear twist and
/// bending modes do not load it (the frame is normalized).
pub const PENALTY_FACTOR: f64 = 1.0;

/// Element properties (constant).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ancf3Props {
    /// Element length l [m].
    pub length: f64,
    /// Mass per length ρA [kg/m].
    pub rho_a: f64,
    /// Twist inertia per length ρI_p [kg m] (polar moment I_p = I_y + I_z).
    pub rho_ip: f64,
    /// Axial stiffness EA [N].
    pub ea: f64,
    /// Bending stiffness about the section y axis E·I_y [N m²] (bending in the x–z plane).
    pub ei_y: f64,
    /// Bending stiffness about the section z axis E·I_z [N m²] (bending in the x–y plane).
    pub ei_z: f64,
    /// Torsional stiffness G·J [N m²].
    pub gj: f64,
    /// Kelvin–Voigt retardation time τ_d [s] (0 = no damping).
    pub damping_time: f64,
    /// With torsion: nodes [r, r_x, r_y] (18 coordinates); without: the cable [r, r_x] (12).
    pub torsion: bool,
}

/// Quadrature tables of an element (shape functions at the points, weights times the Jacobian
/// l/2), computed once per element length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tables3 {
    /// Axial points: (w·EA, dS/dx).
    axial: [(f64, [f64; 4]); 5],
    /// Bending points (Gauss).
    bending: [BendPoint; 3],
    /// The director inertia's points: the two nodes (2-point Lobatto, weights l/2), where
    /// r_x and r_y are both nodal coordinates.
    director: [BendPoint; 2],
    /// dS/dx at the midpoint ξ = ½ (the element twist's midpoint tangent).
    mid: [f64; 4],
}

#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct BendPoint {
    /// Gauss weight × l/2 [m].
    w: f64,
    ds: [f64; 4],
    dds: [f64; 4],
    /// Linear shape functions of r_y (the director inertia and the bending frame).
    ny: [f64; 2],
}

impl Ancf3Props {
    /// Properties of the elements of an ANCF `segment` of a validated scene, split into its
    /// `elements` equal elements, with or without torsion (the scene's `torsion`). Refuses
    /// what this element cannot represent, naming the segment, field and fix: the paper's
    /// simplified strain model, and E·I_y ≠ E·I_z without torsion ([`Ancf3Props::check`]).
    pub fn of_segment(segment: &Segment, torsion: bool) -> Result<Self, String> {
        let name = &segment.name;
        if segment.strain != StrainModel::Exact {
            return Err(format!(
                "segment {name:?}: strain = \"paper\" is planar only; the spatial ANCF element \
                 uses the exact strain measures (remove `strain` or set strain = \"exact\")"
            ));
        }
        let sec = segment.section_props();
        let e = segment.youngs_modulus;
        let rho = segment.density;
        let props = Self {
            length: segment.length / segment.elements.unwrap_or(1) as f64,
            rho_a: rho * sec.area,
            rho_ip: rho * sec.polar,
            ea: e * sec.area,
            ei_y: e * sec.i_y,
            ei_z: e * sec.i_z,
            gj: segment.shear_modulus() * sec.torsion,
            damping_time: segment.damping_time,
            torsion,
        };
        props
            .check()
            .map_err(|m| format!("segment {name:?}: {m}"))?;
        Ok(props)
    }

    /// Number of element coordinates (18 with torsion, 12 without).
    pub fn dofs(&self) -> usize {
        if self.torsion {
            TORSION_DOFS
        } else {
            CABLE_DOFS
        }
    }

    /// Whether the element can represent these properties: the cable (no torsion) has one
    /// bending stiffness, so E·I_y must equal E·I_z (relative 1e-12).
    pub fn check(&self) -> Result<(), String> {
        if !self.torsion
            && (self.ei_y - self.ei_z).abs() > 1e-12 * self.ei_y.abs().max(self.ei_z.abs())
        {
            return Err(format!(
                "torsion = false: the 3D cable element has one bending stiffness, but E·I_y = {} \
                 and E·I_z = {} N m² differ; use a round section or tube, or torsion = true",
                self.ei_y, self.ei_z
            ));
        }
        Ok(())
    }

    /// Bending stiffness of the cable [N m²]: E·I_z (equal to E·I_y, see [`Ancf3Props::check`];
    /// the mean if they differ).
    pub fn cable_ei(&self) -> f64 {
        0.5 * (self.ei_y + self.ei_z)
    }

    /// Whether the bending points take the cable's measure ½EI|r_x × r_xx|²/|r_x|⁴: without
    /// torsion, and with torsion for an undamped section with E·I_y = E·I_z (relative 1e-12),
    /// where the material frame's ½(EI_y κ₂² + EI_z κ₃²) is that energy exactly (κ₂² + κ₃² =
    /// |t × r_xx|²/|r_x|², whatever r_y) at about half the operations. The damped torsion
    /// element keeps the frame: its curvature rates are taken in the material frame, which
    /// turns with the twist (the cable's do not).
    pub fn cable_bending(&self) -> bool {
        let round = (self.ei_y - self.ei_z).abs() <= 1e-12 * self.ei_y.abs().max(self.ei_z.abs());
        !self.torsion || (round && self.damping_time == 0.0)
    }

    /// Stiffness k of the nodal r_y penalty [N]: [`PENALTY_FACTOR`]·GJ/l².
    pub fn penalty_stiffness(&self) -> f64 {
        PENALTY_FACTOR * self.gj / (self.length * self.length)
    }

    /// Start of each node's blocks: (r-slots of the Hermite functions S1..S4, r_y slots).
    fn slots(&self) -> ([usize; 4], [usize; 2]) {
        let st = if self.torsion { 9 } else { 6 };
        ([0, 3, st, st + 3], [6, 15])
    }

    /// Constant part of the consistent mass matrix, row-major d × d (d = [`Ancf3Props::dofs`])
    /// [kg, kg m, kg m²]: ρA ∫SᵀS dx ⊗ I₃ on the r-blocks plus ρI_p l/2 I₃ per node (lumped) on the
    /// r_y blocks (with torsion the configuration-dependent rest is
    /// [`Ancf3Props::director_tangent`]'s).
    pub fn mass_matrix(&self) -> Vec<f64> {
        let d = self.dofs();
        let mut m = vec![0.0; d * d];
        let (rs, ys) = self.slots();
        let h = self.hermite_mass();
        for j in 0..4 {
            for k in 0..4 {
                for c in 0..3 {
                    m[(rs[j] + c) * d + rs[k] + c] += h[j][k];
                }
            }
        }
        if self.torsion {
            let y = self.twist_mass();
            for j in 0..2 {
                for k in 0..2 {
                    for c in 0..3 {
                        m[(ys[j] + c) * d + ys[k] + c] += y[j][k];
                    }
                }
            }
        }
        m
    }

    /// The 4×4 Hermite mass pattern ρA l/420 [156, 22l, 54, −13l; …].
    fn hermite_mass(&self) -> [[f64; 4]; 4] {
        let l = self.length;
        let c = self.rho_a * l / 420.0;
        [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ]
        .map(|r| r.map(|x| c * x))
    }

    /// The 2×2 r_y mass pattern ρI_p l/2 [1 0; 0 1] (lumped at the nodes, as the director
    /// inertia's points).
    fn twist_mass(&self) -> [[f64; 2]; 2] {
        let h = 0.5 * self.rho_ip * self.length;
        [[h, 0.0], [0.0, h]]
    }

    /// The mass matrix's scalar patterns (Hermite 4×4 on the r-blocks, 2×2 on the r_y blocks)
    /// and the block starts, for a residual without the dense matrix.
    pub fn mass_patterns(&self) -> MassPatterns {
        let (rs, ys) = self.slots();
        MassPatterns {
            hermite: self.hermite_mass(),
            twist: if self.torsion {
                self.twist_mass()
            } else {
                [[0.0; 2]; 2]
            },
            r_slots: rs,
            y_slots: ys,
            torsion: self.torsion,
        }
    }

    /// Generalized gravity force ∫ρA S_rᵀ g dx = ρA l [½, l/12, ½, −l/12] ⊗ g on the r-blocks
    /// (first d entries used) [N, N m].
    pub fn gravity_force(&self, g: [f64; 3]) -> [f64; TORSION_DOFS] {
        let l = self.length;
        let w = [0.5, l / 12.0, 0.5, -l / 12.0];
        let (rs, _) = self.slots();
        let mut f = [0.0; TORSION_DOFS];
        for j in 0..4 {
            for c in 0..3 {
                f[rs[j] + c] = self.rho_a * l * w[j] * g[c];
            }
        }
        f
    }

    /// Quadrature tables (weights × l/2 × EA for the axial points).
    pub fn tables(&self) -> Tables3 {
        let l = self.length;
        let mut t = Tables3 {
            axial: [(0.0, [0.0; 4]); 5],
            bending: [BendPoint::default(); 3],
            director: [0.0, 1.0].map(|xi: f64| {
                let (_, ds, dds) = hermite(xi, l);
                BendPoint {
                    w: 0.5 * l,
                    ds,
                    dds,
                    ny: [1.0 - xi, xi],
                }
            }),
            mid: hermite(0.5, l).1,
        };
        for (k, (xg, wg)) in GAUSS5.iter().enumerate() {
            let (_, ds, _) = hermite(0.5 * (xg + 1.0), l);
            t.axial[k] = (wg * 0.5 * l * self.ea, ds);
        }
        for (k, (xg, wg)) in GAUSS3.iter().enumerate() {
            let xi = 0.5 * (xg + 1.0);
            let (_, ds, dds) = hermite(xi, l);
            t.bending[k] = BendPoint {
                w: wg * 0.5 * l,
                ds,
                dds,
                ny: [1.0 - xi, xi],
            };
        }
        t
    }

    /// Internal (elastic + damping) generalized force at (e, ė), positive resisting [N, N m]:
    /// the residual path (f64, no allocation). `D` must be [`Ancf3Props::dofs`].
    pub fn internal_force<const D: usize>(
        &self,
        tab: &Tables3,
        e: &[f64; D],
        ed: &[f64; D],
    ) -> [f64; D] {
        self.force_generic(tab, e, ed)
    }

    /// Internal force, tangent stiffness ∂f/∂e and damping matrix ∂f/∂ė (row-major D × D),
    /// exact: forward-mode AD of the same point functions as [`Ancf3Props::internal_force`],
    /// on each quadrature point's local vectors (r_x; r_x, r_xx, r_y; the nodal r_x, r_y of the
    /// twist; …) and mapped to
    /// the element by the constant shape weights.
    #[allow(clippy::type_complexity)]
    pub fn tangent<const D: usize>(
        &self,
        tab: &Tables3,
        e: &[f64; D],
        ed: &[f64; D],
    ) -> ([f64; D], Box<[[f64; D]; D]>, Box<[[f64; D]; D]>) {
        debug_assert_eq!(D, self.dofs());
        let force = self.internal_force(tab, e, ed);
        let mut k = Box::new([[0.0; D]; D]);
        let mut c = Box::new([[0.0; D]; D]);
        let damped = self.damping_time > 0.0;
        let (rs, ys) = self.slots();
        let mats = (&mut *k, &mut *c);
        for (w, ds) in &tab.axial {
            let maps = [Map::new(ds, &rs)];
            if damped {
                point_tangent::<1, 6, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                    self.axial_point(*w, u, Some(ud))
                });
            } else {
                point_tangent::<1, 3, D>(&maps, e, ed, mats.0, None, |u, _| {
                    self.axial_point(*w, u, None)
                });
            }
        }
        let cable = self.cable_bending();
        for p in &tab.bending {
            if !cable {
                let maps = [
                    Map::new(&p.ds, &rs),
                    Map::new(&p.dds, &rs),
                    Map::new(&p.ny, &ys),
                ];
                if damped {
                    point_tangent::<3, 18, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                        self.bend_point(p.w, u, Some(ud))
                    });
                } else {
                    point_tangent::<3, 9, D>(&maps, e, ed, mats.0, None, |u, _| {
                        self.bend_point(p.w, u, None)
                    });
                }
            } else {
                let maps = [Map::new(&p.ds, &rs), Map::new(&p.dds, &rs)];
                if damped {
                    point_tangent::<2, 12, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                        self.cable_point(p.w, u, Some(ud))
                    });
                } else {
                    point_tangent::<2, 6, D>(&maps, e, ed, mats.0, None, |u, _| {
                        self.cable_point(p.w, u, None)
                    });
                }
            }
        }
        if self.torsion {
            let one = [1.0];
            let sl = TWIST_SLOTS.map(|s| [s]);
            let [m0, m1, m2, m3] = sl.each_ref().map(|s| Map::new(&one, s));
            let maps = [m0, m1, m2, m3, Map::new(&tab.mid, &rs)];
            if damped {
                point_tangent::<5, 30, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                    self.twist_element(u, Some(ud))
                });
            } else {
                point_tangent::<5, 15, D>(&maps, e, ed, mats.0, None, |u, _| {
                    self.twist_element(u, None)
                });
            }
            for node in 0..2 {
                let (xs, ysl) = ([9 * node + 3], [9 * node + 6]);
                let maps = [Map::new(&[1.0], &xs), Map::new(&[1.0], &ysl)];
                point_tangent::<2, 6, D>(&maps, e, ed, mats.0, None, |u, _| self.penalty_node(u));
            }
        }
        (force, k, c)
    }

    /// The director inertia beyond the constant mass pattern at (e, ė, ë), with torsion (zero
    /// without) [N, N m]: at each node (weight w = l/2) the kinetic energy ½wρI_p|v|² of the
    /// director rate relative to the tangent's rotation, v = ṙ_y − w_t × r_y, w_t = (r_x ×
    /// ṙ_x)/|r_x|² (twist only, see the module doc), less ½wρI_p|ṙ_y|² (the pattern's).
    pub fn director_inertia<const D: usize>(
        &self,
        tab: &Tables3,
        e: &[f64; D],
        ed: &[f64; D],
        ea: &[f64; D],
    ) -> [f64; D] {
        let mut f = [0.0; D];
        if !self.torsion {
            return f;
        }
        // at the nodes the point's r_x and r_y are the nodal slots themselves (the tables'
        // director points: unit weights, read here directly)
        let (rs, ys) = self.slots();
        for (p, (xs, yl)) in tab.director.iter().zip([(rs[1], ys[0]), (rs[3], ys[1])]) {
            let v3 = |x: &[f64; D], s: usize| [x[s], x[s + 1], x[s + 2]];
            let loc = |x: &[f64; D]| [v3(x, xs), v3(x, yl)];
            let [fa, fc] = director_point(p.w * self.rho_ip, &loc(e), &loc(ed), &loc(ea));
            for c in 0..3 {
                f[xs + c] += fa[c];
                f[yl + c] += fc[c];
            }
        }
        f
    }

    /// [`Ancf3Props::director_inertia`] and its exact Jacobians (forward-mode AD): adds ∂f/∂e
    /// to `k`, ∂f/∂ė to `c`, and returns the force and ∂f/∂ë (the configuration-dependent part
    /// of the mass matrix, row-major D × D).
    #[allow(clippy::type_complexity)]
    pub fn director_tangent<const D: usize>(
        &self,
        tab: &Tables3,
        x: (&[f64; D], &[f64; D], &[f64; D]),
        k: &mut [[f64; D]; D],
        c: &mut [[f64; D]; D],
    ) -> ([f64; D], Box<[[f64; D]; D]>) {
        let mut f = [0.0; D];
        let mut m = Box::new([[0.0; D]; D]);
        if !self.torsion {
            return (f, m);
        }
        // at the nodes the point's r_x and r_y are the nodal slots themselves (as in
        // `director_inertia`): one-slot maps, no products with the zero shape weights
        let (rs, ys) = self.slots();
        for (p, (xs, yl)) in tab.director.iter().zip([(rs[1], ys[0]), (rs[3], ys[1])]) {
            let (xs, yl) = ([xs], [yl]);
            let maps = [Map::new(&[1.0], &xs), Map::new(&[1.0], &yl)];
            let kw = p.w * self.rho_ip;
            let [fa, fc] = point_tangent_acc::<2, 18, D>(&maps, x, k, c, &mut m, |u, ud, ua| {
                director_point(kw, u, ud, ua)
            });
            for c in 0..3 {
                f[xs[0] + c] += fa[c];
                f[yl[0] + c] += fc[c];
            }
        }
        (f, m)
    }

    /// Kinetic energy [J] at (e, ė) (d entries each): [`Ancf3Props::director_kinetic`] plus
    /// ½ėᵀMė of the constant mass matrix `mass` (row-major d × d, [`Ancf3Props::mass_matrix`]).
    pub fn kinetic_energy(&self, mass: &[f64], tab: &Tables3, e: &[f64], ed: &[f64]) -> f64 {
        let d = self.dofs();
        let mut t = self.director_kinetic(tab, e, ed);
        for i in 0..d {
            let mv: f64 = (0..d).map(|j| mass[i * d + j] * ed[j]).sum();
            t += 0.5 * ed[i] * mv;
        }
        t
    }

    /// The director's kinetic energy beyond the constant pattern's ½ρI_p∫|ṙ_y|² [J]: Σ over the
    /// nodes of ½wρI_p(|v|² − |ṙ_y|²) ([`Ancf3Props::director_inertia`]); 0 without
    /// torsion.
    pub fn director_kinetic(&self, tab: &Tables3, e: &[f64], ed: &[f64]) -> f64 {
        if !self.torsion {
            return 0.0;
        }
        let (rs, ys) = self.slots();
        let mut t = 0.0;
        for p in &tab.director {
            let u = [combine(&p.ds, &rs, e), combine(&p.ny, &ys, e)];
            let ud = [combine(&p.ds, &rs, ed), combine(&p.ny, &ys, ed)];
            let (dv, _) = director_rate(&u, &ud);
            let cd = ud[1];
            t += 0.5 * p.w * self.rho_ip * (dot(&dv, &dv) - dot(&cd, &cd));
        }
        t
    }

    fn force_generic<T: Real, const D: usize>(
        &self,
        tab: &Tables3,
        e: &[T; D],
        ed: &[T; D],
    ) -> [T; D] {
        debug_assert_eq!(D, self.dofs());
        let damped = self.damping_time > 0.0;
        let (rs, ys) = self.slots();
        let mut f = [T::from(0.0); D];
        for (w, ds) in &tab.axial {
            let ud = damped.then(|| [comb(ds, &rs, ed)]);
            let [g] = self.axial_point(*w, &[comb(ds, &rs, e)], ud.as_ref());
            scatter(&mut f, ds, &rs, &g);
        }
        let cable = self.cable_bending();
        for p in &tab.bending {
            let (a, b) = (comb(&p.ds, &rs, e), comb(&p.dds, &rs, e));
            let (ad, bd) = if damped {
                (comb(&p.ds, &rs, ed), comb(&p.dds, &rs, ed))
            } else {
                ([T::from(0.0); 3], [T::from(0.0); 3])
            };
            if !cable {
                let c = comb(&p.ny, &ys, e);
                let ud = damped.then(|| [ad, bd, comb(&p.ny, &ys, ed)]);
                let [ga, gb, gc] = self.bend_point(p.w, &[a, b, c], ud.as_ref());
                scatter(&mut f, &p.ds, &rs, &ga);
                scatter(&mut f, &p.dds, &rs, &gb);
                scatter(&mut f, &p.ny, &ys, &gc);
            } else {
                let ud = damped.then_some([ad, bd]);
                let [ga, gb] = self.cable_point(p.w, &[a, b], ud.as_ref());
                scatter(&mut f, &p.ds, &rs, &ga);
                scatter(&mut f, &p.dds, &rs, &gb);
            }
        }
        if self.torsion {
            let vecs = |x: &[T; D]| {
                let [a, b, c, d] = TWIST_SLOTS.map(|s| [x[s], x[s + 1], x[s + 2]]);
                [a, b, c, d, comb(&tab.mid, &rs, x)]
            };
            let ud = damped.then(|| vecs(ed));
            let g = self.twist_element(&vecs(e), ud.as_ref());
            for (s, gs) in TWIST_SLOTS.iter().zip(&g) {
                for c in 0..3 {
                    f[s + c] += gs[c];
                }
            }
            scatter(&mut f, &tab.mid, &rs, &g[4]);
            for node in 0..2 {
                let (xs, yslot) = (9 * node + 3, 9 * node + 6);
                let x = [e[xs], e[xs + 1], e[xs + 2]];
                let y = [e[yslot], e[yslot + 1], e[yslot + 2]];
                let [fx, fy] = self.penalty_node(&[x, y]);
                for c in 0..3 {
                    f[xs + c] += fx[c];
                    f[yslot + c] += fy[c];
                }
            }
        }
        f
    }

    /// Local force of an axial point (weight `w`·EA): ∂/∂r_x of ½w ε², Kelvin–Voigt stress
    /// ε + τ_d ε̇ with the rate `ud`.
    #[inline(always)]
    fn axial_point<T: Real>(&self, w: f64, u: &[V<T>; 1], ud: Option<&[V<T>; 1]>) -> [V<T>; 1] {
        let a = &u[0];
        let n = dot(a, a).sqrt();
        let inv = n.recip();
        let g = [a[0] * inv, a[1] * inv, a[2] * inv];
        let mut stress = n - 1.0;
        if let Some(ud) = ud {
            stress += dot(&g, &ud[0]) * self.damping_time;
        }
        let s = stress * w;
        [[g[0] * s, g[1] * s, g[2] * s]]
    }

    /// Local forces on (r_x, r_xx, r_y) of a bending point (weight `w` [m]).
    #[inline(always)]
    fn bend_point<T: Real>(&self, w: f64, u: &[V<T>; 3], ud: Option<&[V<T>; 3]>) -> [V<T>; 3] {
        let [a, b, c] = u;
        let (m, g) = bend(a, b, c);
        let stiff = [self.ei_y, self.ei_z];
        let mut s = m;
        if let Some([ad, bd, cd]) = ud {
            for i in 0..2 {
                let gi = &g[i];
                let rate = dot(&gi.a, ad) + dot(&gi.b, bd) + dot(&gi.c, cd);
                s[i] += rate * self.damping_time;
            }
        }
        let s = [0, 1].map(|i| s[i] * (w * stiff[i]));
        [
            lin2(s[0], &g[0].a, s[1], &g[1].a),
            lin2(s[0], &g[0].b, s[1], &g[1].b),
            lin2(s[0], &g[0].c, s[1], &g[1].c),
        ]
    }

    /// Local forces on (r_x,0, r_y,0, r_x,1, r_y,1, r_x(ξ = ½)) of the element twist: energy
    /// ½GJ l τ_e² with τ_e = φ/l ([`twist_angle`]), i.e. ½(GJ/l) φ², Kelvin–Voigt stress
    /// φ + τ_d φ̇ with the rate `ud` (φ̇ = ∇φ·u̇).
    #[inline(always)]
    fn twist_element<T: Real>(&self, u: &[V<T>; 5], ud: Option<&[V<T>; 5]>) -> [V<T>; 5] {
        let (phi, g) = twist_gradient(u);
        let mut s = phi;
        if let Some(ud) = ud {
            let mut rate = T::from(0.0);
            for (ga, va) in g.iter().zip(ud) {
                rate += dot(ga, va);
            }
            s += rate * self.damping_time;
        }
        let s = s * (self.gj / self.length);
        g.map(|ga| [ga[0] * s, ga[1] * s, ga[2] * s])
    }

    /// Twist rate of the element τ_e = φ/l [rad/m] at `e` (18 entries): [`twist_angle`] of the
    /// nodal frames (and the midpoint tangent) over the element length, constant over the
    /// element.
    pub fn twist_rate(&self, e: &[f64]) -> f64 {
        let [a, b, c, d] = TWIST_SLOTS.map(|s| [e[s], e[s + 1], e[s + 2]]);
        let (rs, _) = self.slots();
        let mid = combine(&hermite(0.5, self.length).1, &rs, e);
        twist_angle(&[a, b, c, d, mid]) / self.length
    }

    /// Local forces on (r_x, r_xx) of a cable bending point (weight `w` [m]).
    #[inline(always)]
    fn cable_point<T: Real>(&self, w: f64, u: &[V<T>; 2], ud: Option<&[V<T>; 2]>) -> [V<T>; 2] {
        let [a, b] = u;
        let inv = dot(a, a).recip();
        let bv = cross(a, b);
        let kap = [bv[0] * inv, bv[1] * inv, bv[2] * inv];
        let mut mv = kap;
        if let Some([ad, bd]) = ud {
            // κ̇ − w × κ, w = (a × ȧ)/|a|² (the rotation rate of the tangent):
            // (ȧ × b + a × ḃ)/|a|² − 2κ (a·ȧ)/|a|² − (a × ȧ) × κ/|a|²
            let r1 = cross(ad, b);
            let r2 = cross(a, bd);
            let r3 = cross(&cross(a, ad), &kap);
            let ada = dot(a, ad) * 2.0;
            for c in 0..3 {
                mv[c] += (r1[c] + r2[c] - r3[c] - kap[c] * ada) * (inv * self.damping_time);
            }
        }
        let s = w * self.cable_ei();
        let mv = [mv[0] * s, mv[1] * s, mv[2] * s];
        // Jᵀμ of κ̇_rel = J ė (J = ∂κ/∂e on the elastic part, κ·a = 0):
        // a-part [b × μ − 2(κ·μ) a + (a·μ) κ]/|a|², b-part (μ × a)/|a|²
        let bm = cross(b, &mv);
        let ma = cross(&mv, a);
        let km = dot(&kap, &mv) * (-2.0);
        let am = dot(a, &mv);
        [
            lin3(inv, &bm, km * inv, a, am * inv, &kap),
            [ma[0] * inv, ma[1] * inv, ma[2] * inv],
        ]
    }

    /// Local forces on (r_x, r_y) of a node's penalty ½(l/2)k[(½(|y|² − 1))² + γ²], γ = t·y.
    #[inline(always)]
    fn penalty_node<T: Real>(&self, u: &[V<T>; 2]) -> [V<T>; 2] {
        let kp = 0.5 * self.length * self.penalty_stiffness();
        let [x, y] = u;
        let inv_n = dot(x, x).sqrt().recip();
        let gam = dot(x, y) * inv_n;
        let ystr = (dot(y, y) - 1.0) * 0.5;
        [
            lin2(gam * inv_n * kp, y, -(gam * gam) * inv_n * inv_n * kp, x),
            lin2(ystr * kp, y, gam * inv_n * kp, x),
        ]
    }

    /// Strain energy [J] at the element coordinates `e` (d entries), with the element's
    /// quadrature tables `tab` ([`Ancf3Props::tables`]).
    pub fn strain_energy(&self, tab: &Tables3, e: &[f64]) -> f64 {
        let (rs, ys) = self.slots();
        let v = |w: &[f64], slots: &[usize]| combine(w, slots, e);
        let mut u = 0.0;
        for (w, ds) in &tab.axial {
            let a = v(ds, &rs);
            let eps = dot(&a, &a).sqrt() - 1.0;
            u += 0.5 * w * eps * eps;
        }
        for p in &tab.bending {
            let a = v(&p.ds, &rs);
            let b = v(&p.dds, &rs);
            if self.torsion {
                let c = v(&p.ny, &ys);
                let [_, k2, k3] = strains(a, b, c);
                u += 0.5 * p.w * (self.ei_y * k2 * k2 + self.ei_z * k3 * k3);
            } else {
                let bv = cross(&a, &b);
                let n2 = dot(&a, &a);
                u += 0.5 * p.w * self.cable_ei() * dot(&bv, &bv) / (n2 * n2);
            }
        }
        if self.torsion {
            let tau = self.twist_rate(e);
            u += 0.5 * self.gj * self.length * tau * tau;
            let kp = 0.5 * self.length * self.penalty_stiffness();
            for node in 0..2 {
                let x = [e[9 * node + 3], e[9 * node + 4], e[9 * node + 5]];
                let y = [e[9 * node + 6], e[9 * node + 7], e[9 * node + 8]];
                let gam = dot(&x, &y) / dot(&x, &x).sqrt();
                let ystr = 0.5 * (dot(&y, &y) - 1.0);
                u += 0.5 * kp * (ystr * ystr + gam * gam);
            }
        }
        u
    }

    /// Largest |ε| over the axial quadrature points of `e` (d entries).
    pub fn max_axial_strain(&self, tab: &Tables3, e: &[f64]) -> f64 {
        let (rs, _) = self.slots();
        let mut worst: f64 = 0.0;
        for (_, ds) in &tab.axial {
            let mut a = [0.0; 3];
            for j in 0..4 {
                for c in 0..3 {
                    a[c] += ds[j] * e[rs[j] + c];
                }
            }
            worst = worst.max((dot(&a, &a).sqrt() - 1.0).abs());
        }
        worst
    }

    /// Section-director measures of an element with torsion at `e` (18 entries): the twist
    /// within the element [rad], |φ| = |τ_e| l ([`twist_angle`]: the angle about the node-1
    /// tangent between the node-1 section axis and the node-0 one carried along by parallel
    /// transport; π if a tangent turns back), and the smaller of the two nodes' sines of the
    /// angle between r_x and r_y (0 for a vanishing r_y). Never NaN.
    pub fn section_measures(&self, e: &[f64]) -> (f64, f64) {
        let v = |i: usize| [e[i], e[i + 1], e[i + 2]];
        let unit = |a: [f64; 3]| {
            let n = dot(&a, &a).sqrt();
            a.map(|x| x / n)
        };
        let mut tangents = [[0.0; 3]; 2];
        let mut sine = f64::INFINITY;
        for (node, t) in tangents.iter_mut().enumerate() {
            *t = unit(v(9 * node + 3));
            let y = v(9 * node + 6);
            let u = cross(&*t, &y);
            let s = (dot(&u, &u) / dot(&y, &y)).sqrt();
            sine = sine.min(if s.is_finite() { s } else { 0.0 });
        }
        let (rs, _) = self.slots();
        let mid = combine(&hermite(0.5, self.length).1, &rs, e);
        let [t0, t1] = tangents;
        let tm = unit(mid);
        let turns_back = |a: &[f64; 3], b: &[f64; 3]| {
            let c = dot(a, b);
            c.is_nan() || 1.0 + c <= 1e-12
        };
        let worst = std::f64::consts::PI;
        if turns_back(&t0, &t1) || turns_back(&t0, &tm) || turns_back(&tm, &t1) || sine == 0.0 {
            return (worst, sine);
        }
        let twist = twist_angle(&[v(3), v(6), v(12), v(15), mid]).abs();
        (if twist.is_nan() { worst } else { twist }, sine)
    }

    /// The centreline at ξ ∈ [0, 1] of the element at `e`, `ed` (d entries each): r = S e,
    /// ṙ = S ė, the section frame (with torsion: Gram–Schmidt of r_x and the interpolated r_y,
    /// so the twist shows; without: the smallest rotation of (e_y, e_z) onto the tangent), and
    /// the element's own strain measures ε, (κ2, κ3), τ (the module doc); the cable's curvature
    /// vector r_x × r_xx/|r_x|² on its frame, no twist.
    pub fn sample(&self, e: &[f64], ed: &[f64], xi: f64) -> ShapePoint {
        let (rs, ys) = self.slots();
        let l = self.length;
        let (sh, ds, dds) = hermite(xi, l);
        let (a, b) = (combine(&ds, &rs, e), combine(&dds, &rs, e));
        let mut p = ShapePoint {
            position: combine(&sh, &rs, e),
            velocity: combine(&sh, &rs, ed),
            axial_strain: dot(&a, &a).sqrt() - 1.0,
            ..ShapePoint::default()
        };
        if self.torsion {
            let c = combine(&[1.0 - xi, xi], &ys, e);
            let [_, k2, k3] = strains(a, b, c);
            p.frame = director_frame(a, c);
            p.curvature = [k2, k3];
            p.twist = self.twist_rate(e);
        } else {
            p.frame = minimal_frame(a);
            let k = cross(&a, &b).map(|c| c / dot(&a, &a));
            p.curvature = [dot(&k, &p.frame[1]), dot(&k, &p.frame[2])];
        }
        p
    }

    /// Strain measures (ε, κ2, κ3, τ_e) at ξ ∈ [0, 1] of an element with torsion (τ_e the
    /// element's twist rate, [`Ancf3Props::twist_rate`]).
    pub fn strains_at(&self, e: &[f64; TORSION_DOFS], xi: f64) -> [f64; 4] {
        let l = self.length;
        let (_, ds, dds) = hermite(xi, l);
        let (rs, ys) = self.slots();
        let a = comb(&ds, &rs, e);
        let b = comb(&dds, &rs, e);
        let c = comb(&[1.0 - xi, xi], &ys, e);
        let [eps, k2, k3] = strains(a, b, c);
        [eps, k2, k3, self.twist_rate(e)]
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::model::ancf::{AncfProps, Vec8};
    use crate::scene::StrainModel;

    /// Steel rod d = 2 mm (the paper's), element length 0.05 m; optionally E·I_y ≠ E·I_z.
    pub(crate) fn props(torsion: bool, tau: f64, ei_ratio: f64) -> Ancf3Props {
        let (e, g, rho, d) = (210e9, 210e9 / 2.6, 7850.0, 2e-3);
        let a = PI * d * d / 4.0;
        let i = a * d * d / 16.0;
        Ancf3Props {
            length: 0.05,
            rho_a: rho * a,
            rho_ip: rho * 2.0 * i,
            ea: e * a,
            ei_y: e * i * ei_ratio,
            ei_z: e * i,
            gj: g * 2.0 * i,
            damping_time: tau,
            torsion,
        }
    }

    use std::f64::consts::PI;

    /// Deterministic pseudo-random numbers in [−1, 1].
    pub(crate) fn noise(seed: u64, n: usize) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
            })
            .collect()
    }

    /// A frame (columns x̄, ȳ, z̄) rotated by `angle` about the unit `axis`.
    fn frame(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
        let rot = |v: [f64; 3]| {
            let (s, c) = angle.sin_cos();
            let kv = cross(&axis, &v);
            let kd = dot(&axis, &v);
            [0, 1, 2].map(|i| c * v[i] + s * kv[i] + (1.0 - c) * kd * axis[i])
        };
        [
            rot([1.0, 0.0, 0.0]),
            rot([0.0, 1.0, 0.0]),
            rot([0.0, 0.0, 1.0]),
        ]
    }

    /// A bent, stretched and twisted element (and a rate), deterministic.
    fn deformed<const D: usize>(p: &Ancf3Props, seed: u64) -> ([f64; D], [f64; D]) {
        let n3 = 1.0 / 3f64.sqrt();
        let f = frame([n3, -n3, n3], 0.7);
        let mut e: [f64; D] = straight([0.1, -0.2, 0.3], f, p.length, p.torsion)
            .try_into()
            .unwrap();
        let r = noise(seed, 2 * D);
        for k in 0..D {
            // positions move by ≤ 2 mm, slopes and directors by ≤ 0.15
            let s = if k % 9 < 3 && p.torsion || !p.torsion && k % 6 < 3 {
                2e-3
            } else {
                0.15
            };
            e[k] += s * r[k];
        }
        let ed: [f64; D] = std::array::from_fn(|k| 3.0 * r[D + k]);
        (e, ed)
    }

    fn check_tangent<const D: usize>(p: &Ancf3Props) {
        let tab = p.tables();
        let (e, ed) = deformed::<D>(p, 7);
        let (f, k, c) = p.tangent(&tab, &e, &ed);
        let fast = p.internal_force(&tab, &e, &ed);
        let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for i in 0..D {
            assert!((f[i] - fast[i]).abs() <= 1e-13 * fmax, "force {i}");
        }
        let kmax = k.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let cmax = c.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let (mut ek, mut ec) = (0.0f64, 0.0f64);
        for j in 0..D {
            let h = 1e-6;
            let (mut ep, mut em) = (e, e);
            ep[j] += h;
            em[j] -= h;
            let (fp, fm) = (
                p.internal_force(&tab, &ep, &ed),
                p.internal_force(&tab, &em, &ed),
            );
            let (mut vp, mut vm) = (ed, ed);
            vp[j] += h;
            vm[j] -= h;
            let (gp, gm) = (
                p.internal_force(&tab, &e, &vp),
                p.internal_force(&tab, &e, &vm),
            );
            for i in 0..D {
                ek = ek.max((((fp[i] - fm[i]) / (2.0 * h)) - k[i][j]).abs());
                ec = ec.max((((gp[i] - gm[i]) / (2.0 * h)) - c[i][j]).abs());
            }
        }
        eprintln!(
            "torsion {} tau {}: |K| {kmax:.3e}, FD error {:.1e}; |C| {cmax:.3e}, FD error {:.1e}",
            p.torsion,
            p.damping_time,
            ek / kmax,
            ec / cmax.max(1e-300)
        );
        assert!(ek <= 1e-6 * kmax, "K: {ek:e} of {kmax:e}");
        assert!(ec <= 1e-6 * cmax.max(kmax * p.damping_time), "C: {ec:e}");
        if p.damping_time == 0.0 {
            assert_eq!(cmax, 0.0);
            // symmetric (a Hessian) without damping
            for i in 0..D {
                for j in 0..D {
                    assert!((k[i][j] - k[j][i]).abs() <= 1e-9 * kmax, "K sym {i} {j}");
                }
            }
        } else {
            assert!(cmax > 0.0);
        }
    }

    /// Stiffnesses with EA/l ≈ EI/l³ ≈ GJ/l, so that no part hides behind the axial one in
    /// the relative error.
    fn balanced(torsion: bool, tau: f64) -> Ancf3Props {
        Ancf3Props {
            ea: 1.0,
            ei_y: 2e-3,
            ei_z: if torsion { 3e-3 } else { 2e-3 },
            gj: 1.0,
            ..props(torsion, tau, 1.0)
        }
    }

    #[test]
    fn tangent_and_damping_match_central_differences() {
        for tau in [0.0, 7e-4] {
            check_tangent::<18>(&props(true, tau, 1.0));
            check_tangent::<18>(&props(true, tau, 0.3));
            check_tangent::<12>(&props(false, tau, 1.0));
            check_tangent::<18>(&balanced(true, tau));
            check_tangent::<12>(&balanced(false, tau));
        }
    }

    fn check_gradient<const D: usize>(p: &Ancf3Props) {
        let tab = p.tables();
        let (e, _) = deformed::<D>(p, 11);
        let f = p.internal_force(&tab, &e, &[0.0; D]);
        let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for j in 0..D {
            let h = 1e-6;
            let (mut ep, mut em) = (e, e);
            ep[j] += h;
            em[j] -= h;
            let fd =
                (p.strain_energy(&p.tables(), &ep) - p.strain_energy(&p.tables(), &em)) / (2.0 * h);
            assert!((fd - f[j]).abs() <= 1e-6 * fmax, "{j}: {fd} vs {}", f[j]);
        }
    }

    #[test]
    fn force_is_the_gradient_of_the_strain_energy() {
        check_gradient::<18>(&props(true, 0.0, 1.0));
        check_gradient::<18>(&props(true, 0.0, 2.5));
        check_gradient::<12>(&props(false, 0.0, 1.0));
        check_gradient::<18>(&balanced(true, 0.0));
        check_gradient::<12>(&balanced(false, 0.0));
    }

    fn check_rigid<const D: usize>(p: &Ancf3Props) {
        let tab = p.tables();
        let n3 = 1.0 / 3f64.sqrt();
        for (axis, angle) in [
            ([1.0, 0.0, 0.0], 0.0),
            ([n3, n3, -n3], 2.1),
            ([0.0, 0.6, 0.8], -1.0),
        ] {
            let f = frame(axis, angle);
            let e: [f64; D] = straight([0.3, -0.1, 2.0], f, p.length, p.torsion)
                .try_into()
                .unwrap();
            // rigid velocity: ω × (x − x0) + v0 for every position, ω × director
            let (w, v0) = ([1.5, -2.0, 0.7], [0.2, 0.1, -0.3]);
            let mut ed = [0.0; D];
            let st = if p.torsion { 9 } else { 6 };
            for node in 0..2 {
                let b = st * node;
                let r = [e[b] - e[0], e[b + 1] - e[1], e[b + 2] - e[2]];
                let wr = cross(&w, &r);
                for c in 0..3 {
                    ed[b + c] = v0[c] + wr[c];
                }
                for blk in (3..st).step_by(3) {
                    let d = [e[b + blk], e[b + blk + 1], e[b + blk + 2]];
                    let wd = cross(&w, &d);
                    ed[b + blk..b + blk + 3].copy_from_slice(&wd);
                }
            }
            let force = p.internal_force(&tab, &e, &ed);
            let fmax = force.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(fmax < 1e-14 * p.ea, "{axis:?} {angle}: {fmax:e}");
            let u = p.strain_energy(&p.tables(), &e);
            assert!(u < 1e-25, "{u:e}");
        }
    }

    /// ½ρI_p (l/2) Σ_nodes |v|² with v = ṙ_y − w_t × r_y written out here with the cross
    /// product (w_t = r_x × ṙ_x/|r_x|²) on the nodal slopes and directors, independent of the
    /// kernel's expanded form and of its tables.
    fn director_energy(p: &Ancf3Props, e: &[f64; 18], ed: &[f64; 18]) -> f64 {
        let mut t = 0.0;
        for (x, y) in [(3, 6), (12, 15)] {
            let v3 = |v: &[f64; 18], s: usize| [v[s], v[s + 1], v[s + 2]];
            let (a, c) = (v3(e, x), v3(e, y));
            let (ad, cd) = (v3(ed, x), v3(ed, y));
            let w = cross(&a, &ad).map(|x| x / dot(&a, &a));
            let wc = cross(&w, &c);
            let v = [0, 1, 2].map(|i| cd[i] - wc[i]);
            t += 0.5 * (0.5 * p.length) * p.rho_ip * dot(&v, &v);
        }
        t
    }

    #[test]
    fn director_inertia_is_lagrange_of_its_kinetic_energy() {
        // ρI_p∫NᵀN ë_y + director_inertia = d/dt ∂T_y/∂ė − ∂T_y/∂e by central differences of
        // the energy (T_y is quadratic in ė: its ė-gradient by differences is exact)
        for p in [props(true, 0.0, 1.0), balanced(true, 7e-4)] {
            let tab = p.tables();
            let (e, ed) = deformed::<18>(&p, 5);
            let r = noise(9, 18);
            let ea: [f64; 18] = std::array::from_fn(|k| 40.0 * r[k]);
            let mut f = p.director_inertia(&tab, &e, &ed, &ea);
            let mut pat = p.mass_patterns();
            pat.hermite = [[0.0; 4]; 4];
            pat.add_product(&ea, &mut f);
            let grad_rate = |e: &[f64; 18], ed: &[f64; 18], i: usize| {
                let (mut vp, mut vm) = (*ed, *ed);
                vp[i] += 1.0;
                vm[i] -= 1.0;
                0.5 * (director_energy(&p, e, &vp) - director_energy(&p, e, &vm))
            };
            let h = 1e-6;
            let fmax = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(fmax > 0.0);
            for i in 0..18 {
                let ep: [f64; 18] = std::array::from_fn(|k| e[k] + h * ed[k]);
                let em: [f64; 18] = std::array::from_fn(|k| e[k] - h * ed[k]);
                let vp: [f64; 18] = std::array::from_fn(|k| ed[k] + h * ea[k]);
                let vm: [f64; 18] = std::array::from_fn(|k| ed[k] - h * ea[k]);
                let ddt = (grad_rate(&ep, &vp, i) - grad_rate(&em, &vm, i)) / (2.0 * h);
                let (mut xp, mut xm) = (e, e);
                xp[i] += h;
                xm[i] -= h;
                let dq =
                    (director_energy(&p, &xp, &ed) - director_energy(&p, &xm, &ed)) / (2.0 * h);
                let want = ddt - dq;
                assert!(
                    (f[i] - want).abs() < 1e-7 * fmax,
                    "{i}: {} vs {want} (of {fmax:e})",
                    f[i]
                );
            }
            // the element's kinetic energy is the constant pattern's translational part plus T_y
            let mut m = p.mass_patterns();
            m.twist = [[0.0; 2]; 2];
            let mut mv = [0.0; 18];
            m.add_product(&ed, &mut mv);
            let tr: f64 = 0.5 * (0..18).map(|k| ed[k] * mv[k]).sum::<f64>();
            let want = tr + director_energy(&p, &e, &ed);
            let got = p.kinetic_energy(&p.mass_matrix(), &p.tables(), &e, &ed);
            assert!((got - want).abs() < 1e-13 * want, "{got} vs {want}");
        }
    }

    #[test]
    fn director_inertia_tangent_matches_central_differences() {
        let p = props(true, 0.0, 1.0);
        let tab = p.tables();
        let (e, ed) = deformed::<18>(&p, 3);
        let r = noise(4, 18);
        let ea: [f64; 18] = std::array::from_fn(|k| 40.0 * r[k]);
        let mut k = Box::new([[0.0; 18]; 18]);
        let mut c = Box::new([[0.0; 18]; 18]);
        let (f, m) = p.director_tangent(&tab, (&e, &ed, &ea), &mut k, &mut c);
        let f0 = p.director_inertia(&tab, &e, &ed, &ea);
        let fmax = f0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for i in 0..18 {
            assert!((f[i] - f0[i]).abs() <= 1e-14 * fmax, "force {i}");
        }
        check_jacobians([e, ed, ea], &[(0, &k), (1, &c), (2, &m)], 1e-6, 1e-6, |x| {
            p.director_inertia(&tab, &x[0], &x[1], &x[2])
        });
    }

    /// Central differences (step `h`) of `f` at x = (q, q̇, q̈) against each `(which, matrix)`
    /// (∂f/∂x[which]), to `tol` of the matrix's largest entry, which must not vanish.
    pub(crate) fn check_jacobians<const D: usize>(
        x: [[f64; D]; 3],
        mats: &[(usize, &[[f64; D]; D])],
        h: f64,
        tol: f64,
        f: impl Fn(&[[f64; D]; 3]) -> [f64; D],
    ) {
        for &(which, mat) in mats {
            let big = mat.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
            assert!(big > 0.0, "{which}");
            for j in 0..D {
                let (mut xp, mut xm) = (x, x);
                xp[which][j] += h;
                xm[which][j] -= h;
                let (fp, fm) = (f(&xp), f(&xm));
                for i in 0..D {
                    let fd = (fp[i] - fm[i]) / (2.0 * h);
                    assert!(
                        (fd - mat[i][j]).abs() < tol * big,
                        "{which} ({i},{j}): {fd} vs {}",
                        mat[i][j]
                    );
                }
            }
        }
    }

    #[test]
    fn rigid_rotation_carries_director_inertia_for_the_twist_only() {
        // a bent, sheared, stretched element turning rigidly about Ω: T_y = ½ρI_p Σ w (Ω·t)²|t × r_y|²
        // over the nodes (w = l/2)
        let p = props(true, 0.0, 1.0);
        let (e, _) = deformed::<18>(&p, 2);
        let tab = p.tables();
        let (rs, ys) = p.slots();
        for om in [[0.0, 3.0, -2.0], [1.5, -2.0, 0.7], [4.0, 0.0, 0.0]] {
            let mut ed = [0.0; 18];
            for b in 0..6 {
                let s = 3 * b;
                let x = [e[s], e[s + 1], e[s + 2]];
                ed[s..s + 3].copy_from_slice(&cross(&om, &x));
            }
            let mut want = 0.0;
            for q in &tab.director {
                let (a, c) = (comb(&q.ds, &rs, &e), comb(&q.ny, &ys, &e));
                let t = a.map(|x| x / dot(&a, &a).sqrt());
                let tc = cross(&t, &c);
                let wt = dot(&om, &t);
                want += 0.5 * q.w * p.rho_ip * wt * wt * dot(&tc, &tc);
            }
            let got = director_energy(&p, &e, &ed);
            assert!(
                (got - want).abs() < 1e-12 * want.max(1e-12),
                "{om:?}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn rigid_motion_gives_zero_energy_and_force() {
        check_rigid::<18>(&props(true, 7e-4, 1.0));
        check_rigid::<18>(&props(true, 7e-4, 0.4));
        check_rigid::<12>(&props(false, 7e-4, 1.0));
    }

    #[test]
    fn rigid_rotation_of_a_bent_element_is_not_damped() {
        // bent in the x–y plane, spinning about ẑ (⟂ every tangent): the damping force is zero
        // for both variants (the cable's curvature rate is taken relative to the tangent)
        for torsion in [true, false] {
            let p = props(torsion, 7e-4, 1.0);
            let st = p.dofs() / 2;
            let l = p.length;
            let mut e = vec![0.0; p.dofs()];
            let mut ed = vec![0.0; p.dofs()];
            let w = [0.0, 0.0, 3.0];
            for node in 0..2 {
                let (ang, b) = (0.4 * node as f64, st * node);
                let (sn, cs) = f64::sin_cos(ang);
                let r = [
                    l * sn / 0.4 * node as f64,
                    l * (1.0 - cs) / 0.4 * node as f64,
                    0.0,
                ];
                let mut vecs = vec![r, [cs, sn, 0.0]];
                if torsion {
                    vecs.push([-sn, cs, 0.0]);
                }
                for (k, v) in vecs.iter().enumerate() {
                    e[b + 3 * k..b + 3 * k + 3].copy_from_slice(v);
                    ed[b + 3 * k..b + 3 * k + 3].copy_from_slice(&cross(&w, v));
                }
            }
            let tab = p.tables();
            let (f, f0): (Vec<f64>, Vec<f64>) = if torsion {
                let e: [f64; 18] = e.clone().try_into().unwrap();
                let ed: [f64; 18] = ed.clone().try_into().unwrap();
                let f = p.internal_force(&tab, &e, &ed).to_vec();
                (f, p.internal_force(&tab, &e, &[0.0; 18]).to_vec())
            } else {
                let e: [f64; 12] = e.clone().try_into().unwrap();
                let ed: [f64; 12] = ed.clone().try_into().unwrap();
                let f = p.internal_force(&tab, &e, &ed).to_vec();
                (f, p.internal_force(&tab, &e, &[0.0; 12]).to_vec())
            };
            let fmax = f0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(fmax > 1.0, "bent: {fmax}");
            for (a, b) in f.iter().zip(&f0) {
                assert!((a - b).abs() < 1e-12 * fmax, "{torsion}: {a} vs {b}");
            }
        }
    }

    /// The viewer's samples carry the element's own strain measures ([`Ancf3Props::strains_at`]
    /// with torsion; the cable's curvature |r_x × r_xx|/|r_x|²), the Hermite position and an
    /// orthonormal section frame whose d2 lies in the plane of r_x and r_y.
    #[test]
    fn samples_carry_the_elements_own_strains() {
        let p = props(true, 0.0, 1.0);
        let (e, ed) = deformed::<18>(&p, 7);
        for xi in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let s = p.sample(&e, &ed, xi);
            let [eps, k2, k3, tau] = p.strains_at(&e, xi);
            assert_eq!(
                [s.axial_strain, s.curvature[0], s.curvature[1], s.twist],
                [eps, k2, k3, tau]
            );
            let (h, _, _) = hermite(xi, p.length);
            for c in 0..3 {
                let r = h[0] * e[c] + h[1] * e[3 + c] + h[2] * e[9 + c] + h[3] * e[12 + c];
                assert!((s.position[c] - r).abs() < 1e-15, "{xi}");
            }
            let [t, d2, d3] = s.frame;
            let ry: [f64; 3] = std::array::from_fn(|c| (1.0 - xi) * e[6 + c] + xi * e[15 + c]);
            assert!(dot(&t, &d2).abs() < 1e-14 && dot(&d2, &d3).abs() < 1e-14);
            assert!(
                dot(&cross(&t, &ry), &d2).abs() < 1e-14,
                "d2 in the plane of r_x, r_y"
            );
        }
        let p = props(false, 0.0, 1.0);
        let (e, ed) = deformed::<12>(&p, 11);
        for xi in [0.1, 0.5, 0.9] {
            let s = p.sample(&e, &ed, xi);
            let (_, ds, dds) = hermite(xi, p.length);
            let v = |w: &[f64; 4], o: usize| -> [f64; 3] {
                std::array::from_fn(|c| {
                    w[0] * e[c + o]
                        + w[1] * e[3 + c + o]
                        + w[2] * e[6 + c + o]
                        + w[3] * e[9 + c + o]
                })
            };
            let (a, b) = (v(&ds, 0), v(&dds, 0));
            let k = cross(&a, &b);
            let want = dot(&k, &k).sqrt() / dot(&a, &a);
            assert!(
                (s.bending() - want).abs() < 1e-12 * want,
                "{xi}: {} vs {want}",
                s.bending()
            );
            assert_eq!(s.axial_strain, dot(&a, &a).sqrt() - 1.0);
            assert_eq!(s.twist, 0.0);
        }
    }

    #[test]
    fn strain_measures_of_a_helix_match_the_closed_form() {
        // Helix of radius ρ, pitch parameter h, arc length s: curvature k = ρ/λ²
        // (λ² = ρ² + h²); Frenet frame t, n, b. Director d2 = cos φ n + sin φ b with
        // φ = φ0 + φ1 s; the reference arc length x = s/(1 + ε). Then, per reference length,
        // κ2 = (1+ε) k sin φ, κ3 = (1+ε) k cos φ. r_y = α d2 + β t (stretched and sheared
        // director: the measures must not see α, β). (The twist is the element's, from its
        // nodal frames: `twist_is_zero_for_parallel_transported_frames`.)
        let (rho, h, eps, phi0, phi1, al, be): (f64, f64, f64, f64, f64, f64, f64) =
            (0.3, 0.12, 0.02, 0.4, 2.0, 1.3, 0.2);
        let lam = (rho * rho + h * h).sqrt();
        let k = rho / (lam * lam);
        let st = 1.0 + eps;
        for s in [0.0, 0.37, 1.9] {
            let th = s / lam;
            let (sn, cs) = th.sin_cos();
            let t = [-rho * sn / lam, rho * cs / lam, h / lam];
            let n = [-cs, -sn, 0.0];
            let b = cross(&t, &n);
            // Frenet: t′ = k n (per s)
            let phi = phi0 + phi1 * s;
            let (sp, cp) = phi.sin_cos();
            let d2 = lin2(cp, &n, sp, &b);
            let ts = [k * n[0], k * n[1], k * n[2]];
            // derivatives by the reference length x: d/dx = (1 + ε) d/ds
            let rx = t.map(|v| st * v);
            let rxx = ts.map(|v| st * st * v);
            let ry = lin2(al, &d2, be, &t);
            let [e, k2, k3] = strains(rx, rxx, ry);
            let want = [eps, st * k * sp, st * k * cp];
            for (g, w) in [e, k2, k3].iter().zip(want) {
                assert!(
                    (g - w).abs() < 1e-13,
                    "s {s}: {:?} vs {want:?}",
                    [e, k2, k3]
                );
            }
        }
    }

    #[test]
    fn uniformly_twisted_element_has_the_twist_of_its_nodes() {
        // r_y turns by Δ about the axis between the nodes: τ_e = Δ/l and the twist energy is
        // ½GJΔ²/l exactly for any Δ ∈ (−π, π) (the linear r_y's pointwise twist at 3 Gauss
        // points was too stiff by 1.0005 at 30°, 1.072 at 90°: docs/references.md §7.1).
        let p = props(true, 0.0, 1.0);
        let l = p.length;
        for deg in [-170.0, -45.0, 10.0, 30.0, 45.0, 90.0, 150.0, 179.0] {
            let delta: f64 = deg * PI / 180.0;
            let n3 = 1.0 / 3f64.sqrt();
            let f0 = frame([n3, n3, n3], 0.4);
            // frame rotated about its own axis by Δ: y1 = R(x̄, Δ) ȳ
            let y1 = {
                let (s, c) = delta.sin_cos();
                lin2(c, &f0[1], s, &f0[2])
            };
            let mut e: [f64; 18] = straight([0.0; 3], f0, l, true).try_into().unwrap();
            e[15..18].copy_from_slice(&y1);
            for xi in [0.0, 0.2, 0.5, 0.9] {
                let [eps, k2, k3, tau] = p.strains_at(&e, xi);
                assert!(eps.abs() < 1e-15 && k2.abs() < 1e-12 && k3.abs() < 1e-12);
                assert!((tau * l - delta).abs() < 1e-14, "{deg}° ξ {xi}: {tau}");
            }
            let u = p.strain_energy(&p.tables(), &e);
            let got = u / (0.5 * p.gj * delta * delta / l);
            assert!((got - 1.0).abs() < 1e-12, "{deg}: {got}");
        }
    }

    /// Nodal frames of an element bent in the plane ⟂ `normal` (arc of angle `bend`), the
    /// section directors turned by `theta` about the tangents from the in-plane normal
    /// (twist-free: d2 at node 1 is d2 at node 0 carried along the arc), node 1 turned by
    /// `extra` more about its tangent.
    fn arc_element(
        p: &Ancf3Props,
        f: [[f64; 3]; 3],
        bend: f64,
        theta: f64,
        extra: f64,
    ) -> [f64; 18] {
        let l = p.length;
        let (x, y, z) = (f[0], f[1], f[2]);
        let mut e = [0.0; 18];
        for node in 0..2 {
            let a = bend * node as f64;
            let (sa, ca) = a.sin_cos();
            let rad = l / bend;
            let r = lin2(rad * sa, &x, rad * (1.0 - ca), &y);
            let t = lin2(ca, &x, sa, &y);
            let nrm = lin2(-sa, &x, ca, &y);
            let th = theta + extra * node as f64;
            let (st, ct) = th.sin_cos();
            let d2 = lin2(ct, &nrm, st, &z);
            e[9 * node..9 * node + 3].copy_from_slice(&r);
            e[9 * node + 3..9 * node + 6].copy_from_slice(&t);
            e[9 * node + 6..9 * node + 9].copy_from_slice(&d2);
        }
        e
    }

    #[test]
    fn written_out_twist_gradient_equals_nested_ad() {
        // the written-out gradient of the element twist against forward-mode AD of the angle,
        // on bent, stretched, sheared and twisted elements
        for (k, p) in [props(true, 0.0, 1.0), balanced(true, 0.0)]
            .iter()
            .enumerate()
        {
            for seed in [2, 5, 7, 11] {
                let (e, _) = deformed::<18>(p, seed + k as u64);
                let tab = p.tables();
                let (rs, _) = p.slots();
                let [a, b, c, d] = TWIST_SLOTS.map(|s| [e[s], e[s + 1], e[s + 2]]);
                let u = [a, b, c, d, comb(&tab.mid, &rs, &e)];
                let (phi, g) = twist_gradient(&u);
                let (phi_ad, g_ad) = twist_gradient_ad(&u);
                assert_eq!(phi, phi_ad);
                assert!(phi.abs() > 1e-3, "{phi}");
                let big = g_ad.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
                for (x, y) in g.iter().flatten().zip(g_ad.iter().flatten()) {
                    assert!((x - y).abs() <= 1e-13 * big, "{seed}: {x} vs {y}");
                }
            }
        }
    }

    #[test]
    fn twist_is_zero_for_parallel_transported_frames() {
        // an element bent into an arc in any plane, its section turned by any angle about the
        // tangent without twisting: τ_e = 0 to rounding, so a round rod's energy is the same
        // whatever the bending plane relative to the section (the issue-23 isotropy); an
        // extra turn Δ of node 1 gives τ_e = Δ/l
        let p = props(true, 0.0, 1.0);
        let n3 = 1.0 / 3f64.sqrt();
        for (axis, ang) in [([0.0, 0.0, 1.0], 0.0), ([n3, -n3, n3], 1.3)] {
            let f = frame(axis, ang);
            for bend in [0.05, 0.4, 1.2] {
                let u0 = p.strain_energy(&p.tables(), &arc_element(&p, f, bend, 0.0, 0.0));
                for theta in [0.3, 1.0, 2.5, -2.0] {
                    let e = arc_element(&p, f, bend, theta, 0.0);
                    let tau = p.twist_rate(&e);
                    assert!(tau.abs() * p.length < 1e-15, "{bend} {theta}: {tau:e}");
                    let u = p.strain_energy(&p.tables(), &e);
                    assert!((u - u0).abs() <= 1e-13 * u0, "{bend} {theta}: {u} vs {u0}");
                    for extra in [0.2, -1.0] {
                        let e = arc_element(&p, f, bend, theta, extra);
                        let tau = p.twist_rate(&e);
                        assert!((tau * p.length - extra).abs() < 1e-14, "{tau}");
                    }
                }
            }
        }
    }

    #[test]
    fn in_plane_element_equals_the_planar_element() {
        // an in-plane (x–y) bent, stretched element: κ3 is the planar signed curvature, κ2 = τ
        // = 0 and the penalty vanishes for r_y = ẑ × t; energy, force and mass equal the planar
        // kernel's (Exact strain) to rounding.
        let p3 = props(true, 0.0, 1.7);
        let p2 = AncfProps {
            length: p3.length,
            rho_a: p3.rho_a,
            ea: p3.ea,
            ei: p3.ei_z,
            damping_time: 0.0,
            strain: StrainModel::Exact,
        };
        let e2 = Vec8::from_column_slice(&[0.01, -0.02, 0.9, 0.3, 0.055, 0.01, 0.7, 0.75]);
        for torsion in [true, false] {
            let p = Ancf3Props { torsion, ..p3 };
            let p = if torsion {
                p
            } else {
                Ancf3Props { ei_y: p.ei_z, ..p }
            };
            let st = p.dofs() / 2;
            let mut e3 = vec![0.0; p.dofs()];
            for node in 0..2 {
                let b = st * node;
                let (sx, sy) = (e2[4 * node + 2], e2[4 * node + 3]);
                e3[b..b + 6].copy_from_slice(&[e2[4 * node], e2[4 * node + 1], 0.0, sx, sy, 0.0]);
                if torsion {
                    let n = (sx * sx + sy * sy).sqrt();
                    e3[b + 6..b + 9].copy_from_slice(&[-sy / n, sx / n, 0.0]);
                }
            }
            let (u2, u3) = (p2.strain_energy(&e2), p.strain_energy(&p.tables(), &e3));
            assert!((u2 - u3).abs() <= 1e-14 * u2, "{torsion}: {u2} vs {u3}");
            let f2 = p2.elastic(&e2, &Vec8::zeros(), false).force;
            let tab = p.tables();
            let f3: Vec<f64> = if torsion {
                p.internal_force(
                    &tab,
                    &<[f64; 18]>::try_from(e3.clone()).unwrap(),
                    &[0.0; 18],
                )
                .to_vec()
            } else {
                p.internal_force(
                    &tab,
                    &<[f64; 12]>::try_from(e3.clone()).unwrap(),
                    &[0.0; 12],
                )
                .to_vec()
            };
            let fmax = f2.amax();
            for node in 0..2 {
                let b = st * node;
                for (k2, k3) in [(0, 0), (1, 1), (2, 3), (3, 4)] {
                    let (x2, x3) = (f2[4 * node + k2], f3[b + k3]);
                    assert!(
                        (x2 - x3).abs() <= 1e-12 * fmax,
                        "{torsion} {node} {k2}: {x2} {x3}"
                    );
                }
                for k3 in [2, 5] {
                    assert!(
                        f3[b + k3].abs() <= 1e-12 * fmax,
                        "out of plane {}",
                        f3[b + k3]
                    );
                }
                if torsion {
                    for k3 in 6..9 {
                        assert!(f3[b + k3].abs() <= 1e-12 * fmax, "r_y force {}", f3[b + k3]);
                    }
                }
            }
            let (m2, m3) = (p2.mass_matrix(), p.mass_matrix());
            let d = p.dofs();
            for i in 0..8 {
                for j in 0..8 {
                    let map = |k: usize| st * (k / 4) + [0, 1, 3, 4][k % 4];
                    assert_eq!(m2[(i, j)], m3[map(i) * d + map(j)]);
                }
            }
        }
    }

    #[test]
    fn mass_and_gravity_match_quadrature() {
        // independent: ρA ∫SᵀS by 5-point Gauss (exact for this degree), ρI_p ∫NᵀN lumped; total
        // translational mass ρA l
        let p = props(true, 0.0, 1.0);
        let l = p.length;
        let m = p.mass_matrix();
        let g = p.gravity_force([0.3, -9.81, 1.2]);
        let d = 18;
        let rs = [0, 3, 9, 12];
        let ys = [6, 15];
        let mut mi = [[0.0; 4]; 4];
        let mut yi = [[0.0; 2]; 2];
        let mut gi = [0.0; 4];
        for (xg, wg) in GAUSS5 {
            let xi = 0.5 * (xg + 1.0);
            let (s, _, _) = hermite(xi, l);
            for j in 0..4 {
                gi[j] += wg * 0.5 * l * p.rho_a * s[j];
                for k in 0..4 {
                    mi[j][k] += wg * 0.5 * l * p.rho_a * s[j] * s[k];
                }
            }
        }
        // the director's ρI_p∫NᵀN lumped at the nodes (2-point Lobatto: the trapezoid rule)
        for (xi, wl) in [(0.0, 0.5 * l), (1.0, 0.5 * l)] {
            let n = [1.0 - xi, xi];
            for j in 0..2 {
                for k in 0..2 {
                    yi[j][k] += wl * p.rho_ip * n[j] * n[k];
                }
            }
        }
        for c in 0..3 {
            for j in 0..4 {
                let want = gi[j] * [0.3, -9.81, 1.2][c];
                assert!((g[rs[j] + c] - want).abs() < 1e-15);
                for k in 0..4 {
                    assert!((m[(rs[j] + c) * d + rs[k] + c] - mi[j][k]).abs() < 1e-17);
                }
            }
            for j in 0..2 {
                for k in 0..2 {
                    assert!((m[(ys[j] + c) * d + ys[k] + c] - yi[j][k]).abs() < 1e-20);
                }
            }
        }
        let tot: f64 = [0, 2].iter().flat_map(|&j| [0, 2].map(|k| mi[j][k])).sum();
        assert!((tot - p.rho_a * l).abs() < 1e-16);
        // the patterns' product equals the dense matrix
        let a: [f64; 18] = std::array::from_fn(|k| (k as f64 * 0.37).sin());
        let mut ma = [0.0; 18];
        p.mass_patterns().add_product(&a, &mut ma);
        for i in 0..18 {
            let want: f64 = (0..18).map(|j| m[i * d + j] * a[j]).sum();
            assert!((ma[i] - want).abs() < 1e-16, "{i}");
        }
    }

    #[test]
    fn segment_properties_and_refusals() {
        let text = r#"
            name = "rod"
            kind = "ancf"
            length = 0.4
            diameter = 2e-3
            youngs_modulus = 210e9
            poisson_ratio = 0.3
            density = 7850.0
            elements = 8
            damping_time = 7e-4
        "#;
        let seg: Segment = toml::from_str(text).unwrap();
        let p = Ancf3Props::of_segment(&seg, true).unwrap();
        // independent: the round rod by hand
        let want = props(true, 7e-4, 1.0);
        for (got, want) in [
            (p.length, want.length),
            (p.rho_a, want.rho_a),
            (p.rho_ip, want.rho_ip),
            (p.ea, want.ea),
            (p.ei_y, want.ei_y),
            (p.ei_z, want.ei_z),
            (p.gj, want.gj),
        ] {
            assert!((got - want).abs() <= 1e-14 * want, "{got} vs {want}");
        }
        assert_eq!(p.damping_time, 7e-4);
        let paper = Segment {
            strain: StrainModel::Paper,
            ..seg.clone()
        };
        let msg = Ancf3Props::of_segment(&paper, true).unwrap_err();
        assert!(msg.contains("\"rod\"") && msg.contains("strain"), "{msg}");
        let rect: Segment = toml::from_str(&format!(
            "{}\nsection = \"rectangle\"\nwidth = 2e-3\nheight = 4e-3",
            text.replace("diameter = 2e-3", "")
        ))
        .unwrap();
        assert!(Ancf3Props::of_segment(&rect, true).is_ok());
        let msg = Ancf3Props::of_segment(&rect, false).unwrap_err();
        assert!(
            msg.contains("\"rod\"") && msg.contains("torsion = false"),
            "{msg}"
        );
    }

    #[test]
    fn cable_refuses_unequal_bending_stiffness() {
        assert!(props(false, 0.0, 1.0).check().is_ok());
        assert!(props(true, 0.0, 2.0).check().is_ok());
        let msg = props(false, 0.0, 2.0).check().unwrap_err();
        assert!(
            msg.contains("torsion = false") && msg.contains("E·I_y"),
            "{msg}"
        );
    }
}
