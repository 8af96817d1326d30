//! Runs the papers' experiments and writes tables, plots and summaries under
//! `results/` (see `abtrack_host_tests::experiments`).
//!
//! ```text
//! cd host-tests && cargo run --release --bin experiments -- [--only G1,G2] [--runs N] [--out DIR]
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use abtrack_host_tests::experiments::{common::Context, GROUPS};
use clap::Parser;

/// The groups' names and descriptions for `--help`.
fn groups_help() -> String {
    let mut s = String::from("Groups:\n");
    for g in GROUPS {
        s.push_str(&format!("  {:<16} {}\n", g.name, g.about));
    }
    s
}

/// Reproduces the papers' experiments: writes CSV/Markdown tables, SVG plots
/// and a summary.md per group under DIR.
#[derive(Debug, Parser)]
#[command(name = "experiments", after_help = groups_help())]
struct ExperimentsArgs {
    /// Run only these groups (comma-separated).
    #[arg(
        long,
        value_name = "GROUP[,GROUP...]",
        value_delimiter = ',',
        value_parser = clap::builder::PossibleValuesParser::new(GROUPS.iter().map(|g| g.name)),
        hide_possible_values = true
    )]
    only: Vec<String>,
    /// Override every group's documented Monte Carlo run count (at least 2).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(2..))]
    runs: Option<u64>,
    /// Output directory (default: the repository's results/).
    #[arg(long, value_name = "DIR", default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../results"))]
    out: PathBuf,
}

fn main() -> ExitCode {
    let args = ExperimentsArgs::parse();
    let ctx = Context {
        out_dir: args.out,
        runs_override: args.runs.map(|n| n as usize),
    };
    let only = (!args.only.is_empty()).then_some(args.only);
    let mut failed = false;
    for g in GROUPS
        .iter()
        .filter(|g| only.as_ref().is_none_or(|o| o.iter().any(|n| n == g.name)))
    {
        eprintln!("experiments: running {} ...", g.name);
        let start = std::time::Instant::now();
        match (g.run)(&ctx) {
            Ok(()) => eprintln!(
                "experiments: {} done in {:.1} s",
                g.name,
                start.elapsed().as_secs_f64()
            ),
            Err(e) => {
                eprintln!("experiments: {} failed: {e}", g.name);
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
