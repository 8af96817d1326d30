//! The smoothing gains (α, β, γ), their stability region, and the papers'
//! gain formulas shared by the filters, the schedules, the bank and the
//! closed-form design functions. A leaf module: it uses only [`crate::num`],
//! so [`crate::filter`], [`crate::gain`], [`crate::bank`] and
//! [`crate::design`] can all use it without depending on each other.

use core::fmt;

use crate::num::{Numeric, Quantity, Real};

/// Why a set of gains was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GainError {
    /// A gain is NaN, infinite or not representable.
    NotFinite,
    /// Outside 0 < α < 2 (Al-Wagih eq. 12, Tenne & Singh eq. 7).
    AlphaOutOfRange,
    /// β ≤ 0 (Al-Wagih eq. 13, Tenne & Singh eq. 7).
    BetaNotPositive,
    /// 2α + β ≥ 4 (Al-Wagih eq. 14, Tenne & Singh eq. 8).
    BetaTooLarge,
    /// γ ≤ 0 (Tenne & Singh eq. 7).
    GammaNotPositive,
    /// γ ≥ 4αβ/(2 − α) (Tenne & Singh eq. 8).
    GammaTooLarge,
}

impl core::fmt::Display for GainError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            GainError::NotFinite => "gain is not a finite number",
            GainError::AlphaOutOfRange => "alpha must satisfy 0 < alpha < 2",
            GainError::BetaNotPositive => "beta must be > 0",
            GainError::BetaTooLarge => "gains must satisfy 2*alpha + beta < 4",
            GainError::GammaNotPositive => "gamma must be > 0",
            GainError::GammaTooLarge => "gamma must be < 4*alpha*beta/(2 - alpha)",
        })
    }
}

impl core::error::Error for GainError {}

/// Smoothing gains (α, β, γ) that lie inside a stability region.
///
/// γ uses Tenne & Singh's convention: the acceleration correction is
/// γ/(2T²)·e (eq. 5). For αβ gains γ is zero.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Gains<N: Numeric> {
    alpha: N::Ratio,
    beta: N::Ratio,
    gamma: N::Ratio,
}

impl<N: Numeric> Gains<N> {
    /// αβ gains, checked against the stability triangle 0 < α < 2, β > 0,
    /// 2α + β < 4 (Al-Wagih & Abdulla eqs. 12–14).
    #[inline]
    pub fn alpha_beta(alpha: N::Ratio, beta: N::Ratio) -> Result<Self, GainError> {
        check_alpha_beta(alpha, beta)?;
        Ok(Gains {
            alpha,
            beta,
            gamma: N::Ratio::ZERO,
        })
    }

    /// αβγ gains, checked against the stability volume of Tenne & Singh
    /// eqs. (7)–(8): the αβ triangle and 0 < γ < 4αβ/(2 − α).
    pub fn alpha_beta_gamma(
        alpha: N::Ratio,
        beta: N::Ratio,
        gamma: N::Ratio,
    ) -> Result<Self, GainError> {
        check_alpha_beta(alpha, beta)?;
        if !gamma.is_valid() {
            return Err(GainError::NotFinite);
        }
        if gamma <= N::Ratio::ZERO {
            return Err(GainError::GammaNotPositive);
        }
        let two = N::Ratio::TWO;
        // γ(2 − α) < 4αβ, multiplied out to avoid a division (2 − α > 0).
        if gamma * (two - alpha) >= two * two * alpha * beta {
            return Err(GainError::GammaTooLarge);
        }
        Ok(Gains { alpha, beta, gamma })
    }

    /// αβ gains from `f64` values (for configuration and tools).
    pub fn alpha_beta_f64(alpha: f64, beta: f64) -> Result<Self, GainError> {
        Self::alpha_beta(ratio::<N>(alpha)?, ratio::<N>(beta)?)
    }

    /// αβγ gains from `f64` values (for configuration and tools).
    pub fn alpha_beta_gamma_f64(alpha: f64, beta: f64, gamma: f64) -> Result<Self, GainError> {
        Self::alpha_beta_gamma(ratio::<N>(alpha)?, ratio::<N>(beta)?, ratio::<N>(gamma)?)
    }

    /// α, the position gain.
    pub fn alpha(&self) -> N::Ratio {
        self.alpha
    }
    /// β, the velocity gain (the filters divide it by the interval).
    pub fn beta(&self) -> N::Ratio {
        self.beta
    }
    /// Zero for αβ gains.
    pub fn gamma(&self) -> N::Ratio {
        self.gamma
    }

    /// The same gains in another number system (rounded to nearest). The
    /// stability inequalities are strict and a rounding step is far smaller
    /// than any margin that matters, but the result is re-checked anyway.
    pub fn convert<M: Numeric>(&self) -> Result<Gains<M>, GainError> {
        let c = |v: N::Ratio| ratio::<M>(v.to_f64());
        if self.gamma == N::Ratio::ZERO {
            Gains::alpha_beta(c(self.alpha)?, c(self.beta)?)
        } else {
            Gains::alpha_beta_gamma(c(self.alpha)?, c(self.beta)?, c(self.gamma)?)
        }
    }
}

fn ratio<N: Numeric>(v: f64) -> Result<N::Ratio, GainError> {
    N::Ratio::try_from_f64(v).map_err(|_| GainError::NotFinite)
}

/// The αβ stability triangle (Al-Wagih & Abdulla eqs. 12–14).
#[inline]
fn check_alpha_beta<R: Real>(alpha: R, beta: R) -> Result<(), GainError> {
    if !alpha.is_valid() || !beta.is_valid() {
        return Err(GainError::NotFinite);
    }
    let two = R::TWO;
    if alpha <= R::ZERO || alpha >= two {
        return Err(GainError::AlphaOutOfRange);
    }
    if beta <= R::ZERO {
        return Err(GainError::BetaNotPositive);
    }
    if two * alpha + beta >= two * two {
        return Err(GainError::BetaTooLarge);
    }
    Ok(())
}

/// β = α²/(2 − α) (Al-Wagih & Abdulla eq. 23b; Liu, Wang & Yang eqs. 10–11).
pub fn beta_from_alpha<R: Real>(alpha: R) -> R {
    let two = R::TWO;
    alpha * alpha / (two - alpha)
}

/// α̂(n) = 2(2n − 1)/(n(n + 1)) (Al-Wagih & Abdulla eq. 24a; Li et al.
/// eq. 4; Liu, Wang & Yang eq. 5), rounded once from the integer ratio.
#[inline]
pub fn least_squares_alpha<R: Real>(n: u32) -> R {
    let n = u64::from(n);
    // 2(2n − 1) < 2³⁴ and n(n + 1) < 2⁶⁴ for every u32 n.
    let numerator = n.wrapping_mul(4).saturating_sub(2);
    R::from_ratio(numerator, n.wrapping_mul(n.wrapping_add(1)))
}

/// β̂(n) = 6/(n(n + 1)) (Al-Wagih & Abdulla eq. 24b; Li et al. eq. 5;
/// Liu, Wang & Yang eq. 5), rounded once from the integer ratio.
#[inline]
pub fn least_squares_beta<R: Real>(n: u32) -> R {
    let n = u64::from(n);
    R::from_ratio(6, n.wrapping_mul(n.wrapping_add(1)))
}

/// β = 2(1 − √(1 − α))² (Li et al. eq. 7), evaluated as
/// 2(α/(1 + √(1 − α)))², the same number without the cancellation of
/// 1 − √(1 − α) when α is small (which costs f32 four digits at α = 0.004).
/// For α = α(k) of eq. (4) this is eq. (8).
pub fn li_beta<R: Real>(alpha: R) -> R {
    let two = R::TWO;
    let q = alpha / (R::ONE + (R::ONE - alpha).sqrt());
    two * q * q
}

/// Why a schedule's or bank's configuration was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ConfigError {
    /// The parameter is outside its documented range (or not a number).
    OutOfRange {
        /// The parameter's name in the spec (`alpha`, `k`, ...).
        parameter: &'static str,
    },
    /// The parameter cannot be represented in the chosen number type.
    NotRepresentable {
        /// The parameter's name in the spec.
        parameter: &'static str,
    },
    /// The parameter asks for more storage than the type's const capacity.
    ExceedsCapacity {
        /// The parameter's name in the spec.
        parameter: &'static str,
        /// The type's capacity (its const generic).
        capacity: usize,
    },
    /// The spec names a bank of filters, not a schedule
    /// (build it with [`crate::bank`]).
    NotASchedule,
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConfigError::OutOfRange { parameter } => {
                write!(f, "parameter `{parameter}` is out of range")
            }
            ConfigError::NotRepresentable { parameter } => {
                write!(f, "parameter `{parameter}` is not representable")
            }
            ConfigError::ExceedsCapacity {
                parameter,
                capacity,
            } => write!(f, "parameter `{parameter}` exceeds the capacity {capacity}"),
            ConfigError::NotASchedule => {
                f.write_str("a filter bank is an estimator, not a gain schedule")
            }
        }
    }
}

impl core::error::Error for ConfigError {}

/// Converts a configuration value into a quantity of the schedule's number
/// system.
pub(crate) fn config_quantity<Q: Quantity>(
    v: f64,
    parameter: &'static str,
) -> Result<Q, ConfigError> {
    Q::try_from_f64(v).map_err(|_| ConfigError::NotRepresentable { parameter })
}

/// Checks that `v` entries fit a type whose const capacity is `capacity`.
pub(crate) fn check_capacity(
    v: u16,
    capacity: usize,
    parameter: &'static str,
) -> Result<(), ConfigError> {
    if usize::from(v) > capacity {
        Err(ConfigError::ExceedsCapacity {
            parameter,
            capacity,
        })
    } else {
        Ok(())
    }
}

/// Checks lo < v ≤ hi (or lo ≤ v ≤ hi when `closed_low`), refusing NaN.
pub(crate) fn check_range(
    v: f64,
    lo: f64,
    hi: f64,
    closed_low: bool,
    parameter: &'static str,
) -> Result<(), ConfigError> {
    let low_ok = if closed_low { v >= lo } else { v > lo };
    if low_ok && v <= hi {
        Ok(())
    } else {
        Err(ConfigError::OutOfRange { parameter })
    }
}

/// The `i`-th of `count` evenly spaced points from `lo` to `hi` (both
/// included; `count` ≥ 2, else `lo`): lo + (hi − lo)·i/(count − 1).
pub(crate) fn grid_point<R: Real>(lo: R, hi: R, i: usize, count: usize) -> R {
    if count < 2 {
        return lo;
    }
    let last = count.wrapping_sub(1) as u64;
    lo + (hi - lo) * R::from_ratio(i as u64, last)
}
