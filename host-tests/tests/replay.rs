//! The `replay` tool: CSV errors name their line (and column), the output is
//! the library's arithmetic, the command line is checked, and the binary runs
//! end to end.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command as Process, Stdio};

use abtrack::filter::{Cartesian, Gains, UpdateOutcome};
use abtrack::{FilterError, Fix, GainError, Scalar};
use abtrack_host_tests::cli::{parse_replay_args, Command, Input, UsageError};
use abtrack_host_tests::csv_input::{read_measurements, CsvError};
use abtrack_host_tests::replay::{header, run, FilterKind, Numeric, ReplayConfig, ReplayError};

fn read(text: &str) -> Result<abtrack_host_tests::csv_input::Measurements, CsvError> {
    read_measurements(text.as_bytes())
}

// ------------------------------------------------------------- CSV reader

#[test]
fn accepts_the_three_headers_and_tolerant_spacing() {
    for (text, dims) in [
        ("t,x\n0,1\n", 1),
        ("t,x,y\n0,1,2\n", 2),
        ("t,x,y,z\n0,1,2,3\n", 3),
        ("\u{feff}t , x\r\n0 , 1\r\n\r\n1,2\n", 1),
    ] {
        let m = read(text).unwrap();
        assert_eq!(m.dims, dims, "{text:?}");
        assert_eq!(m.rows[0].t_text, "0");
    }
    let m = read("t,x\n\n0.5,1e3\n\n2,-4\n").unwrap();
    assert_eq!(m.rows.len(), 2);
    assert_eq!(
        (m.rows[1].line, m.rows[1].t, m.rows[1].z[0]),
        (5, 2.0, -4.0)
    );
}

#[test]
fn errors_name_the_line_and_column() {
    let cases: [(&str, CsvError, &str); 9] = [
        ("", CsvError::Empty, "line 1"),
        (
            "time,x\n0,1\n",
            CsvError::BadHeader {
                line: 1,
                found: "time,x".into(),
            },
            "line 1: bad header",
        ),
        (
            "t,y\n0,1\n",
            CsvError::BadHeader {
                line: 1,
                found: "t,y".into(),
            },
            "line 1",
        ),
        (
            "t,x,y,z,w\n",
            CsvError::BadHeader {
                line: 1,
                found: "t,x,y,z,w".into(),
            },
            "line 1",
        ),
        (
            "t,x,y\n0,1,2\n1,2,abc\n",
            CsvError::NotANumber {
                line: 3,
                column: 3,
                name: "y",
                text: "abc".into(),
            },
            "line 3, column 3 (y): \"abc\" is not a number",
        ),
        (
            "t,x\n0,1\n1,\n",
            CsvError::NotANumber {
                line: 3,
                column: 2,
                name: "x",
                text: "".into(),
            },
            "line 3, column 2 (x)",
        ),
        (
            "t,x\n0,NaN\n",
            CsvError::NotFinite {
                line: 2,
                column: 2,
                name: "x",
                text: "NaN".into(),
            },
            "line 2, column 2 (x): \"NaN\" is not a finite number",
        ),
        (
            "t,x\n0,1\n1,2\n\n1,3\n",
            CsvError::TimeNotIncreasing {
                line: 5,
                t: "1".into(),
                previous: "1".into(),
            },
            "line 5, column 1 (t): time 1 does not increase",
        ),
        (
            "t,x,y\n0,1\n",
            CsvError::FieldCount {
                line: 2,
                expected: 3,
                found: 2,
            },
            "line 2: 2 fields, expected 3",
        ),
    ];
    for (text, error, message) in cases {
        let e = read(text).unwrap_err();
        assert_eq!(e, error, "{text:?}");
        assert!(e.to_string().contains(message), "{e} lacks {message}");
    }
    // Also infinities and a decreasing time.
    assert!(matches!(
        read("t,x\ninf,1\n"),
        Err(CsvError::NotFinite {
            line: 2,
            column: 1,
            ..
        })
    ));
    assert!(matches!(
        read("t,x\n2,1\n1,1\n"),
        Err(CsvError::TimeNotIncreasing { line: 3, .. })
    ));
}

// ----------------------------------------------------------------- runner

const TRACK: &str = "t,x,y\n\
                     0.0,1000,-500\n\
                     1.0,1010.5,-480\n\
                     2.5,1031,-451.25\n\
                     3.0,1036,-440\n\
                     4.75,1060.125,-405\n";

fn config(filter: FilterKind, numeric: Numeric) -> ReplayConfig {
    ReplayConfig { filter, numeric }
}

/// Parses an output cell (`None` for an empty residual) the way its
/// representation prints: f32 cells as f32 (shortest round-trip form), others
/// as f64.
fn cells(line: &str, numeric: Numeric) -> Vec<Option<f64>> {
    line.split(',')
        .map(|c| {
            if c.is_empty() {
                None
            } else if numeric == Numeric::F32 {
                Some(c.parse::<f32>().unwrap() as f64)
            } else {
                Some(c.parse::<f64>().unwrap())
            }
        })
        .collect()
}

/// The same rows through `Cartesian<S, ORDER, 2>` directly, as the numbers the
/// output must hold (first interval 1 s, as the tool documents).
fn expected<S: Scalar, const ORDER: usize>(gains: &Gains<S>) -> Vec<Vec<Option<f64>>> {
    let data = read(TRACK).unwrap();
    let mut t = Cartesian::<S, ORDER, 2>::new();
    let mut prev = None;
    let mut rows = Vec::new();
    for r in &data.rows {
        let dt = prev.map_or(S::ONE, |p: f64| S::try_from_f64(r.t - p).unwrap());
        let z = [
            S::try_from_f64(r.z[0]).unwrap(),
            S::try_from_f64(r.z[1]).unwrap(),
        ];
        let out = t.update(z, dt, gains).unwrap();
        prev = Some(r.t);
        let mut row = vec![Some(r.t)];
        for (axis, o) in t.axes().iter().zip(out) {
            row.push(Some(axis.position().to_f64()));
            row.push(Some(axis.velocity().to_f64()));
            row.push(match o {
                UpdateOutcome::Filtered(i) => Some(i.residual.to_f64()),
                _ => None,
            });
            if ORDER == 3 {
                row.push(Some(axis.acceleration().to_f64()));
            }
        }
        rows.push(row);
    }
    rows
}

fn check<S: Scalar, const ORDER: usize>(filter: FilterKind, numeric: Numeric, gains: Gains<S>) {
    let data = read(TRACK).unwrap();
    let out = run(&config(filter, numeric), &data).unwrap();
    let mut lines = out.lines();
    assert_eq!(lines.next().unwrap(), header(ORDER, 2));
    let got: Vec<_> = lines.map(|l| cells(l, numeric)).collect();
    let want = expected::<S, ORDER>(&gains);
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g.len(), w.len());
        for (a, b) in g.iter().zip(w) {
            match (a, b) {
                (Some(a), Some(b)) => {
                    // Printed in the representation's shortest round-trip form
                    // (f64, f32) or as a decimal of the Q32.32 value, which
                    // reads back within 10⁻¹⁰ relative.
                    let tol = if S::NAME == "q32" {
                        1e-10 * (1.0 + b.abs())
                    } else {
                        0.0
                    };
                    assert!(
                        (a - b).abs() <= tol,
                        "{} order {ORDER}: {a} vs {b}",
                        S::NAME
                    );
                }
                (None, None) => {}
                _ => panic!("residual present/absent mismatch: {g:?} vs {w:?}"),
            }
        }
    }
    // The two initialisation rows have no residual, the others do.
    let res_col = 3;
    assert!(got[0][res_col].is_none() && got[1][res_col].is_none());
    assert!(got[2..].iter().all(|r| r[res_col].is_some()));
}

#[test]
fn output_is_the_library_arithmetic() {
    let ab = FilterKind::AlphaBeta {
        alpha: 0.5,
        beta: 0.3,
    };
    let abg = FilterKind::AlphaBetaGamma {
        alpha: 0.5,
        beta: 0.3,
        gamma: 0.1,
    };
    check::<f64, 2>(ab, Numeric::F64, Gains::alpha_beta_f64(0.5, 0.3).unwrap());
    check::<f32, 2>(ab, Numeric::F32, Gains::alpha_beta_f64(0.5, 0.3).unwrap());
    check::<Fix, 2>(ab, Numeric::Fixed, Gains::alpha_beta_f64(0.5, 0.3).unwrap());
    check::<f64, 3>(
        abg,
        Numeric::F64,
        Gains::alpha_beta_gamma_f64(0.5, 0.3, 0.1).unwrap(),
    );
    check::<f32, 3>(
        abg,
        Numeric::F32,
        Gains::alpha_beta_gamma_f64(0.5, 0.3, 0.1).unwrap(),
    );
    check::<Fix, 3>(
        abg,
        Numeric::Fixed,
        Gains::alpha_beta_gamma_f64(0.5, 0.3, 0.1).unwrap(),
    );
}

/// Golden 1-D run, by hand (αβ, α = 0.5, β = 0.3, f64):
/// t = 0, 1, 2 with x = 0, 10, 25:
///   row 1: x = 0, v = 0; row 2: v = (10 − 0)/1 = 10, x = 10;
///   row 3: x_p = 20, e = 5, x = 22.5, v = 10 + 0.3·5 = 11.5.
#[test]
fn golden_one_axis() {
    let data = read("t,x\n0,0\n1,10\n2,25\n").unwrap();
    let out = run(
        &config(
            FilterKind::AlphaBeta {
                alpha: 0.5,
                beta: 0.3,
            },
            Numeric::F64,
        ),
        &data,
    )
    .unwrap();
    assert_eq!(out, "t,x,vx,res_x\n0,0,0,\n1,10,10,\n2,22.5,11.5,5\n");
}

#[test]
fn refused_rows_and_values_name_the_line() {
    let ab = FilterKind::AlphaBeta {
        alpha: 0.5,
        beta: 0.3,
    };
    // 3e9 m does not fit Q32.32: the value is refused, naming line and column.
    let data = read("t,x\n0,0\n1,3e9\n").unwrap();
    let e = run(&config(ab, Numeric::Fixed), &data).unwrap_err();
    assert_eq!(
        e,
        ReplayError::Value {
            line: 3,
            column: 2,
            name: "x",
            error: abtrack::NumError::OutOfRange
        }
    );
    assert!(e.to_string().starts_with("line 3, column 2 (x)"));
    // The second point's velocity overflows Q32.32: refused, naming the line.
    let data = read("t,x\n0,-2e9\n0.001,2e9\n").unwrap();
    let e = run(&config(ab, Numeric::Fixed), &data).unwrap_err();
    assert_eq!(
        e,
        ReplayError::Filter {
            line: 3,
            error: FilterError::Saturated
        }
    );
    // Gains outside the region.
    let bad = FilterKind::AlphaBeta {
        alpha: 1.5,
        beta: 1.5,
    };
    assert_eq!(
        run(&config(bad, Numeric::F64), &read(TRACK).unwrap()),
        Err(ReplayError::Gains(GainError::BetaTooLarge))
    );
}

// ----------------------------------------------------------- command line

fn args(s: &str) -> Result<Command, UsageError> {
    parse_replay_args(s.split_whitespace().map(String::from))
}

#[test]
fn command_line() {
    assert_eq!(
        args("--filter ab --alpha 0.5 --beta 0.3 --numeric f64 data.csv"),
        Ok(Command::Replay {
            config: config(
                FilterKind::AlphaBeta {
                    alpha: 0.5,
                    beta: 0.3
                },
                Numeric::F64
            ),
            input: Input::Path(PathBuf::from("data.csv")),
        })
    );
    assert_eq!(
        args("--filter=abg --alpha=0.5 --beta 0.3 --gamma 0.1 --numeric fixed -"),
        Ok(Command::Replay {
            config: config(
                FilterKind::AlphaBetaGamma {
                    alpha: 0.5,
                    beta: 0.3,
                    gamma: 0.1
                },
                Numeric::Fixed
            ),
            input: Input::Stdin,
        })
    );
    // Default numeric is f64.
    assert!(matches!(
        args("--filter ab --alpha 0.5 --beta 0.3 x.csv"),
        Ok(Command::Replay {
            config: ReplayConfig {
                numeric: Numeric::F64,
                ..
            },
            ..
        })
    ));
    assert_eq!(args("--help"), Ok(Command::Help));
    assert_eq!(args("--filter ab -h"), Ok(Command::Help));
    let refused = [
        (
            "--filter ab --beta 0.3 d.csv",
            UsageError::Missing("--alpha"),
        ),
        (
            "--alpha 0.5 --beta 0.3 d.csv",
            UsageError::Missing("--filter"),
        ),
        (
            "--filter abg --alpha 0.5 --beta 0.3 d.csv",
            UsageError::Missing("--gamma"),
        ),
        (
            "--filter ab --alpha 0.5 --beta 0.3 --gamma 0.1 d.csv",
            UsageError::NotForFilter {
                option: "--gamma",
                filter: "ab".into(),
            },
        ),
        (
            "--filter kalman --alpha 0.5 --beta 0.3 d.csv",
            UsageError::UnknownFilter("kalman".into()),
        ),
        (
            "--filter ab --alpha 0.5 --beta 0.3 --numeric f16 d.csv",
            UsageError::UnknownNumeric("f16".into()),
        ),
        (
            "--filter ab --alpha half --beta 0.3 d.csv",
            UsageError::BadNumber {
                option: "--alpha",
                text: "half".into(),
            },
        ),
        (
            "--filter ab --alpha NaN --beta 0.3 d.csv",
            UsageError::BadNumber {
                option: "--alpha",
                text: "NaN".into(),
            },
        ),
        (
            "--filter ab --alpha 2 --beta 0.3 d.csv",
            UsageError::Gains(GainError::AlphaOutOfRange),
        ),
        (
            "--filter ab --alpha 0.5 --beta 3.1 d.csv",
            UsageError::Gains(GainError::BetaTooLarge),
        ),
        (
            "--filter abg --alpha 0.5 --beta 0.3 --gamma 0.5 d.csv",
            UsageError::Gains(GainError::GammaTooLarge),
        ),
        ("--filter ab --alpha 0.5 --beta 0.3", UsageError::NoInput),
        (
            "--filter ab --alpha 0.5 --beta 0.3 a.csv b.csv",
            UsageError::ExtraInput("b.csv".into()),
        ),
        (
            "--filter ab --alpha 0.5 --alpha 0.4 --beta 0.3 a.csv",
            UsageError::Repeated("--alpha"),
        ),
        (
            "--filter ab --alpha 0.5 --beta",
            UsageError::MissingValue("--beta"),
        ),
        // --tracker is a flag now (tests/replay_tracker.rs); it takes no
        // single-target filter options (the first in name order is named).
        (
            "--filter ab --alpha 0.5 --beta 0.3 --tracker a.csv",
            UsageError::NotForTracker("--alpha"),
        ),
    ];
    for (line, error) in refused {
        assert_eq!(args(line), Err(error), "{line}");
    }
}

// -------------------------------------------------------------- end to end

fn replay_binary() -> Process {
    Process::new(env!("CARGO_BIN_EXE_replay"))
}

fn temp_file(name: &str, contents: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("replay-{}-{name}", std::process::id()));
    std::fs::write(&path, contents).unwrap();
    path
}

#[test]
fn binary_runs_a_file() {
    let path = temp_file("ok.csv", TRACK);
    let out = replay_binary()
        .args([
            "--filter",
            "ab",
            "--alpha",
            "0.5",
            "--beta",
            "0.3",
            "--numeric",
            "f64",
        ])
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let expected = run(
        &config(
            FilterKind::AlphaBeta {
                alpha: 0.5,
                beta: 0.3,
            },
            Numeric::F64,
        ),
        &read(TRACK).unwrap(),
    )
    .unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
    assert!(out.stderr.is_empty());
    let _ = std::fs::remove_file(path);
}

#[test]
fn binary_reads_stdin() {
    let mut child = replay_binary()
        .args([
            "--filter",
            "abg",
            "--alpha",
            "0.5",
            "--beta",
            "0.3",
            "--gamma",
            "0.1",
            "--numeric",
            "fixed",
            "-",
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(TRACK.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("t,x,vx,res_x,ax,y,vy,res_y,ay\n"));
    assert_eq!(text.lines().count(), 6);
}

#[test]
fn binary_fails_cleanly_on_a_bad_file() {
    // The error is on line 5; lines 2–4 are fine, yet nothing is written.
    let path = temp_file("bad.csv", "t,x\n0,1\n1,2\n2,3\n3,three\n4,5\n");
    let out = replay_binary()
        .args(["--filter", "ab", "--alpha", "0.5", "--beta", "0.3"])
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty(), "partial output written");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("line 5, column 2 (x)"), "{err}");
    let _ = std::fs::remove_file(path);

    let missing = replay_binary()
        .args([
            "--filter",
            "ab",
            "--alpha",
            "0.5",
            "--beta",
            "0.3",
            "/nonexistent/abtrack.csv",
        ])
        .output()
        .unwrap();
    assert_eq!(missing.status.code(), Some(1));
    assert!(missing.stdout.is_empty());
}

#[test]
fn binary_rejects_bad_arguments_and_has_help() {
    let out = replay_binary()
        .args(["--filter", "ab", "--alpha", "0.5", "--beta", "3.5", "x.csv"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("stability region"));
    let help = replay_binary().arg("--help").output().unwrap();
    assert!(help.status.success());
    let text = String::from_utf8(help.stdout).unwrap();
    for option in [
        "--filter",
        "--alpha",
        "--beta",
        "--gamma",
        "--numeric",
        "--help",
    ] {
        assert!(text.contains(option), "--help lacks {option}");
    }
}
