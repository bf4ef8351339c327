//! Scene builders shared by the physics tests.
#![allow(dead_code)]

use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::model::{Model, Planar, Space};
use hybeam::scene::Scene;
use hybeam::simulator::{AnySimulator, InputId};
use nalgebra::DMatrix;

/// Steel.
pub const E_STEEL: f64 = 2.1e11;
/// Steel density [kg/m³].
pub const RHO_STEEL: f64 = 7850.0;

/// A scene from a header (top-level fields and tables) and segment tables.
pub fn scene(header: &str, segments: &[String]) -> Scene {
    let mut text = format!("name = \"test\"\n{header}\n");
    for s in segments {
        text.push_str("[[segments]]\n");
        text.push_str(s);
        text.push('\n');
    }
    Scene::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// An ANCF segment table.
pub fn ancf(name: &str, length: f64, section: &str, elements: usize, extra: &str) -> String {
    format!(
        "name = \"{name}\"\nkind = \"ancf\"\nlength = {length:e}\n{section}\nyoungs_modulus = {E_STEEL:e}\ndensity = {RHO_STEEL:e}\nelements = {elements}\n{extra}\n"
    )
}

/// A modal segment table.
pub fn modal(
    name: &str,
    length: f64,
    section: &str,
    modes: usize,
    interface: bool,
    extra: &str,
) -> String {
    format!(
        "name = \"{name}\"\nkind = \"modal\"\nlength = {length:e}\n{section}\nyoungs_modulus = {E_STEEL:e}\ndensity = {RHO_STEEL:e}\nmodes = {modes}\ninterface_modes = {interface}\n{extra}\n"
    )
}

/// Round section of diameter d.
pub fn round(d: f64) -> String {
    format!("section = \"round\"\ndiameter = {d:e}")
}

/// Square section of side b.
pub fn square(b: f64) -> String {
    format!("section = \"rectangle\"\nwidth = {b:e}\nheight = {b:e}")
}

/// Reads the tip y column of a run, sampled every `dt` up to `t_end`.
pub fn tip_history(scene: Scene, t_end: f64, dt: f64) -> Vec<[f64; 2]> {
    let mut sim = hybeam::simulator::Simulator::<Planar>::new(scene).expect("scene builds");
    let mut out = vec![sim.outputs().tip_position];
    let n = (t_end / dt).round() as usize;
    for k in 1..=n {
        sim.advance(k as f64 * dt).expect("step succeeds");
        out.push(sim.outputs().tip_position);
    }
    out
}

/// The largest distance between two tip histories of equal sampling [m].
pub fn max_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt())
        .fold(0.0, f64::max)
}

/// The modes of a model linearized at its initial state (at rest, λ = 0): M and K from the
/// assembled Newton matrix, restricted to the null space of Φ_q (projector
/// I − Φ_qᵀ(Φ_qΦ_qᵀ)⁻¹Φ_q), generalized symmetric eigenproblem. Returns (frequency [Hz],
/// mass-normalized shape on all coordinates) by increasing frequency.
pub fn linearized_modes<S: Space>(model: &mut Model<S>) -> Vec<(f64, Vec<f64>)> {
    let n = model.coordinates();
    let m = model.constraints();
    let q = model.initial_coordinates().to_vec();
    let z = vec![0.0; n];
    let lam = vec![0.0; m];
    let mut res = vec![0.0; n + m];
    let mut dense = |ca: f64, cx: f64| {
        let req = EvalRequest {
            sd: 1.0,
            matrix: Some((ca, 0.0, cx)),
            lambda_hessian: true,
        };
        model.eval(StateRef::new(&q, &z, &z, &lam), req, &mut res);
        let a = model.assembled_dense();
        DMatrix::from_fn(n + m, n + m, |i, j| a[i][j])
    };
    let full_m = dense(1.0, 0.0);
    let full_k = dense(0.0, 1.0);
    let mm = full_m.view((0, 0), (n, n)).into_owned();
    let kk = full_k.view((0, 0), (n, n)).into_owned();
    let basis = if m > 0 {
        let g = full_k.view((n, 0), (m, n)).into_owned();
        let ggt = (&g * g.transpose())
            .try_inverse()
            .expect("independent constraint rows");
        let p = DMatrix::<f64>::identity(n, n) - g.transpose() * ggt * &g;
        let e = p.symmetric_eigen();
        let cols: Vec<_> = (0..n)
            .filter(|&i| e.eigenvalues[i] > 0.5)
            .map(|i| e.eigenvectors.column(i).into_owned())
            .collect();
        assert_eq!(cols.len(), n - m);
        DMatrix::from_columns(&cols)
    } else {
        DMatrix::identity(n, n)
    };
    let mr = basis.transpose() * &mm * &basis;
    let kr = basis.transpose() * &kk * &basis;
    let l = mr
        .cholesky()
        .expect("positive mass on the constraint manifold")
        .l();
    let li = l.try_inverse().unwrap();
    let a = &li * kr * li.transpose();
    let a = 0.5 * (&a + a.transpose());
    let e = a.symmetric_eigen();
    let shapes = &basis * li.transpose() * &e.eigenvectors;
    let mut modes: Vec<(f64, Vec<f64>)> = (0..e.eigenvalues.len())
        .map(|k| {
            let f = e.eigenvalues[k].max(0.0).sqrt() / std::f64::consts::TAU;
            (f, shapes.column(k).iter().copied().collect())
        })
        .collect();
    modes.sort_by(|a, b| a.0.total_cmp(&b.0));
    modes
}

/// A deterministic deformed, moving state of `model` (not a solution): q = the initial
/// coordinates + `amp`·sin waves, q̇ and q̈ of order 0.5 and 3, λ of order 0.1.
pub fn wavy_state<S: Space>(model: &Model<S>, amp: f64) -> [Vec<f64>; 4] {
    let (n, m) = (model.coordinates(), model.constraints());
    let wave = |i: usize, a: f64| (a * i as f64 + 0.3).sin();
    let q: Vec<f64> = model
        .initial_coordinates()
        .iter()
        .enumerate()
        .map(|(i, x)| x + amp * wave(i, 1.7))
        .collect();
    let v: Vec<f64> = (0..n).map(|i| 0.5 * wave(i, 0.9)).collect();
    let a: Vec<f64> = (0..n).map(|i| 3.0 * wave(i, 2.3)).collect();
    let lam: Vec<f64> = (0..m).map(|i| 0.1 * wave(i, 1.1)).collect();
    [q, v, a, lam]
}

/// The assembled Newton matrix (mass, damping, stiffness, joint rows and their λ-Hessian, tip
/// loads) of `model` against central differences of the assembled residual at a perturbed
/// state; panics on a mismatch, returns the worst error as a fraction of its tolerance
/// 1e-6·(1 + |entry|) + 1e-8·max|residual|.
pub fn check_newton_matrix<S: Space>(model: &mut Model<S>) -> f64 {
    let n = model.coordinates();
    let m = model.constraints();
    let d = n + m;
    let [q, v, a, lam] = wavy_state(model, 0.02);
    let mut res = vec![0.0; d];
    let mut matrix = |model: &mut Model<S>, c: (f64, f64, f64)| {
        let req = EvalRequest {
            sd: 1.0,
            matrix: Some(c),
            lambda_hessian: c.2 != 0.0,
        };
        model.eval(StateRef::new(&q, &v, &a, &lam), req, &mut res);
        model.assembled_dense()
    };
    let mats = [
        matrix(model, (0.0, 0.0, 1.0)),
        matrix(model, (0.0, 1.0, 0.0)),
        matrix(model, (1.0, 0.0, 0.0)),
    ];
    let resid = |model: &mut Model<S>, x: [&[f64]; 4]| {
        let mut r = vec![0.0; d];
        let req = EvalRequest {
            sd: 1.0,
            matrix: None,
            lambda_hessian: false,
        };
        model.eval(StateRef::new(x[0], x[1], x[2], x[3]), req, &mut r);
        r
    };
    let base = resid(model, [&q, &v, &a, &lam]);
    let scale = base.iter().fold(1.0f64, |s, x| s.max(x.abs()));
    let mut worst = 0.0f64;
    for (which, mat) in mats.iter().enumerate() {
        for j in 0..d {
            if which > 0 && j >= n {
                continue;
            }
            let h = 1e-7;
            let (mut p, mut mm) = (
                [q.clone(), v.clone(), a.clone(), lam.clone()],
                [q.clone(), v.clone(), a.clone(), lam.clone()],
            );
            let (slot, k) = if j >= n { (3, j - n) } else { (which, j) };
            p[slot][k] += h;
            mm[slot][k] -= h;
            let rp = resid(model, [&p[0], &p[1], &p[2], &p[3]]);
            let rm = resid(model, [&mm[0], &mm[1], &mm[2], &mm[3]]);
            // joint rows hold Φ_q in every assembled matrix; they are checked with the stiffness
            let rows = if which == 0 { d } else { n };
            for i in 0..rows {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                let err = (fd - mat[i][j]).abs();
                let tol = 1e-6 * (1.0 + mat[i][j].abs()) + 1e-8 * scale;
                worst = worst.max(err / tol);
                assert!(
                    err < tol,
                    "{which}: [{i},{j}] analytic {} fd {fd} (n = {n}, m = {m})",
                    mat[i][j]
                );
            }
        }
    }
    worst
}

/// The input of `sim` named `name`.
pub fn input_id(sim: &AnySimulator, name: &str) -> InputId {
    InputId::of_scene(sim.scene())
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no input {name}"))
        .1
}

/// Sets the inputs `values` by name (each must exist).
pub fn set_inputs(sim: &mut AnySimulator, values: &[(String, f64)]) {
    for (name, x) in values {
        let id = input_id(sim, name);
        assert!(sim.set_input(id, *x), "{name}");
    }
}

/// A mount motion: pose, velocities and accelerations at time t [s], by input name.
pub type Drive = fn(f64) -> Vec<(String, f64)>;

/// Planar boom on the car's roof: heave 1 cm and pitch 0.01 rad at 2 Hz from rest.
pub fn boom_mount(t: f64) -> Vec<(String, f64)> {
    let w = 2.0 * std::f64::consts::PI * 2.0;
    let (a, b) = (0.01, 0.01);
    let (s, c) = (w * t).sin_cos();
    [
        ("root.position.x", 0.3),
        ("root.position.y", 1.4 + a * (1.0 - c)),
        ("root.angle", b * (1.0 - c)),
        ("root.velocity.x", 0.0),
        ("root.velocity.y", a * w * s),
        ("root.angular_velocity", b * w * s),
        ("root.acceleration.x", 0.0),
        ("root.acceleration.y", a * w * w * c),
        ("root.angular_acceleration", b * w * w * c),
    ]
    .iter()
    .map(|(n, x)| (n.to_string(), *x))
    .collect()
}

/// The spatial mounted rod's start motion (1 m up, spinning at 2 rad/s about z, accelerating
/// up at 3 m/s²) continued, with a 1 cm heave at 2 Hz from rest on top.
pub fn rod_3d_mount(t: f64) -> Vec<(String, f64)> {
    let w = 2.0 * std::f64::consts::PI * 2.0;
    let a = 0.01;
    let (s, c) = (w * t).sin_cos();
    let (sh, ch) = t.sin_cos(); // half of the spin angle 2t
    [
        ("root.position.x", 0.0),
        ("root.position.y", 0.0),
        ("root.position.z", 1.0 + 1.5 * t * t + a * (1.0 - c)),
        ("root.orientation.e0", ch),
        ("root.orientation.e1", 0.0),
        ("root.orientation.e2", 0.0),
        ("root.orientation.e3", sh),
        ("root.velocity.x", 0.0),
        ("root.velocity.y", 0.0),
        ("root.velocity.z", 3.0 * t + a * w * s),
        ("root.angular_velocity.x", 0.0),
        ("root.angular_velocity.y", 0.0),
        ("root.angular_velocity.z", 2.0),
        ("root.acceleration.x", 0.0),
        ("root.acceleration.y", 0.0),
        ("root.acceleration.z", 3.0 + a * w * w * c),
        ("root.angular_acceleration.x", 0.0),
        ("root.angular_acceleration.y", 0.0),
        ("root.angular_acceleration.z", 0.0),
    ]
    .iter()
    .map(|(n, x)| (n.to_string(), *x))
    .collect()
}

/// `scene` with every modal segment the linear floating frame (`linear = true`): the planar
/// twin of the spatial modal body, which is linear (the planar one is geometrically nonlinear
/// by default, `src/model/modal/body.rs`).
pub fn linear_modal(mut scene: Scene) -> Scene {
    for seg in &mut scene.segments {
        if seg.kind == hybeam::scene::SegmentKind::Modal {
            seg.linear = true;
        }
    }
    scene
}
