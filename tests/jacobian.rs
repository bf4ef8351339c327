//! The assembled Newton matrix (mass, damping, stiffness, joint rows and their λ-Hessian, tip
//! load) against central differences of the assembled residual, at a random deformed state.

mod common;
use common::*;
use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::model::{Model, Planar};

fn check(header: &str, segs: &[String]) {
    let s = scene(header, segs);
    let mut model = Model::<Planar>::from_scene(&s).unwrap();
    model.set_tip_force([0.3, -0.7]);
    let n = model.coordinates();
    let m = model.constraints();
    let d = n + m;
    let wave = |i: usize, a: f64| (a * i as f64 + 0.3).sin();
    let q: Vec<f64> = model
        .initial_coordinates()
        .iter()
        .enumerate()
        .map(|(i, x)| x + 0.02 * wave(i, 1.7))
        .collect();
    let v: Vec<f64> = (0..n).map(|i| 0.5 * wave(i, 0.9)).collect();
    let a: Vec<f64> = (0..n).map(|i| 3.0 * wave(i, 2.3)).collect();
    let lam: Vec<f64> = (0..m).map(|i| 0.1 * wave(i, 1.1)).collect();
    let mut res = vec![0.0; d];
    let mut matrix = |model: &mut Model, c: (f64, f64, f64)| {
        let req = EvalRequest {
            sd: 1.0,
            matrix: Some(c),
            lambda_hessian: c.2 != 0.0,
        };
        model.eval(StateRef::new(&q, &v, &a, &lam), req, &mut res);
        model.assembled_dense()
    };
    let mats = [
        matrix(&mut model, (0.0, 0.0, 1.0)),
        matrix(&mut model, (0.0, 1.0, 0.0)),
        matrix(&mut model, (1.0, 0.0, 0.0)),
    ];
    let resid = |model: &mut Model, q: &[f64], v: &[f64], a: &[f64], lam: &[f64]| {
        let mut r = vec![0.0; d];
        let req = EvalRequest {
            sd: 1.0,
            matrix: None,
            lambda_hessian: false,
        };
        model.eval(StateRef::new(q, v, a, lam), req, &mut r);
        r
    };
    let base = resid(&mut model, &q, &v, &a, &lam);
    let scale = base.iter().fold(1.0f64, |s, x| s.max(x.abs()));
    for (which, mat) in mats.iter().enumerate() {
        for j in 0..d {
            if which > 0 && j >= n {
                continue;
            }
            let h = 1e-7;
            let (mut p, mut mm) = (
                vec![q.clone(), v.clone(), a.clone(), lam.clone()],
                vec![q.clone(), v.clone(), a.clone(), lam.clone()],
            );
            let (slot, k) = if j >= n { (3, j - n) } else { (which, j) };
            p[slot][k] += h;
            mm[slot][k] -= h;
            let rp = resid(&mut model, &p[0], &p[1], &p[2], &p[3]);
            let rm = resid(&mut model, &mm[0], &mm[1], &mm[2], &mm[3]);
            // joint rows hold Φ_q in every assembled matrix; they are checked with the stiffness
            let rows = if which == 0 { d } else { n };
            for i in 0..rows {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                let err = (fd - mat[i][j]).abs();
                assert!(
                    err < 1e-6 * (1.0 + mat[i][j].abs()) + 1e-8 * scale,
                    "{which}: [{i},{j}] analytic {} fd {fd} (n = {n}, m = {m})",
                    mat[i][j]
                );
            }
        }
    }
}

#[test]
fn pinned_modal_root_with_ancf_and_modal_tip() {
    let d = 0.004;
    check(
        "root = \"pinned\"\ngravity = [1.0, -9.81]",
        &[
            modal("m1", 0.2, &round(d), 3, true, "damping_ratio = 0.05"),
            ancf("a", 0.2, &round(d), 2, "damping_time = 1e-3"),
            modal("m2", 0.2, &round(d), 2, false, ""),
        ],
    );
}

#[test]
fn clamped_ancf_root_with_modal_middle() {
    let d = 0.004;
    check(
        "gravity = [0.0, -9.81]",
        &[
            ancf("a1", 0.2, &round(d), 2, "strain = \"paper\""),
            modal("m", 0.2, &round(d), 2, true, "damping_time = 1e-3"),
            modal("m2", 0.1, &round(d), 2, false, ""),
            ancf("a2", 0.2, &round(d), 2, ""),
        ],
    );
}
