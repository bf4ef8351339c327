//! FMI 2.0 co-simulation layer. It drives any [`model::CoSimModel`] and knows nothing of beams.
//!
//! - [`types`]: fmi2 C types and status codes (from `fmi-sys`).
//! - [`state`]: state-machine flags and the one allowed-state table.
//! - [`instance`]: what an `fmi2Component` points to.
//! - [`entry`]: generic implementations of the 34 functions; [`export_fmi2!`](crate::export_fmi2)
//!   emits the C symbols.
//! - [`fmu_state`]: FMU state copies and their serialized form.
//! - [`xml`]: modelDescription.xml; [`guid`]: the GUID of a scene; [`resources`]: the resource
//!   URI; [`log`]: log categories and the call into the host's logger.

pub mod entry;
mod export;
pub mod fmu_state;
pub mod guid;
pub mod instance;
pub mod log;
pub mod model;
pub mod resources;
pub mod state;
pub mod types;
pub mod xml;
