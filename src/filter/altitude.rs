//! Altitude tracker for TCAS intruders: an αβ filter (Al-Wagih & Abdulla
//! eqs. 3–10) on the pressure altitude the intruder's transponder reports,
//! giving altitude and vertical rate.
//!
//! Units are feet and seconds (ft, ft/s), not metres: the reports are
//! quantised in feet (100 ft Mode C, 25 ft Mode S) and every vertical
//! threshold the tracker feeds (TCAS ZTHR, ALIM, the ±1200 ft proximate
//! band) is in feet, so converting would only add a rounding.
//!
//! # Gains
//!
//! Fixed steady-state gains from Kalata's tracking index (P. R. Kalata,
//! "The tracking index: a generalized parameter for α-β and α-β-γ target
//! trackers", IEEE Trans. AES-20(2), 1984):
//!
//! * measurement noise: the quantisation error, uniform over one quantum q,
//!   so σ_v² = q²/12 (σ_v = 28.9 ft for Mode C, 7.2 ft for Mode S);
//! * manoeuvre: white vertical acceleration of standard deviation σ_a,
//!   0.1 g = 3.22 ft/s² by default ([`DEFAULT_MANOEUVRE_G`]): a level-off or
//!   the start of a climb, and less than the 0.25 g of an RA response, so
//!   the tracker smooths hard and lags such a response by a few seconds;
//! * λ = σ_a·T²/σ_v ([`crate::design::tracking_index`]), and the Kalman
//!   steady state of the αβ filter ([`crate::design::kalata_gains`], computed
//!   once in f64 and rounded to the tracker's type):
//!   α = −(λ² + 8λ − (λ + 4)·√(λ² + 8λ))/8,
//!   β = (λ² + 4λ − λ·√(λ² + 8λ))/4, which satisfy λ² = β²/(1 − α).
//!
//! With T = 1 s: Mode C λ = 0.1115, α = 0.3756, β = 0.0881; Mode S
//! λ = 0.4458, α = 0.6077, β = 0.2792 (golden values in host-tests
//! `tcas_altitude.rs`).
//!
//! The q²/12 model assumes the altitude moves through several quanta
//! between reports' errors decorrelating; for a level intruder the
//! quantisation error is a constant of at most q/2, which the filter passes
//! through as a constant altitude offset with zero vertical rate — the right
//! rate, an altitude no worse than the report.
//!
//! # Missing altitude
//!
//! An intruder that never reports altitude (Mode A only, or altitude
//! reporting switched off) is a valid, permanent state: [`AltitudeTracker::estimate`]
//! is `None` and the threat logic treats the intruder as non-altitude
//! reporting. A tracked intruder whose reports stop is coasted for at most
//! `max_coast` seconds, then reverts to that state.

use crate::design;
use crate::filter::{check_interval, AlphaBeta, FilterError, GainError, Gains, Phase};
use crate::num::Scalar;

/// Standard gravity in ft/s² (9.80665 m/s² / 0.3048 m/ft).
pub const STANDARD_GRAVITY_FT_PER_S2: f64 = 9.80665 / 0.3048;
/// Default vertical manoeuvre level σ_a, in g.
pub const DEFAULT_MANOEUVRE_G: f64 = 0.1;
/// Default design interval T, s (TCAS surveillance updates once a second).
pub const DEFAULT_INTERVAL_S: f64 = 1.0;
/// Default longest coast before an intruder counts as non-reporting, s.
pub const DEFAULT_MAX_COAST_S: f64 = 6.0;

/// The altitude quantum of the transponder's reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeQuantum {
    /// Mode C (Gillham code): 100 ft.
    ModeC,
    /// Mode S with 25 ft reporting (Q bit set).
    ModeS25,
}

impl AltitudeQuantum {
    /// The quantum q in feet.
    pub const fn feet(self) -> f64 {
        match self {
            AltitudeQuantum::ModeC => 100.0,
            AltitudeQuantum::ModeS25 => 25.0,
        }
    }
}

/// Why an altitude-tracker configuration was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeConfigError {
    /// The design interval is not a finite number > 0.
    IntervalNotPositive,
    /// The manoeuvre level σ_a is not a finite number > 0.
    ManoeuvreNotPositive,
    /// The longest coast is not a finite number ≥ 0, or not representable.
    InvalidCoast,
    /// The derived gains were refused (tracking index out of range).
    Gains(GainError),
}

impl core::fmt::Display for AltitudeConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AltitudeConfigError::IntervalNotPositive => {
                f.write_str("design interval must be a finite number > 0 s")
            }
            AltitudeConfigError::ManoeuvreNotPositive => {
                f.write_str("manoeuvre level must be a finite number > 0 ft/s²")
            }
            AltitudeConfigError::InvalidCoast => {
                f.write_str("longest coast must be a finite number >= 0 s")
            }
            AltitudeConfigError::Gains(e) => write!(f, "derived gains refused: {e}"),
        }
    }
}

impl core::error::Error for AltitudeConfigError {}

/// Configuration of an [`AltitudeTracker`]: its gains and how long it
/// coasts through missing reports.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeTrackerConfig<S: Scalar> {
    gains: Gains<S>,
    tracking_index: S,
    max_coast: S,
}

impl<S: Scalar> AltitudeTrackerConfig<S> {
    /// Gains from the quantisation noise σ_v = q/√12 and the manoeuvre level
    /// `manoeuvre_ft_per_s2` (σ_a) at the design interval `interval_s`, via
    /// [`design::kalata_gains`]; `max_coast_s` (≥ 0) is the longest run of missing
    /// reports that is coasted through.
    pub fn new(
        quantum: AltitudeQuantum,
        manoeuvre_ft_per_s2: f64,
        interval_s: f64,
        max_coast_s: f64,
    ) -> Result<Self, AltitudeConfigError> {
        // λ uses T², so a negative interval would pass unnoticed: check it.
        if !(interval_s.is_finite() && interval_s > 0.0) {
            return Err(AltitudeConfigError::IntervalNotPositive);
        }
        if !(manoeuvre_ft_per_s2.is_finite() && manoeuvre_ft_per_s2 > 0.0) {
            return Err(AltitudeConfigError::ManoeuvreNotPositive);
        }
        if !(max_coast_s.is_finite() && max_coast_s >= 0.0) {
            return Err(AltitudeConfigError::InvalidCoast);
        }
        // The inputs are checked above, so the design functions can only
        // fail by overflow; the gains are computed once, in f64, and rounded
        // to S (design::kalata_gains, Kalata 1984).
        let overflow = |_| AltitudeConfigError::Gains(GainError::NotFinite);
        let sigma_v = quantum.feet() / libm::sqrt(12.0);
        let lambda =
            design::tracking_index(manoeuvre_ft_per_s2, sigma_v, interval_s).map_err(overflow)?;
        let gains = design::kalata_gains(lambda)
            .map_err(overflow)?
            .convert::<S>()
            .map_err(AltitudeConfigError::Gains)?;
        let tracking_index = S::try_from_f64(lambda)
            .map_err(|_| AltitudeConfigError::Gains(GainError::NotFinite))?;
        let max_coast =
            S::try_from_f64(max_coast_s).map_err(|_| AltitudeConfigError::InvalidCoast)?;
        Ok(AltitudeTrackerConfig {
            gains,
            tracking_index,
            max_coast,
        })
    }

    /// The documented defaults for a quantum: σ_a = 0.1 g, T = 1 s, coast
    /// up to 6 s.
    pub fn default_for(quantum: AltitudeQuantum) -> Result<Self, AltitudeConfigError> {
        Self::new(
            quantum,
            DEFAULT_MANOEUVRE_G * STANDARD_GRAVITY_FT_PER_S2,
            DEFAULT_INTERVAL_S,
            DEFAULT_MAX_COAST_S,
        )
    }

    pub fn gains(&self) -> &Gains<S> {
        &self.gains
    }
    /// Kalata's λ the gains were derived from.
    pub fn tracking_index(&self) -> S {
        self.tracking_index
    }
    /// Longest coast through missing reports, s.
    pub fn max_coast(&self) -> S {
        self.max_coast
    }
}

/// Altitude and vertical rate of an intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeEstimate<S> {
    /// Pressure altitude, ft.
    pub altitude_ft: S,
    /// Vertical rate, ft/s (positive climbing); zero until the second report.
    pub vertical_rate_ft_per_s: S,
}

/// Whether and how well the intruder's altitude is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeStatus {
    /// No altitude: never reported, or reports stopped for longer than the
    /// configured coast.
    NotReporting,
    /// One report: altitude known, vertical rate taken as zero.
    OneReport,
    /// Two or more: altitude and vertical rate filtered.
    Tracking,
}

/// αβ altitude tracker (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeTracker<S: Scalar> {
    config: AltitudeTrackerConfig<S>,
    filter: AlphaBeta<S>,
    /// Time since the last report, s.
    coasted: S,
    /// Saturations counted by filters dropped when reports stopped.
    earlier_saturations: u32,
}

impl<S: Scalar> AltitudeTracker<S> {
    /// A tracker with no altitude yet (status `NotReporting`).
    pub fn new(config: AltitudeTrackerConfig<S>) -> Self {
        AltitudeTracker {
            config,
            filter: AlphaBeta::new(),
            coasted: S::ZERO,
            earlier_saturations: 0,
        }
    }

    pub fn config(&self) -> &AltitudeTrackerConfig<S> {
        &self.config
    }

    pub fn status(&self) -> AltitudeStatus {
        match self.filter.phase() {
            Phase::Empty => AltitudeStatus::NotReporting,
            Phase::OnePoint => AltitudeStatus::OneReport,
            Phase::Tracking => AltitudeStatus::Tracking,
        }
    }

    /// The current estimate; `None` for a non-reporting intruder.
    pub fn estimate(&self) -> Option<AltitudeEstimate<S>> {
        match self.filter.phase() {
            Phase::Empty => None,
            _ => Some(AltitudeEstimate {
                altitude_ft: self.filter.position(),
                vertical_rate_ft_per_s: self.filter.velocity(),
            }),
        }
    }

    /// Time since the last altitude report, s (zero right after one).
    pub fn since_last_report(&self) -> S {
        self.coasted
    }

    /// How many updates or coasts were discarded because they saturated.
    pub fn saturations(&self) -> u32 {
        self.filter
            .saturations()
            .saturating_add(self.earlier_saturations)
    }

    /// One surveillance scan, `dt` seconds after the previous one:
    /// `Some(altitude_ft)` if the reply carried an altitude, `None` if it did
    /// not. A missing altitude coasts the track; after more than
    /// `max_coast` seconds without one the tracker forgets the altitude and
    /// becomes `NotReporting`. Invalid input is refused with the filter's
    /// error and changes nothing.
    pub fn scan(&mut self, altitude_ft: Option<S>, dt: S) -> Result<AltitudeStatus, FilterError> {
        match altitude_ft {
            Some(z) => {
                self.filter.update(z, dt, &self.config.gains)?;
                self.coasted = S::ZERO;
            }
            None => {
                check_interval(dt)?;
                if self.filter.phase() == Phase::Empty {
                    return Ok(AltitudeStatus::NotReporting);
                }
                let coasted = self.coasted + dt;
                if !coasted.is_valid() || coasted > self.config.max_coast {
                    self.earlier_saturations = self.saturations();
                    self.filter = AlphaBeta::new();
                    self.coasted = S::ZERO;
                    return Ok(AltitudeStatus::NotReporting);
                }
                self.filter.coast(dt)?;
                self.coasted = coasted;
            }
        }
        Ok(self.status())
    }
}
