//! Reply identity in the scan loop (docs/tcas.md, "The firmware"): a Mode S
//! address is held by one track at most, and the capacity ranking
//! (abtrack::scan, "Capacity") counts a reply in a confirmed track's gate
//! only if that track may take it.

use abtrack_firmware::demo_config;

use abtrack::filter::range_azimuth::RangeAzimuthNoise;
use abtrack::scan::{MeasurementQueue, ScanConfig, ScanLoop};
use abtrack::track::RangeAzimuthTrack;
use abtrack::wire::{MeasurementReport, ModeSAddress, ScanCounts};
use abtrack::{Fix, Scalar};
use abtrack_host_tests::encounters::NM;

/// The demo's track type, 8 tracks, `M` replies a scan.
type Loop<S, const M: usize> = ScanLoop<S, RangeAzimuthTrack<S>, 8, M>;

/// An identity: a Mode S address, or none (Mode C), and an altitude (ft).
type Identity = (Option<u32>, f64);

fn mode_s(address: u32) -> Identity {
    (Some(address), 8300.0)
}

fn mode_c(altitude_ft: f64) -> Identity {
    (None, altitude_ft)
}

/// A reply at scan `k` (1 s apart) from an intruder closing at 100 m/s
/// from 10 NM on bearing 30°, `extra_m` beyond it in range.
fn reply(k: u32, extra_m: f64, (address, altitude_ft): Identity) -> MeasurementReport {
    let range = 10.0 * NM - 100.0 * f64::from(k) + extra_m;
    let r = MeasurementReport::polar_from_metres(
        k * 1000,
        1,
        range,
        std::f64::consts::FRAC_PI_6,
        Some(altitude_ft),
    )
    .unwrap();
    match address {
        Some(a) => r.with_mode_s(ModeSAddress::new(a).unwrap(), false),
        None => r,
    }
}

/// Runs one scan on `replies` (in that order); its counts.
fn scan<S: Scalar, const M: usize>(
    scan_loop: &mut Loop<S, M>,
    config: &ScanConfig<S, RangeAzimuthNoise<S>>,
    replies: &[MeasurementReport],
) -> ScanCounts {
    let mut queue = Box::new(MeasurementQueue::<16>::new());
    for r in replies {
        queue.push(*r).unwrap();
    }
    let tick = scan_loop.on_tick(config, queue.as_mut(), |_| {}).unwrap();
    assert!(queue.is_empty());
    tick.summary.counts
}

/// The live tracks that hold `address`.
fn holders<S: Scalar, const M: usize>(scan_loop: &Loop<S, M>, address: u32) -> usize {
    let address = ModeSAddress::new(address).unwrap();
    scan_loop
        .table()
        .tracks()
        .filter(|t| scan_loop.address(t.id()) == Some(address))
        .count()
}

/// Two replies from one Mode S address in every scan (the intruder's and a
/// copy 600 m beyond it, as from a reflection; either first): the first
/// two scans could start two tracks, one from each pair; one starts, and
/// the address stays with that one track, which confirms. The other reply
/// is counted (outside the gates) and starts nothing.
#[test]
fn a_mode_s_address_is_held_by_one_track() {
    fn check<S: Scalar>() {
        const ADDRESS: u32 = 0xABC123;
        let config = demo_config::demo_config::<S, _>().unwrap();
        for copy_first in [false, true] {
            let mut scan_loop: Box<Loop<S, 12>> = Box::new(ScanLoop::new());
            for k in 0..8u32 {
                let mut replies = [
                    reply(k, 0.0, mode_s(ADDRESS)),
                    reply(k, 600.0, mode_s(ADDRESS)),
                ];
                if copy_first {
                    replies.reverse();
                }
                let c = scan(&mut scan_loop, &config, &replies);
                let case = format!("{} (copy first: {copy_first}) scan {k}: {c}", S::NAME);
                assert_eq!(c.used, 2, "{case}");
                if k == 1 {
                    assert_eq!((c.started, c.outside_gates), (1, 1), "{case}");
                }
                if k >= 1 {
                    assert_eq!(holders(&scan_loop, ADDRESS), 1, "{case}");
                    assert_eq!(scan_loop.table().len(), 1, "{case}");
                }
            }
            let track = scan_loop.table().tracks().next().unwrap();
            assert!(track.is_confirmed(), "{}: {track:?}", S::NAME);
        }
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// Capacity by identity: a confirmed track, then a scan with room for 2
/// replies: its own reply 30 m beyond its prediction, then two replies of
/// another identity nearer its prediction (5 m beyond, 10 m short), which
/// it may not take. Its own reply is its nearest in the gate that it may
/// take, so it is kept and updates the track; the two others compete as
/// unknown replies (one kept, counted outside the gates; one over
/// capacity).
#[test]
fn a_confirmed_tracks_reply_outranks_replies_it_may_not_take() {
    fn check<S: Scalar>() {
        let config = demo_config::demo_config::<S, _>().unwrap();
        for (intruder, stranger) in [
            (mode_s(0xA00001), mode_c(8300.0)),
            (mode_s(0xA00001), mode_s(0xA00002)),
            (mode_c(8300.0), mode_s(0xA00002)),
            (mode_c(8300.0), mode_c(10300.0)),
        ] {
            let mut scan_loop: Box<Loop<S, 2>> = Box::new(ScanLoop::new());
            for k in 0..10u32 {
                scan(&mut scan_loop, &config, &[reply(k, 0.0, intruder)]);
            }
            let confirmed = scan_loop.table().tracks().filter(|t| t.is_confirmed());
            assert_eq!(confirmed.count(), 1);
            let c = scan(
                &mut scan_loop,
                &config,
                &[
                    reply(10, 30.0, intruder),
                    reply(10, 5.0, stranger),
                    reply(10, -10.0, stranger),
                ],
            );
            let case = format!("{}: {intruder:?} among {stranger:?}: {c}", S::NAME);
            assert_eq!((c.used, c.over_capacity), (2, 1), "{case}");
            assert_eq!((c.updated, c.coasted, c.outside_gates), (1, 0, 1), "{case}");
        }
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// A track lost by its intruder (every reply of its address now 5 km beyond
/// its gate, as after a jump of the range measurement) holds the address
/// until it is deleted; the replies it cannot take are kept as first points
/// but start nothing while it lives. In the scan that deletes it, the
/// address is free: the previous scan's reply and this one start the new
/// track then, not a scan later.
#[test]
fn a_deleted_tracks_address_starts_a_track_in_the_scan_that_deletes_it() {
    fn check<S: Scalar>() {
        const ADDRESS: u32 = 0xABC124;
        let config = demo_config::demo_config::<S, _>().unwrap();
        let mut scan_loop: Box<Loop<S, 4>> = Box::new(ScanLoop::new());
        for k in 0..10u32 {
            scan(&mut scan_loop, &config, &[reply(k, 0.0, mode_s(ADDRESS))]);
        }
        assert_eq!(holders(&scan_loop, ADDRESS), 1);
        let mut deleted_at = None;
        for k in 10..40u32 {
            let c = scan(
                &mut scan_loop,
                &config,
                &[reply(k, 5_000.0, mode_s(ADDRESS))],
            );
            let case = format!("{} scan {k}: {c}", S::NAME);
            assert!(holders(&scan_loop, ADDRESS) <= 1, "{case}");
            if c.deleted > 0 {
                assert_eq!(deleted_at, None, "{case}");
                deleted_at = Some(k);
                assert_eq!(c.started, 1, "{case}");
                assert_eq!(holders(&scan_loop, ADDRESS), 1, "{case}");
            } else if deleted_at.is_none() {
                assert_eq!(c.started, 0, "{case}");
                if k > 10 {
                    assert_eq!(c.outside_gates, 1, "{case}");
                }
            }
        }
        assert!(
            deleted_at.is_some(),
            "{}: the lost track was never deleted",
            S::NAME
        );
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// A track updated and then deleted in the same scan (its update takes it
/// out of the surveillance volume, the square around the 14 NM disc) gets
/// no TCAS slot after the scan: its address is not kept for a dead track.
/// Replies on azimuth 0 from 25.5 km going out at 100 m/s.
#[test]
fn a_track_deleted_after_its_update_keeps_no_slot() {
    fn check<S: Scalar>() {
        const ADDRESS: u32 = 0xABC125;
        let config = demo_config::demo_config::<S, _>().unwrap();
        let mut scan_loop: Box<Loop<S, 4>> = Box::new(ScanLoop::new());
        let outward = |k: u32| {
            MeasurementReport::polar_from_metres(
                k * 1000,
                1,
                25_500.0 + 100.0 * f64::from(k),
                0.0,
                Some(8300.0),
            )
            .unwrap()
            .with_mode_s(ModeSAddress::new(ADDRESS).unwrap(), false)
        };
        let mut left = false;
        for k in 0..10u32 {
            let live = scan_loop.table().tracks().next().map(|t| t.id());
            let c = scan(&mut scan_loop, &config, &[outward(k)]);
            if c.deleted == 1 && c.updated == 1 {
                let id = live.unwrap();
                assert!(scan_loop.table().track(id).is_none(), "{}", S::NAME);
                assert_eq!(scan_loop.address(id), None, "{} scan {k}: {c}", S::NAME);
                left = true;
                break;
            }
        }
        assert!(left, "{}: the track never left the volume", S::NAME);
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}
