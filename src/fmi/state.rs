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

use ModelState as S;

const ANY_INSTANCE: S = S::INSTANTIATED
    .or(S::INIT_MODE)
    .or(S::STEP_COMPLETE)
    .or(S::STEP_FAILED)
    .or(S::STEP_CANCELED)
    .or(S::TERMINATED)
    .or(S::ERROR);
const GETTERS: S = S::INIT_MODE
    .or(S::STEP_COMPLETE)
    .or(S::STEP_FAILED)
    .or(S::STEP_CANCELED)
    .or(S::TERMINATED)
    .or(S::ERROR);
const STATUS: S = S::STEP_COMPLETE
    .or(S::STEP_IN_PROGRESS)
    .or(S::STEP_FAILED)
    .or(S::TERMINATED);

macro_rules! functions {
    ($($variant:ident => $name:literal, $mask:expr;)*) => {
        /// The 34 FMI 2.0 co-simulation functions.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Function {
            $(
                #[doc = concat!("`", $name, "`")]
                $variant,
            )*
        }

        impl Function {
            /// Every function, in the order of the standard's header.
            pub const ALL: &'static [Function] = &[$(Function::$variant),*];

            /// C name, e.g. `fmi2DoStep`.
            pub const fn name(self) -> &'static str {
                match self { $(Function::$variant => $name,)* }
            }

            /// The allowed-state table: the states in which this function may be called.
            pub const fn allowed(self) -> ModelState {
                match self { $(Function::$variant => $mask,)* }
            }
        }
    };
}

functions! {
    GetTypesPlatform => "fmi2GetTypesPlatform", ANY_INSTANCE.or(S::START_AND_END).or(S::FATAL);
    GetVersion => "fmi2GetVersion", ANY_INSTANCE.or(S::START_AND_END).or(S::FATAL);
    SetDebugLogging => "fmi2SetDebugLogging", ANY_INSTANCE.or(S::STEP_IN_PROGRESS);
    Instantiate => "fmi2Instantiate", S::START_AND_END;
    FreeInstance => "fmi2FreeInstance", ANY_INSTANCE.or(S::FATAL);
    SetupExperiment => "fmi2SetupExperiment", S::INSTANTIATED;
    EnterInitializationMode => "fmi2EnterInitializationMode", S::INSTANTIATED;
    ExitInitializationMode => "fmi2ExitInitializationMode", S::INIT_MODE;
    Terminate => "fmi2Terminate", S::STEP_COMPLETE.or(S::STEP_FAILED);
    Reset => "fmi2Reset", ANY_INSTANCE;
    GetReal => "fmi2GetReal", GETTERS;
    GetInteger => "fmi2GetInteger", GETTERS;
    GetBoolean => "fmi2GetBoolean", GETTERS;
    GetString => "fmi2GetString", GETTERS;
    SetReal => "fmi2SetReal", S::INSTANTIATED.or(S::INIT_MODE).or(S::STEP_COMPLETE);
    SetInteger => "fmi2SetInteger", S::INSTANTIATED.or(S::INIT_MODE).or(S::STEP_COMPLETE);
    SetBoolean => "fmi2SetBoolean", S::INSTANTIATED.or(S::INIT_MODE).or(S::STEP_COMPLETE);
    SetString => "fmi2SetString", S::INSTANTIATED.or(S::INIT_MODE).or(S::STEP_COMPLETE);
    GetFMUstate => "fmi2GetFMUstate", ANY_INSTANCE;
    SetFMUstate => "fmi2SetFMUstate", ANY_INSTANCE;
    FreeFMUstate => "fmi2FreeFMUstate", ANY_INSTANCE;
    SerializedFMUstateSize => "fmi2SerializedFMUstateSize", ANY_INSTANCE;
    SerializeFMUstate => "fmi2SerializeFMUstate", ANY_INSTANCE;
    DeSerializeFMUstate => "fmi2DeSerializeFMUstate", ANY_INSTANCE;
    GetDirectionalDerivative => "fmi2GetDirectionalDerivative", GETTERS;
    SetRealInputDerivatives => "fmi2SetRealInputDerivatives", S::INSTANTIATED.or(S::INIT_MODE).or(S::STEP_COMPLETE);
    GetRealOutputDerivatives => "fmi2GetRealOutputDerivatives", S::STEP_COMPLETE.or(S::STEP_FAILED).or(S::STEP_CANCELED).or(S::TERMINATED).or(S::ERROR);
    DoStep => "fmi2DoStep", S::STEP_COMPLETE;
    CancelStep => "fmi2CancelStep", S::STEP_IN_PROGRESS;
    GetStatus => "fmi2GetStatus", STATUS;
    GetRealStatus => "fmi2GetRealStatus", STATUS;
    GetIntegerStatus => "fmi2GetIntegerStatus", STATUS;
    GetBooleanStatus => "fmi2GetBooleanStatus", STATUS;
    GetStringStatus => "fmi2GetStringStatus", STATUS;
}

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
