//! The scan loop's hardware-independent core: what an interrupt-driven
//! tracker does with received bytes and timer ticks, with no interrupt,
//! peripheral or clock in it, so the firmware and the host tests run the same
//! code.
//!
//! ```text
//! receive interrupt:  byte ─▶ Intake::push ─▶ wire::Decoder ─▶ MeasurementQueue ─┐
//!                                                                                  │
//! main loop:  ScanLoop::collect ◀─ the scan clock sorts each measurement ◀─────────┘
//!               (this scan / a later one / late / out of the window)
//!               ─▶ the scan's batch, by priority when over capacity
//!             ScanLoop::on_tick: TrackTable::scan, altitude trackers,
//!               tcas::assess per confirmed track
//!               ─▶ TrackReport per confirmed track, ScanSummary, Health ─▶ callback
//! advisory outputs:   AdvisoryLines::show(highest) ─▶ embedded-hal OutputPin
//! ```
//!
//! * [`Intake`] is the producer half, run in the receive interrupt: bytes
//!   into the [`Decoder`], measurements into a [`MeasurementQueue`] (a plain
//!   ring buffer with no panic path; the firmware shares it through a
//!   critical section, one short one per measurement). A full queue drops
//!   the measurement and counts it; it never blocks or panics.
//! * [`ScanLoop`] is the consumer half, run from the main loop. It owns the
//!   [`TrackTable`], an altitude tracker per altitude-reporting track, the
//!   scan clock and the scan's batch; [`ScanConfig`] holds the tracker
//!   configuration, the own aircraft and the clock's bounds.
//!
//! The rules below are stated once here; `docs/firmware-runtime.md` gives
//! the reasons and the measured figures.
//!
//! # Time: the scan clock
//!
//! Measurements carry the sensor's millisecond clock (`u32`, wrapping). The
//! loop locks onto it at the first measurement: that measurement's time is
//! the first scan's time, and scans follow every `period_ms`
//! ([`ClockConfig`]) of the sensor's clock. For the scan being assembled,
//! at sensor time `N`, a measurement at time `t` (`d = t − N` in wrapping
//! arithmetic, as a signed 32-bit difference) is
//!
//! * **this scan's** if `−period < d ≤ 0`: it joins the batch;
//! * **a later scan's** if `0 < d ≤ jump`: it stays queued, and the scan
//!   runs (the input has moved past it): a silence of up to `jump` runs
//!   empty scans, one per period, in which the tracks coast;
//! * **late** if `−late_window ≤ d ≤ −period`: its scan has run; dropped
//!   and counted (`late`);
//! * **out of the window** otherwise. It is held until the next
//!   measurement: if that one is within one period of it, the sensor's
//!   clock jumped, and the loop **re-locks** (counted): the scan being
//!   assembled runs (if it has measurements), and the next scan is at the
//!   held measurement's time. If not, the held one is dropped and counted
//!   (`out_of_window`). So one wild time stamp never moves the clock, and a
//!   step of the sensor's clock (forwards or back, by any amount, past 2³¹
//!   ms included) costs no measurement.
//!
//! Every measurement is taken from the queue once and ends in exactly one
//! scan's batch or one drop count, so a clock stepping back never makes a
//! frame be processed twice.
//!
//! The tracker has its own time: it advances by exactly one period per scan
//! and never jumps, so [`TrackTable::scan`] always sees a one-period
//! interval, whatever the sensor's clock did; a re-lock takes a clock step
//! to be the sensor's, not the targets'. Reports carry the sensor's time of
//! their scan.
//!
//! # Capacity: who gets the scan's `M` slots
//!
//! When a scan has more measurements than `M`, the batch keeps the most
//! important ones, in this priority:
//!
//! 1. for each confirmed track, the measurement nearest its predicted
//!    position inside its gate (it is never evicted, so a confirmed track
//!    is never starved by clutter);
//! 2. other measurements inside a confirmed track's gate, by normalised
//!    gate distance;
//! 3. all others (tentative tracks' and candidates for new tracks), nearest
//!    to the own aircraft first: an unknown return's threat grows as it
//!    closes in;
//! 4. measurements the tracker would refuse (not finite).
//!
//! A newcomer replaces the least important unprotected entry only if it is
//! strictly more important (or takes a confirmed track's first place);
//! among exact equals the later batch slot goes first. Gates are the
//! tracker's own ([`TrackFilter::gate_region`]) for the next scan. The
//! others are dropped and counted (`over_capacity`).
//!
//! # Own aircraft
//!
//! Positions are relative to the own aircraft (the origin), as a TCAS
//! receiver measures them; so are the tracked velocities. Each confirmed
//! track is assessed against [`ScanConfig::own`] as an
//! [`Intruder`](crate::tcas::Intruder) with its tracked position and
//! velocity and, if it reported altitude, the estimate of its altitude
//! tracker ([`crate::filter::altitude`]); a track that never
//! reported altitude is a non-altitude-reporting intruder (traffic
//! advisories at most).

use embedded_hal::digital::OutputPin;

use crate::filter::altitude::{AltitudeEstimate, AltitudeQuantum, AltitudeTrackerConfig};
use crate::filter::range_azimuth::RangeAzimuthFilter;
use crate::num::{hypot, Scalar};
use crate::tcas::detection::MAX_INTRUDER_RATE_FT_PER_S;
use crate::tcas::{
    range_tau, Advisory, CollisionAvoidance, IntruderTrack, OwnAircraft, Reply, SensitivityLevel,
    ThreatGeometry,
};
use crate::track::{
    Association, ConfigError, DropReason, FixedGainTrack, GateRegion, Measurement, Observation,
    PairRule, RangeAzimuthTrack, ScanError, ScanInterval, ScanReport, TrackFilter, TrackId,
    TrackNumeric, TrackTable, TrackerConfig,
};
use crate::wire::{
    Decoder, DecoderStats, EndOfInput, Health, IntakeCounters, LoopCounters, MeasurementReport,
    Message, ModeSAddress, RaCode, ScanCounts, ScanSummary, TrackReport, WireError,
    MAX_FRAMES_PER_BYTE,
};

fn bump(counter: &mut u32) {
    *counter = counter.saturating_add(1);
}

fn bump16(counter: &mut u16) {
    *counter = counter.saturating_add(1);
}

// ---------------------------------------------------------------------------
// Producer side
// ---------------------------------------------------------------------------

/// A fixed-capacity FIFO of measurements: `Q` slots, no heap, no panic
/// path (indices wrap by comparison, never by `%`).
#[derive(Debug, Clone)]
pub struct MeasurementQueue<const Q: usize> {
    slots: [Option<MeasurementReport>; Q],
    head: usize,
    len: usize,
}

impl<const Q: usize> Default for MeasurementQueue<Q> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const Q: usize> MeasurementQueue<Q> {
    /// An empty queue (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        MeasurementQueue {
            slots: [None; Q],
            head: 0,
            len: 0,
        }
    }

    /// Slot `head + k`, wrapped (k < Q).
    fn index(&self, k: usize) -> usize {
        let i = self.head.wrapping_add(k);
        if i >= Q {
            i.wrapping_sub(Q)
        } else {
            i
        }
    }

    /// Measurements queued.
    pub fn len(&self) -> usize {
        self.len
    }

    /// No measurement queued.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The slot count `Q`.
    pub const fn capacity(&self) -> usize {
        Q
    }

    /// Free slots.
    pub fn free(&self) -> usize {
        Q.saturating_sub(self.len)
    }

    /// Appends; hands the measurement back when full.
    pub fn push(&mut self, m: MeasurementReport) -> Result<(), MeasurementReport> {
        if self.len >= Q {
            return Err(m);
        }
        let i = self.index(self.len);
        match self.slots.get_mut(i) {
            Some(slot) => {
                *slot = Some(m);
                self.len = self.len.saturating_add(1);
                Ok(())
            }
            None => Err(m),
        }
    }

    /// The oldest measurement.
    pub fn peek(&self) -> Option<&MeasurementReport> {
        if self.len == 0 {
            return None;
        }
        self.slots.get(self.head).and_then(|s| s.as_ref())
    }

    /// Takes the oldest measurement.
    pub fn pop(&mut self) -> Option<MeasurementReport> {
        if self.len == 0 {
            return None;
        }
        let m = self.slots.get_mut(self.head).and_then(|s| s.take());
        self.head = self.index(1);
        self.len = self.len.saturating_sub(1);
        m
    }
}

/// Where the scan loop takes its measurements from: the [`Intake`] itself
/// on the host, a critical-section wrapper of it in the firmware.
pub trait MeasurementSource {
    /// The oldest queued measurement, without taking it.
    fn peek(&mut self) -> Option<MeasurementReport>;
    /// Takes the oldest queued measurement.
    fn pop(&mut self) -> Option<MeasurementReport>;
    /// The receive side's counters, for the health report.
    fn receiver_counters(&mut self) -> (DecoderStats, IntakeCounters);
}

/// A queue filled directly (host tests, a source without a decoder).
impl<const Q: usize> MeasurementSource for MeasurementQueue<Q> {
    fn peek(&mut self) -> Option<MeasurementReport> {
        MeasurementQueue::peek(self).copied()
    }
    fn pop(&mut self) -> Option<MeasurementReport> {
        MeasurementQueue::pop(self)
    }
    fn receiver_counters(&mut self) -> (DecoderStats, IntakeCounters) {
        (DecoderStats::new(), IntakeCounters::new())
    }
}

/// The receive-interrupt half: decodes bytes and queues the measurements
/// (at most `Q`).
#[derive(Debug, Clone)]
pub struct Intake<const Q: usize> {
    decoder: Decoder,
    queue: MeasurementQueue<Q>,
    counters: IntakeCounters,
    ended: Option<EndOfInput>,
}

impl<const Q: usize> Default for Intake<Q> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const Q: usize> Intake<Q> {
    /// An empty intake: a fresh decoder, an empty queue, zero counters (a
    /// `const fn`, for a `static`).
    pub const fn new() -> Self {
        Intake {
            decoder: Decoder::new(),
            queue: MeasurementQueue::new(),
            counters: IntakeCounters::new(),
            ended: None,
        }
    }

    /// Free slots in the measurement queue.
    pub fn free_slots(&self) -> usize {
        self.queue.free()
    }

    /// Measurements queued.
    pub fn queued(&self) -> usize {
        self.queue.len()
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
        let mut queued = 0usize;
        let mut event = self.decoder.push(byte);
        while let Some(result) = event {
            queued = queued.saturating_add(self.handle(result));
            event = self.decoder.poll();
        }
        queued
    }

    /// The line went idle: abandons a partial frame and handles whatever the
    /// bytes after it held ([`Decoder::line_idle`]); returns how many
    /// measurements it queued.
    pub fn line_idle(&mut self) -> usize {
        let mut queued = 0usize;
        while let Some(result) = self.decoder.line_idle() {
            queued = queued.saturating_add(self.handle(result));
        }
        queued
    }

    fn handle(&mut self, result: Result<Message, WireError>) -> usize {
        match result {
            Ok(Message::Measurement(m)) => {
                bump(&mut self.counters.measurements);
                match self.queue.push(m) {
                    Ok(()) => return 1,
                    Err(_) => bump(&mut self.counters.queue_full),
                }
            }
            Ok(Message::End(e)) => {
                bump(&mut self.counters.not_measurement);
                self.ended = Some(e);
            }
            Ok(_) => bump(&mut self.counters.not_measurement),
            Err(_) => {}
        }
        0
    }

    /// The end-of-input frame, once received: the sender's recording has
    /// ended (a receiver stops reading there).
    pub fn input_ended(&self) -> Option<EndOfInput> {
        self.ended
    }

    /// Counts a byte the UART lost before it could be read (hardware
    /// overrun flag).
    pub fn count_overrun(&mut self) {
        bump(&mut self.counters.rx_overruns);
    }

    /// The frame decoder, for its statistics ([`Decoder`]).
    pub fn decoder(&self) -> &Decoder {
        &self.decoder
    }

    /// The intake's own counts (queue full, UART overruns).
    pub fn counters(&self) -> &IntakeCounters {
        &self.counters
    }
}

impl<const Q: usize> MeasurementSource for Intake<Q> {
    fn peek(&mut self) -> Option<MeasurementReport> {
        self.queue.peek().copied()
    }
    fn pop(&mut self) -> Option<MeasurementReport> {
        self.queue.pop()
    }
    fn receiver_counters(&mut self) -> (DecoderStats, IntakeCounters) {
        (*self.decoder.stats(), self.counters)
    }
}

// ---------------------------------------------------------------------------
// Configuration
// ---------------------------------------------------------------------------

/// The scan clock's period and windows (see the module docs, "Time"), in
/// milliseconds of the sensor's clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ClockConfig {
    period_ms: u32,
    late_window_ms: u32,
    jump_ms: u32,
}

impl ClockConfig {
    /// Late window, in periods, of [`ClockConfig::new`]: a measurement up
    /// to one period after its scan ran is late; an older one is out of
    /// the window.
    pub const LATE_PERIODS: u32 = 2;
    /// Jump bound, in periods, of [`ClockConfig::new`]: a silence of up to
    /// 30 periods is a gap (empty scans, the tracks coast and are deleted);
    /// a longer step is a jump of the sensor's clock (re-lock).
    pub const JUMP_PERIODS: u32 = 30;

    /// The scan period (inside the filters' 50 ms – 20 s,
    /// [`crate::filter::MIN_INTERVAL_MS`], [`crate::filter::MAX_INTERVAL_MS`])
    /// with the default windows.
    pub const fn new(period_ms: u32) -> Result<Self, ConfigError> {
        let (Some(late), Some(jump)) = (
            period_ms.checked_mul(Self::LATE_PERIODS),
            period_ms.checked_mul(Self::JUMP_PERIODS),
        ) else {
            return Err(ConfigError::OutOfRange);
        };
        Self::with_windows(period_ms, late, jump)
    }

    /// Explicit windows: a period inside the filters' 50 ms – 20 s (the
    /// tracker's interval), late window ≥ period, jump ≥ period, all below
    /// 2³¹ ms.
    pub const fn with_windows(
        period_ms: u32,
        late_window_ms: u32,
        jump_ms: u32,
    ) -> Result<Self, ConfigError> {
        let limit = i32::MAX as u32;
        if period_ms < crate::filter::MIN_INTERVAL_MS
            || period_ms > crate::filter::MAX_INTERVAL_MS
            || late_window_ms < period_ms
            || jump_ms < period_ms
            || late_window_ms > limit
            || jump_ms > limit
        {
            return Err(ConfigError::OutOfRange);
        }
        Ok(ClockConfig {
            period_ms,
            late_window_ms,
            jump_ms,
        })
    }

    /// The scan period, in ms.
    pub const fn period_ms(&self) -> u32 {
        self.period_ms
    }
    /// The late window, in ms: a measurement from a past scan up to this far
    /// back is counted late; older, out of the window.
    pub const fn late_window_ms(&self) -> u32 {
        self.late_window_ms
    }
    /// The jump bound, in ms: a measurement up to this far ahead starts a later
    /// scan; further ahead, it is out of the window (a clock jump candidate).
    pub const fn jump_ms(&self) -> u32 {
        self.jump_ms
    }
}

/// What a [`ScanLoop`] needs besides its state. Kept outside it (as
/// [`TrackerConfig`] is kept outside [`TrackTable`]) so that the loop can be
/// built by a `const fn` in a `static`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanConfig<S: Scalar, P> {
    /// The track table's configuration (gates, lifecycle, region).
    pub tracker: TrackerConfig<S, P>,
    /// The own aircraft, for the threat assessment.
    pub own: OwnAircraft<S>,
    /// The altitude tracker of an intruder reporting in 100 ft steps
    /// (Mode C) …
    pub altitude: AltitudeTrackerConfig<S>,
    /// … and of one reporting in 25 ft steps (Mode S with the Q bit).
    pub altitude_25ft: AltitudeTrackerConfig<S>,
    /// The scan period and the clock's windows.
    pub clock: ClockConfig,
}

// ---------------------------------------------------------------------------
// Consumer side
// ---------------------------------------------------------------------------

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
    /// The range–azimuth filter of this track, if it has one.
    fn bearing_track(&self) -> Option<&RangeAzimuthFilter<S>>;
}

impl<S: Scalar> BearingTrack<S> for RangeAzimuthTrack<S> {
    fn bearing_track(&self) -> Option<&RangeAzimuthFilter<S>> {
        Some(self.filter())
    }
}

impl<S: Scalar> BearingTrack<S> for FixedGainTrack<S> {
    fn bearing_track(&self) -> Option<&RangeAzimuthFilter<S>> {
        None
    }
}

/// What a scan's reply carries besides its position.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ReplyData<S> {
    altitude_ft: Option<S>,
    altitude_25ft: bool,
    address: Option<ModeSAddress>,
}

/// This scan's assessment of one confirmed track.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Assessed<S> {
    advisory: Advisory,
    sensitivity: SensitivityLevel,
    range_tau_s: Option<S>,
}

/// One track's TCAS surveillance: its intruder's Mode S address (kept for
/// the track's life), range and altitude trackers and threat state.
#[derive(Debug, Clone, Copy)]
struct IntruderSlot<S: Scalar> {
    track: TrackId,
    address: Option<ModeSAddress>,
    quantum: AltitudeQuantum,
    tcas: IntruderTrack<S>,
    updated: bool,
    assessed: Option<Assessed<S>>,
}

/// RA threats resolved together at most (the ones with the smallest
/// modified tau; more are counted, `ra_threats_over_capacity`).
pub const MAX_RA_THREATS: usize = 8;

/// Reply identity: a reply with a Mode S address
/// updates only the track of that address, and starts a track only if no
/// track has it; a reply without one (Mode C) updates only a track without
/// an address whose altitude it correlates with, and starts one only with a
/// first point without an address whose altitude correlates.
struct IdentityRule<'a, S: Scalar> {
    intruders: &'a [Option<IntruderSlot<S>>],
    replies: &'a [ReplyData<S>],
    previous: &'a [ReplyData<S>],
    dt: S,
}

impl<S: Scalar> IdentityRule<'_, S> {
    fn slot(&self, track: TrackId) -> Option<&IntruderSlot<S>> {
        self.intruders.iter().flatten().find(|s| s.track == track)
    }

    /// |a − b| within the altitude correlation window for `dt`: two
    /// quanta plus the detection logic's 10 000 ft/min intruder-rate limit
    /// (our choice: the public sources do not give DO-185B's window).
    fn altitudes_correlate(&self, a: S, b: S, quantum: AltitudeQuantum) -> bool {
        let window = S::from_f64_lossy(2.0 * quantum.feet())
            + S::from_f64_lossy(MAX_INTRUDER_RATE_FT_PER_S) * self.dt;
        (a - b).abs() <= window
    }
}

impl<S: Scalar> PairRule for IdentityRule<'_, S> {
    fn may_update(&self, track: TrackId, k: usize) -> bool {
        let Some(reply) = self.replies.get(k) else {
            return false;
        };
        let slot = self.slot(track);
        match (reply.address, slot.and_then(|s| s.address)) {
            (Some(a), Some(b)) => a == b,
            (None, None) => {
                let predicted = slot
                    .and_then(|s| s.tcas.altitude_tracker().estimate())
                    .map(|e| e.altitude_ft + e.vertical_rate_ft_per_s * self.dt);
                match (reply.altitude_ft, predicted, slot) {
                    (Some(z), Some(p), Some(s)) => self.altitudes_correlate(z, p, s.quantum),
                    _ => true,
                }
            }
            _ => false,
        }
    }

    fn may_start(&self, p: usize, k: usize) -> bool {
        let (Some(first), Some(second)) = (self.previous.get(p), self.replies.get(k)) else {
            return false;
        };
        if first.address != second.address {
            return false;
        }
        if let Some(a) = second.address {
            if self
                .intruders
                .iter()
                .flatten()
                .any(|s| s.address == Some(a))
            {
                return false;
            }
        }
        match (first.altitude_ft, second.altitude_ft) {
            (Some(a), Some(b)) => self.altitudes_correlate(a, b, quantum_of(second)),
            _ => true,
        }
    }
}

fn quantum_of<S>(reply: &ReplyData<S>) -> AltitudeQuantum {
    if reply.altitude_25ft {
        AltitudeQuantum::ModeS25
    } else {
        AltitudeQuantum::ModeC
    }
}

/// Where a measurement's time puts it (module docs, "Time").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Timing {
    ThisScan,
    LaterScan,
    Late,
    OutOfWindow,
}

/// A batch entry's claim on a slot; smaller is more important (module
/// docs, "Capacity").
#[derive(Debug, Clone, Copy, PartialEq)]
struct Priority<S> {
    class: u8,
    gate_cost: u16,
    range: S,
}

const CLASS_CONFIRMED_GATE: u8 = 0;
const CLASS_OTHER: u8 = 1;
const CLASS_REFUSED: u8 = 2;

impl<S: Scalar> Priority<S> {
    /// Strictly less important than `other`.
    fn is_worse_than(&self, other: &Self) -> bool {
        (self.class, self.gate_cost) > (other.class, other.gate_cost)
            || ((self.class, self.gate_cost) == (other.class, other.gate_cost)
                && self.range > other.range)
    }
}

/// A confirmed track's gate for the next scan, and its best measurement so
/// far.
#[derive(Debug, Clone, Copy)]
struct TrackGate<S: TrackNumeric> {
    region: GateRegion<S>,
    /// (batch index, gate cost) of the nearest measurement in the gate.
    champion: Option<(usize, u16)>,
}

/// `d` of the module docs: `t − n` as a signed 32-bit difference.
fn signed_difference(t: u32, n: u32) -> i32 {
    i32::from_ne_bytes(t.wrapping_sub(n).to_ne_bytes())
}

fn sat_u16(v: u32) -> u16 {
    u16::try_from(v).unwrap_or(u16::MAX)
}

fn sat_u32(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
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

/// The consumer half: sorts queued measurements into scans, turns each scan
/// into a tracker scan, threat assessments and reports. At most `N` tracks,
/// `M` measurements per scan.
///
/// Memory: the [`TrackTable`] (see [`crate::track`] for its size), plus per
/// measurement slot one `Measurement<S>`, one `Option<S>`, a priority and an
/// [`Association`], plus per track slot a gate region and an `Option` of an
/// [`AltitudeTracker<S>`](crate::filter::altitude::AltitudeTracker).
/// `host-tests/tests/it/scan/loop_on_host.rs` prints the sizes; the firmware prints
/// its own at start-up.
#[derive(Debug)]
pub struct ScanLoop<S: Scalar, F, const N: usize, const M: usize> {
    table: TrackTable<S, F, N, M>,
    /// The tracker's time of the next scan (ms; +1 period per scan).
    tracker_ms: u32,
    /// The sensor's time of the scan being assembled.
    scan_ms: u32,
    locked: bool,
    /// A measurement outside the window, held until the next one.
    candidate: Option<MeasurementReport>,
    /// The next measurement confirmed the candidate: re-lock after this scan.
    relock: bool,
    batch: heapless::Vec<Measurement<S>, M>,
    /// Per batch entry: altitude and Mode S address.
    batch_replies: heapless::Vec<ReplyData<S>, M>,
    /// The previous scan's (the first points of new tracks).
    previous_replies: heapless::Vec<ReplyData<S>, M>,
    batch_priorities: heapless::Vec<Priority<S>, M>,
    /// Per batch entry: of how many confirmed tracks it is the champion.
    batch_champions: heapless::Vec<u8, M>,
    gates: [Option<TrackGate<S>>; N],
    /// The batch overflowed: `gates` and the priorities are computed.
    ranked: bool,
    /// Counts of the scan being assembled (the intake part).
    pending_counts: ScanCounts,
    codes: [Association; M],
    intruders: [Option<IntruderSlot<S>>; N],
    /// The system's TCAS state: sensitivity level, inhibits, the RA.
    cas: CollisionAvoidance<S>,
    counters: LoopCounters,
}

impl<S: Scalar, F: TrackFilter<S> + BearingTrack<S>, const N: usize, const M: usize> Default
    for ScanLoop<S, F, N, M>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, F: TrackFilter<S> + BearingTrack<S>, const N: usize, const M: usize>
    ScanLoop<S, F, N, M>
{
    /// An empty loop: no tracks, no queued batch, zero counters (a `const fn`,
    /// for a `static`).
    pub const fn new() -> Self {
        ScanLoop {
            table: TrackTable::new(),
            tracker_ms: 0,
            scan_ms: 0,
            locked: false,
            candidate: None,
            relock: false,
            batch: heapless::Vec::new(),
            batch_replies: heapless::Vec::new(),
            previous_replies: heapless::Vec::new(),
            batch_priorities: heapless::Vec::new(),
            batch_champions: heapless::Vec::new(),
            gates: [const { None }; N],
            ranked: false,
            pending_counts: ScanCounts::new(),
            codes: [Association::OutsideGates; M],
            intruders: [const { None }; N],
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
        self.batch
            .len()
            .saturating_add(usize::from(self.candidate.is_some()))
    }

    /// The altitude estimate of a track, if it reported altitude.
    pub fn altitude(&self, track: TrackId) -> Option<AltitudeEstimate<S>> {
        self.intruder(track)
            .and_then(|t| t.altitude_tracker().estimate())
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
        self.intruders.iter().flatten().find(|s| s.track == track)
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
        if self.candidate.take().is_some() {
            bump16(&mut self.pending_counts.out_of_window);
            bump(&mut self.counters.out_of_window);
        }
    }

    /// Takes the queued measurements that belong to the scan being
    /// assembled into its batch (converting them: the checked edge), and
    /// counts the late and out-of-window ones; stops at the first one for a
    /// later scan. Call it as often as wanted between scans: it frees queue
    /// space early.
    pub fn collect(
        &mut self,
        config: &ScanConfig<S, F::Params>,
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
                bump(&mut self.counters.clock_locks);
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
                        bump16(&mut self.pending_counts.late);
                        bump(&mut self.counters.late);
                    }
                }
                Timing::OutOfWindow => {
                    let consistent = self.candidate.is_some_and(|c| {
                        signed_difference(head.time_ms, c.time_ms).unsigned_abs() <= clock.period_ms
                    });
                    if consistent {
                        self.relock = true;
                        return Collected::ScanDue;
                    }
                    self.drop_candidate();
                    self.candidate = source.pop();
                }
            }
        }
    }

    /// Re-locks onto the held measurement's time; it joins the (empty)
    /// batch.
    fn apply_relock(&mut self, config: &ScanConfig<S, F::Params>) {
        self.relock = false;
        if let Some(c) = self.candidate.take() {
            self.scan_ms = c.time_ms;
            bump(&mut self.counters.clock_relocks);
            self.take(config, &c);
        }
    }

    /// One measurement of this scan: converted, then into the batch; by
    /// priority once the batch is full.
    fn take(&mut self, config: &ScanConfig<S, F::Params>, report: &MeasurementReport) {
        let converted = report
            .position::<S>()
            .and_then(|m| report.altitude::<S>().map(|a| (m, a)));
        let Ok((measurement, altitude_ft)) = converted else {
            bump16(&mut self.pending_counts.invalid);
            bump(&mut self.counters.invalid);
            return;
        };
        if self.batch.len() < M {
            // Room: no priority needed (yet). Four pushes on vectors of the
            // same length below M.
            let reply = ReplyData {
                altitude_ft,
                altitude_25ft: report.altitude_25ft,
                address: report.address,
            };
            let _ = self.batch.push(measurement);
            let _ = self.batch_replies.push(reply);
            let _ = self.batch_priorities.push(Priority {
                class: CLASS_OTHER,
                gate_cost: 0,
                range: S::ZERO,
            });
            let _ = self.batch_champions.push(0);
            return;
        }
        if !self.ranked {
            self.rank_batch(config);
        }
        let observation = Observation::new(measurement).ok();
        let priority = self.priority(observation.as_ref());
        let Some(index) = self.evictable(&priority, observation.as_ref()) else {
            bump16(&mut self.pending_counts.over_capacity);
            bump(&mut self.counters.over_capacity);
            return;
        };
        self.release(index);
        bump16(&mut self.pending_counts.over_capacity);
        bump(&mut self.counters.over_capacity);
        if let Some(slot) = self.batch.get_mut(index) {
            *slot = measurement;
        }
        if let Some(slot) = self.batch_replies.get_mut(index) {
            *slot = ReplyData {
                altitude_ft,
                altitude_25ft: report.altitude_25ft,
                address: report.address,
            };
        }
        if let Some(slot) = self.batch_priorities.get_mut(index) {
            *slot = priority;
        }
        if let Some(o) = observation {
            self.crown(index, &o);
        }
    }

    /// The batch has just overflowed: the gates of the confirmed tracks,
    /// and the priority and champion places of every entry (in arrival
    /// order). Only a scan with more than `M` measurements pays for this.
    fn rank_batch(&mut self, config: &ScanConfig<S, F::Params>) {
        self.prepare_gates(config);
        self.ranked = true;
        for i in 0..self.batch.len() {
            let observation = self.batch.get(i).and_then(|m| Observation::new(*m).ok());
            let priority = self.priority(observation.as_ref());
            if let Some(slot) = self.batch_priorities.get_mut(i) {
                *slot = priority;
            }
            if let Some(o) = observation {
                self.crown(i, &o);
            }
        }
    }

    /// The priority of a measurement against the gates of the next scan.
    fn priority(&self, observation: Option<&Observation<S>>) -> Priority<S> {
        let Some(o) = observation else {
            return Priority {
                class: CLASS_REFUSED,
                gate_cost: 0,
                range: S::ZERO,
            };
        };
        let best = self
            .gates
            .iter()
            .flatten()
            .filter_map(|g| g.region.cost(o))
            .min();
        // Positions are relative to the own aircraft.
        let [x, y] = o.xy();
        let range = hypot(x, y);
        match best {
            Some(gate_cost) => Priority {
                class: CLASS_CONFIRMED_GATE,
                gate_cost,
                range,
            },
            None => Priority {
                class: CLASS_OTHER,
                gate_cost: 0,
                range,
            },
        }
    }

    /// Which batch entry a new measurement replaces, if any: the least
    /// important one that is no confirmed track's nearest measurement once
    /// the new one is counted (it may take that place from another), if the
    /// new one is more important or takes such a place itself.
    fn evictable(
        &self,
        priority: &Priority<S>,
        observation: Option<&Observation<S>>,
    ) -> Option<usize> {
        // Champion places the new measurement would take from each entry,
        // and whether it would hold one.
        let mut dethroned = [0u8; M];
        let mut crowned = false;
        if let Some(o) = observation {
            for gate in self.gates.iter().flatten() {
                let Some(cost) = gate.region.cost(o) else {
                    continue;
                };
                match gate.champion {
                    Some((i, c)) if cost < c => {
                        crowned = true;
                        if let Some(d) = dethroned.get_mut(i) {
                            *d = d.saturating_add(1);
                        }
                    }
                    None => crowned = true,
                    _ => {}
                }
            }
        }
        // The least important unprotected entry (the last of equals).
        let mut worst: Option<(usize, &Priority<S>)> = None;
        for (i, (p, (&places, &taken))) in self
            .batch_priorities
            .iter()
            .zip(self.batch_champions.iter().zip(dethroned.iter()))
            .enumerate()
        {
            if places > taken {
                continue;
            }
            if worst.is_none_or(|(_, w)| !w.is_worse_than(p)) {
                worst = Some((i, p));
            }
        }
        let (w, worst_priority) = worst?;
        // Ties keep the measurement already in the batch.
        if crowned || worst_priority.is_worse_than(priority) {
            Some(w)
        } else {
            None
        }
    }

    /// Clears a batch entry's champion places (it is being replaced).
    fn release(&mut self, index: usize) {
        for gate in self.gates.iter_mut().flatten() {
            if gate.champion.is_some_and(|(i, _)| i == index) {
                gate.champion = None;
            }
        }
        if let Some(c) = self.batch_champions.get_mut(index) {
            *c = 0;
        }
    }

    /// Makes the entry at `index` the champion of every confirmed track
    /// whose gate it is nearest to so far.
    fn crown(&mut self, index: usize, observation: &Observation<S>) {
        for gate in self.gates.iter_mut().flatten() {
            let Some(cost) = gate.region.cost(observation) else {
                continue;
            };
            let previous = match gate.champion {
                Some((_, c)) if cost >= c => continue,
                previous => previous,
            };
            if let Some((p, _)) = previous {
                if let Some(count) = self.batch_champions.get_mut(p) {
                    *count = count.saturating_sub(1);
                }
            }
            gate.champion = Some((index, cost));
            if let Some(count) = self.batch_champions.get_mut(index) {
                *count = count.saturating_add(1);
            }
        }
    }

    /// The gates of the confirmed tracks for the scan being assembled (one
    /// period after the last).
    fn prepare_gates(&mut self, config: &ScanConfig<S, F::Params>) {
        self.gates = [const { None }; N];
        let params = config.tracker.params();
        let Some(step) = ScanInterval::from_ms(config.clock.period_ms)
            .and_then(|interval| F::step(params, &interval).ok())
        else {
            return;
        };
        let confirmed = self.table.tracks().filter(|t| t.is_confirmed());
        for (gate, track) in self.gates.iter_mut().zip(confirmed) {
            let region = track.filter().predict(params, &step).ok().and_then(|p| {
                track
                    .filter()
                    .gate_region(params, &p, &step, config.tracker.gate())
            });
            *gate = region.map(|region| TrackGate {
                region,
                champion: None,
            });
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
        config: &ScanConfig<S, F::Params>,
        source: &mut impl MeasurementSource,
        mut emit: impl FnMut(&Message),
    ) -> Result<TickReport, ScanError> {
        if self.relock && self.batch.is_empty() {
            // Nothing for the old time base: re-lock at once.
            self.apply_relock(config);
        }
        self.collect(config, source);
        let used = self.batch.len();
        let dt = S::from_f64_lossy(f64::from(config.clock.period_ms) / 1000.0);
        let rule = IdentityRule {
            intruders: &self.intruders,
            replies: &self.batch_replies,
            previous: &self.previous_replies,
            dt,
        };
        let report = self.table.scan_with_rule(
            &config.tracker,
            self.tracker_ms,
            &self.batch,
            &mut self.codes,
            &rule,
            |_| {},
        )?;
        self.update_intruders(config, &report);
        let ra = self.assess_tracks(config, &report);
        let (highest, confirmed_tracks) = self.report_tracks(ra.advisory, &mut emit);

        let mut counts = self.pending_counts;
        counts.used = sat_u16(sat_u32(used));
        for code in self.codes.iter().take(used) {
            bump16(match code {
                Association::Updated(_) => &mut counts.updated,
                Association::Started(_) => &mut counts.started,
                Association::NotAssigned => &mut counts.not_assigned,
                Association::OutsideGates => &mut counts.outside_gates,
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
        counts.restarted = sat_u16(report.restarted);
        counts.tracks = sat_u16(report.tracks);
        counts.confirmed_tracks = sat_u16(confirmed_tracks);

        let c = &mut self.counters;
        bump(&mut c.scans);
        c.used = c.used.saturating_add(sat_u32(used));
        c.tracks_started = c.tracks_started.saturating_add(report.started);
        c.tracks_confirmed = c.tracks_confirmed.saturating_add(report.confirmed);
        c.tracks_deleted = c.tracks_deleted.saturating_add(report.deleted);
        c.tracks_restarted = c.tracks_restarted.saturating_add(report.restarted);
        c.refused_table_full = c
            .refused_table_full
            .saturating_add(report.refused_table_full);

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
        self.batch_champions.clear();
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
            let slot = self
                .intruders
                .iter()
                .flatten()
                .find(|s| s.track == track.id());
            let assessed = slot.and_then(|s| s.assessed);
            let advisory = assessed.map_or(Advisory::None, |a| a.advisory);
            highest = highest.max(advisory);
            let altitude = slot.and_then(|s| s.tcas.altitude_tracker().estimate());
            let [x, y] = track.position();
            let [vx, vy] = track.velocity();
            let tau_ds = assessed.and_then(|a| a.range_tau_s).map(|tau| {
                let ds = scaled_i32(tau, 10.0);
                u16::try_from(ds.max(0)).unwrap_or(u16::MAX)
            });
            let report = TrackReport {
                time_ms: self.scan_ms,
                track_id: track.id().get(),
                status: track.status(),
                advisory,
                sensitivity: assessed.map(|a| a.sensitivity),
                x_cm: scaled_i32(x, 100.0),
                y_cm: scaled_i32(y, 100.0),
                vx_cm_per_s: scaled_i32(vx, 100.0),
                vy_cm_per_s: scaled_i32(vy, 100.0),
                altitude: altitude.map(|a| {
                    let rate = scaled_i32(a.vertical_rate_ft_per_s, 60.0);
                    (
                        scaled_i32(a.altitude_ft, 1.0),
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
            bump(&mut self.counters.track_reports);
        }
        (highest, confirmed)
    }

    /// Feeds each reply the tracker used to its track's range and altitude
    /// trackers (a started track gets its slot, its address and the
    /// altitude tracker of its reply's quantum); coasts the others; frees
    /// the slots of deleted tracks.
    fn update_intruders(&mut self, config: &ScanConfig<S, F::Params>, report: &ScanReport) {
        for slot in self.intruders.iter_mut() {
            match slot {
                Some(s) if self.table.track(s.track).is_some() => {
                    s.updated = false;
                    s.assessed = None;
                }
                _ => *slot = None,
            }
        }
        // The first scan has no interval, and no track yet.
        if report.interval_ms == 0 {
            return;
        }
        let Ok(dt) = S::try_from_f64(f64::from(report.interval_ms) / 1000.0) else {
            return;
        };
        let n = self.batch.len().min(M);
        let replies = self.batch.iter().zip(self.batch_replies.iter());
        for (code, (measurement, reply)) in self.codes.iter().take(n).zip(replies) {
            let (Association::Updated(id) | Association::Started(id)) = *code else {
                continue;
            };
            let index = match self
                .intruders
                .iter()
                .position(|s| matches!(s, Some(s) if s.track == id))
            {
                Some(i) => Some(i),
                None => {
                    // A track per slot at most, and a slot per track: a free
                    // slot exists for every live track.
                    let free = self.intruders.iter().position(|s| s.is_none());
                    let quantum = quantum_of(reply);
                    let altitude = match quantum {
                        AltitudeQuantum::ModeC => config.altitude,
                        AltitudeQuantum::ModeS25 => config.altitude_25ft,
                    };
                    if let Some(Some(slot)) = free.map(|i| self.intruders.get_mut(i)) {
                        *slot = Some(IntruderSlot {
                            track: id,
                            address: reply.address,
                            quantum,
                            tcas: IntruderTrack::new(altitude),
                            updated: false,
                            assessed: None,
                        });
                    }
                    free
                }
            };
            let range_m = match *measurement {
                Measurement::Polar { range, .. } => range,
                Measurement::Cartesian { x, y } => hypot(x, y),
            };
            if let Some(Some(s)) = index.and_then(|i| self.intruders.get_mut(i)) {
                let reply = Reply {
                    range_m,
                    altitude_ft: reply.altitude_ft,
                };
                if s.tcas.scan(Some(reply), dt).is_err() {
                    bump(&mut self.counters.intruder_tracker_errors);
                }
                s.updated = true;
            }
        }
        for s in self.intruders.iter_mut().flatten() {
            if !s.updated && s.tcas.scan(None, dt).is_err() {
                bump(&mut self.counters.intruder_tracker_errors);
            }
        }
    }

    /// The TCAS cycle: the sensitivity level for the own
    /// aircraft, the threat logic of every confirmed track (advisories only
    /// from firm tracks: [`crate::tcas::ThreatState::assess`]), then the RA
    /// against the RA threats ([`CollisionAvoidance::resolve`]). Failures
    /// are counted (`assessment_errors`) and give no advisory.
    fn assess_tracks(
        &mut self,
        config: &ScanConfig<S, F::Params>,
        report: &ScanReport,
    ) -> RaOutput {
        let none = RaOutput {
            advisory: None,
            clear_of_conflict: false,
        };
        if report.interval_ms == 0 {
            return none;
        }
        let Ok(dt) = S::try_from_f64(f64::from(report.interval_ms) / 1000.0) else {
            return none;
        };
        let Ok(cycle) = self.cas.begin_cycle(&config.own, false) else {
            bump(&mut self.counters.assessment_errors);
            return none;
        };
        let mut threats: heapless::Vec<ThreatGeometry<S>, MAX_RA_THREATS> = heapless::Vec::new();
        for track in self.table.tracks().filter(|t| t.is_confirmed()) {
            let Some(slot) = self
                .intruders
                .iter_mut()
                .flatten()
                .find(|s| s.track == track.id())
            else {
                continue;
            };
            let status = match slot.tcas.assess(&cycle, track.filter().bearing_track(), dt) {
                Ok(status) => status,
                Err(_) => {
                    bump(&mut self.counters.assessment_errors);
                    continue;
                }
            };
            let range = slot.tcas.range_tracker().estimate();
            slot.assessed = Some(Assessed {
                advisory: status.map_or(Advisory::None, |s| s.advisory),
                sensitivity: cycle.params.level,
                range_tau_s: range
                    .and_then(|r| range_tau(r.range_m, r.range_rate_m_per_s).ok().flatten()),
            });
            if let Some(g) = status.and_then(|s| s.geometry) {
                add_threat(&mut threats, g, &mut self.counters);
            }
        }
        match self.cas.resolve(&cycle, &threats, dt) {
            Ok(out) => RaOutput {
                advisory: out.advisory.map(|a| RaCode {
                    sense: a.sense,
                    strength: a.strength,
                }),
                clear_of_conflict: out.clear_of_conflict,
            },
            Err(_) => {
                bump(&mut self.counters.assessment_errors);
                none
            }
        }
    }
}

/// This scan's RA, as reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct RaOutput {
    advisory: Option<RaCode>,
    clear_of_conflict: bool,
}

/// Adds an RA threat; beyond [`MAX_RA_THREATS`] the one with the largest
/// modified tau is left out (counted).
fn add_threat<S: Scalar>(
    threats: &mut heapless::Vec<ThreatGeometry<S>, MAX_RA_THREATS>,
    threat: ThreatGeometry<S>,
    counters: &mut LoopCounters,
) {
    let Err(threat) = threats.push(threat) else {
        return;
    };
    bump(&mut counters.ra_threats_over_capacity);
    let latest = threats.iter_mut().reduce(|a, b| {
        if b.modified_tau_s > a.modified_tau_s {
            b
        } else {
            a
        }
    });
    if let Some(latest) = latest {
        if threat.modified_tau_s < latest.modified_tau_s {
            *latest = threat;
        }
    }
}

// ---------------------------------------------------------------------------
// The verdict of a run
// ---------------------------------------------------------------------------

/// Whether a run's input was used, from its last health counters: the rule
/// behind the demo firmware's exit status.
///
/// The sensor sent `sent = accepted frames + frames lost` (from the
/// sequence numbers); of those, `lost = frames lost + measurements not used`
/// (queue full, late, out of the window, over capacity, not representable).
/// A run is **clean** when it used at least one measurement and lost at
/// most one in [`MAX_LOST_FRACTION_INVERSE`] of what was sent, and no
/// threat assessment failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RunVerdict {
    /// Frames the sensor sent: accepted plus lost (from the sequence numbers).
    pub sent: u32,
    /// Frames lost plus measurements not used (queue full, late, out of the
    /// window, over capacity, not representable).
    pub lost: u32,
    /// Measurements used by the track table.
    pub used: u32,
    /// Threat assessments that failed.
    pub assessment_errors: u32,
}

/// A clean run loses at most 1 in this many of the frames sent.
pub const MAX_LOST_FRACTION_INVERSE: u32 = 10;

impl RunVerdict {
    /// The verdict from a run's last health counters.
    pub fn from_health(h: &Health) -> Self {
        let s = &h.scan;
        let lost = [
            h.decoder.frames_lost,
            h.intake.queue_full,
            s.late,
            s.out_of_window,
            s.over_capacity,
            s.invalid,
        ]
        .into_iter()
        .fold(0u32, |a, b| a.saturating_add(b));
        RunVerdict {
            sent: h.decoder.accepted.saturating_add(h.decoder.frames_lost),
            lost,
            used: s.used,
            assessment_errors: s.assessment_errors,
        }
    }

    /// More than one in [`MAX_LOST_FRACTION_INVERSE`] of the frames sent
    /// was not used.
    pub fn lost_too_much(&self) -> bool {
        u64::from(self.lost).saturating_mul(u64::from(MAX_LOST_FRACTION_INVERSE))
            > u64::from(self.sent)
    }

    /// Used at least one measurement, lost at most one in
    /// [`MAX_LOST_FRACTION_INVERSE`] and no assessment failed.
    pub fn is_clean(&self) -> bool {
        self.used > 0 && !self.lost_too_much() && self.assessment_errors == 0
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

    /// Gives the (traffic, resolution) pins back.
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
