//! Regression tests for what the fuzz targets (fuzz/properties/) found,
//! one per finding, written from the minimised input (docs/safety.md lists
//! the findings and their inputs under fuzz/corpus/).
//!
//! F1 (tracker_scan, `fuzz/corpus/tracker_scan/finding-outside-gates-empty-scan`):
//! `ScanReport::outside_gates` counts the table's unused measurement slots,
//! not measurements: a scan with no measurement reported `M` of them.
//! Fixed in track/table.rs ("Counters that lie": only this scan's
//! codes are counted).
//!
//! F2 (csv_recording, `fuzz/corpus/csv_recording/finding-lone-cr-shares-a-line`):
//! a lone carriage return ends a CSV record (as CRLF and LF do) without
//! starting a new `\n` line, so two rows can carry the same line number;
//! the target's property asked for strictly growing line numbers. The
//! reader is right (it accepts the file, and a line number points at the
//! line an editor counting `\n` shows); the property is now non-decreasing.

use abtrack_firmware::demo_config;
use abtrack_host_tests::csv_input::{read_recording, AngleUnit, ReadOptions, Recording, TimeOrder};

use abtrack::track::{Association, FixedGainTrack, Measurement, TrackTable};

type Table = TrackTable<f32, FixedGainTrack<f32>, 8, 16>;

fn scan(
    table: &mut Table,
    now_ms: u32,
    measurements: &[Measurement<f32>],
) -> (u32, Vec<Association>) {
    let config = demo_config::crossing_config::<f32, _>()
        .expect("the demo configuration is valid")
        .tracker;
    let mut codes = vec![Association::NotAssigned; measurements.len()];
    let report = table
        .scan(&config, now_ms, measurements, &mut codes)
        .expect("times increase");
    (report.outside_gates, codes)
}

#[test]
fn f1_outside_gates_counts_measurements_not_free_slots() {
    let mut table: Box<Table> = Box::new(TrackTable::new());
    // The fuzzer's input: one scan, no measurement.
    let (outside, _) = scan(&mut table, 1, &[]);
    assert_eq!(
        outside, 0,
        "a scan with no measurement has none outside the gates"
    );
    // Three measurements far apart, no track yet: all three are outside
    // every gate, and only they.
    let far = [(-4000.0, -4000.0), (0.0, 0.0), (4000.0, 4000.0)];
    let m: Vec<_> = far
        .iter()
        .map(|&(x, y)| Measurement::Cartesian { x, y })
        .collect();
    let (outside, codes) = scan(&mut table, 1001, &m);
    assert!(codes.iter().all(|c| *c == Association::OutsideGates));
    assert_eq!(outside, 3);
}

#[test]
fn f2_a_lone_carriage_return_ends_a_row_on_the_same_line() {
    // The fuzzer's input, after its first byte (scans, degrees).
    let bytes = b"t,range,azimuth,alt\n0,20000,45,10000\r0,21000,46,\n1,19900,45.1,10100\n";
    let options = ReadOptions {
        times: TimeOrder::Scans,
        azimuth_unit: AngleUnit::Degrees,
    };
    let Ok(Recording::RangeAzimuth(m)) = read_recording(&bytes[..], options) else {
        panic!("a range-azimuth recording is accepted");
    };
    let lines: Vec<usize> = m.rows.iter().map(|r| r.line).collect();
    assert_eq!(lines, [2, 2, 3]);
    let ranges: Vec<f64> = m.rows.iter().map(|r| r.range).collect();
    assert_eq!(ranges, [20000.0, 21000.0, 19900.0]);
    assert_eq!(m.rows[1].alt, None);
}
