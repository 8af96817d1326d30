//! One TCAS cycle put together: the system's state (sensitivity selection
//! with hysteresis, low-altitude inhibits, the active RA) and one intruder's
//! state (range tracker, altitude tracker, threat logic).
//!
//! A cycle, every scan: [`CollisionAvoidance::begin_cycle`] with the own
//! aircraft; for each intruder [`IntruderTrack::scan`] with its reply (or
//! none) and [`IntruderTrack::assess`]; then
//! [`CollisionAvoidance::resolve`] with the geometries of the RA threats.

use super::detection::{Cycle, IntruderObservation, ThreatGeometry, ThreatState, ThreatStatus};
use super::measures::line_miss_distance;
use super::range_tracker::RangeTracker;
use super::resolution::{LowAltitudeInhibits, ResolutionOutput, ResolutionState};
use super::sensitivity::{OwnAircraft, SensitivitySelector};
use super::TcasError;
use crate::filter::altitude::{AltitudeState, AltitudeTrackerConfig, OutOfLine};
use crate::filter::range_azimuth::RangeAzimuthState;
use crate::filter::{FilterError, Phase};
use crate::num::{hypot, Numeric, Scalar};

/// The system-wide state of the collision-avoidance logic, named with a
/// number system `N` and computing in `N::Wide` ([`Numeric::Wide`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CollisionAvoidance<N: Numeric> {
    selector: SensitivitySelector,
    inhibits: LowAltitudeInhibits,
    resolution: ResolutionState<N::Wide>,
}

impl<N: Numeric<Wide = S>, S: Scalar> Default for CollisionAvoidance<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> CollisionAvoidance<N> {
    /// No level selected, no inhibit, no active RA (a `const fn`, for a
    /// `static`).
    pub const fn new() -> Self {
        CollisionAvoidance {
            selector: SensitivitySelector::new(),
            inhibits: LowAltitudeInhibits::new(),
            resolution: ResolutionState::new(),
        }
    }

    /// Starts a cycle: the sensitivity level and layer (with hysteresis)
    /// and the inhibits for the own aircraft; `climb_inhibited` is the
    /// aircraft's performance limit.
    pub fn begin_cycle(
        &mut self,
        own: &OwnAircraft<S>,
        climb_inhibited: bool,
    ) -> Result<Cycle<S>, TcasError> {
        let params = self.selector.select(own)?;
        let inhibits = self.inhibits.update(own.radio_altitude_ft, climb_inhibited);
        Ok(Cycle::new(*own, params, inhibits))
    }

    /// Ends a cycle: the RA against this cycle's RA threats
    /// ([`ResolutionState::resolve`]).
    pub fn resolve(
        &mut self,
        cycle: &Cycle<S>,
        threats: &[ThreatGeometry<S>],
        dt: S,
    ) -> Result<ResolutionOutput<S>, TcasError> {
        self.resolution.resolve(cycle, threats, dt)
    }

    /// Whether an RA is in force.
    pub fn ra_active(&self) -> bool {
        self.resolution.is_active()
    }
}

/// One reply of an intruder: its slant range and, if it reports one, its
/// altitude.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Reply<S> {
    /// Slant range, m.
    pub range_m: S,
    /// Reported pressure altitude, ft (quantised).
    pub altitude_ft: Option<S>,
}

/// One intruder as the TCAS logic keeps it (in `N::Wide`, as
/// [`CollisionAvoidance`]). Its altitude tracker's configuration (the
/// system's, per altitude quantum) is not kept: [`Self::scan`] takes it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct IntruderTrack<N: Numeric> {
    range: RangeTracker<N>,
    altitude: AltitudeState<N>,
    threat: ThreatState<N::Wide>,
}

impl<N: Numeric<Wide = S>, S: Scalar> Default for IntruderTrack<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> IntruderTrack<N> {
    /// A new intruder: empty range and altitude trackers, no advisory.
    pub fn new() -> Self {
        IntruderTrack {
            range: RangeTracker::new(),
            altitude: AltitudeState::new(),
            threat: ThreatState::new(),
        }
    }

    /// The intruder's range tracker (DO-185B, [`RangeTracker`]).
    pub fn range_tracker(&self) -> &RangeTracker<N> {
        &self.range
    }
    /// The state of the intruder's altitude tracker
    /// ([`AltitudeTracker`](crate::filter::altitude::AltitudeTracker)).
    pub fn altitude_state(&self) -> &AltitudeState<N> {
        &self.altitude
    }
    /// The intruder's threat-logic state (advisory ages and hysteresis).
    pub fn threat_state(&self) -> &ThreatState<S> {
        &self.threat
    }

    /// One scan `dt` s after the previous: the reply, or `None` when the
    /// intruder did not answer; `altitude` is the altitude tracker's
    /// configuration for the intruder's quantum, the same at every scan.
    /// A reply either tracker refuses (invalid input, or saturated
    /// arithmetic) is taken as no reply by the trackers that did not take
    /// it: they coast, so that the range and altitude trackers stay in step
    /// (each is all-or-nothing, as the track table's refused updates fall
    /// back to a coast); the first error is returned, to be counted.
    pub fn scan(
        &mut self,
        altitude: &AltitudeTrackerConfig<S>,
        reply: Option<Reply<S>>,
        dt: S,
    ) -> Result<(), FilterError> {
        let mut refused = None;
        let mut reply = reply;
        if reply.is_some_and(|r| r.altitude_ft.is_some_and(|z| !z.is_valid())) {
            refused = Some(FilterError::InvalidMeasurement);
            reply = None;
        }
        if let Some(r) = reply {
            if let Err(e) = self.range.update(r.range_m, dt) {
                refused = Some(e);
                reply = None;
            }
        }
        if reply.is_none() && self.range.phase() != Phase::Empty {
            if let Err(e) = self.range.coast(dt) {
                refused.get_or_insert(e);
            }
        }
        let altitude_ft = reply.and_then(|r| r.altitude_ft);
        if let Err(e) = self.altitude.scan(altitude, altitude_ft, dt) {
            refused.get_or_insert(e);
            if altitude_ft.is_some() {
                // The report refused (a saturation, counted by the
                // tracker): a coast, which may saturate too (counted the
                // same way, the state unchanged).
                let _ = self.altitude.scan(altitude, None, dt);
            }
        }
        refused.map_or(Ok(()), Err)
    }

    /// What the threat logic sees; `None` before the range rate is known.
    /// `bearing_track` is the intruder's range–azimuth track, for the
    /// miss-distance cross-check.
    pub fn observation(
        &self,
        bearing_track: Option<&RangeAzimuthState<S>>,
    ) -> Option<IntruderObservation<S>> {
        let range = self.range.estimate()?;
        let bearing_track = bearing_track.filter(|t| t.phase() == Phase::Tracking);
        let bearing_miss_distance_m =
            bearing_track.and_then(|t| line_miss_distance(t.position(), t.velocity()));
        Some(IntruderObservation {
            range,
            bearing_miss_distance_m,
            bearing_miss_distance_sigma_m: bearing_track.and_then(miss_distance_sigma),
            altitude: self.altitude.estimate(),
            altitude_firmness: self.altitude.firmness(),
        })
    }

    /// This cycle's threat status (`None` before the range rate is known).
    pub fn assess(
        &mut self,
        cycle: &Cycle<S>,
        bearing_track: Option<&RangeAzimuthState<S>>,
        dt: S,
    ) -> Result<Option<ThreatStatus<S>>, TcasError> {
        match self.observation(bearing_track) {
            None => Ok(None),
            Some(o) => self.threat.assess(cycle, &o, dt).map(Some),
        }
    }
}

/// The standard deviation of a bearing track's straight-line miss
/// distance, m: its cross-range position σ combined with the cross-range
/// velocity σ carried over the time to go r/|v| (the miss distance is the
/// cross-range offset at closest approach; US patent 5,566,074 uses a
/// bearing-based miss distance with its uncertainty). `None` at zero speed.
fn miss_distance_sigma<S: Scalar>(track: &RangeAzimuthState<S>) -> Option<S> {
    let [vx, vy] = track.velocity();
    let speed = hypot(vx, vy);
    if !(speed.is_valid() && speed > S::ZERO) {
        return None;
    }
    let across = track.cross_range_covariance();
    let time_to_go = track.range().over(speed);
    let sigma = hypot(across.a, time_to_go.times(hypot(across.b, across.c)));
    sigma.is_valid().then_some(sigma)
}
