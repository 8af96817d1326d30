//! The seeded noise generators (src/noise.rs).

use abtrack_host_tests::noise::*;

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
