//! A mounted beam through the C ABI of the built cdylib: the mount ports, the reaction's direct
//! feedthrough and its directional derivatives, input derivatives of the base motion, and
//! refusals of bad mount inputs with the state kept.

mod host;

use fmi2::types::fmi2Status;
use host::*;

/// Case 1 mounted (`[mount]` at `mount`, gravity along −y): the scene text.
fn mounted(mount: &str) -> String {
    let s = SCENE.replace("root = \"clamped\"", "root = \"mounted\"");
    assert!(s.contains("root = \"mounted\""));
    format!("{s}\n[mount]\n{mount}\n")
}

/// The planar mount's acceleration inputs.
const ACCELERATIONS: [&str; 3] = [
    "root.acceleration.x",
    "root.acceleration.y",
    "root.angular_acceleration",
];

/// Value references of `names` in the FMU of `scene`.
fn vrs(scene: &str, names: &[&str]) -> Vec<u32> {
    names.iter().map(|n| vr_in(scene, n)).collect()
}

fn directional(i: &Inst, unknowns: &[u32], knowns: &[u32], seeds: &[f64]) -> Vec<f64> {
    let mut out = vec![f64::NAN; unknowns.len()];
    let s = unsafe {
        i.api.get_directional_derivative.unwrap()(
            i.c,
            unknowns.as_ptr(),
            unknowns.len(),
            knowns.as_ptr(),
            knowns.len(),
            seeds.as_ptr(),
            out.as_mut_ptr(),
        )
    };
    assert_eq!(s, OK, "{:?}", i.log.entries());
    out
}

fn set_derivatives(i: &Inst, vrs: &[u32], order: i32, values: &[f64]) -> fmi2Status {
    let orders = vec![order; vrs.len()];
    unsafe {
        i.api.set_real_input_derivatives.unwrap()(
            i.c,
            vrs.as_ptr(),
            vrs.len(),
            orders.as_ptr(),
            values.as_ptr(),
        )
    }
}

/// The reaction follows a new acceleration input at once (direct feedthrough), and the
/// directional derivative is its slope: central differences of fmi2GetReal after fmi2SetReal.
#[test]
fn reaction_feeds_through_the_mount_acceleration_and_its_derivative_is_provided() {
    let scene = mounted("angle = 0.3");
    let i = initialized_with(&scene, "mount_dd");
    for k in 0..20 {
        assert_eq!(i.do_step(k as f64 * 1e-3, 1e-3), OK);
    }
    let outs = vrs(&scene, &["root.force.x", "root.force.y", "root.moment.z"]);
    let ins = vrs(&scene, &ACCELERATIONS);
    let before = i.get_real(&outs).unwrap();
    let a0 = i.get_real(&ins).unwrap();
    for (c, &input) in ins.iter().enumerate() {
        let mut seed = vec![0.0; 3];
        seed[c] = 1.0;
        let exact = directional(&i, &outs, &ins, &seed);
        let eps = 1e-3;
        let mut f = Vec::new();
        for s in [1.0, -1.0] {
            assert_eq!(i.set_real(&[input], &[a0[c] + s * eps]), OK);
            f.push(i.get_real(&outs).unwrap());
        }
        assert_eq!(i.set_real(&[input], &[a0[c]]), OK);
        for r in 0..3 {
            let fd = (f[0][r] - f[1][r]) / (2.0 * eps);
            eprintln!("∂out{r}/∂in{c}: {:.9e} vs {fd:.9e}", exact[r]);
            assert!(
                (exact[r] - fd).abs() <= 1e-6 * exact[r].abs().max(1e-9),
                "{r} {c}"
            );
        }
        assert!(exact[c].abs() > 0.0);
    }
    assert_eq!(
        i.get_real(&outs).unwrap(),
        before,
        "inputs restored, outputs restored"
    );
}

/// Over one communication step, a mount acceleration that varies linearly (its derivative
/// given) is integrated as such: one step of 10 ms with the derivative equals ten host steps
/// of 1 ms that set the exact motion at each, and differs from a step without it.
#[test]
fn input_derivatives_shape_the_base_motion_over_a_step() {
    let scene = mounted("");
    let names = ["root.position.x", "root.velocity.x", "root.acceleration.x"];
    let v: Vec<u32> = names.iter().map(|n| vr_in(&scene, n)).collect();
    let tip = vr_in(&scene, "tip.position.x");
    let jerk = 40.0; // m/s³: x = j t³/6
    let exact = |t: f64| [jerk * t * t * t / 6.0, jerk * t * t / 2.0, jerk * t];
    let (h, n) = (1e-2, 10);
    let run = |tag: &str, sub: usize, with: bool| {
        let i = initialized_with(&scene, tag);
        let dt = h / sub as f64;
        for k in 0..sub {
            let t = k as f64 * dt;
            assert_eq!(i.set_real(&v, &exact(t)), OK);
            if with {
                assert_eq!(set_derivatives(&i, &v[2..], 1, &[jerk]), OK);
            }
            assert_eq!(i.do_step(t, dt), OK, "{:?}", i.log.entries());
        }
        i.get1(tip)
    };
    let one = run("mount_der1", 1, true);
    let fine = run("mount_der10", n, true);
    let without = run("mount_der0", 1, false);
    eprintln!(
        "tip x: one step with derivative {one:.12e}, ten steps {fine:.12e}, without {without:.12e}"
    );
    // the same path up to rounding (the ten steps re-anchor and jump by rounding-level
    // differences of the host's exact motion): Newton-tolerance agreement
    assert!((one - fine).abs() < 1e-10, "{one} vs {fine}");
    assert!((without - fine).abs() > 1e3 * (one - fine).abs().max(1e-15));
}

/// A zero quaternion, a non-finite input or a pose that jumps by metres: the step is
/// discarded with a message and the state kept.
#[test]
fn bad_mount_inputs_are_discarded_with_the_state_kept() {
    let planar = mounted("");
    let i = initialized_with(&planar, "mount_bad");
    assert_eq!(i.do_step(0.0, 1e-3), OK);
    let tip = vr_in(&planar, "tip.position.y");
    let before = i.get1(tip);
    let x = vr_in(&planar, "root.position.x");
    assert_eq!(i.set_real(&[x], &[f64::NAN]), ERROR);
    let mut saved = i.get_state();
    assert_eq!(i.set_real(&[x], &[2.0]), OK);
    assert_eq!(i.do_step(1e-3, 1e-3), DISCARD);
    i.log.assert_last(2, "logStatusDiscard", &["jumps"]);
    assert_eq!(i.get1(tip), before, "state kept");
    // the host goes back to its saved state (FMI 2.0 after a discard) and moves continuously
    assert_eq!(i.set_state(saved), OK);
    assert_eq!(i.set_real(&[x], &[0.0]), OK);
    assert_eq!(i.do_step(1e-3, 1e-3), OK, "recovers with a continuous pose");
    assert_eq!(i.free_state(&mut saved), OK);
    let spatial = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/case1_3d.toml"
    ))
    .unwrap()
    .replace("root = \"clamped\"", "root = \"mounted\"");
    let s = initialized_with(&spatial, "mount_bad3");
    let e: Vec<u32> = ["e0", "e1", "e2", "e3"]
        .iter()
        .map(|c| vr_in(&spatial, &format!("root.orientation.{c}")))
        .collect();
    let mut saved = s.get_state();
    assert_eq!(s.set_real(&e, &[0.0; 4]), OK);
    assert_eq!(s.do_step(0.0, 1e-3), DISCARD);
    s.log
        .assert_last(2, "logStatusDiscard", &["zero quaternion"]);
    assert_eq!(s.set_state(saved), OK);
    assert_eq!(s.set_real(&e, &[2.0, 0.0, 0.0, 0.0]), OK, "renormalized");
    assert_eq!(s.do_step(0.0, 1e-3), OK);
    assert_eq!(s.free_state(&mut saved), OK);
}

/// The description of a mounted beam declares what the FMU does: input interpolation, the
/// directional derivative, and the reaction's dependencies on exactly the acceleration inputs.
#[test]
fn model_description_declares_the_feedthrough() {
    let scene = mounted("");
    let xml = hybeam_fmu::FmuModel::model_description(&scene, "m").unwrap();
    assert!(xml.contains("canInterpolateInputs=\"true\""));
    assert!(xml.contains("providesDirectionalDerivative=\"true\""));
    let model = <hybeam_fmu::FmuModel as fmi2::CoSimModel>::from_resource(&scene).unwrap();
    let vars = fmi2::CoSimModel::variables(&model);
    let acc = vrs(&scene, &ACCELERATIONS);
    for v in vars {
        let want: &[u32] = if v.name.starts_with("root.force") || v.name.starts_with("root.moment")
        {
            &acc
        } else {
            &[]
        };
        assert_eq!(v.depends_on, want, "{}", v.name);
    }
    let fixed = hybeam_fmu::FmuModel::model_description(SCENE, "f").unwrap();
    assert!(fixed.contains("canInterpolateInputs=\"false\""));
    assert!(fixed.contains("providesDirectionalDerivative=\"false\""));
}
