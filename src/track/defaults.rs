//! The documented default tracker: every parameter derived, by stated rules,
//! from the sensor's figures and the targets' envelope ([`TrackerDesign`]).
//!
//! Nothing here was adjusted to the simulated scenarios: the rules and the
//! four budgets below were fixed first, and the scenarios' results are what
//! they are (`results/multi-target/`).
//!
//! # Inputs
//!
//! * sensor accuracy: per-axis σ (Cartesian) or σ_R, σ_B (polar);
//! * detection probability P_D and false-measurement (clutter) density λ per
//!   m² per scan;
//! * the coverage ([`Coverage`]): a square, a disc, or none (the default).
//!   The rules count clutter over the coverage's area and take its farthest
//!   point as the largest range; with none, over the disc of the sensor's
//!   largest range [`TrackerDesign::max_range`];
//! * target envelope: largest speed v_max (relative speed for a TCAS
//!   sensor) and largest acceleration a_max (the manoeuvre level);
//! * the nominal scan period T.
//!
//! # Rules (in [`TrackerDesign::derive`])
//!
//! 1. **Gate threshold.** A true measurement may fall outside its gate; let
//!    that happen [`GATE_LOSS_FRACTION`] = 1 % as often as a missed
//!    detection: P_G = 1 − 0.01·(1 − P_D). The normalised squared innovation
//!    is χ² with 2 degrees of freedom, P(outside) = e^(−G/2), so
//!    G = −2·ln(0.01·(1 − P_D)) (P_D = 0.9: G = 13.82, P_G = 0.999). P_D is
//!    floored at 1 − 10⁻³ in this formula (a perfect sensor still needs a
//!    finite gate).
//! 2. **Manoeuvre model.** σ_w = a_max/2, the lower end of Bar-Shalom's
//!    ½–1 × a_max rule for a white-acceleration model. Kalata's tracking
//!    index Λ = σ_w·T²/σ (σ_max of rule 3 for a polar sensor) and its
//!    steady-state α_K ([`crate::design`]) give M2's count n_max, the first
//!    n with α̂(n) ≤ α_K (`least_squares_n_max`, for M2 when chosen). The
//!    Cartesian filter is `auto` ([`AutoGains`]): a per-axis Kalman filter
//!    written as αβ gains, configured from σ_max, its manoeuvre level
//!    estimated from the innovations, its covariance sizing the gate. The
//!    polar filter (He et al.) gets Q = σ_w².
//! 3. **Gate allowance** ½·a_max·T² (the drift an unmodelled acceleration
//!    causes over one interval) and **initiation radius** v_max·T plus a
//!    margin √(2G)·σ_max: the two points of a new track each carry the
//!    noise, so their difference has σ√2 per axis, and the margin keeps the
//!    gate's probability P_G. σ_max is the largest per-axis σ in the region
//!    (polar: max(σ_R, R_max·σ_B)).
//! 4. **Confirmation M-of-N** (the scan that starts a track counts as its
//!    first hit): the rule with the smallest M (fastest confirmation), then
//!    the smallest N ≤ 8, such that
//!    * a true target is confirmed with probability ≥
//!      [`MIN_TRUE_CONFIRMATION`] = 0.95: P(at least M − 1 hits in N − 1
//!      scans, each hit with probability P_D·P_G), and
//!    * the expected number of false tracks confirmed per scan is ≤
//!      [`MAX_FALSE_CONFIRMATIONS_PER_SCAN`] = 10⁻³ (one per 1000 scans):
//!      false starts per scan F = C·(1 − e^(−λ·A_init)) (each of the
//!      C = λ·A clutter points of a scan pairs with a clutter point of the
//!      next scan inside the initiation circle A_init), times P(at least
//!      M − 1 hits in N − 1 scans, each with probability q = λ·A_gate),
//!      A_gate the area of the gate right after initiation (the predicted
//!      variance after two points is 5σ² per axis at equal intervals, so
//!      the radius is σ·√(6G) + ½a_max T²; polar: the range/azimuth window
//!      with σ_R in range and R_max·σ_B across, area π·h_R·h_C). The table
//!      holds a tentative track's circle to that gate, grown over the scans
//!      since its last hit (`two_point_gate_radius`).
//!
//!    When no rule up to 8 scans meets both bounds (a low P_D, dense
//!    clutter), the design does not refuse the sensor: it takes the rule
//!    that meets the false-track bound with the highest probability of
//!    confirming a true target (Neyman–Pearson: the false-alarm rate fixed,
//!    the detection probability made largest), or, when none meets it, the
//!    rule with the fewest false confirmations (of equals, the one with the
//!    higher true confirmation; then the earlier in the order above); it
//!    says so ([`DerivedParameters::confirmation_meets_bounds`]) with both
//!    probabilities. The configurations built from the design
//!    ([`TrackerDesign::cartesian_config`] and the others) take that rule
//!    too: a caller that must not run on a compromise checks
//!    [`TrackerDesign::derive`] first.
//! 5. **Deletion.** A confirmed track is deleted after K consecutive misses,
//!    K the smallest with p_m^K·(1 − p_m) ≤ [`MAX_SPURIOUS_DELETIONS_PER_SCAN`]
//!    = 10⁻⁴ (the probability that a run of K misses starts at a given scan,
//!    p_m = 1 − P_D·P_G): a target present for 10 000 scans loses its track
//!    (and its id) to missed detections about once. A tentative track is
//!    deleted after N − M + 1 consecutive misses, the first point at which
//!    M-of-N can become unreachable (the table also deletes it whenever it
//!    does).
//! 6. **Surveillance volume**: the coverage's bounding box (a disc's
//!    bounding square); tracks leaving it are deleted and measurements
//!    outside it start none. With no coverage, no volume: nothing is
//!    dropped for where it is.
//! 7. **Lost in clutter.** A confirmed track is deleted when its gate
//!    (for the scan at hand) holds more false measurements on average than
//!    the chance of its target's own: λ·A_gate > P_D·P_G, a gate wider
//!    than the circle of radius √(P_D·P_G/(π·λ)) (in area, for a
//!    range/azimuth window). Past it a measurement in the gate is more
//!    likely clutter than the target (the track score's increment for a
//!    measurement, ln(P_D·g(ν)/λ) in Blackman & Popoli 1999, "Design and
//!    Analysis of Modern Tracking Systems", is then negative for one
//!    spread over the gate), so a track that coasted or took clutter in a
//!    manoeuvre, its gate grown, would otherwise be kept alive by the
//!    clutter it takes.
//!    No clutter, no bound.
//!
//! # The two nominal sensors
//!
//! [`TrackerDesign::NOMINAL_RADAR`] (σ = 20 m per axis, P_D = 0.9,
//! λ = 10⁻⁷ m⁻², 10 km square, v_max = 300 m/s, 1 s) and
//! [`TrackerDesign::NOMINAL_TCAS`] (σ_R = 50 ft, σ_B = 5°, P_D = 0.9,
//! λ = 3 per scan over a 14 NM disc, v_max = 1200 kt closure, 1 s) are the
//! sensors the multi-target scenarios simulate, stated as sensor specifications.
//! Both use a_max = g·tan 30° = 5.66 m/s², a coordinated turn at the 30°
//! bank limit of transport-aircraft autopilots. What the rules give for
//! them (checked by host-tests `tests/it/claims/multi_target.rs`):
//!
//! | | nominal radar | nominal TCAS |
//! |---|---|---|
//! | filter | `AutoFilter<S, 2>` (params `AutoGains<S, 2>`), σ = 20 m | `RangeAzimuthTrack<S>`, Q = 8.01 m²/s⁴ |
//! | gate | uncertainty, G = 13.82, a_max = 5.66 m/s² | range/azimuth window, G = 13.82, a_max = 5.66 m/s² |
//! | initiation radius | 300 m + 105 m | 617 m + 11.9 km |
//! | confirmation | 3 of 4 | 3 of 4 |
//! | deletion (confirmed, tentative) | 4, 2 | 4, 2 |

//!
//! # Limits
//!
//! Rule 4's false-confirmation estimate counts clutter in a tentative
//! track's first gate only (after a miss the gate it is held to grows): it
//! holds for a Cartesian sensor and is optimistic for a wide bearing window
//! (kilometres across range at 5°), which also takes in other targets'
//! measurements; the measured rates are
//! in `results/multi-target/` (docs/experiments.md, "Many targets").

use super::adapters::RangeAzimuthTrack;
use super::config::{TrackerConfig, Volume};
use super::gate::{ConfigError, Gate};
use crate::design::{kalata_gains, tracking_index};
use crate::filter::auto::AutoFilter;
use crate::filter::range_azimuth::RangeAzimuthNoise;
use crate::gain::al_wagih::{least_squares_alpha, LeastSquaresConfig};
use crate::gain::{AutoConfig, AutoGains};
use crate::num::{Numeric, Quantity, Scalar};

/// Fraction of a missed detection's probability allowed for a true
/// measurement falling outside its gate (rule 1).
pub const GATE_LOSS_FRACTION: f64 = 0.01;
/// Smallest probability of confirming a true target (rule 4).
pub const MIN_TRUE_CONFIRMATION: f64 = 0.95;
/// Largest expected number of false tracks confirmed per scan (rule 4).
pub const MAX_FALSE_CONFIRMATIONS_PER_SCAN: f64 = 1e-3;
/// Largest probability per scan that a true target's track is deleted by
/// missed detections (rule 5).
pub const MAX_SPURIOUS_DELETIONS_PER_SCAN: f64 = 1e-4;
/// σ_w / a_max (rule 2).
pub const MANOEUVRE_SIGMA_FRACTION: f64 = 0.5;
/// Largest confirmation window considered (rule 4).
pub const MAX_CONFIRMATION_WINDOW: u8 = 8;

/// g·tan 30° (m/s²): the lateral acceleration of a coordinated turn at 30°
/// of bank.
pub const BANK_30_ACCELERATION: f64 = 9.80665 * 0.577_350_269_189_625_8;

/// How accurate the sensor is.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SensorAccuracy {
    /// Independent noise of standard deviation `sigma` (m) on x and y.
    Cartesian {
        /// σ per axis (m).
        sigma: f64,
    },
    /// Range noise `range_sigma` (m) and azimuth noise `bearing_sigma` (rad)
    /// from a sensor at the origin.
    Polar {
        /// σ_R, range noise (m).
        range_sigma: f64,
        /// σ_B, azimuth noise (rad).
        bearing_sigma: f64,
    },
}

/// The region watched, centred on the sensor (at the origin).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Coverage {
    /// No region: measurements are used and tracks kept wherever they are.
    #[default]
    None,
    /// The square `-half_width ..= half_width` on x and y (m).
    Square {
        /// Half the side (m).
        half_width: f64,
    },
    /// The disc of radius `radius` (m).
    Disc {
        /// Radius (m).
        radius: f64,
    },
}

impl Coverage {
    /// Area (m²); `None` for no coverage.
    pub fn area(&self) -> Option<f64> {
        match *self {
            Coverage::None => None,
            Coverage::Square { half_width } => Some(4.0 * half_width * half_width),
            Coverage::Disc { radius } => Some(core::f64::consts::PI * radius * radius),
        }
    }

    /// The largest distance from the origin; `None` for no coverage.
    pub fn max_range(&self) -> Option<f64> {
        match *self {
            Coverage::None => None,
            Coverage::Square { half_width } => Some(core::f64::consts::SQRT_2 * half_width),
            Coverage::Disc { radius } => Some(radius),
        }
    }

    /// The bounding box as (min, max); `None` for no coverage.
    pub fn bounds(&self) -> Option<([f64; 2], [f64; 2])> {
        let half = match *self {
            Coverage::None => return None,
            Coverage::Square { half_width } => half_width,
            Coverage::Disc { radius } => radius,
        };
        Some(([-half, -half], [half, half]))
    }
}

/// What the default tracker is designed from (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TrackerDesign {
    /// The sensor's measurement noise.
    pub accuracy: SensorAccuracy,
    /// P_D, in (0, 1].
    pub detection_probability: f64,
    /// λ, false measurements per m² per scan, ≥ 0.
    pub clutter_density: f64,
    /// The region watched (default: none).
    pub coverage: Coverage,
    /// The sensor's largest range (m), > 0: with [`Coverage::None`] the
    /// rules count clutter over the disc of this radius and take it as the
    /// largest range; with a coverage, the coverage is used instead.
    pub max_range: f64,
    /// v_max (m/s), > 0.
    pub max_speed: f64,
    /// a_max (m/s²), > 0: the manoeuvre level.
    pub max_acceleration: f64,
    /// Nominal T (s), > 0.
    pub scan_period: f64,
}

/// The parameters [`TrackerDesign::derive`] chose, with the figures that
/// justify them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DerivedParameters {
    /// G, the gate threshold on the normalised squared innovation.
    pub gate_threshold: f64,
    /// P_G = 1 − e^(−G/2).
    pub gate_probability: f64,
    /// ½·a_max·T² is added by the gate; a_max itself.
    pub max_acceleration: f64,
    /// σ_w = a_max/2 (m/s²).
    pub manoeuvre_sigma: f64,
    /// Kalata's Λ = σ_w T²/σ for the Cartesian tracker (σ_max for a polar
    /// sensor, the σ its converted measurements are gated with).
    pub tracking_index: f64,
    /// α_K, the steady-state α for Λ.
    pub steady_state_alpha: f64,
    /// M2's n_max: first n with α̂(n) ≤ α_K.
    pub least_squares_n_max: u32,
    /// Q = σ_w² (m²/s⁴) for the polar filter.
    pub process_noise: f64,
    /// Largest per-axis measurement σ in the region (m).
    pub max_sigma: f64,
    /// √(2G)·σ_max (m), added to v_max·T for initiation.
    pub initiation_margin: f64,
    /// (M, N).
    pub confirmation: (u8, u8),
    /// Whether (M, N) meets both bounds of rule 4; if not, it is the best
    /// compromise the module docs describe.
    pub confirmation_meets_bounds: bool,
    /// Probability a true target is confirmed by (M, N).
    pub true_confirmation_probability: f64,
    /// Expected false starts per scan (F).
    pub false_starts_per_scan: f64,
    /// q: probability a false tentative track finds clutter in one gate.
    pub false_gate_hit_probability: f64,
    /// F × P(false track confirmed).
    pub false_confirmations_per_scan: f64,
    /// (confirmed K, tentative N − M + 1).
    pub deletion: (u8, u8),
    /// p_m^K·(1 − p_m) for the chosen K.
    pub spurious_deletions_per_scan: f64,
    /// Rule 7: the radius of the largest gate a confirmed track keeps, m
    /// (`None` without clutter).
    pub max_gate_radius: Option<f64>,
}

/// P(at least `need` successes in `trials` Bernoulli(p) trials).
fn at_least(need: u32, trials: u32, p: f64) -> f64 {
    if need == 0 {
        return 1.0;
    }
    if need > trials {
        return 0.0;
    }
    let mut total = 0.0;
    let mut binom = 1.0; // C(trials, k), built up from k = 0
    for k in 0..=trials {
        if k > 0 {
            // k ≤ trials here, so these never saturate.
            binom = binom * f64::from(trials.saturating_sub(k).saturating_add(1)) / f64::from(k);
        }
        if k >= need {
            total += binom
                * libm::pow(p, f64::from(k))
                * libm::pow(1.0 - p, f64::from(trials.saturating_sub(k)));
        }
    }
    total.min(1.0)
}

fn positive(v: f64) -> Result<f64, ConfigError> {
    if !v.is_finite() {
        Err(ConfigError::NotFinite)
    } else if v <= 0.0 {
        Err(ConfigError::OutOfRange)
    } else {
        Ok(v)
    }
}

/// A quantity of the tracker's number system (a length, a speed, ...).
fn scalar<Q: Quantity>(v: f64) -> Result<Q, ConfigError> {
    Q::try_from_f64(v).map_err(|_| ConfigError::NotFinite)
}

impl TrackerDesign {
    /// The simulated radar of the multi-target Cartesian scenarios as a sensor
    /// specification: σ = 20 m per axis, P_D = 0.9, λ = 10⁻⁷ m⁻² per scan
    /// (10 false measurements per scan over the 10 km × 10 km square
    /// centred on the origin), targets up to 300 m/s and
    /// [`BANK_30_ACCELERATION`], T = 1 s.
    pub const NOMINAL_RADAR: Self = TrackerDesign {
        accuracy: SensorAccuracy::Cartesian { sigma: 20.0 },
        detection_probability: 0.9,
        clutter_density: 1e-7,
        coverage: Coverage::Square { half_width: 5000.0 },
        // The square's corner.
        max_range: 5000.0 * core::f64::consts::SQRT_2,
        max_speed: 300.0,
        max_acceleration: BANK_30_ACCELERATION,
        scan_period: 1.0,
    };

    /// A TCAS II surveillance sensor as specified for the multi-target `tcas-30`
    /// scenario: σ_R = 50 ft (15.24 m), σ_B = 5° (0.0873 rad), P_D = 0.9,
    /// 3 false replies per scan over a 14 NM disc (λ = 1.42·10⁻⁹ m⁻²),
    /// closure up to 1200 kt (617.3 m/s, the TCAS II design envelope),
    /// [`BANK_30_ACCELERATION`], T = 1 s.
    pub const NOMINAL_TCAS: Self = TrackerDesign {
        accuracy: SensorAccuracy::Polar {
            range_sigma: 15.24,
            bearing_sigma: 0.087_266_462_599_716_48,
        },
        detection_probability: 0.9,
        // 3 / (π·25 928²)
        clutter_density: 3.0 / (core::f64::consts::PI * 25_928.0 * 25_928.0),
        coverage: Coverage::Disc { radius: 25_928.0 },
        max_range: 25_928.0,
        max_speed: 1200.0 * 1852.0 / 3600.0,
        max_acceleration: BANK_30_ACCELERATION,
        scan_period: 1.0,
    };

    /// The area the rules count clutter over (m²): the coverage's, or else
    /// the disc reaching `max_range` (module docs, inputs). The figures are
    /// not checked here ([`Self::derive`] checks them).
    pub fn clutter_area(&self) -> f64 {
        self.coverage
            .area()
            .unwrap_or(core::f64::consts::PI * self.max_range * self.max_range)
    }

    /// The parameters the rules of the module docs give.
    pub fn derive(&self) -> Result<DerivedParameters, ConfigError> {
        let pd = self.detection_probability;
        if !pd.is_finite() {
            return Err(ConfigError::NotFinite);
        }
        if !(pd > 0.0 && pd <= 1.0) {
            return Err(ConfigError::OutOfRange);
        }
        let clutter = self.clutter_density;
        if !clutter.is_finite() {
            return Err(ConfigError::NotFinite);
        }
        if clutter < 0.0 {
            return Err(ConfigError::OutOfRange);
        }
        let v_max = positive(self.max_speed)?;
        let a_max = positive(self.max_acceleration)?;
        let t = positive(self.scan_period)?;
        let max_range = positive(self.coverage.max_range().unwrap_or(self.max_range))?;
        let area = positive(self.clutter_area())?;
        let (sigma_axis, max_sigma, across_first) = match self.accuracy {
            SensorAccuracy::Cartesian { sigma } => {
                let s = positive(sigma)?;
                (s, s, s)
            }
            SensorAccuracy::Polar {
                range_sigma,
                bearing_sigma,
            } => {
                let sr = positive(range_sigma)?;
                let sc = positive(bearing_sigma)? * max_range;
                (sr, sr.max(sc), sc)
            }
        };

        // Rule 1.
        let miss = (1.0 - pd).max(1e-3);
        let gate_threshold = -2.0 * libm::log(GATE_LOSS_FRACTION * miss);
        let gate_probability = 1.0 - libm::exp(-gate_threshold / 2.0);

        // Rule 2.
        let manoeuvre_sigma = MANOEUVRE_SIGMA_FRACTION * a_max;
        // The Cartesian tracker of a polar sensor's converted measurements
        // assumes σ_max per axis (see `cartesian_config`).
        let index =
            tracking_index(manoeuvre_sigma, max_sigma, t).map_err(|_| ConfigError::OutOfRange)?;
        let steady_state_alpha = kalata_gains(index)
            .map_err(|_| ConfigError::OutOfRange)?
            .alpha();
        let mut n_max = 3u32;
        while n_max < LeastSquaresConfig::N_MAX_LIMIT
            && least_squares_alpha::<f64>(n_max) > steady_state_alpha
        {
            // Bounded by N_MAX_LIMIT.
            n_max = n_max.saturating_add(1);
        }
        let process_noise = manoeuvre_sigma * manoeuvre_sigma;

        // Rule 3.
        let allowance = 0.5 * a_max * t * t;
        let initiation_margin = libm::sqrt(2.0 * gate_threshold) * max_sigma;
        let init_radius = v_max * t + initiation_margin;
        let init_area = core::f64::consts::PI * init_radius * init_radius;

        // Rule 4. First gate after two points: predicted variance
        // 5σ² (+ Q·T⁴/4 for the polar filter, which has process noise).
        let extra = match self.accuracy {
            SensorAccuracy::Cartesian { .. } => 0.0,
            SensorAccuracy::Polar { .. } => process_noise * t * t * t * t / 4.0,
        };
        let half_axis = |s: f64| libm::sqrt(gate_threshold * (6.0 * s * s + extra)) + allowance;
        let gate_area = core::f64::consts::PI * half_axis(sigma_axis) * half_axis(across_first);
        let q = (clutter * gate_area).min(1.0);
        let clutter_per_scan = clutter * area;
        let false_starts = clutter_per_scan * (1.0 - libm::exp(-clutter * init_area));
        let p_hit = pd * gate_probability;
        // The first rule meeting both bounds, in the order of the module
        // docs; else the best compromise (rule 4's last paragraph): a key
        // that orders the rules meeting the false-track bound first, by
        // their true confirmation, then the others by their false
        // confirmations.
        let mut chosen = None;
        let mut compromise: Option<((u8, u8), f64, f64)> = None;
        let better = |a: (f64, f64), b: (f64, f64)| {
            let within = |p_false: f64| p_false <= MAX_FALSE_CONFIRMATIONS_PER_SCAN;
            match (within(a.1), within(b.1)) {
                (true, false) => true,
                (false, true) => false,
                (true, true) => a.0 > b.0,
                (false, false) => a.1 < b.1 || (a.1 == b.1 && a.0 > b.0),
            }
        };
        'search: for m in 2..=MAX_CONFIRMATION_WINDOW {
            for n in m..=MAX_CONFIRMATION_WINDOW {
                // m ≥ 2 and n ≥ m: no saturation.
                let need = u32::from(m.saturating_sub(1));
                let trials = u32::from(n.saturating_sub(1));
                let p_true = at_least(need, trials, p_hit);
                let p_false = false_starts * at_least(need, trials, q);
                if p_true >= MIN_TRUE_CONFIRMATION && p_false <= MAX_FALSE_CONFIRMATIONS_PER_SCAN {
                    chosen = Some(((m, n), p_true, p_false));
                    break 'search;
                }
                if compromise.is_none_or(|(_, t, f)| better((p_true, p_false), (t, f))) {
                    compromise = Some(((m, n), p_true, p_false));
                }
            }
        }
        let confirmation_meets_bounds = chosen.is_some();
        let (confirmation, true_confirmation_probability, false_confirmations_per_scan) =
            chosen.or(compromise).ok_or(ConfigError::Confirmation)?;

        // Rule 5.
        let p_miss = 1.0 - p_hit;
        let mut k = 1u8;
        let run = |k: u8| libm::pow(p_miss, f64::from(k)) * (1.0 - p_miss);
        while run(k) > MAX_SPURIOUS_DELETIONS_PER_SCAN {
            if k == u8::MAX {
                return Err(ConfigError::Deletion);
            }
            // k < u8::MAX here.
            k = k.saturating_add(1);
        }
        // N ≥ M ≥ 2: N − M + 1 is in 1..=7.
        let deletion = (
            k,
            confirmation
                .1
                .saturating_sub(confirmation.0)
                .saturating_add(1),
        );

        // Rule 7.
        let max_gate_radius =
            (clutter > 0.0).then(|| libm::sqrt(p_hit / (core::f64::consts::PI * clutter)));

        Ok(DerivedParameters {
            gate_threshold,
            gate_probability,
            max_acceleration: a_max,
            manoeuvre_sigma,
            tracking_index: index,
            steady_state_alpha,
            least_squares_n_max: n_max,
            process_noise,
            max_sigma,
            initiation_margin,
            confirmation,
            confirmation_meets_bounds,
            true_confirmation_probability,
            false_starts_per_scan: false_starts,
            false_gate_hit_probability: q,
            false_confirmations_per_scan,
            deletion,
            spurious_deletions_per_scan: run(k),
            max_gate_radius,
        })
    }

    /// The lifecycle part shared by every filter: gate, initiation,
    /// confirmation, deletion, volume.
    fn config_with<S: Numeric, P: Copy>(
        &self,
        params: P,
        measurement_sigma: f64,
        d: &DerivedParameters,
    ) -> Result<TrackerConfig<S, P>, ConfigError> {
        let gate = Gate::uncertainty(
            scalar(measurement_sigma)?,
            scalar(d.gate_threshold)?,
            scalar(d.max_acceleration)?,
        )?;
        let mut config = TrackerConfig::new(params, gate, scalar(self.max_speed)?)?
            .with_initiation_margin(scalar(d.initiation_margin)?)?
            .with_confirmation(d.confirmation.0, d.confirmation.1)?
            .with_deletion(d.deletion.0, d.deletion.1)?;
        // A radius beyond the number format: no gate reaches it.
        if let Some(radius) = d.max_gate_radius.and_then(|r| scalar::<S::Length>(r).ok()) {
            config = config.with_max_gate_radius(radius)?;
        }
        match self.coverage.bounds() {
            None => Ok(config),
            Some((min, max)) => Ok(config.with_volume(Volume::new(
                [scalar(min[0])?, scalar(min[1])?],
                [scalar(max[0])?, scalar(max[1])?],
            )?)),
        }
    }

    /// The designed gate, initiation, lifecycle and volume around filter
    /// parameters of the caller's choice (e.g. fixed gains or another
    /// schedule): the uncertainty gate for σ_max (rule 3), so a Cartesian
    /// filter of either sensor.
    pub fn tracker_config<S: Numeric, P: Copy>(
        &self,
        params: P,
    ) -> Result<TrackerConfig<S, P>, ConfigError> {
        let d = self.derive()?;
        self.config_with(params, d.max_sigma, &d)
    }

    /// The default Cartesian tracker: [`AutoFilter`] (`auto` fused with its filter), the
    /// per-axis Kalman gains configured from the sensor's σ (σ_max for a
    /// polar sensor; `docs/auto.md`), whose covariance sizes the
    /// uncertainty gate with
    /// the sensor's σ (for a polar sensor, σ_max: the conversion to x, y is
    /// then covered everywhere, at the cost of gates as wide across range as
    /// at the edge of the region), and the lifecycle of the module docs.
    pub fn cartesian_config<S: Numeric>(
        &self,
    ) -> Result<TrackerConfig<S, AutoGains<S, 2>>, ConfigError> {
        let d = self.derive()?;
        let schedule = AutoGains::new(&AutoConfig::cartesian(d.max_sigma))
            .map_err(|_| ConfigError::OutOfRange)?;
        self.config_with(schedule, d.max_sigma, &d)
    }

    /// The default polar tracker: [`RangeAzimuthTrack`] with the sensor's
    /// σ_R², σ_B² and Q = σ_w² (rule 2), gated by the range/azimuth window,
    /// and the lifecycle of the module docs. A Cartesian sensor is treated
    /// as σ_R = σ and σ_B = σ/R_max (its cross-range error is at least that
    /// everywhere in the region).
    pub fn polar_config<S: Scalar>(
        &self,
    ) -> Result<TrackerConfig<S, RangeAzimuthNoise<S>>, ConfigError> {
        let d = self.derive()?;
        let (range_sigma, bearing_sigma) = match self.accuracy {
            SensorAccuracy::Polar {
                range_sigma,
                bearing_sigma,
            } => (range_sigma, bearing_sigma),
            SensorAccuracy::Cartesian { sigma } => (
                sigma,
                sigma / positive(self.coverage.max_range().unwrap_or(self.max_range))?,
            ),
        };
        // v_max bounds the filter's initiation and velocity, so bearing
        // noise never gives a track a speed no target has
        // (`filter::range_azimuth`, "Initiation under bearing noise").
        let noise = RangeAzimuthNoise::new_f64(
            range_sigma * range_sigma,
            bearing_sigma * bearing_sigma,
            d.process_noise,
        )
        .and_then(|n| n.with_speed_bound_f64(self.max_speed))
        .map_err(|_| ConfigError::OutOfRange)?;
        self.config_with(noise, range_sigma, &d)
    }
}

/// [`TrackerDesign::NOMINAL_RADAR`]'s Cartesian tracker (see the module
/// docs): the configuration `replay --tracker` uses for `t,x,y` input.
pub fn default_cartesian<S: Numeric>() -> Result<TrackerConfig<S, AutoGains<S, 2>>, ConfigError> {
    TrackerDesign::NOMINAL_RADAR.cartesian_config()
}

/// [`TrackerDesign::NOMINAL_TCAS`]'s range–azimuth tracker (see the module
/// docs): the configuration `replay --tracker` uses for `t,range,azimuth`
/// input.
pub fn default_polar<S: Scalar>() -> Result<TrackerConfig<S, RangeAzimuthNoise<S>>, ConfigError> {
    TrackerDesign::NOMINAL_TCAS.polar_config()
}

/// The table types the defaults are meant for.
pub type DefaultCartesianTrack<S> = AutoFilter<S, 2>;
/// See [`DefaultCartesianTrack`].
pub type DefaultPolarTrack<S> = RangeAzimuthTrack<S>;
