use super::*;
use crate::count::{increment, sat_u32};

/// Numbers the frames of one sender's stream (the header's sequence
/// number, +1 per frame, wrapping), so that the receiver counts lost
/// frames.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Encoder {
    next_sequence: u16,
}

impl Encoder {
    /// A stream whose first frame is number 0.
    pub const fn new() -> Self {
        Encoder { next_sequence: 0 }
    }

    /// The number the next frame gets.
    pub fn next_sequence(&self) -> u16 {
        self.next_sequence
    }

    /// Writes the next frame of the stream; the number advances only when
    /// the frame was written.
    pub fn encode(&mut self, message: &Message, buffer: &mut [u8]) -> Result<usize, WireError> {
        let len = message.emit(self.next_sequence, buffer)?;
        self.next_sequence = self.next_sequence.wrapping_add(1);
        Ok(len)
    }

    /// Counts a frame as sent without writing it (a sender that drops a
    /// frame on purpose, e.g. a test of the receiver's loss count).
    pub fn skip(&mut self) {
        self.next_sequence = self.next_sequence.wrapping_add(1);
    }
}

/// Byte-at-a-time frame decoder for a receive interrupt: no allocation,
/// O(1) work per byte except after a failed candidate.
///
/// It hunts for [`SYNC`], checks the type and length bytes as soon as they
/// arrive, and the CRC, fields and envelope at the end of the frame. After
/// any failure it drops only the candidate's first byte and examines the
/// bytes it had taken again, so a valid frame that began inside a corrupted,
/// truncated or made-up one is still found. It never panics, whatever the
/// bytes.
///
/// A candidate whose CRC fails although a frame header (sync, a known type,
/// its length: as many of these bytes as the candidate holds, at least the
/// two sync bytes) starts inside it was cut short by that frame: it is
/// counted as [`truncated`](DecoderStats::truncated), not as a CRC error.
///
/// Each call returns at most one result. A failure, or a frame found among
/// re-examined bytes, can leave further bytes held and unexamined: they are
/// examined on the next [`push`](Decoder::push), or by [`poll`](Decoder::poll)
/// without new input (at most [`MAX_FRAMES_PER_BYTE`] frames plus failures
/// can be pending), so nothing is lost, only delayed. When the line goes
/// idle, [`line_idle`](Decoder::line_idle) abandons a partial frame.
///
/// Sequence numbers: each accepted frame's number is compared with the one
/// after the previous accepted frame; a gap of `d` (less than 2¹⁵) counts
/// `d` [`frames_lost`](DecoderStats::frames_lost), a step back or a repeat
/// counts [`out_of_sequence`](DecoderStats::out_of_sequence) and restarts
/// the count there. The candidates refused before the first accepted frame
/// count as lost too, up to that frame's number (the frames the sender can
/// have sent before it, a sender numbering from 0): a stream whose first
/// frames are damaged loses them as one damaged later would be lost. These
/// are candidates, not frames (one damaged frame can be refused as
/// several), so before a stream joined late more can be counted than were
/// lost; after a sender restart, damaged frames before its first accepted
/// one are not counted (docs/firmware-runtime.md, "Sequence numbers").
#[derive(Debug, Clone)]
pub struct Decoder {
    buffer: [u8; MAX_FRAME_LEN],
    /// Bytes held in `buffer`.
    held: usize,
    /// Leading bytes of `buffer` examined and accepted as the current
    /// candidate frame.
    accepted: usize,
    /// The sequence number the next frame should carry.
    expected_sequence: Option<u16>,
    /// Candidates refused before the first accepted frame (saturating).
    refused_before_first: u16,
    stats: DecoderStats,
}

impl Default for Decoder {
    fn default() -> Self {
        Self::new()
    }
}

enum Verdict {
    Accept,
    /// Not a frame start: drop the first byte quietly.
    Skip,
    /// A candidate failed: drop its first byte, report the error.
    Fail(WireError),
}

impl Decoder {
    /// An empty decoder: nothing held, zero counters, no sequence expected
    /// yet (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        Decoder {
            buffer: [0; MAX_FRAME_LEN],
            held: 0,
            accepted: 0,
            expected_sequence: None,
            refused_before_first: 0,
            stats: DecoderStats::new(),
        }
    }

    /// What the decoder has seen over its lifetime.
    pub fn stats(&self) -> &DecoderStats {
        &self.stats
    }

    /// Bytes held: a partial frame and bytes waiting to be examined again.
    pub fn held(&self) -> usize {
        self.held
    }

    /// Forgets the held bytes (counting them as skipped), e.g. after a line
    /// break.
    pub fn reset(&mut self) {
        self.discard(self.held);
    }

    /// Takes one received byte; returns a frame or a frame-level error if
    /// one completed.
    pub fn push(&mut self, byte: u8) -> Option<Result<Message, WireError>> {
        increment(&mut self.stats.bytes);
        if self.held >= MAX_FRAME_LEN {
            // Unreachable: after every call fewer than MAX_FRAME_LEN bytes
            // are held (a candidate of MAX_FRAME_LEN bytes is complete and
            // examined). Kept so that a broken invariant costs a byte, not a
            // panic.
            self.discard(1);
        }
        if let Some(slot) = self.buffer.get_mut(self.held) {
            *slot = byte;
            self.held = self.held.saturating_add(1);
        }
        self.poll()
    }

    fn byte(&self, i: usize) -> Option<u8> {
        self.buffer.get(..self.held).and_then(|b| b.get(i)).copied()
    }

    /// Examines held bytes without new input; `None` once nothing more can
    /// complete until more bytes arrive.
    pub fn poll(&mut self) -> Option<Result<Message, WireError>> {
        while self.accepted < self.held {
            let i = self.accepted;
            let byte = self.byte(i).unwrap_or(0);
            let verdict = match i {
                0 if byte == SYNC[0] => Verdict::Accept,
                1 if byte == SYNC[1] => Verdict::Accept,
                0 | 1 => Verdict::Skip,
                2 => match FrameKind::from_byte(byte) {
                    Some(_) => Verdict::Accept,
                    None => Verdict::Fail(WireError::UnknownType),
                },
                3 => match self.byte(2).and_then(FrameKind::from_byte) {
                    Some(kind) if kind.payload_len() == usize::from(byte) => Verdict::Accept,
                    _ => Verdict::Fail(WireError::BadLength),
                },
                _ => Verdict::Accept,
            };
            match verdict {
                Verdict::Skip => self.discard(1),
                Verdict::Fail(e) => return Some(Err(self.refuse(e))),
                Verdict::Accept => {
                    self.accepted = self.accepted.saturating_add(1);
                    let frame = Frame::new_unchecked(self.buffer.get(..self.accepted)?);
                    if self.accepted >= HEADER_LEN && self.accepted == frame.frame_len() {
                        let sequence = frame.sequence();
                        return Some(match Message::parse(&frame) {
                            Ok(message) => {
                                self.accept(sequence);
                                Ok(message)
                            }
                            Err(WireError::Checksum) if self.header_inside_candidate() => {
                                Err(self.refuse(WireError::Truncated))
                            }
                            Err(e) => Err(self.refuse(e)),
                        });
                    }
                }
            }
        }
        None
    }

    /// The line went idle (no byte for longer than a frame takes): a partial
    /// frame will not complete. Abandons it (counted as
    /// [`truncated`](DecoderStats::truncated), returned as
    /// [`WireError::Truncated`]) and examines the bytes after its first
    /// again; call until it returns `None`, which leaves nothing held.
    pub fn line_idle(&mut self) -> Option<Result<Message, WireError>> {
        if let Some(event) = self.poll() {
            return Some(event);
        }
        if self.held == 0 {
            return None;
        }
        // `poll` returned None with bytes held: they are an incomplete
        // candidate.
        Some(Err(self.refuse(WireError::Truncated)))
    }

    /// Whether a frame header starts inside the current (complete)
    /// candidate, after its first byte: as many of its four bytes as the
    /// candidate holds, at least the two sync bytes.
    fn header_inside_candidate(&self) -> bool {
        let end = self.accepted;
        (1..end.saturating_sub(1)).any(|i| {
            let at = |k: usize| {
                self.byte(i.saturating_add(k))
                    .filter(|_| i.saturating_add(k) < end)
            };
            let sync = at(0) == Some(SYNC[0]) && at(1) == Some(SYNC[1]);
            let kind = at(2).map(FrameKind::from_byte);
            let type_ok = !matches!(kind, Some(None));
            let length_ok = match (kind, at(3)) {
                (Some(Some(k)), Some(len)) => k.payload_len() == usize::from(len),
                _ => true,
            };
            sync && type_ok && length_ok
        })
    }

    /// Counts a refused candidate and drops its first byte.
    fn refuse(&mut self, e: WireError) -> WireError {
        let s = &mut self.stats;
        increment(&mut s.frames);
        increment(match e {
            WireError::Checksum => &mut s.crc_errors,
            WireError::UnknownType => &mut s.unknown_type,
            WireError::BadLength => &mut s.bad_length,
            WireError::OutOfEnvelope => &mut s.out_of_envelope,
            WireError::Truncated => &mut s.truncated,
            // BadSync and BufferTooShort cannot come out of the decoder's
            // own checks; BadField is the remaining one.
            _ => &mut s.bad_field,
        });
        if self.expected_sequence.is_none() {
            self.refused_before_first = self.refused_before_first.saturating_add(1);
        }
        self.discard(1);
        e
    }

    /// Counts an accepted candidate (and its sequence number) and drops its
    /// bytes.
    fn accept(&mut self, sequence: u16) {
        let s = &mut self.stats;
        increment(&mut s.frames);
        increment(&mut s.accepted);
        s.frame_bytes = s.frame_bytes.saturating_add(sat_u32(self.accepted));
        if let Some(expected) = self.expected_sequence {
            let gap = sequence.wrapping_sub(expected);
            if gap < 0x8000 {
                s.frames_lost = s.frames_lost.saturating_add(u32::from(gap));
            } else {
                increment(&mut s.out_of_sequence);
            }
        } else {
            let before = self.refused_before_first.min(sequence);
            s.frames_lost = s.frames_lost.saturating_add(u32::from(before));
        }
        self.expected_sequence = Some(sequence.wrapping_add(1));
        self.consume(self.accepted);
    }

    /// Drops the first `n` held bytes as skipped; restarts the hunt.
    fn discard(&mut self, n: usize) {
        let n = n.min(self.held);
        self.stats.bytes_skipped = self.stats.bytes_skipped.saturating_add(sat_u32(n));
        self.consume(n);
    }

    /// Drops the first `n` held bytes; restarts the hunt at the next one.
    fn consume(&mut self, n: usize) {
        let n = n.min(self.held);
        let kept = self.held.saturating_sub(n);
        // Element by element: `copy_within` would keep a bounds-check panic
        // path.
        for to in 0..kept {
            let byte = self.byte(to.saturating_add(n)).unwrap_or(0);
            if let Some(slot) = self.buffer.get_mut(to) {
                *slot = byte;
            }
        }
        self.held = kept;
        self.accepted = 0;
    }
}
