//! Regression against recordings made before the engine restructure (issue 7): the tip and root
//! histories of every shipped beam scene and the static results of the table tests, stored as
//! CSV in `tests/golden/` with shortest round-trip decimals (so equality is bit equality).
//!
//! The reference is the code at commit f1a8d8b, an independent build of the same physics: any
//! change in assembly order, coordinate update or step control shows up here. Histories must
//! agree within 1e-12 (m, N, N m, J, rad); the test prints how many rows are bit-identical.
//!
//! The spatial, mounted and driven recordings (`spatial_*`, `driven_*`) were made before the
//! restructure of issue 19 (commit 9fefcd9's engine) and must stay bit-identical: every
//! spatial scene to its `simulation.t_end`, all FMU outputs, and four scenes (planar and spatial, fixed and mounted)
//! under inputs, input derivatives, a mount path and a snapshot restored halfway.
//!
//! Every re-recording so far (what changed, why, and by how much against the recordings
//! before) is logged in docs/engine-findings.md, section "Golden re-recordings"; a new one adds
//! its paragraph there.
//!
//! Re-record (only when a physics change is intended and explained), e.g. the spatial ones:
//! `HYBEAM_RECORD_GOLDEN=1 cargo test --test golden spatial`.

mod common;
use common::*;
use hybeam::model::Planar;
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Output interval of the recorded histories [s].
const DT: f64 = 1e-2;
/// Agreement required where the summation order may have changed.
const TOL: f64 = 1e-12;

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

fn recording() -> bool {
    std::env::var_os("HYBEAM_RECORD_GOLDEN").is_some()
}

/// Every shipped planar beam scene (`scenes/`; the recordings predate the spatial scenes).
fn shipped_scenes() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let planar = |p: &PathBuf| {
        let text = std::fs::read_to_string(p).unwrap();
        Scene::from_toml(&text).unwrap().space == hybeam::scene::SpaceKind::Planar
    };
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml") && planar(p))
        .collect();
    v.sort();
    v
}

fn row(out: &mut String, t: f64, sim: &Simulator<Planar>) {
    let o = sim.outputs();
    let vals = [
        t,
        o.tip_position[0],
        o.tip_position[1],
        o.tip_velocity[0],
        o.tip_velocity[1],
        o.tip_angle,
        o.kinetic,
        o.strain,
        o.potential,
        o.root_force[0],
        o.root_force[1],
        o.root_moment,
    ];
    let line: Vec<String> = vals.iter().map(|x| format!("{x:e}")).collect();
    writeln!(out, "{}", line.join(",")).unwrap();
}

const HEADER: &str =
    "time,tip.x,tip.y,tip.vx,tip.vy,tip.angle,kinetic,strain,potential,root.fx,root.fy,root.mz";

/// Runs a scene to its `simulation.t_end` with outputs every [`DT`]; a refused step ends the
/// history with a `refused,<time>` line.
fn history(scene: Scene) -> String {
    let t_end = scene.simulation.t_end;
    let mut out = format!("{HEADER}\n");
    let mut sim = Simulator::<Planar>::new(scene).expect("shipped scene builds");
    row(&mut out, 0.0, &sim);
    let n = (t_end / DT).round() as usize;
    for k in 1..=n {
        let t = k as f64 * DT;
        if sim.advance(t).is_err() {
            writeln!(out, "refused,{t:e}").unwrap();
            break;
        }
        row(&mut out, t, &sim);
    }
    out
}

/// Static tip position and root reaction of the table tests' set-ups (tests/statics.rs).
fn statics() -> String {
    const L: f64 = 1.0;
    const B: f64 = 0.01;
    let ei = E_STEEL * B.powi(4) / 12.0;
    let rho_a = RHO_STEEL * B * B;
    let mut cases: Vec<(String, Scene)> = Vec::new();
    for alpha in [1.0, 2.0, 5.0, 10.0] {
        let h = format!("[tip]\nforce = [0.0, {:e}]", -alpha * ei / (L * L));
        cases.push((
            format!("elastica alpha={alpha}"),
            scene(&h, &[ancf("rod", L, &square(B), 32, "")]),
        ));
    }
    for gamma in [1.0, 2.0, 5.0, 10.0] {
        let h = format!("gravity = [0.0, {:e}]", -gamma * ei / (rho_a * L.powi(3)));
        cases.push((
            format!("self-weight gamma={gamma}"),
            scene(&h, &[ancf("rod", L, &square(B), 32, "")]),
        ));
    }
    let d = 0.002;
    let forms = || {
        [
            vec![
                modal("m", 0.2, &round(d), 4, true, ""),
                ancf("a", 0.2, &round(d), 8, ""),
            ],
            vec![ancf("a", 0.4, &round(d), 16, "")],
            vec![modal("m", 0.4, &round(d), 4, false, "")],
        ]
    };
    for (i, segs) in forms().into_iter().enumerate() {
        cases.push((
            format!("case1 sag form={i}"),
            scene("gravity = [0.0, -9.81]", &segs),
        ));
    }
    for (i, segs) in forms().into_iter().enumerate() {
        let h = "gravity = [0.0, -9.81]\n[tip]\nforce = [0.0, -5e-2]";
        cases.push((format!("case1 tip load form={i}"), scene(h, &segs)));
    }
    let mut out = String::from("case,tip.x,tip.y,tip.angle,root.fx,root.fy,root.mz\n");
    for (name, s) in cases {
        let mut sim = Simulator::<Planar>::new(s).unwrap();
        sim.solve_static().unwrap();
        let o = sim.outputs();
        let vals = [
            o.tip_position[0],
            o.tip_position[1],
            o.tip_angle,
            o.root_force[0],
            o.root_force[1],
            o.root_moment,
        ];
        let line: Vec<String> = vals.iter().map(|x| format!("{x:e}")).collect();
        writeln!(out, "{name},{}", line.join(",")).unwrap();
    }
    out
}

/// Compares a produced CSV with its recording: same rows and labels, numbers within [`TOL`].
/// Returns (rows, bit-identical rows, largest difference).
fn compare(name: &str, got: &str) -> (usize, usize, f64) {
    let path = golden_dir().join(format!("{name}.csv"));
    if recording() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        std::fs::write(&path, got).unwrap();
        return (0, 0, 0.0);
    }
    let want = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (gl, wl): (Vec<&str>, Vec<&str>) = (got.lines().collect(), want.lines().collect());
    assert_eq!(gl.len(), wl.len(), "{name}: row count differs");
    let (mut same, mut worst) = (0, 0.0f64);
    for (i, (g, w)) in gl.iter().zip(&wl).enumerate().skip(1) {
        if g == w {
            same += 1;
            continue;
        }
        for (a, b) in g.split(',').zip(w.split(',')) {
            match (a.parse::<f64>(), b.parse::<f64>()) {
                (Ok(x), Ok(y)) => {
                    let d = (x - y).abs();
                    worst = worst.max(d);
                    assert!(d <= TOL, "{name} row {i}: {a} vs recorded {b}\n{g}\n{w}");
                }
                _ => assert_eq!(a, b, "{name} row {i}"),
            }
        }
    }
    (wl.len() - 1, same, worst)
}

#[test]
fn shipped_scene_histories_match_the_recordings() {
    for path in shipped_scenes() {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = Scene::from_toml(&text).unwrap();
        let (rows, same, worst) = compare(&name, &history(scene));
        eprintln!("{name}: {same}/{rows} rows bit-identical, largest difference {worst:.1e}");
    }
}

#[test]
fn static_results_match_the_recordings() {
    let (rows, same, worst) = compare("statics", &statics());
    eprintln!("statics: {same}/{rows} rows bit-identical, largest difference {worst:.1e}");
}

// ---- Spatial, mounted and driven recordings (issue 19: made before the restructure) ----

use hybeam::simulator::{AnySimulator, OutputId};

/// Every output of `sim`'s space (and mount), in [`OutputId::named_with`] order, as a row.
fn any_row(out: &mut String, t: f64, sim: &AnySimulator, ids: &[(String, OutputId)]) {
    let o = sim.outputs();
    let mut line = vec![format!("{t:e}")];
    line.extend(
        ids.iter()
            .map(|(_, id)| format!("{:e}", o.value(*id).unwrap())),
    );
    writeln!(out, "{}", line.join(",")).unwrap();
}

/// The output names of a scene's FMU-level outputs, its stations' and beam stress included
/// (header of [`any_row`]).
fn any_ids(scene: &Scene) -> Vec<(String, OutputId)> {
    OutputId::of_scene(scene)
}

/// A history through [`AnySimulator`]: outputs every `dt` to `t_end`; before each step
/// `drive(t, sim)` may set inputs (it returns a replacement simulator to continue with, e.g.
/// one restored from a snapshot). A refused step ends it with `refused,<time>`.
fn any_history(
    scene: Scene,
    t_end: f64,
    dt: f64,
    mut drive: impl FnMut(f64, &mut AnySimulator) -> Option<AnySimulator>,
) -> String {
    let ids = any_ids(&scene);
    let names: Vec<&str> = ids.iter().map(|(n, _)| n.as_str()).collect();
    let mut out = format!("time,{}\n", names.join(","));
    let mut sim = AnySimulator::new(scene).expect("shipped scene builds");
    any_row(&mut out, 0.0, &sim, &ids);
    let n = (t_end / dt).round() as usize;
    for k in 1..=n {
        let t0 = (k - 1) as f64 * dt;
        if let Some(replaced) = drive(t0, &mut sim) {
            sim = replaced;
        }
        let t = k as f64 * dt;
        if sim.advance(t).is_err() {
            writeln!(out, "refused,{t:e}").unwrap();
            break;
        }
        any_row(&mut out, t, &sim, &ids);
    }
    out
}

/// Every shipped spatial scene (mounted ones continue their `[mount]` start motion).
fn spatial_scenes() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "toml") && {
                let text = std::fs::read_to_string(p).unwrap();
                Scene::from_toml(&text).unwrap().space == hybeam::scene::SpaceKind::Spatial
            }
        })
        .collect();
    v.sort();
    v
}

#[test]
fn spatial_scene_histories_match_the_recordings() {
    for path in spatial_scenes() {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let scene = Scene::from_toml(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let start = std::time::Instant::now();
        let t_end = scene.simulation.t_end;
        let got = any_history(scene, t_end, DT, |_, _| None);
        let (rows, same, worst) = compare(&name, &got);
        eprintln!(
            "{name}: {same}/{rows} rows bit-identical, largest difference {worst:.1e} ({:.1} s)",
            start.elapsed().as_secs_f64()
        );
        assert_eq!(same, rows, "{name}: recorded bit for bit, kept bit for bit");
    }
}

/// Histories under inputs set between communication steps (2 ms, 0.2 s): a sinusoidal tip
/// force with its first derivative (the FMU's input derivatives), a tip moment, a gravity
/// change at 0.1 s, the mount driven along a smooth path (mounted scenes), and at 0.1 s the
/// run continued in a fresh simulator restored from a snapshot: what the restructure of the
/// inputs and of the snapshot must keep bit for bit.
#[test]
fn driven_histories_match_the_recordings() {
    let setups: [(&str, f64, Option<Drive>); 4] = [
        ("case1", 0.02, None),
        ("case1_3d", 0.02, None),
        ("boom", 20.0, Some(boom_mount)),
        ("case1_3d_mounted", 0.02, Some(rod_3d_mount)),
    ];
    for (name, amplitude, mount) in setups {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"));
        let scene = Scene::from_toml(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let spatial = scene.space == hybeam::scene::SpaceKind::Spatial;
        let base = scene.clone();
        let g0 = *scene.gravity.last().unwrap_or(&0.0);
        let w = 2.0 * std::f64::consts::PI * 5.0;
        let got = any_history(scene, 0.2, 2e-3, |t, sim| {
            let (s, c) = (w * t).sin_cos();
            let (f, df) = (amplitude * s, amplitude * w * c);
            let lateral = if spatial {
                "tip.force.z"
            } else {
                "tip.force.y"
            };
            let moment = if spatial {
                "tip.moment.x"
            } else {
                "tip.moment.z"
            };
            let mut values = vec![
                (lateral.to_string(), f),
                ("tip.force.x".to_string(), 0.1 * f),
                (moment.to_string(), 0.01 * amplitude * c),
            ];
            if (t - 0.1).abs() < 1e-9 {
                let gravity = if spatial { "gravity.z" } else { "gravity.y" };
                values.push((gravity.to_string(), 1.1 * g0));
            }
            if let Some(m) = mount {
                values.extend(m(t));
            }
            set_inputs(sim, &values);
            let id = input_id(sim, lateral);
            assert!(sim.set_input_derivative(id, 1, df));
            // continue in a restored copy halfway (after the inputs were set: they travel in
            // the snapshot)
            ((t - 0.1).abs() < 1e-9).then(|| {
                let mut fresh = AnySimulator::restorable(base.clone()).unwrap();
                fresh.restore_snapshot(&sim.snapshot()).unwrap();
                fresh
            })
        });
        let (rows, same, worst) = compare(&format!("driven_{name}"), &got);
        assert!(!got.contains("refused"), "{name}: a refused step\n{got}");
        eprintln!(
            "driven {name}: {same}/{rows} rows bit-identical, largest difference {worst:.1e}"
        );
        assert_eq!(same, rows, "{name}: recorded bit for bit, kept bit for bit");
    }
}

/// A recorded setting: (recording, scene, overrides `(key, TOML value)`, t_end [s]).
type Setting = (
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
    f64,
);

/// The shipped settings no scene file holds (issue 38): the angle element, the 3D cable
/// (`torsion = false`) and ESDIRK4, planar and spatial: (recording, scene, overrides, t_end).
/// Recorded at commit 6cf647b's engine; every later change keeps them bit for bit. The
/// degree-5 elements and the error-controlled ESDIRK4 (issue 42) recorded when they landed.
const SETTINGS: [Setting; 8] = [
    (
        "setting_angle",
        "case1_3d_ancf",
        &[
            ("torsion_element", "\"angle\""),
            ("tip.force", "[0.0, 0.0362894, 0.0]"),
            ("tip.moment", "[0.001, 0.0, 0.0]"),
        ],
        0.2,
    ),
    (
        "setting_cable_3d",
        "case1_3d_ancf",
        &[("torsion", "false"), ("tip.force", "[0.0, 0.0362894, 0.0]")],
        0.2,
    ),
    (
        "setting_esdirk4",
        "case1",
        &[
            ("solver.method", "\"esdirk4\""),
            ("solver.max_step", "1e-3"),
        ],
        0.5,
    ),
    (
        "setting_esdirk4_3d",
        "case1_3d",
        &[
            ("solver.method", "\"esdirk4\""),
            ("solver.max_step", "1e-3"),
            ("tip.force", "[0.0, 0.0362894, 0.0]"),
        ],
        0.5,
    ),
    (
        "setting_esdirk4_angle",
        "case1_3d_ancf",
        &[
            ("torsion_element", "\"angle\""),
            ("solver.method", "\"esdirk4\""),
            ("solver.max_step", "5e-4"),
            ("tip.moment", "[0.001, 0.0, 0.0]"),
        ],
        0.2,
    ),
    (
        "setting_degree5",
        "soft_rod",
        &[("segments.0.elements", "4"), ("segments.0.degree", "5")],
        0.3,
    ),
    (
        "setting_degree5_cable_3d",
        "case1_3d_ancf",
        &[
            ("torsion", "false"),
            ("segments.0.elements", "4"),
            ("segments.0.degree", "5"),
            ("tip.force", "[0.0, 0.0362894, 0.0]"),
        ],
        0.2,
    ),
    (
        "setting_error_tolerance",
        "soft_rod",
        &[
            ("solver.method", "\"esdirk4\""),
            ("solver.max_step", "1e-2"),
            ("solver.error_tolerance", "1e-8"),
        ],
        0.3,
    ),
];

#[test]
fn setting_histories_match_the_recordings() {
    for (name, base, sets, t_end) in SETTINGS {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{base}.toml"));
        let sets: Vec<(String, String)> = sets
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = Scene::from_toml_with_overrides(&text, &sets).unwrap();
        let start = std::time::Instant::now();
        let got = any_history(scene, t_end, DT, |_, _| None);
        assert!(!got.contains("refused"), "{name}: a refused step\n{got}");
        let (rows, same, worst) = compare(name, &got);
        eprintln!(
            "{name}: {same}/{rows} rows bit-identical, largest difference {worst:.1e} ({:.1} s)",
            start.elapsed().as_secs_f64()
        );
        assert_eq!(same, rows, "{name}: recorded bit for bit, kept bit for bit");
    }
}
