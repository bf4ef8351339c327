//! Engine kernels: one ANCF element (forces + tangent; planar and spatial), one Newton iteration (assembly +
//! factorization + solve) and one full step of Case 1.
#![allow(missing_docs)] // criterion's macros generate undocumented items

use criterion::{criterion_group, criterion_main, Criterion};
use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::model::ancf::{straight, AncfProps, Vec8};
use hybeam::model::ancf3d::Ancf3Props;
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

/// The spatial ANCF element (with torsion, and the cable) on the planar bench's rod and state
/// (bent in the x–y plane, r_y = ẑ × r_x): forces only and forces + exact tangent (AD).
fn spatial_element(c: &mut Criterion) {
    let e2 = straight([0.0, 0.0], 0.1, 0.025);
    for torsion in [true, false] {
        let p = Ancf3Props {
            length: 0.025,
            rho_a: 0.0247,
            rho_ip: 1.57e-8,
            ea: 6.6e5,
            ei_y: 0.165,
            ei_z: 0.165,
            gj: 0.127,
            damping_time: 0.0,
            torsion,
        };
        let tab = p.tables();
        let mut e = Vec::new();
        for node in 0..2 {
            let (sx, sy) = (e2[4 * node + 2], e2[4 * node + 3] + [0.01, -0.02][node]);
            e.extend([e2[4 * node], e2[4 * node + 1], 0.0, sx, sy, 0.0]);
            if torsion {
                let n = (sx * sx + sy * sy).sqrt();
                e.extend([-sy / n, sx / n, 0.0]);
            }
        }
        let name = if torsion {
            "spatial ancf element"
        } else {
            "spatial ancf cable"
        };
        if torsion {
            let e: [f64; 18] = e.try_into().unwrap();
            let ed = [0.0; 18];
            c.bench_function(&format!("{name}: forces only"), |b| {
                b.iter(|| black_box(p.internal_force(&tab, black_box(&e), &ed)))
            });
            c.bench_function(&format!("{name}: forces + tangent"), |b| {
                b.iter(|| black_box(p.tangent(&tab, black_box(&e), &ed)))
            });
        } else {
            let e: [f64; 12] = e.try_into().unwrap();
            let ed = [0.0; 12];
            c.bench_function(&format!("{name}: forces only"), |b| {
                b.iter(|| black_box(p.internal_force(&tab, black_box(&e), &ed)))
            });
            c.bench_function(&format!("{name}: forces + tangent"), |b| {
                b.iter(|| black_box(p.tangent(&tab, black_box(&e), &ed)))
            });
        }
    }
}

criterion_group!(benches, element, spatial_element, newton, step);
criterion_main!(benches);
