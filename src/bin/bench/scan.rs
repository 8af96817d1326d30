//! The track table's scan (issue 9's rows): `scan_separated` and
//! `scan_crowded`, N confirmed tracks in steady state and M = N
//! measurements per scan, with the scan's stages timed apart and the counts
//! the table reports.

use core::hint::black_box;

use abtrack::filter::Gains;
use abtrack::track::assign::{AssignmentSolver, FORBIDDEN};
use abtrack::track::{
    Association, FixedGainTrack, Gate, Measurement, Observation, ScanReport, TrackFilter,
    TrackTable, TrackerConfig,
};
use abtrack::Scalar;

use crate::counter::{Bench, Size};
use crate::numeric::Numeric;
use crate::synth::Lcg;

/// Scans timed per `scan_*` figure (one by one, averaged).
pub const TIMED_SCANS: u32 = 16;
/// Scans before the timing: initiation and confirmation of every track.
const WARM_UP_SCANS: u32 = 5;
/// Distance between separated targets, and between crowded clusters, m.
const APART_M: f64 = 2_000.0;
/// Distance between neighbours in a crowded cluster, m: inside a
/// steady-state gate (about 24 m in radius here), so neighbours' gates
/// overlap, and six times the noise bound, so the nearest measurement is
/// still each track's own.
const CROWDED_SPACING_M: f64 = 12.0;
/// Measurement noise: uniform in ± this, m.
const NOISE_M: f64 = 2.0;
/// Ground speed of every target, m/s (along x).
const SPEED_M_PER_S: f64 = 100.0;

/// Reads one count of a [`ScanReport`].
type ReportField = fn(&ScanReport) -> u32;

/// The scan's counts reported per scene, by name (the fields of
/// [`ScanReport`] of the last timed scan).
const REPORT_COUNTS: &[(&str, ReportField)] = &[
    ("measurements", |r| r.measurements),
    ("predicted", |r| r.predicted),
    ("gated_pairs", |r| r.gated_pairs),
    ("assigned", |r| r.assigned),
    ("solver_steps", |r| r.solver_steps),
    ("updated", |r| r.updated),
    ("coasted", |r| r.coasted),
    ("not_assigned", |r| r.not_assigned),
    ("outside_gates", |r| r.outside_gates),
    ("started", |r| r.started),
    ("deleted", |r| r.deleted),
    ("tracks", |r| r.tracks),
];

#[derive(Clone, Copy)]
enum Scene {
    /// N targets on a grid 2 km apart: every gate holds one measurement.
    Separated,
    /// Clusters of 4 to 8 targets, 12 m apart across the direction of
    /// flight, the clusters 2 km apart: neighbours' gates overlap.
    Crowded,
}

impl Scene {
    fn operation(self) -> &'static str {
        match self {
            Scene::Separated => "scan_separated",
            Scene::Crowded => "scan_crowded",
        }
    }

    /// The stage rows' operations: `<scene>/<stage>`.
    fn stage(self, stage: Stage) -> &'static str {
        match (self, stage) {
            (Scene::Separated, Stage::Predict) => "scan_separated/predict",
            (Scene::Separated, Stage::Gate) => "scan_separated/gate",
            (Scene::Separated, Stage::Assign) => "scan_separated/assign",
            (Scene::Separated, Stage::Update) => "scan_separated/update",
            (Scene::Crowded, Stage::Predict) => "scan_crowded/predict",
            (Scene::Crowded, Stage::Gate) => "scan_crowded/gate",
            (Scene::Crowded, Stage::Assign) => "scan_crowded/assign",
            (Scene::Crowded, Stage::Update) => "scan_crowded/update",
        }
    }

    /// Where target `i` of `targets` starts (it then flies along +x), m.
    fn start(self, i: usize, targets: usize) -> (f64, f64) {
        let grid = |cell: usize, cells: usize| {
            let side = 1 + libm::sqrt(cells as f64) as usize;
            (
                (cell % side) as f64 * APART_M,
                (cell / side) as f64 * APART_M,
            )
        };
        match self {
            Scene::Separated => grid(i, targets),
            Scene::Crowded => {
                let (cluster, member, clusters) = crowded_cluster(i, targets);
                let (x, y) = grid(cluster, clusters);
                (x, y + member as f64 * CROWDED_SPACING_M)
            }
        }
    }

    /// One measurement per target at scan `k` (1 s apart). The two scans
    /// of two-point initiation (k = 0, 1) are noise-free: the table pairs
    /// first and second points by sequential nearest neighbour, and in a
    /// crowded cluster a neighbour's second point is only 0.7 m farther than
    /// the target's own (12 m across, 100 m along), well inside the noise.
    /// With exact points every track starts on its own target; the scans
    /// measured come later.
    fn measurements<S: Scalar, const M: usize>(self, k: u32, rng: &mut Lcg) -> [Measurement<S>; M] {
        let t = k as f64;
        let noise = if k < 2 { 0.0 } else { NOISE_M };
        core::array::from_fn(|i| {
            let (x, y) = self.start(i, M);
            Measurement::Cartesian {
                x: S::from_f64_lossy(x + SPEED_M_PER_S * t + rng.uniform(-noise, noise)),
                y: S::from_f64_lossy(y + rng.uniform(-noise, noise)),
            }
        })
    }
}

/// The crowded scene's clusters: sizes 4, 5, 6, 7, 8, 4, … in turn, the
/// last two adjusted so that every cluster has 4 to 8 targets (8 targets:
/// one cluster; 16: 4 + 5 + 7). Returns (cluster of target `i`, its place in
/// the cluster, number of clusters).
fn crowded_cluster(i: usize, targets: usize) -> (usize, usize, usize) {
    let (mut first, mut remaining, mut cluster) = (0, targets, 0);
    let mut found = (0, 0);
    while remaining > 0 {
        let size = if remaining <= 8 {
            remaining
        } else {
            let turn = 4 + cluster % 5;
            if remaining - turn < 4 {
                remaining - 4
            } else {
                turn
            }
        };
        if (first..first + size).contains(&i) {
            found = (cluster, i - first);
        }
        first += size;
        remaining -= size;
        cluster += 1;
    }
    (found.0, found.1, cluster)
}

#[derive(Clone, Copy)]
enum Stage {
    Predict,
    Gate,
    Assign,
    Update,
}

type BenchTable<S, const N: usize, const M: usize> = TrackTable<S, FixedGainTrack<S>, N, M>;

#[inline(never)]
fn run_scan<S: Scalar, const N: usize, const M: usize>(
    table: &mut BenchTable<S, N, M>,
    config: &TrackerConfig<S, Gains<S>>,
    now_ms: u32,
    measurements: &[Measurement<S>; M],
    codes: &mut [Association; M],
) -> Option<ScanReport> {
    table.scan(config, now_ms, measurements, codes).ok()
}

/// Both scenes at N tracks, M measurements per scan.
#[inline(never)]
pub fn run<S: Numeric + Scalar, const N: usize, const M: usize>(bench: &mut Bench) {
    scene::<S, N, M>(bench, Scene::Separated);
    scene::<S, N, M>(bench, Scene::Crowded);
}

/// One scene in steady state: the whole `scan`, averaged over
/// [`TIMED_SCANS`] scans, then its stages timed apart by calling the same
/// library functions the scan calls (the track filters' `predict`,
/// `gate_region` and `GateRegion::cost`, the assignment solver, the
/// filters' `update`) on the table's tracks. The scan's other work (intake,
/// bookkeeping, lifecycle, initiation) is the difference.
#[inline(never)]
fn scene<S: Numeric + Scalar, const N: usize, const M: usize>(bench: &mut Bench, scene: Scene) {
    let numeric = S::LABEL;
    let operation = scene.operation();
    let size = Size { n: N, m: M };
    let (Some(gains), Ok(gate)) = (
        Gains::<S>::alpha_beta_f64(0.5, 0.2).ok(),
        Gate::uncertainty(
            S::from_f64_lossy(5.0),
            S::from_f64_lossy(13.8),
            S::from_f64_lossy(5.0),
        ),
    ) else {
        bench.fail(numeric, operation, "tracker configuration refused");
        return;
    };
    let Ok(config) = TrackerConfig::new(gains, gate, S::from_f64_lossy(300.0)) else {
        bench.fail(numeric, operation, "tracker configuration refused");
        return;
    };
    // A constant, copied into place: `new()` would build the table in its
    // own frame and copy it here, twice the table on the stack.
    let mut table = const { BenchTable::<S, N, M>::new() };
    let mut rng = Lcg::new(5);
    let mut codes = [Association::OutsideGates; M];
    let mut k = 0u32;
    while k < WARM_UP_SCANS {
        let m = scene.measurements::<S, M>(k, &mut rng);
        if run_scan(&mut table, &config, 1000 * k, &m, &mut codes).is_none() {
            bench.fail(numeric, operation, "warm-up scan refused");
            return;
        }
        k += 1;
    }
    if table.len() != N.min(M) || !table.tracks().all(|t| t.is_confirmed()) {
        defmt::error!("{=usize} tracks after warm-up", table.len());
        bench.fail(numeric, operation, "not every target has a confirmed track");
        return;
    }

    // Whole scans, timed one by one (the measurements made outside).
    let (mut scan_ticks, mut empty_ticks) = (0u32, 0u32);
    let mut last = ScanReport::default();
    for _ in 0..TIMED_SCANS {
        let m = scene.measurements::<S, M>(k, &mut rng);
        let now = 1000 * k;
        let mut report = None;
        let (Some(t), Some(e)) = (
            bench.time(|| {
                report = black_box(run_scan(
                    &mut table,
                    &config,
                    now,
                    black_box(&m),
                    &mut codes,
                ));
            }),
            bench.time(|| {
                black_box(black_box(&m));
            }),
        ) else {
            bench.fail(numeric, operation, "scan timing failed");
            return;
        };
        let Some(report) = report else {
            bench.fail(numeric, operation, "scan refused");
            return;
        };
        // Steady state: every track keeps its own measurement.
        let steady = report.updated as usize == N.min(M)
            && report.started == 0
            && report.deleted == 0
            && report.tracks as usize == N.min(M);
        if !steady {
            defmt::error!("{}", report);
            bench.fail(numeric, operation, "not in steady state");
            return;
        }
        scan_ticks += t;
        empty_ticks += e;
        last = report;
        k += 1;
    }
    let net = scan_ticks.saturating_sub(empty_ticks);
    bench.figure(
        numeric,
        operation,
        Some(size),
        bench.instructions(net) / TIMED_SCANS as f64,
    );
    for (name, count) in REPORT_COUNTS {
        bench.count(numeric, operation, size, name, count(&last));
    }

    // The stages on the table's tracks, at the next scan (predict and gate
    // read them in place; update works on a copy of each track, made inside
    // the timed loop).
    let dt = S::from_f64_lossy(1.0);
    let m = scene.measurements::<S, M>(k, &mut rng);
    let observations: [Option<Observation<S>>; M] = m.map(|x| Observation::new(x).ok());
    let mut predicted = [None; N];
    let predict = bench.time(|| {
        for (p, t) in predicted.iter_mut().zip(black_box(&table).tracks()) {
            *p = t.filter().predict(&gains, dt).ok();
        }
        black_box(&predicted);
    });
    let mut cost = [[FORBIDDEN; M]; N];
    let gate_ticks = bench.time(|| {
        let tracks = black_box(&table).tracks();
        for ((row, t), p) in cost.iter_mut().zip(tracks).zip(predicted.iter()) {
            let f = t.filter();
            let Some(region) = p.and_then(|p| f.gate_region(&gains, &p, dt, config.gate())) else {
                continue;
            };
            for (c, o) in row.iter_mut().zip(black_box(&observations).iter()) {
                if let Some(o) = o {
                    *c = region.cost(o).unwrap_or(FORBIDDEN);
                }
            }
        }
        black_box(&cost);
    });
    let mut solver = const { AssignmentSolver::<N, M>::new() };
    let mut solution = None;
    let assign = bench.time(|| {
        let c = black_box(&cost);
        solution = solver
            .solve(N, M, |r, col| {
                c.get(r)
                    .and_then(|row| row.get(col))
                    .copied()
                    .unwrap_or(FORBIDDEN)
            })
            .ok();
    });
    let assigned: [Option<usize>; N] = core::array::from_fn(|r| solver.col_for_row(r));
    let mut accepted = 0usize;
    let update = bench.time(|| {
        for (t, a) in black_box(&table).tracks().zip(assigned.iter()) {
            if let Some(Some(o)) = a.and_then(|c| observations.get(c)) {
                let mut f = *t.filter();
                if f.update(&gains, o, dt).is_ok() {
                    accepted += 1;
                }
                black_box(&f);
            }
        }
    });
    let empty = bench.time(|| {
        black_box(&table);
    });
    let (Some(p), Some(g), Some(a), Some(u), Some(e), Some(_)) =
        (predict, gate_ticks, assign, update, empty, solution)
    else {
        bench.fail(numeric, operation, "stage timing failed");
        return;
    };
    bench.check(
        accepted == N.min(M),
        numeric,
        operation,
        "stage updates refused",
    );
    for (stage, ticks) in [
        (Stage::Predict, p),
        (Stage::Gate, g),
        (Stage::Assign, a),
        (Stage::Update, u),
    ] {
        let instructions = bench.instructions(ticks.saturating_sub(e));
        bench.figure(numeric, scene.stage(stage), Some(size), instructions);
    }

    let clusters = Clusters::of(&cost);
    for (name, value) in [
        ("clusters", clusters.count),
        ("largest_cluster_tracks", clusters.largest),
        ("single_track_clusters", clusters.single),
    ] {
        bench.count(numeric, operation, size, name, value);
    }
    if let Scene::Crowded = scene {
        // The scene must be what it claims: overlapping gates.
        bench.check(
            clusters.largest >= 4,
            numeric,
            operation,
            "gates do not overlap",
        );
    }
}

/// The independent groups of the gated pairs: tracks joined when they
/// gate a common measurement (the groups an assignment could be split
/// into). Sizes in tracks.
struct Clusters {
    count: u32,
    largest: u32,
    single: u32,
}

impl Clusters {
    fn of<const N: usize, const M: usize>(cost: &[[u16; M]; N]) -> Self {
        let gated = |r: usize, c: usize| {
            cost.get(r)
                .and_then(|row| row.get(c))
                .is_some_and(|&v| v != FORBIDDEN)
        };
        // Label propagation: each track takes the smallest label of any
        // track it shares a measurement with, until nothing changes.
        let mut label: [usize; N] = core::array::from_fn(|r| r);
        let mut changed = true;
        while changed {
            changed = false;
            for c in 0..M {
                let lowest = (0..N)
                    .filter(|&r| gated(r, c))
                    .filter_map(|r| label.get(r))
                    .min();
                let Some(&lowest) = lowest else { continue };
                for r in (0..N).filter(|&r| gated(r, c)) {
                    if let Some(l) = label.get_mut(r) {
                        if *l != lowest {
                            *l = lowest;
                            changed = true;
                        }
                    }
                }
            }
        }
        let mut clusters = Clusters {
            count: 0,
            largest: 0,
            single: 0,
        };
        for root in 0..N {
            let in_gates = |r: &usize| (0..M).any(|c| gated(*r, c));
            let size = (0..N)
                .filter(|r| label.get(*r) == Some(&root))
                .filter(in_gates)
                .count() as u32;
            if size > 0 {
                clusters.count += 1;
                clusters.largest = clusters.largest.max(size);
                clusters.single += u32::from(size == 1);
            }
        }
        clusters
    }
}
