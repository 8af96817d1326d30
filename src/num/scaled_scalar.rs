//! [`ScaledScalar`]: the fast fixed point's wide format ([`Scaled`](crate::num::scaled::Scaled), a
//! 31-bit mantissa with a binary exponent, rounded to nearest once per
//! operation) as one [`Scalar`] type for every quantity, for the code whose
//! quantities span decades in one variable (the TCAS logic's taus, ratios
//! and products of ranges and rates, the altitude tracker) on cores without
//! an FPU. Every operation is 32-bit integer code: no soft-float call and
//! no 128-bit division (Q32.32's cost). `docs/numerics-fixed-point.md`
//! gives its rounding model and where it is used.

use core::ops::{Add, Div, Mul, Neg, Sub};

use super::fixed32::{self, Fixed32, Ratio};
use super::numeric::{Numeric, Quantity, Real};
use super::{NumError, Scalar};

/// Largest error of [`Numeric::sin_cos`] of a [`ScaledScalar`] angle with
/// |θ| ≤ 2π, each component: the table sine's
/// [`super::sine::SIN_COS_MAX_ERROR_Q31`] units of 2⁻³¹, one more for the
/// rounding to a 31-bit mantissa, and the conversion to a binary angle
/// (1.1·10⁻¹⁰ relative, 7·10⁻¹⁰ at 2π). Checked by
/// `host-tests/tests/it/num/scaled_scalar.rs`.
pub const SIN_COS_MAX_ERROR: f64 =
    (super::sine::SIN_COS_MAX_ERROR_Q31 + 1.0) / 2_147_483_648.0 + 7.0e-10;

/// Largest error of [`Scalar::atan2`] of [`ScaledScalar`] values, rad:
/// CORDIC's 2⁻³² ([`super::cordic::ATAN2_MAX_ERROR`]) and the rounding of
/// a result below π to a 31-bit mantissa (2⁻³⁰). Checked by
/// `host-tests/tests/it/num/scaled_scalar.rs`.
pub const ATAN2_MAX_ERROR: f64 = super::cordic::ATAN2_MAX_ERROR + 1.0 / 1_073_741_824.0;

/// A [`Scaled`](super::scaled::Scaled) dimensionless number used as a
/// [`Scalar`] (module docs). The invalid value (overflow beyond 2¹³¹, a
/// division by zero, the root of a negative number) is sticky, as NaN is.
#[derive(Debug, Clone, Copy, Default, PartialEq, PartialOrd)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScaledScalar(Ratio);

impl ScaledScalar {
    /// The wrapped [`fixed32::Ratio`].
    #[inline]
    pub const fn to_ratio(self) -> Ratio {
        self.0
    }

    /// From a [`fixed32::Ratio`].
    #[inline]
    pub const fn from_ratio(r: Ratio) -> Self {
        ScaledScalar(r)
    }

    /// The number of metres of a fast fixed-point length (exact; a
    /// saturation sentinel gives the invalid value).
    #[inline]
    pub fn from_length(l: fixed32::Length) -> Self {
        Self::from_word(l.to_bits(), fixed32::Length::FRAC_BITS)
    }

    /// The number of m/s of a fast fixed-point speed (exact; a saturation
    /// sentinel gives the invalid value).
    #[inline]
    pub fn from_speed(v: fixed32::Speed) -> Self {
        Self::from_word(v.to_bits(), fixed32::Speed::FRAC_BITS)
    }

    /// A fixed-format word with `frac` fractional bits (its sentinels give
    /// the invalid value).
    fn from_word(bits: i32, frac: u32) -> Self {
        if bits == i32::MIN || bits == i32::MAX {
            ScaledScalar(Ratio::INVALID)
        } else {
            ScaledScalar(Ratio::from_wide(
                i64::from(bits),
                (frac as i32).wrapping_neg(),
            ))
        }
    }
}

impl core::fmt::Display for ScaledScalar {
    /// The value as `f64` prints it (exact: a 31-bit mantissa).
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        core::fmt::Display::fmt(&self.0, f)
    }
}

macro_rules! scaled_scalar_ops {
    ($($trait:ident, $method:ident;)*) => {$(
        impl $trait for ScaledScalar {
            type Output = Self;
            #[inline]
            fn $method(self, rhs: Self) -> Self {
                ScaledScalar($trait::$method(self.0, rhs.0))
            }
        }
    )*};
}

scaled_scalar_ops! {
    Add, add;
    Sub, sub;
    Mul, mul;
    Div, div;
}

impl Neg for ScaledScalar {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        ScaledScalar(-self.0)
    }
}

impl ScaledScalar {
    /// [`Fixed32`]'s table sine of the angle's binary-angle form
    /// ([`super::sine`]): [`Numeric::sin_cos`] of `ScaledScalar`.
    pub(crate) fn sin_cos_table(self) -> (Self, Self) {
        let (s, c) = <Fixed32 as Numeric>::sin_cos(self.0.cast());
        (ScaledScalar(s), ScaledScalar(c))
    }
}

impl Quantity for ScaledScalar {
    const ZERO: Self = ScaledScalar(<Ratio as Quantity>::ZERO);
    /// One unit of the last place of a 31-bit mantissa for sums (products,
    /// quotients and roots are within half of it).
    const UNIT_ROUNDOFF: f64 = <Ratio as Quantity>::UNIT_ROUNDOFF;
    /// Results below 2⁻¹⁷⁰ flush to zero.
    const ABS_RESOLUTION: f64 = <Ratio as Quantity>::ABS_RESOLUTION;
    super::numeric::scalar_quantity_items!();

    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        Ratio::try_from_f64(v).map(ScaledScalar)
    }

    #[inline]
    fn from_f64_lossy(v: f64) -> Self {
        ScaledScalar(Ratio::from_f64_lossy(v))
    }

    /// The wide format's: an integer division, no `f64`.
    #[inline]
    fn seconds_from_ms(ms: u32) -> Self {
        ScaledScalar(<Ratio as Quantity>::seconds_from_ms(ms))
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self.0.to_f64()
    }

    #[inline]
    fn is_valid(self) -> bool {
        self.0.is_valid()
    }

    #[inline]
    fn abs(self) -> Self {
        ScaledScalar(self.0.abs())
    }
}

impl Real for ScaledScalar {
    const ONE: Self = ScaledScalar(<Ratio as Real>::ONE);
    const TWO: Self = ScaledScalar(<Ratio as Real>::TWO);
    super::numeric::scalar_real_items!();

    #[inline]
    fn sqrt(self) -> Self {
        ScaledScalar(Real::sqrt(self.0))
    }

    /// One square root of the sum of the squared mantissas
    /// ([`Real::hypot`] of [`Scaled`](super::scaled::Scaled)).
    #[inline]
    fn hypot(self, other: Self) -> Self {
        ScaledScalar(Real::hypot(self.0, other.0))
    }

    /// One square root of the three squared mantissas ([`Real::hypot3`] of
    /// [`Scaled`](super::scaled::Scaled)).
    #[inline]
    fn hypot3(self, b: Self, c: Self) -> Self {
        ScaledScalar(Real::hypot3(self.0, b.0, c.0))
    }
}

impl Scalar for ScaledScalar {
    /// CORDIC in vectoring mode ([`super::cordic`]) on the two mantissas
    /// aligned to the larger exponent: within 2⁻³² rad plus the rounding to
    /// a 31-bit mantissa.
    fn atan2(self, x: Self) -> Self {
        let (y, x) = (self.0, x.0);
        if y.is_invalid() || x.is_invalid() {
            return ScaledScalar(Ratio::INVALID);
        }
        // Mantissas below 2³¹, placed at bit 62 minus the exponent gap:
        // below 2⁶², never i64::MIN, as atan2_bits asks.
        let top = y.exponent().max(x.exponent());
        let word = |v: Ratio| {
            let gap = top.wrapping_sub(v.exponent()) as u32; // ≥ 0
            (i64::from(v.mantissa()) << 31)
                .checked_shr(gap)
                .unwrap_or(0)
        };
        let angle = super::cordic::atan2_bits(word(y), word(x));
        ScaledScalar(Ratio::from_wide(angle, -32))
    }
}
