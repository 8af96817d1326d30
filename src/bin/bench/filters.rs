//! abtrack's single-target operations, per call: the αβ / αβγ filters in one
//! and two axes, the scheduled 2-D αβ filters, the range–azimuth filter, the
//! altitude tracker and the TCAS assessment.

use core::hint::black_box;

use abtrack::filter::altitude::{
    AltitudeEstimate, AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig,
};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::filter::{Cartesian, Gains, KinematicFilter};
use abtrack::gain::al_wagih::LeastSquaresConfig;
use abtrack::gain::liu::AdaptiveSwitchConfig;
use abtrack::gain::{
    AdaptiveSwitchGains, AutoConfig, AutoGains, GainSchedule, LeastSquaresGains, ScheduledFilter,
};
use abtrack::tcas::{assess, Advisory, Intruder, OwnAircraft};
use abtrack::Scalar;

use crate::counter::Bench;
use crate::data::{at, PlaneRing, RING};
use crate::numeric::Numeric;
use crate::synth::Lcg;

/// Every operation of this module in `S`.
#[inline(never)]
pub fn run<S: Numeric>(bench: &mut Bench) {
    kinematic::<S>(bench);
    range_azimuth::<S>(bench);
    // `auto` does not fit the micro:bit's 256 KiB of flash beside the rest
    // (in Q32.32 on the M0 its update is about 23 KiB of code): measured on
    // the other boards only.
    if !cfg!(abtrack_board = "microbit") {
        auto::<S>(bench);
    }
    // The TCAS trackers and logic of issue 10 are larger than the αβ
    // altitude filter they replace, and the scheduled filters grew with the
    // bounds of issue 12 (`robust_gains`): on the micro:bit these rows run in
    // the natural type only, as the scan rows do (`crate::scans_fit`).
    if crate::scans_fit::<S>() {
        scheduled::<S>(bench);
        altitude::<S>(bench);
        tcas::<S>(bench);
    }
}

/// The αβ gains of the fixed-gain rows (Benedict–Bordner β = α²/(2 − α)).
pub fn ab_gains<S: Scalar>() -> Option<Gains<S>> {
    Gains::alpha_beta_f64(0.5, 0.5 * 0.5 / 1.5).ok()
}

// One call each, never inlined, so that every figure includes the same call
// overhead whatever the inliner decides for the filter's own code (left to
// itself it inlines some instantiations into the loop and not others).

#[inline(never)]
fn update_axis<S: Scalar, const ORDER: usize>(
    filter: &mut KinematicFilter<S, ORDER>,
    z: S,
    dt: S,
    gains: &Gains<S>,
) -> bool {
    filter.update(z, dt, gains).is_ok()
}

#[inline(never)]
fn update_plane<S: Scalar, const ORDER: usize>(
    filter: &mut Cartesian<S, ORDER, 2>,
    z: [S; 2],
    dt: S,
    gains: &Gains<S>,
) -> bool {
    filter.update(z, dt, gains).is_ok()
}

#[inline(never)]
fn update_scheduled<S: Scalar, G: GainSchedule<S, 2>>(
    filter: &mut ScheduledFilter<S, G, 2, 2>,
    z: [S; 2],
    dt: S,
) -> bool {
    filter.update(z, dt).is_ok()
}

#[inline(never)]
fn update_range_azimuth<S: Scalar>(
    filter: &mut RangeAzimuthFilter<S>,
    range: S,
    azimuth: S,
    dt: S,
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

/// αβ and αβγ, one axis and two, fixed gains, on a noisy out-and-back
/// target (σ = 25 m).
#[inline(never)]
fn kinematic<S: Numeric>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let (Some(ab_gains), Ok(abg_gains)) = (
        ab_gains::<S>(),
        Gains::<S>::alpha_beta_gamma_f64(0.657, 0.2295, 0.054),
    ) else {
        bench.fail(numeric, "ab1d_update", "gains refused");
        return;
    };
    // Opaque to the optimiser, as configuration read at run time would be
    // (a constant would be propagated into the non-inlined calls).
    let (ab_gains, abg_gains, dt) = black_box((ab_gains, abg_gains, S::from_f64_lossy(1.0)));
    let target = PlaneRing::<S>::new(25.0);
    let xs = &target.xs;
    let axis_baseline = |k: u32| {
        black_box(black_box(xs[at(k)]));
    };

    let mut ab = KinematicFilter::<S, 2>::new();
    bench.per_accepted_call(
        numeric,
        "ab1d_update",
        |k| update_axis(&mut ab, black_box(xs[at(k)]), dt, &ab_gains),
        axis_baseline,
    );
    let mut abg = KinematicFilter::<S, 3>::new();
    bench.per_accepted_call(
        numeric,
        "abg1d_update",
        |k| update_axis(&mut abg, black_box(xs[at(k)]), dt, &abg_gains),
        axis_baseline,
    );
    let mut ab2d: Cartesian<S, 2, 2> = Cartesian::new();
    bench.per_accepted_call(
        numeric,
        "ab2d_update",
        |k| update_plane(&mut ab2d, target.get(k), dt, &ab_gains),
        |k| target.fetch(k),
    );
    let mut abg2d: Cartesian<S, 3, 2> = Cartesian::new();
    bench.per_accepted_call(
        numeric,
        "abg2d_update",
        |k| update_plane(&mut abg2d, target.get(k), dt, &abg_gains),
        |k| target.fetch(k),
    );
}

/// Scheduled 2-D αβ: Al-Wagih's least-squares gains and Liu's adaptive
/// switch, on Liu, Wang & Yang's σ = 5 m (so that the adaptive schedules see
/// both steady stretches and the turnarounds of the out-and-back track).
#[inline(never)]
fn scheduled<S: Numeric>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let dt = black_box(S::from_f64_lossy(1.0));
    let target = PlaneRing::<S>::new(5.0);
    let (Ok(ls), Ok(liu)) = (
        LeastSquaresGains::new(&LeastSquaresConfig::DEFAULT),
        AdaptiveSwitchGains::<S, 2, 8>::new(&AdaptiveSwitchConfig::DEFAULT),
    ) else {
        bench.fail(numeric, "ab2d_least_squares_update", "schedule refused");
        return;
    };
    let mut ls_track: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(ls);
    bench.per_accepted_call(
        numeric,
        "ab2d_least_squares_update",
        |k| update_scheduled(&mut ls_track, target.get(k), dt),
        |k| target.fetch(k),
    );
    let mut liu_track: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(liu);
    bench.per_accepted_call(
        numeric,
        "ab2d_liu_adaptive_update",
        |k| update_scheduled(&mut liu_track, target.get(k), dt),
        |k| target.fetch(k),
    );
}

/// The `auto` schedule (docs/auto.md), configured with the data's σ, on
/// the same target as the scheduled rows.
#[inline(never)]
fn auto<S: Numeric>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let dt = black_box(S::from_f64_lossy(1.0));
    let target = PlaneRing::<S>::new(5.0);
    let Ok(auto) = AutoGains::<S, 2>::new(&AutoConfig::cartesian(5.0)) else {
        bench.fail(numeric, "auto2d_update", "schedule refused");
        return;
    };
    let mut auto_track: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(auto);
    bench.per_accepted_call(
        numeric,
        "auto2d_update",
        |k| update_scheduled(&mut auto_track, target.get(k), dt),
        |k| target.fetch(k),
    );
}

/// Range–azimuth (He et al.): a target 20 km out going out and back at
/// 150 m/s along the line of sight while the azimuth drifts, 15 m and
/// 0.01 rad of noise.
#[inline(never)]
fn range_azimuth<S: Numeric>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let dt = black_box(S::from_f64_lossy(1.0));
    let mut rng = Lcg::new(3);
    let polar: [(S, S); RING] = core::array::from_fn(|k| {
        let leg = if k < RING / 2 { k } else { RING - k } as f64;
        (
            S::from_f64_lossy(20_000.0 + 150.0 * leg + rng.noise(15.0)),
            S::from_f64_lossy(0.5 + 0.002 * leg + rng.noise(0.01)),
        )
    });
    let Ok(noise) = RangeAzimuthNoise::<S>::paper_bearing_f64(225.0, 1.0) else {
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
fn altitude<S: Numeric>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let dt = black_box(S::from_f64_lossy(1.0));
    let mut rng = Lcg::new(6);
    let reports: [S; RING] = core::array::from_fn(|k| {
        let leg = if k < RING / 2 { k } else { RING - k } as f64;
        let true_ft = 8_000.0 + 20.0 * leg + rng.noise(10.0);
        S::from_f64_lossy(libm::round(true_ft / 100.0) * 100.0)
    });
    let Ok(config) = AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC) else {
        bench.fail(numeric, "altitude_update", "configuration refused");
        return;
    };
    let mut tracker = AltitudeTracker::new(config);
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
fn tcas<S: Numeric>(bench: &mut Bench) {
    let numeric = S::LABEL;
    let own = black_box(OwnAircraft::over_sea_level(
        S::from_f64_lossy(8000.0),
        S::ZERO,
    ));
    let mut rng = Lcg::new(4);
    let c = |v: f64| S::from_f64_lossy(v);
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
    let (mut alerts, mut refused) = (0u32, 0u32);
    bench.per_call(
        numeric,
        "tcas_assess",
        |k| match assess_one(&own, black_box(&intruders[at(k)])) {
            Some(a) if a >= Advisory::Traffic => alerts += 1,
            Some(_) => {}
            None => refused += 1,
        },
        |k| {
            black_box(black_box(&intruders[at(k)]));
        },
    );
    bench.check(refused == 0, numeric, "tcas_assess", "assessments refused");
    // The data must exercise both branches (some TA/RA, not all).
    bench.check(
        alerts > 0 && alerts < crate::CALLS,
        numeric,
        "tcas_assess",
        "no mix of alerting and quiet intruders",
    );
}
