//! The report generator of hybeam: work-precision (accuracy), the paper's figures (paper) and
//! the stability suite (stability). Writes CSV, SVG and markdown under `docs/`.
//!
//! ```text
//! cargo run --release --bin report -- accuracy [--quick|--full] [--fresh]
//! cargo run --release --bin report -- paper
//! cargo run --release --bin report -- stability [--quick|--full]
//! ```

mod accuracy;
mod common;
mod paper;
mod plot;
mod stability;
mod statics;

use std::process::ExitCode;

const USAGE: &str = "usage:
  report accuracy [--quick|--full] [--fresh]   work-precision, cost per step, statics -> docs/accuracy.md
  report paper                                  paper figures (Cases 1-3) -> docs/paper-figures.md
  report stability [--quick|--full]             extreme cases -> docs/stability.md
(--fresh recomputes the cached references under target/report-cache/)";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |f: &str| args.iter().any(|a| a == f);
    let quick = !flag("--full");
    if let Some(bad) = args
        .iter()
        .skip(1)
        .find(|a| !["--quick", "--full", "--fresh"].contains(&a.as_str()))
    {
        eprintln!("error: unknown option {bad}\n{USAGE}");
        return ExitCode::from(2);
    }
    let r = match args.first().map(String::as_str) {
        Some("accuracy") => accuracy::run(&accuracy::Opts {
            quick,
            fresh: flag("--fresh"),
        }),
        Some("paper") => paper::run(),
        Some("stability") => stability::run(quick),
        _ => {
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
