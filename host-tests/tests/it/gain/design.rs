//! The `design` module: golden values worked by hand, and every formula tied
//! to the implemented filter (`AlphaBeta<f64>`, `AlphaBetaGamma<f64>`,
//! `Cartesian`) by simulation.
//!
//! Run from inside host-tests: `cargo test --test it gain::design`.

use abtrack::design::*;
use abtrack::filter::{Cartesian, UpdateOutcome};
use abtrack::{AlphaBeta, AlphaBetaGamma, GainError, Gains};

// ---------------------------------------------------------------------------
// Helpers

#[track_caller]
fn assert_close(actual: f64, expected: f64, relative: f64) {
    let scale = expected.abs().max(1e-300);
    assert!(
        (actual - expected).abs() <= relative * scale,
        "actual {actual:.17e}, expected {expected:.17e}, relative error {:.3e} > {relative:.1e}",
        (actual - expected).abs() / scale
    );
}

#[track_caller]
fn assert_abs(actual: f64, expected: f64, tolerance: f64) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "actual {actual:.17e}, expected {expected:.17e}, |diff| {:.3e} > {tolerance:.1e}",
        (actual - expected).abs()
    );
}

fn residual<const N: usize>(outcome: [UpdateOutcome<f64>; N]) -> [f64; N] {
    outcome.map(|o| match o {
        UpdateOutcome::Filtered(i) => i.residual,
        _ => panic!("expected a filtered update"),
    })
}

fn filtered(o: UpdateOutcome<f64>) -> abtrack::filter::Innovation<f64> {
    match o {
        UpdateOutcome::Filtered(i) => i,
        other => panic!("expected a filtered update, got {other:?}"),
    }
}

type Matrix<const N: usize> = [[f64; N]; N];

fn matrix_product<const N: usize>(a: &Matrix<N>, b: &Matrix<N>) -> Matrix<N> {
    let mut out = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            out[i][j] = (0..N).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

/// Spectral radius by Gelfand's formula ρ = lim ‖Aⁿ‖^{1/n}, n = 2¹⁴, by
/// repeated squaring with renormalisation (so no overflow). Independent of
/// any root formula. The polynomial factor of a Jordan block of size ≤ 3
/// biases it by at most (C n²)^{1/n} ≈ 1 + 0.2 %.
fn gelfand_spectral_radius<const N: usize>(a: &Matrix<N>) -> f64 {
    let norm = |m: &Matrix<N>| m.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    let n0 = norm(a);
    if n0 == 0.0 {
        return 0.0;
    }
    let mut log_scale = n0.ln();
    let mut b = a.map(|row| row.map(|v| v / n0));
    const SQUARINGS: i32 = 14;
    for _ in 0..SQUARINGS {
        let sq = matrix_product(&b, &b);
        let n = norm(&sq);
        if n == 0.0 {
            return 0.0; // nilpotent: every pole at 0
        }
        log_scale = 2.0 * log_scale + n.ln();
        b = sq.map(|row| row.map(|v| v / n));
    }
    (log_scale / 2f64.powi(SQUARINGS)).exp()
}

/// The αβ filter's zero-input transition of the smoothed state (x_s, v_s),
/// measured by running the real filter: column i is the state after one
/// update with z = 0, starting from unit vector i.
fn filter_transition_ab(alpha: f64, beta: f64, dt: f64) -> Matrix<2> {
    let gains = Gains::<f64>::alpha_beta(alpha, beta).unwrap();
    let mut m = [[0.0; 2]; 2];
    for (col, start) in [(1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
        let mut f = AlphaBeta::<f64>::from_state(start.0, start.1, 0.0).unwrap();
        f.update(0.0, dt, &gains).unwrap();
        m[0][col] = f.position();
        m[1][col] = f.velocity();
    }
    m
}

fn filter_transition_abg(alpha: f64, beta: f64, gamma: f64, dt: f64) -> Matrix<3> {
    let gains = Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma).unwrap();
    let mut m = [[0.0; 3]; 3];
    for col in 0..3 {
        let mut s = [0.0; 3];
        s[col] = 1.0;
        let mut f = AlphaBetaGamma::<f64>::from_state(s[0], s[1], s[2]).unwrap();
        f.update(0.0, dt, &gains).unwrap();
        m[0][col] = f.position();
        m[1][col] = f.velocity();
        m[2][col] = f.acceleration();
    }
    m
}

/// The same transition written from the papers' equations (Al-Wagih 3–8,
/// Tenne & Singh 1–5 with γ/(2T²)), for gains the filter would refuse.
fn equations_transition_abg(alpha: f64, beta: f64, gamma: f64, dt: f64) -> Matrix<3> {
    let mut m = [[0.0; 3]; 3];
    for col in 0..3 {
        let mut s = [0.0; 3];
        s[col] = 1.0;
        let xp = s[0] + dt * s[1] + 0.5 * dt * dt * s[2];
        let vp = s[1] + dt * s[2];
        let e = -xp;
        m[0][col] = xp + alpha * e;
        m[1][col] = vp + beta / dt * e;
        m[2][col] = s[2] + gamma / (2.0 * dt * dt) * e;
    }
    m
}

fn equations_transition_ab(alpha: f64, beta: f64, dt: f64) -> Matrix<2> {
    let m = equations_transition_abg(alpha, beta, 0.0, dt);
    [[m[0][0], m[0][1]], [m[1][0], m[1][1]]]
}

/// Characteristic polynomial det(zI − A), highest power first.
fn characteristic_2(a: &Matrix<2>) -> [f64; 3] {
    let trace = a[0][0] + a[1][1];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [1.0, -trace, det]
}

fn characteristic_3(a: &Matrix<3>) -> [f64; 4] {
    let trace = a[0][0] + a[1][1] + a[2][2];
    let minors = a[0][0] * a[1][1] - a[0][1] * a[1][0] + a[0][0] * a[2][2] - a[0][2] * a[2][0]
        + a[1][1] * a[2][2]
        - a[1][2] * a[2][1];
    let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    [1.0, -trace, minors, -det]
}

/// |p(z)| for real coefficients (highest first) at a complex z.
fn polynomial_modulus_at(coefficients: &[f64], z: Pole) -> f64 {
    let (mut re, mut im) = (0.0, 0.0);
    for &c in coefficients {
        let r = re * z.re - im * z.im + c;
        im = re * z.im + im * z.re;
        re = r;
    }
    (re * re + im * im).sqrt()
}

/// Impulse responses of the real αβ filter at rest: a unit measurement at
/// k = 0, zeros after. Returns (Σ x_p(k)², Σ x_s(k)², Σ v_s(k)²).
fn alpha_beta_impulse_sums(alpha: f64, beta: f64, dt: f64, steps: usize) -> (f64, f64, f64) {
    let gains = Gains::<f64>::alpha_beta(alpha, beta).unwrap();
    let mut f = AlphaBeta::<f64>::from_state(0.0, 0.0, 0.0).unwrap();
    let (mut predicted, mut smoothed, mut velocity) = (0.0, 0.0, 0.0);
    for k in 0..steps {
        let z = if k == 0 { 1.0 } else { 0.0 };
        let i = filtered(f.update(z, dt, &gains).unwrap());
        predicted += i.predicted * i.predicted;
        smoothed += f.position() * f.position();
        velocity += f.velocity() * f.velocity();
    }
    (predicted, smoothed, velocity)
}

fn alpha_beta_gamma_impulse_sum(alpha: f64, beta: f64, gamma: f64, steps: usize) -> f64 {
    let gains = Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma).unwrap();
    let mut f = AlphaBetaGamma::<f64>::from_state(0.0, 0.0, 0.0).unwrap();
    let mut predicted = 0.0;
    for k in 0..steps {
        let z = if k == 0 { 1.0 } else { 0.0 };
        let i = filtered(f.update(z, 0.8, &gains).unwrap());
        predicted += i.predicted * i.predicted;
    }
    predicted
}

/// Σ_{k≥0} T·(e(k) − e_ss)² of the real filter at rest at the origin, fed a
/// target x(k) = vTk + ½aT²k² (the zero-state response of Tenne & Singh
/// eq. 18).
fn simulated_transient_cost<const ORDER: usize>(
    gains: &Gains<f64>,
    dt: f64,
    velocity: f64,
    acceleration: f64,
    steady_state: f64,
    steps: usize,
) -> f64 {
    let mut f = abtrack::filter::KinematicFilter::<f64, ORDER>::from_state(0.0, 0.0, 0.0).unwrap();
    let mut cost = 0.0;
    for k in 0..steps {
        let t = k as f64 * dt;
        let z = velocity * t + 0.5 * acceleration * t * t;
        let e = filtered(f.update(z, dt, gains).unwrap()).residual;
        cost += dt * (e - steady_state) * (e - steady_state);
    }
    cost
}

/// A grid over (and beyond) the αβ triangle, offset so that no point falls on
/// a boundary line.
fn alpha_beta_grid() -> impl Iterator<Item = (f64, f64)> {
    (0..52).flat_map(|i| {
        let alpha = -0.2377 + 0.05 * i as f64;
        (0..102).map(move |j| (alpha, -0.4711 + 0.05 * j as f64))
    })
}

fn stable_alpha_beta_samples() -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 1..20 {
        for j in 1..40 {
            let (alpha, beta) = (0.1 * i as f64 - 0.013, 0.1 * j as f64 - 0.021);
            if is_stable_alpha_beta(alpha, beta)
                && alpha_beta_spectral_radius(alpha, beta).unwrap() < 0.97
            {
                out.push((alpha, beta));
            }
        }
    }
    out
}

fn stable_alpha_beta_gamma_samples() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for i in 1..10 {
        for j in 1..20 {
            for k in 1..25 {
                let alpha = 0.2 * i as f64 - 0.017;
                let beta = 0.2 * j as f64 - 0.031;
                let gamma = 0.1 * k as f64 - 0.043;
                if is_stable_alpha_beta_gamma(alpha, beta, gamma)
                    && alpha_beta_gamma_spectral_radius(alpha, beta, gamma).unwrap() < 0.97
                {
                    out.push((alpha, beta, gamma));
                }
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------
// Stability: golden values

#[test]
fn stability_predicates_golden() {
    // Al-Wagih eqs. 12–14: 0 < α < 2, β > 0, 2α + β < 4.
    assert!(is_stable_alpha_beta(0.5, 0.2));
    assert!(is_stable_alpha_beta(1.9, 0.15)); // 3.8 + 0.15 = 3.95 < 4
    assert!(!is_stable_alpha_beta(1.0, 2.0)); // 2 + 2 = 4: on the boundary
    assert!(!is_stable_alpha_beta(1.9, 0.25)); // 3.8 + 0.25 = 4.05
    assert!(!is_stable_alpha_beta(2.0, 0.1));
    assert!(!is_stable_alpha_beta(0.5, 0.0));
    assert!(!is_stable_alpha_beta(f64::NAN, 0.2));
    // Tenne & Singh eq. 8 at α = 0.5, β = 0.2: γ < 4·0.5·0.2/1.5 = 0.2667.
    assert!(is_stable_alpha_beta_gamma(0.5, 0.2, 0.26));
    assert!(!is_stable_alpha_beta_gamma(0.5, 0.2, 0.27));
    assert!(!is_stable_alpha_beta_gamma(0.5, 0.2, 0.0));
}

#[test]
fn alpha_beta_polynomial_and_poles_golden() {
    // Eq. 15 at (0.5, 0.2): z² + (0.5 + 0.2 − 2)z + (1 − 0.5) = z² − 1.3z + 0.5.
    let p = alpha_beta_characteristic_polynomial(0.5, 0.2).unwrap();
    assert_abs(p[0], 1.0, 0.0);
    assert_abs(p[1], -1.3, 1e-15);
    assert_abs(p[2], 0.5, 0.0);
    // Eqs. 16–17: D = 1.69 − 2 = −0.31 < 0, z = 0.65 ± i·√0.31/2
    // = 0.65 ± 0.2783882181415011i, |z|² = 0.5 (the constant term).
    let [z1, z2] = alpha_beta_poles(0.5, 0.2).unwrap();
    assert_abs(z1.re, 0.65, 1e-15);
    assert_abs(z1.im, 0.2783882181415011, 1e-15);
    assert_abs(z2.re, 0.65, 1e-15);
    assert_abs(z2.im, -0.2783882181415011, 1e-15);
    assert_abs(
        alpha_beta_spectral_radius(0.5, 0.2).unwrap(),
        0.5f64.sqrt(),
        1e-15,
    );

    // (0.9, 0.1): z² − z + 0.1, D = 1 − 0.4 = 0.6, z = (1 ± √0.6)/2
    // = 0.8872983346207417 and 0.1127016653792583.
    let [z1, z2] = alpha_beta_poles(0.9, 0.1).unwrap();
    assert_abs(z1.re, 0.8872983346207417, 1e-15);
    assert_abs(z2.re, 0.1127016653792583, 1e-15);
    assert_eq!((z1.im, z2.im), (0.0, 0.0));
    assert_abs(
        alpha_beta_spectral_radius(0.9, 0.1).unwrap(),
        0.8872983346207417,
        1e-15,
    );

    // (1, 1): z² + 0z + 0, the dead-beat filter: both poles at 0.
    let [z1, z2] = alpha_beta_poles(1.0, 1.0).unwrap();
    assert_eq!((z1.modulus(), z2.modulus()), (0.0, 0.0));

    // Outside the triangle (2.5, 0.2): z² + 0.7z − 1.5, D = 0.49 + 6 = 6.49,
    // z = (−0.7 − 2.5475478)/2 = −1.6237739 (the other 0.9237739).
    assert_abs(
        alpha_beta_spectral_radius(2.5, 0.2).unwrap(),
        1.6237739202856996,
        1e-12,
    );
}

#[test]
fn alpha_beta_gamma_polynomial_and_poles_golden() {
    // Eq. 6 at (0.5, 0.2, 0.04): z³ + (0.5 + 0.2 + 0.01 − 3)z² + (−1 − 0.2 + 0.01 + 3)z
    // + (0.5 − 1) = z³ − 2.29z² + 1.81z − 0.5.
    let p = alpha_beta_gamma_characteristic_polynomial(0.5, 0.2, 0.04).unwrap();
    assert_abs(p[0], 1.0, 0.0);
    assert_abs(p[1], -2.29, 1e-15);
    assert_abs(p[2], 1.81, 1e-15);
    assert_abs(p[3], -0.5, 0.0);

    // Built from factors: (a, b, c) = (0.5, 0.2, 0.5) maps (eq. 12) to
    // α = 1 + 0.5·0.5 = 1.25, β = 0.5·1.5 + 0.2·0.5/2 = 0.8, γ = 2·0.2·1.5 = 0.6,
    // so the poles are −c = −0.5 and those of z² − 1.3z + 0.5: 0.65 ± 0.27839i.
    let poles = alpha_beta_gamma_poles(1.25, 0.8, 0.6).unwrap();
    assert_abs(poles[0].re, 0.65, 1e-14);
    assert_abs(poles[0].im, 0.2783882181415011, 1e-14);
    assert_abs(poles[1].re, 0.65, 1e-14);
    assert_abs(poles[1].im, -0.2783882181415011, 1e-14);
    assert_abs(poles[2].re, -0.5, 1e-14);
    assert_abs(poles[2].im, 0.0, 0.0);
    assert_abs(
        alpha_beta_gamma_spectral_radius(1.25, 0.8, 0.6).unwrap(),
        0.5f64.sqrt(),
        1e-14,
    );

    // Three real poles: (a, b, c) = (0.9, 0.1, −0.5) maps to α = 1 − 0.5·0.1 = 0.95,
    // β = 0.9·0.5 + 0.1·1.5/2 = 0.525, γ = 2·0.1·0.5 = 0.1; poles 0.5 and
    // (1 ± √0.6)/2 = 0.8872983346207417, 0.1127016653792583.
    let poles = alpha_beta_gamma_poles(0.95, 0.525, 0.1).unwrap();
    for (pole, expected) in poles
        .iter()
        .zip([0.8872983346207417, 0.5, 0.1127016653792583])
    {
        assert_abs(pole.re, expected, 1e-14);
        assert_eq!(pole.im, 0.0);
    }

    // γ = 0 factors as (z − 1)(αβ polynomial): a pole at exactly 1.
    // (Cardano plus Newton: a few ulps.)
    let poles = alpha_beta_gamma_poles(0.5, 0.2, 0.0).unwrap();
    assert_abs(poles[0].re, 1.0, 1e-14);
    assert_abs(
        alpha_beta_gamma_spectral_radius(0.5, 0.2, 0.0).unwrap(),
        1.0,
        1e-14,
    );
}

// ---------------------------------------------------------------------------
// Stability: tied to the filter's actual error dynamics

#[test]
fn alpha_beta_stability_agrees_with_the_filters_error_dynamics() {
    let dt = 0.7;
    let (mut stable, mut unstable, mut on_boundary) = (0, 0, 0);
    for (alpha, beta) in alpha_beta_grid() {
        let equations = equations_transition_ab(alpha, beta, dt);
        if is_stable_alpha_beta(alpha, beta) {
            // The transition measured on the real filter is the one written
            // from the equations (so the equations stand for it outside
            // the region, where the filter refuses the gains).
            let measured = filter_transition_ab(alpha, beta, dt);
            for i in 0..2 {
                for j in 0..2 {
                    assert_abs(measured[i][j], equations[i][j], 1e-14);
                }
            }
        }
        // Eq. 15 is the characteristic polynomial of that transition.
        let from_matrix = characteristic_2(&equations);
        let from_paper = alpha_beta_characteristic_polynomial(alpha, beta).unwrap();
        for (m, p) in from_matrix.iter().zip(from_paper) {
            assert_abs(*m, p, 1e-13);
        }
        // Eqs. 16–17 are its roots.
        for pole in alpha_beta_poles(alpha, beta).unwrap() {
            assert!(polynomial_modulus_at(&from_matrix, pole) < 1e-12);
        }
        // The spectral radius is Gelfand's, computed from the matrix alone.
        let radius = alpha_beta_spectral_radius(alpha, beta).unwrap();
        let gelfand = gelfand_spectral_radius(&equations);
        assert_abs(gelfand, radius, 5e-3 * radius + 1e-3);
        // The predicate is exactly "spectral radius < 1".
        if (radius - 1.0).abs() < 1e-9 {
            on_boundary += 1;
            continue;
        }
        assert_eq!(
            is_stable_alpha_beta(alpha, beta),
            radius < 1.0,
            "alpha {alpha} beta {beta} radius {radius}"
        );
        if radius < 1.0 {
            stable += 1;
        } else {
            unstable += 1;
        }
    }
    assert!(stable > 1000 && unstable > 1000, "{stable} {unstable}");
    assert_eq!(on_boundary, 0);
}

#[test]
fn alpha_beta_gamma_stability_agrees_with_the_filters_error_dynamics() {
    let dt = 1.3;
    let (mut stable, mut unstable, mut on_boundary) = (0, 0, 0);
    for i in 0..25 {
        for j in 0..47 {
            for k in 0..40 {
                let alpha = -0.1877 + 0.1 * i as f64;
                let beta = -0.3311 + 0.1 * j as f64;
                let gamma = -0.2093 + 0.15 * k as f64;
                let equations = equations_transition_abg(alpha, beta, gamma, dt);
                if is_stable_alpha_beta_gamma(alpha, beta, gamma) {
                    let measured = filter_transition_abg(alpha, beta, gamma, dt);
                    for r in 0..3 {
                        for c in 0..3 {
                            assert_abs(measured[r][c], equations[r][c], 1e-13);
                        }
                    }
                }
                // Eq. 6's denominator is the transition's characteristic
                // polynomial (Tenne & Singh's γ/(2T²) convention).
                let from_matrix = characteristic_3(&equations);
                let from_paper =
                    alpha_beta_gamma_characteristic_polynomial(alpha, beta, gamma).unwrap();
                for (m, p) in from_matrix.iter().zip(from_paper) {
                    assert_abs(*m, p, 1e-12);
                }
                for pole in alpha_beta_gamma_poles(alpha, beta, gamma).unwrap() {
                    assert!(
                        polynomial_modulus_at(&from_matrix, pole) < 1e-9,
                        "{alpha} {beta} {gamma} {pole:?}"
                    );
                }
                let radius = alpha_beta_gamma_spectral_radius(alpha, beta, gamma).unwrap();
                let gelfand = gelfand_spectral_radius(&equations);
                assert_abs(gelfand, radius, 5e-3 * radius + 1e-3);
                if (radius - 1.0).abs() < 1e-9 {
                    on_boundary += 1;
                    continue;
                }
                // Eqs. 7–8 are exactly "all roots inside the unit circle".
                assert_eq!(
                    is_stable_alpha_beta_gamma(alpha, beta, gamma),
                    radius < 1.0,
                    "alpha {alpha} beta {beta} gamma {gamma} radius {radius}"
                );
                if radius < 1.0 {
                    stable += 1;
                } else {
                    unstable += 1;
                }
            }
        }
    }
    assert!(stable > 1000 && unstable > 1000, "{stable} {unstable}");
    assert_eq!(on_boundary, 0);
}

// ---------------------------------------------------------------------------
// Critical damping, Benedict–Bordner, least squares, Kalata

#[test]
fn critically_damped_betas_golden() {
    // α = 0.75: √(1 − α) = 0.5, β = 2 − 0.75 ∓ 1 = 0.25 and 2.25.
    let b = critically_damped_betas(0.75).unwrap();
    assert_abs(b.monotone, 0.25, 1e-16);
    assert_abs(b.alternating, 2.25, 1e-15);
    // α = 0.36: √0.64 = 0.8, β = 1.64 ∓ 1.6 = 0.04 and 3.24.
    let b = critically_damped_betas(0.36).unwrap();
    assert_abs(b.monotone, 0.04, 1e-16);
    assert_abs(b.alternating, 3.24, 1e-15);
    // α = 1: both branches meet at β = 1.
    let b = critically_damped_betas(1.0).unwrap();
    assert_eq!((b.monotone, b.alternating), (1.0, 1.0));
    // Double poles: (0.75, 0.25) gives z² − z + 0.25 = (z − 0.5)²,
    // (0.75, 2.25) gives z² + z + 0.25 = (z + 0.5)².
    for p in alpha_beta_poles(0.75, 0.25).unwrap() {
        assert_abs(p.re, 0.5, 1e-8);
        assert_eq!(p.im, 0.0);
    }
    for p in alpha_beta_poles(0.75, 2.25).unwrap() {
        assert_abs(p.re, -0.5, 1e-8);
        assert_eq!(p.im, 0.0);
    }
    for bad in [0.0, -0.1, 1.0 + 1e-12, 1.5] {
        assert_eq!(
            critically_damped_betas(bad),
            Err(DesignError::AlphaOutOfRange)
        );
    }
    assert_eq!(
        critically_damped_betas(f64::NAN),
        Err(DesignError::NotFinite)
    );
}

#[test]
fn critically_damped_filter_has_a_double_pole_and_the_right_sign_pattern() {
    for alpha in [0.05, 0.2, 0.36, 0.5, 0.75, 0.9] {
        let betas = critically_damped_betas(alpha).unwrap();
        let pole = (1.0 - alpha).sqrt();
        for (beta, double_pole) in [(betas.monotone, pole), (betas.alternating, -pole)] {
            // The real filter's transition: trace 2λ, determinant λ².
            let m = filter_transition_ab(alpha, beta, 2.0);
            let [_, minus_trace, det] = characteristic_2(&m);
            assert_abs(-minus_trace, 2.0 * double_pole, 1e-14);
            assert_abs(det, double_pole * double_pole, 1e-14);
        }
        // Zero-input response from a position offset, (c₁ + c₂k)λᵏ: on the
        // monotone branch it changes sign at most once (where c₁ + c₂k
        // does); on the alternating branch it flips every scan but at most
        // one.
        for (beta, alternating) in [(betas.monotone, false), (betas.alternating, true)] {
            let gains = Gains::<f64>::alpha_beta(alpha, beta).unwrap();
            let mut f = AlphaBeta::<f64>::from_state(1.0, 0.0, 0.0).unwrap();
            let mut previous = f.position();
            let (mut scans, mut sign_changes) = (0, 0);
            for _ in 0..200 {
                f.update(0.0, 2.0, &gains).unwrap();
                let x = f.position();
                if x == 0.0 {
                    continue; // an exact zero has no sign (e.g. α = 0.75 at k = 1)
                }
                if x.abs() < 1e-250 {
                    break;
                }
                scans += 1;
                if x * previous < 0.0 {
                    sign_changes += 1;
                }
                previous = x;
            }
            assert!(
                scans > 20,
                "alpha {alpha} beta {beta}: {scans} scans, x = {previous}"
            );
            if alternating {
                assert!(
                    sign_changes >= scans - 2,
                    "alpha {alpha}: {sign_changes}/{scans}"
                );
            } else {
                assert!(sign_changes <= 1, "alpha {alpha}: {sign_changes}/{scans}");
            }
        }
    }
}

#[test]
fn benedict_bordner_beta_golden() {
    // β = α²/(2 − α): 0.25/1.5 = 1/6; 1/1 = 1; 0.1296/1.64 = 0.07902439024390244.
    assert_abs(benedict_bordner_beta(0.5).unwrap(), 1.0 / 6.0, 1e-16);
    assert_abs(benedict_bordner_beta(1.0).unwrap(), 1.0, 0.0);
    assert_abs(
        benedict_bordner_beta(0.36).unwrap(),
        0.07902439024390244,
        1e-16,
    );
    // It lies between the critically damped β and Kalata's (the optimal
    // curves of Tenne & Singh §3.2 move "towards the critically damped curve").
    for alpha in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let bb = benedict_bordner_beta(alpha).unwrap();
        assert!(bb > critically_damped_betas(alpha).unwrap().monotone);
        assert!(bb < kalata_beta(alpha).unwrap());
        assert!(is_stable_alpha_beta(alpha, bb));
    }
    assert_eq!(
        benedict_bordner_beta(1.1),
        Err(DesignError::AlphaOutOfRange)
    );
    assert_eq!(
        benedict_bordner_beta(0.0),
        Err(DesignError::AlphaOutOfRange)
    );
    assert_eq!(
        benedict_bordner_beta(f64::INFINITY),
        Err(DesignError::NotFinite)
    );
}

#[test]
fn least_squares_gains_golden() {
    // n = 3: α = 2(6 − 1)/(3·4) = 10/12 = 5/6, β = 6/12 = 1/2.
    let g = least_squares_gains(3).unwrap();
    assert_abs(g.alpha(), 5.0 / 6.0, 1e-16);
    assert_abs(g.beta(), 0.5, 1e-16);
    // n = 10: α = 2·19/110 = 0.34545454545454546, β = 6/110 = 0.05454545454545454.
    let g = least_squares_gains(10).unwrap();
    assert_abs(g.alpha(), 0.34545454545454546, 1e-16);
    assert_abs(g.beta(), 0.05454545454545454, 1e-16);
    for n in [0, 1, 2] {
        assert_eq!(least_squares_gains(n), Err(DesignError::TooFewMeasurements));
    }
    assert!(least_squares_gains(u32::MAX).is_ok());
}

#[test]
fn least_squares_gains_make_the_filter_a_growing_least_squares_line_fit() {
    // With two-point initialisation then α(n), β(n) at the n-th measurement,
    // the real filter's (x_s, v_s) is the least-squares line through all n
    // points, evaluated at the last one.
    let dt = 0.9;
    let z = |k: usize| 3.0 + 2.0 * k as f64 * dt + 5.0 * (1.7 * k as f64).sin();
    let mut f = AlphaBeta::<f64>::new();
    let unused = Gains::<f64>::alpha_beta(0.5, 0.1).unwrap();
    f.update(z(1), dt, &unused).unwrap();
    f.update(z(2), dt, &unused).unwrap();
    for n in 3..=300usize {
        f.update(z(n), dt, &least_squares_gains(n as u32).unwrap())
            .unwrap();
        let count = n as f64;
        let ts: Vec<f64> = (1..=n).map(|k| k as f64 * dt).collect();
        let zs: Vec<f64> = (1..=n).map(z).collect();
        let mean_t = ts.iter().sum::<f64>() / count;
        let mean_z = zs.iter().sum::<f64>() / count;
        let sxy: f64 = ts
            .iter()
            .zip(&zs)
            .map(|(t, z)| (t - mean_t) * (z - mean_z))
            .sum();
        let sxx: f64 = ts.iter().map(|t| (t - mean_t) * (t - mean_t)).sum();
        let slope = sxy / sxx;
        let fitted_last = mean_z + slope * (ts[n - 1] - mean_t);
        assert_abs(f.velocity(), slope, 1e-11);
        assert_abs(f.position(), fitted_last, 1e-10);
    }
}

#[test]
fn kalata_beta_golden_and_li_et_al_eq_8() {
    // Eq. 7: α = 0.36: 2(2 − 0.36) − 4·0.8 = 3.28 − 3.2 = 0.08 = 2(1 − 0.8)².
    assert_abs(kalata_beta(0.36).unwrap(), 0.08, 1e-16);
    // α = 0.75: 2·1.25 − 4·0.5 = 0.5.
    assert_abs(kalata_beta(0.75).unwrap(), 0.5, 1e-16);
    // α = 1: 2 — and (1, 2) sits on the stability boundary 2α + β = 4.
    assert_eq!(kalata_beta(1.0).unwrap(), 2.0);
    assert_eq!(
        Gains::<f64>::alpha_beta(1.0, 2.0),
        Err(GainError::BetaTooLarge)
    );
    // Eq. 8 at k = 3: 1 − α(3) = 2·1/(3·4) = 1/6, β = 2(1 − √(1/6))²
    // = 2(1 − 0.4082482904638631)² = 0.7003401714778813.
    let alpha3 = least_squares_gains(3).unwrap().alpha();
    assert_abs(kalata_beta(alpha3).unwrap(), 0.7003401714778813, 1e-15);
    // Eq. 8 = eq. 7 ∘ eq. 4 for every k ≥ 3.
    for k in 3..200u32 {
        let kf = k as f64;
        let eq8 = 2.0 * (1.0 - ((kf - 1.0) * (kf - 2.0) / (kf * (kf + 1.0))).sqrt()).powi(2);
        let alpha = least_squares_gains(k).unwrap().alpha();
        assert_close(kalata_beta(alpha).unwrap(), eq8, 1e-12);
        // The two printed forms of eq. 7 agree.
        let first_form = 2.0 * (2.0 - alpha) - 4.0 * (1.0 - alpha).sqrt();
        assert_close(kalata_beta(alpha).unwrap(), first_form, 1e-10);
    }
    // "β = 2 when k = 1, 2": eq. 4 gives α(1) = 2·1/2 = 1 and α(2) = 2·3/6 = 1.
    for alpha in [0.0, 1.0001, -1.0] {
        assert_eq!(kalata_beta(alpha), Err(DesignError::AlphaOutOfRange));
    }
}

#[test]
fn kalata_beta_is_twice_critical_damping_so_its_poles_are_complex() {
    for alpha in [0.05, 0.3, 0.6, 0.95] {
        let beta = kalata_beta(alpha).unwrap();
        assert_close(
            beta,
            2.0 * critically_damped_betas(alpha).unwrap().monotone,
            1e-15,
        );
        let [z1, z2] = alpha_beta_poles(alpha, beta).unwrap();
        assert!(z1.im > 0.0 && z2.im < 0.0);
        assert_close(z1.modulus(), (1.0 - alpha).sqrt(), 1e-14);
    }
}

#[test]
fn tracking_index_and_kalata_gains_golden() {
    // Λ = σ_w T²/σ_v = 2·0.25/5 = 0.1; r = (4 + 0.1 − √(0.8 + 0.01))/4
    // = (4.1 − 0.9)/4 = 0.8, α = 1 − 0.64 = 0.36, β = 2(1 − 0.8)² = 0.08.
    let lambda = tracking_index(2.0, 5.0, 0.5).unwrap();
    assert_abs(lambda, 0.1, 1e-17);
    let g = kalata_gains(lambda).unwrap();
    assert_abs(g.alpha(), 0.36, 1e-15);
    assert_abs(g.beta(), 0.08, 1e-16);
    // Λ = 1: r = (5 − √9)/4 = 0.5, α = 0.75, β = 2·0.25 = 0.5.
    let g = kalata_gains(1.0).unwrap();
    assert_abs(g.alpha(), 0.75, 1e-15);
    assert_abs(g.beta(), 0.5, 1e-15);
    // Λ = 8/3: Λ² + 8Λ = 64/9 + 64/3 = 256/9, r = (4 + 8/3 − 16/3)/4 = 1/3,
    // α = 8/9, β = 2·(2/3)² = 8/9.
    let g = kalata_gains(8.0 / 3.0).unwrap();
    assert_abs(g.alpha(), 8.0 / 9.0, 1e-15);
    assert_abs(g.beta(), 8.0 / 9.0, 1e-15);
    // Inverse: Λ = β/√(1 − α) = 0.08/0.8 = 0.1.
    assert_abs(tracking_index_of_gains(0.36, 0.08).unwrap(), 0.1, 1e-16);

    // The identity is Λ² = β²/(1 − α), not α²/(1 − α): at Λ = 0.1,
    // β²/(1 − α) = 0.0064/0.64 = 0.01 = Λ², but α²/(1 − α) = 0.1296/0.64 = 0.2025.
    // (The α form holds only by accident where α = β, i.e. at Λ = 8/3.)
    // (Up to Λ = 1e3: beyond, 1 − α ≈ 4/Λ² loses too many digits in f64 for
    // the test itself to recompute Λ from α.)
    for lambda in [1e-4, 0.01, 0.1, 0.48, 1.0, 8.0 / 3.0, 10.0, 1e3] {
        let g = kalata_gains(lambda).unwrap();
        let (alpha, beta) = (g.alpha(), g.beta());
        assert_close(beta * beta / (1.0 - alpha), lambda * lambda, 1e-9);
        assert_close(beta, kalata_beta(alpha).unwrap(), 1e-9);
        assert_close(tracking_index_of_gains(alpha, beta).unwrap(), lambda, 1e-9);
        let alpha_form_holds =
            (alpha * alpha / (1.0 - alpha) - lambda * lambda).abs() < 1e-9 * lambda * lambda;
        assert_eq!(alpha_form_holds, lambda == 8.0 / 3.0, "lambda {lambda}");
    }

    // Extreme indices still give valid gains, approaching (0, 0) and (1, 2).
    let g = kalata_gains(1e-12).unwrap();
    assert!(g.alpha() > 0.0 && g.alpha() < 2e-6 && g.beta() > 0.0);
    let g = kalata_gains(1e6).unwrap();
    assert!(g.alpha() < 1.0 && g.alpha() > 1.0 - 1e-11 && 2.0 - g.beta() < 1e-5);
    assert!(is_stable_alpha_beta(g.alpha(), g.beta()));
    assert_eq!(tracking_index(0.0, 5.0, 1.0), Err(DesignError::NotPositive));
    assert_eq!(
        tracking_index(1.0, -5.0, 1.0),
        Err(DesignError::NotPositive)
    );
    assert_eq!(
        tracking_index(1.0, 5.0, f64::NAN),
        Err(DesignError::NotFinite)
    );
    assert_eq!(kalata_gains(0.0), Err(DesignError::NotPositive));
    assert_eq!(kalata_gains(f64::INFINITY), Err(DesignError::NotFinite));
    assert_eq!(
        tracking_index_of_gains(1.0, 2.0),
        Err(DesignError::AlphaOutOfRange)
    );
}

#[test]
fn kalata_gains_are_the_steady_state_kalman_gains() {
    // Kalman filter for x_{k+1} = F x_k + Γw_k, F = [[1, T], [0, 1]],
    // Γ = [T²/2, T] (piecewise-constant white acceleration, var σ_w²), z = x + v
    // (var σ_v²). Iterate the Riccati equation to steady state; the gain
    // K = [α, β/T] must be Kalata's.
    for (sigma_w, sigma_v, dt) in [
        (1.0f64, 10.0, 1.0f64),
        (3.0, 10.0, 2.0),
        (0.5, 50.0, 4.0),
        (10.0, 1.0, 1.0),
        (0.2, 30.0, 0.5),
    ] {
        let q = sigma_w * sigma_w;
        let r = sigma_v * sigma_v;
        let process = [
            [q * dt.powi(4) / 4.0, q * dt.powi(3) / 2.0],
            [q * dt.powi(3) / 2.0, q * dt * dt],
        ];
        let mut p = [[1e6, 0.0], [0.0, 1e6]];
        let mut k = [0.0, 0.0];
        for _ in 0..20_000 {
            let s = p[0][0] + r;
            k = [p[0][0] / s, p[1][0] / s];
            let u = [
                [p[0][0] - k[0] * p[0][0], p[0][1] - k[0] * p[0][1]],
                [p[1][0] - k[1] * p[0][0], p[1][1] - k[1] * p[0][1]],
            ];
            // P = F U Fᵀ + Q
            let fu = [
                [u[0][0] + dt * u[1][0], u[0][1] + dt * u[1][1]],
                [u[1][0], u[1][1]],
            ];
            p = [
                [
                    fu[0][0] + dt * fu[0][1] + process[0][0],
                    fu[0][1] + process[0][1],
                ],
                [
                    fu[1][0] + dt * fu[1][1] + process[1][0],
                    fu[1][1] + process[1][1],
                ],
            ];
        }
        let g = kalata_gains(tracking_index(sigma_w, sigma_v, dt).unwrap()).unwrap();
        assert_close(g.alpha(), k[0], 1e-9);
        assert_close(g.beta(), k[1] * dt, 1e-9);
    }
}

// ---------------------------------------------------------------------------
// Noise ratios

#[test]
fn alpha_beta_noise_ratios_golden() {
    // Eq. 13 at (0.5, 0.2): (2·0.25 + 0.1 + 0.4)/(0.5·(4 − 0.2 − 1)) = 1/1.4.
    assert_abs(
        alpha_beta_predicted_position_noise_ratio(0.5, 0.2).unwrap(),
        1.0 / 1.4,
        1e-16,
    );
    // Smoothed position: (0.5 + 0.4 − 0.3)/1.4 = 0.6/1.4.
    assert_abs(
        alpha_beta_smoothed_position_noise_ratio(0.5, 0.2).unwrap(),
        0.6 / 1.4,
        1e-16,
    );
    // Velocity at T = 0.7: 2·0.04/(0.49·0.5·2.8) = 0.08/0.686.
    assert_abs(
        alpha_beta_smoothed_velocity_noise_ratio(0.5, 0.2, 0.7).unwrap(),
        0.08 / 0.686,
        1e-16,
    );
    // (1, 1), dead-beat: (2 + 1 + 2)/(1·1) = 5; (2 + 2 − 3)/1 = 1; 2/(T²) at T = 1.
    assert_abs(
        alpha_beta_predicted_position_noise_ratio(1.0, 1.0).unwrap(),
        5.0,
        1e-15,
    );
    assert_abs(
        alpha_beta_smoothed_position_noise_ratio(1.0, 1.0).unwrap(),
        1.0,
        1e-15,
    );
    assert_abs(
        alpha_beta_smoothed_velocity_noise_ratio(1.0, 1.0, 1.0).unwrap(),
        2.0,
        1e-15,
    );
    assert_eq!(
        alpha_beta_predicted_position_noise_ratio(1.0, 2.0),
        Err(DesignError::Unstable(GainError::BetaTooLarge))
    );
    assert_eq!(
        alpha_beta_smoothed_velocity_noise_ratio(0.5, 0.2, 0.0),
        Err(DesignError::NotPositive)
    );
}

#[test]
fn alpha_beta_noise_ratios_equal_the_filters_impulse_response_energy() {
    // White noise of variance σ² through a linear filter comes out with
    // variance σ²·Σh²; the real filter's impulse responses give Σh².
    let dt = 0.7;
    let samples = stable_alpha_beta_samples();
    assert!(samples.len() > 300);
    for (alpha, beta) in samples {
        let (predicted, smoothed, velocity) = alpha_beta_impulse_sums(alpha, beta, dt, 6000);
        assert_close(
            alpha_beta_predicted_position_noise_ratio(alpha, beta).unwrap(),
            predicted,
            1e-9,
        );
        assert_close(
            alpha_beta_smoothed_position_noise_ratio(alpha, beta).unwrap(),
            smoothed,
            1e-9,
        );
        assert_close(
            alpha_beta_smoothed_velocity_noise_ratio(alpha, beta, dt).unwrap(),
            velocity,
            1e-9,
        );
    }
}

#[test]
fn alpha_beta_gamma_noise_ratio_golden() {
    // Direct form at (0.5, 0.2, 0.04): numerator 8·0.25·0.2 + 2·0.25·0.04
    // + 4·0.5·0.04 + 0.5·0.2·0.04 − 4·0.5·0.04 + 8·0.04
    // = 0.4 + 0.02 + 0.08 + 0.004 − 0.08 + 0.32 = 0.744; denominator
    // (4 − 1 − 0.2)(0.4 + 0.02 − 0.08) = 2.8·0.34 = 0.952; ρ² = 0.7815126050420168.
    assert_abs(
        alpha_beta_gamma_predicted_position_noise_ratio(0.5, 0.2, 0.04).unwrap(),
        0.7815126050420168,
        1e-15,
    );
    // Eq. 10 (corrected) at (a, b, c) = (0.5, 0.2, 0.5), by hand:
    // k11 = 2 + 0.25 − 0.1 + 0.05 − 1.5 = 0.7; k12 = 0.05 + 0.02 − 0.6 − 0.25 + 4 = 3.22;
    // k13 = 1.5 − 0.04 − 0.2 + 2 − 0.08 + 0.7 = 3.88; k1 = 0.175 + 1.61 + 3.88 = 5.665;
    // k2 = (0.2 + 1 − 4)(0.125 − 0.25 − 0.25 − 0.4 + 0.1 + 1) = −2.8·0.325 = −0.91;
    // numerator −(0.2 + 0.04 + 0.16) − 1.5·5.665 = −8.8975;
    // denominator 2·0.5·(−2.8)·0.2 + 0.5·1.5·(−0.91) = −0.56 − 0.6825 = −1.2425;
    // ρ² = 8.8975/1.2425 = 7.160965794768613.
    let abc = AbcParameters {
        a: 0.5,
        b: 0.2,
        c: 0.5,
    };
    assert_abs(
        abc_predicted_position_noise_ratio(abc).unwrap(),
        7.160965794768613,
        1e-14,
    );
    // The same point as (α, β, γ) = (1.25, 0.8, 0.6): numerator 10 + 1.875 + 3.2
    // + 0.6 − 3 + 5.12 = 17.795, denominator 0.7·(4 + 0.75 − 1.2) = 2.485.
    assert_abs(
        alpha_beta_gamma_predicted_position_noise_ratio(1.25, 0.8, 0.6).unwrap(),
        17.795 / 2.485,
        1e-14,
    );
    // γ = 0 reduces to eq. 13.
    assert_close(
        alpha_beta_gamma_predicted_position_noise_ratio(0.5, 0.2, 1e-300).unwrap_or(f64::NAN),
        1.0 / 1.4,
        1e-12,
    );
    assert_eq!(
        alpha_beta_gamma_predicted_position_noise_ratio(0.5, 0.2, 0.27),
        Err(DesignError::Unstable(GainError::GammaTooLarge))
    );
}

/// Tenne & Singh eq. 10 exactly as printed (with the stray 4b).
fn printed_eq_10(AbcParameters { a, b, c }: AbcParameters) -> f64 {
    let k11 = 4.0 * a + 2.0 * a.powi(3) - a * b + b * a * a - 6.0 * a * a;
    let k12 = b * a * a + a * b * b - 6.0 * a * b - 2.0 * a.powi(3) + 8.0 * a;
    let k13 = 6.0 * a * a - 2.0 * a * b * b - 4.0 * b * a * a + 4.0 * a - 2.0 * b * b + 7.0 * a * b;
    let k1 = k11 * c * c + k12 * c + k13;
    let k2 = (b + 2.0 * a - 4.0) * (c * c * a - c * a - c * c - 2.0 * b + b * c + 1.0);
    (-(4.0 * b * a * a + 2.0 * a * b * b + 4.0 * b * b) - 4.0 * b * (1.0 + c) * k1)
        / (2.0 * a * (b + 2.0 * a - 4.0) * b + a * (1.0 + c) * k2)
}

#[test]
fn alpha_beta_gamma_noise_ratio_equals_the_filters_impulse_response_energy() {
    let samples = stable_alpha_beta_gamma_samples();
    assert!(samples.len() > 300, "{}", samples.len());
    let mut printed_misses = 0;
    for &(alpha, beta, gamma) in &samples {
        let energy = alpha_beta_gamma_impulse_sum(alpha, beta, gamma, 6000);
        assert_close(
            alpha_beta_gamma_predicted_position_noise_ratio(alpha, beta, gamma).unwrap(),
            energy,
            1e-9,
        );
        let abc = alpha_beta_gamma_to_abc(alpha, beta, gamma).unwrap();
        assert_close(
            abc_predicted_position_noise_ratio(abc).unwrap(),
            energy,
            1e-8,
        );
        if (printed_eq_10(abc) - energy).abs() > 1e-3 * energy {
            printed_misses += 1;
        }
    }
    // The printed eq. 10 is wrong almost everywhere (it is right only where
    // 4b = 1 or on the αβ plane c = −1).
    assert!(
        printed_misses > samples.len() * 9 / 10,
        "{printed_misses}/{}",
        samples.len()
    );
    // The documented example: printed 5.793 against the filter's 7.161.
    let abc = AbcParameters {
        a: 0.5,
        b: 0.2,
        c: 0.5,
    };
    assert_abs(printed_eq_10(abc), 7.198 / 1.2425, 1e-12);
    assert_close(
        alpha_beta_gamma_impulse_sum(1.25, 0.8, 0.6, 6000),
        7.160965794768613,
        1e-9,
    );
}

// ---------------------------------------------------------------------------
// The a-b-c transform

#[test]
fn abc_transform_golden_both_ways() {
    // (0.5, 0.2, 0.5) → α = 1 + 0.5·(1 − 0.5) = 1.25, β = 0.5·1.5 + 0.2·0.5/2 = 0.8,
    // γ = 2·0.2·1.5 = 0.6.
    let g = abc_to_alpha_beta_gamma(AbcParameters {
        a: 0.5,
        b: 0.2,
        c: 0.5,
    })
    .unwrap();
    assert_abs(g.alpha, 1.25, 1e-15);
    assert_abs(g.beta, 0.8, 1e-15);
    assert_abs(g.gamma, 0.6, 1e-15);
    // Back: the only real pole is −0.5, so c = 0.5 and a, b as above.
    let abc = alpha_beta_gamma_to_abc(1.25, 0.8, 0.6).unwrap();
    assert_abs(abc.a, 0.5, 1e-14);
    assert_abs(abc.b, 0.2, 1e-14);
    assert_abs(abc.c, 0.5, 1e-14);
    // c = −1 is the αβ filter: α = a, β = b, γ = 0.
    let g = abc_to_alpha_beta_gamma(AbcParameters {
        a: 0.7,
        b: 0.3,
        c: -1.0,
    })
    .unwrap();
    assert_eq!((g.alpha, g.beta, g.gamma), (0.7, 0.3, 0.0));
    let abc = alpha_beta_gamma_to_abc(0.7, 0.3, 0.0).unwrap();
    assert_abs(abc.c, -1.0, 1e-15);
    assert_abs(abc.a, 0.7, 1e-15);
    assert_abs(abc.b, 0.3, 1e-15);

    // Three real poles (0.95, 0.525, 0.1): poles 0.8873, 0.5, 0.1127 (see the
    // poles test). The inverse takes the largest, c = −0.8872983346207417;
    // the quadratic (z − 0.5)(z − (1 − √0.6)/2) has constant (1 − √0.6)/4
    // = 0.05635083268962915, so a = 0.9436491673103709 and
    // b = −(0.5 + 0.1127016653792583) + 2 − a = 0.4436491673103709.
    let abc = alpha_beta_gamma_to_abc(0.95, 0.525, 0.1).unwrap();
    assert_abs(abc.c, -0.8872983346207417, 1e-14);
    assert_abs(abc.a, 0.9436491673103709, 1e-14);
    assert_abs(abc.b, 0.4436491673103709, 1e-14);
    // The paper's own factorisation (0.9, 0.1, −0.5) is as valid; every
    // metric agrees between the two.
    let other = AbcParameters {
        a: 0.9,
        b: 0.1,
        c: -0.5,
    };
    for candidate in [abc, other] {
        let g = abc_to_alpha_beta_gamma(candidate).unwrap();
        assert_abs(g.alpha, 0.95, 1e-14);
        assert_abs(g.beta, 0.525, 1e-14);
        assert_abs(g.gamma, 0.1, 1e-14);
    }
    assert_close(
        abc_predicted_position_noise_ratio(abc).unwrap(),
        abc_predicted_position_noise_ratio(other).unwrap(),
        1e-12,
    );
    assert_close(
        abc_transient_cost(abc, 0.5, 2.0, 1.0).unwrap(),
        abc_transient_cost(other, 0.5, 2.0, 1.0).unwrap(),
        1e-12,
    );
}

#[test]
fn abc_transform_round_trips() {
    for (alpha, beta, gamma) in stable_alpha_beta_gamma_samples() {
        let abc = alpha_beta_gamma_to_abc(alpha, beta, gamma).unwrap();
        let back = abc_to_alpha_beta_gamma(abc).unwrap();
        assert_abs(back.alpha, alpha, 1e-12);
        assert_abs(back.beta, beta, 1e-12);
        assert_abs(back.gamma, gamma, 1e-12);
        // −c is a pole and the quadratic factor is the αβ-like one (eq. 11).
        let poly = alpha_beta_gamma_characteristic_polynomial(alpha, beta, gamma).unwrap();
        assert!(
            polynomial_modulus_at(
                &poly,
                Pole {
                    re: -abc.c,
                    im: 0.0
                }
            ) < 1e-12
        );
        for p in alpha_beta_poles(abc.a, abc.b).unwrap() {
            assert!(polynomial_modulus_at(&poly, p) < 1e-10);
        }
    }
}

// ---------------------------------------------------------------------------
// Steady-state errors

#[test]
fn acceleration_lag_golden() {
    // Eq. 19: a T²/β = 2·0.49/0.2 = 4.9.
    assert_abs(
        alpha_beta_acceleration_lag(0.5, 0.2, 2.0, 0.7).unwrap(),
        4.9,
        1e-15,
    );
    // −9.81·4/0.5 = −78.48.
    assert_abs(
        alpha_beta_acceleration_lag(0.8, 0.5, -9.81, 2.0).unwrap(),
        -78.48,
        1e-13,
    );
    assert_eq!(
        alpha_beta_acceleration_lag(0.5, -0.2, 2.0, 0.7),
        Err(DesignError::Unstable(GainError::BetaNotPositive))
    );
    assert_eq!(
        alpha_beta_acceleration_lag(0.5, 0.2, 2.0, -1.0),
        Err(DesignError::NotPositive)
    );
}

#[test]
fn acceleration_lag_is_where_the_filters_residual_settles() {
    for (alpha, beta) in stable_alpha_beta_samples().into_iter().step_by(7) {
        for (acceleration, dt) in [(2.0, 0.7), (-9.81, 2.0), (0.3, 5.0)] {
            let gains = Gains::<f64>::alpha_beta(alpha, beta).unwrap();
            let mut f = AlphaBeta::<f64>::new();
            let mut last = 0.0;
            // 1200 scans: the transient has decayed by 0.97^1200 < 1e-15.
            let steps = 1200;
            for k in 0..steps {
                let t = k as f64 * dt;
                if let UpdateOutcome::Filtered(i) =
                    f.update(0.5 * acceleration * t * t, dt, &gains).unwrap()
                {
                    last = i.residual;
                }
            }
            // The residual is the difference of positions as large as
            // ½a(1200T)², so it cannot be better than some ulps of those
            // (rounding errors are amplified by the filter's noise gain):
            // allow 1e-14 of the largest position.
            let largest = 0.5 * acceleration.abs() * (steps as f64 * dt).powi(2);
            let lag = alpha_beta_acceleration_lag(alpha, beta, acceleration, dt).unwrap();
            assert_abs(last, lag, 1e-14 * largest + 1e-12 * lag.abs());
        }
    }
    // The αβγ filter's residual vanishes (Tenne & Singh, after eq. 19).
    for (alpha, beta, gamma) in stable_alpha_beta_gamma_samples().into_iter().step_by(11) {
        let gains = Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma).unwrap();
        let mut f = AlphaBetaGamma::<f64>::new();
        let mut last = f64::NAN;
        let steps = 1200;
        for k in 0..steps {
            let t = k as f64 * 0.7;
            if let UpdateOutcome::Filtered(i) = f.update(t * t, 0.7, &gains).unwrap() {
                last = i.residual;
            }
        }
        // Zero up to the rounding floor of the positions (see above); the
        // αβ filter's lag for this input would be 2·0.49/β > 0.25.
        let largest = (steps as f64 * 0.7).powi(2);
        assert!(
            last.abs() < 1e-14 * largest,
            "{alpha} {beta} {gamma}: {last}"
        );
    }
}

#[test]
fn circular_error_golden() {
    // Eq. 17 at ωT = π/2: cos = 0, sin = 1, sin²(π/4) = 0.5:
    // e = 4R·0.5/√((α + β − 2)² + α²) = 200/√(1.69 + 0.25) = 200/√1.94
    // = 143.59163172354764 for R = 100, α = 0.5, β = 0.2.
    let quarter = core::f64::consts::FRAC_PI_2;
    assert_abs(
        alpha_beta_circular_error(0.5, 0.2, 100.0, quarter, 1.0).unwrap(),
        143.59163172354764,
        1e-12,
    );
    // ωT = π/3: cos = 0.5, sin² = 0.75, sin²(π/6) = 0.25:
    // e = 100/√((0.75 + 0.5 + 0.2 − 2)² + 0.75·0.25) = 100/√(0.3025 + 0.1875) = 100/0.7.
    let sixth = core::f64::consts::FRAC_PI_3;
    assert_abs(
        alpha_beta_circular_error(0.5, 0.2, 100.0, sixth / 2.0, 2.0).unwrap(),
        100.0 / 0.7,
        1e-12,
    );
    // Eq. 16 (corrected) at ωT = π/3, (0.5, 0.2, 0.04), R = 100: numerator
    // 4·100·0.125 = 50; under the root 0.25·(0.3025 + 0.1875)
    // + 0.04·(0.04·1.5/32 − 0.125·0.75) = 0.1225 − 0.003675 = 0.118825;
    // e = 50/0.3447100230628637 = 145.04945216194557.
    assert_abs(
        alpha_beta_gamma_circular_error(0.5, 0.2, 0.04, 100.0, sixth, 1.0).unwrap(),
        145.04945216194557,
        1e-11,
    );
    // At γ → 0 eq. 16 reduces to eq. 17.
    assert_close(
        alpha_beta_gamma_circular_error(0.5, 0.2, 1e-300, 100.0, sixth, 1.0).unwrap(),
        100.0 / 0.7,
        1e-12,
    );
    // Small ωT: eq. 17 → Rω²T²/β, eq. 19 with the centripetal acceleration.
    let (r, w, t) = (5000.0, 1e-4, 1.0);
    assert_close(
        alpha_beta_circular_error(0.5, 0.2, r, w, t).unwrap(),
        alpha_beta_acceleration_lag(0.5, 0.2, r * w * w, t).unwrap(),
        1e-6,
    );
    // A full turn per scan looks stationary: no error.
    assert_abs(
        alpha_beta_circular_error(0.5, 0.2, 100.0, 2.0 * core::f64::consts::PI, 1.0).unwrap(),
        0.0,
        1e-11,
    );
    assert_eq!(
        alpha_beta_circular_error(0.5, 0.2, -1.0, 0.1, 1.0),
        Err(DesignError::NotPositive)
    );
}

/// The steady residual magnitude √(e_x² + e_y²) of a real 2-D filter on a
/// circle, over its last 200 scans: (min, max).
fn simulated_circle<const ORDER: usize>(
    gains: &Gains<f64>,
    radius: f64,
    omega: f64,
    dt: f64,
) -> (f64, f64) {
    let mut f = Cartesian::<f64, ORDER, 2>::new();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    let steps = 3000;
    for k in 0..steps {
        let angle = omega * dt * k as f64;
        let out = f
            .update([radius * angle.cos(), radius * angle.sin()], dt, gains)
            .unwrap();
        if k >= steps - 200 {
            let [ex, ey] = residual(out);
            let m = ex.hypot(ey);
            lo = lo.min(m);
            hi = hi.max(m);
        }
    }
    (lo, hi)
}

/// Eq. 16 as printed in our copy: the root ends before the γ term, and
/// α²sin²ωT is not multiplied by sin²(ωT/2).
fn printed_eq_16(alpha: f64, beta: f64, gamma: f64, radius: f64, theta: f64) -> f64 {
    let s = (theta / 2.0).sin();
    let p = (2.0 - alpha) * theta.cos() + alpha + beta - 2.0;
    4.0 * radius * s.powi(3)
        / ((s * s * p * p + alpha * alpha * theta.sin().powi(2)).sqrt()
            + gamma * (gamma / 32.0 * (theta.cos() + 1.0) - alpha / 4.0 * theta.sin().powi(2)))
}

#[test]
fn circular_error_is_the_filters_steady_residual_on_a_circle() {
    for (alpha, beta) in stable_alpha_beta_samples().into_iter().step_by(5) {
        let gains = Gains::<f64>::alpha_beta(alpha, beta).unwrap();
        for (radius, omega, dt) in [(45.0, 0.034, 1.0), (2000.0, 0.1, 2.0), (500.0, 0.5, 1.5)] {
            let expected = alpha_beta_circular_error(alpha, beta, radius, omega, dt).unwrap();
            let (lo, hi) = simulated_circle::<2>(&gains, radius, omega, dt);
            assert_close(lo, expected, 1e-9);
            assert_close(hi, expected, 1e-9);
        }
    }
    let mut printed_misses = 0;
    let mut cases = 0;
    for (alpha, beta, gamma) in stable_alpha_beta_gamma_samples().into_iter().step_by(5) {
        let gains = Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma).unwrap();
        for (radius, omega, dt) in [(45.0, 0.034, 1.0), (2000.0, 0.1, 2.0), (500.0, 0.5, 1.5)] {
            let expected =
                alpha_beta_gamma_circular_error(alpha, beta, gamma, radius, omega, dt).unwrap();
            let (lo, hi) = simulated_circle::<3>(&gains, radius, omega, dt);
            assert_close(lo, expected, 1e-8);
            assert_close(hi, expected, 1e-8);
            cases += 1;
            if (printed_eq_16(alpha, beta, gamma, radius, omega * dt) - expected).abs()
                > 1e-3 * expected
            {
                printed_misses += 1;
            }
        }
    }
    // The printed form is a different function: it agrees only by accident
    // (3 of 813 cases here, within 0.1 %).
    assert!(
        printed_misses > cases * 99 / 100,
        "{printed_misses}/{cases}"
    );
    // The golden point of `circular_error_golden`: printed
    // 50/(√(0.075625 + 0.1875) − 0.003675) = 98.18 against 145.05; and at
    // γ = 0 it gives 50/√0.263125 = 97.47, not eq. 17's 100/0.7.
    let sixth = core::f64::consts::FRAC_PI_3;
    assert_abs(printed_eq_16(0.5, 0.2, 0.04, 100.0, sixth), 98.18, 0.01);
    assert_abs(printed_eq_16(0.5, 0.2, 0.0, 100.0, sixth), 97.47, 0.01);
}

// ---------------------------------------------------------------------------
// Transient costs

#[test]
fn alpha_beta_transient_cost_golden() {
    // Eq. 22 at α = 0.5, β = 0.2, T = 0.7 (T³ = 0.343, T⁴ = 0.2401, T⁵ = 0.16807):
    // velocity 3 alone: 9·0.343·1.5/(0.5·0.2·2.8) = 4.6305/0.28 = 16.5375;
    assert_abs(
        alpha_beta_transient_cost(0.5, 0.2, 0.7, 3.0, 0.0).unwrap(),
        16.5375,
        1e-12,
    );
    // acceleration 2 alone: 4·0.16807·(0.4 + 0.1 + 0.5)/(4·0.5·0.008) = 42.0175;
    assert_abs(
        alpha_beta_transient_cost(0.5, 0.2, 0.7, 0.0, 2.0).unwrap(),
        42.0175,
        1e-12,
    );
    // both: cross term −3·2·0.2401/0.04 = −36.015, total 16.5375 + 42.0175 − 36.015 = 22.54.
    assert_abs(
        alpha_beta_transient_cost(0.5, 0.2, 0.7, 3.0, 2.0).unwrap(),
        22.54,
        1e-12,
    );
}

/// Eq. 22 as printed (cross term +v·a·T⁴/β²).
fn printed_eq_22(alpha: f64, beta: f64, dt: f64, v: f64, a: f64) -> f64 {
    0.25 * a * a * dt.powi(5) * (2.0 * beta + alpha * beta + 2.0 * alpha * alpha)
        / (alpha * beta.powi(3))
        + v * v * dt.powi(3) * (alpha - 2.0) / (alpha * beta * (2.0 * alpha + beta - 4.0))
        + v * a * dt.powi(4) / (beta * beta)
}

#[test]
fn alpha_beta_transient_cost_is_the_filters_summed_squared_transient() {
    for (alpha, beta) in stable_alpha_beta_samples().into_iter().step_by(3) {
        let gains = Gains::<f64>::alpha_beta(alpha, beta).unwrap();
        for (dt, v, a) in [
            (0.7, 3.0, 0.0),
            (0.7, 0.0, 2.0),
            (0.7, 3.0, 2.0),
            (2.0, -40.0, 5.0),
            (1.0, 1.0, -1.5),
        ] {
            let lag = alpha_beta_acceleration_lag(alpha, beta, a, dt).unwrap();
            let simulated = simulated_transient_cost::<2>(&gains, dt, v, a, lag, 4000);
            let formula = alpha_beta_transient_cost(alpha, beta, dt, v, a).unwrap();
            assert_close(formula, simulated, 1e-9);
            // The printed sign is off by exactly 2vaT⁴/β².
            let printed = printed_eq_22(alpha, beta, dt, v, a);
            assert_abs(
                printed - simulated,
                2.0 * v * a * dt.powi(4) / (beta * beta),
                1e-9 * (simulated.abs() + printed.abs()),
            );
        }
    }
    // The documented example: printed 94.57 against the filter's 22.54.
    let gains = Gains::<f64>::alpha_beta(0.5, 0.2).unwrap();
    assert_close(
        simulated_transient_cost::<2>(&gains, 0.7, 3.0, 2.0, 4.9, 4000),
        22.54,
        1e-9,
    );
    assert_close(printed_eq_22(0.5, 0.2, 0.7, 3.0, 2.0), 94.57, 1e-12);
}

#[test]
fn alpha_beta_gamma_transient_cost_golden() {
    // (0.5, 0.2, 0.04), T = 1: margin 4αβ − γ(2 − α) = 0.4 − 0.06 = 0.34;
    // velocity 1: 4·1.5/(2.8·0.34) = 6/0.952 = 6.302521008403362;
    // acceleration 1: 4·0.5/(0.04·0.34) = 2/0.0136 = 147.05882352941177.
    assert_abs(
        alpha_beta_gamma_transient_cost(0.5, 0.2, 0.04, 1.0, 1.0, 0.0).unwrap(),
        6.302521008403362,
        1e-13,
    );
    assert_abs(
        alpha_beta_gamma_transient_cost(0.5, 0.2, 0.04, 1.0, 0.0, 1.0).unwrap(),
        147.05882352941177,
        1e-12,
    );
    assert_abs(
        alpha_beta_gamma_transient_cost(0.5, 0.2, 0.04, 1.0, 1.0, 1.0).unwrap(),
        6.302521008403362 + 147.05882352941177,
        1e-12,
    );
    // Eq. 21 (corrected) at (a, b, c) = (0.5, 0.2, 0.5), T = v = a_s = 1:
    // Q = 0.5·(0.5 + 0.2 + 0.25) − 1.5² = 0.475 − 2.25 = −1.775;
    // velocity: 2(0.5 − 0.25 − 1)/(0.5·(−2.8)·(−0.5)·(−1.775)) = −1.5/−1.2425 = 1.2072434607645877;
    // acceleration: 0.5·(0.5·(−0.5) − 1)/(0.5·0.2·1.5·(−1.775)) = −0.625/−0.26625 = 2.347417840375587.
    let abc = AbcParameters {
        a: 0.5,
        b: 0.2,
        c: 0.5,
    };
    assert_abs(
        abc_transient_cost(abc, 1.0, 1.0, 0.0).unwrap(),
        1.2072434607645877,
        1e-14,
    );
    assert_abs(
        abc_transient_cost(abc, 1.0, 0.0, 1.0).unwrap(),
        2.347417840375587,
        1e-14,
    );
    // Same point in α, β, γ = (1.25, 0.8, 0.6): margin 4 − 0.45 = 3.55,
    // 4·0.75/(0.7·3.55) = 3/2.485 and 4·1.25/(0.6·3.55) = 5/2.13.
    assert_abs(
        alpha_beta_gamma_transient_cost(1.25, 0.8, 0.6, 1.0, 1.0, 1.0).unwrap(),
        3.0 / 2.485 + 5.0 / 2.13,
        1e-14,
    );
}

/// Eq. 21 as printed (with (1 − c)²).
fn printed_eq_21(AbcParameters { a, b, c }: AbcParameters, t: f64, v: f64, acc: f64) -> f64 {
    let q = c * (a + b + c * a) - (1.0 - c).powi(2);
    2.0 * (c - c * a - 1.0) * t.powi(3) * v * v / (a * (2.0 * a + b - 4.0) * (c - 1.0) * q)
        + 0.5 * acc * acc * t.powi(5) * (c * (a - 1.0) - 1.0) / (a * b * (1.0 + c) * q)
}

#[test]
fn alpha_beta_gamma_transient_cost_is_the_filters_summed_squared_error() {
    let mut printed_misses = 0;
    let mut cases = 0;
    for (alpha, beta, gamma) in stable_alpha_beta_gamma_samples().into_iter().step_by(3) {
        let gains = Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma).unwrap();
        let abc = alpha_beta_gamma_to_abc(alpha, beta, gamma).unwrap();
        for (dt, v, a) in [
            (0.7, 3.0, 0.0),
            (0.7, 0.0, 2.0),
            (0.7, 3.0, 2.0),
            (2.0, -40.0, 5.0),
        ] {
            let simulated = simulated_transient_cost::<3>(&gains, dt, v, a, 0.0, 4000);
            let direct = alpha_beta_gamma_transient_cost(alpha, beta, gamma, dt, v, a).unwrap();
            assert_close(direct, simulated, 1e-9);
            assert_close(abc_transient_cost(abc, dt, v, a).unwrap(), simulated, 1e-8);
            cases += 1;
            if (printed_eq_21(abc, dt, v, a) - simulated).abs() > 1e-3 * simulated {
                printed_misses += 1;
            }
        }
    }
    assert_eq!(printed_misses, cases, "printed eq. 21 should match nowhere");
    // The documented example: printed 0.885 against the filter's 17.878.
    let gains = Gains::<f64>::alpha_beta_gamma(0.5, 0.2, 0.02).unwrap();
    let abc = alpha_beta_gamma_to_abc(0.5, 0.2, 0.02).unwrap();
    let simulated = simulated_transient_cost::<3>(&gains, 0.7, 3.0, 0.0, 0.0, 4000);
    assert_abs(simulated, 17.878, 1e-3);
    assert_abs(printed_eq_21(abc, 0.7, 3.0, 0.0), 0.885, 1e-3);
}

// ---------------------------------------------------------------------------
// Robustness

#[test]
fn no_input_panics_and_every_ok_is_finite() {
    let specials = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        1e-300,
        -1e-300,
        f64::MIN_POSITIVE,
        1e300,
        f64::MAX,
        f64::MIN,
        -1.0,
        0.5,
        1.0,
        1.5,
        2.0,
        4.0,
    ];
    let ok = |r: Result<f64, DesignError>| {
        if let Ok(v) = r {
            assert!(v.is_finite());
        }
    };
    for &x in &specials {
        ok(critically_damped_betas(x).map(|b| b.monotone + b.alternating));
        ok(benedict_bordner_beta(x));
        ok(kalata_beta(x));
        ok(kalata_gains(x).map(|g| g.alpha() + g.beta()));
        for &y in &specials {
            assert_eq!(
                is_stable_alpha_beta(x, y),
                Gains::<f64>::alpha_beta(x, y).is_ok()
            );
            if let Ok(poles) = alpha_beta_poles(x, y) {
                assert!(poles.iter().all(|p| p.re.is_finite() && p.im.is_finite()));
            }
            ok(alpha_beta_spectral_radius(x, y));
            ok(alpha_beta_predicted_position_noise_ratio(x, y));
            ok(alpha_beta_smoothed_position_noise_ratio(x, y));
            ok(tracking_index_of_gains(x, y));
            for &z in &specials {
                if let Ok(poles) = alpha_beta_gamma_poles(x, y, z) {
                    assert!(poles.iter().all(|p| p.re.is_finite() && p.im.is_finite()));
                }
                ok(alpha_beta_gamma_spectral_radius(x, y, z));
                ok(alpha_beta_gamma_predicted_position_noise_ratio(x, y, z));
                ok(alpha_beta_smoothed_velocity_noise_ratio(x, y, z));
                ok(alpha_beta_acceleration_lag(0.5, 0.2, x, y));
                ok(tracking_index(x, y, z));
                ok(alpha_beta_transient_cost(0.5, 0.2, x, y, z));
                ok(alpha_beta_circular_error(0.5, 0.2, x, y, z));
                ok(alpha_beta_gamma_circular_error(0.5, 0.2, 0.04, x, y, z));
                ok(alpha_beta_gamma_transient_cost(0.5, 0.2, 0.04, x, y, z));
                let abc = AbcParameters { a: x, b: y, c: z };
                ok(abc_predicted_position_noise_ratio(abc));
                ok(abc_transient_cost(abc, 1.0, 1.0, 1.0));
                if let Ok(g) = abc_to_alpha_beta_gamma(abc) {
                    assert!(g.alpha.is_finite() && g.beta.is_finite() && g.gamma.is_finite());
                }
                if let Ok(abc) = alpha_beta_gamma_to_abc(x, y, z) {
                    assert!(abc.a.is_finite() && abc.b.is_finite() && abc.c.is_finite());
                }
            }
        }
    }
    assert_eq!(alpha_beta_poles(f64::NAN, 0.1), Err(DesignError::NotFinite));
    assert_eq!(
        alpha_beta_gamma_poles(0.5, f64::INFINITY, 0.1),
        Err(DesignError::NotFinite)
    );
    assert_eq!(
        alpha_beta_transient_cost(0.5, 0.2, 1.0, f64::NAN, 0.0),
        Err(DesignError::NotFinite)
    );
    assert_eq!(
        alpha_beta_transient_cost(0.5, 0.2, 1.0, 1e300, 1e300),
        Err(DesignError::Overflow)
    );
}

// ---------------------------------------------------------------------------
// Tenne & Singh §3: optimal design (abtrack::design::optimal)

mod optimal_design {
    use super::{assert_abs, assert_close, printed_eq_10, printed_eq_16, printed_eq_21};
    use super::{printed_eq_22, stable_alpha_beta_gamma_samples, stable_alpha_beta_samples};
    use abtrack::design::optimal::*;
    use abtrack::design::{alpha_beta_gamma_to_abc, DesignError};

    fn penalty(kappa: f64, noise_variance: f64) -> Penalty {
        Penalty {
            kappa,
            noise_variance,
        }
    }

    fn line(s: StraightLine) -> Manoeuvre {
        Manoeuvre::StraightLine(s)
    }

    #[test]
    fn penalty_and_costs_golden() {
        assert_eq!(penalty(2.0, 200.0).weight(), Ok(400.0));
        assert_eq!(penalty(-1.0, 1.0).weight(), Err(DesignError::NotPositive));
        assert_eq!(penalty(1.0, f64::NAN).weight(), Err(DesignError::NotFinite));
        // Eq. 26 at (0.5, 0.2), v = 3, T = 0.7: J = 9·0.343·1.5/(0.1·2.8)
        // = 16.5375; ρ² (eq. 13) = 1.0/1.4; κx̄o² = 400.
        let cv = line(StraightLine::constant_velocity(3.0, 0.7));
        let c = alpha_beta_cost(&cv, &penalty(2.0, 200.0), Forms::Consistent, 0.5, 0.2).unwrap();
        assert_close(c.manoeuvre, 16.5375, 1e-14);
        assert_close(c.noise, 400.0 / 1.4, 1e-14);
        assert_eq!(c.steady_state, 0.0);
        assert_close(c.total(), 16.5375 + 400.0 / 1.4, 1e-14);
        // Steady-state term (eq. 19): (2·0.49/0.2)² = 24.01.
        let ss = line(StraightLine::steady_state(2.0, 0.7));
        let c = alpha_beta_cost(&ss, &penalty(0.0, 1.0), Forms::Consistent, 0.5, 0.2).unwrap();
        assert_close(c.steady_state, 24.01, 1e-14);
        assert_eq!((c.manoeuvre, c.noise), (0.0, 0.0));
        // Eq. 25 with v and a: the printed eq. 22 (cross term +) against the
        // consistent one, 94.57 vs 22.54 (the documented example).
        let both = line(StraightLine {
            velocity: 3.0,
            acceleration: 2.0,
            ..StraightLine::constant_velocity(0.0, 0.7)
        });
        let p = penalty(0.0, 1.0);
        let consistent = alpha_beta_cost(&both, &p, Forms::Consistent, 0.5, 0.2).unwrap();
        let printed = alpha_beta_cost(&both, &p, Forms::AsPrinted, 0.5, 0.2).unwrap();
        assert_close(
            printed.manoeuvre,
            printed_eq_22(0.5, 0.2, 0.7, 3.0, 2.0),
            1e-14,
        );
        assert_abs(consistent.manoeuvre, 22.54, 0.005);
        // Circle (eq. 24): e² from eq. 17 at ωT = π/2, R = 100: 200²/1.94.
        let circle = Manoeuvre::Circle(Circle {
            radius: 100.0,
            angular_rate: core::f64::consts::FRAC_PI_2,
            dt: 1.0,
        });
        let c = alpha_beta_cost(&circle, &penalty(1.0, 3.0), Forms::Consistent, 0.5, 0.2).unwrap();
        assert_close(c.manoeuvre, 40000.0 / 1.94, 1e-13);
        assert_close(c.noise, 3.0 / 1.4, 1e-14);
        // Outside the triangle, or bad inputs: typed errors.
        assert!(matches!(
            alpha_beta_cost(&cv, &p, Forms::Consistent, 1.5, 1.2),
            Err(DesignError::Unstable(_))
        ));
        let bad = line(StraightLine::constant_velocity(3.0, 0.0));
        assert_eq!(
            alpha_beta_cost(&bad, &p, Forms::Consistent, 0.5, 0.2),
            Err(DesignError::NotPositive)
        );
    }

    #[test]
    fn printed_forms_are_the_printed_equations() {
        let circle = Circle {
            radius: 100.0,
            angular_rate: core::f64::consts::FRAC_PI_3,
            dt: 1.0,
        };
        let mut compared = 0;
        for (alpha, beta, gamma) in stable_alpha_beta_gamma_samples().into_iter().step_by(7) {
            let abc = alpha_beta_gamma_to_abc(alpha, beta, gamma).unwrap();
            let pairs = [
                (printed_abc_noise_ratio(abc), printed_eq_10(abc)),
                (
                    printed_abc_transient_cost(abc, 0.7, 3.0, 2.0),
                    printed_eq_21(abc, 0.7, 3.0, 2.0),
                ),
                (
                    printed_alpha_beta_gamma_circular_error(alpha, beta, gamma, &circle),
                    printed_eq_16(alpha, beta, gamma, 100.0, core::f64::consts::FRAC_PI_3),
                ),
            ];
            for (library, helper) in pairs {
                match library {
                    Ok(v) => {
                        assert_close(v, helper, 1e-9);
                        compared += 1;
                    }
                    // A printed "variance" or magnitude below zero is refused.
                    Err(e) => {
                        assert_eq!(e, DesignError::Negative);
                        assert!(helper < 0.0, "{helper}");
                    }
                }
            }
        }
        assert!(compared > 100, "{compared}");
        // The golden point of `circular_error_golden`: printed 98.18.
        assert_abs(
            printed_alpha_beta_gamma_circular_error(0.5, 0.2, 0.04, &circle).unwrap(),
            98.18,
            0.01,
        );
    }

    #[test]
    fn stationarity_conditions_golden() {
        // Eq. 29 at (0.5, 0.2), v = 3, T = 0.7, κx̄o² = 1:
        // 2·0.2·0.64 + 2·9·0.343·(−2.05) = 0.256 − 12.6567.
        let p = penalty(1.0, 1.0);
        assert_close(
            constant_velocity_condition(0.5, 0.2, 3.0, 0.7, &p).unwrap(),
            0.256 - 12.6567,
            1e-14,
        );
        // Eq. 31 at (0.5, 0.2), a = 2, T = 1: 4·0.008·0.64 + 4·0.05·(−2.8)²
        // = 0.02048 + 1.568.
        assert_close(
            constant_acceleration_condition(0.5, 0.2, 2.0, 1.0, &p).unwrap(),
            0.02048 + 1.568,
            1e-14,
        );
        // Eq. 33: 2κ·0.64; and ∂f/∂β: 4·0.008 − 4·0.5·7.84 (a = 2, T = 1).
        assert_close(
            steady_state_alpha_condition(0.5, 0.2, &p).unwrap(),
            1.28,
            1e-15,
        );
        assert_close(
            steady_state_beta_condition(0.5, 0.2, 2.0, 1.0, &p).unwrap(),
            0.032 - 15.68,
            1e-14,
        );
        assert_eq!(
            constant_velocity_condition(0.5, f64::INFINITY, 3.0, 0.7, &p),
            Err(DesignError::NotFinite)
        );
    }

    /// Central difference of the total cost along α or β.
    fn slope(m: &Manoeuvre, p: &Penalty, alpha: f64, beta: f64, along_alpha: bool) -> f64 {
        let h = 1e-6;
        let f = |a: f64, b: f64| {
            alpha_beta_cost(m, p, Forms::Consistent, a, b)
                .unwrap()
                .total()
        };
        if along_alpha {
            (f(alpha + h, beta) - f(alpha - h, beta)) / (2.0 * h)
        } else {
            (f(alpha, beta + h) - f(alpha, beta - h)) / (2.0 * h)
        }
    }

    #[test]
    fn conditions_are_the_cost_gradient_times_the_papers_factors() {
        // Eq. 29 = α²β(2α+β−4)²·∂f/∂α, eq. 31 = 2α²β³(2α+β−4)²·∂f/∂α,
        // eq. 33 = α²(2α+β−4)²·∂f/∂α, the β condition = αβ³(2α+β−4)²/2·∂f/∂β
        // (sympy), for any stable point, any κ.
        let p = penalty(0.7, 3.0);
        let k = p.weight().unwrap();
        let (v, a, t) = (3.0, 2.0, 0.7);
        for (alpha, beta) in stable_alpha_beta_samples().into_iter().step_by(11) {
            let d2 = (2.0 * alpha + beta - 4.0).powi(2);
            let cv = line(StraightLine::constant_velocity(v, t));
            let ca = line(StraightLine::constant_acceleration(a, t));
            let ss = line(StraightLine::steady_state(a, t));
            let checks = [
                (
                    constant_velocity_condition(alpha, beta, v, t, &p).unwrap(),
                    alpha * alpha * beta * d2 * slope(&cv, &p, alpha, beta, true),
                ),
                (
                    constant_acceleration_condition(alpha, beta, a, t, &p).unwrap(),
                    2.0 * alpha * alpha * beta.powi(3) * d2 * slope(&ca, &p, alpha, beta, true),
                ),
                (
                    steady_state_alpha_condition(alpha, beta, &p).unwrap(),
                    alpha * alpha * d2 * slope(&ss, &p, alpha, beta, true),
                ),
                (
                    steady_state_beta_condition(alpha, beta, a, t, &p).unwrap(),
                    alpha * beta.powi(3) * d2 / 2.0 * slope(&ss, &p, alpha, beta, false),
                ),
            ];
            for (condition, gradient) in checks {
                let scale = condition.abs().max(gradient.abs()).max(k * 1e-3);
                assert!(
                    (condition - gradient).abs() <= 1e-5 * scale,
                    "({alpha}, {beta}): {condition} vs {gradient}"
                );
            }
        }
    }

    #[test]
    fn optimal_curves_golden() {
        // Eq. 30 at α = 0.5: √(36 − 30 + 0.25) = 2.5, β = 3 − 1.25 − 1.25.
        assert_close(
            constant_acceleration_beta(0.5, Branch::Lower).unwrap(),
            0.5,
            1e-15,
        );
        assert_eq!(
            constant_acceleration_beta(0.5, Branch::Upper),
            Err(DesignError::AlphaOutOfRange)
        );
        // α = 0.6: √0.36 = 0.6, β = 1.5 ∓ 0.3; both satisfy
        // 6α² + 5αβ + β² − 6β = 0.
        for (branch, beta) in [(Branch::Lower, 1.2), (Branch::Upper, 1.8)] {
            let b = constant_acceleration_beta(0.6, branch).unwrap();
            assert_close(b, beta, 1e-14);
            assert_abs(6.0 * 0.36 + 3.0 * b + b * b - 6.0 * b, 0.0, 1e-13);
        }
        assert_eq!(
            constant_acceleration_beta(0.61, Branch::Lower),
            Err(DesignError::AlphaOutOfRange)
        );
        // Small α: β ≈ α² (twice Benedict–Bordner), no cancellation.
        assert_close(
            constant_acceleration_beta(1e-6, Branch::Lower).unwrap(),
            1e-12,
            1e-5,
        );
        // Eq. 32 at α = 0.32: √(1 − 0.64) = 0.6, β = 1.36 ∓ 1.2.
        assert_close(steady_state_beta(0.32, Branch::Lower).unwrap(), 0.16, 1e-14);
        assert_close(steady_state_beta(0.32, Branch::Upper).unwrap(), 2.56, 1e-15);
        assert_eq!(
            steady_state_beta(0.51, Branch::Upper),
            Err(DesignError::AlphaOutOfRange)
        );
        // The consistent αβγ curve at α = 0.75: √0.25 = 0.5, β = 2·0.25,
        // γ = β²/α = 1/3 = 4αβ/(8 − 4α − β) = 1.5/4.5.
        let (b, g) = alpha_beta_gamma_acceleration_curve(0.75).unwrap();
        assert_close(b, 0.5, 1e-15);
        assert_close(g, 1.0 / 3.0, 1e-15);
        assert_eq!(
            alpha_beta_gamma_acceleration_curve(1.5),
            Err(DesignError::AlphaOutOfRange)
        );
        // Eqs. 34–35 at a = c = 0.5: b₁ = (2.25·(−0.5) + 0.125)/0.75 = −4/3,
        // b₂ = 1.5·1/0.5 = 3.
        let [b1, b2] = printed_abc_optimal_b(0.5, 0.5).unwrap();
        assert_close(b1, -4.0 / 3.0, 1e-15);
        assert_close(b2, 3.0, 1e-15);
        // b₂ puts −c on the quadratic factor: a repeated pole.
        assert_abs(0.25 + (0.5 + b2 - 2.0) * -0.5 + 0.5, 0.0, 1e-15);
        assert_eq!(printed_abc_optimal_b(0.5, 0.0), Err(DesignError::Overflow));
        // Eq. 34's surface in α-β-γ terms: β = α(4α + γ)/(4(2 − α)).
        assert_close(printed_eq_34_beta(0.5, 0.2).unwrap(), 1.1 / 6.0, 1e-15);
    }

    #[test]
    fn eq_34_is_the_surface_4a2_4ab_ag_8b_and_holds_the_consistent_curve() {
        for (a, c) in [(0.5, 0.5), (0.3, -0.4), (1.2, 0.7), (0.9, -0.95)] {
            let [b1, _] = printed_abc_optimal_b(a, c).unwrap();
            let g = abtrack::design::abc_to_alpha_beta_gamma(abtrack::design::AbcParameters {
                a,
                b: b1,
                c,
            })
            .unwrap();
            assert_close(printed_eq_34_beta(g.alpha, g.gamma).unwrap(), g.beta, 1e-12);
        }
        for alpha in [0.05, 0.3, 0.75, 0.99] {
            let (beta, gamma) = alpha_beta_gamma_acceleration_curve(alpha).unwrap();
            assert_close(printed_eq_34_beta(alpha, gamma).unwrap(), beta, 1e-12);
        }
    }

    const KAPPAS: [f64; 6] = [0.001, 0.01, 0.1, 1.0, 10.0, 100.0];

    #[track_caller]
    fn same_optimum(closed: &AlphaBetaOptimum, numeric: &AlphaBetaOptimum) {
        assert_abs(closed.alpha, numeric.alpha, 2e-6);
        assert_abs(closed.beta, numeric.beta, 2e-6);
        assert_close(closed.cost.total(), numeric.cost.total(), 1e-10);
    }

    #[test]
    fn closed_forms_agree_with_the_optimiser_alpha_beta() {
        for kappa in KAPPAS {
            let p = penalty(kappa, 4.0);
            let (v, a, t) = (10.0, 2.0, 1.0);
            let cv = optimal_constant_velocity(v, t, &p).unwrap();
            let numeric = minimise_alpha_beta(
                &line(StraightLine::constant_velocity(v, t)),
                &p,
                Forms::Consistent,
            )
            .unwrap();
            same_optimum(&cv, &numeric);
            // On Benedict–Bordner (eq. 28), at a root of eq. 29.
            assert_close(cv.beta, cv.alpha * cv.alpha / (2.0 - cv.alpha), 1e-14);
            let ca = optimal_constant_acceleration(a, t, &p).unwrap();
            let numeric = minimise_alpha_beta(
                &line(StraightLine::constant_acceleration(a, t)),
                &p,
                Forms::Consistent,
            )
            .unwrap();
            same_optimum(&ca, &numeric);
            let ss = optimal_steady_state(a, t, &p).unwrap();
            let numeric = minimise_alpha_beta(
                &line(StraightLine::steady_state(a, t)),
                &p,
                Forms::Consistent,
            )
            .unwrap();
            same_optimum(&ss, &numeric);
        }
        // κ = 0: the constant-velocity optimum is deadbeat, α = β = 1.
        let o = optimal_constant_velocity(10.0, 1.0, &penalty(0.0, 1.0)).unwrap();
        assert_eq!((o.alpha, o.beta), (1.0, 1.0));
        // Without a noise penalty the acceleration optima run to the edge of
        // the triangle: no interior optimum.
        assert_eq!(
            optimal_constant_acceleration(2.0, 1.0, &penalty(0.0, 1.0)),
            Err(DesignError::NoOptimum)
        );
        assert_eq!(
            optimal_constant_velocity(0.0, 1.0, &penalty(1.0, 1.0)),
            Err(DesignError::NotPositive)
        );
    }

    #[test]
    fn optima_move_monotonically_with_kappa() {
        // Fig. 2: a larger noise penalty means smaller gains on every curve.
        let mut previous = [(f64::INFINITY, f64::INFINITY); 3];
        for kappa in KAPPAS {
            let p = penalty(kappa, 4.0);
            let now = [
                optimal_constant_velocity(10.0, 1.0, &p).unwrap(),
                optimal_constant_acceleration(2.0, 1.0, &p).unwrap(),
                optimal_steady_state(2.0, 1.0, &p).unwrap(),
            ]
            .map(|o| (o.alpha, o.beta));
            for ((a, b), (pa, pb)) in now.iter().zip(previous) {
                assert!(*b < pb, "β {b} after {pb} at κ = {kappa}");
                assert!(*a <= pa + 1e-9 || *b < pb, "α {a} after {pa}");
            }
            previous = now;
        }
    }

    #[test]
    fn closed_form_agrees_with_the_optimiser_alpha_beta_gamma() {
        let m = line(StraightLine::constant_acceleration(2.0, 1.0));
        for kappa in KAPPAS {
            let p = penalty(kappa, 4.0);
            let closed = optimal_alpha_beta_gamma_constant_acceleration(2.0, 1.0, &p).unwrap();
            let numeric = minimise_alpha_beta_gamma(&m, &p, Forms::Consistent).unwrap();
            assert_abs(closed.alpha, numeric.alpha, 2e-6);
            assert_abs(closed.beta, numeric.beta, 2e-6);
            assert_abs(closed.gamma, numeric.gamma, 2e-6);
            assert_close(closed.cost.total(), numeric.cost.total(), 1e-10);
            // Eq. 34's surface holds the optimum; eq. 35's does not.
            let on_34 = minimise_alpha_beta_gamma_on_printed_surface(
                &m,
                &p,
                Forms::Consistent,
                PrintedSurface::Eq34,
            )
            .unwrap();
            assert_close(on_34.cost.total(), closed.cost.total(), 1e-6);
            let on_35 = minimise_alpha_beta_gamma_on_printed_surface(
                &m,
                &p,
                Forms::Consistent,
                PrintedSurface::Eq35,
            )
            .unwrap();
            assert!(
                on_35.cost.total() > closed.cost.total() * (1.0 + 1e-4),
                "κ = {kappa}: {} vs {}",
                on_35.cost.total(),
                closed.cost.total()
            );
        }
    }

    #[test]
    fn circle_optimum_golden_properties() {
        // The worked example's circle (R = 45 m, ω = 0.034 rad/s, T = 1 s,
        // x̄o² = 200 m²): the optimum is a true minimum of eq. 24 and the
        // αβγ optimum is never worse than the αβ one.
        let circle = Manoeuvre::Circle(Circle {
            radius: 45.0,
            angular_rate: 0.034,
            dt: 1.0,
        });
        for kappa in [0.01, 0.1, 1.0, 2.0, 10.0] {
            let p = penalty(kappa, 200.0);
            let ab = minimise_alpha_beta(&circle, &p, Forms::Consistent).unwrap();
            for (da, db) in [(1e-3, 0.0), (-1e-3, 0.0), (0.0, 1e-4), (0.0, -1e-4)] {
                let nearby =
                    alpha_beta_cost(&circle, &p, Forms::Consistent, ab.alpha + da, ab.beta + db)
                        .unwrap();
                assert!(nearby.total() > ab.cost.total());
            }
            let abg = minimise_alpha_beta_gamma(&circle, &p, Forms::Consistent).unwrap();
            assert!(abg.cost.total() <= ab.cost.total() * (1.0 + 1e-12));
        }
        // Only R²/(κx̄o²) matters: scaling the radius is scaling κ.
        let p = penalty(1.0, 200.0);
        let doubled = Manoeuvre::Circle(Circle {
            radius: 90.0,
            angular_rate: 0.034,
            dt: 1.0,
        });
        let a = minimise_alpha_beta(&doubled, &p, Forms::Consistent).unwrap();
        let b = minimise_alpha_beta(&circle, &penalty(0.25, 200.0), Forms::Consistent).unwrap();
        assert_abs(a.alpha, b.alpha, 1e-6);
        assert_abs(a.beta, b.beta, 1e-6);
    }
}
