//! Command-line runner: simulate a scene without any FMI host.
//!
//! ```text
//! hybeam run SCENE.toml --out tip.csv [--set KEY=VALUE ...] [--t-end T] [--output-step H]
//! hybeam static SCENE.toml [--set KEY=VALUE ...]
//! ```

use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

const USAGE: &str = "usage:
  hybeam run SCENE.toml --out tip.csv [--set KEY=VALUE ...] [--t-end T] [--output-step H] [--quiet]
  hybeam static SCENE.toml [--set KEY=VALUE ...]";

struct Args {
    command: String,
    scene: String,
    out: Option<String>,
    sets: Vec<(String, String)>,
    t_end: Option<f64>,
    output_step: Option<f64>,
    quiet: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let command = it.next().ok_or("missing command")?;
    if command == "-h" || command == "--help" {
        return Err(String::new());
    }
    let scene = it.next().ok_or("missing scene file")?;
    let mut a = Args {
        command,
        scene,
        out: None,
        sets: Vec::new(),
        t_end: None,
        output_step: None,
        quiet: false,
    };
    let num = |flag: &str, v: Option<String>| -> Result<f64, String> {
        let v = v.ok_or(format!("{flag} needs a value"))?;
        v.parse::<f64>()
            .map_err(|_| format!("{flag} {v}: not a number"))
    };
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--out" => a.out = Some(it.next().ok_or("--out needs a file name")?),
            "--set" => {
                let kv = it.next().ok_or("--set needs KEY=VALUE")?;
                let (k, v) = kv.split_once('=').ok_or(format!(
                    "--set {kv}: expected KEY=VALUE, e.g. segments.1.elements=16"
                ))?;
                a.sets.push((k.trim().to_string(), v.trim().to_string()));
            }
            "--t-end" => a.t_end = Some(num("--t-end", it.next())?),
            "--output-step" => a.output_step = Some(num("--output-step", it.next())?),
            "--quiet" => a.quiet = true,
            other => return Err(format!("unknown option {other}")),
        }
    }
    Ok(a)
}

fn load(args: &Args) -> Result<Scene, String> {
    let text = std::fs::read_to_string(&args.scene)
        .map_err(|e| format!("cannot read {}: {e}", args.scene))?;
    let mut sets = args.sets.clone();
    if let Some(t) = args.t_end {
        sets.push(("simulation.t_end".into(), format!("{t:e}")));
    }
    if let Some(h) = args.output_step {
        sets.push(("simulation.output_step".into(), format!("{h:e}")));
    }
    Scene::from_toml_with_overrides(&text, &sets).map_err(|e| format!("{}: {e}", args.scene))
}

const HEADER: &str =
    "time,tip.position.x,tip.position.y,tip.angle,energy.kinetic,energy.strain,energy.potential";

fn row(sim: &Simulator) -> String {
    let o = sim.outputs();
    format!(
        "{:.9e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e}",
        sim.time(),
        o.tip_position[0],
        o.tip_position[1],
        o.tip_angle,
        o.kinetic,
        o.strain,
        o.potential
    )
}

fn run(args: &Args) -> Result<(), String> {
    let scene = load(args)?;
    let out_path = args.out.clone().ok_or("run needs --out FILE.csv")?;
    let t_end = scene.simulation.t_end;
    let dt = scene.simulation.output_step;
    let wall = Instant::now();
    let mut sim = Simulator::new(scene)?;
    let mut out = Vec::with_capacity(64 * 1024);
    writeln!(out, "{HEADER}").map_err(|e| e.to_string())?;
    writeln!(out, "{}", row(&sim)).map_err(|e| e.to_string())?;
    let n_out = (t_end / dt - 1e-9).ceil() as u64;
    let mut last_report = Instant::now();
    for k in 1..=n_out {
        let t = (k as f64 * dt).min(t_end);
        sim.advance(t)
            .map_err(|e| format!("at t = {:.6} s: {e}", sim.time()))?;
        writeln!(out, "{}", row(&sim)).map_err(|e| e.to_string())?;
        if !args.quiet && last_report.elapsed().as_secs_f64() > 1.0 {
            eprint!("\r  t = {t:.4} / {t_end} s ({:.0} %)", 100.0 * t / t_end);
            last_report = Instant::now();
        }
    }
    let elapsed = wall.elapsed().as_secs_f64();
    std::fs::write(&out_path, out).map_err(|e| format!("cannot write {out_path}: {e}"))?;
    let c = sim.counters();
    let o = sim.outputs();
    if !args.quiet {
        eprint!("\r");
    }
    println!(
        "{}: t = {:.4} s, {} steps ({} rejected), {} Newton iterations, {} factorizations, wall {:.4} s; tip = ({:.6e}, {:.6e}) m -> {}",
        args.scene, sim.time(), c.steps, c.rejected, c.iterations, c.factorizations, elapsed,
        o.tip_position[0], o.tip_position[1], out_path
    );
    Ok(())
}

fn statics(args: &Args) -> Result<(), String> {
    let scene = load(args)?;
    let wall = Instant::now();
    let mut sim = Simulator::new(scene)?;
    let it = sim.solve_static()?;
    let o = sim.outputs();
    println!("{HEADER}");
    println!("{}", row(&sim));
    eprintln!(
        "static equilibrium: {it} Newton iterations, wall {:.4} s",
        wall.elapsed().as_secs_f64()
    );
    let _ = o;
    Ok(())
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("error: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    let r = match args.command.as_str() {
        "run" => run(&args),
        "static" => statics(&args),
        other => Err(format!("unknown command {other}\n{USAGE}")),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
