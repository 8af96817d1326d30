use super::*;

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
    pub(super) const fn payload_bound(longest: bool) -> usize {
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
