//! Threat detection per TCAS II v7.1: the range test with DMOD and modified
//! tau and its rule for diverging intruders, the tau cap and the tau-rise
//! count, threats kept through a missed cycle, the horizontal miss-distance
//! filter, the vertical tests (ZTHR, vertical tau, the vertical miss at
//! closest approach, the level-own-aircraft threshold), the 10 000 ft/min
//! limit, the 15 500 ft cap for intruders without altitude, TA hysteresis
//! and minimum TA time, the intruder-on-ground inhibit and firmness gating.
//! Each rule's source is on its function; docs/tcas.md has the table.

use super::measures::{all_valid, floored_closure, valid_result};
use super::range_tracker::{
    RangeEstimate, ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA, MIN_ALERT_FIRMNESS,
    RATE_ACCELERATION_ERROR_CORRELATION, RATE_ERROR_UNCORRELATED_SHARE,
    RATE_SIGMA_PER_RESIDUAL_SIGMA,
};
use super::sensitivity::{AlertThresholds, OwnAircraft, SensitivityParameters};
use super::{
    Advisory, TcasError, CLOSURE_RATE_FLOOR_M_PER_S, METRES_PER_NAUTICAL_MILE,
    PROXIMATE_ALTITUDE_FT, PROXIMATE_RANGE_NM,
};
use crate::filter::altitude::{AltitudeEstimate, OutOfLine};
use crate::num::{hypot, Quantity, Scalar};

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
/// `TMIN_MDF`, SL 4–7; at SL 3 never: `ResolutionLimits::continuing_hmd_cycles`).
pub const CONTINUING_HMD_CYCLES: u8 = 4;
/// Cycles the miss-distance filter stays off after a manoeuvre (DO-185B
/// `mnvr_shtdwn_tm`).
pub const MANOEUVRE_SHUTDOWN_CYCLES: u8 = 10;
/// The bearing cross-check: a range-based HMD more than this times the
/// bearing tracker's is a manoeuvre (DO-185B `rbratio`).
pub const BEARING_CROSS_CHECK_RATIO: f64 = 2.0;
/// The bearing tracker's HMD in the cross-check is its upper bound
/// b + k_c·σ_b with this k_c: a manoeuvre, which turns the filter off for
/// [`MANOEUVRE_SHUTDOWN_CYCLES`], is declared only when the disagreement
/// is beyond the bearing's noise (a one-sided 97.7 % bound, ours; DO-185B
/// compares b alone).
pub const CROSS_CHECK_CONFIDENCE: f64 = 2.0;
/// The HMD filter's confidence factor k for a new threat: its RA needs
/// the combined miss distance's bound m + kσ at or under the level's HMD
/// threshold (US patent 5,566,074: each miss-distance estimate is used
/// with its uncertainty; the bound is ours, k read off the trade-off of
/// docs/tcas.md: 0, the combined estimate itself).
pub const MISS_DISTANCE_CONFIDENCE: f64 = 0.0;
/// The factor for a continuing threat: its RA ends only when the lower
/// bound m − kσ exceeds 1.05·DMOD (booklet, v7.0 changes: the filter ends
/// an RA when confident the miss will be large; a one-sided 97.7 % bound,
/// ours).
pub const CONTINUING_MISS_DISTANCE_CONFIDENCE: f64 = 2.0;
/// The largest modified tau kept by the tau cap, s (any value above every
/// TAU does).
pub const TAU_CAP_LIMIT_S: f64 = 60.0;
/// A threat that has missed the hit tests two cycles running ends only
/// this long after it became a threat, s (DO-185B `TMIN`).
pub const MIN_THREAT_TIME_S: f64 = 4.5;
/// A new threat outside DMOD whose true range tau has not fallen for this
/// many cycles is not a range hit (DO-185B `taurise_thr`) …
pub const TAU_RISE_CYCLES: u8 = 3;
/// … counted only beyond this range, NM (DO-185B `NAFRANGE`).
pub const TAU_RISE_MIN_RANGE_NM: f64 = 1.7;
/// Least vertical firmness for a new RA (DO-185B `MINFIRM`).
pub const MIN_RA_VERTICAL_FIRMNESS: u8 = 2;

// Not inlined: each call site would otherwise carry the f64-to-S
// conversion (soft-float on the M0), which costs flash. Called only when a
// cycle's thresholds are formed ([`CycleThresholds::new`]), never per
// intruder.
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
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Thresholds<S> {
    dmod_m: S,
    tau_s: S,
    zthr_ft: S,
    h1_m2_per_s: S,
}

impl<S: Scalar> Thresholds<S> {
    fn new(t: &AlertThresholds) -> Self {
        Thresholds {
            dmod_m: c(t.dmod_m()),
            tau_s: c(t.tau_s),
            zthr_ft: c(t.zthr_ft),
            h1_m2_per_s: c(t.h1_m2_per_s()),
        }
    }
}

/// The RA thresholds and limits of a level in the tracker's type.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct ResolutionThresholds<S> {
    alert: Thresholds<S>,
    hmd_m: S,
    level_own_vertical_tau_s: S,
    vmd_tau_limit_s: S,
    model_tau_limit_s: S,
    continuing_hmd_cycles: Option<u8>,
}

/// The logic's constants that do not depend on the level (this module's
/// `const`s) in the tracker's type.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Constants<S> {
    closure_rate_floor_m_per_s: S,
    max_ra_range_m: S,
    vertical_convergence_ft_per_s: S,
    max_intruder_rate_ft_per_s: S,
    level_own_rate_ft_per_s: S,
    non_reporting_ta_ceiling_ft: S,
    min_ta_time_s: S,
    on_ground_height_ft: S,
    miss_distance_tau_limit_s: S,
    continuing_hmd_dmod_factor: S,
    bearing_cross_check_ratio: S,
    cross_check_confidence: S,
    miss_distance_confidence: S,
    continuing_miss_distance_confidence: S,
    acceleration_sigma_per_residual_sigma: S,
    rate_sigma_per_residual_sigma: S,
    /// ρ of the ṙ and r̈ errors, and √(1 − ρ²).
    rate_acceleration_correlation: S,
    rate_error_uncorrelated_share: S,
    tau_cap_limit_s: S,
    min_threat_time_s: S,
    tau_rise_min_range_m: S,
    proximate_range_m: S,
    proximate_altitude_ft: S,
}

/// A cycle's thresholds (the level's and the logic's constants) in the
/// tracker's type, converted once per cycle so that no intruder's
/// assessment converts a number (as a filter's step gains are formed once
/// per interval).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct CycleThresholds<S> {
    ta: Thresholds<S>,
    /// TA DMOD widened by [`TA_RANGE_HYSTERESIS_NM`], for an intruder that
    /// already has a TA.
    ta_held_dmod_m: S,
    ra: Option<ResolutionThresholds<S>>,
    constants: Constants<S>,
}

impl<S: Scalar> CycleThresholds<S> {
    /// The thresholds of `params` and the module's constants in `S`.
    pub(crate) fn new(params: &SensitivityParameters) -> Self {
        let ra = match (params.ra, params.resolution) {
            (Some(ra), Some(limits)) => Some(ResolutionThresholds {
                alert: Thresholds::new(&ra),
                hmd_m: c(limits.hmd_m()),
                level_own_vertical_tau_s: c(limits.level_own_vertical_tau_s),
                vmd_tau_limit_s: c(limits.vmd_tau_limit_s),
                model_tau_limit_s: c(limits.model_tau_limit_s),
                continuing_hmd_cycles: limits.continuing_hmd_cycles,
            }),
            _ => None,
        };
        CycleThresholds {
            ta: Thresholds::new(&params.ta),
            ta_held_dmod_m: c(
                (params.ta.dmod_nm + TA_RANGE_HYSTERESIS_NM) * METRES_PER_NAUTICAL_MILE
            ),
            ra,
            constants: Constants {
                closure_rate_floor_m_per_s: c(CLOSURE_RATE_FLOOR_M_PER_S),
                max_ra_range_m: c(MAX_RA_RANGE_NM * METRES_PER_NAUTICAL_MILE),
                vertical_convergence_ft_per_s: c(VERTICAL_CONVERGENCE_FT_PER_S),
                max_intruder_rate_ft_per_s: c(MAX_INTRUDER_RATE_FT_PER_S),
                level_own_rate_ft_per_s: c(LEVEL_OWN_RATE_FT_PER_S),
                non_reporting_ta_ceiling_ft: c(NON_REPORTING_TA_CEILING_FT),
                min_ta_time_s: c(MIN_TA_TIME_S),
                on_ground_height_ft: c(ON_GROUND_HEIGHT_FT),
                miss_distance_tau_limit_s: c(MISS_DISTANCE_TAU_LIMIT_S),
                continuing_hmd_dmod_factor: c(CONTINUING_HMD_DMOD_FACTOR),
                bearing_cross_check_ratio: c(BEARING_CROSS_CHECK_RATIO),
                cross_check_confidence: c(CROSS_CHECK_CONFIDENCE),
                miss_distance_confidence: c(MISS_DISTANCE_CONFIDENCE),
                continuing_miss_distance_confidence: c(CONTINUING_MISS_DISTANCE_CONFIDENCE),
                acceleration_sigma_per_residual_sigma: c(ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA),
                rate_sigma_per_residual_sigma: c(RATE_SIGMA_PER_RESIDUAL_SIGMA),
                rate_acceleration_correlation: c(RATE_ACCELERATION_ERROR_CORRELATION),
                rate_error_uncorrelated_share: c(RATE_ERROR_UNCORRELATED_SHARE),
                tau_cap_limit_s: c(TAU_CAP_LIMIT_S),
                min_threat_time_s: c(MIN_THREAT_TIME_S),
                tau_rise_min_range_m: c(TAU_RISE_MIN_RANGE_NM * METRES_PER_NAUTICAL_MILE),
                proximate_range_m: c(PROXIMATE_RANGE_NM * METRES_PER_NAUTICAL_MILE),
                proximate_altitude_ft: c(PROXIMATE_ALTITUDE_FT),
            },
        }
    }

    /// The TA DMOD, m, and the RA DMOD (`None` at SL 2).
    pub(crate) fn dmod_m(&self) -> (S, Option<S>) {
        (self.ta.dmod_m, self.ra.map(|ra| ra.alert.dmod_m))
    }
}

/// One intruder's horizontal quantities in a cycle, each quotient formed
/// at most once: the range tests, the taus and the vertical miss distance
/// share them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RangeGeometry<S> {
    r: S,
    rdot: S,
    /// ṙ > 10 ft/s (DO-185B `RDTHR`).
    diverging: bool,
    /// The closure speed of the taus: max(−ṙ, 10 ft/s).
    closure: S,
    /// 1/closure and 1/r, once formed, in a format with relative precision
    /// ([`Quantity::RELATIVE_PRECISION`]); the quotients divide otherwise.
    per_closure: Option<S>,
    per_range: Option<S>,
    /// r/closure, once formed.
    range_tau: Option<S>,
    /// The RA τ_mod (uncapped), once formed.
    ra_modified_tau: Option<S>,
    /// The last DMOD given to [`RangeGeometry::excess`] and its result.
    last_excess: Option<(S, Option<S>)>,
}

impl<S: Scalar> RangeGeometry<S> {
    /// Range `r` (m, ≥ 0) and range rate `rdot` (m/s) in a cycle.
    pub(crate) fn new(r: S, rdot: S, thresholds: &CycleThresholds<S>) -> Self {
        let floor = thresholds.constants.closure_rate_floor_m_per_s;
        let closure = floored_closure(rdot, floor);
        RangeGeometry {
            r,
            rdot,
            diverging: closure.is_none(),
            closure: closure.unwrap_or(floor),
            per_closure: None,
            per_range: None,
            range_tau: None,
            ra_modified_tau: None,
            last_excess: None,
        }
    }

    /// [`RangeGeometry::excess_over_dmod`], kept for the last `dmod_m`: the TA range test
    /// and the TA τ_mod of [`super::assess`] share it.
    fn excess(&mut self, dmod_m: S) -> Option<S> {
        match self.last_excess {
            Some((dmod, excess)) if dmod == dmod_m => excess,
            _ => {
                let excess = self.excess_over_dmod(dmod_m);
                self.last_excess = Some((dmod_m, excess));
                excess
            }
        }
    }

    /// r − DMOD²/r as r − DMOD·(DMOD/r) (no square of a range); `None` for
    /// r ≤ DMOD.
    fn excess_over_dmod(&mut self, dmod_m: S) -> Option<S> {
        let r = self.r;
        if r <= dmod_m {
            return None;
        }
        let dmod_over_r = if <S as Quantity>::RELATIVE_PRECISION {
            dmod_m.times(*self.per_range.get_or_insert_with(|| S::ONE.over(r)))
        } else {
            dmod_m.over(r)
        };
        Some(r - dmod_m.times(dmod_over_r))
    }

    /// `distance`/max(−ṙ, 10 ft/s), s: a tau. One reciprocal shared
    /// by every tau of the intruder where it keeps its digits
    /// ([`Scalar::over_each`]).
    fn over_closure(&mut self, distance: S) -> S {
        if <S as Quantity>::RELATIVE_PRECISION {
            let closure = self.closure;
            distance.times(*self.per_closure.get_or_insert_with(|| S::ONE.over(closure)))
        } else {
            distance.over(self.closure)
        }
    }

    /// ṙ > 10 ft/s: no tau (DO-185B `RDTHR`).
    pub(crate) fn diverging(&self) -> bool {
        self.diverging
    }

    /// The true range tau r/max(−ṙ, 10 ft/s), s.
    pub(crate) fn range_tau(&mut self) -> S {
        match self.range_tau {
            Some(tau) => tau,
            None => {
                let tau = self.over_closure(self.r);
                *self.range_tau.insert(tau)
            }
        }
    }

    /// τ_mod = (r − DMOD²/r)/max(−ṙ, 10 ft/s) with DMOD `dmod_m`, 0 inside
    /// DMOD.
    pub(crate) fn modified_tau(&mut self, dmod_m: S) -> S {
        match self.excess(dmod_m) {
            Some(excess) => self.over_closure(excess),
            None => S::ZERO,
        }
    }

    /// [`RangeGeometry::modified_tau`] with the RA DMOD (the same `dmod_m`
    /// on every call), formed once.
    pub(crate) fn ra_modified_tau(&mut self, dmod_m: S) -> S {
        match self.ra_modified_tau {
            Some(tau) => tau,
            None => {
                let tau = match self.excess_over_dmod(dmod_m) {
                    Some(excess) => self.over_closure(excess),
                    None => S::ZERO,
                };
                *self.ra_modified_tau.insert(tau)
            }
        }
    }
}

/// The range test (DO-185B `range_test`; DAIDALUS `TCAS2D::horizontal_RA`):
///
/// * diverging (ṙ > 10 ft/s): a hit only inside DMOD with r·ṙ ≤ H1;
/// * otherwise a hit when τ_mod = (r − DMOD²/r)/max(−ṙ, 10 ft/s) < TAU
///   (τ_mod = 0 inside DMOD), decided as r − DMOD·(DMOD/r) < TAU·closure.
fn range_hit<S: Scalar>(g: &mut RangeGeometry<S>, dmod_m: S, t: &Thresholds<S>) -> bool {
    if g.diverging {
        return g.r <= dmod_m && g.r.times(g.rdot) <= t.h1_m2_per_s;
    }
    match g.excess(dmod_m) {
        None => true,
        Some(excess) => excess < t.tau_s.times(g.closure),
    }
}

/// The vertical miss distance at closest approach, ft (DO-185B
/// `vertical_miss_distance_calculation`): h + ḣ·τ at the true range tau
/// and at the modified tau (the tau cap's `TRTRU` and `TAUR`, both capped
/// at TVPCMD); zero if the two
/// straddle co-altitude, else the smaller; h itself while the range opens
/// (ṙ > 0, DO-185B `hit_or_miss_test`).
fn vertical_miss_distance<S: Scalar>(h: S, hdot: S, range_tau: S, modified_tau: S, cap_s: S) -> S {
    let at_true = h + hdot.times(cap_s.min_of(range_tau));
    let at_modified = h + hdot.times(cap_s.min_of(modified_tau));
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
fn ra_vertical_tau<S: Scalar>(
    own_rate: S,
    intruder_rate: S,
    level_tau: S,
    tau: S,
    k: &Constants<S>,
) -> S {
    let level = k.level_own_rate_ft_per_s;
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
///   below the true range tau `true_tau` (the tau cap's `TRTRU`, `MINTAU`
///   = 0 for a diverging intruder, DO-185B `range_test`);
/// * never when the intruder's rate exceeds 10 000 ft/min.
#[allow(clippy::too_many_arguments)]
fn ra_vertical_hit<S: Scalar>(
    h: S,
    hdot: S,
    intruder_rate: S,
    vmd: S,
    vertical_tau_threshold: S,
    zthr: S,
    true_tau: S,
    k: &Constants<S>,
) -> bool {
    if intruder_rate.abs() > k.max_intruder_rate_ft_per_s {
        return false;
    }
    let a = h.abs();
    if a < zthr {
        return vmd.abs() < zthr;
    }
    let adot = separation_rate(h, hdot);
    if adot >= k.vertical_convergence_ft_per_s {
        return false;
    }
    let closing = -adot;
    a < vertical_tau_threshold.times(closing) && (vmd.abs() < zthr || a < true_tau.times(closing))
}

/// The TA vertical test (DAIDALUS `TCAS3D::vertical_RA` with the TA table;
/// DO-185B `ZDTHRTA`): a < ZTHR, or converging with τ_v below TA TAU.
fn ta_vertical_hit<S: Scalar>(h: S, hdot: S, zthr: S, tau: S, k: &Constants<S>) -> bool {
    let a = h.abs();
    if a < zthr {
        return true;
    }
    let adot = separation_rate(h, hdot);
    adot < k.vertical_convergence_ft_per_s && a < tau.times(-adot)
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

/// The HMDs of one cycle for the two thresholds of the filter, m (`None`:
/// filter off).
#[derive(Debug, Clone, Copy, PartialEq)]
struct MissDistances<S> {
    /// Against the level's HMD threshold, for a new threat.
    new_threat: Option<S>,
    /// Against 1.05·DMOD, for a continuing threat (the lower bound).
    continuing: Option<S>,
}

impl<S> MissDistances<S> {
    const OFF: Self = MissDistances {
        new_threat: None,
        continuing: None,
    };

    /// The same HMD for both (a state vector's exact miss distance).
    fn both(hmd: Option<S>) -> Self
    where
        S: Copy,
    {
        MissDistances {
            new_threat: hmd,
            continuing: hmd,
        }
    }
}

impl MissDistanceFilter {
    /// The HMDs the filter uses this cycle, m (US patent 5,566,074: the
    /// range- and bearing-based miss distances each with its uncertainty).
    /// The range track's d² = r²·x/(x + ṙ²), x = r·r̈ (DO-185B
    /// `project_hmd`), has its σ from those of r̈ and ṙ and their
    /// correlation, each from the track's residual RMS
    /// ([`ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA`]/T²,
    /// [`RATE_SIGMA_PER_RESIDUAL_SIGMA`]/T); the bearing track's b has σ_b.
    /// Each is linearised at the threshold t it is compared with
    /// (d²/(2t) + t/2 is d at d = t: the decision d > t is kept exactly;
    /// [`RangeProjection`]) and the two are combined with
    /// inverse-variance weights into m ± σ, σ scaled up when they disagree
    /// beyond it ([`inverse_variance`]). A new threat's HMD is
    /// m + kσ against the level's HMD threshold (k =
    /// [`MISS_DISTANCE_CONFIDENCE`], or the cycle's), a continuing one's
    /// m − k'σ against 1.05·DMOD (k' =
    /// [`CONTINUING_MISS_DISTANCE_CONFIDENCE`]). `None` (filter off)
    /// without an estimate, at SL 2, and for
    /// [`MANOEUVRE_SHUTDOWN_CYCLES`] after a manoeuvre (DO-185B
    /// `detect_maneuvers`: r̈ below minus its threshold, or the thresholded
    /// range HMD more than twice b + k_c·σ_b, k_c =
    /// [`CROSS_CHECK_CONFIDENCE`]).
    fn miss_distance<S: Scalar>(
        &mut self,
        range: &RangeEstimate<S>,
        bearing: Option<(S, Option<S>)>,
        dt: S,
        thresholds: &CycleThresholds<S>,
    ) -> MissDistances<S> {
        let k = &thresholds.constants;
        let confidence = k.miss_distance_confidence;
        let bearing_upper = bearing.map(|(b, sigma)| match sigma {
            Some(sigma) => b + k.cross_check_confidence.times(sigma),
            None => b,
        });
        let bearing_disagrees = match (range.miss_distance_m(), bearing_upper) {
            (Some(r), Some(b)) => k.bearing_cross_check_ratio.times(b) < r,
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
        let Some(ra) = thresholds.ra else {
            return MissDistances::OFF;
        };
        if self.shutdown_cycles > 0 {
            return MissDistances::OFF;
        }
        let acceleration_sigma = k
            .acceleration_sigma_per_residual_sigma
            .times(range.residual_sigma_m)
            .over(dt.times(dt));
        let rate_sigma = k
            .rate_sigma_per_residual_sigma
            .times(range.residual_sigma_m)
            .over(dt);
        // Formed once, linearised at each threshold.
        let projection = if range.initialised {
            RangeProjection::of(range, (rate_sigma, acceleration_sigma), k)
        } else {
            None
        };
        let combined_at = |threshold: S| {
            let from_range = projection.and_then(|p| p.linearised_at(threshold));
            let from_bearing = bearing.and_then(|(b, sigma)| sigma.map(|s| (b, s)));
            let (m, sigma) = match (from_range, from_bearing) {
                (Some(r), Some(b)) => inverse_variance(r, b),
                (Some(r), None) => r,
                (None, Some(b)) => b,
                (None, None) => return None,
            };
            Some((m, sigma))
        };
        let continuing_threshold = k.continuing_hmd_dmod_factor.times(ra.alert.dmod_m);
        let continuing_confidence = k.continuing_miss_distance_confidence;
        MissDistances {
            new_threat: combined_at(ra.hmd_m).map(|(m, sigma)| m + confidence.times(sigma)),
            continuing: combined_at(continuing_threshold)
                .map(|(m, sigma)| m - continuing_confidence.times(sigma)),
        }
    }

    /// Whether the filter removes the range hit this cycle: for a new
    /// threat when the HMD exceeds the level's HMD threshold; for a
    /// continuing one when it has exceeded 1.05·DMOD for more than the
    /// level's `continuing_hmd_cycles` (never at SL 3: DO-185B `TMIN_MDF`).
    /// Applies only while τ_mod < 35 s.
    fn filters<S: Scalar>(
        &mut self,
        miss_distance: &MissDistances<S>,
        modified_tau_s: S,
        continuing: bool,
        limits: &ResolutionThresholds<S>,
        k: &Constants<S>,
    ) -> bool {
        if modified_tau_s >= k.miss_distance_tau_limit_s {
            return false;
        }
        let (threshold, miss_distance_m) = if continuing {
            (
                k.continuing_hmd_dmod_factor.times(limits.alert.dmod_m),
                miss_distance.continuing,
            )
        } else {
            (limits.hmd_m, miss_distance.new_threat)
        };
        self.exceed_cycles = match miss_distance_m {
            Some(hmd) if hmd > threshold => self.exceed_cycles.saturating_add(1),
            _ => 0,
        };
        if continuing {
            limits
                .continuing_hmd_cycles
                .is_some_and(|n| self.exceed_cycles > n)
        } else {
            self.exceed_cycles > 0
        }
    }
}

/// The range track's squared miss distance d² = r²·x/(x + ṙ²), x = r·r̈,
/// and its σ, from the σ of ṙ and of r̈ and their correlation ρ through
/// ∂d²/∂r̈ = r³ṙ²/D² and ∂d²/∂ṙ = −2r²xṙ/D², D = x + ṙ² (near closest
/// approach, where r̈ is large and ṙ small, the ṙ term dominates), kept as
/// r and the shares d²/r² and σ(d²)/r²: no square of a range is formed.
#[derive(Debug, Clone, Copy)]
struct RangeProjection<S> {
    range_m: S,
    /// x/D = d²/r².
    share: S,
    /// σ(d²)/r².
    sigma_share: S,
}

impl<S: Scalar> RangeProjection<S> {
    /// `None` when D ≤ 0 (no straight path fits) or a step saturates.
    fn of(
        range: &RangeEstimate<S>,
        (rate_sigma, acceleration_sigma): (S, S),
        k: &Constants<S>,
    ) -> Option<Self> {
        let r = range.range_m;
        let rate = range.range_rate_m_per_s;
        let rate_squared = rate.times(rate);
        let x = r.times(range.range_acceleration_m_per_s2);
        let denominator = x + rate_squared;
        let share = (denominator > S::ZERO).then(|| x.over(denominator))?;
        // The two terms of σ(d²)·D/r² (m²/s²), and their correlated sum
        // √(a² + b² + 2ρab) = hypot(a + ρb, b·√(1 − ρ²)).
        let from_acceleration = r
            .times(acceleration_sigma)
            .times(rate_squared.over(denominator));
        let from_rate = -(share.times(rate + rate).times(rate_sigma));
        let both = hypot(
            from_acceleration + k.rate_acceleration_correlation.times(from_rate),
            k.rate_error_uncorrelated_share.times(from_rate),
        );
        Some(RangeProjection {
            range_m: r,
            share,
            sigma_share: both.over(denominator),
        })
    }

    /// The miss distance linearised at the threshold `t` (m), d²/(2t) + t/2
    /// (d itself at d = t: the decision d > t is kept), and its σ, σ(d²)/(2t).
    /// `None` when t ≤ 0 or a step saturates.
    fn linearised_at(&self, t: S) -> Option<(S, S)> {
        let r = self.range_m;
        let r_over_2t = (t > S::ZERO).then(|| r.over(t + t))?;
        let half = S::from_f64_lossy(0.5);
        let m = r_over_2t.times(r.times(self.share)) + half.times(t);
        let sigma = r_over_2t.times(r.times(self.sigma_share));
        (m.is_valid() && sigma.is_valid()).then_some((m, sigma))
    }
}

/// Two independent estimates (value, σ) combined with inverse-variance
/// weights: m_b + (m_a − m_b)·σ_b²/(σ_a² + σ_b²), σ = σ_a·σ_b/√(σ_a² + σ_b²)
/// (no square of a σ is formed), the σ scaled by S = |m_a − m_b|/√(σ_a² +
/// σ_b²) when S > 1: estimates further apart than their σ say have a σ
/// that is too small (the Particle Data Group's scale factor for
/// inconsistent measurements, Review of Particle Physics, "Averaging
/// procedures"). Both σ zero: the first.
fn inverse_variance<S: Scalar>((a, sigma_a): (S, S), (b, sigma_b): (S, S)) -> (S, S) {
    let h = hypot(sigma_a, sigma_b);
    if !(h.is_valid() && h > S::ZERO) {
        return (a, S::ZERO);
    }
    let share_b = sigma_b.over(h);
    let weight_a = share_b.times(share_b);
    let difference = a - b;
    let spread = difference.abs().over(h);
    let sigma = sigma_a.times(share_b);
    let combined = (
        b + difference.times(weight_a),
        if spread > S::ONE {
            sigma.times(spread)
        } else {
            sigma
        },
    );
    if combined.0.is_valid() && combined.1.is_valid() {
        combined
    } else {
        (a, sigma_a)
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
    /// Its standard deviation, m ([`crate::tcas::logic::IntruderTrack::observation`]);
    /// `None` without one.
    pub bearing_miss_distance_sigma_m: Option<S>,
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
    /// True range tau as the tau cap holds it (DO-185B `TRTRU`: it never
    /// rises while the intruder closes), capped at the level's model limit
    /// (TVPE), s; 0 for a diverging intruder (`MINTAU`).
    pub range_tau_s: S,
    /// Modified tau as the tau cap holds it (`TAUR`), capped likewise, s;
    /// 0 when diverging.
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
    /// The HMD the filter used, m (`None`: filter off): a continuing
    /// threat's lower bound, or a new one's estimate.
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
/// the own aircraft, the sensitivity parameters (with hysteresis), the
/// low-altitude inhibits, and the thresholds in the tracker's type.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cycle<S> {
    pub(crate) own: OwnAircraft<S>,
    pub(crate) params: SensitivityParameters,
    pub(crate) inhibits: super::resolution::Inhibits,
    thresholds: CycleThresholds<S>,
}

impl<S: Scalar> Cycle<S> {
    /// A cycle of the own aircraft `own` at the sensitivity parameters
    /// `params` with the inhibits `inhibits`; converts the thresholds to
    /// `S` once for every intruder of the cycle.
    pub fn new(
        own: OwnAircraft<S>,
        params: SensitivityParameters,
        inhibits: super::resolution::Inhibits,
    ) -> Self {
        Cycle {
            own,
            params,
            inhibits,
            thresholds: CycleThresholds::new(&params),
        }
    }

    /// The own aircraft's state this cycle.
    pub fn own(&self) -> &OwnAircraft<S> {
        &self.own
    }

    /// The sensitivity parameters selected with hysteresis (booklet Table 3;
    /// DO-185B `ZSL*`).
    pub fn params(&self) -> &SensitivityParameters {
        &self.params
    }

    /// The low-altitude RA inhibits in force (booklet; DO-185B hysteresis).
    pub fn inhibits(&self) -> &super::resolution::Inhibits {
        &self.inhibits
    }

    /// The same cycle with the HMD filter's confidence factor set to
    /// `sigmas` (default [`MISS_DISTANCE_CONFIDENCE`]): for studies of the
    /// trade-off between false and missed RAs.
    pub fn with_miss_distance_confidence(mut self, sigmas: S) -> Self {
        self.thresholds.constants.miss_distance_confidence = sigmas;
        self
    }

    pub(crate) fn thresholds(&self) -> &CycleThresholds<S> {
        &self.thresholds
    }
}

/// An intruder's standing as an RA threat (DO-185B `KHIT`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum ThreatHits {
    /// Not a threat (`KHIT` 0).
    None,
    /// A threat that passed the hit tests this cycle (`KHIT` 3).
    Hit,
    /// A threat that missed them this cycle (`KHIT` 1): it stays one, and
    /// ends at its next miss once [`MIN_THREAT_TIME_S`] has passed.
    Missed,
}

/// The threat logic's memory of one intruder: TA hysteresis and minimum
/// time, whether it is an RA threat and for how long, the tau cap and the
/// tau-rise count, the miss-distance filter.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatState<S> {
    /// Time since the TA started, s; meaningful while `has_ta` (zero
    /// otherwise). A value and a flag rather than an `Option`: the flags
    /// share the word of the miss-distance counts (docs/tcas.md, "RAM per
    /// intruder").
    ta_age_s: S,
    /// Time since the intruder became an RA threat, s (DO-185B
    /// `TCUR − TCMD`); meaningful while `hits` is not `None`.
    threat_age_s: S,
    /// The smallest RA modified tau and true range tau since the track
    /// became firm and stopped diverging, s (DO-185B `TAUCAP`, `TAUR`,
    /// `TRTRU`: tau may not rise again, so range noise cannot flicker the
    /// tests); meaningful while `has_tau_cap` (zero otherwise).
    ra_tau_cap_s: S,
    true_tau_cap_s: S,
    /// The true range tau of the last cycle, uncapped (DO-185B `TRTUN`);
    /// meaningful while `has_tau_cap`.
    last_true_tau_s: S,
    has_ta: bool,
    hits: ThreatHits,
    has_tau_cap: bool,
    /// Cycles the true range tau has not fallen beyond
    /// [`TAU_RISE_MIN_RANGE_NM`] (DO-185B `TAURISE`).
    tau_rise_cycles: u8,
    miss_distance: MissDistanceFilter,
}

impl<S: Scalar> Default for ThreatState<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// What one cycle's tests take besides the range geometry, from either the
/// trackers or a relative state vector.
#[derive(Debug, Clone, Copy)]
struct Inputs<S> {
    miss_distance: MissDistances<S>,
    altitude: Option<AltitudeEstimate<S>>,
    /// `altitude` against the own aircraft ([`vertical_measures`]).
    vertical: Option<VerticalMeasures<S>>,
    /// Track firmness allows a new TA / a new RA.
    firm_for_ta: bool,
    firm_for_ra: bool,
}

/// An intruder's altitude estimate against the own aircraft: relative
/// altitude h, rate ḣ and τ_v = −h/ḣ (DO-185B vertical tau); refused when a
/// number is invalid.
fn vertical_measures<S: Scalar>(
    own: &OwnAircraft<S>,
    altitude: Option<AltitudeEstimate<S>>,
) -> Result<Option<VerticalMeasures<S>>, TcasError> {
    let Some(a) = altitude else {
        return Ok(None);
    };
    all_valid(&[a.altitude_ft, a.vertical_rate_ft_per_s])?;
    let h = valid_result(a.altitude_ft - own.pressure_altitude_ft)?;
    let hdot = valid_result(a.vertical_rate_ft_per_s - own.vertical_rate_ft_per_s)?;
    Ok(Some(VerticalMeasures {
        relative_altitude_ft: h,
        relative_rate_ft_per_s: hdot,
        vertical_tau_s: super::vertical_tau(h, hdot)?,
    }))
}

impl<S: Scalar> ThreatState<S> {
    /// No TA, not an RA threat, no tau cap yet (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        ThreatState {
            ta_age_s: S::ZERO,
            threat_age_s: S::ZERO,
            ra_tau_cap_s: S::ZERO,
            true_tau_cap_s: S::ZERO,
            last_true_tau_s: S::ZERO,
            has_ta: false,
            hits: ThreatHits::None,
            has_tau_cap: false,
            tau_rise_cycles: 0,
            miss_distance: MissDistanceFilter {
                exceed_cycles: 0,
                shutdown_cycles: 0,
            },
        }
    }

    /// The intruder is an RA threat.
    pub fn is_ra_threat(&self) -> bool {
        self.hits != ThreatHits::None
    }

    /// The intruder has a TA (or an RA).
    pub fn has_traffic_advisory(&self) -> bool {
        self.has_ta
    }

    /// Time since the TA started, s; `None` without a TA.
    fn ta_age(&self) -> Option<S> {
        self.has_ta.then_some(self.ta_age_s)
    }

    fn set_ta_age(&mut self, age: Option<S>) {
        self.has_ta = age.is_some();
        self.ta_age_s = age.unwrap_or(S::ZERO);
    }

    /// This cycle's RA modified tau and true range tau under the tau cap
    /// (DO-185B `tau_calculation`: once the track is firm, each is the
    /// smallest since, in every cycle until the intruder diverges; capped
    /// at [`TAU_CAP_LIMIT_S`]), counting the cycles the true tau has not
    /// fallen (`TAURISE`). `(0, 0)` for a diverging intruder (`MINTAU`),
    /// which ends the cap.
    fn capped_taus(
        &mut self,
        g: &mut RangeGeometry<S>,
        dmod_m: S,
        firm: bool,
        k: &Constants<S>,
    ) -> (S, S) {
        if g.diverging {
            self.has_tau_cap = false;
            self.tau_rise_cycles = 0;
            return (S::ZERO, S::ZERO);
        }
        let true_tau = g.range_tau();
        let now = (
            k.tau_cap_limit_s.min_of(g.ra_modified_tau(dmod_m)),
            k.tau_cap_limit_s.min_of(true_tau),
        );
        let taus = if self.has_tau_cap {
            if true_tau < self.last_true_tau_s {
                self.tau_rise_cycles = 0;
            } else if g.r > k.tau_rise_min_range_m {
                self.tau_rise_cycles = self.tau_rise_cycles.saturating_add(1);
            }
            (
                self.ra_tau_cap_s.min_of(now.0),
                self.true_tau_cap_s.min_of(now.1),
            )
        } else {
            self.tau_rise_cycles = 0;
            now
        };
        if firm || self.has_tau_cap {
            self.has_tau_cap = true;
            (self.ra_tau_cap_s, self.true_tau_cap_s) = taus;
            self.last_true_tau_s = true_tau;
        }
        taus
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
        if dt <= S::ZERO || range.range_m < S::ZERO {
            return Err(TcasError::InvalidInput);
        }
        // Every refusal before the miss-distance filter moves: an `Err`
        // changes nothing.
        let vertical = vertical_measures(&cycle.own, observation.altitude)?;
        let miss_distance = self.miss_distance.miss_distance(
            range,
            observation
                .bearing_miss_distance_m
                .map(|b| (b, observation.bearing_miss_distance_sigma_m)),
            dt,
            &cycle.thresholds,
        );
        let firm = range.firmness >= MIN_ALERT_FIRMNESS;
        let inputs = Inputs {
            miss_distance,
            altitude: observation.altitude,
            vertical,
            firm_for_ta: firm,
            firm_for_ra: firm && observation.altitude_firmness >= MIN_RA_VERTICAL_FIRMNESS,
        };
        let mut geometry =
            RangeGeometry::new(range.range_m, range.range_rate_m_per_s, &cycle.thresholds);
        Ok(self.evaluate(cycle, &mut geometry, &inputs, Some(dt)))
    }

    /// One cycle from a relative state vector (range `geometry`, the
    /// straight-line miss distance), `dt` s after the previous one (`None`:
    /// no memory of time, as the stateless [`super::assess`], which reads
    /// the taus from `geometry` afterwards): the firmness gates are open.
    pub(crate) fn assess_state(
        &mut self,
        cycle: &Cycle<S>,
        geometry: &mut RangeGeometry<S>,
        miss_distance_m: Option<S>,
        altitude: Option<AltitudeEstimate<S>>,
        dt: Option<S>,
    ) -> Result<ThreatStatus<S>, TcasError> {
        // `map`, not `?`: its temporaries copy the measures through a
        // library call at every assessment.
        vertical_measures(&cycle.own, altitude).map(|vertical| {
            let inputs = Inputs {
                miss_distance: MissDistances::both(miss_distance_m),
                altitude,
                vertical,
                firm_for_ta: true,
                firm_for_ra: true,
            };
            self.evaluate(cycle, geometry, &inputs, dt)
        })
    }

    /// The tests of one cycle; `geometry.r` ≥ 0 and valid and the vertical
    /// measures formed, as both callers check: it cannot fail.
    fn evaluate(
        &mut self,
        cycle: &Cycle<S>,
        g: &mut RangeGeometry<S>,
        inputs: &Inputs<S>,
        dt: Option<S>,
    ) -> ThreatStatus<S> {
        let own = &cycle.own;
        let continuing_threat = self.hits != ThreatHits::None;
        let thresholds = &cycle.thresholds;
        let k = &thresholds.constants;
        let vertical = inputs.vertical;
        let on_ground = match (inputs.altitude, own.radio_altitude_ft) {
            (Some(a), Some(radio)) => {
                let ground = own.pressure_altitude_ft - radio;
                a.altitude_ft - ground < k.on_ground_height_ft
            }
            _ => false,
        };

        // Traffic advisory.
        let had_ta = self.has_ta;
        let ta = &thresholds.ta;
        let ta_dmod_m = if had_ta {
            thresholds.ta_held_dmod_m
        } else {
            ta.dmod_m
        };
        let ta_range = range_hit(g, ta_dmod_m, ta);
        let ta_tests = match &vertical {
            Some(v) => {
                ta_range
                    && ta_vertical_hit(
                        v.relative_altitude_ft,
                        v.relative_rate_ft_per_s,
                        ta.zthr_ft,
                        ta.tau_s,
                        k,
                    )
            }
            None => ta_range && own.pressure_altitude_ft < k.non_reporting_ta_ceiling_ft,
        };

        // Resolution advisory (never against a non-reporting intruder):
        // whether the hit tests pass, and the geometry the resolution
        // logic models; `None` when no RA can be evaluated (SL 2, no
        // altitude), which ends a threat at once (DO-185B
        // `detect_conflicts`: a threat that loses its altitude ends).
        let mut status_filtered = false;
        let ra_tests = match (&thresholds.ra, &vertical, inputs.altitude) {
            (Some(limits), Some(v), Some(a)) => {
                let ra = &limits.alert;
                // τ_mod and the true tau under the tau cap, capped at 60 s
                // (TAU ≤ 35 s): the range test, the miss-distance filter's
                // 35 s limit, the vertical tests and the model use them.
                let (modified_tau, true_tau) =
                    self.capped_taus(g, ra.dmod_m, inputs.firm_for_ta, k);
                let range_ok = if g.diverging {
                    range_hit(g, ra.dmod_m, ra)
                } else {
                    g.r <= k.max_ra_range_m
                        && modified_tau < ra.tau_s
                        // DO-185B `TAURISE`: not a new threat outside DMOD
                        // while its true tau keeps rising.
                        && (continuing_threat
                            || self.tau_rise_cycles < TAU_RISE_CYCLES
                            || g.r < ra.dmod_m)
                };
                let filtered = self.miss_distance.filters(
                    &inputs.miss_distance,
                    modified_tau,
                    continuing_threat,
                    limits,
                    k,
                ) && range_ok;
                status_filtered = filtered;
                let range_hit = range_ok && !filtered;
                // A continuing threat skips the vertical test (DO-185B
                // `hit_or_miss_test`, KHIT > 0).
                let vertical_hit = continuing_threat || {
                    let (h, hdot) = (v.relative_altitude_ft, v.relative_rate_ft_per_s);
                    // h itself when the range opens.
                    let vmd = if g.rdot > S::ZERO {
                        h
                    } else {
                        vertical_miss_distance(
                            h,
                            hdot,
                            true_tau,
                            modified_tau,
                            limits.vmd_tau_limit_s,
                        )
                    };
                    let threshold = ra_vertical_tau(
                        own.vertical_rate_ft_per_s,
                        a.vertical_rate_ft_per_s,
                        limits.level_own_vertical_tau_s,
                        ra.tau_s,
                        k,
                    );
                    ra_vertical_hit(
                        h,
                        hdot,
                        a.vertical_rate_ft_per_s,
                        vmd,
                        threshold,
                        ra.zthr_ft,
                        true_tau,
                        k,
                    )
                };
                // The model's taus (DO-185B `model_sep`: `TRTRU` and
                // `TAUR` capped at TVPE; `MINTAU` = 0 for a diverging
                // intruder, whose separation is modelled now).
                let cap = limits.model_tau_limit_s;
                let geometry = ThreatGeometry {
                    intruder: a,
                    range_tau_s: cap.min_of(true_tau),
                    modified_tau_s: cap.min_of(modified_tau),
                };
                Some((range_hit && vertical_hit, geometry))
            }
            _ => None,
        };

        // DO-185B `set_up_working_list`: a hit makes or keeps a threat
        // (KHIT 3); a threat's first miss keeps it (KHIT 1), its next ends
        // it once `TMIN` has passed since it became one.
        if continuing_threat {
            if let Some(dt) = dt {
                self.threat_age_s = self.threat_age_s + dt;
            }
        }
        let mut held_by_firmness = false;
        let (hits, geometry) = match ra_tests {
            None => (ThreatHits::None, None),
            Some(_) if on_ground => (ThreatHits::None, None),
            Some((true, _)) if !continuing_threat && !inputs.firm_for_ra => {
                held_by_firmness = true;
                (ThreatHits::None, None)
            }
            Some((true, geometry)) => (ThreatHits::Hit, Some(geometry)),
            Some((false, geometry)) => match self.hits {
                ThreatHits::Hit => (ThreatHits::Missed, Some(geometry)),
                ThreatHits::Missed if self.threat_age_s <= k.min_threat_time_s => {
                    (ThreatHits::Missed, Some(geometry))
                }
                _ => (ThreatHits::None, None),
            },
        };
        if !continuing_threat {
            self.threat_age_s = S::ZERO;
        }
        self.hits = hits;
        let ra_now = hits != ThreatHits::None;

        let ta_start = ta_tests && (had_ta || inputs.firm_for_ta);
        held_by_firmness |= ta_tests && !had_ta && !inputs.firm_for_ta;
        let held_by_min_time = match (self.ta_age(), dt) {
            (Some(age), Some(dt)) => age + dt < k.min_ta_time_s,
            _ => false,
        };
        let ta_now = !on_ground && (ta_start || ra_now || (had_ta && held_by_min_time));
        let ta_age = match (ta_now, self.ta_age(), dt) {
            (false, _, _) => None,
            (true, None, _) => Some(S::ZERO),
            (true, Some(age), Some(dt)) => Some(age + dt),
            (true, Some(age), None) => Some(age),
        };
        self.set_ta_age(ta_age);

        let proximate = g.r <= k.proximate_range_m
            && vertical.is_none_or(|v| v.relative_altitude_ft.abs() <= k.proximate_altitude_ft);
        let advisory = if ra_now {
            Advisory::Resolution
        } else if ta_now {
            Advisory::Traffic
        } else if proximate {
            Advisory::ProximateTraffic
        } else {
            Advisory::None
        };
        ThreatStatus {
            advisory,
            new_traffic: ta_now && !had_ta,
            miss_distance_m: if continuing_threat {
                inputs.miss_distance.continuing
            } else {
                inputs.miss_distance.new_threat
            },
            miss_distance_filtered: status_filtered,
            held_by_firmness,
            vertical,
            geometry,
        }
    }
}
