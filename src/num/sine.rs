//! Sine and cosine of a binary angle (2³² per turn) in 32-bit integer
//! arithmetic, for the fast fixed point ([`super::fixed32`]) and `f32`
//! ([`sin_cos_f32`]): a table of
//! sin(jπ/512), j = 0..=256, in Q31, and the angle-addition formula with
//! the remainder d < π/512 by its Taylor polynomials (sin d ≈ d − d³/6,
//! cos d ≈ 1 − d²/2):
//!
//! sin(a + d) = sin a − sin a·(d²/2) + cos a·(d − d³/6),
//! cos(a + d) = cos a − cos a·(d²/2) − sin a·(d − d³/6).
//!
//! The quarter turn is exact (two bits of the binary angle), so every
//! direction is reduced without error. Five 32×32→64 products, no division,
//! no loop.
//!
//! # Error
//!
//! Each component within [`SIN_COS_MAX_ERROR_Q31`] units of 2⁻³¹ of the
//! exact value at the exact binary angle: the table's rounding (½), the
//! two products' rounding (½ each), d²/2 and d − d³/6 in Q32 (their
//! rounding and the omitted d⁴/24, d⁵/120: below one Q32 unit each, times
//! sin a or cos a ≤ 1, half a Q31 unit each). `host-tests/tests/it/num/sine.rs`
//! checks the table against f64 and the bound over every table interval's
//! ends and random angles.

use super::wide::wide_mul_unsigned;

/// sin(jπ/512)·2³¹, rounded to nearest, j = 0..=256 (computed with 200-bit
/// mpmath; f64 gives the same words, the closest to a tie being 0.0013
/// units away).
pub const SINE_Q31: [u32; 257] = [
    0, 13176712, 26352928, 39528151, 52701887, 65873638, 79042909, 92209205, 105372028, 118530885,
    131685278, 144834714, 157978697, 171116733, 184248325, 197372981, 210490206, 223599506,
    236700388, 249792358, 262874923, 275947592, 289009871, 302061269, 315101295, 328129457,
    341145265, 354148230, 367137861, 380113669, 393075166, 406021865, 418953276, 431868915,
    444768294, 457650927, 470516330, 483364019, 496193509, 509004318, 521795963, 534567963,
    547319836, 560051104, 572761285, 585449903, 598116479, 610760536, 623381598, 635979190,
    648552838, 661102068, 673626408, 686125387, 698598533, 711045377, 723465451, 735858287,
    748223418, 760560380, 772868706, 785147934, 797397602, 809617249, 821806413, 833964638,
    846091463, 858186435, 870249095, 882278992, 894275671, 906238681, 918167572, 930061894,
    941921200, 953745043, 965532978, 977284562, 988999351, 1000676905, 1012316784, 1023918550,
    1035481766, 1047005996, 1058490808, 1069935768, 1081340445, 1092704411, 1104027237, 1115308496,
    1126547765, 1137744621, 1148898640, 1160009405, 1171076495, 1182099496, 1193077991, 1204011567,
    1214899813, 1225742318, 1236538675, 1247288478, 1257991320, 1268646800, 1279254516, 1289814068,
    1300325060, 1310787095, 1321199781, 1331562723, 1341875533, 1352137822, 1362349204, 1372509294,
    1382617710, 1392674072, 1402678000, 1412629117, 1422527051, 1432371426, 1442161874, 1451898025,
    1461579514, 1471205974, 1480777044, 1490292364, 1499751576, 1509154322, 1518500250, 1527789007,
    1537020244, 1546193612, 1555308768, 1564365367, 1573363068, 1582301533, 1591180426, 1599999411,
    1608758157, 1617456335, 1626093616, 1634669676, 1643184191, 1651636841, 1660027308, 1668355276,
    1676620432, 1684822463, 1692961062, 1701035922, 1709046739, 1716993211, 1724875040, 1732691928,
    1740443581, 1748129707, 1755750017, 1763304224, 1770792044, 1778213194, 1785567396, 1792854372,
    1800073849, 1807225553, 1814309216, 1821324572, 1828271356, 1835149306, 1841958164, 1848697674,
    1855367581, 1861967634, 1868497586, 1874957189, 1881346202, 1887664383, 1893911494, 1900087301,
    1906191570, 1912224073, 1918184581, 1924072871, 1929888720, 1935631910, 1941302225, 1946899451,
    1952423377, 1957873796, 1963250501, 1968553292, 1973781967, 1978936331, 1984016189, 1989021350,
    1993951625, 1998806829, 2003586779, 2008291295, 2012920201, 2017473321, 2021950484, 2026351522,
    2030676269, 2034924562, 2039096241, 2043191150, 2047209133, 2051150040, 2055013723, 2058800036,
    2062508835, 2066139983, 2069693342, 2073168777, 2076566160, 2079885360, 2083126254, 2086288720,
    2089372638, 2092377892, 2095304370, 2098151960, 2100920556, 2103610054, 2106220352, 2108751352,
    2111202959, 2113575080, 2115867626, 2118080511, 2120213651, 2122266967, 2124240380, 2126133817,
    2127947206, 2129680480, 2131333572, 2132906420, 2134398966, 2135811153, 2137142927, 2138394240,
    2139565043, 2140655293, 2141664948, 2142593971, 2143442326, 2144209982, 2144896910, 2145503083,
    2146028480, 2146473080, 2146836866, 2147119825, 2147321946, 2147443222, 2147483648,
];

/// The stated bound of each component's error, in units of 2⁻³¹
/// (module docs).
pub const SIN_COS_MAX_ERROR_Q31: f64 = 3.0;

/// π·2³⁰ rounded: one binary-angle unit (2π/2³² rad) is π·2³⁰ units of
/// 2⁻⁶¹ rad.
const PI_Q30: u32 = 3_373_259_426;

/// `a·b/2³²` rounded to nearest (a, b < 2³²).
#[inline(always)]
fn product_q32(a: u32, b: u32) -> u32 {
    // a·b + 2³¹ < 2⁶⁴: no wrap; the result is below 2³².
    (wide_mul_unsigned(a, b).wrapping_add(1 << 31) >> 32) as u32
}

/// (sin θ, cos θ)·2³¹ for θ = `turns`·2π/2³², each in [−2³¹, 2³¹] (module
/// docs for the method and the error).
pub fn sin_cos_q31(turns: u32) -> (i64, i64) {
    let quadrant = turns >> 30;
    let within = turns & ((1 << 30) - 1);
    // a = jπ/512 (the top 8 bits of the quarter turn), d the rest.
    let index = (within >> 22) as usize;
    let fraction = within & ((1 << 22) - 1);
    let sin_a = SINE_Q31.get(index).copied().unwrap_or(0);
    let cos_a = SINE_Q31
        .get(256usize.wrapping_sub(index))
        .copied()
        .unwrap_or(0);
    // d·2³⁹ = fraction·2π·2⁷ < 2²²·2¹⁰ (exact to 2⁻⁶¹ rad: PI_Q30's
    // rounding); below 2³², d < 0.0062.
    let d39 = (wide_mul_unsigned(fraction, PI_Q30) >> 22) as u32;
    // d²/2 in Q32 (< 2¹⁷): d39²/2⁴⁷, rounded.
    let half_square = (wide_mul_unsigned(d39, d39).wrapping_add(1 << 46) >> 47) as u32;
    // d − d³/6 in Q32: d/2⁷ rounded, minus (d²/2)·d/3 (below 2¹⁰).
    let d32 = d39.wrapping_add(64) >> 7;
    let cube_sixth = ((wide_mul_unsigned(half_square, d39) >> 39) as u32) / 3;
    let sin_d = d32.wrapping_sub(cube_sixth);
    // Every term below 2³² and the sums within [−2³¹·0.01, 2³¹·1.01]: i64.
    let term = |v: u32| i64::from(v);
    let sin = term(sin_a)
        .wrapping_sub(term(product_q32(sin_a, half_square)))
        .wrapping_add(term(product_q32(cos_a, sin_d)));
    let cos = term(cos_a)
        .wrapping_sub(term(product_q32(cos_a, half_square)))
        .wrapping_sub(term(product_q32(sin_a, sin_d)));
    match quadrant {
        0 => (sin, cos),
        1 => (cos, sin.wrapping_neg()),
        2 => (sin.wrapping_neg(), cos.wrapping_neg()),
        _ => (cos.wrapping_neg(), sin),
    }
}

/// Largest error of [`sin_cos_f32`] for |θ| ≤ 2π, each component, before
/// the result's rounding to `f32` (half an ulp): the table sine's
/// [`SIN_COS_MAX_ERROR_Q31`] units of 2⁻³¹ and the angle's conversion to
/// turns (1.8·10⁻¹⁰ relative, as for [`super::fixed32`]'s angles).
/// Checked by `host-tests/tests/it/num/sine.rs`.
pub const SIN_COS_F32_MAX_ERROR: f64 =
    SIN_COS_MAX_ERROR_Q31 / 2_147_483_648.0 + 1.8e-10 * core::f64::consts::TAU;

/// (sin θ, cos θ) of an `f32` angle in integer arithmetic: θ taken exactly
/// (its 24-bit mantissa and exponent) to a binary angle, [`sin_cos_q31`],
/// each result rounded once to `f32` (within [`SIN_COS_F32_MAX_ERROR`]
/// plus half an ulp). No double precision: libm's `sincosf` computes in
/// `f64`, a software library call on the Cortex-M4F's single-precision
/// FPU. NaN and ±∞ give NaN.
pub fn sin_cos_f32(theta: f32) -> (f32, f32) {
    let bits = theta.to_bits();
    let biased = (bits >> 23) & 0xFF;
    if biased == 0xFF {
        return (f32::NAN, f32::NAN);
    }
    // θ = ±m·2^e exactly: a normal f32 has the hidden bit, a subnormal the
    // exponent of the smallest normal.
    let fraction = i64::from(bits & 0x7F_FFFF);
    let (m, e) = if biased == 0 {
        (fraction, -149)
    } else {
        (fraction | (1 << 23), (biased as i32).wrapping_sub(150))
    };
    let m = if bits >> 31 != 0 { m.wrapping_neg() } else { m };
    // A 24-bit mantissa at an exponent in [−149, 104]: exact in the
    // 31-bit format (range [−200, 100] for the normalised mantissa).
    let angle = super::fixed32::Angle::from_wide(m, e);
    let (s, c) = sin_cos_q31(super::fixed32::turns(angle));
    // |s|, |c| ≤ 2³¹: one rounding to f32, then an exact power of two.
    const Q31: f32 = 1.0 / 2_147_483_648.0;
    (s as f32 * Q31, c as f32 * Q31)
}
