//! Contract of the filters on bad input and overflow: an invalid measurement
//! or interval is refused with the state left bit for bit as it was; an update
//! that saturates is refused, counted, and leaves the state as it was; a 2-D
//! or 3-D update applies to every axis or to none.

use abtrack::filter::{Cartesian, Gains, KinematicFilter, Phase};
use abtrack::num::Quantity;
use abtrack::{FilterError, Fix, Scalar};

/// Every field that defines the filter except the saturation counter, as raw
/// bits (so that −0.0 vs 0.0 could not hide behind `==`) and through `Debug`,
/// which also shows the private fields.
fn snapshot<S: Scalar, const O: usize>(f: &KinematicFilter<S, O>) -> String {
    let debug = format!("{f:?}");
    let without_counter = debug.split("saturations").next().unwrap_or("").to_string();
    format!(
        "{:?} {:?} {:?} {:?} {:?} {}",
        f.phase(),
        f.position().to_f64().to_bits(),
        f.velocity().to_f64().to_bits(),
        f.acceleration().to_f64().to_bits(),
        f.last_innovation().map(|i| (
            i.predicted.to_f64().to_bits(),
            i.residual.to_f64().to_bits()
        )),
        without_counter
    )
}

/// A filter in each phase: empty, one point, tracking (with an innovation).
fn filters<S: Scalar, const O: usize>(g: &Gains<S>) -> Vec<KinematicFilter<S, O>> {
    let c = |v: f64| S::try_from_f64(v).unwrap();
    let mut out = vec![KinematicFilter::<S, O>::new()];
    let mut f = KinematicFilter::<S, O>::new();
    f.update(c(100.0), c(1.0), g).unwrap();
    out.push(f);
    f.update(c(110.0), c(1.0), g).unwrap();
    f.update(c(121.0), c(1.0), g).unwrap();
    out.push(f);
    out
}

fn refuses_bad_input<S: Scalar, const O: usize>(g: Gains<S>, bad_values: &[S]) {
    let c = |v: f64| S::try_from_f64(v).unwrap();
    for f in filters::<S, O>(&g) {
        let before = snapshot(&f);
        let count = f.saturations();
        for &bad in bad_values {
            let mut t = f;
            assert_eq!(
                t.update(bad, c(1.0), &g),
                Err(FilterError::InvalidMeasurement)
            );
            assert_eq!(snapshot(&t), before);
            assert_eq!(t.update(c(1.0), bad, &g), Err(FilterError::InvalidInterval));
            assert_eq!(snapshot(&t), before);
            assert_eq!(t.coast(bad), Err(FilterError::InvalidInterval));
            assert_eq!(snapshot(&t), before);
            assert_eq!(t.predict(bad), Err(FilterError::InvalidInterval));
            assert_eq!(t.saturations(), count);
        }
        for dt in [S::ZERO, -S::ONE] {
            let mut t = f;
            assert_eq!(t.update(c(1.0), dt, &g), Err(FilterError::InvalidInterval));
            assert_eq!(t.coast(dt), Err(FilterError::InvalidInterval));
            assert_eq!(snapshot(&t), before);
        }
    }
}

#[test]
fn invalid_measurement_or_interval_leaves_state_untouched() {
    let floats64 = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
    refuses_bad_input::<f64, 2>(Gains::alpha_beta(0.5, 0.3).unwrap(), &floats64);
    refuses_bad_input::<f64, 3>(Gains::alpha_beta_gamma(0.5, 0.3, 0.1).unwrap(), &floats64);
    let floats32 = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];
    refuses_bad_input::<f32, 2>(Gains::alpha_beta(0.5, 0.3).unwrap(), &floats32);
    refuses_bad_input::<f32, 3>(Gains::alpha_beta_gamma(0.5, 0.3, 0.1).unwrap(), &floats32);
    let fixes = [Fix::MAX, Fix::MIN];
    refuses_bad_input::<Fix, 2>(Gains::alpha_beta_f64(0.5, 0.3).unwrap(), &fixes);
    refuses_bad_input::<Fix, 3>(Gains::alpha_beta_gamma_f64(0.5, 0.3, 0.1).unwrap(), &fixes);
}

#[test]
fn saturating_update_is_refused_and_counted() {
    let g = Gains::<Fix>::alpha_beta_f64(0.5, 0.3).unwrap();
    let c = |v: f64| Fix::try_from_f64(v).unwrap();
    // Tracking near the top of the Q32.32 range at high speed: the prediction
    // x + T·v overflows.
    let mut f = KinematicFilter::<Fix, 2>::from_state(c(2.0e9), c(1.0e8), Fix::ZERO).unwrap();
    let before = snapshot(&f);
    assert_eq!(f.update(c(2.0e9), c(2.0), &g), Err(FilterError::Saturated));
    assert_eq!(f.saturations(), 1);
    assert_eq!(f.coast(c(2.0)), Err(FilterError::Saturated));
    assert_eq!(f.saturations(), 2);
    assert_eq!(f.predict(c(2.0)), Err(FilterError::Saturated));
    // Only the counter moved.
    assert_eq!(snapshot(&f), before);
    assert_eq!((f.position(), f.velocity()), (c(2.0e9), c(1.0e8)));
    // A short interval still works afterwards.
    assert!(f.update(c(2.0e9), c(0.01), &g).is_ok());

    // Second point: (z₂ − z₁)/T overflows for a tiny T.
    let mut f = KinematicFilter::<Fix, 3>::new();
    let g3 = Gains::<Fix>::alpha_beta_gamma_f64(0.5, 0.3, 0.1).unwrap();
    f.update(c(-2.0e9), c(1.0), &g3).unwrap();
    assert_eq!(
        f.update(c(2.0e9), c(0.001), &g3),
        Err(FilterError::Saturated)
    );
    assert_eq!(
        (f.phase(), f.saturations(), f.position()),
        (Phase::OnePoint, 1, c(-2.0e9))
    );

    // f32 overflows to infinity: refused and counted the same way.
    let g32 = Gains::<f32>::alpha_beta(0.5, 0.3).unwrap();
    let mut f = KinematicFilter::<f32, 2>::from_state(3.0e38, 1.0e38, 0.0).unwrap();
    assert_eq!(f.update(3.0e38, 20.0, &g32), Err(FilterError::Saturated));
    assert_eq!(
        (f.saturations(), f.position(), f.velocity()),
        (1, 3.0e38, 1.0e38)
    );
}

#[test]
fn cartesian_update_is_all_or_nothing() {
    let g = Gains::<f64>::alpha_beta(0.5, 0.3).unwrap();
    let mut t = Cartesian::<f64, 2, 3>::new();
    t.update([1.0, 2.0, 3.0], 1.0, &g).unwrap();
    t.update([2.0, 4.0, 6.0], 1.0, &g).unwrap();
    let before = t;
    // The third axis is bad: the first two must not move either.
    assert_eq!(
        t.update([3.0, 6.0, f64::NAN], 1.0, &g),
        Err(FilterError::InvalidMeasurement)
    );
    assert_eq!(t, before);
    assert_eq!(
        t.update([3.0, 6.0, 9.0], -1.0, &g),
        Err(FilterError::InvalidInterval)
    );
    assert_eq!(t, before);
    assert_eq!(t.coast(f64::NAN), Err(FilterError::InvalidInterval));
    assert_eq!(t, before);
    assert!(t.update([3.0, 6.0, 9.0], 1.0, &g).is_ok());
    assert_eq!(t.position(), [3.0, 6.0, 9.0]);

    // A saturating axis: refused, counted on that axis, nothing else moves.
    let gf = Gains::<Fix>::alpha_beta_f64(0.5, 0.3).unwrap();
    let c = |v: f64| Fix::try_from_f64(v).unwrap();
    let mut t = Cartesian::<Fix, 2, 2>::new();
    t.update([c(0.0), c(2.0e9)], c(1.0), &gf).unwrap();
    // v_y = (−2e9 − 2e9)/1 does not fit: the update is refused on both axes.
    assert_eq!(
        t.update([c(1.0), c(-2.0e9)], c(1.0), &gf),
        Err(FilterError::Saturated)
    );
    assert_eq!(t.saturations(), 1);
    assert_eq!(t.phase(), Phase::OnePoint);
    assert_eq!(t.position(), [c(0.0), c(2.0e9)]);
}

/// An interval whose square leaves Q32.32 (T = 7·10⁴ s, T²/2 > 2³¹) refuses
/// the per-axis update as saturated and counts it, as the shared-gains
/// update and the coast do.
#[test]
fn a_saturated_interval_is_counted_by_every_update() {
    let c = |v: f64| Fix::try_from_f64(v).unwrap();
    let g = Gains::<Fix>::alpha_beta_f64(0.5, 0.3).unwrap();
    let mut f = Cartesian::<Fix, 2, 2>::new();
    f.update([c(0.0), c(0.0)], c(1.0), &g).unwrap();
    f.update([c(10.0), c(0.0)], c(1.0), &g).unwrap();
    let long = c(7.0e4);
    assert_eq!(
        f.update([c(20.0), c(0.0)], long, &g),
        Err(FilterError::Saturated)
    );
    assert_eq!(f.saturations(), 1);
    assert_eq!(
        f.update_per_axis([c(20.0), c(0.0)], long, &[g, g]),
        Err(FilterError::Saturated)
    );
    assert_eq!(f.saturations(), 2);
    assert_eq!(f.coast(long), Err(FilterError::Saturated));
    assert_eq!(f.saturations(), 3);
}
