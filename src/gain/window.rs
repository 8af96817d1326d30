//! The moving window of Al-Wagih & Abdulla's M3 and M4: the last L filtered
//! updates (measurement, the tracker's prediction, interval), in which
//! candidate gains are re-run to measure their innovation error.

use super::{AxisObservation, GainContext};
use crate::num::Scalar;

/// One axis of a remembered update: z, and the tracker's predicted position
/// and velocity for it (the innovation is z − x_p again when needed).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct WindowAxis<S> {
    pub measurement: S,
    pub predicted: S,
    pub predicted_velocity: S,
}

impl<S: Copy> From<&AxisObservation<S>> for WindowAxis<S> {
    fn from(a: &AxisObservation<S>) -> Self {
        WindowAxis {
            measurement: a.measurement,
            predicted: a.predicted,
            predicted_velocity: a.predicted_velocity,
        }
    }
}

/// One filtered update as the window remembers it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct WindowEntry<S, const D: usize> {
    pub n: u32,
    pub dt: S,
    pub axes: [WindowAxis<S>; D],
}

/// A ring of the last `len` ≤ `length` ≤ `W` entries.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Window<S, const D: usize, const W: usize> {
    entries: [WindowEntry<S, D>; W],
    /// Slot of the oldest entry.
    start: usize,
    len: usize,
    /// L, the configured window length (2 ≤ L ≤ W).
    length: usize,
}

impl<S: Scalar, const D: usize, const W: usize> Window<S, D, W> {
    /// An empty window of length `length`, which the caller has checked is
    /// in 2..=W.
    pub fn new(length: usize) -> Self {
        Window {
            entries: [WindowEntry {
                n: 0,
                dt: S::ONE,
                axes: [WindowAxis {
                    measurement: S::ZERO,
                    predicted: S::ZERO,
                    predicted_velocity: S::ZERO,
                }; D],
            }; W],
            start: 0,
            len: 0,
            length: length.clamp(1, W.max(1)),
        }
    }

    pub fn clear(&mut self) {
        self.start = 0;
        self.len = 0;
    }

    pub fn is_full(&self) -> bool {
        self.len >= self.length
    }

    pub fn push(&mut self, ctx: &GainContext<S, D>) {
        let entry = WindowEntry {
            n: ctx.n,
            dt: ctx.dt,
            axes: ctx.axes.each_ref().map(WindowAxis::from),
        };
        if self.len < self.length {
            let slot = (self.start + self.len) % self.length;
            if let Some(e) = self.entries.get_mut(slot) {
                *e = entry;
                self.len += 1;
            }
        } else if let Some(e) = self.entries.get_mut(self.start) {
            *e = entry;
            self.start = (self.start + 1) % self.length;
        }
    }

    /// Oldest first.
    fn iter(&self) -> impl Iterator<Item = &WindowEntry<S, D>> + '_ {
        (0..self.len).filter_map(move |k| self.entries.get((self.start + k) % self.length))
    }

    /// Sum of squared innovations of a candidate αβ filter re-run over the
    /// window on `axis`, with gains `gains_at(n)` at measurement n.
    ///
    /// The candidate starts from the tracker's own prediction for the oldest
    /// measurement (so it answers "from where the tracker was, which gains
    /// would have predicted the window's measurements best"); that first
    /// innovation is the same for every candidate and is left out, so the
    /// sum has L − 1 terms (Al-Wagih eq. 3, 4, 6, 8 per step).
    ///
    /// An invalid result (overflow) ranks the candidate last.
    pub fn squared_innovation_sum(&self, axis: usize, gains_at: impl Fn(u32) -> (S, S)) -> S {
        let mut it = self.iter();
        let Some(first) = it.next() else {
            return S::ZERO;
        };
        let Some(a0) = first.axes.get(axis) else {
            return S::ZERO;
        };
        let (alpha, beta) = gains_at(first.n);
        let e0 = a0.measurement - a0.predicted;
        let mut x = a0.predicted + alpha * e0;
        let mut v = a0.predicted_velocity + beta * e0 / first.dt;
        let mut sum = S::ZERO;
        for entry in it {
            let Some(a) = entry.axes.get(axis) else {
                break;
            };
            let (alpha, beta) = gains_at(entry.n);
            let xp = x + entry.dt * v;
            let e = a.measurement - xp;
            sum = sum + e * e;
            x = xp + alpha * e;
            v = v + beta * e / entry.dt;
        }
        sum
    }
}

/// Index of the smallest valid cost among `costs(0..count)`, the first on
/// ties; `None` if every cost is invalid.
pub(crate) fn argmin<S: Scalar>(count: usize, cost: impl Fn(usize) -> S) -> Option<usize> {
    let mut best: Option<(usize, S)> = None;
    for i in 0..count {
        let c = cost(i);
        if !c.is_valid() {
            continue;
        }
        match best {
            Some((_, b)) if c >= b => {}
            _ => best = Some((i, c)),
        }
    }
    best.map(|(i, _)| i)
}

/// The `i`-th of `count` evenly spaced points from `lo` to `hi` (both
/// included; `count` ≥ 2, else `lo`).
pub(crate) fn grid_point<S: Scalar>(lo: S, hi: S, i: usize, count: usize) -> S {
    if count < 2 {
        return lo;
    }
    let i_s = S::from_f64_lossy(i as f64);
    let steps = S::from_f64_lossy((count - 1) as f64);
    lo + (hi - lo) * i_s / steps
}
