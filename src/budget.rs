//! The error budget: how far an `f32` or fixed-point run of a filter can drift
//! from the same run in `f64`.
//!
//! [`error_budget`] returns, for a filter with given gains, a representation
//! `S` and the magnitudes of a run ([`RunEnvelope`]), an upper bound on
//! `|x̂_S(k) − x̂_f64(k)|`, `|v̂_S(k) − v̂_f64(k)|` and `|â_S(k) − â_f64(k)|`
//! that holds at *every* update `k` of the run, however long. It is computed
//! on the target as well (the firmware self-tests check their own runs
//! against it): no heap, no panics, a bounded loop.
//!
//! # The derivation
//!
//! **Exact filter and error recursion.** Write the filter state after update
//! `k` as `s_k = (x_k, v_k, a_k)` (`a ≡ 0` for αβ). One update with interval
//! `T` and measurement `z` is (Al-Wagih & Abdulla eqs. (3)–(8); Tenne & Singh
//! eqs. (1)–(5)) `s_{k+1} = F_k(s_k) = A_k s_k + K_k z`, with the prediction
//! `Φ(T)`, the gains `K = (α, β/T, γ/(2T²))` and the closed-loop matrix
//! `A = (I − K·H)·Φ(T)`, `H = (1, 0, 0)`. Let `F_k` be the update evaluated in
//! exact (real) arithmetic on the `f64` inputs `z`, `T`, `α, β, γ`, and `F̃_k`
//! the update as representation `S` computes it (inputs converted to `S`,
//! every operation rounded). With the computed state `s̃_k`, define the local
//! error `δ_k = F̃_k(s̃_k) − F_k(s̃_k)`. Because `F_k` is affine in the state,
//! the accumulated error `d_k = s̃_k − s_k` obeys, *exactly*,
//!
//! ```text
//! d_{k+1} = A_k d_k + δ_k .
//! ```
//!
//! **Step 1: the local error `δ_k`** (running error analysis). Each
//! intermediate of the update, in the library's evaluation order
//! (`StepGains::new` once per interval, then `KinematicFilter::update_step`),
//! is tracked as a pair (bound `M` on its exact magnitude, bound `E` on its
//! computed error), using the rounding model of the intermediate's own
//! quantity, [`Quantity::UNIT_ROUNDOFF`] and [`Quantity::ABS_RESOLUTION`]
//! (`u`, `ε`; per quantity for the fast fixed point, see
//! `docs/numerics-fixed-point.md`):
//!
//! * input (conversion from `f64`): `E = u·M + ε/2`;
//! * `a ± b`: `E = E_a + E_b + u·(M + E_a + E_b)` (fixed point: exact);
//! * `a × b`: `E = M_a E_b + M_b E_a + E_a E_b`, plus `u·(M + that) + ε`;
//! * `a ÷ d`, `d ≥ d_min`: `E = E_a/(d_min − E_d) + M_a E_d/(d_min(d_min − E_d))`,
//!   plus the rounding of the quotient.
//!
//! The magnitudes come from the [`RunEnvelope`] (`M` of a sum is the smaller of
//! `M_a + M_b` and the envelope's bound on the quantity it is, e.g. a
//! predicted position). So for floats every operation injects
//! (unit roundoff × the magnitude it handles), and for fixed formats every
//! product and quotient injects one step of its result's format, the
//! per-interval gains β/T and γ/(2T²) carry the rounding of their division,
//! and the inputs are quantised to half a step. The rounding of the gains
//! multiplies the residual, so the residual's magnitude is part of the
//! envelope.
//!
//! The first two updates (two-point initialisation, Al-Wagih eqs. (9)–(10))
//! inject the initial error `d_2 = (E_z, E[(z₂ − z₁)/T], 0)`.
//!
//! **Step 2: propagation, constant interval and gains.** In the scaled
//! coordinates `y = W d`, `W = diag(1, T₀, T₀²)` (all components in metres),
//! the closed-loop matrix of an update with interval `T = r·T₀` is
//!
//! ```text
//! Ā(r, g)_ij = r^(j−i) · (Φ̄_ij − g_i c_j),   g = (α, β, γ/2),  c = (1, 1, ½),
//! Φ̄ = [[1, 1, ½], [0, 1, 1], [0, 0, 1]],
//! ```
//!
//! which at `r = 1` depends on the gains only (its characteristic polynomial
//! is the denominator of Tenne & Singh eq. (6); of Al-Wagih eq. (11) for αβ).
//! With `T` and the gains constant, `y_k = Σ_j Ā₀^(k−1−j) Wδ_j + Ā₀^(k−2) y_2`,
//! hence, componentwise and for every `k`,
//!
//! ```text
//! |y_k| ≤ L · η,   L = Σ_{n≥0} |Ā₀ⁿ|   (entrywise absolute values),
//! ```
//!
//! where `η` is the componentwise maximum of `|Wδ_k|` and `|y_2|`. `L` is the
//! ℓ1 norm of the impulse response of the error dynamics; it is finite
//! because the gains lie inside the stability region (Al-Wagih eqs. (12)–(14),
//! Tenne & Singh eqs. (7)–(8)). It is computed by summing `|Ā₀ⁿ|` until
//! `g = ‖Ā₀ᴺ‖∞ ≤ 2⁻³⁰`; the rest is bounded by writing `n = j + mN`
//! (`j < N`, `m ≥ 1`): `|Ā₀ⁿ| ≤ |Ā₀ʲ|·|Ā₀ᴺ|ᵐ`, so every entry of the tail is at
//! most `‖S_N‖∞ · g/(1 − g)` (`S_N` the partial sum), which is added to every
//! entry. At most [`MAX_TERMS`] powers are summed; gains whose slowest mode
//! decays slower than that (a pole within about 10⁻⁴ of the unit circle) are
//! refused with [`BudgetError::SlowDecay`]. (`MAX_TERMS` = 2¹⁸ reaches
//! `2⁻³⁰` for a slowest pole up to about `1 − 8·10⁻⁵` in modulus.)
//!
//! **Step 3: varying interval and varying gains** (small-gain argument). When
//! the interval varies in `[dt_min, dt_max]` (and, for
//! [`error_budget_varying_gains`], each gain in nominal ± spread),
//! `T₀ = √(dt_min·dt_max)` and every step's matrix is `Ā₀ + E_k` with
//! `|E_k| ≤ Ē` entrywise. `Ē` is exact: each entry is bilinear in `r^(j−i)`
//! and `g_i`, so the largest deviation sits at a corner of the box. Then
//! `y_{k+1} = Ā₀ y_k + (E_k y_k + Wδ_k)` and, with `Y` the componentwise
//! maximum of `|y_k|` over the run,
//!
//! ```text
//! Y ≤ L·(Ē·Y + η)   ⇒   Y ≤ (I − LĒ)⁻¹ · L · η   if ρ(LĒ) < 1.
//! ```
//!
//! `ρ(LĒ) < 1` is certified by a vector `x > 0` with `LĒ·x ≤ (1 − 10⁻⁹)·x`;
//! without a certificate the budget is refused
//! ([`BudgetError::NotContractive`]): the interval (or gain) spread is too
//! wide for this argument, and indeed an αβ filter whose interval jumps
//! between 0.05 s and 20 s can be unstable, so no bound exists in general.
//! For well-damped gains (α = 0.5, β = 0.3; Benedict–Bordner α ≤ 0.5) interval
//! ratios dt_max/dt_min up to about 2 are certified; near the edges of the
//! stability region a few per cent or less.
//!
//! *Gain schedules.* A schedule that keeps the gains within nominal ± spread is
//! covered by [`error_budget_varying_gains`]; its local error uses the largest
//! gains. A schedule whose gains sweep a wide range (least-squares gains
//! α(n) = 2(2n−1)/(n(n+1)), Al-Wagih eq. (24)) is not contractive around any
//! single nominal; bound it per stretch of near-constant gains, each stretch
//! starting from the previous stretch's bound as its initial error.
//!
//! *Coasts* are not covered. A coast followed by an update at interval `T` is,
//! for the error dynamics, one update at interval `(c+1)T` with gains
//! `(α, (c+1)β, (c+1)²γ)` (`c` coasts), plus the rounding of the extra
//! predictions, which the local error above does not include.
//!
//! **Step 4: against f64.** `|S − f64| ≤ |S − exact| + |f64 − exact|`. The
//! second term is the same analysis with `f64` rounding, doubled so that it
//! also covers an independent `f64` implementation of the same equations in a
//! different evaluation order (the host-tests reference). A fixed-point
//! estimate is compared after conversion to `f64`, which adds 2⁻⁵³ relative.
//!
//! **Where the magnitudes come from.** The envelope must bound the values of
//! the `S` run (measurements, predictions, estimates, residuals). Given the
//! magnitudes of the `f64` run instead, [`error_budget_around_reference`]
//! widens them by twice a first bound `B` and recomputes: if the new bound is
//! at most `2B`, induction over the updates shows the `S` run never leaves the
//! widened envelope, so the new bound holds.
//!
//! **Cost.** Two straight-line error analyses and one loop of at most
//! [`MAX_TERMS`] 3×3 matrix products (60–100 for α = 0.5, β = 0.3; a few
//! thousand near the edges of the region; 4·10⁴ for α = 0.001); no heap.
//!
//! **What it is not.** A worst case over all rounding patterns, not an
//! estimate. For well-damped gains the measured deviations are typically 5 to
//! 50 times below it (a few hundred where a component happens to be computed
//! almost exactly). For very slow gains (α ≤ 0.01) the unbiased rounding of floats
//! averages out and f32 stays 10³–10⁵ times below the bound, while Q32.32
//! multiplication rounds toward −∞, a bias that accumulates, and gets within a
//! factor of about 2 of it (the `precision` tool and the tests in host-tests
//! print both and their ratio). It bounds arithmetic deviation only, not the
//! tracking error of the filter itself.

use core::any::TypeId;

use crate::filter::Gains;
use crate::num::{Numeric, Quantity};

/// At most this many powers of the closed-loop matrix are summed for the ℓ1
/// norm of the impulse response (see the module docs, step 2).
pub const MAX_TERMS: u32 = 1 << 18;

/// The tail of the impulse response is bounded once `‖Āᴺ‖∞` is below this.
const TAIL_NORM: f64 = 1.0 / (1u64 << 30) as f64;

/// Margin of the certificate ρ(LĒ) ≤ 1 − `CONTRACTION_MARGIN`.
const CONTRACTION_MARGIN: f64 = 1e-9;

/// Relative allowance for the budget's own `f64` arithmetic (sums of a few
/// thousand nonnegative terms and one 3×3 solve: far below 10⁻¹⁰).
const OWN_ROUNDING: f64 = 1e-9;

/// The magnitudes of one run, which the per-step rounding errors scale with.
///
/// All fields are bounds on absolute values over the whole run, in metres and
/// seconds. They must hold for the run in the representation being bounded;
/// see [`error_budget_around_reference`] to start from an `f64` run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RunEnvelope {
    /// Bounds `|z|`, the predicted positions `|x_p|` and the estimates `|x_s|`.
    pub max_position: f64,
    /// Bounds `|v_p|`, `|v_s|`, including the two-point velocity (Al-Wagih
    /// eq. (9)).
    pub max_velocity: f64,
    /// Bounds `|a_s|` (αβγ only; ignored for αβ).
    pub max_acceleration: f64,
    /// Bounds the residual `|z − x_p|` (Al-Wagih eq. (4)).
    pub max_residual: f64,
    /// Shortest interval between updates (> 0).
    pub dt_min: f64,
    /// Longest interval between updates (≥ `dt_min`).
    pub dt_max: f64,
}

impl RunEnvelope {
    /// The envelope widened by `factor` times `bound`: what the values of a run
    /// that stays within `factor·bound` of this one can reach. Predictions and
    /// residuals move by the position error plus the extrapolated velocity and
    /// acceleration errors.
    pub fn widened(&self, bound: &ErrorBound, factor: f64) -> RunEnvelope {
        let p = factor * bound.position;
        let v = factor * bound.velocity;
        let a = factor * bound.acceleration;
        let t = self.dt_max;
        let predicted = p + t * v + 0.5 * t * t * a;
        RunEnvelope {
            max_position: self.max_position + predicted,
            max_velocity: self.max_velocity + v + t * a,
            max_acceleration: self.max_acceleration + a,
            max_residual: self.max_residual + predicted,
            ..*self
        }
    }

    fn is_valid(&self) -> bool {
        let nonneg = |v: f64| v.is_finite() && v >= 0.0;
        nonneg(self.max_position)
            && nonneg(self.max_velocity)
            && nonneg(self.max_acceleration)
            && nonneg(self.max_residual)
            && self.dt_min.is_finite()
            && self.dt_min > 0.0
            && self.dt_max.is_finite()
            && self.dt_max >= self.dt_min
    }
}

/// How far each gain of a schedule may move from the nominal gains
/// (absolute, ≥ 0). All zero for fixed gains.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GainSpread {
    /// Largest |α − α_nominal| (dimensionless).
    pub alpha: f64,
    /// Largest |β − β_nominal| (dimensionless).
    pub beta: f64,
    /// Tenne & Singh's γ (the acceleration correction is γ/(2T²)·e).
    pub gamma: f64,
}

/// An upper bound on the deviation of an estimate from the `f64` run, valid at
/// every update of the run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ErrorBound {
    /// Metres.
    pub position: f64,
    /// Metres per second.
    pub velocity: f64,
    /// Metres per second²; zero for αβ.
    pub acceleration: f64,
    /// `‖L‖∞`: how much the error dynamics amplify a per-step error (in the
    /// scaled coordinates of the module docs; ≥ 1).
    pub amplification: f64,
    /// Powers of the closed-loop matrix summed before the tail bound.
    pub terms: u32,
}

impl ErrorBound {
    /// Whether measured deviations (absolute values) lie within the bound.
    pub fn covers(&self, position: f64, velocity: f64, acceleration: f64) -> bool {
        libm::fabs(position) <= self.position
            && libm::fabs(velocity) <= self.velocity
            && libm::fabs(acceleration) <= self.acceleration
    }
}

/// Why no budget could be computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BudgetError {
    /// `ORDER` is neither 2 (αβ) nor 3 (αβγ).
    UnsupportedOrder,
    /// αβγ gains for an αβ filter, αβ gains (γ = 0) for an αβγ filter, or a γ
    /// spread for an αβ filter.
    GainsDoNotMatchOrder,
    /// A magnitude is negative or not finite, `dt_min ≤ 0` or
    /// `dt_max < dt_min`, or a spread is negative or not finite.
    InvalidEnvelope,
    /// An intermediate of the update can leave the representation's range:
    /// the run may saturate, and saturated updates are refused, not bounded.
    MayOverflow,
    /// The error dynamics decay too slowly to sum within [`MAX_TERMS`] powers
    /// (gains very close to the edge of the stability region).
    SlowDecay,
    /// The interval or gain spread is too wide for the small-gain argument.
    NotContractive,
    /// Widening the envelope by the first bound changed the bound by more than
    /// a factor 2: the errors are not small against the magnitudes.
    NotSelfConsistent,
}

impl core::fmt::Display for BudgetError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            BudgetError::UnsupportedOrder => "filter order must be 2 or 3",
            BudgetError::GainsDoNotMatchOrder => "gains do not match the filter order",
            BudgetError::InvalidEnvelope => "run envelope or gain spread is invalid",
            BudgetError::MayOverflow => "the run may overflow the number format",
            BudgetError::SlowDecay => "error dynamics decay too slowly to bound",
            BudgetError::NotContractive => "interval or gain spread too wide to bound",
            BudgetError::NotSelfConsistent => "errors are not small against the run's magnitudes",
        })
    }
}

impl core::error::Error for BudgetError {}

/// Bound on `|estimate_S − estimate_f64|` for a run with fixed gains (module
/// docs, steps 1–4). `ORDER` is 2 (αβ) or 3 (αβγ); `envelope` must bound the
/// `S` run's values.
pub fn error_budget<N: Numeric, const ORDER: usize>(
    gains: &Gains<f64>,
    envelope: &RunEnvelope,
) -> Result<ErrorBound, BudgetError> {
    error_budget_varying_gains::<N, ORDER>(gains, &GainSpread::default(), envelope)
}

/// Bound for a run whose gains stay within `nominal ± spread` at every update
/// (a gain schedule; module docs, step 3).
pub fn error_budget_varying_gains<N: Numeric, const ORDER: usize>(
    nominal: &Gains<f64>,
    spread: &GainSpread,
    envelope: &RunEnvelope,
) -> Result<ErrorBound, BudgetError> {
    let order3 = match ORDER {
        2 => false,
        3 => true,
        _ => return Err(BudgetError::UnsupportedOrder),
    };
    let spreads_ok = [spread.alpha, spread.beta, spread.gamma]
        .iter()
        .all(|s| s.is_finite() && *s >= 0.0);
    if !envelope.is_valid() || !spreads_ok {
        return Err(BudgetError::InvalidEnvelope);
    }
    let (alpha, beta, gamma) = (nominal.alpha(), nominal.beta(), nominal.gamma());
    if order3 != (gamma > 0.0) || (!order3 && spread.gamma > 0.0) {
        return Err(BudgetError::GainsDoNotMatchOrder);
    }
    let n = if order3 { 3 } else { 2 };

    // Step 1: per-step and initial errors, physical units.
    let largest = [
        alpha + spread.alpha,
        beta + spread.beta,
        gamma + spread.gamma,
    ];
    let local_s = local_errors::<N>(order3, envelope, &largest)?;
    let local_f64 = local_errors::<f64>(order3, envelope, &largest)?;

    // Step 2: ℓ1 norm of the impulse response at the nominal gains.
    let t0 = if envelope.dt_min == envelope.dt_max {
        envelope.dt_min
    } else {
        libm::sqrt(envelope.dt_min * envelope.dt_max)
    };
    let g0 = [alpha, beta, gamma / 2.0];
    let a0 = scaled_matrix(n, 1.0, &g0);
    let (l1, terms) = impulse_l1(n, &a0)?;

    // Step 3: deviation of every step's matrix from the nominal one.
    let r_lo = envelope.dt_min / t0;
    let r_hi = envelope.dt_max / t0;
    let g_spread = [spread.alpha, spread.beta, spread.gamma / 2.0];
    let dev = deviation_bound(n, r_lo, r_hi, &g0, &g_spread);
    let gain = mat_mul(n, &l1, &dev);
    let perturbed = dev.iter().flatten().any(|&d| d > 0.0);

    let propagate = |local: &Local| -> Result<[f64; 3], BudgetError> {
        let w = [1.0, t0, t0 * t0];
        let mut eta = [0.0; 3];
        for (((e, w), step), init) in eta
            .iter_mut()
            .zip(w)
            .zip(local.step)
            .zip(local.init)
            .take(n)
        {
            *e = w * max(step, init);
        }
        let direct = mat_vec(n, &l1, &eta);
        if perturbed {
            small_gain(n, &gain, &direct)
        } else {
            Ok(direct)
        }
    };
    let y_s = propagate(&local_s)?;
    let y_f64 = propagate(&local_f64)?;

    // Step 4: S against exact, plus f64 against exact (doubled), back in
    // physical units, plus the conversion of the estimate to f64.
    let to_f64 = <f64 as Quantity>::UNIT_ROUNDOFF;
    let scale = [1.0, 1.0 / t0, 1.0 / (t0 * t0)];
    let magnitude = [
        envelope.max_position,
        envelope.max_velocity,
        if order3 {
            envelope.max_acceleration
        } else {
            0.0
        },
    ];
    let mut total = [0.0; 3];
    let parts = y_s.iter().zip(y_f64).zip(scale).zip(magnitude);
    for (t, (((s, f), scale), magnitude)) in total.iter_mut().zip(parts).take(n) {
        let y = (s + 2.0 * f) * (1.0 + OWN_ROUNDING);
        *t = y * scale + to_f64 * magnitude;
    }
    if total.iter().any(|t| !t.is_finite()) {
        return Err(BudgetError::MayOverflow);
    }
    Ok(ErrorBound {
        position: total[0],
        velocity: total[1],
        acceleration: if order3 { total[2] } else { 0.0 },
        amplification: inf_norm(n, &l1),
        terms,
    })
}

/// The closed-loop error matrix `Ā₀` of the module docs (scaled coordinates,
/// `T = T₀`): `n×n` in the top-left corner, zero elsewhere. Its characteristic
/// polynomial is the denominator of Tenne & Singh eq. (6) (Al-Wagih eq. (11)
/// for αβ).
pub fn closed_loop_matrix<const ORDER: usize>(
    gains: &Gains<f64>,
) -> Result<[[f64; 3]; 3], BudgetError> {
    let n = match ORDER {
        2 => 2,
        3 => 3,
        _ => return Err(BudgetError::UnsupportedOrder),
    };
    if (n == 3) != (gains.gamma() > 0.0) {
        return Err(BudgetError::GainsDoNotMatchOrder);
    }
    let g = [gains.alpha(), gains.beta(), gains.gamma() / 2.0];
    Ok(scaled_matrix(n, 1.0, &g))
}

/// Bound for a run of representation `S` given the magnitudes of the same run
/// in `f64` (the reference): the envelope is widened by twice a first bound
/// and the bound recomputed, which must stay within that factor two (module
/// docs, "Where the magnitudes come from").
pub fn error_budget_around_reference<N: Numeric, const ORDER: usize>(
    gains: &Gains<f64>,
    spread: &GainSpread,
    reference: &RunEnvelope,
) -> Result<ErrorBound, BudgetError> {
    let first = error_budget_varying_gains::<N, ORDER>(gains, spread, reference)?;
    let widened = reference.widened(&first, 2.0);
    let second = error_budget_varying_gains::<N, ORDER>(gains, spread, &widened)?;
    let closes = second.position <= 2.0 * first.position
        && second.velocity <= 2.0 * first.velocity
        && second.acceleration <= 2.0 * first.acceleration;
    if closes {
        Ok(second)
    } else {
        Err(BudgetError::NotSelfConsistent)
    }
}

// ---------------------------------------------------------------------------
// Step 1: running error analysis of one update.

/// A computed quantity: bound on its exact magnitude and on its error.
#[derive(Clone, Copy)]
struct Tracked {
    mag: f64,
    err: f64,
}

/// The rounding model of one quantity ([`Quantity::UNIT_ROUNDOFF`],
/// [`Quantity::ABS_RESOLUTION`]) and its range.
#[derive(Clone, Copy)]
struct Model {
    unit: f64,
    abs: f64,
    fits: fn(f64) -> bool,
}

fn model<Q: Quantity>() -> Model {
    Model {
        unit: Q::UNIT_ROUNDOFF,
        abs: Q::ABS_RESOLUTION,
        fits: |v| v.is_finite() && Q::try_from_f64(v).is_ok(),
    }
}

/// A flag raised when an intermediate may not fit its quantity's range.
struct Analysis {
    overflow: bool,
}

const NO_CAP: f64 = f64::INFINITY;

impl Analysis {
    fn checked(&mut self, q: Model, t: Tracked) -> Tracked {
        if !(q.fits)(t.mag + t.err) {
            self.overflow = true;
        }
        t
    }

    /// A value of the run converted from `f64` (measurement, interval, gain).
    fn input(&mut self, q: Model, mag: f64) -> Tracked {
        let t = Tracked {
            mag,
            err: q.unit * mag + q.abs / 2.0,
        };
        self.checked(q, t)
    }

    /// A value already held exactly (the state).
    fn exact(&mut self, q: Model, mag: f64) -> Tracked {
        self.checked(q, Tracked { mag, err: 0.0 })
    }

    /// `a` converted to another quantity of the same value (rounded once).
    fn convert(&mut self, q: Model, a: Tracked) -> Tracked {
        let err = a.err + q.unit * (a.mag + a.err) + q.abs / 2.0;
        self.checked(q, Tracked { mag: a.mag, err })
    }

    fn add(&mut self, q: Model, a: Tracked, b: Tracked, cap: f64) -> Tracked {
        let mag = min(a.mag + b.mag, cap);
        let e = a.err + b.err;
        // Fixed-point sums are exact (unit = 0); float sums never underflow
        // inexactly, so no absolute term.
        let err = e + q.unit * (mag + e);
        self.checked(q, Tracked { mag, err })
    }

    fn mul(&mut self, q: Model, a: Tracked, b: Tracked, cap: f64) -> Tracked {
        let mag = min(a.mag * b.mag, cap);
        let e = a.mag * b.err + b.mag * a.err + a.err * b.err;
        let err = e + q.unit * (mag + e) + q.abs;
        self.checked(q, Tracked { mag, err })
    }

    /// `a / d` with the exact divisor `d ≥ d_min > d.err`.
    fn div(&mut self, q: Model, a: Tracked, d: Tracked, d_min: f64, cap: f64) -> Tracked {
        let slack = d_min - d.err;
        if slack <= 0.0 {
            self.overflow = true;
            return Tracked {
                mag: f64::INFINITY,
                err: f64::INFINITY,
            };
        }
        let mag = min(a.mag / d_min, cap);
        let e = a.err / slack + a.mag * d.err / (d_min * slack);
        let err = e + q.unit * (mag + e) + q.abs;
        self.checked(q, Tracked { mag, err })
    }

    /// The product `a·b` of a guarded `q + a·b` (rounded like a product);
    /// when the number system forms the sum in a wider word (`fused`), the
    /// product alone need not fit its quantity, only the sum is checked.
    fn term(&mut self, fused: bool, q: Model, a: Tracked, b: Tracked, cap: f64) -> Tracked {
        if fused {
            let mag = min(a.mag * b.mag, cap);
            let e = a.mag * b.err + b.mag * a.err + a.err * b.err;
            Tracked {
                mag,
                err: e + q.unit * (mag + e) + q.abs,
            }
        } else {
            self.mul(q, a, b, cap)
        }
    }

    /// `a/2`: exact in floating formats, half a step in fixed ones.
    fn half(&mut self, q: Model, a: Tracked) -> Tracked {
        let t = Tracked {
            mag: a.mag / 2.0,
            err: a.err / 2.0 + q.abs / 2.0,
        };
        self.checked(q, t)
    }
}

struct Local {
    /// Error injected by one filtered update: position, velocity, acceleration.
    step: [f64; 3],
    /// Error of the state after the two-point initialisation.
    init: [f64; 3],
}

/// Local errors of number system `N`, mirroring the evaluation order of
/// `StepGains::new` (once per interval) and `KinematicFilter::update_step`
/// (per update) operation by operation, each result rounded with the model
/// of its quantity.
fn local_errors<N: Numeric>(
    order3: bool,
    env: &RunEnvelope,
    gains: &[f64; 3],
) -> Result<Local, BudgetError> {
    let length = model::<N::Length>();
    let speed = model::<N::Speed>();
    let acceleration = model::<N::Acceleration>();
    let interval = model::<N::Interval>();
    let interval2 = model::<N::IntervalSquared>();
    let ratio = model::<N::Ratio>();
    let gain = model::<N::Gain>();
    let rate = model::<N::Rate>();
    let rate2 = model::<N::RateSquared>();
    let mut an = Analysis { overflow: false };
    // Whether the hot path's q + a·b narrows only the sum (the fast fixed
    // point) or also the product (sticky operators).
    let fused = N::FUSED_PRODUCTS;
    let pos_cap = env.max_position;
    let vel_cap = env.max_velocity;
    let acc_cap = if order3 { env.max_acceleration } else { 0.0 };

    let x = an.exact(length, pos_cap);
    let v = an.exact(speed, vel_cap);
    let a = an.exact(acceleration, acc_cap);
    let dt = an.input(interval, env.dt_max);
    let z = an.input(length, pos_cap);

    // StepGains::new: α (converted to the per-update gain type where that is
    // another type), β/T, and for αβγ γ/(T² + T²) and T²/2.
    let alpha_ratio = an.input(ratio, gains[0]);
    let alpha = if TypeId::of::<N::Gain>() == TypeId::of::<N::Ratio>() {
        alpha_ratio
    } else {
        an.convert(gain, alpha_ratio)
    };
    let beta = an.input(ratio, gains[1]);
    let velocity_gain = an.div(rate, beta, dt, env.dt_min, NO_CAP);

    // Filtered update (Tenne & Singh eqs. (1)–(5); Al-Wagih eqs. (3)–(8)).
    let step = if order3 {
        let gamma = an.input(ratio, gains[2]);
        let squared = an.mul(interval2, dt, dt, NO_CAP);
        let double = an.add(interval2, squared, squared, NO_CAP);
        let dt_min2 = env.dt_min * env.dt_min;
        let acceleration_gain = an.div(rate2, gamma, double, 2.0 * dt_min2, NO_CAP);
        let half_squared = an.half(interval2, squared);
        // x_p = (x + v·T) + a·(T²/2); v_p = v + a·T
        let v_t = an.term(fused, length, v, dt, NO_CAP);
        let first = an.add(length, x, v_t, NO_CAP);
        let a_t2 = an.term(fused, length, a, half_squared, NO_CAP);
        let x_p = an.add(length, first, a_t2, pos_cap);
        let a_t = an.term(fused, speed, a, dt, NO_CAP);
        let v_p = an.add(speed, v, a_t, vel_cap);
        let e = an.add(length, z, x_p, env.max_residual);
        // x_s = x_p + α·e; v_s = v_p + (β/T)·e; a_s = a + (γ/(2T²))·e
        let alpha_e = an.term(fused, length, alpha, e, NO_CAP);
        let x_s = an.add(length, x_p, alpha_e, pos_cap);
        let dv = an.term(fused, speed, velocity_gain, e, NO_CAP);
        let v_s = an.add(speed, v_p, dv, vel_cap);
        let da = an.term(fused, acceleration, acceleration_gain, e, NO_CAP);
        let a_s = an.add(acceleration, a, da, acc_cap);
        [x_s.err, v_s.err, a_s.err]
    } else {
        let v_t = an.term(fused, length, v, dt, NO_CAP);
        let x_p = an.add(length, x, v_t, pos_cap);
        let e = an.add(length, z, x_p, env.max_residual);
        let alpha_e = an.term(fused, length, alpha, e, NO_CAP);
        let x_s = an.add(length, x_p, alpha_e, pos_cap);
        let dv = an.term(fused, speed, velocity_gain, e, NO_CAP);
        let v_s = an.add(speed, v, dv, vel_cap);
        [x_s.err, v_s.err, 0.0]
    };

    // Two-point initialisation (Al-Wagih eqs. (9)–(10)): x = z₁, then
    // v = (z₂ − x)/(0 + dt), x = z₂; the acceleration starts at zero in both.
    let z1 = an.input(length, pos_cap);
    let z2 = an.input(length, pos_cap);
    let zero = an.exact(interval, 0.0);
    let elapsed = an.add(interval, zero, dt, NO_CAP);
    let diff = an.add(length, z2, z1, vel_cap * env.dt_max);
    let v2 = an.div(speed, diff, elapsed, env.dt_min, vel_cap);
    let init = [z2.err, v2.err, 0.0];

    if an.overflow {
        return Err(BudgetError::MayOverflow);
    }
    Ok(Local { step, init })
}

// ---------------------------------------------------------------------------
// Steps 2 and 3: the error dynamics.

type Mat = [[f64; 3]; 3];

fn min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

fn max(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// `r^p` for `p` in −2..=2.
fn power(r: f64, p: i32) -> f64 {
    match p {
        0 => 1.0,
        1 => r,
        2 => r * r,
        -1 => 1.0 / r,
        -2 => 1.0 / (r * r),
        _ => 0.0,
    }
}

/// Entry (i, j) of a matrix; zero outside it. (Reads and writes go through
/// these so that no index can panic.)
fn at(m: &Mat, i: usize, j: usize) -> f64 {
    m.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0)
}

fn put(m: &mut Mat, i: usize, j: usize, v: f64) {
    if let Some(x) = m.get_mut(i).and_then(|row| row.get_mut(j)) {
        *x = v;
    }
}

/// Entry i of a vector; zero outside it.
fn entry(v: &[f64; 3], i: usize) -> f64 {
    v.get(i).copied().unwrap_or(0.0)
}

/// `Φ̄_ij − g_i c_j` (module docs, step 2).
fn gain_part(i: usize, j: usize, g: &[f64; 3]) -> f64 {
    let phi = match j.wrapping_sub(i) {
        0 | 1 => 1.0,
        2 => 0.5,
        _ => 0.0,
    };
    let c = if j == 2 { 0.5 } else { 1.0 };
    phi - entry(g, i) * c
}

/// `r^(j − i)`.
fn power_of(r: f64, i: usize, j: usize) -> f64 {
    // Indices of a 3×3 matrix: the difference cannot wrap.
    power(r, (j as i32).wrapping_sub(i as i32))
}

/// The closed-loop error matrix Ā(r, g) in scaled coordinates.
fn scaled_matrix(n: usize, r: f64, g: &[f64; 3]) -> Mat {
    let mut m = [[0.0; 3]; 3];
    for i in 0..n {
        for j in 0..n {
            put(&mut m, i, j, power_of(r, i, j) * gain_part(i, j, g));
        }
    }
    m
}

/// Entrywise `sup |Ā(r, g) − Ā(1, g₀)|` over `r ∈ [r_lo, r_hi]` and
/// `g ∈ g₀ ± spread`: each entry is bilinear in `r^(j−i)` and `g_i`, so the
/// supremum is at one of four corners.
fn deviation_bound(n: usize, r_lo: f64, r_hi: f64, g0: &[f64; 3], spread: &[f64; 3]) -> Mat {
    let mut d = [[0.0; 3]; 3];
    for i in 0..n {
        let mut g_lo = *g0;
        let mut g_hi = *g0;
        if let (Some(lo), Some(hi)) = (g_lo.get_mut(i), g_hi.get_mut(i)) {
            *lo -= entry(spread, i);
            *hi += entry(spread, i);
        }
        for j in 0..n {
            let nominal = gain_part(i, j, g0);
            let mut worst: f64 = 0.0;
            for r in [r_lo, r_hi] {
                for g in [&g_lo, &g_hi] {
                    let v = power_of(r, i, j) * gain_part(i, j, g) - nominal;
                    worst = max(worst, libm::fabs(v));
                }
            }
            put(&mut d, i, j, worst);
        }
    }
    d
}

fn mat_mul(n: usize, a: &Mat, b: &Mat) -> Mat {
    let mut c = [[0.0; 3]; 3];
    for i in 0..n {
        for j in 0..n {
            let s = (0..n).map(|k| at(a, i, k) * at(b, k, j)).sum();
            put(&mut c, i, j, s);
        }
    }
    c
}

fn mat_vec(n: usize, a: &Mat, x: &[f64; 3]) -> [f64; 3] {
    let mut y = [0.0; 3];
    for (i, y_i) in y.iter_mut().enumerate().take(n) {
        *y_i = (0..n).map(|j| at(a, i, j) * entry(x, j)).sum();
    }
    y
}

fn inf_norm(n: usize, a: &Mat) -> f64 {
    let mut worst: f64 = 0.0;
    for row in a.iter().take(n) {
        let s: f64 = row.iter().take(n).map(|v| libm::fabs(*v)).sum();
        worst = max(worst, s);
    }
    worst
}

/// `L = Σ_{n≥0} |Āⁿ|` with the tail bound of the module docs, and the number
/// of terms summed.
fn impulse_l1(n: usize, a: &Mat) -> Result<(Mat, u32), BudgetError> {
    let mut power_n = [[0.0; 3]; 3];
    for i in 0..n {
        put(&mut power_n, i, i, 1.0);
    }
    let mut sum = [[0.0; 3]; 3];
    for term in 1..=MAX_TERMS {
        for (sum_row, power_row) in sum.iter_mut().zip(power_n.iter()).take(n) {
            for (s, p) in sum_row.iter_mut().zip(power_row.iter()).take(n) {
                *s += libm::fabs(*p);
            }
        }
        power_n = mat_mul(n, a, &power_n);
        let g = inf_norm(n, &power_n);
        if !g.is_finite() {
            return Err(BudgetError::SlowDecay);
        }
        if g <= TAIL_NORM {
            let tail = inf_norm(n, &sum) * g / (1.0 - g);
            for row in sum.iter_mut().take(n) {
                for v in row.iter_mut().take(n) {
                    *v += tail;
                }
            }
            return Ok((sum, term));
        }
    }
    Err(BudgetError::SlowDecay)
}

/// Solves `(I − m)·y = c` by Gaussian elimination with partial pivoting
/// (the augmented matrix's rows are `[I − m | c]`).
fn solve_i_minus(n: usize, m: &Mat, c: &[f64; 3]) -> Option<[f64; 3]> {
    let n = n.min(3);
    let mut a = [[0.0; 4]; 3];
    for (i, row) in a.iter_mut().enumerate().take(n) {
        for (j, v) in row.iter_mut().enumerate().take(n) {
            *v = if i == j { 1.0 } else { 0.0 } - at(m, i, j);
        }
        if let Some(last) = row.get_mut(3) {
            *last = entry(c, i);
        }
    }
    let get = |a: &[[f64; 4]; 3], i: usize, j: usize| {
        a.get(i).and_then(|r| r.get(j)).copied().unwrap_or(0.0)
    };
    for col in 0..n {
        let mut pivot = col;
        for row in col.saturating_add(1)..n {
            if libm::fabs(get(&a, row, col)) > libm::fabs(get(&a, pivot, col)) {
                pivot = row;
            }
        }
        // Swap rows `col` and `pivot`.
        if let (Some(&pivot_row), Some(&col_row)) = (a.get(pivot), a.get(col)) {
            if let Some(r) = a.get_mut(col) {
                *r = pivot_row;
            }
            if let Some(r) = a.get_mut(pivot) {
                *r = col_row;
            }
        }
        let p = get(&a, col, col);
        if p == 0.0 || p.is_nan() {
            return None;
        }
        let pivot_row = a.get(col).copied().unwrap_or([0.0; 4]);
        for row in a
            .iter_mut()
            .skip(col.saturating_add(1))
            .take(n.saturating_sub(col.saturating_add(1)))
        {
            let f = row.get(col).copied().unwrap_or(0.0) / p;
            for (v, pv) in row.iter_mut().zip(pivot_row.iter()).skip(col) {
                *v -= f * pv;
            }
        }
    }
    let mut y = [0.0; 3];
    for i in (0..n).rev() {
        let s = get(&a, i, 3)
            - (i.saturating_add(1)..n)
                .map(|j| get(&a, i, j) * entry(&y, j))
                .sum::<f64>();
        if let Some(y_i) = y.get_mut(i) {
            *y_i = s / get(&a, i, i);
        }
    }
    if y.iter().all(|v| v.is_finite()) {
        Some(y)
    } else {
        None
    }
}

/// `(I − m)⁻¹·c` for a nonnegative `m` (= LĒ) after certifying ρ(m) < 1 with
/// `x = (I − m)⁻¹·1 > 0` and `m·x ≤ (1 − margin)·x`.
fn small_gain(n: usize, m: &Mat, c: &[f64; 3]) -> Result<[f64; 3], BudgetError> {
    let ones = [1.0; 3];
    let x = solve_i_minus(n, m, &ones).ok_or(BudgetError::NotContractive)?;
    let mx = mat_vec(n, m, &x);
    for (x_i, mx_i) in x.iter().zip(mx.iter()).take(n) {
        if !(*x_i > 0.0 && *mx_i <= (1.0 - CONTRACTION_MARGIN) * *x_i) {
            return Err(BudgetError::NotContractive);
        }
    }
    let mut y = solve_i_minus(n, m, c).ok_or(BudgetError::NotContractive)?;
    // (I − m)⁻¹ ≥ 0 and c ≥ 0, so y ≥ 0 up to the solve's rounding.
    for v in y.iter_mut() {
        *v = max(*v, 0.0);
    }
    Ok(y)
}
