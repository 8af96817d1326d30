//! Prints the measured deviation of the f32, Q32.32 (`q32`) and fast
//! fixed-point (`fixed`, `Fixed32`) filters from the independent f64
//! reference on the documented runs
//! (`abtrack_host_tests::precision::documented_runs`), next to the error
//! budget for each run and the ratio budget / measured maximum; then, per
//! run, how many times closer to f64 than f32 the fast fixed point is
//! (the target is at least 10 in position, velocity and acceleration).
//!
//! `cd host-tests && cargo run --release --bin precision > ../results/precision.md`
//! (from the repository root: `cargo run --release --manifest-path
//! host-tests/Cargo.toml --target host-tuple --bin precision`).

use abtrack::num::Numeric;
use abtrack::{Fix, Fixed32};
use abtrack_host_tests::output::write_stdout;
use abtrack_host_tests::precision::{
    documented_runs, measure_documented, DocumentedRun, RunReport,
};
use clap::Parser;
use std::fmt::Write as _;
use std::process::ExitCode;

/// Prints the deviation of the f32, Q32.32 and fast fixed-point filters from
/// the independent f64 reference on the documented runs, next to the error
/// budget, and how many times closer than f32 the fast fixed point is (a
/// Markdown report on stdout; exit status 1 if a run exceeds its budget or
/// misses the closeness target).
#[derive(Debug, Parser)]
#[command(name = "precision")]
struct PrecisionArgs {}

/// The closeness asked of the fast fixed point: f32's deviation over
/// the fixed point's, at least this on every run and quantity.
const CLOSER_THAN_F32: f64 = 10.0;

fn row<N: Numeric>(out: &mut String, run: &DocumentedRun, report: &RunReport) -> bool {
    let d = &report.deviation;
    let rms = d.rms();
    let axes = if run.order == 3 { 3 } else { 2 };
    let mut cells = Vec::new();
    let mut within = report.refused == 0;
    let budget = match report.budget {
        Ok(b) => Some([b.position, b.velocity, b.acceleration]),
        Err(e) => {
            within = false;
            eprintln!("{}: no budget for {}: {e}", run.name, N::NAME);
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
    if report.refused > 0 {
        eprintln!(
            "{}: {} refused {} updates",
            run.name,
            N::NAME,
            report.refused
        );
    }
    let _ = writeln!(
        out,
        "| {} | {} | {} | {} |",
        run.name,
        N::NAME,
        cells.join(" | "),
        if within { "yes" } else { "NO" }
    );
    within
}

fn main() -> ExitCode {
    PrecisionArgs::parse();
    let mut out = String::new();
    out.push_str("Deviation from the f64 reference over 10 000 updates (max, RMS), error budget and budget/max.\n");
    out.push_str(
        "x in m, v in m/s, a in m/s². Budget: abtrack::budget::error_budget_around_reference.\n",
    );
    out.push_str(
        "Numerics: f32; q32 = Q32.32 (abtrack::Fix); fixed = the fast fixed point (abtrack::Fixed32).\n\n",
    );
    let runs = documented_runs();
    for run in &runs {
        let _ = writeln!(out, "* {}: {}", run.name, run.description);
    }
    out.push('\n');
    out.push_str("| run | numeric | max Δx | RMS Δx | budget x | ratio | max Δv | RMS Δv | budget v | ratio | max Δa | RMS Δa | budget a | ratio | within |\n");
    out.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let mut ok = true;
    let mut closeness = Vec::new();
    for run in &runs {
        let reports = (
            measure_documented::<f32>(run),
            measure_documented::<Fix>(run),
            measure_documented::<Fixed32>(run),
        );
        match reports {
            (Ok(f32_report), Ok(q32_report), Ok(fixed_report)) => {
                ok &= row::<f32>(&mut out, run, &f32_report);
                ok &= row::<Fix>(&mut out, run, &q32_report);
                ok &= row::<Fixed32>(&mut out, run, &fixed_report);
                closeness.push((run, f32_report, fixed_report));
            }
            (a, b, c) => {
                for e in [a.err(), b.err(), c.err()].into_iter().flatten() {
                    eprintln!("{}: {e}", run.name);
                }
                ok = false;
            }
        }
    }
    let _ = writeln!(
        out,
        "\nHow many times closer to f64 the fast fixed point is than f32 (f32 max / fixed max; the target is ≥ {CLOSER_THAN_F32:.0}):\n"
    );
    let _ = writeln!(out, "| run | x | v | a | ≥ {CLOSER_THAN_F32:.0} |");
    out.push_str("|---|---|---|---|---|\n");
    for (run, f32_report, fixed_report) in &closeness {
        let axes = if run.order == 3 { 3 } else { 2 };
        let mut cells = Vec::new();
        let mut enough = true;
        for i in 0..3 {
            if i < axes {
                let ratio = f32_report.deviation.max[i] / fixed_report.deviation.max[i];
                enough &= ratio >= CLOSER_THAN_F32;
                cells.push(format!("{ratio:.0}"));
            } else {
                cells.push("-".into());
            }
        }
        if !enough {
            eprintln!(
                "{}: the fast fixed point is less than {CLOSER_THAN_F32}x closer to f64 than f32",
                run.name
            );
        }
        let _ = writeln!(
            out,
            "| {} | {} | {} |",
            run.name,
            cells.join(" | "),
            if enough { "yes" } else { "NO" }
        );
        ok &= enough;
    }
    let written = write_stdout("precision", out.as_bytes());
    if ok {
        written
    } else {
        eprintln!(
            "some run exceeded its budget, could not be bounded, or missed the closeness target"
        );
        ExitCode::FAILURE
    }
}
