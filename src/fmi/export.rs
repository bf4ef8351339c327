//! [`export_fmi2!`](crate::export_fmi2): the 34 `extern "C"` FMI 2.0 co-simulation symbols.
//!
//! One block per function of the standard (FMI 2.0 header order); each symbol only
//! forwards to the generic implementation in [`entry`](super::entry), and a compile-time check
//! compares its signature with the `fmi-sys` binding of the official header.

/// Exports the 34 FMI 2.0 co-simulation functions (`fmi2Instantiate`, `fmi2DoStep`, ...) as
/// `#[no_mangle] extern "C"` symbols driving the model type `$model` (a
/// [`CoSimModel`](crate::fmi::model::CoSimModel)). Use it once per shared library.
#[macro_export]
macro_rules! export_fmi2 {
    ($model:ty) => {
        #[doc = "FMI 2.0 `fmi2GetTypesPlatform` (forwards to `hybeam::fmi::entry::get_types_platform`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetTypesPlatform() -> *const ::std::ffi::c_char {
            $crate::fmi::entry::get_types_platform()
        }
        const _: $crate::fmi::types::sys::fmi2GetTypesPlatformTYPE = Some(fmi2GetTypesPlatform);
        #[doc = "FMI 2.0 `fmi2GetVersion` (forwards to `hybeam::fmi::entry::get_version`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetVersion() -> *const ::std::ffi::c_char {
            $crate::fmi::entry::get_version()
        }
        const _: $crate::fmi::types::sys::fmi2GetVersionTYPE = Some(fmi2GetVersion);
        #[doc = "FMI 2.0 `fmi2SetDebugLogging` (forwards to `hybeam::fmi::entry::set_debug_logging`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetDebugLogging(c: $crate::fmi::types::fmi2Component, logging_on: $crate::fmi::types::fmi2Boolean, n_categories: usize, categories: *const $crate::fmi::types::fmi2String) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_debug_logging::<$model>(c, logging_on, n_categories, categories) }
        }
        const _: $crate::fmi::types::sys::fmi2SetDebugLoggingTYPE = Some(fmi2SetDebugLogging);
        #[doc = "FMI 2.0 `fmi2Instantiate` (forwards to `hybeam::fmi::entry::instantiate`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2Instantiate(instance_name: $crate::fmi::types::fmi2String, fmu_type: $crate::fmi::types::fmi2Type, fmu_guid: $crate::fmi::types::fmi2String, fmu_resource_location: $crate::fmi::types::fmi2String, functions: *const $crate::fmi::types::fmi2CallbackFunctions, visible: $crate::fmi::types::fmi2Boolean, logging_on: $crate::fmi::types::fmi2Boolean) -> $crate::fmi::types::fmi2Component {
            unsafe { $crate::fmi::entry::instantiate::<$model>(instance_name, fmu_type, fmu_guid, fmu_resource_location, functions, visible, logging_on) }
        }
        const _: $crate::fmi::types::sys::fmi2InstantiateTYPE = Some(fmi2Instantiate);
        #[doc = "FMI 2.0 `fmi2FreeInstance` (forwards to `hybeam::fmi::entry::free_instance`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeInstance(c: $crate::fmi::types::fmi2Component) {
            unsafe { $crate::fmi::entry::free_instance::<$model>(c) }
        }
        const _: $crate::fmi::types::sys::fmi2FreeInstanceTYPE = Some(fmi2FreeInstance);
        #[doc = "FMI 2.0 `fmi2SetupExperiment` (forwards to `hybeam::fmi::entry::setup_experiment`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetupExperiment(c: $crate::fmi::types::fmi2Component, tolerance_defined: $crate::fmi::types::fmi2Boolean, tolerance: $crate::fmi::types::fmi2Real, start_time: $crate::fmi::types::fmi2Real, stop_time_defined: $crate::fmi::types::fmi2Boolean, stop_time: $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::setup_experiment::<$model>(c, tolerance_defined, tolerance, start_time, stop_time_defined, stop_time) }
        }
        const _: $crate::fmi::types::sys::fmi2SetupExperimentTYPE = Some(fmi2SetupExperiment);
        #[doc = "FMI 2.0 `fmi2EnterInitializationMode` (forwards to `hybeam::fmi::entry::enter_initialization_mode`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2EnterInitializationMode(c: $crate::fmi::types::fmi2Component) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::enter_initialization_mode::<$model>(c) }
        }
        const _: $crate::fmi::types::sys::fmi2EnterInitializationModeTYPE = Some(fmi2EnterInitializationMode);
        #[doc = "FMI 2.0 `fmi2ExitInitializationMode` (forwards to `hybeam::fmi::entry::exit_initialization_mode`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2ExitInitializationMode(c: $crate::fmi::types::fmi2Component) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::exit_initialization_mode::<$model>(c) }
        }
        const _: $crate::fmi::types::sys::fmi2ExitInitializationModeTYPE = Some(fmi2ExitInitializationMode);
        #[doc = "FMI 2.0 `fmi2Terminate` (forwards to `hybeam::fmi::entry::terminate`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2Terminate(c: $crate::fmi::types::fmi2Component) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::terminate::<$model>(c) }
        }
        const _: $crate::fmi::types::sys::fmi2TerminateTYPE = Some(fmi2Terminate);
        #[doc = "FMI 2.0 `fmi2Reset` (forwards to `hybeam::fmi::entry::reset`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2Reset(c: $crate::fmi::types::fmi2Component) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::reset::<$model>(c) }
        }
        const _: $crate::fmi::types::sys::fmi2ResetTYPE = Some(fmi2Reset);
        #[doc = "FMI 2.0 `fmi2GetReal` (forwards to `hybeam::fmi::entry::get_real`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetReal(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *mut $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_real::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetRealTYPE = Some(fmi2GetReal);
        #[doc = "FMI 2.0 `fmi2GetInteger` (forwards to `hybeam::fmi::entry::get_integer`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetInteger(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *mut $crate::fmi::types::fmi2Integer) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_integer::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetIntegerTYPE = Some(fmi2GetInteger);
        #[doc = "FMI 2.0 `fmi2GetBoolean` (forwards to `hybeam::fmi::entry::get_boolean`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetBoolean(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *mut $crate::fmi::types::fmi2Boolean) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_boolean::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetBooleanTYPE = Some(fmi2GetBoolean);
        #[doc = "FMI 2.0 `fmi2GetString` (forwards to `hybeam::fmi::entry::get_string`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetString(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *mut $crate::fmi::types::fmi2String) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_string::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetStringTYPE = Some(fmi2GetString);
        #[doc = "FMI 2.0 `fmi2SetReal` (forwards to `hybeam::fmi::entry::set_real`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetReal(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *const $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_real::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2SetRealTYPE = Some(fmi2SetReal);
        #[doc = "FMI 2.0 `fmi2SetInteger` (forwards to `hybeam::fmi::entry::set_integer`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetInteger(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *const $crate::fmi::types::fmi2Integer) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_integer::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2SetIntegerTYPE = Some(fmi2SetInteger);
        #[doc = "FMI 2.0 `fmi2SetBoolean` (forwards to `hybeam::fmi::entry::set_boolean`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetBoolean(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *const $crate::fmi::types::fmi2Boolean) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_boolean::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2SetBooleanTYPE = Some(fmi2SetBoolean);
        #[doc = "FMI 2.0 `fmi2SetString` (forwards to `hybeam::fmi::entry::set_string`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetString(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, value: *const $crate::fmi::types::fmi2String) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_string::<$model>(c, vr, nvr, value) }
        }
        const _: $crate::fmi::types::sys::fmi2SetStringTYPE = Some(fmi2SetString);
        #[doc = "FMI 2.0 `fmi2GetFMUstate` (forwards to `hybeam::fmi::entry::get_fmu_state`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetFMUstate(c: $crate::fmi::types::fmi2Component, fmu_state: *mut $crate::fmi::types::fmi2FMUstate) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_fmu_state::<$model>(c, fmu_state) }
        }
        const _: $crate::fmi::types::sys::fmi2GetFMUstateTYPE = Some(fmi2GetFMUstate);
        #[doc = "FMI 2.0 `fmi2SetFMUstate` (forwards to `hybeam::fmi::entry::set_fmu_state`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetFMUstate(c: $crate::fmi::types::fmi2Component, fmu_state: $crate::fmi::types::fmi2FMUstate) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_fmu_state::<$model>(c, fmu_state) }
        }
        const _: $crate::fmi::types::sys::fmi2SetFMUstateTYPE = Some(fmi2SetFMUstate);
        #[doc = "FMI 2.0 `fmi2FreeFMUstate` (forwards to `hybeam::fmi::entry::free_fmu_state`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeFMUstate(c: $crate::fmi::types::fmi2Component, fmu_state: *mut $crate::fmi::types::fmi2FMUstate) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::free_fmu_state::<$model>(c, fmu_state) }
        }
        const _: $crate::fmi::types::sys::fmi2FreeFMUstateTYPE = Some(fmi2FreeFMUstate);
        #[doc = "FMI 2.0 `fmi2SerializedFMUstateSize` (forwards to `hybeam::fmi::entry::serialized_fmu_state_size`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: $crate::fmi::types::fmi2Component, fmu_state: $crate::fmi::types::fmi2FMUstate, size: *mut usize) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::serialized_fmu_state_size::<$model>(c, fmu_state, size) }
        }
        const _: $crate::fmi::types::sys::fmi2SerializedFMUstateSizeTYPE = Some(fmi2SerializedFMUstateSize);
        #[doc = "FMI 2.0 `fmi2SerializeFMUstate` (forwards to `hybeam::fmi::entry::serialize_fmu_state`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializeFMUstate(c: $crate::fmi::types::fmi2Component, fmu_state: $crate::fmi::types::fmi2FMUstate, serialized_state: *mut $crate::fmi::types::fmi2Byte, size: usize) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::serialize_fmu_state::<$model>(c, fmu_state, serialized_state, size) }
        }
        const _: $crate::fmi::types::sys::fmi2SerializeFMUstateTYPE = Some(fmi2SerializeFMUstate);
        #[doc = "FMI 2.0 `fmi2DeSerializeFMUstate` (forwards to `hybeam::fmi::entry::deserialize_fmu_state`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2DeSerializeFMUstate(c: $crate::fmi::types::fmi2Component, serialized_state: *const $crate::fmi::types::fmi2Byte, size: usize, fmu_state: *mut $crate::fmi::types::fmi2FMUstate) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::deserialize_fmu_state::<$model>(c, serialized_state, size, fmu_state) }
        }
        const _: $crate::fmi::types::sys::fmi2DeSerializeFMUstateTYPE = Some(fmi2DeSerializeFMUstate);
        #[doc = "FMI 2.0 `fmi2GetDirectionalDerivative` (forwards to `hybeam::fmi::entry::get_directional_derivative`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetDirectionalDerivative(c: $crate::fmi::types::fmi2Component, v_unknown_ref: *const $crate::fmi::types::fmi2ValueReference, n_unknown: usize, v_known_ref: *const $crate::fmi::types::fmi2ValueReference, n_known: usize, dv_known: *const $crate::fmi::types::fmi2Real, dv_unknown: *mut $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_directional_derivative::<$model>(c, v_unknown_ref, n_unknown, v_known_ref, n_known, dv_known, dv_unknown) }
        }
        const _: $crate::fmi::types::sys::fmi2GetDirectionalDerivativeTYPE = Some(fmi2GetDirectionalDerivative);
        #[doc = "FMI 2.0 `fmi2SetRealInputDerivatives` (forwards to `hybeam::fmi::entry::set_real_input_derivatives`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetRealInputDerivatives(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, order: *const $crate::fmi::types::fmi2Integer, value: *const $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::set_real_input_derivatives::<$model>(c, vr, nvr, order, value) }
        }
        const _: $crate::fmi::types::sys::fmi2SetRealInputDerivativesTYPE = Some(fmi2SetRealInputDerivatives);
        #[doc = "FMI 2.0 `fmi2GetRealOutputDerivatives` (forwards to `hybeam::fmi::entry::get_real_output_derivatives`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(c: $crate::fmi::types::fmi2Component, vr: *const $crate::fmi::types::fmi2ValueReference, nvr: usize, order: *const $crate::fmi::types::fmi2Integer, value: *mut $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_real_output_derivatives::<$model>(c, vr, nvr, order, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetRealOutputDerivativesTYPE = Some(fmi2GetRealOutputDerivatives);
        #[doc = "FMI 2.0 `fmi2DoStep` (forwards to `hybeam::fmi::entry::do_step`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2DoStep(c: $crate::fmi::types::fmi2Component, current_communication_point: $crate::fmi::types::fmi2Real, communication_step_size: $crate::fmi::types::fmi2Real, no_set_fmu_state_prior_to_current_point: $crate::fmi::types::fmi2Boolean) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::do_step::<$model>(c, current_communication_point, communication_step_size, no_set_fmu_state_prior_to_current_point) }
        }
        const _: $crate::fmi::types::sys::fmi2DoStepTYPE = Some(fmi2DoStep);
        #[doc = "FMI 2.0 `fmi2CancelStep` (forwards to `hybeam::fmi::entry::cancel_step`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2CancelStep(c: $crate::fmi::types::fmi2Component) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::cancel_step::<$model>(c) }
        }
        const _: $crate::fmi::types::sys::fmi2CancelStepTYPE = Some(fmi2CancelStep);
        #[doc = "FMI 2.0 `fmi2GetStatus` (forwards to `hybeam::fmi::entry::get_status`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetStatus(c: $crate::fmi::types::fmi2Component, s: $crate::fmi::types::fmi2StatusKind, value: *mut $crate::fmi::types::fmi2Status) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_status::<$model>(c, s, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetStatusTYPE = Some(fmi2GetStatus);
        #[doc = "FMI 2.0 `fmi2GetRealStatus` (forwards to `hybeam::fmi::entry::get_real_status`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetRealStatus(c: $crate::fmi::types::fmi2Component, s: $crate::fmi::types::fmi2StatusKind, value: *mut $crate::fmi::types::fmi2Real) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_real_status::<$model>(c, s, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetRealStatusTYPE = Some(fmi2GetRealStatus);
        #[doc = "FMI 2.0 `fmi2GetIntegerStatus` (forwards to `hybeam::fmi::entry::get_integer_status`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetIntegerStatus(c: $crate::fmi::types::fmi2Component, s: $crate::fmi::types::fmi2StatusKind, value: *mut $crate::fmi::types::fmi2Integer) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_integer_status::<$model>(c, s, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetIntegerStatusTYPE = Some(fmi2GetIntegerStatus);
        #[doc = "FMI 2.0 `fmi2GetBooleanStatus` (forwards to `hybeam::fmi::entry::get_boolean_status`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetBooleanStatus(c: $crate::fmi::types::fmi2Component, s: $crate::fmi::types::fmi2StatusKind, value: *mut $crate::fmi::types::fmi2Boolean) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_boolean_status::<$model>(c, s, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetBooleanStatusTYPE = Some(fmi2GetBooleanStatus);
        #[doc = "FMI 2.0 `fmi2GetStringStatus` (forwards to `hybeam::fmi::entry::get_string_status`)."]
        #[doc = ""]
        #[doc = "# Safety"]
        #[doc = "FMI 2.0 calling contract."]
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetStringStatus(c: $crate::fmi::types::fmi2Component, s: $crate::fmi::types::fmi2StatusKind, value: *mut $crate::fmi::types::fmi2String) -> $crate::fmi::types::fmi2Status {
            unsafe { $crate::fmi::entry::get_string_status::<$model>(c, s, value) }
        }
        const _: $crate::fmi::types::sys::fmi2GetStringStatusTYPE = Some(fmi2GetStringStatus);
    };
}
