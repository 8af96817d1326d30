// The constants the doc links below name.
#[cfg(doc)]
use super::{MAX_ALTITUDE_FT, MAX_POSITION_CM, MIN_ALTITUDE_FT, SYNC};

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
