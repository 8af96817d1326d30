//! The on-target self-tests' harness and shared helpers (boards/qemu/src/bin/selftest.rs,
//! boards/qemu/src/bin/selftest_tracking.rs): named test functions returning `Result`,
//! a line per test, `N passed, M failed` alone on the last line and the QEMU
//! exit status; the numeric types under test; the run envelope and the
//! library's error budget for fixed-gain runs.
//!
//! Used by each self-test binary; [`ensure!`](crate::ensure) is exported at
//! the crate root.

use abtrack::budget::{error_budget_around_reference, ErrorBound, GainSpread, RunEnvelope};
use abtrack::filter::{Gains, KinematicFilter, Phase};
use abtrack::{Fix, Scalar};

use crate::board;

/// Fails the current test, logging the message, unless the condition holds.
/// (A comparison with NaN does not hold, so a NaN deviation fails.)
#[macro_export]
macro_rules! ensure {
    ($cond:expr, $($msg:tt)+) => {
        let holds: bool = $cond;
        if !holds {
            defmt::error!($($msg)+);
            return Err($crate::selftest_support::Failure);
        }
    };
}

/// A failed check. What failed is logged (defmt::error!) where it is detected.
pub struct Failure;

pub type TestResult = Result<(), Failure>;

/// A named test.
pub type Test = (&'static str, fn() -> TestResult);

/// Runs `tests` in order, printing `ok` or `FAILED` per test, the stack
/// high-water mark and `N passed, M failed` alone on the last line, and
/// leaves QEMU with status 0 only if every test passed.
pub fn run(title: &str, tests: &[Test]) -> ! {
    defmt::println!(
        "abtrack {=str} on {=str} ({=str}): native type {=str} vs f64",
        title,
        board::BOARD,
        board::CORE,
        <board::Native as abtrack::Numeric>::NAME
    );
    let mut passed = 0u32;
    let mut failed = 0u32;
    let mut deepest = 0u32;
    for (name, test) in tests {
        // Each test's own stack high-water mark (the whole stack below this
        // frame is repainted first).
        board::paint_stack();
        let result = test();
        let (used, _) = board::stack_usage();
        deepest = deepest.max(used);
        match result {
            Ok(()) => {
                passed += 1;
                defmt::println!("ok     {=str} (stack {=u32} B)", name, used);
            }
            Err(Failure) => {
                failed += 1;
                defmt::println!("FAILED {=str} (stack {=u32} B)", name, used);
            }
        }
    }
    let (_, available) = board::stack_usage();
    defmt::println!(
        "stack: {=u32} of {=u32} bytes used (high-water mark, deepest test)",
        deepest,
        available
    );
    defmt::println!("{=u32} passed, {=u32} failed", passed, failed);
    board::exit(failed == 0)
}

// ---------------------------------------------------------------------------
// The numeric types under test
// ---------------------------------------------------------------------------

/// What the tests need to know about a representation beyond [`Scalar`]
/// (whose rounding model, `UNIT_ROUNDOFF` and `ABS_RESOLUTION`, the error
/// budget uses).
pub trait TestScalar: Scalar + Bits + defmt::Format {
    /// A representable measurement large enough that the αβ velocity
    /// correction β·e/T (β = 0.25, T = 0.05 s) overflows.
    const HUGE: f64;
    /// Largest absolute error of `sin_cos` (each component) on a
    /// representable angle.
    const SIN_COS_ERROR: f64;
}

impl TestScalar for f64 {
    const HUGE: f64 = 1.7e308;
    // libm's sincos is within 1 ulp (≤ 2⁻⁵³ for |v| < 1); two for margin.
    const SIN_COS_ERROR: f64 = 2.0 * <f64 as abtrack::Quantity>::UNIT_ROUNDOFF;
}

impl Bits for f64 {
    fn bits(self) -> u64 {
        self.to_bits()
    }
}

impl TestScalar for f32 {
    const HUGE: f64 = 3.0e38;
    // The table sine's bound for |θ| ≤ 2π, plus the rounding to f32 (half
    // an ulp, ≤ 2⁻²⁴ for |v| ≤ 1).
    const SIN_COS_ERROR: f64 =
        abtrack::num::sine::SIN_COS_F32_MAX_ERROR + <f32 as abtrack::Quantity>::UNIT_ROUNDOFF;
}

impl Bits for f32 {
    fn bits(self) -> u64 {
        self.to_bits() as u64
    }
}

impl TestScalar for Fix {
    // Representable (< 2³¹), but 0.25·1e9/0.05 = 5e9 is not.
    const HUGE: f64 = 1.0e9;
    const SIN_COS_ERROR: f64 = abtrack::num::cordic::SIN_COS_MAX_ERROR;
}

impl Bits for Fix {
    fn bits(self) -> u64 {
        self.to_bits() as u64
    }
}

impl TestScalar for abtrack::ScaledScalar {
    // Representable (< 2¹³¹ ≈ 2.7·10³⁹), but 0.25·1e39/0.05 = 5·10³⁹ is not.
    const HUGE: f64 = 1.0e39;
    const SIN_COS_ERROR: f64 = abtrack::num::scaled_scalar::SIN_COS_MAX_ERROR;
}

impl Bits for abtrack::ScaledScalar {
    fn bits(self) -> u64 {
        let r = self.to_ratio();
        (u64::from(r.mantissa() as u32) << 16) | u64::from(r.exponent() as u16)
    }
}

/// A quantity's stored bit pattern, for "bit-identical" checks.
pub trait Bits: Copy {
    fn bits(self) -> u64;
}

macro_rules! fixed_bits {
    ($($t:ty),*) => {$(
        impl Bits for $t {
            fn bits(self) -> u64 {
                u64::from(self.to_bits() as u32)
            }
        }
    )*};
}
fixed_bits!(
    abtrack::num::fixed32::Length,
    abtrack::num::fixed32::Speed,
    abtrack::num::fixed32::Acceleration
);

/// What the tests need to know about a number system beyond
/// [`abtrack::Numeric`] (whose per-quantity rounding model the error budget
/// uses).
pub trait TestNumeric:
    abtrack::Numeric<Length: Bits, Speed: Bits, Acceleration: Bits> + defmt::Format
{
    /// A representable measurement large enough that the αβ velocity
    /// correction β·e/T (β = 0.25, T = 0.05 s) overflows.
    const HUGE: f64;
    /// A representable state (position, velocity) and interval whose coast
    /// overflows the position.
    const OVERFLOWING_COAST: [f64; 3];
    /// The envelope of the estimates (docs/numerics-fixed-point.md): the
    /// largest |velocity| and |acceleration|, and |z − x_p|; infinite where
    /// the format holds every value the tests reach.
    const SPEED_LIMIT: f64 = f64::INFINITY;
    const ACCELERATION_LIMIT: f64 = f64::INFINITY;
    const RESIDUAL_LIMIT: f64 = f64::INFINITY;
}

/// A scalar's figures are its [`TestScalar`] ones (its formats hold every
/// estimate the tests reach).
impl<S: TestScalar> TestNumeric for S {
    const HUGE: f64 = <S as TestScalar>::HUGE;
    const OVERFLOWING_COAST: [f64; 3] = [0.0, <S as TestScalar>::HUGE, 100.0];
}
impl TestNumeric for abtrack::Fixed32 {
    // Representable (< 524 288 m), but 0.25·5e5/0.05 = 2.5·10⁶ m/s is not.
    const HUGE: f64 = 5.0e5;
    // 5·10⁵ m + 100 s · 2000 m/s is beyond the ±524 288 m of a length.
    const OVERFLOWING_COAST: [f64; 3] = [5.0e5, 2000.0, 100.0];
    // The formats' ranges (±8192 m/s, ±8192 m/s², ±524 288 m), less a margin.
    const SPEED_LIMIT: f64 = 8000.0;
    const ACCELERATION_LIMIT: f64 = 8000.0;
    const RESIDUAL_LIMIT: f64 = 5.0e5;
}

/// A constant in any quantity (rounded to nearest; out of range: invalid).
pub fn q<Q: abtrack::num::Quantity>(v: f64) -> Q {
    Q::from_f64_lossy(v)
}

/// A value converted into a quantity, refusing what does not fit.
pub fn quantity<Q: abtrack::num::Quantity>(v: f64) -> Result<Q, Failure> {
    match Q::try_from_f64(v) {
        Ok(x) => Ok(x),
        Err(e) => {
            defmt::error!("{=f64} not representable: {}", v, e);
            Err(Failure)
        }
    }
}

pub fn value<S: TestScalar>(v: f64) -> Result<S, Failure> {
    match S::try_from_f64(v) {
        Ok(x) => Ok(x),
        Err(e) => {
            defmt::error!("{=str}: {=f64} not representable: {}", S::NAME, v, e);
            Err(Failure)
        }
    }
}

pub fn never(_: u32) -> bool {
    false
}

pub fn gain_values<N: abtrack::Numeric>(g: &Gains<N>) -> [f64; 3] {
    use abtrack::num::Quantity as Q;
    [
        Q::to_f64(g.alpha()),
        Q::to_f64(g.beta()),
        Q::to_f64(g.gamma()),
    ]
}

/// The largest magnitudes one run reached, as the budget's envelope wants
/// them ([`RunEnvelope`]): measurements, predictions and estimates for the
/// position, predicted and smoothed velocities (the two-point velocity
/// included), accelerations and residuals.
#[derive(Clone, Copy, Default)]
pub struct Magnitudes {
    pub position: f64,
    pub velocity: f64,
    pub acceleration: f64,
    pub residual: f64,
}

impl Magnitudes {
    pub fn position(&mut self, v: f64) {
        self.position = self.position.max(libm::fabs(v));
    }
    pub fn velocity(&mut self, v: f64) {
        self.velocity = self.velocity.max(libm::fabs(v));
    }
    pub fn acceleration(&mut self, v: f64) {
        self.acceleration = self.acceleration.max(libm::fabs(v));
    }
    pub fn residual(&mut self, v: f64) {
        self.residual = self.residual.max(libm::fabs(v));
    }

    /// One f64 update from state (x, v, a) before it to the filter after it.
    pub fn record<const ORDER: usize>(
        &mut self,
        z: f64,
        dt: f64,
        before: (f64, f64, f64),
        after: &KinematicFilter<f64, ORDER>,
    ) {
        self.position(z);
        self.position(before.0);
        if let (Phase::Tracking, Some(i)) = (after.phase(), after.last_innovation()) {
            self.position(i.predicted);
            self.residual(i.residual);
        }
        // The predicted velocity v + T·a of the update.
        self.velocity(before.1 + dt * before.2);
        self.position(after.position());
        self.velocity(after.velocity());
        self.acceleration(after.acceleration());
    }

    pub fn envelope(&self, dt_min: f64, dt_max: f64) -> RunEnvelope {
        RunEnvelope {
            max_position: self.position,
            max_velocity: self.velocity,
            max_acceleration: self.acceleration,
            max_residual: self.residual,
            dt_min,
            dt_max,
        }
    }
}

/// Componentwise maximum of `m` into `into`.
pub fn merge(into: &mut Magnitudes, m: &Magnitudes) {
    into.position(m.position);
    into.velocity(m.velocity);
    into.acceleration(m.acceleration);
    into.residual(m.residual);
}

/// The library's error budget ([`abtrack::budget`]) for a fixed-gain run of
/// `S` whose f64 twin reached the magnitudes `m`: the envelope is widened
/// around the f64 run and the bound re-checked
/// ([`error_budget_around_reference`]), so it bounds |S − f64| at every
/// update of the run. A run the budget refuses fails the test: every
/// fixed-gain run here has a constant interval, which the budget covers
/// (it refuses only interval or gain spreads it cannot certify, gains
/// within about 10⁻⁴ of the stability boundary, and runs that may
/// overflow).
pub fn fixed_gain_budget<S: abtrack::Numeric, const ORDER: usize>(
    gains: &Gains<f64>,
    envelope: &RunEnvelope,
) -> Result<ErrorBound, Failure> {
    match error_budget_around_reference::<S, ORDER>(gains, &GainSpread::default(), envelope) {
        Ok(b) => Ok(b),
        Err(e) => {
            defmt::error!(
                "{=str}/{=usize}: the error budget refused gains ({=f64}, {=f64}, {=f64}), envelope {}: {}",
                S::NAME,
                ORDER,
                gains.alpha(),
                gains.beta(),
                gains.gamma(),
                envelope,
                e
            );
            Err(Failure)
        }
    }
}

/// The library's budget for a fixed-gain run whose gains were computed in
/// `S` (`gains_s`, their exact values) rather than converted from the f64
/// run's (`gains_s − delta` up to sign): |S − f64| ≤ |S − exact(g_S)| +
/// |exact(g_S) − exact(g_64)| + |exact(g_64) − f64|. The first and last terms
/// are the budget at g_S (its f64 term, doubled, covers the 10⁻⁷-relative
/// change of gains). The middle one is two exact filters differing only in
/// their gains: d ← A(g_S)·d + ΔK·e, so in the budget's scaled coordinates
/// (x, vT, aT²), where W·ΔK = (Δα, Δβ, Δγ/2), each component is at most
/// ‖L‖∞·max(|Δα|, |Δβ|, |Δγ|/2)·max|e| (`amplification` is ‖L‖∞).
pub fn fixed_gain_budget_computed_gains<S: abtrack::Numeric, const ORDER: usize>(
    gains_s: &Gains<f64>,
    delta: [f64; 3],
    envelope: &RunEnvelope,
) -> Result<ErrorBound, Failure> {
    let mut b = fixed_gain_budget::<S, ORDER>(gains_s, envelope)?;
    let t = envelope.dt_max;
    let scaled = libm::fabs(delta[0])
        .max(libm::fabs(delta[1]))
        .max(0.5 * libm::fabs(delta[2]));
    let extra = b.amplification * scaled * envelope.max_residual;
    b.position += extra;
    b.velocity += extra / t;
    if ORDER == 3 {
        b.acceleration += extra / (t * t);
    }
    Ok(b)
}
