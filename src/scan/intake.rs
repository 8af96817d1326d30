//! The producer half, run in the receive interrupt: bytes into the decoder,
//! measurements into a queue.

use crate::count::increment;

use crate::wire::{
    Decoder, DecoderStats, EndOfInput, IntakeCounters, MeasurementReport, Message, WireError,
    MAX_FRAMES_PER_BYTE,
};

/// A fixed-capacity FIFO of measurements: `Q` slots, no heap, no panic
/// path (indices wrap by comparison, never by `%`). An empty queue is
/// all-zero bytes, so a `static` one costs no flash.
#[derive(Debug, Clone)]
pub struct MeasurementQueue<const Q: usize> {
    /// The ring's slots, written in order `0, 1, …, Q − 1, 0, …`: the
    /// vector grows to `Q` as the ring's write position first passes each.
    slots: heapless::Vec<MeasurementReport, Q>,
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
            slots: heapless::Vec::new(),
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
        let written = self.slots.len();
        match self.slots.get_mut(i) {
            Some(slot) => *slot = m,
            // The write position reaches a slot for the first time.
            None if i == written => self.slots.push(m)?,
            None => return Err(m),
        }
        self.len = self.len.saturating_add(1);
        Ok(())
    }

    /// The oldest measurement.
    pub fn peek(&self) -> Option<&MeasurementReport> {
        if self.len == 0 {
            return None;
        }
        self.slots.get(self.head)
    }

    /// Takes the oldest measurement.
    pub fn pop(&mut self) -> Option<MeasurementReport> {
        if self.len == 0 {
            return None;
        }
        let m = self.slots.get(self.head).copied();
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
                increment(&mut self.counters.measurements);
                match self.queue.push(m) {
                    Ok(()) => return 1,
                    Err(_) => increment(&mut self.counters.queue_full),
                }
            }
            Ok(Message::End(e)) => {
                increment(&mut self.counters.not_measurement);
                self.ended = Some(e);
            }
            Ok(_) => increment(&mut self.counters.not_measurement),
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
        increment(&mut self.counters.rx_overruns);
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
