//! Static construction and memory figures.

use super::support;

use std::mem::size_of;
use std::sync::Mutex;

use abtrack::num::fixed32::Fixed32;
use abtrack::track::defaults::DefaultCartesianTrack;
use abtrack::track::{
    Association, FixedGainTrack, Observation, PredictedState, ScanInterval, Track, TrackFilter,
    TrackStatus,
};
use abtrack::ScaledScalar;
use abtrack::{FilterError, Fix};
use support::{cart, default_config, Table};

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

/// Bytes per track slot and per table as `docs/track-table.md` documents
/// them (generated there by this test's output).
#[test]
fn bytes_per_track() {
    let per_track = [
        ("f64", size_of::<Option<Track<f64, FixedGainTrack<f64>>>>()),
        ("f32", size_of::<Option<Track<f32, FixedGainTrack<f32>>>>()),
        ("q32", size_of::<Option<Track<Fix, FixedGainTrack<Fix>>>>()),
        (
            "fixed",
            size_of::<Option<Track<Fixed32, FixedGainTrack<Fixed32>>>>(),
        ),
        (
            "scaled",
            size_of::<Option<Track<ScaledScalar, FixedGainTrack<ScaledScalar>>>>(),
        ),
    ];
    let filters = [
        ("f64", size_of::<FixedGainTrack<f64>>()),
        ("f32", size_of::<FixedGainTrack<f32>>()),
        ("q32", size_of::<FixedGainTrack<Fix>>()),
        ("fixed", size_of::<FixedGainTrack<Fixed32>>()),
        ("scaled", size_of::<FixedGainTrack<ScaledScalar>>()),
    ];
    println!("bytes per track slot, Option<Track<_, FixedGainTrack<_>>>: {per_track:?}");
    println!("of which FixedGainTrack<_>: {filters:?}");
    // The target: a 2-D αβ track with its lifecycle in at most 64
    // bytes in f32 and in the fast fixed point.
    assert_eq!(
        per_track,
        [
            ("f64", 88),
            ("f32", 56),
            ("q32", 88),
            ("fixed", 56),
            ("scaled", 84)
        ]
    );
    assert_eq!(
        filters,
        [
            ("f64", 64),
            ("f32", 32),
            ("q32", 64),
            ("fixed", 32),
            ("scaled", 60)
        ]
    );
    // The record header (id, two times, history, hits, scans, lifecycle,
    // misses, refusals): 23 bytes, padded with the filter.
    assert_eq!(size_of::<Option<Track<f32, Tiny>>>(), 24);

    // The whole table, rounded up to its alignment (8).
    let round = |b: usize| b.div_ceil(8) * 8;
    let f64_bytes = |n: usize, m: usize| round(68 + 143 * n + 182 * m);
    let f32_bytes = |n: usize, m: usize| round(64 + 111 * n + 126 * m);
    let fixed_bytes = |n: usize, m: usize| round(64 + 111 * n + 134 * m);
    let scaled_bytes = |n: usize, m: usize| round(64 + 139 * n + 166 * m);
    let tables = [
        ("f64", size_of::<Table<f64, 32, 32>>()),
        ("f32", size_of::<Table<f32, 32, 32>>()),
        ("q32", size_of::<Table<Fix, 32, 32>>()),
        ("fixed", size_of::<Table<Fixed32, 32, 32>>()),
        ("scaled", size_of::<Table<ScaledScalar, 32, 32>>()),
    ];
    println!("TrackTable<_, FixedGainTrack<_>, 32, 32>: {tables:?}");
    assert_eq!(
        tables,
        [
            ("f64", f64_bytes(32, 32)),
            ("f32", f32_bytes(32, 32)),
            ("q32", f64_bytes(32, 32)),
            ("fixed", fixed_bytes(32, 32)),
            ("scaled", scaled_bytes(32, 32)),
        ]
    );
    assert_eq!(size_of::<Table<f64, 8, 16>>(), f64_bytes(8, 16));
    assert_eq!(size_of::<Table<f64, 3, 1>>(), f64_bytes(3, 1));
    assert_eq!(size_of::<Table<Fix, 64, 8>>(), f64_bytes(64, 8));
    assert_eq!(size_of::<Table<f32, 8, 16>>(), f32_bytes(8, 16));
    assert_eq!(size_of::<Table<f32, 64, 8>>(), f32_bytes(64, 8));
    assert_eq!(size_of::<Table<f32, 5, 3>>(), f32_bytes(5, 3));
    assert_eq!(size_of::<Table<Fixed32, 64, 24>>(), fixed_bytes(64, 24));
    assert_eq!(size_of::<Table<Fixed32, 3, 5>>(), fixed_bytes(3, 5));
    assert_eq!(size_of::<Table<Fixed32, 256, 256>>(), fixed_bytes(256, 256));
    assert_eq!(size_of::<Table<ScaledScalar, 8, 12>>(), scaled_bytes(8, 12));
    assert_eq!(size_of::<Table<ScaledScalar, 3, 5>>(), scaled_bytes(3, 5));
    assert_eq!(size_of::<Table<ScaledScalar, 1, 2>>(), scaled_bytes(1, 2));
    assert_eq!(
        size_of::<Table<ScaledScalar, 256, 256>>(),
        scaled_bytes(256, 256)
    );
}

/// A filter of one byte, to weigh the record header alone.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Tiny(u8);

impl TrackFilter<f32> for Tiny {
    type Params = ();
    type Step = ScanInterval<f32>;
    fn step(_: &(), i: &ScanInterval<f32>) -> Result<ScanInterval<f32>, FilterError> {
        Ok(*i)
    }
    fn interval_of(step: &ScanInterval<f32>) -> &ScanInterval<f32> {
        step
    }
    fn empty(_: &()) -> Self {
        Tiny(0)
    }
    fn update(
        &mut self,
        _: &(),
        _: &Observation<f32>,
        _: &ScanInterval<f32>,
    ) -> Result<(), FilterError> {
        Ok(())
    }
    fn coast(&mut self, _: &(), _: &ScanInterval<f32>) -> Result<(), FilterError> {
        Ok(())
    }
    fn predict(&self, _: &(), _: &ScanInterval<f32>) -> Result<PredictedState<f32>, FilterError> {
        Err(FilterError::Saturated)
    }
    fn position(&self) -> [f32; 2] {
        [0.0; 2]
    }
    fn velocity(&self) -> [f32; 2] {
        [0.0; 2]
    }
    fn predicted_variance_ratio(&self, _: &(), _: &ScanInterval<f32>) -> Option<f32> {
        None
    }
    fn gate_alpha(&self, _: &()) -> f32 {
        1.0
    }
}

/// Bytes per track slot of every track filter in every number system it
/// runs in (the table in `docs/track-table.md`; the range–azimuth filter
/// runs in the floats and Q32.32 only). A scheduled track carries the two
/// intervals of robust_gains (the last one and the reference).
#[test]
fn bytes_per_track_of_every_filter() {
    use abtrack::gain::al_wagih::{FixedGains, LeastSquaresGains};
    use abtrack::gain::li::LiImprovedGains;
    use abtrack::gain::tcas::FirmnessGains;
    use abtrack::gain::AnySchedule;
    use abtrack::track::{RangeAzimuthTrack, ScheduledTrack};
    type Slot<S, F> = Option<Track<S, F>>;
    macro_rules! row {
        ($name:expr, $f:ident $(, $g:ident)?) => {
            (
                $name,
                size_of::<Slot<f64, $f<f64 $(, $g)?>>>(),
                size_of::<Slot<f32, $f<f32 $(, $g)?>>>(),
                size_of::<Slot<Fix, $f<Fix $(, $g)?>>>(),
                size_of::<Slot<Fixed32, $f<Fixed32 $(, $g)?>>>(),
            )
        };
    }
    let rows = [
        row!("FixedGainTrack", FixedGainTrack),
        row!(
            "ScheduledTrack, M2 least squares",
            ScheduledTrack,
            LeastSquaresGains
        ),
        row!(
            "ScheduledTrack, TCAS firmness",
            ScheduledTrack,
            FirmnessGains
        ),
        (
            "ScheduledTrack, M1 fixed gains",
            size_of::<Slot<f64, ScheduledTrack<f64, FixedGains<f64>>>>(),
            size_of::<Slot<f32, ScheduledTrack<f32, FixedGains<f32>>>>(),
            size_of::<Slot<Fix, ScheduledTrack<Fix, FixedGains<Fix>>>>(),
            size_of::<Slot<Fixed32, ScheduledTrack<Fixed32, FixedGains<Fixed32>>>>(),
        ),
        (
            "ScheduledTrack, Li",
            size_of::<Slot<f64, ScheduledTrack<f64, LiImprovedGains<f64>>>>(),
            size_of::<Slot<f32, ScheduledTrack<f32, LiImprovedGains<f32>>>>(),
            size_of::<Slot<Fix, ScheduledTrack<Fix, LiImprovedGains<Fix>>>>(),
            size_of::<Slot<Fixed32, ScheduledTrack<Fixed32, LiImprovedGains<Fixed32>>>>(),
        ),
        (
            "ScheduledTrack, any schedule (windows of 8)",
            size_of::<Slot<f64, ScheduledTrack<f64, AnySchedule<f64, 2, 8>>>>(),
            size_of::<Slot<f32, ScheduledTrack<f32, AnySchedule<f32, 2, 8>>>>(),
            size_of::<Slot<Fix, ScheduledTrack<Fix, AnySchedule<Fix, 2, 8>>>>(),
            size_of::<Slot<Fixed32, ScheduledTrack<Fixed32, AnySchedule<Fixed32, 2, 8>>>>(),
        ),
        (
            "AutoFilter, auto fused (the default Cartesian track)",
            size_of::<Slot<f64, DefaultCartesianTrack<f64>>>(),
            size_of::<Slot<f32, DefaultCartesianTrack<f32>>>(),
            size_of::<Slot<Fix, DefaultCartesianTrack<Fix>>>(),
            size_of::<Slot<Fixed32, DefaultCartesianTrack<Fixed32>>>(),
        ),
        (
            "RangeAzimuthTrack",
            size_of::<Slot<f64, RangeAzimuthTrack<f64>>>(),
            size_of::<Slot<f32, RangeAzimuthTrack<f32>>>(),
            size_of::<Slot<Fix, RangeAzimuthTrack<Fix>>>(),
            0,
        ),
    ];
    println!("| filter | f64 | f32 | q32 | fixed |");
    println!("|---|---|---|---|---|");
    for (name, a, b, c, d) in rows {
        let d = if d == 0 {
            "—".to_string()
        } else {
            d.to_string()
        };
        println!("| {name} | {a} | {b} | {c} | {d} |");
    }
    assert_eq!(
        rows,
        [
            ("FixedGainTrack", 88, 56, 88, 56),
            ("ScheduledTrack, M2 least squares", 240, 144, 240, 144),
            ("ScheduledTrack, TCAS firmness", 240, 144, 240, 144),
            ("ScheduledTrack, M1 fixed gains", 264, 152, 264, 164),
            ("ScheduledTrack, Li", 288, 168, 288, 180),
            (
                "ScheduledTrack, any schedule (windows of 8)",
                880,
                480,
                880,
                528
            ),
            (
                "AutoFilter, auto fused (the default Cartesian track)",
                112,
                68,
                112,
                88
            ),
            ("RangeAzimuthTrack", 272, 152, 272, 0),
        ]
    );
}
