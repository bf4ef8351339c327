//! Modal (floating frame of reference) segments.

pub mod basis;
pub mod body;
pub mod body3d;
mod nonlinear;
mod taper;

pub use basis::ModalBasis;

/// The gravity a modal body's distributed mass feels and the one its point masses feel
/// [m/s²]: equal without a line load; a segment's line load q [N/m] is a dead load beside the
/// distributed weight ρA g, so its distributed field is g + q/(ρA).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyGravity<const N: usize> {
    /// On the point masses.
    pub points: [f64; N],
    /// On the distributed mass (with the line load).
    pub distributed: [f64; N],
    /// The line load's share of `distributed`, load · q/ρA_ref [m/s²] (zero without one): a
    /// tapered body (ρA varying along it) takes `points` on its mass and q = ρA_ref · `line` [N/m]
    /// per unit length apart, ρA_ref its ρA at the start.
    pub line: [f64; N],
}

impl<const N: usize> From<[f64; N]> for BodyGravity<N> {
    /// No line load: both fields are `g`.
    fn from(g: [f64; N]) -> Self {
        Self {
            points: g,
            distributed: g,
            line: [0.0; N],
        }
    }
}

impl<const N: usize> BodyGravity<N> {
    /// The fields at load factor `load` of gravity `g` and a line load's q/(ρA) `line`: the
    /// same operations as `load·g` without one.
    pub fn of(g: [f64; N], load: f64, line: Option<[f64; N]>) -> Self {
        let points = g.map(|c| load * c);
        let mut distributed = points;
        let mut share = [0.0; N];
        if let Some(b) = line {
            for ((d, s), b) in distributed.iter_mut().zip(share.iter_mut()).zip(b) {
                *s = load * b;
                *d += *s;
            }
        }
        Self {
            points,
            distributed,
            line: share,
        }
    }
}
pub use body::{rot, BodyOut, ModalBody};
pub use body3d::{ModalBody3, ModalProps3};
