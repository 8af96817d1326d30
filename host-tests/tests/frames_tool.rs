//! The `frames` tool's library side: CSV and scenario input to frames, and
//! the summary of a report stream.

use abtrack::wire::{MeasuredPosition, MeasurementReport, Message};
use abtrack_host_tests::frames::{self, Faults};

#[test]
fn cartesian_csv_becomes_reports() {
    let csv = "t,x,y\n0,1.5,-2\n0, 100.004 ,3\n\n1.25,-4,5\n";
    let r = frames::reports_from_csv(csv, 9).unwrap();
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
        }
    );
    assert_eq!(r[2].time_ms, 1250);
}

#[test]
fn polar_csv_with_and_without_altitude() {
    let csv = "t,range,azimuth,alt\n2,1000,3.141592653589793,7500\n2,2000,0,\n";
    let r = frames::reports_from_csv(csv, 1).unwrap();
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

#[test]
fn bad_csv_names_the_line() {
    let err = |csv: &str| frames::reports_from_csv(csv, 1).unwrap_err();
    assert!(err("").contains("empty"));
    assert!(err("t,a,b\n").contains("line 1"));
    assert!(err("t,x,y\n0,1,2\n0,1\n").contains("line 3"));
    assert!(err("t,x,y\n0,1,nan\n").contains("line 2, column 3"));
    assert!(err("t,x,y\n2,1,1\n1,1,1\n").contains("line 3"));
    assert!(err("t,x,y\n0,500000,0\n").contains("400 km"));
}

#[test]
fn encoded_faults_are_what_the_decoder_counts() {
    let reports = frames::scenario_reports("two-crossing", 1, 1).unwrap();
    let clean = frames::encode(&reports, Faults::default());
    assert_eq!(clean.frames, reports.len());
    let (messages, stats) = frames::decode_all(&clean.bytes);
    assert_eq!(messages.len(), reports.len());
    assert_eq!((stats.crc_errors, stats.bytes_skipped), (0, 0));
    assert!(messages
        .iter()
        .zip(&reports)
        .all(|(m, r)| *m == Message::Measurement(*r)));

    let faults = Faults {
        corrupt_every: Some(10),
        garbage_every: Some(7),
        seed: 3,
    };
    let dirty = frames::encode(&reports, faults);
    let (messages, stats) = frames::decode_all(&dirty.bytes);
    assert_eq!(messages.len(), dirty.frames - dirty.corrupted);
    assert_eq!(stats.crc_errors as usize, dirty.corrupted);
    // Measurement frames of the Cartesian scenario are 28 bytes.
    assert_eq!(
        stats.bytes_skipped as usize,
        dirty.garbage_bytes + 28 * dirty.corrupted
    );
    // The summary of a measurement stream counts them.
    let s = frames::summarise(&dirty.bytes);
    assert_eq!(s.measurements, messages.len());
    assert!(s.to_text().contains("CRC errors"));
}
