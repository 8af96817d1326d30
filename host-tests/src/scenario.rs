//! Truth generators and seeded measurement generation: one scenario per
//! seed paper, a TCAS-realistic encounter, and the multi-target scenarios.
//!
//! A scenario is a fixed truth (the same for every seed) plus random
//! measurements (noise, detections, clutter, row order) drawn from a
//! generator seeded by the caller ([`generate`]). Monte Carlo run `r` of a
//! base seed uses [`monte_carlo_seed`]`(base, r)`. Layouts that are themselves
//! random (`tcas-30`, `dense`) are drawn once from a fixed layout seed, so the
//! picture is the same in every run and only the sensor changes.
//!
//! # Units and frames
//! Metres, seconds, radians; altitudes in feet (as transponders report them).
//! Cartesian scenarios use a fixed ground frame. Polar (TCAS) scenarios use a
//! non-rotating frame centred on the own aircraft with +y along the own
//! aircraft's (constant) track: the truth `x, y, vx, vy` is the intruder's
//! position and velocity *relative to the own aircraft*, which is what a
//! range–azimuth tracker estimates. Azimuth is measured clockwise from +y, as
//! in He, Peng, Ling & Quan §3: x = R sin B, y = R cos B, B ∈ [0, 2π).
//!
//! # CSV formats (written by [`ScenarioRun::measurements_csv`] /
//! [`ScenarioRun::truth_csv`] and the `simulate` binary)
//! * measurements (the `replay` input format): `t,x,y` for Cartesian
//!   scenarios; `t,range,azimuth` for polar ones, plus `,alt` (Mode C reported
//!   pressure altitude, ft) when the scenario has altitudes; an empty `alt`
//!   field is a non-altitude-reporting intruder. In multi-target scenarios
//!   several rows share a `t` (one scan), unlabelled and shuffled; a scan with
//!   no detection and no clutter has no row.
//! * truth: `t,x,y,vx,vy`; multi-target scenarios insert a `target` column
//!   after `t` (`t,target,x,y,vx,vy`, ids from 1); polar scenarios append
//!   `range,azimuth,range_rate,tau` (tau = −r/ṙ in s, empty when the range is
//!   not closing); scenarios with altitude append `alt,own_alt` (true
//!   intruder altitude and own altitude, ft). A target is listed only while it
//!   is inside the surveillance region (multi-target scenarios).
//!
//! Numbers are written in Rust's shortest round-trip form, so a file read back
//! gives the same `f64` values.

use crate::metrics::TruthPoint;
use crate::noise::{
    bernoulli, derive_seed, poisson, rng_from_seed, shuffle, uniform, NoiseError, NoiseModel,
    NoiseProcess, SimRng,
};
use std::f64::consts::{FRAC_PI_4, PI, TAU};
use std::fmt::Write as _;

/// One foot in metres (exact, international foot).
pub const FOOT: f64 = 0.3048;
/// One nautical mile in metres (exact).
pub const NAUTICAL_MILE: f64 = 1852.0;
/// One knot in m/s.
pub const KNOT: f64 = NAUTICAL_MILE / 3600.0;
/// One km/h in m/s.
pub const KM_PER_HOUR: f64 = 1000.0 / 3600.0;

/// Capacity of the track table the `dense` scenario is sized to fill.
pub const DENSE_TABLE_CAPACITY: usize = 64;

/// Seed of the fixed random layouts (`tcas-30`, `dense`): part of the
/// scenario definition, not of a run.
const LAYOUT_SEED: u64 = 0x0AB7_4ACC_2024_0005;

/// How measurements are expressed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeasurementFrame {
    /// Position `x, y` in metres.
    Cartesian,
    /// Range (m) and azimuth (rad, clockwise from +y) from the own aircraft.
    Polar,
}

/// The sensor's measurement noise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SensorNoise {
    /// Independent noise channels on x and y (m).
    Cartesian { x: NoiseModel, y: NoiseModel },
    /// Independent noise on range (m) and azimuth (rad).
    Polar {
        range: NoiseModel,
        azimuth: NoiseModel,
    },
}

impl SensorNoise {
    /// Li, Zhao, Liang & Zhang eq. (11) needs the radius error Δρ and bearing
    /// error Δθ of the sensor at the predicted radius ρ. For a polar sensor
    /// they are its range and azimuth σ. For a Cartesian sensor with equal,
    /// independent per-axis σ the error is isotropic, so along and across the
    /// line of sight it is σ in each direction: Δρ = σ and ρΔθ = σ, i.e.
    /// Δθ = σ/ρ, and √(Δρ² + ρ²Δθ²) = σ√2 whatever ρ is. Unequal Cartesian σ
    /// use their root mean square for both. Returns `(Δρ, Δθ)`; `None` for
    /// ρ ≤ 0.
    pub fn range_bearing_errors(&self, rho: f64) -> Option<(f64, f64)> {
        if !(rho > 0.0 && rho.is_finite()) {
            return None;
        }
        match *self {
            SensorNoise::Polar { range, azimuth } => Some((range.sigma(), azimuth.sigma())),
            SensorNoise::Cartesian { x, y } => {
                let s = ((x.sigma().powi(2) + y.sigma().powi(2)) / 2.0).sqrt();
                Some((s, s / rho))
            }
        }
    }
}

/// Where targets can be seen and clutter falls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Region {
    /// Axis-aligned rectangle (m).
    Rectangle {
        x_min: f64,
        x_max: f64,
        y_min: f64,
        y_max: f64,
    },
    /// Disc of the given radius (m) around the own aircraft.
    Disc { radius: f64 },
}

impl Region {
    pub fn area_m2(&self) -> f64 {
        match *self {
            Region::Rectangle {
                x_min,
                x_max,
                y_min,
                y_max,
            } => (x_max - x_min) * (y_max - y_min),
            Region::Disc { radius } => PI * radius * radius,
        }
    }

    pub fn contains(&self, x: f64, y: f64) -> bool {
        match *self {
            Region::Rectangle {
                x_min,
                x_max,
                y_min,
                y_max,
            } => (x_min..=x_max).contains(&x) && (y_min..=y_max).contains(&y),
            Region::Disc { radius } => x.hypot(y) <= radius,
        }
    }
}

/// Poisson clutter, uniform over a region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClutterSpec {
    pub region: Region,
    /// Mean number of false measurements per scan over the whole region.
    pub mean_per_scan: f64,
    /// Altitude band (ft) of false replies' reported altitudes, uniform and
    /// Mode C quantised; `None` when measurements carry no altitude.
    pub altitude_band_ft: Option<(f64, f64)>,
}

impl ClutterSpec {
    /// Spatial density λ (false measurements per m² per scan).
    pub fn density_per_m2(&self) -> f64 {
        self.mean_per_scan / self.region.area_m2()
    }
}

/// Process-noise levels we recommend for the Kalman-filter yardstick on a
/// scenario (see [`crate::kalman`] for the models).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KalmanTuning {
    /// σ_a (m/s²) of the discrete white-noise-acceleration model for the
    /// 4-state constant-velocity filter.
    pub cv_sigma_acceleration: f64,
    /// σ (m/s² per period) of the acceleration increment of the
    /// Wiener-sequence model for the 6-state constant-acceleration filter.
    pub ca_sigma_acceleration_increment: f64,
    /// Why these values.
    pub rationale: &'static str,
}

/// What a scenario is: everything except the random draws.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioInfo {
    pub name: &'static str,
    /// One line, for `simulate --list`.
    pub description: &'static str,
    /// The paper (and section) it reproduces, or "beyond the papers".
    pub source: &'static str,
    /// Sampling period T (s). Scan k (0-based) is at t = k·T.
    pub period_s: f64,
    pub scans: usize,
    /// Number of true targets.
    pub targets: usize,
    /// Multi-target format (target column in truth, shuffled rows).
    pub multi_target: bool,
    pub frame: MeasurementFrame,
    /// Measurements carry a Mode C altitude.
    pub has_altitude: bool,
    pub noise: SensorNoise,
    /// Probability that a present target yields a measurement in a scan.
    pub detection_probability: f64,
    pub clutter: Option<ClutterSpec>,
    /// Targets outside it are not present (no truth row, no detection).
    pub surveillance: Option<Region>,
    /// Own aircraft's altitude (ft), constant, for the polar scenarios.
    pub own_altitude_ft: Option<f64>,
    /// Monte Carlo runs for the experiments: the paper's number where it
    /// gives one (Li et al. 100, He et al. 200), otherwise 100. Al-Wagih &
    /// Abdulla's five data sets per noise type are runs 0–4 of these
    /// (`monte_carlo_seed(base, 0..5)`); Liu et al. show single runs.
    pub monte_carlo_runs: usize,
    pub kalman: KalmanTuning,
}

impl ScenarioInfo {
    /// Header of the measurements CSV.
    pub fn measurements_header(&self) -> &'static str {
        match (self.frame, self.has_altitude) {
            (MeasurementFrame::Cartesian, _) => "t,x,y",
            (MeasurementFrame::Polar, false) => "t,range,azimuth",
            (MeasurementFrame::Polar, true) => "t,range,azimuth,alt",
        }
    }

    /// Header of the truth CSV.
    pub fn truth_header(&self) -> String {
        let mut h = String::from("t");
        if self.multi_target {
            h.push_str(",target");
        }
        h.push_str(",x,y,vx,vy");
        if self.frame == MeasurementFrame::Polar {
            h.push_str(",range,azimuth,range_rate,tau");
        }
        if self.has_altitude {
            h.push_str(",alt,own_alt");
        }
        h
    }
}

/// The true state of one target at one scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruthState {
    pub t: f64,
    /// Target id, from 1.
    pub target: u32,
    pub x: f64,
    pub y: f64,
    pub vx: f64,
    pub vy: f64,
    /// True pressure altitude (ft), when the scenario has altitudes.
    pub alt_ft: Option<f64>,
}

impl TruthState {
    /// Range from the frame origin (the own aircraft in polar scenarios).
    pub fn range(&self) -> f64 {
        self.x.hypot(self.y)
    }
    /// Azimuth clockwise from +y, in [0, 2π).
    pub fn azimuth(&self) -> f64 {
        wrap_two_pi(self.x.atan2(self.y))
    }
    /// ṙ = (x·vx + y·vy)/r (m/s); `None` at r = 0.
    pub fn range_rate(&self) -> Option<f64> {
        let r = self.range();
        (r > 0.0).then(|| (self.x * self.vx + self.y * self.vy) / r)
    }
    /// Range tau −r/ṙ (s), defined only while closing.
    pub fn tau(&self) -> Option<f64> {
        range_tau(self.x, self.y, self.vx, self.vy)
    }
}

/// Range tau τ = −r/ṙ (s) of a relative state, `None` unless the range is
/// closing (ṙ < 0). TCAS II uses it as the time to closest approach.
pub fn range_tau(x: f64, y: f64, vx: f64, vy: f64) -> Option<f64> {
    let r2 = x * x + y * y;
    let r_rdot = x * vx + y * vy; // r·ṙ
    (r_rdot < 0.0 && r2 > 0.0).then(|| -r2 / r_rdot)
}

/// Time (s from now) and distance (m) of the horizontal closest approach of a
/// constant-velocity relative state: t = −(p·v)/|v|² (clamped at 0),
/// d = |p + v t|.
pub fn closest_approach(x: f64, y: f64, vx: f64, vy: f64) -> (f64, f64) {
    let v2 = vx * vx + vy * vy;
    let t = if v2 > 0.0 {
        (-(x * vx + y * vy) / v2).max(0.0)
    } else {
        0.0
    };
    (t, (x + vx * t).hypot(y + vy * t))
}

/// One measurement (a row of the measurements CSV).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measurement {
    Cartesian {
        t: f64,
        x: f64,
        y: f64,
    },
    Polar {
        t: f64,
        /// Slant range (m), > 0.
        range: f64,
        /// Azimuth (rad) clockwise from +y, in [0, 2π).
        azimuth: f64,
        /// Mode C reported altitude (ft, multiple of 100); `None` for a
        /// non-reporting intruder or a scenario without altitudes.
        alt_ft: Option<f64>,
    },
}

impl Measurement {
    pub fn t(&self) -> f64 {
        match *self {
            Measurement::Cartesian { t, .. } | Measurement::Polar { t, .. } => t,
        }
    }
    /// The measured position in the Cartesian frame (x = R sin B,
    /// y = R cos B for polar measurements).
    pub fn position(&self) -> [f64; 2] {
        match *self {
            Measurement::Cartesian { x, y, .. } => [x, y],
            Measurement::Polar { range, azimuth, .. } => {
                let (s, c) = azimuth.sin_cos();
                [range * s, range * c]
            }
        }
    }
}

/// One scan: the truth of every present target and the measurements
/// (shuffled, unlabelled) delivered at `t`.
#[derive(Debug, Clone, PartialEq)]
pub struct Scan {
    pub t: f64,
    pub truth: Vec<TruthState>,
    pub measurements: Vec<Measurement>,
    /// For each entry of `measurements`, the target it came from (`None`:
    /// clutter). Not written to the CSV (the tracker must not see it); kept
    /// for association-accuracy checks.
    pub origins: Vec<Option<u32>>,
}

/// A generated run.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioRun {
    pub info: ScenarioInfo,
    pub seed: u64,
    pub scans: Vec<Scan>,
}

impl Scan {
    /// The truth as the metrics module takes it.
    pub fn truth_points(&self) -> Vec<TruthPoint> {
        self.truth
            .iter()
            .map(|s| TruthPoint {
                id: s.target,
                x: s.x,
                y: s.y,
            })
            .collect()
    }
}

impl ScenarioRun {
    /// Every truth row, scan by scan.
    pub fn truth(&self) -> impl Iterator<Item = &TruthState> {
        self.scans.iter().flat_map(|s| s.truth.iter())
    }
    /// Every measurement, scan by scan.
    pub fn measurements(&self) -> impl Iterator<Item = &Measurement> {
        self.scans.iter().flat_map(|s| s.measurements.iter())
    }
    /// The truth of one target over the scans where it is present.
    pub fn target_truth(&self, target: u32) -> Vec<TruthState> {
        self.truth()
            .filter(|s| s.target == target)
            .copied()
            .collect()
    }

    /// The measurements CSV (see the module doc for the format).
    pub fn measurements_csv(&self) -> String {
        let mut out = String::with_capacity(32 * self.scans.len());
        out.push_str(self.info.measurements_header());
        out.push('\n');
        for m in self.measurements() {
            match *m {
                Measurement::Cartesian { t, x, y } => {
                    let _ = writeln!(out, "{t},{x},{y}");
                }
                Measurement::Polar {
                    t,
                    range,
                    azimuth,
                    alt_ft,
                } => {
                    let _ = write!(out, "{t},{range},{azimuth}");
                    if self.info.has_altitude {
                        out.push(',');
                        if let Some(a) = alt_ft {
                            let _ = write!(out, "{a}");
                        }
                    }
                    out.push('\n');
                }
            }
        }
        out
    }

    /// The truth CSV (see the module doc for the format).
    pub fn truth_csv(&self) -> String {
        let mut out = String::with_capacity(64 * self.scans.len());
        out.push_str(&self.info.truth_header());
        out.push('\n');
        for s in self.truth() {
            let _ = write!(out, "{}", s.t);
            if self.info.multi_target {
                let _ = write!(out, ",{}", s.target);
            }
            let _ = write!(out, ",{},{},{},{}", s.x, s.y, s.vx, s.vy);
            if self.info.frame == MeasurementFrame::Polar {
                let _ = write!(
                    out,
                    ",{},{},{},",
                    s.range(),
                    s.azimuth(),
                    s.range_rate().unwrap_or(0.0)
                );
                if let Some(tau) = s.tau() {
                    let _ = write!(out, "{tau}");
                }
            }
            if self.info.has_altitude {
                out.push(',');
                if let Some(a) = s.alt_ft {
                    let _ = write!(out, "{a}");
                }
                out.push(',');
                if let Some(a) = self.info.own_altitude_ft {
                    let _ = write!(out, "{a}");
                }
            }
            out.push('\n');
        }
        out
    }
}

/// Why a scenario could not be generated.
#[derive(Debug, Clone, PartialEq)]
pub enum ScenarioError {
    /// No scenario of that name; the names are [`SCENARIO_NAMES`].
    Unknown(String),
    /// A noise model of the scenario table is invalid (a bug in this file).
    Noise(NoiseError),
}

impl std::fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ScenarioError::Unknown(name) => write!(
                f,
                "unknown scenario '{name}' (known: {})",
                SCENARIO_NAMES.join(", ")
            ),
            ScenarioError::Noise(e) => write!(f, "invalid noise model: {e}"),
        }
    }
}

impl std::error::Error for ScenarioError {}

impl From<NoiseError> for ScenarioError {
    fn from(e: NoiseError) -> Self {
        ScenarioError::Noise(e)
    }
}

/// Every scenario, in `--list` order.
pub const SCENARIO_NAMES: &[&str] = &[
    "alwagih-cv",
    "alwagih-cv-coloured",
    "li-maneuver",
    "liu-turn",
    "he-tcas",
    "tcas-converging",
    "two-crossing",
    "parallel-200m",
    "tcas-30",
    "dense",
];

/// The description of every scenario, in [`SCENARIO_NAMES`] order.
pub fn scenarios() -> Vec<ScenarioInfo> {
    SCENARIO_NAMES.iter().filter_map(|n| info(n)).collect()
}

/// Seed of Monte Carlo run `run` of a base seed.
pub fn monte_carlo_seed(base: u64, run: u64) -> u64 {
    derive_seed(base, run)
}

// ---------------------------------------------------------------------------
// Scenario definitions
// ---------------------------------------------------------------------------

/// Al-Wagih & Abdulla §6 give no trajectory, noise level, sampling period or
/// run length, only that the data are "simulated radar data" and that half of
/// the ten sets have white and half coloured Gaussian noise. Our choices:
/// a constant-velocity target (the αβ tracker's design case, and the issue's
/// name for the scenario), T = 1 s, 150 scans, start (0, 0) m, velocity
/// (20, 40) m/s, independent per-axis noise σ = 20 m. The paper's "five
/// experiments" are five seeds of the same trajectory; the coloured sets use
/// AR(1) noise with ρ = 0.8 (correlation time ≈ 4.5 scans) and the same
/// stationary σ, so white and coloured sets differ only in correlation.
/// The paper's Tables 1–2 cannot be regenerated without its trajectory: only
/// the ranking of the methods is comparable.
const ALWAGIH_SIGMA: f64 = 20.0;
const ALWAGIH_RHO: f64 = 0.8;
const ALWAGIH_START: [f64; 2] = [0.0, 0.0];
const ALWAGIH_VELOCITY: [f64; 2] = [20.0, 40.0];

/// Li, Zhao, Liang & Zhang §5: 100 scans, T = 1 s, start (0, 0) m, velocity
/// (10, 5) m/s; accelerations (2, 0) m/s² during scans 12–16, (0, 2) during
/// 32–36, (0, −1.5) during 53–73, (−1.5, 0) during 82–86; "the covariance of
/// noise is 1", read as the measurement-noise covariance I₂ (m²): independent
/// per-axis σ = 1 m. 100 Monte Carlo runs.
///
/// Reading of "during scans a–b": scans are numbered from 1 (scan k at
/// t = (k−1) s, so scan 1 is the start at (0, 0)), and the acceleration acts
/// over the interval from scan k to scan k+1 for every k in a..=b, i.e.
/// b−a+1 whole periods (5, 5, 21 and 5 s). The velocity reported at scan a is
/// still the pre-manoeuvre one; at scan b+1 the manoeuvre is complete.
/// The paper's measurements are Cartesian; for its eq. (11) Δd see
/// [`SensorNoise::range_bearing_errors`] (Δd = λ·√2 m here).
pub const LI_ACCELERATIONS: &[(usize, usize, [f64; 2])] = &[
    (12, 16, [2.0, 0.0]),
    (32, 36, [0.0, 2.0]),
    (53, 73, [0.0, -1.5]),
    (82, 86, [-1.5, 0.0]),
];

/// Liu, Wang & Yang Table 1 and §3.2.1: start (533, 389) m, speed 150 m/s,
/// initial heading ("方位角") 45°, turn radius 9000 m, T = 2 s, 80 samples,
/// error coefficient (μ, σ) = (0, 5): zero-mean noise with σ = 5 m per axis
/// (their σm² = 25 of §2.1.4 agrees). The target flies straight for the first
/// 30 periods, turns for 15 periods, then flies straight again.
///
/// Not stated, chosen: the turn is to the left (counter-clockwise, turn rate
/// +v/R = +1/60 rad/s), a coordinated turn at constant speed. 45° from +x
/// counter-clockwise and 45° from +y clockwise are the same direction, so the
/// heading convention does not matter. The turn lasts 30 s: 0.5 rad (28.6°),
/// centripetal acceleration 150²/9000 = 2.5 m/s². Sample k (0-based) is at
/// t = 2k s: straight on [0, 60] s, turning on [60, 90] s, straight after.
const LIU_START: [f64; 2] = [533.0, 389.0];
const LIU_SPEED: f64 = 150.0;
const LIU_RADIUS: f64 = 9000.0;
const LIU_SIGMA: f64 = 5.0;

/// He, Peng, Ling & Quan §4: two aircraft flying the same direction, the
/// target ahead at 700 km/h, the own aircraft behind at 900 km/h (it closes
/// at 200 km/h = 55.6 m/s); target azimuth 30°, initial range 280 km,
/// T = 1 s, 500 s (scans at t = 0..499), range noise 100 m ("Navr = 100 m"),
/// 200 Monte Carlo runs.
///
/// Geometry (not drawn in the text, chosen): both aircraft fly along +y, the
/// frame's y axis, so the azimuth is also the relative bearing from the own
/// aircraft's nose. Relative position at t = 0: (280 sin 30°, 280 cos 30°) km
/// = (140, 242.487) km; relative velocity (0, −55.556) m/s. After 500 s the
/// range is ≈ 256.3 km and the azimuth ≈ 33.1°.
///
/// Azimuth noise: the paper's cross-range variance VAR = R²·7.569e−3 (eq. 9–10)
/// is R²σ_B² with σ_B² = 7.569e−3 rad², σ_B = 0.087 rad = 4.98° — the usual
/// ≈ 5° TCAS bearing accuracy. We draw the azimuth noise with that σ so the
/// filter's assumed VAR matches the data. At 280 km that is ≈ 24 km of
/// cross-range noise, which dominates the 100 m range noise.
const HE_RANGE0: f64 = 280_000.0;
const HE_AZIMUTH0_DEG: f64 = 30.0;
const HE_OWN_SPEED: f64 = 900.0 * KM_PER_HOUR;
const HE_TARGET_SPEED: f64 = 700.0 * KM_PER_HOUR;
/// σ_B² of He et al. eq. (9)–(10), rad².
pub const HE_AZIMUTH_VARIANCE: f64 = 7.569e-3;

/// A TCAS-realistic converging encounter (beyond the papers; DO-185B-like
/// sensor figures): 1 s surveillance updates, range σ = 50 ft (15.24 m),
/// bearing σ = 5° (0.0873 rad), Mode C altitude (100 ft quantised, no other
/// error).
///
/// Own aircraft: level at 8000 ft (TCAS sensitivity level 5), flying +y at
/// 250 kt. Intruder: head-on with a 0.2 NM lateral offset: it starts at
/// 14 NM range, 0.2 NM to the right (x = +0.2 NM), flying −y at 250 kt, so
/// the closure rate is 500 kt (257.2 m/s); closest approach 0.2 NM
/// (370.4 m) at t = 13.99857 NM / 500 kt = 100.79 s. Intruder altitude: 7500
/// ft at t = 0, climbing 300 ft/min (5 ft/s): 8004 ft at closest approach,
/// i.e. co-altitude. 140 scans (t = 0..139 s) so the track continues 39 s past
/// CPA and the advisory should clear. Truth tau at t = 0 is ≈ 100.8 s.
pub const TCAS_OWN_ALTITUDE_FT: f64 = 8000.0;
const TCAS_RANGE_SIGMA: f64 = 50.0 * FOOT;
const TCAS_BEARING_SIGMA_DEG: f64 = 5.0;
const TCAS_SPEED: f64 = 250.0 * KNOT;
const TCAS_START_RANGE: f64 = 14.0 * NAUTICAL_MILE;
const TCAS_OFFSET: f64 = 0.2 * NAUTICAL_MILE;
const TCAS_INTRUDER_ALT0_FT: f64 = 7500.0;
const TCAS_INTRUDER_VS_FT_S: f64 = 5.0;

/// Multi-target Cartesian scenarios (`two-crossing`, `parallel-200m`,
/// `dense`): per-axis white noise σ = 20 m, Pd = 0.9, Poisson clutter uniform
/// over the surveillance rectangle, T = 1 s.
const MT_SIGMA: f64 = 20.0;
const MT_PD: f64 = 0.9;
const MT_SQUARE_HALF: f64 = 5000.0;
/// 10 false measurements per scan over the 10 km × 10 km square:
/// λ = 1e−7 m⁻² (0.1 per km²).
const MT_CLUTTER_PER_SCAN: f64 = 10.0;

/// `dense`: 64 targets (= [`DENSE_TABLE_CAPACITY`]) on an 8 × 8 grid 1500 m
/// apart, each with a random heading and a speed uniform in 30–80 m/s (drawn
/// once from the fixed layout seed), 30 scans; 16 km × 16 km square with 8
/// false measurements per scan (λ = 3.125e−8 m⁻²). With every target
/// confirmed the table is full and every clutter-started candidate must be
/// refused.
const DENSE_HALF: f64 = 8000.0;
const DENSE_CLUTTER_PER_SCAN: f64 = 8.0;

/// `tcas-30`: 30 intruders around an own aircraft level at 8000 ft flying +y
/// at 250 kt, 60 scans of 1 s, the sensor of `tcas-converging` (range σ 50 ft,
/// bearing σ 5°, Mode C), Pd = 0.9, surveillance disc of 14 NM, 3 false
/// replies per scan uniform over the disc (λ = 1.42e−9 m⁻², 0.0049 per NM²)
/// with reported altitudes uniform in own ± 4000 ft. Intruder 1 is a threat:
/// head-on from 8 NM with a 0.1 NM offset, 250 kt, 200 ft above. Intruders
/// 2–30 (fixed layout seed): range uniform in 2–10 NM, azimuth uniform,
/// ground speed 120–350 kt, heading uniform, altitude own ± 4000 ft, a third
/// of them climbing or descending at up to 1500 ft/min. Intruders 29 and 30
/// do not report altitude (empty `alt`). An intruder beyond 14 NM is not
/// present.
const TCAS30_INTRUDERS: usize = 30;
const TCAS30_RADIUS: f64 = 14.0 * NAUTICAL_MILE;
const TCAS30_CLUTTER_PER_SCAN: f64 = 3.0;
const TCAS30_PD: f64 = 0.9;

fn white(sigma: f64) -> NoiseModel {
    NoiseModel::White { sigma }
}

const STRAIGHT_TUNING: KalmanTuning = KalmanTuning {
    cv_sigma_acceleration: 0.1,
    ca_sigma_acceleration_increment: 0.05,
    rationale: "straight-line truth: the matching process noise is zero; a small σ_a keeps \
                the filter from locking onto a wrong velocity",
};

/// The description of scenario `name`.
pub fn info(name: &str) -> Option<ScenarioInfo> {
    let cart = |sigma: f64| SensorNoise::Cartesian {
        x: white(sigma),
        y: white(sigma),
    };
    let tcas_sensor = SensorNoise::Polar {
        range: white(TCAS_RANGE_SIGMA),
        azimuth: white(TCAS_BEARING_SIGMA_DEG.to_radians()),
    };
    let square = |half: f64| Region::Rectangle {
        x_min: -half,
        x_max: half,
        y_min: -half,
        y_max: half,
    };
    let base = ScenarioInfo {
        name: "",
        description: "",
        source: "",
        period_s: 1.0,
        scans: 0,
        targets: 1,
        multi_target: false,
        frame: MeasurementFrame::Cartesian,
        has_altitude: false,
        noise: cart(1.0),
        detection_probability: 1.0,
        clutter: None,
        surveillance: None,
        own_altitude_ft: None,
        monte_carlo_runs: 100,
        kalman: STRAIGHT_TUNING,
    };
    let info = match name {
        "alwagih-cv" => ScenarioInfo {
            name: "alwagih-cv",
            description: "Al-Wagih & Abdulla s6: constant-velocity 2-D target, white noise \
                          (20 m/axis), T=1 s, 150 scans",
            source: "Al-Wagih & Abdulla, section 6, Tables 1-2 (parameters chosen)",
            scans: 150,
            noise: cart(ALWAGIH_SIGMA),
            ..base
        },
        "alwagih-cv-coloured" => ScenarioInfo {
            name: "alwagih-cv-coloured",
            description: "Al-Wagih & Abdulla s6: the same target with AR(1) coloured noise \
                          (rho 0.8, 20 m/axis)",
            source: "Al-Wagih & Abdulla, section 6, Tables 2, 4, 6 (parameters chosen)",
            scans: 150,
            noise: SensorNoise::Cartesian {
                x: NoiseModel::Ar1 {
                    sigma: ALWAGIH_SIGMA,
                    rho: ALWAGIH_RHO,
                },
                y: NoiseModel::Ar1 {
                    sigma: ALWAGIH_SIGMA,
                    rho: ALWAGIH_RHO,
                },
            },
            ..base
        },
        "li-maneuver" => ScenarioInfo {
            name: "li-maneuver",
            description: "Li et al. s5: 100 scans, T=1 s, (10,5) m/s with four acceleration \
                          stages, noise 1 m/axis",
            source: "Li, Zhao, Liang & Zhang, section 5",
            scans: 100,
            noise: cart(1.0),
            kalman: KalmanTuning {
                cv_sigma_acceleration: 1.2,
                ca_sigma_acceleration_increment: 1.0,
                rationale: "Bar-Shalom's rules of thumb: σ_a ≈ 0.6·a_max (a_max = 2 m/s²); \
                            σ_Δa ≈ 0.5·Δa_max (acceleration switches 0 → 2 m/s² in one period)",
            },
            ..base
        },
        "liu-turn" => ScenarioInfo {
            name: "liu-turn",
            description: "Liu et al. Table 1: (533,389) m, 150 m/s at 45 deg, T=2 s, 80 samples, \
                          15-period left turn of radius 9000 m, noise 5 m/axis",
            source: "Liu, Wang & Yang, Table 1 and section 3.2.1",
            period_s: 2.0,
            scans: 80,
            noise: cart(LIU_SIGMA),
            kalman: KalmanTuning {
                cv_sigma_acceleration: 1.5,
                ca_sigma_acceleration_increment: 1.25,
                rationale: "σ_a ≈ 0.6·a_max with the turn's centripetal a_max = 2.5 m/s²; \
                            σ_Δa ≈ 0.5·Δa_max (the turn starts within one period)",
            },
            ..base
        },
        "he-tcas" => ScenarioInfo {
            name: "he-tcas",
            description: "He et al. s4: same-direction aircraft, own 900 km/h behind target \
                          700 km/h, 280 km at 30 deg, range 100 m, azimuth 0.087 rad, 500 s",
            source: "He, Peng, Ling & Quan, section 4",
            scans: 500,
            frame: MeasurementFrame::Polar,
            noise: SensorNoise::Polar {
                range: white(100.0),
                azimuth: white(HE_AZIMUTH_VARIANCE.sqrt()),
            },
            monte_carlo_runs: 200,
            ..base
        },
        "tcas-converging" => ScenarioInfo {
            name: "tcas-converging",
            description: "TCAS encounter: intruder head-on from 14 NM, 0.2 NM offset, 500 kt \
                          closure, co-altitude at CPA (t=100.8 s); range 50 ft, bearing 5 deg, \
                          Mode C",
            source: "beyond the papers (TCAS II surveillance figures)",
            scans: 140,
            frame: MeasurementFrame::Polar,
            has_altitude: true,
            noise: tcas_sensor,
            own_altitude_ft: Some(TCAS_OWN_ALTITUDE_FT),
            ..base
        },
        "two-crossing" => ScenarioInfo {
            name: "two-crossing",
            description: "two targets crossing at 53 deg at t=30 s, Pd 0.9, 10 clutter/scan \
                          over 10x10 km, noise 20 m/axis, 60 scans",
            source: "beyond the papers (the multi-target scenarios)",
            scans: 60,
            targets: 2,
            multi_target: true,
            noise: cart(MT_SIGMA),
            detection_probability: MT_PD,
            clutter: Some(ClutterSpec {
                region: square(MT_SQUARE_HALF),
                mean_per_scan: MT_CLUTTER_PER_SCAN,
                altitude_band_ft: None,
            }),
            surveillance: Some(square(MT_SQUARE_HALF)),
            ..base
        },
        "parallel-200m" => ScenarioInfo {
            name: "parallel-200m",
            description: "two targets flying in parallel 200 m apart at 120 m/s, Pd 0.9, \
                          10 clutter/scan over 10x10 km, noise 20 m/axis, 60 scans",
            source: "beyond the papers (the multi-target scenarios)",
            scans: 60,
            targets: 2,
            multi_target: true,
            noise: cart(MT_SIGMA),
            detection_probability: MT_PD,
            clutter: Some(ClutterSpec {
                region: square(MT_SQUARE_HALF),
                mean_per_scan: MT_CLUTTER_PER_SCAN,
                altitude_band_ft: None,
            }),
            surveillance: Some(square(MT_SQUARE_HALF)),
            ..base
        },
        "tcas-30" => ScenarioInfo {
            name: "tcas-30",
            description: "TCAS picture: 30 intruders within 14 NM (range/azimuth/Mode C, 2 \
                          non-reporting), Pd 0.9, 3 false replies/scan, 60 scans",
            source: "beyond the papers (the multi-target scenarios)",
            scans: 60,
            targets: TCAS30_INTRUDERS,
            multi_target: true,
            frame: MeasurementFrame::Polar,
            has_altitude: true,
            noise: tcas_sensor,
            detection_probability: TCAS30_PD,
            clutter: Some(ClutterSpec {
                region: Region::Disc {
                    radius: TCAS30_RADIUS,
                },
                mean_per_scan: TCAS30_CLUTTER_PER_SCAN,
                altitude_band_ft: Some((
                    TCAS_OWN_ALTITUDE_FT - 4000.0,
                    TCAS_OWN_ALTITUDE_FT + 4000.0,
                )),
            }),
            surveillance: Some(Region::Disc {
                radius: TCAS30_RADIUS,
            }),
            own_altitude_ft: Some(TCAS_OWN_ALTITUDE_FT),
            ..base
        },
        "dense" => ScenarioInfo {
            name: "dense",
            description: "64 targets (a 64-track table's capacity) on a 1.5 km grid, random \
                          headings, Pd 0.9, 8 clutter/scan over 16x16 km, 30 scans",
            source: "beyond the papers (the multi-target scenarios)",
            scans: 30,
            targets: DENSE_TABLE_CAPACITY,
            multi_target: true,
            noise: cart(MT_SIGMA),
            detection_probability: MT_PD,
            clutter: Some(ClutterSpec {
                region: square(DENSE_HALF),
                mean_per_scan: DENSE_CLUTTER_PER_SCAN,
                altitude_band_ft: None,
            }),
            surveillance: Some(square(DENSE_HALF)),
            ..base
        },
        _ => return None,
    };
    Some(info)
}

// ---------------------------------------------------------------------------
// Truth
// ---------------------------------------------------------------------------

/// What a target does during one sampling period.
#[derive(Debug, Clone, Copy, PartialEq)]
enum StepMotion {
    /// Constant acceleration (m/s²); zero is constant velocity.
    Accelerate([f64; 2]),
    /// Coordinated turn at constant speed, turn rate ω (rad/s, positive =
    /// counter-clockwise).
    Turn(f64),
}

/// A target's initial state and its motion in each period.
struct TargetPlan {
    id: u32,
    position: [f64; 2],
    velocity: [f64; 2],
    /// Motion over period k (from scan k to scan k+1); missing = constant
    /// velocity.
    steps: Vec<StepMotion>,
    /// (altitude at t = 0 in ft, vertical rate in ft/s).
    altitude: Option<(f64, f64)>,
    /// Transponder reports altitude (Mode C).
    reports_altitude: bool,
}

impl TargetPlan {
    fn straight(id: u32, position: [f64; 2], velocity: [f64; 2]) -> Self {
        TargetPlan {
            id,
            position,
            velocity,
            steps: Vec::new(),
            altitude: None,
            reports_altitude: true,
        }
    }

    /// The state at every scan, integrated exactly period by period.
    fn states(&self, period: f64, scans: usize) -> Vec<TruthState> {
        let mut p = self.position;
        let mut v = self.velocity;
        let mut out = Vec::with_capacity(scans);
        for k in 0..scans {
            let t = k as f64 * period;
            out.push(TruthState {
                t,
                target: self.id,
                x: p[0],
                y: p[1],
                vx: v[0],
                vy: v[1],
                alt_ft: self.altitude.map(|(a0, rate)| a0 + rate * t),
            });
            let motion = self
                .steps
                .get(k)
                .copied()
                .unwrap_or(StepMotion::Accelerate([0.0, 0.0]));
            (p, v) = propagate(p, v, motion, period);
        }
        out
    }
}

/// Exact propagation over one period `dt`.
fn propagate(p: [f64; 2], v: [f64; 2], motion: StepMotion, dt: f64) -> ([f64; 2], [f64; 2]) {
    match motion {
        StepMotion::Accelerate(a) => (
            [
                p[0] + v[0] * dt + 0.5 * a[0] * dt * dt,
                p[1] + v[1] * dt + 0.5 * a[1] * dt * dt,
            ],
            [v[0] + a[0] * dt, v[1] + a[1] * dt],
        ),
        StepMotion::Turn(omega) => {
            if omega == 0.0 {
                return ([p[0] + v[0] * dt, p[1] + v[1] * dt], v);
            }
            // Velocity rotates by ωdt; position integrates the rotating
            // velocity: ∫₀^dt R(ωs) v ds = [sin ωdt, −(1−cos ωdt); 1−cos ωdt,
            // sin ωdt]/ω · v.
            let (s, c) = (omega * dt).sin_cos();
            let a = s / omega;
            let b = (1.0 - c) / omega;
            (
                [p[0] + a * v[0] - b * v[1], p[1] + b * v[0] + a * v[1]],
                [c * v[0] - s * v[1], s * v[0] + c * v[1]],
            )
        }
    }
}

fn li_plan(scans: usize) -> TargetPlan {
    let mut steps = vec![StepMotion::Accelerate([0.0, 0.0]); scans];
    for &(first, last, a) in LI_ACCELERATIONS {
        // Scan k (1-based) starts period k−1 (0-based).
        for step in steps.iter_mut().take(last).skip(first - 1) {
            *step = StepMotion::Accelerate(a);
        }
    }
    TargetPlan {
        steps,
        ..TargetPlan::straight(1, [0.0, 0.0], [10.0, 5.0])
    }
}

/// Liu's turn: 30 straight periods, 15 turning, then straight.
pub const LIU_STRAIGHT_PERIODS: usize = 30;
pub const LIU_TURN_PERIODS: usize = 15;

fn liu_plan(scans: usize) -> TargetPlan {
    let omega = LIU_SPEED / LIU_RADIUS;
    let steps = (0..scans)
        .map(|k| {
            if (LIU_STRAIGHT_PERIODS..LIU_STRAIGHT_PERIODS + LIU_TURN_PERIODS).contains(&k) {
                StepMotion::Turn(omega)
            } else {
                StepMotion::Accelerate([0.0, 0.0])
            }
        })
        .collect();
    let (s, c) = FRAC_PI_4.sin_cos();
    TargetPlan {
        steps,
        ..TargetPlan::straight(1, LIU_START, [LIU_SPEED * c, LIU_SPEED * s])
    }
}

fn he_plan() -> TargetPlan {
    let (s, c) = HE_AZIMUTH0_DEG.to_radians().sin_cos();
    TargetPlan::straight(
        1,
        [HE_RANGE0 * s, HE_RANGE0 * c],
        [0.0, HE_TARGET_SPEED - HE_OWN_SPEED],
    )
}

fn tcas_converging_plan() -> TargetPlan {
    let y0 = (TCAS_START_RANGE * TCAS_START_RANGE - TCAS_OFFSET * TCAS_OFFSET).sqrt();
    TargetPlan {
        altitude: Some((TCAS_INTRUDER_ALT0_FT, TCAS_INTRUDER_VS_FT_S)),
        ..TargetPlan::straight(1, [TCAS_OFFSET, y0], [0.0, -2.0 * TCAS_SPEED])
    }
}

fn crossing_plans() -> Vec<TargetPlan> {
    // Both reach (0, 0) at t = 30 s; crossing angle 2·atan(50/100) = 53.1°.
    vec![
        TargetPlan::straight(1, [-3000.0, -1500.0], [100.0, 50.0]),
        TargetPlan::straight(2, [-3000.0, 1500.0], [100.0, -50.0]),
    ]
}

fn parallel_plans() -> Vec<TargetPlan> {
    vec![
        TargetPlan::straight(1, [-4000.0, -100.0], [120.0, 0.0]),
        TargetPlan::straight(2, [-4000.0, 100.0], [120.0, 0.0]),
    ]
}

fn dense_plans() -> Vec<TargetPlan> {
    let mut rng = rng_from_seed(derive_seed(LAYOUT_SEED, 64));
    let side = 8usize;
    let spacing = 1500.0;
    let offset = -(side as f64 - 1.0) / 2.0 * spacing; // −5250 m
    (0..DENSE_TABLE_CAPACITY)
        .map(|i| {
            let (row, col) = (i / side, i % side);
            let heading = uniform(&mut rng, 0.0, TAU);
            let speed = uniform(&mut rng, 30.0, 80.0);
            TargetPlan::straight(
                i as u32 + 1,
                [offset + col as f64 * spacing, offset + row as f64 * spacing],
                [speed * heading.cos(), speed * heading.sin()],
            )
        })
        .collect()
}

fn tcas30_plans() -> Vec<TargetPlan> {
    let own_v = [0.0, TCAS_SPEED];
    let mut plans = Vec::with_capacity(TCAS30_INTRUDERS);
    // Intruder 1: the threat.
    let y0 = ((8.0 * NAUTICAL_MILE).powi(2) - (0.1 * NAUTICAL_MILE).powi(2)).sqrt();
    plans.push(TargetPlan {
        altitude: Some((TCAS_OWN_ALTITUDE_FT + 200.0, 0.0)),
        ..TargetPlan::straight(1, [0.1 * NAUTICAL_MILE, y0], [0.0, -2.0 * TCAS_SPEED])
    });
    let mut rng = rng_from_seed(derive_seed(LAYOUT_SEED, 30));
    for id in 2..=TCAS30_INTRUDERS as u32 {
        let range = uniform(&mut rng, 2.0, 10.0) * NAUTICAL_MILE;
        let azimuth = uniform(&mut rng, 0.0, TAU);
        let speed = uniform(&mut rng, 120.0, 350.0) * KNOT;
        let heading = uniform(&mut rng, 0.0, TAU); // clockwise from +y
        let alt0 = TCAS_OWN_ALTITUDE_FT + uniform(&mut rng, -4000.0, 4000.0);
        let climbs = uniform(&mut rng, 0.0, 1.0) < 1.0 / 3.0;
        let rate = uniform(&mut rng, -25.0, 25.0); // ft/s = ±1500 ft/min
        let v_ground = [speed * heading.sin(), speed * heading.cos()];
        plans.push(TargetPlan {
            altitude: Some((alt0, if climbs { rate } else { 0.0 })),
            reports_altitude: id < 29,
            ..TargetPlan::straight(
                id,
                [range * azimuth.sin(), range * azimuth.cos()],
                [v_ground[0] - own_v[0], v_ground[1] - own_v[1]],
            )
        });
    }
    plans
}

fn plans(info: &ScenarioInfo) -> Vec<TargetPlan> {
    match info.name {
        "alwagih-cv" | "alwagih-cv-coloured" => {
            vec![TargetPlan::straight(1, ALWAGIH_START, ALWAGIH_VELOCITY)]
        }
        "li-maneuver" => vec![li_plan(info.scans)],
        "liu-turn" => vec![liu_plan(info.scans)],
        "he-tcas" => vec![he_plan()],
        "tcas-converging" => vec![tcas_converging_plan()],
        "two-crossing" => crossing_plans(),
        "parallel-200m" => parallel_plans(),
        "tcas-30" => tcas30_plans(),
        "dense" => dense_plans(),
        _ => Vec::new(),
    }
}

/// The truth of scenario `name`, per scan (the same for every seed).
pub fn truth(name: &str) -> Result<Vec<Vec<TruthState>>, ScenarioError> {
    let info = info(name).ok_or_else(|| ScenarioError::Unknown(name.to_string()))?;
    Ok(truth_for(&info, &plans(&info)))
}

fn truth_for(info: &ScenarioInfo, plans: &[TargetPlan]) -> Vec<Vec<TruthState>> {
    let per_target: Vec<Vec<TruthState>> = plans
        .iter()
        .map(|p| p.states(info.period_s, info.scans))
        .collect();
    (0..info.scans)
        .map(|k| {
            per_target
                .iter()
                .map(|states| states[k])
                .filter(|s| info.surveillance.is_none_or(|r| r.contains(s.x, s.y)))
                .collect()
        })
        .collect()
}

// ---------------------------------------------------------------------------
// Measurements
// ---------------------------------------------------------------------------

/// Azimuth folded into [0, 2π).
pub fn wrap_two_pi(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    // rem_euclid can round up to exactly 2π for tiny negative inputs.
    if w >= TAU {
        0.0
    } else {
        w
    }
}

/// Mode C reporting: pressure altitude to the nearest 100 ft (the Gillham
/// code's 100 ft increments, transitions at ±50 ft).
pub fn mode_c(alt_ft: f64) -> f64 {
    (alt_ft / 100.0).round() * 100.0
}

/// Per-target noise channels (each target keeps its own AR(1) memory).
struct Channels {
    a: NoiseProcess,
    b: NoiseProcess,
}

/// Generates run `seed` of scenario `name`.
///
/// Random streams (all derived from `seed`, so changing one part of the
/// model does not shift the others): sensor noise, detections, clutter,
/// row order. The noise of every present target is drawn every scan, detected
/// or not, so the coloured noise evolves in time and the streams stay
/// aligned whatever Pd does.
pub fn generate(name: &str, seed: u64) -> Result<ScenarioRun, ScenarioError> {
    let info = info(name).ok_or_else(|| ScenarioError::Unknown(name.to_string()))?;
    let plans = plans(&info);
    let truth = truth_for(&info, &plans);

    let mut noise_rng = rng_from_seed(derive_seed(seed, 1));
    let mut detect_rng = rng_from_seed(derive_seed(seed, 2));
    let mut clutter_rng = rng_from_seed(derive_seed(seed, 3));
    let mut order_rng = rng_from_seed(derive_seed(seed, 4));

    let (model_a, model_b) = match info.noise {
        SensorNoise::Cartesian { x, y } => (x, y),
        SensorNoise::Polar { range, azimuth } => (range, azimuth),
    };
    let mut channels: Vec<Channels> = plans
        .iter()
        .map(|_| {
            Ok(Channels {
                a: NoiseProcess::new(model_a)?,
                b: NoiseProcess::new(model_b)?,
            })
        })
        .collect::<Result<_, NoiseError>>()?;

    let mut scans = Vec::with_capacity(info.scans);
    for (k, present) in truth.into_iter().enumerate() {
        let t = k as f64 * info.period_s;
        let mut rows: Vec<(Measurement, Option<u32>)> = Vec::new();
        for s in &present {
            let index = plans.iter().position(|p| p.id == s.target).unwrap_or(0);
            let ch = &mut channels[index];
            let na = ch.a.sample(&mut noise_rng);
            let nb = ch.b.sample(&mut noise_rng);
            if info.detection_probability < 1.0
                && !bernoulli(&mut detect_rng, info.detection_probability)
            {
                continue;
            }
            let m = match info.frame {
                MeasurementFrame::Cartesian => Measurement::Cartesian {
                    t,
                    x: s.x + na,
                    y: s.y + nb,
                },
                MeasurementFrame::Polar => Measurement::Polar {
                    t,
                    // A sensor never reports a negative range; at our ranges
                    // (≥ 370 m against σ ≤ 100 m) the fold is never taken.
                    range: (s.range() + na).abs(),
                    azimuth: wrap_two_pi(s.azimuth() + nb),
                    alt_ft: match (info.has_altitude, plans[index].reports_altitude) {
                        (true, true) => s.alt_ft.map(mode_c),
                        _ => None,
                    },
                },
            };
            rows.push((m, Some(s.target)));
        }
        if let Some(clutter) = info.clutter {
            let count = poisson(&mut clutter_rng, clutter.mean_per_scan);
            for _ in 0..count {
                rows.push((clutter_point(&info, &clutter, t, &mut clutter_rng), None));
            }
        }
        if info.multi_target {
            shuffle(&mut order_rng, &mut rows);
        }
        let (measurements, origins) = rows.into_iter().unzip();
        scans.push(Scan {
            t,
            truth: present,
            measurements,
            origins,
        });
    }
    Ok(ScenarioRun { info, seed, scans })
}

fn clutter_point(
    info: &ScenarioInfo,
    clutter: &ClutterSpec,
    t: f64,
    rng: &mut SimRng,
) -> Measurement {
    let (x, y) = match clutter.region {
        Region::Rectangle {
            x_min,
            x_max,
            y_min,
            y_max,
        } => (uniform(rng, x_min, x_max), uniform(rng, y_min, y_max)),
        Region::Disc { radius } => {
            // Uniform over the disc's area: r = R√u.
            let r = radius * uniform(rng, 0.0, 1.0).sqrt();
            let b = uniform(rng, 0.0, TAU);
            (r * b.sin(), r * b.cos())
        }
    };
    match info.frame {
        MeasurementFrame::Cartesian => Measurement::Cartesian { t, x, y },
        MeasurementFrame::Polar => Measurement::Polar {
            t,
            range: x.hypot(y),
            azimuth: wrap_two_pi(x.atan2(y)),
            alt_ft: clutter
                .altitude_band_ft
                .map(|(lo, hi)| mode_c(uniform(rng, lo, hi))),
        },
    }
}
