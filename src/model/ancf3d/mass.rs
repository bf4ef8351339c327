//! The element's constant mass matrix as scalar patterns, and a straight element's coordinates.

/// The scalar patterns of the mass matrix (M = hermite ⊗ I₃ on the r-blocks + twist ⊗ I₃ on
/// the r_y blocks), for `M ë` without the dense matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassPatterns {
    /// ρA ∫S_jS_k dx [kg, kg m, kg m²].
    pub hermite: [[f64; 4]; 4],
    /// ρI_p ∫N_jN_k dx [kg m²].
    pub twist: [[f64; 2]; 2],
    /// Starts of the r-blocks of S1..S4 (r0, r0_x, r1, r1_x).
    pub r_slots: [usize; 4],
    /// Starts of the r_y blocks (r0_y, r1_y).
    pub y_slots: [usize; 2],
    /// Whether the r_y blocks exist (the director element).
    pub director: bool,
}

impl MassPatterns {
    /// `res += M a`.
    #[inline]
    pub fn add_product<const D: usize>(&self, a: &[f64; D], res: &mut [f64; D]) {
        // the slots of D coordinates, constants (the fields hold the same)
        let (rs, ys) = super::slots_of(D);
        debug_assert_eq!((rs, ys), (self.r_slots, self.y_slots));
        for j in 0..4 {
            for k in 0..4 {
                let m = self.hermite[j][k];
                for c in 0..3 {
                    res[rs[j] + c] += m * a[rs[k] + c];
                }
            }
        }
        if self.director {
            for j in 0..2 {
                for k in 0..2 {
                    let m = self.twist[j][k];
                    for c in 0..3 {
                        res[ys[j] + c] += m * a[ys[k] + c];
                    }
                }
            }
        }
    }
}

/// Coordinates of a straight, unstretched element from `p0` with section frame `frame`
/// (columns: axis x̄, section ȳ, z̄ in global axes), d entries (d = 18 for the director
/// element, 12 for the 3D cable).
pub fn straight(p0: [f64; 3], frame: [[f64; 3]; 3], l: f64, director: bool) -> Vec<f64> {
    let [x, y, _] = frame;
    let mut e = Vec::with_capacity(18);
    for s in [0.0, l] {
        e.extend((0..3).map(|c| p0[c] + s * x[c]));
        e.extend(x);
        if director {
            e.extend(y);
        }
    }
    e
}
