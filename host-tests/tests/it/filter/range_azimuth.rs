//! The range–azimuth projection filter (He, Peng, Ling & Quan) in f64, f32
//! and Q32.32 against the independent f64 reference in
//! `abtrack_host_tests::reference_ra`, plus the readings of the paper's slips,
//! azimuth wrap-around and input rejection.

use abtrack::filter::range_azimuth::{
    CovarianceFactor, RangeAzimuthFilter, RangeAzimuthNoise, RangeAzimuthOutcome,
    PAPER_BEARING_VARIANCE,
};
use abtrack::filter::Phase;
use abtrack::num::{Quantity, Real};
use abtrack::{FilterError, Fix, Scalar};
use abtrack_host_tests::reference_ra::ReferenceRangeAzimuth;
use std::f64::consts::{PI, TAU};

/// xorshift64* with Box–Muller: reproducible Gaussian noise.
struct Noise(u64);
impl Noise {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn gaussian(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

/// Measurements (R, B, dt) of a constant-velocity relative track.
fn measurements(
    start: [f64; 2],
    velocity: [f64; 2],
    dt: f64,
    steps: usize,
    range_sigma: f64,
    bearing_sigma: f64,
    seed: u64,
) -> Vec<(f64, f64, f64)> {
    let mut noise = Noise(seed);
    (0..steps)
        .map(|k| {
            let t = k as f64 * dt;
            let (x, y) = (start[0] + velocity[0] * t, start[1] + velocity[1] * t);
            let r = x.hypot(y) + range_sigma * noise.gaussian();
            let b = (x.atan2(y) + bearing_sigma * noise.gaussian()).rem_euclid(TAU);
            (r, b, dt)
        })
        .collect()
}

/// He et al. §4: same direction, own 900 km/h behind, target 700 km/h
/// ahead at azimuth 30°, 280 km, T = 1 s, 500 s, range noise 100 m, bearing
/// noise σ_B² = 7.569e-3. The relative velocity is (700 − 900) km/h along
/// the common heading, taken as the y axis.
fn paper_scenario(seed: u64) -> Vec<(f64, f64, f64)> {
    let r0 = 280_000.0;
    let b0 = 30f64.to_radians();
    let closing = (700.0 - 900.0) / 3.6;
    measurements(
        [r0 * b0.sin(), r0 * b0.cos()],
        [0.0, closing],
        1.0,
        500,
        100.0,
        PAPER_BEARING_VARIANCE.sqrt(),
        seed,
    )
}

#[derive(Debug, Clone, Copy)]
enum Event {
    Measure(f64, f64, f64),
    Coast(f64),
}

fn events(meas: &[(f64, f64, f64)]) -> Vec<Event> {
    meas.iter()
        .map(|&(r, b, t)| Event::Measure(r, b, t))
        .collect()
}

/// Largest differences between the library filter in `S` and the reference
/// over a sequence of events.
#[derive(Debug, Default)]
struct Deviation {
    position: f64,
    velocity: f64,
    gain: f64,
    /// Relative, of the covariance entries (m² units).
    covariance: f64,
    range: f64,
    azimuth: f64,
}

/// Tolerances per numeric type, about four times the largest deviation
/// measured over all the scenarios below (paper scenario with Q = 1 and
/// Q = 0, TCAS encounters with coasts, northward crossing):
///
/// | | position | velocity | gain | covariance (relative) |
/// |---|---|---|---|---|
/// | f64 | 1.7e-10 m | 2.8e-11 m/s | 3.3e-16 | 1.1e-14 |
/// | f32 | 0.11 m | 0.029 m/s | 1.3e-7 | 1.7e-5 |
/// | Q32.32 | 2.8 mm | 6.3e-5 m/s | 4.7e-9 | 1.7e-6 |
///
/// f32 is three f32 steps at 2.8e5 m. For Q32.32 the CORDIC error of
/// 1.2e-10 times R = 2.8e5 m is 3e-5 m per projection, and the gains,
/// resolved to 2.3e-10, multiply residuals of up to 10⁵ m across range. The
/// Q32.32 gain and covariance maxima come from Q = 0, where nothing is
/// forgotten, the rounding of all 500 scans accumulates and the velocity
/// variance decays towards the resolution (with Q = 1: 6e-10 and 4e-8).
struct Bounds {
    position: f64,
    velocity: f64,
    gain: f64,
    /// Relative, of the covariance entries.
    covariance: f64,
    azimuth: f64,
}

fn bounds(name: &str) -> Bounds {
    match name {
        "f64" => Bounds {
            position: 1e-9,
            velocity: 1e-10,
            gain: 2e-15,
            covariance: 5e-14,
            azimuth: 5e-15,
        },
        "f32" => Bounds {
            position: 0.5,
            velocity: 0.15,
            gain: 5e-7,
            covariance: 1e-4,
            azimuth: 2e-6,
        },
        "q32" => Bounds {
            position: 0.012,
            velocity: 2.5e-4,
            gain: 2e-8,
            covariance: 7e-6,
            azimuth: 5e-8,
        },
        // The fast fixed point (abtrack::Fixed32): positions in 2⁻¹² m
        // steps, sines and covariance factors to 2⁻³⁰ relative (at 280 km
        // a sine's rounding alone is 2.6·10⁻⁴ m). About 2.5 times the
        // largest deviations measured on these runs (1.6·10⁻³ m,
        // 2.5·10⁻⁴ m/s, gains 1.1·10⁻⁷, covariance 2.0·10⁻⁷, azimuth
        // 4.0·10⁻⁷ rad at the encounter's short ranges).
        _ => Bounds {
            position: 4e-3,
            velocity: 6e-4,
            gain: 3e-7,
            covariance: 5e-7,
            azimuth: 1e-6,
        },
    }
}

fn compare<S: abtrack::Numeric>(events: &[Event], range_variance: f64, q: f64) -> Deviation {
    use abtrack::num::Quantity;
    let noise = RangeAzimuthNoise::<S>::paper_bearing_f64(range_variance, q).unwrap();
    let mut filter = RangeAzimuthFilter::new(noise);
    let mut reference = ReferenceRangeAzimuth::new(range_variance, PAPER_BEARING_VARIANCE, q);
    let mut d = Deviation::default();
    let interval = |v: f64| S::Interval::try_from_f64(v).unwrap();
    for &event in events {
        match event {
            Event::Coast(dt) => {
                filter.coast(interval(dt)).unwrap();
                reference.coast(dt);
            }
            Event::Measure(r, b, dt) => {
                let outcome = filter
                    .update(
                        S::Length::try_from_f64(r).unwrap(),
                        S::Angle::try_from_f64(b).unwrap(),
                        interval(dt),
                    )
                    .unwrap();
                match (outcome, reference.update(r, b, dt)) {
                    (RangeAzimuthOutcome::Filtered(inn), Some(step)) => {
                        let g = inn.gains;
                        for (a, e) in [
                            (g.alpha, step.alpha),
                            (g.beta, step.beta),
                            (g.w1, step.w1),
                            (g.w2, step.w2),
                        ] {
                            d.gain = d.gain.max((a.to_f64() - e).abs());
                        }
                        assert!((inn.range_residual.to_f64() - step.resid_r).abs() < 1.0);
                        assert!((inn.cross_range_residual.to_f64() - step.resid_cr).abs() < 1.0);
                    }
                    (RangeAzimuthOutcome::FirstPoint, None)
                    | (RangeAzimuthOutcome::SecondPoint, None) => {}
                    other => panic!("library and reference disagree on the phase: {other:?}"),
                }
            }
        }
        if reference.is_tracking() {
            let cov_rel = |f: CovarianceFactor<S>, m: [[f64; 2]; 2]| {
                let p = f.covariance_f64();
                [(p[0], m[0][0]), (p[1], m[0][1]), (p[2], m[1][1])]
                    .iter()
                    .map(|(a, e)| ((a - e) / e).abs())
                    .fold(0.0f64, f64::max)
            };
            d.covariance = d
                .covariance
                .max(cov_rel(filter.range_covariance(), reference.p_range))
                .max(cov_rel(filter.cross_range_covariance(), reference.p_cross));
        }
        let p = filter.position();
        let v = filter.velocity();
        d.position = d
            .position
            .max((p[0].to_f64() - reference.x[0]).abs())
            .max((p[1].to_f64() - reference.y[0]).abs());
        d.velocity = d
            .velocity
            .max((v[0].to_f64() - reference.x[1]).abs())
            .max((v[1].to_f64() - reference.y[1]).abs());
        d.range = d
            .range
            .max((filter.range().to_f64() - reference.range()).abs());
        let az = filter.azimuth().to_f64();
        assert!((0.0..TAU).contains(&az), "azimuth {az} outside [0, 2pi)");
        let da = (az - reference.azimuth()).abs();
        d.azimuth = d.azimuth.max(da.min(TAU - da));
    }
    assert_eq!(filter.saturations(), 0);
    assert_eq!(filter.phase(), Phase::Tracking);
    let b = bounds(S::NAME);
    println!("{}: {d:?}", S::NAME);
    assert!(
        d.position <= b.position,
        "{}: position {:e}",
        S::NAME,
        d.position
    );
    assert!(
        d.velocity <= b.velocity,
        "{}: velocity {:e}",
        S::NAME,
        d.velocity
    );
    assert!(d.gain <= b.gain, "{}: gain {:e}", S::NAME, d.gain);
    assert!(
        d.covariance <= b.covariance,
        "{}: covariance {:e}",
        S::NAME,
        d.covariance
    );
    // The range is re-synthesised from the position: within √2 of it.
    assert!(
        d.range <= 1.5 * b.position,
        "{}: range {:e}",
        S::NAME,
        d.range
    );
    assert!(
        d.azimuth <= b.azimuth,
        "{}: azimuth {:e}",
        S::NAME,
        d.azimuth
    );
    d
}

fn compare_all_types(events: &[Event], range_variance: f64, q: f64) {
    compare::<f64>(events, range_variance, q);
    compare::<f32>(events, range_variance, q);
    compare::<Fix>(events, range_variance, q);
    compare::<abtrack::Fixed32>(events, range_variance, q);
}

#[test]
fn paper_scenario_matches_reference_in_all_types() {
    for seed in [1u64, 2, 3] {
        compare_all_types(&events(&paper_scenario(seed)), 100.0 * 100.0, 1.0);
    }
}

#[test]
fn paper_scenario_without_process_noise_matches_reference() {
    // Q = 0: the gains decay like a least-squares fit's; √Q = 0 exercises
    // the rotations with a zero column.
    compare_all_types(&events(&paper_scenario(7)), 100.0 * 100.0, 0.0);
}

/// A TCAS-like encounter: 15 m range noise, 5° bearing noise, intruder
/// converging from 14 NM at 250 m/s relative, passing 600 m abeam, with
/// irregular intervals and missed scans (coasts).
fn tcas_events(seed: u64) -> Vec<Event> {
    let nm = 1852.0;
    let start = [600.0, 14.0 * nm];
    let velocity = [0.0, -250.0];
    let mut noise = Noise(seed);
    let bearing_sigma = PAPER_BEARING_VARIANCE.sqrt();
    let mut t = 0.0;
    let mut out = Vec::new();
    for k in 0..120 {
        let dt = [1.0, 0.5, 1.5, 1.0][k % 4];
        t += dt;
        if k % 17 == 9 {
            out.push(Event::Coast(dt));
            continue;
        }
        let (x, y) = (start[0] + velocity[0] * t, start[1] + velocity[1] * t);
        let r = x.hypot(y) + 15.0 * noise.gaussian();
        let b = (x.atan2(y) + bearing_sigma * noise.gaussian()).rem_euclid(TAU);
        // The interval since the last *call* is dt whether that call was an
        // update or a coast.
        out.push(Event::Measure(r, b, dt));
    }
    out
}

#[test]
fn tcas_encounter_with_coasts_matches_reference_in_all_types() {
    for seed in [11u64, 12] {
        compare_all_types(&tcas_events(seed), 15.0 * 15.0, 9.0);
    }
}

/// A target crossing north (azimuth through 0/2π): from (−3 km, 20 km) east
/// at 60 m/s for 100 s, azimuth 351.5° → 9.8°.
fn northward_crossing(seed: u64) -> Vec<(f64, f64, f64)> {
    measurements([-3000.0, 20_000.0], [60.0, 0.0], 1.0, 100, 30.0, 0.01, seed)
}

#[test]
fn azimuth_wraps_through_north() {
    let meas = northward_crossing(5);
    // The measured azimuths do wrap.
    assert!(meas.iter().any(|m| m.1 > 6.0) && meas.iter().any(|m| m.1 < 0.3));
    compare_all_types(&events(&meas), 30.0 * 30.0, 1.0);

    fn run<S: Scalar>(meas: &[(f64, f64, f64)], shift: f64) -> Vec<([f64; 2], f64)> {
        let noise = RangeAzimuthNoise::<S>::new_f64(900.0, 1e-4, 1.0).unwrap();
        let mut f = RangeAzimuthFilter::new(noise);
        let c = |v: f64| S::try_from_f64(v).unwrap();
        meas.iter()
            .map(|&(r, b, dt)| {
                f.update(c(r), c(b + shift), c(dt)).unwrap();
                let p = f.position();
                ([p[0].to_f64(), p[1].to_f64()], f.azimuth().to_f64())
            })
            .collect()
    }
    fn same_measurement_any_turn<S: Scalar>(meas: &[(f64, f64, f64)], tol: f64) {
        let base = run::<S>(meas, 0.0);
        for shift in [TAU, -TAU, 2.0 * TAU, -PI - PI] {
            for (a, b) in base.iter().zip(run::<S>(meas, shift)) {
                let d = (a.0[0] - b.0[0]).abs().max((a.0[1] - b.0[1]).abs());
                assert!(d <= tol, "{}: shift {shift}: {d:e} m", S::NAME);
            }
        }
        // The re-synthesised azimuth follows the truth across north, in
        // [0, 2π) throughout, and wraps.
        let mut wrapped = (false, false);
        for (k, (_, az)) in base.iter().enumerate().skip(5) {
            let t = k as f64;
            let truth = (-3000.0 + 60.0 * t).atan2(20_000.0f64).rem_euclid(TAU);
            let d = (az - truth).abs();
            assert!(
                d.min(TAU - d) < 0.01,
                "{}: scan {k}: {az} vs {truth}",
                S::NAME
            );
            assert!((0.0..TAU).contains(az));
            wrapped.0 |= *az > 6.0;
            wrapped.1 |= *az < 0.3;
        }
        assert!(wrapped.0 && wrapped.1);
    }
    // f64: B + 2πk differs from B in the last bits only. f32 resolves an
    // angle near 4π to 4.8e-7 rad, 1 cm at 20 km. Q32.32: the stored 2π is
    // off by 1.4e-10 rad, 3e-6 m at 20 km.
    same_measurement_any_turn::<f64>(&meas, 1e-6);
    same_measurement_any_turn::<f32>(&meas, 0.1);
    same_measurement_any_turn::<Fix>(&meas, 1e-4);
}

/// A filter in each phase, fed from a noiseless track.
fn filters_in_every_phase<S: Scalar>() -> Vec<RangeAzimuthFilter<S>> {
    let noise = RangeAzimuthNoise::<S>::paper_bearing_f64(225.0, 1.0).unwrap();
    let c = |v: f64| S::from_f64_lossy(v);
    let mut f = RangeAzimuthFilter::new(noise);
    let mut out = vec![f];
    for k in 0..4 {
        f.update(c(10_000.0 - 100.0 * k as f64), c(0.3), c(1.0))
            .unwrap();
        out.push(f);
    }
    assert_eq!(out[1].phase(), Phase::OnePoint);
    assert_eq!(out[4].phase(), Phase::Tracking);
    out
}

fn invalid_inputs_leave_state_untouched<S: Scalar>() {
    let c = |v: f64| S::from_f64_lossy(v);
    let bad_numbers: Vec<S> = if S::NAME == "q32" {
        vec![c(f64::INFINITY), c(f64::NEG_INFINITY), c(f64::NAN)] // sentinels
    } else {
        vec![c(f64::NAN), c(f64::INFINITY), c(f64::NEG_INFINITY)]
    };
    for filter in filters_in_every_phase::<S>() {
        let mut cases: Vec<(S, S, S, FilterError)> = vec![
            (c(0.0), c(0.3), c(1.0), FilterError::InvalidMeasurement),
            (c(-5.0), c(0.3), c(1.0), FilterError::InvalidMeasurement),
            (c(9000.0), c(0.3), c(0.0), FilterError::InvalidInterval),
            (c(9000.0), c(0.3), c(-1.0), FilterError::InvalidInterval),
        ];
        for &bad in &bad_numbers {
            cases.push((bad, c(0.3), c(1.0), FilterError::InvalidMeasurement));
            cases.push((c(9000.0), bad, c(1.0), FilterError::InvalidMeasurement));
            cases.push((c(9000.0), c(0.3), bad, FilterError::InvalidInterval));
        }
        for (r, b, dt, expected) in cases {
            let mut f = filter;
            assert_eq!(
                f.update(r, b, dt),
                Err(expected),
                "{}: {r:?} {b:?} {dt:?}",
                S::NAME
            );
            assert_eq!(f, filter, "{}: state changed by a refused update", S::NAME);
        }
        for dt in [c(0.0), c(-1.0), bad_numbers[0]] {
            let mut f = filter;
            assert_eq!(f.coast(dt), Err(FilterError::InvalidInterval));
            assert_eq!(f, filter);
        }
    }
}

#[test]
fn invalid_input_is_refused_without_touching_the_track() {
    invalid_inputs_leave_state_untouched::<f64>();
    invalid_inputs_leave_state_untouched::<f32>();
    invalid_inputs_leave_state_untouched::<Fix>();
}

#[test]
fn fixed_point_saturation_is_refused_and_counted() {
    let noise = RangeAzimuthNoise::<Fix>::paper_bearing_f64(225.0, 1.0).unwrap();
    let mut f = RangeAzimuthFilter::new(noise);
    let c = |v: f64| Fix::try_from_f64(v).unwrap();
    // 2·10⁹ m at azimuth 0, then at azimuth π: the y difference of −4·10⁹
    // is beyond Q32.32 (±2.1·10⁹).
    f.update(c(2.0e9), c(0.0), c(1.0)).unwrap();
    let before = f;
    assert_eq!(
        f.update(c(2.0e9), c(PI), c(1.0)),
        Err(FilterError::Saturated)
    );
    assert_eq!(f.saturations(), 1);
    assert_eq!(f.position(), before.position());
    assert_eq!(f.phase(), Phase::OnePoint);
    // The track goes on with sane input.
    assert_eq!(
        f.update(c(2.0e9 - 100.0), c(0.0), c(1.0)),
        Ok(RangeAzimuthOutcome::SecondPoint)
    );
    assert_eq!(f.saturations(), 1);
}

#[test]
fn paper_scenario_fits_fixed_point_at_280_km_and_400_km() {
    // The module docs: in m², PCOV₁₁ across range would reach 3e9 m² at
    // 280 km. With the factor form nothing saturates, even at 400 km with
    // the shortest interval of the envelope (0.05 s) and long coasts.
    for (r0, dt) in [(280_000.0, 1.0), (400_000.0, 0.05), (400_000.0, 20.0)] {
        let noise = RangeAzimuthNoise::<Fix>::paper_bearing_f64(1e4, 1.0).unwrap();
        let mut f = RangeAzimuthFilter::new(noise);
        let c = |v: f64| Fix::try_from_f64(v).unwrap();
        let mut n = Noise(99);
        for k in 0..200 {
            let r = r0 - 50.0 * k as f64 * dt + 100.0 * n.gaussian();
            let b = 0.5 + 0.087 * n.gaussian();
            f.update(c(r), c(b), c(dt)).unwrap();
        }
        for _ in 0..50 {
            f.coast(c(dt)).unwrap();
        }
        assert_eq!(f.saturations(), 0);
        let covariance = f.cross_range_covariance().covariance_f64();
        println!("R0 {r0} dt {dt}: cross-range P11 {:.3e} m2", covariance[0]);
        if dt == 20.0 {
            // 50 coasts of 20 s: P₁₁ = 1.1e10 m², five times what Q32.32
            // holds in m²; its square root (1.05e5 m) is no trouble.
            assert!(covariance[0] > 2f64.powi(31));
        }
    }
}

#[test]
fn cross_range_sigma_floor_keeps_a_target_through_the_sensor_finite() {
    // A target passing within 2 m of the sensor: R·σ_B would be 0.17 m; the
    // 1 m floor keeps the gains defined and nothing saturates.
    let noise = RangeAzimuthNoise::<Fix>::paper_bearing_f64(1.0, 1.0).unwrap();
    assert_eq!(noise.cross_range_sigma(Fix::from_f64_lossy(2.0)), Fix::ONE);
    let mut f = RangeAzimuthFilter::new(noise);
    for k in 0..40 {
        let (x, y): (f64, f64) = (2.0, 100.0 - 5.0 * k as f64);
        let r = Fix::from_f64_lossy(x.hypot(y));
        let b = Fix::from_f64_lossy(x.atan2(y).rem_euclid(TAU));
        f.update(r, b, Fix::ONE).unwrap();
    }
    assert_eq!(f.saturations(), 0);
    let [x, y] = f.position();
    assert!((x.to_f64() - 2.0).abs() < 0.5 && (y.to_f64() + 95.0).abs() < 0.5);
}

/// A track on a noiseless constant-velocity target, after two-point
/// initialisation and some filtering: the prediction is exact.
fn settled<S: Scalar>(range_variance: f64) -> (RangeAzimuthFilter<S>, [f64; 2], [f64; 2]) {
    let noise = RangeAzimuthNoise::<S>::paper_bearing_f64(range_variance, 1.0).unwrap();
    let mut f = RangeAzimuthFilter::new(noise);
    let (p0, v) = ([3000.0, 8000.0], [-4.0, -9.0]);
    let mut p = p0;
    // f32 holds 8.5 km to 1e-3 m; Q32.32's sin/cos error of 1.2e-10 is
    // 1e-6 m at 8.5 km.
    let tol = match S::NAME {
        "f32" => 5e-3,
        "q32" => 1e-5,
        _ => 1e-9,
    };
    for k in 0..60 {
        p = [p0[0] + v[0] * k as f64, p0[1] + v[1] * k as f64];
        let r = S::from_f64_lossy(p[0].hypot(p[1]));
        let b = S::from_f64_lossy(p[0].atan2(p[1]).rem_euclid(TAU));
        let out = f.update(r, b, S::ONE).unwrap();
        // Reading 1 and 2: measurement = prediction gives zero residuals.
        if let RangeAzimuthOutcome::Filtered(inn) = out {
            assert!(inn.range_residual.to_f64().abs() < tol, "{:?}", inn);
            assert!(inn.cross_range_residual.to_f64().abs() < tol, "{:?}", inn);
        }
    }
    (f, p, v)
}

#[test]
fn reading_noiseless_track_is_followed_without_lag() {
    // Reading 2: starting eqs. (12)–(13) from X_{k−1} instead of the
    // prediction would lag by T·Ẋ = 9.8 m per scan here.
    let (f, p, v) = settled::<f64>(225.0);
    let [x, y] = f.position();
    let [vx, vy] = f.velocity();
    assert!((x - p[0]).abs() < 1e-9 && (y - p[1]).abs() < 1e-9);
    assert!((vx - v[0]).abs() < 1e-9 && (vy - v[1]).abs() < 1e-9);
}

#[test]
fn reading_a_range_error_corrects_along_the_line_of_sight_only() {
    // Measurement 50 m beyond the prediction on the same bearing: RESID_R =
    // 50, RESID_CR = 0, and the estimate moves α·50 m along u = (sin B, cos B).
    let (mut f, p, v) = settled::<f64>(225.0);
    let predicted = [p[0] + v[0], p[1] + v[1]];
    let (r, b) = (
        predicted[0].hypot(predicted[1]),
        predicted[0].atan2(predicted[1]),
    );
    let RangeAzimuthOutcome::Filtered(inn) = f.update(r + 50.0, b, 1.0).unwrap() else {
        panic!("not filtering")
    };
    assert!((inn.range_residual - 50.0).abs() < 1e-9);
    assert!(inn.cross_range_residual.abs() < 1e-9);
    let alpha = inn.gains.alpha;
    let moved = [
        f.position()[0] - predicted[0],
        f.position()[1] - predicted[1],
    ];
    assert!((moved[0] - alpha * 50.0 * b.sin()).abs() < 1e-9);
    assert!((moved[1] - alpha * 50.0 * b.cos()).abs() < 1e-9);
    // Reading 3: α comes from σ_R² = 225 m², W1 from VAR = R²σ_B² ≈ 4.6e5 m²
    // (R ≈ 7.8 km). The two-point start makes both covariances proportional
    // to their σ², so the gains differ only as Q = 1 m²/s⁴ makes itself felt:
    // Kalata's tracking index √Q·T²/σ is 1/15 along range (steady α = 0.31)
    // and 1/680 across (steady W1 = 0.052, still on its way down from the
    // least-squares 2(2k−1)/(k(k+1)) = 0.065 at k = 60). With VAR in eq. (9)
    // as printed, α would equal W1.
    assert!(alpha > 3.0 * inn.gains.w1, "{:?}", inn.gains);
    assert!((alpha - 0.31).abs() < 0.03, "{:?}", inn.gains);
}

#[test]
fn reading_a_bearing_error_pulls_the_estimate_towards_the_measurement() {
    // Measurement on the predicted range but 0.05 rad clockwise. With the
    // reading of eq. (11) (RESID_CR = prediction − measurement across the
    // line of sight) the minus sign of eq. (12) moves the estimate towards
    // the measurement, by W1 times the cross-range offset.
    for delta in [0.05, -0.05] {
        let (mut f, p, v) = settled::<f64>(225.0);
        let predicted = [p[0] + v[0], p[1] + v[1]];
        let r = predicted[0].hypot(predicted[1]);
        let b = predicted[0].atan2(predicted[1]) + delta;
        let z = [r * b.sin(), r * b.cos()];
        let RangeAzimuthOutcome::Filtered(inn) = f.update(r, b, 1.0).unwrap() else {
            panic!("not filtering")
        };
        // Across the measured line of sight v = (cos B, −sin B) the
        // prediction R(sin b₀, cos b₀) sits at R sin(b₀ − B) = −R sin δ, the
        // measurement at 0.
        assert!((inn.cross_range_residual + r * delta.sin()).abs() < 1e-6);
        let moved = [
            f.position()[0] - predicted[0],
            f.position()[1] - predicted[1],
        ];
        let towards = [z[0] - predicted[0], z[1] - predicted[1]];
        let dot = moved[0] * towards[0] + moved[1] * towards[1];
        assert!(dot > 0.0, "the update moved away from the measurement");
        let across = -inn.gains.w1 * inn.cross_range_residual;
        let along = inn.gains.alpha * inn.range_residual;
        let expected = [
            along * b.sin() + across * b.cos(),
            along * b.cos() - across * b.sin(),
        ];
        assert!((moved[0] - expected[0]).abs() < 1e-9 && (moved[1] - expected[1]).abs() < 1e-9);
    }
}

#[test]
fn range_rate_and_polar_outputs() {
    // Noiseless closing track: ṙ = (x ẋ + y ẏ)/r, r, B re-synthesised.
    for name in ["f64", "f32", "fixed"] {
        let (r, rdot, az, p, v) = match name {
            "f64" => polar::<f64>(),
            "f32" => polar::<f32>(),
            _ => polar::<Fix>(),
        };
        let r_true = p[0].hypot(p[1]);
        let rdot_true = (p[0] * v[0] + p[1] * v[1]) / r_true;
        // As in `settled`: f32 resolves 8 km to 1e-3 m, Q32.32's sin/cos
        // error is 1e-6 m there.
        let tol = match name {
            "f32" => 1e-2,
            "fixed" => 1e-5,
            _ => 1e-9,
        };
        assert!((r - r_true).abs() < tol, "{name}: r {r} vs {r_true}");
        assert!(
            (rdot - rdot_true).abs() < tol,
            "{name}: rdot {rdot} vs {rdot_true}"
        );
        assert!(
            (az - p[0].atan2(p[1]).rem_euclid(TAU)).abs() < 1e-6,
            "{name}: {az}"
        );
    }
    fn polar<S: Scalar>() -> (f64, f64, f64, [f64; 2], [f64; 2]) {
        let (f, p, v) = settled::<S>(225.0);
        (
            f.range().to_f64(),
            f.range_rate().to_f64(),
            f.azimuth().to_f64(),
            p,
            v,
        )
    }
}

#[test]
fn noise_configuration_is_validated() {
    use abtrack::filter::range_azimuth::NoiseError;
    assert!(RangeAzimuthNoise::<Fix>::new_f64(1e4, PAPER_BEARING_VARIANCE, 0.0).is_ok());
    assert_eq!(
        RangeAzimuthNoise::<f64>::new_f64(0.0, 1e-3, 1.0),
        Err(NoiseError::OutOfRange)
    );
    assert_eq!(
        RangeAzimuthNoise::<f64>::new_f64(1.0, -1e-3, 1.0),
        Err(NoiseError::OutOfRange)
    );
    assert_eq!(
        RangeAzimuthNoise::<f32>::new_f64(1.0, 1e-3, -1.0),
        Err(NoiseError::OutOfRange)
    );
    assert_eq!(
        RangeAzimuthNoise::<Fix>::new_f64(f64::NAN, 1e-3, 1.0),
        Err(NoiseError::NotFinite)
    );
    assert_eq!(
        RangeAzimuthNoise::<Fix>::new_f64(1e12, 1e-3, 1.0),
        Err(NoiseError::NotFinite)
    );
}
