//! [`Scaled`]: an `i32` mantissa with its own binary exponent, the format of
//! the fast fixed point's quantities whose range spans decades (gains α, β,
//! γ and ratios; the per-interval gains β/T and γ/(2T²); T²). A product with
//! a fixed-format quantity is still one 32×32→64 multiply and a shift
//! ([`super::fixed32`]); relative precision is 2⁻³⁰ over the whole range.
//!
//! Representation: value = `mantissa · 2^exponent` with |mantissa| in
//! [2³⁰, 2³¹) (normalised), or mantissa 0 with exponent [`EXPONENT_MIN`]
//! (zero). The invalid value (the
//! analogue of NaN) has mantissa `i32::MIN`; it is sticky, compares unordered
//! with everything, and is what an overflow ([`EXPONENT_MAX`]), a division
//! by zero or the square root of a negative number gives. Results below
//! 2^([`EXPONENT_MIN`] + 30) flush to zero.
//!
//! Every operation rounds to nearest (ties away from zero) once, except
//! division, which truncates a 32-bit quotient before rounding it to 31 bits:
//! each result is within one unit of the last place (2⁻³⁰ relative) of the
//! exact result, the [`Quantity::UNIT_ROUNDOFF`] the error budget uses.

use core::cmp::Ordering;
use core::fmt;
use core::marker::PhantomData;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::numeric::{Quantity, Real};
use super::NumError;

/// Largest exponent: values up to 2^(100 + 31).
pub const EXPONENT_MAX: i32 = 100;
/// Smallest exponent: smaller results flush to zero.
pub const EXPONENT_MIN: i32 = -200;

/// Mantissa of the invalid value.
const INVALID_MANTISSA: i32 = i32::MIN;
/// Position of a normalised mantissa's leading one.
const TOP_BIT: u32 = 30;

/// Units of [`Scaled`] values (type-level markers, never constructed).
pub mod unit {
    /// Dimensionless.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct One;
    /// 1/s.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct PerSecond;
    /// 1/s².
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct PerSecondSquared;
    /// s².
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct SecondSquared;
    /// Radians.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Radian;
}

/// A number `mantissa · 2^exponent` in unit `U` (module docs).
pub struct Scaled<U> {
    mantissa: i32,
    exponent: i16,
    unit: PhantomData<U>,
}

impl<U> Clone for Scaled<U> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<U> Copy for Scaled<U> {}

impl<U> Default for Scaled<U> {
    fn default() -> Self {
        Self::ZERO_VALUE
    }
}

impl<U> PartialEq for Scaled<U> {
    fn eq(&self, other: &Self) -> bool {
        self.mantissa == other.mantissa && self.exponent == other.exponent
    }
}

/// Integer square root, rounded to nearest: r with |r² − n| ≤ r.
pub(crate) fn isqrt_u64(n: u64) -> u64 {
    let mut rest = n;
    let mut root = 0u64;
    // The largest power of four ≤ n (bit 62 at most).
    let mut bit = 1u64 << 62;
    while bit > rest {
        bit >>= 2;
    }
    while bit != 0 {
        // root + bit ≤ n here, so neither sum overflows.
        let trial = root.wrapping_add(bit);
        if rest >= trial {
            rest = rest.wrapping_sub(trial);
            root = (root >> 1).wrapping_add(bit);
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    // rest = n − root² < 2·root + 1; round up when n − root² > root.
    if rest > root {
        root.wrapping_add(1)
    } else {
        root
    }
}

impl<U> Scaled<U> {
    /// Zero carries the smallest exponent, so that a product with it is
    /// shifted out entirely however it is scaled (see
    /// [`super::fixed32`]'s guarded products).
    const ZERO_VALUE: Self = Scaled {
        mantissa: 0,
        exponent: EXPONENT_MIN as i16,
        unit: PhantomData,
    };
    /// The invalid value (module docs).
    pub const INVALID: Self = Scaled {
        mantissa: INVALID_MANTISSA,
        exponent: 0,
        unit: PhantomData,
    };

    /// The normalised mantissa (0 for zero, `i32::MIN` when invalid).
    #[inline]
    pub const fn mantissa(self) -> i32 {
        self.mantissa
    }

    /// The binary exponent (value = mantissa · 2^exponent).
    #[inline]
    pub const fn exponent(self) -> i32 {
        self.exponent as i32
    }

    #[inline]
    pub const fn is_invalid(self) -> bool {
        self.mantissa == INVALID_MANTISSA
    }

    #[inline]
    pub const fn is_zero(self) -> bool {
        self.mantissa == 0
    }

    /// The same number in another unit (for the few places where a formula
    /// changes a quantity's meaning, e.g. a count of metres into a length).
    #[inline]
    pub const fn cast<V>(self) -> Scaled<V> {
        Scaled {
            mantissa: self.mantissa,
            exponent: self.exponent,
            unit: PhantomData,
        }
    }

    /// `wide · 2^exponent`, rounded to a 31-bit mantissa.
    pub fn from_wide(wide: i64, exponent: i32) -> Self {
        if wide == 0 {
            return Self::ZERO_VALUE;
        }
        let negative = wide < 0;
        let magnitude = wide.unsigned_abs();
        // Bit index of the leading one, 0..=63.
        let top = 63u32.wrapping_sub(magnitude.leading_zeros());
        let (magnitude, exponent) = if top > TOP_BIT {
            let shift = top.wrapping_sub(TOP_BIT); // 1..=33
                                                   // Round half away from zero: drop all but one extra bit, add it.
            let rounded = (magnitude >> shift.wrapping_sub(1)).wrapping_add(1) >> 1;
            let exponent = exponent.saturating_add(shift as i32);
            if rounded >> 31 != 0 {
                // Rounded up to 2³¹: one bit more, exactly.
                (rounded >> 1, exponent.saturating_add(1))
            } else {
                (rounded, exponent)
            }
        } else {
            let shift = TOP_BIT.wrapping_sub(top); // 0..=30
            (magnitude << shift, exponent.saturating_sub(shift as i32))
        };
        if exponent > EXPONENT_MAX {
            return Self::INVALID;
        }
        if exponent < EXPONENT_MIN {
            return Self::ZERO_VALUE;
        }
        // magnitude < 2³¹: the cast is exact and the negation cannot wrap.
        let m = magnitude as i32;
        Scaled {
            mantissa: if negative { m.wrapping_neg() } else { m },
            exponent: exponent as i16,
            unit: PhantomData,
        }
    }

    /// The integer `v`.
    pub fn from_int(v: i64) -> Self {
        Self::from_wide(v, 0)
    }

    fn compare(self, other: Self) -> Option<Ordering> {
        if self.is_invalid() || other.is_invalid() {
            return None;
        }
        let (a, b) = (self.mantissa, other.mantissa);
        let sign = |m: i32| m.signum();
        if sign(a) != sign(b) {
            return Some(sign(a).cmp(&sign(b)));
        }
        if a == 0 {
            return Some(Ordering::Equal);
        }
        let magnitude_order =
            (self.exponent, a.unsigned_abs()).cmp(&(other.exponent, b.unsigned_abs()));
        Some(if a > 0 {
            magnitude_order
        } else {
            magnitude_order.reverse()
        })
    }

    fn multiply(self, other: Self) -> Self {
        if self.is_invalid() || other.is_invalid() {
            return Self::INVALID;
        }
        // |product| < 2⁶²: exact in i64.
        let product = i64::from(self.mantissa).wrapping_mul(i64::from(other.mantissa));
        Self::from_wide(product, self.exponent().wrapping_add(other.exponent()))
    }

    fn divide(self, other: Self) -> Self {
        if self.is_invalid() || other.is_invalid() || other.is_zero() {
            return Self::INVALID;
        }
        // |mantissa| < 2³¹, so the shifted numerator is below 2⁶³; the
        // divisor is neither 0 nor −1 (normalised), so the division is exact
        // integer division with a quotient of at least 32 bits.
        let numerator = i64::from(self.mantissa) << 32;
        match numerator.checked_div(i64::from(other.mantissa)) {
            Some(q) => Self::from_wide(
                q,
                self.exponent()
                    .wrapping_sub(other.exponent())
                    .wrapping_sub(32),
            ),
            None => Self::INVALID,
        }
    }

    fn sum(self, other: Self) -> Self {
        if self.is_invalid() || other.is_invalid() {
            return Self::INVALID;
        }
        if self.is_zero() {
            return other;
        }
        if other.is_zero() {
            return self;
        }
        let (high, low) = if self.exponent >= other.exponent {
            (self, other)
        } else {
            (other, self)
        };
        let gap = high.exponent().wrapping_sub(low.exponent()) as u32; // ≥ 0
                                                                       // Both mantissas times 2³¹ (below 2⁶²); the smaller one aligned by an
                                                                       // arithmetic shift (its dropped bits are below 2⁻³¹ of an ulp).
        let wide_high = i64::from(high.mantissa) << 31;
        let wide_low = if gap < 63 {
            (i64::from(low.mantissa) << 31) >> gap
        } else {
            0
        };
        Self::from_wide(
            wide_high.wrapping_add(wide_low),
            high.exponent().wrapping_sub(31),
        )
    }

    fn negated(self) -> Self {
        if self.is_invalid() {
            return self;
        }
        Scaled {
            mantissa: self.mantissa.wrapping_neg(),
            ..self
        }
    }

    fn root(self) -> Self {
        if self.is_invalid() || self.mantissa < 0 {
            return Self::INVALID;
        }
        if self.is_zero() {
            return self;
        }
        // Make the exponent even: n·2^e2 with e2 even, n < 2⁶³.
        let m = self.mantissa as u64;
        let (n, e2) = if self.exponent & 1 == 0 {
            (m << 32, self.exponent().wrapping_sub(32))
        } else {
            (m << 31, self.exponent().wrapping_sub(31))
        };
        Self::from_wide(isqrt_u64(n) as i64, e2 / 2)
    }
}

impl<U> fmt::Debug for Scaled<U> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_invalid() {
            f.write_str("Scaled(invalid)")
        } else {
            write!(f, "Scaled({:e})", self.to_f64_value())
        }
    }
}

impl<U> fmt::Display for Scaled<U> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.to_f64_value(), f)
    }
}

#[cfg(feature = "defmt")]
impl<U> defmt::Format for Scaled<U> {
    fn format(&self, f: defmt::Formatter) {
        if self.is_invalid() {
            defmt::write!(f, "invalid")
        } else {
            defmt::write!(f, "{=i32}p{=i16}", self.mantissa, self.exponent)
        }
    }
}

impl<U> Scaled<U> {
    fn to_f64_value(self) -> f64 {
        if self.is_invalid() {
            f64::NAN
        } else {
            libm::ldexp(f64::from(self.mantissa), self.exponent())
        }
    }
}

impl<U> PartialOrd for Scaled<U> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.compare(*other)
    }
}

impl<U> Add for Scaled<U> {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        self.sum(rhs)
    }
}

impl<U> Sub for Scaled<U> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        self.sum(rhs.negated())
    }
}

impl<U> Neg for Scaled<U> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.negated()
    }
}

/// Products and quotients between units (only those the filters use).
macro_rules! scaled_unit_ops {
    ($($a:ty, $op:ident, $method:ident, $b:ty => $out:ty;)*) => {$(
        impl $op<Scaled<$b>> for Scaled<$a> {
            type Output = Scaled<$out>;
            #[inline]
            fn $method(self, rhs: Scaled<$b>) -> Scaled<$out> {
                scaled_unit_ops!(@apply $method, self.cast::<$out>(), rhs.cast::<$out>())
            }
        }
    )*};
    (@apply mul, $x:expr, $y:expr) => { $x.multiply($y) };
    (@apply div, $x:expr, $y:expr) => { $x.divide($y) };
}

use unit::{One, PerSecond, PerSecondSquared, SecondSquared};

scaled_unit_ops! {
    One, Mul, mul, One => One;
    One, Div, div, One => One;
    One, Div, div, SecondSquared => PerSecondSquared;
    PerSecond, Mul, mul, One => PerSecond;
    PerSecondSquared, Mul, mul, One => PerSecondSquared;
    SecondSquared, Mul, mul, One => SecondSquared;
}

impl<U: fmt::Debug + Copy + Default + PartialEq + Send + Sync + 'static> Quantity for Scaled<U>
where
    Scaled<U>: super::numeric::MaybeFormat,
{
    const ZERO: Self = Self::ZERO_VALUE;
    /// One unit of the last place of a 31-bit mantissa (module docs).
    const UNIT_ROUNDOFF: f64 = 1.0 / (1u64 << 30) as f64;
    /// Flush to zero below 2^(EXPONENT_MIN + 30) (2⁻¹⁷⁰).
    const ABS_RESOLUTION: f64 = 6.7e-52;

    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        if !v.is_finite() {
            return Err(NumError::NotFinite);
        }
        let s = Self::from_f64_lossy(v);
        if s.is_invalid() {
            Err(NumError::OutOfRange)
        } else {
            Ok(s)
        }
    }

    fn from_f64_lossy(v: f64) -> Self {
        if !v.is_finite() {
            return Self::INVALID;
        }
        if v == 0.0 {
            return Self::ZERO_VALUE;
        }
        // v = f·2^e with 0.5 ≤ |f| < 1; f·2⁶² is exact and below 2⁶².
        let (f, e) = libm::frexp(v);
        let wide = libm::round(f * 4_611_686_018_427_387_904.0) as i64; // 2⁶²
        Self::from_wide(wide, e.saturating_sub(62))
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self.to_f64_value()
    }

    #[inline]
    fn is_valid(self) -> bool {
        !self.is_invalid()
    }

    #[inline]
    fn abs(self) -> Self {
        if self.mantissa < 0 {
            self.negated()
        } else {
            self
        }
    }

    #[inline]
    fn half(self) -> Self {
        if self.is_invalid() || self.is_zero() {
            return self;
        }
        Self::from_wide(i64::from(self.mantissa), self.exponent().wrapping_sub(1))
    }
}

impl Real for Scaled<One> {
    const ONE: Self = Scaled {
        mantissa: 1 << TOP_BIT,
        exponent: -(TOP_BIT as i16),
        unit: PhantomData,
    };

    fn from_ratio(numerator: u64, denominator: u64) -> Self {
        // Halve both until they fit an i64 (exact while both are even; the
        // gain formulas' counts stay far below 2⁶³).
        let (mut n, mut d) = (numerator, denominator);
        while n > i64::MAX as u64 || d > i64::MAX as u64 {
            n >>= 1;
            d >>= 1;
        }
        Self::from_int(n as i64).divide(Self::from_int(d as i64))
    }

    fn sqrt(self) -> Self {
        self.root()
    }
}
