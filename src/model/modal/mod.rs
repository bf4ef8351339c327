//! Modal (floating frame of reference) segments.

pub mod basis;
pub mod body;
pub mod body3d;
mod nonlinear;

pub use basis::ModalBasis;
pub use body::{rot, BodyOut, ModalBody};
pub use body3d::{ModalBody3, ModalProps3};
