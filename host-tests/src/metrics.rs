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

/// A cost [`assignment`] refuses: not a finite number (a NaN or an
/// infinity orders no assignment, and the augmenting-path search would
/// never end on it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NonFiniteCost {
    pub row: usize,
    pub column: usize,
    pub value: f64,
}

impl std::fmt::Display for NonFiniteCost {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "assignment cost (row {}, column {}) is {}, not a finite number (a position that \
             is not finite?)",
            self.row, self.column, self.value
        )
    }
}

impl std::error::Error for NonFiniteCost {}

/// `Ok` if every cost is finite, else the first that is not (in row
/// order). The callers that clip their distances (min(d, c)) check them
/// before clipping: min(NaN, c) is c.
pub fn finite_costs(cost: &[Vec<f64>]) -> Result<(), NonFiniteCost> {
    for (row, costs) in cost.iter().enumerate() {
        if let Some((column, &value)) = costs.iter().enumerate().find(|(_, c)| !c.is_finite()) {
            return Err(NonFiniteCost { row, column, value });
        }
    }
    Ok(())
}

/// Minimum-cost assignment of rows to columns (Hungarian method, the
/// O(n²m) shortest-augmenting-path form with potentials). Any shape: every
/// row is assigned when rows ≤ columns, otherwise every column. Returns, per
/// row, its column; a cost that is not finite is refused (the first one, in
/// row order).
pub fn assignment(cost: &[Vec<f64>]) -> Result<Vec<Option<usize>>, NonFiniteCost> {
    finite_costs(cost)?;
    let rows = cost.len();
    let cols = cost.first().map_or(0, Vec::len);
    if rows == 0 || cols == 0 {
        return Ok(vec![None; rows]);
    }
    if rows > cols {
        let t: Vec<Vec<f64>> = (0..cols)
            .map(|j| (0..rows).map(|i| cost[i][j]).collect())
            .collect();
        let by_col = assignment(&t)?;
        let mut out = vec![None; rows];
        for (j, i) in by_col.iter().enumerate() {
            if let Some(i) = *i {
                out[i] = Some(j);
            }
        }
        return Ok(out);
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
    Ok(out)
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
/// A distance that is not finite (a position that is not), or a cost
/// d^(c)^p that is not (a cut-off or order that is not), is refused.
pub fn ospa(
    x: &[[f64; 2]],
    y: &[[f64; 2]],
    cutoff: f64,
    order: f64,
) -> Result<Ospa, NonFiniteCost> {
    let (small, large) = if x.len() <= y.len() { (x, y) } else { (y, x) };
    let (m, n) = (small.len(), large.len());
    if n == 0 {
        return Ok(Ospa {
            distance: 0.0,
            localisation: 0.0,
            cardinality: 0.0,
        });
    }
    let distance: Vec<Vec<f64>> = small
        .iter()
        .map(|a| {
            large
                .iter()
                .map(|b| (a[0] - b[0]).hypot(a[1] - b[1]))
                .collect()
        })
        .collect();
    finite_costs(&distance)?;
    let cost: Vec<Vec<f64>> = distance
        .iter()
        .map(|row| row.iter().map(|d| d.min(cutoff).powf(order)).collect())
        .collect();
    let assigned = assignment(&cost)?;
    let loc_sum: f64 = assigned
        .iter()
        .enumerate()
        .filter_map(|(i, j)| j.map(|j| cost[i][j]))
        .sum();
    let card_sum = cutoff.powf(order) * (n - m) as f64;
    let nf = n as f64;
    Ok(Ospa {
        distance: ((loc_sum + card_sum) / nf).powf(1.0 / order),
        localisation: (loc_sum / nf).powf(1.0 / order),
        cardinality: (card_sum / nf).powf(1.0 / order),
    })
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
pub fn ospa_against_time(
    scans: &[ScanReport],
    cutoff: f64,
    order: f64,
) -> Result<Vec<(f64, Ospa)>, NonFiniteCost> {
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
            Ok((s.t, ospa(&truth, &tracks, cutoff, order)?))
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
pub struct NeverPairedTrack {
    pub id: u32,
    /// First and last scan times at which it was established.
    pub first_t: f64,
    pub last_t: f64,
    /// Number of scans it was established.
    pub scans: usize,
}

impl NeverPairedTrack {
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
    /// The established tracks never assigned to a target, sorted by track
    /// id.
    pub never_paired: Vec<NeverPairedTrack>,
    /// Σ scans_tracked / Σ scans_present over all targets (time-averaged
    /// completeness); NaN with no truth.
    pub completeness: f64,
    /// Σ id_changes over targets.
    pub id_changes: usize,
    /// Established (track, scan) pairs not assigned to any target: tracks
    /// on no target plus true tracks momentarily outside the assignment
    /// gate.
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
    /// [`Self::never_paired`]' ids), ascending.
    pub mostly_unassigned_tracks: Vec<u32>,
    /// Every assigned (target, track) pair: its scan time, the target and
    /// their distance (m), in scan order (what [`Self::assigned_rmse`] is
    /// formed from).
    pub pairs: Vec<PairedPoint>,
}

/// One assigned (target, track) pair of a scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairedPoint {
    /// The scan's time (s).
    pub t: f64,
    /// The target's id.
    pub target: u32,
    /// The paired track's id.
    pub track: u32,
    /// The distance from the track to the target (m).
    pub distance: f64,
}

/// The identity changes among `pairs` (a target's paired track changes
/// between two of its paired scans) where, after the first of those scans
/// and up to the second, the old track was updated (status
/// [`TrackStatus::Confirmed`] in `scans`, which are in time order) to a
/// position more than `far` m from the target: it took a plot from
/// elsewhere (clutter or another target's). Meaningful for a tracker whose
/// output tells updates from coasting.
pub fn id_changes_after_far_updates(
    scans: &[ScanReport],
    pairs: &[PairedPoint],
    far: f64,
) -> usize {
    let mut by_target: BTreeMap<u32, Vec<&PairedPoint>> = BTreeMap::new();
    for p in pairs {
        by_target.entry(p.target).or_default().push(p);
    }
    let far_update = |target: u32, track: u32, after: f64, until: f64| {
        let first = scans.partition_point(|s| s.t <= after);
        scans[first..].iter().take_while(|s| s.t <= until).any(|s| {
            let truth = s.truth.iter().find(|p| p.id == target);
            let updated = s
                .tracks
                .iter()
                .find(|t| t.id == track && t.status == TrackStatus::Confirmed);
            matches!((truth, updated), (Some(p), Some(t)) if (t.x - p.x).hypot(t.y - p.y) > far)
        })
    };
    by_target
        .values()
        .flat_map(|pairs| pairs.windows(2))
        .filter(|w| w[0].track != w[1].track && far_update(w[0].target, w[0].track, w[0].t, w[1].t))
        .count()
}

/// The RMSE of each of two runs' pairs over the (scan, target) points both
/// paired, and the number of those points: two trackers' accuracy on the
/// same truth, apart from what each covers. `None` without a common point.
pub fn common_rmse(a: &[PairedPoint], b: &[PairedPoint]) -> Option<(f64, f64, usize)> {
    let key = |p: &PairedPoint| ((p.t * 1000.0).round() as i64, p.target);
    let in_b: BTreeMap<(i64, u32), f64> = b.iter().map(|p| (key(p), p.distance)).collect();
    let (mut sa, mut sb, mut n) = (0.0f64, 0.0f64, 0usize);
    for p in a {
        if let Some(d) = in_b.get(&key(p)) {
            sa += p.distance * p.distance;
            sb += d * d;
            n += 1;
        }
    }
    (n > 0).then(|| ((sa / n as f64).sqrt(), (sb / n as f64).sqrt(), n))
}

impl TrackMetrics {
    /// Total scans of the tracks never paired and their mean duration (s).
    pub fn never_paired_time(&self) -> (usize, Option<f64>) {
        let scans = self.never_paired.iter().map(|f| f.scans).sum();
        let mean = (!self.never_paired.is_empty()).then(|| {
            self.never_paired
                .iter()
                .map(NeverPairedTrack::duration_s)
                .sum::<f64>()
                / self.never_paired.len() as f64
        });
        (scans, mean)
    }
}

/// Track-to-truth assignment at each scan, then the per-target and
/// never-paired-track statistics of one run.
///
/// At every scan the established tracks are assigned to the present targets
/// by the assignment minimising Σ min(‖track − truth‖, gate) (optimal, via
/// [`assignment`]); a pair farther apart than `gate` (m) is not an assignment.
/// With that:
/// * completeness, id changes and latency to confirm: see [`TargetMetrics`];
/// * a track never paired is an established track id that is assigned to
///   no target in any scan where it is established; its duration is from
///   its first to its last established scan ([`NeverPairedTrack`]);
/// * continuity, the RMSE of the assigned pairs, and the tracks assigned in
///   under half of their established scans: see [`TrackMetrics`].
///
/// The minimised cost is clipped at the gate, so a pair beyond it costs the
/// same whichever it is and never displaces a pair inside it
/// ([`PairingCost::ClippedAtGate`]; [`track_metrics_with`] takes the other).
pub fn track_metrics(scans: &[ScanReport], gate: f64) -> Result<TrackMetrics, NonFiniteCost> {
    track_metrics_with(scans, gate, PairingCost::ClippedAtGate)
}

/// What the per-scan assignment of [`track_metrics_with`] minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairingCost {
    /// Σ min(‖track − truth‖, gate).
    ClippedAtGate,
    /// Σ ‖track − truth‖ (pairs beyond the gate dropped afterwards):
    /// the real-data evaluation's definition, under which a far pair can
    /// displace a near one.
    Distance,
}

/// [`track_metrics`] with the assignment minimising `cost`. A distance
/// that is not finite (a position that is not) is refused, under either
/// cost.
pub fn track_metrics_with(
    scans: &[ScanReport],
    gate: f64,
    cost: PairingCost,
) -> Result<TrackMetrics, NonFiniteCost> {
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
    let mut paired: Vec<PairedPoint> = Vec::new();

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
        finite_costs(&distance)?;
        let assigned = match pairing_cost {
            PairingCost::Distance => assignment(&distance)?,
            PairingCost::ClippedAtGate => assignment(
                &distance
                    .iter()
                    .map(|row| row.iter().map(|d| d.min(gate)).collect())
                    .collect::<Vec<Vec<f64>>>(),
            )?,
        };
        let mut track_used = vec![false; est.len()];
        for (i, p) in scan.truth.iter().enumerate() {
            let acc = targets.entry(p.id).or_default();
            acc.first_t.get_or_insert(scan.t);
            acc.present += 1;
            let Some(j) = assigned[i].filter(|&j| distance[i][j] <= gate) else {
                if acc.first_tracked_t.is_some() {
                    acc.present_since_first_tracked += 1;
                }
                continue;
            };
            track_used[j] = true;
            let id = est[j].id;
            acc.tracked += 1;
            acc.present_since_first_tracked += 1;
            paired.push(PairedPoint {
                t: scan.t,
                target: p.id,
                track: id,
                distance: distance[i][j],
            });
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
    Ok(TrackMetrics {
        id_changes: target_metrics.iter().map(|t| t.id_changes).sum(),
        targets: target_metrics,
        never_paired: tracks
            .iter()
            .filter(|(_, a)| a.assigned == 0)
            .map(|(&id, a)| NeverPairedTrack {
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
        assigned_rmse: (paired.iter().map(|p| p.distance * p.distance).sum::<f64>()
            / paired.len() as f64)
            .sqrt(),
        mostly_unassigned_tracks: tracks
            .iter()
            .filter(|(_, a)| 2 * a.assigned < a.scans)
            .map(|(&id, _)| id)
            .collect(),
        pairs: paired,
    })
}

/// The mean over scans of [`ospa_against_time`].
pub fn mean_ospa(scans: &[ScanReport], cutoff: f64, order: f64) -> Result<f64, NonFiniteCost> {
    let per_scan = ospa_against_time(scans, cutoff, order)?;
    Ok(per_scan.iter().map(|(_, o)| o.distance).sum::<f64>() / per_scan.len() as f64)
}
