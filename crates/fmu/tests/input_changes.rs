//! Inputs that change at a communication point (issue 7 §4), through the C ABI of the built
//! cdylib. A force held constant over a communication step must be integrated as exactly that
//! force: the generalized-α memory must not smear the old input into the new step.
//!
//! Reference: an FMU whose scene already holds the new force (same equations, no change to
//! handle). The order of convergence under a piecewise-constant input is tested on the
//! integrator (`generalized_alpha::tests`), where the internal steps resolve every frequency.

mod host;

use host::*;

/// A Case 1 instance of `scene`, set up at t = 0 and initialized.
fn initialized(scene: &str, tag: &str) -> Inst {
    initialized_with(scene, tag)
}

/// Case 1 with the `[tip]` table `tip` (a constant load) in the scene, internal step `h` [s] and
/// a tight Newton tolerance (so that the step-size error dominates).
fn case1_with(tip: &str, h: f64) -> String {
    let s = SCENE
        .replace("max_step = 1e-4", &format!("max_step = {h:e}"))
        .replace("tolerance = 1e-11", "tolerance = 1e-13")
        .replace("[initial]", &format!("[tip]\n{tip}\n\n[initial]"));
    assert!(s.contains("[tip]") && s.contains(&format!("max_step = {h:e}")));
    s
}

/// Case 1 with a constant tip force `fy` [N] in the scene (see [`case1_with`]).
fn case1(fy: f64, h: f64) -> String {
    case1_with(&format!("force = [0.0, {fy:e}]"), h)
}

fn tip_y(inst: &Inst) -> f64 {
    inst.get1(vr("tip.position.y"))
}

/// Steps `n` communication steps of `dt` from t = 0; `force(k)` (if any) is set as
/// `tip.force.y` before step k.
fn run(inst: &Inst, dt: f64, n: usize, force: impl Fn(usize) -> Option<f64>) -> Vec<f64> {
    run_setting(inst, "tip.force.y", dt, n, force)
}

/// [`run`] setting the input `name`.
fn run_setting(
    inst: &Inst,
    name: &str,
    dt: f64,
    n: usize,
    input: impl Fn(usize) -> Option<f64>,
) -> Vec<f64> {
    let u = vr(name);
    (0..n)
        .map(|k| {
            if let Some(x) = input(k) {
                assert_eq!(inst.set_real(&[u], &[x]), OK);
            }
            assert_eq!(
                inst.do_step(k as f64 * dt, dt),
                OK,
                "{:?}",
                inst.log.entries()
            );
            tip_y(inst)
        })
        .collect()
}

/// Largest |a − b| over two histories.
fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// A scene force of 0.7 N with the host setting 0.1 N right after initialization ends where an
/// FMU built with 0.1 N does (issue 7 §4: 1.28e-4 m apart at h = 1e-4 s before the fix).
#[test]
fn new_input_after_initialization_matches_an_fmu_built_with_it() {
    let h = 1e-4;
    let (dt, n) = (1e-3, 200);
    let changed = initialized(&case1(0.7, h), "changed");
    let built = initialized(&case1(0.1, h), "built");
    let a = run(&changed, dt, n, |k| (k == 0).then_some(0.1));
    let b = run(&built, dt, n, |_| None);
    let diff = largest_difference(&a, &b);
    println!(
        "tip.position.y after 0.2 s: {:.15e} (0.7 N scene, host 0.1 N) vs {:.15e} (0.1 N scene); largest difference {diff:.3e} m",
        a[n - 1], b[n - 1]
    );
    assert!(diff <= 1e-12, "largest difference {diff:e} m");
    // the force the host reads back is the one the model applies
    assert_eq!(changed.get1(vr("tip.force.y")).to_bits(), 0.1f64.to_bits());
}

/// The tip moment is an input like the force: a scene without it and the host setting
/// `tip.moment.z` = 0.01 N m right after initialization ends where an FMU built with
/// `tip.moment = [0.01]` does, and the moment moves the tip (far beyond that agreement).
#[test]
fn tip_moment_set_by_the_host_matches_an_fmu_built_with_it() {
    let h = 1e-4;
    let (dt, n) = (1e-3, 200);
    let changed = initialized(&case1_with("moment = [0.0]", h), "moment-changed");
    let built = initialized(&case1_with("moment = [0.01]", h), "moment-built");
    let free = initialized(&case1_with("moment = [0.0]", h), "moment-free");
    let a = run_setting(&changed, "tip.moment.z", dt, n, |k| {
        (k == 0).then_some(0.01)
    });
    let b = run_setting(&built, "tip.moment.z", dt, n, |_| None);
    let c = run_setting(&free, "tip.moment.z", dt, n, |_| None);
    let (diff, effect) = (largest_difference(&a, &b), largest_difference(&a, &c));
    println!(
        "tip.position.y after 0.2 s: {:.15e} (host 0.01 N m) vs {:.15e} (0.01 N m scene), \
         {:.15e} (no moment); largest difference {diff:.3e} m, effect of the moment {effect:.3e} m",
        a[n - 1],
        b[n - 1],
        c[n - 1]
    );
    assert!(diff <= 1e-12, "largest difference {diff:e} m");
    assert!(
        effect > 1e-4,
        "the moment moves the tip by only {effect:e} m"
    );
    let mz = vr("tip.moment.z");
    assert_eq!(changed.get1(mz).to_bits(), 0.01f64.to_bits());
    assert_eq!(built.get1(mz).to_bits(), 0.01f64.to_bits());
}

/// Case 1 with `line_load = [0.0, q]` on both segments (and the internal step of [`case1`]).
fn case1_line(q: f64, h: f64) -> String {
    let s = case1(0.0, h).replace(
        "kind = \"modal\"",
        &format!("kind = \"modal\"\nline_load = [0.0, {q:e}]"),
    );
    let s = s.replace(
        "kind = \"ancf\"",
        &format!("kind = \"ancf\"\nline_load = [0.0, {q:e}]"),
    );
    assert_eq!(s.matches("line_load").count(), 2);
    s
}

/// The line-load inputs `<segment>.line_load.<axis>` (issue 39 item 4): set by the host right
/// after initialization they run as an FMU built with them; ramped by fmi2SetRealInputDerivatives
/// the FMU runs bit for bit as the simulator given the same ramp through its Rust API (whose
/// physics `tests/line_load.rs` checks against the exact modal solution).
#[test]
fn line_loads_set_by_the_host_and_their_derivatives() {
    let (h, dt, n, q) = (1e-4, 1e-3, 100, -0.05);
    let scene = case1_line(0.0, h);
    let changed = initialized(&scene, "line-changed");
    let built = initialized(&case1_line(q, h), "line-built");
    let names = ["modal.line_load.y", "ancf.line_load.y"];
    let vrs: Vec<u32> = names.iter().map(|n| vr_in(&scene, n)).collect();
    assert_eq!(vrs, [1021, 2021]);
    assert_eq!(changed.set_real(&vrs, &[q, q]), OK);
    let a = run(&changed, dt, n, |_| None);
    let b = run(&built, dt, n, |_| None);
    let diff = largest_difference(&a, &b);
    let sag = (a[n - 1] - initialized(&scene, "line-free").get1(vr("tip.position.y"))).abs();
    println!("line load set by the host vs built: {diff:.3e} m (sag {sag:.3e} m)");
    assert!(diff <= 1e-12 && sag > 1e-4, "{diff:e} {sag:e}");
    assert_eq!(changed.get_real(&vrs).unwrap(), vec![q, q]);

    // a ramp q = q̇t through the input derivatives, against the simulator's own
    let rate = -0.5;
    let ramped = initialized(&scene, "line-ramped");
    let mut sim =
        hybeam::simulator::AnySimulator::new(hybeam::scene::Scene::from_toml(&scene).unwrap())
            .unwrap();
    let api = api();
    for k in 0..n {
        let t = k as f64 * dt;
        assert_eq!(ramped.set_real(&vrs, &[rate * t, rate * t]), OK);
        let order = [1, 1];
        let status = unsafe {
            api.set_real_input_derivatives.unwrap()(
                ramped.c,
                vrs.as_ptr(),
                2,
                order.as_ptr(),
                [rate, rate].as_ptr(),
            )
        };
        assert_eq!(status, OK, "{:?}", ramped.log.entries());
        assert_eq!(ramped.do_step(t, dt), OK);
        for slot in 0..2 {
            let id = hybeam::simulator::InputId::line_load(slot, 1);
            assert!(sim.set_input(id, rate * t) && sim.set_input_derivative(id, 1, rate));
        }
        sim.advance(t + dt).unwrap();
        let (fmu, direct) = (tip_y(&ramped), sim.outputs().tip_position()[1]);
        assert_eq!(
            fmu.to_bits(),
            direct.to_bits(),
            "step {k}: {fmu:e} vs {direct:e}"
        );
    }
}
