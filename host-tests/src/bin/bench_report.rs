//! `bench_report`: the benchmark firmware's logs (one per core) to
//! `bench/results.csv` and `bench/BENCHMARKS.md`, or a check that each log
//! is a complete, well-formed run (`--check`, the test command's smoke run).
//! `scripts/bench.sh` runs it; the format is in `abtrack_host_tests::bench_report`.

use std::path::PathBuf;
use std::process::ExitCode;

use abtrack_host_tests::bench_report::{benchmarks_md, parse_log, results_csv, CoreRun, Report};

const USAGE: &str = "\
usage: bench_report --check LOG...
       bench_report --qemu-version TEXT --rustc-version TEXT --csv FILE --markdown FILE LOG...

Reads the benchmark firmware's output (one log per core, in the order the
tables should show them). --check verifies each is a complete, well-formed
run and prints what it holds; otherwise writes results.csv and BENCHMARKS.md.";

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

fn parse(args: &[String]) -> Result<Command, String> {
    let mut check = false;
    let (mut qemu, mut rustc, mut csv, mut markdown) = (None, None, None, None);
    let mut logs = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .cloned()
                .ok_or_else(|| format!("{name} needs a value"))
        };
        match a.as_str() {
            "--check" => check = true,
            "--qemu-version" => qemu = Some(value(a)?),
            "--rustc-version" => rustc = Some(value(a)?),
            "--csv" => csv = Some(PathBuf::from(value(a)?)),
            "--markdown" => markdown = Some(PathBuf::from(value(a)?)),
            "-h" | "--help" => return Err(String::new()),
            other if other.starts_with("--") => return Err(format!("unknown option {other}")),
            log => logs.push(PathBuf::from(log)),
        }
    }
    if logs.is_empty() {
        return Err("no log given".into());
    }
    if check {
        if qemu.is_some() || rustc.is_some() || csv.is_some() || markdown.is_some() {
            return Err("--check takes logs only".into());
        }
        return Ok(Command::Check(logs));
    }
    match (qemu, rustc, csv, markdown) {
        (Some(qemu_version), Some(rustc_version), Some(csv), Some(markdown)) => {
            Ok(Command::Write {
                qemu_version,
                rustc_version,
                csv,
                markdown,
                logs,
            })
        }
        _ => Err("--qemu-version, --rustc-version, --csv and --markdown are all needed".into()),
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
    let args: Vec<String> = std::env::args().skip(1).collect();
    match parse(&args) {
        Ok(command) => match run(command) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("bench_report: error: {e}");
                ExitCode::from(1)
            }
        },
        Err(e) if e.is_empty() => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bench_report: error: {e}\n{USAGE}");
            ExitCode::from(2)
        }
    }
}
