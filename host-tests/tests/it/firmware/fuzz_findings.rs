//! Regression tests for what the fuzz targets (fuzz/fuzz_targets/) found,
//! one per finding, written from the minimised input (docs/safety.md lists
//! the findings and their inputs under fuzz/corpus/).
//!
//! F1 (tracker_scan, `fuzz/corpus/tracker_scan/finding-outside-gates-empty-scan`):
//! `ScanReport::outside_gates` counts the table's unused measurement slots,
//! not measurements: a scan with no measurement reported `M` of them.
//! Fixed in track/table.rs ("Counters that lie": only this scan's
//! codes are counted).

use abtrack_firmware::demo_config;

use abtrack::track::{Association, FixedGainTrack, Measurement, TrackTable};

type Table = TrackTable<f32, FixedGainTrack<f32>, 8, 16>;

fn scan(
    table: &mut Table,
    now_ms: u32,
    measurements: &[Measurement<f32>],
) -> (u32, Vec<Association>) {
    let config = demo_config::crossing_config::<f32>()
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
