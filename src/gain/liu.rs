//! Liu, Wang & Yang, "Accuracy analysis and improvement of different
//! alpha-beta filtering algorithms" (in Chinese), §2.1.1–2.1.5.
//!
//! * 2.1.1, gains by scan count (eq. 5): [`super::LeastSquaresGains`], the
//!   same formula as Al-Wagih & Abdulla's eq. (24).
//! * 2.1.2, scan count adjusted by an innovation threshold:
//!   [`ScanCountAdjustedGains`].
//! * 2.1.3, fixed α = 0.5, β = 0.3: [`super::FixedGains::liu`].
//! * 2.1.4, residual accumulation (eqs. 6–11): [`ResidualAccumulationGains`].
//! * 2.1.5, adaptive switch between 2.1.3 and 2.1.4 (eqs. 12–15):
//!   [`AdaptiveSwitchGains`].
//!
//! The paper computes the innovation V(k+1) (eq. 3) before it applies the
//! gain K(k+1) (eq. 4), and 2.1.5 switches on the current |V_x(k)|, |V_y(k)|;
//! so all three adaptive methods here use the innovation of the measurement
//! being incorporated (see the [module docs](super)).

use super::al_wagih::{
    beta_from_alpha, least_squares_alpha, least_squares_beta, LeastSquaresConfig,
};
use super::{
    check_capacity, check_range, config_quantity, ConfigError, FixedGains, GainContext,
    GainSchedule, ScheduleError,
};
use crate::filter::Gains;
use crate::num::{Numeric, Quantity, Real};

/// Configuration of [`ScanCountAdjustedGains`] (`liu-count-adjusted`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanCountAdjustedConfig {
    /// The innovation threshold in metres on each axis, in (0, 10⁹]
    /// (70 m in §3.2.2).
    pub threshold: f64,
    /// Upper bound of k (not in the paper), 3..=10 000. Default 1000.
    pub k_max: u32,
}

impl ScanCountAdjustedConfig {
    /// Threshold 70 m (§3.2.2), k_max = 1000.
    pub const DEFAULT: Self = ScanCountAdjustedConfig {
        threshold: 70.0,
        k_max: 1000,
    };

    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range(self.threshold, 0.0, 1.0e9, false, "threshold")?;
        if !(3..=LeastSquaresConfig::N_MAX_LIMIT).contains(&self.k_max) {
            return Err(ConfigError::OutOfRange { parameter: "k-max" });
        }
        Ok(())
    }
}

/// Liu, Wang & Yang §2.1.2: the gains of eq. (5) with a scan count k that is
/// "no longer determined by the radar scan count alone": +1 when the
/// measurement–prediction differences on both axes are within range, −1
/// otherwise. §3.2.2 gives the range: a difference above 70 m on the x *or*
/// the y axis means a manoeuvre and k is decreased by 1.
///
/// Reading: the count after two-point initialisation is 2; each filtered
/// measurement moves it by ±1 according to its own innovation, and the
/// gains of that measurement use the moved count. Without threshold
/// crossings this is exactly §2.1.1 (k = 3 at the third scan). k is kept in
/// 3..=k_max: filtering starts at k = 3 (§2.1.1) and k = 1 would give
/// α = 1, β = 3, outside the stability triangle (2α + β = 5 > 4). A scan
/// without a measurement leaves k unchanged.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanCountAdjustedGains<N: Numeric> {
    threshold: N::Length,
    k_max: u32,
    /// k of the last filtered update (2 before the first).
    k: u32,
}

impl<N: Numeric> ScanCountAdjustedGains<N> {
    /// §2.1.2's schedule as `c` configures it.
    pub fn new(c: &ScanCountAdjustedConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        Ok(ScanCountAdjustedGains {
            threshold: config_quantity(c.threshold, "threshold")?,
            k_max: c.k_max,
            k: 2,
        })
    }

    /// k of the last filtered update (2 before the first).
    pub fn count(&self) -> u32 {
        self.k
    }

    fn next_count<const D: usize>(&self, ctx: &GainContext<N, D>) -> u32 {
        let manoeuvre = ctx.axes.iter().any(|a| {
            let e = a.innovation.abs();
            // An invalid innovation is no evidence of steady motion.
            !e.is_valid() || e > self.threshold
        });
        if manoeuvre {
            self.k.saturating_sub(1).max(3)
        } else {
            // (No `clamp`: its argument check is a panic path.)
            self.k.saturating_add(1).max(3).min(self.k_max.max(3))
        }
    }
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for ScanCountAdjustedGains<N> {
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        let k = self.next_count(ctx);
        Ok([Gains::alpha_beta(least_squares_alpha(k), least_squares_beta(k))?; D])
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        self.k = self.next_count(ctx);
    }

    fn reset(&mut self) {
        self.k = 2;
    }
}

/// Configuration of [`ResidualAccumulationGains`] (`liu-residual`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ResidualAccumulationConfig {
    /// n, the number of innovations averaged, 1 ≤ n ≤ the type's capacity
    /// (3 in §2.1.4).
    pub n: u16,
    /// σ_m², the measurement-error variance in m² (25 in §2.1.4), in
    /// (0, 10¹²].
    pub sigma_m2: f64,
    /// Lower bound of α (not in the paper), in (0, 0.5]. Default 0.01; it
    /// binds only when the mean squared innovation is below
    /// σ_m²·0.01/0.99 (0.5 m RMS for σ_m = 5 m), i.e. for noise-free data,
    /// where eq. (8) would give α → 0 and β → 0, the edge of the stability
    /// triangle that fixed point rounds onto.
    pub alpha_min: f64,
}

impl ResidualAccumulationConfig {
    /// n = 3, σ_m² = 25 m² (§2.1.4), α_min = 0.01.
    pub const DEFAULT: Self = ResidualAccumulationConfig {
        n: 3,
        sigma_m2: 25.0,
        alpha_min: 0.01,
    };

    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.n == 0 {
            return Err(ConfigError::OutOfRange { parameter: "n" });
        }
        check_range(self.sigma_m2, 0.0, 1.0e12, false, "sigma-m2")?;
        check_range(self.alpha_min, 0.0, 0.5, false, "alpha-min")
    }
}

/// Liu, Wang & Yang §2.1.4, residual accumulation, per axis:
/// σ_p²(k) = (1/n) Σ_{i=1..n} V(k − i + 1)² (eqs. 6–7),
/// α(k) = σ_p²/(σ_p² + σ_m²) (eqs. 8–9), β = α²/(2 − α) (eqs. 10–11).
///
/// # Reading
///
/// Eqs. (6)–(7) print the summand as [x_{k−i+1} − x_{k−i}]², a difference of
/// consecutive positions; the text defines it as "the mean of the squared
/// differences between measurement and prediction" over the last n scans,
/// and §3.2.1 reasons the same way ("if one of the last three
/// measurement–prediction differences is ≥ 5√3, α > 0.5": 75/3 = 25 = σ_m²).
/// We read x_{k−i+1} − x_{k−i} as the measurement at k − i + 1 minus its
/// prediction made at k − i, i.e. the innovation V(k − i + 1); i = 1 is the
/// current innovation. Until n innovations exist the mean is over those
/// there are (one at the first filtered scan).
///
/// α lies in [α_min, 1]: eq. (8) is < 1 for finite σ_p² (and reaches 1 only
/// when a squared innovation overflows, its limit), so β ≤ 1 and every pair
/// is strictly stable (2α + β ≤ 3 < 4). To keep fixed point from overflowing,
/// innovations are divided by σ_m before squaring: α = s/(s + 1) with
/// s = mean((V/σ_m)²), which is eq. (8) rearranged.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ResidualAccumulationGains<N: Numeric, const D: usize, const H: usize> {
    sigma_m: N::Length,
    alpha_min: N::Ratio,
    n: usize,
    /// (V/σ_m)² of past accepted updates, per axis, oldest at `start`.
    history: [[N::Ratio; D]; H],
    start: usize,
    len: usize,
}

impl<N: Numeric, const D: usize, const H: usize> ResidualAccumulationGains<N, D, H> {
    /// §2.1.4's schedule as `c` configures it; n must fit the capacity `H`.
    pub fn new(c: &ResidualAccumulationConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        check_capacity(c.n, H, "n")?;
        // σ_m = √σ_m², taken once in f64 (configuration).
        let sigma_m: N::Length = config_quantity(libm::sqrt(c.sigma_m2), "sigma-m2")?;
        if !(sigma_m.is_valid() && sigma_m > N::Length::ZERO) {
            return Err(ConfigError::NotRepresentable {
                parameter: "sigma-m2",
            });
        }
        Ok(ResidualAccumulationGains {
            sigma_m,
            alpha_min: config_quantity(c.alpha_min, "alpha-min")?,
            n: usize::from(c.n),
            history: [[N::Ratio::ZERO; D]; H],
            start: 0,
            len: 0,
        })
    }

    /// The n − 1 most recent stored terms of `axis`, newest first.
    fn recent(&self, axis: usize) -> impl Iterator<Item = N::Ratio> + '_ {
        let keep = self.len.min(self.n.saturating_sub(1));
        (0..keep).filter_map(move |back| {
            // start + len − 1 − back ≥ start ≥ 0 (back < len); n ≥ 1.
            let slot = self
                .start
                .wrapping_add(self.len)
                .wrapping_sub(1)
                .wrapping_sub(back)
                .checked_rem(self.n.max(1))?;
            self.history.get(slot).and_then(|h| h.get(axis)).copied()
        })
    }

    fn normalised_square(&self, innovation: N::Length) -> N::Ratio {
        let u = innovation / self.sigma_m;
        u * u
    }

    /// α, β of eqs. (8), (10) for one axis with current innovation `v`.
    fn axis_gains(&self, axis: usize, v: N::Length) -> Result<Gains<N>, ScheduleError> {
        let mut sum = self.normalised_square(v);
        let mut count = 1u64;
        for term in self.recent(axis) {
            sum = sum + term;
            count = count.saturating_add(1);
        }
        let s = sum / N::Ratio::from_ratio(count, 1);
        let alpha = if s.is_valid() {
            (s / (s + N::Ratio::ONE))
                .max_of(self.alpha_min)
                .min_of(N::Ratio::ONE)
        } else {
            // A squared innovation overflowed: eq. (8) at its limit.
            N::Ratio::ONE
        };
        Ok(Gains::alpha_beta(alpha, beta_from_alpha(alpha))?)
    }

    fn gains_for(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        let mut out = [Gains::alpha_beta(N::Ratio::ONE, N::Ratio::ONE)?; D];
        for (axis, g) in out.iter_mut().enumerate() {
            let v = ctx
                .axes
                .get(axis)
                .map(|a| a.innovation)
                .ok_or(ScheduleError::InvalidContext)?;
            *g = self.axis_gains(axis, v)?;
        }
        Ok(out)
    }

    fn push(&mut self, innovations: &[N::Length]) {
        let mut terms = [N::Ratio::ZERO; D];
        for (t, v) in terms.iter_mut().zip(innovations) {
            *t = self.normalised_square(*v);
        }
        let cap = self.n.max(1);
        let start = self.start;
        let slot = |k: usize| start.wrapping_add(k).checked_rem(cap).unwrap_or(0);
        if self.len < cap {
            let next = slot(self.len);
            if let Some(h) = self.history.get_mut(next) {
                *h = terms;
                self.len = self.len.saturating_add(1);
            }
        } else {
            let next = slot(1);
            if let Some(h) = self.history.get_mut(start) {
                *h = terms;
                self.start = next;
            }
        }
    }
}

impl<N: Numeric, const D: usize, const H: usize> GainSchedule<N, D>
    for ResidualAccumulationGains<N, D, H>
{
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        self.gains_for(ctx)
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        self.push(&ctx.innovations());
    }

    fn reset(&mut self) {
        self.start = 0;
        self.len = 0;
    }
}

/// Configuration of [`AdaptiveSwitchGains`] (`liu-adaptive`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AdaptiveSwitchConfig {
    /// limitX = limitY, the innovation threshold in metres (19 m in
    /// §2.1.5), in (0, 10⁹].
    pub limit: f64,
    /// The fixed gains of the steady branch (§2.1.3: 0.5, 0.3).
    pub alpha: f64,
    /// β of the steady branch (see `alpha`).
    pub beta: f64,
    /// The residual-accumulation branch (§2.1.4).
    pub residual: ResidualAccumulationConfig,
}

impl AdaptiveSwitchConfig {
    /// limit 19 m, α = 0.5, β = 0.3 (§2.1.3, §2.1.5), the residual branch's defaults.
    pub const DEFAULT: Self = AdaptiveSwitchConfig {
        limit: 19.0,
        alpha: 0.5,
        beta: 0.3,
        residual: ResidualAccumulationConfig::DEFAULT,
    };

    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range(self.limit, 0.0, 1.0e9, false, "limit")?;
        super::al_wagih::FixedConfig {
            alpha: self.alpha,
            beta: self.beta,
            gamma: None,
        }
        .validate()?;
        self.residual.validate()
    }
}

/// Which branch of Liu, Wang & Yang's adaptive switch gave the gains.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SwitchMode {
    /// Both |innovations| ≤ their limits: fixed gains (§2.1.3).
    Steady,
    /// Some |innovation| > its limit: residual accumulation (§2.1.4).
    Manoeuvre,
}

/// Liu, Wang & Yang §2.1.5 (eqs. 12–15): if |V_x(k)| > limitX or
/// |V_y(k)| > limitY, both axes take the residual-accumulation gains of
/// §2.1.4 (each its own α_x, α_y); if both are ≤ their limits, both take the
/// fixed α = 0.5, β = 0.3. Limits 19 m (§2.1.5), the same on every axis.
///
/// The residual window is fed on every accepted update, whichever branch
/// gave the gains: eqs. (6)–(7) average the last n innovations, not the last
/// n manoeuvring ones. The text says "both less than the threshold" for the
/// fixed branch; eqs. (12)–(15) use ≤, which we follow.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AdaptiveSwitchGains<N: Numeric, const D: usize, const H: usize> {
    limit: N::Length,
    fixed: FixedGains<N>,
    residual: ResidualAccumulationGains<N, D, H>,
    last_mode: Option<SwitchMode>,
}

impl<N: Numeric, const D: usize, const H: usize> AdaptiveSwitchGains<N, D, H> {
    /// §2.1.5's switch as `c` configures it; n must fit the capacity `H`.
    pub fn new(c: &AdaptiveSwitchConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        Ok(AdaptiveSwitchGains {
            limit: config_quantity(c.limit, "limit")?,
            fixed: FixedGains::from_config(&super::al_wagih::FixedConfig {
                alpha: c.alpha,
                beta: c.beta,
                gamma: None,
            })?,
            residual: ResidualAccumulationGains::new(&c.residual)?,
            last_mode: None,
        })
    }

    /// The branch that gave the gains of the last accepted update.
    pub fn last_mode(&self) -> Option<SwitchMode> {
        self.last_mode
    }

    /// The branch eqs. (12)–(15) choose for `ctx`.
    pub fn mode(&self, ctx: &GainContext<N, D>) -> SwitchMode {
        let over = ctx.axes.iter().any(|a| {
            let e = a.innovation.abs();
            !e.is_valid() || e > self.limit
        });
        if over {
            SwitchMode::Manoeuvre
        } else {
            SwitchMode::Steady
        }
    }
}

impl<N: Numeric, const D: usize, const H: usize> GainSchedule<N, D>
    for AdaptiveSwitchGains<N, D, H>
{
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        match self.mode(ctx) {
            SwitchMode::Steady => Ok([self.fixed.fixed(); D]),
            SwitchMode::Manoeuvre => self.residual.gains_for(ctx),
        }
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, used: &[Gains<N>; D]) {
        self.last_mode = Some(self.mode(ctx));
        self.residual.accepted(ctx, used);
    }

    fn reset(&mut self) {
        self.residual.reset();
        self.last_mode = None;
    }
}
