//! The fixed-capacity track table and its scan.

use core::marker::PhantomData;

use super::assign::{AssignError, AssignmentSolver, FORBIDDEN};
use super::config::TrackerConfig;
use super::gate::GateRegion;
use super::model::{Measurement, Observation, RejectReason, TrackFilter};
use crate::num::Scalar;

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

/// One record of the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Track<S, F> {
    id: TrackId,
    status: TrackStatus,
    /// Consecutive scans without a measurement.
    misses: u8,
    /// Measurements incorporated (the two initiation points included),
    /// saturating.
    hits: u16,
    /// Scans since the track was started (that scan included), saturating.
    scans: u16,
    /// Bit k set: the scan k scans ago had a measurement (bit 0 = last scan).
    /// Bits older than the track's start are 0.
    history: u32,
    created_ms: u32,
    last_update_ms: u32,
    filter: F,
    _scalar: PhantomData<S>,
}

impl<S: Scalar, F: TrackFilter<S>> Track<S, F> {
    pub fn id(&self) -> TrackId {
        self.id
    }
    pub fn status(&self) -> TrackStatus {
        self.status
    }
    /// Confirmed or coasting.
    pub fn is_confirmed(&self) -> bool {
        self.status != TrackStatus::Tentative
    }
    pub fn filter(&self) -> &F {
        &self.filter
    }
    pub fn position(&self) -> [S; 2] {
        self.filter.position()
    }
    pub fn velocity(&self) -> [S; 2] {
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
    /// Scans since the track started (its first scan counts 1).
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

    fn record_scan(&mut self, hit: bool, now_ms: u32) {
        self.history = (self.history << 1) | hit as u32;
        self.scans = self.scans.saturating_add(1);
        if hit {
            self.hits = self.hits.saturating_add(1);
            self.misses = 0;
            self.last_update_ms = now_ms;
            if self.status == TrackStatus::Coasting {
                self.status = TrackStatus::Confirmed;
            }
        } else {
            self.misses = self.misses.saturating_add(1);
            if self.status == TrackStatus::Confirmed {
                self.status = TrackStatus::Coasting;
            }
        }
    }
}

/// Why a measurement was dropped unused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DropReason {
    /// It would have started a track but the table was full.
    TableFull,
    /// The scan had more than `M` measurements; this is one of the excess.
    ScanOverflow,
}

/// What happened to one measurement of a scan (TI gtrack-style association
/// code).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Association {
    /// Updated this track.
    Updated(TrackId),
    /// Paired with a measurement of the previous scan and started this
    /// (tentative) track.
    Started(TrackId),
    /// Inside at least one gate, but the optimal assignment gave those tracks
    /// other measurements. Not used to start tracks (it would duplicate a
    /// neighbouring track).
    NotAssigned,
    /// Inside no gate and paired with nothing; kept (if inside the
    /// surveillance volume) as a first point for initiation in the next scan.
    OutsideGates,
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
    TimeNotIncreasing { previous_ms: u32, now_ms: u32 },
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
    // --- predict, gate, associate
    /// Tracks predicted to the scan time.
    pub predicted: u32,
    /// (track, measurement) pairs inside a gate.
    pub gated_pairs: u32,
    /// Pairs chosen by the assignment.
    pub assigned: u32,
    /// Inner steps of the assignment solver.
    pub solver_steps: u32,
    // --- update
    /// Tracks updated with their measurement.
    pub updated: u32,
    /// Assigned, but the filter refused the update (the track coasted).
    pub filter_refused: u32,
    /// Tracks that got no measurement and coasted.
    pub coasted: u32,
    /// Measurements inside a gate but not assigned.
    pub not_assigned: u32,
    // --- manage
    /// Tracks started.
    pub started: u32,
    /// Tracks that would have started but the table was full.
    pub refused_table_full: u32,
    /// Measurements left outside every gate and unpaired.
    pub outside_gates: u32,
    /// Tracks confirmed in this scan.
    pub confirmed: u32,
    /// Tracks deleted in this scan (sum of the four reasons below).
    pub deleted: u32,
    /// ... after too many consecutive misses.
    pub deleted_misses: u32,
    /// ... tentative tracks that could no longer meet M-of-N.
    pub deleted_unconfirmed: u32,
    /// ... that left the surveillance volume.
    pub deleted_left_volume: u32,
    /// ... whose filter could not advance (arithmetic saturated).
    pub deleted_numeric: u32,
    // --- result
    /// Live tracks after the scan.
    pub tracks: u32,
}

/// Counters over the table's lifetime (saturating).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TableStats {
    pub scans: u32,
    pub tracks_started: u32,
    pub tracks_confirmed: u32,
    pub tracks_deleted: u32,
    /// Candidate tracks refused because the table was full.
    pub refused_table_full: u32,
    /// Measurements beyond `M` in a scan.
    pub dropped_overflow: u32,
    /// Measurements rejected as bad input.
    pub rejected: u32,
}

const NONE: u16 = u16::MAX;

/// A fixed-capacity multi-target tracker: at most `N` tracks and `M`
/// measurements per scan, no heap, `const fn new` (fits in a `static`).
///
/// See the [module docs](super) for the scan's stages, the time base and the
/// memory figures.
#[derive(Debug)]
pub struct TrackTable<S, F, const N: usize, const M: usize> {
    slots: [Option<Track<S, F>>; N],
    next_id: u32,
    last_scan_ms: Option<u32>,
    /// Unused measurements of the previous scan: first points for two-point
    /// initiation.
    pending: [Option<Observation<S>>; M],
    stats: TableStats,
    // --- per-scan workspace (kept here, not on the stack: N×M can be large)
    cost: [[u16; M]; N],
    observations: [Option<Observation<S>>; M],
    codes: [Association; M],
    slot_measurement: [u16; N],
    row_slot: [u16; N],
    col_measurement: [u16; M],
    solver: AssignmentSolver<N, M>,
}

impl<S: Scalar, F: TrackFilter<S>, const N: usize, const M: usize> Default
    for TrackTable<S, F, N, M>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, F: TrackFilter<S>, const N: usize, const M: usize> TrackTable<S, F, N, M> {
    const CAPACITY_OK: () = assert!(
        N < NONE as usize && M < NONE as usize,
        "track table capacities must be below 65535"
    );

    /// An empty table whose first track gets id 1.
    pub const fn new() -> Self {
        Self::with_first_id(1)
    }

    /// An empty table whose first track gets id `first_id` (to continue an id
    /// sequence across restarts, or to test wrap-around).
    pub const fn with_first_id(first_id: u32) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_OK;
        TrackTable {
            slots: [const { None }; N],
            next_id: first_id,
            last_scan_ms: None,
            pending: [const { None }; M],
            stats: TableStats {
                scans: 0,
                tracks_started: 0,
                tracks_confirmed: 0,
                tracks_deleted: 0,
                refused_table_full: 0,
                dropped_overflow: 0,
                rejected: 0,
            },
            cost: [[FORBIDDEN; M]; N],
            observations: [const { None }; M],
            codes: [Association::OutsideGates; M],
            slot_measurement: [NONE; N],
            row_slot: [NONE; N],
            col_measurement: [NONE; M],
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
        self.slots.iter().filter(|s| s.is_some()).count()
    }
    pub fn is_empty(&self) -> bool {
        self.slots.iter().all(|s| s.is_none())
    }
    pub fn is_full(&self) -> bool {
        self.slots.iter().all(|s| s.is_some())
    }
    /// Live tracks, in slot order.
    pub fn tracks(&self) -> impl Iterator<Item = &Track<S, F>> {
        self.slots.iter().flatten()
    }
    pub fn track(&self, id: TrackId) -> Option<&Track<S, F>> {
        self.tracks().find(|t| t.id == id)
    }
    pub fn stats(&self) -> &TableStats {
        &self.stats
    }
    /// Time of the last accepted scan.
    pub fn last_scan_ms(&self) -> Option<u32> {
        self.last_scan_ms
    }
    /// Measurements held as first points for initiation.
    pub fn pending(&self) -> usize {
        self.pending.iter().filter(|p| p.is_some()).count()
    }
    /// The id the next track will get (unless it is in use then).
    pub fn next_id(&self) -> u32 {
        self.next_id
    }

    /// Sets the id the next track will get, e.g. a sequence restored from
    /// persistent storage after a restart. Ids of live tracks are still
    /// skipped, so this cannot create a duplicate.
    pub fn set_next_id(&mut self, next_id: u32) {
        self.next_id = next_id;
    }

    /// Deletes every track and pending point and forgets the scan time; the
    /// id sequence and the lifetime counters continue.
    pub fn clear(&mut self) {
        self.slots.fill(None);
        self.pending.fill(None);
        self.last_scan_ms = None;
    }

    fn id_in_use(&self, id: u32) -> bool {
        self.tracks().any(|t| t.id.0 == id)
    }

    /// The next id not in use. Called only when a slot is free, so at most
    /// N − 1 ids are live and one of N consecutive candidates is free.
    fn allocate_id(&mut self) -> TrackId {
        let mut candidate = self.next_id;
        for _ in 0..N {
            if !self.id_in_use(candidate) {
                break;
            }
            candidate = candidate.wrapping_add(1);
        }
        self.next_id = candidate.wrapping_add(1);
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
        let (interval_ms, dt) = match self.last_scan_ms {
            None => (0, None),
            Some(previous_ms) => {
                let interval = now_ms.wrapping_sub(previous_ms);
                if interval == 0 || interval > i32::MAX as u32 {
                    return Err(ScanError::TimeNotIncreasing {
                        previous_ms,
                        now_ms,
                    });
                }
                let dt = S::try_from_f64(interval as f64 / 1000.0)
                    .map_err(|_| ScanError::IntervalNotRepresentable)?;
                if dt <= S::ZERO {
                    return Err(ScanError::IntervalNotRepresentable);
                }
                (interval, Some(dt))
            }
        };
        let params = config.params();
        let mut report = ScanReport {
            time_ms: now_ms,
            interval_ms,
            measurements: sat_u32(measurements.len()),
            dropped_overflow: sat_u32(measurements.len().saturating_sub(M)),
            ..ScanReport::default()
        };

        // Intake: validate and project every measurement once.
        // In place: a whole-array assignment may build the array on the stack.
        self.observations.fill(None);
        self.codes.fill(Association::OutsideGates);
        for ((m, obs), code) in measurements
            .iter()
            .zip(self.observations.iter_mut())
            .zip(self.codes.iter_mut())
        {
            match Observation::new(*m) {
                Ok(o) => *obs = Some(o),
                Err(reason) => {
                    *code = Association::Rejected(reason);
                    report.rejected += 1;
                }
            }
        }

        // Predict and gate.
        let mut n_rows = 0usize;
        if let Some(dt) = dt {
            for (slot_index, (slot, cost_row)) in
                self.slots.iter().zip(self.cost.iter_mut()).enumerate()
            {
                cost_row.fill(FORBIDDEN);
                let Some(track) = slot else { continue };
                let region: Option<GateRegion<S>> = match track.filter.predict(params, dt) {
                    Ok(predicted) => {
                        report.predicted += 1;
                        track
                            .filter
                            .gate_region(params, &predicted, dt, config.gate())
                    }
                    Err(_) => None,
                };
                let Some(region) = region else { continue };
                let mut gated = false;
                for ((cost, obs), code) in cost_row
                    .iter_mut()
                    .zip(self.observations.iter())
                    .zip(self.codes.iter_mut())
                {
                    let Some(o) = obs else { continue };
                    if let Some(c) = region.cost(o) {
                        *cost = c;
                        *code = Association::NotAssigned;
                        report.gated_pairs += 1;
                        gated = true;
                    }
                }
                if gated {
                    if let Some(r) = self.row_slot.get_mut(n_rows) {
                        // slot_index < N < 65535.
                        *r = slot_index as u16;
                        n_rows += 1;
                    }
                }
            }
        }
        let mut n_cols = 0usize;
        for (k, code) in self.codes.iter().enumerate() {
            if *code == Association::NotAssigned {
                if let Some(c) = self.col_measurement.get_mut(n_cols) {
                    // k < M < 65535.
                    *c = k as u16;
                    n_cols += 1;
                }
            }
        }

        // Associate: optimal global nearest neighbour on the gated sub-problem.
        self.slot_measurement.fill(NONE);
        {
            let cost = &self.cost;
            let row_slot = &self.row_slot;
            let col_measurement = &self.col_measurement;
            let lookup = |r: usize, c: usize| -> u16 {
                let slot = row_slot.get(r).copied().unwrap_or(NONE) as usize;
                let k = col_measurement.get(c).copied().unwrap_or(NONE) as usize;
                cost.get(slot)
                    .and_then(|row| row.get(k))
                    .copied()
                    .unwrap_or(FORBIDDEN)
            };
            let solution = self
                .solver
                .solve(n_rows, n_cols, lookup)
                .map_err(ScanError::Assignment)?;
            report.assigned = solution.assigned;
            report.solver_steps = solution.steps;
        }
        for r in 0..n_rows {
            let Some(c) = self.solver.col_for_row(r) else {
                continue;
            };
            let slot = self.row_slot.get(r).copied().unwrap_or(NONE) as usize;
            let k = self.col_measurement.get(c).copied().unwrap_or(NONE);
            if let Some(s) = self.slot_measurement.get_mut(slot) {
                *s = k;
            }
        }

        // From here on the table changes: the scan is accepted.
        self.last_scan_ms = Some(now_ms);
        self.stats.scans = self.stats.scans.saturating_add(1);

        // Update, coast, confirm, delete.
        let (confirm_hits, confirm_window) = config.confirmation();
        let (delete_confirmed, delete_tentative) = config.deletion();
        if let Some(dt) = dt {
            for (slot, &k) in self.slots.iter_mut().zip(self.slot_measurement.iter()) {
                let Some(track) = slot else { continue };
                let mut hit = false;
                if let (Some(Some(o)), Some(code)) = (
                    self.observations.get(k as usize),
                    self.codes.get_mut(k as usize),
                ) {
                    match track.filter.update(params, o, dt) {
                        Ok(()) => {
                            hit = true;
                            *code = Association::Updated(track.id);
                            report.updated += 1;
                        }
                        Err(_) => {
                            *code = Association::Rejected(RejectReason::FilterRefused);
                            report.filter_refused += 1;
                        }
                    }
                }
                let mut delete = None;
                if !hit {
                    report.coasted += 1;
                    if track.filter.coast(params, dt).is_err() {
                        delete = Some(Deletion::Numeric);
                    }
                }
                track.record_scan(hit, now_ms);
                if delete.is_none() {
                    delete = manage(
                        track,
                        confirm_hits,
                        confirm_window,
                        delete_confirmed,
                        delete_tentative,
                        &mut report,
                    );
                }
                if delete.is_none() && !config.in_volume(track.filter.position()) {
                    delete = Some(Deletion::LeftVolume);
                }
                if let Some(reason) = delete {
                    *slot = None;
                    report.deleted += 1;
                    match reason {
                        Deletion::Misses => report.deleted_misses += 1,
                        Deletion::Unconfirmed => report.deleted_unconfirmed += 1,
                        Deletion::LeftVolume => report.deleted_left_volume += 1,
                        Deletion::Numeric => report.deleted_numeric += 1,
                    }
                }
            }
        }

        // Initiate: pair the previous scan's unused measurements with this
        // scan's measurements outside every gate (two-point initiation).
        if let Some(dt) = dt {
            self.initiate(config, dt, now_ms, &mut report);
        }

        // The measurements still unused become next scan's first points.
        self.pending.fill(None);
        // Only the codes of this scan's measurements: the slots beyond them
        // hold no measurement (issue 11: they were counted outside gates).
        for ((pending, obs), code) in self
            .pending
            .iter_mut()
            .zip(self.observations.iter())
            .zip(self.codes.iter())
            .take(measurements.len())
        {
            if *code == Association::OutsideGates {
                report.outside_gates += 1;
                if let Some(o) = obs {
                    if config.in_volume(o.xy()) {
                        *pending = Some(*o);
                    }
                }
            }
            if *code == Association::NotAssigned {
                report.not_assigned += 1;
            }
        }

        // Report codes; the measurements beyond M were dropped.
        for (i, out) in codes.iter_mut().take(measurements.len()).enumerate() {
            *out = self
                .codes
                .get(i)
                .copied()
                .unwrap_or(Association::Dropped(DropReason::ScanOverflow));
        }

        report.tracks = sat_u32(self.len());
        let s = &mut self.stats;
        s.tracks_started = s.tracks_started.saturating_add(report.started);
        s.tracks_confirmed = s.tracks_confirmed.saturating_add(report.confirmed);
        s.tracks_deleted = s.tracks_deleted.saturating_add(report.deleted);
        s.refused_table_full = s
            .refused_table_full
            .saturating_add(report.refused_table_full);
        s.dropped_overflow = s.dropped_overflow.saturating_add(report.dropped_overflow);
        s.rejected = s.rejected.saturating_add(report.rejected);
        Ok(report)
    }

    /// Two-point initiation. For each pending first point in turn, the nearest
    /// unused measurement of this scan within `max_speed·T + margin` is its
    /// second point (sequential nearest neighbour, P·L distance tests for P
    /// pending points and L unused measurements; see the module docs for why
    /// not an optimal assignment here).
    fn initiate(
        &mut self,
        config: &TrackerConfig<S, F::Params>,
        dt: S,
        now_ms: u32,
        report: &mut ScanReport,
    ) {
        let params = config.params();
        let radius = config.max_speed() * dt + config.initiation_margin();
        let (confirm_hits, _) = config.confirmation();
        for p in 0..M {
            let Some(Some(first)) = self.pending.get(p).copied() else {
                continue;
            };
            let Some(region) = GateRegion::circle(first.xy(), radius) else {
                continue;
            };
            let mut best: Option<(u16, usize)> = None;
            for (k, (obs, code)) in self.observations.iter().zip(self.codes.iter()).enumerate() {
                if *code != Association::OutsideGates {
                    continue;
                }
                let Some(o) = obs else { continue };
                if !config.in_volume(o.xy()) {
                    continue;
                }
                if let Some(c) = region.cost(o) {
                    if best.is_none_or(|(b, _)| c < b) {
                        best = Some((c, k));
                    }
                }
            }
            let Some((_, k)) = best else { continue };
            let Some(Some(second)) = self.observations.get(k).copied() else {
                continue;
            };
            let code = if let Some(free) = self.slots.iter().position(|s| s.is_none()) {
                let mut filter = F::empty(params);
                let started = filter
                    .update(params, &first, dt)
                    .and_then(|()| filter.update(params, &second, dt));
                if started.is_ok() {
                    let id = self.allocate_id();
                    let mut track = Track {
                        id,
                        status: TrackStatus::Tentative,
                        misses: 0,
                        hits: 2,
                        scans: 1,
                        history: 1,
                        created_ms: now_ms,
                        last_update_ms: now_ms,
                        filter,
                        _scalar: PhantomData,
                    };
                    report.started += 1;
                    if confirm_hits <= 1 {
                        track.status = TrackStatus::Confirmed;
                        report.confirmed += 1;
                    }
                    if let Some(slot) = self.slots.get_mut(free) {
                        *slot = Some(track);
                    }
                    Association::Started(id)
                } else {
                    Association::Rejected(RejectReason::FilterRefused)
                }
            } else {
                report.refused_table_full += 1;
                Association::Dropped(DropReason::TableFull)
            };
            if let Some(c) = self.codes.get_mut(k) {
                *c = code;
            }
            if let Some(pending) = self.pending.get_mut(p) {
                *pending = None;
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
}

/// Confirmation and miss-count deletion after a track's scan was recorded.
fn manage<S: Scalar, F: TrackFilter<S>>(
    track: &mut Track<S, F>,
    confirm_hits: u8,
    confirm_window: u8,
    delete_confirmed: u8,
    delete_tentative: u8,
    report: &mut ScanReport,
) -> Option<Deletion> {
    if track.status == TrackStatus::Tentative {
        // M-of-N over the first N scans (the starting scan is scan 1).
        let mask = match confirm_window {
            32.. => u32::MAX,
            w => (1u32 << w) - 1,
        };
        let hits_in_window = (track.history & mask).count_ones();
        let remaining = (confirm_window as u32).saturating_sub(track.scans as u32);
        if hits_in_window >= confirm_hits as u32 {
            track.status = TrackStatus::Confirmed;
            report.confirmed += 1;
            None
        } else if track.misses >= delete_tentative {
            Some(Deletion::Misses)
        } else if hits_in_window + remaining < confirm_hits as u32 {
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

fn sat_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}
