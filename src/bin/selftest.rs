//! On-target self-test: the filter checks of issue 2 run on the emulated core
//! itself, in the core's natural numeric type (`f32` on the Cortex-M4F, Q32.32
//! fixed point on the Cortex-M3 and M0) against the same generic filter in
//! `f64` (software floating point on all three cores).
//!
//! A tiny harness: named test functions returning `Result`, a line per test,
//! then `N passed, M failed` alone on the last line; QEMU exits with status 1
//! if any test failed (scripts/test.sh runs it on the three boards).
//!
//! What is checked:
//! * native vs f64 on seeded pseudo-random trajectories, on the corners of the
//!   envelope (positions ±400 km, velocities ±1500 m/s, accelerations
//!   ±200 m/s², intervals 0.05 s and 20 s) and over a 10,000-update run, within
//!   [`comparison_tolerance`] (derived there);
//! * invalid inputs (invalid measurement, interval ≤ 0 or invalid) are refused
//!   with the right [`FilterError`] and leave the state bit-identical;
//! * gains outside the stability regions are refused with the right
//!   [`GainError`];
//! * an update or coast that overflows the representation is refused as
//!   [`FilterError::Saturated`], counted, and leaves the state otherwise
//!   untouched;
//! * two-point initialisation and the first filtered update against values
//!   computed by hand;
//! * a 2-D [`Cartesian`] filter is exactly its axes' one-axis filters.
#![no_std]
#![no_main]

#[path = "../firmware/board.rs"]
mod board;
#[path = "../firmware/synth.rs"]
mod synth;

use abtrack::filter::{
    Cartesian, FilterError, GainError, Gains, Innovation, KinematicFilter, Phase, UpdateOutcome,
};
use abtrack::{Fix, Scalar};
use board::Native;
use synth::Lcg;

/// A failed check. What failed is logged (defmt::error!) where it is detected.
struct Failure;

type TestResult = Result<(), Failure>;

/// Fails the current test, logging the message, unless the condition holds.
macro_rules! ensure {
    ($cond:expr, $($msg:tt)+) => {
        if !$cond {
            defmt::error!($($msg)+);
            return Err(Failure);
        }
    };
}

/// A named test.
type Test = (&'static str, fn() -> TestResult);

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
];

#[cortex_m_rt::entry]
fn main() -> ! {
    board::paint_stack();
    defmt::println!(
        "abtrack self-test on {=str} ({=str}): native type {=str} vs f64",
        board::BOARD,
        board::CORE,
        Native::NAME
    );
    let mut passed = 0u32;
    let mut failed = 0u32;
    for (name, test) in TESTS {
        match test() {
            Ok(()) => {
                passed += 1;
                defmt::println!("ok     {=str}", name);
            }
            Err(Failure) => {
                failed += 1;
                defmt::println!("FAILED {=str}", name);
            }
        }
    }
    board::report_stack();
    defmt::println!("{=u32} passed, {=u32} failed", passed, failed);
    board::exit(failed == 0)
}

// ---------------------------------------------------------------------------
// The numeric types under test
// ---------------------------------------------------------------------------

/// What the tests need to know about a representation beyond [`Scalar`].
trait TestScalar: Scalar + defmt::Format {
    /// Largest relative rounding error of one operation or conversion (unit
    /// roundoff, 2⁻ᵖ for p significand bits); 0 for fixed point.
    const UNIT_ROUNDOFF: f64;
    /// Largest absolute rounding error of one operation or conversion; 0 for
    /// floating point.
    const RESOLUTION: f64;
    /// A representable measurement large enough that the αβ velocity
    /// correction β·e/T (β = 0.25, T = 0.05 s) overflows.
    const HUGE: f64;
    /// The stored bit pattern, for "bit-identical" checks.
    fn bits(self) -> u64;
}

impl TestScalar for f64 {
    const UNIT_ROUNDOFF: f64 = 1.0 / 9_007_199_254_740_992.0; // 2⁻⁵³
    const RESOLUTION: f64 = 0.0;
    const HUGE: f64 = 1.7e308;
    fn bits(self) -> u64 {
        self.to_bits()
    }
}

impl TestScalar for f32 {
    const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0; // 2⁻²⁴
    const RESOLUTION: f64 = 0.0;
    const HUGE: f64 = 3.0e38;
    fn bits(self) -> u64 {
        self.to_bits() as u64
    }
}

impl TestScalar for Fix {
    const UNIT_ROUNDOFF: f64 = 0.0;
    // Q32.32: one step is 2⁻³²; products and quotients are rounded or
    // truncated to it, conversions rounded (either way within one step).
    const RESOLUTION: f64 = 1.0 / 4_294_967_296.0;
    // Representable (< 2³¹), but 0.25·1e9/0.05 = 5e9 is not.
    const HUGE: f64 = 1.0e9;
    fn bits(self) -> u64 {
        self.to_bits() as u64
    }
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

fn snapshot<S: TestScalar, const ORDER: usize>(f: &KinematicFilter<S, ORDER>) -> Snapshot {
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
fn gains_for<S: TestScalar, const ORDER: usize>(
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

fn value<S: TestScalar>(v: f64) -> Result<S, Failure> {
    match S::try_from_f64(v) {
        Ok(x) => Ok(x),
        Err(e) => {
            defmt::error!("{=str}: {=f64} not representable: {}", S::NAME, v, e);
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
fn golden<S: TestScalar, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.5, 0.25, 0.125)?;
    let n = |v: f64| S::from_f64_lossy(v);
    let mut f = KinematicFilter::<S, ORDER>::new();
    ensure!(
        f.phase() == Phase::Empty,
        "{=str}: new filter not empty",
        S::NAME
    );

    let first = f.update(n(100.0), n(1.0), &gains);
    ensure!(
        first == Ok(UpdateOutcome::FirstPoint) && f.phase() == Phase::OnePoint,
        "{=str}/{=usize}: first update: {}",
        S::NAME,
        ORDER,
        first
    );
    ensure!(
        f.position() == n(100.0) && f.velocity() == S::ZERO,
        "{=str}/{=usize}: after z1: x={} v={}",
        S::NAME,
        ORDER,
        f.position(),
        f.velocity()
    );
    ensure!(f.coast(n(1.0)).is_ok(), "{=str}: coast refused", S::NAME);
    ensure!(
        f.position() == n(100.0) && f.phase() == Phase::OnePoint,
        "{=str}: coast before the second point moved the position",
        S::NAME
    );

    let second = f.update(n(130.0), n(1.0), &gains);
    ensure!(
        second == Ok(UpdateOutcome::SecondPoint) && f.phase() == Phase::Tracking,
        "{=str}/{=usize}: second update: {}",
        S::NAME,
        ORDER,
        second
    );
    ensure!(
        f.position() == n(130.0) && f.velocity() == n(15.0) && f.acceleration() == S::ZERO,
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

    let third = f.update(n(150.0), n(2.0), &gains);
    let want_innovation = Innovation {
        predicted: n(160.0),
        residual: n(-10.0),
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
        f.position() == n(155.0)
            && f.velocity() == n(13.75)
            && f.acceleration() == n(want_acceleration),
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
fn invalid_inputs<S: TestScalar, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.5, 0.25, 0.125)?;
    let n = |v: f64| S::from_f64_lossy(v);
    let nan = n(f64::NAN);
    let inf = n(f64::INFINITY);
    let minus_inf = n(f64::NEG_INFINITY);
    let ok_z = n(1234.5);
    let ok_dt = n(1.0);
    let update_cases = [
        (nan, ok_dt, FilterError::InvalidMeasurement),
        (inf, ok_dt, FilterError::InvalidMeasurement),
        (minus_inf, ok_dt, FilterError::InvalidMeasurement),
        (ok_z, S::ZERO, FilterError::InvalidInterval),
        (ok_z, n(-1.0), FilterError::InvalidInterval),
        (ok_z, nan, FilterError::InvalidInterval),
        (ok_z, inf, FilterError::InvalidInterval),
        (ok_z, minus_inf, FilterError::InvalidInterval),
    ];
    let bad_intervals = [S::ZERO, n(-1.0), nan, inf, minus_inf];

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
            f.update(n(*z), ok_dt, &gains).is_ok(),
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
fn cartesian_invalid_inputs<S: TestScalar>() -> TestResult {
    let gains = gains_for::<S, 2>(0.5, 0.25, 0.0)?;
    let n = |v: f64| S::from_f64_lossy(v);
    let mut f: Cartesian<S, 2, 2> = Cartesian::new();
    for (x, y) in [(0.0, 0.0), (10.0, 20.0), (21.0, 39.0)] {
        ensure!(
            f.update([n(x), n(y)], n(1.0), &gains).is_ok(),
            "{=str}: 2-D update refused",
            S::NAME
        );
    }
    let before = f;
    let got = f.update([n(30.0), n(f64::NAN)], n(1.0), &gains);
    ensure!(
        got.err() == Some(FilterError::InvalidMeasurement) && f == before,
        "{=str}: 2-D update with a NaN axis: {} (state changed: {=bool})",
        S::NAME,
        got.err(),
        f != before
    );
    let got = f.update([n(30.0), n(60.0)], S::ZERO, &gains);
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
fn gain_checks<S: TestScalar>() -> TestResult {
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
    let nan = S::from_f64_lossy(f64::NAN);
    let half = S::from_f64_lossy(0.5);
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
fn saturation<S: TestScalar, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.5, 0.25, 0.125)?;
    let n = |v: f64| S::from_f64_lossy(v);
    let dt = value::<S>(0.05)?;
    let huge = value::<S>(S::HUGE)?;
    let mut f = KinematicFilter::<S, ORDER>::new();
    for z in [0.0, 1.0, 2.0] {
        ensure!(
            f.update(n(z), dt, &gains).is_ok(),
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
        f.update(n(3.0), dt, &gains).is_ok(),
        "{=str}: update after a saturation refused",
        S::NAME
    );

    let mut fast = match KinematicFilter::<S, ORDER>::from_state(S::ZERO, huge, S::ZERO) {
        Ok(f) => f,
        Err(e) => {
            defmt::error!("{=str}: from_state refused: {}", S::NAME, e);
            return Err(Failure);
        }
    };
    let before = snapshot(&fast);
    let got = fast.coast(n(100.0));
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

/// In 2-D the saturating axis counts it, and neither axis moves.
fn cartesian_saturation<S: TestScalar>() -> TestResult {
    let gains = gains_for::<S, 2>(0.5, 0.25, 0.0)?;
    let n = |v: f64| S::from_f64_lossy(v);
    let dt = value::<S>(0.05)?;
    let mut f: Cartesian<S, 2, 2> = Cartesian::new();
    for z in [0.0, 1.0, 2.0] {
        ensure!(
            f.update([n(z), n(z)], dt, &gains).is_ok(),
            "{=str}: 2-D update refused",
            S::NAME
        );
    }
    let before = f;
    let got = f.update([n(3.0), value::<S>(S::HUGE)?], dt, &gains);
    let x_same = f.axes()[0] == before.axes()[0];
    let y_same = same_state_ignoring_counter(&snapshot(&f.axes()[1]), &snapshot(&before.axes()[1]));
    ensure!(
        got.err() == Some(FilterError::Saturated)
            && x_same
            && y_same
            && f.axes()[1].saturations() == 1
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

fn cartesian_vs_axes<S: TestScalar, const ORDER: usize>() -> TestResult {
    let gains = gains_for::<S, ORDER>(0.6, 0.3, 0.05)?;
    let dt = value::<S>(0.5)?;
    let mut plane: Cartesian<S, ORDER, 2> = Cartesian::new();
    let mut x = KinematicFilter::<S, ORDER>::new();
    let mut y = KinematicFilter::<S, ORDER>::new();
    let mut rng = Lcg::new(0xc0ffee);
    for k in 0..200u32 {
        let t = k as f64 * 0.5;
        let zx = value::<S>(-3000.0 + 120.0 * t + rng.noise(20.0))?;
        let zy = value::<S>(5000.0 - 0.5 * t * t + rng.noise(20.0))?;
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
// Native vs f64
// ---------------------------------------------------------------------------

/// The largest magnitudes seen so far in a run (from the f64 filter), the
/// inputs of [`comparison_tolerance`].
#[derive(Clone, Copy, Default)]
struct Magnitudes {
    /// Positions: measurements, predictions, estimates (m).
    position: f64,
    /// Velocity estimates (m/s).
    velocity: f64,
    /// Acceleration estimates (m/s²).
    acceleration: f64,
    /// Residuals z − x_p (m).
    residual: f64,
}

/// Largest allowed |native − f64| for position (m), velocity (m/s) and
/// acceleration (m/s²).
#[derive(Clone, Copy)]
struct Tolerance {
    position: f64,
    velocity: f64,
    acceleration: f64,
}

/// Gains as plain numbers, for the bound.
#[derive(Clone, Copy)]
struct GainValues {
    alpha: f64,
    beta: f64,
    /// 0 for αβ.
    gamma: f64,
}

/// How far the filter run in `S` may drift from the same filter run in f64,
/// over a run of `updates` updates with gains `g` at interval `dt`, given the
/// magnitudes seen so far. THE ONE PLACE that decides the comparison bound:
/// to be replaced by the library's error budget (`src/budget.rs`) when it
/// lands.
///
/// # Derivation
///
/// Scale the state to metres: y = (x, v·T, a·T²). In these units one update
/// (Tenne & Singh eqs. 1–5, Al-Wagih eqs. 3–8) is y ← A·y + K·z with
/// K = (α, β, γ/2), A = (I − K·H)·F, H = (1, 0, 0) and
/// F = [[1, 1, ½], [0, 1, 2], [0, 0, 1]]: A depends on the gains only, not on
/// T. (For αβ the state is (x, v·T) and A is the upper-left 2×2.)
///
/// The filter is linear, so the difference between the S run and the f64 run
/// obeys d ← A·d + r, where r is what both runs' rounding injects in one
/// update (the measurement and T converted to S, every product, quotient and
/// sum, and the gains rounded to S, whose effect ΔK·e is a residual times a
/// rounding). Two-point initialisation injects at most as much. So after any
/// number of updates |d|∞ ≤ G·δ, with δ the largest |r|∞ and
/// G = Σₖ ‖Aᵏ‖∞ (k from 0 to the run length). G is summed on the target,
/// stopping early at the first k with q = ‖Aᵏ‖∞ ≤ 0.1 and bounding the
/// rest by the geometric tail: Σ_{n≥k} ‖Aⁿ‖ ≤ q·Σ_{n<k} ‖Aⁿ‖/(1 − q)
/// (submultiplicativity).
///
/// δ, counting the rounded operations of `KinematicFilter::update` one by
/// one, with X = M_x + T·M_v + T²·M_a the largest position-scale quantity and
/// M_e the largest residual:
/// * floating point, unit roundoff u: position ≤ u·(7X + (1 + 2α)·M_e),
///   scaled velocity ≤ u·(4X + 4β·M_e), scaled acceleration ≤ u·(X + 3γ·M_e);
///   taken together as u·(8X + 4(1 + α + β + γ)·M_e).
/// * Q32.32, step ε = 2⁻³² (absolute): position
///   ≤ ε·(5 + M_v + (2T + 2)·M_a + M_e); scaled velocity
///   ≤ ε·(1 + M_e + 2T + T·M_a + β·M_e/(2T)); scaled acceleration
///   ≤ ε·(1 + M_e + T² + γ·M_e·(1/T + 1/(2T²))); the 1/T terms are the
///   relative error of the rounded T and 2T² in β/T and γ/(2T²) at short
///   intervals. Bounded together by their sum.
///
/// δ counts both runs (S and f64). The bound is doubled for the second-order
/// terms (a rounding of a rounding) left out above, and because the
/// magnitudes come from the f64 run: position 2·G·δ, velocity 2·G·δ/T,
/// acceleration 2·G·δ/T².
fn comparison_tolerance<S: TestScalar>(
    g: GainValues,
    order: usize,
    dt: f64,
    updates: u32,
    m: &Magnitudes,
) -> Tolerance {
    fn closed_loop(g: GainValues, order: usize) -> [[f64; 3]; 3] {
        let f = [[1.0, 1.0, 0.5], [0.0, 1.0, 2.0], [0.0, 0.0, 1.0]];
        let k = [g.alpha, g.beta, 0.5 * g.gamma];
        let mut a = [[0.0; 3]; 3];
        for i in 0..order {
            for j in 0..order {
                // (I − K·H)·F: row i of F minus k_i times row 0 of F.
                a[i][j] = f[i][j] - k[i] * f[0][j];
            }
        }
        a
    }
    fn product(p: &[[f64; 3]; 3], q: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        let mut r = [[0.0; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                *cell = p[i][0] * q[0][j] + p[i][1] * q[1][j] + p[i][2] * q[2][j];
            }
        }
        r
    }
    fn infinity_norm(p: &[[f64; 3]; 3]) -> f64 {
        p.iter()
            .map(|row| libm::fabs(row[0]) + libm::fabs(row[1]) + libm::fabs(row[2]))
            .fold(0.0, f64::max)
    }
    /// G = Σₖ ‖Aᵏ‖∞ for k < `terms`, with the geometric tail bound.
    fn error_gain(a: &[[f64; 3]; 3], terms: u32) -> f64 {
        let mut power = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mut sum = 0.0;
        for k in 0..terms {
            let q = infinity_norm(&power);
            if k > 0 && q <= 0.1 {
                return sum / (1.0 - q);
            }
            sum += q;
            power = product(&power, a);
        }
        sum
    }
    fn injection(u: f64, eps: f64, g: GainValues, t: f64, m: &Magnitudes) -> f64 {
        let x = m.position + t * m.velocity + t * t * m.acceleration;
        let e = m.residual;
        let float = u * (8.0 * x + 4.0 * (1.0 + g.alpha + g.beta + g.gamma) * e);
        let fixed_position = 5.0 + m.velocity + (2.0 * t + 2.0) * m.acceleration + e;
        let fixed_velocity = 1.0 + e + 2.0 * t + t * m.acceleration + g.beta * e / (2.0 * t);
        let fixed_acceleration = 1.0 + e + t * t + g.gamma * e * (1.0 / t + 1.0 / (2.0 * t * t));
        float + eps * (fixed_position + fixed_velocity + fixed_acceleration)
    }

    let a = closed_loop(g, order);
    let gain = error_gain(&a, updates.saturating_add(1));
    let delta = injection(
        <S as TestScalar>::UNIT_ROUNDOFF,
        <S as TestScalar>::RESOLUTION,
        g,
        dt,
        m,
    ) + injection(
        <f64 as TestScalar>::UNIT_ROUNDOFF,
        <f64 as TestScalar>::RESOLUTION,
        g,
        dt,
        m,
    );
    let scaled = 2.0 * gain * delta;
    Tolerance {
        position: scaled,
        velocity: scaled / dt,
        acceleration: scaled / (dt * dt),
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

/// Worst deviations over the runs of one test.
#[derive(Default)]
struct Deviation {
    position: f64,
    velocity: f64,
    /// Largest deviation / tolerance ratio over every component and step.
    worst_ratio: f64,
    /// Largest residual the runs saw (m).
    residual: f64,
    updates: u32,
}

impl Deviation {
    fn report(&self, what: &str) {
        defmt::println!(
            "       {=str}: {=u32} updates, residuals up to {=f32} m: max |dx| {=f64} m, max |dv| {=f64} m/s, worst deviation/bound {=f32}",
            what,
            self.updates,
            self.residual as f32,
            self.position,
            self.velocity,
            self.worst_ratio as f32
        );
    }
}

/// Runs the same measurements through the filter in `S` and in f64 and checks
/// the largest differences against [`comparison_tolerance`]; both must also
/// accept or refuse the same updates.
fn compare_run<S: TestScalar, const ORDER: usize>(
    gains: GainValues,
    dt: f64,
    start: Start,
    updates: u32,
    mut measurement: impl FnMut(u32) -> f64,
    deviation: &mut Deviation,
) -> TestResult {
    let gains_s = gains_for::<S, ORDER>(gains.alpha, gains.beta, gains.gamma)?;
    let gains_64 = gains_for::<f64, ORDER>(gains.alpha, gains.beta, gains.gamma)?;
    let dt_s = value::<S>(dt)?;
    let mut m = Magnitudes::default();
    let (mut fs, mut f64f) = match start {
        Start::Empty => (
            KinematicFilter::<S, ORDER>::new(),
            KinematicFilter::<f64, ORDER>::new(),
        ),
        Start::State(p, v, a) => {
            let s = KinematicFilter::<S, ORDER>::from_state(value(p)?, value(v)?, value(a)?);
            let r = KinematicFilter::<f64, ORDER>::from_state(p, v, a);
            match (s, r) {
                (Ok(s), Ok(r)) => {
                    m.position = libm::fabs(p);
                    m.velocity = libm::fabs(v);
                    m.acceleration = if ORDER == 3 { libm::fabs(a) } else { 0.0 };
                    (s, r)
                }
                _ => {
                    defmt::error!("{=str}: from_state refused", S::NAME);
                    return Err(Failure);
                }
            }
        }
    };
    let mut worst = Tolerance {
        position: 0.0,
        velocity: 0.0,
        acceleration: 0.0,
    };
    let mut worst_step = [0u32; 3];
    for k in 0..updates {
        let z = measurement(k);
        let zs = value::<S>(z)?;
        let got_s = fs.update(zs, dt_s, &gains_s);
        let got_64 = f64f.update(z, dt, &gains_64);
        ensure!(
            got_s.is_ok() == got_64.is_ok(),
            "{=str}/{=usize} k={=u32} z={=f64} T={=f64}: native {}, f64 {}",
            S::NAME,
            ORDER,
            k,
            z,
            dt,
            got_s.err(),
            got_64.err()
        );
        m.position = m
            .position
            .max(libm::fabs(z))
            .max(libm::fabs(f64f.position()));
        if let Some(i) = f64f.last_innovation() {
            m.position = m.position.max(libm::fabs(i.predicted));
            m.residual = m.residual.max(libm::fabs(i.residual));
        }
        m.velocity = m.velocity.max(libm::fabs(f64f.velocity()));
        m.acceleration = m.acceleration.max(libm::fabs(f64f.acceleration()));

        let dx = libm::fabs(fs.position().to_f64() - f64f.position());
        let dv = libm::fabs(fs.velocity().to_f64() - f64f.velocity());
        let da = libm::fabs(fs.acceleration().to_f64() - f64f.acceleration());
        if dx > worst.position {
            worst.position = dx;
            worst_step[0] = k;
        }
        if dv > worst.velocity {
            worst.velocity = dv;
            worst_step[1] = k;
        }
        if da > worst.acceleration {
            worst.acceleration = da;
            worst_step[2] = k;
        }
    }
    // The bound grows with the magnitudes, so the one for the whole run's
    // magnitudes holds at every step; computing it once keeps the run cheap.
    let tol = comparison_tolerance::<S>(gains, ORDER, dt, updates, &m);
    ensure!(
        worst.position <= tol.position
            && worst.velocity <= tol.velocity
            && worst.acceleration <= tol.acceleration,
        "{=str}/{=usize} T={=f64} gains ({=f64}, {=f64}, {=f64}): max |dx| {=f64} at k={=u32} (bound {=f64}), max |dv| {=f64} at k={=u32} (bound {=f64}), max |da| {=f64} at k={=u32} (bound {=f64})",
        S::NAME,
        ORDER,
        dt,
        gains.alpha,
        gains.beta,
        gains.gamma,
        worst.position,
        worst_step[0],
        tol.position,
        worst.velocity,
        worst_step[1],
        tol.velocity,
        worst.acceleration,
        worst_step[2],
        tol.acceleration
    );
    deviation.position = deviation.position.max(worst.position);
    deviation.velocity = deviation.velocity.max(worst.velocity);
    deviation.worst_ratio = deviation
        .worst_ratio
        .max(worst.position / tol.position)
        .max(worst.velocity / tol.velocity)
        .max(worst.acceleration / tol.acceleration);
    deviation.residual = deviation.residual.max(m.residual);
    deviation.updates += updates;
    Ok(())
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
}

impl RandomTarget {
    fn new(rng: &mut Lcg, dt: f64) -> Self {
        RandomTarget {
            rng: Lcg::new(rng.next_u32() as u64 | (rng.next_u32() as u64) << 32),
            position: rng.uniform(-0.9 * MAX_POSITION, 0.9 * MAX_POSITION),
            velocity: rng.uniform(-MAX_VELOCITY, MAX_VELOCITY),
            acceleration: rng.uniform(-MAX_ACCELERATION, MAX_ACCELERATION),
            dt,
            noise_sigma: rng.uniform(1.0, 150.0),
        }
    }

    fn next_measurement(&mut self) -> f64 {
        if self.rng.index(8) == 0 {
            self.acceleration = self.rng.uniform(-MAX_ACCELERATION, MAX_ACCELERATION);
        }
        self.velocity =
            (self.velocity + self.acceleration * self.dt).clamp(-MAX_VELOCITY, MAX_VELOCITY);
        self.position += self.velocity * self.dt;
        if self.position > MAX_POSITION {
            self.position = 2.0 * MAX_POSITION - self.position;
            self.velocity = -self.velocity;
        } else if self.position < -MAX_POSITION {
            self.position = -2.0 * MAX_POSITION - self.position;
            self.velocity = -self.velocity;
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
        let mut target = RandomTarget::new(&mut rng, dt);
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
            let path = |k: u32| {
                if k + 1 == STEPS {
                    -p
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
    let mut target = RandomTarget::new(&mut rng, 1.0);
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
    let mut target = RandomTarget::new(&mut rng, 1.0);
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
