//! The TCAS encounter suite around recorded intruders: the randomized
//! suite's geometry ([`crate::random_encounters`]: the own aircraft level
//! and straight, a horizontal miss 0–1.5 NM and a vertical miss ±1200 ft at
//! the designed closest approach, closure ≥ 100 kt) drawn around the real
//! paths of `data/real/` (ADS-B truth: the Paris scene's flights and the
//! single segments; see its README), so that the intruder turns, climbs,
//! levels off and speeds up as real aircraft do. The suite's runs, tables
//! and comparison with the reference on the true states are the randomized
//! suite's ([`crate::random_encounters::run_one`]).
//!
//! # The recorded truth between its samples
//!
//! * Position, velocity and acceleration: the natural cubic spline through
//!   the samples (the truth is itself a smoothing spline sampled at the
//!   report times or every 4 s), so the acceleration is continuous through
//!   turns; a recording is cut into pieces where its samples are more than
//!   [`MAX_GAP_S`] apart.
//! * Altitude and rate: the least-squares line through the recorded
//!   altitudes within ±[`ALTITUDE_WINDOW_S`] (ADS-B's 25 ft steps; the
//!   scene's truth interpolates a few); the runs' reports are this truth
//!   quantised again.
//!
//! # Drawing an encounter
//!
//! Along each path, a closest approach every [`CPA_SPACING_S`]; for each,
//! from its seed: the own heading (uniform), speed ([`OWN_SPEED_KT`]),
//! miss distances and side. The own aircraft passes the intruder's position
//! at that time at the drawn horizontal miss, across the relative velocity,
//! and flies level at the intruder's altitude there minus the vertical
//! miss. The run starts where the straight relative path's range tau is
//! the level's TA tau + 30 s (at least 6 NM out), as in the randomized
//! suite, and ends [`AFTER_CPA_S`] after. A candidate is kept when one
//! piece of the recording covers the run, the closure is at least
//! [`MIN_CLOSURE_KT`], the own altitude lies in [`OWN_ALTITUDE_FT`], the
//! intruder stays above [`LOWEST_INTRUDER_FT`] with an altitude at every
//! scan, and the recorded intruder, which need not fly that straight path,
//! also starts at least 6 NM out and, when closing, at a range tau of at
//! least the TA tau + 30 s.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

use abtrack::filter::altitude::AltitudeQuantum;
use serde::Deserialize;

use crate::encounters::{Encounter, IntruderPath, KT, NM};
use crate::noise::{derive_seed, rng_from_seed, uniform};
use crate::random_encounters::{RandomEncounter, AFTER_CPA_S, HMD_NM, LOWEST_INTRUDER_FT, VMD_FT};
use crate::reference_tcas::{level_for, range_and_rate, Relative};

/// Base seed of the drawn geometry.
pub const BASE_SEED: u64 = 0x0019_7CA5_4EC0_4D19;
/// A closest approach every this many seconds along each path.
pub const CPA_SPACING_S: f64 = 30.0;
/// The longest interval between the recording's samples over a run, s.
pub const MAX_GAP_S: f64 = 10.0;
/// The own aircraft's ground speed, kt.
pub const OWN_SPEED_KT: (f64, f64) = (150.0, 350.0);
/// The least closure speed at the designed closest approach, kt (the
/// randomized suite's least).
pub const MIN_CLOSURE_KT: f64 = 100.0;
/// The own altitude band, ft: SL 3–7 (the randomized suite draws within
/// narrower bands away from the levels' edges).
pub const OWN_ALTITUDE_FT: (f64, f64) = (1700.0, 40_000.0);
/// Half-width of the altitude fit, s.
pub const ALTITUDE_WINDOW_S: f64 = 10.0;

/// One sample of a recording: t (s), x, y (m), the altitude (ft) if
/// reported.
type Sample = (f64, [f64; 2], Option<f64>);

/// One recorded path: the truth's samples in time order.
#[derive(Debug, Clone)]
pub struct RecordedPath {
    /// `scene/<scene>:<flight>` or `single/<segment>`.
    pub name: String,
    times: Vec<f64>,
    positions: Vec<[f64; 2]>,
    /// The natural cubic spline's second derivatives at the samples.
    second_derivatives: Vec<[f64; 2]>,
    /// (t, ft) of the samples with an altitude.
    altitudes: Vec<(f64, f64)>,
}

impl RecordedPath {
    /// The path through `samples` (at least two, in time order, distinct
    /// times).
    fn new(name: String, samples: &[Sample]) -> Self {
        let times: Vec<f64> = samples.iter().map(|s| s.0).collect();
        let positions: Vec<[f64; 2]> = samples.iter().map(|s| s.1).collect();
        let second_derivatives = natural_spline(&times, &positions);
        RecordedPath {
            name,
            times,
            positions,
            second_derivatives,
            altitudes: samples
                .iter()
                .filter_map(|s| s.2.map(|a| (s.0, a)))
                .collect(),
        }
    }

    /// The first and last sample times, s.
    pub fn span(&self) -> (f64, f64) {
        (
            self.times.first().copied().unwrap_or(f64::NAN),
            self.times.last().copied().unwrap_or(f64::NAN),
        )
    }

    /// Whether [t0, t1] lies inside the recording (a path has no interval
    /// over [`MAX_GAP_S`]: [`read_paths`] cuts it there).
    pub fn covers(&self, t0: f64, t1: f64) -> bool {
        let (first, last) = self.span();
        t0 >= first && t1 <= last
    }

    /// Position (m), velocity (m/s) and acceleration (m/s²) at `t` inside
    /// the recording (module docs: the natural cubic spline).
    pub fn kinematics(&self, t: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
        let i = self
            .times
            .partition_point(|&ti| ti <= t)
            .clamp(1, self.times.len() - 1)
            - 1;
        let h = self.times[i + 1] - self.times[i];
        let (before, after) = (self.times[i + 1] - t, t - self.times[i]);
        let (p0, p1) = (self.positions[i], self.positions[i + 1]);
        let (m0, m1) = (self.second_derivatives[i], self.second_derivatives[i + 1]);
        // The cubic on [t_i, t_i+1] with second derivatives m0, m1 at its
        // ends through p0, p1.
        let p = |k: usize| {
            m0[k] * before.powi(3) / (6.0 * h)
                + m1[k] * after.powi(3) / (6.0 * h)
                + (p0[k] / h - m0[k] * h / 6.0) * before
                + (p1[k] / h - m1[k] * h / 6.0) * after
        };
        let v = |k: usize| {
            -m0[k] * before * before / (2.0 * h) + m1[k] * after * after / (2.0 * h)
                - (p0[k] / h - m0[k] * h / 6.0)
                + (p1[k] / h - m1[k] * h / 6.0)
        };
        let a = |k: usize| (m0[k] * before + m1[k] * after) / h;
        ([p(0), p(1)], [v(0), v(1)], [a(0), a(1)])
    }

    /// Altitude (ft) and rate (ft/s) at `t`: the least-squares line through
    /// the reported altitudes within ±[`ALTITUDE_WINDOW_S`]; `None` with
    /// fewer than three of them.
    pub fn altitude(&self, t: f64) -> Option<(f64, f64)> {
        let near: Vec<(f64, f64)> = self
            .altitudes
            .iter()
            .filter(|(ti, _)| (ti - t).abs() <= ALTITUDE_WINDOW_S)
            .map(|&(ti, a)| (ti - t, a))
            .collect();
        if near.len() < 3 {
            return None;
        }
        let n = near.len() as f64;
        let (mt, ma) = (
            near.iter().map(|p| p.0).sum::<f64>() / n,
            near.iter().map(|p| p.1).sum::<f64>() / n,
        );
        let sxx: f64 = near.iter().map(|p| (p.0 - mt) * (p.0 - mt)).sum();
        let sxy: f64 = near.iter().map(|p| (p.0 - mt) * (p.1 - ma)).sum();
        if sxx <= 0.0 {
            return None;
        }
        let rate = sxy / sxx;
        Some((ma - rate * mt, rate))
    }
}

/// The second derivatives of the natural cubic spline through
/// (`times`, `values`) (zero at the ends; the tridiagonal system solved by
/// the Thomas algorithm).
fn natural_spline(times: &[f64], values: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let n = times.len();
    let mut m = vec![[0.0; 2]; n];
    if n < 3 {
        return m;
    }
    let h: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    // Rows 1..n−1: h[i−1]·m[i−1] + 2(h[i−1] + h[i])·m[i] + h[i]·m[i+1] = r[i].
    let mut diagonal = vec![0.0; n];
    let mut rhs = vec![[0.0; 2]; n];
    for i in 1..n - 1 {
        diagonal[i] = 2.0 * (h[i - 1] + h[i]);
        for k in 0..2 {
            rhs[i][k] = 6.0
                * ((values[i + 1][k] - values[i][k]) / h[i]
                    - (values[i][k] - values[i - 1][k]) / h[i - 1]);
        }
    }
    for i in 2..n - 1 {
        let w = h[i - 1] / diagonal[i - 1];
        diagonal[i] -= w * h[i - 1];
        let previous = rhs[i - 1];
        for (r, p) in rhs[i].iter_mut().zip(previous) {
            *r -= w * p;
        }
    }
    for i in (1..n - 1).rev() {
        for k in 0..2 {
            m[i][k] = (rhs[i][k] - h[i] * m[i + 1][k]) / diagonal[i];
        }
    }
    m
}

/// `samples` in time order, one per time, cut where they are more than
/// [`MAX_GAP_S`] apart: the pieces of two samples or more.
fn pieces(mut samples: Vec<Sample>) -> Vec<Vec<Sample>> {
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    samples.dedup_by(|a, b| a.0 == b.0);
    let mut out: Vec<Vec<Sample>> = Vec::new();
    for s in samples {
        match out.last_mut() {
            Some(piece) if piece.last().is_some_and(|p| s.0 - p.0 <= MAX_GAP_S) => piece.push(s),
            _ => out.push(vec![s]),
        }
    }
    out.retain(|p| p.len() >= 2);
    out
}

/// A recorded intruder in an [`Encounter`]: its path, the recording's time
/// at scan 0 and the own aircraft's position then, in the path's frame.
#[derive(Debug, Clone, Copy)]
pub struct RecordedIntruder {
    pub path: &'static RecordedPath,
    pub t0: f64,
    pub own_start: [f64; 2],
    /// The recording's time of the designed closest approach, s.
    pub t_cpa: f64,
}

impl RecordedIntruder {
    /// The true relative state at `t` s into the run, the own aircraft
    /// moving at `own_velocity`.
    pub fn relative(&self, t: f64, own_velocity: [f64; 2]) -> Relative {
        let (p, v, _) = self.path.kinematics(self.t0 + t);
        Relative {
            s: [
                p[0] - (self.own_start[0] + own_velocity[0] * t),
                p[1] - (self.own_start[1] + own_velocity[1] * t),
            ],
            v: [v[0] - own_velocity[0], v[1] - own_velocity[1]],
            altitude: self.path.altitude(self.t0 + t),
        }
    }

    /// The intruder's largest horizontal acceleration over the `window` s
    /// before scan `k` (the curve's, every 0.25 s), m/s².
    pub fn largest_acceleration_before(&self, k: usize, window: f64) -> f64 {
        let end = self.t0 + k as f64;
        let steps = (window * 4.0) as usize;
        (0..=steps)
            .map(|i| {
                let t = (end - i as f64 * 0.25).max(self.path.span().0);
                let (_, _, a) = self.path.kinematics(t);
                a[0].hypot(a[1])
            })
            .fold(0.0, f64::max)
    }
}

#[derive(Deserialize)]
struct SceneRow {
    t: f64,
    flight: String,
    x: f64,
    y: f64,
    alt_ft: Option<f64>,
}

#[derive(Deserialize)]
struct SegmentRow {
    t: f64,
    x: f64,
    y: f64,
    alt_ft: Option<f64>,
}

fn read_rows<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<Vec<T>, String> {
    csv::Reader::from_path(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?
        .deserialize()
        .collect::<Result<Vec<T>, _>>()
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// The recorded paths of `dir` (`data/real`): every flight of the
/// `paris_1400` scene's truth (the hard scene has the same truth), then
/// every single segment, by name.
pub fn read_paths(dir: &Path) -> Result<Vec<RecordedPath>, String> {
    let mut flights: BTreeMap<String, Vec<Sample>> = BTreeMap::new();
    for r in read_rows::<SceneRow>(&dir.join("scene/paris_1400.truth.csv"))? {
        flights
            .entry(r.flight)
            .or_default()
            .push((r.t, [r.x, r.y], r.alt_ft));
    }
    let mut paths = Vec::new();
    let mut add = |name: String, samples: Vec<Sample>| {
        let cut = pieces(samples);
        let several = cut.len() > 1;
        for (k, piece) in cut.iter().enumerate() {
            let name = if several {
                format!("{name}, part {}", k + 1)
            } else {
                name.clone()
            };
            paths.push(RecordedPath::new(name, piece));
        }
    };
    for (name, samples) in flights {
        add(format!("scene/paris_1400:{name}"), samples);
    }
    let single = dir.join("single");
    let mut files: Vec<_> = std::fs::read_dir(&single)
        .map_err(|e| format!("cannot list {}: {e}", single.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    files.sort();
    for file in files {
        let rows: Vec<SegmentRow> = read_rows(&file)?;
        let name = file
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        add(
            format!("single/{name}"),
            rows.iter().map(|r| (r.t, [r.x, r.y], r.alt_ft)).collect(),
        );
    }
    Ok(paths)
}

/// The paths of `data/real`, read once per process.
pub fn paths() -> Result<&'static [RecordedPath], String> {
    static PATHS: OnceLock<Result<Vec<RecordedPath>, String>> = OnceLock::new();
    PATHS
        .get_or_init(|| read_paths(&crate::experiments::real_adsb::data_dir()))
        .as_deref()
        .map_err(Clone::clone)
}

/// The candidate closest approach `k` along `path` (number `path_index`),
/// drawn from its seed; `None` when it is not kept (module docs).
fn candidate(
    path: &'static RecordedPath,
    path_index: usize,
    k: usize,
    t_cpa: f64,
) -> Option<RandomEncounter> {
    let mut rng = rng_from_seed(derive_seed(
        derive_seed(BASE_SEED, path_index as u64),
        k as u64,
    ));
    let heading = uniform(&mut rng, 0.0, std::f64::consts::TAU);
    let speed = uniform(&mut rng, OWN_SPEED_KT.0, OWN_SPEED_KT.1) * KT;
    let hmd_m = uniform(&mut rng, HMD_NM.0, HMD_NM.1) * NM;
    let vmd_ft = uniform(&mut rng, VMD_FT.0, VMD_FT.1);
    let side = if uniform(&mut rng, 0.0, 1.0) < 0.5 {
        -1.0
    } else {
        1.0
    };
    let own_velocity = [heading.sin() * speed, heading.cos() * speed];
    let (p, v, _) = path.kinematics(t_cpa);
    let (intruder_ft, intruder_rate) = path.altitude(t_cpa)?;
    let relative = [v[0] - own_velocity[0], v[1] - own_velocity[1]];
    let closure = relative[0].hypot(relative[1]);
    let own_ft = intruder_ft - vmd_ft;
    if closure < MIN_CLOSURE_KT * KT || !(OWN_ALTITUDE_FT.0..=OWN_ALTITUDE_FT.1).contains(&own_ft) {
        return None;
    }
    let level = level_for(own_ft);
    let start_range = (closure * (level.ta_tau + 30.0)).max(6.0 * NM).max(hmd_m);
    let lead = (start_range * start_range - hmd_m * hmd_m).sqrt() / closure;
    let (t0, end) = (t_cpa - lead, t_cpa + AFTER_CPA_S);
    if !path.covers(t0, end) {
        return None;
    }
    let scans = (end - t0).ceil() as usize;
    let intruder_altitudes_fit = (0..scans).all(|s| {
        path.altitude(t0 + s as f64)
            .is_some_and(|(a, _)| a >= LOWEST_INTRUDER_FT)
    });
    if !intruder_altitudes_fit {
        return None;
    }
    // Across the relative velocity, on the drawn side: the relative
    // position at the designed closest approach is hmd·n.
    let n = [relative[1] / closure * side, -relative[0] / closure * side];
    let own_at_cpa = [p[0] - hmd_m * n[0], p[1] - hmd_m * n[1]];
    let own_start = [
        own_at_cpa[0] - own_velocity[0] * lead,
        own_at_cpa[1] - own_velocity[1] * lead,
    ];
    let intruder = RecordedIntruder {
        path,
        t0,
        own_start,
        t_cpa,
    };
    // The recorded intruder need not fly the straight path the start was
    // placed on: kept when it too starts as far out as the randomized
    // suite's (6 NM, and a range tau of the TA tau + 30 s when closing).
    let start = intruder.relative(0.0, own_velocity);
    let (range, rate) = range_and_rate(start.s, start.v);
    let far_enough = range >= 6.0 * NM && (rate >= 0.0 || range / -rate >= level.ta_tau + 30.0);
    if !far_enough {
        return None;
    }
    Some(RandomEncounter {
        index: 0,
        level: level.sl,
        hmd_m,
        vmd_ft,
        closure_kt: closure / KT,
        intruder_rate_ft_per_min: intruder_rate * 60.0,
        encounter: Encounter {
            name: "recorded",
            description: "a recorded intruder against a level, straight own aircraft",
            own_altitude_ft: own_ft,
            own_velocity,
            intruder: IntruderPath::Recorded(intruder),
            quantum: AltitudeQuantum::ModeS25,
            scans,
        },
    })
}

/// The whole suite, numbered in order: every kept candidate of every path.
pub fn suite() -> Result<Vec<RandomEncounter>, String> {
    let mut out = Vec::new();
    for (path_index, path) in paths()?.iter().enumerate() {
        let (first, last) = path.span();
        let mut k = 0;
        loop {
            let t_cpa = first + CPA_SPACING_S * (k as f64 + 1.0);
            if t_cpa + AFTER_CPA_S > last {
                break;
            }
            if let Some(mut e) = candidate(path, path_index, k, t_cpa) {
                e.index = out.len();
                out.push(e);
            }
            k += 1;
        }
    }
    Ok(out)
}
