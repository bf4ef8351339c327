//! One sample of a beam's centreline ([`ShapePoint`]) and the small 3-vector geometry the
//! elements' samplers share (on the model's 3-vector helpers, [`super::vector`]).

use super::vector::{cross, dot};

/// One sample of the centreline.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ShapePoint {
    /// Scene segment index.
    pub segment: usize,
    /// Arc length of the material point in the unstressed reference configuration (straight,
    /// or the arc of a segment's `initial_curvature`), from the root [m].
    pub arc: f64,
    /// Position [m], world axes.
    pub position: [f64; 3],
    /// Velocity [m/s], world axes.
    pub velocity: [f64; 3],
    /// The section frame, world axes: `[t, d2, d3]`, t the unit tangent, d2 and d3 the section
    /// y and z axes (right-handed, orthonormal).
    pub frame: [[f64; 3]; 3],
    /// Axial strain ε = |∂r/∂x| − 1 [-] (0 on a modal segment, which does not stretch), from
    /// the unstressed configuration's (a curved segment's ε₀ subtracted).
    pub axial_strain: f64,
    /// Bending curvature [1/m] about the section axes `[d2, d3]` (plane: `[0, K]` with K the
    /// signed curvature, counter-clockwise positive), from the unstressed configuration's (a
    /// curved segment's initial curvature subtracted: the elastic change).
    pub curvature: [f64; 2],
    /// Twist rate [rad/m] (0 in the plane and on a cable without torsion).
    pub twist: f64,
}

impl ShapePoint {
    /// The magnitude of the bending curvature [1/m].
    pub fn bending(&self) -> f64 {
        (self.curvature[0] * self.curvature[0] + self.curvature[1] * self.curvature[1]).sqrt()
    }
}

/// A vector of the space as three components (z = 0 in the plane).
pub(crate) fn embed(v: &[f64]) -> [f64; 3] {
    std::array::from_fn(|k| v.get(k).copied().unwrap_or(0.0))
}

/// Unit vector of `v` (unchanged if zero).
pub(crate) fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = dot(v, v).sqrt();
    if n > 0.0 {
        v.map(|c| c / n)
    } else {
        v
    }
}

/// The frame `[t, d2, d3]` of tangent direction `t` whose section axes are (e_y, e_z) carried by
/// the smallest rotation taking e_x to t (for a section without a material director; the
/// rotation is undefined for t = −e_x, where (−e_y, e_z) is used).
pub(crate) fn minimal_frame(t: [f64; 3]) -> [[f64; 3]; 3] {
    let t = unit(t);
    let c = t[0];
    if c < -1.0 + 1e-12 {
        return [t, [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    // R = c I + [w]× + w wᵀ/(1 + c), w = e_x × t = (0, −t_z, t_y)
    let w = [0.0, -t[2], t[1]];
    let f = 1.0 / (1.0 + c);
    let col = |e: [f64; 3]| -> [f64; 3] {
        let we = cross(w, e);
        let d = dot(w, e) * f;
        std::array::from_fn(|i| c * e[i] + we[i] + d * w[i])
    };
    [t, col([0.0, 1.0, 0.0]), col([0.0, 0.0, 1.0])]
}

/// The frame `[t, d2, d3]` from the tangent and a section director (Gram–Schmidt).
pub(crate) fn director_frame(t: [f64; 3], d: [f64; 3]) -> [[f64; 3]; 3] {
    let t = unit(t);
    let s = dot(t, d);
    let d2 = unit(std::array::from_fn(|i| d[i] - s * t[i]));
    [t, d2, cross(t, d2)]
}
