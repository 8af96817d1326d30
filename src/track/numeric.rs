//! The number systems a track table runs in ([`TrackNumeric`]): a
//! [`Numeric`] with the few operations the table needs beyond the filters'
//! algebra, for `f64`, `f32`, Q32.32 (every [`Scalar`]) and the fast fixed
//! point ([`Fixed32`]).
//!
//! * The gate test of a circle and its cost, the squared distance
//!   normalised by the radius, quantised to `u16` (the solver's currency):
//!   floats multiply the squared distance by 1/r², Q32.32 the offsets by
//!   1/r (its squares of metres would overflow), each formed once per
//!   track; [`Fixed32`] compares the squared offsets with the squared
//!   radius exactly in 64-bit integers and divides once per gated pair. A
//!   gate given by its squared radius σ²·F ([`TrackNumeric::scaled_circle`])
//!   needs no square root in floats: the box around it takes an upper bound
//!   of √(σ²·F) from the float's bits (within 6.1 %).
//! * Polar geometry (projecting range and azimuth; range/azimuth windows)
//!   runs in a [`Scalar`]: the type itself, or `f32` for [`Fixed32`], which
//!   has no sine or arctangent (in software on its cores, library calls
//!   rather than Q32.32's inlined 128-bit arithmetic, 13 KB less flash on the
//!   micro:bit; 24 significant bits: 6 mm at 100 km). Only polar
//!   measurements and He et al.'s range/azimuth windows take this path.
//! * The covariance that sizes a gate ([`super::ErrorVariance`], in units
//!   of σ²) is kept and propagated in the ratio type, except in [`Fixed32`],
//!   whose ratios ([`Ratio`], a mantissa and an exponent in software) cost
//!   about 100 instructions an operation on the Cortex-M3: there it is
//!   [`FixedVariance`], a 32-bit I16F16 word (its envelope: intervals of at
//!   least 8 ms, `docs/track-table.md`).

use core::fmt::Debug;

use super::assign::MAX_COST;
use super::model::VarianceNumber;
use crate::num::fixed32::{Fixed32, Length, Ratio};
use crate::num::{Numeric, Quantity, Real, Scalar};

/// A [`Numeric`] the track table runs in (module docs).
pub trait TrackNumeric: Numeric {
    /// The scalar type of the polar geometry.
    type Polar: Scalar;
    /// What a circular gate keeps to test measurements (the reciprocal of
    /// its radius, for floats and Q32.32).
    type CircleScale: Copy + Debug + PartialEq;
    /// The number type of the gate's covariance bookkeeping.
    type Variance: VarianceNumber;

    /// The circle's scale for `radius` (> 0), or `None` if it cannot be
    /// formed.
    fn circle_scale(radius: Self::Length) -> Option<Self::CircleScale>;

    /// The circle of radius σ·√`factor` (σ = `sigma` > 0, `factor` > 0):
    /// a half-width at least the radius (its reach: the pre-gate's box and
    /// the first test of each offset) and its scale, or `None` if it cannot
    /// be formed. By default the radius itself and [`Self::circle_scale`];
    /// floats form r² and bound √r² without a square root (module docs).
    fn scaled_circle(
        sigma: Self::Length,
        factor: Self::Ratio,
    ) -> Option<(Self::Length, Self::CircleScale)> {
        let radius = factor.sqrt() * sigma;
        Some((radius, Self::circle_scale(radius)?))
    }

    /// The radius of a circle of reach `reach` and scale `scale`: by
    /// default the reach itself.
    fn circle_radius(reach: Self::Length, _scale: Self::CircleScale) -> Self::Length {
        reach
    }

    /// The cost `round((dx² + dy²)/r²·MAX_COST)` of a measurement offset
    /// (dx, dy) from the centre of a circle of reach `reach` (at least its
    /// radius r) and scale `scale`, or `None` if it lies outside (or an
    /// operand is invalid).
    fn circle_cost(
        dx: Self::Length,
        dy: Self::Length,
        reach: Self::Length,
        scale: Self::CircleScale,
    ) -> Option<u16>;

    /// What the pre-gate's grid keeps per axis to map a coordinate's offset
    /// from the measurements' minimum to its cell.
    type GridScale: Copy + Debug;
    /// A scale that puts every offset in cell 0.
    const GRID_SCALE_ZERO: Self::GridScale;

    /// The scale that spreads `min ..= max` over `cells` cells (about
    /// equal widths); everything in cell 0 if it cannot be formed.
    fn grid_scale(min: Self::Length, max: Self::Length, cells: u16) -> Self::GridScale;

    /// The cell of a valid `v` over `min ..= max` (below `min`, cell 0;
    /// the caller caps the result at the last cell): non-decreasing in `v`,
    /// rounding included, so that a box's cells hold every point inside it.
    fn grid_cell(
        v: Self::Length,
        min: Self::Length,
        max: Self::Length,
        scale: Self::GridScale,
    ) -> u32;

    /// A length in the polar scalar (exact).
    fn length_to_polar(v: Self::Length) -> Self::Polar;
    /// Back, rounded to the length's resolution (invalid if out of range).
    fn length_from_polar(v: Self::Polar) -> Self::Length;
    /// A ratio (an angle in radians) in the polar scalar.
    fn ratio_to_polar(v: Self::Ratio) -> Self::Polar;
    /// Back (invalid if out of range).
    fn ratio_from_polar(v: Self::Polar) -> Self::Ratio;

    /// A ratio as a covariance number (saturating).
    fn to_variance(r: Self::Ratio) -> Self::Variance;
    /// Back.
    fn from_variance(v: Self::Variance) -> Self::Ratio;
}

/// A value in [0, 1] to `0 ..= MAX_COST`, rounded to nearest: scaled in
/// `S` (one product and one sum), then to an integer, `f32` directly (one
/// instruction with an FPU; through `f64` it costs ~110 on the M4F, whose FPU
/// has no double precision), the others through `f64`.
pub(super) fn quantise_unit<S: Scalar>(v: S) -> u16 {
    let scaled = v * S::from_f64_lossy(MAX_COST as f64) + S::from_f64_lossy(0.5);
    // The caller checked 0 ≤ v ≤ 1.
    truncate_to_u32(scaled).min(MAX_COST as u32) as u16
}

/// 1/v if it is a valid number > 0.
fn positive_inverse<S: Scalar>(v: S) -> Option<S> {
    let inverse = S::ONE / v;
    (inverse.is_valid() && inverse > S::ZERO).then_some(inverse)
}

/// A number at least √v for a valid v > 0, `None` otherwise: for a normal
/// `f32` or `f64`, half its bits plus half the exponent bias and one unit
/// in the last place (the tangent of √ at the power of four below v, which
/// lies above it: within 6.1 % of √v, no square root); else `S::sqrt`.
fn square_root_bound<S: Scalar>(v: S) -> Option<S> {
    if !(v.is_valid() && v > S::ZERO) {
        return None;
    }
    let mut bound = v;
    let any: &mut dyn core::any::Any = &mut bound;
    if let Some(single) = any.downcast_mut::<f32>() {
        if *single >= f32::MIN_POSITIVE {
            *single = f32::from_bits((single.to_bits() >> 1).wrapping_add(0x1fc0_0001));
            return Some(bound);
        }
    } else if let Some(double) = any.downcast_mut::<f64>() {
        if *double >= f64::MIN_POSITIVE {
            *double = f64::from_bits((double.to_bits() >> 1).wrapping_add(0x1ff8_0000_0000_0001));
            return Some(bound);
        }
    }
    let root = v.sqrt();
    root.is_valid().then_some(root)
}

/// A number ≥ 0 truncated to an integer: `f32` directly (one instruction
/// with an FPU), the others through `f64`; saturating, NaN to 0.
fn truncate_to_u32<S: Scalar>(v: S) -> u32 {
    let any: &dyn core::any::Any = &v;
    match any.downcast_ref::<f32>() {
        Some(single) => *single as u32,
        None => v.to_f64() as u32,
    }
}

impl<S: Scalar> TrackNumeric for S {
    type Polar = S;
    type CircleScale = S;
    type Variance = S;
    type GridScale = S;
    const GRID_SCALE_ZERO: S = S::ZERO;

    /// cells / (max − min), formed once per scan; the cell is
    /// ⌊(v − min)·scale⌋ (a difference, a product and a truncation, each
    /// monotone).
    fn grid_scale(min: S, max: S, cells: u16) -> S {
        let scale = S::from_f64_lossy(f64::from(cells)) / (max - min);
        if scale.is_valid() && scale > S::ZERO {
            scale
        } else {
            S::ZERO
        }
    }

    /// Not clamped: a coordinate below `min` maps to a number < 0 and one
    /// above `max` to one ≥ the cell of `max`, which the saturating
    /// truncation takes to 0 and to a cell the caller caps.
    fn grid_cell(v: S, min: S, _max: S, scale: S) -> u32 {
        truncate_to_u32((v - min) * scale)
    }

    /// 1/r² for a float, 1/r for Q32.32 (module docs).
    fn circle_scale(radius: S) -> Option<S> {
        let square = if S::RELATIVE_PRECISION {
            radius * radius
        } else {
            radius
        };
        positive_inverse(square)
    }

    /// r² = σ²·F and 1/r² for a float, the reach bounded from r²'s bits
    /// (`square_root_bound`, a private helper); Q32.32 by the default.
    fn scaled_circle(sigma: S, factor: S) -> Option<(S, S)> {
        if !S::RELATIVE_PRECISION {
            let radius = factor.sqrt() * sigma;
            return Some((radius, Self::circle_scale(radius)?));
        }
        let square = sigma * sigma * factor;
        Some((square_root_bound(square)?, positive_inverse(square)?))
    }

    /// A float's reach is its radius when the scale is 1/reach² (a circle
    /// formed from its radius), else the radius is √(1/scale).
    fn circle_radius(reach: S, scale: S) -> S {
        if S::RELATIVE_PRECISION && S::ONE / (reach * reach) != scale {
            (S::ONE / scale).sqrt()
        } else {
            reach
        }
    }

    fn circle_cost(dx: S, dy: S, reach: S, scale: S) -> Option<u16> {
        // `!(a <= b)` is also true for NaN. Each offset is compared with the
        // reach first, so Q32.32's squares are of numbers ≤ 1 and cannot
        // saturate.
        if !(dx.abs() <= reach && dy.abs() <= reach) {
            return None;
        }
        let d2 = if S::RELATIVE_PRECISION {
            (dx * dx + dy * dy) * scale
        } else {
            let (nx, ny) = (dx * scale, dy * scale);
            nx * nx + ny * ny
        };
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
    fn to_variance(r: S) -> S {
        r
    }
    fn from_variance(v: S) -> S {
        v
    }
}

/// A covariance number of the fast fixed point: I16F16 in an `i32` word
/// (±32 768, steps of 2⁻¹⁶), saturating like the [`Fixed32`] quantities
/// (`i32::MIN`/`MAX` are sentinels, sticky). Products and quotients are
/// formed in 64 bits and rounded to nearest once.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedVariance(i32);

impl FixedVariance {
    const FRAC_BITS: u32 = 16;
    /// The binary exponent of one step, −16.
    const EXPONENT: i32 = -16;
    const MAX: Self = FixedVariance(i32::MAX);
    const MIN: Self = FixedVariance(i32::MIN);

    /// The raw word (value × 2¹⁶).
    pub const fn to_bits(self) -> i32 {
        self.0
    }

    fn is_sentinel(self) -> bool {
        self.0 == i32::MIN || self.0 == i32::MAX
    }

    /// `wide` as a word, or the sentinel of its sign.
    fn saturate(wide: i64) -> Self {
        match i32::try_from(wide) {
            Ok(v) if v != i32::MIN && v != i32::MAX => FixedVariance(v),
            _ => {
                if wide < 0 {
                    Self::MIN
                } else {
                    Self::MAX
                }
            }
        }
    }

    /// The sentinel a result with the sign of `negative` saturates to.
    fn sentinel(negative: bool) -> Self {
        if negative {
            Self::MIN
        } else {
            Self::MAX
        }
    }
}

impl core::ops::Add for FixedVariance {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        let wide = i64::from(self.0).wrapping_add(i64::from(rhs.0));
        if self.is_sentinel() || rhs.is_sentinel() {
            return Self::sentinel(wide < 0);
        }
        Self::saturate(wide)
    }
}

impl core::ops::Neg for FixedVariance {
    type Output = Self;
    fn neg(self) -> Self {
        // The valid range is symmetric; the sentinels swap.
        match self {
            Self::MAX => Self::MIN,
            Self::MIN => Self::MAX,
            FixedVariance(v) => FixedVariance(v.wrapping_neg()),
        }
    }
}

impl core::ops::Sub for FixedVariance {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        self + (-rhs)
    }
}

impl core::ops::Mul for FixedVariance {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        // |a·b| < 2⁶²: exact; rounded half up to 16 fractional bits.
        let product = i64::from(self.0).wrapping_mul(i64::from(rhs.0));
        if self.is_sentinel() || rhs.is_sentinel() {
            return Self::sentinel(product < 0);
        }
        let half = 1i64 << (Self::FRAC_BITS - 1);
        Self::saturate(product.wrapping_add(half) >> Self::FRAC_BITS)
    }
}

/// Through the fast fixed point's ratios: the quotients of the bookkeeping
/// (1/T after two points, β/T once per scan) are few, and [`Ratio`]'s
/// division is the one rounding rule of the number system.
impl core::ops::Div for FixedVariance {
    type Output = Self;
    fn div(self, rhs: Self) -> Self {
        Fixed32::to_variance(Fixed32::from_variance(self) / Fixed32::from_variance(rhs))
    }
}

impl VarianceNumber for FixedVariance {
    const ZERO: Self = FixedVariance(0);
    const ONE: Self = FixedVariance(1 << Self::FRAC_BITS);
    fn is_valid(self) -> bool {
        !self.is_sentinel()
    }
}

/// The fast fixed point's grid scale: the offset's word is shifted right
/// by `shift` (the extent then fits 16 bits), multiplied by `multiplier`
/// (⌊cells·2¹⁶ / (extent' + 1)⌋) and shifted right by 16: integers only,
/// no division per point, no overflow (the product is < cells·2¹⁶ ≤ 2²⁴).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FixedGridScale {
    shift: u32,
    multiplier: u32,
}

impl TrackNumeric for Fixed32 {
    type Polar = f32;
    type CircleScale = ();
    type Variance = FixedVariance;
    type GridScale = FixedGridScale;
    const GRID_SCALE_ZERO: FixedGridScale = FixedGridScale {
        shift: 0,
        multiplier: 0,
    };

    /// The offsets are the words' differences, exact in 32 bits for
    /// min ≤ v ≤ max.
    fn grid_scale(min: Length, max: Length, cells: u16) -> FixedGridScale {
        let extent = max.to_bits().wrapping_sub(min.to_bits()) as u32;
        let shift = u32::BITS
            .saturating_sub(extent.leading_zeros())
            .saturating_sub(16);
        let reduced = (extent >> shift).saturating_add(1);
        FixedGridScale {
            shift,
            multiplier: (u32::from(cells) << 16).checked_div(reduced).unwrap_or(0),
        }
    }

    /// `v` clamped to `min ..= max` first (a word's difference beyond
    /// them would wrap).
    fn grid_cell(v: Length, min: Length, max: Length, scale: FixedGridScale) -> u32 {
        // Not `clamp`, which panics should min exceed max.
        let v = v.to_bits().min(max.to_bits()).max(min.to_bits());
        let offset = v.wrapping_sub(min.to_bits()) as u32;
        let reduced = offset >> scale.shift.min(31);
        // reduced ≤ extent' for v ≤ max: the product is below cells·2¹⁶.
        reduced.wrapping_mul(scale.multiplier) >> 16
    }

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
        let shift = u64::BITS
            .saturating_sub(limit.leading_zeros())
            .saturating_sub(32);
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

    fn to_variance(r: Ratio) -> FixedVariance {
        if r.is_invalid() {
            return FixedVariance::MAX;
        }
        // r = m·2^e; the word is m·2^(e + 16), rounded.
        let shift = r.exponent().saturating_add(FixedVariance::FRAC_BITS as i32);
        let m = i64::from(r.mantissa());
        if shift >= 0 {
            // |m| < 2³¹, so m·2³² fits an i64; 32 and more overflow the word.
            let s = shift.unsigned_abs().min(32);
            FixedVariance::saturate(m << s)
        } else {
            let s = shift.unsigned_abs();
            if s >= 63 {
                return FixedVariance::ZERO;
            }
            // 1 ≤ s ≤ 62: round half up.
            let half = 1i64 << s.saturating_sub(1);
            FixedVariance::saturate(m.wrapping_add(half) >> s)
        }
    }

    fn from_variance(v: FixedVariance) -> Ratio {
        if !v.is_valid() {
            return Ratio::INVALID;
        }
        Ratio::from_wide(i64::from(v.0), FixedVariance::EXPONENT)
    }
}
