//! Al-Wagih & Abdulla, §5: methods M1–M4 of choosing α and β (M5, the
//! parallel bank, is an estimator: [`crate::bank`]).
//!
//! * M1, [`FixedGains::m1`]: a fixed α̃ ∈ (0, 1] and β̃ = α̃²/(2 − α̃)
//!   (eq. 23).
//! * M2, [`LeastSquaresGains`]: α̂(n) = 2(2n − 1)/(n(n + 1)),
//!   β̂(n) = 6/(n(n + 1)) (eq. 24), n the number of the measurement.
//! * M3, [`LinearCombinationGains`]: α̂(n) and β_LC = wβ̃ + (1 − w)β̂(n)
//!   (eq. 25, Algorithm 1), w chosen on a moving window.
//! * M4, [`MovingWindowGains`]: the α of a grid that minimises the innovation
//!   error over a moving window, β from eq. (23b) (Algorithm 2).

use super::window::{argmin, Window};
use super::{
    check_capacity, check_range, config_quantity, ConfigError, GainContext, GainSchedule,
    ScheduleError,
};
use crate::filter::Gains;
use crate::gains::grid_point;
use crate::num::{Numeric, Quantity, Real};

pub use crate::gains::{beta_from_alpha, least_squares_alpha, least_squares_beta};

/// Constant gains: M1 (Al-Wagih & Abdulla eq. 23), Liu, Wang & Yang's
/// §2.1.3 (α = 0.5, β = 0.3), or any pair / triple inside the stability
/// region.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedGains<N: Numeric> {
    gains: Gains<N>,
}

/// Configuration of [`FixedGains`] (`fixed:alpha=A,beta=B[,gamma=G]`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedConfig {
    /// α, inside the stability region with β (and γ).
    pub alpha: f64,
    /// β.
    pub beta: f64,
    /// `None` for αβ gains.
    pub gamma: Option<f64>,
}

/// Configuration of M1 (`m1:alpha=A`): α̃ ∈ (0, 1] (eq. 23a).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedAlphaConfig {
    /// α̃ ∈ (0, 1]; β̃ = α̃²/(2 − α̃) (eq. 23b).
    pub alpha: f64,
}

impl FixedAlphaConfig {
    /// α̃ = 0.05, the first value §5.2 suggests ("say α = 0.05 or α = 0.01").
    pub const DEFAULT: Self = FixedAlphaConfig { alpha: 0.05 };

    /// Checks α̃ ∈ (0, 1].
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range(self.alpha, 0.0, 1.0, false, "alpha")
    }
}

impl FixedConfig {
    /// Liu, Wang & Yang §2.1.3: α = 0.5, β = 0.3.
    pub const LIU: Self = FixedConfig {
        alpha: 0.5,
        beta: 0.3,
        gamma: None,
    };

    /// Checks the gains against the αβ triangle or the αβγ volume.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let g = match self.gamma {
            None => Gains::<f64>::alpha_beta(self.alpha, self.beta),
            Some(gamma) => Gains::<f64>::alpha_beta_gamma(self.alpha, self.beta, gamma),
        };
        g.map(|_| ())
            .map_err(|_| ConfigError::OutOfRange { parameter: "gains" })
    }
}

impl<N: Numeric> FixedGains<N> {
    /// A schedule that always gives `gains`.
    pub const fn new(gains: Gains<N>) -> Self {
        FixedGains { gains }
    }

    /// M1: α̃ ∈ (0, 1] and β̃ = α̃²/(2 − α̃) (Al-Wagih & Abdulla eq. 23).
    pub fn m1(alpha: N::Ratio) -> Result<Self, ConfigError> {
        if !(alpha > N::Ratio::ZERO && alpha <= N::Ratio::ONE) {
            return Err(ConfigError::OutOfRange { parameter: "alpha" });
        }
        Gains::alpha_beta(alpha, beta_from_alpha(alpha))
            .map(Self::new)
            .map_err(|_| ConfigError::NotRepresentable { parameter: "alpha" })
    }

    /// Liu, Wang & Yang §2.1.3: α = 0.5, β = 0.3.
    pub fn liu() -> Result<Self, ConfigError> {
        Self::from_config(&FixedConfig::LIU)
    }

    /// The gains a [`FixedConfig`] gives (`fixed:alpha=A,beta=B[,gamma=G]`).
    pub fn from_config(c: &FixedConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        let g = match c.gamma {
            None => Gains::alpha_beta_f64(c.alpha, c.beta),
            Some(gamma) => Gains::alpha_beta_gamma_f64(c.alpha, c.beta, gamma),
        };
        g.map(Self::new)
            .map_err(|_| ConfigError::NotRepresentable { parameter: "gains" })
    }

    /// M1 from its configuration (`m1:alpha=A`).
    pub fn from_m1_config(c: &FixedAlphaConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        Self::m1(config_quantity(c.alpha, "alpha")?)
    }

    /// The gains this schedule gives.
    pub fn fixed(&self) -> Gains<N> {
        self.gains
    }
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for FixedGains<N> {
    fn gains(&self, _ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        Ok([self.gains; D])
    }
    fn accepted(&mut self, _ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {}
    fn count_gains(&self, _n: u32) -> Option<Result<Gains<N>, ScheduleError>> {
        Some(Ok(self.gains))
    }
    fn reset(&mut self) {}
}

/// Configuration of M2 (`least-squares`, `m2`, `liu-count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LeastSquaresConfig {
    /// The gains stop decreasing at n = `n_max` (not in the papers): a
    /// bound that keeps β̂ representable with precision (β̂(10 000) = 6·10⁻⁸
    /// is 258 steps of Q32.32) and u32 counts safe. The default 1000
    /// (α̂ = 0.004, β̂ = 6·10⁻⁶) is never reached by the papers' runs
    /// (at most 100 scans).
    pub n_max: u32,
}

impl LeastSquaresConfig {
    /// n_max = 1000.
    pub const DEFAULT: Self = LeastSquaresConfig { n_max: 1000 };
    /// The largest `n_max` accepted (β̂ = 6·10⁻⁸ there).
    pub const N_MAX_LIMIT: u32 = 10_000;

    /// Checks 3 ≤ `n_max` ≤ [`Self::N_MAX_LIMIT`].
    pub fn validate(&self) -> Result<(), ConfigError> {
        if (3..=Self::N_MAX_LIMIT).contains(&self.n_max) {
            Ok(())
        } else {
            Err(ConfigError::OutOfRange { parameter: "n-max" })
        }
    }

    /// n clamped to 3..=n_max: the first filtered update is n = 3 (eq. 24,
    /// "n > 2"); a filter handed over already tracking is treated the same.
    fn effective(&self, n: u32) -> u32 {
        // (No `clamp`: its argument check is a panic path.)
        n.max(3).min(self.n_max.max(3))
    }
}

/// M2: the least-squares gains α̂(n), β̂(n) of Al-Wagih & Abdulla eq. (24),
/// which are also Li et al.'s standard filter (eqs. 4–5) and Liu, Wang &
/// Yang's §2.1.1 (eq. 5).
///
/// n is the number of the measurement since the track started, counting
/// from 1 ([`GainContext::n`]), so the first filtered update after two-point
/// initialisation has n = 3: α = 2·5/12 = 5/6, β = 6/12 = 1/2 (Liu: "α ≤ 5/6,
/// β ≤ 1/2" when filtering starts at scan 3). Misses do not advance n (the
/// least-squares line fit behind eq. 24 counts measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LeastSquaresGains {
    config: LeastSquaresConfig,
}

impl LeastSquaresGains {
    /// M2 bounded at `config.n_max`.
    pub fn new(config: &LeastSquaresConfig) -> Result<Self, ConfigError> {
        config.validate()?;
        Ok(LeastSquaresGains { config: *config })
    }

    /// The gains for measurement `n` (clamped to 3..=n_max).
    #[inline]
    pub fn gains_at<N: Numeric>(&self, n: u32) -> Result<Gains<N>, ScheduleError> {
        let n = self.config.effective(n);
        Ok(Gains::alpha_beta(
            least_squares_alpha(n),
            least_squares_beta(n),
        )?)
    }
}

impl Default for LeastSquaresGains {
    fn default() -> Self {
        LeastSquaresGains {
            config: LeastSquaresConfig::DEFAULT,
        }
    }
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for LeastSquaresGains {
    #[inline]
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        Ok([self.gains_at(ctx.n)?; D])
    }
    fn accepted(&mut self, _ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {}
    fn count_gains(&self, n: u32) -> Option<Result<Gains<N>, ScheduleError>> {
        Some(self.gains_at(n))
    }
    fn reset(&mut self) {}
}

/// Configuration of M3 (`m3`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LinearCombinationConfig {
    /// α₀ of Algorithm 1 step 1, the M1 value from which β̃ = α₀²/(2 − α₀)
    /// (eq. 23b) is taken; in (0, 1]. Default 0.05 as for M1.
    pub alpha0: f64,
    /// The weight w ∈ [0, 1] of eq. (25): the fixed weight if `steps` = 0,
    /// else the weight used until the window first fills. Default 0.5.
    pub w: f64,
    /// Number of candidate weights 0, 1/(steps − 1), …, 1 searched on the
    /// window; 0 keeps `w` fixed. Default 11 (steps of 0.1).
    pub steps: u16,
    /// Window length L (2 ≤ L ≤ the type's capacity W). Default 8.
    pub window: u16,
    /// Bound on n for α̂(n), β̂(n), as in [`LeastSquaresConfig::n_max`].
    pub n_max: u32,
}

impl LinearCombinationConfig {
    /// α₀ = 0.05, w = 0.5, 11 steps, window 8, n_max 1000.
    pub const DEFAULT: Self = LinearCombinationConfig {
        alpha0: 0.05,
        w: 0.5,
        steps: 11,
        window: 8,
        n_max: LeastSquaresConfig::DEFAULT.n_max,
    };

    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range(self.alpha0, 0.0, 1.0, false, "alpha0")?;
        check_range(self.w, 0.0, 1.0, true, "w")?;
        if self.steps == 1 || self.steps > 1000 {
            return Err(ConfigError::OutOfRange { parameter: "steps" });
        }
        if self.window < 2 {
            return Err(ConfigError::OutOfRange {
                parameter: "window",
            });
        }
        LeastSquaresConfig { n_max: self.n_max }.validate()
    }
}

/// M3, linear combination: α = α̂(n) (eq. 24a) and
/// β_LC = w·β̃ + (1 − w)·β̂(n) (eq. 25), β̃ = α₀²/(2 − α₀) (eq. 23b),
/// β̂(n) = 6/(n(n + 1)) (eq. 24b).
///
/// # Reading of Algorithm 1
///
/// Step 1 "fix the value of α at α₀" and step 2 "calculate β⁻ and β⁺ from
/// (23b) and (24b)" give the two β estimates of M1 and M2: β⁻ = β̃ from the
/// fixed α₀, β⁺ = β̂(n). The text before the algorithm says which α the
/// tracker then uses: "we can use the estimate (24a) for α". So α₀ only
/// produces β̃; the tracker's α is α̂(n).
///
/// Step 3, "search for optimal weight w", names minimising the mean square
/// error as one strategy. The tracker cannot see the truth, so the error we
/// minimise is the innovation: per axis, each of `steps` candidate weights
/// w ∈ {0, …, 1} is re-run over the last L measurements (from the tracker's
/// own prediction at the window's start, with α̂(n) and β_LC(w, n) at each
/// step), and the w with the least sum of squared innovations is used from
/// the next update on (on equal sums, the smaller w). Until the window
/// first fills, and if every candidate overflows, the weight in use stays.
/// With `steps = 0` w is fixed.
///
/// Every gain lies in the stability triangle: α̂(n) ≤ 5/6 and β_LC lies
/// between β̃ ≤ 1 and β̂(n) ≤ 1/2, both > 0, so 2α + β < 4; and β_LC is held
/// at Kalata's β for α̂(n) (see `alpha_beta`), which β̂(n) never exceeds.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LinearCombinationGains<N: Numeric, const D: usize, const W: usize> {
    beta_tilde: N::Ratio,
    initial_w: N::Ratio,
    steps: u16,
    least_squares: LeastSquaresConfig,
    w: [N::Ratio; D],
    window: Window<N, D, W>,
}

impl<N: Numeric, const D: usize, const W: usize> LinearCombinationGains<N, D, W> {
    /// M3 as `c` configures it; the window must fit the capacity `W`.
    pub fn new(c: &LinearCombinationConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        check_capacity(c.window, W, "window")?;
        let alpha0: N::Ratio = config_quantity(c.alpha0, "alpha0")?;
        let w: N::Ratio = config_quantity(c.w, "w")?;
        Ok(LinearCombinationGains {
            beta_tilde: beta_from_alpha(alpha0),
            initial_w: w,
            steps: c.steps,
            least_squares: LeastSquaresConfig { n_max: c.n_max },
            w: [w; D],
            window: Window::new(usize::from(c.window)),
        })
    }

    /// The weight w in use on each axis.
    pub fn weights(&self) -> [N::Ratio; D] {
        self.w
    }

    /// α̂(n) and β_LC(w, n), the latter at most Kalata's β for α̂(n)
    /// ([`crate::gains::li_beta`]): β̃ is fixed while α̂(n) falls
    /// as 4/n, so without the bound the pair drifts to poles within 10⁻³
    /// of the unit circle (α₀ = 0.2: α = 0.004, β = 0.011 at n = 1000) and
    /// the weight search, switching β every update, pumps them to
    /// divergence. The bound binds only where β_LC exceeds it (with the
    /// default α₀ = 0.05, w > ½ and n ≳ 110).
    fn alpha_beta(&self, w: N::Ratio, n: u32) -> (N::Ratio, N::Ratio) {
        let n = self.least_squares.effective(n);
        let alpha = least_squares_alpha::<N::Ratio>(n);
        let beta = w * self.beta_tilde + (N::Ratio::ONE - w) * least_squares_beta::<N::Ratio>(n);
        (alpha, beta.min_of(crate::gains::li_beta(alpha)))
    }

    fn candidate(&self, i: usize) -> N::Ratio {
        grid_point(N::Ratio::ZERO, N::Ratio::ONE, i, usize::from(self.steps))
    }
}

impl<N: Numeric, const D: usize, const W: usize> GainSchedule<N, D>
    for LinearCombinationGains<N, D, W>
{
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        let mut out = [Gains::alpha_beta(N::Ratio::ONE, N::Ratio::ONE)?; D];
        for (g, w) in out.iter_mut().zip(self.w) {
            let (a, b) = self.alpha_beta(w, ctx.n);
            *g = Gains::alpha_beta(a, b)?;
        }
        Ok(out)
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        if self.steps == 0 {
            return;
        }
        self.window.push(ctx);
        if !self.window.is_full() {
            return;
        }
        let steps = usize::from(self.steps);
        for axis in 0..D {
            let best = argmin(steps, |i| {
                let w = self.candidate(i);
                self.window
                    .squared_innovation_sum(axis, |n| self.alpha_beta(w, n))
            });
            if let (Some(i), Some(w)) = (best, self.w.get_mut(axis)) {
                *w = grid_point(N::Ratio::ZERO, N::Ratio::ONE, i, steps);
            }
        }
    }

    fn reset(&mut self) {
        self.w = [self.initial_w; D];
        self.window.clear();
    }
}

/// Configuration of M4 (`m4`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MovingWindowConfig {
    /// α₀ of Algorithm 2 step 1, used until the window first fills
    /// (β₀ from eq. 23b); in (0, 1]. Not given by the paper; default 0.5.
    pub alpha0: f64,
    /// The α grid: `steps` points evenly from `alpha_min` to `alpha_max`,
    /// 0 < min < max ≤ 1 (eq. 23a). Default 0.05 to 1 in 20 steps of 0.05.
    pub alpha_min: f64,
    /// The largest α of the grid (see `alpha_min`).
    pub alpha_max: f64,
    /// The number of α values in the grid, 2 to 1000.
    pub steps: u16,
    /// Window length L (2 ≤ L ≤ the type's capacity W). Default 8.
    pub window: u16,
}

impl MovingWindowConfig {
    /// α₀ = 0.5, α from 0.05 to 1 in 20 steps, window 8.
    pub const DEFAULT: Self = MovingWindowConfig {
        alpha0: 0.5,
        alpha_min: 0.05,
        alpha_max: 1.0,
        steps: 20,
        window: 8,
    };

    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range(self.alpha0, 0.0, 1.0, false, "alpha0")?;
        check_range(self.alpha_min, 0.0, 1.0, false, "min")?;
        check_range(self.alpha_max, self.alpha_min, 1.0, false, "max")?;
        if !(2..=1000).contains(&self.steps) {
            return Err(ConfigError::OutOfRange { parameter: "steps" });
        }
        if self.window < 2 {
            return Err(ConfigError::OutOfRange {
                parameter: "window",
            });
        }
        Ok(())
    }
}

/// M4, the adjusted αβ tracker (Al-Wagih & Abdulla Algorithm 2, Figure 3).
///
/// # Reading of Algorithm 2
///
/// Step 1 fixes α₀, β₀ (β₀ from eq. 23b); step 2 tracks; step 3 "while
/// tracking, search for optimal α and β for a given window"; step 4 adjusts
/// the gains to them "for the next stage of tracking"; step 5 repeats. The
/// text: "the optimal value of α is found for the measurements inside the
/// window with respect to the window innovation … the value of corresponding
/// β is obtained from equation (23b)".
///
/// So, per axis, after every accepted update (the window moves one
/// measurement), each α of the grid is re-run over the last L measurements,
/// starting from the tracker's own prediction for the oldest one, with
/// β = α²/(2 − α); the α whose innovations have the least sum of squares is
/// used from the next update on (on equal sums, the smaller α). Until the
/// window first fills (and if every candidate overflows) the gains in use
/// stay. The paper's suggestion to
/// evaluate candidates "in parallel" is a speed-up; the result is the same.
///
/// Cost per update: `steps` × (L − 1) αβ steps per axis (20 × 7 × 2 = 280
/// with the defaults). Memory: L entries of (n, T, and per axis z, x_p, v_p,
/// e).
///
/// Not bounded on every report-time pattern: gains that switch every update
/// can make an αβ filter diverge although each pair is stable
/// (`docs/auto.md`, "Real timing").
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MovingWindowGains<N: Numeric, const D: usize, const W: usize> {
    initial: Gains<N>,
    alpha_min: N::Ratio,
    alpha_max: N::Ratio,
    steps: u16,
    current: [Gains<N>; D],
    window: Window<N, D, W>,
}

impl<N: Numeric, const D: usize, const W: usize> MovingWindowGains<N, D, W> {
    /// M4 as `c` configures it; the window must fit the capacity `W`.
    pub fn new(c: &MovingWindowConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        check_capacity(c.window, W, "window")?;
        let alpha0: N::Ratio = config_quantity(c.alpha0, "alpha0")?;
        let initial = Gains::alpha_beta(alpha0, beta_from_alpha(alpha0)).map_err(|_| {
            ConfigError::NotRepresentable {
                parameter: "alpha0",
            }
        })?;
        let alpha_min: N::Ratio = config_quantity(c.alpha_min, "min")?;
        let alpha_max: N::Ratio = config_quantity(c.alpha_max, "max")?;
        // Every grid point must give representable stable gains.
        for i in 0..usize::from(c.steps) {
            let a = grid_point(alpha_min, alpha_max, i, usize::from(c.steps));
            Gains::<N>::alpha_beta(a, beta_from_alpha(a))
                .map_err(|_| ConfigError::NotRepresentable { parameter: "min" })?;
        }
        Ok(MovingWindowGains {
            initial,
            alpha_min,
            alpha_max,
            steps: c.steps,
            current: [initial; D],
            window: Window::new(usize::from(c.window)),
        })
    }

    /// The gains in use on each axis.
    pub fn current(&self) -> [Gains<N>; D] {
        self.current
    }

    fn candidate(&self, i: usize) -> N::Ratio {
        grid_point(self.alpha_min, self.alpha_max, i, usize::from(self.steps))
    }
}

impl<N: Numeric, const D: usize, const W: usize> GainSchedule<N, D> for MovingWindowGains<N, D, W> {
    fn gains(&self, _ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        Ok(self.current)
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        self.window.push(ctx);
        if !self.window.is_full() {
            return;
        }
        for axis in 0..D {
            let best = argmin(usize::from(self.steps), |i| {
                let a = self.candidate(i);
                let b = beta_from_alpha(a);
                self.window.squared_innovation_sum(axis, |_| (a, b))
            });
            if let Some(i) = best {
                let a = self.candidate(i);
                if let (Ok(g), Some(slot)) = (
                    Gains::alpha_beta(a, beta_from_alpha(a)),
                    self.current.get_mut(axis),
                ) {
                    *slot = g;
                }
            }
        }
    }

    fn reset(&mut self) {
        self.current = [self.initial; D];
        self.window.clear();
    }
}
