//! The `frames` tool's library side: CSV and scenario input to frames, and
//! the summary of a report stream.

use abtrack::wire::{EndOfInput, FrameKind, MeasuredPosition, MeasurementReport, Message};
use abtrack_host_tests::csv_input::AngleUnit;
use abtrack_host_tests::frames::{self, Fault, Faults};

#[test]
fn cartesian_csv_becomes_reports() {
    let csv = "t,x,y\n0,1.5,-2\n0, 100.004 ,3\n\n1.25,-4,5\n";
    let r = frames::reports_from_csv(csv.as_bytes(), 9, AngleUnit::Radians).unwrap();
    assert_eq!(r.len(), 3);
    assert_eq!(
        r[1],
        MeasurementReport {
            time_ms: 0,
            sensor: 9,
            position: MeasuredPosition::Cartesian {
                x_cm: 10_000,
                y_cm: 300
            },
            altitude_ft: None,
            altitude_25ft: false,
            address: None,
        }
    );
    assert_eq!(r[2].time_ms, 1250);
}

#[test]
fn polar_csv_with_and_without_altitude() {
    let csv = "t,range,azimuth,alt\n2,1000,3.141592653589793,7500\n2,2000,0,\n";
    let r = frames::reports_from_csv(csv.as_bytes(), 1, AngleUnit::Radians).unwrap();
    assert_eq!(
        r[0].position,
        MeasuredPosition::Polar {
            range_cm: 100_000,
            azimuth_bam: 32768
        }
    );
    assert_eq!(r[0].altitude_ft, Some(7500));
    assert_eq!(r[1].altitude_ft, None);
}

/// Rows out of time order are encoded in file order: the receiver's scan
/// clock takes a late measurement (or counts it late), as from a real
/// feed.
#[test]
fn rows_out_of_time_order_are_encoded_as_they_come() {
    let reports =
        frames::reports_from_csv("t,x,y\n2,1,1\n1,1,1\n".as_bytes(), 1, AngleUnit::Radians)
            .unwrap();
    let times: Vec<u32> = reports.iter().map(|r| r.time_ms).collect();
    assert_eq!(times, [2000, 1000]);
}

#[test]
fn bad_csv_names_the_line() {
    let err =
        |csv: &str| frames::reports_from_csv(csv.as_bytes(), 1, AngleUnit::Radians).unwrap_err();
    assert!(err("").contains("empty"));
    assert!(err("t,a,b\n").contains("line 1"));
    assert!(err("t,x,y\n0,1,2\n0,1\n").contains("line 3"));
    assert!(err("t,x,y\n0,1,nan\n").contains("line 2, column 3"));
    let far = err("t,x,y\n0,500000,0\n");
    assert!(
        far.contains("line 2, column 2")
            && far.contains("outside the envelope -400000 ..= 400000 m"),
        "{far}"
    );
}

/// The shared CSV reader's conventions: columns matched by name in any
/// order, extra columns ignored, an azimuth in degrees only when asked for,
/// an altitude on Cartesian rows too; a z column (not on the wire) refused.
#[test]
fn csv_header_by_name_and_explicit_units() {
    let read = |csv: &str, unit| frames::reports_from_csv(csv.as_bytes(), 1, unit);
    let reordered = read(
        "callsign,alt,y,t,x
ABC,7500,3,0,100
",
        AngleUnit::Radians,
    )
    .unwrap();
    assert_eq!(
        reordered[0].position,
        MeasuredPosition::Cartesian {
            x_cm: 10_000,
            y_cm: 300
        }
    );
    assert_eq!(reordered[0].altitude_ft, Some(7500));
    let degrees = read(
        "t,range,azimuth
0,1000,180
",
        AngleUnit::Degrees,
    )
    .unwrap();
    assert_eq!(
        degrees[0].position,
        MeasuredPosition::Polar {
            range_cm: 100_000,
            azimuth_bam: 32768
        }
    );
    let unasked = read(
        "t,range,azimuth
0,1000,180
",
        AngleUnit::Radians,
    )
    .unwrap_err();
    assert!(
        unasked.contains("line 2, column 3") && unasked.contains("--azimuth-unit deg"),
        "{unasked}"
    );
    let z = read(
        "t,x,y,z
0,1,2,3
",
        AngleUnit::Radians,
    )
    .unwrap_err();
    assert!(z.contains("z column"), "{z}");
}

#[test]
fn encoded_faults_are_what_the_decoder_counts() {
    let reports = frames::scenario_reports("two-crossing", 1, 1).unwrap();
    let clean = frames::encode(&reports, Faults::default());
    // One numbered frame per measurement, and the end of input.
    assert_eq!(clean.frames, reports.len() + 1);
    let (messages, stats) = frames::decode_all(&clean.bytes);
    assert_eq!(messages.len(), reports.len() + 1);
    assert_eq!(
        (stats.crc_errors, stats.bytes_skipped, stats.frames_lost),
        (0, 0, 0)
    );
    assert!(messages
        .iter()
        .zip(&reports)
        .all(|(m, r)| *m == Message::Measurement(*r)));
    assert_eq!(
        messages.last(),
        Some(&Message::End(EndOfInput {
            time_ms: reports.last().unwrap().time_ms
        }))
    );

    let faults = Faults {
        corrupt_every: Some(10),
        garbage_every: Some(7),
        seed: 3,
    };
    let dirty = frames::encode(&reports, faults);
    let (messages, stats) = frames::decode_all(&dirty.bytes);
    assert_eq!(messages.len(), dirty.frames - dirty.corrupted);
    assert_eq!(stats.crc_errors as usize, dirty.corrupted);
    assert_eq!(stats.frames_lost as usize, dirty.corrupted);
    // Measurement frames of the Cartesian scenario are 32 bytes.
    assert_eq!(FrameKind::MeasurementCartesian.frame_len(), 32);
    assert_eq!(
        stats.bytes_skipped as usize,
        dirty.garbage_bytes + 32 * dirty.corrupted
    );
    // The summary of a measurement stream counts them.
    let s = frames::summarise(&dirty.bytes);
    assert_eq!(s.measurements, messages.len() - 1);
    assert!(s.to_text().contains("CRC errors"));
}

/// A clutter storm over the first scans only: the storm's scans carry the
/// whole storm's measurements, and every later scan those of the input
/// without a fault (a storm of no scan).
#[test]
fn a_short_clutter_storm_lasts_its_scans() {
    let storm = 30;
    let stream = |scans| frames::fault_stream(Fault::ClutterStorm, 24, scans, 0).unwrap();
    let (short, whole, clear) = (stream(storm), stream(frames::TCAS_DEMO_SCANS), stream(0));
    assert_eq!(short.added, frames::STORM_CLUTTER_PER_SCAN * storm);
    assert_eq!(clear.added, 0);
    let measurements = |s: &frames::FaultStream| -> Vec<MeasurementReport> {
        let (messages, stats) = frames::decode_all(&s.bytes);
        assert_eq!(stats.frames_lost, 0);
        messages
            .into_iter()
            .filter_map(|m| match m {
                Message::Measurement(r) => Some(r),
                _ => None,
            })
            .collect()
    };
    let end_ms = short.scans[storm].0;
    let expected: Vec<MeasurementReport> = measurements(&whole)
        .into_iter()
        .filter(|r| r.time_ms < end_ms)
        .chain(
            measurements(&clear)
                .into_iter()
                .filter(|r| r.time_ms >= end_ms),
        )
        .collect();
    assert_eq!(measurements(&short), expected);
    assert!(short.bytes.len() < whole.bytes.len() / 2);
}

/// Every fault stream holds what it says: the frames sent (numbered), the
/// damaged ones, the garbage; the decoder counts them.
#[test]
fn fault_streams_hold_what_they_say() {
    for fault in Fault::ALL {
        let s = frames::fault_stream(fault, 24, frames::TCAS_DEMO_SCANS, 0).unwrap();
        let (messages, stats) = frames::decode_all(&s.bytes);
        let name = fault.name();
        match fault {
            Fault::GarbageOnly => assert_eq!(stats.accepted, 0, "{name}"),
            _ => {
                assert_eq!(
                    stats.accepted as usize + stats.frames_lost as usize,
                    s.frames,
                    "{name}"
                );
                assert!(matches!(messages.last(), Some(Message::End(_))), "{name}");
            }
        }
        let damaged = s.damaged as u32;
        match fault {
            Fault::CrcErrors => assert_eq!(stats.crc_errors, damaged),
            Fault::Truncated => assert_eq!((stats.truncated, stats.crc_errors), (damaged, 0)),
            Fault::OutOfRange => assert_eq!(stats.out_of_envelope, damaged),
            Fault::Garbage | Fault::SyncGarbage => {
                assert_eq!(stats.bytes_skipped as usize, s.garbage_bytes, "{name}")
            }
            Fault::Flood => assert_eq!(s.added, 240),
            Fault::ClutterStorm => assert_eq!(
                s.added,
                frames::STORM_CLUTTER_PER_SCAN * frames::TCAS_DEMO_SCANS
            ),
            Fault::Gap => assert_eq!(
                s.scans.len(),
                frames::TCAS_DEMO_SCANS - frames::GAP_SCANS as usize
            ),
            _ => {}
        }
        assert!(
            damaged > 0
                || !matches!(
                    fault,
                    Fault::CrcErrors | Fault::Truncated | Fault::Oversize | Fault::OutOfRange
                )
        );
    }
}

/// docs/firmware-runtime.md holds the output of `frames layout` between two
/// markers: it must be the current one (regenerate it with that command).
#[test]
fn the_documented_frame_format_is_current() {
    let doc = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/firmware-runtime.md"),
    )
    .unwrap();
    let start = doc.find("<!-- frames layout -->\n").unwrap() + "<!-- frames layout -->\n".len();
    let end = doc.find("<!-- end frames layout -->").unwrap();
    assert_eq!(
        &doc[start..end],
        frames::layout_markdown(),
        "docs/firmware-runtime.md: run `cargo run --release --bin frames -- layout` in host-tests and paste its output between the markers"
    );
}
