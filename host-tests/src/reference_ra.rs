//! Independent f64 reference of the range–azimuth projection filter of He,
//! Peng, Ling & Quan, written straight from the paper's equations with 2×2
//! matrices in physical units (m², m²/s, m²/s²) — not the library's generic
//! code and not its normalised covariances.
//!
//! It implements the same readings of the paper's slips as
//! `abtrack::filter::range_azimuth` (see that module's docs):
//! 1. eq. (11) with the predicted position and the measured R, B;
//! 2. eqs. (12)–(13) starting from the prediction X_k|k−1;
//! 3. eq. (9) with the range variance σ_R², eq. (10) with VAR = R²·σ_B²;
//! 4. one covariance along and one across the line of sight, each predicted
//!    by eq. (8) and updated by P = (I − K D)·PCOV (in Joseph's form);
//!
//! with two-point initialisation. It does not apply the library's 1 m floor
//! on √VAR (tests keep R above 11.5 m, where the two agree).
//!
//! [`Eq9Reading::AsPrinted`] is the other reading of slip 3: eq. (9) exactly
//! as printed, dividing by PCOV₁₁ + VAR like eq. (10). Then the range
//! direction has the cross-range measurement variance VAR everywhere (two-
//! point start, gains, covariance update), its covariance equals the
//! cross-range one, α = W1 and β/T = W2 at every scan, and eqs. (12)–(13)
//! reduce to x += α(z_x − x_p), y += α(z_y − y_p): a per-axis filter on the
//! converted measurements with gains from the cross-range variance.

type Mat = [[f64; 2]; 2];

fn mul(a: &Mat, b: &Mat) -> Mat {
    let mut c = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    c
}

fn transpose(a: &Mat) -> Mat {
    [[a[0][0], a[1][0]], [a[0][1], a[1][1]]]
}

/// Eq. (8): PCOV = Φ P Φᵀ + Γ Q Γᵀ, Φ = [1 T; 0 1], Γ = [T²/2; T].
pub fn predict_covariance(p: &Mat, t: f64, q: f64) -> Mat {
    let phi = [[1.0, t], [0.0, 1.0]];
    let gamma = [t * t / 2.0, t];
    let fp = mul(&mul(&phi, p), &transpose(&phi));
    let mut out = fp;
    for i in 0..2 {
        for j in 0..2 {
            out[i][j] += gamma[i] * q * gamma[j];
        }
    }
    out
}

/// P = (I − K D)·PCOV, K = (k₁, k₂)ᵀ, D = (1, 0), evaluated in Joseph's
/// form (I − K D)·PCOV·(I − K D)ᵀ + K·σ²·Kᵀ, which is the same matrix for the
/// Kalman gain K = PCOV·Dᵀ/(D·PCOV·Dᵀ + σ²) but does not lose digits to the
/// cancellation in PCOV₂₂ − k₂·PCOV₁₂ (the short form drifts by ~10⁻¹³
/// relative over 100 scans near closest approach, Joseph's by ~10⁻¹⁶).
pub fn update_covariance(pcov: &Mat, k: [f64; 2], measurement_variance: f64) -> Mat {
    let i_kd = [[1.0 - k[0], 0.0], [-k[1], 1.0]];
    let mut p = mul(&mul(&i_kd, pcov), &transpose(&i_kd));
    for i in 0..2 {
        for j in 0..2 {
            p[i][j] += k[i] * measurement_variance * k[j];
        }
    }
    p
}

/// Gains, residuals and prediction of one filtered update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceStep {
    pub predicted: [f64; 2],
    pub alpha: f64,
    pub beta: f64,
    pub w1: f64,
    pub w2: f64,
    pub resid_r: f64,
    pub resid_cr: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Stage {
    Empty,
    One {
        x: f64,
        y: f64,
        var: f64,
        elapsed: f64,
    },
    Tracking,
}

/// Which measurement variance He et al.'s eq. (9) divides by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Eq9Reading {
    /// PCOV₁₁ + σ_R² (the library's reading 3).
    RangeVariance,
    /// PCOV₁₁ + VAR, exactly as printed.
    AsPrinted,
}

/// The reference filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceRangeAzimuth {
    /// Which eq. (9) (see [`Eq9Reading`]).
    pub eq9: Eq9Reading,
    /// σ_R², m².
    pub range_variance: f64,
    /// σ_B², rad².
    pub bearing_variance: f64,
    /// Q, m²/s⁴.
    pub q: f64,
    stage: Stage,
    /// (X, Ẋ) and (Y, Ẏ).
    pub x: [f64; 2],
    pub y: [f64; 2],
    /// Covariance along range (m² units).
    pub p_range: Mat,
    /// Covariance across range (m² units).
    pub p_cross: Mat,
}

impl ReferenceRangeAzimuth {
    pub fn new(range_variance: f64, bearing_variance: f64, q: f64) -> Self {
        ReferenceRangeAzimuth {
            eq9: Eq9Reading::RangeVariance,
            range_variance,
            bearing_variance,
            q,
            stage: Stage::Empty,
            x: [0.0; 2],
            y: [0.0; 2],
            p_range: [[0.0; 2]; 2],
            p_cross: [[0.0; 2]; 2],
        }
    }

    /// The same filter with eq. (9) exactly as printed.
    pub fn as_printed(range_variance: f64, bearing_variance: f64, q: f64) -> Self {
        ReferenceRangeAzimuth {
            eq9: Eq9Reading::AsPrinted,
            ..Self::new(range_variance, bearing_variance, q)
        }
    }

    /// The measurement variance along the line of sight that eq. (9) uses
    /// when the cross-range one is `var`.
    fn range_measurement_variance(&self, var: f64) -> f64 {
        match self.eq9 {
            Eq9Reading::RangeVariance => self.range_variance,
            Eq9Reading::AsPrinted => var,
        }
    }

    pub fn is_tracking(&self) -> bool {
        self.stage == Stage::Tracking
    }

    /// One measurement (R, B) taken `t` after the previous call. Returns the
    /// filtered step from the third measurement on.
    pub fn update(&mut self, r: f64, b: f64, t: f64) -> Option<ReferenceStep> {
        // x = R sin B, y = R cos B (He et al. §3).
        let (zx, zy) = (r * b.sin(), r * b.cos());
        let var = r * r * self.bearing_variance;
        match self.stage {
            Stage::Empty => {
                self.x = [zx, 0.0];
                self.y = [zy, 0.0];
                self.stage = Stage::One {
                    x: zx,
                    y: zy,
                    var,
                    elapsed: 0.0,
                };
                None
            }
            Stage::One {
                x,
                y,
                var: var1,
                elapsed,
            } => {
                let tt = elapsed + t;
                self.x = [zx, (zx - x) / tt];
                self.y = [zy, (zy - y) / tt];
                let s2 = self.range_variance;
                self.p_cross = [[var, var / tt], [var / tt, (var1 + var) / (tt * tt)]];
                self.p_range = match self.eq9 {
                    Eq9Reading::RangeVariance => [[s2, s2 / tt], [s2 / tt, 2.0 * s2 / (tt * tt)]],
                    Eq9Reading::AsPrinted => self.p_cross,
                };
                self.stage = Stage::Tracking;
                None
            }
            Stage::Tracking => {
                // X_k|k−1 = A X_{k−1} (eq. 4).
                let xp = [self.x[0] + t * self.x[1], self.x[1]];
                let yp = [self.y[0] + t * self.y[1], self.y[1]];
                let pr = predict_covariance(&self.p_range, t, self.q);
                let pc = predict_covariance(&self.p_cross, t, self.q);
                // Eq. (9) with σ_R² (or VAR as printed), eq. (10) with VAR.
                let range_var = self.range_measurement_variance(var);
                let alpha = pr[0][0] / (pr[0][0] + range_var);
                let beta = t * pr[0][1] / (pr[0][0] + range_var);
                let w1 = pc[0][0] / (pc[0][0] + var);
                let w2 = pc[0][1] / (pc[0][0] + var);
                // Eq. (11).
                let (sb, cb) = (b.sin(), b.cos());
                let resid_r = r - (xp[0] * sb + yp[0] * cb);
                let resid_cr = xp[0] * cb - yp[0] * sb;
                // Eqs. (12)–(13).
                self.x = [
                    xp[0] + alpha * resid_r * sb - w1 * resid_cr * cb,
                    xp[1] + beta / t * resid_r * sb - w2 * resid_cr * cb,
                ];
                self.y = [
                    yp[0] + alpha * resid_r * cb + w1 * resid_cr * sb,
                    yp[1] + beta / t * resid_r * cb + w2 * resid_cr * sb,
                ];
                self.p_range = update_covariance(&pr, [alpha, beta / t], range_var);
                self.p_cross = update_covariance(&pc, [w1, w2], var);
                Some(ReferenceStep {
                    predicted: [xp[0], yp[0]],
                    alpha,
                    beta,
                    w1,
                    w2,
                    resid_r,
                    resid_cr,
                })
            }
        }
    }

    /// No measurement: predict state and covariances.
    pub fn coast(&mut self, t: f64) {
        match &mut self.stage {
            Stage::Empty => {}
            Stage::One { elapsed, .. } => *elapsed += t,
            Stage::Tracking => {
                self.x[0] += t * self.x[1];
                self.y[0] += t * self.y[1];
                self.p_range = predict_covariance(&self.p_range, t, self.q);
                self.p_cross = predict_covariance(&self.p_cross, t, self.q);
            }
        }
    }

    /// √(X² + Y²), m.
    pub fn range(&self) -> f64 {
        self.x[0].hypot(self.y[0])
    }

    /// atan2(X, Y) in [0, 2π), rad.
    pub fn azimuth(&self) -> f64 {
        self.x[0].atan2(self.y[0]).rem_euclid(std::f64::consts::TAU)
    }
}
