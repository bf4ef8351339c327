//! Stations (`[[stations]]`, issue 40 item 1): the section loads at a cut, by the equilibrium
//! of the part beyond it, against independent references:
//! - a static cantilever under a tip force F and moment M: M(s) = M + F (L − s), V = F, N = 0
//!   (statics of the part beyond the cut), planar and spatial, all-ANCF, all-modal, hybrid, a
//!   station at the joint;
//! - under its weight: M(s) = q (L − s)²/2, V = q (L − s) at 4 elements;
//! - in motion: a station at the root equals minus the support reaction (`root.force`,
//!   `root.moment`) at every communication point, fixed and mounted; stations just inboard and
//!   just outboard of a joint agree;
//! - the stress: σ = N/A ± M c/I and τ = T r/J for round, tube and rectangle sections and the
//!   von Mises combination against hand evaluations;
//! - bad stations are refused naming the field, the value and the fix.

mod common;
use common::*;
use hybeam::model::{Planar, SectionShape, Spatial, StressSection};
use hybeam::scene::Scene;
use hybeam::simulator::{AnySimulator, Simulator};

const L: f64 = 1.0;
const D: f64 = 0.01;

fn ei() -> f64 {
    E_STEEL * std::f64::consts::PI * D.powi(4) / 64.0
}

fn rho_a() -> f64 {
    RHO_STEEL * std::f64::consts::PI * D * D / 4.0
}

/// The rods: (label, segments, stations text). Stations at 0, ¼, ½ (the joint of the hybrids,
/// as the first segment's end), ¾ and L, and inside ANCF elements and modal bodies between them.
fn rods() -> Vec<(&'static str, Vec<String>, String)> {
    let r = round(D);
    let st = |seg: &str, at: f64, name: &str| {
        format!("[[stations]]\nname = \"{name}\"\nsegment = \"{seg}\"\nat = {at:e}\n")
    };
    // the nodes of 8 elements and cuts inside them (the element integrates its part)
    let one = |seg: &str| {
        [0.0, 0.06, 0.25, 0.3, 0.5, 0.61, 0.75, 0.93, 1.0]
            .iter()
            .enumerate()
            .map(|(k, s)| st(seg, *s, &format!("s{k}")))
            .collect::<String>()
    };
    let two = |a: &str, b: &str, a_cuts: &[f64], b_cuts: &[f64]| {
        let mut out = String::new();
        let mut k = 0;
        for s in a_cuts {
            out += &st(a, *s, &format!("s{k}"));
            k += 1;
        }
        for s in b_cuts {
            out += &st(b, *s, &format!("s{k}"));
            k += 1;
        }
        out
    };
    vec![
        ("all-ANCF", vec![ancf("a", L, &r, 8, "")], one("a")),
        ("all-modal", vec![modal("m", L, &r, 8, true, "")], {
            [0.0, 0.1, 0.37, 0.5, 0.81, 1.0]
                .iter()
                .enumerate()
                .map(|(k, s)| st("m", *s, &format!("s{k}")))
                .collect()
        }),
        (
            "hybrid modal+ANCF",
            vec![
                modal("m", 0.5 * L, &r, 6, true, ""),
                ancf("a", 0.5 * L, &r, 4, ""),
            ],
            two(
                "m",
                "a",
                &[0.0, 0.1, 0.33, 0.5],
                &[0.0, 0.05, 0.25, 0.3, 0.5],
            ),
        ),
        (
            "hybrid ANCF+modal",
            vec![
                ancf("a", 0.5 * L, &r, 4, ""),
                modal("m", 0.5 * L, &r, 6, true, ""),
            ],
            two(
                "a",
                "m",
                &[0.0, 0.07, 0.125, 0.2, 0.44, 0.5],
                &[0.0, 0.12, 0.29, 0.5],
            ),
        ),
    ]
}

/// The arc length of each station of `scene` from the root [m].
fn arcs(scene: &Scene) -> Vec<f64> {
    scene
        .stations
        .iter()
        .map(|st| {
            let i = scene
                .segments
                .iter()
                .position(|s| s.name == st.segment)
                .unwrap();
            scene.segments[..i].iter().map(|s| s.length).sum::<f64>() + st.at
        })
        .collect()
}

fn with_stations(header: &str, segs: &[String], stations: &str) -> Scene {
    let mut text = format!("name = \"test\"\n{header}\n");
    for s in segs {
        text += "[[segments]]\n";
        text += s;
        text += "\n";
    }
    text += stations;
    Scene::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The section loads at arc length s of a straight Euler–Bernoulli cantilever (EI, GJ, length
/// L, along x) in static equilibrium under the tip force F and tip moment M (world axes), the
/// deformed geometry to first order: the loads of the part beyond the cut, world axes,
/// F and M + (r_tip − r(s)) × F with the deflections v(s) = (M_z s²/2 + F_y(Ls²/2 − s³/6))/EI,
/// w(s) = −(M_y s²/2 − F_z(Ls²/2 − s³/6))/EI, turned into the section frame rotated by
/// θ(s) = (T s/GJ, −w′(s), v′(s)) (first order: X − θ × X).
fn cantilever_section(s: f64, f: [f64; 3], m: [f64; 3], gj: f64) -> ([f64; 3], [f64; 3]) {
    let e = ei();
    let v = |x: f64| (m[2] * x * x / 2.0 + f[1] * (L * x * x / 2.0 - x.powi(3) / 6.0)) / e;
    let w = |x: f64| -(m[1] * x * x / 2.0 - f[2] * (L * x * x / 2.0 - x.powi(3) / 6.0)) / e;
    let dv = (m[2] * s + f[1] * (L * s - s * s / 2.0)) / e;
    let dw = -(m[1] * s - f[2] * (L * s - s * s / 2.0)) / e;
    let phi = if gj > 0.0 { m[0] * s / gj } else { 0.0 };
    let arm = [L - s, v(L) - v(s), w(L) - w(s)];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mw = {
        let c = cross(arm, f);
        [m[0] + c[0], m[1] + c[1], m[2] + c[2]]
    };
    let theta = [phi, -dw, dv];
    let turn = |x: [f64; 3]| {
        let c = cross(theta, x);
        [x[0] - c[0], x[1] - c[1], x[2] - c[2]]
    };
    (turn(f), turn(mw))
}

#[test]
fn static_cantilever_sections_carry_the_tip_loads() {
    // w(L)/L ≈ 1e-5: the static solve's residual (~1e-9 N) is 1e-7 of the loads, and the
    // reference keeps the first-order turn of the section frames (θ ~ 1e-5)
    let f = 1e-5 * 3.0 * ei() / L.powi(2);
    let m = 0.3 * f * L;
    let mut worst = 0.0f64;
    for (label, segs, stations) in rods() {
        let header = format!("gravity = [0.0, 0.0]\n[tip]\nforce = [0.0, {f:e}]\nmoment = [{m:e}]");
        let s = with_stations(&header, &segs, &stations);
        let at = arcs(&s);
        let mut sim = Simulator::<Planar>::new(s).unwrap();
        sim.solve_static().unwrap();
        let o = sim.outputs();
        for (k, s) in at.iter().enumerate() {
            let st = o.stations[k];
            let (wf, wm) = cantilever_section(*s, [0.0, f, 0.0], [0.0, 0.0, m], 0.0);
            let e = [
                (st.moment[2] - wm[2]).abs() / (f * L),
                (st.force[1] - wf[1]).abs() / f,
                (st.force[0] - wf[0]).abs() / f,
            ];
            eprintln!(
                "planar {label} s = {s}: M {:.6e} vs {:.6e}, V {:.6e}, N {:.3e} vs {:.3e}; errors {:.1e} {:.1e} {:.1e}",
                st.moment[2], wm[2], st.force[1], st.force[0], wf[0], e[0], e[1], e[2]
            );
            for x in e {
                worst = worst.max(x);
                assert!(x <= 1e-6, "planar {label} at s = {s}: {st:?}");
            }
        }
    }
    // spatial: tip force (0, F_y, F_z), moment (T, M_y, M_z); director element and the 3D cable
    let (fy, fz) = (f, -0.5 * f);
    let (t, my, mz) = (0.2 * f * L, -0.1 * f * L, 0.3 * f * L);
    let gj = E_STEEL / (2.0 * 1.3) * std::f64::consts::PI * D.powi(4) / 32.0;
    for torsion in ["torsion = true", "torsion = false"] {
        for (label, segs, stations) in rods() {
            if torsion == "torsion = false" && label == "hybrid ANCF+modal" {
                continue; // refused: a 3D cable cannot hold the modal segment's spin
            }
            let tt = if torsion == "torsion = false" { 0.0 } else { t };
            let header = format!(
                "space = \"spatial\"\n{torsion}\ngravity = [0.0, 0.0, 0.0]\n[tip]\nforce = [0.0, {fy:e}, {fz:e}]\nmoment = [{tt:e}, {my:e}, {mz:e}]"
            );
            let s = with_stations(&header, &segs, &stations);
            let at = arcs(&s);
            let mut sim = Simulator::<Spatial>::new(s).unwrap();
            sim.solve_static().unwrap();
            let o = sim.outputs();
            for (k, s) in at.iter().enumerate() {
                let st = o.stations[k];
                let (want_f, want_m) = cantilever_section(*s, [0.0, fy, fz], [tt, my, mz], gj);
                for c in 0..3 {
                    // a 3D cable carries no torque (its deflection turns the moment off its
                    // tangent), where the first-order reference of a beam with GJ has −θ × M:
                    // its torsion is not compared
                    let cable_torsion = torsion == "torsion = false" && c == 0;
                    let em = if cable_torsion {
                        0.0
                    } else {
                        (st.moment[c] - want_m[c]).abs() / (f * L)
                    };
                    let ef = (st.force[c] - want_f[c]).abs() / f;
                    worst = worst.max(em).max(ef);
                    assert!(
                        em <= 1e-6 && ef <= 1e-6,
                        "spatial {label} ({torsion}) at s = {s}: {st:?} vs {want_f:?} {want_m:?}"
                    );
                }
            }
        }
    }
    eprintln!("worst relative error {worst:.2e}");
}

#[test]
fn sections_under_the_weight_of_the_part_beyond() {
    // gravity −y, 4 elements: M_z(s) = −q (L − s)²/2 (the weight beyond pulls the tip down),
    // V_y = −q (L − s); stiff enough that the sag is 1e-7 L
    let g = 1e-7 * 8.0 * ei() / (rho_a() * L.powi(4));
    let q = rho_a() * g;
    let r = round(D);
    let stations: String = [0.0, 0.25, 0.5, 0.75, 1.0]
        .iter()
        .enumerate()
        .map(|(k, s)| format!("[[stations]]\nname = \"s{k}\"\nsegment = \"a\"\nat = {s:e}\n"))
        .collect();
    let s = with_stations(
        &format!("gravity = [0.0, {:e}]", -g),
        &[ancf("a", L, &r, 4, "")],
        &stations,
    );
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    for (k, s) in [0.0, 0.25, 0.5, 0.75].iter().enumerate() {
        let st = o.stations[k];
        let (m, v) = (-q * (L - s).powi(2) / 2.0, -q * (L - s));
        let (em, ev) = (
            (st.moment[2] / m - 1.0).abs(),
            (st.force[1] / v - 1.0).abs(),
        );
        eprintln!(
            "s = {s}: M {:.6e} vs {m:.6e} ({em:.1e}), V {:.6e} vs {v:.6e} ({ev:.1e})",
            st.moment[2], st.force[1]
        );
        assert!(em <= 1e-5 && ev <= 1e-5, "{st:?}");
    }
    // at the free end nothing is beyond
    assert!(
        o.stations[4].force[1].abs() <= 1e-12 * q && o.stations[4].moment[2].abs() <= 1e-12 * q
    );
}

/// Largest |station at the root + reaction| over a run, relative to the reaction's range.
fn root_station_vs_reaction(scene: Scene, drive: Option<Drive>, t_end: f64, dt: f64) -> (f64, f64) {
    let spatial = scene.space == hybeam::scene::SpaceKind::Spatial;
    let mut sim = AnySimulator::new(scene).unwrap();
    let (mut worst, mut range) = (0.0f64, 0.0f64);
    for k in 0..=(t_end / dt).round() as usize {
        if k > 0 {
            if let Some(d) = drive {
                set_inputs(&mut sim, &d(k as f64 * dt));
            }
            sim.advance(k as f64 * dt).unwrap();
        }
        let o = sim.outputs();
        let name = |n: &str| input_id(&sim, n);
        let _ = name;
        let (f, m): (Vec<f64>, Vec<f64>) = match &o {
            hybeam::simulator::AnyOutputs::Planar(p) => {
                (p.root_force.to_vec(), vec![p.root_moment])
            }
            hybeam::simulator::AnyOutputs::Spatial(p) => {
                (p.root_force.to_vec(), p.root_moment.to_vec())
            }
        };
        let (st, frame) = match &o {
            hybeam::simulator::AnyOutputs::Planar(p) => {
                (p.stations[0], sim.shape(1).points[0].frame)
            }
            hybeam::simulator::AnyOutputs::Spatial(p) => {
                (p.stations[0], sim.shape(1).points[0].frame)
            }
        };
        // the station's loads in world axes: Σ_c comp_c · frame_c
        let world = |v: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|i| (0..3).map(|c| v[c] * frame[c][i]).sum())
        };
        let (sf, sm) = (world(st.force), world(st.moment));
        let dims = if spatial { 3 } else { 2 };
        for i in 0..dims {
            worst = worst.max((sf[i] + f[i]).abs());
            range = range.max(f[i].abs());
        }
        let mw: Vec<f64> = if spatial { sm.to_vec() } else { vec![sm[2]] };
        for (a, b) in mw.iter().zip(&m) {
            worst = worst.max((a + b).abs());
            range = range.max(b.abs());
        }
    }
    (worst, range)
}

#[test]
fn a_station_at_the_root_is_minus_the_reaction_in_motion() {
    let r = round(D);
    let st = "[[stations]]\nname = \"root\"\nsegment = \"m\"\nat = 0.0\n[[stations]]\nname = \"in\"\nsegment = \"m\"\nat = 0.5\n[[stations]]\nname = \"out\"\nsegment = \"a\"\nat = 0.0\n";
    let segs = vec![
        modal("m", 0.5 * L, &r, 4, true, ""),
        ancf("a", 0.5 * L, &r, 6, ""),
    ];
    // released straight under gravity, planar and spatial (director element)
    for header in [
        "gravity = [0.0, -9.81]",
        "space = \"spatial\"\ngravity = [0.0, 0.0, -9.81]",
    ] {
        let s = with_stations(header, &segs, st);
        let (worst, range) = root_station_vs_reaction(s.clone(), None, 0.2, 0.01);
        eprintln!("{header}: |station(0) + reaction| ≤ {worst:.2e} of range {range:.3e}");
        assert!(range > 1e-3 && worst <= 1e-9 * range, "{worst:e} {range:e}");
        // the joint: the end of the modal segment and the start of the ANCF one are one cut
        let mut sim = AnySimulator::new(s).unwrap();
        sim.advance(0.05).unwrap();
        let (a, b) = match sim.outputs() {
            hybeam::simulator::AnyOutputs::Planar(p) => (p.stations[1], p.stations[2]),
            hybeam::simulator::AnyOutputs::Spatial(p) => (p.stations[1], p.stations[2]),
        };
        for c in 0..3 {
            assert!(
                (a.force[c] - b.force[c]).abs() <= 1e-9 * range,
                "{a:?} {b:?}"
            );
            assert!(
                (a.moment[c] - b.moment[c]).abs() <= 1e-9 * range,
                "{a:?} {b:?}"
            );
        }
    }
    // mounted: the roof boom driven by the car's heave and pitch
    let path = format!("{}/scenes/boom.toml", env!("CARGO_MANIFEST_DIR"));
    let mut text = std::fs::read_to_string(path).unwrap();
    let first = Scene::from_toml(&text).unwrap().segments[0].name.clone();
    text += &format!("\n[[stations]]\nname = \"root\"\nsegment = \"{first}\"\nat = 0.0\n");
    let (worst, range) = root_station_vs_reaction(
        Scene::from_toml(&text).unwrap(),
        Some(boom_mount),
        0.2,
        0.01,
    );
    eprintln!("mounted boom: |station(0) + reaction| ≤ {worst:.2e} of range {range:.3e}");
    assert!(range > 1.0 && worst <= 1e-9 * range, "{worst:e} {range:e}");
}

#[test]
fn section_stresses_match_hand_formulas() {
    use std::f64::consts::PI;
    let (r, ri, b, h): (f64, f64, f64, f64) = (0.02, 0.015, 0.03, 0.05);
    let round = StressSection {
        shape: SectionShape::Round(r),
        area: PI * r * r,
        i_y: PI * r.powi(4) / 4.0,
        i_z: PI * r.powi(4) / 4.0,
    };
    let (n, m, t) = (1e4, 300.0, 200.0);
    // axial + bending: the extreme fibre N/A + M r/I
    let want = n / round.area + m * r / round.i_z;
    assert!((round.stress([n, 0.0, 0.0], [0.0, 0.0, m]) / want - 1.0).abs() < 1e-12);
    // torsion: τ = T r/J, σ_v = √3 τ
    let tau = t * r / (PI * r.powi(4) / 2.0);
    assert!((round.stress([0.0; 3], [t, 0.0, 0.0]) / (3f64.sqrt() * tau) - 1.0).abs() < 1e-12);
    // combined: the extreme fibre of the bending about y, where τ_T is the same everywhere
    let s = n / round.area + m * r / round.i_y;
    let vm = (s * s + 3.0 * tau * tau).sqrt();
    assert!((round.stress([n, 0.0, 0.0], [t, m, 0.0]) / vm - 1.0).abs() < 1e-12);
    // shear of a solid round section at its neutral axis: 4V/(3A)
    let v = 500.0;
    let want = 3f64.sqrt() * 4.0 * v / (3.0 * round.area);
    assert!((round.stress([0.0, v, 0.0], [0.0; 3]) / want - 1.0).abs() < 1e-12);
    // tube: N/A + M r_o/I, torsion T r_o/J, thin-walled shear 2V/A at the neutral axis
    let a = PI * (r * r - ri * ri);
    let i = PI * (r.powi(4) - ri.powi(4)) / 4.0;
    let tube = StressSection {
        shape: SectionShape::Tube(r, ri),
        area: a,
        i_y: i,
        i_z: i,
    };
    assert!((tube.stress([n, 0.0, 0.0], [0.0, 0.0, m]) / (n / a + m * r / i) - 1.0).abs() < 1e-12);
    let tau = t * r / (2.0 * i);
    assert!((tube.stress([0.0; 3], [t, 0.0, 0.0]) / (3f64.sqrt() * tau) - 1.0).abs() < 1e-12);
    assert!(
        (tube.stress([0.0, v, 0.0], [0.0; 3]) / (3f64.sqrt() * 2.0 * v / a) - 1.0).abs() < 1e-12
    );
    // rectangle b × h: corners N/A + M_z (h/2)/I_z + M_y (b/2)/I_y; shear 1.5 V/A at mid-depth
    let (iy, iz) = (h * b.powi(3) / 12.0, b * h.powi(3) / 12.0);
    let rect = StressSection {
        shape: SectionShape::Rectangle(b, h),
        area: b * h,
        i_y: iy,
        i_z: iz,
    };
    let want = n / (b * h) + m * (h / 2.0) / iz + 0.5 * m * (b / 2.0) / iy;
    assert!((rect.stress([n, 0.0, 0.0], [0.0, 0.5 * m, m]) / want - 1.0).abs() < 1e-12);
    assert!(
        (rect.stress([0.0, v, 0.0], [0.0; 3]) / (3f64.sqrt() * 1.5 * v / (b * h)) - 1.0).abs()
            < 1e-12
    );
    // torsion of a rectangle: Roark's τ_max within 1 % of the Saint-Venant value for h/b = 5/3
    // (k₂ = 0.2190 … interpolated from Timoshenko & Goodier's table: 0.208 at 1, 0.231 at 1.5,
    // 0.246 at 2): τ_max = T/(k₂ h b²)
    let k2: f64 = 0.231 + (0.246 - 0.231) * ((h / b) - 1.5) / 0.5;
    let sv = t / (k2 * h * b * b);
    let got = rect.stress([0.0; 3], [t, 0.0, 0.0]) / 3f64.sqrt();
    eprintln!("rectangle torsion: {got:.4e} vs Saint-Venant {sv:.4e}");
    assert!((got / sv - 1.0).abs() < 0.01, "{got:e} {sv:e}");
}

#[test]
fn bad_stations_are_refused_naming_the_field() {
    let r = round(D);
    let segs = vec![
        modal("m", 0.5 * L, &r, 4, true, ""),
        ancf("a", 0.5 * L, &r, 4, ""),
    ];
    let text = |stations: &str| {
        let mut t = "name = \"t\"\n".to_string();
        for s in &segs {
            t += "[[segments]]\n";
            t += s;
            t += "\n";
        }
        t + stations
    };
    for (stations, want) in [
        ("[[stations]]\nname = \"w\"\nsegment = \"a\"\nat = 0.6\n", "stations[0].at = 0.6: not a cut of segment \"a\""),

        ("[[stations]]\nname = \"w\"\nsegment = \"m\"\nat = 0.7\n", "stations[0].at = 0.7: not a cut of segment \"m\", which is 0.5 m long; give the arc length from its start, 0 to 0.5 m"),
        ("[[stations]]\nname = \"w\"\nsegment = \"m\"\nat = -0.1\n", "stations[0].at = -0.1: not a cut of segment \"m\""),
        ("[[stations]]\nname = \"w\"\nsegment = \"a\"\nat = nan\n", "stations[0].at = NaN: not a cut of segment \"a\""),
        ("[[stations]]\nname = \"w\"\nsegment = \"x\"\nat = 0.0\n", "stations[0].segment = \"x\": no segment has this name"),
        ("[[stations]]\nname = \"w\"\nsegment = \"a\"\nat = 0.0\n[[stations]]\nname = \"w\"\nsegment = \"a\"\nat = 0.5\n", "stations[1].name = \"w\": station names must be unique"),
        ("[[stations]]\nname = \"a b\"\nsegment = \"a\"\nat = 0.0\n", "stations[0].name = \"a b\""),
    ] {
        let err = Scene::from_toml(&text(stations)).unwrap_err().0;
        assert!(err.contains(want), "{err}\nwanted: {want}");
    }
}

#[test]
fn the_largest_stress_along_a_tip_loaded_cantilever_is_at_its_root() {
    // outputs.stress: σ_max = F L r/I at s = 0 (Euler–Bernoulli: the moment is largest at the
    // clamp); the cubic elements' curvature is exact for the linear moment of a tip load, the
    // modal segment's (8 modes + the interface shapes, which hold the static tip-load shape) too
    let f = 1e-5 * 3.0 * ei() / L.powi(2);
    let i = std::f64::consts::PI * D.powi(4) / 64.0;
    let want = f * L * (D / 2.0) / i;
    for (label, segs, _) in rods() {
        let header =
            format!("gravity = [0.0, 0.0]\n[outputs]\nstress = true\n[tip]\nforce = [0.0, {f:e}]");
        let s = with_stations(&header, &segs, "");
        let mut sim = Simulator::<Planar>::new(s).unwrap();
        sim.solve_static().unwrap();
        let (sigma, at) = sim.outputs().stress_max;
        eprintln!("{label}: σ_max {sigma:.6e} Pa at s = {at} (F L r/I = {want:.6e})");
        assert!(
            (sigma / want - 1.0).abs() < 1e-4 && at == 0.0,
            "{label}: {sigma:e} at {at}"
        );
    }
    // without outputs.stress: no such output
    let s = with_stations("", &rods()[0].1, "");
    let names: Vec<String> = hybeam::simulator::OutputId::of_scene(&s)
        .into_iter()
        .map(|(n, _)| n)
        .collect();
    assert!(!names.iter().any(|n| n.starts_with("beam.")), "{names:?}");
}

#[test]
fn stations_inside_planar_ancf_elements() {
    // the part of the element before the cut integrated by the element: the tip-loaded and the
    // weighted cantilever at cuts between the nodes (4 elements of 0.25 m), against the same
    // closed forms as at the nodes
    let r = round(D);
    let at = [0.1, 0.3, 0.55, 0.9];
    let stations: String = at
        .iter()
        .enumerate()
        .map(|(k, s)| format!("[[stations]]\nname = \"s{k}\"\nsegment = \"a\"\nat = {s:e}\n"))
        .collect();
    let f = 1e-5 * 3.0 * ei() / L.powi(2);
    let header = format!("gravity = [0.0, 0.0]\n[tip]\nforce = [0.0, {f:e}]");
    let mut sim = Simulator::<Planar>::new(with_stations(
        &header,
        &[ancf("a", L, &r, 4, "")],
        &stations,
    ))
    .unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    for (k, s) in at.iter().enumerate() {
        let (wf, wm) = cantilever_section(*s, [0.0, f, 0.0], [0.0; 3], 0.0);
        let st = o.stations[k];
        let e = [
            (st.moment[2] - wm[2]).abs() / (f * L),
            (st.force[1] - wf[1]).abs() / f,
        ];
        eprintln!(
            "tip load, s = {s}: M {:.6e} vs {:.6e}, V {:.6e}; errors {:.1e} {:.1e}",
            st.moment[2], wm[2], st.force[1], e[0], e[1]
        );
        assert!(e[0] <= 1e-6 && e[1] <= 1e-6, "s = {s}: {st:?}");
    }
    // the weight, with a point mass on the second element: M(s) = −q(L − s)²/2 − m g (a − s)⁺
    let g = 1e-7 * 8.0 * ei() / (rho_a() * L.powi(4));
    let (q, mass, a) = (rho_a() * g, 0.2 * rho_a() * L, 0.4);
    let masses =
        format!("[[masses]]\nname = \"m\"\nsegment = \"a\"\nat = {a:e}\nmass = {mass:e}\n");
    let s = with_stations(
        &format!("gravity = [0.0, {:e}]", -g),
        &[ancf("a", L, &r, 4, "")],
        &(stations.clone() + &masses),
    );
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    for (k, s) in at.iter().enumerate() {
        let beyond = if *s < a { 1.0 } else { 0.0 };
        let m = -q * (L - s).powi(2) / 2.0 - beyond * mass * g * (a - s);
        let v = -q * (L - s) - beyond * mass * g;
        let st = o.stations[k];
        let (em, ev) = (
            (st.moment[2] / m - 1.0).abs(),
            (st.force[1] / v - 1.0).abs(),
        );
        eprintln!(
            "weight, s = {s}: M {:.6e} vs {m:.6e} ({em:.1e}), V {:.6e} vs {v:.6e} ({ev:.1e})",
            st.moment[2], st.force[1]
        );
        assert!(em <= 1e-9 && ev <= 1e-9, "s = {s}: {st:?}");
    }
    // in motion: a cut just before a node carries what the node carries (the element's part
    // [0, ξ → 1] is the whole element's d'Alembert load, which the node's projection holds)
    let near = "[[stations]]\nname = \"n\"\nsegment = \"a\"\nat = 0.2499999\n[[stations]]\nname = \"k\"\nsegment = \"a\"\nat = 0.25\n";
    let mut sim = AnySimulator::new(with_stations(
        "gravity = [0.0, -9.81]",
        &[ancf("a", L, &r, 4, "")],
        near,
    ))
    .unwrap();
    sim.advance(0.05).unwrap();
    let hybeam::simulator::AnyOutputs::Planar(o) = sim.outputs() else {
        unreachable!()
    };
    let (a, b) = (o.stations[0], o.stations[1]);
    let scale = b.moment[2].abs().max(b.force[1].abs());
    eprintln!("just before the node: {a:?}\nat the node: {b:?}");
    assert!(scale > 1e-3);
    for c in 0..3 {
        assert!(
            (a.force[c] - b.force[c]).abs() <= 1e-4 * scale
                && (a.moment[c] - b.moment[c]).abs() <= 1e-4 * scale
        );
    }
    // beyond the segment: refused naming the field, the value and the fix
    for (header, seg) in [
        ("space = \"spatial\"", ancf("a", L, &r, 4, "")),
        ("", ancf("a", L, &r, 4, "")),
    ] {
        let text = format!("name = \"t\"\n{header}\n[[segments]]\n{seg}\n[[stations]]\nname = \"w\"\nsegment = \"a\"\nat = 1.3\n");
        let err = Scene::from_toml(&text).unwrap_err().0;
        assert!(
            err.contains("stations[0].at = 1.3: not a cut of segment \"a\", which is 1 m long")
                && err.contains("give the arc length from its start, 0 to 1 m"),
            "{err}"
        );
    }
}

/// Stations at `at` on segment "a" (names s0, s1, …).
fn stations_at(at: &[f64]) -> String {
    at.iter()
        .enumerate()
        .map(|(k, s)| format!("[[stations]]\nname = \"s{k}\"\nsegment = \"a\"\nat = {s:e}\n"))
        .collect()
}

/// A `[[masses]]` table on segment "a" at `at` (`extra`: inertia, offset lines).
fn mass_on_a(name: &str, at: f64, mass: f64, extra: &str) -> String {
    format!(
        "[[masses]]\nname = \"{name}\"\nsegment = \"a\"\nat = {at:e}\nmass = {mass:e}\n{extra}\n"
    )
}

/// ∫_s^L ρA(x) (x − s)^k dx, k = 0, 1, of a round section whose diameter runs linearly from d0
/// to d1 (ρA = ρπd²/4): with d(x) = d_s + c u, u = x − s ∈ [0, ℓ], ℓ = L − s, the polynomials
/// ∫(d_s + cu)² du = d_s²ℓ + d_s c ℓ² + c²ℓ³/3 and ∫(d_s + cu)² u du = d_s²ℓ²/2 + 2d_s c ℓ³/3 +
/// c²ℓ⁴/4, times ρπ/4.
fn tapered_beyond(s: f64, d0: f64, d1: f64) -> (f64, f64) {
    let c = (d1 - d0) / L;
    let ds = d0 + c * s;
    let l = L - s;
    let k = RHO_STEEL * std::f64::consts::PI / 4.0;
    (
        k * (ds * ds * l + ds * c * l * l + c * c * l.powi(3) / 3.0),
        k * (ds * ds * l * l / 2.0 + 2.0 * ds * c * l.powi(3) / 3.0 + c * c * l.powi(4) / 4.0),
    )
}

#[test]
fn stations_inside_tapered_ancf_elements_and_section_bodies() {
    // a linear taper of the diameter, 12 mm to 8 mm, 4 elements of 0.25 m; cuts inside them
    let (d0, d1) = (0.012, 0.008);
    let taper = format!("section = \"round\"\ndiameter = [{d0:e}, {d1:e}]");
    let at = [0.1, 0.3, 0.45, 0.55, 0.9];
    let ei_at = |x: f64| {
        let d = d0 + (d1 - d0) * x / L;
        E_STEEL * std::f64::consts::PI * d.powi(4) / 64.0
    };
    // tip force: M(s) = F(L − s), V = F cos θ, N = F sin θ with θ(s) = ∫₀ˢ F(L − x)/EI(x) dx
    // (Simpson, 2000 intervals)
    let f = 1e-5 * 3.0 * ei_at(L) / L.powi(2);
    let theta = |s: f64| {
        let n = 2000;
        let h = s / n as f64;
        (0..=n)
            .map(|i| {
                let x = i as f64 * h;
                let w = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * f * (L - x) / ei_at(x)
            })
            .sum::<f64>()
            * h
            / 3.0
    };
    let mut worst = 0.0f64;
    let header = format!("gravity = [0.0, 0.0]\n[tip]\nforce = [0.0, {f:e}]");
    let mut sim = Simulator::<Planar>::new(with_stations(
        &header,
        &[ancf("a", L, &taper, 4, "")],
        &stations_at(&at),
    ))
    .unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    for (k, s) in at.iter().enumerate() {
        let st = o.stations[k];
        let th = theta(*s);
        let e = [
            (st.moment[2] - f * (L - s)).abs() / (f * L),
            (st.force[1] - f * th.cos()).abs() / f,
            (st.force[0] - f * th.sin()).abs() / f,
        ];
        eprintln!(
            "planar tapered, tip force, s = {s}: M {:.6e} V {:.6e} N {:.3e} (θ {th:.3e}); errors {:.1e} {:.1e} {:.1e}",
            st.moment[2], st.force[1], st.force[0], e[0], e[1], e[2]
        );
        for x in e {
            worst = worst.max(x);
            assert!(x <= 1e-6, "s = {s}: {st:?}");
        }
    }
    // under gravity −y, with a section body (mass m_b, rotary inertia, offset (o_t, o_n)) at
    // a_b and a point mass m_p at a_p: M(s) = −g[∫_s^L ρA(x)(x − s)dx + m_b(a_b + o_t − s)⁺ +
    // m_p(a_p − s)⁺], V = −g[∫_s^L ρA dx + m_b[s < a_b] + m_p[s < a_p]]
    let g = 1e-7 * 8.0 * ei() / (rho_a() * L.powi(4));
    let (mb, ab, ot, on) = (0.2 * rho_a() * L, 0.4, 0.05, 0.03);
    let (mp, ap) = (0.1 * rho_a() * L, 0.7);
    for (label, section, tapered) in [
        ("uniform", round(D), false),
        ("tapered", taper.clone(), true),
    ] {
        let masses = mass_on_a(
            "b",
            ab,
            mb,
            &format!("inertia = [1e-3]\noffset = [{ot:e}, {on:e}]"),
        ) + &mass_on_a("p", ap, mp, "");
        let s = with_stations(
            &format!("gravity = [0.0, {:e}]", -g),
            &[ancf("a", L, &section, 4, "")],
            &(stations_at(&at) + &masses),
        );
        let mut sim = Simulator::<Planar>::new(s).unwrap();
        sim.solve_static().unwrap();
        let o = sim.outputs();
        for (k, s) in at.iter().enumerate() {
            let (w0, w1) = if tapered {
                tapered_beyond(*s, d0, d1)
            } else {
                (rho_a() * (L - s), rho_a() * (L - s).powi(2) / 2.0)
            };
            let (bb, pb) = ((*s < ab) as u8 as f64, (*s < ap) as u8 as f64);
            let m = -g * (w1 + bb * mb * (ab + ot - s) + pb * mp * (ap - s));
            let v = -g * (w0 + bb * mb + pb * mp);
            let st = o.stations[k];
            let (em, ev) = (
                (st.moment[2] / m - 1.0).abs(),
                (st.force[1] / v - 1.0).abs(),
            );
            eprintln!(
                "planar {label} with a section body, weight, s = {s}: M {:.6e} vs {m:.6e} ({em:.1e}), V {:.6e} vs {v:.6e} ({ev:.1e})",
                st.moment[2], st.force[1]
            );
            worst = worst.max(em).max(ev);
            assert!(em <= 1e-5 && ev <= 1e-5, "{label} s = {s}: {st:?}");
        }
    }
    // spatial, gravity −y: the director element, tapered, a section body with an offset
    // (o_x, o_y, o_z) and a point mass; the 3D cable, tapered, the point mass. Beside M_z and
    // V_y as above, the body's weight on its offset o_z twists: T(s) = m_b g o_z for s < a_b
    let (ox, oy, oz) = (0.05, 0.02, 0.03);
    for torsion in [true, false] {
        let body = if torsion {
            mass_on_a(
                "b",
                ab,
                mb,
                &format!("inertia = [1e-3, 2e-3, 3e-3]\noffset = [{ox:e}, {oy:e}, {oz:e}]"),
            )
        } else {
            String::new()
        };
        let masses = body + &mass_on_a("p", ap, mp, "");
        let s = with_stations(
            &format!(
                "space = \"spatial\"\ntorsion = {torsion}\ngravity = [0.0, {:e}, 0.0]",
                -g
            ),
            &[ancf("a", L, &taper, 4, "")],
            &(stations_at(&at) + &masses),
        );
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        sim.solve_static().unwrap();
        let o = sim.outputs();
        for (k, s) in at.iter().enumerate() {
            let (w0, w1) = tapered_beyond(*s, d0, d1);
            let bb = if torsion && *s < ab { 1.0 } else { 0.0 };
            let pb = (*s < ap) as u8 as f64;
            let m = -g * (w1 + bb * mb * (ab + ox - s) + pb * mp * (ap - s));
            let v = -g * (w0 + bb * mb + pb * mp);
            let t = bb * mb * g * oz;
            let st = o.stations[k];
            let (em, ev, et) = (
                (st.moment[2] / m - 1.0).abs(),
                (st.force[1] / v - 1.0).abs(),
                (st.moment[0] - t).abs() / m.abs(),
            );
            eprintln!(
                "spatial tapered (torsion = {torsion}), weight, s = {s}: M_z {:.6e} vs {m:.6e} ({em:.1e}), V_y {:.6e} vs {v:.6e} ({ev:.1e}), T {:.6e} vs {t:.6e} ({et:.1e})",
                st.moment[2], st.force[1], st.moment[0]
            );
            worst = worst.max(em).max(ev).max(et);
            assert!(em <= 1e-5 && ev <= 1e-5 && et <= 1e-5, "s = {s}: {st:?}");
        }
    }
    eprintln!("worst relative error {worst:.2e}");
}

/// The stations of `scene` (planar or spatial) in static equilibrium.
fn static_stations(scene: Scene) -> Vec<hybeam::model::StationLoads> {
    if scene.space == hybeam::scene::SpaceKind::Spatial {
        let mut sim = Simulator::<Spatial>::new(scene).unwrap();
        sim.solve_static().unwrap();
        sim.outputs().stations.to_vec()
    } else {
        let mut sim = Simulator::<Planar>::new(scene).unwrap();
        sim.solve_static().unwrap();
        sim.outputs().stations.to_vec()
    }
}

/// Largest difference of stations (0, 1) and (2, 3) at t = 0.05 s of a run of `scene` released
/// straight, relative to the largest load of the four.
fn pairs_after_release(scene: Scene) -> (f64, f64) {
    let mut sim = AnySimulator::new(scene).unwrap();
    sim.advance(0.05).unwrap();
    let st = match sim.outputs() {
        hybeam::simulator::AnyOutputs::Planar(p) => p.stations,
        hybeam::simulator::AnyOutputs::Spatial(p) => p.stations,
    };
    let scale = st[..4]
        .iter()
        .flat_map(|s| s.force.iter().chain(&s.moment))
        .fold(0.0f64, |a, b| a.max(b.abs()));
    let mut worst = 0.0f64;
    for (a, b) in [(st[0], st[1]), (st[2], st[3])] {
        for c in 0..3 {
            worst = worst
                .max((a.force[c] - b.force[c]).abs())
                .max((a.moment[c] - b.moment[c]).abs());
        }
    }
    (worst / scale, scale)
}

#[test]
fn a_cut_just_before_a_node_carries_what_the_node_carries_in_motion() {
    // released straight under gravity: a cut 1e-7 m before a node against the cut at the node,
    // and 1e-7 m before the free end against the end (the element's part [0, ξ → 1] is the
    // whole element's d'Alembert load, which the node's projection holds)
    let taper = "section = \"round\"\ndiameter = [0.012, 0.008]";
    let near = stations_at(&[0.25 - 1e-7, 0.25, L - 1e-7, L]);
    let masses = |spatial: bool| {
        let (inertia, offset) = if spatial {
            ("[1e-3, 2e-3, 3e-3]", "[0.05, 0.02, 0.03]")
        } else {
            ("[1e-3]", "[0.05, 0.03]")
        };
        mass_on_a(
            "b",
            0.1,
            0.1,
            &format!("inertia = {inertia}\noffset = {offset}"),
        ) + &mass_on_a("p", 0.2, 0.05, "")
            + &mass_on_a("q", 0.8, 0.05, "")
    };
    for (label, header, masses) in [
        (
            "planar, tapered, section body",
            "gravity = [0.0, -9.81]",
            masses(false),
        ),
        (
            "spatial director, tapered, section body",
            "space = \"spatial\"\ngravity = [0.0, -9.81, -3.0]",
            masses(true),
        ),
        (
            "spatial 3D cable, tapered",
            "space = \"spatial\"\ntorsion = false\ngravity = [0.0, -9.81, -3.0]",
            mass_on_a("p", 0.2, 0.05, "") + &mass_on_a("q", 0.8, 0.05, ""),
        ),
    ] {
        let s = with_stations(
            header,
            &[ancf("a", L, taper, 4, "")],
            &(near.clone() + &masses),
        );
        let (err, scale) = pairs_after_release(s);
        eprintln!(
            "{label}: cut 1e-7 m before the node and the end: {err:.2e} of the loads ({scale:.3e})"
        );
        assert!(scale > 1e-3 && err <= 1e-5, "{label}: {err:e}");
    }
}

#[test]
fn stations_inside_modal_bodies_under_their_weight() {
    // a modal segment "a" (8 modes and the interface shapes), uniform and tapered (diameter 12 mm
    // to 8 mm), with a section body (offset, rotary inertia) at a_b and a point mass at a_p,
    // under gravity −y, planar and spatial: the closed forms of the ANCF test above
    let (d0, d1) = (0.012, 0.008);
    let taper = format!("section = \"round\"\ndiameter = [{d0:e}, {d1:e}]");
    let at = [0.1, 0.3, 0.45, 0.55, 0.9];
    let g = 1e-7 * 8.0 * ei() / (rho_a() * L.powi(4));
    let (mb, ab) = (0.2 * rho_a() * L, 0.4);
    let (mp, ap) = (0.1 * rho_a() * L, 0.7);
    let (ot, on) = (0.05, 0.03);
    let (ox, oy, oz) = (0.05, 0.02, 0.03);
    let mut worst = 0.0f64;
    for (label, section, tapered) in [("uniform", round(D), false), ("tapered", taper, true)] {
        let beyond = |s: f64| {
            if tapered {
                tapered_beyond(s, d0, d1)
            } else {
                (rho_a() * (L - s), rho_a() * (L - s).powi(2) / 2.0)
            }
        };
        let seg = [modal("a", L, &section, 8, true, "")];
        for spatial in [false, true] {
            let (header, body) = if spatial {
                (
                    format!("space = \"spatial\"\ngravity = [0.0, {:e}, 0.0]", -g),
                    format!("inertia = [1e-3, 2e-3, 3e-3]\noffset = [{ox:e}, {oy:e}, {oz:e}]"),
                )
            } else {
                (
                    format!("gravity = [0.0, {:e}]", -g),
                    format!("inertia = [1e-3]\noffset = [{ot:e}, {on:e}]"),
                )
            };
            let masses = mass_on_a("b", ab, mb, &body) + &mass_on_a("p", ap, mp, "");
            let scene = with_stations(&header, &seg, &(stations_at(&at) + &masses));
            let st = static_stations(scene);
            let along = if spatial { ox } else { ot };
            for (k, s) in at.iter().enumerate() {
                let (w0, w1) = beyond(*s);
                let (bb, pb) = ((*s < ab) as u8 as f64, (*s < ap) as u8 as f64);
                let m = -g * (w1 + bb * mb * (ab + along - s) + pb * mp * (ap - s));
                let v = -g * (w0 + bb * mb + pb * mp);
                let t = if spatial { bb * mb * g * oz } else { 0.0 };
                let (em, ev, et) = (
                    (st[k].moment[2] / m - 1.0).abs(),
                    (st[k].force[1] / v - 1.0).abs(),
                    (st[k].moment[0] - t).abs() / m.abs(),
                );
                eprintln!(
                    "modal {label} (spatial {spatial}), weight, s = {s}: M_z {:.6e} vs {m:.6e} ({em:.1e}), V_y {:.6e} vs {v:.6e} ({ev:.1e}), T {:.3e} vs {t:.3e} ({et:.1e})",
                    st[k].moment[2], st[k].force[1], st[k].moment[0]
                );
                worst = worst.max(em).max(ev).max(et);
                assert!(
                    em <= 1e-5 && ev <= 1e-5 && et <= 1e-5,
                    "{label} s = {s}: {:?}",
                    st[k]
                );
            }
        }
    }
    eprintln!("worst relative error {worst:.2e}");
}

#[test]
fn a_cut_just_inside_a_modal_body_carries_what_its_end_carries_in_motion() {
    // released straight under gravity with masses on the modal segment: a cut 1e-7 m before
    // its end against its end, and 1e-7 m after its start against its start — the joint of a
    // hybrid (modal then ANCF) and the root of an all-modal rod; uniform and tapered, planar and
    // spatial
    let taper = "section = \"round\"\ndiameter = [0.012, 0.008]";
    let r = round(D);
    for (label, section) in [("uniform", r.as_str()), ("tapered", taper)] {
        for spatial in [false, true] {
            let (header, body) = if spatial {
                (
                    "space = \"spatial\"\ngravity = [0.0, -9.81, -3.0]",
                    "inertia = [1e-3, 2e-3, 3e-3]\noffset = [0.05, 0.02, 0.03]",
                )
            } else {
                (
                    "gravity = [0.0, -9.81]",
                    "inertia = [1e-3]\noffset = [0.05, 0.03]",
                )
            };
            let masses = |seg: &str| {
                format!("[[masses]]\nname = \"b\"\nsegment = \"{seg}\"\nat = 0.1\nmass = 0.1\n{body}\n[[masses]]\nname = \"p\"\nsegment = \"{seg}\"\nat = 0.3\nmass = 0.05\n")
            };
            let st = |seg: &str, at: f64, name: &str| {
                format!("[[stations]]\nname = \"{name}\"\nsegment = \"{seg}\"\nat = {at:e}\n")
            };
            for (rod, segs, stations) in [
                (
                    "all-modal",
                    vec![modal("m", L, section, 8, true, "")],
                    st("m", L - 1e-7, "a")
                        + &st("m", L, "b")
                        + &st("m", 1e-7, "c")
                        + &st("m", 0.0, "d"),
                ),
                (
                    "hybrid modal+ANCF",
                    vec![
                        modal("m", 0.5 * L, section, 6, true, ""),
                        ancf("x", 0.5 * L, section, 4, ""),
                    ],
                    st("m", 0.5 * L - 1e-7, "a")
                        + &st("m", 0.5 * L, "b")
                        + &st("x", 1e-7, "c")
                        + &st("x", 0.0, "d"),
                ),
            ] {
                let s = with_stations(header, &segs, &(stations + &masses("m")));
                let (err, scale) = pairs_after_release(s);
                eprintln!("{rod} {label} (spatial {spatial}): cuts 1e-7 m inside against the ends: {err:.2e} of the loads ({scale:.3e})");
                assert!(
                    scale > 1e-3 && err <= 1e-5,
                    "{rod} {label} {spatial}: {err:e}"
                );
            }
        }
    }
}

#[test]
fn the_modal_cut_rule_integrates_the_floating_frame_to_1e_10() {
    // a planar modal body (8 modes and the interface shapes) at an arbitrary moving state: its
    // partial load on [0, ξ] against an independent evaluation of ∫ρA(g − r̈) and
    // ∫(r − p) × ρA(g − r̈) with r̈ = R̈ + Äū + 2Ȧu̇̄ + Aǖ, ū = (x − ½∫₀ˣw′², w), on 100 panels
    // of 5-point Gauss (the foreshortening and its rates by a nested 60-panel rule on [0, x])
    use hybeam::model::modal::{BodyGravity, ModalBasis, ModalBody};
    let n = 8;
    let basis = ModalBasis::new(n, true);
    let nb = basis.len();
    let body = ModalBody::new(basis.clone(), L, rho_a(), ei(), 0.0, 0.0);
    let q: Vec<f64> = [0.1, -0.2, 0.3]
        .into_iter()
        .chain((0..nb).map(|k| 0.02 / (k + 1) as f64))
        .collect();
    let v: Vec<f64> = [0.5, 0.7, 2.0]
        .into_iter()
        .chain((0..nb).map(|k| 0.3 * (-1f64).powi(k as i32) / (k + 1) as f64))
        .collect();
    let a: Vec<f64> = [3.0, -2.0, 5.0]
        .into_iter()
        .chain((0..nb).map(|k| 50.0 / (k + 1) as f64))
        .collect();
    let g = [0.0, -9.81];
    let about = [0.4, 0.1, 0.0];
    let gauss = |a0: f64, a1: f64, panels: usize| -> Vec<(f64, f64)> {
        const G: [(f64, f64); 5] = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let h = (a1 - a0) / panels as f64;
        (0..panels)
            .flat_map(|p| G.map(|(x, w)| (a0 + h * (p as f64 + 0.5 * (x + 1.0)), 0.5 * h * w)))
            .collect()
    };
    let mut phi = Vec::new();
    // (w, ẇ, ẅ, w′, ẇ′, ẅ′) at ξ (ξ-derivatives)
    let mut fields = |x: f64| -> [f64; 6] {
        basis.eval_all(x, &mut phi);
        let mut f = [0.0; 6];
        for (k, p) in phi.iter().enumerate() {
            let (qa, va, aa) = (q[3 + k], v[3 + k], a[3 + k]);
            f[0] += p[0] * qa;
            f[1] += p[0] * va;
            f[2] += p[0] * aa;
            f[3] += p[1] * qa;
            f[4] += p[1] * va;
            f[5] += p[1] * aa;
        }
        f
    };
    let (th, thd, thdd) = (q[2], v[2], a[2]);
    let (s, c) = (th.sin(), th.cos());
    let rot = |m: [[f64; 2]; 2], u: [f64; 2]| {
        [
            m[0][0] * u[0] + m[0][1] * u[1],
            m[1][0] * u[0] + m[1][1] * u[1],
        ]
    };
    let am = [[c, -s], [s, c]];
    let ad = [[-s * thd, -c * thd], [c * thd, -s * thd]];
    let add = [
        [-s * thdd - c * thd * thd, -c * thdd + s * thd * thd],
        [c * thdd - s * thd * thd, -s * thdd - c * thd * thd],
    ];
    let mut errs = Vec::new();
    for xi in [0.13, 0.5, 0.77, 0.9, 0.95, 0.99, 1.0 - 1e-9] {
        let (mut f, mut m) = ([0.0; 2], 0.0);
        for (x, w) in gauss(0.0, xi, 100) {
            let fx = fields(x);
            // c(x) = −½/L ∫₀^ξ w′², ċ = −1/L ∫w′ẇ′, c̈ = −1/L ∫(ẇ′² + w′ẅ′)
            let mut cf = [0.0; 3];
            for (y, wy) in gauss(0.0, x, 60) {
                let fy = fields(y);
                cf[0] += wy * fy[3] * fy[3];
                cf[1] += wy * fy[3] * fy[4];
                cf[2] += wy * (fy[4] * fy[4] + fy[3] * fy[5]);
            }
            let u = [x * L - 0.5 * cf[0] / L, fx[0]];
            let ud = [-cf[1] / L, fx[1]];
            let ua = [-cf[2] / L, fx[2]];
            let (t1, t2, t3) = (rot(add, u), rot(ad, ud), rot(am, ua));
            let r = rot(am, u);
            let rdd: [f64; 2] = std::array::from_fn(|i| a[i] + t1[i] + 2.0 * t2[i] + t3[i]);
            let load = [
                w * L * rho_a() * (g[0] - rdd[0]),
                w * L * rho_a() * (g[1] - rdd[1]),
            ];
            f[0] += load[0];
            f[1] += load[1];
            let arm = [q[0] + r[0] - about[0], q[1] + r[1] - about[1]];
            m += arm[0] * load[1] - arm[1] * load[0];
        }
        let (pf, pm) = body
            .partial_load((&q, &v, &a), BodyGravity::from(g), xi, about)
            .unwrap();
        let scale = f[0].hypot(f[1]);
        let ef = (pf[0] - f[0]).hypot(pf[1] - f[1]) / scale;
        let em = (pm[2] - m).abs() / m.abs();
        eprintln!(
            "ξ = {xi}: F ({:.12e}, {:.12e}) vs ({:.12e}, {:.12e}), {ef:.1e}; M {:.12e} vs {m:.12e}, {em:.1e}",
            pf[0], pf[1], f[0], f[1], pm[2]
        );
        errs.push(ef.max(em));
    }
    let worst = errs.iter().fold(0.0f64, |a, b| a.max(*b));
    eprintln!("worst relative difference {worst:.1e}");
    assert!(worst <= 2e-9, "{errs:?}");
}

#[test]
fn stations_inside_elements_under_a_line_load() {
    // a segment line load q (−y) and no gravity, on tapered ANCF (4 elements) and modal (8 +
    // interface) segments, uniform and tapered, planar and spatial: the load beyond the cut,
    // M_z(s) = −q(L − s)²/2, V_y = −q(L − s) (a load per unit length whatever the section)
    let q = 1e-7 * 8.0 * ei() / L.powi(4);
    let at = [0.1, 0.3, 0.45, 0.9];
    let taper = "section = \"round\"\ndiameter = [0.012, 0.008]".to_string();
    let mut worst = 0.0f64;
    for spatial in [false, true] {
        let (header, load) = if spatial {
            (
                "space = \"spatial\"\ngravity = [0.0, 0.0, 0.0]",
                format!("line_load = [0.0, {:e}, 0.0]", -q),
            )
        } else {
            (
                "gravity = [0.0, 0.0]",
                format!("line_load = [0.0, {:e}]", -q),
            )
        };
        for (label, seg) in [
            ("ANCF uniform", ancf("a", L, &round(D), 4, &load)),
            ("ANCF tapered", ancf("a", L, &taper, 4, &load)),
            ("modal uniform", modal("a", L, &round(D), 8, true, &load)),
            ("modal tapered", modal("a", L, &taper, 8, true, &load)),
        ] {
            let scene = with_stations(header, &[seg], &stations_at(&at));
            let st = static_stations(scene);
            for (k, s) in at.iter().enumerate() {
                let (m, v) = (-q * (L - s).powi(2) / 2.0, -q * (L - s));
                let (em, ev) = (
                    (st[k].moment[2] / m - 1.0).abs(),
                    (st[k].force[1] / v - 1.0).abs(),
                );
                eprintln!(
                    "line load, {label} (spatial {spatial}), s = {s}: M_z {:.6e} vs {m:.6e} ({em:.1e}), V_y {:.6e} vs {v:.6e} ({ev:.1e})",
                    st[k].moment[2], st[k].force[1]
                );
                worst = worst.max(em).max(ev);
                assert!(
                    em <= 1e-5 && ev <= 1e-5,
                    "{label} {spatial} s = {s}: {:?}",
                    st[k]
                );
            }
        }
    }
    eprintln!("worst relative error {worst:.2e}");
}

#[test]
fn the_twist_inertia_is_carried_across_a_cut() {
    // a step tip torque T = 1 N m from rest, no gravity, spatial: the torsional waves make the
    // twist inertia a leading part of the loads; a cut 1e-7 m before the free end (and before a
    // node, and after the root) against the end (the node, the root): the modal body's spinning
    // sections −∫ρI_p(ω̄̇_x + θ̈)dx and the director element's lumped twist inertia across the
    // part [0, ξ]
    let r = round(D);
    let header = "space = \"spatial\"\ngravity = [0.0, 0.0, 0.0]\n[tip]\nforce = [0.0, 0.0, 0.0]\nmoment = [1.0, 0.0, 0.0]";
    for (label, seg, near) in [
        (
            "modal",
            modal("a", L, &r, 8, true, ""),
            stations_at(&[L - 1e-7, L, 1e-7, 0.0]),
        ),
        (
            "director",
            ancf("a", L, &r, 4, ""),
            stations_at(&[0.25 - 1e-7, 0.25, L - 1e-7, L]),
        ),
    ] {
        let (err, scale) = pairs_after_release(with_stations(header, &[seg], &near));
        eprintln!("{label}, step tip torque: cuts 1e-7 m from the node/end: {err:.2e} of the loads ({scale:.3e})");
        assert!(scale > 0.5 && err <= 1e-5, "{label}: {err:e}");
    }
}
