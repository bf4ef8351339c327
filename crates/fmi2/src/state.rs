//! The FMI 2.0 co-simulation state machine: [`ModelState`] bit flags and the one
//! allowed-state table ([`Function::allowed`]) that every entry point checks.
//!
//! The masks follow Reference-FMUs `src/fmi2Functions.c` (co-simulation subset), which matches
//! the table of the FMI 2.0.x standard. Two deliberate differences: `fmi2FreeInstance` is accepted
//! in every state but start/end (it must always be able to release memory), and `fmi2Instantiate`
//! has no instance to check.

use std::fmt;

/// One state (or a set of states) of the FMI 2.0 co-simulation state machine.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct ModelState(u32);

impl ModelState {
    /// No instance (before fmi2Instantiate / after fmi2FreeInstance).
    pub const START_AND_END: Self = Self(1 << 0);
    /// After fmi2Instantiate or fmi2Reset.
    pub const INSTANTIATED: Self = Self(1 << 1);
    /// Between fmi2EnterInitializationMode and fmi2ExitInitializationMode.
    pub const INIT_MODE: Self = Self(1 << 2);
    /// Ready for fmi2DoStep.
    pub const STEP_COMPLETE: Self = Self(1 << 3);
    /// Asynchronous step running (never entered by this FMU).
    pub const STEP_IN_PROGRESS: Self = Self(1 << 4);
    /// fmi2DoStep returned fmi2Discard.
    pub const STEP_FAILED: Self = Self(1 << 5);
    /// fmi2CancelStep was called (never entered by this FMU).
    pub const STEP_CANCELED: Self = Self(1 << 6);
    /// After fmi2Terminate.
    pub const TERMINATED: Self = Self(1 << 7);
    /// A function returned fmi2Error because the model failed.
    pub const ERROR: Self = Self(1 << 8);
    /// A function returned fmi2Fatal (e.g. a caught panic).
    pub const FATAL: Self = Self(1 << 9);

    const NAMES: [(Self, &'static str); 10] = [
        (Self::START_AND_END, "startAndEnd"),
        (Self::INSTANTIATED, "instantiated"),
        (Self::INIT_MODE, "initializationMode"),
        (Self::STEP_COMPLETE, "stepComplete"),
        (Self::STEP_IN_PROGRESS, "stepInProgress"),
        (Self::STEP_FAILED, "stepFailed"),
        (Self::STEP_CANCELED, "stepCanceled"),
        (Self::TERMINATED, "terminated"),
        (Self::ERROR, "error"),
        (Self::FATAL, "fatal"),
    ];

    /// The union of two sets of states.
    pub const fn or(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// True if `self` (one state) is in the set `mask`.
    pub const fn is_in(self, mask: Self) -> bool {
        self.0 & mask.0 != 0
    }

    /// The raw bits (used in serialized FMU states).
    pub const fn bits(self) -> u32 {
        self.0
    }

    /// The single state with these bits, or `None` for zero, several or unknown bits.
    pub fn from_bits(bits: u32) -> Option<Self> {
        Self::NAMES.iter().map(|(s, _)| *s).find(|s| s.0 == bits)
    }
}

impl fmt::Debug for ModelState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

/// Names the state, or the states of a mask separated by `|`.
impl fmt::Display for ModelState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for (s, name) in Self::NAMES {
            if self.0 & s.0 != 0 {
                if !first {
                    f.write_str("|")?;
                }
                f.write_str(name)?;
                first = false;
            }
        }
        if first {
            f.write_str("none")?;
        }
        Ok(())
    }
}

/// The sets of states of the allowed-state table (Reference-FMUs `MASK_fmi2…`).
pub mod masks {
    use super::ModelState as S;

    /// Every state with an instance, but `fatal` (and `stepInProgress`, never entered).
    pub const ANY_INSTANCE: S = S::INSTANTIATED
        .or(S::INIT_MODE)
        .or(S::STEP_COMPLETE)
        .or(S::STEP_FAILED)
        .or(S::STEP_CANCELED)
        .or(S::TERMINATED)
        .or(S::ERROR);
    /// Every state, with or without an instance.
    pub const ANY_STATE: S = ANY_INSTANCE.or(S::START_AND_END).or(S::FATAL);
    /// fmi2SetDebugLogging.
    pub const LOGGING: S = ANY_INSTANCE.or(S::STEP_IN_PROGRESS);
    /// fmi2FreeInstance: it must always be able to release memory.
    pub const FREE: S = ANY_INSTANCE.or(S::FATAL);
    /// Before an instance exists.
    pub const START_AND_END: S = S::START_AND_END;
    /// fmi2SetupExperiment, fmi2EnterInitializationMode.
    pub const INSTANTIATED: S = S::INSTANTIATED;
    /// fmi2ExitInitializationMode.
    pub const INIT_MODE: S = S::INIT_MODE;
    /// fmi2Terminate.
    pub const TERMINATE: S = S::STEP_COMPLETE.or(S::STEP_FAILED);
    /// fmi2Get*, fmi2GetDirectionalDerivative.
    pub const GETTERS: S = S::INIT_MODE
        .or(S::STEP_COMPLETE)
        .or(S::STEP_FAILED)
        .or(S::STEP_CANCELED)
        .or(S::TERMINATED)
        .or(S::ERROR);
    /// fmi2Set*, fmi2SetRealInputDerivatives.
    pub const SETTERS: S = S::INSTANTIATED.or(S::INIT_MODE).or(S::STEP_COMPLETE);
    /// fmi2GetRealOutputDerivatives.
    pub const OUTPUT_DERIVATIVES: S = S::STEP_COMPLETE
        .or(S::STEP_FAILED)
        .or(S::STEP_CANCELED)
        .or(S::TERMINATED)
        .or(S::ERROR);
    /// fmi2DoStep.
    pub const STEP_COMPLETE: S = S::STEP_COMPLETE;
    /// fmi2CancelStep.
    pub const STEP_IN_PROGRESS: S = S::STEP_IN_PROGRESS;
    /// fmi2Get*Status.
    pub const STATUS: S = S::STEP_COMPLETE
        .or(S::STEP_IN_PROGRESS)
        .or(S::STEP_FAILED)
        .or(S::TERMINATED);
}

/// The one table of the 34 FMI 2.0 co-simulation functions, in the order of the standard's
/// header: the [`Function`] variant, the C name, the function-pointer type (`crate::sys`) of the
/// official header, the allowed states (a [`masks`] constant) and the C parameters and result.
/// It calls `$callback! { $($extra)* <rows> }`: [`Function`] is generated from it here, the
/// exported shims in [`export_fmi2!`](crate::export_fmi2). Parameter and type names are
/// resolved where the callback expands (`fmi2Component` etc. from [`types`](crate::types)).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_function_table {
    ($callback:path { $($extra:tt)* }) => {
        $callback! {
            $($extra)*
            GetTypesPlatform fmi2GetTypesPlatform fmi2GetTypesPlatformTYPE ANY_STATE
                () -> *const c_char;
            GetVersion fmi2GetVersion fmi2GetVersionTYPE ANY_STATE
                () -> *const c_char;
            SetDebugLogging fmi2SetDebugLogging fmi2SetDebugLoggingTYPE LOGGING
                (c: fmi2Component, logging_on: fmi2Boolean, n_categories: usize,
                 categories: *const fmi2String) -> fmi2Status;
            Instantiate fmi2Instantiate fmi2InstantiateTYPE START_AND_END
                (instance_name: fmi2String, fmu_type: fmi2Type, fmu_guid: fmi2String,
                 fmu_resource_location: fmi2String, functions: *const fmi2CallbackFunctions,
                 visible: fmi2Boolean, logging_on: fmi2Boolean) -> fmi2Component;
            FreeInstance fmi2FreeInstance fmi2FreeInstanceTYPE FREE
                (c: fmi2Component) -> ();
            SetupExperiment fmi2SetupExperiment fmi2SetupExperimentTYPE INSTANTIATED
                (c: fmi2Component, tolerance_defined: fmi2Boolean, tolerance: fmi2Real,
                 start_time: fmi2Real, stop_time_defined: fmi2Boolean, stop_time: fmi2Real)
                -> fmi2Status;
            EnterInitializationMode fmi2EnterInitializationMode fmi2EnterInitializationModeTYPE
                INSTANTIATED (c: fmi2Component) -> fmi2Status;
            ExitInitializationMode fmi2ExitInitializationMode fmi2ExitInitializationModeTYPE
                INIT_MODE (c: fmi2Component) -> fmi2Status;
            Terminate fmi2Terminate fmi2TerminateTYPE TERMINATE
                (c: fmi2Component) -> fmi2Status;
            Reset fmi2Reset fmi2ResetTYPE ANY_INSTANCE
                (c: fmi2Component) -> fmi2Status;
            GetReal fmi2GetReal fmi2GetRealTYPE GETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *mut fmi2Real) -> fmi2Status;
            GetInteger fmi2GetInteger fmi2GetIntegerTYPE GETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *mut fmi2Integer) -> fmi2Status;
            GetBoolean fmi2GetBoolean fmi2GetBooleanTYPE GETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *mut fmi2Boolean) -> fmi2Status;
            GetString fmi2GetString fmi2GetStringTYPE GETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *mut fmi2String) -> fmi2Status;
            SetReal fmi2SetReal fmi2SetRealTYPE SETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *const fmi2Real) -> fmi2Status;
            SetInteger fmi2SetInteger fmi2SetIntegerTYPE SETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *const fmi2Integer) -> fmi2Status;
            SetBoolean fmi2SetBoolean fmi2SetBooleanTYPE SETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *const fmi2Boolean) -> fmi2Status;
            SetString fmi2SetString fmi2SetStringTYPE SETTERS
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 value: *const fmi2String) -> fmi2Status;
            GetFMUstate fmi2GetFMUstate fmi2GetFMUstateTYPE ANY_INSTANCE
                (c: fmi2Component, fmu_state: *mut fmi2FMUstate) -> fmi2Status;
            SetFMUstate fmi2SetFMUstate fmi2SetFMUstateTYPE ANY_INSTANCE
                (c: fmi2Component, fmu_state: fmi2FMUstate) -> fmi2Status;
            FreeFMUstate fmi2FreeFMUstate fmi2FreeFMUstateTYPE ANY_INSTANCE
                (c: fmi2Component, fmu_state: *mut fmi2FMUstate) -> fmi2Status;
            SerializedFMUstateSize fmi2SerializedFMUstateSize fmi2SerializedFMUstateSizeTYPE
                ANY_INSTANCE (c: fmi2Component, fmu_state: fmi2FMUstate, size: *mut usize)
                -> fmi2Status;
            SerializeFMUstate fmi2SerializeFMUstate fmi2SerializeFMUstateTYPE ANY_INSTANCE
                (c: fmi2Component, fmu_state: fmi2FMUstate, serialized_state: *mut fmi2Byte,
                 size: usize) -> fmi2Status;
            DeSerializeFMUstate fmi2DeSerializeFMUstate fmi2DeSerializeFMUstateTYPE ANY_INSTANCE
                (c: fmi2Component, serialized_state: *const fmi2Byte, size: usize,
                 fmu_state: *mut fmi2FMUstate) -> fmi2Status;
            GetDirectionalDerivative fmi2GetDirectionalDerivative
                fmi2GetDirectionalDerivativeTYPE GETTERS
                (c: fmi2Component, v_unknown_ref: *const fmi2ValueReference, n_unknown: usize,
                 v_known_ref: *const fmi2ValueReference, n_known: usize,
                 dv_known: *const fmi2Real, dv_unknown: *mut fmi2Real) -> fmi2Status;
            SetRealInputDerivatives fmi2SetRealInputDerivatives fmi2SetRealInputDerivativesTYPE
                SETTERS (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 order: *const fmi2Integer, value: *const fmi2Real) -> fmi2Status;
            GetRealOutputDerivatives fmi2GetRealOutputDerivatives
                fmi2GetRealOutputDerivativesTYPE OUTPUT_DERIVATIVES
                (c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                 order: *const fmi2Integer, value: *mut fmi2Real) -> fmi2Status;
            DoStep fmi2DoStep fmi2DoStepTYPE STEP_COMPLETE
                (c: fmi2Component, current_communication_point: fmi2Real,
                 communication_step_size: fmi2Real,
                 no_set_fmu_state_prior_to_current_point: fmi2Boolean) -> fmi2Status;
            CancelStep fmi2CancelStep fmi2CancelStepTYPE STEP_IN_PROGRESS
                (c: fmi2Component) -> fmi2Status;
            GetStatus fmi2GetStatus fmi2GetStatusTYPE STATUS
                (c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status;
            GetRealStatus fmi2GetRealStatus fmi2GetRealStatusTYPE STATUS
                (c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status;
            GetIntegerStatus fmi2GetIntegerStatus fmi2GetIntegerStatusTYPE STATUS
                (c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Integer) -> fmi2Status;
            GetBooleanStatus fmi2GetBooleanStatus fmi2GetBooleanStatusTYPE STATUS
                (c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status;
            GetStringStatus fmi2GetStringStatus fmi2GetStringStatusTYPE STATUS
                (c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2String) -> fmi2Status;
        }
    };
}

/// [`Function`] from the table.
macro_rules! function_enum {
    ($($variant:ident $name:ident $ty:ident $mask:ident ($($p:ident: $t:ty),* $(,)?) -> $ret:ty;)*) => {
        /// The 34 FMI 2.0 co-simulation functions.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Function {
            $(
                #[doc = concat!("`", stringify!($name), "`")]
                $variant,
            )*
        }

        impl Function {
            /// Every function, in the order of the standard's header.
            pub const ALL: &'static [Function] = &[$(Function::$variant),*];

            /// C name, e.g. `fmi2DoStep`.
            pub const fn name(self) -> &'static str {
                match self { $(Function::$variant => stringify!($name),)* }
            }

            /// The allowed-state table: the states in which this function may be called.
            pub const fn allowed(self) -> ModelState {
                match self { $(Function::$variant => masks::$mask,)* }
            }
        }
    };
}

crate::__fmi2_function_table!(function_enum {});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thirty_four_functions_with_fmi2_names() {
        assert_eq!(Function::ALL.len(), 34);
        assert!(Function::ALL.iter().all(|f| f.name().starts_with("fmi2")));
    }

    #[test]
    fn do_step_only_in_step_complete() {
        for (s, _) in ModelState::NAMES {
            assert_eq!(
                s.is_in(Function::DoStep.allowed()),
                s == ModelState::STEP_COMPLETE
            );
        }
    }

    #[test]
    fn display_and_bits_round_trip() {
        assert_eq!(
            Function::Terminate.allowed().to_string(),
            "stepComplete|stepFailed"
        );
        for (s, _) in ModelState::NAMES {
            assert_eq!(ModelState::from_bits(s.bits()), Some(s));
        }
        assert_eq!(ModelState::from_bits(0), None);
        assert_eq!(ModelState::from_bits(3), None);
    }
}
