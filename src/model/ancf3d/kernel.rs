//! The element's generic per-point code: Hermite shape values, gathers and scatters of the
//! 3-vector slots, the bending measures with their gradients, the element twist from the nodal
//! frames. Generic over the scalar ([`Real`]), so the residual (f64) and the exact tangent (dual
//! numbers) share it.

use super::*;
use crate::model::vector::scale;
#[cfg(test)]
use num_dual::DualSVec;

/// Hermite shape functions and their derivatives at ξ, as the planar element.
pub(super) fn hermite(xi: f64, l: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let s = crate::model::ancf::Shape::at(xi, l);
    (s.s, s.ds, s.dds)
}

pub(super) type V<T> = [T; 3];

/// α a + β b.
#[inline(always)]
pub(super) fn lin2<T: Real>(al: T, a: &V<T>, be: T, b: &V<T>) -> V<T> {
    [
        al * a[0] + be * b[0],
        al * a[1] + be * b[1],
        al * a[2] + be * b[2],
    ]
}

/// α a + β b + γ c.
#[inline(always)]
pub(super) fn lin3<T: Real>(al: T, a: &V<T>, be: T, b: &V<T>, ga: T, c: &V<T>) -> V<T> {
    [
        al * a[0] + be * b[0] + ga * c[0],
        al * a[1] + be * b[1] + ga * c[1],
        al * a[2] + be * b[2] + ga * c[2],
    ]
}

/// Σ_j w_j e[slot_j..slot_j + 3].
#[inline(always)]
pub(super) fn comb<T: Real, const N: usize, const D: usize>(
    w: &[f64; N],
    slots: &[usize; N],
    e: &[T; D],
) -> V<T> {
    let mut r = [T::from(0.0); 3];
    for j in 0..N {
        let s = slots[j];
        for c in 0..3 {
            r[c] += e[s + c] * w[j];
        }
    }
    r
}

/// [`comb`] on slices: Σ_j w_j x[slot_j..slot_j + 3] (samples and energies, f64).
pub(super) fn combine(w: &[f64], slots: &[usize], x: &[f64]) -> V<f64> {
    let mut r = [0.0; 3];
    for (wj, s) in w.iter().zip(slots) {
        for c in 0..3 {
            r[c] += wj * x[s + c];
        }
    }
    r
}

/// `f[slot_j + c] += w_j v_c`.
#[inline(always)]
pub(super) fn scatter<T: Real, const N: usize, const D: usize>(
    f: &mut [T; D],
    w: &[f64; N],
    slots: &[usize; N],
    v: &V<T>,
) {
    for j in 0..N {
        let s = slots[j];
        for c in 0..3 {
            f[s + c] += v[c] * w[j];
        }
    }
}

/// How a local vector of a quadrature point is made of element coordinates: Σ_j w_j
/// e[slot_j..slot_j + 3].
#[derive(Debug, Clone, Copy)]
pub(super) struct Map<'a> {
    pub(super) w: &'a [f64],
    pub(super) slots: &'a [usize],
}

impl<'a> Map<'a> {
    #[inline(always)]
    pub(super) fn new(w: &'a [f64], slots: &'a [usize]) -> Self {
        Self { w, slots }
    }
}

/// The local vectors of a point.
#[inline(always)]
pub(super) fn gather<T: Real, const K: usize, const D: usize>(
    maps: &[Map<'_>; K],
    e: &[T; D],
) -> [V<T>; K] {
    maps.map(|m| {
        let mut r = [T::from(0.0); 3];
        for (w, s) in m.w.iter().zip(m.slots) {
            for c in 0..3 {
                r[c] += e[s + c] * *w;
            }
        }
        r
    })
}

/// Adds the Jacobians of one point's local forces `g(u, u̇)` (K local vectors) to the element
/// stiffness `k` and, with `c`, damping matrix: AD with N = 3K (positions) or 6K (positions
/// and rates) seeds, then `mapsᵀ J maps`.
pub(super) fn point_tangent<const K: usize, const N: usize, const D: usize>(
    maps: &[Map<'_>; K],
    e: &[f64; D],
    ed: &[f64; D],
    k: &mut [[f64; D]; D],
    c: Option<&mut [[f64; D]; D]>,
    g: impl FnOnce(&[V<DualSVec64<N>>; K], &[V<DualSVec64<N>>; K]) -> [V<DualSVec64<N>>; K],
) {
    debug_assert!(N == 3 * K || (N == 6 * K && c.is_some()));
    let rates = N == 6 * K;
    let out = g(
        &seed(&gather(maps, e), Some(0)),
        &seed(&gather(maps, ed), rates.then_some(3 * K)),
    );
    add_jacobian(maps, &out, 0, k);
    if let (Some(c), true) = (c, rates) {
        add_jacobian(maps, &out, 3 * K, c);
    }
}

/// DIM × DIM blocks [a][b] of a point's local Jacobian ∂g_a/∂u_b (3-vectors).
pub(super) type Blocks<const K: usize> = [[[[f64; 3]; 3]; K]; K];

/// The Jacobians of one point's local forces `g(u, u̇)` (K local vectors `u`, rates `ud`):
/// ∂g/∂u and, with N = 6K seeds, ∂g/∂u̇ (N = 3K: `None`), as 3 × 3 blocks, by forward-mode AD
/// (the element of degree p maps them onto its coordinates, [`crate::model::hierarchic`]).
pub(super) fn local_jacobian<const K: usize, const N: usize>(
    u: &[V<f64>; K],
    ud: &[V<f64>; K],
    g: impl FnOnce(&[V<DualSVec64<N>>; K], &[V<DualSVec64<N>>; K]) -> [V<DualSVec64<N>>; K],
) -> (Blocks<K>, Option<Blocks<K>>) {
    debug_assert!(N == 3 * K || N == 6 * K);
    let rates = N == 6 * K;
    let out = g(&seed(u, Some(0)), &seed(ud, rates.then_some(3 * K)));
    let blocks = |off: usize| {
        let mut b = [[[[0.0; 3]; 3]; K]; K];
        for (al, ga) in out.iter().enumerate() {
            for ci in 0..3 {
                let Some(eps) = &ga[ci].eps.0 else { continue };
                for (be, blk) in b[al].iter_mut().enumerate() {
                    for cj in 0..3 {
                        blk[ci][cj] = eps[off + 3 * be + cj];
                    }
                }
            }
        }
        b
    };
    (blocks(0), rates.then(|| blocks(3 * K)))
}

/// Local vectors as dual numbers, derivative `off + 3α + i` seeded on component i of vector α
/// (`None`: constants).
fn seed<const K: usize, const N: usize>(
    x: &[V<f64>; K],
    off: Option<usize>,
) -> [V<DualSVec64<N>>; K] {
    let mut out = [[DualSVec64::<N>::from_re(0.0); 3]; K];
    for al in 0..K {
        for ci in 0..3 {
            let v = DualSVec64::<N>::from_re(x[al][ci]);
            out[al][ci] = match off {
                Some(off) => v.derivative(off + 3 * al + ci),
                None => v,
            };
        }
    }
    out
}

/// Adds `mapsᵀ J maps` to `mat`, J the derivatives `off .. off + 3K` of the local forces `out`.
fn add_jacobian<const K: usize, const N: usize, const D: usize>(
    maps: &[Map<'_>; K],
    out: &[V<DualSVec64<N>>; K],
    off: usize,
    mat: &mut [[f64; D]; D],
) {
    for (ma, ga) in maps.iter().zip(out) {
        for ci in 0..3 {
            let Some(eps) = &ga[ci].eps.0 else { continue };
            for (mb, bet) in maps.iter().zip(0..K) {
                for cj in 0..3 {
                    let j = eps[off + 3 * bet + cj];
                    if j == 0.0 {
                        continue;
                    }
                    for (wa, sa) in ma.w.iter().zip(ma.slots) {
                        for (wb, sb) in mb.w.iter().zip(mb.slots) {
                            mat[sa + ci][sb + cj] += wa * wb * j;
                        }
                    }
                }
            }
        }
    }
}

/// Gradient of a scalar measure with respect to (r_x, r_xx, r_y) at a point.
#[derive(Debug, Clone, Copy)]
pub(super) struct Grad<T> {
    pub(super) a: V<T>,
    pub(super) b: V<T>,
    pub(super) c: V<T>,
}

/// (κ2, κ3) and their gradients with respect to a = r_x, b = r_xx, c = r_y.
///
/// With C = a × c (so d3 = C/|C|, d2 = ((a·a) c − (a·c) a)/(|C| |a|)), w = |C|, n = |a|:
/// κ2 = −(C·b)/(w n), κ3 = (C·(a × b))/(w n²). For equal weights κ2² + κ3² = |a × b|²/|a|⁴, the
/// cable's curvature, whatever c.
#[inline(always)]
pub(super) fn bend<T: Real>(a: &V<T>, b: &V<T>, c: &V<T>) -> ([T; 2], [Grad<T>; 2]) {
    let n2 = dot(a, a);
    let n = n2.sqrt();
    let inv_n = n.recip();
    let cc = dot(c, c);
    let g = dot(a, c);
    let ab = dot(a, b);
    let bc = dot(b, c);
    let cv = cross(a, c);
    let w2 = n2 * cc - g * g;
    let inv_w = w2.sqrt().recip();
    let p = dot(&cv, b);
    let q = n2 * bc - ab * g;
    let (inv_n2, inv_w2) = (inv_n * inv_n, inv_w * inv_w);
    // ½∂(w²)/w² and ½∂(n²)/n²
    let hw_a = lin2(cc * inv_w2, a, -g * inv_w2, c);
    let hw_c = lin2(n2 * inv_w2, c, -g * inv_w2, a);
    let hn_a = [a[0] * inv_n2, a[1] * inv_n2, a[2] * inv_n2];
    let cxb = cross(c, b);
    let bxa = cross(b, a);
    // κ2
    let h2 = inv_w * inv_n;
    let k2 = -p * h2;
    let g2 = Grad {
        a: lin3(-h2, &cxb, -k2, &hw_a, -k2, &hn_a),
        b: [-h2 * cv[0], -h2 * cv[1], -h2 * cv[2]],
        c: lin2(-h2, &bxa, -k2, &hw_c),
    };
    // κ3
    let h3 = inv_w * inv_n2;
    let k3 = q * h3;
    let dq_a = lin3(bc * 2.0, a, -g, b, -ab, c);
    let g3 = Grad {
        a: lin3(h3, &dq_a, -k3, &hw_a, k3 * (-2.0), &hn_a),
        b: lin2(h3 * n2, c, -h3 * g, a),
        c: lin3(h3 * n2, b, -h3 * ab, a, -k3, &hw_c),
    };
    ([k2, k3], [g2, g3])
}

/// Strain measures (ε, κ2, κ3) at a point from r_x, r_xx, r_y (see the module doc).
pub fn strains(rx: [f64; 3], rxx: [f64; 3], ry: [f64; 3]) -> [f64; 3] {
    let ([k2, k3], _) = bend(&rx, &rxx, &ry);
    [dot(&rx, &rx).sqrt() - 1.0, k2, k3]
}

/// The smallest rotation P taking the unit `t0` to the unit `t1`, by its unnormalized axis
/// k = t0 × t1 and c = t0·t1 (Rodrigues: P v = c v + k × v + (k·v) k/(1 + c)).
pub(super) struct Turn<T> {
    k: V<T>,
    c: T,
}

impl<T: Real> Turn<T> {
    #[inline(always)]
    pub(super) fn new(t0: &V<T>, t1: &V<T>) -> Self {
        Self {
            k: cross(t0, t1),
            c: dot(t0, t1),
        }
    }

    /// P v.
    #[inline(always)]
    pub(super) fn apply(&self, v: &V<T>) -> V<T> {
        let k = &self.k;
        let kv = cross(k, v);
        lin3(self.c, v, T::from(1.0), &kv, dot(k, v) / (self.c + 1.0), k)
    }

    /// k/(1 + c) = t0 × t1/(1 + t0·t1): half the curvature binormal of the turn.
    #[inline(always)]
    fn half_binormal(&self) -> V<T> {
        scale(&self.k, (self.c + 1.0).recip())
    }
}

/// The angle about the unit `t` from `u` to `w` (both ⟂ t, any lengths), in (−π, π].
#[inline(always)]
fn angle_about<T: Real>(t: &V<T>, u: &V<T>, w: &V<T>) -> T {
    math::atan2_dual(dot(&cross(u, w), t), dot(u, w))
}

/// The element's twist angle φ [rad] from its nodal frames: `u` = (r_x,0, r_y,0, r_x,1, r_y,1,
/// r_x at ξ = ½). The discrete twist of Bergou et al. 2008 ("Discrete elastic rods", ACM TOG
/// 27(3):63, the twist by parallel transport of the frame between consecutive tangents;
/// docs/references.md §7.1): with t_i = r_x,i/|r_x,i| and u_i = r_y,i − (t_i·r_y,i) t_i (d2_i
/// unnormalized: the angle does not see the lengths), φ₁ is the angle about t_1 from P u_0 to
/// u_1, P the smallest rotation taking t_0 to t_1 ([`Turn`]). φ₁ differs from the twist
/// relative to parallel transport along the curve by the holonomy of the tangent's path on the
/// sphere (the area between the path and its chord), O(l³) for a non-planar centreline; φ₂,
/// the same through the midpoint tangent t_m (t_0 → t_m → t_1), has a quarter of it, and
/// φ = (4φ₂ − φ₁)/3 removes the leading term (Richardson). For a planar centreline (any
/// plane) every transport is a rotation about the plane's normal, so φ₁ = φ₂ = φ: zero for a
/// twist-free rod bent in any plane, Δ for a straight element whose r_y turns by Δ ∈ (−π, π).
/// The angles are atan2s ([`math::atan2_dual`]: exact derivatives of every order, no std
/// transcendental).
#[inline(always)]
pub fn twist_angle<T: Real>(u: &[V<T>; 5]) -> T {
    let [a0, c0, a1, c1, am] = u;
    let unit = |a: &V<T>| scale(a, dot(a, a).sqrt().recip());
    let (t0, t1, tm) = (unit(a0), unit(a1), unit(am));
    let u0 = lin2(T::from(1.0), c0, -dot(&t0, c0), &t0);
    let u1 = lin2(T::from(1.0), c1, -dot(&t1, c1), &t1);
    let phi1 = angle_about(&t1, &Turn::new(&t0, &t1).apply(&u0), &u1);
    let via = Turn::new(&tm, &t1).apply(&Turn::new(&t0, &tm).apply(&u0));
    let phi2 = angle_about(&t1, &via, &u1);
    (phi2 * 4.0 - phi1) * (1.0 / 3.0)
}

/// φ of [`twist_angle`] and its gradient with respect to its five vectors (r_x,0, r_y,0, r_x,1,
/// r_y,1, r_x(ξ = ½)), the gradient written out (checked against nested AD in the tests). A
/// variation turns each frame [t_i d2_i d3_i] by ω_i; its part about t_i, ω_i·t_i = e_i·δr_y,i −
/// (t_i·r_y,i) e_i·δt_i with e_i = d3_i/|u_i| = (t_i × u_i)/|u_i|², changes φ by ω_1·t_1 −
/// ω_0·t_0; moving the tangents changes each transport step a → b's twist by k_ab·(δt_a + δt_b),
/// k_ab = t_a × t_b/(1 + t_a·t_b) (half the curvature binormal: Bergou et al. 2008, the
/// gradient of the reference twist); δt_i = (I − t_i t_iᵀ) δr_x,i/|r_x,i|.
#[inline(always)]
pub(super) fn twist_gradient<T: Real>(u: &[V<T>; 5]) -> (T, [V<T>; 5]) {
    let [a0, c0, a1, c1, am] = u;
    let inv = |a: &V<T>| dot(a, a).sqrt().recip();
    let (i0, i1, im) = (inv(a0), inv(a1), inv(am));
    let (t0, t1, tm) = (scale(a0, i0), scale(a1, i1), scale(am, im));
    let (g0, g1) = (dot(&t0, c0), dot(&t1, c1));
    let one = T::from(1.0);
    let u0 = lin2(one, c0, -g0, &t0);
    let u1 = lin2(one, c1, -g1, &t1);
    // the three turns, shared by φ and its gradient
    let (p01, p0m, pm1) = (
        Turn::new(&t0, &t1),
        Turn::new(&t0, &tm),
        Turn::new(&tm, &t1),
    );
    let phi1 = angle_about(&t1, &p01.apply(&u0), &u1);
    let via = pm1.apply(&p0m.apply(&u0));
    let phi2 = angle_about(&t1, &via, &u1);
    let phi = (phi2 * 4.0 - phi1) * (1.0 / 3.0);
    let e0 = scale(cross(&t0, &u0), dot(&u0, &u0).recip());
    let e1 = scale(cross(&t1, &u1), dot(&u1, &u1).recip());
    let (k01, k0m, km1) = (
        p01.half_binormal(),
        p0m.half_binormal(),
        pm1.half_binormal(),
    );
    let (four, third) = (T::from(4.0 / 3.0), T::from(-1.0 / 3.0));
    // δφ = w_i·δt_i
    let w0 = lin3(g0, &e0, four, &k0m, third, &k01);
    let w1 = lin3(-g1, &e1, four, &km1, third, &k01);
    let wm = lin2(four, &k0m, four, &km1);
    let proj = |w: &V<T>, t: &V<T>, i: T| lin2(i, w, -dot(t, w) * i, t);
    let grad = [
        proj(&w0, &t0, i0),
        [-e0[0], -e0[1], -e0[2]],
        proj(&w1, &t1, i1),
        e1,
        proj(&wm, &tm, im),
    ];
    (phi, grad)
}

/// [`twist_gradient`] by forward-mode AD nested over the scalar (15 derivatives): the
/// reference the written-out gradient is checked against.
#[cfg(test)]
pub(super) fn twist_gradient_ad<T: Real>(u: &[V<T>; 5]) -> (T, [V<T>; 5]) {
    let x: [V<DualSVec<T, 15>>; 5] = std::array::from_fn(|al| {
        std::array::from_fn(|ci| DualSVec::<T, 15>::from_re(u[al][ci]).derivative(3 * al + ci))
    });
    let phi = twist_angle(&x);
    let zero = T::from(0.0);
    let grad = match &phi.eps.0 {
        Some(g) => std::array::from_fn(|al| std::array::from_fn(|ci| g[3 * al + ci])),
        None => [[zero; 3]; 5],
    };
    (phi.re, grad)
}

/// Adds the Jacobians of one point's local inertial forces `g(u, u̇, ü)` (K local vectors) to the
/// element stiffness `k`, damping `c` and mass `m` matrices: AD with N = 9K seeds (positions,
/// rates, accelerations), then `mapsᵀ J maps`; returns the forces `g` (f64). Only the matrices
/// flagged in `active` (k, c, m) are added to (the others' directions are not differentiated).
#[allow(clippy::type_complexity)]
pub(super) fn point_tangent_acc<const K: usize, const N: usize, const D: usize>(
    maps: &[Map<'_>; K],
    (e, ed, ea): (&[f64; D], &[f64; D], &[f64; D]),
    k: &mut [[f64; D]; D],
    c: &mut [[f64; D]; D],
    m: &mut [[f64; D]; D],
    active: [bool; 3],
    g: impl FnOnce(
        &[V<DualSVec64<N>>; K],
        &[V<DualSVec64<N>>; K],
        &[V<DualSVec64<N>>; K],
    ) -> [V<DualSVec64<N>>; K],
) -> [V<f64>; K] {
    debug_assert!(N == 9 * K);
    // only the active directions carry derivatives (what depends on the others alone is
    // differentiated for nothing): the same Jacobians where active, the same force
    let lanes = |on: bool, off: usize| on.then_some(off);
    let out = g(
        &seed(&gather(maps, e), lanes(active[0], 0)),
        &seed(&gather(maps, ed), lanes(active[1], 3 * K)),
        &seed(&gather(maps, ea), lanes(active[2], 6 * K)),
    );
    for ((mat, off), on) in [(k, 0), (c, 3 * K), (m, 6 * K)].into_iter().zip(active) {
        if on {
            add_jacobian(maps, &out, off, mat);
        }
    }
    out.map(|v| v.map(|x| x.re))
}

/// The director's velocity relative to the tangent's rotation, v = ċ − w × c with w = (a × ȧ)/|a|²
/// (a = r_x, c = r_y at a point): v = ċ + h, h = (a (c·ȧ) − ȧ (a·c))/|a|². For a rigid rotation Ω
/// of the section v = (Ω·t) t × c: the twist alone (bending turns t, and c with it).
#[inline(always)]
pub(super) fn director_rate<T: Real>(u: &[V<T>; 2], ud: &[V<T>; 2]) -> (V<T>, V<T>) {
    let [a, c] = u;
    let [ad, cd] = ud;
    let inv = dot(a, a).recip();
    let h = lin2(dot(c, ad) * inv, a, -dot(a, c) * inv, ad);
    let v = [cd[0] + h[0], cd[1] + h[1], cd[2] + h[2]];
    (v, h)
}

/// Local inertial forces on (a = r_x, c = r_y) of the director kinetic energy T = ½k|v|²
/// ([`director_rate`]; k = weight × ρI_p [kg m]) at a point, d/dt ∂T/∂(ȧ, ċ) − ∂T/∂(a, c),
/// less the constant part k c̈ (the mass pattern's) [N, N m].
#[inline(always)]
pub(super) fn director_point<T: Real>(
    k: f64,
    u: &[V<T>; 2],
    ud: &[V<T>; 2],
    ua: &[V<T>; 2],
) -> [V<T>; 2] {
    let [a, c] = u;
    let [ad, cd] = ud;
    let [aa, ca] = ua;
    let inv = dot(a, a).recip();
    let g = dot(a, c);
    let gd = dot(ad, c) + dot(a, cd);
    let cad = dot(c, ad);
    let aad = dot(a, ad) * 2.0 * inv;
    let (v, h) = director_rate(u, ud);
    // ḣ = [ȧ (c·ȧ) + a (ċ·ȧ + c·ä) − ä g − ȧ ġ]/|a|² − 2 (a·ȧ)/|a|² h
    let s1 = dot(cd, ad) + dot(c, aa);
    let hd: V<T> = std::array::from_fn(|i| {
        (ad[i] * cad + a[i] * s1 - aa[i] * g - ad[i] * gd) * inv - aad * h[i]
    });
    let vd: V<T> = std::array::from_fn(|i| ca[i] + hd[i]);
    let (av, adv, hv) = (dot(a, &v), dot(ad, &v), dot(&h, &v));
    // ∂T/∂ȧ = k p, p = (c (a·v) − g v)/|a|²; ṗ = (ċ m + c ṁ − ġ v − g v̇)/|a|² − 2 (a·ȧ)/|a|² p
    let md = adv + dot(a, &vd);
    let fa: V<T> = std::array::from_fn(|i| {
        let p = (c[i] * av - v[i] * g) * inv;
        let pd = (cd[i] * av + c[i] * md - v[i] * gd - vd[i] * g) * inv - aad * p;
        // ∂T/∂a = k [(v (c·ȧ) − c (ȧ·v))/|a|² − 2 a (h·v)/|a|²]
        let ta = (v[i] * cad - c[i] * adv - a[i] * hv * 2.0) * inv;
        (pd - ta) * k
    });
    // ∂T/∂c = k (ȧ (a·v) − a (ȧ·v))/|a|²
    let fc: V<T> = std::array::from_fn(|i| (hd[i] - (ad[i] * av - a[i] * adv) * inv) * k);
    [fa, fc]
}
