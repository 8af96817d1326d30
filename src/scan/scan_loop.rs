//! The consumer half, run from the main loop: the scan clock, the scan's
//! batch, the tracker scan and the reports.

mod capacity;
mod intruders;

use super::{ClockConfig, MeasurementSource};
use crate::count::{increment, increment16, sat_u16, sat_u32};
use capacity::{Priority, TrackGate, CLASS_OTHER};
pub use intruders::MAX_RA_THREATS;
use intruders::{IdentityRule, IntruderSlot, ReplyData};

use crate::filter::altitude::{AltitudeEstimate, AltitudeQuantum, AltitudeTrackerConfig};
use crate::filter::range_azimuth::RangeAzimuthState;
use crate::num::{Numeric, Scalar};
use crate::tcas::{range_tau, Advisory, CollisionAvoidance, IntruderTrack, OwnAircraft};
use crate::track::{
    Association, DropReason, FixedGainTrack, Measurement, Observation, RangeAzimuthTrack,
    ScanError, ScanReport, TrackFilter, TrackId, TrackTable, TrackerConfig,
};
use crate::wire::{
    Health, LoopCounters, MeasurementReport, Message, ModeSAddress, RaCode, ScanCounts,
    ScanSummary, TrackReport,
};

/// What a [`ScanLoop`] needs besides its state. Kept outside it (as
/// [`TrackerConfig`] is kept outside [`TrackTable`]) so that the loop can be
/// built by a `const fn` in a `static`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanConfig<T: Numeric, P> {
    /// The track table's configuration (gates, lifecycle, region). The
    /// loop keeps the previous scan's replies only, so its identity rule
    /// starts no track from an earlier scan's first point: first points
    /// kept through a miss cost carrying and start nothing (the demo turns
    /// them off, `keep_first_points_through_a_miss(false)`).
    pub tracker: TrackerConfig<T::Wide, P>,
    /// The own aircraft, for the threat assessment.
    pub own: OwnAircraft<T::Wide>,
    /// The altitude tracker of an intruder reporting in 100 ft steps
    /// (Mode C) …
    pub altitude: AltitudeTrackerConfig<T::Wide>,
    /// … and of one reporting in 25 ft steps (Mode S with the Q bit).
    pub altitude_25ft: AltitudeTrackerConfig<T::Wide>,
    /// The scan period and the clock's windows.
    pub clock: ClockConfig,
}

impl<T: Numeric, P> ScanConfig<T, P> {
    /// The altitude tracker's configuration for reports in `quantum`'s steps.
    pub fn altitude_of(&self, quantum: AltitudeQuantum) -> &AltitudeTrackerConfig<T::Wide> {
        match quantum {
            AltitudeQuantum::ModeC => &self.altitude,
            AltitudeQuantum::ModeS25 => &self.altitude_25ft,
        }
    }
}

/// What [`ScanLoop::collect`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Collected {
    /// The queue is empty: this scan may still get measurements.
    Waiting,
    /// The input has moved past this scan (a measurement for a later scan
    /// is at the head of the queue, or the clock must re-lock): run it.
    ScanDue,
}

/// The result of one tick.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TickReport {
    /// The tracker's per-stage counts.
    pub scan: ScanReport,
    /// What was emitted as the scan summary.
    pub summary: ScanSummary,
}

/// The position track's bearing tracker, for the threat logic's
/// miss-distance cross-check (He et al.'s range–azimuth filter; none for a
/// Cartesian track).
pub trait BearingTrack<S: Scalar> {
    /// The state of this track's range–azimuth filter, if it has one.
    fn bearing_track(&self) -> Option<&RangeAzimuthState<S>>;
}

impl<N: Numeric<Wide = S>, S: Scalar> BearingTrack<S> for RangeAzimuthTrack<N> {
    fn bearing_track(&self) -> Option<&RangeAzimuthState<S>> {
        Some(self.state())
    }
}

impl<S: Scalar> BearingTrack<S> for FixedGainTrack<S> {
    fn bearing_track(&self) -> Option<&RangeAzimuthState<S>> {
        None
    }
}

/// Where a measurement's time puts it ([`crate::scan`], "Time").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Timing {
    ThisScan,
    LaterScan,
    Late,
    OutOfWindow,
}

/// `d` of [`crate::scan`]'s docs: `t − n` as a signed 32-bit difference.
fn signed_difference(t: u32, n: u32) -> i32 {
    i32::from_ne_bytes(t.wrapping_sub(n).to_ne_bytes())
}

/// `v·scale` rounded to an integer, saturated to the i32 range (NaN → 0).
/// Reports carry tracks inside the ±400 km envelope, where nothing saturates.
fn scaled_i32<S: Scalar>(v: S, scale: u32) -> i32 {
    v.round_scaled_i32(scale)
}

/// The consumer half: sorts queued measurements into scans, turns each scan
/// into a tracker scan, threat assessments and reports. At most `N` tracks,
/// `M` measurements per scan. Named with the core's number type `T`, it
/// computes in `T::Wide` ([`Numeric::Wide`]), as its table and `F` do.
///
/// Memory: the [`TrackTable`] (see [`crate::track`] for its size), plus per
/// measurement slot one `Measurement<T::Wide>`, one `Option<T::Wide>`, a
/// priority and an [`Association`], plus per track slot a gate region and
/// its TCAS state (an [`IntruderTrack`], its Mode S address and quantum).
/// `host-tests/tests/it/scan/loop_on_host.rs` prints the sizes; the firmware prints
/// its own at start-up.
#[derive(Debug)]
pub struct ScanLoop<T: Numeric, F: TrackFilter<T::Wide>, const N: usize, const M: usize> {
    table: TrackTable<T::Wide, F, N, M>,
    /// The tracker's time of the next scan (ms; +1 period per scan).
    tracker_ms: u32,
    /// The sensor's time of the scan being assembled.
    scan_ms: u32,
    locked: bool,
    /// A measurement outside the window, held until the next one (at most
    /// one: a vector, so that "none" is all-zero bytes).
    candidate: heapless::Vec<MeasurementReport, 1>,
    /// The next measurement confirmed the candidate: re-lock after this scan.
    relock: bool,
    batch: heapless::Vec<Measurement<T::Wide>, M>,
    /// Per batch entry: altitude and Mode S address.
    batch_replies: heapless::Vec<ReplyData<T::Wide>, M>,
    /// The previous scan's (the first points of new tracks).
    previous_replies: heapless::Vec<ReplyData<T::Wide>, M>,
    batch_priorities: heapless::Vec<Priority<T::Wide>, M>,
    /// Per TCAS slot (`intruders`' order), its track's gate if the track is
    /// confirmed (vectors, here and below, so that the empty loop is
    /// all-zero bytes).
    gates: heapless::Vec<TrackGate<T::Wide>, N>,
    /// The batch overflowed: `gates` and the priorities are computed.
    ranked: bool,
    /// Counts of the scan being assembled (the intake part).
    pending_counts: ScanCounts,
    /// Per batch entry, the tracker's code; filled to `M` at the first scan.
    codes: heapless::Vec<Association, M>,
    intruders: heapless::Vec<IntruderSlot<T::Wide>, N>,
    /// The system's TCAS state: sensitivity level, inhibits, the RA.
    cas: CollisionAvoidance<T::Wide>,
    counters: LoopCounters,
}

impl<
        T: Numeric<Wide = S>,
        S: Scalar,
        F: TrackFilter<S> + BearingTrack<S>,
        const N: usize,
        const M: usize,
    > Default for ScanLoop<T, F, N, M>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<
        T: Numeric<Wide = S>,
        S: Scalar,
        F: TrackFilter<S> + BearingTrack<S>,
        const N: usize,
        const M: usize,
    > ScanLoop<T, F, N, M>
{
    /// An empty loop: no tracks, no queued batch, zero counters (a `const fn`,
    /// for a `static`).
    pub const fn new() -> Self {
        ScanLoop {
            table: TrackTable::new(),
            tracker_ms: 0,
            scan_ms: 0,
            locked: false,
            candidate: heapless::Vec::new(),
            relock: false,
            batch: heapless::Vec::new(),
            batch_replies: heapless::Vec::new(),
            previous_replies: heapless::Vec::new(),
            batch_priorities: heapless::Vec::new(),
            gates: heapless::Vec::new(),
            ranked: false,
            pending_counts: ScanCounts::new(),
            codes: heapless::Vec::new(),
            intruders: heapless::Vec::new(),
            cas: CollisionAvoidance::new(),
            counters: LoopCounters::new(),
        }
    }

    /// The track table.
    pub fn table(&self) -> &TrackTable<S, F, N, M> {
        &self.table
    }

    /// The loop's counters (scans, measurements used and not used by reason).
    pub fn counters(&self) -> &LoopCounters {
        &self.counters
    }

    /// The sensor's time of the scan being assembled (meaningful once the
    /// clock has locked).
    pub fn scan_time_ms(&self) -> u32 {
        self.scan_ms
    }

    /// Whether the clock has locked onto the sensor's.
    pub fn is_locked(&self) -> bool {
        self.locked
    }

    /// Measurements collected for the next scan.
    pub fn batch_len(&self) -> usize {
        self.batch.len()
    }

    /// Measurements taken from the queue and not yet used or dropped: the
    /// batch and a held out-of-window measurement.
    pub fn held(&self) -> usize {
        self.batch.len().saturating_add(self.candidate.len())
    }

    /// The altitude estimate of a track, if it reported altitude.
    pub fn altitude(&self, track: TrackId) -> Option<AltitudeEstimate<S>> {
        self.intruder(track)
            .and_then(|t| t.altitude_state().estimate())
    }

    /// The TCAS surveillance of a track: range and altitude trackers,
    /// threat state.
    pub fn intruder(&self, track: TrackId) -> Option<&IntruderTrack<S>> {
        self.slot(track).map(|s| &s.tcas)
    }

    /// The Mode S address a track keeps.
    pub fn address(&self, track: TrackId) -> Option<ModeSAddress> {
        self.slot(track).and_then(|s| s.address)
    }

    fn slot(&self, track: TrackId) -> Option<&IntruderSlot<S>> {
        self.intruders.iter().find(|s| s.track == track)
    }

    fn timing(&self, clock: &ClockConfig, t: u32) -> Timing {
        let d = signed_difference(t, self.scan_ms);
        let distance = d.unsigned_abs();
        if d > 0 {
            if distance <= clock.jump_ms {
                Timing::LaterScan
            } else {
                Timing::OutOfWindow
            }
        } else if distance < clock.period_ms {
            Timing::ThisScan
        } else if distance <= clock.late_window_ms {
            Timing::Late
        } else {
            Timing::OutOfWindow
        }
    }

    /// Drops the held out-of-window measurement, counted.
    fn drop_candidate(&mut self) {
        if self.candidate.pop().is_some() {
            increment16(&mut self.pending_counts.out_of_window);
            increment(&mut self.counters.out_of_window);
        }
    }

    /// Takes the queued measurements that belong to the scan being
    /// assembled into its batch (converting them: the checked edge), and
    /// counts the late and out-of-window ones; stops at the first one for a
    /// later scan. Call it as often as wanted between scans: it frees queue
    /// space early.
    pub fn collect(
        &mut self,
        config: &ScanConfig<T, F::Params>,
        source: &mut impl MeasurementSource,
    ) -> Collected {
        let clock = &config.clock;
        loop {
            if self.relock {
                return Collected::ScanDue;
            }
            let Some(head) = source.peek() else {
                return Collected::Waiting;
            };
            if !self.locked {
                self.locked = true;
                self.scan_ms = head.time_ms;
                increment(&mut self.counters.clock_locks);
            }
            match self.timing(clock, head.time_ms) {
                Timing::ThisScan => {
                    self.drop_candidate();
                    if let Some(m) = source.pop() {
                        self.take(config, &m);
                    }
                }
                Timing::LaterScan => {
                    self.drop_candidate();
                    return Collected::ScanDue;
                }
                Timing::Late => {
                    self.drop_candidate();
                    if source.pop().is_some() {
                        increment16(&mut self.pending_counts.late);
                        increment(&mut self.counters.late);
                    }
                }
                Timing::OutOfWindow => {
                    let consistent = self.candidate.first().is_some_and(|c| {
                        signed_difference(head.time_ms, c.time_ms).unsigned_abs() <= clock.period_ms
                    });
                    if consistent {
                        self.relock = true;
                        return Collected::ScanDue;
                    }
                    self.drop_candidate();
                    if let Some(m) = source.pop() {
                        let _ = self.candidate.push(m);
                    }
                }
            }
        }
    }

    /// Re-locks onto the held measurement's time; it joins the (empty)
    /// batch.
    fn apply_relock(&mut self, config: &ScanConfig<T, F::Params>) {
        self.relock = false;
        if let Some(c) = self.candidate.pop() {
            self.scan_ms = c.time_ms;
            increment(&mut self.counters.clock_relocks);
            self.take(config, &c);
        }
    }

    /// One measurement of this scan: converted, then into the batch; by
    /// priority once the batch is full.
    fn take(&mut self, config: &ScanConfig<T, F::Params>, report: &MeasurementReport) {
        let converted = report
            .position::<S>()
            .and_then(|m| report.altitude::<S>().map(|a| (m, a)));
        let Ok((measurement, altitude_ft)) = converted else {
            increment16(&mut self.pending_counts.invalid);
            increment(&mut self.counters.invalid);
            return;
        };
        let reply = ReplyData {
            altitude_ft,
            altitude_25ft: report.altitude_25ft,
            address: report.address,
        };
        if self.batch.len() < M {
            // Room: no priority needed (yet). Three pushes on vectors of the
            // same length below M.
            let _ = self.batch.push(measurement);
            let _ = self.batch_replies.push(reply);
            let _ = self.batch_priorities.push(Priority {
                class: CLASS_OTHER,
                gate_cost: 0,
                range: S::ZERO,
            });
            return;
        }
        // The identity rule's interval, as in `on_tick`.
        let dt = S::seconds_from_ms(config.clock.period_ms);
        if !self.ranked {
            self.rank_batch(config, dt);
        }
        let observation = Observation::new(measurement).ok();
        let priority = self.priority(observation.as_ref(), &reply, dt);
        let Some(index) = self.evictable(&priority, observation.as_ref(), &reply, dt) else {
            increment16(&mut self.pending_counts.over_capacity);
            increment(&mut self.counters.over_capacity);
            return;
        };
        self.release(index);
        increment16(&mut self.pending_counts.over_capacity);
        increment(&mut self.counters.over_capacity);
        if let Some(slot) = self.batch.get_mut(index) {
            *slot = measurement;
        }
        if let Some(slot) = self.batch_replies.get_mut(index) {
            *slot = reply;
        }
        if let Some(slot) = self.batch_priorities.get_mut(index) {
            *slot = priority;
        }
        if let Some(o) = observation {
            self.crown(index, &o, &reply, dt);
        }
    }

    /// Runs the scan being assembled: collects what is due from `source`,
    /// runs the tracker, updates the altitude trackers, assesses every
    /// confirmed track and passes the reports to `emit`: one
    /// [`Message::Track`] per confirmed track, one [`Message::Scan`], one
    /// [`Message::Health`]. Then the next scan is one period later (or at
    /// the re-lock time).
    ///
    /// On `Err` (the tracker refused the scan: its time does not advance,
    /// which the loop's own tracker clock rules out) nothing is emitted and
    /// the batch is kept for the next call.
    pub fn on_tick(
        &mut self,
        config: &ScanConfig<T, F::Params>,
        source: &mut impl MeasurementSource,
        mut emit: impl FnMut(&Message),
    ) -> Result<TickReport, ScanError> {
        if self.relock && self.batch.is_empty() {
            // Nothing for the old time base: re-lock at once.
            self.apply_relock(config);
        }
        self.collect(config, source);
        let used = self.batch.len();
        let dt = S::seconds_from_ms(config.clock.period_ms);
        if self.codes.len() < M {
            // Empty in a new loop (zero bytes); the tracker writes one per
            // measurement of each scan.
            let _ = self.codes.resize(M, Association::NotAssigned);
        }
        let mut rule = IdentityRule {
            intruders: &mut self.intruders,
            replies: &self.batch_replies,
            previous: &self.previous_replies,
            dt,
        };
        let report = self.table.scan_with_rule(
            &config.tracker,
            self.tracker_ms,
            &self.batch,
            &mut self.codes,
            &mut rule,
            |_| {},
        )?;
        self.update_intruders(config, &report);
        let ra = self.assess_tracks(config, &report);
        let (highest, confirmed_tracks) = self.report_tracks(ra.advisory, &mut emit);

        let mut counts = self.pending_counts;
        counts.used = sat_u16(sat_u32(used));
        for code in self.codes.iter().take(used) {
            increment16(match code {
                Association::Updated(_) => &mut counts.updated,
                Association::Started(_) => &mut counts.started,
                Association::NotAssigned => &mut counts.not_assigned,
                Association::OutsideGates => &mut counts.outside_gates,
                Association::OutsideVolume => &mut counts.outside_volume,
                Association::Rejected(_) => &mut counts.rejected,
                Association::Dropped(DropReason::TableFull) => &mut counts.refused_table_full,
                Association::Dropped(DropReason::ScanOverflow) => &mut counts.over_capacity,
            });
        }
        counts.predicted = sat_u16(report.predicted);
        counts.gated_pairs = sat_u16(report.gated_pairs);
        counts.coasted = sat_u16(report.coasted);
        counts.confirmed = sat_u16(report.confirmed);
        counts.deleted = sat_u16(report.deleted);
        counts.displaced = sat_u16(report.deleted_displaced);
        counts.restarted = sat_u16(report.restarted);
        counts.tracks = sat_u16(report.tracks);
        counts.confirmed_tracks = sat_u16(confirmed_tracks);

        let c = &mut self.counters;
        increment(&mut c.scans);
        c.used = c.used.saturating_add(sat_u32(used));
        c.rejected = c.rejected.saturating_add(u32::from(counts.rejected));
        c.not_assigned = c
            .not_assigned
            .saturating_add(u32::from(counts.not_assigned));

        let summary = ScanSummary {
            time_ms: self.scan_ms,
            interval_ms: report.interval_ms,
            counts,
            highest_advisory: highest,
            ra: ra.advisory,
            clear_of_conflict: ra.clear_of_conflict,
        };
        emit(&Message::Scan(summary));

        // The next scan.
        self.batch.clear();
        core::mem::swap(&mut self.previous_replies, &mut self.batch_replies);
        self.batch_replies.clear();
        self.batch_priorities.clear();
        self.pending_counts = ScanCounts::new();
        self.tracker_ms = self.tracker_ms.wrapping_add(config.clock.period_ms);
        let time_ms = self.scan_ms;
        self.scan_ms = self.scan_ms.wrapping_add(config.clock.period_ms);
        self.ranked = false;
        if self.relock {
            self.apply_relock(config);
        }

        let (decoder, intake) = source.receiver_counters();
        emit(&Message::Health(Health {
            time_ms,
            decoder,
            intake,
            scan: self.counters,
            table: *self.table.stats(),
        }));
        Ok(TickReport {
            scan: report,
            summary,
        })
    }

    /// At the end of a run: drops a held out-of-window measurement
    /// (counted), so that every measurement taken is accounted for.
    pub fn finish(&mut self) {
        self.drop_candidate();
    }

    /// Emits a track report per confirmed track, with this scan's
    /// assessment and, on an RA threat, the RA in force; returns the highest
    /// advisory and the number of confirmed tracks.
    fn report_tracks(
        &mut self,
        ra: Option<RaCode>,
        emit: &mut impl FnMut(&Message),
    ) -> (Advisory, u32) {
        let mut highest = Advisory::None;
        let mut confirmed = 0u32;
        for track in self.table.tracks().filter(|t| t.is_confirmed()) {
            confirmed = confirmed.saturating_add(1);
            let slot = self.intruders.iter().find(|s| s.track == track.id());
            let assessed = slot.and_then(|s| s.assessed);
            let advisory = assessed.map_or(Advisory::None, |a| a.advisory);
            highest = highest.max(advisory);
            let altitude = slot.and_then(|s| s.tcas.altitude_state().estimate());
            let [x, y] = track.position();
            let [vx, vy] = track.velocity();
            // The range tau of this scan's assessment (the range tracker has
            // not moved since).
            let range_tau_s = assessed
                .and(slot.and_then(|s| s.tcas.range_tracker().estimate()))
                .and_then(|r| range_tau(r.range_m, r.range_rate_m_per_s).ok().flatten());
            let tau_ds = range_tau_s.map(|tau| {
                let ds = scaled_i32(tau, 10);
                u16::try_from(ds.max(0)).unwrap_or(u16::MAX)
            });
            let report = TrackReport {
                time_ms: self.scan_ms,
                track_id: track.id().get(),
                status: track.status(),
                advisory,
                sensitivity: assessed.map(|a| a.sensitivity),
                x_cm: scaled_i32(x, 100),
                y_cm: scaled_i32(y, 100),
                vx_cm_per_s: scaled_i32(vx, 100),
                vy_cm_per_s: scaled_i32(vy, 100),
                altitude: altitude.map(|a| {
                    let rate = scaled_i32(a.vertical_rate_ft_per_s, 60);
                    (
                        scaled_i32(a.altitude_ft, 1),
                        i16::try_from(rate).unwrap_or(if rate < 0 { i16::MIN } else { i16::MAX }),
                    )
                }),
                range_tau_ds: tau_ds,
                address: slot.and_then(|s| s.address),
                ra: if advisory == Advisory::Resolution {
                    ra
                } else {
                    None
                },
            };
            emit(&Message::Track(report));
            increment(&mut self.counters.track_reports);
        }
        (highest, confirmed)
    }
}
