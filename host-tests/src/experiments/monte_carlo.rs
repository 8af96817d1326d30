//! Single-target Monte Carlo machinery shared by the gain-schedule paper groups
//! (`alwagih`, `li`, `liu`): every method behind one [`Estimator`] interface,
//! the run loop, per-run RMSE over any subset of scans, paired comparisons
//! and claim verdicts, and the tables and plots the groups write.
//!
//! # What is scored
//! Every method sees the same measurements (Monte Carlo run r of scenario S
//! is `scenario::generate(S, monte_carlo_seed(base, r))`), so methods are
//! compared run by run ([`crate::metrics::paired_difference_ci95`]).
//! All filters start with two-point initialisation (Al-Wagih & Abdulla
//! eqs. 9–10; the Kalman baselines do the same, see [`crate::kalman`]), so
//! after the second measurement every method holds the same state; scoring
//! starts at the first filtered update, scan index [`FIRST_FILTERED`] (the
//! third measurement), for the filtered estimate and the one-step prediction
//! alike.
//!
//! * The *filtered* estimate at scan k is the method's position/velocity
//!   after incorporating measurement k (the quantity Li et al. and Liu et al.
//!   plot).
//! * The *prediction* at scan k is the position the method predicted for
//!   measurement k before seeing it: Al-Wagih & Abdulla's eq. (26) scores
//!   "actual position − predicted position". For their M5 bank the paper's
//!   "prediction" is chosen after seeing measurement k (see
//!   [`BankReadout`]).
//!
//! Per-run RMSE over scans K: √(Σ_{k∈K} e_k²/|K|) (eq. 26); the Monte Carlo
//! figure is the mean of the per-run RMSEs with a 95 % Student-t interval.
//! RMSE against time is √(Σ_r e_{r,k}²/R) per scan.

use std::path::Path;

use rayon::prelude::*;

use abtrack::bank::{BankConfig, BankOutcome, CartesianBank};
use abtrack::filter::{Phase, UpdateOutcome};
use abtrack::gain::spec::ScheduleSpec;
use abtrack::gain::{AnySchedule, ScheduledFilter, SwitchMode};
use abtrack::Scalar;

use super::common::{fmt_ci, plot, PlotSpec, Series, Table};
use crate::kalman::{
    isotropic, ConstantAccelerationKf, ConstantVelocityKf, Kalman, KalmanOutcome, ProcessNoise,
};
use crate::metrics::{mean_ci95, paired_difference_ci95, MeanCi, StateError};
use crate::scenario::{self, monte_carlo_seed, ScenarioInfo, ScenarioRun, SensorNoise, TruthState};

/// Scan index (0-based) of the first filtered update: measurements 0 and 1
/// initialise every method.
pub const FIRST_FILTERED: usize = 2;

/// Window capacity of the schedules built from specs (M3/M4 windows, Liu's
/// residual window). The defaults use 8 and 3.
pub const WINDOW_CAPACITY: usize = 16;

/// Member capacity of the M5 bank. The default bank has 8 members.
pub const BANK_CAPACITY: usize = 16;

/// What one method reports for one measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Output {
    /// The position predicted for this measurement (`None` while
    /// initialising).
    pub predicted: Option<[f64; 2]>,
    /// The filtered position and velocity after it.
    pub position: [f64; 2],
    pub velocity: [f64; 2],
    /// (α, β) per axis that produced the filtered estimate.
    pub gains: Option<[(f64, f64); 2]>,
    /// z − prediction per axis.
    pub innovation: Option<[f64; 2]>,
    /// Liu et al.'s adaptive switch only: the fixed-gain branch was taken.
    pub steady: Option<bool>,
}

/// A 2-D single-target estimator fed one measurement per scan.
pub trait Estimator {
    fn step(&mut self, z: [f64; 2], dt: f64) -> Result<Output, String>;
}

/// An αβ filter driven by a gain schedule named by a spec string (the same
/// strings `replay --schedule` takes), in number type `S`.
pub struct Scheduled<S: Scalar> {
    track: ScheduledFilter<S, AnySchedule<S, 2, WINDOW_CAPACITY>, 2, 2>,
}

impl<S: Scalar> Scheduled<S> {
    pub fn from_spec(spec: &str) -> Result<Self, String> {
        let parsed = ScheduleSpec::parse(spec).map_err(|e| format!("spec {spec:?}: {e}"))?;
        let schedule =
            AnySchedule::from_spec(&parsed).map_err(|e| format!("spec {spec:?}: {e}"))?;
        Ok(Scheduled {
            track: ScheduledFilter::new(schedule),
        })
    }
}

fn to_scalar<S: Scalar>(v: f64) -> Result<S, String> {
    S::try_from_f64(v).map_err(|e| format!("{v} in {}: {e}", S::NAME))
}

impl<S: Scalar> Estimator for Scheduled<S> {
    fn step(&mut self, z: [f64; 2], dt: f64) -> Result<Output, String> {
        let zs = [to_scalar::<S>(z[0])?, to_scalar::<S>(z[1])?];
        let u = self
            .track
            .update(zs, to_scalar(dt)?)
            .map_err(|e| e.to_string())?;
        let (predicted, innovation) = match u.outcome {
            [UpdateOutcome::Filtered(a), UpdateOutcome::Filtered(b)] => (
                Some([a.predicted.to_f64(), b.predicted.to_f64()]),
                Some([a.residual.to_f64(), b.residual.to_f64()]),
            ),
            _ => (None, None),
        };
        let steady = match (self.track.schedule(), u.gains) {
            (AnySchedule::AdaptiveSwitch(s), Some(_)) => {
                s.last_mode().map(|m| m == SwitchMode::Steady)
            }
            _ => None,
        };
        Ok(Output {
            predicted,
            position: self.track.filter().position().map(|v| v.to_f64()),
            velocity: self.track.filter().velocity().map(|v| v.to_f64()),
            gains: u
                .gains
                .map(|g| g.map(|g| (g.alpha().to_f64(), g.beta().to_f64()))),
            innovation,
            steady,
        })
    }
}

/// Which output of Al-Wagih & Abdulla's M5 bank is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BankReadout {
    /// Algorithm 3 step 3 as printed: after measurement z_k, per axis the
    /// member whose prediction had the least |z_k − x_p| is chosen; its
    /// prediction is the bank's "prediction" of z_k and its smoothed state
    /// the estimate. The prediction was chosen *knowing* z_k, so it is not a
    /// one-step-ahead prediction.
    Paper,
    /// The causal reading: the member chosen at the previous measurement
    /// (by the previous innovation) predicts z_k (`ParallelBank::predict`)
    /// and its smoothed state after z_k is the estimate.
    Causal,
}

/// Al-Wagih & Abdulla's M5, one [`abtrack::bank::ParallelBank`] per axis.
pub struct Bank {
    bank: CartesianBank<f64, BANK_CAPACITY, 2>,
    readout: BankReadout,
}

impl Bank {
    pub fn new(config: &BankConfig, readout: BankReadout) -> Result<Self, String> {
        Ok(Bank {
            bank: CartesianBank::from_config(config).map_err(|e| e.to_string())?,
            readout,
        })
    }
}

impl Estimator for Bank {
    fn step(&mut self, z: [f64; 2], dt: f64) -> Result<Output, String> {
        let before = self.bank.axes().map(|a| a.selected());
        let causal_prediction = if self.bank.phase() == Phase::Tracking {
            let [x, y] = self.bank.axes();
            Some([
                x.predict(dt).map_err(|e| e.to_string())?.position,
                y.predict(dt).map_err(|e| e.to_string())?.position,
            ])
        } else {
            None
        };
        let outcome = self.bank.update(z, dt).map_err(|e| e.to_string())?;
        let selections = match outcome {
            [BankOutcome::Filtered(a), BankOutcome::Filtered(b)] => Some([a, b]),
            _ => None,
        };
        let axes = self.bank.axes();
        let chosen: [usize; 2] = match (self.readout, selections) {
            (BankReadout::Paper, Some(s)) => s.map(|s| s.member),
            (BankReadout::Causal, Some(_)) => before,
            (_, None) => [0, 0],
        };
        let member = |axis: usize| {
            axes[axis]
                .member(chosen[axis])
                .ok_or_else(|| format!("bank member {} missing", chosen[axis]))
        };
        let (mx, my) = (member(0)?, member(1)?);
        let gains = selections.and_then(|_| {
            let gx = axes[0].member_gains(chosen[0])?;
            let gy = axes[1].member_gains(chosen[1])?;
            Some([(gx.alpha(), gx.beta()), (gy.alpha(), gy.beta())])
        });
        let (predicted, innovation) = match (self.readout, selections) {
            (BankReadout::Paper, Some(s)) => {
                (Some(s.map(|s| s.predicted)), Some(s.map(|s| s.residual)))
            }
            (BankReadout::Causal, Some(_)) => (
                causal_prediction,
                causal_prediction.map(|p| [z[0] - p[0], z[1] - p[1]]),
            ),
            (_, None) => (None, None),
        };
        Ok(Output {
            predicted,
            position: [mx.position(), my.position()],
            velocity: [mx.velocity(), my.velocity()],
            gains,
            innovation,
            steady: None,
        })
    }
}

/// The f64 Kalman yardstick (4-state CV or 6-state CA).
pub struct KalmanEstimator<const N: usize> {
    kf: Kalman<N>,
}

impl<const N: usize> Estimator for KalmanEstimator<N> {
    fn step(&mut self, z: [f64; 2], dt: f64) -> Result<Output, String> {
        let outcome = self.kf.update(z, dt).map_err(|e| e.to_string())?;
        let (predicted, innovation) = match outcome {
            KalmanOutcome::Filtered {
                predicted,
                innovation,
                ..
            } => (Some(predicted), Some(innovation)),
            _ => (None, None),
        };
        let gains = self
            .kf
            .last_gain()
            .filter(|_| predicted.is_some())
            .map(|k| {
                // Per axis α = K[pos][axis], β = T·K[vel][axis].
                let o = N / 2;
                [(k[0][0], dt * k[1][0]), (k[o][1], dt * k[o + 1][1])]
            });
        Ok(Output {
            predicted,
            position: self.kf.position(),
            velocity: self.kf.velocity(),
            gains,
            innovation,
            steady: None,
        })
    }
}

type Factory = Box<dyn Fn() -> Result<Box<dyn Estimator>, String> + Send + Sync>;

/// One method of an experiment: a label for tables, what it is exactly, and
/// how to build a fresh estimator for each run.
pub struct Method {
    pub label: String,
    /// The exact configuration: a canonical spec string, or the Kalman
    /// model and its parameters.
    pub detail: String,
    make: Factory,
}

impl Method {
    /// An αβ filter with the schedule `spec`, in number type `S`.
    pub fn schedule<S: Scalar + 'static>(label: &str, spec: &str) -> Result<Self, String> {
        // Build once so a bad spec fails before any run, and record the
        // canonical form (every parameter spelled out).
        let canonical = ScheduleSpec::parse(spec)
            .map_err(|e| format!("spec {spec:?}: {e}"))?
            .to_string();
        Scheduled::<S>::from_spec(spec)?;
        let owned = spec.to_string();
        Ok(Method {
            label: label.to_string(),
            detail: format!("`{canonical}` ({})", S::NAME),
            make: Box::new(move || Ok(Box::new(Scheduled::<S>::from_spec(&owned)?))),
        })
    }

    /// Al-Wagih & Abdulla's M5 bank.
    pub fn bank(label: &str, config: BankConfig, readout: BankReadout) -> Result<Self, String> {
        Bank::new(&config, readout)?;
        let spec = ScheduleSpec::Bank(config).to_string();
        let how = match readout {
            BankReadout::Paper => "member chosen by the current innovation, as printed",
            BankReadout::Causal => "member chosen by the previous innovation (causal)",
        };
        Ok(Method {
            label: label.to_string(),
            detail: format!("`{spec}` (f64), {how}"),
            make: Box::new(move || Ok(Box::new(Bank::new(&config, readout)?))),
        })
    }

    /// The 4-state constant-velocity Kalman filter with the scenario's
    /// documented process noise (DWNA σ_a) and R = σ²I.
    pub fn kalman_cv(label: &str, info: &ScenarioInfo) -> Result<Self, String> {
        Self::kalman_cv_with(
            label,
            info.kalman.cv_sigma_acceleration,
            measurement_sigma(info)?,
        )
    }

    /// The 4-state constant-velocity Kalman filter with DWNA σ_a
    /// (`sigma_a`, m/s²) and R = σ²I (`sigma`, m).
    pub fn kalman_cv_with(label: &str, sigma_a: f64, sigma: f64) -> Result<Self, String> {
        let noise = ProcessNoise::DiscreteWhiteAcceleration { sigma: sigma_a };
        let r = isotropic(sigma);
        ConstantVelocityKf::new(noise, r).map_err(|e| e.to_string())?;
        Ok(Method {
            label: label.to_string(),
            detail: format!(
                "4-state CV Kalman (f64), DWNA σ_a = {sigma_a} m/s², R = ({sigma} m)²·I"
            ),
            make: Box::new(move || {
                Ok(Box::new(KalmanEstimator {
                    kf: ConstantVelocityKf::new(noise, r).map_err(|e| e.to_string())?,
                }))
            }),
        })
    }

    /// A method from its parts: `make` builds a fresh estimator per run.
    pub fn from_factory(
        label: &str,
        detail: &str,
        make: impl Fn() -> Result<Box<dyn Estimator>, String> + Send + Sync + 'static,
    ) -> Self {
        Method {
            label: label.to_string(),
            detail: detail.to_string(),
            make: Box::new(make),
        }
    }

    /// The 6-state constant-acceleration Kalman filter (Wiener-sequence
    /// acceleration σ_Δa from the scenario, R = σ²I).
    pub fn kalman_ca(label: &str, info: &ScenarioInfo) -> Result<Self, String> {
        let sigma = info.kalman.ca_sigma_acceleration_increment;
        let noise = ProcessNoise::WienerAcceleration { sigma };
        let r = isotropic(measurement_sigma(info)?);
        ConstantAccelerationKf::new(noise, r).map_err(|e| e.to_string())?;
        Ok(Method {
            label: label.to_string(),
            detail: format!(
                "6-state CA Kalman (f64), Wiener acceleration σ_Δa = {sigma} m/s², R = ({} m)²·I",
                measurement_sigma(info)?
            ),
            make: Box::new(move || {
                Ok(Box::new(KalmanEstimator {
                    kf: ConstantAccelerationKf::new(noise, r).map_err(|e| e.to_string())?,
                }))
            }),
        })
    }

    /// Any other estimator (e.g. an f64 reference of a reading the library
    /// does not implement), built fresh for every run by `make`.
    pub fn estimator(
        label: &str,
        detail: &str,
        make: impl Fn() -> Result<Box<dyn Estimator>, String> + Send + Sync + 'static,
    ) -> Result<Self, String> {
        make()?;
        Ok(Method {
            label: label.to_string(),
            detail: detail.to_string(),
            make: Box::new(make),
        })
    }

    pub fn build(&self) -> Result<Box<dyn Estimator>, String> {
        (self.make)()
    }
}

/// The per-axis measurement σ of a Cartesian scenario (the stationary σ of
/// coloured noise: the Kalman filters assume it white).
pub fn measurement_sigma(info: &ScenarioInfo) -> Result<f64, String> {
    match info.noise {
        SensorNoise::Cartesian { x, y } if x.sigma() == y.sigma() => Ok(x.sigma()),
        _ => Err(format!(
            "{}: the single-target groups need equal Cartesian noise on x and y",
            info.name
        )),
    }
}

/// One method at one scan of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRecord {
    /// Filtered estimate minus truth.
    pub error: StateError,
    /// Prediction minus truth (from [`FIRST_FILTERED`] on).
    pub prediction_error: Option<[f64; 2]>,
    pub output: Output,
}

/// One method over every run.
#[derive(Debug, Clone)]
pub struct MethodResult {
    pub label: String,
    pub detail: String,
    /// `runs[r][k]`: run r, scan k.
    pub runs: Vec<Vec<StepRecord>>,
}

/// A quantity scored by RMSE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    PositionX,
    PositionY,
    VelocityX,
    VelocityY,
    /// √(e_x² + e_y²): Liu et al.'s "distance between filtered and true value".
    PositionDistance,
    VelocityDistance,
    /// One-step prediction error (Al-Wagih & Abdulla eq. 26).
    PredictionX,
    PredictionY,
}

impl Metric {
    pub fn name(self) -> &'static str {
        match self {
            Metric::PositionX => "position x (m)",
            Metric::PositionY => "position y (m)",
            Metric::VelocityX => "velocity x (m/s)",
            Metric::VelocityY => "velocity y (m/s)",
            Metric::PositionDistance => "position distance (m)",
            Metric::VelocityDistance => "velocity distance (m/s)",
            Metric::PredictionX => "prediction x (m)",
            Metric::PredictionY => "prediction y (m)",
        }
    }

    /// The squared error of this metric at one step.
    fn squared(self, s: &StepRecord) -> Option<f64> {
        let e = &s.error;
        Some(match self {
            Metric::PositionX => e.position[0].powi(2),
            Metric::PositionY => e.position[1].powi(2),
            Metric::VelocityX => e.velocity[0].powi(2),
            Metric::VelocityY => e.velocity[1].powi(2),
            Metric::PositionDistance => e.position[0].powi(2) + e.position[1].powi(2),
            Metric::VelocityDistance => e.velocity[0].powi(2) + e.velocity[1].powi(2),
            Metric::PredictionX => s.prediction_error?[0].powi(2),
            Metric::PredictionY => s.prediction_error?[1].powi(2),
        })
    }
}

/// A named subset of scan indices (always from [`FIRST_FILTERED`] on).
#[derive(Clone, Copy)]
pub struct Segment<'a> {
    pub name: &'a str,
    pub contains: &'a dyn Fn(usize) -> bool,
}

/// Every filtered scan.
pub const ALL_SCANS: Segment<'static> = Segment {
    name: "all scans",
    contains: &|_| true,
};

impl MethodResult {
    /// Per-run RMSE of `metric` over the scans of `segment`.
    pub fn per_run(&self, metric: Metric, segment: Segment<'_>) -> Vec<f64> {
        self.runs
            .iter()
            .map(|run| {
                let (sum, n) = run
                    .iter()
                    .enumerate()
                    .skip(FIRST_FILTERED)
                    .filter(|(k, _)| (segment.contains)(*k))
                    .filter_map(|(_, s)| metric.squared(s))
                    .fold((0.0, 0usize), |(s, n), e| (s + e, n + 1));
                if n == 0 {
                    f64::NAN
                } else {
                    (sum / n as f64).sqrt()
                }
            })
            .collect()
    }

    /// Mean per-run RMSE with its 95 % interval.
    pub fn summary(&self, metric: Metric, segment: Segment<'_>) -> MeanCi {
        mean_ci95(&self.per_run(metric, segment))
    }

    /// RMSE across runs at each scan from [`FIRST_FILTERED`] on:
    /// (scan index, RMSE).
    pub fn against_time(&self, metric: Metric) -> Vec<(usize, f64)> {
        let len = self.runs.iter().map(Vec::len).max().unwrap_or(0);
        (FIRST_FILTERED..len)
            .filter_map(|k| {
                let (sum, n) = self
                    .runs
                    .iter()
                    .filter_map(|r| r.get(k).and_then(|s| metric.squared(s)))
                    .fold((0.0, 0usize), |(s, n), e| (s + e, n + 1));
                (n > 0).then(|| (k, (sum / n as f64).sqrt()))
            })
            .collect()
    }
}

/// The outcome of one Monte Carlo experiment.
pub struct Experiment {
    pub info: ScenarioInfo,
    pub base_seed: u64,
    /// The single target's truth per scan.
    pub truth: Vec<TruthState>,
    /// Run 0's data, for the track pictures.
    pub sample: ScenarioRun,
    pub methods: Vec<MethodResult>,
}

impl Experiment {
    pub fn runs(&self) -> usize {
        self.methods.first().map_or(0, |m| m.runs.len())
    }

    pub fn method(&self, label: &str) -> Result<&MethodResult, String> {
        self.methods
            .iter()
            .find(|m| m.label == label)
            .ok_or_else(|| format!("no method labelled {label:?}"))
    }

    /// Time of scan k (s).
    pub fn time(&self, k: usize) -> f64 {
        k as f64 * self.info.period_s
    }
}

/// The single-target measurements of a run: (scan index, z), one per scan.
fn measurements(run: &ScenarioRun) -> Result<Vec<[f64; 2]>, String> {
    run.scans
        .iter()
        .enumerate()
        .map(|(k, s)| match s.measurements.as_slice() {
            [m] => Ok(m.position()),
            other => Err(format!(
                "{} scan {k}: expected one measurement, got {}",
                run.info.name,
                other.len()
            )),
        })
        .collect()
}

fn run_one(
    methods: &[Method],
    run: &ScenarioRun,
    truth: &[TruthState],
) -> Result<Vec<Vec<StepRecord>>, String> {
    let z = measurements(run)?;
    let dt = run.info.period_s;
    methods
        .iter()
        .map(|m| {
            let mut est = m.build()?;
            z.iter()
                .zip(truth)
                .enumerate()
                .map(|(k, (z, t))| {
                    let out = est.step(*z, dt).map_err(|e| {
                        format!("{} at scan {k} of seed {}: {e}", m.label, run.seed)
                    })?;
                    Ok(StepRecord {
                        error: StateError::new(
                            out.position,
                            out.velocity,
                            [t.x, t.y],
                            [t.vx, t.vy],
                        ),
                        prediction_error: out.predicted.map(|p| [p[0] - t.x, p[1] - t.y]),
                        output: out,
                    })
                })
                .collect()
        })
        .collect()
}

/// Runs every method on `runs` Monte Carlo runs of `scenario` (seeds
/// `monte_carlo_seed(base_seed, 0..runs)`), spread over the cores by rayon
/// (its global pool, or the pool `run` is called in).
pub fn run(
    scenario: &str,
    base_seed: u64,
    runs: usize,
    methods: &[Method],
) -> Result<Experiment, String> {
    let info = scenario::info(scenario).ok_or_else(|| format!("unknown scenario {scenario}"))?;
    let truth: Vec<TruthState> = scenario::truth(scenario)
        .map_err(|e| e.to_string())?
        .into_iter()
        .map(|scan| match scan.as_slice() {
            [t] => Ok(*t),
            _ => Err(format!("{scenario} is not a single-target scenario")),
        })
        .collect::<Result<_, String>>()?;
    if runs == 0 {
        return Err("no Monte Carlo runs".into());
    }
    let generate = |r: usize| {
        scenario::generate(scenario, monte_carlo_seed(base_seed, r as u64))
            .map_err(|e| e.to_string())
    };
    let sample = generate(0)?;
    // Each run depends only on its own seed, and rayon's indexed collect
    // keeps run order: the results are the same, bit for bit, on any number
    // of threads (`tests/it/tools/monte_carlo.rs`).
    let per_run: Vec<Result<Vec<Vec<StepRecord>>, String>> = (0..runs)
        .into_par_iter()
        .map(|r| generate(r).and_then(|run| run_one(methods, &run, &truth)))
        .collect();
    let mut results: Vec<MethodResult> = methods
        .iter()
        .map(|m| MethodResult {
            label: m.label.clone(),
            detail: m.detail.clone(),
            runs: Vec::with_capacity(runs),
        })
        .collect();
    for run in per_run {
        for (res, steps) in results.iter_mut().zip(run?) {
            res.runs.push(steps);
        }
    }
    Ok(Experiment {
        info,
        base_seed,
        truth,
        sample,
        methods: results,
    })
}

// ---------------------------------------------------------------------------
// Comparisons and claims
// ---------------------------------------------------------------------------

/// What a paired comparison shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// The claimed-better method has the lower RMSE: the 95 % interval of
    /// (worse − better) lies above zero.
    Holds,
    /// Significantly the other way round.
    Opposite,
    /// The interval contains zero.
    Inconclusive,
}

impl Outcome {
    pub fn text(self) -> &'static str {
        match self {
            Outcome::Holds => "holds",
            Outcome::Opposite => "opposite",
            Outcome::Inconclusive => "inconclusive",
        }
    }
}

/// "`better` has a lower RMSE of `metric` than `worse` over `segment`",
/// tested on the per-run differences.
#[derive(Debug, Clone)]
pub struct Comparison {
    pub better: String,
    pub worse: String,
    pub metric: Metric,
    pub segment: String,
    /// Some context for the row (e.g. the noise type).
    pub context: String,
    pub better_rmse: MeanCi,
    pub worse_rmse: MeanCi,
    /// Mean of RMSE(worse) − RMSE(better) per run, with its 95 % interval.
    pub difference: MeanCi,
}

impl Comparison {
    pub fn outcome(&self) -> Outcome {
        if self.difference.lower() > 0.0 {
            Outcome::Holds
        } else if self.difference.upper() < 0.0 {
            Outcome::Opposite
        } else {
            Outcome::Inconclusive
        }
    }

    /// `worse − better` as "d ± h (x vs y)".
    pub fn describe(&self) -> String {
        format!(
            "{} {:.2} vs {} {:.2}: diff {}",
            self.better,
            self.better_rmse.mean,
            self.worse,
            self.worse_rmse.mean,
            fmt_ci(&self.difference, 2)
        )
    }
}

/// Compares two methods of `exp` run by run.
pub fn compare(
    exp: &Experiment,
    context: &str,
    better: &str,
    worse: &str,
    metric: Metric,
    segment: Segment<'_>,
) -> Result<Comparison, String> {
    let b = exp.method(better)?.per_run(metric, segment);
    let w = exp.method(worse)?.per_run(metric, segment);
    let difference = paired_difference_ci95(&w, &b).ok_or("run counts differ")?;
    Ok(Comparison {
        better: better.to_string(),
        worse: worse.to_string(),
        metric,
        segment: segment.name.to_string(),
        context: context.to_string(),
        better_rmse: mean_ci95(&b),
        worse_rmse: mean_ci95(&w),
        difference,
    })
}

/// Verdict on one of a paper's claims.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    Reproduced,
    Partly,
    NotReproduced,
}

impl Verdict {
    /// The verdict of a claim made of parts: all hold → reproduced, none →
    /// not reproduced, else partly.
    pub fn of_parts(parts: &[bool]) -> Verdict {
        let holds = parts.iter().filter(|&&p| p).count();
        if parts.is_empty() || holds == 0 {
            Verdict::NotReproduced
        } else if holds == parts.len() {
            Verdict::Reproduced
        } else {
            Verdict::Partly
        }
    }

    pub fn text(self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Partly => "partly",
            Verdict::NotReproduced => "not reproduced",
        }
    }

    /// Every comparison holds: reproduced; none: not reproduced; else partly.
    pub fn of(comparisons: &[Comparison]) -> Verdict {
        let parts: Vec<bool> = comparisons
            .iter()
            .map(|c| c.outcome() == Outcome::Holds)
            .collect();
        Verdict::of_parts(&parts)
    }
}

/// One claim of a paper, what we measured and the verdict.
#[derive(Debug, Clone)]
pub struct Claim {
    pub id: String,
    /// Where the paper says it (section / table / figure).
    pub source: String,
    /// The claim, quoted or paraphrased.
    pub claim: String,
    /// The comparisons that test it (may be empty for descriptive claims).
    pub comparisons: Vec<Comparison>,
    /// Our numbers, in a sentence.
    pub ours: String,
    pub verdict: Verdict,
    /// Why, in a sentence.
    pub reason: String,
}

impl Claim {
    /// A claim judged by its comparisons ([`Verdict::of`]).
    pub fn judged(
        id: &str,
        source: &str,
        claim: &str,
        comparisons: Vec<Comparison>,
        ours: String,
        reason: String,
    ) -> Claim {
        let verdict = Verdict::of(&comparisons);
        Claim {
            id: id.into(),
            source: source.into(),
            claim: claim.into(),
            comparisons,
            ours,
            verdict,
            reason,
        }
    }

    /// "k of n comparisons hold (m opposite)".
    pub fn tally(&self) -> String {
        let n = self.comparisons.len();
        let holds = self
            .comparisons
            .iter()
            .filter(|c| c.outcome() == Outcome::Holds)
            .count();
        let opposite = self
            .comparisons
            .iter()
            .filter(|c| c.outcome() == Outcome::Opposite)
            .count();
        format!("{holds} of {n} comparisons hold, {opposite} significantly opposite")
    }
}

/// The comparisons of every claim as one table (`claims.csv` / `.md`).
pub fn claims_table(claims: &[Claim]) -> Table {
    let mut t = Table::new([
        "claim",
        "context",
        "segment",
        "metric",
        "claimed better",
        "RMSE",
        "claimed worse",
        "RMSE",
        "worse − better (95% CI)",
        "outcome",
    ]);
    for c in claims {
        for cmp in &c.comparisons {
            t.push([
                c.id.clone(),
                cmp.context.clone(),
                cmp.segment.clone(),
                cmp.metric.name().to_string(),
                cmp.better.clone(),
                fmt_ci(&cmp.better_rmse, 2),
                cmp.worse.clone(),
                fmt_ci(&cmp.worse_rmse, 2),
                fmt_ci(&cmp.difference, 2),
                cmp.outcome().text().to_string(),
            ]);
        }
    }
    t
}

/// The claims as Markdown lines for `summary.md`.
pub fn claims_markdown(claims: &[Claim]) -> String {
    let mut out = String::new();
    for c in claims {
        out.push_str(&format!(
            "- **{}** ({}) *{}* — ours: {} **Verdict: {}.** {}\n",
            c.id,
            c.source,
            c.claim,
            c.ours,
            c.verdict.text(),
            c.reason
        ));
    }
    out
}

// ---------------------------------------------------------------------------
// Tables and plots
// ---------------------------------------------------------------------------

/// Methods × metrics over one segment: "mean ± 95 % half-width" cells.
pub fn rmse_table(
    methods: &[&MethodResult],
    metrics: &[Metric],
    segment: Segment<'_>,
    digits: usize,
) -> Table {
    let mut headers = vec!["method".to_string()];
    headers.extend(metrics.iter().map(|m| format!("RMSE {}", m.name())));
    headers.push("configuration".into());
    let mut t = Table::new(headers);
    for m in methods {
        let mut row = vec![m.label.clone()];
        row.extend(
            metrics
                .iter()
                .map(|&metric| fmt_ci(&m.summary(metric, segment), digits)),
        );
        row.push(m.detail.clone());
        t.push(row);
    }
    t
}

/// RMSE of `metric` against time for `methods`, as an SVG.
pub fn plot_against_time(
    path: &Path,
    exp: &Experiment,
    methods: &[&MethodResult],
    metric: Metric,
    title: &str,
    y_max: Option<f64>,
) -> Result<(), String> {
    let series: Vec<Series> = methods
        .iter()
        .map(|m| {
            Series::line(
                m.label.clone(),
                m.against_time(metric)
                    .into_iter()
                    .map(|(k, v)| (exp.time(k), v))
                    .collect(),
            )
        })
        .collect();
    let y_label = format!("RMSE {} over {} runs", metric.name(), exp.runs());
    plot(
        path,
        &PlotSpec {
            title,
            x_label: "time (s)",
            y_label: &y_label,
            equal_aspect: false,
            y_max,
        },
        &series,
    )
}

/// Truth, measurements and the filtered tracks of `methods` in run 0.
/// With `predicted`, the methods' predictions are drawn instead (Al-Wagih &
/// Abdulla's Figures 5–6 show "predicted" tracks).
pub fn plot_tracks(
    path: &Path,
    exp: &Experiment,
    methods: &[&MethodResult],
    title: &str,
    predicted: bool,
) -> Result<(), String> {
    let mut series = vec![Series::points(
        "measured",
        exp.sample
            .measurements()
            .map(|m| {
                let p = m.position();
                (p[0], p[1])
            })
            .collect(),
    )];
    for m in methods {
        let run = m.runs.first().ok_or("no runs")?;
        let pts = run
            .iter()
            .skip(FIRST_FILTERED)
            .filter_map(|s| {
                if predicted {
                    s.output.predicted.map(|p| (p[0], p[1]))
                } else {
                    Some((s.output.position[0], s.output.position[1]))
                }
            })
            .collect();
        series.push(Series::line(m.label.clone(), pts));
    }
    // Last, so the estimates do not hide it.
    series.push(Series::line(
        "truth",
        exp.truth.iter().map(|t| (t.x, t.y)).collect(),
    ));
    plot(
        path,
        &PlotSpec {
            title,
            x_label: "x (m)",
            y_label: "y (m)",
            equal_aspect: true,
            y_max: None,
        },
        &series,
    )
}

/// Scan indices at which the truth's velocity differs from the previous
/// scan's: the target accelerated during the period ending there.
pub fn manoeuvring_scans(truth: &[TruthState]) -> Vec<bool> {
    let mut out = vec![false; truth.len()];
    for k in 1..truth.len() {
        let (a, b) = (&truth[k - 1], &truth[k]);
        out[k] = (a.vx - b.vx).abs() > 1e-9 || (a.vy - b.vy).abs() > 1e-9;
    }
    out
}

/// `x` with `d` decimals.
pub fn f(x: f64, d: usize) -> String {
    format!("{x:.d$}")
}
