//! The assignment solver against brute force, plus hand-checked cases
//! (the equivalence of per-cluster and whole solves: tests/it/track/clusters.rs).

#![allow(clippy::needless_range_loop)]

use super::support;

use abtrack::track::assign::{AssignmentSolver, PairCosts, FORBIDDEN, MAX_COST};
use proptest::prelude::*;
use support::Lcg;

/// Every optimal matching (most pairs, then least cost) as a row → column
/// map, by enumerating every partial matching; returns (pairs, cost, the
/// optimal maps).
fn brute_force(cost: &[Vec<u16>], n_cols: usize) -> (u32, u64, Vec<Vec<Option<usize>>>) {
    fn go(
        cost: &[Vec<u16>],
        row: usize,
        used: u32,
        n_cols: usize,
        map: &mut Vec<Option<usize>>,
        best: &mut (u32, u64, Vec<Vec<Option<usize>>>),
        so_far: (u32, u64),
    ) {
        if row == cost.len() {
            if so_far.0 > best.0 || (so_far.0 == best.0 && so_far.1 < best.1) {
                *best = (so_far.0, so_far.1, vec![map.clone()]);
            } else if (so_far.0, so_far.1) == (best.0, best.1) {
                best.2.push(map.clone());
            }
            return;
        }
        // Row left unassigned.
        map.push(None);
        go(cost, row + 1, used, n_cols, map, best, so_far);
        map.pop();
        for c in 0..n_cols {
            let v = cost[row][c];
            if v == FORBIDDEN || used & (1 << c) != 0 {
                continue;
            }
            map.push(Some(c));
            let next = (so_far.0 + 1, so_far.1 + v as u64);
            go(cost, row + 1, used | (1 << c), n_cols, map, best, next);
            map.pop();
        }
    }
    let mut best = (0, 0, Vec::new());
    go(cost, 0, 0, n_cols, &mut Vec::new(), &mut best, (0, 0));
    best
}

/// Runs the solver and checks the matching it reports is consistent:
/// inverse maps agree, no forbidden pair, the sum matches `total_cost`, and
/// the step count is within (m + n)·n(n+1)/2 + n·m (n rows, m columns:
/// the search's bound after the distinct minima's lookups).
fn solve_checked(cost: &[Vec<u16>], n_cols: usize) -> (u32, u64, Vec<Option<usize>>) {
    let n_rows = cost.len();
    let mut solver: AssignmentSolver<8, 8> = AssignmentSolver::new();
    let sol = solver.solve(n_rows, n_cols, |r, c| cost[r][c]).unwrap();
    let mut count = 0;
    let mut total = 0u64;
    for r in 0..n_rows {
        if let Some(c) = solver.col_for_row(r) {
            assert!(c < n_cols);
            assert_eq!(solver.row_for_col(c), Some(r));
            assert_ne!(cost[r][c], FORBIDDEN, "forbidden pair assigned");
            count += 1;
            total += cost[r][c] as u64;
        }
    }
    for c in 0..n_cols {
        if let Some(r) = solver.row_for_col(c) {
            assert_eq!(solver.col_for_row(r), Some(c));
        }
    }
    assert_eq!((sol.assigned, sol.total_cost), (count, total));
    let (n, m) = (n_rows as u32, n_cols as u32);
    let bound = (m + n) * n * (n + 1) / 2 + n * m;
    assert!(sol.steps <= bound, "steps {} > bound {bound}", sol.steps);
    let map = (0..n_rows).map(|r| solver.col_for_row(r)).collect();
    (count, total, map)
}

fn matrix() -> impl Strategy<Value = (Vec<Vec<u16>>, usize)> {
    (0usize..=7, 0usize..=7).prop_flat_map(|(n, m)| {
        // Forbidden pairs, small costs (many ties) and full-range costs.
        let entry = prop_oneof![
            3 => Just(FORBIDDEN),
            3 => 0u16..=4,
            3 => 0u16..=MAX_COST,
        ];
        (
            proptest::collection::vec(proptest::collection::vec(entry, m), n),
            Just(m),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn matches_brute_force((cost, n_cols) in matrix()) {
        let (pairs, total, optima) = brute_force(&cost, n_cols);
        let (got_pairs, got_total, map) = solve_checked(&cost, n_cols);
        prop_assert_eq!((got_pairs, got_total), (pairs, total));
        // The solver's matching is one of the optima; when the optimum is
        // unique it is that one (as with any exact solver: the tie rule in
        // abtrack::track::assign decides only among equal optima).
        prop_assert!(optima.contains(&map));
        if optima.len() == 1 {
            prop_assert_eq!(&map, &optima[0]);
        }
    }
}

/// A problem's allowed pairs, each row's in the order given (not column
/// order), as the track table lists a track's gated pairs.
struct ListedPairs(Vec<Vec<(usize, u16)>>);

impl PairCosts for ListedPairs {
    fn for_each_pair(&self, row: usize, mut pair: impl FnMut(usize, u16)) {
        for &(c, v) in self.0.get(row).into_iter().flatten() {
            pair(c, v);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// The solver given only the allowed pairs, each row's in a shuffled
    /// order, returns the same pairs, total and steps as given every pair
    /// of the matrix.
    #[test]
    fn listed_pairs_match_the_matrix((cost, n_cols) in matrix(), seed in any::<u64>()) {
        let mut rng = Lcg(seed);
        let listed = ListedPairs(
            cost.iter()
                .map(|row| {
                    let mut pairs: Vec<(usize, u16)> = row
                        .iter()
                        .enumerate()
                        .filter(|&(_, &v)| v != FORBIDDEN)
                        .map(|(c, &v)| (c, v))
                        .collect();
                    for i in (1..pairs.len()).rev() {
                        let u = (rng.next_signed() + 1.0) / 2.0;
                        pairs.swap(i, ((u * (i + 1) as f64) as usize).min(i));
                    }
                    pairs
                })
                .collect(),
        );
        let n_rows = cost.len();
        let mut dense: AssignmentSolver<8, 8> = AssignmentSolver::new();
        let mut sparse: AssignmentSolver<8, 8> = AssignmentSolver::new();
        let want = dense.solve(n_rows, n_cols, |r, c| cost[r][c]).unwrap();
        let got = sparse.solve_pairs(n_rows, n_cols, &listed).unwrap();
        prop_assert_eq!(got, want);
        for r in 0..n_rows {
            prop_assert_eq!(sparse.col_for_row(r), dense.col_for_row(r));
        }
    }
}

#[test]
fn hand_checked_square() {
    // Rows/cols 0..3. The six permutations cost
    // (0,1,2): 4+0+2 = 6   (0,2,1): 4+5+2 = 11  (1,0,2): 1+2+2 = 5
    // (1,2,0): 1+5+3 = 9   (2,0,1): 3+2+2 = 7   (2,1,0): 3+0+3 = 6
    // so the optimum is row0→col1, row1→col0, row2→col2 with cost 5.
    let cost = [[4u16, 1, 3], [2, 0, 5], [3, 2, 2]];
    let mut solver: AssignmentSolver<3, 3> = AssignmentSolver::new();
    let sol = solver.solve(3, 3, |r, c| cost[r][c]).unwrap();
    assert_eq!((sol.assigned, sol.total_cost), (3, 5));
    assert_eq!(solver.col_for_row(0), Some(1));
    assert_eq!(solver.col_for_row(1), Some(0));
    assert_eq!(solver.col_for_row(2), Some(2));
}

#[test]
fn more_pairs_beat_lower_cost() {
    // Track 0 gates measurement 0 (cost 0) and 1 (cost 10); track 1 gates
    // only measurement 0 (cost 1). Least cost alone would give track 0 its
    // perfect match and leave track 1 empty (total 0); GNN assigns both:
    // 0→1, 1→0, total 11.
    let cost = [[0u16, 10], [1, FORBIDDEN]];
    let mut solver: AssignmentSolver<2, 2> = AssignmentSolver::new();
    let sol = solver.solve(2, 2, |r, c| cost[r][c]).unwrap();
    assert_eq!((sol.assigned, sol.total_cost), (2, 11));
    assert_eq!(solver.col_for_row(0), Some(1));
    assert_eq!(solver.col_for_row(1), Some(0));
}

#[test]
fn more_rows_than_columns() {
    // Two tracks compete for one measurement: the closer (cost 1) wins.
    let cost = [[5u16], [1], [FORBIDDEN]];
    let mut solver: AssignmentSolver<3, 1> = AssignmentSolver::new();
    let sol = solver.solve(3, 1, |r, c| cost[r][c]).unwrap();
    assert_eq!((sol.assigned, sol.total_cost), (1, 1));
    assert_eq!(solver.col_for_row(1), Some(0));
    assert_eq!(solver.col_for_row(0), None);
    assert_eq!(solver.row_for_col(0), Some(1));
}

#[test]
fn all_forbidden_and_empty() {
    let mut solver: AssignmentSolver<4, 4> = AssignmentSolver::new();
    let sol = solver.solve(3, 4, |_, _| FORBIDDEN).unwrap();
    assert_eq!((sol.assigned, sol.total_cost), (0, 0));
    assert!((0..3).all(|r| solver.col_for_row(r).is_none()));
    let sol = solver.solve(0, 4, |_, _| 0).unwrap();
    assert_eq!(sol.assigned, 0);
    let sol = solver.solve(4, 0, |_, _| 0).unwrap();
    assert_eq!(sol.assigned, 0);
}

#[test]
fn too_large_is_an_error() {
    let mut solver: AssignmentSolver<2, 2> = AssignmentSolver::new();
    assert!(solver.solve(3, 2, |_, _| 0).is_err());
    assert!(solver.solve(2, 3, |_, _| 0).is_err());
}

/// Steps on dense 32×32 problems stay under the bound (m + n)·n(n+1)/2 +
/// n·m = 34 816; prints the largest seen.
#[test]
fn dense_32_by_32_steps() {
    let mut rng = Lcg(7);
    let mut solver: AssignmentSolver<32, 32> = AssignmentSolver::new();
    let mut worst = 0;
    for trial in 0..200 {
        let mut cost = [[0u16; 32]; 32];
        for row in cost.iter_mut() {
            for c in row.iter_mut() {
                let u = (rng.next_signed() + 1.0) / 2.0;
                *c = match trial % 3 {
                    // Dense, distinct costs.
                    0 => (u * MAX_COST as f64) as u16,
                    // Heavy ties.
                    1 => (u * 3.0) as u16,
                    // Sparse gates.
                    _ => {
                        if u < 0.8 {
                            FORBIDDEN
                        } else {
                            (u * 1000.0) as u16
                        }
                    }
                };
            }
        }
        let sol = solver.solve(32, 32, |r, c| cost[r][c]).unwrap();
        assert!(sol.steps <= 34_816);
        worst = worst.max(sol.steps);
        // Costs on the anti-diagonal-free structure are arbitrary; the
        // optimum must at least match a greedy row-by-row matching in size.
        let mut used = [false; 32];
        let mut greedy = 0;
        for row in cost.iter() {
            if let Some(c) = (0..32).find(|&c| !used[c] && row[c] != FORBIDDEN) {
                used[c] = true;
                greedy += 1;
            }
        }
        assert!(sol.assigned >= greedy);
    }
    println!("32x32: worst solver steps seen {worst} (bound 34816)");
}

/// Distinct strict minima (each track's own measurement nearest, its
/// neighbours' inside its gate too): every row gets its own column, in
/// one step per allowed pair (no search), the brute force's unique optimum; a
/// tied or a shared minimum falls through to the search, which agrees with
/// the brute force too.
#[test]
fn distinct_minima_take_no_search() {
    let crowded: Vec<Vec<u16>> = (0..6usize)
        .map(|r| {
            (0..6usize)
                .map(|c| match r.abs_diff(c) {
                    0 => 100 + r as u16,
                    1 => 900,
                    2 => 4000,
                    _ => FORBIDDEN,
                })
                .collect()
        })
        .collect();
    let mut solver: AssignmentSolver<8, 8> = AssignmentSolver::new();
    let allowed = crowded
        .iter()
        .flatten()
        .filter(|&&c| c != FORBIDDEN)
        .count() as u32;
    assert_eq!(allowed, 24);
    let sol = solver.solve(6, 6, |r, c| crowded[r][c]).unwrap();
    assert_eq!(sol.steps, allowed);
    assert_eq!((sol.assigned, sol.total_cost), (6, 615));
    for r in 0..6 {
        assert_eq!(solver.col_for_row(r), Some(r));
    }
    let (pairs, total, optima) = brute_force(&crowded, 6);
    assert_eq!(optima.len(), 1);
    assert_eq!(
        solve_checked(&crowded, 6),
        (pairs, total, optima[0].clone())
    );

    // Row 1's minimum tied between two columns; rows 2 and 3 sharing one.
    for changed in [vec![(1usize, 0usize, 101u16)], vec![(2, 3, 50), (3, 3, 60)]] {
        let mut cost = crowded.clone();
        for &(r, c, v) in &changed {
            cost[r][c] = v;
        }
        let sol = solver.solve(6, 6, |r, c| cost[r][c]).unwrap();
        assert!(sol.steps > allowed, "{changed:?}: no search");
        let (pairs, total, optima) = brute_force(&cost, 6);
        let (got_pairs, got_total, map) = solve_checked(&cost, 6);
        assert_eq!((got_pairs, got_total), (pairs, total));
        assert!(optima.contains(&map));
    }
}
