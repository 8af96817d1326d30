use super::*;

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
/// associates Mode S replies by it). Kept as its three bytes, most
/// significant first (the order is the address's): an `Option` of it is 4
/// bytes, not 8, in every per-track and per-reply record.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ModeSAddress([u8; 3]);

/// The address in hexadecimal, as it is written: `ModeSAddress(4CA123)`.
impl core::fmt::Debug for ModeSAddress {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "ModeSAddress({:06X})", self.get())
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for ModeSAddress {
    fn format(&self, f: defmt::Formatter) {
        defmt::write!(f, "ModeSAddress({=u32:06X})", self.get())
    }
}

impl ModeSAddress {
    /// The address, if it fits 24 bits.
    pub const fn new(address: u32) -> Option<Self> {
        match address.to_be_bytes() {
            [0, a, b, c] => Some(ModeSAddress([a, b, c])),
            _ => None,
        }
    }

    /// The 24-bit address.
    pub const fn get(self) -> u32 {
        let [a, b, c] = self.0;
        u32::from_be_bytes([0, a, b, c])
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
    /// The scan loop's track table's counters.
    pub table: crate::track::TableStats,
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
                table: health::TABLE.get(p),
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
                health::TABLE.set(p, h.table);
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
