//! Bending frequencies of the clamped rod from the linearized model (M, K, Φ_q at the straight
//! state, constrained generalized eigenproblem) against Euler–Bernoulli closed form
//! ω_n = λ_n² √(EI/(ρA L⁴)), λ_n roots of 1 + cos λ cosh λ = 0.

mod common;
use common::*;
use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::model::{Model, Planar};
use nalgebra::DMatrix;

const LAMBDA: [f64; 3] = [
    1.875_104_068_711_961,
    4.694_091_132_974_175,
    7.854_757_438_237_613,
];

fn euler_bernoulli(d: f64, l: f64) -> Vec<f64> {
    let area = std::f64::consts::PI * d * d / 4.0;
    let ei = E_STEEL * area * d * d / 16.0;
    LAMBDA
        .iter()
        .map(|lam| {
            lam * lam * (ei / (RHO_STEEL * area * l.powi(4))).sqrt() / (2.0 * std::f64::consts::PI)
        })
        .collect()
}

/// Lowest frequencies [Hz] of the model linearized at its straight initial state.
fn frequencies(segs: &[String]) -> Vec<f64> {
    let s = scene("gravity = [0.0, 0.0]", segs);
    let mut model = Model::<Planar>::from_scene(&s).unwrap();
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
    // null space of Φ_q from the projector I − Φ_qᵀ(Φ_qΦ_qᵀ)⁻¹Φ_q
    let basis = if m > 0 {
        let g = full_k.view((n, 0), (m, n)).into_owned();
        let ggt = (&g * g.transpose()).try_inverse().unwrap();
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
    let l = mr.cholesky().unwrap().l();
    let li = l.try_inverse().unwrap();
    let a = &li * kr * li.transpose();
    let a = 0.5 * (&a + a.transpose());
    let mut w2: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
    w2.sort_by(f64::total_cmp);
    // transverse bending modes only: the lowest three are bending for these slender rods
    w2.iter()
        .take(3)
        .map(|x| x.sqrt() / (2.0 * std::f64::consts::PI))
        .collect()
}

fn check(name: &str, got: &[f64], want: &[f64], tol: f64) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        let rel = g / w - 1.0;
        eprintln!(
            "{name}: f{} = {g:.5} Hz, Euler-Bernoulli {w:.5} Hz, error {rel:+.2e}",
            i + 1
        );
        assert!(
            rel.abs() < tol,
            "{name}: f{} = {g:.5} Hz vs {w:.5} Hz ({:.3e})",
            i + 1,
            rel
        );
    }
}

#[test]
fn ancf_rod_with_8_elements_within_0_1_percent() {
    let d = 0.002;
    let f = frequencies(&[ancf("a", 0.4, &round(d), 8, "")]);
    check("all-ANCF", &f, &euler_bernoulli(d, 0.4), 1e-3);
}

#[test]
fn modal_rod_reproduces_euler_bernoulli() {
    let d = 0.002;
    let f = frequencies(&[modal("m", 0.4, &round(d), 4, false, "")]);
    check("all-modal", &f, &euler_bernoulli(d, 0.4), 1e-6);
}

#[test]
fn hybrid_rod_within_0_1_percent() {
    let d = 0.002;
    let f = frequencies(&[
        modal("m", 0.2, &round(d), 4, true, ""),
        ancf("a", 0.2, &round(d), 8, ""),
    ]);
    check("hybrid", &f, &euler_bernoulli(d, 0.4), 1e-3);
}

#[test]
fn hybrid_without_interface_modes_converges_slower() {
    // clamped–free modes have zero moment at the joint end: the same count without interface
    // modes is less accurate (docs/references.md §3, interface warning)
    let d = 0.002;
    let eb = euler_bernoulli(d, 0.4);
    let with = frequencies(&[
        modal("m", 0.2, &round(d), 4, true, ""),
        ancf("a", 0.2, &round(d), 8, ""),
    ]);
    let without = frequencies(&[
        modal("m", 0.2, &round(d), 4, false, ""),
        ancf("a", 0.2, &round(d), 8, ""),
    ]);
    let err = |f: &[f64]| (f[2] / eb[2] - 1.0).abs();
    assert!(
        err(&without) > err(&with),
        "without {:e} with {:e}",
        err(&without),
        err(&with)
    );
}
