//! `ScaledScalar`, the fast fixed point's wide format as a `Scalar`: its
//! trigonometry and hypot against f64 within the documented bounds, and
//! its invalid value sticky through every operation.

use abtrack::num::fixed32::{Length, Speed};
use abtrack::num::numeric::ScalarGuard;
use abtrack::num::scaled_scalar::{ATAN2_MAX_ERROR, SIN_COS_MAX_ERROR};
use abtrack::num::{Numeric, Quantity, Real};
use abtrack::{Scalar, ScaledScalar as S};
use proptest::prelude::*;

fn s(v: f64) -> S {
    <S as abtrack::Quantity>::try_from_f64(v).unwrap()
}

/// One unit of the last place of a 31-bit mantissa, relative.
const ULP: f64 = 1.0 / (1u64 << 30) as f64;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn sin_cos_within_its_bound(theta in -std::f64::consts::TAU..std::f64::consts::TAU) {
        let t = s(theta);
        let (sin, cos) = S::sin_cos(t);
        let exact = t.to_f64();
        prop_assert!((sin.to_f64() - exact.sin()).abs() <= SIN_COS_MAX_ERROR, "{theta}");
        prop_assert!((cos.to_f64() - exact.cos()).abs() <= SIN_COS_MAX_ERROR, "{theta}");
    }

    /// Any magnitudes from 10⁻⁶ to 10⁶, and any ratio between them.
    #[test]
    fn atan2_within_its_bound(
        y in -1.0e6f64..1.0e6,
        x in -1.0e6f64..1.0e6,
        ye in -20i32..20,
        xe in -20i32..20,
    ) {
        let (y, x) = (s(y * 2f64.powi(ye)), s(x * 2f64.powi(xe)));
        let a = y.atan2(x).to_f64();
        let exact = y.to_f64().atan2(x.to_f64());
        prop_assert!((a - exact).abs() <= ATAN2_MAX_ERROR, "{y:?} {x:?}: {a} vs {exact}");
    }

    /// Conversion from f64 (integer code on the IEEE fields): rounded to
    /// nearest, within half a unit of the 31-bit mantissa.
    #[test]
    fn conversion_rounds_to_nearest(v in 0.5f64..1.0, negative: bool, e in -150i32..125) {
        let v = if negative { -v } else { v } * 2f64.powi(e);
        let got = s(v).to_f64();
        prop_assert!((got - v).abs() <= ULP / 2.0 * v.abs(), "{v}: {got}");
    }

    /// One root of the squared mantissas: within half an ulp plus the
    /// rounding of the squares (`Scaled`'s docs), so within one ulp.
    #[test]
    fn hypot_within_one_unit(a in -1.0e27f64..1.0e27, b in -1.0e27f64..1.0e27, e in -60i32..40) {
        let (a, b) = (s(a), s(b * 2f64.powi(e)));
        let h = abtrack::num::hypot(a, b).to_f64();
        let exact = a.to_f64().hypot(b.to_f64());
        prop_assert!((h - exact).abs() <= ULP * exact, "{a:?} {b:?}: {h} vs {exact}");
    }
}

#[test]
fn the_invalid_value_is_sticky() {
    let invalid = s(1.0) / S::ZERO;
    assert!(!invalid.is_valid());
    assert!(!(-s(4.0)).sqrt().is_valid());
    for v in [
        invalid + S::ONE,
        S::ONE - invalid,
        invalid * S::ZERO,
        S::ZERO / invalid,
        -invalid,
        invalid.abs(),
        invalid.sqrt(),
        invalid.atan2(S::ONE),
        S::sin_cos(invalid).0,
        abtrack::num::hypot(S::ONE, invalid),
    ] {
        assert!(!v.is_valid(), "{v:?}");
    }
    // It compares unordered with every value, as NaN (it is equal to
    // itself, unlike NaN: `==` compares the stored words).
    assert!(invalid.partial_cmp(&S::ONE).is_none());
    assert!(invalid.partial_cmp(&invalid).is_none());
    // The operators themselves, as a NaN gives them.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    let neither = !(invalid < S::ONE) && !(invalid >= S::ONE);
    assert!(neither);
    // Beyond 2¹³¹: invalid, and refused at the edge.
    assert!(!(s(2.0e39) * s(2.0)).is_valid());
    assert!(<S as abtrack::Quantity>::try_from_f64(1.0e40).is_err());
    assert!(<S as abtrack::Quantity>::try_from_f64(f64::NAN).is_err());
}

/// The hot path's guard (src/num/numeric.rs): passes exactly when every
/// output is valid.
#[test]
fn the_guard_passes_exactly_the_valid_outputs() {
    let mut guard = ScalarGuard::<S>::default();
    for v in [s(1.0e30), s(-1.0e30), s(3.5), S::ZERO] {
        v.check_output(&mut guard);
    }
    assert!(guard.passed());
    (s(1.0) / S::ZERO).check_output(&mut guard);
    assert!(!guard.passed());
}

#[test]
fn fixed_point_words_convert_exactly() {
    let l = <Length as abtrack::Quantity>::try_from_f64(-12_345.678).unwrap();
    assert_eq!(S::from_length(l).to_f64(), abtrack::Quantity::to_f64(l));
    let v = <Speed as abtrack::Quantity>::try_from_f64(271.828).unwrap();
    assert_eq!(S::from_speed(v).to_f64(), abtrack::Quantity::to_f64(v));
    assert!(!S::from_length(Length::MAX).is_valid());
    assert!(!S::from_speed(Speed::MIN).is_valid());
}
