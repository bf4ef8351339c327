//! Cross-sections: the shapes a segment may have and their properties (area, second moments,
//! torsion constant, polar moment), from the scene's dimensions.

use super::Segment;
use crate::math;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One section dimension [m]: a number (uniform along the segment) or `[at_start, at_end]`, a
/// linear taper of the dimension along the segment's arc length (the section properties then
/// follow from the dimensions at each point: A ∝ d², I ∝ d⁴, not an interpolation of the
/// properties). A number serializes as a number, a taper as a list.
#[derive(Debug, Clone, PartialEq)]
pub enum Dim {
    /// The same value along the segment [m].
    Uniform(f64),
    /// `[at_start, at_end]` [m], linear in the arc length (valid after `validate`: two entries).
    Taper(Vec<f64>),
}

impl Dim {
    /// The dimension at the fraction `t` ∈ [0, 1] of the segment's length from its start [m]
    /// (a uniform dimension: its value, for every `t`).
    pub fn at(&self, t: f64) -> f64 {
        match self {
            Dim::Uniform(v) => *v,
            Dim::Taper(v) => {
                let a = v.first().copied().unwrap_or(0.0);
                let b = v.get(1).copied().unwrap_or(a);
                a + t * (b - a)
            }
        }
    }

    /// The value at the segment's start [m].
    pub fn start(&self) -> f64 {
        self.at(0.0)
    }

    /// Whether the dimension varies along the segment (a list, even with equal ends).
    pub fn is_taper(&self) -> bool {
        matches!(self, Dim::Taper(_))
    }

    /// Sets the start value to `x` [m]: a uniform dimension becomes `x`, a taper is scaled by
    /// x / start at both ends (its shape kept; the FMU parameters `<segment>.diameter` etc.).
    pub fn set_start(&mut self, x: f64) {
        match self {
            Dim::Uniform(v) => *v = x,
            Dim::Taper(v) => {
                let s = v.first().copied().unwrap_or(0.0);
                if s != 0.0 && s.is_finite() {
                    let f = x / s;
                    for c in v.iter_mut() {
                        *c *= f;
                    }
                } else {
                    v.iter_mut().for_each(|c| *c = x);
                }
            }
        }
    }
}

impl From<f64> for Dim {
    fn from(v: f64) -> Self {
        Dim::Uniform(v)
    }
}

impl Serialize for Dim {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Dim::Uniform(v) => s.serialize_f64(*v),
            Dim::Taper(v) => v.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Dim {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = Dim;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number of metres or a taper [at_start, at_end] in metres")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Dim, E> {
                Ok(Dim::Uniform(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Dim, E> {
                Ok(Dim::Uniform(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Dim, E> {
                Ok(Dim::Uniform(v as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut a: A) -> Result<Dim, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = a.next_element::<f64>()? {
                    v.push(x);
                }
                Ok(Dim::Taper(v))
            }
        }
        d.deserialize_any(V)
    }
}

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

    /// Whether any section dimension is a taper `[at_start, at_end]` ([`Dim`]).
    pub fn is_tapered(&self) -> bool {
        [
            &self.diameter,
            &self.inner_diameter,
            &self.width,
            &self.height,
        ]
        .iter()
        .any(|d| d.as_ref().is_some_and(Dim::is_taper))
    }

    /// Properties of the cross-section (valid after `validate`) at the segment's start (of the
    /// whole segment unless [`Segment::is_tapered`]; then [`Segment::section_props_at`]).
    pub fn section_props(&self) -> SectionProps {
        self.section_props_at(0.0)
    }

    /// Properties of the cross-section at arc length x = `t`·L from the segment's start
    /// (`t` ∈ [0, 1]), from the dimensions there (valid after `validate`).
    pub fn section_props_at(&self, t: f64) -> SectionProps {
        use std::f64::consts::PI;
        let dim = |d: &Option<Dim>| d.as_ref().map_or(0.0, |d| d.at(t));
        let round = |d: f64| {
            let a = PI * d * d / 4.0;
            (a, a * d * d / 16.0)
        };
        match self.section {
            Section::Round | Section::Tube => {
                let (ao, io) = round(dim(&self.diameter));
                let (ai, ii) = match self.section {
                    Section::Tube => round(dim(&self.inner_diameter)),
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
                let (b, h) = (dim(&self.width), dim(&self.height));
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
