//! The spatial pre-gate: the measurements that can lie inside a gate, found
//! from the gate's bounding box without testing every measurement.
//!
//! The scan's measurements are sorted by x and cut into ⌈√L⌉ strips of
//! consecutive x (L valid measurements); each strip is then sorted by y. A
//! bounding box [x₀, x₁] × [y₀, y₁] visits the strips whose x range meets
//! [x₀, x₁] (two binary searches), and in each the run of y in [y₀, y₁]
//! (one binary search). A query costs O(log L + s·log √L + k) for s strips
//! crossed and k measurements returned, against L for testing all; building
//! costs O(L log L) comparisons (heapsort: no recursion, no allocation, no
//! panic path). The coordinates are copied next to the measurement slots (2
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
    pub(super) const fn new() -> Self {
        let empty = Entry {
            key: S::Length::ZERO,
            slot: u16::MAX,
        };
        MeasurementIndex {
            by_x: [empty; M],
            by_y: [empty; M],
            len: 0,
            strip: 1,
        }
    }

    /// Indexes the valid entries of `observations`.
    pub(super) fn build(&mut self, observations: &[Option<Observation<S>>; M]) {
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
        // len ≤ M < 65535.
        self.len = len as u16;
        let strip = ceil_sqrt(len).max(1);
        self.strip = strip as u16;
        if let Some(by_x) = self.by_x.get_mut(..len) {
            heapsort(by_x);
        }
        for (x, y) in self.by_x.iter().zip(self.by_y.iter_mut()).take(len) {
            let key = observations
                .get(x.slot as usize)
                .and_then(|o| o.as_ref())
                .map_or(S::Length::ZERO, |o| o.xy()[1]);
            *y = Entry { key, slot: x.slot };
        }
        let mut start = 0;
        while start < len {
            let stop = start.saturating_add(strip).min(len);
            if let Some(run) = self.by_y.get_mut(start..stop) {
                heapsort(run);
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
        let (len, strip) = (self.len as usize, self.strip as usize);
        let (Some(by_x), Some(by_y)) = (self.by_x.get(..len), self.by_y.get(..len)) else {
            return;
        };
        // Sorted positions [first, end) have x in [min, max]; the strips
        // holding them are the ones to visit.
        let first = by_x.partition_point(|e| e.key < bounds.min[0]);
        let end = by_x.partition_point(|e| e.key <= bounds.max[0]);
        if first >= end {
            return;
        }
        // strip ≥ 1.
        let mut start = first.checked_div(strip).unwrap_or(0).saturating_mul(strip);
        while start < end {
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

/// Sorts entries by (key, slot): a total order (keys are valid numbers), so
/// the result does not depend on the input order.
fn heapsort<S: PartialOrd + Copy>(v: &mut [Entry<S>]) {
    let n = v.len();
    for root in (0..n / 2).rev() {
        sift_down(v, root, n);
    }
    for end in (1..n).rev() {
        swap(v, 0, end);
        sift_down(v, 0, end);
    }
}

fn less<S: PartialOrd>(a: &Entry<S>, b: &Entry<S>) -> bool {
    a.key < b.key || (a.key == b.key && a.slot < b.slot)
}

/// Restores the max-heap property of `v[..end]` below `root`.
fn sift_down<S: PartialOrd + Copy>(v: &mut [Entry<S>], mut root: usize, end: usize) {
    loop {
        let left = root.saturating_mul(2).saturating_add(1);
        if left >= end {
            return;
        }
        let right = left.saturating_add(1);
        let (Some(&l), Some(&r)) = (v.get(left), v.get(root)) else {
            return;
        };
        let (mut child, mut child_value) = (left, l);
        if right < end {
            if let Some(&rv) = v.get(right) {
                if less(&l, &rv) {
                    (child, child_value) = (right, rv);
                }
            }
        }
        if !less(&r, &child_value) {
            return;
        }
        swap(v, root, child);
        root = child;
    }
}

fn swap<T: Copy>(v: &mut [T], a: usize, b: usize) {
    if let (Some(&x), Some(&y)) = (v.get(a), v.get(b)) {
        if let Some(p) = v.get_mut(a) {
            *p = y;
        }
        if let Some(q) = v.get_mut(b) {
            *q = x;
        }
    }
}
