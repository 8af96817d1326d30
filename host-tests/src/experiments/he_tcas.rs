//! Group `he-tcas`: He, Peng, Ling & Quan §4 — the range–azimuth projection
//! filter against the plain per-axis αβ filter on the converted x/y
//! measurements, 200 Monte Carlo runs of the `he-tcas` scenario (see
//! [`crate::scenario`]: own aircraft 900 km/h behind a 700 km/h target at
//! azimuth 30°, 280 km, T = 1 s, 500 s, range σ 100 m, bearing variance
//! 7.569·10⁻³ rad²).
//!
//! # Methods (all on the same measurements of each run)
//!
//! * **range–azimuth** — `abtrack::filter::range_azimuth` (He et al. eqs.
//!   7–13, the readings documented there), in f64, and also in f32 and Q32.32
//!   ([`abtrack::Fix`]) to measure what the on-target arithmetic changes.
//!   Noise: σ_R² = 100² m², σ_B² = 7.569·10⁻³ rad² (the data's own values) and
//!   process noise Q = σ_a² with σ_a = [`ACCEL_SIGMA`] = 0.1 m/s² (the
//!   scenario's recommended CV tuning: the truth is a straight line, so the
//!   matched Q is 0 and a small σ_a keeps the filter from locking onto a
//!   wrong velocity).
//! * **αβ M2** — the baseline: plain per-axis αβ
//!   (`abtrack::gain::ScheduledFilter` with `LeastSquaresGains`) on
//!   x = R sin B, y = R cos B, with the least-squares gains
//!   α(k) = 2(2k−1)/(k(k+1)), β(k) = 6/(k(k+1)). These are the gains He et al.
//!   themselves give for αβ (their eq. 6, "commonly used … in engineering
//!   practice"), and for a constant-velocity target they are the matched
//!   design: with the two-point start they make the estimate the least-squares
//!   line through all measurements so far. The steady-state (Kalata) gains of
//!   the same process noise with the per-axis converted noise σ_xy =
//!   √((σ_R² + R²σ_B²)/2) ≈ 17 km are α ≈ 0.0034; the usual "least squares,
//!   then steady state" schedule switches when α(k) falls below that, at
//!   k ≈ 1170 > 500 scans (computed in [`kalata_switch_scan`]), so within this
//!   scenario that schedule *is* M2.
//! * **αβ Kalata** — the same per-axis filter with only those steady-state
//!   gains, fixed from the first filtered update. Reported to show why a
//!   schedule is needed (the two-point start leaves a velocity error of
//!   ≈ 30 km/s that gains of 10⁻⁶ take far longer than 500 s to remove); it
//!   is not used for the verdict.
//! * **Kalman CV (CMKF)** — the textbook converted-measurement Kalman filter
//!   (4 states, discrete white acceleration σ_a = 0.1 m/s², each measurement
//!   with its own first-order converted covariance evaluated at the measured
//!   azimuth, [`crate::kalman`]). With R·σ_B²/σ_R ≈ 21 ≫ 1 that first-order
//!   covariance is inconsistent here (it trusts each point to 100 m along a
//!   line of sight that is itself off by ±5°), so it is *not* an optimal
//!   bound; it is what "just use a Kalman filter" gives.
//! * **Batch ML (yardstick)** — the maximum-likelihood straight line through
//!   all polar measurements so far (`track_batch_ml`): the truth is exactly
//!   straight, so this is what the data allow.
//! * **Eq. (9) as printed** (host f64, [`crate::reference_ra`] with
//!   [`crate::reference_ra::Eq9Reading::AsPrinted`]): α, β divided by PCOV₁₁ + VAR as printed,
//!   instead of σ_R². The range direction then carries the cross-range
//!   variance and the filter reduces to per-axis gains α = W1 on the
//!   converted measurements (this reading).
//! * **Diagnostic variants** (host f64): αβ M2 on the debiased conversion
//!   e^{σ_B²/2}·R·(sin B, cos B), and the range–azimuth filter with the range
//!   residual R − |p̂| ([`RangeResidualVariant`]). They isolate the two
//!   ~1 km range biases (conversion and projection) that dominate both
//!   filters' range errors.
//!
//! # Errors
//!
//! Estimate minus truth after each update; the position error is also split
//! into its components along the true line of sight (**range error**) and
//! across it (**cross-range error**). Scans 0 and 1 initialise every filter
//! identically (the estimate is the measurement) and are not scored:
//! *overall* is t = 2..499 s, *late phase* t ≥ [`LATE_PHASE_START_S`] = 400 s.
//! Each run gives one RMSE per window; tables show the mean over runs with
//! its 95 % Student-t interval, and paired per-run differences (same noise
//! for both methods) with theirs ([`crate::metrics`]).

use rayon::prelude::*;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::Path;

use abtrack::design;
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::gain::{LeastSquaresGains, ScheduledFilter};
use abtrack::{Cartesian, Fix, Gains, Scalar};

use super::common::{fmt_ci, plot, write_file, Context, PlotSpec, Series, Table};
use crate::kalman::{polar_measurement_covariance, ConstantVelocityKf, ProcessNoise};
use crate::metrics::{mean_ci95, paired_difference_ci95, MeanCi};
use crate::reference_ra::{predict_covariance, update_covariance, ReferenceRangeAzimuth};
use crate::scenario::{self, Measurement, HE_AZIMUTH_VARIANCE};

/// The group's name (`--only he-tcas`, `results/he-tcas/`).
pub const NAME: &str = "he-tcas";
/// The scenario it runs.
pub const SCENARIO: &str = "he-tcas";
/// Base seed of the Monte Carlo runs (run r uses `monte_carlo_seed(BASE_SEED, r)`).
pub const BASE_SEED: u64 = 0x0003_4E7C_A500_0004;
/// Range noise σ_R (m) the filters assume: the scenario's.
pub const RANGE_SIGMA_M: f64 = 100.0;
/// σ_a (m/s²) of the process noise of the range–azimuth and Kalman filters
/// and of the steady-state αβ design.
pub const ACCEL_SIGMA: f64 = 0.1;
/// Start of the late-phase window, s.
pub const LATE_PHASE_START_S: f64 = 400.0;
/// Smallest relative improvement of the position RMSE that counts as
/// reproducing "significantly less" error (the verdict of `summary.md`).
pub const MEANINGFUL_IMPROVEMENT: f64 = 0.03;
/// First scored scan (scans 0 and 1 initialise).
pub const FIRST_SCORED_SCAN: usize = 2;

/// Files the group writes into `results/he-tcas/`.
pub const FILES: &[&str] = &[
    "rmse.csv",
    "rmse.md",
    "paired_differences.csv",
    "paired_differences.md",
    "numeric_types.csv",
    "numeric_types.md",
    "error_vs_time.csv",
    "position_error_vs_time.svg",
    "range_error_vs_time.svg",
    "range_bias_vs_time.svg",
    "cross_range_error_vs_time.svg",
    "numeric_deviation_vs_time.svg",
    "tracks_run0.svg",
    "summary.md",
];

/// The estimators compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    RangeAzimuthF64,
    RangeAzimuthF32,
    RangeAzimuthFix,
    /// Diagnostic variant (host f64): eq. (11)'s range residual taken as
    /// R − |p̂| instead of the projection R − p̂·u(B).
    RangeAzimuthRangeResidual,
    /// He et al. eq. (9) exactly as printed (VAR for σ_R²), host f64.
    RangeAzimuthEq9AsPrinted,
    AlphaBetaM2,
    /// αβ M2 on the debiased conversion e^{σ_B²/2}·R·(sin B, cos B).
    AlphaBetaM2Debiased,
    AlphaBetaKalata,
    KalmanCv,
    /// Maximum-likelihood straight line through all measurements so far.
    BatchMl,
}

impl Method {
    pub const ALL: [Method; 10] = [
        Method::RangeAzimuthF64,
        Method::RangeAzimuthEq9AsPrinted,
        Method::AlphaBetaM2,
        Method::BatchMl,
        Method::KalmanCv,
        Method::RangeAzimuthRangeResidual,
        Method::AlphaBetaM2Debiased,
        Method::AlphaBetaKalata,
        Method::RangeAzimuthF32,
        Method::RangeAzimuthFix,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Method::RangeAzimuthF64 => "range-azimuth (f64)",
            Method::RangeAzimuthF32 => "range-azimuth (f32)",
            Method::RangeAzimuthFix => "range-azimuth (Q32.32)",
            Method::RangeAzimuthRangeResidual => "range-azimuth, RESID_R = R - r_pred (variant)",
            Method::RangeAzimuthEq9AsPrinted => "range-azimuth, eq. 9 as printed (VAR)",
            Method::AlphaBetaM2 => "alpha-beta M2 (eq. 6 gains)",
            Method::AlphaBetaM2Debiased => "alpha-beta M2, debiased conversion",
            Method::AlphaBetaKalata => "alpha-beta Kalata steady-state only",
            Method::KalmanCv => "Kalman CV, first-order converted (CMKF)",
            Method::BatchMl => "batch ML straight line (yardstick)",
        }
    }

    fn index(self) -> usize {
        Method::ALL.iter().position(|&m| m == self).unwrap_or(0)
    }
}

/// Configuration of a simulation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeTcasConfig {
    pub runs: usize,
    pub base_seed: u64,
    /// σ_a, m/s².
    pub accel_sigma: f64,
    /// Also run the range–azimuth filter in f32 and Q32.32.
    pub numeric_types: bool,
    /// Also compute the batch maximum-likelihood yardstick (the slowest
    /// part: O(k) per scan).
    pub yardstick: bool,
}

impl HeTcasConfig {
    /// The documented experiment with `runs` Monte Carlo runs.
    pub fn with_runs(runs: usize) -> Self {
        HeTcasConfig {
            runs,
            base_seed: BASE_SEED,
            accel_sigma: ACCEL_SIGMA,
            numeric_types: true,
            yardstick: true,
        }
    }
}

/// One scan's error of one method: position (x, y), range and cross-range (m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ScanError {
    pub position: [f64; 2],
    pub range: f64,
    pub cross_range: f64,
}

/// RMSEs of one run over one window, m.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WindowRmse {
    pub position: f64,
    pub range: f64,
    pub cross_range: f64,
    /// Mean signed range error (estimated minus true range direction
    /// component), m: the range bias.
    pub range_mean: f64,
}

/// One method's per-run results.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodRuns {
    pub method: Method,
    /// Per run: RMSE over the overall window.
    pub overall: Vec<WindowRmse>,
    /// Per run: RMSE over the late phase.
    pub late: Vec<WindowRmse>,
    /// Per scan: RMSE across runs (position, range, cross-range), m.
    pub against_time: Vec<WindowRmse>,
    /// Updates the filter refused (should be 0).
    pub refused: usize,
}

/// Deviation of a lower-precision range–azimuth filter from the f64 one.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviation {
    /// Largest |p_S − p_f64| over every run and scan, m.
    pub max_position_m: f64,
    /// RMS of |p_S − p_f64| over every run and scan, m.
    pub rms_position_m: f64,
    /// Largest |v_S − v_f64|, m/s.
    pub max_velocity_m_per_s: f64,
}

/// Everything [`simulate`] measured.
#[derive(Debug, Clone, PartialEq)]
pub struct HeTcasOutcome {
    pub config: HeTcasConfig,
    pub methods: Vec<MethodRuns>,
    /// Per scan: max over runs of |p_S − p_f64| for f32 and Q32.32, m.
    pub deviation_against_time: Vec<[f64; 2]>,
    pub f32_deviation: Option<Deviation>,
    pub fix_deviation: Option<Deviation>,
    /// Run 0, for the track picture: truth, measurements, range–azimuth and
    /// αβ M2 estimates, (x, y) in m.
    pub run0: Run0,
    pub scan_times: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Run0 {
    pub truth: Vec<(f64, f64)>,
    pub measured: Vec<(f64, f64)>,
    pub range_azimuth: Vec<(f64, f64)>,
    pub alpha_beta: Vec<(f64, f64)>,
}

impl HeTcasOutcome {
    pub fn method(&self, m: Method) -> Option<&MethodRuns> {
        self.methods.iter().find(|r| r.method == m)
    }
}

/// A polar measurement with the interval since the previous one.
#[derive(Debug, Clone, Copy)]
struct Polar {
    range: f64,
    azimuth: f64,
    dt: f64,
}

/// Estimated (position, velocity) after each scan, in f64.
type Estimates = Vec<([f64; 2], [f64; 2])>;

/// The range–azimuth filter in arithmetic `S`. A refused update coasts the
/// track (and is counted).
fn track_range_azimuth<S: Scalar>(
    meas: &[Polar],
    accel_sigma: f64,
) -> Result<(Estimates, usize), String> {
    let noise = RangeAzimuthNoise::<S>::new_f64(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        HE_AZIMUTH_VARIANCE,
        accel_sigma * accel_sigma,
    )
    .map_err(|e| format!("range-azimuth noise in {}: {e}", S::NAME))?;
    let mut filter = RangeAzimuthFilter::<S>::new(noise);
    let mut out = Vec::with_capacity(meas.len());
    let mut refused = 0;
    for m in meas {
        let c = |v: f64| S::try_from_f64(v).map_err(|e| format!("{} input {v}: {e:?}", S::NAME));
        let (r, b, dt) = (c(m.range)?, c(m.azimuth)?, c(m.dt)?);
        if filter.update(r, b, dt).is_err() {
            refused += 1;
            let _ = filter.coast(dt);
        }
        out.push((
            filter.position().map(|v| v.to_f64()),
            filter.velocity().map(|v| v.to_f64()),
        ));
    }
    Ok((out, refused))
}

fn converted(m: &Polar) -> [f64; 2] {
    let (s, c) = m.azimuth.sin_cos();
    [m.range * s, m.range * c]
}

/// A diagnostic variant of the range–azimuth filter (host f64, built on the
/// independent reference of `reference_ra`, same readings): the range
/// residual of eq. (11) is R − |p̂| (measured minus predicted range) instead
/// of the projection R − p̂·u(B) onto the *measured* line of sight; nothing
/// else changes. For a bearing error δB the projection is shorter than |p̂|
/// by |p̂|(1 − cos δB), R·σ_B²/2 on average, which pushes the range estimate
/// outwards; this variant shows how much of the error that is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RangeResidualVariant {
    inner: ReferenceRangeAzimuth,
}

impl RangeResidualVariant {
    /// σ_R² (m²), σ_B² (rad²), Q (m²/s⁴).
    pub fn new(range_variance: f64, bearing_variance: f64, process_noise: f64) -> Self {
        RangeResidualVariant {
            inner: ReferenceRangeAzimuth::new(range_variance, bearing_variance, process_noise),
        }
    }

    /// One measurement, `dt` s after the previous one.
    pub fn update(&mut self, range: f64, azimuth: f64, dt: f64) {
        let f = &mut self.inner;
        if !f.is_tracking() {
            f.update(range, azimuth, dt);
            return;
        }
        let (q, sr2) = (f.q, f.range_variance);
        let xp = [f.x[0] + dt * f.x[1], f.x[1]];
        let yp = [f.y[0] + dt * f.y[1], f.y[1]];
        let pr = predict_covariance(&f.p_range, dt, q);
        let pc = predict_covariance(&f.p_cross, dt, q);
        let var = range * range * f.bearing_variance;
        let alpha = pr[0][0] / (pr[0][0] + sr2);
        let kv = pr[0][1] / (pr[0][0] + sr2);
        let w1 = pc[0][0] / (pc[0][0] + var);
        let w2 = pc[0][1] / (pc[0][0] + var);
        let (sb, cb) = azimuth.sin_cos();
        let resid_r = range - xp[0].hypot(yp[0]);
        let resid_cr = xp[0] * cb - yp[0] * sb;
        f.x = [
            xp[0] + alpha * resid_r * sb - w1 * resid_cr * cb,
            xp[1] + kv * resid_r * sb - w2 * resid_cr * cb,
        ];
        f.y = [
            yp[0] + alpha * resid_r * cb + w1 * resid_cr * sb,
            yp[1] + kv * resid_r * cb + w2 * resid_cr * sb,
        ];
        f.p_range = update_covariance(&pr, [alpha, kv], sr2);
        f.p_cross = update_covariance(&pc, [w1, w2], var);
    }

    /// (x, y), m.
    pub fn position(&self) -> [f64; 2] {
        [self.inner.x[0], self.inner.y[0]]
    }
    /// (ẋ, ẏ), m/s.
    pub fn velocity(&self) -> [f64; 2] {
        [self.inner.x[1], self.inner.y[1]]
    }
}

/// Runs an f64 host filter over the measurements: `update` takes
/// (R, B, dt) and returns the estimate (position, velocity) after it.
fn track_host_f64(
    meas: &[Polar],
    mut update: impl FnMut(f64, f64, f64) -> ([f64; 2], [f64; 2]),
) -> (Estimates, usize) {
    let out = meas
        .iter()
        .map(|m| update(m.range, m.azimuth, m.dt))
        .collect();
    (out, 0)
}

fn track_range_residual_variant(meas: &[Polar], accel_sigma: f64) -> (Estimates, usize) {
    let mut f = RangeResidualVariant::new(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        HE_AZIMUTH_VARIANCE,
        accel_sigma * accel_sigma,
    );
    track_host_f64(meas, |r, b, dt| {
        f.update(r, b, dt);
        (f.position(), f.velocity())
    })
}

/// He et al.'s filter with eq. (9) exactly as printed (the f64 reference,
/// [`crate::reference_ra::Eq9Reading::AsPrinted`]).
fn track_eq9_as_printed(meas: &[Polar], accel_sigma: f64) -> (Estimates, usize) {
    let mut f = ReferenceRangeAzimuth::as_printed(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        HE_AZIMUTH_VARIANCE,
        accel_sigma * accel_sigma,
    );
    track_host_f64(meas, |r, b, dt| {
        f.update(r, b, dt);
        ([f.x[0], f.y[0]], [f.x[1], f.y[1]])
    })
}

/// Per-axis αβ on the converted measurements with the least-squares gains
/// (M2, He et al. eq. 6).
/// `scale` multiplies the converted position (1 for the plain conversion,
/// e^{σ_B²/2} for the debiased one: E[sin(B + δB)] = e^{−σ_B²/2}·sin B for
/// Gaussian δB, so the plain conversion is pulled towards the sensor by
/// R·(1 − e^{−σ_B²/2}) ≈ 0.38 % of R).
fn track_alpha_beta_m2(meas: &[Polar], scale: f64) -> (Estimates, usize) {
    let mut track: ScheduledFilter<f64, LeastSquaresGains, 2, 2> =
        ScheduledFilter::new(LeastSquaresGains::default());
    let mut out = Vec::with_capacity(meas.len());
    let mut refused = 0;
    for m in meas {
        if track.update(converted(m).map(|v| v * scale), m.dt).is_err() {
            refused += 1;
            let _ = track.coast(m.dt);
        }
        out.push((track.filter().position(), track.filter().velocity()));
    }
    (out, refused)
}

/// Per-axis αβ with fixed gains.
fn track_alpha_beta_fixed(meas: &[Polar], gains: &Gains<f64>) -> (Estimates, usize) {
    let mut track: Cartesian<f64, 2, 2> = Cartesian::new();
    let mut out = Vec::with_capacity(meas.len());
    let mut refused = 0;
    for m in meas {
        if track.update(converted(m), m.dt, gains).is_err() {
            refused += 1;
            let _ = track.coast(m.dt);
        }
        out.push((track.position(), track.velocity()));
    }
    (out, refused)
}

fn track_kalman(meas: &[Polar], accel_sigma: f64) -> Result<(Estimates, usize), String> {
    let sigma_b = HE_AZIMUTH_VARIANCE.sqrt();
    let first = meas.first().ok_or("no measurements")?;
    let mut kf = ConstantVelocityKf::new(
        ProcessNoise::DiscreteWhiteAcceleration { sigma: accel_sigma },
        polar_measurement_covariance(first.range, first.azimuth, RANGE_SIGMA_M, sigma_b),
    )
    .map_err(|e| format!("Kalman: {e}"))?;
    let mut out = Vec::with_capacity(meas.len());
    let mut refused = 0;
    for m in meas {
        let r = polar_measurement_covariance(m.range, m.azimuth, RANGE_SIGMA_M, sigma_b);
        if kf.update_with_covariance(converted(m), m.dt, r).is_err() {
            refused += 1;
            let _ = kf.coast(m.dt);
        }
        out.push((kf.position(), kf.velocity()));
    }
    Ok((out, refused))
}

/// The yardstick: the maximum-likelihood straight line through all polar
/// measurements so far. The truth is exactly a straight line (Q = 0), so
/// this is what the data allow when every measurement is weighed with its
/// true (polar) noise; no recursive filter here uses more information. At
/// every scan k it minimises the cost Σᵢ ((Rᵢ − |p(tᵢ)|)/σ_R)² +
/// ((Bᵢ − ∠p(tᵢ))/σ_B)² over p(t) = p_k + v·(t − t_k) (bearing residuals
/// wrapped to (−π, π]) by Newton's method from two starts — the previous
/// scan's solution moved on by v·T, and `second_start` (another estimator's
/// state at this scan) — keeping the lower cost: the cost has local minima
/// and a warm start alone stays in one in a few runs. Scans 0 and 1 give the
/// two-point state like the filters. Returns the estimates and the number of
/// scans where neither start converged within [`ML_MAX_ITERATIONS`].
fn track_batch_ml(meas: &[Polar], second_start: &Estimates) -> Result<(Estimates, usize), String> {
    let mut out = Vec::with_capacity(meas.len());
    let mut times = Vec::with_capacity(meas.len());
    let mut t = 0.0;
    let mut theta = [0.0f64; 4]; // x, y, vx, vy at the latest scan
    let mut not_converged = 0;
    for (k, m) in meas.iter().enumerate() {
        if k > 0 {
            t += m.dt;
        }
        times.push(t);
        let z = converted(m);
        match k {
            0 => theta = [z[0], z[1], 0.0, 0.0],
            1 => {
                let dt = m.dt;
                theta = [z[0], z[1], (z[0] - theta[0]) / dt, (z[1] - theta[1]) / dt];
            }
            _ => {
                let warm = [
                    theta[0] + theta[2] * m.dt,
                    theta[1] + theta[3] * m.dt,
                    theta[2],
                    theta[3],
                ];
                // Two starts: the cost has several local minima (the range
                // circles' curvature), and a warm start can stay in one.
                let mut best = newton(&meas[..=k], &times, t, warm);
                if let Some(other) = second_start.get(k).map(|(p, v)| [p[0], p[1], v[0], v[1]]) {
                    let fit = newton(&meas[..=k], &times, t, other);
                    if fit.1 < best.1 {
                        best = fit;
                    }
                }
                let (fit, _, converged) = best;
                theta = fit;
                if !converged {
                    not_converged += 1;
                }
            }
        }
        out.push(([theta[0], theta[1]], [theta[2], theta[3]]));
    }
    Ok((out, not_converged))
}

/// Newton iterations per start of `track_batch_ml` at most.
pub const ML_MAX_ITERATIONS: usize = 50;

/// Cost Σ res², the vector g = Jᵀ·res (−½ the cost's gradient) and the
/// matrix ½·∇²cost = JᵀJ − Σ res·∇²h/σ of the straight line `theta`
/// (x, y, vx, vy at time `now`) against polar measurements, with whitened
/// residuals res = (z − h(θ))/σ. The second-order term matters here: the
/// curvature of the range circle, (I − uuᵀ)/r, weighed by σ_R = 100 m, is
/// comparable to the bearing information across the line of sight, and
/// without it Gauss–Newton converges only linearly.
fn ml_normal_equations(
    meas: &[Polar],
    times: &[f64],
    now: f64,
    theta: &[f64; 4],
    with_derivatives: bool,
) -> (f64, [f64; 4], [[f64; 4]; 4]) {
    let sigma_b = HE_AZIMUTH_VARIANCE.sqrt();
    let mut a = [[0.0f64; 4]; 4];
    let mut g = [0.0f64; 4];
    let mut cost = 0.0;
    for (mi, &ti) in meas.iter().zip(times) {
        let d = ti - now;
        let (px, py) = (theta[0] + theta[2] * d, theta[1] + theta[3] * d);
        let r = px.hypot(py);
        let res_r = (mi.range - r) / RANGE_SIGMA_M;
        let res_b = ((mi.azimuth - px.atan2(py) + PI).rem_euclid(TAU) - PI) / sigma_b;
        cost += res_r * res_r + res_b * res_b;
        if with_derivatives {
            // ∂p/∂θ = [I, d·I]: column i of θ moves p along axis i % 2 with
            // weight 1 (position) or d (velocity).
            let w = [1.0, 1.0, d, d];
            let axis = [0usize, 1, 0, 1];
            let r2 = r * r;
            let r4 = r2 * r2;
            let grad_r = [px / r, py / r];
            let grad_b = [py / r2, -px / r2];
            // ∇²r = (I − uuᵀ)/r, ∇²B for B = atan2(x, y).
            let hess_r = [
                [
                    (1.0 - grad_r[0] * grad_r[0]) / r,
                    -grad_r[0] * grad_r[1] / r,
                ],
                [
                    -grad_r[0] * grad_r[1] / r,
                    (1.0 - grad_r[1] * grad_r[1]) / r,
                ],
            ];
            let bxy = (px * px - py * py) / r4;
            let hess_b = [[-2.0 * px * py / r4, bxy], [bxy, 2.0 * px * py / r4]];
            for i in 0..4 {
                let jr_i = w[i] * grad_r[axis[i]] / RANGE_SIGMA_M;
                let jb_i = w[i] * grad_b[axis[i]] / sigma_b;
                g[i] += jr_i * res_r + jb_i * res_b;
                for j in 0..4 {
                    let jr_j = w[j] * grad_r[axis[j]] / RANGE_SIGMA_M;
                    let jb_j = w[j] * grad_b[axis[j]] / sigma_b;
                    let second = w[i]
                        * w[j]
                        * (res_r * hess_r[axis[i]][axis[j]] / RANGE_SIGMA_M
                            + res_b * hess_b[axis[i]][axis[j]] / sigma_b);
                    a[i][j] += jr_i * jr_j + jb_i * jb_j - second;
                }
            }
        }
    }
    (cost, g, a)
}

/// Minimises the cost of [`ml_normal_equations`] from `start` by
/// Newton's method with step halving (a full step first; halved up to 30 times
/// while it raises the cost). Returns the solution, its cost and whether it
/// converged: a step below 1 mm and 10⁻⁵ m/s, or no step lowering the cost
/// (the minimum to f64's resolution of the cost).
fn newton(meas: &[Polar], times: &[f64], now: f64, start: [f64; 4]) -> ([f64; 4], f64, bool) {
    let mut theta = start;
    let (mut cost, mut g, mut a) = ml_normal_equations(meas, times, now, &theta, true);
    for _ in 0..ML_MAX_ITERATIONS {
        // Newton's step if it descends (the Hessian can be indefinite far
        // from the minimum), else... there is no Gauss–Newton matrix kept, so
        // fall back to steepest descent scaled by the diagonal.
        let full = match solve4(a, g) {
            Some(step) if (0..4).map(|i| step[i] * g[i]).sum::<f64>() > 0.0 => step,
            _ => [0, 1, 2, 3].map(|i| g[i] / a[i][i].abs().max(f64::MIN_POSITIVE)),
        };
        let mut scale = 1.0;
        let mut accepted = None;
        for _ in 0..30 {
            let trial = [0, 1, 2, 3].map(|i| theta[i] + scale * full[i]);
            let (trial_cost, _, _) = ml_normal_equations(meas, times, now, &trial, false);
            if trial_cost <= cost {
                accepted = Some((trial, trial_cost));
                break;
            }
            scale *= 0.5;
        }
        let Some((trial, trial_cost)) = accepted else {
            return (theta, cost, true);
        };
        let step = [0, 1, 2, 3].map(|i| scale * full[i]);
        theta = trial;
        if step[0].hypot(step[1]) < 1e-3 && step[2].hypot(step[3]) < 1e-5 {
            return (theta, trial_cost, true);
        }
        (cost, g, a) = ml_normal_equations(meas, times, now, &theta, true);
    }
    (theta, cost, false)
}

/// Solves the 4×4 system a·x = b by Gaussian elimination with partial
/// pivoting; `None` if singular.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col] == 0.0 || !a[pivot][col].is_finite() {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        let pivot_row = a[col];
        for row in col + 1..4 {
            let f = a[row][col] / pivot_row[col];
            for (entry, &p) in a[row].iter_mut().zip(&pivot_row).skip(col) {
                *entry -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..4).rev() {
        let s: f64 = (row + 1..4).map(|c| a[row][c] * x[c]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    Some(x)
}

/// The steady-state αβ gains (Kalata) for σ_a and the per-axis converted
/// noise σ_xy = √((σ_R² + R²σ_B²)/2) at range `range_m`.
pub fn kalata_baseline_gains(accel_sigma: f64, range_m: f64) -> Result<Gains<f64>, String> {
    let sigma_xy =
        ((RANGE_SIGMA_M * RANGE_SIGMA_M + range_m * range_m * HE_AZIMUTH_VARIANCE) / 2.0).sqrt();
    let lambda =
        design::tracking_index(accel_sigma, sigma_xy, 1.0).map_err(|e| format!("{e:?}"))?;
    design::kalata_gains(lambda).map_err(|e| format!("{e:?}"))
}

/// The first measurement number k at which the least-squares α(k) falls
/// below the steady-state α of [`kalata_baseline_gains`].
pub fn kalata_switch_scan(accel_sigma: f64, range_m: f64) -> Result<u32, String> {
    let steady = kalata_baseline_gains(accel_sigma, range_m)?.alpha();
    (3..1_000_000u32)
        .find(|&k| {
            let k = f64::from(k);
            2.0 * (2.0 * k - 1.0) / (k * (k + 1.0)) < steady
        })
        .ok_or_else(|| "no switch".to_string())
}

fn rmse_window(errors: &[ScanError], range: std::ops::Range<usize>) -> WindowRmse {
    let slice = &errors[range.start.min(errors.len())..range.end.min(errors.len())];
    let n = slice.len().max(1) as f64;
    let (mut p, mut r, mut c, mut b) = (0.0, 0.0, 0.0, 0.0);
    for e in slice {
        p += e.position[0].powi(2) + e.position[1].powi(2);
        r += e.range.powi(2);
        c += e.cross_range.powi(2);
        b += e.range;
    }
    WindowRmse {
        position: (p / n).sqrt(),
        range: (r / n).sqrt(),
        cross_range: (c / n).sqrt(),
        range_mean: b / n,
    }
}

/// What one Monte Carlo run produced.
struct RunResult {
    /// Per method (indexed like [`Method::ALL`]): the error at every scan.
    errors: Vec<Option<Vec<ScanError>>>,
    refused: Vec<usize>,
    /// Per scan: |p − p_f64| and |v − v_f64| for f32 and Q32.32.
    deviation: Vec<[[f64; 2]; 2]>,
    /// Filled for run 0 only.
    run0: Option<Run0>,
}

fn simulate_run(config: &HeTcasConfig, run: usize) -> Result<RunResult, String> {
    let info = scenario::info(SCENARIO).ok_or("scenario he-tcas missing")?;
    let kalata = kalata_baseline_gains(config.accel_sigma, 280_000.0)?;
    let seed = scenario::monte_carlo_seed(config.base_seed, run as u64);
    let data = scenario::generate(SCENARIO, seed).map_err(|e| e.to_string())?;
    let mut meas = Vec::with_capacity(info.scans);
    let mut truth = Vec::with_capacity(info.scans);
    let mut prev_t = None;
    for scan in &data.scans {
        let Some(Measurement::Polar { range, azimuth, .. }) = scan.measurements.first().copied()
        else {
            return Err(format!(
                "run {run}: scan at t={} has no polar measurement",
                scan.t
            ));
        };
        let s = *scan.truth.first().ok_or("scan without truth")?;
        let dt = prev_t.map_or(info.period_s, |p| scan.t - p);
        prev_t = Some(scan.t);
        meas.push(Polar { range, azimuth, dt });
        truth.push(s);
    }

    let mut estimates: Vec<Option<Estimates>> = vec![None; Method::ALL.len()];
    let mut refused = vec![0usize; Method::ALL.len()];
    let mut put = |m: Method, (e, n): (Estimates, usize)| {
        refused[m.index()] += n;
        estimates[m.index()] = Some(e);
    };
    let debiased = track_alpha_beta_m2(&meas, (HE_AZIMUTH_VARIANCE / 2.0).exp());
    if config.yardstick {
        put(Method::BatchMl, track_batch_ml(&meas, &debiased.0)?);
    }
    put(Method::AlphaBetaM2Debiased, debiased);
    put(
        Method::RangeAzimuthF64,
        track_range_azimuth::<f64>(&meas, config.accel_sigma)?,
    );
    put(Method::AlphaBetaM2, track_alpha_beta_m2(&meas, 1.0));
    put(
        Method::RangeAzimuthRangeResidual,
        track_range_residual_variant(&meas, config.accel_sigma),
    );
    put(
        Method::RangeAzimuthEq9AsPrinted,
        track_eq9_as_printed(&meas, config.accel_sigma),
    );
    put(
        Method::AlphaBetaKalata,
        track_alpha_beta_fixed(&meas, &kalata),
    );
    put(Method::KalmanCv, track_kalman(&meas, config.accel_sigma)?);
    if config.numeric_types {
        put(
            Method::RangeAzimuthF32,
            track_range_azimuth::<f32>(&meas, config.accel_sigma)?,
        );
        put(
            Method::RangeAzimuthFix,
            track_range_azimuth::<Fix>(&meas, config.accel_sigma)?,
        );
    }

    let errors = estimates
        .iter()
        .map(|est| {
            est.as_ref().map(|est| {
                est.iter()
                    .zip(&truth)
                    .map(|((p, _), s)| {
                        let e = [p[0] - s.x, p[1] - s.y];
                        let r = s.range();
                        let u = [s.x / r, s.y / r];
                        ScanError {
                            position: e,
                            range: e[0] * u[0] + e[1] * u[1],
                            cross_range: e[0] * u[1] - e[1] * u[0],
                        }
                    })
                    .collect()
            })
        })
        .collect();

    let mut deviation = Vec::new();
    if config.numeric_types {
        let get = |m: Method| {
            estimates[m.index()]
                .as_ref()
                .ok_or_else(|| format!("missing {m:?} estimates"))
        };
        let (reference, single, fixed) = (
            get(Method::RangeAzimuthF64)?,
            get(Method::RangeAzimuthF32)?,
            get(Method::RangeAzimuthFix)?,
        );
        let diff = |a: &([f64; 2], [f64; 2]), b: &([f64; 2], [f64; 2])| {
            [
                (a.0[0] - b.0[0]).hypot(a.0[1] - b.0[1]),
                (a.1[0] - b.1[0]).hypot(a.1[1] - b.1[1]),
            ]
        };
        deviation = reference
            .iter()
            .zip(single)
            .zip(fixed)
            .map(|((r, s), f)| [diff(s, r), diff(f, r)])
            .collect();
    }

    let run0 = (run == 0).then(|| {
        let xy = |e: &Option<Estimates>| -> Vec<(f64, f64)> {
            e.as_ref()
                .map(|v| v.iter().map(|(p, _)| (p[0], p[1])).collect())
                .unwrap_or_default()
        };
        Run0 {
            truth: truth.iter().map(|s| (s.x, s.y)).collect(),
            measured: meas
                .iter()
                .map(|m| {
                    let p = converted(m);
                    (p[0], p[1])
                })
                .collect(),
            range_azimuth: xy(&estimates[Method::RangeAzimuthF64.index()]),
            alpha_beta: xy(&estimates[Method::AlphaBetaM2.index()]),
        }
    });
    Ok(RunResult {
        errors,
        refused,
        deviation,
        run0,
    })
}

/// Runs the Monte Carlo simulation (no files).
pub fn simulate(config: &HeTcasConfig) -> Result<HeTcasOutcome, String> {
    let info = scenario::info(SCENARIO).ok_or("scenario he-tcas missing")?;
    let scans = info.scans;
    let late_start = (LATE_PHASE_START_S / info.period_s).round() as usize;

    // Spread over the cores by rayon; each run is seeded by its index and
    // the indexed collect keeps run order, so the output does not depend on
    // the thread count.
    let results: Vec<Result<RunResult, String>> = (0..config.runs)
        .into_par_iter()
        .map(|run| simulate_run(config, run))
        .collect();

    // errors[method][run][scan]
    let mut errors: Vec<Vec<Vec<ScanError>>> = vec![Vec::new(); Method::ALL.len()];
    let mut refused = vec![0usize; Method::ALL.len()];
    let mut dev_time = vec![[0.0f64; 2]; scans];
    let mut dev = [Deviation::default(); 2];
    let mut dev_sq = [0.0f64; 2];
    let mut dev_n = 0usize;
    let mut run0 = Run0::default();
    for result in results {
        let r = result?;
        for (mi, e) in r.errors.into_iter().enumerate() {
            if let Some(e) = e {
                errors[mi].push(e);
            }
        }
        for (total, n) in refused.iter_mut().zip(&r.refused) {
            *total += n;
        }
        for (k, d) in r.deviation.iter().enumerate() {
            for slot in 0..2 {
                let [dp, dv] = d[slot];
                dev[slot].max_position_m = dev[slot].max_position_m.max(dp);
                dev[slot].max_velocity_m_per_s = dev[slot].max_velocity_m_per_s.max(dv);
                dev_sq[slot] += dp * dp;
                if let Some(t) = dev_time.get_mut(k) {
                    t[slot] = t[slot].max(dp);
                }
            }
        }
        dev_n += r.deviation.len();
        if let Some(r0) = r.run0 {
            run0 = r0;
        }
    }
    let scan_times: Vec<f64> = (0..scans).map(|k| k as f64 * info.period_s).collect();

    let methods = Method::ALL
        .iter()
        .filter(|m| !errors[m.index()].is_empty())
        .map(|&m| {
            let runs = &errors[m.index()];
            let n = runs.len() as f64;
            let against_time = (0..scans)
                .map(|k| {
                    let (mut p, mut r, mut c, mut b) = (0.0, 0.0, 0.0, 0.0);
                    for run in runs {
                        let e = run[k];
                        p += e.position[0].powi(2) + e.position[1].powi(2);
                        r += e.range.powi(2);
                        c += e.cross_range.powi(2);
                        b += e.range;
                    }
                    WindowRmse {
                        position: (p / n).sqrt(),
                        range: (r / n).sqrt(),
                        cross_range: (c / n).sqrt(),
                        range_mean: b / n,
                    }
                })
                .collect();
            MethodRuns {
                method: m,
                overall: runs
                    .iter()
                    .map(|e| rmse_window(e, FIRST_SCORED_SCAN..scans))
                    .collect(),
                late: runs
                    .iter()
                    .map(|e| rmse_window(e, late_start..scans))
                    .collect(),
                against_time,
                refused: refused[m.index()],
            }
        })
        .collect();

    let finish = |slot: usize| {
        config.numeric_types.then(|| Deviation {
            rms_position_m: (dev_sq[slot] / dev_n.max(1) as f64).sqrt(),
            ..dev[slot]
        })
    };
    Ok(HeTcasOutcome {
        config: *config,
        methods,
        deviation_against_time: dev_time,
        f32_deviation: finish(0),
        fix_deviation: finish(1),
        run0,
        scan_times,
    })
}

/// The three per-run RMSE columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    Position,
    Range,
    CrossRange,
    /// Signed mean range error (bias), not an RMSE.
    RangeBias,
}

impl Quantity {
    pub const ALL: [Quantity; 4] = [
        Quantity::Position,
        Quantity::Range,
        Quantity::CrossRange,
        Quantity::RangeBias,
    ];
    pub fn label(self) -> &'static str {
        match self {
            Quantity::Position => "position",
            Quantity::Range => "range",
            Quantity::CrossRange => "cross-range",
            Quantity::RangeBias => "range bias",
        }
    }
    pub fn of(self, w: &WindowRmse) -> f64 {
        match self {
            Quantity::Position => w.position,
            Quantity::Range => w.range,
            Quantity::CrossRange => w.cross_range,
            Quantity::RangeBias => w.range_mean,
        }
    }
}

/// Which window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Window {
    Overall,
    Late,
}

impl MethodRuns {
    pub fn values(&self, window: Window, q: Quantity) -> Vec<f64> {
        let w = match window {
            Window::Overall => &self.overall,
            Window::Late => &self.late,
        };
        w.iter().map(|r| q.of(r)).collect()
    }
    pub fn ci(&self, window: Window, q: Quantity) -> MeanCi {
        mean_ci95(&self.values(window, q))
    }
}

/// Paired difference a − b of one quantity, with the relative change
/// (a − b)/b in %.
pub fn paired(
    a: &MethodRuns,
    b: &MethodRuns,
    window: Window,
    q: Quantity,
) -> Option<(MeanCi, f64)> {
    let (va, vb) = (a.values(window, q), b.values(window, q));
    let d = paired_difference_ci95(&va, &vb)?;
    let mean_b = vb.iter().sum::<f64>() / vb.len().max(1) as f64;
    Some((d, 100.0 * d.mean / mean_b))
}

/// How a paired difference reads.
fn verdict_of(d: &MeanCi) -> &'static str {
    if d.upper() < 0.0 {
        "smaller (significant)"
    } else if d.lower() > 0.0 {
        "larger (significant)"
    } else {
        "no significant difference"
    }
}

fn fmt_m(v: f64) -> String {
    if v.abs() >= 1.0e5 {
        format!("{v:.3e}")
    } else if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.2}")
    }
}

fn fmt_ci_m(c: &MeanCi) -> String {
    if c.mean.abs() >= 1.0e5 {
        format!("{:.3e} ± {:.1e}", c.mean, c.half_width)
    } else if c.mean.abs() >= 100.0 {
        fmt_ci(c, 0)
    } else {
        fmt_ci(c, 2)
    }
}

/// Runs the group with the documented 200 runs (or `--runs`).
pub fn run(ctx: &Context) -> Result<(), String> {
    let info = scenario::info(SCENARIO).ok_or("scenario he-tcas missing")?;
    let config = HeTcasConfig::with_runs(ctx.runs(info.monte_carlo_runs));
    let started = std::time::Instant::now();
    let out = simulate(&config)?;
    let elapsed = started.elapsed().as_secs_f64();
    let dir = ctx.group_dir(NAME)?;
    write_outputs(&dir, &out, elapsed)
}

fn write_outputs(dir: &Path, out: &HeTcasOutcome, elapsed_s: f64) -> Result<(), String> {
    let get = |m: Method| out.method(m).ok_or_else(|| format!("{m:?} missing"));
    let ra = get(Method::RangeAzimuthF64)?;
    let m2 = get(Method::AlphaBetaM2)?;
    let kf = get(Method::KalmanCv)?;

    // RMSE table.
    let mut rmse = Table::new([
        "method",
        "position overall (m)",
        "position late (m)",
        "range overall (m)",
        "range late (m)",
        "cross-range overall (m)",
        "cross-range late (m)",
        "range bias overall (m)",
        "range bias late (m)",
        "refused updates (batch ML: unconverged solves)",
    ]);
    for m in &out.methods {
        let mut row = vec![m.method.label().to_string()];
        for q in Quantity::ALL {
            for w in [Window::Overall, Window::Late] {
                row.push(fmt_ci_m(&m.ci(w, q)));
            }
        }
        row.push(m.refused.to_string());
        rmse.push(row);
    }
    rmse.write(dir, "rmse")?;

    // Paired differences: range–azimuth minus each comparison.
    let mut pairs = Table::new([
        "comparison",
        "quantity",
        "window",
        "mean difference (m)",
        "relative (%)",
        "reading",
    ]);
    let mut others = vec![m2, kf];
    others.extend(out.method(Method::BatchMl));
    for other in others {
        for q in Quantity::ALL {
            for (w, wl) in [(Window::Overall, "t >= 2 s"), (Window::Late, "t >= 400 s")] {
                if let Some((d, rel)) = paired(ra, other, w, q) {
                    pairs.push([
                        format!("range-azimuth - {}", other.method.label()),
                        q.label().to_string(),
                        wl.to_string(),
                        fmt_ci_m(&d),
                        format!("{rel:+.1}"),
                        format!("range-azimuth {}", verdict_of(&d)),
                    ]);
                }
            }
        }
    }
    if let Some(printed) = out.method(Method::RangeAzimuthEq9AsPrinted) {
        for (a, b) in [(printed, m2), (printed, ra)] {
            for q in Quantity::ALL {
                for (w, wl) in [(Window::Overall, "t >= 2 s"), (Window::Late, "t >= 400 s")] {
                    if let Some((d, rel)) = paired(a, b, w, q) {
                        pairs.push([
                            format!("{} - {}", a.method.label(), b.method.label()),
                            q.label().to_string(),
                            wl.to_string(),
                            fmt_ci_m(&d),
                            format!("{rel:+.1}"),
                            format!("eq. 9 as printed {}", verdict_of(&d)),
                        ]);
                    }
                }
            }
        }
    }
    pairs.write(dir, "paired_differences")?;

    // Numeric types.
    let mut types = Table::new([
        "arithmetic",
        "position RMSE overall (m)",
        "position RMSE late (m)",
        "max dist to f64 position (m)",
        "RMS dist to f64 position (m)",
        "max dist to f64 velocity (m/s)",
        "refused updates",
    ]);
    for (m, d) in [
        (Method::RangeAzimuthF64, Some(Deviation::default())),
        (Method::RangeAzimuthF32, out.f32_deviation),
        (Method::RangeAzimuthFix, out.fix_deviation),
    ] {
        if let (Some(r), Some(d)) = (out.method(m), d) {
            types.push([
                m.label().to_string(),
                fmt_ci_m(&r.ci(Window::Overall, Quantity::Position)),
                fmt_ci_m(&r.ci(Window::Late, Quantity::Position)),
                format!("{:.3e}", d.max_position_m),
                format!("{:.3e}", d.rms_position_m),
                format!("{:.3e}", d.max_velocity_m_per_s),
                r.refused.to_string(),
            ]);
        }
    }
    types.write(dir, "numeric_types")?;

    // Error against time (CSV) and plots.
    // Every method but the diverging fixed-gain αβ and the duplicates of the
    // f64 range–azimuth filter in other arithmetics.
    let in_csv: Vec<Method> = out
        .methods
        .iter()
        .map(|m| m.method)
        .filter(|m| {
            !matches!(
                m,
                Method::AlphaBetaKalata | Method::RangeAzimuthF32 | Method::RangeAzimuthFix
            )
        })
        .collect();
    let mut csv = String::from("t");
    for m in &in_csv {
        for q in Quantity::ALL {
            let kind = if q == Quantity::RangeBias {
                "mean"
            } else {
                "rmse"
            };
            let _ = write!(csv, ",{} {} {kind}", m.label(), q.label());
        }
    }
    csv.push('\n');
    for (k, t) in out.scan_times.iter().enumerate() {
        let _ = write!(csv, "{t}");
        for &m in &in_csv {
            let r = out.method(m).and_then(|r| r.against_time.get(k));
            for q in Quantity::ALL {
                let _ = write!(csv, ",{}", r.map_or(f64::NAN, |r| q.of(r)));
            }
        }
        csv.push('\n');
    }
    write_file(&dir.join("error_vs_time.csv"), &csv)?;

    let runs = out.config.runs;
    use Method::*;
    let plots: [(Quantity, &str, &str, &str, &[Method]); 4] = [
        (
            Quantity::Position,
            "position_error_vs_time.svg",
            "He et al. scenario: position error RMSE vs time (range-azimuth under alpha-beta M2)",
            "RMSE across runs (m)",
            &[
                RangeAzimuthF64,
                RangeAzimuthEq9AsPrinted,
                AlphaBetaM2,
                KalmanCv,
                BatchMl,
            ],
        ),
        (
            Quantity::Range,
            "range_error_vs_time.svg",
            "He et al. scenario: range (along line of sight) error RMSE vs time",
            "RMSE across runs (m)",
            &[
                RangeAzimuthF64,
                AlphaBetaM2,
                RangeAzimuthRangeResidual,
                AlphaBetaM2Debiased,
                BatchMl,
            ],
        ),
        (
            Quantity::RangeBias,
            "range_bias_vs_time.svg",
            "He et al. scenario: mean range error (bias) vs time",
            "mean over runs (m)",
            &[
                RangeAzimuthF64,
                RangeAzimuthEq9AsPrinted,
                AlphaBetaM2,
                RangeAzimuthRangeResidual,
                AlphaBetaM2Debiased,
                BatchMl,
            ],
        ),
        (
            Quantity::CrossRange,
            "cross_range_error_vs_time.svg",
            "He et al. scenario: cross-range error RMSE vs time",
            "RMSE across runs (m)",
            &[RangeAzimuthF64, AlphaBetaM2, KalmanCv, BatchMl],
        ),
    ];
    for (q, file, title, y_label, methods) in plots {
        let series: Vec<Series> = methods
            .iter()
            .filter_map(|&m| out.method(m))
            .map(|r| {
                Series::line(
                    format!("{} ({runs} runs)", r.method.label()),
                    out.scan_times
                        .iter()
                        .zip(&r.against_time)
                        .skip(FIRST_SCORED_SCAN)
                        .map(|(&t, e)| (t, q.of(e)))
                        .collect(),
                )
            })
            .collect();
        // The first filtered scans carry the two-point start's error: clip
        // the y axis at 3× the largest value after t = 50 s so the rest of
        // the curves stays readable.
        let late_max = series
            .iter()
            .flat_map(|s| s.points.iter().filter(|p| p.0 >= 50.0).map(|p| p.1.abs()))
            .fold(0.0f64, f64::max);
        plot(
            &dir.join(file),
            &PlotSpec {
                title,
                x_label: "t (s)",
                y_label,
                equal_aspect: false,
                y_max: Some(late_max * 3.0),
            },
            &series,
        )?;
    }

    let dev_series = |slot: usize, name: &str| {
        Series::line(
            name,
            out.scan_times
                .iter()
                .zip(&out.deviation_against_time)
                .map(|(&t, d)| (t, d[slot]))
                .collect(),
        )
    };
    plot(
        &dir.join("numeric_deviation_vs_time.svg"),
        &PlotSpec {
            title: "range-azimuth filter: max over runs of |p - p_f64|",
            x_label: "t (s)",
            y_label: "position deviation from f64 (m)",
            equal_aspect: false,
            y_max: None,
        },
        &[dev_series(0, "f32"), dev_series(1, "Q32.32")],
    )?;

    // Estimates from t = 5 s: the first filtered scans jump by tens of km
    // across the line of sight and would hide the rest.
    let km = |v: &[(f64, f64)], skip: usize| {
        v.iter()
            .skip(skip)
            .map(|&(x, y)| (x / 1e3, y / 1e3))
            .collect::<Vec<_>>()
    };
    plot(
        &dir.join("tracks_run0.svg"),
        &PlotSpec {
            title: "He et al. scenario, run 0: relative track (km; estimates from t = 5 s)",
            x_label: "x = R sin B (km)",
            y_label: "y = R cos B (km)",
            equal_aspect: true,
            y_max: None,
        },
        &[
            Series::points("measurements", km(&out.run0.measured, 0)),
            Series::line("alpha-beta M2", km(&out.run0.alpha_beta, 5)),
            Series::line("range-azimuth", km(&out.run0.range_azimuth, 5)),
            Series::line("truth", km(&out.run0.truth, 0)),
        ],
    )?;

    write_file(&dir.join("summary.md"), &summary(out, elapsed_s)?)
}

/// Host time per update (ns) of the range–azimuth filter and of the αβ M2
/// baseline including its polar-to-x/y conversion, in arithmetic `S`, over
/// run 0's 500 measurements: the fastest of [`COST_BATCHES`] batches of
/// `reps` passes each (the machine is shared; the minimum is the least
/// disturbed). Only the ratio means anything for a target; the firmware
/// benchmarks measure cycles.
pub fn cost_per_update_ns<S: Scalar>(reps: usize) -> Result<(f64, f64), String> {
    let data = scenario::generate(SCENARIO, scenario::monte_carlo_seed(BASE_SEED, 0))
        .map_err(|e| e.to_string())?;
    let meas: Vec<(S, S)> = data
        .scans
        .iter()
        .filter_map(|s| match s.measurements.first() {
            Some(Measurement::Polar { range, azimuth, .. }) => {
                Some((S::from_f64_lossy(*range), S::from_f64_lossy(*azimuth)))
            }
            _ => None,
        })
        .collect();
    let dt = S::ONE;
    let noise = RangeAzimuthNoise::<S>::new_f64(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        HE_AZIMUTH_VARIANCE,
        ACCEL_SIGMA * ACCEL_SIGMA,
    )
    .map_err(|e| e.to_string())?;
    let n = (reps * meas.len()).max(1) as f64;
    let time = |pass: &dyn Fn()| {
        (0..COST_BATCHES)
            .map(|_| {
                let start = std::time::Instant::now();
                for _ in 0..reps {
                    pass();
                }
                start.elapsed().as_secs_f64() * 1e9 / n
            })
            .fold(f64::INFINITY, f64::min)
    };
    let ra = time(&|| {
        let mut f = RangeAzimuthFilter::<S>::new(noise);
        for &(r, b) in &meas {
            let _ = std::hint::black_box(f.update(std::hint::black_box(r), b, dt));
        }
        std::hint::black_box(f.position());
    });
    let ab = time(&|| {
        let mut f: ScheduledFilter<S, LeastSquaresGains, 2, 2> =
            ScheduledFilter::new(LeastSquaresGains::default());
        for &(r, b) in &meas {
            let (sin_b, cos_b) = S::sin_cos(std::hint::black_box(b));
            let _ = std::hint::black_box(f.update([r * sin_b, r * cos_b], dt));
        }
        std::hint::black_box(f.filter().position());
    });
    Ok((ra, ab))
}

/// Batches of [`cost_per_update_ns`].
pub const COST_BATCHES: usize = 7;

fn summary(out: &HeTcasOutcome, elapsed_s: f64) -> Result<String, String> {
    let get = |m: Method| out.method(m).ok_or_else(|| format!("{m:?} missing"));
    let ra = get(Method::RangeAzimuthF64)?;
    let m2 = get(Method::AlphaBetaM2)?;
    let kf = get(Method::KalmanCv)?;
    let kal = get(Method::AlphaBetaKalata)?;
    let ml = out.method(Method::BatchMl);
    let runs = out.config.runs;
    let pd = |q, w| paired(ra, m2, w, q).ok_or("paired");
    let (pos_o, pos_o_rel) = pd(Quantity::Position, Window::Overall)?;
    let (pos_l, pos_l_rel) = pd(Quantity::Position, Window::Late)?;
    let (rng_o, rng_o_rel) = pd(Quantity::Range, Window::Overall)?;
    let (rng_l, rng_l_rel) = pd(Quantity::Range, Window::Late)?;
    let (crs_o, crs_o_rel) = pd(Quantity::CrossRange, Window::Overall)?;
    let (crs_l, crs_l_rel) = pd(Quantity::CrossRange, Window::Late)?;
    let (kf_pos_l, kf_pos_l_rel) =
        paired(ra, kf, Window::Late, Quantity::Position).ok_or("paired")?;
    let c = |m: &MethodRuns, w, q| fmt_ci_m(&m.ci(w, q));
    let switch = kalata_switch_scan(out.config.accel_sigma, 280_000.0)?;
    let kalata = kalata_baseline_gains(out.config.accel_sigma, 280_000.0)?;
    let end = |m: &MethodRuns, q: Quantity| m.against_time.last().map_or(f64::NAN, |e| q.of(e));
    let at =
        |m: &MethodRuns, t: usize, q: Quantity| m.against_time.get(t).map_or(f64::NAN, |e| q.of(e));
    let late_mean = |m: &MethodRuns, q| m.ci(Window::Late, q).mean;
    let lower_range_times: Vec<f64> = out
        .scan_times
        .iter()
        .zip(ra.against_time.iter().zip(&m2.against_time))
        .skip(FIRST_SCORED_SCAN)
        .filter(|(_, (a, b))| a.range < 0.9 * b.range)
        .map(|(&t, _)| t)
        .collect();
    let lower_window = lower_range_times
        .first()
        .zip(lower_range_times.last())
        .map(|(&a, &b)| (a, b));
    let sigma_b = HE_AZIMUTH_VARIANCE.sqrt();
    let final_range = 140_000f64.hypot(280_000.0 * 0.75f64.sqrt() - 200.0 / 3.6 * 499.0);

    // Verdict on claim 1 with a practical threshold: an improvement counts
    // if it is at least [`MEANINGFUL_IMPROVEMENT`] of the baseline's error
    // with 95 % confidence, in both windows.
    let threshold = |w| -MEANINGFUL_IMPROVEMENT * m2.ci(w, Quantity::Position).mean;
    let better = |d: &MeanCi, w| d.upper() < threshold(w);
    let not_better = |d: &MeanCi, w| d.lower() > threshold(w);
    let verdict = if better(&pos_o, Window::Overall) && better(&pos_l, Window::Late) {
        "**reproduced**"
    } else if not_better(&pos_o, Window::Overall) && not_better(&pos_l, Window::Late) {
        "**not reproduced**"
    } else {
        "**partly reproduced**"
    };

    let mut s = String::new();
    let _ = writeln!(
        s,
        "# he-tcas: He, Peng, Ling & Quan, range–azimuth tracking filter (seed 003)\n"
    );
    let _ = writeln!(
        s,
        "Scenario `he-tcas` (He et al. §4): own aircraft at 900 km/h behind a 700 km/h target flying the same \
         direction, azimuth 30°, 280 km, T = 1 s, 500 s; range σ 100 m, bearing variance 7.569e-3 rad² \
         (σ_B = 4.98°, the paper's VAR = R²·7.569e-3: ≈ 24 km across the line of sight at 280 km). {runs} Monte \
         Carlo runs (base seed {:#x}); process noise σ_a = {} m/s² for the range–azimuth and Kalman filters. \
         Scored from t = 2 s (*overall*) and from t = {LATE_PHASE_START_S} s (*late*); mean per-run RMSE ± 95 % \
         CI, paired differences over the same noise. Runtime {elapsed_s:.1} s (release, {} threads; the \
         batch yardstick is most of it).\n",
        out.config.base_seed,
        out.config.accel_sigma,
        rayon::current_num_threads()
    );
    let _ = writeln!(s, "## The paper's claims\n");
    let _ = writeln!(s, "1. The range–azimuth filter's estimation error is \"significantly less\" than the conventional αβ filter's on a uniformly moving target (§4, §5).");
    let _ = writeln!(s, "2. Its estimation error \"tends to zero faster\" than the αβ filter's, \"and the fluctuation is small\" (Fig. 5).");
    let _ = writeln!(s, "3. The filtered error is \"gradually approaching to zero\" while the observation error persists (Figs. 4–5).");
    let _ = writeln!(
        s,
        "4. It retains the αβ filter's low computation cost (abstract, §5).\n"
    );

    let _ = writeln!(s, "## Our numbers ({runs} runs)\n");
    let _ = writeln!(s, "| method | position overall (m) | position late (m) | range late (m) | range bias late (m) | cross-range late (m) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    let mut rows = vec![ra, m2];
    rows.extend(ml);
    rows.push(kf);
    rows.extend(
        [
            Method::RangeAzimuthEq9AsPrinted,
            Method::RangeAzimuthRangeResidual,
            Method::AlphaBetaM2Debiased,
        ]
        .iter()
        .filter_map(|&m| out.method(m)),
    );
    for m in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            m.method.label(),
            c(m, Window::Overall, Quantity::Position),
            c(m, Window::Late, Quantity::Position),
            c(m, Window::Late, Quantity::Range),
            c(m, Window::Late, Quantity::RangeBias),
            c(m, Window::Late, Quantity::CrossRange),
        );
    }
    let _ = writeln!(
        s,
        "\nRange–azimuth minus αβ M2, paired: position {} m ({pos_o_rel:+.1} %) overall, {} m ({pos_l_rel:+.1} %) \
         late; range {} m ({rng_o_rel:+.1} %) overall, {} m ({rng_l_rel:+.1} %) late; cross-range {} m \
         ({crs_o_rel:+.1} %) overall, {} m ({crs_l_rel:+.1} %) late.\n",
        fmt_ci_m(&pos_o),
        fmt_ci_m(&pos_l),
        fmt_ci_m(&rng_o),
        fmt_ci_m(&rng_l),
        fmt_ci_m(&crs_o),
        fmt_ci_m(&crs_l),
    );
    let _ = writeln!(
        s,
        "Against time (RMSE across runs, position / range): t = 10 s: range–azimuth {} / {} m, αβ M2 {} / {} m; \
         t = 100 s: {} / {} m vs {} / {} m; t = 499 s: {} / {} m vs {} / {} m. A single measurement's error at \
         280 km is ≈ {:.0} m in position and 100 m in range.\n",
        fmt_m(at(ra, 10, Quantity::Position)),
        fmt_m(at(ra, 10, Quantity::Range)),
        fmt_m(at(m2, 10, Quantity::Position)),
        fmt_m(at(m2, 10, Quantity::Range)),
        fmt_m(at(ra, 100, Quantity::Position)),
        fmt_m(at(ra, 100, Quantity::Range)),
        fmt_m(at(m2, 100, Quantity::Position)),
        fmt_m(at(m2, 100, Quantity::Range)),
        fmt_m(end(ra, Quantity::Position)),
        fmt_m(end(ra, Quantity::Range)),
        fmt_m(end(m2, Quantity::Position)),
        fmt_m(end(m2, Quantity::Range)),
        (RANGE_SIGMA_M.powi(2) + 280_000f64.powi(2) * HE_AZIMUTH_VARIANCE).sqrt(),
    );
    let _ = writeln!(
        s,
        "**The baseline.** αβ M2 is plain per-axis αβ on x = R sin B, y = R cos B with He et al.'s own eq. (6) \
         gains α(k) = 2(2k−1)/(k(k+1)), β(k) = 6/(k(k+1)) — the least-squares line through all measurements, the \
         matched design for a constant-velocity target from a two-point start. The usual \"least squares, then \
         steady state\" schedule would switch to Kalata's steady-state gains for the same σ_a and the per-axis \
         converted noise (α = {:.4}, β = {:.2e}) only at k = {switch} > 500, so within this run it is the same \
         filter. Those steady-state gains alone (\"αβ Kalata\" in `rmse.md`) never recover from the two-point \
         start's ≈ 30 km/s velocity error (late position RMSE {} m): not a fair baseline, not used.\n",
        kalata.alpha(),
        kalata.beta(),
        c(kal, Window::Late, Quantity::Position),
    );
    let _ = writeln!(
        s,
        "## Verdict: {verdict}\n\n(Claim 1 counts as reproduced if the range–azimuth filter's position RMSE is \
         lower than αβ M2's by at least {:.0} % with 95 % confidence, overall and late; as not reproduced if \
         it is certainly not.)\n",
        100.0 * MEANINGFUL_IMPROVEMENT
    );
    let _ = writeln!(
        s,
        "- **Claim 1 (smaller estimation error): not reproduced.** The position error of the range–azimuth filter \
         is the plain αβ filter's to within {:.1} % ({pos_o_rel:+.1} % overall: {}; {pos_l_rel:+.1} % late: {}). \
         The position error is almost all cross-range error (bearing noise ≈ 24 km at 280 km), and across the \
         line of sight both filters average the same bearing measurements with practically the same weights: M2 \
         is the least-squares line, and the range–azimuth filter's W1, W2 are the Kalman gains of a \
         nearly noise-free constant-velocity model for the same variance."
        ,
        pos_o_rel.abs().max(pos_l_rel.abs()),
        verdict_of(&pos_o),
        verdict_of(&pos_l),
    );
    let _ = writeln!(
        s,
        "- Along the line of sight the range–azimuth filter's range RMSE is lower ({rng_o_rel:+.1} % overall, \
         {rng_l_rel:+.1} % late), but both are dominated by biases of about 1 km and opposite sign (late: {:+.0} m \
         and {:+.0} m). The αβ filter inherits the conversion bias of x = R sin B with a noisy B, \
         −R(1 − e^{{−σ_B²/2}}) ≈ {:+.0} m at the final range; the range–azimuth filter's eq. (11) projects the \
         prediction onto the *measured* line of sight, which is shorter than |p̂| by |p̂|(1 − cos δB), so its range \
         settles ≈ +R·σ_B²/2 ≈ {:+.0} m outwards. Removing each bias (the variant rows: αβ on the debiased \
         conversion e^{{σ_B²/2}}·R·(sin B, cos B); range–azimuth with RESID_R = R − |p̂|) brings the late range \
         RMSE to {} m and {} m and the late position RMSE to {} m and {} m — again the same for both.",
        late_mean(ra, Quantity::RangeBias),
        late_mean(m2, Quantity::RangeBias),
        -final_range * (1.0 - (-HE_AZIMUTH_VARIANCE / 2.0).exp()),
        final_range * HE_AZIMUTH_VARIANCE / 2.0,
        out.method(Method::AlphaBetaM2Debiased).map_or("-".into(), |m| c(m, Window::Late, Quantity::Range)),
        out.method(Method::RangeAzimuthRangeResidual).map_or("-".into(), |m| c(m, Window::Late, Quantity::Range)),
        out.method(Method::AlphaBetaM2Debiased).map_or("-".into(), |m| c(m, Window::Late, Quantity::Position)),
        out.method(Method::RangeAzimuthRangeResidual).map_or("-".into(), |m| c(m, Window::Late, Quantity::Position)),
    );
    if let Some(printed) = out.method(Method::RangeAzimuthEq9AsPrinted) {
        let (po, po_rel) =
            paired(printed, m2, Window::Overall, Quantity::Position).ok_or("paired")?;
        let (pl, pl_rel) = paired(printed, m2, Window::Late, Quantity::Position).ok_or("paired")?;
        let (co, co_rel) =
            paired(printed, ra, Window::Overall, Quantity::Position).ok_or("paired")?;
        let (rl, rl_rel) = paired(printed, ra, Window::Late, Quantity::Range).ok_or("paired")?;
        let printed_verdict = if better(&po, Window::Overall) && better(&pl, Window::Late) {
            "reproduced"
        } else if not_better(&po, Window::Overall) && not_better(&pl, Window::Late) {
            "not reproduced"
        } else {
            "partly reproduced"
        };
        let _ = writeln!(
            s,
            "- **Eq. (9) exactly as printed** (VAR = R²·7.569e-3 in place of σ_R², the literal reading; the \
             f64 reference `reference_ra` with `Eq9Reading::AsPrinted`): the range direction then has the cross-range \
             variance, α = W1 and β/T = W2 at every scan, and eqs. (12)–(13) reduce to a per-axis filter on x = R sin B, \
             y = R cos B. Position RMSE {} m overall, {} m late; minus αβ M2, paired: {} m ({po_rel:+.1} %) overall, {} m \
             ({pl_rel:+.1} %) late; minus the consistent reading: {} m ({co_rel:+.1} %) overall; late range RMSE minus the \
             consistent reading's {} m ({rl_rel:+.1} %), range bias late {} m. **Claim 1 under this reading: \
             {printed_verdict}** (same {:.0} % rule): it is the per-axis αβ filter the paper compares against, with \
             Kalman instead of least-squares gains.",
            c(printed, Window::Overall, Quantity::Position),
            c(printed, Window::Late, Quantity::Position),
            fmt_ci_m(&po),
            fmt_ci_m(&pl),
            fmt_ci_m(&co),
            fmt_ci_m(&rl),
            c(printed, Window::Late, Quantity::RangeBias),
            100.0 * MEANINGFUL_IMPROVEMENT,
        );
    }
    if let Some(ml) = ml {
        let (d, rel) = paired(ra, ml, Window::Late, Quantity::Position).ok_or("paired")?;
        let _ = writeln!(
            s,
            "- What the data allow: the maximum-likelihood straight line through all polar measurements (the \
             yardstick; the truth is exactly straight) reaches {} m late position RMSE and {} m late range RMSE; \
             the range–azimuth filter is {} m ({:+.0} %) above it. The accurate ranges along a slowly rotating \
             line of sight (3° in 500 s) do carry cross-range information, and neither recursive filter uses it. \
             ({} of {} yardstick solves stopped at the iteration limit.)",
            c(ml, Window::Late, Quantity::Position),
            c(ml, Window::Late, Quantity::Range),
            fmt_ci_m(&d),
            rel,
            ml.refused,
            runs * (out.scan_times.len().saturating_sub(FIRST_SCORED_SCAN)),
        );
    }
    let _ = writeln!(
        s,
        "- Where the paper's idea does pay: against the textbook converted-measurement Kalman filter (first-order \
         covariance at the measured azimuth) the range–azimuth filter's late position RMSE is lower by {:.0} ± \
         {:.0} m ({:.0} %). With R·σ_B²/σ_R ≈ {:.0} ≫ 1 the first-order conversion is inconsistent: the \
         Kalman filter takes each measurement as accurate to 100 m along a line of sight that is itself wrong by \
         ±5°, and its covariance collapses in every direction; keeping range and cross-range covariances apart, \
         as He et al. do, avoids that.",
        -kf_pos_l.mean,
        kf_pos_l.half_width,
        -kf_pos_l_rel,
        280_000.0 * HE_AZIMUTH_VARIANCE / RANGE_SIGMA_M,
    );
    let _ = writeln!(
        s,
        "- **Claim 2 (converges faster, fluctuates less): not reproduced** for the position error — the curves \
         of `position_error_vs_time.svg` lie on top of each other (t = 10 s: {} vs {} m; t = 100 s: {} vs {} m). \
         The range–azimuth filter's range RMSE is more than 10 % below αβ M2's only from t = {} s to {} s, while \
         its bias swings from the inward two-point start to its outward steady state (`range_bias_vs_time.svg`).",
        fmt_m(at(ra, 10, Quantity::Position)),
        fmt_m(at(m2, 10, Quantity::Position)),
        fmt_m(at(ra, 100, Quantity::Position)),
        fmt_m(at(m2, 100, Quantity::Position)),
        lower_window.map_or("-".into(), |w| format!("{:.0}", w.0)),
        lower_window.map_or("-".into(), |w| format!("{:.0}", w.1)),
    );
    let _ = writeln!(
        s,
        "- **Claim 3 (error approaches zero): not reproduced** literally: the error falls from ≈ 24 km to {} m \
         (range–azimuth) and {} m (αβ M2) at t = 499 s. With σ_B = 5° the cross-range error of a least-squares \
         line after n scans is ≈ 2·R·σ_B/√n ≈ {:.0} m at n = 500; it cannot approach zero within the run.",
        fmt_m(end(ra, Quantity::Position)),
        fmt_m(end(m2, Quantity::Position)),
        2.0 * final_range * sigma_b / 500f64.sqrt(),
    );
    let costs = (
        cost_per_update_ns::<f64>(20)?,
        cost_per_update_ns::<Fix>(5)?,
    );
    let _ = writeln!(
        s,
        "- **Claim 4 (αβ cost): partly.** Both are O(1) per update with no matrix inversion, but the range–azimuth \
         update also propagates and updates two 2×2 covariances (square-root form here: hypot, square roots, \
         divisions). Host timing of one update (fastest of 7 batches on this shared machine; indicative only): f64 {:.0} ns vs {:.0} ns for \
         αβ M2 including its sin/cos conversion (×{:.1}); Q32.32 {:.0} ns vs {:.0} ns (×{:.1}).",
        costs.0 .0,
        costs.0 .1,
        costs.0 .0 / costs.0 .1,
        costs.1 .0,
        costs.1 .1,
        costs.1 .0 / costs.1 .1,
    );
    if let (Some(f32d), Some(fixd), Some(f32r), Some(fixr)) = (
        out.f32_deviation,
        out.fix_deviation,
        out.method(Method::RangeAzimuthF32),
        out.method(Method::RangeAzimuthFix),
    ) {
        let _ = writeln!(
            s,
            "- **On-target arithmetic**: over the same {runs} runs the f32 filter deviates from f64 by at most \
             {:.3} m in position (RMS {:.3} m; velocity ≤ {:.2e} m/s) and Q32.32 by at most {:.2e} m (RMS {:.2e} \
             m; velocity ≤ {:.2e} m/s); late position RMSE f32 {} m, Q32.32 {} m, f64 {} m; refused updates: f32 \
             {}, Q32.32 {}.",
            f32d.max_position_m,
            f32d.rms_position_m,
            f32d.max_velocity_m_per_s,
            fixd.max_position_m,
            fixd.rms_position_m,
            fixd.max_velocity_m_per_s,
            c(f32r, Window::Late, Quantity::Position),
            c(fixr, Window::Late, Quantity::Position),
            c(ra, Window::Late, Quantity::Position),
            f32r.refused,
            fixr.refused,
        );
    }
    let _ = writeln!(
        s,
        "- Caveats: the paper's figures are not in the seed text (captions only), so their magnitudes cannot be \
         compared; the paper states no bearing noise and no process noise — σ_B² = 7.569e-3 rad² is taken from \
         its own VAR, σ_a = {} m/s² is our choice (a smaller one only brings the range–azimuth filter's gains \
         closer to the least-squares ones).\n",
        out.config.accel_sigma
    );
    let _ = writeln!(s, "Files: `rmse.md`, `paired_differences.md`, `numeric_types.md`, `error_vs_time.csv`, `position_error_vs_time.svg`, `range_error_vs_time.svg`, `range_bias_vs_time.svg`, `cross_range_error_vs_time.svg`, `numeric_deviation_vs_time.svg`, `tracks_run0.svg`.\n");
    let _ = writeln!(
        s,
        "Regenerate: `cd host-tests && cargo run --release --bin experiments -- --only he-tcas`."
    );
    Ok(s)
}
