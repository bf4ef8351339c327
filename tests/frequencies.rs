//! Bending frequencies of the clamped rod from the linearized model (M, K, Φ_q at the straight
//! state, constrained generalized eigenproblem) against Euler–Bernoulli closed form
//! ω_n = λ_n² √(EI/(ρA L⁴)), λ_n roots of 1 + cos λ cosh λ = 0.

mod common;
use common::*;
use hybeam::model::{Model, Planar};

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

/// Lowest frequencies [Hz] of the model linearized at its straight initial state: the lowest
/// three are transverse bending modes for these slender rods.
fn frequencies(segs: &[String]) -> Vec<f64> {
    let s = scene("gravity = [0.0, 0.0]", segs);
    let mut model = Model::<Planar>::from_scene(&s).unwrap();
    linearized_modes(&mut model)
        .iter()
        .take(3)
        .map(|m| m.0)
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
