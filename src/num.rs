//! The numeric representations, and the five number traits ([`numeric`]):
//!
//! | trait | its job |
//! |---|---|
//! | [`Quantity`] | one physical quantity's value: conversions, validity, its report to the hot path's guard |
//! | [`Real`] | a dimensionless number: ×, ÷, √, ratios, hypot |
//! | [`Numeric`] | a number system: a type per quantity, their algebra, the track table's few extra operations |
//! | [`AddProduct`] | the hot path's operator, `q + a·b` rounded once |
//! | [`Scalar`] | one type for every quantity (`f64`, `f32`, Q32.32 [`Fix`], [`ScaledScalar`]) |
//!
//! [`Fixed32`] ([`fixed32`]) is the fast fixed point, a [`Numeric`] with a
//! 32-bit format per quantity. This is the only module that knows how a
//! number is stored; every filter, schedule and tracker is generic over it.
//! The formats, the envelope and how to port code are in
//! `docs/numerics-fixed-point.md`.
//!
//! # Invalid values
//!
//! Every representation has values that mean "this computation left the
//! representable range": NaN and ±∞ for the floats, the two saturation
//! sentinels [`Fix::MAX`]/[`Fix::MIN`] for fixed point. [`Quantity::is_valid`]
//! tells them apart from ordinary numbers, and both kinds are *sticky*: any
//! arithmetic with an invalid operand gives an invalid result, so a filter
//! checks its outputs once instead of every intermediate product. Filters refuse
//! (and count) an update whose result is invalid, so the stored state is never
//! an invalid value.
//!
//! # The fixed-point format: Q32.32 ([`Fix`])
//!
//! `Fix` is [`fixed::types::I32F32`]: a signed 64-bit word, 32 integer bits and
//! 32 fractional bits. Range ±2 147 483 648, resolution 2⁻³² ≈ 2.3·10⁻¹⁰.
//!
//! Why one 64-bit format rather than several 32-bit ones: the envelope asked of
//! the filters is positions ±400 km, velocities ±1500 m/s, accelerations
//! ±200 m/s², intervals 0.05–20 s, and every gain of the stability regions.
//! A 32-bit word cannot hold both ends at once: positions need 20 integer bits
//! (±524 288 m) leaving 11 fractional bits (0.5 mm), while the velocity gain
//! β/T of a slow filter (Benedict–Bordner with α = 0.01 gives β = 5·10⁻⁵, over
//! T = 20 s: 2.5·10⁻⁶) needs at least 25 fractional bits to keep three
//! significant digits. Q32.32 holds every quantity of the envelope with at
//! least 10⁴ of headroom for intermediates (the largest is the velocity
//! correction β·e/T with β < 4, e ≤ 800 km, T ≥ 0.05 s: 6.4·10⁷ < 2.1·10⁹) and
//! keeps the smallest gain to 10⁻⁴ relative. The cost is 64-bit multiplies
//! (four 32×32 partial products on a Cortex-M3, a library call on an M0),
//! measured by the firmware benchmark (docs/benchmarks.md).
//! Measured there: on the M3 and M0 software `f64` is faster than Q32.32
//! (its products need 128-bit intermediates), so this format buys
//! saturation semantics and a fixed absolute resolution, not speed.
//!
//! Arithmetic on `Fix` saturates, never wraps and never panics: an overflow,
//! a division by zero or the square root of a negative number gives a sentinel.
//! A legitimate result can only equal a sentinel if it is exactly ±2³¹, far
//! outside the envelope.

use core::fmt;
use core::ops::{Add, Div, Mul, Neg, Sub};

use fixed::types::I32F32;

pub mod cordic;
pub mod fixed32;
pub mod numeric;
pub mod scaled;
pub mod scaled_scalar;
pub mod sine;
pub mod wide;

pub use fixed32::Fixed32;
pub use numeric::{AddProduct, Numeric, Quantity, Real};
pub use scaled_scalar::ScaledScalar;

/// Why a value from outside could not be converted into a [`Scalar`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum NumError {
    /// NaN or infinite.
    NotFinite,
    /// Finite, but outside the representation's range.
    OutOfRange,
}

impl fmt::Display for NumError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumError::NotFinite => f.write_str("value is NaN or infinite"),
            NumError::OutOfRange => f.write_str("value is outside the representable range"),
        }
    }
}

impl core::error::Error for NumError {}

/// One type for every quantity (`f64`, `f32`, [`Fix`], [`ScaledScalar`]):
/// a [`Real`] that is its own [`Numeric`] (every quantity, the polar
/// scalar, the covariance number: the type itself), so that code whose
/// quantities span decades in one variable (the TCAS logic, the scan loop)
/// names one type. Holds only what the other traits do not: the
/// arctangent, the hot path guard's running check, and two conversions.
///
/// The arithmetic operators never panic. Results that leave the representable
/// range are invalid values (see the module docs) that propagate through later
/// operations and are detected with [`Quantity::is_valid`].
pub trait Scalar:
    Real<Guard = numeric::ScalarGuard<Self>>
    + Numeric<
        Length = Self,
        Speed = Self,
        Acceleration = Self,
        Interval = Self,
        IntervalSquared = Self,
        Ratio = Self,
        Gain = Self,
        Rate = Self,
        RateSquared = Self,
        Angle = Self,
        Guard = numeric::ScalarGuard<Self>,
        Wide = Self,
        Polar = Self,
        CircleScale = Self,
        Variance = Self,
        GridScale = Self,
    >
{
    /// Four-quadrant arctangent of `self / x`, in (−π, π].
    fn atan2(self, x: Self) -> Self;

    /// Each of `values` divided by `divisor`. A format with
    /// [`Quantity::RELATIVE_PRECISION`] forms one reciprocal and a product
    /// each, within two roundings (`2·UNIT_ROUNDOFF` relative) where a
    /// division has one; fixed point (Q32.32, whose 1/r would keep a few
    /// digits) divides each. A zero or invalid divisor gives invalid
    /// results either way.
    #[inline]
    fn over_each<const N: usize>(values: [Self; N], divisor: Self) -> [Self; N] {
        if <Self as Quantity>::RELATIVE_PRECISION {
            let reciprocal = Self::ONE / divisor;
            values.map(|v| v * reciprocal)
        } else {
            values.map(|v| v / divisor)
        }
    }

    /// Folds `value` into the running check of the hot path's guard
    /// ([`numeric::ScalarGuard`]), which starts at zero and passes when
    /// [`Scalar::check_passed`]. By default it adds and passes when
    /// `check − check == 0` (NaN and ±∞ are sticky, and a finite sum of a
    /// few outputs below `MAX/8` cannot overflow): `f64` and
    /// [`ScaledScalar`]. Q32.32 overrides it: a sum of valid values near
    /// 2³¹ could saturate, so it keeps zero while every value is valid.
    /// `f32` overrides it ([`f32_check`]): an exact test for NaN and ±∞,
    /// in integer instructions on a core without an FPU (a library add per
    /// output there), in one multiply–accumulate per output on the M4F.
    #[inline]
    fn accumulate_check(check: Self, value: Self) -> Self {
        check + value
    }

    /// Whether the guard's running check (folded by
    /// [`Scalar::accumulate_check`]) says that every output was valid.
    #[inline]
    #[allow(clippy::eq_op)] // the subtraction of equal operands is the test
    fn check_passed(check: Self) -> bool {
        check - check == Self::ZERO
    }

    /// `self·scale` rounded half away from zero to an integer, saturated to
    /// the `i32` range, NaN → 0: a report's fixed-point field. By default
    /// through `f64` (exact for `f64`'s and `f32`'s products with a scale
    /// below 2²⁹); `f32` gives the same integer from its bits.
    #[inline]
    fn round_scaled_i32(self, scale: u32) -> i32 {
        let f = libm::round(self.to_f64() * f64::from(scale));
        if f.is_nan() {
            0
        } else if f >= i32::MAX as f64 {
            i32::MAX
        } else if f <= i32::MIN as f64 {
            i32::MIN
        } else {
            f as i32
        }
    }
}

/// `v·scale` rounded half away from zero, saturated to `i32`, NaN → 0, in
/// integer arithmetic on `v`'s bits (`m·2ᵉ·scale` is exact in `u64`):
/// [`Scalar::round_scaled_i32`] for `f32`.
fn round_scaled_f32(v: f32, scale: u32) -> i32 {
    if v.is_nan() {
        return 0;
    }
    let bits = v.to_bits();
    let negative = bits >> 31 != 0;
    let biased = (bits >> 23) & 0xFF;
    let fraction = bits & 0x007F_FFFF;
    // v = mantissa·2^exponent (subnormals: exponent −149).
    let (mantissa, exponent) = if biased == 0 {
        (fraction, -149i32)
    } else {
        (
            fraction | 0x0080_0000,
            biased.cast_signed().wrapping_sub(150),
        )
    };
    // Exact: below 2⁵⁶.
    let product = u64::from(mantissa).saturating_mul(u64::from(scale));
    let magnitude = if exponent >= 0 {
        // Beyond 2⁸ a non-zero product is ≥ 2³¹ (∞ included): saturated.
        match 1u64.checked_shl(exponent.unsigned_abs()) {
            Some(power) if exponent < 9 => product.saturating_mul(power),
            _ if product == 0 => 0,
            _ => u64::MAX,
        }
    } else {
        let shift = exponent.unsigned_abs();
        match 1u64.checked_shl(shift.wrapping_sub(1)) {
            // Half away from zero on the magnitude: add half, truncate.
            Some(half) => product.saturating_add(half).checked_shr(shift).unwrap_or(0),
            None => 0,
        }
    };
    if negative {
        i32::try_from(magnitude).map_or(i32::MIN, i32::wrapping_neg)
    } else {
        i32::try_from(magnitude).unwrap_or(i32::MAX)
    }
}

impl Quantity for f64 {
    const ZERO: Self = 0.0;
    const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0; // 2⁻⁵³
    const ABS_RESOLUTION: f64 = f64::from_bits(1); // 2⁻¹⁰⁷⁴
    numeric::scalar_quantity_items!();

    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(NumError::NotFinite)
        }
    }
    #[inline]
    fn from_f64_lossy(v: f64) -> Self {
        v
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn is_valid(self) -> bool {
        self.is_finite()
    }
    #[inline]
    fn abs(self) -> Self {
        libm::fabs(self)
    }
}

impl Real for f64 {
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    numeric::scalar_real_items!();

    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
}

impl Scalar for f64 {
    #[inline]
    fn atan2(self, x: Self) -> Self {
        libm::atan2(self, x)
    }
}

impl Quantity for f32 {
    const ZERO: Self = 0.0;
    const UNIT_ROUNDOFF: f64 = f32::EPSILON as f64 / 2.0; // 2⁻²⁴
    const ABS_RESOLUTION: f64 = f32::from_bits(1) as f64; // 2⁻¹⁴⁹
    numeric::scalar_quantity_items!();

    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        if !v.is_finite() {
            return Err(NumError::NotFinite);
        }
        let r = v as f32;
        if r.is_finite() {
            Ok(r)
        } else {
            Err(NumError::OutOfRange)
        }
    }
    #[inline]
    fn from_f64_lossy(v: f64) -> Self {
        v as f32
    }
    #[inline]
    fn seconds_from_ms(ms: u32) -> Self {
        ms as f32 / 1000.0
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn is_valid(self) -> bool {
        self.is_finite()
    }
    #[inline]
    fn abs(self) -> Self {
        libm::fabsf(self)
    }

    /// Finite and > 0 exactly when the IEEE 754 word is in
    /// `1..=0x7F7F_FFFF` (sign clear, not zero, exponent field not all
    /// ones): one integer compare instead of a soft-float comparison.
    #[inline]
    fn is_valid_and_positive(self) -> bool {
        self.to_bits().wrapping_sub(1) < 0x7F7F_FFFF
    }
}

impl Real for f32 {
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    numeric::scalar_real_items!();

    #[inline]
    fn from_ratio(numerator: u64, denominator: u64) -> Self {
        // Integers up to 2²⁴ are exact in f32; u32 (not u64) converts in
        // one instruction on an FPU.
        const EXACT: u32 = 1 << 24;
        match (u32::try_from(numerator), u32::try_from(denominator)) {
            _ if denominator == 0 => f32::NAN,
            (Ok(n @ ..=EXACT), Ok(d @ ..=EXACT)) => n as f32 / d as f32,
            _ => (numerator as f64 / denominator as f64) as f32,
        }
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrtf(self)
    }
}

impl Scalar for f32 {
    #[inline]
    fn round_scaled_i32(self, scale: u32) -> i32 {
        round_scaled_f32(self, scale)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        libm::atan2f(self, x)
    }

    /// [`f32_check`]: refuses exactly the updates with a NaN or infinite
    /// output, in the cheapest form for the core ([`f32_check::FPU`]).
    #[inline]
    fn accumulate_check(check: Self, value: Self) -> Self {
        if f32_check::FPU {
            f32_check::fold_fpu(check, value)
        } else {
            f32_check::fold_bits(check, value)
        }
    }

    /// See [`Scalar::accumulate_check`].
    #[inline]
    fn check_passed(check: Self) -> bool {
        if f32_check::FPU {
            f32_check::passed_fpu(check)
        } else {
            f32_check::passed_bits(check)
        }
    }
}

/// The `f32` hot-path guard ([`numeric::ScalarGuard`]): its check word
/// starts at zero, [`Scalar::accumulate_check`] folds every output into it,
/// and the guard passes exactly when no output was NaN or ±∞ (the `f32`
/// operators are sticky, so the outputs' validity is every intermediate's).
/// Two forms with that same meaning; [`FPU`](f32_check::FPU) picks one at compile time, and
/// the host tests check both against every class of IEEE 754 value.
pub mod f32_check {
    /// Whether `f32` arithmetic runs on an FPU here (the Cortex-M4F's hard
    /// float ABI): then [`fold_fpu`]/[`passed_fpu`], else
    /// [`fold_bits`]/[`passed_bits`] (the M0 and M3, and the host tests).
    pub const FPU: bool = cfg!(target_abi = "eabihf");

    /// The FPU form: `check + 0·value`. `0·v` is ±0 for a finite `v` and NaN
    /// for NaN or ±∞ (IEEE 754-2008 §7.2: 0·∞ is invalid), and a sum of
    /// zeros is a zero, so the check stays ±0 until an invalid output makes
    /// it NaN, for good. One multiply–accumulate (`vmla`) per output.
    #[inline]
    pub fn fold_fpu(check: f32, value: f32) -> f32 {
        check + 0.0 * value
    }

    /// The FPU form's test: the check is still a zero.
    #[inline]
    pub fn passed_fpu(check: f32) -> bool {
        check == 0.0
    }

    /// The integer form: the check word is a bit pattern, not a number. The
    /// biased exponent field (bits 23–30) is all ones exactly for ±∞ and NaN
    /// (IEEE 754-2008 §3.4), so with the sign cleared a finite value's word
    /// is at most `0x7F7F_FFFF` and a non-finite one's at least
    /// `0x7F80_0000`: adding `0x0080_0000` carries into bit 31 exactly for
    /// the non-finite ones (and never past it: at most `0x807F_FFFF`). The
    /// check ORs those sums: three integer instructions per output, where
    /// a sum of the outputs would cost a library call each on the M0/M3.
    #[inline]
    pub fn fold_bits(check: f32, value: f32) -> f32 {
        let term = (value.to_bits() & 0x7FFF_FFFF).wrapping_add(0x0080_0000);
        f32::from_bits(check.to_bits() | term)
    }

    /// The integer form's test: bit 31 of the check word still clear.
    #[inline]
    pub fn passed_bits(check: f32) -> bool {
        check.to_bits() & 0x8000_0000 == 0
    }
}

/// √(a² + b²) without overflow on the way ([`Real::hypot`]).
#[inline]
pub fn hypot<S: Scalar>(a: S, b: S) -> S {
    Real::hypot(a, b)
}

/// Azimuth of (x, y), clockwise from the y axis, in [0, 2π).
pub fn azimuth_of<S: Scalar>(x: S, y: S) -> S {
    let two_pi = S::from_f64_lossy(core::f64::consts::TAU);
    let a = x.atan2(y);
    if a < S::ZERO {
        let wrapped = a + two_pi;
        // A tiny negative angle plus 2π can round to 2π in f32/f64: that
        // direction is azimuth 0.
        if wrapped >= two_pi {
            S::ZERO
        } else {
            wrapped
        }
    } else {
        a
    }
}

/// Q32.32 saturating fixed point with sticky saturation (see the module docs).
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Fix(I32F32);

impl Fix {
    /// Positive saturation sentinel (invalid).
    pub const MAX: Fix = Fix(I32F32::MAX);
    /// Negative saturation sentinel (invalid).
    pub const MIN: Fix = Fix(I32F32::MIN);
    /// Number of fractional bits.
    pub const FRAC_BITS: u32 = 32;
    /// The smallest positive step, 2⁻³².
    pub const DELTA: Fix = Fix(I32F32::DELTA);

    /// The value as a decimal with six places, without floats (the firmware
    /// log's form): (negative, integer part, millionths), |value| rounded to
    /// the nearest millionth, half up; a fraction that rounds to 1.000000
    /// carries into the integer part. A sentinel gives its bits' value.
    pub fn decimal_millionths(self) -> (bool, u64, u64) {
        let bits = self.0.to_bits();
        let magnitude = bits.unsigned_abs();
        // Below 2⁶⁴ before the shift: (2³² − 1)·10⁶ + 2³¹.
        let millionths = (magnitude & 0xFFFF_FFFF)
            .wrapping_mul(1_000_000)
            .wrapping_add(1 << 31)
            >> 32;
        // The integer part is at most 2³¹: adding the carry cannot wrap.
        let (int, frac) = if millionths == 1_000_000 {
            ((magnitude >> 32).wrapping_add(1), 0)
        } else {
            (magnitude >> 32, millionths)
        };
        (bits < 0, int, frac)
    }

    /// Wraps a raw `fixed` value. A value equal to `I32F32::MIN`/`MAX` is a
    /// saturation sentinel.
    pub const fn from_fixed(v: I32F32) -> Self {
        Fix(v)
    }

    /// The value as the `fixed` crate's `I32F32`.
    pub const fn to_fixed(self) -> I32F32 {
        self.0
    }

    /// The raw two's-complement word (value × 2³²).
    pub const fn to_bits(self) -> i64 {
        self.0.to_bits()
    }

    /// From a raw word (value × 2³²); `i64::MIN`/`MAX` are the sentinels.
    pub const fn from_bits(bits: i64) -> Self {
        Fix(I32F32::from_bits(bits))
    }

    #[inline]
    const fn is_sentinel(self) -> bool {
        let b = self.0.to_bits();
        b == i64::MAX || b == i64::MIN
    }

    /// The sentinel carrying the sign a saturated result would have had.
    #[inline]
    const fn saturated(negative: bool) -> Self {
        if negative {
            Fix::MIN
        } else {
            Fix::MAX
        }
    }

    #[inline]
    fn binary(self, rhs: Fix, checked: Option<I32F32>, negative_if_overflow: bool) -> Fix {
        if self.is_sentinel() || rhs.is_sentinel() {
            return Fix::saturated(negative_if_overflow);
        }
        match checked {
            Some(v) => Fix(v),
            None => Fix::saturated(negative_if_overflow),
        }
    }
}

impl fmt::Debug for Fix {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_sentinel() {
            f.write_str(if self.0.is_negative() {
                "Fix(-SAT)"
            } else {
                "Fix(+SAT)"
            })
        } else {
            write!(f, "Fix({})", self.0)
        }
    }
}

impl fmt::Display for Fix {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for Fix {
    fn format(&self, f: defmt::Formatter) {
        if self.is_sentinel() {
            defmt::write!(f, "SAT")
        } else {
            let (negative, int, frac) = self.decimal_millionths();
            let sign = if negative { "-" } else { "" };
            defmt::write!(f, "{=str}{=u64}.{=u64:06}", sign, int, frac)
        }
    }
}

impl Add for Fix {
    type Output = Fix;
    #[inline]
    fn add(self, rhs: Fix) -> Fix {
        // A sum overflows only when both terms have the same sign.
        let neg = self.0.is_negative() && rhs.0.is_negative();
        self.binary(rhs, self.0.checked_add(rhs.0), neg)
    }
}

impl Sub for Fix {
    type Output = Fix;
    #[inline]
    fn sub(self, rhs: Fix) -> Fix {
        // A difference overflows only when the signs differ: it takes self's.
        let neg = self.0.is_negative();
        self.binary(rhs, self.0.checked_sub(rhs.0), neg)
    }
}

impl Mul for Fix {
    type Output = Fix;
    #[inline]
    fn mul(self, rhs: Fix) -> Fix {
        let neg = self.0.is_negative() != rhs.0.is_negative();
        self.binary(rhs, self.0.checked_mul(rhs.0), neg)
    }
}

impl Div for Fix {
    type Output = Fix;
    /// Division by zero saturates with the numerator's sign.
    #[inline]
    fn div(self, rhs: Fix) -> Fix {
        let neg = self.0.is_negative() != rhs.0.is_negative();
        self.binary(rhs, self.0.checked_div(rhs.0), neg)
    }
}

impl Neg for Fix {
    type Output = Fix;
    #[inline]
    fn neg(self) -> Fix {
        if self.is_sentinel() {
            Fix::saturated(!self.0.is_negative())
        } else {
            // Not a sentinel, so not i64::MIN: the negation cannot wrap.
            Fix(self.0.wrapping_neg())
        }
    }
}

impl Fix {
    /// (sin θ, cos θ) by CORDIC in integer arithmetic ([`cordic`]): any
    /// angle, error at most [`cordic::SIN_COS_MAX_ERROR`] (2⁻³²). A
    /// sentinel gives sentinels. [`Numeric::sin_cos`] of `Fix`.
    pub(crate) fn sin_cos_cordic(self) -> (Self, Self) {
        if self.is_sentinel() {
            return (Fix::MAX, Fix::MAX);
        }
        let (s, c) = cordic::sin_cos_bits(self.to_bits());
        (Fix::from_bits(s), Fix::from_bits(c))
    }
}

impl Quantity for Fix {
    const ZERO: Self = Fix(I32F32::ZERO);
    // `fixed` multiplies with an arithmetic shift (rounds toward −∞) and
    // divides with truncation: either way the error is below one step 2⁻³².
    // Conversions from f64 round to nearest (half a step).
    const UNIT_ROUNDOFF: f64 = 0.0;
    const ABS_RESOLUTION: f64 = 1.0 / 4_294_967_296.0; // 2⁻³²
    numeric::scalar_quantity_items!();

    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        if !v.is_finite() {
            return Err(NumError::NotFinite);
        }
        match I32F32::checked_from_num(v) {
            Some(x) if !Fix(x).is_sentinel() => Ok(Fix(x)),
            _ => Err(NumError::OutOfRange),
        }
    }

    fn from_f64_lossy(v: f64) -> Self {
        if v.is_nan() {
            return Fix::MAX;
        }
        match I32F32::checked_from_num(v) {
            Some(x) => Fix(x),
            None => Fix::saturated(v < 0.0),
        }
    }

    #[inline]
    fn to_f64(self) -> f64 {
        if self.is_sentinel() {
            if self.0.is_negative() {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            }
        } else {
            self.0.to_num::<f64>()
        }
    }

    #[inline]
    fn is_valid(self) -> bool {
        !self.is_sentinel()
    }

    #[inline]
    fn abs(self) -> Self {
        if self.is_sentinel() {
            Fix::MAX
        } else {
            Fix(self.0.abs())
        }
    }
}

impl Real for Fix {
    const ONE: Self = Fix(I32F32::ONE);
    const TWO: Self = Fix(I32F32::from_bits(2 << Self::FRAC_BITS));
    numeric::scalar_real_items!();

    fn sqrt(self) -> Self {
        if self.is_sentinel() {
            return Fix::MAX;
        }
        match self.0.checked_sqrt() {
            Some(r) => Fix(r),
            None => Fix::MAX,
        }
    }
}

impl Scalar for Fix {
    #[inline]
    fn accumulate_check(check: Self, value: Self) -> Self {
        if !check.is_sentinel() && !value.is_sentinel() {
            <Fix as Quantity>::ZERO
        } else {
            Fix::MAX
        }
    }

    /// CORDIC in integer arithmetic ([`cordic`]): result in (−π, π],
    /// atan2(0, 0) = 0, error at most [`cordic::ATAN2_MAX_ERROR`] (2⁻³² rad).
    /// A sentinel operand gives a sentinel.
    fn atan2(self, x: Self) -> Self {
        if self.is_sentinel() || x.is_sentinel() {
            return Fix::MAX;
        }
        Fix::from_bits(cordic::atan2_bits(self.to_bits(), x.to_bits()))
    }
}
