//! The optimal-linear yardstick: 2-D Kalman filters in `f64` with a
//! constant-velocity (4-state) and a constant-acceleration (6-state) model.
//!
//! Users pick an αβ filter over a Kalman filter for its cost; these filters
//! show in every results table what accuracy that choice gives up (or not).
//!
//! # Why hand-written
//! The matrices are at most 6 × 6 and the measurement is 2-D, so the only
//! inverse needed is of a 2 × 2 innovation covariance, written in closed form.
//! A few fixed-size array loops keep the code auditable against the textbook
//! equations, dependency-free and allocation-free; nalgebra would buy nothing
//! here but compile time.
//!
//! # Model
//! State per axis, axes stacked: `[x, ẋ, y, ẏ]` (CV) or
//! `[x, ẋ, ẍ, y, ẏ, ÿ]` (CA). Transition F(T) per axis: [[1, T], [0, 1]] or
//! [[1, T, T²/2], [0, 1, T], [0, 0, 1]]. Measurement z = H·x + w, H picks the
//! two positions, w ~ N(0, R) with R a full 2 × 2 covariance (a converted
//! polar measurement has correlated x/y errors: [`polar_measurement_covariance`]).
//! The axes share no process noise.
//!
//! Process noise (Bar-Shalom, Li & Kirubarajan, *Estimation with Applications
//! to Tracking and Navigation*, 2001, §6.2–6.3), per axis:
//! * [`ProcessNoise::DiscreteWhiteAcceleration`] (DWNA, CV only): the
//!   acceleration is constant over each period and white from period to
//!   period, variance σ²: Q = σ²·Γ Γᵀ, Γ = [T²/2, T]ᵀ.
//! * [`ProcessNoise::ContinuousWhiteAcceleration`] (CWNA, CV only): white
//!   acceleration of power spectral density q (m²/s³):
//!   Q = q·[[T³/3, T²/2], [T²/2, T]].
//! * [`ProcessNoise::WienerAcceleration`] (DWPA, CA only): the acceleration
//!   increment over each period is white with variance σ²:
//!   Q = σ²·Γ Γᵀ, Γ = [T²/2, T, 1]ᵀ.
//!
//! With DWNA and a fixed T the steady-state gains α = K_x, β = T·K_ẋ satisfy
//! Kalata's relation β = 2(2 − α) − 4√(1 − α) (Li, Zhao, Liang & Zhang eq. 7),
//! with tracking index λ = σT²/σ_w and λ² = β²/(1 − α); the
//! Benedict–Bordner relation β = α²/(2 − α) (Al-Wagih & Abdulla eq. 23b) is a
//! different curve and does not hold. Both facts are tested below.
//!
//! # Initialisation
//! Two-point, like the αβ filters (Al-Wagih & Abdulla eqs. 9–10): the first
//! measurement z₁ is stored; the second gives x = z₂, v = (z₂ − z₁)/T (T the
//! time since z₁, coasts included), a = 0, with the covariance of that
//! differencing estimate: P_xx = R₂, P_xv = R₂/T, P_vv = (R₁ + R₂)/T²
//! (Bar-Shalom et al. §5.5.3). For the CA filter the acceleration starts with
//! variance σ_a0² (a parameter, [`DEFAULT_INITIAL_ACCELERATION_SIGMA`]); since
//! (z₂ − z₁)/T is the velocity at the interval's midpoint, v(t₂) differs from
//! it by a·T/2, which adds σ_a0²T²/4 to P_vv and σ_a0²T/2 to P_va. The state
//! after two measurements is therefore exactly the αβ filter's, so the
//! comparison starts from the same point; filtering starts with the third.

use core::fmt;

/// A symmetric 2 × 2 covariance `[[xx, xy], [xy, yy]]` (m²).
pub type Cov2 = [[f64; 2]; 2];

/// σ_a0 (m/s²) of the CA filter's initial acceleration when not given: about
/// 1 g, a generous bound for aircraft and surface targets.
pub const DEFAULT_INITIAL_ACCELERATION_SIGMA: f64 = 10.0;

/// Process-noise model (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProcessNoise {
    /// DWNA: σ (m/s²) of the acceleration, constant within a period. CV only.
    DiscreteWhiteAcceleration { sigma: f64 },
    /// CWNA: power spectral density q (m²/s³) of white acceleration. CV only.
    ContinuousWhiteAcceleration { spectral_density: f64 },
    /// Wiener-sequence acceleration: σ (m/s²) of the acceleration increment
    /// over one period. CA only.
    WienerAcceleration { sigma: f64 },
}

impl ProcessNoise {
    fn order(&self) -> usize {
        match self {
            ProcessNoise::DiscreteWhiteAcceleration { .. }
            | ProcessNoise::ContinuousWhiteAcceleration { .. } => 2,
            ProcessNoise::WienerAcceleration { .. } => 3,
        }
    }

    fn level(&self) -> f64 {
        match *self {
            ProcessNoise::DiscreteWhiteAcceleration { sigma }
            | ProcessNoise::WienerAcceleration { sigma } => sigma,
            ProcessNoise::ContinuousWhiteAcceleration { spectral_density } => spectral_density,
        }
    }

    /// One axis's Q(T), `order` × `order` in the top-left of a 3 × 3.
    fn axis_q(&self, dt: f64) -> [[f64; 3]; 3] {
        let mut q = [[0.0; 3]; 3];
        match *self {
            ProcessNoise::DiscreteWhiteAcceleration { sigma } => {
                let g = [dt * dt / 2.0, dt];
                for i in 0..2 {
                    for j in 0..2 {
                        q[i][j] = sigma * sigma * g[i] * g[j];
                    }
                }
            }
            ProcessNoise::ContinuousWhiteAcceleration {
                spectral_density: s,
            } => {
                q[0][0] = s * dt * dt * dt / 3.0;
                q[0][1] = s * dt * dt / 2.0;
                q[1][0] = q[0][1];
                q[1][1] = s * dt;
            }
            ProcessNoise::WienerAcceleration { sigma } => {
                let g = [dt * dt / 2.0, dt, 1.0];
                for i in 0..3 {
                    for j in 0..3 {
                        q[i][j] = sigma * sigma * g[i] * g[j];
                    }
                }
            }
        }
        q
    }
}

/// Why a Kalman filter refused a call. Its state is unchanged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KalmanError {
    /// A measurement component is NaN or infinite.
    InvalidMeasurement,
    /// The interval is not finite and > 0.
    InvalidInterval,
    /// A covariance is not symmetric positive definite (or not finite).
    InvalidCovariance,
    /// The process-noise level is negative or not finite.
    InvalidProcessNoise,
    /// The process-noise model does not fit the state (DWNA/CWNA need the
    /// CV filter, Wiener acceleration the CA filter).
    ModelMismatch,
}

impl fmt::Display for KalmanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            KalmanError::InvalidMeasurement => "measurement is not finite",
            KalmanError::InvalidInterval => "interval must be finite and > 0",
            KalmanError::InvalidCovariance => "covariance is not symmetric positive definite",
            KalmanError::InvalidProcessNoise => "process-noise level must be finite and >= 0",
            KalmanError::ModelMismatch => "process-noise model does not fit the filter's state",
        };
        f.write_str(s)
    }
}

impl std::error::Error for KalmanError {}

/// Two-point initialisation stage (as [`abtrack::filter::Phase`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KalmanPhase {
    Empty,
    OnePoint,
    Tracking,
}

/// What an update did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KalmanOutcome {
    /// First measurement stored.
    FirstPoint,
    /// Second measurement: state from two-point differencing.
    SecondPoint,
    /// Filtered: the predicted position, innovation ν = z − Hx̂⁻ and its
    /// covariance S = HP⁻Hᵀ + R.
    Filtered {
        predicted: [f64; 2],
        innovation: [f64; 2],
        innovation_covariance: Cov2,
    },
}

/// A 2-D Kalman filter with `N` states: 4 (constant velocity) or 6
/// (constant acceleration). Use [`ConstantVelocityKf`] /
/// [`ConstantAccelerationKf`].
#[derive(Debug, Clone, PartialEq)]
pub struct Kalman<const N: usize> {
    noise: ProcessNoise,
    r: Cov2,
    initial_acceleration_sigma: f64,
    phase: KalmanPhase,
    x: [f64; N],
    p: [[f64; N]; N],
    /// While `OnePoint`: the first measurement, its covariance, and the time
    /// since it.
    first: Option<([f64; 2], Cov2, f64)>,
    last_gain: Option<[[f64; 2]; N]>,
}

/// 4-state `[x, ẋ, y, ẏ]` constant-velocity Kalman filter.
pub type ConstantVelocityKf = Kalman<4>;
/// 6-state `[x, ẋ, ẍ, y, ẏ, ÿ]` constant-acceleration Kalman filter.
pub type ConstantAccelerationKf = Kalman<6>;

fn check_cov(r: &Cov2) -> Result<(), KalmanError> {
    let ok = r.iter().flatten().all(|v| v.is_finite())
        && (r[0][1] - r[1][0]).abs() <= 1e-9 * (r[0][0].abs() + r[1][1].abs())
        && r[0][0] > 0.0
        && r[0][0] * r[1][1] - r[0][1] * r[1][0] > 0.0;
    if ok {
        Ok(())
    } else {
        Err(KalmanError::InvalidCovariance)
    }
}

fn check_dt(dt: f64) -> Result<(), KalmanError> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(KalmanError::InvalidInterval)
    }
}

/// An isotropic measurement covariance σ²·I.
pub fn isotropic(sigma: f64) -> Cov2 {
    [[sigma * sigma, 0.0], [0.0, sigma * sigma]]
}

/// Covariance of a polar measurement converted to x = R sin B, y = R cos B
/// (azimuth B clockwise from +y), to first order: J·diag(σ_R², σ_B²)·Jᵀ with
/// J = ∂(x, y)/∂(R, B) = [[sin B, R cos B], [cos B, −R sin B]], evaluated at
/// the measurement (the standard converted-measurement Kalman filter; at
/// σ_B = 0.087 rad the first-order bias R(1 − e^{−σ_B²/2}) ≈ 0.0038·R is left
/// uncorrected, as He et al. do).
pub fn polar_measurement_covariance(
    range: f64,
    azimuth: f64,
    sigma_range: f64,
    sigma_azimuth: f64,
) -> Cov2 {
    let (s, c) = azimuth.sin_cos();
    let (vr, vb) = (sigma_range * sigma_range, sigma_azimuth * sigma_azimuth);
    let r2 = range * range;
    let xx = s * s * vr + r2 * c * c * vb;
    let yy = c * c * vr + r2 * s * s * vb;
    let xy = s * c * vr - r2 * s * c * vb;
    [[xx, xy], [xy, yy]]
}

impl<const N: usize> Kalman<N> {
    const ORDER: usize = {
        assert!(N == 4 || N == 6, "N is 4 (CV) or 6 (CA)");
        N / 2
    };

    /// An empty filter with process-noise model `noise` and the default
    /// measurement covariance `r`.
    pub fn new(noise: ProcessNoise, r: Cov2) -> Result<Self, KalmanError> {
        if noise.order() != Self::ORDER {
            return Err(KalmanError::ModelMismatch);
        }
        let level = noise.level();
        if !(level.is_finite() && level >= 0.0) {
            return Err(KalmanError::InvalidProcessNoise);
        }
        check_cov(&r)?;
        Ok(Kalman {
            noise,
            r,
            initial_acceleration_sigma: DEFAULT_INITIAL_ACCELERATION_SIGMA,
            phase: KalmanPhase::Empty,
            x: [0.0; N],
            p: [[0.0; N]; N],
            first: None,
            last_gain: None,
        })
    }

    /// Sets σ_a0 (m/s²), the initial acceleration uncertainty of the CA
    /// filter (ignored by the CV filter).
    pub fn with_initial_acceleration_sigma(mut self, sigma: f64) -> Result<Self, KalmanError> {
        if !(sigma.is_finite() && sigma >= 0.0) {
            return Err(KalmanError::InvalidProcessNoise);
        }
        self.initial_acceleration_sigma = sigma;
        Ok(self)
    }

    pub fn phase(&self) -> KalmanPhase {
        self.phase
    }
    pub fn process_noise(&self) -> ProcessNoise {
        self.noise
    }
    /// The whole state vector (see the module doc for the order).
    pub fn state(&self) -> [f64; N] {
        self.x
    }
    /// The state covariance P.
    pub fn covariance(&self) -> [[f64; N]; N] {
        self.p
    }
    /// Estimated position (the first measurement while `OnePoint`).
    pub fn position(&self) -> [f64; 2] {
        match (self.phase, self.first) {
            (KalmanPhase::OnePoint, Some((z, _, _))) => z,
            _ => [self.x[0], self.x[Self::ORDER]],
        }
    }
    /// Estimated velocity (zero before the second measurement).
    pub fn velocity(&self) -> [f64; 2] {
        [self.x[1], self.x[Self::ORDER + 1]]
    }
    /// Estimated acceleration (always zero for the CV filter).
    pub fn acceleration(&self) -> [f64; 2] {
        if Self::ORDER == 3 {
            [self.x[2], self.x[5]]
        } else {
            [0.0, 0.0]
        }
    }
    /// The Kalman gain K (N × 2) of the last filtered update. Per axis the αβ
    /// equivalents are α = `K[pos][axis]`, β = T·`K[vel][axis]` and, for the
    /// CA filter, γ = 2T²·`K[acc][axis]` (Tenne & Singh's γ/(2T²)).
    pub fn last_gain(&self) -> Option<[[f64; 2]; N]> {
        self.last_gain
    }

    fn transition(dt: f64) -> [[f64; N]; N] {
        let o = Self::ORDER;
        let mut f = [[0.0; N]; N];
        for axis in 0..2 {
            let b = axis * o;
            for i in 0..o {
                f[b + i][b + i] = 1.0;
                if i + 1 < o {
                    f[b + i][b + i + 1] = dt;
                }
                if i + 2 < o {
                    f[b + i][b + i + 2] = dt * dt / 2.0;
                }
            }
        }
        f
    }

    fn process_q(&self, dt: f64) -> [[f64; N]; N] {
        let o = Self::ORDER;
        let qa = self.noise.axis_q(dt);
        let mut q = [[0.0; N]; N];
        for axis in 0..2 {
            let b = axis * o;
            for i in 0..o {
                for j in 0..o {
                    q[b + i][b + j] = qa[i][j];
                }
            }
        }
        q
    }

    /// State and covariance predicted `dt` ahead (x̂⁻ = F x̂, P⁻ = F P Fᵀ + Q),
    /// without changing the filter. Before tracking, the state is returned
    /// unchanged.
    pub fn predict(&self, dt: f64) -> Result<([f64; N], [[f64; N]; N]), KalmanError> {
        check_dt(dt)?;
        if self.phase != KalmanPhase::Tracking {
            return Ok((self.x, self.p));
        }
        let f = Self::transition(dt);
        let x = mat_vec(&f, &self.x);
        let mut p = mat_mul(&mat_mul(&f, &self.p), &transpose(&f));
        let q = self.process_q(dt);
        for i in 0..N {
            for j in 0..N {
                p[i][j] += q[i][j];
            }
        }
        Ok((x, p))
    }

    /// No measurement: advance by `dt` (prediction only). Before the second
    /// measurement the interval is added to the differencing time, as the αβ
    /// filter does.
    pub fn coast(&mut self, dt: f64) -> Result<(), KalmanError> {
        check_dt(dt)?;
        match self.phase {
            KalmanPhase::Empty => {}
            KalmanPhase::OnePoint => {
                if let Some((_, _, since)) = self.first.as_mut() {
                    *since += dt;
                }
            }
            KalmanPhase::Tracking => {
                let (x, p) = self.predict(dt)?;
                self.x = x;
                self.p = p;
            }
        }
        Ok(())
    }

    /// Incorporates position `z` measured `dt` after the previous call, with
    /// the filter's default measurement covariance.
    pub fn update(&mut self, z: [f64; 2], dt: f64) -> Result<KalmanOutcome, KalmanError> {
        let r = self.r;
        self.update_with_covariance(z, dt, r)
    }

    /// As [`Self::update`] with this measurement's own covariance `r` (e.g.
    /// from [`polar_measurement_covariance`]).
    pub fn update_with_covariance(
        &mut self,
        z: [f64; 2],
        dt: f64,
        r: Cov2,
    ) -> Result<KalmanOutcome, KalmanError> {
        if !(z[0].is_finite() && z[1].is_finite()) {
            return Err(KalmanError::InvalidMeasurement);
        }
        check_dt(dt)?;
        check_cov(&r)?;
        match (self.phase, self.first) {
            (KalmanPhase::Empty, _) | (KalmanPhase::OnePoint, None) => {
                self.first = Some((z, r, 0.0));
                self.phase = KalmanPhase::OnePoint;
                self.x = [0.0; N];
                self.p = [[0.0; N]; N];
                Ok(KalmanOutcome::FirstPoint)
            }
            (KalmanPhase::OnePoint, Some((z1, r1, since))) => {
                let t = since + dt;
                self.two_point(z1, r1, z, r, t);
                self.first = None;
                self.phase = KalmanPhase::Tracking;
                Ok(KalmanOutcome::SecondPoint)
            }
            (KalmanPhase::Tracking, _) => self.filter(z, dt, r),
        }
    }

    fn two_point(&mut self, z1: [f64; 2], r1: Cov2, z2: [f64; 2], r2: Cov2, t: f64) {
        let o = Self::ORDER;
        let mut x = [0.0; N];
        let mut p = [[0.0; N]; N];
        let sa2 = self.initial_acceleration_sigma.powi(2);
        for a in 0..2 {
            x[a * o] = z2[a];
            x[a * o + 1] = (z2[a] - z1[a]) / t;
            for b in 0..2 {
                let (pa, pb) = (a * o, b * o);
                p[pa][pb] = r2[a][b];
                p[pa][pb + 1] = r2[a][b] / t;
                p[pa + 1][pb] = r2[a][b] / t;
                p[pa + 1][pb + 1] = (r1[a][b] + r2[a][b]) / (t * t);
            }
            if o == 3 {
                let (v, acc) = (a * o + 1, a * o + 2);
                p[v][v] += sa2 * t * t / 4.0;
                p[v][acc] = sa2 * t / 2.0;
                p[acc][v] = sa2 * t / 2.0;
                p[acc][acc] = sa2;
            }
        }
        self.x = x;
        self.p = p;
    }

    fn filter(&mut self, z: [f64; 2], dt: f64, r: Cov2) -> Result<KalmanOutcome, KalmanError> {
        let o = Self::ORDER;
        let (xp, pp) = self.predict(dt)?;
        let hi = [0, o]; // rows of H: the two positions
        let predicted = [xp[hi[0]], xp[hi[1]]];
        let innovation = [z[0] - predicted[0], z[1] - predicted[1]];
        let mut s = [[0.0; 2]; 2];
        for a in 0..2 {
            for b in 0..2 {
                s[a][b] = pp[hi[a]][hi[b]] + r[a][b];
            }
        }
        let det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
        if !(det.is_finite() && det > 0.0) {
            return Err(KalmanError::InvalidCovariance);
        }
        let s_inv = [
            [s[1][1] / det, -s[0][1] / det],
            [-s[1][0] / det, s[0][0] / det],
        ];
        // K = P⁻Hᵀ S⁻¹ (N × 2).
        let mut k = [[0.0; 2]; N];
        for (i, row) in k.iter_mut().enumerate() {
            for (j, kij) in row.iter_mut().enumerate() {
                *kij = (0..2).map(|m| pp[i][hi[m]] * s_inv[m][j]).sum();
            }
        }
        let mut x = xp;
        for (i, xi) in x.iter_mut().enumerate() {
            *xi += k[i][0] * innovation[0] + k[i][1] * innovation[1];
        }
        // Joseph form P = (I − KH) P⁻ (I − KH)ᵀ + K R Kᵀ: stays symmetric
        // positive semi-definite under rounding.
        let mut ikh = [[0.0; N]; N];
        for i in 0..N {
            ikh[i][i] = 1.0;
            for m in 0..2 {
                ikh[i][hi[m]] -= k[i][m];
            }
        }
        let mut p = mat_mul(&mat_mul(&ikh, &pp), &transpose(&ikh));
        for i in 0..N {
            for j in 0..N {
                let mut krk = 0.0;
                for a in 0..2 {
                    for b in 0..2 {
                        krk += k[i][a] * r[a][b] * k[j][b];
                    }
                }
                p[i][j] += krk;
            }
        }
        if !(x.iter().all(|v| v.is_finite()) && p.iter().flatten().all(|v| v.is_finite())) {
            return Err(KalmanError::InvalidCovariance);
        }
        self.x = x;
        self.p = p;
        self.last_gain = Some(k);
        Ok(KalmanOutcome::Filtered {
            predicted,
            innovation,
            innovation_covariance: s,
        })
    }
}

fn mat_mul<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> [[f64; N]; N] {
    let mut c = [[0.0; N]; N];
    for i in 0..N {
        for k in 0..N {
            let aik = a[i][k];
            if aik == 0.0 {
                continue;
            }
            for j in 0..N {
                c[i][j] += aik * b[k][j];
            }
        }
    }
    c
}

fn transpose<const N: usize>(a: &[[f64; N]; N]) -> [[f64; N]; N] {
    let mut t = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            t[j][i] = a[i][j];
        }
    }
    t
}

fn mat_vec<const N: usize>(a: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
    let mut y = [0.0; N];
    for i in 0..N {
        y[i] = (0..N).map(|j| a[i][j] * x[j]).sum();
    }
    y
}

/// Steady-state αβ gains of the CV filter on a fixed period `dt` with
/// isotropic measurement noise σ_w: iterates the Riccati recursion until the
/// gain settles. Returns (α, β) with α = K_x, β = T·K_ẋ.
pub fn steady_state_alpha_beta(
    noise: ProcessNoise,
    dt: f64,
    sigma_w: f64,
) -> Result<(f64, f64), KalmanError> {
    let mut kf = ConstantVelocityKf::new(noise, isotropic(sigma_w))?;
    kf.update([0.0, 0.0], dt)?;
    kf.update([0.0, 0.0], dt)?;
    let mut prev = (f64::NAN, f64::NAN);
    for _ in 0..100_000 {
        kf.update([0.0, 0.0], dt)?;
        let k = kf.last_gain().ok_or(KalmanError::InvalidCovariance)?;
        let ab = (k[0][0], dt * k[1][0]);
        if (ab.0 - prev.0).abs() < 1e-15 && (ab.1 - prev.1).abs() < 1e-15 {
            return Ok(ab);
        }
        prev = ab;
    }
    Ok(prev)
}
