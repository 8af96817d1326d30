//! Number systems with typed quantities ([`Numeric`]): what a filter computes
//! with, one associated type per physical quantity, so that a fixed-point
//! system can give each quantity its own format (see
//! `docs/numerics-fixed-point.md`) while `f64`, `f32` and Q32.32 use one type
//! for all of them (the blanket implementation over [`Scalar`]).
//!
//! # The guarded hot path
//!
//! The per-update arithmetic of the filters goes through [`AddProduct`] and
//! [`SubGuarded`] with a [`Guard`] of the number system: `q + a·b` and
//! `a − b`, each rounded once. The guard records what the results need to be
//! trusted, so the filter checks validity once, after computing everything:
//!
//! * floats: NaN and ±∞ are sticky, so checking the outputs checks every
//!   intermediate. `f64` sums the outputs ([`Checked::check_output`]) and
//!   [`Guard::passed`] tests `s − s == 0`, true exactly when the sum is
//!   finite: it refuses every update with a non-finite output, and accepts
//!   every update whose outputs are all below `MAX/8` (a finite sum of at
//!   most eight of them cannot overflow). `f32` refuses exactly the updates
//!   with a NaN or infinite output, with an integer test of each output's
//!   exponent field on the M0/M3 (where a sum would cost a library call per
//!   output) and `check + 0·output` on the M4F's FPU ([`super::f32_check`]);
//! * Q32.32 ([`crate::Fix`]): a sum of valid values near 2³¹ could
//!   saturate, so its guard keeps zero while every output is valid and a
//!   sentinel otherwise ([`Scalar::accumulate_check`]);
//! * the fast fixed point ([`super::fixed32`]): products and sums are formed
//!   in 64 bits and narrowed once; a result that does not fit its format,
//!   or an input that is a saturation sentinel ([`Checked::check_input`]),
//!   raises the guard's flag. Nothing is sticky there, which is why every
//!   operation reports to the guard.

use core::fmt;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::{NumError, Scalar};

/// `defmt::Format` when the `defmt` feature is on, nothing otherwise: lets
/// the quantity types carry the bound the derived `Format` impls need.
#[cfg(feature = "defmt")]
pub trait MaybeFormat: defmt::Format {}
#[cfg(feature = "defmt")]
impl<T: defmt::Format> MaybeFormat for T {}
/// See the `defmt` variant.
#[cfg(not(feature = "defmt"))]
pub trait MaybeFormat {}
#[cfg(not(feature = "defmt"))]
impl<T> MaybeFormat for T {}

/// A value of one physical quantity in one number system (a position, a
/// speed, a gain, ...). Arithmetic never panics and never wraps: a result
/// outside the representable range is an invalid value ([`Self::is_valid`]),
/// which propagates through later operators (it is sticky).
pub trait Quantity:
    Copy
    + Default
    + PartialEq
    + PartialOrd
    + fmt::Debug
    + Send
    + Sync
    + 'static
    + MaybeFormat
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
{
    /// Zero of this quantity.
    const ZERO: Self;

    /// Rounding model of this quantity, used by the error budget
    /// ([`crate::budget`]): a result rounded to this quantity errs by at most
    /// `UNIT_ROUNDOFF·|exact| + ABS_RESOLUTION`, a conversion from `f64` by at
    /// most `UNIT_ROUNDOFF·|v| + ABS_RESOLUTION/2`, and a sum of two values of
    /// this quantity by at most `UNIT_ROUNDOFF·|exact|`.
    const UNIT_ROUNDOFF: f64;
    /// See [`Self::UNIT_ROUNDOFF`].
    const ABS_RESOLUTION: f64;
    /// Whether the rounding is relative over a wide range (floats, the
    /// [`super::scaled::Scaled`] formats: `UNIT_ROUNDOFF` > 0), so products
    /// of large quantities neither overflow nor lose resolution and a
    /// reciprocal keeps its digits; false for the fixed formats (Q32.32,
    /// `Fixed32`'s words), whose rounding is absolute. A constant: tests
    /// on it are compiled out.
    const RELATIVE_PRECISION: bool = Self::UNIT_ROUNDOFF > 0.0;

    /// Converts an outside value (SI units), refusing NaN, infinities and
    /// values beyond the representable range.
    fn try_from_f64(v: f64) -> Result<Self, NumError>;

    /// Converts a constant, rounding to nearest; out-of-range values become
    /// invalid values.
    fn from_f64_lossy(v: f64) -> Self;

    /// A time in milliseconds as seconds, `ms / 1000` rounded to nearest:
    /// by default through `f64`; `f32` divides in `f32` (the same value for
    /// every `ms` ≤ 2²⁴) and the [`super::scaled::Scaled`] formats divide
    /// their integers, so no double-precision library call on a core
    /// without a double-precision FPU.
    #[inline]
    fn seconds_from_ms(ms: u32) -> Self {
        Self::from_f64_lossy(f64::from(ms) / 1000.0)
    }

    /// The value in SI units (an invalid value gives ±∞ or NaN).
    fn to_f64(self) -> f64;

    /// False for NaN, ±∞ and the fixed-point saturation sentinels.
    fn is_valid(self) -> bool;

    /// [`Self::is_valid`] and > 0 (the filters' test of an interval).
    #[inline]
    fn is_valid_and_positive(self) -> bool {
        self.is_valid() && self > Self::ZERO
    }

    /// Absolute value (invalid stays invalid).
    fn abs(self) -> Self;

    /// Half the value (exact in floating formats, rounded to nearest in
    /// fixed formats).
    fn half(self) -> Self;

    /// The smaller of two valid values.
    #[inline]
    fn min_of(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }

    /// The larger of two valid values.
    #[inline]
    fn max_of(self, other: Self) -> Self {
        if other > self {
            other
        } else {
            self
        }
    }
}

/// A dimensionless real number with a wide range: gains, ratios, sines.
pub trait Real: Quantity + Mul<Output = Self> + Div<Output = Self> {
    /// One.
    const ONE: Self;

    /// `numerator / denominator`, rounded once (invalid for a zero
    /// denominator). Used for the gain formulas of integer counts.
    fn from_ratio(numerator: u64, denominator: u64) -> Self;

    /// Square root; invalid for a negative argument.
    fn sqrt(self) -> Self;

    /// √(a² + b²) without forming a² (the larger magnitude times
    /// √(1 + k²), k ≤ 1); invalid arguments give an invalid result.
    fn hypot(self, other: Self) -> Self {
        let (a, b) = (self.abs(), other.abs());
        if !(a.is_valid() && b.is_valid()) {
            return a + b;
        }
        let (large, small) = if a >= b { (a, b) } else { (b, a) };
        if large == Self::ZERO {
            return small;
        }
        let k = small / large;
        large * (Self::ONE + k * k).sqrt()
    }

    /// √(a² + b² + c²) without forming the squares: two hypots (a format
    /// may do it with one square root).
    fn hypot3(self, b: Self, c: Self) -> Self {
        self.hypot(b).hypot(c)
    }

    /// Whether every value is valid: [`Quantity::is_valid`] of each, or a
    /// format's cheaper running check (a [`Scalar`]'s
    /// [`Scalar::accumulate_check`]).
    #[inline(always)]
    fn all_valid<const K: usize>(values: [Self; K]) -> bool {
        values.iter().all(|v| v.is_valid())
    }
}

/// The hot path's validity check (see the module docs).
pub trait Guard: Default + fmt::Debug {
    /// True when every value reported to the guard is valid.
    fn passed(&self) -> bool;
}

/// How a value reports itself to its number system's [`Guard`].
pub trait Checked<G> {
    /// An input of the computation (a measurement): fixed point flags a
    /// saturation sentinel; floats need nothing (every input reaches an
    /// output, and NaN/∞ are sticky).
    fn check_input(self, guard: &mut G);
    /// A result that will be stored or returned: floats fold it into the
    /// guard's check ([`Scalar::accumulate_check`]); fixed point needs
    /// nothing (its operations report).
    fn check_output(self, guard: &mut G);
}

/// `self + a·b`, rounded once, with overflow reported to the guard `G`.
pub trait AddProduct<A, B, G>: Sized {
    /// `self + a·b`; marks `guard` if the result does not fit.
    fn add_product(self, a: A, b: B, guard: &mut G) -> Self;
}

/// `self − b`, with overflow reported to the guard `G`.
pub trait SubGuarded<G>: Sized {
    /// `self − b`; marks `guard` if the result does not fit.
    fn sub_guarded(self, b: Self, guard: &mut G) -> Self;
}

/// A number system: one type per quantity the filters use, and the
/// operations between them (the bounds below are the whole algebra a
/// generic filter may use).
///
/// `f64`, `f32` and Q32.32 implement it with every quantity the type itself
/// (the blanket implementation over [`Scalar`]); the fast fixed point
/// ([`super::fixed32::Fixed32`]) with a format per quantity.
pub trait Numeric:
    Copy + Default + fmt::Debug + PartialEq + Send + Sync + 'static + MaybeFormat
{
    /// Short name for reports: "f64", "f32", "q32", "fixed".
    const NAME: &'static str;

    /// Whether [`AddProduct`] forms `q + a·b` in a wider word and checks
    /// only the sum (the fast fixed point), rather than rounding and
    /// checking the product on its own (the sticky operators): the error
    /// budget's range checks follow it.
    const FUSED_PRODUCTS: bool = false;

    /// Metres (feet where a tracker works in feet): positions, residuals.
    /// `From<Ratio>` reads a number of metres (invalid beyond the range).
    type Length: Quantity
        + From<Self::Ratio>
        + Checked<Self::Guard>
        + SubGuarded<Self::Guard>
        + AddProduct<Self::Speed, Self::Interval, Self::Guard>
        + AddProduct<Self::Acceleration, Self::IntervalSquared, Self::Guard>
        + AddProduct<Self::Gain, Self::Length, Self::Guard>
        + Div<Self::Interval, Output = Self::Speed>
        + Div<Self::Length, Output = Self::Ratio>;
    /// Metres per second. `From<Ratio>` reads a number of m/s (invalid
    /// beyond the range).
    type Speed: Quantity
        + From<Self::Ratio>
        + Checked<Self::Guard>
        + AddProduct<Self::Acceleration, Self::Interval, Self::Guard>
        + AddProduct<Self::Rate, Self::Length, Self::Guard>
        + Mul<Self::Interval, Output = Self::Length>;
    /// Metres per second².
    type Acceleration: Quantity
        + Checked<Self::Guard>
        + AddProduct<Self::RateSquared, Self::Length, Self::Guard>
        + Mul<Self::Interval, Output = Self::Speed>
        + Mul<Self::IntervalSquared, Output = Self::Length>;
    /// Seconds: the interval T between updates.
    type Interval: Quantity + Mul<Self::Interval, Output = Self::IntervalSquared>;
    /// Seconds², e.g. T²/2 of the αβγ prediction.
    type IntervalSquared: Quantity;
    /// Dimensionless: the gains α, β, γ and ratios. `From<Length>` gives a
    /// length's number of metres (for sums of squares, which would
    /// overflow a length format).
    type Ratio: Real
        + From<Self::Length>
        + From<Self::Interval>
        + Mul<Self::Length, Output = Self::Length>
        + Mul<Self::Speed, Output = Self::Speed>
        + Div<Self::Interval, Output = Self::Rate>
        + Div<Self::IntervalSquared, Output = Self::RateSquared>;
    /// A gain of the per-update path, |g| < 8, where a fixed format is
    /// enough (the smoothing gain α, in (0, 2)); [`Self::gain`] converts.
    type Gain: Quantity;
    /// Per second: the velocity gain β/T. `From<Ratio>` reads a ratio
    /// computed in 1/s (a covariance's velocity gain) as a rate.
    type Rate: Quantity + From<Self::Ratio> + Mul<Self::Length, Output = Self::Speed>;
    /// Per second²: the acceleration gain γ/(2T²).
    type RateSquared: Quantity + Mul<Self::Length, Output = Self::Acceleration>;
    /// Radians: azimuths.
    type Angle: Quantity;
    /// The hot path's validity check (module docs).
    type Guard: Guard;

    /// (sin θ, cos θ).
    fn sin_cos(theta: Self::Angle) -> (Self::Ratio, Self::Ratio);

    /// The azimuth of (x, y), clockwise from the y axis, in [0, 2π).
    fn azimuth(x: Self::Length, y: Self::Length) -> Self::Angle;

    /// A [`Self::Ratio`] as a [`Self::Gain`] (invalid beyond the gain's
    /// range).
    fn gain(r: Self::Ratio) -> Self::Gain;

    /// √(a² + b²), never overflowing on the way (invalid arguments give an
    /// invalid result).
    fn hypot(a: Self::Length, b: Self::Length) -> Self::Length;
}

// ---------------------------------------------------------------------------
// f64, f32 and Q32.32: every quantity is the scalar type itself.

/// The [`Guard`] of a [`Scalar`]: a running check of the outputs, folded
/// by [`Scalar::accumulate_check`] (their sum, or for `f32` the check word
/// of [`super::f32_check`]; module docs).
#[derive(Debug, Clone, Copy, Default)]
pub struct ScalarGuard<S> {
    check: S,
}

impl<S: Scalar> Guard for ScalarGuard<S> {
    /// [`Scalar::check_passed`]: for the sum, `s − s == 0` exactly when `s`
    /// is finite (module docs).
    #[inline]
    fn passed(&self) -> bool {
        S::check_passed(self.check)
    }
}

impl<S: Scalar> Checked<ScalarGuard<S>> for S {
    #[inline]
    fn check_input(self, _guard: &mut ScalarGuard<S>) {}
    #[inline]
    fn check_output(self, guard: &mut ScalarGuard<S>) {
        guard.check = S::accumulate_check(guard.check, self);
    }
}

impl<S: Scalar> AddProduct<S, S, ScalarGuard<S>> for S {
    #[inline]
    fn add_product(self, a: S, b: S, _guard: &mut ScalarGuard<S>) -> S {
        self + a * b
    }
}

impl<S: Scalar> SubGuarded<ScalarGuard<S>> for S {
    #[inline]
    fn sub_guarded(self, b: S, _guard: &mut ScalarGuard<S>) -> S {
        self - b
    }
}

impl<S: Scalar> Quantity for S {
    const ZERO: Self = <S as Scalar>::ZERO;
    const UNIT_ROUNDOFF: f64 = <S as Scalar>::UNIT_ROUNDOFF;
    const ABS_RESOLUTION: f64 = <S as Scalar>::ABS_RESOLUTION;

    #[inline]
    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        <S as Scalar>::try_from_f64(v)
    }
    #[inline]
    fn from_f64_lossy(v: f64) -> Self {
        <S as Scalar>::from_f64_lossy(v)
    }
    #[inline]
    fn seconds_from_ms(ms: u32) -> Self {
        <S as Scalar>::seconds_from_ms(ms)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        <S as Scalar>::to_f64(self)
    }
    #[inline]
    fn is_valid(self) -> bool {
        <S as Scalar>::is_valid(self)
    }
    #[inline]
    fn is_valid_and_positive(self) -> bool {
        <S as Scalar>::is_valid_and_positive(self)
    }
    #[inline]
    fn abs(self) -> Self {
        <S as Scalar>::abs(self)
    }
    #[inline]
    fn half(self) -> Self {
        self * <S as Scalar>::from_f64_lossy(0.5)
    }
}

impl<S: Scalar> Real for S {
    const ONE: Self = <S as Scalar>::ONE;

    /// One running check over the values ([`Scalar::accumulate_check`]).
    #[inline(always)]
    fn all_valid<const K: usize>(values: [Self; K]) -> bool {
        S::check_passed(
            values
                .iter()
                .fold(<S as Scalar>::ZERO, |c, &v| S::accumulate_check(c, v)),
        )
    }

    /// [`Scalar::from_ratio`]: rounded once (through `f64` but in `f32`).
    #[inline]
    fn from_ratio(numerator: u64, denominator: u64) -> Self {
        <S as Scalar>::from_ratio(numerator, denominator)
    }

    #[inline]
    fn sqrt(self) -> Self {
        <S as Scalar>::sqrt(self)
    }

    #[inline]
    fn hypot(self, other: Self) -> Self {
        <S as Scalar>::hypot_pair(self, other)
    }

    #[inline]
    fn hypot3(self, b: Self, c: Self) -> Self {
        <S as Scalar>::hypot_triple(self, b, c)
    }
}

impl<S: Scalar> Numeric for S {
    const NAME: &'static str = <S as Scalar>::NAME;
    type Length = S;
    type Speed = S;
    type Acceleration = S;
    type Interval = S;
    type IntervalSquared = S;
    type Ratio = S;
    type Gain = S;
    type Rate = S;
    type RateSquared = S;
    type Angle = S;
    type Guard = ScalarGuard<S>;

    #[inline]
    fn sin_cos(theta: S) -> (S, S) {
        <S as Scalar>::sin_cos(theta)
    }

    #[inline]
    fn azimuth(x: S, y: S) -> S {
        super::azimuth_of(x, y)
    }

    #[inline]
    fn gain(r: S) -> S {
        r
    }

    #[inline]
    fn hypot(a: S, b: S) -> S {
        super::hypot(a, b)
    }
}
