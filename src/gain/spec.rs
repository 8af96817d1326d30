//! Spec strings naming a gain schedule and its parameters, parsed without
//! allocation (for `replay --schedule` and for firmware configuration).
//!
//! # Grammar
//!
//! ```text
//! spec      = name [ ":" parameter { "," parameter } ]
//! parameter = key "=" value
//! name, key = lower-case words joined by "-"   (see SCHEDULES)
//! value     = decimal number (Rust f64 syntax) or unsigned integer
//! ```
//!
//! Parameters not given take the defaults listed in [`SCHEDULES`]; giving a
//! key twice, an unknown key or a value out of its range is an error that
//! says where. [`ScheduleSpec`]'s `Display` writes the canonical spec with
//! every parameter, which parses back to the same value.
//!
//! Examples: `m1:alpha=0.05`, `least-squares`, `m3:w=0.3,steps=0`,
//! `m4:window=10,steps=19`, `bank:k=8`, `li-improved:r=2.5`,
//! `liu-adaptive:limit=19`, `tcas-firmness`, `auto:sigma=20`,
//! `auto:range-sigma=15,bearing-sigma-deg=5`.

use core::fmt;

use super::al_wagih::{
    FixedAlphaConfig, FixedConfig, LeastSquaresConfig, LinearCombinationConfig, MovingWindowConfig,
};
use super::auto::AutoConfig;
use super::li::LiImprovedConfig;
use super::liu::{AdaptiveSwitchConfig, ResidualAccumulationConfig, ScanCountAdjustedConfig};
use super::ConfigError;
use crate::bank::BankConfig;

/// One schedule name for `--help` texts and the README.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScheduleInfo {
    /// The name and its aliases, as accepted by [`ScheduleSpec::parse`].
    pub names: &'static [&'static str],
    /// The keys and their defaults.
    pub parameters: &'static str,
    /// One line: what the schedule is and where it comes from.
    pub summary: &'static str,
}

/// Every schedule name [`ScheduleSpec::parse`] accepts.
pub const SCHEDULES: &[ScheduleInfo] = &[
    ScheduleInfo {
        names: &["fixed"],
        parameters: "alpha=A,beta=B[,gamma=G] (alpha and beta required)",
        summary: "constant gains inside the stability region",
    },
    ScheduleInfo {
        names: &["m1"],
        parameters: "alpha=0.05",
        summary: "Al-Wagih M1: fixed alpha in (0,1], beta = alpha^2/(2-alpha) (eq 23)",
    },
    ScheduleInfo {
        names: &["least-squares", "m2", "liu-count"],
        parameters: "n-max=1000",
        summary: "Al-Wagih M2 / Liu 2.1.1: alpha(n)=2(2n-1)/(n(n+1)), beta(n)=6/(n(n+1)) (eq 24)",
    },
    ScheduleInfo {
        names: &["m3"],
        parameters: "alpha0=0.05,w=0.5,steps=11,window=8,n-max=1000 (steps=0: fixed w)",
        summary:
            "Al-Wagih M3: alpha(n), beta = w*beta~ + (1-w)*beta^(n), w chosen on a window (eq 25)",
    },
    ScheduleInfo {
        names: &["m4"],
        parameters: "alpha0=0.5,min=0.05,max=1,steps=20,window=8",
        summary: "Al-Wagih M4: alpha on a grid minimising the window's innovations (Algorithm 2)",
    },
    ScheduleInfo {
        names: &["bank", "m5"],
        parameters: "k=8,min=0.05,max=1",
        summary:
            "Al-Wagih M5: k fixed-gain trackers, lowest |innovation| wins (Algorithm 3; a filter)",
    },
    ScheduleInfo {
        names: &["li-improved"],
        parameters: "r=3,range-error=1,bearing-error=0,k-max=1000",
        summary: "Li et al.: effective scan count driven by the motion-stability ratio (eqs 4-15)",
    },
    ScheduleInfo {
        names: &["liu-count-adjusted"],
        parameters: "threshold=70,k-max=1000",
        summary: "Liu 2.1.2: scan count +1, or -1 when an |innovation| exceeds the threshold",
    },
    ScheduleInfo {
        names: &["liu-fixed"],
        parameters: "alpha=0.5,beta=0.3",
        summary: "Liu 2.1.3: fixed alpha = 0.5, beta = 0.3",
    },
    ScheduleInfo {
        names: &["liu-residual"],
        parameters: "n=3,sigma-m2=25,alpha-min=0.01",
        summary: "Liu 2.1.4: alpha = sp^2/(sp^2+sm^2) over the last n innovations (eqs 6-11)",
    },
    ScheduleInfo {
        names: &["liu-adaptive"],
        parameters: "limit=19,alpha=0.5,beta=0.3,n=3,sigma-m2=25,alpha-min=0.01",
        summary: "Liu 2.1.5: fixed gains, residual gains when an |innovation| > limit (eqs 12-15)",
    },
    ScheduleInfo {
        names: &["tcas-firmness"],
        parameters: "(none)",
        summary: "TCAS range tracker: alpha, beta, gamma by track firmness 0..8 (DO-185B)",
    },
    ScheduleInfo {
        names: &["auto"],
        parameters: "sigma=S | range-sigma=R,bearing-sigma-deg=B (required)",
        summary: "per-axis Kalman gains, manoeuvre level from the innovations: given only the sensor noise",
    },
];

/// The sensor and target figures that set the defaults the papers tied to
/// their own noise levels ([`ScheduleSpec::parse_scaled`]; unscaled, `m2`
/// with n-max 1000 or `m1` with α = 0.05 lag by kilometres in a turn, Li's
/// Δρ = 1 m and Liu's σ_m² = 25 m² misjudge every innovation of another
/// sensor).
///
/// * `m1` α and `m3` α₀: α_K, Kalata's steady-state α for the tracking
///   index Λ = σ_w·T²/σ with σ_w = a_max/2 (the rule of the default tracker,
///   `crate::track::defaults` rule 2); `least-squares` and `m3` n-max,
///   `li-improved` and `liu-count-adjusted` k-max (the same count-based
///   gains, eq. 24 / eq. 4 / eq. 5, with the count bound this crate adds):
///   the first n with α̂(n) ≤ α_K (the least-squares gains held at α_K);
/// * `li-improved` Δρ = σ; `liu-residual`, `liu-adaptive` σ_m² = σ²;
///   `liu-count-adjusted` threshold = 14σ and `liu-adaptive` limit = 3.8σ
///   (the paper's 70 m and 19 m at its σ = 5 m);
/// * `auto`: σ.
///
/// `fixed`, `m4`, `bank` and `tcas-firmness` have no such defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensorScale {
    /// σ per axis, m, > 0.
    pub sigma: f64,
    /// The nominal interval T, s, > 0.
    pub period: f64,
    /// a_max, the manoeuvre level, m/s², > 0.
    pub max_acceleration: f64,
}

impl SensorScale {
    /// Liu, Wang & Yang's §3.2.2 threshold (70 m) over their σ (5 m).
    pub const LIU_THRESHOLD_SIGMAS: f64 = 14.0;
    /// Liu, Wang & Yang's §2.1.5 limit (19 m) over their σ (5 m).
    pub const LIU_LIMIT_SIGMAS: f64 = 3.8;

    /// α_K for Λ = (a_max/2)·T²/σ.
    pub fn steady_state_alpha(&self) -> Result<f64, ConfigError> {
        let lambda =
            crate::design::tracking_index(0.5 * self.max_acceleration, self.sigma, self.period)
                .map_err(|_| ConfigError::OutOfRange { parameter: "sigma" })?;
        crate::design::kalata_gains(lambda)
            .map(|g| g.alpha().min(1.0))
            .map_err(|_| ConfigError::OutOfRange { parameter: "sigma" })
    }

    /// The first n ≥ 3 with α̂(n) ≤ α_K (at most the n-max limit).
    pub fn least_squares_n_max(&self) -> Result<u32, ConfigError> {
        let alpha = self.steady_state_alpha()?;
        let mut n = 3u32;
        while n < LeastSquaresConfig::N_MAX_LIMIT
            && crate::gains::least_squares_alpha::<f64>(n) > alpha
        {
            n = n.saturating_add(1);
        }
        Ok(n)
    }
}

/// A parsed spec: which schedule, with which configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScheduleSpec {
    /// `fixed`, `liu-fixed`.
    Fixed(FixedConfig),
    /// `m1`.
    FixedAlpha(FixedAlphaConfig),
    /// `least-squares`, `m2`, `liu-count`.
    LeastSquares(LeastSquaresConfig),
    /// `m3`.
    LinearCombination(LinearCombinationConfig),
    /// `m4`.
    MovingWindow(MovingWindowConfig),
    /// `bank`, `m5`: an estimator ([`crate::bank`]), not a schedule.
    Bank(BankConfig),
    /// `li-improved`.
    LiImproved(LiImprovedConfig),
    /// `liu-count-adjusted`.
    ScanCountAdjusted(ScanCountAdjustedConfig),
    /// `liu-residual`.
    ResidualAccumulation(ResidualAccumulationConfig),
    /// `liu-adaptive`.
    AdaptiveSwitch(AdaptiveSwitchConfig),
    /// `tcas-firmness`.
    Firmness,
    /// `auto`.
    Auto(AutoConfig),
}

/// What is wrong with a spec string.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SpecErrorKind {
    /// Nothing before the `:`.
    Empty,
    /// The name is not in [`SCHEDULES`].
    UnknownSchedule,
    /// A `,`-separated part is empty (e.g. `m1:` or `m4:a=1,,b=2`).
    EmptyParameter,
    /// A part has no `=`.
    MissingValue,
    /// The key is not one of this schedule's.
    UnknownParameter,
    /// The key was given twice.
    DuplicateParameter,
    /// The value does not parse as the key's kind of number.
    InvalidNumber,
    /// A parameter without a default was not given.
    MissingParameter {
        /// The parameter's key.
        parameter: &'static str,
    },
    /// The values parse but the configuration is refused.
    Config(ConfigError),
}

/// A spec string error and the byte offset where it was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpecError {
    /// What is wrong.
    pub kind: SpecErrorKind,
    /// Byte offset in the spec string of the part at fault.
    pub offset: usize,
}

impl fmt::Display for SpecErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpecErrorKind::Empty => f.write_str("empty schedule name"),
            SpecErrorKind::UnknownSchedule => f.write_str("unknown schedule name"),
            SpecErrorKind::EmptyParameter => f.write_str("empty parameter"),
            SpecErrorKind::MissingValue => f.write_str("parameter without `=value`"),
            SpecErrorKind::UnknownParameter => f.write_str("unknown parameter for this schedule"),
            SpecErrorKind::DuplicateParameter => f.write_str("parameter given twice"),
            SpecErrorKind::InvalidNumber => f.write_str("value is not a valid number"),
            SpecErrorKind::MissingParameter { parameter } => {
                write!(f, "parameter `{parameter}` is required")
            }
            SpecErrorKind::Config(e) => fmt::Display::fmt(e, f),
        }
    }
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (at byte {})", self.kind, self.offset)
    }
}

impl core::error::Error for SpecError {}

fn number(v: &str) -> Result<f64, SpecErrorKind> {
    v.parse::<f64>().map_err(|_| SpecErrorKind::InvalidNumber)
}

fn integer<T: core::str::FromStr>(v: &str) -> Result<T, SpecErrorKind> {
    v.parse::<T>().map_err(|_| SpecErrorKind::InvalidNumber)
}

/// The most keys any schedule has.
const MAX_KEYS: usize = 8;

impl ScheduleSpec {
    /// The spec with default parameters for `name` (or an alias).
    pub fn default_for(name: &str) -> Option<Self> {
        Some(match name {
            "fixed" => ScheduleSpec::Fixed(FixedConfig {
                alpha: f64::NAN,
                beta: f64::NAN,
                gamma: None,
            }),
            "liu-fixed" => ScheduleSpec::Fixed(FixedConfig::LIU),
            "m1" => ScheduleSpec::FixedAlpha(FixedAlphaConfig::DEFAULT),
            "least-squares" | "m2" | "liu-count" => {
                ScheduleSpec::LeastSquares(LeastSquaresConfig::DEFAULT)
            }
            "m3" => ScheduleSpec::LinearCombination(LinearCombinationConfig::DEFAULT),
            "m4" => ScheduleSpec::MovingWindow(MovingWindowConfig::DEFAULT),
            "bank" | "m5" => ScheduleSpec::Bank(BankConfig::DEFAULT),
            "li-improved" => ScheduleSpec::LiImproved(LiImprovedConfig::DEFAULT),
            "liu-count-adjusted" => {
                ScheduleSpec::ScanCountAdjusted(ScanCountAdjustedConfig::DEFAULT)
            }
            "liu-residual" => {
                ScheduleSpec::ResidualAccumulation(ResidualAccumulationConfig::DEFAULT)
            }
            "liu-adaptive" => ScheduleSpec::AdaptiveSwitch(AdaptiveSwitchConfig::DEFAULT),
            "tcas-firmness" => ScheduleSpec::Firmness,
            "auto" => ScheduleSpec::Auto(AutoConfig::UNSET),
            _ => return None,
        })
    }

    /// The canonical name (the first of [`ScheduleInfo::names`]).
    pub fn name(&self) -> &'static str {
        match self {
            ScheduleSpec::Fixed(_) => "fixed",
            ScheduleSpec::FixedAlpha(_) => "m1",
            ScheduleSpec::LeastSquares(_) => "least-squares",
            ScheduleSpec::LinearCombination(_) => "m3",
            ScheduleSpec::MovingWindow(_) => "m4",
            ScheduleSpec::Bank(_) => "bank",
            ScheduleSpec::LiImproved(_) => "li-improved",
            ScheduleSpec::ScanCountAdjusted(_) => "liu-count-adjusted",
            ScheduleSpec::ResidualAccumulation(_) => "liu-residual",
            ScheduleSpec::AdaptiveSwitch(_) => "liu-adaptive",
            ScheduleSpec::Firmness => "tcas-firmness",
            ScheduleSpec::Auto(_) => "auto",
        }
    }

    /// This schedule's parameter keys.
    pub fn keys(&self) -> &'static [&'static str] {
        match self {
            ScheduleSpec::Fixed(_) => &["alpha", "beta", "gamma"],
            ScheduleSpec::FixedAlpha(_) => &["alpha"],
            ScheduleSpec::LeastSquares(_) => &["n-max"],
            ScheduleSpec::LinearCombination(_) => &["alpha0", "w", "steps", "window", "n-max"],
            ScheduleSpec::MovingWindow(_) => &["alpha0", "min", "max", "steps", "window"],
            ScheduleSpec::Bank(_) => &["k", "min", "max"],
            ScheduleSpec::LiImproved(_) => &["r", "range-error", "bearing-error", "k-max"],
            ScheduleSpec::ScanCountAdjusted(_) => &["threshold", "k-max"],
            ScheduleSpec::ResidualAccumulation(_) => &["n", "sigma-m2", "alpha-min"],
            ScheduleSpec::AdaptiveSwitch(_) => {
                &["limit", "alpha", "beta", "n", "sigma-m2", "alpha-min"]
            }
            ScheduleSpec::Firmness => &[],
            ScheduleSpec::Auto(_) => &["sigma", "range-sigma", "bearing-sigma-deg"],
        }
    }

    /// Sets key number `key` (an index into [`Self::keys`]) from `value`.
    fn set(&mut self, key: usize, value: &str) -> Result<(), SpecErrorKind> {
        match (self, key) {
            (ScheduleSpec::Fixed(c), 0) => c.alpha = number(value)?,
            (ScheduleSpec::Fixed(c), 1) => c.beta = number(value)?,
            (ScheduleSpec::Fixed(c), 2) => c.gamma = Some(number(value)?),
            (ScheduleSpec::FixedAlpha(c), 0) => c.alpha = number(value)?,
            (ScheduleSpec::LeastSquares(c), 0) => c.n_max = integer(value)?,
            (ScheduleSpec::LinearCombination(c), 0) => c.alpha0 = number(value)?,
            (ScheduleSpec::LinearCombination(c), 1) => c.w = number(value)?,
            (ScheduleSpec::LinearCombination(c), 2) => c.steps = integer(value)?,
            (ScheduleSpec::LinearCombination(c), 3) => c.window = integer(value)?,
            (ScheduleSpec::LinearCombination(c), 4) => c.n_max = integer(value)?,
            (ScheduleSpec::MovingWindow(c), 0) => c.alpha0 = number(value)?,
            (ScheduleSpec::MovingWindow(c), 1) => c.alpha_min = number(value)?,
            (ScheduleSpec::MovingWindow(c), 2) => c.alpha_max = number(value)?,
            (ScheduleSpec::MovingWindow(c), 3) => c.steps = integer(value)?,
            (ScheduleSpec::MovingWindow(c), 4) => c.window = integer(value)?,
            (ScheduleSpec::Bank(c), 0) => c.k = integer(value)?,
            (ScheduleSpec::Bank(c), 1) => c.alpha_min = number(value)?,
            (ScheduleSpec::Bank(c), 2) => c.alpha_max = number(value)?,
            (ScheduleSpec::LiImproved(c), 0) => c.max_ratio = number(value)?,
            (ScheduleSpec::LiImproved(c), 1) => c.range_error = number(value)?,
            (ScheduleSpec::LiImproved(c), 2) => c.bearing_error = number(value)?,
            (ScheduleSpec::LiImproved(c), 3) => c.k_max = integer(value)?,
            (ScheduleSpec::ScanCountAdjusted(c), 0) => c.threshold = number(value)?,
            (ScheduleSpec::ScanCountAdjusted(c), 1) => c.k_max = integer(value)?,
            (ScheduleSpec::ResidualAccumulation(c), 0) => c.n = integer(value)?,
            (ScheduleSpec::ResidualAccumulation(c), 1) => c.sigma_m2 = number(value)?,
            (ScheduleSpec::ResidualAccumulation(c), 2) => c.alpha_min = number(value)?,
            (ScheduleSpec::AdaptiveSwitch(c), 0) => c.limit = number(value)?,
            (ScheduleSpec::AdaptiveSwitch(c), 1) => c.alpha = number(value)?,
            (ScheduleSpec::AdaptiveSwitch(c), 2) => c.beta = number(value)?,
            (ScheduleSpec::AdaptiveSwitch(c), 3) => c.residual.n = integer(value)?,
            (ScheduleSpec::AdaptiveSwitch(c), 4) => c.residual.sigma_m2 = number(value)?,
            (ScheduleSpec::AdaptiveSwitch(c), 5) => c.residual.alpha_min = number(value)?,
            (ScheduleSpec::Auto(c), 0) => c.sigma = Some(number(value)?),
            (ScheduleSpec::Auto(c), 1) => c.range_sigma = Some(number(value)?),
            (ScheduleSpec::Auto(c), 2) => c.bearing_sigma_deg = Some(number(value)?),
            _ => return Err(SpecErrorKind::UnknownParameter),
        }
        Ok(())
    }

    /// Checks the configuration's ranges (capacities are checked when a
    /// schedule or bank is built).
    pub fn validate(&self) -> Result<(), ConfigError> {
        match self {
            ScheduleSpec::Fixed(c) => c.validate(),
            ScheduleSpec::FixedAlpha(c) => c.validate(),
            ScheduleSpec::LeastSquares(c) => c.validate(),
            ScheduleSpec::LinearCombination(c) => c.validate(),
            ScheduleSpec::MovingWindow(c) => c.validate(),
            ScheduleSpec::Bank(c) => c.validate(),
            ScheduleSpec::LiImproved(c) => c.validate(),
            ScheduleSpec::ScanCountAdjusted(c) => c.validate(),
            ScheduleSpec::ResidualAccumulation(c) => c.validate(),
            ScheduleSpec::AdaptiveSwitch(c) => c.validate(),
            ScheduleSpec::Firmness => Ok(()),
            ScheduleSpec::Auto(c) => c.validate(),
        }
    }

    /// Parses `name[:key=value,...]`.
    pub fn parse(spec: &str) -> Result<Self, SpecError> {
        Self::parse_with(spec, None)
    }

    /// [`Self::parse`] with the defaults that the papers tied to their own
    /// noise levels taken from `sensor` instead ([`SensorScale`]); keys the
    /// spec gives keep their values.
    pub fn parse_scaled(spec: &str, sensor: &SensorScale) -> Result<Self, SpecError> {
        Self::parse_with(spec, Some(sensor))
    }

    /// Replaces the defaults [`SensorScale`] covers (see there).
    fn scale_defaults(&mut self, sensor: &SensorScale) -> Result<(), ConfigError> {
        let sigma = sensor.sigma;
        match self {
            ScheduleSpec::FixedAlpha(c) => c.alpha = sensor.steady_state_alpha()?,
            ScheduleSpec::LeastSquares(c) => c.n_max = sensor.least_squares_n_max()?,
            ScheduleSpec::LinearCombination(c) => {
                c.alpha0 = sensor.steady_state_alpha()?;
                c.n_max = sensor.least_squares_n_max()?;
            }
            ScheduleSpec::LiImproved(c) => {
                c.range_error = sigma;
                c.k_max = sensor.least_squares_n_max()?;
            }
            ScheduleSpec::ScanCountAdjusted(c) => {
                c.threshold = sigma * SensorScale::LIU_THRESHOLD_SIGMAS;
                c.k_max = sensor.least_squares_n_max()?;
            }
            ScheduleSpec::ResidualAccumulation(c) => c.sigma_m2 = sigma * sigma,
            ScheduleSpec::AdaptiveSwitch(c) => {
                c.limit = sigma * SensorScale::LIU_LIMIT_SIGMAS;
                c.residual.sigma_m2 = sigma * sigma;
            }
            ScheduleSpec::Auto(c) => *c = AutoConfig::cartesian(sigma),
            ScheduleSpec::Fixed(_)
            | ScheduleSpec::MovingWindow(_)
            | ScheduleSpec::Bank(_)
            | ScheduleSpec::Firmness => {}
        }
        Ok(())
    }

    fn parse_with(spec: &str, sensor: Option<&SensorScale>) -> Result<Self, SpecError> {
        let err = |kind, offset| SpecError { kind, offset };
        let (name, params) = match spec.split_once(':') {
            Some((n, p)) => (n, Some(p)),
            None => (spec, None),
        };
        if name.is_empty() {
            return Err(err(SpecErrorKind::Empty, 0));
        }
        let mut parsed = Self::default_for(name).ok_or(err(SpecErrorKind::UnknownSchedule, 0))?;
        if let Some(sensor) = sensor {
            parsed
                .scale_defaults(sensor)
                .map_err(|e| err(SpecErrorKind::Config(e), 0))?;
        }
        let keys = parsed.keys();
        // Byte offset of each key given, to point config errors at it.
        let mut given: [Option<usize>; MAX_KEYS] = [None; MAX_KEYS];
        if let Some(params) = params {
            // Offsets within a string's length: saturation never happens.
            let mut offset = name.len().saturating_add(1);
            for part in params.split(',') {
                if part.is_empty() {
                    return Err(err(SpecErrorKind::EmptyParameter, offset));
                }
                let (key, value) = part
                    .split_once('=')
                    .ok_or(err(SpecErrorKind::MissingValue, offset))?;
                let index = keys
                    .iter()
                    .position(|k| *k == key)
                    .ok_or(err(SpecErrorKind::UnknownParameter, offset))?;
                let slot = given
                    .get_mut(index)
                    .ok_or(err(SpecErrorKind::UnknownParameter, offset))?;
                if slot.is_some() {
                    return Err(err(SpecErrorKind::DuplicateParameter, offset));
                }
                *slot = Some(offset);
                parsed.set(index, value).map_err(|kind| {
                    err(kind, offset.saturating_add(key.len()).saturating_add(1))
                })?;
                offset = offset.saturating_add(part.len()).saturating_add(1);
            }
        }
        if name == "fixed" {
            // `fixed` has no defaults: its α and β (keys 0 and 1) are required.
            for (index, parameter) in [(0, "alpha"), (1, "beta")] {
                if given.get(index).copied().flatten().is_none() {
                    return Err(err(
                        SpecErrorKind::MissingParameter { parameter },
                        spec.len(),
                    ));
                }
            }
        }
        if let ScheduleSpec::Auto(c) = &parsed {
            // `auto` has no sensor default: σ, or σ_R with σ_B, is required.
            if !c.has_sensor() {
                return Err(err(
                    SpecErrorKind::MissingParameter { parameter: "sigma" },
                    spec.len(),
                ));
            }
        }
        parsed.validate().map_err(|e| {
            let parameter = match e {
                ConfigError::OutOfRange { parameter }
                | ConfigError::NotRepresentable { parameter }
                | ConfigError::ExceedsCapacity { parameter, .. } => Some(parameter),
                ConfigError::NotASchedule => None,
            };
            let offset = parameter
                .and_then(|p| keys.iter().position(|k| *k == p))
                .and_then(|i| given.get(i).copied().flatten())
                .unwrap_or(0);
            err(SpecErrorKind::Config(e), offset)
        })?;
        Ok(parsed)
    }
}

impl core::str::FromStr for ScheduleSpec {
    type Err = SpecError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::parse(s)
    }
}

impl fmt::Display for ScheduleSpec {
    /// The canonical spec with every parameter.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())?;
        match self {
            ScheduleSpec::Fixed(c) => {
                write!(f, ":alpha={},beta={}", c.alpha, c.beta)?;
                if let Some(g) = c.gamma {
                    write!(f, ",gamma={g}")?;
                }
                Ok(())
            }
            ScheduleSpec::FixedAlpha(c) => write!(f, ":alpha={}", c.alpha),
            ScheduleSpec::LeastSquares(c) => write!(f, ":n-max={}", c.n_max),
            ScheduleSpec::LinearCombination(c) => write!(
                f,
                ":alpha0={},w={},steps={},window={},n-max={}",
                c.alpha0, c.w, c.steps, c.window, c.n_max
            ),
            ScheduleSpec::MovingWindow(c) => write!(
                f,
                ":alpha0={},min={},max={},steps={},window={}",
                c.alpha0, c.alpha_min, c.alpha_max, c.steps, c.window
            ),
            ScheduleSpec::Bank(c) => {
                write!(f, ":k={},min={},max={}", c.k, c.alpha_min, c.alpha_max)
            }
            ScheduleSpec::LiImproved(c) => write!(
                f,
                ":r={},range-error={},bearing-error={},k-max={}",
                c.max_ratio, c.range_error, c.bearing_error, c.k_max
            ),
            ScheduleSpec::ScanCountAdjusted(c) => {
                write!(f, ":threshold={},k-max={}", c.threshold, c.k_max)
            }
            ScheduleSpec::ResidualAccumulation(c) => write!(
                f,
                ":n={},sigma-m2={},alpha-min={}",
                c.n, c.sigma_m2, c.alpha_min
            ),
            ScheduleSpec::AdaptiveSwitch(c) => write!(
                f,
                ":limit={},alpha={},beta={},n={},sigma-m2={},alpha-min={}",
                c.limit, c.alpha, c.beta, c.residual.n, c.residual.sigma_m2, c.residual.alpha_min
            ),
            ScheduleSpec::Firmness => Ok(()),
            ScheduleSpec::Auto(c) => {
                let mut separator = ':';
                let figures = [
                    ("sigma", c.sigma),
                    ("range-sigma", c.range_sigma),
                    ("bearing-sigma-deg", c.bearing_sigma_deg),
                ];
                for (key, value) in figures {
                    if let Some(v) = value {
                        write!(f, "{separator}{key}={v}")?;
                        separator = ',';
                    }
                }
                Ok(())
            }
        }
    }
}
