//! Threat measures (`abtrack::tcas`): range tau with the closure-rate floor,
//! modified tau, closest point of approach and vertical tau, with golden
//! values computed by hand, in f64, f32 and Q32.32.

use abtrack::num::{Quantity, Real};
use abtrack::tcas::{
    closest_approach, modified_tau, range_tau, vertical_tau, TcasError, CLOSURE_RATE_FLOOR_M_PER_S,
    METRES_PER_NAUTICAL_MILE, METRES_PER_SECOND_PER_KNOT,
};
use abtrack::{Fix, Scalar};

const NM: f64 = METRES_PER_NAUTICAL_MILE;
const KT: f64 = METRES_PER_SECOND_PER_KNOT;

/// Relative tolerance of each type for these short computations (a few
/// roundings of values up to 2·10⁴): f32 ≈ 8 steps, Q32.32 absolute 2.3e-10
/// on values ≥ 10 is < 1e-10 relative, plus the final division.
fn close<S: Scalar>(got: S, want: f64) -> bool {
    let rel = match S::NAME {
        "f64" => 1e-12,
        "f32" => 1e-6,
        _ => 1e-8,
    };
    (got.to_f64() - want).abs() <= rel * want.abs().max(1.0)
}

fn s<S: Scalar>(v: f64) -> S {
    S::from_f64_lossy(v)
}

fn range_taus<S: Scalar>() {
    // 10 NM closing at 600 kt: 10 NM / (600/3600 NM/s) = 60 s.
    let t = range_tau(s::<S>(10.0 * NM), s(-600.0 * KT))
        .unwrap()
        .unwrap();
    assert!(close(t, 60.0), "{}: {t:?}", S::NAME);
    // Closure below 10 ft/s = 3.048 m/s is floored: 1000 m at 1 m/s or at
    // rest gives 1000/3.048 = 328.083 989 501 s.
    for rate in [-1.0, 0.0, -CLOSURE_RATE_FLOOR_M_PER_S] {
        let t = range_tau(s::<S>(1000.0), s(rate)).unwrap().unwrap();
        assert!(
            close(t, 328.083_989_501_312_3),
            "{}: {rate}: {t:?}",
            S::NAME
        );
    }
    // Faster than the floor: unchanged, 1000/4 = 250 s.
    assert!(close(
        range_tau(s::<S>(1000.0), s(-4.0)).unwrap().unwrap(),
        250.0
    ));
    // Opening slower than the floor counts as closing at it (DO-185B
    // `range_test`): the same tau; faster, diverging, none.
    for rate in [0.1, CLOSURE_RATE_FLOOR_M_PER_S] {
        let t = range_tau(s::<S>(1000.0), s(rate)).unwrap().unwrap();
        assert!(
            close(t, 328.083_989_501_312_3),
            "{}: {rate}: {t:?}",
            S::NAME
        );
    }
    assert_eq!(range_tau(s::<S>(1000.0), s(3.1)).unwrap(), None);
    assert_eq!(range_tau(s::<S>(0.0), s(-10.0)).unwrap(), Some(S::ZERO));

    // Modified tau, head-on at 600 kt with the SL 5 TA DMOD of 0.75 NM, at
    // r = 6.75 NM: (6.75² − 0.75²)/(6.75·(1/6)) = (45.5625 − 0.5625)/1.125
    // = 40 s (the TA threshold: see tests/it/tcas/analytic_encounters.rs).
    let dmod = s::<S>(0.75 * NM);
    let t = modified_tau(s::<S>(6.75 * NM), s(-600.0 * KT), dmod)
        .unwrap()
        .unwrap();
    assert!(close(t, 40.0), "{}: {t:?}", S::NAME);
    // Inside or at DMOD: 0, closing or not.
    for (r, rate) in [
        (0.75 * NM, -10.0),
        (0.5 * NM, -10.0),
        (0.5 * NM, 50.0),
        (0.0, 0.0),
    ] {
        assert_eq!(
            modified_tau(s::<S>(r), s(rate), dmod).unwrap(),
            Some(S::ZERO)
        );
    }
    // Diverging outside DMOD: none; opening under the floor: at the floor,
    // (2 − 0.75²/2)·1852/3.048 = 1.71875·1852/3.048 = 1044.3324 s.
    assert_eq!(modified_tau(s::<S>(2.0 * NM), s(50.0), dmod).unwrap(), None);
    assert_eq!(modified_tau(s::<S>(2.0 * NM), s(3.1), dmod).unwrap(), None);
    let t = modified_tau(s::<S>(2.0 * NM), s(1.0), dmod)
        .unwrap()
        .unwrap();
    assert!((t.to_f64() - 1044.3324).abs() < 2e-2, "{}: {t:?}", S::NAME);
    // The floor: 100 m outside DMOD = 1389 m, at rest. r = 1489 m,
    // DMOD²/r = 1 929 321/1489 = 1295.7159, (1489 − 1295.7159)/3.048
    // = 193.2841/3.048 = 63.4134 s.
    let t = modified_tau(s::<S>(1489.0), s(0.0), s(1389.0))
        .unwrap()
        .unwrap();
    assert!((t.to_f64() - 63.4134).abs() < 1e-4, "{}: {t:?}", S::NAME);
}

#[test]
fn range_and_modified_tau_in_all_types() {
    in_every_tcas_type!(range_taus);
}

fn cpa<S: Scalar>() {
    let c = |p: [f64; 2], v: [f64; 2]| {
        closest_approach([s::<S>(p[0]), s(p[1])], [s::<S>(v[0]), s(v[1])])
            .unwrap()
            .unwrap()
    };
    // p = (3000, 4000) m, v = (−30, −10) m/s: p·v = −90 000 − 40 000
    // = −130 000, |v|² = 1000, t = 130 s; p + 130 v = (−900, 2700),
    // d = √(810 000 + 7 290 000) = √8 100 000 = 900√10 = 2846.0499 m.
    let a = c([3000.0, 4000.0], [-30.0, -10.0]);
    assert!(close(a.time_s, 130.0), "{}: {a:?}", S::NAME);
    assert!(
        close(a.distance_m, 2_846.049_894_151_541_5),
        "{}: {a:?}",
        S::NAME
    );
    // Crossing 1 NM abeam: from (−6 NM, 1 NM) at 360 kt east: 6 NM at
    // 0.1 NM/s = 60 s, miss 1 NM = 1852 m.
    let a = c([-6.0 * NM, 1.0 * NM], [360.0 * KT, 0.0]);
    assert!(close(a.time_s, 60.0), "{}: {a:?}", S::NAME);
    assert!(close(a.distance_m, 1852.0), "{}: {a:?}", S::NAME);
    // Head-on: 60 s, miss 0.
    let a = c([0.0, 10.0 * NM], [0.0, -600.0 * KT]);
    assert!(
        close(a.time_s, 60.0) && a.distance_m.to_f64().abs() < 1e-3,
        "{a:?}"
    );
    // Opening: the closest approach is now.
    let a = c([1000.0, 0.0], [10.0, 3.0]);
    assert_eq!(a.time_s, S::ZERO);
    assert!(close(a.distance_m, 1000.0));
    // No relative motion: the range stays.
    let a = c([300.0, 400.0], [0.0, 0.0]);
    assert_eq!(a.time_s, S::ZERO);
    assert!(close(a.distance_m, 500.0));
}

#[test]
fn closest_approach_in_all_types() {
    in_every_tcas_type!(cpa);
}

#[test]
fn closest_approach_fits_fixed_point_at_the_envelope_edge() {
    // 400 km by 400 km closing at 1500 m/s on each axis: p·v = −1.2e9 per
    // axis, −2.4e9 in total, beyond Q32.32 (2.1e9); the unit-vector form
    // never forms it. t = 400 000/1500 = 266.667 s, miss 0.
    let p = [
        Fix::from_f64_lossy(400_000.0),
        Fix::from_f64_lossy(400_000.0),
    ];
    let v = [Fix::from_f64_lossy(-1500.0), Fix::from_f64_lossy(-1500.0)];
    let a = closest_approach(p, v).unwrap().unwrap();
    assert!((a.time_s.to_f64() - 266.666_667).abs() < 1e-5, "{a:?}");
    assert!(a.distance_m.to_f64().abs() < 1e-3, "{a:?}");
    // A relative speed of 2⁻³² m/s at 400 km: t = 1.7e15 s is not
    // representable, so there is no answer rather than a wrong one.
    let v = [-Fix::DELTA, Fix::ZERO];
    assert_eq!(closest_approach([p[0], Fix::ZERO], v), Ok(None));
}

fn vertical<S: Scalar>() {
    // 500 ft above, closing at 25 ft/s: 20 s.
    assert!(close(
        vertical_tau(s::<S>(500.0), s(-25.0)).unwrap().unwrap(),
        20.0
    ));
    // 300 ft below, closing at 10 ft/s: 30 s.
    assert!(close(
        vertical_tau(s::<S>(-300.0), s(10.0)).unwrap().unwrap(),
        30.0
    ));
    // Co-altitude: 0; diverging or level: none.
    assert_eq!(vertical_tau(s::<S>(0.0), s(5.0)).unwrap(), Some(S::ZERO));
    assert_eq!(vertical_tau(s::<S>(500.0), s(5.0)).unwrap(), None);
    assert_eq!(vertical_tau(s::<S>(500.0), s(0.0)).unwrap(), None);
    assert_eq!(vertical_tau(s::<S>(-500.0), s(-1.0)).unwrap(), None);
}

#[test]
fn vertical_tau_in_all_types() {
    in_every_tcas_type!(vertical);
    // 1000 ft closing at 2⁻³² ft/s: 4.3e12 s does not fit Q32.32: none.
    assert_eq!(
        vertical_tau(Fix::from_f64_lossy(1000.0), -Fix::DELTA),
        Ok(None)
    );
}

#[test]
fn invalid_inputs_are_refused() {
    for bad in [f64::NAN, f64::INFINITY] {
        assert_eq!(range_tau(bad, -1.0), Err(TcasError::InvalidInput));
        assert_eq!(range_tau(100.0, bad), Err(TcasError::InvalidInput));
        assert_eq!(modified_tau(100.0, -1.0, bad), Err(TcasError::InvalidInput));
        assert_eq!(vertical_tau(bad, 1.0), Err(TcasError::InvalidInput));
        assert_eq!(
            closest_approach([bad, 0.0], [1.0, 0.0]),
            Err(TcasError::InvalidInput)
        );
    }
    assert_eq!(range_tau(-1.0, -1.0), Err(TcasError::InvalidInput));
    assert_eq!(modified_tau(-1.0, -1.0, 10.0), Err(TcasError::InvalidInput));
    assert_eq!(range_tau(Fix::MAX, Fix::ONE), Err(TcasError::InvalidInput));
    assert_eq!(
        vertical_tau(Fix::ONE, Fix::MIN),
        Err(TcasError::InvalidInput)
    );
}
