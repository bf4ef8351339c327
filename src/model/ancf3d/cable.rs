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
