//! The director element (18 coordinates, nodes `[r, r_x, r_y]`, r_y the section director): its
//! section frame, twist, director penalty and director inertia, on the [`Ancf3Props`] the 3D
//! cable shares (`super`'s module doc).
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
//! Kelvin–Voigt damping (retardation time τ_d) on ε, κ2, κ3, τ_e, the curvature rates in the
//! material frame (which turns with the twist; the cable's turn with the tangent only).
//!
//! Inertia: beyond the cable's ρA ∫|ṙ|² dx (constant Hermite mass), the director's twist
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
//! Quadrature: the twist from the nodal frames and the midpoint tangent, the penalty at the
//! nodes (the bending points as the cable's).

use super::*;

impl Ancf3Props {
    /// Stiffness k of the nodal r_y penalty [N]: [`PENALTY_FACTOR`]·GJ/l².
    pub fn penalty_stiffness(&self) -> f64 {
        PENALTY_FACTOR * self.gj / (self.length * self.length)
    }

    /// The 2×2 r_y mass pattern ρI_p l/2 [1 0; 0 1] (lumped at the nodes, as the director
    /// inertia's points).
    pub(super) fn twist_mass(&self) -> [[f64; 2]; 2] {
        let h = 0.5 * self.rho_ip * self.length;
        [[h, 0.0], [0.0, h]]
    }

    /// The director inertia beyond the constant mass pattern at (e, ė, ë) of the director element
    /// (zero for the 3D cable) [N, N m]: at each node (weight w = l/2) the kinetic energy
    /// ½wρI_p|v|² of the director rate relative to the tangent's rotation, v = ṙ_y − w_t × r_y, w_t
    /// = (r_x × ṙ_x)/|r_x|² (twist only, see the module doc), less ½wρI_p|ṙ_y|² (the pattern's).
    pub fn director_inertia<const D: usize>(
        &self,
        tab: &Tables3,
        e: &[f64; D],
        ed: &[f64; D],
        ea: &[f64; D],
    ) -> [f64; D] {
        let mut f = [0.0; D];
        if !self.director {
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

    /// The moment about the world axes of the director's twist inertia at each node (world
    /// axes) [N m]: the virtual work of its residual on the node's r_x, r_y (the constant
    /// pattern's ρI_p (l/2) r̈_y and [`Ancf3Props::director_inertia`]'s rest, f_x, f_y) under
    /// a rigid rotation δθ (δr_x = δθ × r_x, δr_y = δθ × r_y): r_x × f_x + r_y × f_y. Zero for
    /// the 3D cable. Each is the lumped weight l/2 of the element's twist inertia.
    pub fn director_node_moments<const D: usize>(
        &self,
        tab: &Tables3,
        e: &[f64; D],
        ed: &[f64; D],
        ea: &[f64; D],
    ) -> [[f64; 3]; 2] {
        let mut out = [[0.0; 3]; 2];
        if !self.director {
            return out;
        }
        let (rs, ys) = self.slots();
        let nodes = [(rs[1], ys[0]), (rs[3], ys[1])];
        for ((p, (xs, yl)), o) in tab.director.iter().zip(nodes).zip(&mut out) {
            let v3 = |x: &[f64; D], s: usize| [x[s], x[s + 1], x[s + 2]];
            let loc = |x: &[f64; D]| [v3(x, xs), v3(x, yl)];
            let [fa, fc] = director_point(p.w * self.rho_ip, &loc(e), &loc(ed), &loc(ea));
            let h = 0.5 * self.rho_ip * self.length;
            let ya = v3(ea, yl);
            let fy: [f64; 3] = std::array::from_fn(|c| fc[c] + h * ya[c]);
            let (mx, my) = (cross(&v3(e, xs), &fa), cross(&v3(e, yl), &fy));
            *o = std::array::from_fn(|c| mx[c] + my[c]);
        }
        out
    }

    /// [`Ancf3Props::director_inertia`] and its exact Jacobians (forward-mode AD): adds ∂f/∂e
    /// to `k`, ∂f/∂ė to `c`, and returns the force and ∂f/∂ë (the configuration-dependent part
    /// of the mass matrix, row-major D × D); of the three only those flagged in `active`
    /// (the others stay zero and cost nothing).
    #[allow(clippy::type_complexity)]
    pub fn director_tangent<const D: usize>(
        &self,
        tab: &Tables3,
        x: (&[f64; D], &[f64; D], &[f64; D]),
        k: &mut [[f64; D]; D],
        c: &mut [[f64; D]; D],
        active: [bool; 3],
    ) -> ([f64; D], [[f64; D]; D]) {
        let mut f = [0.0; D];
        let mut m = [[0.0; D]; D];
        if !self.director {
            return (f, m);
        }
        // at the nodes the point's r_x and r_y are the nodal slots themselves (as in
        // `director_inertia`): one-slot maps, no products with the zero shape weights
        let (rs, ys) = self.slots();
        for (p, (xs, yl)) in tab.director.iter().zip([(rs[1], ys[0]), (rs[3], ys[1])]) {
            let (xs, yl) = ([xs], [yl]);
            let maps = [Map::new(&[1.0], &xs), Map::new(&[1.0], &yl)];
            let kw = p.w * self.rho_ip;
            let [fa, fc] =
                point_tangent_acc::<2, 18, D>(&maps, x, k, c, &mut m, active, |u, ud, ua| {
                    director_point(kw, u, ud, ua)
                });
            for c in 0..3 {
                f[xs[0] + c] += fa[c];
                f[yl[0] + c] += fc[c];
            }
        }
        (f, m)
    }

    /// The director's kinetic energy beyond the constant pattern's ½ρI_p∫|ṙ_y|² [J]: Σ over the
    /// nodes of ½wρI_p(|v|² − |ṙ_y|²) ([`Ancf3Props::director_inertia`]); 0 without
    /// torsion.
    pub fn director_kinetic(&self, tab: &Tables3, e: &[f64], ed: &[f64]) -> f64 {
        if !self.director {
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

    /// Local forces on (r_x, r_xx, r_y) of a bending point (weight `w` [m], (E·I_y, E·I_z) `ei`
    /// [N m²] there).
    #[inline(always)]
    pub(super) fn bend_point<T: Real>(
        &self,
        w: f64,
        q: usize,
        ei: [f64; 2],
        u: &[V<T>; 3],
        ud: Option<&[V<T>; 3]>,
    ) -> [V<T>; 3] {
        let [a, b, c] = u;
        let (m, g) = bend(a, b, c);
        let stiff = ei;
        let mut s = m;
        if let Some(r) = &self.reference {
            // curvatures from the reference's (κ2₀, κ3₀) at bending point q
            s = [0, 1].map(|i| s[i] - r.bending[q][i]);
        }
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
    pub(super) fn twist_element<T: Real>(
        &self,
        u: &[V<T>; 5],
        ud: Option<&[V<T>; 5]>,
    ) -> [V<T>; 5] {
        let (phi, g) = twist_gradient(u);
        let mut s = phi;
        if let Some(r) = &self.reference {
            s -= r.twist;
        }
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

    /// Twist rate of the element τ_e = (φ − φ₀)/l [rad/m] at `e` (18 entries): [`twist_angle`]
    /// of the nodal frames (and the midpoint tangent) over the element length, constant over
    /// the element, from the reference's φ₀ (0 when straight).
    pub fn twist_rate(&self, e: &[f64]) -> f64 {
        let [a, b, c, d] = TWIST_SLOTS.map(|s| [e[s], e[s + 1], e[s + 2]]);
        let (rs, _) = self.slots();
        let mid = combine(&hermite(0.5, self.length).1, &rs, e);
        let phi = twist_angle(&[a, b, c, d, mid]);
        match &self.reference {
            None => phi / self.length,
            Some(r) => (phi - r.twist) / self.length,
        }
    }

    /// Local forces on (r_x, r_y) of a node's penalty ½(l/2)k[(½(|y|² − 1))² + γ²], γ = t·y.
    #[inline(always)]
    pub(super) fn penalty_node<T: Real>(&self, u: &[V<T>; 2]) -> [V<T>; 2] {
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

    /// Section-director measures of the director element at `e` (18 entries): the twist
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

    /// Strain measures (ε, κ2, κ3, τ_e) at ξ ∈ [0, 1] of the director element (τ_e the
    /// element's twist rate, [`Ancf3Props::twist_rate`]).
    pub fn strains_at(&self, e: &[f64; DIRECTOR_DOFS], xi: f64) -> [f64; 4] {
        let l = self.length;
        let (_, ds, dds) = hermite(xi, l);
        let (rs, ys) = self.slots();
        let a = comb(&ds, &rs, e);
        let b = comb(&dds, &rs, e);
        let c = comb(&[1.0 - xi, xi], &ys, e);
        let [mut eps, mut k2, mut k3] = strains(a, b, c);
        if let Some(r) = &self.reference {
            let e0 = arc_element(l, r.curvature);
            let (a0, b0) = (comb(&ds, &rs, &e0), comb(&dds, &rs, &e0));
            let [eps0, k20, k30] = strains(a0, b0, comb(&[1.0 - xi, xi], &ys, &e0));
            (eps, k2, k3) = (eps - eps0, k2 - k20, k3 - k30);
        }
        [eps, k2, k3, self.twist_rate(e)]
    }
}
