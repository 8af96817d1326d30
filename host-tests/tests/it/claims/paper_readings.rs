//! The readings of the papers' formulas and tables (Tenne & Singh's
//! closed forms, He et al.'s eq. 9, Liu's window, Al-Wagih's tables),
//! checked on reduced runs (the full runs: `cd host-tests && cargo run
//! --release --bin experiments -- --only tenne-singh,he-tcas,liu,alwagih`;
//! their numbers are in the groups' `summary.md`).
//!
//! Seeded, so deterministic; the asserted differences are many half-widths
//! of their 95 % intervals from zero at these run counts.

use abtrack_host_tests::experiments::monte_carlo::Verdict;
use abtrack_host_tests::experiments::tenne_singh::{self, Figure2Curve};

/// Monte Carlo runs of the simulated worked example here (the committed
/// results use 200).
const TENNE_SINGH_RUNS: usize = 40;

#[test]
fn tenne_singh_closed_forms_optimiser_and_simulation() {
    let out = tenne_singh::evaluate(TENNE_SINGH_RUNS).unwrap();
    // Fig. 2: every closed form (where the optimum is interior) is the
    // optimiser's optimum.
    for curve in Figure2Curve::ALL {
        let points: Vec<_> = out.figure2.iter().filter(|p| p.curve == curve).collect();
        let with_closed = points.iter().filter(|p| p.closed.is_some()).count();
        assert!(with_closed + 1 >= points.len(), "{curve:?}: {with_closed}");
        for p in points {
            if let Some(d) = p.deviation() {
                assert!(d < 1e-5, "{curve:?} at κ = {}: {d}", p.kappa);
            }
        }
    }
    // The αβγ acceleration optimum: closed form = optimiser; on eq. 34's
    // surface; eq. 35's surface is always worse.
    for r in &out.abc {
        assert!((r.closed.3 - r.numeric.3).abs() <= 1e-9 * r.closed.3);
        assert!(r.on_eq34 <= r.closed.3 * (1.0 + 1e-9));
        assert!(r.on_eq35 > r.closed.3 * (1.0 + 1e-5), "κ = {}", r.kappa);
    }
    // Fig. 1: the interior optimum falls with κ; γ vanishes by κ = 10.
    let interior: Vec<_> = out
        .figure1
        .iter()
        .filter(|r| r.region() == "interior")
        .collect();
    assert!(interior.len() >= 15);
    assert!(interior
        .windows(2)
        .all(|w| w[1].alpha_beta.0 < w[0].alpha_beta.0 && w[1].alpha_beta.1 < w[0].alpha_beta.1));
    assert!(out
        .figure1
        .iter()
        .filter(|r| r.kappa >= 10.0)
        .all(|r| r.alpha_beta_gamma.2 < 1e-9));
    // The worked example, simulated: every prediction within two 95 %
    // half-widths of its simulated mean (at 40 runs a half-width is ≈ 1 %;
    // the committed 200 runs are within 1 %), and every perturbed gain
    // costs more than the optimum (paired 95 % intervals).
    assert_eq!(out.examples.len(), 2);
    for ex in &out.examples {
        for (c, s) in ex.candidates.iter().zip(&ex.simulated) {
            assert!(
                (c.predicted - s.mean).abs() <= 2.0 * s.half_width,
                "κ = {}, {}: predicted {} simulated {s:?}",
                ex.kappa,
                c.label,
                c.predicted
            );
        }
        for (c, d) in ex.candidates.iter().zip(&ex.excess) {
            if let Some(d) = d {
                assert!(d.lower() > 0.0, "κ = {}, {}: {d:?}", ex.kappa, c.label);
            }
        }
        // Benedict–Bordner's best is among the beaten.
        assert!(ex
            .candidates
            .iter()
            .any(|c| c.label.starts_with("Benedict")));
    }
    // The verdicts the summary reports (T8–T9 judge the simulation at the
    // committed run count, see above).
    let verdicts: Vec<(String, Verdict)> = tenne_singh::claims(&out)
        .into_iter()
        .map(|c| (c.id, c.verdict))
        .collect();
    let expected = [
        ("T1", Verdict::Reproduced),
        ("T2", Verdict::Reproduced),
        ("T3", Verdict::Reproduced),
        ("T4", Verdict::Reproduced),
        ("T5", Verdict::Partly),
        ("T6", Verdict::Partly),
        ("T7", Verdict::Partly),
    ];
    for (id, v) in expected {
        assert!(
            verdicts.contains(&(id.to_string(), v)),
            "{id}: {verdicts:?}"
        );
    }
}

// ---------------------------------------------------------------------------
// He et al. eq. (9) as printed

use abtrack_host_tests::experiments::he_tcas::{self, HeTcasConfig, Method, Quantity, Window};
use abtrack_host_tests::reference_ra::ReferenceRangeAzimuth;

#[test]
fn he_eq_9_as_printed_collapses_to_per_axis_gains() {
    // Deterministic: with VAR in eq. 9, α = W1 and β/T = W2 at every scan.
    let mut f = ReferenceRangeAzimuth::as_printed(100.0 * 100.0, 7.569e-3, 0.01);
    let (mut r, mut b) = (280_000.0, 0.52);
    for k in 0..300 {
        r -= 55.0 + 40.0 * ((k as f64) * 0.7).sin();
        b += 1e-4 * ((k as f64) * 1.3).cos();
        if let Some(step) = f.update(r, b, 1.0) {
            assert!((step.alpha - step.w1).abs() <= 1e-15 * step.w1.abs());
            assert!((step.beta - step.w2).abs() <= 1e-12 * step.w2.abs());
        }
    }
    // Statistically: its position error is the per-axis αβ filter's (M2),
    // and it is not better than the consistent reading.
    let out = he_tcas::simulate(&HeTcasConfig {
        numeric_types: false,
        yardstick: false,
        ..HeTcasConfig::with_runs(100)
    })
    .unwrap();
    let printed = out.method(Method::RangeAzimuthEq9AsPrinted).unwrap();
    let m2 = out.method(Method::AlphaBetaM2).unwrap();
    let ra = out.method(Method::RangeAzimuthF64).unwrap();
    for window in [Window::Overall, Window::Late] {
        let (d, _) = he_tcas::paired(printed, m2, window, Quantity::Position).unwrap();
        let scale = m2.ci(window, Quantity::Position).mean;
        assert!(
            d.lower() > -0.01 * scale && d.upper() < 0.01 * scale,
            "{window:?}: {d:?} of {scale}"
        );
    }
    let (d, _) = he_tcas::paired(printed, ra, Window::Overall, Quantity::Position).unwrap();
    assert!(d.lower() > 0.0, "{d:?}");
}

// ---------------------------------------------------------------------------
// Liu et al. 2.1.4, "the n scans before now"

use abtrack_host_tests::experiments::liu::{self, LiuResidualReference};
use abtrack_host_tests::experiments::monte_carlo::Scheduled;
use abtrack_host_tests::experiments::monte_carlo::{compare, Estimator, Metric};
use abtrack_host_tests::reference::LiuWindow;
use abtrack_host_tests::scenario;

#[test]
fn liu_reference_reproduces_the_library_reading_exactly() {
    // The reference with the current innovation included is the library's
    // `liu-residual` (f64): same gains, same estimates, on a scenario run.
    let run = scenario::generate("liu-turn", 7).unwrap();
    let mut library = Scheduled::<f64>::from_spec("liu-residual").unwrap();
    let mut reference = LiuResidualReference::new(LiuWindow::IncludingCurrent);
    let mut before = LiuResidualReference::new(LiuWindow::ExcludingCurrent);
    let mut differs = 0;
    for scan in &run.scans {
        let z = scan.measurements[0].position();
        let a = library.step(z, 2.0).unwrap();
        let b = reference.step(z, 2.0).unwrap();
        let c = before.step(z, 2.0).unwrap();
        for axis in 0..2 {
            assert!((a.position[axis] - b.position[axis]).abs() < 1e-9);
            assert!((a.velocity[axis] - b.velocity[axis]).abs() < 1e-9);
        }
        match (a.gains, b.gains) {
            (Some(ga), Some(gb)) => {
                for (x, y) in ga.iter().zip(&gb) {
                    assert!((x.0 - y.0).abs() < 1e-12 && (x.1 - y.1).abs() < 1e-12);
                }
            }
            (None, None) => {}
            other => panic!("gains {other:?}"),
        }
        if b.gains != c.gains {
            differs += 1;
        }
    }
    // The two windows really differ (all but the first filtered scan).
    assert_eq!(differs, run.scans.len() - 3);
}

#[test]
fn liu_before_now_window_is_better_straight_and_worse_in_the_turn() {
    let exp = liu::evaluate(Some(100)).unwrap();
    let seg = liu::Segments::new(&exp);
    let (straight, turn) = (seg.straight_segment(), seg.turn_segment());
    let d = Metric::PositionDistance;
    // Straight: the before-now window (current innovation left out) has the
    // lower error; in the turn the current-included one does.
    let c = compare(&exp, "", liu::RESIDUAL_BEFORE, liu::RESIDUAL, d, straight).unwrap();
    assert!(c.difference.lower() > 0.0, "{}", c.describe());
    let c = compare(&exp, "", liu::RESIDUAL, liu::RESIDUAL_BEFORE, d, turn).unwrap();
    assert!(c.difference.lower() > 0.0, "{}", c.describe());
    // In the turn it still beats the fixed gains by far (U3b, second part).
    let c = compare(&exp, "", liu::RESIDUAL_BEFORE, liu::FIXED, d, turn).unwrap();
    assert!(c.difference.lower() > 5.0, "{}", c.describe());
}

// ---------------------------------------------------------------------------
// Al-Wagih & Abdulla: which trajectory

use abtrack_host_tests::experiments::alwagih::{PAPER_TABLE_1, PAPER_TABLE_2};
use abtrack_host_tests::experiments::alwagih_trajectories::{
    distance, evaluate, fit_threshold, paper_means, paper_methods, Trajectory, ALL_METHODS,
    LINE_FIT_METHODS,
};

#[test]
fn alwagih_tables_fit_a_constant_acceleration_only_in_the_m2_m3_columns() {
    // The best fit of the committed search (results/alwagih/trajectories.md):
    // a = (0.042, 0.085) m/s², σ = 45 m.
    let methods = paper_methods().unwrap();
    let table1 = paper_means(&PAPER_TABLE_1);
    let ca = Trajectory::ConstantAcceleration {
        ax: 0.0425,
        ay: 0.085,
    };
    let cells = evaluate(&methods, &ca, 45.0, false, 40).unwrap();
    let line_limit = fit_threshold(&PAPER_TABLE_1, &LINE_FIT_METHODS);
    assert!(distance(&cells, &table1, &LINE_FIT_METHODS) <= line_limit);
    // All ten cells: far outside (M1, M4, M5 do not follow).
    assert!(
        distance(&cells, &table1, &ALL_METHODS) > 3.0 * fit_threshold(&PAPER_TABLE_1, &ALL_METHODS)
    );
    // A constant-velocity target cannot give M2/M3's errors at any σ: M2 is the least-squares line there, its errors are equal in
    // X and Y, and the paper's Y is about twice its X.
    for sigma in [5.0, 10.0, 20.0, 45.0, 63.0, 90.0] {
        let cv = evaluate(&methods, &Trajectory::ConstantVelocity, sigma, false, 20).unwrap();
        assert!(
            distance(&cv, &table1, &LINE_FIT_METHODS) > line_limit,
            "σ = {sigma}"
        );
    }
    // The thresholds are the paper's own scatter, not ours.
    assert!(fit_threshold(&PAPER_TABLE_2, &ALL_METHODS) > 0.1);
}
