//! The fast fixed point ([`Fixed32`]): 32-bit words with a format per
//! quantity, products through 64 bits, saturation instead of wrapping. Made
//! for cores without an FPU (Cortex-M0/M3), where it replaces both soft
//! floats and Q32.32 ([`crate::Fix`]). The formats, the envelope they hold
//! and the rounding model are in `docs/numerics-fixed-point.md`.
//!
//! | quantity | type | format | range | resolution |
//! |---|---|---|---|---|
//! | length (m) | [`Length`] | I20F12 | ±524 288 | 2.4·10⁻⁴ |
//! | speed (m/s) | [`Speed`] | I14F18 | ±8 192 | 3.8·10⁻⁶ |
//! | acceleration (m/s²) | [`Acceleration`] | I14F18 | ±8 192 | 3.8·10⁻⁶ |
//! | interval (s) | [`Interval`] | I8F24 | ±128 | 6.0·10⁻⁸ |
//! | α in the per-update path | [`Gain`] | I4F28 | ±8 | 3.7·10⁻⁹ |
//! | gains, ratios | [`Ratio`] | [`Scaled`] | 2⁻¹⁷⁰…2¹³¹ | 2⁻³⁰ relative |
//! | β/T (1/s) | [`Rate`] | [`Scaled`] | | 2⁻³⁰ relative |
//! | γ/(2T²) (1/s²) | [`RateSquared`] | [`Scaled`] | | 2⁻³⁰ relative |
//! | T² (s²) | [`IntervalSquared`] | [`Scaled`] | | 2⁻³⁰ relative |
//!
//! A fixed-format word equal to `i32::MIN` or `i32::MAX` is a saturation
//! sentinel (invalid), as for Q32.32. The operators are sticky: an invalid
//! operand or a result out of range gives a sentinel. The guarded operations
//! of the filters' hot path ([`AddProduct`], [`Quantity::sub_guarded`]) instead form
//! the whole `q + a·b` in 64 bits, round the product once (to nearest) and
//! raise the [`Fixed32Guard`]'s flag if the result does not fit.

use core::fmt;
use core::ops::{Add, Div, Mul, Neg, Sub};

use fixed::types::{I14F18, I20F12, I4F28, I8F24};

use super::numeric::{AddProduct, Numeric, Quantity};
use super::scaled::{isqrt_u64, unit, Scaled};
use super::wide::{wide_mul, wide_mul_signed_unsigned, wide_mul_unsigned};
use super::NumError;
use crate::track::numeric::fixed as fixed_track;
use crate::track::numeric::{FixedGridScale, FixedVariance};

/// Dimensionless gains and ratios.
pub type Ratio = Scaled<unit::One>;
/// 1/s: the velocity gain β/T.
pub type Rate = Scaled<unit::PerSecond>;
/// 1/s²: the acceleration gain γ/(2T²).
pub type RateSquared = Scaled<unit::PerSecondSquared>;
/// s².
pub type IntervalSquared = Scaled<unit::SecondSquared>;
/// Radians.
pub type Angle = Scaled<unit::Radian>;

/// The fast fixed-point number system (module docs).
///
/// Values enter and leave through [`Quantity`]'s conversions, in SI units,
/// rounded to the quantity's format:
///
/// ```
/// use abtrack::num::fixed32::{Fixed32, Length, Speed};
/// use abtrack::{NumError, Numeric, Quantity};
///
/// let x: <Fixed32 as Numeric>::Length = Length::try_from_f64(1234.5678)?;
/// assert_eq!(Length::FRAC_BITS, 12); // I20F12: steps of 2⁻¹² m
/// assert!((x.to_f64() - 1234.5678).abs() <= 0.5 / 4096.0);
/// assert_eq!(x.to_bits(), (1234.5678f64 * 4096.0).round() as i32);
/// // Beyond ±524 288 m, or not a number: refused, never wrapped.
/// assert_eq!(Length::try_from_f64(6.0e5), Err(NumError::OutOfRange));
/// assert_eq!(Speed::try_from_f64(f64::NAN), Err(NumError::NotFinite));
/// // A result out of range is a sticky sentinel, caught by `is_valid`.
/// let far = Length::try_from_f64(500_000.0)?;
/// assert!(!(far + far).is_valid());
/// assert!(!(far + far - far).is_valid());
/// # Ok::<(), NumError>(())
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Fixed32;

/// The hot path's overflow flag (see [`super::numeric`]): nonzero once a
/// result did not fit its word, or an input or output is a sentinel.
#[derive(Debug, Clone, Copy, Default)]
pub struct Fixed32Guard {
    bad: u32,
}

impl Fixed32Guard {
    /// `wide` as a word; marks the guard when it does not fit an `i32`
    /// (the high word is not the low word's sign extension). A result that
    /// fits but is a sentinel is caught by [`Quantity::check_output`].
    #[inline(always)]
    pub(crate) fn narrow(&mut self, wide: i64) -> i32 {
        let low = wide as i32;
        let high = (wide >> 32) as i32;
        self.bad |= (high ^ (low >> 31)) as u32;
        low
    }

    /// Marks the guard if `bits` is a sentinel: `bits ^ (bits >> 31)` is
    /// `i32::MAX` exactly for the two sentinels, and adding one then sets
    /// the sign bit.
    #[inline(always)]
    pub(crate) fn reject_sentinel(&mut self, bits: i32) {
        self.bad |= ((bits ^ (bits >> 31)).wrapping_add(1) as u32) >> 31;
    }

    /// Marks the guard if `invalid`.
    #[inline(always)]
    pub(crate) fn reject_if(&mut self, invalid: bool) {
        self.bad |= u32::from(invalid);
    }

    /// `wide / 2^shift` rounded to nearest for the hot path's products by a
    /// [`Scaled`] coefficient (|wide| < 2⁶²): a shift below 1 would mean a
    /// coefficient of 2³⁰ or more, which marks the guard; shifts above 62
    /// round to 0 or ±1, within a step of the exact (tiny) product.
    #[inline(always)]
    fn shift_round(&mut self, wide: i64, shift: i32) -> i64 {
        // shift − 1 < 0 sets the sign bit; the shift below is then masked
        // (wrapping), its result meaningless, and the guard already marked.
        let minus_one = shift.wrapping_sub(1).min(61);
        self.bad |= (minus_one as u32) >> 31;
        wide.wrapping_shr(minus_one as u32).wrapping_add(1) >> 1
    }
}

impl Fixed32Guard {
    /// True when every value reported to the guard is valid and every
    /// result fitted its word ([`Numeric::passed`] of [`Fixed32`]).
    #[inline]
    pub fn passed(&self) -> bool {
        self.bad == 0
    }
}

#[inline(always)]
const fn is_sentinel(bits: i32) -> bool {
    bits == i32::MIN || bits == i32::MAX
}

/// `wide` as a word, a sentinel of its sign when it does not fit.
#[inline]
const fn saturate(wide: i64) -> i32 {
    if wide >= i32::MAX as i64 {
        i32::MAX
    } else if wide <= i32::MIN as i64 {
        i32::MIN
    } else {
        wide as i32
    }
}

/// The sentinel with the sign of `wide`.
#[inline]
const fn sentinel(negative: bool) -> i32 {
    if negative {
        i32::MIN
    } else {
        i32::MAX
    }
}

/// `wide / 2^shift` rounded to nearest (ties toward +∞) for a shift in
/// 1..=62 known at compile time and |wide| < 2⁶²: one 64-bit addition and a
/// shift (for a shift of 32 the result is the high word).
#[inline(always)]
const fn shift_round_const(wide: i64, shift: u32) -> i64 {
    // shift ∈ 1..=62: the subtraction cannot wrap.
    wide.wrapping_add(1 << shift.wrapping_sub(1)) >> shift
}

/// `wide / 2^shift` rounded to nearest (ties toward +∞), for |wide| < 2⁶²
/// and any shift; a negative shift multiplies by 2^−shift, saturating at
/// ±2⁶² (which no word can absorb, so a narrowing refuses it).
#[inline(always)]
fn shift_round(wide: i64, shift: i32) -> i64 {
    const LIMIT: i64 = 1 << 62;
    if shift > 0 {
        if shift >= 63 {
            0
        } else {
            // |wide >> (shift − 1)| < 2⁶²: adding one cannot overflow.
            (wide >> shift.wrapping_sub(1)).wrapping_add(1) >> 1
        }
    } else if shift == 0 {
        wide
    } else {
        let left = shift.unsigned_abs();
        if wide == 0 {
            0
        } else if left >= 62 || wide.unsigned_abs() >= (LIMIT as u64) >> left {
            if wide < 0 {
                -LIMIT
            } else {
                LIMIT
            }
        } else {
            wide << left
        }
    }
}

macro_rules! fixed_quantity {
    ($name:ident, $fixed:ty, $frac:expr, $what:literal) => {
        #[doc = concat!($what, ": a `", stringify!($fixed), "` word (see the module docs).")]
        #[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name(i32);

        impl $name {
            /// Number of fractional bits.
            pub const FRAC_BITS: u32 = $frac;
            /// Positive saturation sentinel (invalid).
            pub const MAX: Self = $name(i32::MAX);
            /// Negative saturation sentinel (invalid).
            pub const MIN: Self = $name(i32::MIN);
            /// One step, 2^−FRAC_BITS.
            pub const DELTA: Self = $name(1);

            /// The raw word (value × 2^FRAC_BITS).
            #[inline]
            pub const fn to_bits(self) -> i32 {
                self.0
            }

            /// From a raw word; `i32::MIN`/`MAX` are the sentinels.
            #[inline]
            pub const fn from_bits(bits: i32) -> Self {
                $name(bits)
            }

            /// The value as the `fixed` crate's type.
            #[inline]
            pub const fn to_fixed(self) -> $fixed {
                <$fixed>::from_bits(self.0)
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self.0 {
                    i32::MAX => write!(f, "{}(+SAT)", stringify!($name)),
                    i32::MIN => write!(f, "{}(-SAT)", stringify!($name)),
                    _ => write!(f, "{}({})", stringify!($name), self.to_fixed()),
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Display::fmt(&self.to_fixed(), f)
            }
        }

        #[cfg(feature = "defmt")]
        impl defmt::Format for $name {
            fn format(&self, f: defmt::Formatter) {
                if is_sentinel(self.0) {
                    defmt::write!(f, "SAT")
                } else {
                    defmt::write!(f, "{=f64}", Quantity::to_f64(*self))
                }
            }
        }

        impl Add for $name {
            type Output = Self;
            #[inline]
            fn add(self, rhs: Self) -> Self {
                let wide = i64::from(self.0).wrapping_add(i64::from(rhs.0));
                if is_sentinel(self.0) || is_sentinel(rhs.0) {
                    return $name(sentinel(wide < 0));
                }
                $name(saturate(wide))
            }
        }

        impl Sub for $name {
            type Output = Self;
            #[inline]
            fn sub(self, rhs: Self) -> Self {
                self + (-rhs)
            }
        }

        impl Neg for $name {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                // The valid range is symmetric; the sentinels swap.
                match self.0 {
                    i32::MAX => Self::MIN,
                    i32::MIN => Self::MAX,
                    v => $name(v.wrapping_neg()),
                }
            }
        }

        impl Quantity for $name {
            const ZERO: Self = $name(0);
            const UNIT_ROUNDOFF: f64 = 0.0;
            const ABS_RESOLUTION: f64 = 1.0 / (1u64 << $frac) as f64;
            type Guard = Fixed32Guard;

            fn try_from_f64(v: f64) -> Result<Self, NumError> {
                if !v.is_finite() {
                    return Err(NumError::NotFinite);
                }
                match <$fixed>::checked_from_num(v) {
                    Some(x) if !is_sentinel(x.to_bits()) => Ok($name(x.to_bits())),
                    _ => Err(NumError::OutOfRange),
                }
            }

            fn from_f64_lossy(v: f64) -> Self {
                if v.is_nan() {
                    return Self::MAX;
                }
                match <$fixed>::checked_from_num(v) {
                    Some(x) => $name(x.to_bits()),
                    None => $name(sentinel(v < 0.0)),
                }
            }

            /// ms·2^FRAC_BITS/1000 rounded to nearest in integers (no
            /// double-precision library call; a constant `ms` folds to a
            /// constant).
            #[inline]
            fn seconds_from_ms(ms: u32) -> Self {
                // ms < 2³², so ms·2^FRAC_BITS < 2⁶⁴ for FRAC_BITS ≤ 32.
                let scaled = (u64::from(ms) << $frac).saturating_add(500) / 1000;
                $name(saturate(i64::try_from(scaled).unwrap_or(i64::MAX)))
            }

            #[inline]
            fn to_f64(self) -> f64 {
                match self.0 {
                    i32::MAX => f64::INFINITY,
                    i32::MIN => f64::NEG_INFINITY,
                    v => f64::from(v) / (1u64 << $frac) as f64,
                }
            }

            #[inline]
            fn is_valid(self) -> bool {
                !is_sentinel(self.0)
            }

            #[inline]
            fn abs(self) -> Self {
                if is_sentinel(self.0) {
                    Self::MAX
                } else {
                    $name(self.0.wrapping_abs())
                }
            }

            #[inline]
            fn half(self) -> Self {
                if is_sentinel(self.0) {
                    self
                } else {
                    $name(shift_round(i64::from(self.0), 1) as i32)
                }
            }

            #[inline(always)]
            fn check_input(self, guard: &mut Fixed32Guard) {
                guard.reject_sentinel(self.0);
            }
            #[inline(always)]
            fn check_output(self, guard: &mut Fixed32Guard) {
                guard.reject_sentinel(self.0);
            }
            #[inline(always)]
            fn sub_guarded(self, b: Self, guard: &mut Fixed32Guard) -> Self {
                $name(guard.narrow(i64::from(self.0).wrapping_sub(i64::from(b.0))))
            }
        }
    };
}

fixed_quantity!(Length, I20F12, 12, "A length in metres");
fixed_quantity!(Speed, I14F18, 18, "A speed in m/s");
fixed_quantity!(Acceleration, I14F18, 18, "An acceleration in m/s²");
fixed_quantity!(Interval, I8F24, 24, "An interval in seconds");
fixed_quantity!(Gain, I4F28, 28, "A gain of the per-update path (α)");

/// Fixed × fixed → fixed: the product of the words, rounded from
/// `F_a + F_b` to `F_out` fractional bits.
macro_rules! fixed_times_fixed {
    ($($a:ident * $b:ident => $out:ident;)*) => {$(
        impl Mul<$b> for $a {
            type Output = $out;
            #[inline]
            fn mul(self, rhs: $b) -> $out {
                let product = wide_mul(self.0, rhs.0);
                if is_sentinel(self.0) || is_sentinel(rhs.0) {
                    return $out(sentinel(product < 0));
                }
                let shift = ($a::FRAC_BITS + $b::FRAC_BITS - $out::FRAC_BITS) as i32;
                $out(saturate(shift_round(product, shift)))
            }
        }

        impl AddProduct<$a, $b> for $out {
            #[inline(always)]
            fn add_product(self, a: $a, b: $b, guard: &mut Fixed32Guard) -> $out {
                let product = wide_mul(a.0, b.0);
                const SHIFT: u32 = $a::FRAC_BITS + $b::FRAC_BITS - $out::FRAC_BITS;
                // |product| < 2⁶², shifted ≥ 1 bit: the sum fits an i64.
                let term = shift_round_const(product, SHIFT);
                $out(guard.narrow(i64::from(self.0).wrapping_add(term)))
            }
        }
    )*};
}

fixed_times_fixed! {
    Gain * Length => Length;
    Speed * Interval => Length;
    Acceleration * Interval => Speed;
}

/// Scaled × fixed → fixed: one 32×32→64 product of the mantissa and the
/// word, shifted by the scaled value's exponent.
macro_rules! fixed_times_scaled {
    ($($a:ty, $b:ident => $out:ident;)*) => {$(
        impl Mul<$b> for $a {
            type Output = $out;
            #[inline]
            fn mul(self, rhs: $b) -> $out {
                if self.is_invalid() || is_sentinel(rhs.0) {
                    let negative = (self.mantissa() < 0) != (rhs.0 < 0);
                    return $out(sentinel(negative));
                }
                let product = wide_mul(self.mantissa(), rhs.0);
                let shift = ($b::FRAC_BITS as i32).wrapping_sub($out::FRAC_BITS as i32).wrapping_sub(self.exponent());
                $out(saturate(shift_round(product, shift)))
            }
        }

        impl AddProduct<$a, $b> for $out {
            #[inline(always)]
            fn add_product(self, a: $a, b: $b, guard: &mut Fixed32Guard) -> $out {
                let product = wide_mul(a.mantissa(), b.0);
                let shift = ($b::FRAC_BITS as i32).wrapping_sub($out::FRAC_BITS as i32).wrapping_sub(a.exponent());
                // |shifted product| < 2⁶²: the sum fits an i64.
                let term = guard.shift_round(product, shift);
                $out(guard.narrow(i64::from(self.0).wrapping_add(term)))
            }
        }
    )*};
}

fixed_times_scaled! {
    Ratio, Length => Length;
    Ratio, Speed => Speed;
    Rate, Length => Speed;
    RateSquared, Length => Acceleration;
}

// Acceleration × T² (the αβγ prediction's a·T²/2): the same product with the
// fixed operand on the left.
impl Mul<IntervalSquared> for Acceleration {
    type Output = Length;
    #[inline]
    fn mul(self, rhs: IntervalSquared) -> Length {
        if rhs.is_invalid() || is_sentinel(self.0) {
            let negative = (rhs.mantissa() < 0) != (self.0 < 0);
            return Length(sentinel(negative));
        }
        let product = wide_mul(rhs.mantissa(), self.0);
        let shift = (Acceleration::FRAC_BITS as i32)
            .wrapping_sub(Length::FRAC_BITS as i32)
            .wrapping_sub(rhs.exponent());
        Length(saturate(shift_round(product, shift)))
    }
}

impl AddProduct<Acceleration, IntervalSquared> for Length {
    #[inline(always)]
    fn add_product(self, a: Acceleration, b: IntervalSquared, guard: &mut Fixed32Guard) -> Length {
        let product = wide_mul(b.mantissa(), a.0);
        let shift = (Acceleration::FRAC_BITS as i32)
            .wrapping_sub(Length::FRAC_BITS as i32)
            .wrapping_sub(b.exponent());
        let term = guard.shift_round(product, shift);
        Length(guard.narrow(i64::from(self.0).wrapping_add(term)))
    }
}

impl Mul for Interval {
    type Output = IntervalSquared;
    #[inline]
    fn mul(self, rhs: Interval) -> IntervalSquared {
        if is_sentinel(self.0) || is_sentinel(rhs.0) {
            return IntervalSquared::INVALID;
        }
        let product = wide_mul(self.0, rhs.0);
        IntervalSquared::from_wide(product, (Interval::FRAC_BITS as i32).wrapping_mul(-2))
    }
}

impl Interval {
    /// The interval as a [`Scaled`] number of seconds.
    fn scaled<U>(self) -> Scaled<U> {
        if is_sentinel(self.0) {
            Scaled::INVALID
        } else {
            Scaled::from_wide(
                i64::from(self.0),
                (Interval::FRAC_BITS as i32).wrapping_neg(),
            )
        }
    }
}

impl Div<Interval> for Ratio {
    type Output = Rate;
    #[inline]
    fn div(self, rhs: Interval) -> Rate {
        let quotient: Ratio = self / rhs.scaled::<unit::One>();
        quotient.cast()
    }
}

impl Div<Interval> for Length {
    type Output = Speed;
    /// Rounded to nearest; division by zero saturates with the numerator's
    /// sign.
    #[inline]
    fn div(self, rhs: Interval) -> Speed {
        if is_sentinel(self.0) || is_sentinel(rhs.0) || rhs.0 == 0 {
            return Speed(sentinel((self.0 < 0) != (rhs.0 < 0)));
        }
        // Length·2^(F_speed + F_interval − F_length) < 2⁵⁹.
        let shift = Speed::FRAC_BITS + Interval::FRAC_BITS - Length::FRAC_BITS;
        let numerator = i64::from(self.0) << shift;
        let divisor = i64::from(rhs.0);
        // Round half away from zero: add half the divisor's magnitude in the
        // numerator's direction (|numerator| + |divisor|/2 < 2⁶³).
        let half = divisor.unsigned_abs() as i64 / 2;
        let biased = if numerator < 0 {
            numerator.wrapping_sub(half)
        } else {
            numerator.wrapping_add(half)
        };
        Speed(saturate(biased.checked_div(divisor).unwrap_or(i64::MAX)))
    }
}

impl Div for Length {
    type Output = Ratio;
    #[inline]
    fn div(self, rhs: Length) -> Ratio {
        if is_sentinel(self.0) || is_sentinel(rhs.0) {
            return Ratio::INVALID;
        }
        Ratio::from_int(i64::from(self.0)) / Ratio::from_int(i64::from(rhs.0))
    }
}

impl From<Length> for Ratio {
    /// The number of metres (a sentinel gives the invalid value).
    fn from(l: Length) -> Ratio {
        if is_sentinel(l.0) {
            Ratio::INVALID
        } else {
            Ratio::from_wide(i64::from(l.0), (Length::FRAC_BITS as i32).wrapping_neg())
        }
    }
}

/// A scaled number as a fixed-format word with `frac` fractional bits,
/// rounded to nearest; a sentinel when invalid or out of range.
fn scaled_to_word<U>(v: Scaled<U>, frac: u32) -> i32 {
    if v.is_invalid() {
        return i32::MAX;
    }
    // frac ≤ 32 and the exponent is an i16: no wrap.
    let shift = (frac as i32).wrapping_neg().wrapping_sub(v.exponent());
    saturate(shift_round(i64::from(v.mantissa()), shift))
}

impl From<Ratio> for Length {
    /// A number of metres.
    fn from(r: Ratio) -> Length {
        Length(scaled_to_word(r, Length::FRAC_BITS))
    }
}

impl From<Ratio> for Speed {
    /// A number of m/s.
    fn from(r: Ratio) -> Speed {
        Speed(scaled_to_word(r, Speed::FRAC_BITS))
    }
}

impl From<Interval> for Ratio {
    /// The number of seconds.
    fn from(t: Interval) -> Ratio {
        t.scaled()
    }
}

impl From<Ratio> for Rate {
    /// A ratio computed in 1/s, as a rate.
    fn from(r: Ratio) -> Rate {
        r.cast()
    }
}

/// 2³⁴/(2π), rounded: radians to binary-angle units (2³² per turn), with
/// two extra bits (relative error 1.1·10⁻¹⁰).
const TURNS_PER_RADIAN_Q34: u32 = 2_734_261_102;

/// 2π in Q32.32.
const TWO_PI_Q32: i64 = 26_986_075_409;

/// The binary angle (2³² per turn) of a valid angle: any angle maps to one
/// direction (the reduction modulo a turn is the wrap of the u32).
pub(super) fn turns(theta: Angle) -> u32 {
    // θ·2³²/(2π) = m·2^e·C·2⁻² with C = 2³⁴/(2π); |m|·C < 2⁶³.
    let wide = wide_mul_signed_unsigned(theta.mantissa(), TURNS_PER_RADIAN_Q34);
    let shift = 2i32.wrapping_sub(theta.exponent());
    let turns = if shift >= 0 {
        shift_round(wide, shift)
    } else {
        // |θ| ≥ 2³¹·…: only the wrapped low bits are a direction.
        wide.wrapping_shl(shift.unsigned_abs())
    };
    turns as u32
}

impl Numeric for Fixed32 {
    const NAME: &'static str = "fixed";
    const FUSED_PRODUCTS: bool = true;
    type Length = Length;
    type Speed = Speed;
    type Acceleration = Acceleration;
    type Interval = Interval;
    type IntervalSquared = IntervalSquared;
    type Ratio = Ratio;
    type Gain = Gain;
    type Rate = Rate;
    type RateSquared = RateSquared;
    type Angle = Angle;
    type Guard = Fixed32Guard;
    type Wide = super::ScaledScalar;
    type Polar = f32;
    type CircleScale = ();
    type Variance = FixedVariance;
    type GridScale = FixedGridScale;
    const GRID_SCALE_ZERO: FixedGridScale = FixedGridScale::ZERO;

    #[inline]
    fn passed(guard: &Fixed32Guard) -> bool {
        guard.passed()
    }

    /// Table and Taylor correction on the binary angle ([`super::sine`]):
    /// within [`super::sine::SIN_COS_MAX_ERROR_Q31`]·2⁻³¹ of the sine and
    /// cosine of the binary angle, plus the rounding to 31-bit mantissas
    /// and the angle's conversion to turns (1.8·10⁻¹⁰ relative). An
    /// invalid angle gives invalid values.
    fn sin_cos(theta: Angle) -> (Ratio, Ratio) {
        if theta.is_invalid() {
            return (Ratio::INVALID, Ratio::INVALID);
        }
        let (s, c) = super::sine::sin_cos_q31(turns(theta));
        (Ratio::from_wide(s, -31), Ratio::from_wide(c, -31))
    }

    /// CORDIC in vectoring mode on the exact words (lengths in Q32.32 are
    /// the words shifted by 20 bits), within 2⁻³² rad plus the rounding to
    /// a 31-bit mantissa; a sentinel gives the invalid angle.
    fn azimuth(x: Length, y: Length) -> Angle {
        if is_sentinel(x.0) || is_sentinel(y.0) {
            return Angle::INVALID;
        }
        let shift = 32 - Length::FRAC_BITS;
        let a = super::cordic::atan2_bits(i64::from(x.0) << shift, i64::from(y.0) << shift);
        let a = if a < 0 { a.wrapping_add(TWO_PI_Q32) } else { a };
        let a = if a >= TWO_PI_Q32 { 0 } else { a };
        Angle::from_wide(a, -32)
    }

    /// Rounded to nearest; a sentinel beyond ±8.
    fn gain(r: Ratio) -> Gain {
        Gain(scaled_to_word(r, Gain::FRAC_BITS))
    }

    /// Exact to the nearest step: the sum of the squared words (below 2⁶³)
    /// and its integer square root.
    fn hypot(a: Length, b: Length) -> Length {
        if is_sentinel(a.0) || is_sentinel(b.0) {
            return Length::MAX;
        }
        let square = |v: i32| wide_mul_unsigned(v.unsigned_abs(), v.unsigned_abs());
        let sum = square(a.0).wrapping_add(square(b.0));
        Length(saturate(isqrt_u64(sum) as i64))
    }

    fn circle_scale(radius: Length) -> Option<()> {
        fixed_track::circle_scale(radius)
    }

    fn circle_cost(dx: Length, dy: Length, radius: Length, scale: ()) -> Option<u16> {
        fixed_track::circle_cost(dx, dy, radius, scale)
    }

    #[inline]
    fn circle_cost_at(z: [Length; 2], center: [Length; 2], reach: Length, _: ()) -> Option<u16> {
        fixed_track::circle_cost_at(z, center, reach)
    }

    #[inline]
    fn circle_bounds(center: [Length; 2], reach: Length) -> ([Length; 2], [Length; 2]) {
        fixed_track::circle_bounds(center, reach)
    }

    fn grid_scale(min: Length, max: Length, cells: u16) -> FixedGridScale {
        fixed_track::grid_scale(min, max, cells)
    }

    fn grid_cell(v: Length, min: Length, max: Length, scale: FixedGridScale) -> u32 {
        fixed_track::grid_cell(v, min, max, scale)
    }

    fn length_to_polar(v: Length) -> f32 {
        fixed_track::length_to_polar(v)
    }

    fn length_from_polar(v: f32) -> Length {
        fixed_track::length_from_polar(v)
    }

    fn ratio_to_polar(v: Ratio) -> f32 {
        fixed_track::ratio_to_polar(v)
    }

    fn ratio_from_polar(v: f32) -> Ratio {
        fixed_track::ratio_from_polar(v)
    }

    fn to_variance(r: Ratio) -> FixedVariance {
        FixedVariance::from_fixed_ratio(r)
    }

    fn from_variance(v: FixedVariance) -> Ratio {
        v.to_fixed_ratio()
    }
}
