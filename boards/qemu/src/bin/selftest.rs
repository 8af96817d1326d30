//! On-target self-test, first image: the filters, the gain schedules and the
//! M5 bank run on the emulated core itself, in the core's natural numeric
//! type (`board::Native`: `f32` on the Cortex-M4F, the fast fixed point
//! `Fixed32` on the Cortex-M3 and M0) against the same generic code in `f64`
//! (software floating point on all three cores). The TCAS inputs and the
//! track table are in the second image, `selftest-tracking` (both together
//! do not fit the micro:bit's 256 KiB of flash).
//!
//! The harness (`abtrack_firmware::selftest_support`): named test functions
//! returning `Result`, a line per test with its stack high-water mark, then
//! `N passed, M failed` alone on the last line; QEMU exits with status 1 if
//! any test failed (scripts/test.sh runs both images on the three boards).
//!
//! What is checked:
//! * native vs f64 on seeded pseudo-random trajectories, on the corners of the
//!   envelope (positions ±400 km, velocities ±1500 m/s, accelerations
//!   ±200 m/s², intervals 0.05 s and 20 s) and over a 10,000-update run, within
//!   the library's error budget ([`abtrack::budget`]), the deviation printed
//!   as a fraction of it;
//! * invalid inputs (invalid measurement, interval ≤ 0 or invalid) are refused
//!   with the right [`FilterError`] and leave the state bit-identical;
//! * gains outside the stability regions are refused with the right
//!   [`GainError`];
//! * an update or coast that overflows the representation is refused as
//!   [`FilterError::Saturated`], counted, and leaves the state otherwise
//!   untouched;
//! * two-point initialisation and the first filtered update against values
//!   computed by hand;
//! * a 2-D [`Cartesian`] filter is exactly its axes' one-axis filters;
//! * gain schedules (least squares, Liu's adaptive switch, Li's improved
//!   filter, M4, TCAS firmness) driving a 2-D filter through a manoeuvre: the
//!   same decisions as f64 and a deviation within a bound propagated from
//!   the library's budget ([`compare_schedule`] says why the budget alone
//!   cannot be used);
//! * the M5 bank: the same member selected as in f64 at every update, every
//!   member within the library's budget for its gains.
#![no_std]
#![no_main]

use abtrack_firmware::selftest_support as support;
use abtrack_firmware::{board, ensure, propagation, synth};

use abtrack::bank::{BankConfig, BankOutcome, CartesianBank};
use abtrack::budget::{error_budget_around_reference, BudgetError, ErrorBound, GainSpread};
use abtrack::filter::{
    Cartesian, FilterError, GainError, Gains, Innovation, KinematicFilter, Phase, UpdateOutcome,
};
use abtrack::gain::al_wagih::{LeastSquaresConfig, MovingWindowConfig};
use abtrack::gain::li::LiImprovedConfig;
use abtrack::gain::liu::AdaptiveSwitchConfig;
use abtrack::gain::{AnySchedule, ScheduleSpec, ScheduledFilter};
use abtrack::num::{Numeric, Quantity};
use abtrack::Fix;
use board::Native;
use propagation::{kinematic_prediction, kinematic_update, ErrorPropagation, Lag};
use support::{
    fixed_gain_budget, fixed_gain_budget_computed_gains, gain_values, merge, never, q, quantity,
    Bits, Failure, Magnitudes, Test, TestNumeric, TestResult,
};
use synth::Lcg;

const TESTS: &[Test] = &[
    (
        "two_point_initialisation_golden",
        two_point_initialisation_golden,
    ),
    (
        "invalid_inputs_refused_state_bit_identical",
        invalid_inputs_refused_state_bit_identical,
    ),
    ("unstable_gains_refused", unstable_gains_refused),
    (
        "saturation_reported_counted_state_untouched",
        saturation_reported_counted_state_untouched,
    ),
    (
        "cartesian_is_its_axes_bit_for_bit",
        cartesian_is_its_axes_bit_for_bit,
    ),
    (
        "native_vs_f64_random_trajectories_ab",
        native_vs_f64_random_trajectories_ab,
    ),
    (
        "native_vs_f64_random_trajectories_abg",
        native_vs_f64_random_trajectories_abg,
    ),
    (
        "native_vs_f64_envelope_corners",
        native_vs_f64_envelope_corners,
    ),
    (
        "native_vs_f64_long_run_10000_updates",
        native_vs_f64_long_run_10000_updates,
    ),
    (
        "schedule_least_squares_vs_f64",
        schedule_least_squares_vs_f64,
    ),
    ("schedule_liu_adaptive_vs_f64", schedule_liu_adaptive_vs_f64),
    ("schedule_li_improved_vs_f64", schedule_li_improved_vs_f64),
    (
        "schedule_m4_moving_window_vs_f64",
        schedule_m4_moving_window_vs_f64,
    ),
    (
        "schedule_tcas_firmness_vs_f64",
        schedule_tcas_firmness_vs_f64,
    ),
    ("bank_m5_vs_f64", bank_m5_vs_f64),
];

#[cortex_m_rt::entry]
fn main() -> ! {
    board::paint_stack();
    support::run("self-test (filters, gain schedules, M5 bank)", TESTS)
}

/// Everything observable of a one-axis filter, as bit patterns.
#[derive(PartialEq, Eq, Clone, Copy)]
struct Snapshot {
    phase: Phase,
    position: u64,
    velocity: u64,
    acceleration: u64,
    last: Option<(u64, u64)>,
    saturations: u32,
}

fn snapshot<S: TestNumeric, const ORDER: usize>(f: &KinematicFilter<S, ORDER>) -> Snapshot {
    Snapshot {
        phase: f.phase(),
        position: f.position().bits(),
        velocity: f.velocity().bits(),
        acceleration: f.acceleration().bits(),
        last: f
            .last_innovation()
            .map(|i| (i.predicted.bits(), i.residual.bits())),
        saturations: f.saturations(),
    }
}

/// Gains of the filter order: αβ for ORDER 2, αβγ for ORDER 3 (γ ignored for
/// αβ).
fn gains_for<S: TestNumeric, const ORDER: usize>(
    alpha: f64,
    beta: f64,
    gamma: f64,
) -> Result<Gains<S>, Failure> {
    let g = if ORDER == 3 {
        Gains::<S>::alpha_beta_gamma_f64(alpha, beta, gamma)
    } else {
        Gains::<S>::alpha_beta_f64(alpha, beta)
    };
    match g {
        Ok(g) => Ok(g),
        Err(e) => {
            defmt::error!(
                "{=str}: gains ({=f64}, {=f64}, {=f64}) refused: {}",
                S::NAME,
                alpha,
                beta,
                gamma,
                e
            );
            Err(Failure)
        }
    }
}

// ---------------------------------------------------------------------------
// Golden values
// ---------------------------------------------------------------------------

fn two_point_initialisation_golden() -> TestResult {
    golden::<Native, 2>()?;
    golden::<Native, 3>()?;
    golden::<f32, 2>()?;
    golden::<f32, 3>()?;
    golden::<Fix, 2>()?;
    golden::<Fix, 3>()?;
    golden::<f64, 2>()?;
    golden::<f64, 3>()
}

/// Two-point initialisation (Al-Wagih & Abdulla eqs. 9–10) and one filtered
/// update, by hand. Every number is exact in f32, Q32.32 and f64, so the
/// results must be equal, not merely close.
///
/// z₁ = 100 at t = 0; a coast of 1 s; z₂ = 130 one second later (T = 2 s
/// since z₁): x = 130, v = (130 − 100)/2 = 15 (eq. 9).
/// z₃ = 150 at T = 2 s, α = 0.5, β = 0.25, γ = 0.125:
///   x_p = 130 + 2·15 (+ ½·4·0 for αβγ) = 160, e = 150 − 160 = −10,
///   x = 160 + 0.5·(−10) = 155, v = 15 + 0.25·(−10)/2 = 13.75,
///   a = 0 + 0.125·(−10)/(2·2²) = −0.15625 (αβγ; 0 for αβ).
fn golden<S: TestNumeric, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.5, 0.25, 0.125)?;
    let mut f = KinematicFilter::<S, ORDER>::new();
    ensure!(
        f.phase() == Phase::Empty,
        "{=str}: new filter not empty",
        S::NAME
    );

    let first = f.update(q(100.0), q(1.0), &gains);
    ensure!(
        first == Ok(UpdateOutcome::FirstPoint) && f.phase() == Phase::OnePoint,
        "{=str}/{=usize}: first update: {}",
        S::NAME,
        ORDER,
        first
    );
    ensure!(
        f.position() == q(100.0) && f.velocity() == q(0.0),
        "{=str}/{=usize}: after z1: x={} v={}",
        S::NAME,
        ORDER,
        f.position(),
        f.velocity()
    );
    ensure!(f.coast(q(1.0)).is_ok(), "{=str}: coast refused", S::NAME);
    ensure!(
        f.position() == q(100.0) && f.phase() == Phase::OnePoint,
        "{=str}: coast before the second point moved the position",
        S::NAME
    );

    let second = f.update(q(130.0), q(1.0), &gains);
    ensure!(
        second == Ok(UpdateOutcome::SecondPoint) && f.phase() == Phase::Tracking,
        "{=str}/{=usize}: second update: {}",
        S::NAME,
        ORDER,
        second
    );
    ensure!(
        f.position() == q(130.0) && f.velocity() == q(15.0) && f.acceleration() == q(0.0),
        "{=str}/{=usize}: after z2: x={} v={} a={} (want 130, 15, 0)",
        S::NAME,
        ORDER,
        f.position(),
        f.velocity(),
        f.acceleration()
    );
    ensure!(
        f.last_innovation().is_none(),
        "{=str}: innovation before filtering",
        S::NAME
    );

    let third = f.update(q(150.0), q(2.0), &gains);
    let want_innovation = Innovation {
        predicted: q(160.0),
        residual: q(-10.0),
    };
    ensure!(
        third == Ok(UpdateOutcome::Filtered(want_innovation))
            && f.last_innovation() == Some(want_innovation),
        "{=str}/{=usize}: third update: {} (want predicted 160, residual -10)",
        S::NAME,
        ORDER,
        third
    );
    let want_acceleration = if ORDER == 3 { -0.15625 } else { 0.0 };
    ensure!(
        f.position() == q(155.0)
            && f.velocity() == q(13.75)
            && f.acceleration() == q(want_acceleration),
        "{=str}/{=usize}: after z3: x={} v={} a={} (want 155, 13.75, {=f64})",
        S::NAME,
        ORDER,
        f.position(),
        f.velocity(),
        f.acceleration(),
        want_acceleration
    );
    ensure!(f.saturations() == 0, "{=str}: saturations counted", S::NAME);
    Ok(())
}

// ---------------------------------------------------------------------------
// Invalid inputs
// ---------------------------------------------------------------------------

fn invalid_inputs_refused_state_bit_identical() -> TestResult {
    invalid_inputs::<f32, 2>()?;
    invalid_inputs::<f32, 3>()?;
    invalid_inputs::<Fix, 2>()?;
    invalid_inputs::<Fix, 3>()?;
    invalid_inputs::<f64, 2>()?;
    invalid_inputs::<f64, 3>()?;
    cartesian_invalid_inputs::<Native>()?;
    cartesian_invalid_inputs::<f64>()
}

/// Every refusal, in each phase of the filter (empty, one point, tracking).
/// "Invalid" is NaN or ±∞ for the floats and the saturation sentinels for
/// fixed point (what NaN and ±∞ convert to).
fn invalid_inputs<S: TestNumeric, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.5, 0.25, 0.125)?;
    let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
    let ok_z: S::Length = q(1234.5);
    let ok_dt: S::Interval = q(1.0);
    let update_cases = [
        (q(bad[0]), ok_dt, FilterError::InvalidMeasurement),
        (q(bad[1]), ok_dt, FilterError::InvalidMeasurement),
        (q(bad[2]), ok_dt, FilterError::InvalidMeasurement),
        (ok_z, q(0.0), FilterError::InvalidInterval),
        (ok_z, q(-1.0), FilterError::InvalidInterval),
        (ok_z, q(bad[0]), FilterError::InvalidInterval),
        (ok_z, q(bad[1]), FilterError::InvalidInterval),
        (ok_z, q(bad[2]), FilterError::InvalidInterval),
    ];
    let bad_intervals: [S::Interval; 5] = [q(0.0), q(-1.0), q(bad[0]), q(bad[1]), q(bad[2])];

    let mut f = KinematicFilter::<S, ORDER>::new();
    // Measurements that bring the filter through its phases (and give it a
    // residual to keep).
    let advance = [100.0, 130.0, 150.0];
    for (phase_index, z) in advance.iter().enumerate() {
        let before = f;
        let before_bits = snapshot(&f);
        for (i, (z_bad, dt_bad, want)) in update_cases.iter().enumerate() {
            let got = f.update(*z_bad, *dt_bad, &gains);
            ensure!(
                got == Err(*want),
                "{=str}/{=usize} phase {=usize} case {=usize}: got {}, want {}",
                S::NAME,
                ORDER,
                phase_index,
                i,
                got,
                want
            );
            ensure!(
                f == before && snapshot(&f) == before_bits,
                "{=str}/{=usize} phase {=usize} case {=usize}: refused update changed the state",
                S::NAME,
                ORDER,
                phase_index,
                i
            );
        }
        for (i, dt_bad) in bad_intervals.iter().enumerate() {
            let coast = f.coast(*dt_bad);
            let predict = f.predict(*dt_bad);
            ensure!(
                coast == Err(FilterError::InvalidInterval)
                    && predict.err() == Some(FilterError::InvalidInterval),
                "{=str}/{=usize} phase {=usize} interval {=usize}: coast {}, predict {}",
                S::NAME,
                ORDER,
                phase_index,
                i,
                coast,
                predict
            );
            ensure!(
                f == before && snapshot(&f) == before_bits,
                "{=str}/{=usize} phase {=usize} interval {=usize}: refused coast changed the state",
                S::NAME,
                ORDER,
                phase_index,
                i
            );
        }
        ensure!(
            f.update(q(*z), ok_dt, &gains).is_ok(),
            "{=str}: valid update refused",
            S::NAME
        );
    }
    ensure!(
        f.phase() == Phase::Tracking && f.last_innovation().is_some(),
        "{=str}: did not reach tracking",
        S::NAME
    );
    Ok(())
}

/// A 2-D update with one bad axis changes neither axis.
fn cartesian_invalid_inputs<S: TestNumeric>() -> TestResult {
    let gains = gains_for::<S, 2>(0.5, 0.25, 0.0)?;
    let mut f: Cartesian<S, 2, 2> = Cartesian::new();
    for (x, y) in [(0.0, 0.0), (10.0, 20.0), (21.0, 39.0)] {
        ensure!(
            f.update([q(x), q(y)], q(1.0), &gains).is_ok(),
            "{=str}: 2-D update refused",
            S::NAME
        );
    }
    let before = f;
    let got = f.update([q(30.0), q(f64::NAN)], q(1.0), &gains);
    ensure!(
        got.err() == Some(FilterError::InvalidMeasurement) && f == before,
        "{=str}: 2-D update with a NaN axis: {} (state changed: {=bool})",
        S::NAME,
        got.err(),
        f != before
    );
    let got = f.update([q(30.0), q(60.0)], q(0.0), &gains);
    ensure!(
        got.err() == Some(FilterError::InvalidInterval) && f == before,
        "{=str}: 2-D update with dt = 0: {}",
        S::NAME,
        got.err()
    );
    Ok(())
}

// ---------------------------------------------------------------------------
// Gains
// ---------------------------------------------------------------------------

fn unstable_gains_refused() -> TestResult {
    gain_checks::<f32>()?;
    gain_checks::<Fix>()?;
    gain_checks::<f64>()
}

/// The stability regions: αβ 0 < α < 2, β > 0, 2α + β < 4 (Al-Wagih &
/// Abdulla eqs. 12–14); αβγ adds 0 < γ < 4αβ/(2 − α) (Tenne & Singh eqs.
/// 7–8). The boundary cases use values exact in every type (1.5, 1.0, 0.375,
/// 0.5), so "on the boundary" is really on it.
fn gain_checks<S: TestNumeric>() -> TestResult {
    use GainError::*;
    let ab_cases: [(f64, f64, Result<(), GainError>); 11] = [
        (0.5, 0.25, Ok(())),
        (0.0, 0.1, Err(AlphaOutOfRange)),
        (-0.1, 0.1, Err(AlphaOutOfRange)),
        (2.0, 0.1, Err(AlphaOutOfRange)),
        (0.5, 0.0, Err(BetaNotPositive)),
        (0.5, -0.1, Err(BetaNotPositive)),
        (1.5, 1.0, Err(BetaTooLarge)), // 2α + β = 4 exactly
        (1.5, 0.999, Ok(())),
        (1.0, 2.5, Err(BetaTooLarge)),
        (f64::NAN, 0.1, Err(NotFinite)),
        (0.5, f64::INFINITY, Err(NotFinite)),
    ];
    for (i, (a, b, want)) in ab_cases.iter().enumerate() {
        let got = Gains::<S>::alpha_beta_f64(*a, *b).map(|_| ());
        ensure!(
            got == *want,
            "{=str}: alpha_beta case {=usize} ({=f64}, {=f64}): {}, want {}",
            S::NAME,
            i,
            *a,
            *b,
            got,
            want
        );
    }
    // 4αβ/(2 − α) at α = 0.5, β = 0.375 is exactly 0.5.
    let abg_cases: [(f64, f64, f64, Result<(), GainError>); 8] = [
        (0.5, 0.375, 0.49, Ok(())),
        (0.5, 0.375, 0.5, Err(GammaTooLarge)),
        (0.5, 0.375, 0.6, Err(GammaTooLarge)),
        (0.5, 0.375, 0.0, Err(GammaNotPositive)),
        (0.5, 0.375, -0.01, Err(GammaNotPositive)),
        (2.5, 0.375, 0.1, Err(AlphaOutOfRange)),
        (1.5, 1.0, 0.1, Err(BetaTooLarge)),
        (0.5, 0.375, f64::NAN, Err(NotFinite)),
    ];
    for (i, (a, b, g, want)) in abg_cases.iter().enumerate() {
        let got = Gains::<S>::alpha_beta_gamma_f64(*a, *b, *g).map(|_| ());
        ensure!(
            got == *want,
            "{=str}: alpha_beta_gamma case {=usize} ({=f64}, {=f64}, {=f64}): {}, want {}",
            S::NAME,
            i,
            *a,
            *b,
            *g,
            got,
            want
        );
    }
    // The same checks on values already in the representation: NaN (a
    // saturation sentinel for fixed point) is refused.
    let nan = q(f64::NAN);
    let half = q(0.5);
    let got = Gains::<S>::alpha_beta(nan, half).map(|_| ());
    ensure!(
        got == Err(NotFinite),
        "{=str}: alpha_beta(NaN, 0.5): {}",
        S::NAME,
        got
    );
    Ok(())
}

// ---------------------------------------------------------------------------
// Saturation
// ---------------------------------------------------------------------------

fn saturation_reported_counted_state_untouched() -> TestResult {
    saturation::<f32, 2>()?;
    saturation::<f32, 3>()?;
    saturation::<Fix, 2>()?;
    saturation::<Fix, 3>()?;
    saturation::<f64, 2>()?;
    saturation::<f64, 3>()?;
    cartesian_saturation::<Native>()
}

/// Everything but the saturation counter.
fn same_state_ignoring_counter(a: &Snapshot, b: &Snapshot) -> bool {
    Snapshot {
        saturations: 0,
        ..*a
    } == Snapshot {
        saturations: 0,
        ..*b
    }
}

/// A representable but huge measurement (1e9 m for Q32.32) makes β·e/T
/// overflow: refused as `Saturated`, counted, state otherwise untouched. Then
/// a coast whose extrapolation overflows, likewise.
fn saturation<S: TestNumeric, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.5, 0.25, 0.125)?;
    let dt = quantity(0.05)?;
    let huge = quantity(S::HUGE)?;
    let mut f = KinematicFilter::<S, ORDER>::new();
    for z in [0.0, 1.0, 2.0] {
        ensure!(
            f.update(q(z), dt, &gains).is_ok(),
            "{=str}: valid update refused",
            S::NAME
        );
    }
    let before = snapshot(&f);
    let got = f.update(huge, dt, &gains);
    let after = snapshot(&f);
    ensure!(
        got == Err(FilterError::Saturated),
        "{=str}/{=usize}: update with z = {=f64}: {}, want Saturated",
        S::NAME,
        ORDER,
        S::HUGE,
        got
    );
    ensure!(
        f.saturations() == 1 && same_state_ignoring_counter(&before, &after),
        "{=str}/{=usize}: saturation count {=u32} (want 1) or state changed",
        S::NAME,
        ORDER,
        f.saturations()
    );
    // The filter still works afterwards.
    ensure!(
        f.update(q(3.0), dt, &gains).is_ok(),
        "{=str}: update after a saturation refused",
        S::NAME
    );

    let [x0, v0, coast] = S::OVERFLOWING_COAST;
    let mut fast = match KinematicFilter::<S, ORDER>::from_state(q(x0), q(v0), q(0.0)) {
        Ok(f) => f,
        Err(e) => {
            defmt::error!("{=str}: from_state refused: {}", S::NAME, e);
            return Err(Failure);
        }
    };
    let before = snapshot(&fast);
    let got = fast.coast(q(coast));
    ensure!(
        got == Err(FilterError::Saturated)
            && fast.saturations() == 1
            && same_state_ignoring_counter(&before, &snapshot(&fast)),
        "{=str}/{=usize}: overflowing coast: {}, count {=u32}",
        S::NAME,
        ORDER,
        got,
        fast.saturations()
    );
    Ok(())
}

/// In 2-D a saturating update is counted once (on the first axis), and
/// neither axis moves.
fn cartesian_saturation<S: TestNumeric>() -> TestResult {
    let gains = gains_for::<S, 2>(0.5, 0.25, 0.0)?;
    let dt = quantity(0.05)?;
    let mut f: Cartesian<S, 2, 2> = Cartesian::new();
    for z in [0.0, 1.0, 2.0] {
        ensure!(
            f.update([q(z), q(z)], dt, &gains).is_ok(),
            "{=str}: 2-D update refused",
            S::NAME
        );
    }
    let before = f;
    let got = f.update([q(3.0), quantity(S::HUGE)?], dt, &gains);
    let x_same = same_state_ignoring_counter(&snapshot(&f.axes()[0]), &snapshot(&before.axes()[0]));
    let y_same = f.axes()[1] == before.axes()[1];
    ensure!(
        got.err() == Some(FilterError::Saturated)
            && x_same
            && y_same
            && f.axes()[0].saturations() == 1
            && f.saturations() == 1,
        "{=str}: 2-D saturation: {}, x same {=bool}, y same {=bool}, count {=u32}",
        S::NAME,
        got.err(),
        x_same,
        y_same,
        f.saturations()
    );
    Ok(())
}

// ---------------------------------------------------------------------------
// 2-D composition
// ---------------------------------------------------------------------------

fn cartesian_is_its_axes_bit_for_bit() -> TestResult {
    cartesian_vs_axes::<Native, 2>()?;
    cartesian_vs_axes::<Native, 3>()
}

fn cartesian_vs_axes<S: TestNumeric, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.6, 0.3, 0.05)?;
    let dt = quantity(0.5)?;
    let mut plane: Cartesian<S, ORDER, 2> = Cartesian::new();
    let mut x = KinematicFilter::<S, ORDER>::new();
    let mut y = KinematicFilter::<S, ORDER>::new();
    let mut rng = Lcg::new(0xc0ffee);
    for k in 0..200u32 {
        let t = k as f64 * 0.5;
        let zx = quantity(-3000.0 + 120.0 * t + rng.noise(20.0))?;
        let zy = quantity(5000.0 - 0.5 * t * t + rng.noise(20.0))?;
        let p = plane.update([zx, zy], dt, &gains);
        let a = x.update(zx, dt, &gains);
        let b = y.update(zy, dt, &gains);
        ensure!(
            p.is_ok() && a.is_ok() && b.is_ok(),
            "{=str}: update refused at k={=u32}",
            S::NAME,
            k
        );
        ensure!(
            snapshot(&plane.axes()[0]) == snapshot(&x)
                && snapshot(&plane.axes()[1]) == snapshot(&y),
            "{=str}/{=usize}: 2-D filter differs from its axes at k={=u32}",
            S::NAME,
            ORDER,
            k
        );
    }
    Ok(())
}
// ---------------------------------------------------------------------------
// Native vs f64, against the library's error budget
// ---------------------------------------------------------------------------

/// Worst deviations over the runs of one test, and how close they came to
/// their budgets.
#[derive(Default)]
struct Deviation {
    position: f64,
    velocity: f64,
    /// Largest deviation / budget ratio over every component and run.
    worst_ratio: f64,
    /// Largest residual the runs saw (m).
    residual: f64,
    updates: u32,
    runs: u32,
    /// Runs ended where the f64 run left the native envelope.
    left_envelope: u32,
}

impl Deviation {
    fn add(&mut self, worst: [f64; 3], bound: &ErrorBound, residual: f64, updates: u32) {
        self.position = self.position.max(worst[0]);
        self.velocity = self.velocity.max(worst[1]);
        let ratio = |d: f64, b: f64| if b > 0.0 { d / b } else { 0.0 };
        self.worst_ratio = self
            .worst_ratio
            .max(ratio(worst[0], bound.position))
            .max(ratio(worst[1], bound.velocity))
            .max(ratio(worst[2], bound.acceleration));
        self.residual = self.residual.max(residual);
        self.updates += updates;
        self.runs += 1;
    }

    fn report(&self, what: &str) {
        defmt::println!(
            "       {=str}: {=u32} runs, {=u32} updates, residuals up to {=f32} m: max |dx| {=f64} m, max |dv| {=f64} m/s; worst deviation = {=f32} of the budget; {=u32} runs ended where the f64 run left the {=str} envelope",
            what,
            self.runs,
            self.updates,
            self.residual as f32,
            self.position,
            self.velocity,
            self.worst_ratio as f32,
            self.left_envelope,
            what
        );
    }
}

/// How a comparison run starts.
#[derive(Clone, Copy)]
enum Start {
    /// Empty: two-point initialisation from the first measurements.
    Empty,
    /// Already tracking (position, velocity, acceleration).
    State(f64, f64, f64),
}

/// Runs the same measurements through the filter in `S` and in f64 and checks
/// the largest differences against the library's error budget for the run
/// ([`fixed_gain_budget`]); both must also accept or refuse the same updates.
fn compare_run<S: TestNumeric, const ORDER: usize>(
    gains: GainValues,
    dt: f64,
    start: Start,
    updates: u32,
    mut measurement: impl FnMut(u32) -> f64,
    deviation: &mut Deviation,
) -> TestResult {
    let gains_s = gains_for::<S, ORDER>(gains.alpha, gains.beta, gains.gamma)?;
    let gains_64 = gains_for::<f64, ORDER>(gains.alpha, gains.beta, gains.gamma)?;
    let dt_s = quantity(dt)?;
    let mut m = Magnitudes::default();
    let (mut fs, mut f64f) = match start {
        Start::Empty => (
            KinematicFilter::<S, ORDER>::new(),
            KinematicFilter::<f64, ORDER>::new(),
        ),
        Start::State(p, v, a) => {
            let s =
                KinematicFilter::<S, ORDER>::from_state(quantity(p)?, quantity(v)?, quantity(a)?);
            let r = KinematicFilter::<f64, ORDER>::from_state(p, v, a);
            match (s, r) {
                (Ok(s), Ok(r)) => (s, r),
                _ => {
                    defmt::error!("{=str}: from_state refused", S::NAME);
                    return Err(Failure);
                }
            }
        }
    };
    let mut worst = [0.0f64; 3];
    let mut worst_step = [0u32; 3];
    for k in 0..updates {
        let z = measurement(k);
        let zs = quantity(z)?;
        let before = (f64f.position(), f64f.velocity(), f64f.acceleration());
        let got_s = fs.update(zs, dt_s, &gains_s);
        let got_64 = f64f.update(z, dt, &gains_64);
        // Where the f64 run leaves the native number system's envelope
        // (its estimates beyond the native formats' ranges, e.g. an
        // oscillating filter with near-edge random gains), the native run
        // refuses the update as saturated, as it must; the comparison ends
        // there.
        let (predicted, residual) = f64f
            .last_innovation()
            .map_or((0.0, 0.0), |i| (i.predicted, i.residual));
        let left_envelope = libm::fabs(f64f.velocity()) > S::SPEED_LIMIT
            || libm::fabs(f64f.acceleration()) > S::ACCELERATION_LIMIT
            || libm::fabs(f64f.position()) > S::RESIDUAL_LIMIT
            || libm::fabs(predicted) > S::RESIDUAL_LIMIT
            || libm::fabs(residual) > S::RESIDUAL_LIMIT
            || libm::fabs(z - before.0) > S::RESIDUAL_LIMIT;
        if got_s == Err(FilterError::Saturated) && got_64.is_ok() && left_envelope {
            deviation.left_envelope += 1;
            break;
        }
        ensure!(
            got_s.is_ok() == got_64.is_ok(),
            "{=str}/{=usize} k={=u32} z={=f64} T={=f64}: native {}, f64 {} (f64 state before {=f64} {=f64} {=f64}, after {=f64} {=f64} {=f64}, gains {=f64} {=f64} {=f64})",
            S::NAME,
            ORDER,
            k,
            z,
            dt,
            got_s.err(),
            got_64.err(),
            before.0,
            before.1,
            before.2,
            f64f.position(),
            f64f.velocity(),
            f64f.acceleration(),
            gains.alpha,
            gains.beta,
            gains.gamma
        );
        m.record(z, dt, before, &f64f);
        let d = [
            libm::fabs(fs.position().to_f64() - f64f.position()),
            libm::fabs(fs.velocity().to_f64() - f64f.velocity()),
            libm::fabs(fs.acceleration().to_f64() - f64f.acceleration()),
        ];
        for i in 0..3 {
            if d[i] > worst[i] {
                worst[i] = d[i];
                worst_step[i] = k;
            }
        }
    }
    // The budget holds at every update of a run whose magnitudes stay in the
    // envelope, so the one for the whole run's envelope covers every step.
    let bound = fixed_gain_budget::<S, ORDER>(&gains_64, &m.envelope(dt, dt))?;
    ensure!(
        bound.covers(worst[0], worst[1], worst[2]),
        "{=str}/{=usize} T={=f64} gains ({=f64}, {=f64}, {=f64}): max |dx| {=f64} at k={=u32} (budget {=f64}), max |dv| {=f64} at k={=u32} (budget {=f64}), max |da| {=f64} at k={=u32} (budget {=f64})",
        S::NAME,
        ORDER,
        dt,
        gains.alpha,
        gains.beta,
        gains.gamma,
        worst[0],
        worst_step[0],
        bound.position,
        worst[1],
        worst_step[1],
        bound.velocity,
        worst[2],
        worst_step[2],
        bound.acceleration
    );
    deviation.add(worst, &bound, m.residual, updates);
    Ok(())
}

/// Gains as plain numbers.
#[derive(Clone, Copy)]
struct GainValues {
    alpha: f64,
    beta: f64,
    /// 0 for αβ.
    gamma: f64,
}

const MAX_POSITION: f64 = 400_000.0;
const MAX_VELOCITY: f64 = 1_500.0;
const MAX_ACCELERATION: f64 = 200.0;
const MIN_INTERVAL: f64 = 0.05;
const MAX_INTERVAL: f64 = 20.0;

/// A target moving on one axis inside the envelope: piecewise-constant
/// acceleration (redrawn on one scan in eight), velocity clipped to
/// ±1500 m/s, reflected at ±400 km; measured with bounded noise and clipped
/// to the envelope.
struct RandomTarget {
    rng: Lcg,
    position: f64,
    velocity: f64,
    acceleration: f64,
    dt: f64,
    noise_sigma: f64,
    reverse_at_walls: bool,
    /// 1, or less where the filter's lag a·T²/β would leave `S`'s residual
    /// envelope.
    acceleration_scale: f64,
}

/// The fraction of the ±200 m/s² envelope the target may use so that the
/// filter stays inside `S`'s envelope: its steady lag a·T²/β (Al-Wagih
/// eq. 19's acceleration error) within a quarter of the residual limit, and
/// the velocity correction of a manoeuvre's residual, (β/T)·(a·T²/2), within
/// a quarter of the speed headroom above 1500 m/s, and a·T within half of
/// it. 1 for floats and Q32.32.
fn acceleration_scale<S: TestNumeric>(gains: GainValues, dt: f64) -> f64 {
    let lag = S::RESIDUAL_LIMIT * gains.beta / (4.0 * dt * dt);
    let correction = (S::SPEED_LIMIT - MAX_VELOCITY) * 2.0 / (4.0 * gains.beta * dt);
    // And the target's own velocity change per interval within half the
    // headroom, so an estimate's overshoot after it stays in range.
    let step = (S::SPEED_LIMIT - MAX_VELOCITY) / (2.0 * dt);
    (lag.min(correction).min(step) / MAX_ACCELERATION).min(1.0)
}

/// The largest measurement noise σ for which `S`'s estimates stay inside its
/// envelope with the given gains and interval: a residual e moves the
/// velocity by (β/T)·e and the acceleration by γ/(2T²)·e, and an 8σ
/// residual must leave the speed and acceleration limits above the
/// target's own 1500 m/s and 200 m/s². Infinite for floats and Q32.32.
fn noise_cap<S: TestNumeric>(gains: GainValues, dt: f64) -> f64 {
    let speed = (S::SPEED_LIMIT - MAX_VELOCITY) * dt / (8.0 * gains.beta.max(1.0));
    let acceleration = if gains.gamma > 0.0 {
        (S::ACCELERATION_LIMIT - MAX_ACCELERATION) * 2.0 * dt * dt / (8.0 * gains.gamma)
    } else {
        f64::INFINITY
    };
    speed.min(acceleration)
}

impl RandomTarget {
    /// A target for the native number system `S` with gains `gains`: the
    /// noise is capped so that the filter's estimates stay inside `S`'s
    /// envelope ([`noise_cap`]), and where `S` has a finite speed range the
    /// target stops at the ±400 km walls instead of reversing (an instant
    /// 3000 m/s reversal is outside the 200 m/s² envelope, and the
    /// estimates' overshoot after it leaves a ±2048 m/s speed format).
    fn new<S: TestNumeric>(rng: &mut Lcg, dt: f64, gains: GainValues) -> Self {
        RandomTarget {
            rng: Lcg::new(rng.next_u32() as u64 | (rng.next_u32() as u64) << 32),
            position: rng.uniform(-0.9 * MAX_POSITION, 0.9 * MAX_POSITION),
            velocity: rng.uniform(-MAX_VELOCITY, MAX_VELOCITY),
            acceleration: rng.uniform(-MAX_ACCELERATION, MAX_ACCELERATION)
                * acceleration_scale::<S>(gains, dt),
            acceleration_scale: acceleration_scale::<S>(gains, dt),
            dt,
            noise_sigma: rng.uniform(1.0, 150.0).min(noise_cap::<S>(gains, dt)),
            reverse_at_walls: S::SPEED_LIMIT.is_infinite(),
        }
    }

    fn next_measurement(&mut self) -> f64 {
        if self.rng.index(8) == 0 {
            self.acceleration =
                self.rng.uniform(-MAX_ACCELERATION, MAX_ACCELERATION) * self.acceleration_scale;
        }
        self.velocity =
            (self.velocity + self.acceleration * self.dt).clamp(-MAX_VELOCITY, MAX_VELOCITY);
        self.position += self.velocity * self.dt;
        if self.position > MAX_POSITION {
            self.position = 2.0 * MAX_POSITION - self.position;
            self.velocity = if self.reverse_at_walls {
                -self.velocity
            } else {
                0.0
            };
        } else if self.position < -MAX_POSITION {
            self.position = -2.0 * MAX_POSITION - self.position;
            self.velocity = if self.reverse_at_walls {
                -self.velocity
            } else {
                0.0
            };
        }
        (self.position + self.rng.noise(self.noise_sigma)).clamp(-MAX_POSITION, MAX_POSITION)
    }
}

/// Random gains strictly inside the stability region (between 2 % and 90 % of
/// each allowed range), γ = 0 for αβ.
fn random_gains(rng: &mut Lcg, order: usize) -> GainValues {
    let alpha = rng.uniform(0.02, 1.8);
    let beta = (4.0 - 2.0 * alpha) * rng.uniform(0.02, 0.9);
    let gamma = if order == 3 {
        4.0 * alpha * beta / (2.0 - alpha) * rng.uniform(0.02, 0.9)
    } else {
        0.0
    };
    GainValues { alpha, beta, gamma }
}

/// Log-uniform interval in [0.05 s, 20 s]; the first two runs take the ends.
fn random_interval(rng: &mut Lcg, run: u32) -> f64 {
    match run {
        0 => MIN_INTERVAL,
        1 => MAX_INTERVAL,
        _ => MIN_INTERVAL * libm::pow(MAX_INTERVAL / MIN_INTERVAL, rng.unit()),
    }
}

fn random_trajectories<const ORDER: usize>(seed: u64) -> TestResult {
    const RUNS: u32 = 16;
    const UPDATES: u32 = 300;
    let mut rng = Lcg::new(seed);
    let mut deviation = Deviation::default();
    for run in 0..RUNS {
        let gains = random_gains(&mut rng, ORDER);
        let dt = random_interval(&mut rng, run);
        let mut target = RandomTarget::new::<Native>(&mut rng, dt, gains);
        compare_run::<Native, ORDER>(
            gains,
            dt,
            Start::Empty,
            UPDATES,
            |_| target.next_measurement(),
            &mut deviation,
        )?;
    }
    deviation.report(Native::NAME);
    Ok(())
}

fn native_vs_f64_random_trajectories_ab() -> TestResult {
    random_trajectories::<2>(0x5eed_0ab0)
}

fn native_vs_f64_random_trajectories_abg() -> TestResult {
    random_trajectories::<3>(0x5eed_0ab9)
}

/// Every corner of the envelope (position ±400 km, velocity ±1500 m/s,
/// acceleration ±200 m/s², interval 0.05 s or 20 s) as the starting state,
/// for a mid-range, a slow and a fast gain set. The measurements follow the
/// corner's constant-acceleration path clipped to ±400 km (so the filter
/// sees the envelope's largest residuals), and the last one is the opposite
/// edge, −p: a residual of about 800 km.
fn native_vs_f64_envelope_corners() -> TestResult {
    const STEPS: u32 = 6;
    let gain_sets = [
        GainValues {
            alpha: 0.5,
            beta: 0.3,
            gamma: 0.05,
        },
        GainValues {
            alpha: 0.05,
            beta: 0.05 * 0.05 / 1.95,
            gamma: 0.0001,
        },
        GainValues {
            alpha: 1.8,
            beta: 0.35,
            gamma: 0.5,
        },
    ];
    let mut deviation = Deviation::default();
    let mut skipped = 0u32;
    for gains in gain_sets {
        for corner in 0..16u32 {
            let sign = |bit: u32| if corner & (1 << bit) == 0 { 1.0 } else { -1.0 };
            let p = sign(0) * MAX_POSITION;
            let v = sign(1) * MAX_VELOCITY;
            let a = sign(2) * MAX_ACCELERATION;
            let dt = if corner & 8 == 0 {
                MIN_INTERVAL
            } else {
                MAX_INTERVAL
            };
            // A corner whose predicted velocity (v + a·T) or position
            // (x + (v + 2aT)·T) is outside the native number system's
            // envelope is not run; the final jump goes to −p, or to 0 where
            // an 800 km residual is outside it (docs/numerics-fixed-point.md).
            let reach = MAX_POSITION + (MAX_VELOCITY + 2.0 * MAX_ACCELERATION * dt) * dt;
            if MAX_VELOCITY + MAX_ACCELERATION * dt > Native::SPEED_LIMIT
                || reach > Native::RESIDUAL_LIMIT
            {
                skipped += 1;
                continue;
            }
            let far = if 2.0 * MAX_POSITION <= Native::RESIDUAL_LIMIT {
                -p
            } else {
                0.0
            };
            let path = |k: u32| {
                if k + 1 == STEPS {
                    far
                } else {
                    let t = (k + 1) as f64 * dt;
                    (p + v * t + 0.5 * a * t * t).clamp(-MAX_POSITION, MAX_POSITION)
                }
            };
            compare_run::<Native, 2>(
                gains,
                dt,
                Start::State(p, v, 0.0),
                STEPS,
                path,
                &mut deviation,
            )?;
            compare_run::<Native, 3>(
                gains,
                dt,
                Start::State(p, v, a),
                STEPS,
                path,
                &mut deviation,
            )?;
        }
    }
    deviation.report(Native::NAME);
    defmt::println!(
        "       {=u32} corners outside the {=str} envelope not run",
        skipped,
        Native::NAME
    );
    Ok(())
}

/// 10,000 updates of each filter on one long random trajectory at T = 1 s.
fn native_vs_f64_long_run_10000_updates() -> TestResult {
    const UPDATES: u32 = 10_000;
    let mut deviation = Deviation::default();
    let mut rng = Lcg::new(0x10_0000);
    let ab = GainValues {
        alpha: 0.5,
        beta: 0.5 * 0.5 / 1.5,
        gamma: 0.0,
    };
    let mut target = RandomTarget::new::<Native>(&mut rng, 1.0, ab);
    compare_run::<Native, 2>(
        ab,
        1.0,
        Start::Empty,
        UPDATES,
        |_| target.next_measurement(),
        &mut deviation,
    )?;
    let abg = GainValues {
        alpha: 0.657,
        beta: 0.2295,
        gamma: 0.054,
    };
    let mut target = RandomTarget::new::<Native>(&mut rng, 1.0, abg);
    compare_run::<Native, 3>(
        abg,
        1.0,
        Start::Empty,
        UPDATES,
        |_| target.next_measurement(),
        &mut deviation,
    )?;
    deviation.report(Native::NAME);
    Ok(())
}

// ---------------------------------------------------------------------------
// Gain schedules driving the filter, and the M5 bank
// ---------------------------------------------------------------------------

/// Window capacity of the schedules that keep one (M3, M4, Liu's residual
/// accumulation); their defaults use 3 to 8.
const SCHEDULE_WINDOW: usize = 8;

type Schedule<S> = AnySchedule<S, 2, SCHEDULE_WINDOW>;
type ScheduledTrack<S, const ORDER: usize> = ScheduledFilter<S, Schedule<S>, ORDER, 2>;

/// Lags kept exactly by the error propagation of the schedule runs: with
/// the gains these runs reach (α ≥ 0.04) the closed loop forgets an error by
/// e⁻¹ within about 25 steps (`abtrack_firmware::propagation`).
const SCHEDULE_LAGS: usize = 32;

/// A target in the plane for the schedule and bank tests, after Liu, Wang &
/// Yang's turn scenario (start (533, 389) m, 150 m/s at heading 45°, 30 scans
/// straight, a 9000 m radius turn for 15 scans of 2 s, then straight; σ = 5 m
/// per axis): every schedule sees a steady stretch and a manoeuvre.
/// `miss(k)` drops scan k (the track coasts).
#[derive(Clone, Copy)]
struct PlaneScenario {
    target: synth::TurningTarget,
    turn_end: f64,
    dt: f64,
    scans: u32,
    noise_sigma: f64,
    seed: u64,
    miss: fn(u32) -> bool,
}

impl PlaneScenario {
    fn liu_turn(dt: f64, scans: u32, seed: u64, miss: fn(u32) -> bool) -> Self {
        let speed = 150.0;
        let (s, c) = libm::sincos(core::f64::consts::FRAC_PI_4);
        PlaneScenario {
            target: synth::TurningTarget {
                start: [533.0, 389.0],
                velocity: [speed * c, speed * s],
                turn_start: 60.0,
                turn_rate: -speed / 9000.0,
            },
            turn_end: 90.0,
            dt,
            scans,
            noise_sigma: 5.0,
            seed,
            miss,
        }
    }

    /// The truth at time t: straight, the turn from `turn_start` to
    /// `turn_end`, straight again.
    fn truth(&self, t: f64) -> [f64; 2] {
        let turned = self.target.at(t.min(self.turn_end));
        let after = (t - self.turn_end).max(0.0);
        [
            turned.position[0] + turned.velocity[0] * after,
            turned.position[1] + turned.velocity[1] * after,
        ]
    }

    /// Scan k's measurement, `None` for a missed scan; the same sequence on
    /// every call.
    fn measurements(&self) -> impl Iterator<Item = Option<[f64; 2]>> + '_ {
        let mut rng = Lcg::new(self.seed);
        (0..self.scans).map(move |k| {
            let p = self.truth(k as f64 * self.dt);
            let z = [
                p[0] + rng.noise(self.noise_sigma),
                p[1] + rng.noise(self.noise_sigma),
            ];
            if (self.miss)(k) {
                None
            } else {
                Some(z)
            }
        })
    }
}

/// What a step did to one axis.
#[derive(Clone, Copy, PartialEq, Eq, defmt::Format)]
enum StepKind {
    /// Two-point initialisation, first or second point (also a restart).
    Initialisation,
    Filtered,
    Coast,
}

/// What one scan did to one axis in the two runs (coast: no gains, no
/// residual).
#[derive(Clone, Copy)]
struct AxisScan {
    kind: StepKind,
    gains_64: [f64; 3],
    gains_s: [f64; 3],
    /// The larger |residual| and |prediction| of the two runs.
    residual: f64,
    predicted: f64,
    z_abs: f64,
}

impl AxisScan {
    const COAST: Self = AxisScan {
        kind: StepKind::Coast,
        gains_64: [0.0; 3],
        gains_s: [0.0; 3],
        residual: 0.0,
        predicted: 0.0,
        z_abs: 0.0,
    };
}

/// One step of a run in both representations, for one axis.
#[derive(Clone, Copy)]
struct PairStep {
    kind: StepKind,
    dt: f64,
    /// Gains (α, β, γ) the f64 and the native run used (zero when none).
    gains_64: [f64; 3],
    gains_s: [f64; 3],
    /// The larger |residual| of the two runs (0 when none).
    residual: f64,
    /// |native − f64| of (x, v, a) after the step.
    deviation: [f64; 3],
}

fn axis_state<S: Numeric, const ORDER: usize>(f: &KinematicFilter<S, ORDER>) -> [f64; 3] {
    [
        f.position().to_f64(),
        f.velocity().to_f64(),
        f.acceleration().to_f64(),
    ]
}

fn step_kind<S: Numeric>(o: &UpdateOutcome<S>) -> StepKind {
    match o {
        UpdateOutcome::Filtered(_) => StepKind::Filtered,
        _ => StepKind::Initialisation,
    }
}

/// The schedule `spec` names, built from the typed configuration: parsing a
/// spec string on the target would link core's `f64::from_str`, which has
/// panic paths (docs/safety.md).
fn schedule_for<S: Numeric>(spec: &ScheduleSpec) -> Result<Schedule<S>, Failure> {
    match Schedule::<S>::from_spec(spec) {
        Ok(s) => Ok(s),
        Err(e) => {
            defmt::error!("{=str}: schedule {} refused: {}", S::NAME, spec, e);
            Err(Failure)
        }
    }
}

/// Runs `spec` on `scenario` in `S` and in f64, calling `visit(k, axis,
/// step, magnitudes)` for every scan and axis; the two runs must accept,
/// refuse and restart alike.
fn run_schedule<S: TestNumeric, const ORDER: usize>(
    spec: &ScheduleSpec,
    scenario: &PlaneScenario,
    mut visit: impl FnMut(u32, usize, &PairStep, &Magnitudes) -> TestResult,
) -> TestResult {
    let mut ts = ScheduledTrack::<S, ORDER>::new(schedule_for::<S>(spec)?);
    let mut tf = ScheduledTrack::<f64, ORDER>::new(schedule_for::<f64>(spec)?);
    let dt = scenario.dt;
    let dt_s = quantity(dt)?;
    for (k, z) in (0u32..).zip(scenario.measurements()) {
        let before_s = ts.filter().axes().map(|a| axis_state(&a));
        let before_64 = tf.filter().axes().map(|a| axis_state(&a));
        let mut scans = [AxisScan::COAST; 2];
        match z {
            Some(z) => {
                let [z_x, z_y] = z;
                let zs = [quantity(z_x)?, quantity(z_y)?];
                let (us, uf) = match (ts.update(zs, dt_s), tf.update(z, dt)) {
                    (Ok(us), Ok(uf)) => (us, uf),
                    (a, b) => {
                        defmt::error!(
                            "{=str} {} scan {=u32}: native {}, f64 {}",
                            S::NAME,
                            spec,
                            k,
                            a.err(),
                            b.err()
                        );
                        return Err(Failure);
                    }
                };
                ensure!(
                    us.restarted == uf.restarted,
                    "{=str} {} scan {=u32}: restart differs",
                    S::NAME,
                    spec,
                    k
                );
                let gains = us.gains.zip(uf.gains);
                let outcomes = us.outcome.into_iter().zip(uf.outcome);
                for (i, ((scan, (os, of)), z)) in scans.iter_mut().zip(outcomes).zip(z).enumerate()
                {
                    scan.kind = step_kind(&of);
                    ensure!(
                        step_kind(&os) == scan.kind,
                        "{=str} {} scan {=u32}: native {}, f64 {}",
                        S::NAME,
                        spec,
                        k,
                        os,
                        of
                    );
                    if let (UpdateOutcome::Filtered(a), UpdateOutcome::Filtered(b)) = (os, of) {
                        scan.residual = libm::fabs(a.residual.to_f64()).max(libm::fabs(b.residual));
                        scan.predicted =
                            libm::fabs(a.predicted.to_f64()).max(libm::fabs(b.predicted));
                    }
                    if let Some((Some(gs), Some(gf))) =
                        gains.as_ref().map(|(gs, gf)| (gs.get(i), gf.get(i)))
                    {
                        scan.gains_s = gain_values(gs);
                        scan.gains_64 = gain_values(gf);
                    }
                    scan.z_abs = libm::fabs(z);
                }
            }
            None => {
                let (a, b) = (ts.coast(dt_s), tf.coast(dt));
                ensure!(
                    a.is_ok() && b.is_ok(),
                    "{=str} {} scan {=u32}: coast native {}, f64 {}",
                    S::NAME,
                    spec,
                    k,
                    a.err(),
                    b.err()
                );
            }
        }
        let after_s = ts.filter().axes().map(|a| axis_state(&a));
        let after_64 = tf.filter().axes().map(|a| axis_state(&a));
        let states = (before_s.into_iter().zip(after_s)).zip(before_64.into_iter().zip(after_64));
        for (i, (scan, (native, reference))) in scans.iter().zip(states).enumerate() {
            let mut m = Magnitudes::default();
            for ([x0, v0, a0], [x1, v1, a1]) in [native, reference] {
                m.position(x0);
                m.velocity(v0 + dt * a0);
                m.position(x1);
                m.velocity(v1);
                m.acceleration(a1);
            }
            m.position(scan.z_abs);
            m.position(scan.predicted);
            m.residual(scan.residual);
            let mut deviation = [0.0; 3];
            for ((d, s), f) in deviation.iter_mut().zip(native.1).zip(reference.1) {
                *d = libm::fabs(s - f);
            }
            let step = PairStep {
                kind: scan.kind,
                dt,
                gains_64: scan.gains_64,
                gains_s: scan.gains_s,
                residual: scan.residual,
                deviation,
            };
            visit(k, i, &step, &m)?;
        }
    }
    Ok(())
}

/// A gain schedule in `S` against the same schedule in f64, both driving a
/// 2-D filter of order `ORDER` over `scenario`.
///
/// Checked: both runs take the same decisions (their gains agree to 10⁻⁴
/// at every update: the schedules' thresholds, counters and argmins came
/// out alike) and at every update |native − f64| stays within a bound for
/// this run:
///
/// * The library's budget for the schedule's gain spread
///   ([`error_budget_varying_gains`], nominal and spread spanning every gain
///   the run used) is computed and printed, but these schedules sweep wide
///   ranges (least squares from α = 5/6 down, Liu's switch between 0.5 and
///   residual gains near 1, Li's counter falling back on a manoeuvre, TCAS
///   firmness from 0.83 to 0.4), which its small-gain argument cannot
///   certify: it answers `NotContractive`. Besides, gains computed in `S`
///   differ from the f64 run's by more than one conversion, which the
///   budget does not model.
/// * Fallback (`abtrack_firmware::propagation`): the exact error recursion
///   d ← A·d + w along the gains the f64 run actually used, with |w| at most
///   the library's per-update error budget at the largest gains of the run
///   ([`error_budget_around_reference`] with fixed gains bounds the local
///   error of every update with smaller gains: the local error grows with
///   each gain, and the budget is L·η ≥ η) plus |K_native − K_f64|·|e| for
///   the difference of the two runs' gains; two-point initialisation and
///   restarts inject the budget's initial error, coasts propagate by Φ(T).
fn compare_schedule<S: TestNumeric, const ORDER: usize>(
    spec: &ScheduleSpec,
    scenario: &PlaneScenario,
) -> TestResult {
    // Pass 1: magnitudes, gain ranges, decisions.
    let mut env = Magnitudes::default();
    let mut g_max = [0.0f64; 3];
    let mut g_min = [f64::INFINITY; 3];
    let mut differing = 0u32;
    let mut filtered = 0u32;
    let mut largest_gain_difference = 0.0f64;
    run_schedule::<S, ORDER>(spec, scenario, |_, _, step, m| {
        merge(&mut env, m);
        if step.kind == StepKind::Filtered {
            filtered = filtered.saturating_add(1);
            let mut differs = false;
            let extremes = g_max.iter_mut().zip(g_min.iter_mut());
            let gains = step.gains_64.into_iter().zip(step.gains_s);
            for ((max, min), (a, b)) in extremes.zip(gains) {
                *max = max.max(a).max(b);
                *min = min.min(a).min(b);
                let d = libm::fabs(a - b);
                largest_gain_difference = largest_gain_difference.max(d);
                differs |= d > 1e-4 * (1.0 + libm::fabs(a));
            }
            if differs {
                differing = differing.saturating_add(1);
            }
        }
        Ok(())
    })?;
    ensure!(
        differing == 0,
        "{=str} {}: the gains of {=u32} of {=u32} updates differ from f64 by more than rounding (a threshold or argmin decided differently)",
        S::NAME,
        spec,
        differing,
        filtered
    );
    let envelope = env.envelope(scenario.dt, scenario.dt);
    let gains_of = |[alpha, beta, gamma]: [f64; 3]| {
        if ORDER == 3 {
            Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma)
        } else {
            Gains::<f64>::alpha_beta(alpha, beta)
        }
    };
    // What the library's budget says about the whole gain spread.
    let [max_a, max_b, max_c] = g_max;
    let [min_a, min_b, min_c] = g_min;
    let mid = [
        0.5 * (max_a + min_a),
        0.5 * (max_b + min_b),
        0.5 * (max_c + min_c),
    ];
    let verdict = match gains_of(mid) {
        Ok(nominal) => {
            let spread = GainSpread {
                alpha: 0.5 * (max_a - min_a),
                beta: 0.5 * (max_b - min_b),
                gamma: if ORDER == 3 {
                    0.5 * (max_c - min_c)
                } else {
                    0.0
                },
            };
            error_budget_around_reference::<S, ORDER>(&nominal, &spread, &envelope)
        }
        Err(_) => Err(BudgetError::InvalidEnvelope),
    };
    let local = match gains_of(g_max) {
        Ok(g) => fixed_gain_budget::<S, ORDER>(&g, &envelope)?,
        Err(e) => {
            defmt::error!(
                "{=str} {}: largest gains ({=f64}, {=f64}, {=f64}) unstable: {}",
                S::NAME,
                spec,
                max_a,
                max_b,
                max_c,
                e
            );
            return Err(Failure);
        }
    };
    let local_error = [local.position, local.velocity, local.acceleration];

    // Pass 2, one axis at a time (one propagation in memory at a time).
    let mut worst_ratio = 0.0f64;
    let mut worst = [0.0f64; 3];
    for axis in 0..2 {
        let mut window = [Lag::<ORDER>::EMPTY; SCHEDULE_LAGS];
        let mut propagation = ErrorPropagation::new(&mut window, [0.0; ORDER]);
        run_schedule::<S, ORDER>(spec, scenario, |k, i, step, _| {
            if i != axis {
                return Ok(());
            }
            let dt = step.dt;
            let mut injection = [0.0; ORDER];
            for (w, e) in injection.iter_mut().zip(local_error) {
                *w = e;
            }
            let a = match step.kind {
                StepKind::Initialisation => [[0.0; ORDER]; ORDER],
                StepKind::Coast => kinematic_prediction::<ORDER>(dt),
                StepKind::Filtered => {
                    let [a64, b64, c64] = step.gains_64;
                    let [a_s, b_s, c_s] = step.gains_s;
                    let dk = [
                        libm::fabs(a_s - a64),
                        libm::fabs(b_s - b64) / dt,
                        libm::fabs(c_s - c64) / (2.0 * dt * dt),
                    ];
                    let e = step.residual * (1.0 + 1e-6);
                    for (w, dk) in injection.iter_mut().zip(dk) {
                        *w += dk * e;
                    }
                    kinematic_update::<ORDER>(a64, b64, c64, dt)
                }
            };
            let bound = propagation.step(&a, injection);
            let per_state = step.deviation.into_iter().zip(bound).zip(worst.iter_mut());
            for (j, ((d, bound), worst)) in per_state.enumerate() {
                *worst = worst.max(d);
                if bound > 0.0 {
                    worst_ratio = worst_ratio.max(d / bound);
                }
                ensure!(
                    d <= bound,
                    "{=str} {} scan {=u32} axis {=usize}: |d{=usize}| = {=f64} > bound {=f64}",
                    S::NAME,
                    spec,
                    k,
                    axis,
                    j,
                    d,
                    bound
                );
            }
            Ok(())
        })?;
    }
    match verdict {
        Ok(b) => defmt::println!(
            "       {=str} {}: library budget for the gain spread: {=f64} m (not used: gains computed in S)",
            S::NAME,
            spec,
            b.position
        ),
        Err(e) => defmt::println!(
            "       {=str} {}: library budget for the gain spread alpha {=f64}..{=f64}: refused ({}); fallback used",
            S::NAME,
            spec,
            min_a,
            max_a,
            e
        ),
    }
    let [worst_x, worst_v, worst_a] = worst;
    defmt::println!(
        "       {=str} {}: {=u32} filtered updates x 2 axes, same decisions, gains within {=f64}; max |dx| {=f64} m, |dv| {=f64} m/s, |da| {=f64} m/s2; worst deviation = {=f32} of the propagated bound",
        S::NAME,
        spec,
        filtered / 2,
        largest_gain_difference,
        worst_x,
        worst_v,
        worst_a,
        worst_ratio as f32
    );
    Ok(())
}

fn schedule_least_squares_vs_f64() -> TestResult {
    let s = PlaneScenario::liu_turn(2.0, 80, 0x5c4e_0001, never);
    compare_schedule::<Native, 2>(&ScheduleSpec::LeastSquares(LeastSquaresConfig::DEFAULT), &s)
}

fn schedule_liu_adaptive_vs_f64() -> TestResult {
    let s = PlaneScenario::liu_turn(2.0, 80, 0x5c4e_0002, never);
    compare_schedule::<Native, 2>(
        &ScheduleSpec::AdaptiveSwitch(AdaptiveSwitchConfig::DEFAULT),
        &s,
    )
}

fn schedule_li_improved_vs_f64() -> TestResult {
    // Δρ = σ = 5 m, the scenario's noise (the paper's simulation has σ = 1 m
    // and Δρ = 1 m).
    let s = PlaneScenario::liu_turn(2.0, 80, 0x5c4e_0003, never);
    let spec = ScheduleSpec::LiImproved(LiImprovedConfig {
        range_error: 5.0,
        ..LiImprovedConfig::DEFAULT
    });
    compare_schedule::<Native, 2>(&spec, &s)
}

fn schedule_m4_moving_window_vs_f64() -> TestResult {
    let s = PlaneScenario::liu_turn(2.0, 80, 0x5c4e_0004, never);
    compare_schedule::<Native, 2>(&ScheduleSpec::MovingWindow(MovingWindowConfig::DEFAULT), &s)
}

/// Misses: three in a row at scans 20–22 (firmness 8 → 5) and every 11th
/// scan after 30.
fn firmness_misses(k: u32) -> bool {
    (20..23).contains(&k) || (k > 30 && k.is_multiple_of(11))
}

fn schedule_tcas_firmness_vs_f64() -> TestResult {
    let s = PlaneScenario::liu_turn(1.0, 120, 0x5c4e_0005, firmness_misses);
    compare_schedule::<Native, 3>(&ScheduleSpec::Firmness, &s)
}

const BANK_MEMBERS: usize = 8;

/// The bank `config` describes (typed, like [`schedule_for`]).
fn bank_for<S: Numeric>(config: &BankConfig) -> Result<CartesianBank<S, BANK_MEMBERS, 2>, Failure> {
    match CartesianBank::from_config(config) {
        Ok(b) => Ok(b),
        Err(e) => {
            defmt::error!("{=str}: bank {} refused: {}", S::NAME, config, e);
            Err(Failure)
        }
    }
}

/// Al-Wagih & Abdulla's M5 (Algorithm 3) in `S` against f64: K fixed-gain
/// members per axis, the least |innovation| selected. Both banks must select
/// the same member at every update, and every member must stay within the
/// library's budget for its gains (computed in `S` by the bank's
/// configuration: [`fixed_gain_budget_computed_gains`]).
fn compare_bank<S: TestNumeric>(config: &BankConfig, scenario: &PlaneScenario) -> TestResult {
    let mut bs = bank_for::<S>(config)?;
    let mut bf = bank_for::<f64>(config)?;
    let dt = scenario.dt;
    let dt_s = quantity(dt)?;
    let mut magnitudes = [[Magnitudes::default(); BANK_MEMBERS]; 2];
    let mut deviation = [[[0.0f64; 2]; BANK_MEMBERS]; 2];
    let mut selections = 0u32;
    let mut switches = 0u32;
    let mut last_selected = [usize::MAX; 2];
    for (k, z) in (0u32..).zip(scenario.measurements()) {
        let Some(z) = z else {
            continue;
        };
        let before: [[(f64, f64); BANK_MEMBERS]; 2] = bf.axes().each_ref().map(|axis| {
            core::array::from_fn(|m| {
                axis.member(m)
                    .map_or((0.0, 0.0), |f| (f.position(), f.velocity()))
            })
        });
        let zs = [quantity(z[0])?, quantity(z[1])?];
        let (os, of) = match (bs.update(zs, dt_s), bf.update(z, dt)) {
            (Ok(a), Ok(b)) => (a, b),
            (a, b) => {
                defmt::error!(
                    "{=str} bank scan {=u32}: native {}, f64 {}",
                    S::NAME,
                    k,
                    a.err(),
                    b.err()
                );
                return Err(Failure);
            }
        };
        for i in 0..2 {
            match (os[i], of[i]) {
                (BankOutcome::Filtered(a), BankOutcome::Filtered(b)) => {
                    ensure!(
                        a.member == b.member,
                        "{=str} bank scan {=u32} axis {=usize}: native selects member {=usize} (residual {}), f64 member {=usize} (residual {=f64})",
                        S::NAME,
                        k,
                        i,
                        a.member,
                        a.residual,
                        b.member,
                        b.residual
                    );
                    selections += 1;
                    if last_selected[i] != b.member {
                        switches += 1;
                    }
                    last_selected[i] = b.member;
                }
                (BankOutcome::FirstPoint, BankOutcome::FirstPoint)
                | (BankOutcome::SecondPoint, BankOutcome::SecondPoint) => {}
                (a, b) => {
                    defmt::error!(
                        "{=str} bank scan {=u32}: native {}, f64 {}",
                        S::NAME,
                        k,
                        a,
                        b
                    );
                    return Err(Failure);
                }
            }
            for m in 0..BANK_MEMBERS {
                let (Some(ms), Some(mf)) = (bs.axes()[i].member(m), bf.axes()[i].member(m)) else {
                    continue;
                };
                let mag = &mut magnitudes[i][m];
                mag.position(z[i]);
                mag.position(before[i][m].0);
                mag.velocity(before[i][m].1);
                for f in [axis_state(ms), axis_state(mf)] {
                    mag.position(f[0]);
                    mag.velocity(f[1]);
                }
                for inn in [
                    ms.last_innovation()
                        .map(|v| (v.predicted.to_f64(), v.residual.to_f64())),
                    mf.last_innovation().map(|v| (v.predicted, v.residual)),
                ]
                .into_iter()
                .flatten()
                {
                    mag.position(inn.0);
                    mag.residual(inn.1);
                }
                let d = &mut deviation[i][m];
                d[0] = d[0].max(libm::fabs(ms.position().to_f64() - mf.position()));
                d[1] = d[1].max(libm::fabs(ms.velocity().to_f64() - mf.velocity()));
            }
        }
    }
    let mut worst_ratio = 0.0f64;
    let mut worst = [0.0f64; 2];
    for i in 0..2 {
        for m in 0..BANK_MEMBERS {
            let (Some(gs), Some(gf)) = (bs.axes()[i].member_gains(m), bf.axes()[i].member_gains(m))
            else {
                defmt::error!("{=str}: bank member {=usize} missing", S::NAME, m);
                return Err(Failure);
            };
            let (gs, gf) = (gain_values(gs), gain_values(gf));
            let exact_s = match Gains::<f64>::alpha_beta(gs[0], gs[1]) {
                Ok(g) => g,
                Err(e) => {
                    defmt::error!("{=str}: member gains refused: {}", S::NAME, e);
                    return Err(Failure);
                }
            };
            let delta = [gs[0] - gf[0], gs[1] - gf[1], 0.0];
            let env = magnitudes[i][m].envelope(dt, dt);
            let b = fixed_gain_budget_computed_gains::<S, 2>(&exact_s, delta, &env)?;
            let d = deviation[i][m];
            ensure!(
                b.covers(d[0], d[1], 0.0),
                "{=str} bank axis {=usize} member {=usize} (alpha {=f64}): |dx| {=f64} |dv| {=f64} beyond the budget {=f64} m, {=f64} m/s",
                S::NAME,
                i,
                m,
                gf[0],
                d[0],
                d[1],
                b.position,
                b.velocity
            );
            worst[0] = worst[0].max(d[0]);
            worst[1] = worst[1].max(d[1]);
            worst_ratio = worst_ratio.max(d[0] / b.position).max(d[1] / b.velocity);
        }
    }
    defmt::println!(
        "       {=str} bank k={=u16}: {=u32} selections on 2 axes, all the same as f64 ({=u32} changes of member); members: max |dx| {=f64} m, |dv| {=f64} m/s; worst deviation = {=f32} of the budget",
        S::NAME,
        config.k,
        selections,
        switches,
        worst[0],
        worst[1],
        worst_ratio as f32
    );
    Ok(())
}

fn bank_m5_vs_f64() -> TestResult {
    let s = PlaneScenario::liu_turn(2.0, 80, 0x5c4e_0006, never);
    compare_bank::<Native>(&BankConfig::DEFAULT, &s)
}
