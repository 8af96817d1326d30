//! `FixedVariance` (the fast fixed point's covariance number, I16F16 in a
//! word): sums, differences and products against the exact values, on any
//! words, the sentinels and the words next to them included.

use abtrack::num::Quantity;
use abtrack::track::FixedVariance;
use proptest::prelude::*;

/// The number whose word is `bits` (exact: |bits| < 2⁵³ steps).
fn from_bits(bits: i32) -> FixedVariance {
    FixedVariance::from_f64_lossy(f64::from(bits) / 65_536.0)
}

fn is_sentinel(bits: i32) -> bool {
    bits == i32::MAX || bits == i32::MIN
}

/// What the documented rule gives for an exact result `wide` (in steps of
/// 2⁻¹⁶): the word, or the sentinel of its sign at or beyond them, and a
/// sentinel of the result's sign when an operand is one.
fn expected(wide: i128, sentinel_operand: bool) -> i32 {
    if sentinel_operand || wide >= i128::from(i32::MAX) || wide <= i128::from(i32::MIN) {
        if wide < 0 {
            i32::MIN
        } else {
            i32::MAX
        }
    } else {
        wide as i32
    }
}

/// Any word, with the sentinels and their neighbours often.
fn word() -> impl Strategy<Value = i32> {
    prop_oneof![
        any::<i32>(),
        Just(i32::MAX),
        Just(i32::MIN),
        Just(i32::MAX - 1),
        Just(i32::MIN + 1),
        Just(0),
        Just(1),
        Just(-1),
        Just(65_536),
        -70_000i32..70_000,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 5000, ..ProptestConfig::default() })]

    /// The exact result, saturated at the sentinels; with a sentinel
    /// operand, the sentinel of the exact result's sign.
    #[test]
    fn sums_differences_and_products_against_the_exact_values(a in word(), b in word()) {
        let (x, y) = (from_bits(a), from_bits(b));
        prop_assert_eq!(x.to_bits(), a);
        let sentinel = is_sentinel(a) || is_sentinel(b);
        let (wa, wb) = (i128::from(a), i128::from(b));
        prop_assert_eq!((x + y).to_bits(), expected(wa + wb, sentinel));
        // The exact difference, also of the lowest valid word with itself
        // (whose negation alone is a sentinel); with a sentinel operand the
        // sum with −y, whose sentinels swap (MIN − MIN is MIN + MAX: MIN).
        let difference = if sentinel {
            let negated = match b {
                i32::MAX => i32::MIN,
                i32::MIN => i32::MAX,
                v => -v,
            };
            wa + i128::from(negated)
        } else {
            wa - wb
        };
        prop_assert_eq!((x - y).to_bits(), expected(difference, sentinel));
        // Products rounded half up to 16 fractional bits.
        let product = (wa * wb + (1 << 15)) >> 16;
        prop_assert_eq!((x * y).to_bits(), expected(product, sentinel));
        prop_assert_eq!(x.is_valid(), !is_sentinel(a));
    }
}

/// The words next to the sentinels: the last valid result on each side,
/// the first that saturates, and the differences with the lowest valid
/// word (whose negation is a sentinel) as the subtrahend.
#[test]
fn results_at_the_saturation_boundaries() {
    let (max, min) = (i32::MAX, i32::MIN);
    for (result, expected_bits) in [
        (from_bits(max - 1) + from_bits(0), max - 1),
        (from_bits(max - 1) + from_bits(1), max),
        (from_bits(min + 1) - from_bits(0), min + 1),
        (from_bits(min + 1) - from_bits(1), min),
        (from_bits(-1) - from_bits(min + 1), max - 1),
        (from_bits(0) - from_bits(min + 1), max),
        (from_bits(min + 1) - from_bits(min + 1), 0),
        (from_bits(max - 1) - from_bits(max - 1), 0),
    ] {
        assert_eq!(result.to_bits(), expected_bits);
    }
}
