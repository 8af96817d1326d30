//! Prints the measured deviation of the f32 and fixed-point filters from the
//! independent f64 reference on the documented runs
//! (`abtrack_host_tests::precision::documented_runs`), next to the error
//! budget for each run and the ratio budget / measured maximum.
//!
//! `cd host-tests && cargo run --release --bin precision`
//! (from the repository root: `cargo run --release --manifest-path
//! host-tests/Cargo.toml --target host-tuple --bin precision`).

use abtrack::{Fix, Scalar};
use abtrack_host_tests::output::write_stdout;
use abtrack_host_tests::precision::{documented_runs, measure_documented, DocumentedRun};
use clap::Parser;
use std::fmt::Write as _;
use std::process::ExitCode;

/// Prints the deviation of the f32 and Q32.32 filters from the independent
/// f64 reference on the documented runs, next to the error budget (a
/// Markdown table on stdout; exit status 1 if a run exceeds its budget).
#[derive(Debug, Parser)]
#[command(name = "precision")]
struct PrecisionArgs {}

fn row<S: Scalar>(out: &mut String, run: &DocumentedRun) -> Result<bool, String> {
    let report = measure_documented::<S>(run)?;
    let d = &report.deviation;
    let rms = d.rms();
    let axes = if run.order == 3 { 3 } else { 2 };
    let mut cells = Vec::new();
    let mut within = report.refused == 0;
    let budget = match report.budget {
        Ok(b) => Some([b.position, b.velocity, b.acceleration]),
        Err(e) => {
            within = false;
            eprintln!("{}: no budget for {}: {e}", run.name, S::NAME);
            None
        }
    };
    for i in 0..axes {
        let (b, ratio) = match budget {
            Some(b) => {
                within &= d.max[i] <= b[i];
                (format!("{:.2e}", b[i]), format!("{:.0}", b[i] / d.max[i]))
            }
            None => ("-".into(), "-".into()),
        };
        cells.push(format!(
            "{:.2e} | {:.2e} | {} | {}",
            d.max[i], rms[i], b, ratio
        ));
    }
    if axes == 2 {
        cells.push("- | - | - | -".into());
    }
    let _ = writeln!(
        out,
        "| {} | {} | {} | {} |",
        run.name,
        S::NAME,
        cells.join(" | "),
        if within { "yes" } else { "NO" }
    );
    Ok(within)
}

fn main() -> ExitCode {
    PrecisionArgs::parse();
    let mut out = String::new();
    out.push_str("Deviation from the f64 reference over 10 000 updates (max, RMS), error budget and budget/max.\n");
    out.push_str(
        "x in m, v in m/s, a in m/s². Budget: abtrack::budget::error_budget_around_reference.\n\n",
    );
    let runs = documented_runs();
    for run in &runs {
        let _ = writeln!(out, "* {}: {}", run.name, run.description);
    }
    out.push('\n');
    out.push_str("| run | numeric | max Δx | RMS Δx | budget x | ratio | max Δv | RMS Δv | budget v | ratio | max Δa | RMS Δa | budget a | ratio | within |\n");
    out.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let mut ok = true;
    for run in &runs {
        for result in [row::<f32>(&mut out, run), row::<Fix>(&mut out, run)] {
            match result {
                Ok(within) => ok &= within,
                Err(e) => {
                    eprintln!("{}: {e}", run.name);
                    ok = false;
                }
            }
        }
    }
    let written = write_stdout("precision", out.as_bytes());
    if ok {
        written
    } else {
        eprintln!("some run exceeded its budget or could not be bounded");
        ExitCode::FAILURE
    }
}
