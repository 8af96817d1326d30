//! Initiation, M-of-N confirmation, coasting and K-miss deletion, the
//! surveillance volume, and time handling.

use super::support;

use abtrack::track::{
    Association, Measurement, ScanError, ScanReport, TrackId, TrackStatus, Volume,
};
use support::{cart, default_config, Config, Table};

type T = Table<f64, 8, 8>;

/// A target at (1000 + 50t, 2000 − 20t) m, t in seconds.
fn target(t_ms: u32) -> Measurement<f64> {
    let t = t_ms as f64 / 1000.0;
    cart(1000.0 + 50.0 * t, 2000.0 - 20.0 * t)
}

/// Scans at 0, 1000, 2000, ... ms; `detect[k]` says whether scan k sees the
/// target. Returns the table and the per-scan (code, report) of the target.
/// Per scan: the target's code (if it was detected), the report, and the
/// status of every track.
type ScanLog = Vec<(Option<Association>, ScanReport, Vec<TrackStatus>)>;

fn run(config: &Config<f64>, detect: &[bool]) -> (T, ScanLog) {
    let mut table = T::new();
    let mut out = Vec::new();
    for (k, &d) in detect.iter().enumerate() {
        let t = k as u32 * 1000;
        let meas: Vec<_> = if d { vec![target(t)] } else { vec![] };
        let mut codes = [Association::OutsideGates; 1];
        let report = table.scan(config, t, &meas, &mut codes).unwrap();
        let statuses = table.tracks().map(|tr| tr.status()).collect();
        out.push((d.then_some(codes[0]), report, statuses));
    }
    (table, out)
}

#[test]
fn two_point_start_then_confirm_on_next_hit() {
    let config = default_config::<f64>();
    let (table, out) = run(&config, &[true, true, true]);
    // Scan 0: first point only.
    assert_eq!(out[0].0, Some(Association::OutsideGates));
    assert_eq!(out[0].1.started, 0);
    // Scan 1: second point starts tentative track 1.
    assert_eq!(out[1].0, Some(Association::Started(id(1))));
    assert_eq!(out[1].2, vec![TrackStatus::Tentative]);
    // Scan 2: 2 hits of 3 scans (the start counts 1) → confirmed.
    assert_eq!(out[2].0, Some(Association::Updated(id(1))));
    assert_eq!(out[2].1.confirmed, 1);
    assert_eq!(out[2].2, vec![TrackStatus::Confirmed]);
    let track = table.tracks().next().unwrap();
    assert_eq!(track.hits(), 3);
    assert_eq!(track.history() & 0b111, 0b11);
    // Two-point velocity (Al-Wagih eq. 9) then a filtered update of a
    // noise-free constant-velocity target: exact.
    assert!((track.velocity()[0] - 50.0).abs() < 1e-9);
    assert!((track.velocity()[1] + 20.0).abs() < 1e-9);
    assert!((track.position()[0] - 1100.0).abs() < 1e-9);
}

fn id(id: u32) -> TrackId {
    TrackId::new(id)
}

#[test]
fn confirm_after_one_miss() {
    let config = default_config::<f64>();
    let (_, out) = run(&config, &[true, true, false, true]);
    assert_eq!(out[2].2, vec![TrackStatus::Tentative]);
    assert_eq!(out[2].1.coasted, 1);
    // History 101: 2 of the first 3 scans.
    assert_eq!(out[3].1.confirmed, 1);
    assert_eq!(out[3].2, vec![TrackStatus::Confirmed]);
}

/// A target missed in the scan after its first detection starts from that
/// detection when it is seen again (two-point start over both intervals),
/// and confirms on the next hit: one scan earlier than a start from the
/// next two detections, which is what the option turned off gives.
#[test]
fn a_first_point_waits_through_one_miss() {
    let config = default_config::<f64>();
    assert!(config.first_points_through_a_miss());
    let (table, out) = run(&config, &[true, false, true, true]);
    assert_eq!(out[1].1.started, 0);
    assert_eq!(out[2].0, Some(Association::Started(id(1))));
    assert_eq!(out[3].1.confirmed, 1);
    assert_eq!(out[3].2, vec![TrackStatus::Confirmed]);
    // Velocity differenced over the 2 s since the first point, then a
    // filtered update: exact on a noise-free constant-velocity target.
    let track = table.tracks().next().unwrap();
    assert!((track.velocity()[0] - 50.0).abs() < 1e-9);
    assert!((track.velocity()[1] + 20.0).abs() < 1e-9);

    // Its M-of-N window starts at the missed scan: with 2 of 3 it must be
    // seen in the next scan, where a track started from two consecutive
    // detections may miss it (confirm_after_one_miss).
    let (_, out) = run(&config, &[true, false, true, false, true]);
    assert_eq!(out[3].1.deleted_unconfirmed, 1);
    assert!(out[3].2.is_empty());

    let config = default_config::<f64>().keep_first_points_through_a_miss(false);
    let (_, out) = run(&config, &[true, false, true, true, true]);
    assert_eq!(out[2].0, Some(Association::OutsideGates));
    assert_eq!(out[3].0, Some(Association::Started(id(1))));
    assert_eq!(out[4].1.confirmed, 1);
}

/// With M-of-M confirmation a window starting at the missed scan could
/// never be met: first points are not kept through a miss then.
#[test]
fn m_of_m_confirmation_keeps_no_first_point_through_a_miss() {
    let config = default_config::<f64>().with_confirmation(3, 3).unwrap();
    assert!(!config.first_points_through_a_miss());
    let (_, out) = run(&config, &[true, false, true, true, true, true]);
    assert_eq!(out[2].0, Some(Association::OutsideGates));
    assert_eq!(out[3].0, Some(Association::Started(id(1))));
    assert_eq!(out[5].1.confirmed, 1);
    // 3 of 4 leaves a way: kept.
    let config = default_config::<f64>().with_confirmation(3, 4).unwrap();
    assert!(config.first_points_through_a_miss());
}

/// An earlier first point waits one scan, not more; and the two intervals
/// together must be within the filters' longest, else it is too old.
#[test]
fn an_earlier_first_point_waits_one_scan_only() {
    let config = default_config::<f64>();
    let (_, out) = run(&config, &[true, false, false, true, true]);
    assert_eq!(out[3].0, Some(Association::OutsideGates));
    assert_eq!(out[4].0, Some(Association::Started(id(1))));

    let mut table = T::new();
    let mut codes = [Association::OutsideGates; 1];
    table.scan(&config, 0, &[target(0)], &mut codes).unwrap();
    table.scan(&config, 12_000, &[], &mut codes).unwrap();
    let r = table
        .scan(&config, 24_000, &[target(24_000)], &mut codes)
        .unwrap();
    assert_eq!((r.started, codes[0]), (0, Association::OutsideGates));
}

/// The previous scan's unused measurements take their own indices; an
/// earlier first point at one of them moves to a free index above this
/// scan's measurements and still starts its target. The previous scan's
/// first points pair first.
#[test]
fn earlier_first_points_make_room_for_the_previous_scans() {
    let config = default_config::<f64>();
    let mut table = T::new();
    let far = cart(-40_000.0, -40_000.0);
    let mut codes = [Association::OutsideGates; 2];
    table.scan(&config, 0, &[target(0)], &mut codes).unwrap();
    // Missed; a far plot takes index 0, the target's first point moves up.
    table.scan(&config, 1000, &[far], &mut codes[..1]).unwrap();
    assert_eq!(table.pending(), 2);
    let r = table
        .scan(&config, 2000, &[far, target(2000)], &mut codes)
        .unwrap();
    assert_eq!(r.started, 2);
    // The far plot's own first point (previous scan) took the far plot;
    // the target's earlier one took the target.
    assert_eq!(
        codes,
        [Association::Started(id(1)), Association::Started(id(2))]
    );
    let t = table.tracks().find(|t| t.id() == id(2)).unwrap();
    assert!((t.velocity()[0] - 50.0).abs() < 1e-9);

    // With every place taken by this scan's measurements, the earlier one
    // has no room and is dropped.
    let mut table = Table::<f64, 8, 1>::new();
    let mut codes = [Association::OutsideGates; 1];
    table.scan(&config, 0, &[target(0)], &mut codes).unwrap();
    table.scan(&config, 1000, &[far], &mut codes).unwrap();
    assert_eq!(table.pending(), 1);
}

#[test]
fn tentative_deleted_after_two_misses() {
    let config = default_config::<f64>();
    let (table, out) = run(&config, &[true, true, false, false]);
    assert_eq!(out[2].1.deleted, 0);
    assert_eq!(out[3].1.deleted, 1);
    assert_eq!(out[3].1.deleted_misses, 1);
    assert!(table.is_empty());
}

#[test]
fn confirmed_coasts_then_deleted_after_three_misses() {
    let config = default_config::<f64>();
    let (_, out) = run(
        &config,
        &[true, true, true, false, false, true, false, false, false],
    );
    use TrackStatus::*;
    assert_eq!(out[3].2, vec![Coasting]);
    assert_eq!(out[4].2, vec![Coasting]);
    // A hit brings a coasting track back to confirmed and resets the misses.
    assert_eq!(out[5].0, Some(Association::Updated(id(1))));
    assert_eq!(out[5].2, vec![Confirmed]);
    assert_eq!(out[6].2, vec![Coasting]);
    assert_eq!(out[7].2, vec![Coasting]);
    assert_eq!(out[8].1.deleted_misses, 1);
    assert!(out[8].2.is_empty());
}

#[test]
fn coasting_follows_the_target() {
    // A coasting track is predicted along its velocity, so the target is
    // picked up again after two missed scans.
    let config = default_config::<f64>();
    let (table, out) = run(&config, &[true, true, true, false, false, true]);
    assert_eq!(out[5].0, Some(Association::Updated(id(1))));
    let track = table.tracks().next().unwrap();
    assert!((track.position()[0] - (1000.0 + 250.0)).abs() < 1e-9);
}

#[test]
fn configurable_m_of_n_and_deletion() {
    let config = default_config::<f64>()
        .with_confirmation(3, 5)
        .unwrap()
        .with_deletion(4, 3)
        .unwrap();
    // Start (hit), miss, hit, miss, hit: 3 of 5 at the fifth scan of the
    // track (= scan 5 of the run, the first point being scan 0).
    let (_, out) = run(&config, &[true, true, false, true, false, true]);
    for (k, o) in out.iter().enumerate().take(5).skip(1) {
        assert_eq!(o.2, vec![TrackStatus::Tentative], "scan {k}");
    }
    assert_eq!(out[5].1.confirmed, 1);
    // Start, hit, miss, miss, miss: 2 hits, 2 scans left of 5 → 4 reachable;
    // but 3 misses ≥ the tentative limit 3 → deleted at the third miss.
    let (_, out) = run(&config, &[true, true, true, false, false, false]);
    assert_eq!(out[4].2, vec![TrackStatus::Tentative]);
    assert_eq!(out[5].1.deleted_misses, 1);
    // 3 of 4: start, miss, hit (2 hits, 1 scan left: still reachable), miss
    // (2 hits, no scan left) → M-of-N deletion, not a miss deletion (1 miss).
    let config = default_config::<f64>()
        .with_confirmation(3, 4)
        .unwrap()
        .with_deletion(4, 3)
        .unwrap();
    let (_, out) = run(&config, &[true, true, false, true, false]);
    assert_eq!(out[3].2, vec![TrackStatus::Tentative]);
    assert_eq!(out[4].1.deleted_unconfirmed, 1);
    // 1 of 1: confirmed when started.
    let config = default_config::<f64>().with_confirmation(1, 1).unwrap();
    let (_, out) = run(&config, &[true, true]);
    assert_eq!(out[1].1.started, 1);
    assert_eq!(out[1].1.confirmed, 1);
    assert_eq!(out[1].2, vec![TrackStatus::Confirmed]);
}

#[test]
fn bad_configuration_refused() {
    let c = default_config::<f64>();
    assert!(c.with_confirmation(0, 3).is_err());
    assert!(c.with_confirmation(4, 3).is_err());
    assert!(c.with_confirmation(2, 33).is_err());
    assert!(c.with_deletion(0, 1).is_err());
    assert!(c.with_deletion(1, 0).is_err());
    assert!(c.with_initiation_margin(-1.0).is_err());
    assert!(Volume::<f64>::new([0.0, 0.0], [0.0, 1.0]).is_err());
    assert!(Volume::<f64>::new([0.0, f64::NAN], [1.0, 1.0]).is_err());
}

#[test]
fn leaving_the_volume_deletes() {
    // The target moves +50 m/s in x from 1000; the volume ends at x = 1120.
    let volume = Volume::new([0.0, 0.0], [1120.0, 3000.0]).unwrap();
    let config = default_config::<f64>().with_volume(volume);
    let (_, out) = run(&config, &[true, true, true, true]);
    assert_eq!(out[2].2, vec![TrackStatus::Confirmed]);
    // Scan 3: position 1150 > 1120.
    assert_eq!(out[3].0, Some(Association::Updated(id(1))));
    assert_eq!(out[3].1.deleted_left_volume, 1);
    assert!(out[3].2.is_empty());
}

/// The design's rule 7 as the table applies it: a confirmed track whose
/// gate is wider than the configured largest gates nothing and is deleted,
/// counted; a tentative one is not bounded; a bound no gate reaches
/// changes nothing.
#[test]
fn a_confirmed_track_whose_gate_outgrows_the_bound_is_deleted() {
    let base = default_config::<f64>();
    let (_, plain) = run(&base, &[true; 6]);
    let (_, far) = run(&base.with_max_gate_radius(1e9).unwrap(), &[true; 6]);
    assert_eq!(plain, far);
    let (_, out) = run(&base.with_max_gate_radius(1.0).unwrap(), &[true; 4]);
    // Tentative through scan 2 (its gate then is wider than 1 m), confirmed.
    assert_eq!(out[2].0, Some(Association::Updated(id(1))));
    assert_eq!(out[2].2, vec![TrackStatus::Confirmed]);
    // Scan 3: confirmed, its gate wider than 1 m: it takes nothing and ends.
    assert_eq!(out[3].0, Some(Association::OutsideGates));
    assert_eq!(out[3].1.deleted_gate_too_wide, 1);
    assert_eq!(out[3].1.deleted, 1);
    assert_eq!(out[3].1.coasted, 0);
    assert!(out[3].2.is_empty());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(base.with_max_gate_radius(bad).is_err(), "{bad}");
    }
}

#[test]
fn no_initiation_outside_the_volume() {
    let volume = Volume::new([0.0, 0.0], [500.0, 500.0]).unwrap();
    let config = default_config::<f64>().with_volume(volume);
    let (table, out) = run(&config, &[true, true, true]);
    assert!(out.iter().all(|o| o.1.started == 0));
    assert_eq!(table.pending(), 0);
}

#[test]
fn speed_gate_limits_initiation() {
    // Two points 400 m apart in 1 s exceed v_max = 300 m/s; 290 m do not.
    let config = default_config::<f64>();
    let mut table = T::new();
    let mut codes = [Association::OutsideGates; 1];
    table
        .scan(&config, 0, &[cart(0.0, 0.0)], &mut codes)
        .unwrap();
    let r = table
        .scan(&config, 1000, &[cart(400.0, 0.0)], &mut codes)
        .unwrap();
    assert_eq!(r.started, 0);
    assert_eq!(codes[0], Association::OutsideGates);
    let r = table
        .scan(&config, 2000, &[cart(690.0, 0.0)], &mut codes)
        .unwrap();
    assert_eq!(r.started, 1);
    // The margin widens the gate: 400 m in 1 s with 300 m/s + 120 m.
    let config = default_config::<f64>()
        .with_initiation_margin(120.0)
        .unwrap();
    let mut table = T::new();
    table
        .scan(&config, 0, &[cart(0.0, 0.0)], &mut codes)
        .unwrap();
    let r = table
        .scan(&config, 1000, &[cart(400.0, 0.0)], &mut codes)
        .unwrap();
    assert_eq!(r.started, 1);
}

#[test]
fn variable_intervals_and_clock_wrap() {
    // The same target seen at intervals 1000, 700, 1300, 400 ms, once from
    // t0 = 0 and once from a clock about to wrap: identical tracks.
    let config = default_config::<f64>();
    let offsets = [0u32, 1000, 1700, 3000, 3400];
    let mut a = T::new();
    let mut b = T::new();
    let base = u32::MAX - 1500;
    let mut codes = [Association::OutsideGates; 1];
    for &o in &offsets {
        let m = [target(o)];
        a.scan(&config, o, &m, &mut codes).unwrap();
        let rb = b
            .scan(&config, base.wrapping_add(o), &m, &mut codes)
            .unwrap();
        if o > 0 {
            assert_eq!(
                rb.interval_ms,
                o - offsets[offsets.iter().position(|&x| x == o).unwrap() - 1]
            );
        }
    }
    let ta = a.tracks().next().unwrap();
    let tb = b.tracks().next().unwrap();
    assert_eq!(ta.position(), tb.position());
    assert_eq!(ta.velocity(), tb.velocity());
    assert_eq!(ta.status(), TrackStatus::Confirmed);
    // Noise-free constant velocity: exact after variable intervals too.
    assert!((ta.velocity()[0] - 50.0).abs() < 1e-9);
    assert!((ta.position()[0] - (1000.0 + 50.0 * 3.4)).abs() < 1e-9);
    assert_eq!(tb.last_update_ms(), base.wrapping_add(3400));
}

#[test]
fn time_must_increase() {
    let config = default_config::<f64>();
    let mut table = T::new();
    let mut codes = [Association::OutsideGates; 1];
    table.scan(&config, 5000, &[target(0)], &mut codes).unwrap();
    let before_pending = table.pending();
    codes[0] = Association::NotAssigned;
    for bad in [5000u32, 4999, 5000u32.wrapping_add(1 << 31)] {
        let e = table.scan(&config, bad, &[target(1000)], &mut codes);
        assert_eq!(
            e,
            Err(ScanError::TimeNotIncreasing {
                previous_ms: 5000,
                now_ms: bad
            })
        );
    }
    // Nothing changed, nothing written.
    assert_eq!(codes[0], Association::NotAssigned);
    assert_eq!(table.pending(), before_pending);
    assert_eq!(table.last_scan_ms(), Some(5000));
    assert_eq!(table.stats().scans, 1);
}

#[test]
fn polar_measurements() {
    // Range 1000 m at azimuth 90° (east): x = 1000, y = 0 (He et al. x = R sin B,
    // y = R cos B). Two such points 1 s apart start a track at x ≈ 1000/1010.
    let config = default_config::<f64>();
    let mut table = T::new();
    let mut codes = [Association::OutsideGates; 1];
    let p = |r: f64| Measurement::Polar {
        range: r,
        azimuth: std::f64::consts::FRAC_PI_2,
    };
    table.scan(&config, 0, &[p(1000.0)], &mut codes).unwrap();
    table.scan(&config, 1000, &[p(1010.0)], &mut codes).unwrap();
    assert!(matches!(codes[0], Association::Started(_)));
    let t = table.tracks().next().unwrap();
    assert!((t.position()[0] - 1010.0).abs() < 1e-9);
    assert!(t.position()[1].abs() < 1e-9);
    assert!((t.velocity()[0] - 10.0).abs() < 1e-9);
}
