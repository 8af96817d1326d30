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
//! * Gains come with every call, so a gain schedule can change them from one
//!   update to the next. [`Gains`] can only be constructed inside the
//!   stability region of the filter it is meant for.
//! * The interval `dt` is the time since the previous call (update or coast)
//!   that the filter took, and may differ on every call (a skipped
//!   measurement, [`UpdateOutcome::Skipped`], changes nothing: the next
//!   interval counts from before it); β is divided by the actual interval
//!   (Al-Wagih eq. 8, Tenne & Singh eq. 4). The gains that depend on the
//!   interval (β/T, γ/(2T²)) are formed once per interval in a [`StepGains`]
//!   (a tracker's interval is the same for all its tracks), so the
//!   per-update path ([`KinematicFilter::update_step`],
//!   [`Cartesian::update_step`]) has no division; `update(z, dt, &gains)`
//!   builds the [`StepGains`] and calls it.
//! * A measurement or interval that is not a valid number, or an interval ≤ 0,
//!   is refused with a [`FilterError`] and the state is left untouched.
//! * The filters are specified for intervals of [`MIN_INTERVAL_S`] to
//!   [`MAX_INTERVAL_S`] ([`IntervalSpan`]). These filters compute the
//!   papers' equations for any interval > 0 (their arithmetic is checked
//!   beyond that range); what holds a track applies the interval policy,
//!   never refusing a report for its timing: after a longer interval the
//!   estimate restarts (the report is the first point of a new two-point
//!   initialisation, [`UpdateOutcome::Restarted`]), a report closer than the
//!   shortest is skipped with the state untouched ([`UpdateOutcome::Skipped`]):
//!   [`crate::gain::ScheduledFilter`] (any schedule), the M5 bank
//!   ([`crate::bank`]) and the track table (on the interval between scans; a
//!   coasting track steps by each scan's interval). So is
//!   an update whose arithmetic saturates (fixed point) or overflows (floats):
//!   it is counted in [`KinematicFilter::saturations`] and discarded.

use crate::num::{AddProduct, Numeric, Quantity};

pub use crate::gains::{GainError, Gains};

pub mod altitude;
pub mod auto;
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

impl core::error::Error for FilterError {}

/// The shortest interval between two measurements of one target that the
/// filters are specified for, s: the envelope's ([`crate::envelope::INTERVAL_S`]).
/// Two reports closer carry no velocity information, and the velocity gain
/// β/T would multiply their noise by up to 1/T.
pub const MIN_INTERVAL_S: f64 = crate::envelope::INTERVAL_S.min;

/// The longest interval between two measurements of one target that the
/// filters are specified for, s ([`crate::envelope::INTERVAL_S`]): beyond it
/// an estimate is restarted, not extrapolated.
pub const MAX_INTERVAL_S: f64 = crate::envelope::INTERVAL_S.max;

/// [`MIN_INTERVAL_S`] in milliseconds (the track table's clock).
pub const MIN_INTERVAL_MS: u32 = (MIN_INTERVAL_S * 1000.0) as u32;
/// [`MAX_INTERVAL_S`] in milliseconds (the track table's clock).
pub const MAX_INTERVAL_MS: u32 = (MAX_INTERVAL_S * 1000.0) as u32;

/// Where a valid interval falls against the range the filters are specified
/// for ([`MIN_INTERVAL_S`] ..= [`MAX_INTERVAL_S`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum IntervalSpan {
    /// Shorter than [`MIN_INTERVAL_S`]: the measurement is skipped.
    TooShort,
    /// Inside the range: filtered.
    InRange,
    /// Longer than [`MAX_INTERVAL_S`]: the estimate restarts.
    TooLong,
}

impl IntervalSpan {
    /// The span of `dt`; refuses an interval that is not a valid number or
    /// is ≤ 0 ([`FilterError::InvalidInterval`]): that is malformed input,
    /// not timing.
    pub fn of<Q: Quantity>(dt: Q) -> Result<Self, FilterError> {
        check_interval(dt)?;
        // From milliseconds: a constant for every format (the fast fixed
        // point's conversion from f64 is a library call).
        Ok(if dt < Q::seconds_from_ms(MIN_INTERVAL_MS) {
            IntervalSpan::TooShort
        } else if dt > Q::seconds_from_ms(MAX_INTERVAL_MS) {
            IntervalSpan::TooLong
        } else {
            IntervalSpan::InRange
        })
    }

    /// The span of an update `dt` after the previous call, the first point
    /// of a two-point start having been taken `since_first` before that
    /// call: as [`Self::of`], and too long also when the time since the
    /// first point, over which eq. (9) takes the velocity, is longer than
    /// [`MAX_INTERVAL_S`] or left the number format (a first point coasted
    /// past the filters' range).
    pub fn of_second_point<Q: Quantity>(since_first: Q, dt: Q) -> Result<Self, FilterError> {
        let span = Self::of(dt)?;
        let elapsed = since_first + dt;
        let within = elapsed.is_valid() && elapsed <= Q::seconds_from_ms(MAX_INTERVAL_MS);
        Ok(match span {
            IntervalSpan::InRange if !within => IntervalSpan::TooLong,
            other => other,
        })
    }
}

/// The prediction terms of one interval: T and T²/2, checked once.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct IntervalTerms<N: Numeric> {
    interval: N::Interval,
    half_squared: N::IntervalSquared,
}

impl<N: Numeric> IntervalTerms<N> {
    /// T and T²/2; refuses an interval that is not a valid number or is
    /// ≤ 0, and one whose square is not representable. (Callers chain it
    /// with `and_then`: `?` copies the terms through a library call, byte by
    /// byte in the fast fixed point, at every update.)
    pub fn new(dt: N::Interval) -> Result<Self, FilterError> {
        check_interval(dt)?;
        let half_squared = (dt * dt).half();
        if !half_squared.is_valid() {
            return Err(FilterError::Saturated);
        }
        Ok(IntervalTerms {
            interval: dt,
            half_squared,
        })
    }

    /// T.
    pub fn interval(&self) -> N::Interval {
        self.interval
    }

    /// T²/2.
    pub fn half_squared(&self) -> N::IntervalSquared {
        self.half_squared
    }
}

/// The gains of one update interval T, formed once per interval: α, the
/// velocity gain β/T (Al-Wagih eq. 8, Tenne & Singh eq. 4) and the
/// acceleration gain γ/(2T²) (Tenne & Singh eq. 5), with T and T²/2 for the
/// prediction. The per-update path multiplies by them and never divides.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StepGains<N: Numeric> {
    terms: IntervalTerms<N>,
    alpha: N::Gain,
    velocity_gain: N::Rate,
    acceleration_gain: N::RateSquared,
}

impl<N: Numeric> StepGains<N> {
    /// The gains of `gains` for interval `dt`. Refuses an interval that is
    /// not a valid number or is ≤ 0 ([`FilterError::InvalidInterval`]), and
    /// one for which β/T, γ/(2T²) or T² is not representable
    /// ([`FilterError::Saturated`]).
    pub fn new(gains: &Gains<N>, dt: N::Interval) -> Result<Self, FilterError> {
        IntervalTerms::new(dt).and_then(|terms| Self::with_terms(gains, &terms))
    }

    /// [`Self::new`] with the interval's terms formed already (one interval,
    /// gains per axis). αβ gains (γ = 0) take no γ division.
    #[inline]
    pub fn with_terms(gains: &Gains<N>, terms: &IntervalTerms<N>) -> Result<Self, FilterError> {
        let dt = terms.interval;
        let velocity_gain = gains.beta() / dt;
        let acceleration_gain = if gains.gamma() == N::Ratio::ZERO {
            N::RateSquared::ZERO
        } else {
            let squared = dt * dt;
            gains.gamma() / (squared + squared)
        };
        let alpha = N::gain(gains.alpha());
        if !(alpha.is_valid() && velocity_gain.is_valid() && acceleration_gain.is_valid()) {
            return Err(FilterError::Saturated);
        }
        Ok(StepGains {
            terms: *terms,
            alpha,
            velocity_gain,
            acceleration_gain,
        })
    }

    /// T and T²/2.
    pub fn terms(&self) -> &IntervalTerms<N> {
        &self.terms
    }
    /// T.
    pub fn interval(&self) -> N::Interval {
        self.terms.interval
    }
    /// α.
    pub fn alpha(&self) -> N::Gain {
        self.alpha
    }
    /// β/T, 1/s.
    pub fn velocity_gain(&self) -> N::Rate {
        self.velocity_gain
    }
    /// γ/(2T²), 1/s² (zero for αβ gains).
    pub fn acceleration_gain(&self) -> N::RateSquared {
        self.acceleration_gain
    }
}

/// What an update did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum UpdateOutcome<N: Numeric> {
    /// First measurement: the position is taken as the estimate (Al-Wagih §3).
    FirstPoint,
    /// Second measurement: velocity from the difference (Al-Wagih eq. 9).
    SecondPoint,
    /// A filtered update with the prediction it corrected and its residual
    /// z − prediction (Al-Wagih eq. 4).
    Filtered(Innovation<N>),
    /// The estimate was dropped before this measurement, which became the
    /// first point of a new one: the interval since the previous update
    /// was longer than [`MAX_INTERVAL_S`] (or a gain schedule required it).
    /// Given by what applies the interval policy (module docs).
    Restarted,
    /// Less than [`MIN_INTERVAL_S`] after the previous update: the
    /// measurement was not used and the estimate is unchanged.
    Skipped,
}

/// What an update did, without the innovation (which the filter keeps:
/// [`KinematicFilter::last_innovation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum UpdateKind {
    /// First measurement: the position is taken as the estimate.
    FirstPoint,
    /// Second measurement: velocity from the difference (Al-Wagih eq. 9).
    SecondPoint,
    /// A filtered update (Al-Wagih eqs. 3–8, Tenne & Singh eqs. 1–5).
    Filtered,
}

/// The prediction an update corrected and the innovation (residual).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Innovation<N: Numeric> {
    /// Predicted position x_p (Al-Wagih eq. 3, Tenne & Singh eq. 1).
    pub predicted: N::Length,
    /// e = z − x_p (Al-Wagih eq. 4).
    pub residual: N::Length,
}

/// Predicted kinematic state after an interval, without changing the filter.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Prediction<N: Numeric> {
    /// Predicted position, m.
    pub position: N::Length,
    /// Predicted velocity, m/s.
    pub velocity: N::Speed,
    /// Predicted acceleration, m/s² (zero for αβ).
    pub acceleration: N::Acceleration,
}

impl<N: Numeric> Prediction<N> {
    pub(crate) const ZERO: Self = Prediction {
        position: N::Length::ZERO,
        velocity: N::Speed::ZERO,
        acceleration: N::Acceleration::ZERO,
    };
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
pub struct KinematicFilter<N: Numeric, const ORDER: usize> {
    phase: Phase,
    position: N::Length,
    velocity: N::Speed,
    acceleration: N::Acceleration,
    /// While `OnePoint`: time since the first measurement (coasts add to it).
    since_first: N::Interval,
    last: Option<Innovation<N>>,
    saturations: u32,
}

/// αβ filter, Al-Wagih & Abdulla eqs. (3)–(10).
pub type AlphaBeta<N> = KinematicFilter<N, 2>;
/// αβγ filter, Tenne & Singh eqs. (1)–(5).
pub type AlphaBetaGamma<N> = KinematicFilter<N, 3>;

impl<N: Numeric, const ORDER: usize> Default for KinematicFilter<N, ORDER> {
    fn default() -> Self {
        Self::new()
    }
}

/// Refuses an interval that is not a valid number or is ≤ 0 (every
/// filter's contract).
#[inline]
pub(crate) fn check_interval<Q: Quantity>(dt: Q) -> Result<(), FilterError> {
    if dt.is_valid_and_positive() {
        Ok(())
    } else {
        Err(FilterError::InvalidInterval)
    }
}

/// One axis's filtered update, computed before anything is written.
#[derive(Clone, Copy)]
struct Filtered<N: Numeric> {
    position: N::Length,
    velocity: N::Speed,
    acceleration: N::Acceleration,
    predicted: N::Length,
    residual: N::Length,
}

impl<N: Numeric> Filtered<N> {
    const ZERO: Self = Filtered {
        position: N::Length::ZERO,
        velocity: N::Speed::ZERO,
        acceleration: N::Acceleration::ZERO,
        predicted: N::Length::ZERO,
        residual: N::Length::ZERO,
    };
}

impl<N: Numeric, const ORDER: usize> KinematicFilter<N, ORDER> {
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
            position: N::Length::ZERO,
            velocity: N::Speed::ZERO,
            acceleration: N::Acceleration::ZERO,
            since_first: N::Interval::ZERO,
            last: None,
            saturations: 0,
        }
    }

    /// A filter already tracking from a known state (e.g. a handed-over
    /// track). The acceleration is ignored for `ORDER = 2`.
    pub fn from_state(
        position: N::Length,
        velocity: N::Speed,
        acceleration: N::Acceleration,
    ) -> Result<Self, FilterError> {
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
                N::Acceleration::ZERO
            },
            ..Self::new()
        })
    }

    /// Which stage of two-point initialisation the filter is in.
    pub fn phase(&self) -> Phase {
        self.phase
    }
    /// Smoothed position x_s.
    pub fn position(&self) -> N::Length {
        self.position
    }
    /// Smoothed velocity v_s (zero before the second measurement).
    pub fn velocity(&self) -> N::Speed {
        self.velocity
    }
    /// Smoothed acceleration a_s (always zero for αβ).
    pub fn acceleration(&self) -> N::Acceleration {
        self.acceleration
    }
    /// Prediction and residual of the last filtered update (kept for adaptive
    /// gain schedules and gates); `None` until the first filtered update.
    pub fn last_innovation(&self) -> Option<Innovation<N>> {
        self.last
    }
    /// How many updates or coasts were discarded because they saturated.
    pub fn saturations(&self) -> u32 {
        self.saturations
    }

    fn count_saturation(&mut self) {
        self.saturations = self.saturations.saturating_add(1);
    }

    /// The span of an update `dt` from now under the interval policy
    /// ([`IntervalSpan::of`]; while one point is known,
    /// [`IntervalSpan::of_second_point`]). Out of line: the policy's
    /// holders call it off their tracking path.
    #[inline(never)]
    pub fn interval_span(&self, dt: N::Interval) -> Result<IntervalSpan, FilterError> {
        if self.phase == Phase::OnePoint {
            IntervalSpan::of_second_point(self.since_first, dt)
        } else {
            IntervalSpan::of(dt)
        }
    }

    /// Back to [`Phase::Empty`], keeping the saturation count (an interval
    /// policy's restart).
    pub(crate) fn restart(&mut self) {
        *self = KinematicFilter {
            saturations: self.saturations,
            ..Self::new()
        };
    }

    /// The state predicted `dt` ahead, without changing the filter
    /// (Tenne & Singh eqs. 1–2; for αβ, Al-Wagih eq. 3).
    pub fn predict(&self, dt: N::Interval) -> Result<Prediction<N>, FilterError> {
        IntervalTerms::new(dt).and_then(|terms| self.predict_terms(&terms))
    }

    /// [`Self::predict`] with the interval's terms formed already.
    #[inline]
    pub fn predict_terms(&self, terms: &IntervalTerms<N>) -> Result<Prediction<N>, FilterError> {
        let mut guard = N::Guard::default();
        let p = self.extrapolate(terms, &mut guard);
        p.position.check_output(&mut guard);
        p.velocity.check_output(&mut guard);
        if N::passed(&guard) {
            Ok(p)
        } else {
            Err(FilterError::Saturated)
        }
    }

    /// Tenne & Singh eqs. (1)–(2): x + T·v + (T²/2)·a, v + T·a.
    #[inline(always)]
    fn extrapolate(&self, terms: &IntervalTerms<N>, guard: &mut N::Guard) -> Prediction<N> {
        let t = terms.interval;
        let position = self.position.add_product(self.velocity, t, guard);
        if Self::HAS_ACCELERATION {
            Prediction {
                position: position.add_product(self.acceleration, terms.half_squared, guard),
                velocity: self.velocity.add_product(self.acceleration, t, guard),
                acceleration: self.acceleration,
            }
        } else {
            Prediction {
                position,
                velocity: self.velocity,
                acceleration: N::Acceleration::ZERO,
            }
        }
    }

    /// One filtered update (Tenne & Singh eqs. 1–5, Al-Wagih eqs. 3–8):
    /// predict, e = z − x_p, x_s = x_p + αe, v_s = v_p + (β/T)e,
    /// a_s = a + γ/(2T²)·e. Every result goes through `guard`.
    #[inline(always)]
    fn filtered(&self, z: N::Length, step: &StepGains<N>, guard: &mut N::Guard) -> Filtered<N> {
        z.check_input(guard);
        let p = self.extrapolate(&step.terms, guard);
        let residual = z.sub_guarded(p.position, guard);
        let position = p.position.add_product(step.alpha, residual, guard);
        let velocity = p.velocity.add_product(step.velocity_gain, residual, guard);
        p.position.check_output(guard);
        position.check_output(guard);
        velocity.check_output(guard);
        residual.check_output(guard);
        let acceleration = if Self::HAS_ACCELERATION {
            let a = p
                .acceleration
                .add_product(step.acceleration_gain, residual, guard);
            a.check_output(guard);
            a
        } else {
            N::Acceleration::ZERO
        };
        Filtered {
            position,
            velocity,
            acceleration,
            predicted: p.position,
            residual,
        }
    }

    #[inline(always)]
    fn commit(&mut self, f: &Filtered<N>) {
        self.position = f.position;
        self.velocity = f.velocity;
        if Self::HAS_ACCELERATION {
            self.acceleration = f.acceleration;
        }
        self.last = Some(Innovation {
            predicted: f.predicted,
            residual: f.residual,
        });
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
    ///
    /// Forms the [`StepGains`] and calls [`Self::update_step`] (for any
    /// interval > 0: the interval policy is the caller's, module docs).
    pub fn update(
        &mut self,
        z: N::Length,
        dt: N::Interval,
        gains: &Gains<N>,
    ) -> Result<UpdateOutcome<N>, FilterError> {
        let step = step_gains(core::array::from_mut(self), [z], dt, gains)?;
        let kind = update_axes(core::array::from_mut(self), [z], &step)?;
        Ok(outcome(kind, self.last))
    }

    /// [`Self::update`] with the interval's gains formed already: the
    /// per-update path. A refused update leaves the filter bit-identical
    /// (but for the saturation count of a [`FilterError::Saturated`]).
    pub fn update_step(
        &mut self,
        z: N::Length,
        step: &StepGains<N>,
    ) -> Result<UpdateKind, FilterError> {
        update_axes(core::array::from_mut(self), [z], step)
    }

    /// No measurement this scan: advance the state by `dt` (predict only).
    /// Before the second measurement there is no velocity to extrapolate with,
    /// so the position holds and the interval is remembered for eq. (9).
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        coast_axes(core::array::from_mut(self), dt)
    }
}

/// The step gains of `gains` at `dt`, checking the measurement first (so
/// that a bad measurement is reported as such whatever the interval); a
/// saturated β/T or γ/(2T²) counts as a saturated update.
fn step_gains<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    z: [N::Length; D],
    dt: N::Interval,
    gains: &Gains<N>,
) -> Result<StepGains<N>, FilterError> {
    if z.iter().any(|v| !v.is_valid()) {
        return Err(FilterError::InvalidMeasurement);
    }
    StepGains::new(gains, dt).inspect_err(|e| count_if_saturated(axes, e))
}

/// Counts `e` on the first axis if it is a saturation.
fn count_if_saturated<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    e: &FilterError,
) {
    if *e == FilterError::Saturated {
        if let Some(first) = axes.first_mut() {
            first.count_saturation();
        }
    }
}

/// The [`UpdateOutcome`] of an update of `kind` that left the innovation
/// `last`.
pub(crate) fn outcome<N: Numeric>(
    kind: UpdateKind,
    last: Option<Innovation<N>>,
) -> UpdateOutcome<N> {
    match (kind, last) {
        (UpdateKind::FirstPoint, _) => UpdateOutcome::FirstPoint,
        (UpdateKind::SecondPoint, _) => UpdateOutcome::SecondPoint,
        (UpdateKind::Filtered, Some(i)) => UpdateOutcome::Filtered(i),
        // A filtered update always leaves an innovation.
        (UpdateKind::Filtered, None) => UpdateOutcome::SecondPoint,
    }
}

/// The update of `D` axes that share one phase, all or nothing: every
/// axis is computed first, the results are checked once (one [`Numeric::Guard`]),
/// and only then written. A refusal leaves every axis bit-identical, except
/// that a saturation is counted once, on the first axis.
#[inline(always)]
fn update_axes<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    z: [N::Length; D],
    step: &StepGains<N>,
) -> Result<UpdateKind, FilterError> {
    update_axes_each(axes, z, [step; D])
}

#[inline(always)]
fn update_axes_each<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    z: [N::Length; D],
    steps: [&StepGains<N>; D],
) -> Result<UpdateKind, FilterError> {
    let phase = axes.first().map_or(Phase::Empty, |a| a.phase);
    if phase != Phase::Tracking {
        let dt = steps.first().map(|s| s.interval());
        return initialise(axes, z, dt.unwrap_or(N::Interval::ZERO));
    }
    // Straight-line code for one to three axes (the slice patterns are
    // resolved at compile time), so that every result stays in registers
    // until it is written; the loop covers larger D.
    let mut guard = N::Guard::default();
    macro_rules! unrolled {
        ($(($axis:ident, $z:ident, $step:ident, $f:ident)),+) => {{
            $(let $f = $axis.filtered(*$z, $step, &mut guard);)+
            if !N::passed(&guard) {
                return Err(refuse(axes, &z));
            }
            $($axis.commit(&$f);)+
        }};
    }
    match (axes.as_mut_slice(), z.as_slice(), steps.as_slice()) {
        ([a0], [z0], [s0]) => unrolled!((a0, z0, s0, f0)),
        ([a0, a1], [z0, z1], [s0, s1]) => unrolled!((a0, z0, s0, f0), (a1, z1, s1, f1)),
        ([a0, a1, a2], [z0, z1, z2], [s0, s1, s2]) => {
            unrolled!((a0, z0, s0, f0), (a1, z1, s1, f1), (a2, z2, s2, f2))
        }
        (all, _, _) => {
            let mut next = [Filtered::<N>::ZERO; D];
            for (((slot, axis), z), step) in next.iter_mut().zip(all.iter()).zip(z).zip(steps) {
                *slot = axis.filtered(z, step, &mut guard);
            }
            if !N::passed(&guard) {
                return Err(refuse(axes, &z));
            }
            for (axis, f) in axes.iter_mut().zip(next.iter()) {
                axis.commit(f);
            }
        }
    }
    Ok(UpdateKind::Filtered)
}

/// Why a checked computation failed: an invalid measurement (not counted),
/// or a saturation (counted on the first axis).
#[cold]
fn refuse<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    z: &[N::Length; D],
) -> FilterError {
    if z.iter().any(|v| !v.is_valid()) {
        return FilterError::InvalidMeasurement;
    }
    if let Some(first) = axes.first_mut() {
        first.count_saturation();
    }
    FilterError::Saturated
}

/// Whether a measurement holds a value that is not a valid number (out of
/// line: the paths that call it are off the tracking path).
#[inline(never)]
pub(crate) fn invalid_measurement<Q: Quantity>(z: &[Q]) -> bool {
    z.iter().any(|v| !v.is_valid())
}

/// Why an update whose checked arithmetic failed is refused: an invalid
/// measurement, else a saturation.
#[cold]
pub(crate) fn refusal<Q: Quantity>(z: &[Q]) -> FilterError {
    if invalid_measurement(z) {
        FilterError::InvalidMeasurement
    } else {
        FilterError::Saturated
    }
}

/// Two-point initialisation (Al-Wagih eqs. 9–10) of `D` axes sharing one
/// phase (`Empty` or `OnePoint`).
#[cold]
fn initialise<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    z: [N::Length; D],
    dt: N::Interval,
) -> Result<UpdateKind, FilterError> {
    if z.iter().any(|v| !v.is_valid()) {
        return Err(FilterError::InvalidMeasurement);
    }
    check_interval(dt)?;
    let phase = axes.first().map_or(Phase::Empty, |a| a.phase);
    if phase == Phase::Empty {
        for (axis, z) in axes.iter_mut().zip(z) {
            axis.position = z;
            axis.velocity = N::Speed::ZERO;
            axis.acceleration = N::Acceleration::ZERO;
            axis.since_first = N::Interval::ZERO;
            axis.phase = Phase::OnePoint;
        }
        return Ok(UpdateKind::FirstPoint);
    }
    let mut velocity = [N::Speed::ZERO; D];
    for ((v, axis), z) in velocity.iter_mut().zip(axes.iter()).zip(z) {
        let elapsed = axis.since_first + dt;
        *v = (z - axis.position) / elapsed;
    }
    if velocity.iter().any(|v| !v.is_valid()) {
        return Err(refuse(axes, &z));
    }
    for ((axis, z), v) in axes.iter_mut().zip(z).zip(velocity) {
        axis.position = z;
        axis.velocity = v;
        axis.phase = Phase::Tracking;
    }
    Ok(UpdateKind::SecondPoint)
}

/// Coasts `D` axes sharing one phase, all or nothing.
fn coast_axes<N: Numeric, const ORDER: usize, const D: usize>(
    axes: &mut [KinematicFilter<N, ORDER>; D],
    dt: N::Interval,
) -> Result<(), FilterError> {
    let terms = IntervalTerms::<N>::new(dt).inspect_err(|e| count_if_saturated(axes, e))?;
    match axes.first().map_or(Phase::Empty, |a| a.phase) {
        Phase::Empty => Ok(()),
        Phase::OnePoint => {
            let mut since = [N::Interval::ZERO; D];
            for (s, axis) in since.iter_mut().zip(axes.iter()) {
                *s = axis.since_first + dt;
            }
            if since.iter().any(|s| !s.is_valid()) {
                return Err(refuse(axes, &[N::Length::ZERO; D]));
            }
            for (axis, s) in axes.iter_mut().zip(since) {
                axis.since_first = s;
            }
            Ok(())
        }
        Phase::Tracking => {
            let mut guard = N::Guard::default();
            let mut next = [Prediction::<N>::ZERO; D];
            for (p, axis) in next.iter_mut().zip(axes.iter()) {
                *p = axis.extrapolate(&terms, &mut guard);
                p.position.check_output(&mut guard);
                p.velocity.check_output(&mut guard);
            }
            if !N::passed(&guard) {
                return Err(refuse(axes, &[N::Length::ZERO; D]));
            }
            for (axis, p) in axes.iter_mut().zip(next) {
                axis.position = p.position;
                axis.velocity = p.velocity;
            }
            Ok(())
        }
    }
}

/// `D` independent one-axis filters (x, y[, z]) updated together: a 2-D or
/// 3-D αβ / αβγ tracker. An update either applies to every axis or, if any
/// axis refuses it, to none; a refused update is counted once, on the first
/// axis.
///
/// A 2-D αβ filter in f32 on a target moving at (10, −5) m/s, measured
/// every second without noise:
///
/// ```
/// use abtrack::filter::{Phase, UpdateOutcome};
/// use abtrack::{Cartesian, FilterError, Gains};
///
/// let gains = Gains::<f32>::alpha_beta(0.5, 0.2)?;
/// let mut xy = Cartesian::<f32, 2, 2>::new();
/// for k in 0..20 {
///     let t = k as f32;
///     let out = xy.update([100.0 + 10.0 * t, 50.0 - 5.0 * t], 1.0, &gains)?;
///     if k >= 2 {
///         // Residual z − prediction (Al-Wagih eq. 4): zero on a straight line.
///         assert!(matches!(out[0], UpdateOutcome::Filtered(i) if i.residual.abs() < 1e-3));
///     }
/// }
/// assert_eq!(xy.phase(), Phase::Tracking);
/// let [x, y] = xy.position();
/// assert!((x - 290.0).abs() < 1e-3 && (y - (-45.0)).abs() < 1e-3);
/// let [vx, vy] = xy.velocity();
/// assert!((vx - 10.0).abs() < 1e-3 && (vy + 5.0).abs() < 1e-3);
/// // A measurement that is not a number is refused; the state is unchanged.
/// assert_eq!(xy.update([f32::NAN, 0.0], 1.0, &gains), Err(FilterError::InvalidMeasurement));
/// assert_eq!(xy.position(), [x, y]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cartesian<N: Numeric, const ORDER: usize, const D: usize> {
    axes: [KinematicFilter<N, ORDER>; D],
}

impl<N: Numeric, const ORDER: usize, const D: usize> Default for Cartesian<N, ORDER, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Numeric, const ORDER: usize, const D: usize> Cartesian<N, ORDER, D> {
    /// A filter that has seen no measurement ([`Phase::Empty`]).
    pub const fn new() -> Self {
        Cartesian {
            axes: [KinematicFilter::new(); D],
        }
    }

    /// The per-axis filters.
    pub fn axes(&self) -> &[KinematicFilter<N, ORDER>; D] {
        &self.axes
    }

    /// Axis `i`'s filter (0 = x, 1 = y, 2 = z), `None` past `D`.
    pub fn axis(&self, i: usize) -> Option<&KinematicFilter<N, ORDER>> {
        self.axes.get(i)
    }

    /// The axes' initialisation stage (all the same).
    pub fn phase(&self) -> Phase {
        // All axes move through the phases together.
        self.axes.first().map_or(Phase::Empty, |a| a.phase())
    }

    /// [`KinematicFilter::interval_span`] (the axes share their phase and
    /// times).
    pub fn interval_span(&self, dt: N::Interval) -> Result<IntervalSpan, FilterError> {
        self.axes
            .first()
            .map_or_else(|| IntervalSpan::of(dt), |a| a.interval_span(dt))
    }

    /// Smoothed position per axis, m.
    pub fn position(&self) -> [N::Length; D] {
        self.axes.map(|a| a.position())
    }

    /// Smoothed velocity per axis, m/s.
    pub fn velocity(&self) -> [N::Speed; D] {
        self.axes.map(|a| a.velocity())
    }

    /// Sum of the axes' saturation counters.
    pub fn saturations(&self) -> u32 {
        self.axes
            .iter()
            .fold(0u32, |n, a| n.saturating_add(a.saturations()))
    }

    /// Every axis back to [`Phase::Empty`], keeping the saturation counts
    /// (an interval policy's restart).
    pub(crate) fn restart(&mut self) {
        for axis in self.axes.iter_mut() {
            axis.restart();
        }
    }

    /// Updates every axis with the same gains (forms the [`StepGains`] and
    /// calls [`Self::update_step`]).
    pub fn update(
        &mut self,
        z: [N::Length; D],
        dt: N::Interval,
        gains: &Gains<N>,
    ) -> Result<[UpdateOutcome<N>; D], FilterError> {
        let step = step_gains(&mut self.axes, z, dt, gains)?;
        let kind = update_axes(&mut self.axes, z, &step)?;
        Ok(self.outcomes(kind))
    }

    /// Updates every axis with the interval's gains formed already: the
    /// per-update path (no division). All or nothing; a refused update
    /// leaves the filter bit-identical, but for the saturation count.
    pub fn update_step(
        &mut self,
        z: [N::Length; D],
        step: &StepGains<N>,
    ) -> Result<UpdateKind, FilterError> {
        update_axes(&mut self.axes, z, step)
    }

    /// Updates each axis with its own gains (schedules that adapt per axis).
    pub fn update_per_axis(
        &mut self,
        z: [N::Length; D],
        dt: N::Interval,
        gains: &[Gains<N>; D],
    ) -> Result<[UpdateOutcome<N>; D], FilterError> {
        if z.iter().any(|v| !v.is_valid()) {
            return Err(FilterError::InvalidMeasurement);
        }
        IntervalTerms::<N>::new(dt)
            .inspect_err(|e| count_if_saturated(&mut self.axes, e))
            .and_then(|terms| self.update_per_axis_terms(z, &terms, gains))
    }

    /// [`Self::update_per_axis`] with the interval's terms formed already
    /// (a measurement that is not valid is refused all the same).
    #[inline(always)]
    pub fn update_per_axis_terms(
        &mut self,
        z: [N::Length; D],
        terms: &IntervalTerms<N>,
        gains: &[Gains<N>; D],
    ) -> Result<[UpdateOutcome<N>; D], FilterError> {
        let mut refused = None;
        let steps = gains.each_ref().map(|g| {
            StepGains::with_terms(g, terms).unwrap_or_else(|e| {
                refused = Some(e);
                StepGains {
                    terms: *terms,
                    alpha: N::Gain::ZERO,
                    velocity_gain: N::Rate::ZERO,
                    acceleration_gain: N::RateSquared::ZERO,
                }
            })
        });
        if let Some(e) = refused {
            if e == FilterError::Saturated {
                self.count_saturation();
            }
            return Err(e);
        }
        let kind = update_axes_each(&mut self.axes, z, steps.each_ref())?;
        Ok(self.outcomes(kind))
    }

    /// Counts one discarded update (on the first axis, as every refusal
    /// does).
    pub(crate) fn count_saturation(&mut self) {
        if let Some(first) = self.axes.first_mut() {
            first.count_saturation();
        }
    }

    fn outcomes(&self, kind: UpdateKind) -> [UpdateOutcome<N>; D] {
        self.axes.map(|a| outcome(kind, a.last))
    }

    /// The state of every axis predicted `dt` ahead, without changing the
    /// filter ([`KinematicFilter::predict`] per axis).
    pub fn predict(&self, dt: N::Interval) -> Result<[Prediction<N>; D], FilterError> {
        IntervalTerms::new(dt).and_then(|terms| self.predict_terms(&terms))
    }

    /// [`Self::predict`] with the interval's terms formed already.
    #[inline(always)]
    pub fn predict_terms(
        &self,
        terms: &IntervalTerms<N>,
    ) -> Result<[Prediction<N>; D], FilterError> {
        match self.predicted(terms) {
            (out, true) => Ok(out),
            (_, false) => Err(FilterError::Saturated),
        }
    }

    /// The predictions of [`Self::predict_terms`] and whether they are all
    /// valid (one guard over the axes).
    #[inline(always)]
    pub(crate) fn predicted(&self, terms: &IntervalTerms<N>) -> ([Prediction<N>; D], bool) {
        let mut guard = N::Guard::default();
        let out = self.axes.each_ref().map(|axis| {
            let p = axis.extrapolate(terms, &mut guard);
            p.position.check_output(&mut guard);
            p.velocity.check_output(&mut guard);
            p
        });
        (out, N::passed(&guard))
    }

    /// Coasts every axis (no measurement this scan), all or nothing.
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        coast_axes(&mut self.axes, dt)
    }
}
