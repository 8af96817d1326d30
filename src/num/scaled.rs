//! [`Scaled`]: an `i32` mantissa with its own binary exponent, the format of
//! the fast fixed point's quantities whose range spans decades (gains α, β,
//! γ and ratios; the per-interval gains β/T and γ/(2T²); T²). A product with
//! a fixed-format quantity is still one 32×32→64 multiply and a shift
//! ([`super::fixed32`]); relative precision is 2⁻³⁰ over the whole range.
//!
//! Representation: value = `mantissa · 2^exponent` with |mantissa| in
//! [2³⁰, 2³¹) (normalised), or mantissa 0 with exponent [`EXPONENT_MIN`]
//! (zero). The exponent is stored biased by −[`EXPONENT_MIN`] (as IEEE 754
//! stores its exponent), so that zero is all-zero bytes and a `static`
//! holding zeros lands in `.bss`. The invalid value (the
//! analogue of NaN) has mantissa `i32::MIN`; it is sticky, compares unordered
//! with everything, and is what an overflow ([`EXPONENT_MAX`]), a division
//! by zero or the square root of a negative number gives. Results below
//! 2^([`EXPONENT_MIN`] + 30) flush to zero.
//!
//! Every operation rounds to nearest (ties away from zero) once, on 32-bit
//! words (no 64-bit division: Knuth's algorithm D with 16-bit digits, and a
//! table-seeded Newton square root): products, quotients and square roots
//! within half a unit of the last place, hypot within half a unit plus
//! 2⁻⁶⁰ relative, sums within one unit (2⁻³⁰ relative), the
//! [`Quantity::UNIT_ROUNDOFF`] the error budget uses.

use core::cmp::Ordering;
use core::fmt;
use core::marker::PhantomData;
use core::num::NonZeroU32;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::numeric::{Quantity, Real};
use super::wide::{
    div_wide, reciprocal_estimate, wide_mul_signed_unsigned, wide_mul_unsigned, ARMV6M,
};
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
    /// exponent − [`EXPONENT_MIN`], in 0..=300.
    biased_exponent: u32,
    unit: PhantomData<U>,
}

/// The stored form of an exponent in [`EXPONENT_MIN`, `EXPONENT_MAX`].
#[inline(always)]
const fn biased(exponent: i32) -> u32 {
    exponent.wrapping_sub(EXPONENT_MIN) as u32
}

/// The largest stored exponent.
const BIASED_MAX: u32 = biased(EXPONENT_MAX);

/// An exponent's stored form for [`Scaled::finish`], before its range
/// check; an exponent far out of the range is first brought within 1000 of
/// zero, where it stays out of it (and `finish` can add one without a
/// wrap).
#[inline(always)]
fn stored(exponent: i32) -> i32 {
    exponent.clamp(-1000, 1000).wrapping_sub(EXPONENT_MIN)
}

/// Whether a mantissa is zero's or the invalid value's: the two whose
/// double is 0 as a word (one test for the operations' rare cases).
#[inline(always)]
const fn is_special(mantissa: i32) -> bool {
    (mantissa as u32).wrapping_shl(1) == 0
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
        self.mantissa == other.mantissa && self.biased_exponent == other.biased_exponent
    }
}

/// √((i + 64.5)·2²⁴), rounded, for i = 0..192: a first estimate of the
/// square root of a word in [2³⁰, 2³²) from its top 8 bits (within 0.4 %).
const SQRT_SEED: [u16; 192] = [
    32896, 33150, 33402, 33652, 33900, 34147, 34392, 34635, 34876, 35116, 35354, 35590, 35825,
    36059, 36291, 36521, 36750, 36978, 37204, 37429, 37652, 37874, 38095, 38315, 38533, 38750,
    38966, 39181, 39394, 39606, 39818, 40028, 40237, 40445, 40652, 40857, 41062, 41266, 41469,
    41671, 41871, 42071, 42270, 42468, 42665, 42861, 43057, 43251, 43445, 43637, 43829, 44020,
    44210, 44400, 44588, 44776, 44963, 45149, 45334, 45519, 45703, 45886, 46069, 46250, 46431,
    46612, 46791, 46970, 47149, 47326, 47503, 47679, 47855, 48030, 48204, 48378, 48551, 48723,
    48895, 49067, 49237, 49407, 49577, 49746, 49914, 50082, 50249, 50416, 50582, 50747, 50912,
    51077, 51241, 51404, 51567, 51730, 51892, 52053, 52214, 52374, 52534, 52694, 52853, 53011,
    53169, 53327, 53484, 53640, 53797, 53952, 54108, 54262, 54417, 54571, 54724, 54877, 55030,
    55182, 55334, 55485, 55636, 55787, 55937, 56087, 56236, 56385, 56534, 56682, 56830, 56977,
    57124, 57271, 57417, 57563, 57709, 57854, 57999, 58143, 58287, 58431, 58574, 58717, 58860,
    59002, 59144, 59286, 59427, 59568, 59709, 59849, 59989, 60129, 60268, 60407, 60546, 60684,
    60822, 60960, 61098, 61235, 61372, 61508, 61644, 61780, 61916, 62051, 62186, 62321, 62456,
    62590, 62724, 62857, 62991, 63124, 63256, 63389, 63521, 63653, 63785, 63916, 64047, 64178,
    64309, 64439, 64569, 64699, 64828, 64957, 65086, 65215, 65344, 65472,
];

/// ⌊√n⌋ for n in [2⁶², 2⁶⁴): by divisions where the core divides
/// ([`isqrt_floor_by_divisions`]), by products alone on the Cortex-M0,
/// which has no divide ([`isqrt_floor_by_products`]); the same result.
#[inline]
fn isqrt_floor_normalized(n: u64) -> u32 {
    if ARMV6M {
        isqrt_floor_by_products(n)
    } else {
        isqrt_floor_by_divisions(n)
    }
}

/// The index in [`SQRT_SEED`] of a high word in [2³⁰, 2³²) (its top 8
/// bits less 64) and the seed there, about its square root.
#[inline(always)]
fn sqrt_seed(high: u32) -> (usize, u32) {
    let index = usize::try_from(high >> 24).unwrap_or(0).wrapping_sub(64);
    let seed = u32::from(SQRT_SEED.get(index).copied().unwrap_or(u16::MAX));
    (index, seed)
}

/// `2³¹/s` for each `s` of [`SQRT_SEED`], rounded (every `s` > 2¹⁵: below
/// 2¹⁶, which the build checks).
const SQRT_SEED_RECIPROCAL: [u16; 192] = sqrt_seed_reciprocal();

// Evaluated at compile time only: an index out of range or an overflow
// would fail the build, not the firmware.
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
const fn sqrt_seed_reciprocal() -> [u16; 192] {
    let mut table = [0u16; 192];
    let mut i = 0;
    while i < 192 {
        let s = SQRT_SEED[i] as u32;
        let reciprocal = ((1u32 << 31) + s / 2) / s;
        assert!(reciprocal < 1 << 16);
        table[i] = reciprocal as u16;
        i += 1;
    }
    table
}

/// ⌊√n⌋ for n in [2⁶², 2⁶⁴) with multiplications alone, what the
/// Cortex-M0 runs (public so that the host tests compare it with exact
/// arithmetic): a seed s ≈ √h from a table on the high word h's top 8
/// bits; a Newton step s + (h − s²)/(2s) with 1/s from a second table
/// (within 2⁻¹⁶ of √n relative: half the seed's 0.4 % squared, plus the
/// table's rounding); a Newton step x − (x² − n)/(2x) on n with 1/x from
/// the wide division's first reciprocal estimate (within 3 of √n); then
/// the floor found by stepping x² by 2x ± 1, checked with exact products
/// (at most 64 steps either way, a few in practice). Outside its domain
/// the result is meaningless, but nothing panics.
pub fn isqrt_floor_by_products(n: u64) -> u32 {
    let high = (n >> 32) as u32;
    let (index, seed) = sqrt_seed(high);
    let inverse = u32::from(SQRT_SEED_RECIPROCAL.get(index).copied().unwrap_or(1));
    // h − s²: within ±2²⁵ (the seed is within 0.4 % of √h < 2¹⁶), a word.
    let offset = high.wrapping_sub(seed.wrapping_mul(seed)) as i32;
    // (h − s²)/(2s) in units of 2⁻¹⁶: offset·(2³¹/s)/2¹⁶.
    let correction = wide_mul_signed_unsigned(offset, inverse) >> 16;
    let first = (i64::from(seed) << 16)
        .wrapping_add(correction)
        .clamp(1 << 31, i64::from(u32::MAX)) as u32;
    // e = x² − n = (x − √n)(x + √n), |e| < 2¹⁶·2³³ (x within 2⁻¹⁶ of
    // √n < 2³²): an i64 as the wrapping difference.
    let excess = wide_mul_unsigned(first, first).wrapping_sub(n) as i64;
    // |e|/(2x) = |e|·(2⁶³/x)/2⁶⁴, e shifted to a word first (|e|/2¹⁸ <
    // 2³¹; what it drops moves the step by under 2⁻¹³).
    let magnitude = (excess.unsigned_abs() >> 18) as u32;
    let step = (wide_mul_unsigned(magnitude, reciprocal_estimate(first)) >> 46) as u32;
    let mut root = if excess < 0 {
        first.saturating_add(step)
    } else {
        first.saturating_sub(step)
    };
    // The floor: root² ≤ n < (root + 1)², root² updated by 2·root ∓ 1.
    let mut square = wide_mul_unsigned(root, root);
    for _ in 0..64 {
        if square <= n {
            break;
        }
        square = square.wrapping_sub(u64::from(root) << 1).wrapping_add(1);
        root = root.wrapping_sub(1);
    }
    for _ in 0..64 {
        // (root + 1)² = root² + 2·root + 1, below 2⁶⁴ for root < 2³² − 1.
        if root == u32::MAX {
            break;
        }
        let next = square.wrapping_add(u64::from(root) << 1).wrapping_add(1);
        if next > n {
            break;
        }
        (square, root) = (next, root.wrapping_add(1));
    }
    root
}

/// [`isqrt_floor_normalized`] where the core divides: the seed of
/// [`SQRT_SEED`], a Newton step on the high word (32-bit divisions), a
/// Newton step on n ([`div_wide`]) and at most two corrections checked
/// with exact products.
fn isqrt_floor_by_divisions(n: u64) -> u32 {
    let (high, low) = ((n >> 32) as u32, n as u32);
    let (_, seed) = sqrt_seed(high);
    let seed_nz = NonZeroU32::new(seed).unwrap_or(NonZeroU32::MIN);
    // (seed + high/seed)/2 with 16 fractional bits: √n within 8·10⁻⁶
    // relative (the seed's 0.4 % squared), at most 3.5 below the exact
    // Newton value, which is ≥ √n; +4 keeps it an upper bound.
    let (quotient, rest) = (high / seed_nz, high % seed_nz);
    let fraction = (rest << 16) / seed_nz;
    let sum = (u64::from(seed) << 16)
        .wrapping_add(u64::from(quotient) << 16)
        .wrapping_add(u64::from(fraction));
    let first = u32::try_from((sum >> 1).wrapping_add(4))
        .unwrap_or(u32::MAX)
        .max(1 << 31);
    // Newton from above: ⌊(x + ⌊n/x⌋)/2⌋ ≥ ⌊√n⌋ for x ≥ √n, here within 1.
    // x ≥ √n also makes n/x ≤ √n < 2³², div_wide's precondition, except
    // where the clamp to u32::MAX left x just below √n (n within 2³³ of
    // 2⁶⁴): there ⌊√n⌋ = u32::MAX, which a saturated quotient gives.
    let q = if high >= first {
        u32::MAX
    } else {
        div_wide(high, low, first).0
    };
    let mut root = ((u64::from(first).wrapping_add(u64::from(q))) >> 1) as u32;
    for _ in 0..2 {
        if wide_mul_unsigned(root, root) > n {
            root = root.wrapping_sub(1);
        }
    }
    root
}

/// Integer square root, rounded to nearest: r with |r² − n| ≤ r.
pub(crate) fn isqrt_u64(n: u64) -> u64 {
    if n == 0 {
        return 0;
    }
    // n·4^k in [2⁶², 2⁶⁴): ⌊√(n·4^k)⌋ / 2^k, truncated, is ⌊√n⌋.
    let shift = n.leading_zeros() & !1;
    let root = u64::from(isqrt_floor_normalized(n << shift) >> (shift / 2));
    // n − root² < 2·root + 1; round up when n − root² > root.
    if n.wrapping_sub(root.wrapping_mul(root)) > root {
        root.wrapping_add(1)
    } else {
        root
    }
}

impl<U> Scaled<U> {
    /// Zero carries the smallest exponent, so that a product with it is
    /// shifted out entirely however it is scaled (see
    /// [`super::fixed32`]'s guarded products); stored biased, it is
    /// all-zero bytes.
    const ZERO_VALUE: Self = Scaled {
        mantissa: 0,
        biased_exponent: biased(EXPONENT_MIN),
        unit: PhantomData,
    };
    /// The invalid value (module docs).
    pub const INVALID: Self = Scaled {
        mantissa: INVALID_MANTISSA,
        biased_exponent: biased(0),
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
        // At most 300 above EXPONENT_MIN: no wrap.
        (self.biased_exponent as i32).wrapping_add(EXPONENT_MIN)
    }

    /// Whether this is the invalid value (the sticky result of an overflow).
    #[inline]
    pub const fn is_invalid(self) -> bool {
        self.mantissa == INVALID_MANTISSA
    }

    /// Whether the value is zero.
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
            biased_exponent: self.biased_exponent,
            unit: PhantomData,
        }
    }

    /// `wide · 2^exponent`, rounded to a 31-bit mantissa.
    pub fn from_wide(wide: i64, exponent: i32) -> Self {
        if wide == 0 {
            return Self::ZERO_VALUE;
        }
        if let Ok(word) = i32::try_from(wide) {
            return Self::from_word(word, exponent);
        }
        // Beyond a word: the leading one at bit 31..=63, above the
        // mantissa's bit 30.
        let negative = wide < 0;
        let magnitude = wide.unsigned_abs();
        let top = 63u32.wrapping_sub(magnitude.leading_zeros());
        // 1..=33 bits to drop. Round half away from zero: drop all but one
        // extra bit, add it (at most 2³¹, which `finish` takes as one bit
        // more).
        let shift = top.wrapping_sub(TOP_BIT);
        let rounded = (magnitude >> shift.wrapping_sub(1)).wrapping_add(1) >> 1;
        Self::finish(
            negative,
            rounded as u32,
            stored(exponent.saturating_add(shift as i32)),
        )
    }

    /// `word · 2^exponent` for a nonzero word, with 32-bit operations: a
    /// magnitude below 2³¹ is normalised exactly by a left shift.
    #[inline(always)]
    fn from_word(word: i32, exponent: i32) -> Self {
        let negative = word < 0;
        let magnitude = word.unsigned_abs();
        if magnitude >> 31 != 0 {
            // i32::MIN: 2³¹, which `finish` takes as one bit more.
            return Self::finish(negative, magnitude, stored(exponent));
        }
        // A nonzero magnitude below 2³¹ has 1..=31 leading zeros.
        let shift = magnitude.leading_zeros().wrapping_sub(1); // 0..=30
        Self::finish(
            negative,
            magnitude << shift,
            stored(exponent.saturating_sub(shift as i32)),
        )
    }

    /// The integer `v`.
    pub fn from_int(v: i64) -> Self {
        Self::from_wide(v, 0)
    }

    fn compare(self, other: Self) -> Option<Ordering> {
        if self.is_invalid() || other.is_invalid() {
            return None;
        }
        Some(self.order_key().cmp(&other.order_key()))
    }

    /// Whether neither is the invalid value (which is unordered).
    #[inline(always)]
    fn ordered_with(self, other: Self) -> bool {
        !self.is_invalid() && !other.is_invalid()
    }

    /// A key whose order is the values' (valid values), in two words: the
    /// stored exponent, complemented for a negative mantissa, above the
    /// mantissa with its sign bit flipped. Normalised mantissas make a
    /// larger exponent a larger magnitude, and zero (mantissa 0, stored
    /// exponent 0) sorts as the smallest non-negative value.
    #[inline(always)]
    fn order_key(self) -> i64 {
        let sign = self.mantissa >> 31;
        let high = (self.biased_exponent as i32) ^ sign;
        let low = (self.mantissa as u32) ^ (1 << 31);
        (i64::from(high) << 32) | i64::from(low)
    }

    /// Rounded to nearest, ties away from zero: the product of two
    /// normalised mantissas lies in [2⁶⁰, 2⁶²), so its leading bit is one of
    /// two, both in its word above 2³⁰ ([`Self::rounded`]).
    fn multiply(self, other: Self) -> Self {
        if is_special(self.mantissa) || is_special(other.mantissa) {
            return if self.is_invalid() || other.is_invalid() {
                Self::INVALID
            } else {
                Self::ZERO_VALUE
            };
        }
        let negative = (self.mantissa ^ other.mantissa) < 0;
        let product =
            wide_mul_unsigned(self.mantissa.unsigned_abs(), other.mantissa.unsigned_abs());
        // The stored exponents lie in [0, 300]: their sum cannot wrap, and
        // that sum plus EXPONENT_MIN is the stored form of e_a + e_b.
        let stored = (self.biased_exponent.wrapping_add(other.biased_exponent) as i32)
            .wrapping_add(EXPONENT_MIN);
        // ⌊product/2³⁰⌋ is in [2³⁰, 2³² − 4], the next bit down is bit 29.
        Self::rounded(
            negative,
            (product >> 30) as u32,
            ((product as u32) >> 29) & 1,
            stored.wrapping_add(30),
        )
    }

    /// ±`magnitude`·2^e for a magnitude in [2³⁰, 2³¹] (2³¹ is one bit
    /// more) and `stored` = e − [`EXPONENT_MIN`], within about 1000 of the
    /// range [0, 300] it is checked against: the last step of every
    /// operation.
    #[inline(always)]
    fn finish(negative: bool, magnitude: u32, stored: i32) -> Self {
        let (m, stored) = if magnitude >> 31 != 0 {
            (magnitude >> 1, stored.wrapping_add(1))
        } else {
            (magnitude, stored)
        };
        // One unsigned test for both ends; the rare case tells them apart.
        if stored as u32 > BIASED_MAX {
            return if stored < 0 {
                Self::ZERO_VALUE
            } else {
                Self::INVALID
            };
        }
        // m < 2³¹: the cast is exact and the negation cannot wrap.
        let m = m as i32;
        Scaled {
            mantissa: if negative { m.wrapping_neg() } else { m },
            biased_exponent: stored as u32,
            unit: PhantomData,
        }
    }

    /// Correctly rounded (to nearest, ties away from zero): the 32-bit
    /// quotient of the mantissas by [`div_wide`], whose last bit is the
    /// rounding bit.
    fn divide(self, other: Self) -> Self {
        if self.is_invalid() || other.is_invalid() || other.is_zero() {
            return Self::INVALID;
        }
        if self.is_zero() {
            return Self::ZERO_VALUE;
        }
        let negative = (self.mantissa ^ other.mantissa) < 0;
        let (a, b) = (self.mantissa.unsigned_abs(), other.mantissa.unsigned_abs());
        // a, b in [2³⁰, 2³¹): with v = 2b ≥ 2³¹ the quotient q of
        // (2a or a)·2³² by v lies in [2³¹, 2³²): q = ⌊a·2³²/b⌋ when a < b,
        // ⌊a·2³¹/b⌋ otherwise.
        let difference = self.exponent().wrapping_sub(other.exponent());
        let (high, exponent) = if a < b {
            (a << 1, difference.wrapping_sub(31))
        } else {
            (a, difference.wrapping_sub(30))
        };
        let (q, _) = div_wide(high, 0, b << 1);
        // q/2, rounded half up on the exact quotient: its half bit is q's
        // last bit (the remainder only decides ties, which round up too).
        Self::finish(negative, (q >> 1).wrapping_add(q & 1), stored(exponent))
    }

    fn sum(self, other: Self) -> Self {
        if is_special(self.mantissa) || is_special(other.mantissa) {
            return if self.is_invalid() || other.is_invalid() {
                Self::INVALID
            } else if self.is_zero() {
                other
            } else {
                self
            };
        }
        // One copy of the rest for each order (no selects to swap them).
        if self.biased_exponent >= other.biased_exponent {
            Self::ordered_sum(self, other)
        } else {
            Self::ordered_sum(other, self)
        }
    }

    /// The sum of two nonzero numbers, `high`'s exponent the larger.
    #[inline(always)]
    fn ordered_sum(high: Self, low: Self) -> Self {
        let gap = high.biased_exponent.wrapping_sub(low.biased_exponent); // ≥ 0
        if gap > 31 {
            return Self::sum_far_apart(high, low, gap);
        }
        let (low_word, fraction) = Self::aligned(low, gap);
        if (high.mantissa ^ low.mantissa) >= 0 {
            Self::sum_of_magnitudes(high, low_word, fraction)
        } else if gap < 2 {
            Self::close_difference(high, low, gap)
        } else {
            Self::difference_of_magnitudes(high, low_word, fraction)
        }
    }

    /// The sum of two nonzero numbers whose exponents are `gap` ≥ 32 apart,
    /// `high` the larger: the smaller is below 2⁻¹ of an ulp of the larger,
    /// so the sum rounds to the larger, with one exception. With opposite
    /// signs, a gap of 32 and |m_high| = 2³⁰ the difference 2³⁰ − |m_low|/2³²
    /// (in units of 2^e_high) is within half a unit of 2³¹ − 1 at the next
    /// lower exponent unless |m_low| = 2³⁰ (a tie, rounded away from zero,
    /// back to the larger). At a gap above 32 (|m_low| below 2⁻² units) it
    /// rounds back to the larger at any scale.
    #[cold]
    fn sum_far_apart(high: Self, low: Self, gap: u32) -> Self {
        let opposite = (high.mantissa ^ low.mantissa) < 0;
        let high_is_power = high.mantissa.unsigned_abs() == 1 << TOP_BIT;
        let low_is_power = low.mantissa.unsigned_abs() == 1 << TOP_BIT;
        if gap == 32 && opposite && high_is_power && !low_is_power {
            // The exponent is at least 32 above the smaller's: no flush.
            let m = i32::MAX;
            Scaled {
                mantissa: if high.mantissa < 0 {
                    m.wrapping_neg()
                } else {
                    m
                },
                biased_exponent: high.biased_exponent.wrapping_sub(1),
                unit: PhantomData,
            }
        } else {
            high
        }
    }

    /// |m_low|·2^(32 − `gap`) split into the word above 2³² and the word
    /// below (`gap` ≤ 31): the smaller magnitude aligned to the larger's
    /// exponent, with the bits shifted out kept at the top of a word
    /// (shifting twice keeps both shift counts below 32: none for gap 0).
    #[inline(always)]
    fn aligned(low: Self, gap: u32) -> (u32, u32) {
        let magnitude = low.mantissa.unsigned_abs();
        (
            magnitude.wrapping_shr(gap),
            (magnitude << 1).wrapping_shl(31u32.wrapping_sub(gap)),
        )
    }

    /// The sum of two nonzero numbers of the same sign, `high`'s exponent
    /// the larger, correctly rounded on 32-bit words: the exact sum of the
    /// magnitudes is (`word` + `fraction`/2³²)·2^e_high, `word` = |m_high| +
    /// `low_word` < 2³², so its leading bit is bit 30 or 31 of `word` and
    /// the rounding bit the next one down. Only a carry into bit 31 moves
    /// the exponent (up: the one overflow); otherwise it is `high`'s own.
    #[inline(always)]
    fn sum_of_magnitudes(high: Self, low_word: u32, fraction: u32) -> Self {
        let word = high.mantissa.unsigned_abs().wrapping_add(low_word);
        let negative = high.mantissa < 0;
        if word >> 31 != 0 {
            // word/2 rounded half up: the half bit is word's last bit.
            Self::finish(
                negative,
                word.wrapping_add(1) >> 1,
                (high.biased_exponent as i32).wrapping_add(1),
            )
        } else {
            Self::at_valid_exponent(
                negative,
                word.wrapping_add(fraction >> 31),
                high.biased_exponent,
            )
        }
    }

    /// ±(`word` + `next_bit`/2 + less)·2^e for a word in [2³⁰, 2³² − 1) and
    /// `stored` = e − [`EXPONENT_MIN`] as [`Self::finish`] takes it, rounded
    /// to nearest, ties away from zero: a word of 32 bits is halved, its
    /// last bit the rounding bit; otherwise `next_bit` rounds it (to 2³¹ at
    /// most, rarely: [`Self::rounded_to_power`]).
    #[inline(always)]
    fn rounded(negative: bool, word: u32, next_bit: u32, stored: i32) -> Self {
        if word >> 31 != 0 {
            Self::finish(negative, word.wrapping_add(1) >> 1, stored.wrapping_add(1))
        } else {
            let m = word.wrapping_add(next_bit);
            if m >> 31 != 0 {
                return Self::rounded_to_power(negative, stored);
            }
            Self::finish(negative, m, stored)
        }
    }

    /// ±2³¹·2^e, `stored` = e − [`EXPONENT_MIN`] as [`Self::finish`] takes
    /// it: a mantissa rounded up to the next power of two (rare; apart, so
    /// that the common paths test for it with one branch).
    #[cold]
    #[inline(never)]
    fn rounded_to_power(negative: bool, stored: i32) -> Self {
        Self::finish(negative, 1 << 31, stored)
    }

    /// ±`magnitude`·2^e for a magnitude in [2³⁰, 2³¹] and e a valid
    /// value's exponent (`stored` = e − [`EXPONENT_MIN`] in 0..=300), as
    /// [`Self::finish`] gives it with fewer tests: only the magnitude 2³¹
    /// (rare) can leave the range.
    #[inline(always)]
    fn at_valid_exponent(negative: bool, magnitude: u32, stored: u32) -> Self {
        if magnitude >> 31 != 0 {
            return Self::rounded_to_power(negative, stored as i32);
        }
        // m < 2³¹: the cast is exact and the negation cannot wrap.
        let m = magnitude as i32;
        Scaled {
            mantissa: if negative { m.wrapping_neg() } else { m },
            biased_exponent: stored,
            unit: PhantomData,
        }
    }

    /// The sum of two nonzero numbers of opposite signs whose exponents are
    /// `gap` ≤ 1 apart: exact, and normalised exactly unless it has 32 bits
    /// at the smaller exponent (then rounded by one bit). At gap 0 it is
    /// the difference of the mantissas (of either sign, below 2³⁰ in
    /// magnitude; zero when they cancel); at gap 1, 2·|m_high| − |m_low|
    /// at the smaller exponent, positive and below 3·2³⁰.
    #[inline(always)]
    fn close_difference(high: Self, low: Self, gap: u32) -> Self {
        let stored = (high.biased_exponent as i32).wrapping_sub(gap as i32);
        let (negative, magnitude) = if gap == 0 {
            // Opposite signs: no wrap.
            let difference = high.mantissa.wrapping_add(low.mantissa);
            if difference == 0 {
                return Self::ZERO_VALUE;
            }
            (difference < 0, difference.unsigned_abs())
        } else {
            let magnitude =
                (high.mantissa.unsigned_abs() << 1).wrapping_sub(low.mantissa.unsigned_abs());
            if magnitude >> 31 != 0 {
                return Self::finish(
                    high.mantissa < 0,
                    magnitude.wrapping_add(1) >> 1,
                    stored.wrapping_add(1),
                );
            }
            (high.mantissa < 0, magnitude)
        };
        // A nonzero magnitude below 2³¹: 0..=30 places to the leading bit.
        let shift = magnitude.leading_zeros().wrapping_sub(1);
        Self::finish(
            negative,
            magnitude << shift,
            stored.wrapping_sub(shift as i32),
        )
    }

    /// The sum of two nonzero numbers of opposite signs, `high`'s exponent
    /// 2..=31 above the smaller's, correctly rounded: the exact difference
    /// of the magnitudes is (`word` + `fraction`/2³²)·2^e_high. The smaller
    /// is below 2²⁹ units, so `word`'s leading bit is bit 29 or 30 and the
    /// rounding takes one or two bits of `fraction`.
    #[inline(always)]
    fn difference_of_magnitudes(high: Self, low_word: u32, low_fraction: u32) -> Self {
        let negative = high.mantissa < 0;
        // (|m_high|·2³² − (low_word·2³² + low_fraction)), borrowing from the word.
        let difference = (u64::from(high.mantissa.unsigned_abs()) << 32)
            .wrapping_sub((u64::from(low_word) << 32) | u64::from(low_fraction));
        let word = (difference >> 32) as u32;
        let fraction = difference as u32;
        if word >> 30 != 0 {
            Self::at_valid_exponent(
                negative,
                word.wrapping_add(fraction >> 31),
                high.biased_exponent,
            )
        } else {
            // One bit up from the fraction, the next one rounds.
            let m = (difference >> 31) as u32;
            Self::finish(
                negative,
                m.wrapping_add((fraction >> 30) & 1),
                (high.biased_exponent as i32).wrapping_sub(1),
            )
        }
    }

    /// |self| (the invalid value stays invalid).
    fn magnitude(self) -> Self {
        if self.mantissa < 0 && !self.is_invalid() {
            self.negated()
        } else {
            self
        }
    }

    /// −self; the invalid value's mantissa `i32::MIN` is its own wrapping
    /// negation, so it stays invalid.
    fn negated(self) -> Self {
        Scaled {
            mantissa: self.mantissa.wrapping_neg(),
            ..self
        }
    }

    /// Correctly rounded: the floor of the root of the mantissa (made
    /// even-exponent and normalised to [2⁶², 2⁶⁴)) has 32 bits, and its
    /// last bit is the rounding bit.
    fn root(self) -> Self {
        if self.is_invalid() || self.mantissa < 0 {
            return Self::INVALID;
        }
        if self.is_zero() {
            return self;
        }
        let m = u64::from(self.mantissa.unsigned_abs());
        let (n, exponent) = if self.exponent() & 1 == 0 {
            (m << 32, self.exponent().wrapping_sub(32))
        } else {
            (m << 33, self.exponent().wrapping_sub(33))
        };
        let r = isqrt_floor_normalized(n);
        // √(n·2^e) = r·2^(e/2) with e even; r/2 rounded, one bit up.
        Self::finish(
            false,
            (r >> 1).wrapping_add(r & 1),
            stored((exponent >> 1).wrapping_add(1)),
        )
    }

    /// √(a² + b²) from the exact squares of the mantissas (the smaller one
    /// aligned, truncated below 2⁻⁶¹ of the sum) and one correctly rounded
    /// square root: within half an ulp plus 2⁻⁶⁰ relative, and never
    /// overflowing on the way (the exponents are added, not the squares
    /// formed in the format).
    fn hypot_of(self, other: Self) -> Self {
        if self.is_invalid() || other.is_invalid() {
            return Self::INVALID;
        }
        if self.is_zero() {
            return other.magnitude();
        }
        if other.is_zero() {
            return self.magnitude();
        }
        let (high, low) = if self.biased_exponent >= other.biased_exponent {
            (self, other)
        } else {
            (other, self)
        };
        let square = |m: i32| wide_mul_unsigned(m.unsigned_abs(), m.unsigned_abs());
        let gap = high.exponent().wrapping_sub(low.exponent()) as u32; // ≥ 0
        let low_square = if gap < 32 {
            square(low.mantissa) >> (gap << 1)
        } else {
            0
        };
        // Below 2⁶² + 2⁶² = 2⁶³, and at least 2⁶⁰.
        Self::root_of_squares(
            square(high.mantissa).wrapping_add(low_square),
            high.exponent(),
        )
    }

    /// √(a² + b² + c²) as [`Self::hypot_of`]: the squares of the mantissas
    /// aligned to the largest exponent (each truncated below 2⁻⁶² of the
    /// largest square), one correctly rounded square root: within half an
    /// ulp plus 2⁻⁵⁹ relative.
    fn hypot3_of(self, b: Self, c: Self) -> Self {
        if self.is_invalid() || b.is_invalid() || c.is_invalid() {
            return Self::INVALID;
        }
        // Zero carries the smallest exponent: the largest is a nonzero
        // one's unless all three are zero.
        let top = self.exponent().max(b.exponent()).max(c.exponent());
        let square_at_top = |v: Self| {
            let gap = top.wrapping_sub(v.exponent()) as u32; // ≥ 0
            let magnitude = v.mantissa.unsigned_abs();
            if gap < 32 {
                wide_mul_unsigned(magnitude, magnitude) >> (gap << 1)
            } else {
                0
            }
        };
        // Each below 2⁶²: the sum is below 3·2⁶² < 2⁶⁴.
        let sum = square_at_top(self)
            .wrapping_add(square_at_top(b))
            .wrapping_add(square_at_top(c));
        if sum == 0 {
            return Self::ZERO_VALUE;
        }
        Self::root_of_squares(sum, top)
    }

    /// √(`sum`)·2^`exponent` for a sum of squared mantissas in [2⁶⁰, 2⁶⁴)
    /// (at scale 2^(2·`exponent`)), correctly rounded: normalised to
    /// [2⁶², 2⁶⁴) by an even shift, its floor root has 32 bits and its last
    /// bit is the rounding bit.
    fn root_of_squares(sum: u64, exponent: i32) -> Self {
        let (n, exponent) = if sum >> 62 == 0 {
            (sum << 2, exponent.wrapping_sub(1))
        } else {
            (sum, exponent)
        };
        let r = isqrt_floor_normalized(n);
        // √n·2^exponent with √n = r + f, f < 1: r/2 rounded, one bit up.
        Self::finish(
            false,
            (r >> 1).wrapping_add(r & 1),
            stored(exponent.wrapping_add(1)),
        )
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
            defmt::write!(f, "{=i32}p{=i16}", self.mantissa, self.exponent() as i16)
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

    // The comparisons from the keys directly (the same results as through
    // `partial_cmp`, without forming an `Ordering`).
    #[inline]
    fn lt(&self, other: &Self) -> bool {
        self.ordered_with(*other) && self.order_key() < other.order_key()
    }

    #[inline]
    fn le(&self, other: &Self) -> bool {
        self.ordered_with(*other) && self.order_key() <= other.order_key()
    }

    #[inline]
    fn gt(&self, other: &Self) -> bool {
        self.ordered_with(*other) && self.order_key() > other.order_key()
    }

    #[inline]
    fn ge(&self, other: &Self) -> bool {
        self.ordered_with(*other) && self.order_key() >= other.order_key()
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
    Scaled<U>: super::numeric::sealed::MaybeFormat,
{
    const ZERO: Self = Self::ZERO_VALUE;
    /// The fast fixed point's: these are its wide quantities.
    type Guard = super::fixed32::Fixed32Guard;
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
        // From the IEEE 754 fields, in integer code (soft-float calls on
        // the M0/M3 would cost hundreds of instructions, `is_finite` among
        // them): a normal v is ±(2⁵² + fraction)·2^(biased exponent −
        // 1075), exact in an i64, rounded once by `from_wide`. The largest
        // biased exponent is NaN or ±∞. Zero and subnormals (below 2⁻¹⁰²²,
        // far below the flush to zero) give zero.
        let bits = v.to_bits();
        let biased = ((bits >> 52) & 0x7FF) as i32;
        if biased == 0x7FF {
            return Self::INVALID;
        }
        if biased == 0 {
            return Self::ZERO_VALUE;
        }
        let significand = ((bits & ((1u64 << 52) - 1)) | (1u64 << 52)) as i64;
        let wide = if bits >> 63 != 0 {
            significand.wrapping_neg()
        } else {
            significand
        };
        Self::from_wide(wide, biased.wrapping_sub(1075))
    }

    /// `ms`/1000 correctly rounded by the format's division (the same value as
    /// the default's through `f64`: ms/1000 is never within 2⁻⁵³ of a
    /// rounding tie of a 31-bit mantissa unless it is one).
    fn seconds_from_ms(ms: u32) -> Self {
        Self::from_int(i64::from(ms)).divide(Self::from_int(1000))
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

    /// Flags the invalid value.
    #[inline(always)]
    fn check_input(self, guard: &mut Self::Guard) {
        guard.reject_if(self.is_invalid());
    }

    /// Flags the invalid value.
    #[inline(always)]
    fn check_output(self, guard: &mut Self::Guard) {
        guard.reject_if(self.is_invalid());
    }

    /// The rounded difference; flags an invalid result.
    #[inline(always)]
    fn sub_guarded(self, b: Self, guard: &mut Self::Guard) -> Self {
        let difference = self - b;
        guard.reject_if(difference.is_invalid());
        difference
    }

    #[inline]
    fn half(self) -> Self {
        if is_special(self.mantissa) {
            return self;
        }
        // Exact: the same mantissa one exponent down (flushed to zero
        // below the range, as every result).
        if self.biased_exponent == 0 {
            return Self::ZERO_VALUE;
        }
        Scaled {
            mantissa: self.mantissa,
            biased_exponent: self.biased_exponent.wrapping_sub(1),
            unit: PhantomData,
        }
    }
}

impl Real for Scaled<One> {
    const ONE: Self = Scaled {
        mantissa: 1 << TOP_BIT,
        biased_exponent: biased(-(TOP_BIT as i32)),
        unit: PhantomData,
    };
    const TWO: Self = Scaled {
        mantissa: 1 << TOP_BIT,
        biased_exponent: biased(1 - TOP_BIT as i32),
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

    /// From the squares of the mantissas ([`Scaled`]'s own exponent range
    /// holds them): within half an ulp, one square root.
    fn hypot(self, other: Self) -> Self {
        self.hypot_of(other)
    }

    /// The same with three squares: within half an ulp plus 2⁻⁵⁹ relative.
    fn hypot3(self, b: Self, c: Self) -> Self {
        self.hypot3_of(b, c)
    }
}
