//! Nothing allocated in the step (issue 41 §2): after fmi2ExitInitializationMode, the calls a
//! real-time host makes every communication step — fmi2SetReal, fmi2SetRealInputDerivatives,
//! fmi2DoStep, fmi2GetReal and, where the FMU declares them (mounted scenes),
//! fmi2GetRealOutputDerivatives — allocate no heap memory, on every shipped scene and three with elements of degree 5 (planar, spatial, mounted with the mount on a smooth path, with the partner
//! inputs, `visualization.directory` empty): none allocates.
//!
//! The FMI functions are called in-process through the library's Rust exports
//! (`hybeam_fmu::fmi2_exports`), so this test binary's counting global allocator sees every
//! allocation the FMU makes on the calling thread.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ffi::{c_char, c_uint, c_void, CString};

use fmi2::types::*;
use hybeam_fmu::fmi2_exports as fmi;

/// Counts allocations (alloc, alloc_zeroed, realloc) of the threads that switched it on.
struct Counting;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<u64> = const { Cell::new(0) };
    /// Inside the allocator's own bookkeeping (a backtrace being captured).
    static INSIDE: Cell<bool> = const { Cell::new(false) };
    /// With `HYBEAM_ALLOC_TRACE=1`: the first allocations' backtraces (a debugging aid: where
    /// a step allocates).
    static TRACES: std::cell::RefCell<Vec<std::backtrace::Backtrace>> =
        const { std::cell::RefCell::new(Vec::new()) };
    static TRACING: Cell<bool> = const { Cell::new(false) };
}

fn note() {
    let _ = COUNTING.try_with(|on| {
        if on.get() && !INSIDE.with(|i| i.get()) {
            COUNT.with(|c| c.set(c.get() + 1));
            if TRACING.with(|t| t.get()) {
                INSIDE.with(|i| i.set(true));
                TRACES.with(|t| {
                    let mut t = t.borrow_mut();
                    if t.len() < 1500 {
                        t.push(std::backtrace::Backtrace::force_capture());
                    }
                });
                INSIDE.with(|i| i.set(false));
            }
        }
    });
}

/// The allocation sites recorded (`HYBEAM_ALLOC_TRACE=1`): the first frames of hybeam code of
/// each backtrace, counted.
fn print_traces(id: &str) {
    let traces = TRACES.with(|t| std::mem::take(&mut *t.borrow_mut()));
    let mut sites: std::collections::BTreeMap<String, usize> = Default::default();
    for bt in &traces {
        let text = format!("{bt}");
        let frames: Vec<&str> = text
            .lines()
            .map(str::trim)
            .filter(|l| l.starts_with("at ./") || l.starts_with("at /work"))
            .filter(|l| !l.contains("no_alloc.rs"))
            .take(3)
            .collect();
        *sites.entry(frames.join(" < ")).or_default() += 1;
    }
    let mut sites: Vec<_> = sites.into_iter().collect();
    sites.sort_by_key(|s| std::cmp::Reverse(s.1));
    for (site, n) in sites.iter().take(25) {
        eprintln!("{id}: {n:4} × {site}");
    }
}

// SAFETY: forwards to the system allocator; the counter is a const-initialized thread local
// (no allocation of its own).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations(f: impl FnOnce()) -> u64 {
    let before = COUNT.with(|c| c.get());
    COUNTING.with(|on| on.set(true));
    f();
    COUNTING.with(|on| on.set(false));
    COUNT.with(|c| c.get()) - before
}

/// The non-variadic logger of `tests/host/mod.rs` (same ABI on x86_64 System V): prints.
unsafe extern "C" fn logger(
    _env: *mut c_void,
    _name: *const c_char,
    status: c_uint,
    _category: *const c_char,
    _format: *const c_char,
    message: *const c_char,
) {
    if !message.is_null() {
        let m = unsafe { std::ffi::CStr::from_ptr(message) };
        eprintln!("[fmu {status}] {}", m.to_string_lossy());
    }
}

#[repr(C)]
struct Callbacks {
    logger: Option<
        unsafe extern "C" fn(
            *mut c_void,
            *const c_char,
            c_uint,
            *const c_char,
            *const c_char,
            *const c_char,
        ),
    >,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, c_uint)>,
    component_environment: *mut c_void,
}

/// A variable of the scene's model: value reference, start value.
fn var(model: &hybeam_fmu::FmuModel, name: &str) -> Option<(u32, f64)> {
    use fmi2::CoSimModel;
    model
        .variables()
        .iter()
        .find(|v| v.name == name)
        .map(|v| (v.vr, v.start.unwrap_or(0.0)))
}

/// Instantiates `scene` (the file's text), steps it `warm` steps then counts the allocations
/// of `steps` more, each setting the tip force (a sine) and, when mounted, the mount on a
/// smooth heave path, with the force's derivative, and reading every output. Returns the
/// count.
fn count(id: &str, scene: &str, dt: f64, warm: usize, steps: usize) -> u64 {
    use fmi2::CoSimModel;
    let model = hybeam_fmu::FmuModel::from_resource(scene).unwrap();
    let outputs: Vec<u32> = model
        .variables()
        .iter()
        .filter(|v| format!("{:?}", v.causality) == "Output")
        .map(|v| v.vr)
        .collect();
    assert!(!outputs.is_empty(), "{id}: no outputs");
    let space3 = var(&model, "tip.force.z").is_some();
    let (force, _) = var(&model, if space3 { "tip.force.z" } else { "tip.force.y" }).unwrap();
    // the mount's vertical coordinate and its rates (mounted scenes)
    let up = if space3 { "z" } else { "y" };
    let mount = ["position", "velocity", "acceleration"]
        .map(|k| var(&model, &format!("root.{k}.{up}")))
        .into_iter()
        .collect::<Option<Vec<_>>>();
    let partner = var(&model, "root.mobility.ax_fx");

    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("no_alloc")
        .join(format!("{}-{id}", std::process::id()))
        .join("resources");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let location = CString::new(format!("file://{}", dir.display())).unwrap();
    let name = CString::new(id).unwrap();
    let guid = CString::new(fmi2::guid::guid::<hybeam_fmu::FmuModel>(scene.as_bytes())).unwrap();
    let callbacks = Callbacks {
        logger: Some(logger),
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: std::ptr::null_mut(),
    };
    // SAFETY: valid C strings and callbacks; the instance is freed below.
    unsafe {
        let c = fmi::fmi2Instantiate(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            location.as_ptr(),
            &callbacks as *const Callbacks as *const fmi2CallbackFunctions,
            0,
            0,
        );
        assert!(!c.is_null(), "{id}: instantiate failed");
        assert_eq!(fmi::fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), 0);
        assert_eq!(fmi::fmi2EnterInitializationMode(c), 0);
        assert_eq!(fmi::fmi2ExitInitializationMode(c), 0);
        let mut values = vec![0.0; outputs.len()];
        let mut rates = vec![0.0; outputs.len()];
        let orders = vec![1 as fmi2Integer; outputs.len()];
        let derivatives = mount.is_some();
        let amp = 0.0;
        let w = 2.0 * std::f64::consts::PI * 2.0;
        let (a, wm) = (0.01, 2.0 * std::f64::consts::PI * 1.0);
        let mut step = |k: usize| {
            let t = k as f64 * dt;
            let (s, co) = (w * t).sin_cos();
            assert_eq!(fmi::fmi2SetReal(c, &force, 1, &(amp * s)), 0);
            assert_eq!(
                fmi::fmi2SetRealInputDerivatives(c, &force, 1, &1, &(amp * w * co)),
                0
            );
            if let Some(m) = &mount {
                let (sm, cm) = (wm * t).sin_cos();
                // y = a (1 − cos), y' = a w sin, y'' = a w² cos: at rest at t = 0
                let path = [m[0].1 + a * (1.0 - cm), a * wm * sm, a * wm * wm * cm];
                let vrs = [m[0].0, m[1].0, m[2].0];
                assert_eq!(fmi::fmi2SetReal(c, vrs.as_ptr(), 3, path.as_ptr()), 0);
            }
            if let Some((p, _)) = partner {
                // a small mobility (the partner model switched on)
                assert_eq!(fmi::fmi2SetReal(c, &p, 1, &1e-4), 0);
            }
            let st = fmi::fmi2DoStep(c, t, dt, 1);
            assert_eq!(st, 0, "{id}: step {k} at t = {t}");
            assert_eq!(
                fmi::fmi2GetReal(c, outputs.as_ptr(), outputs.len(), values.as_mut_ptr()),
                0
            );
            if derivatives {
                let st = fmi::fmi2GetRealOutputDerivatives(
                    c,
                    outputs.as_ptr(),
                    outputs.len(),
                    orders.as_ptr(),
                    rates.as_mut_ptr(),
                );
                assert_eq!(st, 0, "{id}: output derivatives");
            }
        };
        for k in 0..warm {
            step(k);
        }
        let trace = std::env::var("HYBEAM_ALLOC_TRACE").is_ok_and(|v| v == "1");
        TRACING.with(|t| t.set(trace));
        let n = allocations(|| {
            for k in warm..warm + steps {
                step(k);
            }
        });
        TRACING.with(|t| t.set(false));
        if trace {
            print_traces(id);
        }
        fmi::fmi2Terminate(c);
        fmi::fmi2FreeInstance(c);
        n
    }
}

/// Every shipped scene: (id, text, communication steps counted).
fn scenes() -> Vec<(String, String)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes");
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "toml").then(|| {
                let id = p.file_stem().unwrap().to_string_lossy().into_owned();
                (id, std::fs::read_to_string(&p).unwrap())
            })
        })
        .collect();
    // elements of degree 5 (element-internal bubble coordinates): the soft rod, the mounted
    // boom's ANCF tip segment with its root station, the spatial mounted Case 1 rod's ANCF half
    // as a 3D cable
    let variant = |id: &str, edits: &[(&str, &str)]| {
        let (_, text) = out.iter().find(|(i, _)| i == id).unwrap();
        let mut text = text.clone();
        for (from, to) in edits {
            assert!(text.contains(from), "{id}: {from}");
            text = text.replacen(from, to, 1);
        }
        (format!("{id}_degree5"), text)
    };
    let degree5 = |n: &str| ("elements = ".to_string() + n, "elements = 2\ndegree = 5");
    let (soft, boom, cable) = (degree5("16"), degree5("8"), degree5("8"));
    let cable3d = ("root = \"mounted\"", "root = \"mounted\"\ntorsion = false");
    let extra = [
        variant("soft_rod", &[(&soft.0, soft.1)]),
        variant("boom", &[(&boom.0, boom.1)]),
        variant("case1_3d_mounted", &[cable3d, (&cable.0, cable.1)]),
    ];
    out.extend(extra);
    out.sort();
    out
}

/// The scenes a real-time host runs (the booms and their real-time twins, mounted, with the
/// partner model): 10 000 steps each; every other scene 1000.
const LONG: [&str; 4] = ["boom", "boom_3d", "boom_rt", "boom_3d_rt"];

#[test]
fn no_heap_allocation_in_the_step() {
    let mut report = Vec::new();
    let mut failed = Vec::new();
    // HYBEAM_ALLOC_SCENE=<id>: that scene alone (a debugging aid)
    let only = std::env::var("HYBEAM_ALLOC_SCENE").ok();
    for (id, scene) in scenes() {
        if only.as_ref().is_some_and(|o| *o != id) {
            continue;
        }
        // the soft rods' modal segments are refused as the rod falls (0.131 s, 0.153 s:
        // docs/engine-findings.md)
        let steps = if id == "soft_rod_hybrid" || id == "soft_rod_modal" {
            100
        } else if LONG.contains(&id.as_str()) {
            10_000
        } else {
            1000
        };
        let n = count(&id, &scene, 1e-3, 20, steps);
        report.push(format!("{id}: {n} allocations in {steps} steps"));
        if n != 0 {
            failed.push(format!("{id}: {n} allocations in {steps} steps"));
        }
    }
    for r in &report {
        eprintln!("{r}");
    }
    assert!(failed.is_empty(), "allocations in the step: {failed:?}");
}

/// The same with the ESDIRK4's error control (`solver.error_tolerance`): its estimate's
/// working memory is sized with the integrator, its rejected attempts redo a step from the same
/// state (every shipped scene but the real-time ones, which refuse it; 200 steps each, the
/// soft rods with modal segments 100).
#[test]
fn no_heap_allocation_in_an_error_controlled_step() {
    let mut failed = Vec::new();
    for (id, scene) in scenes() {
        if id.ends_with("_rt") {
            continue;
        }
        let text = scene.replacen(
            "[solver]\n",
            "[solver]\nmethod = \"esdirk4\"\nerror_tolerance = 1e-6\n",
            1,
        );
        assert!(text.contains("error_tolerance"), "{id}");
        // the soft rods' modal segments are refused at 0.131 s and 0.153 s, as above
        let steps = if id.starts_with("soft_rod_") {
            100
        } else {
            200
        };
        let n = count(&format!("{id}-controlled"), &text, 1e-3, 20, steps);
        eprintln!("{id} (error control): {n} allocations in {steps} steps");
        if n != 0 {
            failed.push(format!("{id}: {n} allocations in {steps} steps"));
        }
    }
    assert!(failed.is_empty(), "allocations in the step: {failed:?}");
}
