//! `hybeam-realtime FMU.fmu [options]`: a native FMI 2.0 co-simulation host that measures an
//! FMU's time per communication step as a real-time host sees it (issue 41).
//!
//! It unpacks the FMU, loads `binaries/linux64/<modelIdentifier>.so`, instantiates it, sets the
//! inputs at t = 0 in initialization mode, then runs N steps of: compute the inputs (a sine tip
//! force; a vertical heave of the mount for a mounted FMU), and, timed, one fmi2SetReal of the
//! inputs, one fmi2DoStep and one fmi2GetReal of every output. Per step it records the wall time
//! (`std::time::Instant`, monotonic) and the calling thread's CPU time
//! (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`) in arrays allocated before the loop; it prints the
//! percentiles of both, max/median and the headroom = step / worst CPU time, and optionally a
//! histogram (SVG), the per-step CSV, a JSON summary or a Markdown table row (docs/realtime.md).
//!
//! Linux only (the thread CPU clock, sched_setaffinity, mlockall; `src/os.rs`).

mod fmu;
mod histogram;
mod host;
mod inputs;
mod os;
mod stats;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;

use fmu::Causality;
use host::{CallError, Instance};
use inputs::{InputPlan, Sine};
use stats::Summary;

/// Measures an FMU's per-step time (wall and thread CPU) as a real-time host sees it.
#[derive(Parser, Debug)]
#[command(name = "hybeam-realtime", version, about, long_about = None)]
struct Args {
    /// The FMU (.fmu) to drive; it must contain binaries/linux64/<modelIdentifier>.so.
    #[arg(required_unless_present = "markdown_header")]
    fmu: Option<PathBuf>,
    /// Communication steps to run.
    #[arg(long, default_value_t = 10_000)]
    steps: usize,
    /// Communication step size [s].
    #[arg(long, default_value_t = 1e-3)]
    step: f64,
    /// Amplitude of the tip force sine [N] (tip.force.z in space, tip.force.y in the plane).
    /// Pick it for the beam: 10 N suits the 10 kg roof boom; the 2 mm rods of case1 want about
    /// 0.01 N (10 N is refused there: the modal segment would deflect beyond its validity).
    #[arg(long, default_value_t = 10.0)]
    amplitude: f64,
    /// Frequency of the tip force sine [Hz].
    #[arg(long, default_value_t = 2.0)]
    frequency: f64,
    /// Amplitude of the mount's vertical heave [m] (mounted FMUs only).
    #[arg(long, default_value_t = 0.01)]
    heave: f64,
    /// Frequency of the mount's heave [Hz].
    #[arg(long, default_value_t = 1.0)]
    heave_frequency: f64,
    /// Pin the measuring thread to this CPU (sched_setaffinity).
    #[arg(long)]
    pin: Option<usize>,
    /// Run the measuring thread SCHED_FIFO at this priority (1..=99), as a real-time host would;
    /// a refusal is an error.
    #[arg(long, value_name = "PRIORITY", value_parser = clap::value_parser!(i32).range(1..=99))]
    fifo: Option<i32>,
    /// Pace the steps as a real-time host does: step k starts at the k-th period boundary
    /// (clock_nanosleep to start + k · step, no sleep when behind) instead of back to back;
    /// records each step's wake-up lateness and counts the steps that end past their period.
    #[arg(long)]
    paced: bool,
    /// Lock all memory, current and future (mlockall); a refusal is reported, not fatal.
    #[arg(long)]
    mlock: bool,
    /// Steps at the start excluded from the statistics.
    #[arg(long, default_value_t = 100)]
    warmup: usize,
    /// Write the histogram of the per-step CPU time to this SVG.
    #[arg(long, value_name = "SVG")]
    histogram: Option<PathBuf>,
    /// Write step, time [s], wall [µs] and CPU [µs] of every step to this CSV.
    #[arg(long, value_name = "CSV")]
    csv: Option<PathBuf>,
    /// Print the summary as one JSON object (instead of the text).
    #[arg(long, conflicts_with = "markdown")]
    json: bool,
    /// Print the summary as one Markdown table row (docs/realtime.md; see --markdown-header).
    #[arg(long)]
    markdown: bool,
    /// Print the Markdown table's header (and, with an FMU and --markdown, then its row).
    #[arg(long)]
    markdown_header: bool,
    /// The FMU's name in the Markdown row and the histogram title (default: modelIdentifier).
    #[arg(long)]
    label: Option<String>,
    /// fmi2Instantiate with loggingOn = true (the FMU's debug messages go to stderr).
    #[arg(long)]
    logging: bool,
}

/// One communication step as a host makes it: fmi2SetReal of the inputs, fmi2DoStep from `t`
/// over `h` [s], fmi2GetReal of the outputs into `out`.
///
/// Not inlined and not mangled, so that an instruction counter can find it by name: under
/// `valgrind --tool=callgrind --collect-atstart=no --toggle-collect=hybeam_realtime_step
/// --dump-after=hybeam_realtime_step` each dump holds the instructions of one step
/// (`check_instructions.sh`).
#[no_mangle]
#[inline(never)]
pub fn hybeam_realtime_step(
    instance: &Instance,
    in_vrs: &[u32],
    in_values: &[f64],
    t: f64,
    h: f64,
    out_vrs: &[u32],
    out: &mut [f64],
) -> Result<(), CallError> {
    instance.set_real(in_vrs, in_values)?;
    instance.do_step(t, h)?;
    instance.get_real(out_vrs, out)
}

/// What the OS granted.
#[derive(Debug, Default)]
struct Conditions {
    /// The CPU the thread was pinned to.
    pinned: Option<usize>,
    /// The SCHED_FIFO priority of the thread, if asked.
    fifo: Option<i32>,
    /// Whether the steps were paced (--paced).
    paced: bool,
    /// Whether mlockall succeeded; the refusal's reason otherwise (None: not asked).
    locked: Option<Result<(), String>>,
    /// Resolution of the thread CPU clock [ns].
    clock_resolution_ns: u64,
    /// Page faults of the process during the loop (minor, major).
    faults: (u64, u64),
    /// Context switches of the thread during the loop (voluntary, involuntary).
    switches: (u64, u64),
    /// The 1-minute load average after the loop (other work on the machine), if readable.
    load: Option<f64>,
}

impl Conditions {
    fn pin_lock(&self) -> String {
        let pin = self
            .pinned
            .map_or("not pinned".to_string(), |c| format!("pinned to CPU {c}"));
        let lock = match &self.locked {
            None => "memory not locked",
            Some(Ok(())) => "memory locked",
            Some(Err(_)) => "mlockall refused",
        };
        let fifo = self
            .fifo
            .map_or(String::new(), |p| format!(", SCHED_FIFO {p}"));
        let paced = if self.paced {
            ", paced"
        } else {
            ", back to back"
        };
        format!("{pin}, {lock}{fifo}{paced}")
    }
}

/// A finished run.
struct Run {
    label: String,
    model_identifier: String,
    steps: usize,
    warmup: usize,
    step: f64,
    inputs: Vec<String>,
    outputs: usize,
    /// Per step [µs].
    wall_us: Vec<f64>,
    /// Per step [µs].
    cpu_us: Vec<f64>,
    wall: Summary,
    cpu: Summary,
    conditions: Conditions,
    elapsed_s: f64,
    /// With --paced: per-step wake-up lateness [µs], its summary and the steps (after the
    /// warm-up) that ended past their period.
    paced: Option<Paced>,
}

/// What pacing measured.
struct Paced {
    /// Per step: how late the step started after its period boundary [µs].
    late_us: Vec<f64>,
    /// The summary of `late_us` after the warm-up.
    late: Summary,
    /// Steps after the warm-up that ended past the end of their period.
    overruns: usize,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("hybeam-realtime: {e}");
            ExitCode::FAILURE
        }
    }
}

const MARKDOWN_HEADER: &str = "| FMU | steps | step [ms] | pinned, mlock, sched | CPU median [µs] | CPU p99 | CPU p99.9 | CPU p99.99 | CPU max | CPU max/median | wall median [µs] | wall p99 | wall p99.9 | wall p99.99 | wall max | wall max/median | headroom (step / CPU max) |\n|---|--:|--:|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|";

fn run(args: &Args) -> Result<(), String> {
    if args.markdown_header {
        println!("{MARKDOWN_HEADER}");
    }
    let Some(fmu_path) = &args.fmu else {
        return Ok(());
    };
    if !(args.step > 0.0 && args.step.is_finite()) {
        return Err(format!(
            "--step {}: must be a positive number of seconds",
            args.step
        ));
    }
    if args.steps <= args.warmup {
        return Err(format!(
            "--steps {} must exceed --warmup {} (the warm-up steps are not counted)",
            args.steps, args.warmup
        ));
    }
    for (name, v) in [
        ("--amplitude", args.amplitude),
        ("--frequency", args.frequency),
        ("--heave", args.heave),
        ("--heave-frequency", args.heave_frequency),
    ] {
        if !v.is_finite() {
            return Err(format!("{name} {v}: must be finite"));
        }
    }
    let run = measure(args, fmu_path)?;
    if let Some(csv) = &args.csv {
        write_csv(csv, &run)?;
    }
    if let Some(svg) = &args.histogram {
        let title = format!(
            "{}: thread CPU time per {} ms step, {} steps ({})",
            run.label,
            fmt_ms(run.step),
            run.steps - run.warmup,
            run.conditions.pin_lock()
        );
        histogram::write(
            svg,
            &title,
            &run.cpu_us[run.warmup..],
            &run.cpu,
            run.step * 1e6,
        )?;
    }
    if args.json {
        println!("{}", json(&run));
    } else if args.markdown {
        println!("{}", markdown_row(&run));
    } else {
        print!("{}", text(&run));
    }
    if let Some(Err(reason)) = &run.conditions.locked {
        eprintln!("hybeam-realtime: {reason}");
    }
    Ok(())
}

/// Loads, initializes and steps the FMU; the timing loop.
fn measure(args: &Args, fmu_path: &Path) -> Result<Run, String> {
    let clock_resolution_ns = os::check_thread_clock()?;
    let unpacked = fmu::unpack(fmu_path)?;
    let md = &unpacked.description;
    let binary = unpacked.binary();
    if !binary.exists() {
        return Err(format!(
            "{} has no binaries/linux64/{}.so",
            fmu_path.display(),
            md.model_identifier
        ));
    }
    let mut plan = InputPlan::new(
        md,
        Sine {
            amplitude: args.amplitude,
            frequency: args.frequency,
        },
        Sine {
            amplitude: args.heave,
            frequency: args.heave_frequency,
        },
    )
    .map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    let out_vrs: Vec<u32> = md
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.vr)
        .collect();

    let mut conditions = Conditions {
        clock_resolution_ns,
        paced: args.paced,
        ..Conditions::default()
    };
    if let Some(cpu) = args.pin {
        os::pin_to(cpu)?;
        conditions.pinned = Some(cpu);
    }
    if let Some(p) = args.fifo {
        os::fifo(p)?;
        conditions.fifo = Some(p);
    }
    if args.mlock {
        conditions.locked = Some(os::lock_memory());
    }

    let api = host::Api::load(&binary)?;
    let mut instance = Instance::new(
        &api,
        &md.model_identifier,
        &md.guid,
        &unpacked.resources(),
        args.logging,
    )?;
    let at = |what: &str, e: CallError| format!("{what}: {e}");
    instance
        .setup_experiment(0.0)
        .map_err(|e| at("setting up", e))?;
    instance
        .enter_initialization_mode()
        .map_err(|e| at("initializing", e))?;
    plan.fill(0.0);
    instance
        .set_real(&plan.vrs, &plan.values)
        .map_err(|e| at("setting the inputs at t = 0 in initialization mode", e))?;
    instance
        .exit_initialization_mode()
        .map_err(|e| at("initializing", e))?;

    // everything the loop writes, allocated (and touched) before it
    let n = args.steps;
    let h = args.step;
    let mut wall_ns = vec![0u64; n];
    let mut cpu_ns = vec![0u64; n];
    // paced: how late each step started after its period boundary [ns]
    let mut late_ns = vec![0u64; if args.paced { n } else { 0 }];
    let mut overruns = 0usize;
    let h_ns = (h * 1e9).round() as u64;
    let mut outputs = vec![0.0f64; out_vrs.len()];
    let mut failure: Option<(usize, f64, CallError)> = None;
    let (faults0, switches0) = (os::page_faults(), os::context_switches());
    let start = Instant::now();
    // the first period boundary: one step from now
    let origin = os::monotonic_ns() + h_ns;
    let mut t = 0.0f64;
    for k in 0..n {
        plan.fill(t);
        if args.paced {
            let boundary = origin + k as u64 * h_ns;
            os::sleep_until_ns(boundary);
            late_ns[k] = os::monotonic_ns().saturating_sub(boundary);
        }
        let w0 = Instant::now();
        let c0 = os::thread_cpu_ns();
        let r = hybeam_realtime_step(
            &instance,
            &plan.vrs,
            &plan.values,
            t,
            h,
            &out_vrs,
            &mut outputs,
        );
        let c1 = os::thread_cpu_ns();
        let w1 = Instant::now();
        wall_ns[k] = (w1 - w0).as_nanos() as u64;
        cpu_ns[k] = c1.saturating_sub(c0);
        if args.paced && k >= args.warmup && os::monotonic_ns() > origin + (k as u64 + 1) * h_ns {
            overruns += 1;
        }
        if let Err(e) = r {
            failure = Some((k, t, e));
            break;
        }
        t += h;
    }
    let elapsed_s = start.elapsed().as_secs_f64();
    let (faults1, switches1) = (os::page_faults(), os::context_switches());
    conditions.faults = (faults1.0 - faults0.0, faults1.1 - faults0.1);
    conditions.switches = (switches1.0 - switches0.0, switches1.1 - switches0.1);
    conditions.load = os::load_average();

    if let Some((k, t, e)) = failure {
        return Err(format!(
            "{}: step {k} (t = {t} s, step {h} s): {e}",
            fmu_path.display()
        ));
    }
    if let Some(i) = outputs.iter().position(|v| !v.is_finite()) {
        let name = md
            .variables
            .iter()
            .find(|v| v.vr == out_vrs[i])
            .map_or("?", |v| v.name.as_str());
        return Err(format!(
            "output {name} is {} after the last step",
            outputs[i]
        ));
    }
    instance.terminate().map_err(|e| at("terminating", e))?;
    debug_assert!(instance.terminated());
    drop(instance);

    let wall_us: Vec<f64> = wall_ns.iter().map(|v| *v as f64 / 1e3).collect();
    let cpu_us: Vec<f64> = cpu_ns.iter().map(|v| *v as f64 / 1e3).collect();
    let w = args.warmup;
    let shift = |mut s: Summary| {
        s.argmax += w;
        s
    };
    let wall = shift(Summary::of(&wall_us[w..]).ok_or("no steps measured")?);
    let cpu = shift(Summary::of(&cpu_us[w..]).ok_or("no steps measured")?);
    let paced = if args.paced {
        let late_us: Vec<f64> = late_ns.iter().map(|v| *v as f64 / 1e3).collect();
        let late = shift(Summary::of(&late_us[w..]).ok_or("no steps measured")?);
        Some(Paced {
            late_us,
            late,
            overruns,
        })
    } else {
        None
    };
    Ok(Run {
        label: args
            .label
            .clone()
            .unwrap_or_else(|| md.model_identifier.clone()),
        model_identifier: md.model_identifier.clone(),
        steps: n,
        warmup: w,
        step: h,
        inputs: plan.names.clone(),
        outputs: out_vrs.len(),
        wall_us,
        cpu_us,
        wall,
        cpu,
        conditions,
        elapsed_s,
        paced,
    })
}

/// `h` [s] in ms, without trailing zeros.
fn fmt_ms(h: f64) -> String {
    format!("{}", h * 1e3)
}

fn write_csv(path: &Path, run: &Run) -> Result<(), String> {
    let err = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    let mut f = std::io::BufWriter::new(std::fs::File::create(path).map_err(err)?);
    let paced = run.paced.as_ref();
    let late_header = if paced.is_some() { ",late_us" } else { "" };
    writeln!(f, "step,t_s,wall_us,cpu_us,warmup{late_header}").map_err(err)?;
    for k in 0..run.steps {
        write!(
            f,
            "{k},{},{:.3},{:.3},{}",
            k as f64 * run.step,
            run.wall_us[k],
            run.cpu_us[k],
            u8::from(k < run.warmup)
        )
        .map_err(err)?;
        match paced {
            Some(p) => writeln!(f, ",{:.3}", p.late_us[k]),
            None => writeln!(f),
        }
        .map_err(err)?;
    }
    f.flush().map_err(err)
}

fn text(run: &Run) -> String {
    let c = &run.conditions;
    let row = |name: &str, s: &Summary| {
        format!(
            "{name:<10}{:>9.1}{:>9.1}{:>9.1}{:>9.1}{:>9.1}{:>12.2}   (max at step {})\n",
            s.median,
            s.p99,
            s.p999,
            s.p9999,
            s.max,
            s.max_over_median(),
            s.argmax
        )
    };
    let mut out = format!(
        "{} ({}): {} steps of {} ms, statistics over steps {}..{} (warm-up {} excluded)\n\
         inputs set per step: {}; outputs read per step: {}\n\
         {}; thread CPU clock resolution {} ns; loop {:.2} s wall\n\
         during the loop: page faults minor {} major {}, context switches voluntary {} involuntary {}; \
         load average (1 min) {} on {} CPUs\n\n",
        run.label,
        run.model_identifier,
        run.steps,
        fmt_ms(run.step),
        run.warmup,
        run.steps,
        run.warmup,
        run.inputs.join(", "),
        run.outputs,
        c.pin_lock(),
        c.clock_resolution_ns,
        run.elapsed_s,
        c.faults.0,
        c.faults.1,
        c.switches.0,
        c.switches.1,
        c.load.map_or("unknown".to_string(), |l| format!("{l:.2}")),
        os::cpus_online(),
    );
    out.push_str("per step [µs]   median      p99    p99.9   p99.99      max  max/median\n");
    out.push_str(&row("wall", &run.wall));
    out.push_str(&row("CPU", &run.cpu));
    if let Some(p) = &run.paced {
        out.push_str(&row("late", &p.late));
        out.push_str(&format!(
            "(paced: late = wake-up after the period boundary; {} steps ended past their period)\n",
            p.overruns
        ));
    }
    out.push_str(&format!(
        "\nheadroom = step / worst CPU time = {:.2}{}\n",
        run.step * 1e6 / run.cpu.max,
        if run.step * 1e6 < run.cpu.max {
            " (slower than real time at its worst step)"
        } else {
            ""
        }
    ));
    out
}

fn markdown_row(run: &Run) -> String {
    let (w, c) = (&run.wall, &run.cpu);
    format!(
        "| {} | {} | {} | {} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} | {:.2} |",
        run.label,
        run.steps - run.warmup,
        fmt_ms(run.step),
        match &run.paced {
            Some(p) => format!(
                "{} ({} overruns, wake-up late ≤ {:.0} µs)",
                run.conditions.pin_lock(),
                p.overruns,
                p.late.max
            ),
            None => run.conditions.pin_lock(),
        },
        c.median,
        c.p99,
        c.p999,
        c.p9999,
        c.max,
        c.max_over_median(),
        w.median,
        w.p99,
        w.p999,
        w.p9999,
        w.max,
        w.max_over_median(),
        run.step * 1e6 / c.max
    )
}

fn json_summary(s: &Summary) -> String {
    format!(
        "{{\"median\": {}, \"p99\": {}, \"p99_9\": {}, \"p99_99\": {}, \"max\": {}, \"max_step\": {}, \"max_over_median\": {}}}",
        s.median,
        s.p99,
        s.p999,
        s.p9999,
        s.max,
        s.argmax,
        s.max_over_median()
    )
}

/// A JSON string literal of `s`.
fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn json(run: &Run) -> String {
    let c = &run.conditions;
    let locked = match &c.locked {
        None => "null".to_string(),
        Some(Ok(())) => "true".to_string(),
        Some(Err(e)) => json_string(e),
    };
    format!(
        "{{\"label\": {}, \"model_identifier\": {}, \"steps\": {}, \"warmup\": {}, \"step_s\": {}, \"pinned_cpu\": {}, \"fifo\": {}, \"mlock\": {}, \"clock_resolution_ns\": {}, \"page_faults\": [{}, {}], \"context_switches\": [{}, {}], \"load_average\": {}, \"inputs\": [{}], \"outputs\": {}, \"wall_us\": {}, \"cpu_us\": {}, \"paced\": {}, \"headroom\": {}}}",
        json_string(&run.label),
        json_string(&run.model_identifier),
        run.steps,
        run.warmup,
        run.step,
        c.pinned.map_or("null".to_string(), |p| p.to_string()),
        c.fifo.map_or("null".to_string(), |p| p.to_string()),
        locked,
        c.clock_resolution_ns,
        c.faults.0,
        c.faults.1,
        c.switches.0,
        c.switches.1,
        c.load.map_or("null".to_string(), |l| l.to_string()),
        run.inputs
            .iter()
            .map(|s| json_string(s))
            .collect::<Vec<_>>()
            .join(", "),
        run.outputs,
        json_summary(&run.wall),
        json_summary(&run.cpu),
        run.paced.as_ref().map_or("null".to_string(), |p| format!(
            "{{\"late_us\": {}, \"overruns\": {}}}",
            json_summary(&p.late),
            p.overruns
        )),
        run.step * 1e6 / run.cpu.max
    )
}
