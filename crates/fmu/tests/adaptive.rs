//! The ESDIRK4's error control (`solver.error_tolerance`, issue 42) in the FMU: the scene key
//! reaches the model the FMU builds from its resources; communication steps of 1 ms end on
//! their points, repeat bit for bit, and survive fmi2GetFMUstate/fmi2SetFMUstate.

mod host;

use host::*;
use hybeam::scene::Scene;
use hybeam::simulator::{AnySimulator, InputId};

/// Communication step [s].
const H: f64 = 1e-3;

/// `scenes/case1.toml` (the hybrid: a modal segment jointed to an ANCF one) with the ESDIRK4
/// under error control, internal steps up to 1 ms, and no `solver.tolerance`: the Newton
/// tolerance follows the error tolerance (1e-3 × 1e-7).
fn scene() -> String {
    let text = SCENE.replace(
        "max_step = 1e-4\ntolerance = 1e-11",
        "method = \"esdirk4\"\nmax_step = 1e-3\nerror_tolerance = 1e-7",
    );
    assert!(text.contains("error_tolerance = 1e-7"));
    text
}

/// The tip forces of step k: within the rod's small-deformation range, switching sign every
/// 20 steps (a jump of the inputs at those communication points).
fn forces(k: usize) -> [f64; 2] {
    let fx = if k % 40 < 20 { 0.03 } else { -0.02 };
    [fx, 0.005 * (k as f64 * 0.1).sin()]
}

/// Steps `from..to` of 1 ms through the FMU; the bits of the tip position after each.
fn fmu_steps(inst: &Inst, text: &str, from: usize, to: usize) -> Vec<[u64; 2]> {
    let f = [vr_in(text, "tip.force.x"), vr_in(text, "tip.force.y")];
    let tip = [vr_in(text, "tip.position.x"), vr_in(text, "tip.position.y")];
    (from..to)
        .map(|k| {
            assert_eq!(inst.set_real(&f, &forces(k)), OK);
            assert_eq!(
                inst.do_step(k as f64 * H, H),
                OK,
                "{:?}",
                inst.log.entries()
            );
            let p = inst.get_real(&tip).unwrap();
            [p[0].to_bits(), p[1].to_bits()]
        })
        .collect()
}

#[test]
fn error_controlled_steps_through_the_fmu_repeat_and_restore_bit_for_bit() {
    let text = scene();
    let a = initialized_with(&text, "adaptive-a");
    // the Newton tolerance the FMU shows is the tied one
    assert_eq!(a.get1(vr_in(&text, "solver.tolerance")), 1e-10);
    let first = fmu_steps(&a, &text, 0, 60);
    // a second instance: the same bits
    let b = initialized_with(&text, "adaptive-b");
    assert_eq!(fmu_steps(&b, &text, 0, 60), first);
    // the simulator itself, driven to the same points with the same inputs: the same bits,
    // and more than one internal step in some communication steps, one in others (the
    // proposal, carried from one to the next, is below and above 1 ms)
    let mut sim = AnySimulator::new(Scene::from_toml(&text).unwrap()).unwrap();
    let ids: Vec<InputId> = ["tip.force.x", "tip.force.y"]
        .iter()
        .map(|name| {
            InputId::of_scene(sim.scene())
                .into_iter()
                .find(|(n, _)| n == name)
                .unwrap()
                .1
        })
        .collect();
    let mut per_step = Vec::new();
    for (k, want) in first.iter().enumerate() {
        for (id, x) in ids.iter().zip(forces(k)) {
            assert!(sim.set_input(*id, x));
        }
        let before = sim.counters().steps;
        sim.advance(k as f64 * H + H).unwrap();
        per_step.push(sim.counters().steps - before);
        let o = sim.outputs();
        let p = o.tip_position();
        assert_eq!([p[0].to_bits(), p[1].to_bits()], *want, "step {k}");
    }
    println!("internal steps per communication step: {per_step:?}");
    assert!(
        per_step.iter().any(|&n| n > 1) && per_step.contains(&1),
        "{per_step:?}"
    );
    // fmi2GetFMUstate at step 30, on to 60, back, again: the same bits (the proposed step is
    // part of the state), also in a new instance
    let c = initialized_with(&text, "adaptive-c");
    fmu_steps(&c, &text, 0, 30);
    let s = c.get_state();
    assert_eq!(fmu_steps(&c, &text, 30, 60), first[30..]);
    assert_eq!(c.set_state(s), OK);
    assert_eq!(fmu_steps(&c, &text, 30, 60), first[30..]);
    let bytes = c.serialize(s);
    let d = initialized_with(&text, "adaptive-d");
    let (st, restored) = d.deserialize(&bytes);
    assert_eq!(st, OK);
    assert_eq!(d.set_state(restored), OK, "{:?}", d.log.entries());
    assert_eq!(fmu_steps(&d, &text, 30, 60), first[30..]);
}
