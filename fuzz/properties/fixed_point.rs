//! Q32.32 fixed point (`abtrack::Fix`) on arbitrary raw words: the
//! arithmetic the M3 and M0 firmware tracks with. Built with overflow checks
//! on (fuzz/Cargo.toml), so any integer wrap inside, CORDIC's included, is a
//! crash.
//!
//! Property: fixed point never wraps. Every result is the exact value
//! (rounded as documented: within one step of 2⁻³²) when that is
//! representable, and otherwise the saturation sentinel of the right sign;
//! a sentinel operand gives a sentinel; `sin`/`cos` stay within [−1, 1] and
//! within 2⁻³² of f64's, `atan2` within (−π, π] and 2⁻³² of f64's (checked
//! where the input converts to f64 exactly, |x| ≤ 2²¹).

use abtrack::num::cordic::{ATAN2_MAX_ERROR, SIN_COS_MAX_ERROR};
use abtrack::{Fix, Numeric, Quantity, Real, Scalar};

const MAX: i128 = i64::MAX as i128;
const MIN: i128 = i64::MIN as i128;

fn is_sentinel(x: Fix) -> bool {
    x == Fix::MAX || x == Fix::MIN
}

/// `result` is `exact` (raw 2⁻³² steps) within `slack` steps if that lies
/// strictly between the sentinels, else the sentinel of `exact`'s sign.
fn check_operation(op: &str, a: Fix, b: Fix, result: Fix, exact: i128, slack: i128) {
    if is_sentinel(a) || is_sentinel(b) {
        assert!(
            is_sentinel(result),
            "{op}({a:?}, {b:?}) = {result:?}: not a sentinel"
        );
        return;
    }
    let r = i128::from(result.to_bits());
    if exact > MIN + slack && exact < MAX - slack {
        assert!(
            (r - exact).abs() <= slack,
            "{op}({a:?}, {b:?}) = {result:?}, exact {exact} steps"
        );
    } else if exact >= MAX || exact <= MIN {
        let expected = if exact < 0 { Fix::MIN } else { Fix::MAX };
        assert_eq!(
            result, expected,
            "{op}({a:?}, {b:?}) out of range, exact {exact}"
        );
    } else {
        // Within `slack` of the range's end: either is right.
        assert!(
            is_sentinel(result) || (r - exact).abs() <= slack,
            "{op}({a:?}, {b:?}) = {result:?}, exact {exact} steps"
        );
    }
}

/// Exactly convertible to f64 (53 bits), and small enough that f64's own
/// sin/cos/atan2 error is far below a step.
fn f64_exact(x: Fix) -> Option<f64> {
    (x.to_bits().unsigned_abs() <= 1 << 53).then(|| x.to_f64())
}

/// The fuzz target's input: two raw Q32.32 words and a byte that picks
/// how `a` is drawn.
pub type Words = (i64, i64, u8);

/// One corpus input: its words drawn from the bytes as libfuzzer-sys's
/// typed `fuzz_target!` draws them (an input too short for them, or that
/// does not decode, is skipped, as libFuzzer rejects it). The host tests'
/// corpus replay calls it; the fuzz target is typed and calls
/// [`check_words`].
#[allow(dead_code)]
pub fn check(data: &[u8]) {
    use arbitrary::{Arbitrary, Unstructured};
    if data.len() < <Words as Arbitrary>::size_hint(0).0 {
        return;
    }
    if let Ok(words) = Words::arbitrary_take_rest(Unstructured::new(data)) {
        check_words(words);
    }
}

/// The properties, on one input's words.
pub fn check_words(words: Words) {
    let (a, b, pick) = (Fix::from_bits(words.0), Fix::from_bits(words.1), words.2);
    // Sentinels and near-range values more often than uniform bits give.
    let a = match pick % 8 {
        0 => Fix::MAX,
        1 => Fix::MIN,
        2 => Fix::from_bits(words.0 >> 24),
        _ => a,
    };
    let b = match (pick / 8) % 8 {
        0 => Fix::ZERO,
        1 => Fix::from_bits(words.1 >> 40),
        2 => Fix::from_bits(words.1 >> 20),
        _ => b,
    };
    let (x, y) = (i128::from(a.to_bits()), i128::from(b.to_bits()));

    check_operation("add", a, b, a + b, x + y, 0);
    check_operation("sub", a, b, a - b, x - y, 0);
    // Multiplication rounds toward −∞ (an arithmetic shift).
    check_operation("mul", a, b, a * b, (x * y) >> 32, 1);
    if y != 0 {
        // Division truncates.
        check_operation("div", a, b, a / b, (x << 32) / y, 1);
    } else {
        assert!(
            is_sentinel(a / b),
            "{a:?} / 0 = {:?}: not a sentinel",
            a / b
        );
    }
    check_operation("neg", a, Fix::ZERO, -a, -x, 0);

    let abs = a.abs();
    if is_sentinel(a) {
        assert!(is_sentinel(abs));
    } else {
        assert_eq!(i128::from(abs.to_bits()), x.abs(), "abs({a:?})");
    }

    let root = a.sqrt();
    if is_sentinel(a) || x < 0 {
        assert!(is_sentinel(root), "sqrt({a:?}) = {root:?}: not a sentinel");
    } else {
        // root² ≈ a: (r − 1)² ≤ a·2³² ≤ (r + 1)², in steps.
        let r = i128::from(root.to_bits());
        let scaled = x << 32;
        assert!(
            r >= 0 && (r == 0 || (r - 1) * (r - 1) <= scaled) && scaled <= (r + 1) * (r + 1),
            "sqrt({a:?}) = {root:?}"
        );
    }

    let (s, c) = Fix::sin_cos(a);
    if is_sentinel(a) {
        assert!(is_sentinel(s) && is_sentinel(c));
    } else {
        let one = 1i64 << 32;
        for v in [s, c] {
            assert!(
                v.to_bits().abs() <= one + 1,
                "sin_cos({a:?}) = ({s:?}, {c:?}): outside [-1, 1]"
            );
        }
        if let Some(t) = f64_exact(a) {
            let tolerance = SIN_COS_MAX_ERROR + 1e-15;
            assert!(
                (s.to_f64() - t.sin()).abs() <= tolerance,
                "sin({a:?}) = {s:?}"
            );
            assert!(
                (c.to_f64() - t.cos()).abs() <= tolerance,
                "cos({a:?}) = {c:?}"
            );
        }
    }

    let angle = a.atan2(b);
    if is_sentinel(a) || is_sentinel(b) {
        assert!(is_sentinel(angle));
    } else {
        let pi = core::f64::consts::PI;
        let v = angle.to_f64();
        assert!(
            v > -pi - 1e-9 && v <= pi + 1e-9,
            "atan2({a:?}, {b:?}) = {angle:?}: outside (-pi, pi]"
        );
        if let (Some(ya), Some(xb)) = (f64_exact(a), f64_exact(b)) {
            let expected = ya.atan2(xb);
            // The two ends of (−π, π] are the same angle.
            let d = (v - expected).abs();
            let d = d.min((d - 2.0 * pi).abs());
            assert!(
                d <= ATAN2_MAX_ERROR + 1e-15,
                "atan2({a:?}, {b:?}) = {angle:?}, f64 {expected}"
            );
        }
    }
}
