//! Generic implementations of the 34 FMI 2.0 co-simulation functions, one per C function,
//! generic over the [`CoSimModel`]. [`export_fmi2!`](crate::export_fmi2) turns them into the
//! `extern "C"` symbols of the shared library.
//!
//! Every function that takes an instance:
//! 1. checks the `fmi2Component` (NULL or not a live instance → fmi2Error, nothing to log to);
//! 2. runs the rest inside `catch_unwind`: a panic sets the state to `fatal`, is logged, and
//!    returns fmi2Fatal (or NULL / nothing); no panic unwinds into the host;
//! 3. checks the state against the one table [`Function::allowed`](super::state::Function::allowed);
//! 4. checks NULL arrays with a non-zero length, sizes and values, naming the argument and value
//!    in the logged message.
//!
//! Argument and call-sequence errors return fmi2Error and leave the state unchanged, as in
//! Reference-FMUs; a failure of the model itself (initialize, reset) moves the instance to
//! state `error`.

use std::any::Any;
use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr;
use std::slice;

use super::fmu_state::{self, FmuState};
use super::guid;
use super::instance::{self, Instance};
use super::log::LogCategory;
use super::model::{Causality, CoSimModel, StepError, Variability, Variable};
use super::resources;
use super::state::{Function as F, ModelState};
use super::types::*;

/// Relative tolerance of the communication-point and stop-time checks of fmi2DoStep.
///
/// `currentCommunicationPoint` is accepted if
/// `|t − time| ≤ min(TIME_RTOL · max(|t|, |time|, h), h/2)`.
/// Hosts compute `t0 + n·h` or a running sum, which differ from the FMU's `t + h` by a few ulps
/// of `|t|` per step; 1e-9 covers ~10⁶ accumulated roundings, and the h/2 cap keeps consecutive
/// communication points apart even at large times. After a successful step the FMU's time is
/// set to the host's `t + h`, so no drift builds up.
pub const TIME_RTOL: f64 = 1e-9;

/// Returns early from a closure returning [`Status`] with the error status of a `Result`.
macro_rules! tri {
    ($e:expr) => {
        match $e {
            Ok(v) => v,
            Err(status) => return status,
        }
    };
}

fn panic_message(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "non-string panic payload".to_owned()
    }
}

/// Drops a panic payload without letting a panicking destructor escape.
fn drop_payload(payload: Box<dyn Any + Send>) {
    if let Err(again) = catch_unwind(AssertUnwindSafe(move || drop(payload))) {
        std::mem::forget(again);
    }
}

/// The instance behind `c`, if `c` is a live instance of this FMU.
unsafe fn live_instance<M>(c: fmi2Component) -> Option<*mut Instance<M>> {
    if c.is_null() {
        return None;
    }
    let p = c as *mut Instance<M>;
    // SAFETY: the host passes a pointer returned by fmi2Instantiate; the marker is a best-effort
    // check against freed or foreign pointers.
    (unsafe { (*p).live } == instance::LIVE).then_some(p)
}

/// Runs `body` on the instance `c` after the pointer and state checks, catching panics.
unsafe fn with_instance<M: CoSimModel>(
    c: fmi2Component,
    f: F,
    body: impl FnOnce(&mut Instance<M>) -> Status,
) -> fmi2Status {
    // SAFETY: forwarded contract of the entry point.
    let Some(p) = (unsafe { live_instance::<M>(c) }) else {
        return Status::Error.to_c();
    };
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: live instance; the standard forbids concurrent calls on one instance.
        let inst = unsafe { &mut *p };
        if !inst.layer.state.is_in(f.allowed()) {
            return inst.error(
                f,
                format!(
                    "illegal call sequence: allowed in {}, but the instance is in {}",
                    f.allowed(),
                    inst.layer.state
                ),
            );
        }
        body(inst)
    }));
    match result {
        Ok(status) => status.to_c(),
        Err(payload) => {
            let message = panic_message(&*payload);
            drop_payload(payload);
            let logged = catch_unwind(AssertUnwindSafe(|| {
                // SAFETY: the borrow inside the closure above ended with the unwind.
                let inst = unsafe { &mut *p };
                inst.layer.state = ModelState::FATAL;
                inst.log(
                    Status::Fatal,
                    &format!(
                        "{}: internal error (panic: {message}); the instance can only be freed",
                        f.name()
                    ),
                );
            }));
            if let Err(payload) = logged {
                drop_payload(payload);
            }
            Status::Fatal.to_c()
        }
    }
}

/// `p[..n]`, or an error if `p` is NULL while `n > 0`.
unsafe fn arg_in<'a, T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    name: &str,
    count_name: &str,
    p: *const T,
    n: usize,
) -> Result<&'a [T], Status> {
    if n == 0 {
        Ok(&[])
    } else if p.is_null() {
        Err(inst.error(f, format!("{name} is NULL but {count_name} = {n}")))
    } else {
        // SAFETY: the host guarantees `n` readable elements at `p`.
        Ok(unsafe { slice::from_raw_parts(p, n) })
    }
}

/// `p[..n]` for writing, or an error if `p` is NULL while `n > 0`.
unsafe fn arg_out<'a, T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    name: &str,
    count_name: &str,
    p: *mut T,
    n: usize,
) -> Result<&'a mut [T], Status> {
    if n == 0 {
        Ok(&mut [])
    } else if p.is_null() {
        Err(inst.error(f, format!("{name} is NULL but {count_name} = {n}")))
    } else {
        // SAFETY: the host guarantees `n` writable elements at `p`.
        Ok(unsafe { slice::from_raw_parts_mut(p, n) })
    }
}

/// A non-NULL output pointer.
fn out_ptr<T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    name: &str,
    p: *mut T,
) -> Result<*mut T, Status> {
    if p.is_null() {
        Err(inst.error(f, format!("{name} is NULL")))
    } else {
        Ok(p)
    }
}

/// The FMU state behind `s`, if it is a live state made by this FMU.
unsafe fn fmu_state_ref<'a, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    s: fmi2FMUstate,
) -> Result<&'a mut FmuState, Status> {
    if s.is_null() {
        return Err(inst.error(f, "FMUstate is NULL"));
    }
    let p = s as *mut FmuState;
    // SAFETY: the host passes a pointer returned by fmi2GetFMUstate / fmi2DeSerializeFMUstate.
    if unsafe { (*p).live } != fmu_state::LIVE {
        return Err(inst.error(
            f,
            format!("FMUstate {s:p} is not a live FMU state of this FMU (already freed?)"),
        ));
    }
    // SAFETY: checked above.
    Ok(unsafe { &mut *p })
}

fn c_str_arg<'a>(p: *const c_char, name: &str) -> Result<&'a str, String> {
    if p.is_null() {
        return Err(format!("{name} is NULL"));
    }
    // SAFETY: the host passes NUL-terminated strings.
    unsafe { CStr::from_ptr(p) }
        .to_str()
        .map_err(|_| format!("{name} is not valid UTF-8"))
}

/// Why `var` cannot be set in `state`, if it cannot.
fn check_settable(var: &Variable, state: ModelState) -> Result<(), String> {
    match (var.causality, var.variability) {
        (Causality::Output, _) => Err(format!(
            "{} (value reference {}) is an output and cannot be set",
            var.name, var.vr
        )),
        (Causality::Input, _) | (Causality::Parameter, Variability::Tunable) => Ok(()),
        (Causality::Parameter, _) => {
            if state.is_in(ModelState::INSTANTIATED.or(ModelState::INIT_MODE)) {
                Ok(())
            } else {
                Err(format!(
                    "{} (value reference {}) is a fixed parameter: it can only be set before \
                     fmi2ExitInitializationMode (the instance is in {state})",
                    var.name, var.vr
                ))
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Common functions
// ---------------------------------------------------------------------------------------------

/// fmi2GetTypesPlatform: `"default"`.
pub fn get_types_platform() -> *const c_char {
    TYPES_PLATFORM.as_ptr()
}

/// fmi2GetVersion: `"2.0"`.
pub fn get_version() -> *const c_char {
    VERSION.as_ptr()
}

/// fmi2SetDebugLogging.
///
/// # Safety
/// FMI 2.0 calling contract: `c` from fmi2Instantiate, `categories` with `n_categories` strings.
pub unsafe fn set_debug_logging<M: CoSimModel>(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    n_categories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    let f = F::SetDebugLogging;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let on = logging_on != FMI2_FALSE;
            let names = tri!(arg_in(
                inst,
                f,
                "categories[]",
                "nCategories",
                categories,
                n_categories
            ));
            if names.is_empty() {
                inst.log_filter.set_all(on);
                return Status::Ok;
            }
            let mut filter = inst.log_filter;
            for (i, &p) in names.iter().enumerate() {
                let name = match c_str_arg(p, &format!("categories[{i}]")) {
                    Ok(s) => s,
                    Err(e) => return inst.error(f, e),
                };
                match LogCategory::from_name(name) {
                    Some(cat) => filter.set(cat, on),
                    None => {
                        let known: Vec<&str> = LogCategory::ALL.iter().map(|c| c.name()).collect();
                        return inst.error(
                            f,
                            format!(
                                "categories[{i}] = \"{name}\" is not a log category of this FMU \
                                 (known: {}); nothing was changed",
                                known.join(", ")
                            ),
                        );
                    }
                }
            }
            inst.log_filter = filter;
            Status::Ok
        })
    }
}

/// fmi2Instantiate: checks the type, reads `resources/scene.toml`, checks the GUID, builds the
/// model. Returns NULL (with a logged reason if a logger was given) on any failure.
///
/// # Safety
/// FMI 2.0 calling contract: NUL-terminated strings or NULL, `functions` NULL or valid.
pub unsafe fn instantiate<M: CoSimModel>(
    instance_name: fmi2String,
    fmu_type: fmi2Type,
    fmu_guid: fmi2String,
    fmu_resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    if functions.is_null() {
        return ptr::null_mut();
    }
    // SAFETY: non-NULL, and the standard requires it valid for the call; copied by value because
    // the host may free its struct after this call.
    let callbacks: fmi2CallbackFunctions = unsafe { *functions };
    let result = catch_unwind(AssertUnwindSafe(|| -> Result<*mut Instance<M>, String> {
        let name = c_str_arg(instance_name, "instanceName")?;
        if fmu_type != FMI2_CO_SIMULATION {
            let kind = if fmu_type == FMI2_MODEL_EXCHANGE {
                "fmi2ModelExchange"
            } else {
                "unknown"
            };
            return Err(format!(
                "fmuType = {fmu_type} ({kind}) is not supported: this FMU implements \
                 fmi2CoSimulation only"
            ));
        }
        let given_guid = c_str_arg(fmu_guid, "fmuGUID")?;
        if fmu_resource_location.is_null() {
            return Err(
                "fmuResourceLocation is NULL: this FMU needs its resources/ folder \
                        (scene.toml)"
                    .into(),
            );
        }
        let location = c_str_arg(fmu_resource_location, "fmuResourceLocation")?;
        let scene = resources::read_scene(location)?;
        let expected = guid::guid(&scene);
        if !guid::same_guid(given_guid, &expected) {
            return Err(format!(
                "fmuGUID = {given_guid} does not match this FMU's GUID {expected} (from \
                 resources/{} and hybeam {}): modelDescription.xml, binary and resources come \
                 from different builds",
                resources::SCENE_FILE,
                guid::CRATE_VERSION
            ));
        }
        let text = String::from_utf8(scene)
            .map_err(|_| format!("resources/{} is not valid UTF-8", resources::SCENE_FILE))?;
        let model = M::from_scene(&text)
            .map_err(|e| format!("invalid resources/{}: {e}", resources::SCENE_FILE))?;
        let inst = Instance::new(
            CString::new(name).unwrap_or_default(),
            callbacks,
            logging_on != FMI2_FALSE,
            expected,
            model,
        )?;
        inst.trace(|| format!("fmi2Instantiate: instance \"{name}\" of GUID {}", inst.guid));
        Ok(Box::into_raw(Box::new(inst)))
    }));
    let message = match result {
        Ok(Ok(p)) => return p as fmi2Component,
        Ok(Err(message)) => (Status::Error, format!("fmi2Instantiate: {message}")),
        Err(payload) => {
            let m = format!(
                "fmi2Instantiate: internal error (panic: {})",
                panic_message(&*payload)
            );
            drop_payload(payload);
            (Status::Fatal, m)
        }
    };
    let logged = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: callbacks from the host.
        unsafe {
            Instance::<M>::log_without_instance(&callbacks, instance_name, message.0, &message.1)
        }
    }));
    if let Err(payload) = logged {
        drop_payload(payload);
    }
    ptr::null_mut()
}

/// fmi2FreeInstance: frees the instance (in any state; NULL or a non-instance is ignored).
///
/// # Safety
/// `c` from fmi2Instantiate, not used after this call.
pub unsafe fn free_instance<M: CoSimModel>(c: fmi2Component) {
    // SAFETY: forwarded contract.
    let Some(p) = (unsafe { live_instance::<M>(c) }) else {
        return;
    };
    let freed = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: a live instance allocated by `instantiate`; the marker is cleared first.
        unsafe {
            (*p).trace(|| "fmi2FreeInstance".to_owned());
            (*p).live = 0;
            drop(Box::from_raw(p));
        }
    }));
    if let Err(payload) = freed {
        drop_payload(payload);
    }
}

/// fmi2SetupExperiment: stores tolerance, start and stop time.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn setup_experiment<M: CoSimModel>(
    c: fmi2Component,
    tolerance_defined: fmi2Boolean,
    tolerance: fmi2Real,
    start_time: fmi2Real,
    stop_time_defined: fmi2Boolean,
    stop_time: fmi2Real,
) -> fmi2Status {
    let f = F::SetupExperiment;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let tolerance = (tolerance_defined != FMI2_FALSE).then_some(tolerance);
            if let Some(t) = tolerance.filter(|t| !(t.is_finite() && *t > 0.0)) {
                return inst.error(f, format!("tolerance = {t} must be finite and > 0"));
            }
            if !start_time.is_finite() {
                return inst.error(f, format!("startTime = {start_time} must be finite"));
            }
            let stop = (stop_time_defined != FMI2_FALSE).then_some(stop_time);
            if let Some(s) = stop.filter(|s| !(s.is_finite() && *s >= start_time)) {
                return inst.error(
                    f,
                    format!("stopTime = {s} must be finite and >= startTime = {start_time}"),
                );
            }
            inst.layer.tolerance = tolerance;
            inst.layer.start_time = start_time;
            inst.layer.stop_time = stop;
            inst.layer.time = start_time;
            inst.layer.last_successful_time = start_time;
            inst.trace(|| {
                let opt = |x: Option<f64>| x.map_or("undefined".to_owned(), |x| x.to_string());
                format!(
                    "fmi2SetupExperiment: tolerance {}, startTime {start_time}, stopTime {}",
                    opt(tolerance),
                    opt(stop)
                )
            });
            Status::Ok
        })
    }
}

/// fmi2EnterInitializationMode.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn enter_initialization_mode<M: CoSimModel>(c: fmi2Component) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, F::EnterInitializationMode, |inst| {
            inst.layer.state = ModelState::INIT_MODE;
            inst.trace(|| "fmi2EnterInitializationMode".to_owned());
            Status::Ok
        })
    }
}

/// fmi2ExitInitializationMode: `model.initialize(start_time)`, then state `stepComplete`.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn exit_initialization_mode<M: CoSimModel>(c: fmi2Component) -> fmi2Status {
    let f = F::ExitInitializationMode;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            match inst.model.initialize(inst.layer.start_time) {
                Ok(()) => {
                    inst.layer.state = ModelState::STEP_COMPLETE;
                    inst.layer.time = inst.layer.start_time;
                    inst.layer.last_successful_time = inst.layer.start_time;
                    inst.layer.terminated = false;
                    inst.trace(|| {
                        format!("fmi2ExitInitializationMode: t = {}", inst.layer.start_time)
                    });
                    Status::Ok
                }
                Err(e) => inst.model_error(f, format!("model initialization failed: {e}")),
            }
        })
    }
}

/// fmi2Terminate: state `terminated` (the model keeps its values for fmi2GetReal).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn terminate<M: CoSimModel>(c: fmi2Component) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, F::Terminate, |inst| {
            inst.layer.state = ModelState::TERMINATED;
            inst.trace(|| format!("fmi2Terminate at t = {}", inst.layer.time));
            Status::Ok
        })
    }
}

/// fmi2Reset: `model.reset()`, then state `instantiated` with the experiment cleared.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn reset<M: CoSimModel>(c: fmi2Component) -> fmi2Status {
    let f = F::Reset;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| match inst.model.reset() {
            Ok(()) => {
                inst.reset_layer();
                inst.trace(|| "fmi2Reset".to_owned());
                Status::Ok
            }
            Err(e) => inst.model_error(f, format!("model reset failed: {e}")),
        })
    }
}

/// fmi2GetReal.
///
/// # Safety
/// FMI 2.0 calling contract: `vr` and `value` hold `nvr` elements (or are NULL with `nvr = 0`).
pub unsafe fn get_real<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    let f = F::GetReal;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let vrs = tri!(arg_in(inst, f, "vr[]", "nvr", vr, nvr));
            let out = tri!(arg_out(inst, f, "value[]", "nvr", value, nvr));
            for (&r, slot) in vrs.iter().zip(out.iter_mut()) {
                if inst.variable(r).is_none() {
                    return inst.error(
                        f,
                        format!("value reference {r} is not a variable of this model"),
                    );
                }
                match inst.model.get_real(r) {
                    Ok(v) => *slot = v,
                    Err(e) => return inst.error(f, format!("value reference {r}: {e}")),
                }
            }
            Status::Ok
        })
    }
}

/// fmi2SetReal: all values are checked (variable exists, settable in this state, finite) before
/// any is set; if the model refuses one, those already set are restored. So on fmi2Error nothing
/// has changed.
///
/// # Safety
/// FMI 2.0 calling contract: `vr` and `value` hold `nvr` elements (or are NULL with `nvr = 0`).
pub unsafe fn set_real<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    let f = F::SetReal;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let vrs = tri!(arg_in(inst, f, "vr[]", "nvr", vr, nvr));
            let vals = tri!(arg_in(inst, f, "value[]", "nvr", value, nvr));
            for (&r, &v) in vrs.iter().zip(vals) {
                let Some(var) = inst.variable(r) else {
                    return inst.error(
                        f,
                        format!("value reference {r} is not a variable of this model"),
                    );
                };
                if let Err(e) = check_settable(var, inst.layer.state) {
                    return inst.error(f, e);
                }
                if !v.is_finite() {
                    return inst.error(
                        f,
                        format!(
                            "{} (value reference {r}) = {v} is not finite; nothing was set",
                            var.name
                        ),
                    );
                }
            }
            // Previous values, to undo if the model refuses one (no allocation for n <= 8).
            let mut small = [0.0; 8];
            let mut large = Vec::new();
            let old: &mut [f64] = if vrs.len() <= small.len() {
                &mut small[..vrs.len()]
            } else {
                large.resize(vrs.len(), 0.0);
                &mut large
            };
            for (&r, slot) in vrs.iter().zip(old.iter_mut()) {
                match inst.model.get_real(r) {
                    Ok(v) => *slot = v,
                    Err(e) => return inst.error(f, format!("value reference {r}: {e}")),
                }
            }
            for (i, (&r, &v)) in vrs.iter().zip(vals).enumerate() {
                if let Err(e) = inst.model.set_real(r, v) {
                    // Reverse order restores repeated value references correctly.
                    for (&r_done, &v_old) in vrs[..i].iter().zip(&old[..i]).rev() {
                        let _ = inst.model.set_real(r_done, v_old);
                    }
                    let name = inst.variable(r).map(|x| x.name.as_str()).unwrap_or("");
                    return inst.error(
                        f,
                        format!("{name} (value reference {r}) = {v} refused: {e}; nothing was set"),
                    );
                }
            }
            Status::Ok
        })
    }
}

/// Get/Set of a type this model does not have (all hybeam variables are Real): fmi2OK for
/// `nvr = 0`, otherwise fmi2Error naming the first value reference.
unsafe fn no_variables_of_type<M: CoSimModel>(
    c: fmi2Component,
    f: F,
    type_name: &str,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value_is_null: bool,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let vrs = tri!(arg_in(inst, f, "vr[]", "nvr", vr, nvr));
            if nvr > 0 && value_is_null {
                return inst.error(f, format!("value[] is NULL but nvr = {nvr}"));
            }
            match vrs.first() {
                None => Status::Ok,
                Some(r) => inst.error(
                    f,
                    format!(
                        "value reference {r} is not {type_name} variable of this model \
                         (it has only Real variables)"
                    ),
                ),
            }
        })
    }
}

/// fmi2GetInteger (the model has no Integer variables).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_integer<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe { no_variables_of_type::<M>(c, F::GetInteger, "an Integer", vr, nvr, value.is_null()) }
}

/// fmi2GetBoolean (the model has no Boolean variables).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_boolean<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe { no_variables_of_type::<M>(c, F::GetBoolean, "a Boolean", vr, nvr, value.is_null()) }
}

/// fmi2GetString (the model has no String variables).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_string<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe { no_variables_of_type::<M>(c, F::GetString, "a String", vr, nvr, value.is_null()) }
}

/// fmi2SetInteger (the model has no Integer variables).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn set_integer<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe { no_variables_of_type::<M>(c, F::SetInteger, "an Integer", vr, nvr, value.is_null()) }
}

/// fmi2SetBoolean (the model has no Boolean variables).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn set_boolean<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe { no_variables_of_type::<M>(c, F::SetBoolean, "a Boolean", vr, nvr, value.is_null()) }
}

/// fmi2SetString (the model has no String variables).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn set_string<M: CoSimModel>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    // SAFETY: forwarded contract.
    unsafe { no_variables_of_type::<M>(c, F::SetString, "a String", vr, nvr, value.is_null()) }
}

/// fmi2GetFMUstate: an owned copy (FMI layer state + `model.save_state()`). A non-NULL
/// `*fmu_state` is a state from an earlier call and is overwritten in place.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_fmu_state<M: CoSimModel>(
    c: fmi2Component,
    fmu_state: *mut fmi2FMUstate,
) -> fmi2Status {
    let f = F::GetFMUstate;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let out = tri!(out_ptr(inst, f, "FMUstate", fmu_state));
            let layer = inst.layer_state();
            let bytes = inst.model.save_state();
            if (*out).is_null() {
                *out = Box::into_raw(Box::new(FmuState::new(layer, bytes))) as fmi2FMUstate;
            } else {
                let s = tri!(fmu_state_ref(inst, f, *out));
                s.layer = layer;
                s.model = bytes;
            }
            inst.trace(|| format!("fmi2GetFMUstate at t = {}", inst.layer.time));
            Status::Ok
        })
    }
}

/// fmi2SetFMUstate: `model.load_state`, then the FMI layer state (time, state machine, flags).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn set_fmu_state<M: CoSimModel>(
    c: fmi2Component,
    fmu_state: fmi2FMUstate,
) -> fmi2Status {
    let f = F::SetFMUstate;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let s = tri!(fmu_state_ref(inst, f, fmu_state));
            if let Err(e) = inst.model.load_state(&s.model) {
                return inst.error(f, format!("the model refused the FMU state: {e}"));
            }
            inst.set_layer_state(&s.layer);
            inst.trace(|| format!("fmi2SetFMUstate: t = {}", inst.layer.time));
            Status::Ok
        })
    }
}

/// fmi2FreeFMUstate (a NULL `*fmu_state` is accepted and ignored).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn free_fmu_state<M: CoSimModel>(
    c: fmi2Component,
    fmu_state: *mut fmi2FMUstate,
) -> fmi2Status {
    let f = F::FreeFMUstate;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let out = tri!(out_ptr(inst, f, "FMUstate", fmu_state));
            if (*out).is_null() {
                return Status::Ok;
            }
            let s = tri!(fmu_state_ref(inst, f, *out));
            s.live = 0;
            drop(Box::from_raw(s as *mut FmuState));
            *out = ptr::null_mut();
            Status::Ok
        })
    }
}

/// fmi2SerializedFMUstateSize.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn serialized_fmu_state_size<M: CoSimModel>(
    c: fmi2Component,
    fmu_state: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    let f = F::SerializedFMUstateSize;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let size = tri!(out_ptr(inst, f, "size", size));
            let s = tri!(fmu_state_ref(inst, f, fmu_state));
            *size = s.serialized_len(&inst.guid);
            Status::Ok
        })
    }
}

/// fmi2SerializeFMUstate: `size` must be the value from fmi2SerializedFMUstateSize.
///
/// # Safety
/// FMI 2.0 calling contract: `serialized_state` holds `size` bytes.
pub unsafe fn serialize_fmu_state<M: CoSimModel>(
    c: fmi2Component,
    fmu_state: fmi2FMUstate,
    serialized_state: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    let f = F::SerializeFMUstate;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let s = tri!(fmu_state_ref(inst, f, fmu_state));
            let need = s.serialized_len(&inst.guid);
            if size != need {
                return inst.error(
                    f,
                    format!(
                        "size = {size}, but this FMU state serializes to {need} bytes \
                         (the value of fmi2SerializedFMUstateSize)"
                    ),
                );
            }
            let out = tri!(arg_out(
                inst,
                f,
                "serializedState[]",
                "size",
                serialized_state,
                size
            ));
            let bytes = s.serialize(&inst.guid);
            for (o, b) in out.iter_mut().zip(&bytes) {
                *o = *b as fmi2Byte;
            }
            Status::Ok
        })
    }
}

/// fmi2DeSerializeFMUstate: validates the bytes (magic, format version, GUID, checksum, FMI
/// state) and returns a new FMU state; the model bytes are checked by fmi2SetFMUstate. A new
/// state is always allocated: `*fmu_state` on input is ignored (never freed or reused).
///
/// # Safety
/// FMI 2.0 calling contract: `serialized_state` holds `size` bytes.
pub unsafe fn deserialize_fmu_state<M: CoSimModel>(
    c: fmi2Component,
    serialized_state: *const fmi2Byte,
    size: usize,
    fmu_state: *mut fmi2FMUstate,
) -> fmi2Status {
    let f = F::DeSerializeFMUstate;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let out = tri!(out_ptr(inst, f, "FMUstate", fmu_state));
            let bytes = tri!(arg_in(
                inst,
                f,
                "serializedState[]",
                "size",
                serialized_state as *const u8,
                size
            ));
            match FmuState::deserialize(bytes, &inst.guid) {
                Ok(s) => {
                    *out = Box::into_raw(Box::new(s)) as fmi2FMUstate;
                    Status::Ok
                }
                Err(e) => inst.error(f, format!("serializedState ({size} bytes) refused: {e}")),
            }
        })
    }
}

/// fmi2GetDirectionalDerivative: not provided (`providesDirectionalDerivative="false"`).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_directional_derivative<M: CoSimModel>(
    c: fmi2Component,
    _v_unknown_ref: *const fmi2ValueReference,
    _n_unknown: usize,
    _v_known_ref: *const fmi2ValueReference,
    _n_known: usize,
    _dv_known: *const fmi2Real,
    _dv_unknown: *mut fmi2Real,
) -> fmi2Status {
    let f = F::GetDirectionalDerivative;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            inst.error(
                f,
                "not provided by this FMU (providesDirectionalDerivative=\"false\")",
            )
        })
    }
}

// ---------------------------------------------------------------------------------------------
// Co-simulation functions
// ---------------------------------------------------------------------------------------------

/// fmi2SetRealInputDerivatives: not supported (`canInterpolateInputs="false"`).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn set_real_input_derivatives<M: CoSimModel>(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *const fmi2Real,
) -> fmi2Status {
    let f = F::SetRealInputDerivatives;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            inst.error(
                f,
                "not supported by this FMU (canInterpolateInputs=\"false\")",
            )
        })
    }
}

/// fmi2GetRealOutputDerivatives: not supported (`maxOutputDerivativeOrder="0"`).
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_real_output_derivatives<M: CoSimModel>(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    let f = F::GetRealOutputDerivatives;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            inst.error(
                f,
                "not supported by this FMU (maxOutputDerivativeOrder=\"0\")",
            )
        })
    }
}

/// fmi2DoStep: checks the step (`h` finite and > 0, `t` equal to the FMU time within
/// [`TIME_RTOL`], `t + h` finite, later than `t` in floating point, and not beyond stopTime),
/// then `model.do_step(t, h)`. Ok → fmi2OK and time = `t + h`. Err → fmi2Discard, state
/// `stepFailed`, fmi2LastSuccessfulTime = the time before the step (the model keeps its last
/// good state), fmi2Terminated = true only for [`StepError::Terminate`]; after a recoverable
/// [`StepError::Discard`] fmi2SetFMUstate resumes, e.g. to retry with a smaller step.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn do_step<M: CoSimModel>(
    c: fmi2Component,
    current_communication_point: fmi2Real,
    communication_step_size: fmi2Real,
    _no_set_fmu_state_prior_to_current_point: fmi2Boolean,
) -> fmi2Status {
    let f = F::DoStep;
    let (t, h) = (current_communication_point, communication_step_size);
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            if !(h.is_finite() && h > 0.0) {
                return inst.error(
                    f,
                    format!("communicationStepSize = {h} must be finite and > 0"),
                );
            }
            let tol = (TIME_RTOL * t.abs().max(inst.layer.time.abs()).max(h)).min(0.5 * h);
            if !t.is_finite() || (t - inst.layer.time).abs() > tol {
                return inst.error(
                    f,
                    format!(
                        "currentCommunicationPoint = {t} differs from the FMU time {} by {:e} \
                         (tolerance {tol:e}): each step must start where the last one ended",
                        inst.layer.time,
                        t - inst.layer.time
                    ),
                );
            }
            let end = t + h;
            if !(end.is_finite() && end > t) {
                let spacing = t.abs().next_up() - t.abs();
                return inst.error(
                    f,
                    format!(
                        "communicationStepSize = {h:e} does not advance time from \
                         currentCommunicationPoint = {t:e}: t + h = {end:e} in double precision \
                         (at |t| = {:e} s consecutive times are {spacing:e} s apart); use a \
                         larger step, or a start time nearer 0",
                        t.abs()
                    ),
                );
            }
            if let Some(stop) = inst.layer.stop_time {
                if end > stop + TIME_RTOL * stop.abs().max(h) {
                    return inst.error(
                        f,
                        format!(
                            "currentCommunicationPoint + communicationStepSize = {end} is beyond \
                             stopTime = {stop}"
                        ),
                    );
                }
            }
            inst.trace(|| format!("fmi2DoStep: t = {t}, h = {h}"));
            match inst.model.do_step(t, h) {
                Ok(()) => {
                    inst.layer.time = end;
                    inst.layer.last_successful_time = end;
                    inst.last_do_step_status = Status::Ok;
                    Status::Ok
                }
                Err(e) => {
                    let terminate = matches!(e, StepError::Terminate(_));
                    inst.layer.state = ModelState::STEP_FAILED;
                    inst.layer.terminated = terminate;
                    inst.layer.last_successful_time = inst.layer.time;
                    inst.last_do_step_status = Status::Discard;
                    let next = if terminate {
                        "fmi2Terminated = true: the model cannot continue"
                    } else {
                        "fmi2Terminated = false: fmi2SetFMUstate to a saved state continues, e.g. \
                         with a smaller step or other inputs"
                    };
                    inst.log(
                        Status::Discard,
                        &format!(
                            "fmi2DoStep: the step from t = {t} with h = {h} failed: {}; the model \
                             keeps its state at t = {} ({next})",
                            e.message(),
                            inst.layer.time
                        ),
                    );
                    Status::Discard
                }
            }
        })
    }
}

/// fmi2CancelStep: this FMU never runs asynchronous steps, so it is never in `stepInProgress`.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn cancel_step<M: CoSimModel>(c: fmi2Component) -> fmi2Status {
    let f = F::CancelStep;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            inst.error(f, "this FMU runs no asynchronous step to cancel")
        })
    }
}

/// The name of a status kind, or `None` if `s` is no fmi2StatusKind.
fn status_kind_name(s: fmi2StatusKind) -> Option<&'static str> {
    match s {
        FMI2_DO_STEP_STATUS => Some("fmi2DoStepStatus"),
        FMI2_PENDING_STATUS => Some("fmi2PendingStatus"),
        FMI2_LAST_SUCCESSFUL_TIME => Some("fmi2LastSuccessfulTime"),
        FMI2_TERMINATED => Some("fmi2Terminated"),
        _ => None,
    }
}

/// A status query for a kind this function does not provide: fmi2Discard (FMI 2.0 §4.2.3) for
/// a kind that exists, fmi2Error for a value that is no status kind.
fn unavailable_status<M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    s: fmi2StatusKind,
    available: &str,
) -> Status {
    match status_kind_name(s) {
        Some(name) => inst.discard(
            f,
            format!("status kind {s} ({name}) is not available ({available})"),
        ),
        None => inst.error(
            f,
            format!("s = {s} is not an fmi2StatusKind (0 to 3); {available}"),
        ),
    }
}

/// fmi2GetStatus: `fmi2DoStepStatus` gives the status of the last fmi2DoStep.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_status<M: CoSimModel>(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Status,
) -> fmi2Status {
    let f = F::GetStatus;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let out = tri!(out_ptr(inst, f, "value", value));
            if s == FMI2_DO_STEP_STATUS {
                *out = inst.last_do_step_status.to_c();
                Status::Ok
            } else {
                unavailable_status(inst, f, s, "only fmi2DoStepStatus = 0")
            }
        })
    }
}

/// fmi2GetRealStatus: `fmi2LastSuccessfulTime`.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_real_status<M: CoSimModel>(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    let f = F::GetRealStatus;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let out = tri!(out_ptr(inst, f, "value", value));
            if s == FMI2_LAST_SUCCESSFUL_TIME {
                *out = inst.layer.last_successful_time;
                Status::Ok
            } else {
                unavailable_status(inst, f, s, "only fmi2LastSuccessfulTime = 2")
            }
        })
    }
}

/// fmi2GetIntegerStatus: FMI 2.0 defines no Integer status.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_integer_status<M: CoSimModel>(
    c: fmi2Component,
    s: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    let f = F::GetIntegerStatus;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            unavailable_status(inst, f, s, "FMI 2.0 defines no Integer status")
        })
    }
}

/// fmi2GetBooleanStatus: `fmi2Terminated`.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_boolean_status<M: CoSimModel>(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    let f = F::GetBooleanStatus;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            let out = tri!(out_ptr(inst, f, "value", value));
            if s == FMI2_TERMINATED {
                *out = if inst.layer.terminated {
                    FMI2_TRUE
                } else {
                    FMI2_FALSE
                };
                Status::Ok
            } else {
                unavailable_status(inst, f, s, "only fmi2Terminated = 3")
            }
        })
    }
}

/// fmi2GetStringStatus: `fmi2PendingStatus` only exists while a step is pending, which never
/// happens here.
///
/// # Safety
/// FMI 2.0 calling contract.
pub unsafe fn get_string_status<M: CoSimModel>(
    c: fmi2Component,
    s: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    let f = F::GetStringStatus;
    // SAFETY: forwarded contract.
    unsafe {
        with_instance::<M>(c, f, |inst| {
            unavailable_status(inst, f, s, "this FMU never has a pending step")
        })
    }
}
