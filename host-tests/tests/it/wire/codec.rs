//! The wire codec: CRC, frame layout, parse/emit round trips, checked
//! conversions, and the streaming decoder (resynchronisation, counters, no
//! panic on any input).

use abtrack::num::Quantity;
use abtrack::tcas::{Advisory, RaSense, RaStrength, SensitivityLevel};
use abtrack::track::{Measurement, TableStats, TrackStatus};
use abtrack::wire::*;
use abtrack::Fix;
use proptest::prelude::*;

/// CRC-32C written out bit by bit, straight from its definition (reflected
/// polynomial 0x82F63B78, LSB first, init and final XOR 0xFFFFFFFF),
/// independent of the library's table.
fn crc_bitwise(data: &[u8]) -> u32 {
    let mut crc: u32 = 0xFFFF_FFFF;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0x82F6_3B78
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn crc_has_the_crc32c_check_value() {
    // The catalogue check value of CRC-32C (CRC-32/ISCSI): CRC of the ASCII
    // string "123456789".
    assert_eq!(crc32c(b"123456789"), 0xE306_9283);
    assert_eq!(crc_bitwise(b"123456789"), 0xE306_9283);
    // Nothing processed: the initial value, inverted.
    assert_eq!(crc32c(b""), 0);
    // Incremental equals one-shot.
    assert_eq!(
        !crc32c_update(crc32c_update(CRC_INIT, b"1234"), b"56789"),
        0xE306_9283
    );
}

proptest! {
    #[test]
    fn crc_table_matches_the_bitwise_definition(data in prop::collection::vec(any::<u8>(), 0..64)) {
        prop_assert_eq!(crc32c(&data), crc_bitwise(&data));
    }
}

/// Sets the CRC of a frame whose bytes were changed by hand.
fn refresh_crc(frame: &mut [u8]) {
    let n = frame.len();
    let crc = crc32c(&frame[2..n - 4]);
    frame[n - 4..].copy_from_slice(&crc.to_be_bytes());
}

fn cartesian(time_ms: u32, x_cm: i32, y_cm: i32, alt: Option<i32>) -> MeasurementReport {
    MeasurementReport {
        time_ms,
        sensor: 7,
        position: MeasuredPosition::Cartesian { x_cm, y_cm },
        altitude_ft: alt,
        altitude_25ft: false,
        address: None,
    }
}

fn emit(m: &Message) -> Vec<u8> {
    emit_numbered(m, 0)
}

fn emit_numbered(m: &Message, sequence: u16) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = m.emit(sequence, &mut buf).unwrap();
    buf[..n].to_vec()
}

#[test]
fn cartesian_frame_has_the_documented_layout() {
    let m = Message::Measurement(
        cartesian(0x0102_0304, -2, 300, Some(8000))
            .with_mode_s(ModeSAddress::new(0x00AB_CDEF).unwrap(), true),
    );
    let bytes = emit_numbered(&m, 0x1234);
    // Written by hand from the table in the module docs.
    let mut expected = vec![
        0xAB, 0xCD, // sync
        0x01, 22, // type, payload length
        0x12, 0x34, // sequence number
        0x01, 0x02, 0x03, 0x04, // time 0x01020304 ms
        7,    // sensor
        0x07, // flags: altitude present, Mode S address, 25 ft steps
        0xFF, 0xFF, 0xFF, 0xFE, // x = -2 cm
        0x00, 0x00, 0x01, 0x2C, // y = 300 cm
        0x00, 0x00, 0x1F, 0x40, // altitude 8000 ft
        0x00, 0xAB, 0xCD, 0xEF, // Mode S address ABCDEF
    ];
    let crc = crc_bitwise(&expected[2..]);
    expected.extend_from_slice(&crc.to_be_bytes());
    assert_eq!(bytes, expected);
    assert_eq!(bytes.len(), FrameKind::MeasurementCartesian.frame_len());
    assert_eq!(Frame::new_checked(&bytes[..]).unwrap().sequence(), 0x1234);
    assert_eq!(Message::parse_bytes(&bytes), Ok(m));
}

#[test]
fn polar_frame_has_the_documented_layout() {
    let m = Message::Measurement(MeasurementReport {
        time_ms: 5000,
        sensor: 2,
        position: MeasuredPosition::Polar {
            range_cm: 2_593_000,
            azimuth_bam: 0x4000,
        },
        altitude_ft: None,
        altitude_25ft: false,
        address: None,
    });
    let bytes = emit_numbered(&m, 0xFFFF);
    let mut expected = vec![
        0xAB, 0xCD, 0x02, 20, 0xFF, 0xFF, // header
        0x00, 0x00, 0x13, 0x88, // 5000 ms
        2, 0x00, // sensor, no altitude, no address
        0x00, 0x27, 0x90, 0xE8, // 2 593 000 cm = 0x2790E8
        0x40, 0x00, // azimuth 90°
        0x00, 0x00, 0x00, 0x00, // altitude absent
        0x00, 0x00, 0x00, 0x00, // address absent (Mode C)
    ];
    let crc = crc_bitwise(&expected[2..]);
    expected.extend_from_slice(&crc.to_be_bytes());
    assert_eq!(bytes, expected);
    assert_eq!(Message::parse_bytes(&bytes), Ok(m));
}

fn track_report() -> TrackReport {
    TrackReport {
        time_ms: 30_000,
        track_id: 42,
        status: TrackStatus::Coasting,
        advisory: Advisory::Traffic,
        sensitivity: Some(SensitivityLevel::Sl5),
        x_cm: -123_456,
        y_cm: 654_321,
        vx_cm_per_s: 10_000,
        vy_cm_per_s: -5_000,
        altitude: Some((7_900, -300)),
        range_tau_ds: Some(173),
        address: ModeSAddress::new(0x00AB_CDEF),
        ra: None,
    }
}

fn scan_summary() -> ScanSummary {
    ScanSummary {
        time_ms: 1,
        interval_ms: 2,
        counts: ScanCounts::from_values(std::array::from_fn(|i| 3 + i as u16)),
        highest_advisory: Advisory::Resolution,
        ra: Some(RaCode {
            sense: RaSense::Down,
            strength: RaStrength::Increase,
        }),
        clear_of_conflict: false,
    }
}

fn health() -> Health {
    Health {
        time_ms: 9,
        decoder: DecoderStats::from_values(std::array::from_fn(|i| 100 + i as u32)),
        intake: IntakeCounters::from_values(std::array::from_fn(|i| 200 + i as u32)),
        scan: LoopCounters::from_values(std::array::from_fn(|i| u32::MAX - i as u32)),
        table: TableStats::from_values(std::array::from_fn(|i| 300 + i as u32)),
    }
}

#[test]
fn report_frames_round_trip() {
    for m in [
        Message::Track(track_report()),
        Message::Track(TrackReport {
            altitude: None,
            range_tau_ds: None,
            sensitivity: None,
            ..track_report()
        }),
        Message::Track(TrackReport {
            advisory: Advisory::Resolution,
            ra: Some(RaCode {
                sense: RaSense::Up,
                strength: RaStrength::Preventive,
            }),
            address: None,
            ..track_report()
        }),
        Message::Scan(scan_summary()),
        Message::Scan(ScanSummary {
            ra: None,
            clear_of_conflict: true,
            ..scan_summary()
        }),
        Message::Health(health()),
    ] {
        let bytes = emit(&m);
        assert_eq!(bytes.len(), m.buffer_len());
        assert_eq!(bytes[3] as usize, m.kind().payload_len());
        assert_eq!(Message::parse_bytes(&bytes), Ok(m));
    }
    // Field positions of the track report, by hand: id at payload offset 4,
    // status at 8, advisory at 9, flags at 10, level at 11, tau at 34.
    let b = emit(&Message::Track(track_report()));
    let p = &b[HEADER_LEN..];
    assert_eq!(&p[4..8], &[0, 0, 0, 42]);
    assert_eq!(p[8], 2); // coasting
    assert_eq!(p[9], 2); // TA
    assert_eq!(p[10], 0b111); // altitude, tau and address valid
    assert_eq!(p[11], 5);
    assert_eq!(&p[34..36], &[0, 173]);
    assert_eq!(&p[36..40], &[0, 0xAB, 0xCD, 0xEF]); // address
    assert_eq!(p[40], 0); // no RA
    assert_eq!(FrameKind::TrackReport.payload_len(), 41);
    // The scan summary: time, interval, advisory, the RA (increase
    // descent: sense 2, strength 3), then the counts in the order of
    // ScanCounts::NAMES, u16 each.
    let b = emit(&Message::Scan(scan_summary()));
    let p = &b[HEADER_LEN..];
    assert_eq!(&p[..10], &[0, 0, 0, 1, 0, 0, 0, 2, 3, 0b1110]);
    for i in 0..ScanCounts::LEN {
        assert_eq!(&p[10 + 2 * i..12 + 2 * i], &(3 + i as u16).to_be_bytes());
    }
    assert_eq!(p.len() - 4, 10 + 2 * ScanCounts::LEN);
    // The health report: time, then the three lists, u32 each.
    let b = emit(&Message::Health(health()));
    let p = &b[HEADER_LEN..b.len() - CRC_LEN];
    assert_eq!(&p[..4], &[0, 0, 0, 9]);
    assert_eq!(&p[4..8], &100u32.to_be_bytes());
    let intake_at = 4 + 4 * DecoderStats::LEN;
    assert_eq!(&p[intake_at..intake_at + 4], &200u32.to_be_bytes());
    assert_eq!(
        p.len(),
        4 + 4 * (DecoderStats::LEN + IntakeCounters::LEN + LoopCounters::LEN + TableStats::LEN)
    );
    let table_at = intake_at + 4 * (IntakeCounters::LEN + LoopCounters::LEN);
    assert_eq!(&p[table_at..table_at + 4], &300u32.to_be_bytes());
}

#[test]
fn counter_lists_name_every_counter_once() {
    for (names, labels) in [
        (&DecoderStats::NAMES[..], &DecoderStats::LABELS[..]),
        (&IntakeCounters::NAMES[..], &IntakeCounters::LABELS[..]),
        (&LoopCounters::NAMES[..], &LoopCounters::LABELS[..]),
        (&TableStats::NAMES[..], &TableStats::LABELS[..]),
        (&ScanCounts::NAMES[..], &ScanCounts::LABELS[..]),
    ] {
        let unique: std::collections::BTreeSet<_> = names.iter().collect();
        assert_eq!(unique.len(), names.len(), "{names:?}");
        let unique: std::collections::BTreeSet<_> = labels.iter().collect();
        assert_eq!(unique.len(), labels.len(), "{labels:?}");
    }
    // Display lists every counter with its label, in wire order.
    let text = health().decoder.to_string();
    assert!(
        text.starts_with("100 bytes, 101 frame bytes, 102 bytes skipped"),
        "{text}"
    );
    assert_eq!(text.matches(", ").count(), DecoderStats::LEN - 1);
}

#[test]
fn emit_refuses_a_short_buffer() {
    let m = Message::Track(track_report());
    let mut buf = [0u8; 45];
    assert_eq!(m.emit(0, &mut buf), Err(WireError::BufferTooShort));
    let mut encoder = Encoder::new();
    assert!(encoder.encode(&m, &mut buf).is_err());
    assert_eq!(encoder.next_sequence(), 0);
}

#[test]
fn new_checked_and_parse_name_what_is_wrong() {
    let good = emit(&Message::Measurement(cartesian(1, 2, 3, None)));
    assert!(Frame::new_checked(&good[..]).is_ok());
    assert_eq!(
        Frame::new_checked(&good[..3]).err(),
        Some(WireError::Truncated)
    );
    assert_eq!(
        Frame::new_checked(&good[..good.len() - 1]).err(),
        Some(WireError::Truncated)
    );
    let mut bad = good.clone();
    bad[1] = 0xCC;
    assert_eq!(Frame::new_checked(&bad[..]).err(), Some(WireError::BadSync));
    let mut bad = good.clone();
    bad[2] = 0x7F;
    assert_eq!(
        Frame::new_checked(&bad[..]).err(),
        Some(WireError::UnknownType)
    );
    let mut bad = good.clone();
    bad[3] = 17;
    assert_eq!(
        Frame::new_checked(&bad[..]).err(),
        Some(WireError::BadLength)
    );
    let mut bad = good.clone();
    bad[10] ^= 0x40;
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::Checksum));
    // A changed sequence number is caught by the CRC too.
    let mut bad = good.clone();
    bad[5] ^= 0x01;
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::Checksum));
    // A reserved flag bit, with a valid CRC: refused as a bad field.
    let mut bad = good.clone();
    bad[HEADER_LEN + 5] = 0x08;
    refresh_crc(&mut bad);
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::BadField));
    // The 25 ft flag without altitude, and an address beyond 24 bits (or
    // without its flag): refused too.
    let mut bad = good.clone();
    bad[HEADER_LEN + 5] = 0x04;
    refresh_crc(&mut bad);
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::BadField));
    let mut bad = good.clone();
    bad[HEADER_LEN + 5] = 0x02;
    bad[HEADER_LEN + 18] = 0x01;
    refresh_crc(&mut bad);
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::BadField));
    let mut bad = good.clone();
    bad[HEADER_LEN + 21] = 0x01;
    refresh_crc(&mut bad);
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::BadField));
    // An altitude value without the altitude flag: refused too.
    let mut bad = good.clone();
    bad[HEADER_LEN + 17] = 1;
    refresh_crc(&mut bad);
    assert_eq!(Message::parse_bytes(&bad), Err(WireError::BadField));
    // Outside the envelope, with a valid CRC: x = 400.00001 km, or an
    // altitude of 126 701 ft.
    let far = cartesian(1, 40_000_001, 3, None);
    assert_eq!(
        Message::parse_bytes(&emit(&Message::Measurement(far))),
        Err(WireError::OutOfEnvelope)
    );
    let high = cartesian(1, 2, 3, Some(126_701));
    assert_eq!(
        Message::parse_bytes(&emit(&Message::Measurement(high))),
        Err(WireError::OutOfEnvelope)
    );
    let far_polar = MeasurementReport {
        time_ms: 0,
        sensor: 1,
        position: MeasuredPosition::Polar {
            range_cm: 2_882_300_000,
            azimuth_bam: 0,
        },
        altitude_ft: None,
        altitude_25ft: false,
        address: None,
    };
    assert_eq!(
        Message::parse_bytes(&emit(&Message::Measurement(far_polar))),
        Err(WireError::OutOfEnvelope)
    );
    // Extra bytes after a frame are not part of it.
    let mut longer = good.clone();
    longer.extend_from_slice(&[1, 2, 3]);
    assert!(Message::parse_bytes(&longer).is_ok());
    assert_eq!(
        Frame::new_checked(&longer[..]).unwrap().frame_len(),
        good.len()
    );
}

#[test]
fn frame_accessors_do_not_panic_on_short_buffers() {
    for len in 0..8 {
        let bytes = [0xABu8; 8];
        let f = Frame::new_unchecked(&bytes[..len]);
        let _ = (
            f.kind(),
            f.payload(),
            f.crc(),
            f.verify_crc(),
            f.frame_len(),
        );
    }
    let mut small = [0u8; 5];
    let mut f = Frame::new_unchecked(&mut small[..]);
    f.set_header(FrameKind::Health, 3);
    f.payload_mut().fill(1);
    f.fill_crc();
}

// ---------------------------------------------------------------------------
// Conversions at the edge
// ---------------------------------------------------------------------------

#[test]
fn cartesian_conversion_checks_the_envelope() {
    let at = |x_cm: i32| cartesian(0, x_cm, 0, None).position::<f64>();
    assert_eq!(
        at(40_000_000),
        Ok(Measurement::Cartesian {
            x: 400_000.0,
            y: 0.0
        })
    );
    assert_eq!(
        at(-40_000_000),
        Ok(Measurement::Cartesian {
            x: -400_000.0,
            y: 0.0
        })
    );
    assert_eq!(at(40_000_001), Err(ConversionError::PositionOutOfRange));
    assert_eq!(at(i32::MIN), Err(ConversionError::PositionOutOfRange));
    assert_eq!(
        cartesian(0, 0, 40_000_001, None).position::<Fix>(),
        Err(ConversionError::PositionOutOfRange)
    );
    // 12.34 m in Q32.32 is the nearest representable value.
    assert_eq!(
        cartesian(0, 1234, -1, None).position::<Fix>(),
        Ok(Measurement::Cartesian {
            x: Fix::from_f64_lossy(12.34),
            y: Fix::from_f64_lossy(-0.01)
        })
    );
}

#[test]
fn altitude_conversion_checks_the_mode_c_range() {
    let with = |a: i32| cartesian(0, 0, 0, Some(a)).altitude::<f32>();
    assert_eq!(with(-1000), Ok(Some(-1000.0)));
    assert_eq!(with(126_700), Ok(Some(126_700.0)));
    assert_eq!(with(-1001), Err(ConversionError::AltitudeOutOfRange));
    assert_eq!(with(126_701), Err(ConversionError::AltitudeOutOfRange));
    assert_eq!(cartesian(0, 0, 0, None).altitude::<f32>(), Ok(None));
}

#[test]
fn polar_conversion_uses_binary_angles() {
    let polar = |bam: u16, range_cm: u32| MeasurementReport {
        time_ms: 0,
        sensor: 1,
        position: MeasuredPosition::Polar {
            range_cm,
            azimuth_bam: bam,
        },
        altitude_ft: None,
        altitude_25ft: false,
        address: None,
    };
    // 16384 steps = a quarter turn = π/2.
    match polar(16384, 100).position::<f64>() {
        Ok(Measurement::Polar { range, azimuth }) => {
            assert_eq!(range, 1.0);
            assert_eq!(azimuth, std::f64::consts::FRAC_PI_2);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        polar(0, 40_000_001).position::<f64>(),
        Err(ConversionError::RangeOutOfRange)
    );
    // From radians: −90° is 270° = 49152 steps; a hair below 360° rounds to
    // 0; 1 m = 100 cm.
    let r = MeasurementReport::polar_from_metres(0, 1, 1.0, -std::f64::consts::FRAC_PI_2, None)
        .unwrap();
    assert_eq!(
        r.position,
        MeasuredPosition::Polar {
            range_cm: 100,
            azimuth_bam: 49152
        }
    );
    let r = MeasurementReport::polar_from_metres(0, 1, 5.0, std::f64::consts::TAU - 1e-9, None)
        .unwrap();
    assert_eq!(
        r.position,
        MeasuredPosition::Polar {
            range_cm: 500,
            azimuth_bam: 0
        }
    );
    assert_eq!(
        MeasurementReport::polar_from_metres(0, 1, -1.0, 0.0, None),
        Err(ConversionError::RangeOutOfRange)
    );
    assert_eq!(
        MeasurementReport::polar_from_metres(0, 1, f64::NAN, 0.0, None),
        Err(ConversionError::NotRepresentable)
    );
}

#[test]
fn metres_to_frames_round_to_centimetres_and_check() {
    let r = MeasurementReport::cartesian_from_metres(3, 4, 1.005, -2.004, Some(7999.6)).unwrap();
    // 1.005 m · 100 = 100.49999999999999 in f64 → 100 cm; −200.4 → −200.
    assert_eq!(
        r.position,
        MeasuredPosition::Cartesian {
            x_cm: 100,
            y_cm: -200
        }
    );
    assert_eq!(r.altitude_ft, Some(8000));
    assert_eq!(
        MeasurementReport::cartesian_from_metres(0, 0, 400_001.0, 0.0, None),
        Err(ConversionError::PositionOutOfRange)
    );
    assert_eq!(
        MeasurementReport::cartesian_from_metres(0, 0, 0.0, f64::INFINITY, None),
        Err(ConversionError::NotRepresentable)
    );
    assert_eq!(
        MeasurementReport::cartesian_from_metres(0, 0, 0.0, 0.0, Some(200_000.0)),
        Err(ConversionError::AltitudeOutOfRange)
    );
}

// ---------------------------------------------------------------------------
// Streaming decoder
// ---------------------------------------------------------------------------

/// Pushes every byte; returns the results in order and the per-push counts
/// of completed frames.
fn decode(decoder: &mut Decoder, bytes: &[u8]) -> (Vec<Result<Message, WireError>>, usize) {
    let mut out = Vec::new();
    let mut most_per_push = 0;
    for &b in bytes {
        let mut frames_now = 0;
        let mut event = decoder.push(b);
        while let Some(r) = event {
            if r.is_ok() {
                frames_now += 1;
            }
            out.push(r);
            event = decoder.poll();
        }
        most_per_push = most_per_push.max(frames_now);
    }
    (out, most_per_push)
}

fn oks(results: &[Result<Message, WireError>]) -> Vec<Message> {
    results.iter().filter_map(|r| r.ok()).collect()
}

/// The decoder's accounting invariants: every byte pushed is in an accepted
/// frame, skipped or held; every candidate decided is accepted or refused
/// for one reason.
fn assert_accounts(d: &Decoder) {
    let s = d.stats();
    assert_eq!(
        s.bytes as usize,
        s.frame_bytes as usize + s.bytes_skipped as usize + d.held(),
        "{s:?}"
    );
    assert_eq!(
        s.frames,
        s.accepted
            + s.crc_errors
            + s.unknown_type
            + s.bad_length
            + s.bad_field
            + s.out_of_envelope
            + s.truncated,
        "{s:?}"
    );
}

/// A stream of numbered frames, as an Encoder writes them.
fn numbered(messages: &[Message]) -> Vec<Vec<u8>> {
    let mut encoder = Encoder::new();
    messages
        .iter()
        .map(|m| {
            let mut buf = [0u8; MAX_FRAME_LEN];
            let n = encoder.encode(m, &mut buf).unwrap();
            buf[..n].to_vec()
        })
        .collect()
}

#[test]
fn decoder_skips_garbage_and_counts_it() {
    let a = Message::Measurement(cartesian(1, 10, 20, None));
    let b = Message::Track(track_report());
    let frames = numbered(&[a, b]);
    let mut stream = vec![0x00, 0x13, 0xAB, 0x37, 0xAB]; // 0xAB not followed by 0xCD
    stream.extend(&frames[0]);
    stream.extend([0xCD, 0xAB, 0xAB]);
    stream.extend(&frames[1]);
    let mut d = Decoder::new();
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(results, vec![Ok(a), Ok(b)]);
    assert_eq!((d.stats().frames, d.stats().accepted), (2, 2));
    assert_eq!(d.stats().bytes_skipped, 8);
    assert_eq!(d.stats().frames_lost, 0);
    assert_eq!(d.held(), 0);
    assert_accounts(&d);
}

#[test]
fn decoder_recovers_a_frame_that_started_inside_a_truncated_one() {
    // The first frame loses its last k bytes on the line; the decoder takes
    // the start of the second as the rest of the first, fails its CRC, and
    // must still find the second frame among the bytes it had taken. The
    // failed candidate holds the second frame's header: counted as a
    // truncation, not a CRC error, and the sequence numbers show
    // one frame lost.
    // (With only the last byte lost, the candidate holds one byte of the
    // next frame, too little to recognise: a CRC error.)
    for k in [2, 3, 4, 5, 12, 22] {
        let zeroth = Message::Measurement(cartesian(0, 0, 0, None));
        let first = Message::Measurement(cartesian(1, 10, 20, None));
        let second = Message::Measurement(cartesian(2, 30, 40, Some(900)));
        let frames = numbered(&[zeroth, first, second]);
        let mut stream = frames[0].clone();
        stream.extend(&frames[1][..frames[1].len() - k]);
        stream.extend(&frames[2]);
        let mut d = Decoder::new();
        let (results, _) = decode(&mut d, &stream);
        assert_eq!(oks(&results), vec![zeroth, second], "k = {k}");
        let s = d.stats();
        assert_eq!((s.truncated, s.crc_errors), (1, 0), "k = {k}: {s:?}");
        assert_eq!(s.bytes_skipped as usize, frames[1].len() - k);
        assert_eq!(s.frames_lost, 1);
        assert_accounts(&d);
    }
}

#[test]
fn decoder_refuses_a_bad_header_at_once() {
    let good = Message::Measurement(cartesian(5, 6, 7, None));
    let mut d = Decoder::new();
    // A corrupted length byte is refused on arrival, so the following frame
    // is not swallowed.
    let mut stream = vec![0xAB, 0xCD, 0x01, 200];
    stream.extend(emit(&good));
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(results, vec![Err(WireError::BadLength), Ok(good)]);
    let mut stream = vec![0xAB, 0xCD, 0x55];
    stream.extend(emit(&good));
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(results, vec![Err(WireError::UnknownType), Ok(good)]);
    assert_eq!(d.stats().bad_length, 1);
    assert_eq!(d.stats().unknown_type, 1);
    assert_eq!((d.stats().frames, d.stats().accepted), (4, 2));
    assert_accounts(&d);
}

#[test]
fn decoder_reports_crc_errors() {
    let mut bytes = emit(&Message::Measurement(cartesian(5, 6, 7, None)));
    bytes[12] ^= 0x01;
    let mut d = Decoder::new();
    let (results, _) = decode(&mut d, &bytes);
    assert_eq!(results, vec![Err(WireError::Checksum)]);
    assert_eq!(d.stats().crc_errors, 1);
    assert_eq!(d.stats().bytes_skipped as usize, bytes.len());
    assert_accounts(&d);
}

/// Ten measurement messages, a second apart, and their frames numbered
/// 0 to 9.
fn ten_numbered_measurements() -> (Vec<Message>, Vec<Vec<u8>>) {
    let messages: Vec<Message> = (0..10)
        .map(|k| Message::Measurement(cartesian(k * 1000, 100 * k as i32, 0, None)))
        .collect();
    let frames = numbered(&messages);
    (messages, frames)
}

#[test]
fn decoder_counts_lost_frames_from_the_sequence_numbers() {
    let (messages, frames) = ten_numbered_measurements();
    // Frames 3, 4 and 7 never arrive; frame 8 arrives corrupted.
    let mut stream = Vec::new();
    for (k, f) in frames.iter().enumerate() {
        match k {
            3 | 4 | 7 => {}
            8 => {
                let mut bad = f.clone();
                bad[HEADER_LEN] ^= 0x80;
                stream.extend(bad);
            }
            _ => stream.extend(f),
        }
    }
    let mut d = Decoder::new();
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(oks(&results).len(), 6);
    assert_eq!(d.stats().frames_lost, 4);
    assert_eq!(d.stats().crc_errors, 1);
    assert_eq!(d.stats().out_of_sequence, 0);
    // A repeated frame (a replay) is out of sequence; the count restarts
    // after it, so the frames after the replay do not count as lost again.
    let mut d = Decoder::new();
    let mut stream = Vec::new();
    for k in [0, 1, 2, 1, 2, 3] {
        stream.extend(&frames[k]);
    }
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(oks(&results).len(), 6);
    assert_eq!((d.stats().out_of_sequence, d.stats().frames_lost), (1, 0));
    // The sequence number wraps.
    let mut d = Decoder::new();
    let mut stream = Vec::new();
    for seq in [65534u16, 65535, 0, 2] {
        stream.extend(emit_numbered(&messages[0], seq));
    }
    decode(&mut d, &stream);
    assert_eq!((d.stats().frames_lost, d.stats().out_of_sequence), (1, 0));
}

/// Frames refused before the first accepted one have no sequence number to
/// place them: they count as lost up to the first accepted frame's number,
/// so a stream whose first frames are all damaged is not a clean one. A
/// receiver that joins a stream late (a first frame numbered 5,000 after
/// one damaged frame) counts only the refused ones; garbage before a
/// stream numbered from 0 counts none.
#[test]
fn damaged_frames_before_the_first_accepted_one_count_as_lost() {
    let (messages, frames) = ten_numbered_measurements();
    let mut stream = Vec::new();
    for (k, f) in frames.iter().enumerate() {
        let mut f = f.clone();
        if k < 6 {
            f[HEADER_LEN] ^= 0x80;
        }
        stream.extend(f);
    }
    let mut d = Decoder::new();
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(oks(&results).len(), 4);
    assert_eq!((d.stats().crc_errors, d.stats().frames_lost), (6, 6));
    assert_accounts(&d);

    let mut stream = frames[0].clone();
    stream[HEADER_LEN] ^= 0x80;
    stream.extend(emit_numbered(&messages[1], 5_000));
    let mut d = Decoder::new();
    decode(&mut d, &stream);
    assert_eq!((d.stats().crc_errors, d.stats().frames_lost), (1, 1));

    let mut stream = frames[0].clone();
    stream[HEADER_LEN] ^= 0x80;
    stream.extend(&frames[0]);
    let mut d = Decoder::new();
    decode(&mut d, &stream);
    assert_eq!((d.stats().crc_errors, d.stats().frames_lost), (1, 0));
}

/// The finding: "A fuzzer built a CRC-16 collision that made up a polar
/// measurement at 28,823 km and swallowed the real frame behind it,
/// counting nothing." Rebuilt with CRC-32C: a polar frame at 28,823 km whose
/// CRC (forged by solving for four payload bytes) is the next real frame's
/// first four bytes. The made-up frame passes the CRC, fails the envelope,
/// and the real frame inside it is found.
#[test]
fn a_made_up_frame_does_not_swallow_the_real_one() {
    let real = Message::Measurement(cartesian(2000, 150_000, -70_000, None));
    let real_bytes = emit_numbered(&real, 7);
    // Header (6 bytes) and 20 payload bytes of a polar frame; its 4 CRC
    // bytes are the real frame's sync, type and length.
    let mut fake = vec![0xAB, 0xCD, 0x02, 20, 0x00, 0x06];
    let mut payload = [0u8; 20];
    payload[6..10].copy_from_slice(&2_882_300_000u32.to_be_bytes());
    fake.extend_from_slice(&payload);
    let target = u32::from_be_bytes(real_bytes[0..4].try_into().unwrap());
    // The time field (payload bytes 0..4) is free: CRC-32C is affine in
    // those 32 bits over GF(2), so solve A·x = target ⊕ crc(0).
    let free = 6..10;
    let crc_with = |x: u32, fake: &mut Vec<u8>| {
        fake[free.clone()].copy_from_slice(&x.to_be_bytes());
        crc32c(&fake[2..])
    };
    let base = crc_with(0, &mut fake);
    let columns: Vec<u32> = (0..32)
        .map(|i| crc_with(1 << i, &mut fake) ^ base)
        .collect();
    let x = solve_gf2(&columns, target ^ base).expect("the CRC can be forged");
    assert_eq!(crc_with(x, &mut fake), target);
    let mut stream = fake;
    stream.extend(&real_bytes);
    // The made-up frame is a complete frame with a valid CRC.
    let made_up = Frame::new_checked(&stream[..]).unwrap();
    assert!(made_up.verify_crc());
    assert_eq!(Message::parse(&made_up), Err(WireError::OutOfEnvelope));

    let mut d = Decoder::new();
    let (results, _) = decode(&mut d, &stream);
    assert_eq!(oks(&results), vec![real]);
    assert_eq!(d.stats().out_of_envelope, 1);
    assert_accounts(&d);
}

/// Solves Σ xᵢ·columnsᵢ = target over GF(2) (32 unknowns).
fn solve_gf2(columns: &[u32], target: u32) -> Option<u32> {
    // Rows: one per output bit, 32 unknowns + the right-hand side.
    let mut rows: Vec<(u32, u32)> = (0..32)
        .map(|bit| {
            let mut row = 0u32;
            for (i, c) in columns.iter().enumerate() {
                row |= ((c >> bit) & 1) << i;
            }
            (row, (target >> bit) & 1)
        })
        .collect();
    let mut pivot_row = 0;
    let mut pivots = Vec::new();
    for col in 0..32 {
        let Some(r) = (pivot_row..32).find(|&r| rows[r].0 >> col & 1 == 1) else {
            continue;
        };
        rows.swap(pivot_row, r);
        for r in 0..32 {
            if r != pivot_row && rows[r].0 >> col & 1 == 1 {
                rows[r].0 ^= rows[pivot_row].0;
                rows[r].1 ^= rows[pivot_row].1;
            }
        }
        pivots.push((pivot_row, col));
        pivot_row += 1;
    }
    if rows[pivot_row..]
        .iter()
        .any(|&(row, rhs)| row == 0 && rhs == 1)
    {
        return None;
    }
    let mut x = 0u32;
    for (r, col) in pivots {
        x |= rows[r].1 << col;
    }
    Some(x)
}

fn any_message() -> impl Strategy<Value = Message> {
    let alt = prop::option::of(-1000i32..126_700);
    let coordinate = -40_000_000i32..=40_000_000;
    let measurement = (
        any::<u32>(),
        any::<u8>(),
        any::<bool>(),
        coordinate.clone(),
        coordinate,
        0u32..=40_000_000,
        any::<u16>(),
        alt,
    )
        .prop_map(|(t, s, polar, x, y, r, b, a)| {
            Message::Measurement(MeasurementReport {
                time_ms: t,
                sensor: s,
                position: if polar {
                    MeasuredPosition::Polar {
                        range_cm: r,
                        azimuth_bam: b,
                    }
                } else {
                    MeasuredPosition::Cartesian { x_cm: x, y_cm: y }
                },
                altitude_ft: a,
                altitude_25ft: false,
                address: None,
            })
        });
    let track = (
        any::<u32>(),
        any::<u32>(),
        0u8..3,
        0u8..4,
        prop::option::of((any::<i32>(), any::<i16>())),
        prop::option::of(any::<u16>()),
        [any::<i32>(); 4],
    )
        .prop_map(|(t, id, st, adv, alt, tau, v)| {
            let status = [
                TrackStatus::Tentative,
                TrackStatus::Confirmed,
                TrackStatus::Coasting,
            ][st as usize];
            let advisory = [
                Advisory::None,
                Advisory::ProximateTraffic,
                Advisory::Traffic,
                Advisory::Resolution,
            ][adv as usize];
            Message::Track(TrackReport {
                time_ms: t,
                track_id: id,
                status,
                advisory,
                sensitivity: Some(SensitivityLevel::Sl4),
                x_cm: v[0],
                y_cm: v[1],
                vx_cm_per_s: v[2],
                vy_cm_per_s: v[3],
                altitude: alt,
                range_tau_ds: tau,
                address: ModeSAddress::new(t & 0x00FF_FFFF),
                ra: (advisory == Advisory::Resolution).then_some(RaCode {
                    sense: if id % 2 == 0 {
                        RaSense::Up
                    } else {
                        RaSense::Down
                    },
                    strength: RaStrength::Positive,
                }),
            })
        });
    let scan = (
        any::<u32>(),
        any::<u32>(),
        0u8..4,
        [any::<u16>(); ScanCounts::LEN],
    )
        .prop_map(|(t, i, adv, c)| {
            Message::Scan(ScanSummary {
                time_ms: t,
                interval_ms: i,
                counts: ScanCounts::from_values(c),
                highest_advisory: [
                    Advisory::None,
                    Advisory::ProximateTraffic,
                    Advisory::Traffic,
                    Advisory::Resolution,
                ][adv as usize],
                ra: None,
                clear_of_conflict: t % 2 == 0,
            })
        });
    let health = (
        any::<u32>(),
        [any::<u32>(); DecoderStats::LEN],
        [any::<u32>(); IntakeCounters::LEN],
        [any::<u32>(); LoopCounters::LEN],
        [any::<u32>(); TableStats::LEN],
    )
        .prop_map(|(t, d, i, l, s)| {
            Message::Health(Health {
                time_ms: t,
                decoder: DecoderStats::from_values(d),
                intake: IntakeCounters::from_values(i),
                scan: LoopCounters::from_values(l),
                table: TableStats::from_values(s),
            })
        });
    prop_oneof![measurement, track, scan, health]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// emit then parse gives the message back.
    #[test]
    fn every_message_round_trips(m in any_message(), seq in any::<u16>()) {
        let bytes = emit_numbered(&m, seq);
        prop_assert_eq!(Message::parse_bytes(&bytes), Ok(m));
    }

    /// Any byte sequence: no panic, and every byte pushed is accounted for:
    /// in a returned frame, skipped, or still held; every candidate is
    /// accepted or refused for one reason.
    #[test]
    fn decoder_never_panics_and_accounts_for_every_byte(
        bytes in prop::collection::vec(any::<u8>(), 0..600)
    ) {
        let mut d = Decoder::new();
        let (results, most) = decode(&mut d, &bytes);
        let in_frames: usize = oks(&results).iter().map(|m| m.buffer_len()).sum();
        prop_assert_eq!(in_frames + d.stats().bytes_skipped as usize + d.held(), bytes.len());
        prop_assert!(d.held() < MAX_FRAME_LEN);
        prop_assert!(most <= MAX_FRAMES_PER_BYTE);
        assert_accounts(&d);
    }

    /// Random bytes biased towards the sync bytes and the valid headers, so
    /// that false candidates of every kind occur often.
    #[test]
    fn decoder_survives_sync_heavy_noise(
        bytes in prop::collection::vec(
            prop_oneof![
                Just(0xABu8), Just(0xCD), Just(0x01), Just(0x02), Just(0x81), Just(0x82),
                Just(0x84), Just(18), Just(16), Just(36), Just(46), any::<u8>()
            ],
            0..800,
        )
    ) {
        let mut d = Decoder::new();
        let (results, most) = decode(&mut d, &bytes);
        let in_frames: usize = oks(&results).iter().map(|m| m.buffer_len()).sum();
        prop_assert_eq!(in_frames + d.stats().bytes_skipped as usize + d.held(), bytes.len());
        prop_assert!(most <= MAX_FRAMES_PER_BYTE);
        while d.line_idle().is_some() {}
        prop_assert_eq!(d.held(), 0);
        assert_accounts(&d);
    }

    /// Valid frames with garbage (free of the first sync byte) between them:
    /// every frame comes out, in order, and exactly the garbage is skipped.
    #[test]
    fn decoder_finds_every_frame_between_garbage(
        parts in prop::collection::vec(
            (any_message(), prop::collection::vec(any::<u8>().prop_filter("no sync", |b| *b != 0xAB), 0..20)),
            1..20,
        )
    ) {
        let messages: Vec<Message> = parts.iter().map(|(m, _)| *m).collect();
        let frames = numbered(&messages);
        let mut stream = Vec::new();
        let mut garbage = 0;
        for ((_, g), f) in parts.iter().zip(&frames) {
            stream.extend_from_slice(g);
            garbage += g.len();
            stream.extend(f);
        }
        let mut d = Decoder::new();
        let (results, _) = decode(&mut d, &stream);
        prop_assert_eq!(oks(&results), messages);
        prop_assert_eq!(d.stats().bytes_skipped as usize, garbage);
        prop_assert_eq!(d.stats().frames_lost, 0);
        assert_accounts(&d);
    }
}

proptest! {
    // A fixed seed: the property below fails, legitimately, when the bytes
    // of a damaged frame and its successors happen to carry a matching CRC
    // (probability 2⁻³² per false candidate); a fixed set of cases keeps
    // the test command repeatable.
    #![proptest_config(ProptestConfig {
        cases: 512,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xAB7C_0001),
        ..ProptestConfig::default()
    })]

    /// One frame truncated anywhere: the frames after the damage are all
    /// recovered, once the line has gone idle (until then the decoder cannot
    /// tell a truncated frame from one still arriving), and the damage is
    /// counted as a truncation, never as a CRC error.
    #[test]
    fn decoder_resynchronises_after_a_truncated_frame(
        before in any_message(),
        cut in 1usize..160,
        after in prop::collection::vec(any_message(), 1..5),
    ) {
        let mut all = vec![before];
        all.extend(after.iter().copied());
        let frames = numbered(&all);
        let cut = cut.min(frames[0].len() - 1);
        let mut stream = frames[0][..cut].to_vec();
        for f in &frames[1..] {
            stream.extend(f);
        }
        // Not a truncation at all if the bytes that follow are the missing
        // ones (e.g. a lost last CRC byte equal to the next sync byte).
        prop_assume!(!stream[cut..].starts_with(&frames[0][cut..]));
        let mut d = Decoder::new();
        let (mut results, _) = decode(&mut d, &stream);
        while let Some(r) = d.line_idle() {
            results.push(r);
        }
        prop_assert_eq!(d.held(), 0);
        prop_assert_eq!(oks(&results), after);
        let s = d.stats();
        // (A lone first sync byte is not a candidate yet.)
        if cut >= 2 {
            prop_assert!(s.frames > s.accepted);
        }
        // A cut inside the header is refused by the header checks; a cut
        // that leaves two or more of the next frame's bytes inside the
        // candidate is a truncation, never a CRC error.
        if cut >= HEADER_LEN && frames[0].len() - cut >= 2 {
            prop_assert_eq!(s.crc_errors, 0);
            prop_assert!(s.truncated >= 1);
        }
        assert_accounts(&d);
    }
}

#[test]
fn line_idle_abandons_a_partial_frame() {
    let whole = emit(&Message::Measurement(cartesian(1, 2, 3, None)));
    let mut d = Decoder::new();
    let (results, _) = decode(&mut d, &whole[..10]);
    assert!(results.is_empty());
    assert_eq!(d.held(), 10);
    assert_eq!(d.line_idle(), Some(Err(WireError::Truncated)));
    // The 9 bytes after the first hold no frame start: skipped by the next
    // call, which then has nothing left.
    assert_eq!(d.line_idle(), None);
    assert_eq!(d.held(), 0);
    assert_eq!(d.stats().truncated, 1);
    assert_eq!(d.stats().bytes_skipped, 10);
    // Then a whole frame decodes normally.
    let (results, _) = decode(&mut d, &whole);
    assert_eq!(oks(&results).len(), 1);
    assert_accounts(&d);
}
