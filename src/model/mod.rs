//! Model assembly: ANCF elements, modal bodies, joints. No FMI, no time stepping.

pub mod ancf;
pub mod joint;
pub mod modal;
mod system;

pub use system::{Model, Outputs, SegmentCoords};
