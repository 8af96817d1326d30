//! Gain schedules: how α, β (and γ) are chosen while tracking.
//!
//! The papers' main contribution is the choice of gains. Each method is a
//! *schedule*: a small `Copy` state machine that, given the context of the
//! next measurement ([`GainContext`]: its number since initialisation, the
//! interval, and per axis the measurement, the filter's prediction and the
//! innovation), produces the gains for that update ([`GainSchedule`]). A
//! schedule never owns the filter it schedules; it keeps only its own state
//! (counters, windows of past innovations), sized by const generics.
//!
//! | family (file) | schedule | paper |
//! |---|---|---|
//! | [`al_wagih`] | [`FixedGains`] (M1: [`FixedGains::m1`]) | Al-Wagih & Abdulla eq. (23) |
//! | | [`LeastSquaresGains`] (M2) | Al-Wagih & Abdulla eq. (24) |
//! | | [`LinearCombinationGains`] (M3) | Al-Wagih & Abdulla eq. (25), Algorithm 1 |
//! | | [`MovingWindowGains`] (M4) | Al-Wagih & Abdulla Algorithm 2 |
//! | [`li`] | [`LiImprovedGains`] | Li, Zhao, Liang & Zhang eqs. (4), (7)–(15) |
//! | [`liu`] | 2.1.1 = [`LeastSquaresGains`], 2.1.3 = [`FixedGains::liu`] | Liu, Wang & Yang eq. (5), §2.1.3 |
//! | | [`ScanCountAdjustedGains`] | Liu, Wang & Yang §2.1.2 |
//! | | [`ResidualAccumulationGains`] | Liu, Wang & Yang eqs. (6)–(11) |
//! | | [`AdaptiveSwitchGains`] | Liu, Wang & Yang eqs. (12)–(15) |
//! | [`tcas`] | [`FirmnessGains`] | TCAS range tracker (DO-185B firmness table) |
//! | [`auto`] | [`AutoGains`] | beyond the papers: a per-axis Kalman filter as αβ gains, q from the innovations (`docs/auto.md`) |
//!
//! Al-Wagih & Abdulla's M5 (a bank of K fixed-gain trackers) is not a
//! schedule: it owns K filter states and outputs one of their predictions, so
//! it lives with the estimators in [`crate::bank`].
//!
//! # When a schedule sees an innovation
//!
//! [`GainSchedule::gains`] receives the context of the measurement about to be
//! incorporated, *including its innovation* e = z − x_p: the innovation needs
//! only the prediction, which exists before the update. Liu, Wang & Yang
//! compute the innovation (their eq. 3) before the gain is applied (eq. 4) and
//! switch on the current |V_x(k)|, |V_y(k)| (eqs. 12–15), so their schedules
//! use it. Al-Wagih & Abdulla (M3, M4: "employed for the next stage of
//! tracking") and Li et al. (§4: gains first, then d and r_k) adapt from past
//! innovations only; their schedules ignore the current one in `gains` and
//! learn from it in [`GainSchedule::accepted`].
//!
//! # Axes
//!
//! `gains` returns one [`Gains`] per axis. Schedules whose paper gives one
//! gain for the whole track (M1, M2, Li, TCAS) return the same gains on every
//! axis; Li's ratio r_k uses the Euclidean innovation distance over all axes
//! (eq. 10). Schedules whose paper works per coordinate (Al-Wagih's M3/M4 are
//! evaluated per coordinate in their Tables 1–2; Liu's residual accumulation
//! has α_x and α_y, eqs. 8–9) keep per-axis state. Liu's adaptive switch is
//! joint: either axis over its threshold switches both (eqs. 12–15).
//!
//! # Using a schedule
//!
//! [`ScheduledFilter`] holds a [`Cartesian`] filter, a schedule and the
//! measurement count, and runs the protocol: two-point initialisation (gains
//! unused), then predict → context → `gains` → update → `accepted`; coasts
//! call [`GainSchedule::missed`]. A tracker keeps one per track.
//!
//! Spec strings such as `m1:alpha=0.05` or `bank:k=8` are parsed without
//! allocation by [`spec::ScheduleSpec`]; [`AnySchedule`] holds any schedule a
//! spec names, so a replay tool or firmware can pick one at run time:
//!
//! ```
//! use abtrack::gain::{AnySchedule, ScheduleSpec, ScheduledFilter};
//!
//! let spec = ScheduleSpec::parse("liu-adaptive:limit=19")?;
//! let schedule = AnySchedule::<f32, 2, 8>::from_spec(&spec)?;
//! let mut track: ScheduledFilter<f32, _, 2, 2> = ScheduledFilter::new(schedule);
//! for k in 0..10u8 {
//!     let update = track.update([100.0 + 20.0 * f32::from(k), 50.0], 1.0)?;
//!     // Two-point initialisation first: gains once filtering.
//!     assert_eq!(update.gains.is_some(), k >= 2);
//! }
//! let [x, y] = track.filter().position();
//! assert!((x - 280.0).abs() < 1e-3 && (y - 50.0).abs() < 1e-3);
//! assert!(ScheduleSpec::parse("liu-adaptive:limit=x").is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use core::fmt;

use crate::filter::{
    Cartesian, FilterError, GainError, Gains, IntervalTerms, Phase, Prediction, UpdateOutcome,
};
use crate::gains::li_beta;
use crate::num::{Numeric, Quantity, Real};

pub mod al_wagih;
pub mod auto;
pub mod li;
pub mod liu;
pub mod spec;
pub mod tcas;
mod window;

pub use al_wagih::{FixedGains, LeastSquaresGains, LinearCombinationGains, MovingWindowGains};
pub use auto::{AutoConfig, AutoGains};
pub use li::LiImprovedGains;
pub use liu::{AdaptiveSwitchGains, ResidualAccumulationGains, ScanCountAdjustedGains, SwitchMode};
pub use spec::{ScheduleSpec, SpecError, SpecErrorKind};
pub use tcas::FirmnessGains;

/// What one axis of the filter knows about the measurement about to be
/// incorporated.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisObservation<N: Numeric> {
    /// z, the measurement.
    pub measurement: N::Length,
    /// x_p, the predicted position for this measurement (Al-Wagih eq. 3).
    pub predicted: N::Length,
    /// v_p, the predicted velocity (the smoothed velocity carried forward).
    pub predicted_velocity: N::Speed,
    /// e = z − x_p (Al-Wagih eq. 4; Liu eq. 3).
    pub innovation: N::Length,
}

/// The context of one filtered update, given to [`GainSchedule::gains`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GainContext<N: Numeric, const D: usize> {
    /// The number of this measurement since the track was (re)initialised,
    /// counting from 1: the first filtered update after two-point
    /// initialisation has n = 3 (Al-Wagih eq. 24, "n > 2").
    pub n: u32,
    /// T, the interval since the previous update or coast.
    pub dt: N::Interval,
    /// What each axis knows about the measurement.
    pub axes: [AxisObservation<N>; D],
}

impl<N: Numeric, const D: usize> GainContext<N, D> {
    /// The context of measurement `z` against the filter's `predictions`
    /// (from [`crate::filter::KinematicFilter::predict`]).
    #[inline(always)]
    pub fn new(
        n: u32,
        dt: N::Interval,
        z: [N::Length; D],
        predictions: &[Prediction<N>; D],
    ) -> Result<Self, ScheduleError> {
        let ctx = Self::of_predictions(n, dt, z, predictions);
        ctx.check()?;
        Ok(ctx)
    }

    /// [`Self::new`] unchecked (the caller checks what it does not know
    /// valid already).
    #[inline(always)]
    fn of_predictions(
        n: u32,
        dt: N::Interval,
        z: [N::Length; D],
        predictions: &[Prediction<N>; D],
    ) -> Self {
        let axes = core::array::from_fn(|i| {
            let z = z.get(i).copied().unwrap_or(N::Length::ZERO);
            let p = predictions.get(i).copied().unwrap_or(Prediction::ZERO);
            AxisObservation {
                measurement: z,
                predicted: p.position,
                predicted_velocity: p.velocity,
                innovation: z - p.position,
            }
        });
        GainContext { n, dt, axes }
    }

    /// e per axis.
    pub fn innovations(&self) -> [N::Length; D] {
        self.axes.map(|a| a.innovation)
    }

    /// x_p per axis.
    pub fn predicted_positions(&self) -> [N::Length; D] {
        self.axes.map(|a| a.predicted)
    }

    /// Refuses a context with an invalid number or an interval ≤ 0, which a
    /// schedule could otherwise learn from.
    #[inline(always)]
    pub fn check(&self) -> Result<(), ScheduleError> {
        crate::filter::check_interval(self.dt).map_err(|_| ScheduleError::InvalidContext)?;
        for a in &self.axes {
            if !(a.measurement.is_valid()
                && a.predicted.is_valid()
                && a.predicted_velocity.is_valid()
                && a.innovation.is_valid())
            {
                return Err(ScheduleError::InvalidContext);
            }
        }
        Ok(())
    }
}

/// Why a schedule produced no gains.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScheduleError {
    /// The context holds an invalid number or an interval ≤ 0.
    InvalidContext,
    /// The computed gains fell outside the stability region (a rounding
    /// failure the schedule could not absorb; the tests show none occur).
    Gain(GainError),
    /// The schedule needs the track restarted before it can give gains
    /// ([`GainSchedule::restart_required`]); [`ScheduledFilter`] does that.
    RestartRequired,
}

impl From<GainError> for ScheduleError {
    fn from(e: GainError) -> Self {
        ScheduleError::Gain(e)
    }
}

impl fmt::Display for ScheduleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScheduleError::InvalidContext => f.write_str("gain context holds an invalid number"),
            ScheduleError::Gain(e) => write!(f, "scheduled gains rejected: {e}"),
            ScheduleError::RestartRequired => f.write_str("schedule requires a track restart"),
        }
    }
}

impl core::error::Error for ScheduleError {}

pub use crate::gains::ConfigError;
pub(crate) use crate::gains::{check_capacity, check_range, config_quantity};

/// A gain schedule: a small state machine that gives the gains of each
/// filtered update.
///
/// Protocol (what [`ScheduledFilter`] does): for the first two measurements
/// of a track the filter initialises itself (Al-Wagih eqs. 9–10) and ignores
/// gains, and the schedule is told with [`initialised`](Self::initialised);
/// for every later measurement the caller builds the [`GainContext`], asks
/// [`gains`](Self::gains), updates the filter with them and, if the filter
/// accepted the update, reports it with [`accepted`](Self::accepted); a
/// schedule whose gains depend on the count alone gives them by
/// [`count_gains`](Self::count_gains) instead, with no context and no
/// report. A scan without a measurement is reported with
/// [`missed`](Self::missed).
///
/// `gains` does not change the schedule, so a refused update leaves it as it
/// was. Schedules are `Copy`: a track table stores them by value.
pub trait GainSchedule<N: Numeric, const D: usize>: Copy {
    /// The gains, one per axis, for the update described by `ctx`.
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError>;

    /// The filter applied the update described by `ctx` with `used` (the
    /// gains `gains` returned).
    fn accepted(&mut self, ctx: &GainContext<N, D>, used: &[Gains<N>; D]);

    /// Measurement `n` (1 or 2), `dt` after the previous call, initialised
    /// the filter; no gains were used.
    fn initialised(&mut self, _n: u32, _dt: N::Interval) {}

    /// A scan `dt` long passed without a measurement for this track.
    fn missed(&mut self, _dt: N::Interval) {}

    /// The gains of measurement `n`, when they depend on the count alone
    /// and are the same on every axis (M1's, M2's): what
    /// [`gains`](Self::gains) gives for every context of measurement `n`.
    /// [`ScheduledFilter`] then builds no [`GainContext`] and does not call
    /// [`accepted`](Self::accepted), so a schedule that gives them keeps no
    /// state `accepted` would change; it asks for them before the filter
    /// predicts, so their error comes before a saturation. `None` (the
    /// default): the gains need the context.
    fn count_gains(&self, _n: u32) -> Option<Result<Gains<N>, ScheduleError>> {
        None
    }

    /// Whether the gains already account for the real interval (a
    /// covariance propagated with it), so that [`ScheduledFilter`] applies
    /// them without [`robust_gains`]' bounds.
    fn gains_follow_interval(&self) -> bool {
        false
    }

    /// The predicted position variance over the measurement variance per
    /// axis, for an update `dt` from now, when the schedule carries a
    /// covariance (a gate scales with it).
    fn predicted_variance_ratios(&self, _dt: N::Interval) -> Option<[N::Ratio; D]> {
        None
    }

    /// Whether the track must be restarted (filter emptied, schedule
    /// [`reset`](Self::reset)) before the next measurement, given the
    /// filter's phase. Only track-firmness schedules use it.
    fn restart_required(&self, _phase: Phase) -> bool {
        false
    }

    /// Back to the state of a freshly configured schedule.
    fn reset(&mut self);
}

/// Why a [`ScheduledFilter`] refused a measurement. Nothing changed (except
/// the filter's saturation counter for a saturated update).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScheduledError {
    /// The filter refused the measurement or interval, or saturated.
    Filter(FilterError),
    /// The schedule gave no gains.
    Schedule(ScheduleError),
}

pub use crate::filter::{IntervalSpan, MAX_INTERVAL_S, MIN_INTERVAL_S};

impl From<FilterError> for ScheduledError {
    fn from(e: FilterError) -> Self {
        ScheduledError::Filter(e)
    }
}

impl From<ScheduleError> for ScheduledError {
    fn from(e: ScheduleError) -> Self {
        ScheduledError::Schedule(e)
    }
}

impl fmt::Display for ScheduledError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScheduledError::Filter(e) => fmt::Display::fmt(e, f),
            ScheduledError::Schedule(e) => fmt::Display::fmt(e, f),
        }
    }
}

impl core::error::Error for ScheduledError {}

/// What a [`ScheduledFilter::update`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScheduledUpdate<N: Numeric, const D: usize> {
    /// The filter's outcome per axis.
    pub outcome: [UpdateOutcome<N>; D],
    /// The gains applied; `None` during two-point initialisation, and for
    /// a skipped measurement.
    pub gains: Option<[Gains<N>; D]>,
    /// The track was restarted before this measurement, which became its
    /// first point (the outcome is [`UpdateOutcome::Restarted`]): the
    /// interval was longer than [`MAX_INTERVAL_S`], or the schedule
    /// required it ([`GainSchedule::restart_required`]).
    pub restarted: bool,
}

/// A [`Cartesian`] filter driven by a gain schedule: what a track holds.
///
/// With an αβγ filter (`ORDER = 3`), schedules that give αβ gains (γ = 0)
/// leave the acceleration at its initial zero, i.e. the filter behaves as
/// αβ; with an αβ filter the γ of αβγ gains (TCAS) is ignored.
///
/// One axis under M2, the least-squares gains (Al-Wagih & Abdulla eq. 24):
///
/// ```
/// use abtrack::filter::UpdateOutcome;
/// use abtrack::gain::{LeastSquaresGains, ScheduledFilter};
///
/// let mut track = ScheduledFilter::<f64, _, 2, 1>::new(LeastSquaresGains::default());
/// track.update([0.0], 1.0)?;
/// track.update([10.0], 1.0)?; // two-point initialisation: v = 10 m/s
/// // n = 3: α̂ = 2(2n − 1)/(n(n + 1)) = 5/6, β̂ = 6/(n(n + 1)) = 1/2.
/// let g = track.update([21.0], 1.0)?.gains.ok_or("no gains")?[0];
/// assert!((g.alpha() - 5.0 / 6.0).abs() < 1e-12 && (g.beta() - 0.5).abs() < 1e-12);
/// // Prediction 20 m, innovation 1 m: x = 20 + α·1, v = 10 + β·1/T.
/// assert!((track.filter().position()[0] - (20.0 + 5.0 / 6.0)).abs() < 1e-9);
/// assert!((track.filter().velocity()[0] - 10.5).abs() < 1e-9);
/// // A report 1 ms after the previous one is skipped; nothing changes.
/// let skipped = track.update([21.0], 0.001)?;
/// assert_eq!(skipped.outcome, [UpdateOutcome::Skipped]);
/// assert_eq!(track.measurements(), 3);
/// // One 30 s later (beyond the 20 s the filters are specified for)
/// // restarts the track: it is the first point of a new estimate.
/// let restarted = track.update([400.0], 30.0)?;
/// assert!(restarted.restarted && restarted.outcome == [UpdateOutcome::Restarted]);
/// assert_eq!(track.measurements(), 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScheduledFilter<N: Numeric, G, const ORDER: usize, const D: usize> {
    filter: Cartesian<N, ORDER, D>,
    schedule: G,
    measurements: u32,
    /// The intervals [`robust_gains`] reads.
    intervals: RecentIntervals<N::Interval>,
}

impl<N, G, const ORDER: usize, const D: usize> ScheduledFilter<N, G, ORDER, D>
where
    N: Numeric,
    G: GainSchedule<N, D>,
{
    /// An empty track driven by `schedule`.
    pub const fn new(schedule: G) -> Self {
        ScheduledFilter {
            filter: Cartesian::new(),
            schedule,
            measurements: 0,
            intervals: RecentIntervals::NONE,
        }
    }

    /// A track from its parts, e.g. a filter handed over already tracking
    /// with `measurements` counted so far (schedules that count treat
    /// n < 3 as 3).
    pub const fn from_parts(
        filter: Cartesian<N, ORDER, D>,
        schedule: G,
        measurements: u32,
    ) -> Self {
        ScheduledFilter {
            filter,
            schedule,
            measurements,
            intervals: RecentIntervals::NONE,
        }
    }

    /// The track's filter.
    pub fn filter(&self) -> &Cartesian<N, ORDER, D> {
        &self.filter
    }

    /// The track's schedule and its state.
    pub fn schedule(&self) -> &G {
        &self.schedule
    }

    /// Measurements incorporated since the track was (re)started.
    pub fn measurements(&self) -> u32 {
        self.measurements
    }

    /// Incorporates measurement `z`, taken `dt` after the previous call
    /// that the track took (a skipped one changed nothing).
    ///
    /// If the interval is longer than [`MAX_INTERVAL_S`] (after the first
    /// measurement; while one point is held, the time since it:
    /// [`IntervalSpan::of_second_point`]) or the schedule requires a
    /// restart, the filter is
    /// emptied and the schedule [reset](GainSchedule::reset) first, and `z`
    /// becomes the first point of the restarted track
    /// ([`UpdateOutcome::Restarted`]). The first two
    /// measurements initialise the filter (no gains). Later ones: each axis
    /// predicts, the [`GainContext`] is built, the schedule gives the gains,
    /// the filter updates every axis with them (all or none) and the
    /// schedule hears that the update was [accepted](GainSchedule::accepted)
    /// (gains of the count alone, [`GainSchedule::count_gains`], skip the
    /// context and the report).
    /// A refused update changes neither the filter (but for its saturation
    /// count) nor the schedule.
    ///
    /// # Real timing
    ///
    /// A measurement less than [`MIN_INTERVAL_S`] after the previous one is
    /// skipped ([`UpdateOutcome::Skipped`]): neither the filter nor the
    /// schedule changes. When the interval
    /// differs from the previous ones, the schedule's gains are bounded for
    /// this update ([`robust_gains`]): α at most 1, β at most Kalata's
    /// steady-state β for α, and the velocity correction of a short
    /// interval at most what the recent longer ones would give. Equal
    /// intervals leave the gains as they are.
    pub fn update(
        &mut self,
        z: [N::Length; D],
        dt: N::Interval,
    ) -> Result<ScheduledUpdate<N, D>, ScheduledError> {
        let gap = match self.filter.phase() {
            Phase::Empty => false,
            _ => {
                if z.iter().any(|v| !v.is_valid()) {
                    return Err(FilterError::InvalidMeasurement.into());
                }
                match IntervalSpan::of(dt)? {
                    IntervalSpan::InRange => false,
                    IntervalSpan::TooLong => true,
                    IntervalSpan::TooShort => {
                        return Ok(ScheduledUpdate {
                            outcome: [UpdateOutcome::Skipped; D],
                            gains: None,
                            restarted: false,
                        })
                    }
                }
            }
        };
        let restarted = gap || self.schedule.restart_required(self.filter.phase());
        if !restarted && self.filter.phase() == Phase::Tracking {
            let n = self.measurements.saturating_add(1);
            return match self.schedule.count_gains(n) {
                Some(gains) => self.counted_update(z, dt, n, gains),
                None => self.filtered_update(z, dt, n),
            };
        }
        // A first point held beyond the filters' range restarts too: the
        // second point's interval is the time since it.
        let restarted = restarted
            || (self.filter.phase() == Phase::OnePoint
                && self.filter.interval_span(dt) == Ok(IntervalSpan::TooLong));
        let mut filter = self.filter;
        if restarted {
            filter.restart();
        }
        let n = if restarted {
            1
        } else {
            self.measurements.saturating_add(1)
        };

        // Two-point initialisation (the filter is empty or has one point)
        // ignores gains; any valid pair will do.
        let unused = unused_gains::<N>()?;
        match filter.update(z, dt, &unused) {
            Ok(outcome) => {
                self.filter = filter;
                self.measurements = n;
                self.intervals
                    .started(filter.phase() == Phase::Tracking, dt);
                if restarted {
                    self.schedule.reset();
                }
                self.schedule.initialised(n, dt);
                Ok(ScheduledUpdate {
                    outcome: if restarted {
                        [UpdateOutcome::Restarted; D]
                    } else {
                        outcome
                    },
                    gains: None,
                    restarted,
                })
            }
            Err(e) => {
                if e == FilterError::Saturated && !restarted {
                    self.filter = filter;
                }
                Err(e.into())
            }
        }
    }

    /// A filtered update of a tracking filter (the measurement is valid):
    /// the axes' predictions once, the context, the gains, the update from
    /// those predictions; all or nothing on the filter and the schedule.
    #[inline(always)]
    fn filtered_update(
        &mut self,
        z: [N::Length; D],
        dt: N::Interval,
        n: u32,
    ) -> Result<ScheduledUpdate<N, D>, ScheduledError> {
        let terms = match IntervalTerms::<N>::new(dt) {
            Ok(t) => t,
            Err(FilterError::Saturated) => return self.refuse_overflow(self.filter, z, dt),
            Err(e) => return Err(e.into()),
        };
        let (predictions, valid) = self.filter.predicted(&terms);
        // z, dt and the predictions are valid: what is left to check is
        // that no innovation overflowed.
        let ctx = GainContext::of_predictions(n, dt, z, &predictions);
        if !(valid && ctx.axes.iter().all(|a| a.innovation.is_valid())) {
            return self.refuse_overflow(self.filter, z, dt);
        }
        // Matched rather than `?` (here and below): the conversion's
        // temporaries cost a library copy of the gains each.
        let scheduled = match self.schedule.gains(&ctx) {
            Ok(g) => g,
            Err(e) => return Err(ScheduledError::Schedule(e)),
        };
        let gains = match self.interval_bounded(scheduled, dt) {
            Ok(g) => g,
            Err(e) => return Err(ScheduledError::Schedule(e)),
        };
        let outcome = match self.filter.update_per_axis_terms(z, &terms, &gains) {
            Ok(o) => o,
            Err(e) => return Err(ScheduledError::Filter(e)),
        };
        self.record_filtered(n, dt);
        self.schedule.accepted(&ctx, &gains);
        Ok(ScheduledUpdate {
            outcome,
            gains: Some(gains),
            restarted: false,
        })
    }

    /// A filtered update with gains of the count alone
    /// ([`GainSchedule::count_gains`]): the filter's own update with one
    /// set of gains for every axis, bounded as in [`Self::filtered_update`];
    /// no context, and the schedule is not told. The same arithmetic as
    /// [`Self::filtered_update`] (the filter predicts, checks and refuses
    /// alike, but for f64 outputs above `f64::MAX`/8, where f64's summing
    /// guard is not exact), without the predictions formed twice.
    #[inline(always)]
    fn counted_update(
        &mut self,
        z: [N::Length; D],
        dt: N::Interval,
        n: u32,
        gains: Result<Gains<N>, ScheduleError>,
    ) -> Result<ScheduledUpdate<N, D>, ScheduledError> {
        let scheduled = match gains {
            Ok(g) => g,
            Err(e) => return Err(ScheduledError::Schedule(e)),
        };
        let [gains] = match self.interval_bounded([scheduled], dt) {
            Ok(g) => g,
            Err(e) => return Err(ScheduledError::Schedule(e)),
        };
        let outcome = match self.filter.update(z, dt, &gains) {
            Ok(o) => o,
            Err(e) => return Err(ScheduledError::Filter(e)),
        };
        self.record_filtered(n, dt);
        Ok(ScheduledUpdate {
            outcome,
            gains: Some([gains; D]),
            restarted: false,
        })
    }

    /// The schedule's gains for an update `dt` after the previous one,
    /// bounded by [`robust_gains`] unless they follow the interval or the
    /// intervals are regular (per axis, or one set for every axis).
    #[inline(always)]
    fn interval_bounded<const K: usize>(
        &self,
        scheduled: [Gains<N>; K],
        dt: N::Interval,
    ) -> Result<[Gains<N>; K], ScheduleError> {
        if self.schedule.gains_follow_interval() || self.intervals.regular(dt) {
            return Ok(scheduled);
        }
        self.intervals.bound(scheduled, dt)
    }

    /// Measurement `n`, `dt` after the previous one, was filtered: the
    /// count and the intervals [`robust_gains`] reads.
    #[inline(always)]
    fn record_filtered(&mut self, n: u32, dt: N::Interval) {
        self.measurements = n;
        self.intervals.filtered(dt);
    }

    /// The prediction or innovation of this update overflowed: let the
    /// filter refuse (and count) the update, as it would without a schedule.
    /// Its gains are not the schedule's (α = β = 1), and its update can stay
    /// in the number format where the schedule's would not; then the result
    /// is discarded and the saturation counted all the same.
    fn refuse_overflow(
        &mut self,
        mut filter: Cartesian<N, ORDER, D>,
        z: [N::Length; D],
        dt: N::Interval,
    ) -> Result<ScheduledUpdate<N, D>, ScheduledError> {
        let unused = unused_gains::<N>()?;
        match filter.update(z, dt, &unused) {
            Err(e) => {
                if e == FilterError::Saturated {
                    self.filter = filter;
                }
                Err(e.into())
            }
            Ok(_) => {
                self.filter.count_saturation();
                Err(FilterError::Saturated.into())
            }
        }
    }

    /// No measurement this scan: the filter coasts and the schedule hears of
    /// the miss.
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        self.filter.coast(dt)?;
        self.schedule.missed(dt);
        Ok(())
    }
}

/// The gains of an update at interval `dt`, after one at `previous` (zero:
/// none) with reference interval `reference` (the longest recent interval,
/// [`next_reference`]), bounded so that irregular intervals do not make the
/// filter diverge (the reasoning and the tests are in
/// `docs/auto.md`). When `dt` equals both (every experiment of the papers)
/// the gains are returned unchanged. Otherwise:
///
/// * α is at most 1 (a gain above 1 overshoots the measurement, and its
///   stable β shrink to nothing on irregular intervals);
/// * β is at most Kalata's steady-state β for α, 2(α/(1 + √(1 − α)))²
///   ([`li_beta`]; Li et al. eq. 7), the least-damped pairing a
///   steady-state Kalman filter uses: pairs far above it (α = 0.002,
///   β = 0.1667) have poles within 10⁻³ of the unit circle, and irregular
///   intervals pump them;
/// * when `dt` is shorter than half the reference, β is scaled by
///   2·dt/reference, so that the velocity gain is at most 2β/reference: in
///   units of the last interval the error dynamics multiply the velocity
///   error by T_prev/T, and a short interval after long ones (or a burst
///   of short ones) would otherwise grow it without bound, whatever the
///   gains (the factor 2 leaves the interval after a missed scan alone);
/// * γ in proportion to β, and once more by the same factor (its gain is
///   γ/(2T²)), at most half its bound 4αβ/(2 − α).
#[inline(never)]
pub fn robust_gains<N: Numeric, const D: usize>(
    gains: [Gains<N>; D],
    dt: N::Interval,
    previous: N::Interval,
    reference: N::Interval,
) -> Result<[Gains<N>; D], ScheduleError> {
    if intervals_regular(dt, previous, reference) {
        return Ok(gains);
    }
    let one = N::Ratio::ONE;
    // 2·dt/reference as (2 m/reference)·dt in metres (the algebra has no
    // interval-by-interval division).
    let shorter = if dt + dt < reference {
        N::Ratio::from((N::Length::from_f64_lossy(2.0) / reference) * dt).min_of(one)
    } else {
        one
    };
    let mut out = gains;
    for g in out.iter_mut() {
        let (alpha, beta, gamma) = (g.alpha().min_of(one), g.beta(), g.gamma());
        let capped = beta.min_of(li_beta(alpha));
        let mut bounded = capped * shorter;
        if !(bounded.is_valid() && bounded > N::Ratio::ZERO) {
            // Rounded to nothing (fixed point, a tiny β): the cap alone.
            bounded = capped;
        }
        *g = if gamma == N::Ratio::ZERO {
            Gains::alpha_beta(alpha, bounded)?
        } else {
            let two = N::Ratio::TWO;
            let limit = two * alpha * bounded / (two - alpha);
            let scaled = (gamma * (bounded / beta) * shorter).min_of(limit);
            let scaled = if scaled > N::Ratio::ZERO {
                scaled
            } else {
                limit
            };
            Gains::alpha_beta_gamma(alpha, bounded, scaled)?
        };
    }
    Ok(out)
}

/// Whether [`robust_gains`] leaves the gains as they are: no previous
/// interval, or `dt` equal to the previous and the reference interval.
#[inline(always)]
fn intervals_regular<Q: Quantity>(dt: Q, previous: Q, reference: Q) -> bool {
    previous <= Q::ZERO || (dt == previous && dt == reference)
}

/// The intervals [`robust_gains`] reads, as a track's updates leave them:
/// T of the last update that left the filter tracking (zero before), and
/// the reference interval, the longest recent one relaxing toward shorter
/// ones by a quarter of the gap per update ([`next_reference`]). Kept by
/// [`ScheduledFilter`] and the M5 bank ([`crate::bank`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RecentIntervals<Q> {
    previous: Q,
    reference: Q,
}

impl<Q: Quantity> RecentIntervals<Q> {
    /// Before the second point (and after a restart).
    pub(crate) const NONE: Self = RecentIntervals {
        previous: Q::ZERO,
        reference: Q::ZERO,
    };

    /// Whether gains for an update at `dt` need no bound
    /// ([`intervals_regular`]).
    #[inline(always)]
    pub(crate) fn regular(&self, dt: Q) -> bool {
        intervals_regular(dt, self.previous, self.reference)
    }

    /// [`robust_gains`] of `gains` for an update at `dt`.
    #[inline(always)]
    pub(crate) fn bound<N: Numeric<Interval = Q>, const D: usize>(
        &self,
        gains: [Gains<N>; D],
        dt: Q,
    ) -> Result<[Gains<N>; D], ScheduleError> {
        robust_gains(gains, dt, self.previous, self.reference)
    }

    /// After a first or second point taken `dt` after the previous one:
    /// `dt` once the filter is tracking (the second point), else none.
    pub(crate) fn started(&mut self, tracking: bool, dt: Q) {
        let previous = if tracking { dt } else { Q::ZERO };
        *self = RecentIntervals {
            previous,
            reference: previous,
        };
    }

    /// After a filtered update `dt` after the previous one.
    #[inline(always)]
    pub(crate) fn filtered(&mut self, dt: Q) {
        self.previous = dt;
        self.reference = next_reference(self.reference, dt);
    }
}

/// The reference interval after an update at `dt`: `dt` if it is not
/// shorter, else the reference moved a quarter of the way toward `dt`.
pub fn next_reference<Q: Quantity>(reference: Q, dt: Q) -> Q {
    if dt >= reference {
        dt
    } else {
        reference - (reference - dt).half().half()
    }
}

/// Gains for the updates that ignore them (two-point initialisation): any
/// valid pair will do.
fn unused_gains<N: Numeric>() -> Result<Gains<N>, ScheduledError> {
    use crate::num::Real;
    Gains::alpha_beta(N::Ratio::ONE, N::Ratio::ONE)
        .map_err(|e| ScheduledError::Schedule(ScheduleError::Gain(e)))
}

/// Euclidean norm of a vector (a chain of [`Numeric::hypot`], which never
/// squares its arguments).
pub(crate) fn norm<N: Numeric>(v: &[N::Length]) -> N::Length {
    v.iter().fold(N::Length::ZERO, |acc, &x| N::hypot(acc, x))
}

/// Any schedule a [`ScheduleSpec`] can name, in one `Copy` type, so a tool or
/// firmware can choose the schedule at run time. `W` is the capacity of the
/// windows of M3, M4 and Liu's residual accumulation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AnySchedule<N: Numeric, const D: usize, const W: usize> {
    /// `fixed`, `m1`, `liu-fixed`: constant gains.
    Fixed(FixedGains<N>),
    /// `least-squares`, `m2`, `liu-count`: Al-Wagih eq. 24.
    LeastSquares(LeastSquaresGains),
    /// `m3`: Al-Wagih eq. 25, Algorithm 1.
    LinearCombination(LinearCombinationGains<N, D, W>),
    /// `m4`: Al-Wagih Algorithm 2.
    MovingWindow(MovingWindowGains<N, D, W>),
    /// `li-improved`: Li et al. eqs. 4, 7–15.
    LiImproved(LiImprovedGains<N>),
    /// `liu-count-adjusted`: Liu, Wang & Yang §2.1.2.
    ScanCountAdjusted(ScanCountAdjustedGains<N>),
    /// `liu-residual`: Liu, Wang & Yang eqs. 6–11.
    ResidualAccumulation(ResidualAccumulationGains<N, D, W>),
    /// `liu-adaptive`: Liu, Wang & Yang eqs. 12–15.
    AdaptiveSwitch(AdaptiveSwitchGains<N, D, W>),
    /// `tcas-firmness`: the DO-185B firmness table.
    Firmness(FirmnessGains),
    /// `auto`: per-axis Kalman gains, q from the innovations (`docs/auto.md`).
    Auto(AutoGains<N, D>),
}

impl<N: Numeric, const D: usize, const W: usize> AnySchedule<N, D, W> {
    /// The schedule `spec` names, configured as it says.
    /// [`ScheduleSpec::Bank`] is refused with [`ConfigError::NotASchedule`].
    pub fn from_spec(spec: &ScheduleSpec) -> Result<Self, ConfigError> {
        Ok(match spec {
            ScheduleSpec::Fixed(c) => AnySchedule::Fixed(FixedGains::from_config(c)?),
            ScheduleSpec::FixedAlpha(c) => AnySchedule::Fixed(FixedGains::from_m1_config(c)?),
            ScheduleSpec::LeastSquares(c) => AnySchedule::LeastSquares(LeastSquaresGains::new(c)?),
            ScheduleSpec::LinearCombination(c) => {
                AnySchedule::LinearCombination(LinearCombinationGains::new(c)?)
            }
            ScheduleSpec::MovingWindow(c) => AnySchedule::MovingWindow(MovingWindowGains::new(c)?),
            ScheduleSpec::LiImproved(c) => AnySchedule::LiImproved(LiImprovedGains::new(c)?),
            ScheduleSpec::ScanCountAdjusted(c) => {
                AnySchedule::ScanCountAdjusted(ScanCountAdjustedGains::new(c)?)
            }
            ScheduleSpec::ResidualAccumulation(c) => {
                AnySchedule::ResidualAccumulation(ResidualAccumulationGains::new(c)?)
            }
            ScheduleSpec::AdaptiveSwitch(c) => {
                AnySchedule::AdaptiveSwitch(AdaptiveSwitchGains::new(c)?)
            }
            ScheduleSpec::Firmness => AnySchedule::Firmness(FirmnessGains::new()),
            ScheduleSpec::Auto(c) => AnySchedule::Auto(AutoGains::new(c)?),
            ScheduleSpec::Bank(_) => return Err(ConfigError::NotASchedule),
        })
    }
}

macro_rules! dispatch {
    ($self:expr, $s:ident => $e:expr) => {
        match $self {
            AnySchedule::Fixed($s) => $e,
            AnySchedule::LeastSquares($s) => $e,
            AnySchedule::LinearCombination($s) => $e,
            AnySchedule::MovingWindow($s) => $e,
            AnySchedule::LiImproved($s) => $e,
            AnySchedule::ScanCountAdjusted($s) => $e,
            AnySchedule::ResidualAccumulation($s) => $e,
            AnySchedule::AdaptiveSwitch($s) => $e,
            AnySchedule::Firmness($s) => $e,
            AnySchedule::Auto($s) => $e,
        }
    };
}

impl<N: Numeric, const D: usize, const W: usize> GainSchedule<N, D> for AnySchedule<N, D, W> {
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        dispatch!(self, s => s.gains(ctx))
    }
    fn accepted(&mut self, ctx: &GainContext<N, D>, used: &[Gains<N>; D]) {
        dispatch!(self, s => s.accepted(ctx, used))
    }
    fn initialised(&mut self, n: u32, dt: N::Interval) {
        dispatch!(self, s => GainSchedule::<N, D>::initialised(s, n, dt))
    }
    fn missed(&mut self, dt: N::Interval) {
        dispatch!(self, s => GainSchedule::<N, D>::missed(s, dt))
    }
    fn count_gains(&self, n: u32) -> Option<Result<Gains<N>, ScheduleError>> {
        dispatch!(self, s => GainSchedule::<N, D>::count_gains(s, n))
    }
    fn gains_follow_interval(&self) -> bool {
        dispatch!(self, s => GainSchedule::<N, D>::gains_follow_interval(s))
    }
    fn predicted_variance_ratios(&self, dt: N::Interval) -> Option<[N::Ratio; D]> {
        dispatch!(self, s => GainSchedule::<N, D>::predicted_variance_ratios(s, dt))
    }
    fn restart_required(&self, phase: Phase) -> bool {
        dispatch!(self, s => GainSchedule::<N, D>::restart_required(s, phase))
    }
    fn reset(&mut self) {
        dispatch!(self, s => GainSchedule::<N, D>::reset(s))
    }
}
