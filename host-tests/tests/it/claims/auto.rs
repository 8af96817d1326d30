//! What holds of `auto`'s RMSE against the best method and a tuned
//! constant-velocity Kalman filter (within 10 %) on the simulated scenarios
//! of the groups, asserted on reduced Monte Carlo runs of the
//! `auto` group's seeds (`results/auto/` holds the full runs). A case is
//! judged on the paired per-run differences RMSE(auto) − 1.1·RMSE(other)
//! with their 95 % interval (`Within`).
//!
//! Asserted: exactly the cases listed in [`TRADED`] fail (the interval is
//! above zero), and the cases listed in [`HOLDS`] hold (the interval lies
//! below zero) at these run counts; the others are inconclusive there.

use abtrack_host_tests::experiments::auto::{
    alwagih_cases, he_cases, li_cases, liu_cases, scene_cases, Case, Within,
};

/// Runs of the single-target groups here (their documented counts are
/// 100–200).
const RUNS: usize = 40;
/// Runs of he-tcas here (200 documented).
const HE_RUNS: usize = 30;
/// Runs of the multi-target scenes here (200 documented).
const SCENE_RUNS: usize = 60;

/// (scenario label, metric): auto is worse than 1.1 × the best method or the
/// tuned Kalman filter. These are simulated targets on an exact straight
/// line, where the best filter has no process noise at all, and `auto`'s
/// manoeuvre level never falls below the floor of a real aircraft
/// (`Q_MIN`, docs/auto.md "Limits"): the price of holding on recorded
/// flights (`results/real-adsb/`).
const TRADED: &[(&str, &str)] = &[
    ("alwagih-cv (white)", "prediction x (m)"),
    ("alwagih-cv (white)", "prediction y (m)"),
    ("alwagih-cv-coloured", "prediction x (m)"),
    ("alwagih-cv-coloured", "prediction y (m)"),
    ("li-maneuver", "position x (m)"),
    ("two-crossing (per target)", "position distance (m)"),
    ("parallel-200m (per target)", "position distance (m)"),
    ("dense (per target)", "position distance (m)"),
    ("he-tcas", "position, overall (m)"),
];

/// (scenario label, metric): auto is within 10 % of the best method and
/// of the tuned Kalman filter, both holding at the reduced counts.
const HOLDS: &[(&str, &str)] = &[
    ("li-maneuver", "position y (m)"),
    ("tcas-30 (per target)", "position distance (m)"),
];

fn check(cases: &[Case]) {
    // A case that fails and is not listed in TRADED, or is listed and does
    // not fail.
    let mut mismatched = Vec::new();
    for c in cases {
        let best = c.against(c.best().unwrap()).unwrap();
        let kalman = c.against(c.tuned_kalman().unwrap()).unwrap();
        let what = |a: &abtrack_host_tests::experiments::auto::Against| {
            format!(
                "{} / {}: auto {:.3} vs {} {:.3} (ratio {:.3}), auto − 1.1·other {:.3} ± {:.3}",
                c.label,
                c.metric,
                a.auto_rmse.mean,
                a.other,
                a.other_rmse.mean,
                a.ratio,
                a.margin.mean,
                a.margin.half_width
            )
        };
        println!("{}", what(&best));
        println!("{}", what(&kalman));
        let case = (c.label.as_str(), c.metric.as_str());
        let fails = best.within == Within::Fails || kalman.within == Within::Fails;
        if fails != TRADED.contains(&case) {
            mismatched.push(format!("{} / {}", what(&best), what(&kalman)));
        }
        let holds = best.within == Within::Holds && kalman.within == Within::Holds;
        if HOLDS.contains(&case) && !holds {
            mismatched.push(format!("listed as holding: {}", what(&best)));
        }
    }
    assert!(
        mismatched.is_empty(),
        "not as TRADED says:\n{}",
        mismatched.join("\n")
    );
}

#[test]
fn single_target_groups() {
    let mut cases = alwagih_cases(Some(RUNS)).unwrap();
    cases.extend(li_cases(Some(RUNS)).unwrap());
    cases.extend(liu_cases(Some(RUNS)).unwrap());
    assert_eq!(cases.len(), 7);
    check(&cases);
}

/// he-tcas: auto is within 10 % of the tuned converted-measurement Kalman
/// filter (it is worse than 1.1 × the best method: [`TRADED`]).
#[test]
fn he_tcas() {
    let cases = he_cases(Some(HE_RUNS)).unwrap();
    check(&cases);
    let c = &cases[0];
    let kalman = c.against(c.tuned_kalman().unwrap()).unwrap();
    assert_eq!(kalman.within, Within::Holds, "{}", c.label);
}

#[test]
fn multi_target_scenes_per_target() {
    let cases = scene_cases(Some(SCENE_RUNS)).unwrap();
    assert_eq!(cases.len(), 4);
    check(&cases);
}
