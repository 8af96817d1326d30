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
//! panic path). Strips rather than one sort by x because targets aligned in
//! x (a grid, a column of aircraft on one airway) would otherwise all fall
//! into every box of their column.
//!
//! Only comparisons of the number type are used, so the candidates are the
//! same in every type up to rounding of the coordinates themselves, and the
//! exact gate test decides; the box only has to contain every point the
//! exact test accepts ([`GateRegion::bounds`](super::GateRegion::bounds)).

use super::gate::BoundingBox;
use super::model::Observation;
use crate::num::Scalar;

/// "No measurement".
const NONE: u16 = u16::MAX;

/// The scan's measurements in strips (see the module docs). Indices are
/// measurement slots (< M < 65535).
#[derive(Debug, Clone)]
pub(super) struct MeasurementIndex<const M: usize> {
    /// The valid measurements sorted by (x, slot).
    by_x: [u16; M],
    /// `by_x` with each strip sorted by (y, slot).
    by_y: [u16; M],
    /// Valid measurements (the used prefix of both arrays).
    len: u16,
    /// Measurements per strip, ⌈√len⌉ (the last strip may hold fewer).
    strip: u16,
}

impl<const M: usize> MeasurementIndex<M> {
    pub(super) const fn new() -> Self {
        MeasurementIndex {
            by_x: [NONE; M],
            by_y: [NONE; M],
            len: 0,
            strip: 1,
        }
    }

    /// Indexes the valid entries of `observations`.
    pub(super) fn build<S: Scalar>(&mut self, observations: &[Option<Observation<S>>; M]) {
        let mut len = 0usize;
        for (k, obs) in observations.iter().enumerate() {
            if obs.is_none() {
                continue;
            }
            if let Some(slot) = self.by_x.get_mut(len) {
                // k < M < 65535.
                *slot = k as u16;
                len = len.saturating_add(1);
            }
        }
        // len ≤ M < 65535.
        self.len = len as u16;
        let strip = ceil_sqrt(len).max(1);
        self.strip = strip as u16;
        let key = |axis: usize| {
            move |k: u16| {
                observations
                    .get(k as usize)
                    .and_then(|o| o.as_ref())
                    .and_then(|o| o.xy().get(axis).copied())
            }
        };
        let Some(by_x) = self.by_x.get_mut(..len) else {
            return;
        };
        heapsort(by_x, key(0));
        for (x, y) in self.by_x.iter().zip(self.by_y.iter_mut()).take(len) {
            *y = *x;
        }
        let mut start = 0;
        while start < len {
            let stop = start.saturating_add(strip).min(len);
            if let Some(run) = self.by_y.get_mut(start..stop) {
                heapsort(run, key(1));
            }
            start = stop;
        }
    }

    /// Calls `visit(k)` for every indexed measurement `k` inside `bounds`
    /// (boundaries included), strip by strip, in increasing y within a
    /// strip.
    pub(super) fn for_each_in<S: Scalar>(
        &self,
        observations: &[Option<Observation<S>>; M],
        bounds: &BoundingBox<S>,
        mut visit: impl FnMut(usize),
    ) {
        let xy = |k: u16| {
            observations
                .get(k as usize)
                .and_then(|o| o.as_ref())
                .map(|o| o.xy())
        };
        let (len, strip) = (self.len as usize, self.strip as usize);
        let (Some(by_x), Some(by_y)) = (self.by_x.get(..len), self.by_y.get(..len)) else {
            return;
        };
        // Sorted positions [first, end) have x in [min, max]; the strips
        // holding them are the ones to visit.
        let first = by_x.partition_point(|&k| xy(k).is_some_and(|p| p[0] < bounds.min[0]));
        let end = by_x.partition_point(|&k| xy(k).is_some_and(|p| p[0] <= bounds.max[0]));
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
            let from = run.partition_point(|&k| xy(k).is_some_and(|p| p[1] < bounds.min[1]));
            for &k in run.iter().skip(from) {
                let Some(p) = xy(k) else { continue };
                if p[1] > bounds.max[1] {
                    break;
                }
                if p[0] >= bounds.min[0] && p[0] <= bounds.max[0] {
                    visit(k as usize);
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

/// Sorts measurement indices by (`key`, index): a total order, so the result
/// does not depend on the input order. Values without a key sort last.
fn heapsort<S: PartialOrd>(v: &mut [u16], key: impl Fn(u16) -> Option<S>) {
    let less = |a: u16, b: u16| match (key(a), key(b)) {
        (Some(ka), Some(kb)) => match ka.partial_cmp(&kb) {
            Some(core::cmp::Ordering::Less) => true,
            Some(core::cmp::Ordering::Greater) => false,
            _ => a < b,
        },
        (Some(_), None) => true,
        (None, Some(_)) => false,
        (None, None) => a < b,
    };
    let n = v.len();
    for root in (0..n / 2).rev() {
        sift_down(v, root, n, &less);
    }
    for end in (1..n).rev() {
        swap(v, 0, end);
        sift_down(v, 0, end, &less);
    }
}

/// Restores the max-heap property of `v[..end]` below `root`.
fn sift_down(v: &mut [u16], mut root: usize, end: usize, less: &impl Fn(u16, u16) -> bool) {
    loop {
        let left = root.saturating_mul(2).saturating_add(1);
        if left >= end {
            return;
        }
        let right = left.saturating_add(1);
        let (Some(&l), Some(&r)) = (v.get(left), v.get(root)) else {
            return;
        };
        let mut child = left;
        let mut child_value = l;
        if right < end {
            if let Some(&rv) = v.get(right) {
                if less(l, rv) {
                    child = right;
                    child_value = rv;
                }
            }
        }
        if !less(r, child_value) {
            return;
        }
        swap(v, root, child);
        root = child;
    }
}

fn swap(v: &mut [u16], a: usize, b: usize) {
    if let (Some(&x), Some(&y)) = (v.get(a), v.get(b)) {
        if let Some(p) = v.get_mut(a) {
            *p = y;
        }
        if let Some(q) = v.get_mut(b) {
            *q = x;
        }
    }
}
