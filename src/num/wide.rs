//! Exact 64-bit products and quotients on 32-bit words, the one multiply
//! and divide of the fast fixed point's formats ([`super::fixed32`],
//! [`super::scaled`]), its sine ([`super::sine`]) and the track table's
//! fixed-point gate and variances.
//!
//! The Cortex-M0 (ARMv6-M; recognised on stable Rust by its lack of 32-bit
//! atomics) has neither a 32×32→64 multiply nor a divide: LLVM would call
//! the general 64×64 `__aeabi_lmul` for a product of two widened words, and
//! a software 32-bit division for each digit of a quotient. There the
//! products are four 16×16 partial products inline ([`wide_mul_by_halves`]
//! and the like, about half the library call) and the quotient is formed
//! from a reciprocal by multiplications alone ([`div_wide_by_reciprocal`]).
//! Elsewhere a product is one instruction and a quotient two `udiv`
//! ([`div_wide_by_digits`]).
//! Each form is public so that the host tests compare it with exact
//! arithmetic (`host-tests/tests/it/num/wide.rs`).

use core::num::NonZeroU32;

/// Whether this target lacks a 32×32→64 multiply and a divide (ARMv6-M).
pub(crate) const ARMV6M: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// The exact product of two signed words.
#[inline(always)]
pub fn wide_mul(a: i32, b: i32) -> i64 {
    if ARMV6M {
        wide_mul_by_halves(a, b)
    } else {
        // |a·b| ≤ 2⁶²: exact.
        i64::from(a).wrapping_mul(i64::from(b))
    }
}

/// The exact product of two unsigned words.
#[inline(always)]
pub fn wide_mul_unsigned(a: u32, b: u32) -> u64 {
    if ARMV6M {
        wide_mul_unsigned_by_halves(a, b)
    } else {
        // Below 2⁶⁴: exact.
        u64::from(a).wrapping_mul(u64::from(b))
    }
}

/// The exact product of a signed and an unsigned word.
#[inline(always)]
pub fn wide_mul_signed_unsigned(a: i32, b: u32) -> i64 {
    if ARMV6M {
        wide_mul_signed_unsigned_by_halves(a, b)
    } else {
        // |a·b| < 2⁶³: exact.
        i64::from(a).wrapping_mul(i64::from(b))
    }
}

/// ⌊(u1·2³² + u0)/v⌋ and the remainder, for v ≥ 2³¹ and u1 < v (the
/// quotient then fits a word), without a 64-bit division routine. Outside
/// its preconditions the result is meaningless, but nothing panics.
#[inline]
pub fn div_wide(u1: u32, u0: u32, v: u32) -> (u32, u32) {
    if ARMV6M {
        div_wide_by_reciprocal(u1, u0, v)
    } else {
        div_wide_by_digits(u1, u0, v)
    }
}

/// [`div_wide`] by Knuth's algorithm D with 16-bit digits (Warren,
/// *Hacker's Delight*, 2nd ed., §9-4, `divlu`): two 32-bit divisions (the
/// Cortex-M3's `udiv`) and at most four corrections.
pub fn div_wide_by_digits(u1: u32, u0: u32, v: u32) -> (u32, u32) {
    let digit = |high: u32, low: u32| quotient_digit(high, low, v);
    let (u0_high, u0_low) = (u0 >> 16, u0 & 0xFFFF);
    let q1 = digit(u1, u0_high);
    // The partial remainder u1·2¹⁶ + u0_high − q1·v < v (modulo 2³²).
    let partial = ((u1 << 16) | u0_high).wrapping_sub(q1.wrapping_mul(v));
    let q0 = digit(partial, u0_low);
    let remainder = ((partial << 16) | u0_low).wrapping_sub(q0.wrapping_mul(v));
    ((q1 << 16) | q0, remainder)
}

/// One quotient digit ⌊(high·2¹⁶ + low)/v⌋ of Knuth's algorithm D with
/// 16-bit digits, for v ≥ 2³¹, high < v and low < 2¹⁶: estimated from v's
/// high digit, then corrected (at most twice, Knuth's step D3).
#[inline(always)]
fn quotient_digit(high: u32, low: u32, v: u32) -> u32 {
    const DIGIT: u32 = 1 << 16;
    // v ≥ 2³¹, so its high digit is at least 2¹⁵.
    let v_high = NonZeroU32::new(v >> 16).unwrap_or(NonZeroU32::MIN);
    let v_low = v & 0xFFFF;
    let mut q = high / v_high;
    let mut rest = high.wrapping_sub(q.wrapping_mul(v_high.get()));
    for _ in 0..2 {
        // rest < 2¹⁶ here, so rest·2¹⁶ + low fits a word.
        if q >= DIGIT || q.wrapping_mul(v_low) > ((rest << 16) | low) {
            q = q.wrapping_sub(1);
            rest = rest.wrapping_add(v_high.get());
            if rest < DIGIT {
                continue;
            }
        }
        break;
    }
    q
}

/// [`div_wide`]'s quotient when it is below 2¹⁶: for v ≥ 2³¹ and
/// u1·2¹⁶ + ⌊u0/2¹⁶⌋ < v. Knuth's first quotient digit is then 0, so the
/// Cortex-M3 runs only the second digit's step (`quotient_digit`); the
/// Cortex-M0 divides as [`div_wide`].
#[inline]
pub fn div_wide_short(u1: u32, u0: u32, v: u32) -> u32 {
    if ARMV6M {
        div_wide_by_reciprocal(u1, u0, v).0
    } else {
        quotient_digit((u1 << 16) | (u0 >> 16), u0 & 0xFFFF, v)
    }
}

/// ⌊2²⁴/(257 + i)⌋ for i = 0..256: a first reciprocal of a word v ≥ 2³¹
/// from its 8 bits below the leading one, i (1/a for a = v/2³² in
/// [½ + i/512, ½ + (i + 1)/512), from below, in units of 2⁻¹⁵; within
/// 2⁻⁸ relative).
const RECIPROCAL_SEED: [u16; 256] = reciprocal_seed();

// Evaluated at compile time only: an index out of range or an overflow
// would fail the build, not the firmware.
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
const fn reciprocal_seed() -> [u16; 256] {
    let mut table = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        table[i] = ((1u32 << 24) / (257 + i as u32)) as u16;
        i += 1;
    }
    table
}

/// ⌊2⁶⁴/v⌋ − 2³² for v ≥ 2³¹ (at most `u32::MAX`), from below and within
/// 16: [`RECIPROCAL_SEED`] and two Newton steps z ← z + z·(1 − a·z) for
/// 1/a, a = v/2³² (the first on v's top 16 bits in 32-bit words, the
/// second on v in wide products). A Newton step from any z gives
/// (1 − ε²)/a ≤ 1/a, and every rounding here is down, so the result never
/// exceeds the reciprocal.
#[inline(always)]
fn reciprocal(v: u32) -> u32 {
    let first = reciprocal_estimate(v);
    // e = 1 − a·z1 in units of 2⁻⁶³, |e| < 2⁴⁹ (z1 is within 2⁻¹⁵ of 1/a,
    // from either side: 1/a′ ≥ 1/a).
    let error = (1u64 << 63).wrapping_sub(wide_mul_unsigned(v, first)) as i64;
    // z2 = z1 + z1·e in units of 2⁻³², the correction rounded down.
    let step = (error >> 30) as i32; // |step| < 2¹⁹
    let correction = wide_mul_unsigned(first, step.unsigned_abs());
    let correction = if step < 0 {
        (correction.wrapping_add(u64::from(u32::MAX)) >> 32).wrapping_neg()
    } else {
        correction >> 32
    };
    // 2·z1 + correction − 2³²: the reciprocal less 2³², in [0, 2³²) (0
    // when v is so close to 2³² that the estimate falls below 2³²).
    (u64::from(first) << 1)
        .wrapping_add(correction)
        .saturating_sub(1 << 32)
        .min(u64::from(u32::MAX)) as u32
}

/// The first Newton step of [`reciprocal`]: 1/a for a = v/2³² (v ≥ 2³¹)
/// in units of 2⁻³¹, about 2⁶³/v, within 2⁻¹⁵ of it relative, on 32-bit
/// words ([`RECIPROCAL_SEED`] and one step on v's top 16 bits).
#[inline(always)]
pub(crate) fn reciprocal_estimate(v: u32) -> u32 {
    let seed = u32::from(
        RECIPROCAL_SEED
            .get(((v >> 23) & 0xFF) as usize)
            .copied()
            .unwrap_or(0),
    );
    // a′·z0 in units of 2⁻³¹, a′ = (v >> 16)/2¹⁶ ≤ a: at most 2³¹ (the seed
    // is below 1/a′), at least 2³¹(1 − 2⁻⁷); e = 1 − a′·z0 below 2²⁴.
    let product = (v >> 16).wrapping_mul(seed);
    let error = (1u32 << 31).wrapping_sub(product);
    // z1 = z0·(1 + e) in units of 2⁻³¹ (below 2³²: z1 ≤ 1/a′ ≤ 2).
    (seed << 16).wrapping_add(seed.wrapping_mul(error >> 8) >> 7)
}

/// [`div_wide`] by multiplications alone (the Cortex-M0 has no divide; in
/// the manner of Möller & Granlund, "Improved division by invariant
/// integers", IEEE Trans. Computers 60(2), 2011): the quotient estimated
/// from below, u1 + ⌊u1·m/2³²⌋ with m within 16 below ⌊2⁶⁴/v⌋ − 2³², and
/// the remainder's excess taken off by whole divisors (fewer than 20
/// steps).
pub fn div_wide_by_reciprocal(u1: u32, u0: u32, v: u32) -> (u32, u32) {
    let m = reciprocal(v);
    let mut q = u1.wrapping_add((wide_mul_unsigned(u1, m) >> 32) as u32);
    let dividend = (u64::from(u1) << 32) | u64::from(u0);
    let mut remainder = dividend.wrapping_sub(wide_mul_unsigned(q, v));
    let divisor = u64::from(v);
    // Fewer than u1·17/2³² + u0/v + 1 < 20 steps under the preconditions;
    // bounded anyway, so that nothing outside them loops long.
    for _ in 0..32 {
        if remainder < divisor {
            break;
        }
        remainder = remainder.wrapping_sub(divisor);
        q = q.wrapping_add(1);
    }
    (q, remainder as u32)
}

/// [`wide_mul`] from four 16×16 partial products (what the Cortex-M0
/// runs; public so that the host tests compare it with the plain product).
#[inline(always)]
pub fn wide_mul_by_halves(a: i32, b: i32) -> i64 {
    // a = ah·2¹⁶ + al with ah signed (|ah| ≤ 2¹⁵) and 0 ≤ al < 2¹⁶, so
    // every partial product fits its word: |ah·bh| ≤ 2³⁰, |ah·bl| < 2³¹,
    // al·bl < 2³² (unsigned).
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let high = ah.wrapping_mul(bh);
    let middle = i64::from(ah.wrapping_mul(bl)).wrapping_add(i64::from(al.wrapping_mul(bh)));
    let low = (al as u32).wrapping_mul(bl as u32);
    (i64::from(high) << 32)
        .wrapping_add(middle << 16)
        .wrapping_add(i64::from(low))
}

/// [`wide_mul_unsigned`] from four 16×16 partial products (as
/// [`wide_mul_by_halves`]).
#[inline(always)]
pub fn wide_mul_unsigned_by_halves(a: u32, b: u32) -> u64 {
    // Each partial product is below 2³², the middle sum below 2³³.
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let middle = u64::from(ah.wrapping_mul(bl)).wrapping_add(u64::from(al.wrapping_mul(bh)));
    (u64::from(ah.wrapping_mul(bh)) << 32)
        .wrapping_add(middle << 16)
        .wrapping_add(u64::from(al.wrapping_mul(bl)))
}

/// [`wide_mul_signed_unsigned`] from [`wide_mul_unsigned_by_halves`] of
/// the magnitude, then signed (|a|·b < 2⁶³: exact).
#[inline(always)]
pub fn wide_mul_signed_unsigned_by_halves(a: i32, b: u32) -> i64 {
    let magnitude = wide_mul_unsigned_by_halves(a.unsigned_abs(), b) as i64;
    if a < 0 {
        magnitude.wrapping_neg()
    } else {
        magnitude
    }
}
