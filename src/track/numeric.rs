//! The track table's operations of each number system ([`Numeric`](crate::num::Numeric)'s
//! circle, grid, polar and covariance items, whose docs say what each
//! does): their generic forms for every [`Scalar`] and the fast fixed
//! point's ([`Fixed32`](crate::num::Fixed32)) integer forms, and the fast fixed point's two
//! track-table numbers, [`FixedVariance`] and [`FixedGridScale`].

use super::assign::MAX_COST;
use crate::num::fixed32::{Fixed32Guard, Ratio};
use crate::num::wide::wide_mul;
use crate::num::{NumError, Quantity, Real, Scalar};

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

/// The track table's operations of a [`Scalar`] (its [`Numeric`](crate::num::Numeric) items).
pub(crate) mod scalar {
    use super::{positive_inverse, quantise_unit, square_root_bound, truncate_to_u32};
    use crate::num::Scalar;

    /// cells / (max − min), formed once per scan; the cell is
    /// ⌊(v − min)·scale⌋ (a difference, a product and a truncation, each
    /// monotone).
    pub(crate) fn grid_scale<S: Scalar>(min: S, max: S, cells: u16) -> S {
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
    pub(crate) fn grid_cell<S: Scalar>(v: S, min: S, _max: S, scale: S) -> u32 {
        truncate_to_u32((v - min) * scale)
    }

    /// 1/r² for a float, 1/r for Q32.32 (module docs).
    pub(crate) fn circle_scale<S: Scalar>(radius: S) -> Option<S> {
        let square = if S::RELATIVE_PRECISION {
            radius * radius
        } else {
            radius
        };
        positive_inverse(square)
    }

    /// r² = σ²·F and 1/r² for a float, the reach bounded from r²'s bits
    /// (`square_root_bound`, a private helper); Q32.32 the radius itself.
    pub(crate) fn scaled_circle<S: Scalar>(sigma: S, factor: S) -> Option<(S, S)> {
        if !S::RELATIVE_PRECISION {
            let radius = factor.sqrt() * sigma;
            return Some((radius, circle_scale(radius)?));
        }
        let square = sigma * sigma * factor;
        Some((square_root_bound(square)?, positive_inverse(square)?))
    }

    /// A float's reach is its radius when the scale is 1/reach² (a circle
    /// formed from its radius), else the radius is √(1/scale).
    pub(crate) fn circle_radius<S: Scalar>(reach: S, scale: S) -> S {
        if S::RELATIVE_PRECISION && S::ONE / (reach * reach) != scale {
            (S::ONE / scale).sqrt()
        } else {
            reach
        }
    }

    pub(crate) fn circle_cost<S: Scalar>(dx: S, dy: S, reach: S, scale: S) -> Option<u16> {
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
}

/// A covariance number of the fast fixed point: I16F16 in an `i32` word
/// (±32 768, steps of 2⁻¹⁶), saturating like the [`Fixed32`](crate::num::Fixed32) quantities
/// (`i32::MIN`/`MAX` are sentinels, sticky). Products and quotients are
/// formed in 64 bits and rounded to nearest once.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
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

    /// `i32::MAX` or `i32::MIN`: the word less `i32::MAX`, unsigned, is 0
    /// or (wrapping) 1 for them alone.
    #[inline(always)]
    fn is_sentinel(self) -> bool {
        (self.0 as u32).wrapping_sub(i32::MAX as u32) < 2
    }

    /// `wide` as a word, or the sentinel of its sign: a value within a
    /// word (its high word the sign of its low one) is that word, the
    /// sentinels' own values included; one beyond, the sentinel of its
    /// sign.
    #[inline(always)]
    fn saturate(wide: i64) -> Self {
        let low = wide as i32;
        if (wide >> 32) as i32 == low >> 31 {
            FixedVariance(low)
        } else {
            Self::sentinel(wide < 0)
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
        // The sentinels swap; the lowest valid word, 1 − 2³¹, negates to
        // i32::MAX, the sentinel its exact negation saturates to.
        match self {
            Self::MAX => Self::MIN,
            Self::MIN => Self::MAX,
            FixedVariance(v) => FixedVariance(v.wrapping_neg()),
        }
    }
}

impl core::ops::Sub for FixedVariance {
    type Output = Self;
    /// The exact difference, saturated; with a sentinel operand, the sum
    /// with −`rhs` (whose sentinels swap). Not `self + (-rhs)` for valid
    /// operands: the negation of the lowest valid word is a sentinel, which
    /// made a difference with that word as `rhs` a sentinel for any
    /// negative `self`.
    fn sub(self, rhs: Self) -> Self {
        if self.is_sentinel() || rhs.is_sentinel() {
            return self + (-rhs);
        }
        Self::saturate(i64::from(self.0).wrapping_sub(i64::from(rhs.0)))
    }
}

impl core::ops::Mul for FixedVariance {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        // |a·b| < 2⁶²: exact; rounded half up to 16 fractional bits.
        let product = wide_mul(self.0, rhs.0);
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
        Self::from_fixed_ratio(self.to_fixed_ratio() / rhs.to_fixed_ratio())
    }
}

impl Quantity for FixedVariance {
    const ZERO: Self = FixedVariance(0);
    const UNIT_ROUNDOFF: f64 = 0.0;
    const ABS_RESOLUTION: f64 = 1.0 / (1u32 << Self::FRAC_BITS) as f64;
    /// The fast fixed point's: this is its covariance number.
    type Guard = Fixed32Guard;

    fn try_from_f64(v: f64) -> Result<Self, NumError> {
        if !v.is_finite() {
            return Err(NumError::NotFinite);
        }
        let converted = Self::from_f64_lossy(v);
        if converted.is_sentinel() {
            Err(NumError::OutOfRange)
        } else {
            Ok(converted)
        }
    }

    fn from_f64_lossy(v: f64) -> Self {
        if v.is_nan() {
            return Self::MAX;
        }
        let steps = libm::round(v * f64::from(1u32 << Self::FRAC_BITS));
        if steps >= f64::from(i32::MAX) {
            Self::MAX
        } else if steps <= f64::from(i32::MIN) {
            Self::MIN
        } else {
            FixedVariance(steps as i32)
        }
    }

    fn to_f64(self) -> f64 {
        match self {
            Self::MAX => f64::INFINITY,
            Self::MIN => f64::NEG_INFINITY,
            FixedVariance(v) => f64::from(v) / f64::from(1u32 << Self::FRAC_BITS),
        }
    }

    fn is_valid(self) -> bool {
        !self.is_sentinel()
    }

    fn abs(self) -> Self {
        if self.is_sentinel() {
            Self::MAX
        } else {
            FixedVariance(self.0.wrapping_abs())
        }
    }

    /// Rounded half up.
    fn half(self) -> Self {
        if self.is_sentinel() {
            self
        } else {
            FixedVariance(self.0.wrapping_add(1) >> 1)
        }
    }

    fn check_input(self, guard: &mut Fixed32Guard) {
        guard.reject_sentinel(self.0);
    }

    fn check_output(self, guard: &mut Fixed32Guard) {
        guard.reject_sentinel(self.0);
    }

    fn sub_guarded(self, b: Self, guard: &mut Fixed32Guard) -> Self {
        FixedVariance(guard.narrow(i64::from(self.0).wrapping_sub(i64::from(b.0))))
    }
}

impl Real for FixedVariance {
    const ONE: Self = FixedVariance(1 << Self::FRAC_BITS);
    const TWO: Self = FixedVariance(2 << Self::FRAC_BITS);

    /// Through the fast fixed point's ratios, as the quotients.
    fn sqrt(self) -> Self {
        Self::from_fixed_ratio(self.to_fixed_ratio().sqrt())
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

impl FixedGridScale {
    /// Every offset in cell 0.
    pub(crate) const ZERO: Self = FixedGridScale {
        shift: 0,
        multiplier: 0,
    };
}

/// The track table's operations of the fast fixed point ([`Fixed32`](crate::num::Fixed32)'s
/// [`Numeric`](crate::num::Numeric) items).
pub(crate) mod fixed {
    use super::{FixedGridScale, MAX_COST};
    use crate::num::fixed32::{Length, Ratio};
    use crate::num::wide::div_wide_short;
    use crate::num::wide::wide_mul_unsigned;
    use crate::num::Quantity;

    /// The offsets are the words' differences, exact in 32 bits for
    /// min ≤ v ≤ max.
    pub(crate) fn grid_scale(min: Length, max: Length, cells: u16) -> FixedGridScale {
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
    pub(crate) fn grid_cell(v: Length, min: Length, max: Length, scale: FixedGridScale) -> u32 {
        // Not `clamp`, which panics should min exceed max.
        let v = v.to_bits().min(max.to_bits()).max(min.to_bits());
        let offset = v.wrapping_sub(min.to_bits()) as u32;
        let reduced = offset >> scale.shift.min(31);
        // reduced ≤ extent' for v ≤ max: the product is below cells·2¹⁶.
        reduced.wrapping_mul(scale.multiplier) >> 16
    }

    pub(crate) fn circle_scale(radius: Length) -> Option<()> {
        (radius.is_valid() && radius > Length::ZERO).then_some(())
    }

    /// [`crate::num::numeric::circle_box`] on the words: for a centre
    /// within ±(2³⁰ − 1) steps and a reach within ±2²⁹ steps no sum
    /// saturates or meets a sentinel, so the saturating operations are the
    /// words' own (each halving rounds as `Length::half`, up on a tie);
    /// anything else takes the saturating operations.
    #[inline]
    pub(crate) fn circle_bounds(center: [Length; 2], reach: Length) -> ([Length; 2], [Length; 2]) {
        let [x, y] = center.map(Length::to_bits);
        let r = reach.to_bits();
        let within = |v: i32, limit: u32| v.unsigned_abs() < limit;
        if !(within(x, 1 << 30) && within(y, 1 << 30) && within(r, (1 << 29) + 1)) {
            return crate::num::numeric::circle_box::<crate::num::Fixed32>(center, reach);
        }
        // |r| ≤ 2²⁹: no step wraps, and |half| < 2³⁰.
        let sixteenth = (0..4).fold(r, |h, _| h.wrapping_add(1) >> 1);
        let half = r.wrapping_add(sixteenth);
        let word = Length::from_bits;
        (
            [word(x.wrapping_sub(half)), word(y.wrapping_sub(half))],
            [word(x.wrapping_add(half)), word(y.wrapping_add(half))],
        )
    }

    /// The offsets `z` − `center` on the words when both lie within
    /// ±(2³⁰ − 1) steps (no difference then saturates or meets a
    /// sentinel, so the saturating subtraction is the words' own), then
    /// [`circle_cost`]; anything else through the saturating subtraction.
    #[inline]
    pub(crate) fn circle_cost_at(
        z: [Length; 2],
        center: [Length; 2],
        reach: Length,
    ) -> Option<u16> {
        let within = |v: Length| v.to_bits().unsigned_abs() < 1 << 30;
        if !(within(z[0]) && within(z[1]) && within(center[0]) && within(center[1])) {
            return circle_cost(z[0] - center[0], z[1] - center[1], reach, ());
        }
        let offset =
            |a: Length, b: Length| Length::from_bits(a.to_bits().wrapping_sub(b.to_bits()));
        circle_cost(offset(z[0], center[0]), offset(z[1], center[1]), reach, ())
    }

    /// Exact in integers: the offsets and the radius are words of the same
    /// format, so (dx² + dy²) ≤ r² is decided exactly in 64 bits (each
    /// square < 2⁶²), and the ratio is formed by one division of the two,
    /// shifted so that the divisor fits 32 bits (2⁻³¹ relative), on 32-bit
    /// words (no 64-bit division routine).
    pub(crate) fn circle_cost(dx: Length, dy: Length, radius: Length, _: ()) -> Option<u16> {
        if !(dx.is_valid() && dy.is_valid() && radius.is_valid()) {
            return None;
        }
        let r = radius.to_bits().unsigned_abs();
        let (x, y) = (dx.to_bits().unsigned_abs(), dy.to_bits().unsigned_abs());
        if x > r || y > r {
            return None;
        }
        let square = |v: u32| wide_mul_unsigned(v, v);
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
        // n ≤ d < 2³² (the cast is exact), so n·MAX_COST < 2⁴⁸; d ≥ 1.
        let numerator = wide_mul_unsigned(n as u32, u32::from(MAX_COST)).wrapping_add(d / 2);
        // The floor of numerator/d without a 64-bit division: both scaled
        // by 2^s so that d's top bit is set ([`div_wide_short`]'s divisor);
        // the quotient (≤ MAX_COST + ½ < 2¹⁶) is unchanged, and
        // numerator·2^s < d·2^s·2¹⁶ < 2⁴⁸: its bits above the low 16 are
        // below the divisor ([`div_wide_short`]'s condition).
        let d = u32::try_from(d).ok().filter(|&d| d != 0)?;
        let s = d.leading_zeros();
        let numerator = numerator << s;
        let cost = div_wide_short((numerator >> 32) as u32, numerator as u32, d << s);
        u16::try_from(cost).ok().map(|c| c.min(MAX_COST))
    }

    pub(crate) fn length_to_polar(v: Length) -> f32 {
        match v {
            Length::MAX => f32::INFINITY,
            Length::MIN => f32::NEG_INFINITY,
            // Exact below 2²⁴ steps (4 096 m), 24 significant bits beyond.
            _ => v.to_bits() as f32 * (1.0 / (1u32 << Length::FRAC_BITS) as f32),
        }
    }

    pub(crate) fn length_from_polar(v: f32) -> Length {
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

    pub(crate) fn ratio_to_polar(v: Ratio) -> f32 {
        if v.is_invalid() {
            return f32::NAN;
        }
        libm::ldexpf(v.mantissa() as f32, v.exponent())
    }

    pub(crate) fn ratio_from_polar(v: f32) -> Ratio {
        if !v.is_finite() {
            return Ratio::INVALID;
        }
        // v = f·2^e, 0.5 ≤ |f| < 1: f·2²⁴ is an exact integer.
        let (f, e) = libm::frexpf(v);
        Ratio::from_wide((f * (1u32 << 24) as f32) as i64, e.saturating_sub(24))
    }
}

impl FixedVariance {
    /// A ratio as a covariance number (saturating): [`Numeric::to_variance`](crate::num::Numeric::to_variance)
    /// of [`Fixed32`](crate::num::Fixed32).
    pub(crate) fn from_fixed_ratio(r: Ratio) -> FixedVariance {
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

    /// Back: [`Numeric::from_variance`](crate::num::Numeric::from_variance) of [`Fixed32`](crate::num::Fixed32).
    pub(crate) fn to_fixed_ratio(self) -> Ratio {
        if !self.is_valid() {
            return Ratio::INVALID;
        }
        Ratio::from_wide(i64::from(self.0), FixedVariance::EXPONENT)
    }
}
