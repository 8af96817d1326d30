//! Group `tcas-advisory`. The encounter suite ([`encounter_suite`]): the
//! encounter suite against the independent reference and the altitude
//! tracker's figures. Below: the TCAS-realistic encounter
//! `tcas-converging`
//! (see [`crate::scenario`]: own aircraft level at 8000 ft, SL 5; intruder
//! head-on from 14 NM with a 0.2 NM offset, 500 kt closure, climbing from
//! 7500 ft to co-altitude at closest approach (t = 100.8 s); 1 s updates,
//! range σ 50 ft, bearing σ 5°, Mode C altitude), 100 Monte Carlo runs.
//!
//! Each scan the intruder is tracked with the range–azimuth filter
//! (`abtrack::filter::range_azimuth`, σ_R² and σ_B² of the sensor, process
//! noise σ_a) and the Mode C altitude tracker
//! (`abtrack::filter::altitude`, its documented defaults), and
//! `abtrack::tcas::assess` turns the track into range tau, modified tau,
//! t_cpa, d_cpa and the advisory level. The same assessment of the *true*
//! relative state (true altitude and vertical rate) is the reference
//! timeline. The estimated chain runs in f64, f32 and Q32.32 on every run.
//!
//! Process noise: σ_a = [`ACCEL_SIGMAS`]`[0]` = 0.1 m/s² (the scenario's
//! recommended constant-velocity tuning: the truth is a straight line) for
//! the plots; the tables also give σ_a = 1 m/s², a tuning that would follow
//! a manoeuvring intruder, to show how much the timeline depends on it.
//!
//! Also reported: the diagnostic variant of the filter with the range
//! residual R − |p̂| ([`RangeResidualVariant`], f64), and a bearing-noise
//! sensitivity ([`bearing_sensitivity`]: the same runs with the azimuth
//! errors and the filter's σ_B scaled) that shows the estimate's late alerts
//! come from a range-rate bias growing with σ_B².
//!
//! # Definitions
//!
//! * Level L ∈ {TA, RA}: a scan is "at L" when the advisory is at least L
//!   (an RA scan also counts as TA).
//! * Onset: the first scan at L; end: the last scan at L. Delay = estimated
//!   minus true time (positive: the estimate alerts later).
//! * Missed: the truth reaches L and the estimate never does. False alert:
//!   the estimate is at L at a scan more than [`TOLERANCE_S`] from every
//!   scan at which the truth is at L.
//! * Agreement: the fraction of scans whose estimated advisory level equals
//!   the truth's.

use rayon::prelude::*;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::Path;

use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::filter::Phase;
use abtrack::tcas::{assess, Advisory, Intruder, OwnAircraft};
use abtrack::{Fix, Scalar};

use super::common::{fmt_ci, plot, write_file, Context, PlotSpec, Series, Table};

pub mod encounter_suite;
use super::he_tcas::RangeResidualVariant;
use crate::metrics::{mean_ci95, MeanCi};
use crate::scenario::{self, Measurement, TruthState, FOOT};

/// The group's name (`--only tcas-advisory`, `results/tcas-advisory/`).
pub const NAME: &str = "tcas-advisory";
/// The scenario it runs.
pub const SCENARIO: &str = "tcas-converging";
/// Base seed of the Monte Carlo runs.
pub const BASE_SEED: u64 = 0x0004_7CA5_AD71_0004;
/// Range σ the filter assumes (the scenario's 50 ft), m.
pub const RANGE_SIGMA_M: f64 = 50.0 * FOOT;
/// Bearing σ the filter assumes (the scenario's 5°), rad.
pub const BEARING_SIGMA_RAD: f64 = 5.0 * std::f64::consts::PI / 180.0;
/// Process noise levels σ_a (m/s²): the first is the one plotted.
pub const ACCEL_SIGMAS: [f64; 2] = [0.1, 1.0];
/// Tolerance of the false-alert definition and of the "within" counts, s.
pub const TOLERANCE_S: f64 = 3.0;
/// Times at which the threat-measure errors are tabulated, s.
pub const REPORT_TIMES_S: [f64; 6] = [20.0, 40.0, 55.0, 70.0, 85.0, 95.0];

/// Files the group writes into `results/tcas-advisory/`.
pub const FILES: &[&str] = &[
    "onsets.csv",
    "onsets.md",
    "threat_errors.csv",
    "threat_errors.md",
    "numeric_types.csv",
    "numeric_types.md",
    "bearing_sensitivity.csv",
    "bearing_sensitivity.md",
    "timeline_run0.csv",
    "encounters_exact.csv",
    "encounters_exact.md",
    "encounters_noise.csv",
    "encounters_noise.md",
    "altitude_tracker.csv",
    "altitude_tracker.md",
    "range_acceleration.csv",
    "range_acceleration.md",
    "tau_vs_time.svg",
    "tau_mod_vs_time.svg",
    "d_cpa_vs_time.svg",
    "advisory_timeline.svg",
    "alert_fraction_vs_time.svg",
    "summary.md",
];

/// The estimated chains: the library's filter in each arithmetic, and (f64
/// only) the diagnostic variant of the filter whose range residual is
/// R − |p̂| ([`RangeResidualVariant`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Arithmetic {
    F64,
    F32,
    Fix,
    VariantF64,
}

impl Arithmetic {
    /// The library's filter in the three arithmetics.
    pub const ALL: [Arithmetic; 3] = [Arithmetic::F64, Arithmetic::F32, Arithmetic::Fix];
    /// Every chain, in the order of [`RunTimelines::estimated`].
    pub const CHAINS: [Arithmetic; 4] = [
        Arithmetic::F64,
        Arithmetic::F32,
        Arithmetic::Fix,
        Arithmetic::VariantF64,
    ];
    pub fn label(self) -> &'static str {
        match self {
            Arithmetic::F64 => "f64",
            Arithmetic::F32 => "f32",
            Arithmetic::Fix => "Q32.32",
            Arithmetic::VariantF64 => "f64, variant RESID_R = R - r_pred",
        }
    }
    fn index(self) -> usize {
        Arithmetic::CHAINS
            .iter()
            .position(|&a| a == self)
            .unwrap_or(0)
    }
}

/// The threat measures of one scan, in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanThreat {
    pub t: f64,
    pub range_m: f64,
    pub range_rate_m_per_s: f64,
    /// Range tau, s (`None` when diverging).
    pub tau_s: Option<f64>,
    /// Modified tau with the TA DMOD, s.
    pub tau_mod_ta_s: Option<f64>,
    /// Modified tau with the RA DMOD, s.
    pub tau_mod_ra_s: Option<f64>,
    pub t_cpa_s: Option<f64>,
    pub d_cpa_m: Option<f64>,
    pub advisory: Advisory,
}

impl ScanThreat {
    fn empty(t: f64) -> Self {
        ScanThreat {
            t,
            range_m: f64::NAN,
            range_rate_m_per_s: f64::NAN,
            tau_s: None,
            tau_mod_ta_s: None,
            tau_mod_ra_s: None,
            t_cpa_s: None,
            d_cpa_m: None,
            advisory: Advisory::None,
        }
    }
}

/// One Monte Carlo run: the truth's timeline and the estimated one per
/// chain ([`Arithmetic::CHAINS`] order), per σ_a ([`ACCEL_SIGMAS`] order).
#[derive(Debug, Clone, PartialEq)]
pub struct RunTimelines {
    pub truth: Vec<ScanThreat>,
    /// `estimated[sigma][arithmetic][scan]`
    pub estimated: Vec<Vec<Vec<ScanThreat>>>,
    /// Refused filter/tracker updates and failed assessments, per σ_a and
    /// arithmetic (should all be 0).
    pub refused: Vec<Vec<usize>>,
}

#[derive(Debug, Clone, Copy)]
struct Scan {
    t: f64,
    dt: f64,
    range: f64,
    azimuth: f64,
    alt_ft: Option<f64>,
}

fn own_aircraft<S: Scalar>(altitude_ft: f64) -> OwnAircraft<S> {
    OwnAircraft {
        pressure_altitude_ft: S::from_f64_lossy(altitude_ft),
        vertical_rate_ft_per_s: S::ZERO,
        // Above a radio altimeter's range: the level comes from the pressure
        // altitude (SL 5 at 8000 ft).
        radio_altitude_ft: None,
    }
}

fn to_scan_threat<S: Scalar>(t: f64, a: &abtrack::tcas::ThreatAssessment<S>) -> ScanThreat {
    let f = |v: Option<S>| v.map(|v| v.to_f64());
    ScanThreat {
        t,
        range_m: a.range_m.to_f64(),
        range_rate_m_per_s: a.range_rate_m_per_s.to_f64(),
        tau_s: f(a.range_tau_s),
        tau_mod_ta_s: f(a.ta_modified_tau_s),
        tau_mod_ra_s: f(a.ra_modified_tau_s),
        t_cpa_s: a.closest_approach.map(|c| c.time_s.to_f64()),
        d_cpa_m: a.closest_approach.map(|c| c.distance_m.to_f64()),
        advisory: a.advisory,
    }
}

/// The estimated chain (filter, altitude tracker, assessment) in `S`.
fn estimated_timeline<S: Scalar>(
    scans: &[Scan],
    own_alt_ft: f64,
    accel_sigma: f64,
    bearing_sigma: f64,
) -> Result<(Vec<ScanThreat>, usize), String> {
    let noise = RangeAzimuthNoise::<S>::new_f64(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        bearing_sigma * bearing_sigma,
        accel_sigma * accel_sigma,
    )
    .map_err(|e| format!("noise: {e}"))?;
    let mut filter = RangeAzimuthFilter::<S>::new(noise);
    let config = AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC)
        .map_err(|e| format!("altitude tracker: {e}"))?;
    let mut altitude = AltitudeTracker::<S>::new(config);
    let own = own_aircraft::<S>(own_alt_ft);
    let mut out = Vec::with_capacity(scans.len());
    let mut refused = 0;
    for s in scans {
        let c = |v: f64| S::try_from_f64(v).map_err(|e| format!("{} input {v}: {e:?}", S::NAME));
        let dt = c(s.dt)?;
        if filter.update(c(s.range)?, c(s.azimuth)?, dt).is_err() {
            refused += 1;
            let _ = filter.coast(dt);
        }
        let alt = s.alt_ft.map(c).transpose()?;
        if altitude.scan(alt, dt).is_err() {
            refused += 1;
        }
        if filter.phase() == Phase::Empty {
            out.push(ScanThreat::empty(s.t));
            continue;
        }
        match assess(&own, &Intruder::from_track(&filter, altitude.estimate())) {
            Ok(a) => out.push(to_scan_threat(s.t, &a)),
            Err(_) => {
                refused += 1;
                out.push(ScanThreat::empty(s.t));
            }
        }
    }
    Ok((out, refused))
}

/// The diagnostic variant's chain (f64).
fn variant_timeline(
    scans: &[Scan],
    own_alt_ft: f64,
    accel_sigma: f64,
) -> Result<(Vec<ScanThreat>, usize), String> {
    let mut filter = RangeResidualVariant::new(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        BEARING_SIGMA_RAD * BEARING_SIGMA_RAD,
        accel_sigma * accel_sigma,
    );
    let config = AltitudeTrackerConfig::<f64>::default_for(AltitudeQuantum::ModeC)
        .map_err(|e| format!("altitude tracker: {e}"))?;
    let mut altitude = AltitudeTracker::<f64>::new(config);
    let own = own_aircraft::<f64>(own_alt_ft);
    let mut out = Vec::with_capacity(scans.len());
    let mut refused = 0;
    for s in scans {
        filter.update(s.range, s.azimuth, s.dt);
        if altitude.scan(s.alt_ft, s.dt).is_err() {
            refused += 1;
        }
        let intruder = Intruder {
            relative_position_m: filter.position(),
            relative_velocity_m_per_s: filter.velocity(),
            altitude: altitude.estimate(),
        };
        match assess(&own, &intruder) {
            Ok(a) => out.push(to_scan_threat(s.t, &a)),
            Err(_) => {
                refused += 1;
                out.push(ScanThreat::empty(s.t));
            }
        }
    }
    Ok((out, refused))
}

/// The reference timeline: the same assessment of the true relative state
/// (true altitude, vertical rate from consecutive true altitudes).
fn true_timeline(truth: &[TruthState], own_alt_ft: f64) -> Result<Vec<ScanThreat>, String> {
    let own = own_aircraft::<f64>(own_alt_ft);
    truth
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let rate = match (
                truth.get(k + 1),
                k.checked_sub(1).and_then(|j| truth.get(j)),
            ) {
                (Some(n), _) => n.alt_ft.zip(s.alt_ft).map(|(a, b)| (a - b) / (n.t - s.t)),
                (None, Some(p)) => s.alt_ft.zip(p.alt_ft).map(|(a, b)| (a - b) / (s.t - p.t)),
                _ => Some(0.0),
            };
            let intruder = Intruder {
                relative_position_m: [s.x, s.y],
                relative_velocity_m_per_s: [s.vx, s.vy],
                altitude: s.alt_ft.zip(rate).map(|(a, r)| {
                    abtrack::filter::altitude::AltitudeEstimate {
                        altitude_ft: a,
                        vertical_rate_ft_per_s: r,
                    }
                }),
            };
            assess(&own, &intruder)
                .map(|a| to_scan_threat(s.t, &a))
                .map_err(|e| format!("truth assessment at t={}: {e}", s.t))
        })
        .collect()
}

/// The measurements and truth of Monte Carlo run `run`, with the azimuth
/// noise multiplied by `bearing_scale` (1 for the scenario as defined; the
/// same draws scaled, for the bearing-noise sensitivity).
fn load_run(
    base_seed: u64,
    run: usize,
    bearing_scale: f64,
) -> Result<(Vec<Scan>, Vec<TruthState>, f64), String> {
    let info = scenario::info(SCENARIO).ok_or("scenario tcas-converging missing")?;
    let own_alt = info
        .own_altitude_ft
        .ok_or("scenario without own altitude")?;
    let data = scenario::generate(SCENARIO, scenario::monte_carlo_seed(base_seed, run as u64))
        .map_err(|e| e.to_string())?;
    let mut scans = Vec::with_capacity(data.scans.len());
    let mut truth = Vec::with_capacity(data.scans.len());
    let mut prev_t: Option<f64> = None;
    for s in &data.scans {
        let Some(Measurement::Polar {
            range,
            azimuth,
            alt_ft,
            ..
        }) = s.measurements.first().copied()
        else {
            return Err(format!("run {run}: no polar measurement at t={}", s.t));
        };
        let tr = *s.truth.first().ok_or("scan without truth")?;
        let azimuth = if bearing_scale == 1.0 {
            azimuth
        } else {
            let error = (azimuth - tr.azimuth() + PI).rem_euclid(TAU) - PI;
            scenario::wrap_two_pi(tr.azimuth() + bearing_scale * error)
        };
        scans.push(Scan {
            t: s.t,
            dt: prev_t.map_or(info.period_s, |p| s.t - p),
            range,
            azimuth,
            alt_ft,
        });
        prev_t = Some(s.t);
        truth.push(tr);
    }
    Ok((scans, truth, own_alt))
}

/// Runs Monte Carlo run `run` of the scenario.
pub fn simulate_run(base_seed: u64, run: usize) -> Result<RunTimelines, String> {
    let (scans, truth, own_alt) = load_run(base_seed, run, 1.0)?;
    let mut estimated = Vec::new();
    let mut refused = Vec::new();
    for &sigma in &ACCEL_SIGMAS {
        let runs = [
            estimated_timeline::<f64>(&scans, own_alt, sigma, BEARING_SIGMA_RAD)?,
            estimated_timeline::<f32>(&scans, own_alt, sigma, BEARING_SIGMA_RAD)?,
            estimated_timeline::<Fix>(&scans, own_alt, sigma, BEARING_SIGMA_RAD)?,
            variant_timeline(&scans, own_alt, sigma)?,
        ];
        refused.push(runs.iter().map(|r| r.1).collect());
        estimated.push(runs.into_iter().map(|r| r.0).collect());
    }
    Ok(RunTimelines {
        truth: true_timeline(&truth, own_alt)?,
        estimated,
        refused,
    })
}

/// Bearing-noise levels of the sensitivity table, as multiples of the
/// scenario's 5°.
pub const BEARING_SCALES: [f64; 4] = [1.0, 0.5, 0.2, 0.02];

/// One row of the bearing-noise sensitivity: the f64 chain with σ_a =
/// [`ACCEL_SIGMAS`]`[0]` on the scenario's runs with the azimuth noise (and
/// the filter's σ_B) scaled.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingSensitivity {
    pub bearing_sigma_deg: f64,
    /// Per [`REPORT_TIMES_S`]: estimated minus true range rate, m/s.
    pub range_rate_error: Vec<MeanCi>,
    pub ta: OnsetStats,
}

/// Runs the bearing-noise sensitivity for one scale.
pub fn bearing_sensitivity(
    base_seed: u64,
    runs: usize,
    bearing_scale: f64,
) -> Result<BearingSensitivity, String> {
    let mut errors = vec![Vec::new(); REPORT_TIMES_S.len()];
    let mut timelines = Vec::with_capacity(runs);
    for run in 0..runs {
        let (scans, truth, own_alt) = load_run(base_seed, run, bearing_scale)?;
        let (est, _) = estimated_timeline::<f64>(
            &scans,
            own_alt,
            ACCEL_SIGMAS[0],
            bearing_scale * BEARING_SIGMA_RAD,
        )?;
        let truth_timeline = true_timeline(&truth, own_alt)?;
        for (i, &t) in REPORT_TIMES_S.iter().enumerate() {
            if let (Some(e), Some(tr)) = (
                est.iter().find(|s| s.t == t),
                truth_timeline.iter().find(|s| s.t == t),
            ) {
                errors[i].push(e.range_rate_m_per_s - tr.range_rate_m_per_s);
            }
        }
        timelines.push(RunTimelines {
            truth: truth_timeline,
            estimated: vec![vec![est]],
            refused: vec![vec![0]],
        });
    }
    Ok(BearingSensitivity {
        bearing_sigma_deg: bearing_scale * BEARING_SIGMA_RAD.to_degrees(),
        range_rate_error: errors.iter().map(|e| mean_ci95(e)).collect(),
        ta: onset_stats(&timelines, Level::Ta, 0, Arithmetic::F64),
    })
}

/// Runs `runs` Monte Carlo runs, spread over the cores by rayon (results in
/// run order: each run depends only on its seed).
pub fn simulate(base_seed: u64, runs: usize) -> Result<Vec<RunTimelines>, String> {
    (0..runs)
        .into_par_iter()
        .map(|r| simulate_run(base_seed, r))
        .collect()
}

/// The continuous-time onset of a range test (r − DMOD²/r ≤ TAU·closure,
/// with the 10 ft/s closure floor, or r ≤ DMOD) for the straight relative
/// track through `s`, searched in 1 ms steps from `s.t` up to `horizon_s`:
/// the analytic reference for the scan-quantised true onsets.
pub fn continuous_range_test_onset(
    s: &TruthState,
    dmod_m: f64,
    tau_s: f64,
    horizon_s: f64,
) -> Option<f64> {
    let steps = (horizon_s / 1e-3).round() as usize;
    (0..=steps).map(|i| s.t + i as f64 * 1e-3).find(|&t| {
        let d = t - s.t;
        let (x, y) = (s.x + s.vx * d, s.y + s.vy * d);
        let r = x.hypot(y);
        let closure = -(x * s.vx + y * s.vy) / r;
        r <= dmod_m
            || (closure >= 0.0
                && r - dmod_m * dmod_m / r
                    <= tau_s * closure.max(abtrack::tcas::CLOSURE_RATE_FLOOR_M_PER_S))
    })
}

/// Alert level of the onset statistics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    Ta,
    Ra,
}

impl Level {
    pub const ALL: [Level; 2] = [Level::Ta, Level::Ra];
    pub fn label(self) -> &'static str {
        match self {
            Level::Ta => "TA",
            Level::Ra => "RA",
        }
    }
    pub fn reached(self, a: Advisory) -> bool {
        match self {
            Level::Ta => a >= Advisory::Traffic,
            Level::Ra => a == Advisory::Resolution,
        }
    }
}

/// First and last time at a level.
pub fn onset_and_end(timeline: &[ScanThreat], level: Level) -> Option<(f64, f64)> {
    let first = timeline.iter().find(|s| level.reached(s.advisory))?;
    let last = timeline.iter().rev().find(|s| level.reached(s.advisory))?;
    Some((first.t, last.t))
}

/// Scans where the estimate is at `level` more than [`TOLERANCE_S`] away
/// from every scan where the truth is.
pub fn false_alert_scans(truth: &[ScanThreat], estimate: &[ScanThreat], level: Level) -> usize {
    let truth_times: Vec<f64> = truth
        .iter()
        .filter(|s| level.reached(s.advisory))
        .map(|s| s.t)
        .collect();
    estimate
        .iter()
        .filter(|s| level.reached(s.advisory))
        .filter(|s| truth_times.iter().all(|t| (t - s.t).abs() > TOLERANCE_S))
        .count()
}

/// Fraction of scans with the same advisory level.
pub fn agreement(a: &[ScanThreat], b: &[ScanThreat]) -> f64 {
    let same = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.advisory == y.advisory)
        .count();
    same as f64 / a.len().max(1) as f64
}

/// Onset/end statistics of one level over runs.
#[derive(Debug, Clone, PartialEq)]
pub struct OnsetStats {
    pub level: Level,
    pub accel_sigma: f64,
    /// True onset and end, s (the same every run: the truth is fixed).
    pub truth_onset_s: Option<f64>,
    pub truth_end_s: Option<f64>,
    pub onset_delays_s: Vec<f64>,
    pub end_delays_s: Vec<f64>,
    pub missed: usize,
    /// Runs with at least one false-alert scan.
    pub false_alert_runs: usize,
    pub runs: usize,
}

impl OnsetStats {
    pub fn onset_ci(&self) -> MeanCi {
        mean_ci95(&self.onset_delays_s)
    }
    pub fn end_ci(&self) -> MeanCi {
        mean_ci95(&self.end_delays_s)
    }
    /// Runs whose onset is within ±`tol` s of the truth's.
    pub fn onsets_within(&self, tol: f64) -> usize {
        self.onset_delays_s
            .iter()
            .filter(|d| d.abs() <= tol + 1e-9)
            .count()
    }
}

/// Onset statistics of `level` for σ_a index `sigma` and arithmetic `arith`.
pub fn onset_stats(
    runs: &[RunTimelines],
    level: Level,
    sigma: usize,
    arith: Arithmetic,
) -> OnsetStats {
    let ai = arith.index();
    let truth = runs.first().and_then(|r| onset_and_end(&r.truth, level));
    let mut s = OnsetStats {
        level,
        accel_sigma: ACCEL_SIGMAS.get(sigma).copied().unwrap_or(f64::NAN),
        truth_onset_s: truth.map(|t| t.0),
        truth_end_s: truth.map(|t| t.1),
        onset_delays_s: Vec::new(),
        end_delays_s: Vec::new(),
        missed: 0,
        false_alert_runs: 0,
        runs: runs.len(),
    };
    for r in runs {
        let Some(est) = r.estimated.get(sigma).and_then(|e| e.get(ai)) else {
            continue;
        };
        let t = onset_and_end(&r.truth, level);
        match (t, onset_and_end(est, level)) {
            (Some(t), Some(e)) => {
                s.onset_delays_s.push(e.0 - t.0);
                s.end_delays_s.push(e.1 - t.1);
            }
            (Some(_), None) => s.missed += 1,
            _ => {}
        }
        if false_alert_scans(&r.truth, est, level) > 0 {
            s.false_alert_runs += 1;
        }
    }
    s
}

/// Per-run mean agreement of arithmetic `arith` with the truth (σ_a index
/// `sigma`).
pub fn truth_agreement(runs: &[RunTimelines], sigma: usize, arith: Arithmetic) -> MeanCi {
    let ai = arith.index();
    let v: Vec<f64> = runs
        .iter()
        .filter_map(|r| {
            r.estimated
                .get(sigma)?
                .get(ai)
                .map(|e| agreement(&r.truth, e))
        })
        .collect();
    mean_ci95(&v)
}

fn fmt_opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".to_string(), |v| format!("{v:.digits$}"))
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

/// Runs the group with the documented 100 runs (or `--runs`).
pub fn run(ctx: &Context) -> Result<(), String> {
    let info = scenario::info(SCENARIO).ok_or("scenario tcas-converging missing")?;
    let runs = ctx.runs(info.monte_carlo_runs);
    let started = std::time::Instant::now();
    let timelines = simulate(BASE_SEED, runs)?;
    let sensitivity = BEARING_SCALES
        .iter()
        .map(|&scale| bearing_sensitivity(BASE_SEED, runs, scale))
        .collect::<Result<Vec<_>, _>>()?;
    let elapsed = started.elapsed().as_secs_f64();
    let dir = ctx.group_dir(NAME)?;
    let encounter_suite_section = encounter_suite::write(&dir, ctx.runs(encounter_suite::RUNS))?;
    write_outputs(
        &dir,
        &timelines,
        &sensitivity,
        elapsed,
        &encounter_suite_section,
    )
}

fn write_outputs(
    dir: &Path,
    runs: &[RunTimelines],
    sensitivity: &[BearingSensitivity],
    elapsed_s: f64,
    encounter_suite_section: &str,
) -> Result<(), String> {
    let run0 = runs.first().ok_or("no runs")?;
    let n = runs.len();

    let mut bearing = Table::new(
        ["bearing sigma (deg)".to_string()]
            .into_iter()
            .chain(
                REPORT_TIMES_S
                    .iter()
                    .map(|t| format!("range-rate error at t = {t} s (m/s)")),
            )
            .chain([
                "TA onset delay (s)".to_string(),
                "TA missed / false-alert runs".to_string(),
            ]),
    );
    for b in sensitivity {
        let mut row = vec![format!("{:.2}", b.bearing_sigma_deg)];
        row.extend(b.range_rate_error.iter().map(|c| fmt_ci(c, 2)));
        row.push(fmt_ci(&b.ta.onset_ci(), 2));
        row.push(format!("{} / {}", b.ta.missed, b.ta.false_alert_runs));
        bearing.push(row);
    }
    bearing.write(dir, "bearing_sensitivity")?;

    // Onset table.
    let mut onsets = Table::new([
        "sigma_a (m/s2)",
        "arithmetic",
        "level",
        "true onset (s)",
        "onset delay mean ± 95% CI (s)",
        "onset delay min..max (s)",
        format!("onset within ±1 s / ±{TOLERANCE_S} s").as_str(),
        "true end (s)",
        "end delay mean ± 95% CI (s)",
        "missed",
        "runs with false alerts",
        "runs",
    ]);
    for (si, sigma) in ACCEL_SIGMAS.iter().enumerate() {
        for arith in Arithmetic::CHAINS {
            for level in Level::ALL {
                let s = onset_stats(runs, level, si, arith);
                let (lo, hi) = s
                    .onset_delays_s
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &d| {
                        (a.min(d), b.max(d))
                    });
                onsets.push([
                    format!("{sigma}"),
                    arith.label().to_string(),
                    level.label().to_string(),
                    fmt_opt(s.truth_onset_s, 0),
                    fmt_ci(&s.onset_ci(), 2),
                    format!("{lo:+.0}..{hi:+.0}"),
                    format!(
                        "{} / {}",
                        s.onsets_within(1.0),
                        s.onsets_within(TOLERANCE_S)
                    ),
                    fmt_opt(s.truth_end_s, 0),
                    fmt_ci(&s.end_ci(), 2),
                    s.missed.to_string(),
                    s.false_alert_runs.to_string(),
                    s.runs.to_string(),
                ]);
            }
        }
    }
    onsets.write(dir, "onsets")?;

    // Threat-measure errors at fixed times (f64, each σ_a).
    let mut errors = Table::new([
        "sigma_a (m/s2)",
        "t (s)",
        "quantity",
        "true",
        "estimate mean",
        "estimate 5%..95%",
        "RMSE",
    ]);
    type Getter = fn(&ScanThreat) -> Option<f64>;
    let quantities: [(&str, Getter); 5] = [
        ("range tau (s)", |s| s.tau_s),
        ("TA tau_mod (s)", |s| s.tau_mod_ta_s),
        ("range rate (m/s)", |s| Some(s.range_rate_m_per_s)),
        ("t_cpa (s)", |s| s.t_cpa_s),
        ("d_cpa (m)", |s| s.d_cpa_m),
    ];
    for (si, sigma) in ACCEL_SIGMAS.iter().enumerate() {
        for &t in &REPORT_TIMES_S {
            let k = run0.truth.iter().position(|s| (s.t - t).abs() < 1e-9);
            let Some(k) = k else { continue };
            for (label, get) in quantities {
                let truth = get(&run0.truth[k]);
                let mut v: Vec<f64> = runs
                    .iter()
                    .filter_map(|r| get(r.estimated.get(si)?.first()?.get(k)?))
                    .collect();
                v.sort_by(f64::total_cmp);
                let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
                let rmse = truth.map(|tr| {
                    (v.iter().map(|e| (e - tr).powi(2)).sum::<f64>() / v.len().max(1) as f64).sqrt()
                });
                errors.push([
                    format!("{sigma}"),
                    format!("{t:.0}"),
                    label.to_string(),
                    fmt_opt(truth, 2),
                    format!("{mean:.2} ({} of {n} defined)", v.len()),
                    format!("{:.2}..{:.2}", quantile(&v, 0.05), quantile(&v, 0.95)),
                    fmt_opt(rmse, 2),
                ]);
            }
        }
    }
    errors.write(dir, "threat_errors")?;

    // Numeric types: each arithmetic's estimated timeline against the f64 one.
    let mut types = Table::new([
        "sigma_a (m/s2)",
        "arithmetic",
        "scans with the f64 advisory (%)",
        "runs with an identical timeline",
        "max tau deviation from f64 while tau_f64 <= 60 s (s)",
        "max tau deviation from f64 (s)",
        "max d_cpa deviation from f64 (m)",
        "agreement with truth (% of scans)",
        "refused updates",
    ]);
    for (si, sigma) in ACCEL_SIGMAS.iter().enumerate() {
        for (ai, arith) in Arithmetic::ALL.iter().enumerate() {
            let (mut same, mut total, mut identical) = (0usize, 0usize, 0usize);
            let (mut dtau, mut dtau_alerting, mut dcpa) = (0.0f64, 0.0f64, 0.0f64);
            let mut refused = 0;
            for r in runs {
                let (Some(reference), Some(other)) = (
                    r.estimated.get(si).and_then(|e| e.first()),
                    r.estimated.get(si).and_then(|e| e.get(ai)),
                ) else {
                    continue;
                };
                let s = reference
                    .iter()
                    .zip(other)
                    .filter(|(a, b)| a.advisory == b.advisory)
                    .count();
                same += s;
                total += reference.len();
                identical += usize::from(s == reference.len());
                for (a, b) in reference.iter().zip(other) {
                    if let (Some(x), Some(y)) = (a.tau_s, b.tau_s) {
                        dtau = dtau.max((x - y).abs());
                        if x <= 60.0 {
                            dtau_alerting = dtau_alerting.max((x - y).abs());
                        }
                    }
                    if let (Some(x), Some(y)) = (a.d_cpa_m, b.d_cpa_m) {
                        dcpa = dcpa.max((x - y).abs());
                    }
                }
                refused += r
                    .refused
                    .get(si)
                    .and_then(|v| v.get(ai))
                    .copied()
                    .unwrap_or(0);
            }
            let agree = truth_agreement(runs, si, *arith);
            types.push([
                format!("{sigma}"),
                arith.label().to_string(),
                format!("{:.3}", 100.0 * same as f64 / total.max(1) as f64),
                format!("{identical} / {n}"),
                format!("{dtau_alerting:.2e}"),
                format!("{dtau:.2e}"),
                format!("{dcpa:.2e}"),
                format!(
                    "{:.2} ± {:.2}",
                    100.0 * agree.mean,
                    100.0 * agree.half_width
                ),
                refused.to_string(),
            ]);
        }
    }
    types.write(dir, "numeric_types")?;

    // Run 0's timeline (CSV).
    let mut csv = String::from("t,true_advisory,true_tau,true_tau_mod_ta,true_d_cpa");
    for a in Arithmetic::ALL {
        let l = a.label();
        let _ = write!(
            csv,
            ",{l}_advisory,{l}_tau,{l}_tau_mod_ta,{l}_t_cpa,{l}_d_cpa"
        );
    }
    csv.push('\n');
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
    for (k, tr) in run0.truth.iter().enumerate() {
        let _ = write!(
            csv,
            "{},{},{},{},{}",
            tr.t,
            tr.advisory.name(),
            opt(tr.tau_s),
            opt(tr.tau_mod_ta_s),
            opt(tr.d_cpa_m)
        );
        for a in 0..Arithmetic::ALL.len() {
            if let Some(e) = run0
                .estimated
                .first()
                .and_then(|e| e.get(a))
                .and_then(|e| e.get(k))
            {
                let _ = write!(
                    csv,
                    ",{},{},{},{},{}",
                    e.advisory.name(),
                    opt(e.tau_s),
                    opt(e.tau_mod_ta_s),
                    opt(e.t_cpa_s),
                    opt(e.d_cpa_m)
                );
            }
        }
        csv.push('\n');
    }
    write_file(&dir.join("timeline_run0.csv"), &csv)?;

    // Plots (σ_a index 0).
    let series_of = |timeline: &[ScanThreat], name: &str, get: Getter| {
        Series::line(
            name,
            timeline
                .iter()
                .filter_map(|s| get(s).map(|v| (s.t, v)))
                .collect(),
        )
    };
    let band = |get: Getter, q: f64| -> Vec<(f64, f64)> {
        run0.truth
            .iter()
            .enumerate()
            .filter_map(|(k, s)| {
                let mut v: Vec<f64> = runs
                    .iter()
                    .filter_map(|r| get(r.estimated.first()?.first()?.get(k)?))
                    .collect();
                // Only where most runs define it (a quantile of a few is noise).
                if v.len() * 2 < runs.len() {
                    return None;
                }
                v.sort_by(f64::total_cmp);
                Some((s.t, quantile(&v, q)))
            })
            .collect()
    };
    let est0 = |a: usize| {
        run0.estimated
            .first()
            .and_then(|e| e.get(a))
            .map(Vec::as_slice)
            .unwrap_or(&[])
    };
    let sigma0 = ACCEL_SIGMAS[0];
    for (file, title, ylabel, get, cap) in [
        (
            "tau_vs_time.svg",
            "tcas-converging: range tau, truth vs estimate",
            "range tau (s)",
            (|s: &ScanThreat| s.tau_s) as Getter,
            Some(130.0),
        ),
        (
            "tau_mod_vs_time.svg",
            "tcas-converging: TA modified tau (SL 5: alert at 40 s)",
            "TA tau_mod (s)",
            (|s: &ScanThreat| s.tau_mod_ta_s) as Getter,
            Some(130.0),
        ),
        (
            "d_cpa_vs_time.svg",
            "tcas-converging: horizontal miss distance d_cpa",
            "d_cpa (m)",
            (|s: &ScanThreat| s.d_cpa_m) as Getter,
            Some(6000.0),
        ),
    ] {
        plot(
            &dir.join(file),
            &PlotSpec {
                title,
                x_label: "t (s)",
                y_label: ylabel,
                equal_aspect: false,
                y_max: cap,
            },
            &[
                series_of(&run0.truth, "truth", get),
                series_of(
                    est0(0),
                    &format!("run 0 estimate, f64 (sigma_a {sigma0})"),
                    get,
                ),
                series_of(est0(1), "run 0 estimate, f32", get),
                series_of(est0(2), "run 0 estimate, Q32.32", get),
                Series::line(format!("5% of {n} runs"), band(get, 0.05)),
                Series::line(format!("95% of {n} runs"), band(get, 0.95)),
            ],
        )?;
    }

    // Advisory timeline: levels as steps (0 none, 1 proximate, 2 TA, 3 RA);
    // the estimates are offset by 0.04/0.08/0.12 so coinciding steps stay
    // visible.
    let level = |a: Advisory| match a {
        Advisory::None => 0.0,
        Advisory::ProximateTraffic => 1.0,
        Advisory::Traffic => 2.0,
        Advisory::Resolution => 3.0,
    };
    let steps = |timeline: &[ScanThreat], name: &str, offset: f64| {
        let mut pts = Vec::with_capacity(2 * timeline.len());
        for (i, s) in timeline.iter().enumerate() {
            if i > 0 {
                pts.push((s.t, level(timeline[i - 1].advisory) + offset));
            }
            pts.push((s.t, level(s.advisory) + offset));
        }
        Series::line(name, pts)
    };
    plot(
        &dir.join("advisory_timeline.svg"),
        &PlotSpec {
            title: "advisory level (0 none, 1 proximate, 2 TA, 3 RA): truth vs run 0",
            x_label: "t (s)",
            y_label: "advisory level",
            equal_aspect: false,
            y_max: Some(3.5),
        },
        &[
            steps(&run0.truth, "truth", 0.0),
            steps(est0(0), "estimate f64 (+0.04)", 0.04),
            steps(est0(1), "estimate f32 (+0.08)", 0.08),
            steps(est0(2), "estimate Q32.32 (+0.12)", 0.12),
        ],
    )?;

    let fraction = |lvl: Level| -> Vec<(f64, f64)> {
        run0.truth
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let at = runs
                    .iter()
                    .filter(|r| {
                        r.estimated
                            .first()
                            .and_then(|e| e.first())
                            .and_then(|e| e.get(k))
                            .is_some_and(|e| lvl.reached(e.advisory))
                    })
                    .count();
                (s.t, at as f64 / runs.len().max(1) as f64)
            })
            .collect()
    };
    let truth_at = |lvl: Level| -> Vec<(f64, f64)> {
        run0.truth
            .iter()
            .map(|s| (s.t, f64::from(u8::from(lvl.reached(s.advisory)))))
            .collect()
    };
    plot(
        &dir.join("alert_fraction_vs_time.svg"),
        &PlotSpec {
            title: "fraction of runs alerting (estimate, f64) vs the truth's alert",
            x_label: "t (s)",
            y_label: "fraction of runs",
            equal_aspect: false,
            y_max: Some(1.05),
        },
        &[
            Series::line("truth at TA or above", truth_at(Level::Ta)),
            Series::line("truth at RA", truth_at(Level::Ra)),
            Series::line(
                format!("estimate at TA or above ({n} runs)"),
                fraction(Level::Ta),
            ),
            Series::line(format!("estimate at RA ({n} runs)"), fraction(Level::Ra)),
        ],
    )?;

    // The encounter suite's section goes before the closing "Regenerate" line.
    let regenerate = "Regenerate: `cd host-tests && cargo run --release --bin experiments -- --only tcas-advisory`.";
    let mut text = summary(runs, sensitivity, elapsed_s)?.replace(regenerate, "");
    text.push_str(encounter_suite_section);
    text.push_str(regenerate);
    text.push('\n');
    write_file(&dir.join("summary.md"), &text)
}

fn summary(
    runs: &[RunTimelines],
    sensitivity: &[BearingSensitivity],
    elapsed_s: f64,
) -> Result<String, String> {
    let n = runs.len();
    let run0 = runs.first().ok_or("no runs")?;
    let truth0 = scenario::truth(SCENARIO)
        .map_err(|e| e.to_string())?
        .first()
        .and_then(|s| s.first().copied())
        .ok_or("no truth")?;
    let own_alt = scenario::info(SCENARIO)
        .and_then(|i| i.own_altitude_ft)
        .ok_or("no own altitude")?;
    let params =
        abtrack::tcas::sensitivity(&own_aircraft::<f64>(own_alt)).map_err(|e| e.to_string())?;
    let ra = params.ra.ok_or("no RA thresholds")?;
    let horizon = 140.0;
    let ta_continuous =
        continuous_range_test_onset(&truth0, params.ta.dmod_m(), params.ta.tau_s, horizon);
    let ra_continuous = continuous_range_test_onset(&truth0, ra.dmod_m(), ra.tau_s, horizon);
    let st = |level, si, arith| onset_stats(runs, level, si, arith);
    let ta = st(Level::Ta, 0, Arithmetic::F64);
    let ra_stats = st(Level::Ra, 0, Arithmetic::F64);
    let agree0 = truth_agreement(runs, 0, Arithmetic::F64);

    let mut s = String::new();
    let _ = writeln!(
        s,
        "# tcas-advisory: estimated vs true tau and advisory timeline\n"
    );
    let _ = writeln!(
        s,
        "Scenario `tcas-converging`: own aircraft level at {own_alt} ft (SL {}: TA τ {} s / DMOD {} NM, RA τ {} s / \
         DMOD {} NM, ZTHR {}/{} ft), intruder head-on from 14 NM with a 0.2 NM offset at 500 kt closure, \
         climbing 300 ft/min from 7500 ft to co-altitude at closest approach (t = 100.8 s); range σ 50 ft, \
         bearing σ 5°, Mode C altitude, 1 s updates, 140 s. {n} Monte Carlo runs (base seed {BASE_SEED:#x}). \
         Each run is tracked with the range–azimuth filter (σ_a = {} m/s², and {} m/s² as a sensitivity) and \
         the Mode C altitude tracker, and `abtrack::tcas::assess` gives tau, τ_mod, t_cpa, d_cpa and the \
         advisory every scan, in f64, f32 and Q32.32; the same assessment of the true relative state is the \
         reference. Runtime {elapsed_s:.1} s (release, 2 threads; the bearing sensitivity included).\n",
        params.level.number(),
        params.ta.tau_s,
        params.ta.dmod_nm,
        ra.tau_s,
        ra.dmod_nm,
        params.ta.zthr_ft,
        ra.zthr_ft,
        ACCEL_SIGMAS[0],
        ACCEL_SIGMAS[1],
    );
    let truth_ta = onset_and_end(&run0.truth, Level::Ta);
    let truth_ra = onset_and_end(&run0.truth, Level::Ra);
    let _ = writeln!(
        s,
        "**True timeline**: TA at scans t = {}…{} s, RA at t = {}…{} s. The continuous-time range tests \
         (r − DMOD²/r ≤ TAU·closure on the straight track) are met at t = {} s (TA) and {} s (RA), so the first \
         scans at or after them are the onsets; the vertical tests pass throughout (|h| ≤ 500 ft < ZTHR). Both \
         clear when the opening range passes DMOD after closest approach.\n",
        fmt_opt(truth_ta.map(|t| t.0), 0),
        fmt_opt(truth_ta.map(|t| t.1), 0),
        fmt_opt(truth_ra.map(|t| t.0), 0),
        fmt_opt(truth_ra.map(|t| t.1), 0),
        fmt_opt(ta_continuous, 2),
        fmt_opt(ra_continuous, 2),
    );
    let _ = writeln!(
        s,
        "## Advisory onsets (estimated minus true, s; {n} runs)\n"
    );
    let _ = writeln!(s, "| σ_a (m/s²) | filter | level | onset delay | within ±1 s | end delay | missed | runs with false alerts |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for (si, sigma) in ACCEL_SIGMAS.iter().enumerate() {
        for (arith, level) in [Arithmetic::F64, Arithmetic::VariantF64]
            .into_iter()
            .flat_map(|a| Level::ALL.map(|l| (a, l)))
        {
            let o = st(level, si, arith);
            let _ = writeln!(
                s,
                "| {sigma} | {} | {} | {} | {} / {} | {} | {} | {} |",
                arith.label(),
                level.label(),
                fmt_ci(&o.onset_ci(), 2),
                o.onsets_within(1.0),
                o.onset_delays_s.len(),
                fmt_ci(&o.end_ci(), 2),
                o.missed,
                o.false_alert_runs,
            );
        }
    }
    let agree1 = truth_agreement(runs, 1, Arithmetic::F64);
    let _ = writeln!(
        s,
        "\nThe estimated advisory equals the truth's in {:.2} % ± {:.2} of the scans (σ_a = {}) and {:.2} % ± {:.2} \
         (σ_a = {}); the scans that differ are at the (mostly one-scan-late) TA and RA onsets and ends.\n",
        100.0 * agree0.mean,
        100.0 * agree0.half_width,
        ACCEL_SIGMAS[0],
        100.0 * agree1.mean,
        100.0 * agree1.half_width,
        ACCEL_SIGMAS[1],
    );

    // Numeric types.
    let mut differing = [0usize; 3];
    let mut identical = [0usize; 3];
    let mut scans = 0usize;
    for r in runs {
        for e in &r.estimated {
            let Some(reference) = e.first() else { continue };
            for (ai, other) in e.iter().take(Arithmetic::ALL.len()).enumerate() {
                let d = reference
                    .iter()
                    .zip(other)
                    .filter(|(a, b)| a.advisory != b.advisory)
                    .count();
                differing[ai] += d;
                identical[ai] += usize::from(d == 0);
            }
            scans += reference.len();
        }
    }
    let _ = writeln!(
        s,
        "**Numeric types**: over all {n} runs and both σ_a ({scans} scans per arithmetic) the f32 chain's advisory \
         differs from the f64 chain's in {} scans and the Q32.32 chain's in {} ({} and {} of {} timelines \
         identical); tau and d_cpa deviations are in `numeric_types.md`.\n",
        differing[1],
        differing[2],
        identical[1],
        identical[2],
        2 * n,
    );

    let _ = writeln!(s, "## Why the estimate alerts late, and by how much\n");
    let at = |t: f64| REPORT_TIMES_S.iter().position(|&r| r == t);
    if let (Some(first), Some(i55)) = (sensitivity.first(), at(55.0)) {
        let _ = writeln!(
            s,
            "The estimated range rate is biased towards opening: {} m/s at t = 55 s (true closure 257 m/s), \
             so tau is over-estimated (mean {} s against the true {} s at t = 55 s) and the TA, decided at \
             τ_mod = 40 s, comes {} s late on average. The bias is a second-order effect of the bearing \
             noise in the filter's projections (eqs. 11–13 with the *measured* azimuth): scaling the same azimuth \
             errors (and the filter's σ_B) down shrinks it roughly with σ_B²:\n",
            fmt_ci(&first.range_rate_error[i55], 2),
            mean_at(runs, 55.0, |s| s.tau_s).map_or("-".into(), |v| format!("{v:.2}")),
            run0.truth
                .iter()
                .find(|s| s.t == 55.0)
                .and_then(|s| s.tau_s)
                .map_or("-".into(), |v| format!("{v:.2}")),
            fmt_ci(&first.ta.onset_ci(), 2),
        );
        let _ = writeln!(
            s,
            "| bearing σ (°) | range-rate error at t = 55 s (m/s) | TA onset delay (s) |"
        );
        let _ = writeln!(s, "|---|---|---|");
        for b in sensitivity {
            let _ = writeln!(
                s,
                "| {:.2} | {} | {} |",
                b.bearing_sigma_deg,
                fmt_ci(&b.range_rate_error[i55], 2),
                fmt_ci(&b.ta.onset_ci(), 2),
            );
        }
        let _ = writeln!(
            s,
            "\nThe same effect gives the he-tcas experiment's outward range bias (+R·σ_B²/2). The obvious change — \
             range residual R − |p̂| instead of the projection onto the measured line of sight (the \"variant\" rows) — \
             is not a fix: at 14 NM the two-point start leaves a cross-range prediction error of kilometres, \
             |p̂| exceeds the range by (cross error)²/2R, and the variant's range-rate kick raises false TAs (the \
             earliest at t = {} s) in {} of {n} runs (σ_a = {}).\n",
            {
                let v = st(Level::Ta, 0, Arithmetic::VariantF64);
                let earliest = v.onset_delays_s.iter().copied().fold(f64::INFINITY, f64::min);
                fmt_opt(v.truth_onset_s.map(|t| t + earliest), 0)
            },
            st(Level::Ta, 0, Arithmetic::VariantF64).false_alert_runs,
            ACCEL_SIGMAS[0],
        );
    }
    let _ = writeln!(s, "## Threat measures\n");
    let _ = writeln!(
        s,
        "`threat_errors.md` gives tau, τ_mod, ṙ, t_cpa and d_cpa at t = 20…95 s. Range, range rate and the taus \
         come from the along-range channel (50 ft noise) and are within about a second of the truth from t = 40 s \
         on; t_cpa and above all d_cpa depend on the cross-range velocity, i.e. on the 5° bearing noise: d_cpa is \
         {} m on average (5–95 %: {}) at t = 20 s against the true 370 m, and still {} m at t = 55 s — which is why \
         TCAS II alerts on range and range rate (tau) rather than on a bearing-derived miss distance.\n",
        mean_at(runs, 20.0, |s| s.d_cpa_m).map_or("-".into(), |v| format!("{v:.0}")),
        band_at(runs, 20.0, |s| s.d_cpa_m),
        mean_at(runs, 55.0, |s| s.d_cpa_m).map_or("-".into(), |v| format!("{v:.0}")),
    );
    let _ = writeln!(
        s,
        "## Verdict\n\nOn this encounter the advisory timeline from the estimated track matches the truth's: every \
         run raises the TA and the RA, none early, none missed, no false alerts; TA onset {} s late on average \
         ({} of {n} runs within 1 s), RA onset {} s late ({} of {n} within 1 s); the largest onset/end \
         difference in any run is {} s. f32 and Q32.32 reproduce the f64 timeline. With σ_a = {} m/s² the delays \
         are similar but spread more (TA within 1 s in {} of {n} runs).\n",
        fmt_ci(&ta.onset_ci(), 2),
        ta.onsets_within(1.0),
        fmt_ci(&ra_stats.onset_ci(), 2),
        ra_stats.onsets_within(1.0),
        ta.onset_delays_s
            .iter()
            .chain(&ta.end_delays_s)
            .chain(&ra_stats.onset_delays_s)
            .chain(&ra_stats.end_delays_s)
            .fold(0.0f64, |m, d| m.max(d.abs())),
        ACCEL_SIGMAS[1],
        st(Level::Ta, 1, Arithmetic::F64).onsets_within(1.0),
    );
    let _ = writeln!(s, "Plots: `tau_vs_time.svg`, `tau_mod_vs_time.svg`, `d_cpa_vs_time.svg`, `advisory_timeline.svg`, `alert_fraction_vs_time.svg`. Tables: `onsets.md`, `threat_errors.md`, `numeric_types.md`, `bearing_sensitivity.md`; run 0 in `timeline_run0.csv`.\n");
    let _ = writeln!(s, "Regenerate: `cd host-tests && cargo run --release --bin experiments -- --only tcas-advisory`.");
    Ok(s)
}

/// Mean over runs of a measure of the f64 chain (σ_a index 0) at time `t`.
fn mean_at(runs: &[RunTimelines], t: f64, get: fn(&ScanThreat) -> Option<f64>) -> Option<f64> {
    let v = values_at(runs, t, get);
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

fn values_at(runs: &[RunTimelines], t: f64, get: fn(&ScanThreat) -> Option<f64>) -> Vec<f64> {
    let mut v: Vec<f64> = runs
        .iter()
        .filter_map(|r| {
            let e = r.estimated.first()?.first()?;
            get(e.iter().find(|s| s.t == t)?)
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v
}

/// "5%..95%" of a measure at time `t`.
fn band_at(runs: &[RunTimelines], t: f64, get: fn(&ScanThreat) -> Option<f64>) -> String {
    let v = values_at(runs, t, get);
    format!("{:.0}..{:.0} m", quantile(&v, 0.05), quantile(&v, 0.95))
}
