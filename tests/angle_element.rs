//! Issue 23: the ANCF element with nodal twist angles (`torsion_element = "angle"`, nodes
//! [r, r_x, θ]) built from scenes, against closed forms (helix under an end moment, uniform
//! twist), the director element and the 3D cable on the same runs, and central differences of
//! the whole Newton matrix (joints to modal segments included).

mod common;
use common::*;
use hybeam::integrator::{solve_static, Integrable, State};
use hybeam::model::{Model, Spatial};
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use nalgebra::{Rotation3, UnitQuaternion, Vector3};

const ANGLE: &str = "torsion_element = \"angle\"";

/// Static equilibrium of `scene`: (tip position, tip frame, root moment).
fn statics(scene: &Scene) -> (Vector3<f64>, Rotation3<f64>, Vector3<f64>) {
    let mut model = Model::<Spatial>::from_scene(scene).unwrap();
    let m = model.constraints();
    let mut s = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
    solve_static(&mut model, &mut s, 1e-12).unwrap();
    let o = model.outputs(&s.q, &s.v, &s.acc, &s.lambda);
    let [w, x, y, z] = o.tip_angle;
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
    (
        Vector3::from(o.tip_position),
        rot.to_rotation_matrix(),
        Vector3::from(o.root_moment),
    )
}

/// A 1 m round rod with E·I = 1 N m², G·J = 0.7 N m² (ν = 3/7), clamped along x, `n`
/// elements, no gravity, `tip` the `[tip]` table's lines.
fn unit_rod(element: &str, n: usize, tip: &str) -> Scene {
    let d: f64 = 0.02;
    let i = std::f64::consts::PI * d.powi(4) / 64.0;
    let header = format!(
        "space = \"spatial\"\n{element}\ngravity = [0.0, 0.0, 0.0]\n[tip]\n{tip}\n\
         [solver]\nmax_step = 1e-4\ntolerance = 1e-12\n"
    );
    let seg = format!(
        "name = \"rod\"\nkind = \"ancf\"\nlength = 1.0\n{}\nyoungs_modulus = {:e}\n\
         poisson_ratio = {:e}\ndensity = 1000.0\nelements = {n}\n",
        round(d),
        1.0 / i,
        3.0 / 7.0
    );
    scene(&header, &[seg])
}

/// spatial.md B2: the dead end moment M = (1, 0, 1.5) N m (section axes = global here) bends
/// the rod (EI = 1, GJ = 0.7, L = 1) into a helix; tip position and frame in closed form
/// (as `tests/spatial_ancf.rs` for the director element).
#[test]
fn end_moment_gives_the_closed_form_helix() {
    let (ei, gj): (f64, f64) = (1.0, 0.7);
    let m: Vector3<f64> = Vector3::new(1.0, 0.0, 1.5);
    let (om, mhat) = (m.norm() / ei, m.normalize());
    let ca = m[0] / m.norm();
    let sa = (1.0 - ca * ca).sqrt();
    let u0 = (Vector3::x() - ca * mhat) / sa;
    let w0 = mhat.cross(&u0);
    let r_tip = ca * mhat + (sa / om) * (om.sin() * u0 + (1.0 - om.cos()) * w0);
    let frame_tip =
        Rotation3::new(m / ei) * Rotation3::new(Vector3::x() * m[0] * (1.0 / gj - 1.0 / ei));
    let mut last = (f64::INFINITY, f64::INFINITY);
    for n in [4, 8, 16, 32] {
        let sc = unit_rod(ANGLE, n, "moment = [1.0, 0.0, 1.5]");
        let (tip, frame, root) = statics(&sc);
        let ep = (tip - r_tip).norm();
        // the angle between the frames (|R₁ − R₂|_F/√2: acos loses the small ones)
        let er = (frame_tip.matrix() - frame.matrix()).norm() / 2f64.sqrt();
        // the support holds the applied moment: root moment = −M
        let em = (root + m).norm();
        println!("B2 helix, angle element, {n:2} elements: tip {ep:.3e} m, frame {er:.3e} rad, root moment {em:.1e} N m");
        assert!(
            ep < last.0 && er < last.1,
            "{n}: {ep:e} {er:e} after {last:?}"
        );
        assert!(em < 1e-8, "{n}: root moment {root} vs {m}");
        last = (ep, er);
    }
    // the director element's: 1.1e-8 m at 32 elements (EA 1e4); here EA = 3.1e4 N
    assert!(last.0 < 2e-5 && last.1 < 5e-5, "{last:?}");
}

/// A tip torque twists the clamped rod uniformly: tip rotation M L/(GJ) about x, exact for
/// any mesh (the element twist is the difference of the nodal angles), also beyond π per
/// element.
#[test]
fn tip_torque_twists_by_ml_over_gj() {
    for (n, mt) in [(2, 0.35), (4, 7.0)] {
        let sc = unit_rod(ANGLE, n, &format!("moment = [{mt:e}, 0.0, 0.0]"));
        let (tip, frame, root) = statics(&sc);
        let want = mt / 0.7;
        let (axis, angle) = frame.axis_angle().unwrap();
        let got = angle * axis.x.signum();
        // a rotation angle is reported in [0, π]: compare the rotation itself (|R₁ − R₂|_F/√2)
        let er =
            (Rotation3::new(Vector3::x() * want).matrix() - frame.matrix()).norm() / 2f64.sqrt();
        println!("{n} elements, M_t = {mt}: tip twist {got:.15} (want {want:.15} mod 2π), frame error {er:.1e}");
        assert!(er < 1e-10, "{n}: {er:e}");
        assert!((tip - Vector3::x()).norm() < 1e-12, "{n}: {tip}");
        assert!(
            (root + Vector3::new(mt, 0.0, 0.0)).norm() < 1e-9 * mt,
            "{n}: {root}"
        );
    }
}

/// The spatial Case 1 rod under gravity with a sideways tip force (the peer comparison's
/// problem, `scenes/case1_3d_ancf.toml`), 16 elements, ESDIRK4 at 2e-4 s over 0.5 s: the angle
/// element's tip history against the director element's and the 3D cable's on the same mesh
/// and steps (no torque about the axis: the twist stays at the level of the bending's
/// geometric coupling).
#[test]
fn sideways_loaded_rod_meets_the_director_element_and_the_cable() {
    let run = |element: &str| {
        let text = std::fs::read_to_string(format!(
            "{}/scenes/case1_3d_ancf.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let sets: Vec<(String, String)> = [
            element,
            "tip.force=[0.0, 0.0362894, 0.0]",
            "solver.method=\"esdirk4\"",
            "solver.max_step=2e-4",
        ]
        .iter()
        .map(|s| {
            let (k, v) = s.split_once('=').unwrap();
            (k.to_string(), v.to_string())
        })
        .collect();
        let sc = Scene::from_toml_with_overrides(&text, &sets).unwrap();
        let mut sim = Simulator::<Spatial>::start_at(sc, 0.0).expect("builds");
        let mut tips = Vec::new();
        for k in 1..=250 {
            sim.advance(k as f64 * 2e-3).expect("steps");
            tips.push(Vector3::from(sim.outputs().tip_position));
        }
        tips
    };
    let angle = run("torsion_element=\"angle\"");
    let director = run("torsion_element=\"director\"");
    let cable = run("torsion=false");
    let dist = |a: &[Vector3<f64>], b: &[Vector3<f64>]| {
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).norm()))
    };
    let peak = angle.iter().fold(0.0f64, |m, x| {
        m.max((x - Vector3::new(0.4, 0.0, 0.0)).norm())
    });
    let (ad, ac) = (dist(&angle, &director), dist(&angle, &cable));
    println!("sideways Case 1 over 0.5 s: angle vs director {ad:.2e} m, vs cable {ac:.2e} m (peak {peak:.2e} m)");
    assert!(peak > 1e-2, "{peak}");
    assert!(ad < 1e-8, "angle vs director: {ad:e}");
    assert!(ac < 1e-6, "angle vs cable: {ac:e}");
}

/// The whole Newton matrix (masses, damping, stiffness, joint rows with their λ-Hessian, tip
/// loads) against central differences of the residual, at a deformed moving state: a clamped
/// damped rod with tip force and moment, a ball-rooted rod, and hybrids with a modal segment
/// before and after the ANCF one (their joints take the node's section axis d2(r_x, θ) and its
/// Hessian).
#[test]
fn newton_matrices_match_central_differences() {
    let rod = |root: &str, tip: &str, segs: Vec<String>| {
        let header = format!(
            "space = \"spatial\"\n{ANGLE}\nroot = \"{root}\"\ngravity = [0.0, 0.0, -9.81]\n[tip]\n{tip}\n"
        );
        scene(&header, &segs)
    };
    let a = |n: usize, extra: &str| ancf("a", 0.3, &round(2e-3), n, extra);
    let md = |extra: &str| modal("m", 0.2, &round(3e-3), 3, true, extra);
    for (name, sc) in [
        (
            "clamped, damped",
            rod(
                "clamped",
                "force = [0.0, 0.01, 0.02]\nmoment = [0.003, 0.0, 0.001]",
                vec![a(4, "damping_time = 1e-3")],
            ),
        ),
        (
            "ball",
            rod("ball", "force = [0.0, 0.01, 0.0]", vec![a(3, "")]),
        ),
        (
            "modal then angle",
            rod("clamped", "", vec![md(""), a(3, "")]),
        ),
        (
            "angle then modal",
            rod("clamped", "", vec![a(3, ""), md("")]),
        ),
    ] {
        let mut model = Model::<Spatial>::from_scene(&sc).expect(name);
        let worst = check_newton_matrix(&mut model);
        println!("{name}: worst {worst:.2} of the tolerance");
    }
}

/// Scenes the angle element cannot take are refused before a model exists, naming the field
/// and the fix; a node turned too far from the initial axis is refused by the step.
#[test]
fn refusals_name_the_field_and_the_fix() {
    let seg = ancf("a", 0.3, &round(2e-3), 2, "");
    for (header, want) in [
        ("torsion_element = \"angle\"", "spatial"),
        ("space = \"spatial\"\ntorsion = false\ntorsion_element = \"angle\"", "torsion = true"),
        (
            "space = \"spatial\"\ntorsion_element = \"angle\"\nroot = \"mounted\"\n[mount]\nposition = [0.0, 0.0, 0.0]",
            "director",
        ),
    ] {
        let text = format!("name = \"t\"\n{header}\n[[segments]]\n{seg}");
        let err = Scene::from_toml(&text)
            .and_then(|s| s.validate().map(|_| s))
            .map(|s| Model::<Spatial>::from_scene(&s).map(|_| ()))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.contains("torsion_element") && err.contains(want), "{header}: {err}");
    }
    let flat = scene(
        &format!("space = \"spatial\"\n{ANGLE}"),
        &[ancf(
            "a",
            0.3,
            &square(2e-3).replace("height = 2e-3", "height = 4e-3"),
            2,
            "",
        )],
    );
    let err = Model::<Spatial>::from_scene(&flat)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("E·I_y") && err.contains("director"), "{err}");
    // a ball-rooted rod along x swings down under gravity along −z and up the other side past
    // 150° from its initial axis
    let swing = scene(
        &format!("space = \"spatial\"\n{ANGLE}\nroot = \"ball\"\ngravity = [0.0, 0.0, -9.81]\n[solver]\nmax_step = 1e-3\n"),
        &[ancf("a", 0.3, &round(5e-3), 2, "")],
    );
    let mut sim = Simulator::<Spatial>::start_at(swing, 0.0).expect("builds");
    let mut refused = None;
    for k in 1..=200 {
        if let Err(e) = sim.advance(k as f64 * 5e-3) {
            refused = Some(e.to_string());
            break;
        }
    }
    let why = refused.expect("the swing passes 150°");
    assert!(why.contains("150°") && why.contains("director"), "{why}");
}

/// The linearized spectrum of a clamped round rod (bending in both planes, torsion) equals the
/// director element's on the same mesh (an independent formulation with the same lumped twist
/// inertia and element twist; its r_y penalty adds modes of its own, which the angle element
/// does not have): every angle-element frequency has a director-element one within 1e-7.
#[test]
fn spectrum_equals_the_director_elements() {
    let rod = |element: &str| {
        let sc = scene(
            &format!("space = \"spatial\"\n{element}\ngravity = [0.0, 0.0, 0.0]"),
            &[ancf("a", 0.4, &round(2e-3), 6, "")],
        );
        linearized_modes(&mut Model::<Spatial>::from_scene(&sc).unwrap())
    };
    let angle = rod(ANGLE);
    let director = rod("torsion = true");
    assert!(
        director.len() > angle.len(),
        "{} vs {}",
        director.len(),
        angle.len()
    );
    let mut worst = 0.0f64;
    for (f, _) in angle.iter().filter(|(f, _)| *f > 1.0) {
        let near = director
            .iter()
            .map(|(g, _)| ((g - f) / f).abs())
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(near);
    }
    let n_torsion = angle.len();
    println!("{n_torsion} modes of the angle element, worst relative distance to the director element's {worst:.1e}");
    assert!(worst < 1e-7, "{worst:e}");
}
