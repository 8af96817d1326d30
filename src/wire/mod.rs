//! The serial protocol: measurement frames in; track, scan and health report
//! frames out. Sans-IO and allocation-free (in the style of smoltcp's
//! `wire`): a byte view [`Frame`] with `new_checked`, the typed [`Message`]
//! with [`Message::parse`] / [`Message::emit`], named field offsets
//! ([`field`]), a numbering [`Encoder`] and a byte-at-a-time [`Decoder`] for
//! an interrupt handler.
//!
//! The layouts are tables ([`field`]): each field is declared once, with its
//! type, and its offset follows from the fields before it, so adding a field
//! is one line in a table (and its meaning in `parse` and `emit`); the
//! payload length follows from the table. `docs/firmware-runtime.md` prints
//! every layout.
//!
//! # Frame
//!
//! | offset | bytes | field |
//! |---|---|---|
//! | 0 | 2 | sync `0xAB 0xCD` ([`SYNC`]) |
//! | 2 | 1 | message type ([`FrameKind`]) |
//! | 3 | 1 | payload length `L`: must be the type's length |
//! | 4 | 2 | sequence number: the sender's frame count, +1 per frame, wrapping |
//! | 6 | `L` | payload, big-endian (network order) fields |
//! | 6 + `L` | 4 | CRC-32C of bytes 2 .. 6 + `L`, big-endian |
//!
//! CRC-32C (Castagnoli et al., IEEE Trans. Commun. 41(6), 1993; the iSCSI
//! CRC of RFC 3720): reflected polynomial 0x82F63B78, initial value and final
//! XOR 0xFFFFFFFF; check value 0xE3069283 for the ASCII bytes `123456789`
//! ([`crc32c`]). The sync bytes are not covered (they are constant); the
//! length and the sequence number are. Why 32 bits and not 16:
//! `docs/firmware-runtime.md`, "Framing".
//!
//! Every type has one fixed payload length. The decoder checks the type at
//! byte 2 and the length at byte 3, so a corrupted header is refused at once
//! instead of swallowing the following frames.
//!
//! # Payloads
//!
//! Integers only: the bytes mean the same thing whatever number
//! representation (f64, f32, Q32.32) either end computes in, every value has
//! exactly one encoding, and a receiver needs no float parsing in its
//! interrupt handler. Resolution: 1 cm, 1 cm/s, 1 ft, 2π/65536 rad (0.0055°,
//! the binary angle of ASTERIX radar data), 1 ms, 0.1 s. Unused bits and
//! absent fields must be 0 ([`WireError::BadField`] otherwise).
//!
//! | type | message | payload layout |
//! |---|---|---|
//! | `0x01` | Cartesian measurement | [`field::cartesian`] |
//! | `0x02` | polar measurement | [`field::polar`] |
//! | `0x03` | end of input: a recording ends here | [`field::end`] |
//! | `0x81` | track report, one per confirmed track per scan | [`field::track`] |
//! | `0x82` | scan summary, one per scan | [`field::scan`], counts [`ScanCounts`] |
//! | `0x84` | health, one per scan: every lifetime counter | [`field::health`] |
//!
//! # The envelope
//!
//! A measurement frame with a valid CRC is still refused
//! ([`WireError::OutOfEnvelope`], counted) when it is not physical for the
//! tracker: a position or range beyond 400 km ([`MAX_POSITION_CM`], the
//! numeric envelope of the fixed-point filters) or a reported
//! altitude outside Mode C's −1000 … 126 700 ft. The decoder then examines
//! the candidate's bytes again, so a made-up frame (a CRC collision in
//! garbage) cannot swallow a real frame behind it. Times are checked by the
//! scan clock ([`crate::scan`]); speeds by the tracker's gates and
//! initiation bound.

mod counters;
mod crc;
mod error;
mod frame;
#[macro_use]
mod layout;
mod message;
mod stream;

/// The layouts: the frame header and each message's payload (offsets within
/// the payload). See the module docs for the frame around them.
pub mod field;

pub use counters::*;
pub use crc::*;
pub use error::*;
pub use frame::*;
pub use layout::*;
pub use message::*;
pub use stream::*;

use core::marker::PhantomData;

use crate::num::Scalar;
use crate::tcas::{Advisory, RaSense, RaStrength, SensitivityLevel};
use crate::track::{Measurement, TrackStatus};

/// The two bytes that start every frame.
pub const SYNC: [u8; 2] = [0xAB, 0xCD];
/// Sync, type, length and sequence number.
pub const HEADER_LEN: usize = field::header::LEN;
/// The CRC at the end.
pub const CRC_LEN: usize = 4;
/// The longest payload of any type.
pub const MAX_PAYLOAD_LEN: usize = FrameKind::payload_bound(true);
/// The longest frame.
pub const MAX_FRAME_LEN: usize = frame_len_for(MAX_PAYLOAD_LEN);
/// The shortest frame (the end of input).
pub const MIN_FRAME_LEN: usize = frame_len_for(FrameKind::payload_bound(false));
/// At most this many frames can complete on one byte pushed into the
/// [`Decoder`]: after a failed candidate, the bytes it held are examined
/// again, and up to `MAX_FRAME_LEN / MIN_FRAME_LEN` frames fit in them. A
/// producer that wants no message dropped keeps this many queue slots free.
pub const MAX_FRAMES_PER_BYTE: usize = MAX_FRAME_LEN / MIN_FRAME_LEN;

const fn frame_len_for(payload: usize) -> usize {
    HEADER_LEN.saturating_add(payload).saturating_add(CRC_LEN)
}

/// Largest |x|, |y| or range accepted, cm: 400 km, the position envelope of
/// the fixed-point filters.
pub const MAX_POSITION_CM: u32 = 40_000_000;
/// Lowest pressure altitude accepted, ft (Mode C, ICAO Annex 10 Vol. IV).
pub const MIN_ALTITUDE_FT: i32 = -1_000;
/// Highest pressure altitude accepted, ft (Mode C).
pub const MAX_ALTITUDE_FT: i32 = 126_700;

use field::{cartesian, end, header, health, polar, scan, track};
