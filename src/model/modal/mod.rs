//! Modal (floating frame of reference) segments.

pub mod basis;
pub mod body;
pub mod body3d;
mod nonlinear;

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
}

impl<const N: usize> From<[f64; N]> for BodyGravity<N> {
    /// No line load: both fields are `g`.
    fn from(g: [f64; N]) -> Self {
        Self {
            points: g,
            distributed: g,
        }
    }
}

impl<const N: usize> BodyGravity<N> {
    /// The fields at load factor `load` of gravity `g` and a line load's q/(ρA) `line`: the
    /// same operations as `load·g` without one.
    pub fn of(g: [f64; N], load: f64, line: Option<[f64; N]>) -> Self {
        let points = g.map(|c| load * c);
        let mut distributed = points;
        if let Some(b) = line {
            for (d, b) in distributed.iter_mut().zip(b) {
                *d += load * b;
            }
        }
        Self {
            points,
            distributed,
        }
    }
}
pub use body::{rot, BodyOut, ModalBody};
pub use body3d::{ModalBody3, ModalProps3};
