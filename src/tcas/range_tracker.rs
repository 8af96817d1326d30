//! The TCAS II range tracker: range, range rate and range acceleration from
//! the slant-range replies of one intruder, with α, β, γ scheduled by track
//! firmness (RTCA DO-185B, as transcribed in ledieuke/tcas_simulator
//! `tracking_intruders.py`: `horizontal_tracking`, `smoother`,
//! `update_firmness`, `coast_horizontal_track`, `calc_acc_thresh`,
//! `project_hmd`; the gain table is [`crate::gain::tcas`]).
//!
//! γ convention: DO-185B's smoother corrects the acceleration by γ·e/T²;
//! abtrack's αβγ filter (Tenne & Singh eq. 5) by γ/(2T²)·e, so the table's γ
//! enters the filter as 2γ. Bearing is not used here (see docs/tcas.md).

use crate::filter::{check_interval, AlphaBetaGamma, FilterError, Gains, Phase, UpdateOutcome};
use crate::gain::tcas::{FIRMNESS_ALPHA, FIRMNESS_BETA, FIRMNESS_GAMMA, MAX_FIRMNESS};
use crate::num::Scalar;

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
        let x = self.range_m * self.range_acceleration_m_per_s2;
        let rate = self.range_rate_m_per_s;
        let ratio = x / (x + rate * rate);
        let hmd = self.range_m * ratio.sqrt();
        if hmd.is_valid() {
            Some(hmd)
        } else {
            None
        }
    }
}

/// The range tracker of one intruder (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeTracker<S> {
    filter: AlphaBetaGamma<S>,
    firmness: u8,
    initialised: bool,
    /// Running mean of the squared range residual, m² (DO-185B `smoressq`).
    residual_mean_square_m2: S,
    /// Saturations counted by a filter replaced when the track lost its
    /// acceleration.
    earlier_saturations: u32,
}

impl<S: Scalar> Default for RangeTracker<S> {
    fn default() -> Self {
        Self::new()
    }
}

fn nominal_residual_variance<S: Scalar>() -> S {
    let sigma = NOMINAL_RESIDUAL_SIGMA_FT * METRES_PER_FOOT;
    S::from_f64_lossy(sigma * sigma)
}

impl<S: Scalar> RangeTracker<S> {
    /// A tracker waiting for its first reply.
    pub fn new() -> Self {
        RangeTracker {
            filter: AlphaBetaGamma::new(),
            firmness: 0,
            initialised: false,
            residual_mean_square_m2: nominal_residual_variance(),
            earlier_saturations: 0,
        }
    }

    pub fn phase(&self) -> Phase {
        self.filter.phase()
    }

    pub fn firmness(&self) -> u8 {
        self.firmness
    }

    /// How many updates or coasts were discarded because they saturated.
    pub fn saturations(&self) -> u32 {
        self.filter
            .saturations()
            .saturating_add(self.earlier_saturations)
    }

    /// The current estimate; `None` before the second reply (no range rate).
    pub fn estimate(&self) -> Option<RangeEstimate<S>> {
        if self.filter.phase() != Phase::Tracking {
            return None;
        }
        let nominal = nominal_residual_variance::<S>();
        let threshold = S::from_f64_lossy(ACCELERATION_THRESHOLD_FT_PER_S2 * METRES_PER_FOOT);
        // max(ACCTHR, ACCTHR·σ/σ_n) = ACCTHR·max(1, √(ms/σ_n²)).
        let scale = (self.residual_mean_square_m2 / nominal)
            .sqrt()
            .max_of(S::ONE);
        Some(RangeEstimate {
            range_m: self.filter.position(),
            range_rate_m_per_s: self.filter.velocity(),
            range_acceleration_m_per_s2: self.filter.acceleration(),
            firmness: self.firmness,
            initialised: self.initialised,
            acceleration_threshold_m_per_s2: threshold * scale,
        })
    }

    /// One reply: slant range `range_m` (m, ≥ 0), `dt` s after the previous
    /// scan. Invalid input is refused and changes nothing.
    pub fn update(&mut self, range_m: S, dt: S) -> Result<(), FilterError> {
        if !range_m.is_valid() || range_m < S::ZERO {
            return Err(FilterError::InvalidMeasurement);
        }
        check_interval(dt)?;
        let firmness = if self.filter.phase() == Phase::Empty {
            0
        } else {
            self.firmness.saturating_add(1).min(MAX_FIRMNESS)
        };
        let initialised = self.initialised || firmness == MAX_FIRMNESS;
        let gains = table_gains(firmness.max(1), initialised)?;
        let outcome = self.filter.update(range_m, dt, &gains)?;
        if let (true, UpdateOutcome::Filtered(innovation)) = (initialised, outcome) {
            let clip = S::from_f64_lossy(RESIDUAL_CLIP_M);
            let e = innovation.residual.max_of(-clip).min_of(clip);
            let w = S::from_f64_lossy(RESIDUAL_SMOOTHING);
            let mean_square = w * e * e + (S::ONE - w) * self.residual_mean_square_m2;
            if mean_square.is_valid() {
                self.residual_mean_square_m2 = mean_square;
            }
        }
        self.firmness = firmness;
        self.initialised = initialised;
        Ok(())
    }

    /// No reply this scan: predict `dt` ahead and lose one firmness; below
    /// [`MIN_ALERT_FIRMNESS`] the track is no longer initialised and its
    /// acceleration is dropped (DO-185B `coast_horizontal_track`).
    pub fn coast(&mut self, dt: S) -> Result<(), FilterError> {
        self.filter.coast(dt)?;
        self.firmness = self.firmness.saturating_sub(1);
        if self.firmness < MIN_ALERT_FIRMNESS && self.initialised {
            self.initialised = false;
            self.residual_mean_square_m2 = nominal_residual_variance();
            if self.filter.phase() == Phase::Tracking {
                let rebuilt = AlphaBetaGamma::from_state(
                    self.filter.position(),
                    self.filter.velocity(),
                    S::ZERO,
                );
                if let Ok(f) = rebuilt {
                    self.earlier_saturations = self.saturations();
                    self.filter = f;
                }
            }
        }
        Ok(())
    }
}

/// The gains of the reply that raises the firmness to `firmness` (DO-185B
/// applies the entry after counting the reply). γ/T² as DO-185B, through
/// the filter's γ/(2T²): 2γ; before the track is initialised DO-185B holds
/// r̈ at zero, so the gains are αβ.
fn table_gains<S: Scalar>(firmness: u8, initialised: bool) -> Result<Gains<S>, FilterError> {
    let i = usize::from(firmness);
    let (Some(&a), Some(&b), Some(&g)) = (
        FIRMNESS_ALPHA.get(i),
        FIRMNESS_BETA.get(i),
        FIRMNESS_GAMMA.get(i),
    ) else {
        return Err(FilterError::Saturated);
    };
    let gains = if initialised && g > 0.0 {
        Gains::alpha_beta_gamma_f64(a, b, 2.0 * g)
    } else {
        Gains::alpha_beta_f64(a, b)
    };
    // Entries 1..=8 lie inside the stability region (tested), so a refusal
    // means the type cannot hold them.
    gains.map_err(|_| FilterError::Saturated)
}
