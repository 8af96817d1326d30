//! The wide products and quotients of `abtrack::num::wide` in both their
//! forms (the Cortex-M0's partial products and reciprocal division, the
//! other cores' digit division) against exact 64-bit arithmetic.

use abtrack::num::wide::{
    div_wide_by_digits, div_wide_by_reciprocal, div_wide_short, wide_mul_by_halves,
    wide_mul_signed_unsigned_by_halves, wide_mul_unsigned_by_halves,
};
use proptest::prelude::*;

/// The words where a carry or a sign is at its limit.
const EDGES: [u32; 12] = [
    0,
    1,
    0x8000,
    0xFFFF,
    0x1_0000,
    0x7FFF_FFFF,
    0x8000_0000,
    0x8000_0001,
    0xFFFF_0000,
    0xFFFF_8000,
    0xFFFF_FFFE,
    0xFFFF_FFFF,
];

#[test]
fn partial_products_are_exact_at_the_edges() {
    for &a in &EDGES {
        for &b in &EDGES {
            assert_eq!(
                wide_mul_unsigned_by_halves(a, b),
                u64::from(a) * u64::from(b),
                "{a:#x} · {b:#x}"
            );
            let (sa, sb) = (a as i32, b as i32);
            assert_eq!(
                wide_mul_by_halves(sa, sb),
                i64::from(sa) * i64::from(sb),
                "{sa} · {sb}"
            );
            assert_eq!(
                wide_mul_signed_unsigned_by_halves(sa, b),
                i64::from(sa) * i64::from(b),
                "{sa} · {b}"
            );
        }
    }
}

/// Both divisions give the exact quotient and remainder of
/// (u1·2³² + u0)/v.
fn assert_divisions(u1: u32, u0: u32, v: u32) {
    let dividend = (u64::from(u1) << 32) | u64::from(u0);
    let exact = (
        (dividend / u64::from(v)) as u32,
        (dividend % u64::from(v)) as u32,
    );
    assert_eq!(
        div_wide_by_reciprocal(u1, u0, v),
        exact,
        "{dividend:#x} / {v:#x}"
    );
    assert_eq!(
        div_wide_by_digits(u1, u0, v),
        exact,
        "{dividend:#x} / {v:#x}"
    );
}

#[test]
fn divisions_are_exact_at_the_edges() {
    // Every seed interval's ends (the 8 bits below v's leading one), with
    // the largest and smallest dividends the preconditions allow.
    for i in 0..256u32 {
        for low in [0, 1, 2, 1 << 22, (1 << 23) - 2, (1 << 23) - 1] {
            let v = (1 << 31) | (i << 23) | low;
            for (u1, u0) in [
                (0, 0),
                (0, u32::MAX),
                (v - 1, u32::MAX),
                (v - 1, 0),
                (v >> 1, 1 << 31),
            ] {
                assert_divisions(u1, u0, v);
            }
        }
    }
    // Divisors next to 2³² and 2³¹, where the reciprocal is at its ends.
    for k in 0..4096u32 {
        for v in [u32::MAX - k, (1 << 31) + k] {
            assert_divisions(v - 1, u32::MAX, v);
            assert_divisions(v >> 1, k, v);
        }
    }
}

/// Marsaglia's xorshift32 from `state` (nonzero): a cheap, seeded stream
/// of words across the whole range.
fn xorshift32(mut state: u32) -> impl FnMut() -> u32 {
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    }
}

#[test]
fn divisions_are_exact_on_many_draws() {
    // 200,000 divisors and dividends across the whole range.
    let mut next = xorshift32(0x9E37_79B9);
    for _ in 0..200_000 {
        let v = next() | (1 << 31);
        let (high, u0) = (next(), next());
        assert_divisions(high % v, u0, v);
    }
}

/// The short division's quotient, for a dividend whose bits above its
/// low 16 (`above`, below v) and low 16 bits (`low`) are given: exact.
fn assert_short_division(above: u32, low: u32, v: u32) {
    let (u1, u0) = (above >> 16, (above << 16) | (low & 0xFFFF));
    let dividend = (u64::from(u1) << 32) | u64::from(u0);
    assert_eq!(
        div_wide_short(u1, u0, v),
        (dividend / u64::from(v)) as u32,
        "{dividend:#x} / {v:#x}"
    );
}

#[test]
fn short_divisions_are_exact() {
    for &low in &EDGES {
        for k in 0..4096u32 {
            for v in [u32::MAX - k, (1 << 31) + k] {
                for above in [0, k, v >> 1, v - 1 - k.min(v - 1), v - 1] {
                    assert_short_division(above, low, v);
                }
            }
        }
    }
    let mut next = xorshift32(0x2545_F491);
    for _ in 0..200_000 {
        let v = next() | (1 << 31);
        let (above, low) = (next(), next());
        assert_short_division(above % v, low, v);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, ..ProptestConfig::default() })]

    #[test]
    fn divisions_are_exact(v in (1u32 << 31)..=u32::MAX, high in any::<u32>(), u0 in any::<u32>()) {
        assert_divisions(high % v, u0, v);
    }

    /// The scaled format's quotients: (2a or a)·2³² over 2b for
    /// normalised mantissas a and b.
    #[test]
    fn mantissa_quotients_are_exact(a in (1u32 << 30)..(1u32 << 31), b in (1u32 << 30)..(1u32 << 31)) {
        let high = if a < b { a << 1 } else { a };
        assert_divisions(high, 0, b << 1);
    }

    #[test]
    fn partial_products_are_exact(a in any::<u32>(), b in any::<u32>()) {
        prop_assert_eq!(wide_mul_unsigned_by_halves(a, b), u64::from(a) * u64::from(b));
        let (sa, sb) = (a as i32, b as i32);
        prop_assert_eq!(wide_mul_by_halves(sa, sb), i64::from(sa) * i64::from(sb));
        prop_assert_eq!(wide_mul_signed_unsigned_by_halves(sa, b), i64::from(sa) * i64::from(b));
    }
}
