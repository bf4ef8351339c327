//! Cross-sections: the shapes a segment may have and their properties (area, second moments,
//! torsion constant, polar moment), from the scene's dimensions.

use super::Segment;
use crate::math;
use serde::{Deserialize, Serialize};

/// Cross-section shape. Section axes: y (the bending plane of a planar scene) and z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Section {
    /// Solid round rod of `diameter`.
    #[default]
    Round,
    /// Solid rectangle `width` (along z, out of the planar bending plane) × `height` (along y).
    Rectangle,
    /// Round tube of outer `diameter` and `inner_diameter`.
    Tube,
}

/// Properties of a cross-section (valid after [`Scene::validate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionProps {
    /// Area A [m²].
    pub area: f64,
    /// Second moment about the section's y axis [m⁴] (bending in the x–z plane).
    pub i_y: f64,
    /// Second moment about the section's z axis [m⁴] (bending in the x–y plane: the planar I).
    pub i_z: f64,
    /// Torsion constant J [m⁴] (GJ is the torsional stiffness): I_p for round sections and
    /// tubes, Saint-Venant's series for a rectangle.
    pub torsion: f64,
    /// Polar moment I_p = I_y + I_z [m⁴] (torsional rotary inertia ρI_p per length).
    pub polar: f64,
}

impl Segment {
    /// Area A [m²] and second moment I [m⁴] of the cross-section in the planar bending plane
    /// (about z; valid after `validate`).
    pub fn area_inertia(&self) -> (f64, f64) {
        let p = self.section_props();
        (p.area, p.i_z)
    }

    /// Shear modulus G = E/(2(1 + ν)) [Pa].
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Properties of the cross-section (valid after `validate`).
    pub fn section_props(&self) -> SectionProps {
        use std::f64::consts::PI;
        let round = |d: f64| {
            let a = PI * d * d / 4.0;
            (a, a * d * d / 16.0)
        };
        match self.section {
            Section::Round | Section::Tube => {
                let (ao, io) = round(self.diameter.unwrap_or(0.0));
                let (ai, ii) = match self.section {
                    Section::Tube => round(self.inner_diameter.unwrap_or(0.0)),
                    _ => (0.0, 0.0),
                };
                let i = io - ii;
                SectionProps {
                    area: ao - ai,
                    i_y: i,
                    i_z: i,
                    torsion: 2.0 * i,
                    polar: 2.0 * i,
                }
            }
            Section::Rectangle => {
                let (b, h) = (self.width.unwrap_or(0.0), self.height.unwrap_or(0.0));
                let (i_y, i_z) = (h * b * b * b / 12.0, b * h * h * h / 12.0);
                SectionProps {
                    area: b * h,
                    i_y,
                    i_z,
                    torsion: rectangle_torsion_constant(b, h),
                    polar: i_y + i_z,
                }
            }
        }
    }
}

/// Saint-Venant torsion constant of a solid `b` × `h` rectangle [m⁴]:
/// J = a b³ [1/3 − (64/π⁵)(b/a) Σ_{n odd} tanh(nπa/(2b))/n⁵], a ≥ b (Timoshenko & Goodier §109);
/// the series is summed to n = 99 (relative remainder below 1e-10).
pub fn rectangle_torsion_constant(b: f64, h: f64) -> f64 {
    use std::f64::consts::PI;
    let (a, b) = if h >= b { (h, b) } else { (b, h) };
    let sum: f64 = (0..50)
        .map(|k| {
            let n = (2 * k + 1) as f64;
            math::tanh(n * PI * a / (2.0 * b)) / n.powi(5)
        })
        .sum();
    a * b * b * b * (1.0 / 3.0 - 64.0 / PI.powi(5) * (b / a) * sum)
}
