//! Gate sizes and the error covariance behind them: hand-computed values and
//! Tenne & Singh's noise ratio.

use super::support;
use abtrack::num::Quantity;

use abtrack::num::fixed32::Fixed32;
use abtrack::track::assign::MAX_COST;
use abtrack::track::{
    hypot, ErrorVariance, FixedGainStep, FixedGainTrack, Gate, GateRegion, Measurement,
    Observation, ScanInterval, TrackFilter,
};
use abtrack::{Fix, Gains, Numeric};
use support::{cart, q, s};

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn two_point_covariance_by_hand() {
    // x = z₂, v = z₂ − z₁ over T = 1: predicted x = 2z₂ − z₁ has variance
    // 4 + 1 = 5 (in units of σ²).
    let p = ErrorVariance::<f64>::after_two_points(1.0);
    assert_eq!((p.p11, p.p12, p.p22), (1.0, 1.0, 2.0));
    let q = p.predicted(1.0);
    assert_eq!((q.p11, q.p12, q.p22), (5.0, 3.0, 2.0));
    // Update with α = 0.5, β = 0.2, T = 1 (k1 = 0.5, k2 = 0.2):
    // p11 = (1−k1)²·5 + k1² = 1.25 + 0.25 = 1.5
    // p12 = (1−k1)(3 − k2·5) + k1·k2 = 0.5·2 + 0.1 = 1.1
    // p22 = 2 − 2·k2·3 + k2²·(5 + 1) = 2 − 1.2 + 0.24 = 1.04
    let u = q.updated(0.5, 0.2, 1.0);
    assert!(close(u.p11, 1.5, 1e-12));
    assert!(close(u.p12, 1.1, 1e-12));
    assert!(close(u.p22, 1.04, 1e-12));
    // α = β = 1 reproduces the two-point estimator exactly: a fixed point.
    let w = q.updated(1.0, 1.0, 1.0);
    assert!(close(w.p11, 1.0, 1e-12) && close(w.p12, 1.0, 1e-12) && close(w.p22, 2.0, 1e-12));
}

/// Tenne & Singh eq. (13): ρ² = (2α² + αβ + 2β) / (α(4 − β − 2α)).
fn tenne_singh_13(a: f64, b: f64) -> f64 {
    (2.0 * a * a + a * b + 2.0 * b) / (a * (4.0 - b - 2.0 * a))
}

#[test]
fn steady_state_matches_tenne_singh_eq13() {
    // Hand value for α = 0.5, β = 0.2: (0.5 + 0.1 + 0.4)/(0.5·2.8) = 1/1.4.
    assert!(close(tenne_singh_13(0.5, 0.2), 1.0 / 1.4, 1e-15));
    for &(a, b) in &[
        (0.5, 0.2),
        (0.3, 0.05),
        (1.0, 1.0),
        (0.8, 0.4),
        (0.1, 0.0053),
    ] {
        for &t in &[1.0, 0.5, 4.0] {
            let mut p = ErrorVariance::<f64>::after_two_points(t);
            for _ in 0..20_000 {
                p = p.predicted(t).updated(a, b, t);
            }
            let predicted = p.predicted(t).p11;
            assert!(
                close(predicted, tenne_singh_13(a, b), 1e-9),
                "α={a} β={b} T={t}: {predicted} vs {}",
                tenne_singh_13(a, b)
            );
        }
    }
}

/// The fixed-gain tracks' step for an interval of `ms`.
fn step<S: Numeric>(gains: &Gains<S>, ms: u32) -> FixedGainStep<S> {
    FixedGainTrack::step(gains, &ScanInterval::from_ms(ms).unwrap()).unwrap()
}

/// A stationary fixed-gain track at (3000, 4000) started from two points 1 s
/// apart, plus its prediction 1 s ahead.
fn stationary<S: Numeric>(
    gains: &Gains<S>,
) -> (FixedGainTrack<S>, abtrack::track::PredictedState<S>) {
    let z = Observation::new(cart::<S>(3000.0, 4000.0)).unwrap();
    let mut f = FixedGainTrack::empty(gains);
    let second = step(gains, 1000);
    f.update(gains, &z, &second).unwrap();
    f.update(gains, &z, &second).unwrap();
    let p = f.predict(gains, &second).unwrap();
    (f, p)
}

#[test]
fn uncertainty_gate_radius_by_hand() {
    let gains = Gains::<f64>::alpha_beta(0.5, 0.2).unwrap();
    let second = step(&gains, 1000);
    let (mut f, p) = stationary(&gains);
    // p = 5 one second after initiation; σ = 5, G = 6, a_max = 4:
    // r = 5·√(6·(5 + 1)) + ½·4·1² = 30 + 2 = 32.
    let gate = Gate::uncertainty(5.0, 6.0, 4.0).unwrap();
    let region = f.gate_region(&gains, &p, &second, &gate).unwrap();
    assert_eq!(region.radius(), 32.0);
    // After one filtered update p⁻ = 1.5 + 2·1.1 + 1.04 = 4.74 (see above):
    // r = 5·√(6·5.74) = 5·√34.44 = 29.3428...
    let z = Observation::new(Measurement::Cartesian {
        x: 3000.0,
        y: 4000.0,
    })
    .unwrap();
    f.update(&gains, &z, &second).unwrap();
    let gate = Gate::uncertainty(5.0, 6.0, 0.0).unwrap();
    let p = f.predict(&gains, &second).unwrap();
    let r = f.gate_region(&gains, &p, &second, &gate).unwrap().radius();
    assert!(close(r, 5.0 * 34.44f64.sqrt(), 1e-9), "{r}");
    // Coasting widens it: one coast of 1 s, then predict 1 s:
    // P after update (1.5, 1.1, 1.04) → coast → (4.74, 2.14, 1.04)
    // → predicted p11 = 4.74 + 2·2.14 + 1.04 = 10.06; r = 5·√(6·11.06).
    f.coast(&gains, &second).unwrap();
    let p = f.predict(&gains, &second).unwrap();
    let r = f.gate_region(&gains, &p, &second, &gate).unwrap().radius();
    assert!(close(r, 5.0 * (6.0f64 * 11.06).sqrt(), 1e-9), "{r}");
}

#[test]
fn wave_gate_radius_by_hand() {
    // Li et al. eqs. (11)–(12): ρ = |(3000, 4000)| = 5000 m, Δρ = 30 m,
    // Δθ = 0.008 rad → ρΔθ = 40, √(30² + 40²) = 50; α = 0.5 → λ = √0.5;
    // κ = 2: r = 2·√0.5·50 = 70.7107 m.
    let expected = 2.0 * 0.5f64.sqrt() * 50.0;
    let gains = Gains::<f64>::alpha_beta(0.5, 0.2).unwrap();
    let (f, p) = stationary(&gains);
    let gate = Gate::wave(30.0, 0.008, 2.0).unwrap();
    let r = f
        .gate_region(&gains, &p, &step(&gains, 1000), &gate)
        .unwrap()
        .radius();
    assert!(close(r, expected, 1e-9), "{r}");
    // The same in Q32.32, f32 and the fast fixed point.
    fn wave<S: Numeric>(tolerance: f64) {
        let expected = 2.0 * 0.5f64.sqrt() * 50.0;
        let gains = Gains::<S>::alpha_beta_f64(0.5, 0.2).unwrap();
        let (f, p) = stationary(&gains);
        let gate = Gate::<S>::wave(q(30.0), q(0.008), q(2.0)).unwrap();
        let r = f
            .gate_region(&gains, &p, &step(&gains, 1000), &gate)
            .unwrap()
            .radius();
        assert!(
            close(abtrack::num::Quantity::to_f64(r), expected, tolerance),
            "{r:?}"
        );
    }
    wave::<Fix>(1e-6);
    wave::<f32>(1e-3);
    wave::<Fixed32>(1e-3);
}

#[test]
fn gate_costs_and_edges() {
    // Radius 8: its inverse 0.125 is exact in binary, so the edge is exact.
    let region = GateRegion::<f64>::circle([100.0, 200.0], 8.0).unwrap();
    let at =
        |x: f64, y: f64| region.cost(&Observation::new(Measurement::Cartesian { x, y }).unwrap());
    assert_eq!(at(100.0, 200.0), Some(0));
    // d = r/2: (1/2)²·65534 = 16383.5 → rounds to 16384.
    assert_eq!(at(104.0, 200.0), Some(16384));
    assert_eq!(at(100.0, 196.0), Some(16384));
    // On the edge: cost MAX_COST; just beyond: outside.
    assert_eq!(at(108.0, 200.0), Some(MAX_COST));
    assert_eq!(at(108.001, 200.0), None);
    assert_eq!(at(100.0, 191.999), None);
    // Inside the bounding box but outside the circle: (6, 6) has d = 8.49.
    assert_eq!(at(106.0, 206.0), None);
    assert!(GateRegion::<f64>::circle([0.0, 0.0], 0.0).is_none());
    assert!(GateRegion::<f64>::circle([0.0, 0.0], f64::NAN).is_none());
    assert!(GateRegion::<f64>::circle([f64::INFINITY, 0.0], 1.0).is_none());
}

#[test]
fn far_measurements_do_not_saturate_fixed_point() {
    // 800 km apart: squaring would exceed Q32.32's 2.1e9; the gate test
    // compares per axis first.
    let region = GateRegion::<Fix>::circle([s(-400_000.0), s(0.0)], s(100.0)).unwrap();
    let far = Observation::new(Measurement::Cartesian {
        x: s(400_000.0),
        y: s(0.0),
    })
    .unwrap();
    assert_eq!(region.cost(&far), None);
    let h = hypot(s::<Fix>(400_000.0), s(300_000.0));
    assert!(h.is_valid());
    assert!(close(h.to_f64(), 500_000.0, 1e-3));
}

#[test]
fn bad_gates_refused() {
    type G = Gate<f64>;
    assert!(G::uncertainty(0.0, 9.0, 0.0).is_err());
    assert!(G::uncertainty(5.0, -1.0, 0.0).is_err());
    assert!(G::uncertainty(5.0, 9.0, -1.0).is_err());
    assert!(G::uncertainty(f64::NAN, 9.0, 0.0).is_err());
    assert!(G::wave(0.0, 0.0, 2.0).is_err());
    assert!(G::wave(1.0, 0.0, 0.0).is_err());
    assert!(G::Wave {
        range_sigma: -1.0,
        bearing_sigma: 0.1,
        multiple: 1.0
    }
    .validated()
    .is_err());
}

/// `GateRegion::is_larger_than_circle` (the design's rule 7): a circle by
/// its radius, formed from it or from its square; a range/azimuth window
/// by its area π·half_range·half_cross, in each number system.
#[test]
fn regions_are_compared_with_a_circle_by_radius_and_by_area() {
    fn check<S: Numeric>() {
        let l = |v: f64| S::Length::try_from_f64(v).unwrap();
        let circle = GateRegion::<S>::circle([l(100.0), l(200.0)], l(800.0)).unwrap();
        assert!(circle.is_larger_than_circle(l(790.0)));
        assert!(!circle.is_larger_than_circle(l(810.0)));
        // σ 100 m, factor 16: radius 400 m.
        let factor = S::Ratio::try_from_f64(16.0).unwrap();
        let scaled = GateRegion::<S>::scaled_circle([l(0.0), l(0.0)], l(100.0), factor).unwrap();
        assert!(scaled.is_larger_than_circle(l(395.0)));
        assert!(!scaled.is_larger_than_circle(l(405.0)));
        // 10 km out, 200 m in range and 2 km across: the area of a circle
        // of radius √(200·2000) = 632.5 m.
        let window = GateRegion::<S>::polar([l(6000.0), l(8000.0)], l(200.0), l(2000.0)).unwrap();
        assert!(window.is_larger_than_circle(l(625.0)));
        assert!(!window.is_larger_than_circle(l(640.0)));
        // 300 km out, 10 km by 3 km (radius √(10⁴·3000) = 5477 m): products
        // beyond Q32.32's 2³¹ m², which its form avoids.
        let far = GateRegion::<S>::polar([l(300_000.0), l(0.0)], l(10_000.0), l(3000.0)).unwrap();
        assert!(far.is_larger_than_circle(l(5300.0)));
        assert!(!far.is_larger_than_circle(l(5600.0)));
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
    check::<Fixed32>();
}

/// A tentative track's gate is held to the gate the design's rule 4 counts
/// clutter in (σ·√(2G·(1 + m + m²)) + m²·½·a_max·T², m the scans since its
/// last hit), in every number system; a confirmed track keeps its filter's.
/// The design's radar with a 12 s scan and no clutter (no rule 7, which
/// would end the confirmed track): after a miss, the default filter's gate
/// (its covariance with the starting manoeuvre level over 24 s) is far
/// wider than that.
#[test]
fn a_tentative_tracks_gate_is_held_to_the_two_point_gate() {
    fn check<S: Numeric>() {
        use abtrack::track::defaults::{DefaultCartesianTrack, TrackerDesign};
        use abtrack::track::{Association, TrackTable};
        let design = TrackerDesign {
            scan_period: 12.0,
            clutter_density: 0.0,
            ..TrackerDesign::NOMINAL_RADAR
        };
        let derived = design.derive().unwrap();
        let (sigma, g, a, t) = (20.0, derived.gate_threshold, 5.66, 12.0);
        let cap = |m: f64| sigma * (2.0 * g * (1.0 + m + m * m)).sqrt() + m * m * 0.5 * a * t * t;
        for confirmed in [false, true] {
            let config = design.cartesian_config::<S>().unwrap();
            let config = if confirmed {
                config.with_confirmation(1, 1).unwrap()
            } else {
                config
            };
            // A target at 100 m/s along x, seen at 0 and 12 s, missed at
            // 24 s; at 36 s, a plot off its prediction (3600 m, 0) by d.
            let started = || {
                let mut table: TrackTable<S, DefaultCartesianTrack<S>, 4, 4> = TrackTable::new();
                let mut codes = [Association::OutsideGates; 1];
                for (ms, x) in [(0u32, 0.0), (12_000, 1200.0)] {
                    table
                        .scan(&config, ms, &[cart(x, 0.0)], &mut codes)
                        .unwrap();
                }
                assert!(matches!(codes[0], Association::Started(_)), "{codes:?}");
                table.scan(&config, 24_000, &[], &mut codes).unwrap();
                table
            };
            let table = started();
            let track = table.tracks().next().unwrap();
            assert_eq!(track.is_confirmed(), confirmed);
            let interval = ScanInterval::<S>::from_ms(12_000).unwrap();
            let step =
                <DefaultCartesianTrack<S> as TrackFilter<S>>::step(config.params(), &interval)
                    .unwrap();
            let predicted = TrackFilter::predict(track.filter(), config.params(), &step).unwrap();
            let own = TrackFilter::gate_region(
                track.filter(),
                config.params(),
                &predicted,
                &step,
                config.gate(),
            )
            .unwrap()
            .radius();
            let own = Quantity::to_f64(own);
            println!("{} confirmed {confirmed}: the filter's own gate {own:.0} m, the two-point gate {:.0} m", S::NAME, cap(2.0));
            // The filter's own gate is the wider by far: the test is of the
            // cap, not of the filter.
            assert!(
                own > 1.2 * cap(2.0),
                "{} own {own} cap {}",
                S::NAME,
                cap(2.0)
            );
            let predicted_x = Quantity::to_f64(predicted.position[0]);
            for (d, inside_cap) in [(0.95 * cap(2.0), true), (1.05 * cap(2.0), false)] {
                let mut table = started();
                let mut codes = [Association::OutsideGates; 1];
                table
                    .scan(&config, 36_000, &[cart(predicted_x, d)], &mut codes)
                    .unwrap();
                let taken = matches!(codes[0], Association::Updated(_));
                assert_eq!(
                    taken,
                    inside_cap || confirmed,
                    "{} d {d} {codes:?}",
                    S::NAME
                );
            }
        }
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
    check::<Fixed32>();
}
