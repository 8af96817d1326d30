//! abtrack's single-target operations, per call: the αβ / αβγ filters in one
//! and two axes, the scheduled 2-D αβ filters, the range–azimuth filter, the
//! altitude tracker and the TCAS assessment.
//!
//! The fixed-gain rows call the per-interval path a tracker uses
//! (`update_step`): the step gains (α, β/T, γ/(2T²), T, T²/2) are formed
//! once for the interval, before the loop, outside the timed call.

use core::hint::black_box;

use abtrack::filter::altitude::{
    AltitudeEstimate, AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig,
};
use abtrack::filter::auto::{AutoFilter, AutoInterval};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::filter::{Cartesian, Gains, KinematicFilter, StepGains};
use abtrack::gain::al_wagih::LeastSquaresConfig;
use abtrack::gain::auto::SharedNoise;
use abtrack::gain::liu::AdaptiveSwitchConfig;
use abtrack::gain::{
    AdaptiveSwitchGains, AutoConfig, AutoGains, GainSchedule, LeastSquaresGains, ScheduledFilter,
};
use abtrack::num::Quantity;
use abtrack::tcas::{
    assess, assess_in, stateless_cycle, Advisory, Cycle, Intruder, IntruderTrack, OwnAircraft,
    Reply, MAX_CLOSURE_SPEED_M_PER_S,
};
use abtrack::Scalar;

use crate::counter::Bench;
use crate::data::{at, PlaneRing, RING};
use crate::numeric::BenchNumber;
use crate::synth::Lcg;

/// Every operation of this module that runs in any number system
/// ([`abtrack::Numeric`]).
#[inline(never)]
pub fn run<N: BenchNumber>(bench: &mut Bench) {
    kinematic::<N>(bench);
    scheduled::<N>(bench);
    range_azimuth::<N>(bench);
    auto::<N>(bench);
}

/// The operations still written for [`Scalar`] (`f32`, `f64`, Q32.32): the
/// altitude tracker and the TCAS assessment (not yet ported to
/// [`abtrack::Numeric`]).
#[inline(never)]
pub fn run_scalar<S: BenchNumber + Scalar>(bench: &mut Bench) {
    altitude::<S>(bench);
    tcas::<S>(bench);
}

/// The αβ gains of the fixed-gain rows (Benedict–Bordner β = α²/(2 − α)).
pub fn ab_gains<N: abtrack::Numeric>() -> Option<Gains<N>> {
    Gains::alpha_beta_f64(0.5, 0.5 * 0.5 / 1.5).ok()
}

// One call each, never inlined, so that every figure includes the same call
// overhead whatever the inliner decides for the filter's own code (left to
// itself it inlines some instantiations into the loop and not others).

#[inline(never)]
fn update_axis<N: abtrack::Numeric, const ORDER: usize>(
    filter: &mut KinematicFilter<N, ORDER>,
    z: N::Length,
    step: &StepGains<N>,
) -> bool {
    filter.update_step(z, step).is_ok()
}

#[inline(never)]
fn update_plane<N: abtrack::Numeric, const ORDER: usize>(
    filter: &mut Cartesian<N, ORDER, 2>,
    z: [N::Length; 2],
    step: &StepGains<N>,
) -> bool {
    filter.update_step(z, step).is_ok()
}

#[inline(never)]
fn update_scheduled<N: abtrack::Numeric, G: GainSchedule<N, 2>>(
    filter: &mut ScheduledFilter<N, G, 2, 2>,
    z: [N::Length; 2],
    dt: N::Interval,
) -> bool {
    filter.update(z, dt).is_ok()
}

#[inline(never)]
fn update_auto<N: abtrack::Numeric>(
    filter: &mut AutoFilter<N, 2>,
    noise: &SharedNoise<N>,
    z: [N::Length; 2],
    step: &AutoInterval<N>,
) -> bool {
    filter.update_step(noise, z, step).is_ok()
}

#[inline(never)]
fn update_auto_per_call_interval<N: abtrack::Numeric>(
    filter: &mut AutoFilter<N, 2>,
    noise: &SharedNoise<N>,
    z: [N::Length; 2],
    dt: N::Interval,
) -> bool {
    filter.update(noise, z, dt).is_ok()
}

#[inline(never)]
fn update_range_azimuth<N: abtrack::Numeric>(
    filter: &mut RangeAzimuthFilter<N>,
    range: N::Length,
    azimuth: N::Angle,
    dt: N::Interval,
) -> bool {
    filter.update(range, azimuth, dt).is_ok()
}

#[inline(never)]
fn update_altitude<S: Scalar>(tracker: &mut AltitudeTracker<S>, altitude_ft: S, dt: S) -> bool {
    tracker.scan(Some(altitude_ft), dt).is_ok()
}

#[inline(never)]
fn assess_one<S: Scalar>(own: &OwnAircraft<S>, intruder: &Intruder<S>) -> Option<Advisory> {
    assess(own, intruder).ok().map(|a| a.advisory)
}

/// How many assessments alerted (TA or RA) and how many were refused.
#[derive(Default, PartialEq)]
struct AdvisoryTally {
    alerts: u32,
    refused: u32,
}

impl AdvisoryTally {
    fn count(&mut self, advisory: Option<Advisory>) {
        match advisory {
            Some(a) if a >= Advisory::Traffic => self.alerts += 1,
            Some(_) => {}
            None => self.refused += 1,
        }
    }
}

#[inline(never)]
fn assess_one_in<S: Scalar>(cycle: &Cycle<S>, intruder: &Intruder<S>) -> Option<Advisory> {
    assess_in(cycle, intruder).ok().map(|a| a.advisory)
}

#[inline(never)]
fn form_cycle<S: Scalar>(own: &OwnAircraft<S>) -> Option<Cycle<S>> {
    stateless_cycle(own).ok()
}

/// One reply of a tracked intruder (range, bearing, altitude) through its
/// bearing track, its range and altitude trackers and its assessment.
#[inline(never)]
fn scan_intruder<S: Scalar>(
    cycle: &Cycle<S>,
    bearing: &mut RangeAzimuthFilter<S>,
    (track, altitude): (&mut IntruderTrack<S>, &AltitudeTrackerConfig<S>),
    (range_m, bearing_rad, altitude_ft): (S, S, S),
    dt: S,
) -> Option<Advisory> {
    bearing.update(range_m, bearing_rad, dt).ok()?;
    let reply = Reply {
        range_m,
        altitude_ft: Some(altitude_ft),
    };
    track.scan(altitude, Some(reply), dt).ok()?;
    let status = track.assess(cycle, Some(bearing), dt).ok()??;
    Some(status.advisory)
}

/// αβ and αβγ, one axis and two, fixed gains, on a noisy out-and-back
/// target (σ = 25 m), through the per-interval path: the step gains of the
/// interval formed once, outside the timed calls.
#[inline(never)]
fn kinematic<N: BenchNumber>(bench: &mut Bench) {
    let numeric = N::LABEL;
    let dt = N::Interval::from_f64_lossy(1.0);
    let steps = ab_gains::<N>()
        .zip(Gains::<N>::alpha_beta_gamma_f64(0.657, 0.2295, 0.054).ok())
        .and_then(|(ab, abg)| {
            Some((
                StepGains::new(&ab, dt).ok()?,
                StepGains::new(&abg, dt).ok()?,
            ))
        });
    let Some((ab_step, abg_step)) = steps else {
        bench.fail(numeric, "ab1d_update", "gains refused");
        return;
    };
    // Opaque to the optimiser, as gains formed at run time would be (a
    // constant would be propagated into the non-inlined calls).
    let (ab_step, abg_step) = black_box((ab_step, abg_step));
    let target = PlaneRing::<N>::new(25.0);
    let xs = &target.xs;
    let axis_baseline = |k: u32| {
        black_box(black_box(xs[at(k)]));
    };

    let mut ab = KinematicFilter::<N, 2>::new();
    bench.per_accepted_call(
        numeric,
        "ab1d_update",
        |k| update_axis(&mut ab, black_box(xs[at(k)]), &ab_step),
        axis_baseline,
    );
    let mut abg = KinematicFilter::<N, 3>::new();
    bench.per_accepted_call(
        numeric,
        "abg1d_update",
        |k| update_axis(&mut abg, black_box(xs[at(k)]), &abg_step),
        axis_baseline,
    );
    let mut ab2d: Cartesian<N, 2, 2> = Cartesian::new();
    bench.per_accepted_call(
        numeric,
        "ab2d_update",
        |k| update_plane(&mut ab2d, target.get(k), &ab_step),
        |k| target.fetch(k),
    );
    let mut abg2d: Cartesian<N, 3, 2> = Cartesian::new();
    bench.per_accepted_call(
        numeric,
        "abg2d_update",
        |k| update_plane(&mut abg2d, target.get(k), &abg_step),
        |k| target.fetch(k),
    );
}

/// Scheduled 2-D αβ: Al-Wagih's least-squares gains and Liu's adaptive
/// switch, on Liu, Wang & Yang's σ = 5 m (so that the adaptive schedules see
/// both steady stretches and the turnarounds of the out-and-back track).
#[inline(never)]
fn scheduled<N: BenchNumber>(bench: &mut Bench) {
    let numeric = N::LABEL;
    let dt = black_box(N::Interval::from_f64_lossy(1.0));
    let target = PlaneRing::<N>::new(5.0);
    let (Ok(ls), Ok(liu)) = (
        LeastSquaresGains::new(&LeastSquaresConfig::DEFAULT),
        AdaptiveSwitchGains::<N, 2, 8>::new(&AdaptiveSwitchConfig::DEFAULT),
    ) else {
        bench.fail(numeric, "ab2d_least_squares_update", "schedule refused");
        return;
    };
    let mut ls_track: ScheduledFilter<N, _, 2, 2> = ScheduledFilter::new(ls);
    bench.per_accepted_call(
        numeric,
        "ab2d_least_squares_update",
        |k| update_scheduled(&mut ls_track, target.get(k), dt),
        |k| target.fetch(k),
    );
    let mut liu_track: ScheduledFilter<N, _, 2, 2> = ScheduledFilter::new(liu);
    bench.per_accepted_call(
        numeric,
        "ab2d_liu_adaptive_update",
        |k| update_scheduled(&mut liu_track, target.get(k), dt),
        |k| target.fetch(k),
    );
}

/// `auto` as the default Cartesian track runs it ([`AutoFilter`]: one
/// covariance for both axes, docs/auto.md), configured with the data's σ,
/// on the same target as the scheduled rows: with the interval's terms
/// formed once, before the loop ([`AutoInterval`], as the fixed-gain rows'
/// step gains and a track table's scan), and formed in every call
/// (`AutoFilter::update`, as for reports that each come with their own
/// interval).
#[inline(never)]
fn auto<N: BenchNumber>(bench: &mut Bench) {
    let numeric = N::LABEL;
    let dt = black_box(N::Interval::from_f64_lossy(1.0));
    let target = PlaneRing::<N>::new(5.0);
    let (Ok(auto), Ok(step)) = (
        AutoGains::<N, 2>::new(&AutoConfig::cartesian(5.0)),
        AutoInterval::new(dt),
    ) else {
        for row in ["auto2d_update", "auto2d_update_per_call_interval"] {
            bench.fail(numeric, row, "schedule or interval refused");
        }
        return;
    };
    let noise = black_box(*auto.shared_noise());
    let step = black_box(step);
    let mut filter = AutoFilter::<N, 2>::new();
    bench.per_accepted_call(
        numeric,
        "auto2d_update",
        |k| update_auto(&mut filter, &noise, target.get(k), &step),
        |k| target.fetch(k),
    );
    let mut filter = AutoFilter::<N, 2>::new();
    bench.per_accepted_call(
        numeric,
        "auto2d_update_per_call_interval",
        |k| update_auto_per_call_interval(&mut filter, &noise, target.get(k), dt),
        |k| target.fetch(k),
    );
}

/// Range–azimuth (He et al.): a target 20 km out going out and back at
/// 150 m/s along the line of sight while the azimuth drifts, 15 m and
/// 0.01 rad of noise.
#[inline(never)]
fn range_azimuth<N: BenchNumber>(bench: &mut Bench) {
    let numeric = N::LABEL;
    let dt = black_box(N::Interval::from_f64_lossy(1.0));
    let mut rng = Lcg::new(3);
    let polar: [(N::Length, N::Angle); RING] = core::array::from_fn(|k| {
        let leg = if k < RING / 2 { k } else { RING - k } as f64;
        (
            N::Length::from_f64_lossy(20_000.0 + 150.0 * leg + rng.noise(15.0)),
            N::Angle::from_f64_lossy(0.5 + 0.002 * leg + rng.noise(0.01)),
        )
    });
    let Ok(noise) = RangeAzimuthNoise::<N>::paper_bearing_f64(225.0, 1.0) else {
        bench.fail(numeric, "range_azimuth_update", "noise refused");
        return;
    };
    let mut filter = RangeAzimuthFilter::new(noise);
    let get = |k: u32| {
        let (r, b) = polar[at(k)];
        (black_box(r), black_box(b))
    };
    bench.per_accepted_call(
        numeric,
        "range_azimuth_update",
        |k| {
            let (r, b) = get(k);
            update_range_azimuth(&mut filter, r, b, dt)
        },
        |k| {
            black_box(get(k));
        },
    );
}

/// The altitude tracker with Mode C reports (100 ft steps) of an intruder
/// climbing and descending at 20 ft/s around 8000 ft, one per second.
#[inline(never)]
fn altitude<S: BenchNumber + Scalar>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let dt = black_box(<S as abtrack::Quantity>::from_f64_lossy(1.0));
    let mut rng = Lcg::new(6);
    let reports: [S; RING] = core::array::from_fn(|k| {
        let leg = if k < RING / 2 { k } else { RING - k } as f64;
        let true_ft = 8_000.0 + 20.0 * leg + rng.noise(10.0);
        <S as abtrack::Quantity>::from_f64_lossy(libm::round(true_ft / 100.0) * 100.0)
    });
    let Ok(config) = AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC) else {
        bench.fail(numeric, "altitude_update", "configuration refused");
        return;
    };
    let mut tracker = AltitudeTracker::<S>::new(config);
    bench.per_accepted_call(
        numeric,
        "altitude_update",
        |k| update_altitude(&mut tracker, black_box(reports[at(k)]), dt),
        |k| {
            black_box(black_box(reports[at(k)]));
        },
    );
}

/// One TCAS assessment per intruder: intruders within ±6 NM on each axis,
/// ±300 m/s, ±1000 ft and ±30 ft/s of the own aircraft, level at 8000 ft
/// (SL 5), a mix of none, proximate, TA and RA.
#[inline(never)]
fn tcas<S: BenchNumber + Scalar>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let own = black_box(OwnAircraft::over_sea_level(
        <S as abtrack::Quantity>::from_f64_lossy(8000.0),
        <S as abtrack::Quantity>::ZERO,
    ));
    let mut rng = Lcg::new(4);
    let c = |v: f64| <S as abtrack::Quantity>::from_f64_lossy(v);
    let intruders: [Intruder<S>; RING] = core::array::from_fn(|_| Intruder {
        relative_position_m: [
            c(rng.uniform(-11_112.0, 11_112.0)),
            c(rng.uniform(-11_112.0, 11_112.0)),
        ],
        relative_velocity_m_per_s: [c(rng.uniform(-300.0, 300.0)), c(rng.uniform(-300.0, 300.0))],
        altitude: Some(AltitudeEstimate {
            altitude_ft: c(8000.0 + rng.uniform(-1000.0, 1000.0)),
            vertical_rate_ft_per_s: c(rng.uniform(-30.0, 30.0)),
        }),
    });
    let baseline = |k: u32| {
        black_box(black_box(&intruders[at(k)]));
    };
    let mut one_shot = AdvisoryTally::default();
    bench.per_call(
        numeric,
        "tcas_assess",
        |k| one_shot.count(assess_one(&own, black_box(&intruders[at(k)]))),
        baseline,
    );
    bench.check(
        one_shot.refused == 0,
        numeric,
        "tcas_assess",
        "assessments refused",
    );
    // The data must exercise both branches (some TA/RA, not all).
    bench.check(
        one_shot.alerts > 0 && one_shot.alerts < crate::CALLS,
        numeric,
        "tcas_assess",
        "no mix of alerting and quiet intruders",
    );
    // The same assessment split as a scan runs it: the cycle (level and
    // thresholds) once per scan, then each intruder in it.
    let mut formed = 0u32;
    bench.per_call(
        numeric,
        "tcas_cycle",
        |_| formed += u32::from(form_cycle(black_box(&own)).is_some()),
        |_| {
            black_box(black_box(&own));
        },
    );
    bench.check(
        formed == crate::CALLS,
        numeric,
        "tcas_cycle",
        "cycles refused",
    );
    let Some(cycle) = form_cycle(&own) else {
        bench.fail(numeric, "tcas_assess_in_cycle", "cycle refused");
        return;
    };
    let cycle = black_box(cycle);
    let mut in_cycle = AdvisoryTally::default();
    bench.per_call(
        numeric,
        "tcas_assess_in_cycle",
        |k| in_cycle.count(assess_one_in(&cycle, black_box(&intruders[at(k)]))),
        baseline,
    );
    bench.check(
        in_cycle == one_shot,
        numeric,
        "tcas_assess_in_cycle",
        "assessments refused or different from tcas_assess",
    );
    tracked_intruder(bench, &cycle);
}

/// `tcas_intruder_scan`: one intruder's reply in a formed cycle as the scan
/// loop takes it: its bearing track's update (the range–azimuth filter,
/// σ_R 15.24 m, σ_B 5°), its range and altitude trackers' scan (25 ft
/// reports) and its assessment on those tracks (`IntruderTrack::assess`,
/// the miss-distance filter included). The intruder's range swings 3–9 km
/// (up to 294 m/s of closure) and its bearing ±0.3 rad, 300 ft above the
/// own aircraft, one reply a second: closing and opening, with and without
/// an advisory.
#[inline(never)]
fn tracked_intruder<S: BenchNumber + Scalar>(bench: &mut Bench, cycle: &Cycle<S>) {
    const OPERATION: &str = "tcas_intruder_scan";
    let numeric = S::LABEL;
    let c = |v: f64| <S as abtrack::Quantity>::from_f64_lossy(v);
    let dt = black_box(c(1.0));
    let mut rng = Lcg::new(7);
    let replies: [(S, S, S); RING] = core::array::from_fn(|k| {
        let phase = 2.0 * core::f64::consts::PI * k as f64 / RING as f64;
        let altitude_ft = 8_300.0 + rng.noise(5.0);
        (
            c(6_000.0 + 3_000.0 * libm::cos(phase) + rng.noise(15.24)),
            c(0.3 * libm::sin(phase) + rng.noise(0.087)),
            c(libm::round(altitude_ft / 25.0) * 25.0),
        )
    });
    let configured = (
        RangeAzimuthNoise::<S>::new_f64(15.24 * 15.24, 0.087 * 0.087, 1.0)
            .and_then(|n| n.with_speed_bound_f64(MAX_CLOSURE_SPEED_M_PER_S)),
        AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeS25),
    );
    let (Ok(noise), Ok(altitude)) = configured else {
        bench.fail(numeric, OPERATION, "configuration refused");
        return;
    };
    let mut bearing = RangeAzimuthFilter::<S>::new(noise);
    let mut track = IntruderTrack::<S>::new();
    // Two laps first: firm tracks, as in a scan loop that has run a while.
    for k in 0..2 * RING as u32 {
        scan_intruder(
            cycle,
            &mut bearing,
            (&mut track, &altitude),
            replies[at(k)],
            dt,
        );
    }
    let mut tally = AdvisoryTally::default();
    bench.per_call(
        numeric,
        OPERATION,
        |k| {
            tally.count(scan_intruder(
                cycle,
                &mut bearing,
                (&mut track, &altitude),
                black_box(replies[at(k)]),
                dt,
            ))
        },
        |k| {
            black_box(black_box(replies[at(k)]));
        },
    );
    bench.check(tally.refused == 0, numeric, OPERATION, "replies refused");
    bench.check(
        tally.alerts > 0 && tally.alerts < crate::CALLS,
        numeric,
        OPERATION,
        "no mix of alerting and quiet replies",
    );
}
