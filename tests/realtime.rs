//! The real-time mode (`solver.mode = "realtime"`, issue 41 §3): a fixed work per step, its
//! accuracy against the normal mode on a converged reference, and its refusal of a step it
//! cannot converge in its fixed iterations (the FMU's fmi2Discard is tested in
//! crates/fmu/tests/fmi_hardening.rs).

mod common;
use common::max_distance;
use hybeam::integrator::Mode;
use hybeam::scene::{Scene, Solver};
use hybeam::simulator::{AnySimulator, OutputId};

fn case1(set: impl FnOnce(&mut Solver)) -> Scene {
    let mut scene = Scene::from_toml(include_str!("../scenes/case1.toml")).unwrap();
    set(&mut scene.solver);
    scene.validate().unwrap();
    scene
}

/// Tip positions at every 1 ms to `t_end` [s].
fn run(scene: Scene, t_end: f64) -> (Vec<[f64; 2]>, hybeam::integrator::Counters) {
    let mut sim = AnySimulator::new(scene).unwrap();
    let id = |name: &str| {
        OutputId::named_with(sim.space(), false)
            .into_iter()
            .find(|(n, _)| n == name)
            .unwrap()
            .1
    };
    let (x, y) = (id("tip.position.x"), id("tip.position.y"));
    let n = (t_end / 1e-3).round() as usize;
    let mut out = Vec::with_capacity(n);
    for k in 1..=n {
        sim.advance(k as f64 * 1e-3).unwrap();
        let o = sim.outputs();
        out.push([o.value(x).unwrap(), o.value(y).unwrap()]);
    }
    (out, sim.counters())
}

/// The real-time mode at the normal mode's step is as accurate as the normal mode against a
/// converged reference (generalized-α at a quarter of the step, tolerance 1e-13), and its
/// work is fixed: `realtime_iterations` Newton iterations and one factorization per step.
#[test]
fn realtime_mode_fixed_work_and_accuracy() {
    let t_end = 0.3;
    let (reference, _) = run(
        case1(|s| {
            s.max_step = 2.5e-5;
            s.tolerance = Some(1e-13);
        }),
        t_end,
    );
    let (normal, _) = run(case1(|_| {}), t_end);
    let (rt, counters) = run(case1(|s| s.mode = Mode::Realtime), t_end);
    let (e_normal, e_rt) = (
        max_distance(&normal, &reference),
        max_distance(&rt, &reference),
    );
    eprintln!("case1 to {t_end} s at 1e-4 s: normal {e_normal:.3e} m, realtime {e_rt:.3e} m");
    // the step's discretization error dominates both: they agree to 1 %
    assert!(
        (e_rt - e_normal).abs() <= 0.01 * e_normal,
        "{e_rt} vs {e_normal}"
    );
    let steps = (t_end / 1e-4).round() as u64;
    assert_eq!(counters.steps, steps);
    assert_eq!(counters.iterations, 3 * steps);
    // one factorization per solve (realtime_refresh = 1), plus the initial accelerations'
    assert_eq!(counters.factorizations, steps + 1, "{counters:?}");
    assert_eq!(counters.rejected, 0);
    // bit-identical reruns
    let (again, _) = run(case1(|s| s.mode = Mode::Realtime), t_end);
    assert!(rt.iter().zip(&again).all(|(a, b)| a == b));
}

/// A step the fixed iterations cannot converge is refused, naming the increment and the
/// bound, and the state stays at the start of the communication step.
#[test]
fn realtime_mode_refuses_an_unconverged_step() {
    // one iteration per step at a 1 ms step: the second step's increment is ~1e3 x tolerance
    let scene = case1(|s| {
        s.mode = Mode::Realtime;
        s.max_step = 1e-3;
        s.realtime_iterations = 1;
    });
    let mut sim = AnySimulator::new(scene).unwrap();
    let mut last_ok = None;
    let mut err = None;
    for k in 1..=20 {
        let before = sim.outputs();
        match sim.advance(k as f64 * 1e-3) {
            Ok(()) => last_ok = Some(k),
            Err(e) => {
                err = Some(e.to_string());
                assert_eq!(sim.outputs(), before, "the state moved on a refused step");
                assert_eq!(sim.time(), (k - 1) as f64 * 1e-3);
                break;
            }
        }
    }
    let err = err.expect("a one-iteration real-time step at 1 ms is refused");
    assert!(
        err.contains("real-time") && err.contains("solver.realtime_bound"),
        "{err}"
    );
    eprintln!("refused after {last_ok:?} steps: {err}");
}

/// Bad real-time settings name the field, the value and the range.
#[test]
fn realtime_settings_are_validated() {
    for (k, v) in [
        ("realtime_iterations", "0"),
        ("realtime_refresh", "0"),
        ("realtime_bound", "0.5"),
    ] {
        let mut text = include_str!("../scenes/case1.toml").to_string();
        text = text.replace("[solver]\n", &format!("[solver]\n{k} = {v}\n"));
        let e = Scene::from_toml(&text).unwrap_err().0;
        assert!(e.contains(&format!("solver.{k} = {v}")), "{e}");
    }
    let text =
        include_str!("../scenes/case1.toml").replace("[solver]\n", "[solver]\nmode = \"fast\"\n");
    assert!(Scene::from_toml(&text).unwrap_err().0.contains("mode"));
}
