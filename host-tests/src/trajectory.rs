//! Seeded measurement sequences for the checks: every run is reproducible
//! from its seed (ChaCha8, `rand_chacha`), on any host.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// One call of the filter: a measurement (one value per axis) or a coast,
/// `dt` seconds after the previous call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step<const D: usize> {
    pub dt: f64,
    /// `None`: no measurement this scan (coast).
    pub z: Option<[f64; D]>,
}

/// How the true target moves, per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// `x(t) = centre + amplitude·sin(ωt + φ)` with a random phase φ per axis:
    /// peak speed amplitude·ω, peak acceleration amplitude·ω². Reaches the
    /// corners of the envelope without leaving it over long runs.
    Oscillation {
        centre: f64,
        amplitude: f64,
        omega: f64,
    },
    /// Straight line from `start` at `velocity` (same on every axis).
    ConstantVelocity { start: f64, velocity: f64 },
    /// Piecewise-constant accelerations, uniform in ±`max_acceleration`, held
    /// for exponentially distributed times of mean `mean_segment` seconds;
    /// speed limited to `max_velocity`, and the target turns back at
    /// ±`limit_position`.
    Manoeuvres {
        limit_position: f64,
        max_velocity: f64,
        max_acceleration: f64,
        mean_segment: f64,
    },
}

/// A scenario: length, interval, gaps, noise and motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScenarioSpec {
    /// Number of filter calls (updates and coasts).
    pub steps: usize,
    /// Each interval is uniform in `[dt.0, dt.1]` (equal: constant interval).
    pub dt: (f64, f64),
    /// Probability that a call after the second measurement is a coast.
    pub coast_probability: f64,
    /// Standard deviation of the Gaussian measurement noise, metres.
    pub noise_sigma: f64,
    pub motion: Motion,
}

/// A standard normal variate (Box–Muller), so that no distribution crate is
/// needed.
pub fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

#[derive(Clone, Copy)]
struct AxisTruth {
    position: f64,
    velocity: f64,
    acceleration: f64,
    segment_left: f64,
    phase: f64,
}

/// The measurement sequence of `spec`, reproducible from `seed`.
pub fn generate<const D: usize>(seed: u64, spec: &ScenarioSpec) -> Vec<Step<D>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut axes = [AxisTruth {
        position: 0.0,
        velocity: 0.0,
        acceleration: 0.0,
        segment_left: 0.0,
        phase: 0.0,
    }; D];
    for axis in axes.iter_mut() {
        axis.phase = rng.random_range(0.0..std::f64::consts::TAU);
        match spec.motion {
            Motion::ConstantVelocity { start, velocity } => {
                axis.position = start;
                axis.velocity = velocity;
            }
            Motion::Manoeuvres {
                limit_position,
                max_velocity,
                ..
            } => {
                axis.position = rng.random_range(-limit_position..=limit_position);
                axis.velocity = rng.random_range(-max_velocity..=max_velocity);
            }
            Motion::Oscillation { .. } => {}
        }
    }
    let mut t = 0.0;
    let mut measured = 0usize;
    let mut steps = Vec::with_capacity(spec.steps);
    for _ in 0..spec.steps {
        let dt = if spec.dt.1 > spec.dt.0 {
            rng.random_range(spec.dt.0..=spec.dt.1)
        } else {
            spec.dt.0
        };
        t += dt;
        for axis in axes.iter_mut() {
            advance(axis, &spec.motion, t, dt, &mut rng);
        }
        let coast = measured >= 2 && rng.random_bool(spec.coast_probability.clamp(0.0, 1.0));
        let z = if coast {
            None
        } else {
            measured += 1;
            let mut z = [0.0; D];
            for (zi, axis) in z.iter_mut().zip(axes.iter()) {
                *zi = axis.position + spec.noise_sigma * standard_normal(&mut rng);
            }
            Some(z)
        };
        steps.push(Step { dt, z });
    }
    steps
}

fn advance(axis: &mut AxisTruth, motion: &Motion, t: f64, dt: f64, rng: &mut ChaCha8Rng) {
    match *motion {
        Motion::Oscillation {
            centre,
            amplitude,
            omega,
        } => {
            axis.position = centre + amplitude * (omega * t + axis.phase).sin();
        }
        Motion::ConstantVelocity { .. } => {
            axis.position += axis.velocity * dt;
        }
        Motion::Manoeuvres {
            limit_position,
            max_velocity,
            max_acceleration,
            mean_segment,
        } => {
            axis.segment_left -= dt;
            if axis.segment_left <= 0.0 {
                axis.acceleration = rng.random_range(-max_acceleration..=max_acceleration);
                let u: f64 = 1.0 - rng.random::<f64>();
                axis.segment_left = -mean_segment * u.ln();
            }
            // Turn back towards the centre near the edges.
            if axis.position.abs() > 0.9 * limit_position
                && axis.position.signum() == axis.velocity.signum()
            {
                axis.acceleration = -axis.position.signum() * max_acceleration;
            }
            let v_next =
                (axis.velocity + axis.acceleration * dt).clamp(-max_velocity, max_velocity);
            axis.position += 0.5 * (axis.velocity + v_next) * dt;
            axis.velocity = v_next;
            axis.position = axis.position.clamp(-limit_position, limit_position);
        }
    }
}
