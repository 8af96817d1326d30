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
        /// The scan loop's track table's
        /// ([`TableStats`](crate::track::TableStats)).
        TABLE: crate::track::TableStats,
    }
}
