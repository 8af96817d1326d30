//! Figures of the quantisation-aware altitude tracker
//! (`abtrack::filter::altitude`) on the TCAS altitude profiles: a steady
//! 300 ft/min climb, a level-off from 2000 ft/min, and a 0.25 g RA response
//! from level to 1500 ft/min, each reported in Mode C (100 ft) and Mode S
//! (25 ft) steps once a second, over the phase of the profile against the
//! report grid (the same profile started at 20 offsets within one bin).
//! Used by the `tcas-advisory` experiment (its `altitude_tracker` table) and
//! by `tests/it/tcas/altitude.rs`.

use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig};
use abtrack::Scalar;

/// Offsets of the profile within one bin: `PHASES` evenly spaced starts.
pub const PHASES: usize = 20;

/// The report of a true altitude: rounded to the nearest quantum.
pub fn report(altitude_ft: f64, quantum: AltitudeQuantum) -> f64 {
    let q = quantum.feet();
    (altitude_ft / q).round() * q
}

/// A vertical profile: altitude (ft) at time t (s).
pub trait Profile {
    fn altitude_ft(&self, t: f64) -> f64;
    fn rate_ft_per_s(&self, t: f64) -> f64;
}

/// Constant rate from `start_ft`.
#[derive(Debug, Clone, Copy)]
pub struct SteadyClimb {
    pub start_ft: f64,
    pub rate_ft_per_s: f64,
}

impl Profile for SteadyClimb {
    fn altitude_ft(&self, t: f64) -> f64 {
        self.start_ft + self.rate_ft_per_s * t
    }
    fn rate_ft_per_s(&self, _t: f64) -> f64 {
        self.rate_ft_per_s
    }
}

/// A rate change from `rate0` to `rate1` at `t_change` with acceleration
/// `accel` (ft/s²; infinite for a step).
#[derive(Debug, Clone, Copy)]
pub struct RateChange {
    pub start_ft: f64,
    pub rate0: f64,
    pub rate1: f64,
    pub t_change: f64,
    pub accel: f64,
}

impl RateChange {
    fn ramp_time(&self) -> f64 {
        if self.accel.is_infinite() {
            0.0
        } else {
            (self.rate1 - self.rate0).abs() / self.accel
        }
    }
}

impl Profile for RateChange {
    fn altitude_ft(&self, t: f64) -> f64 {
        if t <= self.t_change {
            return self.start_ft + self.rate0 * t;
        }
        let z0 = self.start_ft + self.rate0 * self.t_change;
        let tr = self.ramp_time();
        let dt = t - self.t_change;
        let a = if tr > 0.0 {
            (self.rate1 - self.rate0) / tr
        } else {
            0.0
        };
        if dt <= tr {
            z0 + self.rate0 * dt + 0.5 * a * dt * dt
        } else {
            z0 + self.rate0 * tr + 0.5 * a * tr * tr + self.rate1 * (dt - tr)
        }
    }
    fn rate_ft_per_s(&self, t: f64) -> f64 {
        if t <= self.t_change {
            return self.rate0;
        }
        let tr = self.ramp_time();
        let dt = t - self.t_change;
        if dt <= tr && tr > 0.0 {
            self.rate0 + (self.rate1 - self.rate0) * dt / tr
        } else {
            self.rate1
        }
    }
}

/// One run's estimated rates (ft/s) at t = 0, 1, … and the true ones.
pub struct RateTrace {
    pub estimated: Vec<f64>,
    pub truth: Vec<f64>,
}

/// Runs the tracker in `S` on `profile` for `seconds` reports.
pub fn trace<S: Scalar>(
    profile: &dyn Profile,
    quantum: AltitudeQuantum,
    seconds: usize,
) -> RateTrace {
    let config = AltitudeTrackerConfig::<S>::default_for(quantum).expect("default configuration");
    let mut tracker = AltitudeTracker::<S>::new(config);
    let mut estimated = Vec::with_capacity(seconds);
    let mut truth = Vec::with_capacity(seconds);
    for k in 0..seconds {
        let t = k as f64;
        let z = S::from_f64_lossy(report(profile.altitude_ft(t), quantum));
        tracker.scan(Some(z), S::ONE).expect("valid report");
        let e = tracker.estimate().expect("reporting");
        estimated.push(e.vertical_rate_ft_per_s.to_f64());
        truth.push(profile.rate_ft_per_s(t));
    }
    RateTrace { estimated, truth }
}

/// Min and max of the estimated rate (ft/min) over [from, to) s, over every
/// phase of a steady climb at `rate_ft_per_min`.
pub fn steady_climb_rate_range<S: Scalar>(
    quantum: AltitudeQuantum,
    rate_ft_per_min: f64,
    from: usize,
    to: usize,
) -> (f64, f64) {
    let q = quantum.feet();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for phase in 0..PHASES {
        let profile = SteadyClimb {
            start_ft: 8000.0 + q * phase as f64 / PHASES as f64,
            rate_ft_per_s: rate_ft_per_min / 60.0,
        };
        let tr = trace::<S>(&profile, quantum, to);
        for &r in &tr.estimated[from..to] {
            lo = lo.min(r * 60.0);
            hi = hi.max(r * 60.0);
        }
    }
    (lo, hi)
}

/// After a rate change at `t_change` (s): over the phases, the worst
/// estimated rate `delay` s after the change, and the worst time after the
/// change until the estimate stays within `tolerance_ft_per_min` of the new
/// rate for good (within `horizon` s; `None` if some phase never settles).
pub struct RateChangeFigures {
    /// Per phase: the estimate `probe_s` after the change, ft/min.
    pub at_probe_ft_per_min: Vec<f64>,
    /// Per phase: the settling time, s.
    pub settling_s: Vec<Option<f64>>,
}

pub fn rate_change<S: Scalar>(
    quantum: AltitudeQuantum,
    change: RateChange,
    probe_s: usize,
    tolerance_ft_per_min: f64,
    horizon: usize,
) -> RateChangeFigures {
    let q = quantum.feet();
    let mut at_probe = Vec::new();
    let mut settling = Vec::new();
    for phase in 0..PHASES {
        let profile = RateChange {
            start_ft: change.start_ft + q * phase as f64 / PHASES as f64,
            ..change
        };
        let tr = trace::<S>(&profile, quantum, horizon);
        let k_change = change.t_change as usize;
        at_probe.push(tr.estimated[k_change + probe_s] * 60.0);
        let settled = (k_change..horizon).find(|&k| {
            tr.estimated[k..]
                .iter()
                .zip(&tr.truth[k..])
                .all(|(e, t)| (e - t).abs() * 60.0 <= tolerance_ft_per_min)
        });
        settling.push(settled.map(|k| k as f64 - change.t_change));
    }
    RateChangeFigures {
        at_probe_ft_per_min: at_probe,
        settling_s: settling,
    }
}

/// The level-off: climbing 2000 ft/min, level at t = 60 s.
pub fn level_off() -> RateChange {
    RateChange {
        start_ft: 8000.0,
        rate0: 2000.0 / 60.0,
        rate1: 0.0,
        t_change: 60.0,
        accel: f64::INFINITY,
    }
}

/// A 0.25 g RA response: level, then 8 ft/s² up to 1500 ft/min at t = 60 s
/// (DO-185B `VACCEL`, `CLMRT`).
pub fn ra_response() -> RateChange {
    RateChange {
        start_ft: 8000.0,
        rate0: 0.0,
        rate1: 1500.0 / 60.0,
        t_change: 60.0,
        accel: 8.0,
    }
}
