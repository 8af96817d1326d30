//! `replay` with every `--schedule` and with `--filter range-azimuth`
//! and `--own-alt`, against the library driven
//! directly; the advisory timeline of analytic encounters; errors.
//!
//! The expected outputs are built by calling the library (schedules, bank,
//! range–azimuth filter, altitude tracker, `tcas::assess`) and formatting
//! every value with `Display`, so the comparisons are exact string equality
//! in all three representations.

use super::{replay_binary, temp_file};
use std::fmt::{Display, Write as _};

use abtrack::bank::{BankOutcome, CartesianBank};
use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::{
    RangeAzimuthFilter, RangeAzimuthNoise, RangeAzimuthOutcome, PAPER_BEARING_VARIANCE,
};
use abtrack::filter::{Phase, UpdateOutcome};
use abtrack::gain::spec::{ScheduleSpec, SpecErrorKind, SCHEDULES};
use abtrack::gain::{AnySchedule, ConfigError, ScheduledFilter};
use abtrack::tcas::{
    assess, Advisory, CollisionAvoidance, Intruder, OwnAircraft, ThreatState,
    METRES_PER_NAUTICAL_MILE, METRES_PER_SECOND_PER_KNOT,
};
use abtrack::{Fix, Scalar, ScaledScalar};
use abtrack_host_tests::cli::{parse_schedule, Command, ReplayArgs, ScheduleArgError};
use abtrack_host_tests::csv_input::{
    read_measurements, read_range_azimuth, CsvError, InputFormat, ReadOptions, Refusal, TimeOrder,
};
use abtrack_host_tests::replay::{
    replay_reader, Failure, FilterKind, Numeric, Order, RangeAzimuthOptions, ReplayConfig,
};
use abtrack_host_tests::scenario;
use clap::{CommandFactory, Parser};

const NM: f64 = METRES_PER_NAUTICAL_MILE;
const KT: f64 = METRES_PER_SECOND_PER_KNOT;

// ------------------------------------------------------------------ helpers

fn args(s: &str) -> Result<Command, clap::Error> {
    ReplayArgs::try_parse_from(std::iter::once("replay").chain(s.split_whitespace()))?
        .into_command()
}

/// The message of a refused command line (and that it exits with 2).
fn refusal(s: &str) -> String {
    let e = args(s).expect_err(s);
    assert_eq!(e.exit_code(), 2, "{s}");
    e.to_string()
}

fn config_of(s: &str) -> ReplayConfig {
    match args(s) {
        Ok(Command::Replay { config, .. }) => config,
        other => panic!("{s}: {other:?}"),
    }
}

/// Runs `replay <command line> -` on `input` in-process.
fn replay(command_line: &str, input: &str) -> Result<String, Failure> {
    replay_reader(&config_of(&format!("{command_line} -")), input.as_bytes())
}

/// xorshift64* with Box–Muller: reproducible noise without a dependency.
struct Noise(u64);

impl Noise {
    fn new(seed: u64) -> Self {
        Noise(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn uniform(&mut self) -> f64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        ((x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn gaussian(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

/// A small generated track on `dims` axes: 40 rows, T = 1 s but for a 2.5 s
/// gap, straight for 15 rows, then 8 rows of a 15 m/s² turn, then straight;
/// Gaussian noise σ = 8 m. The turn's innovations exceed Liu's 70 m and 19 m
/// thresholds and move the bank's selection and the windows' choices.
fn generated_track(dims: usize) -> (String, Vec<(f64, [f64; 3])>) {
    let mut noise = Noise::new(dims as u64 + 7);
    let mut p = [100.0, -50.0, 1000.0];
    let mut v = [30.0, 12.0, -4.0];
    let mut t = 0.0;
    let mut rows = Vec::new();
    for k in 0..40 {
        if k > 0 {
            let dt = if k == 25 { 2.5 } else { 1.0 };
            let a = if (15..23).contains(&k) {
                [-15.0, 15.0, 2.0]
            } else {
                [0.0; 3]
            };
            for i in 0..3 {
                p[i] += v[i] * dt + 0.5 * a[i] * dt * dt;
                v[i] += a[i] * dt;
            }
            t += dt;
        }
        let mut z = [0.0; 3];
        for i in 0..dims {
            z[i] = p[i] + 8.0 * noise.gaussian();
        }
        rows.push((t, z));
    }
    let names = ["x", "y", "z"];
    let mut text = String::from("t");
    for n in names.iter().take(dims) {
        text.push(',');
        text.push_str(n);
    }
    text.push('\n');
    for (t, z) in &rows {
        let _ = write!(text, "{t}");
        for zi in z.iter().take(dims) {
            let _ = write!(text, ",{zi}");
        }
        text.push('\n');
    }
    (text, rows)
}

/// `,value`.
fn cell<S: Display>(out: &mut String, v: S) {
    let _ = write!(out, ",{v}");
}

/// `,value` or `,`.
fn optional<S: Display>(out: &mut String, v: Option<S>) {
    out.push(',');
    if let Some(v) = v {
        let _ = write!(out, "{v}");
    }
}

fn interval<S: Scalar>(previous: Option<f64>, t: f64) -> S {
    // Read to the microsecond, as replay's module docs say.
    previous.map_or(S::ONE, |p| {
        S::try_from_f64(((t - p) * 1e6).round() / 1e6).unwrap()
    })
}

fn kinematic_header(order: usize, dims: usize, bank: bool) -> String {
    let mut h = String::from("t");
    for a in ["x", "y", "z"].iter().take(dims) {
        let _ = write!(h, ",{a},v{a},res_{a}");
        if order == 3 {
            let _ = write!(h, ",a{a}");
        }
        if bank {
            let _ = write!(h, ",member_{a}");
        }
    }
    h.push_str(",event\n");
    h
}

/// The output of `spec` on `rows`, by `ScheduledFilter` + `AnySchedule`
/// (window capacity 64, as `replay` documents).
fn expected_scheduled<S: Scalar + Display, const ORDER: usize, const D: usize>(
    spec: &ScheduleSpec,
    rows: &[(f64, [f64; 3])],
) -> String {
    let schedule = AnySchedule::<S, D, 64>::from_spec(spec).unwrap();
    let mut track = ScheduledFilter::<S, _, ORDER, D>::new(schedule);
    let mut out = kinematic_header(ORDER, D, false);
    let mut previous = None;
    for (t, z) in rows {
        let dt = interval::<S>(previous, *t);
        let z: [S; D] = core::array::from_fn(|i| S::try_from_f64(z[i]).unwrap());
        let update = track.update(z, dt).unwrap();
        previous = Some(*t);
        let _ = write!(out, "{t}");
        for (axis, o) in track.filter().axes().iter().zip(update.outcome) {
            cell(&mut out, axis.position());
            cell(&mut out, axis.velocity());
            optional(
                &mut out,
                match o {
                    UpdateOutcome::Filtered(i) => Some(i.residual),
                    _ => None,
                },
            );
            if ORDER == 3 {
                cell(&mut out, axis.acceleration());
            }
        }
        out.push_str(",\n");
    }
    out
}

/// The output of the M5 bank on `rows`, by `CartesianBank` (capacity 64).
fn expected_bank<S: Scalar + Display, const D: usize>(
    spec: &ScheduleSpec,
    rows: &[(f64, [f64; 3])],
) -> String {
    let ScheduleSpec::Bank(config) = spec else {
        panic!("not a bank: {spec}")
    };
    let mut bank = CartesianBank::<S, 64, D>::from_config(config).unwrap();
    let mut out = kinematic_header(2, D, true);
    let mut previous = None;
    for (t, z) in rows {
        let dt = interval::<S>(previous, *t);
        let z: [S; D] = core::array::from_fn(|i| S::try_from_f64(z[i]).unwrap());
        let outcomes = bank.update(z, dt).unwrap();
        previous = Some(*t);
        let _ = write!(out, "{t}");
        for (axis, o) in bank.axes().iter().zip(outcomes) {
            cell(&mut out, axis.position());
            cell(&mut out, axis.velocity());
            match o {
                BankOutcome::Filtered(sel) => {
                    cell(&mut out, sel.residual);
                    cell(&mut out, sel.member);
                }
                _ => out.push_str(",,"),
            }
        }
        out.push_str(",\n");
    }
    out
}

fn expected_kinematic<S: Scalar + Display, const D: usize>(
    order: Order,
    spec: &ScheduleSpec,
    rows: &[(f64, [f64; 3])],
) -> String {
    match (spec, order) {
        (ScheduleSpec::Bank(_), _) => expected_bank::<S, D>(spec, rows),
        (_, Order::AlphaBeta) => expected_scheduled::<S, 2, D>(spec, rows),
        (_, Order::AlphaBetaGamma) => expected_scheduled::<S, 3, D>(spec, rows),
    }
}

/// The spec text `replay` is given for schedule name `name` (only `fixed`
/// has required parameters).
fn spec_text(name: &str, order: Order) -> String {
    match (name, order) {
        ("fixed", Order::AlphaBeta) => "fixed:alpha=0.6,beta=0.25".into(),
        ("fixed", Order::AlphaBetaGamma) => "fixed:alpha=0.6,beta=0.25,gamma=0.05".into(),
        ("auto", _) => "auto:sigma=5".into(),
        _ => name.into(),
    }
}

const NUMERICS: [(Numeric, &str); 3] = [
    (Numeric::F64, "f64"),
    (Numeric::F32, "f32"),
    (Numeric::Q32, "q32.32"),
];

// ---------------------------------------------------------------- schedules

#[test]
fn every_schedule_name_runs_in_every_representation_and_matches_the_library() {
    let mut names_run = 0;
    for dims in 1..=3 {
        let (text, rows) = generated_track(dims);
        for info in SCHEDULES {
            for name in info.names {
                for order in [Order::AlphaBeta, Order::AlphaBetaGamma] {
                    let spec_text = spec_text(name, order);
                    let spec = ScheduleSpec::parse(&spec_text).unwrap();
                    let is_bank = matches!(spec, ScheduleSpec::Bank(_));
                    for (numeric, numeric_name) in NUMERICS {
                        let line = format!(
                            "--filter {} --schedule {spec_text} --numeric {numeric_name}",
                            order.name()
                        );
                        if is_bank && order == Order::AlphaBetaGamma {
                            assert!(refusal(&format!("{line} -"))
                                .contains("the M5 bank is made of αβ filters; use --filter ab"));
                            continue;
                        }
                        let config = config_of(&format!("{line} -"));
                        assert_eq!(config.numeric, numeric);
                        let got = replay_reader(&config, text.as_bytes())
                            .unwrap_or_else(|e| panic!("{line} (dims {dims}): {e}"));
                        let want = match (numeric, dims) {
                            (Numeric::F64, 1) => expected_kinematic::<f64, 1>(order, &spec, &rows),
                            (Numeric::F64, 2) => expected_kinematic::<f64, 2>(order, &spec, &rows),
                            (Numeric::F64, _) => expected_kinematic::<f64, 3>(order, &spec, &rows),
                            (Numeric::F32, 1) => expected_kinematic::<f32, 1>(order, &spec, &rows),
                            (Numeric::F32, 2) => expected_kinematic::<f32, 2>(order, &spec, &rows),
                            (Numeric::F32, _) => expected_kinematic::<f32, 3>(order, &spec, &rows),
                            (Numeric::Q32, 1) => expected_kinematic::<Fix, 1>(order, &spec, &rows),
                            (Numeric::Q32, 2) => expected_kinematic::<Fix, 2>(order, &spec, &rows),
                            (Numeric::Q32, _) => expected_kinematic::<Fix, 3>(order, &spec, &rows),
                            (Numeric::Fixed32, _) => unreachable!("not among NUMERICS"),
                        };
                        assert_eq!(got, want, "{line} (dims {dims})");
                        assert_eq!(got.lines().count(), rows.len() + 1);
                        names_run += 1;
                    }
                }
            }
        }
    }
    // Every name of the table, three representations, three dimensions, αβ
    // and αβγ, but the bank on αβγ (refused above).
    let names: usize = SCHEDULES.iter().map(|i| i.names.len()).sum();
    let bank_names = 2; // bank, m5
    assert_eq!(names_run, 3 * 3 * (2 * names - bank_names));
}

#[test]
fn schedules_differ_and_aliases_agree() {
    let (text, _) = generated_track(2);
    let mut outputs: Vec<(usize, &str, String)> = Vec::new();
    for (entry, info) in SCHEDULES.iter().enumerate() {
        for name in info.names {
            let out = replay(
                &format!(
                    "--filter ab --schedule {}",
                    spec_text(name, Order::AlphaBeta)
                ),
                &text,
            )
            .unwrap();
            outputs.push((entry, name, out));
        }
    }
    for (i, (entry_a, name_a, a)) in outputs.iter().enumerate() {
        for (entry_b, name_b, b) in &outputs[i + 1..] {
            if entry_a == entry_b {
                assert_eq!(a, b, "aliases {name_a} and {name_b} differ");
            } else {
                assert_ne!(a, b, "{name_a} and {name_b} give the same output");
            }
        }
    }
    // The bank's selection moves between members on this track.
    let bank = &outputs.iter().find(|o| o.1 == "bank").unwrap().2;
    let mut members: Vec<&str> = bank
        .lines()
        .skip(3)
        .map(|l| l.split(',').nth(4).unwrap())
        .collect();
    members.sort();
    members.dedup();
    assert!(members.len() >= 3, "bank selected only {members:?}");
}

/// Golden rows by hand, one axis, t = 0, 1, 2 with x = 0, 10, 25: rows 1–2
/// initialise (x = 10, v = 10); row 3 predicts x_p = 20, e = 5.
/// * least-squares, n = 3 (eq. 24): α = 2·5/12 = 5/6, β = 6/12 = 1/2:
///   x = 20 + 25/6 = 24.1666…, v = 10 + 5/2 = 12.5.
/// * tcas-firmness on abg, firmness 2: α = 0.83, β = 0.5, γ = 0.16:
///   x = 20 + 4.15 = 24.15, v = 12.5, a = 0.16/(2·1²)·5 = 0.4.
/// * bank:k=4: members α = 0.05, 0.3667, 0.6833, 1; all predict 20, so the
///   tie goes to member 0: x = 20 + 0.05·5 = 20.25,
///   v = 10 + (0.05²/1.95)·5 = 10 + 0.0064103 = 10.0064103.
#[test]
fn golden_scheduled_rows() {
    let input = "t,x\n0,0\n1,10\n2,25\n";
    let ls = replay("--filter ab --schedule least-squares", input).unwrap();
    let row: Vec<f64> = ls
        .lines()
        .nth(3)
        .unwrap()
        .trim_end_matches(',')
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    assert!((row[1] - (20.0 + 25.0 / 6.0)).abs() < 1e-12, "{ls}");
    assert_eq!((row[2], row[3]), (12.5, 5.0));

    let tcas = replay("--filter abg --schedule tcas-firmness", input).unwrap();
    let row: Vec<f64> = tcas
        .lines()
        .nth(3)
        .unwrap()
        .trim_end_matches(',')
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    assert!((row[1] - 24.15).abs() < 1e-12, "{tcas}");
    assert_eq!(row[2], 12.5);
    assert!((row[4] - 0.4).abs() < 1e-12, "{tcas}");

    let bank = replay("--filter ab --schedule bank:k=4", input).unwrap();
    let last = bank.lines().nth(3).unwrap();
    let cells: Vec<&str> = last.split(',').collect();
    assert_eq!(cells[1], "20.25");
    assert!((cells[2].parse::<f64>().unwrap() - (10.0 + 0.0025 / 1.95 * 5.0)).abs() < 1e-12);
    assert_eq!((cells[3], cells[4]), ("5", "0"));
    assert_eq!(bank.lines().nth(1), Some("0,0,0,,,"));
}

#[test]
fn shorthand_is_the_fixed_schedule() {
    // --alpha/--beta run the filter directly, --schedule fixed through
    // ScheduledFilter: the same arithmetic, the same output.
    let (text, _) = generated_track(2);
    for (_, n) in NUMERICS {
        assert_eq!(
            replay(
                &format!("--filter ab --alpha 0.6 --beta 0.25 --numeric {n}"),
                &text
            )
            .unwrap(),
            replay(
                &format!("--filter ab --schedule fixed:alpha=0.6,beta=0.25 --numeric {n}"),
                &text
            )
            .unwrap()
        );
        assert_eq!(
            replay(
                &format!("--filter abg --alpha 0.6 --beta 0.25 --gamma 0.05 --numeric {n}"),
                &text
            )
            .unwrap(),
            replay(
                &format!(
                    "--filter abg --schedule fixed:alpha=0.6,beta=0.25,gamma=0.05 --numeric {n}"
                ),
                &text
            )
            .unwrap()
        );
    }
}

#[test]
fn bad_specs_give_the_parsers_error_and_position() {
    let spec_error = |line: &str| {
        let spec = line
            .split_whitespace()
            .skip_while(|w| *w != "--schedule")
            .nth(1)
            .unwrap();
        // The command line refuses it with the same message.
        let message = refusal(line);
        match parse_schedule(spec) {
            Err(e @ ScheduleArgError { .. }) => {
                assert!(message.contains(&e.to_string()), "{message}");
                (e.text, e.error.kind, e.error.offset)
            }
            other => panic!("{line}: {other:?}"),
        }
    };
    assert_eq!(
        spec_error("--filter ab --schedule m1:beta=0.3 d.csv"),
        ("m1:beta=0.3".into(), SpecErrorKind::UnknownParameter, 3)
    );
    assert_eq!(
        spec_error("--filter ab --schedule kalman d.csv"),
        ("kalman".into(), SpecErrorKind::UnknownSchedule, 0)
    );
    assert_eq!(
        spec_error("--filter ab --schedule m4:window=8,steps=x d.csv").1,
        SpecErrorKind::InvalidNumber
    );
    assert_eq!(
        spec_error("--filter ab --schedule m1:alpha=2 d.csv"),
        (
            "m1:alpha=2".into(),
            SpecErrorKind::Config(ConfigError::OutOfRange { parameter: "alpha" }),
            3
        )
    );
    assert_eq!(
        spec_error("--filter ab --schedule fixed:alpha=0.5 d.csv").1,
        SpecErrorKind::MissingParameter { parameter: "beta" }
    );
    // Capacities are checked when the schedule is built; the error still
    // points at the key.
    assert_eq!(
        spec_error("--filter ab --schedule m4:steps=10,window=65 d.csv"),
        (
            "m4:steps=10,window=65".into(),
            SpecErrorKind::Config(ConfigError::ExceedsCapacity {
                parameter: "window",
                capacity: 64
            }),
            12
        )
    );
    assert_eq!(spec_error("--filter ab --schedule bank:k=65 d.csv").2, 5);
    assert!(args("--filter ab --schedule bank:k=64 d.csv").is_ok());
    assert!(args("--filter ab --schedule liu-residual:n=64 d.csv").is_ok());
    // The message carries the position and a caret under it.
    assert!(
        refusal("--filter ab --schedule m1:beta=0.3 d.csv").contains(
            "--schedule: unknown parameter for this schedule (at byte 3)\n  m1:beta=0.3\n     ^"
        )
    );
}

#[test]
fn schedule_options_are_checked() {
    let refused = [
        (
            "--filter ab --schedule m1 --alpha 0.5 --beta 0.3 d.csv",
            "--schedule and --alpha/--beta/--gamma cannot be combined",
        ),
        (
            "--filter abg --schedule m1 --alpha 0.5 --beta 0.3 --gamma 0.1 d.csv",
            "--schedule and --alpha/--beta/--gamma cannot be combined",
        ),
        (
            "--filter ab d.csv",
            "--filter ab needs --schedule (or --alpha and --beta)",
        ),
        (
            "--filter abg --schedule bank d.csv",
            "the M5 bank is made of αβ filters",
        ),
        (
            "--filter ab --schedule fixed:alpha=0.5,beta=0.3,gamma=0.1 d.csv",
            "gamma (in --schedule fixed) does not apply to --filter ab",
        ),
        (
            "--filter range-azimuth --schedule m1 d.csv",
            "--schedule does not apply to --filter range-azimuth",
        ),
        (
            "--filter ab --schedule m1 --own-alt 8000 d.csv",
            "--own-alt does not apply to --filter ab",
        ),
    ];
    for (line, message) in refused {
        let text = refusal(line);
        assert!(text.contains(message), "{line}: {text}");
    }
    // The examples parse.
    for line in [
        "--filter ab --schedule least-squares d.csv",
        "--filter ab --schedule m1:alpha=0.05 d.csv",
        "--filter ab --schedule bank:k=8 d.csv",
        "--filter ab --schedule liu-adaptive d.csv",
        "--filter abg --schedule tcas-firmness d.csv",
    ] {
        assert!(args(line).is_ok(), "{line}");
    }
    assert!(matches!(
        config_of("--filter ab --schedule bank:k=8 d.csv").filter,
        FilterKind::Bank(c) if c.k == 8
    ));
}

// ----------------------------------------------------------- range-azimuth

/// The library's output for a range–azimuth file: the filter, the altitude
/// tracker on `alt` and `tcas::assess` against an own aircraft level at
/// `own_alt` over sea level.
fn expected_range_azimuth<S: Scalar + Display>(
    text: &str,
    range_variance: f64,
    bearing_variance: f64,
    process_noise: f64,
    quantum: AltitudeQuantum,
    own_alt: Option<f64>,
) -> String {
    let data = read_range_azimuth(text.as_bytes(), ReadOptions::default()).unwrap();
    let noise =
        RangeAzimuthNoise::<S>::new_f64(range_variance, bearing_variance, process_noise).unwrap();
    let mut filter = RangeAzimuthFilter::new(noise);
    let mut altitude =
        AltitudeTracker::<S>::new(AltitudeTrackerConfig::<S>::default_for(quantum).unwrap());
    let own = own_alt.map(|a| OwnAircraft::over_sea_level(S::try_from_f64(a).unwrap(), S::ZERO));
    let mut out = String::from("t,x,vx,res_x,y,vy,res_y,range,azimuth");
    if data.has_alt {
        out.push_str(",alt,alt_rate");
    }
    if own.is_some() {
        out.push_str(
            ",tau,tau_mod,t_cpa,d_cpa,advisory,tau_mod_ra,ra_sense,ra_strength,clear_of_conflict",
        );
    }
    out.push_str(",event\n");
    let mut previous = None;
    let mut cas = CollisionAvoidance::<S>::new();
    let mut threat_state = ThreatState::<S>::new();
    for row in &data.rows {
        let dt = interval::<S>(previous, row.t);
        previous = Some(row.t);
        let r = S::try_from_f64(row.range).unwrap();
        let b = S::try_from_f64(row.azimuth).unwrap();
        let outcome = filter.update(r, b, dt).unwrap();
        if data.has_alt {
            altitude
                .scan(row.alt.map(|a| S::try_from_f64(a).unwrap()), dt)
                .unwrap();
        }
        out.push_str(&row.t_text);
        let residual = match outcome {
            RangeAzimuthOutcome::Filtered(i) => {
                let (s, c) = S::sin_cos(b);
                Some([r * s - i.predicted[0], r * c - i.predicted[1]])
            }
            _ => None,
        };
        for k in 0..2 {
            cell(&mut out, filter.position()[k]);
            cell(&mut out, filter.velocity()[k]);
            optional(&mut out, residual.map(|v| v[k]));
        }
        cell(&mut out, filter.range());
        cell(&mut out, filter.azimuth());
        if data.has_alt {
            optional(&mut out, altitude.estimate().map(|e| e.altitude_ft));
            optional(
                &mut out,
                altitude.estimate().map(|e| e.vertical_rate_ft_per_s),
            );
        }
        if let Some(own) = own {
            if filter.phase() == Phase::Tracking {
                let a = assess(&own, &Intruder::from_track(&filter, altitude.estimate())).unwrap();
                optional(&mut out, a.range_tau_s);
                optional(&mut out, a.ta_modified_tau_s);
                optional(&mut out, a.closest_approach.map(|c| c.time_s));
                optional(&mut out, a.closest_approach.map(|c| c.distance_m));
                out.push(',');
                out.push_str(a.advisory.name());
                optional(&mut out, a.ra_modified_tau_s);
            } else {
                out.push_str(",,,,,,");
            }
            // The RA with memory: the threat state and the resolution.
            let cycle = cas.begin_cycle(&own, false).unwrap();
            let threats: Vec<_> = (filter.phase() == Phase::Tracking)
                .then(|| {
                    threat_state
                        .assess_intruder(
                            &cycle,
                            &Intruder::from_track(&filter, altitude.estimate()),
                            dt,
                        )
                        .unwrap()
                        .geometry
                })
                .flatten()
                .into_iter()
                .collect();
            let ra = cas.resolve(&cycle, &threats, dt).unwrap();
            match ra.advisory {
                Some(a) => {
                    let _ = write!(out, ",{},{}", a.sense.name(), a.strength.name());
                }
                None => out.push_str(",,"),
            }
            out.push(',');
            if ra.clear_of_conflict {
                out.push('1');
            }
        }
        out.push_str(",\n");
    }
    out
}

/// A crossing intruder north of the sensor, from x = −6 km to x = +6 km at
/// y = 5 km (its azimuth wraps from just under 2π to just over 0), range
/// noise σ 15 m, bearing noise σ 0.01 rad; the altitude reported in 100 ft
/// steps, descending 20 ft/s from 9000 ft, with a gap of replies without
/// altitude.
fn crossing_file() -> String {
    let mut noise = Noise::new(99);
    let mut text = String::from("t,range,azimuth,alt\n");
    for k in 0..60 {
        let t = k as f64;
        let (x, y) = (-6000.0 + 200.0 * t, 5000.0);
        let r = x.hypot(y) + 15.0 * noise.gaussian();
        let b = scenario::wrap_two_pi(x.atan2(y) + 0.01 * noise.gaussian());
        let alt = if (20..24).contains(&k) {
            String::new()
        } else {
            format!("{}", ((9000.0 - 20.0 * t) / 100.0).round() * 100.0)
        };
        let _ = writeln!(text, "{t},{r},{b},{alt}");
    }
    text
}

/// [`expected_range_azimuth`] in the representation `--numeric` names
/// (`fixed32`: the Cortex-M3 firmware's range-azimuth filter runs in the
/// fast fixed point's wide format, ScaledScalar).
fn expected_range_azimuth_in(
    numeric: Numeric,
    text: &str,
    args: (f64, f64, f64, AltitudeQuantum, Option<f64>),
) -> String {
    match numeric {
        Numeric::F64 => expected_range_azimuth::<f64>(text, args.0, args.1, args.2, args.3, args.4),
        Numeric::F32 => expected_range_azimuth::<f32>(text, args.0, args.1, args.2, args.3, args.4),
        Numeric::Q32 => expected_range_azimuth::<Fix>(text, args.0, args.1, args.2, args.3, args.4),
        Numeric::Fixed32 => {
            expected_range_azimuth::<ScaledScalar>(text, args.0, args.1, args.2, args.3, args.4)
        }
    }
}

#[test]
fn range_azimuth_output_is_the_library_arithmetic() {
    let text = crossing_file();
    for (numeric, n) in NUMERICS.into_iter().chain([(Numeric::Fixed32, "fixed32")]) {
        // Defaults (σ_R 100 m, σ_B² 7.569e-3, Q 1, Mode C), without threat.
        let got = replay(&format!("--filter range-azimuth --numeric {n}"), &text).unwrap();
        let defaults = (
            1e4,
            PAPER_BEARING_VARIANCE,
            1.0,
            AltitudeQuantum::ModeC,
            None,
        );
        assert_eq!(
            got,
            expected_range_azimuth_in(numeric, &text, defaults),
            "{n}"
        );
        // Every option, with the threat columns.
        let line = format!(
            "--filter range-azimuth --range-sigma-m 15 --bearing-variance 1e-4 --process-noise 0.5 \
             --alt-quantum 25 --own-alt 9000 --numeric {n}"
        );
        let got = replay(&line, &text).unwrap();
        let args = (225.0, 1e-4, 0.5, AltitudeQuantum::ModeS25, Some(9000.0));
        assert_eq!(
            got,
            expected_range_azimuth_in(numeric, &text, args),
            "{line}"
        );
    }
}

/// Output cells of `column` (by header name), `None` for an empty cell.
fn column(output: &str, name: &str) -> Vec<Option<String>> {
    let mut lines = output.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let index = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no {name}"));
    lines
        .map(|l| {
            let c = l.split(',').nth(index).unwrap();
            (!c.is_empty()).then(|| c.to_string())
        })
        .collect()
}

fn numbers(output: &str, name: &str) -> Vec<Option<f64>> {
    column(output, name)
        .into_iter()
        .map(|c| c.map(|c| c.parse().unwrap()))
        .collect()
}

#[test]
fn range_azimuth_tracks_through_the_azimuth_wrap() {
    let text = crossing_file();
    for (_, n) in NUMERICS {
        let out = replay(
            &format!(
                "--filter range-azimuth --range-sigma-m 15 --bearing-variance 1e-4 --numeric {n}"
            ),
            &text,
        )
        .unwrap();
        let x = numbers(&out, "x");
        let azimuth = numbers(&out, "azimuth");
        let vx = numbers(&out, "vx");
        // Truth x = −6000 + 200 t: the estimate stays within 150 m (σ_C is
        // 50–78 m here) and the velocity within 30 m/s once settled,
        // straight through the wrap at t = 30 s; no jump of the estimate.
        for k in 10..60 {
            let truth = -6000.0 + 200.0 * k as f64;
            assert!(
                (x[k].unwrap() - truth).abs() < 150.0,
                "{n} t={k}: {:?}",
                x[k]
            );
            assert!(
                (vx[k].unwrap() - 200.0).abs() < 30.0,
                "{n} t={k}: {:?}",
                vx[k]
            );
        }
        // The output azimuth is in [0, 2π) and wraps once, near t = 30 s.
        let az: Vec<f64> = azimuth.iter().map(|a| a.unwrap()).collect();
        assert!(az.iter().all(|a| (0.0..std::f64::consts::TAU).contains(a)));
        let wraps: Vec<usize> = (1..az.len()).filter(|&k| az[k] < az[k - 1] - 3.0).collect();
        assert_eq!(wraps.len(), 1, "{n}: {wraps:?}");
        assert!((28..=32).contains(&wraps[0]), "{n}: {wraps:?}");
        // Residual columns empty exactly on the two initialisation rows.
        let res = column(&out, "res_x");
        assert!(res[0].is_none() && res[1].is_none());
        assert!(res[2..].iter().all(Option::is_some));
    }
}

// Head-on at 600 kt closure, same altitude, own altitude 8000 ft (SL 5:
// TA tau 40 s, DMOD 0.75 NM; RA tau 25 s, DMOD 0.55 NM); the intruder
// starts at 10 NM on azimuth 1 rad, one noiseless report a second. With the
// closure c = 600 kt = 1/6 NM/s, tests/it/tcas/analytic_encounters.rs solves τ_mod = TAU:
// the TA starts at r = 6.75 NM, the RA at r = 4.238044 NM. In time:
//   TA: (10 − 6.75)·6 = 19.5 s, so the first TA row is t = 20;
//   RA: (10 − 4.238044)·6 = 34.572 s, so the first RA row is t = 35.
// Range tau and t_cpa are r/c = 60 − t; d_cpa = 0;
// τ_mod(TA) = (r² − 0.75²)/(r·c) with r = 10 − t/6 NM.
const HEAD_ON_ROWS: usize = 56;

fn head_on_file(alt: impl Fn(usize) -> Option<f64>, with_alt: bool) -> String {
    let closure = 600.0 * KT;
    let mut text = String::from(if with_alt {
        "t,range,azimuth,alt\n"
    } else {
        "t,range,azimuth\n"
    });
    for k in 0..HEAD_ON_ROWS {
        let r = 10.0 * NM - closure * k as f64;
        let _ = write!(text, "{k},{r},1");
        if with_alt {
            text.push(',');
            if let Some(a) = alt(k) {
                let _ = write!(text, "{a}");
            }
        }
        text.push('\n');
    }
    text
}

fn advisories(out: &str) -> Vec<String> {
    column(out, "advisory")
        .into_iter()
        .map(|c| c.unwrap_or_default())
        .collect()
}

/// `n` copies of `s`.
fn run_of(s: &str, n: usize) -> Vec<String> {
    vec![s.to_string(); n]
}

/// The RA columns: a head-on 0.1 NM abeam from 5 NM at 600 kt, the
/// intruder level 100 ft above the own aircraft (8000 ft), past closest
/// approach (t = 30 s) to t = 59. One RA: a positive descend (the
/// non-crossing sense, as the head-on worked by hand in
/// `tcas::logic::sense_and_strength_of_the_head_on`) from the first row
/// the stateless advisory is an RA, in force on every row until the range
/// opens, then clear of conflict on exactly one row and no RA after it.
#[test]
fn ra_columns_give_one_descend_then_clear_of_conflict() {
    let mut text = String::from("t,range,azimuth,alt\n");
    for k in 0..60 {
        let (x, y) = (0.1 * NM, 5.0 * NM - 600.0 * KT * k as f64);
        let azimuth = x.atan2(y).rem_euclid(std::f64::consts::TAU);
        let _ = writeln!(text, "{k},{},{azimuth},8100", x.hypot(y));
    }
    for (_, n) in NUMERICS {
        let out = replay(
            &format!("--filter range-azimuth --range-sigma-m 15 --own-alt 8000 --numeric {n}"),
            &text,
        )
        .unwrap();
        let sense = column(&out, "ra_sense");
        let strength = column(&out, "ra_strength");
        let coc = column(&out, "clear_of_conflict");
        let onset = sense.iter().position(Option::is_some).unwrap();
        let end = coc.iter().position(Option::is_some).unwrap();
        assert_eq!(
            Some(onset),
            advisories(&out).iter().position(|a| a == "ra"),
            "{n}"
        );
        assert!(end > 30 && end < 45, "{n}: clear of conflict at {end}");
        assert!(
            sense[onset..end]
                .iter()
                .all(|s| s.as_deref() == Some("down")),
            "{n}: {sense:?}"
        );
        assert_eq!(strength[onset].as_deref(), Some("positive"), "{n}");
        assert!(sense[end..].iter().all(Option::is_none), "{n}");
        assert_eq!(coc.iter().filter(|c| c.is_some()).count(), 1, "{n}");
        assert_eq!(coc[end].as_deref(), Some("1"), "{n}");
    }
}

#[test]
fn head_on_encounter_gives_ta_then_ra_at_the_analytic_onsets() {
    let text = head_on_file(|_| Some(8000.0), true);
    for (_, n) in NUMERICS {
        let out = replay(
            &format!("--filter range-azimuth --range-sigma-m 15 --own-alt 8000 --numeric {n}"),
            &text,
        )
        .unwrap();
        // First row: no velocity, no threat columns; then none until t = 19,
        // TA from t = 20, RA from t = 35.
        let mut want = run_of("", 1);
        want.extend(run_of("none", 19));
        want.extend(run_of("ta", 15));
        want.extend(run_of("ra", HEAD_ON_ROWS - 35));
        assert_eq!(advisories(&out), want, "{n}");

        let tau = numbers(&out, "tau");
        let tau_mod = numbers(&out, "tau_mod");
        let tau_mod_ra = numbers(&out, "tau_mod_ra");
        let t_cpa = numbers(&out, "t_cpa");
        let d_cpa = numbers(&out, "d_cpa");
        assert!(tau[0].is_none() && tau_mod[0].is_none() && t_cpa[0].is_none());
        let tol = if n == "f32" { 2e-2 } else { 1e-6 };
        for k in 1..HEAD_ON_ROWS {
            let t = k as f64;
            let r_nm = 10.0 - t / 6.0;
            assert!(
                (tau[k].unwrap() - (60.0 - t)).abs() < tol,
                "{n} t={t}: {:?}",
                tau[k]
            );
            assert!((t_cpa[k].unwrap() - (60.0 - t)).abs() < tol, "{n} t={t}");
            assert!(d_cpa[k].unwrap().abs() < 0.05, "{n} t={t}: {:?}", d_cpa[k]);
            let ta = (r_nm * r_nm - 0.75 * 0.75) / (r_nm / 6.0);
            assert!((tau_mod[k].unwrap() - ta).abs() < tol, "{n} t={t}");
            let ra = (r_nm * r_nm - 0.55 * 0.55) / (r_nm / 6.0);
            assert!((tau_mod_ra[k].unwrap() - ra).abs() < tol, "{n} t={t}");
        }
        // The onsets are where the modified taus cross TAU.
        assert!(tau_mod[19].unwrap() > 40.0 && tau_mod[20].unwrap() <= 40.0);
        assert!(tau_mod_ra[34].unwrap() > 25.0 && tau_mod_ra[35].unwrap() <= 25.0);
        // The altitude columns hold the reported, level altitude.
        for a in numbers(&out, "alt") {
            assert!((a.unwrap() - 8000.0).abs() < 1e-6);
        }
    }
}

#[test]
fn without_altitude_the_intruder_raises_at_most_a_ta() {
    // No alt column: same TA onset (no vertical test), never an RA, and no
    // altitude columns.
    let text = head_on_file(|_| None, false);
    for (_, n) in NUMERICS {
        let out = replay(
            &format!("--filter range-azimuth --range-sigma-m 15 --own-alt 8000 --numeric {n}"),
            &text,
        )
        .unwrap();
        assert_eq!(
            out.lines().next(),
            Some(
                "t,x,vx,res_x,y,vy,res_y,range,azimuth,tau,tau_mod,t_cpa,d_cpa,advisory,tau_mod_ra,\
                 ra_sense,ra_strength,clear_of_conflict,event"
            )
        );
        let mut want = run_of("", 1);
        want.extend(run_of("none", 19));
        want.extend(run_of("ta", HEAD_ON_ROWS - 20));
        assert_eq!(advisories(&out), want, "{n}");
    }
    // Reports stop after t = 10: the tracker coasts 6 s (alt still given at
    // t = 11..16), then the intruder counts as not reporting (empty from
    // t = 17): the TA still comes at t = 20, the RA never.
    let text = head_on_file(|k| (k <= 10).then_some(8000.0), true);
    for (_, n) in NUMERICS {
        let out = replay(
            &format!("--filter range-azimuth --range-sigma-m 15 --own-alt 8000 --numeric {n}"),
            &text,
        )
        .unwrap();
        let alt = column(&out, "alt");
        assert!(alt[..17].iter().all(Option::is_some), "{n}: {alt:?}");
        assert!(alt[17..].iter().all(Option::is_none), "{n}: {alt:?}");
        let mut want = run_of("", 1);
        want.extend(run_of("none", 19));
        want.extend(run_of("ta", HEAD_ON_ROWS - 20));
        assert_eq!(advisories(&out), want, "{n}");
    }
    // An alt column without --own-alt: the altitude columns, no threat.
    let out = replay(
        "--filter range-azimuth",
        &head_on_file(|_| Some(8000.0), true),
    )
    .unwrap();
    assert_eq!(
        out.lines().next(),
        Some("t,x,vx,res_x,y,vy,res_y,range,azimuth,alt,alt_rate,event")
    );
}

#[test]
fn diverging_intruder_has_empty_taus_and_no_alert() {
    // Opening from 1 NM at 300 kt on azimuth 4 rad, same altitude: range
    // tau undefined (empty), modified taus empty (outside both DMODs),
    // t_cpa = 0, d_cpa = r; proximate while within 6 NM, then none.
    let mut text = String::from("t,range,azimuth,alt\n");
    for k in 0..30 {
        let r = NM + 300.0 * KT * k as f64;
        let _ = writeln!(text, "{k},{r},4,8000");
    }
    let out = replay(
        "--filter range-azimuth --range-sigma-m 15 --own-alt 8000",
        &text,
    )
    .unwrap();
    for name in ["tau", "tau_mod", "tau_mod_ra"] {
        assert!(column(&out, name).iter().all(Option::is_none), "{name}");
    }
    let t_cpa = numbers(&out, "t_cpa");
    let d_cpa = numbers(&out, "d_cpa");
    let range = numbers(&out, "range");
    for k in 1..30 {
        assert_eq!(t_cpa[k], Some(0.0));
        assert!((d_cpa[k].unwrap() - range[k].unwrap()).abs() < 1e-6);
    }
    // r ≤ 6 NM while 1 + t/12 ≤ 6 NM, i.e. t ≤ 60: proximate throughout.
    assert!(advisories(&out)[1..].iter().all(|a| a == "proximate"));
}

/// The TCAS-realistic scenario (14 NM head-on with 0.2 NM offset, range σ
/// 50 ft, bearing σ 5°, Mode C) end to end: `simulate`'s measurements
/// through `replay --own-alt 8000`, against the truth's advisory timeline.
#[test]
fn tcas_converging_scenario_advisories_follow_the_truth() {
    let run = scenario::generate("tcas-converging", 1).unwrap();
    let text = run.measurements_csv();
    let bearing_variance = (5f64.to_radians()).powi(2);
    let own = OwnAircraft::over_sea_level(8000.0, 0.0);
    let truth: Vec<Advisory> = run
        .truth()
        .map(|s| {
            let intruder = Intruder {
                relative_position_m: [s.x, s.y],
                relative_velocity_m_per_s: [s.vx, s.vy],
                altitude: s
                    .alt_ft
                    .map(|a| abtrack::filter::altitude::AltitudeEstimate {
                        altitude_ft: a,
                        vertical_rate_ft_per_s: 5.0,
                    }),
            };
            assess(&own, &intruder).unwrap().advisory
        })
        .collect();
    let onset = |seq: &[Advisory], level: Advisory| seq.iter().position(|a| *a >= level);
    let truth_ta = onset(&truth, Advisory::Traffic).unwrap();
    let truth_ra = onset(&truth, Advisory::Resolution).unwrap();
    let end_of = |seq: &[Advisory], level: Advisory| seq.iter().rposition(|a| *a >= level);
    let truth_end = end_of(&truth, Advisory::Traffic).unwrap();
    for (_, n) in NUMERICS {
        let out = replay(
            &format!(
                "--filter range-azimuth --range-sigma-m 15.24 --bearing-variance {bearing_variance} \
                 --own-alt 8000 --numeric {n}"
            ),
            &text,
        )
        .unwrap();
        let estimated: Vec<Advisory> = advisories(&out)
            .iter()
            .map(|a| match a.as_str() {
                "ra" => Advisory::Resolution,
                "ta" => Advisory::Traffic,
                "proximate" => Advisory::ProximateTraffic,
                _ => Advisory::None,
            })
            .collect();
        let ta = onset(&estimated, Advisory::Traffic).unwrap();
        let ra = onset(&estimated, Advisory::Resolution).unwrap();
        let end = end_of(&estimated, Advisory::Traffic).unwrap();
        eprintln!(
            "{n}: TA from {ta} s (truth {truth_ta}), RA from {ra} s (truth {truth_ra}), \
             TA or RA until {end} s (truth {truth_end})"
        );
        assert!(ta.abs_diff(truth_ta) <= 3, "{n}: TA {ta} vs {truth_ta}");
        assert!(ra.abs_diff(truth_ra) <= 3, "{n}: RA {ra} vs {truth_ra}");
        assert!(
            end.abs_diff(truth_end) <= 3,
            "{n}: end {end} vs {truth_end}"
        );
        // One alert, without flicker: TA or RA throughout, the RA in one
        // piece inside it.
        assert!(
            estimated[ta..=end].iter().all(|a| *a >= Advisory::Traffic),
            "{n}"
        );
        let ra_end = end_of(&estimated, Advisory::Resolution).unwrap();
        assert!(
            estimated[ra..=ra_end]
                .iter()
                .all(|a| *a == Advisory::Resolution),
            "{n}"
        );
    }
}

// ------------------------------------------------------------------ errors

#[test]
fn range_azimuth_input_errors_name_line_and_column() {
    let field = |line, column, name, text: &str, why| CsvError::Field {
        line,
        column,
        name,
        text: text.into(),
        why,
    };
    let cases: [(&str, CsvError, &str); 6] = [
        (
            "t,x,y\n0,1,2\n",
            CsvError::MissingColumns {
                format: InputFormat::RangeAzimuth,
                missing: vec!["range", "azimuth"],
                found: "t,x,y".into(),
            },
            "line 1: the header \"t,x,y\" has no column range, azimuth; this input needs the \
             columns t, range, azimuth (optional: alt) in any order, other columns are ignored \
             (this header is for --filter ab or abg)",
        ),
        (
            "t,range,azimuth\n0,1000,0.5\n1,0,0.5\n",
            field(3, 2, "range", "0", Refusal::NotPositive),
            "line 3, column 2 (range): 0 is not > 0",
        ),
        (
            "t,range,azimuth,alt\n0,1000,0.5,8000\n1,990,,8000\n",
            field(3, 3, "azimuth", "", Refusal::NotANumber),
            "line 3, column 3 (azimuth)",
        ),
        (
            "t,range,azimuth,alt\n0,1000,0.5,FL80\n",
            field(2, 4, "alt", "FL80", Refusal::NotANumber),
            "line 2, column 4 (alt): \"FL80\" is not a number",
        ),
        (
            "t,range,azimuth,alt\n0,1000,0.5\n",
            CsvError::FieldCount {
                line: 2,
                expected: 4,
                found: 3,
            },
            "line 2: 3 fields, expected 4",
        ),
        (
            "t,range,azimuth\n0,1000,inf\n",
            field(2, 3, "azimuth", "inf", Refusal::NotFinite),
            "line 2, column 3 (azimuth)",
        ),
    ];
    for (text, error, message) in cases {
        let e = replay("--filter range-azimuth", text).unwrap_err();
        assert_eq!(e, Failure::Input(error), "{text:?}");
        assert!(e.to_string().contains(message), "{e} lacks {message}");
    }
    // And the other way round.
    let e = replay("--filter ab --schedule m1", "t,range,azimuth\n0,1,2\n").unwrap_err();
    assert!(
        e.to_string()
            .ends_with("(this header is for --filter range-azimuth)"),
        "{e}"
    );
    // Empty alt is allowed; the header alone is an empty (valid) run.
    assert!(replay(
        "--filter range-azimuth",
        "t,range,azimuth,alt\n0,1000,0.5,\n"
    )
    .is_ok());
    assert_eq!(
        replay("--filter range-azimuth", "t,range,azimuth\n").unwrap(),
        "t,x,vx,res_x,y,vy,res_y,range,azimuth,event\n"
    );
}

#[test]
fn range_azimuth_options_are_checked() {
    let refused = [
        (
            "--filter range-azimuth --range-sigma-m 0 d.csv",
            "--range-sigma-m: 0 is out of range (must be > 0)",
        ),
        (
            "--filter range-azimuth --bearing-variance -1e-3 d.csv",
            "--bearing-variance: -0.001 is out of range (must be > 0)",
        ),
        (
            "--filter range-azimuth --process-noise -1 d.csv",
            "--process-noise: -1 is out of range (must be >= 0)",
        ),
        (
            "--filter range-azimuth --own-alt high d.csv",
            "\"high\" is not a finite number",
        ),
        ("--filter range-azimuth --alt-quantum 50 d.csv", "'50'"),
        (
            "--filter range-azimuth --bearing-variance 1e-3 --bearing-sigma-deg 2 d.csv",
            "cannot be used with",
        ),
        (
            "--filter range-azimuth --alpha 0.5 --beta 0.3 d.csv",
            "--alpha does not apply to --filter range-azimuth",
        ),
    ];
    for (line, message) in refused {
        let text = refusal(line);
        assert!(text.contains(message), "{line}: {text}");
    }
    // --bearing-sigma-deg is the same variance in degrees.
    assert_eq!(
        config_of("--filter range-azimuth --bearing-sigma-deg 5 d.csv").filter,
        FilterKind::RangeAzimuth(RangeAzimuthOptions {
            bearing_variance_rad2: 5f64.to_radians().powi(2),
            ..RangeAzimuthOptions::DEFAULT
        })
    );
    assert_eq!(
        config_of("--filter range-azimuth d.csv").filter,
        FilterKind::RangeAzimuth(RangeAzimuthOptions::DEFAULT)
    );
    assert_eq!(
        config_of("--filter=range-azimuth --own-alt=8000 --alt-quantum 25 --process-noise 0 d.csv")
            .filter,
        FilterKind::RangeAzimuth(RangeAzimuthOptions {
            own_altitude_ft: Some(8000.0),
            altitude_quantum: AltitudeQuantum::ModeS25,
            process_noise: 0.0,
            ..RangeAzimuthOptions::DEFAULT
        })
    );
}

#[test]
fn scans_group_rows_sharing_a_time() {
    let scans = ReadOptions {
        times: TimeOrder::Scans,
        ..ReadOptions::default()
    };
    let text = "t,x,y\n0,1,1\n0,2,2\n1,3,3\n2,4,4\n2,5,5\n2,6,6\n";
    let m = read_measurements(text.as_bytes(), scans).unwrap();
    let sizes: Vec<usize> = m.scans().map(<[_]>::len).collect();
    assert_eq!(sizes, [2, 1, 3]);
    // Single-target reading takes the repeated time (a duplicate report,
    // which the runner skips).
    assert!(read_measurements(text.as_bytes(), ReadOptions::default()).is_ok());
    // A time going back is read as it is (the runners skip and count it).
    let m = read_measurements("t,x\n1,0\n0,0\n".as_bytes(), scans).unwrap();
    assert_eq!(m.scans().count(), 2);
    // Two scans 1 ms apart are read as two scans (the track table skips the
    // second and counts it).
    let m = read_measurements("t,x\n1,0\n1.001,0\n".as_bytes(), scans).unwrap();
    assert_eq!(m.scans().count(), 2);
}

#[test]
fn help_lists_every_schedule_and_option() {
    let help = ReplayArgs::command().render_long_help().to_string();
    for info in SCHEDULES {
        // Each entry's names on a line of their own, as "a | b | c".
        let listed = help
            .lines()
            .any(|l| l.trim().split(" | ").eq(info.names.iter().copied()));
        assert!(listed, "--help lacks {:?}", info.names);
        assert!(
            help.contains(info.parameters),
            "--help lacks {}",
            info.parameters
        );
    }
    for option in [
        "--filter",
        "--schedule",
        "--alpha",
        "--beta",
        "--gamma",
        "--range-sigma",
        "--bearing-variance",
        "--process-noise",
        "--alt-quantum",
        "--own-alt",
        "--numeric",
        "--help",
        "range-azimuth",
        "tau_mod_ra",
        "member_a",
    ] {
        assert!(help.contains(option), "--help lacks {option}");
    }
}

// -------------------------------------------------------------- end to end

#[test]
fn binary_runs_schedules_and_range_azimuth() {
    let (text, _) = generated_track(2);
    binary_writes_what_the_library_does(
        "--filter ab --schedule liu-adaptive --numeric q32.32",
        "track.csv",
        &text,
    );
    let text = head_on_file(|_| Some(8000.0), true);
    binary_writes_what_the_library_does(
        "--filter range-azimuth --own-alt 8000 --numeric f32",
        "head-on.csv",
        &text,
    );
}

/// The binary, run on `text` written to a file, succeeds and prints what
/// the library's replay gives for the same arguments.
fn binary_writes_what_the_library_does(args: &str, file_name: &str, text: &str) {
    let path = temp_file(file_name, text);
    let out = replay_binary()
        .args(args.split_whitespace())
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        replay(args, text).unwrap()
    );
    let _ = std::fs::remove_file(path);
}

#[test]
fn binary_writes_nothing_on_a_late_error() {
    // A bad azimuth on the last line: nothing written, the line and column
    // named, exit status 1.
    let mut text = head_on_file(|_| Some(8000.0), true);
    text.push_str("56,1000,east,8000\n");
    let path = temp_file("late-error.csv", &text);
    let out = replay_binary()
        .args(["--filter", "range-azimuth", "--own-alt", "8000"])
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty(), "partial output written");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains(&format!("line {}, column 3 (azimuth)", HEAD_ON_ROWS + 2)),
        "{err}"
    );
    let _ = std::fs::remove_file(path);

    // A bad spec: exit status 2, the parser's message with the caret.
    let out = replay_binary()
        .args(["--filter", "ab", "--schedule", "m4:window=0", "x.csv"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("parameter `window` is out of range (at byte 3)"),
        "{err}"
    );
    assert!(err.contains("\n  m4:window=0\n     ^"), "{err}");
}
