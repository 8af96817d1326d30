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
//! (the global-nearest-neighbour criterion), with ties broken by the rule
//! below. Criterion 1 first means a track is never left without a
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
//! A forbidden pair is no edge at all (Crouse's infinite cost: the search
//! never crosses it). The solver reads a row's allowed pairs only
//! ([`PairCosts`], in any order): a track table lists each track's gated
//! pairs, and the solver is generic over the list, so reading a cost is an
//! inlined step, not a call. Each row also has a column of its own, "unassigned",
//! of cost `BIG = (min(n, m) + 1)·65536`, larger than the total of any set of
//! allowed pairs, so every row can be placed and leaving one more row
//! unassigned always costs more than any combination of allowed costs: the
//! optimum is exactly the lexicographic optimum (most allowed pairs, then
//! least cost) stated above.
//!
//! All arithmetic is on `i64` (costs are `u16`), so the result is exact and
//! identical whatever number type produced the costs.
//!
//! # Ties, and solving the independent parts apart
//!
//! Rows are added in index order. A search settles, among the columns of
//! least tentative distance, a free one before an assigned one, and among
//! those the one of lowest index (the measurement columns in index order,
//! then the rows' own "unassigned" columns in row order). No other order
//! enters the computation.
//!
//! Consequence: the search from a row only reaches the columns joined to it
//! by allowed pairs, the rows assigned to those, their columns, and so on
//! (one connected component of the allowed pairs, with the "unassigned"
//! columns of its rows), and every choice it makes compares only those.
//! So the solution restricted to a component is, pair for pair, the
//! solution of that component solved alone with its rows and columns in the
//! same relative order. The track table relies on this to solve each
//! cluster of overlapping gates apart (`TrackTable` in `super`);
//! `host-tests/tests/it/track/clusters.rs` checks it, ties included, against
//! this solver on the whole table and against a brute force.
//!
//! # Distinct minima
//!
//! Before any search, each row's cheapest allowed column is looked up. If
//! every row has one, strictly cheaper than its other allowed columns, and no
//! two rows share it, that assignment is the unique optimum: every row is
//! assigned (the most pairs there can be), each at its least cost, and any
//! other assignment costs more in some row and less in none. The search would
//! return the same pairs, so they are taken without it (one step per allowed
//! pair). A
//! crowded cluster, where each gate holds its neighbours' measurements but
//! each track's own measurement is the nearest, takes this path; anything
//! else falls through to the search.
//!
//! # Cost
//!
//! With `n` rows and `m` columns: the search for row k visits at most k + 1
//! rows before it reaches a free column, and each visit scans the `m + n`
//! columns once, so the inner step (one reduced cost, two comparisons) runs
//! at most `(m + n)·n(n+1)/2` times, after at most `n·m` allowed pairs read
//! by the distinct minima. [`Solution::steps`] reports the count actually
//! taken (both); the property tests check it against the bound
//! `(m + n)·n(n+1)/2 + n·m`.
//!
//! Memory: 16 bytes per row and 24 per column of capacity, plus 24 per row
//! for its "unassigned" column ([`AssignmentSolver`]); no heap, no
//! recursion.

/// Cost of a pair that must not be assigned (outside the gate).
pub const FORBIDDEN: u16 = u16::MAX;
/// Largest cost of an allowed pair.
pub const MAX_COST: u16 = u16::MAX - 1;

/// Sentinel for "no index" in the workspaces (so `rows + columns < 65535`).
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

/// A problem's allowed pairs, row by row: what the solver reads of its
/// costs.
pub trait PairCosts {
    /// Calls `pair(column, cost)` for each allowed pair of `row`, each
    /// column once at most. A pair at [`FORBIDDEN`] or beyond the problem's
    /// columns is ignored.
    fn for_each_pair(&self, row: usize, pair: impl FnMut(usize, u16));
}

/// Every column of a row from a cost function, [`FORBIDDEN`] left out.
struct DenseCosts<'c, F> {
    n_cols: usize,
    cost: &'c F,
}

impl<F: Fn(usize, usize) -> u16> PairCosts for DenseCosts<'_, F> {
    fn for_each_pair(&self, row: usize, mut pair: impl FnMut(usize, u16)) {
        for col in 0..self.n_cols {
            match (self.cost)(row, col) {
                FORBIDDEN => {}
                c => pair(col, c),
            }
        }
    }
}

/// Per-row workspace entry.
#[derive(Debug, Clone, Copy)]
struct RowNode {
    /// Dual potential u.
    dual: i64,
    /// The column assigned (measurement columns first, then the rows' own
    /// "unassigned" columns), or `NONE`.
    mate: u16,
    /// Reached in this search.
    visited: bool,
}

/// Per-column workspace entry (a measurement column, or a row's own
/// "unassigned" column).
#[derive(Debug, Clone, Copy)]
struct ColumnNode {
    /// Dual potential v.
    dual: i64,
    /// Shortest reduced path length found in this search.
    shortest: i64,
    /// The row the shortest path arrived from.
    path: u16,
    /// The row assigned, or `NONE`.
    mate: u16,
    /// Settled in this search.
    visited: bool,
}

impl RowNode {
    const EMPTY: RowNode = RowNode {
        dual: 0,
        mate: NONE,
        visited: false,
    };
}

impl ColumnNode {
    const EMPTY: ColumnNode = ColumnNode {
        dual: 0,
        shortest: INF,
        path: NONE,
        mate: NONE,
        visited: false,
    };
}

/// Workspace for problems up to `R` rows × `C` columns (`R + C < 65535`).
///
/// `const fn new` so it can live inside a `static` track table.
#[derive(Debug, Clone)]
pub struct AssignmentSolver<const R: usize, const C: usize> {
    rows: [RowNode; R],
    cols: [ColumnNode; C],
    /// Row i's own "unassigned" column.
    unassigned: [ColumnNode; R],
    n_rows: u16,
    n_cols: u16,
}

impl<const R: usize, const C: usize> Default for AssignmentSolver<R, C> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const R: usize, const C: usize> AssignmentSolver<R, C> {
    const CAPACITY_OK: () = assert!(
        R < NONE as usize && C < NONE as usize && R + C < NONE as usize,
        "assignment capacities must be below 65535 together"
    );

    /// An empty solver for up to `R` rows (tracks) and `C` columns
    /// (measurements); the capacities are checked at compile time.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_OK;
        // Zero bytes (a `static` table lands in `.bss`): each solve resets
        // the nodes it uses before reading them.
        let row = RowNode {
            dual: 0,
            mate: 0,
            visited: false,
        };
        let column = ColumnNode {
            dual: 0,
            shortest: 0,
            path: 0,
            mate: 0,
            visited: false,
        };
        AssignmentSolver {
            rows: [row; R],
            cols: [column; C],
            unassigned: [column; R],
            n_rows: 0,
            n_cols: 0,
        }
    }

    /// Solves the `n_rows × n_cols` problem whose pair costs `cost(row, col)`
    /// returns ([`FORBIDDEN`] for a pair that must not be assigned).
    ///
    /// `cost` is called for every pair of a row each time the solver reads
    /// the row (see the module docs); it should be a table lookup. A sparse
    /// problem is cheaper as [`Self::solve_pairs`].
    pub fn solve(
        &mut self,
        n_rows: usize,
        n_cols: usize,
        cost: impl Fn(usize, usize) -> u16,
    ) -> Result<Solution, AssignError> {
        self.solve_pairs(
            n_rows,
            n_cols,
            &DenseCosts {
                n_cols,
                cost: &cost,
            },
        )
    }

    /// Solves the `n_rows × n_cols` problem whose allowed pairs `costs`
    /// lists row by row (every other pair is forbidden).
    pub fn solve_pairs(
        &mut self,
        n_rows: usize,
        n_cols: usize,
        costs: &impl PairCosts,
    ) -> Result<Solution, AssignError> {
        if n_rows > R || n_cols > C {
            return Err(AssignError::TooLarge);
        }
        // Both fit in u16 because R + C < 65535 (CAPACITY_OK).
        self.n_rows = n_rows as u16;
        self.n_cols = n_cols as u16;
        let problem = Problem {
            rows: self.rows.get_mut(..n_rows).ok_or(AssignError::Internal)?,
            cols: self.cols.get_mut(..n_cols).ok_or(AssignError::Internal)?,
            unassigned: self
                .unassigned
                .get_mut(..n_rows)
                .ok_or(AssignError::Internal)?,
        };
        let result = problem.solve(costs);
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
        let c = self.rows.get(row)?.mate as usize;
        (c < self.n_cols as usize).then_some(c)
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

/// One problem's slices of the workspace. Column index `j` is measurement
/// column `j` for `j < cols.len()`, else row `j − cols.len()`'s
/// "unassigned" column.
struct Problem<'w> {
    rows: &'w mut [RowNode],
    cols: &'w mut [ColumnNode],
    unassigned: &'w mut [ColumnNode],
}

impl Problem<'_> {
    fn row(&mut self, i: usize) -> Result<&mut RowNode, AssignError> {
        self.rows.get_mut(i).ok_or(AssignError::Internal)
    }

    fn column(&mut self, j: usize) -> Result<&mut ColumnNode, AssignError> {
        match j.checked_sub(self.cols.len()) {
            None => self.cols.get_mut(j),
            Some(d) => self.unassigned.get_mut(d),
        }
        .ok_or(AssignError::Internal)
    }

    /// Crouse 2016, Alg. 4, with forbidden pairs as missing edges and one
    /// "unassigned" column per row (module docs).
    fn solve(mut self, costs: &impl PairCosts) -> Result<Solution, AssignError> {
        let n = self.rows.len();
        let m = self.cols.len();
        self.rows.fill(RowNode::EMPTY);
        self.cols.fill(ColumnNode::EMPTY);
        self.unassigned.fill(ColumnNode::EMPTY);
        let mut solution = Solution::default();
        if self.distinct_minima(costs, &mut solution)? {
            return Ok(solution);
        }
        self.rows.fill(RowNode::EMPTY);
        self.cols.fill(ColumnNode::EMPTY);
        // BIG = (min(n, m) + 1)·65536 > min(n, m)·MAX_COST, the largest
        // total of allowed pairs (n, m < 65535: no overflow in i64).
        let big = (n.min(m) as i64).saturating_add(1).saturating_mul(1 << 16);
        for cur in 0..n {
            let (sink, min_val) = self.search(cur, big, costs, &mut solution.steps)?;
            self.update_duals(cur, min_val)?;
            self.augment(cur, sink)?;
        }
        for i in 0..n {
            let j = self.row(i)?.mate as usize;
            if j < m {
                solution.assigned = solution.assigned.saturating_add(1);
                // A measurement column is reached by an allowed pair only.
                let mut cost = 0u64;
                costs.for_each_pair(i, |col, c| {
                    if col == j && c != FORBIDDEN {
                        cost = u64::from(c);
                    }
                });
                solution.total_cost = solution.total_cost.saturating_add(cost);
            }
        }
        Ok(solution)
    }

    /// Assigns every row its cheapest allowed column when each row has one
    /// strictly cheaper than its other allowed columns and no two rows
    /// share it (module docs, "Distinct minima"), with the solution's pairs
    /// and total: true if it did; false as soon as a row has no allowed
    /// pair, a tied minimum or another row's column (a partial assignment
    /// left for the caller to clear). One step per allowed pair scanned.
    fn distinct_minima(
        &mut self,
        costs: &impl PairCosts,
        solution: &mut Solution,
    ) -> Result<bool, AssignError> {
        let m = self.cols.len();
        let mut total = 0u64;
        for i in 0..self.rows.len() {
            let (mut least, mut at, mut unique) = (FORBIDDEN, NONE, false);
            let mut scanned = 0u32;
            costs.for_each_pair(i, |j, c| {
                if j >= m {
                    return;
                }
                scanned = scanned.saturating_add(1);
                if c < least {
                    // j < m < 65535.
                    (least, at, unique) = (c, j as u16, true);
                } else if c == least && c != FORBIDDEN {
                    unique = false;
                }
            });
            solution.steps = solution.steps.saturating_add(scanned);
            if !unique {
                return Ok(false);
            }
            let column = self
                .cols
                .get_mut(usize::from(at))
                .ok_or(AssignError::Internal)?;
            if column.mate != NONE {
                return Ok(false);
            }
            column.mate = i as u16;
            self.row(i)?.mate = at;
            total = total.saturating_add(u64::from(least));
        }
        solution.assigned = self.rows.len() as u32;
        solution.total_cost = total;
        Ok(true)
    }

    /// The shortest augmenting path from row `cur` (Crouse Alg. 4, lines
    /// 6–19): the free column it ends at, and its reduced length.
    fn search(
        &mut self,
        cur: usize,
        big: i64,
        costs: &impl PairCosts,
        steps: &mut u32,
    ) -> Result<(usize, i64), AssignError> {
        for c in self.cols.iter_mut().chain(self.unassigned.iter_mut()) {
            c.shortest = INF;
            c.path = NONE;
            c.visited = false;
        }
        for r in self.rows.iter_mut() {
            r.visited = false;
        }
        let mut min_val: i64 = 0;
        let mut i = cur;
        loop {
            let u_i = {
                let r = self.row(i)?;
                r.visited = true;
                r.dual
            };
            // The columns row i reaches: its allowed pairs and its own
            // "unassigned" column; no other edge leaves it.
            let relax = |cj: &mut ColumnNode, c_ij: i64| {
                if cj.visited {
                    return;
                }
                let reduced = min_val
                    .saturating_add(c_ij)
                    .saturating_sub(u_i)
                    .saturating_sub(cj.dual);
                if reduced < cj.shortest {
                    // i < n < 65535.
                    cj.path = i as u16;
                    cj.shortest = reduced;
                }
            };
            let cols = &mut *self.cols;
            costs.for_each_pair(i, |j, c| {
                if let (Some(cj), false) = (cols.get_mut(j), c == FORBIDDEN) {
                    relax(cj, i64::from(c));
                }
            });
            if let Some(cj) = self.unassigned.get_mut(i) {
                relax(cj, big);
            }
            // Least tentative distance; a free column first; lowest index.
            let mut best: Option<(i64, bool, usize)> = None;
            let columns = self.cols.iter().chain(self.unassigned.iter());
            for (j, cj) in columns.enumerate() {
                if cj.visited {
                    continue;
                }
                *steps = steps.saturating_add(1);
                if cj.shortest == INF {
                    continue;
                }
                let free = cj.mate == NONE;
                let better = best.is_none_or(|(lowest, best_free, _)| {
                    cj.shortest < lowest || (cj.shortest == lowest && free && !best_free)
                });
                if better {
                    best = Some((cj.shortest, free, j));
                }
            }
            // Row `cur`'s own "unassigned" column is always reachable.
            let (lowest, free, j) = best.ok_or(AssignError::Internal)?;
            min_val = lowest;
            let cj = self.column(j)?;
            cj.visited = true;
            if free {
                return Ok((j, min_val));
            }
            i = cj.mate as usize;
        }
    }

    /// Crouse Alg. 4, lines 20–26.
    fn update_duals(&mut self, cur: usize, min_val: i64) -> Result<(), AssignError> {
        for k in 0..self.rows.len() {
            let (visited, mate) = {
                let r = self.row(k)?;
                (r.visited, r.mate as usize)
            };
            if !visited {
                continue;
            }
            let delta = if k == cur {
                min_val
            } else {
                min_val.saturating_sub(self.column(mate)?.shortest)
            };
            let r = self.row(k)?;
            r.dual = r.dual.saturating_add(delta);
        }
        for c in self.cols.iter_mut().chain(self.unassigned.iter_mut()) {
            if c.visited {
                c.dual = c.dual.saturating_sub(min_val.saturating_sub(c.shortest));
            }
        }
        Ok(())
    }

    /// Flips the path from column `sink` back to row `cur`.
    fn augment(&mut self, cur: usize, sink: usize) -> Result<(), AssignError> {
        let mut j = sink;
        loop {
            let i = self.column(j)?.path as usize;
            // i < n < 65535.
            self.column(j)?.mate = i as u16;
            let r = self.row(i)?;
            let previous = r.mate;
            // j < m + n < 65535.
            r.mate = j as u16;
            if i == cur {
                return Ok(());
            }
            j = previous as usize;
        }
    }
}
