//! Claims of the randomized TCAS encounter suite
//! (`host-tests/src/random_encounters.rs`; figures in
//! `results/tcas-random/`, written by
//! `cd host-tests && cargo run --release --bin experiments -- --only tcas-random`)
//! and of the bearing tracker's initiation under bearing noise
//! (`abtrack::filter::range_azimuth`, "Initiation under bearing noise").

use std::f64::consts::PI;

use abtrack::filter::altitude::AltitudeQuantum;
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::tcas::MAX_CLOSURE_SPEED_M_PER_S;
use abtrack::{Scalar, ScaledScalar};
use abtrack_host_tests::experiments::tcas_random::LATE_ONSET_S;
use abtrack_host_tests::noise::{rng_from_seed, standard_normal};
use abtrack_host_tests::random_encounters::{
    ra_onset, reference, run_one, suite, trace_one, Condition, RandomEncounter, Tally, CONDITIONS,
    LEVELS, PER_LEVEL,
};
use rayon::prelude::*;

/// Noisy runs per encounter and condition.
pub(super) const SEEDS: usize = 5;

/// The tally of every run of `encounters` under `condition` in `S`, each
/// compared with its timeline in `references`.
pub(super) fn tally<S: Scalar>(
    encounters: &[RandomEncounter],
    references: &[Vec<abtrack_host_tests::encounters::ScanOutcome>],
    condition: &Condition,
) -> Tally {
    let runs: Vec<_> = encounters
        .par_iter()
        .zip(references)
        .flat_map_iter(|(e, r)| {
            let n = if condition.noisy { SEEDS } else { 1 };
            (0..n).map(move |run| (e, run_one::<S>(e, condition, run, r, None)))
        })
        .collect();
    let mut t = Tally::default();
    runs.iter().for_each(|(e, r)| t.add(e, r));
    t
}

/// The other sense than the rules on the true states is taken only in
/// encounters this near co-altitude at closest approach, ft: within what
/// 25 ft reports place the intruder 20 s ahead (the report's ±12.5 ft and
/// the rate's error over the tau), so the sign of the projected VMD, which
/// decides the sense, is not known there (docs/tcas.md).
const NEAR_TIE_VMD_FT: f64 = 60.0;

fn assert_near_ties(t: &Tally, condition: &Condition) {
    if let Some(vmd) = t.wrong_sense_largest_vmd_ft {
        assert!(
            vmd <= NEAR_TIE_VMD_FT,
            "{}: a wrong sense at |VMD| {vmd} ft",
            condition.name
        );
    }
}

/// The tallies of `condition` in f64, f32 and the firmware's type, which
/// refuse no run and count the same false, missed, wrong-sense, in-pieces
/// and reversed RAs.
pub(super) fn tallies_in_every_type(
    encounters: &[RandomEncounter],
    references: &[Vec<abtrack_host_tests::encounters::ScanOutcome>],
    condition: &Condition,
) -> [Tally; 3] {
    let tallies = [
        tally::<f64>(encounters, references, condition),
        tally::<f32>(encounters, references, condition),
        tally::<ScaledScalar>(encounters, references, condition),
    ];
    let counts = |t: &Tally| {
        (
            t.refused,
            t.false_ra,
            t.missed_ra,
            t.wrong_sense,
            t.in_pieces,
            t.reversed,
        )
    };
    for t in &tallies {
        assert_eq!(t.refused, 0, "{}", condition.name);
        assert_eq!(
            counts(t),
            counts(&tallies[0]),
            "{}: the types differ",
            condition.name
        );
    }
    tallies
}

pub(super) fn fraction(n: usize, d: usize) -> f64 {
    n as f64 / d as f64
}

#[test]
fn the_suite_spans_the_specified_ranges() {
    let s = suite();
    assert!(s.len() >= 300);
    for (i, (level, _, _)) in LEVELS.iter().enumerate() {
        let at: Vec<_> = s.iter().filter(|e| e.level == *level).collect();
        assert_eq!(at.len(), PER_LEVEL, "SL{level}");
        assert!(at.iter().all(|e| e.index / PER_LEVEL == i));
    }
    let (lo, hi) = s.iter().fold((f64::MAX, f64::MIN), |(lo, hi), e| {
        (lo.min(e.closure_kt), hi.max(e.closure_kt))
    });
    assert!((100.0..150.0).contains(&lo) && hi <= 1000.0 && hi > 950.0);
    assert!(s
        .iter()
        .all(|e| e.hmd_m <= 1.5 * 1852.0 && e.vmd_ft.abs() <= 1200.0));
    assert!(s.iter().all(|e| e.intruder_rate_ft_per_min.abs() <= 3000.0));
    // Both RA and no-RA encounters at every level.
    for (level, _, _) in LEVELS {
        let with_ra = s
            .iter()
            .filter(|e| e.level == level)
            .filter(|e| reference(e).iter().any(|o| o.sense.is_some()))
            .count();
        assert!(with_ra > 0 && with_ra < PER_LEVEL, "SL{level}: {with_ra}");
    }
}

/// Under a TCAS receiver's noise (range σ 15 m, bearing σ 5° or 10°) no
/// run is refused, in f64, f32 and the firmware's `Fixed32`; missed
/// RAs ≤ 1 %, false RAs ≤ 2 % and at most 5 % at every level, RA onset
/// delay median ≤ 1 s and 95th percentile ≤ 5 s at σB 5° with 25 ft
/// altitudes (6 s with 100 ft). At σB 10° it is 6 s, a target missed by one
/// RA: 19 of 376 (5.05 %) come 6 s or more late, the same runs as before
/// the tau cap held the true tau (DO-185B `TRTRU`), which removed 10 of the
/// reference's RAs, none of them late. One RA per encounter in every run: the RA is held
/// while the threat's range test holds, and the continuing HMD filter ends
/// it only when the combined miss distance's lower bound m − 2σ is beyond
/// 1.05·DMOD, σ scaled up when the range and bearing estimates disagree
/// beyond their σ (2 runs of one encounter, SL 4 HMD 389 m, had their RA
/// in two pieces before: the range track's r̈ near closest approach, far
/// from the true one, held that bound over it). At 5° and 25 ft:
/// false RAs 24 of 1500 runs (1.6 %; 2.6 % when a bearing disagreement
/// within 0.35σ_b was a manoeuvre, 5.7 % with the bearing miss distance
/// alone bounding the range projection), 6 missed, 22 with the other sense
/// at onset and 6 reversed; the three types agree run for run. Every run
/// with the other sense, in every condition, is a near-tie
/// ([`NEAR_TIE_VMD_FT`]).
#[test]
fn noisy_runs_are_never_refused_and_ras_are_timely_in_every_type() {
    let encounters = suite();
    let references: Vec<_> = encounters.par_iter().map(reference).collect();
    for condition in CONDITIONS.iter().filter(|c| c.noisy) {
        let tallies = tallies_in_every_type(&encounters, &references, condition);
        for t in &tallies {
            assert_eq!(t.runs, encounters.len() * SEEDS);
            assert!(
                fraction(t.missed_ra, t.accepted()) <= 0.01,
                "{}: missed {}",
                condition.name,
                t.missed_ra
            );
            assert!(t.delay_quantile(0.5).unwrap() <= 1.0, "{}", condition.name);
            let p95_limit = match condition.quantum {
                AltitudeQuantum::ModeS25 if condition.name == "σB 10°, 25 ft" => {
                    // Missed by one RA: 19 of the 376 paired RAs (5.05 %)
                    // come 6 s or more late.
                    let late = t
                        .onset_delays_s
                        .iter()
                        .filter(|&&d| d > LATE_ONSET_S)
                        .count();
                    assert_eq!((late, t.onset_delays_s.len()), (19, 376));
                    LATE_ONSET_S + 1.0
                }
                AltitudeQuantum::ModeS25 => LATE_ONSET_S,
                AltitudeQuantum::ModeC => 6.0,
            };
            assert!(
                t.delay_quantile(0.95).unwrap() <= p95_limit,
                "{}",
                condition.name
            );
            assert_eq!(t.in_pieces, 0, "{}: RAs in pieces", condition.name);
            assert_near_ties(t, condition);
        }
        let f = fraction(tallies[0].false_ra, tallies[0].accepted());
        assert!(f <= 0.02, "{}: false RAs {f}", condition.name);
        if condition.name == "σB 5°, 25 ft" {
            let t = &tallies[0];
            assert_eq!(
                (
                    t.false_ra,
                    t.missed_ra,
                    t.wrong_sense,
                    t.in_pieces,
                    t.reversed
                ),
                (24, 6, 22, 0, 6)
            );
        }
        for (i, (level, _, _)) in LEVELS.iter().enumerate() {
            let at = &encounters[i * PER_LEVEL..(i + 1) * PER_LEVEL];
            let refs = &references[i * PER_LEVEL..(i + 1) * PER_LEVEL];
            let t = tally::<f64>(at, refs, condition);
            let f = fraction(t.false_ra, t.accepted());
            assert!(f <= 0.05, "{} SL{level}: false RAs {f}", condition.name);
        }
    }
}

/// The late RA docs/tcas.md ("Late RAs") traces: encounter 20 (SL 3, a
/// 121 m pass), seed 0 at σB 5° and 25 ft, in f64
/// (`results/tcas-random/late_ra_traces.md`). Its RA comes more than
/// [`LATE_ONSET_S`] after the reference's, and in at least 5 of the scans
/// between the two onsets the HMD filter removes the RA while the range
/// track's r̈ is more than 10 × the true r̈ (the straight-path prediction
/// holding a miss distance the range noise gave it) and the bearing track's
/// miss distance is below the one the filter compared. An estimator that
/// ends this fails the test, and the docs must change with it.
#[test]
fn a_near_collision_is_late_while_the_range_track_holds_a_false_miss() {
    let encounters = suite();
    let e = &encounters[20];
    assert_eq!((e.index, e.level, e.hmd_m.round()), (20, 3, 121.0));
    let condition = &CONDITIONS[1];
    assert_eq!(condition.name, "σB 5°, 25 ft");
    let (outcomes, trace) = trace_one::<f64>(e, condition, 0).unwrap();
    let onset = |timeline| ra_onset(timeline).unwrap().0;
    let (expected, got) = (onset(&reference(e)), onset(&outcomes));
    assert!(
        got as f64 > expected as f64 + LATE_ONSET_S,
        "onsets {expected} and {got}"
    );
    let held = trace[expected..got]
        .iter()
        .filter(|t| {
            t.miss_distance_filtered
                && t.range_acceleration_m_per_s2
                    .is_some_and(|a| a > 10.0 * t.true_range_acceleration_m_per_s2)
                && matches!(
                    (t.bearing_miss_distance_m, t.filter_miss_distance_m),
                    (Some(b), Some(f)) if b < f
                )
        })
        .count();
    assert!(held >= 5, "{held} scans held by a false range miss");
}

/// On exact measurements no RA is false or missed, no run refused, no RA in
/// pieces (7 false RAs before the range track's miss distance counted with
/// its σ: its r̈ was used only above DO-185B's fixed threshold); 1 run
/// reverses (the intruder crosses the level own aircraft's altitude) and 4
/// take the other sense at onset (near-ties, [`NEAR_TIE_VMD_FT`], decided
/// by the 25 ft altitude tracker's rate; docs/tcas.md).
#[test]
fn exact_runs_miss_no_ra() {
    let encounters = suite();
    let references: Vec<_> = encounters.par_iter().map(reference).collect();
    let t = tally::<f64>(&encounters, &references, &CONDITIONS[0]);
    assert_near_ties(&t, &CONDITIONS[0]);
    assert_eq!(
        (
            t.refused,
            t.false_ra,
            t.missed_ra,
            t.in_pieces,
            t.reversed,
            t.wrong_sense
        ),
        (0, 0, 0, 0, 1, 4)
    );
    assert!(t.reference_ra > 0);
}

/// A head-on from `range_m` at 500 kt closure measured with range σ 15 m
/// and bearing σ `bearing_deg`: the bearing tracker with the TCAS speed
/// bound accepts every scan and never reports a speed above the bound.
/// (Its range rate is not claimed: at 40 km and 10° it was measured up to
/// 275 m/s off after 20 scans; the TCAS logic takes ṙ from the range
/// tracker.)
fn head_on_under_bearing_noise<S: Scalar>(range_m: f64, bearing_deg: f64, seed: u64) {
    let sigma_b = bearing_deg * PI / 180.0;
    let noise = RangeAzimuthNoise::<S>::new_f64(225.0, sigma_b * sigma_b, 1.0)
        .unwrap()
        .with_speed_bound_f64(MAX_CLOSURE_SPEED_M_PER_S)
        .unwrap();
    let mut filter = RangeAzimuthFilter::new(noise);
    let mut rng = rng_from_seed(seed);
    let closure = 500.0 * 1852.0 / 3600.0;
    let bearing = 0.3;
    for k in 0..40 {
        let r = range_m - closure * k as f64;
        let measured_r = r + 15.0 * standard_normal(&mut rng);
        let measured_b = bearing + sigma_b * standard_normal(&mut rng);
        filter
            .update(
                S::from_f64_lossy(measured_r),
                S::from_f64_lossy(measured_b),
                S::ONE,
            )
            .unwrap_or_else(|e| panic!("{range_m} m, {bearing_deg}°, scan {k}: {e}"));
        let [vx, vy] = filter.velocity().map(|v| v.to_f64());
        assert!(
            vx.hypot(vy) <= MAX_CLOSURE_SPEED_M_PER_S * (1.0 + 1e-5),
            "{range_m} m, {bearing_deg}°, scan {k}: speed {}",
            vx.hypot(vy)
        );
    }
}

#[test]
fn bearing_noise_up_to_10_degrees_at_40_km_never_leaves_the_speed_bound() {
    for seed in 0..20 {
        for (range_m, bearing_deg) in [(18_520.0, 2.0), (18_520.0, 5.0), (40_000.0, 10.0)] {
            head_on_under_bearing_noise::<f64>(range_m, bearing_deg, seed);
            head_on_under_bearing_noise::<f32>(range_m, bearing_deg, seed);
            head_on_under_bearing_noise::<ScaledScalar>(range_m, bearing_deg, seed);
        }
    }
}

/// Without a bound the two-point start of the same head-on (10 NM,
/// bearing σ 2°) is faster than any aircraft in some runs: the case the
/// bound exists for.
#[test]
fn the_two_point_start_alone_exceeds_the_envelope() {
    let sigma_b: f64 = 2.0 * PI / 180.0;
    let too_fast = (0..20)
        .filter(|&seed| {
            let noise = RangeAzimuthNoise::<f64>::new_f64(225.0, sigma_b * sigma_b, 1.0).unwrap();
            let mut filter = RangeAzimuthFilter::new(noise);
            let mut rng = rng_from_seed(seed);
            for k in 0..2 {
                let r = 18_520.0 - 257.0 * k as f64 + 15.0 * standard_normal(&mut rng);
                let b = 0.3 + sigma_b * standard_normal(&mut rng);
                filter.update(r, b, 1.0).unwrap();
            }
            let [vx, vy] = filter.velocity();
            vx.hypot(vy) > MAX_CLOSURE_SPEED_M_PER_S
        })
        .count();
    assert!(too_fast >= 5, "{too_fast}");
}
