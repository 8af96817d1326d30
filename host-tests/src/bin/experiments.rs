//! Runs the papers' experiments and writes tables, plots and summaries under
//! `results/` (see `abtrack_host_tests::experiments`).
//!
//! ```text
//! cd host-tests && cargo run --release --bin experiments -- [--only G1,G2] [--runs N] [--out DIR]
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use abtrack_host_tests::experiments::{common::Context, GROUPS};

fn usage() -> String {
    let mut s = String::from(
        "usage: experiments [--only GROUP[,GROUP...]] [--runs N] [--out DIR]\n\n\
         Reproduces the papers' experiments; writes CSV/Markdown tables, SVG plots and a\n\
         summary.md per group under DIR (default: ../results, the repository's results folder).\n\
         --runs N overrides every group's documented Monte Carlo run count.\n\ngroups:\n",
    );
    for g in GROUPS {
        s.push_str(&format!("  {:<16} {}\n", g.name, g.about));
    }
    s
}

fn main() -> ExitCode {
    let mut only: Option<Vec<String>> = None;
    let mut ctx = Context {
        out_dir: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../results")),
        runs_override: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |name: &str| args.next().ok_or_else(|| format!("{name} needs a value"));
        let r = match a.as_str() {
            "--only" => {
                value("--only").map(|v| only = Some(v.split(',').map(str::to_owned).collect()))
            }
            "--runs" => value("--runs").and_then(|v| match v.parse::<usize>() {
                Ok(n) if n >= 2 => {
                    ctx.runs_override = Some(n);
                    Ok(())
                }
                _ => Err(format!("--runs takes a whole number >= 2, not {v:?}")),
            }),
            "--out" => value("--out").map(|v| ctx.out_dir = PathBuf::from(v)),
            "-h" | "--help" => {
                print!("{}", usage());
                return ExitCode::SUCCESS;
            }
            other => Err(format!("unknown argument {other:?}")),
        };
        if let Err(e) = r {
            eprintln!("experiments: error: {e}\n\n{}", usage());
            return ExitCode::from(2);
        }
    }
    if let Some(names) = &only {
        if let Some(bad) = names
            .iter()
            .find(|n| !GROUPS.iter().any(|g| g.name == n.as_str()))
        {
            eprintln!("experiments: error: no group named {bad:?}\n\n{}", usage());
            return ExitCode::from(2);
        }
    }
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
