//! The reference Kalman filters of the host tools (src/kalman.rs): the
//! anchors the experiments compare the library's filters with.

use abtrack::filter::Cartesian;
use abtrack::Gains;
use abtrack_host_tests::kalman::*;
use abtrack_host_tests::metrics::{mean_ci95, paired_difference_ci95};
use abtrack_host_tests::noise::{rng_from_seed, standard_normal};

#[test]
fn dwna_steady_state_gains_satisfy_kalata_not_benedict_bordner() {
    for (sigma_a, sigma_w, dt) in [
        (0.1, 20.0, 1.0),
        (1.0, 1.0, 1.0),
        (2.0, 5.0, 2.0),
        (5.0, 1.0, 1.0),
    ] {
        let (alpha, beta) = steady_state_alpha_beta(
            ProcessNoise::DiscreteWhiteAcceleration { sigma: sigma_a },
            dt,
            sigma_w,
        )
        .unwrap();
        let kalata = 2.0 * (2.0 - alpha) - 4.0 * (1.0 - alpha).sqrt();
        assert!(
            (beta - kalata).abs() < 1e-9,
            "α {alpha} β {beta} Kalata {kalata}"
        );
        // Tracking index λ = σ_a T²/σ_w and λ² = β²/(1 − α).
        let lambda = sigma_a * dt * dt / sigma_w;
        assert!(
            (beta * beta / (1.0 - alpha) - lambda * lambda).abs() < 1e-9 * (1.0 + lambda * lambda)
        );
        // Benedict–Bordner is a different curve (e.g. at α = 0.5 Kalata
        // gives β = 3 − 2√2 = 0.1716, Benedict–Bordner 0.25/1.5 = 0.1667).
        let bb = alpha * alpha / (2.0 - alpha);
        assert!(
            (beta - bb).abs() > 1e-4 * beta,
            "α {alpha}: β {beta} ≈ BB {bb}"
        );
    }
}

#[test]
fn cwna_steady_state_gains_do_not_satisfy_kalata() {
    // The continuous model's Q couples position and velocity differently;
    // its steady-state gains lie off Kalata's curve.
    let (alpha, beta) = steady_state_alpha_beta(
        ProcessNoise::ContinuousWhiteAcceleration {
            spectral_density: 1.0,
        },
        1.0,
        1.0,
    )
    .unwrap();
    let kalata = 2.0 * (2.0 - alpha) - 4.0 * (1.0 - alpha).sqrt();
    assert!((beta - kalata).abs() > 1e-3, "α {alpha} β {beta}");
}

#[test]
fn two_point_initialisation_matches_the_alpha_beta_filter() {
    let mut kf = ConstantVelocityKf::new(
        ProcessNoise::DiscreteWhiteAcceleration { sigma: 1.0 },
        isotropic(5.0),
    )
    .unwrap();
    let mut ab = Cartesian::<f64, 2, 2>::new();
    let g = Gains::alpha_beta_f64(0.5, 0.3).unwrap();
    let zs = [([10.0, 20.0], 1.0), ([14.0, 29.0], 2.0)];
    // A coast between the points: both use T = 1 + 2 = 3 s.
    kf.update(zs[0].0, zs[0].1).unwrap();
    ab.update(zs[0].0, zs[0].1, &g).unwrap();
    kf.coast(1.0).unwrap();
    ab.coast(1.0).unwrap();
    assert_eq!(kf.position(), ab.position());
    kf.update(zs[1].0, zs[1].1).unwrap();
    ab.update(zs[1].0, zs[1].1, &g).unwrap();
    assert_eq!(kf.position(), ab.position());
    assert_eq!(kf.velocity(), ab.velocity());
    assert_eq!(kf.velocity(), [4.0 / 3.0, 3.0]);
    // P from differencing: P_xx = 25, P_xv = 25/3, P_vv = 50/9.
    let p = kf.covariance();
    assert_eq!((p[0][0], p[0][1], p[1][1]), (25.0, 25.0 / 3.0, 50.0 / 9.0));
    assert_eq!(p[0][2], 0.0);
}

#[test]
fn first_filtered_update_by_hand() {
    // 1-D view (x axis), T = 1, R = 1, DWNA σ = 0 (no process noise).
    // After z = 0, 1: x = 1, v = 1, P = [[1, 1], [1, 2]].
    // Predict: x⁻ = 2, P⁻ = F P Fᵀ = [[1+2·1+2, 1+2], [3, 2]] = [[5, 3], [3, 2]].
    // z = 3: ν = 1, S = 6, K = [5/6, 3/6] → x = 2 + 5/6, v = 1 + 1/2:
    // exactly the least-squares line through (0,0), (1,1), (2,3) at t = 2
    // (slope 1.5, value 2.8333) — Al-Wagih eq. 24 at n = 3: α = 5/6, β = 1/2.
    let mut kf = ConstantVelocityKf::new(
        ProcessNoise::DiscreteWhiteAcceleration { sigma: 0.0 },
        isotropic(1.0),
    )
    .unwrap();
    kf.update([0.0, 0.0], 1.0).unwrap();
    kf.update([1.0, 0.0], 1.0).unwrap();
    let out = kf.update([3.0, 0.0], 1.0).unwrap();
    match out {
        KalmanOutcome::Filtered {
            predicted,
            innovation,
            innovation_covariance,
        } => {
            assert_eq!(predicted[0], 2.0);
            assert_eq!(innovation[0], 1.0);
            assert!((innovation_covariance[0][0] - 6.0).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    let k = kf.last_gain().unwrap();
    assert!((k[0][0] - 5.0 / 6.0).abs() < 1e-12 && (k[1][0] - 0.5).abs() < 1e-12);
    assert!((kf.position()[0] - (2.0 + 5.0 / 6.0)).abs() < 1e-12);
    assert!((kf.velocity()[0] - 1.5).abs() < 1e-12);
}

#[test]
fn refused_inputs_leave_the_state_untouched() {
    let mut kf = ConstantAccelerationKf::new(
        ProcessNoise::WienerAcceleration { sigma: 1.0 },
        isotropic(1.0),
    )
    .unwrap();
    for (i, z) in [[0.0, 0.0], [1.0, 1.0], [2.0, 2.5]].iter().enumerate() {
        kf.update(*z, 1.0).unwrap();
        assert_eq!(kf.phase() == KalmanPhase::Tracking, i >= 1);
    }
    let before = kf.clone();
    assert_eq!(
        kf.update([f64::NAN, 0.0], 1.0),
        Err(KalmanError::InvalidMeasurement)
    );
    assert_eq!(
        kf.update([0.0, 0.0], 0.0),
        Err(KalmanError::InvalidInterval)
    );
    assert_eq!(
        kf.update([0.0, 0.0], f64::INFINITY),
        Err(KalmanError::InvalidInterval)
    );
    assert_eq!(
        kf.update_with_covariance([0.0, 0.0], 1.0, [[1.0, 2.0], [2.0, 1.0]]),
        Err(KalmanError::InvalidCovariance)
    );
    assert_eq!(kf.coast(-1.0), Err(KalmanError::InvalidInterval));
    assert_eq!(kf, before);
    assert_eq!(
        ConstantAccelerationKf::new(
            ProcessNoise::DiscreteWhiteAcceleration { sigma: 1.0 },
            isotropic(1.0)
        )
        .err(),
        Some(KalmanError::ModelMismatch)
    );
    assert_eq!(
        ConstantVelocityKf::new(
            ProcessNoise::DiscreteWhiteAcceleration { sigma: -1.0 },
            isotropic(1.0)
        )
        .err(),
        Some(KalmanError::InvalidProcessNoise)
    );
}

#[test]
fn polar_covariance_by_hand() {
    // B = 0 (target on +y): x error is cross-range R·σ_B, y error is σ_R.
    let c = polar_measurement_covariance(1000.0, 0.0, 10.0, 0.01);
    assert!((c[0][0] - 100.0).abs() < 1e-9 && (c[1][1] - 100.0).abs() < 1e-9);
    assert!(c[0][1].abs() < 1e-12);
    // B = 90° (on +x): x error is σ_R, y error is R·σ_B = 20.
    let c = polar_measurement_covariance(2000.0, std::f64::consts::FRAC_PI_2, 3.0, 0.01);
    assert!((c[0][0] - 9.0).abs() < 1e-9 && (c[1][1] - 400.0).abs() < 1e-9);
    // B = 45°, σ_R = R·σ_B: isotropic, no correlation.
    let c = polar_measurement_covariance(100.0, std::f64::consts::FRAC_PI_4, 1.0, 0.01);
    assert!(c[0][1].abs() < 1e-12 && (c[0][0] - 1.0).abs() < 1e-12);
}

/// Truth with DWNA process noise (per-period constant random
/// acceleration) and white measurement noise, per axis.
fn dwna_run(seed: u64, steps: usize, dt: f64, sigma_a: f64, sigma_w: f64) -> Run {
    let mut rng = rng_from_seed(seed);
    let mut s = [0.0, 30.0, 0.0, -10.0];
    let mut truth = Vec::with_capacity(steps);
    let mut z = Vec::with_capacity(steps);
    for _ in 0..steps {
        truth.push(s);
        z.push([
            s[0] + sigma_w * standard_normal(&mut rng),
            s[2] + sigma_w * standard_normal(&mut rng),
        ]);
        for axis in 0..2 {
            let a = sigma_a * standard_normal(&mut rng);
            let (p, v) = (s[2 * axis], s[2 * axis + 1]);
            s[2 * axis] = p + v * dt + 0.5 * a * dt * dt;
            s[2 * axis + 1] = v + a * dt;
        }
    }
    (truth, z)
}

#[test]
fn kf_is_consistent_on_its_own_model() {
    // Normalised estimation error squared, 4 states, 200 runs, at step 60:
    // 200·NEES ~ χ²(800): 99 % interval [711, 897] → mean in [3.56, 4.49].
    let (dt, sa, sw) = (1.0, 0.5, 10.0);
    let mut total = 0.0;
    let runs = 200;
    for seed in 0..runs {
        let (truth, z) = dwna_run(seed, 60, dt, sa, sw);
        let mut kf = ConstantVelocityKf::new(
            ProcessNoise::DiscreteWhiteAcceleration { sigma: sa },
            isotropic(sw),
        )
        .unwrap();
        for zk in &z {
            kf.update(*zk, dt).unwrap();
        }
        let s = truth[59];
        let e = [
            kf.state()[0] - s[0],
            kf.state()[1] - s[1],
            kf.state()[2] - s[2],
            kf.state()[3] - s[3],
        ];
        // e' P⁻¹ e via the two decoupled 2×2 blocks (R isotropic, axes
        // independent).
        let p = kf.covariance();
        for axis in 0..2 {
            let b = 2 * axis;
            let (a11, a12, a22) = (p[b][b], p[b][b + 1], p[b + 1][b + 1]);
            let det = a11 * a22 - a12 * a12;
            let (e1, e2) = (e[b], e[b + 1]);
            total += (a22 * e1 * e1 - 2.0 * a12 * e1 * e2 + a11 * e2 * e2) / det;
        }
    }
    let nees = total / runs as f64;
    assert!((3.56..=4.49).contains(&nees), "mean NEES {nees}");
}

/// One run: truth states `[x, ẋ, y, ẏ]` and measurements, per scan.
type Run = (Vec<[f64; 4]>, Vec<[f64; 2]>);

/// Per-run position RMSE (distance) of a 2-D estimator over scans
/// `from..`, on DWNA data.
fn scored_rmse(
    data: &[Run],
    from: usize,
    mut estimator: impl FnMut() -> Box<dyn FnMut([f64; 2]) -> [f64; 2]>,
) -> Vec<f64> {
    data.iter()
        .map(|(truth, z)| {
            let mut step = estimator();
            let mut sum = 0.0;
            for (k, (zk, t)) in z.iter().zip(truth).enumerate() {
                let e = step(*zk);
                if k >= from {
                    sum += (e[0] - t[0]).powi(2) + (e[1] - t[2]).powi(2);
                }
            }
            (sum / (z.len() - from) as f64).sqrt()
        })
        .collect()
}

#[test]
fn kf_is_not_worse_than_the_best_fixed_alpha_beta() {
    // CV target with DWNA σ_a = 0.5 m/s², σ_w = 10 m, T = 1 s (tracking
    // index λ = 0.05), 100 scans, 100 runs. The KF with the matching q
    // against every fixed αβ on a grid of α (step 0.025) with β from
    // Kalata's relation or Benedict–Bordner's, all from the same two-point
    // start. Scored (a) from the third scan, the first filtered estimate,
    // and (b) in steady state, from scan 40.
    let (dt, sa, sw, steps, runs) = (1.0, 0.5, 10.0, 100, 100u64);
    let data: Vec<_> = (0..runs)
        .map(|s| dwna_run(1000 + s, steps, dt, sa, sw))
        .collect();
    let noise = ProcessNoise::DiscreteWhiteAcceleration { sigma: sa };
    let kf = |from| {
        scored_rmse(&data, from, || {
            let mut kf = ConstantVelocityKf::new(noise, isotropic(sw)).unwrap();
            Box::new(move |z| {
                kf.update(z, dt).unwrap();
                kf.position()
            })
        })
    };
    let best_ab = |from| {
        let mut best: Option<(f64, f64, Vec<f64>)> = None;
        for i in 1..40 {
            let alpha = i as f64 * 0.025;
            for beta in [
                2.0 * (2.0 - alpha) - 4.0 * (1.0 - alpha).sqrt(),
                alpha * alpha / (2.0 - alpha),
            ] {
                let g = Gains::alpha_beta_f64(alpha, beta).unwrap();
                let r = scored_rmse(&data, from, || {
                    let mut f = Cartesian::<f64, 2, 2>::new();
                    Box::new(move |z| {
                        f.update(z, dt, &g).unwrap();
                        f.position()
                    })
                });
                let m = mean_ci95(&r).mean;
                if best.as_ref().is_none_or(|b| m < b.0) {
                    best = Some((m, alpha, r));
                }
            }
        }
        best.unwrap()
    };
    let (alpha_ss, _) = steady_state_alpha_beta(noise, dt, sw).unwrap();
    for from in [2, 40] {
        let kf_runs = kf(from);
        let (best_mean, best_alpha, best_runs) = best_ab(from);
        let diff = paired_difference_ci95(&kf_runs, &best_runs).unwrap();
        // Not worse: KF − best αβ is not significantly positive, although
        // the best α is chosen on these very runs, which favours αβ.
        assert!(
            diff.lower() <= 0.0,
            "from scan {from}: KF {:.3} vs best αβ (α = {best_alpha}) {best_mean:.3}; diff {diff:?}",
            mean_ci95(&kf_runs).mean
        );
        if from == 2 {
            // Measured: KF 7.71 m, best αβ (α = 0.425) 9.39 m: with the
            // transient after two-point start scored, the KF's decreasing
            // gains win clearly.
            assert!(diff.upper() < 0.0, "{diff:?}");
        } else {
            // Steady state: the best fixed α is the KF's steady-state
            // α ≈ 0.271 (to a grid step) and the two are equally accurate
            // (measured: 7.384 vs 7.387 m, diff −0.003 ± 0.006).
            assert!(
                (best_alpha - alpha_ss).abs() <= 0.05,
                "best α {best_alpha}, KF steady state {alpha_ss}"
            );
            assert!(diff.mean.abs() < 0.02 * best_mean, "{diff:?}");
        }
    }
}

#[test]
fn ca_filter_follows_constant_acceleration_without_lag() {
    // Constant acceleration (1, −0.5) m/s², σ_w = 5 m, T = 1 s, 80 scans.
    // The CV filter (small q) lags; the CA filter's mean error is ≈ 0.
    let (dt, sw) = (1.0, 5.0);
    let runs = 50;
    let mut cv_bias = [0.0; 2];
    let mut ca_bias = [0.0; 2];
    for seed in 0..runs {
        let mut rng = rng_from_seed(500 + seed);
        let mut cv = ConstantVelocityKf::new(
            ProcessNoise::DiscreteWhiteAcceleration { sigma: 0.05 },
            isotropic(sw),
        )
        .unwrap();
        let mut ca = ConstantAccelerationKf::new(
            ProcessNoise::WienerAcceleration { sigma: 0.01 },
            isotropic(sw),
        )
        .unwrap();
        for k in 0..80 {
            let t = k as f64 * dt;
            let truth = [0.5 * t * t, -0.25 * t * t];
            let z = [
                truth[0] + sw * standard_normal(&mut rng),
                truth[1] + sw * standard_normal(&mut rng),
            ];
            cv.update(z, dt).unwrap();
            ca.update(z, dt).unwrap();
            if k >= 40 {
                for a in 0..2 {
                    cv_bias[a] += cv.position()[a] - truth[a];
                    ca_bias[a] += ca.position()[a] - truth[a];
                }
            }
        }
    }
    let n = (runs * 40) as f64;
    let (cv_bias, ca_bias) = (cv_bias.map(|b| b / n), ca_bias.map(|b| b / n));
    // CV lag: about a/λ-scale metres, negative along +a. Observed ≫ 1 m.
    assert!(cv_bias[0] < -2.0 && cv_bias[1] > 1.0, "CV bias {cv_bias:?}");
    // CA: unbiased up to its noise (per-estimate σ ≈ 2–3 m, 2000 correlated
    // samples): |bias| < 0.5 m.
    assert!(
        ca_bias[0].abs() < 0.5 && ca_bias[1].abs() < 0.5,
        "CA bias {ca_bias:?}"
    );
    let a = ConstantAccelerationKf::new(
        ProcessNoise::WienerAcceleration { sigma: 0.01 },
        isotropic(sw),
    )
    .unwrap();
    assert_eq!(a.acceleration(), [0.0, 0.0]);
}

#[test]
fn coast_adds_process_noise() {
    // After tracking, a coast of T gives P⁻ = F P Fᵀ + Q; check the
    // position variance against the formula for DWNA.
    let mut kf = ConstantVelocityKf::new(
        ProcessNoise::DiscreteWhiteAcceleration { sigma: 2.0 },
        isotropic(3.0),
    )
    .unwrap();
    kf.update([0.0, 0.0], 1.0).unwrap();
    kf.update([1.0, 1.0], 1.0).unwrap();
    let p = kf.covariance();
    kf.coast(2.0).unwrap();
    // P_xx' = P_xx + 2T P_xv + T² P_vv + σ²T⁴/4 with T = 2:
    // 9 + 4·9 + 4·18 + 4·16/4 = 9 + 36 + 72 + 16 = 133.
    let expected = p[0][0] + 4.0 * p[0][1] + 4.0 * p[1][1] + 4.0 * 16.0 / 4.0;
    assert_eq!(expected, 133.0);
    assert!((kf.covariance()[0][0] - 133.0).abs() < 1e-9);
    // x = 1, v = 1 on both axes after the two points; 2 s later x = 3.
    assert_eq!(kf.position(), [3.0, 3.0]);
}
