//! `auto`: a gain schedule configured from the sensor's noise alone, which
//! adapts its gains to the target from the innovations (see `docs/auto.md`
//! for the design, its derivation and the measured figures).
//!
//! Per axis it keeps an *effective count* n and uses the least-squares gains
//! α̂(n), β̂(n) of Al-Wagih & Abdulla eq. (24) (the Kalman gains of a
//! constant-velocity target without process noise, from a two-point start).
//! The count grows by one per update, as in the least-squares filter, and is
//! cut when the normalised innovation squared (NIS, Bar-Shalom, Li &
//! Kirubarajan 2001, §5.4) shows the target leaving the straight line:
//!
//! * a fast test on a fading average of the NIS (weight ½) catches the onset
//!   of a manoeuvre and lowers n so that the innovation's variance is what
//!   the filter expects (covariance matching, ibid. §11.2.2);
//! * a slow average (weight 1/16) catches a sustained manoeuvre too weak for
//!   the fast test and holds a ceiling on n, which then relaxes.
//!
//! Li, Zhao, Liang & Zhang's improved filter (eqs. 13–15) drives an
//! effective count by an innovation ratio in the same way; here the ratio is
//! the NIS, whose distribution is known, so the thresholds are probabilities.
//! Every pair (α̂(n), β̂(n)) with n ≥ 3 lies inside the stability triangle and
//! below Kalata's steady-state β for its α, and n can only fall by a cut or
//! rise by one per update, as a Kalman filter's covariance does.

use super::al_wagih::LeastSquaresConfig;
use super::{check_range, config_quantity, ConfigError, GainContext, GainSchedule, ScheduleError};
use crate::filter::Gains;
use crate::num::{Numeric, Quantity, Real};

/// The fast test's threshold on the fading-average NIS: under white noise
/// matching σ it is exceeded about 4·10⁻⁴ of the time per axis and update
/// (host-tests `tests/it/gain/auto.rs` measures it).
pub const DETECTION_LEVEL: u64 = 7;
/// The slow average's threshold: twice the expected NIS.
pub const SUSTAINED_LEVEL: u64 = 2;
/// The slow average's weight of the newest NIS is 1/`SLOW_MEMORY` (a power
/// of two: the weight is formed by halvings).
pub const SLOW_MEMORY: u64 = 16;
/// The ceiling grows by 1/`CEILING_GROWTH` of itself per update without a
/// sustained manoeuvre (a power of two).
pub const CEILING_GROWTH: u64 = 64;
/// The first filtered update has count 3 (Al-Wagih eq. 24, "n > 2").
pub const FIRST_COUNT: u64 = 3;

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
    /// The largest count (as [`LeastSquaresConfig::n_max`]), 3..=10 000.
    /// Default 1000.
    pub n_max: u32,
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
        n_max: 1000,
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

    /// Checks the sensor figures and `n_max`.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.sensor()?;
        LeastSquaresConfig { n_max: self.n_max }.validate()
    }
}

/// The sensor noise in the schedule's number system.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Noise<N: Numeric> {
    /// 1/σ (per metre), so that e/σ is a product.
    Cartesian { inverse_sigma: N::Ratio },
    /// σ_R and σ_B (rad).
    Polar {
        range_sigma: N::Length,
        bearing_sigma: N::Ratio,
    },
}

/// What `auto` keeps per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoAxis<N: Numeric> {
    /// n, the effective count of the next update (≥ 3, real-valued).
    pub count: N::Ratio,
    /// The fast fading average of the NIS (weight ½).
    pub fast: N::Ratio,
    /// The slow fading average of the NIS (weight 1/16).
    pub slow: N::Ratio,
    /// The ceiling on n a sustained manoeuvre set (n_max when none).
    pub ceiling: N::Ratio,
}

/// The self-tuning schedule (module docs; `docs/auto.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoGains<N: Numeric, const D: usize> {
    noise: Noise<N>,
    n_max: N::Ratio,
    axes: [AutoAxis<N>; D],
    /// Scans missed since the last update.
    misses: u16,
    /// T of the last update (zero before the first) and (1 m)/T.
    last_interval: N::Interval,
    per_last_interval: N::Speed,
}

/// The integer `k` as a ratio, by doubling and adding one (exact; no
/// conversion from a float, which costs a fixed-point core code and time).
fn int<R: Real>(k: u64) -> R {
    let mut out = R::ZERO;
    let bits = u64::BITS.saturating_sub(k.leading_zeros());
    for bit in (0..bits).rev() {
        out = out + out;
        if (k >> bit) & 1 == 1 {
            out = out + R::ONE;
        }
    }
    out
}

/// 1/2^k (k halvings of one).
fn inverse_power_of_two<R: Real>(k: u32) -> R {
    (0..k).fold(R::ONE, |r, _| r.half())
}

/// (α̂(n), β̂(n)) = (2(2n − 1), 6)/(n(n + 1)) (Al-Wagih & Abdulla eq. 24) for
/// a real count n ≥ 3.
#[inline(never)]
fn least_squares<R: Real>(n: R) -> (R, R) {
    let q = R::ONE / (n * (n + R::ONE));
    let two = R::ONE + R::ONE;
    let six = two + two + two;
    ((two * (two * n - R::ONE)) * q, six * q)
}

/// The count whose least-squares α is `alpha` ∈ (0, 1): the larger root of
/// αn² + (α − 4)n + 2 = 0 (eq. 24a solved for n).
#[inline(never)]
fn count_for_alpha<R: Real>(alpha: R) -> R {
    let two = R::ONE + R::ONE;
    let four = two + two;
    let b = four - alpha;
    let root = (b * b - (four + four) * alpha).sqrt();
    (b + root) / (two * alpha)
}

/// The thresholds and weights of the rules, in the schedule's ratio type.
#[derive(Clone, Copy)]
struct Constants<R> {
    floor: R,
    detection: R,
    sustained: R,
    slow_weight: R,
    growth: R,
}

impl<R: Real> Constants<R> {
    fn new() -> Self {
        Constants {
            floor: int(FIRST_COUNT),
            detection: int(DETECTION_LEVEL),
            sustained: int(SUSTAINED_LEVEL),
            slow_weight: inverse_power_of_two(SLOW_MEMORY.trailing_zeros()),
            growth: R::ONE + inverse_power_of_two(CEILING_GROWTH.trailing_zeros()),
        }
    }
}

impl<N: Numeric, const D: usize> AutoGains<N, D> {
    /// The schedule for the sensor `c` describes (`docs/auto.md`).
    pub fn new(c: &AutoConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        let noise = match c.sensor()? {
            AutoSensor::Cartesian { sigma } => Noise::Cartesian {
                inverse_sigma: config_quantity(1.0 / sigma, "sigma")?,
            },
            AutoSensor::Polar {
                range_sigma,
                bearing_sigma,
            } => Noise::Polar {
                range_sigma: config_quantity(range_sigma, "range-sigma")?,
                bearing_sigma: config_quantity(bearing_sigma, "bearing-sigma-deg")?,
            },
        };
        let n_max: N::Ratio = config_quantity(f64::from(c.n_max), "n-max")?;
        Ok(AutoGains {
            noise,
            n_max,
            axes: [Self::fresh_axis(n_max); D],
            misses: 0,
            last_interval: N::Interval::ZERO,
            per_last_interval: N::Speed::ZERO,
        })
    }

    fn fresh_axis(n_max: N::Ratio) -> AutoAxis<N> {
        AutoAxis {
            count: int::<N::Ratio>(FIRST_COUNT),
            fast: N::Ratio::ONE,
            slow: N::Ratio::ONE,
            ceiling: n_max,
        }
    }

    /// The per-axis state (the count of the next update, the averages, the
    /// ceiling).
    pub fn axes(&self) -> &[AutoAxis<N>; D] {
        &self.axes
    }

    /// e/σ of every axis: Cartesian σ, or for a polar sensor σ along the
    /// axis at the predicted position p: σ_x = √((σ_R·x/|p|)² + (σ_B·y)²),
    /// σ_y likewise (range and cross-range errors projected; their
    /// correlation ignored). Axes past the second use σ_R.
    fn normalised_innovations(&self, ctx: &GainContext<N, D>) -> [N::Ratio; D] {
        let mut out = [N::Ratio::ZERO; D];
        match self.noise {
            Noise::Cartesian { inverse_sigma } => {
                for (o, a) in out.iter_mut().zip(&ctx.axes) {
                    *o = N::Ratio::from(a.innovation) * inverse_sigma;
                }
            }
            Noise::Polar {
                range_sigma,
                bearing_sigma,
            } => {
                let x = ctx.axes.first().map_or(N::Length::ZERO, |a| a.predicted);
                let y = ctx.axes.get(1).map_or(N::Length::ZERO, |a| a.predicted);
                let range = N::hypot(x, y);
                for (i, (o, a)) in out.iter_mut().zip(&ctx.axes).enumerate() {
                    let sigma = match (i, range > N::Length::ZERO) {
                        (0, true) => N::hypot((x / range) * range_sigma, bearing_sigma * y),
                        (1, true) => N::hypot((y / range) * range_sigma, bearing_sigma * x),
                        _ => range_sigma,
                    };
                    *o = a.innovation / sigma;
                }
            }
        }
        out
    }

    /// h², the extrapolation span of this update over that of the last
    /// (scans missed in between, and T over the last T), when it exceeds 1.
    fn span_squared(&self, dt: N::Interval) -> Option<N::Ratio> {
        let mut h = int::<N::Ratio>(u64::from(self.misses).saturating_add(1));
        if self.last_interval > N::Interval::ZERO && dt != self.last_interval {
            h = h * N::Ratio::from(self.per_last_interval * dt);
        }
        (h.is_valid() && h > N::Ratio::ONE).then_some(h * h)
    }

    /// The gains of the update `ctx` and the state after it.
    fn plan(&self, ctx: &GainContext<N, D>) -> Result<Plan<N, D>, ScheduleError> {
        let constants = Constants::new();
        let span = self.span_squared(ctx.dt);
        let nu = self.normalised_innovations(ctx);
        let one = N::Ratio::ONE;
        let mut gains = [Gains::alpha_beta(one, one)?; D];
        let mut next = self.axes;
        for ((g, s), nu) in gains.iter_mut().zip(next.iter_mut()).zip(nu) {
            *g = step_axis(s, nu, span, self.n_max, &constants)?;
        }
        Ok((gains, next))
    }
}

/// One axis's update of the rules (module docs): the gains, and `s` moved
/// to the state after the update. `nu` = e/σ, `span` = h² when above 1.
#[inline(never)]
fn step_axis<N: Numeric>(
    s: &mut AutoAxis<N>,
    nu: N::Ratio,
    span: Option<N::Ratio>,
    n_max: N::Ratio,
    c: &Constants<N::Ratio>,
) -> Result<Gains<N>, ScheduleError> {
    let one = N::Ratio::ONE;
    let (alpha, _) = least_squares(s.count);
    // NIS = e²/S with S = σ²(1 − α + αh²)/(1 − α): the least-squares
    // prediction variance is σ²α/(1 − α), its velocity part scaled by the
    // span h².
    let keep = one - alpha;
    let nis = match span {
        None => nu * nu * keep,
        Some(h2) => nu * nu * keep / (keep + alpha * h2),
    };
    let fast = (s.fast + nis).half();
    let slow = s.slow + (nis - s.slow) * c.slow_weight;
    let mut count = s.count;
    if slow.is_valid() && slow <= c.sustained {
        s.slow = slow;
        s.ceiling = (s.ceiling * c.growth).min_of(n_max);
    } else {
        // A sustained manoeuvre: halve the ceiling (below the count).
        s.slow = one;
        s.ceiling = s.ceiling.min_of(count).half().max_of(c.floor);
    }
    if fast.is_valid() && fast <= c.detection {
        s.fast = fast;
    } else {
        // The onset of a manoeuvre: cut the count so that the prediction
        // variance absorbs the excess of the NIS over the threshold,
        // 1 − α* = (1 − α)·level/m.
        s.fast = one;
        count = if fast.is_valid() {
            let target = one - keep * c.detection / fast;
            count.min_of(count_for_alpha(target)).max_of(c.floor)
        } else {
            c.floor
        };
        if !count.is_valid() {
            count = c.floor;
        }
    }
    let (a, b) = least_squares(count);
    s.count = (count + one)
        .min_of(s.ceiling)
        .min_of(n_max)
        .max_of(c.floor);
    Ok(Gains::alpha_beta(a, b)?)
}

impl<N: Numeric, const D: usize> GainSchedule<N, D> for AutoGains<N, D> {
    fn gains(&self, ctx: &GainContext<N, D>) -> Result<[Gains<N>; D], ScheduleError> {
        self.plan(ctx).map(|(g, _)| g)
    }

    fn accepted(&mut self, ctx: &GainContext<N, D>, _used: &[Gains<N>; D]) {
        if let Ok((_, next)) = self.plan(ctx) {
            self.axes = next;
        }
        self.misses = 0;
        if ctx.dt != self.last_interval {
            let per = N::Length::from_f64_lossy(1.0) / ctx.dt;
            if per.is_valid() {
                self.last_interval = ctx.dt;
                self.per_last_interval = per;
            }
        }
    }

    fn initialised(&mut self, n: u32) {
        if n <= 1 {
            GainSchedule::<N, D>::reset(self);
        }
    }

    fn missed(&mut self) {
        self.misses = self.misses.saturating_add(1);
    }

    fn reset(&mut self) {
        self.axes = [Self::fresh_axis(self.n_max); D];
        self.misses = 0;
        self.last_interval = N::Interval::ZERO;
        self.per_last_interval = N::Speed::ZERO;
    }
}

// The gains of an update and the axes' state after it (`AutoGains::plan`).
type Plan<N, const D: usize> = ([Gains<N>; D], [AutoAxis<N>; D]);
