//! # hybeam
//!
//! A flexible beam, planar or spatial, made of segments, each either a floating-frame body
//! with modal coordinates or a chain of ANCF elements, joined rigidly (Sohn & Yoo), its root
//! clamped, pinned/ball or mounted on a moving body, integrated as an index-3 system by
//! generalized-α or the order-4 ESDIRK (`solver.method`), and shipped as an FMI 2.0
//! co-simulation FMU.
//!
//! Data flow: [`scene`] (TOML, validated) → [`model`] (assembly: elements, modal bodies,
//! joints) → [`integrator`] (generalized-α, ESDIRK4, statics) → [`simulator`] (run to a time,
//! outputs, snapshots). The engine knows nothing of FMI and has no `unsafe`: the `hybeam-fmu`
//! crate adapts the simulator as the beam's FMU (`cosim`) and exports it through the `fmi2`
//! crate.

#![forbid(unsafe_code)]

pub mod error;
pub mod integrator;
pub mod linalg;
pub mod math;
pub mod model;
pub mod scene;
pub mod simulator;
