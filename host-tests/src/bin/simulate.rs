//! `simulate`: writes one seeded run of a scenario as CSV files.
//!
//! ```text
//! simulate --scenario NAME [--seed N] --out-dir DIR
//! simulate --list
//! simulate --help
//! ```
//!
//! A closed stdout (`simulate --list | head -1`) ends it quietly with status
//! 0.
//!
//! Writes `DIR/measurements.csv` (the `replay` input format) and
//! `DIR/truth.csv`; the formats are documented in
//! `abtrack_host_tests::scenario`. The same scenario and seed always give
//! byte-identical files.

use abtrack_host_tests::output::write_all_or_closed;
use abtrack_host_tests::scenario::{self, SCENARIO_NAMES};
use clap::error::ErrorKind;
use clap::Parser;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Writes one seeded run of a tracking scenario as CSV: DIR/measurements.csv
/// (the replay input format) and DIR/truth.csv.
#[derive(Debug, Parser)]
#[command(
    name = "simulate",
    after_help = "Output:\n  \
    measurements.csv  t,x,y (Cartesian) or t,range,azimuth[,alt] (polar: range m, azimuth\n                    \
    rad clockwise from +y, alt = Mode C feet, empty when not reported);\n                    \
    several rows share t in multi-target scenarios\n  \
    truth.csv         t,x,y,vx,vy; multi-target scenarios add a target column after t;\n                    \
    polar scenarios add range,azimuth,range_rate,tau; scenarios with altitude\n                    \
    add alt,own_alt (feet)"
)]
struct SimulateArgs {
    /// Scenario to generate (see --list).
    #[arg(
        long,
        value_name = "NAME",
        value_parser = clap::builder::PossibleValuesParser::new(SCENARIO_NAMES),
        hide_possible_values = true,
        required_unless_present = "list"
    )]
    scenario: Option<String>,
    /// Seed of the noise, detections, clutter and row order; the truth does
    /// not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    seed: u64,
    /// Directory for measurements.csv and truth.csv (created if missing;
    /// existing files are overwritten).
    #[arg(long, value_name = "DIR", required_unless_present = "list")]
    out_dir: Option<PathBuf>,
    /// List the scenarios with a one-line description.
    #[arg(long)]
    list: bool,
}

/// What went wrong, and the exit code it maps to.
#[derive(Debug)]
enum CliError {
    /// Bad command line: exit 2 (clap's message).
    Usage(clap::Error),
    /// Could not write the output: exit 1.
    Io(String),
}

impl CliError {
    fn exit_code(&self) -> u8 {
        match self {
            CliError::Usage(_) => 2,
            CliError::Io(_) => 1,
        }
    }
    fn message(&self) -> String {
        match self {
            CliError::Usage(e) => e.to_string(),
            CliError::Io(m) => m.clone(),
        }
    }
}

fn list_text() -> String {
    let width = SCENARIO_NAMES.iter().map(|n| n.len()).max().unwrap_or(0);
    scenario::scenarios()
        .iter()
        .map(|s| format!("{:width$}  {}\n", s.name, s.description))
        .collect()
}

fn write_file(path: &Path, contents: &str) -> Result<(), CliError> {
    std::fs::write(path, contents)
        .map_err(|e| CliError::Io(format!("cannot write {}: {e}", path.display())))
}

/// Writes `text` to `out`; a closed pipe is not an error (the reader took
/// what it wanted).
fn emit(out: &mut dyn Write, text: &str) -> Result<(), CliError> {
    write_all_or_closed(out, text.as_bytes())
        .map(|_| ())
        .map_err(|e| CliError::Io(format!("cannot write to stdout: {e}")))
}

/// Runs the command line `args` (without the program name), writing normal
/// output to `out`.
fn run(args: &[String], out: &mut dyn Write) -> Result<(), CliError> {
    let parsed = match SimulateArgs::try_parse_from(
        std::iter::once("simulate".to_string()).chain(args.iter().cloned()),
    ) {
        Ok(p) => p,
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => {
            return emit(out, &e.render().to_string());
        }
        Err(e) => return Err(CliError::Usage(e)),
    };
    if parsed.list {
        return emit(out, &list_text());
    }
    let (Some(scenario), Some(out_dir)) = (parsed.scenario, parsed.out_dir) else {
        unreachable!("clap requires --scenario and --out-dir without --list")
    };
    let seed = parsed.seed;
    let run = scenario::generate(&scenario, seed)
        .map_err(|e| CliError::Io(format!("{scenario}: {e}")))?;
    std::fs::create_dir_all(&out_dir)
        .map_err(|e| CliError::Io(format!("cannot create {}: {e}", out_dir.display())))?;
    let measurements = out_dir.join("measurements.csv");
    let truth = out_dir.join("truth.csv");
    write_file(&measurements, &run.measurements_csv())?;
    write_file(&truth, &run.truth_csv())?;
    emit(
        out,
        &format!(
            "{scenario} seed {seed}: {} scans, {} measurements -> {}, {} truth rows -> {}\n",
            run.scans.len(),
            run.measurements().count(),
            measurements.display(),
            run.truth().count(),
            truth.display()
        ),
    )
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let stdout = std::io::stdout();
    match run(&args, &mut stdout.lock()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Usage(e)) => e.exit(),
        Err(e) => {
            eprintln!("simulate: error: {}", e.message());
            ExitCode::from(e.exit_code())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &[&str]) -> Vec<String> {
        s.iter().map(|a| a.to_string()).collect()
    }

    /// A fresh directory under the system temp dir, removed on drop.
    struct TempDir(PathBuf);
    impl TempDir {
        fn new(tag: &str) -> Self {
            let p =
                std::env::temp_dir().join(format!("abtrack-simulate-{}-{tag}", std::process::id()));
            let _ = std::fs::remove_dir_all(&p);
            TempDir(p)
        }
        fn read(&self, file: &str) -> String {
            std::fs::read_to_string(self.0.join(file)).unwrap()
        }
    }
    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    fn simulate(scenario: &str, seed: &str, dir: &TempDir) {
        let dir = dir.0.to_str().unwrap();
        let mut out = Vec::new();
        run(
            &args(&["--scenario", scenario, "--seed", seed, "--out-dir", dir]),
            &mut out,
        )
        .unwrap();
        assert!(String::from_utf8(out).unwrap().starts_with(scenario));
    }

    #[test]
    fn same_seed_gives_identical_files() {
        for name in [
            "li-maneuver",
            "alwagih-cv-coloured",
            "tcas-30",
            "two-crossing",
        ] {
            let (a, b, c) = (
                TempDir::new(&format!("{name}-a")),
                TempDir::new(&format!("{name}-b")),
                TempDir::new(&format!("{name}-c")),
            );
            simulate(name, "7", &a);
            simulate(name, "7", &b);
            simulate(name, "8", &c);
            for f in ["measurements.csv", "truth.csv"] {
                assert_eq!(a.read(f), b.read(f), "{name} {f}");
            }
            assert_ne!(
                a.read("measurements.csv"),
                c.read("measurements.csv"),
                "{name}"
            );
            assert_eq!(a.read("truth.csv"), c.read("truth.csv"), "{name}");
        }
    }

    #[test]
    fn li_maneuver_files() {
        let d = TempDir::new("li");
        simulate("li-maneuver", "1", &d);
        let m = d.read("measurements.csv");
        let t = d.read("truth.csv");
        assert_eq!(m.lines().next(), Some("t,x,y"));
        assert_eq!(m.lines().count(), 101);
        assert_eq!(t.lines().next(), Some("t,x,y,vx,vy"));
        // Hand-integrated final state (see scenario tests): every increment is
        // a multiple of 0.25, so the f64 sums are exact.
        assert_eq!(t.lines().last(), Some("99,1728.75,0.25,12.5,-16.5"));
        assert_eq!(t.lines().nth(1), Some("0,0,0,10,5"));
    }

    #[test]
    fn polar_and_multi_target_headers() {
        let cases = [
            (
                "he-tcas",
                "t,range,azimuth",
                "t,x,y,vx,vy,range,azimuth,range_rate,tau",
            ),
            (
                "tcas-converging",
                "t,range,azimuth,alt",
                "t,x,y,vx,vy,range,azimuth,range_rate,tau,alt,own_alt",
            ),
            ("parallel-200m", "t,x,y", "t,target,x,y,vx,vy"),
            ("dense", "t,x,y", "t,target,x,y,vx,vy"),
        ];
        for (name, mh, th) in cases {
            let d = TempDir::new(name);
            simulate(name, "3", &d);
            assert_eq!(d.read("measurements.csv").lines().next(), Some(mh));
            assert_eq!(d.read("truth.csv").lines().next(), Some(th));
        }
        // Multi-target: several rows share a t.
        let d = TempDir::new("dense-rows");
        simulate("dense", "3", &d);
        let m = d.read("measurements.csv");
        let at0 = m.lines().skip(1).filter(|l| l.starts_with("0,")).count();
        assert!(at0 > 50, "{at0} rows at t = 0");
    }

    #[test]
    fn list_and_help() {
        let mut out = Vec::new();
        run(&args(&["--list"]), &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        for name in SCENARIO_NAMES {
            assert!(
                text.lines().any(|l| l.starts_with(name)),
                "{name} missing from --list"
            );
        }
        assert_eq!(text.lines().count(), SCENARIO_NAMES.len());
        let mut out = Vec::new();
        run(&args(&["--help"]), &mut out).unwrap();
        let help = String::from_utf8(out).unwrap();
        assert!(help.contains("--out-dir <DIR>"), "{help}");
    }

    #[test]
    fn errors_are_clear() {
        let err = |a: &[&str]| run(&args(a), &mut Vec::new()).unwrap_err();
        let e = err(&["--scenario", "nope", "--out-dir", "x"]);
        assert_eq!(e.exit_code(), 2);
        assert!(
            e.message().contains("invalid value 'nope'") && e.message().contains("--scenario"),
            "{}",
            e.message()
        );
        let e = err(&[
            "--scenario",
            "li-maneuver",
            "--seed",
            "x1",
            "--out-dir",
            "x",
        ]);
        assert_eq!(e.exit_code(), 2);
        assert!(e.message().contains("--seed"), "{}", e.message());
        assert!(err(&["--scenario", "li-maneuver"])
            .message()
            .contains("--out-dir <DIR>"));
        assert!(err(&["--out-dir", "x"])
            .message()
            .contains("--scenario <NAME>"));
        assert!(err(&["--seed"]).message().contains("--seed <N>"));
        assert!(err(&["--frobnicate"])
            .message()
            .contains("unexpected argument '--frobnicate'"));
        assert!(err(&[]).message().contains("--scenario"));
        // --key=value form.
        let d = TempDir::new("eq");
        let dir = format!("--out-dir={}", d.0.display());
        run(
            &args(&["--scenario=liu-turn", "--seed=4", &dir]),
            &mut Vec::new(),
        )
        .unwrap();
        assert_eq!(d.read("measurements.csv").lines().count(), 81);
        // An output path that cannot be a directory: I/O error, exit 1.
        let blocker = TempDir::new("blocker");
        std::fs::write(&blocker.0, "a file").unwrap();
        let e = err(&[
            "--scenario",
            "li-maneuver",
            "--out-dir",
            blocker.0.to_str().unwrap(),
        ]);
        assert_eq!(e.exit_code(), 1);
        assert!(e.message().contains("cannot create"));
        let _ = std::fs::remove_file(&blocker.0);
    }
}
