//! TCAS II collision-avoidance logic, version 7.1 as published: threat
//! measures, sensitivity levels, the range tracker, threat detection and
//! resolution advisories, written from the public sources and cited per
//! rule in each submodule:
//!
//! * FAA, "Introduction to TCAS II Version 7.1", 2011 (the booklet);
//! * NASA DAIDALUS, `C++/src/TCAS2D.cpp`, `TCAS3D.cpp`, `TCASTable.cpp`
//!   (RA detection with the HMD filter; Muñoz, Narkawicz & Chamberlain,
//!   "A TCAS-II Resolution Advisory Detection Algorithm", AIAA GNC 2013);
//! * ledieuke/tcas_simulator, an unofficial transcription of RTCA DO-185B
//!   (`tracking.py`, `tracking_intruders.py`, `detect.py`,
//!   `tcasConstant.py`): trackers, detection details and constants;
//! * FlightGear `src/Instrumentation/tcas.cxx` (a simplified v7 emulation:
//!   RA sense and crossing).
//!
//! docs/tcas.md says which source each rule follows, where they disagree,
//! and what is not modelled (coordination with another TCAS aircraft among
//! it).
//!
//! # Units
//!
//! Horizontal quantities are metres and seconds (range m, range rate m/s);
//! vertical ones feet and ft/s, as transponders report altitude. Tables in
//! NM, ft and s are converted with the constants below. No square of a
//! range is formed (Q32.32's range is ±2.1·10⁹): τ ≤ TAU tests are decided
//! as products, and DMOD²/r as DMOD·(DMOD/r).
//!
//! # Layers
//!
//! [`RangeTracker`] and [`crate::filter::altitude::AltitudeTracker`] track
//! one intruder; [`ThreatState::assess`] decides its advisory level;
//! [`ResolutionState::resolve`] turns the RA threats into one RA;
//! [`CollisionAvoidance`] and [`IntruderTrack`] put a cycle together.
//! [`assess`] is the stateless assessment of a relative state vector (no
//! firmness, no hysteresis), for tools and the scan loop.

use crate::filter::altitude::AltitudeEstimate;
use crate::filter::range_azimuth::RangeAzimuthState;
use crate::num::Scalar;
use detection::RangeGeometry;
use measures::RelativeRange;

pub mod detection;
mod held;
pub mod logic;
pub mod measures;
pub mod range_tracker;
pub mod resolution;
pub mod sensitivity;

pub use detection::{
    Cycle, IntruderObservation, MissDistanceFilter, ThreatGeometry, ThreatState, ThreatStatus,
    VerticalMeasures,
};
pub use logic::{CollisionAvoidance, IntruderTrack, Reply};
pub use measures::{
    closest_approach, line_miss_distance, modified_tau, range_tau, vertical_tau, ClosestApproach,
};
pub use range_tracker::{RangeEstimate, RangeTracker};
pub use resolution::{
    Inhibits, LowAltitudeInhibits, RaSense, RaStrength, ResolutionAdvisory, ResolutionOutput,
    ResolutionState,
};
pub use sensitivity::{
    parameters, sensitivity, AlertThresholds, AltitudeLayer, OwnAircraft, ResolutionLimits,
    SensitivityLevel, SensitivityParameters, SensitivitySelector, SENSITIVITY_TABLE,
    SL3_RADIO_ALTITUDE_FT, SL4_RADIO_ALTITUDE_FT, SL5_PRESSURE_ALTITUDE_FT,
    SL6_PRESSURE_ALTITUDE_FT, SL7_HIGH_PRESSURE_ALTITUDE_FT, SL7_PRESSURE_ALTITUDE_FT,
};

/// Metres per international nautical mile.
pub const METRES_PER_NAUTICAL_MILE: f64 = 1852.0;
/// Metres per international foot.
pub const METRES_PER_FOOT: f64 = 0.3048;
/// Metres per second per knot (1 NM/h).
pub const METRES_PER_SECOND_PER_KNOT: f64 = METRES_PER_NAUTICAL_MILE / 3600.0;
/// Floor on the closure speed used in range tau and modified tau, and the
/// range rate above which an intruder is diverging (no tau), ft/s (DO-185B
/// `RDTHR`: one threshold for both).
pub const CLOSURE_RATE_FLOOR_FT_PER_S: f64 = 10.0;
/// The same floor in m/s.
pub const CLOSURE_RATE_FLOOR_M_PER_S: f64 = CLOSURE_RATE_FLOOR_FT_PER_S * METRES_PER_FOOT;
/// The largest closure speed TCAS II surveillance is designed for, kt
/// (FAA booklet, "Surveillance": closure rates up to 1200 kt): the bound
/// on an intruder's speed relative to the own aircraft given to the
/// bearing tracker ([`crate::filter::range_azimuth::RangeAzimuthNoise::with_speed_bound`]).
pub const MAX_CLOSURE_SPEED_KT: f64 = 1200.0;
/// The same in m/s.
pub const MAX_CLOSURE_SPEED_M_PER_S: f64 = MAX_CLOSURE_SPEED_KT * METRES_PER_SECOND_PER_KNOT;
/// Proximate traffic: within this range, NM … (DO-185B `PROXR`)
pub const PROXIMATE_RANGE_NM: f64 = 6.0;
/// … and within this relative altitude, ft (DO-185B `PROXA`).
pub const PROXIMATE_ALTITUDE_FT: f64 = 1200.0;

/// Why an assessment was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TcasError {
    /// An input is NaN, infinite or a saturated fixed-point value, or a
    /// range or interval is negative.
    InvalidInput,
    /// An intermediate left the representable range.
    Saturated,
}

impl core::fmt::Display for TcasError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            TcasError::InvalidInput => "threat assessment input is not a valid number",
            TcasError::Saturated => "threat assessment overflowed the number format",
        })
    }
}

impl core::error::Error for TcasError {}

/// An intruder as the threat logic sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Intruder<S> {
    /// Horizontal position relative to the own aircraft, m.
    pub relative_position_m: [S; 2],
    /// Horizontal velocity relative to the own aircraft, m/s.
    pub relative_velocity_m_per_s: [S; 2],
    /// Tracked pressure altitude and vertical rate; `None` for an intruder
    /// that does not report altitude.
    pub altitude: Option<AltitudeEstimate<S>>,
}

impl<S: Scalar> Intruder<S> {
    /// From a range–azimuth track (its x/y state is already relative to the
    /// own aircraft) and the intruder's altitude track.
    pub fn from_track(track: &RangeAzimuthState<S>, altitude: Option<AltitudeEstimate<S>>) -> Self {
        Intruder {
            relative_position_m: track.position(),
            relative_velocity_m_per_s: track.velocity(),
            altitude,
        }
    }
}

/// Advisory level, ordered by severity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Advisory {
    /// Other traffic: outside the proximate volume and no advisory (booklet,
    /// "Traffic Display").
    None,
    /// Within 6 NM and ±1200 ft.
    ProximateTraffic,
    /// Traffic advisory.
    Traffic,
    /// Resolution advisory (level only: the climb/descend sense is not
    /// chosen here).
    Resolution,
}

impl Advisory {
    /// Short name for reports: none, proximate, ta, ra.
    pub const fn name(self) -> &'static str {
        match self {
            Advisory::None => "none",
            Advisory::ProximateTraffic => "proximate",
            Advisory::Traffic => "ta",
            Advisory::Resolution => "ra",
        }
    }
}

/// Everything the stateless assessment computed for one intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatAssessment<S> {
    /// The sensitivity level the thresholds were taken at (booklet Table 3).
    pub sensitivity: SensitivityLevel,
    /// Horizontal range, m.
    pub range_m: S,
    /// Range rate, m/s (negative closing).
    pub range_rate_m_per_s: S,
    /// Range tau, s ([`range_tau`]).
    pub range_tau_s: Option<S>,
    /// Modified tau with the TA DMOD, s ([`modified_tau`]).
    pub ta_modified_tau_s: Option<S>,
    /// Modified tau with the RA DMOD, s; `None` also at SL 2.
    pub ra_modified_tau_s: Option<S>,
    /// Closest point of approach ([`closest_approach`]).
    pub closest_approach: Option<ClosestApproach<S>>,
    /// `None` for a non-altitude-reporting intruder.
    pub vertical: Option<VerticalMeasures<S>>,
    /// The RA range test passed and the HMD filter removed it.
    pub miss_distance_filtered: bool,
    /// The advisory level issued for this intruder (booklet, "CAS Logic
    /// Functions").
    pub advisory: Advisory,
}

/// Assesses one intruder from its relative state, without memory: the
/// band's sensitivity level (no hysteresis), the detection tests of
/// [`ThreatState`] for a new intruder (no TA hysteresis, no minimum TA
/// time, no firmness gate), and the HMD filter on the straight-line miss
/// distance d_cpa of [`closest_approach`] (DAIDALUS `TCAS3D::TCASII_RA`
/// uses the same state-vector form). The cycle is [`stateless_cycle`];
/// with many intruders, form it once and call [`assess_in`].
pub fn assess<S: Scalar>(
    own: &OwnAircraft<S>,
    intruder: &Intruder<S>,
) -> Result<ThreatAssessment<S>, TcasError> {
    assess_in(&stateless_cycle(own)?, intruder)
}

/// The cycle of [`assess`] for the own aircraft `own`: the band's
/// sensitivity level ([`sensitivity()`], no hysteresis) and no low-altitude
/// inhibit history.
pub fn stateless_cycle<S: Scalar>(own: &OwnAircraft<S>) -> Result<Cycle<S>, TcasError> {
    Ok(Cycle::new(
        *own,
        sensitivity(own)?,
        LowAltitudeInhibits::new().update(own.radio_altitude_ft, false),
    ))
}

/// [`assess`] of one intruder in a cycle formed once for all of them
/// ([`stateless_cycle`], or [`CollisionAvoidance::begin_cycle`]'s, whose
/// hysteresis then applies to the level).
pub fn assess_in<S: Scalar>(
    cycle: &Cycle<S>,
    intruder: &Intruder<S>,
) -> Result<ThreatAssessment<S>, TcasError> {
    // Chained rather than `?`, which copies the relative state through
    // memcpy in the wide formats.
    relative_state(intruder).and_then(|(relative, closest)| {
        let (range, range_rate) = (relative.range_m, relative.range_rate_m_per_s);
        let mut geometry = RangeGeometry::new(range, range_rate, cycle.thresholds());
        let status = ThreatState::new().assess_state(
            cycle,
            &mut geometry,
            closest.map(|c| c.distance_m),
            intruder.altitude,
            None,
        )?;
        // The taus of the report from the quotients the tests formed: none
        // while the intruder diverges (as `range_tau`), except τ_mod = 0
        // inside DMOD.
        let diverging = geometry.diverging();
        let (ta_dmod_m, ra_dmod_m) = cycle.thresholds().dmod_m();
        let modified_tau = |g: &mut RangeGeometry<S>, dmod_m: S, ra: bool| {
            if range <= dmod_m {
                Ok(Some(S::ZERO))
            } else if diverging {
                Ok(None)
            } else if ra {
                measures::valid_result(g.ra_modified_tau(dmod_m)).map(Some)
            } else {
                measures::valid_result(g.modified_tau(dmod_m)).map(Some)
            }
        };
        Ok(ThreatAssessment {
            sensitivity: cycle.params().level,
            range_m: range,
            range_rate_m_per_s: range_rate,
            range_tau_s: if diverging {
                None
            } else {
                Some(measures::valid_result(geometry.range_tau())?)
            },
            ta_modified_tau_s: modified_tau(&mut geometry, ta_dmod_m, false)?,
            ra_modified_tau_s: match ra_dmod_m {
                Some(dmod_m) => modified_tau(&mut geometry, dmod_m, true)?,
                None => None,
            },
            closest_approach: closest,
            vertical: status.vertical,
            miss_distance_filtered: status.miss_distance_filtered,
            advisory: status.advisory,
        })
    })
}

/// The range, range rate and closest approach of a relative state vector.
fn relative_state<S: Scalar>(
    intruder: &Intruder<S>,
) -> Result<(RelativeRange<S>, Option<ClosestApproach<S>>), TcasError> {
    let relative = RelativeRange::new(
        intruder.relative_position_m,
        intruder.relative_velocity_m_per_s,
    )?;
    let closest = relative.closest_approach(intruder.relative_velocity_m_per_s)?;
    Ok((relative, closest))
}

impl<S: Scalar> ThreatState<S> {
    /// [`assess_in`]'s tests with this intruder's memory, `dt` s after the
    /// previous cycle: TA hysteresis and minimum time, the continuing RA
    /// threat and its tau cap, the miss-distance filter's count (the HMD
    /// is the state vector's straight-line d_cpa). The status carries the
    /// RA geometry for [`CollisionAvoidance::resolve`]; for tools that
    /// have a state vector rather than the TCAS trackers (`replay`).
    pub fn assess_intruder(
        &mut self,
        cycle: &Cycle<S>,
        intruder: &Intruder<S>,
        dt: S,
    ) -> Result<ThreatStatus<S>, TcasError> {
        if !(dt.is_valid() && dt > S::ZERO) {
            return Err(TcasError::InvalidInput);
        }
        let (relative, closest) = relative_state(intruder)?;
        let mut geometry = RangeGeometry::new(
            relative.range_m,
            relative.range_rate_m_per_s,
            cycle.thresholds(),
        );
        self.assess_state(
            cycle,
            &mut geometry,
            closest.map(|c| c.distance_m),
            intruder.altitude,
            Some(dt),
        )
    }
}
