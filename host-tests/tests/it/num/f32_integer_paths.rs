//! `f32`'s integer paths of `Scalar::seconds_from_ms` and
//! `Scalar::round_scaled_i32` give the values of the `f64` route they
//! replace (the default methods), so the M4F links no double-precision
//! library for them.

use abtrack::Scalar;

/// The default method's route, through `f64` (which keeps the defaults).
fn seconds_via_f64(ms: u32) -> f32 {
    <f64 as abtrack::Quantity>::seconds_from_ms(ms) as f32
}

fn round_via_f64(v: f32, scale: u32) -> i32 {
    <f64 as Scalar>::round_scaled_i32(f64::from(v), scale)
}

#[test]
fn seconds_from_ms_matches_f64_for_every_ms_to_2_pow_24() {
    for ms in 0..=(1u32 << 24) {
        assert_eq!(
            <f32 as abtrack::Quantity>::seconds_from_ms(ms).to_bits(),
            seconds_via_f64(ms).to_bits(),
            "{ms} ms"
        );
    }
}

#[test]
fn round_scaled_matches_f64_on_edges_and_a_sweep() {
    let scales = [1u32, 10, 60, 100, 1000];
    let mut values = vec![
        0.0f32,
        -0.0,
        0.5,
        -0.5,
        1.5,
        -1.5,
        2.5,
        0.005,
        -0.005,
        0.015,
        0.49999997,
        f32::MIN_POSITIVE,
        f32::from_bits(1),
        -f32::from_bits(1),
        f32::MAX,
        f32::MIN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        2147483520.0,
        -2147483648.0,
        21474836.0,
        -21474837.0,
        4.0e5,
        -4.0e5,
        399_999.97,
    ];
    // Every 4099th bit pattern: all exponents and signs.
    values.extend((0..=u32::MAX).step_by(4099).map(f32::from_bits));
    for v in values {
        for scale in scales {
            assert_eq!(
                v.round_scaled_i32(scale),
                round_via_f64(v, scale),
                "{v:e} × {scale}"
            );
        }
    }
}
