//! The FMI 2.0 co-simulation calls the harness makes, through the C ABI of a loaded binary.
//!
//! The function-pointer types are the bindings of the official header in `fmi2::types::sys`.
//!
//! The logger: FMI 2.0's `fmi2CallbackLogger` is C-variadic, which stable Rust cannot define.
//! As in `crates/fmu/tests/host/mod.rs`, the harness declares a logger with exactly six
//! parameters `(env, instance, status, category, format, arg)`: the hybeam FMU always calls its
//! logger as `logger(env, name, status, category, "%s", message)`. On x86_64 (System V) a
//! variadic call passes its arguments in the same registers as a non-variadic one (it only also
//! sets %al, which a non-variadic callee ignores), so the two are ABI-compatible for this call.
//! An FMU that passes a format with other conversions would have its message printed as the raw
//! format string and the first argument read as a string: a host for arbitrary FMUs would need a
//! C shim; this harness is for hybeam's FMUs (the logger prints the format when it is not "%s").

use std::ffi::{c_char, c_uint, c_void, CStr, CString};
use std::path::Path;
use std::sync::Mutex;

use fmi2::types::{
    fmi2CallbackFunctions, fmi2Component, fmi2Real, fmi2Status, fmi2ValueReference, sys,
    FMI2_CO_SIMULATION, FMI2_FALSE, FMI2_TRUE,
};
use libloading::Library;

/// `fmi2OK`.
pub const OK: fmi2Status = sys::fmi2Status_fmi2OK;

/// The name of an fmi2Status.
pub fn status_name(s: fmi2Status) -> &'static str {
    match s {
        sys::fmi2Status_fmi2OK => "fmi2OK",
        sys::fmi2Status_fmi2Warning => "fmi2Warning",
        sys::fmi2Status_fmi2Discard => "fmi2Discard",
        sys::fmi2Status_fmi2Error => "fmi2Error",
        sys::fmi2Status_fmi2Fatal => "fmi2Fatal",
        sys::fmi2Status_fmi2Pending => "fmi2Pending",
        _ => "an unknown status",
    }
}

/// The six-parameter logger (see the module doc for why it is not variadic).
type Logger = unsafe extern "C" fn(
    env: *mut c_void,
    instance_name: *const c_char,
    status: c_uint,
    category: *const c_char,
    format: *const c_char,
    arg: *const c_char,
);

/// `fmi2CallbackFunctions` with the non-variadic logger: the same layout as
/// [`fmi2CallbackFunctions`] (five pointers; checked by a test below).
#[repr(C)]
struct Callbacks {
    logger: Option<Logger>,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, c_uint)>,
    component_environment: *mut c_void,
}

/// The component environment: the last message the FMU logged (for error reports).
#[derive(Default)]
struct Environment {
    last: Mutex<Option<String>>,
}

unsafe fn text(p: *const c_char) -> String {
    if p.is_null() {
        "<NULL>".into()
    } else {
        // SAFETY: the FMU passes NUL-terminated strings valid for the call.
        unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
    }
}

/// Prints every message to stderr and keeps the last one in the [`Environment`].
unsafe extern "C" fn logger(
    env: *mut c_void,
    instance_name: *const c_char,
    status: c_uint,
    category: *const c_char,
    format: *const c_char,
    arg: *const c_char,
) {
    // SAFETY: the pointers are the FMU's, valid for this call; env is the Environment the
    // harness passed to fmi2Instantiate, alive until after fmi2FreeInstance.
    let (instance, category, format) =
        unsafe { (text(instance_name), text(category), text(format)) };
    let message = if format == "%s" {
        // SAFETY: "%s" means one string argument
        unsafe { text(arg) }
    } else {
        format
    };
    eprintln!("[{instance}] {} {category}: {message}", status_name(status));
    if !env.is_null() {
        let env = unsafe { &*(env as *const Environment) };
        if let Ok(mut last) = env.last.lock() {
            *last = Some(message);
        }
    }
}

/// The entry points of the loaded binary the harness calls.
pub struct Api {
    instantiate: unsafe extern "C" fn(
        sys::fmi2String,
        sys::fmi2Type,
        sys::fmi2String,
        sys::fmi2String,
        *const fmi2CallbackFunctions,
        sys::fmi2Boolean,
        sys::fmi2Boolean,
    ) -> fmi2Component,
    free_instance: unsafe extern "C" fn(fmi2Component),
    setup_experiment: unsafe extern "C" fn(
        fmi2Component,
        sys::fmi2Boolean,
        fmi2Real,
        fmi2Real,
        sys::fmi2Boolean,
        fmi2Real,
    ) -> fmi2Status,
    enter_initialization_mode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    exit_initialization_mode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    terminate: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    set_real: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2Real,
    ) -> fmi2Status,
    get_real: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *mut fmi2Real,
    ) -> fmi2Status,
    do_step:
        unsafe extern "C" fn(fmi2Component, fmi2Real, fmi2Real, sys::fmi2Boolean) -> fmi2Status,
    /// Kept last: the function pointers above are valid while the library is loaded.
    _library: Library,
}

/// Looks up `name` in `lib` as the header's function-pointer type `T` (an `Option<fn>`).
///
/// # Safety
/// `T` must be the symbol's true type (the header's binding).
unsafe fn symbol<F: Copy>(lib: &Library, path: &Path, name: &str) -> Result<F, String> {
    // SAFETY: the caller names the header's type of the symbol.
    let f: Option<F> = unsafe { lib.get::<Option<F>>(name) }
        .map(|s| *s)
        .map_err(|e| format!("{}: no symbol {name}: {e}", path.display()))?;
    f.ok_or_else(|| format!("{}: symbol {name} is null", path.display()))
}

impl Api {
    /// Loads the binary at `path` and resolves the nine functions the harness calls.
    pub fn load(path: &Path) -> Result<Api, String> {
        // SAFETY: loading a shared library runs its initialisers; an FMU's binary is trusted
        // code by the nature of FMI (the host runs it in-process).
        let lib = unsafe { Library::new(path) }
            .map_err(|e| format!("cannot load {}: {e}", path.display()))?;
        // SAFETY: each type is the binding of the official header's typedef for that symbol
        // (fmi2::sys::fmi2<Name>TYPE is Option<that fn>).
        unsafe {
            Ok(Api {
                instantiate: symbol(&lib, path, "fmi2Instantiate")?,
                free_instance: symbol(&lib, path, "fmi2FreeInstance")?,
                setup_experiment: symbol(&lib, path, "fmi2SetupExperiment")?,
                enter_initialization_mode: symbol(&lib, path, "fmi2EnterInitializationMode")?,
                exit_initialization_mode: symbol(&lib, path, "fmi2ExitInitializationMode")?,
                terminate: symbol(&lib, path, "fmi2Terminate")?,
                set_real: symbol(&lib, path, "fmi2SetReal")?,
                get_real: symbol(&lib, path, "fmi2GetReal")?,
                do_step: symbol(&lib, path, "fmi2DoStep")?,
                _library: lib,
            })
        }
    }
}

// The resolved types must be the header's: a mismatch here fails to compile.
const _: () = {
    fn check(api: &Api) {
        let _: sys::fmi2InstantiateTYPE = Some(api.instantiate);
        let _: sys::fmi2FreeInstanceTYPE = Some(api.free_instance);
        let _: sys::fmi2SetupExperimentTYPE = Some(api.setup_experiment);
        let _: sys::fmi2EnterInitializationModeTYPE = Some(api.enter_initialization_mode);
        let _: sys::fmi2ExitInitializationModeTYPE = Some(api.exit_initialization_mode);
        let _: sys::fmi2TerminateTYPE = Some(api.terminate);
        let _: sys::fmi2SetRealTYPE = Some(api.set_real);
        let _: sys::fmi2GetRealTYPE = Some(api.get_real);
        let _: sys::fmi2DoStepTYPE = Some(api.do_step);
    }
    let _ = check;
};

/// A failed FMI call: which, its status and the last logged message.
#[derive(Debug)]
pub struct CallError {
    /// The function, e.g. `fmi2DoStep`.
    pub function: &'static str,
    /// Its status.
    pub status: fmi2Status,
    /// The last message the FMU logged, if any.
    pub message: Option<String>,
}

impl std::fmt::Display for CallError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} returned {}", self.function, status_name(self.status))?;
        match &self.message {
            Some(m) => write!(f, "; the FMU logged: {m}"),
            None => write!(f, "; the FMU logged nothing"),
        }
    }
}

/// An instantiated FMU (co-simulation), freed on drop.
pub struct Instance<'a> {
    api: &'a Api,
    c: fmi2Component,
    /// Boxed: its address is the component environment the logger receives.
    env: Box<Environment>,
    /// Boxed: the FMU may keep the pointer to the callbacks for the instance's life.
    _callbacks: Box<Callbacks>,
    terminated: bool,
}

impl<'a> Instance<'a> {
    /// fmi2Instantiate (co-simulation, not visible, `logging_on` as given) with the resources
    /// directory `resources` (passed as a `file://` URI).
    pub fn new(
        api: &'a Api,
        name: &str,
        guid: &str,
        resources: &Path,
        logging_on: bool,
    ) -> Result<Self, String> {
        let env = Box::<Environment>::default();
        let callbacks = Box::new(Callbacks {
            logger: Some(logger),
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: &*env as *const Environment as *mut c_void,
        });
        let uri = file_uri(resources);
        let cstr = |s: &str, what: &str| {
            CString::new(s).map_err(|_| format!("the {what} {s:?} contains a NUL byte"))
        };
        let (name_c, guid_c, uri_c) = (
            cstr(name, "instance name")?,
            cstr(guid, "GUID")?,
            cstr(&uri, "resource location")?,
        );
        // SAFETY: valid C strings for the call; the callbacks struct has the header's layout
        // (see Callbacks) and outlives the instance (boxed in it).
        let c = unsafe {
            (api.instantiate)(
                name_c.as_ptr(),
                FMI2_CO_SIMULATION,
                guid_c.as_ptr(),
                uri_c.as_ptr(),
                &*callbacks as *const Callbacks as *const fmi2CallbackFunctions,
                FMI2_FALSE,
                if logging_on { FMI2_TRUE } else { FMI2_FALSE },
            )
        };
        if c.is_null() {
            let last = env.last.lock().ok().and_then(|m| m.clone());
            return Err(format!(
                "fmi2Instantiate returned NULL (resources {uri}); the FMU logged: {}",
                last.as_deref().unwrap_or("nothing")
            ));
        }
        Ok(Instance {
            api,
            c,
            env,
            _callbacks: callbacks,
            terminated: false,
        })
    }

    fn check(&self, function: &'static str, status: fmi2Status) -> Result<(), CallError> {
        if status == OK {
            Ok(())
        } else {
            Err(CallError {
                function,
                status,
                message: self.env.last.lock().ok().and_then(|m| m.clone()),
            })
        }
    }

    /// fmi2SetupExperiment(no tolerance, start, no stop time).
    pub fn setup_experiment(&self, start: f64) -> Result<(), CallError> {
        // SAFETY: a live component.
        let s =
            unsafe { (self.api.setup_experiment)(self.c, FMI2_FALSE, 0.0, start, FMI2_FALSE, 0.0) };
        self.check("fmi2SetupExperiment", s)
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization_mode(&self) -> Result<(), CallError> {
        // SAFETY: a live component.
        let s = unsafe { (self.api.enter_initialization_mode)(self.c) };
        self.check("fmi2EnterInitializationMode", s)
    }

    /// fmi2ExitInitializationMode.
    pub fn exit_initialization_mode(&self) -> Result<(), CallError> {
        // SAFETY: a live component.
        let s = unsafe { (self.api.exit_initialization_mode)(self.c) };
        self.check("fmi2ExitInitializationMode", s)
    }

    /// fmi2SetReal of `values` to the variables `vrs` (equal lengths).
    #[inline]
    pub fn set_real(&self, vrs: &[u32], values: &[f64]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), values.len());
        // SAFETY: a live component; both arrays have vrs.len() elements.
        let s = unsafe { (self.api.set_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) };
        self.check("fmi2SetReal", s)
    }

    /// fmi2GetReal of the variables `vrs` into `values` (equal lengths).
    #[inline]
    pub fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), values.len());
        // SAFETY: a live component; both arrays have vrs.len() elements.
        let s =
            unsafe { (self.api.get_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        self.check("fmi2GetReal", s)
    }

    /// fmi2DoStep from `t` [s] over `h` [s] (noSetFMUStatePriorToCurrentPoint = true: the
    /// harness never rolls back).
    #[inline]
    pub fn do_step(&self, t: f64, h: f64) -> Result<(), CallError> {
        // SAFETY: a live component.
        let s = unsafe { (self.api.do_step)(self.c, t, h, FMI2_TRUE) };
        self.check("fmi2DoStep", s)
    }

    /// fmi2Terminate (once; fmi2FreeInstance follows on drop).
    pub fn terminate(&mut self) -> Result<(), CallError> {
        self.terminated = true;
        // SAFETY: a live component.
        let s = unsafe { (self.api.terminate)(self.c) };
        self.check("fmi2Terminate", s)
    }

    /// Whether fmi2Terminate was called.
    pub fn terminated(&self) -> bool {
        self.terminated
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        // SAFETY: the component is live and freed once; the environment and the callbacks are
        // dropped only after this.
        unsafe { (self.api.free_instance)(self.c) };
    }
}

/// `file://` URI of an absolute directory (characters outside the URI's unreserved set and
/// `/` percent-encoded).
pub fn file_uri(dir: &Path) -> String {
    let mut uri = String::from("file://");
    for b in dir.to_string_lossy().bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            uri.push(b as char);
        } else {
            uri.push_str(&format!("%{b:02X}"));
        }
    }
    uri
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn callbacks_have_the_header_layout() {
        assert_eq!(
            std::mem::size_of::<Callbacks>(),
            std::mem::size_of::<fmi2CallbackFunctions>()
        );
        assert_eq!(
            std::mem::offset_of!(Callbacks, component_environment),
            std::mem::offset_of!(fmi2CallbackFunctions, componentEnvironment)
        );
    }

    #[test]
    fn file_uri_percent_encodes() {
        assert_eq!(
            file_uri(Path::new("/tmp/a b/résources")),
            "file:///tmp/a%20b/r%C3%A9sources"
        );
    }
}
