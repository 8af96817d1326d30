//! The independent `f64` reference: the αβ and αβγ filters written straight
//! from the papers' equations, in plain `f64`, sharing no code with the
//! library's generic filter (no `Scalar`, no `KinematicFilter`).
//!
//! * αβ: Al-Wagih & Abdulla, eqs. (3)–(8), two-point initialisation (9)–(10).
//! * αβγ: Tenne & Singh, eqs. (1)–(5), with their γ/(2T²).
//!
//! What the papers leave open, taken from the library's documented contract so
//! that the two can be compared: the interval `T` is the time since the
//! previous call and may change on every call; a coast (no measurement)
//! replaces the smoothed state by the prediction; before the second
//! measurement a coast only adds to the time since the first one, which is the
//! `T` of eq. (9); the αβγ filter's acceleration starts at zero.

/// Smoothing gains in the papers' notation; `gamma` is unused by αβ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefGains {
    pub alpha: f64,
    pub beta: f64,
    pub gamma: f64,
}

/// What one reference update produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RefStep {
    /// First measurement: x_s = x_m(1).
    First,
    /// Second: v_s(2) from eq. (9), x_s = x_m(2).
    Second,
    /// Filtered: the prediction x_p and the innovation e = x_m − x_p (eq. 4).
    Filtered { predicted: f64, innovation: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Stage {
    NoMeasurement,
    /// One measurement; the time since it (coasts included).
    OneMeasurement {
        since: f64,
    },
    Tracking,
}

/// αβ tracker, Al-Wagih & Abdulla eqs. (3)–(10).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefAlphaBeta {
    /// x_s, smoothed position.
    pub x_s: f64,
    /// v_s, smoothed velocity.
    pub v_s: f64,
    stage: Stage,
}

impl Default for RefAlphaBeta {
    fn default() -> Self {
        Self::new()
    }
}

impl RefAlphaBeta {
    pub fn new() -> Self {
        RefAlphaBeta {
            x_s: 0.0,
            v_s: 0.0,
            stage: Stage::NoMeasurement,
        }
    }

    /// Measurement x_m taken T seconds after the previous call.
    pub fn update(&mut self, x_m: f64, t: f64, g: &RefGains) -> RefStep {
        match self.stage {
            Stage::NoMeasurement => {
                // "The measured position is considered to be the initial
                // predicted target position till the second time step" (§3).
                self.x_s = x_m;
                self.v_s = 0.0;
                self.stage = Stage::OneMeasurement { since: 0.0 };
                RefStep::First
            }
            Stage::OneMeasurement { since } => {
                let t_total = since + t;
                // eq. (9): v_s(2) = (x_m(2) − x_m(1)) / T
                self.v_s = (x_m - self.x_s) / t_total;
                self.x_s = x_m;
                self.stage = Stage::Tracking;
                RefStep::Second
            }
            Stage::Tracking => {
                // eq. (3) (eq. (10) on the third step, since x_s(2) = x_m(2)):
                let x_p = self.x_s + t * self.v_s;
                // eq. (4)
                let e = x_m - x_p;
                // eq. (6)
                self.x_s = x_p + g.alpha * e;
                // eq. (8): v_s(t) = v_s(t−1) + β/T·e(t)
                self.v_s += (g.beta / t) * e;
                RefStep::Filtered {
                    predicted: x_p,
                    innovation: e,
                }
            }
        }
    }

    /// No measurement for T seconds: the state becomes the prediction, eq. (3).
    pub fn coast(&mut self, t: f64) {
        match self.stage {
            Stage::NoMeasurement => {}
            Stage::OneMeasurement { since } => {
                self.stage = Stage::OneMeasurement { since: since + t };
            }
            Stage::Tracking => {
                self.x_s += t * self.v_s;
            }
        }
    }
}

/// αβγ filter, Tenne & Singh eqs. (1)–(5), initialised by two points as the αβ
/// tracker (Al-Wagih eqs. (9)–(10)) with zero initial acceleration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefAlphaBetaGamma {
    pub x_s: f64,
    pub v_s: f64,
    pub a_s: f64,
    stage: Stage,
}

impl Default for RefAlphaBetaGamma {
    fn default() -> Self {
        Self::new()
    }
}

impl RefAlphaBetaGamma {
    pub fn new() -> Self {
        RefAlphaBetaGamma {
            x_s: 0.0,
            v_s: 0.0,
            a_s: 0.0,
            stage: Stage::NoMeasurement,
        }
    }

    /// Observation x_o taken T seconds after the previous call.
    pub fn update(&mut self, x_o: f64, t: f64, g: &RefGains) -> RefStep {
        match self.stage {
            Stage::NoMeasurement => {
                self.x_s = x_o;
                self.v_s = 0.0;
                self.a_s = 0.0;
                self.stage = Stage::OneMeasurement { since: 0.0 };
                RefStep::First
            }
            Stage::OneMeasurement { since } => {
                self.v_s = (x_o - self.x_s) / (since + t);
                self.x_s = x_o;
                self.a_s = 0.0;
                self.stage = Stage::Tracking;
                RefStep::Second
            }
            Stage::Tracking => {
                // eq. (1): x_p(k+1) = x_s(k) + T v_s(k) + ½T² a_s(k)
                let x_p = self.x_s + t * self.v_s + 0.5 * t * t * self.a_s;
                // eq. (2): v_p(k+1) = v_s(k) + T a_s(k)
                let v_p = self.v_s + t * self.a_s;
                let innovation = x_o - x_p;
                // eq. (3)
                self.x_s = x_p + g.alpha * innovation;
                // eq. (4)
                self.v_s = v_p + (g.beta / t) * innovation;
                // eq. (5): a_s(k) = a_s(k−1) + γ/(2T²)·(x_o − x_p)
                self.a_s += g.gamma / (2.0 * t * t) * innovation;
                RefStep::Filtered {
                    predicted: x_p,
                    innovation,
                }
            }
        }
    }

    /// No observation for T seconds: the state becomes the prediction,
    /// eqs. (1)–(2); the acceleration is held.
    pub fn coast(&mut self, t: f64) {
        match self.stage {
            Stage::NoMeasurement => {}
            Stage::OneMeasurement { since } => {
                self.stage = Stage::OneMeasurement { since: since + t };
            }
            Stage::Tracking => {
                let x_p = self.x_s + t * self.v_s + 0.5 * t * t * self.a_s;
                let v_p = self.v_s + t * self.a_s;
                self.x_s = x_p;
                self.v_s = v_p;
            }
        }
    }
}

/// Either reference filter, so that runs can be written once for both orders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RefFilter {
    AlphaBeta(RefAlphaBeta),
    AlphaBetaGamma(RefAlphaBetaGamma),
}

impl RefFilter {
    /// An empty αβ (`order` 2) or αβγ (`order` 3) reference.
    pub fn new(order: usize) -> Self {
        if order == 3 {
            RefFilter::AlphaBetaGamma(RefAlphaBetaGamma::new())
        } else {
            RefFilter::AlphaBeta(RefAlphaBeta::new())
        }
    }

    pub fn update(&mut self, z: f64, t: f64, g: &RefGains) -> RefStep {
        match self {
            RefFilter::AlphaBeta(f) => f.update(z, t, g),
            RefFilter::AlphaBetaGamma(f) => f.update(z, t, g),
        }
    }

    pub fn coast(&mut self, t: f64) {
        match self {
            RefFilter::AlphaBeta(f) => f.coast(t),
            RefFilter::AlphaBetaGamma(f) => f.coast(t),
        }
    }

    /// (x_s, v_s, a_s); a_s = 0 for αβ.
    pub fn state(&self) -> (f64, f64, f64) {
        match self {
            RefFilter::AlphaBeta(f) => (f.x_s, f.v_s, 0.0),
            RefFilter::AlphaBetaGamma(f) => (f.x_s, f.v_s, f.a_s),
        }
    }
}

/// Which innovations Liu, Wang & Yang's residual accumulation (§2.1.4,
/// eqs. 6–7) averages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LiuWindow {
    /// V(k), V(k − 1), …, V(k − n + 1): the current innovation and the n − 1
    /// before it (the library's `liu-residual` reading).
    IncludingCurrent,
    /// V(k − 1), …, V(k − n): "the n measurement–prediction differences
    /// before the current time" (the text of §2.1.4), the current one left
    /// out. At the first filtered update, where no earlier innovation
    /// exists, the current one is used (both readings agree there).
    ExcludingCurrent,
}

/// Liu, Wang & Yang §2.1.4 in plain f64, per axis: σ_p² the mean of n
/// squared innovations (eqs. 6–7, read as innovations like the library),
/// α = σ_p²/(σ_p² + σ_m²) (eqs. 8–9) floored at `alpha_min` (the library's
/// default 0.01), β = α²/(2 − α) (eqs. 10–11), driving [`RefAlphaBeta`].
#[derive(Debug, Clone, PartialEq)]
pub struct RefLiuResidual {
    pub window: LiuWindow,
    pub n: usize,
    pub sigma_m2: f64,
    pub alpha_min: f64,
    pub axes: Vec<RefAlphaBeta>,
    /// Past innovations per axis, newest last (at most n kept).
    history: Vec<Vec<f64>>,
}

/// What one [`RefLiuResidual`] update did on one axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefLiuStep {
    pub predicted: f64,
    pub innovation: f64,
    pub alpha: f64,
    pub beta: f64,
}

impl RefLiuResidual {
    pub fn new(window: LiuWindow, n: usize, sigma_m2: f64, alpha_min: f64, axes: usize) -> Self {
        RefLiuResidual {
            window,
            n,
            sigma_m2,
            alpha_min,
            axes: vec![RefAlphaBeta::new(); axes],
            history: vec![Vec::new(); axes],
        }
    }

    /// One measurement per axis, `t` after the previous one. `None` per axis
    /// while initialising (two-point start).
    pub fn update(&mut self, z: &[f64], t: f64) -> Vec<Option<RefLiuStep>> {
        let (n, sigma_m2, alpha_min, window) = (self.n, self.sigma_m2, self.alpha_min, self.window);
        self.axes
            .iter_mut()
            .zip(self.history.iter_mut())
            .zip(z)
            .map(|((axis, past), &z)| {
                if axis.stage != Stage::Tracking {
                    axis.update(
                        z,
                        t,
                        &RefGains {
                            alpha: 1.0,
                            beta: 1.0,
                            gamma: 0.0,
                        },
                    );
                    return None;
                }
                // Eq. (3): the prediction, and the innovation V(k).
                let predicted = axis.x_s + t * axis.v_s;
                let v = z - predicted;
                let terms: Vec<f64> = match window {
                    LiuWindow::IncludingCurrent => past
                        .iter()
                        .rev()
                        .take(n - 1)
                        .copied()
                        .chain(std::iter::once(v))
                        .collect(),
                    LiuWindow::ExcludingCurrent if past.is_empty() => vec![v],
                    LiuWindow::ExcludingCurrent => past.iter().rev().take(n).copied().collect(),
                };
                let sigma_p2 = terms.iter().map(|e| e * e).sum::<f64>() / terms.len() as f64;
                let alpha = (sigma_p2 / (sigma_p2 + sigma_m2)).clamp(alpha_min, 1.0);
                let beta = alpha * alpha / (2.0 - alpha);
                axis.update(
                    z,
                    t,
                    &RefGains {
                        alpha,
                        beta,
                        gamma: 0.0,
                    },
                );
                past.push(v);
                if past.len() > n {
                    past.remove(0);
                }
                Some(RefLiuStep {
                    predicted,
                    innovation: v,
                    alpha,
                    beta,
                })
            })
            .collect()
    }
}

/// One axis of `auto` written straight from the Kalman filter's equations
/// in metres (Bar-Shalom, Li & Kirubarajan 2001 §5.2.3, CWNA Q of §6.2.2,
/// two-point start of §5.5.3), not normalised: P⁻ = FPFᵀ + Q,
/// S = P⁻_xx + σ², K = P⁻Hᵀ/S, P = (I − KH)P⁻, x = x_p + K·ν; the
/// manoeuvre level q by the documented covariance matching: m += w(ν²/S −
/// m) with w = min(τ/8, ½), q ← clamp(q·(1 + (m − 1)/4), q_min, q_max).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefKalmanAxis {
    pub sigma: f64,
    pub q_bounds: (f64, f64, f64),
    pub x: f64,
    pub v: f64,
    /// [P_xx, P_xv, P_vv], m², m²/s, m²/s².
    pub p: [f64; 3],
    pub q: f64,
    pub nis_mean: f64,
    stage: Option<f64>,
    started: bool,
    coasted: f64,
}

impl RefKalmanAxis {
    /// `q_bounds` = (q_min, q_start, q_max), m²/s³.
    pub fn new(sigma: f64, q_bounds: (f64, f64, f64)) -> Self {
        RefKalmanAxis {
            sigma,
            q_bounds,
            x: 0.0,
            v: 0.0,
            p: [0.0; 3],
            q: q_bounds.1,
            nis_mean: 1.0,
            stage: None,
            started: false,
            coasted: 0.0,
        }
    }

    /// No measurement for `dt`: the state is predicted, the covariance
    /// waits (CWNA over T₁ then T₂ is CWNA over T₁ + T₂).
    pub fn coast(&mut self, dt: f64) {
        if self.started {
            self.x += self.v * dt;
        }
        self.coasted += dt;
    }

    /// Measurement `z`, `dt` after the previous call; returns (α, β).
    pub fn update(&mut self, z: f64, dt: f64) -> Option<(f64, f64)> {
        let r = self.sigma * self.sigma;
        let tau = self.coasted + dt;
        self.coasted = 0.0;
        match (self.stage, self.started) {
            (None, _) => {
                self.stage = Some(z);
                self.x = z;
                return None;
            }
            (Some(z1), false) => {
                self.v = (z - z1) / tau;
                self.x = z;
                self.p = [r, r / tau, 2.0 * r / (tau * tau)];
                self.q = self.q_bounds.1;
                self.nis_mean = 1.0;
                self.started = true;
                return None;
            }
            _ => {}
        }
        let [pxx, pxv, pvv] = self.p;
        let q = self.q;
        let mxx = pxx + 2.0 * tau * pxv + tau * tau * pvv + q * tau.powi(3) / 3.0;
        let mxv = pxv + tau * pvv + q * tau * tau / 2.0;
        let mvv = pvv + q * tau;
        let xp = self.x + self.v * dt;
        let s = mxx + r;
        let (kx, kv) = (mxx / s, mxv / s);
        let nu = z - xp;
        self.x = xp + kx * nu;
        self.v += kv * nu;
        self.p = [(1.0 - kx) * mxx, (1.0 - kx) * mxv, mvv - kv * mxv];
        let w = (tau / 8.0).min(0.5);
        self.nis_mean += w * (nu * nu / s - self.nis_mean);
        self.q = (q * (1.0 + (self.nis_mean - 1.0) / 4.0)).clamp(self.q_bounds.0, self.q_bounds.2);
        Some((kx, kv * dt))
    }
}
