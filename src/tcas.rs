//! Threat assessment for a collision-avoidance unit: range tau, modified
//! tau, closest point of approach, vertical tau, sensitivity levels and the
//! advisory level per intruder, following the public description of the
//! TCAS II version 7.1 logic (FAA, "Introduction to TCAS II Version 7.1",
//! 2011; the RA detection model of Muñoz, Narkawicz & Chamberlain, "A
//! TCAS-II Resolution Advisory Detection Algorithm", AIAA GNC 2013).
//!
//! # Units
//!
//! Horizontal quantities are metres and seconds, as the filters give them
//! (relative position m, relative velocity m/s, range rate m/s). Vertical
//! quantities are feet and ft/s, as transponders report altitude and
//! [`crate::filter::altitude`] tracks it. The TCAS tables are in NM, ft and
//! s; they are converted with the named constants below where they meet a
//! horizontal quantity. Times are seconds.
//!
//! # Threat measures
//!
//! * **Range tau** τ = −r/ṙ: time to collision if the range kept closing at
//!   the current rate.
//! * **Modified tau** τ_mod = (DMOD² − r²)/(r·ṙ), which is 0 when r ≤ DMOD:
//!   range tau shortened so that a slowly closing intruder alerts when it is
//!   about to come within DMOD (for ṙ < 0 and r > DMOD it is positive). It is
//!   computed as (r − DMOD·(DMOD/r))/(−ṙ) so no r² (up to 10¹¹ m² at 400 km,
//!   beyond Q32.32) is formed.
//! * **Closure-rate floor.** Both taus divide by the closure speed −ṙ. For an
//!   intruder that is not diverging (ṙ ≤ 0) the closure speed used is
//!   max(−ṙ, 10 ft/s) ([`CLOSURE_RATE_FLOOR_M_PER_S`] = 3.048 m/s): a
//!   co-moving or barely closing intruder gets a large but finite tau instead
//!   of a division by (nearly) zero, and still alerts as it creeps up to DMOD
//!   (τ_mod ≤ TAU once r − DMOD²/r ≤ TAU·10 ft/s). A diverging intruder
//!   (ṙ > 0) has no tau ([`None`]); its modified tau is 0 inside DMOD and
//!   [`None`] outside, so it can alert only while within DMOD. The floor
//!   never applies to closures faster than 10 ft/s (6 kt).
//! * **Closest point of approach** of the straight relative track, from now
//!   on: t_cpa = max(0, −(p·v)/|v|²), d_cpa = |p + v·t_cpa|, evaluated as
//!   r·|sin θ| (θ between p and v) so nothing of size r² appears; with no
//!   relative motion the range stays r (t_cpa = 0, d_cpa = r).
//! * **Vertical tau** τ_v = −h/ḣ for relative altitude h (intruder minus
//!   own, ft) and relative vertical rate ḣ, when the two are converging
//!   (h·ḣ < 0); 0 at co-altitude; [`None`] when not converging.
//!
//! # Advisory level
//!
//! With the thresholds of the own aircraft's sensitivity level
//! ([`SensitivityParameters`]):
//!
//! * range test: r ≤ DMOD, or not diverging and τ_mod ≤ TAU;
//! * vertical test (Muñoz et al.): |h| ≤ ZTHR, or converging with τ_v ≤ TAU;
//! * **resolution advisory**: the RA range and vertical tests pass, the
//!   level has RAs (not SL 2) and the intruder reports altitude;
//! * **traffic advisory**: the TA range test passes and the TA vertical test
//!   passes, or the intruder does not report altitude (TCAS issues TAs, never
//!   RAs, against non-altitude-reporting intruders);
//! * **proximate traffic**: within 6 NM and ±1200 ft (a non-reporting
//!   intruder within 6 NM counts as proximate: its altitude is unknown);
//! * otherwise none.
//!
//! The tests compare τ ≤ TAU as products (|h| ≤ TAU·|ḣ|, r − DMOD²/r ≤
//! TAU·closure) so the decision never depends on a quotient that a slow
//! closure could push out of range.
//!
//! Not modelled (out of scope here): the RA sense and strength, the
//! horizontal miss distance filter, sensitivity-level hysteresis, altitude
//! inhibits near the ground, coordination, and multi-threat logic.

use crate::filter::altitude::AltitudeEstimate;
use crate::filter::range_azimuth::{hypot, RangeAzimuthFilter};
use crate::num::Scalar;

/// Metres per international nautical mile.
pub const METRES_PER_NAUTICAL_MILE: f64 = 1852.0;
/// Metres per international foot.
pub const METRES_PER_FOOT: f64 = 0.3048;
/// Metres per second per knot (1 NM/h).
pub const METRES_PER_SECOND_PER_KNOT: f64 = METRES_PER_NAUTICAL_MILE / 3600.0;
/// Floor on the closure speed used in range tau and modified tau, ft/s.
pub const CLOSURE_RATE_FLOOR_FT_PER_S: f64 = 10.0;
/// The same floor in m/s.
pub const CLOSURE_RATE_FLOOR_M_PER_S: f64 = CLOSURE_RATE_FLOOR_FT_PER_S * METRES_PER_FOOT;
/// Proximate traffic: within this range, NM …
pub const PROXIMATE_RANGE_NM: f64 = 6.0;
/// … and within this relative altitude, ft.
pub const PROXIMATE_ALTITUDE_FT: f64 = 1200.0;

/// Why an assessment was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TcasError {
    /// An input is NaN, infinite or a saturated fixed-point value, or a
    /// range is negative.
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

/// TCAS II sensitivity level (2–7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SensitivityLevel {
    Sl2 = 2,
    Sl3 = 3,
    Sl4 = 4,
    Sl5 = 5,
    Sl6 = 6,
    Sl7 = 7,
}

impl SensitivityLevel {
    /// The level's number, 2–7.
    pub const fn number(self) -> u8 {
        self as u8
    }
}

/// The thresholds of one alert type at one sensitivity level.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AlertThresholds {
    /// TAU, s.
    pub tau_s: f64,
    /// DMOD, NM.
    pub dmod_nm: f64,
    /// ZTHR, ft.
    pub zthr_ft: f64,
}

impl AlertThresholds {
    /// DMOD in metres.
    pub fn dmod_m(&self) -> f64 {
        self.dmod_nm * METRES_PER_NAUTICAL_MILE
    }
}

/// One row of the sensitivity level table.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensitivityParameters {
    pub level: SensitivityLevel,
    /// Traffic advisory thresholds.
    pub ta: AlertThresholds,
    /// Resolution advisory thresholds; `None` at SL 2 (TA only).
    pub ra: Option<AlertThresholds>,
    /// ALIM, ft: the vertical separation an RA aims for (carried for the RA
    /// sense logic, which is out of scope here); `None` at SL 2.
    pub alim_ft: Option<f64>,
}

// One argument per column of the table, in the order, so the rows
// below read like the table.
#[allow(clippy::too_many_arguments)]
const fn row(
    level: SensitivityLevel,
    ta_tau: f64,
    ra_tau: f64,
    ta_dmod: f64,
    ra_dmod: f64,
    ta_zthr: f64,
    ra_zthr: f64,
    alim: f64,
) -> SensitivityParameters {
    SensitivityParameters {
        level,
        ta: AlertThresholds {
            tau_s: ta_tau,
            dmod_nm: ta_dmod,
            zthr_ft: ta_zthr,
        },
        ra: Some(AlertThresholds {
            tau_s: ra_tau,
            dmod_nm: ra_dmod,
            zthr_ft: ra_zthr,
        }),
        alim_ft: Some(alim),
    }
}

/// The sensitivity level table of issue 4 (TCAS II v7.1), one row per own
/// altitude band, in order:
///
/// | own altitude (ft) | SL | TA tau | RA tau | TA DMOD | RA DMOD | TA ZTHR | RA ZTHR | ALIM |
/// |---|---|---|---|---|---|---|---|---|
/// | < 1000 AGL | 2 | 20 | – | 0.30 | – | 850 | – | – |
/// | 1000–2350 AGL | 3 | 25 | 15 | 0.33 | 0.20 | 850 | 600 | 300 |
/// | 2350–5000 | 4 | 30 | 20 | 0.48 | 0.35 | 850 | 600 | 300 |
/// | 5000–10000 | 5 | 40 | 25 | 0.75 | 0.55 | 850 | 600 | 350 |
/// | 10000–20000 | 6 | 45 | 30 | 1.00 | 0.80 | 850 | 600 | 400 |
/// | 20000–42000 | 7 | 48 | 35 | 1.30 | 1.10 | 850 | 700 | 600 |
/// | above 42000 | 7 | 48 | 35 | 1.30 | 1.10 | 1200 | 800 | 700 |
///
/// (tau s, DMOD NM, ZTHR and ALIM ft).
pub const SENSITIVITY_TABLE: [SensitivityParameters; 7] = [
    SensitivityParameters {
        level: SensitivityLevel::Sl2,
        ta: AlertThresholds {
            tau_s: 20.0,
            dmod_nm: 0.30,
            zthr_ft: 850.0,
        },
        ra: None,
        alim_ft: None,
    },
    row(
        SensitivityLevel::Sl3,
        25.0,
        15.0,
        0.33,
        0.20,
        850.0,
        600.0,
        300.0,
    ),
    row(
        SensitivityLevel::Sl4,
        30.0,
        20.0,
        0.48,
        0.35,
        850.0,
        600.0,
        300.0,
    ),
    row(
        SensitivityLevel::Sl5,
        40.0,
        25.0,
        0.75,
        0.55,
        850.0,
        600.0,
        350.0,
    ),
    row(
        SensitivityLevel::Sl6,
        45.0,
        30.0,
        1.00,
        0.80,
        850.0,
        600.0,
        400.0,
    ),
    row(
        SensitivityLevel::Sl7,
        48.0,
        35.0,
        1.30,
        1.10,
        850.0,
        700.0,
        600.0,
    ),
    row(
        SensitivityLevel::Sl7,
        48.0,
        35.0,
        1.30,
        1.10,
        1200.0,
        800.0,
        700.0,
    ),
];

/// Lower bounds of the table's bands, ft: radio altitude for the first two
/// (AGL), pressure altitude for the rest.
pub const SL3_RADIO_ALTITUDE_FT: f64 = 1000.0;
pub const SL4_RADIO_ALTITUDE_FT: f64 = 2350.0;
pub const SL5_PRESSURE_ALTITUDE_FT: f64 = 5000.0;
pub const SL6_PRESSURE_ALTITUDE_FT: f64 = 10000.0;
pub const SL7_PRESSURE_ALTITUDE_FT: f64 = 20000.0;
pub const SL7_HIGH_PRESSURE_ALTITUDE_FT: f64 = 42000.0;

/// The own aircraft.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct OwnAircraft<S> {
    /// Pressure altitude, ft.
    pub pressure_altitude_ft: S,
    /// Vertical rate, ft/s (positive climbing).
    pub vertical_rate_ft_per_s: S,
    /// Radio (height above ground) altitude, ft; `None` when not available
    /// or above the radio altimeter's range.
    pub radio_altitude_ft: Option<S>,
}

impl<S: Scalar> OwnAircraft<S> {
    /// An own aircraft over terrain at sea level: the pressure altitude is
    /// also the height above ground (for tools given a single altitude).
    pub fn over_sea_level(altitude_ft: S, vertical_rate_ft_per_s: S) -> Self {
        OwnAircraft {
            pressure_altitude_ft: altitude_ft,
            vertical_rate_ft_per_s,
            radio_altitude_ft: Some(altitude_ft),
        }
    }

    fn is_valid(&self) -> bool {
        self.pressure_altitude_ft.is_valid()
            && self.vertical_rate_ft_per_s.is_valid()
            && self.radio_altitude_ft.is_none_or(|h| h.is_valid())
    }
}

/// Selects the sensitivity level from the own aircraft's altitudes.
///
/// Every band includes its lower bound and excludes its upper one (as
/// "< 1000 ft" puts 1000 ft in SL 3): radio altitude < 1000 ft → SL 2,
/// < 2350 ft → SL 3; otherwise, by pressure altitude, < 5000 → SL 4,
/// < 10 000 → SL 5, < 20 000 → SL 6, < 42 000 → SL 7, and from 42 000 ft on
/// SL 7 with the high-altitude ZTHR and ALIM. Without a radio altitude the
/// two AGL bands cannot be chosen and the lowest level is SL 4.
pub fn sensitivity<S: Scalar>(own: &OwnAircraft<S>) -> Result<SensitivityParameters, TcasError> {
    if !own.is_valid() {
        return Err(TcasError::InvalidInput);
    }
    let below = |v: S, bound: f64| v < S::from_f64_lossy(bound);
    let index = match own.radio_altitude_ft {
        Some(h) if below(h, SL3_RADIO_ALTITUDE_FT) => 0,
        Some(h) if below(h, SL4_RADIO_ALTITUDE_FT) => 1,
        _ => {
            let p = own.pressure_altitude_ft;
            if below(p, SL5_PRESSURE_ALTITUDE_FT) {
                2
            } else if below(p, SL6_PRESSURE_ALTITUDE_FT) {
                3
            } else if below(p, SL7_PRESSURE_ALTITUDE_FT) {
                4
            } else if below(p, SL7_HIGH_PRESSURE_ALTITUDE_FT) {
                5
            } else {
                6
            }
        }
    };
    // `index` is 0..=6 by construction; `get` keeps that free of a panic path.
    SENSITIVITY_TABLE
        .get(index)
        .copied()
        .ok_or(TcasError::InvalidInput)
}

/// Closure speed for the taus: max(−ṙ, floor), or `None` when diverging.
fn floored_closure<S: Scalar>(range_rate: S) -> Option<S> {
    if range_rate > S::ZERO {
        None
    } else {
        Some((-range_rate).max_of(S::from_f64_lossy(CLOSURE_RATE_FLOOR_M_PER_S)))
    }
}

fn all_valid<S: Scalar>(values: &[S]) -> Result<(), TcasError> {
    if values.iter().all(|v| v.is_valid()) {
        Ok(())
    } else {
        Err(TcasError::InvalidInput)
    }
}

fn valid_result<S: Scalar>(v: S) -> Result<S, TcasError> {
    if v.is_valid() {
        Ok(v)
    } else {
        Err(TcasError::Saturated)
    }
}

/// Range tau τ = r/max(−ṙ, 10 ft/s), s, for range `range_m` (m, ≥ 0) and
/// range rate `range_rate_m_per_s` (negative closing); `None` when the
/// intruder is diverging (ṙ > 0). See the module docs for the floor.
pub fn range_tau<S: Scalar>(range_m: S, range_rate_m_per_s: S) -> Result<Option<S>, TcasError> {
    all_valid(&[range_m, range_rate_m_per_s])?;
    if range_m < S::ZERO {
        return Err(TcasError::InvalidInput);
    }
    match floored_closure(range_rate_m_per_s) {
        None => Ok(None),
        Some(closure) => valid_result(range_m / closure).map(Some),
    }
}

/// Modified tau τ_mod = (DMOD² − r²)/(r·ṙ), s, with the closure floor: 0
/// when r ≤ DMOD (diverging or not), `None` when diverging outside DMOD.
/// `dmod_m` in metres.
pub fn modified_tau<S: Scalar>(
    range_m: S,
    range_rate_m_per_s: S,
    dmod_m: S,
) -> Result<Option<S>, TcasError> {
    all_valid(&[range_m, range_rate_m_per_s, dmod_m])?;
    if range_m < S::ZERO || dmod_m < S::ZERO {
        return Err(TcasError::InvalidInput);
    }
    if range_m <= dmod_m {
        return Ok(Some(S::ZERO));
    }
    match floored_closure(range_rate_m_per_s) {
        None => Ok(None),
        // r > DMOD ≥ 0, so the division by r is safe and r − DMOD²/r > 0.
        Some(closure) => valid_result((range_m - dmod_m * (dmod_m / range_m)) / closure).map(Some),
    }
}

/// The range test of one alert type: r ≤ DMOD, or not diverging and
/// τ_mod ≤ TAU, decided as r − DMOD²/r ≤ TAU·closure (no quotient by the
/// closure).
fn range_test<S: Scalar>(range_m: S, range_rate_m_per_s: S, dmod_m: S, tau_s: S) -> bool {
    if range_m <= dmod_m {
        return true;
    }
    match floored_closure(range_rate_m_per_s) {
        None => false,
        Some(closure) => range_m - dmod_m * (dmod_m / range_m) <= tau_s * closure,
    }
}

/// Closest point of approach of a straight relative track.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ClosestApproach<S> {
    /// t_cpa ≥ 0, s from now (0 when the range is already opening or the
    /// relative velocity is zero).
    pub time_s: S,
    /// d_cpa, m: the horizontal miss distance.
    pub distance_m: S,
}

/// The closest point of approach from the relative position
/// `position_m` (intruder minus own, m) and relative velocity
/// `velocity_m_per_s` (m/s), from now on (see the module docs).
/// `None` when the time is beyond the representation's range (a relative
/// speed of less than r/2³¹ m/s in fixed point).
pub fn closest_approach<S: Scalar>(
    position_m: [S; 2],
    velocity_m_per_s: [S; 2],
) -> Result<Option<ClosestApproach<S>>, TcasError> {
    let [px, py] = position_m;
    let [vx, vy] = velocity_m_per_s;
    all_valid(&[px, py, vx, vy])?;
    let range = valid_result(hypot(px, py))?;
    let speed = valid_result(hypot(vx, vy))?;
    if speed == S::ZERO || range == S::ZERO {
        return Ok(Some(ClosestApproach {
            time_s: S::ZERO,
            distance_m: range,
        }));
    }
    // Unit vectors: every product below is bounded by 1.
    let (ux, uy) = (px / range, py / range);
    let (wx, wy) = (vx / speed, vy / speed);
    let cos = ux * wx + uy * wy;
    if cos >= S::ZERO {
        // Opening (or tangential): the closest approach is now.
        return Ok(Some(ClosestApproach {
            time_s: S::ZERO,
            distance_m: range,
        }));
    }
    // t = −(p·v)/|v|² = −cos θ · r/|v|; d = r·|sin θ|.
    let time = -cos * (range / speed);
    if !time.is_valid() {
        return Ok(None);
    }
    let sin = ux * wy - uy * wx;
    let distance = valid_result(range * sin.abs())?;
    Ok(Some(ClosestApproach {
        time_s: time,
        distance_m: distance,
    }))
}

/// Vertical tau τ_v = −h/ḣ, s, for relative altitude `relative_altitude_ft`
/// (intruder minus own, ft) and relative vertical rate
/// `relative_rate_ft_per_s` (ft/s): 0 at co-altitude, `None` when the two
/// are not converging (or the time is beyond the representation's range).
pub fn vertical_tau<S: Scalar>(
    relative_altitude_ft: S,
    relative_rate_ft_per_s: S,
) -> Result<Option<S>, TcasError> {
    let (h, hdot) = (relative_altitude_ft, relative_rate_ft_per_s);
    all_valid(&[h, hdot])?;
    if h == S::ZERO {
        return Ok(Some(S::ZERO));
    }
    if !converging(h, hdot) {
        return Ok(None);
    }
    let tau = -h / hdot;
    Ok(if tau.is_valid() { Some(tau) } else { None })
}

fn converging<S: Scalar>(h: S, hdot: S) -> bool {
    (h > S::ZERO && hdot < S::ZERO) || (h < S::ZERO && hdot > S::ZERO)
}

/// The vertical test of one alert type (Muñoz et al.): |h| ≤ ZTHR, or
/// converging with τ_v ≤ TAU, decided as |h| ≤ TAU·|ḣ|.
fn vertical_test<S: Scalar>(h: S, hdot: S, zthr_ft: S, tau_s: S) -> bool {
    h.abs() <= zthr_ft || (converging(h, hdot) && h.abs() <= tau_s * hdot.abs())
}

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
    pub fn from_track(
        track: &RangeAzimuthFilter<S>,
        altitude: Option<AltitudeEstimate<S>>,
    ) -> Self {
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

/// Vertical threat measures of an altitude-reporting intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VerticalMeasures<S> {
    /// Intruder minus own altitude, ft.
    pub relative_altitude_ft: S,
    /// Intruder minus own vertical rate, ft/s.
    pub relative_rate_ft_per_s: S,
    /// τ_v, s ([`vertical_tau`]).
    pub vertical_tau_s: Option<S>,
}

/// Everything the threat logic computed for one intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatAssessment<S> {
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
    pub advisory: Advisory,
}

/// Assesses one intruder against the own aircraft (see the module docs).
pub fn assess<S: Scalar>(
    own: &OwnAircraft<S>,
    intruder: &Intruder<S>,
) -> Result<ThreatAssessment<S>, TcasError> {
    let params = sensitivity(own)?;
    let [px, py] = intruder.relative_position_m;
    let [vx, vy] = intruder.relative_velocity_m_per_s;
    all_valid(&[px, py, vx, vy])?;
    if let Some(a) = intruder.altitude {
        all_valid(&[a.altitude_ft, a.vertical_rate_ft_per_s])?;
    }
    let range = valid_result(hypot(px, py))?;
    // ṙ = p̂·v, with ṙ = 0 at r = 0.
    let range_rate = if range == S::ZERO {
        S::ZERO
    } else {
        valid_result((px / range) * vx + (py / range) * vy)?
    };
    let c = |v: f64| S::from_f64_lossy(v);
    let ta_dmod = c(params.ta.dmod_m());
    let ta_tau = c(params.ta.tau_s);
    let vertical = match intruder.altitude {
        None => None,
        Some(a) => {
            let h = valid_result(a.altitude_ft - own.pressure_altitude_ft)?;
            let hdot = valid_result(a.vertical_rate_ft_per_s - own.vertical_rate_ft_per_s)?;
            Some(VerticalMeasures {
                relative_altitude_ft: h,
                relative_rate_ft_per_s: hdot,
                vertical_tau_s: vertical_tau(h, hdot)?,
            })
        }
    };
    let vertical_passes = |zthr: f64, tau: S| match vertical {
        None => true,
        Some(v) => vertical_test(
            v.relative_altitude_ft,
            v.relative_rate_ft_per_s,
            c(zthr),
            tau,
        ),
    };
    let traffic = range_test(range, range_rate, ta_dmod, ta_tau)
        && vertical_passes(params.ta.zthr_ft, ta_tau);
    let resolution = match (params.ra, vertical) {
        (Some(ra), Some(_)) => {
            let tau = c(ra.tau_s);
            range_test(range, range_rate, c(ra.dmod_m()), tau) && vertical_passes(ra.zthr_ft, tau)
        }
        _ => false,
    };
    let proximate = range <= c(PROXIMATE_RANGE_NM * METRES_PER_NAUTICAL_MILE)
        && vertical.is_none_or(|v| v.relative_altitude_ft.abs() <= c(PROXIMATE_ALTITUDE_FT));
    let advisory = if resolution {
        Advisory::Resolution
    } else if traffic {
        Advisory::Traffic
    } else if proximate {
        Advisory::ProximateTraffic
    } else {
        Advisory::None
    };
    Ok(ThreatAssessment {
        sensitivity: params.level,
        range_m: range,
        range_rate_m_per_s: range_rate,
        range_tau_s: range_tau(range, range_rate)?,
        ta_modified_tau_s: modified_tau(range, range_rate, ta_dmod)?,
        ra_modified_tau_s: match params.ra {
            Some(ra) => modified_tau(range, range_rate, c(ra.dmod_m()))?,
            None => None,
        },
        closest_approach: closest_approach(
            intruder.relative_position_m,
            intruder.relative_velocity_m_per_s,
        )?,
        vertical,
        advisory,
    })
}
