//! Optimal rectangular assignment with forbidden pairs, in integer arithmetic
//! and fixed-size workspaces.
//!
//! # Problem
//!
//! Rows (tracks) and columns (measurements) with a cost for every pair:
//! `0 ..= MAX_COST`, or [`FORBIDDEN`] for a pair outside the gate. The solver
//! returns the assignment that
//!
//! 1. assigns the **largest number** of allowed pairs, and among those
//! 2. has the **smallest total cost**
//!
//! (the global-nearest-neighbour criterion; ties broken deterministically by
//! index). Criterion 1 first means a track is never left without a
//! measurement only to give a neighbour a slightly closer one.
//!
//! # Algorithm
//!
//! Shortest augmenting paths with dual potentials (Jonker & Volgenant 1987,
//! in the rectangular form of Crouse 2016, "On implementing 2D rectangular
//! assignment algorithms", Alg. 4 — the algorithm behind SciPy's
//! `linear_sum_assignment`). Each row in turn is added by a Dijkstra search
//! over reduced costs; the potentials keep every reduced cost ≥ 0, so after
//! row k the partial assignment is optimal for rows 0..=k.
//!
//! Forbidden pairs are given the cost `BIG = (min(n, m) + 1)·65535`, larger
//! than the total of any set of allowed pairs; the search then runs on a
//! complete matrix, and pairs of cost `BIG` are removed afterwards. Because one
//! more forbidden pair always costs more than any combination of allowed
//! costs, the optimum on the complete matrix is exactly the lexicographic
//! optimum (most allowed pairs, then least cost) stated above.
//!
//! All arithmetic is on `i64` (costs are `u16`), so the result is exact and
//! identical whatever number type produced the costs.
//!
//! # Cost
//!
//! With `n = min(rows, cols)` and `m = max(rows, cols)` (the solver
//! transposes so the shorter side is the row side): the search for row k
//! visits at most k + 1 columns before reaching a free one, and each visit
//! scans at most `m` remaining columns, so the inner step (one reduced cost,
//! two comparisons) runs at most `m·n(n+1)/2` times. For 32 tracks × 32
//! measurements that is 16 896 steps. [`Solution::steps`] reports the count
//! actually taken; the property tests check it against this bound.
//!
//! Memory: 24 bytes per row and per column of capacity ([`AssignmentSolver`]),
//! no heap, no recursion.

/// Cost of a pair that must not be assigned (outside the gate).
pub const FORBIDDEN: u16 = u16::MAX;
/// Largest cost of an allowed pair.
pub const MAX_COST: u16 = u16::MAX - 1;

/// Sentinel for "no index" in the workspaces (so capacities are < 65535).
const NONE: u16 = u16::MAX;
const INF: i64 = i64::MAX;

/// Why the solver refused a problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AssignError {
    /// More rows or columns than the workspace holds.
    TooLarge,
    /// An internal index was out of range. Unreachable if the algorithm is
    /// correct; kept as an error instead of a panic.
    Internal,
}

/// Summary of a solved problem. The pairs themselves are read with
/// [`AssignmentSolver::col_for_row`] / [`AssignmentSolver::row_for_col`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Solution {
    /// Number of allowed pairs assigned (maximum possible).
    pub assigned: u32,
    /// Sum of their costs (minimum among maximum assignments).
    pub total_cost: u64,
    /// Inner steps taken (see the module docs for the bound).
    pub steps: u32,
}

/// Per-row / per-column workspace entry.
#[derive(Debug, Clone, Copy)]
struct Node {
    /// Dual potential (u for a row, v for a column).
    dual: i64,
    /// Column side: shortest reduced path length found in this search.
    shortest: i64,
    /// Column side: the row the shortest path arrived from.
    path: u16,
    /// The index assigned on the other side, or `NONE`.
    mate: u16,
    /// Column side: the list of columns not yet settled in this search
    /// (position i holds a column index).
    remaining: u16,
    /// Settled / visited in this search.
    visited: bool,
}

impl Node {
    const EMPTY: Node = Node {
        dual: 0,
        shortest: INF,
        path: NONE,
        mate: NONE,
        remaining: NONE,
        visited: false,
    };
}

/// Workspace for problems up to `R` rows × `C` columns (`R, C < 65535`).
///
/// `const fn new` so it can live inside a `static` track table.
#[derive(Debug, Clone)]
pub struct AssignmentSolver<const R: usize, const C: usize> {
    rows: [Node; R],
    cols: [Node; C],
    n_rows: u16,
    n_cols: u16,
}

impl<const R: usize, const C: usize> Default for AssignmentSolver<R, C> {
    fn default() -> Self {
        Self::new()
    }
}

fn node(s: &[Node], i: usize) -> Result<&Node, AssignError> {
    s.get(i).ok_or(AssignError::Internal)
}

fn node_mut(s: &mut [Node], i: usize) -> Result<&mut Node, AssignError> {
    s.get_mut(i).ok_or(AssignError::Internal)
}

impl<const R: usize, const C: usize> AssignmentSolver<R, C> {
    const CAPACITY_OK: () = assert!(
        R < NONE as usize && C < NONE as usize,
        "assignment capacities must be below 65535"
    );

    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_OK;
        AssignmentSolver {
            rows: [Node::EMPTY; R],
            cols: [Node::EMPTY; C],
            n_rows: 0,
            n_cols: 0,
        }
    }

    /// Solves the `n_rows × n_cols` problem whose pair costs `cost(row, col)`
    /// returns ([`FORBIDDEN`] for a pair that must not be assigned).
    ///
    /// `cost` is called O(n²m) times (see the module docs); it should be a
    /// table lookup.
    pub fn solve(
        &mut self,
        n_rows: usize,
        n_cols: usize,
        cost: impl Fn(usize, usize) -> u16,
    ) -> Result<Solution, AssignError> {
        if n_rows > R || n_cols > C {
            return Err(AssignError::TooLarge);
        }
        // Both fit in u16 because R, C < 65535 (CAPACITY_OK).
        self.n_rows = n_rows as u16;
        self.n_cols = n_cols as u16;
        let rows = self.rows.get_mut(..n_rows).ok_or(AssignError::Internal)?;
        let cols = self.cols.get_mut(..n_cols).ok_or(AssignError::Internal)?;
        // The search needs rows ≤ columns; otherwise the roles are swapped.
        // Original row r keeps its node in `rows` either way and its `mate`
        // is always an original column index (and vice versa).
        let result = if n_rows <= n_cols {
            solve_core(rows, cols, &cost)
        } else {
            solve_core(cols, rows, &|i, j| cost(j, i))
        };
        if result.is_err() {
            // Leave no half-built assignment behind.
            self.n_rows = 0;
            self.n_cols = 0;
        }
        result
    }

    /// The column assigned to `row` in the last solution, if any.
    pub fn col_for_row(&self, row: usize) -> Option<usize> {
        if row >= self.n_rows as usize {
            return None;
        }
        match self.rows.get(row)?.mate {
            NONE => None,
            c => Some(c as usize),
        }
    }

    /// The row assigned to `col` in the last solution, if any.
    pub fn row_for_col(&self, col: usize) -> Option<usize> {
        if col >= self.n_cols as usize {
            return None;
        }
        match self.cols.get(col)?.mate {
            NONE => None,
            r => Some(r as usize),
        }
    }
}

/// Crouse 2016, Alg. 4, on `row.len() ≤ col.len()`. `cost(i, j)` is indexed
/// in this orientation.
fn solve_core(
    row: &mut [Node],
    col: &mut [Node],
    cost: &dyn Fn(usize, usize) -> u16,
) -> Result<Solution, AssignError> {
    let n = row.len();
    let m = col.len();
    row.fill(Node::EMPTY);
    col.fill(Node::EMPTY);
    let mut solution = Solution::default();
    if n == 0 {
        return Ok(solution);
    }
    // BIG > n·MAX_COST, the largest total of allowed pairs (module docs).
    let big = (n as i64 + 1) * (MAX_COST as i64 + 1);
    let cost_of = |i: usize, j: usize| -> i64 {
        match cost(i, j) {
            FORBIDDEN => big,
            c => c as i64,
        }
    };

    for cur in 0..n {
        for (k, c) in col.iter_mut().enumerate() {
            c.shortest = INF;
            c.path = NONE;
            c.visited = false;
            // k < m ≤ 65534.
            c.remaining = k as u16;
        }
        for r in row.iter_mut() {
            r.visited = false;
        }
        let mut num_remaining = m;
        let mut min_val: i64 = 0;
        let mut i = cur;
        let sink = loop {
            let u_i = {
                let r = node_mut(row, i)?;
                r.visited = true;
                r.dual
            };
            let mut lowest = INF;
            let mut best_pos = usize::MAX;
            for pos in 0..num_remaining {
                let j = node(col, pos)?.remaining as usize;
                let c_ij = cost_of(i, j);
                let cj = node_mut(col, j)?;
                let reduced = min_val
                    .saturating_add(c_ij)
                    .saturating_sub(u_i)
                    .saturating_sub(cj.dual);
                if reduced < cj.shortest {
                    // i < n ≤ 65534.
                    cj.path = i as u16;
                    cj.shortest = reduced;
                }
                // Prefer a free column on ties: it ends the search sooner.
                if cj.shortest < lowest || (cj.shortest == lowest && cj.mate == NONE) {
                    lowest = cj.shortest;
                    best_pos = pos;
                }
                solution.steps = solution.steps.saturating_add(1);
            }
            if lowest == INF {
                // Cannot happen on a complete matrix (forbidden = BIG).
                return Err(AssignError::Internal);
            }
            min_val = lowest;
            let j = node(col, best_pos)?.remaining as usize;
            num_remaining -= 1;
            let last = node(col, num_remaining)?.remaining;
            node_mut(col, best_pos)?.remaining = last;
            let cj = node_mut(col, j)?;
            cj.visited = true;
            if cj.mate == NONE {
                break j;
            }
            i = cj.mate as usize;
        };

        // Update the potentials (Crouse Alg. 4, lines 20–26).
        for k in 0..n {
            let r = node(row, k)?;
            if !r.visited {
                continue;
            }
            let delta = if k == cur {
                min_val
            } else {
                let shortest = node(col, r.mate as usize)?.shortest;
                min_val.saturating_sub(shortest)
            };
            let r = node_mut(row, k)?;
            r.dual = r.dual.saturating_add(delta);
        }
        for c in col.iter_mut() {
            if c.visited {
                c.dual = c.dual.saturating_sub(min_val.saturating_sub(c.shortest));
            }
        }

        // Augment along the path back to `cur`.
        let mut j = sink;
        loop {
            let i = node(col, j)?.path as usize;
            // i < n ≤ 65534.
            node_mut(col, j)?.mate = i as u16;
            let r = node_mut(row, i)?;
            let previous = r.mate;
            // j < m ≤ 65534.
            r.mate = j as u16;
            if i == cur {
                break;
            }
            j = previous as usize;
        }
    }

    // Drop the forbidden pairs the complete-matrix search had to use.
    for i in 0..n {
        let j = node(row, i)?.mate;
        if j == NONE {
            continue;
        }
        let c = cost(i, j as usize);
        if c == FORBIDDEN {
            node_mut(row, i)?.mate = NONE;
            node_mut(col, j as usize)?.mate = NONE;
        } else {
            solution.assigned += 1;
            solution.total_cost += c as u64;
        }
    }
    Ok(solution)
}
