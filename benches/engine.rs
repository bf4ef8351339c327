//! Engine kernels: one ANCF element (forces + tangent; planar and spatial), the planar modal
//! body of the hybrid Case 1 (residual; residual + matrices), one Newton iteration (assembly +
//! factorization + solve), one full step of Case 1 (planar and spatial) and the spatial cost per
//! element (all-ANCF rods of 8 to 512 elements, with a fit printed to stderr).
#![allow(missing_docs)] // criterion's macros generate undocumented items

use criterion::{criterion_group, criterion_main, Criterion};
use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::linalg::{LuMethod, INVERSE_MAX_DIM};
use hybeam::model::ancf::{straight, AncfProps, Vec8};
use hybeam::model::ancf3d::angle::Angle3;
use hybeam::model::ancf3d::Ancf3Props;
use hybeam::model::modal::{BodyOut, ModalBasis, ModalBody};
use hybeam::model::{Model, Planar, Space, Spatial};
use hybeam::scene::{Scene, StrainModel, TorsionElement};
use hybeam::simulator::Simulator;
use std::hint::black_box;
use std::time::Instant;

fn scene(name: &str) -> Scene {
    let path = format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    Scene::from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn case1() -> Scene {
    scene("case1.toml")
}

fn element(c: &mut Criterion) {
    let p = AncfProps {
        length: 0.025,
        rho_a: 0.0247,
        ea: 6.6e5,
        ei: 0.165,
        damping_time: 0.0,
        strain: StrainModel::Exact,
        reference: None,
        taper: None,
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

/// The planar nonlinear modal body of the hybrid Case 1 (scenes/case1.toml: 0.2 m of the
/// d = 2 mm steel rod, 4 clamped-free modes + 2 interface shapes) at a bent, moving state: its
/// residual (every Newton iteration) and residual + matrices (every refactorization).
fn modal_body(c: &mut Criterion) {
    let d: f64 = 0.002;
    let area = std::f64::consts::PI * d * d / 4.0;
    let ei = 2.1e11 * area * d * d / 16.0;
    let body = ModalBody::new(ModalBasis::new(4, true), 0.2, 7850.0 * area, ei, 0.0, 0.0);
    let dim = body.dim();
    let q: Vec<f64> = (0..dim).map(|i| 1e-3 * (1.0 + i as f64).sin()).collect();
    let v: Vec<f64> = (0..dim).map(|i| 1e-2 * (0.5 + i as f64).cos()).collect();
    let a: Vec<f64> = (0..dim).map(|i| 0.3 * (0.2 + i as f64).sin()).collect();
    let mut out = BodyOut::new(dim);
    let g = [0.0, -9.81];
    c.bench_function("modal body case 1 (4 + 2 shapes): residual", |b| {
        b.iter(|| body.eval(black_box(&q), &v, &a, g, false, &mut out))
    });
    c.bench_function(
        "modal body case 1 (4 + 2 shapes): residual + matrices",
        |b| b.iter(|| body.eval(black_box(&q), &v, &a, g, true, &mut out)),
    );
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
    let mut sim = Simulator::<Planar>::new(case1()).unwrap();
    let h = sim.scene().solver.max_step;
    c.bench_function("case 1 full step (h = max_step)", |b| {
        b.iter(|| {
            let t = sim.time() + h;
            sim.advance(t).unwrap();
        })
    });
}

/// One full step of spatial Case 1 (`scenes/case1_3d.toml`, the twin of the planar bench's
/// scene), h = max_step: the target is at most 3× the planar step.
fn spatial_step(c: &mut Criterion) {
    let mut sim = Simulator::<Spatial>::start_at(scene("case1_3d.toml"), 0.0).unwrap();
    let h = sim.scene().solver.max_step;
    c.bench_function("spatial case 1 full step (h = max_step)", |b| {
        b.iter(|| {
            let t = sim.time() + h;
            sim.advance(t).unwrap();
        })
    });
}

/// A clamped spatial all-ANCF steel rod (0.4 m, d = 2 mm, with torsion) of `n` elements.
fn spatial_rod(n: usize) -> Model<Spatial> {
    let text = format!(
        "name = \"rod\"\nspace = \"spatial\"\ngravity = [0.0, 0.0, -9.81]\nroot = \"clamped\"\n\
         [[segments]]\nname = \"a\"\nkind = \"ancf\"\nlength = 0.4\nsection = \"round\"\n\
         diameter = 0.002\nyoungs_modulus = 2.1e11\ndensity = 7850.0\nelements = {n}\n"
    );
    Model::<Spatial>::from_scene(&Scene::from_toml(&text).unwrap()).unwrap()
}

/// Cost per element of the spatial model: one Newton iteration (assemble with the matrix +
/// factorize + solve) of all-ANCF rods of 8 to 512 elements, sagging state (q from the
/// straight one bent by gravity-like offsets). Prints the least-squares fit t = a + b·n and the
/// log–log slope (1 = linear) of best-of-batches timings to stderr.
fn spatial_sweep(c: &mut Criterion) {
    let req = EvalRequest {
        sd: 1e-8,
        matrix: Some((1.1, 1e-4, 1e-8)),
        lambda_hessian: true,
    };
    let mut points = Vec::new();
    for n in [8usize, 32, 128, 512] {
        let mut model = spatial_rod(n);
        let (nc, m) = (model.coordinates(), model.constraints());
        let mut q = model.initial_coordinates().to_vec();
        for (k, x) in q.iter_mut().enumerate() {
            *x += 1e-4 * ((k as f64) * 0.37).sin();
        }
        let z = vec![0.0; nc];
        let lam = vec![0.0; m];
        let mut res = vec![0.0; nc + m];
        let mut iteration = || {
            model.eval(StateRef::new(&q, &z, &z, &lam), req, &mut res);
            model.factorize().unwrap();
            black_box(model.solve(&mut res));
        };
        c.bench_function(
            &format!("spatial all-ANCF {n} el.: assemble + factorize + solve"),
            |b| b.iter(&mut iteration),
        );
        let reps = (4096 / n).max(4);
        let best = (0..7)
            .map(|_| {
                let t0 = Instant::now();
                for _ in 0..reps {
                    iteration();
                }
                t0.elapsed().as_secs_f64() / reps as f64
            })
            .fold(f64::INFINITY, f64::min);
        points.push((n as f64, best));
    }
    let k = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
    let (sxx, sxy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 * p.0, b + p.0 * p.1));
    let slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    let icpt = (sy - slope * sx) / k;
    let ln: Vec<(f64, f64)> = points.iter().map(|p| (p.0.ln(), p.1.ln())).collect();
    let (lx, ly) = ln.iter().fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
    let (lxx, lxy) = ln
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 * p.0, b + p.0 * p.1));
    let expo = (k * lxy - lx * ly) / (k * lxx - lx * lx);
    eprintln!(
        "spatial sweep (best of 7): {}; fit t = {:.2} µs + {:.3} µs/element, log-log slope {expo:.3}",
        points
            .iter()
            .map(|(n, t)| format!("{n} el. {:.1} µs", t * 1e6))
            .collect::<Vec<_>>()
            .join(", "),
        icpt * 1e6,
        slope * 1e6
    );
}

/// Cost per step against the number of elements, for every family of the peer comparison
/// (issue 23: linear from 8 to 512): Case 1 as planar all-ANCF, hybrid (modal + n ANCF
/// elements), the 3D cable, the director element and the angle element, h = 1e-4 s, after
/// 0.05 s of the released fall.
/// Prints best-of-7 batches per step and the log–log slope between 8 and 512 elements to stderr.
fn step_sweep(_c: &mut Criterion) {
    fn per_step<S: Space>(mut sim: Simulator<S>, n: usize) -> f64 {
        let h = 1e-4;
        sim.advance(0.05).unwrap();
        let reps = (2048 / n).max(4);
        (0..7)
            .map(|_| {
                let t0 = Instant::now();
                for _ in 0..reps {
                    let t = sim.time() + h;
                    sim.advance(t).unwrap();
                }
                t0.elapsed().as_secs_f64() / reps as f64
            })
            .fold(f64::INFINITY, f64::min)
    }
    let sized = |file: &str, segment: usize, n: usize, torsion: Option<bool>| {
        let mut s = scene(file);
        s.segments[segment].elements = Some(n);
        s.solver.max_step = 1e-4;
        if let Some(t) = torsion {
            s.torsion = t;
        }
        s
    };
    let families: [(&str, &dyn Fn(usize) -> f64); 5] = [
        ("planar all-ANCF", &|n| {
            per_step(
                Simulator::<Planar>::new(sized("case1_ancf.toml", 0, n, None)).unwrap(),
                n,
            )
        }),
        ("planar hybrid", &|n| {
            per_step(
                Simulator::<Planar>::new(sized("case1.toml", 1, n, None)).unwrap(),
                n,
            )
        }),
        ("3D cable", &|n| {
            let s = sized("case1_3d_ancf.toml", 0, n, Some(false));
            per_step(Simulator::<Spatial>::start_at(s, 0.0).unwrap(), n)
        }),
        ("3D director element", &|n| {
            let s = sized("case1_3d_ancf.toml", 0, n, Some(true));
            per_step(Simulator::<Spatial>::start_at(s, 0.0).unwrap(), n)
        }),
        ("3D angle element", &|n| {
            let mut s = sized("case1_3d_ancf.toml", 0, n, Some(true));
            s.torsion_element = TorsionElement::Angle;
            per_step(Simulator::<Spatial>::start_at(s, 0.0).unwrap(), n)
        }),
    ];
    for (name, run) in families {
        let sizes = [8usize, 32, 128, 512];
        let t: Vec<f64> = sizes.iter().map(|&n| run(n)).collect();
        let slope = (t[3] / t[0]).ln() / (512.0f64 / 8.0).ln();
        eprintln!(
            "step sweep {name}: {}; log-log slope 8 -> 512: {slope:.3}",
            sizes
                .iter()
                .zip(&t)
                .map(|(n, t)| format!("{n} el. {:.1} µs", t * 1e6))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
}

/// The spatial ANCF element (with torsion, and the cable) on the planar bench's rod and state
/// (bent in the x–y plane, r_y = ẑ × r_x): forces only and forces + exact tangent (AD).
/// A spatial element of a 2 mm steel rod, 25 mm long.
fn bench_props(torsion: bool) -> Ancf3Props {
    Ancf3Props {
        length: 0.025,
        rho_a: 0.0247,
        rho_ip: 1.57e-8,
        ea: 6.6e5,
        ei_y: 0.165,
        ei_z: 0.165,
        gj: 0.127,
        damping_time: 0.0,
        director: torsion,
        reference: None,
        taper: None,
    }
}

fn spatial_element(c: &mut Criterion) {
    let e2 = straight([0.0, 0.0], 0.1, 0.025);
    for torsion in [true, false] {
        let p = bench_props(torsion);
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

/// The angle element (nodes [r, r_x, θ], `hybeam::model::ancf3d::angle`, not yet in scenes) on
/// the same bent state as [`spatial_element`]: forces, tangent, and the nodal twist inertia.
fn angle_element(c: &mut Criterion) {
    let e2 = straight([0.0, 0.0], 0.1, 0.025);
    let p = Angle3::new(bench_props(false), [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).unwrap();
    let tab = p.tables();
    let mut e = [0.0; 14];
    for node in 0..2 {
        let (sx, sy) = (e2[4 * node + 2], e2[4 * node + 3] + [0.01, -0.02][node]);
        e[7 * node..7 * node + 7].copy_from_slice(&[
            e2[4 * node],
            e2[4 * node + 1],
            0.0,
            sx,
            sy,
            0.0,
            0.1 * node as f64,
        ]);
    }
    let ed = [0.0; 14];
    c.bench_function("spatial ancf angle element: forces only", |b| {
        b.iter(|| black_box(p.internal_force(&tab, black_box(&e), &ed)))
    });
    c.bench_function("spatial ancf angle element: forces + tangent", |b| {
        b.iter(|| black_box(p.tangent(&tab, black_box(&e), &ed)))
    });
    let ea = [0.3; 14];
    c.bench_function("spatial ancf angle element: twist inertia", |b| {
        b.iter(|| black_box(p.twist_inertia(black_box(&e), &ed, &ea)))
    });
}

/// The Newton matrix's LU by both methods on the peer comparison's models (planar Case 1 rod of
/// 8 elements, spatial cable of 16, torsion rods of 16 and 512): factorize, and solve with a
/// held factorization (what a modified-Newton iteration pays).
fn lu(c: &mut Criterion) {
    let rod = |n: usize, torsion: bool| {
        let text = format!(
            "name = \"rod\"\nspace = \"spatial\"\ngravity = [0.0, 0.0, -9.81]\n\
             root = \"clamped\"\ntorsion = {torsion}\n[[segments]]\nname = \"a\"\n\
             kind = \"ancf\"\nlength = 0.4\nsection = \"round\"\ndiameter = 0.002\n\
             youngs_modulus = 2.1e11\ndensity = 7850.0\nelements = {n}\n"
        );
        Model::<Spatial>::from_scene(&Scene::from_toml(&text).unwrap()).unwrap()
    };
    let mut planar = scene("case1_ancf.toml");
    planar.segments[0].elements = Some(8);
    lu_of(
        c,
        "planar ANCF 8 el.",
        Model::<Planar>::from_scene(&planar).unwrap(),
    );
    for (n, torsion) in [(16, false), (16, true), (512, true)] {
        let kind = if torsion { "torsion" } else { "cable" };
        lu_of(c, &format!("spatial {kind} {n} el."), rod(n, torsion));
    }
}

fn lu_of<S: Space>(c: &mut Criterion, name: &str, mut model: Model<S>) {
    let req = EvalRequest {
        sd: 1e-8,
        matrix: Some((1.1, 1e-4, 1e-8)),
        lambda_hessian: true,
    };
    let mut methods = vec![LuMethod::Band, LuMethod::General];
    if model.coordinates() + model.constraints() <= INVERSE_MAX_DIM {
        methods.push(LuMethod::Inverse);
    }
    for method in methods {
        model.set_lu_method(method);
        let (n, m) = (model.coordinates(), model.constraints());
        let q = model.initial_coordinates().to_vec();
        let z = vec![0.0; n];
        let lam = vec![0.0; m];
        let mut res = vec![0.0; n + m];
        model.eval(StateRef::new(&q, &z, &z, &lam), req, &mut res);
        // factors for the solve even when a filter skips the factorization's benchmark
        model.factorize().unwrap();
        c.bench_function(&format!("lu {name} {method:?}: factorize"), |b| {
            b.iter(|| model.factorize().unwrap())
        });
        // a right-hand side with no zero entry: the residual at rest has zeros (the components
        // across gravity) that the band solve skips, which a step's residual does not have
        let rhs: Vec<f64> = (0..res.len())
            .map(|i| 1.0 + ((i * 7919) % 101) as f64 * 1e-2)
            .collect();
        c.bench_function(&format!("lu {name} {method:?}: solve"), |b| {
            b.iter(|| {
                res.copy_from_slice(&rhs);
                black_box(model.solve(&mut res))
            })
        });
    }
}

criterion_group!(
    benches,
    element,
    spatial_element,
    angle_element,
    modal_body,
    newton,
    step,
    spatial_step,
    lu,
    spatial_sweep,
    step_sweep
);
criterion_main!(benches);
