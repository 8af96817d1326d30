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

#[cfg(test)]
mod tests {
    use super::*;

    fn mean_var(xs: &[f64]) -> (f64, f64) {
        let n = xs.len() as f64;
        let m = xs.iter().sum::<f64>() / n;
        let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
        (m, v)
    }

    fn lag1_correlation(xs: &[f64]) -> f64 {
        let (m, _) = mean_var(xs);
        let num: f64 = xs.windows(2).map(|w| (w[0] - m) * (w[1] - m)).sum();
        let den: f64 = xs.iter().map(|x| (x - m) * (x - m)).sum();
        num / den
    }

    #[test]
    fn same_seed_same_sequence_different_seed_different() {
        let model = NoiseModel::Ar1 {
            sigma: 3.0,
            rho: 0.8,
        };
        let a = noise_sequence(model, 100, 7).unwrap();
        let b = noise_sequence(model, 100, 7).unwrap();
        let c = noise_sequence(model, 100, 8).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
    }

    #[test]
    fn white_noise_has_zero_mean_and_the_stated_variance() {
        let sigma = 5.0;
        let n = 200_000;
        let xs = noise_sequence(NoiseModel::White { sigma }, n, 1).unwrap();
        let (m, v) = mean_var(&xs);
        // Standard error of the mean: σ/√n = 5/447 = 0.0112; 5 s.e. = 0.056.
        assert!(m.abs() < 0.056, "mean {m}");
        // Standard error of the variance: σ²√(2/n) = 25·0.00316 = 0.079;
        // 5 s.e. = 0.40.
        assert!((v - 25.0).abs() < 0.40, "variance {v}");
        // Independent samples: lag-1 correlation s.e. 1/√n = 0.0022.
        assert!(lag1_correlation(&xs).abs() < 0.011);
    }

    #[test]
    fn ar1_has_stationary_variance_and_lag_one_correlation_rho() {
        let (sigma, rho) = (2.0, 0.8);
        let n = 200_000;
        let xs = noise_sequence(NoiseModel::Ar1 { sigma, rho }, n, 2).unwrap();
        let (_, v) = mean_var(&xs);
        // Correlated samples inflate the variance estimator's spread by about
        // (1+ρ²)/(1−ρ²) = 4.56: s.e. ≈ 4·√(2·4.56/200000) = 0.027; allow 0.15.
        assert!((v - 4.0).abs() < 0.15, "variance {v}");
        // s.e. of the lag-1 estimate ≈ √((1−ρ²)/n) = 0.0013.
        let r1 = lag1_correlation(&xs);
        assert!((r1 - rho).abs() < 0.01, "lag-1 correlation {r1}");
    }

    #[test]
    fn ar1_starts_stationary() {
        // The first sample of many independent sequences must already have
        // variance σ² (not zero, as a start at n_0 = 0 would give).
        let model = NoiseModel::Ar1 {
            sigma: 1.0,
            rho: 0.95,
        };
        let firsts: Vec<f64> = (0..20_000)
            .map(|s| noise_sequence(model, 1, s).unwrap()[0])
            .collect();
        let (_, v) = mean_var(&firsts);
        // s.e. √(2/20000) = 0.01.
        assert!((v - 1.0).abs() < 0.05, "variance {v}");
    }

    #[test]
    fn ar1_with_rho_zero_is_the_white_sequence() {
        let white = noise_sequence(NoiseModel::White { sigma: 1.5 }, 50, 3).unwrap();
        let ar0 = noise_sequence(
            NoiseModel::Ar1 {
                sigma: 1.5,
                rho: 0.0,
            },
            50,
            3,
        )
        .unwrap();
        assert_eq!(white, ar0);
    }

    #[test]
    fn bad_parameters_are_refused() {
        assert_eq!(
            NoiseProcess::new(NoiseModel::White { sigma: -1.0 }),
            Err(NoiseError::InvalidSigma)
        );
        assert_eq!(
            NoiseProcess::new(NoiseModel::White { sigma: f64::NAN }),
            Err(NoiseError::InvalidSigma)
        );
        assert_eq!(
            NoiseProcess::new(NoiseModel::Ar1 {
                sigma: 1.0,
                rho: 1.0
            }),
            Err(NoiseError::InvalidRho)
        );
        assert_eq!(
            NoiseProcess::new(NoiseModel::Ar1 {
                sigma: 1.0,
                rho: f64::INFINITY
            }),
            Err(NoiseError::InvalidRho)
        );
    }

    #[test]
    fn derived_seeds_are_distinct() {
        let mut seen = std::collections::HashSet::new();
        for base in 0..20u64 {
            for i in 0..200u64 {
                assert!(seen.insert(derive_seed(base, i)));
            }
        }
    }

    #[test]
    fn poisson_counts_have_the_stated_mean_and_variance() {
        let mut rng = rng_from_seed(4);
        let lambda = 3.5;
        let n = 100_000;
        let xs: Vec<f64> = (0..n).map(|_| poisson(&mut rng, lambda) as f64).collect();
        let (m, v) = mean_var(&xs);
        // s.e. of the mean √(λ/n) = 0.0059.
        assert!((m - lambda).abs() < 0.03, "mean {m}");
        assert!((v - lambda).abs() < 0.1, "variance {v}");
        assert_eq!(poisson(&mut rng, 0.0), 0);
    }

    #[test]
    fn uniform_index_is_unbiased_and_in_range() {
        let mut rng = rng_from_seed(5);
        let mut counts = [0usize; 3];
        for _ in 0..30_000 {
            counts[uniform_index(&mut rng, 3)] += 1;
        }
        // Each ≈ 10000 ± 82 (binomial s.d.).
        for c in counts {
            assert!((c as i64 - 10_000).abs() < 400, "{counts:?}");
        }
        let mut items: Vec<u32> = (0..10).collect();
        shuffle(&mut rng, &mut items);
        let mut sorted = items.clone();
        sorted.sort();
        assert_eq!(sorted, (0..10).collect::<Vec<_>>());
    }
}
