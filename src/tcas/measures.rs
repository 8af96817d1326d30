//! Threat measures: range tau, modified tau, closest point of approach and
//! vertical tau (FAA, "Introduction to TCAS II Version 7.1", 2011; DAIDALUS
//! `TCAS2D.cpp` `tau_mod`), computed without squares of ranges.

use super::{TcasError, CLOSURE_RATE_FLOOR_M_PER_S};
use crate::filter::altitude::OutOfLine;
use crate::num::{hypot, Scalar};

/// Closure speed for the taus, max(−ṙ, `floor`), or `None` when the
/// intruder is diverging, ṙ > `floor` (DO-185B `range_test`: one threshold,
/// `RDTHR`, for both; [`CLOSURE_RATE_FLOOR_M_PER_S`]).
pub(crate) fn floored_closure<S: Scalar>(range_rate: S, floor: S) -> Option<S> {
    if range_rate > floor {
        None
    } else {
        Some((-range_rate).max_of(floor))
    }
}

/// [`floored_closure`] at [`CLOSURE_RATE_FLOOR_M_PER_S`].
fn closure<S: Scalar>(range_rate: S) -> Option<S> {
    floored_closure(range_rate, S::from_f64_lossy(CLOSURE_RATE_FLOOR_M_PER_S))
}

pub(crate) fn all_valid<S: Scalar>(values: &[S]) -> Result<(), TcasError> {
    if values.iter().all(|v| v.is_valid()) {
        Ok(())
    } else {
        Err(TcasError::InvalidInput)
    }
}

pub(crate) fn valid_result<S: Scalar>(v: S) -> Result<S, TcasError> {
    if v.is_valid() {
        Ok(v)
    } else {
        Err(TcasError::Saturated)
    }
}

/// Range tau τ = r/max(−ṙ, 10 ft/s), s, for range `range_m` (m, ≥ 0) and
/// range rate `range_rate_m_per_s` (negative closing); `None` when the
/// intruder is diverging, ṙ > 10 ft/s (DO-185B `RDTHR`: an opening rate
/// below it counts as closing at the floor, as in the threat logic).
pub fn range_tau<S: Scalar>(range_m: S, range_rate_m_per_s: S) -> Result<Option<S>, TcasError> {
    all_valid(&[range_m, range_rate_m_per_s])?;
    if range_m < S::ZERO {
        return Err(TcasError::InvalidInput);
    }
    match closure(range_rate_m_per_s) {
        None => Ok(None),
        Some(closure) => valid_result(range_m.over(closure)).map(Some),
    }
}

/// Modified tau τ_mod = (DMOD² − r²)/(r·ṙ), s, with the closure floor: 0
/// when r ≤ DMOD (diverging or not), `None` when diverging (as
/// [`range_tau`]) outside DMOD.
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
    match closure(range_rate_m_per_s) {
        None => Ok(None),
        // r > DMOD ≥ 0, so the division by r is safe and r − DMOD²/r > 0.
        Some(closure) => {
            valid_result((range_m - dmod_m.times(dmod_m.over(range_m))).over(closure)).map(Some)
        }
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
    let polar = RelativeRange::new(position_m, velocity_m_per_s)?;
    polar.closest_approach(velocity_m_per_s)
}

/// Range, the unit vector towards the intruder and range rate of a relative
/// state vector, formed once for [`super::assess`]'s range rate and
/// closest approach.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RelativeRange<S> {
    /// r = |p|, m.
    pub(crate) range_m: S,
    /// p/r (zero at r = 0).
    unit: [S; 2],
    /// ṙ = p̂·v, m/s (zero at r = 0).
    pub(crate) range_rate_m_per_s: S,
}

impl<S: Scalar> RelativeRange<S> {
    /// From position `position_m` (m) and velocity `velocity_m_per_s`
    /// (m/s), both checked.
    pub(crate) fn new(position_m: [S; 2], velocity_m_per_s: [S; 2]) -> Result<Self, TcasError> {
        let [px, py] = position_m;
        let [vx, vy] = velocity_m_per_s;
        all_valid(&[px, py, vx, vy])?;
        let range = valid_result(hypot(px, py))?;
        if range == S::ZERO {
            return Ok(RelativeRange {
                range_m: range,
                unit: [S::ZERO; 2],
                range_rate_m_per_s: S::ZERO,
            });
        }
        let unit = S::over_each([px, py], range);
        let range_rate = valid_result(unit[0].times(vx) + unit[1].times(vy))?;
        Ok(RelativeRange {
            range_m: range,
            unit,
            range_rate_m_per_s: range_rate,
        })
    }

    /// The closest point of approach with velocity `velocity_m_per_s` (the
    /// one given to [`RelativeRange::new`]): with cos θ = ṙ/|v| and
    /// |sin θ| = |p̂ × v|/|v|, t = −cos θ·r/|v| and d = r·|sin θ|.
    pub(crate) fn closest_approach(
        &self,
        velocity_m_per_s: [S; 2],
    ) -> Result<Option<ClosestApproach<S>>, TcasError> {
        let [vx, vy] = velocity_m_per_s;
        let range = self.range_m;
        let speed = valid_result(hypot(vx, vy))?;
        // Opening or tangential (ṙ ≥ 0), no relative motion, or no range:
        // the closest approach is now.
        if speed == S::ZERO || range == S::ZERO || self.range_rate_m_per_s >= S::ZERO {
            return Ok(Some(ClosestApproach {
                time_s: S::ZERO,
                distance_m: range,
            }));
        }
        let [ux, uy] = self.unit;
        let [minus_cos, range_per_speed, sin] = S::over_each(
            [-self.range_rate_m_per_s, range, ux.times(vy) - uy.times(vx)],
            speed,
        );
        let time = minus_cos.times(range_per_speed);
        if !time.is_valid() {
            return Ok(None);
        }
        let distance = valid_result(range.times(sin.abs()))?;
        Ok(Some(ClosestApproach {
            time_s: time,
            distance_m: distance,
        }))
    }
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
    let tau = (-h).over(hdot);
    Ok(if tau.is_valid() { Some(tau) } else { None })
}

fn converging<S: Scalar>(h: S, hdot: S) -> bool {
    (h > S::ZERO && hdot < S::ZERO) || (h < S::ZERO && hdot > S::ZERO)
}

/// The miss distance of the straight line through `position_m` along
/// `velocity_m_per_s` (|p × v|/|v|, DO-185B's bearing-tracker `HMDRB`),
/// m, computed as r·|sin θ| with unit vectors (no r²); the range itself
/// when there is no relative motion. `None` for invalid input.
pub fn line_miss_distance<S: Scalar>(position_m: [S; 2], velocity_m_per_s: [S; 2]) -> Option<S> {
    let [px, py] = position_m;
    let [vx, vy] = velocity_m_per_s;
    let range = hypot(px, py);
    let speed = hypot(vx, vy);
    if !(range.is_valid() && speed.is_valid()) {
        return None;
    }
    if speed == S::ZERO || range == S::ZERO {
        return Some(range);
    }
    let sin = px.over(range).times(vy.over(speed)) - py.over(range).times(vx.over(speed));
    let d = range.times(sin.abs());
    d.is_valid().then_some(d)
}
