//! The altitude tracker (`abtrack::filter::altitude`): Kalata gains from
//! the quantisation noise, tracking quantised Mode C / Mode S reports, and
//! non-reporting intruders, in f64, f32 and Q32.32.

use abtrack::design::kalata_gains;
use abtrack::filter::altitude::{
    AltitudeQuantum, AltitudeStatus, AltitudeTracker, AltitudeTrackerConfig, DEFAULT_MANOEUVRE_G,
    STANDARD_GRAVITY_FT_PER_S2,
};
use abtrack::{FilterError, Fix, Scalar};

fn tol<S: Scalar>() -> f64 {
    match S::NAME {
        "f32" => 1e-6,
        _ => 1e-9,
    }
}

fn gains_golden<S: Scalar>() {
    // Mode C: σ_v = 100/√12 = 28.867513 ft; σ_a = 0.1 g = 3.2174049 ft/s²;
    // λ = 3.2174049/28.867513 = 0.1114542.
    // λ² + 8λ = 0.0124220 + 0.8916334 = 0.9040554, √ = 0.9508183.
    // α = −(0.9040554 − 4.1114542·0.9508183)/8 = −(0.9040554 − 3.9092458)/8
    //   = 0.3756488;
    // β = (0.0124220 + 0.4458167 − 0.1114542·0.9508183)/4
    //   = (0.4582387 − 0.1059727)/4 = 0.0880665.
    let c = AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC).unwrap();
    let (a, b) = (c.gains().alpha().to_f64(), c.gains().beta().to_f64());
    assert!((c.tracking_index().to_f64() - 0.1114542).abs() < 1e-6);
    assert!((a - 0.3756488).abs() < 1e-6, "{}: alpha {a}", S::NAME);
    assert!((b - 0.0880665).abs() < 1e-6, "{}: beta {b}", S::NAME);
    // Mode S (25 ft): σ_v = 7.216878 ft, λ = 0.4458167; λ² + 8λ = 0.1987525
    // + 3.5665336 = 3.7652861, √ = 1.9404345;
    // α = −(3.7652861 − 4.4458167·1.9404345)/8 = −(3.7652861 − 8.6268162)/8
    //   = 0.6076913;
    // β = (0.1987525 + 1.7832668 − 0.4458167·1.9404345)/4
    //   = (1.9820193 − 0.8650780)/4 = 0.2792353.
    let c = AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeS25).unwrap();
    let (a, b) = (c.gains().alpha().to_f64(), c.gains().beta().to_f64());
    assert!((a - 0.6076913).abs() < 1e-6, "{}: alpha {a}", S::NAME);
    assert!((b - 0.2792353).abs() < 1e-6, "{}: beta {b}", S::NAME);
}

#[test]
fn kalata_gains_golden_values() {
    gains_golden::<f64>();
    gains_golden::<f32>();
    gains_golden::<Fix>();
    assert!((STANDARD_GRAVITY_FT_PER_S2 - 32.174049).abs() < 1e-6);
    assert_eq!(DEFAULT_MANOEUVRE_G, 0.1);
}

#[test]
fn kalata_gains_satisfy_the_tracking_index_identity() {
    // λ² = β²/(1 − α) (Kalata), over four decades of λ, and inside the
    // stability triangle (checked by Gains::alpha_beta itself).
    let mut l = 1e-3;
    while l < 30.0 {
        let g = kalata_gains(l).unwrap();
        let (a, b) = (g.alpha(), g.beta());
        // Forming 1 − α here costs ε/(1 − α) of relative accuracy (1 − α is
        // 0.005 at λ = 24); the gains themselves have no cancellation.
        let e = ((b * b / (1.0 - a)) - l * l).abs() / (l * l);
        assert!(e <= 8.0 * f64::EPSILON / (1.0 - a), "λ = {l}: {e:e}");
        assert!(a > 0.0 && a < 1.0 && b > 0.0);
        l *= 1.37;
    }
    assert!(kalata_gains(0.0).is_err());
    assert!(kalata_gains(-1.0).is_err());
    assert!(kalata_gains(f64::NAN).is_err());
}

/// Reported altitude: the true altitude rounded to the nearest quantum.
fn report(altitude: f64, quantum: f64) -> f64 {
    (altitude / quantum).round() * quantum
}

fn climbing_intruder<S: Scalar>(quantum: AltitudeQuantum) -> (f64, f64) {
    let config = AltitudeTrackerConfig::<S>::default_for(quantum).unwrap();
    let mut t = AltitudeTracker::new(config);
    let q = quantum.feet();
    let (mut worst_rate, mut worst_alt) = (0.0f64, 0.0f64);
    // 8000 ft climbing at 1400 ft/min (23.3 ft/s, not a multiple of either
    // quantum per second), one report a second.
    let rate = 1400.0 / 60.0;
    for k in 0..120 {
        let truth = 8000.0 + rate * k as f64;
        let z = S::from_f64_lossy(report(truth, q));
        t.scan(Some(z), S::ONE).unwrap();
        if k >= 30 {
            let e = t.estimate().unwrap();
            worst_rate = worst_rate.max((e.vertical_rate_ft_per_s.to_f64() - rate).abs());
            worst_alt = worst_alt.max((e.altitude_ft.to_f64() - truth).abs());
        }
    }
    assert_eq!(t.status(), AltitudeStatus::Tracking);
    (worst_rate, worst_alt)
}

#[test]
fn climbing_intruder_rate_within_the_quantisation_noise() {
    // The standard αβ velocity variance-reduction ratio
    // 2β²/(T²α(4 − 2α − β)) with σ_v = q/√12 gives
    // Mode C: 2·0.0880665²/(0.3756488·3.1606359) = 0.013065, σ_rate =
    //   0.11430·28.868 = 3.30 ft/s;
    // Mode S: 2·0.2792353²/(0.6076913·2.5053822) = 0.102427, σ_rate =
    //   0.32004·7.2169 = 2.31 ft/s.
    // After 30 s of settling the rate error stays within 3.5σ, the altitude
    // error within one quantum (half a quantum of reporting error plus the
    // smoothing).
    for (quantum, sigma_rate) in [
        (AltitudeQuantum::ModeC, 3.30),
        (AltitudeQuantum::ModeS25, 2.31),
    ] {
        for (name, (rate, alt)) in [
            ("f64", climbing_intruder::<f64>(quantum)),
            ("f32", climbing_intruder::<f32>(quantum)),
            ("fixed", climbing_intruder::<Fix>(quantum)),
        ] {
            println!("{name} {quantum:?}: rate error {rate:.2} ft/s, altitude error {alt:.1} ft");
            assert!(
                rate <= 3.5 * sigma_rate,
                "{name} {quantum:?}: rate error {rate}"
            );
            assert!(
                alt <= quantum.feet(),
                "{name} {quantum:?}: altitude error {alt}"
            );
        }
    }
}

fn level_intruder<S: Scalar>() {
    // True 8040 ft, Mode C reports 8000: the estimate converges to the
    // report (a constant bias of 40 ft ≤ q/2) with zero vertical rate.
    let mut t = AltitudeTracker::new(
        AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC).unwrap(),
    );
    for _ in 0..200 {
        t.scan(Some(S::from_f64_lossy(report(8040.0, 100.0))), S::ONE)
            .unwrap();
    }
    let e = t.estimate().unwrap();
    assert!((e.altitude_ft.to_f64() - 8000.0).abs() < tol::<S>() * 8000.0);
    assert!(e.vertical_rate_ft_per_s.to_f64().abs() < tol::<S>() * 100.0);
}

#[test]
fn level_intruder_settles_on_its_report() {
    level_intruder::<f64>();
    level_intruder::<f32>();
    level_intruder::<Fix>();
}

fn missing_altitude<S: Scalar>() {
    let one = S::ONE;
    let config = AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeS25).unwrap();
    let mut t = AltitudeTracker::new(config);
    // A non-reporting intruder is a valid, lasting state.
    for _ in 0..10 {
        assert_eq!(t.scan(None, one), Ok(AltitudeStatus::NotReporting));
    }
    assert_eq!(t.estimate(), None);
    // Reports start: one report gives an altitude, rate zero.
    assert_eq!(
        t.scan(Some(S::from_f64_lossy(5000.0)), one),
        Ok(AltitudeStatus::OneReport)
    );
    let e = t.estimate().unwrap();
    assert_eq!(e.altitude_ft, S::from_f64_lossy(5000.0));
    assert_eq!(e.vertical_rate_ft_per_s, S::ZERO);
    // Climbing 10 ft/s (reports 5000, 5000+10k... quantised to 25 ft).
    for k in 1..40 {
        let z = report(5000.0 + 10.0 * k as f64, 25.0);
        assert_eq!(
            t.scan(Some(S::from_f64_lossy(z)), one),
            Ok(AltitudeStatus::Tracking)
        );
    }
    let before = t.estimate().unwrap();
    // Six missing reports: coasted with the vertical rate.
    for k in 1..=6 {
        assert_eq!(t.scan(None, one), Ok(AltitudeStatus::Tracking));
        assert_eq!(t.since_last_report(), S::from_f64_lossy(k as f64));
    }
    let coasted = t.estimate().unwrap();
    let expected = before.altitude_ft.to_f64() + 6.0 * before.vertical_rate_ft_per_s.to_f64();
    // f32 holds 5.5e3 ft to 4.9e-4 ft; six coasts round six times.
    let tolerance = if S::NAME == "f32" { 5e-3 } else { 1e-6 };
    assert!(
        (coasted.altitude_ft.to_f64() - expected).abs() < tolerance,
        "{}: {coasted:?} vs {expected}",
        S::NAME
    );
    // The seventh exceeds the 6 s coast: the intruder is non-reporting.
    assert_eq!(t.scan(None, one), Ok(AltitudeStatus::NotReporting));
    assert_eq!(t.estimate(), None);
    // Invalid input changes nothing.
    let snapshot = t;
    let bad = S::from_f64_lossy(f64::NAN);
    assert_eq!(t.scan(Some(bad), one), Err(FilterError::InvalidMeasurement));
    assert_eq!(t.scan(None, S::ZERO), Err(FilterError::InvalidInterval));
    assert_eq!(
        t.scan(Some(S::from_f64_lossy(5000.0)), -one),
        Err(FilterError::InvalidInterval)
    );
    assert_eq!(t, snapshot);
}

#[test]
fn missing_altitude_is_a_valid_state() {
    missing_altitude::<f64>();
    missing_altitude::<f32>();
    missing_altitude::<Fix>();
}

#[test]
fn configuration_refuses_bad_interval_manoeuvre_and_coast() {
    use abtrack::filter::altitude::AltitudeConfigError;
    let q = AltitudeQuantum::ModeC;
    // A negative interval would give a valid λ (T² > 0); it must be refused.
    assert_eq!(
        AltitudeTrackerConfig::<f64>::new(q, 3.22, -1.0, 6.0),
        Err(AltitudeConfigError::IntervalNotPositive)
    );
    assert_eq!(
        AltitudeTrackerConfig::<f64>::new(q, 3.22, 0.0, 6.0),
        Err(AltitudeConfigError::IntervalNotPositive)
    );
    assert_eq!(
        AltitudeTrackerConfig::<f64>::new(q, -3.22, 1.0, 6.0),
        Err(AltitudeConfigError::ManoeuvreNotPositive)
    );
    assert_eq!(
        AltitudeTrackerConfig::<Fix>::new(q, f64::NAN, 1.0, 6.0),
        Err(AltitudeConfigError::ManoeuvreNotPositive)
    );
    assert_eq!(
        AltitudeTrackerConfig::<f32>::new(q, 3.22, 1.0, -1.0),
        Err(AltitudeConfigError::InvalidCoast)
    );
    assert!(AltitudeTrackerConfig::<Fix>::new(q, 3.22, 1.0, 0.0).is_ok());
}
