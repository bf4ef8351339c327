//! The partner model's inputs through the named scalars an FMU host writes
//! (`root.mobility.<a>_<r>`, `root.reaction_reference.<r>`): a zero mobility leaves a run bit
//! for bit as without the model, a snapshot holds them, and a mobility that cancels the beam's
//! inertia is refused with the state kept. (The coupled physics, a rigid payload on the car
//! against one body, is checked with the FMUs in examples/vehicle/test_cosim.py.)

use hybeam::scene::{Scene, SpaceKind};
use hybeam::simulator::{AnySimulator, InputId, InputKind};

fn boom() -> AnySimulator {
    boom_with(|_| {})
}

/// The boom scene with `edit` applied.
fn boom_with(edit: impl FnOnce(&mut Scene)) -> AnySimulator {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/boom.toml")).unwrap();
    let mut scene = Scene::from_toml(&text).unwrap();
    edit(&mut scene);
    AnySimulator::new(scene).unwrap()
}

fn input(name: &str) -> InputId {
    InputId::named_with(SpaceKind::Planar, true)
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("{name}"))
        .1
}

fn partner_inputs() -> Vec<(String, InputId)> {
    InputId::named_with(SpaceKind::Planar, true)
        .into_iter()
        .filter(|(_, id)| id.kind.is_partner())
        .collect()
}

/// The mount swinging vertically (12 mm, 40 rad/s) at the scene's pose, 1 ms steps: the
/// outputs' values after each step, as bits.
fn swing(sim: &mut AnySimulator, partner: impl Fn(&mut AnySimulator)) -> Vec<u64> {
    outputs_of_swing(sim, partner, |_| true)
        .into_iter()
        .map(f64::to_bits)
        .collect()
}

/// [`swing`]'s values of the outputs whose names pass `keep`.
fn outputs_of_swing(
    sim: &mut AnySimulator,
    partner: impl Fn(&mut AnySimulator),
    keep: impl Fn(&str) -> bool,
) -> Vec<f64> {
    let (y0, ids) = (
        sim.input(input("root.position.y")).unwrap(),
        ["root.position.y", "root.velocity.y", "root.acceleration.y"].map(input),
    );
    let names: Vec<_> = hybeam::simulator::OutputId::named_with(SpaceKind::Planar, true)
        .into_iter()
        .filter(|(n, _)| keep(n))
        .collect();
    let mut values = Vec::new();
    for k in 1..=60 {
        let t = sim.time();
        let (a, w) = (0.012, 40.0);
        let (s, c) = (w * t).sin_cos();
        for (id, x) in ids.iter().zip([y0 + a * s, a * w * c, -a * w * w * s]) {
            assert!(sim.set_input(*id, x));
        }
        partner(sim);
        sim.advance(k as f64 * 1e-3).unwrap();
        let o = sim.outputs();
        values.extend(names.iter().filter_map(|(_, id)| o.value(*id)));
    }
    values
}

#[test]
fn a_zero_mobility_leaves_the_run_bit_for_bit() {
    let plain = swing(&mut boom(), |_| {});
    let inputs = partner_inputs();
    assert_eq!(
        inputs.len(),
        9 + 3,
        "planar: 3 x 3 mobility and 3 references"
    );
    let zero = swing(&mut boom(), |sim| {
        for (name, id) in &inputs {
            // a reference without a mobility does nothing
            let x = if name.contains("reference") {
                1234.5
            } else {
                0.0
            };
            assert!(sim.set_input(*id, x), "{name}");
        }
    });
    assert_eq!(plain, zero);
}

#[test]
fn a_snapshot_holds_the_partner_inputs() {
    let mut sim = boom();
    let id = input("root.mobility.ay_fy");
    sim.set_input(id, -1e-3);
    sim.advance(1e-3).unwrap();
    let saved = sim.snapshot();
    sim.set_input(id, -2e-3);
    sim.restore_snapshot(&saved).unwrap();
    assert_eq!(sim.input(id), Some(-1e-3));
    assert_eq!(id.kind, InputKind::MountMobility);
}

#[test]
fn a_mobility_that_cancels_the_beams_inertia_is_refused_with_the_state_kept() {
    let mut sim = boom();
    let m = sim.apparent_mass().unwrap();
    let inv = nalgebra::Matrix3::from_fn(|i, j| m[i][j])
        .try_inverse()
        .unwrap();
    let (acc, reaction) = (["ax", "ay", "alphaz"], ["fx", "fy", "mz"]);
    for i in 0..3 {
        for j in 0..3 {
            let name = format!("root.mobility.{}_{}", acc[i], reaction[j]);
            assert!(sim.set_input(input(&name), inv[(i, j)]));
        }
    }
    let before = sim.outputs();
    let e = sim.advance(1e-3).unwrap_err().to_string();
    assert!(e.contains("root.mobility"), "{e}");
    assert_eq!(sim.time(), 0.0);
    assert_eq!(sim.outputs(), before);
}

/// The boom (a hybrid on a driven mount) coupled to a partner of mobility −1e-3 m/s² per N
/// vertically, integrated by `solver.method = "esdirk4"` (the partner's deviation at every
/// stage time): at one step per 1 ms communication step its tip meets generalized-α converged
/// (h = 10 µs) closer than generalized-α at ten steps (9.9e-8 vs 1.1e-7 m here; 2.9e-8 m at
/// 0.5 ms, 1.2e-8 m at 0.25 ms).
#[test]
fn esdirk_with_a_partner_meets_generalized_alpha_converged() {
    use hybeam::integrator::Method;
    let run = |method: Method, h: f64| {
        let mut sim = boom_with(|s| {
            s.solver.method = method;
            s.solver.max_step = h;
        });
        let id = input("root.mobility.ay_fy");
        outputs_of_swing(
            &mut sim,
            |sim| assert!(sim.set_input(id, -1e-3)),
            |n| n.starts_with("tip.position"),
        )
    };
    let diff = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let reference = run(Method::GeneralizedAlpha, 1e-5);
    let plain = run(Method::GeneralizedAlpha, 1e-4);
    let es = diff(&run(Method::Esdirk4, 1e-3), &reference);
    let ga = diff(&plain, &reference);
    eprintln!(
        "boom with a partner, 60 ms: ESDIRK h = 1 ms {es:.3e} m, generalized-α h = 0.1 ms {ga:.3e} m"
    );
    assert!(es < ga, "{es:e} vs {ga:e}");
}
