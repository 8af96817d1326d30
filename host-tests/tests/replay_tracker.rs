//! `replay --tracker` (issue 5): the output against the track table driven
//! directly, ids through a crossing, the threat columns on a TCAS picture,
//! options and errors.
//!
//! The expected outputs are built by running `TrackTable` on the scenario's
//! own scans (not on the CSV) and formatting every value with `Display`, so
//! the comparisons are exact string equality in all three representations,
//! and they also check the CSV round trip.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::{Display, Write as _};
use std::path::PathBuf;
use std::process::Command as Process;

use abtrack::gain::spec::ScheduleSpec;
use abtrack::tcas::{assess, Intruder, OwnAircraft};
use abtrack::track::defaults::{
    default_cartesian, default_polar, DefaultCartesianTrack, DefaultPolarTrack,
};
use abtrack::track::{
    Association, Measurement, ScheduledTrack, TrackFilter, TrackTable, TrackerConfig,
};
use abtrack::{Fix, Scalar};
use abtrack_host_tests::cli::{parse_replay_args, replay_usage, Command, UsageError};
use abtrack_host_tests::csv_input::CsvError;
use abtrack_host_tests::replay::{Failure, ReplayError, ReplaySchedule};
use abtrack_host_tests::replay_tracker::{
    replay_tracker_reader, with_large_stack, with_params, TrackerReplay,
};
use abtrack_host_tests::scenario::{self, ScenarioRun};

const SEED: u64 = 1;

fn args(s: &str) -> Result<Command, UsageError> {
    parse_replay_args(s.split_whitespace().map(String::from))
}

/// Runs `replay <command line> -` on `input` in-process.
fn tracker(command_line: &str, input: &str) -> Result<TrackerReplay, Failure> {
    match args(&format!("{command_line} -")) {
        Ok(Command::Tracker { options, .. }) => replay_tracker_reader(&options, input.as_bytes()),
        other => panic!("{command_line}: {other:?}"),
    }
}

fn to_measurement<S: Scalar>(m: &scenario::Measurement) -> Measurement<S> {
    match *m {
        scenario::Measurement::Cartesian { x, y, .. } => Measurement::Cartesian {
            x: S::try_from_f64(x).unwrap(),
            y: S::try_from_f64(y).unwrap(),
        },
        scenario::Measurement::Polar { range, azimuth, .. } => Measurement::Polar {
            range: S::try_from_f64(range).unwrap(),
            azimuth: S::try_from_f64(azimuth).unwrap(),
        },
    }
}

/// The table driven directly over the scenario's scans: the expected
/// `replay --tracker` output (without threat columns). Scans without a
/// measurement have no row in the CSV, so they are skipped here too; the
/// clock is round((t − t₀)·1000) ms.
fn expected<S: Scalar + Display + Send + Sync, F: TrackFilter<S>, const N: usize>(
    run: &ScenarioRun,
    config: &TrackerConfig<S, F::Params>,
) -> String
where
    F::Params: Sync,
{
    with_large_stack(|| expected_on_this_thread::<S, F, N>(run, config))
}

fn expected_on_this_thread<S: Scalar + Display, F: TrackFilter<S>, const N: usize>(
    run: &ScenarioRun,
    config: &TrackerConfig<S, F::Params>,
) -> String {
    let mut table: Box<TrackTable<S, F, N, 256>> = Box::new(TrackTable::new());
    let mut out = String::from("t,track_id,status,x,y,vx,vy\n");
    let scans: Vec<_> = run
        .scans
        .iter()
        .filter(|s| !s.measurements.is_empty())
        .collect();
    let t0 = scans[0].t;
    for scan in scans {
        let measurements: Vec<Measurement<S>> =
            scan.measurements.iter().map(to_measurement).collect();
        let mut codes = vec![Association::OutsideGates; measurements.len()];
        let now_ms = ((scan.t - t0) * 1000.0).round() as u32;
        table
            .scan(config, now_ms, &measurements, &mut codes)
            .unwrap();
        let mut tracks: Vec<_> = table.tracks().collect();
        tracks.sort_by_key(|t| t.id());
        for t in tracks {
            let [x, y] = t.position();
            let [vx, vy] = t.velocity();
            writeln!(
                out,
                "{},{},{},{x},{y},{vx},{vy}",
                scan.t,
                t.id(),
                t.status().as_str()
            )
            .unwrap();
        }
    }
    out
}

/// (t, id, status, x, y, vx, vy) of every output row.
type Row = (f64, u32, String, f64, f64, f64, f64);

fn rows(csv: &str) -> Vec<Row> {
    csv.lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let n = |i: usize| f[i].parse::<f64>().unwrap();
            (
                n(0),
                f[1].parse().unwrap(),
                f[2].to_string(),
                n(3),
                n(4),
                n(5),
                n(6),
            )
        })
        .collect()
}

fn crossing() -> ScenarioRun {
    scenario::generate("two-crossing", SEED).unwrap()
}

#[test]
fn default_cartesian_output_is_the_table_driven_directly_in_every_numeric() {
    let run = crossing();
    let csv = run.measurements_csv();
    fn check<S: Scalar + Display>(run: &ScenarioRun, csv: &str, numeric: &str) {
        let config = default_cartesian::<S>().unwrap();
        let want = expected::<S, DefaultCartesianTrack<S>, 64>(run, &config);
        let got = tracker(&format!("--tracker --numeric {numeric}"), csv).unwrap();
        assert!(got.csv.lines().count() > 100, "{numeric}: too few rows");
        assert_eq!(got.csv, want, "{numeric}");
    }
    check::<f64>(&run, &csv, "f64");
    check::<f32>(&run, &csv, "f32");
    check::<Fix>(&run, &csv, "fixed");
    // No option at all is the f64 default.
    assert_eq!(
        tracker("--tracker", &csv).unwrap().csv,
        tracker("--tracker --numeric f64 --capacity 64", &csv)
            .unwrap()
            .csv
    );
}

#[test]
fn two_crossing_targets_keep_two_confirmed_ids() {
    let run = crossing();
    let out = tracker("--tracker", &run.measurements_csv()).unwrap();
    let rows = rows(&out.csv);
    let confirmed: BTreeSet<u32> = rows
        .iter()
        .filter(|r| r.2 == "confirmed")
        .map(|r| r.1)
        .collect();
    assert_eq!(confirmed.len(), 2, "ids ever confirmed: {confirmed:?}");

    // Each id is present in every scan from its confirmation to the end.
    let times: Vec<f64> = {
        let mut t: Vec<f64> = run
            .scans
            .iter()
            .filter(|s| !s.measurements.is_empty())
            .map(|s| s.t)
            .collect();
        t.dedup();
        t
    };
    let last_t = *times.last().unwrap();
    for &id in &confirmed {
        let first = rows
            .iter()
            .find(|r| r.1 == id && r.2 == "confirmed")
            .unwrap()
            .0;
        let present: Vec<f64> = rows
            .iter()
            .filter(|r| r.1 == id && r.0 >= first)
            .map(|r| r.0)
            .collect();
        let scans: Vec<f64> = times.iter().copied().filter(|&t| t >= first).collect();
        assert_eq!(present, scans, "track {id} is not continuous");
        assert!(
            rows.iter()
                .any(|r| r.1 == id && r.0 == last_t && r.2 != "tentative"),
            "track {id} is not held to the end"
        );
    }

    // Each id stays on the same target: nearest target at the first scan
    // where both are confirmed and at the last scan (after the crossing).
    let nearest = |t: f64, id: u32| -> u32 {
        let r = rows.iter().find(|r| r.0 == t && r.1 == id).unwrap();
        let scan = run.scans.iter().find(|s| s.t == t).unwrap();
        scan.truth
            .iter()
            .min_by(|a, b| {
                let da = (a.x - r.3).hypot(a.y - r.4);
                let db = (b.x - r.3).hypot(b.y - r.4);
                da.total_cmp(&db)
            })
            .unwrap()
            .target
    };
    let both_from = confirmed
        .iter()
        .map(|&id| {
            rows.iter()
                .find(|r| r.1 == id && r.2 == "confirmed")
                .unwrap()
                .0
        })
        .fold(f64::MIN, f64::max);
    let start: BTreeMap<u32, u32> = confirmed
        .iter()
        .map(|&id| (id, nearest(both_from, id)))
        .collect();
    let end: BTreeMap<u32, u32> = confirmed
        .iter()
        .map(|&id| (id, nearest(last_t, id)))
        .collect();
    assert_eq!(
        start.values().collect::<BTreeSet<_>>().len(),
        2,
        "{start:?}"
    );
    assert_eq!(start, end, "ids swapped targets through the crossing");
}

#[test]
fn options_match_the_table_configured_the_same_way() {
    let run = crossing();
    let csv = run.measurements_csv();

    // --capacity 16 --confirm 2/3 --delete 5.
    let config = default_cartesian::<f64>()
        .unwrap()
        .with_confirmation(2, 3)
        .unwrap()
        .with_deletion(5, 2)
        .unwrap();
    let want = expected::<f64, DefaultCartesianTrack<f64>, 16>(&run, &config);
    let got = tracker("--tracker --capacity 16 --confirm 2/3 --delete 5", &csv).unwrap();
    assert_eq!(got.csv, want);
    assert_ne!(
        got.csv,
        tracker("--tracker", &csv).unwrap().csv,
        "options had no effect"
    );

    // --schedule: the same lifecycle with another schedule, in f32.
    let spec = ScheduleSpec::parse("m1:alpha=0.5").unwrap();
    let schedule = ReplaySchedule::<f32, 2>::from_spec(&spec).unwrap();
    let config = with_params(&default_cartesian::<f32>().unwrap(), schedule).unwrap();
    let want = expected::<f32, ScheduledTrack<f32, ReplaySchedule<f32, 2>>, 256>(&run, &config);
    let got = tracker(
        "--tracker --schedule m1:alpha=0.5 --numeric f32 --capacity 256",
        &csv,
    )
    .unwrap();
    assert_eq!(got.csv, want);
}

#[test]
fn polar_tcas_picture_with_own_altitude() {
    let run = scenario::generate("tcas-30", SEED).unwrap();
    let csv = run.measurements_csv();
    assert!(csv.starts_with("t,range,azimuth"), "{}", &csv[..40]);
    let own_ft = scenario::TCAS_OWN_ALTITUDE_FT;

    // Without --own-alt: the default polar table driven directly.
    let config = default_polar::<f64>().unwrap();
    let want = expected::<f64, DefaultPolarTrack<f64>, 64>(&run, &config);
    let plain = tracker("--tracker", &csv).unwrap();
    assert_eq!(plain.csv, want);

    let out = tracker(&format!("--tracker --own-alt {own_ft}"), &csv).unwrap();
    let mut lines = out.csv.lines();
    assert_eq!(
        lines.next(),
        Some("t,track_id,status,x,y,vx,vy,tau,tau_mod,t_cpa,d_cpa,advisory,tau_mod_ra")
    );
    // The first seven columns are the plain run's.
    for (a, b) in out.csv.lines().skip(1).zip(plain.csv.lines().skip(1)) {
        assert!(a.starts_with(&format!("{b},")), "{a} vs {b}");
    }
    // Each row's threat columns are tcas::assess on that row's state, with
    // no altitude (the table keeps none).
    let own = OwnAircraft::over_sea_level(own_ft, 0.0);
    let mut advisories = BTreeMap::<String, usize>::new();
    let mut confirmed = BTreeSet::new();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 13, "{line}");
        let n = |i: usize| f[i].parse::<f64>().unwrap();
        let a = assess(
            &own,
            &Intruder {
                relative_position_m: [n(3), n(4)],
                relative_velocity_m_per_s: [n(5), n(6)],
                altitude: None,
            },
        )
        .unwrap();
        let opt = |v: Option<f64>| v.map(|v| v.to_string()).unwrap_or_default();
        assert_eq!(f[7], opt(a.range_tau_s), "{line}");
        assert_eq!(f[8], opt(a.ta_modified_tau_s), "{line}");
        assert_eq!(f[9], opt(a.closest_approach.map(|c| c.time_s)), "{line}");
        assert_eq!(
            f[10],
            opt(a.closest_approach.map(|c| c.distance_m)),
            "{line}"
        );
        assert_eq!(f[11], a.advisory.name(), "{line}");
        assert_eq!(f[12], opt(a.ra_modified_tau_s), "{line}");
        *advisories.entry(f[11].to_string()).or_default() += 1;
        if f[2] == "confirmed" {
            confirmed.insert(f[1].to_string());
        }
    }
    // Horizontal only: never an RA; the picture has traffic inside 6 NM.
    assert!(!advisories.contains_key("ra"), "{advisories:?}");
    assert!(
        advisories.contains_key("proximate") || advisories.contains_key("ta"),
        "{advisories:?}"
    );
    assert!(
        confirmed.len() >= 20,
        "{} confirmed tracks",
        confirmed.len()
    );

    // Every numeric runs on the polar file too.
    for numeric in ["f32", "fixed"] {
        let o = tracker(
            &format!("--tracker --own-alt {own_ft} --numeric {numeric}"),
            &csv,
        )
        .unwrap();
        assert!(o.csv.lines().count() > 1000, "{numeric}");
    }
}

#[test]
fn verbose_log_counts_the_association_codes() {
    let text = "t,x,y\n0,0,0\n0,3000,3000\n1,100,0\n1,3000,3100\n2,200,0\n3,300,0\n3,-4000,-4000\n";
    let out = tracker("--tracker", text).unwrap();
    let log: Vec<&str> = out.scan_log.lines().collect();
    assert_eq!(log.len(), 4);
    assert!(
        log[0].starts_with("t=0 measurements=2 updated=0 started=0 "),
        "{}",
        log[0]
    );
    assert!(log[0].contains("outside-gates=2"), "{}", log[0]);
    assert!(
        log[1].starts_with("t=1 measurements=2 updated=0 started=2 "),
        "{}",
        log[1]
    );
    assert!(log[1].ends_with("tracks=2"), "{}", log[1]);
    // Scan 2 updates the first track; the second misses.
    assert!(
        log[2].starts_with("t=2 measurements=1 updated=1 started=0 "),
        "{}",
        log[2]
    );
    // One output row per track per scan: none at t=0, two at t=1.
    let t1: Vec<&str> = out.csv.lines().filter(|l| l.starts_with("1,")).collect();
    assert_eq!(
        t1,
        ["1,1,tentative,100,0,100,0", "1,2,tentative,3000,3100,0,100"]
    );
}

#[test]
fn errors_name_the_line() {
    // A decreasing time.
    let e = tracker("--tracker", "t,x,y\n0,1,1\n0,2,2\n1,3,3\n0.5,4,4\n").unwrap_err();
    assert_eq!(
        e,
        Failure::Input(CsvError::TimeDecreasing {
            line: 5,
            t: "0.5".into(),
            previous: "1".into()
        })
    );
    assert!(e.to_string().starts_with("line 5, column 1 (t)"), "{e}");
    // Two scans on the same millisecond: the line of the second scan.
    let e = tracker("--tracker", "t,x,y\n0,1,1\n1,2,2\n1.0002,3,3\n").unwrap_err();
    assert!(
        matches!(e, Failure::Replay(ReplayError::Scan { line: 4, .. })),
        "{e:?}"
    );
    assert!(e.to_string().starts_with("line 4: "), "{e}");
    // Beyond the u32 millisecond clock.
    let e = tracker("--tracker", "t,x,y\n0,1,1\n4294968,2,2\n").unwrap_err();
    assert!(
        matches!(e, Failure::Replay(ReplayError::ScanTime { line: 3, .. })),
        "{e:?}"
    );
    // Epoch-like start times are fine (the clock starts at the first scan).
    assert!(tracker("--tracker", "t,x,y\n1700000000,1,1\n1700000001,2,2\n").is_ok());
    // Layouts the 2-D table cannot take.
    for text in ["t,x\n0,1\n", "t,x,y,z\n0,1,1,1\n"] {
        let e = tracker("--tracker", text).unwrap_err();
        assert!(
            matches!(e, Failure::Replay(ReplayError::TrackerAxes { .. })),
            "{e:?}"
        );
    }
    let e = tracker("--tracker", "t,a,b\n0,1,1\n").unwrap_err();
    assert!(
        matches!(e, Failure::Input(CsvError::BadHeader { line: 1, .. })),
        "{e:?}"
    );
    // --schedule on polar input.
    let e = tracker("--tracker --schedule m1", "t,range,azimuth\n0,1000,0\n").unwrap_err();
    assert_eq!(
        e,
        Failure::Replay(ReplayError::TrackerScheduleNeedsCartesian)
    );
}

#[test]
fn tracker_options_are_checked() {
    for (line, want) in [
        (
            "--tracker --filter ab x.csv",
            UsageError::NotForTracker("--filter"),
        ),
        (
            "--tracker --alpha 0.5 x.csv",
            UsageError::NotForTracker("--alpha"),
        ),
        (
            "--tracker --schedule bank x.csv",
            UsageError::NotForTracker("--schedule bank"),
        ),
        (
            "--filter ab --schedule m1 --verbose x.csv",
            UsageError::TrackerOnly("--verbose"),
        ),
        (
            "--tracker --tracker x.csv",
            UsageError::Repeated("--tracker"),
        ),
        ("--tracker", UsageError::NoInput),
    ] {
        assert_eq!(args(line), Err(want), "{line}");
    }
    for (line, option) in [
        ("--tracker --capacity 32 x.csv", "--capacity"),
        ("--tracker --confirm 3/2 x.csv", "--confirm"),
        ("--tracker --confirm 0/3 x.csv", "--confirm"),
        ("--tracker --confirm 3/33 x.csv", "--confirm"),
        ("--tracker --confirm 3 x.csv", "--confirm"),
        ("--tracker --delete 0 x.csv", "--delete"),
        ("--tracker --delete 256 x.csv", "--delete"),
    ] {
        assert!(
            matches!(args(line), Err(UsageError::OutOfRange { option: o, .. }) if o == option),
            "{line}: {:?}",
            args(line)
        );
    }
    assert!(matches!(
        args("--tracker --schedule m3:window=0 x.csv"),
        Err(UsageError::Spec { .. })
    ));
    match args("--tracker --verbose --numeric fixed --capacity=256 --confirm 2/3 --delete 6 --own-alt 8000 -") {
        Ok(Command::Tracker { options, verbose, .. }) => {
            assert!(verbose);
            assert_eq!(options.capacity, 256);
            assert_eq!(options.confirmation, Some((2, 3)));
            assert_eq!(options.delete_confirmed, Some(6));
            assert_eq!(options.own_altitude_ft, Some(8000.0));
        }
        other => panic!("{other:?}"),
    }
    let help = replay_usage();
    for s in [
        "--tracker",
        "--verbose",
        "--capacity",
        "--confirm",
        "--delete",
        "t,track_id,status",
    ] {
        assert!(help.contains(s), "--help lacks {s}");
    }
}

// -------------------------------------------------------------- end to end

fn temp_file(name: &str, contents: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("replay-tracker-{}-{name}", std::process::id()));
    std::fs::write(&path, contents).unwrap();
    path
}

#[test]
fn binary_runs_the_tracker_and_names_the_bad_line() {
    let csv = crossing().measurements_csv();
    let path = temp_file("crossing.csv", &csv);
    let out = Process::new(env!("CARGO_BIN_EXE_replay"))
        .args(["--tracker", "--numeric", "fixed", "--verbose"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let want = tracker("--tracker --numeric fixed", &csv).unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), want.csv);
    assert_eq!(String::from_utf8(out.stderr).unwrap(), want.scan_log);
    let _ = std::fs::remove_file(path);

    let path = temp_file("decreasing.csv", "t,x,y\n0,1,1\n2,2,2\n2,3,3\n1,4,4\n");
    let out = Process::new(env!("CARGO_BIN_EXE_replay"))
        .arg("--tracker")
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("line 5, column 1 (t): time 1 is before"),
        "{err}"
    );
    let _ = std::fs::remove_file(path);
}
