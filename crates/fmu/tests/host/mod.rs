//! A minimal FMI 2.0 host for the tests: loads the built cdylib with libloading and drives it
//! through the C ABI, capturing every logger call.
//!
//! The library is the `libhybeam_fmu.so` that `cargo test` builds next to the test executable,
//! together with the rlib the test links (the lib target has `crate-type = ["rlib", "cdylib"]`).
//! The scene is `SCENE` (Case 1), written into a temporary `resources/` folder under
//! `CARGO_TARGET_TMPDIR`.
//!
//! The logger: FMI 2.0's logger is C-variadic, which stable Rust cannot define. The FMU always
//! calls it as `logger(env, name, status, category, "%s", message)`, so the test logger is
//! declared with exactly those six parameters. On x86_64 (System V) a variadic call passes its
//! arguments in the same registers as a non-variadic one (it only also sets %al, which a
//! non-variadic callee ignores), so the two are ABI-compatible for this call. The logger records
//! the format too, and the tests assert it is always `"%s"`.

#![allow(dead_code)]

use std::ffi::{c_char, c_uint, c_void, CStr, CString};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

use fmi2::types::{sys, *};
use fmi2::CoSimModel;
use libloading::Library;

/// The scene the FMU is tested with.
pub const SCENE: &str = include_str!("../../../../scenes/case1.toml");

/// fmi2 status codes.
pub const OK: fmi2Status = 0;
pub const WARNING: fmi2Status = 1;
pub const DISCARD: fmi2Status = 2;
pub const ERROR: fmi2Status = 3;
pub const FATAL: fmi2Status = 4;

/// The test logger's signature (see the module doc).
pub type Logger = unsafe extern "C" fn(
    env: *mut c_void,
    instance_name: *const c_char,
    status: c_uint,
    category: *const c_char,
    format: *const c_char,
    arg: *const c_char,
);

/// `fmi2CallbackFunctions` with the non-variadic test logger.
#[repr(C)]
pub struct Callbacks {
    pub logger: Option<Logger>,
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    pub step_finished: Option<unsafe extern "C" fn(*mut c_void, c_uint)>,
    pub component_environment: *mut c_void,
}

/// One logger call.
#[derive(Debug, Clone)]
pub struct Entry {
    pub instance: String,
    pub status: u32,
    pub category: String,
    pub format: String,
    pub message: String,
}

/// The messages of one instance.
#[derive(Default)]
pub struct Log(Mutex<Vec<Entry>>);

impl Log {
    pub fn entries(&self) -> Vec<Entry> {
        self.0.lock().unwrap().clone()
    }
    pub fn clear(&self) {
        self.0.lock().unwrap().clear();
    }
    /// The last message; panics if none.
    pub fn last(&self) -> Entry {
        self.entries().last().cloned().expect("a logged message")
    }
    /// Asserts that the last message has `status`, `category` and contains every part.
    pub fn assert_last(&self, status: u32, category: &str, parts: &[&str]) {
        let e = self.last();
        assert_eq!(e.status, status, "{e:?}");
        assert_eq!(e.category, category, "{e:?}");
        for p in parts {
            assert!(e.message.contains(p), "{:?} lacks {p:?}", e.message);
        }
    }
}

unsafe fn text(p: *const c_char) -> String {
    if p.is_null() {
        "<NULL>".into()
    } else {
        unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
    }
}

/// The test logger: appends to the [`Log`] passed as component environment.
pub unsafe extern "C" fn test_logger(
    env: *mut c_void,
    instance_name: *const c_char,
    status: c_uint,
    category: *const c_char,
    format: *const c_char,
    arg: *const c_char,
) {
    let log = unsafe { &*(env as *const Log) };
    let entry = unsafe {
        Entry {
            instance: text(instance_name),
            status,
            category: text(category),
            format: text(format),
            message: text(arg),
        }
    };
    log.0.lock().unwrap().push(entry);
}

macro_rules! api {
    ($($field:ident: $ty:ident = $sym:literal;)*) => {
        /// The 34 functions of the loaded library.
        pub struct Api {
            _lib: Library,
            $(pub $field: sys::$ty,)*
        }

        impl Api {
            fn load(path: &Path) -> Api {
                // SAFETY: loading our own cdylib, whose initialisers are Rust's own.
                let lib = unsafe { Library::new(path) }
                    .unwrap_or_else(|e| panic!("cannot load {}: {e}", path.display()));
                // SAFETY: the symbol types are the bindings of the official header (fmi2::sys).
                unsafe {
                    Api {
                        $($field: *lib.get::<sys::$ty>($sym).unwrap_or_else(|e| panic!("{e}")),)*
                        _lib: lib,
                    }
                }
            }
        }
    };
}

api! {
    get_types_platform: fmi2GetTypesPlatformTYPE = b"fmi2GetTypesPlatform";
    get_version: fmi2GetVersionTYPE = b"fmi2GetVersion";
    set_debug_logging: fmi2SetDebugLoggingTYPE = b"fmi2SetDebugLogging";
    instantiate: fmi2InstantiateTYPE = b"fmi2Instantiate";
    free_instance: fmi2FreeInstanceTYPE = b"fmi2FreeInstance";
    setup_experiment: fmi2SetupExperimentTYPE = b"fmi2SetupExperiment";
    enter_initialization_mode: fmi2EnterInitializationModeTYPE = b"fmi2EnterInitializationMode";
    exit_initialization_mode: fmi2ExitInitializationModeTYPE = b"fmi2ExitInitializationMode";
    terminate: fmi2TerminateTYPE = b"fmi2Terminate";
    reset: fmi2ResetTYPE = b"fmi2Reset";
    get_real: fmi2GetRealTYPE = b"fmi2GetReal";
    get_integer: fmi2GetIntegerTYPE = b"fmi2GetInteger";
    get_boolean: fmi2GetBooleanTYPE = b"fmi2GetBoolean";
    get_string: fmi2GetStringTYPE = b"fmi2GetString";
    set_real: fmi2SetRealTYPE = b"fmi2SetReal";
    set_integer: fmi2SetIntegerTYPE = b"fmi2SetInteger";
    set_boolean: fmi2SetBooleanTYPE = b"fmi2SetBoolean";
    set_string: fmi2SetStringTYPE = b"fmi2SetString";
    get_fmu_state: fmi2GetFMUstateTYPE = b"fmi2GetFMUstate";
    set_fmu_state: fmi2SetFMUstateTYPE = b"fmi2SetFMUstate";
    free_fmu_state: fmi2FreeFMUstateTYPE = b"fmi2FreeFMUstate";
    serialized_fmu_state_size: fmi2SerializedFMUstateSizeTYPE = b"fmi2SerializedFMUstateSize";
    serialize_fmu_state: fmi2SerializeFMUstateTYPE = b"fmi2SerializeFMUstate";
    deserialize_fmu_state: fmi2DeSerializeFMUstateTYPE = b"fmi2DeSerializeFMUstate";
    get_directional_derivative: fmi2GetDirectionalDerivativeTYPE = b"fmi2GetDirectionalDerivative";
    set_real_input_derivatives: fmi2SetRealInputDerivativesTYPE = b"fmi2SetRealInputDerivatives";
    get_real_output_derivatives: fmi2GetRealOutputDerivativesTYPE = b"fmi2GetRealOutputDerivatives";
    do_step: fmi2DoStepTYPE = b"fmi2DoStep";
    cancel_step: fmi2CancelStepTYPE = b"fmi2CancelStep";
    get_status: fmi2GetStatusTYPE = b"fmi2GetStatus";
    get_real_status: fmi2GetRealStatusTYPE = b"fmi2GetRealStatus";
    get_integer_status: fmi2GetIntegerStatusTYPE = b"fmi2GetIntegerStatus";
    get_boolean_status: fmi2GetBooleanStatusTYPE = b"fmi2GetBooleanStatus";
    get_string_status: fmi2GetStringStatusTYPE = b"fmi2GetStringStatus";
}

/// Path of the cdylib built with this test. Cargo writes the cdylib of the library under test
/// next to the test executable (`target/<profile>/deps/libhybeam_fmu.so`, built together with the
/// rlib the test links); `target/<profile>/libhybeam_fmu.so` (from `cargo build --lib`) is the
/// fallback.
pub fn library_path() -> PathBuf {
    let file = format!(
        "{}hybeam_fmu{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    );
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let candidates = [deps.join(&file), deps.parent().unwrap().join(&file)];
    candidates
        .iter()
        .find(|p| p.exists())
        .cloned()
        .unwrap_or_else(|| {
            panic!("{file} not found in {candidates:?}: run `cargo build -p hybeam-fmu --lib`")
        })
}

/// The loaded library (loaded once per test process).
pub fn api() -> &'static Api {
    static API: OnceLock<Api> = OnceLock::new();
    API.get_or_init(|| Api::load(&library_path()))
}

/// A fresh directory under the cargo target tmpdir.
pub fn temp_dir(tag: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("fmi_host")
        .join(format!("{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `DIR/resources/scene.toml` with `scene`; returns the resources directory.
pub fn resources_with(scene: &str, tag: &str) -> PathBuf {
    let dir = temp_dir(tag).join("resources");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    dir
}

/// `file://` URI of a directory (spaces percent-encoded).
pub fn file_uri(dir: &Path) -> String {
    format!("file://{}", dir.display().to_string().replace(' ', "%20"))
}

/// The GUID of a scene.
pub fn guid_of(scene: &str) -> String {
    fmi2::guid::guid::<hybeam_fmu::FmuModel>(scene.as_bytes())
}

/// Value reference of a variable of the scene's model, by name.
pub fn vr(name: &str) -> u32 {
    vr_in(SCENE, name)
}

/// Value reference of a variable of the model of `scene`, by name.
pub fn vr_in(scene: &str, name: &str) -> u32 {
    let model = hybeam_fmu::FmuModel::from_resource(scene).unwrap();
    model
        .variables()
        .iter()
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .vr
}

/// An instance of `scene` (resources under `tag`), set up at t = 0, in initialization mode.
pub fn in_initialization(scene: &str, tag: &str) -> Inst {
    let args = InstantiateArgs {
        guid: guid_of(scene),
        location: Some(file_uri(&resources_with(scene, tag))),
        ..InstantiateArgs::valid(tag)
    };
    let (c, log) = instantiate_raw(&args);
    assert!(!c.is_null(), "instantiate failed: {:?}", log.entries());
    let i = Inst { c, log, api: api() };
    assert_eq!(i.setup(0.0, None), OK);
    assert_eq!(i.enter_init(), OK);
    i
}

/// An instance of `scene` (resources under `tag`), set up at t = 0 and initialized.
pub fn initialized_with(scene: &str, tag: &str) -> Inst {
    let i = in_initialization(scene, tag);
    assert_eq!(i.exit_init(), OK);
    i
}

/// The value references of the variables matching `pred`.
/// Start value of a variable in the model description of `SCENE`.
pub fn start_of(vr: u32) -> f64 {
    let model = hybeam_fmu::FmuModel::from_resource(SCENE).unwrap();
    let v = model
        .variables()
        .iter()
        .find(|v| v.vr == vr)
        .expect("known value reference");
    v.start.expect("variable has a start value")
}

pub fn vrs_where(pred: impl Fn(&fmi2::Variable) -> bool) -> Vec<u32> {
    let model = hybeam_fmu::FmuModel::from_resource(SCENE).unwrap();
    model
        .variables()
        .iter()
        .filter(|v| pred(v))
        .map(|v| v.vr)
        .collect()
}

/// Arguments of fmi2Instantiate.
pub struct InstantiateArgs {
    pub name: String,
    pub fmu_type: fmi2Type,
    pub guid: String,
    pub location: Option<String>,
    pub logging_on: bool,
}

impl InstantiateArgs {
    /// Valid arguments for a fresh resources dir holding `SCENE`.
    pub fn valid(tag: &str) -> Self {
        Self {
            name: format!("inst-{tag}"),
            fmu_type: 1,
            guid: guid_of(SCENE),
            location: Some(file_uri(&resources_with(SCENE, tag))),
            logging_on: false,
        }
    }
}

/// Replaces the little-endian bytes of `old` by those of `new` in `bytes`, leaving the first
/// `skip` occurrences alone; returns how many were replaced. Used to craft snapshots without
/// depending on the model's byte layout beyond the order of its fields.
pub fn replace_f64(bytes: &mut [u8], old: f64, new: f64, skip: usize) -> usize {
    let (old, new) = (old.to_le_bytes(), new.to_le_bytes());
    let mut seen = 0;
    let mut i = 0;
    while i + 8 <= bytes.len() {
        if bytes[i..i + 8] == old {
            if seen >= skip {
                bytes[i..i + 8].copy_from_slice(&new);
            }
            seen += 1;
            i += 8;
        } else {
            i += 1;
        }
    }
    seen.saturating_sub(skip)
}

/// A live instance with its log; frees the instance on drop.
pub struct Inst {
    pub c: fmi2Component,
    pub log: Box<Log>,
    pub api: &'static Api,
}

/// Calls fmi2Instantiate; returns the component (maybe NULL) and the log.
pub fn instantiate_raw(args: &InstantiateArgs) -> (fmi2Component, Box<Log>) {
    let api = api();
    let log = Box::new(Log::default());
    let mut callbacks = Callbacks {
        logger: Some(test_logger),
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: &*log as *const Log as *mut c_void,
    };
    let name = CString::new(args.name.as_str()).unwrap();
    let guid = CString::new(args.guid.as_str()).unwrap();
    let location = args.location.as_deref().map(|l| CString::new(l).unwrap());
    // SAFETY: valid C strings and callbacks for the duration of the call (the FMU copies them).
    let c = unsafe {
        api.instantiate.unwrap()(
            name.as_ptr(),
            args.fmu_type,
            guid.as_ptr(),
            location.as_ref().map_or(std::ptr::null(), |l| l.as_ptr()),
            &callbacks as *const Callbacks as *const fmi2CallbackFunctions,
            0,
            args.logging_on as fmi2Boolean,
        )
    };
    // The FMU must have copied the struct: clobber ours (later log messages must still arrive).
    callbacks.logger = None;
    callbacks.component_environment = std::ptr::null_mut();
    std::hint::black_box(&mut callbacks);
    (c, log)
}

impl Inst {
    /// A new instance of `SCENE` (panics on failure).
    pub fn new(tag: &str) -> Self {
        let (c, log) = instantiate_raw(&InstantiateArgs::valid(tag));
        assert!(!c.is_null(), "instantiate failed: {:?}", log.entries());
        Self { c, log, api: api() }
    }

    /// Instantiated, set up (start 0, optional stop) and initialized: state stepComplete.
    pub fn initialized(tag: &str, stop: Option<f64>) -> Self {
        let i = Self::new(tag);
        assert_eq!(i.setup(0.0, stop), OK);
        assert_eq!(i.enter_init(), OK);
        assert_eq!(i.exit_init(), OK);
        i
    }

    pub fn setup(&self, start: f64, stop: Option<f64>) -> fmi2Status {
        unsafe {
            self.api.setup_experiment.unwrap()(
                self.c,
                0,
                0.0,
                start,
                stop.is_some() as fmi2Boolean,
                stop.unwrap_or(0.0),
            )
        }
    }
    pub fn enter_init(&self) -> fmi2Status {
        unsafe { self.api.enter_initialization_mode.unwrap()(self.c) }
    }
    pub fn exit_init(&self) -> fmi2Status {
        unsafe { self.api.exit_initialization_mode.unwrap()(self.c) }
    }
    pub fn terminate(&self) -> fmi2Status {
        unsafe { self.api.terminate.unwrap()(self.c) }
    }
    pub fn reset(&self) -> fmi2Status {
        unsafe { self.api.reset.unwrap()(self.c) }
    }
    pub fn do_step(&self, t: f64, h: f64) -> fmi2Status {
        unsafe { self.api.do_step.unwrap()(self.c, t, h, 1) }
    }
    pub fn set_real(&self, vrs: &[u32], values: &[f64]) -> fmi2Status {
        assert_eq!(vrs.len(), values.len());
        unsafe { self.api.set_real.unwrap()(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }
    pub fn get_real(&self, vrs: &[u32]) -> Result<Vec<f64>, fmi2Status> {
        let mut out = vec![f64::NAN; vrs.len()];
        let s = unsafe {
            self.api.get_real.unwrap()(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        };
        if s == OK {
            Ok(out)
        } else {
            Err(s)
        }
    }
    /// fmi2SetString with owned copies of `values` (freed after the call: the FMU must copy).
    pub fn set_string(&self, vrs: &[u32], values: &[&str]) -> fmi2Status {
        assert_eq!(vrs.len(), values.len());
        let owned: Vec<CString> = values.iter().map(|v| CString::new(*v).unwrap()).collect();
        let ptrs: Vec<*const c_char> = owned.iter().map(|c| c.as_ptr()).collect();
        unsafe { self.api.set_string.unwrap()(self.c, vrs.as_ptr(), vrs.len(), ptrs.as_ptr()) }
    }
    /// fmi2GetString, the values copied before any other call.
    pub fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, fmi2Status> {
        let mut out = vec![std::ptr::null(); vrs.len()];
        let s = unsafe {
            self.api.get_string.unwrap()(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        };
        if s != OK {
            return Err(s);
        }
        Ok(out.iter().map(|&p| unsafe { text(p) }).collect())
    }
    pub fn set_logging(&self, on: bool, categories: &[&str]) -> fmi2Status {
        let owned: Vec<CString> = categories
            .iter()
            .map(|c| CString::new(*c).unwrap())
            .collect();
        let ptrs: Vec<*const c_char> = owned.iter().map(|c| c.as_ptr()).collect();
        unsafe {
            self.api.set_debug_logging.unwrap()(
                self.c,
                on as fmi2Boolean,
                ptrs.len(),
                ptrs.as_ptr(),
            )
        }
    }
    pub fn get1(&self, vr: u32) -> f64 {
        self.get_real(&[vr]).expect("fmi2GetReal")[0]
    }
    pub fn terminated(&self) -> (fmi2Status, bool) {
        let mut b: fmi2Boolean = -1;
        let s = unsafe { self.api.get_boolean_status.unwrap()(self.c, 3, &mut b) };
        (s, b != 0)
    }
    pub fn last_successful_time(&self) -> (fmi2Status, f64) {
        let mut t = f64::NAN;
        let s = unsafe { self.api.get_real_status.unwrap()(self.c, 2, &mut t) };
        (s, t)
    }
    pub fn get_state(&self) -> fmi2FMUstate {
        let mut s: fmi2FMUstate = std::ptr::null_mut();
        assert_eq!(
            unsafe { self.api.get_fmu_state.unwrap()(self.c, &mut s) },
            OK
        );
        assert!(!s.is_null());
        s
    }
    pub fn set_state(&self, s: fmi2FMUstate) -> fmi2Status {
        unsafe { self.api.set_fmu_state.unwrap()(self.c, s) }
    }
    pub fn free_state(&self, s: &mut fmi2FMUstate) -> fmi2Status {
        unsafe { self.api.free_fmu_state.unwrap()(self.c, s) }
    }
    pub fn serialize(&self, s: fmi2FMUstate) -> Vec<u8> {
        let mut n = 0usize;
        assert_eq!(
            unsafe { self.api.serialized_fmu_state_size.unwrap()(self.c, s, &mut n) },
            OK
        );
        let mut bytes = vec![0u8; n];
        let st = unsafe {
            self.api.serialize_fmu_state.unwrap()(self.c, s, bytes.as_mut_ptr() as *mut _, n)
        };
        assert_eq!(st, OK);
        bytes
    }
    pub fn deserialize(&self, bytes: &[u8]) -> (fmi2Status, fmi2FMUstate) {
        let mut s: fmi2FMUstate = std::ptr::null_mut();
        let st = unsafe {
            self.api.deserialize_fmu_state.unwrap()(
                self.c,
                bytes.as_ptr() as *const _,
                bytes.len(),
                &mut s,
            )
        };
        (st, s)
    }
    /// Asserts no message of status Warning or worse was logged.
    pub fn assert_no_problems(&self) {
        let bad: Vec<Entry> = self
            .log
            .entries()
            .into_iter()
            .filter(|e| e.status > 0)
            .collect();
        assert!(bad.is_empty(), "{bad:?}");
    }
}

impl Drop for Inst {
    fn drop(&mut self) {
        unsafe { self.api.free_instance.unwrap()(self.c) };
        if !std::thread::panicking() {
            for e in self.log.entries() {
                assert_eq!(
                    e.format, "%s",
                    "logger called with a format other than %s: {e:?}"
                );
            }
        }
    }
}
