//! What the views cost a run: Case 1 (`scenes/case1.toml`) for 0.2 s with 1 ms outputs, plain
//! and with the shape sampled (8 intervals per element), written as a ParaView series, and
//! recorded for the animation page, per output.
//!
//! `cargo bench -p hybeam-view --bench views`
#![allow(missing_docs)] // criterion's macros generate undocumented items

use criterion::{criterion_group, criterion_main, Criterion};
use hybeam::scene::Scene;
use hybeam::simulator::AnySimulator;
use hybeam_view::{Look, Recorder, Series};
use std::path::PathBuf;

fn case1() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/case1.toml");
    Scene::from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Runs 200 outputs of 1 ms, calling `view` after each.
fn run(scene: &Scene, mut view: impl FnMut(&AnySimulator)) {
    let mut sim = AnySimulator::new(scene.clone()).unwrap();
    view(&sim);
    for k in 1..=200 {
        sim.advance(k as f64 * 1e-3).unwrap();
        view(&sim);
    }
}

fn views(c: &mut Criterion) {
    let scene = case1();
    let radii = Look::of(&scene);
    let dir = std::env::temp_dir().join(format!("hybeam-bench-views-{}", std::process::id()));
    let mut g = c.benchmark_group("case1_0.2s_1ms_outputs");
    g.sample_size(20);
    g.bench_function("plain", |b| b.iter(|| run(&scene, |_| {})));
    g.bench_function("shape", |b| {
        b.iter(|| run(&scene, |s| drop(std::hint::black_box(s.shape(8)))))
    });
    g.bench_function("shape+vtk", |b| {
        b.iter(|| {
            let mut series = Series::create(&dir, "beam", radii.clone()).unwrap();
            run(&scene, |s| {
                series.write(s.time(), &s.shape(8)).unwrap();
            });
            series.finish().unwrap();
        })
    });
    g.bench_function("shape+page", |b| {
        b.iter(|| {
            let mut rec = Recorder::new("case1", &scene.gravity, radii.clone(), vec!["y".into()]);
            run(&scene, |s| {
                rec.push(s.time(), &s.shape(8), &[s.outputs().tip_position()[1]])
            });
            std::hint::black_box(rec.page());
        })
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, views);
criterion_main!(benches);
