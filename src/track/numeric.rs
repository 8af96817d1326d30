//! The number systems a track table runs in ([`TrackNumeric`]): a
//! [`Numeric`] with the few operations the table needs beyond the filters'
//! algebra, for `f64`, `f32`, Q32.32 (every [`Scalar`]) and the fast fixed
//! point ([`Fixed32`]).
//!
//! * The gate test of a circle and its cost, the squared distance
//!   normalised by the radius, quantised to `u16` (the solver's currency):
//!   floats and Q32.32 multiply by the reciprocal of the radius, formed once
//!   per track; [`Fixed32`] compares the squared offsets with the squared
//!   radius exactly in 64-bit integers and divides once per gated pair.
//! * Polar geometry (projecting range and azimuth; range/azimuth windows)
//!   runs in a [`Scalar`]: the type itself, or `f32` for [`Fixed32`], which
//!   has no sine or arctangent (in software on its cores, library calls
//!   rather than Q32.32's inlined 128-bit arithmetic, 13 KB less flash on the
//!   micro:bit; 24 significant bits: 6 mm at 100 km). Only polar
//!   measurements and He et al.'s range/azimuth windows take this path.
//! * A track stores three ratios (its gate's covariance) packed: the
//!   [`Scaled`] ratios of [`Fixed32`] are an `i32` mantissa and an `i16`
//!   exponent, 8 bytes with padding each; three mantissas and three
//!   exponents take 20 (`docs/track-table.md`, bytes per track).

use core::fmt::Debug;

use super::assign::MAX_COST;
use crate::num::fixed32::{Fixed32, Length, Ratio};
use crate::num::{Numeric, Quantity, Scalar};

/// A [`Numeric`] the track table runs in (module docs).
pub trait TrackNumeric: Numeric {
    /// The scalar type of the polar geometry.
    type Polar: Scalar;
    /// What a circular gate keeps to test measurements (the reciprocal of
    /// its radius, for floats and Q32.32).
    type CircleScale: Copy + Debug + PartialEq;
    /// Three ratios as a track stores them.
    type PackedRatios: Copy + Debug + PartialEq;

    /// The circle's scale for `radius` (> 0), or `None` if it cannot be
    /// formed.
    fn circle_scale(radius: Self::Length) -> Option<Self::CircleScale>;

    /// The cost `round((dx² + dy²)/r²·MAX_COST)` of a measurement offset
    /// (dx, dy) from the centre of a circle of radius `r`, or `None` if it
    /// lies outside (or an operand is invalid).
    fn circle_cost(
        dx: Self::Length,
        dy: Self::Length,
        radius: Self::Length,
        scale: Self::CircleScale,
    ) -> Option<u16>;

    /// A length in the polar scalar (exact).
    fn length_to_polar(v: Self::Length) -> Self::Polar;
    /// Back, rounded to the length's resolution (invalid if out of range).
    fn length_from_polar(v: Self::Polar) -> Self::Length;
    /// A ratio (an angle in radians) in the polar scalar.
    fn ratio_to_polar(v: Self::Ratio) -> Self::Polar;
    /// Back (invalid if out of range).
    fn ratio_from_polar(v: Self::Polar) -> Self::Ratio;

    fn pack(ratios: [Self::Ratio; 3]) -> Self::PackedRatios;
    fn unpack(packed: Self::PackedRatios) -> [Self::Ratio; 3];
}

/// A value in [0, 1] to `0 ..= MAX_COST`, rounded to nearest.
pub(super) fn quantise_unit<S: Scalar>(v: S) -> u16 {
    let scaled = v.to_f64() * MAX_COST as f64 + 0.5;
    // `as` saturates (and maps NaN to 0); the caller checked 0 ≤ v ≤ 1.
    let q = scaled as u32;
    if q > MAX_COST as u32 {
        MAX_COST
    } else {
        q as u16
    }
}

impl<S: Scalar> TrackNumeric for S {
    type Polar = S;
    type CircleScale = S;
    type PackedRatios = [S; 3];

    fn circle_scale(radius: S) -> Option<S> {
        let inverse = S::ONE / radius;
        (inverse.is_valid() && inverse > S::ZERO).then_some(inverse)
    }

    fn circle_cost(dx: S, dy: S, radius: S, inverse_radius: S) -> Option<u16> {
        // `!(a <= b)` is also true for NaN. Each offset is compared with the
        // radius first, so the squares are of numbers ≤ 1 and cannot
        // saturate in fixed point.
        if !(dx.abs() <= radius && dy.abs() <= radius) {
            return None;
        }
        let nx = dx * inverse_radius;
        let ny = dy * inverse_radius;
        let d2 = nx * nx + ny * ny;
        if !(d2.is_valid() && d2 <= S::ONE) {
            return None;
        }
        Some(quantise_unit(d2))
    }

    fn length_to_polar(v: S) -> S {
        v
    }
    fn length_from_polar(v: S) -> S {
        v
    }
    fn ratio_to_polar(v: S) -> S {
        v
    }
    fn ratio_from_polar(v: S) -> S {
        v
    }
    fn pack(ratios: [S; 3]) -> [S; 3] {
        ratios
    }
    fn unpack(packed: [S; 3]) -> [S; 3] {
        packed
    }
}

/// Three [`Ratio`]s of [`Fixed32`] without the padding of each (module
/// docs): the mantissas and the exponents.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PackedScaled {
    mantissas: [i32; 3],
    exponents: [i16; 3],
}

impl TrackNumeric for Fixed32 {
    type Polar = f32;
    type CircleScale = ();
    type PackedRatios = PackedScaled;

    fn circle_scale(radius: Length) -> Option<()> {
        (radius.is_valid() && radius > Length::ZERO).then_some(())
    }

    /// Exact in integers: the offsets and the radius are words of the same
    /// format, so (dx² + dy²) ≤ r² is decided exactly in 64 bits (each
    /// square < 2⁶²), and the ratio is formed by one division of the two,
    /// shifted so that the divisor fits 32 bits (2⁻³¹ relative).
    fn circle_cost(dx: Length, dy: Length, radius: Length, _: ()) -> Option<u16> {
        if !(dx.is_valid() && dy.is_valid() && radius.is_valid()) {
            return None;
        }
        let r = radius.to_bits().unsigned_abs();
        let (x, y) = (dx.to_bits().unsigned_abs(), dy.to_bits().unsigned_abs());
        if x > r || y > r {
            return None;
        }
        let square = |v: u32| u64::from(v).wrapping_mul(u64::from(v));
        // Each square < 2⁶², so the sum fits.
        let offset = square(x).wrapping_add(square(y));
        let limit = square(r);
        if offset > limit || limit == 0 {
            return None;
        }
        let shift = (u64::BITS - limit.leading_zeros()).saturating_sub(32);
        let (n, d) = (offset >> shift, limit >> shift);
        // n ≤ d < 2³², so n·MAX_COST < 2⁴⁸; d ≥ 1.
        let cost = n
            .wrapping_mul(u64::from(MAX_COST))
            .wrapping_add(d / 2)
            .checked_div(d)?;
        u16::try_from(cost).ok().map(|c| c.min(MAX_COST))
    }

    fn length_to_polar(v: Length) -> f32 {
        match v {
            Length::MAX => f32::INFINITY,
            Length::MIN => f32::NEG_INFINITY,
            // Exact below 2²⁴ steps (4 096 m), 24 significant bits beyond.
            _ => v.to_bits() as f32 * (1.0 / (1u32 << Length::FRAC_BITS) as f32),
        }
    }

    fn length_from_polar(v: f32) -> Length {
        let steps = libm::roundf(v * (1u32 << Length::FRAC_BITS) as f32);
        // NaN fails both tests; the sentinels are out of range.
        if steps > i32::MIN as f32 && steps < i32::MAX as f32 {
            Length::from_bits(steps as i32)
        } else if steps < 0.0 {
            Length::MIN
        } else {
            Length::MAX
        }
    }

    fn ratio_to_polar(v: Ratio) -> f32 {
        if v.is_invalid() {
            return f32::NAN;
        }
        libm::ldexpf(v.mantissa() as f32, v.exponent())
    }

    fn ratio_from_polar(v: f32) -> Ratio {
        if !v.is_finite() {
            return Ratio::INVALID;
        }
        // v = f·2^e, 0.5 ≤ |f| < 1: f·2²⁴ is an exact integer.
        let (f, e) = libm::frexpf(v);
        Ratio::from_wide((f * (1u32 << 24) as f32) as i64, e.saturating_sub(24))
    }

    fn pack(ratios: [Ratio; 3]) -> PackedScaled {
        PackedScaled {
            mantissas: ratios.map(|r| r.mantissa()),
            // The exponents of valid values lie in −200..=100; the invalid
            // value's is 0.
            exponents: ratios.map(|r| r.exponent() as i16),
        }
    }

    fn unpack(packed: PackedScaled) -> [Ratio; 3] {
        let mut out = [Ratio::ZERO; 3];
        for ((o, &m), &e) in out
            .iter_mut()
            .zip(packed.mantissas.iter())
            .zip(packed.exponents.iter())
        {
            *o = if m == i32::MIN {
                Ratio::INVALID
            } else {
                // Already normalised: from_wide gives back the same value.
                Ratio::from_wide(i64::from(m), i32::from(e))
            };
        }
        out
    }
}
