//! Command-line runner: simulate a scene without any FMI host.
//!
//! ```text
//! hybeam run SCENE.toml --out tip.csv [--set KEY=VALUE ...] [--t-end T] [--output-step H] [--quiet]
//!            [--vtk DIR] [--animate PAGE.html] [--samples N]
//! hybeam static SCENE.toml [--set KEY=VALUE ...]
//! hybeam animate RESULT_DIR [--out PAGE.html] [--body LX,LY,LZ --body-centre X,Y,Z]
//! ```
//!
//! `hybeam --help` and `hybeam run --help` print the generated help. Exit code 2 for a bad
//! command line, 1 for a bad scene or a failed simulation.

use clap::{Args, Parser, Subcommand};
use hybeam::scene::{Root, Scene, SpaceKind};
use hybeam::simulator::{AnyOutputs, AnySimulator, OutputId, Quantity};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Simulate a hybeam scene (docs/scene-format.md) without an FMI host.
#[derive(Debug, Parser)]
#[command(name = "hybeam", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Simulate to the end time and write the tip history as CSV.
    Run(RunArgs),
    /// Solve the static equilibrium and print the outputs as CSV on stdout.
    Static(SceneArgs),
    /// Write the animation page of a ParaView series written by `run --vtk DIR` or by the FMU
    /// (`visualization.directory`).
    Animate(AnimateArgs),
}

#[derive(Debug, Args)]
struct AnimateArgs {
    /// The series' directory (holding one `.pvd` collection) or the `.pvd` file.
    result: PathBuf,
    /// The page to write [default: RESULT_DIR/animation.html].
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Draw a box of these edge lengths [m] carried by the root (mount) frame: a vehicle body.
    #[arg(long, value_name = "LX,LY,LZ", value_parser = triple)]
    body: Option<[f64; 3]>,
    /// The box centre in the root frame [m] (with --body).
    #[arg(long, value_name = "X,Y,Z", value_parser = triple, requires = "body", allow_hyphen_values = true)]
    body_centre: Option<[f64; 3]>,
    /// Page title [default: the collection's file name].
    #[arg(long)]
    title: Option<String>,
}

/// The scene file and its overrides, common to both commands.
#[derive(Debug, Args)]
struct SceneArgs {
    /// Scene file (TOML).
    scene: PathBuf,
    /// Override a scene value before validation (TOML syntax, repeatable),
    /// e.g. --set segments.1.elements=16.
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = key_value)]
    sets: Vec<(String, String)>,
}

#[derive(Debug, Args)]
struct RunArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Output CSV file.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// End time [s] (replaces simulation.t_end).
    #[arg(long, value_name = "T", value_parser = positive_seconds, allow_negative_numbers = true)]
    t_end: Option<f64>,
    /// Output interval [s] (replaces simulation.output_step).
    #[arg(long, value_name = "H", value_parser = positive_seconds, allow_negative_numbers = true)]
    output_step: Option<f64>,
    /// No progress line on stderr.
    #[arg(long)]
    quiet: bool,
    /// Also write the beam's shape at every output time as a ParaView series
    /// DIR/beam.pvd of DIR/beam_NNNNNN.vtu.
    #[arg(long, value_name = "DIR")]
    vtk: Option<PathBuf>,
    /// Also write a self-contained 3D animation page of the run (opens offline in a browser).
    #[arg(long, value_name = "FILE")]
    animate: Option<PathBuf>,
    /// The most output rows (and --vtk pieces) a run may write: a run that would write more
    /// (t_end / output_step + 1) is refused before it starts.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_ROWS, value_parser = clap::value_parser!(u64).range(1..))]
    max_rows: u64,
    /// Centreline samples per element (intervals) for --vtk and --animate.
    #[arg(long, value_name = "N", default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=64))]
    samples: u32,
}

/// The default of `hybeam run --max-rows`: a million rows (a CSV of ~0.1–0.4 GB).
const DEFAULT_MAX_ROWS: u64 = 1_000_000;

/// `X,Y,Z`: three finite numbers.
fn triple(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .map_err(|_| format!("{x:?} is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [a, b, c] if v.iter().all(|x| x.is_finite()) => Ok([*a, *b, *c]),
        _ => Err("expected three finite numbers X,Y,Z, e.g. 4.2,1.8,1.2".into()),
    }
}

/// `KEY=VALUE` of `--set`, both trimmed.
fn key_value(kv: &str) -> Result<(String, String), String> {
    let (k, v) = kv
        .split_once('=')
        .ok_or("expected KEY=VALUE, e.g. segments.1.elements=16")?;
    Ok((k.trim().to_string(), v.trim().to_string()))
}

/// A finite, positive time in seconds.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        Ok(_) => Err("must be a finite, positive time in seconds".into()),
        Err(_) => Err("not a number (seconds, e.g. 2 or 1e-3)".into()),
    }
}

impl SceneArgs {
    /// Reads the scene and applies the `--set` overrides (validated).
    fn load(&self) -> Result<Scene, String> {
        let path = self.scene.display();
        let text =
            std::fs::read_to_string(&self.scene).map_err(|e| format!("cannot read {path}: {e}"))?;
        Scene::from_toml_with_overrides(&text, &self.sets).map_err(|e| format!("{path}: {e}"))
    }
}

/// The CSV columns of a planar scene after `time` (a subset of its outputs, unchanged since the
/// first release). A spatial scene's CSV has every output of the simulator.
const PLANAR_COLUMNS: [&str; 6] = [
    "tip.position.x",
    "tip.position.y",
    "tip.angle",
    "energy.kinetic",
    "energy.strain",
    "energy.potential",
];

/// The CSV columns after `time` of a scene in `space`: the simulator's named outputs (the same
/// names as the FMU's output variables, checked by the test `columns_are_fmu_outputs`). A
/// mounted scene's CSV has every output, the reactions and the rigid inertia at the mount
/// included.
fn columns(space: SpaceKind, mounted: bool) -> Vec<(String, OutputId)> {
    let all = OutputId::named_with(space, mounted);
    match space {
        SpaceKind::Planar if !mounted => all
            .into_iter()
            .filter(|(name, _)| PLANAR_COLUMNS.contains(&name.as_str()))
            .collect(),
        _ => all,
    }
}

/// The CSV columns after `time` of `scene`: [`columns`], then its stations' outputs
/// (`station.<name>.force.*`, `.moment.*`, `.stress`).
fn scene_columns(scene: &Scene) -> Vec<(String, OutputId)> {
    let mut out = columns(scene.space, scene.root == Root::Mounted);
    out.extend(OutputId::of_scene(scene).into_iter().filter(|(_, id)| {
        matches!(
            id.quantity,
            Quantity::StationForce
                | Quantity::StationMoment
                | Quantity::StationStress
                | Quantity::BeamStressMax
                | Quantity::BeamStressMaxAt
        )
    }));
    out
}

/// The CSV header line.
fn header(columns: &[(String, OutputId)]) -> String {
    std::iter::once("time")
        .chain(columns.iter().map(|(name, _)| name.as_str()))
        .collect::<Vec<_>>()
        .join(",")
}

/// The CSV row of the current state, whose outputs are `o`: time to 10 digits, outputs in the
/// shortest decimal that reads back to the same f64 (exact round trip; the fixed 18 digits of
/// `{:.17e}` took the slow exact-digit path, ~6 % of a Case 1 run at 1 ms outputs).
fn row(sim: &AnySimulator, o: &AnyOutputs, columns: &[(String, OutputId)]) -> String {
    use std::fmt::Write as _;
    let mut s = format!("{:.9e}", sim.time());
    for (_, id) in columns {
        let value = o.value(*id).unwrap_or(f64::NAN);
        let _ = write!(s, ",{value:e}");
    }
    s
}

/// The views a run writes beside its CSV (`--vtk DIR` as `DIR/beam.pvd`, `--animate PAGE`),
/// the page showing the tip columns.
fn views(
    args: &RunArgs,
    scene: &Scene,
    columns: &[(String, OutputId)],
) -> Result<hybeam_view::Views, String> {
    let tip = columns
        .iter()
        .filter(|(name, _)| name.starts_with("tip."))
        .cloned()
        .collect();
    let title = format!("{} ({})", scene.name, args.scene.scene.display());
    hybeam_view::Views::create(
        scene,
        args.vtk.as_deref().map(|dir| (dir, "beam")),
        args.animate.clone().map(|page| (page, title)),
        tip,
        args.samples as usize,
    )
    .map_err(|e| e.to_string())
}

fn run(args: &RunArgs) -> Result<(), String> {
    let mut scene = args.scene.load()?;
    if let Some(t) = args.t_end {
        scene.simulation.t_end = t;
    }
    if let Some(h) = args.output_step {
        scene.simulation.output_step = h;
    }
    let t_end = scene.simulation.t_end;
    let dt = scene.simulation.output_step;
    let n_out = (t_end / dt - 1e-9).ceil();
    if n_out.is_nan() || n_out >= args.max_rows as f64 {
        return Err(format!(
            "output_step = {dt:e} s over t_end = {t_end} s gives {:.3e} output rows, more than \
             --max-rows {}: raise --output-step (or simulation.output_step), shorten --t-end, \
             or raise --max-rows",
            n_out + 1.0,
            args.max_rows
        ));
    }
    let n_out = n_out as u64;
    let wall = Instant::now();
    let columns = scene_columns(&scene);
    let mut views = views(args, &scene, &columns)?;
    let mut sim = AnySimulator::new(scene).map_err(|e| e.to_string())?;
    // the rows streamed to the file as they come: a run cut short keeps what it computed
    let out_path = args.out.display();
    let cannot = |e: std::io::Error| format!("cannot write {out_path}: {e}");
    let file = std::fs::File::create(&args.out).map_err(cannot)?;
    let mut out = std::io::BufWriter::with_capacity(64 * 1024, file);
    writeln!(out, "{}", header(&columns)).map_err(cannot)?;
    // the outputs once per output time, for the row and the page
    let mut record = |sim: &AnySimulator, out: &mut std::io::BufWriter<std::fs::File>| {
        let o = sim.outputs();
        writeln!(out, "{}", row(sim, &o, &columns)).map_err(cannot)?;
        views.record(sim, &o).map(drop).map_err(|e| e.to_string())
    };
    record(&sim, &mut out)?;
    let mut last_report = Instant::now();
    for k in 1..=n_out {
        let t = (k as f64 * dt).min(t_end);
        if let Err(e) = sim.advance(t) {
            out.flush().map_err(cannot)?;
            return Err(format!(
                "at t = {:.6} s: {e} (the rows up to it are in {out_path})",
                sim.time()
            ));
        }
        record(&sim, &mut out)?;
        if !args.quiet && last_report.elapsed().as_secs_f64() > 1.0 {
            eprint!("\r  t = {t:.4} / {t_end} s ({:.0} %)", 100.0 * t / t_end);
            last_report = Instant::now();
        }
    }
    // the views' last pieces and page are part of the run's time
    views.finish().map_err(|e| e.to_string())?;
    let mut written = String::new();
    if let Some((pvd, pieces)) = views.collection() {
        written.push_str(&format!(", {pieces} pieces -> {}", pvd.display()));
    }
    if let Some(page) = views.page() {
        written.push_str(&format!(", animation -> {}", page.display()));
    }
    out.flush().map_err(cannot)?;
    let elapsed = wall.elapsed().as_secs_f64();
    let c = sim.counters();
    let o = sim.outputs();
    if !args.quiet {
        eprint!("\r");
    }
    let tip: Vec<String> = o
        .tip_position()
        .iter()
        .map(|x| format!("{x:.6e}"))
        .collect();
    println!(
        "{}: t = {:.4} s, {} steps ({} rejected), {} Newton iterations, {} factorizations, wall {:.4} s; tip = ({}) m -> {out_path}{written}",
        args.scene.scene.display(), sim.time(), c.steps, c.rejected, c.iterations, c.factorizations, elapsed,
        tip.join(", ")
    );
    Ok(())
}

/// `hybeam animate`: the page of a written series.
fn animate(args: &AnimateArgs) -> Result<(), String> {
    let pvd = if args.result.is_dir() {
        let found: Vec<PathBuf> = std::fs::read_dir(&args.result)
            .map_err(|e| format!("cannot read {}: {e}", args.result.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "pvd"))
            .collect();
        match found.as_slice() {
            [one] => one.clone(),
            [] => return Err(format!("{}: no .pvd collection (write one with `hybeam run SCENE --vtk DIR` or the FMU's visualization.directory)", args.result.display())),
            _ => return Err(format!("{}: several .pvd collections; name one: hybeam animate DIR/NAME.pvd", args.result.display())),
        }
    } else {
        args.result.clone()
    };
    let pieces = hybeam_view::read::read_series(&pvd).map_err(|e| e.to_string())?;
    let first = pieces
        .first()
        .ok_or_else(|| format!("{}: the collection is empty", pvd.display()))?;
    // up: from the first frame's root frame is not gravity; a spatial series (any z) is z-up
    let spatial = pieces
        .iter()
        .any(|p| p.shape.points.iter().any(|q| q.position[2] != 0.0));
    let gravity: &[f64] = if spatial {
        &[0.0, 0.0, -1.0]
    } else {
        &[0.0, -1.0]
    };
    let title = args.title.clone().unwrap_or_else(|| {
        pvd.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    let names: Vec<String> = if spatial {
        &["x", "y", "z"][..]
    } else {
        &["x", "y"][..]
    }
    .iter()
    .map(|a| format!("tip.position.{a}"))
    .collect();
    // the masses' spheres from the first piece (their centres from each piece)
    let look = hybeam_view::Look {
        radii: Vec::new(),
        segments: Vec::new(),
        masses: first
            .masses
            .iter()
            .map(|(_, radius)| hybeam_view::look::MassLook {
                segment: 0,
                at: 0.0,
                offset: [0.0; 3],
                radius: *radius,
            })
            .collect(),
    };
    let mut rec = hybeam_view::Recorder::new(&title, gravity, look, names.clone());
    if let Some(size) = args.body {
        rec = rec.with_body(hybeam_view::BodyBox {
            size,
            centre: args.body_centre.unwrap_or([0.0; 3]),
        });
    }
    for p in &pieces {
        let tip = p
            .shape
            .points
            .last()
            .map(|q| q.position)
            .unwrap_or_default();
        let centres: Vec<[f64; 3]> = p.masses.iter().map(|(c, _)| *c).collect();
        rec.push_dressed(p.time, &p.shape, &p.radius, &centres, &tip[..names.len()]);
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| pvd.with_file_name("animation.html"));
    rec.write(&out).map_err(|e| e.to_string())?;
    println!(
        "{}: {} frames -> {}",
        pvd.display(),
        pieces.len(),
        out.display()
    );
    Ok(())
}

fn statics(args: &SceneArgs) -> Result<(), String> {
    let scene = args.load()?;
    let wall = Instant::now();
    let columns = scene_columns(&scene);
    let mut sim = AnySimulator::new(scene).map_err(|e| e.to_string())?;
    let it = sim.solve_static().map_err(|e| e.to_string())?;
    println!("{}", header(&columns));
    println!("{}", row(&sim, &sim.outputs(), &columns));
    eprintln!(
        "static equilibrium: {it} Newton iterations, wall {:.4} s",
        wall.elapsed().as_secs_f64()
    );
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let r = match &cli.command {
        Command::Run(a) => run(a),
        Command::Static(a) => statics(a),
        Command::Animate(a) => animate(a),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        Cli::try_parse_from(std::iter::once("hybeam").chain(args.iter().copied()))
    }

    #[test]
    fn parses_the_documented_invocations() {
        // README.md, docs/*.md, tests/python/test_beam.py
        let cli = parse(&[
            "run",
            "scenes/case1.toml",
            "--out",
            "tip.csv",
            "--set",
            "segments.1.elements=16",
            "--set",
            " solver.max_step = 5e-5",
            "--t-end",
            "0.3",
            "--output-step",
            "1e-3",
            "--quiet",
        ])
        .unwrap();
        let Command::Run(a) = cli.command else {
            panic!("not run: {cli:?}")
        };
        assert_eq!(a.scene.scene, Path::new("scenes/case1.toml"));
        assert_eq!(a.out, Path::new("tip.csv"));
        assert_eq!(
            a.scene.sets,
            [
                ("segments.1.elements".into(), "16".into()),
                ("solver.max_step".into(), "5e-5".into())
            ]
        );
        assert_eq!(
            (a.t_end, a.output_step, a.quiet),
            (Some(0.3), Some(1e-3), true)
        );
        let cli = parse(&["static", "scenes/case3.toml"]).unwrap();
        assert!(matches!(cli.command, Command::Static(s) if s.sets.is_empty()));
        // docs/view.md
        let cli = parse(&[
            "run",
            "scenes/strip_3d.toml",
            "--out",
            "out/strip.csv",
            "--vtk",
            "out/strip_vtk",
            "--animate",
            "out/strip.html",
            "--samples",
            "4",
        ])
        .unwrap();
        let Command::Run(a) = cli.command else {
            panic!("not run")
        };
        assert_eq!(a.vtk.as_deref(), Some(Path::new("out/strip_vtk")));
        assert_eq!(a.animate.as_deref(), Some(Path::new("out/strip.html")));
        assert_eq!(a.samples, 4);
        let cli = parse(&[
            "animate",
            "out/vehicle/view",
            "--body",
            "4.1,1.3,1.8",
            "--body-centre",
            "-0.45, -0.65, 0",
            "--out",
            "page.html",
        ])
        .unwrap();
        let Command::Animate(a) = cli.command else {
            panic!("not animate")
        };
        assert_eq!(a.body, Some([4.1, 1.3, 1.8]));
        assert_eq!(a.body_centre, Some([-0.45, -0.65, 0.0]));
    }

    #[test]
    fn rejects_bad_command_lines() {
        for bad in [
            &["run", "s.toml"][..],                           // no --out
            &["run", "s.toml", "--out", "a", "--t-end", "x"], // not a number
            &["run", "s.toml", "--out", "a", "--t-end", "0"], // not positive
            &["run", "s.toml", "--out", "a", "--t-end", "-1"],
            &["run", "s.toml", "--out", "a", "--output-step", "inf"],
            &["static", "s.toml", "--set", "no-equals-sign"],
            &["static", "s.toml", "--bogus"],
            &["static"],
            &["simulate", "s.toml"],
            &["run", "s.toml", "--out", "a", "--samples", "0"], // at least one interval
            &["run", "s.toml", "--out", "a", "--samples", "65"],
            &["animate", "d", "--body", "1,2"], // three numbers
            &["animate", "d", "--body", "1,2,nan"],
            &["animate", "d", "--body-centre", "1,2,3"], // needs --body
            &["animate"],
        ] {
            assert!(parse(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn header_names_every_column_of_a_row() {
        let planar = columns(SpaceKind::Planar, false);
        assert_eq!(
            header(&planar),
            "time,tip.position.x,tip.position.y,tip.angle,energy.kinetic,energy.strain,energy.potential"
        );
        assert_eq!(
            header(&columns(SpaceKind::Spatial, false)),
            "time,tip.position.x,tip.position.y,tip.position.z,tip.velocity.x,tip.velocity.y,\
             tip.velocity.z,tip.orientation.e0,tip.orientation.e1,tip.orientation.e2,\
             tip.orientation.e3,tip.angular_velocity.x,tip.angular_velocity.y,\
             tip.angular_velocity.z,root.force.x,root.force.y,root.force.z,root.moment.x,\
             root.moment.y,root.moment.z,energy.kinetic,energy.strain,energy.potential"
        );
        let scene = Scene::from_toml(
            "name = \"t\"\n[[segments]]\nname = \"a\"\nkind = \"ancf\"\nlength = 0.4\n\
             section = \"round\"\ndiameter = 0.002\nyoungs_modulus = 2.1e11\ndensity = 7850.0\n\
             elements = 2\n",
        )
        .unwrap();
        let sim = AnySimulator::new(scene).unwrap();
        let row = row(&sim, &sim.outputs(), &planar);
        assert_eq!(row.split(',').count(), header(&planar).split(',').count());
        assert!(!row.contains("NaN"), "{row}");
    }

    /// Every CSV column after `time` of either space is an FMU output of the same name that
    /// reads the same quantity (docs/fmu-variables.md); on a planar state where positions,
    /// energies and the angle are all nonzero, the same value.
    #[test]
    fn columns_are_fmu_outputs() {
        use hybeam_fmu::cosim::variables::{Access, Table};
        let read = |name: &str| {
            let path = format!("{}/../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
            Scene::from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
        };
        let mut sim = AnySimulator::new(read("case1")).unwrap();
        sim.advance(2e-3).unwrap();
        let outputs = sim.outputs();
        for scene in [read("case1"), read("case1_3d")] {
            let table = Table::of(&scene);
            let planar = scene.space == SpaceKind::Planar;
            for (name, id) in columns(scene.space, scene.root == Root::Mounted) {
                let index = table
                    .variables()
                    .iter()
                    .position(|v| v.name == name)
                    .unwrap_or_else(|| panic!("CSV column {name} is not an FMU variable"));
                assert_eq!(table.variables()[index].causality, fmi2::Causality::Output);
                let Access::Output(fmu) = table.access(index) else {
                    panic!("{name} is not read from the outputs");
                };
                assert_eq!(fmu, id, "{name}");
                if planar {
                    let value = outputs.value(id).unwrap();
                    assert_ne!(value, 0.0, "{name} must discriminate");
                }
            }
        }
    }

    /// `hybeam run` with `args` after `run SCENES/case1.toml --out OUT --quiet`.
    fn run_case1(out: &Path, args: &[&str]) -> Result<(), String> {
        let scene = format!("{}/../scenes/case1.toml", env!("CARGO_MANIFEST_DIR"));
        let mut all = vec!["run", &scene, "--out", out.to_str().unwrap(), "--quiet"];
        all.extend_from_slice(args);
        let Command::Run(a) = parse(&all).unwrap().command else {
            panic!("not run")
        };
        run(&a)
    }

    fn temp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("hybeam-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    /// T5: a run that would write more rows than `--max-rows` is refused before it starts,
    /// naming the output step, the row count and the fix (it ran for minutes before, growing
    /// by ~1 GB a minute).
    #[test]
    fn too_many_output_rows_are_refused_up_front() {
        let out = temp("rows.csv");
        let e = run_case1(&out, &["--t-end", "0.2", "--output-step", "1e-7"]).unwrap_err();
        assert!(
            e.contains("output_step = 1e-7") && e.contains("2.000e6 output rows"),
            "{e}"
        );
        assert!(e.contains("--max-rows 1000000"), "{e}");
        assert!(!out.exists(), "nothing written");
        // within a raised bound it runs
        let args = [
            "--t-end",
            "2e-4",
            "--output-step",
            "1e-6",
            "--max-rows",
            "201",
        ];
        run_case1(&out, &args).unwrap();
        let rows = std::fs::read_to_string(&out).unwrap().lines().count() - 1;
        assert_eq!(rows, 201);
    }

    /// T5: the rows are streamed to the file: a run refused half-way keeps the rows up to the
    /// refusal, the same bytes as a run that ends there.
    #[test]
    fn a_run_cut_short_keeps_its_rows() {
        // an axial tip force whose dynamic overshoot passes the 5 % strain limit at 41 us
        let (cut, whole) = (temp("cut.csv"), temp("whole.csv"));
        let force = ["--set", "tip.force=[1.8e4, 0.0]", "--output-step", "1e-6"];
        let e = run_case1(&cut, &[&force[..], &["--t-end", "1e-3"]].concat()).unwrap_err();
        assert!(
            e.contains("axial strain") && e.contains("the rows up to it"),
            "{e}"
        );
        let cut = std::fs::read_to_string(&cut).unwrap();
        let rows = cut.lines().count() - 1;
        assert!(rows > 10, "{rows} rows before the refusal");
        let t_last: f64 = cut
            .lines()
            .last()
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let t_end = format!("{t_last:e}");
        run_case1(&whole, &[&force[..], &["--t-end", &t_end]].concat()).unwrap();
        assert_eq!(cut, std::fs::read_to_string(&whole).unwrap());
    }
}
