//! The `replay` tool: CSV errors name their line (and column), the output is
//! the library's arithmetic, the command line is checked, and the binary runs
//! end to end.

use super::{replay_binary, temp_file};
use std::io::Write;
use std::path::PathBuf;
use std::process::Stdio;

use abtrack::filter::{Gains, UpdateOutcome};
use abtrack::gain::{FixedGains, ScheduledFilter};
use abtrack::{FilterError, Fix, GainError, Scalar};
use abtrack_host_tests::cli::{Command, Input, ReplayArgs};
use abtrack_host_tests::csv_input::{
    read_measurements, read_range_azimuth, AngleUnit, CsvError, InputFormat, Measurements,
    ReadOptions, Refusal, Row,
};
use abtrack_host_tests::replay::{header, run, FilterKind, Numeric, ReplayConfig, ReplayError};
use clap::error::ErrorKind;
use clap::Parser;

fn read(text: &str) -> Result<Measurements, CsvError> {
    read_measurements(text.as_bytes(), ReadOptions::default())
}

// ------------------------------------------------------------- CSV reader

#[test]
fn accepts_the_three_layouts_and_tolerant_spacing() {
    for (text, dims) in [
        ("t,x\n0,1\n", 1),
        ("t,x,y\n0,1,2\n", 2),
        ("t,x,y,z\n0,1,2,3\n", 3),
        ("\u{feff}t , x\r\n0 , 1\r\n\r\n1,2\n", 1),
        ("\"t\",\"x\"\n\"0\",1\n", 1),
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

/// Lines of nothing but spaces or tabs are blank lines too (they were
/// refused as rows of one field); the lines after them keep their numbers,
/// also after such a line inside a quoted (text) field.
#[test]
fn whitespace_only_lines_are_blank_lines() {
    let m = read("t,x\n0,1\n   \n\t\n1,2\n  \r\n2,x\n");
    let Err(e) = m else {
        panic!("the row at line 7 is malformed");
    };
    assert!(e.to_string().contains("line 7"), "{e}");
    let m = read("t,x\n0,1\n   \n\t\n1,2\n  \r\n2,3\n \n").unwrap();
    assert_eq!(m.rows.len(), 3);
    assert_eq!((m.rows[1].line, m.rows[2].line), (5, 7));
    // Inside quotes: a field with a newline and a blank-looking line.
    let m = read("t,x,note\n0,1,\"a\n  \nb\"\n1,2,c\n").unwrap();
    assert_eq!(m.rows.len(), 2);
    assert_eq!(m.rows[1].line, 5);
}

/// Before: a header `t,x,y,alt`, extra columns and another column order
/// were refused; the header is now matched by name.
#[test]
fn header_is_matched_by_name_in_any_order_with_extra_columns() {
    let reference = read("t,x,y\n0,1,2\n1,3,4\n").unwrap();
    for text in [
        "t,x,y,alt\n0,1,2,8000\n1,3,4,\n",
        "callsign,y,t,speed,x\nABC,2,0,250,1\nABC,4,1,251,3\n",
        "t,x,y,icao24,squawk\n0,1,2,4ca7b4,7000\n1,3,4,4ca7b4,7000\n",
    ] {
        let m = read(text).unwrap_or_else(|e| panic!("{text:?}: {e}"));
        assert_eq!(m.dims, 2, "{text:?}");
        let z = |m: &Measurements| m.rows.iter().map(|r| (r.t, r.z)).collect::<Vec<_>>();
        assert_eq!(z(&m), z(&reference), "{text:?}");
    }
    // The alt column is read (and checked) when present; empty or NaN is
    // no altitude, an infinity is refused.
    let m = read("t,x,y,alt\n0,1,2,8000\n1,3,4,\n2,5,6,NaN\n3,7,8,nan\n").unwrap();
    assert_eq!(
        m.rows.iter().map(|r: &Row| r.alt).collect::<Vec<_>>(),
        [Some(8000.0), None, None, None]
    );
    let e = read("t,x,y,alt\n0,1,2,inf\n").unwrap_err();
    assert!(
        matches!(
            e,
            CsvError::Field {
                line: 2,
                name: "alt",
                ..
            }
        ),
        "{e}"
    );
    // Polar: any order, extra columns, alt optional.
    let p = read_range_azimuth(
        "azimuth,alt,range,t,note\n0.5,9000,1000,0,a\n0.6,,1100,1,b\n".as_bytes(),
        ReadOptions::default(),
    )
    .unwrap();
    assert!(p.has_alt);
    assert_eq!(
        (
            p.rows[1].t,
            p.rows[1].range,
            p.rows[1].azimuth,
            p.rows[1].alt
        ),
        (1.0, 1100.0, 0.6, None)
    );
}

#[test]
fn errors_name_the_line_and_column() {
    let cases: Vec<(&str, CsvError, &str)> = vec![
        (
            "",
            CsvError::Empty {
                format: Some(InputFormat::Cartesian),
            },
            "line 1: empty input, expected a header with the columns t, x",
        ),
        (
            "time,x\n0,1\n",
            CsvError::MissingColumns {
                format: InputFormat::Cartesian,
                missing: vec!["t"],
                found: "time,x".into(),
            },
            "line 1: the header \"time,x\" has no column t; this input needs the columns t, x \
             (optional: y, z (needs y), alt) in any order, other columns are ignored",
        ),
        (
            "t,x,z\n0,1,2\n",
            CsvError::MissingColumns {
                format: InputFormat::Cartesian,
                missing: vec!["y"],
                found: "t,x,z".into(),
            },
            "has no column y",
        ),
        (
            "t,x,x\n0,1,2\n",
            CsvError::DuplicateColumn { name: "x".into() },
            "the column \"x\" twice",
        ),
        (
            "t,range,azimuth\n0,1,2\n",
            CsvError::MissingColumns {
                format: InputFormat::Cartesian,
                missing: vec!["x"],
                found: "t,range,azimuth".into(),
            },
            "(this header is for --filter range-azimuth)",
        ),
        (
            "t,x,y\n0,1,2\n1,2,abc\n",
            CsvError::Field {
                line: 3,
                column: 3,
                name: "y",
                text: "abc".into(),
                why: Refusal::NotANumber,
            },
            "line 3, column 3 (y): \"abc\" is not a number",
        ),
        (
            "t,x\n0,1\n1,\n",
            CsvError::Field {
                line: 3,
                column: 2,
                name: "x",
                text: "".into(),
                why: Refusal::NotANumber,
            },
            "line 3, column 2 (x): empty, expected a number",
        ),
        (
            "t,x\n0,NaN\n",
            CsvError::Field {
                line: 2,
                column: 2,
                name: "x",
                text: "NaN".into(),
                why: Refusal::NotFinite,
            },
            "line 2, column 2 (x): \"NaN\" is not a finite number",
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
        assert!(e.to_string().contains(message), "{e}\nlacks\n{message}");
    }
    // Also infinities; a decreasing time is read (the runners skip it).
    assert!(matches!(
        read("t,x\ninf,1\n"),
        Err(CsvError::Field {
            line: 2,
            column: 1,
            why: Refusal::NotFinite,
            ..
        })
    ));
    assert_eq!(read("t,x\n2,1\n1,1\n").unwrap().rows.len(), 2);
}

/// Before: absurd values in f64 ran with exit status 0, and x = 1e308 was
/// reported one line late. Every value is now checked against the
/// library's envelope where it is, naming its line and column.
#[test]
fn values_outside_the_envelope_are_refused_at_their_line() {
    let cases: Vec<(&str, usize, usize, &str, &str)> = vec![
        // (file, line, column, name, message part)
        (
            "t,x,y\n0,1,2\n1,1e308,2\n2,3,4\n",
            3,
            2,
            "x",
            "1e308 is outside the envelope -400000 ..= 400000 m",
        ),
        (
            "t,x,y\n0,1,2\n1,1,400000.5\n",
            3,
            3,
            "y",
            "outside the envelope",
        ),
        (
            "t,x,y,alt\n0,1,2,8000\n1,3,4,1e12\n",
            3,
            4,
            "alt",
            "1e12 is outside the envelope -1000 ..= 126700 ft",
        ),
        (
            "t,x,y,alt\n0,1,2,-1001\n",
            2,
            4,
            "alt",
            "outside the envelope",
        ),
        (
            "t,x\n1e308,1\n",
            2,
            1,
            "t",
            "1e308 is outside the envelope -8589934592 ..= 8589934592 s",
        ),
    ];
    for (text, line, column, name, message) in cases {
        let e = read(text).unwrap_err();
        match &e {
            CsvError::Field {
                line: l,
                column: c,
                name: n,
                why: Refusal::OutOfEnvelope { .. },
                ..
            } => assert_eq!((*l, *c, *n), (line, column, name), "{text:?}: {e}"),
            other => panic!("{text:?}: {other:?}"),
        }
        let shown = e.to_string();
        assert!(
            shown.starts_with(&format!("line {line}, column {column} ({name}): ")),
            "{shown}"
        );
        assert!(shown.contains(message), "{shown}\nlacks {message}");
    }
    // Δt = 1e-300, 1 ms (where m2 printed 1e190) and a 30 s gap are read:
    // timing is the filters' business (skipped, restarted; gaps_restart.rs).
    for text in [
        "t,x\n0,1\n1e-300,2\n",
        "t,x\n0,1\n1,2\n1.001,2\n",
        "t,x\n0,1\n30,2\n",
    ] {
        assert!(read(text).is_ok(), "{text:?}");
    }
    // 0.15 − 0.1 is 0.0499… in f64: the interval limit is not that strict.
    assert!(read("t,x\n0.1,1\n0.15,2\n").is_ok());
    // A bad field is echoed by a short prefix only.
    let long = format!("t,x\n0,{}\n", "9".repeat(400));
    let e = read(&long).unwrap_err().to_string();
    assert!(e.len() < 160, "{e}");
    assert!(e.contains("999999999999999999999999…"), "{e}");
    let long = format!("t,x\n0,{}\n", "z".repeat(400));
    let e = read(&long).unwrap_err().to_string();
    assert!(
        e.len() < 120 && e.contains("\"zzzzzzzzzzzzzzzzzzzzzzzz…\" is not a number"),
        "{e}"
    );
}

/// Before: an azimuth in degrees ran without a warning. The unit is
/// explicit: a radian column beyond 2π is refused naming the option, and
/// `--azimuth-unit deg` reads degrees.
#[test]
fn azimuth_unit_is_explicit_never_guessed() {
    let degrees = "t,range,azimuth\n0,1000,45\n1,1010,46\n";
    let e = read_range_azimuth(degrees.as_bytes(), ReadOptions::default()).unwrap_err();
    assert_eq!(
        e,
        CsvError::Field {
            line: 2,
            column: 3,
            name: "azimuth",
            text: "45".into(),
            why: Refusal::LooksLikeDegrees
        }
    );
    assert!(e.to_string().contains("--azimuth-unit deg"), "{e}");
    let as_degrees = ReadOptions {
        azimuth_unit: AngleUnit::Degrees,
        ..ReadOptions::default()
    };
    let m = read_range_azimuth(degrees.as_bytes(), as_degrees).unwrap();
    assert_eq!(m.rows[0].azimuth, 45f64.to_radians());
    // Degrees beyond one turn, radians at 1e308, and a range beyond 400 km.
    for (text, options, column, name) in [
        ("t,range,azimuth\n0,1000,361\n", as_degrees, 3, "azimuth"),
        (
            "t,range,azimuth\n0,1000,1e308\n",
            ReadOptions::default(),
            3,
            "azimuth",
        ),
        (
            "t,range,azimuth\n0,400001,1\n",
            ReadOptions::default(),
            2,
            "range",
        ),
        (
            "t,range,azimuth,alt\n0,1000,1,1e12\n",
            ReadOptions::default(),
            4,
            "alt",
        ),
    ] {
        match read_range_azimuth(text.as_bytes(), options) {
            Err(CsvError::Field {
                line: 2,
                column: c,
                name: n,
                ..
            }) if (c, n) == (column, name) => {}
            other => panic!("{text:?}: {other:?}"),
        }
    }
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
/// What the library computes for TRACK: fixed gains through
/// ScheduledFilter (robust_gains bounds them on TRACK's irregular intervals).
fn expected<S: Scalar, const ORDER: usize>(gains: &Gains<S>) -> Vec<Vec<Option<f64>>> {
    let data = read(TRACK).unwrap();
    let mut track = ScheduledFilter::<S, _, ORDER, 2>::new(FixedGains::new(*gains));
    let mut prev = None;
    let mut rows = Vec::new();
    for r in &data.rows {
        let dt = prev.map_or(S::ONE, |p: f64| S::try_from_f64(r.t - p).unwrap());
        let z = [
            S::try_from_f64(r.z[0]).unwrap(),
            S::try_from_f64(r.z[1]).unwrap(),
        ];
        let out = track.update(z, dt).unwrap().outcome;
        prev = Some(r.t);
        let mut row = vec![Some(r.t)];
        for (axis, o) in track.filter().axes().iter().zip(out) {
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
    let got: Vec<_> = lines
        .map(|l| {
            // The last column, `event`, is empty on regular timing.
            let (l, event) = l.rsplit_once(',').unwrap();
            assert_eq!(event, "");
            cells(l, numeric)
        })
        .collect();
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
    check::<Fix, 2>(ab, Numeric::Q32, Gains::alpha_beta_f64(0.5, 0.3).unwrap());
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
        Numeric::Q32,
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
    assert_eq!(
        out,
        "t,x,vx,res_x,event\n0,0,0,,\n1,10,10,,\n2,22.5,11.5,5,\n"
    );
}

/// A file of rows made directly (not through the reader, which refuses
/// values outside the envelope first).
fn rows(points: &[(f64, f64)]) -> Measurements {
    Measurements {
        dims: 1,
        rows: points
            .iter()
            .enumerate()
            .map(|(i, &(t, x))| Row {
                line: i + 2,
                t_text: t.to_string(),
                t,
                z: [x, 0.0, 0.0],
                alt: None,
            })
            .collect(),
    }
}

#[test]
fn refused_rows_and_values_name_the_line() {
    let ab = FilterKind::AlphaBeta {
        alpha: 0.5,
        beta: 0.3,
    };
    // 3e9 m does not fit Q32.32: the value is refused, naming line and column.
    let data = rows(&[(0.0, 0.0), (1.0, 3e9)]);
    let e = run(&config(ab, Numeric::Q32), &data).unwrap_err();
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
    // Two reports 1 ms apart: the second is skipped (under the filters'
    // 0.05 s), marked in the event column.
    let data = rows(&[(0.0, 0.0), (0.001, 1.0)]);
    let out = run(&config(ab, Numeric::Q32), &data).unwrap();
    assert!(out.ends_with("\n0.001,0,0,,skipped\n"), "{out}");
    // The second point's velocity overflows Q32.32: refused, naming the line.
    let data = rows(&[(0.0, 0.0), (0.06, 2e9)]);
    let e = run(&config(ab, Numeric::Q32), &data).unwrap_err();
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

/// No run ends with status 0 after an absurd estimate. In f64
/// (where nothing saturates) an estimate outside the envelope stops the run
/// at the row that produced it; a start that leaves it is first started
/// again from its row (`StartCheck`), so reports that keep moving too fast
/// stop the run at the second start.
#[test]
fn estimates_outside_the_envelope_stop_the_run_at_their_row() {
    let ab = FilterKind::AlphaBeta {
        alpha: 0.5,
        beta: 0.3,
    };
    // Inside the input envelope, but every two points imply 2000 m/s.
    let text = "t,x\n0,0\n1,2000\n2,4000\n";
    for numeric in [Numeric::F64, Numeric::F32, Numeric::Q32] {
        let e = run(&config(ab, numeric), &read(text).unwrap()).unwrap_err();
        match e {
            ReplayError::Estimate {
                line: 4,
                name: "vx",
                value,
                ..
            } => assert_eq!(value, 2000.0),
            other => panic!("{numeric:?}: {other:?}"),
        }
        assert!(e.to_string().starts_with("line 4: after this row the estimate vx = 2.000000e3 m/s is outside the envelope -1500 ..= 1500 m/s"), "{e}");
    }
    // The issue's divergence: gains inside the stability triangle for one
    // interval, on irregular report times, grew without bound (834 km,
    // status 0). Replay runs fixed gains through ScheduledFilter, whose
    // robust_gains bound them per update (tests/it/gain/robustness.rs): the
    // run ends with every estimate inside the envelope.
    let diverging = FilterKind::AlphaBeta {
        alpha: 0.002,
        beta: 0.1667,
    };
    let mut text = String::from("t,x\n");
    let mut t = 0.0;
    for k in 0..400 {
        t += if k % 2 == 0 { 0.06 } else { 3.0 };
        text.push_str(&format!("{t},{}\n", 100.0 * t));
    }
    let out = run(&config(diverging, Numeric::F64), &read(&text).unwrap()).unwrap();
    assert_eq!(out.lines().count(), 401);
}

// ----------------------------------------------------------- command line

fn args(s: &str) -> Result<Command, clap::Error> {
    ReplayArgs::try_parse_from(std::iter::once("replay").chain(s.split_whitespace()))?
        .into_command()
}

#[test]
fn command_line() {
    assert_eq!(
        args("--filter ab --alpha 0.5 --beta 0.3 --numeric f64 data.csv").unwrap(),
        Command::Replay {
            config: config(
                FilterKind::AlphaBeta {
                    alpha: 0.5,
                    beta: 0.3
                },
                Numeric::F64
            ),
            input: Input::Path(PathBuf::from("data.csv")),
        }
    );
    assert_eq!(
        args("--filter=abg --alpha=0.5 --beta 0.3 --gamma 0.1 --numeric q32.32 -").unwrap(),
        Command::Replay {
            config: config(
                FilterKind::AlphaBetaGamma {
                    alpha: 0.5,
                    beta: 0.3,
                    gamma: 0.1
                },
                Numeric::Q32
            ),
            input: Input::Stdin,
        }
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
    assert_eq!(args("--help").unwrap_err().kind(), ErrorKind::DisplayHelp);
    assert_eq!(
        args("--filter ab -h").unwrap_err().kind(),
        ErrorKind::DisplayHelp
    );
    let refused = [
        ("--filter ab --beta 0.3 d.csv", "--alpha"),
        ("--alpha 0.5 --beta 0.3 d.csv", "--filter"),
        ("--filter abg --alpha 0.5 --beta 0.3 d.csv", "--gamma"),
        (
            "--filter ab --alpha 0.5 --beta 0.3 --gamma 0.1 d.csv",
            "--gamma does not apply to --filter ab",
        ),
        ("--filter kalman --alpha 0.5 --beta 0.3 d.csv", "'kalman'"),
        (
            "--filter ab --alpha 0.5 --beta 0.3 --numeric f16 d.csv",
            "'f16'",
        ),
        (
            "--filter ab --alpha half --beta 0.3 d.csv",
            "\"half\" is not a finite number",
        ),
        (
            "--filter ab --alpha NaN --beta 0.3 d.csv",
            "\"NaN\" is not a finite number",
        ),
        (
            "--filter auto --sigma-m 50 --numeric fixed32 d.csv",
            "not the single x/y filters",
        ),
        ("--filter ab --alpha 2 --beta 0.3 d.csv", "stability region"),
        (
            "--filter ab --alpha 0.5 --beta 3.1 d.csv",
            "stability region",
        ),
        (
            "--filter abg --alpha 0.5 --beta 0.3 --gamma 0.5 d.csv",
            "stability region",
        ),
        ("--filter ab --alpha 0.5 --beta 0.3", "<INPUT>"),
        ("--filter ab --alpha 0.5 --beta 0.3 a.csv b.csv", "'b.csv'"),
        (
            "--filter ab --alpha 0.5 --alpha 0.4 --beta 0.3 a.csv",
            "--alpha",
        ),
        ("--filter ab --alpha 0.5 --beta", "--beta"),
        (
            "--filter ab --alpha 0.5 --beta 0.3 --tracker a.csv",
            "--tracker",
        ),
        (
            "--tracker --alpha 0.5 --beta 0.3 a.csv",
            "--alpha does not apply to --tracker",
        ),
        (
            "--filter ab --alpha 0.5 --beta 0.3 --region-m 5000 a.csv",
            "--region-m does not apply to --filter ab",
        ),
    ];
    for (line, message) in refused {
        let e = args(line).unwrap_err();
        let text = e.to_string();
        assert!(text.contains(message), "{line}: {text}");
        assert_eq!(e.exit_code(), 2, "{line}");
    }
}

/// `--help` names no internal issue number.
#[test]
fn help_names_no_issue_number() {
    for long in [false, true] {
        let flag = if long { "--help" } else { "-h" };
        let help = args(flag).unwrap_err().render().to_string();
        assert!(help.contains("--region-m"), "{help}");
        for word in ["issue", "Issue"] {
            assert!(!help.contains(word), "{flag} mentions {word}:\n{help}");
        }
    }
}

// -------------------------------------------------------------- end to end

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

/// A file with its header only runs (status 0, the header on stdout) and
/// says so on stderr, in every single-target layout.
#[test]
fn binary_notes_a_file_without_data_rows() {
    for (header, args, columns) in [
        (
            "t,x,y\n",
            &["--filter", "auto", "--sigma-m", "50"][..],
            "t,x,vx,res_x,y,vy,res_y,event\n",
        ),
        (
            "t,range,azimuth\n",
            &["--filter", "range-azimuth"][..],
            "t,x,vx,res_x,y,vy,res_y,range,azimuth,event\n",
        ),
        (
            "t,x\n",
            &["--filter", "ab", "--schedule", "bank"][..],
            "t,x,vx,res_x,member_x,event\n",
        ),
    ] {
        let path = temp_file("header-only.csv", header);
        let out = replay_binary().args(args).arg(&path).output().unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        assert_eq!(String::from_utf8(out.stdout).unwrap(), columns, "{args:?}");
        assert_eq!(
            String::from_utf8(out.stderr).unwrap(),
            "replay: no data rows (the input has its header only)\n",
            "{args:?}"
        );
        let _ = std::fs::remove_file(path);
    }
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
            "q32.32",
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
    assert!(text.starts_with("t,x,vx,res_x,ax,y,vy,res_y,ay,event\n"));
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

/// The host tools and the firmware's wire edge refuse the same values: the
/// wire's limits are the library envelope's (one set of limits).
#[test]
fn the_envelope_is_the_wire_edge() {
    use abtrack::{envelope, wire};
    assert_eq!(
        f64::from(wire::MAX_POSITION_CM) / 100.0,
        envelope::MAX_POSITION_M
    );
    assert_eq!(f64::from(wire::MIN_ALTITUDE_FT), envelope::ALTITUDE_FT.min);
    assert_eq!(f64::from(wire::MAX_ALTITUDE_FT), envelope::ALTITUDE_FT.max);
}
