//! The moving window of Al-Wagih & Abdulla's M3 and M4: the last L filtered
//! updates (measurement, the tracker's prediction, interval), in which
//! candidate gains are re-run to measure their innovation error.

use super::{AxisObservation, GainContext};
use crate::num::{Numeric, Quantity};

/// One axis of a remembered update: z, and the tracker's predicted position
/// and velocity for it (the innovation is z − x_p again when needed).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct WindowAxis<N: Numeric> {
    pub measurement: N::Length,
    pub predicted: N::Length,
    pub predicted_velocity: N::Speed,
}

impl<N: Numeric> From<&AxisObservation<N>> for WindowAxis<N> {
    fn from(a: &AxisObservation<N>) -> Self {
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
pub(crate) struct WindowEntry<N: Numeric, const D: usize> {
    pub n: u32,
    pub dt: N::Interval,
    pub axes: [WindowAxis<N>; D],
}

/// A ring of the last `len` ≤ `length` ≤ `W` entries.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Window<N: Numeric, const D: usize, const W: usize> {
    entries: [WindowEntry<N, D>; W],
    /// Slot of the oldest entry.
    start: usize,
    len: usize,
    /// L, the configured window length (1 ≤ L ≤ W).
    length: usize,
}

impl<N: Numeric, const D: usize, const W: usize> Window<N, D, W> {
    /// An empty window of length `length`, which the caller has checked is
    /// in 2..=W.
    pub fn new(length: usize) -> Self {
        Window {
            entries: [WindowEntry {
                n: 0,
                dt: N::Interval::ZERO,
                axes: [WindowAxis {
                    measurement: N::Length::ZERO,
                    predicted: N::Length::ZERO,
                    predicted_velocity: N::Speed::ZERO,
                }; D],
            }; W],
            start: 0,
            len: 0,
            length: length.max(1).min(W.max(1)),
        }
    }

    pub fn clear(&mut self) {
        self.start = 0;
        self.len = 0;
    }

    pub fn is_full(&self) -> bool {
        self.len >= self.length
    }

    /// Slot `k` places after the oldest (`length` ≥ 1, so the remainder is
    /// defined; `checked_rem` keeps the compiler from emitting a panic).
    fn slot(&self, k: usize) -> usize {
        self.start
            .wrapping_add(k)
            .checked_rem(self.length)
            .unwrap_or(0)
    }

    pub fn push(&mut self, ctx: &GainContext<N, D>) {
        let entry = WindowEntry {
            n: ctx.n,
            dt: ctx.dt,
            axes: ctx.axes.each_ref().map(WindowAxis::from),
        };
        if self.len < self.length {
            let slot = self.slot(self.len);
            if let Some(e) = self.entries.get_mut(slot) {
                *e = entry;
                self.len = self.len.saturating_add(1);
            }
        } else if let Some(e) = self.entries.get_mut(self.start) {
            *e = entry;
            self.start = self.slot(1);
        }
    }

    /// Oldest first.
    fn iter(&self) -> impl Iterator<Item = &WindowEntry<N, D>> + '_ {
        (0..self.len).filter_map(move |k| self.entries.get(self.slot(k)))
    }

    /// Sum of squared innovations (in m², as a [`Numeric::Ratio`]) of a
    /// candidate αβ filter re-run over the window on `axis`, with gains
    /// `gains_at(n)` at measurement n.
    ///
    /// The candidate starts from the tracker's own prediction for the oldest
    /// measurement (so it answers "from where the tracker was, which gains
    /// would have predicted the window's measurements best"); that first
    /// innovation is the same for every candidate and is left out, so the
    /// sum has L − 1 terms (Al-Wagih eq. 3, 4, 6, 8 per step).
    ///
    /// An invalid result (overflow) ranks the candidate last.
    pub fn squared_innovation_sum(
        &self,
        axis: usize,
        gains_at: impl Fn(u32) -> (N::Ratio, N::Ratio),
    ) -> N::Ratio {
        let mut it = self.iter();
        let Some(first) = it.next() else {
            return N::Ratio::ZERO;
        };
        let Some(a0) = first.axes.get(axis) else {
            return N::Ratio::ZERO;
        };
        let (alpha, beta) = gains_at(first.n);
        let e0 = a0.measurement - a0.predicted;
        let mut x = a0.predicted + alpha * e0;
        let mut v = a0.predicted_velocity + (beta / first.dt) * e0;
        let mut sum = N::Ratio::ZERO;
        for entry in it {
            let Some(a) = entry.axes.get(axis) else {
                break;
            };
            let (alpha, beta) = gains_at(entry.n);
            let xp = x + v * entry.dt;
            let e = a.measurement - xp;
            let metres = N::Ratio::from(e);
            sum = sum + metres * metres;
            x = xp + alpha * e;
            v = v + (beta / entry.dt) * e;
        }
        sum
    }
}

/// Index of the smallest valid cost among `costs(0..count)`, the first on
/// ties; `None` if every cost is invalid.
pub(crate) fn argmin<Q: Quantity>(count: usize, cost: impl Fn(usize) -> Q) -> Option<usize> {
    let mut best: Option<(usize, Q)> = None;
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
