//! # hybeam
//!
//! A planar flexible beam made of segments, each either a floating-frame body with modal
//! coordinates or a chain of ANCF cable elements, joined rigidly (Sohn & Yoo), integrated by
//! an index-3 generalized-α solver, and shipped as an FMI 2.0 co-simulation FMU.
//!
//! Data flow: [`scene`] (TOML, validated) → [`model`] (assembly: elements, modal bodies,
//! joints) → [`integrator`] (generalized-α, statics) → [`simulator`] (run to a time, outputs,
//! snapshots) → `cosim` in `hybeam-fmu` (the beam's FMU variables) → the `fmi2` crate (FMI 2.0 entry points,
//! which know nothing of beams).

pub mod integrator;
pub mod linalg;
pub mod model;
pub mod scene;
pub mod simulator;
