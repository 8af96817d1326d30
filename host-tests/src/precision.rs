//! Runs the library filter in a representation `S` next to the independent
//! `f64` reference on the same measurements, and measures how far apart they
//! are (maximum and RMS over every update) and the magnitudes of the run (the
//! [`RunEnvelope`] the error budget needs).

use abtrack::budget::{
    error_budget_around_reference, BudgetError, ErrorBound, GainSpread, RunEnvelope,
};
use abtrack::filter::{Gains, KinematicFilter, UpdateOutcome};
use abtrack::num::{Numeric, Quantity};
use abtrack::FilterError;

use crate::reference::{RefFilter, RefGains, RefStep};
use crate::trajectory::{ScenarioSpec, Step};

/// Deviation statistics of position, velocity and acceleration (index 0, 1, 2).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviation {
    pub max: [f64; 3],
    pub sum_squares: [f64; 3],
    pub samples: usize,
}

impl Deviation {
    pub fn record(&mut self, d: [f64; 3]) {
        for (i, di) in d.iter().enumerate() {
            // NaN must not hide: it becomes an infinite deviation.
            let a = if di.is_nan() { f64::INFINITY } else { di.abs() };
            self.max[i] = self.max[i].max(a);
            self.sum_squares[i] += a * a;
        }
        self.samples += 1;
    }

    pub fn rms(&self) -> [f64; 3] {
        let n = self.samples.max(1) as f64;
        self.sum_squares.map(|s| (s / n).sqrt())
    }

    pub fn merge(&mut self, other: &Deviation) {
        for i in 0..3 {
            self.max[i] = self.max[i].max(other.max[i]);
            self.sum_squares[i] += other.sum_squares[i];
        }
        self.samples += other.samples;
    }
}

/// The magnitudes of a reference run, accumulated update by update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvelopeTracker {
    env: RunEnvelope,
    seen_interval: bool,
}

impl Default for EnvelopeTracker {
    fn default() -> Self {
        Self::new()
    }
}

impl EnvelopeTracker {
    pub fn new() -> Self {
        EnvelopeTracker {
            env: RunEnvelope {
                max_position: 0.0,
                max_velocity: 0.0,
                max_acceleration: 0.0,
                max_residual: 0.0,
                dt_min: f64::INFINITY,
                dt_max: 0.0,
            },
            seen_interval: false,
        }
    }

    pub fn position(&mut self, x: f64) {
        self.env.max_position = self.env.max_position.max(x.abs());
    }
    pub fn velocity(&mut self, v: f64) {
        self.env.max_velocity = self.env.max_velocity.max(v.abs());
    }
    pub fn acceleration(&mut self, a: f64) {
        self.env.max_acceleration = self.env.max_acceleration.max(a.abs());
    }
    pub fn residual(&mut self, e: f64) {
        self.env.max_residual = self.env.max_residual.max(e.abs());
    }
    pub fn interval(&mut self, dt: f64) {
        self.env.dt_min = self.env.dt_min.min(dt);
        self.env.dt_max = self.env.dt_max.max(dt);
        self.seen_interval = true;
    }

    /// The envelope seen so far (`None` before any interval was recorded).
    pub fn envelope(&self) -> Option<RunEnvelope> {
        self.seen_interval.then_some(self.env)
    }

    /// Combines the envelopes of several runs (e.g. the axes of one track).
    pub fn merge(&mut self, other: &EnvelopeTracker) {
        self.position(other.env.max_position);
        self.velocity(other.env.max_velocity);
        self.acceleration(other.env.max_acceleration);
        self.residual(other.env.max_residual);
        if other.seen_interval {
            self.interval(other.env.dt_min);
            self.interval(other.env.dt_max);
        }
    }
}

/// Outcome of running `S` and the reference side by side on one axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// Deviation of the `S` estimates from the reference after every update.
    pub deviation: Deviation,
    /// Magnitudes of the reference run. The interval range covers the updates
    /// from the second on (the first update's interval is not used).
    pub envelope: EnvelopeTracker,
    /// Updates the `S` filter refused (saturation); the reference never does.
    pub refused: usize,
}

/// Runs axis `axis` of `steps` through `KinematicFilter<N, ORDER>` and the
/// reference with the same gains. Inputs are converted to `N`'s quantities
/// with `try_from_f64` (the conversion a user's code does at its edge).
pub fn compare_axis<N: Numeric, const ORDER: usize, const D: usize>(
    steps: &[Step<D>],
    axis: usize,
    gains: &RefGains,
) -> Result<Comparison, String> {
    let lib_gains: Gains<N> = if ORDER == 3 {
        Gains::alpha_beta_gamma_f64(gains.alpha, gains.beta, gains.gamma)
    } else {
        Gains::alpha_beta_f64(gains.alpha, gains.beta)
    }
    .map_err(|e| format!("gains: {e}"))?;
    let length =
        |v: f64| N::Length::try_from_f64(v).map_err(|e| format!("{v} m in {}: {e}", N::NAME));
    let interval =
        |v: f64| N::Interval::try_from_f64(v).map_err(|e| format!("{v} s in {}: {e}", N::NAME));

    let mut filter = KinematicFilter::<N, ORDER>::new();
    let mut reference = RefFilter::new(ORDER);
    let mut deviation = Deviation::default();
    let mut envelope = EnvelopeTracker::new();
    let mut refused = 0usize;
    let mut updates = 0usize;

    for step in steps {
        let dt = interval(step.dt)?;
        match step.z {
            Some(z) => {
                let z = z[axis];
                let (_, v_before, a_before) = reference.state();
                let outcome = reference.update(z, step.dt, gains);
                updates += 1;
                if updates >= 2 {
                    envelope.interval(step.dt);
                }
                envelope.position(z);
                if let RefStep::Filtered {
                    predicted,
                    innovation,
                } = outcome
                {
                    envelope.position(predicted);
                    envelope.residual(innovation);
                    envelope.velocity(v_before + step.dt * a_before);
                }
                let (x, v, a) = reference.state();
                envelope.position(x);
                envelope.velocity(v);
                envelope.acceleration(a);

                match filter.update(length(z)?, dt, &lib_gains) {
                    Ok(UpdateOutcome::FirstPoint)
                    | Ok(UpdateOutcome::SecondPoint)
                    | Ok(UpdateOutcome::Filtered(_)) => {}
                    // The scenarios' intervals are inside the filters' range.
                    Ok(o @ (UpdateOutcome::Restarted | UpdateOutcome::Skipped)) => {
                        return Err(format!("interval outside the filters' range: {o:?}"))
                    }
                    Err(FilterError::Saturated) => refused += 1,
                    Err(e) => return Err(format!("update refused: {e}")),
                }
                deviation.record([
                    filter.position().to_f64() - x,
                    filter.velocity().to_f64() - v,
                    filter.acceleration().to_f64() - a,
                ]);
            }
            None => {
                reference.coast(step.dt);
                match filter.coast(dt) {
                    Ok(()) => {}
                    Err(FilterError::Saturated) => refused += 1,
                    Err(e) => return Err(format!("coast refused: {e}")),
                }
            }
        }
    }
    Ok(Comparison {
        deviation,
        envelope,
        refused,
    })
}

/// A run whose deviations docs/numerics.md quotes, produced by
/// `cargo run --release --bin precision` and checked against the budget by
/// `tests/it/num/error_budget.rs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DocumentedRun {
    pub name: &'static str,
    pub description: &'static str,
    /// 2 (αβ) or 3 (αβγ).
    pub order: usize,
    pub gains: RefGains,
    pub spec: ScenarioSpec,
    pub seed: u64,
}

/// The documented runs: 10 000 updates each, one axis, no coasts, spanning the
/// envelope (positions to ±400 km, speeds to 1500 m/s, accelerations to
/// 200 m/s², intervals 0.05–20 s).
pub fn documented_runs() -> Vec<DocumentedRun> {
    use crate::trajectory::Motion;
    const N: usize = 10_000;
    let bb = |a: f64| a * a / (2.0 - a); // Benedict–Bordner (Al-Wagih eq. 23b)
    vec![
        DocumentedRun {
            name: "ab-1s",
            description: "αβ α=0.5 β=0.3, T=1 s, weaving target at −390 km (±10 km, 500 m/s, 25 m/s²), σ=30 m",
            order: 2,
            gains: RefGains { alpha: 0.5, beta: 0.3, gamma: 0.0 },
            spec: ScenarioSpec {
                steps: N,
                dt: (1.0, 1.0),
                coast_probability: 0.0,
                noise_sigma: 30.0,
                motion: Motion::Oscillation { centre: -390e3, amplitude: 10e3, omega: 0.05 },
            },
            seed: 1,
        },
        DocumentedRun {
            name: "abg-1s",
            description: "αβγ α=0.5 β=0.3 γ=0.1, same target and interval as ab-1s",
            order: 3,
            gains: RefGains { alpha: 0.5, beta: 0.3, gamma: 0.1 },
            spec: ScenarioSpec {
                steps: N,
                dt: (1.0, 1.0),
                coast_probability: 0.0,
                noise_sigma: 30.0,
                motion: Motion::Oscillation { centre: -390e3, amplitude: 10e3, omega: 0.05 },
            },
            seed: 1,
        },
        DocumentedRun {
            name: "ab-fast",
            description: "αβ α=0.5 β=0.3, T=0.05 s, 1500 m/s straight line from −399 km to +351 km, σ=10 m",
            order: 2,
            gains: RefGains { alpha: 0.5, beta: 0.3, gamma: 0.0 },
            spec: ScenarioSpec {
                steps: N,
                dt: (0.05, 0.05),
                coast_probability: 0.0,
                noise_sigma: 10.0,
                motion: Motion::ConstantVelocity { start: -399e3, velocity: 1500.0 },
            },
            seed: 2,
        },
        DocumentedRun {
            name: "abg-fast",
            description: "αβγ α=0.5 β=0.3 γ=0.1, T=0.05 s, weaving at +388.75 km with 1500 m/s and 200 m/s² peaks, σ=10 m",
            order: 3,
            gains: RefGains { alpha: 0.5, beta: 0.3, gamma: 0.1 },
            spec: ScenarioSpec {
                steps: N,
                dt: (0.05, 0.05),
                coast_probability: 0.0,
                noise_sigma: 10.0,
                motion: Motion::Oscillation { centre: 388.75e3, amplitude: 11.25e3, omega: 200.0 / 1500.0 },
            },
            seed: 3,
        },
        DocumentedRun {
            name: "ab-slow",
            description: "αβ Benedict–Bordner α=0.1, T=20 s, ±300 km swing about +100 km at 1500 m/s peak, σ=100 m",
            order: 2,
            gains: RefGains { alpha: 0.1, beta: bb(0.1), gamma: 0.0 },
            spec: ScenarioSpec {
                steps: N,
                dt: (20.0, 20.0),
                coast_probability: 0.0,
                noise_sigma: 100.0,
                motion: Motion::Oscillation { centre: 100e3, amplitude: 300e3, omega: 0.005 },
            },
            seed: 4,
        },
        DocumentedRun {
            name: "abg-jitter",
            description: "αβγ α=0.5 β=0.3 γ=0.1, T uniform in 0.95–1.05 s, random manoeuvres within ±400 km, 1500 m/s, 200 m/s², σ=30 m",
            order: 3,
            gains: RefGains { alpha: 0.5, beta: 0.3, gamma: 0.1 },
            spec: ScenarioSpec {
                steps: N,
                dt: (0.95, 1.05),
                coast_probability: 0.0,
                noise_sigma: 30.0,
                motion: Motion::Manoeuvres {
                    limit_position: 400e3,
                    max_velocity: 1500.0,
                    max_acceleration: 200.0,
                    mean_segment: 20.0,
                },
            },
            seed: 5,
        },
        DocumentedRun {
            name: "ab-edge",
            description: "αβ α=1.99 β=0.015 (near the α<2 and 2α+β<4 edges), T=1 s, weaving at −390 km, σ=30 m",
            order: 2,
            gains: RefGains { alpha: 1.99, beta: 0.015, gamma: 0.0 },
            spec: ScenarioSpec {
                steps: N,
                dt: (1.0, 1.0),
                coast_probability: 0.0,
                noise_sigma: 30.0,
                motion: Motion::Oscillation { centre: -390e3, amplitude: 10e3, omega: 0.05 },
            },
            seed: 6,
        },
    ]
}

/// Measured deviation and budget of one representation on one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunReport {
    pub deviation: Deviation,
    pub refused: usize,
    /// The budget for this run's magnitudes
    /// ([`abtrack::budget::error_budget_around_reference`]).
    pub budget: Result<ErrorBound, BudgetError>,
}

/// The library's gains for reference gains, as `f64` (what the budget takes).
pub fn budget_gains(order: usize, g: &RefGains) -> Result<Gains<f64>, abtrack::GainError> {
    if order == 3 {
        Gains::<f64>::alpha_beta_gamma(g.alpha, g.beta, g.gamma)
    } else {
        Gains::<f64>::alpha_beta(g.alpha, g.beta)
    }
}

/// Runs `steps` (axis `axis`) in `N` and the reference, and computes the
/// budget for the reference's magnitudes.
pub fn measure<N: Numeric, const D: usize>(
    order: usize,
    gains: &RefGains,
    steps: &[Step<D>],
    axis: usize,
    spread: &GainSpread,
) -> Result<RunReport, String> {
    let comparison = if order == 3 {
        compare_axis::<N, 3, D>(steps, axis, gains)?
    } else {
        compare_axis::<N, 2, D>(steps, axis, gains)?
    };
    let envelope = comparison
        .envelope
        .envelope()
        .ok_or_else(|| "run has fewer than two updates".to_string())?;
    let g = budget_gains(order, gains).map_err(|e| format!("gains: {e}"))?;
    let budget = if order == 3 {
        error_budget_around_reference::<N, 3>(&g, spread, &envelope)
    } else {
        error_budget_around_reference::<N, 2>(&g, spread, &envelope)
    };
    Ok(RunReport {
        deviation: comparison.deviation,
        refused: comparison.refused,
        budget,
    })
}

/// [`measure`] on a documented run.
pub fn measure_documented<N: Numeric>(run: &DocumentedRun) -> Result<RunReport, String> {
    let steps = crate::trajectory::generate::<1>(run.seed, &run.spec);
    measure::<N, 1>(run.order, &run.gains, &steps, 0, &GainSpread::default())
}
