//! Engine kernels: one ANCF element (forces + tangent), one Newton iteration (assembly +
//! factorization + solve) and one full step of Case 1.
#![allow(missing_docs)] // criterion's macros generate undocumented items

use criterion::{criterion_group, criterion_main, Criterion};
use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::model::ancf::{straight, AncfProps, Vec8};
use hybeam::model::{Model, Planar};
use hybeam::scene::{Scene, StrainModel};
use hybeam::simulator::Simulator;
use std::hint::black_box;

fn case1() -> Scene {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/case1.toml")).unwrap();
    Scene::from_toml(&text).unwrap()
}

fn element(c: &mut Criterion) {
    let p = AncfProps {
        length: 0.025,
        rho_a: 0.0247,
        ea: 6.6e5,
        ei: 0.165,
        damping_time: 0.0,
        strain: StrainModel::Exact,
    };
    let mut e = straight([0.0, 0.0], 0.1, p.length);
    e[3] += 0.01;
    e[7] -= 0.02;
    let ed = Vec8::zeros();
    c.bench_function("ancf element: forces + tangent", |b| {
        b.iter(|| black_box(p.elastic(black_box(&e), &ed, true)))
    });
    c.bench_function("ancf element: forces only", |b| {
        b.iter(|| black_box(p.elastic(black_box(&e), &ed, false)))
    });
}

fn newton(c: &mut Criterion) {
    let mut model = Model::<Planar>::from_scene(&case1()).unwrap();
    let n = model.coordinates();
    let m = model.constraints();
    let q = model.initial_coordinates().to_vec();
    let z = vec![0.0; n];
    let lam = vec![0.0; m];
    let mut res = vec![0.0; n + m];
    let req = EvalRequest {
        sd: 1e-8,
        matrix: Some((1.1, 1e-4, 1e-8)),
        lambda_hessian: true,
    };
    c.bench_function(
        "case 1 newton iteration: assemble + factorize + solve",
        |b| {
            b.iter(|| {
                model.eval(StateRef::new(&q, &z, &z, &lam), req, &mut res);
                model.factorize().unwrap();
                black_box(model.solve(&mut res));
            })
        },
    );
    let req = EvalRequest {
        sd: 1e-8,
        matrix: None,
        lambda_hessian: true,
    };
    c.bench_function("case 1 modified newton iteration: residual + solve", |b| {
        b.iter(|| {
            model.eval(StateRef::new(&q, &z, &z, &lam), req, &mut res);
            black_box(model.solve(&mut res));
        })
    });
}

fn step(c: &mut Criterion) {
    let mut sim = Simulator::new(case1()).unwrap();
    let h = sim.scene().solver.max_step;
    c.bench_function("case 1 full step (h = max_step)", |b| {
        b.iter(|| {
            let t = sim.time() + h;
            sim.advance(t).unwrap();
        })
    });
}

criterion_group!(benches, element, newton, step);
criterion_main!(benches);
