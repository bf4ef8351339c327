//! The checked-in FMI 2.0 C types (`src/sys.rs`) against `fmi-sys`'s bindings generated from
//! the official headers at build time: every type alias must be the same type (checked by the
//! compiler), every constant the same value, every struct the same layout.
#![allow(non_snake_case)]

use fmi2::sys as ours;
use fmi_sys::fmi2 as official;

/// Each alias converts to the official one by identity: compiles only if they are one type.
/// Not listed: `fmi2InstantiateTYPE` and `fmi2NewDiscreteStatesTYPE`, whose parameters point to
/// the two structs (nominally distinct types in the two crates; their layouts are checked below
/// and the Rust declarations of the two signatures are textually the bindgen ones).
#[test]
fn type_aliases_are_the_official_ones() {
    let _: fn(ours::fmi2Component) -> official::fmi2Component = |x| x;
    let _: fn(ours::fmi2ComponentEnvironment) -> official::fmi2ComponentEnvironment = |x| x;
    let _: fn(ours::fmi2FMUstate) -> official::fmi2FMUstate = |x| x;
    let _: fn(ours::fmi2ValueReference) -> official::fmi2ValueReference = |x| x;
    let _: fn(ours::fmi2Real) -> official::fmi2Real = |x| x;
    let _: fn(ours::fmi2Integer) -> official::fmi2Integer = |x| x;
    let _: fn(ours::fmi2Boolean) -> official::fmi2Boolean = |x| x;
    let _: fn(ours::fmi2Char) -> official::fmi2Char = |x| x;
    let _: fn(ours::fmi2String) -> official::fmi2String = |x| x;
    let _: fn(ours::fmi2Byte) -> official::fmi2Byte = |x| x;
    let _: fn(ours::fmi2Status) -> official::fmi2Status = |x| x;
    let _: fn(ours::fmi2Type) -> official::fmi2Type = |x| x;
    let _: fn(ours::fmi2StatusKind) -> official::fmi2StatusKind = |x| x;
    let _: fn(ours::fmi2CallbackLogger) -> official::fmi2CallbackLogger = |x| x;
    let _: fn(ours::fmi2CallbackAllocateMemory) -> official::fmi2CallbackAllocateMemory = |x| x;
    let _: fn(ours::fmi2CallbackFreeMemory) -> official::fmi2CallbackFreeMemory = |x| x;
    let _: fn(ours::fmi2StepFinished) -> official::fmi2StepFinished = |x| x;
    let _: fn(ours::fmi2GetTypesPlatformTYPE) -> official::fmi2GetTypesPlatformTYPE = |x| x;
    let _: fn(ours::fmi2GetVersionTYPE) -> official::fmi2GetVersionTYPE = |x| x;
    let _: fn(ours::fmi2SetDebugLoggingTYPE) -> official::fmi2SetDebugLoggingTYPE = |x| x;
    let _: fn(ours::fmi2FreeInstanceTYPE) -> official::fmi2FreeInstanceTYPE = |x| x;
    let _: fn(ours::fmi2SetupExperimentTYPE) -> official::fmi2SetupExperimentTYPE = |x| x;
    let _: fn(ours::fmi2EnterInitializationModeTYPE) -> official::fmi2EnterInitializationModeTYPE =
        |x| x;
    let _: fn(ours::fmi2ExitInitializationModeTYPE) -> official::fmi2ExitInitializationModeTYPE =
        |x| x;
    let _: fn(ours::fmi2TerminateTYPE) -> official::fmi2TerminateTYPE = |x| x;
    let _: fn(ours::fmi2ResetTYPE) -> official::fmi2ResetTYPE = |x| x;
    let _: fn(ours::fmi2GetRealTYPE) -> official::fmi2GetRealTYPE = |x| x;
    let _: fn(ours::fmi2GetIntegerTYPE) -> official::fmi2GetIntegerTYPE = |x| x;
    let _: fn(ours::fmi2GetBooleanTYPE) -> official::fmi2GetBooleanTYPE = |x| x;
    let _: fn(ours::fmi2GetStringTYPE) -> official::fmi2GetStringTYPE = |x| x;
    let _: fn(ours::fmi2SetRealTYPE) -> official::fmi2SetRealTYPE = |x| x;
    let _: fn(ours::fmi2SetIntegerTYPE) -> official::fmi2SetIntegerTYPE = |x| x;
    let _: fn(ours::fmi2SetBooleanTYPE) -> official::fmi2SetBooleanTYPE = |x| x;
    let _: fn(ours::fmi2SetStringTYPE) -> official::fmi2SetStringTYPE = |x| x;
    let _: fn(ours::fmi2GetFMUstateTYPE) -> official::fmi2GetFMUstateTYPE = |x| x;
    let _: fn(ours::fmi2SetFMUstateTYPE) -> official::fmi2SetFMUstateTYPE = |x| x;
    let _: fn(ours::fmi2FreeFMUstateTYPE) -> official::fmi2FreeFMUstateTYPE = |x| x;
    let _: fn(ours::fmi2SerializedFMUstateSizeTYPE) -> official::fmi2SerializedFMUstateSizeTYPE =
        |x| x;
    let _: fn(ours::fmi2SerializeFMUstateTYPE) -> official::fmi2SerializeFMUstateTYPE = |x| x;
    let _: fn(ours::fmi2DeSerializeFMUstateTYPE) -> official::fmi2DeSerializeFMUstateTYPE = |x| x;
    let _: fn(
        ours::fmi2GetDirectionalDerivativeTYPE,
    ) -> official::fmi2GetDirectionalDerivativeTYPE = |x| x;
    let _: fn(ours::fmi2EnterEventModeTYPE) -> official::fmi2EnterEventModeTYPE = |x| x;
    let _: fn(ours::fmi2EnterContinuousTimeModeTYPE) -> official::fmi2EnterContinuousTimeModeTYPE =
        |x| x;
    let _: fn(ours::fmi2CompletedIntegratorStepTYPE) -> official::fmi2CompletedIntegratorStepTYPE =
        |x| x;
    let _: fn(ours::fmi2SetTimeTYPE) -> official::fmi2SetTimeTYPE = |x| x;
    let _: fn(ours::fmi2SetContinuousStatesTYPE) -> official::fmi2SetContinuousStatesTYPE = |x| x;
    let _: fn(ours::fmi2GetDerivativesTYPE) -> official::fmi2GetDerivativesTYPE = |x| x;
    let _: fn(ours::fmi2GetEventIndicatorsTYPE) -> official::fmi2GetEventIndicatorsTYPE = |x| x;
    let _: fn(ours::fmi2GetContinuousStatesTYPE) -> official::fmi2GetContinuousStatesTYPE = |x| x;
    let _: fn(
        ours::fmi2GetNominalsOfContinuousStatesTYPE,
    ) -> official::fmi2GetNominalsOfContinuousStatesTYPE = |x| x;
    let _: fn(ours::fmi2SetRealInputDerivativesTYPE) -> official::fmi2SetRealInputDerivativesTYPE =
        |x| x;
    let _: fn(
        ours::fmi2GetRealOutputDerivativesTYPE,
    ) -> official::fmi2GetRealOutputDerivativesTYPE = |x| x;
    let _: fn(ours::fmi2DoStepTYPE) -> official::fmi2DoStepTYPE = |x| x;
    let _: fn(ours::fmi2CancelStepTYPE) -> official::fmi2CancelStepTYPE = |x| x;
    let _: fn(ours::fmi2GetStatusTYPE) -> official::fmi2GetStatusTYPE = |x| x;
    let _: fn(ours::fmi2GetRealStatusTYPE) -> official::fmi2GetRealStatusTYPE = |x| x;
    let _: fn(ours::fmi2GetIntegerStatusTYPE) -> official::fmi2GetIntegerStatusTYPE = |x| x;
    let _: fn(ours::fmi2GetBooleanStatusTYPE) -> official::fmi2GetBooleanStatusTYPE = |x| x;
    let _: fn(ours::fmi2GetStringStatusTYPE) -> official::fmi2GetStringStatusTYPE = |x| x;
}

#[test]
fn constants_have_the_official_values() {
    assert_eq!(ours::fmi2TypesPlatform, official::fmi2TypesPlatform);
    assert_eq!(ours::fmi2True, official::fmi2True);
    assert_eq!(ours::fmi2False, official::fmi2False);
    assert_eq!(ours::fmi2Version, official::fmi2Version);
    assert_eq!(ours::fmi2Status_fmi2OK, official::fmi2Status_fmi2OK);
    assert_eq!(
        ours::fmi2Status_fmi2Warning,
        official::fmi2Status_fmi2Warning
    );
    assert_eq!(
        ours::fmi2Status_fmi2Discard,
        official::fmi2Status_fmi2Discard
    );
    assert_eq!(ours::fmi2Status_fmi2Error, official::fmi2Status_fmi2Error);
    assert_eq!(ours::fmi2Status_fmi2Fatal, official::fmi2Status_fmi2Fatal);
    assert_eq!(
        ours::fmi2Status_fmi2Pending,
        official::fmi2Status_fmi2Pending
    );
    assert_eq!(
        ours::fmi2Type_fmi2ModelExchange,
        official::fmi2Type_fmi2ModelExchange
    );
    assert_eq!(
        ours::fmi2Type_fmi2CoSimulation,
        official::fmi2Type_fmi2CoSimulation
    );
    assert_eq!(
        ours::fmi2StatusKind_fmi2DoStepStatus,
        official::fmi2StatusKind_fmi2DoStepStatus
    );
    assert_eq!(
        ours::fmi2StatusKind_fmi2PendingStatus,
        official::fmi2StatusKind_fmi2PendingStatus
    );
    assert_eq!(
        ours::fmi2StatusKind_fmi2LastSuccessfulTime,
        official::fmi2StatusKind_fmi2LastSuccessfulTime
    );
    assert_eq!(
        ours::fmi2StatusKind_fmi2Terminated,
        official::fmi2StatusKind_fmi2Terminated
    );
}

#[test]
fn structs_have_the_official_layout() {
    assert_eq!(
        std::mem::size_of::<ours::fmi2CallbackFunctions>(),
        std::mem::size_of::<official::fmi2CallbackFunctions>()
    );
    assert_eq!(
        std::mem::align_of::<ours::fmi2CallbackFunctions>(),
        std::mem::align_of::<official::fmi2CallbackFunctions>()
    );
    assert_eq!(
        std::mem::size_of::<ours::fmi2EventInfo>(),
        std::mem::size_of::<official::fmi2EventInfo>()
    );
    assert_eq!(
        std::mem::align_of::<ours::fmi2EventInfo>(),
        std::mem::align_of::<official::fmi2EventInfo>()
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2CallbackFunctions, logger),
        std::mem::offset_of!(official::fmi2CallbackFunctions, logger)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2CallbackFunctions, allocateMemory),
        std::mem::offset_of!(official::fmi2CallbackFunctions, allocateMemory)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2CallbackFunctions, freeMemory),
        std::mem::offset_of!(official::fmi2CallbackFunctions, freeMemory)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2CallbackFunctions, stepFinished),
        std::mem::offset_of!(official::fmi2CallbackFunctions, stepFinished)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2CallbackFunctions, componentEnvironment),
        std::mem::offset_of!(official::fmi2CallbackFunctions, componentEnvironment)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2EventInfo, newDiscreteStatesNeeded),
        std::mem::offset_of!(official::fmi2EventInfo, newDiscreteStatesNeeded)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2EventInfo, terminateSimulation),
        std::mem::offset_of!(official::fmi2EventInfo, terminateSimulation)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2EventInfo, nominalsOfContinuousStatesChanged),
        std::mem::offset_of!(official::fmi2EventInfo, nominalsOfContinuousStatesChanged)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2EventInfo, valuesOfContinuousStatesChanged),
        std::mem::offset_of!(official::fmi2EventInfo, valuesOfContinuousStatesChanged)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2EventInfo, nextEventTimeDefined),
        std::mem::offset_of!(official::fmi2EventInfo, nextEventTimeDefined)
    );
    assert_eq!(
        std::mem::offset_of!(ours::fmi2EventInfo, nextEventTime),
        std::mem::offset_of!(official::fmi2EventInfo, nextEventTime)
    );
}
