//! Static construction and memory figures.

use super::support;

use std::mem::size_of;
use std::sync::Mutex;

use abtrack::num::fixed32::Fixed32;
use abtrack::track::defaults::DefaultCartesianTrack;
use abtrack::track::{
    Association, FixedGainTrack, Observation, PredictedState, ScanInterval, TrackFilter, TrackSlot,
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
        ("f64", size_of::<TrackSlot<f64, FixedGainTrack<f64>>>()),
        ("f32", size_of::<TrackSlot<f32, FixedGainTrack<f32>>>()),
        ("q32", size_of::<TrackSlot<Fix, FixedGainTrack<Fix>>>()),
        (
            "fixed",
            size_of::<TrackSlot<Fixed32, FixedGainTrack<Fixed32>>>(),
        ),
        (
            "scaled",
            size_of::<TrackSlot<ScaledScalar, FixedGainTrack<ScaledScalar>>>(),
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
            ("f64", 96),
            ("f32", 60),
            ("q32", 96),
            ("fixed", 60),
            ("scaled", 88)
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
    // misses, refusals): 23 bytes, padded with the filter, and the slot's
    // tag, padded to the record's alignment.
    assert_eq!(size_of::<TrackSlot<f32, Tiny>>(), 28);

    // The whole table, rounded up to its alignment (8).
    let round = |b: usize| b.div_ceil(8) * 8;
    let f64_bytes = |n: usize, m: usize| round(140 + 151 * n + 157 * m);
    let f32_bytes = |n: usize, m: usize| round(112 + 115 * n + 117 * m);
    let fixed_bytes = |n: usize, m: usize| round(120 + 115 * n + 125 * m);
    let scaled_bytes = |n: usize, m: usize| round(134 + 143 * n + 149 * m);
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

    // The default track's table in the fast fixed point (the micro:bit's
    // default-filter benchmark rows): its slot (92 bytes) and, in the
    // workspace, the part of the predicted covariance the gate keeps for
    // the update (`AutoPrediction`, two scaled numbers).
    type Default<const N: usize, const M: usize> =
        abtrack::track::TrackTable<Fixed32, abtrack::filter::auto::AutoFilter<Fixed32, 2>, N, M>;
    let default_bytes = |n: usize, m: usize| round(120 + 163 * n + 125 * m);
    println!(
        "TrackTable<Fixed32, AutoFilter<Fixed32, 2>, 32, 32>: {}",
        size_of::<Default<32, 32>>()
    );
    assert_eq!(size_of::<Default<32, 32>>(), default_bytes(32, 32));
    assert_eq!(size_of::<Default<64, 32>>(), default_bytes(64, 32));
    assert_eq!(size_of::<Default<3, 5>>(), default_bytes(3, 5));
}

/// A filter of one byte, to weigh the record header alone.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Tiny(u8);

impl TrackFilter<f32> for Tiny {
    type Params = ();
    type Step = ScanInterval<f32>;
    type GateKept = ();
    const NOTHING_KEPT: () = ();
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
/// runs in (the table in `docs/track-table.md`; the range–azimuth track of
/// the fast fixed point runs in its wide format, `ScaledScalar`). A scheduled track carries the two
/// intervals of robust_gains (the last one and the reference).
#[test]
fn bytes_per_track_of_every_filter() {
    use abtrack::gain::al_wagih::{FixedGains, LeastSquaresGains};
    use abtrack::gain::li::LiImprovedGains;
    use abtrack::gain::tcas::FirmnessGains;
    use abtrack::gain::AnySchedule;
    use abtrack::track::{RangeAzimuthTrack, ScheduledTrack};
    type Slot<S, F> = TrackSlot<S, F>;
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
            // The table of a Fixed32 scan runs in its wide format.
            size_of::<Slot<ScaledScalar, RangeAzimuthTrack<Fixed32>>>(),
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
            ("FixedGainTrack", 96, 60, 96, 60),
            ("ScheduledTrack, M2 least squares", 248, 148, 248, 148),
            ("ScheduledTrack, TCAS firmness", 248, 148, 248, 148),
            ("ScheduledTrack, M1 fixed gains", 272, 156, 272, 168),
            ("ScheduledTrack, Li", 296, 172, 296, 184),
            (
                "ScheduledTrack, any schedule (windows of 8)",
                888,
                488,
                888,
                536
            ),
            (
                "AutoFilter, auto fused (the default Cartesian track)",
                120,
                72,
                120,
                92
            ),
            ("RangeAzimuthTrack", 136, 80, 136, 128),
        ]
    );
}

/// Whether `value`'s bytes are all zero.
fn is_zero_bytes<T>(value: &T) -> bool {
    // SAFETY: `value` is a live `T` of `size_of::<T>()` bytes, read as bytes
    // only; the statics below are written by the compiler in full (padding
    // included, as zeros).
    let bytes =
        unsafe { std::slice::from_raw_parts((value as *const T).cast::<u8>(), size_of::<T>()) };
    bytes.iter().all(|&b| b == 0)
}

mod zero_tables {
    use abtrack::num::fixed32::Fixed32;
    use abtrack::track::defaults::{DefaultCartesianTrack, DefaultPolarTrack};
    use abtrack::track::{FixedGainTrack, TrackTable};
    use abtrack::Fix;

    pub static F32_FIXED_GAINS: TrackTable<f32, FixedGainTrack<f32>, 16, 16> = TrackTable::new();
    pub static F32_DEFAULT: TrackTable<f32, DefaultCartesianTrack<f32>, 16, 16> = TrackTable::new();
    pub static F32_POLAR: TrackTable<f32, DefaultPolarTrack<f32>, 16, 16> = TrackTable::new();
    pub static FIXED_FIXED_GAINS: TrackTable<Fixed32, FixedGainTrack<Fixed32>, 16, 16> =
        TrackTable::new();
    pub static FIXED_DEFAULT: TrackTable<Fixed32, DefaultCartesianTrack<Fixed32>, 16, 16> =
        TrackTable::new();
    pub static Q32_FIXED_GAINS: TrackTable<Fix, FixedGainTrack<Fix>, 8, 8> = TrackTable::new();
    pub static F64_DEFAULT: TrackTable<f64, DefaultCartesianTrack<f64>, 8, 8> = TrackTable::new();
}

/// A new table, its tracks' slots and every workspace, is zero bytes, so a
/// `static` table lands in `.bss` and costs no flash.
#[test]
fn new_table_is_zero_bytes() {
    use zero_tables::*;
    assert!(is_zero_bytes(&F32_FIXED_GAINS), "f32, fixed gains");
    assert!(is_zero_bytes(&F32_DEFAULT), "f32, default filter");
    assert!(is_zero_bytes(&F32_POLAR), "f32, range-azimuth filter");
    assert!(is_zero_bytes(&FIXED_FIXED_GAINS), "fixed, fixed gains");
    assert!(is_zero_bytes(&FIXED_DEFAULT), "fixed, default filter");
    assert!(is_zero_bytes(&Q32_FIXED_GAINS), "q32, fixed gains");
    assert!(is_zero_bytes(&F64_DEFAULT), "f64, default filter");
    // And it is a working empty table: first id 1.
    assert_eq!(F32_DEFAULT.next_id(), 1);
    assert!(FIXED_DEFAULT.is_empty());
}
