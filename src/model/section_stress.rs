//! The stress in a cross-section from its loads: the largest von Mises stress over the
//! boundary of a round, tube or rectangular section (`docs/stations.md`).

use crate::scene::{Section, Segment};

/// A cross-section's shape and properties for the stress at a station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SectionShape {
    /// Solid round, radius [m].
    Round(f64),
    /// Round tube, outer and inner radius [m].
    Tube(f64, f64),
    /// Rectangle: width b along the section z axis, height h along y [m].
    Rectangle(f64, f64),
}

/// A station's section: its shape and the properties (A, I_y, I_z, J) of the segment at the cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressSection {
    /// The shape.
    pub shape: SectionShape,
    /// Area [m²].
    pub area: f64,
    /// Second moments about the section's y and z axes [m⁴].
    pub i_y: f64,
    /// Second moment about z [m⁴].
    pub i_z: f64,
}

impl StressSection {
    /// The section of `seg` at the fraction `t` of its length from its start.
    pub fn of(seg: &Segment, t: f64) -> Self {
        let d = |x: &Option<crate::scene::Dim>| x.as_ref().map_or(0.0, |d| d.at(t));
        let shape = match seg.section {
            Section::Round => SectionShape::Round(0.5 * d(&seg.diameter)),
            Section::Tube => {
                SectionShape::Tube(0.5 * d(&seg.diameter), 0.5 * d(&seg.inner_diameter))
            }
            Section::Rectangle => SectionShape::Rectangle(d(&seg.width), d(&seg.height)),
        };
        let p = seg.section_props_at(t);
        Self {
            shape,
            area: p.area,
            i_y: p.i_y,
            i_z: p.i_z,
        }
    }

    /// The largest von Mises stress σ_v = √(σ² + 3τ²) [Pa] over the boundary points of the
    /// section under the loads `force` (N, V_y, V_z) [N] and `moment` (T, M_y, M_z) [N m],
    /// section frame. At a boundary point (y, z): σ = N/A + M_y z/I_y − M_z y/I_z (beam
    /// theory); τ = |τ_T| + |τ_V| (the two added as magnitudes: exact where they are parallel,
    /// on the safe side elsewhere) with, for a solid round section of radius r, τ_T = T r/J
    /// (J = πr⁴/2) and τ_V = (4V/3A)(1 − η²/r²), η the point's coordinate along the shear
    /// force V (Jourawski on the chord); for a tube (r_o, r_i), τ_T = T r_o/J
    /// (J = π(r_o⁴ − r_i⁴)/2) and τ_V = (2V/A)|sin β|, β the angle of the point from V's
    /// direction (thin-walled shear flow); for a rectangle (long side a, short side b),
    /// τ_T = T/(k₂ a b²) at the middle of the long sides and k₃ times that at the middle of the
    /// short sides, zero at the corners, parabolic along each side (Saint-Venant; k₂, k₃ by
    /// Roark's fits, docs/stations.md), and τ_V = 1.5 (V_s/A)(1 − (2η/d)²) for the shear V_s
    /// parallel to a side of depth d (η from the side's middle). 72 points around a circle,
    /// 4 × 17 along a rectangle's sides.
    pub fn stress(&self, force: [f64; 3], moment: [f64; 3]) -> f64 {
        let [n, vy, vz] = force;
        let [t, my, mz] = moment;
        let sigma = |y: f64, z: f64| {
            n / self.area
                + if self.i_y > 0.0 {
                    my * z / self.i_y
                } else {
                    0.0
                }
                - if self.i_z > 0.0 {
                    mz * y / self.i_z
                } else {
                    0.0
                }
        };
        let vm = |s: f64, tau: f64| (s * s + 3.0 * tau * tau).sqrt();
        let v = (vy * vy + vz * vz).sqrt();
        let mut worst: f64 = 0.0;
        match self.shape {
            SectionShape::Round(r) | SectionShape::Tube(r, _) => {
                let ri = match self.shape {
                    SectionShape::Tube(_, ri) => ri,
                    _ => 0.0,
                };
                let j = 0.5 * std::f64::consts::PI * (r.powi(4) - ri.powi(4));
                let tau_t = if j > 0.0 { (t * r / j).abs() } else { 0.0 };
                if v == 0.0 && self.i_y == self.i_z {
                    // no shear force: τ is the same all round and σ = N/A + (r/I)|M| cos(φ − φ₀)
                    // is largest in magnitude at |N/A| + |M| r/I
                    let i = self.i_z;
                    let bend = if i > 0.0 {
                        (my * my + mz * mz).sqrt() * r / i
                    } else {
                        0.0
                    };
                    return vm((n / self.area).abs() + bend, tau_t);
                }
                // the 72 points 5° apart by rotating (cos, sin) (no trigonometry per point)
                const COS_5: f64 = 0.996_194_698_091_745_5;
                const SIN_5: f64 = 0.087_155_742_747_658_17;
                let (mut c, mut sn) = (1.0f64, 0.0f64);
                for _ in 0..72 {
                    let (y, z) = (r * c, r * sn);
                    (c, sn) = (c * COS_5 - sn * SIN_5, sn * COS_5 + c * SIN_5);
                    // the point's coordinate along V and the angle from it
                    let eta = if v > 0.0 { (y * vy + z * vz) / v } else { 0.0 };
                    let tau_v = if v == 0.0 {
                        0.0
                    } else if ri > 0.0 {
                        2.0 * v / self.area * (1.0 - (eta / r).powi(2)).max(0.0).sqrt()
                    } else {
                        4.0 * v / (3.0 * self.area) * (1.0 - (eta / r).powi(2)).max(0.0)
                    };
                    worst = worst.max(vm(sigma(y, z), tau_t + tau_v));
                }
            }
            SectionShape::Rectangle(b, h) => {
                let (long, short) = (h.max(b), h.min(b));
                let beta = short / long;
                // Roark (Table 10.7 case 4): τ_max = 3T/(8 a b²)[1 + 0.6095β + 0.8865β² −
                // 1.8023β³ + 0.9100β⁴] with half sides a ≥ b; mid short side ≈ τ_max (0.7425
                // for a square's equal sides is 1, β → 0: 0.742)
                let (a2, b2) = (0.5 * long, 0.5 * short);
                let tau_max = 3.0 * t.abs() / (8.0 * a2 * b2 * b2)
                    * (1.0 + 0.6095 * beta + 0.8865 * beta * beta - 1.8023 * beta.powi(3)
                        + 0.9100 * beta.powi(4));
                let short_factor = 1.0 - 0.258 * (1.0 - beta);
                // sides: (fixed coordinate on y or z, half length, τ_T at the middle)
                for side in 0..4 {
                    let along_z = side < 2; // the sides y = ±h/2 run along z (length b)
                    let half = if along_z { 0.5 * b } else { 0.5 * h };
                    let is_long = (along_z && b >= h) || (!along_z && h > b);
                    let tau_mid = if is_long {
                        tau_max
                    } else {
                        tau_max * short_factor
                    };
                    for k in 0..=16 {
                        let u = -1.0 + 2.0 * k as f64 / 16.0; // −1 … 1 along the side
                        let (y, z) = if along_z {
                            (if side == 0 { 0.5 * h } else { -0.5 * h }, u * half)
                        } else {
                            (u * half, if side == 2 { 0.5 * b } else { -0.5 * b })
                        };
                        let tau_t = tau_mid * (1.0 - u * u);
                        // V_y along h (depth h, η = y), V_z along b (depth b, η = z)
                        let tau_v = 1.5 * vy.abs() / self.area
                            * (1.0 - (2.0 * y / h).powi(2)).max(0.0)
                            + 1.5 * vz.abs() / self.area * (1.0 - (2.0 * z / b).powi(2)).max(0.0);
                        worst = worst.max(vm(sigma(y, z), tau_t + tau_v));
                    }
                }
            }
        }
        worst
    }
}
