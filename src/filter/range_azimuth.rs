//! The range–azimuth projection filter of He, Peng, Ling & Quan ("A Distance
//! Azimuth Tracking Algorithm Based on Alpha-beta Filtering"), for TCAS-style
//! inputs: slant range R (m) and azimuth B (rad, clockwise from the y axis,
//! x = R sin B, y = R cos B).
//!
//! The state is a constant-velocity track in x/y. Every measurement is split
//! into the direction along the line of sight (range, measured with variance
//! σ_R²) and the direction across it (cross-range, measured with variance
//! VAR = R²·σ_B² because a bearing error δB moves the point by R·δB). Each
//! direction has its own gains from its own covariance: α, β along range
//! (He et al. eq. 9), W1, W2 across (eq. 10). The residuals along and across
//! (eq. 11) are projected back onto x and y (eqs. 12–13).
//!
//! # Readings of the paper
//!
//! The paper's notation slips in four places. This module implements the
//! reading that is mathematically consistent, and the host tests check it
//! against an independent f64 implementation of the same reading
//! (`host-tests/src/reference_ra.rs`):
//!
//! 1. **Eq. (11) uses the predicted position.** The paper writes
//!    RESID_R = R − (X_k sin B + Y_k cos B) and RESID_CR = X_k cos B − Y_k sin B
//!    right after defining X_k = R sin B, Y_k = R cos B as the *measured*
//!    projections; with those both residuals are identically zero. The
//!    residuals are only meaningful with the *predicted* position
//!    (X_k|k−1, Y_k|k−1) and the *measured* R, B: RESID_R is then the
//!    measurement-minus-prediction along the line of sight u = (sin B, cos B),
//!    and RESID_CR = p·v with v = (cos B, −sin B) is the
//!    prediction-minus-measurement across it (the measurement has no v
//!    component). That sign is why eq. (12) *subtracts* the W terms.
//! 2. **Eqs. (12)–(13) start from the prediction.** They write X_{k−1},
//!    Ẋ_{k−1} on the right-hand side; without the prediction step
//!    X_k|k−1 = X_{k−1} + T·Ẋ_{k−1} (the paper's own eq. 4) the position
//!    would lag by T·Ẋ every scan. The velocity prediction is Ẋ_{k−1}.
//! 3. **Eq. (9) uses the range variance.** The paper divides by
//!    PCOV₁₁ + VAR in both eq. (9) and eq. (10). With the same variance the
//!    gains coincide (α = W1, β/T = W2) and eqs. (12)–(13) collapse to
//!    x += α·(z_x − x_p): a plain per-axis filter, contradicting the paper's
//!    premise that range and cross-range residuals are treated differently.
//!    Along the line of sight the measurement variance is the range variance
//!    σ_R² (the paper's "Navr = 100 m" range noise), so eq. (9) uses
//!    PCOV₁₁ + σ_R².
//! 4. **Two covariances, and their update.** Eqs. (7)–(8) predict one matrix
//!    P, but eqs. (9) and (10) need the covariance *along* and *across* the
//!    line of sight, which differ because the measurement variances do. The
//!    filter keeps one 2×2 position/velocity covariance per direction
//!    (P_R along, P_C across), predicts each with eq. (8), and — the paper
//!    gives no update — applies the Kalman update that eq. (7)'s P_{k−1}
//!    ("the variance matrix of the estimated error") presupposes:
//!    P⁺ = (I − K·D)·PCOV with K = (α, β/T) or (W1, W2) and D = (1, 0).
//!    This is exactly the Kalman filter on the converted measurement when
//!    the covariance is aligned with the line of sight; the only
//!    approximation left is that the line of sight's rotation between scans
//!    is not carried into the covariances (it is small: the azimuth changes
//!    by (cross-range speed)·T/R per scan).
//!
//! VAR uses the *measured* range of the current scan (as the paper writes
//! it). Its square root σ_C = R·σ_B has a floor of 1 m
//! ([`CROSS_RANGE_SIGMA_FLOOR`], active only below R = 11.5 m with the
//! default σ_B²) so the gains stay defined for a target passing through the
//! sensor.
//!
//! Initialisation is two-point, as the αβ filter (Al-Wagih & Abdulla eqs.
//! 9–10): position from the first measurement, velocity from the difference
//! of the first two; the covariances start at the two-point differencing
//! values P = [σ², σ²/T; σ²/T, (σ₁² + σ²)/T²] (σ₁, σ the first and second
//! points' standard deviations in that direction), and filtering with eqs.
//! (7)–(13) starts at the third measurement.
//!
//! # Initiation under bearing noise
//!
//! A two-point velocity carries the cross-range noise over T: at 18.5 km
//! with σ_B = 2° it is √2·646 m/s per scan, faster than any aircraft.
//! With a bound V on the relative speed
//! ([`RangeAzimuthNoise::with_speed_bound`]; TCAS II tracks closures up to
//! 1200 kt, FAA booklet "Introduction to TCAS II Version 7.1", Surveillance) the
//! first point is a state with covariance: position measured (σ_R along,
//! R·σ_B across), velocity zero with σ_v = V/2 per component (a velocity
//! uniform on the disc |v| ≤ V has that variance), and the second
//! measurement is an ordinary filtered update over the time since the
//! first (Bar-Shalom, Li & Kirubarajan, *Estimation with Applications to
//! Tracking and Navigation*, §5.5.3: one-point initialisation with a
//! velocity prior). Each direction keeps its own weights: along range
//! σ_R ≪ T·σ_v and the range rate is taken from the two ranges; across
//! range R·σ_B ≫ T·σ_v and the cross-range velocity stays with the prior
//! until the bearing track has the information. A filtered velocity faster
//! than V is scaled onto it (the projection onto the speeds that exist),
//! so noise alone never takes the track out of the envelope.
//!
//! # Fixed point: covariances as square-root factors
//!
//! In m² the covariances do not fit Q32.32 (range ±2.1·10⁹) in the paper's
//! own scenario: at R = 280 km, VAR = 280 000²·7.569·10⁻³ = 5.93·10⁸ m², and
//! the first prediction across range is PCOV₁₁ = VAR + 2VAR + 2VAR =
//! 2.97·10⁹ m² (T = 1 s), already saturated; at 400 km VAR alone is 1.2·10⁹.
//! Dividing by VAR fixes the range but not the resolution: the steady-state
//! velocity variance across range (≈ 1 m²/s²) over VAR is ≈ 2·10⁻⁹, seven
//! Q32.32 steps, and a first version built that way drifted 17 m from the
//! f64 reference over the paper's 500 s.
//!
//! So each covariance is kept as its Cholesky factor L (P = L·Lᵀ, see
//! [`CovarianceFactor`]) in physical units: standard deviations in m and
//! m/s, which Q32.32 holds from 2.3·10⁻¹⁰ to 2.1·10⁹ — a variance range of
//! 10⁻¹⁹ to 4·10¹⁸. Nothing of size R² is ever formed (√VAR = R·σ_B is
//! used, and σ_B = √σ_B² is taken once). The algebra is the same filter:
//!
//! * eq. (8) becomes L⁻ = the Cholesky factor of M·Mᵀ for
//!   M = [Φ·L | Γ·√Q] (L⁻L⁻ᵀ = ΦPΦᵀ + ΓQΓᵀ exactly), formed from M's rows:
//!   their lengths, dot product and 2×2 minors (Lagrange's identity),
//!   every length taken with a hypot that never squares its arguments;
//! * eqs. (9)–(10) and the update P⁺ = (I − KD)·PCOV become, with
//!   u = a/σ (a = √PCOV₁₁, σ the direction's measurement standard
//!   deviation): gains u²/(1 + u²) and (b/σ)·u/(1 + u²); a and b divided
//!   by √(1 + u²), c unchanged — written with the ratio ≤ 1 of a and σ so
//!   no square exceeds 1.
//!
//! Magnitudes: a ≤ √5·σ after initialisation and < σ after an update (a few
//! 10⁴ m across range at 400 km); b ≈ σ/T up to 7·10⁵ m/s for the worst
//! initialisation (35 km over 0.05 s), c similar; coasting grows a
//! linearly (a ≈ c·t), so saturation (a > 2.1·10⁹ m) takes 3·10³ s of
//! coasting even from that worst start. Positions (±400 km), velocities and the
//! products R·sin B stay within the ranges of the αβ filter. A saturated
//! step is refused and counted like [`crate::filter::KinematicFilter`].
//!
//! In a [`Numeric`] system the covariance factors, the noise's standard
//! deviations and the velocity are [`Numeric::Ratio`] numbers in SI units:
//! their range spans decades, and in the fast fixed point
//! ([`crate::Fixed32`]) a ratio carries its own exponent (2⁻³⁰ relative).
//! The velocity is one of them because a two-point velocity from polar
//! measurements carries the cross-range noise over T (34 km/s for the
//! paper's 5° at 280 km), beyond a speed format. Positions are
//! [`Numeric::Length`]; sin and cos come from [`Numeric::sin_cos`] (a sine
//! table with a Taylor correction on a binary angle in the fast fixed
//! point).
//!
//! Accuracy against the independent f64 reference (host-tests
//! `tests/it/filter/range_azimuth.rs`, the paper's 280 km scenario over 500 scans and a
//! TCAS encounter with coasts): f32 within 0.15 m and 0.03 m/s, Q32.32
//! within 3.8 mm and 6.6·10⁻⁵ m/s, gains within 5.6·10⁻⁹; the fast fixed
//! point within 1.9 mm and 2.6·10⁻⁴ m/s, gains within 1.1·10⁻⁷.

use crate::filter::{check_interval, FilterError, Phase};
use crate::num::{Numeric, Quantity, Real};

/// σ_B² used by He et al. (VAR = R²·7.569·10⁻³, about 5° RMS).
pub const PAPER_BEARING_VARIANCE: f64 = 7.569e-3;

/// Smallest cross-range standard deviation used, in metres (see the module
/// docs: keeps the cross-range gains defined as R → 0).
pub const CROSS_RANGE_SIGMA_FLOOR: f64 = 1.0;
const _: () = assert!(
    CROSS_RANGE_SIGMA_FLOOR == 1.0,
    "cross_range_sigma uses Ratio::ONE"
);

/// Why a noise configuration was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum NoiseError {
    /// A variance is NaN, infinite or not representable.
    NotFinite,
    /// A measurement variance is ≤ 0, or the process noise is < 0.
    OutOfRange,
}

impl core::fmt::Display for NoiseError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            NoiseError::NotFinite => "noise variance is not a finite number",
            NoiseError::OutOfRange => {
                "measurement variances must be > 0 and the process noise >= 0"
            }
        })
    }
}

impl core::error::Error for NoiseError {}

/// Measurement and process noise of a [`RangeAzimuthFilter`]. Variances and
/// standard deviations are [`Numeric::Ratio`] numbers in SI units (m², rad²,
/// m²/s⁴; m, rad, m/s²): their range spans decades.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeAzimuthNoise<N: Numeric> {
    range_variance: N::Ratio,
    bearing_variance: N::Ratio,
    process_noise: N::Ratio,
    /// σ_R, m.
    range_sigma: N::Ratio,
    /// σ_B, rad.
    bearing_sigma: N::Ratio,
    /// √Q, m/s².
    process_sigma: N::Ratio,
    /// The largest speed of the target relative to the sensor, m/s, and
    /// the prior standard deviation of each velocity component it implies
    /// (half of it: a velocity uniform on the disc of that radius); `None`:
    /// He et al.'s two-point initiation.
    speed_bound: Option<(N::Ratio, N::Ratio)>,
}

impl<N: Numeric> RangeAzimuthNoise<N> {
    /// * `range_variance` σ_R², m², > 0: the along-range measurement
    ///   variance (reading 3 of the module docs).
    /// * `bearing_variance` σ_B², rad², > 0: VAR = R²·σ_B² (He et al. use
    ///   [`PAPER_BEARING_VARIANCE`]).
    /// * `process_noise` Q, m²/s⁴, ≥ 0: the variance of the white
    ///   acceleration u_k of eq. (1), the Q of eqs. (7)–(8), the same along
    ///   and across range.
    pub fn new(
        range_variance: N::Ratio,
        bearing_variance: N::Ratio,
        process_noise: N::Ratio,
    ) -> Result<Self, NoiseError> {
        if !(range_variance.is_valid() && bearing_variance.is_valid() && process_noise.is_valid()) {
            return Err(NoiseError::NotFinite);
        }
        let zero = N::Ratio::ZERO;
        if range_variance <= zero || bearing_variance <= zero || process_noise < zero {
            return Err(NoiseError::OutOfRange);
        }
        let range_sigma = range_variance.sqrt();
        let bearing_sigma = bearing_variance.sqrt();
        let process_sigma = process_noise.sqrt();
        if !(range_sigma.is_valid() && bearing_sigma.is_valid() && process_sigma.is_valid())
            || range_sigma == zero
            || bearing_sigma == zero
        {
            // A variance below the representation's resolution.
            return Err(NoiseError::OutOfRange);
        }
        Ok(RangeAzimuthNoise {
            range_variance,
            bearing_variance,
            process_noise,
            range_sigma,
            bearing_sigma,
            process_sigma,
            speed_bound: None,
        })
    }

    /// The same noise with a bound `max_speed` (m/s, > 0) on the target's
    /// speed relative to the sensor: initiation then weights the
    /// measurements by their covariance against a velocity prior (zero
    /// mean, σ = `max_speed`/2 per component, along and across range
    /// apart) instead of differencing two points, and a filtered velocity
    /// is never faster than the bound (see the module docs, "Initiation
    /// under bearing noise").
    pub fn with_speed_bound(self, max_speed: N::Ratio) -> Result<Self, NoiseError> {
        if !max_speed.is_valid() {
            return Err(NoiseError::NotFinite);
        }
        let prior = max_speed.half();
        if max_speed <= N::Ratio::ZERO || prior <= N::Ratio::ZERO {
            return Err(NoiseError::OutOfRange);
        }
        Ok(RangeAzimuthNoise {
            speed_bound: Some((max_speed, prior)),
            ..self
        })
    }

    /// [`Self::with_speed_bound`] from an `f64` speed, m/s.
    pub fn with_speed_bound_f64(self, max_speed: f64) -> Result<Self, NoiseError> {
        let v = N::Ratio::try_from_f64(max_speed).map_err(|_| NoiseError::NotFinite)?;
        self.with_speed_bound(v)
    }

    /// The bound on the relative speed, m/s, if any.
    pub fn speed_bound(&self) -> Option<N::Ratio> {
        self.speed_bound.map(|(v, _)| v)
    }

    /// [`Self::new`] from `f64` values (configuration, tools).
    pub fn new_f64(
        range_variance: f64,
        bearing_variance: f64,
        process_noise: f64,
    ) -> Result<Self, NoiseError> {
        let c = |v| N::Ratio::try_from_f64(v).map_err(|_| NoiseError::NotFinite);
        Self::new(c(range_variance)?, c(bearing_variance)?, c(process_noise)?)
    }

    /// The paper's bearing variance ([`PAPER_BEARING_VARIANCE`]) with the
    /// given range variance (m²) and process noise (m²/s⁴).
    pub fn paper_bearing_f64(range_variance: f64, process_noise: f64) -> Result<Self, NoiseError> {
        Self::new_f64(range_variance, PAPER_BEARING_VARIANCE, process_noise)
    }

    /// σ_R², m².
    pub fn range_variance(&self) -> N::Ratio {
        self.range_variance
    }
    /// σ_B², rad².
    pub fn bearing_variance(&self) -> N::Ratio {
        self.bearing_variance
    }
    /// Q, m²/s⁴.
    pub fn process_noise(&self) -> N::Ratio {
        self.process_noise
    }
    /// σ_R = √(σ_R²), m (formed once, at construction).
    pub fn range_sigma(&self) -> N::Ratio {
        self.range_sigma
    }
    /// σ_B = √(σ_B²), rad (formed once, at construction).
    pub fn bearing_sigma(&self) -> N::Ratio {
        self.bearing_sigma
    }
    /// √Q, m/s² (formed once, at construction).
    pub fn process_sigma(&self) -> N::Ratio {
        self.process_sigma
    }

    /// Cross-range standard deviation √VAR = R·σ_B at range R (m), floored
    /// at [`CROSS_RANGE_SIGMA_FLOOR`].
    pub fn cross_range_sigma(&self, range: N::Length) -> N::Ratio {
        // The floor is one metre (checked at compile time below): `ONE`,
        // not a conversion from f64 on every update.
        (N::Ratio::from(range) * self.bearing_sigma).max_of(N::Ratio::ONE)
    }
}

pub use crate::num::{azimuth_of, hypot};

/// A position/velocity covariance along one direction, as its lower
/// Cholesky factor L = [a 0; b c] (P = L·Lᵀ): P₁₁ = a² (m²),
/// P₁₂ = a·b (m²/s), P₂₂ = b² + c² (m²/s²); a, c ≥ 0 in m and m/s, held as
/// [`Numeric::Ratio`] numbers (their range spans decades).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CovarianceFactor<N: Numeric> {
    /// L₁₁ = √P₁₁, m (≥ 0).
    pub a: N::Ratio,
    /// L₂₁ = P₁₂/a, m/s.
    pub b: N::Ratio,
    /// L₂₂ = √(P₂₂ − b²), m/s (≥ 0).
    pub c: N::Ratio,
}

impl<N: Numeric> CovarianceFactor<N> {
    const ZERO: Self = CovarianceFactor {
        a: N::Ratio::ZERO,
        b: N::Ratio::ZERO,
        c: N::Ratio::ZERO,
    };

    /// The covariance [P₁₁, P₁₂, P₂₂] in f64 (for tools and tests; in m²
    /// units it may exceed what `N` can hold).
    pub fn covariance_f64(&self) -> [f64; 3] {
        let (a, b, c) = (self.a.to_f64(), self.b.to_f64(), self.c.to_f64());
        [a * a, a * b, b * b + c * c]
    }

    /// A measured position (σ) and a velocity prior (σ_v, uncorrelated):
    /// P = [σ², 0; 0, σ_v²], whose factor is a = σ, b = 0, c = σ_v.
    fn position_with_prior(sigma: N::Ratio, velocity_sigma: N::Ratio) -> Self {
        CovarianceFactor {
            a: sigma,
            b: N::Ratio::ZERO,
            c: velocity_sigma,
        }
    }

    /// Two-point differencing: P = [σ², σ²/T; σ²/T, (σ₁² + σ²)/T²], whose
    /// factor is a = σ, b = σ/T, c = σ₁/T.
    fn two_point(sigma: N::Ratio, first_sigma: N::Ratio, elapsed: N::Ratio) -> Self {
        CovarianceFactor {
            a: sigma,
            b: sigma / elapsed,
            c: first_sigma / elapsed,
        }
    }

    /// He et al. eq. (8), PCOV = Φ P Φᵀ + Γ Q Γᵀ with Φ = [1 T; 0 1],
    /// Γ = [T²/2; T], in factor form: the rows of M = [Φ·L | Γ·√Q] =
    /// [a + T b, T c, g₀; b, c, g₁] (`noise` = (g₀, g₁), formed once per
    /// interval) give PCOV = M·Mᵀ, whose factor is a' = |row₀|,
    /// b' = row₀·row₁/a' and c' = |row₀ × row₁|/a' (Lagrange's identity,
    /// c'² = |row₀|²|row₁|² − (row₀·row₁)² over a'², without the
    /// subtraction). The 2×2 minors of M are a·c (det Φ = 1), a g₁ + b g₀
    /// and c g₀ (T g₁ = 2 g₀): no cancellation. Every product is of a
    /// quantity and a ratio to a' in a fixed-range format (Q32.32 would
    /// overflow on a·c); a format with relative precision (floats,
    /// [`crate::num::scaled::Scaled`]) forms the dot product and the minors
    /// themselves and divides each by a' once: two quotients instead of four
    /// ([`Quantity::RELATIVE_PRECISION`]). Lengths by hypots that never square their
    /// arguments.
    fn predict(&self, dt: N::Ratio, noise: &ProcessNoiseColumn<N>) -> Self {
        let CovarianceFactor { a, b, c } = *self;
        let (g0, g1) = (noise.position, noise.velocity);
        let (m00, m01, a_new) = self.first_row(dt, noise);
        if a_new == N::Ratio::ZERO {
            // Row 0 is zero: PCOV = [0 0; 0 |row₁|²].
            return CovarianceFactor {
                a: a_new,
                b: N::Ratio::ZERO,
                c: b.hypot3(c, g1),
            };
        }
        if <N::Ratio as Quantity>::RELATIVE_PRECISION {
            let (dot, cross) = self.row_products(m00, m01, noise);
            return CovarianceFactor {
                a: a_new,
                b: dot / a_new,
                c: cross / a_new,
            };
        }
        let (u, v, w, s) = (m00 / a_new, m01 / a_new, g0 / a_new, a / a_new);
        CovarianceFactor {
            a: a_new,
            b: u * b + v * c + w * g1,
            c: (c * s).hypot3(g1 * s + b * w, c * w),
        }
    }

    /// Row 0 of M = [Φ·L | Γ·√Q] of [`Self::predict`], (a + T b, T c), and
    /// its length a' = √PCOV₁₁.
    #[inline(always)]
    fn first_row(
        &self,
        dt: N::Ratio,
        noise: &ProcessNoiseColumn<N>,
    ) -> (N::Ratio, N::Ratio, N::Ratio) {
        let m00 = self.a + dt * self.b;
        let m01 = dt * self.c;
        (m00, m01, m00.hypot3(m01, noise.position))
    }

    /// row₀·row₁ and |row₀ × row₁| = |(c g₀, a g₁ + b g₀, a c)| of
    /// [`Self::predict`]'s M, for formats with relative precision.
    #[inline(always)]
    fn row_products(
        &self,
        m00: N::Ratio,
        m01: N::Ratio,
        noise: &ProcessNoiseColumn<N>,
    ) -> (N::Ratio, N::Ratio) {
        let CovarianceFactor { a, b, c } = *self;
        let (g0, g1) = (noise.position, noise.velocity);
        let dot = m00 * b + m01 * c + g0 * g1;
        let cross = (a * c).hypot3(a * g1 + b * g0, c * g0);
        (dot, cross)
    }

    /// [`Self::predict`] then [`Self::update`] (eqs. 8–10 and the update).
    /// In the fast fixed point, whose [`crate::num::scaled::Scaled`]
    /// quotient costs about two products, the predicted b' = row₀·row₁/a'
    /// is not formed: the update needs b'/h = row₀·row₁/(a'·h) and
    /// b'·σ/h = (b'/h)·σ, one quotient instead of two. (Floats keep the two
    /// quotients: in soft float on the M3 the fused form measured slower.)
    #[inline(always)]
    fn predict_update(
        &self,
        dt: N::Ratio,
        noise: &ProcessNoiseColumn<N>,
        sigma: N::Ratio,
    ) -> (N::Ratio, N::Ratio, Self) {
        if !(<N::Ratio as Quantity>::RELATIVE_PRECISION && N::FUSED_PRODUCTS) {
            return self.predict(dt, noise).update(sigma);
        }
        let (m00, m01, a_new) = self.first_row(dt, noise);
        if a_new == N::Ratio::ZERO {
            return self.predict(dt, noise).update(sigma);
        }
        let (dot, cross) = self.row_products(m00, m01, noise);
        let h = a_new.hypot(sigma);
        let a_over_h = a_new / h;
        let shrink = sigma / h;
        let a_times_h = a_new * h;
        // a'·h beyond the format (a' above 2⁶⁵ m): two quotients instead.
        // (a'·h ≥ a'² cannot underflow: a' ≥ σ/√n after n updates.)
        let b_over_h = if a_times_h.is_valid() {
            dot / a_times_h
        } else {
            dot / a_new / h
        };
        (
            a_over_h * a_over_h,
            b_over_h * a_over_h,
            CovarianceFactor {
                a: a_new * shrink,
                b: b_over_h * sigma,
                c: cross / a_new,
            },
        )
    }

    /// Position and velocity gains K = PCOV·Dᵀ/(PCOV₁₁ + σ²) for a position
    /// measurement of standard deviation `sigma` (eq. 9: α and β/T; eq. 10:
    /// W1 and W2), and the factor of the updated covariance (I − K D)·PCOV.
    /// With h = √(a² + σ²) (a hypot: no square is formed): the gains are
    /// (a/h)² and (b/h)·(a/h), and a, b shrink by σ/h (P₁₁⁺ = a²σ²/h²), c
    /// unchanged. Every ratio formed is ≤ 1 or b/h ≤ b/σ.
    fn update(&self, sigma: N::Ratio) -> (N::Ratio, N::Ratio, Self) {
        let CovarianceFactor { a, b, c } = *self;
        let h = a.hypot(sigma);
        let a_over_h = a / h;
        let shrink = sigma / h;
        (
            a_over_h * a_over_h,
            (b / h) * a_over_h,
            CovarianceFactor {
                a: a * shrink,
                b: b * shrink,
                c,
            },
        )
    }

    fn is_valid(&self) -> bool {
        self.a.is_valid() && self.b.is_valid() && self.c.is_valid()
    }
}

/// Γ·√Q of eq. (8) for one interval T: (T²·√Q/2, T·√Q), the same along
/// and across range.
struct ProcessNoiseColumn<N: Numeric> {
    position: N::Ratio,
    velocity: N::Ratio,
}

impl<N: Numeric> ProcessNoiseColumn<N> {
    fn new(dt: N::Ratio, process_sigma: N::Ratio) -> Self {
        let velocity = dt * process_sigma;
        ProcessNoiseColumn {
            position: (dt * velocity).half(),
            velocity,
        }
    }
}

/// The gains an update used.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeAzimuthGains<N: Numeric> {
    /// α along range (eq. 9).
    pub alpha: N::Ratio,
    /// β along range (eq. 9: T·PCOV₁₂/(PCOV₁₁ + σ_R²); the velocity gain is β/T).
    pub beta: N::Ratio,
    /// W1, position gain across range (eq. 10).
    pub w1: N::Ratio,
    /// W2, velocity gain across range (eq. 10), in 1/s.
    pub w2: N::Ratio,
}

/// The prediction an update corrected and its residuals.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeAzimuthInnovation<N: Numeric> {
    /// Predicted position (x, y), m.
    pub predicted: [N::Length; 2],
    /// RESID_R = R − (x_p sin B + y_p cos B), m (eq. 11, reading 1).
    pub range_residual: N::Length,
    /// RESID_CR = x_p cos B − y_p sin B, m (eq. 11, reading 1): prediction
    /// minus measurement across the line of sight.
    pub cross_range_residual: N::Length,
    /// The gains the update used (eqs. 9–10).
    pub gains: RangeAzimuthGains<N>,
}

/// What an update did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RangeAzimuthOutcome<N: Numeric> {
    /// First measurement: position only.
    FirstPoint,
    /// Second measurement: velocity from the difference, covariances set.
    SecondPoint,
    /// A filtered update (eqs. 7–13).
    Filtered(RangeAzimuthInnovation<N>),
}

/// Predicted position and velocity after an interval.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PlanarPrediction<N: Numeric> {
    /// (x, y), m.
    pub position: [N::Length; 2],
    /// (ẋ, ẏ), m/s, as [`Numeric::Ratio`] numbers
    /// ([`RangeAzimuthState::velocity`]).
    pub velocity: [N::Ratio; 2],
}

/// The range–azimuth projection filter (He, Peng, Ling & Quan, eqs. 7–13):
/// its noise figures and its [`RangeAzimuthState`], which it dereferences to
/// for reading. See the module docs for the readings implemented.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeAzimuthFilter<N: Numeric> {
    noise: RangeAzimuthNoise<N>,
    state: RangeAzimuthState<N>,
}

impl<N: Numeric> RangeAzimuthFilter<N> {
    /// An empty filter, waiting for its first measurement.
    pub fn new(noise: RangeAzimuthNoise<N>) -> Self {
        RangeAzimuthFilter {
            noise,
            state: RangeAzimuthState::EMPTY,
        }
    }

    /// The measurement and process noise the gains are computed from.
    pub fn noise(&self) -> &RangeAzimuthNoise<N> {
        &self.noise
    }

    /// [`RangeAzimuthState::update`] with this filter's noise.
    pub fn update(
        &mut self,
        range: N::Length,
        azimuth: N::Angle,
        dt: N::Interval,
    ) -> Result<RangeAzimuthOutcome<N>, FilterError> {
        self.state.update(&self.noise, range, azimuth, dt)
    }

    /// [`RangeAzimuthState::coast`] with this filter's noise.
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        self.state.coast(&self.noise, dt)
    }
}

impl<N: Numeric> core::ops::Deref for RangeAzimuthFilter<N> {
    type Target = RangeAzimuthState<N>;

    fn deref(&self) -> &RangeAzimuthState<N> {
        &self.state
    }
}

/// The state of a [`RangeAzimuthFilter`] without its noise figures: what a
/// track table keeps per track, the noise being the table's configuration
/// ([`crate::track::RangeAzimuthTrack`]). Every call that needs the noise
/// takes it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeAzimuthState<N: Numeric> {
    phase: Phase,
    position: [N::Length; 2],
    /// m/s, as [`Numeric::Ratio`] numbers: a two-point velocity from
    /// polar measurements carries the cross-range noise divided by T (34 km/s
    /// for He et al.'s 5° bearing noise at 280 km), beyond a speed format.
    velocity: [N::Ratio; 2],
    /// While `OnePoint`: time since the first measurement (coasts add to it).
    since_first: N::Interval,
    /// While `OnePoint`: √VAR of the first measurement.
    first_cross_sigma: N::Ratio,
    range_factor: CovarianceFactor<N>,
    cross_factor: CovarianceFactor<N>,
    /// Saturating (u16: the state's bytes are per track; the getter widens).
    saturations: u16,
}

impl<N: Numeric> RangeAzimuthState<N> {
    /// Waiting for the first measurement.
    pub const EMPTY: Self = RangeAzimuthState {
        phase: Phase::Empty,
        position: [N::Length::ZERO; 2],
        velocity: [N::Ratio::ZERO; 2],
        since_first: N::Interval::ZERO,
        first_cross_sigma: N::Ratio::ZERO,
        range_factor: CovarianceFactor::ZERO,
        cross_factor: CovarianceFactor::ZERO,
        saturations: 0,
    };

    /// Which stage of two-point initialisation the filter is in.
    pub fn phase(&self) -> Phase {
        self.phase
    }
    /// Estimated (x, y), m (x = R sin B, y = R cos B).
    pub fn position(&self) -> [N::Length; 2] {
        self.position
    }
    /// Estimated (ẋ, ẏ), m/s, as [`Numeric::Ratio`] numbers (zero before
    /// the second measurement; see the field's note on why not a speed).
    pub fn velocity(&self) -> [N::Ratio; 2] {
        self.velocity
    }
    /// Estimated range √(x² + y²), m: the re-synthesis of He et al. §3.
    /// Invalid only if the position is beyond the length format.
    pub fn range(&self) -> N::Length {
        let [x, y] = self.position;
        N::hypot(x, y)
    }
    /// Estimated azimuth atan2(x, y) in [0, 2π), rad.
    pub fn azimuth(&self) -> N::Angle {
        let [x, y] = self.position;
        N::azimuth(x, y)
    }
    /// Estimated range rate ṙ = (x ẋ + y ẏ)/r, m/s (negative when closing),
    /// computed as the velocity's component along the unit line of sight so
    /// no product of a position and a velocity is formed. Zero at r = 0.
    pub fn range_rate(&self) -> N::Speed {
        let [x, y] = self.position;
        let [vx, vy] = self.velocity;
        let r = N::hypot(x, y);
        if r == N::Length::ZERO {
            return N::Speed::ZERO;
        }
        N::Speed::from((x / r) * vx + (y / r) * vy)
    }
    /// Covariance factor along range (zero before tracking).
    pub fn range_covariance(&self) -> CovarianceFactor<N> {
        self.range_factor
    }
    /// Covariance factor across range (zero before tracking).
    pub fn cross_range_covariance(&self) -> CovarianceFactor<N> {
        self.cross_factor
    }
    /// How many updates or coasts were discarded because they saturated
    /// (saturating at 65,535).
    pub fn saturations(&self) -> u32 {
        u32::from(self.saturations)
    }

    fn saturated(&mut self) -> FilterError {
        self.saturations = self.saturations.saturating_add(1);
        FilterError::Saturated
    }

    /// The position and velocity predicted `dt` ahead, without changing the
    /// filter (constant velocity, eq. 4).
    pub fn predict(&self, dt: N::Interval) -> Result<PlanarPrediction<N>, FilterError> {
        check_interval(dt)?;
        let [x, y] = self.position;
        let [vx, vy] = self.velocity;
        let t = N::Ratio::from(dt);
        let p = PlanarPrediction::<N> {
            position: [x + N::Length::from(vx * t), y + N::Length::from(vy * t)],
            velocity: self.velocity,
        };
        if p.position.iter().all(|v| v.is_valid()) {
            Ok(p)
        } else {
            Err(FilterError::Saturated)
        }
    }

    /// Incorporates range `range` (m, > 0) and azimuth `azimuth` (rad, any
    /// finite value: it is used through sin and cos only, so B + 2π and
    /// B − 2π are the same measurement as B), taken `dt` after the previous
    /// call.
    ///
    /// A non-finite range or azimuth, a range ≤ 0, an interval that is not
    /// a finite number > 0, or an update whose arithmetic saturates, is
    /// refused and leaves the filter unchanged (the last is counted).
    pub fn update(
        &mut self,
        noise: &RangeAzimuthNoise<N>,
        range: N::Length,
        azimuth: N::Angle,
        dt: N::Interval,
    ) -> Result<RangeAzimuthOutcome<N>, FilterError> {
        if !(range.is_valid() && azimuth.is_valid()) || range <= N::Length::ZERO {
            return Err(FilterError::InvalidMeasurement);
        }
        check_interval(dt)?;
        let (sin_b, cos_b) = N::sin_cos(azimuth);
        let cross_sigma = noise.cross_range_sigma(range);
        if !cross_sigma.is_valid() {
            return Err(self.saturated());
        }
        match self.phase {
            // The filter projects on sin B and cos B itself: the measured
            // point (R sin B, R cos B) is formed for initialisation only.
            Phase::Tracking => self.filter(noise, range, sin_b, cos_b, cross_sigma, dt),
            Phase::Empty => {
                let measured = self.measured_point(range, sin_b, cos_b)?;
                self.position = measured;
                self.velocity = [N::Ratio::ZERO; 2];
                self.since_first = N::Interval::ZERO;
                self.first_cross_sigma = cross_sigma;
                if let Some((_, prior)) = noise.speed_bound {
                    self.range_factor =
                        CovarianceFactor::position_with_prior(noise.range_sigma, prior);
                    self.cross_factor = CovarianceFactor::position_with_prior(cross_sigma, prior);
                }
                self.phase = Phase::OnePoint;
                Ok(RangeAzimuthOutcome::FirstPoint)
            }
            Phase::OnePoint if noise.speed_bound.is_some() => {
                // The first point and the velocity prior are a state with
                // its covariance: the second measurement is a filtered
                // update over the time since the first.
                let elapsed = self.since_first + dt;
                if !elapsed.is_valid() {
                    return Err(self.saturated());
                }
                let outcome = self.filter(noise, range, sin_b, cos_b, cross_sigma, elapsed)?;
                self.phase = Phase::Tracking;
                Ok(outcome)
            }
            Phase::OnePoint => {
                let measured = self.measured_point(range, sin_b, cos_b)?;
                let elapsed = self.since_first + dt;
                let [x, y] = self.position;
                let t = N::Ratio::from(elapsed);
                let velocity = [
                    N::Ratio::from(measured[0] - x) / t,
                    N::Ratio::from(measured[1] - y) / t,
                ];
                let sigma_r = noise.range_sigma;
                let range_factor = CovarianceFactor::two_point(sigma_r, sigma_r, t);
                let cross_factor =
                    CovarianceFactor::two_point(cross_sigma, self.first_cross_sigma, t);
                if !(velocity.iter().all(|v| v.is_valid())
                    && range_factor.is_valid()
                    && cross_factor.is_valid())
                {
                    return Err(self.saturated());
                }
                self.position = measured;
                self.velocity = velocity;
                self.range_factor = range_factor;
                self.cross_factor = cross_factor;
                self.phase = Phase::Tracking;
                Ok(RangeAzimuthOutcome::SecondPoint)
            }
        }
    }

    /// The measured point (x, y) = (R sin B, R cos B); refused (and
    /// counted) if it saturates.
    fn measured_point(
        &mut self,
        range: N::Length,
        sin_b: N::Ratio,
        cos_b: N::Ratio,
    ) -> Result<[N::Length; 2], FilterError> {
        let measured = [sin_b * range, cos_b * range];
        if measured.iter().all(|v| v.is_valid()) {
            Ok(measured)
        } else {
            Err(self.saturated())
        }
    }

    fn filter(
        &mut self,
        noise: &RangeAzimuthNoise<N>,
        range: N::Length,
        sin_b: N::Ratio,
        cos_b: N::Ratio,
        cross_sigma: N::Ratio,
        dt: N::Interval,
    ) -> Result<RangeAzimuthOutcome<N>, FilterError> {
        let [x, y] = self.position;
        let [vx, vy] = self.velocity;
        let t = N::Ratio::from(dt);
        // Prediction (eq. 4 of the paper's αβ section; reading 2).
        let (xp, yp) = (x + N::Length::from(vx * t), y + N::Length::from(vy * t));
        // Eqs. (7)–(8), then eq. (9) with σ_R (reading 3) and eq. (10) with
        // √VAR, and the covariance update (reading 4).
        let process = ProcessNoiseColumn::new(t, noise.process_sigma);
        let (alpha, range_velocity_gain, range_factor) =
            self.range_factor
                .predict_update(t, &process, noise.range_sigma);
        let (w1, w2, cross_factor) = self.cross_factor.predict_update(t, &process, cross_sigma);
        // Eq. (11) with the predicted position (reading 1).
        let range_residual = range - (sin_b * xp + cos_b * yp);
        let cross_residual = cos_b * xp - sin_b * yp;
        // Eqs. (12)–(13).
        let along_x = sin_b * range_residual;
        let along_y = cos_b * range_residual;
        let across_x = cos_b * cross_residual;
        let across_y = sin_b * cross_residual;
        let position = [
            xp + alpha * along_x - w1 * across_x,
            yp + alpha * along_y + w1 * across_y,
        ];
        let metres = |l: N::Length| N::Ratio::from(l);
        let velocity = Self::within_speed_bound(
            noise,
            [
                vx + range_velocity_gain * metres(along_x) - w2 * metres(across_x),
                vy + range_velocity_gain * metres(along_y) + w2 * metres(across_y),
            ],
        );
        let innovation = RangeAzimuthInnovation::<N> {
            predicted: [xp, yp],
            range_residual,
            cross_range_residual: cross_residual,
            gains: RangeAzimuthGains::<N> {
                alpha,
                beta: range_velocity_gain * t,
                w1,
                w2,
            },
        };
        // Invalid values are sticky: checking the results covers every
        // intermediate.
        if !(position.iter().all(|v| v.is_valid())
            && velocity.iter().all(|v| v.is_valid())
            && range_factor.is_valid()
            && cross_factor.is_valid()
            && innovation.gains.beta.is_valid())
        {
            return Err(self.saturated());
        }
        self.position = position;
        self.velocity = velocity;
        self.range_factor = range_factor;
        self.cross_factor = cross_factor;
        Ok(RangeAzimuthOutcome::Filtered(innovation))
    }

    /// `velocity` scaled onto the speed bound when it is faster (the
    /// projection onto the speeds real targets fly); unchanged without a
    /// bound or when invalid (the caller refuses that).
    fn within_speed_bound(noise: &RangeAzimuthNoise<N>, velocity: [N::Ratio; 2]) -> [N::Ratio; 2] {
        let Some((max_speed, _)) = noise.speed_bound else {
            return velocity;
        };
        let [vx, vy] = velocity;
        let speed = vx.hypot(vy);
        if speed.is_valid() && speed > max_speed {
            let scale = max_speed / speed;
            [vx * scale, vy * scale]
        } else {
            velocity
        }
    }

    /// No measurement this scan: advance the state and both covariances by
    /// `dt` (eqs. 4 and 8). Before the second measurement the position holds
    /// and the interval is remembered for the velocity difference.
    pub fn coast(
        &mut self,
        noise: &RangeAzimuthNoise<N>,
        dt: N::Interval,
    ) -> Result<(), FilterError> {
        check_interval(dt)?;
        match self.phase {
            Phase::Empty => Ok(()),
            Phase::OnePoint => {
                let since_first = self.since_first + dt;
                if !since_first.is_valid() {
                    return Err(self.saturated());
                }
                self.since_first = since_first;
                Ok(())
            }
            Phase::Tracking => {
                let t = N::Ratio::from(dt);
                let process = ProcessNoiseColumn::new(t, noise.process_sigma);
                let range_factor = self.range_factor.predict(t, &process);
                let cross_factor = self.cross_factor.predict(t, &process);
                let position = self.predict(dt).map(|p| p.position);
                match position {
                    Ok(position) if range_factor.is_valid() && cross_factor.is_valid() => {
                        self.position = position;
                        self.range_factor = range_factor;
                        self.cross_factor = cross_factor;
                        Ok(())
                    }
                    _ => Err(self.saturated()),
                }
            }
        }
    }
}
