//! Sine, cosine and arctangent of Q32.32 values ([`Fix`](super::Fix)) in
//! integer arithmetic only: CORDIC (Volder's COordinate Rotation DIgital
//! Computer iteration) with 40 iterations on 64-bit words scaled by 2⁶¹, after
//! an exact argument reduction in 128-bit words scaled by 2⁹⁴.
//!
//! No floating point is used on this path (the Cortex-M0/M3 have no FPU and
//! the M4F's is single precision), no operation can overflow (the bounds are
//! given next to each step) and no input panics: the callers in `num.rs` turn
//! saturation sentinels into sentinels before calling in.
//!
//! # Error bounds
//!
//! Against the exact value of the function at the exact Q32.32 input (f64 libm
//! as the reference, measured by the sweeps in `host-tests/tests/it/num/cordic.rs`):
//!
//! * `sin`, `cos`: at most [`SIN_COS_MAX_ERROR`] = 2⁻³² ≈ 2.33·10⁻¹⁰ (one
//!   Q32.32 step), for *any* representable angle, ±2³¹ rad included. The
//!   final rounding to 2⁻³² contributes half a step; the rest is the
//!   iteration's residual angle (≤ atan 2⁻³⁹ ≈ 1.8·10⁻¹²), the rounding of the
//!   2⁻⁶¹ intermediates (≤ 40·2⁻⁶¹) and the reduction (≤ 2³⁰·2⁻⁹⁴), together
//!   a few 10⁻¹² — the stated bound keeps a margin of a half step.
//! * `atan2`: at most [`ATAN2_MAX_ERROR`] = 2⁻³² rad, for any pair of
//!   representable inputs (result in (−π, π]); same composition, plus the
//!   step away from −π described in `atan2_bits`.
//!
//! Measured (10⁷ angles and 1.2·10⁶ pairs, every magnitude from 2⁻³² to 2³¹,
//! every octant boundary): sin/cos 0.508 steps (1.18·10⁻¹⁰), atan2 0.522
//! steps (1.22·10⁻¹⁰). Half a step is the best any Q32.32 result can do.

/// Maximum absolute error of [`Fix`](super::Fix) `sin_cos`, each component
/// (see the module docs for how it is composed and measured).
pub const SIN_COS_MAX_ERROR: f64 = 2.328_306_436_538_696_3e-10; // 2⁻³²

/// Maximum absolute error of [`Fix`](super::Fix) `atan2`, in radians.
pub const ATAN2_MAX_ERROR: f64 = 2.328_306_436_538_696_3e-10; // 2⁻³²

/// Number of CORDIC iterations. After `n` iterations the residual angle is at
/// most atan 2⁻⁽ⁿ⁻¹⁾, 1.8·10⁻¹² for 40: under 1 % of a Q32.32 step.
const ITERATIONS: usize = 40;

/// atan(2⁻ⁱ)·2⁶¹, rounded to nearest (computed with 300-bit mpmath; from
/// i = 21 on, atan 2⁻ⁱ rounds to 2⁻ⁱ at this scale).
const ATAN_TABLE: [i64; ITERATIONS] = [
    1811004864519280711,
    1069098597953152948,
    564882337777596249,
    286743094836456889,
    143927976672616092,
    72034151524184357,
    36025865417378411,
    18014032019027246,
    9007153442175927,
    4503593900760542,
    2251799097857775,
    1125899817364151,
    562949942236502,
    281474975312555,
    140737488180565,
    70368744155819,
    35184372086101,
    17592186044075,
    8796093022165,
    4398046511099,
    2199023255551,
    1099511627776,
    549755813888,
    274877906944,
    137438953472,
    68719476736,
    34359738368,
    17179869184,
    8589934592,
    4294967296,
    2147483648,
    1073741824,
    536870912,
    268435456,
    134217728,
    67108864,
    33554432,
    16777216,
    8388608,
    4194304,
];

/// The CORDIC gain compensation Π 1/√(1 + 2⁻²ⁱ), i < 40, times 2⁶¹.
const GAIN_INVERSE_Q61: i64 = 1400229935014726477;
/// π·2⁶¹ (7.24·10¹⁸, below i64::MAX = 9.22·10¹⁸).
const PI_Q61: i64 = 7244019458077122842;

/// 2π, π/2 and π/4 times 2⁹⁴ for the argument reduction. The reduction of an
/// angle of magnitude up to 2³¹ rad takes up to 3.4·10⁸ multiples of 2π, so
/// the constant carries 94 fractional bits: the accumulated error
/// (≤ 3.4·10⁸ · 2⁻⁹⁵) stays below 10⁻²⁰ rad.
const TWO_PI_Q94: i128 = 124451306656115542615260972311;
const HALF_PI_Q94: i128 = 31112826664028885653815243078;
const QUARTER_PI_Q94: i128 = 15556413332014442826907621539;

/// Q32.32 → Q94 shift, and Q94 → Q61 shift.
const Q32_TO_Q94: u32 = 62;
const Q94_TO_Q61: u32 = 33;
/// Q61 → Q32.32 shift.
const Q61_TO_Q32: u32 = 29;
/// 1.0 in Q32.32.
const ONE_Q32: i64 = 1 << 32;

/// Rounds a Q61 value to Q32.32 (half away from −∞; magnitudes here are
/// ≤ 2⁶³ − 2²⁸ so the addition cannot overflow).
#[inline]
fn round_q61_to_q32(v: i64) -> i64 {
    // Cannot wrap (bound above); wrapping_add keeps the step panic-free.
    v.wrapping_add(1 << (Q61_TO_Q32 - 1)) >> Q61_TO_Q32
}

/// (sin θ, cos θ) of a Q32.32 angle given as its raw word, results as raw
/// Q32.32 words in [−1, 1]. Every i64 input is accepted (the caller filters
/// the sentinels).
pub(super) fn sin_cos_bits(theta: i64) -> (i64, i64) {
    // Argument reduction to r ∈ [0, 2π), exact up to the constant's rounding.
    // |theta| < 2⁶³, so theta·2⁶² < 2¹²⁵ fits an i128.
    let t = (theta as i128) << Q32_TO_Q94;
    let r = if (0..TWO_PI_Q94).contains(&t) {
        t
    } else if (-TWO_PI_Q94..0).contains(&t) {
        // t ∈ [−2π, 0): the sum is in [0, 2π), no wrap.
        t.wrapping_add(TWO_PI_Q94)
    } else {
        // Larger angles (rare: azimuths stay within a turn or two) take the
        // slower 128-bit remainder; the divisor is a positive constant.
        t.rem_euclid(TWO_PI_Q94)
    };
    // Quadrant q: r − q·π/2 ∈ [−π/4, π/4]. q = 4 is the same as q = 0.
    let mut quadrant = 0u8;
    let mut bound = QUARTER_PI_Q94;
    // quadrant ≤ 4 and bound ≤ 9π/4·2⁹⁴ < 2⁹⁷: these steps cannot wrap.
    while quadrant < 4 && r >= bound {
        quadrant = quadrant.wrapping_add(1);
        bound = bound.wrapping_add(HALF_PI_Q94);
    }
    let reduced = r.wrapping_sub(i128::from(quadrant).wrapping_mul(HALF_PI_Q94));
    // |reduced| ≤ π/4·2⁹⁴ < 2⁹⁴, so after the shift it is < 2⁶¹: fits an i64.
    let z = (reduced.wrapping_add(1i128 << (Q94_TO_Q61 - 1)) >> Q94_TO_Q61) as i64;
    let (s, c) = rotate(z);
    // |s|, |c| ≤ 2⁶¹: negation cannot wrap.
    let (s, c) = match quadrant & 3 {
        0 => (s, c),
        1 => (c, s.wrapping_neg()),
        2 => (s.wrapping_neg(), c.wrapping_neg()),
        _ => (c.wrapping_neg(), s),
    };
    let clamp = |v: i64| round_q61_to_q32(v).clamp(-ONE_Q32, ONE_Q32);
    (clamp(s), clamp(c))
}

/// CORDIC in rotation mode: (sin z, cos z) in Q61 for |z| ≤ π/4 (Q61).
///
/// Starting from (K, 0), K the inverse gain, every iteration keeps the
/// vector's length ≤ 1, so |x|, |y| ≤ 2⁶¹ and each sum below is < 2⁶²; |z|
/// stays below π/4 + atan 1 < 2⁶¹·1.6.
fn rotate(mut z: i64) -> (i64, i64) {
    let mut x = GAIN_INVERSE_Q61;
    let mut y = 0i64;
    for (i, &step) in ATAN_TABLE.iter().enumerate() {
        let (dx, dy) = (y >> i, x >> i);
        // Fixed-width CORDIC steps; the bounds above keep them from wrapping.
        if z >= 0 {
            x = x.wrapping_sub(dx);
            y = y.wrapping_add(dy);
            z = z.wrapping_sub(step);
        } else {
            x = x.wrapping_add(dx);
            y = y.wrapping_sub(dy);
            z = z.wrapping_add(step);
        }
    }
    (y, x)
}

/// atan2(y, x) of raw Q32.32 words, as a raw Q32.32 word in (−π, π].
/// atan2(0, 0) is 0, as in C's `atan2(+0, +0)`. Every input except `i64::MIN` is accepted (the caller
/// filters the sentinels, which include it).
pub(super) fn atan2_bits(y: i64, x: i64) -> i64 {
    // On the axes the answer is a constant; returning it exactly also keeps
    // the iteration's last-bit wobble from putting −0 or π − 2⁻³² there.
    if y == 0 {
        return if x < 0 { round_q61_to_q32(PI_Q61) } else { 0 };
    }
    if x == 0 {
        let half_pi = round_q61_to_q32(PI_Q61 >> 1);
        return if y < 0 {
            half_pi.wrapping_neg()
        } else {
            half_pi
        };
    }
    let (ay, ax) = (y.unsigned_abs(), x.unsigned_abs());
    let largest = ay.max(ax); // > 0: neither is zero here
                              // Scale both magnitudes by the same power of two so the larger lies in
                              // [2⁵⁹, 2⁶⁰): the ratio, hence the angle, is unchanged, and the vectoring
                              // growth (≤ 1.65·√2) keeps every intermediate below 2⁶².
    let top = largest.checked_ilog2().unwrap_or(0); // bit index of the leading one
    let (ax, ay) = if top > 59 {
        let down = top.saturating_sub(59); // > 0 here
        (ax >> down, ay >> down)
    } else {
        let up = 59u32.saturating_sub(top); // ≤ 59 here
        (ax << up, ay << up)
    };
    // Both are now < 2⁶⁰, so the casts are exact.
    let first_quadrant = vector(ax as i64, ay as i64); // ∈ [0, π/2]
    let unsigned = if x < 0 {
        // first_quadrant ∈ [0, π/2]: no wrap.
        PI_Q61.wrapping_sub(first_quadrant)
    } else {
        first_quadrant
    };
    if y < 0 {
        // Below the negative x axis the angle is > −π, but within half a step
        // of it the nearest Q32.32 value is −π itself (the representation of
        // the excluded end of (−π, π]); the next one up is still within
        // 0.53 steps of the true value.
        // unsigned ∈ [0, π] in Q61 and π in Q32.32 < 2³⁴: no wrap.
        round_q61_to_q32(unsigned.wrapping_neg()).max(1i64.wrapping_sub(round_q61_to_q32(PI_Q61)))
    } else {
        round_q61_to_q32(unsigned)
    }
}

/// CORDIC in vectoring mode: the angle of (x, y), x, y ≥ 0, in Q61.
/// The iteration drives y to zero; the accumulated angle is atan(y/x).
fn vector(mut x: i64, mut y: i64) -> i64 {
    let mut z = 0i64;
    for (i, &step) in ATAN_TABLE.iter().enumerate() {
        let (dx, dy) = (y >> i, x >> i);
        // Fixed-width CORDIC steps; inputs < 2⁶⁰ and the growth ≤ 1.65·√2
        // keep them below 2⁶²: no wrap.
        if y > 0 {
            x = x.wrapping_add(dx);
            y = y.wrapping_sub(dy);
            z = z.wrapping_add(step);
        } else {
            x = x.wrapping_sub(dx);
            y = y.wrapping_add(dy);
            z = z.wrapping_sub(step);
        }
    }
    z
}
