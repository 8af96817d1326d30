//! Clusters: the tracks and measurements of one scan split into groups that
//! share no gated pair, so that each group's assignment is solved alone.
//!
//! Built while gating: each gated pair (track t, measurement k) joins t with
//! the first track that gated k (union–find over tracks, the smallest slot of
//! each group its root, path halving), and its cost goes into a cache of
//! [`PAIRS_PER_MEASUREMENT`]·M pairs, each track's pairs contiguous. Then
//! [`Clusters::link`] threads each group's tracks (in slot order) and
//! measurements (in index order) into lists starting at its root. Before a
//! cluster is solved, its measurements are numbered as the solver's columns
//! ([`Clusters::list_measurements`]), so each cached pair gives the solver
//! its column by one index. All of it is O(N + M + pairs), in arrays of the
//! table's capacities.
//!
//! A track whose pairs do not fit the cache is marked uncached: the table
//! then recomputes its costs from the gate when the solver asks for them
//! (same numbers, more work) and counts it
//! ([`ScanReport::uncached_tracks`](super::ScanReport::uncached_tracks)).

/// Gated pairs cached per measurement slot of capacity (pairs of a scan
/// beyond `PAIRS_PER_MEASUREMENT·M` are recomputed when needed).
pub const PAIRS_PER_MEASUREMENT: usize = 8;

/// "No track", "no measurement", "no pair".
pub(super) const NONE: u16 = u16::MAX;
/// `TrackLinks::pairs` of a track whose pairs did not fit the cache.
const UNCACHED: u16 = u16::MAX;

/// One cached gated pair of a track.
#[derive(Debug, Clone, Copy)]
struct GatedPair {
    measurement: u16,
    cost: u16,
}

/// A track's place in the scan's clusters.
#[derive(Debug, Clone, Copy)]
struct TrackLinks {
    /// Union–find parent; `NONE` if the track gated nothing.
    parent: u16,
    /// Next track of its cluster, in slot order.
    next: u16,
    /// For a cluster's root: its first measurement.
    first_measurement: u16,
    /// Its pairs in the cache: `pairs` entries from `first_pair`, or
    /// `pairs == UNCACHED`.
    first_pair: u16,
    pairs: u16,
    /// The measurement the assignment gave it, or `NONE`.
    assigned: u16,
}

impl TrackLinks {
    const EMPTY: TrackLinks = TrackLinks {
        parent: NONE,
        next: NONE,
        first_measurement: NONE,
        first_pair: 0,
        pairs: 0,
        assigned: NONE,
    };
}

/// A measurement's place in the scan's clusters.
#[derive(Debug, Clone, Copy)]
struct MeasurementLinks {
    /// Until [`Clusters::link`] has threaded it: the first track (lowest
    /// slot) that gated it, or `NONE`. Once [`Clusters::list_measurements`]
    /// has numbered its cluster: its column in the cluster's assignment
    /// problem (its place in the cluster's list). One field, as no step
    /// needs both.
    owner_then_column: u16,
    /// Next measurement of its cluster, in index order.
    next: u16,
}

impl MeasurementLinks {
    const EMPTY: MeasurementLinks = MeasurementLinks {
        owner_then_column: NONE,
        next: NONE,
    };
}

/// The clusters of one scan (module docs). `N` tracks, `M` measurements.
#[derive(Debug, Clone)]
pub(super) struct Clusters<const N: usize, const M: usize> {
    tracks: [TrackLinks; N],
    measurements: [MeasurementLinks; M],
    pairs: [[GatedPair; PAIRS_PER_MEASUREMENT]; M],
    /// Cache entries in use (u32: the struct's alignment stays 4).
    pairs_used: u32,
}

impl<const N: usize, const M: usize> Clusters<N, M> {
    /// Zero bytes, not yet a valid workspace: [`Self::reset`] before each
    /// scan makes it one.
    pub(super) const fn new() -> Self {
        const ZERO: u16 = 0;
        Clusters {
            tracks: [TrackLinks {
                parent: ZERO,
                next: ZERO,
                first_measurement: ZERO,
                first_pair: ZERO,
                pairs: ZERO,
                assigned: ZERO,
            }; N],
            measurements: [MeasurementLinks {
                owner_then_column: ZERO,
                next: ZERO,
            }; M],
            pairs: [[GatedPair {
                measurement: ZERO,
                cost: ZERO,
            }; PAIRS_PER_MEASUREMENT]; M],
            pairs_used: 0,
        }
    }

    /// Forgets the previous scan (and makes [`Self::new`]'s zeros a valid
    /// workspace).
    pub(super) fn reset(&mut self) {
        self.tracks.fill(TrackLinks::EMPTY);
        self.measurements.fill(MeasurementLinks::EMPTY);
        self.pairs_used = 0;
    }

    /// Records that track `t` (slots in increasing order) gates measurement
    /// `k` at `cost`.
    pub(super) fn add_pair(&mut self, t: usize, k: usize, cost: u16) {
        self.cache(t, k, cost);
        let Some(links) = self.tracks.get_mut(t) else {
            return;
        };
        if links.parent == NONE {
            // t < N < 65535.
            links.parent = t as u16;
        }
        let Some(m) = self.measurements.get_mut(k) else {
            return;
        };
        if m.owner_then_column == NONE {
            m.owner_then_column = t as u16;
        } else {
            let owner = m.owner_then_column as usize;
            // Tracks under one parent are one cluster already (in a crowded
            // cluster, most pairs after a track's first): no union needed.
            let parent_of = |x: usize| self.tracks.get(x).map(|l| l.parent);
            if parent_of(t) != parent_of(owner) {
                self.union(t, owner);
            }
        }
    }

    fn cache(&mut self, t: usize, k: usize, cost: u16) {
        let used = self.pairs_used as usize;
        let Some(links) = self.tracks.get_mut(t) else {
            return;
        };
        if links.pairs == 0 {
            match u16::try_from(used) {
                Ok(first) if first != NONE => links.first_pair = first,
                _ => links.pairs = UNCACHED,
            }
        }
        if links.pairs == UNCACHED {
            return;
        }
        // Contiguous: the pairs of track t follow each other.
        let slot = self.pairs.as_flattened_mut().get_mut(used);
        match slot {
            Some(p) => {
                // k < M < 65535.
                *p = GatedPair {
                    measurement: k as u16,
                    cost,
                };
                self.pairs_used = self.pairs_used.saturating_add(1);
                links.pairs = links.pairs.saturating_add(1);
            }
            None => links.pairs = UNCACHED,
        }
    }

    /// The root (lowest slot) of `t`'s cluster, halving the path.
    fn find(&mut self, t: usize) -> usize {
        let mut x = t;
        loop {
            let Some(parent) = self.tracks.get(x).map(|l| l.parent as usize) else {
                return x;
            };
            if parent == x || parent == NONE as usize {
                return x;
            }
            let grandparent = self
                .tracks
                .get(parent)
                .map_or(parent, |l| l.parent as usize);
            if let Some(l) = self.tracks.get_mut(x) {
                // grandparent < N.
                l.parent = grandparent as u16;
            }
            x = grandparent;
        }
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        let (low, high) = if ra < rb { (ra, rb) } else { (rb, ra) };
        if low != high {
            if let Some(l) = self.tracks.get_mut(high) {
                // low < N.
                l.parent = low as u16;
            }
        }
    }

    /// After the last pair: points every track at its root and threads each
    /// cluster's tracks and measurements into lists.
    pub(super) fn link(&mut self) {
        for t in 0..N {
            let root = self.find(t);
            if let Some(l) = self.tracks.get_mut(t) {
                if l.parent != NONE {
                    // root < N.
                    l.parent = root as u16;
                }
            }
        }
        // Backwards, inserting after the root: lists in increasing order.
        for t in (0..N).rev() {
            let Some(root) = self.root_of(t) else {
                continue;
            };
            if root == t {
                continue;
            }
            let after_root = self.tracks.get(root).map_or(NONE, |l| l.next);
            if let Some(l) = self.tracks.get_mut(t) {
                l.next = after_root;
            }
            if let Some(r) = self.tracks.get_mut(root) {
                r.next = t as u16;
            }
        }
        for k in (0..M).rev() {
            let owner = self
                .measurements
                .get(k)
                .map_or(NONE, |m| m.owner_then_column);
            let Some(root) = self.root_of(owner as usize) else {
                continue;
            };
            let first = self.tracks.get(root).map_or(NONE, |l| l.first_measurement);
            if let Some(m) = self.measurements.get_mut(k) {
                m.next = first;
            }
            if let Some(r) = self.tracks.get_mut(root) {
                // k < M.
                r.first_measurement = k as u16;
            }
        }
    }

    fn root_of(&self, t: usize) -> Option<usize> {
        match self.tracks.get(t)?.parent {
            NONE => None,
            r => Some(r as usize),
        }
    }

    /// Whether track `t` roots a cluster (valid after [`Self::link`]).
    pub(super) fn is_root(&self, t: usize) -> bool {
        self.root_of(t) == Some(t)
    }

    /// The measurement of the cluster rooted at `root` if it is one track
    /// and one measurement (assigned without the solver).
    pub(super) fn single_pair(&self, root: usize) -> Option<usize> {
        let links = self.tracks.get(root)?;
        let k = links.first_measurement;
        let alone = links.next == NONE && self.measurements.get(k as usize)?.next == NONE;
        alone.then_some(k as usize)
    }

    /// The tracks of the cluster rooted at `root`, in slot order.
    pub(super) fn tracks_of(&self, root: usize) -> impl Iterator<Item = usize> + '_ {
        let first = if self.is_root(root) {
            root as u16
        } else {
            NONE
        };
        walk(first, |t| self.tracks.get(t).map(|l| l.next))
    }

    /// Lists the measurements of the cluster rooted at `root` in index
    /// order into `columns` and numbers each as its column there; returns
    /// how many it listed.
    pub(super) fn list_measurements(&mut self, root: usize, columns: &mut [u16]) -> usize {
        let mut k = self.tracks.get(root).map_or(NONE, |l| l.first_measurement);
        let mut column = 0u16;
        let mut slots = columns.iter_mut();
        while let (Some(m), Some(slot)) = (self.measurements.get_mut(usize::from(k)), slots.next())
        {
            *slot = k;
            m.owner_then_column = column;
            // Fewer than M < 65535 measurements.
            column = column.saturating_add(1);
            k = m.next;
        }
        usize::from(column)
    }

    /// Calls `pair(column, cost)` for each cached gated pair of track `t`
    /// (columns as [`Self::list_measurements`] numbered its cluster's);
    /// false, with no call, if its pairs did not fit the cache.
    pub(super) fn for_each_pair(&self, t: usize, mut pair: impl FnMut(usize, u16)) -> bool {
        let Some(links) = self.tracks.get(t) else {
            return true;
        };
        if links.pairs == UNCACHED {
            return false;
        }
        let first = usize::from(links.first_pair);
        let pairs = self
            .pairs
            .as_flattened()
            .get(first..first.saturating_add(usize::from(links.pairs)));
        for p in pairs.unwrap_or_default() {
            if let Some(m) = self.measurements.get(usize::from(p.measurement)) {
                pair(usize::from(m.owner_then_column), p.cost);
            }
        }
        true
    }

    /// Whether track `t`'s pairs did not fit the cache.
    pub(super) fn is_uncached(&self, t: usize) -> bool {
        self.tracks.get(t).is_some_and(|l| l.pairs == UNCACHED)
    }

    /// Gives track `t` measurement `k`.
    pub(super) fn assign(&mut self, t: usize, k: usize) {
        if let Some(l) = self.tracks.get_mut(t) {
            // k < M < 65535.
            l.assigned = k as u16;
        }
    }

    /// The measurement the assignment gave track `t`.
    pub(super) fn assigned(&self, t: usize) -> Option<usize> {
        match self.tracks.get(t)?.assigned {
            NONE => None,
            k => Some(k as usize),
        }
    }
}

/// The indices of a linked list from `first`, following `next` until `NONE`.
fn walk(first: u16, next: impl Fn(usize) -> Option<u16>) -> impl Iterator<Item = usize> {
    core::iter::successors(Some(first), move |&i| next(usize::from(i)))
        .take_while(|&i| i != NONE)
        .map(usize::from)
}
