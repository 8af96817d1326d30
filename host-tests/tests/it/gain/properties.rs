//! Property tests: no schedule ever produces gains outside the stability
//! region, or fails to produce gains, whatever the innovations; and
//! scheduled filters never panic on any measurement sequence.

use super::support;
use abtrack::num::Quantity;

use abtrack::filter::{FilterError, Phase};
use abtrack::gain::spec::ScheduleSpec;
use abtrack::gain::{
    AnySchedule, AxisObservation, GainContext, GainSchedule, ScheduledError, ScheduledFilter,
};
use abtrack::{Fix, Gains, Scalar};
use proptest::prelude::*;
use support::ALL_SCHEDULES;

/// The stability region re-checked in f64 from the gains' values:
/// 0 < α < 2, β > 0, 2α + β < 4 (Al-Wagih eqs. 12–14), and for αβγ gains
/// 0 < γ < 4αβ/(2 − α) (Tenne & Singh eqs. 7–8).
fn assert_stable<S: Scalar>(g: &Gains<S>, what: &str) {
    let (a, b, c) = (g.alpha().to_f64(), g.beta().to_f64(), g.gamma().to_f64());
    assert!(a > 0.0 && a < 2.0, "{what}: alpha {a}");
    assert!(b > 0.0, "{what}: beta {b}");
    assert!(2.0 * a + b < 4.0, "{what}: 2a+b = {}", 2.0 * a + b);
    if c != 0.0 {
        assert!(c > 0.0 && c < 4.0 * a * b / (2.0 - a), "{what}: gamma {c}");
    }
}

/// One event of a track's life, as proptest draws it.
#[derive(Debug, Clone)]
enum Event {
    /// A measurement: per axis the innovation and predicted position.
    Measure {
        innovation: [f64; 2],
        predicted: [f64; 2],
        velocity: [f64; 2],
        dt: f64,
    },
    Miss,
}

fn event() -> impl Strategy<Value = Event> {
    // Innovations from sub-millimetre to 100 km (log-uniform magnitude,
    // either sign, exact zeros too), positions to ±400 km, intervals
    // 0.05–20 s (the envelope of src/num.rs).
    let magnitude = prop_oneof![
        1 => Just(0.0),
        9 => (-4.0f64..5.0).prop_map(|e| 10f64.powf(e)),
    ];
    let signed = (magnitude, any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m });
    prop_oneof![
        9 => (
            [signed.clone(), signed],
            [-4.0e5f64..4.0e5, -4.0e5f64..4.0e5],
            [-1.5e3f64..1.5e3, -1.5e3f64..1.5e3],
            0.05f64..20.0,
        )
            .prop_map(|(innovation, predicted, velocity, dt)| Event::Measure {
                innovation,
                predicted,
                velocity,
                dt,
            }),
        1 => Just(Event::Miss),
    ]
}

fn context<S: Scalar>(n: u32, e: &Event) -> Option<GainContext<S, 2>> {
    let Event::Measure {
        innovation,
        predicted,
        velocity,
        dt,
    } = e
    else {
        return None;
    };
    let c = |v: f64| S::try_from_f64(v).unwrap();
    let mut axes = [AxisObservation::<S>::default(); 2];
    for i in 0..2 {
        let (p, inn) = (c(predicted[i]), c(innovation[i]));
        axes[i] = AxisObservation {
            measurement: p + inn,
            predicted: p,
            predicted_velocity: c(velocity[i]),
            innovation: inn,
        };
    }
    Some(GainContext {
        n,
        dt: c(*dt),
        axes,
    })
}

/// Drives a schedule directly through the protocol of [`GainSchedule`]
/// with arbitrary innovations: it must give stable gains every time.
fn drive<S: Scalar>(spec: &str, events: &[Event]) {
    let spec = ScheduleSpec::parse(spec).unwrap();
    let mut s = AnySchedule::<S, 2, { support::W }>::from_spec(&spec).unwrap();
    let mut n = 0u32;
    let mut phase = Phase::Empty;
    for e in events {
        match context::<S>(n + 1, e) {
            None => GainSchedule::<S, 2>::missed(&mut s, S::ONE),
            Some(ctx) => {
                if s.restart_required(phase) {
                    s.reset();
                    n = 0;
                    phase = Phase::Empty;
                }
                n += 1;
                if phase != Phase::Tracking {
                    GainSchedule::<S, 2>::initialised(&mut s, n, ctx.dt);
                    phase = if n >= 2 {
                        Phase::Tracking
                    } else {
                        Phase::OnePoint
                    };
                    continue;
                }
                let ctx = GainContext { n, ..ctx };
                let g = s
                    .gains(&ctx)
                    .unwrap_or_else(|err| panic!("{spec} in {}: no gains: {err}", S::NAME));
                for gi in &g {
                    assert_stable(gi, &format!("{spec} in {}", S::NAME));
                }
                s.accepted(&ctx, &g);
            }
        }
    }
}

fn drive_all<S: Scalar>(events: &[Event]) {
    for spec in ALL_SCHEDULES {
        drive::<S>(spec, events);
    }
}

/// Runs a scheduled filter on arbitrary measurements: every call returns
/// (never panics); refusals are only the filter's own (saturation); gains
/// used are stable; a refused update leaves the track unchanged.
fn run_filter<S: Scalar>(spec: &str, zs: &[([f64; 2], f64, bool)]) {
    let spec = ScheduleSpec::parse(spec).unwrap();
    let s = AnySchedule::<S, 2, { support::W }>::from_spec(&spec).unwrap();
    let mut track: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(s);
    let c = |v: f64| S::try_from_f64(v).unwrap();
    for (z, dt, miss) in zs {
        if *miss {
            let _ = track.coast(c(*dt));
            continue;
        }
        let before = track;
        match track.update([c(z[0]), c(z[1])], c(*dt)) {
            Ok(u) => {
                for g in u.gains.iter().flatten() {
                    assert_stable(g, &format!("{spec} in {}", S::NAME));
                }
            }
            Err(ScheduledError::Filter(FilterError::Saturated)) => {
                assert_eq!(track.filter().position(), before.filter().position());
                assert_eq!(track.schedule(), before.schedule());
            }
            Err(e) => panic!("{spec} in {}: unexpected refusal {e}", S::NAME),
        }
    }
}

fn measurements() -> impl Strategy<Value = Vec<([f64; 2], f64, bool)>> {
    prop::collection::vec(
        (
            [-4.0e5f64..4.0e5, -4.0e5f64..4.0e5],
            0.05f64..20.0,
            prop::bool::weighted(0.1),
        ),
        0..60,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn schedules_give_stable_gains_f64(events in prop::collection::vec(event(), 0..60)) {
        drive_all::<f64>(&events);
    }

    #[test]
    fn schedules_give_stable_gains_f32(events in prop::collection::vec(event(), 0..60)) {
        drive_all::<f32>(&events);
    }

    #[test]
    fn schedules_give_stable_gains_fixed(events in prop::collection::vec(event(), 0..60)) {
        drive_all::<Fix>(&events);
    }

    #[test]
    fn scheduled_filters_never_panic(zs in measurements()) {
        for spec in ALL_SCHEDULES {
            run_filter::<f64>(spec, &zs);
            run_filter::<f32>(spec, &zs);
            run_filter::<Fix>(spec, &zs);
        }
    }
}

/// Innovations that overflow Q32.32 when squared (|e| > 46 341 m, or
/// (e/σ_m)² beyond 2³¹) still give stable gains: the schedules take the
/// formulas' limits rather than fail.
#[test]
fn huge_innovations_in_fixed_point() {
    let events: Vec<Event> = (0..12)
        .map(|k| Event::Measure {
            innovation: [2.0e9 * if k % 2 == 0 { 1.0 } else { -1.0 }, 1.0e6],
            predicted: [1.0e8, -1.0e8],
            velocity: [0.0, 0.0],
            dt: 0.05,
        })
        .collect();
    drive_all::<Fix>(&events);
    drive_all::<f32>(&events);
}

/// Invalid numbers in a context are refused, not learnt from.
#[test]
fn invalid_context_is_refused() {
    let mut ctx = support::context::<f64, 2>(3, 1.0, [0.0; 2], [1.0; 2]);
    ctx.axes[1].innovation = f64::NAN;
    assert!(ctx.check().is_err());
    ctx.axes[1].innovation = 1.0;
    ctx.dt = 0.0;
    assert!(ctx.check().is_err());
    let p = abtrack::filter::Prediction::<f64> {
        position: 0.0,
        velocity: 0.0,
        acceleration: 0.0,
    };
    assert!(GainContext::new(3, 1.0, [f64::INFINITY, 0.0], &[p, p]).is_err());
}

/// An update whose prediction overflows Q32.32 is refused and counted by
/// the filter, and the schedule does not learn from it.
#[test]
fn overflowing_prediction_is_refused_and_counted() {
    use abtrack::gain::{al_wagih::MovingWindowConfig, MovingWindowGains};
    let m4 = MovingWindowGains::<Fix, 1, 8>::new(&MovingWindowConfig::DEFAULT).unwrap();
    let mut track: ScheduledFilter<Fix, _, 2, 1> = ScheduledFilter::new(m4);
    let f = Fix::from_f64_lossy;
    // Velocity 1e8 m/s from two points; a 20 s prediction is 2e9 + 2e9.
    track.update([f(0.0)], f(1.0)).unwrap();
    track.update([f(1.0e8)], f(1.0)).unwrap();
    track.update([f(2.0e8)], f(1.0)).unwrap();
    let before = track;
    assert_eq!(
        track.update([f(2.1e9)], f(20.0)),
        Err(ScheduledError::Filter(FilterError::Saturated))
    );
    assert_eq!(
        track.filter().saturations(),
        before.filter().saturations() + 1
    );
    assert_eq!(track.filter().position(), before.filter().position());
    assert_eq!(track.schedule(), before.schedule());
    assert_eq!(track.measurements(), 3);
}
