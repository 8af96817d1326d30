//! Closed-form analysis of the αβ and αβγ filters: stability, gain
//! selection, noise ratios, steady-state and transient errors.
//!
//! Pure `f64` functions (libm for the maths, no heap), meant for design work on
//! the host or at start-up: pick gains here, then build [`Gains`] in the
//! representation the filter runs in with [`Gains::convert`].
//!
//! # Sources and conventions
//!
//! * αβ: Al-Wagih & Abdulla (eqs. 11–24); αβγ: Tenne & Singh (eqs. 6–22),
//!   whose acceleration gain is γ/(2T²) (their eq. 5), the convention of
//!   [`crate::filter`]. Li et al. eqs. (7)–(8) for Kalata's relation, and
//!   Kalata (1984) for the tracking index.
//! * "Residual" or "error" e(k) = x_o(k) − x_p(k): measurement minus the
//!   one-step prediction (Al-Wagih eq. 4, Tenne & Singh §2.2), exactly what
//!   the filter reports as `Innovation::residual`.
//! * A "noise ratio" is a variance ratio (output variance over the variance of
//!   white measurement noise), i.e. the sum of squares of the corresponding
//!   impulse response (Tenne & Singh eq. 9 squared).
//! * Transient costs assume the zero-state response of the z-domain analysis:
//!   the filter at rest at the origin (`KinematicFilter::from_state(0, 0, 0)`)
//!   while the target starts at the origin with velocity v and acceleration
//!   a_s (Tenne & Singh eq. 18).
//!
//! # Where the papers' printed formulas are wrong
//!
//! Every formula here was checked symbolically against the filter equations
//! and numerically against the implemented filter (host-tests/tests/it/gain/design.rs).
//! Four printed formulas of Tenne & Singh do not reproduce; the functions
//! implement the corrected forms, documented on each:
//!
//! * eq. (10), ρ² of αβγ: the term `4b(1+c)k₁` must read `(1+c)k₁`
//!   ([`abc_predicted_position_noise_ratio`]);
//! * eq. (16), circular error of αβγ: `sin²(ωT/2)` multiplies α²sin²ωT too and
//!   the γ term is under the root ([`alpha_beta_gamma_circular_error`]);
//! * eq. (21), J_abc: `(1−c)²` must read `(1+c)²` ([`abc_transient_cost`]);
//! * eq. (22), J_αβ: the cross term is `−v·a_s·T⁴/β²`, not `+`
//!   ([`alpha_beta_transient_cost`]).
//!
//! Tenne & Singh's optimal design (§3, eqs. 23–35) is in [`optimal`].
//!
//! # Designing gains from sensor noise and manoeuvre level
//!
//! ```
//! use abtrack::design::{kalata_gains, tracking_index};
//! use abtrack::{Fix, Quantity};
//! // Radar σ = 25 m, targets manoeuvre with σ_a ≈ 3 m/s², one scan per 2 s:
//! let lambda = tracking_index(3.0, 25.0, 2.0)?; // Λ = 3·2²/25 = 0.48
//! assert!((lambda - 0.48).abs() < 1e-15);
//! // r = 4/(4 + Λ + √(Λ(Λ + 8))), α = 1 − r², β = 2(1 − r)²:
//! let gains = kalata_gains(lambda)?;
//! assert!((gains.alpha() - 0.621013011077497).abs() < 1e-12);
//! assert!((gains.beta() - 0.29549721191196504).abs() < 1e-12);
//! // The same gains in the representation the filter runs in on the target:
//! let fixed = gains.convert::<Fix>()?;
//! assert!((fixed.alpha().to_f64() - 0.621013011077497).abs() < 1e-9);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

use crate::gains::{GainError, Gains};

pub mod optimal;

/// Why a design formula refused its input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DesignError {
    /// An input is NaN or infinite.
    NotFinite,
    /// A quantity that must be positive is not: an interval, a noise standard
    /// deviation, a tracking index (or a radius, which must be ≥ 0).
    NotPositive,
    /// α lies outside the domain of the formula (e.g. 0 < α ≤ 1 for critical
    /// damping, Al-Wagih eq. 20).
    AlphaOutOfRange,
    /// Least-squares gains need n > 2 measurements (Al-Wagih eq. 24).
    TooFewMeasurements,
    /// The gains are outside the stability region, where the quantity asked
    /// for (a noise ratio, a steady state, a cost) is infinite or undefined.
    /// Carries the library's reason ([`Gains::alpha_beta`]).
    Unstable(GainError),
    /// The result does not fit in a finite `f64`.
    Overflow,
    /// An optimisation found no point where its cost is defined, or its
    /// stationarity condition has no root in the formula's domain.
    NoOptimum,
    /// A printed formula gave a negative variance or sum of squares: it is
    /// not a cost there (Tenne & Singh's misprinted eqs. 10, 16, 21).
    Negative,
}

impl core::fmt::Display for DesignError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            DesignError::NotFinite => f.write_str("input is not a finite number"),
            DesignError::NotPositive => f.write_str("input must be positive"),
            DesignError::AlphaOutOfRange => f.write_str("alpha is outside the formula's domain"),
            DesignError::TooFewMeasurements => {
                f.write_str("least-squares gains need more than 2 measurements")
            }
            DesignError::Unstable(e) => write!(f, "gains are not stable: {e}"),
            DesignError::Overflow => f.write_str("result overflows f64"),
            DesignError::NoOptimum => f.write_str("no optimum found in the stability region"),
            DesignError::Negative => f.write_str("a printed variance or squared error is negative"),
        }
    }
}

impl core::error::Error for DesignError {}

/// A root of a characteristic polynomial: a pole of the filter's error
/// dynamics, as a complex number.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pole {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Pole {
    /// |z|. The filter is stable when every pole has modulus < 1.
    pub fn modulus(&self) -> f64 {
        libm::hypot(self.re, self.im)
    }
}

/// β for critical damping at a given α, both branches of Al-Wagih eq. (20).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CriticallyDampedBetas {
    /// β = 2 − α − 2√(1−α) = (1 − √(1−α))²: double pole at z = +√(1−α). The
    /// error decays as (c₁ + c₂k)·√(1−α)ᵏ, without oscillating (it changes
    /// sign at most once); this is the useful branch.
    pub monotone: f64,
    /// β = 2 − α + 2√(1−α) = (1 + √(1−α))²: double pole at z = −√(1−α). Also
    /// a double real root, but negative, so the error flips sign every scan
    /// (a period-2T ringing); inside the stability triangle, yet of no use
    /// for tracking.
    pub alternating: f64,
}

/// Tenne & Singh's a-b-c parameters (eq. 12): the αβγ characteristic
/// polynomial factored as (z + c)(z² + (a + b − 2)z + 1 − a) (eq. 11).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AbcParameters {
    /// a: the quadratic factor z² + (a + b − 2)z + 1 − a (eq. 11); equals α when c = −1.
    pub a: f64,
    /// b: the quadratic factor's second parameter (eq. 11); equals β when c = −1.
    pub b: f64,
    /// c: the third pole is z = −c (eq. 11); c = −1 is the αβ filter.
    pub c: f64,
}

/// (α, β, γ) as plain numbers, not checked for stability (the image of an
/// arbitrary a-b-c point need not be stable; use [`Gains::alpha_beta_gamma`]
/// to check).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AlphaBetaGammaParameters {
    /// Position gain α (dimensionless).
    pub alpha: f64,
    /// Velocity gain β (the velocity correction is β/T·e).
    pub beta: f64,
    /// Tenne & Singh's γ (the acceleration correction is γ/(2T²)·e, eq. 5).
    pub gamma: f64,
}

// ---------------------------------------------------------------------------
// Input and output checks

fn finite(values: &[f64]) -> Result<(), DesignError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(DesignError::NotFinite)
    }
}

fn positive(v: f64) -> Result<(), DesignError> {
    finite(&[v])?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(DesignError::NotPositive)
    }
}

fn result(v: f64) -> Result<f64, DesignError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(DesignError::Overflow)
    }
}

fn gain_error(e: GainError) -> DesignError {
    match e {
        GainError::NotFinite => DesignError::NotFinite,
        e => DesignError::Unstable(e),
    }
}

/// The library's own stability check (one copy of the inequalities).
fn require_stable_alpha_beta(alpha: f64, beta: f64) -> Result<(), DesignError> {
    Gains::<f64>::alpha_beta(alpha, beta)
        .map(|_| ())
        .map_err(gain_error)
}

fn require_stable_alpha_beta_gamma(alpha: f64, beta: f64, gamma: f64) -> Result<(), DesignError> {
    Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma)
        .map(|_| ())
        .map_err(gain_error)
}

// ---------------------------------------------------------------------------
// Stability

/// Whether (α, β) lie in the αβ stability triangle 0 < α < 2, β > 0,
/// 2α + β < 4 (Al-Wagih & Abdulla eqs. 12–14).
///
/// This is the check [`Gains::alpha_beta`] makes, not a second copy of it.
/// Those inequalities are exactly the Jury conditions |1−α| < 1, P(1) = β > 0
/// and P(−1) = 4 − 2α − β > 0 for the characteristic polynomial of eq. (15),
/// so the predicate is equivalent to [`alpha_beta_spectral_radius`] < 1.
pub fn is_stable_alpha_beta(alpha: f64, beta: f64) -> bool {
    Gains::<f64>::alpha_beta(alpha, beta).is_ok()
}

/// Whether (α, β, γ) lie in the αβγ stability volume of Tenne & Singh
/// eqs. (7)–(8): 0 < α < 2, 0 < β < 4 − 2α, 0 < γ < 4αβ/(2 − α).
///
/// This is the check [`Gains::alpha_beta_gamma`] makes. For the denominator
/// of eq. (6), z³ + a₂z² + a₁z + a₀, Jury's test gives P(1) = γ/2 > 0,
/// −P(−1) = 8 − 4α − 2β > 0, |a₀| = |α − 1| < 1 and
/// |a₀² − 1| > |a₀a₂ − a₁| ⇔ γ(2 − α) < 4αβ (the other side of that absolute
/// value holds automatically): exactly eqs. (7)–(8), with β > 0 implied. So
/// the predicate is equivalent to [`alpha_beta_gamma_spectral_radius`] < 1.
pub fn is_stable_alpha_beta_gamma(alpha: f64, beta: f64, gamma: f64) -> bool {
    Gains::<f64>::alpha_beta_gamma(alpha, beta, gamma).is_ok()
}

/// Coefficients, highest power first, of the αβ characteristic polynomial
/// z² + (α + β − 2)z + (1 − α) (Al-Wagih & Abdulla eq. 15, the denominator
/// of eq. 11). Any finite gains, stable or not.
pub fn alpha_beta_characteristic_polynomial(
    alpha: f64,
    beta: f64,
) -> Result<[f64; 3], DesignError> {
    finite(&[alpha, beta])?;
    Ok([1.0, result(alpha + beta - 2.0)?, 1.0 - alpha])
}

/// Roots of z² + p·z + q, larger modulus first; a complex pair as (+im, −im).
fn quadratic_roots(p: f64, q: f64) -> [Pole; 2] {
    let disc = p * p - 4.0 * q;
    if disc >= 0.0 {
        // Cancellation-free: the root of larger modulus first, then q/z₁
        // (product of the roots).
        let w = -0.5 * (p + libm::copysign(libm::sqrt(disc), p));
        let other = if w != 0.0 { q / w } else { 0.0 };
        [Pole { re: w, im: 0.0 }, Pole { re: other, im: 0.0 }]
    } else {
        let im = 0.5 * libm::sqrt(-disc);
        [
            Pole { re: -0.5 * p, im },
            Pole {
                re: -0.5 * p,
                im: -im,
            },
        ]
    }
}

fn poles_finite<const N: usize>(poles: [Pole; N]) -> Result<[Pole; N], DesignError> {
    if poles.iter().all(|p| p.re.is_finite() && p.im.is_finite()) {
        Ok(poles)
    } else {
        Err(DesignError::Overflow)
    }
}

/// The two poles of the αβ error dynamics, the roots z₁, z₂ of eq. (15)
/// (Al-Wagih & Abdulla eqs. 16–17), larger modulus first, a complex pair as
/// (+im, −im).
///
/// Evaluated in the cancellation-free form z₁ = −(p + sign(p)√D)/2,
/// z₂ = (1 − α)/z₁ (p = α + β − 2, D = p² − 4(1 − α)), which is eqs. (16)–(17)
/// rearranged. The same poles govern the prediction, the smoothed state and
/// the residual (Tenne & Singh eq. 15), and they do not depend on T.
pub fn alpha_beta_poles(alpha: f64, beta: f64) -> Result<[Pole; 2], DesignError> {
    let [_, p, q] = alpha_beta_characteristic_polynomial(alpha, beta)?;
    poles_finite(quadratic_roots(p, q))
}

/// Largest pole modulus of the αβ filter (eqs. 16–17): < 1 exactly when
/// [`is_stable_alpha_beta`]; the error envelope shrinks by this factor per
/// scan.
pub fn alpha_beta_spectral_radius(alpha: f64, beta: f64) -> Result<f64, DesignError> {
    let [z1, z2] = alpha_beta_poles(alpha, beta)?;
    result(z1.modulus().max(z2.modulus()))
}

/// Coefficients, highest power first, of the αβγ characteristic polynomial,
/// the denominator of Tenne & Singh eq. (6):
/// z³ + (α + β + γ/4 − 3)z² + (−2α − β + γ/4 + 3)z + (α − 1).
///
/// Verified symbolically against the filter equations (1)–(5) with the
/// γ/(2T²) acceleration gain: it is the characteristic polynomial of the
/// filter's state-transition matrix under zero input.
pub fn alpha_beta_gamma_characteristic_polynomial(
    alpha: f64,
    beta: f64,
    gamma: f64,
) -> Result<[f64; 4], DesignError> {
    finite(&[alpha, beta, gamma])?;
    Ok([
        1.0,
        result(alpha + beta + 0.25 * gamma - 3.0)?,
        result(-2.0 * alpha - beta + 0.25 * gamma + 3.0)?,
        alpha - 1.0,
    ])
}

/// The real roots of a monic cubic: either one real root and a complex pair,
/// or three real roots.
enum CubicRoots {
    OneReal { real: f64, pair: [Pole; 2] },
    ThreeReal([f64; 3]),
}

fn cubic_value(a2: f64, a1: f64, a0: f64, z: f64) -> f64 {
    ((z + a2) * z + a1) * z + a0
}

/// A few Newton steps on a real root, each kept only if it reduces |P(z)|.
fn polish_real_root(a2: f64, a1: f64, a0: f64, mut z: f64) -> f64 {
    let mut residual = libm::fabs(cubic_value(a2, a1, a0, z));
    for _ in 0..4 {
        let slope = (3.0 * z + 2.0 * a2) * z + a1;
        if residual == 0.0 || slope == 0.0 || !slope.is_finite() {
            break;
        }
        let next = z - cubic_value(a2, a1, a0, z) / slope;
        let next_residual = libm::fabs(cubic_value(a2, a1, a0, next));
        if next_residual < residual {
            z = next;
            residual = next_residual;
        } else {
            break;
        }
    }
    z
}

/// Roots of z³ + a₂z² + a₁z + a₀ (Cardano, trigonometric form for three real
/// roots), each real root polished by Newton.
fn cubic_roots(a2: f64, a1: f64, a0: f64) -> Result<CubicRoots, DesignError> {
    let shift = a2 / 3.0;
    // Depressed cubic t³ + p t + q = 0 with z = t − a₂/3.
    let p = a1 - a2 * a2 / 3.0;
    let q = 2.0 * a2 * a2 * a2 / 27.0 - a2 * a1 / 3.0 + a0;
    let half_q = 0.5 * q;
    let third_p = p / 3.0;
    let disc = half_q * half_q + third_p * third_p * third_p;
    if !disc.is_finite() {
        return Err(DesignError::Overflow);
    }
    Ok(if disc > 0.0 {
        // One real root. u is the cube root of larger modulus, so u − p/(3u)
        // has no cancellation.
        let u = libm::cbrt(-half_q - libm::copysign(libm::sqrt(disc), half_q));
        let t = if u != 0.0 { u - third_p / u } else { 0.0 };
        let real = polish_real_root(a2, a1, a0, t - shift);
        // Deflate: P(z) = (z − r)(z² + (a₂ + r)z + a₁ + r(a₂ + r)).
        let lin = a2 + real;
        let pair = quadratic_roots(lin, a1 + real * lin);
        CubicRoots::OneReal { real, pair }
    } else if third_p < 0.0 {
        let m = 2.0 * libm::sqrt(-third_p);
        // cos 3θ = (3q/(2p))·√(−3/p) = 3q/(p·m).
        let cos_arg = (3.0 * q / (p * m)).clamp(-1.0, 1.0);
        let theta = libm::acos(cos_arg) / 3.0;
        let step = 2.0 * core::f64::consts::PI / 3.0;
        let root = |k: f64| polish_real_root(a2, a1, a0, m * libm::cos(theta - k * step) - shift);
        CubicRoots::ThreeReal([root(0.0), root(1.0), root(2.0)])
    } else {
        // p = q = 0 (or NaN): a triple root.
        CubicRoots::ThreeReal([-shift; 3])
    })
}

/// The three poles of the αβγ error dynamics: the roots of the denominator
/// of Tenne & Singh eq. (6), sorted by decreasing modulus (a complex pair as
/// (+im, −im)). Any finite gains.
pub fn alpha_beta_gamma_poles(alpha: f64, beta: f64, gamma: f64) -> Result<[Pole; 3], DesignError> {
    let [_, a2, a1, a0] = alpha_beta_gamma_characteristic_polynomial(alpha, beta, gamma)?;
    let mut poles = match cubic_roots(a2, a1, a0)? {
        CubicRoots::OneReal { real, pair } => [Pole { re: real, im: 0.0 }, pair[0], pair[1]],
        CubicRoots::ThreeReal(r) => r.map(|re| Pole { re, im: 0.0 }),
    };
    poles.sort_unstable_by(|x, y| {
        y.modulus()
            .total_cmp(&x.modulus())
            .then(y.im.total_cmp(&x.im))
    });
    poles_finite(poles)
}

/// Largest pole modulus of the αβγ filter (roots of Tenne & Singh eq. 6):
/// < 1 exactly when [`is_stable_alpha_beta_gamma`].
pub fn alpha_beta_gamma_spectral_radius(
    alpha: f64,
    beta: f64,
    gamma: f64,
) -> Result<f64, DesignError> {
    let poles = alpha_beta_gamma_poles(alpha, beta, gamma)?;
    result(poles.iter().fold(0.0, |m, p| p.modulus().max(m)))
}

// ---------------------------------------------------------------------------
// Choosing gains

/// Both critically damped β for a given α (Al-Wagih & Abdulla eq. 20):
/// β = 2 − α ± 2√(1 − α), where the roots (16)–(17) coincide (eq. 18), for
/// 0 < α ≤ 1 (eq. 21; for α > 1 the square root is imaginary). The paper's
/// "final stability boundaries" (21)–(22) describe where eq. (20) applies
/// and the edge β = 4 − 2α; they do not shrink the stability region, which
/// stays eqs. (12)–(14) (gains with 1 < α < 2 are stable, just never
/// critically damped).
///
/// The paper does not say which sign to use. The minus sign
/// ([`CriticallyDampedBetas::monotone`]) gives the double pole +√(1−α) and a
/// non-oscillating transient: that is the critically damped filter of the
/// literature. The plus sign gives the double pole −√(1−α): an error that
/// alternates in sign every scan. It is computed as (1 − √(1−α))² =
/// α²/(1 + √(1−α))², the same number without cancellation for small α.
///
/// Errors: [`DesignError::AlphaOutOfRange`] outside 0 < α ≤ 1.
pub fn critically_damped_betas(alpha: f64) -> Result<CriticallyDampedBetas, DesignError> {
    finite(&[alpha])?;
    if !(alpha > 0.0 && alpha <= 1.0) {
        return Err(DesignError::AlphaOutOfRange);
    }
    let root = libm::sqrt(1.0 - alpha);
    let one_minus_root = alpha / (1.0 + root);
    Ok(CriticallyDampedBetas {
        monotone: one_minus_root * one_minus_root,
        alternating: (1.0 + root) * (1.0 + root),
    })
}

/// Benedict–Bordner β = α²/(2 − α): Al-Wagih & Abdulla eqs. (23a)–(23b)
/// (method M1), Tenne & Singh eq. (28) (optimal for constant-velocity
/// transients against noise).
///
/// Errors: [`DesignError::AlphaOutOfRange`] outside 0 < α ≤ 1 (eq. 23a; past
/// α = 4 − 2√2 ≈ 1.17 the pair would leave the stability triangle).
///
/// ```
/// use abtrack::design::{benedict_bordner_beta, DesignError};
/// // α = 0.5: β = 0.25/1.5 = 1/6.
/// assert!((benedict_bordner_beta(0.5)? - 1.0 / 6.0).abs() < 1e-15);
/// assert_eq!(benedict_bordner_beta(1.5), Err(DesignError::AlphaOutOfRange));
/// # Ok::<(), DesignError>(())
/// ```
pub fn benedict_bordner_beta(alpha: f64) -> Result<f64, DesignError> {
    finite(&[alpha])?;
    if !(alpha > 0.0 && alpha <= 1.0) {
        return Err(DesignError::AlphaOutOfRange);
    }
    Ok(crate::gains::beta_from_alpha(alpha))
}

/// Least-squares ("growing memory") gains for the n-th measurement:
/// α = 2(2n − 1)/(n(n + 1)), β = 6/(n(n + 1)) (Al-Wagih & Abdulla eqs.
/// 24a–24b, method M2; Li et al. eqs. 4–5).
///
/// With these gains at every scan n ≥ 3 after the two-point initialisation
/// (Al-Wagih eqs. 9–10) the filter's smoothed position and velocity are
/// exactly the least-squares straight line through all n measurements
/// (verified in host-tests). For n = 1, 2 the formula gives (1, 3) and (1, 1):
/// the two-point start already is that fit, which is why the paper requires
/// n > 2.
///
/// Errors: [`DesignError::TooFewMeasurements`] for n ≤ 2.
pub fn least_squares_gains(n: u32) -> Result<Gains<f64>, DesignError> {
    if n <= 2 {
        return Err(DesignError::TooFewMeasurements);
    }
    use crate::gains::{least_squares_alpha, least_squares_beta};
    Gains::alpha_beta(least_squares_alpha(n), least_squares_beta(n)).map_err(gain_error)
}

/// Kalata's relation β = 2(2 − α) − 4√(1 − α) = 2(1 − √(1 − α))² (Li et al.
/// eq. 7), for 0 < α ≤ 1: the steady-state Kalman gains of the
/// piecewise-constant white-acceleration model (Kalata 1984) lie on this
/// curve (see [`kalata_gains`]).
///
/// Li et al.'s two forms agree (expand the square). Their eq. (8), this
/// relation with the least-squares α of eq. (4), β = 2(1 − √((k−1)(k−2)/
/// (k(k+1))))², also checks: 1 − α(k) = (k−1)(k−2)/(k(k+1)). Its remark
/// "β = 2 when k = 1, 2" is right too (α = 1 there), but (α, β) = (1, 2) lies
/// on the stability boundary 2α + β = 4, which [`Gains`] rejects.
///
/// β is exactly twice the monotone critically damped β
/// ([`critically_damped_betas`]). For α < 12√2 − 16 ≈ 0.9706 (√(1 − α) >
/// 3 − 2√2) the gains are underdamped, a complex pole pair of modulus
/// √(1 − α); above it the two poles are real. Computed as
/// 2α²/(1 + √(1−α))² to avoid cancellation at small α.
///
/// Errors: [`DesignError::AlphaOutOfRange`] outside 0 < α ≤ 1.
pub fn kalata_beta(alpha: f64) -> Result<f64, DesignError> {
    finite(&[alpha])?;
    if !(alpha > 0.0 && alpha <= 1.0) {
        return Err(DesignError::AlphaOutOfRange);
    }
    Ok(crate::gains::li_beta(alpha))
}

/// Kalata's tracking index Λ = σ_w T²/σ_v (Kalata 1984, not in the five
/// papers): the manoeuvre (process-noise) displacement over one scan
/// relative to the measurement noise.
///
/// `accel_noise_std` σ_w is the standard deviation of the target's
/// acceleration, modelled as white and constant over each scan (m/s²);
/// `measurement_noise_std` σ_v that of the position measurement (m); `dt` the
/// scan interval T (s).
///
/// Errors: [`DesignError::NotPositive`] unless all three are > 0.
pub fn tracking_index(
    accel_noise_std: f64,
    measurement_noise_std: f64,
    dt: f64,
) -> Result<f64, DesignError> {
    positive(accel_noise_std)?;
    positive(measurement_noise_std)?;
    positive(dt)?;
    result(accel_noise_std * dt * dt / measurement_noise_std)
}

/// The optimal (steady-state Kalman) αβ gains for tracking index Λ
/// (Kalata 1984):
/// r = (4 + Λ − √(Λ² + 8Λ))/4, α = 1 − r², β = 2(2 − α) − 4√(1 − α) = 2(1 − r)².
///
/// These satisfy Kalata's identity Λ² = β²/(1 − α) (the identity is in β,
/// not α: α²/(1 − α) = Λ² is false, e.g. Λ = 0.1 gives α = 0.36 and
/// α²/(1 − α) = 0.2025 ≠ 0.01), and β is Kalata's relation of Li et al.
/// eq. (7). Derivation: Λ = β/√(1−α) = 2(1 − r)²/r with r = √(1 − α) gives
/// 2r² − (4 + Λ)r + 2 = 0, whose root below 1 is the r above. Computed as
/// r = 4/(4 + Λ + √Λ·√(Λ + 8)) (the roots multiply to 1), which is exact
/// for every Λ without cancellation or overflow. host-tests checks the result
/// against a Riccati iteration of the Kalman filter for the
/// piecewise-constant white-acceleration model.
///
/// Errors: [`DesignError::NotPositive`] unless Λ > 0;
/// [`DesignError::Unstable`] if Λ is so extreme that the gains round onto
/// the stability boundary (Λ ≳ 1e16 or ≲ 1e-300).
pub fn kalata_gains(tracking_index: f64) -> Result<Gains<f64>, DesignError> {
    positive(tracking_index)?;
    let lambda = tracking_index;
    let root = libm::sqrt(lambda) * libm::sqrt(lambda + 8.0);
    let denominator = 4.0 + lambda + root;
    let r = 4.0 / denominator;
    let one_minus_r = (lambda + root) / denominator;
    let alpha = one_minus_r * (1.0 + r);
    let beta = 2.0 * one_minus_r * one_minus_r;
    Gains::alpha_beta(alpha, beta).map_err(gain_error)
}

/// The tracking index of gains on Kalata's curve, Λ = β/√(1 − α)
/// (Kalata 1984's identity Λ² = β²/(1 − α)); the inverse of [`kalata_gains`].
/// For gains off the curve this is the Λ that identity assigns, not a
/// property of the filter.
///
/// Errors: [`DesignError::AlphaOutOfRange`] outside 0 < α < 1,
/// [`DesignError::NotPositive`] unless β > 0.
pub fn tracking_index_of_gains(alpha: f64, beta: f64) -> Result<f64, DesignError> {
    finite(&[alpha, beta])?;
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(DesignError::AlphaOutOfRange);
    }
    positive(beta)?;
    result(beta / libm::sqrt(1.0 - alpha))
}

// ---------------------------------------------------------------------------
// Noise ratios

/// Noise ratio ρ² of the αβ filter's predicted position,
/// (2α² + αβ + 2β)/(α(4 − β − 2α)) (Tenne & Singh eq. 13): the variance of
/// x_p over the variance of white measurement noise, the sum of squares of
/// the prediction's impulse response. This is the classic one-step
/// prediction variance reduction of Benedict & Bordner / Kalata, despite the
/// paper's remark that it differs from theirs.
///
/// Errors: [`DesignError::Unstable`] outside the stability triangle (where the
/// variance is infinite).
pub fn alpha_beta_predicted_position_noise_ratio(
    alpha: f64,
    beta: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta(alpha, beta)?;
    result((2.0 * alpha * alpha + alpha * beta + 2.0 * beta) / (alpha * (4.0 - beta - 2.0 * alpha)))
}

/// Noise ratio of the αβ filter's smoothed position x_s,
/// (2α² + 2β − 3αβ)/(α(4 − 2α − β)).
///
/// Not in the five papers: the standard smoothed-position variance reduction
/// (Benedict & Bordner 1962; Kalata 1984), here the steady-state solution of
/// the discrete Lyapunov equation of the filter and checked in host-tests as
/// the sum of squares of the implemented filter's x_s impulse response.
///
/// Errors: [`DesignError::Unstable`] outside the stability triangle.
pub fn alpha_beta_smoothed_position_noise_ratio(alpha: f64, beta: f64) -> Result<f64, DesignError> {
    require_stable_alpha_beta(alpha, beta)?;
    result(
        (2.0 * alpha * alpha + 2.0 * beta - 3.0 * alpha * beta)
            / (alpha * (4.0 - 2.0 * alpha - beta)),
    )
}

/// The velocity counterpart of Tenne & Singh eq. (13): the variance of the
/// αβ filter's velocity estimate over the variance of white position noise,
/// 2β²/(T²α(4 − 2α − β)), in 1/s² (multiply by σ_v² in m² to get (m/s)²).
/// The predicted and smoothed velocities are the same in an αβ filter.
///
/// Not in the five papers: the standard velocity variance reduction
/// (Benedict & Bordner 1962; Kalata 1984), checked in host-tests as the sum
/// of squares of the implemented filter's velocity impulse response.
///
/// Errors: [`DesignError::Unstable`] outside the stability triangle,
/// [`DesignError::NotPositive`] unless T > 0.
pub fn alpha_beta_smoothed_velocity_noise_ratio(
    alpha: f64,
    beta: f64,
    dt: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta(alpha, beta)?;
    positive(dt)?;
    result(2.0 * beta * beta / (dt * dt * alpha * (4.0 - 2.0 * alpha - beta)))
}

/// Noise ratio ρ² of the αβγ filter's predicted position (Tenne & Singh
/// eq. 10 through the a-b-c transform eq. 12, corrected, written back in α, β, γ):
///
/// ρ² = (8α²β + 2α²γ + 4αβ² + αβγ − 4αγ + 8β²) / ((4 − 2α − β)(4αβ + αγ − 2γ)).
///
/// Derived from the filter equations (1)–(5) by the discrete Lyapunov
/// equation; it equals [`abc_predicted_position_noise_ratio`] of any a-b-c
/// factorisation of (α, β, γ), reduces to eq. (13) at γ = 0, and its
/// denominator vanishes exactly on the boundaries 2α + β = 4 and
/// γ = 4αβ/(2 − α) of eq. (8). Computing it in α, β, γ avoids solving the
/// cubic that the inverse of eq. (12) needs.
///
/// Errors: [`DesignError::Unstable`] outside the stability volume.
pub fn alpha_beta_gamma_predicted_position_noise_ratio(
    alpha: f64,
    beta: f64,
    gamma: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta_gamma(alpha, beta, gamma)?;
    let (a, b, g) = (alpha, beta, gamma);
    let numerator =
        8.0 * a * a * b + 2.0 * a * a * g + 4.0 * a * b * b + a * b * g - 4.0 * a * g + 8.0 * b * b;
    let denominator = (4.0 - 2.0 * a - b) * (4.0 * a * b - g * (2.0 - a));
    result(numerator / denominator)
}

/// Tenne & Singh eq. (10), ρ² of the αβγ predicted position in the a-b-c
/// space, **with the paper's typo corrected**:
///
/// ρ² = (−(4ba² + 2ab² + 4b²) − (1 + c)k₁) / (2a(b + 2a − 4)b + a(1 + c)k₂),
///
/// k₁ = k₁₁c² + k₁₂c + k₁₃ and k₁₁, k₁₂, k₁₃, k₂ exactly as printed. The paper
/// prints the second numerator term as −4b(1 + c)k₁; that does not match the
/// filter (e.g. (a, b, c) = (0.5, 0.2, 0.5), i.e. (α, β, γ) = (1.25, 0.8, 0.6):
/// printed 5.793, filter's Σh² 7.161). Symbolic comparison with the Lyapunov
/// solution shows the true numerator is the printed one with the factor 4b
/// removed from that term; the denominator is right. Both forms reduce to
/// eq. (13) at c = −1, which is why the slip is invisible for the αβ filter.
///
/// Errors: [`DesignError::Unstable`] if the (α, β, γ) image of (a, b, c)
/// (eq. 12) is outside the stability volume.
pub fn abc_predicted_position_noise_ratio(abc: AbcParameters) -> Result<f64, DesignError> {
    abc_noise_ratio(abc, 1.0)
}

/// Eq. (10) with the factor `k1_factor` on its (1 + c)k₁ numerator term:
/// 1 is the corrected form, 4b the printed one ([`optimal::printed_abc_noise_ratio`]).
fn abc_noise_ratio(abc: AbcParameters, k1_factor: f64) -> Result<f64, DesignError> {
    let g = abc_to_alpha_beta_gamma(abc)?;
    require_stable_alpha_beta_gamma(g.alpha, g.beta, g.gamma)?;
    let AbcParameters { a, b, c } = abc;
    let k11 = 4.0 * a + 2.0 * a * a * a - a * b + b * a * a - 6.0 * a * a;
    let k12 = b * a * a + a * b * b - 6.0 * a * b - 2.0 * a * a * a + 8.0 * a;
    let k13 = 6.0 * a * a - 2.0 * a * b * b - 4.0 * b * a * a + 4.0 * a - 2.0 * b * b + 7.0 * a * b;
    let k1 = (k11 * c + k12) * c + k13;
    let k2 = (b + 2.0 * a - 4.0) * (c * c * a - c * a - c * c - 2.0 * b + b * c + 1.0);
    let numerator = -(4.0 * b * a * a + 2.0 * a * b * b + 4.0 * b * b) - k1_factor * (1.0 + c) * k1;
    let denominator = 2.0 * a * (b + 2.0 * a - 4.0) * b + a * (1.0 + c) * k2;
    result(numerator / denominator)
}

// ---------------------------------------------------------------------------
// The a-b-c transform

/// Tenne & Singh eq. (12), a-b-c → α-β-γ:
/// α = 1 + c(1 − a), β = a(1 + c) + b(1 − c)/2, γ = 2b(1 + c).
///
/// Verified symbolically: with these, the denominator of eq. (6) is
/// (z + c)(z² + (a + b − 2)z + 1 − a) (eq. 11). c = −1 gives γ = 0, α = a,
/// β = b (the αβ filter).
pub fn abc_to_alpha_beta_gamma(
    abc: AbcParameters,
) -> Result<AlphaBetaGammaParameters, DesignError> {
    let AbcParameters { a, b, c } = abc;
    finite(&[a, b, c])?;
    Ok(AlphaBetaGammaParameters {
        alpha: result(1.0 + c * (1.0 - a))?,
        beta: result(a * (1.0 + c) + 0.5 * b * (1.0 - c))?,
        gamma: result(2.0 * b * (1.0 + c))?,
    })
}

/// The inverse of Tenne & Singh eq. (12): factor the denominator of eq. (6)
/// as (z + c)(z² + (a + b − 2)z + 1 − a).
///
/// The paper calls the transform unique, but when the cubic has three real
/// roots any of them can be the "third pole" −c. This picks the **largest
/// real root** as −c: for stable gains with γ → 0 that root tends to z = 1,
/// so c → −1, a → α, b → β, continuing the paper's degenerate case. Every
/// metric here (ρ², J) is the same for any valid choice (checked in
/// host-tests).
pub fn alpha_beta_gamma_to_abc(
    alpha: f64,
    beta: f64,
    gamma: f64,
) -> Result<AbcParameters, DesignError> {
    let [_, a2, a1, a0] = alpha_beta_gamma_characteristic_polynomial(alpha, beta, gamma)?;
    let largest_real = match cubic_roots(a2, a1, a0)? {
        CubicRoots::OneReal { real, .. } => real,
        CubicRoots::ThreeReal([r0, r1, r2]) => r0.max(r1).max(r2),
    };
    let c = -largest_real;
    // Deflation: z² + P z + Q with P = a₂ − c, Q = a₁ − cP.
    let p = a2 - c;
    let q = a1 - c * p;
    let a = 1.0 - q;
    let b = p + 2.0 - a;
    finite(&[a, b, c]).map_err(|_| DesignError::Overflow)?;
    Ok(AbcParameters { a, b, c })
}

// ---------------------------------------------------------------------------
// Tracking errors

/// Steady-state residual of the αβ filter on a target with constant
/// acceleration a: e(∞) = aT²/β (Tenne & Singh eq. 19, by the final value
/// theorem on eq. 18). Positive for positive a: the prediction lags behind
/// the measurement. (The αβγ filter's is zero.)
///
/// Errors: [`DesignError::Unstable`] outside the stability triangle (no
/// steady state), [`DesignError::NotPositive`] unless T > 0.
pub fn alpha_beta_acceleration_lag(
    alpha: f64,
    beta: f64,
    acceleration: f64,
    dt: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta(alpha, beta)?;
    finite(&[acceleration])?;
    positive(dt)?;
    result(acceleration * dt * dt / beta)
}

/// Transient cost of the αβ filter, J = Σ_{k≥0} T(e(k) − e(∞))² with
/// e(∞) = a_s T²/β (Tenne & Singh eqs. 20 and 22), for a target starting at
/// the filter's origin with velocity v and acceleration a_s (zero state):
///
/// J = a_s²T⁵(2β + αβ + 2α²)/(4αβ³) + v²T³(α − 2)/(αβ(2α + β − 4)) − v·a_s·T⁴/β².
///
/// **Deviation:** the paper prints the last term with a plus sign. The
/// simulated filter and an exact Parseval evaluation (sympy) both give the
/// minus sign: e.g. α = 0.5, β = 0.2, T = 0.7, v = 3, a_s = 2 sums to 22.54,
/// the printed formula gives 94.57. A sign convention cannot explain it
/// (flipping e flips e(∞) too), so it is a typo. The pure-velocity and
/// pure-acceleration terms are as printed.
///
/// Errors: [`DesignError::Unstable`] outside the stability triangle,
/// [`DesignError::NotPositive`] unless T > 0.
pub fn alpha_beta_transient_cost(
    alpha: f64,
    beta: f64,
    dt: f64,
    velocity: f64,
    acceleration: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta(alpha, beta)?;
    finite(&[velocity, acceleration])?;
    positive(dt)?;
    let (a, b, t, v, acc) = (alpha, beta, dt, velocity, acceleration);
    let t2 = t * t;
    let t3 = t2 * t;
    let acceleration_term =
        acc * acc * t3 * t2 * (2.0 * b + a * b + 2.0 * a * a) / (4.0 * a * b * b * b);
    let velocity_term = v * v * t3 * (2.0 - a) / (a * b * (4.0 - 2.0 * a - b));
    let cross_term = -v * acc * t2 * t2 / (b * b);
    result(acceleration_term + velocity_term + cross_term)
}

/// Transient cost of the αβγ filter, J = Σ_{k≥0} T e(k)² (Tenne & Singh
/// eqs. 20–21; no steady-state error to subtract), zero-state response to
/// a target with velocity v and acceleration a_s, written in α, β, γ:
///
/// J = 4v²T³(2 − α)/((4 − 2α − β)(4αβ − γ(2 − α))) + 4a_s²T⁵α/(γ(4αβ − γ(2 − α))).
///
/// This is eq. (21) with its typo corrected ([`abc_transient_cost`]) mapped
/// through eq. (12); the v·a_s cross term is exactly zero for αβγ, as the
/// paper's formula implies. The velocity term tends to eq. (22)'s as γ → 0.
///
/// Errors: [`DesignError::Unstable`] outside the stability volume,
/// [`DesignError::NotPositive`] unless T > 0.
pub fn alpha_beta_gamma_transient_cost(
    alpha: f64,
    beta: f64,
    gamma: f64,
    dt: f64,
    velocity: f64,
    acceleration: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta_gamma(alpha, beta, gamma)?;
    finite(&[velocity, acceleration])?;
    positive(dt)?;
    let (a, b, g, t, v, acc) = (alpha, beta, gamma, dt, velocity, acceleration);
    let t2 = t * t;
    let t3 = t2 * t;
    let margin = 4.0 * a * b - g * (2.0 - a);
    let velocity_term = 4.0 * v * v * t3 * (2.0 - a) / ((4.0 - 2.0 * a - b) * margin);
    let acceleration_term = 4.0 * acc * acc * t3 * t2 * a / (g * margin);
    result(velocity_term + acceleration_term)
}

/// Tenne & Singh eq. (21), J_abc, **with the paper's typo corrected**:
///
/// J = 2(c − ca − 1)T³v² / (a(2a + b − 4)(c − 1)Q) + ½a_s²T⁵(c(a − 1) − 1) / (ab(1 + c)Q),
/// Q = c(a + b + ca) − (1 + c)².
///
/// The paper prints Q = c(a + b + ca) − (1 − c)², which is off by a factor of
/// about 20 against the simulated filter (e.g. (α, β, γ) = (0.5, 0.2, 0.02),
/// T = 0.7, v = 3: printed 0.885, filter 17.878). The exact Parseval sum
/// (sympy) is the printed expression with (1 + c)²; with that change it
/// matches the filter to rounding.
///
/// Errors: [`DesignError::Unstable`] if the (α, β, γ) image of (a, b, c) is
/// outside the stability volume, [`DesignError::NotPositive`] unless T > 0.
pub fn abc_transient_cost(
    abc: AbcParameters,
    dt: f64,
    velocity: f64,
    acceleration: f64,
) -> Result<f64, DesignError> {
    abc_transient(abc, dt, velocity, acceleration, 1.0)
}

/// Eq. (21) with Q = c(a + b + ca) − (1 + `sign`·c)²: `sign` 1 is the
/// corrected form, −1 the printed one ([`optimal::printed_abc_transient_cost`]).
fn abc_transient(
    abc: AbcParameters,
    dt: f64,
    velocity: f64,
    acceleration: f64,
    sign: f64,
) -> Result<f64, DesignError> {
    let g = abc_to_alpha_beta_gamma(abc)?;
    require_stable_alpha_beta_gamma(g.alpha, g.beta, g.gamma)?;
    finite(&[velocity, acceleration])?;
    positive(dt)?;
    let AbcParameters { a, b, c } = abc;
    let (t, v, acc) = (dt, velocity, acceleration);
    let t2 = t * t;
    let t3 = t2 * t;
    let q = c * (a + b + c * a) - (1.0 + sign * c) * (1.0 + sign * c);
    let velocity_term =
        2.0 * (c - c * a - 1.0) * t3 * v * v / (a * (2.0 * a + b - 4.0) * (c - 1.0) * q);
    let acceleration_term =
        0.5 * acc * acc * t3 * t2 * (c * (a - 1.0) - 1.0) / (a * b * (1.0 + c) * q);
    result(velocity_term + acceleration_term)
}

fn check_circle(radius: f64, angular_rate: f64, dt: f64) -> Result<(), DesignError> {
    finite(&[radius, angular_rate])?;
    if radius < 0.0 {
        return Err(DesignError::NotPositive);
    }
    positive(dt)
}

/// Steady-state residual magnitude of an αβ filter (one per axis, x and y)
/// on a target circling at radius R with angular rate ω (Tenne & Singh
/// eq. 17, after Sklansky):
///
/// e = 4R sin²(ωT/2) / √([(2 − α)cos ωT + α + β − 2]² + α² sin² ωT).
///
/// It is R·|(z − 1)²/CP(z)| at z = e^{jωT} (eq. 15), constant from scan to
/// scan. For small ωT it tends to Rω²T²/β, eq. (19) with the centripetal
/// acceleration.
///
/// Errors: [`DesignError::Unstable`] outside the stability triangle,
/// [`DesignError::NotPositive`] for R < 0 or T ≤ 0.
pub fn alpha_beta_circular_error(
    alpha: f64,
    beta: f64,
    radius: f64,
    angular_rate: f64,
    dt: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta(alpha, beta)?;
    check_circle(radius, angular_rate, dt)?;
    let theta = angular_rate * dt;
    let half_sin = libm::sin(0.5 * theta);
    let (sin, cos) = libm::sincos(theta);
    let real = (2.0 - alpha) * cos + alpha + beta - 2.0;
    let denominator = libm::hypot(real, alpha * sin);
    result(4.0 * radius * half_sin * half_sin / denominator)
}

/// Steady-state residual magnitude of an αβγ filter on a circular path
/// (Tenne & Singh eq. 16, **as corrected here**):
///
/// e = 4R|sin³(ωT/2)| / √( sin²(ωT/2)·([(2 − α)cos ωT + α + β − 2]² + α² sin² ωT)
///                        + γ(γ(cos ωT + 1)/32 − (α/4) sin² ωT) ).
///
/// This is R·|(z − 1)³/CP(z)| at z = e^{jωT} (eq. 14), using
/// CP = (z − 1)·CP_αβ + (γ/4)z(z + 1). The printed eq. (16) leaves α² sin² ωT
/// outside the factor sin²(ωT/2), and in our copy the γ term falls outside the
/// root; neither version reduces to eq. (17) at γ = 0, as the paper says it
/// must, and neither matches the filter. The reading above does both.
///
/// Errors: [`DesignError::Unstable`] outside the stability volume,
/// [`DesignError::NotPositive`] for R < 0 or T ≤ 0.
pub fn alpha_beta_gamma_circular_error(
    alpha: f64,
    beta: f64,
    gamma: f64,
    radius: f64,
    angular_rate: f64,
    dt: f64,
) -> Result<f64, DesignError> {
    require_stable_alpha_beta_gamma(alpha, beta, gamma)?;
    check_circle(radius, angular_rate, dt)?;
    let theta = angular_rate * dt;
    let half_sin = libm::sin(0.5 * theta);
    let (sin, cos) = libm::sincos(theta);
    let real = (2.0 - alpha) * cos + alpha + beta - 2.0;
    let squared = half_sin * half_sin * (real * real + alpha * alpha * sin * sin)
        + gamma * (gamma * (cos + 1.0) / 32.0 - 0.25 * alpha * sin * sin);
    // |CP|² ≥ 0 and > 0 for stable gains; clamp a rounding-negative zero.
    let denominator = libm::sqrt(squared.max(0.0));
    let numerator = 4.0 * radius * libm::fabs(half_sin * half_sin * half_sin);
    if numerator == 0.0 {
        return Ok(0.0);
    }
    result(numerator / denominator)
}
