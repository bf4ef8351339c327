//! # hybeam
//!
//! A flexible beam simulator shipped as an FMI 2.0 co-simulation FMU.
//!
//! On this branch: the FMI layer ([`fmi`]), which drives any [`fmi::model::CoSimModel`], and a
//! [`toy`] model that stands in for the beam until the branches merge.

pub mod fmi;
pub mod toy;

/// The model this library exports as an FMU (and that `fmu-build` packages).
pub type FmuModel = toy::Toy;

export_fmi2!(FmuModel);
