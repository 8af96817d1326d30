//! `simulate`: writes one seeded run of a scenario as CSV files.
//!
//! ```text
//! simulate --scenario NAME [--seed N] --out-dir DIR
//! simulate --list
//! simulate --help
//! ```
//!
//! Writes `DIR/measurements.csv` (the `replay` input format) and
//! `DIR/truth.csv`; the formats are documented in
//! `abtrack_host_tests::scenario`. The same scenario and seed always give
//! byte-identical files.

use abtrack_host_tests::scenario::{self, SCENARIO_NAMES};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "\
simulate: write one seeded run of a tracking scenario as CSV

USAGE:
    simulate --scenario NAME [--seed N] --out-dir DIR
    simulate --list
    simulate --help

OPTIONS:
    --scenario NAME   scenario to generate (see --list)
    --seed N          unsigned 64-bit seed of the noise, detections, clutter and
                      row order (default 0); the truth does not depend on it
    --out-dir DIR     directory for measurements.csv and truth.csv (created if
                      missing; existing files are overwritten)
    --list            list the scenarios with a one-line description
    -h, --help        this text

OUTPUT:
    measurements.csv  t,x,y (Cartesian) or t,range,azimuth[,alt] (polar: range m,
                      azimuth rad clockwise from +y, alt = Mode C feet, empty when
                      not reported); several rows share t in multi-target scenarios
    truth.csv         t,x,y,vx,vy; multi-target scenarios add a target column after
                      t; polar scenarios add range,azimuth,range_rate,tau; scenarios
                      with altitude add alt,own_alt (feet)
";

/// What went wrong, and the exit code it maps to.
#[derive(Debug, PartialEq)]
enum CliError {
    /// Bad command line: exit 2.
    Usage(String),
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
    fn message(&self) -> &str {
        match self {
            CliError::Usage(m) | CliError::Io(m) => m,
        }
    }
}

#[derive(Debug, PartialEq)]
enum Command {
    Help,
    List,
    Generate {
        scenario: String,
        seed: u64,
        out_dir: PathBuf,
    },
}

fn parse(args: &[String]) -> Result<Command, CliError> {
    let mut scenario = None;
    let mut seed = None;
    let mut out_dir = None;
    let mut list = false;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let (key, inline) = match arg.split_once('=') {
            Some((k, v)) if k.starts_with("--") => (k, Some(v.to_string())),
            _ => (arg.as_str(), None),
        };
        let mut value = |name: &str| -> Result<String, CliError> {
            match inline.clone().or_else(|| it.next().cloned()) {
                Some(v) if !v.is_empty() => Ok(v),
                _ => Err(CliError::Usage(format!("{name} needs a value"))),
            }
        };
        match key {
            "-h" | "--help" => return Ok(Command::Help),
            "--list" => list = true,
            "--scenario" => scenario = Some(value("--scenario")?),
            "--seed" => {
                let v = value("--seed")?;
                seed = Some(v.parse::<u64>().map_err(|_| {
                    CliError::Usage(format!(
                        "--seed must be an unsigned 64-bit integer, got '{v}'"
                    ))
                })?);
            }
            "--out-dir" => out_dir = Some(PathBuf::from(value("--out-dir")?)),
            other => {
                return Err(CliError::Usage(format!(
                    "unknown argument '{other}' (try --help)"
                )))
            }
        }
    }
    if list {
        return Ok(Command::List);
    }
    let scenario = scenario
        .ok_or_else(|| CliError::Usage("--scenario NAME is required (see --list)".into()))?;
    if scenario::info(&scenario).is_none() {
        return Err(CliError::Usage(format!(
            "unknown scenario '{scenario}' (known: {})",
            SCENARIO_NAMES.join(", ")
        )));
    }
    let out_dir = out_dir.ok_or_else(|| CliError::Usage("--out-dir DIR is required".into()))?;
    Ok(Command::Generate {
        scenario,
        seed: seed.unwrap_or(0),
        out_dir,
    })
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

/// Runs the command line `args` (without the program name), writing normal
/// output to `out`.
fn run(args: &[String], out: &mut dyn Write) -> Result<(), CliError> {
    let io = |e: std::io::Error| CliError::Io(format!("cannot write to stdout: {e}"));
    match parse(args)? {
        Command::Help => out.write_all(USAGE.as_bytes()).map_err(io),
        Command::List => out.write_all(list_text().as_bytes()).map_err(io),
        Command::Generate {
            scenario,
            seed,
            out_dir,
        } => {
            let run =
                scenario::generate(&scenario, seed).map_err(|e| CliError::Usage(e.to_string()))?;
            std::fs::create_dir_all(&out_dir)
                .map_err(|e| CliError::Io(format!("cannot create {}: {e}", out_dir.display())))?;
            let measurements = out_dir.join("measurements.csv");
            let truth = out_dir.join("truth.csv");
            write_file(&measurements, &run.measurements_csv())?;
            write_file(&truth, &run.truth_csv())?;
            writeln!(
                out,
                "{scenario} seed {seed}: {} scans, {} measurements -> {}, {} truth rows -> {}",
                run.scans.len(),
                run.measurements().count(),
                measurements.display(),
                run.truth().count(),
                truth.display()
            )
            .map_err(io)
        }
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let stdout = std::io::stdout();
    match run(&args, &mut stdout.lock()) {
        Ok(()) => ExitCode::SUCCESS,
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
        assert!(String::from_utf8(out).unwrap().contains("--out-dir DIR"));
    }

    #[test]
    fn errors_are_clear() {
        let err = |a: &[&str]| run(&args(a), &mut Vec::new()).unwrap_err();
        let e = err(&["--scenario", "nope", "--out-dir", "x"]);
        assert_eq!(e.exit_code(), 2);
        assert!(
            e.message().contains("unknown scenario 'nope'") && e.message().contains("li-maneuver")
        );
        assert!(err(&[
            "--scenario",
            "li-maneuver",
            "--seed",
            "-1",
            "--out-dir",
            "x"
        ])
        .message()
        .contains("--seed must be an unsigned"));
        assert!(err(&["--scenario", "li-maneuver"])
            .message()
            .contains("--out-dir DIR is required"));
        assert!(err(&["--out-dir", "x"])
            .message()
            .contains("--scenario NAME is required"));
        assert!(err(&["--seed"]).message().contains("--seed needs a value"));
        assert!(err(&["--frobnicate"])
            .message()
            .contains("unknown argument '--frobnicate'"));
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
