//! What holds on the real ADS-B data (host-tests/data/real/), checked on
//! the code of the `real-adsb` experiment group
//! (`abtrack_host_tests::experiments::real_adsb`); results/real-adsb/ has
//! the full figures.

use abtrack::gain::spec::{ScheduleSpec, SensorScale};
use abtrack::track::defaults::BANK_30_ACCELERATION;
use abtrack_host_tests::experiments::real_adsb::{
    auto_spec, best_kalman_q, data_dir, evaluate_segment, median, read_scene_truth, read_segments,
    run_scene, score_tracks, sigma_row, truth_for, Figure, Scene, SceneRun, Segment, Timing, AUTO,
    GRID_MAX_GAP_S, KALMAN_Q_GRID, SCENES, SCENE_NUMERICS, SCENE_PERIOD_MS, SCHEDULES, SEEDS,
    SIGMA_M, SIGMA_SWEEP_M,
};
use abtrack_host_tests::experiments::scene_draws::{
    self, draw, measurements, CONDITIONS, DEV_SENSOR_CONDITION_COUNT, DRAW_SEEDS,
};
use abtrack_host_tests::metrics::{
    mean_ospa, track_metrics_with, PairingCost, ScanReport, TrackPoint, TrackStatus, TruthPoint,
};
use abtrack_host_tests::replay::Numeric;

/// The fixed αβ and `auto`, seed 1: enough for the claims, fast.
const SPECS: [&str; 2] = ["fixed:alpha=0.5,beta=0.2", AUTO];

#[test]
fn only_streams_with_an_interval_over_20_s_are_refused() {
    let segments = read_segments(&data_dir()).unwrap();
    assert_eq!(segments.len(), 16);
    for segment in &segments {
        for timing in Timing::ALL {
            let r = evaluate_segment(segment, timing, &[1], &SPECS, SIGMA_M).unwrap();
            for (spec, figure) in &r.schedules {
                if let Figure::Refused(why) = figure {
                    assert!(
                        r.max_interval_s > GRID_MAX_GAP_S,
                        "{} {timing:?} {spec}: refused ({why}) with no interval over 20 s",
                        r.segment
                    );
                }
            }
        }
    }
}

#[test]
fn the_one_q_kalman_filter_beats_the_raw_measurements_at_both_timings() {
    let segments = read_segments(&data_dir()).unwrap();
    for timing in Timing::ALL {
        let results: Vec<_> = segments
            .iter()
            .map(|s| evaluate_segment(s, timing, &[1], &[], SIGMA_M).unwrap())
            .collect();
        let refs: Vec<_> = results.iter().collect();
        let (kq, kf) = best_kalman_q(&refs);
        let raw = median(&results.iter().map(|r| r.raw).collect::<Vec<_>>());
        // Raw is σ√2 ≈ 70.7 m; the filter is below it.
        assert!((raw - 70.7).abs() < 3.0, "{timing:?}: raw {raw}");
        assert!(
            kf < 0.95 * raw,
            "{timing:?}: Kalman q {} median {kf} vs raw {raw}",
            KALMAN_Q_GRID[kq]
        );
    }
}

/// Every schedule of the experiment whose defaults follow the sensor
/// (`--sigma-m`, `SensorScale`) stays within 1.2× the one-q Kalman filter's median
/// per-segment RMSE at both timings (seed 1): comparable filters, where a
/// default tied to a paper's own sensor was 15× (`liu-count-adjusted`'s
/// count bound, docs/auto.md).
#[test]
fn every_sensor_scaled_schedule_is_within_a_fifth_of_the_kalman_filter() {
    // The experiment's schedules whose defaults change with the sensor.
    let sensor = SensorScale {
        sigma: SIGMA_M,
        period: 1.0,
        max_acceleration: BANK_30_ACCELERATION,
    };
    let sensor_scaled: Vec<&str> = SCHEDULES
        .into_iter()
        .filter(|s| ScheduleSpec::parse_scaled(s, &sensor).ok() != ScheduleSpec::parse(s).ok())
        .collect();
    assert_eq!(sensor_scaled.len(), 7, "{sensor_scaled:?}");
    let segments = read_segments(&data_dir()).unwrap();
    for timing in Timing::ALL {
        let results: Vec<_> = segments
            .iter()
            .map(|s| evaluate_segment(s, timing, &[1], &sensor_scaled, SIGMA_M).unwrap())
            .collect();
        let refs: Vec<_> = results.iter().collect();
        let (_, kf) = best_kalman_q(&refs);
        for &spec in &sensor_scaled {
            let rmse: Vec<f64> = results
                .iter()
                .map(|r| r.schedule(spec).and_then(Figure::rmse).unwrap())
                .collect();
            let ratio = median(&rmse) / kf;
            assert!(
                ratio <= 1.2,
                "{timing:?} {spec}: {ratio} × the Kalman filter"
            );
        }
    }
}

/// The experiment names `auto` at σ 50 m three ways (its schedule list,
/// its summary's method, the σ table's spec): they are one spec.
#[test]
fn the_experiments_auto_is_the_one_configured_from_its_sigma() {
    assert_eq!(AUTO, auto_spec(SIGMA_M));
    assert!(SCHEDULES.contains(&AUTO));
    assert!(SIGMA_SWEEP_M.contains(&SIGMA_M));
}

/// `auto` configured from the sensor's σ alone stays within 1.05× the
/// one-q Kalman filter (its q the best for the set at that σ) at every σ of
/// the sweep, at both timings (seeds 1–3, as the table), refusing nothing; no segment is
/// more than 2 % worse than raw up to σ 50 m, and beyond it only the
/// firefighting flight at its real timing (reports 19 s apart, in turns;
/// results/real-adsb/sigma.md, docs/experiments.md).
#[test]
fn auto_stays_near_the_kalman_filter_at_other_sensors_sigma() {
    let segments = read_segments(&data_dir()).unwrap();
    for sigma in SIGMA_SWEEP_M {
        for timing in Timing::ALL {
            let r = sigma_row(&segments, timing, &SEEDS, sigma).unwrap();
            let ratio = r.auto / r.kalman;
            assert!(
                ratio <= 1.05,
                "σ {sigma} {timing:?}: {ratio:.3} × the Kalman filter"
            );
            assert_eq!(r.refused, 0, "σ {sigma} {timing:?}");
            if sigma <= SIGMA_M {
                assert_eq!(
                    r.over_102_raw, 0,
                    "σ {sigma} {timing:?}: {:?}",
                    r.worst_against_raw
                );
            } else if r.over_102_raw > 0 {
                assert_eq!(r.over_102_raw, 1, "σ {sigma} {timing:?}");
                assert_eq!(timing, Timing::Real, "σ {sigma}: {:?}", r.worst_against_raw);
                assert_eq!(r.worst_against_raw.0, "firefighting_calfire", "σ {sigma}");
            }
        }
    }
}

#[test]
fn the_four_second_grid_skips_only_points_inside_long_gaps() {
    // Reports at 0, 8 and 40 s: the grid 0, 4, 8 (interpolated at 4) and
    // 40; 12 ... 36 lie inside the 32 s gap.
    let segment = Segment {
        name: "hand".into(),
        points: vec![(0.0, [0.0, 0.0]), (8.0, [80.0, -8.0]), (40.0, [400.0, 0.0])],
    };
    let grid = truth_for(&segment, Timing::Grid);
    assert_eq!(
        grid,
        vec![
            (0.0, [0.0, 0.0]),
            (4.0, [40.0, -4.0]),
            (8.0, [80.0, -8.0]),
            (40.0, [400.0, 0.0])
        ]
    );
    assert_eq!(truth_for(&segment, Timing::Real), segment.points);
}

#[test]
fn the_scene_tracker_agrees_in_f64_f32_and_the_fast_fixed_point() {
    let dir = data_dir();
    let scene = &SCENES[0];
    let truth = read_scene_truth(&dir, scene).unwrap();
    let runs: Vec<_> = [Numeric::F64, Numeric::F32, Numeric::Fixed32]
        .iter()
        .map(|&n| run_scene(&dir, scene, &truth, &scene.options(n, None), "").unwrap())
        .collect();
    let f64_run = &runs[0];
    // Today's figures on the P_D 0.9 scene (results/real-adsb/scene.md).
    assert!(f64_run.coverage >= 0.95, "coverage {}", f64_run.coverage);
    assert!(
        f64_run.continuity >= 0.98,
        "continuity {}",
        f64_run.continuity
    );
    assert!(f64_run.ospa <= 180.0, "OSPA {}", f64_run.ospa);
    assert!(
        f64_run.false_tracks <= 1,
        "false tracks {}",
        f64_run.false_tracks
    );
    for r in &runs[1..] {
        assert!((r.coverage - f64_run.coverage).abs() <= 0.005);
        assert!(r.id_changes.abs_diff(f64_run.id_changes) <= 2);
        assert!((r.rmse - f64_run.rmse).abs() <= 1.0);
        assert!((r.ospa - f64_run.ospa).abs() <= 0.02 * f64_run.ospa);
    }
}

/// The P_D 0.7 scene with 60 clutter plots a scan: at least as good as
/// Stone Soup 1.9.1's GNN tracker on coverage (0.921), identity changes
/// (12), OSPA (285.5 m) and false tracks (9), its figures on this scene
/// quoted in docs/experiments.md; a confirmed track coasts through its
/// misses to the deletion rule instead of ending 20 s after its last
/// update (that gave 16 id changes).
#[test]
fn the_hard_scene_keeps_identities_through_missed_detections() {
    let dir = data_dir();
    let scene = &SCENES[1];
    assert!(scene.name.ends_with("hard"), "{}", scene.name);
    let truth = read_scene_truth(&dir, scene).unwrap();
    let run = run_scene(&dir, scene, &truth, &scene.options(Numeric::F64, None), "").unwrap();
    assert!(run.coverage >= 0.921, "coverage {}", run.coverage);
    assert!(run.id_changes <= 12, "id changes {}", run.id_changes);
    assert!(run.ospa <= 285.5, "OSPA {}", run.ospa);
    assert!(run.false_tracks <= 9, "false tracks {}", run.false_tracks);
}

/// A first point kept through one missed scan starts the real flights
/// sooner (docs/track-table.md, "First points"): on both dev files fewer
/// truth points are unpaired before their flight's first pairing, OSPA is
/// lower and there are no more false tracks than with the previous scan's
/// first points only (`replay --tracker --no-first-point-wait`); on the
/// scene drawn again, coverage is higher and OSPA lower on the mean of
/// every condition with the dev files' sensor (σ 50 m, 4 s). Not claimed
/// for the other sensors' figures (docs/track-table.md, "First points"):
/// at 12 s scans a first point cannot wait (two scans exceed the filter's
/// 20 s) and the runs are the same; at σ 150 m the mean coverage is 0.0004
/// lower and OSPA 0.6 m higher with the wait (at 8 s and σ 100 m they are
/// 0.005 higher and 14 m lower).
#[test]
fn first_points_kept_through_a_miss_start_real_flights_sooner() {
    use abtrack_host_tests::replay_tracker::{replay_tracker_reader, TrackerOptions};
    let dir = data_dir();
    for scene in SCENES.iter() {
        let truth = read_scene_truth(&dir, scene).unwrap();
        let kept = scene.options(Numeric::F64, None);
        assert!(kept.first_points_through_a_miss);
        let next_scan_only = TrackerOptions {
            first_points_through_a_miss: false,
            ..kept
        };
        let a = run_scene(&dir, scene, &truth, &kept, "").unwrap();
        let b = run_scene(&dir, scene, &truth, &next_scan_only, "").unwrap();
        let name = scene.name;
        assert!(
            a.unpaired_before_first < b.unpaired_before_first,
            "{name}: {} against {}",
            a.unpaired_before_first,
            b.unpaired_before_first
        );
        assert!(
            a.ospa < b.ospa,
            "{name}: OSPA {} against {}",
            a.ospa,
            b.ospa
        );
        assert!(a.false_tracks <= b.false_tracks, "{name}");
    }
    let truth = read_scene_truth(&dir, &SCENES[0]).unwrap();
    for (index, condition) in CONDITIONS[..DEV_SENSOR_CONDITION_COUNT].iter().enumerate() {
        let (mut coverage, mut ospa) = ([0.0; 2], [0.0; 2]);
        for seed in DRAW_SEEDS {
            let text = measurements(&truth, index, seed);
            for (i, keep) in [true, false].into_iter().enumerate() {
                let options = TrackerOptions {
                    first_points_through_a_miss: keep,
                    ..condition.options(Numeric::F64, None)
                };
                let replay = replay_tracker_reader(&options, text.as_bytes()).unwrap();
                let run = score_tracks(
                    "",
                    "",
                    &replay.csv,
                    &scene_draws::truth_at_scans(&truth, condition),
                    f64::NAN,
                    String::new(),
                )
                .unwrap();
                coverage[i] += run.coverage;
                ospa[i] += run.ospa;
            }
        }
        let name = condition.name;
        assert!(coverage[0] > coverage[1], "{name}: coverage {coverage:?}");
        assert!(ospa[0] < ospa[1], "{name}: OSPA {ospa:?}");
    }
}

/// The scene drawn again follows its README's recipe: every truth point
/// detected with P_D and perturbed by N(0, 50²) m per axis, Poisson clutter
/// uniform over the ±50 km square, every 4 s to 1200 s.
#[test]
fn a_drawn_scene_follows_the_recipe_of_the_folders_files() {
    let truth = read_scene_truth(&data_dir(), &SCENES[0]).unwrap();
    let points: usize = truth.values().map(Vec::len).sum();
    let plots = |condition: &Scene, stream: u64| -> Vec<(i64, f64, f64)> {
        let text = draw(&truth, condition, stream);
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("t,x,y"));
        lines
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|f| f.parse().unwrap()).collect();
                ((v[0] * 1000.0).round() as i64, v[1], v[2])
            })
            .collect()
    };
    // Clutter per km² over the 100 km square: 0.01 is 100 plots a scan.
    let only = |pd: f64, clutter_per_km2: f64| Scene {
        name: "recipe",
        detection_probability: pd,
        clutter_per_km2,
        sigma_m: SIGMA_M,
        scan_period_ms: SCENE_PERIOD_MS,
    };
    // Every point detected, no clutter: one plot per truth point, within
    // 5σ of a truth point of its scan.
    let all = plots(&only(1.0, 0.0), 1);
    assert_eq!(all.len(), points);
    for &(t, x, y) in &all {
        let near = truth[&t]
            .iter()
            .any(|p| (p.x - x).hypot(p.y - y) < 5.0 * 50.0 * 2f64.sqrt());
        assert!(near, "plot at {t} ms ({x}, {y}) far from every truth point");
    }
    // P_D 0.7: the binomial count within 4σ.
    let detected = plots(&only(0.7, 0.0), 2).len() as f64;
    let sd = (points as f64 * 0.7 * 0.3).sqrt();
    assert!(
        (detected - 0.7 * points as f64).abs() < 4.0 * sd,
        "{detected} of {points}"
    );
    // Clutter alone: Poisson(100) in each of the 301 scans, within 4σ of
    // the total, inside the square, at the scan times.
    let clutter = plots(&only(0.0, 0.01), 3);
    let expected = 100.0 * 301.0;
    assert!((clutter.len() as f64 - expected).abs() < 4.0 * expected.sqrt());
    for &(t, x, y) in &clutter {
        assert!(t % 4000 == 0 && (0..=1_200_000).contains(&t), "{t}");
        assert!(x.abs() <= 50_000.0 && y.abs() <= 50_000.0, "({x}, {y})");
    }
}

/// The scene drawn again in every condition (the held-out scene's, not in
/// the repository: P_D 0.7, 100 clutter plots a scan; and the other
/// sensors' figures; results/real-adsb/scene_draws.md): the design is
/// configured from each condition's figures, and the tracker gives the
/// same figures in f64, f32 and the fast fixed point on every draw.
#[test]
fn the_scene_drawn_again_agrees_in_every_number_type() {
    let truth = read_scene_truth(&data_dir(), &SCENES[0]).unwrap();
    for ((index, condition), seed) in CONDITIONS
        .iter()
        .enumerate()
        .flat_map(|c| DRAW_SEEDS.iter().map(move |&seed| (c, seed)))
    {
        let text = measurements(&truth, index, seed);
        let runs: Vec<_> = SCENE_NUMERICS
            .iter()
            .map(|&(n, label)| scene_draws::track(&truth, condition, &text, n, label).unwrap())
            .collect();
        let f64_run = &runs[0];
        let sensor = format!(
            "σ {} m per axis, T {} s, P_D {}, clutter {} per km²",
            condition.sigma_m,
            condition.scan_period_ms / 1000,
            condition.detection_probability,
            condition.clutter_per_km2
        );
        assert!(f64_run.design.contains(&sensor), "{}", f64_run.design);
        for r in &runs[1..] {
            assert!(
                (r.coverage - f64_run.coverage).abs() <= 0.005,
                "{} seed {seed} {}",
                condition.name,
                r.label
            );
            assert!(
                r.id_changes.abs_diff(f64_run.id_changes) <= 2,
                "{} seed {seed} {}",
                condition.name,
                r.label
            );
            assert!(
                (r.rmse - f64_run.rmse).abs() <= 1.0,
                "{} seed {seed} {}",
                condition.name,
                r.label
            );
            assert!(
                (r.ospa - f64_run.ospa).abs() <= 0.02 * f64_run.ospa,
                "{} seed {seed} {}",
                condition.name,
                r.label
            );
        }
    }
}

/// The scene drawn again, three seeds in each of the six conditions, three
/// of them other sensors' figures (results/real-adsb/scene_draws_means.md):
/// on the mean over the seeds,
/// the tracker covers at least as much of the truth as Stone Soup 1.9.1's
/// GNN tracker on the same draws (its tracks committed in
/// results/real-adsb/stonesoup/draws/), with no more identity changes, no
/// more false tracks and no larger OSPA. (Its RMSE is not claimed: it is
/// 1–2 m above Stone Soup's at P_D 0.7 and 0.7–3.8 m above with the other
/// sensors' figures, docs/experiments.md.)
#[test]
fn on_the_scene_drawn_again_the_tracker_is_at_least_as_good_as_stone_soup() {
    let truth = read_scene_truth(&data_dir(), &SCENES[0]).unwrap();
    let group = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../results/real-adsb");
    for (index, condition) in CONDITIONS.iter().enumerate() {
        let (mut ours, mut theirs) = (Vec::new(), Vec::new());
        for seed in DRAW_SEEDS {
            let text = measurements(&truth, index, seed);
            ours.push(scene_draws::track(&truth, condition, &text, Numeric::F64, "f64").unwrap());
            let ss = scene_draws::stonesoup_draw(&group, condition, seed, &truth).unwrap();
            theirs.push(ss.unwrap_or_else(|| {
                panic!("no Stone Soup tracks for {} seed {seed}", condition.name)
            }));
        }
        let mean = |runs: &[SceneRun], f: &dyn Fn(&SceneRun) -> f64| {
            runs.iter().map(f).sum::<f64>() / runs.len() as f64
        };
        let name = condition.name;
        let coverage = (mean(&ours, &|r| r.coverage), mean(&theirs, &|r| r.coverage));
        assert!(coverage.0 >= coverage.1, "{name}: coverage {coverage:?}");
        let ids = (
            mean(&ours, &|r| r.id_changes as f64),
            mean(&theirs, &|r| r.id_changes as f64),
        );
        assert!(ids.0 <= ids.1, "{name}: id changes {ids:?}");
        let false_tracks = (
            mean(&ours, &|r| r.false_tracks as f64),
            mean(&theirs, &|r| r.false_tracks as f64),
        );
        assert!(
            false_tracks.0 <= false_tracks.1,
            "{name}: false tracks {false_tracks:?}"
        );
        let ospa = (mean(&ours, &|r| r.ospa), mean(&theirs, &|r| r.ospa));
        assert!(ospa.0 <= ospa.1, "{name}: OSPA {ospa:?}");
    }
}

/// Metrics on a hand-made scene: two flights, scored against tracks that
/// sit on them, 30 m off, or 600 m off (beyond the 500 m pairing limit).
#[test]
fn scene_metrics_of_known_configurations() {
    let scans = |offset: f64, swap_at: Option<usize>| -> Vec<ScanReport> {
        (0..10)
            .map(|k| {
                let t = 4.0 * k as f64;
                let truth = vec![
                    TruthPoint {
                        id: 1,
                        x: 100.0 * k as f64,
                        y: 0.0,
                    },
                    TruthPoint {
                        id: 2,
                        x: 0.0,
                        y: 5000.0 + 100.0 * k as f64,
                    },
                ];
                let id = |n: u32| {
                    if swap_at.is_some_and(|s| k >= s) {
                        n + 10
                    } else {
                        n
                    }
                };
                let tracks = truth
                    .iter()
                    .map(|p| TrackPoint {
                        id: id(p.id),
                        status: TrackStatus::Confirmed,
                        x: p.x + offset,
                        y: p.y,
                    })
                    .collect();
                ScanReport { t, truth, tracks }
            })
            .collect()
    };
    let on = scans(0.0, None);
    let m = track_metrics_with(&on, 500.0, PairingCost::Distance).unwrap();
    assert_eq!((m.completeness, m.continuity, m.id_changes), (1.0, 1.0, 0));
    assert_eq!(m.assigned_rmse, 0.0);
    assert_eq!(mean_ospa(&on, 1000.0, 2.0).unwrap(), 0.0);
    let off = scans(30.0, Some(4));
    let m = track_metrics_with(&off, 500.0, PairingCost::Distance).unwrap();
    assert!((m.assigned_rmse - 30.0).abs() < 1e-9);
    assert!((mean_ospa(&off, 1000.0, 2.0).unwrap() - 30.0).abs() < 1e-9);
    // New ids from scan 4 on: one change per flight.
    assert_eq!(m.id_changes, 2);
    assert!(m.mostly_unassigned_tracks.is_empty());
    let far = scans(600.0, None);
    let m = track_metrics_with(&far, 500.0, PairingCost::Distance).unwrap();
    assert_eq!(m.completeness, 0.0);
    assert_eq!(m.mostly_unassigned_tracks, vec![1, 2]);
    assert!((mean_ospa(&far, 1000.0, 2.0).unwrap() - 600.0).abs() < 1e-9);
}

/// `--numeric fixed32` runs what the Cortex-M3 firmware runs: the x/y
/// track table in Fixed32, range/azimuth input and the threat columns in
/// its wide format ScaledScalar (the demo's scan loop and TCAS logic), and
/// refuses the single x/y filters.
#[test]
fn fixed32_runs_what_the_cortex_m3_firmware_runs() {
    use abtrack_host_tests::replay::{
        replay_reader, Failure, FilterKind, ReplayConfig, ReplayError,
    };
    use abtrack_host_tests::replay_tracker::{replay_tracker_reader, TrackerOptions};
    let options = TrackerOptions {
        numeric: Numeric::Fixed32,
        ..TrackerOptions::default()
    };
    let cartesian = "t,x,y\n0,100,200\n1,110,200\n2,120,200\n3,130,200\n";
    let run = replay_tracker_reader(&options, cartesian.as_bytes()).unwrap();
    // Tentative from the second scan, confirmed at the third (2 of 3).
    assert!(
        run.csv.lines().any(|l| l.starts_with("3,1,confirmed,130")),
        "{}",
        run.csv
    );
    // Range/azimuth and the threat columns: ScaledScalar's run, which
    // differs from f64's only in the rounding.
    let polar = "t,range,azimuth\n0,1000,0.1\n1,1010,0.1\n2,1020,0.1\n3,1030,0.1\n";
    let own_alt = TrackerOptions {
        own_altitude_ft: Some(9000.0),
        ..options
    };
    for (options, input) in [(&options, polar), (&own_alt, cartesian)] {
        let fixed32 = replay_tracker_reader(options, input.as_bytes()).unwrap();
        let f64_options = TrackerOptions {
            numeric: Numeric::F64,
            ..*options
        };
        let f64_run = replay_tracker_reader(&f64_options, input.as_bytes()).unwrap();
        assert_eq!(
            fixed32.csv.lines().count(),
            f64_run.csv.lines().count(),
            "{}",
            fixed32.csv
        );
        assert_ne!(fixed32.csv, f64_run.csv, "not run in the fixed point");
        for (a, b) in fixed32.csv.lines().zip(f64_run.csv.lines()).skip(1) {
            for (x, y) in a.split(',').zip(b.split(',')) {
                match (x.parse::<f64>(), y.parse::<f64>()) {
                    (Ok(x), Ok(y)) => {
                        assert!((x - y).abs() <= 1e-6 * y.abs().max(1.0), "{a} / {b}")
                    }
                    _ => assert_eq!(x, y, "{a} / {b}"),
                }
            }
        }
    }
    let single = ReplayConfig {
        filter: FilterKind::AlphaBeta {
            alpha: 0.5,
            beta: 0.2,
        },
        numeric: Numeric::Fixed32,
    };
    assert_eq!(
        replay_reader(&single, cartesian.as_bytes()).unwrap_err(),
        Failure::Replay(ReplayError::Fixed32SingleFilter)
    );
}

/// A tracker output with a position or time that is not finite (`nan`, as
/// an exporter writes a missing value) is refused with the file and the
/// line, instead of scored (an unclipped NaN distance never ended the
/// assignment's search).
#[test]
fn a_tracker_output_that_is_not_finite_is_refused_with_its_line() {
    let truth = std::collections::BTreeMap::from([(
        0,
        vec![TruthPoint {
            id: 1,
            x: 0.0,
            y: 0.0,
        }],
    )]);
    for (row, column) in [
        ("0,1,confirmed,nan,0", "x = NaN"),
        ("0,1,confirmed,0,-inf", "y = -inf"),
        ("NaN,1,confirmed,0,0", "t = NaN"),
    ] {
        let text = format!("t,track_id,status,x,y\n0,2,confirmed,10,0\n{row}\n");
        let e = score_tracks(
            "label",
            "tracks.csv",
            &text,
            &truth,
            f64::NAN,
            String::new(),
        )
        .unwrap_err();
        assert_eq!(
            e,
            format!("tracks.csv, line 3: {column} is not a finite number"),
            "{row}"
        );
    }
}

/// The scans are the truth's own times, wherever they start: a truth and a
/// tracker on one flight at 2, 6, 10 … s are scored (coverage 1), a scan of
/// the truth without a flight keeps its tracks (unpaired there), a row a
/// millisecond off joins its scan, and a row at no scan of the truth (0.3 s
/// late) is refused with its line instead of scored as a scan of its own.
#[test]
fn the_scans_scored_are_the_truths_times() {
    let point = |t_ms: i64| TruthPoint {
        id: 1,
        x: t_ms as f64,
        y: 0.0,
    };
    let mut truth: std::collections::BTreeMap<i64, Vec<TruthPoint>> = (0..5)
        .map(|k| 2000 + 4000 * k)
        .map(|t| (t, vec![point(t)]))
        .collect();
    let rows = |late_s: f64| {
        let mut text = String::from("t,track_id,status,x,y\n");
        for k in 0..5 {
            let t_ms = 2000 + 4000 * k;
            let t = t_ms as f64 / 1000.0 + late_s;
            text.push_str(&format!("{t},1,confirmed,{},0\n", t_ms + 10));
        }
        text
    };
    let score = |truth: &std::collections::BTreeMap<i64, Vec<TruthPoint>>, text: &str| {
        score_tracks("", "out.csv", text, truth, f64::NAN, String::new())
    };
    let run = score(&truth, &rows(0.0)).unwrap();
    assert_eq!(run.scans.len(), 5);
    assert_eq!(
        (run.coverage, run.continuity, run.id_changes),
        (1.0, 1.0, 0)
    );
    assert!((run.rmse - 10.0).abs() < 1e-9, "{}", run.rmse);
    // Within the tolerance.
    assert_eq!(score(&truth, &rows(0.001)).unwrap().coverage, 1.0);
    let e = score(&truth, &rows(0.3)).unwrap_err();
    assert_eq!(
        e,
        "out.csv, line 2: t = 2.3 s is at no scan of the truth (none within 1 ms)"
    );
    // The flight absent from the last two scans, which stay scans: the
    // track there is unpaired, so it is paired in 3 of its 5 scans.
    truth.insert(14_000, Vec::new());
    truth.insert(18_000, Vec::new());
    let run = score(&truth, &rows(0.0)).unwrap();
    assert_eq!(run.scans.len(), 5);
    assert_eq!(run.pairs.len(), 3);
    assert_eq!((run.false_tracks, run.never_paired), (0, 0));
}

/// The group's accuracy tables are the same on every run: the wall-clock
/// times (abtrack's replays, Stone Soup's processes and their ratio) are
/// written apart, into `scene_times.*`. Two runs of the group into scratch
/// folders, each with the committed Stone Soup tracks and times.
#[test]
fn the_scene_tables_are_the_same_on_every_run_and_the_times_are_apart() {
    use abtrack_host_tests::experiments::{common::Context, real_adsb};
    fn copy_dir(from: &std::path::Path, to: &std::path::Path) {
        std::fs::create_dir_all(to).unwrap();
        for entry in std::fs::read_dir(from).unwrap() {
            let path = entry.unwrap().path();
            let target = to.join(path.file_name().unwrap());
            if path.is_dir() {
                copy_dir(&path, &target);
            } else {
                std::fs::copy(&path, &target).unwrap();
            }
        }
    }
    let committed = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../results/real-adsb")
        .join(real_adsb::STONESOUP_DIR);
    let read = |dir: &std::path::Path, file: &str| {
        std::fs::read_to_string(dir.join(real_adsb::NAME).join(file)).unwrap()
    };
    let runs: Vec<std::path::PathBuf> = (0..2)
        .map(|k| {
            let out =
                std::env::temp_dir().join(format!("abtrack-real-adsb-{}-{k}", std::process::id()));
            let _ = std::fs::remove_dir_all(&out);
            copy_dir(
                &committed,
                &out.join(real_adsb::NAME).join(real_adsb::STONESOUP_DIR),
            );
            let ctx = Context {
                out_dir: out.clone(),
                runs_override: None,
            };
            real_adsb::run(&ctx).unwrap();
            out
        })
        .collect();
    for file in ["scene.csv", "scene.md", "summary.md"] {
        assert_eq!(read(&runs[0], file), read(&runs[1], file), "{file}");
        assert!(!read(&runs[0], file).contains("time (ms)"), "{file}");
    }
    let times = read(&runs[0], "scene_times.csv");
    let mut lines = times.lines();
    assert_eq!(lines.next(), Some("scene,tracker,replay time (ms)"));
    // Per scene: the four configurations of abtrack and Stone Soup.
    assert_eq!(lines.count(), 2 * 5, "{times}");
    let text = read(&runs[0], "scene_times.md");
    assert!(
        text.contains("Whole-process time of Stone Soup against abtrack's whole replay in f64"),
        "{text}"
    );
    assert!(text.contains("×"), "{text}");
    for out in runs {
        let _ = std::fs::remove_dir_all(out);
    }
}
