//! The only unsafe code of the FMI layer: C arguments to Rust references, slices and strings;
//! panic capture; the allocation of instances and FMU states; the call into the host's logger.
//! One `pub unsafe fn` per C function, named as it and generic over the model, turns the C
//! arguments into those of the safe method of [`Instance`] (`fmi2DoStep` → `do_step`);
//! [`export_fmi2!`](crate::export_fmi2) emits the `extern "C"` symbols that call them.
//!
//! # Pointers from the host
//! - **Instances and FMU states** (`fmi2Component`, `fmi2FMUstate`): FMI 2.0 lets a host pass
//!   only pointers this FMU returned and that were not freed since; anything else is a host bug
//!   and undefined behaviour in any FMU. NULL and misaligned pointers are refused (fmi2Error; a
//!   NULL instance has nothing to log to); any other pointer is trusted, and nothing is read
//!   through it to "check" it first. Such a check (a marker field) would read freed memory
//!   exactly in the case it is meant to catch, and a registry of live pointers would be
//!   process-wide mutable state shared by all instances; both are ruled out. The trade-off: a
//!   freed, foreign or twice-freed pointer is not detected, as in Reference-FMUs.
//! - **Arrays** `p` with `n` elements: NULL with `n > 0` is refused, naming the argument.
//! - **Strings**: NUL-terminated; NULL or invalid UTF-8 is refused, naming the argument.
//!
//! # Panics
//! Every function runs inside `catch_unwind`. A panic sets the state to `fatal` (only
//! fmi2FreeInstance is then accepted), is logged as fmi2Fatal and returns fmi2Fatal (NULL from
//! fmi2Instantiate); a panicking payload destructor is contained too. Nothing unwinds into the
//! host.
//!
//! # Safety
//! Every `pub unsafe fn` here has the FMI 2.0 calling contract of its C function: pointers as
//! the standard describes them (arrays with the given number of elements, NUL-terminated
//! strings, instances and FMU states returned by this FMU and not freed), and no concurrent
//! calls on one instance.

#![allow(non_snake_case)]

use std::any::Any;
use std::ffi::{c_char, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr;
use std::slice;

use crate::fmu_state::FmuState;
use crate::instance::Instance;
use crate::log::{c_string, LogCategory, Logger};
use crate::model::CoSimModel;
use crate::state::{Function as F, ModelState};
use crate::types::*;

/// The host's callbacks, valid for the life of an instance (FMI 2.0): what
/// [`Logger::Host`] calls.
#[derive(Debug, Clone, Copy)]
pub struct HostCallbacks(fmi2CallbackFunctions);

impl HostCallbacks {
    /// Wraps callbacks copied from the host.
    ///
    /// # Safety
    /// `callbacks.logger`, if set, must be an FMI 2.0 logger that may be called with
    /// `callbacks.componentEnvironment` for as long as the instance lives.
    pub unsafe fn new(callbacks: fmi2CallbackFunctions) -> Self {
        Self(callbacks)
    }
}

/// Sends one message to the host's logger, if there is one: format `"%s"`, the message as its
/// one argument.
pub(crate) fn call_logger(
    callbacks: &HostCallbacks,
    instance_name: &CStr,
    status: Status,
    category: LogCategory,
    text: &str,
) {
    let c = &callbacks.0;
    if let Some(logger) = c.logger {
        let message = c_string(text);
        // SAFETY: the logger and its environment are the host's (`HostCallbacks::new`); every
        // pointer is a NUL-terminated string that lives across the call, and "%s" consumes
        // exactly the one argument passed.
        unsafe {
            logger(
                c.componentEnvironment,
                instance_name.as_ptr(),
                status.to_c(),
                category.c_name().as_ptr(),
                c"%s".as_ptr(),
                message.as_ptr(),
            )
        };
    }
}

/// Returns early with the error status of a `Result<_, Status>`.
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

/// Runs `f`, containing a panic of `f` or of its payload.
fn contained(f: impl FnOnce()) {
    if let Err(payload) = catch_unwind(AssertUnwindSafe(f)) {
        drop_payload(payload);
    }
}

/// `c` as an instance pointer, if it is not NULL and aligned.
fn instance_ptr<M>(c: fmi2Component) -> Option<*mut Instance<M>> {
    let p = c as *mut Instance<M>;
    (!p.is_null() && p.is_aligned()).then_some(p)
}

/// Runs `body` on the instance `c` inside `catch_unwind`: fmi2Error for a NULL or misaligned
/// pointer, fmi2Fatal (state `fatal`) after a panic.
///
/// # Safety
/// `c` as in the FMI 2.0 calling contract.
unsafe fn with_instance<M: CoSimModel>(
    c: fmi2Component,
    f: F,
    body: impl FnOnce(&mut Instance<M>) -> Status,
) -> fmi2Status {
    let Some(p) = instance_ptr::<M>(c) else {
        return Status::Error.to_c();
    };
    // SAFETY: a live instance (calling contract); the standard forbids concurrent calls on one
    // instance, so this is the only reference.
    let result = catch_unwind(AssertUnwindSafe(|| body(unsafe { &mut *p })));
    match result {
        Ok(status) => status.to_c(),
        Err(payload) => {
            let message = panic_message(&*payload);
            drop_payload(payload);
            contained(|| {
                // SAFETY: the reference inside the closure above ended with the unwind.
                let inst = unsafe { &mut *p };
                inst.layer.state = ModelState::FATAL;
                inst.log(
                    Status::Fatal,
                    &format!(
                        "{}: internal error (panic: {message}); the instance can only be freed",
                        f.name()
                    ),
                );
            });
            Status::Fatal.to_c()
        }
    }
}

/// `p[..n]`, or a logged fmi2Error if `p` is NULL while `n > 0`.
///
/// # Safety
/// `p` points to `n` readable elements or is NULL.
unsafe fn slice_in<'a, T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    (name, count): (&str, &str),
    p: *const T,
    n: usize,
) -> Result<&'a [T], Status> {
    if n == 0 {
        Ok(&[])
    } else if p.is_null() {
        Err(inst.error(f, format!("{name} is NULL but {count} = {n}")))
    } else {
        check_len::<T, M>(inst, f, (name, count), n)?;
        // SAFETY: the caller's contract; `n` elements fit in isize::MAX bytes (checked).
        Ok(unsafe { slice::from_raw_parts(p, n) })
    }
}

/// Refuses a count whose array would exceed `isize::MAX` bytes (no Rust slice, and no array
/// in memory, can be that long): a logged fmi2Error naming the count.
fn check_len<T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    (name, count): (&str, &str),
    n: usize,
) -> Result<(), Status> {
    let size = std::mem::size_of::<T>().max(1);
    if n > isize::MAX as usize / size {
        return Err(inst.error(
            f,
            format!(
                "{count} = {n} cannot be the length of {name}: {n} elements of {size} bytes \
                 exceed the largest array of this platform ({} bytes)",
                isize::MAX
            ),
        ));
    }
    Ok(())
}

/// `p[..n]` for writing, or a logged fmi2Error if `p` is NULL while `n > 0`.
///
/// # Safety
/// `p` points to `n` writable elements or is NULL.
unsafe fn slice_out<'a, T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    (name, count): (&str, &str),
    p: *mut T,
    n: usize,
) -> Result<&'a mut [T], Status> {
    if n == 0 {
        Ok(&mut [])
    } else if p.is_null() {
        Err(inst.error(f, format!("{name} is NULL but {count} = {n}")))
    } else {
        check_len::<T, M>(inst, f, (name, count), n)?;
        // SAFETY: the caller's contract; `n` elements fit in isize::MAX bytes (checked).
        Ok(unsafe { slice::from_raw_parts_mut(p, n) })
    }
}

/// `*p` for writing, or a logged fmi2Error if `p` is NULL.
///
/// # Safety
/// `p` is NULL or points to a writable `T`.
unsafe fn out_ref<'a, T, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    name: &str,
    p: *mut T,
) -> Result<&'a mut T, Status> {
    if p.is_null() {
        Err(inst.error(f, format!("{name} is NULL")))
    } else {
        // SAFETY: the caller's contract.
        Ok(unsafe { &mut *p })
    }
}

/// The FMU state behind `s`, or a logged fmi2Error if it is NULL or misaligned.
///
/// # Safety
/// `s` is NULL or an FMU state of this FMU that was not freed.
unsafe fn fmu_state_ref<'a, M: CoSimModel>(
    inst: &Instance<M>,
    f: F,
    s: fmi2FMUstate,
) -> Result<&'a mut FmuState, Status> {
    let p = s as *mut FmuState;
    if p.is_null() || !p.is_aligned() {
        return Err(inst.error(f, format!("FMUstate {s:p} is not an FMU state of this FMU")));
    }
    // SAFETY: the caller's contract.
    Ok(unsafe { &mut *p })
}

/// A C string argument as `&str`.
///
/// # Safety
/// `p` is NULL or a NUL-terminated string.
unsafe fn c_str<'a>(p: *const c_char, name: &str) -> Result<&'a str, String> {
    if p.is_null() {
        return Err(format!("{name} is NULL"));
    }
    // SAFETY: the caller's contract.
    unsafe { CStr::from_ptr(p) }
        .to_str()
        .map_err(|_| format!("{name} is not valid UTF-8"))
}

const VR: (&str, &str) = ("vr[]", "nvr");
const VALUE: (&str, &str) = ("value[]", "nvr");

/// fmi2GetTypesPlatform: `"default"`.
pub fn fmi2GetTypesPlatform() -> *const c_char {
    TYPES_PLATFORM.as_ptr()
}

/// fmi2GetVersion: `"2.0"`.
pub fn fmi2GetVersion() -> *const c_char {
    VERSION.as_ptr()
}

/// fmi2Instantiate: a new instance, or NULL with a logged reason (if a logger was given).
///
/// # Safety
/// The FMI 2.0 calling contract (module doc); `functions` NULL or valid.
pub unsafe fn fmi2Instantiate<M: CoSimModel>(
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
    // SAFETY: non-NULL and valid for the call; copied because the host may free its struct,
    // while the functions it points to stay valid for the instance's life (FMI 2.0).
    let callbacks = unsafe { HostCallbacks::new(*functions) };
    let result = catch_unwind(AssertUnwindSafe(|| -> Result<Box<Instance<M>>, String> {
        // SAFETY: the calling contract.
        let (name, guid, location) = unsafe {
            let location = if fmu_resource_location.is_null() {
                None
            } else {
                Some(c_str(fmu_resource_location, "fmuResourceLocation")?)
            };
            (
                c_str(instance_name, "instanceName")?,
                c_str(fmu_guid, "fmuGUID")?,
                location,
            )
        };
        let logger = Logger::Host(callbacks);
        Instance::instantiate(
            name,
            fmu_type,
            guid,
            location,
            logger,
            logging_on != FMI2_FALSE,
        )
        .map(Box::new)
    }));
    let (status, message) = match result {
        Ok(Ok(inst)) => return Box::into_raw(inst) as fmi2Component,
        Ok(Err(message)) => (Status::Error, message),
        Err(payload) => {
            let m = format!("internal error (panic: {})", panic_message(&*payload));
            drop_payload(payload);
            (Status::Fatal, m)
        }
    };
    contained(|| {
        // SAFETY: the calling contract.
        let name = unsafe { c_str(instance_name, "") }.unwrap_or("");
        let text = format!("fmi2Instantiate: {message}");
        let category = LogCategory::for_status(status);
        call_logger(&callbacks, &c_string(name), status, category, &text);
    });
    ptr::null_mut()
}

/// fmi2FreeInstance: frees the instance (in any state; NULL or misaligned is ignored).
///
/// # Safety
/// The FMI 2.0 calling contract (module doc); `c` is not used after this call.
pub unsafe fn fmi2FreeInstance<M: CoSimModel>(c: fmi2Component) {
    if let Some(p) = instance_ptr::<M>(c) {
        // SAFETY: allocated by fmi2Instantiate with Box::into_raw, freed once (contract).
        contained(|| unsafe { Box::from_raw(p) }.free_instance());
    }
}

/// The guard functions of the 32 C functions that take an instance: each runs its body on the
/// instance `$i` (with `$f` its [`Function`](F)) inside [`with_instance`], after turning the
/// C arguments into Rust ones.
macro_rules! guarded {
    ($(
        $(#[$doc:meta])*
        $name:ident $variant:ident ($($p:ident: $t:ty),*) |$i:ident, $f:ident| $body:expr;
    )*) => {$(
        $(#[$doc])*
        ///
        /// # Safety
        /// The FMI 2.0 calling contract (module doc).
        pub unsafe fn $name<M: CoSimModel>(c: fmi2Component, $($p: $t),*) -> fmi2Status {
            let $f = F::$variant;
            // SAFETY: the calling contract, for `c` and for every pointer the body reads.
            unsafe { with_instance::<M>(c, $f, |$i| $body) }
        }
    )*};
}

/// fmi2Get{Real,Integer,Boolean,String}, fmi2Set…: `vr[..nvr]` and `value[..nvr]` as slices.
macro_rules! values {
    ($($name:ident $variant:ident $method:ident $slice:ident ($ptr:ty);)*) => {
        guarded! {$(
            #[doc = concat!("`", stringify!($name), "`: `vr[..nvr]`, `value[..nvr]`.")]
            $name $variant (vr: *const fmi2ValueReference, nvr: usize, value: $ptr) |i, f| {
                let vrs = tri!(slice_in(i, f, VR, vr, nvr));
                i.$method(vrs, tri!($slice(i, f, VALUE, value, nvr)))
            };
        )*}
    };
}

values! {
    fmi2GetReal GetReal get_real_prepared slice_out (*mut fmi2Real);
    fmi2GetInteger GetInteger get_integer slice_out (*mut fmi2Integer);
    fmi2GetBoolean GetBoolean get_boolean slice_out (*mut fmi2Boolean);
    fmi2GetString GetString get_string slice_out (*mut fmi2String);
    fmi2SetReal SetReal set_real slice_in (*const fmi2Real);
    fmi2SetInteger SetInteger set_integer slice_in (*const fmi2Integer);
    fmi2SetBoolean SetBoolean set_boolean slice_in (*const fmi2Boolean);
}

guarded! {
    /// fmi2SetString: `vr[..nvr]`, `value[..nvr]`, each value a NUL-terminated UTF-8 string
    /// (NULL or invalid UTF-8 is refused, naming `value[k]`), copied by the model.
    fmi2SetString SetString
    (vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2String) |i, f| {
        let vrs = tri!(slice_in(i, f, VR, vr, nvr));
        let ptrs = tri!(slice_in(i, f, VALUE, value, nvr));
        // grown per element read, never sized by a count up front
        let mut values = smallvec::SmallVec::<[&str; 8]>::new();
        for (k, &p) in ptrs.iter().enumerate() {
            values.push(tri!(c_str(p, &format!("value[{k}]")).map_err(|e| i.error(f, e))));
        }
        i.set_string(vrs, &values)
    };
}

guarded! {
    /// fmi2SetDebugLogging: `categories[..n_categories]`.
    fmi2SetDebugLogging SetDebugLogging
    (logging_on: fmi2Boolean, n_categories: usize, categories: *const fmi2String) |i, f| {
        let names = ("categories[]", "nCategories");
        let ptrs = tri!(slice_in(i, f, names, categories, n_categories));
        let mut names = Vec::new();
        for (k, &p) in ptrs.iter().enumerate() {
            names.push(tri!(c_str(p, &format!("categories[{k}]")).map_err(|e| i.error(f, e))));
        }
        i.set_debug_logging(logging_on != FMI2_FALSE, &names)
    };
    /// fmi2SetupExperiment.
    fmi2SetupExperiment SetupExperiment
    (tolerance_defined: fmi2Boolean, tolerance: fmi2Real, start_time: fmi2Real,
     stop_time_defined: fmi2Boolean, stop_time: fmi2Real) |i, _f| {
        let tolerance = (tolerance_defined != FMI2_FALSE).then_some(tolerance);
        let stop = (stop_time_defined != FMI2_FALSE).then_some(stop_time);
        i.setup_experiment(tolerance, start_time, stop)
    };
    /// fmi2EnterInitializationMode.
    fmi2EnterInitializationMode EnterInitializationMode () |i, _f| i.enter_initialization_mode();
    /// fmi2ExitInitializationMode.
    fmi2ExitInitializationMode ExitInitializationMode () |i, _f| i.exit_initialization_mode();
    /// fmi2Terminate.
    fmi2Terminate Terminate () |i, _f| i.terminate();
    /// fmi2Reset.
    fmi2Reset Reset () |i, _f| i.reset();
    /// fmi2GetFMUstate: a new FMU state, or, if `*fmu_state` is not NULL, that earlier state
    /// overwritten in place.
    fmi2GetFMUstate GetFMUstate (fmu_state: *mut fmi2FMUstate) |i, f| {
        let out = tri!(out_ref(i, f, "FMUstate", fmu_state));
        let state = tri!(i.get_fmu_state());
        if out.is_null() {
            *out = Box::into_raw(Box::new(state)) as fmi2FMUstate;
        } else {
            *tri!(fmu_state_ref(i, f, *out)) = state;
        }
        Status::Ok
    };
    /// fmi2SetFMUstate.
    fmi2SetFMUstate SetFMUstate (fmu_state: fmi2FMUstate)
    |i, f| i.set_fmu_state(tri!(fmu_state_ref(i, f, fmu_state)));
    /// fmi2FreeFMUstate: frees `*fmu_state` and sets it to NULL (NULL is accepted).
    fmi2FreeFMUstate FreeFMUstate (fmu_state: *mut fmi2FMUstate) |i, f| {
        let out = tri!(out_ref(i, f, "FMUstate", fmu_state));
        let mut owned = if out.is_null() {
            None
        } else {
            let p: *mut FmuState = tri!(fmu_state_ref(i, f, *out));
            // SAFETY: allocated by fmi2GetFMUstate or fmi2DeSerializeFMUstate (Box::into_raw).
            Some(Box::from_raw(p))
        };
        let status = i.free_fmu_state(&mut owned);
        *out = match owned {
            // not freed (illegal call): the state stays the host's
            Some(kept) => Box::into_raw(kept) as fmi2FMUstate,
            None => ptr::null_mut(),
        };
        status
    };
    /// fmi2SerializedFMUstateSize.
    fmi2SerializedFMUstateSize SerializedFMUstateSize (fmu_state: fmi2FMUstate, size: *mut usize)
    |i, f| {
        let size = tri!(out_ref(i, f, "size", size));
        *size = tri!(i.serialized_fmu_state_size(tri!(fmu_state_ref(i, f, fmu_state))));
        Status::Ok
    };
    /// fmi2SerializeFMUstate: `serialized_state[..size]`.
    fmi2SerializeFMUstate SerializeFMUstate
    (fmu_state: fmi2FMUstate, serialized_state: *mut fmi2Byte, size: usize) |i, f| {
        let s = tri!(fmu_state_ref(i, f, fmu_state));
        let names = ("serializedState[]", "size");
        i.serialize_fmu_state(s, tri!(slice_out(i, f, names, serialized_state, size)))
    };
    /// fmi2DeSerializeFMUstate: `serialized_state[..size]`; always a new FMU state
    /// (`*fmu_state` on input is ignored, never freed or reused).
    fmi2DeSerializeFMUstate DeSerializeFMUstate
    (serialized_state: *const fmi2Byte, size: usize, fmu_state: *mut fmi2FMUstate) |i, f| {
        let out = tri!(out_ref(i, f, "FMUstate", fmu_state));
        let names = ("serializedState[]", "size");
        let bytes = tri!(slice_in(i, f, names, serialized_state as *const u8, size));
        *out = Box::into_raw(Box::new(tri!(i.deserialize_fmu_state(bytes)))) as fmi2FMUstate;
        Status::Ok
    };
    /// fmi2GetDirectionalDerivative: `vUnknown_ref[..nUnknown]`, `vKnown_ref[..nKnown]`,
    /// `dvKnown[..nKnown]`, `dvUnknown[..nUnknown]`.
    fmi2GetDirectionalDerivative GetDirectionalDerivative
    (v_unknown_ref: *const fmi2ValueReference, n_unknown: usize,
     v_known_ref: *const fmi2ValueReference, n_known: usize, dv_known: *const fmi2Real,
     dv_unknown: *mut fmi2Real) |i, f| {
        let unknowns = tri!(slice_in(i, f, ("vUnknown_ref[]", "nUnknown"), v_unknown_ref, n_unknown));
        let knowns = tri!(slice_in(i, f, ("vKnown_ref[]", "nKnown"), v_known_ref, n_known));
        let seeds = tri!(slice_in(i, f, ("dvKnown[]", "nKnown"), dv_known, n_known));
        let out = tri!(slice_out(i, f, ("dvUnknown[]", "nUnknown"), dv_unknown, n_unknown));
        i.get_directional_derivative(unknowns, knowns, seeds, out)
    };
    /// fmi2SetRealInputDerivatives: `vr[..nvr]`, `order[..nvr]`, `value[..nvr]`.
    fmi2SetRealInputDerivatives SetRealInputDerivatives
    (vr: *const fmi2ValueReference, nvr: usize, order: *const fmi2Integer,
     value: *const fmi2Real) |i, f| {
        let vrs = tri!(slice_in(i, f, VR, vr, nvr));
        let orders = tri!(slice_in(i, f, ("order[]", "nvr"), order, nvr));
        let values = tri!(slice_in(i, f, VALUE, value, nvr));
        i.set_real_input_derivatives(vrs, orders, values)
    };
    /// fmi2GetRealOutputDerivatives: `vr[..nvr]`, `order[..nvr]`, `value[..nvr]`.
    fmi2GetRealOutputDerivatives GetRealOutputDerivatives
    (vr: *const fmi2ValueReference, nvr: usize, order: *const fmi2Integer,
     value: *mut fmi2Real) |i, f| {
        let vrs = tri!(slice_in(i, f, VR, vr, nvr));
        let orders = tri!(slice_in(i, f, ("order[]", "nvr"), order, nvr));
        i.get_real_output_derivatives(vrs, orders, tri!(slice_out(i, f, VALUE, value, nvr)))
    };
    /// fmi2DoStep.
    fmi2DoStep DoStep (t: fmi2Real, h: fmi2Real, _no_set_fmu_state_prior: fmi2Boolean)
    |i, _f| i.do_step(t, h);
    /// fmi2CancelStep.
    fmi2CancelStep CancelStep () |i, _f| i.cancel_step();
    /// fmi2GetStatus: `*value` = the status of the last fmi2DoStep.
    fmi2GetStatus GetStatus (s: fmi2StatusKind, value: *mut fmi2Status) |i, f| {
        *tri!(out_ref(i, f, "value", value)) = tri!(i.get_status(s)).to_c();
        Status::Ok
    };
    /// fmi2GetRealStatus: `*value` = the last successful time.
    fmi2GetRealStatus GetRealStatus (s: fmi2StatusKind, value: *mut fmi2Real) |i, f| {
        *tri!(out_ref(i, f, "value", value)) = tri!(i.get_real_status(s));
        Status::Ok
    };
    /// fmi2GetIntegerStatus (no Integer status exists).
    fmi2GetIntegerStatus GetIntegerStatus (s: fmi2StatusKind, _value: *mut fmi2Integer)
    |i, _f| i.get_integer_status(s);
    /// fmi2GetBooleanStatus: `*value` = fmi2Terminated.
    fmi2GetBooleanStatus GetBooleanStatus (s: fmi2StatusKind, value: *mut fmi2Boolean) |i, f| {
        let out = tri!(out_ref(i, f, "value", value));
        *out = if tri!(i.get_boolean_status(s)) { FMI2_TRUE } else { FMI2_FALSE };
        Status::Ok
    };
    /// fmi2GetStringStatus (no step is ever pending).
    fmi2GetStringStatus GetStringStatus (s: fmi2StatusKind, _value: *mut fmi2String)
    |i, _f| i.get_string_status(s);
}
