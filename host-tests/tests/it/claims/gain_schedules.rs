//! The gain-schedule papers' claims that reproduce (`results/{alwagih,li,liu}`),
//! asserted on reduced Monte Carlo runs with paired 95 % confidence
//! intervals, so that a regression in a schedule, the bank or the filters
//! fails a test. The full runs are `experiments --only alwagih,li,liu`.
//!
//! Claims that do not reproduce are not asserted. Where we observe the
//! opposite, stably and for a reason (documented at each test), that
//! observation is asserted instead and named as such.
//!
//! Each experiment uses the group's own base seed, so the runs here are the
//! first [`RUNS`] of the committed results.

use abtrack_host_tests::experiments::common::Context;
use abtrack_host_tests::experiments::monte_carlo::{
    compare, Comparison, Experiment, Metric, Outcome, Segment, ALL_SCANS,
};
use abtrack_host_tests::experiments::{alwagih, li, liu};

/// Monte Carlo runs per experiment in these tests (the committed results
/// use 100 / 100 / 200). The seeds are fixed, so the tests are
/// deterministic; at this count every asserted difference is at least 2.4
/// half-widths of its 95 % interval from zero (the closest: Liu's
/// straight-flight comparisons U3/U4 and Al-Wagih's M5 vs M4). All five
/// tests take about a second in release.
const RUNS: usize = 60;

fn assert_holds(c: &Comparison) {
    assert_eq!(
        c.outcome(),
        Outcome::Holds,
        "expected {} < {} ({}, {}, {}): {}",
        c.better,
        c.worse,
        c.context,
        c.segment,
        c.metric.name(),
        c.describe()
    );
}

fn holds(exp: &Experiment, better: &str, worse: &str, metric: Metric, segment: Segment<'_>) {
    let c = compare(exp, "", better, worse, metric, segment).unwrap();
    assert_holds(&c);
}

const PREDICTION: [Metric; 2] = [Metric::PredictionX, Metric::PredictionY];
const POSITION: [Metric; 2] = [Metric::PositionX, Metric::PositionY];
const VELOCITY: [Metric; 2] = [Metric::VelocityX, Metric::VelocityY];

// ---------------------------------------------------------------------------
// Al-Wagih & Abdulla
// ---------------------------------------------------------------------------

#[test]
fn alwagih_claims_and_observations() {
    let r = alwagih::evaluate(Some(RUNS)).unwrap();
    for exp in [&r.white, &r.coloured] {
        for metric in PREDICTION {
            // Claim A4 (Tables 5–6), reproduced: M4 and M5 reduce the
            // prediction RMSE of M1 (α = 0.05) on both noise types.
            holds(exp, alwagih::M4, alwagih::M1, metric, ALL_SCANS);
            holds(exp, alwagih::M5, alwagih::M1, metric, ALL_SCANS);
            // The part of claims A1/A3 that holds: M5 (as printed) beats M4.
            holds(exp, alwagih::M5, alwagih::M4, metric, ALL_SCANS);
            // Observed, the opposite of claims A1–A3: on a constant-velocity
            // target the least-squares gains M2 (the Kalman filter with no
            // process noise) beat M3, M4 and M5. Stable because it is
            // optimality, not chance.
            for other in [alwagih::M4, alwagih::M5] {
                holds(exp, alwagih::M2, other, metric, ALL_SCANS);
            }
            // Observed: the Kalman CV yardstick is not worse than M1.
            holds(exp, alwagih::KF_CV, alwagih::M1, metric, ALL_SCANS);
            // Observed: the printed M5 "prediction" is chosen after seeing
            // the measurement, so it beats the causal reading of the same
            // bank (the reason both are reported).
            holds(exp, alwagih::M5, alwagih::M5_CAUSAL, metric, ALL_SCANS);
        }
    }
    // Observed on white noise (on coloured noise M3 and M2 are level):
    // M2 beats M3.
    for metric in PREDICTION {
        holds(&r.white, alwagih::M2, alwagih::M3, metric, ALL_SCANS);
    }
    // α = 0.01, the paper's other M1 value, is worse than α = 0.05 here
    // (a slower transient from the same initial velocity error).
    for metric in PREDICTION {
        holds(&r.white, alwagih::M1, alwagih::M1_SMALL, metric, ALL_SCANS);
    }
}

// ---------------------------------------------------------------------------
// Li, Zhao, Liang & Zhang
// ---------------------------------------------------------------------------

#[test]
fn li_claims() {
    let exp = li::evaluate(Some(RUNS)).unwrap();
    let seg = li::Segments::new(&exp);
    let man = |k: usize| seg.is_manoeuvring(k);
    let steady = |k: usize| !seg.is_manoeuvring(k);
    let first = |k: usize| seg.before_first(k);
    let manoeuvring = Segment {
        name: "manoeuvring",
        contains: &man,
    };
    let non_manoeuvring = Segment {
        name: "non-manoeuvring",
        contains: &steady,
    };
    let before_first = Segment {
        name: "before the first manoeuvre",
        contains: &first,
    };
    for metric in VELOCITY {
        // L1 (Fig. 3): better velocity from the third scan on.
        holds(&exp, li::IMPROVED, li::STANDARD, metric, ALL_SCANS);
        // L2 (Fig. 3): and while the motion switches.
        holds(&exp, li::IMPROVED, li::STANDARD, metric, manoeuvring);
    }
    for metric in POSITION {
        // L3 (Fig. 4), the parts that hold: better position while
        // manoeuvring and over the non-manoeuvring scans as a whole.
        holds(&exp, li::IMPROVED, li::STANDARD, metric, manoeuvring);
        holds(&exp, li::IMPROVED, li::STANDARD, metric, non_manoeuvring);
        // Observed, against L3's "whether … non-maneuvering": before the
        // first manoeuvre the standard gains are the least-squares line fit
        // and beat the improved filter, whose count keeps returning towards
        // k = 3 (diff −0.14 ± 0.03 m over 100 runs).
        holds(&exp, li::STANDARD, li::IMPROVED, metric, before_first);
    }
    // Observed: the improved filter is within reach of the CV Kalman
    // yardstick, the standard one is not (it diverges once the target
    // manoeuvres): a lag regression in either would show here.
    let kf = exp.method(li::KF_CV).unwrap();
    let improved = exp.method(li::IMPROVED).unwrap();
    let standard = exp.method(li::STANDARD).unwrap();
    for metric in POSITION {
        let k = kf.summary(metric, ALL_SCANS).mean;
        assert!(improved.summary(metric, ALL_SCANS).mean < 1.5 * k);
        assert!(standard.summary(metric, ALL_SCANS).mean > 10.0 * k);
    }
}

// ---------------------------------------------------------------------------
// Liu, Wang & Yang
// ---------------------------------------------------------------------------

#[test]
fn liu_claims() {
    let exp = liu::evaluate(Some(RUNS)).unwrap();
    let seg = liu::Segments::new(&exp);
    let (straight, turn) = (seg.straight_segment(), seg.turn_segment());
    let d = Metric::PositionDistance;
    // U1: 2.1.1 diverges; every other method beats it.
    for m in [
        liu::COUNT_ADJUSTED,
        liu::FIXED,
        liu::RESIDUAL,
        liu::ADAPTIVE,
    ] {
        holds(&exp, m, liu::COUNT, d, ALL_SCANS);
    }
    // U2: 2.1.2 beats 2.1.1 but is not the best.
    holds(&exp, liu::ADAPTIVE, liu::COUNT_ADJUSTED, d, ALL_SCANS);
    holds(&exp, liu::FIXED, liu::COUNT_ADJUSTED, d, ALL_SCANS);
    // U3 (Fig. 1): fixed beats residual when straight, residual beats fixed
    // in the turn.
    holds(&exp, liu::FIXED, liu::RESIDUAL, d, straight);
    holds(&exp, liu::RESIDUAL, liu::FIXED, d, turn);
    // U4 (Figs. 7–8): the adaptive switch beats residual when straight and
    // fixed in the turn.
    holds(&exp, liu::ADAPTIVE, liu::RESIDUAL, d, straight);
    holds(&exp, liu::ADAPTIVE, liu::FIXED, d, turn);
    // U5, the parts that hold: the adaptive switch beats 2.1.1–2.1.3 over
    // the run. (Against 2.1.4 it is slightly worse over 200 runs, −0.10 ±
    // 0.05 m, too small to assert either way on 60.)
    for m in [liu::COUNT, liu::COUNT_ADJUSTED, liu::FIXED] {
        holds(&exp, liu::ADAPTIVE, m, d, ALL_SCANS);
    }
    // U6–U8, the mechanism (Figs. 2–4).
    let mech = liu::mechanism(&exp).unwrap();
    assert!(
        mech.residual_alpha_above_half_straight > 0.6,
        "U6: {mech:?}"
    );
    assert!(mech.adaptive_fixed_share_straight > 0.9, "U7: {mech:?}");
    // U7's second part does not reproduce (the switch alternates in the
    // turn); observed: the residual branch is used far more in the turn.
    assert!(
        mech.adaptive_fixed_share_turn < mech.adaptive_fixed_share_straight - 0.2,
        "U7: {mech:?}"
    );
    assert!(mech.fixed_over_limit_straight < 0.1, "U8: {mech:?}");
    assert!(mech.fixed_over_limit_turn > 0.6, "U8: {mech:?}");
}

#[test]
fn liu_adaptive_agrees_across_representations() {
    let exp = liu::evaluate(Some(5)).unwrap();
    let reference = exp.method(liu::ADAPTIVE).unwrap();
    for (label, bound) in [(liu::ADAPTIVE_F32, 0.05), (liu::ADAPTIVE_FIX, 1e-6)] {
        let m = exp.method(label).unwrap();
        for (run, (a, b)) in m.runs.iter().zip(&reference.runs).enumerate() {
            for (k, (s, r)) in a.iter().zip(b).enumerate() {
                assert_eq!(
                    s.output.steady, r.output.steady,
                    "{label} run {run} scan {k}"
                );
                for axis in 0..2 {
                    let e = (s.output.position[axis] - r.output.position[axis]).abs();
                    assert!(e < bound, "{label} run {run} scan {k}: {e}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// The documented files
// ---------------------------------------------------------------------------

#[test]
fn groups_write_the_documented_files() {
    let dir = std::env::temp_dir().join(format!(
        "abtrack-claims-gain-schedules-{}",
        std::process::id()
    ));
    let ctx = Context {
        out_dir: dir.clone(),
        runs_override: Some(3),
    };
    alwagih::run(&ctx).unwrap();
    li::run(&ctx).unwrap();
    liu::run(&ctx).unwrap();
    let expect: &[(&str, &[&str])] = &[
        (
            "alwagih",
            &[
                "summary.md",
                "claims.csv",
                "claims.md",
                "rmse_white.csv",
                "rmse_white.md",
                "rmse_coloured.csv",
                "rmse_coloured.md",
                "sets_white.md",
                "sets_coloured.md",
                "differences_white.md",
                "differences_coloured.md",
                "paper_vs_ours.md",
                "track_white.svg",
                "track_coloured.svg",
                "rmse_time_white_x.svg",
                "rmse_time_white_y.svg",
                "rmse_time_coloured_x.svg",
                "rmse_time_coloured_y.svg",
            ],
        ),
        (
            "li",
            &[
                "summary.md",
                "claims.csv",
                "claims.md",
                "rmse.csv",
                "rmse.md",
                "rmse_manoeuvring.md",
                "rmse_non_manoeuvring.md",
                "sensitivity.md",
                "track.svg",
                "rmse_velocity_x.svg",
                "rmse_velocity_y.svg",
                "rmse_position_x.svg",
                "rmse_position_y.svg",
                "alpha.svg",
            ],
        ),
        (
            "liu",
            &[
                "summary.md",
                "claims.csv",
                "claims.md",
                "rmse.csv",
                "rmse.md",
                "rmse_straight.md",
                "rmse_turn.md",
                "rmse_before_turn.md",
                "rmse_after_turn.md",
                "representations.md",
                "track.svg",
                "rmse_distance_time.svg",
                "distance_run0.svg",
                "alpha.svg",
                "innovation_x.svg",
                "innovation_y.svg",
            ],
        ),
    ];
    for (group, files) in expect {
        for f in *files {
            let path = dir.join(group).join(f);
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            if f.ends_with(".svg") {
                assert!(text.starts_with("<svg"), "{}", path.display());
            } else if f.ends_with(".csv") {
                assert!(text.lines().count() >= 2, "{}", path.display());
            } else {
                assert!(
                    text.contains('|') || text.starts_with('#'),
                    "{}",
                    path.display()
                );
            }
        }
        // Every claim line has a verdict; the run count is the override.
        let summary = std::fs::read_to_string(dir.join(group).join("summary.md")).unwrap();
        let claims = summary.lines().filter(|l| l.starts_with("- **")).count();
        let verdicts = summary.matches("**Verdict: ").count();
        assert!(
            claims >= 4 && claims == verdicts,
            "{group}: {claims} claims, {verdicts} verdicts"
        );
        assert!(summary.contains("3 Monte Carlo runs"), "{group}");
    }
    // The Markdown and CSV tables agree on their shape.
    let csv = std::fs::read_to_string(dir.join("liu/rmse.csv")).unwrap();
    let md = std::fs::read_to_string(dir.join("liu/rmse.md")).unwrap();
    assert_eq!(csv.lines().count() + 1, md.lines().count());
    std::fs::remove_dir_all(&dir).unwrap();
}
