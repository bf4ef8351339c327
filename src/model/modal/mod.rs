//! Modal (floating frame of reference) segments.

pub mod basis;
pub mod body;

pub use basis::ModalBasis;
pub use body::{rot, BodyOut, ModalBody};
