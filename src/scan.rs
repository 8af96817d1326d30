//! The scan loop's hardware-independent core: what an interrupt-driven
//! tracker does with received bytes and timer ticks, with no interrupt,
//! peripheral or clock in it, so the firmware and the host tests run the same
//! code.
//!
//! ```text
//! receive interrupt:  byte ─▶ Intake::push ─▶ wire::Decoder ─▶ spsc queue ─┐
//!                                                                          │
//! timer tick (main):  ScanLoop::on_tick(now) ◀─ drain measurements ≤ now ◀─┘
//!                       ├─ MeasurementReport::position / altitude (checked)
//!                       ├─ TrackTable::scan: predict, gate, associate,
//!                       │  update, initiate / confirm / coast / delete
//!                       ├─ altitude trackers of the tracks (Mode C reports)
//!                       ├─ tcas::assess of each confirmed track
//!                       └─ reports: wire::TrackReport per confirmed track,
//!                          wire::ScanSummary per scan ─▶ caller's callback
//! advisory outputs:   AdvisoryLines::show(highest) ─▶ embedded-hal OutputPin
//! ```
//!
//! * [`Intake`] is the producer half, run in the receive interrupt: bytes
//!   into the [`Decoder`], measurement frames into a
//!   `heapless::spsc` queue. A full queue drops the measurement and counts
//!   it ([`LinkStatus::queue_full`]); it never blocks or panics.
//! * [`ScanLoop`] is the consumer half, run from the main loop on each tick.
//!   It owns the [`TrackTable`], an altitude tracker per altitude-reporting
//!   track and the scan's measurement batch; [`ScanConfig`] holds the
//!   tracker configuration and the own aircraft.
//!
//! # Time
//!
//! Measurements carry the sensor's millisecond clock; `on_tick(now_ms)` takes
//! the queued measurements timestamped at or before `now_ms` (in wrapping
//! `u32` arithmetic, like [`TrackTable::scan`]) and leaves later ones queued
//! for the next scan. A measurement timestamped at or before the previous
//! scan arrived too late for it and is dropped and counted (`late`). The
//! scan runs at `now_ms`, so a scan's measurements are treated as
//! simultaneous: the tick period should be the sensor's scan period.
//!
//! # Own aircraft
//!
//! Positions are relative to the own aircraft (the origin), as a TCAS
//! receiver measures them; so are the tracked velocities. Each confirmed
//! track is assessed against [`ScanConfig::own`] as an [`Intruder`] with its
//! tracked position and velocity and, if it reported altitude, the estimate
//! of its altitude tracker ([`crate::filter::altitude`]); a track that never
//! reported altitude is a non-altitude-reporting intruder (traffic
//! advisories at most).

use embedded_hal::digital::OutputPin;
use heapless::spsc::{Consumer, Producer};

use crate::filter::altitude::{AltitudeEstimate, AltitudeTracker, AltitudeTrackerConfig};
use crate::num::Scalar;
use crate::tcas::{self, Advisory, Intruder, OwnAircraft};
use crate::track::{
    Association, Measurement, ScanError, ScanReport, TrackFilter, TrackId, TrackTable,
    TrackerConfig,
};
use crate::wire::{
    ConversionError, Decoder, LinkStatus, MeasurementReport, Message, ScanSummary, TrackReport,
    WireError, MAX_FRAMES_PER_BYTE,
};

// ---------------------------------------------------------------------------
// Producer side
// ---------------------------------------------------------------------------

/// The receive-interrupt half: decodes bytes and queues the measurements.
pub struct Intake<'q> {
    decoder: Decoder,
    producer: Producer<'q, MeasurementReport>,
    queue_full: u32,
    not_measurement: u32,
    rx_overruns: u32,
}

impl core::fmt::Debug for Intake<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Intake")
            .field("decoder", &self.decoder)
            .field("queued", &self.producer.len())
            .field("queue_full", &self.queue_full)
            .field("not_measurement", &self.not_measurement)
            .field("rx_overruns", &self.rx_overruns)
            .finish()
    }
}

impl<'q> Intake<'q> {
    pub const fn new(producer: Producer<'q, MeasurementReport>) -> Self {
        Intake {
            decoder: Decoder::new(),
            producer,
            queue_full: 0,
            not_measurement: 0,
            rx_overruns: 0,
        }
    }

    /// Free slots in the measurement queue.
    pub fn free_slots(&self) -> usize {
        self.producer.capacity().saturating_sub(self.producer.len())
    }

    /// Whether the next byte cannot overflow the queue, whatever it
    /// completes ([`MAX_FRAMES_PER_BYTE`] slots free). A receiver with flow
    /// control stops reading while this is false; one without reads anyway
    /// and the overflow is counted.
    pub fn can_take_byte(&self) -> bool {
        self.free_slots() >= MAX_FRAMES_PER_BYTE
    }

    /// Takes one received byte; returns how many measurements it queued.
    /// Every frame it completes is handled here: measurements are queued (or
    /// counted as lost when the queue is full), other valid frames are
    /// counted, errors are counted by the decoder.
    pub fn push(&mut self, byte: u8) -> usize {
        let mut queued = 0;
        let mut event = self.decoder.push(byte);
        while let Some(result) = event {
            queued += self.handle(result);
            event = self.decoder.poll();
        }
        queued
    }

    /// The line went idle: abandons a partial frame and handles whatever the
    /// bytes after it held ([`Decoder::line_idle`]); returns how many
    /// measurements it queued.
    pub fn line_idle(&mut self) -> usize {
        let mut queued = 0;
        while let Some(result) = self.decoder.line_idle() {
            queued += self.handle(result);
        }
        queued
    }

    fn handle(&mut self, result: Result<Message, WireError>) -> usize {
        match result {
            Ok(Message::Measurement(m)) => match self.producer.enqueue(m) {
                Ok(()) => return 1,
                Err(_) => self.queue_full = self.queue_full.saturating_add(1),
            },
            Ok(_) => self.not_measurement = self.not_measurement.saturating_add(1),
            Err(_) => {}
        }
        0
    }

    /// Counts a byte the UART lost before it could be read (hardware
    /// overrun flag).
    pub fn count_overrun(&mut self) {
        self.rx_overruns = self.rx_overruns.saturating_add(1);
    }

    pub fn decoder(&self) -> &Decoder {
        &self.decoder
    }

    /// Measurements lost because the queue was full.
    pub fn queue_full(&self) -> u32 {
        self.queue_full
    }

    /// The counters as a link status report stamped `time_ms`.
    pub fn status(&self, time_ms: u32) -> LinkStatus {
        let d = self.decoder.stats();
        LinkStatus {
            time_ms,
            frames: d.frames,
            crc_errors: d.crc_errors,
            unknown_type: d.unknown_type,
            bad_length: d.bad_length,
            bad_field: d.bad_field,
            truncated: d.truncated,
            bytes_skipped: d.bytes_skipped,
            queue_full: self.queue_full,
            not_measurement: self.not_measurement,
            rx_overruns: self.rx_overruns,
        }
    }
}

// ---------------------------------------------------------------------------
// Consumer side
// ---------------------------------------------------------------------------

/// What a [`ScanLoop`] needs besides its state. Kept outside it (as
/// [`TrackerConfig`] is kept outside [`TrackTable`]) so that the loop can be
/// built by a `const fn` in a `static`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanConfig<S: Scalar, P> {
    pub tracker: TrackerConfig<S, P>,
    /// The own aircraft, for the threat assessment.
    pub own: OwnAircraft<S>,
    /// The altitude trackers of altitude-reporting tracks.
    pub altitude: AltitudeTrackerConfig<S>,
}

/// Counters over the loop's lifetime (saturating).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LoopCounters {
    /// Scans run.
    pub scans: u32,
    /// Measurements taken from the queue.
    pub taken: u32,
    /// ... refused at the conversion: position or range beyond 400 km,
    pub position_out_of_range: u32,
    /// ... altitude outside the Mode C range,
    pub altitude_out_of_range: u32,
    /// ... not representable in the number type,
    pub not_representable: u32,
    /// ... timestamped at or before the previous scan,
    pub late: u32,
    /// ... beyond the `M` measurements of one scan.
    pub dropped: u32,
    /// Track reports emitted.
    pub track_reports: u32,
    /// Confirmed tracks whose threat assessment failed (reported without
    /// one).
    pub assessment_errors: u32,
    /// Altitude updates refused by the altitude tracker.
    pub altitude_errors: u32,
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

/// Counts of the batch being assembled for the next scan.
#[derive(Debug, Clone, Copy, Default)]
struct BatchCounts {
    taken: u32,
    invalid: u32,
    late: u32,
    dropped: u32,
}

#[derive(Debug, Clone, Copy)]
struct AltitudeSlot<S: Scalar> {
    track: TrackId,
    tracker: AltitudeTracker<S>,
    updated: bool,
}

/// `t` is after `reference` on a wrapping millisecond clock (less than 2³¹
/// ms after it).
fn is_after(t: u32, reference: u32) -> bool {
    let d = t.wrapping_sub(reference);
    d != 0 && d <= i32::MAX as u32
}

fn sat_u16(v: u32) -> u16 {
    u16::try_from(v).unwrap_or(u16::MAX)
}

/// `v·scale` rounded to an integer, saturated to the i32 range (NaN → 0).
/// Reports carry tracks inside the ±400 km envelope, where nothing saturates.
fn scaled_i32<S: Scalar>(v: S, scale: f64) -> i32 {
    let f = libm::round(v.to_f64() * scale);
    if f.is_nan() {
        0
    } else if f >= i32::MAX as f64 {
        i32::MAX
    } else if f <= i32::MIN as f64 {
        i32::MIN
    } else {
        f as i32
    }
}

/// The consumer half: turns a tick into a tracker scan, threat assessments
/// and reports. At most `N` tracks, `M` measurements per scan.
///
/// Memory: the [`TrackTable`] (see [`crate::track`] for its size), plus per
/// measurement slot one `Measurement<S>`, one `Option<S>` and an
/// [`Association`], plus per track slot an `Option` of an
/// [`AltitudeTracker<S>`] and its id. `host-tests/tests/scan_loop.rs`
/// prints the sizes; the firmware prints its own at start-up.
#[derive(Debug)]
pub struct ScanLoop<S: Scalar, F, const N: usize, const M: usize> {
    table: TrackTable<S, F, N, M>,
    batch: heapless::Vec<Measurement<S>, M>,
    batch_altitudes: heapless::Vec<Option<S>, M>,
    batch_counts: BatchCounts,
    codes: [Association; M],
    altitudes: [Option<AltitudeSlot<S>>; N],
    counters: LoopCounters,
}

impl<S: Scalar, F: TrackFilter<S>, const N: usize, const M: usize> Default
    for ScanLoop<S, F, N, M>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, F: TrackFilter<S>, const N: usize, const M: usize> ScanLoop<S, F, N, M> {
    pub const fn new() -> Self {
        ScanLoop {
            table: TrackTable::new(),
            batch: heapless::Vec::new(),
            batch_altitudes: heapless::Vec::new(),
            batch_counts: BatchCounts {
                taken: 0,
                invalid: 0,
                late: 0,
                dropped: 0,
            },
            codes: [Association::OutsideGates; M],
            altitudes: [const { None }; N],
            counters: LoopCounters {
                scans: 0,
                taken: 0,
                position_out_of_range: 0,
                altitude_out_of_range: 0,
                not_representable: 0,
                late: 0,
                dropped: 0,
                track_reports: 0,
                assessment_errors: 0,
                altitude_errors: 0,
            },
        }
    }

    pub fn table(&self) -> &TrackTable<S, F, N, M> {
        &self.table
    }

    pub fn counters(&self) -> &LoopCounters {
        &self.counters
    }

    /// Measurements collected for the next scan.
    pub fn batch_len(&self) -> usize {
        self.batch.len()
    }

    /// The next scan has as many measurements as it can take; more are
    /// dropped (and counted).
    pub fn batch_is_full(&self) -> bool {
        self.batch.is_full()
    }

    /// The altitude estimate of a track, if it reported altitude.
    pub fn altitude(&self, track: TrackId) -> Option<AltitudeEstimate<S>> {
        self.altitudes
            .iter()
            .flatten()
            .find(|s| s.track == track)
            .and_then(|s| s.tracker.estimate())
    }

    /// Moves the queued measurements timestamped at or before `up_to_ms`
    /// into the next scan's batch, converting them (the checked edge);
    /// stops at the first later one. Returns how many it took. `on_tick`
    /// calls it; calling it between ticks too frees queue space early.
    pub fn collect(&mut self, queue: &mut Consumer<'_, MeasurementReport>, up_to_ms: u32) -> usize {
        let mut taken = 0;
        while let Some(head) = queue.peek() {
            if is_after(head.time_ms, up_to_ms) {
                break;
            }
            let Some(report) = queue.dequeue() else {
                break;
            };
            self.take(&report);
            taken += 1;
        }
        taken
    }

    fn take(&mut self, report: &MeasurementReport) {
        let b = &mut self.batch_counts;
        let c = &mut self.counters;
        b.taken += 1;
        c.taken = c.taken.saturating_add(1);
        if let Some(last) = self.table.last_scan_ms() {
            if !is_after(report.time_ms, last) {
                b.late += 1;
                c.late = c.late.saturating_add(1);
                return;
            }
        }
        let converted = report
            .position::<S>()
            .and_then(|m| report.altitude::<S>().map(|a| (m, a)));
        match converted {
            Ok((m, a)) => {
                if self.batch.push(m).is_ok() {
                    // Same capacity as `batch`, one push each: cannot fail.
                    let _ = self.batch_altitudes.push(a);
                } else {
                    b.dropped += 1;
                    c.dropped = c.dropped.saturating_add(1);
                }
            }
            Err(e) => {
                b.invalid += 1;
                let counter = match e {
                    ConversionError::PositionOutOfRange | ConversionError::RangeOutOfRange => {
                        &mut c.position_out_of_range
                    }
                    ConversionError::AltitudeOutOfRange => &mut c.altitude_out_of_range,
                    ConversionError::NotRepresentable => &mut c.not_representable,
                };
                *counter = counter.saturating_add(1);
            }
        }
    }

    /// One scan at `now_ms`: collects the queued measurements up to
    /// `now_ms`, runs the tracker, updates the altitude trackers, assesses
    /// every confirmed track and passes the reports to `emit` (one
    /// [`Message::Track`] per confirmed track, then one [`Message::Scan`]).
    ///
    /// On `Err` (a `now_ms` not after the previous scan) nothing is emitted,
    /// the tracker is unchanged and the collected measurements stay in the
    /// batch for the next successful call.
    pub fn on_tick(
        &mut self,
        config: &ScanConfig<S, F::Params>,
        now_ms: u32,
        queue: &mut Consumer<'_, MeasurementReport>,
        mut emit: impl FnMut(&Message),
    ) -> Result<TickReport, ScanError> {
        self.collect(queue, now_ms);
        let report = self
            .table
            .scan(&config.tracker, now_ms, &self.batch, &mut self.codes)?;
        self.counters.scans = self.counters.scans.saturating_add(1);
        self.update_altitudes(config, &report);

        let mut highest = Advisory::None;
        let mut confirmed = 0u32;
        for track in self.table.tracks().filter(|t| t.is_confirmed()) {
            confirmed += 1;
            let altitude = self
                .altitudes
                .iter()
                .flatten()
                .find(|s| s.track == track.id())
                .and_then(|s| s.tracker.estimate());
            let intruder = Intruder {
                relative_position_m: track.position(),
                relative_velocity_m_per_s: track.velocity(),
                altitude,
            };
            let assessment = tcas::assess(&config.own, &intruder).ok();
            if assessment.is_none() {
                self.counters.assessment_errors = self.counters.assessment_errors.saturating_add(1);
            }
            let advisory = assessment.map_or(Advisory::None, |a| a.advisory);
            highest = highest.max(advisory);
            let [x, y] = track.position();
            let [vx, vy] = track.velocity();
            let tau_ds = assessment.and_then(|a| a.range_tau_s).map(|tau| {
                let ds = scaled_i32(tau, 10.0);
                u16::try_from(ds.max(0)).unwrap_or(u16::MAX)
            });
            let report = TrackReport {
                time_ms: now_ms,
                track_id: track.id().get(),
                status: track.status(),
                advisory,
                sensitivity: assessment.map(|a| a.sensitivity),
                x_cm: scaled_i32(x, 100.0),
                y_cm: scaled_i32(y, 100.0),
                vx_cm_per_s: scaled_i32(vx, 100.0),
                vy_cm_per_s: scaled_i32(vy, 100.0),
                altitude: altitude.map(|a| {
                    let rate = scaled_i32(a.vertical_rate_ft_per_s, 60.0);
                    (
                        scaled_i32(a.altitude_ft, 1.0),
                        rate.clamp(i16::MIN as i32, i16::MAX as i32) as i16,
                    )
                }),
                range_tau_ds: tau_ds,
            };
            emit(&Message::Track(report));
            self.counters.track_reports = self.counters.track_reports.saturating_add(1);
        }

        let b = self.batch_counts;
        let summary = ScanSummary {
            time_ms: now_ms,
            interval_ms: report.interval_ms,
            measurements: sat_u16(b.taken),
            invalid: sat_u16(b.invalid),
            late: sat_u16(b.late),
            dropped: sat_u16(b.dropped),
            rejected: sat_u16(report.rejected),
            predicted: sat_u16(report.predicted),
            gated_pairs: sat_u16(report.gated_pairs),
            assigned: sat_u16(report.assigned),
            updated: sat_u16(report.updated),
            coasted: sat_u16(report.coasted),
            started: sat_u16(report.started),
            confirmed: sat_u16(report.confirmed),
            deleted: sat_u16(report.deleted),
            tracks: sat_u16(report.tracks),
            confirmed_tracks: sat_u16(confirmed),
            highest_advisory: highest,
        };
        emit(&Message::Scan(summary));

        self.batch.clear();
        self.batch_altitudes.clear();
        self.batch_counts = BatchCounts::default();
        Ok(TickReport {
            scan: report,
            summary,
        })
    }

    /// Feeds the scan's altitude reports to the trackers of the tracks they
    /// updated or started; coasts the others; frees the trackers of deleted
    /// tracks.
    fn update_altitudes(&mut self, config: &ScanConfig<S, F::Params>, report: &ScanReport) {
        for slot in self.altitudes.iter_mut() {
            match slot {
                Some(s) if self.table.track(s.track).is_some() => s.updated = false,
                _ => *slot = None,
            }
        }
        // The first scan has no interval, and no track yet.
        let Ok(dt) = S::try_from_f64(report.interval_ms as f64 / 1000.0) else {
            return;
        };
        if report.interval_ms == 0 {
            return;
        }
        let n = self.batch.len().min(M);
        for (code, altitude) in self.codes.iter().take(n).zip(self.batch_altitudes.iter()) {
            let (Association::Updated(id) | Association::Started(id)) = *code else {
                continue;
            };
            let Some(altitude) = *altitude else { continue };
            let index = match self
                .altitudes
                .iter()
                .position(|s| matches!(s, Some(s) if s.track == id))
            {
                Some(i) => Some(i),
                None => {
                    // A track per slot at most, and a slot per track: a free
                    // slot exists for every live track.
                    let free = self.altitudes.iter().position(|s| s.is_none());
                    if let Some(Some(slot)) = free.map(|i| self.altitudes.get_mut(i)) {
                        *slot = Some(AltitudeSlot {
                            track: id,
                            tracker: AltitudeTracker::new(config.altitude),
                            updated: false,
                        });
                    }
                    free
                }
            };
            if let Some(Some(s)) = index.and_then(|i| self.altitudes.get_mut(i)) {
                if s.tracker.scan(Some(altitude), dt).is_err() {
                    self.counters.altitude_errors = self.counters.altitude_errors.saturating_add(1);
                }
                s.updated = true;
            }
        }
        for s in self.altitudes.iter_mut().flatten() {
            if !s.updated && s.tracker.scan(None, dt).is_err() {
                self.counters.altitude_errors = self.counters.altitude_errors.saturating_add(1);
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Advisory outputs
// ---------------------------------------------------------------------------

/// Two discrete outputs for the advisory level, as a TCAS processor drives
/// its display and aural-warning lines: the traffic line is high while any
/// intruder has a traffic or a resolution advisory, the resolution line
/// while any has a resolution advisory. The pins are embedded-hal 1.0
/// [`OutputPin`]s: the board behind them is the caller's.
#[derive(Debug)]
pub struct AdvisoryLines<P> {
    traffic: P,
    resolution: P,
    shown: Option<Advisory>,
    changes: u32,
}

impl<P: OutputPin> AdvisoryLines<P> {
    /// Takes the pins; they are first driven by [`AdvisoryLines::show`].
    pub fn new(traffic: P, resolution: P) -> Self {
        AdvisoryLines {
            traffic,
            resolution,
            shown: None,
            changes: 0,
        }
    }

    /// Drives the lines for the most severe advisory of a scan; true if the
    /// lines changed. The first call always drives both.
    pub fn show(&mut self, highest: Advisory) -> Result<bool, P::Error> {
        let traffic = highest >= Advisory::Traffic;
        let resolution = highest >= Advisory::Resolution;
        let before = self
            .shown
            .map(|a| (a >= Advisory::Traffic, a >= Advisory::Resolution));
        if before == Some((traffic, resolution)) {
            self.shown = Some(highest);
            return Ok(false);
        }
        set(&mut self.traffic, traffic)?;
        set(&mut self.resolution, resolution)?;
        if before.is_some() {
            self.changes = self.changes.saturating_add(1);
        }
        self.shown = Some(highest);
        Ok(true)
    }

    /// Times the lines changed after the first [`show`](Self::show).
    pub fn changes(&self) -> u32 {
        self.changes
    }

    /// (traffic, resolution) pins, e.g. to read them back.
    pub fn pins(&self) -> (&P, &P) {
        (&self.traffic, &self.resolution)
    }

    pub fn release(self) -> (P, P) {
        (self.traffic, self.resolution)
    }
}

fn set<P: OutputPin>(pin: &mut P, high: bool) -> Result<(), P::Error> {
    if high {
        pin.set_high()
    } else {
        pin.set_low()
    }
}
