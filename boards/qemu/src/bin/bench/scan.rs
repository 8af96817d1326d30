//! The track table's scan (the benchmark's scan rows): `scan_separated` and
//! `scan_crowded` with fixed gains (`FixedGainTrack`), `scan_default_separated`
//! and `scan_default_crowded` with the tracker's default filter
//! (`DefaultCartesianTrack`), N confirmed tracks in steady state and M = N
//! measurements per scan, with the scan's stages timed inside the scan
//! (`TrackTable::scan_with_probe`), the counts the table reports and the
//! sizes of the clusters of the gated pairs.

use core::hint::black_box;

use abtrack::filter::Gains;
use abtrack::gain::{AutoConfig, AutoGains};
use abtrack::num::Quantity;
use abtrack::track::ScanInterval;
use abtrack::track::{
    defaults::DefaultCartesianTrack, Association, FixedGainTrack, Gate, Measurement, Observation,
    ScanReport, ScanStage, TrackFilter, TrackTable, TrackerConfig,
};
use abtrack::Numeric;
use cortex_m::peripheral::SYST;

use crate::counter::{Bench, Size};
use crate::numeric::BenchNumber;

/// The scan rows in `S`, one line per size (each a table type of its own,
/// with its own code). The micro:bit's 16 KiB of RAM hold the table (on
/// the stack) up to 32 × 32 in the fast fixed point, and 64 tracks with 32
/// measurements a scan (11,480 bytes; 64 × 64 is 15,480, the whole RAM);
/// with the default filter up to 32 × 32 (9,336 bytes; `docs/track-table.md`
/// gives the formulas): its 64 × 32 table is 14,552 bytes (64 slots of 92
/// bytes where the fixed-gain one has 60, and what each track's gate keeps
/// for its update), and with the scan's own
/// frames it overflows the 16,224-byte stack (measured: the benchmark's
/// hard-fault report). The default filter's rows stop at 64 × 64 (the
/// sizes the cost targets are set for). The test command's smoke image
/// (feature `bench-smoke`) keeps each filter's smallest and largest size.
#[inline(never)]
pub fn sizes<S: BenchNumber>(bench: &mut Bench) {
    run::<S, FixedGainTrack<S>, 8, 8>(bench);
    #[cfg(not(feature = "bench-smoke"))]
    {
        run::<S, FixedGainTrack<S>, 16, 16>(bench);
        run::<S, FixedGainTrack<S>, 32, 32>(bench);
    }
    #[cfg(abtrack_board = "microbit")]
    run::<S, FixedGainTrack<S>, 64, 32>(bench);
    #[cfg(not(abtrack_board = "microbit"))]
    {
        #[cfg(not(feature = "bench-smoke"))]
        {
            run::<S, FixedGainTrack<S>, 64, 64>(bench);
            run::<S, FixedGainTrack<S>, 128, 128>(bench);
        }
        run::<S, FixedGainTrack<S>, 256, 256>(bench);
    }
    // The micro:bit's full image leaves out the default filter's smallest
    // size for its flash (its smoke image keeps it).
    #[cfg(any(feature = "bench-smoke", not(abtrack_board = "microbit")))]
    run::<S, DefaultCartesianTrack<S>, 8, 8>(bench);
    #[cfg(not(feature = "bench-smoke"))]
    run::<S, DefaultCartesianTrack<S>, 16, 16>(bench);
    #[cfg(any(not(feature = "bench-smoke"), abtrack_board = "microbit"))]
    run::<S, DefaultCartesianTrack<S>, 32, 32>(bench);
    #[cfg(not(abtrack_board = "microbit"))]
    run::<S, DefaultCartesianTrack<S>, 64, 64>(bench);
}

/// A filter of the scan rows: its configuration and its rows' names.
pub trait BenchFilter<S: Numeric>: TrackFilter<S> {
    /// The rows of the separated and the crowded scene.
    const ROWS: [Rows; 2];
    /// The filter's parameters in the scenes.
    fn params() -> Option<Self::Params>;
}

/// The names of one scene's rows: the whole scan and each stage of
/// [`STAGES`].
pub struct Rows {
    scan: &'static str,
    stages: [&'static str; 8],
}

/// The rows of one scan operation: `<scan>` and `<scan>/<stage>`.
macro_rules! rows {
    ($scan:literal) => {
        Rows {
            scan: $scan,
            stages: [
                concat!($scan, "/intake"),
                concat!($scan, "/index"),
                concat!($scan, "/gate"),
                concat!($scan, "/cluster"),
                concat!($scan, "/assign"),
                concat!($scan, "/update"),
                concat!($scan, "/manage"),
                concat!($scan, "/initiate"),
            ],
        }
    };
}

/// The fixed-gain rows' gains, α and β.
pub const FIXED_GAINS: (f64, f64) = (0.5, 0.2);

/// Fixed gains [`FIXED_GAINS`].
impl<S: Numeric> BenchFilter<S> for FixedGainTrack<S> {
    const ROWS: [Rows; 2] = [rows!("scan_separated"), rows!("scan_crowded")];
    fn params() -> Option<Gains<S>> {
        Gains::<S>::alpha_beta_f64(FIXED_GAINS.0, FIXED_GAINS.1).ok()
    }
}

/// The default filter (`auto`, the per-axis Kalman gains) for σ = 5 m, the
/// σ of the scenes' gate.
impl<S: Numeric> BenchFilter<S> for DefaultCartesianTrack<S> {
    const ROWS: [Rows; 2] = [
        rows!("scan_default_separated"),
        rows!("scan_default_crowded"),
    ];
    fn params() -> Option<AutoGains<S, 2>> {
        AutoGains::new(&AutoConfig::cartesian(GATE_SIGMA_M)).ok()
    }
}
use crate::synth::Lcg;

/// Scans timed per `scan_*` figure (one by one, averaged).
pub const TIMED_SCANS: u32 = 16;
/// Scans before the timing: initiation and confirmation of every track.
pub const WARM_UP_SCANS: u32 = 5;
/// Distance between separated targets, and between crowded clusters, m.
const APART_M: f64 = 2_000.0;
/// Distance between neighbours in a crowded cluster, m: inside a
/// steady-state gate (about 24 m in radius here), so neighbours' gates
/// overlap, and six times the noise bound, so the nearest measurement is
/// still each track's own.
const CROWDED_SPACING_M: f64 = 12.0;
/// σ of the gate (and of the default filter's sensor), m.
pub const GATE_SIGMA_M: f64 = 5.0;
/// The gate's threshold G on the normalised distance squared.
pub const GATE_THRESHOLD: f64 = 13.8;
/// The gate's manoeuvre allowance a_max, m/s² (½·a_max·T² added to a
/// fixed-gain track's radius).
pub const GATE_MAX_ACCELERATION_M_PER_S2: f64 = 5.0;
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
    ("candidates", |r| r.candidates),
    ("gated_pairs", |r| r.gated_pairs),
    ("uncached_tracks", |r| r.uncached_tracks),
    ("clusters", |r| r.clusters),
    ("single_pairs", |r| r.single_pairs),
    ("largest_cluster", |r| r.largest_cluster),
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

/// The scan's stages in the order `scan_with_probe` reports them (the
/// order of [`Rows::stages`]).
const STAGES: [ScanStage; 8] = [
    ScanStage::Intake,
    ScanStage::Index,
    ScanStage::Gate,
    ScanStage::Cluster,
    ScanStage::Assign,
    ScanStage::Update,
    ScanStage::Manage,
    ScanStage::Initiate,
];

/// Cluster sizes counted (tracks per cluster): the bounds of each class
/// and its counter's name.
const CLUSTER_CLASSES: [(u32, u32, &str); 4] = [
    (1, 1, "clusters_of_1"),
    (2, 3, "clusters_of_2_3"),
    (4, 8, "clusters_of_4_8"),
    (9, u32::MAX, "clusters_of_9_up"),
];

#[derive(Clone, Copy)]
pub enum Scene {
    /// N targets on a grid 2 km apart: every gate holds one measurement.
    Separated,
    /// Clusters of 4 to 8 targets, 12 m apart across the direction of
    /// flight, the clusters 2 km apart: neighbours' gates overlap.
    Crowded,
}

impl Scene {
    /// The scene's rows for filter `F`.
    fn rows<S: Numeric, F: BenchFilter<S>>(self) -> &'static Rows {
        match self {
            Scene::Separated => &F::ROWS[0],
            Scene::Crowded => &F::ROWS[1],
        }
    }

    /// Where target `i` of `targets` starts (it then flies along +x), m.
    fn start(self, i: usize, targets: usize) -> (f64, f64) {
        let grid = |cell: usize, cells: usize| {
            // Never 0: no division by zero.
            let side =
                core::num::NonZeroUsize::MIN.saturating_add(libm::sqrt(cells as f64) as usize);
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
    pub fn measurements<S: Numeric, const M: usize>(
        self,
        k: u32,
        rng: &mut Lcg,
    ) -> [Measurement<S>; M] {
        core::array::from_fn(|i| {
            let (x, y) = self.position(k, i, M, rng);
            Measurement::Cartesian {
                x: S::Length::from_f64_lossy(x),
                y: S::Length::from_f64_lossy(y),
            }
        })
    }

    /// Target `i` of `targets` as measured at scan `k` (x, y), m: each
    /// scan's targets in turn from one `rng` ([`Self::measurements`]).
    pub fn position(self, k: u32, i: usize, targets: usize, rng: &mut Lcg) -> (f64, f64) {
        let noise = if k < 2 { 0.0 } else { NOISE_M };
        let (x, y) = self.start(i, targets);
        (
            x + SPEED_M_PER_S * k as f64 + rng.uniform(-noise, noise),
            y + rng.uniform(-noise, noise),
        )
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

/// One scan; `marks[i]` gets SysTick's value as stage `STAGES[i]` ends.
#[inline(never)]
fn run_scan<S: Numeric, F: TrackFilter<S>, const N: usize, const M: usize>(
    table: &mut TrackTable<S, F, N, M>,
    config: &TrackerConfig<S, F::Params>,
    now_ms: u32,
    measurements: &[Measurement<S>; M],
    codes: &mut [Association; M],
    marks: &mut [u32; STAGES.len()],
) -> Option<ScanReport> {
    table
        .scan_with_probe(config, now_ms, measurements, codes, |stage| {
            if let Some(m) = marks.get_mut(stage as usize) {
                *m = SYST::get_current();
            }
        })
        .ok()
}

/// Both scenes at N tracks, M measurements per scan.
#[inline(never)]
fn run<S: BenchNumber, F: BenchFilter<S>, const N: usize, const M: usize>(bench: &mut Bench) {
    scene::<S, F, N, M>(bench, Scene::Separated);
    scene::<S, F, N, M>(bench, Scene::Crowded);
}

/// One scene in steady state: the whole `scan` and each of its stages,
/// averaged over [`TIMED_SCANS`] scans timed one by one (each stage from
/// SysTick read where the scan reports the stage's end); the counts of the
/// last scan; the sizes of the clusters of the gated pairs.
#[inline(never)]
fn scene<S: BenchNumber, F: BenchFilter<S>, const N: usize, const M: usize>(
    bench: &mut Bench,
    scene: Scene,
) {
    let numeric = S::LABEL;
    let rows = scene.rows::<S, F>();
    let operation = rows.scan;
    let size = Size { n: N, m: M };
    let (Some(params), Ok(gate)) = (
        F::params(),
        Gate::uncertainty(
            S::Length::from_f64_lossy(GATE_SIGMA_M),
            S::Ratio::from_f64_lossy(GATE_THRESHOLD),
            S::Acceleration::from_f64_lossy(GATE_MAX_ACCELERATION_M_PER_S2),
        ),
    ) else {
        bench.fail(numeric, operation, "tracker configuration refused");
        return;
    };
    let Ok(config) = TrackerConfig::new(params, gate, S::Speed::from_f64_lossy(300.0)) else {
        bench.fail(numeric, operation, "tracker configuration refused");
        return;
    };
    // A constant, copied into place: `new()` would build the table in its
    // own frame and copy it here, twice the table on the stack.
    let mut table = const { TrackTable::<S, F, N, M>::new() };
    let mut rng = Lcg::new(5);
    let mut codes = [Association::OutsideGates; M];
    let mut marks = [0u32; STAGES.len()];
    let mut k = 0u32;
    while k < WARM_UP_SCANS {
        let m = scene.measurements::<S, M>(k, &mut rng);
        if run_scan(&mut table, &config, 1000 * k, &m, &mut codes, &mut marks).is_none() {
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
    let mut stage_ticks = [0u32; STAGES.len()];
    let mut last = ScanReport::default();
    for _ in 0..TIMED_SCANS {
        let m = scene.measurements::<S, M>(k, &mut rng);
        let now = 1000 * k;
        let mut report = None;
        let mut start = 0u32;
        let (Some(t), Some(e)) = (
            bench.time(|| {
                start = SYST::get_current();
                report = black_box(run_scan(
                    &mut table,
                    &config,
                    now,
                    black_box(&m),
                    &mut codes,
                    &mut marks,
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
        // SysTick counts down: each stage is the previous mark minus its own.
        let mut previous = start;
        for (ticks, &mark) in stage_ticks.iter_mut().zip(marks.iter()) {
            *ticks += previous.saturating_sub(mark);
            previous = mark;
        }
        scan_ticks += t;
        empty_ticks += e;
        last = report;
        k += 1;
    }
    let net = scan_ticks.saturating_sub(empty_ticks);
    let per_scan = |ticks: u32| bench.instructions(ticks) / TIMED_SCANS as f64;
    let (scan, stages) = (per_scan(net), stage_ticks.map(per_scan));
    bench.figure(numeric, operation, Some(size), scan);
    for (stage, instructions) in rows.stages.iter().zip(stages.iter()) {
        bench.figure(numeric, stage, Some(size), *instructions);
    }
    for (name, count) in REPORT_COUNTS {
        bench.count(numeric, operation, size, name, count(&last));
    }

    // The clusters the next scan's gated pairs form, sized by the
    // benchmark from the public API (every pair tested, untimed).
    let m = scene.measurements::<S, M>(k, &mut rng);
    let sizes = ClusterSizes::<N>::of(&table, &config, &m);
    for (low, high, name) in CLUSTER_CLASSES {
        let n = sizes.count(low, high);
        bench.count(numeric, operation, size, name, n);
    }
    if let Scene::Crowded = scene {
        // The scene must be what it claims: overlapping gates.
        bench.check(
            last.largest_cluster >= 4,
            numeric,
            operation,
            "gates do not overlap",
        );
    }
}

/// Tracks per cluster of one scan's gated pairs: tracks joined when they
/// gate a common measurement (union–find, smallest slot the root).
struct ClusterSizes<const N: usize> {
    parent: [u16; N],
    gated: [bool; N],
}

impl<const N: usize> ClusterSizes<N> {
    fn of<S: Numeric, F: TrackFilter<S>, const M: usize>(
        table: &TrackTable<S, F, N, M>,
        config: &TrackerConfig<S, F::Params>,
        measurements: &[Measurement<S>; M],
    ) -> Self {
        let mut sizes = ClusterSizes {
            parent: core::array::from_fn(|t| t as u16),
            gated: [false; N],
        };
        let mut owner = [u16::MAX; M];
        let Some(dt) = ScanInterval::from_ms(1000).and_then(|i| F::step(config.params(), &i).ok())
        else {
            return sizes;
        };
        let observations = measurements.map(|z| Observation::new(z).ok());
        for (t, track) in table.tracks().enumerate() {
            let f = track.filter();
            let Some(region) = f
                .predict(config.params(), &dt)
                .ok()
                .and_then(|p| f.gate_region(config.params(), &p, &dt, config.gate()))
            else {
                continue;
            };
            for (o, first) in observations.iter().zip(owner.iter_mut()) {
                let Some(o) = o else { continue };
                if region.cost(o).is_none() {
                    continue;
                }
                if let Some(g) = sizes.gated.get_mut(t) {
                    *g = true;
                }
                if *first == u16::MAX {
                    *first = t as u16;
                } else {
                    let (a, b) = (sizes.find(t), sizes.find(*first as usize));
                    if let Some(p) = sizes.parent.get_mut(a.max(b)) {
                        *p = a.min(b) as u16;
                    }
                }
            }
        }
        sizes
    }

    fn find(&self, mut t: usize) -> usize {
        while let Some(&p) = self.parent.get(t) {
            if p as usize == t {
                break;
            }
            t = p as usize;
        }
        t
    }

    /// Clusters of `low ..= high` tracks.
    fn count(&self, low: u32, high: u32) -> u32 {
        let mut n = 0;
        for root in 0..N {
            if self.find(root) != root || !self.gated.get(root).copied().unwrap_or(false) {
                continue;
            }
            let tracks = (0..N)
                .filter(|&t| self.find(t) == root && self.gated.get(t).copied().unwrap_or(false))
                .count() as u32;
            n += u32::from(tracks >= low && tracks <= high);
        }
        n
    }
}
