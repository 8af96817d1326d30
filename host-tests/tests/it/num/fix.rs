//! `Fix` (Q32.32) arithmetic: saturation instead of wrap-around, sticky invalid
//! values, division by zero, conversions, and no panics on any bit pattern.

use abtrack::num::{Numeric, Quantity, Real};
use abtrack::{Fix, NumError, Scalar};
use proptest::prelude::*;

const TWO_POW_32: f64 = 4_294_967_296.0;

fn fix(v: f64) -> Fix {
    Fix::try_from_f64(v).unwrap()
}

#[test]
fn overflow_saturates_with_the_right_sign() {
    let big = fix(2.0e9);
    assert_eq!(big + big, Fix::MAX);
    assert_eq!(-big - big, Fix::MIN);
    assert_eq!(big * fix(2.0), Fix::MAX);
    assert_eq!(big * fix(-2.0), Fix::MIN);
    assert_eq!(big / fix(0.5), Fix::MAX);
    assert_eq!(-big / fix(0.5), Fix::MIN);
    assert_eq!(-big - fix(2.0e9), Fix::MIN);
    assert_eq!(big - fix(-2.0e9), Fix::MAX);
    // A wrap-around would have produced a valid number of the other sign.
    for v in [big + big, -big - big, big * big] {
        assert!(!v.is_valid());
    }
}

#[test]
fn invalid_values_are_sticky() {
    let one = Fix::ONE;
    for s in [Fix::MAX, Fix::MIN] {
        for r in [
            s + one,
            one + s,
            s - one,
            one - s,
            s * one,
            one * s,
            s * Fix::ZERO,
            s / one,
            one / s,
            -s,
            s.abs(),
            s.sqrt(),
            s.atan2(one),
            Fix::sin_cos(s).0,
            Fix::sin_cos(s).1,
        ] {
            assert!(!r.is_valid(), "{s:?} gave a valid {r:?}");
        }
        // Even an operation that would cancel the saturation stays invalid.
        assert!(!(Fix::MAX + Fix::MIN).is_valid());
        assert!(!(s - s).is_valid());
        assert_eq!(s.to_f64().abs(), f64::INFINITY);
    }
}

#[test]
fn division_by_zero_saturates_with_the_numerator_sign() {
    assert_eq!(fix(3.5) / Fix::ZERO, Fix::MAX);
    assert_eq!(fix(-3.5) / Fix::ZERO, Fix::MIN);
    assert!(!(Fix::ZERO / Fix::ZERO).is_valid());
}

#[test]
fn sqrt_of_negative_is_invalid() {
    assert!(!fix(-1.0).sqrt().is_valid());
    assert_eq!(fix(2.25).sqrt(), fix(1.5));
}

#[test]
fn conversions_check_range_and_round_to_nearest() {
    assert_eq!(Fix::try_from_f64(f64::NAN), Err(NumError::NotFinite));
    assert_eq!(Fix::try_from_f64(f64::INFINITY), Err(NumError::NotFinite));
    assert_eq!(Fix::try_from_f64(3e9), Err(NumError::OutOfRange));
    assert_eq!(Fix::try_from_f64(-3e9), Err(NumError::OutOfRange));
    // ±2³¹ is not representable (2³¹ − 2⁻³² is the largest value, and −2³¹
    // is the negative sentinel).
    assert_eq!(Fix::try_from_f64(2147483648.0), Err(NumError::OutOfRange));
    assert_eq!(Fix::try_from_f64(-2147483648.0), Err(NumError::OutOfRange));
    assert!(Fix::try_from_f64(2147483647.0).is_ok());
    // Round to nearest: 2⁻³³ above a grid point goes either way (ties to even),
    // anything less than half a step rounds to the grid point.
    let step = 1.0 / TWO_POW_32;
    assert_eq!(fix(1.0 + 0.4 * step).to_bits(), 1i64 << 32);
    assert_eq!(fix(1.0 + 0.6 * step).to_bits(), (1i64 << 32) + 1);
    assert_eq!(fix(-1.0 - 0.6 * step).to_bits(), -(1i64 << 32) - 1);
    // Lossy conversion of literals: out of range saturates, NaN is invalid.
    assert_eq!(Fix::from_f64_lossy(1e300), Fix::MAX);
    assert_eq!(Fix::from_f64_lossy(-1e300), Fix::MIN);
    assert!(!Fix::from_f64_lossy(f64::NAN).is_valid());
    assert_eq!(Fix::from_f64_lossy(0.5).to_bits(), 1i64 << 31);
    // Exact values come back exactly.
    for v in [0.0, 1.0, -1.0, 0.5, 400e3, -1500.25, 2147483647.0] {
        assert_eq!(fix(v).to_f64(), v);
    }
    assert_eq!(Fix::DELTA.to_f64(), step);
}

/// The rounding model the error budget uses (`Scalar::UNIT_ROUNDOFF`,
/// `Scalar::ABS_RESOLUTION`): products and quotients are within one step,
/// sums exact.
#[test]
fn rounding_model_constants() {
    assert_eq!(Fix::UNIT_ROUNDOFF, 0.0);
    assert_eq!(Fix::ABS_RESOLUTION, 1.0 / TWO_POW_32);
    assert_eq!(f32::UNIT_ROUNDOFF, 2f64.powi(-24));
    assert_eq!(f64::UNIT_ROUNDOFF, 2f64.powi(-53));
}

fn is_sentinel(bits: i64) -> bool {
    bits == i64::MAX || bits == i64::MIN
}

/// The exact result as a raw Q32.32 word if it is a valid value (in range and
/// not a sentinel), given as i128 arithmetic.
fn valid_word(v: i128) -> Option<i64> {
    if v > i64::MIN as i128 && v < i64::MAX as i128 {
        Some(v as i64)
    } else {
        None
    }
}

fn bits() -> impl Strategy<Value = i64> {
    // Every bit pattern, with the sentinels and small values well represented.
    prop_oneof![
        any::<i64>(),
        Just(i64::MAX),
        Just(i64::MIN),
        Just(i64::MAX - 1),
        Just(i64::MIN + 1),
        Just(0i64),
        -(1i64 << 40)..(1i64 << 40),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// No operation panics; a valid result is the exact result (sums) or the
    /// exact result rounded down / toward zero (products / quotients); an
    /// invalid result happens exactly when an operand is invalid or the
    /// exact result does not fit.
    #[test]
    fn arithmetic_on_any_bits(a in bits(), b in bits()) {
        let (x, y) = (Fix::from_bits(a), Fix::from_bits(b));
        let invalid_operand = is_sentinel(a) || is_sentinel(b);
        let (wa, wb) = (a as i128, b as i128);

        let cases: [(Fix, Option<i128>); 4] = [
            (x + y, Some(wa + wb)),
            (x - y, Some(wa - wb)),
            // Product of two Q32.32 words is Q64.64: shift back, rounding
            // toward −∞ (arithmetic shift).
            (x * y, Some((wa * wb) >> 32)),
            // Quotient: (a·2³²)/b truncated toward zero; none for b = 0.
            (x / y, if b == 0 { None } else { Some((wa << 32) / wb) }),
        ];
        for (k, (r, exact)) in cases.iter().enumerate() {
            let expected = if invalid_operand { None } else { exact.and_then(valid_word) };
            match expected {
                Some(w) => prop_assert_eq!(r.to_bits(), w, "op {} of {} {}", k, a, b),
                None => prop_assert!(!r.is_valid(), "op {} of {} {} gave {:?}", k, a, b, r),
            }
        }
        // Negation and absolute value: exact or invalid.
        let n = -x;
        if is_sentinel(a) { prop_assert!(!n.is_valid()); } else { prop_assert_eq!(n.to_bits(), -a); }
        let m = x.abs();
        if is_sentinel(a) { prop_assert!(!m.is_valid()); } else { prop_assert_eq!(m.to_bits(), a.abs()); }
        // The other Scalar operations must not panic either.
        let _ = (x.sqrt(), Fix::sin_cos(x), x.atan2(y), x.min_of(y), x.max_of(y), x.to_f64());
    }

    /// Conversions: a finite value in range converts to the nearest grid
    /// point (within half a step) and back; out of range or non-finite is an
    /// error, never a wrapped value.
    #[test]
    fn conversion_round_trip(v in prop_oneof![any::<f64>(), -3e9f64..3e9, -1e3f64..1e3]) {
        match Fix::try_from_f64(v) {
            Ok(f) => {
                prop_assert!(f.is_valid());
                prop_assert!((f.to_f64() - v).abs() <= 0.5 / TWO_POW_32 + v.abs() * f64::EPSILON);
            }
            Err(NumError::NotFinite) => prop_assert!(!v.is_finite()),
            Err(NumError::OutOfRange) => prop_assert!(v.abs() >= 2147483647.0),
        }
        // Within a step of ±2³¹ the rounded value may hit a sentinel; no
        // claim is made there.
        let lossy = Fix::from_f64_lossy(v);
        if v.is_finite() && v.abs() < 2147483647.0 {
            prop_assert!(lossy.is_valid());
        } else if !v.is_finite() || v.abs() >= 2147483648.0 {
            prop_assert!(!lossy.is_valid());
        }
    }
}

/// The firmware log's decimal form (`Fix::decimal_millionths`, defmt's
/// `Format`): rounded to the nearest millionth, a fraction that rounds to
/// 1.000000 carried into the integer part, the sign apart.
#[test]
fn decimal_millionths_round_and_carry() {
    let bits = |b: i64| Fix::from_bits(b);
    assert_eq!(fix(3.25).decimal_millionths(), (false, 3, 250_000));
    assert_eq!(fix(-3.25).decimal_millionths(), (true, 3, 250_000));
    // 3 + (2³² − 1)/2³²: the fraction rounds up to 1.000000.
    assert_eq!(bits((4 << 32) - 1).decimal_millionths(), (false, 4, 0));
    assert_eq!(bits(-((4 << 32) - 1)).decimal_millionths(), (true, 4, 0));
    // Half a millionth is 2147.48 steps of 2⁻³²: 2148 rounds up, 2147
    // down.
    assert_eq!(bits((1 << 32) + 2148).decimal_millionths(), (false, 1, 1));
    assert_eq!(bits((1 << 32) + 2147).decimal_millionths(), (false, 1, 0));
    // The largest magnitude carries to 2³¹ without a wrap.
    assert_eq!(bits(i64::MIN + 1).decimal_millionths(), (true, 1 << 31, 0));
}
