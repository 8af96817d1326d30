//! On-target self-test, second image: the TCAS inputs and the multi-target
//! tracker on the emulated core, in the type its TCAS runs in
//! (`board::Wide`: `f32` on the Cortex-M4F, `Fixed32`'s wide format
//! `ScaledScalar` on the Cortex-M3, software `f32` on the Cortex-M0)
//! against `f64` on the same core, or against values computed by hand.
//! Split from `selftest` (filters, gain schedules, M5 bank) because both
//! together do not fit the micro:bit's 256 KiB of flash; same harness
//! (`abtrack_firmware::selftest_support`), same last line `N passed, M failed`.
//!
//! What is checked:
//! * the range–azimuth filter (He et al.) on a short He-like scenario and a
//!   TCAS-like encounter with irregular intervals and missed scans: within a
//!   bound derived from the filter's operations and propagated along its
//!   closed loop ([`compare_range_azimuth`]); bad inputs refused;
//! * the altitude tracker: a quantised climb against f64 (the same
//!   classification every scan, altitude and rate within 0.05 ft and
//!   0.05 ft/s: a provisional tolerance until the quantisation-aware
//!   tracker gets a derived bound), coasting through missing
//!   reports and reverting to non-reporting, bad inputs refused;
//! * TCAS threat assessment on the analytic head-on encounter (600 kt
//!   closure, 8000 ft, SL 5: TA from 6.75 NM, RA from 4.238 NM, range tau,
//!   CPA), through the filters, on a diverging intruder and on a
//!   non-altitude-reporting one;
//! * the TCAS cycle of the firmware (range tracker, altitude tracker,
//!   threat state, resolution) on the demo's threat against f64: the same
//!   advisory, RA sense and strength and clear of conflict every scan, and
//!   the range track within a provisional tolerance;
//! * the track table: two crossing targets keep their ids, a cluttered
//!   scenario gets the same association codes and per-stage counts as in
//!   f64, a full table refuses and counts, bad measurements are rejected,
//!   and the table sizes match the library's documentation.
#![no_std]
#![no_main]

use abtrack_firmware::selftest_support as support;
use abtrack_firmware::{board, ensure, propagation, synth};

use core::mem::size_of;

use abtrack::filter::altitude::{
    AltitudeEstimate, AltitudeQuantum, AltitudeStatus, AltitudeTracker, AltitudeTrackerConfig,
};
use abtrack::filter::range_azimuth::{
    RangeAzimuthFilter, RangeAzimuthNoise, RangeAzimuthOutcome, PAPER_BEARING_VARIANCE,
};
use abtrack::filter::{FilterError, Gains, Phase};
#[cfg(not(abtrack_board = "microbit"))]
use abtrack::num::fixed32::Fixed32;
use abtrack::tcas::{
    assess, Advisory, CollisionAvoidance, Intruder, IntruderTrack, OwnAircraft, RaSense,
    RaStrength, Reply, SensitivityLevel, ThreatAssessment, ThreatGeometry,
    METRES_PER_NAUTICAL_MILE, METRES_PER_SECOND_PER_KNOT,
};
use abtrack::track::{
    Association, DropReason, FixedGainTrack, Gate, Measurement, RejectReason, ScanError,
    ScanReport, TrackId, TrackSlot, TrackStatus, TrackTable, TrackerConfig,
};
use abtrack::Numeric;
use abtrack::{Quantity, Scalar};
use board::Wide;
use propagation::{ErrorPropagation, Lag, Matrix};
use support::{never, value, Failure, Test, TestResult, TestScalar};
use synth::Lcg;

const TESTS: &[Test] = &[
    (
        "range_azimuth_he_scenario_vs_f64",
        range_azimuth_he_scenario_vs_f64,
    ),
    (
        "range_azimuth_tcas_encounter_vs_f64",
        range_azimuth_tcas_encounter_vs_f64,
    ),
    (
        "range_azimuth_invalid_inputs_refused",
        range_azimuth_invalid_inputs_refused,
    ),
    (
        "altitude_quantised_climb_vs_f64",
        altitude_quantised_climb_vs_f64,
    ),
    (
        "altitude_missing_reports_and_bad_input",
        altitude_missing_reports_and_bad_input,
    ),
    ("tcas_head_on_golden", tcas_head_on_golden),
    (
        "tcas_head_on_through_the_filters",
        tcas_head_on_through_the_filters,
    ),
    (
        "tcas_diverging_intruder_never_alerts",
        tcas_diverging_intruder_never_alerts,
    ),
    (
        "tcas_non_reporting_intruder_at_most_ta",
        tcas_non_reporting_intruder_at_most_ta,
    ),
    (
        "tcas_cycle_demo_threat_vs_f64",
        tcas_cycle_demo_threat_vs_f64,
    ),
    (
        "track_table_sizes_match_documentation",
        track_table_sizes_match_documentation,
    ),
    (
        "track_crossing_targets_keep_ids",
        track_crossing_targets_keep_ids,
    ),
    (
        "track_cluttered_scans_same_codes_as_f64",
        track_cluttered_scans_same_codes_as_f64,
    ),
    // The micro:bit's flash does not hold a third table type beside the
    // rest of this image; the Cortex-M3 (mps2-an385) runs it without an FPU.
    #[cfg(not(abtrack_board = "microbit"))]
    (
        "track_fast_fixed_point_same_codes_as_f64",
        track_fast_fixed_point_same_codes_as_f64,
    ),
    (
        "track_full_table_refuses_and_counts",
        track_full_table_refuses_and_counts,
    ),
    (
        "track_bad_measurements_rejected",
        track_bad_measurements_rejected,
    ),
];

#[cortex_m_rt::entry]
fn main() -> ! {
    board::paint_stack();
    support::run(
        "self-test (range-azimuth, altitude, TCAS, track table)",
        TESTS,
    )
}

const NM: f64 = METRES_PER_NAUTICAL_MILE;
const KT: f64 = METRES_PER_SECOND_PER_KNOT;
// ---------------------------------------------------------------------------
// Range–azimuth projection filter (He, Peng, Ling & Quan)
// ---------------------------------------------------------------------------

/// One scan of a range–azimuth scenario: a measurement (range m, azimuth
/// rad) or a missed scan, `dt` after the previous call.
#[derive(Clone, Copy)]
enum RaEvent {
    Measure { range: f64, azimuth: f64, dt: f64 },
    Coast { dt: f64 },
}

/// A straight relative track measured in range and azimuth with bounded
/// pseudo-noise (σ_R, σ_B); `interval(k)` and `miss(k)` shape the scans.
#[derive(Clone, Copy)]
struct RaScenario {
    start: [f64; 2],
    velocity: [f64; 2],
    scans: u32,
    range_sigma: f64,
    bearing_sigma: f64,
    seed: u64,
    interval: fn(u32) -> f64,
    miss: fn(u32) -> bool,
}

fn one_second(_: u32) -> f64 {
    1.0
}

fn tcas_interval(k: u32) -> f64 {
    [1.0, 0.5, 1.5, 1.0][(k % 4) as usize]
}

fn tcas_miss(k: u32) -> bool {
    k % 17 == 9
}

impl RaScenario {
    /// He et al. §4, shortened to 100 scans: own aircraft 900 km/h behind a
    /// target flying 700 km/h the same way, target ahead at azimuth 30° and
    /// 280 km, T = 1 s, range noise 100 m, bearing noise σ_B² = 7.569·10⁻³.
    /// Relative velocity (700 − 900)/3.6 m/s along the common heading (y).
    fn he_short() -> Self {
        let (s, c) = libm::sincos(30.0f64.to_radians());
        RaScenario {
            start: [280_000.0 * s, 280_000.0 * c],
            velocity: [0.0, (700.0 - 900.0) / 3.6],
            scans: 100,
            range_sigma: 100.0,
            bearing_sigma: libm::sqrt(PAPER_BEARING_VARIANCE),
            seed: 0x4e5e_0003,
            interval: one_second,
            miss: never,
        }
    }

    /// A TCAS-like encounter (as host-tests `tests/it/filter/range_azimuth.rs`): intruder
    /// converging from 14 NM at 250 m/s, passing 600 m abeam (the azimuth
    /// sweeps from 1° through 90° to 170°), range noise 15 m, bearing noise
    /// 5° RMS, intervals 1, 0.5, 1.5, 1 s, every 17th scan missed.
    fn tcas_encounter() -> Self {
        RaScenario {
            start: [600.0, 14.0 * METRES_PER_NAUTICAL_MILE],
            velocity: [0.0, -250.0],
            scans: 120,
            range_sigma: 15.0,
            bearing_sigma: libm::sqrt(PAPER_BEARING_VARIANCE),
            seed: 0x7ca5_0011,
            interval: tcas_interval,
            miss: tcas_miss,
        }
    }

    fn events(&self) -> impl Iterator<Item = RaEvent> + '_ {
        let mut rng = Lcg::new(self.seed);
        let mut t = 0.0;
        (0..self.scans).map(move |k| {
            let dt = (self.interval)(k);
            t += dt;
            let x = self.start[0] + self.velocity[0] * t;
            let y = self.start[1] + self.velocity[1] * t;
            let range = libm::hypot(x, y) + rng.noise(self.range_sigma);
            let azimuth = libm::atan2(x, y) + rng.noise(self.bearing_sigma);
            let tau = core::f64::consts::TAU;
            let azimuth = if azimuth < 0.0 {
                azimuth + tau
            } else {
                azimuth
            };
            if (self.miss)(k) {
                RaEvent::Coast { dt }
            } else {
                RaEvent::Measure { range, azimuth, dt }
            }
        })
    }
}

/// Lags kept exactly for the range–azimuth error propagation (4 states:
/// 32 × 192 bytes).
const RA_LAGS: usize = 32;

/// Rounding model of one representation for the range–azimuth bound.
#[derive(Clone, Copy)]
struct Rounding {
    /// Unit roundoff u (relative, per operation).
    u: f64,
    /// Absolute resolution ε (per product or quotient; half of it per
    /// conversion from f64).
    eps: f64,
    /// Absolute error of sin and cos of a representable angle.
    trig: f64,
}

impl Rounding {
    fn of<S: TestScalar>() -> Self {
        Rounding {
            u: S::UNIT_ROUNDOFF,
            eps: S::ABS_RESOLUTION,
            trig: S::SIN_COS_ERROR,
        }
    }

    /// |sin B_S − sin B| (and cos) for the azimuth B converted to S: the
    /// function's error plus the conversion's (sin and cos are 1-Lipschitz).
    fn angle(&self, azimuth: f64) -> f64 {
        self.trig + self.u * libm::fabs(azimuth) + 0.5 * self.eps
    }
}

/// Magnitudes of one range–azimuth step (both runs), for the local error.
#[derive(Clone, Copy, Default)]
struct RaMagnitudes {
    /// Positions, predictions and the range, m.
    position: f64,
    /// Velocity components, m/s.
    velocity: f64,
    range_residual: f64,
    cross_residual: f64,
    /// Largest position gain (α, W1) and velocity gain (β/T, W2).
    position_gain: f64,
    velocity_gain: f64,
}

/// Local error bound of one filtered update of [`RangeAzimuthFilter`] in
/// one representation, by counting the rounded operations of
/// `RangeAzimuthFilter::filter` (P = position scale, V = velocity, E_R, E_C
/// the residuals, K_p ≤ 1 and K_v the gains, τ the sin/cos error, u, ε the
/// rounding model; the gains themselves are taken as exact: their
/// differences between the runs are added separately):
///
/// * prediction x_p = x + T·v_x: e_p ≤ u·P + 2u·T·V + V·ε/2 + ε;
/// * RESID_R = R − (x_p sin B + y_p cos B): ≤ 2P·τ + 2e_p + 4u·P + u·E_R
///   + 2.5ε, RESID_CR likewise with E_C (eq. 11, reading 1);
/// * the projections RESID·sin B: + E·(τ + u) + ε each;
/// * position x_p + α·(…) − W1·(…): e_p + K_p·(both projections)
///   + u·K_p·(E_R + E_C) + 2ε + 2u·P;
/// * velocity v + (β/T)·(…) − W2·(…): K_v·(both projections)
///   + u·K_v·(E_R + E_C) + 2ε + 2u·V.
///
/// Returns (position, velocity) per axis (the same bound for x and y).
fn ra_local_error(r: &Rounding, m: &RaMagnitudes, dt: f64, azimuth: f64) -> (f64, f64) {
    let (u, eps) = (r.u, r.eps);
    let tau = r.angle(azimuth);
    let (p, v, er, ec) = (m.position, m.velocity, m.range_residual, m.cross_residual);
    let e_pred = u * p + 2.0 * u * dt * v + 0.5 * v * eps + eps;
    let e_range = 2.0 * p * tau + 2.0 * e_pred + 4.0 * u * p + u * er + 2.5 * eps;
    let e_cross = 2.0 * p * tau + 2.0 * e_pred + 3.0 * u * p + u * ec + 2.0 * eps;
    let projections = e_range + e_cross + (er + ec) * (tau + u) + 2.0 * eps;
    let position = e_pred
        + m.position_gain * projections
        + u * m.position_gain * (er + ec)
        + 2.0 * eps
        + 2.0 * u * p;
    let velocity =
        m.velocity_gain * projections + u * m.velocity_gain * (er + ec) + 2.0 * eps + 2.0 * u * v;
    (position, velocity)
}

/// The closed loop of one filtered update, state (x, y, ẋ, ẏ): with
/// u = (sin B, cos B), w = (cos B, −sin B), G = α·uuᵀ + W1·wwᵀ and
/// H = (β/T)·uuᵀ + W2·wwᵀ (eqs. 12–13, readings 1–2 of the module docs),
/// p ← (I − G)(p + T·v), v ← v − H(p + T·v):
/// A = [[I − G, T(I − G)], [−H, I − T·H]].
fn ra_closed_loop(gains: [f64; 4], dt: f64, azimuth: f64) -> Matrix<4> {
    let [alpha, velocity_gain, w1, w2] = gains;
    let (s, c) = libm::sincos(azimuth);
    let uu = [[s * s, s * c], [s * c, c * c]];
    let ww = [[c * c, -s * c], [-s * c, s * s]];
    let mut a = [[0.0; 4]; 4];
    for i in 0..2 {
        for j in 0..2 {
            let id = if i == j { 1.0 } else { 0.0 };
            let g = alpha * uu[i][j] + w1 * ww[i][j];
            let h = velocity_gain * uu[i][j] + w2 * ww[i][j];
            a[i][j] = id - g;
            a[i][j + 2] = dt * (id - g);
            a[i + 2][j] = -h;
            a[i + 2][j + 2] = id - dt * h;
        }
    }
    a
}

/// The two-point initialisation's second step: position ← measurement,
/// velocity ← (measurement − old position)/T.
fn ra_second_point(elapsed: f64) -> Matrix<4> {
    let mut a = [[0.0; 4]; 4];
    a[2][0] = -1.0 / elapsed;
    a[3][1] = -1.0 / elapsed;
    a
}

fn ra_coast(dt: f64) -> Matrix<4> {
    let mut a = propagation::identity::<4>();
    a[0][2] = dt;
    a[1][3] = dt;
    a
}

fn ra_state<S: Scalar>(f: &RangeAzimuthFilter<S>) -> [f64; 4] {
    let [x, y] = f.position();
    let [vx, vy] = f.velocity();
    [x.to_f64(), y.to_f64(), vx.to_f64(), vy.to_f64()]
}

/// The range–azimuth filter in `S` against the same filter in f64 on the
/// same core, with `range_variance` (m²), the paper's bearing variance and
/// process noise `q` (m²/s⁴).
///
/// The bound: no library budget covers this filter, so it is derived here
/// the way the budget is (its module docs). The update is affine in the
/// state given the gains, which come from the covariances and the measured
/// range, not from the state (He et al. eqs. 7–10), so the difference of
/// the two runs obeys d ← A_k·d + w_k exactly, A_k the closed loop of the
/// f64 run ([`ra_closed_loop`]). |w_k| is at most the local errors of both
/// runs ([`ra_local_error`], doubled for second-order terms) plus, measured,
/// |gain_S − gain_f64| × |residual| for each of α, β/T, W1, W2 (the
/// covariance recursions round differently, and the gains carry that).
/// Two-point initialisation injects the error of the projected
/// measurement R·(sin B, cos B): R·(τ + 2u) + 1.5ε, and of the difference
/// quotient; a coast propagates by Φ(T) and injects the prediction's
/// rounding. The bound then follows from the windowed propagation of
/// `abtrack_firmware::propagation`.
fn compare_range_azimuth<S: TestScalar>(
    what: &str,
    scenario: &RaScenario,
    range_variance: f64,
    q: f64,
) -> TestResult {
    let (ns, nf) = match (
        RangeAzimuthNoise::<S>::paper_bearing_f64(range_variance, q),
        RangeAzimuthNoise::<f64>::paper_bearing_f64(range_variance, q),
    ) {
        (Ok(a), Ok(b)) => (a, b),
        (a, b) => {
            defmt::error!("{=str}: noise refused: {} {}", S::NAME, a.err(), b.err());
            return Err(Failure);
        }
    };
    let mut fs = RangeAzimuthFilter::new(ns);
    let mut ff = RangeAzimuthFilter::new(nf);
    let rs = Rounding::of::<S>();
    let r64 = Rounding::of::<f64>();
    let mut window = [Lag::EMPTY; RA_LAGS];
    let mut propagation = ErrorPropagation::new(&mut window, [0.0; 4]);
    let mut since_first = 0.0;
    let mut worst = [0.0f64; 4];
    let mut worst_ratio = 0.0f64;
    let mut worst_range = 0.0f64;
    let mut largest_gain_difference = 0.0f64;
    let mut filtered = 0u32;
    for (k, event) in (0u32..).zip(scenario.events()) {
        let before = [ra_state(&fs), ra_state(&ff)];
        let (a, injection) = match event {
            RaEvent::Coast { dt } => {
                let (x, y) = (fs.coast(value::<S>(dt)?), ff.coast(dt));
                ensure!(
                    x.is_ok() && y.is_ok(),
                    "{=str} {=str} scan {=u32}: coast native {}, f64 {}",
                    S::NAME,
                    what,
                    k,
                    x.err(),
                    y.err()
                );
                since_first += dt;
                let mut m = RaMagnitudes::default();
                for s in before {
                    m.position = m.position.max(libm::fabs(s[0])).max(libm::fabs(s[1]));
                    m.velocity = m.velocity.max(libm::fabs(s[2])).max(libm::fabs(s[3]));
                }
                let e = |r: &Rounding| {
                    r.u * m.position
                        + 2.0 * r.u * dt * m.velocity
                        + 0.5 * m.velocity * r.eps
                        + r.eps
                };
                let w = 2.0 * (e(&rs) + e(&r64));
                (ra_coast(dt), [w, w, 0.0, 0.0])
            }
            RaEvent::Measure { range, azimuth, dt } => {
                let (os, of) = match (
                    fs.update(value::<S>(range)?, value::<S>(azimuth)?, value::<S>(dt)?),
                    ff.update(range, azimuth, dt),
                ) {
                    (Ok(a), Ok(b)) => (a, b),
                    (a, b) => {
                        defmt::error!(
                            "{=str} {=str} scan {=u32}: native {}, f64 {}",
                            S::NAME,
                            what,
                            k,
                            a.err(),
                            b.err()
                        );
                        return Err(Failure);
                    }
                };
                // Error of the projected measurement R·(sin B, cos B).
                let projected = |r: &Rounding| range * (r.angle(azimuth) + 2.0 * r.u) + 1.5 * r.eps;
                let e_z = 2.0 * (projected(&rs) + projected(&r64));
                match (os, of) {
                    (RangeAzimuthOutcome::FirstPoint, RangeAzimuthOutcome::FirstPoint) => {
                        since_first = 0.0;
                        ([[0.0; 4]; 4], [e_z, e_z, 0.0, 0.0])
                    }
                    (RangeAzimuthOutcome::SecondPoint, RangeAzimuthOutcome::SecondPoint) => {
                        let elapsed = since_first + dt;
                        let quotient =
                            |r: &Rounding| (2.0 * r.u * range) / elapsed * (1.0 + r.u) + r.eps;
                        let w_v = e_z / elapsed + 2.0 * (quotient(&rs) + quotient(&r64));
                        (ra_second_point(elapsed), [e_z, e_z, w_v, w_v])
                    }
                    (RangeAzimuthOutcome::Filtered(is), RangeAzimuthOutcome::Filtered(iff)) => {
                        filtered += 1;
                        let gains_s = [
                            is.gains.alpha.to_f64(),
                            is.gains.beta.to_f64() / dt,
                            is.gains.w1.to_f64(),
                            is.gains.w2.to_f64(),
                        ];
                        let gains_64 = [
                            iff.gains.alpha,
                            iff.gains.beta / dt,
                            iff.gains.w1,
                            iff.gains.w2,
                        ];
                        let mut m = RaMagnitudes {
                            position: range,
                            range_residual: libm::fabs(is.range_residual.to_f64())
                                .max(libm::fabs(iff.range_residual)),
                            cross_residual: libm::fabs(is.cross_range_residual.to_f64())
                                .max(libm::fabs(iff.cross_range_residual)),
                            position_gain: gains_64[0].max(gains_64[2]),
                            velocity_gain: gains_64[1].max(gains_64[3]),
                            ..RaMagnitudes::default()
                        };
                        for p in [
                            is.predicted[0].to_f64(),
                            is.predicted[1].to_f64(),
                            iff.predicted[0],
                            iff.predicted[1],
                        ] {
                            m.position = m.position.max(libm::fabs(p));
                        }
                        for s in before.iter().chain([ra_state(&fs), ra_state(&ff)].iter()) {
                            m.position = m.position.max(libm::fabs(s[0])).max(libm::fabs(s[1]));
                            m.velocity = m.velocity.max(libm::fabs(s[2])).max(libm::fabs(s[3]));
                        }
                        let (ps, vs) = ra_local_error(&rs, &m, dt, azimuth);
                        let (p64, v64) = ra_local_error(&r64, &m, dt, azimuth);
                        // The reported β is (β/T)·T rounded in S: undo with
                        // one more rounding's allowance.
                        let mut d = [0.0f64; 4];
                        for ((d, s), f) in d.iter_mut().zip(gains_s).zip(gains_64) {
                            *d = libm::fabs(s - f);
                        }
                        let [_, beta_64, _, _] = gains_64;
                        let dv_gain = d[1] + 2.0 * rs.u * beta_64 + rs.eps / dt;
                        for g in d {
                            largest_gain_difference = largest_gain_difference.max(g);
                        }
                        let (er, ec) = (m.range_residual, m.cross_residual);
                        let wp = 2.0 * (ps + p64) + d[0] * er + d[2] * ec;
                        let wv = 2.0 * (vs + v64) + dv_gain * er + d[3] * ec;
                        (ra_closed_loop(gains_64, dt, azimuth), [wp, wp, wv, wv])
                    }
                    (a, b) => {
                        defmt::error!(
                            "{=str} {=str} scan {=u32}: native {}, f64 {}",
                            S::NAME,
                            what,
                            k,
                            a,
                            b
                        );
                        return Err(Failure);
                    }
                }
            }
        };
        let bound = propagation.step(&a, injection);
        let (ss, sf) = (ra_state(&fs), ra_state(&ff));
        for j in 0..4 {
            let d = libm::fabs(ss[j] - sf[j]);
            worst[j] = worst[j].max(d);
            if bound[j] > 0.0 {
                worst_ratio = worst_ratio.max(d / bound[j]);
            }
            ensure!(
                d <= bound[j],
                "{=str} {=str} scan {=u32}: state {=usize} differs by {=f64}, bound {=f64}",
                S::NAME,
                what,
                k,
                j,
                d,
                bound[j]
            );
        }
        // The range re-synthesised from the position (hypot: a handful of
        // roundings of r).
        let r = ff.range();
        let dr = libm::fabs(fs.range().to_f64() - r);
        worst_range = worst_range.max(dr);
        ensure!(
            dr <= bound[0] + bound[1] + 8.0 * (rs.u + r64.u) * r + 8.0 * rs.eps,
            "{=str} {=str} scan {=u32}: range differs by {=f64}",
            S::NAME,
            what,
            k,
            dr
        );
    }
    ensure!(
        fs.saturations() == 0 && ff.saturations() == 0 && fs.phase() == Phase::Tracking,
        "{=str} {=str}: saturations {=u32} / {=u32}",
        S::NAME,
        what,
        fs.saturations(),
        ff.saturations()
    );
    defmt::println!(
        "       {=str} {=str}: {=u32} filtered updates, gains within {=f64}; max |dx| {=f64} m, |dy| {=f64} m, |dvx| {=f64} m/s, |dvy| {=f64} m/s, |dr| {=f64} m; worst deviation = {=f32} of the bound",
        S::NAME,
        what,
        filtered,
        largest_gain_difference,
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        worst_range,
        worst_ratio as f32
    );
    Ok(())
}

fn range_azimuth_he_scenario_vs_f64() -> TestResult {
    compare_range_azimuth::<Wide>("He 280 km", &RaScenario::he_short(), 100.0 * 100.0, 1.0)
}

fn range_azimuth_tcas_encounter_vs_f64() -> TestResult {
    compare_range_azimuth::<Wide>(
        "TCAS 14 NM",
        &RaScenario::tcas_encounter(),
        15.0 * 15.0,
        9.0,
    )
}

/// A range ≤ 0, a non-finite range or azimuth, or a bad interval is refused
/// and leaves the filter as it was, in every phase.
fn range_azimuth_invalid_inputs_refused() -> TestResult {
    ra_invalid::<Wide>()?;
    ra_invalid::<f64>()
}

fn ra_invalid<S: TestScalar>() -> TestResult {
    let noise = match RangeAzimuthNoise::<S>::paper_bearing_f64(225.0, 1.0) {
        Ok(n) => n,
        Err(e) => {
            defmt::error!("{=str}: noise refused: {}", S::NAME, e);
            return Err(Failure);
        }
    };
    let n = |v: f64| S::from_f64_lossy(v);
    let mut f = RangeAzimuthFilter::new(noise);
    let cases = [
        (n(0.0), n(0.5), n(1.0), FilterError::InvalidMeasurement),
        (n(-10.0), n(0.5), n(1.0), FilterError::InvalidMeasurement),
        (n(f64::NAN), n(0.5), n(1.0), FilterError::InvalidMeasurement),
        (
            n(5000.0),
            n(f64::INFINITY),
            n(1.0),
            FilterError::InvalidMeasurement,
        ),
        (n(5000.0), n(0.5), n(0.0), FilterError::InvalidInterval),
        (n(5000.0), n(0.5), n(f64::NAN), FilterError::InvalidInterval),
    ];
    for (phase, (r, b)) in [(5000.0, 0.5), (4900.0, 0.51), (4800.0, 0.52)]
        .iter()
        .enumerate()
    {
        for (i, (range, azimuth, dt, want)) in cases.iter().enumerate() {
            let before = f;
            let got = f.update(*range, *azimuth, *dt);
            ensure!(
                got.err() == Some(*want) && f == before,
                "{=str} phase {=usize} case {=usize}: {}, want {} (state changed: {=bool})",
                S::NAME,
                phase,
                i,
                got.err(),
                want,
                f != before
            );
        }
        ensure!(
            f.update(n(*r), n(*b), n(1.0)).is_ok(),
            "{=str}: valid update refused",
            S::NAME
        );
    }
    ensure!(
        f.phase() == Phase::Tracking,
        "{=str}: not tracking",
        S::NAME
    );
    Ok(())
}

// ---------------------------------------------------------------------------
// Altitude tracker
// ---------------------------------------------------------------------------

fn altitude_config<S: TestScalar>(
    quantum: AltitudeQuantum,
) -> Result<AltitudeTrackerConfig<S>, Failure> {
    match AltitudeTrackerConfig::<S>::default_for(quantum) {
        Ok(c) => Ok(c),
        Err(e) => {
            defmt::error!("{=str}: altitude configuration refused: {}", S::NAME, e);
            Err(Failure)
        }
    }
}

/// The altitude of a climbing intruder: level at 9000 ft, climbing
/// 1500 ft/min (25 ft/s) from t = 20 s to t = 60 s, level at 10 000 ft
/// after; reported in Mode C (rounded to 100 ft) once a second.
fn climb_report(k: u32) -> f64 {
    let t = k as f64;
    let h = 9000.0 + 25.0 * (t - 20.0).clamp(0.0, 40.0);
    100.0 * libm::round(h / 100.0)
}

fn altitude_quantised_climb_vs_f64() -> TestResult {
    altitude_climb::<Wide>()
}

/// The tracker in `S` against f64 on the quantised climb, 80 reports: the
/// same status, class and firmness every scan, and altitude and rate within
/// [`ALTITUDE_TOLERANCE`] (provisional: the tracker's branches compare
/// times, so a derived bound needs the decision margins, not derived
/// yet).
fn altitude_climb<S: TestScalar>() -> TestResult {
    let cs = altitude_config::<S>(AltitudeQuantum::ModeC)?;
    let cf = altitude_config::<f64>(AltitudeQuantum::ModeC)?;
    let mut ts = AltitudeTracker::<S>::new(cs);
    let mut tf = AltitudeTracker::<f64>::new(cf);
    let one = value::<S>(1.0)?;
    let mut worst = [0.0f64; 2];
    for k in 0..80 {
        let z = climb_report(k);
        let (a, b) = (ts.scan(Some(value::<S>(z)?), one), tf.scan(Some(z), 1.0));
        ensure!(
            a.is_ok() && a == b && ts.class() == tf.class() && ts.firmness() == tf.firmness(),
            "{=str} altitude scan {=u32}: native {}, f64 {}",
            S::NAME,
            k,
            a,
            b
        );
        match (ts.estimate(), tf.estimate()) {
            (Some(es), Some(ef)) => {
                worst[0] = worst[0].max(libm::fabs(es.altitude_ft.to_f64() - ef.altitude_ft));
                worst[1] = worst[1].max(libm::fabs(
                    es.vertical_rate_ft_per_s.to_f64() - ef.vertical_rate_ft_per_s,
                ));
            }
            _ => {
                defmt::error!("{=str}: no altitude estimate at scan {=u32}", S::NAME, k);
                return Err(Failure);
            }
        }
    }
    ensure!(
        worst[0] <= ALTITUDE_TOLERANCE && worst[1] <= ALTITUDE_TOLERANCE,
        "{=str} altitude: |dh| {=f64} ft, |dh/dt| {=f64} ft/s beyond {=f64}",
        S::NAME,
        worst[0],
        worst[1],
        ALTITUDE_TOLERANCE
    );
    defmt::println!(
        "       {=str} altitude climb: 80 reports, max |dh| {=f64} ft, |dh/dt| {=f64} ft/s",
        S::NAME,
        worst[0],
        worst[1]
    );
    Ok(())
}

/// Altitude (ft) and rate (ft/s) tolerance of [`altitude_climb`].
const ALTITUDE_TOLERANCE: f64 = 0.05;

// ---------------------------------------------------------------------------
// The TCAS cycle
// ---------------------------------------------------------------------------

fn tcas_cycle_demo_threat_vs_f64() -> TestResult {
    tcas_cycle::<Wide>()
}

/// What one scan of [`tcas_cycle`] decided.
type CycleOutcome = (Option<Advisory>, Option<(RaSense, RaStrength)>, bool);

/// One intruder through the firmware's TCAS cycle in `S`, one scan a second
/// (`IntruderTrack::scan`/`assess`, `CollisionAvoidance::resolve`): the
/// demo's threat, head-on 0.2 NM abeam from 14 NM at 500
/// kt closure, level 300 ft above an own aircraft level at 8000 ft, exact
/// ranges, altitude in 25 ft steps. Calls `each` with the scan's outcome
/// and range estimate (range m, range rate m/s).
fn tcas_cycle_run<S: TestScalar>(
    mut each: impl FnMut(u32, CycleOutcome, Option<(f64, f64)>) -> TestResult,
) -> TestResult {
    let one = value::<S>(1.0)?;
    let own = OwnAircraft::over_sea_level(value::<S>(8000.0)?, S::ZERO);
    let mut cas = CollisionAvoidance::<S>::new();
    let altitude = altitude_config::<S>(AltitudeQuantum::ModeS25)?;
    let mut track = IntruderTrack::<S>::new();
    let closure = 500.0 * KT;
    for k in 0..110u32 {
        let along = 14.0 * NM - closure * k as f64;
        let range = libm::hypot(0.2 * NM, along);
        let reply = Reply {
            range_m: value::<S>(range)?,
            altitude_ft: Some(value::<S>(8300.0)?),
        };
        let (Ok(cycle), Ok(())) = (
            cas.begin_cycle(&own, false),
            track.scan(&altitude, Some(reply), one),
        ) else {
            defmt::error!("{=str}: scan {=u32} refused", S::NAME, k);
            return Err(Failure);
        };
        let Ok(status) = track.assess(&cycle, None, one) else {
            defmt::error!("{=str}: assessment {=u32} refused", S::NAME, k);
            return Err(Failure);
        };
        let threats: heapless::Vec<ThreatGeometry<S>, 1> =
            status.and_then(|s| s.geometry).into_iter().collect();
        let Ok(ra) = cas.resolve(&cycle, &threats, one) else {
            defmt::error!("{=str}: resolution {=u32} refused", S::NAME, k);
            return Err(Failure);
        };
        let range = track
            .range_tracker()
            .estimate()
            .map(|e| (e.range_m.to_f64(), e.range_rate_m_per_s.to_f64()));
        let outcome = (
            status.map(|s| s.advisory),
            ra.advisory.map(|a| (a.sense, a.strength)),
            ra.clear_of_conflict,
        );
        each(k, outcome, range)?;
    }
    Ok(())
}

/// [`tcas_cycle_run`] in `S` against f64: the same outcome every scan (the
/// advisory, the RA's sense and strength, the clear of conflict), an RA
/// down and a clear of conflict at all, and the range track within
/// [`RANGE_TRACK_TOLERANCE`] (provisional, like the altitude tracker's: the
/// range tracker's firmness branches compare residuals, so a derived bound
/// needs their decision margins).
fn tcas_cycle<S: TestScalar>() -> TestResult {
    let mut reference: heapless::Vec<(CycleOutcome, Option<(f64, f64)>), 110> =
        heapless::Vec::new();
    tcas_cycle_run::<f64>(|_, outcome, range| {
        reference.push((outcome, range)).map_err(|_| Failure)
    })?;
    let mut worst = [0.0f64; 2];
    let (mut ra_down, mut coc) = (None, None);
    tcas_cycle_run::<S>(|k, outcome, range| {
        let Some((want, want_range)) = reference.get(k as usize) else {
            return Err(Failure);
        };
        ensure!(
            outcome == *want,
            "{=str} TCAS cycle scan {=u32}: native {}, f64 {}",
            S::NAME,
            k,
            outcome,
            want
        );
        if let (Some(a), Some(b)) = (range, want_range) {
            worst[0] = worst[0].max(libm::fabs(a.0 - b.0));
            worst[1] = worst[1].max(libm::fabs(a.1 - b.1));
        } else {
            ensure!(
                range.is_none() && want_range.is_none(),
                "{=str} TCAS cycle scan {=u32}: range track in one type only",
                S::NAME,
                k
            );
        }
        if ra_down.is_none() && matches!(outcome.1, Some((RaSense::Down, _))) {
            ra_down = Some(k);
        }
        if coc.is_none() && outcome.2 {
            coc = Some(k);
        }
        Ok(())
    })?;
    let (Some(ra), Some(coc)) = (ra_down, coc) else {
        defmt::error!(
            "{=str} TCAS cycle: no RA down or no clear of conflict",
            S::NAME
        );
        return Err(Failure);
    };
    ensure!(
        worst[0] <= RANGE_TRACK_TOLERANCE[0] && worst[1] <= RANGE_TRACK_TOLERANCE[1],
        "{=str} TCAS cycle: |dr| {=f64} m, |dr/dt| {=f64} m/s beyond the tolerance",
        S::NAME,
        worst[0],
        worst[1]
    );
    defmt::println!(
        "       {=str} TCAS cycle: RA down at {=u32} s, clear of conflict at {=u32} s, as f64; max |dr| {=f64} m, |dr/dt| {=f64} m/s",
        S::NAME,
        ra,
        coc,
        worst[0],
        worst[1]
    );
    Ok(())
}

/// Range (m) and range-rate (m/s) tolerance of [`tcas_cycle`].
const RANGE_TRACK_TOLERANCE: [f64; 2] = [0.5, 0.05];

fn altitude_missing_reports_and_bad_input() -> TestResult {
    altitude_gaps::<Wide>()?;
    altitude_gaps::<f64>()
}

/// A track coasts through up to 6 s without reports (default `max_coast`)
/// and becomes non-reporting after that; a new report starts it again.
/// Bad input changes nothing.
fn altitude_gaps<S: TestScalar>() -> TestResult {
    let mut t = AltitudeTracker::<S>::new(altitude_config::<S>(AltitudeQuantum::ModeS25)?);
    let one = value::<S>(1.0)?;
    let n = |v: f64| S::from_f64_lossy(v);
    ensure!(
        t.estimate().is_none() && t.status() == AltitudeStatus::NotReporting,
        "{=str}: new tracker has an altitude",
        S::NAME
    );
    // Never reported: stays non-reporting through missing scans.
    ensure!(
        t.scan(None, one) == Ok(AltitudeStatus::NotReporting),
        "{=str}: missing report on an empty tracker",
        S::NAME
    );
    let expected = [AltitudeStatus::OneReport, AltitudeStatus::Tracking];
    for (k, want) in expected.iter().enumerate() {
        let got = t.scan(Some(n(12_000.0 + 25.0 * k as f64)), one);
        ensure!(
            got == Ok(*want),
            "{=str}: report {=usize}: {}",
            S::NAME,
            k,
            got
        );
    }
    for _ in 0..10 {
        ensure!(
            t.scan(Some(n(12_050.0)), one).is_ok(),
            "{=str}: report refused",
            S::NAME
        );
    }
    // Bad input: refused, state bit-identical.
    let before = t;
    let cases = [
        (Some(n(f64::NAN)), one, FilterError::InvalidMeasurement),
        (Some(n(f64::INFINITY)), one, FilterError::InvalidMeasurement),
        (Some(n(12_000.0)), S::ZERO, FilterError::InvalidInterval),
        (None, S::ZERO, FilterError::InvalidInterval),
        (None, n(-1.0), FilterError::InvalidInterval),
    ];
    for (i, (z, dt, want)) in cases.iter().enumerate() {
        let got = t.scan(*z, *dt);
        ensure!(
            got == Err(*want) && t == before,
            "{=str}: bad input {=usize}: {}, want {}",
            S::NAME,
            i,
            got,
            want
        );
    }
    // Six seconds of missing reports: coasting, altitude still known.
    for k in 0..6 {
        let got = t.scan(None, one);
        ensure!(
            got == Ok(AltitudeStatus::Tracking) && t.estimate().is_some(),
            "{=str}: coast {=u32}: {}",
            S::NAME,
            k,
            got
        );
    }
    ensure!(
        libm::fabs(t.since_last_report().to_f64() - 6.0) < 1e-6,
        "{=str}: since last report {}",
        S::NAME,
        t.since_last_report()
    );
    // The seventh: beyond max_coast, the altitude is forgotten.
    let got = t.scan(None, one);
    ensure!(
        got == Ok(AltitudeStatus::NotReporting) && t.estimate().is_none(),
        "{=str}: 7 s without reports: {}",
        S::NAME,
        got
    );
    let got = t.scan(Some(n(12_300.0)), one);
    ensure!(
        got == Ok(AltitudeStatus::OneReport)
            && t.estimate().map(|e| e.altitude_ft) == Some(n(12_300.0)),
        "{=str}: restart: {}",
        S::NAME,
        got
    );
    ensure!(t.saturations() == 0, "{=str}: saturations", S::NAME);
    Ok(())
}

// ---------------------------------------------------------------------------
// TCAS threat assessment
// ---------------------------------------------------------------------------

/// Own aircraft level at `own_alt` ft; the intruder at relative position `p`
/// (m) with relative velocity `v` (m/s), and its altitude and vertical rate
/// (ft, ft/s) if it reports one.
fn assess_at<S: TestScalar>(
    own_alt: f64,
    p: [f64; 2],
    v: [f64; 2],
    altitude: Option<(f64, f64)>,
) -> Result<ThreatAssessment<S>, Failure> {
    let c = |x: f64| S::from_f64_lossy(x);
    let own = OwnAircraft::over_sea_level(c(own_alt), S::ZERO);
    let intruder = Intruder {
        relative_position_m: [c(p[0]), c(p[1])],
        relative_velocity_m_per_s: [c(v[0]), c(v[1])],
        altitude: altitude.map(|(a, r)| AltitudeEstimate {
            altitude_ft: c(a),
            vertical_rate_ft_per_s: c(r),
        }),
    };
    match assess(&own, &intruder) {
        Ok(a) => Ok(a),
        Err(e) => {
            defmt::error!("{=str}: assessment refused: {}", S::NAME, e);
            Err(Failure)
        }
    }
}

// Head-on at 600 kt closure, same altitude, own altitude 8000 ft (SL 5:
// TA tau 40 s, DMOD 0.75 NM; RA tau 25 s, DMOD 0.55 NM). With the closure
// c = 600 kt = 1/6 NM/s, τ_mod = (r² − DMOD²)/(r·c) = TAU is the quadratic
// r² − TAU·c·r − DMOD² = 0, r = (TAU·c + √((TAU·c)² + 4·DMOD²))/2:
//   TA: TAU·c = 20/3 NM, (20/3)² + 4·0.5625 = 420.25/9, √ = 20.5/3,
//       r = (20/3 + 20.5/3)/2 = 6.75 NM;
//   RA: TAU·c = 25/6 = 4.166 667 NM, (25/6)² + 4·0.3025 = 18.571 111,
//       √ = 4.309 421, r = (4.166 667 + 4.309 421)/2 = 4.238 044 NM.
const TA_START_NM: f64 = 6.75;
const RA_START_NM: f64 = 4.238_044;
const HEAD_ON_CLOSURE: f64 = 600.0 * KT;

fn head_on<S: TestScalar>(r: f64) -> Result<ThreatAssessment<S>, Failure> {
    assess_at::<S>(
        8000.0,
        [0.0, r],
        [0.0, -HEAD_ON_CLOSURE],
        Some((8000.0, 0.0)),
    )
}

fn tcas_head_on_golden() -> TestResult {
    head_on_golden::<Wide>()?;
    head_on_golden::<f64>()
}

fn head_on_golden<S: TestScalar>() -> TestResult {
    let a = head_on::<S>(TA_START_NM * NM)?;
    let ta_tau = a.ta_modified_tau_s.map(|t| t.to_f64());
    ensure!(
        a.sensitivity == SensitivityLevel::Sl5
            && ta_tau.is_some_and(|t| libm::fabs(t - 40.0) < 1e-3),
        "{=str}: at 6.75 NM: {}, TA tau_mod {}",
        S::NAME,
        a.sensitivity,
        ta_tau
    );
    // One metre either side of each boundary (3.2 ms of closure).
    let around = |r: f64| -> Result<(Advisory, Advisory), Failure> {
        Ok((
            head_on::<S>(r + 1.0)?.advisory,
            head_on::<S>(r - 1.0)?.advisory,
        ))
    };
    let ta = around(TA_START_NM * NM)?;
    ensure!(
        ta == (Advisory::None, Advisory::Traffic),
        "{=str}: around 6.75 NM: {}",
        S::NAME,
        ta
    );
    let a = head_on::<S>(RA_START_NM * NM)?;
    let ra_tau = a.ra_modified_tau_s.map(|t| t.to_f64());
    ensure!(
        ra_tau.is_some_and(|t| libm::fabs(t - 25.0) < 1e-3),
        "{=str}: RA tau_mod at 4.238 NM: {}",
        S::NAME,
        ra_tau
    );
    let ra = around(RA_START_NM * NM)?;
    ensure!(
        ra == (Advisory::Traffic, Advisory::Resolution),
        "{=str}: around 4.238 NM: {}",
        S::NAME,
        ra
    );
    // At 6 NM: range tau = 6 NM / (1/6 NM/s) = 36 s; t_cpa = 36 s, d_cpa = 0.
    let a = head_on::<S>(6.0 * NM)?;
    let tau = a.range_tau_s.map(|t| t.to_f64());
    let cpa = a
        .closest_approach
        .map(|c| (c.time_s.to_f64(), c.distance_m.to_f64()));
    ensure!(
        tau.is_some_and(|t| libm::fabs(t - 36.0) < 1e-3)
            && cpa.is_some_and(|(t, d)| libm::fabs(t - 36.0) < 1e-3 && libm::fabs(d) < 1e-2),
        "{=str}: at 6 NM: tau {}, cpa {}",
        S::NAME,
        tau,
        cpa
    );
    // Scans every second from 8 NM: the first TA and RA come within one
    // scan (308.67 m) inside the boundaries.
    let (mut first_ta, mut first_ra) = (None, None);
    for k in 0..200 {
        let r = 8.0 * NM - HEAD_ON_CLOSURE * k as f64;
        if r < 0.0 {
            break;
        }
        let adv = head_on::<S>(r)?.advisory;
        if adv >= Advisory::Traffic && first_ta.is_none() {
            first_ta = Some(r);
        }
        if adv == Advisory::Resolution && first_ra.is_none() {
            first_ra = Some(r);
        }
    }
    for (first, boundary) in [(first_ta, TA_START_NM * NM), (first_ra, RA_START_NM * NM)] {
        ensure!(
            first.is_some_and(|r| r <= boundary && r > boundary - HEAD_ON_CLOSURE),
            "{=str}: first alert at {} m, boundary {=f64} m",
            S::NAME,
            first,
            boundary
        );
    }
    Ok(())
}

fn tcas_head_on_through_the_filters() -> TestResult {
    let native = head_on_through_filters::<Wide>()?;
    let reference = head_on_through_filters::<f64>()?;
    ensure!(
        native == reference,
        "{=str}: first TA / RA at scans {} but f64 at {}",
        Wide::NAME,
        native,
        reference
    );
    defmt::println!(
        "       {=str} and f64: first TA at scan {=u32} (r = {=f64} NM), first RA at scan {=u32} (r = {=f64} NM)",
        Wide::NAME,
        native.0,
        (10.0 * NM - HEAD_ON_CLOSURE * native.0 as f64) / NM,
        native.1,
        (10.0 * NM - HEAD_ON_CLOSURE * native.1 as f64) / NM
    );
    Ok(())
}

/// The noiseless head-on through the range–azimuth filter (σ_R = 15 m,
/// q = 1) and the Mode C altitude tracker, 1 s scans from 10 NM: the TA
/// comes at the first scan inside 6.75 NM and the RA at the first inside
/// 4.238 NM. Returns the scan numbers of both.
fn head_on_through_filters<S: TestScalar>() -> Result<(u32, u32), Failure> {
    let c = |x: f64| S::from_f64_lossy(x);
    let (Ok(noise), Ok(config)) = (
        RangeAzimuthNoise::<S>::paper_bearing_f64(225.0, 1.0),
        AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC),
    ) else {
        defmt::error!("{=str}: configuration refused", S::NAME);
        return Err(Failure);
    };
    let mut track = RangeAzimuthFilter::new(noise);
    let mut altitude = AltitudeTracker::<S>::new(config);
    let own = OwnAircraft::over_sea_level(c(8000.0), S::ZERO);
    let mut first_ta = None;
    for k in 0..200u32 {
        let r = 10.0 * NM - HEAD_ON_CLOSURE * k as f64;
        let (a, b) = (
            track.update(c(r), S::ZERO, S::ONE),
            altitude.scan(Some(c(8000.0)), S::ONE),
        );
        ensure!(
            a.is_ok() && b.is_ok(),
            "{=str}: scan {=u32} refused: {} {}",
            S::NAME,
            k,
            a.err(),
            b.err()
        );
        if k < 2 {
            continue;
        }
        let advisory = match assess(&own, &Intruder::from_track(&track, altitude.estimate())) {
            Ok(a) => a.advisory,
            Err(e) => {
                defmt::error!("{=str}: assessment refused: {}", S::NAME, e);
                return Err(Failure);
            }
        };
        if advisory >= Advisory::Traffic && first_ta.is_none() {
            ensure!(
                r <= TA_START_NM * NM && r > TA_START_NM * NM - HEAD_ON_CLOSURE,
                "{=str}: first TA at r = {=f64} m",
                S::NAME,
                r
            );
            first_ta = Some(k);
        }
        if advisory == Advisory::Resolution {
            ensure!(
                r <= RA_START_NM * NM && r > RA_START_NM * NM - HEAD_ON_CLOSURE,
                "{=str}: first RA at r = {=f64} m",
                S::NAME,
                r
            );
            if let Some(ta) = first_ta {
                return Ok((ta, k));
            }
        }
    }
    defmt::error!("{=str}: no RA", S::NAME);
    Err(Failure)
}

fn tcas_diverging_intruder_never_alerts() -> TestResult {
    diverging::<Wide>()?;
    diverging::<f64>()
}

/// From 2 NM opening at 300 kt, same altitude: no tau, never a TA or RA;
/// proximate traffic while within 6 NM (4 NM at 300 kt: 48 s), none after.
fn diverging<S: TestScalar>() -> TestResult {
    for k in 0..=60 {
        let t = k as f64;
        let a = assess_at::<S>(
            8000.0,
            [0.0, 2.0 * NM + 300.0 * KT * t],
            [0.0, 300.0 * KT],
            Some((8000.0, 0.0)),
        )?;
        let expected = if t < 48.0 {
            Advisory::ProximateTraffic
        } else if t > 48.0 {
            Advisory::None
        } else {
            a.advisory // exactly 6 NM: either side is right
        };
        ensure!(
            a.range_tau_s.is_none()
                && a.ta_modified_tau_s.is_none()
                && a.ra_modified_tau_s.is_none()
                && a.advisory == expected,
            "{=str}: t = {=f64} s: {}, want {}",
            S::NAME,
            t,
            a.advisory,
            expected
        );
    }
    Ok(())
}

fn tcas_non_reporting_intruder_at_most_ta() -> TestResult {
    non_reporting::<Wide>()?;
    non_reporting::<f64>()
}

/// The head-on without an altitude: the TA starts at the same range (no
/// vertical test), never an RA (TCAS issues none against an intruder whose
/// altitude is unknown), down to 0.05 NM.
fn non_reporting<S: TestScalar>() -> TestResult {
    let at = |r: f64| assess_at::<S>(8000.0, [0.0, r], [0.0, -HEAD_ON_CLOSURE], None);
    ensure!(
        at(TA_START_NM * NM + 1.0)?.advisory == Advisory::None
            && at(TA_START_NM * NM - 1.0)?.advisory == Advisory::Traffic,
        "{=str}: non-reporting TA boundary",
        S::NAME
    );
    for r in [4.0, 2.0, 1.0, 0.5, 0.05] {
        let a = at(r * NM)?;
        ensure!(
            a.advisory == Advisory::Traffic && a.vertical.is_none(),
            "{=str}: non-reporting at {=f64} NM: {}",
            S::NAME,
            r,
            a.advisory
        );
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Track table
// ---------------------------------------------------------------------------

/// Table capacity used on target: 8 tracks, 8 measurements per scan. The
/// micro:bit has 16 KiB of RAM; the tests below hold a table in `S` and
/// one in f64 at once (2.6 KB each for Q32.32, documented formula in
/// [`track_table_sizes_match_documentation`]). Tables are made as
/// constants (`const { Table::new() }`, copied into place): `new()` called
/// at run time builds the table in its own frame first, twice the table on
/// the stack.
const TRACKS: usize = 8;
const PER_SCAN: usize = 8;

type Table<S> = TrackTable<S, FixedGainTrack<S>, TRACKS, PER_SCAN>;
type Config<S> = TrackerConfig<S, Gains<S>>;

/// The host tests' default configuration (host-tests/tests/it/track/support.rs):
/// α = 0.5, β = 0.2; uncertainty gate σ = 5 m, G = 13.8 (99.9 %),
/// a_max = 5 m/s²; v_max = 300 m/s; confirmation 2 of 3, deletion after
/// 3 / 2 misses.
fn track_config<S: Numeric>() -> Result<Config<S>, Failure> {
    let gains = Gains::<S>::alpha_beta_f64(0.5, 0.2);
    let gate = Gate::uncertainty(quantity(5.0)?, quantity(13.8)?, quantity(5.0)?);
    match (gains, gate) {
        (Ok(g), Ok(gate)) => match TrackerConfig::new(g, gate, quantity(300.0)?) {
            Ok(c) => Ok(c),
            Err(e) => {
                defmt::error!("{=str}: tracker configuration refused: {}", S::NAME, e);
                Err(Failure)
            }
        },
        _ => {
            defmt::error!("{=str}: gains or gate refused", S::NAME);
            Err(Failure)
        }
    }
}

/// Bytes per table of `S` as `docs/track-table.md` documents them, rounded
/// up to a multiple of 8: f64 and Q32.32: 140 + 151·N + 157·M; f32: 112 +
/// 115·N + 117·M; the scaled format: 134 + 143·N + 149·M.
fn documented_table_bytes<S: Scalar>(n: usize, m: usize) -> usize {
    let bytes = match S::NAME {
        "f32" => 112 + 115 * n + 117 * m,
        "scaled" => 134 + 143 * n + 149 * m,
        _ => 140 + 151 * n + 157 * m,
    };
    bytes.div_ceil(8) * 8
}

fn track_table_sizes_match_documentation() -> TestResult {
    let sizes = [
        (
            "TrackTable<native, FixedGainTrack, 8, 8>",
            size_of::<Table<Wide>>(),
            documented_table_bytes::<Wide>(8, 8),
        ),
        (
            "TrackTable<f64, FixedGainTrack, 8, 8>",
            size_of::<Table<f64>>(),
            documented_table_bytes::<f64>(8, 8),
        ),
        (
            "TrackTable<native, FixedGainTrack, 16, 16>",
            size_of::<TrackTable<Wide, FixedGainTrack<Wide>, 16, 16>>(),
            documented_table_bytes::<Wide>(16, 16),
        ),
        (
            "TrackTable<f64, FixedGainTrack, 16, 16>",
            size_of::<TrackTable<f64, FixedGainTrack<f64>, 16, 16>>(),
            documented_table_bytes::<f64>(16, 16),
        ),
    ];
    for (name, got, documented) in sizes {
        defmt::println!(
            "       size_of {=str} = {=usize} bytes (documented {=usize})",
            name,
            got,
            documented
        );
        ensure!(
            got == documented,
            "{=str}: {=usize} bytes, documented {=usize}",
            name,
            got,
            documented
        );
    }
    let slot = size_of::<TrackSlot<Wide, FixedGainTrack<Wide>>>();
    let documented_slot = match Wide::NAME {
        "f32" => 60,
        "scaled" => 88,
        _ => 96,
    };
    ensure!(
        slot == documented_slot,
        "track slot {=usize} bytes, documented {=usize}",
        slot,
        documented_slot
    );
    defmt::println!(
        "       size_of per track slot TrackSlot<native, FixedGainTrack> = {=usize}, TrackerConfig<native> = {=usize}, RangeAzimuthFilter<native> = {=usize}, AltitudeTracker<native> = {=usize}, ThreatAssessment<native> = {=usize} bytes",
        slot,
        size_of::<Config<Wide>>(),
        size_of::<RangeAzimuthFilter<Wide>>(),
        size_of::<AltitudeTracker<Wide>>(),
        size_of::<ThreatAssessment<Wide>>()
    );
    Ok(())
}

/// Scan times (ms) with a varying interval: 0, 1000, 1700, 3000, 4000, ...
fn scan_time(k: u32) -> u32 {
    let steps = [1000u32, 700, 1300, 1000];
    (0..k).map(|i| steps[(i % 4) as usize]).sum()
}

/// Two targets on an X (host-tests `tests/it/track/crossing.rs`): both move +100 m/s
/// in x, one +10 m/s and the other −10 m/s in y; they meet at (0, 0) at
/// t = 10.5 s. Noise uniform ±2 m per axis.
fn crossing_scan(k: u32, rng: &mut Lcg) -> [(f64, f64); 2] {
    let t = scan_time(k) as f64 / 1000.0;
    let x = -1050.0 + 100.0 * t;
    let mut n = || rng.uniform(-2.0, 2.0);
    [
        (x + n(), -105.0 + 10.0 * t + n()),
        (x + n(), 105.0 - 10.0 * t + n()),
    ]
}

/// A quantity of any number system (a length, a ratio, ...).
fn quantity<Q: abtrack::num::Quantity>(v: f64) -> Result<Q, Failure> {
    Q::try_from_f64(v).map_err(|e| {
        defmt::error!("{=f64} not representable: {}", v, e);
        Failure
    })
}

fn cartesian<S: Numeric>(x: f64, y: f64) -> Result<Measurement<S>, Failure> {
    Ok(Measurement::Cartesian {
        x: quantity(x)?,
        y: quantity(y)?,
    })
}

/// Runs one scan of f64 measurements through the table in `S`.
fn scan_table<S: Numeric>(
    table: &mut Table<S>,
    config: &Config<S>,
    now_ms: u32,
    points: &[(f64, f64)],
    codes: &mut [Association; PER_SCAN],
) -> Result<ScanReport, Failure> {
    let mut m = [Measurement::Cartesian {
        x: <S::Length as abtrack::num::Quantity>::ZERO,
        y: <S::Length as abtrack::num::Quantity>::ZERO,
    }; PER_SCAN];
    let n = points.len().min(PER_SCAN);
    for (slot, &(x, y)) in m.iter_mut().zip(points) {
        *slot = cartesian::<S>(x, y)?;
    }
    match table.scan(config, now_ms, &m[..n], codes) {
        Ok(r) => Ok(r),
        Err(e) => {
            defmt::error!("{=str}: scan at {=u32} ms refused: {}", S::NAME, now_ms, e);
            Err(Failure)
        }
    }
}

fn track_crossing_targets_keep_ids() -> TestResult {
    let mut native = const { Table::<Wide>::new() };
    let mut reference = const { Table::<f64>::new() };
    crossing_keeps_ids(&mut native, &mut reference)
}

/// Scan 1 starts both tracks; every later scan updates each with its own
/// target, including the scans near the crossing where both measurements
/// lie in both gates (4 gated pairs) and the optimal assignment decides; at
/// the end both are confirmed and head their own way. The native table's
/// codes and per-stage counts equal the f64 table's at every scan.
fn crossing_keeps_ids<N: Numeric>(native: &mut Table<N>, reference: &mut Table<f64>) -> TestResult {
    let (cn, cf) = (track_config::<N>()?, track_config::<f64>()?);
    let mut rng = Lcg::new(2024);
    let mut ids = None;
    let mut contested = 0u32;
    for k in 0..22u32 {
        let points = crossing_scan(k, &mut rng);
        let mut codes_n = [Association::OutsideGates; PER_SCAN];
        let mut codes_f = [Association::OutsideGates; PER_SCAN];
        let now = scan_time(k);
        let rn = scan_table(native, &cn, now, &points, &mut codes_n)?;
        let rf = scan_table(reference, &cf, now, &points, &mut codes_f)?;
        ensure!(
            codes_n[..2] == codes_f[..2] && rn == rf,
            "scan {=u32}: native codes {} report {}, f64 codes {} report {}",
            k,
            codes_n[..2],
            rn,
            codes_f[..2],
            rf
        );
        if rn.gated_pairs == 4 {
            contested += 1;
        }
        match (k, codes_n[0], codes_n[1], ids) {
            (0, Association::OutsideGates, Association::OutsideGates, None) => {}
            (1, Association::Started(a), Association::Started(b), None) => ids = Some((a, b)),
            (_, Association::Updated(a), Association::Updated(b), Some((ia, ib)))
                if k >= 2 && a == ia && b == ib && rn.started == 0 => {}
            (_, a, b, _) => {
                defmt::error!("scan {=u32}: codes {} {} (ids {})", k, a, b, ids);
                return Err(Failure);
            }
        }
    }
    ensure!(contested >= 2, "only {=u32} contested scans", contested);
    let Some((a, b)) = ids else {
        return Err(Failure);
    };
    let mut tracks = native.tracks();
    let (ta, tb) = (tracks.next(), tracks.next());
    let ok = matches!((ta, tb), (Some(ta), Some(tb))
        if ta.id() == a && tb.id() == b
            && ta.status() == TrackStatus::Confirmed
            && tb.status() == TrackStatus::Confirmed
            && abtrack::num::Quantity::to_f64(ta.velocity()[1]) > 5.0
            && abtrack::num::Quantity::to_f64(tb.velocity()[1]) < -5.0);
    ensure!(
        ok && native.len() == 2,
        "after the crossing the tracks are not ({}, confirmed, vy > 0) and ({}, confirmed, vy < 0)",
        a,
        b
    );
    defmt::println!(
        "       {=str}: ids {} and {} kept through {=u32} contested scans; codes and per-stage counts equal to f64 on all 22 scans",
        <N as abtrack::num::Numeric>::NAME,
        a,
        b,
        contested
    );
    Ok(())
}

/// The crossing and the cluttered scenarios in the fast fixed point
/// ([`Fixed32`], the stand-alone table's format on cores without an FPU):
/// the same codes and per-stage counts as f64 at every scan.
#[cfg(not(abtrack_board = "microbit"))]
fn track_fast_fixed_point_same_codes_as_f64() -> TestResult {
    let mut fixed = const { Table::<Fixed32>::new() };
    let mut reference = const { Table::<f64>::new() };
    crossing_keeps_ids(&mut fixed, &mut reference)?;
    let mut fixed = const { Table::<Fixed32>::new() };
    let mut reference = const { Table::<f64>::new() };
    cluttered_same_codes(&mut fixed, &mut reference)
}

fn track_cluttered_scans_same_codes_as_f64() -> TestResult {
    let mut native = const { Table::<Wide>::new() };
    let mut reference = const { Table::<f64>::new() };
    cluttered_same_codes(&mut native, &mut reference)
}

/// Three targets (one missed every 7th scan, one turning) and 5 clutter
/// points per scan over a 6 km square, 40 scans (host-tests
/// `tests/it/track/crossing.rs`, on an 8-track table): clutter starts tentative
/// tracks, most are deleted, the table fills at times. The association code
/// of every measurement and the per-stage counts (solver steps included)
/// must equal f64's at every scan.
fn cluttered_same_codes<N: Numeric>(
    native: &mut Table<N>,
    reference: &mut Table<f64>,
) -> TestResult {
    let (cn, cf) = (track_config::<N>()?, track_config::<f64>()?);
    let mut rng = Lcg::new(99);
    let mut totals = ScanReport::default();
    for k in 0..40u32 {
        let t = scan_time(k) as f64 / 1000.0;
        let mut points = [(0.0, 0.0); PER_SCAN];
        let mut n = 0;
        let mut push = |p: (f64, f64)| {
            if let Some(slot) = points.get_mut(n) {
                *slot = p;
                n += 1;
            }
        };
        let mut noise = |a: f64| rng.uniform(-a, a);
        if k % 7 != 3 {
            push((-2000.0 + 80.0 * t + noise(3.0), 500.0 + noise(3.0)));
        }
        push((
            1500.0 - 60.0 * t + noise(3.0),
            -1500.0 + 60.0 * t + noise(3.0),
        ));
        let w = 0.5 + t / 57.3;
        let (s, c) = libm::sincos(w);
        push((1500.0 * c + noise(3.0), 1500.0 * s + noise(3.0)));
        for _ in 0..5 {
            push((noise(3000.0), noise(3000.0)));
        }
        let Some(points) = points.get(..n) else {
            defmt::error!(
                "scan {=u32}: {=usize} points counted in {=usize} slots",
                k,
                n,
                PER_SCAN
            );
            return Err(Failure);
        };
        let mut codes_n = [Association::OutsideGates; PER_SCAN];
        let mut codes_f = [Association::OutsideGates; PER_SCAN];
        let now = scan_time(k);
        let rn = scan_table(native, &cn, now, points, &mut codes_n)?;
        let rf = scan_table(reference, &cf, now, points, &mut codes_f)?;
        ensure!(
            codes_n == codes_f && rn == rf,
            "scan {=u32}: native codes {} report {}, f64 codes {} report {}",
            k,
            codes_n,
            rn,
            codes_f,
            rf
        );
        totals.started += rn.started;
        totals.confirmed += rn.confirmed;
        totals.deleted += rn.deleted;
        totals.refused_table_full += rn.refused_table_full;
        totals.gated_pairs += rn.gated_pairs;
        totals.not_assigned += rn.not_assigned;
        totals.solver_steps += rn.solver_steps;
    }
    ensure!(
        totals.started > 3 && totals.deleted > 0 && totals.confirmed >= 3,
        "scenario too easy: {}",
        totals
    );
    defmt::println!(
        "       {=str}: 40 scans, same codes and counts as f64: {=u32} tracks started, {=u32} confirmed, {=u32} deleted, {=u32} refused (table full), {=u32} gated pairs, {=u32} not assigned",
        <N as abtrack::num::Numeric>::NAME,
        totals.started,
        totals.confirmed,
        totals.deleted,
        totals.refused_table_full,
        totals.gated_pairs,
        totals.not_assigned
    );
    Ok(())
}

fn track_full_table_refuses_and_counts() -> TestResult {
    let mut table = const { SmallTable::<Wide>::new() };
    full_table(&mut table)
}

/// A table of 4 tracks (8 measurements per scan), so that a scan can hold
/// more targets than the table.
type SmallTable<S> = TrackTable<S, FixedGainTrack<S>, 4, PER_SCAN>;

/// Six targets 2 km apart flying in parallel on a 4-track table. Scan 1
/// starts 4 tracks and refuses the other 2 (`Dropped(TableFull)`, counted
/// in the report and the lifetime stats). A refused candidate is used up:
/// its measurement is outside every gate again in the next scan (a first
/// point), pairs the scan after and is refused again, so from scan 2 on the
/// two extra targets alternate between `OutsideGates` and `Dropped`. The 4
/// tracks keep their ids, are confirmed, and are never evicted.
fn full_table(table: &mut SmallTable<Wide>) -> TestResult {
    let config = track_config::<Wide>()?;
    let mut ids = [TrackId::new(0); 4];
    for k in 0..9u32 {
        let t = scan_time(k) as f64 / 1000.0;
        let mut m = [Measurement::Cartesian {
            x: Wide::ZERO,
            y: Wide::ZERO,
        }; 6];
        for (i, slot) in m.iter_mut().enumerate() {
            *slot = cartesian::<Wide>(2000.0 * i as f64, 50.0 * t)?;
        }
        let mut codes = [Association::OutsideGates; 6];
        let report = match table.scan(&config, scan_time(k), &m, &mut codes) {
            Ok(r) => r,
            Err(e) => {
                defmt::error!("full table scan {=u32}: {}", k, e);
                return Err(Failure);
            }
        };
        let extra = if k == 0 || k % 2 == 0 {
            Association::OutsideGates
        } else {
            Association::Dropped(DropReason::TableFull)
        };
        ensure!(
            codes[4..] == [extra; 2] && report.refused_table_full == if k % 2 == 1 { 2 } else { 0 },
            "scan {=u32}: extra targets {}, report {}",
            k,
            codes[4..],
            report
        );
        for (i, c) in codes[..4].iter().enumerate() {
            let ok = match (k, c) {
                (0, Association::OutsideGates) => true,
                (1, Association::Started(id)) => {
                    ids[i] = *id;
                    true
                }
                (_, Association::Updated(id)) => k >= 2 && *id == ids[i],
                _ => false,
            };
            ensure!(ok, "scan {=u32} measurement {=usize}: {}", k, i, c);
        }
    }
    let kept = table
        .tracks()
        .zip(ids.iter())
        .all(|(t, id)| t.id() == *id && t.is_confirmed());
    // Refused at scans 1, 3, 5, 7: 2 each.
    ensure!(
        kept && table.is_full() && table.stats().refused_table_full == 8,
        "tracks evicted or refusals not counted: full {=bool}, refused {=u32}",
        table.is_full(),
        table.stats().refused_table_full
    );
    defmt::println!(
        "       {=str}: 4-track table, 6 targets: {=u32} candidates refused and counted over 9 scans, no track evicted",
        Wide::NAME,
        table.stats().refused_table_full
    );
    Ok(())
}

fn track_bad_measurements_rejected() -> TestResult {
    let mut table = const { Table::<Wide>::new() };
    bad_measurements(&mut table)
}

/// Bad numbers are rejected with a reason and touch no track; a scan that
/// is not after the previous one is refused and changes nothing.
fn bad_measurements(table: &mut Table<Wide>) -> TestResult {
    let config = track_config::<Wide>()?;
    let n = |v: f64| Wide::from_f64_lossy(v);
    // Two scans of one target: a tentative track.
    for k in 0..2u32 {
        let t = scan_time(k) as f64 / 1000.0;
        let mut codes = [Association::OutsideGates; PER_SCAN];
        scan_table(
            table,
            &config,
            scan_time(k),
            &[(100.0 * t, 0.0)],
            &mut codes,
        )?;
    }
    ensure!(table.len() == 1, "no track started");
    let track_before = table.tracks().next().map(|t| (t.id(), t.position()));
    let rejected_before = table.stats().rejected;
    let bad = [
        (
            Measurement::Cartesian {
                x: n(f64::NAN),
                y: n(0.0),
            },
            RejectReason::NotFinite,
        ),
        (
            Measurement::Cartesian {
                x: n(0.0),
                y: n(f64::INFINITY),
            },
            RejectReason::NotFinite,
        ),
        (
            Measurement::Polar {
                range: n(-5.0),
                azimuth: n(0.3),
            },
            RejectReason::NegativeRange,
        ),
        (
            Measurement::Polar {
                range: n(500.0),
                azimuth: n(f64::NAN),
            },
            RejectReason::NotFinite,
        ),
    ];
    let mut m = [Measurement::Cartesian {
        x: n(0.0),
        y: n(0.0),
    }; 4];
    for (slot, (b, _)) in m.iter_mut().zip(bad.iter()) {
        *slot = *b;
    }
    // A scan that is not after the last one: refused, nothing written.
    let mut codes = [Association::OutsideGates; PER_SCAN];
    let refused = table.scan(&config, scan_time(1), &m, &mut codes);
    ensure!(
        matches!(refused, Err(ScanError::TimeNotIncreasing { .. }))
            && codes == [Association::OutsideGates; PER_SCAN]
            && table.stats().rejected == rejected_before,
        "repeated scan time: {}",
        refused
    );
    let report = match table.scan(&config, scan_time(2), &m, &mut codes) {
        Ok(r) => r,
        Err(e) => {
            defmt::error!("scan refused: {}", e);
            return Err(Failure);
        }
    };
    for (i, (_, reason)) in bad.iter().enumerate() {
        ensure!(
            codes[i] == Association::Rejected(*reason),
            "bad measurement {=usize}: {}, want Rejected({})",
            i,
            codes[i],
            reason
        );
    }
    ensure!(
        report.rejected == 4
            && table.stats().rejected == rejected_before + 4
            && report.updated == 0
            && report.coasted == 1,
        "report {}",
        report
    );
    // The track only coasted: same id, moved by its own prediction.
    let after = table.tracks().next().map(|t| t.id());
    ensure!(
        after == track_before.map(|(id, _)| id),
        "track changed identity"
    );
    // More measurements than the table takes per scan: the excess is
    // dropped and counted.
    let mut many = [Measurement::Cartesian {
        x: n(-30_000.0),
        y: n(0.0),
    }; PER_SCAN + 1];
    for (i, slot) in many.iter_mut().enumerate() {
        *slot = cartesian::<Wide>(-30_000.0 + 1000.0 * i as f64, 20_000.0)?;
    }
    let mut codes = [Association::OutsideGates; PER_SCAN + 1];
    let report = match table.scan(&config, scan_time(3), &many, &mut codes) {
        Ok(r) => r,
        Err(e) => {
            defmt::error!("scan refused: {}", e);
            return Err(Failure);
        }
    };
    ensure!(
        codes[PER_SCAN] == Association::Dropped(DropReason::ScanOverflow)
            && report.dropped_overflow == 1
            && table.stats().dropped_overflow == 1,
        "scan overflow: {} {}",
        codes[PER_SCAN],
        report
    );
    Ok(())
}
