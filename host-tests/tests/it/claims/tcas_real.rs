//! Claims of the TCAS encounter suite around recorded intruders
//! (`host-tests/src/recorded_encounters.rs`; figures in
//! `results/tcas-real/`, written by
//! `cd host-tests && cargo run --release --bin experiments -- --only tcas-real`).

use abtrack_host_tests::experiments::tcas_random::LATE_ONSET_S;
use abtrack_host_tests::random_encounters::{
    exact_library_timeline, ra_onset, reference, trace_one, CONDITIONS, LEVELS,
};
use abtrack_host_tests::recorded_encounters::{suite, MIN_CLOSURE_KT, OWN_ALTITUDE_FT};
use rayon::prelude::*;

use super::tcas_random::{fraction, tallies_in_every_type, tally};

/// The suite: 596 encounters around the recorded paths of the Paris scene
/// and the single segments, at every level SL 3–7, closures of at least
/// 100 kt, own altitudes in the band.
#[test]
fn the_recorded_suite_spans_the_levels() {
    let s = suite().unwrap();
    assert_eq!(s.len(), 596);
    for (level, _, _) in LEVELS {
        assert!(s.iter().any(|e| e.level == level), "SL{level}");
    }
    assert!(s.iter().all(|e| e.closure_kt >= MIN_CLOSURE_KT));
    assert!(s.iter().all(|e| {
        (OWN_ALTITUDE_FT.0..=OWN_ALTITUDE_FT.1).contains(&e.encounter.own_altitude_ft)
    }));
    let mut paths: Vec<&str> = s
        .iter()
        .filter_map(|e| e.encounter.intruder_recording)
        .map(|r| r.path.name.as_str())
        .collect();
    assert_eq!(paths.len(), s.len(), "every intruder is recorded");
    paths.dedup();
    assert!(paths.len() >= 40, "{} paths", paths.len());
}

/// The receiver's noise alone, on real intruders: against the library's
/// own f64 run on exact ranges and bearings, the noisy runs at σB 5° and
/// 10° with 25 ft altitudes are never refused and meet the randomized
/// suite's targets (false RAs ≤ 2 %, missed ≤ 1 %, onset median ≤ 1 s and
/// 95th percentile ≤ 5 s), with the same counts in f64, f32 and the
/// firmware's type. At σB 5°: 1.0 % false, 0.8 % missed, +0/+1 s.
#[test]
fn the_receivers_noise_changes_little_on_recorded_intruders_in_every_type() {
    let encounters = suite().unwrap();
    let exact: Vec<_> = encounters.par_iter().map(exact_library_timeline).collect();
    assert!(exact.iter().all(|t| !t.is_empty()), "an exact run refused");
    for condition in CONDITIONS.iter().filter(|c| c.noisy).take(2) {
        for t in &tallies_in_every_type(&encounters, &exact, condition) {
            assert!(
                fraction(t.false_ra, t.accepted()) <= 0.02,
                "{}",
                condition.name
            );
            assert!(
                fraction(t.missed_ra, t.accepted()) <= 0.01,
                "{}",
                condition.name
            );
            assert!(t.delay_quantile(0.5).unwrap() <= 1.0, "{}", condition.name);
            assert!(
                t.delay_quantile(0.95).unwrap() <= LATE_ONSET_S,
                "{}",
                condition.name
            );
        }
    }
}

/// Against the rules on the true states (whose HMD filter holds the true
/// velocity's straight path), the surveillance disagrees on real intruders
/// already on exact inputs, and noise adds little to it: on exact inputs
/// 35 false RAs of 596 runs (5.9 %) and 3 missed; at σB 5° and 25 ft (f64)
/// 174 of 2980 (5.8 %) and 8 missed. Most of the exact inputs' false RAs
/// (24 of the 35) begin while the HMD filter is off after a
/// manoeuvre the range track detected (DO-185B `detect_maneuvers`: the
/// range track's r̈ below minus its threshold, or its HMD beyond twice the
/// bearing track's bound); the reference has no such detection
/// (docs/tcas.md).
#[test]
fn on_recorded_intruders_the_surveillance_departs_from_the_straight_path_rules() {
    let encounters = suite().unwrap();
    let references: Vec<_> = encounters.par_iter().map(reference).collect();
    let released: Vec<bool> = encounters
        .par_iter()
        .zip(&references)
        .filter_map(|(e, r)| {
            let (outcomes, traces) = trace_one::<f64>(e, &CONDITIONS[0], 0).unwrap();
            match (ra_onset(&outcomes), ra_onset(r)) {
                (Some((k, _)), None) => Some(traces[k].filter_miss_distance_m.is_none()),
                _ => None,
            }
        })
        .collect();
    let exact = tally::<f64>(&encounters, &references, &CONDITIONS[0]);
    assert_eq!((exact.refused, exact.false_ra, exact.missed_ra), (0, 35, 3));
    assert_eq!(released.len(), exact.false_ra);
    let off = released.iter().filter(|&&r| r).count();
    assert_eq!(off, 24, "{off} of {}", released.len());
    for condition in CONDITIONS.iter().filter(|c| c.noisy) {
        let tallies = tallies_in_every_type(&encounters, &references, condition);
        if condition.name == "σB 5°, 25 ft" {
            let t = &tallies[0];
            assert_eq!((t.runs, t.false_ra, t.missed_ra), (2980, 174, 8));
        }
    }
}
