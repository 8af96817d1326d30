//! The error budget (`abtrack::budget`) against measurement: f32 and fixed
//! point must stay within it over long runs (10 000 updates), at the corners
//! of the envelope (positions ±400 km, speeds 1500 m/s, accelerations
//! 200 m/s², intervals 0.05 s and 20 s, gains near the edges of the stability
//! regions) and, as property tests, anywhere in the envelope. The deviation is
//! measured against the independent f64 reference (src/reference.rs).

use abtrack::budget::{
    closed_loop_matrix, error_budget, error_budget_around_reference, error_budget_varying_gains,
    BudgetError, ErrorBound, GainSpread, RunEnvelope,
};
use abtrack::filter::{Gains, KinematicFilter};
use abtrack::{Fix, Scalar};
use abtrack_host_tests::precision::{
    documented_runs, measure, measure_documented, Deviation, EnvelopeTracker, RunReport,
};
use abtrack_host_tests::reference::{RefFilter, RefGains};
use abtrack_host_tests::trajectory::{generate, Motion, ScenarioSpec};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn within(report: &RunReport, what: &str) -> ErrorBound {
    let b = match report.budget {
        Ok(b) => b,
        Err(e) => panic!("{what}: no budget: {e}"),
    };
    assert_eq!(report.refused, 0, "{what}: updates refused");
    let d = &report.deviation;
    assert!(
        d.max[0] <= b.position && d.max[1] <= b.velocity && d.max[2] <= b.acceleration,
        "{what}: deviation {:?} exceeds budget {b:?}",
        d.max
    );
    b
}

fn ref_gains(alpha: f64, beta: f64, gamma: f64) -> RefGains {
    RefGains { alpha, beta, gamma }
}

// ------------------------------------------------------------ documented runs

/// The target: on every documented run the fast fixed point is at least ten
/// times closer to f64 than f32 is, in position, velocity and (αβγ)
/// acceleration.
#[test]
fn fast_fixed_point_is_ten_times_closer_than_f32() {
    for run in documented_runs() {
        let f32_max = measure_documented::<f32>(&run).unwrap().deviation.max;
        let fixed = measure_documented::<abtrack::Fixed32>(&run).unwrap();
        assert_eq!(fixed.refused, 0, "{}: updates refused", run.name);
        let components = if run.order == 3 { 3 } else { 2 };
        for (i, (f32_max, fixed_max)) in f32_max
            .iter()
            .zip(&fixed.deviation.max)
            .take(components)
            .enumerate()
        {
            let ratio = f32_max / fixed_max;
            assert!(
                ratio >= 10.0,
                "{} component {i}: only {ratio:.1} times closer than f32",
                run.name
            );
        }
    }
}

/// The runs the README quotes: within budget, and the budget is not vacuous
/// (at most 1000 times the measured maximum on every component).
#[test]
fn documented_runs_stay_within_budget() {
    for run in documented_runs() {
        assert_eq!(run.spec.steps, 10_000);
        for (name, report) in [
            ("f32", measure_documented::<f32>(&run).unwrap()),
            ("q32", measure_documented::<Fix>(&run).unwrap()),
            (
                "fixed",
                measure_documented::<abtrack::Fixed32>(&run).unwrap(),
            ),
        ] {
            let what = format!("{} {name}", run.name);
            let b = within(&report, &what);
            let d = &report.deviation;
            let components = if run.order == 3 { 3 } else { 2 };
            let bounds = [b.position, b.velocity, b.acceleration];
            for (bound, measured) in bounds.iter().zip(d.max).take(components) {
                assert!(measured > 0.0, "{what}: no deviation at all?");
                let ratio = bound / measured;
                assert!(
                    ratio < 1000.0,
                    "{what}: budget {ratio:.0} times the deviation"
                );
            }
            let rms = d.rms();
            println!(
                "{what}: max {:.2e}/{:.2e}/{:.2e} rms {:.2e}/{:.2e}/{:.2e} budget {:.2e}/{:.2e}/{:.2e}",
                d.max[0], d.max[1], d.max[2], rms[0], rms[1], rms[2], b.position, b.velocity,
                b.acceleration
            );
        }
    }
}

// -------------------------------------------------------------- the corners

const NEAR_EDGE_AB: [(f64, f64); 6] = [
    (0.5, 0.3),
    (1.99, 0.015),               // α → 2 and 2α + β → 4 (Al-Wagih eqs. 12, 14)
    (1.0, 1.99),                 // 2α + β = 3.99
    (0.5, 2.99),                 // 2α + β = 3.99
    (0.01, 5.0251256281407e-5),  // Benedict–Bordner α²/(2−α) at α = 0.01
    (0.001, 5.0025012506253e-7), // and at α = 0.001: β → 0 (eq. 13)
];

fn near_edge_abg() -> [(f64, f64, f64); 5] {
    let gamma_max = |a: f64, b: f64| 4.0 * a * b / (2.0 - a); // Tenne & Singh eq. 8
    [
        (0.5, 0.3, 0.1),
        (0.5, 0.3, 0.99 * gamma_max(0.5, 0.3)),
        (1.9, 0.19, 0.5),
        (1.0, 1.99, 0.5 * gamma_max(1.0, 1.99)),
        (0.05, 0.002, 0.0001),
    ]
}

/// Oscillating targets that reach 1500 m/s, up to 200 m/s² (less where the
/// interval is too long to follow them) and ±400 km, for 10 000 updates.
fn corner_spec(dt: f64, side: f64) -> ScenarioSpec {
    let omega = (200.0f64 / 1500.0).min(0.4 / dt);
    let amplitude = (1500.0 / omega).min(200.0 / (omega * omega));
    ScenarioSpec {
        steps: 10_000,
        dt: (dt, dt),
        coast_probability: 0.0,
        noise_sigma: 30.0,
        motion: Motion::Oscillation {
            centre: side * (400e3 - amplitude),
            amplitude,
            omega,
        },
    }
}

fn corners<S: Scalar>() {
    let mut seed = 100;
    for dt in [0.05, 1.0, 20.0] {
        for side in [-1.0, 1.0] {
            let steps = generate::<1>(seed, &corner_spec(dt, side));
            seed += 1;
            for (a, b) in NEAR_EDGE_AB {
                let r =
                    measure::<S, 1>(2, &ref_gains(a, b, 0.0), &steps, 0, &GainSpread::default());
                within(
                    &r.unwrap(),
                    &format!("{} ab {a} {b} dt {dt} side {side}", S::NAME),
                );
            }
            for (a, b, g) in near_edge_abg() {
                let r = measure::<S, 1>(3, &ref_gains(a, b, g), &steps, 0, &GainSpread::default());
                within(
                    &r.unwrap(),
                    &format!("{} abg {a} {b} {g} dt {dt} side {side}", S::NAME),
                );
            }
        }
    }
}

#[test]
fn f32_within_budget_at_the_corners() {
    corners::<f32>();
}

#[test]
fn fixed_within_budget_at_the_corners() {
    corners::<Fix>();
}

/// The 1500 m/s corner as a straight line across the whole position range.
#[test]
fn straight_line_across_the_range() {
    let spec = ScenarioSpec {
        steps: 10_000,
        dt: (0.05, 0.05),
        coast_probability: 0.0,
        noise_sigma: 1.0,
        motion: Motion::ConstantVelocity {
            start: 399e3,
            velocity: -1500.0,
        },
    };
    let steps = generate::<1>(7, &spec);
    for (a, b, g) in [(0.5, 0.3, 0.0), (0.2, 0.02, 0.0), (0.5, 0.3, 0.1)] {
        let order = if g > 0.0 { 3 } else { 2 };
        for r in [
            measure::<f32, 1>(
                order,
                &ref_gains(a, b, g),
                &steps,
                0,
                &GainSpread::default(),
            ),
            measure::<Fix, 1>(
                order,
                &ref_gains(a, b, g),
                &steps,
                0,
                &GainSpread::default(),
            ),
        ] {
            within(&r.unwrap(), &format!("line {a} {b} {g}"));
        }
    }
}

/// Interval jitter of ±30 % (well inside what the small-gain certificate
/// accepts for α = 0.5, β = 0.3) with random manoeuvres, 10 000 updates.
#[test]
fn jittered_interval_within_budget() {
    let spec = ScenarioSpec {
        steps: 10_000,
        dt: (0.7, 1.3),
        coast_probability: 0.0,
        noise_sigma: 30.0,
        motion: Motion::Manoeuvres {
            limit_position: 400e3,
            max_velocity: 1500.0,
            max_acceleration: 200.0,
            mean_segment: 20.0,
        },
    };
    let steps = generate::<1>(8, &spec);
    let g = ref_gains(0.5, 0.3, 0.0);
    within(
        &measure::<f32, 1>(2, &g, &steps, 0, &GainSpread::default()).unwrap(),
        "f32 jitter",
    );
    within(
        &measure::<Fix, 1>(2, &g, &steps, 0, &GainSpread::default()).unwrap(),
        "fixed jitter",
    );
}

// ------------------------------------------------------------ gain schedules

/// Gains redrawn at every update within nominal ± spread: the library gets the
/// gains per call, the reference the same values.
fn schedule_run<S: Scalar, const ORDER: usize>(seed: u64) {
    let nominal = ref_gains(0.5, 0.3, if ORDER == 3 { 0.1 } else { 0.0 });
    let spread = GainSpread {
        alpha: 0.05,
        beta: 0.03,
        gamma: if ORDER == 3 { 0.01 } else { 0.0 },
    };
    let spec = corner_spec(1.0, 1.0);
    let steps = generate::<1>(seed, &spec);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut lib = KinematicFilter::<S, ORDER>::new();
    let mut reference = RefFilter::new(ORDER);
    let mut dev = Deviation::default();
    let mut env = EnvelopeTracker::new();
    for (k, step) in steps.iter().enumerate() {
        let g = RefGains {
            alpha: nominal.alpha + spread.alpha * rng.random_range(-1.0..=1.0),
            beta: nominal.beta + spread.beta * rng.random_range(-1.0..=1.0),
            gamma: nominal.gamma + spread.gamma * rng.random_range(-1.0..=1.0),
        };
        let lib_g: Gains<S> = if ORDER == 3 {
            Gains::alpha_beta_gamma_f64(g.alpha, g.beta, g.gamma).unwrap()
        } else {
            Gains::alpha_beta_f64(g.alpha, g.beta).unwrap()
        };
        let z = step.z.unwrap()[0];
        let (_, v0, a0) = reference.state();
        let out = reference.update(z, step.dt, &g);
        if k >= 1 {
            env.interval(step.dt);
        }
        env.position(z);
        if let abtrack_host_tests::reference::RefStep::Filtered {
            predicted,
            innovation,
        } = out
        {
            env.position(predicted);
            env.residual(innovation);
            env.velocity(v0 + step.dt * a0);
        }
        let (x, v, a) = reference.state();
        env.position(x);
        env.velocity(v);
        env.acceleration(a);
        lib.update(
            S::try_from_f64(z).unwrap(),
            S::try_from_f64(step.dt).unwrap(),
            &lib_g,
        )
        .unwrap();
        dev.record([
            lib.position().to_f64() - x,
            lib.velocity().to_f64() - v,
            lib.acceleration().to_f64() - a,
        ]);
    }
    let nominal_g = if ORDER == 3 {
        Gains::alpha_beta_gamma(nominal.alpha, nominal.beta, nominal.gamma).unwrap()
    } else {
        Gains::alpha_beta(nominal.alpha, nominal.beta).unwrap()
    };
    let b =
        error_budget_around_reference::<S, ORDER>(&nominal_g, &spread, &env.envelope().unwrap())
            .unwrap();
    let fixed_gains = error_budget_around_reference::<S, ORDER>(
        &nominal_g,
        &GainSpread::default(),
        &env.envelope().unwrap(),
    )
    .unwrap();
    assert!(
        b.position > fixed_gains.position,
        "a spread must cost something"
    );
    assert!(
        dev.max[0] <= b.position && dev.max[1] <= b.velocity && dev.max[2] <= b.acceleration,
        "{} order {ORDER}: {:?} vs {b:?}",
        S::NAME,
        dev.max
    );
}

#[test]
fn gain_schedule_within_spread_budget() {
    schedule_run::<f32, 2>(31);
    schedule_run::<Fix, 2>(32);
    schedule_run::<f32, 3>(33);
    schedule_run::<Fix, 3>(34);
}

// ------------------------------------------------ the error dynamics

/// The budget's closed-loop matrix is the papers' filter: its characteristic
/// polynomial z³ − tr·z² + m₂·z − det (m₂ the sum of principal 2×2 minors)
/// must be the denominator of Tenne & Singh eq. (6),
/// z³ + (α+β+γ/4−3)z² + (−2α−β+γ/4+3)z + (α−1), and for αβ
/// z² − tr·z + det that of Al-Wagih eq. (11), z² + (α+β−2)z + (1−α).
#[test]
fn closed_loop_matrix_has_the_papers_characteristic_polynomial() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..200 {
        let alpha: f64 = rng.random_range(0.01..1.99);
        let beta = rng.random_range(0.01..0.99) * (4.0 - 2.0 * alpha);
        let gamma = rng.random_range(0.01..0.99) * 4.0 * alpha * beta / (2.0 - alpha);

        let m =
            closed_loop_matrix::<3>(&Gains::alpha_beta_gamma(alpha, beta, gamma).unwrap()).unwrap();
        let trace = m[0][0] + m[1][1] + m[2][2];
        let minor = |i: usize, j: usize| m[i][i] * m[j][j] - m[i][j] * m[j][i];
        let minors = minor(0, 1) + minor(0, 2) + minor(1, 2);
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(-trace, alpha + beta + gamma / 4.0 - 3.0));
        assert!(close(minors, -2.0 * alpha - beta + gamma / 4.0 + 3.0));
        assert!(close(-det, alpha - 1.0));

        let m = closed_loop_matrix::<2>(&Gains::alpha_beta(alpha, beta).unwrap()).unwrap();
        assert!(close(-(m[0][0] + m[1][1]), alpha + beta - 2.0));
        assert!(close(m[0][0] * m[1][1] - m[0][1] * m[1][0], 1.0 - alpha));
        assert_eq!(m[2], [0.0; 3]);
    }
}

// ------------------------------------------------- what the budget refuses

fn envelope() -> RunEnvelope {
    RunEnvelope {
        max_position: 400e3,
        max_velocity: 1500.0,
        max_acceleration: 200.0,
        max_residual: 1000.0,
        dt_min: 1.0,
        dt_max: 1.0,
    }
}

#[test]
fn refuses_invalid_envelopes_and_mismatched_gains() {
    let ab = Gains::alpha_beta(0.5, 0.3).unwrap();
    let abg = Gains::alpha_beta_gamma(0.5, 0.3, 0.1).unwrap();
    let bad = [
        RunEnvelope {
            dt_min: 0.0,
            ..envelope()
        },
        RunEnvelope {
            dt_min: 2.0,
            dt_max: 1.0,
            ..envelope()
        },
        RunEnvelope {
            max_position: -1.0,
            ..envelope()
        },
        RunEnvelope {
            max_residual: f64::NAN,
            ..envelope()
        },
        RunEnvelope {
            max_velocity: f64::INFINITY,
            ..envelope()
        },
    ];
    for env in bad {
        assert_eq!(
            error_budget::<f32, 2>(&ab, &env),
            Err(BudgetError::InvalidEnvelope),
            "{env:?}"
        );
    }
    let negative = GainSpread {
        alpha: -0.1,
        ..GainSpread::default()
    };
    assert_eq!(
        error_budget_varying_gains::<f32, 2>(&ab, &negative, &envelope()),
        Err(BudgetError::InvalidEnvelope)
    );
    assert_eq!(
        error_budget::<f32, 2>(&abg, &envelope()),
        Err(BudgetError::GainsDoNotMatchOrder)
    );
    assert_eq!(
        error_budget::<f32, 3>(&ab, &envelope()),
        Err(BudgetError::GainsDoNotMatchOrder)
    );
    assert_eq!(
        error_budget::<f32, 4>(&ab, &envelope()),
        Err(BudgetError::UnsupportedOrder)
    );
}

#[test]
fn refuses_runs_that_may_overflow() {
    let ab = Gains::alpha_beta(0.5, 0.3).unwrap();
    // Q32.32 holds ±2³¹ ≈ ±2.1e9.
    let far = RunEnvelope {
        max_position: 3e9,
        ..envelope()
    };
    assert_eq!(
        error_budget::<Fix, 2>(&ab, &far),
        Err(BudgetError::MayOverflow)
    );
    assert!(error_budget::<f32, 2>(&ab, &far).is_ok());
    // f32 overflows near 3.4e38.
    let huge = RunEnvelope {
        max_position: 1e38,
        max_velocity: 1e38,
        dt_max: 20.0,
        ..envelope()
    };
    assert_eq!(
        error_budget::<f32, 2>(&ab, &huge),
        Err(BudgetError::MayOverflow)
    );
}

/// The claim of num.rs: Q32.32 holds every intermediate of the envelope, the
/// largest being the velocity correction β·e/T with β < 4, |e| ≤ 800 km and
/// T ≥ 0.05 s (6.4·10⁷ < 2.1·10⁹).
#[test]
fn q32_32_holds_the_whole_envelope() {
    let worst = RunEnvelope {
        max_position: 400e3,
        max_velocity: 1500.0,
        max_acceleration: 200.0,
        max_residual: 800e3,
        dt_min: 0.05,
        dt_max: 0.05,
    };
    let steep = Gains::alpha_beta(0.001, 3.99).unwrap();
    let b = error_budget::<Fix, 2>(&steep, &worst).unwrap();
    assert!(b.position.is_finite());
    let abg = Gains::alpha_beta_gamma(1.0, 1.99, 7.9).unwrap();
    assert!(error_budget::<Fix, 3>(&abg, &worst).is_ok());
    let slow = RunEnvelope {
        dt_min: 20.0,
        dt_max: 20.0,
        ..worst
    };
    assert!(error_budget::<Fix, 3>(&abg, &slow).is_ok());
}

#[test]
fn refuses_gains_too_close_to_the_edge() {
    let creeping = Gains::alpha_beta(0.5, 1e-9).unwrap();
    assert_eq!(
        error_budget::<f32, 2>(&creeping, &envelope()),
        Err(BudgetError::SlowDecay)
    );
}

#[test]
fn refuses_interval_spreads_it_cannot_bound() {
    let ab = Gains::alpha_beta(0.5, 0.3).unwrap();
    let wide = RunEnvelope {
        dt_min: 0.05,
        dt_max: 20.0,
        ..envelope()
    };
    assert_eq!(
        error_budget::<f32, 2>(&ab, &wide),
        Err(BudgetError::NotContractive)
    );
    // Some spread is fine, and costs something.
    let jitter = RunEnvelope {
        dt_min: 0.9,
        dt_max: 1.1,
        ..envelope()
    };
    let with = error_budget::<f32, 2>(&ab, &jitter).unwrap();
    let without = error_budget::<f32, 2>(&ab, &envelope()).unwrap();
    assert!(with.position > without.position && with.velocity > without.velocity);
}

/// The budget follows the rounding model: f32 errors scale with the
/// magnitudes, Q32.32 errors are absolute, f64 is far below both; αβ has no
/// acceleration error.
#[test]
fn budget_scales_as_the_rounding_model_says() {
    let ab = Gains::alpha_beta(0.5, 0.3).unwrap();
    let near = RunEnvelope {
        max_position: 1e3,
        max_velocity: 15.0,
        max_acceleration: 2.0,
        ..envelope()
    };
    let far = envelope();
    let f32_near = error_budget::<f32, 2>(&ab, &near).unwrap();
    let f32_far = error_budget::<f32, 2>(&ab, &far).unwrap();
    let fix_near = error_budget::<Fix, 2>(&ab, &near).unwrap();
    let fix_far = error_budget::<Fix, 2>(&ab, &far).unwrap();
    let f64_far = error_budget::<f64, 2>(&ab, &far).unwrap();
    // 400 times the magnitudes: f32 budget grows by 100–400.
    let growth = f32_far.position / f32_near.position;
    assert!((100.0..=400.0).contains(&growth), "f32 growth {growth}");
    // Fixed point: the absolute resolution and the gain rounding (∝ residual,
    // the same here) dominate; only the f64 comparison term grows with the
    // position.
    let growth = fix_far.position / fix_near.position;
    assert!(growth < 5.0, "fixed growth {growth}");
    assert!(f64_far.position < 1e-6 * f32_far.position);
    assert_eq!(f32_far.acceleration, 0.0);
    // Zero spread is the fixed-gain budget.
    assert_eq!(
        error_budget_varying_gains::<f32, 2>(&ab, &GainSpread::default(), &far),
        Ok(f32_far)
    );
}

// ---------------------------------------------------------- property tests

#[derive(Debug, Clone)]
struct Case {
    gains: RefGains,
    order: usize,
    spec: ScenarioSpec,
    seed: u64,
}

/// Anywhere in the envelope: gains across the stability regions (fractions
/// 0.01–0.99 of each bound), intervals 0.05–20 s (half the cases with up to
/// ±5 % jitter), targets oscillating within ±400 km, ≤ 1500 m/s, ≤ 200 m/s²,
/// noise 0.01–300 m; 300 updates per case.
fn case(order: usize) -> impl Strategy<Value = Case> {
    (
        0.005f64..0.995,
        0.01f64..0.99,
        0.01f64..0.99,
        -1.3f64..1.301,
        prop_oneof![Just(0.0), 0.0f64..0.05],
        (-4.0f64..0.0, 0.01f64..1.0, -1.0f64..1.0),
        -2.0f64..2.5,
        any::<u64>(),
    )
        .prop_map(
            move |(fa, fb, fg, log_dt, jitter, (log_w, size, side), log_sigma, seed)| {
                let alpha = 2.0 * fa;
                let beta = fb * (4.0 - 2.0 * alpha);
                let gamma = if order == 3 {
                    fg * 4.0 * alpha * beta / (2.0 - alpha)
                } else {
                    0.0
                };
                let dt: f64 = 10f64.powf(log_dt).clamp(0.05, 20.0);
                let omega = 10f64.powf(log_w).min(200.0 / 1500.0).min(0.4 / dt);
                let amplitude = (1500.0 / omega).min(200.0 / (omega * omega)).min(400e3) * size;
                Case {
                    gains: RefGains { alpha, beta, gamma },
                    order,
                    spec: ScenarioSpec {
                        steps: 300,
                        dt: (dt * (1.0 - jitter), dt * (1.0 + jitter)),
                        coast_probability: 0.0,
                        noise_sigma: 10f64.powf(log_sigma),
                        motion: Motion::Oscillation {
                            centre: side * (400e3 - amplitude),
                            amplitude,
                            omega,
                        },
                    },
                    seed,
                }
            },
        )
}

/// Gains within 10 % of the stability region's edge (α, β or γ at ≥ 0.9 of
/// its bound), where the rounding errors' sum is amplified the most.
fn near_stability_edge(g: &RefGains, order: usize) -> bool {
    let beta_bound = 4.0 - 2.0 * g.alpha;
    let gamma_bound = 4.0 * g.alpha * g.beta / (2.0 - g.alpha);
    g.alpha >= 0.9 * 2.0
        || g.beta >= 0.9 * beta_bound
        || (order == 3 && g.gamma >= 0.9 * gamma_bound)
}

/// Within budget whenever the budget exists. It is refused only for gains
/// whose error dynamics decay too slowly to sum (`SlowDecay`), a jitter the
/// small-gain certificate cannot cover (`NotContractive`), or errors that
/// are not small against the run's magnitudes (`NotSelfConsistent`); those
/// cases are discarded (no claim is made for them). Anywhere else a refusal
/// fails the test. `NotSelfConsistent` was first found near the stability
/// edge only (α = 1.95 in f32), then also away from it on a run about the
/// origin ([`found_away_from_the_edge`]): it is a property of the run's
/// magnitudes as much as of the gains.
fn check_case<S: Scalar>(c: &Case) -> Result<(), TestCaseError> {
    let steps = generate::<1>(c.seed, &c.spec);
    let report = measure::<S, 1>(c.order, &c.gains, &steps, 0, &GainSpread::default())
        .map_err(TestCaseError::fail)?;
    let b = match report.budget {
        Ok(b) => b,
        Err(BudgetError::SlowDecay) => return Err(TestCaseError::reject("slow decay")),
        Err(BudgetError::NotContractive) if c.spec.dt.1 > c.spec.dt.0 => {
            return Err(TestCaseError::reject("jitter not certified"))
        }
        Err(BudgetError::NotSelfConsistent) => {
            let why = if near_stability_edge(&c.gains, c.order) {
                "errors not small, gains near the edge"
            } else {
                "errors not small against the run's magnitudes"
            };
            return Err(TestCaseError::reject(why));
        }
        Err(e) => return Err(TestCaseError::fail(format!("no budget: {e}"))),
    };
    prop_assert_eq!(report.refused, 0);
    let d = &report.deviation;
    prop_assert!(
        d.max[0] <= b.position && d.max[1] <= b.velocity && d.max[2] <= b.acceleration,
        "deviation {:?} > budget {:?}",
        d.max,
        b
    );
    Ok(())
}

/// The case proptest found in f32 αβγ with gains at 0.8 of α's bound and
/// below 0.45 of γ's (not near the edge) and a ±112.5 m oscillation about
/// the origin: the budget is refused as not self-consistent, and the
/// library makes no claim for it rather than a wrong one.
fn found_away_from_the_edge() -> Case {
    Case {
        gains: RefGains {
            alpha: 1.6002668040396026,
            beta: 0.5081350112087482,
            gamma: 3.3748730247927385,
        },
        order: 3,
        spec: ScenarioSpec {
            steps: 300,
            dt: (0.9703607225127778, 1.029639277487222),
            coast_probability: 0.0,
            noise_sigma: 1.0,
            motion: Motion::Oscillation {
                centre: 0.0,
                amplitude: 112.5,
                omega: 0.13333333333333333,
            },
        },
        seed: 8945066891977146129,
    }
}

#[test]
fn a_run_about_the_origin_gets_no_budget_rather_than_a_wrong_one() {
    let c = found_away_from_the_edge();
    assert!(!near_stability_edge(&c.gains, c.order));
    let steps = generate::<1>(c.seed, &c.spec);
    let report = measure::<f32, 1>(c.order, &c.gains, &steps, 0, &GainSpread::default()).unwrap();
    assert_eq!(report.refused, 0);
    match report.budget {
        Ok(b) => {
            let d = &report.deviation;
            assert!(d.max[0] <= b.position && d.max[1] <= b.velocity && d.max[2] <= b.acceleration);
        }
        Err(e) => assert_eq!(e, BudgetError::NotSelfConsistent),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, max_global_rejects: 100_000, ..ProptestConfig::default() })]

    #[test]
    fn f32_alpha_beta_within_budget(c in case(2)) { check_case::<f32>(&c)?; }

    #[test]
    fn fixed_alpha_beta_within_budget(c in case(2)) { check_case::<Fix>(&c)?; }

    #[test]
    fn f32_alpha_beta_gamma_within_budget(c in case(3)) { check_case::<f32>(&c)?; }

    #[test]
    fn fixed_alpha_beta_gamma_within_budget(c in case(3)) { check_case::<Fix>(&c)?; }
}
