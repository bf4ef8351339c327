//! Cost per step of spatial Case 1 against planar Case 1 (issue 9: at most 3×), for
//! instruction counting: `cargo test --release --test spatial_perf -- --ignored --nocapture
//! case1_steps_planar` (or `_spatial`) under
//! `valgrind --tool=callgrind --toggle-collect='*run_fixed_steps*'`: the count covers the
//! steps only (model build and initialization excluded). Both models take the same fixed
//! steps (h = max_step = 1e-4 s, 0.2 s) with the integrator's own Newton-matrix reuse; the
//! test prints the step, iteration and factorization counts. Ignored: a measurement, not a
//! check (the spatial test suites check the physics).

use hybeam::integrator::{GeneralizedAlpha, Integrable, State};
use hybeam::model::{Model, Planar, Space, Spatial};
use hybeam::scene::Scene;

fn scene(name: &str) -> Scene {
    let path = format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    Scene::from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Takes `steps` steps of `h`; returns (steps, Newton iterations, factorizations).
#[inline(never)]
fn run_fixed_steps<S: Space>(
    model: &mut Model<S>,
    integ: &mut GeneralizedAlpha,
    state: &mut State,
    h: f64,
    steps: usize,
) -> (u64, u64, u64) {
    for k in 0..steps {
        integ
            .step(model, state, h)
            .unwrap_or_else(|e| panic!("step {k}: {e}"));
    }
    let c = integ.counters();
    (c.steps, c.iterations, c.factorizations)
}

fn case1<S: Space>(model: &mut Model<S>, scene: &Scene) {
    let (n, m) = (model.coordinates(), model.constraints());
    let mut state = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
    let mut integ = GeneralizedAlpha::new(&scene.solver, n, m);
    integ.initialize(model, &mut state).unwrap();
    let h = scene.solver.max_step;
    let (s, it, f) = run_fixed_steps(model, &mut integ, &mut state, h, (0.2 / h) as usize);
    eprintln!(
        "{}: {n} coordinates, {m} constraints: {s} steps, {it} Newton iterations, {f} factorizations",
        scene.name
    );
}

#[test]
#[ignore = "measurement: run under callgrind"]
fn case1_steps_planar() {
    let sc = scene("case1.toml");
    case1(&mut Model::<Planar>::from_scene(&sc).unwrap(), &sc);
}

#[test]
#[ignore = "measurement: run under callgrind"]
fn case1_steps_spatial() {
    let sc = scene("case1_3d.toml");
    case1(&mut Model::<Spatial>::from_scene(&sc).unwrap(), &sc);
}

#[test]
#[ignore = "measurement: run under callgrind"]
fn case1_steps_spatial_cable() {
    let mut sc = scene("case1_3d.toml");
    sc.torsion = false;
    case1(&mut Model::<Spatial>::from_scene(&sc).unwrap(), &sc);
}
