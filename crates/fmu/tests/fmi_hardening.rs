//! The second outside audit (issue 18), one test per finding, through the C ABI of the built
//! cdylib: counts checked before memory is touched (1) and before a slice is built (2), a
//! restored FMU state checked completely (3) and never a panic on a crafted one (4), and no
//! getter answering a non-finite number with fmi2OK (5). Each was written against the code
//! before the fix and failed there (the note of issue 18 records how).

mod host;

use std::ffi::c_char;
use std::ptr;

use fmi2::types::*;
use fmi2::CoSimModel;
use host::*;

/// A value reference no variable has.
const BOGUS: u32 = 99_999;
/// The magic of the beam's serialized FMU states.
const MAGIC: [u8; 8] = <hybeam_fmu::FmuModel as CoSimModel>::STATE_MAGIC;
/// What a refused huge-count call may add to the process's peak resident memory (other tests
/// run in parallel threads of this process; the defects zero-filled or allocated ≥ 1 GiB).
const GROWTH_BOUND: u64 = 256 << 20;

/// Case 1 mounted at `mount` (pose, velocity and acceleration inputs), gravity along −y.
fn mounted(mount: &str) -> String {
    let s = SCENE.replace("root = \"clamped\"", "root = \"mounted\"");
    assert!(s.contains("root = \"mounted\""));
    format!("{s}\n[mount]\n{mount}\n")
}

/// Peak resident memory of this process [bytes] (`VmHWM`; 0 where /proc is not available).
fn peak_rss() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(0, |kb| kb << 10)
}

/// Runs `call`, which must answer fmi2Error with a logged message containing `part`, without
/// growing the peak resident memory by more than [`GROWTH_BOUND`]; prints its wall time.
fn refused(i: &Inst, label: &str, part: &str, call: impl FnOnce() -> fmi2Status) {
    let before = peak_rss();
    let start = std::time::Instant::now();
    let status = call();
    let seconds = start.elapsed().as_secs_f64();
    let growth = peak_rss().saturating_sub(before);
    eprintln!(
        "{label}: status {status} in {:.3} ms, peak RSS +{} kB",
        1e3 * seconds,
        growth >> 10
    );
    assert_eq!(status, ERROR, "{label}: {:?}", i.log.entries());
    let last = i.log.last();
    assert!(
        last.message.contains(part),
        "{label}: {:?} should name {part}",
        last.message
    );
    assert!(
        growth <= GROWTH_BOUND,
        "{label}: peak RSS grew by {growth} bytes"
    );
}

/// The instance still steps (the refused calls changed nothing).
fn still_steps(i: &Inst, t: f64) {
    assert_eq!(i.do_step(t, 1e-3), OK, "{:?}", i.log.entries());
}

/// Finding 1: a count far beyond the arrays (a host bug) with an invalid reference in them is
/// refused at that reference, without allocating or zero-filling anything sized by the count.
#[test]
fn counts_are_checked_before_memory_is_touched() {
    let scene = mounted("position = [0.0, 1.0]");
    let i = initialized_with(&scene, "hard_counts");
    let (ax, fx) = (
        vr_in(&scene, "root.acceleration.x"),
        vr_in(&scene, "root.force.x"),
    );
    let api = i.api;
    let vrs = [ax, BOGUS];
    let orders = [1, 1];
    let values = [0.0, 0.0];
    for n in [1usize << 27, 1 << 31] {
        refused(&i, &format!("fmi2SetReal nvr = {n}"), "99999", || unsafe {
            api.set_real.unwrap()(i.c, vrs.as_ptr(), n, values.as_ptr())
        });
        let label = format!("fmi2SetRealInputDerivatives nvr = {n}");
        refused(&i, &label, "99999", || unsafe {
            api.set_real_input_derivatives.unwrap()(
                i.c,
                vrs.as_ptr(),
                n,
                orders.as_ptr(),
                values.as_ptr(),
            )
        });
        let mut out = [0.0; 2];
        let label = format!("fmi2GetDirectionalDerivative nKnown = {n}");
        refused(&i, &label, "99999", || unsafe {
            api.get_directional_derivative.unwrap()(
                i.c,
                [fx].as_ptr(),
                1,
                vrs.as_ptr(),
                n,
                values.as_ptr(),
                out.as_mut_ptr(),
            )
        });
        let label = format!("fmi2GetDirectionalDerivative nUnknown = {n}");
        refused(&i, &label, "99999", || unsafe {
            api.get_directional_derivative.unwrap()(
                i.c,
                [fx, BOGUS].as_ptr(),
                n,
                [ax].as_ptr(),
                1,
                values.as_ptr(),
                out.as_mut_ptr(),
            )
        });
        let categories: [*const c_char; 2] = [c"logAll".as_ptr(), ptr::null()];
        let label = format!("fmi2SetDebugLogging nCategories = {n}");
        refused(&i, &label, "categories[1]", || unsafe {
            api.set_debug_logging.unwrap()(i.c, 1, n, categories.as_ptr())
        });
    }
    still_steps(&i, 0.0);
}

/// A named FMI call of a test: function, count argument, the call.
type Call<'a> = (&'a str, &'a str, Box<dyn Fn() -> fmi2Status + 'a>);

/// Finding 2: a count whose array would exceed isize::MAX bytes is refused before any slice
/// is built, with fmi2Error (the instance is not lost), in every function that takes arrays.
#[test]
fn counts_beyond_the_largest_array_are_errors_not_fatal() {
    let scene = mounted("position = [0.0, 1.0]");
    let i = initialized_with(&scene, "hard_isize");
    let (ax, fx) = (
        vr_in(&scene, "root.acceleration.x"),
        vr_in(&scene, "root.force.x"),
    );
    let api = i.api;
    let mut s = i.get_state();
    let bytes = i.serialize(s);
    let (vrs, orders, values, mut out) = ([ax, fx], [1, 1], [0.0, 0.0], [0.0; 2]);
    let out_p = out.as_mut_ptr();
    let mut p: fmi2FMUstate = ptr::null_mut();
    for n in [1usize << 62, usize::MAX] {
        let calls: Vec<Call> = vec![
            (
                "fmi2SetReal",
                "nvr",
                Box::new(|| unsafe {
                    api.set_real.unwrap()(i.c, vrs.as_ptr(), n, values.as_ptr())
                }),
            ),
            (
                "fmi2GetReal",
                "nvr",
                Box::new(|| unsafe { api.get_real.unwrap()(i.c, vrs.as_ptr(), n, out_p) }),
            ),
            (
                "fmi2SetRealInputDerivatives",
                "nvr",
                Box::new(|| unsafe {
                    api.set_real_input_derivatives.unwrap()(
                        i.c,
                        vrs.as_ptr(),
                        n,
                        orders.as_ptr(),
                        values.as_ptr(),
                    )
                }),
            ),
            (
                "fmi2GetRealOutputDerivatives",
                "nvr",
                Box::new(|| unsafe {
                    api.get_real_output_derivatives.unwrap()(
                        i.c,
                        [fx, fx].as_ptr(),
                        n,
                        orders.as_ptr(),
                        out_p,
                    )
                }),
            ),
            (
                "fmi2GetDirectionalDerivative",
                "nKnown",
                Box::new(|| unsafe {
                    api.get_directional_derivative.unwrap()(
                        i.c,
                        [fx].as_ptr(),
                        1,
                        vrs.as_ptr(),
                        n,
                        values.as_ptr(),
                        out_p,
                    )
                }),
            ),
            (
                "fmi2GetDirectionalDerivative",
                "nUnknown",
                Box::new(|| unsafe {
                    api.get_directional_derivative.unwrap()(
                        i.c,
                        [fx, fx].as_ptr(),
                        n,
                        [ax].as_ptr(),
                        1,
                        values.as_ptr(),
                        out_p,
                    )
                }),
            ),
            (
                "fmi2SetInteger",
                "nvr",
                Box::new(|| unsafe {
                    api.set_integer.unwrap()(i.c, vrs.as_ptr(), n, [0, 0].as_ptr())
                }),
            ),
            (
                "fmi2DeSerializeFMUstate",
                "size",
                Box::new(|| unsafe {
                    let mut q: fmi2FMUstate = ptr::null_mut();
                    api.deserialize_fmu_state.unwrap()(i.c, bytes.as_ptr() as *const _, n, &mut q)
                }),
            ),
        ];
        for (name, count, call) in &calls {
            let label = format!("{name} {count} = {n}");
            refused(&i, &label, &n.to_string(), call);
        }
        // the serialized state's own length is compared with the size argument first
        let label = format!("fmi2DeSerializeFMUstate size = {}", bytes.len() + 1);
        refused(&i, &label, "header declares", || unsafe {
            api.deserialize_fmu_state.unwrap()(
                i.c,
                bytes.as_ptr() as *const _,
                bytes.len() + 1,
                &mut p,
            )
        });
    }
    assert!(p.is_null());
    assert_eq!(i.free_state(&mut s), OK);
    still_steps(&i, 0.0);
}

/// A state of `i` serialized, its model bytes changed by `craft`, the checksum recomputed.
fn crafted(i: &Inst, scene: &str, craft: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut s = i.get_state();
    let bytes = i.serialize(s);
    assert_eq!(i.free_state(&mut s), OK);
    let guid = guid_of(scene);
    let mut st = fmi2::fmu_state::FmuState::deserialize(&bytes, &MAGIC, &guid).unwrap();
    craft(&mut st.model);
    st.serialize(&MAGIC, &guid)
}

/// fmi2DeSerializeFMUstate accepts `bytes` (the envelope is valid), fmi2SetFMUstate refuses
/// them with fmi2Error and a message naming `part`; the instance keeps its state.
fn set_refused(i: &Inst, scene: &str, label: &str, bytes: &[u8], part: &str) {
    let tip = [vr_in(scene, "tip.position.y")];
    let outputs_before = i.get_real(&tip);
    let (d, mut p) = i.deserialize(bytes);
    assert_eq!(d, OK, "{label}: {:?}", i.log.entries());
    let status = i.set_state(p);
    assert_eq!(i.free_state(&mut p), OK);
    eprintln!("{label}: {:?}", i.log.last().message);
    assert_eq!(status, ERROR, "{label}: {:?}", i.log.entries());
    let last = i.log.last().message;
    assert!(last.contains(part), "{label}: {last:?} should name {part}");
    assert_eq!(i.get_real(&tip), outputs_before, "{label}: state kept");
}

/// Finding 3: every value of a restored state is checked, including the mount's path, the load
/// rates and the FMU's backward differences, and a state whose outputs would overflow is
/// refused.
#[test]
fn restored_states_are_checked_completely() {
    let scene = mounted("position = [0.0, 1.0]");
    let i = initialized_with(&scene, "hard_restore");
    let a = 0.123_456_789;
    let ax = vr_in(&scene, "root.acceleration.x");
    assert_eq!(i.set_real(&[ax], &[a]), OK);
    for k in 0..3 {
        still_steps(&i, k as f64 * 1e-3);
    }
    let t = 3e-3;
    // the mount's path: its base acceleration (the first occurrence of the value; the last
    // input and the held matrix's motion after it keep theirs, as in the audit)
    let bytes = crafted(&i, &scene, |m| {
        let (old, at) = (
            a.to_le_bytes(),
            m.windows(8).position(|w| w == a.to_le_bytes()),
        );
        let at = at.expect("the base acceleration in the bytes");
        assert_eq!(m[at..at + 8], old);
        m[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    });
    set_refused(
        &i,
        &scene,
        "mount base acceleration NaN",
        &bytes,
        "memory.mount",
    );
    // the FMU's backward differences (the last field of its part)
    let bytes = crafted(&i, &scene, |m| {
        let n = m.len();
        m[n - 8..].copy_from_slice(&f64::NAN.to_le_bytes());
    });
    set_refused(
        &i,
        &scene,
        "backward difference NaN",
        &bytes,
        "backward difference",
    );
    // the tip loads' rates set for the next step
    let fy = vr_in(&scene, "tip.force.y");
    let rate = 0.987_654_321;
    let set_rate = unsafe {
        i.api.set_real_input_derivatives.unwrap()(
            i.c,
            [fy].as_ptr(),
            1,
            [1].as_ptr(),
            [rate].as_ptr(),
        )
    };
    assert_eq!(set_rate, OK, "{:?}", i.log.entries());
    let bytes = crafted(&i, &scene, |m| {
        assert_eq!(replace_f64(m, rate, f64::INFINITY, 0), 1);
    });
    set_refused(&i, &scene, "load rate inf", &bytes, "load_rates");
    // a coordinate of 1e300: finite, but the energies overflow
    let tip_x = i.get1(vr_in(&scene, "tip.position.x"));
    let bytes = crafted(&i, &scene, |m| {
        assert!(replace_f64(m, tip_x, 1e300, 0) >= 1);
    });
    set_refused(&i, &scene, "tip coordinate 1e300", &bytes, "");
    still_steps(&i, t);
}

/// Finding 3, space: the mount path's Euler parameters must have unit norm, and a pending
/// input's must be normalizable.
#[test]
fn restored_mount_orientations_must_be_usable() {
    // the mount of case1_3d_mounted turned 73.7° about z (unit Euler parameters, exact in
    // binary): the path keeps these bits at its start until an input is taken
    let text = include_str!("../../../scenes/case1_3d_mounted.toml");
    let scene = text.replace(
        "position = [0.0, 0.0, 1.0]",
        "position = [0.0, 0.0, 1.0]\norientation = [0.8, 0.0, 0.0, 0.6]",
    );
    assert_ne!(scene, text);
    let i = initialized_with(&scene, "hard_quaternion");
    for k in 0..3 {
        still_steps(&i, k as f64 * 1e-3);
    }
    let bytes = crafted(&i, &scene, |m| {
        assert!(replace_f64(m, 0.8, 1.6, 0) >= 1);
    });
    set_refused(
        &i,
        &scene,
        "mount base e0 doubled",
        &bytes,
        "memory.mount.base.attitude",
    );
    // a pending orientation input of twice the unit parameters is legal (normalized when
    // taken); crafted to zero it is not
    let e: Vec<u32> = ["e0", "e1", "e2", "e3"]
        .iter()
        .map(|c| vr_in(&scene, &format!("root.orientation.{c}")))
        .collect();
    let now = i.get_real(&e).unwrap();
    let twice: Vec<f64> = now.iter().map(|x| 2.0 * x).collect();
    assert_eq!(i.set_real(&e, &twice), OK);
    let bytes = crafted(&i, &scene, |m| {
        for x in twice.iter().filter(|x| **x != 0.0) {
            assert!(replace_f64(m, *x, 0.0, 0) >= 1);
        }
    });
    set_refused(&i, &scene, "pending e zero", &bytes, "memory.mount.pending");
    still_steps(&i, 3e-3);
}

/// The prefix of the simulator's snapshot (format version 7) up to the held Newton matrix's
/// point, mirrored to craft one: the test fails loudly if the format changes.
#[derive(serde::Serialize, serde::Deserialize)]
struct Prefix {
    version: u32,
    coordinates: u64,
    constraints: u64,
    scene: u64,
    /// Planar inputs: tip force, tip moment, gravity, the line-load slots.
    inputs: (
        [f64; 2],
        f64,
        [f64; 2],
        [[f64; 2]; hybeam::scene::MAX_LINE_LOADS],
    ),
    state: hybeam::integrator::State,
    eta: f64,
    jacobian: Option<hybeam::integrator::JacobianPoint>,
}

/// Finding 4: a Newton-matrix point of the wrong length is refused with fmi2Error, never a
/// panic (the instance would be lost).
#[test]
fn a_crafted_newton_matrix_point_is_an_error_not_fatal() {
    let i = Inst::initialized("hard_jacobian", None);
    for k in 0..3 {
        still_steps(&i, k as f64 * 1e-3);
    }
    for (what, change) in [
        ("v one shorter", -1i32),
        ("v one longer", 1),
        ("acc one shorter", -2),
    ] {
        let bytes = crafted(&i, SCENE, |m| {
            type Fmu = (Vec<f64>, Vec<u8>, Vec<f64>);
            let (params, sim, backward): Fmu = postcard::from_bytes(m).unwrap();
            let (mut prefix, rest): (Prefix, &[u8]) = postcard::take_from_bytes(&sim).unwrap();
            assert_eq!(prefix.version, hybeam::simulator::SNAPSHOT_VERSION);
            let jp = prefix.jacobian.as_mut().expect("a held Newton matrix");
            let x = if change.abs() == 1 {
                &mut jp.v
            } else {
                &mut jp.acc
            };
            if change > 0 {
                x.push(0.0);
            } else {
                x.pop();
            }
            let mut sim = postcard::to_allocvec(&prefix).unwrap();
            sim.extend_from_slice(rest);
            *m = postcard::to_allocvec(&(params, sim, backward)).unwrap();
        });
        set_refused(&i, SCENE, what, &bytes, "dimensions");
    }
    still_steps(&i, 3e-3);
}

/// Finding 5: a directional derivative that overflows is fmi2Error, not infinity with fmi2OK.
#[test]
fn an_overflowing_directional_derivative_is_an_error() {
    let scene = include_str!("../../../scenes/boom.toml");
    let i = initialized_with(scene, "hard_directional");
    still_steps(&i, 0.0);
    let (fx, ax) = (
        vr_in(scene, "root.force.x"),
        vr_in(scene, "root.acceleration.x"),
    );
    let mut out = [0.0];
    let call = |seed: f64, out: &mut [f64; 1]| unsafe {
        i.api.get_directional_derivative.unwrap()(
            i.c,
            [fx].as_ptr(),
            1,
            [ax].as_ptr(),
            1,
            [seed].as_ptr(),
            out.as_mut_ptr(),
        )
    };
    assert_eq!(call(1.0, &mut out), OK);
    assert!(out[0].is_finite() && out[0] != 0.0, "{out:?}");
    let status = call(1e308, &mut out);
    eprintln!("seed 1e308: status {status}, {:?}", i.log.last().message);
    assert_eq!(status, ERROR, "{out:?}");
    assert!(i.log.last().message.contains("root.force.x"));
    still_steps(&i, 1e-3);
}
