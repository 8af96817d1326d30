//! Real aircraft: the filters on recorded ADS-B flights and the track table
//! on a recorded multi-target scene (OpenSky Network data from the
//! `traffic` 2.13 samples, `host-tests/data/real/`, whose README says what
//! the files hold and how the truth was made).
//!
//! * Single segments: measurements are the truth plus N(0, σ²) per axis
//!   (σ = [`SIGMA_M`], seeds [`SEEDS`]) at the real report times, and on a
//!   [`GRID_PERIOD_S`] grid (the truth interpolated linearly, points inside
//!   a report gap over [`GRID_MAX_GAP_S`] left out: nothing is known of the
//!   flight there). Every method runs the same noise: raw measurements,
//!   every schedule of `replay --filter ab --schedule SPEC --sigma-m σ
//!   --scan-period-s T` (the same code: [`crate::replay::replay_reader`]; T the
//!   stream's median interval) and a constant-velocity Kalman filter whose
//!   one white-acceleration density q (m²/s³, from [`KALMAN_Q_GRID`]) is the
//!   one with the least median per-segment RMSE over the whole set. A
//!   segment's figure is the mean over the seeds of the run's position RMSE
//!   √(mean of e_x² + e_y²) over every report. A stream the filter refuses
//!   is counted as refused with the reason, not dropped.
//! * Scene: `replay --tracker` ([`crate::replay_tracker`]) with the sensor's
//!   figures, in f64, f32 and the fast fixed point, scored by
//!   [`crate::metrics::track_metrics_with`] (assignment on the distance,
//!   pairs beyond [`PAIR_LIMIT_M`] dropped) and OSPA ([`OSPA_CUTOFF_M`], order 2) averaged over the scans;
//!   the whole replay (read, track, write the CSV) is timed in-process,
//!   into a file of its own (`scene_times.md`), so that the accuracy
//!   tables are the same on every run.
//! * The scene drawn again ([`super::scene_draws`]): its truth measured
//!   with new seeds, also at the held-out scene's clutter density.
//!
//! Regenerate with `cd host-tests && cargo run --release --bin experiments
//! -- --only real-adsb`.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use abtrack::gain::spec::{ScheduleSpec, SensorScale};
use abtrack::track::defaults::BANK_30_ACCELERATION;
use serde::Deserialize;

use super::common::{plot, write_file, Context, PlotSpec, Series, Table};
use super::scene_draws;
use crate::kalman::{isotropic, ConstantVelocityKf, ProcessNoise};
use crate::metrics::{
    common_rmse, mean_ospa, track_metrics_with, PairedPoint, PairingCost, ScanReport, TrackPoint,
    TrackStatus, TruthPoint,
};
use crate::noise::{derive_seed, rng_from_seed, standard_normal};
use crate::replay::{self, FilterKind, Numeric, Order, ReplayConfig};
use crate::replay_tracker::{replay_tracker_reader, SensorOptions, TrackerOptions};

pub const NAME: &str = "real-adsb";
pub const ABOUT: &str =
    "real ADS-B (OpenSky): filters on 16 flights at real and 4 s timing, tracker on the Paris scene";

/// Measurement σ per axis, m.
pub const SIGMA_M: f64 = 50.0;
/// Noise seeds of the single segments.
pub const SEEDS: [u64; 3] = [1, 2, 3];
/// The scan grid's period, s.
pub const GRID_PERIOD_S: f64 = 4.0;
/// Grid points inside a report gap longer than this (s) are left out.
pub const GRID_MAX_GAP_S: f64 = 20.0;
/// The Kalman filter's candidate white-acceleration densities, m²/s³.
pub const KALMAN_Q_GRID: [f64; 10] = [1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0];
/// Truth–track pairs farther apart are dropped, m.
pub const PAIR_LIMIT_M: f64 = 500.0;
/// OSPA cut-off c, m (order p = 2).
pub const OSPA_CUTOFF_M: f64 = 1000.0;
const OSPA_ORDER: f64 = 2.0;
/// Whole-replay timings: the least of this many runs.
const TIMING_REPEATS: usize = 3;

/// The schedules run on every segment, as `replay --schedule` takes them
/// (scaled to σ and T as `--sigma-m` does); the first is the fixed αβ.
pub const SCHEDULES: [&str; 13] = [
    "fixed:alpha=0.5,beta=0.2",
    "m1",
    "least-squares",
    "m3",
    "m4",
    "bank",
    "li-improved",
    "liu-count-adjusted",
    "liu-fixed",
    "liu-residual",
    "liu-adaptive",
    "tcas-firmness",
    "auto:sigma=50",
];
/// The schedule compared with the Kalman filter in the summary.
pub const AUTO: &str = "auto:sigma=50";
/// The sensors' σ per axis (m) of the table that runs `auto` and the
/// one-q Kalman filter at other accuracies than [`SIGMA_M`] (beside it).
pub const SIGMA_SWEEP_M: [f64; 4] = [20.0, SIGMA_M, 100.0, 150.0];

/// `auto` configured from the sensor's σ (m), as `--schedule` takes it.
pub fn auto_spec(sigma: f64) -> String {
    format!("auto:sigma={sigma}")
}

/// `auto` against the one-q Kalman filter (q the best for the set at that
/// σ) and raw, over one timing's segments at one σ.
#[derive(Debug, Clone)]
pub struct SigmaRow {
    pub sigma: f64,
    pub timing: Timing,
    /// The Kalman filter's q, m²/s³, then the median per-segment RMSE of
    /// the Kalman filter, of `auto` and of raw over the segments `auto` ran.
    pub kalman_q: f64,
    pub kalman: f64,
    pub auto: f64,
    pub raw: f64,
    pub refused: usize,
    pub worse_than_raw: usize,
    pub over_102_raw: usize,
    /// Segments where the Kalman filter is more than 2 % worse than raw.
    pub kalman_over_102_raw: usize,
    /// The segment where `auto` is worst against raw, and that ratio.
    pub worst_against_raw: (String, f64),
    /// The segment where `auto` is worst against the Kalman filter, and
    /// that ratio.
    pub worst_against_kalman: (String, f64),
}

/// [`SigmaRow`] of `segments` at `timing`, measured with σ = `sigma` over
/// `seeds`.
pub fn sigma_row(
    segments: &[Segment],
    timing: Timing,
    seeds: &[u64],
    sigma: f64,
) -> Result<SigmaRow, String> {
    let spec = auto_spec(sigma);
    let results = segments
        .iter()
        .map(|s| evaluate_segment(s, timing, seeds, &[spec.as_str()], sigma))
        .collect::<Result<Vec<_>, _>>()?;
    let refs: Vec<&SegmentResult> = results.iter().collect();
    Ok(sigma_row_of(&refs, &spec, sigma, timing))
}

/// [`SigmaRow`] of `results` (one timing's, measured with σ = `sigma`,
/// which ran `spec`, `auto` configured from that σ); the medians over the
/// segments every schedule of `results` ran.
pub fn sigma_row_of(
    results: &[&SegmentResult],
    spec: &str,
    sigma: f64,
    timing: Timing,
) -> SigmaRow {
    let (kq, _) = best_kalman_q(results);
    let rows = summarise(results, &[spec], kq);
    let auto = &rows[2];
    let worst = |of: &dyn Fn(&SegmentResult) -> f64| {
        results
            .iter()
            .filter_map(|r| {
                let a = r.schedule(spec).and_then(Figure::rmse)?;
                Some((r.segment.clone(), a / of(r)))
            })
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or_default()
    };
    SigmaRow {
        sigma,
        timing,
        kalman_q: KALMAN_Q_GRID[kq],
        kalman: rows[1].median_common,
        auto: auto.median_common,
        raw: rows[0].median_common,
        refused: auto.refused,
        worse_than_raw: auto.worse_than_raw,
        over_102_raw: auto.over_102_raw,
        kalman_over_102_raw: rows[1].over_102_raw,
        worst_against_raw: worst(&|r| r.raw),
        worst_against_kalman: worst(&|r| r.kalman[kq]),
    }
}

/// `host-tests/data/real`.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/real")
}

// ---------------------------------------------------------------------------
// Single segments
// ---------------------------------------------------------------------------

/// One recorded single-aircraft segment: the truth at the report times.
#[derive(Debug, Clone)]
pub struct Segment {
    pub name: String,
    pub points: Vec<(f64, [f64; 2])>,
}

#[derive(Deserialize)]
struct PositionRow {
    t: f64,
    x: f64,
    y: f64,
}

fn read_csv<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<Vec<T>, String> {
    let mut reader =
        csv::Reader::from_path(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    reader
        .deserialize()
        .collect::<Result<Vec<T>, _>>()
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Every `single/*.csv` of `dir`, by name.
pub fn read_segments(dir: &Path) -> Result<Vec<Segment>, String> {
    let single = dir.join("single");
    let mut paths: Vec<PathBuf> = fs::read_dir(&single)
        .map_err(|e| format!("cannot list {}: {e}", single.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| {
            let rows: Vec<PositionRow> = read_csv(p)?;
            Ok(Segment {
                name: p
                    .file_stem()
                    .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
                points: rows.iter().map(|r| (r.t, [r.x, r.y])).collect(),
            })
        })
        .collect()
}

/// When the measurements are taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Timing {
    /// At the real report times.
    Real,
    /// Every [`GRID_PERIOD_S`].
    Grid,
}

impl Timing {
    pub const ALL: [Timing; 2] = [Timing::Real, Timing::Grid];

    pub fn label(self) -> &'static str {
        match self {
            Timing::Real => "real report times",
            Timing::Grid => "4 s scans",
        }
    }

    pub fn short(self) -> &'static str {
        match self {
            Timing::Real => "real",
            Timing::Grid => "4s",
        }
    }
}

/// The truth at the times the measurements of `timing` are taken.
pub fn truth_for(segment: &Segment, timing: Timing) -> Vec<(f64, [f64; 2])> {
    match timing {
        Timing::Real => segment.points.clone(),
        Timing::Grid => {
            let pts = &segment.points;
            let end = pts.last().map_or(0.0, |p| p.0);
            let mut out = Vec::new();
            let mut i = 0;
            let mut k = 0u32;
            loop {
                let t = f64::from(k) * GRID_PERIOD_S;
                if t > end {
                    break;
                }
                k += 1;
                while i + 1 < pts.len() && pts[i + 1].0 < t {
                    i += 1;
                }
                let (a, b) = (pts[i], pts[(i + 1).min(pts.len() - 1)]);
                if t == a.0 {
                    out.push(a);
                    continue;
                }
                if t == b.0 {
                    out.push(b);
                    continue;
                }
                if b.0 - a.0 > GRID_MAX_GAP_S || b.0 <= a.0 {
                    continue;
                }
                let w = (t - a.0) / (b.0 - a.0);
                out.push((
                    t,
                    [
                        a.1[0] + w * (b.1[0] - a.1[0]),
                        a.1[1] + w * (b.1[1] - a.1[1]),
                    ],
                ));
            }
            out
        }
    }
}

/// The noise stream of one segment, timing and seed: independent of the
/// other segments and of the order they are listed in.
fn noise_stream(name: &str, timing: Timing, seed: u64) -> u64 {
    // FNV-1a of the name and timing.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes().chain(timing.short().bytes()) {
        h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
    }
    derive_seed(seed, h)
}

/// The truth plus N(0, σ²) per axis (x then y at each point), σ =
/// `sigma` m: the same draws scaled, whatever σ.
pub fn measure(truth: &[(f64, [f64; 2])], stream: u64, sigma: f64) -> Vec<(f64, [f64; 2])> {
    let mut rng = rng_from_seed(stream);
    truth
        .iter()
        .map(|&(t, p)| {
            let ex = sigma * standard_normal(&mut rng);
            let ey = sigma * standard_normal(&mut rng);
            (t, [p[0] + ex, p[1] + ey])
        })
        .collect()
}

/// The median interval of a stream, s.
pub fn median_interval(stream: &[(f64, [f64; 2])]) -> f64 {
    let times: Vec<f64> = stream.iter().map(|p| p.0).collect();
    crate::replay_tracker::median_scan_interval(&times).unwrap_or(1.0)
}

/// The longest interval of a stream, s.
pub fn max_interval(stream: &[(f64, [f64; 2])]) -> f64 {
    stream
        .windows(2)
        .map(|w| w[1].0 - w[0].0)
        .fold(0.0, f64::max)
}

/// What a method gave on one stream.
#[derive(Debug, Clone, PartialEq)]
pub enum Estimates {
    Positions(Vec<[f64; 2]>),
    /// The filter refused the stream: the reason.
    Refused(String),
}

/// `replay --filter ab --schedule text --sigma-m sigma --scan-period-s T`
/// on the stream written as a `t,x,y` file (T its median interval): the
/// estimates, or what replay refused (the file or a row).
pub fn run_schedule(
    text: &str,
    stream: &[(f64, [f64; 2])],
    sigma: f64,
) -> Result<Estimates, String> {
    let scale = SensorScale {
        sigma,
        period: median_interval(stream),
        max_acceleration: BANK_30_ACCELERATION,
    };
    let spec = ScheduleSpec::parse_scaled(text, &scale).map_err(|e| format!("{text}: {e}"))?;
    let filter = match spec {
        ScheduleSpec::Bank(c) => FilterKind::Bank(c),
        spec => FilterKind::Scheduled {
            order: Order::AlphaBeta,
            spec,
        },
    };
    let mut input = String::from("t,x,y\n");
    for &(t, z) in stream {
        let _ = writeln!(input, "{t},{},{}", z[0], z[1]);
    }
    let config = ReplayConfig {
        filter,
        numeric: Numeric::F64,
    };
    match replay::replay_reader(&config, input.as_bytes()) {
        Err(e) => Ok(Estimates::Refused(e.to_string())),
        Ok(csv) => {
            let mut reader = csv::Reader::from_reader(csv.as_bytes());
            let positions: Vec<[f64; 2]> = reader
                .deserialize::<PositionRow>()
                .map(|r| r.map(|r| [r.x, r.y]))
                .collect::<Result<_, _>>()
                .map_err(|e| format!("{text}: replay output: {e}"))?;
            if positions.len() != stream.len() {
                return Err(format!(
                    "{text}: replay wrote {} rows for {} measurements",
                    positions.len(),
                    stream.len()
                ));
            }
            Ok(Estimates::Positions(positions))
        }
    }
}

/// The constant-velocity Kalman filter (white acceleration of density q,
/// R = σ²I with σ = `sigma` m, two-point start as the αβ filters) on the
/// stream.
pub fn run_kalman(q: f64, stream: &[(f64, [f64; 2])], sigma: f64) -> Result<Vec<[f64; 2]>, String> {
    let noise = ProcessNoise::ContinuousWhiteAcceleration {
        spectral_density: q,
    };
    let mut kf = ConstantVelocityKf::new(noise, isotropic(sigma)).map_err(|e| e.to_string())?;
    let mut previous: Option<f64> = None;
    stream
        .iter()
        .map(|&(t, z)| {
            let dt = previous.map_or(1.0, |p| t - p);
            previous = Some(t);
            kf.update(z, dt).map_err(|e| format!("Kalman q {q}: {e}"))?;
            Ok(kf.position())
        })
        .collect()
}

/// √(mean ‖estimate − truth‖²).
pub fn position_rmse(estimates: &[[f64; 2]], truth: &[(f64, [f64; 2])]) -> f64 {
    let sum: f64 = estimates
        .iter()
        .zip(truth)
        .map(|(e, (_, p))| (e[0] - p[0]).powi(2) + (e[1] - p[1]).powi(2))
        .sum();
    (sum / truth.len() as f64).sqrt()
}

/// One method's figure on one segment: the mean RMSE over the seeds, or
/// the refusal.
#[derive(Debug, Clone, PartialEq)]
pub enum Figure {
    Rmse(f64),
    Refused(String),
}

impl Figure {
    pub fn rmse(&self) -> Option<f64> {
        match self {
            Figure::Rmse(v) => Some(*v),
            Figure::Refused(_) => None,
        }
    }
}

/// Every method on one segment at one timing.
#[derive(Debug, Clone)]
pub struct SegmentResult {
    pub segment: String,
    pub timing: Timing,
    pub points: usize,
    pub max_interval_s: f64,
    pub raw: f64,
    /// By schedule spec, in [`SCHEDULES`] order.
    pub schedules: Vec<(String, Figure)>,
    /// Per q of [`KALMAN_Q_GRID`].
    pub kalman: Vec<f64>,
}

impl SegmentResult {
    pub fn schedule(&self, spec: &str) -> Option<&Figure> {
        self.schedules
            .iter()
            .find(|(s, _)| s == spec)
            .map(|(_, f)| f)
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// Runs every method on `segment` at `timing` over `seeds`, for the
/// schedules `specs`, the measurements' σ per axis `sigma` m.
pub fn evaluate_segment(
    segment: &Segment,
    timing: Timing,
    seeds: &[u64],
    specs: &[&str],
    sigma: f64,
) -> Result<SegmentResult, String> {
    let truth = truth_for(segment, timing);
    let mut raw = Vec::new();
    let mut per_spec: Vec<Vec<Estimates>> = vec![Vec::new(); specs.len()];
    let mut kalman: Vec<Vec<f64>> = vec![Vec::new(); KALMAN_Q_GRID.len()];
    for &seed in seeds {
        let stream = measure(&truth, noise_stream(&segment.name, timing, seed), sigma);
        let z: Vec<[f64; 2]> = stream.iter().map(|p| p.1).collect();
        raw.push(position_rmse(&z, &truth));
        for (i, spec) in specs.iter().enumerate() {
            per_spec[i].push(run_schedule(spec, &stream, sigma)?);
        }
        for (i, &q) in KALMAN_Q_GRID.iter().enumerate() {
            kalman[i].push(position_rmse(&run_kalman(q, &stream, sigma)?, &truth));
        }
    }
    let schedules = specs
        .iter()
        .zip(per_spec)
        .map(|(spec, runs)| {
            let mut rmses = Vec::new();
            for run in &runs {
                match run {
                    Estimates::Positions(p) => rmses.push(position_rmse(p, &truth)),
                    Estimates::Refused(why) => {
                        return (spec.to_string(), Figure::Refused(why.clone()))
                    }
                }
            }
            (spec.to_string(), Figure::Rmse(mean(&rmses)))
        })
        .collect();
    Ok(SegmentResult {
        segment: segment.name.clone(),
        timing,
        points: truth.len(),
        max_interval_s: max_interval(&truth),
        raw: mean(&raw),
        schedules,
        kalman: kalman.iter().map(|r| mean(r)).collect(),
    })
}

/// The median of `v` (NaN if empty).
pub fn median(v: &[f64]) -> f64 {
    let mut s: Vec<f64> = v.to_vec();
    s.sort_by(f64::total_cmp);
    match s.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => s[n / 2],
        n => 0.5 * (s[n / 2 - 1] + s[n / 2]),
    }
}

/// The index in [`KALMAN_Q_GRID`] of the q with the least median
/// per-segment RMSE over `results` (one timing), and that median.
pub fn best_kalman_q(results: &[&SegmentResult]) -> (usize, f64) {
    (0..KALMAN_Q_GRID.len())
        .map(|i| {
            (
                i,
                median(&results.iter().map(|r| r.kalman[i]).collect::<Vec<_>>()),
            )
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, f64::NAN))
}

/// One method's figures over a timing's segments.
#[derive(Debug, Clone)]
pub struct MethodSummary {
    pub method: String,
    /// Median per-segment RMSE over the segments it ran.
    pub median: f64,
    pub ran: usize,
    pub refused: usize,
    /// Median over the segments every method ran.
    pub median_common: f64,
    /// Segments where it is worse than raw, and more than 2 % worse.
    pub worse_than_raw: usize,
    pub over_102_raw: usize,
}

/// The per-method summary of one timing's results, with the Kalman filter
/// at q index `kq`.
pub fn summarise(results: &[&SegmentResult], specs: &[&str], kq: usize) -> Vec<MethodSummary> {
    let common: Vec<&&SegmentResult> = results
        .iter()
        .filter(|r| r.schedules.iter().all(|(_, f)| f.rmse().is_some()))
        .collect();
    let summary = |method: String, of: &dyn Fn(&SegmentResult) -> Option<f64>| {
        let ran: Vec<(f64, f64)> = results
            .iter()
            .filter_map(|r| of(r).map(|v| (v, r.raw)))
            .collect();
        let values: Vec<f64> = ran.iter().map(|p| p.0).collect();
        let common_values: Vec<f64> = common.iter().filter_map(|r| of(r)).collect();
        MethodSummary {
            method,
            median: median(&values),
            ran: ran.len(),
            refused: results.len() - ran.len(),
            median_common: median(&common_values),
            worse_than_raw: ran.iter().filter(|(v, raw)| v > raw).count(),
            over_102_raw: ran.iter().filter(|(v, raw)| *v > 1.02 * raw).count(),
        }
    };
    let mut out = vec![summary("raw".into(), &|r| Some(r.raw))];
    out.push(summary(
        format!("Kalman CV, q = {} m²/s³", KALMAN_Q_GRID[kq]),
        &|r| Some(r.kalman[kq]),
    ));
    for spec in specs {
        out.push(summary(spec.to_string(), &|r| {
            r.schedule(spec).and_then(Figure::rmse)
        }));
    }
    out
}

// ---------------------------------------------------------------------------
// Scene
// ---------------------------------------------------------------------------

/// The scene's truth as one sensor measures it: its detection, clutter,
/// σ and scan period, which also configure the tracker.
#[derive(Debug, Clone, Copy)]
pub struct Scene {
    pub name: &'static str,
    pub detection_probability: f64,
    pub clutter_per_km2: f64,
    /// The measurement σ per axis, m.
    pub sigma_m: f64,
    /// The scan period, ms: a multiple of the truth's period
    /// ([`SCENE_PERIOD_MS`]), whose points at the scans are scored.
    pub scan_period_ms: i64,
}

/// The dev scene in its two difficulties.
pub const SCENES: [Scene; 2] = [
    Scene {
        name: "paris_1400",
        detection_probability: 0.9,
        clutter_per_km2: 0.002,
        sigma_m: SIGMA_M,
        scan_period_ms: SCENE_PERIOD_MS,
    },
    Scene {
        name: "paris_1400_hard",
        detection_probability: 0.7,
        clutter_per_km2: 0.006,
        sigma_m: SIGMA_M,
        scan_period_ms: SCENE_PERIOD_MS,
    },
];

impl Scene {
    /// `replay --tracker --region-m 50000 --sigma-m σ --scan-period-s T
    /// --pd P --clutter-per-km2 C [--schedule SPEC] --numeric N`.
    pub fn options(&self, numeric: Numeric, schedule: Option<ScheduleSpec>) -> TrackerOptions {
        TrackerOptions {
            numeric,
            schedule,
            sensor: SensorOptions {
                region_m: Some(SCENE_HALF_WIDTH_M),
                sigma_m: Some(self.sigma_m),
                scan_period_s: Some(self.scan_period_ms as f64 / 1000.0),
                detection_probability: Some(self.detection_probability),
                clutter_per_km2: Some(self.clutter_per_km2),
                ..SensorOptions::default()
            },
            ..TrackerOptions::default()
        }
    }
}

#[derive(Deserialize)]
struct SceneTruthRow {
    t: f64,
    flight: String,
    x: f64,
    y: f64,
}

#[derive(Deserialize)]
struct TrackRow {
    t: f64,
    track_id: u32,
    status: String,
    x: f64,
    y: f64,
}

/// The truth's period and the dev sensor's scan period, ms.
pub const SCENE_PERIOD_MS: i64 = 4000;
/// Half the side of the scene's square (centred on the origin), m.
pub const SCENE_HALF_WIDTH_M: f64 = 50_000.0;

/// A time as integer milliseconds (the scans' common key).
fn ms(t: f64) -> i64 {
    (t * 1000.0).round() as i64
}

/// The scene's truth per scan time, ms: the file's times are the scans
/// (flights numbered by first appearance).
pub fn read_scene_truth(
    dir: &Path,
    scene: &Scene,
) -> Result<BTreeMap<i64, Vec<TruthPoint>>, String> {
    let rows: Vec<SceneTruthRow> = read_csv(&dir.join(format!("scene/{}.truth.csv", scene.name)))?;
    let mut ids: BTreeMap<String, u32> = BTreeMap::new();
    let mut by_time: BTreeMap<i64, Vec<TruthPoint>> = BTreeMap::new();
    for r in rows {
        let next = ids.len() as u32 + 1;
        let id = *ids.entry(r.flight).or_insert(next);
        by_time
            .entry(ms(r.t))
            .or_default()
            .push(TruthPoint { id, x: r.x, y: r.y });
    }
    Ok(by_time)
}

/// One tracker run on one scene.
#[derive(Debug, Clone)]
pub struct SceneRun {
    pub label: String,
    pub coverage: f64,
    pub continuity: f64,
    pub id_changes: usize,
    pub rmse: f64,
    pub ospa: f64,
    /// Tracks paired in under half of their reported scans.
    pub false_tracks: usize,
    /// Reported tracks never paired.
    pub never_paired: usize,
    pub reported_tracks: usize,
    /// Truth points not paired before their flight's first pairing (the
    /// track's start and confirmation) and after it (losses).
    pub unpaired_before_first: usize,
    pub unpaired_after_first: usize,
    /// The least whole-replay time of `TIMING_REPEATS` runs, s.
    pub seconds: f64,
    /// The design `replay --tracker` printed.
    pub design: String,
    pub scans: Vec<ScanReport>,
    /// Every paired (scan, flight) point with its distance.
    pub pairs: Vec<PairedPoint>,
}

/// `replay --tracker` with `options` on the scene, scored against `truth`.
pub fn run_scene(
    dir: &Path,
    scene: &Scene,
    truth: &BTreeMap<i64, Vec<TruthPoint>>,
    options: &TrackerOptions,
    label: &str,
) -> Result<SceneRun, String> {
    let path = dir.join(format!("scene/{}.meas.csv", scene.name));
    let mut best = f64::INFINITY;
    let mut output = None;
    for _ in 0..TIMING_REPEATS {
        let start = Instant::now();
        let bytes = fs::read(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let run = replay_tracker_reader(options, bytes.as_slice())
            .map_err(|e| format!("{} {label}: {e}", scene.name))?;
        best = best.min(start.elapsed().as_secs_f64());
        output = Some(run);
    }
    let Some(run) = output else {
        return Err("no run".into());
    };
    score_tracks(
        label,
        &format!("replay --tracker output on {}", path.display()),
        &run.csv,
        truth,
        best,
        run.design.to_string(),
    )
    .map_err(|e| format!("{}: {e}", scene.name))
}

/// How far (ms) the time of a tracker output's row may be from the truth's
/// scan it is scored at.
pub const SCAN_TIME_TOLERANCE_MS: i64 = 1;

/// Scores a tracker's output in `replay --tracker`'s layout (`t,track_id,
/// status,x,y`, other columns ignored) against `truth`: the truth's points
/// of every scan, keyed by the scan's time in ms (a scan without a target
/// is a key with no points). The scans are the truth's times; each row of
/// the output joins the scan within [`SCAN_TIME_TOLERANCE_MS`] of its `t`,
/// and a row with none is refused with its line, as is a row that cannot
/// be read or whose `t`, `x` or `y` is not finite. `source` names where the
/// output came from (a file's path) in the errors; `label`, `seconds` and
/// `design` are carried into the result.
pub fn score_tracks(
    label: &str,
    source: &str,
    csv_text: &str,
    truth: &BTreeMap<i64, Vec<TruthPoint>>,
    seconds: f64,
    design: String,
) -> Result<SceneRun, String> {
    let mut tracks: BTreeMap<i64, Vec<TrackPoint>> = BTreeMap::new();
    let mut reader = csv::Reader::from_reader(csv_text.as_bytes());
    let headers = reader
        .headers()
        .map_err(|e| format!("{source}: {e}"))?
        .clone();
    for record in reader.records() {
        let record = record.map_err(|e| format!("{source}: {e}"))?;
        let line = record.position().map_or(0, csv::Position::line);
        let refused = |why: String| format!("{source}, line {line}: {why}");
        let r: TrackRow = record
            .deserialize(Some(&headers))
            .map_err(|e| refused(e.to_string()))?;
        for (column, v) in [("t", r.t), ("x", r.x), ("y", r.y)] {
            if !v.is_finite() {
                return Err(refused(format!("{column} = {v} is not a finite number")));
            }
        }
        let status: TrackStatus = r.status.parse().map_err(refused)?;
        let t = ms(r.t);
        let scan = truth
            .range(
                t.saturating_sub(SCAN_TIME_TOLERANCE_MS)..=t.saturating_add(SCAN_TIME_TOLERANCE_MS),
            )
            .map(|(&scan, _)| scan)
            .min_by_key(|scan| scan.abs_diff(t))
            .ok_or_else(|| {
                refused(format!(
                    "t = {} s is at no scan of the truth (none within {SCAN_TIME_TOLERANCE_MS} \
                     ms)",
                    r.t
                ))
            })?;
        tracks.entry(scan).or_default().push(TrackPoint {
            id: r.track_id,
            status,
            x: r.x,
            y: r.y,
        });
    }
    let scans: Vec<ScanReport> = truth
        .iter()
        .map(|(&k, points)| ScanReport {
            t: k as f64 / 1000.0,
            truth: points.clone(),
            tracks: tracks.remove(&k).unwrap_or_default(),
        })
        .collect();
    let m = track_metrics_with(&scans, PAIR_LIMIT_M, PairingCost::Distance)
        .map_err(|e| format!("{source}: {e}"))?;
    let (unpaired_before_first, unpaired_after_first) =
        m.targets.iter().fold((0, 0), |(before, after), t| {
            (
                before + t.scans_present - t.scans_present_since_first_assignment,
                after + t.scans_present_since_first_assignment - t.scans_tracked,
            )
        });
    Ok(SceneRun {
        label: label.to_string(),
        coverage: m.completeness,
        continuity: m.continuity,
        id_changes: m.id_changes,
        rmse: m.assigned_rmse,
        ospa: mean_ospa(&scans, OSPA_CUTOFF_M, OSPA_ORDER).map_err(|e| format!("{source}: {e}"))?,
        false_tracks: m.mostly_unassigned_tracks.len(),
        never_paired: m.never_paired.len(),
        reported_tracks: m.established_tracks,
        unpaired_before_first,
        unpaired_after_first,
        seconds,
        design,
        scans,
        pairs: m.pairs,
    })
}

/// Stone Soup's tracks (with their file's path) and whole-process time
/// for `scene`, if `scripts/stonesoup_scene.py` has written them into
/// `group_dir`.
fn stonesoup_output(group_dir: &Path, scene: &Scene) -> Option<(String, String, f64)> {
    let base = group_dir.join(STONESOUP_DIR);
    let (path, csv_text) = stonesoup_tracks(&base, scene.name)?;
    let seconds = fs::read_to_string(base.join(format!("{}.time", scene.name)))
        .ok()?
        .trim()
        .parse()
        .ok()?;
    Some((path, csv_text, seconds))
}

/// The tracks `scripts/stonesoup_scene.py` wrote into `dir` for the
/// measurement file `name`, if it did: the file's path and its text.
pub fn stonesoup_tracks(dir: &Path, name: &str) -> Option<(String, String)> {
    let path = dir.join(format!("{name}.csv"));
    let text = fs::read_to_string(&path).ok()?;
    Some((path.display().to_string(), text))
}

/// Where `scripts/stonesoup_scene.py` writes, under the group's folder.
pub const STONESOUP_DIR: &str = "stonesoup";
/// The label of those tracks' rows.
pub const STONESOUP_LABEL: &str = "Stone Soup 1.9.1 GNN (scripts/stonesoup_scene.py)";

/// The number types the scene runs the default filter in, with their
/// labels.
pub const SCENE_NUMERICS: [(Numeric, &str); 3] = [
    (Numeric::F64, "f64"),
    (Numeric::F32, "f32"),
    (Numeric::Fixed32, "fast fixed point"),
];

/// The tracker configurations of the scene table: the default filter in
/// each of [`SCENE_NUMERICS`], and `--schedule auto:sigma=50` in f64.
pub fn scene_configurations(scene: &Scene) -> Result<Vec<(String, TrackerOptions)>, String> {
    let auto = ScheduleSpec::parse(AUTO).map_err(|e| format!("{AUTO}: {e}"))?;
    let mut configurations: Vec<(String, TrackerOptions)> = SCENE_NUMERICS
        .iter()
        .map(|&(numeric, label)| (label.to_string(), scene.options(numeric, None)))
        .collect();
    configurations.push((
        format!("f64, --schedule {AUTO}"),
        scene.options(Numeric::F64, Some(auto)),
    ));
    Ok(configurations)
}

// ---------------------------------------------------------------------------
// The group
// ---------------------------------------------------------------------------

fn cell(v: f64) -> String {
    format!("{v:.1}")
}

/// Segments shown in the flight plots.
const PLOTTED: [&str; 3] = [
    "calibration_nice",
    "helicopter_samu31",
    "survey_mecsek_mountains",
];

pub fn run(ctx: &Context) -> Result<(), String> {
    let dir = ctx.group_dir(NAME)?;
    let data = data_dir();
    let segments = read_segments(&data)?;
    let mut results: Vec<SegmentResult> = Vec::new();
    for segment in &segments {
        for timing in Timing::ALL {
            results.push(evaluate_segment(
                segment, timing, &SEEDS, &SCHEDULES, SIGMA_M,
            )?);
        }
    }

    let mut summary = String::new();
    let _ = writeln!(
        summary,
        "# Real aircraft (ADS-B): filters on recorded flights, the tracker on a recorded scene\n\n\
         Generated by `cd host-tests && cargo run --release --bin experiments -- --only {NAME}` \
         from `host-tests/data/real/` (OpenSky Network via the `traffic` 2.13 samples; see its \
         README).\n\n\
         ## Single segments\n\n\
         {} segments; measurements = truth + N(0, {SIGMA_M}²) m per axis, seeds {:?}, at the real \
         report times and on a {GRID_PERIOD_S} s grid (truth interpolated linearly; grid points \
         inside report gaps over {GRID_MAX_GAP_S} s left out). A segment's figure: the mean over \
         the seeds of the position RMSE √(mean e_x² + e_y²) over every report. Schedules run as \
         `replay --filter ab --schedule SPEC --sigma-m {SIGMA_M} --scan-period-s T` (T the \
         stream's median interval). The Kalman filter (constant velocity, white acceleration of \
         density q) uses one q for the whole set, the one of {:?} m²/s³ with the least median. \
         \"common\": the median over the segments every method ran. \"> raw\": segments where the \
         method is worse than the raw measurements; \"> 1.02 raw\": more than 2 % worse.\n",
        segments.len(),
        SEEDS,
        KALMAN_Q_GRID
    );

    let mut per_segment = Table::new(
        ["segment", "timing", "points", "max interval (s)", "raw"]
            .into_iter()
            .map(String::from)
            .chain(KALMAN_Q_GRID.iter().map(|q| format!("KF q={q}")))
            .chain(SCHEDULES.iter().map(|s| s.to_string())),
    );
    for r in &results {
        let mut row = vec![
            r.segment.clone(),
            r.timing.short().to_string(),
            r.points.to_string(),
            format!("{:.0}", r.max_interval_s),
            cell(r.raw),
        ];
        row.extend(r.kalman.iter().map(|&v| cell(v)));
        row.extend(r.schedules.iter().map(|(_, f)| match f {
            Figure::Rmse(v) => cell(*v),
            Figure::Refused(_) => "refused".into(),
        }));
        per_segment.push(row);
    }
    per_segment.write(&dir, "segments")?;

    let mut methods = Table::new([
        "timing",
        "method",
        "median RMSE (m)",
        "segments run",
        "refused",
        "median, common set",
        "÷ Kalman (common set)",
        "> raw",
        "> 1.02 raw",
    ]);
    let mut q_table = Table::new(
        std::iter::once("timing".to_string()).chain(KALMAN_Q_GRID.iter().map(|q| format!("q={q}"))),
    );
    let mut refusals = Table::new([
        "timing",
        "segment",
        "max interval (s)",
        "schedules refused",
        "reason (first)",
    ]);
    for timing in Timing::ALL {
        let of_timing: Vec<&SegmentResult> =
            results.iter().filter(|r| r.timing == timing).collect();
        let (kq, _) = best_kalman_q(&of_timing);
        q_table.push(std::iter::once(timing.short().to_string()).chain(
            (0..KALMAN_Q_GRID.len()).map(|i| {
                cell(median(
                    &of_timing.iter().map(|r| r.kalman[i]).collect::<Vec<_>>(),
                ))
            }),
        ));
        let rows = summarise(&of_timing, &SCHEDULES, kq);
        let kalman_common = rows[1].median_common;
        for m in &rows {
            methods.push([
                timing.short().to_string(),
                m.method.clone(),
                cell(m.median),
                m.ran.to_string(),
                m.refused.to_string(),
                cell(m.median_common),
                format!("{:.3}", m.median_common / kalman_common),
                m.worse_than_raw.to_string(),
                m.over_102_raw.to_string(),
            ]);
        }
        for r in &of_timing {
            let refused: Vec<&(String, Figure)> = r
                .schedules
                .iter()
                .filter(|(_, f)| f.rmse().is_none())
                .collect();
            if let Some((_, Figure::Refused(why))) = refused.first() {
                refusals.push([
                    timing.short().to_string(),
                    r.segment.clone(),
                    format!("{:.0}", r.max_interval_s),
                    refused.len().to_string(),
                    why.clone(),
                ]);
            }
        }
        let auto = rows.iter().find(|m| m.method == AUTO);
        let _ = writeln!(
            summary,
            "### {}\n\nKalman q = {} m²/s³. {}\n",
            timing.label(),
            KALMAN_Q_GRID[kq],
            auto.map_or_else(String::new, |a| format!(
                "`{AUTO}`: median {:.1} m over the {} segments it ran ({} refused), {:.3}× the \
                 Kalman filter's on the common set; worse than raw on {} segments, more than 2 % \
                 worse on {}.",
                a.median,
                a.ran,
                a.refused,
                a.median_common / kalman_common,
                a.worse_than_raw,
                a.over_102_raw
            ))
        );
        let mut t = Table::new([
            "method",
            "median RMSE (m)",
            "run",
            "refused",
            "common set",
            "÷ KF",
            "> raw",
            "> 1.02 raw",
        ]);
        for m in &rows {
            t.push([
                m.method.clone(),
                cell(m.median),
                m.ran.to_string(),
                m.refused.to_string(),
                cell(m.median_common),
                format!("{:.3}", m.median_common / kalman_common),
                m.worse_than_raw.to_string(),
                m.over_102_raw.to_string(),
            ]);
        }
        summary.push_str(&t.to_markdown());
        summary.push('\n');
    }
    methods.write(&dir, "methods")?;
    q_table.write(&dir, "kalman_q")?;
    refusals.write(&dir, "refusals")?;
    let _ = writeln!(
        summary,
        "Per segment: `segments.csv`; the Kalman filter's median per q: `kalman_q.md`; streams \
         refused: `refusals.md` ({} segment-timings).\n",
        refusals.rows.len()
    );

    // Other sensors' σ.
    let mut sigma_table = Table::new([
        "σ (m)",
        "timing",
        "raw",
        "Kalman q (m²/s³)",
        "Kalman",
        "auto",
        "auto ÷ Kalman",
        "refused",
        "> raw",
        "> 1.02 raw",
        "Kalman > 1.02 raw",
        "worst ÷ raw",
        "worst ÷ Kalman",
    ]);
    for sigma in SIGMA_SWEEP_M {
        for timing in Timing::ALL {
            // σ 50 m: the main table's runs, not measured again.
            let r = if sigma == SIGMA_M {
                let of_timing: Vec<&SegmentResult> =
                    results.iter().filter(|r| r.timing == timing).collect();
                sigma_row_of(&of_timing, AUTO, sigma, timing)
            } else {
                sigma_row(&segments, timing, &SEEDS, sigma)?
            };
            sigma_table.push([
                format!("{sigma}"),
                timing.short().to_string(),
                cell(r.raw),
                format!("{}", r.kalman_q),
                cell(r.kalman),
                cell(r.auto),
                format!("{:.3}", r.auto / r.kalman),
                r.refused.to_string(),
                r.worse_than_raw.to_string(),
                r.over_102_raw.to_string(),
                r.kalman_over_102_raw.to_string(),
                format!("{} {:.3}", r.worst_against_raw.0, r.worst_against_raw.1),
                format!(
                    "{} {:.3}",
                    r.worst_against_kalman.0, r.worst_against_kalman.1
                ),
            ]);
        }
    }
    sigma_table.write(&dir, "sigma")?;
    let sigmas: Vec<String> = SIGMA_SWEEP_M.iter().map(|s| format!("{s}")).collect();
    let _ = writeln!(
        summary,
        "### Other sensors' σ\n\n\
         The same segments, seeds and timings measured with σ = {} m per axis: `auto:sigma=σ` \
         (configured from that σ alone) against raw and the one-q Kalman filter (R = σ²I) whose q \
         is the best for the set at that σ; medians over the segments auto ran (\"refused\": auto's \
         refusals; \"> 1.02 raw\": segments where auto is more than 2 % worse than raw, \
         \"Kalman > 1.02 raw\" the same for the Kalman filter); the segment where auto is worst against raw and against the Kalman filter \
         (the ratio of their RMSEs). Also `sigma.csv`.\n\n{}",
        sigmas.join(", "),
        sigma_table.to_markdown()
    );

    // Flight plots: seed 1 at the real report times.
    for name in PLOTTED {
        let Some(segment) = segments.iter().find(|s| s.name == name) else {
            continue;
        };
        let truth = truth_for(segment, Timing::Real);
        let stream = measure(&truth, noise_stream(name, Timing::Real, SEEDS[0]), SIGMA_M);
        let of_real: Vec<&SegmentResult> = results
            .iter()
            .filter(|r| r.timing == Timing::Real)
            .collect();
        let (kq, _) = best_kalman_q(&of_real);
        let kf = run_kalman(KALMAN_Q_GRID[kq], &stream, SIGMA_M)?;
        let xy = |v: &[(f64, [f64; 2])]| v.iter().map(|p| (p.1[0], p.1[1])).collect::<Vec<_>>();
        let mut series = vec![
            Series::points("measurements", xy(&stream)),
            Series::line("truth", xy(&truth)),
            Series::line(
                format!("Kalman CV q={}", KALMAN_Q_GRID[kq]),
                kf.iter().map(|p| (p[0], p[1])).collect(),
            ),
        ];
        if let Estimates::Positions(p) = run_schedule(AUTO, &stream, SIGMA_M)? {
            series.push(Series::line(AUTO, p.iter().map(|p| (p[0], p[1])).collect()));
        }
        plot(
            &dir.join(format!("flight_{name}.svg")),
            &PlotSpec {
                title: &format!(
                    "{name}: seed {}, real report times, σ {SIGMA_M} m",
                    SEEDS[0]
                ),
                x_label: "x east (m)",
                y_label: "y north (m)",
                equal_aspect: true,
                y_max: None,
            },
            &series,
        )?;
    }

    // Scene.
    let _ = writeln!(
        summary,
        "## Scene\n\n\
         `replay --tracker --region-m 50000 --sigma-m {SIGMA_M} --scan-period-s 4 --pd P \
         --clutter-per-km2 C` on `scene/<name>.meas.csv`. Reported tracks: confirmed or coasting. \
         Each scan, truth and reported positions are paired by the optimal assignment on distance \
         (not clipped), pairs beyond {PAIR_LIMIT_M} m dropped; coverage = paired \
         truth points / truth points; continuity = paired points / truth points from the flight's \
         first pairing; id changes: changes of the paired track id between consecutive paired \
         scans of a flight; false tracks: paired in under half of their reported scans; never \
         paired: paired in none; OSPA c = {OSPA_CUTOFF_M} m, p = 2, averaged over the scans; RMSE \
         over the paired points; the truth points not paired, split at the flight's first \
         pairing (before it: the track's start and its M-of-N confirmation; after it: losses). \
         The Stone Soup rows, when present, score the tracks `scripts/stonesoup_scene.py` \
         wrote into `{STONESOUP_DIR}/` (Stone Soup 1.9.1's GNN tracker configured from the same \
         design). The replay times, and Stone Soup's against abtrack's, are in `{TIMES}.md`, \
         apart from these tables, which are the same on every run.\n"
    );
    let mut scene_table = Table::new([
        "scene",
        "tracker",
        "coverage",
        "continuity",
        "id changes",
        "RMSE (m)",
        "OSPA (m)",
        "false tracks",
        "never paired",
        "reported tracks",
        "truth unpaired before its first pairing",
        "truth unpaired after it",
    ]);
    let mut times = Table::new(["scene", "tracker", "replay time (ms)"]);
    let mut speed: Vec<String> = Vec::new();
    let mut common: Vec<String> = Vec::new();
    for scene in &SCENES {
        let truth = read_scene_truth(&data, scene)?;
        let mut design = String::new();
        let mut f64_seconds = f64::NAN;
        let mut f64_pairs = Vec::new();
        for (label, options) in scene_configurations(scene)? {
            let r = run_scene(&data, scene, &truth, &options, &label)?;
            if design.is_empty() {
                design = r.design.clone();
            }
            scene_table.push(scene_row(scene, &r));
            times.push(time_row(scene, &r));
            if label == "f64" {
                scene_plot(&dir, scene, &r)?;
                f64_seconds = r.seconds;
                f64_pairs = r.pairs.clone();
            }
        }
        if let Some((path, csv_text, seconds)) = stonesoup_output(&dir, scene) {
            let r = score_tracks(
                STONESOUP_LABEL,
                &path,
                &csv_text,
                &truth,
                seconds,
                String::new(),
            )?;
            scene_table.push(scene_row(scene, &r));
            times.push(time_row(scene, &r));
            if let Some((ours, theirs, n)) = common_rmse(&f64_pairs, &r.pairs) {
                common.push(format!(
                    "{}: {n} points (of {} and {} paired), abtrack (f64) {:.1} m, Stone Soup {:.1} m",
                    scene.name,
                    f64_pairs.len(),
                    r.pairs.len(),
                    ours,
                    theirs
                ));
            }
            speed.push(format!(
                "{}: Stone Soup {:.1} s, abtrack (f64) {:.3} s: {:.0}×",
                scene.name,
                seconds,
                f64_seconds,
                seconds / f64_seconds
            ));
        }
        let _ = writeln!(
            summary,
            "{} (P_D {}, clutter {} per km²):\n\n```text\n{}```\n",
            scene.name, scene.detection_probability, scene.clutter_per_km2, design
        );
    }
    scene_table.write(&dir, "scene")?;
    summary.push_str(&scene_table.to_markdown());
    write_scene_times(&dir, &times, &speed)?;
    if !common.is_empty() {
        let _ = writeln!(
            summary,
            "\nRMSE over the (scan, flight) points both trackers paired, so that what one covers \
             and the other does not (a coasting track kept, a track started sooner) does not \
             weigh on the comparison: {}.",
            common.join("; ")
        );
    }
    summary.push_str("\nTracks over truth: `scene_<name>.svg`; flights: `flight_<name>.svg`.\n\n");
    let truth = read_scene_truth(&data, &SCENES[0])?;
    scene_draws::run(&dir, &scene_draws::scratch_dir(), &truth, &mut summary)?;
    write_file(&dir.join("summary.md"), &summary)
}

/// One row of the scene table.
fn scene_row(scene: &Scene, r: &SceneRun) -> Vec<String> {
    vec![
        scene.name.to_string(),
        r.label.clone(),
        format!("{:.3}", r.coverage),
        format!("{:.3}", r.continuity),
        r.id_changes.to_string(),
        cell(r.rmse),
        cell(r.ospa),
        r.false_tracks.to_string(),
        r.never_paired.to_string(),
        r.reported_tracks.to_string(),
        r.unpaired_before_first.to_string(),
        r.unpaired_after_first.to_string(),
    ]
}

/// The file of the scene's wall-clock times (`<TIMES>.csv`, `.md`).
const TIMES: &str = "scene_times";

/// One row of the times table.
fn time_row(scene: &Scene, r: &SceneRun) -> Vec<String> {
    vec![
        scene.name.to_string(),
        r.label.clone(),
        format!("{:.0}", r.seconds * 1000.0),
    ]
}

/// Writes the scene's replay times and, when Stone Soup's are there, the
/// comparison `speed` ([`TIMES`]): wall-clock times change on every run,
/// so they are kept out of the accuracy tables.
fn write_scene_times(dir: &Path, times: &Table, speed: &[String]) -> Result<(), String> {
    write_file(&dir.join(format!("{TIMES}.csv")), &times.to_csv())?;
    let mut text = format!(
        "# Real scene: replay times\n\n\
         Written by `cd host-tests && cargo run --release --bin experiments -- --only {NAME}` \
         with the scene's accuracy figures (`scene.md`, `summary.md`), apart from them: these \
         vary between runs and hosts. abtrack: the whole replay (read the file, track, write the \
         CSV) in-process on this host, the least of {TIMING_REPEATS} runs. Stone Soup: the whole \
         Python process (imports included, one process per scene) that \
         `scripts/stonesoup_scene.py` timed into `{STONESOUP_DIR}/<scene>.time`.\n\n{}",
        times.to_markdown()
    );
    if !speed.is_empty() {
        let _ = writeln!(
            text,
            "\nWhole-process time of Stone Soup against abtrack's whole replay in f64: {}.",
            speed.join("; ")
        );
    }
    write_file(&dir.join(format!("{TIMES}.md")), &text)
}

/// The truth and the reported tracks' positions of every scan.
fn scene_plot(dir: &Path, scene: &Scene, run: &SceneRun) -> Result<(), String> {
    let truth: Vec<(f64, f64)> = run
        .scans
        .iter()
        .flat_map(|s| s.truth.iter().map(|p| (p.x, p.y)))
        .collect();
    let tracks: Vec<(f64, f64)> = run
        .scans
        .iter()
        .flat_map(|s| {
            s.tracks
                .iter()
                .filter(|t| t.status.is_established())
                .map(|t| (t.x, t.y))
        })
        .collect();
    plot(
        &dir.join(format!("scene_{}.svg", scene.name)),
        &PlotSpec {
            title: &format!("{}: reported tracks (f64) over the truth", scene.name),
            x_label: "x east (m)",
            y_label: "y north (m)",
            equal_aspect: true,
            y_max: None,
        },
        &[
            Series::points("truth", truth),
            Series::points("confirmed or coasting tracks", tracks),
        ],
    )
}
