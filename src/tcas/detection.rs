//! Threat detection per TCAS II v7.1: the range test with DMOD and modified
//! tau and its rule for diverging intruders, the horizontal miss-distance
//! filter, the vertical tests (ZTHR, vertical tau, the vertical miss at
//! closest approach, the level-own-aircraft threshold), the 10 000 ft/min
//! limit, the 15 500 ft cap for intruders without altitude, TA hysteresis
//! and minimum TA time, the intruder-on-ground inhibit and firmness gating.
//! Each rule's source is on its function; docs/tcas.md has the table.

use super::measures::{all_valid, valid_result};
use super::range_tracker::{RangeEstimate, MIN_ALERT_FIRMNESS};
use super::sensitivity::{AlertThresholds, OwnAircraft, SensitivityParameters};
use super::{
    Advisory, TcasError, METRES_PER_FOOT, METRES_PER_NAUTICAL_MILE, PROXIMATE_ALTITUDE_FT,
    PROXIMATE_RANGE_NM,
};
use crate::filter::altitude::{AltitudeEstimate, OutOfLine};
use crate::num::Scalar;

/// Range rate above which an intruder counts as diverging, and the floor
/// on the closure speed in the taus, ft/s (DO-185B `RDTHR`, `RDTHRTA`).
pub const DIVERGING_RATE_FT_PER_S: f64 = 10.0;
/// Farthest range of an RA range hit, NM (DO-185B `RMAX`).
pub const MAX_RA_RANGE_NM: f64 = 12.0;
/// d|h|/dt must be below this for the vertical-tau test, ft/s (DO-185B
/// `ZDTHR`, `ZDTHRTA`).
pub const VERTICAL_CONVERGENCE_FT_PER_S: f64 = -1.0;
/// Intruder vertical rates beyond this are not believed for an RA, ft/s
/// (DO-185B `MAXZDINT`, 10 000 ft/min).
pub const MAX_INTRUDER_RATE_FT_PER_S: f64 = 10000.0 / 60.0;
/// Own vertical rate counted as level for the vertical threshold, ft/s
/// (DO-185B `OLEV`, 600 ft/min).
pub const LEVEL_OWN_RATE_FT_PER_S: f64 = 600.0 / 60.0;
/// Highest own altitude at which non-altitude-reporting intruders raise
/// TAs, ft (DO-185B `ABOVNMC`).
pub const NON_REPORTING_TA_CEILING_FT: f64 = 15500.0;
/// TA range hysteresis, NM (DO-185B `TARHYST`): added to the TA DMOD of an
/// intruder that already has a TA.
pub const TA_RANGE_HYSTERESIS_NM: f64 = 0.20;
/// A TA is shown at least this long, s (DO-185B `MINTATIME`).
pub const MIN_TA_TIME_S: f64 = 8.0;
/// An intruder less than this above the ground is on the ground and gets
/// no advisories, ft (FAA TCAS II v7.0 booklet, as quoted in FlightGear
/// `tcas.cxx`).
pub const ON_GROUND_HEIGHT_FT: f64 = 360.0;
/// The miss-distance filter uses the range tau below this, s (DO-185B
/// `TRTETBL[7]`).
pub const MISS_DISTANCE_TAU_LIMIT_S: f64 = 35.0;
/// Continuing threats: the HMD threshold is this times DMOD (DO-185B
/// `HMDMULT`) …
pub const CONTINUING_HMD_DMOD_FACTOR: f64 = 1.05;
/// … and must be exceeded for more than this many cycles (DO-185B
/// `TMIN_MDF`).
pub const CONTINUING_HMD_CYCLES: u8 = 4;
/// Cycles the miss-distance filter stays off after a manoeuvre (DO-185B
/// `mnvr_shtdwn_tm`).
pub const MANOEUVRE_SHUTDOWN_CYCLES: u8 = 10;
/// The bearing cross-check: a range-based HMD more than this times the
/// bearing tracker's is a manoeuvre (DO-185B `rbratio`).
pub const BEARING_CROSS_CHECK_RATIO: f64 = 2.0;
/// The largest modified tau kept by the tau cap, s (any value above every
/// TAU does).
pub const TAU_CAP_LIMIT_S: f64 = 60.0;
/// Least vertical firmness for a new RA (DO-185B `MINFIRM`).
pub const MIN_RA_VERTICAL_FIRMNESS: u8 = 2;

// Not inlined: each call site would otherwise carry the f64-to-S
// conversion (soft-float on the M0), which costs flash.
#[inline(never)]
fn c<S: Scalar>(v: f64) -> S {
    S::from_f64_lossy(v)
}

/// Vertical threat measures of an altitude-reporting intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VerticalMeasures<S> {
    /// Intruder minus own altitude, ft.
    pub relative_altitude_ft: S,
    /// Intruder minus own vertical rate, ft/s.
    pub relative_rate_ft_per_s: S,
    /// τ_v, s ([`super::vertical_tau`]).
    pub vertical_tau_s: Option<S>,
}

/// One alert type's thresholds in the tracker's type.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Thresholds<S> {
    dmod_m: S,
    tau_s: S,
    zthr_ft: S,
    h1_m2_per_s: S,
}

impl<S: Scalar> Thresholds<S> {
    fn new(t: &AlertThresholds, extra_dmod_nm: f64) -> Self {
        Thresholds {
            dmod_m: c((t.dmod_nm + extra_dmod_nm) * METRES_PER_NAUTICAL_MILE),
            tau_s: c(t.tau_s),
            zthr_ft: c(t.zthr_ft),
            h1_m2_per_s: c(t.h1_m2_per_s()),
        }
    }
}

/// The closure speed of the taus: max(−ṙ, 10 ft/s).
fn closure<S: Scalar>(range_rate_m_per_s: S) -> S {
    (-range_rate_m_per_s).max_of(c(DIVERGING_RATE_FT_PER_S * METRES_PER_FOOT))
}

fn diverging<S: Scalar>(range_rate_m_per_s: S) -> bool {
    range_rate_m_per_s > c(DIVERGING_RATE_FT_PER_S * METRES_PER_FOOT)
}

/// The range test (DO-185B `range_test`; DAIDALUS `TCAS2D::horizontal_RA`):
///
/// * diverging (ṙ > 10 ft/s): a hit only inside DMOD with r·ṙ ≤ H1;
/// * otherwise a hit when τ_mod = (r − DMOD²/r)/max(−ṙ, 10 ft/s) < TAU
///   (τ_mod = 0 inside DMOD), decided as r − DMOD·(DMOD/r) < TAU·closure;
///   RAs also need r ≤ 12 NM (`max_range_m`).
fn range_hit<S: Scalar>(r: S, rdot: S, t: &Thresholds<S>, max_range_m: Option<S>) -> bool {
    if diverging(rdot) {
        return r <= t.dmod_m && r.times(rdot) <= t.h1_m2_per_s;
    }
    if max_range_m.is_some_and(|max| r > max) {
        return false;
    }
    r <= t.dmod_m || r - t.dmod_m.times(t.dmod_m.over(r)) < t.tau_s.times(closure(rdot))
}

/// min(r/closure, cap): the true range tau, capped so the quotient stays
/// bounded.
fn capped_range_tau<S: Scalar>(r: S, rdot: S, cap_s: S) -> S {
    let closure = closure(rdot);
    if r >= cap_s.times(closure) {
        cap_s
    } else {
        r.over(closure)
    }
}

/// min(τ_mod, cap), 0 inside DMOD.
fn capped_modified_tau<S: Scalar>(r: S, rdot: S, dmod_m: S, cap_s: S) -> S {
    if r <= dmod_m {
        return S::ZERO;
    }
    let excess = r - dmod_m.times(dmod_m.over(r));
    let closure = closure(rdot);
    if excess >= cap_s.times(closure) {
        cap_s
    } else {
        excess.over(closure)
    }
}

/// The vertical miss distance at closest approach, ft (DO-185B
/// `vertical_miss_distance_calculation`): h + ḣ·τ at the true range tau
/// and at the modified tau (both capped at TVPCMD); zero if the two
/// straddle co-altitude, else the smaller; h itself when diverging.
fn vertical_miss_distance<S: Scalar>(h: S, hdot: S, r: S, rdot: S, dmod_m: S, cap_s: S) -> S {
    if rdot > S::ZERO {
        return h;
    }
    let at_true = h + hdot.times(capped_range_tau(r, rdot, cap_s));
    let at_modified = h + hdot.times(capped_modified_tau(r, rdot, dmod_m, cap_s));
    let straddle = (at_true <= S::ZERO && at_modified >= S::ZERO)
        || (at_true >= S::ZERO && at_modified <= S::ZERO);
    if straddle {
        S::ZERO
    } else if at_true.abs() <= at_modified.abs() {
        at_true
    } else {
        at_modified
    }
}

/// d|h|/dt from h and ḣ (DO-185B `ADOT`, with sign(0) = +1).
fn separation_rate<S: Scalar>(h: S, hdot: S) -> S {
    if h < S::ZERO {
        -hdot
    } else {
        hdot
    }
}

/// The RA vertical-tau threshold (DO-185B `set_detection_parameters`): the
/// level-own-aircraft value `TVVTT` when own is level (|ż| ≤ 600 ft/min) or
/// moving the same way as the intruder but slower; RA TAU otherwise.
fn ra_vertical_tau<S: Scalar>(own_rate: S, intruder_rate: S, level_tau: S, tau: S) -> S {
    let level = c::<S>(LEVEL_OWN_RATE_FT_PER_S);
    let same_way_slower =
        own_rate.times(intruder_rate) >= S::ZERO && own_rate.abs() < intruder_rate.abs();
    if own_rate.abs() <= level || same_way_slower {
        level_tau
    } else {
        tau
    }
}

/// The RA vertical test (DO-185B `altitude_test`): with a = |h| and
/// ȧ = d|h|/dt,
///
/// * a < ZTHR: a hit when the vertical miss distance is below ZTHR;
/// * otherwise converging (ȧ < −1 ft/s) with τ_v = a/(−ȧ) below the
///   vertical threshold, and either the miss distance below ZTHR or τ_v
///   below the true range tau (decided as a·closure < r·(−ȧ));
/// * never when the intruder's rate exceeds 10 000 ft/min.
#[allow(clippy::too_many_arguments)]
fn ra_vertical_hit<S: Scalar>(
    h: S,
    hdot: S,
    intruder_rate: S,
    vmd: S,
    vertical_tau_threshold: S,
    zthr: S,
    r: S,
    rdot: S,
) -> bool {
    if intruder_rate.abs() > c(MAX_INTRUDER_RATE_FT_PER_S) {
        return false;
    }
    let a = h.abs();
    if a < zthr {
        return vmd.abs() < zthr;
    }
    let adot = separation_rate(h, hdot);
    if adot >= c(VERTICAL_CONVERGENCE_FT_PER_S) {
        return false;
    }
    let closing = -adot;
    a < vertical_tau_threshold.times(closing)
        && (vmd.abs() < zthr || a.times(closure(rdot)) < r.times(closing))
}

/// The TA vertical test (DAIDALUS `TCAS3D::vertical_RA` with the TA table;
/// DO-185B `ZDTHRTA`): a < ZTHR, or converging with τ_v below TA TAU.
fn ta_vertical_hit<S: Scalar>(h: S, hdot: S, zthr: S, tau: S) -> bool {
    let a = h.abs();
    if a < zthr {
        return true;
    }
    let adot = separation_rate(h, hdot);
    adot < c(VERTICAL_CONVERGENCE_FT_PER_S) && a < tau.times(-adot)
}

/// The horizontal miss-distance filter's state for one intruder (DO-185B
/// `range_test` MDF part and `detect_maneuvers`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MissDistanceFilter {
    /// Consecutive cycles the HMD exceeded the threshold.
    exceed_cycles: u8,
    /// Cycles left with the filter off after a manoeuvre.
    shutdown_cycles: u8,
}

impl MissDistanceFilter {
    /// The HMD the filter uses this cycle, m: the range tracker's
    /// projection, capped by the bearing tracker's; `None` (filter off)
    /// until the range track is initialised, while r̈ is below its
    /// threshold, and for [`MANOEUVRE_SHUTDOWN_CYCLES`] after a manoeuvre (r̈
    /// below minus the threshold, or the range HMD more than twice the
    /// bearing HMD).
    fn miss_distance<S: Scalar>(
        &mut self,
        range: &RangeEstimate<S>,
        bearing_miss_distance_m: Option<S>,
    ) -> Option<S> {
        let from_range = range.miss_distance_m();
        let bearing_disagrees = match (from_range, bearing_miss_distance_m) {
            (Some(r), Some(b)) => c::<S>(BEARING_CROSS_CHECK_RATIO).times(b) < r,
            _ => false,
        };
        let manoeuvre = range.initialised
            && (range.range_acceleration_m_per_s2 < -range.acceleration_threshold_m_per_s2
                || bearing_disagrees);
        self.shutdown_cycles = if manoeuvre {
            MANOEUVRE_SHUTDOWN_CYCLES
        } else {
            self.shutdown_cycles.saturating_sub(1)
        };
        if self.shutdown_cycles > 0 || !range.initialised {
            return None;
        }
        from_range.map(|r| bearing_miss_distance_m.map_or(r, |b| r.min_of(b)))
    }

    /// Whether the filter removes the range hit this cycle: for a new
    /// threat when the HMD exceeds the level's HMD threshold; for a
    /// continuing one when it has exceeded 1.05·DMOD for more than four
    /// cycles. Applies only while τ_mod < 35 s.
    fn filters<S: Scalar>(
        &mut self,
        miss_distance_m: Option<S>,
        modified_tau_s: S,
        continuing: bool,
        new_threshold_m: S,
        dmod_m: S,
    ) -> bool {
        if modified_tau_s >= c(MISS_DISTANCE_TAU_LIMIT_S) {
            return false;
        }
        let threshold = if continuing {
            c::<S>(CONTINUING_HMD_DMOD_FACTOR).times(dmod_m)
        } else {
            new_threshold_m
        };
        self.exceed_cycles = match miss_distance_m {
            Some(hmd) if hmd > threshold => self.exceed_cycles.saturating_add(1),
            _ => 0,
        };
        if continuing {
            self.exceed_cycles > CONTINUING_HMD_CYCLES
        } else {
            self.exceed_cycles > 0
        }
    }
}

/// What the threat logic sees of one intruder this cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct IntruderObservation<S> {
    /// The range tracker's estimate.
    pub range: RangeEstimate<S>,
    /// The horizontal miss distance of the bearing (range–azimuth) track,
    /// m, for the cross-check; `None` without one.
    pub bearing_miss_distance_m: Option<S>,
    /// Tracked pressure altitude and rate; `None` for an intruder that does
    /// not report altitude.
    pub altitude: Option<AltitudeEstimate<S>>,
    /// The altitude tracker's vertical firmness 0–3.
    pub altitude_firmness: u8,
}

/// The part of an RA threat the resolution logic needs.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatGeometry<S> {
    /// Intruder altitude and rate, ft, ft/s.
    pub intruder: AltitudeEstimate<S>,
    /// True range tau, capped at the level's model limit (TVPE), s.
    pub range_tau_s: S,
    /// Modified tau, capped likewise, s.
    pub modified_tau_s: S,
}

/// Everything the threat logic decided about one intruder this cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatStatus<S> {
    /// The advisory level issued this cycle (booklet, "CAS Logic Functions").
    pub advisory: Advisory,
    /// The TA started this cycle.
    pub new_traffic: bool,
    /// The HMD the filter used, m (`None`: filter off).
    pub miss_distance_m: Option<S>,
    /// The RA range test passed but the miss-distance filter removed it.
    pub miss_distance_filtered: bool,
    /// The firmness gate held back an advisory the tests would give.
    pub held_by_firmness: bool,
    /// `None` for a non-altitude-reporting intruder.
    pub vertical: Option<VerticalMeasures<S>>,
    /// For an RA threat: what the resolution logic needs.
    pub geometry: Option<ThreatGeometry<S>>,
}

/// What the whole system decided for this cycle, shared by every intruder:
/// the own aircraft, the sensitivity parameters (with hysteresis) and the
/// low-altitude inhibits.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cycle<S> {
    /// The own aircraft's state this cycle.
    pub own: OwnAircraft<S>,
    /// The sensitivity parameters selected with hysteresis (booklet Table 3;
    /// DO-185B `ZSL*`).
    pub params: SensitivityParameters,
    /// The low-altitude RA inhibits in force (booklet; DO-185B hysteresis).
    pub inhibits: super::resolution::Inhibits,
}

/// The threat logic's memory of one intruder: TA hysteresis and minimum
/// time, whether it is an RA threat, the miss-distance filter.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatState<S> {
    /// Time since the TA started, s; `None` without a TA.
    ta_age_s: Option<S>,
    /// An RA threat (DO-185B `KHIT` > 0).
    ra_threat: bool,
    /// The smallest RA modified tau since the track became firm and
    /// stopped diverging, s (DO-185B `TAUCAP`: tau may not rise again, so
    /// range noise cannot flicker the range test).
    ra_tau_cap_s: Option<S>,
    miss_distance: MissDistanceFilter,
}

impl<S: Scalar> Default for ThreatState<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// The geometry of one cycle's tests, from either the trackers or a
/// relative state vector.
#[derive(Debug, Clone, Copy)]
struct Inputs<S> {
    range_m: S,
    range_rate_m_per_s: S,
    miss_distance_m: Option<S>,
    altitude: Option<AltitudeEstimate<S>>,
    /// Track firmness allows a new TA / a new RA.
    firm_for_ta: bool,
    firm_for_ra: bool,
}

impl<S: Scalar> ThreatState<S> {
    /// No TA, not an RA threat, no tau cap yet (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        ThreatState {
            ta_age_s: None,
            ra_threat: false,
            ra_tau_cap_s: None,
            miss_distance: MissDistanceFilter {
                exceed_cycles: 0,
                shutdown_cycles: 0,
            },
        }
    }

    /// The intruder is an RA threat.
    pub fn is_ra_threat(&self) -> bool {
        self.ra_threat
    }

    /// The intruder has a TA (or an RA).
    pub fn has_traffic_advisory(&self) -> bool {
        self.ta_age_s.is_some()
    }

    /// One cycle, `dt` s after the previous one, from the trackers.
    /// Advisories start only from firm tracks: range firmness ≥ 3
    /// (DO-185B `MININITHFIRM`) for a TA or an RA, vertical firmness ≥ 2
    /// (`MINFIRM`) for an RA; a continuing advisory is not gated.
    pub fn assess(
        &mut self,
        cycle: &Cycle<S>,
        observation: &IntruderObservation<S>,
        dt: S,
    ) -> Result<ThreatStatus<S>, TcasError> {
        let range = &observation.range;
        all_valid(&[range.range_m, range.range_rate_m_per_s, dt])?;
        if dt <= S::ZERO {
            return Err(TcasError::InvalidInput);
        }
        let miss_distance = self
            .miss_distance
            .miss_distance(range, observation.bearing_miss_distance_m);
        let firm = range.firmness >= MIN_ALERT_FIRMNESS;
        let inputs = Inputs {
            range_m: range.range_m,
            range_rate_m_per_s: range.range_rate_m_per_s,
            miss_distance_m: miss_distance,
            altitude: observation.altitude,
            firm_for_ta: firm,
            firm_for_ra: firm && observation.altitude_firmness >= MIN_RA_VERTICAL_FIRMNESS,
        };
        self.evaluate(cycle, &inputs, Some(dt))
    }

    /// One cycle from a relative state vector (position m, velocity m/s,
    /// intruder minus own): HMD is the straight-line miss distance, and the
    /// firmness gates are open. Used by [`super::assess`].
    pub(crate) fn assess_state(
        &mut self,
        cycle: &Cycle<S>,
        range_m: S,
        range_rate_m_per_s: S,
        miss_distance_m: Option<S>,
        altitude: Option<AltitudeEstimate<S>>,
    ) -> Result<ThreatStatus<S>, TcasError> {
        let inputs = Inputs {
            range_m,
            range_rate_m_per_s,
            miss_distance_m,
            altitude,
            firm_for_ta: true,
            firm_for_ra: true,
        };
        self.evaluate(cycle, &inputs, None)
    }

    fn evaluate(
        &mut self,
        cycle: &Cycle<S>,
        inputs: &Inputs<S>,
        dt: Option<S>,
    ) -> Result<ThreatStatus<S>, TcasError> {
        let own = &cycle.own;
        let params = &cycle.params;
        let (r, rdot) = (inputs.range_m, inputs.range_rate_m_per_s);
        if r < S::ZERO {
            return Err(TcasError::InvalidInput);
        }
        let vertical = match inputs.altitude {
            None => None,
            Some(a) => {
                all_valid(&[a.altitude_ft, a.vertical_rate_ft_per_s])?;
                let h = valid_result(a.altitude_ft - own.pressure_altitude_ft)?;
                let hdot = valid_result(a.vertical_rate_ft_per_s - own.vertical_rate_ft_per_s)?;
                Some(VerticalMeasures {
                    relative_altitude_ft: h,
                    relative_rate_ft_per_s: hdot,
                    vertical_tau_s: super::vertical_tau(h, hdot)?,
                })
            }
        };
        let on_ground = match (inputs.altitude, own.radio_altitude_ft) {
            (Some(a), Some(radio)) => {
                let ground = own.pressure_altitude_ft - radio;
                a.altitude_ft - ground < c(ON_GROUND_HEIGHT_FT)
            }
            _ => false,
        };

        // Traffic advisory.
        let had_ta = self.ta_age_s.is_some();
        let hysteresis = if had_ta { TA_RANGE_HYSTERESIS_NM } else { 0.0 };
        let ta = Thresholds::<S>::new(&params.ta, hysteresis);
        let ta_range = range_hit(r, rdot, &ta, None);
        let ta_tests = match (&vertical, inputs.altitude) {
            (Some(v), _) => {
                ta_range
                    && ta_vertical_hit(
                        v.relative_altitude_ft,
                        v.relative_rate_ft_per_s,
                        ta.zthr_ft,
                        ta.tau_s,
                    )
            }
            (None, _) => ta_range && own.pressure_altitude_ft < c(NON_REPORTING_TA_CEILING_FT),
        };

        // Resolution advisory (never against a non-reporting intruder).
        let mut status_filtered = false;
        let mut geometry = None;
        let ra_tests = match (params.ra, params.resolution, &vertical, inputs.altitude) {
            (Some(ra_t), Some(limits), Some(v), Some(a)) => {
                let ra = Thresholds::<S>::new(&ra_t, 0.0);
                // τ_mod, never rising once the track is firm (DO-185B
                // `tau_calculation` with `TAUCAP`), capped at 60 s so the
                // quotient stays bounded (TAU ≤ 35 s); both the range test
                // and the miss-distance filter's 35 s limit use it.
                let modified_tau = if diverging(rdot) {
                    self.ra_tau_cap_s = None;
                    S::ZERO
                } else {
                    let now = capped_modified_tau(r, rdot, ra.dmod_m, c(TAU_CAP_LIMIT_S));
                    let tau = self.ra_tau_cap_s.map_or(now, |cap| cap.min_of(now));
                    if inputs.firm_for_ta {
                        self.ra_tau_cap_s = Some(tau);
                    }
                    tau
                };
                let range_ok = if diverging(rdot) {
                    range_hit(r, rdot, &ra, None)
                } else {
                    r <= c(MAX_RA_RANGE_NM * METRES_PER_NAUTICAL_MILE) && modified_tau < ra.tau_s
                };
                let filtered = self.miss_distance.filters(
                    inputs.miss_distance_m,
                    modified_tau,
                    self.ra_threat,
                    c(limits.hmd_m()),
                    ra.dmod_m,
                ) && range_ok;
                status_filtered = filtered;
                let range_hit = range_ok && !filtered;
                // A continuing threat stays one while the range test holds
                // (DO-185B `hit_or_miss_test` skips the vertical test for
                // KHIT > 0).
                let vertical_hit = self.ra_threat || {
                    let (h, hdot) = (v.relative_altitude_ft, v.relative_rate_ft_per_s);
                    let vmd = vertical_miss_distance(
                        h,
                        hdot,
                        r,
                        rdot,
                        ra.dmod_m,
                        c(limits.vmd_tau_limit_s),
                    );
                    let threshold = ra_vertical_tau(
                        own.vertical_rate_ft_per_s,
                        a.vertical_rate_ft_per_s,
                        c(limits.level_own_vertical_tau_s),
                        ra.tau_s,
                    );
                    ra_vertical_hit(
                        h,
                        hdot,
                        a.vertical_rate_ft_per_s,
                        vmd,
                        threshold,
                        ra.zthr_ft,
                        r,
                        rdot,
                    )
                };
                let hit = range_hit && vertical_hit;
                if hit {
                    let cap = c(limits.model_tau_limit_s);
                    geometry = Some(ThreatGeometry {
                        intruder: a,
                        range_tau_s: capped_range_tau(r, rdot, cap),
                        modified_tau_s: capped_modified_tau(r, rdot, ra.dmod_m, cap),
                    });
                }
                hit
            }
            _ => false,
        };

        let mut held_by_firmness = false;
        let ra_now = if on_ground {
            false
        } else if self.ra_threat {
            ra_tests
        } else if ra_tests && !inputs.firm_for_ra {
            held_by_firmness = true;
            false
        } else {
            ra_tests
        };
        if !ra_now {
            geometry = None;
        }
        self.ra_threat = ra_now;

        let ta_start = ta_tests && (had_ta || inputs.firm_for_ta);
        held_by_firmness |= ta_tests && !had_ta && !inputs.firm_for_ta;
        let held_by_min_time = match (self.ta_age_s, dt) {
            (Some(age), Some(dt)) => age + dt < c(MIN_TA_TIME_S),
            _ => false,
        };
        let ta_now = !on_ground && (ta_start || ra_now || (had_ta && held_by_min_time));
        self.ta_age_s = match (ta_now, self.ta_age_s, dt) {
            (false, _, _) => None,
            (true, None, _) => Some(S::ZERO),
            (true, Some(age), Some(dt)) => Some(age + dt),
            (true, Some(age), None) => Some(age),
        };

        let proximate = r <= c(PROXIMATE_RANGE_NM * METRES_PER_NAUTICAL_MILE)
            && vertical.is_none_or(|v| v.relative_altitude_ft.abs() <= c(PROXIMATE_ALTITUDE_FT));
        let advisory = if ra_now {
            Advisory::Resolution
        } else if ta_now {
            Advisory::Traffic
        } else if proximate {
            Advisory::ProximateTraffic
        } else {
            Advisory::None
        };
        Ok(ThreatStatus {
            advisory,
            new_traffic: ta_now && !had_ta,
            miss_distance_m: inputs.miss_distance_m,
            miss_distance_filtered: status_filtered,
            held_by_firmness,
            vertical,
            geometry,
        })
    }
}
