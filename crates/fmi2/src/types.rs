//! FMI 2.0 C types and status codes, from the bindings of the official headers in [`crate::sys`].
//!
//! Only the ten or so types the exporter needs are re-exported here, under their C names, plus a
//! small Rust [`Status`] enum ordered by severity (so statuses combine with `max`).

pub use crate::sys::{
    fmi2Boolean, fmi2Byte, fmi2CallbackFunctions, fmi2CallbackLogger, fmi2Char, fmi2Component,
    fmi2ComponentEnvironment, fmi2FMUstate, fmi2Integer, fmi2Real, fmi2Status, fmi2StatusKind,
    fmi2String, fmi2Type, fmi2ValueReference,
};

/// The raw bindings (function-pointer types used to check the exported signatures).
pub use crate::sys;

/// `fmi2True`.
pub const FMI2_TRUE: fmi2Boolean = sys::fmi2True as fmi2Boolean;
/// `fmi2False`.
pub const FMI2_FALSE: fmi2Boolean = sys::fmi2False as fmi2Boolean;
/// `fmi2CoSimulation`.
pub const FMI2_CO_SIMULATION: fmi2Type = sys::fmi2Type_fmi2CoSimulation;
/// `fmi2ModelExchange`.
pub const FMI2_MODEL_EXCHANGE: fmi2Type = sys::fmi2Type_fmi2ModelExchange;
/// `fmi2DoStepStatus`.
pub const FMI2_DO_STEP_STATUS: fmi2StatusKind = sys::fmi2StatusKind_fmi2DoStepStatus;
/// `fmi2PendingStatus`.
pub const FMI2_PENDING_STATUS: fmi2StatusKind = sys::fmi2StatusKind_fmi2PendingStatus;
/// `fmi2LastSuccessfulTime`.
pub const FMI2_LAST_SUCCESSFUL_TIME: fmi2StatusKind = sys::fmi2StatusKind_fmi2LastSuccessfulTime;
/// `fmi2Terminated`.
pub const FMI2_TERMINATED: fmi2StatusKind = sys::fmi2StatusKind_fmi2Terminated;
/// `fmi2TypesPlatform` as a C string ("default").
pub const TYPES_PLATFORM: &std::ffi::CStr = c"default";
/// `fmi2Version` as a C string ("2.0").
pub const VERSION: &std::ffi::CStr = c"2.0";

/// fmi2Status as a Rust enum, ordered by severity (`Pending` is never returned by this layer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// fmi2OK.
    Ok,
    /// fmi2Warning.
    Warning,
    /// fmi2Discard.
    Discard,
    /// fmi2Error.
    Error,
    /// fmi2Fatal.
    Fatal,
}

impl Status {
    /// The C value.
    pub const fn to_c(self) -> fmi2Status {
        match self {
            Status::Ok => sys::fmi2Status_fmi2OK,
            Status::Warning => sys::fmi2Status_fmi2Warning,
            Status::Discard => sys::fmi2Status_fmi2Discard,
            Status::Error => sys::fmi2Status_fmi2Error,
            Status::Fatal => sys::fmi2Status_fmi2Fatal,
        }
    }

    /// The C name, e.g. `fmi2Discard`.
    pub const fn name(self) -> &'static str {
        match self {
            Status::Ok => "fmi2OK",
            Status::Warning => "fmi2Warning",
            Status::Discard => "fmi2Discard",
            Status::Error => "fmi2Error",
            Status::Fatal => "fmi2Fatal",
        }
    }
}

/// Checks the bindings against the C values fixed by the FMI 2.0 standard.
const _: () = {
    assert!(Status::Ok.to_c() == 0);
    assert!(Status::Warning.to_c() == 1);
    assert!(Status::Discard.to_c() == 2);
    assert!(Status::Error.to_c() == 3);
    assert!(Status::Fatal.to_c() == 4);
    assert!(FMI2_CO_SIMULATION == 1);
    assert!(FMI2_TERMINATED == 3);
    assert!(FMI2_LAST_SUCCESSFUL_TIME == 2);
};
