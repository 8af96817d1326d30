//! The scan's equivalence: its pre-gate and per-cluster assignment
//! give, pair for pair (ties included), what the assignment solver gives on
//! the whole table's gated pairs, and that is optimal (a brute force).
//!
//! Three levels:
//! 1. the solver: each connected component of a random sparse cost matrix
//!    solved alone equals the whole matrix solved at once, pair for pair;
//! 2. the pre-gate: every observation a gate accepts lies in the gate's
//!    bounding box, for circles and range/azimuth windows in every type;
//! 3. the table: random separated and crowded scenes (duplicate targets and
//!    duplicate measurements make ties), the table's codes against the
//!    whole-table solve of the gated pairs computed through the public API,
//!    and against a brute force; also with the pair cache overflowing.

#![allow(clippy::needless_range_loop)]

use super::support;

use abtrack::num::fixed32::Fixed32;
use abtrack::track::assign::{AssignmentSolver, FORBIDDEN, MAX_COST};
use abtrack::track::ScanInterval;
use abtrack::track::{
    Association, FirstPoint, FixedGainTrack, GateRegion, Measurement, Observation, PairRule,
    ScanReport, TrackFilter, TrackId, TrackTable, TrackerConfig,
};
use abtrack::Fix;
use abtrack::Numeric;
use proptest::prelude::*;
use support::{cart, default_config, parked_config, q, Lcg, Parked, ParkedParams};

// ---------------------------------------------------------------------------
// 1. The solver: components solved apart = the whole solved at once.
// ---------------------------------------------------------------------------

/// Connected components of the allowed pairs: (rows, columns) of each, in
/// increasing order; rows and columns in no allowed pair are left out.
fn components(cost: &[Vec<u16>], n_cols: usize) -> Vec<(Vec<usize>, Vec<usize>)> {
    let n_rows = cost.len();
    // Nodes: rows 0..n_rows, columns n_rows.. .
    let mut parent: Vec<usize> = (0..n_rows + n_cols).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut linked = vec![false; n_rows + n_cols];
    for r in 0..n_rows {
        for c in 0..n_cols {
            if cost[r][c] != FORBIDDEN {
                let (a, b) = (find(&mut parent, r), find(&mut parent, n_rows + c));
                parent[a.max(b)] = a.min(b);
                linked[r] = true;
                linked[n_rows + c] = true;
            }
        }
    }
    let mut groups: Vec<(usize, Vec<usize>, Vec<usize>)> = Vec::new();
    for node in 0..n_rows + n_cols {
        if !linked[node] {
            continue;
        }
        let root = find(&mut parent, node);
        let g = match groups.iter().position(|g| g.0 == root) {
            Some(i) => i,
            None => {
                groups.push((root, Vec::new(), Vec::new()));
                groups.len() - 1
            }
        };
        if node < n_rows {
            groups[g].1.push(node);
        } else {
            groups[g].2.push(node - n_rows);
        }
    }
    groups.into_iter().map(|(_, r, c)| (r, c)).collect()
}

/// The whole problem's row → column map, and the same from its components
/// solved one by one.
fn whole_and_by_component(
    cost: &[Vec<u16>],
    n_cols: usize,
) -> (Vec<Option<usize>>, Vec<Option<usize>>) {
    let n_rows = cost.len();
    let mut solver: AssignmentSolver<12, 12> = AssignmentSolver::new();
    solver.solve(n_rows, n_cols, |r, c| cost[r][c]).unwrap();
    let whole: Vec<Option<usize>> = (0..n_rows).map(|r| solver.col_for_row(r)).collect();
    let mut parts = vec![None; n_rows];
    for (rows, cols) in components(cost, n_cols) {
        solver
            .solve(rows.len(), cols.len(), |r, c| cost[rows[r]][cols[c]])
            .unwrap();
        for (i, &r) in rows.iter().enumerate() {
            parts[r] = solver.col_for_row(i).map(|c| cols[c]);
        }
    }
    (whole, parts)
}

fn sparse_matrix() -> impl Strategy<Value = (Vec<Vec<u16>>, usize)> {
    (0usize..=12, 0usize..=12).prop_flat_map(|(n, m)| {
        // Mostly forbidden (several components), and few distinct costs
        // (many ties).
        let entry = prop_oneof![
            8 => Just(FORBIDDEN),
            3 => 0u16..=2,
            1 => 0u16..=MAX_COST,
        ];
        (
            proptest::collection::vec(proptest::collection::vec(entry, m), n),
            Just(m),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4000))]

    #[test]
    fn components_solved_apart_equal_the_whole((cost, n_cols) in sparse_matrix()) {
        let (whole, parts) = whole_and_by_component(&cost, n_cols);
        prop_assert_eq!(whole, parts);
    }
}

/// A hand-made tie: two rows, two columns, every cost equal, and a second
/// component beside it. The whole and the parts agree, and the rule picks
/// row 0 → column 0, row 1 → column 1.
#[test]
fn all_equal_costs_tie_the_same_way() {
    let f = FORBIDDEN;
    let cost = vec![
        vec![5, 5, f, f],
        vec![f, f, 7, 7],
        vec![5, 5, f, f],
        vec![f, f, 7, 7],
    ];
    let (whole, parts) = whole_and_by_component(&cost, 4);
    assert_eq!(whole, parts);
    assert_eq!(whole, vec![Some(0), Some(2), Some(1), Some(3)]);
}

// ---------------------------------------------------------------------------
// 2. The pre-gate's boxes hold every gated observation.
// ---------------------------------------------------------------------------

fn region_holds_gated<S: Numeric>(
    region: &GateRegion<S>,
    points: &[(f64, f64)],
) -> Result<usize, String> {
    let bounds = region.bounds();
    let mut inside = 0;
    for &(x, y) in points {
        let Ok(o) = Observation::new(cart::<S>(x, y)) else {
            continue;
        };
        if region.cost(&o).is_some() {
            inside += 1;
            if !bounds.contains(o.xy()) {
                return Err(format!(
                    "{}: ({x}, {y}) gated but outside {bounds:?} of {region:?}",
                    <S as abtrack::num::Numeric>::NAME
                ));
            }
        }
    }
    Ok(inside)
}

/// Points spread over and just around the region: uniform in a box of
/// `scale` times its size, and on its rim.
fn points_around(center: (f64, f64), size: f64, rng: &mut Lcg, scale: f64) -> Vec<(f64, f64)> {
    (0..200)
        .map(|i| {
            if i % 2 == 0 {
                (
                    center.0 + scale * size * rng.next_signed(),
                    center.1 + scale * size * rng.next_signed(),
                )
            } else {
                // Near the edge of a disc of radius `size`.
                let a = std::f64::consts::PI * rng.next_signed();
                let r = size * (1.0 + 1e-6 * rng.next_signed());
                (center.0 + r * a.cos(), center.1 + r * a.sin())
            }
        })
        .collect()
}

fn pregate_case<S: Numeric>(seed: u64) {
    let mut rng = Lcg(seed);
    let mut gated = 0;
    for _ in 0..40 {
        let center = (200_000.0 * rng.next_signed(), 200_000.0 * rng.next_signed());
        let radius = 10f64.powf(3.0 * rng.next_signed() + 1.5);
        if let Some(region) = GateRegion::<S>::circle([q(center.0), q(center.1)], q(radius)) {
            let pts = points_around(center, radius, &mut rng, 1.2);
            gated += region_holds_gated(&region, &pts).unwrap();
        }
        let along = 10f64.powf(2.0 * rng.next_signed() + 1.5);
        let across = 10f64.powf(2.5 * rng.next_signed() + 2.0);
        if let Some(region) =
            GateRegion::<S>::polar([q(center.0), q(center.1)], q(along), q(across))
        {
            let size = along + across * (1.0 + along / center.0.hypot(center.1));
            let pts = points_around(center, size, &mut rng, 1.2);
            gated += region_holds_gated(&region, &pts).unwrap();
        }
    }
    assert!(
        gated > 100,
        "{}: only {gated} gated points tried",
        <S as abtrack::num::Numeric>::NAME
    );
}

#[test]
fn gated_observations_lie_in_the_bounding_box() {
    for seed in 1..40 {
        pregate_case::<f64>(seed);
        pregate_case::<f32>(seed);
        pregate_case::<Fix>(seed);
        pregate_case::<Fixed32>(seed);
    }
}

// ---------------------------------------------------------------------------
// 3. The table against the whole-table solve and a brute force.
// ---------------------------------------------------------------------------

type Table<S, const N: usize, const M: usize> = TrackTable<S, FixedGainTrack<S>, N, M>;

/// A target's start: position (m) and velocity (m/s).
type Target = ((f64, f64), (f64, f64));

/// A random scene: `targets` start positions and velocities, crowded (all
/// within 60 m, so gates overlap) or separated (3 km apart); some targets
/// duplicated exactly (identical tracks: ties between rows).
fn scene(rng: &mut Lcg, targets: usize, crowded: bool) -> Vec<Target> {
    let mut v: Vec<Target> = Vec::new();
    for i in 0..targets {
        if i > 0 && rng.next_signed() > 0.6 {
            let twin = v[(rng.next_signed().abs() * i as f64) as usize % i];
            v.push(twin);
            continue;
        }
        let spread = if crowded {
            30.0
        } else {
            3000.0 * targets as f64
        };
        let p = (spread * rng.next_signed(), spread * rng.next_signed());
        let vel = (100.0 * rng.next_signed(), 100.0 * rng.next_signed());
        v.push((p, vel));
    }
    v
}

/// The measurements of scan `k` (1 s apart): each target with probability
/// 0.9, noisy after the two initiation scans, some duplicated exactly
/// (ties between columns), plus clutter near the targets.
fn measurements(rng: &mut Lcg, targets: &[Target], k: u32, max: usize) -> Vec<(f64, f64)> {
    let t = k as f64;
    let mut m = Vec::new();
    for &((x, y), (vx, vy)) in targets {
        if k >= 2 && rng.next_signed() > 0.8 {
            continue;
        }
        let noise = if k < 2 { 0.0 } else { 4.0 };
        let p = (
            x + vx * t + noise * rng.next_signed(),
            y + vy * t + noise * rng.next_signed(),
        );
        m.push(p);
        if k >= 2 && rng.next_signed() > 0.7 {
            m.push(p);
        }
    }
    if k >= 2 {
        for _ in 0..3 {
            let &((x, y), (vx, vy)) =
                &targets[(rng.next_signed().abs() * targets.len() as f64) as usize % targets.len()];
            m.push((
                x + vx * t + 25.0 * rng.next_signed(),
                y + vy * t + 25.0 * rng.next_signed(),
            ));
        }
    }
    // Shuffle, so that slot order and measurement order are unrelated.
    for i in (1..m.len()).rev() {
        let j = (rng.next_signed().abs() * (i + 1) as f64) as usize % (i + 1);
        m.swap(i, j);
    }
    m.truncate(max);
    m
}

/// Cost matrix of the table's tracks (slot order) × the measurements, as the
/// scan's gate stage defines it, computed through the public API.
fn gated_costs<S: Numeric, F: TrackFilter<S>, const N: usize, const M: usize>(
    table: &TrackTable<S, F, N, M>,
    config: &TrackerConfig<S, F::Params>,
    interval_ms: u32,
    m: &[Measurement<S>],
) -> (Vec<TrackId>, Vec<Vec<u16>>) {
    let params = config.params();
    let step = F::step(params, &ScanInterval::from_ms(interval_ms).unwrap()).unwrap();
    let dt = &step;
    let mut ids = Vec::new();
    let mut cost = Vec::new();
    for track in table.tracks() {
        ids.push(track.id());
        let f = track.filter();
        let region = f
            .predict(params, dt)
            .ok()
            .and_then(|p| f.gate_region(params, &p, dt, config.gate()));
        cost.push(
            m.iter()
                .map(|&z| match (&region, Observation::new(z)) {
                    (Some(r), Ok(o)) => r.cost(&o).unwrap_or(FORBIDDEN),
                    _ => FORBIDDEN,
                })
                .collect(),
        );
    }
    (ids, cost)
}

/// Best (most pairs, then least cost) over every partial matching.
fn brute_force(cost: &[Vec<u16>], n_cols: usize) -> (u32, u64) {
    fn go(cost: &[Vec<u16>], row: usize, used: &mut Vec<bool>) -> (u32, u64) {
        if row == cost.len() {
            return (0, 0);
        }
        let mut best = go(cost, row + 1, used);
        for c in 0..used.len() {
            let v = cost[row][c];
            if v == FORBIDDEN || used[c] {
                continue;
            }
            used[c] = true;
            let (k, t) = go(cost, row + 1, used);
            used[c] = false;
            let cand = (k + 1, t + v as u64);
            if cand.0 > best.0 || (cand.0 == best.0 && cand.1 < best.1) {
                best = cand;
            }
        }
        best
    }
    go(cost, 0, &mut vec![false; n_cols])
}

/// What one checked scan found.
#[derive(Default, Debug)]
struct Checked {
    scans: u32,
    contested: u32,
    ties: u32,
    brute_forced: u32,
    largest_cluster: u32,
}

/// Runs `scans` scans of a random scene through the table; from the third
/// on, checks the table's assignment against the whole-table solve and, for
/// small problems, a brute force.
fn run_scene<S: Numeric, const N: usize, const M: usize>(
    seed: u64,
    targets: usize,
    crowded: bool,
    scans: u32,
    checked: &mut Checked,
) -> Vec<ScanReport> {
    let mut rng = Lcg(seed);
    let config = default_config::<S>();
    let scene = scene(&mut rng, targets, crowded);
    let mut table: Box<Table<S, N, M>> = Box::new(Table::new());
    let mut reports = Vec::new();
    for k in 0..scans {
        let points = measurements(&mut rng, &scene, k, M);
        let m: Vec<Measurement<S>> = points.iter().map(|&(x, y)| cart::<S>(x, y)).collect();
        let expected = (k >= 2).then(|| gated_costs(&table, &config, 1000, &m));
        let mut codes = vec![Association::OutsideGates; m.len()];
        let report = table.scan(&config, 1000 * k, &m, &mut codes).unwrap();
        reports.push(report);
        let Some((ids, cost)) = expected else {
            continue;
        };
        check_scan(&ids, &cost, &codes, &report, checked);
    }
    reports
}

fn check_scan(
    ids: &[TrackId],
    cost: &[Vec<u16>],
    codes: &[Association],
    report: &ScanReport,
    checked: &mut Checked,
) {
    let n_cols = codes.len();
    let mut solver: AssignmentSolver<64, 64> = AssignmentSolver::new();
    let whole = solver.solve(ids.len(), n_cols, |r, c| cost[r][c]).unwrap();
    // The table's pairs, from the codes.
    let mut got: Vec<(TrackId, usize)> = codes
        .iter()
        .enumerate()
        .filter_map(|(k, c)| match c {
            Association::Updated(id) => Some((*id, k)),
            _ => None,
        })
        .collect();
    got.sort();
    let mut want: Vec<(TrackId, usize)> = (0..ids.len())
        .filter_map(|r| solver.col_for_row(r).map(|c| (ids[r], c)))
        .collect();
    want.sort();
    assert_eq!(got, want, "table vs whole-table solve; costs {cost:?}");
    // Every gated measurement not assigned is coded so.
    for k in 0..n_cols {
        let gated = cost.iter().any(|row| row[k] != FORBIDDEN);
        let assigned = want.iter().any(|&(_, c)| c == k);
        if gated && !assigned {
            assert_eq!(codes[k], Association::NotAssigned, "measurement {k}");
        }
    }
    assert_eq!(report.assigned, whole.assigned);
    let gated: u32 = cost.iter().flatten().filter(|&&c| c != FORBIDDEN).count() as u32;
    assert_eq!(report.gated_pairs, gated);
    assert!(report.candidates >= report.gated_pairs);
    // Ties: some measurement gated by two tracks at the same cost, or two
    // gated measurements at the same cost for one track.
    let tie = (0..n_cols).any(|k| {
        let mut c: Vec<u16> = cost
            .iter()
            .map(|r| r[k])
            .filter(|&v| v != FORBIDDEN)
            .collect();
        c.sort();
        c.windows(2).any(|w| w[0] == w[1])
    }) || cost.iter().any(|row| {
        let mut c: Vec<u16> = row.iter().copied().filter(|&v| v != FORBIDDEN).collect();
        c.sort();
        c.windows(2).any(|w| w[0] == w[1])
    });
    checked.scans += 1;
    checked.ties += u32::from(tie);
    checked.contested += u32::from(report.largest_cluster >= 2);
    checked.largest_cluster = checked.largest_cluster.max(report.largest_cluster);
    let rows_gated = cost
        .iter()
        .filter(|r| r.iter().any(|&c| c != FORBIDDEN))
        .count();
    if rows_gated <= 8 {
        let (count, total) = brute_force(cost, n_cols);
        assert_eq!(
            (whole.assigned, whole.total_cost),
            (count, total),
            "brute force"
        );
        checked.brute_forced += 1;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn crowded_scenes_match_the_whole_table_solve(seed in any::<u64>(), targets in 2usize..=14) {
        let mut checked = Checked::default();
        run_scene::<f64, 16, 24>(seed, targets, true, 6, &mut checked);
    }

    #[test]
    fn separated_scenes_match_the_whole_table_solve(seed in any::<u64>(), targets in 1usize..=14) {
        let mut checked = Checked::default();
        run_scene::<f64, 16, 24>(seed, targets, false, 6, &mut checked);
    }
}

/// The scenes exercise what they claim: contested clusters, ties, brute
/// force, in every number type.
#[test]
fn scenes_cover_ties_and_clusters() {
    let mut checked = Checked::default();
    for seed in 0..60 {
        run_scene::<f64, 16, 24>(seed, 2 + seed as usize % 12, seed % 2 == 0, 6, &mut checked);
        run_scene::<f32, 16, 24>(seed, 2 + seed as usize % 12, seed % 2 == 0, 6, &mut checked);
        run_scene::<Fix, 16, 24>(seed, 2 + seed as usize % 12, seed % 2 == 0, 6, &mut checked);
        run_scene::<Fixed32, 16, 24>(seed, 2 + seed as usize % 12, seed % 2 == 0, 6, &mut checked);
    }
    println!("{checked:?}");
    assert!(checked.scans >= 600, "{checked:?}");
    assert!(checked.ties >= 100, "{checked:?}");
    assert!(checked.contested >= 200, "{checked:?}");
    assert!(checked.brute_forced >= 300, "{checked:?}");
    assert!(checked.largest_cluster >= 6, "{checked:?}");
}

/// Tracks gating a 60 m circle only when the gates are on: so that they
/// can be started close together without gating each other's points.
fn parked_gates(on: bool) -> TrackerConfig<f64, ParkedParams> {
    parked_config(ParkedParams {
        gate_radius: on.then_some(60.0),
        refuse_after: None,
    })
}

/// 24 parked tracks within 20 m of each other (four stationary targets per
/// two scans, first and second point, gates off), the time of the next
/// scan, and 4 measurements among them: every pair inside every gate.
fn crowded_parked_scene(
    seed: u64,
) -> (
    Box<TrackTable<f64, Parked, 24, 4>>,
    u32,
    Vec<Measurement<f64>>,
) {
    let mut rng = Lcg(seed);
    let mut point = || Measurement::Cartesian {
        x: 10.0 * rng.next_signed(),
        y: 10.0 * rng.next_signed(),
    };
    let mut table: Box<TrackTable<f64, Parked, 24, 4>> = Box::new(TrackTable::new());
    let mut now = 0;
    for _ in 0..6 {
        let group: Vec<Measurement<f64>> = (0..4).map(|_| point()).collect();
        for _ in 0..2 {
            let mut codes = vec![Association::OutsideGates; 4];
            table
                .scan(&parked_gates(false), now, &group, &mut codes)
                .unwrap();
            now += 1000;
        }
    }
    assert_eq!(table.len(), 24);
    let m = (0..4).map(|_| point()).collect();
    (table, now, m)
}

/// The crowded parked scene: up to 96 gated pairs, more than the cache holds
/// for 4 measurement slots (8 each): the costs of the tracks that do not fit
/// are recomputed, with the same result.
#[test]
fn overflowing_pair_cache_gives_the_same_assignment() {
    let mut checked = Checked::default();
    let mut overflowed = 0;
    for seed in 0..40 {
        let (mut table, now, m) = crowded_parked_scene(seed);
        let on = parked_gates(true);
        let (ids, cost) = gated_costs(&table, &on, 1000, &m);
        let mut codes = vec![Association::OutsideGates; m.len()];
        let report = table.scan(&on, now, &m, &mut codes).unwrap();
        check_scan(&ids, &cost, &codes, &report, &mut checked);
        assert_eq!(report.gated_pairs, 96);
        overflowed += u32::from(report.uncached_tracks > 0);
    }
    assert_eq!(overflowed, 40);
}

/// A scan's pair rule holds for the tracks whose pairs did not fit the
/// cache too: their costs are recomputed for the solver, and a pair the rule
/// refuses must stay refused there as it is in the gate stage.
#[test]
fn pair_rule_holds_for_tracks_outside_the_pair_cache() {
    /// The tracks started last (ids 17 to 24, the last in the gate stage's
    /// order, so outside the cache) may take only measurement 0.
    struct LastTracksFirstMeasurement;
    impl PairRule for LastTracksFirstMeasurement {
        fn may_update(&self, track: TrackId, k: usize) -> bool {
            track.get() <= 16 || k == 0
        }
        fn may_start(&self, _: FirstPoint, _: usize) -> bool {
            true
        }
    }
    let mut overflowed = 0;
    let mut updated = 0;
    for seed in 0..40 {
        let (mut table, now, m) = crowded_parked_scene(seed);
        let mut codes = vec![Association::OutsideGates; m.len()];
        let report = table
            .scan_with_rule(
                &parked_gates(true),
                now,
                &m,
                &mut codes,
                &mut LastTracksFirstMeasurement,
                |_| {},
            )
            .unwrap();
        // 16 tracks with 4 pairs and 8 with one: more than 4 slots' cache.
        assert_eq!(report.gated_pairs, 72);
        overflowed += u32::from(report.uncached_tracks > 0);
        for (k, code) in codes.iter().enumerate() {
            if let Association::Updated(id) = code {
                updated += 1;
                assert!(
                    LastTracksFirstMeasurement.may_update(*id, k),
                    "seed {seed}: measurement {k} updated track {} against the rule",
                    id.get()
                );
            }
        }
    }
    assert_eq!(overflowed, 40);
    assert_eq!(updated, 160);
}

/// The pre-gate's point: in a separated scene the exact gate runs on about
/// one measurement per track, not on all of them.
#[test]
fn separated_scene_tests_few_candidates() {
    let mut checked = Checked::default();
    let reports = run_scene::<f64, 64, 64>(11, 60, false, 8, &mut checked);
    let last = reports.last().unwrap();
    assert!(last.tracks >= 40, "{last:?}");
    assert!(
        last.candidates <= 2 * last.measurements,
        "{} candidates for {} tracks and {} measurements",
        last.candidates,
        last.tracks,
        last.measurements
    );
}
