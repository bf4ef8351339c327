//! The spatial ANCF elements: pure functions of the element coordinates (`docs/spatial.md`,
//! element; `docs/references.md` §7.1). Three families, one name each:
//! * the 3D cable (12 coordinates, nodes `[r, r_x]`; `torsion = false`): stretching and
//!   bending, no twist ([`cable`]);
//! * the director element (18 coordinates, nodes `[r, r_x, r_y]`, r_y the section director):
//!   the cable's stretching and bending with the section frame and its twist ([`director`]);
//! * the angle element (14 coordinates, nodes `[r, r_x, θ]`, θ the nodal twist angle;
//!   `torsion_element = "angle"`): the 3D cable plus the twist angle ([`angle`]).
//!
//! The 3D cable and the director element share [`Ancf3Props`] (its `director` flag chooses):
//! this file holds their common parts (properties, quadrature tables, mass, gravity, the
//! stretching, the assembly of the element force and its tangent), `cable.rs` and
//! `director.rs` each family's own terms; the angle element ([`angle::Angle3`]) is built
//! on a 3D cable's properties.
//!
//! Coordinates (global axes), node 0 then node 1. x is the arc length of the straight reference
//! configuration, ξ = x/l. `r(x)` is the cubic Hermite interpolation of the planar element
//! ([`super::ancf::Shape`]); the director element's `r_y(x) = (1 − ξ) r0_y + ξ r1_y` (linear).
//! Stretching ε = |r_x| − 1, energy ½∫EA ε² dx on 5 Gauss points; bending on 3 ([`cable`],
//! [`director`]); Kelvin–Voigt damping (retardation time τ_d) on every strain measure.
//! Inertia ρA ∫|ṙ|² dx (the constant Hermite mass, [`MassPatterns`]) and, in the director
//! element, the director's twist inertia ([`director`]).
//!
//! An initially curved director element ([`Ancf3Props::reference`], a segment's
//! `initial_curvature`) counts ε, κ2, κ3 and the element twist from its unstressed arc
//! ([`Reference3`]: the arc's own measures at each quadrature point through the same
//! interpolation); x is then the arc length of the curved reference.
//!
//! The residual path ([`Ancf3Props::internal_force`]) is plain f64 on fixed-size arrays; the
//! tangent and damping matrices ([`Ancf3Props::tangent`]) are the exact Jacobians of the same
//! generic code by forward-mode AD (`num-dual`).

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
pub mod cable;
pub mod cable_p;
pub mod director;
mod kernel;
mod mass;

use kernel::*;
pub use kernel::{strains, twist_angle};
pub use mass::{straight, MassPatterns};

/// Coordinates of the director element (2 nodes × [r, r_x, r_y]).
pub const DIRECTOR_DOFS: usize = 18;
/// Coordinates of the 3D cable (2 nodes × [r, r_x]).
pub const CABLE_DOFS: usize = 12;
/// Starts of the nodal vectors of the element twist in the director element: r_x,0, r_y,0,
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

/// [`Ancf3Props::slots`] of the element with `d` coordinates (18: the director element, 12:
/// the 3D cable); of a const `D`, constants the fixed-size paths index without bounds checks.
#[inline(always)]
const fn slots_of(d: usize) -> ([usize; 4], [usize; 2]) {
    let st = if d == DIRECTOR_DOFS { 9 } else { 6 };
    ([0, 3, st, st + 3], [6, 15])
}

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
    /// True: the director element, nodes [r, r_x, r_y] (18 coordinates); false: the 3D cable,
    /// nodes [r, r_x] (12). The scene's `torsion`, the public key, keeps its name.
    pub director: bool,
    /// The measures of a curved unstressed configuration (the director element only),
    /// subtracted from ε, κ2, κ3 and the element twist φ; `None`: straight, the measures count
    /// from zero.
    pub reference: Option<Reference3>,
    /// A tapered element's section properties at its quadrature points ([`SectionTable3`]);
    /// `None`: uniform. With a table, `ea`, `ei_y`, `ei_z`, `rho_a` hold the mid-element values
    /// and `gj`, `rho_ip` the element's means (1/l)∫GJ dx, (1/l)∫ρI_p dx (the element twist is
    /// one rate per element, its twist inertia lumped at the nodes).
    pub taper: Option<SectionTable3>,
}

/// The strain measures of a director element's unstressed configuration, an arc of constant
/// curvature `[κ_y, κ_z]` [1/m] about the section axes (its nodal r, r_x, r_y on the arc,
/// [`arc_element`]), through the element's own interpolation, so that this configuration is
/// exactly stress-free; invariant under rigid motions (one table per segment).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference3 {
    /// ε₀ at the 5 axial points [-].
    pub axial: [f64; 5],
    /// (κ2₀, κ3₀) at the 3 bending points [1/m].
    pub bending: [[f64; 2]; 3],
    /// The element twist angle φ₀ [rad] ([`twist_angle`]).
    pub twist: f64,
    /// The arc's curvature [κ_y, κ_z] [1/m].
    pub curvature: [f64; 2],
}

/// The section frame [t, d2, d3] (columns, start-frame axes) at arc length `s` [m] along an arc
/// of curvature k = (0, κ_y, κ_z) [1/m] about the section axes, and the position [m]: the frame
/// R(s) = exp(s [k]×) (Rodrigues, axis n = k/|k|, angle |k| s), the position
/// ∫₀ˢ R e₁ = e₁ sin(|k|s)/|k| + (n × e₁)(1 − cos(|k|s))/|k| (straight for k = 0; 1 − cos
/// as 2 sin²(|k|s/2), so that a small |k| loses no digits). The world frame is R₀ R(s), the
/// world position p₀ + R₀ p(s).
pub fn arc_frame(curvature: [f64; 2], s: f64) -> ([f64; 3], [[f64; 3]; 3]) {
    let [ky, kz] = curvature;
    let w = (ky * ky + kz * kz).sqrt();
    if w == 0.0 {
        return (
            [s, 0.0, 0.0],
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        );
    }
    let n = [0.0, ky / w, kz / w];
    let (sn, cs) = math::sin_cos(w * s);
    // Rodrigues: R v = v cos + (n × v) sin + n (n·v)(1 − cos)
    let rot = |v: [f64; 3]| {
        let nv = cross(&n, &v);
        let d = dot(&n, &v) * (1.0 - cs);
        [0, 1, 2].map(|i| v[i] * cs + nv[i] * sn + n[i] * d)
    };
    let ne1 = cross(&n, &[1.0, 0.0, 0.0]);
    let half = math::sin(0.5 * w * s);
    let vers = 2.0 * half * half / w; // (1 − cos(|k|s))/|k|
    let p = [sn / w, ne1[1] * vers, ne1[2] * vers];
    (
        p,
        [
            rot([1.0, 0.0, 0.0]),
            rot([0.0, 1.0, 0.0]),
            rot([0.0, 0.0, 1.0]),
        ],
    )
}

/// The director element's 18 coordinates of length `l` [m] on an arc of curvature
/// `[κ_y, κ_z]` from the origin, start frame the identity (nodes [r, r_x = t, r_y = d2]).
pub fn arc_element(l: f64, curvature: [f64; 2]) -> [f64; DIRECTOR_DOFS] {
    let (p, f) = arc_frame(curvature, l);
    let mut e = [0.0; DIRECTOR_DOFS];
    e[3] = 1.0;
    e[7] = 1.0;
    e[9..12].copy_from_slice(&p);
    e[12..15].copy_from_slice(&f[0]);
    e[15..18].copy_from_slice(&f[1]);
    e
}

impl Reference3 {
    /// The measures of the director element `props` (its length, no reference yet) on the arc
    /// of curvature `[κ_y, κ_z]` [1/m].
    pub fn arc(props: &Ancf3Props, curvature: [f64; 2]) -> Self {
        let p = Ancf3Props {
            director: true,
            reference: None,
            ..*props
        };
        let e = arc_element(p.length, curvature);
        let tab = p.tables();
        let (rs, ys) = p.slots();
        let mut r = Self {
            axial: [0.0; 5],
            bending: [[0.0; 2]; 3],
            twist: twist_angle(&[
                [e[3], e[4], e[5]],
                [e[6], e[7], e[8]],
                [e[12], e[13], e[14]],
                [e[15], e[16], e[17]],
                combine(&tab.mid, &rs, &e),
            ]),
            curvature,
        };
        for (k, (_, ds)) in tab.axial.iter().enumerate() {
            let a = combine(ds, &rs, &e);
            r.axial[k] = dot(&a, &a).sqrt() - 1.0;
        }
        for (k, b) in tab.bending.iter().enumerate() {
            let [_, k2, k3] = strains(
                combine(&b.ds, &rs, &e),
                combine(&b.dds, &rs, &e),
                combine(&b.ny, &ys, &e),
            );
            r.bending[k] = [k2, k3];
        }
        r
    }
}

/// The section properties of a tapered spatial element at its quadrature points (a segment
/// whose dimensions vary, [`crate::scene::Dim`]): EA on the 5 axial Gauss points, (E·I_y, E·I_z)
/// on the 3 bending points, ρA on the 5 points for the mass matrix and gravity (exact: ρA(x) is
/// at most quadratic in x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionTable3 {
    /// EA [N] at the [`GAUSS5`] points.
    pub ea: [f64; 5],
    /// (E·I_y, E·I_z) [N m²] at the [`GAUSS3`] points.
    pub ei: [[f64; 2]; 3],
    /// ρA [kg/m] at the [`GAUSS5`] points.
    pub rho_a: [f64; 5],
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
    /// The same points laid out for the 3D cable's residual ([`cable::Lanes`]).
    lanes: cable::Lanes3,
}

#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct BendPoint {
    /// Gauss weight × l/2 [m].
    w: f64,
    /// (E·I_y, E·I_z) at the point [N m²] (the element's constants unless tapered).
    ei: [f64; 2],
    ds: [f64; 4],
    dds: [f64; 4],
    /// Linear shape functions of r_y (the director inertia and the bending frame).
    ny: [f64; 2],
}

impl Ancf3Props {
    /// Properties of the elements of an ANCF `segment` of a validated scene, split into its
    /// `elements` equal elements: the director element with torsion, the 3D cable without (the
    /// scene's `torsion`). Refuses
    /// what this element cannot represent, naming the segment, field and fix: the paper's
    /// simplified strain model, and E·I_y ≠ E·I_z without torsion ([`Ancf3Props::check`]).
    pub fn of_segment(segment: &Segment, director: bool) -> Result<Self, String> {
        Self::of_element(segment, director, 0.0)
    }

    /// [`Ancf3Props::of_segment`] for the element starting at arc length `x0` [m] from the
    /// segment's start: on a tapered segment ([`Segment::is_tapered`]) the element's section
    /// table ([`Ancf3Props::taper`]); on a uniform one the same as `of_segment`.
    pub fn of_element(segment: &Segment, director: bool, x0: f64) -> Result<Self, String> {
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
            director,
            reference: None,
            taper: None,
        };
        props
            .check()
            .map_err(|m| format!("segment {name:?}: {m}"))?;
        if segment.is_tapered() {
            // I_y − I_z is zero along the segment iff it is at both ends (b = h, linear in x)
            for t in [0.0, 1.0] {
                let p = segment.section_props_at(t);
                Self {
                    ei_y: e * p.i_y,
                    ei_z: e * p.i_z,
                    ..props
                }
                .check()
                .map_err(|m| format!("segment {name:?}: {m} (at x/L = {t})"))?;
            }
            return Ok(props.tapered(segment, x0));
        }
        Ok(props)
    }

    /// These properties with the section table of the element [x0, x0 + l] of the tapered
    /// `segment` (x0 [m] from its start).
    pub fn tapered(self, segment: &Segment, x0: f64) -> Self {
        let (e, g, rho) = (
            segment.youngs_modulus,
            segment.shear_modulus(),
            segment.density,
        );
        let l = self.length;
        let at = |xg: f64| segment.section_props_at((x0 + 0.5 * (xg + 1.0) * l) / segment.length);
        let mid = at(0.0);
        // element means of GJ and ρI_p: quartic in x at most, exact on 3 Gauss points
        let mean = |f: &dyn Fn(&crate::scene::SectionProps) -> f64| {
            GAUSS3
                .iter()
                .map(|(xg, wg)| 0.5 * wg * f(&at(*xg)))
                .sum::<f64>()
        };
        Self {
            rho_a: rho * mid.area,
            rho_ip: rho * mean(&|p| p.polar),
            ea: e * mid.area,
            ei_y: e * mid.i_y,
            ei_z: e * mid.i_z,
            gj: g * mean(&|p| p.torsion),
            taper: Some(SectionTable3 {
                ea: GAUSS5.map(|(xg, _)| e * at(xg).area),
                ei: GAUSS3.map(|(xg, _)| {
                    let p = at(xg);
                    [e * p.i_y, e * p.i_z]
                }),
                rho_a: GAUSS5.map(|(xg, _)| rho * at(xg).area),
            }),
            ..self
        }
    }

    /// Number of element coordinates (18 for the director element, 12 for the 3D cable).
    pub fn dofs(&self) -> usize {
        if self.director {
            DIRECTOR_DOFS
        } else {
            CABLE_DOFS
        }
    }

    /// Whether the element can represent these properties: the cable (no torsion) has one
    /// bending stiffness, so E·I_y must equal E·I_z (relative 1e-12).
    pub fn check(&self) -> Result<(), String> {
        if !self.director
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

    /// Start of each node's blocks: (r-slots of the Hermite functions S1..S4, r_y slots).
    fn slots(&self) -> ([usize; 4], [usize; 2]) {
        slots_of(self.dofs())
    }

    /// Constant part of the consistent mass matrix, row-major d × d (d = [`Ancf3Props::dofs`])
    /// [kg, kg m, kg m²]: ρA ∫SᵀS dx ⊗ I₃ on the r-blocks plus ρI_p l/2 I₃ per node (lumped) on the
    /// r_y blocks (the director element's configuration-dependent rest is
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
        if self.director {
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
        if let Some(t) = &self.taper {
            // ∫ρA(x) S_j S_k dx on 5 Gauss points (exact for ρA quadratic in x)
            let mut p = [[0.0; 4]; 4];
            for ((xg, wg), ra) in GAUSS5.iter().zip(t.rho_a) {
                let (sh, _, _) = hermite(0.5 * (xg + 1.0), l);
                for j in 0..4 {
                    for k in 0..4 {
                        p[j][k] += wg * 0.5 * l * ra * sh[j] * sh[k];
                    }
                }
            }
            return p;
        }
        let c = self.rho_a * l / 420.0;
        [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ]
        .map(|r| r.map(|x| c * x))
    }

    /// The mass matrix's scalar patterns (Hermite 4×4 on the r-blocks, 2×2 on the r_y blocks)
    /// and the block starts, for a residual without the dense matrix.
    pub fn mass_patterns(&self) -> MassPatterns {
        let (rs, ys) = self.slots();
        MassPatterns {
            hermite: self.hermite_mass(),
            twist: if self.director {
                self.twist_mass()
            } else {
                [[0.0; 2]; 2]
            },
            r_slots: rs,
            y_slots: ys,
            director: self.director,
        }
    }

    /// Generalized gravity force ∫ρA S_rᵀ g dx = ρA l [½, l/12, ½, −l/12] ⊗ g on the r-blocks
    /// (first d entries used) [N, N m].
    pub fn gravity_force(&self, g: [f64; 3]) -> [f64; DIRECTOR_DOFS] {
        let l = self.length;
        let (rs, _) = self.slots();
        let mut f = [0.0; DIRECTOR_DOFS];
        if let Some(t) = &self.taper {
            for ((xg, wg), ra) in GAUSS5.iter().zip(t.rho_a) {
                let (sh, _, _) = hermite(0.5 * (xg + 1.0), l);
                for j in 0..4 {
                    for c in 0..3 {
                        f[rs[j] + c] += wg * 0.5 * l * ra * sh[j] * g[c];
                    }
                }
            }
            return f;
        }
        let w = [0.5, l / 12.0, 0.5, -l / 12.0];
        for j in 0..4 {
            for c in 0..3 {
                f[rs[j] + c] = self.rho_a * l * w[j] * g[c];
            }
        }
        f
    }

    /// The distributed dead load of gravity `g` [m/s²] and the line load `line` q [N/m] (world
    /// axes; `None`: none): ∫Sᵀ(ρA g + q) dx on the r-blocks [N, N m]. A uniform element takes
    /// it as gravity g + q/(ρA); a tapered one integrates ρA(x) g and adds q ∫Sᵀ dx, a load per
    /// unit length whatever the section.
    pub fn load_force(&self, g: [f64; 3], line: Option<[f64; 3]>) -> [f64; DIRECTOR_DOFS] {
        match line {
            None => self.gravity_force(g),
            Some(q) if self.taper.is_none() => {
                let b = q.map(|c| c / self.rho_a);
                self.gravity_force([g[0] + b[0], g[1] + b[1], g[2] + b[2]])
            }
            Some(q) => {
                let mut f = self.gravity_force(g);
                let l = self.length;
                let w = [0.5, l / 12.0, 0.5, -l / 12.0];
                let (rs, _) = self.slots();
                for j in 0..4 {
                    for c in 0..3 {
                        f[rs[j] + c] += l * w[j] * q[c];
                    }
                }
                f
            }
        }
    }

    /// (E·I_y, E·I_z) [N m²] at bending Gauss point `k`.
    fn ei_at(&self, k: usize) -> [f64; 2] {
        self.taper
            .as_ref()
            .map_or([self.ei_y, self.ei_z], |t| t.ei[k])
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
                    ei: [0.0; 2],
                    ds,
                    dds,
                    ny: [1.0 - xi, xi],
                }
            }),
            mid: hermite(0.5, l).1,
            lanes: cable::Lanes3::default(),
        };
        for (k, (xg, wg)) in GAUSS5.iter().enumerate() {
            let (_, ds, _) = hermite(0.5 * (xg + 1.0), l);
            let ea = self.taper.as_ref().map_or(self.ea, |t| t.ea[k]);
            t.axial[k] = (wg * 0.5 * l * ea, ds);
        }
        for (k, (xg, wg)) in GAUSS3.iter().enumerate() {
            let xi = 0.5 * (xg + 1.0);
            let (_, ds, dds) = hermite(xi, l);
            t.bending[k] = BendPoint {
                w: wg * 0.5 * l,
                ei: self.ei_at(k),
                ds,
                dds,
                ny: [1.0 - xi, xi],
            };
        }
        t.lanes = cable::Lanes3::of(&t);
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
        if !self.director {
            if let (Ok(e), Ok(ed)) = (e[..].try_into(), ed[..].try_into()) {
                let mut f = [0.0; D];
                f.copy_from_slice(&self.cable_force(tab, e, ed));
                return f;
            }
        }
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
    ) -> ([f64; D], [[f64; D]; D], [[f64; D]; D]) {
        debug_assert_eq!(D, self.dofs());
        let force = self.internal_force(tab, e, ed);
        let mut k = [[0.0; D]; D];
        let mut c = [[0.0; D]; D];
        let damped = self.damping_time > 0.0;
        let (rs, ys) = self.slots();
        let mats = (&mut k, &mut c);
        for (q, (w, ds)) in tab.axial.iter().enumerate() {
            let maps = [Map::new(ds, &rs)];
            if damped {
                point_tangent::<1, 6, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                    self.axial_point(*w, q, u, Some(ud))
                });
            } else {
                point_tangent::<1, 3, D>(&maps, e, ed, mats.0, None, |u, _| {
                    self.axial_point(*w, q, u, None)
                });
            }
        }
        let cable = self.cable_bending();
        for (q, p) in tab.bending.iter().enumerate() {
            if !cable {
                let maps = [
                    Map::new(&p.ds, &rs),
                    Map::new(&p.dds, &rs),
                    Map::new(&p.ny, &ys),
                ];
                if damped {
                    point_tangent::<3, 18, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                        self.bend_point(p.w, q, p.ei, u, Some(ud))
                    });
                } else {
                    point_tangent::<3, 9, D>(&maps, e, ed, mats.0, None, |u, _| {
                        self.bend_point(p.w, q, p.ei, u, None)
                    });
                }
            } else {
                let maps = [Map::new(&p.ds, &rs), Map::new(&p.dds, &rs)];
                if damped {
                    point_tangent::<2, 12, D>(&maps, e, ed, mats.0, Some(&mut *mats.1), |u, ud| {
                        self.cable_point(p.w, p.ei, u, Some(ud))
                    });
                } else {
                    point_tangent::<2, 6, D>(&maps, e, ed, mats.0, None, |u, _| {
                        self.cable_point(p.w, p.ei, u, None)
                    });
                }
            }
        }
        if self.director {
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

    fn force_generic<T: Real, const D: usize>(
        &self,
        tab: &Tables3,
        e: &[T; D],
        ed: &[T; D],
    ) -> [T; D] {
        debug_assert_eq!(D, self.dofs());
        let damped = self.damping_time > 0.0;
        let (rs, ys) = slots_of(D);
        let mut f = [T::from(0.0); D];
        for (q, (w, ds)) in tab.axial.iter().enumerate() {
            let ud = damped.then(|| [comb(ds, &rs, ed)]);
            let [g] = self.axial_point(*w, q, &[comb(ds, &rs, e)], ud.as_ref());
            scatter(&mut f, ds, &rs, &g);
        }
        let cable = self.cable_bending();
        for (q, p) in tab.bending.iter().enumerate() {
            let (a, b) = (comb(&p.ds, &rs, e), comb(&p.dds, &rs, e));
            let (ad, bd) = if damped {
                (comb(&p.ds, &rs, ed), comb(&p.dds, &rs, ed))
            } else {
                ([T::from(0.0); 3], [T::from(0.0); 3])
            };
            if !cable {
                let c = comb(&p.ny, &ys, e);
                let ud = damped.then(|| [ad, bd, comb(&p.ny, &ys, ed)]);
                let [ga, gb, gc] = self.bend_point(p.w, q, p.ei, &[a, b, c], ud.as_ref());
                scatter(&mut f, &p.ds, &rs, &ga);
                scatter(&mut f, &p.dds, &rs, &gb);
                scatter(&mut f, &p.ny, &ys, &gc);
            } else {
                let ud = damped.then_some([ad, bd]);
                let [ga, gb] = self.cable_point(p.w, p.ei, &[a, b], ud.as_ref());
                scatter(&mut f, &p.ds, &rs, &ga);
                scatter(&mut f, &p.dds, &rs, &gb);
            }
        }
        if self.director {
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

    /// Local force of axial point `q` (weight `w`·EA): ∂/∂r_x of ½w (ε − ε₀)², Kelvin–Voigt
    /// stress ε − ε₀ + τ_d ε̇ with the rate `ud` (ε₀ the reference's, none when straight).
    #[inline(always)]
    fn axial_point<T: Real>(
        &self,
        w: f64,
        q: usize,
        u: &[V<T>; 1],
        ud: Option<&[V<T>; 1]>,
    ) -> [V<T>; 1] {
        let a = &u[0];
        let n = dot(a, a).sqrt();
        let inv = n.recip();
        let g = [a[0] * inv, a[1] * inv, a[2] * inv];
        let mut stress = n - 1.0;
        if let Some(r) = &self.reference {
            stress -= r.axial[q];
        }
        if let Some(ud) = ud {
            stress += dot(&g, &ud[0]) * self.damping_time;
        }
        let s = stress * w;
        [[g[0] * s, g[1] * s, g[2] * s]]
    }

    /// Strain energy [J] at the element coordinates `e` (d entries), with the element's
    /// quadrature tables `tab` ([`Ancf3Props::tables`]).
    pub fn strain_energy(&self, tab: &Tables3, e: &[f64]) -> f64 {
        let (rs, ys) = self.slots();
        let v = |w: &[f64], slots: &[usize]| combine(w, slots, e);
        let mut u = 0.0;
        for (q, (w, ds)) in tab.axial.iter().enumerate() {
            let a = v(ds, &rs);
            let mut eps = dot(&a, &a).sqrt() - 1.0;
            if let Some(r) = &self.reference {
                eps -= r.axial[q];
            }
            u += 0.5 * w * eps * eps;
        }
        for (q, p) in tab.bending.iter().enumerate() {
            let a = v(&p.ds, &rs);
            let b = v(&p.dds, &rs);
            if self.director {
                let c = v(&p.ny, &ys);
                let [_, mut k2, mut k3] = strains(a, b, c);
                if let Some(r) = &self.reference {
                    k2 -= r.bending[q][0];
                    k3 -= r.bending[q][1];
                }
                u += 0.5 * p.w * (p.ei[0] * k2 * k2 + p.ei[1] * k3 * k3);
            } else {
                let bv = cross(&a, &b);
                let n2 = dot(&a, &a);
                u += 0.5 * p.w * (0.5 * (p.ei[0] + p.ei[1])) * dot(&bv, &bv) / (n2 * n2);
            }
        }
        if self.director {
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
        for (q, (_, ds)) in tab.axial.iter().enumerate() {
            let mut a = [0.0; 3];
            for j in 0..4 {
                for c in 0..3 {
                    a[c] += ds[j] * e[rs[j] + c];
                }
            }
            let e0 = self.reference.map_or(0.0, |r| r.axial[q]);
            worst = worst.max((dot(&a, &a).sqrt() - 1.0 - e0).abs());
        }
        worst
    }

    /// The centreline at ξ ∈ [0, 1] of the element at `e`, `ed` (d entries each): r = S e, ṙ = S ė,
    /// the section frame (the director element: Gram–Schmidt of r_x and the interpolated r_y, so
    /// the twist shows; the 3D cable: the smallest rotation of (e_y, e_z) onto the tangent), and
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
        if self.director {
            let c = combine(&[1.0 - xi, xi], &ys, e);
            let [_, k2, k3] = strains(a, b, c);
            p.frame = director_frame(a, c);
            p.curvature = [k2, k3];
            if let Some(r) = &self.reference {
                // the arc's own measures at ξ through the same interpolation
                let e0 = arc_element(l, r.curvature);
                let (a0, b0) = (combine(&ds, &rs, &e0), combine(&dds, &rs, &e0));
                let [_, k20, k30] = strains(a0, b0, combine(&[1.0 - xi, xi], &ys, &e0));
                p.axial_strain -= dot(&a0, &a0).sqrt() - 1.0;
                p.curvature = [k2 - k20, k3 - k30];
            }
            p.twist = self.twist_rate(e);
        } else {
            p.frame = minimal_frame(a);
            let k = cross(&a, &b).map(|c| c / dot(&a, &a));
            p.curvature = [dot(&k, &p.frame[1]), dot(&k, &p.frame[2])];
        }
        p
    }
}

#[cfg(test)]
pub(crate) mod tests;
