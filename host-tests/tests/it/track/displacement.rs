//! A full table: a new track displaces the weakest tentative track that
//! missed the last scan (counted as a deletion, its id ends); confirmed,
//! coasting and just-updated tracks are never displaced, and with none to
//! displace the candidate is refused and counted.

use super::support;

use std::collections::BTreeSet;

use abtrack::track::{Association, DropReason, ScanReport, TrackId, TrackStatus};
use support::{cart, default_config, Config, Lcg, Table};

/// Target k at (10 000·k, 0) + t·(0, 100) m: far apart, never in each
/// other's gates.
fn target(k: usize, t_ms: u32) -> abtrack::track::Measurement<f64> {
    cart(10_000.0 * k as f64, 100.0 * t_ms as f64 / 1000.0)
}

/// Confirmation `hits` of 8, deletion after 3 misses (confirmed) and 4
/// (tentative): tentative tracks live long enough to differ in strength.
fn config(hits: u8) -> Config<f64> {
    default_config::<f64>()
        .with_confirmation(hits, 8)
        .unwrap()
        .with_deletion(3, 4)
        .unwrap()
}

/// One scan of the listed targets, in that order.
fn scan<const N: usize>(
    table: &mut Table<f64, N, 8>,
    config: &Config<f64>,
    t_ms: u32,
    targets: &[usize],
    codes: &mut [Association; 8],
) -> ScanReport {
    let m: Vec<_> = targets.iter().map(|&k| target(k, t_ms)).collect();
    table.scan(config, t_ms, &m, codes).unwrap()
}

fn ids<const N: usize>(table: &Table<f64, N, 8>) -> Vec<TrackId> {
    table.tracks().map(|t| t.id()).collect()
}

#[test]
fn full_table_displaces_the_weakest_tentative_track() {
    let config = config(5);
    let mut table: Table<f64, 3, 8> = Table::new();
    let mut codes = [Association::OutsideGates; 8];
    // Targets 0, 1, 2 start three tentative tracks at 1 s (slots 0, 1, 2).
    scan(&mut table, &config, 0, &[0, 1, 2], &mut codes);
    let r = scan(&mut table, &config, 1000, &[0, 1, 2], &mut codes);
    assert_eq!(r.started, 3);
    assert!(table.is_full());
    let [a, b, c] = <[TrackId; 3]>::try_from(ids(&table)).unwrap();
    // Target 0 is seen once more, target 1 never, target 2 every scan;
    // target 3 appears at 3 s.
    scan(&mut table, &config, 2000, &[0, 2], &mut codes);
    scan(&mut table, &config, 3000, &[2, 3], &mut codes);
    assert_eq!(table.pending(), 1);
    // At 4 s target 3's second point: the table is full. Track a has 2 hits
    // in its window and 2 misses, b 1 hit and 3 misses, c was updated (not
    // displaceable): b is displaced.
    let r = scan(&mut table, &config, 4000, &[2, 3], &mut codes);
    let Association::Started(d) = codes[1] else {
        panic!("target 3 did not start: {:?}", codes[1]);
    };
    assert_eq!(codes[0], Association::Updated(c));
    assert_eq!(r.started, 1);
    assert_eq!(r.refused_table_full, 0);
    assert_eq!(r.deleted_displaced, 1);
    assert_eq!(r.deleted, 1);
    assert!(d > c, "a new id: {d:?}");
    // The displaced track's slot holds the new track; its id has ended.
    assert_eq!(ids(&table), vec![a, d, c]);
    assert!(table.track(b).is_none());
    assert!(table.tracks().all(|t| t.status() == TrackStatus::Tentative));
    let stats = table.stats();
    assert_eq!(stats.tracks_displaced, 1);
    assert_eq!(stats.tracks_deleted, 1);
    assert_eq!(stats.tracks_started, 4);
    assert_eq!(stats.refused_table_full, 0);
}

#[test]
fn confirmed_coasting_and_updated_tracks_are_never_displaced() {
    // 4 of 8: targets 0 and 1 confirm at 4 s.
    let config = config(4);
    let mut table: Table<f64, 3, 8> = Table::new();
    let mut codes = [Association::OutsideGates; 8];
    for t in [0, 1000, 2000] {
        scan(&mut table, &config, t, &[0, 1], &mut codes);
    }
    scan(&mut table, &config, 3000, &[0, 1, 2], &mut codes);
    scan(&mut table, &config, 4000, &[0, 1, 2], &mut codes);
    let before = ids(&table);
    assert!(table.is_full());
    // Target 0 missed from 5 s on (coasting), target 1 confirmed, target
    // 2's track tentative and updated every scan; target 3 appears.
    scan(&mut table, &config, 5000, &[1, 2, 3], &mut codes);
    let r = scan(&mut table, &config, 6000, &[1, 2, 3], &mut codes);
    let status: Vec<_> = table.tracks().map(|t| t.status()).collect();
    use TrackStatus::*;
    assert_eq!(status, vec![Coasting, Confirmed, Tentative]);
    assert_eq!(codes[2], Association::Dropped(DropReason::TableFull));
    assert_eq!(r.refused_table_full, 1);
    assert_eq!((r.started, r.deleted, r.deleted_displaced), (0, 0, 0));
    assert_eq!(ids(&table), before);
    // Target 2 is missed twice: its tentative track is then the one a new
    // track displaces; the confirmed tracks stay (target 0 back in its gate).
    scan(&mut table, &config, 7000, &[0, 1, 3], &mut codes);
    let r = scan(&mut table, &config, 8000, &[0, 1, 3], &mut codes);
    assert!(matches!(codes[2], Association::Started(_)), "{codes:?}");
    assert_eq!(r.deleted_displaced, 1);
    let after = ids(&table);
    assert_eq!(after[..2], before[..2]);
    assert!(table.track(before[2]).is_none());
    let stats = table.stats();
    assert_eq!(stats.refused_table_full, 1);
    assert_eq!(stats.tracks_displaced, 1);
    assert_eq!(stats.tracks_confirmed, 2);
}

/// Four tentative tracks (slots 0–3): 0 updated in the last scan, 1 with 2
/// hits and 2 misses, 2 and 3 with 1 hit and 3 misses; targets 4 and 5
/// (in `order`) start two tracks in the full table. Returns the codes of
/// that scan and the table's ids after it.
fn two_candidates(order: [usize; 2]) -> (Vec<Association>, Vec<TrackId>, Vec<TrackId>) {
    let config = config(5);
    let mut table: Table<f64, 4, 8> = Table::new();
    let mut codes = [Association::OutsideGates; 8];
    scan(&mut table, &config, 0, &[0, 1, 2, 3], &mut codes);
    scan(&mut table, &config, 1000, &[0, 1, 2, 3], &mut codes);
    let before = ids(&table);
    scan(&mut table, &config, 2000, &[0, 1], &mut codes);
    scan(
        &mut table,
        &config,
        3000,
        &[0, order[0], order[1]],
        &mut codes,
    );
    let r = scan(
        &mut table,
        &config,
        4000,
        &[0, order[0], order[1]],
        &mut codes,
    );
    assert_eq!((r.started, r.deleted_displaced, r.deleted), (2, 2, 2));
    assert_eq!(r.refused_table_full, 0);
    (codes[..3].to_vec(), before, ids(&table))
}

#[test]
fn which_track_is_displaced_is_deterministic() {
    let (codes, before, after) = two_candidates([4, 5]);
    // Slots 2 and 3 tie (1 hit, 3 misses): the first candidate takes the
    // lower slot; the second the other (the first candidate's track was
    // started in this scan: not displaceable). Slots 0 and 1 stay.
    let (Association::Started(d4), Association::Started(d5)) = (codes[1], codes[2]) else {
        panic!("{codes:?}");
    };
    assert_eq!(after, vec![before[0], before[1], d4, d5]);
    // The same inputs give the same table.
    assert_eq!(two_candidates([4, 5]), (codes, before.clone(), after));
    // In the other order, the same tracks are displaced.
    let (codes, _, after) = two_candidates([5, 4]);
    let (Association::Started(d5), Association::Started(d4)) = (codes[1], codes[2]) else {
        panic!("{codes:?}");
    };
    assert_eq!(after, vec![before[0], before[1], d5, d4]);
}

/// Two real targets outside a 3 km × 3 km square of 12 clutter points a
/// scan, into
/// a 4-track table: the table fills with tentative clutter tracks. Every
/// scan: the codes agree with the counts, `deleted` is the sum of its
/// reasons, the track count follows from the starts and ends, no track
/// started in the scan is displaced, and no confirmed track ends but by a
/// counted deletion for misses or the volume.
#[test]
fn clutter_displaces_only_tentative_tracks_and_every_end_is_counted() {
    let config = default_config::<f64>().with_confirmation(3, 5).unwrap();
    let mut table: Table<f64, 4, 16> = Table::new();
    let mut codes = [Association::OutsideGates; 16];
    let mut rng = Lcg(7);
    let (mut displaced, mut refused) = (0u32, 0u32);
    let mut tracked = [false; 2];
    for k in 0..80u32 {
        let t = k * 1000;
        let tf = t as f64 / 1000.0;
        let mut m = vec![
            cart(4000.0, -2000.0 + 50.0 * tf),
            cart(-4000.0, 3000.0 - 40.0 * tf),
        ];
        m.extend((0..12).map(|_| cart(1500.0 * rng.next_signed(), 1500.0 * rng.next_signed())));
        let confirmed_before: BTreeSet<TrackId> = table
            .tracks()
            .filter(|t| t.is_confirmed())
            .map(|t| t.id())
            .collect();
        let len_before = table.len() as u32;
        let r = table.scan(&config, t, &m, &mut codes).unwrap();
        let count = |f: &dyn Fn(&Association) -> bool| codes.iter().filter(|c| f(c)).count() as u32;
        assert_eq!(count(&|c| matches!(c, Association::Started(_))), r.started);
        assert_eq!(
            count(&|c| *c == Association::Dropped(DropReason::TableFull)),
            r.refused_table_full
        );
        if r.refused_table_full > 0 {
            assert!(table.is_full());
        }
        assert_eq!(
            r.deleted,
            r.deleted_misses
                + r.deleted_unconfirmed
                + r.deleted_left_volume
                + r.deleted_numeric
                + r.deleted_displaced
        );
        assert_eq!(
            table.len() as u32,
            len_before + r.started - r.deleted - r.restarted
        );
        for c in &codes {
            if let Association::Started(id) = c {
                assert!(
                    table.track(*id).is_some(),
                    "{id:?} started and displaced at {t} ms"
                );
            }
        }
        let confirmed_ended = confirmed_before
            .iter()
            .filter(|id| table.track(**id).is_none())
            .count() as u32;
        assert!(confirmed_ended <= r.deleted_misses + r.deleted_left_volume);
        displaced += r.deleted_displaced;
        refused += r.refused_table_full;
        for (i, tracked) in tracked.iter_mut().enumerate() {
            let abtrack::track::Measurement::Cartesian { x, y } = m[i] else {
                unreachable!()
            };
            *tracked |= table.tracks().any(|t| {
                t.is_confirmed() && (t.position()[0] - x).hypot(t.position()[1] - y) < 50.0
            });
        }
    }
    let stats = table.stats();
    println!("{displaced} displaced, {refused} refused, {stats:?}");
    assert!(displaced > 0);
    assert_eq!(stats.tracks_displaced, displaced);
    assert_eq!(stats.refused_table_full, refused);
    assert!(stats.tracks_deleted >= displaced);
    // Both real targets get confirmed tracks despite the clutter.
    assert_eq!(tracked, [true, true]);
}
