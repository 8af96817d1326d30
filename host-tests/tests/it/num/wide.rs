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

/// The Cortex-M0's square root (by products alone) is the exact floor of
/// √n over its whole domain [2⁶², 2⁶⁴): at the domain's ends, at every
/// seed bucket's ends, at squares and beside them, and on random words.
#[test]
fn the_square_root_by_products_is_the_exact_floor() {
    use abtrack::num::scaled::isqrt_floor_by_products;
    let check = |n: u64| {
        assert_eq!(u64::from(isqrt_floor_by_products(n)), n.isqrt(), "⌊√{n}⌋");
    };
    let mut cases = vec![1u64 << 62, u64::MAX, (1u64 << 62) + 1, u64::MAX - 1];
    // Each seed bucket (the high word's top 8 bits, 64..=255) at its ends.
    for top in 64u64..=255 {
        let start = top << 56;
        cases.extend([
            start,
            start + 1,
            start.wrapping_sub(1),
            start | ((1 << 56) - 1),
        ]);
    }
    // Squares, one below and the last value before the next square.
    for k in [
        1u64 << 31,
        (1 << 31) + 1,
        0xB504_F333,
        0xFFFF_FFFE,
        0xFFFF_FFFF,
    ] {
        let square = k * k;
        cases.extend([square, square - 1, square.saturating_add(2 * k)]);
    }
    for n in cases.into_iter().filter(|&n| n >= 1 << 62) {
        check(n);
    }
    // Random words, and squares of random roots with small offsets
    // (a fixed generator: the same cases on every run).
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..1_000_000 {
        check(next() | (1 << 62));
        let root = (next() >> 32) | (1 << 31);
        let square = root * root;
        let offset = next() % (2 * root + 1);
        check(square + offset);
        if let Some(below) = square
            .checked_sub((offset & 0xFF) + 1)
            .filter(|&n| n >= 1 << 62)
        {
            check(below);
        }
    }
}
