//! Work-precision: error against converged references vs wall time, for Cases 1–3, the soft
//! rod and the spatial Case 1 (beside the planar one); cost per step vs element count; static
//! errors against the elastica.

use super::common::{self, e3, md_table, scene, timed, tip_errors, Progress};
use super::plot::{self, Axes, Extras, Series};
use super::statics;
use hybeam::scene::{Scene, SegmentKind, SpaceKind};
use std::fmt::Write as _;

/// Options of the accuracy report.
pub struct Opts {
    /// Smaller sweeps, one repetition.
    pub quick: bool,
    /// Recompute cached references.
    pub fresh: bool,
}

/// Tip error goal [m].
const GOAL: f64 = 1e-5;
/// Simulated time [s] and sampling step [s] of every dynamic run.
const T_END: f64 = 2.0;
const OUT: f64 = 1e-3;
/// Reference step [s] and Newton tolerance.
const H_REF: f64 = 1e-5;

struct Spec {
    key: &'static str,
    title: &'static str,
    /// File of the scene whose settings are swept.
    main: &'static str,
    /// (formulation, file) of the twins of the same physical beam.
    variants: &'static [(&'static str, &'static str)],
    /// The all-ANCF twin: the physical reference is it, refined.
    ancf: &'static str,
    /// Element refinement factor of the reference.
    refine: usize,
    /// Element counts of the `combined` grids, as factors of the scene's own count.
    grid: &'static [f64],
    /// (formulation, file) of the twins also swept in step with `solver.method = "esdirk4"`.
    esdirk: &'static [(&'static str, &'static str)],
}

const SPECS: &[Spec] = &[
    Spec {
        key: "case1",
        title: "Case 1 (d = 2 mm steel, 40 cm, undamped)",
        main: "case1",
        variants: &[("all-ANCF", "case1_ancf"), ("all-modal", "case1_modal")],
        ancf: "case1_ancf",
        refine: 4,
        grid: &[0.25, 0.5, 1.0],
        esdirk: &[
            ("hybrid", "case1"),
            ("all-ANCF", "case1_ancf"),
            ("all-modal", "case1_modal"),
        ],
    },
    Spec {
        key: "case2",
        title: "Case 2 (Case 1 with Kelvin-Voigt damping)",
        main: "case2",
        variants: &[("all-ANCF", "case2_ancf"), ("all-modal", "case2_modal")],
        ancf: "case2_ancf",
        refine: 4,
        grid: &[0.25, 0.5, 1.0],
        esdirk: &[
            ("hybrid", "case2"),
            ("all-ANCF", "case2_ancf"),
            ("all-modal", "case2_modal"),
        ],
    },
    Spec {
        key: "case3",
        title: "Case 3 (stepped 2 mm / 1 mm rod, damped)",
        main: "case3",
        variants: &[("all-ANCF", "case3_ancf"), ("all-modal", "case3_modal")],
        ancf: "case3_ancf",
        refine: 4,
        grid: &[0.25, 0.5, 1.0],
        esdirk: &[
            ("hybrid", "case3"),
            ("all-ANCF", "case3_ancf"),
            ("all-modal", "case3_modal"),
        ],
    },
    Spec {
        key: "case1_3d",
        title: "Spatial Case 1 (case1_3d: the Case 1 rod in space, z up, undamped)",
        main: "case1_3d",
        variants: &[
            ("all-ANCF", "case1_3d_ancf"),
            ("all-modal", "case1_3d_modal"),
        ],
        ancf: "case1_3d_ancf",
        refine: 4,
        grid: &[0.25, 0.5, 1.0],
        esdirk: &[
            ("hybrid", "case1_3d"),
            ("all-ANCF", "case1_3d_ancf"),
            ("all-modal", "case1_3d_modal"),
        ],
    },
    Spec {
        key: "soft_rod",
        title: "Soft rod (gamma = 17.3, all-ANCF, undamped)",
        main: "soft_rod",
        variants: &[
            ("hybrid", "soft_rod_hybrid"),
            ("all-modal", "soft_rod_modal"),
        ],
        ancf: "soft_rod",
        refine: 8,
        grid: &[1.0, 2.0, 4.0],
        esdirk: &[
            ("hybrid", "soft_rod_hybrid"),
            ("all-ANCF", "soft_rod"),
            ("all-modal", "soft_rod_modal"),
        ],
    },
];

/// Overrides that set the total element count `n` of the ANCF segments of `s` (spread by
/// length, at least one per segment).
fn elements_sets(s: &Scene, n: usize) -> Vec<String> {
    let total: f64 = s
        .segments
        .iter()
        .filter(|g| g.kind == SegmentKind::Ancf)
        .map(|g| g.length)
        .sum();
    s.segments
        .iter()
        .enumerate()
        .filter(|(_, g)| g.kind == SegmentKind::Ancf)
        .map(|(i, g)| {
            let k = ((n as f64 * g.length / total).round() as usize).max(1);
            format!("segments.{i}.elements={k}")
        })
        .collect()
}

/// Overrides multiplying every ANCF segment's elements by `f`.
fn refine_sets(s: &Scene, f: usize) -> Vec<String> {
    s.segments
        .iter()
        .enumerate()
        .filter(|(_, g)| g.kind == SegmentKind::Ancf)
        .map(|(i, g)| format!("segments.{i}.elements={}", g.elements.unwrap_or(1) * f))
        .collect()
}

/// Overrides setting the modes of every modal segment.
fn modes_sets(s: &Scene, n: usize, interface: Option<bool>) -> Vec<String> {
    let mut v = Vec::new();
    for (i, g) in s.segments.iter().enumerate() {
        if g.kind == SegmentKind::Modal {
            v.push(format!("segments.{i}.modes={n}"));
            if let Some(b) = interface {
                v.push(format!("segments.{i}.interface_modes={b}"));
            }
        }
    }
    v
}

fn ancf_elements(s: &Scene) -> usize {
    s.segments.iter().filter_map(|g| g.elements).sum()
}

fn has_modal(s: &Scene) -> bool {
    s.segments.iter().any(|g| g.kind == SegmentKind::Modal)
}

/// One planned run.
struct Point {
    family: String,
    formulation: String,
    file: &'static str,
    param: String,
    sets: Vec<String>,
}

/// One measured run.
struct Row {
    p: Point,
    wall: f64,
    steps: u64,
    iterations: u64,
    factorizations: u64,
    rejected: u64,
    err_max: f64,
    err_end: f64,
    err_max_y: f64,
    own_max: f64,
    status: String,
}

fn h_of(sets: &[String]) -> f64 {
    sets.iter()
        .rev()
        .find_map(|s| s.strip_prefix("solver.max_step="))
        .and_then(|v| v.parse().ok())
        .unwrap_or(1e-4)
}

fn plan(spec: &Spec, main: &Scene, quick: bool) -> Result<Vec<Point>, String> {
    let steps: &[f64] = if quick {
        &[2e-3, 1e-3, 2e-4, 5e-5]
    } else {
        &[2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5]
    };
    let d = ancf_elements(main);
    let factors: &[f64] = if quick {
        &[0.25, 0.5, 1.0, 2.0, 4.0]
    } else {
        &[0.125, 0.25, 0.5, 1.0, 2.0, 4.0]
    };
    let scaled = |d: usize, f: f64| ((d as f64 * f).round() as usize).max(1);
    let mut els: Vec<usize> = factors.iter().map(|&f| scaled(d, f)).collect();
    els.dedup();
    let modes: &[usize] = if quick {
        &[1, 2, 4, 8]
    } else {
        &[1, 2, 3, 4, 6, 8, 12]
    };
    let rhos: &[f64] = if quick {
        &[0.5, 0.8, 0.9, 0.99]
    } else {
        &[0.0, 0.3, 0.6, 0.8, 0.9, 0.95, 0.99]
    };
    let main_form = if has_modal(main) {
        "hybrid"
    } else {
        "all-ANCF"
    };
    let mut v = Vec::new();
    let mut push =
        |family: &str, form: &str, file: &'static str, param: String, sets: Vec<String>| {
            v.push(Point {
                family: family.into(),
                formulation: form.into(),
                file,
                param,
                sets,
            })
        };
    for &h in steps {
        push(
            "step",
            main_form,
            spec.main,
            format!("h={h:e}"),
            vec![format!("solver.max_step={h:e}")],
        );
    }
    for &n in &els {
        push(
            "elements",
            main_form,
            spec.main,
            format!("elements={n}"),
            elements_sets(main, n),
        );
    }
    if has_modal(main) {
        for &n in modes {
            push(
                "modes+interface",
                main_form,
                spec.main,
                format!("modes={n}"),
                modes_sets(main, n, Some(true)),
            );
        }
        for &n in modes {
            push(
                "modes (no interface)",
                main_form,
                spec.main,
                format!("modes={n}"),
                modes_sets(main, n, Some(false)),
            );
        }
    }
    for &r in rhos {
        push(
            "rho_inf",
            main_form,
            spec.main,
            format!("rho_inf={r}"),
            vec![format!("solver.rho_inf={r}")],
        );
    }
    for (form, file) in spec.variants {
        for &h in steps {
            push(
                &format!("{form} step"),
                form,
                file,
                format!("h={h:e}"),
                vec![format!("solver.max_step={h:e}")],
            );
        }
    }
    for (form, file) in spec.esdirk {
        for &h in steps {
            push(
                &format!("{form} ESDIRK4 step"),
                form,
                file,
                format!("h={h:e} esdirk4"),
                vec![
                    format!("solver.max_step={h:e}"),
                    "solver.method=esdirk4".into(),
                ],
            );
        }
    }
    // small grids of combined settings on the main scene and on its all-ANCF twin
    let (gh, gm): (&[f64], &[usize]) = if quick {
        (&[2e-3, 1e-3, 5e-4, 2e-4], &[2, 4])
    } else {
        (&[2e-3, 1e-3, 5e-4, 2e-4, 1e-4], &[2, 4])
    };
    let gm: &[usize] = if has_modal(main) { gm } else { &[0] };
    if spec.ancf != spec.main {
        let twin = scene(spec.ancf, &[])?;
        let dt = ancf_elements(&twin);
        for &h in gh {
            for &f in spec.grid {
                let e = scaled(dt, f);
                let mut sets = vec![format!("solver.max_step={h:e}")];
                sets.extend(elements_sets(&twin, e));
                push(
                    "all-ANCF combined",
                    "all-ANCF",
                    spec.ancf,
                    format!("h={h:e} elements={e}"),
                    sets,
                );
            }
        }
    }
    for &h in gh {
        for &f in spec.grid {
            let e = scaled(d, f);
            for &m in gm {
                let mut sets = vec![format!("solver.max_step={h:e}")];
                sets.extend(elements_sets(main, e));
                let mut param = format!("h={h:e} elements={e}");
                if m > 0 {
                    sets.extend(modes_sets(main, m, Some(true)));
                    let _ = write!(param, " modes={m}+interface");
                }
                push("combined", main_form, spec.main, param, sets);
            }
        }
    }
    Ok(v)
}

/// Reference tip history of a scene file refined: elements × `refine`, 12 modes, step
/// `h`, tolerance 1e-12.
fn reference(file: &str, refine: usize, h: f64, fresh: bool) -> Result<Vec<[f64; 3]>, String> {
    let base = scene(file, &[])?;
    let mut sets = refine_sets(&base, refine);
    if has_modal(&base) {
        sets.extend(modes_sets(&base, 12, None));
    }
    sets.push(format!("solver.max_step={h:e}"));
    sets.push("solver.tolerance=1e-12".into());
    let s = scene(file, &sets)?;
    common::cached(&format!("{file}-x{refine}-h{h:e}"), &s, T_END, OUT, fresh)
}

struct SceneResult {
    rows: Vec<Row>,
    /// The physical reference's tip history.
    phys: Vec<[f64; 3]>,
    ref_check: f64,
    /// Model error floor of each formulation, or why its converged model could not be run.
    floors: Vec<(String, Result<f64, String>)>,
}

/// Index of the vertical axis of a scene: y in the plane, z in the spatial scenes (z up).
fn up(s: &Scene) -> usize {
    match s.space {
        SpaceKind::Planar => 1,
        SpaceKind::Spatial => 2,
    }
}

fn measure(spec: &Spec, opts: &Opts, prog: &mut Progress) -> Result<SceneResult, String> {
    let main = scene(spec.main, &[])?;
    let up = up(&main);
    let phys = reference(spec.ancf, spec.refine, H_REF, opts.fresh)?;
    // reference check: half the refinement, twice the step
    let check = reference(spec.ancf, spec.refine / 2, 2.0 * H_REF, opts.fresh)?;
    let ref_check = tip_errors(&check, &phys, 1, up).0;
    // own-formulation references (converged model of the same formulation)
    let mut own = std::collections::HashMap::new();
    own.insert(spec.ancf, phys.clone());
    let mut floors = Vec::new();
    for file in std::iter::once(spec.main).chain(spec.variants.iter().map(|v| v.1)) {
        if own.contains_key(file) {
            continue;
        }
        match reference(file, spec.refine, H_REF, opts.fresh) {
            Ok(r) => {
                floors.push((file.to_string(), Ok(tip_errors(&r, &phys, 1, up).0)));
                own.insert(file, r);
            }
            // e.g. a modal segment beyond its validity: the engine refuses the run
            Err(e) => floors.push((file.to_string(), Err(e))),
        }
    }
    let reps = if opts.quick { 1 } else { 3 };
    let mut rows = Vec::new();
    for p in plan(spec, &main, opts.quick)? {
        prog.item(&format!("{} {} {}", spec.key, p.family, p.param));
        let h = h_of(&p.sets);
        let chunk = (h / OUT).round().max(1.0) * OUT;
        let stride = (chunk / OUT).round() as usize;
        let s = match scene(p.file, &p.sets) {
            Ok(s) => s,
            Err(e) => {
                rows.push(failed(p, e));
                continue;
            }
        };
        let r = timed(&s, T_END, chunk, reps);
        if let Some(e) = r.err {
            rows.push(failed(p, e.to_string()));
            continue;
        }
        let (err_max, err_end, err_max_y) = tip_errors(&r.tip, &phys, stride, up);
        let own_max = own
            .get(p.file)
            .map_or(f64::NAN, |o| tip_errors(&r.tip, o, stride, up).0);
        rows.push(Row {
            p,
            wall: r.wall,
            steps: r.counters.steps,
            iterations: r.counters.iterations,
            factorizations: r.counters.factorizations,
            rejected: r.counters.rejected,
            err_max,
            err_end,
            err_max_y,
            own_max,
            status: "ok".into(),
        });
    }
    Ok(SceneResult {
        rows,
        phys,
        ref_check,
        floors,
    })
}

fn failed(p: Point, e: String) -> Row {
    Row {
        p,
        wall: f64::NAN,
        steps: 0,
        iterations: 0,
        factorizations: 0,
        rejected: 0,
        err_max: f64::NAN,
        err_end: f64::NAN,
        err_max_y: f64::NAN,
        own_max: f64::NAN,
        status: format!("refused: {}", e.replace([',', '\n', '|'], ";")),
    }
}

fn command(row: &Row) -> String {
    let mut c = format!("hybeam run scenes/{}.toml", row.p.file);
    for s in &row.p.sets {
        let _ = write!(c, " --set {s}");
    }
    c
}

fn table_row(r: &Row) -> Vec<String> {
    vec![
        r.p.family.clone(),
        r.p.formulation.clone(),
        format!("`{}`", r.p.param),
        format!("{:.4}", r.wall),
        r.steps.to_string(),
        r.iterations.to_string(),
        r.factorizations.to_string(),
        e3(r.err_max),
        e3(r.err_end),
        e3(r.err_max_y),
        e3(r.own_max),
        r.status.clone(),
    ]
}

const TABLE_HEAD: &[&str] = &[
    "family",
    "formulation",
    "setting",
    "wall [s]",
    "steps",
    "Newton it.",
    "factor.",
    "max tip err [m]",
    "end err [m]",
    "max vertical err [m]",
    "max err vs own-formulation ref [m]",
    "status",
];

fn cheapest(rows: &[Row], err: impl Fn(&Row) -> f64) -> Option<&Row> {
    rows.iter()
        .filter(|r| err(r) <= GOAL)
        .min_by(|a, b| a.wall.total_cmp(&b.wall))
}

fn describe(r: Option<&Row>) -> String {
    match r {
        Some(r) => format!(
            "{} `{}` ({}): wall {:.4} s, max tip error {} m vs physical reference, {} m vs own-formulation reference (`{}`)",
            r.p.formulation,
            r.p.param,
            r.p.family,
            r.wall,
            e3(r.err_max),
            e3(r.own_max),
            command(r)
        ),
        None => "none of the measured settings".into(),
    }
}

/// Runs the accuracy report and writes `docs/accuracy.md`.
/// What the work-precision figures show of a run.
struct Run {
    family: String,
    wall: f64,
    err: f64,
    own: f64,
}

/// The two work-precision figures of a scene (`accuracy_<key>.svg`: error against the physical
/// reference; `accuracy_<key>_own.svg`: against the converged model of each run's own
/// formulation): a marker for every run, a line through each family's Pareto front and, on the
/// first, the Pareto front over all runs circled.
fn plots(spec: &Spec, runs: &[Run]) -> Result<(), String> {
    let mut families: Vec<&str> = Vec::new();
    for r in runs {
        if !families.contains(&r.family.as_str()) {
            families.push(&r.family);
        }
    }
    let pts: Vec<(f64, f64)> = runs.iter().map(|r| (r.wall, r.err)).collect();
    let front = plot::pareto(&pts);
    for (suffix, own) in [("", false), ("_own", true)] {
        let series: Vec<Series> = families
            .iter()
            .map(|&f| {
                let p = runs
                    .iter()
                    .filter(|r| r.family == f)
                    .map(|r| (r.wall, if own { r.own } else { r.err }))
                    .collect();
                Series::cloud(f, p)
            })
            .collect();
        let extras = Extras {
            pareto: if own {
                Vec::new()
            } else {
                front.iter().map(|&i| pts[i]).collect()
            },
            hlines: vec![(GOAL, "1e-5 m".into())],
            vlines: if spec.key == "case1" {
                vec![(0.03, "0.03 s".into())]
            } else {
                Vec::new()
            },
        };
        let title = if own {
            format!(
                "{}: error vs converged model of the same formulation",
                spec.title
            )
        } else {
            format!("{}: max tip error vs wall time (2 s simulated)", spec.title)
        };
        plot::plot(
            &format!("accuracy_{}{suffix}.svg", spec.key),
            &Axes {
                title: &title,
                x: "wall time [s]",
                y: "max tip position error [m]",
                log_x: true,
                log_y: true,
            },
            &series,
            &extras,
        )?;
    }
    Ok(())
}

/// Redraws the work-precision figures from the CSV files of the last `accuracy` run
/// (`docs/report/accuracy_<key>.csv`), without running anything.
pub fn replot() -> Result<(), String> {
    for spec in SPECS {
        let path = common::out_dir().join(format!("accuracy_{}.csv", spec.key));
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let mut lines = text.lines();
        let head: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
        let col = |name: &str| {
            head.iter()
                .position(|h| *h == name)
                .ok_or_else(|| format!("{}: no column {name}", path.display()))
        };
        let (family, wall, err, own) = (
            col("family")?,
            col("wall_s")?,
            col("max_tip_err_m")?,
            col("max_tip_err_own_ref_m")?,
        );
        let num = |v: &str| v.parse::<f64>().unwrap_or(f64::NAN);
        let runs: Vec<Run> = lines
            .map(|l| l.split(',').collect::<Vec<_>>())
            .filter(|c| c.len() == head.len())
            .map(|c| Run {
                family: c[family].to_string(),
                wall: num(c[wall]),
                err: num(c[err]),
                own: num(c[own]),
            })
            .collect();
        plots(spec, &runs)?;
        eprintln!("  {}: {} runs redrawn", path.display(), runs.len());
    }
    Ok(())
}

pub fn run(opts: &Opts) -> Result<(), String> {
    let mode = if opts.quick { "--quick" } else { "--full" };
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Accuracy: work-precision of hybeam\n\nGenerated by `cargo run --release -p hybeam-report -- accuracy {mode}` \
         (numbers below are what that run measured; `--full` uses denser sweeps and the median of 3 runs).\n\n\
         Machine: {}.\n",
        common::machine()
    );
    md.push_str(METHOD);
    let mut summary = String::new();
    // count for the progress line
    let mut total = 0;
    for spec in SPECS {
        let main = scene(spec.main, &[])?;
        total += plan(spec, &main, opts.quick)?.len();
    }
    let mut prog = Progress::new("accuracy", total);
    let mut case1_target = String::new();
    let (mut planar1, mut spatial1) = (None, None);
    for spec in SPECS {
        let res = measure(spec, opts, &mut prog)?;
        let rows = &res.rows;
        // CSV
        let csv: Vec<Vec<String>> = rows
            .iter()
            .map(|r| {
                vec![
                    spec.key.into(),
                    r.p.family.clone(),
                    r.p.formulation.clone(),
                    r.p.param.clone(),
                    r.p.file.into(),
                    r.p.sets.join(";"),
                    format!("{:.6}", r.wall),
                    r.steps.to_string(),
                    r.iterations.to_string(),
                    r.factorizations.to_string(),
                    r.rejected.to_string(),
                    format!("{:e}", r.err_max),
                    format!("{:e}", r.err_end),
                    format!("{:e}", r.err_max_y),
                    format!("{:e}", r.own_max),
                    r.status.clone(),
                ]
            })
            .collect();
        common::write_csv(
            &format!("accuracy_{}.csv", spec.key),
            &[
                "scene",
                "family",
                "formulation",
                "setting",
                "scene_file",
                "overrides",
                "wall_s",
                "steps",
                "newton_iterations",
                "factorizations",
                "rejected",
                "max_tip_err_m",
                "end_tip_err_m",
                "max_tip_vertical_err_m",
                "max_tip_err_own_ref_m",
                "status",
            ],
            &csv,
        )?;
        let cloud: Vec<Run> = rows
            .iter()
            .map(|r| Run {
                family: r.p.family.clone(),
                wall: r.wall,
                err: r.err_max,
                own: r.own_max,
            })
            .collect();
        plots(spec, &cloud)?;
        let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r.wall, r.err_max)).collect();
        let front = plot::pareto(&pts);
        // page section
        let _ = writeln!(md, "## {}\n", spec.title);
        let _ = writeln!(
            md,
            "Reference: `scenes/{}.toml` with {}× the elements, step {H_REF:e} s, tolerance 1e-12 \
             (cached). Its own error, estimated as the distance to the run with half the refinement \
             and twice the step: **{} m**.",
            spec.ancf,
            spec.refine,
            e3(res.ref_check)
        );
        for (file, floor) in &res.floors {
            let _ = match floor {
                Ok(f) => writeln!(
                    md,
                    "Model error floor of `{file}` (its own converged model: 12 modes, {}× elements, \
                     step {H_REF:e} s) against this reference: **{} m**.",
                    spec.refine,
                    e3(*f)
                ),
                Err(e) => writeln!(md, "Converged model of `{file}` not run: {e}."),
            };
        }
        let _ = writeln!(
            md,
            "\n![{k}](report/accuracy_{k}.svg)\n\nError against the converged model of each run's own \
             formulation (discretization error alone):\n\n![{k} own](report/accuracy_{k}_own.svg)\n",
            k = spec.key
        );
        let pareto_rows: Vec<Vec<String>> = front.iter().map(|&i| table_row(&rows[i])).collect();
        let _ = writeln!(
            md,
            "Pareto front (error vs wall time, all runs of this scene):\n"
        );
        md.push_str(&md_table(TABLE_HEAD, &pareto_rows));
        let best = cheapest(rows, |r| r.err_max);
        let best_own = cheapest(rows, |r| r.own_max);
        let _ = writeln!(
            md,
            "\n**Recommended (cheapest measured setting with max tip error ≤ 1e-5 m against the \
             physical reference):** {}.\n\nCheapest with error ≤ 1e-5 m against its own \
             formulation's converged model: {}.\n",
            describe(best),
            describe(best_own)
        );
        let _ = writeln!(
            summary,
            "| {} | {} | {} |",
            spec.key,
            describe(best),
            describe(best_own)
        );
        if spec.key == "case1" {
            let hybrid: Vec<&Row> = rows
                .iter()
                .filter(|r| r.p.formulation == "hybrid")
                .collect();
            let best_h = hybrid
                .iter()
                .filter(|r| r.own_max <= GOAL)
                .min_by(|a, b| a.wall.total_cmp(&b.wall))
                .copied();
            let best_hyb_err = hybrid
                .iter()
                .map(|r| r.err_max)
                .filter(|e| e.is_finite())
                .fold(f64::INFINITY, f64::min);
            let under = rows
                .iter()
                .filter(|r| r.wall < 0.03)
                .min_by(|a, b| a.err_max.total_cmp(&b.err_max));
            let yes = best.is_some_and(|r| r.wall < 0.03);
            let _ = write!(
                case1_target,
                "**Project target (Case 1 tip error ≤ 1e-5 m in < 0.03 s wall for 2 s simulated): {}.** \
                 Cheapest measured run reaching 1e-5 m: {}. Smallest error of any hybrid run: {} m. \
                 Best error among runs under 0.03 s: {}. Cheapest hybrid run within 1e-5 m of the \
                 hybrid's own converged model (discretization error only): {}.",
                if yes { "MET" } else { "NOT MET" },
                describe(best),
                e3(best_hyb_err),
                under
                    .map(|r| format!(
                        "{} m ({} `{}`, {:.4} s)",
                        e3(r.err_max),
                        r.p.formulation,
                        r.p.param,
                        r.wall
                    ))
                    .unwrap_or_else(|| "no run was that fast".into()),
                describe(best_h)
            );
        }
        let all_rows: Vec<Vec<String>> = rows.iter().map(table_row).collect();
        let _ = writeln!(
            md,
            "<details><summary>All {} runs of {} (CSV: <code>docs/report/accuracy_{}.csv</code>, \
             with the exact overrides)</summary>\n\n{}\n</details>\n",
            rows.len(),
            spec.key,
            spec.key,
            md_table(TABLE_HEAD, &all_rows)
        );
        match spec.key {
            "case1" => planar1 = Some(res),
            "case1_3d" => spatial1 = Some(res),
            _ => {}
        }
    }
    prog.finish();
    if let (Some(p), Some(s)) = (&planar1, &spatial1) {
        md.push_str(&side_by_side(p, s));
    }
    let head = format!(
        "## Summary\n\n{case1_target}\n\n| scene | cheapest ≤ 1e-5 m vs physical reference | \
         cheapest ≤ 1e-5 m vs own-formulation converged model |\n|---|---|---|\n{summary}\n"
    );
    // cost per step and statics
    let cost = cost_per_step(opts)?;
    let stat = statics::run(opts.quick)?;
    let page = md.replacen(METHOD, &format!("{head}{METHOD}"), 1);
    // the error control's section, measured by benches/adaptive.py (kept, not recomputed here)
    let control = std::fs::read_to_string(common::root().join("docs/report/error_control.md"))
        .unwrap_or_default();
    let page = format!("{page}{control}{cost}\n{stat}");
    common::write_doc("accuracy.md", &page)?;
    eprintln!("wrote docs/accuracy.md");
    Ok(())
}

/// The planar Case 1 and the spatial Case 1 (`case1_3d`) runs of the same settings side by
/// side, and the distance between the two converged references (planar y against spatial z).
fn side_by_side(planar: &SceneResult, spatial: &SceneResult) -> String {
    const FAMILIES: [&str; 4] = ["step", "elements", "all-ANCF step", "all-modal step"];
    let mut rows = Vec::new();
    for p in planar
        .rows
        .iter()
        .filter(|r| FAMILIES.contains(&r.p.family.as_str()))
    {
        let Some(s) = spatial
            .rows
            .iter()
            .find(|s| s.p.family == p.p.family && s.p.param == p.p.param)
        else {
            continue;
        };
        rows.push(vec![
            p.p.family.clone(),
            p.p.formulation.clone(),
            format!("`{}`", p.p.param),
            format!("{:.4}", p.wall),
            e3(p.err_max),
            format!("{:.4}", s.wall),
            e3(s.err_max),
            e3(s.own_max),
            format!("{:.2}", s.wall / p.wall),
        ]);
    }
    // the converged references: planar (x, y) against spatial (x, z); spatial y must stay 0
    let (mut d_ref, mut y_out) = (0.0f64, 0.0f64);
    for (a, b) in planar.phys.iter().zip(&spatial.phys) {
        d_ref = d_ref.max(((a[0] - b[0]).powi(2) + (a[1] - b[2]).powi(2)).sqrt());
        y_out = y_out.max(b[1].abs());
    }
    let n = planar.phys.len().min(spatial.phys.len());
    format!(
        "## Spatial Case 1 beside planar Case 1 (same machine, same run)\n\n\
         The same settings of `scenes/case1*.toml` (planar, gravity along −y) and \
         `scenes/case1_3d*.toml` (spatial, gravity along −z), each against the converged all-ANCF \
         reference of its own space (4× elements, step 1e-5 s, tolerance 1e-12). The two \
         converged references are the same rod: over their {n} samples the largest distance \
         between the planar tip (x, y) and the spatial tip (x, z) is **{} m**, and the spatial \
         tip's largest out-of-plane |y| is **{} m**. Wall times are single runs on a machine \
         shared with other jobs (see the top of the page): compare them within a row, not \
         across pages.\n\n{}\n",
        e3(d_ref),
        e3(y_out),
        md_table(
            &[
                "family",
                "formulation",
                "setting",
                "planar wall [s]",
                "planar max tip err [m]",
                "spatial wall [s]",
                "spatial max tip err [m]",
                "spatial err vs own-formulation ref [m]",
                "wall spatial / planar",
            ],
            &rows
        )
    )
}

const METHOD: &str = "## Method\n\n\
- Every run simulates 2 s from the scene's initial state and samples the tip position every \
1 ms (runs with an internal step above 1 ms advance, and are compared, every step).\n\
- Wall time covers building the simulator, initial accelerations, stepping and reading the \
outputs at every sample (the median of the repetitions).\n\
- **Physical reference:** the all-ANCF twin of the scene (exact strain measures, no modal \
linearization) with refined mesh and step 1e-5 s. *Max tip error* is the largest Euclidean \
distance of the tip from the reference over all samples, *end error* the distance at t = 2 s, \
*max vertical error* the largest difference of the vertical component (y in the plane, z in \
the spatial scenes).\n\
- **Own-formulation reference:** the same scene file with 12 modes per modal segment, the \
refined mesh and step 1e-5 s. The error against it is the discretization error of a run; the \
distance between it and the physical reference is the model error of the formulation (a modal \
segment, planar or spatial, carries the foreshortening of every point and the inextensible \
curvature to third order).\n\
- Families: `step` (solver.max_step), `elements` (ANCF elements of the swept scene, spread over \
its ANCF segments by length), `modes+interface` and `modes (no interface)` (every modal segment), \
`rho_inf`, one step sweep per twin formulation, and a small `combined` grid. The ANCF \
segments keep the scenes' cubic elements; elements of higher degree (`segments.<i>.degree`) are \
measured in `docs/elements.md` (the soft rod: 16 elements of degree 5 reach 4.4e-7 m where 64 \
cubic ones reach 3.9e-6 m).\n\
- Figures: a marker for every run, a line through each family's own Pareto front (the runs no \
cheaper run of the family beats in error), the Pareto front over all runs circled in black. \
`cargo run --release -p hybeam-report -- accuracy-plots` redraws them from the CSV files.\n\n";

fn cost_per_step(opts: &Opts) -> Result<String, String> {
    let ns: &[usize] = &[8, 16, 32, 64, 128, 256, 512];
    let (t_end, reps) = if opts.quick { (0.02, 1) } else { (0.05, 3) };
    let h = 1e-4;
    let mut prog = Progress::new("cost/step", ns.len());
    let mut rows = Vec::new();
    let mut pts = Vec::new();
    for &n in ns {
        prog.item(&format!("{n} elements"));
        let s = scene(
            "case1_ancf",
            &[
                format!("segments.0.elements={n}"),
                format!("solver.max_step={h:e}"),
            ],
        )?;
        let r = timed(&s, t_end, 1e-3, reps);
        if let Some(e) = &r.err {
            rows.push(vec![n.to_string(), format!("refused: {e}")]);
            continue;
        }
        let c = r.counters;
        let per_step = r.wall / c.steps as f64;
        let per_it = r.wall / c.iterations as f64;
        pts.push((n as f64, per_step));
        rows.push(vec![
            n.to_string(),
            format!("{:.4}", r.wall),
            c.steps.to_string(),
            c.iterations.to_string(),
            c.factorizations.to_string(),
            format!("{:.2}", c.iterations as f64 / c.steps as f64),
            format!("{:.1}", per_step * 1e6),
            format!("{:.1}", per_it * 1e6),
            format!("{:.3}", per_step * 1e9 / n as f64),
        ]);
    }
    prog.finish();
    // least squares cost = a + b n
    let k = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / k, sy / k);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let b = sxy / sxx;
    let a = my - b * mx;
    let ss_tot: f64 = pts.iter().map(|p| (p.1 - my).powi(2)).sum();
    let ss_res: f64 = pts.iter().map(|p| (p.1 - a - b * p.0).powi(2)).sum();
    let r2 = 1.0 - ss_res / ss_tot;
    // log-log slope between the two largest meshes
    let slope = if pts.len() >= 2 {
        let (p, q) = (pts[pts.len() - 2], pts[pts.len() - 1]);
        (q.1 / p.1).ln() / (q.0 / p.0).ln()
    } else {
        f64::NAN
    };
    let csv: Vec<Vec<String>> = rows.clone();
    let head = [
        "elements",
        "wall [s]",
        "steps",
        "Newton it.",
        "factor.",
        "it./step",
        "wall/step [µs]",
        "wall/iteration [µs]",
        "wall/step/element [ns]",
    ];
    common::write_csv("cost_per_step.csv", &head, &csv)?;
    let fit: Vec<(f64, f64)> = ns.iter().map(|&n| (n as f64, a + b * n as f64)).collect();
    plot::plot(
        "cost_per_step.svg",
        &Axes {
            title: "Cost per step vs ANCF elements (case1_ancf, h = 1e-4 s)",
            x: "elements",
            y: "wall time per step [s]",
            log_x: true,
            log_y: true,
        },
        &[
            Series::marked("measured", pts.clone()),
            Series::line("linear fit a + b n", fit),
        ],
        &Extras::default(),
    )?;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "## Cost per step vs number of elements\n\nAll-ANCF Case 1 beam (`case1_ancf`, \
         overrides `segments.0.elements=N`, `solver.max_step=1e-4`), {t_end} s simulated from the \
         straight release, {} repetition(s), median wall.\n\n{}\n\
         Least-squares fit wall/step = a + b·n: a = {:.2} µs, b = {:.3} µs per element, R² = {:.4}. \
         Log-log slope between the two largest meshes: {:.2} (1 = linear). {}\n\n\
         ![cost per step](report/cost_per_step.svg)\n",
        reps,
        md_table(&head, &rows),
        a * 1e6,
        b * 1e6,
        r2,
        slope,
        if r2 > 0.98 && (0.8..1.25).contains(&slope) {
            "The cost grows linearly with the number of elements."
        } else {
            "The cost does not follow a clean linear law over this range (see the table: iterations per step and factorizations change with the mesh)."
        }
    );
    Ok(s)
}
