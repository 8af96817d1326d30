//! `replay --tracker`: the output against the track table driven directly,
//! ids through a crossing, the threat columns on a TCAS picture, the
//! configuration from sensor figures, the account of unused measurements,
//! options and errors.
//!
//! The expected outputs are built by running `TrackTable` on the scenario's
//! own scans (not on the CSV) and formatting every value with `Display`, so
//! the comparisons are exact string equality in all three representations,
//! and they also check the CSV round trip.

use super::{replay_binary, temp_file};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::{Display, Write as _};

use abtrack::gain::spec::ScheduleSpec;
use abtrack::tcas::{assess, Intruder, OwnAircraft};
use abtrack::track::defaults::{
    default_cartesian, default_polar, Coverage, DefaultCartesianTrack, DefaultPolarTrack,
    SensorAccuracy, TrackerDesign,
};
use abtrack::track::{
    Association, Measurement, ScheduledTrack, TrackFilter, TrackTable, TrackerConfig,
};
use abtrack::{Fix, Scalar};
use abtrack_host_tests::cli::{Command, ReplayArgs};
use abtrack_host_tests::csv_input::CsvError;
use abtrack_host_tests::replay::{Failure, ReplayError, ReplaySchedule};
use abtrack_host_tests::replay_tracker::{
    replay_tracker_reader, with_large_stack, TrackerReplay, MAX_MEASUREMENTS,
};
use abtrack_host_tests::scenario::{self, ScenarioRun};
use clap::{CommandFactory, Parser};

const SEED: u64 = 1;

fn args(s: &str) -> Result<Command, clap::Error> {
    ReplayArgs::try_parse_from(std::iter::once("replay").chain(s.split_whitespace()))?
        .into_command()
}

/// The nominal radar's square and the nominal TCAS sensor's disc: with
/// these, `replay --tracker` is `default_cartesian` / `default_polar`.
const NOMINAL_SQUARE: &str = "--region-m 5000";
const NOMINAL_DISC: &str = "--region-m 25928";

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
/// `replay --tracker` output (without threat columns). Empty scans before
/// the first measurement are not in the CSV; later ones are run by replay
/// too (it fills gaps of whole scan periods); the clock is
/// round((t − t₀)·1000) ms.
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
        .skip_while(|s| s.measurements.is_empty())
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
        let got = tracker(
            &format!("--tracker {NOMINAL_SQUARE} --numeric {numeric}"),
            csv,
        )
        .unwrap();
        assert!(got.csv.lines().count() > 100, "{numeric}: too few rows");
        assert_eq!(got.csv, want, "{numeric}");
    }
    check::<f64>(&run, &csv, "f64");
    check::<f32>(&run, &csv, "f32");
    check::<Fix>(&run, &csv, "q32.32");
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
    let got = tracker(
        &format!("--tracker {NOMINAL_SQUARE} --capacity 16 --confirm 2/3 --delete 5"),
        &csv,
    )
    .unwrap();
    assert_eq!(got.csv, want);
    assert_ne!(
        got.csv,
        tracker(&format!("--tracker {NOMINAL_SQUARE}"), &csv)
            .unwrap()
            .csv,
        "options had no effect"
    );

    // --schedule: the same lifecycle with another schedule, in f32.
    let spec = ScheduleSpec::parse("m1:alpha=0.5").unwrap();
    let schedule = ReplaySchedule::<f32, 2>::from_spec(&spec).unwrap();
    let config = TrackerDesign::NOMINAL_RADAR
        .tracker_config::<f32, _>(schedule)
        .unwrap();
    let want = expected::<f32, ScheduledTrack<f32, ReplaySchedule<f32, 2>>, 256>(&run, &config);
    let got = tracker(
        &format!("--tracker {NOMINAL_SQUARE} --schedule m1:alpha=0.5 --numeric f32 --capacity 256"),
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
    let plain = tracker(&format!("--tracker {NOMINAL_DISC}"), &csv).unwrap();
    assert_eq!(plain.csv, want);

    let out = tracker(
        &format!("--tracker {NOMINAL_DISC} --own-alt {own_ft}"),
        &csv,
    )
    .unwrap();
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
    for numeric in ["f32", "q32.32", "fixed32"] {
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

/// A file whose median scan interval is outside the filters' range (a
/// sparse recording, or plots stamped one by one) is run with the nearest
/// end of the range and says so; it was refused before.
#[test]
fn a_median_scan_interval_outside_the_range_is_clamped_not_refused() {
    use abtrack_host_tests::replay_tracker::PeriodSource;
    let sparse = "t,x,y\n0,1000,1000\n26,1500,1000\n52,2000,1000\n";
    let run = tracker("--tracker --sigma-m 50 --clutter-per-km2 0.002", sparse).unwrap();
    assert_eq!(run.design.period, PeriodSource::FileMedianClamped(26.0));
    assert_eq!(run.design.design.scan_period, 20.0);
    assert_eq!(run.unused.measurements, 3);
    assert!(
        run.report()
            .contains("the file's median scan interval, 26, is outside"),
        "{}",
        run.report()
    );
    let dense = "t,x,y\n0,1000,1000\n0.01,1001,1000\n0.02,1002,1000\n";
    let run = tracker("--tracker --sigma-m 50 --clutter-per-km2 0.002", dense).unwrap();
    assert_eq!(run.design.design.scan_period, 0.05);
    // Given, the period is checked, as an argument.
    let e = args("--tracker --scan-period-s 30 -").unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
}

#[test]
fn errors_name_the_line() {
    // A scan before the previous one (rows out of time order, as merged
    // feeds give): skipped, its rows counted with their lines (the file was
    // refused before).
    let run = tracker(
        "--tracker",
        "t,x,y\n0,1,1\n0,2,2\n1,3,3\n0.5,4,4\n0.5,5,5\n2,6,6\n",
    )
    .unwrap();
    assert_eq!(run.unused.out_of_order.lines, [5, 6]);
    assert_eq!(run.unused.scans, 3);
    // The scan count says which scans were not run.
    assert_eq!(run.unused.out_of_order_scans, 1);
    assert!(
        run.unused
            .to_string()
            .contains("6 measurements in 3 scans (and 1 scan out of time order, not run)"),
        "{}",
        run.unused
    );
    assert!(
        run.unused
            .to_string()
            .contains("2 in scans before the previous one (out of time order) (line 5, 6)"),
        "{}",
        run.unused
    );
    // Two scans 0.2 ms apart: the second is skipped and counted, naming
    // its line.
    let run = tracker("--tracker", "t,x,y\n0,1,1\n1,2,2\n1.0002,3,3\n").unwrap();
    assert_eq!(run.unused.too_close.lines, [4]);
    // Beyond the u32 millisecond clock.
    let e = tracker("--tracker", "t,x,y\n0,1,1\n4294968,2,2\n").unwrap_err();
    assert!(
        matches!(e, Failure::Replay(ReplayError::ScanTime { line: 3, .. })),
        "{e:?}"
    );
    // Epoch-like start times are fine (the clock starts at the first scan).
    assert!(tracker("--tracker", "t,x,y\n1700000000,1,1\n1700000001,2,2\n").is_ok());
    // Layouts the 2-D table cannot take.
    let e = tracker("--tracker", "t,x,y,z\n0,1,1,1\n").unwrap_err();
    assert!(
        matches!(e, Failure::Replay(ReplayError::TrackerAxes { dims: 3 })),
        "{e:?}"
    );
    for text in ["t,x\n0,1\n", "t,a,b\n0,1,1\n"] {
        let e = tracker("--tracker", text).unwrap_err();
        assert!(
            matches!(
                e,
                Failure::Input(CsvError::UnknownLayout { both: false, .. })
            ),
            "{e:?}"
        );
    }
    let e = tracker("--tracker", "t,x,y,range,azimuth\n0,1,1,1,1\n").unwrap_err();
    assert!(
        matches!(
            e,
            Failure::Input(CsvError::UnknownLayout { both: true, .. })
        ),
        "{e:?}"
    );
    // --schedule on polar input.
    let e = tracker("--tracker --schedule m1", "t,range,azimuth\n0,1000,0\n").unwrap_err();
    assert_eq!(
        e,
        Failure::Replay(ReplayError::TrackerScheduleNeedsCartesian)
    );
    // Figures no confirmation rule meets both bounds for (rule 4): the run
    // goes on with the best rule, and the report says so, with the clutter
    // it weighed (100 per km² over the disc to the farthest point, √8 m)
    // and the fixes.
    let run = match args("--tracker --clutter-per-km2 100 -") {
        Ok(Command::Tracker { options, .. }) => {
            replay_tracker_reader(&options, "t,x,y\n0,1,1\n1,2,2\n".as_bytes()).unwrap()
        }
        other => panic!("{other:?}"),
    };
    for message in [
        "clutter 100 per km²",
        "warning: no M-of-N within 8 scans confirms a target with probability 0.95",
        "0.00251 false measurements a scan expected over the 0.0000251 km² counted",
        "--clutter-per-km2 0",
    ] {
        assert!(
            run.report().contains(message),
            "{message}: {}",
            run.report()
        );
    }
    let report = |line: &str| match args(line) {
        Ok(Command::Tracker { options, .. }) => {
            replay_tracker_reader(&options, "t,x,y\n0,1,1\n1,2,2\n".as_bytes()).map(|r| r.report())
        }
        other => panic!("{line}: {other:?}"),
    };
    // The rule given with --confirm replaces the design's: no warning.
    let given = report("--tracker --clutter-per-km2 100 --confirm 3/5 -").unwrap();
    assert!(!given.contains("warning"), "{given}");
    // Without clutter only P_D is left to blame.
    let low = report("--tracker --clutter-per-km2 0 --pd 0.3 -").unwrap();
    assert!(low.contains("confirm 2 of 8"), "{low}");
    assert!(
        low.contains("without clutter, P_D (--pd) is too low for it"),
        "{low}"
    );
    // So low a P_D that no deletion count up to 255 misses meets rule 5 is
    // refused, and the message says so.
    let e = report("--tracker --clutter-per-km2 0 --pd 0.01 -")
        .unwrap_err()
        .to_string();
    assert!(e.contains("P_D 0.01 is too low for design rule 5"), "{e}");
}

#[test]
fn tracker_options_are_checked() {
    for (line, message) in [
        ("--tracker --filter ab x.csv", "--filter"),
        (
            "--tracker --alpha 0.5 --beta 0.3 x.csv",
            "--alpha does not apply to --tracker",
        ),
        (
            "--tracker --schedule bank x.csv",
            "--schedule bank does not apply to --tracker",
        ),
        (
            "--filter ab --schedule m1 --verbose x.csv",
            "--verbose does not apply to --filter ab",
        ),
        ("--tracker --tracker x.csv", "--tracker"),
        ("--tracker", "<INPUT>"),
        ("--tracker --capacity 32 x.csv", "--capacity"),
        ("--tracker --confirm 3/2 x.csv", "--confirm"),
        ("--tracker --confirm 0/3 x.csv", "--confirm"),
        ("--tracker --confirm 3/33 x.csv", "--confirm"),
        ("--tracker --confirm 3 x.csv", "--confirm"),
        ("--tracker --delete 0 x.csv", "--delete"),
        ("--tracker --delete 256 x.csv", "--delete"),
        ("--tracker --schedule m3:window=0 x.csv", "--schedule: "),
        (
            "--tracker --pd high x.csv",
            "\"high\" is not a finite number",
        ),
        ("--tracker --azimuth-unit grad x.csv", "'grad'"),
        // The sensor's figures outside the values they take: argument
        // errors, found before any input is read.
        ("--tracker --pd 0 x.csv", "--pd 0 is outside 0.001 ..= 1"),
        ("--tracker --pd 1.5 x.csv", "--pd 1.5 is outside"),
        (
            "--tracker --scan-period-s 30 x.csv",
            "--scan-period-s 30 is outside 0.05 ..= 20",
        ),
        ("--tracker --sigma-m -1 x.csv", "--sigma-m -1 is outside"),
        ("--tracker --region-m 0 x.csv", "--region-m 0 is outside"),
        (
            "--tracker --bearing-sigma-deg 200 x.csv",
            "--bearing-sigma-deg 200 is outside",
        ),
        (
            "--tracker --clutter-per-km2 -1 x.csv",
            "--clutter-per-km2 -1 is outside",
        ),
        (
            "--tracker --max-speed-mps 2000 x.csv",
            "--max-speed-mps 2000 is outside",
        ),
        (
            "--tracker --max-accel-mps2 0 x.csv",
            "--max-accel-mps2 0 is outside",
        ),
        (
            "--tracker --sigma-m 20 --range-sigma-m 20 x.csv",
            "cannot be combined",
        ),
    ] {
        let e = args(line).expect_err(line);
        assert_eq!(e.exit_code(), 2, "{line}");
        assert!(e.to_string().contains(message), "{line}: {e}");
    }
    // Options built without the command line are checked by the run.
    let options = abtrack_host_tests::replay_tracker::TrackerOptions {
        sensor: abtrack_host_tests::replay_tracker::SensorOptions {
            detection_probability: Some(0.0),
            ..Default::default()
        },
        ..Default::default()
    };
    let e = replay_tracker_reader(&options, "t,x,y\n0,1,1\n".as_bytes()).unwrap_err();
    assert_eq!(
        e,
        Failure::Replay(ReplayError::Design("--pd 0 is outside 0.001 ..= 1".into()))
    );
    match args(
        "--tracker --verbose --numeric q32.32 --capacity=256 --confirm 2/3 --delete 6 \
         --own-alt 8000 --region-m 50000 --sigma-m 30 --scan-period-s 4.8 --pd 0.8 \
         --clutter-per-km2 0.5 --max-speed-mps 250 --max-accel-mps2 3 --azimuth-unit deg -",
    ) {
        Ok(Command::Tracker {
            options, verbose, ..
        }) => {
            assert!(verbose);
            assert_eq!(options.capacity, 256);
            assert_eq!(options.confirmation, Some((2, 3)));
            assert_eq!(options.delete_confirmed, Some(6));
            assert_eq!(options.own_altitude_ft, Some(8000.0));
            let s = options.sensor;
            assert_eq!(
                (
                    s.region_m,
                    s.sigma_m,
                    s.scan_period_s,
                    s.detection_probability,
                    s.clutter_per_km2,
                    s.max_speed_m_per_s,
                    s.max_acceleration_m_per_s2
                ),
                (
                    Some(50000.0),
                    Some(30.0),
                    Some(4.8),
                    Some(0.8),
                    Some(0.5),
                    Some(250.0),
                    Some(3.0)
                )
            );
        }
        other => panic!("{other:?}"),
    }
    let help = ReplayArgs::command().render_long_help().to_string();
    for s in [
        "--tracker",
        "--verbose",
        "--capacity",
        "--confirm",
        "--delete",
        "--region-m",
        "--sigma-m",
        "--range-sigma-m",
        "--bearing-sigma-deg",
        "--scan-period-s",
        "--pd",
        "--clutter-per-km2",
        "--azimuth-unit",
        "t,track_id,status",
    ] {
        assert!(help.contains(s), "--help lacks {s}");
    }
}

// -------------------------------------------------------------- end to end

/// A recorded single flight with the default clutter density (the nominal
/// radar's, counted over the disc to its farthest report) expects too many
/// false plots a scan for any confirmation rule to meet both bounds: it is
/// not refused, the report warns and gives the fix first; with
/// `--clutter-per-km2 0` every flight of host-tests/data/real/single runs
/// without the warning.
#[test]
fn a_single_flight_with_the_default_clutter_is_warned_and_told_the_fix() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/real/single");
    let mut flights: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    flights.sort();
    assert_eq!(flights.len(), 16);
    let text = std::fs::read_to_string(&flights[0]).unwrap();
    let run = tracker("--tracker --sigma-m 50", &text).expect("not refused");
    let report = run.report();
    assert!(
        report.contains("replay --tracker: warning: no M-of-N"),
        "{report}"
    );
    assert!(
        report.contains("a recording without clutter takes --clutter-per-km2 0"),
        "{report}"
    );
    for path in &flights {
        let text = std::fs::read_to_string(path).unwrap();
        let run = tracker("--tracker --sigma-m 50 --clutter-per-km2 0", &text);
        let run = run.unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        assert!(!run.report().contains("warning"), "{}", path.display());
    }
}

/// A bad sensor figure is a usage error (status 2) reported before the
/// input is read: the empty file is not what the message is about.
#[test]
fn binary_refuses_a_bad_sensor_figure_before_reading_the_input() {
    let empty = temp_file("tracker-empty.csv", "");
    for (options, message) in [
        (
            &["--tracker", "--pd", "1.5", "--sigma-m", "50"][..],
            "--pd 1.5 is outside",
        ),
        (
            &["--tracker", "--scan-period-s", "100"][..],
            "--scan-period-s 100",
        ),
        (
            &["--tracker", "--sigma-m", "50", "--range-sigma-m", "20"][..],
            "cannot be combined",
        ),
        (
            &[
                "--filter",
                "ab",
                "--schedule",
                "m1",
                "--sigma-m",
                "50",
                "--scan-period-s",
                "100",
            ][..],
            "--scan-period-s: 100 is out of range",
        ),
    ] {
        let out = replay_binary().args(options).arg(&empty).output().unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{options:?}: {err}");
        assert!(err.contains(message), "{options:?}: {err}");
        assert!(!err.contains("empty input"), "{options:?}: {err}");
        assert!(out.stdout.is_empty());
    }
    let _ = std::fs::remove_file(empty);
}

#[test]
fn binary_runs_the_tracker_and_names_the_bad_line() {
    let csv = crossing().measurements_csv();
    let path = temp_file("crossing.csv", &csv);
    let out = replay_binary()
        .args(["--tracker", "--numeric", "q32.32", "--verbose"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let want = tracker("--tracker --numeric q32.32", &csv).unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), want.csv);
    // --verbose's lines, then the report printed on every run.
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        format!("{}{}", want.scan_log, want.report())
    );
    let _ = std::fs::remove_file(path);

    let path = temp_file("decreasing.csv", "t,x,y\n0,1,1\n2,2,2\n2,3,3\n1,4,4\n");
    let out = replay_binary()
        .arg("--tracker")
        .arg(&path)
        .output()
        .unwrap();
    // Out of time order: run, the late scan's row counted by its line.
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("1 in scans before the previous one (out of time order) (line 5)"),
        "{err}"
    );
    let _ = std::fs::remove_file(path);
}

// ------------------------------------------------- configured from the sensor

/// A 100 km scene like the reported one: six aircraft crossing ±50 km at
/// 150–250 m/s, σ = 20 m per axis, one scan per second, every aircraft
/// detected. Returns the CSV and the truth (id → final position).
fn hundred_km_scene() -> (String, Vec<[f64; 2]>) {
    // xorshift64* with Box–Muller: reproducible noise without a dependency.
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut uniform = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        ((state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let mut gaussian = move || {
        let (u, v) = (uniform(), uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    };
    // (start x, start y, vx, vy)
    let aircraft = [
        (-48_000.0, -30_000.0, 240.0, 60.0),
        (45_000.0, 20_000.0, -200.0, -90.0),
        (-20_000.0, 47_000.0, 30.0, -230.0),
        (10_000.0, -46_000.0, -40.0, 210.0),
        (-40_000.0, 10_000.0, 150.0, 0.0),
        (30_000.0, -35_000.0, -120.0, 110.0),
    ];
    let scans = 120;
    let mut csv = String::from("t,x,y,alt\n");
    for k in 0..scans {
        let t = k as f64;
        for &(x0, y0, vx, vy) in &aircraft {
            let (x, y) = (x0 + vx * t, y0 + vy * t);
            writeln!(
                csv,
                "{t},{},{},35000",
                x + 20.0 * gaussian(),
                y + 20.0 * gaussian()
            )
            .unwrap();
        }
    }
    let last = (scans - 1) as f64;
    let truth = aircraft
        .iter()
        .map(|&(x0, y0, vx, vy)| [x0 + vx * last, y0 + vy * last])
        .collect();
    (csv, truth)
}

/// The finding: on a 100 km scene the fixed 10 km square dropped 10,430 of
/// 10,455 measurements, counted only under --verbose. The default region is
/// now none, the sensor's σ is an option, every aircraft is tracked, and
/// the account of unused measurements is printed on every run.
#[test]
fn hundred_km_scene_is_tracked_with_no_region_and_drops_are_reported() {
    let (csv, truth) = hundred_km_scene();
    let out = tracker("--tracker --sigma-m 20", &csv).unwrap();
    let rows = rows(&out.csv);
    let last_t = rows.iter().map(|r| r.0).fold(0.0, f64::max);
    let last: Vec<&Row> = rows
        .iter()
        .filter(|r| r.0 == last_t && r.2 == "confirmed")
        .collect();
    for target in &truth {
        let nearest = last
            .iter()
            .map(|r| (r.3 - target[0]).hypot(r.4 - target[1]))
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest < 60.0,
            "no confirmed track near {target:?} ({nearest} m)"
        );
    }
    assert_eq!(last.len(), truth.len(), "{last:?}");
    let u = &out.unused;
    assert_eq!(u.measurements, 6 * 120);
    assert_eq!(u.outside_region.count, 0);
    assert_eq!(u.used() + u.not_used(), u.measurements);
    // Only the first scan's points wait a scan, and they start the tracks.
    assert!(u.not_used() <= 6, "{}", out.report());
    let report = out.report();
    assert!(report.contains("no region"), "{report}");
    assert!(report.contains("outside the region: 0"), "{report}");
    assert!(
        report.contains(&format!("{} measurements in 120 scans", 6 * 120)),
        "{report}"
    );

    // The configuration, a 10 km square: what is dropped is now
    // said, with the lines, without --verbose.
    let square = tracker("--tracker --sigma-m 20 --region-m 5000", &csv).unwrap();
    let u = &square.unused;
    assert!(
        u.outside_region.count > u.measurements * 9 / 10,
        "{}",
        square.report()
    );
    assert_eq!(u.used() + u.not_used(), u.measurements);
    let report = square.report();
    assert!(
        report.contains(&format!(
            "outside the region: {} (line 2, 3,",
            u.outside_region.count
        )),
        "{report}"
    );
}

/// A scan of a dense-clutter recording (1,000 plots, four times the
/// firmware boards' 256) is taken whole: the aircraft among them is tracked
/// and nothing is counted over capacity; only plots beyond
/// `MAX_MEASUREMENTS` in one scan are, each with its line.
#[test]
fn a_scan_of_a_thousand_plots_is_taken_whole() {
    // A reproducible spread of clutter over ±50 km, new in every scan.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) * 100_000.0 - 50_000.0
    };
    let plots_per_scan = 1000;
    let scans = 12;
    let mut csv = String::from("t,x,y\n");
    for k in 0..scans {
        let t = 4.0 * k as f64;
        writeln!(csv, "{t},{},{}", 1000.0 + 200.0 * t, 500.0).unwrap();
        for _ in 1..plots_per_scan {
            writeln!(csv, "{t},{},{}", uniform(), uniform()).unwrap();
        }
    }
    let command = "--tracker --sigma-m 50 --region-m 50000 --scan-period-s 4 --capacity 256 \
                   --clutter-per-km2 0.1";
    let out = tracker(command, &csv).unwrap();
    let u = &out.unused;
    assert_eq!(u.measurements, plots_per_scan * scans, "{}", out.report());
    assert_eq!(u.over_scan_capacity.count, 0, "{}", out.report());
    assert_eq!(u.used() + u.not_used(), u.measurements);
    let last_t = 4.0 * (scans - 1) as f64;
    let on_aircraft = rows(&out.csv).into_iter().any(|r| {
        r.0 == last_t
            && r.2 == "confirmed"
            && (r.3 - (1000.0 + 200.0 * last_t)).hypot(r.4 - 500.0) < 100.0
    });
    assert!(on_aircraft, "{}", out.report());

    // One scan beyond the limit: the surplus, and only it, is counted.
    let limit = MAX_MEASUREMENTS;
    let mut csv = String::from("t,x,y\n");
    for k in 0..limit + 5 {
        writeln!(csv, "0,{},{}", 10.0 * k as f64, 0.0).unwrap();
    }
    let out = tracker(command, &csv).unwrap();
    assert_eq!(out.unused.over_scan_capacity.count, 5, "{}", out.report());
    assert!(
        out.report().contains(&format!(
            "over capacity: 5 more than {limit} in a scan (line"
        )),
        "{}",
        out.report()
    );
}

/// Each sensor option changes the one figure it names: the run equals the
/// table configured by `TrackerDesign` with those figures, driven directly.
#[test]
fn sensor_options_are_the_design_figures() {
    let run = crossing();
    let csv = run.measurements_csv();
    let design = TrackerDesign {
        accuracy: SensorAccuracy::Cartesian { sigma: 30.0 },
        detection_probability: 0.8,
        clutter_density: 0.2e-6,
        coverage: Coverage::Square { half_width: 6000.0 },
        scan_period: 1.0,
        max_speed: 250.0,
        max_acceleration: 4.0,
        ..TrackerDesign::NOMINAL_RADAR
    };
    let config = design.cartesian_config::<f64>().unwrap();
    let want = expected::<f64, DefaultCartesianTrack<f64>, 64>(&run, &config);
    let got = tracker(
        "--tracker --sigma-m 30 --pd 0.8 --clutter-per-km2 0.2 --region-m 6000 \
         --scan-period-s 1 --max-speed-mps 250 --max-accel-mps2 4",
        &csv,
    )
    .unwrap();
    assert_eq!(got.csv, want);
    // (max_range, the farthest measurement, is not used with a coverage.)
    let used = got.design.design;
    assert_eq!(
        used,
        TrackerDesign {
            max_range: used.max_range,
            ..design
        }
    );
    assert_ne!(
        got.csv,
        tracker(&format!("--tracker {NOMINAL_SQUARE}"), &csv)
            .unwrap()
            .csv
    );

    // Polar figures: range σ and bearing σ in degrees, a disc.
    let run = scenario::generate("tcas-30", SEED).unwrap();
    let csv = run.measurements_csv();
    let design = TrackerDesign {
        accuracy: SensorAccuracy::Polar {
            range_sigma: 30.0,
            bearing_sigma: 3f64.to_radians(),
        },
        coverage: Coverage::Disc { radius: 30_000.0 },
        ..TrackerDesign::NOMINAL_TCAS
    };
    let config = design.polar_config::<f64>().unwrap();
    let want = expected::<f64, DefaultPolarTrack<f64>, 64>(&run, &config);
    let got = tracker(
        "--tracker --range-sigma-m 30 --bearing-sigma-deg 3 --region-m 30000",
        &csv,
    )
    .unwrap();
    let used = got.design.design;
    assert_eq!(
        used,
        TrackerDesign {
            max_range: used.max_range,
            ..design
        }
    );
    assert_eq!(got.csv, want);
    // The same file with its azimuths in degrees and the option to say so.
    let degrees: String = csv
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                return format!("{l}\n");
            }
            let mut f: Vec<String> = l.split(',').map(String::from).collect();
            f[2] = f[2].parse::<f64>().unwrap().to_degrees().to_string();
            format!("{}\n", f.join(","))
        })
        .collect();
    let line = "--tracker --range-sigma-m 30 --bearing-sigma-deg 3 --region-m 30000";
    let e = tracker(line, &degrees).unwrap_err();
    assert!(e.to_string().contains("--azimuth-unit deg"), "{e}");
    let got = tracker(&format!("{line} --azimuth-unit deg"), &degrees).unwrap();
    // Degrees round-trip to radians within an ulp or two; the tracks agree
    // to far below the noise.
    let (a, b) = (rows(&got.csv), rows(&want));
    assert_eq!(a.len(), b.len());
    for (a, b) in a.iter().zip(&b) {
        assert_eq!((a.0, a.1, &a.2), (b.0, b.1, &b.2));
        assert!(
            (a.3 - b.3).abs() < 1e-6 && (a.4 - b.4).abs() < 1e-6,
            "{a:?} {b:?}"
        );
    }
}

/// Where the file skips scans, empty scans are run at the scan period: a
/// target that stops reporting is deleted after the design's K misses,
/// counted in scans, not kept alive by one long interval.
#[test]
fn gaps_are_run_as_empty_scans() {
    // Two targets for 10 s, then only the second for 1 s more after a 9 s
    // gap.
    let mut csv = String::from("t,x,y\n");
    for k in 0..10 {
        let t = k as f64;
        writeln!(csv, "{t},{},0", 100.0 * t).unwrap();
        writeln!(csv, "{t},0,{}", 3000.0 + 100.0 * t).unwrap();
    }
    writeln!(csv, "18,0,4800").unwrap();
    let out = tracker("--tracker --clutter-per-km2 0 --scan-period-s 1", &csv).unwrap();
    assert_eq!(out.unused.empty_scans, 8);
    assert!(
        out.report().contains("(and 8 empty scans run for gaps)"),
        "{}",
        out.report()
    );
    // Both tracks coast, then are deleted after K misses: none is left at 18 s
    // to take the second target's report.
    let k = TrackerDesign {
        clutter_density: 0.0,
        ..TrackerDesign::NOMINAL_RADAR
    }
    .derive()
    .unwrap()
    .deletion
    .0;
    let rows = rows(&out.csv);
    let last_seen = rows
        .iter()
        .filter(|r| r.1 <= 2)
        .map(|r| r.0)
        .fold(0.0, f64::max);
    assert_eq!(last_seen, 9.0 + f64::from(k) - 1.0, "{}", out.csv);
    // The added scans are written with their times from the clock.
    for t in 10..(9 + k) {
        assert!(
            out.csv.lines().any(|l| l.starts_with(&format!("{t},"))),
            "no rows at t = {t}:\n{}",
            out.csv
        );
    }
    assert!(rows.iter().all(|r| r.0 < 18.0 || r.1 > 2));
    // Without the added scans (a scan period as long as the gap) the two
    // tracks would have survived the gap with one miss each.
    let long = tracker("--tracker --clutter-per-km2 0 --scan-period-s 9", &csv).unwrap();
    assert_eq!(long.unused.empty_scans, 0);
}

/// Plots time-stamped one by one (two targets 3 km apart, each reported
/// every second, their plots half a second apart) are read as scans of
/// one plot each; the report says so. The same targets in scans, and one
/// target alone, raise no note.
#[test]
fn plots_time_stamped_one_by_one_are_noted() {
    let (mut one_by_one, mut in_scans, mut alone) = (
        String::from("t,x,y\n"),
        String::from("t,x,y\n"),
        String::from("t,x,y\n"),
    );
    for k in 0..20 {
        let t = k as f64;
        writeln!(one_by_one, "{t},{},0", 100.0 * t).unwrap();
        writeln!(one_by_one, "{},0,{}", t + 0.5, 3000.0 + 100.0 * t).unwrap();
        writeln!(in_scans, "{t},{},0", 100.0 * t).unwrap();
        writeln!(in_scans, "{t},0,{}", 3000.0 + 100.0 * t).unwrap();
        writeln!(alone, "{t},{},0", 100.0 * t).unwrap();
    }
    let command = "--tracker --clutter-per-km2 0 --scan-period-s 1";
    let out = tracker(command, &one_by_one).unwrap();
    assert_eq!(
        (out.one_plot_scans.pairs, out.one_plot_scans.apart),
        (39, 39)
    );
    assert!(
        out.report()
            .contains("the plots look time-stamped one by one"),
        "{}",
        out.report()
    );
    for csv in [&in_scans, &alone] {
        let out = tracker(command, csv).unwrap();
        assert!(!out.one_plot_scans.look_stamped_one_by_one(), "{csv}");
        assert!(!out.report().contains("note:"), "{}", out.report());
    }
}
