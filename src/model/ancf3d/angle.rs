//! The angle element: the spatial ANCF element with a nodal twist angle (14 coordinates):
//! nodes `[r, r_x, θ]` (global axes; [m], [-], [rad]), `torsion_element = "angle"`. Pure
//! functions of the element coordinates, as the director element's ([`super::Ancf3Props`]);
//! docs/references.md §7.7, docs/spatial.md.
//!
//! Why: the director element carries twist by a nodal vector r_y (9 coordinates per node, a
//! penalty on its length and shear, a 9-wide band); one angle per node gives 7, the cable's 6
//! plus one.
//!
//! Section director of node i: d2_i = Rot(t_i, θ_i) P(t⁰ → t_i) d⁰, the reference section axis
//! d⁰ (unit, ⟂ t⁰) carried by the smallest rotation P taking the reference axis t⁰ to the
//! node's tangent t_i = r_x,i/|r_x,i|, then turned by θ_i about t_i: the smallest-rotation
//! triad of Meier, Popp & Wall 2014 (CMAME 278:445–478; docs/references.md §7.7). It is
//! defined unless a tangent turns onto −t⁰ ([`Angle3::chart_margin`]): by the hairy-ball
//! theorem no map from the tangent alone to a section axis is smooth on the whole sphere, so a
//! node that must turn that far needs its reference (t⁰, d⁰) moved on (not done here: the
//! simulator refuses such a step, [`crate::simulator::MIN_CHART_MARGIN`]).
//!
//! Stretching and bending are the 3D cable's ([`Ancf3Props`] with `torsion` false): for a round
//! section (E·I_y = E·I_z, required) the bending energy does not see the section frame. Twist:
//! the director element's element twist ([`super::twist_angle`]: parallel transport of the
//! nodal frames between the tangents, with the midpoint's Richardson step) of the frames (t_i,
//! d2_i). Turning d2_i about t_i adds to that angle, so φ = θ₁ − θ₀ + φ_ref(r_x,0, r_x,1,
//! r_x(½)), φ_ref the twist of the reference frames P(t⁰ → t_i) d⁰, taken as the signed solid
//! angles of the spherical triangles (t⁰, t_a, t_b) (three atan2s, [`solid_angle`]): no wrap at
//! ±π per element, no penalty. Energy ½(GJ/l)φ², Kelvin–Voigt stress φ + τ_d φ̇. Its gradient
//! equals the director element's with respect to the tangents plus ∓σ(r_x,i) (the turn of
//! each reference frame about its tangent, [`spin`]; the tests compare the two).
//!
//! Twist inertia lumped at the nodes (weights l/2, as the director element): the section spins
//! about t_i at ω_i = θ̇_i + σ(r_x,i)·ṙ_x,i, where σ(a) = −(t⁰ × a)/(|a| (|a| + t⁰·a)) is the
//! spin of P(t⁰ → t) about t per unit ṙ_x ([`spin`]); T_i = ½ρI_p(l/2)ω_i². Bending turns t,
//! not the section about it: no rotary inertia of bending, as the cable.

// The kernels pass dual-number 3-vectors to the `vector` helpers by reference on purpose.
#![allow(clippy::needless_borrows_for_generic_args)]

use super::kernel::{comb, combine, hermite, lin2, scatter, Turn, V};
use super::{Ancf3Props, MassPatterns, Tables3, CABLE_DOFS};
use crate::model::sample::{director_frame, ShapePoint};
use crate::model::vector::{cross, dot, scale, Real};
use num_dual::DualSVec64;

/// Coordinates of an element with a nodal twist angle (2 nodes × [r, r_x, θ]).
pub const ANGLE_DOFS: usize = 14;
/// Starts of the r-blocks of the Hermite functions S1..S4 (r0, r0_x, r1, r1_x).
const R_SLOTS: [usize; 4] = [0, 3, 7, 10];
/// The nodal twist angles θ0, θ1.
const THETA: [usize; 2] = [6, 13];
/// The nodal slopes r0_x, r1_x.
const SLOPE: [usize; 2] = [3, 10];
/// Where the cable's 12 coordinates sit among the 14.
const CABLE_SLOTS: [usize; CABLE_DOFS] = [0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12];

/// Element properties (constant): the cable part and the reference frame of the angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Angle3 {
    /// Stretching and bending: the 3D cable (`torsion` false); also ρI_p, GJ and τ_d.
    pub cable: Ancf3Props,
    /// Reference axis t⁰ (unit, global axes): the straight initial element's axis.
    pub t0: [f64; 3],
    /// Reference section axis d⁰ (unit, ⟂ t⁰, global axes).
    pub d0: [f64; 3],
}

impl Angle3 {
    /// The element of `props` (round section: E·I_y = E·I_z, [`Ancf3Props::check`] of the
    /// cable) with reference axis `t0` and section axis `d0` (normalized here; `d0` made ⟂
    /// `t0`).
    pub fn new(props: Ancf3Props, t0: [f64; 3], d0: [f64; 3]) -> Result<Self, String> {
        let cable = Ancf3Props {
            director: false,
            ..props
        };
        if cable.check().is_err() {
            return Err(format!(
                "the angle element bends as the 3D cable, with one bending stiffness, but E·I_y = \
                 {} and E·I_z = {} N m² differ; use a round section or tube, or \
                 torsion_element = \"director\"",
                props.ei_y, props.ei_z
            ));
        }
        let t = scale(&t0, dot(&t0, &t0).sqrt().recip());
        let u = lin2(1.0, &d0, -dot(&t, &d0), &t);
        let n = dot(&u, &u).sqrt();
        if !(n > 1e-12 && t.iter().all(|x| x.is_finite())) {
            return Err(format!(
                "the reference section axis {d0:?} must not be parallel to the axis {t0:?}"
            ));
        }
        Ok(Self {
            cable,
            t0: t,
            d0: scale(&u, n.recip()),
        })
    }

    /// Quadrature tables (the cable's).
    pub fn tables(&self) -> Tables3 {
        self.cable.tables()
    }

    /// GJ/l [N m]: the element's twist stiffness.
    fn twist_stiffness(&self) -> f64 {
        self.cable.gj / self.cable.length
    }

    /// ρI_p l/2 [kg m²]: the twist inertia lumped at each node.
    pub fn node_inertia(&self) -> f64 {
        0.5 * self.cable.rho_ip * self.cable.length
    }

    /// 1 + t⁰·t of the node nearer to turning back onto −t⁰ (2 straight, 0 turned back): the
    /// angles are defined for a margin > 0; their Jacobians grow as its inverse.
    pub fn chart_margin(&self, e: &[f64]) -> f64 {
        SLOPE
            .iter()
            .map(|&s| {
                let a = [e[s], e[s + 1], e[s + 2]];
                1.0 + dot(&self.t0, &a) / dot(&a, &a).sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The section axis d2 [-] of a node with slope `a` and twist angle `theta` (unit, ⟂ t).
    pub fn director(&self, a: [f64; 3], theta: f64) -> [f64; 3] {
        section_frame(&self.t0, &self.d0, &a, theta)[1]
    }

    /// Generalized gravity force (the cable's on its r-blocks) [N, N m].
    pub fn gravity_force(&self, g: [f64; 3]) -> [f64; 14] {
        let fc = self.cable.gravity_force(g);
        from_cable(&std::array::from_fn(|k| fc[k]))
    }

    /// Gravity `g` [m/s²] and the line load `line` q [N/m] ([`Ancf3Props::load_force`] of the
    /// cable) [N, N m].
    pub fn load_force(&self, g: [f64; 3], line: Option<[f64; 3]>) -> [f64; 14] {
        let fc = self.cable.load_force(g, line);
        from_cable(&std::array::from_fn(|k| fc[k]))
    }

    /// `res += M ë` with the constant mass matrix: the cable's patterns `pat`
    /// ([`Ancf3Props::mass_patterns`] of [`Self::cable`]) on the r-blocks, ρI_p l/2 on each θ.
    pub fn add_mass_product(&self, pat: &MassPatterns, ea: &[f64; 14], res: &mut [f64; 14]) {
        let mut r = [0.0; CABLE_DOFS];
        pat.add_product(&cable_part(ea), &mut r);
        for (k, &s) in CABLE_SLOTS.iter().enumerate() {
            res[s] += r[k];
        }
        let k = self.node_inertia();
        for s in THETA {
            res[s] += k * ea[s];
        }
    }

    /// Largest |ε| over the axial quadrature points of `e` (14 entries).
    pub fn max_axial_strain(&self, tab: &Tables3, e: &[f64]) -> f64 {
        self.cable.max_axial_strain(tab, &cable_part(e))
    }

    /// The centreline at ξ ∈ [0, 1] of the element at `e`, `ed` (14 entries each): the
    /// cable's position, velocity and axial strain; the section frame from r_x(ξ) and the
    /// nodal section axes interpolated linearly (d2 = (1 − ξ) d2₀ + ξ d2₁ made ⟂ t); the
    /// curvature vector r_x × r_xx/|r_x|² on that frame; the twist rate φ/l.
    pub fn sample(&self, tab: &Tables3, e: &[f64], ed: &[f64], xi: f64) -> ShapePoint {
        let (sh, ds, dds) = hermite(xi, self.cable.length);
        let (a, b) = (combine(&ds, &R_SLOTS, e), combine(&dds, &R_SLOTS, e));
        let v = |s: usize| [e[s], e[s + 1], e[s + 2]];
        let d0 = self.director(v(SLOPE[0]), e[THETA[0]]);
        let d1 = self.director(v(SLOPE[1]), e[THETA[1]]);
        let frame = director_frame(a, lin2(1.0 - xi, &d0, xi, &d1));
        let k = scale(&cross(&a, &b), dot(&a, &a).recip());
        ShapePoint {
            position: combine(&sh, &R_SLOTS, e),
            velocity: combine(&sh, &R_SLOTS, ed),
            axial_strain: dot(&a, &a).sqrt() - 1.0,
            curvature: [dot(&k, &frame[1]), dot(&k, &frame[2])],
            frame,
            twist: self.twist(tab, e) / self.cable.length,
            ..ShapePoint::default()
        }
    }

    /// The element twist φ [rad] at `e` (14 entries): θ₁ − θ₀ + φ_ref (module doc).
    pub fn twist(&self, tab: &Tables3, e: &[f64]) -> f64 {
        let v = |s: usize| [e[s], e[s + 1], e[s + 2]];
        let am = combine(&tab.mid, &R_SLOTS, e);
        let (phi_ref, _) = self.reference_twist(&[v(SLOPE[0]), v(SLOPE[1]), am]);
        e[THETA[1]] - e[THETA[0]] + phi_ref
    }

    /// φ_ref and its gradient with respect to (r_x,0, r_x,1, r_x(½)): the transports of the
    /// reference frames around the spherical triangles (t⁰, t_a, t_b) turn them by the
    /// triangles' signed solid angles Ω (Gauss–Bonnet), so φ₁ = −Ω(t⁰, t₀, t₁), φ₂ =
    /// −Ω(t⁰, t₀, t_m) − Ω(t⁰, t_m, t₁) and φ_ref = (4φ₂ − φ₁)/3 ([`solid_angle`]; equal to
    /// [`super::twist_angle`] of the frames P(t⁰ → t_i) d⁰, which the tests check): three
    /// atan2s, no frame, d⁰ drops out.
    #[inline(always)]
    fn reference_twist<T: Real>(&self, a: &[V<T>; 3]) -> (T, [V<T>; 3]) {
        let [a0, a1, am] = a;
        let inv = |a: &V<T>| dot(a, a).sqrt().recip();
        let (i0, i1, im) = (inv(a0), inv(a1), inv(am));
        let (t0, t1, tm) = (scale(a0, i0), scale(a1, i1), scale(am, im));
        let r = self.t0.map(T::from);
        let (w01, g01) = solid_angle(&r, &t0, &t1);
        let (w0m, g0m) = solid_angle(&r, &t0, &tm);
        let (wm1, gm1) = solid_angle(&r, &tm, &t1);
        let (four, third) = (T::from(-4.0 / 3.0), T::from(1.0 / 3.0));
        let phi = (w0m + wm1) * four + w01 * third;
        // ∂φ/∂t, then δt = (I − t tᵀ) δa/|a|
        let d0 = lin2(four, &g0m[0], third, &g01[0]);
        let d1 = lin2(four, &gm1[1], third, &g01[1]);
        let dm = lin2(four, &g0m[1], four, &gm1[0]);
        let proj = |w: &V<T>, t: &V<T>, i: T| lin2(i, w, -dot(t, w) * i, t);
        (
            phi,
            [proj(&d0, &t0, i0), proj(&d1, &t1, i1), proj(&dm, &tm, im)],
        )
    }

    /// Internal (elastic + damping) generalized force at (e, ė), positive resisting [N, N m]:
    /// the cable's on its 12 coordinates plus the twist's.
    pub fn internal_force(&self, tab: &Tables3, e: &[f64; 14], ed: &[f64; 14]) -> [f64; 14] {
        let (c, cd) = (cable_part(e), cable_part(ed));
        let mut f = from_cable(&self.cable.internal_force(tab, &c, &cd));
        let mid = tab.mid;
        let loc = |x: &[f64; 14]| [v3(x, SLOPE[0]), v3(x, SLOPE[1]), comb(&mid, &R_SLOTS, x)];
        let (phi_ref, g) = self.reference_twist(&loc(e));
        let mut s = e[THETA[1]] - e[THETA[0]] + phi_ref;
        if self.cable.damping_time > 0.0 {
            let r = loc(ed);
            let rate = ed[THETA[1]] - ed[THETA[0]] + (0..3).map(|i| dot(&g[i], &r[i])).sum::<f64>();
            s += self.cable.damping_time * rate;
        }
        let s = s * self.twist_stiffness();
        f[THETA[0]] -= s;
        f[THETA[1]] += s;
        for (i, &sl) in SLOPE.iter().enumerate() {
            for c in 0..3 {
                f[sl + c] += s * g[i][c];
            }
        }
        scatter(&mut f, &mid, &R_SLOTS, &scale(&g[2], s));
        f
    }

    /// Internal force, tangent stiffness ∂f/∂e and damping matrix ∂f/∂ė (row-major 14 × 14),
    /// exact: the cable's, and the twist's from φ's gradient and its Hessian (forward-mode AD
    /// of [`Self::reference_twist`] over the three tangent vectors).
    #[allow(clippy::type_complexity)]
    pub fn tangent(
        &self,
        tab: &Tables3,
        e: &[f64; 14],
        ed: &[f64; 14],
    ) -> ([f64; 14], [[f64; 14]; 14], [[f64; 14]; 14]) {
        let force = self.internal_force(tab, e, ed);
        let (c, cd) = (cable_part(e), cable_part(ed));
        let (_, kc, cc) = self.cable.tangent(tab, &c, &cd);
        let mut k = [[0.0; 14]; 14];
        let mut cm = [[0.0; 14]; 14];
        for (i, &si) in CABLE_SLOTS.iter().enumerate() {
            for (j, &sj) in CABLE_SLOTS.iter().enumerate() {
                k[si][sj] = kc[i][j];
                cm[si][sj] = cc[i][j];
            }
        }
        // local unknowns: r_x,0 (0..3), r_x,1 (3..6), r_x(½) (6..9), θ0 (9), θ1 (10)
        let mid = tab.mid;
        let loc = |x: &[f64; 14]| [v3(x, SLOPE[0]), v3(x, SLOPE[1]), comb(&mid, &R_SLOTS, x)];
        let u = loc(e);
        let x: [V<DualSVec64<9>>; 3] = std::array::from_fn(|al| {
            std::array::from_fn(|ci| DualSVec64::<9>::from_re(u[al][ci]).derivative(3 * al + ci))
        });
        let (phi_ref, g) = self.reference_twist(&x);
        let mut grad = [0.0; 11];
        let mut hess = [[0.0; 11]; 11];
        for al in 0..3 {
            for ci in 0..3 {
                grad[3 * al + ci] = g[al][ci].re;
                if let Some(eps) = &g[al][ci].eps.0 {
                    for b in 0..9 {
                        hess[3 * al + ci][b] = eps[b];
                    }
                }
            }
        }
        grad[9] = -1.0;
        grad[10] = 1.0;
        let kt = self.twist_stiffness();
        let tau = self.cable.damping_time;
        let mut phi = e[THETA[1]] - e[THETA[0]] + phi_ref.re;
        let mut hu = [0.0; 11];
        if tau > 0.0 {
            let r = loc(ed);
            let rl: [f64; 11] = std::array::from_fn(|i| match i {
                0..=8 => r[i / 3][i % 3],
                9 => ed[THETA[0]],
                _ => ed[THETA[1]],
            });
            phi += tau * (0..11).map(|i| grad[i] * rl[i]).sum::<f64>();
            for (i, h) in hu.iter_mut().enumerate() {
                *h = (0..11).map(|j| hess[i][j] * rl[j]).sum();
            }
        }
        // K = κ[∇φ ∇φᵀ + τ ∇φ (H u̇)ᵀ + (φ + τφ̇) H], C = κτ ∇φ ∇φᵀ (κ = GJ/l)
        // each local unknown as element slots and weights (the midpoint's: the 4 Hermite ones)
        let maps: [([(usize, f64); 4], usize); 11] = std::array::from_fn(|i| {
            let mut m = [(0, 0.0); 4];
            let n = match i {
                0..=5 => {
                    m[0] = (SLOPE[i / 3] + i % 3, 1.0);
                    1
                }
                6..=8 => {
                    for j in 0..4 {
                        m[j] = (R_SLOTS[j] + i - 6, mid[j]);
                    }
                    4
                }
                _ => {
                    m[0] = (THETA[i - 9], 1.0);
                    1
                }
            };
            (m, n)
        });
        for i in 0..11 {
            for j in 0..11 {
                let kij = kt * (grad[i] * grad[j] + tau * grad[i] * hu[j] + phi * hess[i][j]);
                let cij = kt * tau * grad[i] * grad[j];
                if kij == 0.0 && cij == 0.0 {
                    continue;
                }
                for &(p, wp) in &maps[i].0[..maps[i].1] {
                    for &(q, wq) in &maps[j].0[..maps[j].1] {
                        k[p][q] += wp * wq * kij;
                        cm[p][q] += wp * wq * cij;
                    }
                }
            }
        }
        (force, k, cm)
    }

    /// The twist inertia beyond the constant ρI_p(l/2) θ̈ at each node, at (e, ė, ë) [N, N m]:
    /// d/dt ∂T/∂q̇ − ∂T/∂q of T = ½ρI_p(l/2)(θ̇ + σ·ṙ_x)² per node (module doc).
    pub fn twist_inertia(&self, e: &[f64; 14], ed: &[f64; 14], ea: &[f64; 14]) -> [f64; 14] {
        let mut f = [0.0; ANGLE_DOFS];
        for (&xs, &ts) in SLOPE.iter().zip(&THETA) {
            let (fa, ft) = node_inertia(
                self.node_inertia(),
                &self.t0,
                [v3(e, xs), v3(ed, xs), v3(ea, xs)],
                [ed[ts], ea[ts]],
            );
            for c in 0..3 {
                f[xs + c] += fa[c];
            }
            f[ts] += ft;
        }
        f
    }

    /// [`Self::twist_inertia`] and its exact Jacobians (forward-mode AD over each node's slope
    /// and angle, their rates and accelerations): adds ∂f/∂e to `k`, ∂f/∂ė to `c`, and returns
    /// the force and ∂f/∂ë (the configuration-dependent part of the mass matrix).
    #[allow(clippy::type_complexity)]
    pub fn twist_inertia_tangent(
        &self,
        (e, ed, ea): (&[f64; 14], &[f64; 14], &[f64; 14]),
        k: &mut [[f64; 14]; 14],
        c: &mut [[f64; 14]; 14],
    ) -> ([f64; 14], [[f64; 14]; 14]) {
        let mut f = [0.0; ANGLE_DOFS];
        let mut m = [[0.0; 14]; 14];
        for (&xs, &ts) in SLOPE.iter().zip(&THETA) {
            // seeds: q (a, θ) 0..4, q̇ 4..8, q̈ 8..12
            let slots = [xs, xs + 1, xs + 2, ts];
            let d = |x: &[f64; 14], i: usize, off: usize| {
                DualSVec64::<12>::from_re(x[slots[i]]).derivative(off + i)
            };
            let a: V<DualSVec64<12>> = std::array::from_fn(|i| d(e, i, 0));
            let ad: V<DualSVec64<12>> = std::array::from_fn(|i| d(ed, i, 4));
            let aa: V<DualSVec64<12>> = std::array::from_fn(|i| d(ea, i, 8));
            let (thd, tha) = (d(ed, 3, 4), d(ea, 3, 8));
            let (fa, ft) = node_inertia(self.node_inertia(), &self.t0, [a, ad, aa], [thd, tha]);
            let out = [fa[0], fa[1], fa[2], ft];
            for (i, o) in out.iter().enumerate() {
                f[slots[i]] += o.re;
                let Some(eps) = &o.eps.0 else { continue };
                for (j, &sj) in slots.iter().enumerate() {
                    k[slots[i]][sj] += eps[j];
                    c[slots[i]][sj] += eps[4 + j];
                    m[slots[i]][sj] += eps[8 + j];
                }
            }
        }
        (f, m)
    }

    /// Constant part of the mass matrix, row-major 14 × 14 [kg, kg m, kg m²]: the cable's
    /// Hermite mass on the r-blocks, ρI_p l/2 on each θ.
    pub fn mass_matrix(&self) -> Vec<f64> {
        let mc = self.cable.mass_matrix();
        let mut m = vec![0.0; ANGLE_DOFS * ANGLE_DOFS];
        for (i, &si) in CABLE_SLOTS.iter().enumerate() {
            for (j, &sj) in CABLE_SLOTS.iter().enumerate() {
                m[si * ANGLE_DOFS + sj] = mc[i * CABLE_DOFS + j];
            }
        }
        for s in THETA {
            m[s * ANGLE_DOFS + s] = self.node_inertia();
        }
        m
    }

    /// Strain energy [J] at `e` (14 entries): the cable's plus ½(GJ/l)φ².
    pub fn strain_energy(&self, tab: &Tables3, e: &[f64; 14]) -> f64 {
        let phi = self.twist(tab, e);
        self.cable.strain_energy(tab, &cable_part(e)) + 0.5 * self.twist_stiffness() * phi * phi
    }

    /// Kinetic energy [J] at (e, ė): the cable's Hermite part ½ėᵀMė (with its mass patterns
    /// `pat`, [`Ancf3Props::mass_patterns`] of [`Self::cable`], as [`Self::add_mass_product`])
    /// plus Σ_nodes ½ρI_p(l/2)ω_i².
    pub fn kinetic_energy(&self, pat: &MassPatterns, e: &[f64; 14], ed: &[f64; 14]) -> f64 {
        let cd = cable_part(ed);
        let mut mv = [0.0; CABLE_DOFS];
        pat.add_product(&cd, &mut mv);
        let mut t = 0.5 * cd.iter().zip(&mv).map(|(v, m)| v * m).sum::<f64>();
        for (&xs, &ts) in SLOPE.iter().zip(&THETA) {
            let w = ed[ts] + dot(&spin(&self.t0, &v3(e, xs)), &v3(ed, xs));
            t += 0.5 * self.node_inertia() * w * w;
        }
        t
    }
}

/// The signed solid angle Ω [sr] of the spherical triangle of the unit vectors (r, b, c) and
/// its gradients with respect to b and c: tan(Ω/2) = r·(b × c)/(1 + r·b + b·c + c·r) (Van
/// Oosterom & Strackee 1983, IEEE Trans. Biomed. Eng. 30(2):125–126). Parallel transport
/// around the triangle's geodesic edges turns a frame by Ω about r.
#[inline(always)]
fn solid_angle<T: Real>(r: &V<T>, b: &V<T>, c: &V<T>) -> (T, [V<T>; 2]) {
    let n = dot(r, &cross(b, c));
    let d = dot(r, b) + dot(b, c) + dot(c, r) + 1.0;
    let w = crate::math::atan2_dual(n, d) * 2.0;
    // dΩ = 2 (d dn − n dd)/(n² + d²); ∂n/∂b = c × r, ∂n/∂c = r × b; ∂d/∂b = r + c, ∂d/∂c = r + b
    let s = (n * n + d * d).recip() * 2.0;
    let (sd, sn) = (s * d, -(s * n));
    let one = T::from(1.0);
    let gb = lin2(sd, &cross(c, r), sn, &lin2(one, r, one, c));
    let gc = lin2(sd, &cross(r, b), sn, &lin2(one, r, one, b));
    (w, [gb, gc])
}

/// The section frame [t, d2, d3] (columns, global axes) of a node with slope `a` and twist
/// angle `theta` for the reference axes `t0`, `d0` (module doc): t = a/|a|, d2 =
/// Rot(t, θ) P(t⁰ → t) d⁰, d3 = t × d2. Generic over the scalar (the node port's Jacobians).
#[inline(always)]
pub fn section_frame<T: Real>(t0: &[f64; 3], d0: &[f64; 3], a: &V<T>, theta: T) -> [V<T>; 3] {
    let t = unit(a);
    let u = reference(&t0.map(T::from), &d0.map(T::from), &t);
    let (s, c) = crate::math::sin_cos_dual(theta);
    let d2 = lin2(c, &u, s, &cross(&t, &u));
    let d3 = cross(&t, &d2);
    [t, d2, d3]
}

/// The reference section axis P(t⁰ → t) d⁰ of a node with unit tangent `t`.
#[inline(always)]
fn reference<T: Real>(t0: &V<T>, d0: &V<T>, t: &V<T>) -> V<T> {
    Turn::new(t0, t).apply(d0)
}

/// σ(a) = −(t⁰ × a)/(|a|(|a| + t⁰·a)) [-]: the spin about t = a/|a| of the smallest rotation
/// P(t⁰ → t) per unit rate of a, ω·t = σ(a)·ȧ (from P v = c v + k × v + (k·v) k/(1 + c), k =
/// t⁰ × t, c = t⁰·t: the spin is −k·ṫ/(1 + c), and k ⟂ t turns ṫ into ȧ/|a|).
#[inline(always)]
pub fn spin<T: Real>(t0: &[f64; 3], a: &V<T>) -> V<T> {
    let n = dot(a, a).sqrt();
    let t0 = t0.map(T::from);
    let k = cross(&t0, a);
    let d = n * (n + dot(&t0, a));
    scale(&k, -d.recip())
}

/// Local inertial forces on (r_x, θ) of a node's twist kinetic energy T = ½k ω², ω = θ̇ + σ·ȧ
/// ([`spin`]; k = ρI_p l/2 [kg m²]), d/dt ∂T/∂(ȧ, θ̇) − ∂T/∂(a, θ) less the constant k θ̈:
/// with σ̇ = ∇σ ȧ and s = ∇σᵀ ȧ (∇σ written out: σ = −k/D, D = |a|(|a| + t⁰·a)),
/// Q_a = k(ω̇ σ + ω(σ̇ − s)), Q_θ = k(ω̇ − θ̈), ω̇ = θ̈ + σ·ä + σ̇·ȧ.
#[inline(always)]
fn node_inertia<T: Real>(
    k: f64,
    t0: &[f64; 3],
    [a, ad, aa]: [V<T>; 3],
    [thd, tha]: [T; 2],
) -> (V<T>, T) {
    let n = dot(&a, &a).sqrt();
    let tv = t0.map(T::from);
    let c = dot(&tv, &a);
    let kv = cross(&tv, &a);
    let inv_d = (n * (n + c)).recip();
    let sigma = scale(&kv, -inv_d);
    // ∇D = 2a + (c/n) a + n t⁰
    let grad_d = lin2(c / n + 2.0, &a, n, &tv);
    let t0_ad = cross(&tv, &ad);
    let kad = dot(&kv, &ad) * inv_d * inv_d;
    let dd = dot(&grad_d, &ad) * inv_d * inv_d;
    // σ̇ = −(t⁰ × ȧ)/D + k (∇D·ȧ)/D², ∇σᵀȧ = (t⁰ × ȧ)/D + ∇D (k·ȧ)/D²
    let sigma_dot = lin2(-inv_d, &t0_ad, dd, &kv);
    let s = lin2(inv_d, &t0_ad, kad, &grad_d);
    let w = thd + dot(&sigma, &ad);
    let wd = tha + dot(&sigma, &aa) + dot(&sigma_dot, &ad);
    let kk = T::from(k);
    let qa: V<T> = std::array::from_fn(|i| (wd * sigma[i] + w * (sigma_dot[i] - s[i])) * kk);
    (qa, (wd - tha) * kk)
}

fn v3<T: Copy>(x: &[T; 14], s: usize) -> [T; 3] {
    [x[s], x[s + 1], x[s + 2]]
}

fn unit<T: Real>(a: &V<T>) -> V<T> {
    scale(a, dot(a, a).sqrt().recip())
}

/// The cable's 12 coordinates of the element's 14 (`x`: 14 entries).
fn cable_part(x: &[f64]) -> [f64; CABLE_DOFS] {
    CABLE_SLOTS.map(|s| x[s])
}

/// The cable's 12 entries `fc` spread onto the element's 14 (zero on the angles).
fn from_cable(fc: &[f64; CABLE_DOFS]) -> [f64; ANGLE_DOFS] {
    let mut f = [0.0; ANGLE_DOFS];
    for (k, &s) in CABLE_SLOTS.iter().enumerate() {
        f[s] = fc[k];
    }
    f
}

#[cfg(test)]
mod tests;
