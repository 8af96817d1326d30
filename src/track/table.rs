//! The fixed-capacity track table and its scan.

use core::marker::PhantomData;

use super::assign::{AssignError, AssignmentSolver, PairCosts};
use super::cluster::{Clusters, NONE};
use super::config::TrackerConfig;
use super::gate::{Gate, GateRegion};
use super::model::{
    two_point_gate_radius, Measurement, Observation, RejectReason, ScanInterval, TrackFilter,
};
use super::pregate::MeasurementIndex;
use crate::count::{increment, sat_u32};
use crate::filter::{MAX_INTERVAL_MS, MIN_INTERVAL_MS};
use crate::num::Numeric;

/// A track's identity, unique over the lifetime of its table: ids are issued
/// in increasing order and, after 2³² of them, wrap around skipping any id
/// still in use. A consumer never sees a new track under the id of a live
/// one, and sees a deleted track's id again only after 2³² − N more tracks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TrackId(u32);

impl TrackId {
    /// The id with this number (for comparing with ids received elsewhere,
    /// e.g. from a wire frame; only the table issues ids to tracks).
    pub const fn new(id: u32) -> Self {
        TrackId(id)
    }
    /// The id's number.
    pub const fn get(self) -> u32 {
        self.0
    }
}

impl core::fmt::Display for TrackId {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        core::fmt::Display::fmt(&self.0, f)
    }
}

/// Lifecycle state of a track.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TrackStatus {
    /// Started by two-point initiation, not yet confirmed by M-of-N.
    Tentative,
    /// Confirmed, and updated by a measurement in the last scan.
    Confirmed,
    /// Confirmed, but missed the last scan(s): predicted only.
    Coasting,
}

impl TrackStatus {
    /// "tentative", "confirmed", "coasting" (the replay CSV's status column).
    pub const fn as_str(self) -> &'static str {
        match self {
            TrackStatus::Tentative => "tentative",
            TrackStatus::Confirmed => "confirmed",
            TrackStatus::Coasting => "coasting",
        }
    }
}

/// Whether a track has passed M-of-N confirmation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Lifecycle {
    Tentative,
    Confirmed,
}

/// One slot of a [`TrackTable`]: empty or a track. An explicit tag, 0 for
/// empty (not `Option`, whose `None` the compiler would store in a niche
/// of the filter's state, a non-zero byte), so that a new table is zero
/// bytes and a `static` one lands in `.bss`. Its size is the table's bytes
/// per track (`docs/track-table.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(u8)]
pub enum TrackSlot<S: Numeric, F> {
    /// No track.
    Empty = 0,
    /// A live track.
    Live(Track<S, F>) = 1,
}

impl<S: Numeric, F> TrackSlot<S, F> {
    /// The track, if the slot holds one.
    pub fn track(&self) -> Option<&Track<S, F>> {
        match self {
            TrackSlot::Live(track) => Some(track),
            TrackSlot::Empty => None,
        }
    }

    fn track_mut(&mut self) -> Option<&mut Track<S, F>> {
        match self {
            TrackSlot::Live(track) => Some(track),
            TrackSlot::Empty => None,
        }
    }

    fn is_live(&self) -> bool {
        matches!(self, TrackSlot::Live(_))
    }

    /// Empties the slot; whether it held a track.
    fn clear(&mut self) -> bool {
        let was_live = self.is_live();
        *self = TrackSlot::Empty;
        was_live
    }
}

/// One record of the table: the filter and the lifecycle, nothing that can
/// be derived (the status from the confirmation and the last scan's hit;
/// bytes per track in `docs/track-table.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Track<S: Numeric, F> {
    filter: F,
    id: TrackId,
    created_ms: u32,
    last_update_ms: u32,
    /// Bit k set: the scan k scans ago had a measurement (bit 0 = last scan).
    /// Bits older than the track's start are 0.
    history: u32,
    /// Measurements incorporated (the two initiation points included),
    /// saturating.
    hits: u16,
    /// Scans since the track was started (that scan included; from an
    /// earlier first point, the missed scan before it too), saturating.
    scans: u16,
    lifecycle: Lifecycle,
    /// Consecutive scans without a measurement (the history holds only 32;
    /// deletion thresholds go to 255), saturating.
    misses: u8,
    /// Updates or coasts the filter refused (arithmetic saturated),
    /// saturating.
    refusals: u8,
    _scalar: PhantomData<S>,
}

impl<S: Numeric, F: TrackFilter<S>> Track<S, F> {
    /// The track's id, unique among live tracks.
    pub fn id(&self) -> TrackId {
        self.id
    }
    /// Tentative; confirmed and updated in the last scan; or confirmed and
    /// missed it (coasting).
    pub fn status(&self) -> TrackStatus {
        match (self.lifecycle, self.history & 1) {
            (Lifecycle::Tentative, _) => TrackStatus::Tentative,
            (Lifecycle::Confirmed, 1) => TrackStatus::Confirmed,
            (Lifecycle::Confirmed, _) => TrackStatus::Coasting,
        }
    }
    /// Confirmed or coasting.
    pub fn is_confirmed(&self) -> bool {
        self.lifecycle == Lifecycle::Confirmed
    }
    /// The track's filter.
    pub fn filter(&self) -> &F {
        &self.filter
    }
    /// Estimated position (x, y) at the last scan (m).
    pub fn position(&self) -> [S::Length; 2] {
        self.filter.position()
    }
    /// Estimated velocity (x, y) at the last scan (m/s).
    pub fn velocity(&self) -> [S::Speed; 2] {
        self.filter.velocity()
    }
    /// Consecutive missed scans.
    pub fn misses(&self) -> u8 {
        self.misses
    }
    /// Measurements incorporated, both initiation points included.
    pub fn hits(&self) -> u16 {
        self.hits
    }
    /// Scans since the track started (its first scan counts 1; started from
    /// a first point kept through a miss, the missed scan counts too).
    pub fn scans(&self) -> u16 {
        self.scans
    }
    /// Hit pattern of the last 32 scans, bit 0 = the last scan.
    pub fn history(&self) -> u32 {
        self.history
    }
    /// Scan time at which the track started (ms).
    pub fn created_ms(&self) -> u32 {
        self.created_ms
    }
    /// Scan time of the last measurement update (ms).
    pub fn last_update_ms(&self) -> u32 {
        self.last_update_ms
    }
    /// Updates and coasts the filter refused (its arithmetic saturated;
    /// the track coasted or was deleted), saturating at 255.
    pub fn refusals(&self) -> u8 {
        self.refusals
    }

    /// The region this track gates with: its filter's, a tentative track's
    /// circle held to the gate the design's rule 4 counts clutter in
    /// ([`two_point_gate_radius`], m = its misses + 1), so that a track
    /// started on clutter does not take plots kilometres away before it is
    /// confirmed.
    #[inline(always)]
    fn held_region(
        &self,
        region: GateRegion<S>,
        gate: &Gate<S>,
        interval: &ScanInterval<S>,
    ) -> GateRegion<S> {
        if self.lifecycle != Lifecycle::Tentative {
            return region;
        }
        match two_point_gate_radius(gate, self.misses.saturating_add(1), interval) {
            Some(radius) => region.limited_to(radius),
            None => region,
        }
    }

    fn record_scan(&mut self, hit: bool, now_ms: u32) {
        self.history = (self.history << 1) | hit as u32;
        self.scans = self.scans.saturating_add(1);
        if hit {
            self.hits = self.hits.saturating_add(1);
            self.misses = 0;
            self.last_update_ms = now_ms;
        } else {
            self.misses = self.misses.saturating_add(1);
        }
    }
}

/// Which pairs may associate in a scan ([`TrackTable::scan_with_rule`]),
/// besides the gates: e.g. only replies with a track's Mode S address.
pub trait PairRule {
    /// Measurement `k` of this scan may update track `track`.
    fn may_update(&self, track: TrackId, k: usize) -> bool;
    /// `first` and measurement `k` of this scan may start a track together.
    fn may_start(&self, first: FirstPoint, k: usize) -> bool;
    /// Track `track` was deleted by its deletion rules in this scan, before
    /// the scan's starts are decided: a rule that refuses starts for a live
    /// track's sake (its identity) may allow them from here on. Not called
    /// for a tentative track displaced by a start (the table full) nor for
    /// the tracks a scan after too long a gap restarts.
    fn track_deleted(&mut self, _track: TrackId) {}
}

/// Which scan a first point of two-point initiation came from
/// ([`PairRule::may_start`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FirstPoint {
    /// Measurement `p` of the previous scan.
    PreviousScan(usize),
    /// An unused measurement of the scan before the previous one, kept
    /// through a miss ([`TrackerConfig::keep_first_points_through_a_miss`]).
    ScanBefore,
}

/// Every pair allowed ([`TrackTable::scan`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct AnyPair;

impl PairRule for AnyPair {
    fn may_update(&self, _: TrackId, _: usize) -> bool {
        true
    }
    fn may_start(&self, _: FirstPoint, _: usize) -> bool {
        true
    }
}

/// Why a measurement was dropped unused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DropReason {
    /// It would have started a track, but the table was full and held no
    /// tentative track it could displace.
    TableFull,
    /// The scan had more than `M` measurements; this is one of the excess.
    ScanOverflow,
}

/// What happened to one measurement of a scan (TI gtrack-style association
/// code).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Association {
    /// Inside no gate and paired with nothing, inside the surveillance
    /// volume; kept as a first point for initiation in the next scan
    /// (and, unpaired there, the one after:
    /// [`TrackerConfig::keep_first_points_through_a_miss`]).
    /// (First: the code of a table's workspace before its first scan is zero
    /// bytes.)
    OutsideGates,
    /// Inside no gate and outside the surveillance volume
    /// ([`TrackerConfig::with_volume`]): not used (a track there would be
    /// deleted as having left it).
    OutsideVolume,
    /// Updated this track.
    Updated(TrackId),
    /// Paired with a first point (a measurement of the previous scan, or of
    /// the scan before it) and started this (tentative) track.
    Started(TrackId),
    /// Inside at least one gate, but the optimal assignment gave those tracks
    /// other measurements. Not used to start tracks (it would duplicate a
    /// neighbouring track).
    NotAssigned,
    /// Bad input (or refused by the filter); no track was changed.
    Rejected(RejectReason),
    /// Not used for lack of room.
    Dropped(DropReason),
}

/// Why a scan was refused. The table is unchanged and no code was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScanError {
    /// `now_ms` is not after the previous scan's time (in wrapping u32
    /// arithmetic: 1 ..= 2³¹ − 1 ms later).
    TimeNotIncreasing {
        /// The previous scan's time (ms).
        previous_ms: u32,
        /// The refused scan's time (ms).
        now_ms: u32,
    },
    /// The interval does not fit the number type.
    IntervalNotRepresentable,
    /// The assignment solver failed (unreachable; kept instead of a panic).
    Assignment(AssignError),
}

impl core::fmt::Display for ScanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ScanError::TimeNotIncreasing {
                previous_ms,
                now_ms,
            } => write!(
                f,
                "scan time {now_ms} ms is not after the previous scan ({previous_ms} ms)"
            ),
            ScanError::IntervalNotRepresentable => {
                f.write_str("scan interval is not representable in the number type")
            }
            ScanError::Assignment(_) => f.write_str("assignment solver failed"),
        }
    }
}

impl core::error::Error for ScanError {}

/// Per-stage counts of one scan (for logs and benchmarks).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanReport {
    /// The scan's time (ms, wrapping u32).
    pub time_ms: u32,
    /// Time since the previous scan (0 for the first).
    pub interval_ms: u32,
    // --- intake
    /// Measurements passed in.
    pub measurements: u32,
    /// Rejected as bad input (not finite, negative range).
    pub rejected: u32,
    /// Beyond the table's `M` per scan; dropped.
    pub dropped_overflow: u32,
    // --- predict, pre-gate, gate
    /// Tracks predicted to the scan time.
    pub predicted: u32,
    /// (track, measurement) pairs inside a gate's bounding box: the exact
    /// gate tests made (the spatial pre-gate's output).
    pub candidates: u32,
    /// (track, measurement) pairs inside a gate.
    pub gated_pairs: u32,
    /// Tracks whose gated pairs did not fit the pair cache: their costs
    /// were recomputed for the solver.
    pub uncached_tracks: u32,
    // --- cluster, assign
    /// Groups of tracks and measurements sharing no gated pair.
    pub clusters: u32,
    /// Clusters of one track and one measurement, assigned without the
    /// solver.
    pub single_pairs: u32,
    /// Tracks in the largest cluster.
    pub largest_cluster: u32,
    /// Pairs chosen by the assignment.
    pub assigned: u32,
    /// Inner steps of the assignment solver, over all clusters.
    pub solver_steps: u32,
    // --- update
    /// Tracks updated with their measurement.
    pub updated: u32,
    /// Measurements the filter refused (its arithmetic saturated): assigned
    /// to a track, which coasted instead, or a new track's two points
    /// (counted on the second), and the track did not start (its first
    /// point is spent).
    pub filter_refused: u32,
    /// Tracks left to coast: no measurement, or the filter refused theirs
    /// (a coast the filter cannot make deletes the track, counted in
    /// `deleted_numeric`).
    pub coasted: u32,
    /// Measurements inside a gate but not assigned.
    pub not_assigned: u32,
    // --- manage
    /// Tracks started.
    pub started: u32,
    /// Tracks that would have started, but the table was full and held no
    /// tentative track to displace.
    pub refused_table_full: u32,
    /// Measurements left outside every gate and unpaired, inside the
    /// surveillance volume (kept as first points).
    pub outside_gates: u32,
    /// Measurements outside every gate and outside the surveillance volume
    /// (not used).
    pub outside_volume: u32,
    /// Tracks confirmed in this scan.
    pub confirmed: u32,
    /// Tracks deleted in this scan (sum of the six reasons below).
    pub deleted: u32,
    /// ... after too many consecutive misses.
    pub deleted_misses: u32,
    /// ... tentative tracks that could no longer meet M-of-N.
    pub deleted_unconfirmed: u32,
    /// ... that left the surveillance volume.
    pub deleted_left_volume: u32,
    /// ... whose filter could not advance (arithmetic saturated).
    pub deleted_numeric: u32,
    /// ... confirmed tracks whose gate grew larger than the
    /// configuration's largest ([`TrackerConfig::with_max_gate_radius`]):
    /// lost among false measurements.
    pub deleted_gate_too_wide: u32,
    /// ... tentative tracks displaced by a new track when the table was
    /// full (the [module docs](super), step 8): their ids end.
    pub deleted_displaced: u32,
    /// Tracks ended because this scan came more than
    /// [`MAX_INTERVAL_S`](crate::filter::MAX_INTERVAL_S) after the previous
    /// one (not counted in `deleted`): an interval beyond what the filters
    /// are specified for restarts every estimate, and the targets' next
    /// reports start new tracks by two-point initiation.
    pub restarted: u32,
    /// Measurements of a scan that came less than
    /// [`MIN_INTERVAL_S`](crate::filter::MIN_INTERVAL_S) after the previous
    /// one: the scan was skipped (nothing changed), each measurement coded
    /// [`RejectReason::TooClose`].
    pub too_close: u32,
    // --- result
    /// Live tracks after the scan.
    pub tracks: u32,
}

counter_list! {
    /// Counters over the table's lifetime (saturating); the scan loop sends
    /// them in its health report.
    pub struct TableStats: u32 {
        /// Scans accepted.
        scans => "scans accepted",
        /// Tentative tracks started.
        tracks_started => "tracks started",
        /// Tentative tracks confirmed.
        tracks_confirmed => "tracks confirmed",
        /// Tracks deleted, tentative or confirmed (the displaced ones
        /// included).
        tracks_deleted => "tracks deleted",
        /// Candidate tracks refused: the table was full and held no
        /// tentative track to displace.
        refused_table_full => "refused, table full",
        /// Tentative tracks displaced by a new track when the table was full
        /// (also in `tracks_deleted`).
        tracks_displaced => "tentative tracks displaced",
        /// Measurements beyond `M` in a scan.
        dropped_overflow => "dropped, scan overflow",
        /// Measurements rejected as bad input (not finite, a negative
        /// range).
        rejected => "rejected as bad input",
        /// Measurements the filter refused ([`ScanReport::filter_refused`]).
        filter_refused => "refused by the filter",
        /// Measurements outside every gate and outside the surveillance
        /// volume ([`ScanReport::outside_volume`]).
        outside_volume => "outside the volume",
        /// Measurements of the scans skipped for coming too close to the
        /// previous one ([`ScanReport::too_close`]).
        too_close => "in scans too close",
        /// Tracks restarted (ended by a scan interval beyond the filters'
        /// range, [`ScanReport::restarted`]).
        tracks_restarted => "tracks restarted",
        /// Scans skipped for coming too close to the previous one
        /// ([`ScanReport::too_close`]).
        scans_skipped => "scans skipped",
    }
}

/// The stages of [`TrackTable::scan`], in order: what
/// [`TrackTable::scan_with_probe`] reports as each one ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScanStage {
    /// Measurements checked and projected to x, y.
    Intake,
    /// The spatial pre-gate's index of the measurements built.
    Index,
    /// Every track predicted, its gate formed, the measurements in the
    /// gate's bounding box tested exactly, the gated pairs cached and
    /// joined into clusters.
    Gate,
    /// Each cluster's tracks and measurements listed.
    Cluster,
    /// Each cluster's optimal assignment.
    Assign,
    /// Each track updated with its measurement, or coasted.
    Update,
    /// Confirmation, deletion.
    Manage,
    /// Two-point initiation, the next scan's first points, the codes.
    Initiate,
}

/// What the update stage did to one track.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// No track in the slot.
    Empty,
    /// Updated with a measurement.
    Hit,
    /// Coasted.
    Miss,
    /// Could not advance (arithmetic saturated): to be deleted.
    Failed,
    /// Confirmed, and its gate larger than the configuration's largest
    /// ([`TrackerConfig::max_gate_radius`]): gated nothing, to be deleted.
    GateTooWide,
}

/// How a scan's time stands to the previous scan's.
#[derive(Clone, Copy)]
enum ScanTiming<Step> {
    /// The first scan (or the first after [`TrackTable::clear`]).
    First,
    /// Less than the shortest interval: the scan is skipped.
    TooClose,
    /// More than the longest interval: every track restarts, and the
    /// previous scan's first points are too old to pair with.
    TooLong,
    /// In range: every track's step for the interval.
    Step(Step),
}

/// A fixed-capacity multi-target tracker: at most `N` tracks and `M`
/// measurements per scan, no heap, `const fn new` (fits in a `static`).
///
/// See the [module docs](super) for the scan's stages, the time base and the
/// memory figures.
///
/// Two targets, one scan a second: the first scan's measurements are first
/// points, the second starts two tentative tracks (two-point initiation,
/// Al-Wagih eq. 9), the third confirms them (2 of 3).
///
/// ```
/// use abtrack::track::{
///     Association, FixedGainTrack, Gate, Measurement, TrackStatus, TrackTable, TrackerConfig,
/// };
/// use abtrack::Gains;
/// // α = 0.5, β = 0.2; σ = 5 m, G = 13.8 (99.9 %), a_max = 5 m/s²; v_max = 300 m/s.
/// let gate = Gate::uncertainty(5.0, 13.8, 5.0)?;
/// let config = TrackerConfig::new(Gains::alpha_beta(0.5, 0.2)?, gate, 300.0)?;
/// let mut table: TrackTable<f64, FixedGainTrack<f64>, 4, 8> = TrackTable::new();
/// let mut codes = [Association::NotAssigned; 8];
/// for k in 0..3u32 {
///     let t = f64::from(k);
///     let targets = [
///         Measurement::Cartesian { x: 100.0 * t, y: 1000.0 },  // east at 100 m/s
///         Measurement::Cartesian { x: 5000.0, y: -50.0 * t }, // south at 50 m/s
///     ];
///     table.scan(&config, 1000 * k, &targets, &mut codes)?;
/// }
/// assert_eq!(table.len(), 2);
/// assert!(table.tracks().all(|t| t.status() == TrackStatus::Confirmed));
/// let east = table.tracks().find(|t| t.position()[1] > 500.0).ok_or("no track")?;
/// assert!((east.position()[0] - 200.0).abs() < 1e-9);
/// assert!((east.velocity()[0] - 100.0).abs() < 1e-9);
/// assert_eq!(table.stats().tracks_confirmed, 2);
/// # Ok::<(), Box<dyn core::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct TrackTable<S: Numeric, F: TrackFilter<S>, const N: usize, const M: usize> {
    slots: [TrackSlot<S, F>; N],
    /// The id the next track gets, minus 1 (wrapping): 0 for a new table,
    /// whose first id is 1.
    previous_id: u32,
    last_scan_ms: Option<u32>,
    /// First points for two-point initiation: unused measurements of the
    /// previous scan (at their index), and those of the scan before that
    /// found no second point (`pending_earlier`), in the places above the
    /// previous scan's measurements.
    pending: [Option<Observation<S>>; M],
    /// Which of `pending` are from the scan before the previous one.
    pending_earlier: [bool; M],
    /// How many of `pending` hold a first point (≤ M < 65535).
    pending_count: u16,
    /// The previous accepted scan's interval (ms): with this scan's, the
    /// interval to an earlier first point.
    previous_interval_ms: u32,
    stats: TableStats,
    // --- per-scan workspace (kept here, not on the stack)
    observations: [Option<Observation<S>>; M],
    codes: [Association; M],
    index: MeasurementIndex<S, M>,
    clusters: Clusters<N, M>,
    outcomes: [Outcome; N],
    /// What each track's gate kept for its update this scan
    /// ([`TrackFilter::gate_region_keeping`]); read only for a track
    /// assigned a measurement, which its gate gave a region this scan.
    gate_kept: [F::GateKept; N],
    /// The cluster being solved: its tracks' slots and measurements.
    row_slot: [u16; N],
    col_measurement: [u16; M],
    solver: AssignmentSolver<N, M>,
}

impl<S: Numeric, F: TrackFilter<S>, const N: usize, const M: usize> Default
    for TrackTable<S, F, N, M>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Numeric, F: TrackFilter<S>, const N: usize, const M: usize> TrackTable<S, F, N, M> {
    const CAPACITY_OK: () = assert!(
        N < NONE as usize && M < NONE as usize && N + M < NONE as usize,
        "track table capacities must be below 65535 together"
    );

    /// An empty table whose first track gets id 1: all zero bytes (a
    /// `static` table costs no flash).
    pub const fn new() -> Self {
        Self::with_first_id(1)
    }

    /// An empty table whose first track gets id `first_id` (to continue an id
    /// sequence across restarts, or to test wrap-around).
    pub const fn with_first_id(first_id: u32) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_OK;
        TrackTable {
            slots: [const { TrackSlot::Empty }; N],
            previous_id: first_id.wrapping_sub(1),
            last_scan_ms: None,
            pending: [const { None }; M],
            pending_earlier: [false; M],
            pending_count: 0,
            previous_interval_ms: 0,
            stats: TableStats::new(),
            // The workspace is written at the start of each scan before it
            // is read; zero bytes until then.
            observations: [const { None }; M],
            codes: [Association::OutsideGates; M],
            index: MeasurementIndex::new(),
            clusters: Clusters::new(),
            outcomes: [Outcome::Empty; N],
            gate_kept: [F::NOTHING_KEPT; N],
            row_slot: [0; N],
            col_measurement: [0; M],
            solver: AssignmentSolver::new(),
        }
    }

    /// Maximum number of tracks.
    pub const fn capacity(&self) -> usize {
        N
    }
    /// Maximum measurements used per scan.
    pub const fn max_measurements(&self) -> usize {
        M
    }
    /// Live tracks.
    pub fn len(&self) -> usize {
        self.slots.iter().filter(|s| s.is_live()).count()
    }
    /// No live track.
    pub fn is_empty(&self) -> bool {
        self.slots.iter().all(|s| !s.is_live())
    }
    /// Every slot holds a live track: a new track starts only by
    /// displacing a tentative one that missed the last scan, and is
    /// refused when there is none (`DropReason::TableFull`).
    pub fn is_full(&self) -> bool {
        self.slots.iter().all(TrackSlot::is_live)
    }
    /// Live tracks, in slot order.
    pub fn tracks(&self) -> impl Iterator<Item = &Track<S, F>> {
        self.slots.iter().filter_map(TrackSlot::track)
    }
    /// The live track with this id, if any.
    pub fn track(&self, id: TrackId) -> Option<&Track<S, F>> {
        self.tracks().find(|t| t.id == id)
    }
    /// Counters over the table's lifetime.
    pub fn stats(&self) -> &TableStats {
        &self.stats
    }
    /// Time of the last accepted scan.
    pub fn last_scan_ms(&self) -> Option<u32> {
        self.last_scan_ms
    }
    /// Measurements held as first points for initiation.
    pub fn pending(&self) -> usize {
        self.pending_count as usize
    }
    /// The id the next track will get (unless it is in use then).
    pub fn next_id(&self) -> u32 {
        self.previous_id.wrapping_add(1)
    }

    /// Sets the id the next track will get, e.g. a sequence restored from
    /// persistent storage after a restart. Ids of live tracks are still
    /// skipped, so this cannot create a duplicate.
    pub fn set_next_id(&mut self, next_id: u32) {
        self.previous_id = next_id.wrapping_sub(1);
    }

    /// Deletes every track and pending point and forgets the scan time; the
    /// id sequence and the lifetime counters continue.
    pub fn clear(&mut self) {
        self.slots.fill(TrackSlot::Empty);
        self.pending.fill(None);
        self.pending_earlier.fill(false);
        self.pending_count = 0;
        self.last_scan_ms = None;
    }

    fn id_in_use(&self, id: u32) -> bool {
        self.tracks().any(|t| t.id.0 == id)
    }

    /// The next id not in use. Called only when a slot is free, so at most
    /// N − 1 ids are live and one of N consecutive candidates is free.
    fn allocate_id(&mut self) -> TrackId {
        let mut candidate = self.next_id();
        for _ in 0..N {
            if !self.id_in_use(candidate) {
                break;
            }
            candidate = candidate.wrapping_add(1);
        }
        self.previous_id = candidate;
        TrackId(candidate)
    }

    /// One scan at time `now_ms` (a monotonic u32 millisecond clock; it may
    /// wrap, see the module docs) with this scan's measurements.
    ///
    /// Writes the association code of measurement `i` to `codes[i]` for every
    /// `i < min(measurements.len(), codes.len())`; pass a buffer at least as
    /// long as `measurements` to get them all (the report counts them all
    /// regardless). On `Err` nothing changes and nothing is written.
    pub fn scan(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        now_ms: u32,
        measurements: &[Measurement<S>],
        codes: &mut [Association],
    ) -> Result<ScanReport, ScanError> {
        self.scan_with_probe(config, now_ms, measurements, codes, |_| {})
    }

    /// [`Self::scan`], calling `probe` as each [`ScanStage`] ends (for
    /// per-stage timing: the benchmark reads a timer there). Stages that do
    /// not run (the first scan has no tracks to gate) are not reported.
    pub fn scan_with_probe(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        now_ms: u32,
        measurements: &[Measurement<S>],
        codes: &mut [Association],
        probe: impl FnMut(ScanStage),
    ) -> Result<ScanReport, ScanError> {
        self.scan_with_rule(config, now_ms, measurements, codes, &mut AnyPair, probe)
    }

    /// [`Self::scan_with_probe`] where only the pairs `rule` allows may
    /// gate (a track and a measurement) or start a track (a first point,
    /// [`FirstPoint`], and a measurement): reply identity.
    pub fn scan_with_rule(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        now_ms: u32,
        measurements: &[Measurement<S>],
        codes: &mut [Association],
        rule: &mut impl PairRule,
        mut probe: impl FnMut(ScanStage),
    ) -> Result<ScanReport, ScanError> {
        let (interval_ms, timing) = self.interval_to(now_ms, config)?;
        let used = measurements.len().min(M);
        let mut report = ScanReport {
            time_ms: now_ms,
            interval_ms,
            measurements: sat_u32(measurements.len()),
            dropped_overflow: sat_u32(measurements.len().saturating_sub(M)),
            ..ScanReport::default()
        };
        let dt = match timing {
            ScanTiming::TooClose => return Ok(self.skip(measurements, codes, report)),
            ScanTiming::Step(step) => Some(step),
            ScanTiming::First | ScanTiming::TooLong => None,
        };
        self.intake(measurements, &mut report);
        probe(ScanStage::Intake);
        if let Some(dt) = &dt {
            self.index.build(&self.observations);
            probe(ScanStage::Index);
            self.gate(config, dt, &*rule, &mut report);
            probe(ScanStage::Gate);
            self.clusters.link();
            probe(ScanStage::Cluster);
            self.assign(config, dt, &*rule, &mut report)?;
            probe(ScanStage::Assign);
        }
        // From here on the table changes: the scan is accepted.
        self.last_scan_ms = Some(now_ms);
        increment(&mut self.stats.scans);
        if matches!(timing, ScanTiming::TooLong) {
            self.restart_all(&mut report);
        }
        if let Some(dt) = &dt {
            self.update(config, dt, &mut report);
            probe(ScanStage::Update);
            self.manage(config, now_ms, rule, &mut report);
            probe(ScanStage::Manage);
            self.initiate(config, dt, now_ms, &*rule, &mut report);
        }
        self.keep_pending(config, used, &mut report);
        self.previous_interval_ms = interval_ms;
        self.write_codes(codes, measurements.len());
        self.count_lifetime(&mut report);
        probe(ScanStage::Initiate);
        Ok(report)
    }

    /// The interval since the last scan in ms, and how it stands to the
    /// filters' range: in range, the filters' step for it, formed once for
    /// every track.
    fn interval_to(
        &self,
        now_ms: u32,
        config: &TrackerConfig<S, F::Params>,
    ) -> Result<(u32, ScanTiming<F::Step>), ScanError> {
        let Some(previous_ms) = self.last_scan_ms else {
            return Ok((0, ScanTiming::First));
        };
        let interval = now_ms.wrapping_sub(previous_ms);
        if interval == 0 || interval > i32::MAX as u32 {
            return Err(ScanError::TimeNotIncreasing {
                previous_ms,
                now_ms,
            });
        }
        if interval < MIN_INTERVAL_MS {
            return Ok((interval, ScanTiming::TooClose));
        }
        if interval > MAX_INTERVAL_MS {
            return Ok((interval, ScanTiming::TooLong));
        }
        let step = Self::step_of(config, interval).ok_or(ScanError::IntervalNotRepresentable)?;
        Ok((interval, ScanTiming::Step(step)))
    }

    /// The filters' step for an interval of `ms` milliseconds, formed once
    /// for every track; `None` if not representable.
    fn step_of(config: &TrackerConfig<S, F::Params>, ms: u32) -> Option<F::Step> {
        ScanInterval::from_ms(ms).and_then(|i| F::step(config.params(), &i).ok())
    }

    /// A scan too close to the previous one: nothing changes but the
    /// counts; every measurement is coded [`RejectReason::TooClose`].
    fn skip(
        &mut self,
        measurements: &[Measurement<S>],
        codes: &mut [Association],
        mut report: ScanReport,
    ) -> ScanReport {
        report.too_close = sat_u32(measurements.len());
        report.dropped_overflow = 0;
        report.tracks = sat_u32(self.len());
        for code in codes.iter_mut().take(measurements.len()) {
            *code = Association::Rejected(RejectReason::TooClose);
        }
        increment(&mut self.stats.scans_skipped);
        let s = &mut self.stats;
        s.too_close = s.too_close.saturating_add(report.too_close);
        report
    }

    /// A scan more than the longest interval after the previous one:
    /// every track restarts (is ended, counted), and the previous scan's
    /// first points are dropped (too old to pair with).
    fn restart_all(&mut self, report: &mut ScanReport) {
        for slot in self.slots.iter_mut() {
            if slot.clear() {
                increment(&mut report.restarted);
            }
        }
        self.pending.fill(None);
        self.pending_earlier.fill(false);
        self.pending_count = 0;
    }

    /// Intake: validate and project every measurement once, and forget the
    /// previous scan's workspace.
    fn intake(&mut self, measurements: &[Measurement<S>], report: &mut ScanReport) {
        // In place: a whole-array assignment may build the array on the stack.
        self.clusters.reset();
        self.outcomes.fill(Outcome::Empty);
        let mut slots = self.observations.iter_mut().zip(self.codes.iter_mut());
        // Measurements first: `zip` then stops without taking a slot.
        for (m, (obs, code)) in measurements.iter().zip(slots.by_ref()) {
            (*obs, *code) = match Observation::new(*m) {
                Ok(o) => (Some(o), Association::OutsideGates),
                Err(reason) => {
                    increment(&mut report.rejected);
                    (None, Association::Rejected(reason))
                }
            };
        }
        // The slots beyond this scan's measurements.
        for (obs, code) in slots {
            (*obs, *code) = (None, Association::OutsideGates);
        }
    }

    /// Predict, pre-gate and gate: each track's region, the measurements in
    /// its bounding box, the exact test on those; every gated pair is cached
    /// and joins its track's cluster.
    fn gate(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: &F::Step,
        rule: &impl PairRule,
        report: &mut ScanReport,
    ) {
        let params = config.params();
        // Counted in registers, added to the report once: at most N
        // predictions and N·M < 2³² pairs, so no count wraps.
        let (mut predictions, mut candidates, mut gated_pairs) = (0u32, 0u32, 0u32);
        for (t, slot) in self.slots.iter().enumerate() {
            let Some(track) = slot.track() else { continue };
            let Ok(predicted) = track.filter.predict(params, dt) else {
                continue;
            };
            predictions = predictions.wrapping_add(1);
            // One place per slot, so always there. (Indexed, not zipped with
            // the slots: zipped, the M4F's scan is 2.3 % dearer.)
            let Some(kept) = self.gate_kept.get_mut(t) else {
                continue;
            };
            let Some(region) =
                track
                    .filter
                    .gate_region_keeping(params, &predicted, dt, config.gate(), kept)
            else {
                continue;
            };
            if track.lifecycle == Lifecycle::Confirmed && config.gate_too_wide(&region) {
                if let Some(outcome) = self.outcomes.get_mut(t) {
                    *outcome = Outcome::GateTooWide;
                }
                continue;
            }
            let region = track.held_region(region, config.gate(), F::interval_of(dt));
            let (observations, codes, clusters) =
                (&self.observations, &mut self.codes, &mut self.clusters);
            self.index
                .for_each_in(observations, &region.bounds(), |k, o| {
                    candidates = candidates.wrapping_add(1);
                    if !rule.may_update(track.id, k) {
                        return;
                    }
                    let Some(cost) = region.cost(o) else { return };
                    gated_pairs = gated_pairs.wrapping_add(1);
                    clusters.add_pair(t, k, cost);
                    if let Some(code) = codes.get_mut(k) {
                        *code = Association::NotAssigned;
                    }
                });
            if self.clusters.is_uncached(t) {
                increment(&mut report.uncached_tracks);
            }
        }
        report.predicted = report.predicted.saturating_add(predictions);
        report.candidates = report.candidates.saturating_add(candidates);
        report.gated_pairs = report.gated_pairs.saturating_add(gated_pairs);
    }

    /// Associate: the optimal global-nearest-neighbour assignment of each
    /// cluster, solved apart (identical to solving the whole table: see
    /// [`assign`](super::assign), "Ties"). A cluster of one track and one
    /// measurement needs no solver.
    fn assign(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: &F::Step,
        rule: &impl PairRule,
        report: &mut ScanReport,
    ) -> Result<(), ScanError> {
        // Counted in registers, added to the report once (at most N each).
        let (mut clusters, mut single_pairs) = (0u32, 0u32);
        for root in 0..N {
            if !self.clusters.is_root(root) {
                continue;
            }
            clusters = clusters.wrapping_add(1);
            if let Some(k) = self.clusters.single_pair(root) {
                single_pairs = single_pairs.wrapping_add(1);
                self.clusters.assign(root, k);
                continue;
            }
            let (rows, cols) = self.list_cluster(root);
            report.largest_cluster = report.largest_cluster.max(sat_u32(rows));
            self.solve_cluster(config, dt, rule, rows, cols, report)?;
        }
        if single_pairs > 0 {
            report.largest_cluster = report.largest_cluster.max(1);
        }
        report.clusters = report.clusters.saturating_add(clusters);
        report.single_pairs = report.single_pairs.saturating_add(single_pairs);
        report.assigned = report.assigned.saturating_add(single_pairs);
        Ok(())
    }

    /// Copies the cluster rooted at `root` into `row_slot` and
    /// `col_measurement` (and numbers its measurements as its columns in
    /// `clusters`); returns its numbers of tracks and measurements.
    fn list_cluster(&mut self, root: usize) -> (usize, usize) {
        let mut rows = 0usize;
        for (t, r) in self.clusters.tracks_of(root).zip(self.row_slot.iter_mut()) {
            // t < N < 65535.
            *r = t as u16;
            rows = rows.saturating_add(1);
        }
        let cols = self
            .clusters
            .list_measurements(root, &mut self.col_measurement);
        (rows, cols)
    }

    /// The solver on the listed cluster; its pairs into the clusters' links.
    fn solve_cluster(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: &F::Step,
        rule: &impl PairRule,
        rows: usize,
        cols: usize,
        report: &mut ScanReport,
    ) -> Result<(), ScanError> {
        let costs = ClusterCosts {
            slots: &self.slots,
            observations: &self.observations,
            clusters: &self.clusters,
            row_slot: &self.row_slot,
            col_measurement: self.col_measurement.get(..cols).unwrap_or_default(),
            config,
            dt,
            rule,
        };
        let solution = self
            .solver
            .solve_pairs(rows, cols, &costs)
            .map_err(ScanError::Assignment)?;
        report.assigned = report.assigned.saturating_add(solution.assigned);
        report.solver_steps = report.solver_steps.saturating_add(solution.steps);
        for r in 0..rows {
            let Some(c) = self.solver.col_for_row(r) else {
                continue;
            };
            let t = self.row_slot.get(r).copied().unwrap_or(NONE) as usize;
            let k = self.col_measurement.get(c).copied().unwrap_or(NONE) as usize;
            self.clusters.assign(t, k);
        }
        Ok(())
    }

    /// Update each assigned track; coast every other one.
    fn update(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: &F::Step,
        report: &mut ScanReport,
    ) {
        let params = config.params();
        for (t, ((slot, outcome), kept)) in self
            .slots
            .iter_mut()
            .zip(self.outcomes.iter_mut())
            .zip(self.gate_kept.iter())
            .enumerate()
        {
            let Some(track) = slot.track_mut() else {
                continue;
            };
            if *outcome == Outcome::GateTooWide {
                continue;
            }
            *outcome = Outcome::Miss;
            // Only a track whose gate gave a region this scan is assigned:
            // what its gate kept is this scan's.
            if let Some(k) = self.clusters.assigned(t) {
                if let (Some(Some(o)), Some(code)) =
                    (self.observations.get(k), self.codes.get_mut(k))
                {
                    match track.filter.update_after_gate(params, o, dt, kept) {
                        Ok(()) => {
                            *outcome = Outcome::Hit;
                            *code = Association::Updated(track.id);
                            increment(&mut report.updated);
                        }
                        Err(_) => {
                            *code = Association::Rejected(RejectReason::FilterRefused);
                            increment(&mut report.filter_refused);
                            track.refusals = track.refusals.saturating_add(1);
                        }
                    }
                }
            }
            if *outcome == Outcome::Miss {
                increment(&mut report.coasted);
                if track.filter.coast(params, dt).is_err() {
                    *outcome = Outcome::Failed;
                    track.refusals = track.refusals.saturating_add(1);
                }
            }
        }
    }

    /// Confirm, and delete (misses, M-of-N out of reach, left the volume,
    /// arithmetic failed, gate too wide), telling `rule` of each deletion.
    fn manage(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        now_ms: u32,
        rule: &mut impl PairRule,
        report: &mut ScanReport,
    ) {
        for (slot, outcome) in self.slots.iter_mut().zip(self.outcomes.iter()) {
            let Some(track) = slot.track_mut() else {
                continue;
            };
            let hit = *outcome == Outcome::Hit;
            track.record_scan(hit, now_ms);
            let delete = match *outcome {
                Outcome::Failed => Some(Deletion::Numeric),
                Outcome::GateTooWide => Some(Deletion::GateTooWide),
                _ => lifecycle(track, config, report).or_else(|| {
                    (!config.in_volume(track.filter.position())).then_some(Deletion::LeftVolume)
                }),
            };
            if let Some(reason) = delete {
                rule.track_deleted(track.id);
                slot.clear();
                increment(&mut report.deleted);
                match reason {
                    Deletion::Misses => increment(&mut report.deleted_misses),
                    Deletion::Unconfirmed => increment(&mut report.deleted_unconfirmed),
                    Deletion::LeftVolume => increment(&mut report.deleted_left_volume),
                    Deletion::Numeric => increment(&mut report.deleted_numeric),
                    Deletion::GateTooWide => increment(&mut report.deleted_gate_too_wide),
                }
            }
        }
    }

    /// Two-point initiation: the previous scan's first points (`dt` after
    /// them), then the scan before's, if both intervals together are in
    /// range (else they are too old). For each first point in turn, the
    /// nearest unused measurement of this scan within `max_speed·T + margin`
    /// (T the time since the first point) is its second point (sequential
    /// nearest neighbour over the measurements the pre-gate finds in the
    /// circle's bounding box; ties go to the lowest measurement index; see
    /// the module docs for why not an optimal assignment here). One loop
    /// for both (one copy of the code per table type, kept inside the
    /// scan's frame).
    fn initiate(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: &F::Step,
        now_ms: u32,
        rule: &impl PairRule,
        report: &mut ScanReport,
    ) {
        for earlier in [false, true] {
            if self.pending_count == 0 {
                return;
            }
            let since_earlier;
            let dt = if earlier {
                if !self.pending_earlier.contains(&true) {
                    return;
                }
                let interval = self.previous_interval_ms.saturating_add(report.interval_ms);
                if interval > MAX_INTERVAL_MS {
                    return;
                }
                let Some(step) = Self::step_of(config, interval) else {
                    return;
                };
                since_earlier = step;
                &since_earlier
            } else {
                dt
            };
            let interval = F::interval_of(dt).interval();
            let radius = config.max_speed() * interval + config.initiation_margin();
            for p in 0..M {
                if self.pending_earlier.get(p) != Some(&earlier) {
                    continue;
                }
                let Some(Some(first)) = self.pending.get(p) else {
                    continue;
                };
                let Some(region) = GateRegion::circle(first.xy(), radius) else {
                    continue;
                };
                let which = if earlier {
                    FirstPoint::ScanBefore
                } else {
                    FirstPoint::PreviousScan(p)
                };
                let Some(k) = self.nearest_unused(config, &region, |k| rule.may_start(which, k))
                else {
                    continue;
                };
                let code = self.start_track(config, dt, now_ms, [p, k], earlier, report);
                if let Some(c) = self.codes.get_mut(k) {
                    *c = code;
                }
                if let (Some(pending), Some(flag)) =
                    (self.pending.get_mut(p), self.pending_earlier.get_mut(p))
                {
                    *pending = None;
                    *flag = false;
                    self.pending_count = self.pending_count.saturating_sub(1);
                }
            }
        }
    }

    /// The unused measurement (outside every gate, inside the volume) of
    /// least cost in `region`; the lowest index among equal costs.
    fn nearest_unused(
        &self,
        config: &TrackerConfig<S, F::Params>,
        region: &GateRegion<S>,
        allowed: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        let mut best: Option<(u16, usize)> = None;
        let (observations, codes) = (&self.observations, &self.codes);
        self.index
            .for_each_in(observations, &region.bounds(), |k, o| {
                if codes.get(k) != Some(&Association::OutsideGates) || !allowed(k) {
                    return;
                }
                if !config.in_volume(o.xy()) {
                    return;
                }
                if let Some(c) = region.cost(o) {
                    if best.is_none_or(|b| (c, k) < b) {
                        best = Some((c, k));
                    }
                }
            });
        best.map(|(_, k)| k)
    }

    /// A tentative track from first point `p` (`earlier`: of the scan before
    /// the previous one) and this scan's measurement `k`, in a free slot or,
    /// the table full, in the slot of the weakest displaceable tentative
    /// track ([`Self::displaceable`]), which ends there; the second point's
    /// code. The points are read in place, not copied (this is the scan's
    /// deepest call).
    fn start_track(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: &F::Step,
        now_ms: u32,
        [p, k]: [usize; 2],
        earlier: bool,
        report: &mut ScanReport,
    ) -> Association {
        let free = self.slots.iter().position(|s| !s.is_live());
        let Some(slot) = free.or_else(|| self.displaceable(config)) else {
            increment(&mut report.refused_table_full);
            return Association::Dropped(DropReason::TableFull);
        };
        let (Some(Some(first)), Some(Some(second))) =
            (self.pending.get(p), self.observations.get(k))
        else {
            // Not reached: the caller found both.
            return Association::OutsideGates;
        };
        let params = config.params();
        let mut filter = F::empty(params);
        let started = filter
            .update(params, first, dt)
            .and_then(|()| filter.update(params, second, dt));
        if started.is_err() {
            increment(&mut report.filter_refused);
            return Association::Rejected(RejectReason::FilterRefused);
        }
        // The displaced track ends before the id is allocated: at most
        // N − 1 ids are live then.
        if self.slots.get_mut(slot).is_some_and(TrackSlot::clear) {
            increment(&mut report.deleted);
            increment(&mut report.deleted_displaced);
        }
        let id = self.allocate_id();
        let mut track = Track {
            filter,
            id,
            created_ms: now_ms,
            last_update_ms: now_ms,
            history: 1,
            hits: 2,
            // From an earlier first point, the M-of-N window starts at the
            // missed scan between the two points.
            scans: if earlier { 2 } else { 1 },
            lifecycle: Lifecycle::Tentative,
            misses: 0,
            refusals: 0,
            _scalar: PhantomData,
        };
        increment(&mut report.started);
        // Its start is its first hit: confirmed now under a 1-of-N rule.
        if meets_confirmation(&track, config) {
            track.lifecycle = Lifecycle::Confirmed;
            increment(&mut report.confirmed);
        }
        if let Some(slot) = self.slots.get_mut(slot) {
            *slot = TrackSlot::Live(track);
        }
        Association::Started(id)
    }

    /// The slot of the tentative track a new track may displace when the
    /// table is full: among the tentative tracks that missed the last scan
    /// (never a confirmed or coasting track, nor one updated in the last
    /// scan or started in this one), the weakest — the fewest hits in its
    /// M-of-N window, then the most consecutive misses, then the most
    /// scans, then the lowest slot. `None`: no track may be displaced.
    fn displaceable(&self, config: &TrackerConfig<S, F::Params>) -> Option<usize> {
        let window = config.confirmation().1;
        self.slots
            .iter()
            .enumerate()
            .filter_map(|(i, slot)| slot.track().map(|track| (i, track)))
            .filter(|(_, track)| track.lifecycle == Lifecycle::Tentative && track.misses > 0)
            .min_by_key(|&(i, track)| {
                (
                    hits_in_window(track.history, window),
                    core::cmp::Reverse(track.misses),
                    core::cmp::Reverse(track.scans),
                    i,
                )
            })
            .map(|(i, _)| i)
    }

    /// The measurements of this scan still unused become the next scan's
    /// first points (those inside the volume).
    fn keep_pending(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        used: usize,
        report: &mut ScanReport,
    ) {
        let mut count = self.keep_unpaired_first_points(config, used);
        // Only the codes of this scan's measurements: the slots beyond them
        // hold no measurement (counting them put them outside gates).
        for (((pending, earlier), obs), code) in self
            .pending
            .iter_mut()
            .zip(self.pending_earlier.iter_mut())
            .zip(self.observations.iter())
            .zip(self.codes.iter_mut())
            .take(used)
        {
            *pending = None;
            *earlier = false;
            match code {
                Association::OutsideGates => match obs {
                    Some(o) if config.in_volume(o.xy()) => {
                        increment(&mut report.outside_gates);
                        *pending = Some(*o);
                        count = count.saturating_add(1);
                    }
                    _ => {
                        increment(&mut report.outside_volume);
                        *code = Association::OutsideVolume;
                    }
                },
                Association::NotAssigned => increment(&mut report.not_assigned),
                _ => {}
            }
        }
        self.pending_count = count;
    }

    /// Drops the earlier first points; with
    /// [`TrackerConfig::first_points_through_a_miss`], marks the previous
    /// scan's unpaired ones as earlier and moves those at this scan's
    /// measurement places (`..used`, where this scan's first points go) to
    /// free places above them, from the top; those that find none are
    /// dropped.
    /// Returns how many are kept above `used` (those below are about to be
    /// overwritten). With no first point pending, nothing to do: the places
    /// are empty (their `pending_earlier` flags say nothing then).
    fn keep_unpaired_first_points(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        used: usize,
    ) -> u16 {
        if self.pending_count == 0 {
            return 0;
        }
        if !config.first_points_through_a_miss() {
            // Option off: every first point is dropped (a flag left on an
            // empty place says nothing).
            self.pending.fill(None);
            return 0;
        }
        let (mut kept, mut above) = (false, 0u16);
        for (p, (pending, earlier)) in self
            .pending
            .iter_mut()
            .zip(self.pending_earlier.iter_mut())
            .enumerate()
        {
            if *earlier {
                *pending = None;
            }
            *earlier = pending.is_some();
            kept |= *earlier;
            if *earlier && p >= used {
                above = above.saturating_add(1);
            }
        }
        if !kept {
            return 0;
        }
        // Free places are looked for below `top`, downwards.
        let mut top = M;
        for p in 0..used {
            let Some(Some(first)) = self.pending.get(p) else {
                continue;
            };
            let first = *first;
            let Some(free) = (used..top)
                .rev()
                .find(|&q| matches!(self.pending.get(q), Some(None)))
            else {
                break;
            };
            top = free;
            if let (Some(to), Some(earlier)) = (
                self.pending.get_mut(free),
                self.pending_earlier.get_mut(free),
            ) {
                *to = Some(first);
                *earlier = true;
                above = above.saturating_add(1);
            }
        }
        above
    }

    /// The codes out; the measurements beyond M were dropped.
    fn write_codes(&self, codes: &mut [Association], measurements: usize) {
        for (i, out) in codes.iter_mut().take(measurements).enumerate() {
            *out = self
                .codes
                .get(i)
                .copied()
                .unwrap_or(Association::Dropped(DropReason::ScanOverflow));
        }
    }

    /// The report's result and the lifetime counters.
    fn count_lifetime(&mut self, report: &mut ScanReport) {
        report.tracks = sat_u32(self.len());
        let s = &mut self.stats;
        s.tracks_started = s.tracks_started.saturating_add(report.started);
        s.tracks_confirmed = s.tracks_confirmed.saturating_add(report.confirmed);
        s.tracks_deleted = s.tracks_deleted.saturating_add(report.deleted);
        s.refused_table_full = s
            .refused_table_full
            .saturating_add(report.refused_table_full);
        s.tracks_displaced = s.tracks_displaced.saturating_add(report.deleted_displaced);
        s.dropped_overflow = s.dropped_overflow.saturating_add(report.dropped_overflow);
        s.rejected = s.rejected.saturating_add(report.rejected);
        s.filter_refused = s.filter_refused.saturating_add(report.filter_refused);
        s.outside_volume = s.outside_volume.saturating_add(report.outside_volume);
        s.tracks_restarted = s.tracks_restarted.saturating_add(report.restarted);
    }
}

/// The gated pairs of the cluster being solved, row by row, for the
/// solver: a track's cached pairs, or for a track whose pairs did not fit
/// the cache, its gate (the scan's pair rule, predict, region, exact test)
/// recomputed against each measurement of the cluster, as the gate stage
/// computed it.
struct ClusterCosts<'a, S: Numeric, F: TrackFilter<S>, R: PairRule, const N: usize, const M: usize>
{
    slots: &'a [TrackSlot<S, F>; N],
    observations: &'a [Option<Observation<S>>; M],
    clusters: &'a Clusters<N, M>,
    row_slot: &'a [u16; N],
    /// The cluster's measurements, column by column.
    col_measurement: &'a [u16],
    config: &'a TrackerConfig<S, F::Params>,
    dt: &'a F::Step,
    rule: &'a R,
}

impl<S: Numeric, F: TrackFilter<S>, R: PairRule, const N: usize, const M: usize> PairCosts
    for ClusterCosts<'_, S, F, R, N, M>
{
    fn for_each_pair(&self, row: usize, mut pair: impl FnMut(usize, u16)) {
        let t = self.row_slot.get(row).copied().unwrap_or(NONE) as usize;
        if self.clusters.for_each_pair(t, &mut pair) {
            return;
        }
        let params = self.config.params();
        let Some(track) = self.slots.get(t).and_then(TrackSlot::track) else {
            return;
        };
        let gate = self.config.gate();
        let region = track.filter.predict(params, self.dt).ok().and_then(|p| {
            let region = track.filter.gate_region(params, &p, self.dt, gate)?;
            Some(track.held_region(region, gate, F::interval_of(self.dt)))
        });
        let Some(region) = region else { return };
        for (column, &k) in self.col_measurement.iter().enumerate() {
            if !self.rule.may_update(track.id, usize::from(k)) {
                continue;
            }
            let cost = self
                .observations
                .get(usize::from(k))
                .and_then(Option::as_ref)
                .and_then(|o| region.cost(o));
            if let Some(cost) = cost {
                pair(column, cost);
            }
        }
    }
}

#[derive(Clone, Copy)]
enum Deletion {
    Misses,
    Unconfirmed,
    LeftVolume,
    Numeric,
    GateTooWide,
}

/// Confirmation and miss-count deletion after a track's scan was recorded.
fn lifecycle<S: Numeric, F: TrackFilter<S>>(
    track: &mut Track<S, F>,
    config: &TrackerConfig<S, F::Params>,
    report: &mut ScanReport,
) -> Option<Deletion> {
    let (confirm_hits, confirm_window) = config.confirmation();
    let (delete_confirmed, delete_tentative) = config.deletion();
    if track.lifecycle == Lifecycle::Tentative {
        let hits_in_window = hits_in_window(track.history, confirm_window);
        let remaining = (confirm_window as u32).saturating_sub(track.scans as u32);
        if hits_in_window >= u32::from(confirm_hits) {
            track.lifecycle = Lifecycle::Confirmed;
            increment(&mut report.confirmed);
            None
        } else if track.misses >= delete_tentative {
            Some(Deletion::Misses)
        } else if hits_in_window.saturating_add(remaining) < confirm_hits as u32 {
            Some(Deletion::Unconfirmed)
        } else {
            None
        }
    } else if track.misses >= delete_confirmed {
        Some(Deletion::Misses)
    } else {
        None
    }
}

/// Whether the track's hits meet the M-of-N confirmation rule (a new
/// track's start; [`lifecycle`] applies the same test with its window's
/// count at hand).
fn meets_confirmation<S: Numeric, F: TrackFilter<S>>(
    track: &Track<S, F>,
    config: &TrackerConfig<S, F::Params>,
) -> bool {
    let (confirm_hits, confirm_window) = config.confirmation();
    hits_in_window(track.history, confirm_window) >= u32::from(confirm_hits)
}

/// Scans with a measurement among the last `window` of `history`: for a
/// tentative track (at most `window` scans old), the hits of M-of-N over
/// its first N scans (the starting scan is scan 1, or scan 2 after the
/// missed scan of a first point kept through a miss).
fn hits_in_window(history: u32, window: u8) -> u32 {
    let mask = match window {
        32.. => u32::MAX,
        // w < 32.
        w => (1u32 << w).wrapping_sub(1),
    };
    (history & mask).count_ones()
}
