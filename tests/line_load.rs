//! Segment line loads (`line_load = [qx, qy(, qz)]` on a `[[segments]]` table, issue 39 item 4)
//! against independent references:
//! - a cantilever under a small uniform transverse line load q, gravity off: tip deflection
//!   qL⁴/(8EI) (Roark's Formulas for Stress and Strain, Table 8.1 case 2a, w_a = w_l): all-ANCF,
//!   all-modal and both hybrids, planar and spatial (cable, director and angle elements);
//! - a line load equal to ρA g with gravity off runs as gravity without a line load (tip history
//!   over 0.2 s, hybrid rods, planar and spatial);
//! - an undamped swing under a line load keeps kinetic + strain + potential (the line load's
//!   −∫qᵀr dx in the potential) constant, the start's potential against −q_x L²/2;
//! - the Newton matrices with line loads, gravity and point masses (the masses feel g, the
//!   distributed mass g + q/(ρA)) against central differences;
//! - malformed line loads are refused naming `segments.<name>.line_load`;
//! - the FMU input `<segment>.line_load.<axis>`: set at run time it runs as the scene's line
//!   load; ramped through its input derivatives (q = q̇t, communication steps of 10 ms) the tip
//!   follows the Euler–Bernoulli cantilever's exact modal solution for a ramped uniform load
//!   (clamped–free eigenfunctions, Meirovitch, Fundamentals of Vibrations §8.6), closer than
//!   the same ramp held at each step's start value.

mod common;
use common::*;
use hybeam::model::{Model, Planar, Spatial};
use hybeam::simulator::Simulator;

/// Rod: L = 1 m, steel, round d = 1 cm.
const L: f64 = 1.0;
const D: f64 = 0.01;

fn rho_a() -> f64 {
    RHO_STEEL * std::f64::consts::PI * D * D / 4.0
}

fn ei() -> f64 {
    E_STEEL * std::f64::consts::PI * D.powi(4) / 64.0
}

/// The test rods with `extra` (the line load) on every segment: (label, segments).
fn rods(extra: &str) -> Vec<(&'static str, Vec<String>)> {
    let r = round(D);
    vec![
        ("all-ANCF", vec![ancf("a", L, &r, 8, extra)]),
        ("all-modal", vec![modal("m", L, &r, 12, true, extra)]),
        (
            "hybrid modal+ANCF",
            vec![
                modal("m", 0.5 * L, &r, 10, true, extra),
                ancf("a", 0.5 * L, &r, 8, extra),
            ],
        ),
        (
            "hybrid ANCF+modal",
            vec![
                ancf("a", 0.5 * L, &r, 8, extra),
                modal("m", 0.5 * L, &r, 10, true, extra),
            ],
        ),
    ]
}

/// The spatial variants' headers: 3D cable, director element, angle element.
const SPATIAL: [&str; 3] = [
    "torsion = false",
    "torsion = true",
    "torsion = true\ntorsion_element = \"angle\"",
];

#[test]
fn uniform_line_load_deflects_the_tip_as_roark() {
    // w(L)/L = 1e-4: the linear range (the geometric correction is of order (w/L)²)
    let want = 1e-4 * L;
    let q = want * 8.0 * ei() / L.powi(4);
    let mut worst = 0.0f64;
    for (label, segs) in rods(&format!("line_load = [0.0, {:e}]", -q)) {
        let mut sim = Simulator::<Planar>::new(scene("", &segs)).unwrap();
        sim.solve_static().unwrap();
        let o = sim.outputs();
        let rel = -o.tip_position[1] / want - 1.0;
        eprintln!("planar {label}: tip deflection error {rel:+.2e}");
        worst = worst.max(rel.abs());
        // the support carries the load qL and its moment qL²/2
        assert!(
            (o.root_force[1] / (q * L) - 1.0).abs() < 1e-9,
            "{:?}",
            o.root_force
        );
    }
    for (label, segs) in rods(&format!("line_load = [0.0, 0.0, {:e}]", -q)) {
        for header in SPATIAL {
            if label == "hybrid ANCF+modal" && header == SPATIAL[0] {
                continue; // refused: a 3D cable cannot hold the modal segment's spin
            }
            let s = scene(&format!("space = \"spatial\"\n{header}"), &segs);
            let mut sim = Simulator::<Spatial>::new(s).unwrap();
            sim.solve_static().unwrap();
            let rel = -sim.outputs().tip_position[2] / want - 1.0;
            eprintln!("spatial {label} ({header}): tip deflection error {rel:+.2e}");
            worst = worst.max(rel.abs());
        }
    }
    eprintln!("worst relative error {worst:.2e}");
    assert!(worst < 1e-6, "{worst:e}");
}

/// The tip positions of a spatial run sampled every `dt` up to `t_end`.
fn tip_history_3d(s: hybeam::scene::Scene, t_end: f64, dt: f64) -> Vec<[f64; 3]> {
    let mut sim = Simulator::<Spatial>::new(s).unwrap();
    let mut out = vec![sim.outputs().tip_position];
    for k in 1..=(t_end / dt).round() as usize {
        sim.advance(k as f64 * dt).unwrap();
        out.push(sim.outputs().tip_position);
    }
    out
}

#[test]
fn line_load_of_rho_a_g_runs_as_gravity() {
    // hybrid rods released straight under gravity (g_x, g_y) vs gravity off and the line load
    // ρA g on every segment: the same motion (the loads are equal; rounding apart)
    let (gx, g) = (2.0, -9.81);
    let r = round(D);
    let segs = |extra: &str| {
        vec![
            modal("m", 0.5 * L, &r, 4, true, extra),
            ancf("a", 0.5 * L, &r, 6, extra),
        ]
    };
    let q = [rho_a() * gx, rho_a() * g];
    let mut worst = 0.0f64;
    let a = tip_history(
        scene(&format!("gravity = [{gx:e}, {g:e}]"), &segs("")),
        0.2,
        0.01,
    );
    let b = tip_history(
        scene("", &segs(&format!("line_load = [{:e}, {:e}]", q[0], q[1]))),
        0.2,
        0.01,
    );
    for (x, y) in a.iter().zip(&b) {
        for k in 0..2 {
            worst = worst.max((x[k] - y[k]).abs());
        }
    }
    let swing = (a[a.len() - 1][1] - a[0][1]).abs();
    eprintln!("planar: tip moved {swing:.3e} m, worst difference {worst:.2e} m");
    assert!(swing > 1e-3 && worst < 1e-12, "{swing:e} {worst:e}");
    for header in SPATIAL {
        let h = format!("space = \"spatial\"\n{header}");
        let a = tip_history_3d(
            scene(&format!("{h}\ngravity = [{gx:e}, 0.0, {g:e}]"), &segs("")),
            0.2,
            0.01,
        );
        let b = tip_history_3d(
            scene(
                &h,
                &segs(&format!("line_load = [{:e}, 0.0, {:e}]", q[0], q[1])),
            ),
            0.2,
            0.01,
        );
        let mut w = 0.0f64;
        for (x, y) in a.iter().zip(&b) {
            for k in 0..3 {
                w = w.max((x[k] - y[k]).abs());
            }
        }
        let swing = (a[a.len() - 1][2] - a[0][2]).abs();
        eprintln!("spatial ({header}): tip moved {swing:.3e} m, worst difference {w:.2e} m");
        assert!(swing > 1e-3 && w < 1e-12, "{swing:e} {w:e}");
        worst = worst.max(w);
    }
    eprintln!("worst difference {worst:.2e} m");
}

/// Kinetic + strain + potential over 0.5 s of a swinging rod: (start potential, largest
/// drift of the total, largest kinetic energy) [J].
fn swing_energy<S: hybeam::model::Space>(s: hybeam::scene::Scene) -> (f64, f64, f64) {
    let mut sim = Simulator::<S>::new(s).unwrap();
    let total = |o: &hybeam::model::Outputs<S>| o.kinetic + o.strain + o.potential;
    let o = sim.outputs();
    let (u0, e0) = (o.potential, total(&o));
    let (mut drift, mut kmax) = (0.0f64, 0.0f64);
    for k in 1..=500 {
        sim.advance(k as f64 * 1e-3).unwrap();
        let o = sim.outputs();
        drift = drift.max((total(&o) - e0).abs());
        kmax = kmax.max(o.kinetic);
    }
    (u0, drift, kmax)
}

#[test]
fn swinging_rod_under_a_line_load_keeps_its_energy() {
    // a pinned (planar) or ball-rooted (spatial) hybrid rod, gravity off, released straight
    // along x under the line load (q_x, q_y): kinetic + strain + potential constant over 0.5 s,
    // the drift falling with the step as the integrator's second order (h/2: about 1/4); the
    // start's potential −∫qᵀr dx = −q_x L²/2
    let r = round(0.004);
    let rho_a = RHO_STEEL * std::f64::consts::PI * 0.004f64.powi(2) / 4.0;
    let (l, qx, qy) = (0.4, 0.5 * rho_a, -9.81 * rho_a);
    let segs = |line: &str| {
        [
            modal("m", 0.5 * l, &r, 4, true, line),
            ancf("a", 0.5 * l, &r, 6, line),
        ]
    };
    let scale = -qy * l * l / 2.0;
    let want_u0 = -qx * l * l / 2.0;
    for spatial in [false, true] {
        let mut drifts = Vec::new();
        for h in [5e-4, 2.5e-4] {
            let solver = format!(
                "[solver]\nrho_inf = 0.99\nmax_step = {h:e}\ntolerance = 1e-11\nmax_iterations = 20\n"
            );
            let (u0, drift, kmax) = if spatial {
                let header =
                    format!("space = \"spatial\"\ntorsion = false\nroot = \"ball\"\n{solver}");
                let line = format!("line_load = [{qx:e}, 0.0, {qy:e}]");
                swing_energy::<Spatial>(scene(&header, &segs(&line)))
            } else {
                let header = format!("root = \"pinned\"\n{solver}");
                let line = format!("line_load = [{qx:e}, {qy:e}]");
                swing_energy::<Planar>(scene(&header, &segs(&line)))
            };
            let (drift, kmax) = (drift / scale, kmax / scale);
            eprintln!(
                "spatial {spatial}, max_step {h:e}: start potential {u0:.12e} J (closed form {want_u0:.12e}), energy drift {drift:.2e} of q L²/2, peak kinetic {kmax:.3} of it"
            );
            assert!((u0 / want_u0 - 1.0).abs() < 1e-12);
            assert!(kmax > 0.5, "it swings: {kmax}");
            assert!(drift < 1e-3, "{drift:e}");
            drifts.push(drift);
        }
        let ratio = drifts[0] / drifts[1];
        eprintln!("spatial {spatial}: drift ratio at h/2 {ratio:.2}");
        assert!(ratio > 3.0, "{ratio}");
    }
}

#[test]
fn newton_matrices_with_line_loads_match_central_differences() {
    let r = round(0.004);
    let mass = "[[masses]]\nname = \"p\"\nsegment = \"m1\"\nat = 0.13\nmass = 0.01\n";
    for lin in [false, true] {
        let lin = if lin { "linear = true" } else { "" };
        let segs = |line: &str| {
            vec![
                modal("m1", 0.2, &r, 3, true, &format!("{line}\n{lin}")),
                ancf("a", 0.2, &r, 2, line),
                modal("m2", 0.2, &r, 2, false, &format!("{line}\n{lin}\n{mass}")),
            ]
        };
        let s = scene(
            "root = \"pinned\"\ngravity = [1.0, -9.81]",
            &segs("line_load = [0.3, -0.5]"),
        );
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        let w = check_newton_matrix(&mut model);
        eprintln!("planar {lin}: worst error {w:.2e} of the tolerance");
        for torsion in ["torsion = true", "torsion_element = \"angle\""] {
            let s = scene(
                &format!(
                    "space = \"spatial\"\n{torsion}\nroot = \"ball\"\ngravity = [0.0, 1.0, -9.81]"
                ),
                &segs("line_load = [0.3, 0.2, -0.5]"),
            );
            let mut model = Model::<Spatial>::from_scene(&s).unwrap();
            let w = check_newton_matrix(&mut model);
            eprintln!("spatial {torsion} {lin}: worst error {w:.2e} of the tolerance");
        }
    }
}

#[test]
fn malformed_line_loads_are_refused_naming_the_field() {
    let r = round(D);
    let bad = |header: &str, line: &str| {
        let text = format!(
            "name = \"t\"\n{header}\n[[segments]]\n{}",
            ancf("rod", L, &r, 2, line)
        );
        hybeam::scene::Scene::from_toml(&text)
            .and_then(|s| s.validate().map(|_| s))
            .expect_err("refused")
            .to_string()
    };
    for (header, line, says) in [
        ("", "line_load = [1.0, 2.0, 3.0]", "takes 2 components"),
        (
            "space = \"spatial\"",
            "line_load = [1.0, 2.0]",
            "takes 3 components",
        ),
        ("", "line_load = [1.0, nan]", "finite"),
        (
            "root = \"mounted\"\n[initial]\nstate = \"static\"\n[mount]\nangle = 0.5",
            "line_load = [0.0, -1.0]",
            "initial.state",
        ),
    ] {
        let e = bad(header, line);
        eprintln!("{e}");
        assert!(
            e.contains("segments.rod.line_load") && e.contains(says),
            "{e}"
        );
    }
}

/// The tip of a run whose segments declare `line_load = [0, …]`, with the line-load inputs set
/// at each communication point t_k = k·dt by `load(t) = (q, q̇)` along `axis` (q̇ as the first
/// input derivative when `rates`); the tip component `axis` at every t_k.
fn ramped_tip(s: hybeam::scene::Scene, axis: usize, t_end: f64, dt: f64, rates: bool) -> Vec<f64> {
    use hybeam::simulator::{AnySimulator, InputId};
    let slots = s.line_load_segments().len();
    let mut sim = AnySimulator::new(s).unwrap();
    let mut out = vec![sim.outputs().tip_position()[axis]];
    for k in 0..(t_end / dt).round() as usize {
        let t = k as f64 * dt;
        for slot in 0..slots {
            let id = InputId::line_load(slot, axis);
            assert!(sim.set_input(id, RAMP * t));
            if rates {
                assert!(sim.set_input_derivative(id, 1, RAMP));
            }
        }
        sim.advance(t + dt).unwrap();
        out.push(sim.outputs().tip_position()[axis]);
    }
    out
}

/// The ramp rate of the line-load input tests [N/(m s)].
const RAMP: f64 = 2.0;

/// Tip deflection at time t of the uniform Euler–Bernoulli cantilever (length L, EI, ρA) at
/// rest until t = 0 under the uniform transverse load q = q̇t: the modal series
/// Σ_k φ_k(L) (q̇ ∫φ_k dx)/(ρA ∫φ_k² dx ω_k²) (t − sin(ω_k t)/ω_k) over the first `modes`
/// clamped–free eigenfunctions φ_k = cosh βx − cos βx − σ_k (sinh βx − sin βx),
/// σ_k = (cosh βL + cos βL)/(sinh βL + sin βL), ω_k = β_k² √(EI/ρA), cos βL cosh βL = −1;
/// the integrals by 40-point composite Gauss–Legendre per mode.
fn exact_ramp_tip(t: f64, modes: usize) -> f64 {
    // roots of cos x cosh x = -1 by Newton from (2k - 1)π/2
    let root = |k: usize| {
        let mut x = (2 * k - 1) as f64 * std::f64::consts::FRAC_PI_2;
        if k == 1 {
            x = 1.875;
        }
        for _ in 0..50 {
            let f = x.cos() * x.cosh() + 1.0;
            let df = -x.sin() * x.cosh() + x.cos() * x.sinh();
            x -= f / df;
        }
        x
    };
    let mut w = 0.0;
    for k in 1..=modes {
        let bl = root(k);
        let b = bl / L;
        let sigma = (bl.cosh() + bl.cos()) / (bl.sinh() + bl.sin());
        // cosh y − σ sinh y written without the cancellation of its large parts
        let phi = |x: f64| {
            let y = b * x;
            0.5 * ((1.0 - sigma) * y.exp() + (1.0 + sigma) * (-y).exp()) - y.cos() + sigma * y.sin()
        };
        let (g, w4) = (
            [
                -0.861_136_311_594_052_6,
                -0.339_981_043_584_856_3,
                0.339_981_043_584_856_3,
                0.861_136_311_594_052_6,
            ],
            [
                0.347_854_845_137_453_9,
                0.652_145_154_862_546_1,
                0.652_145_154_862_546_1,
                0.347_854_845_137_453_9,
            ],
        );
        let (mut i1, mut i2) = (0.0, 0.0);
        let panels = 40;
        let hp = L / panels as f64;
        for p in 0..panels {
            for (xg, wg) in g.iter().zip(&w4) {
                let x = (p as f64 + 0.5 * (xg + 1.0)) * hp;
                let f = phi(x);
                i1 += 0.5 * hp * wg * f;
                i2 += 0.5 * hp * wg * f * f;
            }
        }
        let omega = b * b * (ei() / rho_a()).sqrt();
        let p = RAMP * i1 / (rho_a() * i2 * omega * omega) * (t - (omega * t).sin() / omega);
        w += phi(L) * p;
    }
    w
}

#[test]
fn line_load_inputs_set_at_run_time_run_as_the_scene_line_load() {
    // q set through the input at t = 0 (the scene declares zero) against the scene's q: the
    // same run (the input is a jump at the start, applied as the scene's load is)
    let q = 0.7;
    // the test rods and a tapered ANCF rod (d = 1 cm → 5 mm), whose elements keep q per metre
    let with_taper = |extra: &str| {
        let mut r = rods(extra);
        let taper = "section = \"round\"\ndiameter = [0.01, 0.005]";
        r.push(("tapered ANCF", vec![ancf("a", L, taper, 8, extra)]));
        r
    };
    for (label, segs) in with_taper("line_load = [0.0, 0.0]") {
        let scene_q: Vec<String> = with_taper(&format!("line_load = [0.0, {q:e}]"))
            .into_iter()
            .find(|(l, _)| *l == label)
            .unwrap()
            .1;
        let reference = tip_history(scene("", &scene_q), 0.1, 0.01);
        let s = scene("", &segs);
        let slots = s.line_load_segments().len();
        let mut sim = hybeam::simulator::AnySimulator::new(s).unwrap();
        for slot in 0..slots {
            assert!(sim.set_input(hybeam::simulator::InputId::line_load(slot, 1), q));
        }
        let mut worst = 0.0f64;
        for (k, r) in reference.iter().enumerate().skip(1) {
            sim.advance(k as f64 * 0.01).unwrap();
            worst = worst.max((sim.outputs().tip_position()[1] - r[1]).abs());
        }
        let sag = reference.last().unwrap()[1].abs();
        eprintln!("{label}: tip sag {sag:.3e} m, input vs scene {worst:.2e} m");
        assert!(
            sag > 1e-5 && worst <= 1e-12 * sag.max(1.0),
            "{label}: {worst:e}"
        );
    }
}

#[test]
fn a_line_load_ramped_by_its_input_derivatives_follows_the_exact_modal_solution() {
    // q = q̇t on a clamped rod at rest, communication steps of 10 ms: with q̇ given as the
    // input's derivative every internal step integrates the ramp; held at each step's start
    // value the load lags by half a step
    let (t_end, dt): (f64, f64) = (0.3, 0.01);
    let exact: Vec<f64> = (0..=(t_end / dt).round() as usize)
        .map(|k| exact_ramp_tip(k as f64 * dt, 8))
        .collect();
    let peak = exact.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let error = |tip: &[f64]| {
        tip.iter()
            .zip(&exact)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / peak
    };
    let header = "[solver]\nmax_step = 1e-4";
    let planar = "line_load = [0.0, 0.0]";
    let spatial = "line_load = [0.0, 0.0, 0.0]";
    for (label, segs) in rods(planar) {
        let with = error(&ramped_tip(scene(header, &segs), 1, t_end, dt, true));
        let held = error(&ramped_tip(scene(header, &segs), 1, t_end, dt, false));
        eprintln!(
            "{label}: peak {peak:.3e} m, error/peak with derivatives {with:.2e}, held {held:.2e}"
        );
        assert!(
            with < 2e-5 && held > 100.0 * with,
            "{label}: {with:e} {held:e}"
        );
    }
    for torsion in SPATIAL {
        let h = format!("space = \"spatial\"\n{torsion}\n{header}");
        let segs = rods(spatial).remove(2).1; // the modal+ANCF hybrid
        let with = error(&ramped_tip(scene(&h, &segs), 2, t_end, dt, true));
        eprintln!("spatial hybrid ({torsion}): error/peak with derivatives {with:.2e}");
        assert!(with < 2e-5, "{torsion}: {with:e}");
    }
}
