//! The TCAS range tracker's gains (beyond the papers): α, β, γ indexed by
//! track *firmness*, from the public RTCA DO-185B figures.

use super::{GainContext, GainSchedule, ScheduleError};
use crate::filter::{Gains, Phase};
use crate::num::{Numeric, Real};

/// α by firmness 0..=8.
pub const FIRMNESS_ALPHA: [f64; 9] = [1.0, 1.0, 0.83, 0.7, 0.6, 0.46, 0.4, 0.4, 0.4];
/// β by firmness 0..=8.
pub const FIRMNESS_BETA: [f64; 9] = [0.0, 1.0, 0.5, 0.3, 0.2, 0.11, 0.1, 0.1, 0.1];
/// γ by firmness 0..=8.
pub const FIRMNESS_GAMMA: [f64; 9] = [0.0, 0.0, 0.16, 0.07, 0.035, 0.013, 0.01, 0.01, 0.01];
/// The highest firmness.
pub const MAX_FIRMNESS: u8 = 8;

/// TCAS range-tracker gains by track firmness: +1 per valid report, −1 per
/// miss, within 0..=8; the gains of a report are the table entry at the
/// firmness before the report is counted.
///
/// # Firmness 0 and 1
///
/// Entry 0 (α = 1, β = 0, γ = 0) takes the report as the position and
/// estimates no velocity; entry 1 (α = 1, β = 1, γ = 0) then sets the
/// velocity to v_p + (z − x_p)/T = (z₂ − z₁)/T. Together they *are* two-point
/// initialisation (Al-Wagih & Abdulla eqs. 9–10), which is how the filter
/// starts a track, ignoring gains; so on a new track entries 0 and 1 are
/// never turned into [`Gains`] (β = 0 and γ = 0 lie on the boundary of the
/// strict stability region, which [`Gains`] refuses, and stays refusing).
///
/// Misses can bring an established track back to firmness 1 or 0:
///
/// * firmness 0: the track has no confirmed position left;
///   [`restart_required`](GainSchedule::restart_required) is true and
///   [`super::ScheduledFilter`] restarts it, so the report becomes a first
///   point, which is entry 0's effect on position (DO-185B would keep the
///   coasted velocity; a restart estimates it afresh from the next report,
///   as entry 1 would).
/// * firmness 1 on a tracking filter: entry 1 is applied as the αβ gains
///   α = 1, β = 1, which lie strictly inside the αβ stability triangle
///   (2·1 + 1 = 3 < 4) and are built by [`Gains::alpha_beta`] with its full
///   check; γ = 0 means this one update leaves the acceleration as
///   predicted, which is DO-185B's entry. It happens at most once before the
///   firmness is back at 2.
///
/// Entries 2–8 are inside the strict αβγ volume (Tenne & Singh eqs. 7–8):
/// e.g. entry 2, γ = 0.16 < 4·0.83·0.5/(2 − 0.83) = 1.42; entry 6–8,
/// 0.01 < 4·0.4·0.1/1.6 = 0.1 (tested).
///
/// # γ convention
///
/// abtrack's acceleration correction is γ/(2T²)·e (Tenne & Singh eq. 5) and
/// the table's γ is used in it as given. DO-185B's range tracker corrects
/// by γ·e/T² ([`crate::tcas`]'s range tracker, tested), so with these values
/// this schedule corrects acceleration half as much as that tracker. The
/// values are inside the stability volume under both conventions
/// (γ/(2T²) here, γ/T² in the range tracker). The entries
/// do satisfy γ ≈ β²/(2α) (e.g. 0.5²/1.66 = 0.151 vs 0.16; 0.1²/0.8 = 0.0125
/// vs 0.01) to within the table's rounding.
///
/// With an αβ filter (`--filter ab`), γ is ignored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FirmnessGains {
    firmness: u8,
}

impl FirmnessGains {
    /// A new track, firmness 0.
    pub const fn new() -> Self {
        FirmnessGains { firmness: 0 }
    }

    /// The current firmness, 0 to [`MAX_FIRMNESS`] (DO-185B `CASFIRM`).
    pub fn firmness(&self) -> u8 {
        self.firmness
    }

    /// The gains of table entry `firmness` ≥ 2 (αβγ).
    pub fn table_gains<N: Numeric>(firmness: u8) -> Result<Gains<N>, ScheduleError> {
        // (No `clamp`: its argument check is a panic path.)
        #[allow(clippy::manual_clamp)]
        let i = usize::from(firmness.max(2).min(MAX_FIRMNESS));
        match (
            FIRMNESS_ALPHA.get(i),
            FIRMNESS_BETA.get(i),
            FIRMNESS_GAMMA.get(i),
        ) {
            (Some(&a), Some(&b), Some(&g)) => Ok(Gains::alpha_beta_gamma_f64(a, b, g)?),
            _ => Err(ScheduleError::InvalidContext),
        }
    }

    fn count_report(&mut self) {
        self.firmness = self.firmness.saturating_add(1).min(MAX_FIRMNESS);
    }
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for FirmnessGains {
    fn gains(&self, _ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        let g = match self.firmness {
            0 => return Err(ScheduleError::RestartRequired),
            1 => Gains::alpha_beta(N::Ratio::ONE, N::Ratio::ONE)?,
            f => Self::table_gains(f)?,
        };
        Ok([g; D])
    }

    fn accepted(&mut self, _ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        self.count_report();
    }

    fn initialised(&mut self, _n: u32, _dt: N::Interval) {
        self.count_report();
    }

    fn missed(&mut self, _dt: N::Interval) {
        self.firmness = self.firmness.saturating_sub(1);
    }

    fn restart_required(&self, phase: Phase) -> bool {
        self.firmness == 0 && phase != Phase::Empty
    }

    fn reset(&mut self) {
        self.firmness = 0;
    }
}
