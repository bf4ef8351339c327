//! The report generator of hybeam: work-precision (accuracy), the paper's figures (paper) and
//! the stability suite (stability). Writes CSV, SVG and markdown under `docs/`.
//!
//! ```text
//! cargo run --release -p hybeam-report -- accuracy [--quick|--full] [--fresh]
//! cargo run --release -p hybeam-report -- accuracy-plots
//! cargo run --release -p hybeam-report -- paper
//! cargo run --release -p hybeam-report -- stability [--quick|--full]
//! ```
//!
//! `report --help` prints the generated help.

mod accuracy;
mod common;
mod paper;
mod plot;
mod stability;
mod statics;

use clap::{Args, Parser, Subcommand};
use std::process::ExitCode;

/// Regenerate hybeam's reports (docs/accuracy.md, docs/paper-figures.md, docs/stability.md and
/// their CSV/SVG under docs/report/).
#[derive(Debug, Parser)]
#[command(name = "report", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Work-precision (Cases 1-3, soft rod, spatial Case 1 beside planar Case 1), cost per step
    /// and static references -> docs/accuracy.md.
    Accuracy {
        #[command(flatten)]
        depth: Depth,
        /// Recompute the cached references under target/report-cache/.
        #[arg(long)]
        fresh: bool,
    },
    /// Redraw the work-precision figures (docs/report/accuracy_*.svg) from the CSV files of the
    /// last `accuracy` run, running nothing.
    AccuracyPlots,
    /// The paper's figures (Cases 1-3, planar and spatial, and the spatial strip) ->
    /// docs/paper-figures.md.
    Paper,
    /// Extreme cases, planar and spatial -> docs/stability.md.
    Stability {
        #[command(flatten)]
        depth: Depth,
    },
}

/// How much to run: `--quick` (the default) or `--full`.
#[derive(Debug, Args)]
struct Depth {
    /// Short sweeps, one repetition (the default).
    #[arg(long, conflicts_with = "full")]
    quick: bool,
    /// Complete run: denser sweeps and the median of 3 runs (accuracy), the long variants
    /// (stability). Slow.
    #[arg(long)]
    full: bool,
}

fn main() -> ExitCode {
    let r = match Cli::parse().command {
        Command::Accuracy { depth, fresh } => accuracy::run(&accuracy::Opts {
            quick: !depth.full,
            fresh,
        }),
        Command::AccuracyPlots => accuracy::replot(),
        Command::Paper => paper::run(),
        Command::Stability { depth } => stability::run(!depth.full),
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

    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        Cli::try_parse_from(std::iter::once("report").chain(args.iter().copied()))
    }

    #[test]
    fn parses_the_documented_invocations() {
        let full = |args: &[&str]| match parse(args).unwrap().command {
            Command::Accuracy { depth, .. } | Command::Stability { depth } => depth.full,
            Command::Paper | Command::AccuracyPlots => panic!("{args:?}: not a depth command"),
        };
        assert!(!full(&["accuracy"]));
        assert!(!full(&["accuracy", "--quick"]));
        assert!(full(&["accuracy", "--full", "--fresh"]));
        assert!(!full(&["stability", "--quick"]));
        assert!(full(&["stability", "--full"]));
        assert!(matches!(
            parse(&["accuracy", "--fresh"]).unwrap().command,
            Command::Accuracy { fresh: true, .. }
        ));
        assert!(matches!(parse(&["paper"]).unwrap().command, Command::Paper));
        assert!(matches!(
            parse(&["accuracy-plots"]).unwrap().command,
            Command::AccuracyPlots
        ));
    }

    #[test]
    fn rejects_bad_command_lines() {
        for bad in [
            &[][..],
            &["accuracy", "--quick", "--full"],
            &["stability", "--fresh"],
            &["paper", "--full"],
            &["accuracy-plots", "--quick"],
            &["accuracy", "--bogus"],
            &["figures"],
        ] {
            assert!(parse(bad).is_err(), "{bad:?} accepted");
        }
    }
}
