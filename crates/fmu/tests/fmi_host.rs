//! FMI 2.0 host tests through the C ABI of the built cdylib (see `host/mod.rs`).
//!
//! Variables are found by name (`tip.force.*`, `tip.position.*`) or by causality/variability,
//! not by value reference. `HUGE_FORCE` must make the model's step fail (the beam refuses it:
//! no convergence or beyond its validity).

mod host;

use std::ffi::{c_char, CString};
use std::ptr;

use fmi2::types::*;
use fmi2::{Causality, CoSimModel, Variability};
use host::*;

const H: f64 = 0.01;
/// The magic of the beam's serialized FMU states.
const MAGIC: [u8; 8] = <hybeam_fmu::FmuModel as CoSimModel>::STATE_MAGIC;
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
    // NULL and misaligned FMU states are refused without being read
    assert_eq!(inst.set_state(ptr::null_mut()), ERROR);
    assert_eq!(inst.set_state(1usize as fmi2FMUstate), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2SetFMUstate", "is not an FMU state of this FMU"],
    );
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

/// Issue 8 item 4: a failing step (no convergence, or a refusal) is a recoverable fmi2Discard:
/// the model keeps its state, fmi2Terminated stays false (a master that honours it would stop
/// instead of retrying), and rolling back with fmi2SetFMUstate continues bit for bit.
#[test]
fn failing_step_is_a_recoverable_discard_that_keeps_the_state() {
    let inst = Inst::initialized("discard", None);
    run(&inst, 0, 10);
    let saved = inst.get_state();
    let expected = run(&inst, 10, 10);
    let before = inst.get_real(&outputs()).unwrap();
    let t = 20.0 * H;
    assert_eq!(inst.set_real(&forces(), &[HUGE_FORCE, 0.0]), OK);
    assert_eq!(inst.do_step(t, H), DISCARD);
    inst.log.assert_last(
        DISCARD,
        "logStatusDiscard",
        &["fmi2DoStep", "t = 0.2", "failed", "fmi2Terminated = false"],
    );
    assert_eq!(
        inst.terminated(),
        (OK, false),
        "recoverable: not terminated"
    );
    assert_eq!(inst.last_successful_time(), (OK, t));
    let mut status: fmi2Status = 99;
    assert_eq!(
        unsafe { inst.api.get_status.unwrap()(inst.c, 0, &mut status) },
        OK
    );
    assert_eq!(status, DISCARD);
    assert_eq!(bits(&[inst.get_real(&outputs()).unwrap()]), bits(&[before]));
    assert_eq!(inst.do_step(t, H), ERROR, "no DoStep in stepFailed");
    // Roll back ten steps and go again: the same bits as the first time.
    assert_eq!(inst.set_state(saved), OK);
    assert_eq!(inst.terminated(), (OK, false));
    assert_eq!(bits(&run(&inst, 10, 10)), bits(&expected));
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

/// Every function that takes an instance refuses a NULL or misaligned `fmi2Component` with
/// fmi2Error (fmi2FreeInstance ignores it), without reading through it. A freed or foreign
/// pointer is outside the FMI 2.0 contract and is not detected: checking it would mean reading
/// memory the FMU may no longer own, or a process-wide registry of instances
/// (`fmi2::guard`, docs/fmi-layer.md).
#[test]
fn null_or_misaligned_component_is_an_error_not_a_crash() {
    let api = api();
    let mut st: fmi2FMUstate = ptr::null_mut();
    let (mut size, mut x) = (0usize, 0.0f64);
    let (mut status, mut b, mut i) = (0 as fmi2Status, 0 as fmi2Boolean, 0 as fmi2Integer);
    let mut s: fmi2String = ptr::null();
    for c in [ptr::null_mut(), 1usize as fmi2Component] {
        let results: Vec<(fmi2Status, &str)> = unsafe {
            vec![
                (
                    api.set_debug_logging.unwrap()(c, 1, 0, ptr::null()),
                    "SetDebugLogging",
                ),
                (
                    api.setup_experiment.unwrap()(c, 0, 0.0, 0.0, 0, 0.0),
                    "SetupExperiment",
                ),
                (
                    api.enter_initialization_mode.unwrap()(c),
                    "EnterInitializationMode",
                ),
                (
                    api.exit_initialization_mode.unwrap()(c),
                    "ExitInitializationMode",
                ),
                (api.terminate.unwrap()(c), "Terminate"),
                (api.reset.unwrap()(c), "Reset"),
                (
                    api.get_real.unwrap()(c, ptr::null(), 0, ptr::null_mut()),
                    "GetReal",
                ),
                (
                    api.get_integer.unwrap()(c, ptr::null(), 0, ptr::null_mut()),
                    "GetInteger",
                ),
                (
                    api.get_boolean.unwrap()(c, ptr::null(), 0, ptr::null_mut()),
                    "GetBoolean",
                ),
                (
                    api.get_string.unwrap()(c, ptr::null(), 0, ptr::null_mut()),
                    "GetString",
                ),
                (
                    api.set_real.unwrap()(c, ptr::null(), 0, ptr::null()),
                    "SetReal",
                ),
                (
                    api.set_integer.unwrap()(c, ptr::null(), 0, ptr::null()),
                    "SetInteger",
                ),
                (
                    api.set_boolean.unwrap()(c, ptr::null(), 0, ptr::null()),
                    "SetBoolean",
                ),
                (
                    api.set_string.unwrap()(c, ptr::null(), 0, ptr::null()),
                    "SetString",
                ),
                (api.get_fmu_state.unwrap()(c, &mut st), "GetFMUstate"),
                (api.set_fmu_state.unwrap()(c, st), "SetFMUstate"),
                (api.free_fmu_state.unwrap()(c, &mut st), "FreeFMUstate"),
                (
                    api.serialized_fmu_state_size.unwrap()(c, st, &mut size),
                    "SerializedFMUstateSize",
                ),
                (
                    api.serialize_fmu_state.unwrap()(c, st, ptr::null_mut(), 0),
                    "SerializeFMUstate",
                ),
                (
                    api.deserialize_fmu_state.unwrap()(c, ptr::null(), 0, &mut st),
                    "DeSerializeFMUstate",
                ),
                (
                    api.get_directional_derivative.unwrap()(
                        c,
                        ptr::null(),
                        0,
                        ptr::null(),
                        0,
                        ptr::null(),
                        ptr::null_mut(),
                    ),
                    "GetDirectionalDerivative",
                ),
                (
                    api.set_real_input_derivatives.unwrap()(
                        c,
                        ptr::null(),
                        0,
                        ptr::null(),
                        ptr::null(),
                    ),
                    "SetRealInputDerivatives",
                ),
                (
                    api.get_real_output_derivatives.unwrap()(
                        c,
                        ptr::null(),
                        0,
                        ptr::null(),
                        ptr::null_mut(),
                    ),
                    "GetRealOutputDerivatives",
                ),
                (api.do_step.unwrap()(c, 0.0, H, 0), "DoStep"),
                (api.cancel_step.unwrap()(c), "CancelStep"),
                (api.get_status.unwrap()(c, 0, &mut status), "GetStatus"),
                (api.get_real_status.unwrap()(c, 2, &mut x), "GetRealStatus"),
                (
                    api.get_integer_status.unwrap()(c, 0, &mut i),
                    "GetIntegerStatus",
                ),
                (
                    api.get_boolean_status.unwrap()(c, 3, &mut b),
                    "GetBooleanStatus",
                ),
                (
                    api.get_string_status.unwrap()(c, 1, &mut s),
                    "GetStringStatus",
                ),
            ]
        };
        assert_eq!(results.len(), 30);
        for (result, name) in results {
            assert_eq!(result, ERROR, "fmi2{name}({c:p})");
        }
        unsafe { api.free_instance.unwrap()(c) };
    }
    assert!(st.is_null() && s.is_null(), "nothing was written");
}

#[test]
fn debug_logging_categories() {
    let inst = Inst::initialized("logging", None);
    inst.log.clear();
    assert_eq!(inst.do_step(0.0, H), OK);
    assert!(inst.log.entries().is_empty(), "logging off: no trace");
    let set = |on: bool, cats: &[&str]| inst.set_logging(on, cats);
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

// ---------------------------------------------------------------------------------------------
// Issue 8: hardening after the outside FMI audit
// ---------------------------------------------------------------------------------------------

/// The smallest `solver.max_step` (and held internal step) the model accepts [s]
/// (docs/fmi-layer.md, "Step-size bounds").
const MIN_STEP: f64 = 1e-8;

/// Item 1: `solver.max_step` below the bound is refused by the scene validation, the parameter
/// setter and the snapshot reader alike, each with a message naming the bound.
#[test]
fn step_size_below_the_bound_is_refused_by_scene_setter_and_snapshot() {
    let below = [1e-12, 1e-300, 5e-324, 0.999 * MIN_STEP];
    // scene validation
    for h in below {
        let scene = SCENE.replace("max_step = 1e-4", &format!("max_step = {h:e}"));
        assert_ne!(scene, SCENE);
        let e = hybeam::scene::Scene::from_toml(&scene).unwrap_err().0;
        assert!(e.contains("solver.max_step") && e.contains("1e-8"), "{e}");
    }
    // parameter setter (fixed parameter, before initialization)
    let inst = Inst::new("minstep-set");
    let p = vr("solver.max_step");
    for h in below {
        assert_eq!(inst.set_real(&[p], &[h]), ERROR, "max_step = {h:e}");
        inst.log
            .assert_last(ERROR, "logStatusError", &["solver.max_step", "1e-8"]);
    }
    assert_eq!(
        inst.set_real(&[p], &[MIN_STEP]),
        OK,
        "the bound itself is allowed"
    );
    // snapshot reader: a saved state whose held internal step is below the bound (checksum
    // recomputed, as anyone can), and one whose max_step parameter is
    let inst = Inst::initialized("minstep-snap", None);
    run(&inst, 0, 3);
    let mut s = inst.get_state();
    let bytes = inst.serialize(s);
    let guid = guid_of(SCENE);
    let max_step = start_of(p);
    for (what, skip) in [("held step", 1), ("max_step parameter", 0)] {
        for h in below {
            let mut st = fmi2::fmu_state::FmuState::deserialize(&bytes, &MAGIC, &guid).unwrap();
            let n = replace_f64(&mut st.model, max_step, h, skip);
            assert!(n >= 1, "{what}: no field holds {max_step:e}");
            let (status, mut crafted) = inst.deserialize(&st.serialize(&MAGIC, &guid));
            assert_eq!(status, OK, "the envelope is valid");
            assert_eq!(inst.set_state(crafted), ERROR, "{what} = {h:e}");
            inst.log
                .assert_last(ERROR, "logStatusError", &["fmi2SetFMUstate", "1e-8"]);
            assert_eq!(inst.free_state(&mut crafted), OK);
        }
    }
    assert_eq!(inst.do_step(3.0 * H, H), OK, "the instance is unchanged");
    assert_eq!(inst.free_state(&mut s), OK);
}

/// Items 1 and 4: a communication step that needs more internal steps than the cap is refused
/// at once with fmi2Discard (a message that says what to change, the state kept, not
/// terminated); restoring the FMU state and retrying with a smaller step continues.
#[test]
fn work_cap_discards_a_long_step_and_a_smaller_retry_continues() {
    let inst = Inst::initialized("cap", None);
    run(&inst, 0, 5);
    let t = 5.0 * H;
    let before = inst.get_real(&outputs()).unwrap();
    let mut saved = inst.get_state();
    let start = std::time::Instant::now();
    assert_eq!(inst.do_step(t, 100.0), DISCARD);
    eprintln!("refused 100 s step in {:?}", start.elapsed());
    inst.log.assert_last(
        DISCARD,
        "logStatusDiscard",
        &[
            "fmi2DoStep",
            "solver.max_internal_steps",
            "split",
            "solver.max_step",
        ],
    );
    assert_eq!(inst.terminated(), (OK, false));
    assert_eq!(inst.last_successful_time(), (OK, t));
    assert_eq!(bits(&[inst.get_real(&outputs()).unwrap()]), bits(&[before]));
    assert_eq!(inst.do_step(t, H), ERROR, "no DoStep in stepFailed");
    // retry with a smaller step after restoring the state at the start of the failed step
    assert_eq!(inst.set_state(saved), OK);
    let rows = run(&inst, 5, 5);
    // the same as an instance that never tried the long step
    let other = Inst::initialized("cap-other", None);
    run(&other, 0, 5);
    assert_eq!(bits(&run(&other, 5, 5)), bits(&rows));
    assert_eq!(inst.free_state(&mut saved), OK);
}

/// Item 2: a status kind that is not available is fmi2Discard (FMI 2.0 §4.2.3), logged in
/// `logStatusDiscard`; a value that is no status kind at all is a bad argument (fmi2Error).
#[test]
fn unavailable_status_kinds_are_discard() {
    let inst = Inst::initialized("status", None);
    assert_eq!(inst.do_step(0.0, H), OK);
    let (api, c) = (inst.api, inst.c);
    let mut st: fmi2Status = 99;
    let mut x = 0.0f64;
    let mut i: fmi2Integer = 0;
    let mut b: fmi2Boolean = 0;
    let mut s: fmi2String = ptr::null();
    // kinds: 0 fmi2DoStepStatus, 1 fmi2PendingStatus, 2 fmi2LastSuccessfulTime, 3 fmi2Terminated
    for kind in 0..4u32 {
        for (name, available) in [
            ("fmi2GetStatus", kind == 0),
            ("fmi2GetRealStatus", kind == 2),
            ("fmi2GetIntegerStatus", false),
            ("fmi2GetBooleanStatus", kind == 3),
            ("fmi2GetStringStatus", false),
        ] {
            let status = unsafe {
                match name {
                    "fmi2GetStatus" => api.get_status.unwrap()(c, kind, &mut st),
                    "fmi2GetRealStatus" => api.get_real_status.unwrap()(c, kind, &mut x),
                    "fmi2GetIntegerStatus" => api.get_integer_status.unwrap()(c, kind, &mut i),
                    "fmi2GetBooleanStatus" => api.get_boolean_status.unwrap()(c, kind, &mut b),
                    _ => api.get_string_status.unwrap()(c, kind, &mut s),
                }
            };
            if available {
                assert_eq!(status, OK, "{name}({kind})");
            } else {
                assert_eq!(status, DISCARD, "{name}({kind})");
                inst.log.assert_last(
                    DISCARD,
                    "logStatusDiscard",
                    &[name, &format!("status kind {kind}"), "not available"],
                );
            }
        }
    }
    assert_eq!(unsafe { api.get_real_status.unwrap()(c, 7, &mut x) }, ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["fmi2GetRealStatus", "7"]);
    assert_eq!(inst.do_step(H, H), OK, "status queries change no state");
}

/// Item 3: the shared library exports exactly the 34 fmi2 functions (nothing from dependencies,
/// e.g. a `#[no_mangle]` helper such as `fmi-sys`'s `callback_log`, which is why the FMI types are
/// checked in rather than linked from that crate, that could clash between FMUs loaded with
/// `RTLD_GLOBAL`).
#[test]
fn exports_exactly_the_34_fmi2_functions() {
    use object::{Object, ObjectSymbol};
    let path = library_path();
    let data = std::fs::read(&path).unwrap();
    let file = object::File::parse(&*data).unwrap();
    let mut exported: Vec<String> = file
        .dynamic_symbols()
        .filter(|s| s.is_definition() && s.is_global())
        .map(|s| s.name().unwrap().to_owned())
        .collect();
    exported.sort();
    let mut want: Vec<&str> = fmi2::Function::ALL.iter().map(|f| f.name()).collect();
    want.sort();
    assert_eq!(want.len(), 34);
    assert_eq!(exported, want, "{}", path.display());
}

/// Item 5: `logAll` means all messages (FMI 2.0 §2.2.4): selecting it after logging was switched
/// off brings the error messages back, not only the call trace.
#[test]
fn log_all_brings_back_every_message() {
    let inst = Inst::initialized("logall", None);
    assert_eq!(inst.set_logging(false, &[]), OK);
    inst.log.clear();
    assert_eq!(inst.do_step(5.0, H), ERROR);
    assert!(inst.log.entries().is_empty(), "everything off");
    assert_eq!(inst.set_logging(true, &["logAll"]), OK);
    assert_eq!(inst.do_step(5.0, H), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &["fmi2DoStep", "currentCommunicationPoint = 5"],
    );
    assert_eq!(inst.do_step(0.0, H), OK);
    inst.log.assert_last(OK, "logAll", &["fmi2DoStep: t = 0"]);
    // logAll off again: the status categories keep their own (off) setting
    assert_eq!(inst.set_logging(false, &["logAll"]), OK);
    inst.log.clear();
    assert_eq!(inst.do_step(5.0, H), ERROR);
    assert!(inst.log.entries().is_empty());
    // one status category alone: its messages, no trace
    assert_eq!(inst.set_logging(true, &["logStatusError"]), OK);
    assert_eq!(inst.do_step(5.0, H), ERROR);
    inst.log
        .assert_last(ERROR, "logStatusError", &["fmi2DoStep"]);
    assert_eq!(inst.do_step(H, H), OK);
    assert_eq!(
        inst.log.entries().len(),
        1,
        "no trace: {:?}",
        inst.log.entries()
    );
}

/// Item 6: a step with `t + h == t` in floating point, or from a start time so large that steps
/// no longer advance time, is a bad argument (fmi2Error, state unchanged), not accepted
/// silently or reported as a model failure.
#[test]
fn steps_that_do_not_advance_time_are_bad_arguments() {
    let inst = Inst::initialized("noadvance", None);
    run(&inst, 0, 50);
    let t = 50.0 * H;
    let before = inst.get_real(&outputs()).unwrap();
    assert_eq!(t + 1e-17, t);
    assert_eq!(inst.do_step(t, 1e-17), ERROR);
    inst.log.assert_last(
        ERROR,
        "logStatusError",
        &[
            "fmi2DoStep",
            "communicationStepSize = 1e-17",
            "does not advance",
        ],
    );
    assert_eq!(bits(&[inst.get_real(&outputs()).unwrap()]), bits(&[before]));
    assert_eq!(inst.do_step(t, H), OK, "still stepComplete");

    let big = Inst::new("bigstart");
    assert_eq!(big.setup(1e20, None), OK);
    assert_eq!(big.enter_init(), OK);
    assert_eq!(big.exit_init(), OK);
    let x0 = big.get_real(&outputs()).unwrap();
    assert_eq!(big.do_step(1e20, 1e-3), ERROR);
    big.log.assert_last(
        ERROR,
        "logStatusError",
        &["currentCommunicationPoint = 1e20", "does not advance"],
    );
    assert_eq!(bits(&[big.get_real(&outputs()).unwrap()]), bits(&[x0]));
    assert_eq!(big.last_successful_time(), (OK, 1e20));
}

/// Item 7: the URI scheme of the resource location is case-insensitive (RFC 3986 §3.1).
#[test]
fn resource_uri_scheme_is_case_insensitive() {
    let dir = resources_with(SCENE, "scheme");
    for scheme in ["FILE", "File", "fIlE"] {
        let mut args = InstantiateArgs::valid("scheme");
        args.location = Some(format!("{scheme}://{}", dir.display()));
        let (c, log) = instantiate_raw(&args);
        assert!(!c.is_null(), "{scheme}: {:?}", log.entries());
        unsafe { api().free_instance.unwrap()(c) };
    }
}

/// One timed FMI call of the acceptance run.
struct Timed {
    label: String,
    call: &'static str,
    status: fmi2Status,
    seconds: f64,
}

/// Times `f` and records its status.
fn timed(
    log: &mut Vec<Timed>,
    label: &str,
    call: &'static str,
    f: impl FnOnce() -> fmi2Status,
) -> fmi2Status {
    let start = std::time::Instant::now();
    let status = f();
    log.push(Timed {
        label: label.to_owned(),
        call,
        status,
        seconds: start.elapsed().as_secs_f64(),
    });
    status
}

/// Timed steps of H, 1 s and 1000 s from `t` until one does not return fmi2OK. Each either is
/// refused (fmi2Discard/fmi2Error) or completes within the work cap: at most `cap` internal
/// steps of at most `solver.max_step`, so `h ≤ cap · max_step` (rounding guard 1e-9).
fn steps_within_cap(log: &mut Vec<Timed>, label: &str, inst: &Inst, mut t: f64, cap: u64) {
    let max_step = inst.get1(vr("solver.max_step"));
    for h in [H, 1.0, 1000.0] {
        let status = timed(log, label, "fmi2DoStep", || inst.do_step(t, h));
        match status {
            DISCARD | ERROR => return,
            OK => assert!(
                h <= cap as f64 * max_step * (1.0 + 1e-9),
                "{label}: a step of {h} s completed with more than {cap} internal steps of {max_step:e} s"
            ),
            other => panic!("{label}: fmi2DoStep returned {other}"),
        }
        t += h;
    }
}

/// Issue 8 acceptance: extreme parameter values and crafted snapshots (tiny, huge, subnormal,
/// NaN step sizes and tolerances, and extreme physical parameters), and (issue 18) huge array
/// counts. Every call returns a refusal (fmi2Error), an fmi2Discard, or completes within the
/// work cap. Each call's wall time
/// is printed (`--nocapture`), never asserted (speed is not asserted in tests).
#[test]
fn extreme_values_and_crafted_snapshots_return_promptly() {
    let cap = hybeam::scene::Scene::from_toml(SCENE)
        .unwrap()
        .solver
        .max_internal_steps;
    let extremes = [
        1e-12,
        1e-300,
        5e-324,
        0.0,
        -1e-4,
        f64::NAN,
        f64::INFINITY,
        1e300,
        MIN_STEP,
        1.0,
    ];
    let mut calls = Vec::new();
    let p_step = vr("solver.max_step");
    // parameters set before initialization, then steps of H, 1 s and 1000 s
    let params = [
        "solver.max_step",
        "solver.tolerance",
        "solver.rho_inf",
        "gravity.y",
        "modal.length",
        "ancf.length",
        "modal.youngs_modulus",
        "ancf.density",
        "ancf.diameter",
    ];
    for name in params {
        for x in extremes {
            let label = format!("{name} = {x:e}");
            let inst = Inst::new("extreme");
            let l = &mut calls;
            let set = timed(l, &label, "fmi2SetReal", || {
                inst.set_real(&[vr(name)], &[x])
            });
            assert!(set == OK || set == ERROR, "{label}: {set}");
            if set != OK {
                continue;
            }
            assert_eq!(inst.setup(0.0, None), OK);
            assert_eq!(inst.enter_init(), OK);
            let init = timed(l, &label, "fmi2ExitInitializationMode", || inst.exit_init());
            assert!(init == OK || init == ERROR, "{label}: {init}");
            if init != OK {
                continue;
            }
            steps_within_cap(l, &label, &inst, 0.0, cap);
        }
    }
    // crafted snapshots: the held step, max_step and tolerance replaced, checksum recomputed
    let base = Inst::initialized("crafted", None);
    run(&base, 0, 3);
    let mut s = base.get_state();
    let bytes = base.serialize(s);
    assert_eq!(base.free_state(&mut s), OK);
    let guid = guid_of(SCENE);
    let max_step = start_of(p_step);
    let tolerance = start_of(vr("solver.tolerance"));
    for (what, old, skip) in [
        ("held step", max_step, 1),
        ("max_step", max_step, 0),
        ("tolerance", tolerance, 0),
    ] {
        for x in extremes {
            let label = format!("snapshot {what} = {x:e}");
            let mut st = fmi2::fmu_state::FmuState::deserialize(&bytes, &MAGIC, &guid).unwrap();
            assert!(replace_f64(&mut st.model, old, x, skip) >= 1, "{label}");
            let crafted = st.serialize(&MAGIC, &guid);
            let inst = Inst::new("crafted-into");
            let l = &mut calls;
            let mut p: fmi2FMUstate = ptr::null_mut();
            let d = timed(l, &label, "fmi2DeSerializeFMUstate", || {
                let (st, q) = inst.deserialize(&crafted);
                p = q;
                st
            });
            assert_eq!(d, OK, "{label}: the envelope is valid");
            let set = timed(l, &label, "fmi2SetFMUstate", || inst.set_state(p));
            assert!(set == OK || set == ERROR, "{label}: {set}");
            if set == OK {
                steps_within_cap(l, &label, &inst, 3.0 * H, cap);
            }
            assert_eq!(inst.free_state(&mut p), OK);
        }
    }
    // huge counts (issue 18): arrays of two elements, the second reference invalid, passed
    // with counts up to usize::MAX; each call is an fmi2Error and the instance keeps working
    let inst = Inst::initialized("huge-counts", None);
    let api = inst.api;
    let (f0, x0) = (forces()[0], vr("tip.position.x"));
    let (refs, orders, values) = ([f0, 99_999], [1, 1], [0.0, 0.0]);
    let mut out = [0.0; 2];
    let out_p = out.as_mut_ptr();
    for n in [1usize << 27, 1 << 31, 1 << 62, usize::MAX] {
        let label = format!("count = {n}");
        let l = &mut calls;
        let statuses = [
            timed(l, &label, "fmi2SetReal", || unsafe {
                api.set_real.unwrap()(inst.c, refs.as_ptr(), n, values.as_ptr())
            }),
            timed(l, &label, "fmi2GetReal", || unsafe {
                api.get_real.unwrap()(inst.c, [x0, 99_999].as_ptr(), n, out_p)
            }),
            timed(l, &label, "fmi2SetRealInputDerivatives", || unsafe {
                let (r, o, v) = (refs.as_ptr(), orders.as_ptr(), values.as_ptr());
                api.set_real_input_derivatives.unwrap()(inst.c, r, n, o, v)
            }),
            timed(l, &label, "fmi2GetRealOutputDerivatives", || unsafe {
                let (r, o) = ([x0, 99_999].as_ptr(), orders.as_ptr());
                api.get_real_output_derivatives.unwrap()(inst.c, r, n, o, out_p)
            }),
            timed(l, &label, "fmi2GetDirectionalDerivative", || unsafe {
                let (u, k, v) = ([x0, 99_999].as_ptr(), refs.as_ptr(), values.as_ptr());
                api.get_directional_derivative.unwrap()(inst.c, u, n, k, n, v, out_p)
            }),
        ];
        assert!(
            statuses.iter().all(|&s| s == ERROR),
            "{label}: {statuses:?}"
        );
    }
    assert_eq!(inst.do_step(0.0, H), OK, "{:?}", inst.log.entries());
    let name = |s| match s {
        OK => "OK",
        DISCARD => "Discard",
        ERROR => "Error",
        _ => "other",
    };
    for c in &calls {
        eprintln!(
            "{:>10.3} ms  {:<8} {:<27} {}",
            1e3 * c.seconds,
            name(c.status),
            c.call,
            c.label
        );
    }
    let worst = calls
        .iter()
        .max_by(|a, b| a.seconds.total_cmp(&b.seconds))
        .unwrap();
    eprintln!(
        "{} calls; the longest: {:.3} ms ({} {} -> {})",
        calls.len(),
        1e3 * worst.seconds,
        worst.call,
        worst.label,
        name(worst.status)
    );
}

/// The resident set size of this process [bytes] (Linux: /proc/self/statm, pages of 4 KiB).
#[cfg(target_os = "linux")]
fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap();
    let pages: u64 = statm.split_whitespace().nth(1).unwrap().parse().unwrap();
    pages * 4096
}

/// What a parameter study does to one instance (docs/sweeps.md): 1,000 cycles of fmi2Reset, a
/// parameter set, initialization and 2 steps repeat the first cycle's outputs bit for bit
/// (reset returns to the instantiated state, caches included), and the process's memory stays
/// flat: between cycle 100 and cycle 1,000 it grows by less than 16 MiB (a leak of one model
/// per cycle, ~100 kB for Case 1, would be ~90 MB; the bound leaves room for the other tests of
/// this binary running in parallel threads).
#[test]
#[cfg(target_os = "linux")]
fn a_thousand_reset_cycles_repeat_the_first_run_in_flat_memory() {
    let inst = Inst::new("resets");
    let p0 = vrs_where(|v| v.causality == Causality::Parameter)[0];
    let start = start_of(p0);
    let cycle = || {
        assert_eq!(inst.reset(), OK);
        assert_eq!(inst.set_real(&[p0], &[start]), OK);
        assert_eq!(inst.setup(0.0, None), OK);
        assert_eq!(inst.enter_init(), OK);
        assert_eq!(inst.exit_init(), OK);
        bits(&run(&inst, 0, 2))
    };
    let first = cycle();
    let mut at_100 = 0;
    for k in 1..=1000 {
        assert_eq!(cycle(), first, "cycle {k}");
        if k == 100 {
            at_100 = resident_bytes();
        }
    }
    let growth = resident_bytes().saturating_sub(at_100);
    println!("resident growth over cycles 100..1000: {growth} bytes");
    assert!(growth < 16 << 20, "{growth} bytes");
    inst.assert_no_problems();
}

/// Instances created and freed 1,000 times (what a sweep's workers do between chunks) leave the
/// process's memory flat: less than 16 MiB of growth from the 100th to the 1,000th (as above).
#[test]
#[cfg(target_os = "linux")]
fn a_thousand_instances_created_and_freed_leave_memory_flat() {
    let mut at_100 = 0;
    for k in 1..=1000 {
        let inst = Inst::new("instances");
        assert_eq!(inst.setup(0.0, None), OK);
        drop(inst);
        if k == 100 {
            at_100 = resident_bytes();
        }
    }
    let growth = resident_bytes().saturating_sub(at_100);
    println!("resident growth over instances 100..1000: {growth} bytes");
    assert!(growth < 16 << 20, "{growth} bytes");
}
