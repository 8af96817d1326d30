//! What the track table needs from a filter ([`TrackFilter`]), the
//! measurements it feeds it ([`Measurement`], [`Observation`]), and the
//! implementation for the fixed-gain Cartesian αβ filter ([`FixedGainTrack`]).

use super::gate::{Gate, GateRegion};
use crate::filter::{
    FilterError, Gains, IntervalTerms, KinematicFilter, Phase, StepGains, UpdateKind,
};
use crate::num::{Numeric, Quantity, Real};

/// One detection of one scan, as the sensor reports it. (The tags start at
/// 1 so that an absent measurement, `None`, is zero bytes: a table's
/// measurement slots start as zeros; a word, as the payload's alignment
/// would make it anyway, so that copies stay whole words.)
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u32)]
pub enum Measurement<S: Numeric> {
    /// Position in the tracking plane (m).
    Cartesian {
        /// x (m).
        x: S::Length,
        /// y (m).
        y: S::Length,
    } = 1,
    /// Range (m, ≥ 0) and azimuth (rad, clockwise from the +y axis) from a
    /// sensor at the origin; projected as x = R·sin B, y = R·cos B
    /// (He, Peng, Ling & Quan, §2).
    Polar {
        /// R, the slant range (m, ≥ 0).
        range: S::Length,
        /// B, the azimuth (rad, clockwise from the +y axis).
        azimuth: S::Ratio,
    } = 2,
}

/// Why a measurement was rejected (it touched no track).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RejectReason {
    /// A coordinate is NaN, infinite or a saturated fixed-point value, or its
    /// Cartesian projection is.
    NotFinite,
    /// A polar measurement with a negative range.
    NegativeRange,
    /// The filter refused it (the arithmetic saturated): it won its
    /// track's gate and the track coasted instead, or it was a new track's
    /// second point and the filter refused the two points: the track did
    /// not start.
    FilterRefused,
    /// Its scan came less than [`crate::filter::MIN_INTERVAL_S`] after the
    /// previous scan: the whole scan was skipped, no track changed.
    TooClose,
}

/// A validated measurement with its Cartesian projection, computed once.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Observation<S: Numeric> {
    measurement: Measurement<S>,
    xy: [S::Length; 2],
}

impl<S: Numeric> Observation<S> {
    /// Checks the measurement and projects it to x, y (a polar one in the
    /// number system's polar scalar, [`Numeric::Polar`]).
    pub fn new(measurement: Measurement<S>) -> Result<Self, RejectReason> {
        let xy = match measurement {
            Measurement::Cartesian { x, y } => [x, y],
            Measurement::Polar { range, azimuth } => {
                if !(range.is_valid() && Quantity::is_valid(azimuth)) {
                    return Err(RejectReason::NotFinite);
                }
                if range < S::Length::ZERO {
                    return Err(RejectReason::NegativeRange);
                }
                let r = S::length_to_polar(range);
                let (sin_b, cos_b) = <S::Polar as Numeric>::sin_cos(S::ratio_to_polar(azimuth));
                [
                    S::length_from_polar(r * sin_b),
                    S::length_from_polar(r * cos_b),
                ]
            }
        };
        if !(xy[0].is_valid() && xy[1].is_valid()) {
            return Err(RejectReason::NotFinite);
        }
        Ok(Observation { measurement, xy })
    }

    /// The measurement as the sensor reported it.
    pub fn measurement(&self) -> Measurement<S> {
        self.measurement
    }

    /// Cartesian position (m).
    pub fn xy(&self) -> [S::Length; 2] {
        self.xy
    }
}

/// A track's state predicted to the scan time, without changing it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PredictedState<S: Numeric> {
    /// Predicted position (x, y) (m).
    pub position: [S::Length; 2],
    /// Predicted velocity (x, y) (m/s).
    pub velocity: [S::Speed; 2],
}

/// The interval of one scan, formed once per scan by the table and passed
/// to every track's filter: T as the filters' interval quantity, T as the
/// covariance bookkeeping's number of seconds, and T²/2 (the gate's
/// manoeuvre allowance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanInterval<S: Numeric> {
    terms: IntervalTerms<S>,
    seconds: S::Variance,
}

impl<S: Numeric> ScanInterval<S> {
    /// The interval of `ms` milliseconds (> 0); `None` if it is 0 or not
    /// representable.
    pub fn from_ms(ms: u32) -> Option<Self> {
        let terms = IntervalTerms::new(S::Interval::seconds_from_ms(ms)).ok()?;
        let seconds = S::to_variance(S::Ratio::seconds_from_ms(ms));
        (seconds.is_valid() && seconds != S::Variance::ZERO)
            .then_some(ScanInterval { terms, seconds })
    }

    /// T.
    pub fn interval(&self) -> S::Interval {
        self.terms.interval()
    }

    /// T and T²/2.
    pub fn terms(&self) -> &IntervalTerms<S> {
        &self.terms
    }

    /// The number of seconds T, in the covariance's number type.
    pub fn seconds(&self) -> S::Variance {
        self.seconds
    }
}

/// What a filter must provide to live in a [`TrackTable`](super::TrackTable).
///
/// The implementing type is the whole per-track estimator state: for a filter
/// driven by a gain schedule, the filter *and* the schedule's per-track state
/// (update count, innovation window, ...) in one `Copy` record, as
/// [`ScheduledTrack`](super::ScheduledTrack) holds a
/// [`ScheduledFilter`](crate::gain::ScheduledFilter) and each axis's
/// [`Uncertainty`](super::Uncertainty). Everything shared by all tracks (fixed
/// gains, schedule constants, noise figures) is [`Self::Params`], stored once
/// in the [`TrackerConfig`](super::TrackerConfig) and passed to every call,
/// so it costs no bytes per track; what depends only on the parameters and
/// the scan's interval (β/T of fixed gains) is [`Self::Step`], formed once
/// per scan ([`Self::step`]); what a track's gate forms that its update in
/// the same scan needs again (the default track's predicted covariance
/// terms) is [`Self::GateKept`], held in the table's per-scan workspace.
///
/// Contract (as for [`crate::filter`]): the step is for the time since the
/// previous `update` or `coast`. An `Err` leaves the state untouched.
///
/// Keeping (`GateKept` other than `()`): [`Self::gate_region_keeping`]
/// gives the region [`Self::gate_region`] gives (the table recomputes an
/// uncached track's costs with the latter) and writes all of `kept`
/// whenever it gives one, whatever `kept` held (an earlier scan's or
/// another track's); [`Self::update_after_gate`] gives what
/// [`Self::update`] gives, bit for bit. The table calls
/// `update_after_gate` only for a track whose `gate_region_keeping` gave
/// a region in the same scan, with the same step and the filter unchanged
/// since; called with anything else (another state's, [`Self::NOTHING_KEPT`])
/// it gives wrong estimates, not an error. [`Self::NOTHING_KEPT`] should be
/// all zero bytes, so that a new table still is (a `static` one lands in
/// `.bss`).
pub trait TrackFilter<S: Numeric>: Copy {
    /// Configuration shared by every track.
    type Params: Copy;
    /// What every track's update needs of one scan's interval.
    type Step: Copy;
    /// What the gate forms of a track that the same scan's update of it
    /// takes again ([`Self::gate_region_keeping`],
    /// [`Self::update_after_gate`]): the default track's predicted
    /// covariance terms; `()` for a filter that keeps nothing (no bytes).
    type GateKept: Copy + core::fmt::Debug;
    /// A placeholder [`Self::GateKept`]: the table's workspace before a
    /// gate writes it (all zero bytes; never passed to an update).
    const NOTHING_KEPT: Self::GateKept;

    /// The step of an interval, formed once per scan for every track.
    fn step(params: &Self::Params, interval: &ScanInterval<S>) -> Result<Self::Step, FilterError>;

    /// A filter that has seen no measurement.
    fn empty(params: &Self::Params) -> Self;

    /// Incorporates a measurement taken `step`'s interval after the previous
    /// call. The table initiates tracks by two updates on an empty filter
    /// (two-point initialisation, Al-Wagih & Abdulla eqs. 9–10).
    fn update(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        step: &Self::Step,
    ) -> Result<(), FilterError>;

    /// No measurement this scan: advance by the step's interval.
    fn coast(&mut self, params: &Self::Params, step: &Self::Step) -> Result<(), FilterError>;

    /// The state the step's interval ahead, without changing the filter.
    fn predict(
        &self,
        params: &Self::Params,
        step: &Self::Step,
    ) -> Result<PredictedState<S>, FilterError>;

    /// Smoothed position (m).
    fn position(&self) -> [S::Length; 2];

    /// Smoothed velocity (m/s).
    fn velocity(&self) -> [S::Speed; 2];

    /// Variance of the position predicted the step's interval ahead, per
    /// axis, in units of the measurement noise variance (1 = as uncertain as
    /// one measurement). `None` if unknown (before two measurements).
    fn predicted_variance_ratio(
        &self,
        params: &Self::Params,
        step: &Self::Step,
    ) -> Option<S::Ratio>;

    /// The position gain α for [`Self::gate_region`]'s default, Li et
    /// al.'s wave gate (λ = √α, eq. 12): a filter whose gains follow the
    /// interval gives them for a 1 s scan here (this signature has no
    /// interval) and overrides `gate_region` to use the scan's own.
    fn gate_alpha(&self, params: &Self::Params) -> S::Ratio;

    /// The step's interval and T²/2.
    fn interval_of(step: &Self::Step) -> &ScanInterval<S>;

    /// This track's validation region for a scan the step's interval ahead
    /// whose predicted state is `predicted`; `None` if no region can be
    /// formed (the track then gets no measurement and coasts).
    ///
    /// The default builds the Cartesian circle described on [`Gate`]. A
    /// filter that gates differently (range/azimuth windows) overrides it.
    fn gate_region(
        &self,
        params: &Self::Params,
        predicted: &PredictedState<S>,
        step: &Self::Step,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        let radius = match *gate {
            Gate::Uncertainty {
                measurement_sigma,
                threshold,
                max_acceleration,
            } => {
                let p = self.predicted_variance_ratio(params, step)?;
                let interval = Self::interval_of(step);
                return uncertainty_region(
                    predicted.position,
                    measurement_sigma,
                    threshold,
                    max_acceleration,
                    p,
                    interval,
                );
            }
            Gate::Wave {
                range_sigma,
                bearing_sigma,
                multiple,
            } => wave_radius::<S>(
                range_sigma,
                bearing_sigma,
                multiple,
                self.gate_alpha(params),
                predicted.position,
            ),
        };
        GateRegion::circle(predicted.position, radius)
    }

    /// [`Self::gate_region`], writing to `kept` what the update of the same
    /// scan takes again ([`Self::update_after_gate`]) when it gives a
    /// region (the trait's "Keeping"). The default keeps nothing.
    fn gate_region_keeping(
        &self,
        params: &Self::Params,
        predicted: &PredictedState<S>,
        step: &Self::Step,
        gate: &Gate<S>,
        kept: &mut Self::GateKept,
    ) -> Option<GateRegion<S>> {
        let _ = kept;
        self.gate_region(params, predicted, step, gate)
    }

    /// [`Self::update`] in the scan whose gate kept `kept` for this filter
    /// as it is and this step ([`Self::gate_region_keeping`]): the same
    /// result. The default forms everything again.
    fn update_after_gate(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        step: &Self::Step,
        kept: &Self::GateKept,
    ) -> Result<(), FilterError> {
        let _ = kept;
        self.update(params, z, step)
    }
}

/// One second: the interval [`TrackFilter::gate_alpha`] assumes (its
/// signature has none).
pub(super) fn one_second<S: Numeric>() -> Option<ScanInterval<S>> {
    ScanInterval::from_ms(1000)
}

/// The region of [`Gate::Uncertainty`] around `center` for predicted
/// variance ratio `p` (the rule documented on [`Gate`]): radius
/// σ·√(G·(p + 1)) + ½·a_max·T². Without a manoeuvre allowance it is formed
/// from its square σ²·G·(p + 1) ([`GateRegion::scaled_circle`]: no square
/// root in floats).
pub(super) fn uncertainty_region<S: Numeric>(
    center: [S::Length; 2],
    measurement_sigma: S::Length,
    threshold: S::Ratio,
    max_acceleration: S::Acceleration,
    p: S::Ratio,
    interval: &ScanInterval<S>,
) -> Option<GateRegion<S>> {
    let factor = threshold * (p + <S::Ratio as Real>::ONE);
    // No allowance (the default filter's gate, a constant there): no
    // product formed.
    let allowance = if max_acceleration == S::Acceleration::ZERO {
        S::Length::ZERO
    } else {
        max_acceleration * interval.terms().half_squared()
    };
    if allowance == S::Length::ZERO {
        return GateRegion::scaled_circle(center, measurement_sigma, factor);
    }
    GateRegion::circle(center, factor.sqrt() * measurement_sigma + allowance)
}

/// The gate the design's rule 4 counts clutter in, for a track `scans`
/// scans after its last hit (1: the scan after it) at intervals T, under
/// [`Gate::Uncertainty`]: two points T apart give position variance σ² and
/// velocity variance 2σ²/T² (covariance σ²/T), so m·T ahead, without
/// process noise, the innovation's variance is 2σ²(1 + m + m²) and the
/// radius σ·√(2G·(1 + m + m²)) + ½·a_max·(mT)². `None` for the wave gate or
/// if not representable.
pub(super) fn two_point_gate_radius<S: Numeric>(
    gate: &Gate<S>,
    scans: u8,
    interval: &ScanInterval<S>,
) -> Option<S::Length> {
    let Gate::Uncertainty {
        measurement_sigma,
        threshold,
        max_acceleration,
    } = *gate
    else {
        return None;
    };
    let m = u64::from(scans);
    // m ≤ 255: nothing saturates.
    let squared = m.saturating_mul(m);
    let spread = 1u64
        .saturating_add(m)
        .saturating_add(squared)
        .saturating_mul(2);
    let spread = <S::Ratio as Real>::from_ratio(spread, 1);
    let growth = <S::Ratio as Real>::from_ratio(squared, 1);
    let allowance = max_acceleration * interval.terms().half_squared();
    let radius = (threshold * spread).sqrt() * measurement_sigma + growth * allowance;
    radius.is_valid().then_some(radius)
}

/// Li et al. eqs. (11)–(12): the wave gate's radius κ·λ·√(Δρ² + ρ²Δθ²),
/// λ = √α, ρ the range of the predicted `position`.
pub(super) fn wave_radius<S: Numeric>(
    range_sigma: S::Length,
    bearing_sigma: S::Ratio,
    multiple: S::Ratio,
    alpha: S::Ratio,
    position: [S::Length; 2],
) -> S::Length {
    let rho = S::hypot(position[0], position[1]);
    (multiple * alpha.sqrt()) * S::hypot(range_sigma, bearing_sigma * rho)
}

/// Covariance of one axis's (position, velocity) estimation error, in units
/// of the measurement noise variance σ² (so `p11` is dimensionless, `p12` in
/// 1/s, `p22` in 1/s²), for white measurement noise and no process noise.
///
/// It follows the αβ recursion exactly, for any gain sequence and any
/// intervals, which is what a gate needs right after initiation, when the
/// filter is far from its steady state. In steady state with fixed gains and
/// T = 1 the predicted `p11` converges to Tenne & Singh's noise ratio, eq. (13):
/// ρ² = (2α² + αβ + 2β) / (α(4 − β − 2α)) — their "RMS of the system
/// response" is the one-step prediction (α = β = 1 gives 2z_k − z_{k−1},
/// variance 5; eq. 13 gives 5), which the tests check.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ErrorVariance<R> {
    /// Position error variance (dimensionless, in units of σ²).
    pub p11: R,
    /// Position–velocity error covariance (1/s, in units of σ²).
    pub p12: R,
    /// Velocity error variance (1/s², in units of σ²).
    pub p22: R,
}

impl<R: Real> ErrorVariance<R> {
    /// After two-point initialisation over interval T (Al-Wagih eq. 9):
    /// x = z₂ (variance 1), v = (z₂ − z₁)/T (variance 2/T²), and
    /// cov(z₂, (z₂ − z₁)/T) = 1/T. `interval` in seconds.
    pub fn after_two_points(interval: R) -> Self {
        let inv = R::ONE / interval;
        ErrorVariance {
            p11: R::ONE,
            p12: inv,
            p22: R::TWO * inv * inv,
        }
    }

    /// Propagated over `dt` seconds by Φ = [[1, T], [0, 1]]: P⁻ = Φ·P·Φᵀ.
    pub fn predicted(&self, dt: R) -> Self {
        let two = R::TWO;
        ErrorVariance {
            p11: self.p11 + dt * (two * self.p12 + dt * self.p22),
            p12: self.p12 + dt * self.p22,
            p22: self.p22,
        }
    }

    /// `self` is the prediction P⁻; the update with gain K = [α, β/T]ᵀ
    /// (Al-Wagih eqs. 6 and 8), in Joseph form, which holds for any gain:
    /// P = (I − KH)·P⁻·(I − KH)ᵀ + K·Kᵀ (R = 1 in these units).
    pub fn updated(&self, alpha: R, beta: R, dt: R) -> Self {
        self.updated_with(alpha, beta / dt)
    }

    /// [`Self::updated`] with the velocity gain k₂ = β/T formed already.
    pub fn updated_with(&self, alpha: R, velocity_gain: R) -> Self {
        self.updated_by(&UpdateTerms::new(alpha, velocity_gain))
    }

    /// [`Self::updated`] with the gains' terms formed already (once per
    /// interval, for fixed gains): the same results.
    pub fn updated_by(&self, t: &UpdateTerms<R>) -> Self {
        ErrorVariance {
            p11: t.one_minus_alpha_squared * self.p11 + t.alpha_squared,
            p12: t.one_minus_alpha * (self.p12 - t.velocity_gain * self.p11) + t.alpha_velocity,
            p22: self.p22 - t.twice_velocity_gain * self.p12
                + t.velocity_gain_squared * (self.p11 + R::ONE),
        }
    }

    /// False if any entry is NaN, ±∞ or saturated.
    pub fn is_valid(&self) -> bool {
        self.p11.is_valid() && self.p12.is_valid() && self.p22.is_valid()
    }
}

/// The terms of [`ErrorVariance::updated`] (the Joseph form of Al-Wagih
/// eqs. 6 and 8) that depend on the gains alone, α and k₂ = β/T: 1 − α,
/// (1 − α)², α², k₂, α·k₂, 2·k₂ and k₂², each rounded as the update
/// formed it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct UpdateTerms<R> {
    one_minus_alpha: R,
    one_minus_alpha_squared: R,
    alpha_squared: R,
    velocity_gain: R,
    alpha_velocity: R,
    twice_velocity_gain: R,
    velocity_gain_squared: R,
}

impl<R: Real> UpdateTerms<R> {
    /// The terms for gains `alpha` and `velocity_gain` (k₂ = β/T).
    pub fn new(alpha: R, velocity_gain: R) -> Self {
        let one_minus_alpha = R::ONE - alpha;
        UpdateTerms {
            one_minus_alpha,
            one_minus_alpha_squared: one_minus_alpha * one_minus_alpha,
            alpha_squared: alpha * alpha,
            velocity_gain,
            alpha_velocity: alpha * velocity_gain,
            twice_velocity_gain: R::TWO * velocity_gain,
            velocity_gain_squared: velocity_gain * velocity_gain,
        }
    }
}

/// The estimation-error bookkeeping that goes with a two-point-initialised
/// αβ filter: nothing, one point (and the seconds since), or a covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Uncertainty<R> {
    /// No measurement yet.
    Empty,
    /// One measurement so far.
    OnePoint {
        /// Seconds since that measurement.
        elapsed: R,
    },
    /// Two or more measurements: the error covariance.
    Tracking(ErrorVariance<R>),
}

impl<R: Real> Uncertainty<R> {
    /// The bookkeeping after an update of kind `kind` with the gains'
    /// terms `gains` over `dt` seconds; `None` if it left the
    /// representable range.
    pub fn after_update(&self, kind: UpdateKind, gains: &UpdateTerms<R>, dt: R) -> Option<Self> {
        let next = match (kind, self) {
            (UpdateKind::FirstPoint, _) => Uncertainty::OnePoint { elapsed: R::ZERO },
            (UpdateKind::SecondPoint, Uncertainty::OnePoint { elapsed }) => {
                Uncertainty::Tracking(ErrorVariance::after_two_points(*elapsed + dt))
            }
            (UpdateKind::SecondPoint, _) => {
                Uncertainty::Tracking(ErrorVariance::after_two_points(dt))
            }
            (UpdateKind::Filtered, Uncertainty::Tracking(p)) => {
                Uncertainty::Tracking(p.predicted(dt).updated_by(gains))
            }
            // A filtered update without a covariance (a filter started with
            // `from_state`): start from the two-point covariance.
            (UpdateKind::Filtered, _) => Uncertainty::Tracking(
                ErrorVariance::after_two_points(dt)
                    .predicted(dt)
                    .updated_by(gains),
            ),
        };
        next.is_valid().then_some(next)
    }

    /// The bookkeeping after coasting `dt` seconds.
    pub fn after_coast(&self, dt: R) -> Option<Self> {
        let next = match self {
            Uncertainty::Empty => Uncertainty::Empty,
            Uncertainty::OnePoint { elapsed } => Uncertainty::OnePoint {
                elapsed: *elapsed + dt,
            },
            Uncertainty::Tracking(p) => Uncertainty::Tracking(p.predicted(dt)),
        };
        next.is_valid().then_some(next)
    }

    /// Predicted position variance ratio `dt` seconds ahead (see
    /// [`TrackFilter::predicted_variance_ratio`]).
    pub fn predicted_variance_ratio(&self, dt: R) -> Option<R> {
        match self {
            Uncertainty::Tracking(p) => {
                let r = p.predicted(dt).p11;
                r.is_valid().then_some(r)
            }
            _ => None,
        }
    }

    fn is_valid(&self) -> bool {
        match self {
            Uncertainty::Empty => true,
            Uncertainty::OnePoint { elapsed } => elapsed.is_valid(),
            Uncertainty::Tracking(p) => p.is_valid(),
        }
    }
}

/// A 2-D αβ filter with one fixed set of gains for every track (`Params =
/// Gains<S>`, the per-interval gains β/T formed once per scan), plus the
/// error covariance that sizes its gate, in as few bytes as the state
/// allows: position and velocity in the number system's own formats, the
/// covariance (three [`Numeric::Variance`] numbers) shared by both
/// axes (the same gains and intervals give both axes the same covariance),
/// nothing else (no innovation, no per-axis phase or counter: a refusal is
/// counted by the table, [`Track::refusals`](super::Track::refusals)).
/// `docs/track-table.md` gives its bytes per number system.
///
/// The arithmetic is [`KinematicFilter`]'s (two-point initialisation,
/// Al-Wagih & Abdulla eqs. 3–10, and the per-interval update), run on the
/// two axes of this state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedGainTrack<S: Numeric> {
    state: FixedGainState<S>,
}

/// [`FixedGainTrack`]'s state by phase of two-point initialisation.
#[derive(Debug, Clone, Copy, PartialEq)]
enum FixedGainState<S: Numeric> {
    Empty,
    /// One measurement; the time since (coasts add to it), as the filter's
    /// interval and as seconds for the covariance.
    OnePoint {
        position: [S::Length; 2],
        elapsed: S::Interval,
        elapsed_seconds: S::Variance,
    },
    Tracking {
        position: [S::Length; 2],
        velocity: [S::Speed; 2],
        variance: ErrorVariance<S::Variance>,
    },
}

/// [`FixedGainTrack`]'s per-scan step: the interval, the step gains of both
/// axes, and the covariance update's terms of α and β/T.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedGainStep<S: Numeric> {
    interval: ScanInterval<S>,
    gains: StepGains<S>,
    covariance: UpdateTerms<S::Variance>,
}

impl<S: Numeric> FixedGainStep<S> {
    /// The covariance bookkeeping after an update of kind `kind` with this
    /// step's gains (Al-Wagih eqs. 6, 8).
    fn after(
        &self,
        uncertainty: Uncertainty<S::Variance>,
        kind: UpdateKind,
    ) -> Option<Uncertainty<S::Variance>> {
        uncertainty.after_update(kind, &self.covariance, self.interval.seconds())
    }
}

impl<S: Numeric> FixedGainTrack<S> {
    /// The phase of two-point initialisation.
    pub fn phase(&self) -> Phase {
        match self.state {
            FixedGainState::Empty => Phase::Empty,
            FixedGainState::OnePoint { .. } => Phase::OnePoint,
            FixedGainState::Tracking { .. } => Phase::Tracking,
        }
    }

    /// The covariance bookkeeping.
    pub fn uncertainty(&self) -> Uncertainty<S::Variance> {
        match self.state {
            FixedGainState::Empty => Uncertainty::Empty,
            FixedGainState::OnePoint {
                elapsed_seconds, ..
            } => Uncertainty::OnePoint {
                elapsed: elapsed_seconds,
            },
            FixedGainState::Tracking { variance, .. } => Uncertainty::Tracking(variance),
        }
    }

    /// The tracking state with the covariance `uncertainty` (refused if
    /// the bookkeeping left its range).
    fn tracking(
        position: [S::Length; 2],
        velocity: [S::Speed; 2],
        uncertainty: Option<Uncertainty<S::Variance>>,
    ) -> Result<Self, FilterError> {
        let Some(Uncertainty::Tracking(variance)) = uncertainty else {
            return Err(FilterError::Saturated);
        };
        Ok(FixedGainTrack {
            state: FixedGainState::Tracking {
                position,
                velocity,
                variance,
            },
        })
    }

    /// Two-point initialisation through the filter's own code: the first
    /// point at `position`, `elapsed` before this step's interval.
    fn second_point(
        position: [S::Length; 2],
        elapsed: S::Interval,
        elapsed_seconds: S::Variance,
        z: [S::Length; 2],
        step: &FixedGainStep<S>,
    ) -> Result<Self, FilterError> {
        let mut velocity = [S::Speed::ZERO; 2];
        let mut next = [S::Length::ZERO; 2];
        for (((v, p), &first), &z) in velocity
            .iter_mut()
            .zip(next.iter_mut())
            .zip(&position)
            .zip(&z)
        {
            let mut axis = KinematicFilter::<S, 2>::new();
            axis.update_step(first, &step.gains)?;
            if elapsed > S::Interval::ZERO {
                axis.coast(elapsed)?;
            }
            axis.update_step(z, &step.gains)?;
            *v = axis.velocity();
            *p = axis.position();
        }
        let one_point = Uncertainty::OnePoint {
            elapsed: elapsed_seconds,
        };
        Self::tracking(
            next,
            velocity,
            step.after(one_point, UpdateKind::SecondPoint),
        )
    }
}

impl<S: Numeric> TrackFilter<S> for FixedGainTrack<S> {
    type Params = Gains<S>;
    type Step = FixedGainStep<S>;
    type GateKept = ();
    const NOTHING_KEPT: () = ();

    fn step(gains: &Gains<S>, interval: &ScanInterval<S>) -> Result<FixedGainStep<S>, FilterError> {
        let alpha = S::to_variance(gains.alpha());
        let velocity_gain = S::to_variance(gains.beta()) / interval.seconds();
        let covariance = UpdateTerms::new(alpha, velocity_gain);
        if !(alpha.is_valid() && velocity_gain.is_valid()) {
            return Err(FilterError::Saturated);
        }
        Ok(FixedGainStep {
            interval: *interval,
            gains: StepGains::new(gains, interval.interval())?,
            covariance,
        })
    }

    fn interval_of(step: &FixedGainStep<S>) -> &ScanInterval<S> {
        &step.interval
    }

    fn empty(_: &Gains<S>) -> Self {
        FixedGainTrack {
            state: FixedGainState::Empty,
        }
    }

    fn update(
        &mut self,
        _: &Gains<S>,
        z: &Observation<S>,
        step: &FixedGainStep<S>,
    ) -> Result<(), FilterError> {
        let z = z.xy();
        let next = match self.state {
            FixedGainState::Empty => {
                if !(z[0].is_valid() && z[1].is_valid()) {
                    return Err(FilterError::InvalidMeasurement);
                }
                FixedGainTrack {
                    state: FixedGainState::OnePoint {
                        position: z,
                        elapsed: S::Interval::ZERO,
                        elapsed_seconds: S::Variance::ZERO,
                    },
                }
            }
            FixedGainState::OnePoint {
                position,
                elapsed,
                elapsed_seconds,
            } => Self::second_point(position, elapsed, elapsed_seconds, z, step)?,
            FixedGainState::Tracking {
                position, velocity, ..
            } => {
                // Both axes computed on copies, written only if both pass.
                let mut next_position = position;
                let mut next_velocity = velocity;
                for ((p, v), &z) in next_position
                    .iter_mut()
                    .zip(next_velocity.iter_mut())
                    .zip(&z)
                {
                    let mut axis =
                        KinematicFilter::<S, 2>::from_state(*p, *v, S::Acceleration::ZERO)?;
                    axis.update_step(z, &step.gains)?;
                    *p = axis.position();
                    *v = axis.velocity();
                }
                let uncertainty = step.after(self.uncertainty(), UpdateKind::Filtered);
                Self::tracking(next_position, next_velocity, uncertainty)?
            }
        };
        *self = next;
        Ok(())
    }

    fn coast(&mut self, _: &Gains<S>, step: &FixedGainStep<S>) -> Result<(), FilterError> {
        let next = match self.state {
            FixedGainState::Empty => return Ok(()),
            FixedGainState::OnePoint {
                position,
                elapsed,
                elapsed_seconds,
            } => {
                let elapsed = elapsed + step.interval.interval();
                let elapsed_seconds = elapsed_seconds + step.interval.seconds();
                if !(elapsed.is_valid() && elapsed_seconds.is_valid()) {
                    return Err(FilterError::Saturated);
                }
                FixedGainTrack {
                    state: FixedGainState::OnePoint {
                        position,
                        elapsed,
                        elapsed_seconds,
                    },
                }
            }
            FixedGainState::Tracking { .. } => {
                let p = self.predict_with(step)?;
                let uncertainty = self.uncertainty().after_coast(step.interval.seconds());
                Self::tracking(p.position, p.velocity, uncertainty)?
            }
        };
        *self = next;
        Ok(())
    }

    fn predict(
        &self,
        _: &Gains<S>,
        step: &FixedGainStep<S>,
    ) -> Result<PredictedState<S>, FilterError> {
        self.predict_with(step)
    }

    fn position(&self) -> [S::Length; 2] {
        match self.state {
            FixedGainState::Empty => [S::Length::ZERO; 2],
            FixedGainState::OnePoint { position, .. }
            | FixedGainState::Tracking { position, .. } => position,
        }
    }

    fn velocity(&self) -> [S::Speed; 2] {
        match self.state {
            FixedGainState::Tracking { velocity, .. } => velocity,
            _ => [S::Speed::ZERO; 2],
        }
    }

    fn predicted_variance_ratio(&self, _: &Gains<S>, step: &FixedGainStep<S>) -> Option<S::Ratio> {
        self.uncertainty()
            .predicted_variance_ratio(step.interval.seconds())
            .map(S::from_variance)
    }

    fn gate_alpha(&self, gains: &Gains<S>) -> S::Ratio {
        gains.alpha()
    }
}

impl<S: Numeric> FixedGainTrack<S> {
    /// Tenne & Singh eqs. (1)–(2) per axis, through the filter's own
    /// prediction; the position holds before two points.
    fn predict_with(&self, step: &FixedGainStep<S>) -> Result<PredictedState<S>, FilterError> {
        let (position, velocity) = match self.state {
            FixedGainState::Tracking {
                position, velocity, ..
            } => (position, velocity),
            _ => (self.position(), [S::Speed::ZERO; 2]),
        };
        let mut out = PredictedState { position, velocity };
        for (p, v) in out.position.iter_mut().zip(out.velocity.iter_mut()) {
            let axis = KinematicFilter::<S, 2>::from_state(*p, *v, S::Acceleration::ZERO)?;
            let q = axis.predict_terms(step.interval.terms())?;
            *p = q.position;
            *v = q.velocity;
        }
        Ok(out)
    }
}
