//! The fast fixed point's sine and cosine (`abtrack::num::sine`): the table
//! against f64, and the error of sin_cos_q31 against f64 at the exact
//! binary angle, within the stated bound, over the ends of every table
//! interval, the quarter turns and random angles; `f32`'s sin_cos (the
//! same table, no double precision) within its bound.

use abtrack::num::fixed32::Angle;
use abtrack::num::sine::{
    sin_cos_f32, sin_cos_q31, SINE_Q31, SIN_COS_F32_MAX_ERROR, SIN_COS_MAX_ERROR_Q31,
};
use abtrack::num::{Numeric, Quantity};
use abtrack::Fixed32;
use proptest::prelude::*;

const Q31: f64 = 2147483648.0;

/// The error of each component, in units of 2⁻³¹, at binary angle `turns`.
fn error_q31(turns: u32) -> (f64, f64) {
    let theta = f64::from(turns) * std::f64::consts::TAU / 4294967296.0;
    let (s, c) = sin_cos_q31(turns);
    (
        (s as f64 - theta.sin() * Q31).abs(),
        (c as f64 - theta.cos() * Q31).abs(),
    )
}

#[test]
fn the_table_is_the_rounded_sine() {
    for (j, &v) in SINE_Q31.iter().enumerate() {
        let exact = (std::f64::consts::PI * j as f64 / 512.0).sin() * Q31;
        assert_eq!(f64::from(v), exact.round(), "entry {j}");
    }
}

/// Every table interval's first and last angles (where d is 0 and largest),
/// in every quadrant, and the largest error seen over them.
#[test]
fn within_the_bound_at_every_interval_end() {
    let mut worst = 0.0f64;
    for quadrant in 0u32..4 {
        for index in 0u32..256 {
            let start = (quadrant << 30) | (index << 22);
            for turns in [start, start + 1, start + (1 << 21), start + (1 << 22) - 1] {
                let (es, ec) = error_q31(turns);
                worst = worst.max(es).max(ec);
            }
        }
    }
    println!("largest error over the interval ends: {worst:.3} units of 2^-31");
    assert!(worst <= SIN_COS_MAX_ERROR_Q31, "{worst}");
}

#[test]
fn quarter_turns_are_exact() {
    assert_eq!(sin_cos_q31(0), (0, 1 << 31));
    assert_eq!(sin_cos_q31(1 << 30), (1 << 31, 0));
    assert_eq!(sin_cos_q31(2 << 30), (0, -(1 << 31)));
    assert_eq!(sin_cos_q31(3 << 30), (-(1 << 31), 0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200_000))]

    #[test]
    fn within_the_bound_everywhere(turns in any::<u32>()) {
        let (es, ec) = error_q31(turns);
        prop_assert!(es <= SIN_COS_MAX_ERROR_Q31 && ec <= SIN_COS_MAX_ERROR_Q31, "{es} {ec}");
    }

    /// Through `Fixed32::sin_cos` on an angle in radians: the table's bound,
    /// plus the conversion to turns (1.8·10⁻¹⁰ relative) and the rounding
    /// to 31-bit mantissas (2⁻³¹ relative).
    #[test]
    fn fixed32_sin_cos_of_radians(theta in -20.0f64..20.0) {
        let angle = Angle::from_f64_lossy(theta);
        let exact = angle.to_f64();
        let (s, c) = Fixed32::sin_cos(angle);
        let bound = SIN_COS_MAX_ERROR_Q31 / Q31 + exact.abs() * 1.8e-10 + 1.0 / Q31;
        prop_assert!((s.to_f64() - exact.sin()).abs() <= bound);
        prop_assert!((c.to_f64() - exact.cos()).abs() <= bound);
    }

    /// `f32`'s sin_cos (the library's, no libm `sincosf`): within
    /// SIN_COS_F32_MAX_ERROR plus half an ulp of each result, at the exact
    /// f32 angle, for |θ| ≤ 2π.
    #[test]
    fn f32_sin_cos_within_its_bound(theta in -std::f64::consts::TAU..std::f64::consts::TAU) {
        let t = theta as f32;
        let exact = f64::from(t);
        let (s, c) = <f32 as abtrack::Numeric>::sin_cos(t);
        let half_ulp = |v: f32| f64::from(f32::EPSILON) / 2.0 * f64::from(v.abs());
        prop_assert!(
            (f64::from(s) - exact.sin()).abs() <= SIN_COS_F32_MAX_ERROR + half_ulp(s),
            "sin {t}: {s} vs {}", exact.sin()
        );
        prop_assert!(
            (f64::from(c) - exact.cos()).abs() <= SIN_COS_F32_MAX_ERROR + half_ulp(c),
            "cos {t}: {c} vs {}", exact.cos()
        );
    }
}

/// `f32` sin_cos at the quarter turns' exact angles, of NaN and ±∞, and of
/// a subnormal angle.
#[test]
fn f32_sin_cos_special_values() {
    assert_eq!(sin_cos_f32(0.0), (0.0, 1.0));
    let (s, c) = sin_cos_f32(std::f32::consts::FRAC_PI_2);
    assert!((s - 1.0).abs() <= f32::EPSILON && c.abs() < 1e-7, "{s} {c}");
    let (s, c) = sin_cos_f32(-std::f32::consts::PI);
    assert!(s.abs() < 1e-7 && (c + 1.0).abs() <= f32::EPSILON, "{s} {c}");
    for v in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let (s, c) = sin_cos_f32(v);
        assert!(s.is_nan() && c.is_nan(), "{v}: {s} {c}");
    }
    assert_eq!(sin_cos_f32(1.0e-45), (0.0, 1.0));
}

/// The largest error over a sweep of 2²⁴ evenly spaced angles (every 256th
/// binary angle), printed for the documentation.
#[test]
fn measured_error_over_a_sweep() {
    let mut worst = 0.0f64;
    for k in 0u32..(1 << 24) {
        let (es, ec) = error_q31(k << 8 | (k & 0xFF));
        worst = worst.max(es).max(ec);
    }
    println!("largest error over the sweep: {worst:.3} units of 2^-31");
    assert!(worst <= SIN_COS_MAX_ERROR_Q31);
}
