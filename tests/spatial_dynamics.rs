//! Spatial dynamics against independent references:
//! * an undamped flexible pendulum on a ball root (all-ANCF cable, then a hybrid with a free
//!   modal frame), swung out of plane by a short sideways tip-force pulse: total energy (from
//!   the outputs) and the vertical angular momentum about the pivot (∫ρA r × ṙ dx by Gauss
//!   quadrature over the Hermite interpolation of the state, written here) stay constant once
//!   the pulse is over, and their drift shrinks with the step;
//! * the shipped 3D Cases 1–3: hybrid vs all-ANCF vs all-modal, and each 3D case's vertical
//!   (z) tip history against the planar case's y history;
//! * bad spatial input through [`Simulator`] and [`AnySimulator`]: refused with the field or the
//!   reason named, and a failed step keeps the last good state.

mod common;
use common::*;
use hybeam::error::{Refusal, SimError, SnapshotError};
use hybeam::model::{Outputs, Planar, Spatial};
use hybeam::scene::{Scene, SpaceKind};
use hybeam::simulator::{AnySimulator, InputId, InputKind, Simulator};
use nalgebra::Vector3;

/// Gauss–Legendre points and weights on [0, 1] (4 points: exact to degree 7; ρA r × ṙ of cubic
/// Hermite r is of degree 6).
fn gauss4() -> [(f64, f64); 4] {
    let (a, b) = (
        (3.0 / 7.0 - 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt(),
        (3.0 / 7.0 + 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt(),
    );
    let (wa, wb) = (
        (18.0 + 30.0f64.sqrt()) / 36.0,
        (18.0 - 30.0f64.sqrt()) / 36.0,
    );
    [(-b, wb), (-a, wa), (a, wa), (b, wb)].map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w))
}

/// Cubic Hermite shape functions at ξ ∈ [0, 1] of an element of length `l`: weights of r0,
/// r0_x, r1, r1_x.
fn hermite(xi: f64, l: f64) -> [f64; 4] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    [
        1.0 - 3.0 * x2 + 2.0 * x3,
        l * (xi - 2.0 * x2 + x3),
        3.0 * x2 - 2.0 * x3,
        l * (x3 - x2),
    ]
}

/// Angular momentum ∫ρA r × ṙ dx about the origin [N m s] of a chain of cable nodes
/// `[(r, r_x)]` with rates `[(ṙ, ṙ_x)]`, elements of length `l` (no rotary inertia: exact for
/// the 3D cable).
fn cable_angular_momentum(
    nodes: &[[Vector3<f64>; 2]],
    rates: &[[Vector3<f64>; 2]],
    rho_a: f64,
    l: f64,
) -> Vector3<f64> {
    let mut h = Vector3::zeros();
    for e in 0..nodes.len() - 1 {
        let c = [nodes[e][0], nodes[e][1], nodes[e + 1][0], nodes[e + 1][1]];
        let cd = [rates[e][0], rates[e][1], rates[e + 1][0], rates[e + 1][1]];
        for (xi, w) in gauss4() {
            let s = hermite(xi, l);
            let r: Vector3<f64> = (0..4).map(|k| c[k] * s[k]).sum();
            let rd: Vector3<f64> = (0..4).map(|k| cd[k] * s[k]).sum();
            h += w * l * rho_a * r.cross(&rd);
        }
    }
    h
}

/// Nodes `[(r, r_x)]` of an all-ANCF cable chain on a ball root at the origin from a vector of
/// free coordinates (the root's r is held at 0): `[r0_x, r1, r1_x, r2, r2_x, …]`.
fn cable_nodes(q: &[f64], root: Vector3<f64>) -> Vec<[Vector3<f64>; 2]> {
    let v = |i: usize| Vector3::new(q[i], q[i + 1], q[i + 2]);
    let mut out = vec![[root, v(0)]];
    let mut i = 3;
    while i < q.len() {
        out.push([v(i), v(i + 3)]);
        i += 6;
    }
    out
}

const D: f64 = 0.002;
const L: f64 = 0.4;
const G: f64 = 9.81;

/// Total energy [J] of outputs (kinetic + strain + gravity).
fn energy<S: hybeam::model::Space>(o: &Outputs<S>) -> f64 {
    o.kinetic + o.strain + o.potential
}

/// The undamped pendulum: the Case 1 rod on a ball root at the origin, horizontal along x,
/// gravity along −z, at the step `h` and ρ∞ = `rho_inf`.
fn pendulum(segments: &[String], torsion: bool, h: f64, rho_inf: f64) -> Scene {
    scene(
        &format!(
            "space = \"spatial\"\ntorsion = {torsion}\nroot = \"ball\"\ngravity = [0.0, 0.0, {}]\n\
             [solver]\nrho_inf = {rho_inf}\nmax_step = {h:e}\ntolerance = 1e-11\nmax_iterations = 20\n",
            -G
        ),
        segments,
    )
}

struct Swing {
    /// Largest |E − E(pulse end)| over the energy scale m g L/2.
    energy_drift: f64,
    /// Largest |H_z − H_z(pulse end)| over max |H_z| (None: not measured).
    momentum_drift: Option<f64>,
    /// H_z at the end of the pulse [N m s].
    h_z: f64,
    /// Largest |tip y| [m]: how far it swung out of the x–z plane.
    out_of_plane: f64,
    /// Lowest tip z [m].
    lowest: f64,
}

/// Runs the pendulum: sideways tip force (0, F, 0) for `pulse` seconds, then free for `t_free`;
/// samples every `dt`.
fn swing(scene: Scene, cable: Option<(f64, f64)>, t_free: f64) -> Swing {
    let (pulse, force, dt): (f64, f64, f64) = (0.02, 0.02, 1e-3);
    let mut sim = Simulator::<Spatial>::start_at(scene, 0.0).expect("builds");
    sim.set_tip_force([0.0, force, 0.0]);
    let n_pulse = (pulse / dt).round() as usize;
    for k in 1..=n_pulse {
        sim.advance(k as f64 * dt).expect("pulse step");
    }
    sim.set_tip_force([0.0; 3]);
    let momentum = |sim: &Simulator<Spatial>| {
        cable.map(|(rho_a, le)| {
            let s = sim.state();
            let nodes = cable_nodes(&s.q, Vector3::zeros());
            let rates = cable_nodes(&s.v, Vector3::zeros());
            cable_angular_momentum(&nodes, &rates, rho_a, le)[2]
        })
    };
    let e0 = energy(&sim.outputs());
    let h0 = momentum(&sim);
    let mass = RHO_STEEL * std::f64::consts::PI * D * D / 4.0 * L;
    let scale = mass * G * L / 2.0;
    let (mut de, mut dh, mut hmax, mut side, mut lowest) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let n = (t_free / dt).round() as usize;
    for k in 1..=n {
        sim.advance(pulse + k as f64 * dt).expect("free step");
        let o = sim.outputs();
        de = de.max((energy(&o) - e0).abs());
        if let (Some(h), Some(h0)) = (momentum(&sim), h0) {
            dh = dh.max((h - h0).abs());
            hmax = hmax.max(h.abs());
        }
        side = side.max(o.tip_position[1].abs());
        lowest = lowest.min(o.tip_position[2]);
    }
    Swing {
        energy_drift: de / scale,
        momentum_drift: h0.map(|h0| dh / hmax.max(h0.abs())),
        h_z: h0.unwrap_or(f64::NAN),
        out_of_plane: side,
        lowest,
    }
}

#[test]
fn undamped_cable_pendulum_keeps_energy_and_vertical_angular_momentum() {
    let elements = 8;
    let segs = [ancf("a", L, &round(D), elements, "")];
    let rho_a = RHO_STEEL * std::f64::consts::PI * D * D / 4.0;
    let le = L / elements as f64;
    // the layout cable_nodes reads: the straight initial state, r0 held at the origin
    let s0 = pendulum(&segs, false, 1e-3, 0.99);
    let sim = Simulator::<Spatial>::start_at(s0, 0.0).unwrap();
    let q0 = cable_nodes(&sim.state().q, Vector3::zeros());
    assert_eq!(q0.len(), elements + 1);
    for (k, [r, rx]) in q0.iter().enumerate() {
        assert!((r - Vector3::new(k as f64 * le, 0.0, 0.0)).norm() < 1e-15);
        assert!((rx - Vector3::x()).norm() < 1e-15);
    }
    let mut rows = Vec::new();
    for h in [1e-3, 5e-4] {
        let r = swing(pendulum(&segs, false, h, 0.99), Some((rho_a, le)), 2.0);
        eprintln!(
            "cable pendulum h = {h:e}: energy drift {:.2e} of m g L/2, H_z drift {:.2e} (H_z = {:.3e} N m s), out of plane {:.3} m, lowest tip z {:.3} m",
            r.energy_drift,
            r.momentum_drift.unwrap(),
            r.h_z,
            r.out_of_plane,
            r.lowest
        );
        rows.push(r);
    }
    for r in &rows {
        // it swings down and out of the x–z plane
        assert!(
            r.lowest < -0.3 && r.out_of_plane > 0.05,
            "{}",
            r.out_of_plane
        );
        assert!(r.energy_drift < 1e-3 && r.momentum_drift.unwrap() < 1e-3);
    }
    assert!(rows[1].energy_drift < 0.5 * rows[0].energy_drift);
    assert!(rows[1].momentum_drift.unwrap() < 0.5 * rows[0].momentum_drift.unwrap());
}

/// The hybrid: a modal first segment on the ball root (R held, Euler parameters free with
/// their normalization row) joined to an ANCF segment. The cable variant's drift shrinks with
/// h at about second order; with torsion the 2 kHz twist modes are far beyond the step (ωh ≈ 6
/// at h = 0.5 ms) and, nearly undamped at ρ∞ = 0.99, exchange energy with the swing: bounded,
/// not monotone in h (printed, checked against the bound only).
#[test]
fn undamped_hybrid_pendulum_keeps_energy() {
    let segs = [
        modal("m", 0.5 * L, &round(D), 4, true, ""),
        ancf("a", 0.5 * L, &round(D), 4, ""),
    ];
    for torsion in [false, true] {
        let mut rows = Vec::new();
        for h in [1e-3, 5e-4] {
            let r = swing(pendulum(&segs, torsion, h, 0.99), None, 2.0);
            eprintln!(
                "hybrid pendulum, torsion = {torsion}, h = {h:e}: energy drift {:.2e} of m g L/2, out of plane {:.3} m, lowest tip z {:.3} m",
                r.energy_drift, r.out_of_plane, r.lowest
            );
            rows.push(r);
        }
        for r in &rows {
            assert!(r.lowest < -0.3 && r.out_of_plane > 0.05);
            assert!(r.energy_drift < 1e-3);
        }
        if !torsion {
            assert!(rows[1].energy_drift < 0.5 * rows[0].energy_drift);
        }
    }
}

fn shipped(name: &str) -> Scene {
    let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::from_toml(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

/// Tip positions of a scene's run to `t_end`, every `dt`.
fn history<S: hybeam::model::Space>(scene: Scene, t_end: f64, dt: f64) -> Vec<S::Vec> {
    let mut sim = Simulator::<S>::start_at(scene, 0.0).expect("builds");
    let mut out = vec![sim.outputs().tip_position];
    for k in 1..=(t_end / dt).round() as usize {
        sim.advance(k as f64 * dt).expect("steps");
        out.push(sim.outputs().tip_position);
    }
    out
}

#[test]
fn case_3d_formulations_agree_and_match_the_planar_cases() {
    let (t_end, dt) = (0.3, 1e-3);
    // bounds: with linear modal frames the planar report's 2 s figures were 0.40 %, 0.06 %,
    // 0.01 % (hybrid) and 0.48 %, 0.09 %, 2.93 % (all-modal) of the peak; the nonlinear planar
    // body is now within 0.01 %, 0.00 %, 0.00 % and 0.02 %, 0.00 %, 0.05 %
    // (docs/paper-figures.md), and so is the nonlinear spatial body here (0.3 s)
    for (case, hybrid_bound, modal_bound) in [
        ("case1", 0.01, 0.01),
        ("case2", 0.01, 0.01),
        ("case3", 0.01, 0.05),
    ] {
        let runs: Vec<Vec<[f64; 3]>> = ["_3d", "_3d_ancf", "_3d_modal"]
            .iter()
            .map(|s| history::<Spatial>(shipped(&format!("{case}{s}")), t_end, dt))
            .collect();
        // the planar twin, both modal bodies geometrically nonlinear
        let planar = history::<Planar>(shipped(case), t_end, dt);
        let peak = runs[1].iter().fold(0.0f64, |a, p| a.max(p[2].abs()));
        let diff = |a: &[[f64; 3]], b: &[[f64; 3]]| {
            a.iter().zip(b).fold(0.0f64, |m, (p, q)| {
                m.max((Vector3::from(*p) - Vector3::from(*q)).norm())
            })
        };
        let (dh, dm) = (diff(&runs[0], &runs[1]), diff(&runs[2], &runs[1]));
        // the planar twin: its y is the 3D z, its x the 3D x, and nothing moves along 3D y
        let dp = runs[0].iter().zip(&planar).fold(0.0f64, |m, (s, p)| {
            m.max((s[2] - p[1]).abs())
                .max((s[0] - p[0]).abs())
                .max(s[1].abs())
        });
        eprintln!(
            "{case} 3D, {t_end} s: ANCF peak |z| {:.3} mm; max |hybrid − ANCF| {dh:.2e} m ({:.2} %), |modal − ANCF| {dm:.2e} m ({:.2} %); max |3D hybrid − planar hybrid| {dp:.2e} m",
            peak * 1e3,
            100.0 * dh / peak,
            100.0 * dm / peak
        );
        assert!(peak > 1e-3);
        assert!(dh < hybrid_bound * peak && dm < modal_bound * peak);
        // through the simulator (each model's own Newton iterations and step control; both modal
        // bodies nonlinear): 1.7e-14, 9.4e-9 and 2.4e-10 m measured (with both linear: 1.1e-14,
        // 5.0e-13, 7.3e-10 m); at fixed steps tests/spatial.rs holds the twins to 1e-10 m
        // (measured ≤ 5.6e-13 m)
        assert!(dp < 2e-8, "{case}: {dp:e}");
    }
}

/// An all-ANCF rod with torsion along x, clamped, `elements` elements, damping τ_d = 0.7 ms.
fn twist_rod(elements: usize, header: &str) -> Scene {
    scene(
        &format!("space = \"spatial\"\n{header}"),
        &[ancf("a", L, &round(D), elements, "damping_time = 7e-4")],
    )
}

/// The error message of a failed build through both [`Simulator`] and [`AnySimulator`] (the
/// same message).
fn build_error(scene: Scene) -> String {
    let e = Simulator::<Spatial>::start_at(scene.clone(), 0.0).expect_err("refused");
    let any = AnySimulator::new(scene).expect_err("refused");
    assert_eq!(e, any);
    assert!(matches!(e, SimError::Scene(_)), "{e:?}");
    e.to_string()
}

#[test]
fn bad_spatial_scenes_are_refused_naming_the_field() {
    let good = twist_rod(4, "gravity = [0.0, 0.0, -9.81]");
    for bad in [
        [0.0; 4],
        [1.0, f64::NAN, 0.0, 0.0],
        [f64::INFINITY, 0.0, 0.0, 0.0],
    ] {
        let mut s = good.clone();
        s.initial.orientation = Some(bad);
        let e = build_error(s);
        eprintln!("orientation {bad:?}: {e}");
        assert!(e.contains("initial.orientation"), "{e}");
    }
    // zero components alone are fine: [0, 0, 0, 1] turns the root frame by 180° about z
    let mut s = good.clone();
    s.initial.orientation = Some([0.0, 0.0, 0.0, 1.0]);
    let sim = Simulator::<Spatial>::start_at(s, 0.0).unwrap();
    let tip = Vector3::from(sim.outputs().tip_position);
    assert!((tip - Vector3::new(-L, 0.0, 0.0)).norm() < 1e-15, "{tip}");
    // vectors of the wrong length for a spatial scene
    for (field, len) in [("gravity", 2), ("tip.force", 4), ("tip.moment", 1)] {
        let mut s = good.clone();
        let v = vec![0.1; len];
        match field {
            "gravity" => s.gravity = v,
            "tip.force" => s.tip.force = v,
            _ => s.tip.moment = v,
        }
        let e = build_error(s);
        eprintln!("{field}: {e}");
        assert!(
            e.contains(&format!("{field} = [")) && e.contains("a spatial scene takes 3 components"),
            "{e}"
        );
    }
    // a planar scene is not built as a spatial model
    let mut s = good.clone();
    s.space = SpaceKind::Planar;
    s.gravity.clear();
    let e = Simulator::<Spatial>::start_at(s, 0.0).expect_err("refused");
    assert!(e.to_string().contains("space = \"planar\""), "{e}");
    // a host input component this space does not have: refused, nothing changed
    let mut any = AnySimulator::new(good).unwrap();
    let fw = InputId {
        kind: InputKind::TipForce,
        component: 3,
    };
    assert!(!any.set_input(fw, 1.0) && any.input(fw).is_none());
}

/// Little-endian bytes of `v`, concatenated.
fn bytes_of(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

#[test]
fn a_section_director_along_the_slope_is_refused_from_a_snapshot() {
    let scene = twist_rod(4, "gravity = [0.0, 0.0, -9.81]");
    let mut sim = Simulator::<Spatial>::start_at(scene.clone(), 0.0).unwrap();
    sim.advance(2e-3).unwrap();
    let bytes = sim.snapshot();
    let q = sim.state().q.clone();
    let at = bytes
        .windows(8 * q.len())
        .position(|w| w == bytes_of(&q))
        .expect("the coordinates in the snapshot");
    let n = q.len();
    // the tip node is last: [r, r_x, r_y]; r_y := r_x (parallel), then r_y := 0
    let rx = q[n - 6..n - 3].to_vec();
    for (label, ry) in [("parallel", rx.clone()), ("zero", vec![0.0; 3])] {
        let mut spoiled = bytes.clone();
        let start = at + 8 * (n - 3);
        spoiled[start..start + 24].copy_from_slice(&bytes_of(&ry));
        let mut fresh = Simulator::<Spatial>::restorable(scene.clone()).unwrap();
        let e = fresh.restore_snapshot(&spoiled).expect_err("refused");
        eprintln!("r_y {label}: {e}");
        assert!(
            matches!(
                &e,
                SimError::Snapshot(SnapshotError::Refused(Refusal::SectionDirector { segment, .. }))
                    if segment == "a"
            ),
            "{e:?}"
        );
        assert!(e.to_string().contains("r_y"), "{e}");
        let mut any = AnySimulator::restorable(scene.clone()).unwrap();
        assert_eq!(any.restore_snapshot(&spoiled).expect_err("refused"), e);
        // the refusal left the simulator as it was: the intact bytes restore and continue
        fresh.restore_snapshot(&bytes).unwrap();
        assert_eq!(fresh.state(), sim.state());
    }
}

#[test]
fn twist_beyond_what_the_mesh_resolves_is_refused_and_keeps_the_last_good_state() {
    // G·J of the round rod; a dead moment M about the axis twists each element of length l_e
    // by M l_e/GJ statically, up to twice that dynamically
    let g = E_STEEL / 2.6;
    let gj = g * std::f64::consts::PI * D.powi(4) / 32.0;
    let per_element = |m: f64, n: usize| (m * L / n as f64 / gj).to_degrees();
    let m_small = 0.1;
    let m_big = 1.0;
    for any in [false, true] {
        let coarse = twist_rod(2, "");
        let mut sim = AnySimulator::new(coarse).unwrap();
        let mx = InputId {
            kind: InputKind::TipMoment,
            component: 0,
        };
        sim.set_input(mx, m_small);
        sim.advance(0.01).unwrap();
        let before = sim.outputs();
        sim.set_input(mx, m_big);
        let e = if any {
            sim.advance(0.02).expect_err("refused")
        } else {
            let AnySimulator::Spatial(s) = &mut sim else {
                unreachable!()
            };
            s.advance(0.02).expect_err("refused")
        };
        eprintln!(
            "twist {:.0}° per element (static) on 2 elements: {e}",
            per_element(m_big, 2)
        );
        assert!(
            matches!(&e, SimError::Refused { refusal: Refusal::Twist { segment, value }, .. } if segment == "a" && *value > std::f64::consts::FRAC_PI_4),
            "{e:?}"
        );
        assert!(e.to_string().contains("more elements"), "{e}");
        assert_eq!(sim.outputs(), before);
        assert_eq!(sim.time(), 0.01);
        // with the small moment again it goes on
        sim.set_input(mx, m_small);
        sim.advance(0.02).unwrap();
    }
    // the same moment on a mesh that resolves it (8 elements) runs
    let mut fine = Simulator::<Spatial>::start_at(twist_rod(8, ""), 0.0).unwrap();
    fine.set_tip_moment([m_big, 0.0, 0.0]);
    fine.advance(0.02).unwrap();
    let twist = fine.model().validity(&fine.state().q).max_twist.unwrap().1;
    eprintln!(
        "8 elements: {:.0}° per element static, {:.1}° at 20 ms",
        per_element(m_big, 8),
        twist.to_degrees()
    );
    // overdamped twist (τ_d ω ≫ 1): at the static twist per element M l_e/GJ by 20 ms
    let want = m_big * L / 8.0 / gj;
    assert!((twist / want - 1.0).abs() < 0.03 && twist < std::f64::consts::FRAC_PI_4);
}

/// The twist measure behind the refusal against constructed node frames: node 1's slope bent by
/// β about an axis ⟂ the node-0 tangent and its section axis turned by φ about its tangent
/// (r_y stretched and sheared along r_x, which the measure must ignore): twist φ; the sine of
/// the angle between r_x and r_y, closed form.
#[test]
fn twist_and_director_measures_match_constructed_frames() {
    use hybeam::model::ancf3d::Ancf3Props;
    use nalgebra::{Rotation3, Unit};
    let props = Ancf3Props {
        length: 0.05,
        rho_a: 1.0,
        rho_ip: 1.0,
        ea: 1.0,
        ei_y: 1.0,
        ei_z: 1.0,
        gj: 1.0,
        damping_time: 0.0,
        director: true,
        reference: None,
        taper: None,
    };
    let frame0 =
        Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(0.2, -0.7, 0.4)), 1.1);
    let (x0, y0) = (frame0 * Vector3::x(), frame0 * Vector3::y());
    for (beta, phi, shear) in [
        (0.0, 0.3, 0.0),
        (0.8, -0.6, 0.4),
        (1.2, 1.4, -0.2),
        (0.5, 3.0, 0.0),
    ] {
        // bend about an axis ⟂ x0 (in the section plane), then twist about the new tangent
        let bend = Rotation3::from_axis_angle(
            &Unit::new_normalize(frame0 * Vector3::new(0.0, 0.6, 0.8)),
            beta,
        );
        let x1 = bend * x0;
        let twist = Rotation3::from_axis_angle(&Unit::new_normalize(x1), phi);
        let y1 = 1.7 * (twist * bend * y0) + shear * x1;
        let mut e = Vec::new();
        for (r, rx, ry) in [(Vector3::zeros(), x0, y0), (0.05 * x1, 1.02 * x1, y1)] {
            e.extend(r.iter().chain(rx.iter()).chain(ry.iter()));
        }
        let (t, sine) = props.section_measures(&e);
        let want_sine = x1.cross(&y1).norm() / y1.norm();
        eprintln!("β = {beta}, φ = {phi}: twist {t:.15} (want {}), sine {sine:.15} (want {want_sine:.15})", phi.abs());
        assert!((t - phi.abs()).abs() < 1e-12, "{t} vs {phi}");
        assert!((sine - want_sine).abs() < 1e-14);
    }
}
