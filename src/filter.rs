//! Single-target estimators: the αβ and αβγ filters on one axis, and their
//! composition into 2-D and 3-D ([`Cartesian`]).
//!
//! * αβ: Al-Wagih & Abdulla, eqs. (3)–(8), two-point initialisation (9)–(10).
//! * αβγ: Tenne & Singh, eqs. (1)–(5), with their acceleration update
//!   `a += γ/(2T²)·e` (eq. 5).
//!
//! Both are one generic type, [`KinematicFilter`], whose `ORDER` (2 or 3) is the
//! number of kinematic states; an αβ filter is exactly an αβγ filter whose
//! acceleration is held at zero, so the shared code is the equations of
//! Tenne & Singh with the acceleration terms compiled out for `ORDER = 2`.
//!
//! # Contract
//!
//! * Gains come with every call ([`Gains`]), so a gain schedule can change them
//!   from one update to the next. [`Gains`] can only be constructed inside the
//!   stability region of the filter it is meant for.
//! * The interval `dt` is the time since the previous call (update or coast)
//!   and may differ on every call; β is divided by the actual interval
//!   (Al-Wagih eq. 8, Tenne & Singh eq. 4).
//! * A measurement or interval that is not a valid number, or an interval ≤ 0,
//!   is refused with a [`FilterError`] and the state is left untouched. So is
//!   an update whose arithmetic saturates (fixed point) or overflows (floats):
//!   it is counted in [`KinematicFilter::saturations`] and discarded.

use crate::num::Scalar;

pub mod altitude;
pub mod range_azimuth;

/// Why a filter refused a call. The filter's state is unchanged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FilterError {
    /// The measurement is NaN, infinite or a saturated fixed-point value.
    InvalidMeasurement,
    /// The interval is not a valid number, or is ≤ 0.
    InvalidInterval,
    /// The update's arithmetic left the representable range; it was discarded
    /// and counted.
    Saturated,
}

impl core::fmt::Display for FilterError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            FilterError::InvalidMeasurement => "measurement is not a finite number",
            FilterError::InvalidInterval => "sampling interval is not a finite number > 0",
            FilterError::Saturated => "update overflowed the number format and was discarded",
        })
    }
}

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

/// Smoothing gains (α, β, γ) that lie inside a stability region.
///
/// γ uses Tenne & Singh's convention: the acceleration correction is
/// γ/(2T²)·e (eq. 5). For αβ gains γ is zero.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Gains<S> {
    alpha: S,
    beta: S,
    gamma: S,
}

impl<S: Scalar> Gains<S> {
    /// αβ gains, checked against the stability triangle 0 < α < 2, β > 0,
    /// 2α + β < 4 (Al-Wagih & Abdulla eqs. 12–14).
    pub fn alpha_beta(alpha: S, beta: S) -> Result<Self, GainError> {
        if !alpha.is_valid() || !beta.is_valid() {
            return Err(GainError::NotFinite);
        }
        let two = S::ONE + S::ONE;
        if alpha <= S::ZERO || alpha >= two {
            return Err(GainError::AlphaOutOfRange);
        }
        if beta <= S::ZERO {
            return Err(GainError::BetaNotPositive);
        }
        if two * alpha + beta >= two * two {
            return Err(GainError::BetaTooLarge);
        }
        Ok(Gains {
            alpha,
            beta,
            gamma: S::ZERO,
        })
    }

    /// αβγ gains, checked against the stability volume of Tenne & Singh
    /// eqs. (7)–(8): the αβ triangle and 0 < γ < 4αβ/(2 − α).
    pub fn alpha_beta_gamma(alpha: S, beta: S, gamma: S) -> Result<Self, GainError> {
        let ab = Self::alpha_beta(alpha, beta)?;
        if !gamma.is_valid() {
            return Err(GainError::NotFinite);
        }
        if gamma <= S::ZERO {
            return Err(GainError::GammaNotPositive);
        }
        let two = S::ONE + S::ONE;
        // γ(2 − α) < 4αβ, multiplied out to avoid a division (2 − α > 0).
        if gamma * (two - alpha) >= two * two * alpha * beta {
            return Err(GainError::GammaTooLarge);
        }
        Ok(Gains { gamma, ..ab })
    }

    /// αβ gains from `f64` values (for configuration and tools).
    pub fn alpha_beta_f64(alpha: f64, beta: f64) -> Result<Self, GainError> {
        let c = |v| S::try_from_f64(v).map_err(|_| GainError::NotFinite);
        Self::alpha_beta(c(alpha)?, c(beta)?)
    }

    /// αβγ gains from `f64` values (for configuration and tools).
    pub fn alpha_beta_gamma_f64(alpha: f64, beta: f64, gamma: f64) -> Result<Self, GainError> {
        let c = |v| S::try_from_f64(v).map_err(|_| GainError::NotFinite);
        Self::alpha_beta_gamma(c(alpha)?, c(beta)?, c(gamma)?)
    }

    pub fn alpha(&self) -> S {
        self.alpha
    }
    pub fn beta(&self) -> S {
        self.beta
    }
    /// Zero for αβ gains.
    pub fn gamma(&self) -> S {
        self.gamma
    }

    /// The same gains in another representation (rounded to nearest). The
    /// stability inequalities are strict and a rounding step is far smaller
    /// than any margin that matters, but the result is re-checked anyway.
    pub fn convert<T: Scalar>(&self) -> Result<Gains<T>, GainError> {
        let c = |v: S| T::try_from_f64(v.to_f64()).map_err(|_| GainError::NotFinite);
        if self.gamma == S::ZERO {
            Gains::alpha_beta(c(self.alpha)?, c(self.beta)?)
        } else {
            Gains::alpha_beta_gamma(c(self.alpha)?, c(self.beta)?, c(self.gamma)?)
        }
    }
}

/// What an update did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum UpdateOutcome<S> {
    /// First measurement: the position is taken as the estimate (Al-Wagih §3).
    FirstPoint,
    /// Second measurement: velocity from the difference (Al-Wagih eq. 9).
    SecondPoint,
    /// A filtered update with the prediction it corrected and its residual
    /// z − prediction (Al-Wagih eq. 4).
    Filtered(Innovation<S>),
}

/// The prediction an update corrected and the innovation (residual).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Innovation<S> {
    /// Predicted position x_p (Al-Wagih eq. 3, Tenne & Singh eq. 1).
    pub predicted: S,
    /// e = z − x_p (Al-Wagih eq. 4).
    pub residual: S,
}

/// Predicted kinematic state after an interval, without changing the filter.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Prediction<S> {
    pub position: S,
    pub velocity: S,
    pub acceleration: S,
}

/// Which stage of two-point initialisation the filter is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Phase {
    /// No measurement yet.
    Empty,
    /// One measurement: position known, velocity not.
    OnePoint,
    /// Two or more: filtering.
    Tracking,
}

/// A one-axis kinematic filter: αβ for `ORDER = 2`, αβγ for `ORDER = 3`.
///
/// Use the aliases [`AlphaBeta`] and [`AlphaBetaGamma`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KinematicFilter<S, const ORDER: usize> {
    phase: Phase,
    position: S,
    velocity: S,
    acceleration: S,
    /// While `OnePoint`: time since the first measurement (coasts add to it).
    since_first: S,
    last: Option<Innovation<S>>,
    saturations: u32,
}

/// αβ filter, Al-Wagih & Abdulla eqs. (3)–(10).
pub type AlphaBeta<S> = KinematicFilter<S, 2>;
/// αβγ filter, Tenne & Singh eqs. (1)–(5).
pub type AlphaBetaGamma<S> = KinematicFilter<S, 3>;

impl<S: Scalar, const ORDER: usize> Default for KinematicFilter<S, ORDER> {
    fn default() -> Self {
        Self::new()
    }
}

#[inline]
fn check_interval<S: Scalar>(dt: S) -> Result<(), FilterError> {
    if dt.is_valid() && dt > S::ZERO {
        Ok(())
    } else {
        Err(FilterError::InvalidInterval)
    }
}

impl<S: Scalar, const ORDER: usize> KinematicFilter<S, ORDER> {
    const HAS_ACCELERATION: bool = {
        assert!(
            ORDER == 2 || ORDER == 3,
            "ORDER is 2 (alpha-beta) or 3 (alpha-beta-gamma)"
        );
        ORDER == 3
    };

    /// An empty filter, waiting for its first measurement.
    pub const fn new() -> Self {
        KinematicFilter {
            phase: Phase::Empty,
            position: S::ZERO,
            velocity: S::ZERO,
            acceleration: S::ZERO,
            since_first: S::ZERO,
            last: None,
            saturations: 0,
        }
    }

    /// A filter already tracking from a known state (e.g. a handed-over
    /// track). The acceleration is ignored for `ORDER = 2`.
    pub fn from_state(position: S, velocity: S, acceleration: S) -> Result<Self, FilterError> {
        if !(position.is_valid() && velocity.is_valid() && acceleration.is_valid()) {
            return Err(FilterError::InvalidMeasurement);
        }
        Ok(KinematicFilter {
            phase: Phase::Tracking,
            position,
            velocity,
            acceleration: if Self::HAS_ACCELERATION {
                acceleration
            } else {
                S::ZERO
            },
            ..Self::new()
        })
    }

    pub fn phase(&self) -> Phase {
        self.phase
    }
    /// Smoothed position x_s.
    pub fn position(&self) -> S {
        self.position
    }
    /// Smoothed velocity v_s (zero before the second measurement).
    pub fn velocity(&self) -> S {
        self.velocity
    }
    /// Smoothed acceleration a_s (always zero for αβ).
    pub fn acceleration(&self) -> S {
        self.acceleration
    }
    /// Prediction and residual of the last filtered update (kept for adaptive
    /// gain schedules and gates); `None` until the first filtered update.
    pub fn last_innovation(&self) -> Option<Innovation<S>> {
        self.last
    }
    /// How many updates or coasts were discarded because they saturated.
    pub fn saturations(&self) -> u32 {
        self.saturations
    }

    /// The state predicted `dt` ahead, without changing the filter
    /// (Tenne & Singh eqs. 1–2; for αβ, Al-Wagih eq. 3).
    pub fn predict(&self, dt: S) -> Result<Prediction<S>, FilterError> {
        check_interval(dt)?;
        let p = self.extrapolate(dt);
        if p.position.is_valid() && p.velocity.is_valid() {
            Ok(p)
        } else {
            Err(FilterError::Saturated)
        }
    }

    #[inline]
    fn extrapolate(&self, dt: S) -> Prediction<S> {
        if Self::HAS_ACCELERATION {
            let half = S::from_f64_lossy(0.5);
            Prediction {
                position: self.position + dt * self.velocity + half * dt * dt * self.acceleration,
                velocity: self.velocity + dt * self.acceleration,
                acceleration: self.acceleration,
            }
        } else {
            Prediction {
                position: self.position + dt * self.velocity,
                velocity: self.velocity,
                acceleration: S::ZERO,
            }
        }
    }

    /// Incorporates measurement `z`, taken `dt` after the previous call.
    ///
    /// * First measurement: x_s = z, no velocity yet (`dt` is checked but
    ///   otherwise unused).
    /// * Second: v_s = (z₂ − z₁)/T (Al-Wagih eq. 9), x_s = z₂, where T is the
    ///   total time since the first measurement, coasts included. The
    ///   acceleration of an αβγ filter starts at zero.
    /// * Then: predict (Tenne & Singh eqs. 1–2), e = z − x_p (Al-Wagih eq. 4),
    ///   x_s = x_p + αe (eq. 6), v_s = v_p + (β/T)e (eq. 8; Tenne & Singh
    ///   eq. 4), a_s = a_s + γ/(2T²)·e (Tenne & Singh eq. 5).
    pub fn update(
        &mut self,
        z: S,
        dt: S,
        gains: &Gains<S>,
    ) -> Result<UpdateOutcome<S>, FilterError> {
        if !z.is_valid() {
            return Err(FilterError::InvalidMeasurement);
        }
        check_interval(dt)?;
        match self.phase {
            Phase::Empty => {
                self.position = z;
                self.velocity = S::ZERO;
                self.acceleration = S::ZERO;
                self.since_first = S::ZERO;
                self.phase = Phase::OnePoint;
                Ok(UpdateOutcome::FirstPoint)
            }
            Phase::OnePoint => {
                let elapsed = self.since_first + dt;
                let velocity = (z - self.position) / elapsed;
                if !velocity.is_valid() {
                    self.saturations = self.saturations.saturating_add(1);
                    return Err(FilterError::Saturated);
                }
                self.position = z;
                self.velocity = velocity;
                self.phase = Phase::Tracking;
                Ok(UpdateOutcome::SecondPoint)
            }
            Phase::Tracking => {
                let p = self.extrapolate(dt);
                let residual = z - p.position;
                let position = p.position + gains.alpha * residual;
                let velocity = p.velocity + gains.beta * residual / dt;
                let acceleration = if Self::HAS_ACCELERATION {
                    let two = S::ONE + S::ONE;
                    p.acceleration + gains.gamma * residual / (two * dt * dt)
                } else {
                    S::ZERO
                };
                // Invalid values are sticky, so checking the outputs (and the
                // residual we report) covers every intermediate.
                if !(position.is_valid()
                    && velocity.is_valid()
                    && acceleration.is_valid()
                    && residual.is_valid())
                {
                    self.saturations = self.saturations.saturating_add(1);
                    return Err(FilterError::Saturated);
                }
                self.position = position;
                self.velocity = velocity;
                self.acceleration = acceleration;
                let innovation = Innovation {
                    predicted: p.position,
                    residual,
                };
                self.last = Some(innovation);
                Ok(UpdateOutcome::Filtered(innovation))
            }
        }
    }

    /// No measurement this scan: advance the state by `dt` (predict only).
    /// Before the second measurement there is no velocity to extrapolate with,
    /// so the position holds and the interval is remembered for eq. (9).
    pub fn coast(&mut self, dt: S) -> Result<(), FilterError> {
        check_interval(dt)?;
        match self.phase {
            Phase::Empty => Ok(()),
            Phase::OnePoint => {
                let since_first = self.since_first + dt;
                if !since_first.is_valid() {
                    self.saturations = self.saturations.saturating_add(1);
                    return Err(FilterError::Saturated);
                }
                self.since_first = since_first;
                Ok(())
            }
            Phase::Tracking => {
                let p = self.extrapolate(dt);
                if !(p.position.is_valid() && p.velocity.is_valid()) {
                    self.saturations = self.saturations.saturating_add(1);
                    return Err(FilterError::Saturated);
                }
                self.position = p.position;
                self.velocity = p.velocity;
                Ok(())
            }
        }
    }
}

/// `D` independent one-axis filters (x, y[, z]) updated together: a 2-D or
/// 3-D αβ / αβγ tracker. An update either applies to every axis or, if any
/// axis refuses it, to none.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cartesian<S, const ORDER: usize, const D: usize> {
    axes: [KinematicFilter<S, ORDER>; D],
}

impl<S: Scalar, const ORDER: usize, const D: usize> Default for Cartesian<S, ORDER, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, const ORDER: usize, const D: usize> Cartesian<S, ORDER, D> {
    pub const fn new() -> Self {
        Cartesian {
            axes: [KinematicFilter::new(); D],
        }
    }

    pub fn axes(&self) -> &[KinematicFilter<S, ORDER>; D] {
        &self.axes
    }

    pub fn axis(&self, i: usize) -> Option<&KinematicFilter<S, ORDER>> {
        self.axes.get(i)
    }

    pub fn phase(&self) -> Phase {
        // All axes move through the phases together.
        self.axes.first().map_or(Phase::Empty, |a| a.phase())
    }

    pub fn position(&self) -> [S; D] {
        self.axes.map(|a| a.position())
    }

    pub fn velocity(&self) -> [S; D] {
        self.axes.map(|a| a.velocity())
    }

    /// Sum of the axes' saturation counters.
    pub fn saturations(&self) -> u32 {
        self.axes
            .iter()
            .fold(0u32, |n, a| n.saturating_add(a.saturations()))
    }

    /// Updates every axis with the same gains.
    pub fn update(
        &mut self,
        z: [S; D],
        dt: S,
        gains: &Gains<S>,
    ) -> Result<[UpdateOutcome<S>; D], FilterError> {
        self.update_per_axis(z, dt, &[*gains; D])
    }

    /// Updates each axis with its own gains (schedules that adapt per axis).
    pub fn update_per_axis(
        &mut self,
        z: [S; D],
        dt: S,
        gains: &[Gains<S>; D],
    ) -> Result<[UpdateOutcome<S>; D], FilterError> {
        let mut next = self.axes;
        let mut out = [UpdateOutcome::FirstPoint; D];
        let axes = self
            .axes
            .iter_mut()
            .zip(next.iter_mut())
            .zip(out.iter_mut());
        for (((current, candidate), outcome), (z, gains)) in axes.zip(z.iter().zip(gains)) {
            match candidate.update(*z, dt, gains) {
                Ok(o) => *outcome = o,
                Err(e) => {
                    // Keep the saturation count of the refused update.
                    current.saturations = candidate.saturations;
                    return Err(e);
                }
            }
        }
        self.axes = next;
        Ok(out)
    }

    /// Coasts every axis (no measurement this scan).
    pub fn coast(&mut self, dt: S) -> Result<(), FilterError> {
        let mut next = self.axes;
        for (current, candidate) in self.axes.iter_mut().zip(next.iter_mut()) {
            if let Err(e) = candidate.coast(dt) {
                // Keep the saturation count of the refused coast.
                current.saturations = candidate.saturations;
                return Err(e);
            }
        }
        self.axes = next;
        Ok(())
    }
}
