//! How the views dress a scene's sampled centreline: the tube's outer radius along each segment
//! (a taper's radius varies linearly between its ends) and the attached masses (`[[masses]]`),
//! drawn as spheres at their centres. Display only: a mass's centre is interpolated linearly
//! between the centreline samples that bracket its arc length (the samples are the elements'
//! own interpolation, 8 per element by default), its offset turned by the interpolated section
//! frame.

use hybeam::model::{strain_stress, Shape};
use hybeam::scene::{Dim, Scene, Section, Segment};

/// The density of the sphere a mass is drawn as [kg/m³]: an equipment box of mixed metal and
/// plastic (a 1 kg mass is a sphere of 4.9 cm radius).
pub const MASS_DENSITY: f64 = 2000.0;

/// An attached mass as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct MassLook {
    /// Its segment's index.
    pub segment: usize,
    /// Arc length from its segment's start [m].
    pub at: f64,
    /// Its centre from the centreline point, section axes (t, d2, d3) [m].
    pub offset: [f64; 3],
    /// The sphere's radius [m].
    pub radius: f64,
}

/// The look of a scene's beam: each segment's outer radius at its start and end [m], the
/// attached masses.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Look {
    /// Outer radius [m] at each segment's start and end (equal but on a taper): a tube of it
    /// shows the real section; a rectangle by half its larger side, any other shape by the
    /// equal-area circle.
    pub radii: Vec<[f64; 2]>,
    /// The attached masses.
    pub masses: Vec<MassLook>,
    /// The scene's segments, for the von Mises stress at each point (empty: a look read back
    /// from a series, which has no stress).
    pub segments: Vec<Segment>,
}

impl Look {
    /// The look of `scene` (valid after its validation).
    pub fn of(scene: &Scene) -> Self {
        let radius = |s: &hybeam::scene::Segment, t: f64| match s.section {
            Section::Round | Section::Tube => 0.5 * s.diameter.as_ref().map_or(0.0, |d| d.at(t)),
            Section::Rectangle => {
                let at = |d: &Option<Dim>| d.as_ref().map_or(0.0, |d| d.at(t));
                0.5 * at(&s.width).max(at(&s.height))
            }
        };
        let radii = scene
            .segments
            .iter()
            .map(|s| [radius(s, 0.0), radius(s, 1.0)])
            .collect();
        let masses = scene
            .masses
            .iter()
            .filter_map(|m| {
                let segment = scene.segments.iter().position(|s| s.name == m.segment)?;
                let o = m.offset.clone().unwrap_or_default();
                let offset = std::array::from_fn(|k| o.get(k).copied().unwrap_or(0.0));
                let radius = (3.0 * m.mass / (4.0 * std::f64::consts::PI * MASS_DENSITY)).cbrt();
                Some(MassLook {
                    segment,
                    at: m.at,
                    offset,
                    radius,
                })
            })
            .collect();
        Self {
            radii,
            masses,
            segments: scene.segments.clone(),
        }
    }

    /// A look of segments whose radii are `radii` at both ends, without masses.
    pub fn uniform(radii: &[f64]) -> Self {
        Self {
            radii: radii.iter().map(|r| [*r, *r]).collect(),
            masses: Vec::new(),
            segments: Vec::new(),
        }
    }

    /// The outer radius at each point of `shape` [m]: its segment's, linear in the arc length
    /// between the segment's first and last sample.
    pub fn point_radii(&self, shape: &Shape) -> Vec<f64> {
        along(shape, |si, t, _| {
            let [r0, r1] = self.radii.get(si).copied().unwrap_or_default();
            r0 + t * (r1 - r0)
        })
    }

    /// The largest von Mises stress over the section at each point of `shape` [Pa], from the
    /// point's strains ([`hybeam::model::strain_stress`]); `None` without the scene's segments.
    pub fn point_stresses(&self, shape: &Shape) -> Option<Vec<f64>> {
        if self.segments.is_empty() {
            return None;
        }
        Some(along(shape, |si, t, p| {
            self.segments
                .get(si)
                .map_or(0.0, |seg| strain_stress(seg, t, p))
        }))
    }

    /// The masses' centres [m], world axes, on `shape` (a mass whose segment has no samples at
    /// the origin).
    pub fn mass_centres(&self, shape: &Shape) -> Vec<[f64; 3]> {
        self.masses
            .iter()
            .map(|m| {
                let Some(range) = shape.segments.get(m.segment) else {
                    return [0.0; 3];
                };
                let pts = &shape.points[range.clone()];
                let Some(first) = pts.first() else {
                    return [0.0; 3];
                };
                let s = first.arc + m.at;
                // the last sample at or before s, and the next one
                let k = pts.iter().rposition(|p| p.arc <= s).unwrap_or(0);
                let (a, b) = (&pts[k], &pts[(k + 1).min(pts.len() - 1)]);
                let t = if b.arc > a.arc {
                    ((s - a.arc) / (b.arc - a.arc)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let lerp = |x: &[f64; 3], y: &[f64; 3]| -> [f64; 3] {
                    std::array::from_fn(|i| x[i] + t * (y[i] - x[i]))
                };
                let mut c = lerp(&a.position, &b.position);
                for (axis, o) in m.offset.iter().enumerate() {
                    if *o != 0.0 {
                        let d = lerp(&a.frame[axis], &b.frame[axis]);
                        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-300);
                        for i in 0..3 {
                            c[i] += o * d[i] / n;
                        }
                    }
                }
                c
            })
            .collect()
    }

    /// The masses' sphere radii [m].
    pub fn mass_radii(&self) -> Vec<f64> {
        self.masses.iter().map(|m| m.radius).collect()
    }
}

/// `f(segment, t, point)` at each point of `shape`, t ∈ [0, 1] the point's fraction of its
/// segment (linear in the arc length between the segment's first and last sample).
fn along(shape: &Shape, f: impl Fn(usize, f64, &hybeam::model::ShapePoint) -> f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(shape.points.len());
    for (si, range) in shape.segments.iter().enumerate() {
        let pts = &shape.points[range.clone()];
        let (a0, a1) = match (pts.first(), pts.last()) {
            (Some(a), Some(b)) => (a.arc, b.arc),
            _ => (0.0, 0.0),
        };
        for p in pts {
            let t = if a1 > a0 {
                (p.arc - a0) / (a1 - a0)
            } else {
                0.0
            };
            out.push(f(si, t, p));
        }
    }
    out
}
