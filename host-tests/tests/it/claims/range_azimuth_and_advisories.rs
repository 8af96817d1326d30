//! The claims of the range–azimuth and TCAS advisory experiments, checked statistically on reduced
//! Monte Carlo runs (the full runs are `cargo run --release --bin
//! experiments -- --only he-tcas,tcas-advisory`; their numbers are in
//! `results/he-tcas/summary.md` and `results/tcas-advisory/summary.md`).
//!
//! The runs are seeded, so every assertion below is deterministic; the
//! bounds are set from the statistics (95 % intervals, documented margins),
//! not fitted to one outcome.
//!
//! He, Peng, Ling & Quan (seed 003) claim that their range–azimuth filter's
//! estimation error is significantly less than the per-axis αβ filter's.
//! On their scenario with the bearing noise of their own VAR (σ_B² =
//! 7.569e-3 rad²) that does not reproduce: the tests pin down what does
//! hold (equal position error, range errors dominated by opposite
//! ~R·σ_B²/2 biases, a clear gain over the first-order converted Kalman
//! filter, a clear loss against the maximum-likelihood yardstick, and
//! agreement of the on-target arithmetics).

use abtrack_host_tests::experiments::common::Context;
use abtrack_host_tests::experiments::he_tcas::{
    self, paired, HeTcasConfig, Method, Quantity, Window, MEANINGFUL_IMPROVEMENT,
};
use abtrack_host_tests::experiments::tcas_advisory::{
    self, bearing_sensitivity, continuous_range_test_onset, onset_and_end, onset_stats, Arithmetic,
    Level, REPORT_TIMES_S,
};
use abtrack_host_tests::experiments::GROUPS;
use abtrack_host_tests::scenario;

/// σ_B² of He et al. (rad²).
const BEARING_VARIANCE: f64 = 7.569e-3;

fn he_tcas_runs(runs: usize, numeric_types: bool, yardstick: bool) -> he_tcas::HeTcasOutcome {
    he_tcas::simulate(&HeTcasConfig {
        numeric_types,
        yardstick,
        ..HeTcasConfig::with_runs(runs)
    })
    .expect("simulation runs")
}

#[test]
fn he_tcas_position_error_is_the_alpha_beta_filters_claim_1_does_not_reproduce() {
    let out = he_tcas_runs(150, false, false);
    let ra = out.method(Method::RangeAzimuthF64).unwrap();
    let m2 = out.method(Method::AlphaBetaM2).unwrap();
    for window in [Window::Overall, Window::Late] {
        let (d, rel) = paired(ra, m2, window, Quantity::Position).unwrap();
        let scale = m2.ci(window, Quantity::Position).mean;
        // Not better by the verdict's 3 % (95 % confidence) — and not worse
        // by 3 % either: the two filters have the same position error.
        assert!(
            d.lower() > -MEANINGFUL_IMPROVEMENT * scale
                && d.upper() < MEANINGFUL_IMPROVEMENT * scale,
            "{window:?}: difference {d:?} ({rel:+.2} %) of {scale:.0} m"
        );
    }
    // The position error is cross-range error: the range error is a small
    // part of it for both filters (late: ~1 km of ~2 km, in quadrature).
    for m in [ra, m2] {
        let late = m.ci(Window::Late, Quantity::Position).mean;
        let cross = m.ci(Window::Late, Quantity::CrossRange).mean;
        assert!(
            cross > 0.75 * late,
            "{:?}: cross {cross} of {late}",
            m.method
        );
    }
}

#[test]
fn he_tcas_range_errors_are_opposite_conversion_and_projection_biases() {
    let out = he_tcas_runs(150, false, false);
    let ra = out.method(Method::RangeAzimuthF64).unwrap();
    let m2 = out.method(Method::AlphaBetaM2).unwrap();
    // Late phase: R from 262 km (t = 400 s) to 256 km (t = 499 s).
    let r = 259_000.0;
    let outward = r * BEARING_VARIANCE / 2.0; // ≈ 980 m
    let inward = -r * (1.0 - (-BEARING_VARIANCE / 2.0f64).exp()); // ≈ −978 m
    let ra_bias = ra.ci(Window::Late, Quantity::RangeBias);
    let m2_bias = m2.ci(Window::Late, Quantity::RangeBias);
    assert!(
        (0.8 * outward..1.2 * outward).contains(&ra_bias.mean),
        "range-azimuth late range bias {ra_bias:?}, expected ≈ +{outward:.0} m"
    );
    assert!(
        (1.2 * inward..0.8 * inward).contains(&m2_bias.mean),
        "alpha-beta late range bias {m2_bias:?}, expected ≈ {inward:.0} m"
    );
    // The range-azimuth filter's range RMSE is lower overall (its bias
    // crosses zero on the way out) — significantly, with the paired interval.
    let (d, _) = paired(ra, m2, Window::Overall, Quantity::Range).unwrap();
    assert!(d.upper() < 0.0, "range RMSE difference {d:?}");
    // Removing either bias (the diagnostic variants) takes the late range
    // RMSE from ~1 km to below 200 m.
    for m in [
        Method::RangeAzimuthRangeResidual,
        Method::AlphaBetaM2Debiased,
    ] {
        let late = out.method(m).unwrap().ci(Window::Late, Quantity::Range);
        assert!(late.upper() < 200.0, "{m:?}: {late:?}");
    }
}

#[test]
fn he_tcas_range_azimuth_beats_the_first_order_converted_kalman_filter() {
    let out = he_tcas_runs(150, false, false);
    let ra = out.method(Method::RangeAzimuthF64).unwrap();
    let kf = out.method(Method::KalmanCv).unwrap();
    for window in [Window::Overall, Window::Late] {
        let (d, rel) = paired(ra, kf, window, Quantity::Position).unwrap();
        let scale = kf.ci(window, Quantity::Position).mean;
        assert!(d.upper() < -0.15 * scale, "{window:?}: {d:?} ({rel:+.1} %)");
    }
}

#[test]
fn he_tcas_maximum_likelihood_yardstick_is_well_below_both_filters() {
    let out = he_tcas_runs(10, false, true);
    let ra = out.method(Method::RangeAzimuthF64).unwrap();
    let ml = out.method(Method::BatchMl).unwrap();
    let (d, rel) = paired(ra, ml, Window::Overall, Quantity::Position).unwrap();
    assert!(
        d.lower() > 0.0,
        "range-azimuth minus ML overall: {d:?} ({rel:+.1} %)"
    );
    // The yardstick uses the accurate ranges: tens of metres, not ~1 km.
    let range = ml.ci(Window::Late, Quantity::Range);
    assert!(range.upper() < 60.0, "{range:?}");
}

#[test]
fn he_tcas_on_target_arithmetic_stays_close_to_f64() {
    let out = he_tcas_runs(10, true, false);
    let f32d = out.f32_deviation.unwrap();
    let fixd = out.fix_deviation.unwrap();
    // Range–azimuth module docs: f32 within 0.11 m of the reference on one
    // run; ten runs, allow 1 m. Q32.32: 3 mm on one run, allow 5 cm.
    assert!(f32d.max_position_m < 1.0, "{f32d:?}");
    assert!(fixd.max_position_m < 0.05, "{fixd:?}");
    for m in [Method::RangeAzimuthF32, Method::RangeAzimuthFix] {
        assert_eq!(out.method(m).unwrap().refused, 0, "{m:?}");
    }
}

#[test]
fn tcas_true_timeline_matches_the_analytic_onsets() {
    let runs = tcas_advisory::simulate(tcas_advisory::BASE_SEED, 2).unwrap();
    let truth0 = scenario::truth("tcas-converging").unwrap()[0][0];
    // SL 5 at 8000 ft: TA τ 40 s / DMOD 0.75 NM, RA τ 25 s / DMOD 0.55 NM.
    let ta = continuous_range_test_onset(&truth0, 0.75 * 1852.0, 40.0, 140.0).unwrap();
    let ra = continuous_range_test_onset(&truth0, 0.55 * 1852.0, 25.0, 140.0).unwrap();
    // By hand: r − D²/r = τ·c gives r = (τc + √((τc)² + 4D²))/2 with the
    // closure c = 257.22·y/r m/s (500 kt, head-on with a 370.4 m offset):
    // TA c ≈ 257.1, r = 10 468 m; RA c ≈ 256.8, r = 6 578 m. With
    // y0 = √(25 928² − 370.4²) = 25 925.4 m, t = (y0 − √(r² − 370.4²))/257.22
    // = 60.12 s and 75.26 s.
    assert!((ta - 60.12).abs() < 0.05, "TA {ta}");
    assert!((ra - 75.26).abs() < 0.05, "RA {ra}");
    for r in &runs {
        assert_eq!(onset_and_end(&r.truth, Level::Ta).unwrap().0, ta.ceil());
        assert_eq!(onset_and_end(&r.truth, Level::Ra).unwrap().0, ra.ceil());
    }
}

/// The advisory timeline from the estimated track matches the truth's on the
/// converging encounter: TA and RA onsets within ±1 s (one scan) of the
/// truth's in at least 90 % of the runs, none missed, no false alert; the
/// f32 and Q32.32 chains give the f64 chain's timeline.
#[test]
fn tcas_estimated_advisory_timeline_matches_the_truth() {
    let runs = tcas_advisory::simulate(tcas_advisory::BASE_SEED, 40).unwrap();
    for level in Level::ALL {
        let s = onset_stats(&runs, level, 0, Arithmetic::F64);
        assert_eq!(s.missed, 0, "{level:?}");
        assert_eq!(s.false_alert_runs, 0, "{level:?}");
        assert_eq!(s.onset_delays_s.len(), runs.len());
        let within = s.onsets_within(1.0);
        assert!(
            within * 10 >= runs.len() * 9,
            "{level:?}: {within} of {} onsets within ±1 s",
            runs.len()
        );
        // Ends (the range opening past DMOD) within one scan too.
        assert!(s.end_delays_s.iter().all(|d| d.abs() <= 1.0), "{level:?}");
        // The estimate never alerts early here (its tau is biased high).
        assert!(s.onset_delays_s.iter().all(|&d| d >= 0.0), "{level:?}");
    }
    for r in &runs {
        for per_sigma in &r.estimated {
            let reference: Vec<_> = per_sigma[0].iter().map(|s| s.advisory).collect();
            for other in &per_sigma[1..3] {
                let o: Vec<_> = other.iter().map(|s| s.advisory).collect();
                assert_eq!(o, reference);
            }
        }
        assert!(r.refused.iter().flatten().all(|&n| n == 0));
    }
}

/// The late TA comes from a range-rate bias towards opening that scales with
/// the bearing variance (a second-order effect of the projections): ≈ 6 m/s
/// at 5°, under 0.5 m/s at 1° (σ_B² 25× smaller).
#[test]
fn tcas_range_rate_bias_scales_with_bearing_variance() {
    let i55 = REPORT_TIMES_S.iter().position(|&t| t == 55.0).unwrap();
    let five = bearing_sensitivity(tcas_advisory::BASE_SEED, 30, 1.0).unwrap();
    let one = bearing_sensitivity(tcas_advisory::BASE_SEED, 30, 0.2).unwrap();
    let e5 = five.range_rate_error[i55];
    let e1 = one.range_rate_error[i55];
    assert!(e5.lower() > 3.0, "5°: {e5:?}");
    assert!(
        e1.upper() < 0.6 && e1.mean < e5.mean / 10.0,
        "1°: {e1:?} vs {e5:?}"
    );
    assert!(five.ta.onset_ci().mean > 0.2 && one.ta.onset_ci().mean < 0.2);
}

#[test]
fn groups_write_their_documented_files() {
    let names: Vec<&str> = GROUPS.iter().map(|g| g.name).collect();
    assert!(names.contains(&"he-tcas") && names.contains(&"tcas-advisory"));
    let dir = std::env::temp_dir().join(format!(
        "abtrack-claims-range-azimuth-{}",
        std::process::id()
    ));
    let ctx = Context {
        out_dir: dir.clone(),
        runs_override: Some(3),
    };
    for (name, files) in [
        (he_tcas::NAME, he_tcas::FILES),
        (tcas_advisory::NAME, tcas_advisory::FILES),
    ] {
        let group = GROUPS.iter().find(|g| g.name == name).unwrap();
        (group.run)(&ctx).unwrap_or_else(|e| panic!("{name}: {e}"));
        let written: std::collections::BTreeSet<String> = std::fs::read_dir(dir.join(name))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        let documented: std::collections::BTreeSet<String> =
            files.iter().map(|f| f.to_string()).collect();
        assert_eq!(written, documented, "{name}");
        for f in files {
            let text = std::fs::read_to_string(dir.join(name).join(f)).unwrap();
            assert!(!text.is_empty(), "{name}/{f} is empty");
            if f.ends_with(".svg") {
                assert!(text.starts_with("<svg"), "{name}/{f}");
            } else if f.ends_with(".md") && !f.starts_with("summary") {
                assert!(text.starts_with("| "), "{name}/{f}");
                // A '|' inside a cell would shift the columns.
                let columns: Vec<usize> = text.lines().map(|l| l.matches('|').count()).collect();
                assert!(
                    columns.iter().all(|&c| c == columns[0]),
                    "{name}/{f}: {columns:?}"
                );
            }
        }
        let summary = std::fs::read_to_string(dir.join(name).join("summary.md")).unwrap();
        assert!(summary.contains("Verdict"), "{name}");
        assert!(summary.contains(&format!("--only {name}")), "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
