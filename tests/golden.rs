//! Regression against recordings made before the engine restructure (issue 7): the tip and root
//! histories of every shipped beam scene and the static results of the table tests, stored as
//! CSV in `tests/golden/` with shortest round-trip decimals (so equality is bit equality).
//!
//! The reference is the code at commit f1a8d8b, an independent build of the same physics: any
//! change in assembly order, coordinate update or step control shows up here. Histories must
//! agree within 1e-12 (m, N, N m, J, rad); the test prints how many rows are bit-identical.
//!
//! Re-record (only when a physics change is intended and explained):
//! `HYBEAM_RECORD_GOLDEN=1 cargo test --test golden`.

mod common;
use common::*;
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

fn row(out: &mut String, t: f64, sim: &Simulator) {
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
    let mut sim = Simulator::new(scene).expect("shipped scene builds");
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
        let mut sim = Simulator::new(s).unwrap();
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
