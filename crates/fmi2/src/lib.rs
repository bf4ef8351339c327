//! FMI 2.0 co-simulation layer. It drives any [`CoSimModel`] and knows nothing of the model
//! behind it: the model supplies its resource file, GUID identity, state magic and generation
//! tool as associated constants.
//!
//! - [`model`]: the [`CoSimModel`] trait, variables, [`StepError`].
//! - [`state`]: state-machine flags and the one table of the 34 functions (allowed states, C
//!   signatures) that generates [`Function`] and the exported shims.
//! - [`instance`]: what an `fmi2Component` points to; its methods are the 34 functions as safe
//!   Rust (slices, `&str`, [`Status`]), unit-testable without a C host.
//! - [`guard`]: the only unsafe code of the layer: C pointers to references and slices, panic
//!   capture, allocation of instances and FMU states, the call into the host's logger.
//! - [`export_fmi2!`]: the 34 `extern "C"` symbols of a shared library, forwarding to
//!   [`guard`].
//! - [`fmu_state`]: FMU state copies and their serialized form; [`xml`]: modelDescription.xml;
//!   [`guid`]: the GUID of a resource; [`resources`]: the resource URI; [`log`]: log categories;
//!   [`hash`]: FNV-1a.

#![deny(unsafe_code, unsafe_op_in_unsafe_fn)]
#![warn(clippy::undocumented_unsafe_blocks)]

mod calls;
mod export;
pub mod fmu_state;
#[allow(unsafe_code)]
pub mod guard;
pub mod guid;
pub mod hash;
pub mod instance;
pub mod log;
pub mod model;
pub mod osp;
pub mod resources;
pub mod state;
pub mod sys;
pub mod types;
pub mod xml;

pub use instance::Instance;
pub use model::{
    Capabilities, Causality, CoSimModel, ModelInfo, StepError, StringVariable, Variability,
    Variable,
};
pub use state::{Function, ModelState};
pub use types::Status;
