//! The 3D cable (12 coordinates, nodes `[r, r_x]`, `torsion = false`): its bending, on the
//! [`Ancf3Props`] the director element shares (`super`'s module doc).
//!
//! Energy ½∫[EA ε² + EI |r_x × r_xx|²/|r_x|⁴] dx (round or equal-I sections: one bending
//! stiffness, [`Ancf3Props::check`]). The director element's undamped round sections take the
//! same bending measure ([`Ancf3Props::cable_bending`]). The cable has no material
//! frame, so the rate of its curvature vector κ = r_x × r_xx/|r_x|² is taken relative to the
//! rotation of the tangent, κ̇ − w × κ with w = t × ṫ (dissipation ½EIτ_d|κ̇ − w × κ|²): exact
//! for rigid rotations about axes ⟂ t, but a rigid spin Ω about an axis with Ω·t ≠ 0 of a
//! *curved* cable is damped by a moment ~EIτ_d(Ω·t)|κ| (no frame can tell it from bending).
//! No rotary inertia.

use super::*;
use crate::model::lanes::lane_comb;
pub use crate::model::lanes::Lanes;

impl Ancf3Props {
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
        !self.director || (round && self.damping_time == 0.0 && self.reference.is_none())
    }

    /// Local forces on (r_x, r_xx) of a cable bending point (weight `w` [m], (E·I_y, E·I_z)
    /// `ei` [N m²] there; the cable's stiffness is their mean as in [`Ancf3Props::cable_ei`]).
    #[inline(always)]
    pub(super) fn cable_point<T: Real>(
        &self,
        w: f64,
        ei: [f64; 2],
        u: &[V<T>; 2],
        ud: Option<&[V<T>; 2]>,
    ) -> [V<T>; 2] {
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
        let s = w * (0.5 * (ei[0] + ei[1]));
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
}

/// A 3-vector per quadrature point: component, then point (one lane per point, so that the
/// point-wise arithmetic runs on the points together).
type Lv<const N: usize> = [[f64; N]; 3];

/// The cubic cable's lanes ([`Tables3`]'s points).
pub(super) type Lanes3 = Lanes<4, 5, 3>;

impl Lanes3 {
    /// The lanes of the tables `t`.
    pub(super) fn of(t: &Tables3) -> Self {
        Self::new(
            t.axial.iter().map(|(w, ds)| (*w, &ds[..])),
            (t.bending.iter()).map(|p| (p.w * (0.5 * (p.ei[0] + p.ei[1])), &p.ds[..], &p.dds[..])),
        )
    }
}

/// a · b per lane ([`dot`]'s operations).
#[inline(always)]
fn lane_dot<const N: usize>(a: &Lv<N>, b: &Lv<N>) -> [f64; N] {
    let mut r = [0.0; N];
    for q in 0..N {
        r[q] = a[0][q] * b[0][q] + a[1][q] * b[1][q] + a[2][q] * b[2][q];
    }
    r
}

/// a × b per lane ([`cross`]'s operations).
#[inline(always)]
fn lane_cross<const N: usize>(a: &Lv<N>, b: &Lv<N>) -> Lv<N> {
    let mut r = [[0.0; N]; 3];
    for q in 0..N {
        r[0][q] = a[1][q] * b[2][q] - a[2][q] * b[1][q];
        r[1][q] = a[2][q] * b[0][q] - a[0][q] * b[2][q];
        r[2][q] = a[0][q] * b[1][q] - a[1][q] * b[0][q];
    }
    r
}

/// x_c s per lane.
#[inline(always)]
fn lane_scale<const N: usize>(x: &Lv<N>, s: &[f64; N]) -> Lv<N> {
    let mut r = *x;
    for rc in &mut r {
        for q in 0..N {
            rc[q] *= s[q];
        }
    }
    r
}

impl Ancf3Props {
    /// [`Ancf3Props::internal_force`] of the 3D cable (f64): [`Lanes::force`] on its tables'
    /// lanes, the generic path's operations and bits without its runtime slots and bounds
    /// checks.
    pub(super) fn cable_force(
        &self,
        tab: &Tables3,
        e: &[f64; CABLE_DOFS],
        ed: &[f64; CABLE_DOFS],
    ) -> [f64; CABLE_DOFS] {
        let e0 = self.reference.as_ref().map(|r| &r.axial);
        tab.lanes
            .force::<4, 5, 3, CABLE_DOFS>(self.damping_time, e0, e, ed)
    }
}

impl<const S: usize, const A: usize, const B: usize> Lanes<S, A, B> {
    /// A cable's internal force at (e, ė) on its first M shapes, QA axial and QB bending
    /// points ([`Ancf3Props::axial_point`] with the axial reference strains `e0`, and
    /// [`Ancf3Props::cable_point`], with retardation time `tau`): the point functions on all
    /// points at once (lanes) and the sums into each coordinate in the per-point path's order
    /// (the axial points, then each bending point's r_x and r_xx parts), so the same
    /// operations and bits.
    #[inline(always)]
    pub(super) fn force<const M: usize, const QA: usize, const QB: usize, const D: usize>(
        &self,
        tau: f64,
        e0: Option<&[f64; A]>,
        e: &[f64; D],
        ed: &[f64; D],
    ) -> [f64; D] {
        const { assert!(M <= S && QA <= A && QB <= B && 3 * M <= D) };
        let t = self;
        let damped = tau > 0.0;
        // axial points: g s on r_x, g = r_x/|r_x|, s = w (ε − ε₀ + τ_d g·ṙ_x)
        let a = lane_comb::<3, M, QA, S, A, D>(&t.axial_ds, e);
        let n = lane_dot(&a, &a).map(f64::sqrt);
        let g = lane_scale(&a, &n.map(f64::recip));
        let mut s = [0.0; QA];
        for q in 0..QA {
            s[q] = n[q] - 1.0;
        }
        if let Some(e0) = e0 {
            for q in 0..QA {
                s[q] -= e0[q];
            }
        }
        if damped {
            let rate = lane_dot(&g, &lane_comb::<3, M, QA, S, A, D>(&t.axial_ds, ed));
            for q in 0..QA {
                s[q] += rate[q] * tau;
            }
        }
        for q in 0..QA {
            s[q] *= t.axial_w[q];
        }
        let fx = lane_scale(&g, &s);
        // bending points (`cable_point`): κ = a × b/|a|², μ = w EI (κ + rate terms)
        let comb = |w: &[[f64; B]; S], e: &[f64; D]| lane_comb::<3, M, QB, S, B, D>(w, e);
        let (a, b) = (comb(&t.ds, e), comb(&t.dds, e));
        let inv = lane_dot(&a, &a).map(f64::recip);
        let kap = lane_scale(&lane_cross(&a, &b), &inv);
        let mut mv = kap;
        if damped {
            let (ad, bd) = (comb(&t.ds, ed), comb(&t.dds, ed));
            let r1 = lane_cross(&ad, &b);
            let r2 = lane_cross(&a, &bd);
            let r3 = lane_cross(&lane_cross(&a, &ad), &kap);
            let ada = lane_dot(&a, &ad);
            for c in 0..3 {
                for q in 0..QB {
                    mv[c][q] += (r1[c][q] + r2[c][q] - r3[c][q] - kap[c][q] * (ada[q] * 2.0))
                        * (inv[q] * tau);
                }
            }
        }
        let mut w = [0.0; QB];
        w.copy_from_slice(&t.bend_w[..QB]);
        let mv = lane_scale(&mv, &w);
        let bm = lane_cross(&b, &mv);
        let fb = lane_scale(&lane_cross(&mv, &a), &inv);
        let km = lane_dot(&kap, &mv);
        let am = lane_dot(&a, &mv);
        let mut fa = bm;
        for c in 0..3 {
            for q in 0..QB {
                fa[c][q] = inv[q] * bm[c][q]
                    + km[q] * (-2.0) * inv[q] * a[c][q]
                    + am[q] * inv[q] * kap[c][q];
            }
        }
        // f_{3j+c}: the axial points, then each bending point's r_x and r_xx parts (the
        // coordinates of a component as lanes)
        let mut fc = [[0.0; S]; 3];
        for (c, fc) in fc.iter_mut().enumerate() {
            for q in 0..QA {
                let x = fx[c][q];
                for j in 0..M {
                    fc[j] += x * t.axial_t[q][j];
                }
            }
            for q in 0..QB {
                let (xa, xb) = (fa[c][q], fb[c][q]);
                for j in 0..M {
                    fc[j] += xa * t.ds_t[q][j];
                    fc[j] += xb * t.dds_t[q][j];
                }
            }
        }
        let mut f = [0.0; D];
        for j in 0..M {
            for c in 0..3 {
                f[3 * j + c] = fc[c][j];
            }
        }
        f
    }
}
