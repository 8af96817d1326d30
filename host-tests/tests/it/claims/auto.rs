//! What holds of `auto`'s target (RMSE within 10 % of the
//! best method and of a tuned constant-velocity Kalman filter on every
//! scenario of the groups), asserted on reduced Monte Carlo runs of the
//! `auto` group's seeds (`results/auto/` holds the full runs). A case is
//! judged on the paired per-run differences RMSE(auto) − 1.1·RMSE(other)
//! with their 95 % interval (`Within`).
//!
//! Asserted: no case fails (the interval is never above zero), and the
//! cases listed in [`HOLDS`] hold (the interval lies below zero) at these
//! run counts. Not asserted as holding: he-tcas against the best method
//! (the full 200 runs give −45 ± 89 m: inconclusive; docs/auto.md says why)
//! and the cases whose interval reaches zero at the reduced counts.

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

/// (scenario label, metric): auto is within 10 % of the best method and
/// of the tuned Kalman filter, both holding at the reduced counts.
const HOLDS: &[(&str, &str)] = &[
    ("alwagih-cv (white)", "prediction x (m)"),
    ("alwagih-cv (white)", "prediction y (m)"),
    ("alwagih-cv-coloured", "prediction y (m)"),
    ("li-maneuver", "position y (m)"),
    ("liu-turn", "position distance (m)"),
    ("two-crossing (per target)", "position distance (m)"),
    ("parallel-200m (per target)", "position distance (m)"),
    ("dense (per target)", "position distance (m)"),
    ("tcas-30 (per target)", "position distance (m)"),
];

fn check(cases: &[Case]) {
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
        assert_ne!(best.within, Within::Fails, "{}", what(&best));
        assert_ne!(kalman.within, Within::Fails, "{}", what(&kalman));
        if HOLDS.contains(&(c.label.as_str(), c.metric.as_str())) {
            assert_eq!(best.within, Within::Holds, "{}", what(&best));
            assert_eq!(kalman.within, Within::Holds, "{}", what(&kalman));
        }
    }
}

#[test]
fn single_target_groups() {
    let mut cases = alwagih_cases(Some(RUNS)).unwrap();
    cases.extend(li_cases(Some(RUNS)).unwrap());
    cases.extend(liu_cases(Some(RUNS)).unwrap());
    assert_eq!(cases.len(), 7);
    check(&cases);
}

/// he-tcas: auto beats the tuned converted-measurement Kalman filter by
/// more than 10 % (its first-order conversion is inconsistent at 5° of
/// bearing noise), and is not shown worse than 1.1 × the best method.
#[test]
fn he_tcas() {
    let cases = he_cases(Some(HE_RUNS)).unwrap();
    check(&cases);
    let c = &cases[0];
    let kalman = c.against(c.tuned_kalman().unwrap()).unwrap();
    assert_eq!(kalman.within, Within::Holds, "{}", c.label);
    assert!(
        kalman.ratio < 0.9,
        "auto / tuned Kalman {:.3}",
        kalman.ratio
    );
}

#[test]
fn multi_target_scenes_per_target() {
    let cases = scene_cases(Some(SCENE_RUNS)).unwrap();
    assert_eq!(cases.len(), 4);
    check(&cases);
}
