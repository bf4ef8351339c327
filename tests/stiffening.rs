//! Geometric (centrifugal) stiffening of a beam on a spinning mount, spatial.md B6 (Rayleigh–
//! Ritz with 12 clamped–free modes; the flap column is Wright et al. 1982's): the Case 1 rod
//! (d = 2 mm steel, 40 cm) clamped to a mount spinning at Ω about the world z axis, gravity off,
//! a small constant tip force along z (the spin axis: constant in the rotating frame) sets it
//! flapping; the flap frequency, from the period of the tip's z motion, against the table. A
//! linear floating frame stays at ω₁* = 3.5160 at every Ω; the all-ANCF rod is geometrically
//! nonlinear by itself; the modal segment of a held frame carries K_G = ρAL Ω²G2 (+ the axial
//! inertia term), the hybrid's joint rows the outboard tension.

use hybeam::model::Space;
use hybeam::model::{Planar, Spatial};
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;

/// ω* = ω / √(EI/(ρAL⁴)) of the Case 1 rod: √(EI/(ρAL⁴)) [rad/s].
fn omega_ref() -> f64 {
    let (e, rho, d, l): (f64, f64, f64, f64) = (2.1e11, 7850.0, 0.002, 0.4);
    let (a, i) = (
        std::f64::consts::PI * d * d / 4.0,
        std::f64::consts::PI * d.powi(4) / 64.0,
    );
    (e * i / (rho * a * l.powi(4))).sqrt()
}

fn spinning(name: &str, omega: f64) -> Scene {
    spinning_under(name, omega, "[0.0, 0.0, 0.0]")
}

/// [`spinning`] under the gravity vector `gravity`.
fn spinning_under(name: &str, omega: f64, gravity: &str) -> Scene {
    let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("root = \"clamped\"", "root = \"mounted\"")
        .replace(
            "gravity = [0.0, 0.0, -9.81]",
            &format!("gravity = {gravity}"),
        );
    let text = format!("{text}\n[mount]\nangular_velocity = [0.0, 0.0, {omega:e}]\n\n[tip]\nforce = [0.0, 0.0, 1e-4]\n");
    Scene::from_toml(&text).unwrap_or_else(|e| panic!("{e}"))
}

/// Flap frequency [rad/s] from the tip's z motion over `t_end` (see [`frequency_of`]).
fn flap_frequency(scene: Scene, t_end: f64) -> f64 {
    let mut sim = Simulator::<Spatial>::start_at(scene, 0.0).unwrap();
    frequency_of(&mut sim, t_end, |s| s.outputs().tip_position[2])
}

/// The angular frequency [rad/s] of `signal` from the mean period between its upward
/// crossings of its mean, sampled every 0.2 ms over `t_end`.
fn frequency_of<S: Space>(
    sim: &mut Simulator<S>,
    t_end: f64,
    signal: impl Fn(&Simulator<S>) -> f64,
) -> f64 {
    frequency_after(sim, 0.0, t_end, signal)
}

/// [`frequency_of`] over (`t_skip`, `t_end`] only.
fn frequency_after<S: Space>(
    sim: &mut Simulator<S>,
    t_skip: f64,
    t_end: f64,
    signal: impl Fn(&Simulator<S>) -> f64,
) -> f64 {
    let dt = 2e-4;
    let n = (t_end / dt) as usize;
    let skip = (t_skip / dt) as usize;
    let mut z = Vec::with_capacity(n);
    for k in 1..=n {
        sim.advance(k as f64 * dt).unwrap();
        if k > skip {
            z.push(signal(sim));
        }
    }
    let n = z.len();
    let mean = z.iter().sum::<f64>() / n as f64;
    let mut ups = Vec::new();
    for k in 1..n {
        let (a, b) = (z[k - 1] - mean, z[k] - mean);
        if a < 0.0 && b >= 0.0 {
            ups.push((k as f64 + a / (a - b)) * dt);
        }
    }
    let periods = (ups.len() - 1) as f64;
    2.0 * std::f64::consts::PI * periods / (ups[ups.len() - 1] - ups[0])
}

#[test]
fn b6_spinning_cantilever_flap_frequencies() {
    let w0 = omega_ref();
    for (omega_star, flap) in [(0.0, 3.5160), (2.0, 4.1373), (4.0, 5.5850)] {
        for name in ["case1_3d_ancf", "case1_3d_modal", "case1_3d"] {
            let w = flap_frequency(spinning(name, omega_star * w0), 1.0) / w0;
            let err = w / flap - 1.0;
            eprintln!("Ω* = {omega_star}: {name} flap ω₁* = {w:.4} vs {flap} ({err:+.2e})");
            assert!(err.abs() < 5e-3, "{name} Ω* = {omega_star}: {w} vs {flap}");
        }
    }
}

/// Gravity along the rod's axis: hanging (tension) raises the flap frequency, standing
/// (compression) lowers it, by the axial-inertia term −ρA ā_x G1 of the modal segment; the
/// geometrically nonlinear all-ANCF rod is the reference.
#[test]
fn axial_gravity_stiffens_a_hanging_rod_and_softens_a_standing_one() {
    let w0 = omega_ref();
    for (label, g) in [
        ("hanging", "[9.81, 0.0, 0.0]"),
        ("standing", "[-9.81, 0.0, 0.0]"),
    ] {
        let reference = flap_frequency(spinning_under("case1_3d_ancf", 0.0, g), 1.0) / w0;
        for name in ["case1_3d_modal", "case1_3d"] {
            let w = flap_frequency(spinning_under(name, 0.0, g), 1.0) / w0;
            let err = w / reference - 1.0;
            eprintln!("{label}: {name} flap ω₁* = {w:.4} vs all-ANCF {reference:.4} ({err:+.2e})");
            assert!(err.abs() < 1e-3, "{label} {name}: {w} vs {reference}");
        }
        let shift = reference / 3.5160 - 1.0;
        assert!(
            if label == "hanging" {
                shift > 5e-3
            } else {
                shift < -5e-3
            },
            "{label} {shift}"
        );
    }
}

/// The stiffening integrals of the clamped–free modes against spatial.md §2.4 (SciPy): diagonals
/// of G1 = ∫(1 − ξ)φ′φ′ and G2 = ∫½(1 − ξ²)φ′φ′; G2₁₁ is Southwell's coefficient 1.19334.
#[test]
fn stiffening_integrals_are_the_tabulated_ones() {
    let basis = hybeam::model::modal::ModalBasis::new(4, false);
    let (g1, g2) = basis.stiffening_grams();
    let want1 = [1.57088, 8.64714, 24.95211, 51.45911];
    let want2 = [1.19334, 6.47822, 17.85952, 36.05539];
    for k in 0..4 {
        assert!(
            (g1[5 * k] / want1[k] - 1.0).abs() < 5e-6,
            "G1[{k}] {}",
            g1[5 * k]
        );
        assert!(
            (g2[5 * k] / want2[k] - 1.0).abs() < 5e-6,
            "G2[{k}] {}",
            g2[5 * k]
        );
    }
    // G2 is full: the off-diagonal term of spatial.md (its sign is that of the shapes' signs)
    assert!((g2[1].abs() - 0.68586).abs() < 5e-5, "G2[0][1] {}", g2[1]);
}

/// `scene` (of a shipped file's text) spinning at `omega` [rad/s] about z with no gravity, a
/// dead tip moment `moment` about z, and Kelvin–Voigt damping `damping_time` on every segment.
fn lag_scene(text: &str, omega: &str, moment: &str, damping_time: f64) -> Scene {
    let mut text = text
        .replace("root = \"clamped\"", "root = \"mounted\"")
        .replace("gravity = [0.0, -9.81]", "gravity = [0.0, 0.0]")
        .replace("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, 0.0]");
    for kind in ["kind = \"ancf\"", "kind = \"modal\""] {
        text = text.replace(kind, &format!("{kind}\ndamping_time = {damping_time:e}"));
    }
    let text = format!("{text}\n[mount]\nangular_velocity = {omega}\n\n[tip]\nmoment = {moment}\n");
    Scene::from_toml(&text).unwrap_or_else(|e| panic!("{e}"))
}

/// The tip's position across the rod in the mount frame (its y component, relative to the
/// mount point) [m].
fn across<S: Space>(sim: &Simulator<S>) -> f64 {
    let (o, m) = (sim.outputs(), sim.mount().unwrap());
    let mut r = o.tip_position;
    for c in 0..S::DIM {
        r[c] -= m.position[c];
    }
    S::to_frame(&m.attitude, &r)[1]
}

/// The lag (in-plane) frequency on a mount spinning in its plane: ω_lag² = ω_flap² − Ω²
/// (B6 lag column 3.5160, 3.6218, 3.8977 at Ω* = 0, 2, 4), from the tip's motion across the
/// rod in the rotating frame, set off by a dead tip moment about the spin axis, for the
/// all-ANCF, hybrid and all-modal rods in the plane and in space. The rod starts unstretched:
/// its centrifugal stretch in the first axial periods moves it outward, and the Coriolis force
/// of that motion kicks every lag mode; so the moment (1e-4 N m, a tip deflection of ~1e-4 m)
/// makes the first mode dominate, Kelvin–Voigt damping of 1e-4 s (ζ = τω/2: 2.8e-3 on the
/// first mode, a frequency shift of 4e-6; six times more on the second) takes the higher ones
/// out, and the period is counted over the second half second. Without the damping the count
/// over the whole second reads the mixture (4.03 for the planar all-ANCF rod at Ω* = 2, 4.32
/// for the hybrid at Ω* = 4). Seen: within 5.1e-4 of the table for all five rods.
#[test]
fn b6_lag_frequencies() {
    let w0 = omega_ref();
    let read = |name: &str| {
        let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(path).unwrap()
    };
    for (omega_star, lag) in [(0.0, 3.5160), (2.0, 3.6218), (4.0, 3.8977)] {
        let omega = omega_star * w0;
        let mut results = Vec::new();
        for name in ["case1_ancf", "case1", "case1_modal"] {
            let scene = lag_scene(&read(name), &format!("[{omega:e}]"), "[1e-4]", 1e-4);
            let mut sim = Simulator::<Planar>::start_at(scene, 0.0).unwrap();
            results.push((name, frequency_after(&mut sim, 0.5, 1.0, across) / w0));
        }
        for name in ["case1_3d_ancf", "case1_3d"] {
            let scene = lag_scene(
                &read(name),
                &format!("[0.0, 0.0, {omega:e}]"),
                "[0.0, 0.0, 1e-4]",
                1e-4,
            );
            let mut sim = Simulator::<Spatial>::start_at(scene, 0.0).unwrap();
            results.push((name, frequency_after(&mut sim, 0.5, 1.0, across) / w0));
        }
        for (name, w) in results {
            let err = w / lag - 1.0;
            eprintln!("Ω* = {omega_star}: {name} lag ω₁* = {w:.4} vs {lag} ({err:+.2e})");
            assert!(err.abs() < 1e-3, "{name} Ω* = {omega_star}: {w} vs {lag}");
        }
    }
}
