//! The clamp of an all-ANCF root holds the slope's direction, not its length
//! (`src/model/direction.rs`): an axial tip force stretches the clamped Case 1 rod by FL/(EA)
//! at any mesh (before: −2.9 % at 4 elements), a transverse one bends it by FL³/(3EI), and
//! the support's reaction balances the load — planar, spatial with torsion and the 3D cable.

use hybeam::scene::Scene;
use hybeam::simulator::{AnySimulator, OutputId};
use std::f64::consts::PI;
use std::path::PathBuf;

fn statics(name: &str, sets: &[(&str, &str)]) -> AnySimulator {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let sets: Vec<(String, String)> = sets
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let mut sim =
        AnySimulator::new(Scene::from_toml_with_overrides(&text, &sets).unwrap()).unwrap();
    sim.solve_static().unwrap();
    sim
}

fn output(sim: &AnySimulator, name: &str) -> f64 {
    let id = OutputId::named_with(sim.space(), false)
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap()
        .1;
    sim.outputs().value(id).unwrap()
}

#[test]
fn an_axial_tip_force_stretches_the_clamped_rod_by_fl_over_ea() {
    let (l, e, d) = (0.4, 2.1e11, 0.002);
    let ea = e * PI * d * d / 4.0;
    let ei = e * PI * d.powi(4) / 64.0;
    for (name, zero, axial, lateral, down, torsion) in [
        (
            "case1_ancf",
            "[0.0, 0.0]",
            "[1.0, 0.0]",
            "[0.0, -0.01]",
            "y",
            None,
        ),
        (
            "case1_3d_ancf",
            "[0.0, 0.0, 0.0]",
            "[1.0, 0.0, 0.0]",
            "[0.0, 0.0, -0.01]",
            "z",
            Some("true"),
        ),
        (
            "case1_3d_ancf",
            "[0.0, 0.0, 0.0]",
            "[1.0, 0.0, 0.0]",
            "[0.0, 0.0, -0.01]",
            "z",
            Some("false"),
        ),
    ] {
        for n in ["4", "16"] {
            let mut sets = vec![
                ("gravity", zero),
                ("segments.0.elements", n),
                ("tip.force", axial),
            ];
            if let Some(t) = torsion {
                sets.push(("torsion", t));
            }
            let sim = statics(name, &sets);
            let stretch = output(&sim, "tip.position.x") - l;
            let want = l / ea;
            assert!(
                (stretch / want - 1.0).abs() < 1e-4,
                "{name} torsion {torsion:?}, {n} elements: stretch {stretch:e} vs FL/EA {want:e}"
            );
            // the support holds the load
            assert!((output(&sim, "root.force.x") + 1.0).abs() < 1e-9, "{name}");
            // bending: FL³/(3EI) for a small transverse force, the root moment F·x_tip
            sets.retain(|(k, _)| *k != "tip.force");
            sets.push(("tip.force", lateral));
            let sim = statics(name, &sets);
            let w = output(&sim, &format!("tip.position.{down}"));
            let want = -0.01 * l.powi(3) / (3.0 * ei);
            assert!(
                (w / want - 1.0).abs() < 1e-3,
                "{name} {n}: deflection {w:e} vs {want:e}"
            );
            let moment = if down == "y" {
                "root.moment.z"
            } else {
                "root.moment.y"
            };
            let arm = output(&sim, "tip.position.x");
            let m = output(&sim, moment);
            let want_m = if down == "y" { 0.01 * arm } else { -0.01 * arm };
            assert!(
                (m - want_m).abs() < 1e-9 * 0.01 * l,
                "{name} {n}: root moment {m:e} vs {want_m:e}"
            );
        }
    }
}
