//! Views of a hybeam run, for people: the beam's shape over time (the engine's
//! [`hybeam::model::Shape`]) as a ParaView series ([`vtk`]: `.pvd` of `.vtu`, written with
//! vtkio) and as one self-contained 3D animation page ([`animation`]: three.js bundled in).
//! Used by the `hybeam` command line (`--vtk`, `--animate`, `animate`) and by the FMU
//! (`visualization.directory`). Knows the engine's shape, not FMI.

pub mod animation;
pub mod look;
pub mod read;
pub mod recording;
pub mod vtk;

pub use animation::{BodyBox, Recorder};
pub use look::Look;
pub use recording::Views;
pub use vtk::{Series, ViewError};
