//! What the track table needs from a filter ([`TrackFilter`]), the
//! measurements it feeds it ([`Measurement`], [`Observation`]), and the
//! implementation for the fixed-gain Cartesian αβ filter ([`FixedGainTrack`]).

use super::gate::{hypot, Gate, GateRegion};
use crate::filter::{Cartesian, FilterError, Gains, UpdateOutcome};
use crate::num::Scalar;

/// One detection of one scan, as the sensor reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Measurement<S> {
    /// Position in the tracking plane (m).
    Cartesian { x: S, y: S },
    /// Range (m, ≥ 0) and azimuth (rad, clockwise from the +y axis) from a
    /// sensor at the origin; projected as x = R·sin B, y = R·cos B
    /// (He, Peng, Ling & Quan, §2).
    Polar { range: S, azimuth: S },
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
    /// It won its track's gate, but the filter refused the update (the
    /// arithmetic saturated); the track coasted instead.
    FilterRefused,
}

/// A validated measurement with its Cartesian projection, computed once.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Observation<S> {
    measurement: Measurement<S>,
    xy: [S; 2],
}

impl<S: Scalar> Observation<S> {
    /// Checks the measurement and projects it to x, y.
    pub fn new(measurement: Measurement<S>) -> Result<Self, RejectReason> {
        let xy = match measurement {
            Measurement::Cartesian { x, y } => [x, y],
            Measurement::Polar { range, azimuth } => {
                if !(range.is_valid() && azimuth.is_valid()) {
                    return Err(RejectReason::NotFinite);
                }
                if range < S::ZERO {
                    return Err(RejectReason::NegativeRange);
                }
                let (sin_b, cos_b) = azimuth.sin_cos();
                [range * sin_b, range * cos_b]
            }
        };
        if !(xy[0].is_valid() && xy[1].is_valid()) {
            return Err(RejectReason::NotFinite);
        }
        Ok(Observation { measurement, xy })
    }

    pub fn measurement(&self) -> Measurement<S> {
        self.measurement
    }

    /// Cartesian position (m).
    pub fn xy(&self) -> [S; 2] {
        self.xy
    }
}

/// A track's state predicted to the scan time, without changing it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PredictedState<S> {
    pub position: [S; 2],
    pub velocity: [S; 2],
}

/// What a filter must provide to live in a [`TrackTable`](super::TrackTable).
///
/// The implementing type is the whole per-track estimator state: for a filter
/// driven by a gain schedule, the filter *and* the schedule's per-track state
/// (update count, innovation window, ...) in one `Copy` record, e.g.
/// `struct Scheduled { filter: Cartesian<S, 2, 2>, schedule: G::State,
/// uncertainty: Uncertainty<S> }`. Everything shared by all tracks (fixed
/// gains, schedule constants, noise figures) is [`Self::Params`], stored once
/// in the [`TrackerConfig`](super::TrackerConfig) and passed to every call,
/// so it costs no bytes per track.
///
/// Contract (as for [`crate::filter`]): `dt` is the time since the previous
/// `update` or `coast`, in seconds, > 0. An `Err` leaves the state untouched.
pub trait TrackFilter<S: Scalar>: Copy {
    /// Configuration shared by every track.
    type Params: Copy;

    /// A filter that has seen no measurement.
    fn empty(params: &Self::Params) -> Self;

    /// Incorporates a measurement taken `dt` after the previous call. The
    /// table initiates tracks by two updates on an empty filter (two-point
    /// initialisation, Al-Wagih & Abdulla eqs. 9–10).
    fn update(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        dt: S,
    ) -> Result<(), FilterError>;

    /// No measurement this scan: advance by `dt`.
    fn coast(&mut self, params: &Self::Params, dt: S) -> Result<(), FilterError>;

    /// The state `dt` ahead, without changing the filter.
    fn predict(&self, params: &Self::Params, dt: S) -> Result<PredictedState<S>, FilterError>;

    /// Smoothed position (m).
    fn position(&self) -> [S; 2];

    /// Smoothed velocity (m/s).
    fn velocity(&self) -> [S; 2];

    /// Variance of the position predicted `dt` ahead, per axis, in units of
    /// the measurement noise variance (1 = as uncertain as one measurement).
    /// `None` if unknown (before two measurements).
    fn predicted_variance_ratio(&self, params: &Self::Params, dt: S) -> Option<S>;

    /// The position gain α the next update will use (Li et al.'s wave gate
    /// scales by λ = √α, eq. 12).
    fn gate_alpha(&self, params: &Self::Params) -> S;

    /// This track's validation region for a scan `dt` ahead whose predicted
    /// state is `predicted`; `None` if no region can be formed (the track then
    /// gets no measurement and coasts).
    ///
    /// The default builds the Cartesian circle described on [`Gate`]. A
    /// filter that gates differently (range/azimuth windows) overrides it.
    fn gate_region(
        &self,
        params: &Self::Params,
        predicted: &PredictedState<S>,
        dt: S,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        let radius = match *gate {
            Gate::Uncertainty {
                measurement_sigma,
                threshold,
                max_acceleration,
            } => {
                let p = self.predicted_variance_ratio(params, dt)?;
                let half = S::from_f64_lossy(0.5);
                measurement_sigma * (threshold * (p + S::ONE)).sqrt()
                    + half * max_acceleration * dt * dt
            }
            Gate::Wave {
                range_sigma,
                bearing_sigma,
                multiple,
            } => {
                // Li et al. eqs. (11)–(12): Δd = λ·√(Δρ² + ρ²Δθ²), λ = √α.
                let rho = hypot(predicted.position[0], predicted.position[1]);
                let lambda = self.gate_alpha(params).sqrt();
                multiple * lambda * hypot(range_sigma, rho * bearing_sigma)
            }
        };
        GateRegion::circle(predicted.position, radius)
    }
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
pub struct ErrorVariance<S> {
    pub p11: S,
    pub p12: S,
    pub p22: S,
}

impl<S: Scalar> ErrorVariance<S> {
    /// After two-point initialisation over interval T (Al-Wagih eq. 9):
    /// x = z₂ (variance 1), v = (z₂ − z₁)/T (variance 2/T²), and
    /// cov(z₂, (z₂ − z₁)/T) = 1/T.
    pub fn after_two_points(interval: S) -> Self {
        let inv = S::ONE / interval;
        ErrorVariance {
            p11: S::ONE,
            p12: inv,
            p22: (S::ONE + S::ONE) * inv * inv,
        }
    }

    /// Propagated over `dt` by Φ = [[1, T], [0, 1]]: P⁻ = Φ·P·Φᵀ.
    pub fn predicted(&self, dt: S) -> Self {
        let two = S::ONE + S::ONE;
        ErrorVariance {
            p11: self.p11 + dt * (two * self.p12 + dt * self.p22),
            p12: self.p12 + dt * self.p22,
            p22: self.p22,
        }
    }

    /// `self` is the prediction P⁻; the update with gain K = [α, β/T]ᵀ
    /// (Al-Wagih eqs. 6 and 8), in Joseph form, which holds for any gain:
    /// P = (I − KH)·P⁻·(I − KH)ᵀ + K·Kᵀ (R = 1 in these units).
    pub fn updated(&self, alpha: S, beta: S, dt: S) -> Self {
        let k1 = alpha;
        let k2 = beta / dt;
        let one_minus = S::ONE - k1;
        let two = S::ONE + S::ONE;
        ErrorVariance {
            p11: one_minus * one_minus * self.p11 + k1 * k1,
            p12: one_minus * (self.p12 - k2 * self.p11) + k1 * k2,
            p22: self.p22 - two * k2 * self.p12 + k2 * k2 * (self.p11 + S::ONE),
        }
    }

    pub fn is_valid(&self) -> bool {
        self.p11.is_valid() && self.p12.is_valid() && self.p22.is_valid()
    }
}

/// The estimation-error bookkeeping that goes with a two-point-initialised
/// αβ filter: nothing, one point (and the time since), or a covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Uncertainty<S> {
    Empty,
    OnePoint { elapsed: S },
    Tracking(ErrorVariance<S>),
}

impl<S: Scalar> Uncertainty<S> {
    /// The bookkeeping after an update that produced `outcome` with gains
    /// (α, β) over `dt`; `None` if it left the representable range.
    pub fn after_update(
        &self,
        outcome: &UpdateOutcome<S>,
        alpha: S,
        beta: S,
        dt: S,
    ) -> Option<Self> {
        let next = match (outcome, self) {
            (UpdateOutcome::FirstPoint, _) => Uncertainty::OnePoint { elapsed: S::ZERO },
            (UpdateOutcome::SecondPoint, Uncertainty::OnePoint { elapsed }) => {
                Uncertainty::Tracking(ErrorVariance::after_two_points(*elapsed + dt))
            }
            (UpdateOutcome::SecondPoint, _) => {
                Uncertainty::Tracking(ErrorVariance::after_two_points(dt))
            }
            (UpdateOutcome::Filtered(_), Uncertainty::Tracking(p)) => {
                Uncertainty::Tracking(p.predicted(dt).updated(alpha, beta, dt))
            }
            // A filtered update without a covariance (a filter started with
            // `from_state`): start from the two-point covariance.
            (UpdateOutcome::Filtered(_), _) => Uncertainty::Tracking(
                ErrorVariance::after_two_points(dt)
                    .predicted(dt)
                    .updated(alpha, beta, dt),
            ),
        };
        next.is_valid().then_some(next)
    }

    /// The bookkeeping after coasting `dt`.
    pub fn after_coast(&self, dt: S) -> Option<Self> {
        let next = match self {
            Uncertainty::Empty => Uncertainty::Empty,
            Uncertainty::OnePoint { elapsed } => Uncertainty::OnePoint {
                elapsed: *elapsed + dt,
            },
            Uncertainty::Tracking(p) => Uncertainty::Tracking(p.predicted(dt)),
        };
        next.is_valid().then_some(next)
    }

    /// Predicted position variance ratio `dt` ahead (see
    /// [`TrackFilter::predicted_variance_ratio`]).
    pub fn predicted_variance_ratio(&self, dt: S) -> Option<S> {
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

/// The crate's 2-D αβ filter ([`Cartesian<S, 2, 2>`]) with one fixed set of
/// gains for every track (`Params = Gains<S>`), plus the error covariance
/// that sizes its gate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedGainTrack<S: Scalar> {
    filter: Cartesian<S, 2, 2>,
    uncertainty: Uncertainty<S>,
}

impl<S: Scalar> FixedGainTrack<S> {
    pub fn filter(&self) -> &Cartesian<S, 2, 2> {
        &self.filter
    }
    pub fn uncertainty(&self) -> &Uncertainty<S> {
        &self.uncertainty
    }
}

impl<S: Scalar> TrackFilter<S> for FixedGainTrack<S> {
    type Params = Gains<S>;

    fn empty(_: &Gains<S>) -> Self {
        FixedGainTrack {
            filter: Cartesian::new(),
            uncertainty: Uncertainty::Empty,
        }
    }

    fn update(&mut self, gains: &Gains<S>, z: &Observation<S>, dt: S) -> Result<(), FilterError> {
        let mut filter = self.filter;
        let outcome = match filter.update(z.xy(), dt, gains) {
            Ok(outcome) => outcome,
            Err(e) => {
                // A refused update leaves the filter as it was but for the
                // saturation it counted: keep that count.
                self.filter = filter;
                return Err(e);
            }
        };
        // Both axes pass through the same phases, so axis 0 speaks for both.
        let uncertainty = self
            .uncertainty
            .after_update(&outcome[0], gains.alpha(), gains.beta(), dt)
            .ok_or(FilterError::Saturated)?;
        self.filter = filter;
        self.uncertainty = uncertainty;
        Ok(())
    }

    fn coast(&mut self, _: &Gains<S>, dt: S) -> Result<(), FilterError> {
        let mut filter = self.filter;
        if let Err(e) = filter.coast(dt) {
            self.filter = filter; // unchanged but for the saturation count
            return Err(e);
        }
        let uncertainty = self
            .uncertainty
            .after_coast(dt)
            .ok_or(FilterError::Saturated)?;
        self.filter = filter;
        self.uncertainty = uncertainty;
        Ok(())
    }

    fn predict(&self, _: &Gains<S>, dt: S) -> Result<PredictedState<S>, FilterError> {
        let [px, py] = self.filter.predict(dt)?;
        Ok(PredictedState {
            position: [px.position, py.position],
            velocity: [px.velocity, py.velocity],
        })
    }

    fn position(&self) -> [S; 2] {
        self.filter.position()
    }

    fn velocity(&self) -> [S; 2] {
        self.filter.velocity()
    }

    fn predicted_variance_ratio(&self, _: &Gains<S>, dt: S) -> Option<S> {
        self.uncertainty.predicted_variance_ratio(dt)
    }

    fn gate_alpha(&self, gains: &Gains<S>) -> S {
        gains.alpha()
    }
}
