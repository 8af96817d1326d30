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

/// Why bytes are not a valid frame or message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum WireError {
    /// Fewer bytes than the header says (or than a header); from the
    /// decoder: a frame cut short (the line went idle, or another frame's
    /// header starts inside it).
    Truncated,
    /// The first two bytes are not [`SYNC`].
    BadSync,
    /// The type byte names no message type.
    UnknownType,
    /// The length byte is not the type's length.
    BadLength,
    /// The CRC does not match.
    Checksum,
    /// A field holds a value the format does not allow (reserved bits set,
    /// an unknown status or advisory code, a value given for an absent
    /// field).
    BadField,
    /// A measurement outside the physical envelope (see the module docs).
    OutOfEnvelope,
    /// The output buffer is too short for the frame.
    BufferTooShort,
}

impl core::fmt::Display for WireError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            WireError::Truncated => "frame truncated",
            WireError::BadSync => "no sync bytes",
            WireError::UnknownType => "unknown message type",
            WireError::BadLength => "length does not match the message type",
            WireError::Checksum => "CRC mismatch",
            WireError::BadField => "field value not allowed",
            WireError::OutOfEnvelope => "measurement outside the physical envelope",
            WireError::BufferTooShort => "output buffer too short",
        })
    }
}

impl core::error::Error for WireError {}

/// Why a measurement cannot enter the tracker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ConversionError {
    /// |x| or |y| beyond [`MAX_POSITION_CM`].
    PositionOutOfRange,
    /// Range beyond [`MAX_POSITION_CM`].
    RangeOutOfRange,
    /// Altitude outside [`MIN_ALTITUDE_FT`] ..= [`MAX_ALTITUDE_FT`].
    AltitudeOutOfRange,
    /// A value (on the host side: NaN or infinite) that the number type
    /// cannot hold.
    NotRepresentable,
}

impl core::fmt::Display for ConversionError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            ConversionError::PositionOutOfRange => "position beyond 400 km",
            ConversionError::RangeOutOfRange => "range beyond 400 km",
            ConversionError::AltitudeOutOfRange => "altitude outside -1000..126700 ft",
            ConversionError::NotRepresentable => "value not representable",
        })
    }
}

impl core::error::Error for ConversionError {}

// ---------------------------------------------------------------------------
// CRC-32C
// ---------------------------------------------------------------------------

/// CRC-32C's polynomial 0x1EDC6F41, bit-reversed (the CRC is computed
/// least significant bit first).
const CRC32C_POLY_REFLECTED: u32 = 0x82F6_3B78;
/// Initial value (and final XOR) of CRC-32C.
pub const CRC_INIT: u32 = 0xFFFF_FFFF;

// Evaluated at compile time only: an index out of range or an overflow
// would fail the build, not the firmware.
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
const fn crc_table() -> [u32; 256] {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut crc = i as u32;
        let mut bit = 0;
        while bit < 8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ CRC32C_POLY_REFLECTED
            } else {
                crc >> 1
            };
            bit += 1;
        }
        table[i] = crc;
        i += 1;
    }
    table
}

/// 1 KiB of flash buys one table lookup per byte instead of eight shifts
/// in the receive interrupt.
static CRC_TABLE: [u32; 256] = crc_table();

/// Continues a CRC-32C over `data` from the running register `crc` (start
/// from [`CRC_INIT`]; the final value is `!crc`, see [`crc32c`]).
pub fn crc32c_update(mut crc: u32, data: &[u8]) -> u32 {
    for &b in data {
        // The index is a u8: always inside the 256-entry table.
        let index = usize::from((crc as u8) ^ b);
        crc = (crc >> 8) ^ CRC_TABLE.get(index).copied().unwrap_or(0);
    }
    crc
}

/// CRC-32C (CRC-32/ISCSI: reflected poly 0x82F63B78, init and final XOR
/// 0xFFFFFFFF) of `data`; 0xE3069283 for `b"123456789"`.
pub fn crc32c(data: &[u8]) -> u32 {
    !crc32c_update(CRC_INIT, data)
}

// ---------------------------------------------------------------------------
// Field tables
// ---------------------------------------------------------------------------

/// A value with a fixed big-endian encoding: an integer, or a list of
/// counters ([`ScanCounts`], ...).
pub trait WireValue: Copy {
    /// Bytes on the wire.
    const WIDTH: usize;
    /// Reads the value from `bytes` (exactly `WIDTH` of them; a shorter
    /// slice reads as zeros where bytes are missing). Never panics.
    fn read(bytes: &[u8]) -> Self;
    /// Writes the value into `bytes` (as many of its bytes as fit).
    fn write(self, bytes: &mut [u8]);
}

macro_rules! wire_int {
    ($($t:ty),*) => {$(
        impl WireValue for $t {
            const WIDTH: usize = core::mem::size_of::<$t>();
            fn read(bytes: &[u8]) -> Self {
                let mut be = [0u8; core::mem::size_of::<$t>()];
                // Element by element: `copy_from_slice` would keep a
                // length-check panic path.
                for (b, src) in be.iter_mut().zip(bytes) {
                    *b = *src;
                }
                <$t>::from_be_bytes(be)
            }
            fn write(self, bytes: &mut [u8]) {
                for (dst, b) in bytes.iter_mut().zip(self.to_be_bytes()) {
                    *dst = b;
                }
            }
        }
    )*};
}
wire_int!(u8, u16, i16, u32, i32);

/// A named field of a layout: its offset and, in the type, its encoding
/// (smoltcp's `mod field`, with the width checked by the type).
#[derive(Debug)]
pub struct Field<T> {
    start: usize,
    _value: PhantomData<fn() -> T>,
}

impl<T> Clone for Field<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Field<T> {}

impl<T: WireValue> Field<T> {
    /// The field at `start`.
    pub const fn at(start: usize) -> Self {
        Field {
            start,
            _value: PhantomData,
        }
    }
    /// First byte.
    pub const fn start(self) -> usize {
        self.start
    }
    /// One past the last byte: where the next field starts.
    pub const fn end(self) -> usize {
        self.start.saturating_add(T::WIDTH)
    }
    /// Reads the field of `bytes` (0 for bytes beyond the end). Never
    /// panics.
    pub fn get(self, bytes: &[u8]) -> T {
        T::read(bytes.get(self.start..).unwrap_or(&[]))
    }
    /// Writes the field into `bytes` (the part that fits). Never panics.
    pub fn set(self, bytes: &mut [u8], value: T) {
        if let Some(dst) = bytes.get_mut(self.start..) {
            value.write(dst);
        }
    }
}

/// Declares a layout: each field's offset is the end of the one before,
/// `LEN` is the end of the last, and `FIELDS` lists them (name, offset,
/// width, doc) for the documentation (`frames layout`).
macro_rules! layout {
    (
        $(#[$meta:meta])*
        pub mod $name:ident { $( $(#[doc = $doc:literal])* $field:ident: $t:ty, )* }
    ) => {
        $(#[$meta])*
        pub mod $name {
            #[allow(unused_imports)]
            use super::super::*;
            layout!(@fields 0usize; $( $(#[doc = $doc])* $field: $t, )*);
            /// Every field: name, offset, width, what it holds.
            pub const FIELDS: &[FieldRow] = &[
                $( (stringify!($field), $field.start(), <$t as WireValue>::WIDTH, concat!($($doc),*)), )*
            ];
        }
    };
    (@fields $at:expr;) => {
        /// Bytes in the layout.
        pub const LEN: usize = $at;
    };
    (@fields $at:expr; $(#[doc = $doc:literal])* $field:ident: $t:ty, $($rest:tt)*) => {
        $(#[doc = $doc])*
        pub const $field: Field<$t> = Field::at($at);
        layout!(@fields $field.end(); $($rest)*);
    };
}

/// The layouts: the frame header and each message's payload (offsets within
/// the payload). See the module docs for the frame around them.
pub mod field {
    layout! {
        /// The frame header.
        pub mod header {
            /// [`SYNC`] as a big-endian u16.
            SYNC: u16,
            /// [`FrameKind`] byte.
            TYPE: u8,
            /// Payload length (must be the type's).
            LENGTH: u8,
            /// The sender's frame count, wrapping ([`Encoder`]).
            SEQUENCE: u16,
        }
    }
    layout! {
        /// Cartesian measurement (type `0x01`).
        pub mod cartesian {
            /// Sensor clock, ms (it may wrap; see [`crate::scan`]).
            TIME: u32,
            /// Sensor id.
            SENSOR: u8,
            /// Bit 0 altitude present, bit 1 Mode S address present, bit 2
            /// altitude in 25 ft steps (Mode S Q bit; only with bit 0); bits
            /// 3–7 must be 0.
            FLAGS: u8,
            /// cm.
            X: i32,
            /// cm.
            Y: i32,
            /// Pressure altitude, ft (0 when absent).
            ALTITUDE: i32,
            /// 24-bit Mode S address in the low bits (0 when absent; the
            /// high byte must be 0).
            ADDRESS: u32,
        }
    }
    layout! {
        /// Polar measurement (type `0x02`).
        pub mod polar {
            /// Sensor clock, ms.
            TIME: u32,
            /// Sensor id.
            SENSOR: u8,
            /// As in the Cartesian measurement.
            FLAGS: u8,
            /// cm.
            RANGE: u32,
            /// Binary angle, 65536 = 360°, clockwise from +y.
            AZIMUTH: u16,
            /// Pressure altitude, ft (0 when absent).
            ALTITUDE: i32,
            /// 24-bit Mode S address (as in the Cartesian measurement).
            ADDRESS: u32,
        }
    }
    layout! {
        /// End of input (type `0x03`): the sender's recording ends here (a
        /// replay's last frame; its sequence number also reveals frames
        /// lost just before it).
        pub mod end {
            /// The sensor's clock at the end, ms.
            TIME: u32,
        }
    }
    layout! {
        /// Track report (type `0x81`), one per confirmed track per scan.
        pub mod track {
            /// Scan time, ms (the sensor's clock).
            TIME: u32,
            /// Track id (never reused while the track lives).
            TRACK_ID: u32,
            /// 0 tentative, 1 confirmed, 2 coasting.
            STATUS: u8,
            /// 0 none, 1 proximate traffic, 2 traffic (TA), 3 resolution (RA).
            ADVISORY: u8,
            /// Bit 0 altitude valid, bit 1 range tau valid, bit 2 Mode S
            /// address valid; bits 3–7 must be 0.
            FLAGS: u8,
            /// TCAS sensitivity level 2–7, 0 = not assessed.
            SENSITIVITY: u8,
            /// cm, relative to the own aircraft.
            X: i32,
            /// cm.
            Y: i32,
            /// cm/s.
            VX: i32,
            /// cm/s.
            VY: i32,
            /// ft (0 when not valid).
            ALTITUDE: i32,
            /// ft/min (0 when not valid).
            VERTICAL_RATE: i16,
            /// 0.1 s (0 when not valid).
            RANGE_TAU: u16,
            /// The intruder's 24-bit Mode S address (0 when not valid).
            ADDRESS: u32,
            /// The RA in force when ADVISORY is 3 ([`RaCode`]), else 0.
            RA: u8,
        }
    }
    layout! {
        /// Scan summary (type `0x82`), one per scan.
        pub mod scan {
            /// Scan time, ms (the sensor's clock).
            TIME: u32,
            /// Since the previous scan, ms (0 for the first).
            INTERVAL: u32,
            /// The most severe advisory over all tracks (as in the track report).
            HIGHEST_ADVISORY: u8,
            /// The RA in force ([`RaCode`]); 0 without one.
            RA: u8,
            /// This scan's counts, u16 each, saturating.
            COUNTS: ScanCounts,
        }
    }
    layout! {
        /// Health (type `0x84`), one per scan: every lifetime counter of
        /// the receiving and scanning side, u32 each, saturating.
        pub mod health {
            /// Scan time, ms (the sensor's clock).
            TIME: u32,
            /// The decoder's counters ([`DecoderStats`]).
            DECODER: DecoderStats,
            /// The receive side's ([`IntakeCounters`]).
            INTAKE: IntakeCounters,
            /// The scan loop's ([`LoopCounters`]).
            SCAN: LoopCounters,
        }
    }
}

use field::{cartesian, end, header, health, polar, scan, track};

/// A field of a layout, for the documentation: name, offset, width, what it
/// holds.
pub type FieldRow = (&'static str, usize, usize, &'static str);

/// Every layout: (name, type byte if a message, fields), for the
/// documentation (`frames layout`).
pub const LAYOUTS: [(&str, Option<FrameKind>, &[FieldRow]); 7] = [
    ("frame header", None, header::FIELDS),
    (
        "Cartesian measurement",
        Some(FrameKind::MeasurementCartesian),
        cartesian::FIELDS,
    ),
    (
        "polar measurement",
        Some(FrameKind::MeasurementPolar),
        polar::FIELDS,
    ),
    ("end of input", Some(FrameKind::EndOfInput), end::FIELDS),
    ("track report", Some(FrameKind::TrackReport), track::FIELDS),
    ("scan summary", Some(FrameKind::ScanSummary), scan::FIELDS),
    ("health", Some(FrameKind::Health), health::FIELDS),
];

// ---------------------------------------------------------------------------
// Counter lists
// ---------------------------------------------------------------------------

/// Declares a list of counters once: the struct, its names and labels in
/// wire order, the wire encoding ([`WireValue`]), the log line
/// (`defmt::Format`, non-zero counters) and the text ([`core::fmt::Display`],
/// every counter), so that none of them can drift from the others.
macro_rules! counter_list {
    (
        $(#[$meta:meta])*
        pub struct $name:ident: $int:ty {
            $( $(#[doc = $doc:literal])* $field:ident => $label:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
        pub struct $name {
            $( $(#[doc = $doc])* pub $field: $int, )+
        }

        impl $name {
            /// Number of counters.
            pub const LEN: usize = [$(stringify!($field)),+].len();
            /// Field names in wire order (CSV column names).
            pub const NAMES: [&'static str; Self::LEN] = [$(stringify!($field)),+];
            /// What each counter counts, in wire order (log and text).
            pub const LABELS: [&'static str; Self::LEN] = [$($label),+];

            /// All zero.
            pub const fn new() -> Self {
                Self::from_values([0; Self::LEN])
            }
            /// The values in wire order.
            pub const fn values(&self) -> [$int; Self::LEN] {
                [$(self.$field),+]
            }
            /// From values in wire order.
            pub const fn from_values(values: [$int; Self::LEN]) -> Self {
                let [$($field),+] = values;
                Self { $($field),+ }
            }
            /// The counters added one by one, saturating.
            pub fn saturating_add(self, other: Self) -> Self {
                let mut sum = self.values();
                for (s, o) in sum.iter_mut().zip(other.values()) {
                    *s = s.saturating_add(o);
                }
                Self::from_values(sum)
            }
        }

        impl WireValue for $name {
            const WIDTH: usize = Self::LEN.saturating_mul(<$int as WireValue>::WIDTH);
            fn read(bytes: &[u8]) -> Self {
                let mut values = [0; Self::LEN];
                for (v, chunk) in values
                    .iter_mut()
                    .zip(bytes.chunks(<$int as WireValue>::WIDTH))
                {
                    *v = <$int as WireValue>::read(chunk);
                }
                Self::from_values(values)
            }
            fn write(self, bytes: &mut [u8]) {
                for (v, chunk) in self
                    .values()
                    .into_iter()
                    .zip(bytes.chunks_mut(<$int as WireValue>::WIDTH))
                {
                    v.write(chunk);
                }
            }
        }

        impl core::fmt::Display for $name {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                for (i, (value, label)) in self.values().into_iter().zip(Self::LABELS).enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{value} {label}")?;
                }
                Ok(())
            }
        }

        #[cfg(feature = "defmt")]
        impl defmt::Format for $name {
            fn format(&self, f: defmt::Formatter) {
                let mut first = true;
                for (value, label) in self.values().into_iter().zip(Self::LABELS) {
                    if value == 0 {
                        continue;
                    }
                    if !first {
                        defmt::write!(f, ", ");
                    }
                    defmt::write!(f, "{} {=str}", value, label);
                    first = false;
                }
                if first {
                    defmt::write!(f, "all zero");
                }
            }
        }
    };
}

counter_list! {
    /// What the [`Decoder`] has seen over its lifetime (saturating).
    ///
    /// Invariants (`host-tests/tests/it/wire/codec.rs`): `bytes = frame_bytes +
    /// bytes_skipped + held`, and `frames = accepted + crc_errors +
    /// unknown_type + bad_length + bad_field + out_of_envelope + truncated`.
    pub struct DecoderStats: u32 {
        /// Bytes pushed.
        bytes => "bytes",
        /// Bytes of the accepted frames.
        frame_bytes => "frame bytes",
        /// Bytes discarded: not part of any accepted frame (garbage, the
        /// bytes of refused candidates).
        bytes_skipped => "bytes skipped",
        /// Frame candidates decided: accepted or refused for one reason.
        frames => "frames",
        /// Valid frames returned.
        accepted => "accepted",
        /// Refused: the CRC did not match.
        crc_errors => "CRC errors",
        /// Refused: a message type the format does not define.
        unknown_type => "unknown type",
        /// Refused: a length byte other than the type's fixed payload length.
        bad_length => "bad length",
        /// Valid CRC, a value the format does not allow.
        bad_field => "bad field",
        /// Valid CRC, a measurement outside the envelope.
        out_of_envelope => "out of envelope",
        /// Cut short: the line went idle, or another frame started inside.
        truncated => "truncated",
        /// Frames missing from the sender's sequence numbers.
        frames_lost => "frames lost",
        /// Accepted frames whose sequence number went back or repeated
        /// (a sender restart or a replayed frame); the count restarts there.
        out_of_sequence => "out of sequence",
    }
}

counter_list! {
    /// The receive side's own counters ([`crate::scan::Intake`]): what
    /// became of the accepted frames (saturating).
    ///
    /// Invariant: `decoder.accepted = measurements + not_measurement`.
    pub struct IntakeCounters: u32 {
        /// Measurement frames accepted (queued or lost to a full queue).
        measurements => "measurements received",
        /// Measurements lost because the queue was full.
        queue_full => "lost, queue full",
        /// Accepted frames of a type the receiver does not take as input.
        not_measurement => "not measurements",
        /// Bytes the UART lost before the decoder saw them (hardware
        /// overrun).
        rx_overruns => "UART overruns",
    }
}

counter_list! {
    /// The scan loop's lifetime counters ([`crate::scan::ScanLoop`]),
    /// saturating.
    ///
    /// Every measurement taken from the queue ends in exactly one of `used`,
    /// `late`, `out_of_window`, `over_capacity`, `invalid` (or is still
    /// held for the next scan): `intake.measurements = intake.queue_full +
    /// those + held` ([`crate::scan::ScanLoop::held`]).
    pub struct LoopCounters: u32 {
        /// Scans run.
        scans => "scans",
        /// The scan clock locked onto the sensor's clock (the first
        /// measurement).
        clock_locks => "clock locks",
        /// ... and locked again after a jump beyond the window.
        clock_relocks => "clock re-locks",
        /// Measurements that entered a tracker scan.
        used => "used",
        /// Timestamped for a scan already run (within the late window).
        late => "late",
        /// Timestamped outside the clock's window, and not confirmed as a
        /// new time base by the next measurement.
        out_of_window => "out of time window",
        /// Beyond a scan's capacity (the lowest priority ones).
        over_capacity => "over capacity",
        /// Not representable in the tracker's number type.
        invalid => "not representable",
        /// Tentative tracks started.
        tracks_started => "tracks started",
        /// Tracks confirmed.
        tracks_confirmed => "tracks confirmed",
        /// Tracks deleted.
        tracks_deleted => "tracks deleted",
        /// Tracks restarted: last updated more than the filters' longest
        /// interval ago ([`crate::track::ScanReport::restarted`]).
        tracks_restarted => "tracks restarted",
        /// Candidate tracks refused because the table was full.
        refused_table_full => "refused, table full",
        /// Track report frames emitted.
        track_reports => "track reports",
        /// Confirmed tracks whose threat assessment failed (or the
        /// cycle's sensitivity selection or resolution).
        assessment_errors => "assessment errors",
        /// RA threats beyond the [`crate::scan::MAX_RA_THREATS`] resolved
        /// together (the latest by modified tau are left out).
        ra_threats_over_capacity => "RA threats over capacity",
        /// Replies the intruder's range or altitude tracker refused.
        intruder_tracker_errors => "intruder tracker errors",
    }
}

counter_list! {
    /// One scan's counts (the scan summary, type `0x82`), u16 saturating.
    ///
    /// The measurements taken for the scan: `used + late + out_of_window +
    /// over_capacity + invalid`; the used ones, by what the tracker did with
    /// them: `used = updated + started + not_assigned + outside_gates +
    /// rejected + refused_table_full`.
    pub struct ScanCounts: u16 {
        /// Entered the tracker scan.
        used => "used",
        /// Timestamped for a scan already run.
        late => "late",
        /// Outside the clock's window.
        out_of_window => "out of time window",
        /// Beyond the scan's capacity.
        over_capacity => "over capacity",
        /// Not representable in the number type.
        invalid => "not representable",
        /// Updated a track.
        updated => "updated",
        /// Started a (tentative) track with a point of the previous scan.
        started => "started",
        /// Inside a gate, but the assignment gave the track another one.
        not_assigned => "not assigned",
        /// Inside no gate, and not paired (kept as a first point).
        outside_gates => "outside gates",
        /// Refused by the tracker (not finite, the filter refused it, or the
        /// scan came too soon after the previous one).
        rejected => "rejected",
        /// Would have started a track; the table was full.
        refused_table_full => "refused, table full",
        /// Tracks predicted to the scan time.
        predicted => "predicted",
        /// (track, measurement) pairs inside a gate.
        gated_pairs => "gated pairs",
        /// Tracks without a measurement this scan.
        coasted => "coasted",
        /// Tracks confirmed in this scan.
        confirmed => "confirmed",
        /// Tracks deleted in this scan.
        deleted => "deleted",
        /// Tracks restarted in this scan (last updated more than the
        /// filters' longest interval ago; not in `deleted`).
        restarted => "restarted",
        /// Live tracks after the scan.
        tracks => "tracks",
        /// Confirmed (or coasting) tracks after the scan.
        confirmed_tracks => "confirmed tracks",
    }
}

// ---------------------------------------------------------------------------
// Frame: the byte view
// ---------------------------------------------------------------------------

/// The message types and their fixed payload lengths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrameKind {
    /// A measurement in Cartesian coordinates (sensor to tracker).
    MeasurementCartesian = 0x01,
    /// A measurement in range and azimuth (sensor to tracker).
    MeasurementPolar = 0x02,
    /// The end of a recording (sensor to tracker).
    EndOfInput = 0x03,
    /// One track's report (tracker out).
    TrackReport = 0x81,
    /// One scan's summary and counts (tracker out).
    ScanSummary = 0x82,
    /// The lifetime counters (tracker out).
    Health = 0x84,
}

impl FrameKind {
    /// Every kind.
    pub const ALL: [FrameKind; 6] = [
        FrameKind::MeasurementCartesian,
        FrameKind::MeasurementPolar,
        FrameKind::EndOfInput,
        FrameKind::TrackReport,
        FrameKind::ScanSummary,
        FrameKind::Health,
    ];

    /// The kind with this type byte.
    pub const fn from_byte(b: u8) -> Option<Self> {
        match b {
            0x01 => Some(FrameKind::MeasurementCartesian),
            0x02 => Some(FrameKind::MeasurementPolar),
            0x03 => Some(FrameKind::EndOfInput),
            0x81 => Some(FrameKind::TrackReport),
            0x82 => Some(FrameKind::ScanSummary),
            0x84 => Some(FrameKind::Health),
            _ => None,
        }
    }

    /// The type byte.
    pub const fn byte(self) -> u8 {
        self as u8
    }

    /// The payload length every frame of this kind has (from its layout).
    pub const fn payload_len(self) -> usize {
        match self {
            FrameKind::MeasurementCartesian => cartesian::LEN,
            FrameKind::MeasurementPolar => polar::LEN,
            FrameKind::EndOfInput => end::LEN,
            FrameKind::TrackReport => track::LEN,
            FrameKind::ScanSummary => scan::LEN,
            FrameKind::Health => health::LEN,
        }
    }

    /// Header + payload + CRC.
    pub const fn frame_len(self) -> usize {
        frame_len_for(self.payload_len())
    }

    // Compile time only (MAX_PAYLOAD_LEN, MIN_FRAME_LEN): see `crc_table`.
    /// The longest (or shortest) payload of any kind.
    #[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
    const fn payload_bound(longest: bool) -> usize {
        let mut bound = Self::ALL[0].payload_len();
        let mut i = 1;
        while i < Self::ALL.len() {
            let len = Self::ALL[i].payload_len();
            if (longest && len > bound) || (!longest && len < bound) {
                bound = len;
            }
            i += 1;
        }
        bound
    }
}

// The length byte holds every payload length.
const _: () = assert!(MAX_PAYLOAD_LEN <= u8::MAX as usize);

/// A frame in a byte buffer (smoltcp-style view: the accessors read and
/// write the buffer in place).
///
/// On a buffer that did not pass [`Frame::new_checked`], the accessors do not
/// panic: a field beyond the end of the buffer reads as 0 and the payload as
/// the bytes that are there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> Frame<T> {
    /// Wraps a buffer without checking it.
    pub const fn new_unchecked(buffer: T) -> Self {
        Frame { buffer }
    }

    /// Wraps a buffer that starts with a structurally valid frame: sync
    /// bytes, a known type, that type's length, and enough bytes for the
    /// whole frame (extra bytes after it are allowed: see
    /// [`Frame::frame_len`]). The CRC is checked by [`Frame::verify_crc`] and
    /// [`Message::parse`].
    pub fn new_checked(buffer: T) -> Result<Self, WireError> {
        let frame = Frame::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// The structural checks of [`Frame::new_checked`].
    pub fn check_len(&self) -> Result<(), WireError> {
        let bytes = self.buffer.as_ref();
        if bytes.len() < HEADER_LEN {
            return Err(WireError::Truncated);
        }
        if header::SYNC.get(bytes).to_be_bytes() != SYNC {
            return Err(WireError::BadSync);
        }
        let kind = self.kind().ok_or(WireError::UnknownType)?;
        if self.payload_len() != kind.payload_len() {
            return Err(WireError::BadLength);
        }
        if bytes.len() < self.frame_len() {
            return Err(WireError::Truncated);
        }
        Ok(())
    }

    /// The type byte.
    pub fn type_byte(&self) -> u8 {
        header::TYPE.get(self.buffer.as_ref())
    }

    /// The message type, if the type byte names one.
    pub fn kind(&self) -> Option<FrameKind> {
        FrameKind::from_byte(self.type_byte())
    }

    /// The length byte.
    pub fn payload_len(&self) -> usize {
        usize::from(header::LENGTH.get(self.buffer.as_ref()))
    }

    /// The sender's sequence number.
    pub fn sequence(&self) -> u16 {
        header::SEQUENCE.get(self.buffer.as_ref())
    }

    /// Header + payload + CRC, from the length byte.
    pub fn frame_len(&self) -> usize {
        frame_len_for(self.payload_len())
    }

    fn payload_end(&self) -> usize {
        HEADER_LEN
            .saturating_add(self.payload_len())
            .min(self.buffer.as_ref().len())
    }

    /// The payload (as much of it as the buffer holds).
    pub fn payload(&self) -> &[u8] {
        let end = self.payload_end();
        self.buffer.as_ref().get(HEADER_LEN..end).unwrap_or(&[])
    }

    /// The CRC stored in the frame.
    pub fn crc(&self) -> u32 {
        let at = HEADER_LEN.saturating_add(self.payload_len());
        Field::<u32>::at(at).get(self.buffer.as_ref())
    }

    /// The CRC computed over type, length, sequence number and payload.
    pub fn compute_crc(&self) -> u32 {
        let end = self.payload_end();
        crc32c(
            self.buffer
                .as_ref()
                .get(header::TYPE.start()..end)
                .unwrap_or(&[]),
        )
    }

    /// Whether the stored CRC matches (false on a truncated buffer).
    pub fn verify_crc(&self) -> bool {
        self.buffer.as_ref().len() >= self.frame_len() && self.crc() == self.compute_crc()
    }

    /// Gives the buffer back.
    pub fn into_inner(self) -> T {
        self.buffer
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> Frame<T> {
    /// Writes sync, type, length and sequence number.
    pub fn set_header(&mut self, kind: FrameKind, sequence: u16) {
        let bytes = self.buffer.as_mut();
        header::SYNC.set(bytes, u16::from_be_bytes(SYNC));
        header::TYPE.set(bytes, kind.byte());
        // Every payload length is ≤ u8::MAX (asserted above).
        header::LENGTH.set(bytes, u8::try_from(kind.payload_len()).unwrap_or(u8::MAX));
        header::SEQUENCE.set(bytes, sequence);
    }

    /// The payload, for writing (as much of it as the buffer holds).
    pub fn payload_mut(&mut self) -> &mut [u8] {
        let end = self.payload_end();
        self.buffer
            .as_mut()
            .get_mut(HEADER_LEN..end)
            .unwrap_or(&mut [])
    }

    /// Computes and stores the CRC (after the header and payload are
    /// written).
    pub fn fill_crc(&mut self) {
        let crc = self.compute_crc();
        let at = HEADER_LEN.saturating_add(self.payload_len());
        Field::<u32>::at(at).set(self.buffer.as_mut(), crc);
    }
}

// ---------------------------------------------------------------------------
// Messages
// ---------------------------------------------------------------------------

/// Where a sensor saw the target, as sent on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MeasuredPosition {
    /// Position in the tracking plane, cm.
    Cartesian {
        /// x, cm.
        x_cm: i32,
        /// y, cm.
        y_cm: i32,
    },
    /// Range (cm) and azimuth (binary angle, 65536 per turn, clockwise from
    /// +y) from the own aircraft.
    Polar {
        /// Slant range, cm.
        range_cm: u32,
        /// Azimuth, binary angle (65536 per turn, clockwise from +y).
        azimuth_bam: u16,
    },
}

/// One measurement as a sensor reports it (frame types 0x01 and 0x02).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MeasurementReport {
    /// Sensor clock, ms.
    pub time_ms: u32,
    /// The sender's sensor number, carried through unchanged.
    pub sensor: u8,
    /// Where the sensor saw the target.
    pub position: MeasuredPosition,
    /// Reported pressure altitude, ft; `None` for a non-reporting target.
    pub altitude_ft: Option<i32>,
    /// The altitude came in 25 ft steps (a Mode S reply with the Q bit);
    /// false for 100 ft (Gillham, Mode C) steps and without altitude.
    pub altitude_25ft: bool,
    /// The replying transponder's Mode S address; `None` for a Mode C (or
    /// Mode A) reply, which carries none.
    pub address: Option<ModeSAddress>,
}

/// A 24-bit Mode S (ICAO) aircraft address (ICAO Annex 10 Vol. III; DO-185B
/// associates Mode S replies by it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ModeSAddress(u32);

impl ModeSAddress {
    /// The address, if it fits 24 bits.
    pub const fn new(address: u32) -> Option<Self> {
        if address <= 0x00FF_FFFF {
            Some(ModeSAddress(address))
        } else {
            None
        }
    }

    /// The 24-bit address.
    pub const fn get(self) -> u32 {
        self.0
    }
}

/// A resolution advisory as reported: sense and strength (the RA byte of
/// the track report and scan summary: bits 0–1 sense, 1 up, 2 down; bits
/// 2–3 strength, 0 preventive, 1 level-off, 2 positive, 3 increase; 0 for
/// none; in the scan summary bit 7 is clear of conflict).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RaCode {
    /// Up or down (bits 0–1).
    pub sense: RaSense,
    /// Preventive, level-off, positive or increase (bits 2–3).
    pub strength: RaStrength,
}

const RA_CLEAR_OF_CONFLICT: u8 = 0x80;

impl RaCode {
    /// The byte (never 0).
    pub const fn byte(self) -> u8 {
        let sense = match self.sense {
            RaSense::Up => 1,
            RaSense::Down => 2,
        };
        let strength = match self.strength {
            RaStrength::Preventive => 0,
            RaStrength::LevelOff => 1,
            RaStrength::Positive => 2,
            RaStrength::Increase => 3,
        };
        sense | (strength << 2)
    }

    /// From the byte's low bits: `Ok(None)` for 0; other bits refused.
    fn from_byte(b: u8) -> Result<Option<Self>, WireError> {
        let sense = match b & 0x03 {
            0 if b == 0 => return Ok(None),
            1 => RaSense::Up,
            2 => RaSense::Down,
            _ => return Err(WireError::BadField),
        };
        let strength = match (b >> 2) & 0x03 {
            0 => RaStrength::Preventive,
            1 => RaStrength::LevelOff,
            2 => RaStrength::Positive,
            _ => RaStrength::Increase,
        };
        if b & 0xF0 != 0 {
            return Err(WireError::BadField);
        }
        Ok(Some(RaCode { sense, strength }))
    }

    /// A name for logs: e.g. "climb", "don't descend", "level-off (up)".
    pub const fn name(self) -> &'static str {
        match (self.sense, self.strength) {
            (RaSense::Up, RaStrength::Preventive) => "don't descend",
            (RaSense::Down, RaStrength::Preventive) => "don't climb",
            (RaSense::Up, RaStrength::LevelOff) => "level off (up)",
            (RaSense::Down, RaStrength::LevelOff) => "level off (down)",
            (RaSense::Up, RaStrength::Positive) => "climb",
            (RaSense::Down, RaStrength::Positive) => "descend",
            (RaSense::Up, RaStrength::Increase) => "increase climb",
            (RaSense::Down, RaStrength::Increase) => "increase descent",
        }
    }
}

fn ra_byte(ra: Option<RaCode>) -> u8 {
    ra.map_or(0, RaCode::byte)
}

/// Radians per binary-angle step: 2π / 65536.
const RAD_PER_BAM: f64 = core::f64::consts::TAU / 65536.0;

fn cm_from_m(v: f64) -> Option<i64> {
    if !v.is_finite() {
        return None;
    }
    let cm = libm::round(v * 100.0);
    // Beyond ±2⁶² cm the i64 cast would clamp; far outside the envelope
    // anyway, so any out-of-range marker will do.
    Some(if cm.abs() > 4.0e18 {
        i64::MAX
    } else {
        cm as i64
    })
}

fn checked_altitude(altitude_ft: Option<f64>) -> Result<Option<i32>, ConversionError> {
    match altitude_ft {
        None => Ok(None),
        Some(a) if !a.is_finite() => Err(ConversionError::NotRepresentable),
        Some(a) => {
            let ft = libm::round(a);
            if ft < MIN_ALTITUDE_FT as f64 || ft > MAX_ALTITUDE_FT as f64 {
                Err(ConversionError::AltitudeOutOfRange)
            } else {
                Ok(Some(ft as i32))
            }
        }
    }
}

impl MeasurementReport {
    /// A Cartesian report from metres (rounded to cm) and an optional
    /// altitude in feet (rounded to 1 ft), checked against the envelope.
    pub fn cartesian_from_metres(
        time_ms: u32,
        sensor: u8,
        x_m: f64,
        y_m: f64,
        altitude_ft: Option<f64>,
    ) -> Result<Self, ConversionError> {
        let limit = i64::from(MAX_POSITION_CM);
        let (Some(x), Some(y)) = (cm_from_m(x_m), cm_from_m(y_m)) else {
            return Err(ConversionError::NotRepresentable);
        };
        if x.abs() > limit || y.abs() > limit {
            return Err(ConversionError::PositionOutOfRange);
        }
        Ok(MeasurementReport {
            time_ms,
            sensor,
            // |x|, |y| ≤ 4·10⁷ < 2³¹.
            position: MeasuredPosition::Cartesian {
                x_cm: x as i32,
                y_cm: y as i32,
            },
            altitude_ft: checked_altitude(altitude_ft)?,
            altitude_25ft: false,
            address: None,
        })
    }

    /// A polar report from a range in metres (rounded to cm) and an azimuth
    /// in radians clockwise from +y (any value: reduced to one turn and
    /// rounded to the nearest binary angle).
    pub fn polar_from_metres(
        time_ms: u32,
        sensor: u8,
        range_m: f64,
        azimuth_rad: f64,
        altitude_ft: Option<f64>,
    ) -> Result<Self, ConversionError> {
        let Some(range) = cm_from_m(range_m) else {
            return Err(ConversionError::NotRepresentable);
        };
        if !azimuth_rad.is_finite() {
            return Err(ConversionError::NotRepresentable);
        }
        if !(0..=i64::from(MAX_POSITION_CM)).contains(&range) {
            return Err(ConversionError::RangeOutOfRange);
        }
        let turns = azimuth_rad / core::f64::consts::TAU;
        let fraction = turns - libm::floor(turns);
        // fraction ∈ [0, 1]; 65536 (a rounding up of the last step) wraps to 0.
        let bam = (libm::round(fraction * 65536.0) as u32 & 0xFFFF) as u16;
        Ok(MeasurementReport {
            time_ms,
            sensor,
            position: MeasuredPosition::Polar {
                range_cm: range as u32,
                azimuth_bam: bam,
            },
            altitude_ft: checked_altitude(altitude_ft)?,
            altitude_25ft: false,
            address: None,
        })
    }

    /// The same report as a Mode S reply from `address`, its altitude (if
    /// any) in 25 ft steps when `altitude_25ft`.
    pub fn with_mode_s(self, address: ModeSAddress, altitude_25ft: bool) -> Self {
        MeasurementReport {
            address: Some(address),
            altitude_25ft: altitude_25ft && self.altitude_ft.is_some(),
            ..self
        }
    }

    /// The envelope check of a received measurement: position or range
    /// within 400 km, altitude within Mode C's range.
    pub fn check_envelope(&self) -> Result<(), ConversionError> {
        match self.position {
            MeasuredPosition::Cartesian { x_cm, y_cm } => {
                if x_cm.unsigned_abs() > MAX_POSITION_CM || y_cm.unsigned_abs() > MAX_POSITION_CM {
                    return Err(ConversionError::PositionOutOfRange);
                }
            }
            MeasuredPosition::Polar { range_cm, .. } => {
                if range_cm > MAX_POSITION_CM {
                    return Err(ConversionError::RangeOutOfRange);
                }
            }
        }
        match self.altitude_ft {
            Some(a) if !(MIN_ALTITUDE_FT..=MAX_ALTITUDE_FT).contains(&a) => {
                Err(ConversionError::AltitudeOutOfRange)
            }
            _ => Ok(()),
        }
    }

    /// The measurement for the tracker, in metres and radians in the number
    /// type `S`: the checked edge of the input path.
    pub fn position<S: Scalar>(&self) -> Result<Measurement<S>, ConversionError> {
        self.check_envelope()?;
        let s = |v: f64| S::try_from_f64(v).map_err(|_| ConversionError::NotRepresentable);
        match self.position {
            MeasuredPosition::Cartesian { x_cm, y_cm } => Ok(Measurement::Cartesian {
                x: s(f64::from(x_cm) / 100.0)?,
                y: s(f64::from(y_cm) / 100.0)?,
            }),
            MeasuredPosition::Polar {
                range_cm,
                azimuth_bam,
            } => Ok(Measurement::Polar {
                range: s(f64::from(range_cm) / 100.0)?,
                azimuth: s(f64::from(azimuth_bam) * RAD_PER_BAM)?,
            }),
        }
    }

    /// The reported altitude in feet in the number type `S` (`None` when not
    /// reported), checked against the Mode C range.
    pub fn altitude<S: Scalar>(&self) -> Result<Option<S>, ConversionError> {
        match self.altitude_ft {
            None => Ok(None),
            Some(a) if !(MIN_ALTITUDE_FT..=MAX_ALTITUDE_FT).contains(&a) => {
                Err(ConversionError::AltitudeOutOfRange)
            }
            Some(a) => S::try_from_f64(f64::from(a))
                .map(Some)
                .map_err(|_| ConversionError::NotRepresentable),
        }
    }

    fn kind(&self) -> FrameKind {
        match self.position {
            MeasuredPosition::Cartesian { .. } => FrameKind::MeasurementCartesian,
            MeasuredPosition::Polar { .. } => FrameKind::MeasurementPolar,
        }
    }
}

/// One confirmed track at the end of a scan, with its threat assessment
/// (frame type 0x81).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TrackReport {
    /// Scan time, ms (the sensor's clock).
    pub time_ms: u32,
    /// The track table's identifier of the track.
    pub track_id: u32,
    /// Tentative, confirmed or coasting.
    pub status: TrackStatus,
    /// The advisory level issued against this intruder.
    pub advisory: Advisory,
    /// `None` when the track was not assessed (the assessment failed).
    pub sensitivity: Option<SensitivityLevel>,
    /// Position relative to the own aircraft, x, cm.
    pub x_cm: i32,
    /// Position relative to the own aircraft, y, cm.
    pub y_cm: i32,
    /// Velocity relative to the own aircraft, x, cm/s.
    pub vx_cm_per_s: i32,
    /// Velocity relative to the own aircraft, y, cm/s.
    pub vy_cm_per_s: i32,
    /// Tracked pressure altitude (ft) and vertical rate (ft/min); `None` for
    /// a target without altitude.
    pub altitude: Option<(i32, i16)>,
    /// Range tau, 0.1 s; `None` when diverging or not assessed.
    pub range_tau_ds: Option<u16>,
    /// The intruder's Mode S address; `None` for a Mode C intruder.
    pub address: Option<ModeSAddress>,
    /// The RA in force, when `advisory` is an RA against this intruder.
    pub ra: Option<RaCode>,
}

/// One scan (frame type 0x82): its time, interval, counts and the most
/// severe advisory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanSummary {
    /// Scan time, ms (the sensor's clock).
    pub time_ms: u32,
    /// Since the previous scan, ms (0 for the first).
    pub interval_ms: u32,
    /// The scan's measurement and track counts.
    pub counts: ScanCounts,
    /// The most severe advisory over all tracks.
    pub highest_advisory: Advisory,
    /// The RA in force.
    pub ra: Option<RaCode>,
    /// The last RA ended in this scan.
    pub clear_of_conflict: bool,
}

/// Every lifetime counter of the receiving and scanning side (frame type
/// 0x84), sent after each scan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Health {
    /// Scan time, ms (the sensor's clock).
    pub time_ms: u32,
    /// The frame decoder's counters.
    pub decoder: DecoderStats,
    /// The receive side's counters.
    pub intake: IntakeCounters,
    /// The scan loop's counters.
    pub scan: LoopCounters,
}

/// The end of a recording (frame type 0x03).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EndOfInput {
    /// The sensor's clock at the end, ms.
    pub time_ms: u32,
}

/// A decoded frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Message {
    /// A measurement, Cartesian or polar (types 0x01, 0x02).
    Measurement(MeasurementReport),
    /// The end of a recording (type 0x03).
    End(EndOfInput),
    /// One track's report (type 0x81).
    Track(TrackReport),
    /// One scan's summary (type 0x82).
    Scan(ScanSummary),
    /// The lifetime counters (type 0x84).
    Health(Health),
}

fn status_code(s: TrackStatus) -> u8 {
    match s {
        TrackStatus::Tentative => 0,
        TrackStatus::Confirmed => 1,
        TrackStatus::Coasting => 2,
    }
}

fn status_from_code(c: u8) -> Result<TrackStatus, WireError> {
    match c {
        0 => Ok(TrackStatus::Tentative),
        1 => Ok(TrackStatus::Confirmed),
        2 => Ok(TrackStatus::Coasting),
        _ => Err(WireError::BadField),
    }
}

/// 0 none, 1 proximate, 2 TA, 3 RA.
pub fn advisory_code(a: Advisory) -> u8 {
    match a {
        Advisory::None => 0,
        Advisory::ProximateTraffic => 1,
        Advisory::Traffic => 2,
        Advisory::Resolution => 3,
    }
}

fn advisory_from_code(c: u8) -> Result<Advisory, WireError> {
    match c {
        0 => Ok(Advisory::None),
        1 => Ok(Advisory::ProximateTraffic),
        2 => Ok(Advisory::Traffic),
        3 => Ok(Advisory::Resolution),
        _ => Err(WireError::BadField),
    }
}

fn level_from_code(c: u8) -> Result<Option<SensitivityLevel>, WireError> {
    Ok(Some(match c {
        0 => return Ok(None),
        2 => SensitivityLevel::Sl2,
        3 => SensitivityLevel::Sl3,
        4 => SensitivityLevel::Sl4,
        5 => SensitivityLevel::Sl5,
        6 => SensitivityLevel::Sl6,
        7 => SensitivityLevel::Sl7,
        _ => return Err(WireError::BadField),
    }))
}

const FLAG_ALTITUDE: u8 = 0x01;
const FLAG_TAU: u8 = 0x02;
/// Measurement: Mode S address present.
const FLAG_ADDRESS: u8 = 0x02;
/// Measurement: altitude in 25 ft steps.
const FLAG_25FT: u8 = 0x04;
/// Track report: Mode S address valid.
const FLAG_TRACK_ADDRESS: u8 = 0x04;

/// The altitude of a measurement payload: flag bit 0 and the field; a value
/// with the flag clear, or other flag bits, are refused.
fn parse_altitude(flags: u8, field: i32) -> Result<Option<i32>, WireError> {
    if flags & !(FLAG_ALTITUDE | FLAG_ADDRESS | FLAG_25FT) != 0 {
        return Err(WireError::BadField);
    }
    match flags & (FLAG_ALTITUDE | FLAG_25FT) {
        0 if field == 0 => Ok(None),
        FLAG_ALTITUDE => Ok(Some(field)),
        x if x == FLAG_ALTITUDE | FLAG_25FT => Ok(Some(field)),
        _ => Err(WireError::BadField),
    }
}

/// The address of a measurement payload (flag bit 1); an address with the
/// flag clear, or beyond 24 bits, is refused.
fn parse_address(flags: u8, field: u32) -> Result<Option<ModeSAddress>, WireError> {
    parse_flagged_address(flags & FLAG_ADDRESS != 0, field)
}

fn parse_flagged_address(present: bool, field: u32) -> Result<Option<ModeSAddress>, WireError> {
    match (present, ModeSAddress::new(field)) {
        (false, _) if field == 0 => Ok(None),
        (true, Some(a)) => Ok(Some(a)),
        _ => Err(WireError::BadField),
    }
}

fn measurement_flags(m: &MeasurementReport) -> u8 {
    let mut flags = 0;
    if m.altitude_ft.is_some() {
        flags |= FLAG_ALTITUDE;
        if m.altitude_25ft {
            flags |= FLAG_25FT;
        }
    }
    if m.address.is_some() {
        flags |= FLAG_ADDRESS;
    }
    flags
}

impl Message {
    /// Decodes a frame: structure ([`Frame::check_len`]), CRC, every field,
    /// then the envelope of a measurement.
    pub fn parse<T: AsRef<[u8]>>(frame: &Frame<T>) -> Result<Message, WireError> {
        frame.check_len()?;
        if !frame.verify_crc() {
            return Err(WireError::Checksum);
        }
        let p = frame.payload();
        let kind = frame.kind().ok_or(WireError::UnknownType)?;
        let message = match kind {
            FrameKind::MeasurementCartesian => Message::Measurement(MeasurementReport {
                time_ms: cartesian::TIME.get(p),
                sensor: cartesian::SENSOR.get(p),
                position: MeasuredPosition::Cartesian {
                    x_cm: cartesian::X.get(p),
                    y_cm: cartesian::Y.get(p),
                },
                altitude_ft: parse_altitude(cartesian::FLAGS.get(p), cartesian::ALTITUDE.get(p))?,
                altitude_25ft: cartesian::FLAGS.get(p) & FLAG_25FT != 0,
                address: parse_address(cartesian::FLAGS.get(p), cartesian::ADDRESS.get(p))?,
            }),
            FrameKind::MeasurementPolar => Message::Measurement(MeasurementReport {
                time_ms: polar::TIME.get(p),
                sensor: polar::SENSOR.get(p),
                position: MeasuredPosition::Polar {
                    range_cm: polar::RANGE.get(p),
                    azimuth_bam: polar::AZIMUTH.get(p),
                },
                altitude_ft: parse_altitude(polar::FLAGS.get(p), polar::ALTITUDE.get(p))?,
                altitude_25ft: polar::FLAGS.get(p) & FLAG_25FT != 0,
                address: parse_address(polar::FLAGS.get(p), polar::ADDRESS.get(p))?,
            }),
            FrameKind::EndOfInput => Message::End(EndOfInput {
                time_ms: end::TIME.get(p),
            }),
            FrameKind::TrackReport => Message::Track(parse_track(p)?),
            FrameKind::ScanSummary => {
                let ra = scan::RA.get(p);
                Message::Scan(ScanSummary {
                    time_ms: scan::TIME.get(p),
                    interval_ms: scan::INTERVAL.get(p),
                    counts: scan::COUNTS.get(p),
                    highest_advisory: advisory_from_code(scan::HIGHEST_ADVISORY.get(p))?,
                    ra: RaCode::from_byte(ra & !RA_CLEAR_OF_CONFLICT)?,
                    clear_of_conflict: ra & RA_CLEAR_OF_CONFLICT != 0,
                })
            }
            FrameKind::Health => Message::Health(Health {
                time_ms: health::TIME.get(p),
                decoder: health::DECODER.get(p),
                intake: health::INTAKE.get(p),
                scan: health::SCAN.get(p),
            }),
        };
        if let Message::Measurement(m) = &message {
            m.check_envelope().map_err(|_| WireError::OutOfEnvelope)?;
        }
        Ok(message)
    }

    /// Decodes the frame at the start of `bytes` (extra bytes after it are
    /// ignored; [`Message::buffer_len`] says how many were used).
    pub fn parse_bytes(bytes: &[u8]) -> Result<Message, WireError> {
        Message::parse(&Frame::new_checked(bytes)?)
    }

    /// The frame type.
    pub fn kind(&self) -> FrameKind {
        match self {
            Message::Measurement(m) => m.kind(),
            Message::End(_) => FrameKind::EndOfInput,
            Message::Track(_) => FrameKind::TrackReport,
            Message::Scan(_) => FrameKind::ScanSummary,
            Message::Health(_) => FrameKind::Health,
        }
    }

    /// Bytes of the whole frame.
    pub fn buffer_len(&self) -> usize {
        self.kind().frame_len()
    }

    /// Writes the whole frame (sync, header with `sequence`, payload, CRC)
    /// at the start of `buffer`; returns its length. An [`Encoder`] numbers
    /// a stream's frames.
    pub fn emit(&self, sequence: u16, buffer: &mut [u8]) -> Result<usize, WireError> {
        let len = self.buffer_len();
        let Some(bytes) = buffer.get_mut(..len) else {
            return Err(WireError::BufferTooShort);
        };
        let mut frame = Frame::new_unchecked(bytes);
        frame.set_header(self.kind(), sequence);
        let p = frame.payload_mut();
        match self {
            Message::Measurement(m) => match m.position {
                MeasuredPosition::Cartesian { x_cm, y_cm } => {
                    cartesian::TIME.set(p, m.time_ms);
                    cartesian::SENSOR.set(p, m.sensor);
                    cartesian::FLAGS.set(p, measurement_flags(m));
                    cartesian::ADDRESS.set(p, m.address.map_or(0, ModeSAddress::get));
                    cartesian::X.set(p, x_cm);
                    cartesian::Y.set(p, y_cm);
                    cartesian::ALTITUDE.set(p, m.altitude_ft.unwrap_or(0));
                }
                MeasuredPosition::Polar {
                    range_cm,
                    azimuth_bam,
                } => {
                    polar::TIME.set(p, m.time_ms);
                    polar::SENSOR.set(p, m.sensor);
                    polar::FLAGS.set(p, measurement_flags(m));
                    polar::ADDRESS.set(p, m.address.map_or(0, ModeSAddress::get));
                    polar::RANGE.set(p, range_cm);
                    polar::AZIMUTH.set(p, azimuth_bam);
                    polar::ALTITUDE.set(p, m.altitude_ft.unwrap_or(0));
                }
            },
            Message::End(e) => end::TIME.set(p, e.time_ms),
            Message::Track(t) => emit_track(t, p),
            Message::Scan(s) => {
                scan::TIME.set(p, s.time_ms);
                scan::INTERVAL.set(p, s.interval_ms);
                scan::HIGHEST_ADVISORY.set(p, advisory_code(s.highest_advisory));
                let coc = if s.clear_of_conflict {
                    RA_CLEAR_OF_CONFLICT
                } else {
                    0
                };
                scan::RA.set(p, ra_byte(s.ra) | coc);
                scan::COUNTS.set(p, s.counts);
            }
            Message::Health(h) => {
                health::TIME.set(p, h.time_ms);
                health::DECODER.set(p, h.decoder);
                health::INTAKE.set(p, h.intake);
                health::SCAN.set(p, h.scan);
            }
        }
        frame.fill_crc();
        Ok(len)
    }
}

fn parse_track(p: &[u8]) -> Result<TrackReport, WireError> {
    let flags = track::FLAGS.get(p);
    if flags & !(FLAG_ALTITUDE | FLAG_TAU | FLAG_TRACK_ADDRESS) != 0 {
        return Err(WireError::BadField);
    }
    let advisory = advisory_from_code(track::ADVISORY.get(p))?;
    let ra = RaCode::from_byte(track::RA.get(p))?;
    if ra.is_some() && advisory != Advisory::Resolution {
        return Err(WireError::BadField);
    }
    let (alt, rate, tau) = (
        track::ALTITUDE.get(p),
        track::VERTICAL_RATE.get(p),
        track::RANGE_TAU.get(p),
    );
    let altitude = if flags & FLAG_ALTITUDE != 0 {
        Some((alt, rate))
    } else if alt == 0 && rate == 0 {
        None
    } else {
        return Err(WireError::BadField);
    };
    let range_tau_ds = if flags & FLAG_TAU != 0 {
        Some(tau)
    } else if tau == 0 {
        None
    } else {
        return Err(WireError::BadField);
    };
    Ok(TrackReport {
        time_ms: track::TIME.get(p),
        track_id: track::TRACK_ID.get(p),
        status: status_from_code(track::STATUS.get(p))?,
        advisory,
        sensitivity: level_from_code(track::SENSITIVITY.get(p))?,
        x_cm: track::X.get(p),
        y_cm: track::Y.get(p),
        vx_cm_per_s: track::VX.get(p),
        vy_cm_per_s: track::VY.get(p),
        altitude,
        range_tau_ds,
        address: parse_flagged_address(flags & FLAG_TRACK_ADDRESS != 0, track::ADDRESS.get(p))?,
        ra,
    })
}

fn emit_track(t: &TrackReport, p: &mut [u8]) {
    let mut flags = 0;
    if t.altitude.is_some() {
        flags |= FLAG_ALTITUDE;
    }
    if t.range_tau_ds.is_some() {
        flags |= FLAG_TAU;
    }
    if t.address.is_some() {
        flags |= FLAG_TRACK_ADDRESS;
    }
    let (alt, rate) = t.altitude.unwrap_or((0, 0));
    track::TIME.set(p, t.time_ms);
    track::TRACK_ID.set(p, t.track_id);
    track::STATUS.set(p, status_code(t.status));
    track::ADVISORY.set(p, advisory_code(t.advisory));
    track::FLAGS.set(p, flags);
    track::SENSITIVITY.set(p, t.sensitivity.map_or(0, |l| l.number()));
    track::X.set(p, t.x_cm);
    track::Y.set(p, t.y_cm);
    track::VX.set(p, t.vx_cm_per_s);
    track::VY.set(p, t.vy_cm_per_s);
    track::ALTITUDE.set(p, alt);
    track::VERTICAL_RATE.set(p, rate);
    track::RANGE_TAU.set(p, t.range_tau_ds.unwrap_or(0));
    track::ADDRESS.set(p, t.address.map_or(0, ModeSAddress::get));
    // Only an RA carries its sense (parse refuses it otherwise).
    let ra = if t.advisory == Advisory::Resolution {
        t.ra
    } else {
        None
    };
    track::RA.set(p, ra_byte(ra));
}

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

// ---------------------------------------------------------------------------
// Streaming decoder
// ---------------------------------------------------------------------------

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
/// the count there.
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

fn bump(counter: &mut u32) {
    *counter = counter.saturating_add(1);
}

fn saturating_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
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
        bump(&mut self.stats.bytes);
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
        bump(&mut s.frames);
        bump(match e {
            WireError::Checksum => &mut s.crc_errors,
            WireError::UnknownType => &mut s.unknown_type,
            WireError::BadLength => &mut s.bad_length,
            WireError::OutOfEnvelope => &mut s.out_of_envelope,
            WireError::Truncated => &mut s.truncated,
            // BadSync and BufferTooShort cannot come out of the decoder's
            // own checks; BadField is the remaining one.
            _ => &mut s.bad_field,
        });
        self.discard(1);
        e
    }

    /// Counts an accepted candidate (and its sequence number) and drops its
    /// bytes.
    fn accept(&mut self, sequence: u16) {
        let s = &mut self.stats;
        bump(&mut s.frames);
        bump(&mut s.accepted);
        s.frame_bytes = s.frame_bytes.saturating_add(saturating_u32(self.accepted));
        if let Some(expected) = self.expected_sequence {
            let gap = sequence.wrapping_sub(expected);
            if gap < 0x8000 {
                s.frames_lost = s.frames_lost.saturating_add(u32::from(gap));
            } else {
                bump(&mut s.out_of_sequence);
            }
        }
        self.expected_sequence = Some(sequence.wrapping_add(1));
        self.consume(self.accepted);
    }

    /// Drops the first `n` held bytes as skipped; restarts the hunt.
    fn discard(&mut self, n: usize) {
        let n = n.min(self.held);
        self.stats.bytes_skipped = self.stats.bytes_skipped.saturating_add(saturating_u32(n));
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
