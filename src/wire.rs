//! The serial protocol: measurement frames in, track and scan report frames
//! out. Sans-IO and allocation-free (in the style of smoltcp's `wire`): a
//! byte view [`Frame`] with `new_checked`, the typed [`Message`] with
//! [`Message::parse`] / [`Message::emit`], and a byte-at-a-time streaming
//! [`Decoder`] for an interrupt handler.
//!
//! # Frame
//!
//! | offset | bytes | field |
//! |---|---|---|
//! | 0 | 2 | sync `0xAB 0xCD` ([`SYNC`]) |
//! | 2 | 1 | message type ([`FrameKind`]) |
//! | 3 | 1 | payload length `L` — must equal the type's fixed length |
//! | 4 | `L` | payload, big-endian (network order) fields |
//! | 4 + `L` | 2 | CRC-16/CCITT-FALSE of bytes 2 .. 4 + `L` (type, length, payload), big-endian |
//!
//! CRC-16/CCITT-FALSE: polynomial 0x1021, initial value 0xFFFF, no
//! reflection, no final XOR; check value 0x29B1 for the ASCII bytes
//! `123456789` ([`crc16`]). The sync bytes are not covered (they are
//! constant); the length is, so a corrupted length is caught even when it
//! happens to be a valid one.
//!
//! Every type has one fixed payload length. The decoder checks the type at
//! byte 2 and the length at byte 3, so a corrupted header is refused at once
//! instead of swallowing up to 255 bytes of the following frames.
//!
//! # Payloads
//!
//! Integers only: the bytes mean the same thing whatever number
//! representation (f64, f32, Q32.32) either end computes in, every value has
//! exactly one encoding, and a receiver needs no float parsing in its
//! interrupt handler. Resolution: 1 cm, 1 cm/s, 1 ft, 2π/65536 rad (0.0055°,
//! the binary angle of ASTERIX radar data), 1 ms, 0.1 s.
//!
//! **Measurement, Cartesian** (type `0x01`, 18 bytes):
//!
//! | offset | type | field |
//! |---|---|---|
//! | 0 | u32 | time, ms (the sensor's monotonic clock; it may wrap) |
//! | 4 | u8 | sensor id |
//! | 5 | u8 | flags: bit 0 = altitude present; bits 1–7 must be 0 |
//! | 6 | i32 | x, cm |
//! | 10 | i32 | y, cm |
//! | 14 | i32 | pressure altitude, ft (0 when absent) |
//!
//! **Measurement, polar** (type `0x02`, 16 bytes):
//!
//! | offset | type | field |
//! |---|---|---|
//! | 0 | u32 | time, ms |
//! | 4 | u8 | sensor id |
//! | 5 | u8 | flags: bit 0 = altitude present; bits 1–7 must be 0 |
//! | 6 | u32 | range, cm |
//! | 10 | u16 | azimuth, binary angle: 65536 = 360°, clockwise from +y |
//! | 12 | i32 | pressure altitude, ft (0 when absent) |
//!
//! **Track report** (type `0x81`, 36 bytes), one per confirmed track per scan:
//!
//! | offset | type | field |
//! |---|---|---|
//! | 0 | u32 | scan time, ms |
//! | 4 | u32 | track id |
//! | 8 | u8 | status: 0 tentative, 1 confirmed, 2 coasting |
//! | 9 | u8 | advisory: 0 none, 1 proximate traffic, 2 traffic (TA), 3 resolution (RA) |
//! | 10 | u8 | flags: bit 0 altitude valid, bit 1 range tau valid; bits 2–7 must be 0 |
//! | 11 | u8 | TCAS sensitivity level 2–7, 0 = not assessed |
//! | 12 | i32 | x, cm (relative to the own aircraft) |
//! | 16 | i32 | y, cm |
//! | 20 | i32 | vx, cm/s |
//! | 24 | i32 | vy, cm/s |
//! | 28 | i32 | altitude, ft (0 when not valid) |
//! | 32 | i16 | vertical rate, ft/min (0 when not valid) |
//! | 34 | u16 | range tau, 0.1 s (0 when not valid) |
//!
//! **Scan summary** (type `0x82`, 40 bytes), one per scan: u32 scan time (ms),
//! u32 interval (ms), then fifteen u16 counts (saturating) in this order:
//! measurements taken, invalid (failed the conversion), late, dropped (over
//! the scan's capacity), rejected by the tracker, predicted, gated pairs,
//! assigned, updated, coasted, started, confirmed, deleted, live tracks,
//! confirmed tracks; then u8 highest advisory and a u8 that must be 0.
//!
//! **Link status** (type `0x83`, 44 bytes): u32 time (ms), then ten u32
//! counters of the receiving side, in the order of the fields of
//! [`LinkStatus`].
//!
//! # Conversions
//!
//! [`MeasurementReport::position`] and [`MeasurementReport::altitude`] are
//! the checked edge into the tracker: positions and ranges beyond ±400 km
//! (the numeric envelope the filters are specified for, issue 2) and
//! altitudes outside the Mode C range −1000 … 126 700 ft are refused with a
//! [`ConversionError`].

use crate::num::Scalar;
use crate::tcas::{Advisory, SensitivityLevel};
use crate::track::{Measurement, TrackStatus};

/// The two bytes that start every frame.
pub const SYNC: [u8; 2] = [0xAB, 0xCD];
/// Sync, type and length.
pub const HEADER_LEN: usize = 4;
/// The CRC at the end.
pub const CRC_LEN: usize = 2;
/// The longest payload of any type.
pub const MAX_PAYLOAD_LEN: usize = 44;
/// The longest frame.
pub const MAX_FRAME_LEN: usize = HEADER_LEN + MAX_PAYLOAD_LEN + CRC_LEN;
/// The shortest frame (a polar measurement).
pub const MIN_FRAME_LEN: usize = HEADER_LEN + 16 + CRC_LEN;
/// At most this many frames can complete on one byte pushed into the
/// [`Decoder`]: after a failed candidate, the bytes it held are examined
/// again, and up to `MAX_FRAME_LEN / MIN_FRAME_LEN` frames fit in them. A
/// producer that wants no message dropped keeps this many queue slots free.
pub const MAX_FRAMES_PER_BYTE: usize = MAX_FRAME_LEN / MIN_FRAME_LEN;

/// Largest |x|, |y| or range accepted, cm: 400 km, the position envelope of
/// the fixed-point filters (issue 2).
pub const MAX_POSITION_CM: u32 = 40_000_000;
/// Lowest pressure altitude accepted, ft (Mode C, ICAO Annex 10 Vol. IV).
pub const MIN_ALTITUDE_FT: i32 = -1_000;
/// Highest pressure altitude accepted, ft (Mode C).
pub const MAX_ALTITUDE_FT: i32 = 126_700;

/// Why bytes are not a valid frame or message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum WireError {
    /// Fewer bytes than the header says (or than a header).
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
            WireError::BufferTooShort => "output buffer too short",
        })
    }
}

/// Why a measurement frame cannot enter the tracker.
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

// ---------------------------------------------------------------------------
// CRC-16/CCITT-FALSE
// ---------------------------------------------------------------------------

const CRC_POLY: u16 = 0x1021;
/// Initial value of CRC-16/CCITT-FALSE.
pub const CRC_INIT: u16 = 0xFFFF;

const fn crc_table() -> [u16; 256] {
    let mut table = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let mut crc = (i as u16) << 8;
        let mut bit = 0;
        while bit < 8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ CRC_POLY
            } else {
                crc << 1
            };
            bit += 1;
        }
        table[i] = crc;
        i += 1;
    }
    table
}

/// 512 bytes of flash buy one table lookup per byte instead of eight shifts
/// in the receive interrupt.
static CRC_TABLE: [u16; 256] = crc_table();

/// Continues a CRC-16/CCITT-FALSE over `data` from the running value `crc`
/// (start from [`CRC_INIT`]).
pub fn crc16_update(mut crc: u16, data: &[u8]) -> u16 {
    for &b in data {
        // The index is a u8: always inside the 256-entry table.
        let index = ((crc >> 8) as u8 ^ b) as usize;
        crc = (crc << 8) ^ CRC_TABLE[index];
    }
    crc
}

/// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, not reflected, no final
/// XOR) of `data`; 0x29B1 for `b"123456789"`.
pub fn crc16(data: &[u8]) -> u16 {
    crc16_update(CRC_INIT, data)
}

// ---------------------------------------------------------------------------
// Field access without panics
// ---------------------------------------------------------------------------

fn get_array<const K: usize>(bytes: &[u8], at: usize) -> [u8; K] {
    let mut out = [0u8; K];
    if let Some(src) = bytes.get(at..at.saturating_add(K)) {
        // Element by element: `copy_from_slice` would keep a length-check
        // panic path the compiler cannot remove.
        for (o, b) in out.iter_mut().zip(src) {
            *o = *b;
        }
    }
    out
}

fn get_u8(bytes: &[u8], at: usize) -> u8 {
    bytes.get(at).copied().unwrap_or(0)
}
fn get_u16(bytes: &[u8], at: usize) -> u16 {
    u16::from_be_bytes(get_array(bytes, at))
}
fn get_i16(bytes: &[u8], at: usize) -> i16 {
    i16::from_be_bytes(get_array(bytes, at))
}
fn get_u32(bytes: &[u8], at: usize) -> u32 {
    u32::from_be_bytes(get_array(bytes, at))
}
fn get_i32(bytes: &[u8], at: usize) -> i32 {
    i32::from_be_bytes(get_array(bytes, at))
}

/// Writes big-endian fields in order into a payload; never panics (a write
/// past the end is dropped, and [`Message::emit`] checks the length first).
struct PayloadWriter<'a> {
    bytes: &'a mut [u8],
    at: usize,
}

impl PayloadWriter<'_> {
    fn put(&mut self, src: &[u8]) {
        let end = self.at.saturating_add(src.len());
        if let Some(dst) = self.bytes.get_mut(self.at..end) {
            for (d, b) in dst.iter_mut().zip(src) {
                *d = *b;
            }
        }
        self.at = end;
    }
    fn u8(&mut self, v: u8) {
        self.put(&[v]);
    }
    fn u16(&mut self, v: u16) {
        self.put(&v.to_be_bytes());
    }
    fn i16(&mut self, v: i16) {
        self.put(&v.to_be_bytes());
    }
    fn u32(&mut self, v: u32) {
        self.put(&v.to_be_bytes());
    }
    fn i32(&mut self, v: i32) {
        self.put(&v.to_be_bytes());
    }
}

// ---------------------------------------------------------------------------
// Frame: the byte view
// ---------------------------------------------------------------------------

/// The message types and their fixed payload lengths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrameKind {
    MeasurementCartesian = 0x01,
    MeasurementPolar = 0x02,
    TrackReport = 0x81,
    ScanSummary = 0x82,
    LinkStatus = 0x83,
}

impl FrameKind {
    /// The kind with this type byte.
    pub const fn from_byte(b: u8) -> Option<Self> {
        match b {
            0x01 => Some(FrameKind::MeasurementCartesian),
            0x02 => Some(FrameKind::MeasurementPolar),
            0x81 => Some(FrameKind::TrackReport),
            0x82 => Some(FrameKind::ScanSummary),
            0x83 => Some(FrameKind::LinkStatus),
            _ => None,
        }
    }

    /// The type byte.
    pub const fn byte(self) -> u8 {
        self as u8
    }

    /// The payload length every frame of this kind has.
    pub const fn payload_len(self) -> usize {
        match self {
            FrameKind::MeasurementCartesian => 18,
            FrameKind::MeasurementPolar => 16,
            FrameKind::TrackReport => 36,
            FrameKind::ScanSummary => 40,
            FrameKind::LinkStatus => 44,
        }
    }

    /// Header + payload + CRC.
    pub const fn frame_len(self) -> usize {
        HEADER_LEN + self.payload_len() + CRC_LEN
    }
}

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
        if get_array::<2>(bytes, 0) != SYNC {
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
        get_u8(self.buffer.as_ref(), 2)
    }

    /// The message type, if the type byte names one.
    pub fn kind(&self) -> Option<FrameKind> {
        FrameKind::from_byte(self.type_byte())
    }

    /// The length byte.
    pub fn payload_len(&self) -> usize {
        get_u8(self.buffer.as_ref(), 3) as usize
    }

    /// Header + payload + CRC, from the length byte.
    pub fn frame_len(&self) -> usize {
        HEADER_LEN + self.payload_len() + CRC_LEN
    }

    /// The payload (as much of it as the buffer holds).
    pub fn payload(&self) -> &[u8] {
        let bytes = self.buffer.as_ref();
        let end = (HEADER_LEN + self.payload_len()).min(bytes.len());
        bytes.get(HEADER_LEN..end).unwrap_or(&[])
    }

    /// The CRC stored in the frame.
    pub fn crc(&self) -> u16 {
        get_u16(self.buffer.as_ref(), HEADER_LEN + self.payload_len())
    }

    /// The CRC computed over type, length and payload.
    pub fn compute_crc(&self) -> u16 {
        let bytes = self.buffer.as_ref();
        let end = (HEADER_LEN + self.payload_len()).min(bytes.len());
        crc16(bytes.get(2..end).unwrap_or(&[]))
    }

    /// Whether the stored CRC matches (false on a truncated buffer).
    pub fn verify_crc(&self) -> bool {
        self.buffer.as_ref().len() >= self.frame_len() && self.crc() == self.compute_crc()
    }

    pub fn into_inner(self) -> T {
        self.buffer
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> Frame<T> {
    /// Writes sync, type and length.
    pub fn set_header(&mut self, kind: FrameKind) {
        let mut w = PayloadWriter {
            bytes: self.buffer.as_mut(),
            at: 0,
        };
        w.put(&SYNC);
        w.u8(kind.byte());
        // Every payload length is ≤ MAX_PAYLOAD_LEN = 40.
        w.u8(kind.payload_len() as u8);
    }

    /// The payload, for writing (as much of it as the buffer holds).
    pub fn payload_mut(&mut self) -> &mut [u8] {
        let len = self.payload_len();
        let bytes = self.buffer.as_mut();
        let end = (HEADER_LEN + len).min(bytes.len());
        bytes.get_mut(HEADER_LEN..end).unwrap_or(&mut [])
    }

    /// Computes and stores the CRC (after the header and payload are
    /// written).
    pub fn fill_crc(&mut self) {
        let crc = self.compute_crc();
        let at = HEADER_LEN + self.payload_len();
        let mut w = PayloadWriter {
            bytes: self.buffer.as_mut(),
            at,
        };
        w.u16(crc);
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
    Cartesian { x_cm: i32, y_cm: i32 },
    /// Range (cm) and azimuth (binary angle, 65536 per turn, clockwise from
    /// +y) from the own aircraft.
    Polar { range_cm: u32, azimuth_bam: u16 },
}

/// One measurement as a sensor reports it (frame types 0x01 and 0x02).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MeasurementReport {
    /// Sensor clock, ms.
    pub time_ms: u32,
    pub sensor: u8,
    pub position: MeasuredPosition,
    /// Reported pressure altitude, ft; `None` for a non-reporting target.
    pub altitude_ft: Option<i32>,
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
    /// altitude in feet (rounded to 1 ft), checked against the limits of
    /// [`MeasurementReport::position`].
    pub fn cartesian_from_metres(
        time_ms: u32,
        sensor: u8,
        x_m: f64,
        y_m: f64,
        altitude_ft: Option<f64>,
    ) -> Result<Self, ConversionError> {
        let limit = MAX_POSITION_CM as i64;
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
        if !(0..=MAX_POSITION_CM as i64).contains(&range) {
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
        })
    }

    /// The measurement for the tracker, in metres and radians in the number
    /// type `S`: the checked edge of the input path.
    pub fn position<S: Scalar>(&self) -> Result<Measurement<S>, ConversionError> {
        let s = |v: f64| S::try_from_f64(v).map_err(|_| ConversionError::NotRepresentable);
        match self.position {
            MeasuredPosition::Cartesian { x_cm, y_cm } => {
                if x_cm.unsigned_abs() > MAX_POSITION_CM || y_cm.unsigned_abs() > MAX_POSITION_CM {
                    return Err(ConversionError::PositionOutOfRange);
                }
                Ok(Measurement::Cartesian {
                    x: s(x_cm as f64 / 100.0)?,
                    y: s(y_cm as f64 / 100.0)?,
                })
            }
            MeasuredPosition::Polar {
                range_cm,
                azimuth_bam,
            } => {
                if range_cm > MAX_POSITION_CM {
                    return Err(ConversionError::RangeOutOfRange);
                }
                Ok(Measurement::Polar {
                    range: s(range_cm as f64 / 100.0)?,
                    azimuth: s(azimuth_bam as f64 * RAD_PER_BAM)?,
                })
            }
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
            Some(a) => S::try_from_f64(a as f64)
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
    /// Scan time, ms.
    pub time_ms: u32,
    pub track_id: u32,
    pub status: TrackStatus,
    pub advisory: Advisory,
    /// `None` when the track was not assessed (the assessment failed).
    pub sensitivity: Option<SensitivityLevel>,
    /// Position relative to the own aircraft, cm.
    pub x_cm: i32,
    pub y_cm: i32,
    /// Velocity relative to the own aircraft, cm/s.
    pub vx_cm_per_s: i32,
    pub vy_cm_per_s: i32,
    /// Tracked pressure altitude (ft) and vertical rate (ft/min); `None` for
    /// a target without altitude.
    pub altitude: Option<(i32, i16)>,
    /// Range tau, 0.1 s; `None` when diverging or not assessed.
    pub range_tau_ds: Option<u16>,
}

/// Per-stage counts of one scan (frame type 0x82); see the module docs for
/// the field order on the wire. Counts saturate at 65535.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanSummary {
    pub time_ms: u32,
    pub interval_ms: u32,
    /// Measurements taken from the queue for this scan.
    pub measurements: u16,
    /// Failed the conversion ([`ConversionError`]).
    pub invalid: u16,
    /// Timestamped at or before the previous scan.
    pub late: u16,
    /// Beyond the scan's capacity.
    pub dropped: u16,
    /// Refused by the tracker as bad input.
    pub rejected: u16,
    pub predicted: u16,
    pub gated_pairs: u16,
    pub assigned: u16,
    pub updated: u16,
    pub coasted: u16,
    pub started: u16,
    pub confirmed: u16,
    pub deleted: u16,
    /// Live tracks after the scan.
    pub tracks: u16,
    /// Confirmed (or coasting) tracks after the scan.
    pub confirmed_tracks: u16,
    /// The most severe advisory over all tracks.
    pub highest_advisory: Advisory,
}

/// Counters of the receiving side (frame type 0x83): the decoder's and the
/// measurement queue's. Saturating.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LinkStatus {
    pub time_ms: u32,
    /// Valid frames decoded.
    pub frames: u32,
    pub crc_errors: u32,
    pub unknown_type: u32,
    pub bad_length: u32,
    /// Frames with a valid CRC and an invalid field.
    pub bad_field: u32,
    /// Partial frames abandoned when the line went idle.
    pub truncated: u32,
    /// Bytes that were not part of any valid frame.
    pub bytes_skipped: u32,
    /// Measurements lost because the queue was full.
    pub queue_full: u32,
    /// Valid frames of a type the receiver does not take as input.
    pub not_measurement: u32,
    /// Bytes the UART lost before the decoder saw them (hardware overrun).
    pub rx_overruns: u32,
}

/// A decoded frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Message {
    Measurement(MeasurementReport),
    Track(TrackReport),
    Scan(ScanSummary),
    Link(LinkStatus),
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

/// The altitude of a measurement payload: flag bit 0 and the field; a value
/// with the flag clear, or other flag bits, are refused.
fn parse_altitude(flags: u8, field: i32) -> Result<Option<i32>, WireError> {
    match flags {
        0 if field == 0 => Ok(None),
        FLAG_ALTITUDE => Ok(Some(field)),
        _ => Err(WireError::BadField),
    }
}

impl Message {
    /// Decodes a frame: structure ([`Frame::check_len`]), CRC, then every
    /// field.
    pub fn parse<T: AsRef<[u8]>>(frame: &Frame<T>) -> Result<Message, WireError> {
        frame.check_len()?;
        if !frame.verify_crc() {
            return Err(WireError::Checksum);
        }
        let p = frame.payload();
        let kind = frame.kind().ok_or(WireError::UnknownType)?;
        Ok(match kind {
            FrameKind::MeasurementCartesian => Message::Measurement(MeasurementReport {
                time_ms: get_u32(p, 0),
                sensor: get_u8(p, 4),
                position: MeasuredPosition::Cartesian {
                    x_cm: get_i32(p, 6),
                    y_cm: get_i32(p, 10),
                },
                altitude_ft: parse_altitude(get_u8(p, 5), get_i32(p, 14))?,
            }),
            FrameKind::MeasurementPolar => Message::Measurement(MeasurementReport {
                time_ms: get_u32(p, 0),
                sensor: get_u8(p, 4),
                position: MeasuredPosition::Polar {
                    range_cm: get_u32(p, 6),
                    azimuth_bam: get_u16(p, 10),
                },
                altitude_ft: parse_altitude(get_u8(p, 5), get_i32(p, 12))?,
            }),
            FrameKind::TrackReport => {
                let flags = get_u8(p, 10);
                if flags & !(FLAG_ALTITUDE | FLAG_TAU) != 0 {
                    return Err(WireError::BadField);
                }
                let (alt, rate, tau) = (get_i32(p, 28), get_i16(p, 32), get_u16(p, 34));
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
                Message::Track(TrackReport {
                    time_ms: get_u32(p, 0),
                    track_id: get_u32(p, 4),
                    status: status_from_code(get_u8(p, 8))?,
                    advisory: advisory_from_code(get_u8(p, 9))?,
                    sensitivity: level_from_code(get_u8(p, 11))?,
                    x_cm: get_i32(p, 12),
                    y_cm: get_i32(p, 16),
                    vx_cm_per_s: get_i32(p, 20),
                    vy_cm_per_s: get_i32(p, 24),
                    altitude,
                    range_tau_ds,
                })
            }
            FrameKind::ScanSummary => {
                if get_u8(p, 39) != 0 {
                    return Err(WireError::BadField);
                }
                let c = |i: usize| get_u16(p, 8 + 2 * i);
                Message::Scan(ScanSummary {
                    time_ms: get_u32(p, 0),
                    interval_ms: get_u32(p, 4),
                    measurements: c(0),
                    invalid: c(1),
                    late: c(2),
                    dropped: c(3),
                    rejected: c(4),
                    predicted: c(5),
                    gated_pairs: c(6),
                    assigned: c(7),
                    updated: c(8),
                    coasted: c(9),
                    started: c(10),
                    confirmed: c(11),
                    deleted: c(12),
                    tracks: c(13),
                    confirmed_tracks: c(14),
                    highest_advisory: advisory_from_code(get_u8(p, 38))?,
                })
            }
            FrameKind::LinkStatus => {
                let c = |i: usize| get_u32(p, 4 + 4 * i);
                Message::Link(LinkStatus {
                    time_ms: get_u32(p, 0),
                    frames: c(0),
                    crc_errors: c(1),
                    unknown_type: c(2),
                    bad_length: c(3),
                    bad_field: c(4),
                    truncated: c(5),
                    bytes_skipped: c(6),
                    queue_full: c(7),
                    not_measurement: c(8),
                    rx_overruns: c(9),
                })
            }
        })
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
            Message::Track(_) => FrameKind::TrackReport,
            Message::Scan(_) => FrameKind::ScanSummary,
            Message::Link(_) => FrameKind::LinkStatus,
        }
    }

    /// Bytes of the whole frame.
    pub fn buffer_len(&self) -> usize {
        self.kind().frame_len()
    }

    /// Writes the whole frame (sync, header, payload, CRC) at the start of
    /// `buffer`; returns its length.
    pub fn emit(&self, buffer: &mut [u8]) -> Result<usize, WireError> {
        let len = self.buffer_len();
        let Some(bytes) = buffer.get_mut(..len) else {
            return Err(WireError::BufferTooShort);
        };
        let mut frame = Frame::new_unchecked(bytes);
        frame.set_header(self.kind());
        let mut w = PayloadWriter {
            bytes: frame.payload_mut(),
            at: 0,
        };
        match self {
            Message::Measurement(m) => {
                w.u32(m.time_ms);
                w.u8(m.sensor);
                w.u8(if m.altitude_ft.is_some() {
                    FLAG_ALTITUDE
                } else {
                    0
                });
                match m.position {
                    MeasuredPosition::Cartesian { x_cm, y_cm } => {
                        w.i32(x_cm);
                        w.i32(y_cm);
                    }
                    MeasuredPosition::Polar {
                        range_cm,
                        azimuth_bam,
                    } => {
                        w.u32(range_cm);
                        w.u16(azimuth_bam);
                    }
                }
                w.i32(m.altitude_ft.unwrap_or(0));
            }
            Message::Track(t) => {
                w.u32(t.time_ms);
                w.u32(t.track_id);
                w.u8(status_code(t.status));
                w.u8(advisory_code(t.advisory));
                let mut flags = 0;
                if t.altitude.is_some() {
                    flags |= FLAG_ALTITUDE;
                }
                if t.range_tau_ds.is_some() {
                    flags |= FLAG_TAU;
                }
                w.u8(flags);
                w.u8(t.sensitivity.map_or(0, |l| l.number()));
                w.i32(t.x_cm);
                w.i32(t.y_cm);
                w.i32(t.vx_cm_per_s);
                w.i32(t.vy_cm_per_s);
                let (alt, rate) = t.altitude.unwrap_or((0, 0));
                w.i32(alt);
                w.i16(rate);
                w.u16(t.range_tau_ds.unwrap_or(0));
            }
            Message::Scan(s) => {
                w.u32(s.time_ms);
                w.u32(s.interval_ms);
                for c in [
                    s.measurements,
                    s.invalid,
                    s.late,
                    s.dropped,
                    s.rejected,
                    s.predicted,
                    s.gated_pairs,
                    s.assigned,
                    s.updated,
                    s.coasted,
                    s.started,
                    s.confirmed,
                    s.deleted,
                    s.tracks,
                    s.confirmed_tracks,
                ] {
                    w.u16(c);
                }
                w.u8(advisory_code(s.highest_advisory));
                w.u8(0);
            }
            Message::Link(l) => {
                w.u32(l.time_ms);
                for c in [
                    l.frames,
                    l.crc_errors,
                    l.unknown_type,
                    l.bad_length,
                    l.bad_field,
                    l.truncated,
                    l.bytes_skipped,
                    l.queue_full,
                    l.not_measurement,
                    l.rx_overruns,
                ] {
                    w.u32(c);
                }
            }
        }
        frame.fill_crc();
        Ok(len)
    }
}

// ---------------------------------------------------------------------------
// Streaming decoder
// ---------------------------------------------------------------------------

/// What the [`Decoder`] has seen (saturating counters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DecoderStats {
    /// Valid frames returned.
    pub frames: u32,
    pub crc_errors: u32,
    pub unknown_type: u32,
    pub bad_length: u32,
    pub bad_field: u32,
    /// Partial frames abandoned by [`Decoder::line_idle`].
    pub truncated: u32,
    /// Bytes discarded: not part of any valid frame (garbage, the bytes of
    /// failed candidates). Every byte pushed ends up in a returned frame, in
    /// this count, or still held ([`Decoder::held`]).
    pub bytes_skipped: u32,
}

/// Byte-at-a-time frame decoder for a receive interrupt: no allocation,
/// O(1) work per byte except after a failed candidate.
///
/// It hunts for [`SYNC`], checks the type and length bytes as soon as they
/// arrive, and the CRC and fields at the end of the frame. After any failure
/// it drops only the candidate's first byte and examines the bytes it had
/// taken again, so a valid frame that began inside a corrupted or truncated
/// one is still found. It never panics, whatever the bytes.
///
/// Each call returns at most one result. A failure, or a frame found among
/// re-examined bytes, can leave further bytes held and unexamined: they are
/// examined on the next [`push`](Decoder::push), or by [`poll`](Decoder::poll)
/// without new input (at most [`MAX_FRAMES_PER_BYTE`] frames plus failures
/// can be pending), so nothing is lost, only delayed.
///
/// A truncated frame is only recognised once the bytes it claims have
/// arrived (they are then examined again, so a frame that started among them
/// is found). When the line goes idle, [`line_idle`](Decoder::line_idle)
/// abandons a partial frame at once.
#[derive(Debug, Clone)]
pub struct Decoder {
    buffer: [u8; MAX_FRAME_LEN],
    /// Bytes held in `buffer`.
    held: usize,
    /// Leading bytes of `buffer` examined and accepted as the current
    /// candidate frame.
    accepted: usize,
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
    pub const fn new() -> Self {
        Decoder {
            buffer: [0; MAX_FRAME_LEN],
            held: 0,
            accepted: 0,
            stats: DecoderStats {
                frames: 0,
                crc_errors: 0,
                unknown_type: 0,
                bad_length: 0,
                bad_field: 0,
                truncated: 0,
                bytes_skipped: 0,
            },
        }
    }

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
        self.stats.bytes_skipped = self.stats.bytes_skipped.saturating_add(self.held as u32);
        self.held = 0;
        self.accepted = 0;
    }

    /// Takes one received byte; returns a frame or a frame-level error if
    /// one completed.
    pub fn push(&mut self, byte: u8) -> Option<Result<Message, WireError>> {
        if self.held >= MAX_FRAME_LEN {
            // Unreachable: after every call fewer than MAX_FRAME_LEN bytes
            // are held (a candidate of MAX_FRAME_LEN bytes is complete and
            // examined). Kept so that a broken invariant costs a byte, not a
            // panic.
            self.discard(1);
        }
        if let Some(slot) = self.buffer.get_mut(self.held) {
            *slot = byte;
            self.held += 1;
        }
        self.poll()
    }

    /// Examines held bytes without new input; `None` once nothing more can
    /// complete until more bytes arrive.
    pub fn poll(&mut self) -> Option<Result<Message, WireError>> {
        while self.accepted < self.held {
            let i = self.accepted;
            let byte = self.buffer.get(i).copied().unwrap_or(0);
            let verdict = match i {
                0 if byte == SYNC[0] => Verdict::Accept,
                1 if byte == SYNC[1] => Verdict::Accept,
                0 | 1 => Verdict::Skip,
                2 => match FrameKind::from_byte(byte) {
                    Some(_) => Verdict::Accept,
                    None => Verdict::Fail(WireError::UnknownType),
                },
                3 => match self.buffer.get(2).copied().and_then(FrameKind::from_byte) {
                    Some(kind) if kind.payload_len() == byte as usize => Verdict::Accept,
                    _ => Verdict::Fail(WireError::BadLength),
                },
                _ => Verdict::Accept,
            };
            match verdict {
                Verdict::Skip => self.discard(1),
                Verdict::Fail(e) => {
                    self.count(e);
                    self.discard(1);
                    return Some(Err(e));
                }
                Verdict::Accept => {
                    self.accepted += 1;
                    let frame = Frame::new_unchecked(self.buffer.get(..self.accepted)?);
                    if self.accepted >= HEADER_LEN && self.accepted == frame.frame_len() {
                        let result = Message::parse(&frame);
                        match result {
                            Ok(_) => {
                                self.stats.frames = self.stats.frames.saturating_add(1);
                                self.consume(self.accepted);
                            }
                            Err(e) => {
                                self.count(e);
                                self.discard(1);
                            }
                        }
                        return Some(result);
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
        self.stats.truncated = self.stats.truncated.saturating_add(1);
        self.discard(1);
        Some(Err(WireError::Truncated))
    }

    fn count(&mut self, e: WireError) {
        let s = &mut self.stats;
        let counter = match e {
            WireError::Checksum => &mut s.crc_errors,
            WireError::UnknownType => &mut s.unknown_type,
            WireError::BadLength => &mut s.bad_length,
            // Truncated, BadSync and BufferTooShort cannot come out of the
            // decoder's own checks; BadField is the remaining one.
            _ => &mut s.bad_field,
        };
        *counter = counter.saturating_add(1);
    }

    /// Drops the first `n` held bytes as skipped; restarts the hunt.
    fn discard(&mut self, n: usize) {
        self.stats.bytes_skipped = self.stats.bytes_skipped.saturating_add(n as u32);
        self.consume(n);
    }

    /// Drops the first `n` held bytes; restarts the hunt at the next one.
    fn consume(&mut self, n: usize) {
        let n = n.min(self.held);
        for to in 0..self.held - n {
            let byte = self.buffer.get(to + n).copied().unwrap_or(0);
            if let Some(slot) = self.buffer.get_mut(to) {
                *slot = byte;
            }
        }
        self.held -= n;
        self.accepted = 0;
    }
}
