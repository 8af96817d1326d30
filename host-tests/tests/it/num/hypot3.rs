//! `Real::hypot3` of the `Scalar` types (one square root) against
//! f64's √(a² + b² + c²): within a few
//! roundings for the floats and Q32.32, within ScaledScalar's documented
//! half ulp; invalid arguments give an invalid result.

use abtrack::num::Real;
use abtrack::{Fix, Scalar, ScaledScalar};
use proptest::prelude::*;

/// √(a² + b² + c²) in f64 with the squares scaled by the largest.
fn exact(a: f64, b: f64, c: f64) -> f64 {
    let large = a.abs().max(b.abs()).max(c.abs());
    if large == 0.0 {
        return 0.0;
    }
    let (a, b, c) = (a / large, b / large, c / large);
    large * (a * a + b * b + c * c).sqrt()
}

/// |hypot3 − exact| ≤ relative·exact + absolute, in `S`.
fn check<S: Scalar + Real>(a: f64, b: f64, c: f64, relative: f64, absolute: f64) {
    let f = |v: S| abtrack::Quantity::to_f64(v);
    let zero = <S as abtrack::Quantity>::ZERO;
    let [sa, sb, sc] = [a, b, c].map(<S as abtrack::Quantity>::from_f64_lossy);
    let want = exact(f(sa), f(sb), f(sc));
    let got = f(Real::hypot3(sa, sb, sc));
    assert!(
        (got - want).abs() <= relative * want + absolute,
        "{}: hypot3({a}, {b}, {c}) = {got}, exact {want}",
        <S as abtrack::Numeric>::NAME
    );
    // The order of the arguments does not matter beyond rounding, and a
    // zero third argument gives hypot.
    let swapped = f(Real::hypot3(sc, sa, sb));
    assert!((swapped - want).abs() <= relative * want + absolute);
    let pair = f(Real::hypot3(sa, sb, zero));
    let want_pair = exact(f(sa), f(sb), 0.0);
    assert!((pair - want_pair).abs() <= relative * want_pair + absolute);
}

proptest! {
    #[test]
    fn hypot3_is_one_root_of_three_squares(
        a in -4.0e5f64..4.0e5,
        b in -4.0e5f64..4.0e5,
        c in -4.0e5f64..4.0e5,
        scale in -12i32..1,
    ) {
        let s = 2f64.powi(scale);
        let (a, b, c) = (a * s, b * s, c * s);
        // Two divisions, three products, two sums, a root and a product.
        check::<f64>(a, b, c, 10.0 * f64::EPSILON, 0.0);
        check::<f32>(a, b, c, 10.0 * f32::EPSILON as f64, 0.0);
        // Q32.32: the ratios and their squares to 2⁻³², the root and the
        // product to 2⁻³² of the largest magnitude.
        check::<Fix>(a, b, c, 8.0 / 4_294_967_296.0, 4.0 / 4_294_967_296.0);
        // Half an ulp plus 2⁻⁵⁹ (scaled.rs), and the conversion's half ulp.
        check::<ScaledScalar>(a, b, c, 1.0 / 1_073_741_824.0, 0.0);
    }
}

fn invalid_propagates<S: Scalar + Real>(invalid: S) {
    let (zero, one) = (
        <S as abtrack::Quantity>::ZERO,
        <S as abtrack::num::Real>::ONE,
    );
    for args in [
        (invalid, one, one),
        (one, invalid, one),
        (one, one, invalid),
        (invalid, zero, zero),
    ] {
        assert!(
            !abtrack::Quantity::is_valid(Real::hypot3(args.0, args.1, args.2)),
            "{}: an invalid argument gave a valid hypot3",
            <S as abtrack::Numeric>::NAME
        );
    }
    assert_eq!(
        abtrack::Quantity::to_f64(Real::hypot3(zero, zero, zero)),
        0.0
    );
}

#[test]
fn an_invalid_argument_gives_an_invalid_result() {
    invalid_propagates(f64::NAN);
    invalid_propagates(f64::INFINITY);
    invalid_propagates(f32::NAN);
    invalid_propagates(f32::NEG_INFINITY);
    invalid_propagates(<Fix as abtrack::Quantity>::from_f64_lossy(f64::NAN));
    invalid_propagates(<ScaledScalar as abtrack::Quantity>::from_f64_lossy(
        f64::NAN,
    ));
}
