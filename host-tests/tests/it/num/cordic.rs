//! Fixed-point sine, cosine and arctangent (CORDIC, `abtrack::num::cordic`)
//! against f64 libm, swept over the whole input range. The error is measured
//! against the function at the exact Q32.32 input, so every reference input
//! here is exactly representable in f64 (53 bits) or the effect of its
//! rounding is shown to be negligible.

use abtrack::num::cordic::{ATAN2_MAX_ERROR, SIN_COS_MAX_ERROR};
use abtrack::num::{Numeric, Quantity, Real};
use abtrack::{Fix, Scalar};
use std::f64::consts::PI;

/// xorshift64*: a fixed, reproducible stream of test inputs.
struct Stream(u64);
impl Stream {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
}

/// Largest |error| of sin and cos over the given raw Q32.32 angles, with the
/// angle where it occurs.
fn sin_cos_error(angles: impl Iterator<Item = i64>) -> (f64, i64, usize) {
    let mut worst = (0.0f64, 0i64, 0usize);
    for bits in angles {
        let theta = Fix::from_bits(bits);
        let exact = theta.to_f64();
        // f64 holds the Q32.32 value exactly when it has ≤ 53 significant bits.
        assert_eq!(Fix::try_from_f64(exact).unwrap(), theta, "input not exact");
        let (s, c) = Fix::sin_cos(theta);
        assert!(s.is_valid() && c.is_valid());
        let e = (s.to_f64() - exact.sin())
            .abs()
            .max((c.to_f64() - exact.cos()).abs());
        if e > worst.0 {
            worst.0 = e;
            worst.1 = bits;
        }
        worst.2 += 1;
    }
    worst
}

fn check_sin_cos(name: &str, angles: impl Iterator<Item = i64>) {
    let (e, at, n) = sin_cos_error(angles);
    println!(
        "sin_cos {name}: {n} angles, max error {e:.3e} ({:.3} Q32.32 steps) at {}",
        e * 2f64.powi(32),
        Fix::from_bits(at).to_f64()
    );
    assert!(
        e <= SIN_COS_MAX_ERROR,
        "{name}: error {e:e} at {at} exceeds the documented bound"
    );
}

#[test]
fn sin_cos_dense_over_four_turns() {
    // 4·10⁶ angles over [−4π, 4π], step ≈ 6.3·10⁻⁶ rad (an odd number of
    // Q32.32 steps so the samples fall at unrelated fractional bits).
    let span = (4.0 * PI * 2f64.powi(32)) as i64;
    let step = (2 * span / 4_000_000) | 1;
    check_sin_cos("dense [-4pi, 4pi]", (-span..=span).step_by(step as usize));
}

#[test]
fn sin_cos_around_every_octant_boundary() {
    // The reduction switches quadrant at odd multiples of π/4 and the
    // reduction wraps at multiples of 2π: every step within ±2000 of each.
    let mut angles = Vec::new();
    for k in -40i64..=40 {
        let centre = (k as f64 * PI / 4.0 * 2f64.powi(32)).round() as i64;
        angles.extend(centre - 2000..=centre + 2000);
    }
    check_sin_cos("octant boundaries", angles.into_iter());
}

#[test]
fn sin_cos_over_the_whole_q32_range() {
    // Random angles up to ±2³¹ rad. Clearing the low 11 bits leaves 52
    // significant bits, so the f64 reference gets the exact angle (libm
    // reduces large arguments exactly, Payne–Hanek).
    let mut s = Stream(0x9E37_79B9_7F4A_7C15);
    let angles = (0..1_000_000).map(move |i| {
        let shift = (i % 63) as u32; // every magnitude from 2⁻³² to 2³¹
        let v = (s.next() as i64) >> shift;
        (v >> 11) << 11
    });
    check_sin_cos("random, all magnitudes", angles);
    // The extremes just inside the sentinels.
    let edge = (i64::MAX >> 11) << 11;
    check_sin_cos("extremes", [edge, -edge, 1, -1, 0].into_iter());
}

#[test]
fn sin_cos_exact_points_and_sentinels() {
    let (s, c) = Fix::sin_cos(Fix::ZERO);
    assert_eq!((s, c), (Fix::ZERO, Fix::ONE));
    // |sin|, |cos| never exceed 1 (the result is clamped after rounding).
    for bits in (0..2_000_000i64).map(|k| k * 13_493) {
        let (s, c) = Fix::sin_cos(Fix::from_bits(bits));
        assert!(s.abs() <= Fix::ONE && c.abs() <= Fix::ONE);
    }
    for sentinel in [Fix::MAX, Fix::MIN] {
        let (s, c) = Fix::sin_cos(sentinel);
        assert!(!s.is_valid() && !c.is_valid());
    }
}

fn check_atan2(name: &str, pairs: impl Iterator<Item = (i64, i64)>) {
    let mut worst = (0.0f64, (0i64, 0i64));
    let mut n = 0usize;
    for (yb, xb) in pairs {
        let (y, x) = (Fix::from_bits(yb), Fix::from_bits(xb));
        let a = y.atan2(x);
        assert!(a.is_valid());
        // Rounding the inputs to 53 bits moves the angle by at most
        // 2⁻⁵³ rad, far below the bound being checked.
        let reference = y.to_f64().atan2(x.to_f64());
        let e = (a.to_f64() - reference).abs();
        // (−π, π] in the representation: π itself is its nearest Q32.32
        // value, −π is excluded.
        let pi = Fix::from_f64_lossy(PI);
        assert!(a > -pi && a <= pi, "{a:?} outside (-pi, pi]");
        if e > worst.0 {
            worst = (e, (yb, xb));
        }
        n += 1;
    }
    println!(
        "atan2 {name}: {n} pairs, max error {:.3e} ({:.3} Q32.32 steps) at y={} x={}",
        worst.0,
        worst.0 * 2f64.powi(32),
        Fix::from_bits(worst.1 .0).to_f64(),
        Fix::from_bits(worst.1 .1).to_f64()
    );
    assert!(
        worst.0 <= ATAN2_MAX_ERROR,
        "{name}: error {:e} at {:?} exceeds the documented bound",
        worst.0,
        worst.1
    );
}

#[test]
fn atan2_around_the_circle_at_every_scale() {
    // 20 000 directions × radii from 2⁻²⁰ to 2³⁰ (tiny vectors lose
    // direction to the 2⁻³² grid, which the reference sees too).
    let mut pairs = Vec::new();
    for k in 0..20_000 {
        let phi = -PI + (k as f64 + 0.37) * (2.0 * PI / 20_000.0);
        for e in (-20..=30).step_by(5) {
            let rho = 2f64.powi(e) * 1.7;
            let y = Fix::from_f64_lossy(rho * phi.sin()).to_bits();
            let x = Fix::from_f64_lossy(rho * phi.cos()).to_bits();
            pairs.push((y, x));
        }
    }
    check_atan2("circle x scales", pairs.into_iter());
}

#[test]
fn atan2_random_pairs_and_extreme_ratios() {
    let mut s = Stream(0xD1B5_4A32_D192_ED03);
    let pairs = (0..1_000_000).map(move |i| {
        let (sy, sx) = ((i % 63) as u32, ((i / 63) % 63) as u32);
        let y = (s.next() as i64) >> sy;
        let x = (s.next() as i64) >> sx;
        // Keep clear of the sentinels.
        (
            y.clamp(i64::MIN + 1, i64::MAX - 1),
            x.clamp(i64::MIN + 1, i64::MAX - 1),
        )
    });
    check_atan2("random, all magnitudes", pairs);
    let big = i64::MAX - 1;
    check_atan2(
        "extreme ratios",
        [
            (1, big),
            (-1, big),
            (1, -big),
            (-1, -big),
            (big, 1),
            (big, -1),
            (-big, 1),
            (big, big),
            (-big, -big),
            (1, 1),
            (-1, -1),
        ]
        .into_iter(),
    );
}

#[test]
fn atan2_axes_signs_and_sentinels() {
    let one = Fix::ONE;
    let pi = Fix::from_f64_lossy(PI);
    let half_pi = Fix::from_f64_lossy(PI / 2.0);
    assert_eq!(Fix::ZERO.atan2(Fix::ZERO), Fix::ZERO);
    assert_eq!(Fix::ZERO.atan2(one), Fix::ZERO);
    // The negative x axis is +π: the range is (−π, π].
    assert_eq!(Fix::ZERO.atan2(-one), pi);
    assert_eq!(one.atan2(Fix::ZERO), half_pi);
    assert_eq!((-one).atan2(Fix::ZERO), -half_pi);
    // Just above and below the negative x axis: ±(π − 2⁻³²). π·2³² =
    // 13 493 037 704.52, so π − 2⁻³² rounds to 13 493 037 704 steps, one
    // below the representation of π (13 493 037 705).
    assert_eq!(Fix::DELTA.atan2(-one), pi - Fix::DELTA);
    assert_eq!((-Fix::DELTA).atan2(-one), -pi + Fix::DELTA);
    for s in [Fix::MAX, Fix::MIN] {
        assert!(!s.atan2(one).is_valid());
        assert!(!one.atan2(s).is_valid());
    }
}
