//! `auto`: a gain schedule configured from the sensor's noise alone — a
//! decoupled per-axis constant-velocity Kalman filter written as αβ gains,
//! whose manoeuvre level is estimated online (design, derivation and the
//! measured figures in `docs/auto.md`).
//!
//! Per axis it carries the 2×2 covariance of (position, velocity),
//! normalised by the measurement variance (p̃ = P/σ², three numbers), and
//! propagates it with the real interval T under the continuous white-noise
//! acceleration model (Bar-Shalom, Li & Kirubarajan 2001 §6.2.2:
//! Q = q·[T³/3, T²/2; T²/2, T]). The gains are the Kalman gains:
//! S̃ = p̃⁻_xx + 1, α = p̃⁻_xx/S̃, β/T = p̃⁻_xv/S̃ (ibid. §5.2.3), so each
//! update has one reciprocal per axis and the updated covariance is
//! (α, β/T, p̃⁻_vv − (β/T)·p̃⁻_xv) (the standard form (I − KH)P⁻, whose
//! position row is the gains themselves once normalised). Coasting is
//! exact: the CWNA covariance over T₁ then T₂ is the covariance over
//! T₁ + T₂, so missed scans add to the next interval. The track starts from
//! its two points: p̃ = [1, 1/T; 1/T, 2/T²] (ibid. §5.5.3).
//!
//! The manoeuvre level q is estimated per axis by covariance matching on
//! the normalised innovation squared ν²/S (ibid. §5.4, §11.2.2): a fading
//! average m of it (weight T/8 s, at most ½) moves q by the factor
//! 1 + (m − 1)/4 each update, within the physical bounds [`Q_MIN`] ..
//! [`Q_MAX`]. Kalman gains lie inside the αβ stability triangle for every
//! interval (0 < α < 1, 0 < β < 2(2 − α)); a rounding failure is clamped
//! there.

use super::{check_range, config_quantity, ConfigError, GainContext, GainSchedule, ScheduleError};
use crate::filter::Gains;
use crate::num::{Numeric, Quantity, Real};

/// The manoeuvre level's floor, m²/s³: the white-acceleration spectral
/// density of an aircraft in straight flight (turbulence, autopilot and
/// report-time jitter), below which real tracks are never smoother.
pub const Q_MIN: u64 = 30;
/// The manoeuvre level of a new track, m²/s³: a ±0.5 g manoeuvre over a
/// 4 s scan (Bar-Shalom, Li & Kirubarajan 2001 §6.2.2: q ≈ a²·T, here
/// 4.9²·4 ≈ 96).
pub const Q_START: u64 = 100;
/// The manoeuvre level's ceiling, m²/s³: above any aircraft's at the
/// filters' intervals (a²·T for 7 g over the longest interval, 20 s, is
/// about 94,000); it keeps the level inside the number formats.
pub const Q_MAX: u64 = 100_000;
/// The time constant of the fading average of the normalised innovation
/// squared, s (its weight T/τ is formed by three halvings).
pub const NIS_MEMORY_S: u64 = 8;
const _: () = assert!(NIS_MEMORY_S == 8, "CovarianceTerms::new halves three times");
/// The largest normalised innovation squared the average takes in.
pub const NIS_CAP: u64 = 100;
const _: () = assert!(NIS_CAP == 100, "nis_cap builds the cap as 10·10");

/// Configuration of [`AutoGains`] (`auto:sigma=S` or
/// `auto:range-sigma=R,bearing-sigma-deg=B`). The sensor is given either as
/// a Cartesian σ per axis or as range and bearing σ (the sensor at the
/// origin); the figures not given are `None`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoConfig {
    /// σ per axis, m, in (0, 10⁶].
    pub sigma: Option<f64>,
    /// σ_R, m, in (0, 10⁶].
    pub range_sigma: Option<f64>,
    /// σ_B, degrees, in (0, 90].
    pub bearing_sigma_deg: Option<f64>,
}

/// The sensor an [`AutoConfig`] describes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AutoSensor {
    /// σ per axis, m.
    Cartesian {
        /// σ, m.
        sigma: f64,
    },
    /// σ_R (m) and σ_B (rad) of a sensor at the origin.
    Polar {
        /// σ_R, m.
        range_sigma: f64,
        /// σ_B, rad.
        bearing_sigma: f64,
    },
}

impl AutoConfig {
    /// No sensor figures yet (the spec parser fills them in).
    pub const UNSET: Self = AutoConfig {
        sigma: None,
        range_sigma: None,
        bearing_sigma_deg: None,
    };

    /// A Cartesian sensor with σ per axis (m).
    pub const fn cartesian(sigma: f64) -> Self {
        AutoConfig {
            sigma: Some(sigma),
            ..Self::UNSET
        }
    }

    /// A range–bearing sensor with σ_R (m) and σ_B (degrees).
    pub const fn polar(range_sigma: f64, bearing_sigma_deg: f64) -> Self {
        AutoConfig {
            range_sigma: Some(range_sigma),
            bearing_sigma_deg: Some(bearing_sigma_deg),
            ..Self::UNSET
        }
    }

    /// Whether any sensor figure was given.
    pub fn has_sensor(&self) -> bool {
        self.sigma.is_some() || self.range_sigma.is_some() || self.bearing_sigma_deg.is_some()
    }

    /// The sensor: `sigma` alone, or `range-sigma` with `bearing-sigma-deg`.
    pub fn sensor(&self) -> Result<AutoSensor, ConfigError> {
        if let Some(sigma) = self.sigma {
            if self.range_sigma.is_some() || self.bearing_sigma_deg.is_some() {
                // Both forms given: the Cartesian σ is the one refused.
                return Err(ConfigError::OutOfRange { parameter: "sigma" });
            }
            check_range(sigma, 0.0, 1.0e6, false, "sigma")?;
            return Ok(AutoSensor::Cartesian { sigma });
        }
        // A missing figure is NaN, which every range refuses.
        let range_sigma = self.range_sigma.unwrap_or(f64::NAN);
        let bearing_sigma_deg = self.bearing_sigma_deg.unwrap_or(f64::NAN);
        check_range(range_sigma, 0.0, 1.0e6, false, "range-sigma")?;
        check_range(bearing_sigma_deg, 0.0, 90.0, false, "bearing-sigma-deg")?;
        Ok(AutoSensor::Polar {
            range_sigma,
            bearing_sigma: bearing_sigma_deg.to_radians(),
        })
    }

    /// Checks the sensor figures.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.sensor().map(|_| ())
    }
}

/// What `auto` keeps per axis: the normalised covariance of the last update
/// (P/σ²) and the manoeuvre level's estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoAxis<N: Numeric> {
    /// P_xx/σ².
    pub position: N::Ratio,
    /// P_xv/σ², 1/s.
    pub cross: N::Ratio,
    /// P_vv/σ², 1/s².
    pub velocity: N::Ratio,
    /// q/(3σ²), 1/s³: the manoeuvre level, scaled so that Q/σ² is
    /// (q̃·T³, 1.5·q̃·T², 3·q̃·T) without a division.
    pub manoeuvre: N::Ratio,
    /// The fading average of ν²/S.
    pub nis: N::Ratio,
}

/// Where the track is in its start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Start {
    /// No measurement yet.
    Empty,
    /// One measurement: the coasted time is summed toward the two-point
    /// interval.
    FirstPoint,
    /// Two: the two-point covariance is held in units of the reference σ²
    /// and scaled by each axis's measurement variance at the next update
    /// (a polar sensor's variance depends on where the target is).
    TwoPoint,
    /// Three or more: the covariance holds.
    Tracking,
}

/// The configuration of a filter whose axes share one σ: 1/σ (per metre;
/// the covariance is normalised by σ²) and the manoeuvre level's bounds as
/// q/(3σ²) ([`AutoGains::shared_noise`]). A polar sensor's σ here is σ_R.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SharedNoise<N: Numeric> {
    pub(crate) inverse_sigma: N::Ratio,
    pub(crate) manoeuvre_min: N::Ratio,
    pub(crate) manoeuvre_max: N::Ratio,
    /// [`NIS_CAP`].
    pub(crate) nis_cap: N::Ratio,
}

impl<N: Numeric> SharedNoise<N> {
    /// The manoeuvre level of a new track ([`Q_START`]).
    pub(crate) fn start_manoeuvre(&self) -> N::Ratio {
        self.manoeuvre_min * N::Ratio::from_ratio(Q_START, Q_MIN)
    }

    pub(crate) fn bounds(&self) -> (N::Ratio, N::Ratio) {
        (self.manoeuvre_min, self.manoeuvre_max)
    }
}

/// The self-tuning schedule (module docs; `docs/auto.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoGains<N: Numeric, const D: usize> {
    /// 1/σ (a polar sensor's 1/σ_R), the manoeuvre level's bounds, the
    /// NIS cap.
    noise: SharedNoise<N>,
    /// A polar sensor's σ_B/σ_R (rad per metre); `None` for a Cartesian
    /// one.
    bearing_over_range: Option<N::Ratio>,
    axes: [AutoAxis<N>; D],
    /// Time coasted since the last update, s (added to the next interval).
    coasted: N::Ratio,
    start: Start,
}

/// The terms of an interval that the covariance's prediction and the NIS
/// average take, shared by the axes: τ (the next interval plus the
/// time coasted), τ³, 1.5τ², 3τ, the fading weight min(τ/8 s, ½), and the
/// update's own interval T.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct CovarianceTerms<R> {
    tau: R,
    cube: R,
    square: R,
    triple: R,
    weight: R,
    interval: R,
}

impl<R: Real> CovarianceTerms<R> {
    pub(crate) fn new(coasted: R, dt: R) -> Self {
        let tau = coasted + dt;
        let squared = tau * tau;
        let weight = tau.half().half().half().min_of(R::ONE.half());
        CovarianceTerms {
            tau,
            cube: squared * tau,
            square: squared + squared.half(),
            triple: tau + tau + tau,
            weight,
            interval: dt,
        }
    }
}

/// [`NIS_CAP`] in `R`, built by additions (exact in every format; formed
/// once per configuration).
fn nis_cap<R: Real>() -> R {
    let two = R::TWO;
    let ten = (two + two) + (two + two) + two;
    ten * ten
}

/// The part of an axis's predicted covariance (P⁻ = FPFᵀ + Q) that a
/// gate forms: p̃⁻_xx, which sizes the gate, and p̃_xv + τ·p̃_vv, the cross
/// term before its process noise, which only the update needs. The track
/// table keeps it from a default track's gate for its update in the same
/// scan ([`crate::track::TrackFilter::GateKept`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoPrediction<N: Numeric> {
    position: N::Ratio,
    cross_before_noise: N::Ratio,
}

impl<N: Numeric> AutoPrediction<N> {
    /// A placeholder (zero bytes) for a workspace no gate has written yet.
    pub const NONE: Self = AutoPrediction {
        position: N::Ratio::ZERO,
        cross_before_noise: N::Ratio::ZERO,
    };

    /// p̃⁻_xx: the predicted position variance over σ².
    pub fn predicted_variance_ratio(&self) -> N::Ratio {
        self.position
    }
}

/// [`AutoPrediction`] of covariance `a` over the interval of `s`.
#[inline(always)]
pub(crate) fn predicted_part<N: Numeric>(
    a: &AutoAxis<N>,
    s: &CovarianceTerms<N::Ratio>,
) -> AutoPrediction<N> {
    let cross_before_noise = a.cross + s.tau * a.velocity;
    AutoPrediction {
        position: a.position + s.tau * (a.cross + cross_before_noise) + a.manoeuvre * s.cube,
        cross_before_noise,
    }
}

/// An axis's covariance predicted over the interval of `s` (P⁻ = FPFᵀ +
/// Q), as (p̃_xx, p̃_xv, p̃_vv), from its part `part` over the same interval.
#[inline(always)]
fn predicted_from<N: Numeric>(
    a: &AutoAxis<N>,
    s: &CovarianceTerms<N::Ratio>,
    part: &AutoPrediction<N>,
) -> (N::Ratio, N::Ratio, N::Ratio) {
    let q = a.manoeuvre;
    (
        part.position,
        part.cross_before_noise + q * s.square,
        a.velocity + q * s.triple,
    )
}

/// The gains of one Kalman step of a normalised covariance: α, the
/// velocity gain β/T (1/s) and β, inside the stability triangle.
#[derive(Clone, Copy)]
pub(crate) struct KalmanGains<R> {
    pub(crate) alpha: R,
    pub(crate) rate: R,
    pub(crate) beta: R,
}

/// The covariance half of one Kalman step ([`covariance_step`]): what
/// does not depend on the innovations.
#[derive(Clone, Copy)]
pub(crate) struct CovarianceStep<N: Numeric> {
    pub(crate) gains: KalmanGains<N::Ratio>,
    /// 1/S̃ (S̃ = p̃⁻_xx + R/σ²): an axis's ν²/S is (ν/σ · 1/S̃)·ν/σ
    /// ([`capped_nis`]).
    pub(crate) inverse: N::Ratio,
    /// P⁺/σ², with the manoeuvre level and NIS average not yet moved.
    pub(crate) next: AutoAxis<N>,
    /// Whether the manoeuvre level follows this step's innovations
    /// ([`match_manoeuvre`]); not after the last-resort gains of
    /// [`covariance_step_or_restart`].
    pub(crate) matched: bool,
}

/// The measurement variance over σ² of a covariance step: `None` is 1
/// (the fused filter's, whose σ is the sensor's), which takes no product.
pub(crate) type VarianceRatio<R> = Option<R>;

/// `v`·`r` (`v` itself when `r` is 1).
#[inline(always)]
fn scaled_by<R: Real>(v: R, r: VarianceRatio<R>) -> R {
    // A match, not `map_or`, which opt-level "s" leaves as a call.
    match r {
        Some(r) => v * r,
        None => v,
    }
}

/// One Kalman update of the normalised covariance `a` for measurement
/// variance ratio `r` (R/σ²), `part` being [`predicted_part`] of `a` over
/// `s`: the gains, 1/S̃ and P⁺, or `None` when the covariance left the
/// number format. One division (1/S̃); no libm.
#[inline(always)]
pub(crate) fn covariance_step<N: Numeric>(
    a: &AutoAxis<N>,
    s: &CovarianceTerms<N::Ratio>,
    part: &AutoPrediction<N>,
    r: VarianceRatio<N::Ratio>,
) -> Option<CovarianceStep<N>> {
    let one = N::Ratio::ONE;
    let (pxx, pxv, pvv) = predicted_from(a, s, part);
    let inverse = one / (pxx + r.unwrap_or(one));
    let alpha = pxx * inverse;
    let mut rate = pxv * inverse;
    // Inside the stability triangle (β < 2(2 − α)) whatever the rounding.
    // The bound is formed only when it can bind: for α ≤ 1 it is at least
    // 1.5 (rounding is monotone), so a β ≤ 1 is inside it.
    let mut beta = rate * s.interval;
    let clearly_inside = beta <= one && alpha <= one;
    if !clearly_inside {
        let two = N::Ratio::TWO;
        let limit = (two - alpha) + (two - alpha).half();
        if beta > limit {
            beta = limit;
            rate = limit / s.interval;
        }
    }
    let mut velocity = pvv - rate * pxv;
    let (position, cross) = (scaled_by(alpha, r), scaled_by(rate, r));
    if velocity * position <= cross * cross {
        // Rounding left P⁺ not positive definite (its determinant is
        // det P⁻·r/S > 0 exactly): the smallest p̃_vv that keeps it so.
        let floor = cross * cross / position;
        velocity = floor + floor;
    }
    // α and β/T are the stored position and cross terms over r, so these
    // three cover every result (invalid values are sticky). One check each:
    // a fold over an array is a loop at opt-level "s".
    let valid = |v: N::Ratio| N::Ratio::all_valid([v]);
    (valid(position) & valid(cross) & valid(velocity)).then_some(CovarianceStep {
        gains: KalmanGains { alpha, rate, beta },
        inverse,
        next: AutoAxis {
            position,
            cross,
            velocity,
            ..*a
        },
        matched: true,
    })
}

/// [`covariance_step`] (`part` is [`predicted_part`] of `a` over `s`), and
/// should the covariance have left the number
/// format (a narrow format, a tiny σ and a long interval), a restart from a
/// two-point start over the interval at the manoeuvre ceiling `bounds.1`,
/// scaled by `r`; should that fail too, the gains of a two-point start at
/// equal intervals without process noise (α = 5/6, β = 1/2: Al-Wagih &
/// Abdulla eq. 24 at n = 3), the manoeuvre level left as it is.
#[inline(always)]
pub(crate) fn covariance_step_or_restart<N: Numeric>(
    a: &AutoAxis<N>,
    s: &CovarianceTerms<N::Ratio>,
    part: &AutoPrediction<N>,
    r: VarianceRatio<N::Ratio>,
    bounds: (N::Ratio, N::Ratio),
) -> CovarianceStep<N> {
    if let Some(step) = covariance_step(a, s, part, r) {
        return step;
    }
    let start = two_point::<N>(s.tau, bounds.1);
    let start = AutoAxis {
        position: scaled_by(start.position, r),
        cross: scaled_by(start.cross, r),
        velocity: scaled_by(start.velocity, r),
        ..start
    };
    let terms = CovarianceTerms::new(N::Ratio::ZERO, s.interval);
    covariance_step(&start, &terms, &predicted_part(&start, &terms), r).unwrap_or_else(|| {
        let beta = N::Ratio::ONE.half();
        CovarianceStep {
            gains: KalmanGains {
                alpha: N::Ratio::from_ratio(5, 6),
                rate: beta / s.interval,
                beta,
            },
            inverse: N::Ratio::ZERO,
            next: start,
            matched: false,
        }
    })
}

/// One axis's ν²/S (from ν/σ and 1/S̃), capped at `cap`: a NIS beyond the
/// cap is a manoeuvre whatever its size, and capping it keeps the average
/// in range; so is one that left the number format (an invalid value
/// compares false, so `cap.min_of` gives the cap). It is formed as
/// (ν/S̃)·ν. A format with a relative precision
/// (floats, the fast fixed point's ratios) holds the product whatever ν;
/// a narrow absolute one (Q32.32) forms it only when |ν/S̃| < 1 (the
/// product is then smaller than |ν|) or |ν| is under the cap (it is then
/// at most cap²/S̃): a polar axis's S̃ can be far above 1, and then a large
/// ν is not a manoeuvre.
#[inline(always)]
pub(crate) fn capped_nis<R: Real>(nu: R, inverse: R, cap: R) -> R {
    let weighted = nu * inverse;
    if R::RELATIVE_PRECISION || weighted.abs() < R::ONE || nu.abs() < cap {
        cap.min_of(weighted * nu)
    } else {
        cap
    }
}

/// The mean of the capped ν²/S of `K` axes from their sum (their number a
/// power of two: halvings).
#[inline(always)]
pub(crate) fn mean_over_axes<R: Real, const K: usize>(sum: R) -> R {
    let () = AxesPowerOfTwo::<K>::CHECK;
    let mut mean = sum;
    for _ in 0..K.trailing_zeros() {
        mean = mean.half();
    }
    mean
}

/// Covariance matching (module docs): the fading average of ν²/S takes in
/// `nis` (this update's, averaged over the axes sharing `a`) with the
/// interval's weight, and the manoeuvre level moves by 1 + (average − 1)/4
/// within `bounds`. Both stay valid without a check: `nis` is a mean of
/// [`capped_nis`] (in [0, cap] whatever ν), so the average stays between
/// the previous one and the cap, and the level's step is bounded before
/// it is clamped.
#[inline(always)]
pub(crate) fn match_manoeuvre<N: Numeric>(
    a: &mut AutoAxis<N>,
    nis: N::Ratio,
    s: &CovarianceTerms<N::Ratio>,
    bounds: (N::Ratio, N::Ratio),
) {
    a.nis = a.nis + (nis - a.nis) * s.weight;
    // At the floor with an average ≤ 1 the step is toward the floor (the
    // rounded level is then at most the floor), so the clamp gives the
    // floor back: not formed.
    if a.manoeuvre == bounds.0 && a.nis <= N::Ratio::ONE {
        return;
    }
    a.manoeuvre = (a.manoeuvre + a.manoeuvre * (a.nis - N::Ratio::ONE).half().half())
        .min_of(bounds.1)
        .max_of(bounds.0);
}

/// Refuses, at compile time, a number of axes sharing a covariance that is
/// not a power of two (their mean ν²/S is formed by halvings).
struct AxesPowerOfTwo<const K: usize>;

impl<const K: usize> AxesPowerOfTwo<K> {
    const CHECK: () = assert!(K.is_power_of_two(), "axes sharing a covariance: 1, 2, 4…");
}

/// One axis's update as a schedule gives it: the covariance step (or its
/// restart) and the manoeuvre level matched on the axis's own ν/σ, as
/// [`Gains`].
#[inline(always)]
fn step_axis<N: Numeric>(
    a: &mut AutoAxis<N>,
    s: &CovarianceTerms<N::Ratio>,
    r: N::Ratio,
    nu: N::Ratio,
    bounds: (N::Ratio, N::Ratio),
    cap: N::Ratio,
) -> Result<Gains<N>, ScheduleError> {
    let step = covariance_step_or_restart(a, s, &predicted_part(a, s), Some(r), bounds);
    *a = step.next;
    if step.matched {
        match_manoeuvre(a, capped_nis(nu, step.inverse, cap), s, bounds);
    }
    Ok(Gains::alpha_beta(step.gains.alpha, step.gains.beta)?)
}

/// The two-point start over interval `t` (Bar-Shalom, Li & Kirubarajan
/// 2001 §5.5.3): p̃ = [1, 1/T; 1/T, 2/T²], the manoeuvre level `manoeuvre`.
pub(crate) fn two_point<N: Numeric>(t: N::Ratio, manoeuvre: N::Ratio) -> AutoAxis<N> {
    let per = N::Ratio::ONE / t;
    let per_squared = per * per;
    AutoAxis {
        position: N::Ratio::ONE,
        cross: per,
        velocity: per_squared + per_squared,
        manoeuvre,
        nis: N::Ratio::ONE,
    }
}

impl<N: Numeric, const D: usize> AutoGains<N, D> {
    /// The schedule for the sensor `c` describes (`docs/auto.md`).
    pub fn new(c: &AutoConfig) -> Result<Self, ConfigError> {
        // σ (a polar sensor's σ_R) and, for a polar sensor, σ_B/σ_R.
        let (sigma, sigma_name, bearing_over_range) = match c.sensor()? {
            AutoSensor::Cartesian { sigma } => (sigma, "sigma", None),
            AutoSensor::Polar {
                range_sigma,
                bearing_sigma,
            } => (
                range_sigma,
                "range-sigma",
                Some(bearing_sigma / range_sigma),
            ),
        };
        let variance = 3.0 * sigma * sigma;
        let noise = SharedNoise {
            inverse_sigma: config_quantity(1.0 / sigma, sigma_name)?,
            manoeuvre_min: config_quantity(Q_MIN as f64 / variance, sigma_name)?,
            manoeuvre_max: config_quantity(Q_MAX as f64 / variance, sigma_name)?,
            nis_cap: nis_cap(),
        };
        let bearing_over_range = match bearing_over_range {
            Some(ratio) => Some(config_quantity(ratio, "bearing-sigma-deg")?),
            None => None,
        };
        let mut out = AutoGains {
            noise,
            bearing_over_range,
            axes: [two_point::<N>(N::Ratio::ONE, N::Ratio::ZERO); D],
            coasted: N::Ratio::ZERO,
            start: Start::Empty,
        };
        GainSchedule::<N, D>::reset(&mut out);
        Ok(out)
    }

    /// The per-axis state after the last update.
    pub fn axes(&self) -> &[AutoAxis<N>; D] {
        &self.axes
    }

    /// What the fused filter [`crate::filter::auto::AutoFilter`] needs of
    /// this configuration: 1/σ (a polar sensor's 1/σ_R: that filter takes
    /// one σ for every axis) and the manoeuvre level's bounds.
    pub fn shared_noise(&self) -> &SharedNoise<N> {
        &self.noise
    }

    /// R/σ² and ν/σ of every axis: 1 and e/σ for a Cartesian sensor; for a
    /// polar one σ along the axis at the predicted position p,
    /// σ_x² = (σ_R·x/|p|)² + (σ_B·y)² and likewise σ_y (range and
    /// cross-range errors projected, their correlation ignored), over σ_R².
    /// The ratio is at least 2⁻¹⁰. Axes past the second use σ_R.
    fn measurement_ratios(&self, ctx: &GainContext<N, D>) -> [(N::Ratio, N::Ratio); D] {
        let one = N::Ratio::ONE;
        let mut out = [(one, N::Ratio::ZERO); D];
        let inverse_sigma = self.noise.inverse_sigma;
        for (o, a) in out.iter_mut().zip(&ctx.axes) {
            o.1 = N::Ratio::from(a.innovation) * inverse_sigma;
        }
        if let Some(bearing_over_range) = self.bearing_over_range {
            let x = ctx.axes.first().map_or(N::Length::ZERO, |a| a.predicted);
            let y = ctx.axes.get(1).map_or(N::Length::ZERO, |a| a.predicted);
            let range = N::hypot(x, y);
            for (i, o) in out.iter_mut().enumerate() {
                let (along, across) = match i {
                    0 => (x, y),
                    1 => (y, x),
                    _ => continue,
                };
                if range > N::Length::ZERO {
                    let u = along / range;
                    let c = N::Ratio::from(across) * bearing_over_range;
                    // Floored at (σ_R/32)²: a target at the sensor would
                    // otherwise have no measurement noise.
                    let floor = (0..10).fold(one, |f, _| f.half());
                    o.0 = (u * u + c * c).max_of(floor);
                }
            }
        }
        out
    }

    /// The covariance the next update starts from: the axes', or a
    /// two-point start over the update's interval for a filter handed over
    /// already tracking.
    /// A two-point covariance is that of the two measurements, so it is
    /// scaled by the axis's variance ratio `r` (1 for a Cartesian sensor).
    fn current(
        &self,
        dt: N::Ratio,
        ratios: Option<&[(N::Ratio, N::Ratio); D]>,
    ) -> [AutoAxis<N>; D] {
        let mut axes = match self.start {
            Start::Tracking => return self.axes,
            Start::TwoPoint => self.axes,
            Start::Empty | Start::FirstPoint => {
                [two_point::<N>(dt, self.noise.start_manoeuvre()); D]
            }
        };
        if let Some(ratios) = ratios {
            for (a, (r, _)) in axes.iter_mut().zip(ratios) {
                a.position = a.position * *r;
                a.cross = a.cross * *r;
                a.velocity = a.velocity * *r;
            }
        }
        axes
    }

    /// p̃⁻_xx per axis for an update `dt` from now (the predicted position
    /// variance over σ²): the innovation variance over σ² is this plus
    /// R/σ² (1 for a Cartesian sensor), which a gate uses. A polar
    /// sensor's two-point start is in units of σ_R² until its first update.
    pub fn predicted_position_ratios(&self, dt: N::Interval) -> [N::Ratio; D] {
        let dt = N::Ratio::from(dt);
        let terms = CovarianceTerms::new(self.coasted, dt);
        self.current(dt, None)
            .map(|a| predicted_part(&a, &terms).predicted_variance_ratio())
    }

    /// The gains of the update `ctx` and the state after it.
    fn plan(&self, ctx: &GainContext<N, D>) -> Result<Plan<N, D>, ScheduleError> {
        let dt = N::Ratio::from(ctx.dt);
        let terms = CovarianceTerms::new(self.coasted, dt);
        let ratios = self.measurement_ratios(ctx);
        let bounds = self.noise.bounds();
        let one = N::Ratio::ONE;
        let mut gains = [Gains::alpha_beta(one, one)?; D];
        let mut next = self.current(dt, Some(&ratios));
        for ((g, a), (r, nu)) in gains.iter_mut().zip(next.iter_mut()).zip(ratios) {
            *g = step_axis(a, &terms, r, nu, bounds, self.noise.nis_cap)?;
        }
        Ok((gains, next))
    }
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for AutoGains<N, D> {
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        self.plan(ctx).map(|(g, _)| g)
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        if let Ok((_, next)) = self.plan(ctx) {
            self.axes = next;
            self.start = Start::Tracking;
        }
        self.coasted = N::Ratio::ZERO;
    }

    fn initialised(&mut self, n: u32, dt: N::Interval) {
        if n <= 1 {
            GainSchedule::<N, D>::reset(self);
            self.start = Start::FirstPoint;
        } else {
            let t = self.coasted + N::Ratio::from(dt);
            self.axes = [two_point::<N>(t, self.noise.start_manoeuvre()); D];
            self.coasted = N::Ratio::ZERO;
            self.start = Start::TwoPoint;
        }
    }

    fn missed(&mut self, dt: N::Interval) {
        let coasted = self.coasted + N::Ratio::from(dt);
        if coasted.is_valid() {
            self.coasted = coasted;
        }
    }

    fn gains_follow_interval(&self) -> bool {
        true
    }

    fn predicted_variance_ratios(&self, dt: N::Interval) -> Option<[N::Ratio; D]> {
        matches!(self.start, Start::Tracking | Start::TwoPoint)
            .then(|| self.predicted_position_ratios(dt))
    }

    fn reset(&mut self) {
        self.axes = [two_point::<N>(N::Ratio::ONE, self.noise.start_manoeuvre()); D];
        self.coasted = N::Ratio::ZERO;
        self.start = Start::Empty;
    }
}

// The gains of an update and the axes' state after it (`AutoGains::plan`).
type Plan<N, const D: usize> = ([Gains<N>; D], [AutoAxis<N>; D]);
