//! The TCAS encounter suite (`abtrack_host_tests::encounters`):
//! head-on, crossing, overtaking, offset passes either side of the HMD
//! threshold (and the 1.2 NM pass at 480 kt), a level intruder
//! 1000 ft away, a descending intruder, a diverging one, a level-off, and
//! non-altitude-reporting intruders below and above 15 500 ft. The
//! expected TA and RA onsets, RA sense and clear of conflict come from the
//! independent reference on the true states (and by hand below for two);
//! the library runs its trackers on the measurements, on exact inputs and
//! with noise (range σ 15 m, bearing σ 5°, altitude quantised) over seeds,
//! in f64, f32 and Q32.32. Figures: `experiments -- --only tcas-advisory`.

use abtrack::{Fix, Scalar, ScaledScalar};
use abtrack_host_tests::encounters::{
    measurements, noisy_runs, run_library, run_reference, suite, timeline, Encounter, Noise,
    NoiseCounts, Timeline,
};
use abtrack_host_tests::reference_tcas::{Alert, Sense};

fn encounter(name: &str) -> Encounter {
    suite().into_iter().find(|e| e.name == name).unwrap()
}

/// By hand, the head-on (14 NM, 500 kt closure c = 0.138 889 NM/s, SL 5,
/// intruder level 200 ft above):
/// * TA when τ_mod = (r² − 0.75²)/(r c) < 40 s: r < (40c + √((40c)² +
///   4·0.5625))/2 = (5.5556 + √(30.864 + 2.25))/2 = 5.6550 NM, i.e.
///   t > (14 − 5.6550)/c = 60.08 s: first scan 61 (h = 200 < 850 ft);
/// * RA when τ_mod < 25 s with DMOD 0.55 NM: r < (3.4722 + √(12.056 +
///   1.21))/2 = 3.5572 NM, t > 75.19 s: scan 76 (h = 200 < 600 ft, the
///   vertical miss stays 200 ft, HMD 0);
/// * sense: down (tests/it/tcas/logic.rs `sense_and_strength_of_the_head_on`);
/// * clear of conflict: at t = 101 s the range is |14 − 101c| = 0.0278 NM
///   = 51 m, opening at 257 m/s: r·ṙ = 13 100 m²/s > H1 = 0.00278 NM²/s =
///   9535 m²/s, so the range test fails (at t = 100 s, 206 m closing, it
///   holds): the threat's first miss, at scan 101, keeps it (DO-185B
///   `KHIT` 3 → 1), its second, at scan 102, 26 s after the RA (over
///   `TMIN`, 4.5 s), ends it: scan 102.
///
/// The level intruder 1000 ft above: |h| = 1000 > 850 ft and not
/// converging: never a TA (nor an RA); proximate (within 6 NM and
/// 1200 ft) from r ≤ 6 NM, t ≥ (14 − 6)/c = 57.6 s: scan 58.
#[test]
fn reference_matches_the_hand_computations() {
    let head_on = timeline(&run_reference(&encounter("head-on")));
    assert_eq!(
        head_on,
        Timeline {
            ta_onset_s: Some(61.0),
            ra_onset_s: Some(76.0),
            sense: Some(Sense::Down),
            clear_of_conflict_s: Some(102.0),
            ta_scans: head_on.ta_scans,
            ra_scans: 26,
        }
    );
    let level = run_reference(&encounter("level-1000ft"));
    let t = timeline(&level);
    assert_eq!((t.ta_onset_s, t.ra_onset_s), (None, None));
    assert_eq!(
        level.iter().position(|s| s.alert == Alert::Proximate),
        Some(58)
    );
}

/// What the reference expects per encounter (and so what the suite covers):
/// an RA with its sense where the published logic gives one, none for the
/// pass beyond the HMD threshold, the level intruder, the diverging one,
/// the level-off and the non-reporting ones; a TA except for the level
/// intruder, the diverging one and the non-reporting one above 15 500 ft.
#[test]
fn reference_expectations_per_encounter() {
    let want: &[(&str, bool, Option<Sense>)] = &[
        ("head-on", true, Some(Sense::Down)),
        ("crossing", true, Some(Sense::Up)),
        ("overtaking", true, Some(Sense::Down)),
        ("offset-inside-hmd", true, Some(Sense::Down)),
        ("offset-beyond-hmd", true, None),
        ("abeam-1.2nm", true, None),
        ("level-1000ft", false, None),
        ("descending", true, Some(Sense::Down)),
        ("diverging", false, None),
        ("level-off", true, None),
        ("non-reporting", true, None),
        ("non-reporting-high", false, None),
    ];
    let names: Vec<&str> = suite().iter().map(|e| e.name).collect();
    assert_eq!(names, want.iter().map(|w| w.0).collect::<Vec<_>>());
    for &(name, ta, sense) in want {
        let t = timeline(&run_reference(&encounter(name)));
        assert_eq!(t.ta_onset_s.is_some(), ta, "{name}");
        assert_eq!(t.ra_onset_s.is_some(), sense.is_some(), "{name}");
        assert_eq!(t.sense, sense, "{name}");
        assert_eq!(t.clear_of_conflict_s.is_some(), sense.is_some(), "{name}");
    }
}

/// On exact inputs (noise-free range and bearing, altitude quantised to
/// 100 ft) the library gives the reference's timeline: TA and RA onsets
/// within one scan (the trackers' estimates can cross a threshold a scan
/// apart from the true state's), the same RA sense, RA exactly where the
/// reference has one, and clear of conflict within two scans (through the
/// closest approach the range tracker's ṙ lags the kink of |r|).
fn exact<S: Scalar>() {
    for e in suite() {
        let want = timeline(&run_reference(&e));
        let got = timeline(&run_library::<S>(&e, &measurements(&e, Noise::Exact)).unwrap());
        let within = |a: Option<f64>, b: Option<f64>, tol: f64| match (a, b) {
            (Some(a), Some(b)) => (a - b).abs() <= tol,
            (None, None) => true,
            _ => false,
        };
        assert!(
            within(got.ta_onset_s, want.ta_onset_s, 1.0),
            "{} {}: {got:?} vs {want:?}",
            S::NAME,
            e.name
        );
        assert!(
            within(got.ra_onset_s, want.ra_onset_s, 1.0),
            "{} {}: {got:?} vs {want:?}",
            S::NAME,
            e.name
        );
        assert_eq!(got.sense, want.sense, "{} {}", S::NAME, e.name);
        assert!(
            within(got.clear_of_conflict_s, want.clear_of_conflict_s, 2.0),
            "{} {}: {got:?} vs {want:?}",
            S::NAME,
            e.name
        );
    }
}

#[test]
fn exact_inputs_follow_the_reference() {
    in_every_tcas_type!(exact);
}

/// Noisy runs per encounter and type.
const RUNS: usize = 30;

fn noisy<S: Scalar>() -> Vec<(Encounter, NoiseCounts)> {
    suite()
        .into_iter()
        .enumerate()
        .map(|(i, e)| {
            let n = noisy_runs::<S>(&e, i as u64, RUNS);
            (e, n)
        })
        .collect()
}

/// With noise (range σ 15 m, bearing σ 5°, 30 seeds): no missed TA or RA,
/// no wrong sense, nothing refused, no RA in pieces, in any type. False
/// alerts (an onset more than 3 s from every scan at which the reference
/// has the alert) only where the measured limits are:
/// * `overtaking` (100 kt closure): TA onsets up to 4 s early in a few runs
///   — at slow closure τ_mod is DMOD-dominated and the 15 m range noise
///   moves it by seconds; at most 20 % of the runs;
/// * `offset-beyond-hmd` (0.8 NM pass, 1.46 × SL 5's HMD threshold): an
///   RA in at most 2 of the 30 runs (measured 2 with the new threat's
///   bound at the combined miss distance itself, 1 with m + 0.35σ, 18
///   before the HMD filter combined the range and bearing miss distances
///   by their σ; the randomized suite's false RAs fell from 2.6 to 1.6 %
///   with the first: docs/tcas.md); none on `abeam-1.2nm`.
///
/// Onsets that are not false lie within ±4 s of the reference's, except on
/// `offset-inside-hmd` (0.4 NM pass, 0.73 × the threshold), where the HMD
/// filter holds the RA until the combined miss distance m is under the
/// threshold: measured, 25 of the 30 onsets on time, 4 later than 4 s,
/// the latest 11 s (20 on time with the bound m + 0.35σ; the trade-off of
/// `results/tcas-random/trade_off.md`).
fn noise_counts<S: Scalar>() {
    for (e, n) in noisy::<S>() {
        let name = format!("{} {}", S::NAME, e.name);
        println!(
            "{name}: missed TA {} RA {}, false TA {} RA {}, wrong sense {}, interrupted RA {}, of {}",
            n.missed_ta, n.missed_ra, n.false_ta, n.false_ra, n.wrong_sense, n.interrupted_ra, n.runs
        );
        assert_eq!(
            (
                n.missed_ta,
                n.missed_ra,
                n.wrong_sense,
                n.refused,
                n.interrupted_ra
            ),
            (0, 0, 0, 0, 0),
            "{name}"
        );
        match e.name {
            "overtaking" => assert!(n.false_ta * 5 <= n.runs, "{name}: {}", n.false_ta),
            _ => assert_eq!(n.false_ta, 0, "{name}"),
        }
        match e.name {
            "offset-beyond-hmd" => assert!(n.false_ra <= 2, "{name}: {}", n.false_ra),
            _ => assert_eq!(n.false_ra, 0, "{name}"),
        }
        for d in &n.ta_delays {
            assert!(d.abs() <= 4.0, "{name}: TA onset delay {d}");
        }
        if e.name == "offset-inside-hmd" {
            let on_time = n.ra_delays.iter().filter(|d| d.abs() <= 1.0).count();
            let late = n.ra_delays.iter().filter(|d| d.abs() > 4.0).count();
            assert!(
                on_time * 3 >= n.runs * 2 && late <= 4,
                "{name}: {:?}",
                n.ra_delays
            );
            assert!(
                n.ra_delays.iter().all(|d| (-4.0..=11.0).contains(d)),
                "{name}"
            );
        } else {
            for d in &n.ra_delays {
                assert!(d.abs() <= 4.0, "{name}: RA onset delay {d}");
            }
        }
    }
}

#[test]
fn noisy_runs_miss_nothing_and_false_alerts_are_bounded_f64() {
    noise_counts::<f64>();
}

#[test]
fn noisy_runs_miss_nothing_and_false_alerts_are_bounded_f32() {
    noise_counts::<f32>();
}

#[test]
fn noisy_runs_miss_nothing_and_false_alerts_are_bounded_q32_32() {
    noise_counts::<Fix>();
}

#[test]
fn noisy_runs_miss_nothing_and_false_alerts_are_bounded_scaled() {
    noise_counts::<ScaledScalar>();
}

/// The false RAs of the passes beyond the HMD threshold are one RA each,
/// at most 15 s long, and end before the closest approach: the
/// continuing-threat filter drops them once the combined miss distance's
/// lower bound m − 2σ is beyond 1.05·DMOD. Measured: 1 of the 30 runs of
/// the 0.8 NM pass has one, 10 s long (before the combined filter, 18 of
/// 30, lasting 6–20 s).
#[test]
fn false_ras_beyond_the_hmd_threshold_are_short() {
    use abtrack_host_tests::encounters::{derive_run_seed, ScanOutcome};
    for (i, e) in suite().into_iter().enumerate() {
        if !matches!(e.name, "offset-beyond-hmd" | "abeam-1.2nm") {
            continue;
        }
        let cpa = closest_approach_s(&e);
        for run in 0..RUNS {
            let meas = measurements(&e, Noise::Seeded(derive_run_seed(i as u64, run as u64)));
            let out: Vec<ScanOutcome> = run_library::<f64>(&e, &meas).unwrap();
            let t = timeline(&out);
            if let (Some(on), Some(off)) = (t.ra_onset_s, t.clear_of_conflict_s) {
                assert!(
                    off - on <= 15.0 && off < cpa,
                    "{} run {run}: RA {on}–{off}",
                    e.name
                );
                assert_eq!(t.ra_scans as f64, off - on, "{} run {run}: one RA", e.name);
            }
        }
    }
}

fn closest_approach_s(e: &Encounter) -> f64 {
    let x = e.relative(0.0);
    let vv = x.v[0] * x.v[0] + x.v[1] * x.v[1];
    -(x.s[0] * x.v[0] + x.s[1] * x.v[1]) / vv
}

/// The demo scenario: the reference gives intruder 0 a
/// TA, then an RA, then clear of conflict; intruder 1 (level 1000 ft
/// above) and intruder 3 (1 NM abeam, beyond the HMD) no RA; intruder 2
/// (no altitude) a TA at most. The library, per intruder on the demo's
/// noisy replies (association is the firmware's), gives the same RAs with
/// the reference's sense. False replies are present, with no altitude.
#[test]
fn demo_scenario_meets_its_specification() {
    use abtrack_host_tests::encounters::{
        demo_intruders, demo_reference, demo_scenario, Measurement,
    };
    let scans = 150;
    let reference = demo_reference(scans);
    let ever = |i: usize, a: Alert| reference.iter().any(|s| s[i] == a);
    assert!(ever(0, Alert::Ta) && ever(0, Alert::Ra));
    assert!(!ever(1, Alert::Ra) && !ever(2, Alert::Ra) && !ever(3, Alert::Ra));
    assert!(ever(2, Alert::Ta));
    let replies = demo_scenario(0xDE40, scans);
    assert!(replies
        .iter()
        .any(|r| r.intruder.is_none() && r.altitude_ft.is_none()));
    for (i, e) in demo_intruders().iter().enumerate() {
        let meas: Vec<Measurement> = replies
            .iter()
            .filter(|r| r.intruder == Some(i))
            .map(|r| Measurement {
                range_m: r.range_m,
                bearing_rad: r.bearing_rad,
                altitude_ft: r.altitude_ft,
            })
            .collect();
        assert_eq!(meas.len(), scans);
        let e = Encounter { scans, ..*e };
        let got = timeline(&run_library::<f64>(&e, &meas).unwrap());
        let want = timeline(&run_reference(&e));
        assert_eq!(
            got.ra_onset_s.is_some(),
            want.ra_onset_s.is_some(),
            "intruder {i}"
        );
        assert_eq!(got.sense, want.sense, "intruder {i}");
        if i == 0 {
            assert_eq!(got.sense, Some(Sense::Down));
            assert!(got.clear_of_conflict_s.is_some());
        }
    }
}
