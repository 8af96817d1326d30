//! `bench_report`: the benchmark firmware's logs (one per core) to
//! `bench/results.csv` and `bench/BENCHMARKS.md`, or a check that each log
//! is a complete, well-formed run (`--check`, the test command's smoke run).
//! `scripts/bench.sh` runs it; the format is in `abtrack_host_tests::bench_report`.

use clap::Parser;
use std::path::PathBuf;
use std::process::ExitCode;

use abtrack_host_tests::bench_report::{benchmarks_md, parse_log, results_csv, CoreRun, Report};

/// The benchmark firmware's logs (one per core, in the order the tables
/// should show them) to results.csv and BENCHMARKS.md, or with --check a
/// check that each is a complete, well-formed run (printing what it holds).
#[derive(Debug, Parser)]
#[command(name = "bench_report")]
struct Cli {
    /// Only check the logs and print what each holds.
    #[arg(long, conflicts_with_all = ["qemu_version", "rustc_version", "csv", "markdown"])]
    check: bool,
    /// The QEMU version the logs were measured with (for BENCHMARKS.md).
    #[arg(long, value_name = "TEXT", required_unless_present = "check")]
    qemu_version: Option<String>,
    /// The rustc version the firmware was built with (for BENCHMARKS.md).
    #[arg(long, value_name = "TEXT", required_unless_present = "check")]
    rustc_version: Option<String>,
    /// Where to write results.csv.
    #[arg(long, value_name = "FILE", required_unless_present = "check")]
    csv: Option<PathBuf>,
    /// Where to write BENCHMARKS.md.
    #[arg(long, value_name = "FILE", required_unless_present = "check")]
    markdown: Option<PathBuf>,
    /// The benchmark firmware's output, one log per core.
    #[arg(value_name = "LOG", required = true)]
    logs: Vec<PathBuf>,
}

enum Command {
    Check(Vec<PathBuf>),
    Write {
        qemu_version: String,
        rustc_version: String,
        csv: PathBuf,
        markdown: PathBuf,
        logs: Vec<PathBuf>,
    },
}

impl Cli {
    fn into_command(self) -> Command {
        match self {
            Cli {
                qemu_version: Some(qemu_version),
                rustc_version: Some(rustc_version),
                csv: Some(csv),
                markdown: Some(markdown),
                logs,
                check: false,
            } => Command::Write {
                qemu_version,
                rustc_version,
                csv,
                markdown,
                logs,
            },
            // clap requires the four without --check and refuses them with it.
            Cli { logs, .. } => Command::Check(logs),
        }
    }
}

fn read_runs(logs: &[PathBuf]) -> Result<Vec<CoreRun>, String> {
    logs.iter()
        .map(|path| {
            let text =
                std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
            parse_log(&text).map_err(|e| format!("{}: {e}", path.display()))
        })
        .collect()
}

fn run(command: Command) -> Result<(), String> {
    match command {
        Command::Check(logs) => {
            let runs = read_runs(&logs)?;
            Report::new(runs.clone()).map_err(|e| e.to_string())?;
            for (path, r) in logs.iter().zip(&runs) {
                println!(
                    "{}: core {}: {} figures, {} counts, complete",
                    path.display(),
                    r.core,
                    r.figures.len(),
                    r.counts.len()
                );
            }
            Ok(())
        }
        Command::Write {
            qemu_version,
            rustc_version,
            csv,
            markdown,
            logs,
        } => {
            let report = Report::new(read_runs(&logs)?).map_err(|e| e.to_string())?;
            let write = |path: &PathBuf, text: String| {
                std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
            };
            write(&csv, results_csv(&report))?;
            write(
                &markdown,
                benchmarks_md(&report, &qemu_version, &rustc_version),
            )?;
            println!("wrote {} and {}", csv.display(), markdown.display());
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    // Usage errors exit with status 2 (clap), failures with 1.
    match run(Cli::parse().into_command()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bench_report: error: {e}");
            ExitCode::from(1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    fn parse(args: &[&str]) -> Result<Command, clap::Error> {
        Cli::try_parse_from(std::iter::once("bench_report").chain(args.iter().copied()))
            .map(Cli::into_command)
    }

    #[test]
    fn command_lines_of_scripts_parse() {
        Cli::command().debug_assert();
        assert!(matches!(
            parse(&["--check", "a.log", "b.log"]),
            Ok(Command::Check(logs)) if logs.len() == 2
        ));
        // scripts/bench.sh
        let Ok(Command::Write {
            qemu_version,
            csv,
            logs,
            ..
        }) = parse(&[
            "--qemu-version",
            "QEMU emulator version 8.2.2",
            "--rustc-version",
            "rustc 1.95.0",
            "--csv",
            "bench/results.csv",
            "--markdown",
            "bench/BENCHMARKS.md",
            "m4f.log",
            "m3.log",
            "m0.log",
        ])
        else {
            panic!("the write command line not parsed")
        };
        assert_eq!(qemu_version, "QEMU emulator version 8.2.2");
        assert_eq!(csv, PathBuf::from("bench/results.csv"));
        assert_eq!(logs.len(), 3);
    }

    #[test]
    fn refuses_bad_command_lines() {
        for args in [
            &[][..],
            &["--check"],
            &["--check", "--csv", "x.csv", "a.log"],
            &["--csv", "x.csv", "a.log"],
            &["--frobnicate", "a.log"],
        ] {
            let e = parse(args).map(|_| ()).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{args:?}: {e}");
        }
    }
}
