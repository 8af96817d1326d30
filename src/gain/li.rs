//! Li, Zhao, Liang & Zhang, "An Improved α-β Filter for Maneuvering Target
//! Tracking": gains from an effective scan count that a motion-stability
//! ratio raises while the target moves steadily and cuts when it manoeuvres.

use super::al_wagih::{least_squares_alpha, LeastSquaresConfig};
use super::{
    check_range, config_quantity, norm, ConfigError, GainContext, GainSchedule, ScheduleError,
};
use crate::filter::Gains;
use crate::num::{Numeric, Quantity, Real};

pub use crate::gains::li_beta;

/// Configuration of [`LiImprovedGains`] (`li-improved`). The paper gives
/// none of these values.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LiImprovedConfig {
    /// R, the largest motion-stability ratio d/Δd still taken as steady
    /// motion (eq. 13–14), in (0, 10⁶]. Default 3 (a three-"sigma" gate).
    pub max_ratio: f64,
    /// Δρ, the range (radius) error in metres (eq. 11), in (0, 10⁶]. Default 1 m,
    /// the noise standard deviation of the paper's simulation.
    pub range_error: f64,
    /// Δθ, the bearing error in radians (eq. 11), in [0, 1]. Default 0: the
    /// paper's simulation adds Cartesian noise, whose error is covered by Δρ.
    pub bearing_error: f64,
    /// Upper bound of the effective scan count (not in the paper), 3..=10 000,
    /// as for [`super::al_wagih::LeastSquaresConfig::n_max`]. Default 1000.
    pub k_max: u32,
}

impl LiImprovedConfig {
    /// R = 3, Δρ = 1 m, Δθ = 0, k_max = 1000.
    pub const DEFAULT: Self = LiImprovedConfig {
        max_ratio: 3.0,
        range_error: 1.0,
        bearing_error: 0.0,
        k_max: 1000,
    };

    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range(self.max_ratio, 0.0, 1.0e6, false, "r")?;
        check_range(self.range_error, 0.0, 1.0e6, false, "range-error")?;
        check_range(self.bearing_error, 0.0, 1.0, true, "bearing-error")?;
        if !(3..=LeastSquaresConfig::N_MAX_LIMIT).contains(&self.k_max) {
            return Err(ConfigError::OutOfRange { parameter: "k-max" });
        }
        Ok(())
    }
}

/// Li et al.'s improved αβ filter, as a schedule.
///
/// # Equations
///
/// * α = 2(2k − 1)/(k(k + 1)) (eq. 4) and β = 2(1 − √(1 − α))² (eqs. 7–8),
///   one pair for both axes (eq. 3), from the effective scan count k.
/// * λ = √α (eq. 12), the scale of the wave gate.
/// * d = ‖z − x_p‖ over the axes (eq. 10); Δd = λ·√(Δρ² + ρ²Δθ²) (eq. 11),
///   ρ = ‖x_p‖ the range of the predicted position (sensor at the origin).
/// * r = d/Δd (eq. 13). If r ≤ R the motion is steady and k grows by 1;
///   otherwise k falls by Δr = round((r − R)·r) (eqs. 14–15).
///
/// # Reading
///
/// The paper uses r_k for two things: the ratio d/Δd of eq. (13), and the
/// quantity that "+1" and eq. (15) update, from which "we can get the values
/// of α, β and λ". A ratio recomputed from d and Δd every scan cannot be
/// incremented, and α, β of eqs. (4), (8) are functions of a scan count, so
/// the consistent reading has two quantities: the ratio r = d/Δd of this
/// scan, compared with R, and an *effective scan count* k, which replaces the
/// scan count in eqs. (4), (8), (12), is incremented when r ≤ R and is
/// reduced by Δr = round((r − R)r) (eq. 14 evaluated on the ratio, the only
/// quantity for which r − R > 0 is the manoeuvre condition) otherwise.
/// "Target maneuvers increase with the decreasing r_k" then reads correctly
/// for the count: a manoeuvre lowers k and raises α, β, λ.
///
/// Following §4's order, the gains of scan k come from the count before the
/// scan (gains first), and the ratio uses the λ of those gains; the count is
/// then updated for the next scan. With r ≤ R every scan the schedule is the
/// standard filter's count k = n, started at 3 where §3 says the filter
/// "can regularly work from the 3rd scan"; the count is kept in 3..=k_max, so
/// α ≤ 5/6 and β(3) = 2(1 − √(1/6))² ≈ 0.7003 is the largest β (k = 1, 2 give
/// α = 1, β = 2, on the stability boundary 2α + β = 4).
///
/// The wave gate of §4 ("λΔx × λΔy") is exposed as [`Self::gate_scale`]
/// and [`Self::distance_error`]; gating itself is the tracker's.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LiImprovedGains<N: Numeric> {
    max_ratio: N::Ratio,
    range_error: N::Length,
    bearing_error: N::Ratio,
    k_max: u32,
    count: u32,
    last_ratio: Option<N::Ratio>,
}

/// The effective scan count at the first filtered update.
const FIRST_COUNT: u32 = 3;

impl<N: Numeric> LiImprovedGains<N> {
    /// Li et al.'s improved schedule as `c` configures it, at scan count 3.
    pub fn new(c: &LiImprovedConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        Ok(LiImprovedGains {
            max_ratio: config_quantity(c.max_ratio, "r")?,
            range_error: config_quantity(c.range_error, "range-error")?,
            bearing_error: config_quantity(c.bearing_error, "bearing-error")?,
            k_max: c.k_max,
            count: FIRST_COUNT,
            last_ratio: None,
        })
    }

    /// The effective scan count k for the next update.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The ratio r = d/Δd of the last accepted update (eq. 13).
    pub fn last_ratio(&self) -> Option<N::Ratio> {
        self.last_ratio
    }

    /// α and β for the effective count k (eqs. 4, 8).
    pub fn gains_for_count(k: u32) -> Result<Gains<N>, ScheduleError> {
        let alpha = least_squares_alpha::<N::Ratio>(k);
        Ok(Gains::alpha_beta(alpha, li_beta(alpha))?)
    }

    /// λ = √α (eq. 12) of the next update: the factor by which the wave
    /// gate is scaled.
    pub fn gate_scale(&self) -> N::Ratio {
        least_squares_alpha::<N::Ratio>(self.count).sqrt()
    }

    /// Δd = λ·√(Δρ² + ρ²Δθ²) (eq. 11) of the next update at predicted range
    /// ρ. Computed as a scaled norm, so ρΔθ may be large in fixed point.
    pub fn distance_error(&self, predicted_range: N::Length) -> N::Length {
        self.gate_scale() * norm::<N>(&[self.range_error, self.bearing_error * predicted_range])
    }
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for LiImprovedGains<N> {
    fn gains(&self, _ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        Ok([Self::gains_for_count(self.count)?; D])
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        let d = norm::<N>(&ctx.innovations());
        let range = norm::<N>(&ctx.predicted_positions());
        let ratio = d / self.distance_error(range);
        self.last_ratio = Some(ratio);
        if ratio.is_valid() && ratio <= self.max_ratio {
            self.count = self.count.saturating_add(1).min(self.k_max);
            return;
        }
        // Δr = round((r − R)·r) (eq. 14), in N: the count only needs Δr up
        // to count − 3, found by bisection on Δr ≥ k − ½ (round half away
        // from zero; Δr > 0 here). An invalid product (a ratio far beyond R,
        // or no ratio) drops the count to its floor.
        let drop = (ratio - self.max_ratio) * ratio;
        let reaches = |k: u32| {
            // k − ½ = (2k − 1)/2, exact in every format for k ≤ k_max.
            let threshold =
                N::Ratio::from_ratio(u64::from(k).saturating_mul(2).saturating_sub(1), 2);
            !drop.is_valid() || drop >= threshold
        };
        // The largest k in [0, count − 3] with Δr ≥ k − ½ (k = 0 always).
        let (mut low, mut high) = (0u32, self.count.saturating_sub(FIRST_COUNT));
        while low < high {
            let middle = high.saturating_sub(high.saturating_sub(low) / 2);
            if reaches(middle) {
                low = middle;
            } else {
                high = middle.saturating_sub(1);
            }
        }
        self.count = self.count.saturating_sub(low).max(FIRST_COUNT);
    }

    fn reset(&mut self) {
        self.count = FIRST_COUNT;
        self.last_ratio = None;
    }
}
