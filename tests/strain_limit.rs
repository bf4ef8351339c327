//! `solver.max_axial_strain`: the strain limit a scene sets. A soft rod stretched 15 % by an
//! axial tip force runs with the limit raised to 0.25 and settles where the exact-strain rod
//! (ε = |r′| − 1, axial force EA ε) puts it, L (1 + F/(EA)); with the default 0.05 the step is
//! refused with a message that names the field.

use hybeam::scene::Scene;
use hybeam::simulator::{AnySimulator, OutputId, Quantity};

/// `scenes/<base>.toml` with gravity off, an axial tip force giving the strain `eps` and the
/// strain limit `limit` (the scene's default if `None`), started at its static equilibrium.
fn stretched(base: &str, eps: f64, limit: Option<f64>) -> (Scene, f64) {
    let path = format!("{}/scenes/{base}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let scene = Scene::from_toml(&text).unwrap();
    let seg = &scene.segments[0];
    let ea = seg.youngs_modulus * seg.section_props().area;
    let length = seg.length;
    let f = eps * ea;
    let spatial = scene.space == hybeam::scene::SpaceKind::Spatial;
    let zeros = if spatial {
        "[0.0, 0.0, 0.0]"
    } else {
        "[0.0, 0.0]"
    };
    let force = if spatial {
        format!("[{f:e}, 0.0, 0.0]")
    } else {
        format!("[{f:e}, 0.0]")
    };
    let mut sets = vec![
        ("gravity".to_string(), zeros.to_string()),
        ("tip.force".to_string(), force),
        ("initial.state".to_string(), "\"static\"".to_string()),
    ];
    if let Some(l) = limit {
        sets.push(("solver.max_axial_strain".into(), format!("{l:e}")));
    }
    (
        Scene::from_toml_with_overrides(&text, &sets).unwrap(),
        length,
    )
}

fn tip_x(sim: &AnySimulator) -> f64 {
    let id = OutputId {
        quantity: Quantity::TipPosition,
        component: 0,
    };
    sim.outputs().value(id).unwrap()
}

#[test]
fn a_soft_rod_stretches_past_five_percent_when_the_scene_allows_it() {
    for base in ["case1_ancf", "case1_3d_ancf"] {
        let eps = 0.15;
        let (scene, length) = stretched(base, eps, Some(0.25));
        let mut sim = AnySimulator::new(scene).unwrap();
        let want = length * (1.0 + eps);
        let err = (tip_x(&sim) - want).abs() / length;
        eprintln!(
            "{base}: static tip x {:.12} m, L(1 + F/EA) {want:.12} m, {err:.1e} of L",
            tip_x(&sim)
        );
        assert!(err < 1e-9, "{base}: {err:e}");
        // the state is within the raised limit: the steps are taken and stay there
        sim.advance(0.01).unwrap();
        let err = (tip_x(&sim) - want).abs() / length;
        assert!(err < 1e-6, "{base} after 10 ms: {err:e}");
    }
}

#[test]
fn beyond_the_limit_the_step_is_refused_naming_the_field() {
    for base in ["case1_ancf", "case1_3d_ancf"] {
        let (scene, _) = stretched(base, 0.15, None);
        let mut sim = AnySimulator::new(scene).unwrap();
        let e = sim.advance(0.001).unwrap_err().to_string();
        assert!(
            e.contains("axial strain 15.0 %") && e.contains("solver.max_axial_strain = 0.05"),
            "{base}: {e}"
        );
        let (scene, _) = stretched(base, 0.15, Some(0.1));
        let e = AnySimulator::new(scene)
            .unwrap()
            .advance(0.001)
            .unwrap_err()
            .to_string();
        assert!(e.contains("solver.max_axial_strain = 0.1"), "{base}: {e}");
    }
    // a limit outside (0, 1] is refused by the scene, naming the field and the value
    let text = std::fs::read_to_string(format!(
        "{}/scenes/case1_ancf.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    for bad in ["0.0", "-0.1", "1.5", "nan"] {
        let sets = [("solver.max_axial_strain".to_string(), bad.to_string())];
        let e = Scene::from_toml_with_overrides(&text, &sets).unwrap_err().0;
        assert!(e.contains("solver.max_axial_strain = "), "{bad}: {e}");
    }
}
