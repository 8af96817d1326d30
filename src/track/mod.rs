//! Multi-target tracking in fixed memory: a [`TrackTable`] of at most `N`
//! tracks that takes at most `M` measurements per scan.
//!
//! # One scan
//!
//! [`TrackTable::scan`] runs the stages in order and counts each in the
//! [`ScanReport`]; every measurement gets an [`Association`] code.
//!
//! 1. **Intake.** Each measurement is checked and projected to x, y once
//!    ([`Observation`]). Bad numbers (and negative ranges) are
//!    [`Rejected`](Association::Rejected) and touch nothing; measurements
//!    beyond the `M`th are [`Dropped`](Association::Dropped) and counted.
//! 2. **Predict** every track to the scan time (the interval may change from
//!    scan to scan).
//! 3. **Pre-gate and gate.** Each track builds a validation region from its
//!    prediction ([`TrackFilter::gate_region_keeping`], which keeps what
//!    the update needs again: [`TrackFilter::GateKept`]): sized from the filter's
//!    predicted uncertainty, or Li et al.'s wave gate λ = √α ([`Gate`]); a
//!    tentative track's circle under [`Gate::Uncertainty`] is held to the
//!    gate the design's rule 4 assumes ([`defaults`], rule 4). The
//!    measurements inside the region's bounding box are found in an index of
//!    the scan's measurements (a bucket grid built in O(M), the cells the
//!    box crosses visited per track, [`GateRegion::bounds`]), and only those
//!    are tested exactly. Each pair
//!    inside the gate gets a cost, the squared distance normalised by the
//!    gate radius, quantised to `u16`.
//! 4. **Cluster.** Gated pairs join their tracks and measurements into
//!    clusters that share no gated pair (union–find).
//! 5. **Associate** by global nearest neighbour, solved exactly per cluster
//!    ([`assign`]): the assignment with the most gated pairs and, among
//!    those, the least total cost; a cluster of one track and one
//!    measurement is assigned directly. The result is the whole table's
//!    solve, pair for pair, ties included ([`assign`], "Ties").
//! 6. **Update** each assigned track ([`TrackFilter::update_after_gate`],
//!    with what its gate kept); **coast** every other one.
//! 7. **Manage.** Confirm a tentative track when M of its first N scans had a
//!    measurement (default 2 of 3, the starting scan counting as the first
//!    hit); delete a confirmed track after K consecutive misses (default 3), a
//!    tentative one after fewer (default 2) or once M-of-N is out of reach,
//!    and any track that leaves the surveillance [`Volume`]. When the
//!    configuration bounds the gate ([`TrackerConfig::with_max_gate_radius`],
//!    the design's rule 7), a confirmed track whose gate (step 3) is larger
//!    (wider; a range/azimuth window, in area) gates nothing and is deleted
//!    ([`ScanReport::deleted_gate_too_wide`]).
//! 8. **Initiate** (two-point method, Al-Wagih & Abdulla eqs. 9–10): a
//!    measurement outside every gate pairs with an unused measurement of the
//!    previous scan at most `v_max·T` (+ margin) away and starts a tentative
//!    track; then, by default, with one of the scan before that found none,
//!    `v_max·(T₁ + T₂)` away (a target missed once; its M-of-N window starts
//!    at the missed scan: [`TrackerConfig::keep_first_points_through_a_miss`]).
//!    When the table is full the candidate displaces the weakest
//!    tentative track that missed the last scan (fewest hits in its M-of-N
//!    window, then most consecutive misses, then most scans, then lowest
//!    slot): that track's id ends, counted as a deletion
//!    ([`ScanReport::deleted_displaced`]). A confirmed or coasting track,
//!    and a tentative one updated in the last scan or started in this one,
//!    is never displaced; with none other, the candidate is refused and
//!    counted ([`DropReason::TableFull`]). Replacing the least promising
//!    tentative track keeps a clutter-filled table open to new targets
//!    (`docs/track-table.md`, "Full table"). Unpaired measurements outside
//!    every gate become the first points for the next scan, and the previous
//!    scan's that found no second point wait one more where there is room.
//!
//! # Time
//!
//! `scan` takes a timestamp, not an interval: `now_ms`, a `u32` millisecond
//! monotonic clock (the usual hardware timer width). Intervals are computed
//! in integers by wrapping subtraction, so the clock may wrap (every 49.7
//! days) as long as scans are less than 2³¹ ms (24.8 days) apart; a
//! timestamp that is not after the previous one is refused
//! ([`ScanError::TimeNotIncreasing`]). Integer time keeps 1 ms resolution
//! forever, where an `f32` seconds clock has 8 ms steps after 2¹⁶ s
//! (18 hours) and 1 s steps after 2²³ s (97 days). Each interval is converted
//! once to seconds in the filter's number type. The table keeps each track's
//! start time and last update time.
//!
//! The filters are specified for intervals of 0.05–20 s
//! ([`crate::filter::IntervalSpan`]); outside, nothing is refused. Every
//! track steps by the scan's interval, so a coasting track stays in range
//! however long it coasts: its deletion rules (K consecutive misses; a
//! bound on its gate, when configured) end it, and its filter carries the
//! coasted time (the default filter's
//! covariance grows over it exactly, and so does its gate; in `Fixed32` up
//! to 128 s, docs/auto.md, "Limits"). A scan more
//! than 20 s after the previous one restarts every track and drops the
//! previous scan's first points ([`ScanReport::restarted`]). A scan less
//! than 0.05 s after the previous one is skipped: nothing changes, its
//! measurements are coded [`RejectReason::TooClose`] and counted
//! ([`ScanReport::too_close`]).
//!
//! # Initiation pairing: why not optimal
//!
//! Pairing first points with second points is done by sequential nearest
//! neighbour (each first point looks up the unused measurements in its
//! circle's bounding box through the pre-gate's index; ties go to the lowest
//! index) instead of a second optimal assignment: an optimal solve would need
//! a second workspace, and a wrong pairing
//! among new candidates is corrected by M-of-N (its velocity is wrong, so its
//! next gate misses and it is deleted) at the cost of one scan of latency.
//!
//! # Number systems
//!
//! The table runs in any [`Numeric`](crate::Numeric): `f64`, `f32`, Q32.32
//! ([`crate::Fix`]) and the fast fixed point
//! ([`Fixed32`](crate::num::fixed32::Fixed32)), whose gate test and cost are
//! exact integer arithmetic and whose covariance bookkeeping is
//! [`FixedVariance`].
//!
//! # Memory
//!
//! No heap, nothing that grows with N·M; all per-scan workspace is in the
//! table, so the stack use of [`TrackTable::scan`] does not grow with N or
//! M. Bytes per track slot of every filter in every number system, the
//! formula for the table's size and the firmware's capacities are in
//! `docs/track-table.md` (`host-tests/tests/it/track/static_construction.rs` asserts them).
//!
//! # Extending
//!
//! A filter joins by implementing [`TrackFilter`] (a gain schedule's
//! per-track state goes inside the same `Copy` record, its constants in
//! [`TrackFilter::Params`]; what its gate forms that its update needs again
//! may be kept for the scan in [`TrackFilter::GateKept`], or `()`).
//! [`ScheduledTrack`] (any gain schedule) and
//! [`RangeAzimuthTrack`] (He et al., gated by a range/azimuth window) do
//! this for the library's other filters, with their bytes per track;
//! [`defaults`] derives the documented default configuration from the
//! sensor's figures.

mod adapters;
pub mod assign;
mod auto;
mod cluster;
mod config;
pub mod defaults;
mod gate;
mod model;
pub(crate) mod numeric;
mod pregate;
mod table;

pub use adapters::{RangeAzimuthTrack, ScheduledTrack};
pub use auto::AutoStep;
pub use cluster::PAIRS_PER_MEASUREMENT;
pub use config::{TrackerConfig, Volume};
pub use gate::{hypot, BoundingBox, ConfigError, Gate, GateRegion, PolarWindow};
pub use model::{
    ErrorVariance, FixedGainStep, FixedGainTrack, Measurement, Observation, PredictedState,
    RejectReason, ScanInterval, TrackFilter, Uncertainty, UpdateTerms,
};
pub use numeric::{FixedGridScale, FixedVariance};
pub use table::{
    AnyPair, Association, DropReason, FirstPoint, PairRule, ScanError, ScanReport, ScanStage,
    TableStats, Track, TrackId, TrackSlot, TrackStatus, TrackTable,
};
