//! Shared helpers for the track_* tests.
#![allow(dead_code)]

use abtrack::num::Quantity;
use abtrack::track::{FixedGainTrack, Gate, Measurement, TrackNumeric, TrackerConfig};
use abtrack::{Gains, Scalar};

pub type Config<S> = TrackerConfig<S, Gains<S>>;
pub type Table<S, const N: usize, const M: usize> =
    abtrack::track::TrackTable<S, FixedGainTrack<S>, N, M>;

pub fn s<S: Scalar>(v: f64) -> S {
    S::try_from_f64(v).unwrap()
}

/// A quantity of any number system (a length, a ratio, ...).
pub fn q<Q: Quantity>(v: f64) -> Q {
    Q::try_from_f64(v).unwrap()
}

pub fn cart<S: TrackNumeric>(x: f64, y: f64) -> Measurement<S> {
    Measurement::Cartesian { x: q(x), y: q(y) }
}

/// α = 0.5, β = 0.2 (inside Al-Wagih's triangle: 2α + β = 1.2 < 4);
/// uncertainty gate σ = 5 m, G = 13.8 (99.9 %), a_max = 5 m/s²;
/// v_max = 300 m/s; defaults otherwise (2 of 3, delete after 3 / 2 misses).
pub fn default_config<S: TrackNumeric>() -> Config<S> {
    let gains = Gains::alpha_beta_f64(0.5, 0.2).unwrap();
    let gate = Gate::uncertainty(q(5.0), q(13.8), q(5.0)).unwrap();
    TrackerConfig::new(gains, gate, q(300.0)).unwrap()
}

/// Deterministic pseudo-random numbers (64-bit LCG, Knuth's MMIX constants).
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in [-1, 1).
    pub fn next_signed(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}
