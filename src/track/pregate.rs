//! The spatial pre-gate: the measurements that can lie inside a gate, found
//! from the gate's bounding box without testing every measurement.
//!
//! The scan's L valid measurements are bucketed in a grid of G × G cells,
//! G = ⌊√L⌋, over their own bounding box (a bucket grid, counting sort:
//! two passes over the measurements and one over the cells, no comparison
//! sort, no search). A gate's bounding box maps to a range of cells in each
//! axis by the same monotone map as the measurements
//! ([`Numeric::grid_cell`]); in each row of cells the range is one run
//! of the bucketed measurements, and each measurement of the run is tested
//! against the box. Building costs O(L) whatever the order the measurements
//! come in, a query O(rows crossed + k) for k measurements in the cells
//! crossed (`docs/scan-cost.md` gives the measured costs).
//!
//! The box must contain every point the exact test accepts
//! ([`GateRegion::bounds`](super::GateRegion::bounds)); any point inside the
//! box lies in a cell of the box's range, because the map from a coordinate
//! to its cell (subtract the minimum, scale, truncate saturating; the fast
//! fixed point clamps to the grid's bounds first) is monotone in every
//! number type, rounding included, so the
//! candidates are every measurement in the box whatever the rounding.

use super::gate::BoundingBox;
use super::model::Observation;
use crate::num::{Numeric, Quantity};

/// "No cell": an invalid measurement's slot in `cell_of`.
const NO_CELL: u16 = u16::MAX;

/// The scan's measurements in a grid of cells (module docs). Slots are
/// measurement indices (< M < 65535); there are at most L ≤ M cells.
#[derive(Debug, Clone)]
pub(super) struct MeasurementIndex<S: Numeric, const M: usize> {
    /// The valid measurements' slots, by cell (row by row), in slot order
    /// within a cell.
    slots: [u16; M],
    /// For each cell, the index in `slots` of its first measurement.
    cell_start: [u16; M],
    /// Each measurement slot's cell (`NO_CELL` if invalid).
    cell_of: [u16; M],
    /// The lower corner of the measurements' bounding box (x, y).
    min: [S::Length; 2],
    /// The upper corner.
    max: [S::Length; 2],
    /// The map from offsets from `min` to cells, per axis.
    scale: [S::GridScale; 2],
    /// Valid measurements (the used prefix of `slots`).
    len: u16,
    /// Cells per axis, G ≥ 1 (G² ≤ len when len ≥ 1).
    cells: u16,
}

impl<S: Numeric, const M: usize> MeasurementIndex<S, M> {
    /// No measurement indexed; zero bytes (the entries beyond `len` are
    /// never read).
    pub(super) const fn new() -> Self {
        MeasurementIndex {
            slots: [0; M],
            cell_start: [0; M],
            cell_of: [0; M],
            min: [S::Length::ZERO; 2],
            max: [S::Length::ZERO; 2],
            scale: [S::GRID_SCALE_ZERO; 2],
            len: 0,
            cells: 0,
        }
    }

    /// The cell of a point: its row times G plus its column.
    fn cell(&self, [x, y]: [S::Length; 2]) -> usize {
        let last = u32::from(self.cells).saturating_sub(1);
        let ([x_min, y_min], [x_max, y_max], [x_scale, y_scale]) = (self.min, self.max, self.scale);
        let column = axis_cell::<S>(x, x_min, x_max, x_scale, last);
        let row = axis_cell::<S>(y, y_min, y_max, y_scale, last);
        // row, column < G ≤ 255: no overflow.
        row.wrapping_mul(u32::from(self.cells)).wrapping_add(column) as usize
    }

    /// Indexes the valid entries of `observations`.
    pub(super) fn build(&mut self, observations: &[Option<Observation<S>>; M]) {
        let mut len = 0usize;
        let mut bounds: Option<BoundingBox<S>> = None;
        for o in observations.iter().flatten() {
            let [x, y] = o.xy();
            bounds = Some(match bounds {
                None => BoundingBox {
                    min: [x, y],
                    max: [x, y],
                },
                Some(BoundingBox { min, max }) => BoundingBox {
                    min: [min[0].min_of(x), min[1].min_of(y)],
                    max: [max[0].max_of(x), max[1].max_of(y)],
                },
            });
            len = len.saturating_add(1);
        }
        // len ≤ M < 65535.
        self.len = len as u16;
        let Some(BoundingBox { min, max }) = bounds else {
            self.cells = 0;
            return;
        };
        // G² ≤ L ≤ M: the cells fit `cell_start`; G ≤ 255.
        let cells = len.isqrt().max(1);
        self.cells = cells as u16;
        self.min = min;
        self.max = max;
        self.scale = [
            S::grid_scale(min[0], max[0], cells as u16),
            S::grid_scale(min[1], max[1], cells as u16),
        ];
        let grid = cells.saturating_mul(cells);
        let Some(starts) = self.cell_start.get_mut(..grid) else {
            return;
        };
        starts.fill(0);
        // Counts per cell.
        for (k, obs) in observations.iter().enumerate() {
            let cell = match obs {
                Some(o) => self.cell(o.xy()),
                None => NO_CELL as usize,
            };
            if let Some(c) = self.cell_of.get_mut(k) {
                // cell < G² ≤ M < 65535.
                *c = cell as u16;
            }
            if let Some(n) = self.cell_start.get_mut(cell) {
                *n = n.saturating_add(1);
            }
        }
        // Each cell's end, then (placing the slots from the last backwards)
        // its start: the slots end up in slot order within a cell.
        let mut end = 0u16;
        for n in self.cell_start.iter_mut().take(grid) {
            end = end.saturating_add(*n);
            *n = end;
        }
        for (k, &cell) in self.cell_of.iter().enumerate().rev() {
            let Some(next) = self.cell_start.get_mut(cell as usize) else {
                continue;
            };
            *next = next.saturating_sub(1);
            if let Some(s) = self.slots.get_mut(*next as usize) {
                // k < M < 65535.
                *s = k as u16;
            }
        }
    }

    /// Calls `visit(k, observation)` for every indexed measurement `k`
    /// inside `bounds` (boundaries included), row of cells by row, in slot
    /// order within a cell.
    pub(super) fn for_each_in(
        &self,
        observations: &[Option<Observation<S>>; M],
        bounds: &BoundingBox<S>,
        mut visit: impl FnMut(usize, &Observation<S>),
    ) {
        let (len, cells) = (usize::from(self.len), usize::from(self.cells));
        // Nothing indexed, or the box misses the measurements' bounds (or
        // holds an invalid number: every test below fails for NaN).
        if len == 0
            || !(bounds.max[0] >= self.min[0]
                && bounds.min[0] <= self.max[0]
                && bounds.max[1] >= self.min[1]
                && bounds.min[1] <= self.max[1])
        {
            return;
        }
        let last_cell = u32::from(self.cells).saturating_sub(1);
        let ([x_min, y_min], [x_max, y_max], [x_scale, y_scale]) = (self.min, self.max, self.scale);
        let column = |v| axis_cell::<S>(v, x_min, x_max, x_scale, last_cell) as usize;
        let row = |v| axis_cell::<S>(v, y_min, y_max, y_scale, last_cell) as usize;
        let (x0, x1) = (column(bounds.min[0]), column(bounds.max[0]));
        let (y0, y1) = (row(bounds.min[1]), row(bounds.max[1]));
        let grid = cells.saturating_mul(cells);
        for row in y0..=y1 {
            // The cells x0 ..= x1 of a row are one run of `slots`; row,
            // x0, x1 < G ≤ 255: no overflow.
            let first = row.wrapping_mul(cells).wrapping_add(x0);
            let last = row.wrapping_mul(cells).wrapping_add(x1);
            let start = self.cell_start.get(first).map_or(len, |&s| s as usize);
            let stop = if last.saturating_add(1) < grid {
                self.cell_start
                    .get(last.saturating_add(1))
                    .map_or(len, |&s| s as usize)
            } else {
                len
            };
            let Some(run) = self.slots.get(start..stop) else {
                continue;
            };
            for &k in run {
                let k = k as usize;
                if let Some(Some(o)) = observations.get(k) {
                    if bounds.contains(o.xy()) {
                        visit(k, o);
                    }
                }
            }
        }
    }
}

/// The cell along one axis of a coordinate: mapped
/// ([`Numeric::grid_cell`], which takes a coordinate outside
/// `min ..= max` to the nearest end's cell or beyond it), at most `last`;
/// monotone in `v`.
fn axis_cell<S: Numeric>(
    v: S::Length,
    min: S::Length,
    max: S::Length,
    scale: S::GridScale,
    last: u32,
) -> u32 {
    S::grid_cell(v, min, max, scale).min(last)
}
