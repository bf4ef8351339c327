//! FMI overhead of one fmi2DoStep: the exported C symbol (shim, pointer check, catch_unwind,
//! state table, argument and communication-point checks, logging off) against the toy model's
//! own `do_step`, with one internal substep per call. Overhead = difference of the two times.
//!
//! `cargo bench -p fmi2-toy --bench fmi_overhead`
#![allow(missing_docs)] // criterion's macros generate undocumented items

use std::ffi::CString;
use std::hint::black_box;
use std::ptr;

use criterion::{criterion_group, criterion_main, Criterion};
use fmi2::types::fmi2CallbackFunctions;
use fmi2::CoSimModel;
use fmi2_toy::fmi2_exports as fmu;
use fmi2_toy::Toy;

const RESOURCE: &str = include_str!("../toy.toml");
/// Equal to the toy's internal step: one substep per call.
const H: f64 = 1e-3;

fn fmi_overhead(c: &mut Criterion) {
    let mut group = c.benchmark_group("fmi_overhead");

    let mut model = Toy::from_resource(RESOURCE).unwrap();
    model.initialize(0.0).unwrap();
    let mut t = 0.0;
    group.bench_function("model do_step (direct)", |b| {
        b.iter(|| {
            model.do_step(black_box(t), black_box(H)).unwrap();
            t += H;
        })
    });

    let dir = std::env::temp_dir().join(format!("fmi2-toy-bench-{}", std::process::id()));
    let resources = dir.join("resources");
    std::fs::create_dir_all(&resources).unwrap();
    std::fs::write(resources.join(Toy::RESOURCE), RESOURCE).unwrap();
    let callbacks = fmi2CallbackFunctions {
        logger: None,
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: ptr::null_mut(),
    };
    let name = CString::new("bench").unwrap();
    let guid = CString::new(fmi2::guid::guid::<Toy>(RESOURCE.as_bytes())).unwrap();
    let uri = CString::new(format!("file://{}", resources.display())).unwrap();
    // SAFETY: valid arguments per the FMI 2.0 contract; the instance is freed below.
    unsafe {
        let inst = fmu::fmi2Instantiate(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            uri.as_ptr(),
            &callbacks,
            0,
            0,
        );
        assert!(!inst.is_null());
        assert_eq!(fmu::fmi2SetupExperiment(inst, 0, 0.0, 0.0, 0, 0.0), 0);
        assert_eq!(fmu::fmi2EnterInitializationMode(inst), 0);
        assert_eq!(fmu::fmi2ExitInitializationMode(inst), 0);
        let mut t = 0.0;
        let mut failures = 0u64;
        group.bench_function("fmi2DoStep (FMI layer + model)", |b| {
            b.iter(|| {
                let s = fmu::fmi2DoStep(black_box(inst), black_box(t), black_box(H), 1);
                failures += (s != 0) as u64;
                t += H;
            })
        });
        assert_eq!(failures, 0, "fmi2DoStep failed during the benchmark");
        fmu::fmi2FreeInstance(inst);
    }
    let _ = std::fs::remove_dir_all(&dir);
    group.finish();
}

criterion_group!(benches, fmi_overhead);
criterion_main!(benches);
