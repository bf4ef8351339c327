//! Issue 23: the director element is isotropic in bending. A round rod with
//! torsion, clamped, loaded at the tip by a force in the y–z plane at 0°, 30°, 45° and 90°:
//! statics (Newton on the static residual) and a short step-load dynamic run at fixed steps
//! give deflections of equal magnitude along the load (the independent reference: the same
//! run along y, turned by the angle about x), as the 3D cable does. And a sideways-loaded
//! converged torsion run meets the converged cable run (no director inertia in bending).

mod common;
use common::*;
use hybeam::integrator::{solve_static, Integrable, State};
use hybeam::model::{Model, Spatial};
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use nalgebra::{Rotation3, Vector3};

const ANGLES: [f64; 4] = [0.0, 30.0, 45.0, 90.0];

/// The 0.4 m, d = 2 mm steel rod clamped along x, `elements` elements, tip force `f` [N] at
/// `deg` degrees from y towards z, no gravity, fixed step `h`.
fn rod(element: &str, elements: usize, f: f64, deg: f64, h: f64) -> Scene {
    let a = deg.to_radians();
    let header = format!(
        "space = \"spatial\"\n{element}\ngravity = [0.0, 0.0, 0.0]\n\
         [tip]\nforce = [0.0, {:e}, {:e}]\n\
         [solver]\nmax_step = {h:e}\nrho_inf = 0.9\ntolerance = 1e-15\n",
        f * a.cos(),
        f * a.sin()
    );
    scene(&header, &[ancf("a", 0.4, &round(2e-3), elements, "")])
}

/// Tip displacement of the static equilibrium.
fn static_tip(scene: &Scene) -> Vector3<f64> {
    let mut model = Model::<Spatial>::from_scene(scene).unwrap();
    let m = model.constraints();
    let mut s = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
    solve_static(&mut model, &mut s, 1e-13).unwrap();
    let o = model.outputs(&s.q, &s.v, &s.acc, &s.lambda);
    Vector3::from(o.tip_position) - Vector3::new(0.4, 0.0, 0.0)
}

/// Tip displacements of a run to `t_end`, every `dt`.
fn tip_run(scene: Scene, t_end: f64, dt: f64) -> Vec<Vector3<f64>> {
    let mut sim = Simulator::<Spatial>::start_at(scene, 0.0).expect("builds");
    let x0 = Vector3::new(0.4, 0.0, 0.0);
    let mut out = vec![Vector3::from(sim.outputs().tip_position) - x0];
    for k in 1..=(t_end / dt).round() as usize {
        sim.advance(k as f64 * dt).expect("steps");
        out.push(Vector3::from(sim.outputs().tip_position) - x0);
    }
    out
}

/// The reference turned by `deg` about x (y towards z).
fn turned(u: &Vector3<f64>, deg: f64) -> Vector3<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), deg.to_radians()) * u
}

/// Largest distance of the runs at each angle from the 0° run turned by the angle, over the
/// peak deflection.
fn spread(runs: &[Vec<Vector3<f64>>]) -> f64 {
    let peak = runs[0].iter().fold(0.0f64, |m, u| m.max(u.norm()));
    assert!(peak > 1e-3, "{peak}");
    let mut worst = 0.0f64;
    for (deg, run) in ANGLES.iter().zip(runs) {
        for (u, r) in run.iter().zip(&runs[0]) {
            worst = worst.max((u - turned(r, *deg)).norm());
        }
    }
    worst / peak
}

#[test]
fn round_rod_deflects_alike_in_every_transverse_direction() {
    // 0.03 N: ~4 cm static tip deflection (10 % of the length: large rotation). The issue's
    // target: 1e-10 of the peak, statics and dynamics. Measured (`cargo test --release -p
    // hybeam --test torsion_isotropy -- --nocapture`, Newton tolerance 1e-15): cable 9.0e-16
    // static, 1.59e-11 dynamic; torsion 1.44e-14, 1.52e-11. Static, torsion: the element twist
    // from the nodal frames by parallel transport is zero for any twist-free bent rod (2.5e-7
    // with the Gauss-point twist of the linear r_y, before). Dynamic, torsion: the director
    // inertia lumped at the nodes (3.02e-8 at tolerance 1e-12, as the cable's 3.93e-8; at the 3
    // Gauss points it was 1.07e-5: the linear r_y lags the tangent's rotation between the
    // nodes, a rotary inertia for a director in the bending plane, none for one normal to it).
    // The angle element (torsion_element = "angle"): the twist of its smallest-rotation frames
    // is zero for a rod bent in any plane through its initial axis.
    for element in [
        "torsion = false",
        "torsion = true",
        "torsion_element = \"angle\"",
    ] {
        let statics: Vec<Vec<Vector3<f64>>> = ANGLES
            .iter()
            .map(|&deg| vec![static_tip(&rod(element, 8, 0.03, deg, 1e-4))])
            .collect();
        let s = spread(&statics);
        let dynamics: Vec<Vec<Vector3<f64>>> = ANGLES
            .iter()
            .map(|&deg| tip_run(rod(element, 8, 0.03, deg, 1e-4), 0.05, 1e-3))
            .collect();
        let d = spread(&dynamics);
        eprintln!("{element}: static spread {s:.2e}, dynamic spread {d:.2e} of the peak");
        assert!(s < 1e-10, "{element}: static {s:e}");
        assert!(d < 1e-10, "{element}: dynamic {d:e}");
    }
}
