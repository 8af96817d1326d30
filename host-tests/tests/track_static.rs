//! Static construction and memory figures.

mod track_support;

use std::mem::size_of;
use std::sync::Mutex;

use abtrack::track::{Association, FixedGainTrack, Track, TrackStatus};
use abtrack::Fix;
use track_support::{cart, default_config, Table};

/// The firmware's shape: a table in a `static`, behind a lock.
static TABLE: Mutex<Table<Fix, 32, 32>> = Mutex::new(Table::new());

/// And as a constant (every field built by `const fn`).
const EMPTY: Table<f32, 4, 4> = Table::new();

#[test]
fn static_table_tracks() {
    let config = default_config::<Fix>();
    let mut table = TABLE.lock().unwrap();
    let mut codes = [Association::OutsideGates; 1];
    for k in 0..3u32 {
        let t = k * 1000;
        table
            .scan(&config, t, &[cart(100.0 * k as f64, 0.0)], &mut codes)
            .unwrap();
    }
    let track = table.tracks().next().unwrap();
    assert_eq!(track.status(), TrackStatus::Confirmed);
    assert_eq!(table.capacity(), 32);
}

#[test]
fn const_table_is_empty() {
    let mut t = EMPTY;
    assert!(t.is_empty());
    assert_eq!(t.max_measurements(), 4);
    let config = default_config::<f32>();
    let mut codes = [Association::OutsideGates; 1];
    t.scan(&config, 0, &[cart(0.0, 0.0)], &mut codes).unwrap();
    assert_eq!(t.pending(), 1);
    // The constant itself is untouched (each use is a fresh copy).
    assert_eq!(EMPTY.pending(), 0);
}

#[test]
fn bytes_per_track() {
    let per_track = [
        ("f64", size_of::<Option<Track<f64, FixedGainTrack<f64>>>>()),
        ("f32", size_of::<Option<Track<f32, FixedGainTrack<f32>>>>()),
        (
            "fixed",
            size_of::<Option<Track<Fix, FixedGainTrack<Fix>>>>(),
        ),
    ];
    let tables = [
        ("f64", size_of::<Table<f64, 32, 32>>()),
        ("f32", size_of::<Table<f32, 32, 32>>()),
        ("fixed", size_of::<Table<Fix, 32, 32>>()),
    ];
    println!("bytes per track slot: {per_track:?}");
    println!("TrackTable<_, FixedGainTrack<_>, 32, 32>: {tables:?}");
    // The figures documented in abtrack::track (module docs, "Memory").
    assert_eq!(per_track, [("f64", 184), ("f32", 112), ("fixed", 184)]);
    assert_eq!(size_of::<FixedGainTrack<f64>>(), 160);
    assert_eq!(size_of::<FixedGainTrack<f32>>(), 88);
    assert_eq!(size_of::<abtrack::Cartesian<f64, 2, 2>>(), 128);
    assert_eq!(size_of::<abtrack::Cartesian<f32, 2, 2>>(), 72);
    // The documented formulas, rounded up to the table's alignment (8).
    let round = |b: usize| b.div_ceil(8) * 8;
    let f64_bytes = |n: usize, m: usize| round(56 + 239 * n + 154 * m);
    let f32_bytes = |n: usize, m: usize| round(56 + 167 * n + 114 * m);
    assert_eq!(
        tables,
        [
            ("f64", f64_bytes(32, 32)),
            ("f32", f32_bytes(32, 32)),
            ("fixed", f64_bytes(32, 32))
        ]
    );
    assert_eq!(size_of::<Table<f64, 8, 16>>(), f64_bytes(8, 16));
    assert_eq!(size_of::<Table<f64, 3, 1>>(), f64_bytes(3, 1));
    assert_eq!(size_of::<Table<Fix, 64, 8>>(), f64_bytes(64, 8));
    assert_eq!(size_of::<Table<f32, 8, 16>>(), f32_bytes(8, 16));
    assert_eq!(size_of::<Table<f32, 64, 8>>(), f32_bytes(64, 8));
    assert_eq!(size_of::<Table<f32, 5, 3>>(), f32_bytes(5, 3));
}
