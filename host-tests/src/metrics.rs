//! Accuracy and multi-target metrics over Monte Carlo runs (host side, f64).
//!
//! # Single-target accuracy
//! For each run r and axis, the run's RMSE over its scored scans is
//! RMSE_r = √(Σ_k e_{r,k}² / K) (Al-Wagih & Abdulla eq. 26, with e the
//! estimate minus the truth). Over R runs we report the mean of the per-run
//! RMSEs with a 95 % confidence interval mean ± t_{0.975, R−1}·s/√R (s the
//! sample standard deviation of the per-run RMSEs, t the Student quantile):
//! the runs are independent, so the interval is exact for normal per-run
//! RMSEs and asymptotically right otherwise. Two methods run on the same
//! noise are compared with [`paired_difference_ci95`] (per-run differences),
//! which is much tighter than comparing two separate intervals.
//! RMSE against time is √(Σ_r e_{r,k}² / R) per scan k (the curve the papers
//! plot).
//!
//! # Multi-target
//! Inputs are per-scan lists of truth `(id, x, y)` and of reported tracks
//! `(track id, status, x, y)` ([`ScanReport`]). Only *established* tracks —
//! status confirmed or coasting, what a consumer is shown — count; tentative
//! tracks are the tracker's internal business and are ignored by every metric
//! here. See [`track_metrics`] and [`ospa`] for the definitions.

use std::collections::BTreeMap;

// ---------------------------------------------------------------------------
// Confidence intervals
// ---------------------------------------------------------------------------

/// A sample mean with its 95 % confidence half-width.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanCi {
    pub mean: f64,
    /// t_{0.975, n−1}·s/√n; infinite for n = 1, NaN for n = 0.
    pub half_width: f64,
    /// Sample standard deviation s (n − 1 denominator).
    pub std_dev: f64,
    pub n: usize,
}

impl MeanCi {
    pub fn lower(&self) -> f64 {
        self.mean - self.half_width
    }
    pub fn upper(&self) -> f64 {
        self.mean + self.half_width
    }
    /// The two intervals do not overlap and this one is entirely below.
    pub fn significantly_below(&self, other: &MeanCi) -> bool {
        self.upper() < other.lower()
    }
}

/// Two-sided 95 % Student t quantile t_{0.975, df}. Exact table (to 7
/// digits) for df ≤ 30; above, the Cornish–Fisher expansion in 1/df
/// (Abramowitz & Stegun 26.7.5), whose error is < 1e−5 there. df = 0 gives
/// infinity.
pub fn student_t_975(df: usize) -> f64 {
    const TABLE: [f64; 30] = [
        12.706_204_7,
        4.302_652_7,
        3.182_446_3,
        2.776_445_1,
        2.570_581_8,
        2.446_911_9,
        2.364_624_3,
        2.306_004_1,
        2.262_157_2,
        2.228_138_9,
        2.200_985_2,
        2.178_812_8,
        2.160_368_7,
        2.144_786_7,
        2.131_449_5,
        2.119_905_3,
        2.109_815_6,
        2.100_922_0,
        2.093_024_1,
        2.085_963_4,
        2.079_613_8,
        2.073_873_1,
        2.068_657_6,
        2.063_898_6,
        2.059_538_6,
        2.055_529_4,
        2.051_830_5,
        2.048_407_1,
        2.045_229_6,
        2.042_272_5,
    ];
    if df == 0 {
        return f64::INFINITY;
    }
    if df <= 30 {
        return TABLE[df - 1];
    }
    let z: f64 = 1.959_963_984_540_054;
    let n = df as f64;
    let z3 = z.powi(3);
    let z5 = z.powi(5);
    let z7 = z.powi(7);
    let z9 = z.powi(9);
    z + (z3 + z) / (4.0 * n)
        + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * n * n)
        + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * n.powi(3))
        + (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z) / (92160.0 * n.powi(4))
}

/// Mean of `samples` with its 95 % Student-t confidence interval.
pub fn mean_ci95(samples: &[f64]) -> MeanCi {
    let n = samples.len();
    if n == 0 {
        return MeanCi {
            mean: f64::NAN,
            half_width: f64::NAN,
            std_dev: f64::NAN,
            n,
        };
    }
    let mean = samples.iter().sum::<f64>() / n as f64;
    if n == 1 {
        return MeanCi {
            mean,
            half_width: f64::INFINITY,
            std_dev: f64::NAN,
            n,
        };
    }
    let var = samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let std_dev = var.sqrt();
    MeanCi {
        mean,
        half_width: student_t_975(n - 1) * std_dev / (n as f64).sqrt(),
        std_dev,
        n,
    }
}

/// The 95 % interval of the mean per-run difference a_r − b_r (two methods
/// run on the same noise realisations). `None` if the lengths differ.
pub fn paired_difference_ci95(a: &[f64], b: &[f64]) -> Option<MeanCi> {
    if a.len() != b.len() {
        return None;
    }
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    Some(mean_ci95(&d))
}

// ---------------------------------------------------------------------------
// Single-target RMSE
// ---------------------------------------------------------------------------

/// Estimate minus truth at one scan.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StateError {
    pub position: [f64; 2],
    pub velocity: [f64; 2],
}

impl StateError {
    pub fn new(
        estimate_pos: [f64; 2],
        estimate_vel: [f64; 2],
        truth_pos: [f64; 2],
        truth_vel: [f64; 2],
    ) -> Self {
        StateError {
            position: [
                estimate_pos[0] - truth_pos[0],
                estimate_pos[1] - truth_pos[1],
            ],
            velocity: [
                estimate_vel[0] - truth_vel[0],
                estimate_vel[1] - truth_vel[1],
            ],
        }
    }
}

/// RMSE of one run (or, from [`rmse_against_time`], of one scan across runs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rmse {
    /// Per axis x, y (m).
    pub position: [f64; 2],
    /// Per axis (m/s).
    pub velocity: [f64; 2],
    /// Of the position error's length √(e_x² + e_y²) (m): the "distance
    /// between filtered and true position" of Liu et al. and He et al.
    pub position_distance: f64,
    /// Of the velocity error's length (m/s).
    pub velocity_distance: f64,
}

fn rmse_of<'a>(errors: impl Iterator<Item = &'a StateError>) -> Rmse {
    let mut sum = [0.0f64; 4];
    let mut n = 0usize;
    for e in errors {
        sum[0] += e.position[0].powi(2);
        sum[1] += e.position[1].powi(2);
        sum[2] += e.velocity[0].powi(2);
        sum[3] += e.velocity[1].powi(2);
        n += 1;
    }
    let m = sum.map(|s| {
        if n == 0 {
            f64::NAN
        } else {
            (s / n as f64).sqrt()
        }
    });
    Rmse {
        position: [m[0], m[1]],
        velocity: [m[2], m[3]],
        position_distance: m[0].hypot(m[1]),
        velocity_distance: m[2].hypot(m[3]),
    }
}

/// Al-Wagih & Abdulla eq. (26) per axis over one run's scored scans.
pub fn run_rmse(errors: &[StateError]) -> Rmse {
    rmse_of(errors.iter())
}

/// Monte Carlo summary: mean per-run RMSE with 95 % intervals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RmseSummary {
    pub position: [MeanCi; 2],
    pub velocity: [MeanCi; 2],
    pub position_distance: MeanCi,
    pub velocity_distance: MeanCi,
    pub runs: usize,
}

/// Summarises runs (each a list of per-scan errors over its scored scans).
pub fn monte_carlo_rmse(runs: &[Vec<StateError>]) -> RmseSummary {
    let per_run: Vec<Rmse> = runs.iter().map(|r| run_rmse(r)).collect();
    let col = |f: &dyn Fn(&Rmse) -> f64| mean_ci95(&per_run.iter().map(f).collect::<Vec<_>>());
    RmseSummary {
        position: [col(&|r| r.position[0]), col(&|r| r.position[1])],
        velocity: [col(&|r| r.velocity[0]), col(&|r| r.velocity[1])],
        position_distance: col(&|r| r.position_distance),
        velocity_distance: col(&|r| r.velocity_distance),
        runs: runs.len(),
    }
}

/// RMSE at each scan index across runs: √(Σ_r e_{r,k}² / R_k), R_k the runs
/// that have scan k.
pub fn rmse_against_time(runs: &[Vec<StateError>]) -> Vec<Rmse> {
    let len = runs.iter().map(Vec::len).max().unwrap_or(0);
    (0..len)
        .map(|k| rmse_of(runs.iter().filter_map(|r| r.get(k))))
        .collect()
}

// ---------------------------------------------------------------------------
// Optimal assignment
// ---------------------------------------------------------------------------

/// Minimum-cost assignment of rows to columns (Hungarian method, the
/// O(n²m) shortest-augmenting-path form with potentials). Any shape: every
/// row is assigned when rows ≤ columns, otherwise every column. Returns, per
/// row, its column. Costs must be finite.
pub fn assignment(cost: &[Vec<f64>]) -> Vec<Option<usize>> {
    let rows = cost.len();
    let cols = cost.first().map_or(0, Vec::len);
    if rows == 0 || cols == 0 {
        return vec![None; rows];
    }
    if rows > cols {
        let t: Vec<Vec<f64>> = (0..cols)
            .map(|j| (0..rows).map(|i| cost[i][j]).collect())
            .collect();
        let by_col = assignment(&t);
        let mut out = vec![None; rows];
        for (j, i) in by_col.iter().enumerate() {
            if let Some(i) = *i {
                out[i] = Some(j);
            }
        }
        return out;
    }
    // 1-based arrays as in the classical formulation; row 0 / column 0 are
    // the virtual start.
    let (n, m) = (rows, cols);
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; m + 1];
    let mut p = vec![0usize; m + 1]; // p[j]: row matched to column j
    let mut way = vec![0usize; m + 1];
    for i in 1..=n {
        p[0] = i;
        let mut j0 = 0usize;
        let mut minv = vec![f64::INFINITY; m + 1];
        let mut used = vec![false; m + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = f64::INFINITY;
            let mut j1 = 0usize;
            for j in 1..=m {
                if !used[j] {
                    let cur = cost[i0 - 1][j - 1] - u[i0] - v[j];
                    if cur < minv[j] {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=m {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if p[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut out = vec![None; n];
    for j in 1..=m {
        if p[j] != 0 {
            out[p[j] - 1] = Some(j - 1);
        }
    }
    out
}

// ---------------------------------------------------------------------------
// OSPA
// ---------------------------------------------------------------------------

/// OSPA distance and its two parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ospa {
    /// d_p^(c)(X, Y) (m).
    pub distance: f64,
    /// Localisation part: ((1/n)·min_π Σ d^(c)(x_i, y_π(i))^p)^(1/p).
    pub localisation: f64,
    /// Cardinality part: ((1/n)·c^p·(n − m))^(1/p).
    pub cardinality: f64,
}

/// Optimal sub-pattern assignment distance (Schuhmacher, Vo & Vo, "A
/// consistent metric for performance evaluation of multi-object filters",
/// IEEE TSP 56(8), 2008, eq. 3) between point sets X (m points) and Y
/// (n points), m ≤ n after swapping:
///
/// d_p^(c)(X, Y) = ( (1/n)·( min_π Σ_{i=1}^{m} d^(c)(x_i, y_π(i))^p + c^p·(n − m) ) )^(1/p),
///
/// with d^(c)(x, y) = min(c, ‖x − y‖), cut-off c > 0, order p ≥ 1; the
/// minimum over assignments is found with [`assignment`]. Both sets empty:
/// 0; exactly one empty: c. Distance^p = localisation^p + cardinality^p.
pub fn ospa(x: &[[f64; 2]], y: &[[f64; 2]], cutoff: f64, order: f64) -> Ospa {
    let (small, large) = if x.len() <= y.len() { (x, y) } else { (y, x) };
    let (m, n) = (small.len(), large.len());
    if n == 0 {
        return Ospa {
            distance: 0.0,
            localisation: 0.0,
            cardinality: 0.0,
        };
    }
    let cost: Vec<Vec<f64>> = small
        .iter()
        .map(|a| {
            large
                .iter()
                .map(|b| ((a[0] - b[0]).hypot(a[1] - b[1])).min(cutoff).powf(order))
                .collect()
        })
        .collect();
    let assigned = assignment(&cost);
    let loc_sum: f64 = assigned
        .iter()
        .enumerate()
        .filter_map(|(i, j)| j.map(|j| cost[i][j]))
        .sum();
    let card_sum = cutoff.powf(order) * (n - m) as f64;
    let nf = n as f64;
    Ospa {
        distance: ((loc_sum + card_sum) / nf).powf(1.0 / order),
        localisation: (loc_sum / nf).powf(1.0 / order),
        cardinality: (card_sum / nf).powf(1.0 / order),
    }
}

// ---------------------------------------------------------------------------
// Track-level metrics
// ---------------------------------------------------------------------------

/// A true target's position at one scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruthPoint {
    pub id: u32,
    pub x: f64,
    pub y: f64,
}

/// Lifecycle status of a reported track (the `status` column of
/// `replay --tracker`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrackStatus {
    Tentative,
    Confirmed,
    Coasting,
}

impl TrackStatus {
    /// Confirmed or coasting: shown to the consumer, so scored.
    pub fn is_established(self) -> bool {
        matches!(self, TrackStatus::Confirmed | TrackStatus::Coasting)
    }
}

impl std::str::FromStr for TrackStatus {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "tentative" => Ok(TrackStatus::Tentative),
            "confirmed" => Ok(TrackStatus::Confirmed),
            "coasting" => Ok(TrackStatus::Coasting),
            other => Err(format!(
                "unknown track status '{other}' (tentative|confirmed|coasting)"
            )),
        }
    }
}

/// A reported track at one scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackPoint {
    pub id: u32,
    pub status: TrackStatus,
    pub x: f64,
    pub y: f64,
}

/// Truth and tracker output at one scan time.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanReport {
    pub t: f64,
    pub truth: Vec<TruthPoint>,
    pub tracks: Vec<TrackPoint>,
}

/// OSPA between the truth and the established tracks at every scan.
pub fn ospa_against_time(scans: &[ScanReport], cutoff: f64, order: f64) -> Vec<(f64, Ospa)> {
    scans
        .iter()
        .map(|s| {
            let truth: Vec<[f64; 2]> = s.truth.iter().map(|p| [p.x, p.y]).collect();
            let tracks: Vec<[f64; 2]> = s
                .tracks
                .iter()
                .filter(|t| t.status.is_established())
                .map(|t| [t.x, t.y])
                .collect();
            (s.t, ospa(&truth, &tracks, cutoff, order))
        })
        .collect()
}

/// Per true target.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetMetrics {
    pub target: u32,
    /// Scans in which the target is in the truth.
    pub scans_present: usize,
    /// Scans in which an established track is assigned to it.
    pub scans_tracked: usize,
    /// scans_tracked / scans_present.
    pub completeness: f64,
    /// Times the assigned track id differs from the previously assigned one
    /// (scans without an assignment are skipped, so losing a track and
    /// re-acquiring it under the same id is not a change).
    pub id_changes: usize,
    /// Distinct track ids assigned, in order of first assignment.
    pub track_ids: Vec<u32>,
    /// Time from the target's first scan in the truth to the first scan an
    /// established track is assigned to it; `None` if never.
    pub latency_to_confirm_s: Option<f64>,
    /// Scans in which the target is in the truth, from its first assignment
    /// on (that scan included): the continuity's denominator.
    pub scans_present_since_first_assignment: usize,
}

/// An established track never assigned to any target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FalseTrack {
    pub id: u32,
    /// First and last scan times at which it was established.
    pub first_t: f64,
    pub last_t: f64,
    /// Number of scans it was established.
    pub scans: usize,
}

impl FalseTrack {
    /// last_t − first_t (0 for a track established in one scan only).
    pub fn duration_s(&self) -> f64 {
        self.last_t - self.first_t
    }
}

/// Track-level metrics of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackMetrics {
    /// Sorted by target id.
    pub targets: Vec<TargetMetrics>,
    /// Sorted by track id.
    pub false_tracks: Vec<FalseTrack>,
    /// Σ scans_tracked / Σ scans_present over all targets (time-averaged
    /// completeness); NaN with no truth.
    pub completeness: f64,
    /// Σ id_changes over targets.
    pub id_changes: usize,
    /// Established (track, scan) pairs not assigned to any target: false
    /// tracks plus true tracks momentarily outside the assignment gate.
    pub unassigned_track_scans: usize,
    /// Distinct track ids that were established at some scan.
    pub established_tracks: usize,
    /// Σ scans_tracked / Σ scans_present_since_first_assignment: how much
    /// of a target's life is tracked once it has been picked up; NaN if no
    /// target was ever assigned.
    pub continuity: f64,
    /// √(Σ d²/K) over the K assigned (target, track) pairs of every scan, d
    /// their distance (m); NaN with no pair.
    pub assigned_rmse: f64,
    /// Established track ids assigned to a target in fewer than half of the
    /// scans in which they were established (a superset of
    /// [`Self::false_tracks`]' ids), ascending.
    pub mostly_unassigned_tracks: Vec<u32>,
}

impl TrackMetrics {
    /// Total scans of false tracks and the mean false-track duration (s).
    pub fn false_track_time(&self) -> (usize, Option<f64>) {
        let scans = self.false_tracks.iter().map(|f| f.scans).sum();
        let mean = (!self.false_tracks.is_empty()).then(|| {
            self.false_tracks
                .iter()
                .map(FalseTrack::duration_s)
                .sum::<f64>()
                / self.false_tracks.len() as f64
        });
        (scans, mean)
    }
}

/// Track-to-truth assignment at each scan, then the per-target and
/// false-track statistics of one run.
///
/// At every scan the established tracks are assigned to the present targets
/// by the assignment minimising Σ min(‖track − truth‖, gate) (optimal, via
/// [`assignment`]); a pair at distance ≥ `gate` (m) is not an assignment.
/// With that:
/// * completeness, id changes and latency to confirm: see [`TargetMetrics`];
/// * a false track is an established track id that is assigned to no target
///   in any scan where it is established; its duration is from its first to
///   its last established scan ([`FalseTrack`]);
/// * continuity, the RMSE of the assigned pairs, and the tracks assigned in
///   under half of their established scans: see [`TrackMetrics`].
///
/// The minimised cost is clipped at the gate, so a pair beyond it costs the
/// same whichever it is and never displaces a pair inside it
/// ([`PairingCost::ClippedAtGate`]; [`track_metrics_with`] takes the other).
pub fn track_metrics(scans: &[ScanReport], gate: f64) -> TrackMetrics {
    track_metrics_with(scans, gate, PairingCost::ClippedAtGate)
}

/// What the per-scan assignment of [`track_metrics_with`] minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairingCost {
    /// Σ min(‖track − truth‖, gate).
    ClippedAtGate,
    /// Σ ‖track − truth‖ (pairs at or beyond the gate dropped afterwards):
    /// the real-data evaluation's definition, under which a far pair can
    /// displace a near one.
    Distance,
}

/// [`track_metrics`] with the assignment minimising `cost`.
pub fn track_metrics_with(scans: &[ScanReport], gate: f64, cost: PairingCost) -> TrackMetrics {
    let pairing_cost = cost;
    #[derive(Default)]
    struct TargetAcc {
        first_t: Option<f64>,
        present: usize,
        tracked: usize,
        last_id: Option<u32>,
        changes: usize,
        ids: Vec<u32>,
        first_tracked_t: Option<f64>,
        present_since_first_tracked: usize,
    }
    struct TrackAcc {
        first_t: f64,
        last_t: f64,
        scans: usize,
        assigned: usize,
    }
    let mut targets: BTreeMap<u32, TargetAcc> = BTreeMap::new();
    let mut tracks: BTreeMap<u32, TrackAcc> = BTreeMap::new();
    let mut unassigned_track_scans = 0usize;
    let (mut squared_distances, mut pairs) = (0.0f64, 0usize);

    for scan in scans {
        let est: Vec<&TrackPoint> = scan
            .tracks
            .iter()
            .filter(|t| t.status.is_established())
            .collect();
        let distance: Vec<Vec<f64>> = scan
            .truth
            .iter()
            .map(|p| est.iter().map(|t| (t.x - p.x).hypot(t.y - p.y)).collect())
            .collect();
        let assigned = match pairing_cost {
            PairingCost::Distance => assignment(&distance),
            PairingCost::ClippedAtGate => assignment(
                &distance
                    .iter()
                    .map(|row| row.iter().map(|d| d.min(gate)).collect())
                    .collect::<Vec<Vec<f64>>>(),
            ),
        };
        let mut track_used = vec![false; est.len()];
        for (i, p) in scan.truth.iter().enumerate() {
            let acc = targets.entry(p.id).or_default();
            acc.first_t.get_or_insert(scan.t);
            acc.present += 1;
            let Some(j) = assigned[i].filter(|&j| distance[i][j] < gate) else {
                if acc.first_tracked_t.is_some() {
                    acc.present_since_first_tracked += 1;
                }
                continue;
            };
            track_used[j] = true;
            let id = est[j].id;
            acc.tracked += 1;
            acc.present_since_first_tracked += 1;
            squared_distances += distance[i][j] * distance[i][j];
            pairs += 1;
            acc.first_tracked_t.get_or_insert(scan.t);
            if acc.last_id.is_some_and(|last| last != id) {
                acc.changes += 1;
            }
            acc.last_id = Some(id);
            if !acc.ids.contains(&id) {
                acc.ids.push(id);
            }
        }
        for (j, t) in est.iter().enumerate() {
            let acc = tracks.entry(t.id).or_insert(TrackAcc {
                first_t: scan.t,
                last_t: scan.t,
                scans: 0,
                assigned: 0,
            });
            acc.last_t = scan.t;
            acc.scans += 1;
            acc.assigned += usize::from(track_used[j]);
            if !track_used[j] {
                unassigned_track_scans += 1;
            }
        }
    }

    let (present, tracked) = targets
        .values()
        .fold((0usize, 0usize), |(p, t), a| (p + a.present, t + a.tracked));
    let present_since_first: usize = targets
        .values()
        .map(|a| a.present_since_first_tracked)
        .sum();
    let ratio = |n: usize, d: usize| {
        if d == 0 {
            f64::NAN
        } else {
            n as f64 / d as f64
        }
    };
    let target_metrics: Vec<TargetMetrics> = targets
        .into_iter()
        .map(|(id, a)| TargetMetrics {
            target: id,
            scans_present: a.present,
            scans_tracked: a.tracked,
            completeness: a.tracked as f64 / a.present as f64,
            id_changes: a.changes,
            track_ids: a.ids,
            latency_to_confirm_s: match (a.first_t, a.first_tracked_t) {
                (Some(f), Some(c)) => Some(c - f),
                _ => None,
            },
            scans_present_since_first_assignment: a.present_since_first_tracked,
        })
        .collect();
    TrackMetrics {
        id_changes: target_metrics.iter().map(|t| t.id_changes).sum(),
        targets: target_metrics,
        false_tracks: tracks
            .iter()
            .filter(|(_, a)| a.assigned == 0)
            .map(|(&id, a)| FalseTrack {
                id,
                first_t: a.first_t,
                last_t: a.last_t,
                scans: a.scans,
            })
            .collect(),
        completeness: ratio(tracked, present),
        unassigned_track_scans,
        established_tracks: tracks.len(),
        continuity: ratio(tracked, present_since_first),
        assigned_rmse: (squared_distances / pairs as f64).sqrt(),
        mostly_unassigned_tracks: tracks
            .iter()
            .filter(|(_, a)| 2 * a.assigned < a.scans)
            .map(|(&id, _)| id)
            .collect(),
    }
}

/// The mean over scans of [`ospa_against_time`].
pub fn mean_ospa(scans: &[ScanReport], cutoff: f64, order: f64) -> f64 {
    let per_scan = ospa_against_time(scans, cutoff, order);
    per_scan.iter().map(|(_, o)| o.distance).sum::<f64>() / per_scan.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn student_t_quantiles() {
        // Table values and known quantiles beyond the table (to 4 digits).
        assert!(close(student_t_975(1), 12.7062, 1e-4));
        assert!(close(student_t_975(10), 2.2281, 1e-4));
        assert!(close(student_t_975(30), 2.0423, 1e-4));
        assert!(close(student_t_975(31), 2.0395, 1e-4));
        assert!(close(student_t_975(40), 2.0211, 1e-4));
        assert!(close(student_t_975(60), 2.0003, 1e-4));
        assert!(close(student_t_975(99), 1.9842, 1e-4));
        assert!(close(student_t_975(120), 1.9799, 1e-4));
        assert!(close(student_t_975(199), 1.9720, 1e-4));
        assert!(close(student_t_975(1_000_000), 1.96, 1e-4));
        assert!(student_t_975(0).is_infinite());
    }

    #[test]
    fn mean_ci_by_hand() {
        // 1..5: mean 3, s² = (4+1+0+1+4)/4 = 2.5, s = 1.58114;
        // half-width = 2.776445·1.58114/√5 = 2.776445·0.707107 = 1.963243.
        let ci = mean_ci95(&[1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(ci.mean, 3.0);
        assert!(close(ci.std_dev, 2.5f64.sqrt(), 1e-12));
        assert!(close(ci.half_width, 1.963243, 1e-6));
        assert!(close(ci.lower(), 1.036757, 1e-6));
        assert!(mean_ci95(&[2.0]).half_width.is_infinite());
        assert!(mean_ci95(&[]).mean.is_nan());
        // Paired: a − b = [1, 1, 1, 1]: mean 1, zero width.
        let d = paired_difference_ci95(&[2.0, 3.0, 4.0, 5.0], &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!((d.mean, d.half_width), (1.0, 0.0));
        assert!(paired_difference_ci95(&[1.0], &[]).is_none());
        let lo = mean_ci95(&[1.0, 1.1, 0.9]);
        let hi = mean_ci95(&[5.0, 5.1, 4.9]);
        assert!(lo.significantly_below(&hi) && !hi.significantly_below(&lo));
    }

    #[test]
    fn rmse_by_hand() {
        // Position x errors 3, 4 → √((9+16)/2) = √12.5; y errors 0, 0;
        // velocity x 1, −1 → 1; y 2, 2 → 2. Distance RMSE √(12.5 + 0).
        let errs = vec![
            StateError::new([3.0, 0.0], [1.0, 2.0], [0.0, 0.0], [0.0, 0.0]),
            StateError::new([4.0, 0.0], [-1.0, 2.0], [0.0, 0.0], [0.0, 0.0]),
        ];
        let r = run_rmse(&errs);
        assert!(close(r.position[0], 12.5f64.sqrt(), 1e-12));
        assert_eq!(r.position[1], 0.0);
        assert_eq!(r.velocity, [1.0, 2.0]);
        assert!(close(r.velocity_distance, 5f64.sqrt(), 1e-12));
        // Two runs: per-run x RMSE √12.5 and 1 (errors [1, 1]).
        let runs = vec![
            errs.clone(),
            vec![StateError::new([1.0, 0.0], [0.0; 2], [0.0; 2], [0.0; 2]); 2],
        ];
        let s = monte_carlo_rmse(&runs);
        assert!(close(
            s.position[0].mean,
            (12.5f64.sqrt() + 1.0) / 2.0,
            1e-12
        ));
        assert_eq!(s.runs, 2);
        // Against time: scan 0 has x errors 3 and 1 → √((9+1)/2) = √5;
        // scan 1: 4 and 1 → √8.5.
        let t = rmse_against_time(&runs);
        assert!(close(t[0].position[0], 5f64.sqrt(), 1e-12));
        assert!(close(t[1].position[0], 8.5f64.sqrt(), 1e-12));
        // Ragged runs: scan 2 exists in one run only.
        let ragged = vec![
            vec![StateError::default(); 3],
            vec![StateError::default(); 2],
        ];
        assert_eq!(rmse_against_time(&ragged).len(), 3);
    }

    #[test]
    fn ospa_by_hand() {
        // X = {(0,0), (10,0)}, Y = {(1,0), (10,2), (50,50)}, c = 20.
        // Optimal: (0,0)–(1,0): 1; (10,0)–(10,2): 2; one unmatched: c.
        // p = 2: √((1 + 4 + 400)/3) = √135 = 11.61895;
        //   localisation √(5/3) = 1.29099, cardinality √(400/3) = 11.54701.
        // p = 1: (1 + 2 + 20)/3 = 7.66667.
        let x = [[0.0, 0.0], [10.0, 0.0]];
        let y = [[1.0, 0.0], [10.0, 2.0], [50.0, 50.0]];
        let o = ospa(&x, &y, 20.0, 2.0);
        assert!(close(o.distance, 135f64.sqrt(), 1e-12));
        assert!(close(o.localisation, (5.0f64 / 3.0).sqrt(), 1e-12));
        assert!(close(o.cardinality, (400.0f64 / 3.0).sqrt(), 1e-12));
        assert!(close(
            o.distance.powi(2),
            o.localisation.powi(2) + o.cardinality.powi(2),
            1e-9
        ));
        assert!(close(ospa(&x, &y, 20.0, 1.0).distance, 23.0 / 3.0, 1e-12));
        // Symmetric.
        assert_eq!(ospa(&y, &x, 20.0, 2.0), o);
        // Cut-off per pair: one point each, 100 m apart, c = 20 → 20.
        assert_eq!(
            ospa(&[[0.0, 0.0]], &[[100.0, 0.0]], 20.0, 1.0).distance,
            20.0
        );
        // Empty cases.
        assert_eq!(ospa(&[], &[], 20.0, 2.0).distance, 0.0);
        assert_eq!(ospa(&x, &[], 20.0, 2.0).distance, 20.0);
    }

    #[test]
    fn ospa_uses_the_optimal_not_the_greedy_assignment() {
        // On a line: x1 = 0, x2 = 2.1; y1 = 1, y2 = −2. Distances:
        // x1–y1 1, x1–y2 2, x2–y1 1.1, x2–y2 4.1. Greedy (closest pair first)
        // takes x1–y1 then x2–y2: 5.1. Optimal x1–y2 + x2–y1 = 3.1.
        // p = 1, c = 100: OSPA = 3.1/2 = 1.55.
        let o = ospa(
            &[[0.0, 0.0], [2.1, 0.0]],
            &[[1.0, 0.0], [-2.0, 0.0]],
            100.0,
            1.0,
        );
        assert!(close(o.distance, 1.55, 1e-12), "{o:?}");
    }

    #[test]
    fn hungarian_matches_brute_force() {
        use crate::noise::{rng_from_seed, uniform};
        fn brute(cost: &[Vec<f64>]) -> f64 {
            // rows ≤ cols: try every injective map.
            fn rec(cost: &[Vec<f64>], i: usize, used: &mut Vec<bool>) -> f64 {
                if i == cost.len() {
                    return 0.0;
                }
                let mut best = f64::INFINITY;
                for j in 0..used.len() {
                    if !used[j] {
                        used[j] = true;
                        best = best.min(cost[i][j] + rec(cost, i + 1, used));
                        used[j] = false;
                    }
                }
                best
            }
            rec(cost, 0, &mut vec![false; cost[0].len()])
        }
        let mut rng = rng_from_seed(11);
        for trial in 0..300 {
            let rows = 1 + trial % 5;
            let cols = rows + (trial / 5) % 3;
            let cost: Vec<Vec<f64>> = (0..rows)
                .map(|_| {
                    (0..cols)
                        .map(|_| uniform(&mut rng, 0.0, 10.0).floor())
                        .collect()
                })
                .collect();
            let a = assignment(&cost);
            let total: f64 = a.iter().enumerate().map(|(i, j)| cost[i][j.unwrap()]).sum();
            assert!(close(total, brute(&cost), 1e-9), "trial {trial}: {cost:?}");
            let mut cols_used: Vec<usize> = a.iter().map(|j| j.unwrap()).collect();
            cols_used.sort();
            cols_used.dedup();
            assert_eq!(cols_used.len(), rows);
            // Transposed shape gives the same total.
            let t: Vec<Vec<f64>> = (0..cols)
                .map(|j| (0..rows).map(|i| cost[i][j]).collect())
                .collect();
            let at = assignment(&t);
            let tt: f64 = at
                .iter()
                .enumerate()
                .filter_map(|(j, i)| i.map(|i| t[j][i]))
                .sum();
            assert!(close(tt, total, 1e-9));
            assert_eq!(at.iter().filter(|i| i.is_some()).count(), rows);
        }
        assert!(assignment(&[]).is_empty());
    }

    fn tp(id: u32, status: TrackStatus, x: f64, y: f64) -> TrackPoint {
        TrackPoint { id, status, x, y }
    }

    #[test]
    fn track_metrics_by_hand() {
        use TrackStatus::*;
        // Targets A (id 1) along y = 0 and B (id 2) along y = 100, x = 10·t.
        // Gate 50 m.
        // t=0: only tentative tracks → nothing tracked.
        // t=1: track 7 (confirmed) on A; nothing on B.
        // t=2: 7 on A, 8 on B; track 9 (confirmed) at (500, 500): false.
        // t=3: ids swap: 8 on A, 7 on B; 9 coasting at (510, 500).
        // t=4: 8 on A; B's track 7 is 80 m off (outside the gate): B not
        //      tracked, track 7 unassigned this scan (but not a false track:
        //      it was assigned before).
        // t=5: 8 on A, 7 back on B; 9 gone.
        let truth = |t: f64| {
            vec![
                TruthPoint {
                    id: 1,
                    x: 10.0 * t,
                    y: 0.0,
                },
                TruthPoint {
                    id: 2,
                    x: 10.0 * t,
                    y: 100.0,
                },
            ]
        };
        let scans = vec![
            ScanReport {
                t: 0.0,
                truth: truth(0.0),
                tracks: vec![tp(7, Tentative, 0.0, 0.0), tp(8, Tentative, 0.0, 100.0)],
            },
            ScanReport {
                t: 1.0,
                truth: truth(1.0),
                tracks: vec![tp(7, Confirmed, 11.0, 0.0), tp(8, Tentative, 10.0, 100.0)],
            },
            ScanReport {
                t: 2.0,
                truth: truth(2.0),
                tracks: vec![
                    tp(7, Confirmed, 20.0, 1.0),
                    tp(8, Confirmed, 20.0, 99.0),
                    tp(9, Confirmed, 500.0, 500.0),
                ],
            },
            ScanReport {
                t: 3.0,
                truth: truth(3.0),
                tracks: vec![
                    tp(8, Confirmed, 30.0, 2.0),
                    tp(7, Confirmed, 30.0, 98.0),
                    tp(9, Coasting, 510.0, 500.0),
                ],
            },
            ScanReport {
                t: 4.0,
                truth: truth(4.0),
                tracks: vec![tp(8, Confirmed, 40.0, 0.0), tp(7, Coasting, 40.0, 180.0)],
            },
            ScanReport {
                t: 5.0,
                truth: truth(5.0),
                tracks: vec![tp(8, Confirmed, 50.0, 0.0), tp(7, Confirmed, 50.0, 100.0)],
            },
        ];
        let m = track_metrics(&scans, 50.0);
        let a = &m.targets[0];
        let b = &m.targets[1];
        assert_eq!((a.target, b.target), (1, 2));
        // A: tracked at t = 1..5 (5 of 6); ids 7,7,8,8,8 → 1 change;
        // latency 1 s.
        assert_eq!((a.scans_present, a.scans_tracked, a.id_changes), (6, 5, 1));
        assert_eq!(a.track_ids, vec![7, 8]);
        assert_eq!(a.latency_to_confirm_s, Some(1.0));
        // B: tracked at t = 2, 3, 5 (3 of 6); ids 8, 7, 7 → 1 change;
        // latency 2 s.
        assert_eq!((b.scans_present, b.scans_tracked, b.id_changes), (6, 3, 1));
        assert_eq!(b.track_ids, vec![8, 7]);
        assert_eq!(b.latency_to_confirm_s, Some(2.0));
        assert!(close(b.completeness, 0.5, 1e-15));
        // Overall completeness (5 + 3)/12; 2 id changes.
        assert!(close(m.completeness, 8.0 / 12.0, 1e-15));
        assert_eq!(m.id_changes, 2);
        // One false track: 9, established at t = 2 and 3 → 2 scans, 1 s.
        assert_eq!(
            m.false_tracks,
            vec![FalseTrack {
                id: 9,
                first_t: 2.0,
                last_t: 3.0,
                scans: 2
            }]
        );
        assert_eq!(m.false_track_time(), (2, Some(1.0)));
        // Unassigned established track-scans: 9 at t=2,3 and 7 at t=4.
        assert_eq!(m.unassigned_track_scans, 3);
        assert_eq!(m.established_tracks, 3);
        // Continuity: A tracked 5 of the 5 scans from t = 1, B 3 of the 4
        // from t = 2 → 8/9.
        assert_eq!(
            (
                a.scans_present_since_first_assignment,
                b.scans_present_since_first_assignment
            ),
            (5, 4)
        );
        assert!(close(m.continuity, 8.0 / 9.0, 1e-15));
        // Assigned pairs' distances: t=1: 1; t=2: 1, 1; t=3: 2, 2;
        // t=4: 0 (B's track is beyond the gate); t=5: 0, 0 → √(11/8).
        assert!(close(m.assigned_rmse, (11.0f64 / 8.0).sqrt(), 1e-12));
        // Only 9 is assigned in under half of its established scans (0 of
        // 2); 7 in 4 of 5, 8 in 4 of 4.
        assert_eq!(m.mostly_unassigned_tracks, vec![9]);

        // OSPA at t = 4 (c = 100, p = 1): truth (40,0), (40,100); established
        // tracks (40,0), (40,180): 0 + 80 → 40. At t = 0 no established
        // track: c = 100.
        let o = ospa_against_time(&scans, 100.0, 1.0);
        assert!(close(o[4].1.distance, 40.0, 1e-12));
        assert_eq!(o[0].1.distance, 100.0);
    }

    #[test]
    fn a_track_assigned_in_under_half_its_scans_is_counted_not_at_half() {
        use TrackStatus::*;
        // One target at the origin. Track 5 is on it at t = 0, then 600 m
        // away (beyond the 500 m gate) at t = 1 and 2: assigned in 1 of 3
        // scans, so mostly unassigned but not a false track. Track 6 appears
        // at t = 1 on the target (assigned) and is 600 m off at t = 2: 1 of
        // 2, exactly half, not counted. The target: id 5, then 6 → 1 change;
        // tracked at t = 0, 1, not 2 → continuity 2/3.
        let truth = vec![TruthPoint {
            id: 1,
            x: 0.0,
            y: 0.0,
        }];
        let scan = |t: f64, tracks: Vec<TrackPoint>| ScanReport {
            t,
            truth: truth.clone(),
            tracks,
        };
        let scans = vec![
            scan(0.0, vec![tp(5, Confirmed, 3.0, 4.0)]),
            scan(
                1.0,
                vec![tp(5, Coasting, 600.0, 0.0), tp(6, Confirmed, 0.0, 6.0)],
            ),
            scan(
                2.0,
                vec![tp(5, Coasting, 0.0, 600.0), tp(6, Coasting, -600.0, 0.0)],
            ),
        ];
        let m = track_metrics(&scans, 500.0);
        assert_eq!(m.mostly_unassigned_tracks, vec![5]);
        assert!(m.false_tracks.is_empty());
        assert_eq!(m.id_changes, 1);
        assert!(close(m.completeness, 2.0 / 3.0, 1e-15));
        assert!(close(m.continuity, 2.0 / 3.0, 1e-15));
        // Pairs at 5 m and 6 m: √((25 + 36)/2).
        assert!(close(m.assigned_rmse, 30.5f64.sqrt(), 1e-12));
        // No pair at all: NaN, as the continuity.
        let none = track_metrics(&scans[..1], 1.0);
        assert!(none.assigned_rmse.is_nan() && none.continuity.is_nan());
    }

    #[test]
    fn the_unclipped_pairing_lets_a_far_pair_displace_a_near_one() {
        use TrackStatus::*;
        // Targets A (0, 0) and B (300, 0); tracks 1 at (200, 0) and 2 at
        // (10 km, 0); gate 500 m. Σ d: A–1 + B–2 = 200 + 9700 < A–2 + B–1 =
        // 10000 + 100, so A gets track 1 (B–2 is dropped). Clipped:
        // A–1 + B–2 = 200 + 500 > A–2 + B–1 = 500 + 100, so B gets it.
        let scans = vec![ScanReport {
            t: 0.0,
            truth: vec![
                TruthPoint {
                    id: 1,
                    x: 0.0,
                    y: 0.0,
                },
                TruthPoint {
                    id: 2,
                    x: 300.0,
                    y: 0.0,
                },
            ],
            tracks: vec![
                tp(1, Confirmed, 200.0, 0.0),
                tp(2, Confirmed, 10_000.0, 0.0),
            ],
        }];
        let tracked = |m: &TrackMetrics| -> Vec<usize> {
            m.targets.iter().map(|t| t.scans_tracked).collect()
        };
        let distance = track_metrics_with(&scans, 500.0, PairingCost::Distance);
        assert_eq!(tracked(&distance), vec![1, 0]);
        assert!(close(distance.assigned_rmse, 200.0, 1e-12));
        let clipped = track_metrics(&scans, 500.0);
        assert_eq!(tracked(&clipped), vec![0, 1]);
        assert!(close(clipped.assigned_rmse, 100.0, 1e-12));
    }

    #[test]
    fn mean_ospa_averages_every_scan() {
        use TrackStatus::*;
        // c = 1000, p = 2. t = 0: one target, no established track (a
        // tentative one does not count) → c. t = 1: a track 50 m off (3-4-5)
        // → 50. t = 2: nothing at all → 0. Mean (1000 + 50 + 0)/3 = 350.
        let target = TruthPoint {
            id: 1,
            x: 0.0,
            y: 0.0,
        };
        let scans = vec![
            ScanReport {
                t: 0.0,
                truth: vec![target],
                tracks: vec![tp(1, Tentative, 0.0, 0.0)],
            },
            ScanReport {
                t: 1.0,
                truth: vec![target],
                tracks: vec![tp(1, Confirmed, 30.0, 40.0)],
            },
            ScanReport {
                t: 2.0,
                truth: vec![],
                tracks: vec![],
            },
        ];
        assert!(close(mean_ospa(&scans, 1000.0, 2.0), 350.0, 1e-9));
    }

    #[test]
    fn a_target_never_tracked_has_no_latency() {
        let scans = vec![ScanReport {
            t: 3.0,
            truth: vec![TruthPoint {
                id: 4,
                x: 0.0,
                y: 0.0,
            }],
            tracks: vec![],
        }];
        let m = track_metrics(&scans, 10.0);
        assert_eq!(m.targets[0].latency_to_confirm_s, None);
        assert_eq!(m.completeness, 0.0);
        assert!(m.false_tracks.is_empty());
        assert!(track_metrics(&[], 10.0).completeness.is_nan());
        assert_eq!("coasting".parse::<TrackStatus>(), Ok(TrackStatus::Coasting));
        assert!("lost".parse::<TrackStatus>().is_err());
    }
}
