//! The hybeam FMU: the beam's co-simulation model exported through the generic FMI 2.0 layer
//! (the `fmi2` crate). This crate is the shared library `fmu-build` packages; the engine
//! (`hybeam`) knows nothing of FMI.

pub mod cosim;

/// The model this library exports as an FMU (and that `fmu-build` packages).
pub type FmuModel = cosim::BeamFmu;

fmi2::export_fmi2!(FmuModel);
