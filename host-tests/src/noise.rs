//! Seeded, reproducible measurement noise: white Gaussian and coloured
//! (first-order autoregressive) Gaussian.
//!
//! Al-Wagih & Abdulla §6 corrupt half of their simulated radar sets with
//! Gaussian white noise and half with "Gaussian colored noise" without saying
//! how it was coloured. We use the simplest stationary coloured Gaussian
//! process, AR(1) (a first-order Gauss–Markov sequence):
//!
//! n_k = ρ·n_{k−1} + √(1−ρ²)·σ·w_k,  w_k ~ N(0, 1) i.i.d.,
//!
//! started from its stationary distribution n_0 = σ·w_0, so every sample has
//! variance σ² and the lag-j correlation is ρ^j. ρ = 0 is white noise, so the
//! two kinds of set differ only in correlation, never in power: RMSE
//! differences between them are due to colour alone. ρ is a parameter of each
//! scenario (see [`crate::scenario`]).
//!
//! Every random draw in the host tools comes from a [`ChaCha8Rng`] seeded
//! from a `u64` ([`rng_from_seed`]), so a seed reproduces a run bit for bit on
//! every platform (ChaCha is portable; `rand_distr`'s normal sampler is
//! deterministic given the generator; the versions are pinned by
//! `Cargo.lock`).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// The generator every host tool uses: ChaCha with 8 rounds (fast and
/// statistically sound for simulation; cryptographic strength is not needed).
pub type SimRng = ChaCha8Rng;

/// A generator whose whole output is fixed by `seed`.
pub fn rng_from_seed(seed: u64) -> SimRng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// Derives an independent seed for a sub-stream (e.g. Monte Carlo run `index`
/// of a base seed, or the x and y noise of one run) so that streams never
/// share a generator and adding a stream does not shift the others.
/// SplitMix64 finaliser of `base ⊕ golden-ratio·(index+1)`: a bijection of the
/// 64-bit input, so distinct (base, index) pairs with the same base never
/// collide.
pub fn derive_seed(base: u64, index: u64) -> u64 {
    let mut z = base ^ index.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// What kind of noise a sequence is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoiseModel {
    /// Independent N(0, σ²) samples.
    White {
        /// Standard deviation σ (same unit as the measurement).
        sigma: f64,
    },
    /// AR(1): n_k = ρ·n_{k−1} + √(1−ρ²)·σ·w_k, stationary variance σ²,
    /// lag-j autocorrelation ρ^j.
    Ar1 {
        /// Stationary standard deviation σ.
        sigma: f64,
        /// Lag-one correlation coefficient ρ, −1 < ρ < 1. The correlation
        /// time in samples is −1/ln|ρ| (ρ = 0.8: about 4.5 samples).
        rho: f64,
    },
}

impl NoiseModel {
    /// Stationary standard deviation σ of every sample.
    pub fn sigma(&self) -> f64 {
        match *self {
            NoiseModel::White { sigma } | NoiseModel::Ar1 { sigma, .. } => sigma,
        }
    }

    /// Lag-one autocorrelation (0 for white noise).
    pub fn rho(&self) -> f64 {
        match *self {
            NoiseModel::White { .. } => 0.0,
            NoiseModel::Ar1 { rho, .. } => rho,
        }
    }

    /// Checks the parameters: σ finite and ≥ 0; ρ finite with |ρ| < 1 (|ρ| = 1
    /// is a random walk, which has no stationary variance).
    pub fn validate(&self) -> Result<(), NoiseError> {
        let sigma = self.sigma();
        if !(sigma.is_finite() && sigma >= 0.0) {
            return Err(NoiseError::InvalidSigma);
        }
        let rho = self.rho();
        if !(rho.is_finite() && rho.abs() < 1.0) {
            return Err(NoiseError::InvalidRho);
        }
        Ok(())
    }
}

/// Why a noise model was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseError {
    /// σ is negative, NaN or infinite.
    InvalidSigma,
    /// ρ is NaN, infinite or |ρ| ≥ 1.
    InvalidRho,
}

impl core::fmt::Display for NoiseError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            NoiseError::InvalidSigma => write!(f, "noise sigma must be finite and >= 0"),
            NoiseError::InvalidRho => write!(f, "AR(1) rho must be finite with |rho| < 1"),
        }
    }
}

impl std::error::Error for NoiseError {}

/// One noise channel (e.g. the x-axis noise of a sensor): a model plus the
/// AR(1) memory. Draws come from a generator the caller passes in, so several
/// channels can share one seeded stream in a fixed order.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseProcess {
    model: NoiseModel,
    previous: Option<f64>,
}

impl NoiseProcess {
    /// A channel with the given model, before its first sample.
    pub fn new(model: NoiseModel) -> Result<Self, NoiseError> {
        model.validate()?;
        Ok(NoiseProcess {
            model,
            previous: None,
        })
    }

    pub fn model(&self) -> NoiseModel {
        self.model
    }

    /// The next sample. Exactly one standard-normal draw per call, whatever
    /// the model, so switching white ↔ coloured keeps the other channels'
    /// streams aligned.
    pub fn sample<R: Rng + ?Sized>(&mut self, rng: &mut R) -> f64 {
        let w: f64 = StandardNormal.sample(rng);
        let n = match (self.model, self.previous) {
            (NoiseModel::White { sigma }, _) => sigma * w,
            // Stationary start: the first sample already has variance σ².
            (NoiseModel::Ar1 { sigma, .. }, None) => sigma * w,
            (NoiseModel::Ar1 { sigma, rho }, Some(prev)) => {
                rho * prev + (1.0 - rho * rho).sqrt() * sigma * w
            }
        };
        self.previous = Some(n);
        n
    }

    /// Forgets the AR(1) memory (the next sample starts a new stationary
    /// sequence).
    pub fn reset(&mut self) {
        self.previous = None;
    }
}

/// `len` samples of `model` drawn from a generator seeded with `seed`.
pub fn noise_sequence(model: NoiseModel, len: usize, seed: u64) -> Result<Vec<f64>, NoiseError> {
    let mut process = NoiseProcess::new(model)?;
    let mut rng = rng_from_seed(seed);
    Ok((0..len).map(|_| process.sample(&mut rng)).collect())
}

/// A standard-normal draw (for callers that need one outside a channel, such
/// as process noise in a truth generator).
pub fn standard_normal<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    StandardNormal.sample(rng)
}

/// A uniform draw in [lo, hi).
pub fn uniform<R: Rng + ?Sized>(rng: &mut R, lo: f64, hi: f64) -> f64 {
    // 53 random mantissa bits → u in [0, 1) exactly representable.
    let u = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    lo + (hi - lo) * u
}

/// A uniform index in 0..n (n > 0), without modulo bias (Lemire's method
/// with rejection).
pub fn uniform_index<R: Rng + ?Sized>(rng: &mut R, n: usize) -> usize {
    debug_assert!(n > 0);
    let n = n as u64;
    let threshold = n.wrapping_neg() % n;
    loop {
        let m = (rng.next_u64() as u128) * (n as u128);
        if (m as u64) >= threshold {
            return (m >> 64) as usize;
        }
    }
}

/// Fisher–Yates shuffle (written out here so the permutation for a seed does
/// not depend on a library's choice of algorithm).
pub fn shuffle<T, R: Rng + ?Sized>(rng: &mut R, items: &mut [T]) {
    for i in (1..items.len()).rev() {
        let j = uniform_index(rng, i + 1);
        items.swap(i, j);
    }
}

/// A Bernoulli(p) draw (detection with probability Pd).
pub fn bernoulli<R: Rng + ?Sized>(rng: &mut R, p: f64) -> bool {
    uniform(rng, 0.0, 1.0) < p
}

/// A Poisson(λ) count (number of clutter points in a scan). Knuth's
/// multiplication method for λ ≤ 30 (exact; our clutter means are small),
/// otherwise `rand_distr::Poisson`.
pub fn poisson<R: Rng + ?Sized>(rng: &mut R, lambda: f64) -> usize {
    if !(lambda.is_finite() && lambda > 0.0) {
        return 0;
    }
    if lambda <= 30.0 {
        let limit = (-lambda).exp();
        let mut k = 0usize;
        let mut product = uniform(rng, 0.0, 1.0);
        while product > limit {
            k += 1;
            product *= uniform(rng, 0.0, 1.0);
        }
        k
    } else {
        match rand_distr::Poisson::new(lambda) {
            Ok(d) => {
                let x: f64 = d.sample(rng);
                x as usize
            }
            Err(_) => 0,
        }
    }
}
