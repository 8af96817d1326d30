//! The spatial pre-gate: the measurements that can lie inside a gate, found
//! from the gate's bounding box without testing every measurement.
//!
//! The scan's measurements are sorted by x and cut into ⌈√L⌉ strips of
//! consecutive x (L valid measurements); each strip is then sorted by y. A
//! bounding box [x₀, x₁] × [y₀, y₁] visits the strips whose x range meets
//! [x₀, x₁] (two binary searches), and in each the run of y in [y₀, y₁]
//! (one binary search). A query costs O(log L + s·log √L + k) for s strips
//! crossed and k measurements returned, against L for testing all; building
//! costs O(L log L) comparisons at worst (a natural merge sort: a scan whose
//! measurements come in the order of the last one's, a sensor's sweep,
//! costs a pass or two; no recursion, no allocation, no panic path). The coordinates are copied next to the measurement slots (2
//! numbers and 4 bytes per measurement slot) so that sorting and searching
//! read one array. Strips rather than one sort by x because targets aligned in
//! x (a grid, a column of aircraft on one airway) would otherwise all fall
//! into every box of their column.
//!
//! Only comparisons of the number type are used, so the candidates are the
//! same in every type up to rounding of the coordinates themselves, and the
//! exact gate test decides; the box only has to contain every point the
//! exact test accepts ([`GateRegion::bounds`](super::GateRegion::bounds)).

use super::gate::BoundingBox;
use super::model::Observation;
use super::numeric::TrackNumeric;
use crate::num::Quantity;

/// One indexed measurement: a coordinate (x in `by_x`, y in `by_y`) and
/// its slot.
#[derive(Debug, Clone, Copy)]
struct Entry<S> {
    key: S,
    slot: u16,
}

/// The scan's measurements in strips (see the module docs). Slots are
/// measurement indices (< M < 65535). The keys are copied next to the slots
/// so that sorting and searching read one array.
#[derive(Debug, Clone)]
pub(super) struct MeasurementIndex<S: TrackNumeric, const M: usize> {
    /// The valid measurements sorted by (x, slot).
    by_x: [Entry<S::Length>; M],
    /// `by_x` with each strip sorted by (y, slot).
    by_y: [Entry<S::Length>; M],
    /// Valid measurements (the used prefix of both arrays).
    len: u16,
    /// Measurements per strip, ⌈√len⌉ (the last strip may hold fewer).
    strip: u16,
}

impl<S: TrackNumeric, const M: usize> MeasurementIndex<S, M> {
    /// No measurement indexed; zero bytes (the entries beyond `len` are
    /// never read).
    pub(super) const fn new() -> Self {
        let empty = Entry {
            key: S::Length::ZERO,
            slot: 0,
        };
        MeasurementIndex {
            by_x: [empty; M],
            by_y: [empty; M],
            len: 0,
            strip: 0,
        }
    }

    /// Indexes the valid entries of `observations`.
    ///
    /// When the valid measurements are the same slots as in the last scan
    /// (a sensor that reports its targets in the same order every scan), the
    /// last scan's order is the starting point: re-keyed, then insertion
    /// sorted, which costs O(L + inversions) — targets moving past each
    /// other swap places, nothing else moves. Beyond a budget of
    /// L·⌈log₂ L⌉ moves, or from scratch, a natural merge sort.
    pub(super) fn build(&mut self, observations: &[Option<Observation<S>>; M]) {
        let xy = |k: u16| {
            observations
                .get(k as usize)
                .and_then(|o| o.as_ref())
                .map(|o| o.xy())
        };
        let previous = self.len as usize;
        // The same slots: as many valid ones, and all the last scan's valid.
        let reusable = self
            .by_x
            .iter()
            .take(previous)
            .all(|e| xy(e.slot).is_some())
            && observations.iter().filter(|o| o.is_some()).count() == previous;
        let len = if reusable {
            for e in self.by_x.iter_mut().take(previous) {
                e.key = xy(e.slot).map_or(S::Length::ZERO, |p| p[0]);
            }
            previous
        } else {
            let mut len = 0usize;
            for (k, obs) in observations.iter().enumerate() {
                let Some(o) = obs else { continue };
                if let Some(e) = self.by_x.get_mut(len) {
                    // k < M < 65535.
                    *e = Entry {
                        key: o.xy()[0],
                        slot: k as u16,
                    };
                    len = len.saturating_add(1);
                }
            }
            len
        };
        // len ≤ M < 65535; the strip width changes only with it.
        self.len = len as u16;
        self.strip = ceil_sqrt(len).max(1) as u16;
        let strip = usize::from(self.strip);
        let (Some(by_x), Some(by_y)) = (self.by_x.get_mut(..len), self.by_y.get_mut(..len)) else {
            return;
        };
        let budget = len.saturating_mul(ceil_log2(len));
        let moved = if reusable {
            insertion_sort(by_x, budget)
        } else {
            None
        };
        match moved {
            // Same order as the last scan: the strips hold the same
            // measurements, in the last scan's y order.
            Some(0) => {
                for e in by_y.iter_mut() {
                    e.key = xy(e.slot).map_or(S::Length::ZERO, |p| p[1]);
                }
            }
            _ => {
                if moved.is_none() {
                    merge_sort(by_x, by_y);
                }
                for (x, y) in by_x.iter().zip(by_y.iter_mut()) {
                    let key = xy(x.slot).map_or(S::Length::ZERO, |p| p[1]);
                    *y = Entry { key, slot: x.slot };
                }
            }
        }
        let mut start = 0;
        while start < len {
            let stop = start.saturating_add(strip).min(len);
            if let Some(run) = by_y.get_mut(start..stop) {
                // A strip holds ⌈√L⌉ entries: O(L) moves at worst.
                insertion_sort(run, usize::MAX);
            }
            start = stop;
        }
    }

    /// Calls `visit(k)` for every indexed measurement `k` inside `bounds`
    /// (boundaries included), strip by strip, in increasing y within a
    /// strip.
    pub(super) fn for_each_in(
        &self,
        observations: &[Option<Observation<S>>; M],
        bounds: &BoundingBox<S>,
        mut visit: impl FnMut(usize),
    ) {
        let (len, strip) = (self.len as usize, usize::from(self.strip).max(1));
        let (Some(by_x), Some(by_y)) = (self.by_x.get(..len), self.by_y.get(..len)) else {
            return;
        };
        // From the strip holding the first x ≥ min, every strip whose first
        // x is ≤ max.
        let first = by_x.partition_point(|e| e.key < bounds.min[0]);
        // strip ≥ 1.
        let mut start = first.checked_div(strip).unwrap_or(0).saturating_mul(strip);
        while by_x
            .get(start)
            .is_some_and(|e| e.key <= bounds.max[0] && start < len)
        {
            let stop = start.saturating_add(strip).min(len);
            let Some(run) = by_y.get(start..stop) else {
                return;
            };
            let from = run.partition_point(|e| e.key < bounds.min[1]);
            for e in run.iter().skip(from) {
                if e.key > bounds.max[1] {
                    break;
                }
                let k = e.slot as usize;
                let inside_x = observations
                    .get(k)
                    .and_then(|o| o.as_ref())
                    .is_some_and(|o| o.xy()[0] >= bounds.min[0] && o.xy()[0] <= bounds.max[0]);
                if inside_x {
                    visit(k);
                }
            }
            start = stop;
        }
    }
}

/// ⌈√n⌉.
fn ceil_sqrt(n: usize) -> usize {
    let r = n.isqrt();
    if r.saturating_mul(r) < n {
        r.saturating_add(1)
    } else {
        r
    }
}

fn less<K: PartialOrd>(a: &Entry<K>, b: &Entry<K>) -> bool {
    a.key < b.key || (a.key == b.key && a.slot < b.slot)
}

/// Sorts entries by (key, slot), a total order (keys are valid numbers), so
/// the result does not depend on the algorithm or the input order: a
/// natural merge sort (runs already in order are merged, not re-sorted: a
/// sensor's sweep or a repeated scene costs a pass or two), with `scratch`
/// (at least as long) as the other buffer. O(n log n) comparisons at worst,
/// no recursion.
fn merge_sort<K: PartialOrd + Copy>(data: &mut [Entry<K>], scratch: &mut [Entry<K>]) {
    let Some(scratch) = scratch.get_mut(..data.len()) else {
        return;
    };
    if run_end(data, 0) >= data.len() {
        return;
    }
    loop {
        if merge_runs(data, scratch) <= 1 {
            // Sorted already: `data` was one run, nothing was moved that
            // matters (the copy in `scratch` is the same).
            return;
        }
        if merge_runs(scratch, data) <= 1 {
            return;
        }
    }
}

/// One pass: merges each pair of adjacent runs of `src` into `dst`; returns
/// the number of runs it found (1: `src` was sorted; `dst` holds a copy).
fn merge_runs<K: PartialOrd + Copy>(src: &[Entry<K>], dst: &mut [Entry<K>]) -> usize {
    let n = src.len();
    let (mut start, mut runs) = (0, 0usize);
    while start < n {
        let mid = run_end(src, start);
        let end = run_end(src, mid);
        runs = runs.saturating_add(if mid < end { 2 } else { 1 });
        let (Some(left), Some(right), Some(out)) = (
            src.get(start..mid),
            src.get(mid..end),
            dst.get_mut(start..end),
        ) else {
            return 0;
        };
        merge(left, right, out);
        start = end;
    }
    runs
}

/// The end of the ascending run starting at `start`.
fn run_end<K: PartialOrd>(v: &[Entry<K>], start: usize) -> usize {
    let mut i = start.saturating_add(1);
    while let (Some(previous), Some(next)) = (v.get(i.saturating_sub(1)), v.get(i)) {
        if less(next, previous) {
            break;
        }
        i = i.saturating_add(1);
    }
    i.min(v.len())
}

/// Merges two sorted runs into `out` (their total length).
fn merge<K: PartialOrd + Copy>(left: &[Entry<K>], right: &[Entry<K>], out: &mut [Entry<K>]) {
    let (mut l, mut r) = (left.iter().peekable(), right.iter().peekable());
    for slot in out.iter_mut() {
        let take_right = match (l.peek(), r.peek()) {
            (Some(a), Some(b)) => less(b, a),
            (None, Some(_)) => true,
            _ => false,
        };
        let next = if take_right { r.next() } else { l.next() };
        if let Some(&e) = next {
            *slot = e;
        }
    }
}

/// Insertion sort by (key, slot); `Some(moves)`, or `None` (and the entries
/// partly sorted) once the moves exceed `budget`.
fn insertion_sort<K: PartialOrd + Copy>(v: &mut [Entry<K>], budget: usize) -> Option<usize> {
    let mut moves = 0usize;
    for i in 1..v.len() {
        let Some(&current) = v.get(i) else { break };
        let mut j = i;
        while let Some(&previous) = j.checked_sub(1).and_then(|p| v.get(p)) {
            if !less(&current, &previous) {
                break;
            }
            if let Some(slot) = v.get_mut(j) {
                *slot = previous;
            }
            j = j.saturating_sub(1);
            moves = moves.saturating_add(1);
        }
        if let Some(slot) = v.get_mut(j) {
            *slot = current;
        }
        if moves > budget {
            return None;
        }
    }
    Some(moves)
}

/// ⌈log₂ n⌉ (0 for n ≤ 1).
fn ceil_log2(n: usize) -> usize {
    usize::BITS.saturating_sub(n.saturating_sub(1).leading_zeros()) as usize
}
