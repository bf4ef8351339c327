//! FMI 2.0 host tests through the C ABI of the built cdylib (see `host/mod.rs`).
//!
//! Model-agnostic where possible: variables are found by name (`tip.force.*`, `tip.position.*`)
//! or by causality/variability, so the tests also run on the beam FMU after the merge.
//! `HUGE_FORCE` must make the model's step fail (the toy refuses |F| > max_force).

mod host;

use std::ffi::{c_char, CString};
use std::ptr;

use host::*;
use hybeam::fmi::model::{Causality, Variability};
use hybeam::fmi::types::*;

const H: f64 = 0.01;
const HUGE_FORCE: f64 = 1e9;

fn outputs() -> Vec<u32> {
    vrs_where(|v| v.causality == Causality::Output)
}

fn forces() -> [u32; 2] {
    [vr("tip.force.x"), vr("tip.force.y")]
}

/// Runs `n` steps from `t0 = start` with t = start + k·h and a force schedule; returns the
/// outputs after every step.
fn run(inst: &Inst, start_step: usize, n: usize) -> Vec<Vec<f64>> {
    let outs = outputs();
    let mut rows = Vec::new();
    for k in start_step..start_step + n {
        let t = k as f64 * H;
        // forces within the beam's small-deformation range (Case 1 rod: PL²/EI = 1 at 1 N)
        let fx = if k % 40 < 20 { 0.03 } else { -0.02 };
        assert_eq!(
            inst.set_real(&forces(), &[fx, 0.005 * (k as f64 * 0.1).sin()]),
            OK
        );
        assert_eq!(inst.do_step(t, H), OK, "{:?}", inst.log.entries());
        rows.push(inst.get_real(&outs).unwrap());
    }
    rows
}

fn bits(rows: &[Vec<f64>]) -> Vec<Vec<u64>> {
    rows.iter()
        .map(|r| r.iter().map(|x| x.to_bits()).collect())
        .collect()
}

#[test]
fn platform_and_version() {
    let api = api();
    let s = |p: *const c_char| {
        unsafe { std::ffi::CStr::from_ptr(p) }
            .to_str()
            .unwrap()
            .to_owned()
    };
    assert_eq!(s(unsafe { api.get_types_platform.unwrap()() }), "default");
    assert_eq!(s(unsafe { api.get_version.unwrap()() }), "2.0");
}

#[test]
fn full_call_sequence() {
    let inst = Inst::new("full");
    let fixed =
        vrs_where(|v| v.causality == Causality::Parameter && v.variability == Variability::Fixed);
    // Parameters may be set in instantiated and initialization mode (a last one wins).
    let p0 = *fixed.last().unwrap();
    let start = start_of(p0);
    assert_eq!(inst.set_real(&[p0], &[1.5 * start]), OK);
    assert_eq!(inst.setup(0.0, Some(1.0)), OK);
    assert_eq!(inst.enter_init(), OK);
    assert_eq!(inst.set_real(&[p0], &[start]), OK);
    let x0 = inst.get1(vr("tip.position.x"));
    assert_eq!(inst.exit_init(), OK);
    let rows = run(&inst, 0, 100);
    assert_ne!(rows.last().unwrap()[0], x0, "the model moved");
    assert_eq!(inst.terminated(), (OK, false));
    let (s, t) = inst.last_successful_time();
    assert_eq!(s, OK);
    assert!((t - 1.0).abs() < 1e-12, "{t}");
    let mut status: fmi2Status = 99;
    assert_eq!(
        unsafe { inst.api.get_status.unwrap()(inst.c, 0, &mut status) },
        OK
    );
    assert_eq!(status, OK);
    assert_eq!(inst.terminate(), OK);
    assert!(
        inst.get_real(&outputs()).is_ok(),
        "outputs readable after terminate"
    );
    // Reset: back to instantiated; a second run reproduces the first bit for bit.
    assert_eq!(inst.reset(), OK);
    assert_eq!(inst.set_real(&[p0], &[start]), OK);
    assert_eq!(inst.setup(0.0, Some(1.0)), OK);
    assert_eq!(inst.enter_init(), OK);
    assert_eq!(inst.exit_init(), OK);
    assert_eq!(bits(&run(&inst, 0, 100)), bits(&rows));
    inst.assert_no_problems();
}

#[test]
fn illegal_call_sequences_are_errors_with_messages() {
    let inst = Inst::new("sequence");
    assert_eq!(inst.do_step(0.0, H), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &[
            "fmi2DoStep",
            "illegal call sequence",
            "stepComplete",
            "instantiated",
        ],
    );
    assert_eq!(inst.exit_init(), ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["fmi2ExitInitializationMode"]);
    assert_eq!(inst.terminate(), ERROR);
    assert!(
        inst.get_real(&outputs()).is_err(),
        "no GetReal before initialization mode"
    );
    assert_eq!(inst.enter_init(), OK);
    assert_eq!(
        inst.setup(0.0, None),
        ERROR,
        "SetupExperiment only when instantiated"
    );
    assert_eq!(inst.enter_init(), ERROR);
    assert_eq!(inst.exit_init(), OK);
    assert_eq!(inst.exit_init(), ERROR);
    // The instance is still usable after argument/sequence errors.
    assert_eq!(inst.do_step(0.0, H), OK);
    // After terminate: no more steps.
    assert_eq!(inst.terminate(), OK);
    assert_eq!(inst.do_step(H, H), ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["fmi2DoStep", "terminated"]);
}

#[test]
fn set_and_get_real_errors_name_the_argument() {
    let inst = Inst::initialized("setget", None);
    let out = vr("tip.position.x");
    let [fx, fy] = forces();

    assert_eq!(inst.set_real(&[out], &[1.0]), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2SetReal", "tip.position.x", "is an output"],
    );

    assert_eq!(inst.get_real(&[999]), Err(ERROR));
    assert_eq!(
        inst.log.last().message,
        "fmi2GetReal: value reference 999 is not a variable of this model"
    );
    assert_eq!(inst.set_real(&[999], &[0.0]), ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["fmi2SetReal", "999"]);

    // NULL arrays with n > 0.
    let mut v = [0.0f64; 2];
    let st = unsafe { inst.api.get_real.unwrap()(inst.c, ptr::null(), 2, v.as_mut_ptr()) };
    assert_eq!(st, ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2GetReal", "vr[] is NULL", "nvr = 2"],
    );
    let st = unsafe { inst.api.get_real.unwrap()(inst.c, [out].as_ptr(), 1, ptr::null_mut()) };
    assert_eq!(st, ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["value[] is NULL"]);
    let st = unsafe { inst.api.set_real.unwrap()(inst.c, [fx].as_ptr(), 1, ptr::null()) };
    assert_eq!(st, ERROR);
    // n = 0 with NULL arrays is fine.
    let st = unsafe { inst.api.get_real.unwrap()(inst.c, ptr::null(), 0, ptr::null_mut()) };
    assert_eq!(st, OK);

    // NaN / Inf refused, and nothing of the call is applied.
    assert_eq!(inst.set_real(&[fx], &[4.0]), OK);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(inst.set_real(&[fx, fy], &[7.0, bad]), ERROR);
        inst.log
            .assert_last(ERROR, "logStatusError", &["tip.force.y", "not finite"]);
        assert_eq!(inst.get_real(&[fx, fy]).unwrap(), vec![4.0, 0.0]);
    }

    // Fixed parameters only before the end of initialization; tunable ones any time.
    let fixed =
        vrs_where(|v| v.causality == Causality::Parameter && v.variability == Variability::Fixed);
    let p = fixed[0];
    let before = inst.get1(p);
    assert_eq!(inst.set_real(&[p], &[before * 2.0]), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["fixed parameter", "stepComplete"],
    );
    assert_eq!(inst.get1(p), before);
    let tunable =
        vrs_where(|v| v.causality == Causality::Parameter && v.variability == Variability::Tunable);
    if let Some(&t) = tunable.first() {
        assert_eq!(inst.set_real(&[t], &[inst.get1(t)]), OK);
    }
}

#[test]
fn bad_steps_are_errors() {
    let inst = Inst::initialized("steps", Some(1.0));
    for h in [0.0, -H, f64::NAN, f64::INFINITY] {
        assert_eq!(inst.do_step(0.0, h), ERROR, "h = {h}");
        inst.log.assert_last(
            ERROR,
            "logStatusError",
            &["fmi2DoStep", "communicationStepSize"],
        );
    }
    assert_eq!(inst.do_step(0.5, H), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["currentCommunicationPoint = 0.5", "FMU time 0"],
    );
    assert_eq!(inst.do_step(f64::NAN, H), ERROR);
    // Host-style drift (t0 + n·h vs a running sum) is accepted.
    let mut t_sum = 0.0;
    for n in 0..50 {
        let t = if n % 2 == 0 { n as f64 * H } else { t_sum };
        assert_eq!(inst.do_step(t, H), OK, "n = {n}: {:?}", inst.log.last());
        t_sum += H;
    }
    // Beyond stopTime.
    assert_eq!(inst.do_step(0.5, 0.6), ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["beyond stopTime = 1"]);
    // Up to stopTime exactly (with rounding) is fine.
    for n in 50..100 {
        assert_eq!(inst.do_step(n as f64 * H, H), OK);
    }
    assert_eq!(inst.last_successful_time().1, 100.0 * H);
}

#[test]
fn instantiate_failures_return_null_with_a_reason() {
    type Change = Box<dyn Fn(&mut InstantiateArgs)>;
    let cases: Vec<(&str, Change, &[&str])> = vec![
        (
            "guid",
            Box::new(|a| a.guid = "{00000000-0000-0000-0000-000000000000}".into()),
            &["fmuGUID", "does not match"],
        ),
        (
            "me",
            Box::new(|a| a.fmu_type = 0),
            &["fmuType = 0", "fmi2ModelExchange"],
        ),
        (
            "missing",
            Box::new(|a| a.location = Some("file:///nonexistent/hybeam/resources".into())),
            &["/nonexistent/hybeam/resources", "does not exist"],
        ),
        (
            "null",
            Box::new(|a| a.location = None),
            &["fmuResourceLocation is NULL"],
        ),
        (
            "http",
            Box::new(|a| a.location = Some("http://example/resources".into())),
            &["not a file URI"],
        ),
        (
            "empty",
            Box::new(|a| {
                let dir = temp_dir("empty-res");
                a.location = Some(file_uri(&dir));
            }),
            &["cannot read", "scene.toml"],
        ),
        (
            "badscene",
            Box::new(|a| {
                let bad = "[model]\nname = 1\n";
                a.location = Some(file_uri(&resources_with(bad, "badscene")));
                a.guid = guid_of(bad);
            }),
            &["invalid resources/scene.toml"],
        ),
    ];
    for (tag, change, parts) in cases {
        let mut args = InstantiateArgs::valid(tag);
        change(&mut args);
        let (c, log) = instantiate_raw(&args);
        assert!(c.is_null(), "{tag}");
        log.assert_last(ERROR, "logStatusError", parts);
        assert!(log.last().message.starts_with("fmi2Instantiate: "), "{tag}");
        assert_eq!(log.last().format, "%s");
        assert_eq!(log.last().instance, args.name);
    }
    // NULL callbacks: NULL, nothing to log to.
    let name = CString::new("x").unwrap();
    let c = unsafe {
        api().instantiate.unwrap()(
            name.as_ptr(),
            1,
            name.as_ptr(),
            name.as_ptr(),
            ptr::null(),
            0,
            0,
        )
    };
    assert!(c.is_null());
}

#[test]
fn resource_uri_forms() {
    let spaced = temp_dir("uri").join("my resources");
    std::fs::create_dir_all(&spaced).unwrap();
    std::fs::write(spaced.join("scene.toml"), SCENE).unwrap();
    let plain = spaced.display().to_string();
    for location in [
        format!("file://{}", plain.replace(' ', "%20")),
        format!("file://{}/", plain.replace(' ', "%20")),
        format!("file:{}", plain.replace(' ', "%20")),
        format!("file://localhost{}", plain.replace(' ', "%20")),
    ] {
        let mut args = InstantiateArgs::valid("uri");
        args.location = Some(location.clone());
        let (c, log) = instantiate_raw(&args);
        assert!(!c.is_null(), "{location}: {:?}", log.entries());
        unsafe { api().free_instance.unwrap()(c) };
    }
}

#[test]
fn fmu_state_round_trips_bit_for_bit() {
    let inst = Inst::initialized("state", None);
    run(&inst, 0, 10);
    let mut s = inst.get_state();
    let a = run(&inst, 10, 30);
    // Restore in place: same outputs.
    assert_eq!(inst.set_state(s), OK);
    assert_eq!(bits(&run(&inst, 10, 30)), bits(&a));
    // Overwrite an existing state in place (GetFMUstate with *state != NULL).
    let mut s2 = inst.get_state();
    assert_eq!(
        unsafe { inst.api.get_fmu_state.unwrap()(inst.c, &mut s2) },
        OK
    );
    assert_eq!(inst.free_state(&mut s2), OK);
    assert!(s2.is_null());
    // Serialize, restore into a NEW instance, continue: same bits.
    let bytes = inst.serialize(s);
    let other = Inst::new("state-other");
    let (st, restored) = other.deserialize(&bytes);
    assert_eq!(st, OK);
    assert_eq!(other.set_state(restored), OK, "{:?}", other.log.entries());
    assert_eq!(bits(&run(&other, 10, 30)), bits(&a));
    // Serialize again: identical bytes (deterministic).
    assert_eq!(other.serialize(restored), bytes);
    // Wrong size for SerializeFMUstate.
    let mut buf = vec![0u8; bytes.len() + 1];
    let st = unsafe {
        inst.api.serialize_fmu_state.unwrap()(inst.c, s, buf.as_mut_ptr() as *mut _, buf.len())
    };
    assert_eq!(st, ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2SerializeFMUstate", "size ="],
    );
    // Garbage and corrupted bytes are refused.
    for garbage in [b"garbage".to_vec(), vec![0u8; bytes.len()], {
        let mut c = bytes.clone();
        let mid = c.len() / 2;
        c[mid] ^= 1;
        c
    }] {
        let (st, p) = inst.deserialize(&garbage);
        assert_eq!(st, ERROR);
        assert!(p.is_null());
        inst.log.assert_last(
            ERROR,
            "logStatusError",
            &["fmi2DeSerializeFMUstate", "refused"],
        );
    }
    let (st, _) = inst.deserialize(&[]);
    assert_eq!(st, ERROR);
    // Free: NULL *state is fine; a freed state is refused.
    let dangling = s;
    assert_eq!(inst.free_state(&mut s), OK);
    let mut null: fmi2FMUstate = ptr::null_mut();
    assert_eq!(inst.free_state(&mut null), OK);
    let mut r = restored;
    assert_eq!(other.free_state(&mut r), OK);
    let _ = dangling; // (not dereferenced: using a freed state is undefined for any FMU)
    inst.assert_no_problems_except_errors();
}

trait NoProblemsExceptErrors {
    fn assert_no_problems_except_errors(&self);
}
impl NoProblemsExceptErrors for Inst {
    fn assert_no_problems_except_errors(&self) {
        assert!(self
            .log
            .entries()
            .iter()
            .all(|e| e.status == 0 || e.status == ERROR));
    }
}

#[test]
fn failing_step_discards_terminates_and_keeps_state() {
    let inst = Inst::initialized("discard", None);
    run(&inst, 0, 20);
    let before = inst.get_real(&outputs()).unwrap();
    let saved = inst.get_state();
    let t = 20.0 * H;
    assert_eq!(inst.set_real(&forces(), &[HUGE_FORCE, 0.0]), OK);
    assert_eq!(inst.do_step(t, H), DISCARD);
    inst.log
        .assert_last(DISCARD, "logStatusDiscard", &["fmi2DoStep", "failed"]);
    assert_eq!(inst.terminated(), (OK, true));
    let (s, last) = inst.last_successful_time();
    assert_eq!(s, OK);
    assert_eq!(last, t);
    let mut status: fmi2Status = 99;
    assert_eq!(
        unsafe { inst.api.get_status.unwrap()(inst.c, 0, &mut status) },
        OK
    );
    assert_eq!(status, DISCARD);
    assert_eq!(bits(&[inst.get_real(&outputs()).unwrap()]), bits(&[before]));
    assert_eq!(inst.do_step(t, H), ERROR, "no DoStep in stepFailed");
    // Rollback to the saved state: the simulation can go on.
    assert_eq!(inst.set_state(saved), OK);
    assert_eq!(inst.terminated(), (OK, false));
    run(&inst, 20, 5);
    let mut s = saved;
    assert_eq!(inst.free_state(&mut s), OK);
    // Terminate is legal after a failed step.
    let inst2 = Inst::initialized("discard2", None);
    assert_eq!(inst2.set_real(&forces(), &[0.0, -HUGE_FORCE]), OK);
    assert_eq!(inst2.do_step(0.0, H), DISCARD);
    assert_eq!(inst2.terminate(), OK);
}

#[test]
fn two_threads_give_the_bits_of_one_instance_alone() {
    let alone = {
        let inst = Inst::initialized("alone", None);
        run(&inst, 0, 200)
    };
    let handles: Vec<_> = (0..2)
        .map(|i| {
            std::thread::spawn(move || {
                let inst = Inst::initialized(&format!("thread{i}"), None);
                run(&inst, 0, 200)
            })
        })
        .collect();
    for h in handles {
        assert_eq!(bits(&h.join().unwrap()), bits(&alone));
    }
}

#[test]
fn unsupported_functions_exist_and_return_error() {
    let inst = Inst::initialized("unsupported", None);
    let api = inst.api;
    let c = inst.c;
    let vr0 = [vr("tip.position.x")];
    let mut x = [0.0f64; 1];
    let order = [1 as fmi2Integer];
    let mut i = [0 as fmi2Integer; 1];
    let mut b = [0 as fmi2Boolean; 1];
    let mut s: [fmi2String; 1] = [ptr::null()];
    unsafe {
        let calls: Vec<(fmi2Status, &str)> = vec![
            (
                api.get_directional_derivative.unwrap()(
                    c,
                    vr0.as_ptr(),
                    1,
                    vr0.as_ptr(),
                    1,
                    x.as_ptr(),
                    x.as_mut_ptr(),
                ),
                "fmi2GetDirectionalDerivative",
            ),
            (
                api.set_real_input_derivatives.unwrap()(
                    c,
                    vr0.as_ptr(),
                    1,
                    order.as_ptr(),
                    x.as_ptr(),
                ),
                "fmi2SetRealInputDerivatives",
            ),
            (
                api.get_real_output_derivatives.unwrap()(
                    c,
                    vr0.as_ptr(),
                    1,
                    order.as_ptr(),
                    x.as_mut_ptr(),
                ),
                "fmi2GetRealOutputDerivatives",
            ),
            (api.cancel_step.unwrap()(c), "fmi2CancelStep"),
            (
                api.get_integer.unwrap()(c, vr0.as_ptr(), 1, i.as_mut_ptr()),
                "not an Integer variable",
            ),
            (
                api.get_boolean.unwrap()(c, vr0.as_ptr(), 1, b.as_mut_ptr()),
                "not a Boolean variable",
            ),
            (
                api.get_string.unwrap()(c, vr0.as_ptr(), 1, s.as_mut_ptr()),
                "not a String variable",
            ),
            (
                api.set_integer.unwrap()(c, vr0.as_ptr(), 1, i.as_ptr()),
                "fmi2SetInteger",
            ),
            (
                api.set_boolean.unwrap()(c, vr0.as_ptr(), 1, b.as_ptr()),
                "fmi2SetBoolean",
            ),
            (
                api.set_string.unwrap()(c, vr0.as_ptr(), 1, s.as_ptr()),
                "fmi2SetString",
            ),
            (
                api.get_integer_status.unwrap()(c, 0, i.as_mut_ptr()),
                "fmi2GetIntegerStatus",
            ),
            (
                api.get_string_status.unwrap()(c, 1, s.as_mut_ptr()),
                "fmi2GetStringStatus",
            ),
            (
                api.get_real_status.unwrap()(c, 0, x.as_mut_ptr()),
                "fmi2GetRealStatus: status kind 0",
            ),
            (
                api.get_boolean_status.unwrap()(c, 0, b.as_mut_ptr()),
                "fmi2GetBooleanStatus: status kind 0",
            ),
        ];
        for (status, part) in calls {
            assert_eq!(status, ERROR, "{part}");
            // Each call's own message is the last one logged at that time; check it was logged.
            assert!(
                inst.log.entries().iter().any(|e| e.message.contains(part)),
                "{part}"
            );
        }
        // Zero-length Integer access is fine.
        assert_eq!(
            api.get_integer.unwrap()(c, ptr::null(), 0, ptr::null_mut()),
            OK
        );
    }
}

#[test]
fn null_or_freed_component_is_an_error_not_a_crash() {
    let api = api();
    unsafe {
        assert_eq!(api.do_step.unwrap()(ptr::null_mut(), 0.0, H, 0), ERROR);
        assert_eq!(
            api.enter_initialization_mode.unwrap()(ptr::null_mut()),
            ERROR
        );
        assert_eq!(
            api.get_real.unwrap()(ptr::null_mut(), ptr::null(), 0, ptr::null_mut()),
            ERROR
        );
        api.free_instance.unwrap()(ptr::null_mut());
    }
}

#[test]
fn debug_logging_categories() {
    let inst = Inst::initialized("logging", None);
    inst.log.clear();
    assert_eq!(inst.do_step(0.0, H), OK);
    assert!(inst.log.entries().is_empty(), "logging off: no trace");
    let set = |on: bool, cats: &[&str]| {
        let owned: Vec<CString> = cats.iter().map(|c| CString::new(*c).unwrap()).collect();
        let ptrs: Vec<*const c_char> = owned.iter().map(|c| c.as_ptr()).collect();
        unsafe {
            inst.api.set_debug_logging.unwrap()(
                inst.c,
                on as fmi2Boolean,
                ptrs.len(),
                ptrs.as_ptr(),
            )
        }
    };
    assert_eq!(set(true, &["logAll"]), OK);
    assert_eq!(inst.do_step(H, H), OK);
    inst.log
        .assert_last(OK, "logAll", &["fmi2DoStep: t = 0.01, h = 0.01"]);
    assert_eq!(set(true, &["logNothing"]), ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["categories[0] = \"logNothing\""]);
    let null_list = unsafe { inst.api.set_debug_logging.unwrap()(inst.c, 1, 2, ptr::null()) };
    assert_eq!(null_list, ERROR);
    // Everything off: even errors are silent.
    assert_eq!(set(false, &[]), OK);
    inst.log.clear();
    assert_eq!(inst.do_step(5.0, H), ERROR);
    assert!(inst.log.entries().is_empty());
    // Instantiate with loggingOn = true traces from the start.
    let mut args = InstantiateArgs::valid("logging-on");
    args.logging_on = true;
    let (c, log) = instantiate_raw(&args);
    assert!(!c.is_null());
    log.assert_last(OK, "logAll", &["fmi2Instantiate"]);
    unsafe { api().free_instance.unwrap()(c) };
}
