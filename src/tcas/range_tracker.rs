//! The TCAS II range tracker: range, range rate and range acceleration from
//! the slant-range replies of one intruder, with α, β, γ scheduled by track
//! firmness (RTCA DO-185B, as transcribed in ledieuke/tcas_simulator
//! `tracking_intruders.py`: `horizontal_tracking`, `smoother`,
//! `update_firmness`, `coast_horizontal_track`, `calc_acc_thresh`,
//! `project_hmd`, `linear_extrap`; the gain table is [`crate::gain::tcas`]).
//!
//! * γ convention: DO-185B's smoother corrects the acceleration by γ·e/T²
//!   (`smoother`: `srdd = srddp + gamma*residual/dt**2`), and that is what
//!   this tracker does with the table's γ (abtrack's αβγ filter uses
//!   Tenne & Singh's γ/(2T²)·e, so the same table entry there is half the
//!   correction).
//! * Prediction: DO-185B keeps two range trackers with the same gains, a
//!   parabolic one (r + ṙT + r̈T²/2) whose r̈ gives the miss distance, and a
//!   "Cartesian" one whose prediction follows a straight relative path
//!   (`linear_extrap`). This tracker is one tracker with the straight-path
//!   prediction once r̈ > 0 is estimated (parabolic before): with the
//!   table's small γ the parabolic r̈ lags so much that the miss-distance
//!   filter never acts (docs/tcas.md has the figures), while the
//!   straight-path prediction is exact for an unaccelerated intruder.
//! * Bearing is not used here; the range–azimuth filter is the bearing
//!   tracker (docs/tcas.md).
//!
//! No square of a range is formed: the straight-path prediction works with
//! the miss distance d = r·√(r r̈/(r r̈ + ṙ²)) and the along-track distance
//! y = r ṙ/v, and r' = hypot(d, y + vT).

use crate::filter::altitude::OutOfLine;
use crate::filter::{check_interval, FilterError, Phase};
use crate::gain::tcas::{FIRMNESS_ALPHA, FIRMNESS_BETA, FIRMNESS_GAMMA, MAX_FIRMNESS};
use crate::num::{hypot, Numeric, Scalar};

use super::METRES_PER_FOOT;

/// Firmness a track needs before it can raise a new advisory, and below
/// which it stops using the range acceleration (DO-185B `MININITHFIRM`).
pub const MIN_ALERT_FIRMNESS: u8 = 3;
/// Nominal range-acceleration threshold for the miss-distance estimate,
/// ft/s² (DO-185B `P_ACCTHR`).
pub const ACCELERATION_THRESHOLD_FT_PER_S2: f64 = 1.5;
/// Nominal standard deviation of the range residual, ft (DO-185B
/// `P_RESSD_N`): the threshold grows in proportion above it.
pub const NOMINAL_RESIDUAL_SIGMA_FT: f64 = 35.0;
/// Weight of a new squared residual in its running mean (DO-185B
/// `P_ALPHARESSQ`).
pub const RESIDUAL_SMOOTHING: f64 = 0.1;
/// σ of the firm track's r̈ per σ of its range residual, at T = 1 s
/// (scales as 1/T²): the steady state of the firmness-8 gains (α 0.4,
/// β 0.1, γ 0.01 with DO-185B's γ·e/T²) on white range noise, r̈ σ
/// 0.014 20·σ_R and residual σ 1.225 6·σ_R (the Lyapunov equation of the
/// error; `tests/it/tcas/logic.rs` solves it again). Ours: DO-185B gives
/// r̈ no σ.
pub const ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA: f64 = 0.011_586;
/// σ of the firm track's ṙ per σ of its range residual, at T = 1 s
/// (scales as 1/T): the same steady state, ṙ σ 0.140 57·σ_R. Ours.
pub const RATE_SIGMA_PER_RESIDUAL_SIGMA: f64 = 0.114_692;
/// The correlation of the firm track's ṙ and r̈ errors in that steady
/// state (both follow the same residuals). Ours.
pub const RATE_ACCELERATION_ERROR_CORRELATION: f64 = 0.959_645;
/// √(1 − ρ²) of [`RATE_ACCELERATION_ERROR_CORRELATION`]: the share of the ṙ
/// error's σ that r̈'s does not explain (a constant, so that no cycle takes
/// a square root).
pub const RATE_ERROR_UNCORRELATED_SHARE: f64 = 0.281_214;
/// Residuals are clipped to this magnitude before squaring, m (a reply
/// far off the track is a gate's business, and the square stays within
/// Q32.32's range).
pub const RESIDUAL_CLIP_M: f64 = 1000.0;

/// What the range tracker knows about one intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeEstimate<S> {
    /// Slant range r, m.
    pub range_m: S,
    /// ṙ, m/s (negative closing).
    pub range_rate_m_per_s: S,
    /// r̈, m/s²; zero until the track is initialised.
    pub range_acceleration_m_per_s2: S,
    /// 0..=8: +1 per reply, −1 per scan without one.
    pub firmness: u8,
    /// The track reached firmness 8 and has not fallen below 3 since: the
    /// acceleration is estimated (DO-185B `init`).
    pub initialised: bool,
    /// Range acceleration above which the miss distance is projected,
    /// m/s² (DO-185B `rhoddthr`).
    pub acceleration_threshold_m_per_s2: S,
    /// RMS of the range residuals, m (√ of DO-185B `smoressq`; the
    /// nominal 35 ft until the track is initialised).
    pub residual_sigma_m: S,
}

impl<S: Scalar> RangeEstimate<S> {
    /// The horizontal miss distance the range track implies, m, for a
    /// straight relative path: r·r̈ = v² − ṙ² gives
    /// HMD² = r²·(r·r̈)/(r·r̈ + ṙ²) (DO-185B `project_hmd`), computed as
    /// r·√(x/(x + ṙ²)) with x = r·r̈ so no r² is formed. `None` until the
    /// track is initialised or while r̈ is at or below the threshold (the
    /// filter is then off, as DO-185B's `HMD_DISABLE_VAL`).
    pub fn miss_distance_m(&self) -> Option<S> {
        if !self.initialised
            || self.range_acceleration_m_per_s2 <= self.acceleration_threshold_m_per_s2
        {
            return None;
        }
        let x = self.range_m.times(self.range_acceleration_m_per_s2);
        let rate = self.range_rate_m_per_s;
        let ratio = x.over(x + rate.times(rate));
        let hmd = self.range_m.times(ratio.sqrt());
        if hmd.is_valid() {
            Some(hmd)
        } else {
            None
        }
    }
}

/// The range tracker of one intruder (see the module docs), computing in
/// `N::Wide` ([`Numeric::Wide`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeTracker<N: Numeric> {
    phase: Phase,
    range_m: N::Wide,
    range_rate_m_per_s: N::Wide,
    range_acceleration_m_per_s2: N::Wide,
    /// While `OnePoint`: time since the first reply (coasts add to it).
    since_first_s: N::Wide,
    firmness: u8,
    initialised: bool,
    /// Running mean of the squared range residual, m² (DO-185B `smoressq`).
    residual_mean_square_m2: N::Wide,
    saturations: u32,
}

/// A predicted range state.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Predicted<S> {
    range: S,
    rate: S,
    acceleration: S,
}

impl<N: Numeric<Wide = S>, S: Scalar> Default for RangeTracker<N> {
    fn default() -> Self {
        Self::new()
    }
}

fn nominal_residual_variance<S: Scalar>() -> S {
    let sigma = NOMINAL_RESIDUAL_SIGMA_FT * METRES_PER_FOOT;
    S::from_f64_lossy(sigma * sigma)
}

impl<N: Numeric<Wide = S>, S: Scalar> RangeTracker<N> {
    /// A tracker waiting for its first reply.
    pub fn new() -> Self {
        RangeTracker {
            phase: Phase::Empty,
            range_m: S::ZERO,
            range_rate_m_per_s: S::ZERO,
            range_acceleration_m_per_s2: S::ZERO,
            since_first_s: S::ZERO,
            firmness: 0,
            initialised: false,
            residual_mean_square_m2: nominal_residual_variance(),
            saturations: 0,
        }
    }

    /// The track's phase: empty, one reply, or tracking.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// Track firmness, 0..=8: +1 per reply, −1 per scan without one (DO-185B
    /// `update_firmness`).
    pub fn firmness(&self) -> u8 {
        self.firmness
    }

    /// How many updates or coasts were discarded because they saturated.
    pub fn saturations(&self) -> u32 {
        self.saturations
    }

    /// The current estimate; `None` before the second reply (no range rate).
    pub fn estimate(&self) -> Option<RangeEstimate<S>> {
        if self.phase != Phase::Tracking {
            return None;
        }
        let nominal = nominal_residual_variance::<S>();
        let threshold = S::from_f64_lossy(ACCELERATION_THRESHOLD_FT_PER_S2 * METRES_PER_FOOT);
        // max(ACCTHR, ACCTHR·σ/σ_n) = ACCTHR·max(1, √(ms/σ_n²)).
        let scale = (self.residual_mean_square_m2.over(nominal))
            .sqrt()
            .max_of(S::ONE);
        let residual_sigma_m = self.residual_mean_square_m2.sqrt();
        Some(RangeEstimate {
            range_m: self.range_m,
            range_rate_m_per_s: self.range_rate_m_per_s,
            range_acceleration_m_per_s2: self.range_acceleration_m_per_s2,
            firmness: self.firmness,
            initialised: self.initialised,
            acceleration_threshold_m_per_s2: threshold.times(scale),
            residual_sigma_m,
        })
    }

    /// The state `dt` ahead: along a straight relative path when the track
    /// is initialised and r̈ > 0 (r r̈ = v² − ṙ², DO-185B `linear_extrap`),
    /// parabolic otherwise.
    fn predict(&self, dt: S) -> Predicted<S> {
        let (r, rate, acc) = (
            self.range_m,
            self.range_rate_m_per_s,
            self.range_acceleration_m_per_s2,
        );
        if self.initialised && acc > S::ZERO && r > S::ZERO {
            let x = r.times(acc);
            let speed_squared = x + rate.times(rate);
            let speed = speed_squared.sqrt();
            let miss = r.times(x.over(speed_squared).sqrt());
            let along = r.times(rate.over(speed)) + speed.times(dt);
            let range = hypot(miss, along);
            if range > S::ONE {
                let k = miss.over(range).times(speed);
                return Predicted {
                    range,
                    rate: along.times(speed.over(range)),
                    acceleration: k.times(k).over(range),
                };
            }
        }
        let half = S::from_f64_lossy(0.5);
        Predicted {
            range: r + rate.times(dt) + half.times(acc).times(dt).times(dt),
            rate: rate + acc.times(dt),
            acceleration: acc,
        }
    }

    /// One reply: slant range `range_m` (m, ≥ 0), `dt` s after the previous
    /// scan. Invalid input, or an update whose arithmetic saturates
    /// (counted), is refused and changes nothing.
    pub fn update(&mut self, range_m: S, dt: S) -> Result<(), FilterError> {
        if !range_m.is_valid() || range_m < S::ZERO {
            return Err(FilterError::InvalidMeasurement);
        }
        check_interval(dt)?;
        let mut next = *self;
        match self.phase {
            Phase::Empty => {
                next.phase = Phase::OnePoint;
                next.range_m = range_m;
                next.since_first_s = S::ZERO;
                next.firmness = 0;
            }
            Phase::OnePoint => {
                // Entry 1 (α = β = 1): two-point initialisation.
                next.phase = Phase::Tracking;
                next.range_rate_m_per_s = (range_m - self.range_m).over(self.since_first_s + dt);
                next.range_m = range_m;
                next.range_acceleration_m_per_s2 = S::ZERO;
                next.firmness = 1;
            }
            Phase::Tracking => {
                let firmness = self.firmness.saturating_add(1).min(MAX_FIRMNESS);
                let initialised = self.initialised || firmness == MAX_FIRMNESS;
                let (alpha, beta, gamma) = table_gains::<S>(firmness.max(1))?;
                let p = self.predict(dt);
                let e = range_m - p.range;
                next.range_m = p.range + alpha.times(e);
                next.range_rate_m_per_s = p.rate + beta.times(e).over(dt);
                // DO-185B holds r̈ at zero until the track is initialised.
                next.range_acceleration_m_per_s2 = if initialised {
                    p.acceleration + gamma.times(e).over(dt.times(dt))
                } else {
                    S::ZERO
                };
                if initialised && self.initialised {
                    let clip = S::from_f64_lossy(RESIDUAL_CLIP_M);
                    let e = e.max_of(-clip).min_of(clip);
                    let w = S::from_f64_lossy(RESIDUAL_SMOOTHING);
                    next.residual_mean_square_m2 =
                        w.times(e).times(e) + (S::ONE - w).times(self.residual_mean_square_m2);
                }
                next.firmness = firmness;
                next.initialised = initialised;
            }
        }
        next.clamp_range();
        if !next.is_valid() {
            self.saturations = self.saturations.saturating_add(1);
            return Err(FilterError::Saturated);
        }
        *self = next;
        Ok(())
    }

    /// A range is never negative: through closest approach the estimate can
    /// overshoot zero; DO-185B then takes r = 0 and ṙ ≥ 0.
    fn clamp_range(&mut self) {
        if self.range_m < S::ZERO {
            self.range_m = S::ZERO;
            self.range_rate_m_per_s = self.range_rate_m_per_s.max_of(S::ZERO);
        }
    }

    fn is_valid(&self) -> bool {
        [
            self.range_m,
            self.range_rate_m_per_s,
            self.range_acceleration_m_per_s2,
            self.since_first_s,
            self.residual_mean_square_m2,
        ]
        .iter()
        .all(|v| v.is_valid())
    }

    /// No reply this scan: predict `dt` ahead and lose one firmness; below
    /// [`MIN_ALERT_FIRMNESS`] the track is no longer initialised and its
    /// acceleration is dropped (DO-185B `coast_horizontal_track`).
    pub fn coast(&mut self, dt: S) -> Result<(), FilterError> {
        check_interval(dt)?;
        let mut next = *self;
        match self.phase {
            Phase::Empty => return Ok(()),
            Phase::OnePoint => next.since_first_s = self.since_first_s + dt,
            Phase::Tracking => {
                let p = self.predict(dt);
                next.range_m = p.range;
                next.range_rate_m_per_s = p.rate;
                next.range_acceleration_m_per_s2 = p.acceleration;
                next.firmness = self.firmness.saturating_sub(1);
                if next.firmness < MIN_ALERT_FIRMNESS && self.initialised {
                    next.initialised = false;
                    next.range_acceleration_m_per_s2 = S::ZERO;
                    next.residual_mean_square_m2 = nominal_residual_variance();
                }
            }
        }
        next.clamp_range();
        if !next.is_valid() {
            self.saturations = self.saturations.saturating_add(1);
            return Err(FilterError::Saturated);
        }
        *self = next;
        Ok(())
    }
}

/// The table entry of the reply that raises the firmness to `firmness`
/// (DO-185B applies the entry after counting the reply), in `S`. One arm per
/// entry, so each entry's conversions fold at compile time into constants
/// of S where the conversion inlines (a conversion at run time per gain and
/// update otherwise).
#[inline(always)]
fn table_gains<S: Scalar>(firmness: u8) -> Result<(S, S, S), FilterError> {
    let [a0, a1, a2, a3, a4, a5, a6, a7, a8] = FIRMNESS_ALPHA;
    let [b0, b1, b2, b3, b4, b5, b6, b7, b8] = FIRMNESS_BETA;
    let [g0, g1, g2, g3, g4, g5, g6, g7, g8] = FIRMNESS_GAMMA;
    Ok(match firmness {
        0 => gains(a0, b0, g0),
        1 => gains(a1, b1, g1),
        2 => gains(a2, b2, g2),
        3 => gains(a3, b3, g3),
        4 => gains(a4, b4, g4),
        5 => gains(a5, b5, g5),
        6 => gains(a6, b6, g6),
        7 => gains(a7, b7, g7),
        8 => gains(a8, b8, g8),
        _ => return Err(FilterError::Saturated),
    })
}

/// One table entry's gains as S; inlined into each arm of [`table_gains`]
/// so that the conversions of its constants fold.
#[inline(always)]
fn gains<S: Scalar>(alpha: f64, beta: f64, gamma: f64) -> (S, S, S) {
    (
        S::from_f64_lossy(alpha),
        S::from_f64_lossy(beta),
        S::from_f64_lossy(gamma),
    )
}
