//! Capacity is a hard fact; ids are unique; bad input touches nothing.

use super::support;
use abtrack::num::Quantity;

use std::collections::HashSet;

use abtrack::track::{Association, DropReason, Measurement, RejectReason, TrackStatus};
use abtrack::{Fix, Scalar};
use support::{cart, default_config, s, Table};

/// Target k at (10 000·k, 0) + t·(0, 100) m: far apart, never in each
/// other's gates.
fn spread<S: Scalar>(k: usize, t_ms: u32) -> Measurement<S> {
    cart(10_000.0 * k as f64, 100.0 * t_ms as f64 / 1000.0)
}

#[test]
fn full_table_refuses_and_counts() {
    let config = default_config::<f64>();
    let mut table: Table<f64, 2, 8> = Table::new();
    let mut codes = [Association::OutsideGates; 8];
    // Three targets appear; scan 1 can start only two tracks.
    let scan = |table: &mut Table<f64, 2, 8>, t: u32, n: usize, codes: &mut [Association]| {
        let m: Vec<_> = (0..n).map(|k| spread(k, t)).collect();
        table.scan(&config, t, &m, codes).unwrap()
    };
    scan(&mut table, 0, 3, &mut codes);
    let r = scan(&mut table, 1000, 3, &mut codes);
    assert_eq!(r.started, 2);
    assert_eq!(r.refused_table_full, 1);
    assert!(matches!(codes[0], Association::Started(_)));
    assert!(matches!(codes[1], Association::Started(_)));
    assert_eq!(codes[2], Association::Dropped(DropReason::TableFull));
    assert!(table.is_full());
    let ids: Vec<_> = table.tracks().map(|t| t.id()).collect();

    // The two tracks confirm; five more targets keep appearing for 10 scans.
    // A refused candidate drops both its points, so each new target pairs
    // every other scan (odd scans: refused; even scans: first points again).
    // The confirmed tracks are never evicted.
    let mut refused = 1;
    for k in 2..12u32 {
        let t = k * 1000;
        let r = scan(&mut table, t, 7, &mut codes);
        assert_eq!(r.updated, 2);
        assert_eq!(r.started, 0);
        if k % 2 == 1 {
            assert_eq!(r.refused_table_full, 5);
            assert!(codes[2..7]
                .iter()
                .all(|c| *c == Association::Dropped(DropReason::TableFull)));
        } else {
            assert_eq!(r.refused_table_full, 0);
            assert!(codes[2..7].iter().all(|c| *c == Association::OutsideGates));
        }
        refused += r.refused_table_full;
        assert_eq!(table.tracks().map(|t| t.id()).collect::<Vec<_>>(), ids);
        assert!(table.tracks().all(|t| t.status() == TrackStatus::Confirmed));
    }
    assert_eq!(table.stats().refused_table_full, refused);
    assert_eq!(table.stats().tracks_started, 2);
}

#[test]
fn excess_measurements_are_dropped_and_counted() {
    let config = default_config::<f64>();
    let mut table: Table<f64, 8, 4> = Table::new();
    let m: Vec<_> = (0..6).map(|k| spread::<f64>(k, 0)).collect();
    let mut codes = [Association::NotAssigned; 6];
    let r = table.scan(&config, 0, &m, &mut codes).unwrap();
    assert_eq!(r.measurements, 6);
    assert_eq!(r.dropped_overflow, 2);
    assert_eq!(r.outside_gates, 4);
    assert_eq!(codes[4], Association::Dropped(DropReason::ScanOverflow));
    assert_eq!(codes[5], Association::Dropped(DropReason::ScanOverflow));
    assert_eq!(table.pending(), 4);
    assert_eq!(table.stats().dropped_overflow, 2);
    // A short code buffer: codes beyond it are not written, counts still hold.
    let mut short = [Association::NotAssigned; 2];
    let m: Vec<_> = (0..6).map(|k| spread::<f64>(k, 1000)).collect();
    let r = table.scan(&config, 1000, &m, &mut short).unwrap();
    assert_eq!(r.started, 4);
    assert_eq!(r.dropped_overflow, 2);
    assert!(short.iter().all(|c| matches!(c, Association::Started(_))));
}

/// Runs create/delete cycles on a 3-slot table from `first_id`, returning
/// the ids in the order issued.
fn cycle_ids(first_id: u32, cycles: usize) -> Vec<u32> {
    let config = default_config::<f64>();
    let mut table: Table<f64, 3, 4> = Table::with_first_id(first_id);
    let mut issued = Vec::new();
    let mut codes = [Association::OutsideGates; 4];
    let mut t = 0u32;
    for c in 0..cycles {
        // Two targets at positions that change every cycle: two scans start
        // two tracks, then two empty scans delete them (tentative limit 2).
        for k in 0..2u32 {
            let m: Vec<_> = (0..2)
                .map(|j| cart::<f64>(50_000.0 * j as f64 + 1000.0 * c as f64, 10.0 * k as f64))
                .collect();
            table.scan(&config, t, &m, &mut codes).unwrap();
            t += 1000;
            for code in &codes[..2] {
                if let Association::Started(id) = code {
                    issued.push(id.get());
                }
            }
        }
        for _ in 0..2 {
            table.scan(&config, t, &[], &mut codes).unwrap();
            t += 1000;
        }
        assert!(table.is_empty());
    }
    issued
}

#[test]
fn ids_never_repeat_across_cycles_and_wrap() {
    let first = u32::MAX - 9;
    let ids = cycle_ids(first, 20);
    assert_eq!(ids.len(), 40);
    let unique: HashSet<_> = ids.iter().collect();
    assert_eq!(unique.len(), 40);
    // Issued in sequence through the wrap: MAX−9 .. MAX, 0, 1, ..., 29.
    let expected: Vec<u32> = (0..40u32).map(|k| first.wrapping_add(k)).collect();
    assert_eq!(ids, expected);
}

#[test]
fn wrapped_ids_skip_live_tracks() {
    let config = default_config::<f64>();
    let mut table: Table<f64, 4, 4> = Table::with_first_id(u32::MAX - 1);
    let mut codes = [Association::OutsideGates; 4];
    // Two long-lived tracks get MAX−1 and MAX.
    let two = |t: u32| vec![spread::<f64>(0, t), spread::<f64>(1, t)];
    table.scan(&config, 0, &two(0), &mut codes).unwrap();
    table.scan(&config, 1000, &two(1000), &mut codes).unwrap();
    let live: Vec<u32> = table.tracks().map(|t| t.id().get()).collect();
    assert_eq!(live, vec![u32::MAX - 1, u32::MAX]);
    // The counter comes round to the live ids again (as after 2³² tracks).
    table.set_next_id(u32::MAX - 1);
    // A new target: its track must skip both live ids and wrap to 0.
    let three = |t: u32| {
        let mut m = two(t);
        m.push(spread::<f64>(2, t));
        m
    };
    table.scan(&config, 2000, &three(2000), &mut codes).unwrap();
    table.scan(&config, 3000, &three(3000), &mut codes).unwrap();
    assert_eq!(
        codes[2],
        Association::Started(abtrack::track::TrackId::new(0))
    );
    assert_eq!(table.next_id(), 1);
    let mut live: Vec<u32> = table.tracks().map(|t| t.id().get()).collect();
    live.sort();
    assert_eq!(live, vec![0, u32::MAX - 1, u32::MAX]);
}

/// A confirmed track at scan 2; returns the table (scan time 2000 ms).
fn confirmed_table<S: Scalar>() -> Table<S, 4, 8> {
    let config = default_config::<S>();
    let mut table: Table<S, 4, 8> = Table::new();
    let mut codes = [Association::OutsideGates; 8];
    for t in [0u32, 1000, 2000] {
        table.scan(&config, t, &[spread(0, t)], &mut codes).unwrap();
    }
    assert_eq!(
        table.tracks().next().unwrap().status(),
        TrackStatus::Confirmed
    );
    table
}

fn invalid_rejected_without_touching_tracks<S: Scalar>(invalid: &[Measurement<S>]) {
    let config = default_config::<S>();
    let mut with_bad = confirmed_table::<S>();
    let mut clean = confirmed_table::<S>();
    let mut codes = [Association::NotAssigned; 8];
    let good = spread::<S>(0, 3000);

    // Bad measurements around one good one: same result as the good alone.
    let mut m = invalid.to_vec();
    m.insert(1, good);
    let r = with_bad.scan(&config, 3000, &m, &mut codes).unwrap();
    let mut clean_codes = [Association::NotAssigned; 1];
    clean
        .scan(&config, 3000, &[good], &mut clean_codes)
        .unwrap();
    assert_eq!(r.rejected as usize, invalid.len());
    for (i, c) in codes[..m.len()].iter().enumerate() {
        if i == 1 {
            assert_eq!(*c, clean_codes[0]);
            assert!(matches!(c, Association::Updated(_)));
        } else {
            assert!(
                matches!(
                    c,
                    Association::Rejected(RejectReason::NotFinite | RejectReason::NegativeRange)
                ),
                "{c:?}"
            );
        }
    }
    // Only bad measurements: the track coasts exactly as with none.
    let r = with_bad.scan(&config, 4000, invalid, &mut codes).unwrap();
    clean.scan(&config, 4000, &[], &mut clean_codes).unwrap();
    assert_eq!(r.updated, 0);
    assert_eq!(r.coasted, 1);
    let a: Vec<_> = with_bad.tracks().copied().collect();
    let b: Vec<_> = clean.tracks().copied().collect();
    assert_eq!(a, b);
    // And no bad value became a pending first point.
    assert_eq!(with_bad.pending(), clean.pending());
    assert_eq!(with_bad.stats().rejected as usize, 2 * invalid.len());
}

#[test]
fn invalid_measurements_rejected_f64() {
    let x = 0.0;
    invalid_rejected_without_touching_tracks::<f64>(&[
        Measurement::Cartesian { x: f64::NAN, y: x },
        Measurement::Cartesian {
            x,
            y: f64::INFINITY,
        },
        Measurement::Polar {
            range: -5.0,
            azimuth: 0.1,
        },
        Measurement::Polar {
            range: 100.0,
            azimuth: f64::NAN,
        },
    ]);
}

#[test]
fn invalid_measurements_rejected_f32() {
    invalid_rejected_without_touching_tracks::<f32>(&[
        Measurement::Cartesian {
            x: f32::NEG_INFINITY,
            y: 0.0,
        },
        Measurement::Polar {
            range: f32::NAN,
            azimuth: 0.0,
        },
    ]);
}

#[test]
fn invalid_measurements_rejected_fix() {
    invalid_rejected_without_touching_tracks::<Fix>(&[
        Measurement::Cartesian {
            x: Fix::MAX,
            y: s(0.0),
        },
        Measurement::Cartesian {
            x: s(0.0),
            y: Fix::MIN,
        },
        Measurement::Polar {
            range: s(-1.0),
            azimuth: s(0.0),
        },
    ]);
}

/// A refused (saturating) update of a `FixedGainTrack` leaves the track
/// bit-identical; the table counts the refusal on the track
/// (`Track::refusals`) and in the scan's report.
#[test]
fn fixed_gain_track_refuses_a_saturating_update_unchanged() {
    use abtrack::track::{FixedGainTrack, Observation, ScanInterval, TrackFilter};
    use abtrack::Gains;
    let gains = Gains::<Fix>::alpha_beta_f64(0.5, 0.3).unwrap();
    let at = |x: f64| {
        Observation::new(Measurement::Cartesian {
            x: Fix::from_f64_lossy(x),
            y: Fix::ZERO,
        })
        .unwrap()
    };
    let step = |ms| FixedGainTrack::step(&gains, &ScanInterval::from_ms(ms).unwrap()).unwrap();
    let mut track = FixedGainTrack::<Fix>::empty(&gains);
    track.update(&gains, &at(0.0), &step(1000)).unwrap();
    track.update(&gains, &at(10.0), &step(1000)).unwrap();
    let before = track;
    // β/T·e = 0.3/0.001 s · 2e9 m leaves Q32.32: refused, nothing changed.
    assert_eq!(
        track.update(&gains, &at(2.0e9), &step(1)),
        Err(abtrack::FilterError::Saturated)
    );
    assert_eq!(track, before);
}

/// A filter that refuses every update after its two initiation points (as
/// a saturating one would): the table codes the measurement
/// `FilterRefused`, the track coasts, and the refusal is counted on it.
#[test]
fn refused_updates_are_counted_on_the_track() {
    let (config, mut table) = refusing_table(2);
    let mut codes = [Association::OutsideGates; 1];
    for t in [0, 1000] {
        table
            .scan(&config, t, &[cart(100.0, 0.0)], &mut codes)
            .unwrap();
    }
    assert_eq!(
        codes[0],
        Association::Started(table.tracks().next().unwrap().id())
    );
    for (k, t) in [2000, 3000].into_iter().enumerate() {
        let r = table
            .scan(&config, t, &[cart(101.0, 0.0)], &mut codes)
            .unwrap();
        assert_eq!((r.filter_refused, r.coasted, r.updated), (1, 1, 0));
        assert_eq!(codes[0], Association::Rejected(RejectReason::FilterRefused));
        let track = table.tracks().next().unwrap();
        assert_eq!(track.refusals() as usize, k + 1);
        assert_eq!(track.misses() as usize, k + 1);
    }
}

/// A filter that refuses a new track's second point: no track starts, the
/// measurement is coded `FilterRefused` and counted with the refused
/// updates, and its first point is spent.
#[test]
fn a_refused_start_is_counted() {
    let (config, mut table) = refusing_table(1);
    let mut codes = [Association::OutsideGates; 1];
    table
        .scan(&config, 0, &[cart(100.0, 0.0)], &mut codes)
        .unwrap();
    let r = table
        .scan(&config, 1000, &[cart(101.0, 0.0)], &mut codes)
        .unwrap();
    assert_eq!(codes[0], Association::Rejected(RejectReason::FilterRefused));
    assert_eq!((r.filter_refused, r.started, r.tracks), (1, 0, 0));
    assert_eq!(table.tracks().count(), 0);
    // The refused point is not a first point either: the next scan's
    // measurement waits as one.
    let r = table
        .scan(&config, 2000, &[cart(102.0, 0.0)], &mut codes)
        .unwrap();
    assert_eq!(codes[0], Association::OutsideGates);
    assert_eq!((r.filter_refused, r.started), (0, 0));
}

/// A 2-track table of [`support::Parked`] filters (20 m gates) that refuse
/// every update after their first `refuse_after` points, and its config.
fn refusing_table(
    refuse_after: u8,
) -> (
    abtrack::track::TrackerConfig<f64, support::ParkedParams>,
    abtrack::track::TrackTable<f64, support::Parked, 2, 2>,
) {
    let config = support::parked_config(support::ParkedParams {
        gate_radius: Some(20.0),
        refuse_after: Some(refuse_after),
    });
    (config, abtrack::track::TrackTable::new())
}
