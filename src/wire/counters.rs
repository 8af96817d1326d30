counter_list! {
    /// What the [`Decoder`](super::Decoder) has seen over its lifetime (saturating).
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
        /// Frames missing from the sender's sequence numbers, and the
        /// candidates refused before the first accepted frame, at most its
        /// number ([`crate::wire::Decoder`]).
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
        /// Overruns of the UART's receiver: each lost one byte or more
        /// before the decoder saw them (the flag tells no more).
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
    /// those + held` ([`crate::scan::ScanLoop::held`]). Of the `used`, the
    /// tracker refused `rejected` and gave `not_assigned` no track (the
    /// scan summaries' counts of the same names, added up). The tracks'
    /// lifetime counts are the track table's own
    /// ([`crate::track::TableStats`], in the same health report).
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
        /// Used, and refused by the tracker (not finite, a negative range,
        /// the filter refused it, or the scan came too soon after the
        /// previous one).
        rejected => "rejected by the tracker",
        /// Used, inside a gate, and the assignment gave the track another
        /// measurement.
        not_assigned => "not assigned",
        /// Track report frames emitted.
        track_reports => "track reports",
        /// Confirmed tracks whose threat assessment failed (or the
        /// cycle's sensitivity selection or resolution).
        assessment_errors => "assessment errors",
        /// RA threats beyond the [`crate::scan::MAX_RA_THREATS`] resolved
        /// together (the latest by modified tau are left out).
        ra_threats_over_capacity => "RA threats over capacity",
        /// Scans where an intruder's range or altitude tracker refused its
        /// reply or its coast (invalid input or saturated arithmetic); a
        /// tracker that did not take a reply coasts instead.
        intruder_tracker_errors => "intruder tracker errors",
        /// Altitude reports the intruder's altitude tracker found not
        /// credible (DO-185B) and coasted through.
        altitude_not_credible => "altitude reports not credible",
    }
}

counter_list! {
    /// One scan's counts (the scan summary, type `0x82`), u16 saturating.
    ///
    /// The measurements taken for the scan: `used + late + out_of_window +
    /// over_capacity + invalid`; the used ones, by what the tracker did with
    /// them: `used = updated + started + not_assigned + outside_gates +
    /// outside_volume + rejected + refused_table_full` (a start that displaced a tentative
    /// track is in `started`; the track it ended in `displaced`).
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
        /// Inside no gate, and outside the surveillance volume (not used).
        outside_volume => "outside the volume",
        /// Refused by the tracker (not finite, a negative range, the filter
        /// refused it, or the scan came too soon after the previous one).
        rejected => "rejected",
        /// Would have started a track; the table was full and held no
        /// tentative track to displace.
        refused_table_full => "refused, table full",
        /// Tracks predicted to the scan time.
        predicted => "predicted",
        /// (track, measurement) pairs inside a gate.
        gated_pairs => "gated pairs",
        /// Tracks left to coast this scan: no measurement, or the filter
        /// refused theirs.
        coasted => "coasted",
        /// Tracks confirmed in this scan.
        confirmed => "confirmed",
        /// Tracks deleted in this scan (the displaced ones included).
        deleted => "deleted",
        /// Tentative tracks displaced in this scan by a new track because the
        /// table was full (also in `deleted`).
        displaced => "displaced",
        /// Tracks restarted in this scan (it came more than the filters'
        /// longest interval after the previous one; not in `deleted`).
        restarted => "restarted",
        /// Live tracks after the scan.
        tracks => "tracks",
        /// Confirmed (or coasting) tracks after the scan.
        confirmed_tracks => "confirmed tracks",
    }
}
