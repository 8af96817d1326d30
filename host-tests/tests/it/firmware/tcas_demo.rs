//! The firmware's default input, the TCAS demo scenario,
//! through the firmware's scan-loop core on the host in the boards' number
//! types and capacities (`frames::run_like_the_firmware`): the threat goes
//! proximate → TA → RA with a sense → clear of conflict; the intruder level
//! 1000 ft away, the one without altitude and the one abeam beyond the HMD
//! threshold get no RA; every track keeps its intruder's Mode S address;
//! the run is clean. Prints the timeline of each intruder (the figures of
//! docs/tcas.md, "The demo"):
//!
//! cargo test --release --test it firmware::tcas_demo -- --nocapture

use abtrack_firmware::capacity::microbit;
use abtrack_firmware::demo_config;
use abtrack_firmware::number_types::cortex_m0;

use abtrack::tcas::{Advisory, RaSense};
use abtrack::track::RangeAzimuthTrack;
use abtrack::wire::{Message, RaCode, ScanSummary, TrackReport};
use abtrack::{Fix, Scalar, ScaledScalar};
use abtrack_host_tests::encounters::{demo_intruders, demo_reference, NM};
use abtrack_host_tests::frames::{self, Faults, TCAS_DEMO, TCAS_DEMO_SCANS};
use abtrack_host_tests::reference_tcas::Alert;

/// The demo input as scripts/demo-input.sh writes it.
fn demo_input() -> Vec<u8> {
    let reports = frames::scenario_reports(TCAS_DEMO, 1, 1).unwrap();
    frames::encode(
        &reports,
        Faults {
            corrupt_every: Some(97),
            garbage_every: Some(41),
            seed: 0,
        },
    )
    .bytes
}

/// What one intruder's tracks showed: first times (s) of each level, the
/// RA sense at onset, addresses seen.
#[derive(Debug, Default)]
struct Timeline {
    proximate_s: Option<f64>,
    ta_s: Option<f64>,
    ra_s: Option<f64>,
    sense: Option<RaCode>,
    worst: Option<Advisory>,
    addresses: Vec<Option<u32>>,
}

/// Which intruder a track report is: by address when it has one, else the
/// nearest true position (within 3 km).
fn intruder_of(t: &TrackReport) -> Option<usize> {
    let intruders = demo_intruders();
    let addresses = [Some(0x004C_A123), None, None, Some(0x003C_6601)];
    if let Some(a) = t.address {
        return addresses.iter().position(|x| *x == Some(a.get()));
    }
    let time = f64::from(t.time_ms) / 1000.0;
    let (x, y) = (f64::from(t.x_cm) / 100.0, f64::from(t.y_cm) / 100.0);
    intruders
        .iter()
        .enumerate()
        .filter(|(i, _)| addresses[*i].is_none())
        .map(|(i, e)| {
            let s = e.relative(time).s;
            (i, (s[0] - x).hypot(s[1] - y))
        })
        .filter(|(_, d)| *d < 3000.0)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

struct DemoRun {
    timelines: Vec<Timeline>,
    clear_of_conflict_s: Vec<f64>,
    ra_scans: Vec<(f64, RaCode)>,
    /// Confirmed tracks not matched to an intruder, worst advisory.
    unmatched: Vec<(u32, Advisory)>,
}

fn run<S: Scalar, const N: usize, const M: usize, const Q: usize>() -> DemoRun {
    let config = demo_config::demo_config::<S, _>().unwrap();
    let fw = frames::run_like_the_firmware::<S, _, RangeAzimuthTrack<S>, N, M, Q>(
        &demo_input(),
        &config,
    );
    let verdict = fw.verdict.unwrap();
    assert!(verdict.is_clean(), "{}: {verdict:?}", S::NAME);
    let (messages, stats) = frames::decode_all(&fw.output);
    assert_eq!(stats.crc_errors, 0);
    let mut timelines: Vec<Timeline> = (0..4).map(|_| Timeline::default()).collect();
    let mut unmatched: Vec<(u32, Advisory)> = Vec::new();
    let mut coc = Vec::new();
    let mut ra_scans = Vec::new();
    for m in &messages {
        match m {
            Message::Track(t) => {
                let time = f64::from(t.time_ms) / 1000.0;
                let Some(i) = intruder_of(t) else {
                    match unmatched.iter_mut().find(|(id, _)| *id == t.track_id) {
                        Some(u) => u.1 = u.1.max(t.advisory),
                        None => unmatched.push((t.track_id, t.advisory)),
                    }
                    continue;
                };
                let tl = &mut timelines[i];
                let addr = t.address.map(|a| a.get());
                if !tl.addresses.contains(&addr) {
                    tl.addresses.push(addr);
                }
                tl.worst = tl.worst.max(Some(t.advisory));
                if t.advisory >= Advisory::ProximateTraffic && tl.proximate_s.is_none() {
                    tl.proximate_s = Some(time);
                }
                if t.advisory >= Advisory::Traffic && tl.ta_s.is_none() {
                    tl.ta_s = Some(time);
                }
                if t.advisory == Advisory::Resolution && tl.ra_s.is_none() {
                    tl.ra_s = Some(time);
                    tl.sense = t.ra;
                }
            }
            Message::Scan(ScanSummary {
                time_ms,
                clear_of_conflict,
                ra,
                ..
            }) => {
                if *clear_of_conflict {
                    coc.push(f64::from(*time_ms) / 1000.0);
                }
                if let Some(ra) = ra {
                    ra_scans.push((f64::from(*time_ms) / 1000.0, *ra));
                }
            }
            _ => {}
        }
    }
    DemoRun {
        timelines,
        clear_of_conflict_s: coc,
        ra_scans,
        unmatched,
    }
}

fn first(alerts: &[Vec<Alert>], i: usize, level: Alert) -> Option<usize> {
    alerts.iter().position(|a| a[i] >= level)
}

fn check<S: Scalar, const N: usize, const M: usize, const Q: usize>() {
    let r = run::<S, N, M, Q>();
    let reference = demo_reference(TCAS_DEMO_SCANS);
    let names = ["threat", "level 1000 ft", "no altitude", "abeam 1 NM"];
    println!("{} ({N} tracks, {M} per scan):", S::NAME);
    for (i, tl) in r.timelines.iter().enumerate() {
        println!(
            "  {}: proximate {:?} s, TA {:?} s (reference {:?}), RA {:?} s (reference {:?}) {}, worst {:?}, addresses {:X?}",
            names[i],
            tl.proximate_s,
            tl.ta_s,
            first(&reference, i, Alert::Ta),
            tl.ra_s,
            first(&reference, i, Alert::Ra),
            tl.sense.map_or("-", |s| s.name()),
            tl.worst,
            tl.addresses
        );
    }
    println!(
        "  clear of conflict at {:?} s; RA scans {}..{}; unmatched confirmed tracks {:?}",
        r.clear_of_conflict_s,
        r.ra_scans.first().map_or(-1.0, |s| s.0),
        r.ra_scans.last().map_or(-1.0, |s| s.0),
        r.unmatched
    );
    let threat = &r.timelines[0];
    assert!(threat.proximate_s.is_some() && threat.ta_s.is_some());
    let (ta, ra) = (threat.ta_s.unwrap(), threat.ra_s.expect("the threat's RA"));
    assert!(threat.proximate_s.unwrap() <= ta && ta < ra, "{threat:?}");
    let sense = threat.sense.expect("the RA's sense in the track report");
    // 300 ft above, level: the RA is downward (not crossing).
    assert_eq!(sense.sense, RaSense::Down);
    let coc = *r.clear_of_conflict_s.first().expect("clear of conflict");
    assert!(coc > ra, "clear of conflict at {coc} s, RA at {ra} s");
    assert_eq!(threat.addresses, vec![Some(0x004C_A123)]);
    for (name, tl) in names.iter().zip(&r.timelines).skip(1) {
        assert!(tl.worst < Some(Advisory::Resolution), "{name}: {tl:?}");
    }
    assert!(
        r.timelines[2].worst.is_some(),
        "the non-reporting intruder is tracked"
    );
    assert_eq!(r.timelines[3].addresses, vec![Some(0x003C_6601)]);
    assert!(
        r.unmatched.iter().all(|(_, a)| *a < Advisory::Traffic),
        "a false track alerted: {:?}",
        r.unmatched
    );
    // The TA starts near the reference's (true states; the trackers need a
    // few scans to be firm).
    let ta_ref = first(&reference, 0, Alert::Ta).unwrap() as f64;
    assert!(
        (ta - ta_ref).abs() <= 8.0,
        "TA at {ta} s, reference {ta_ref} s"
    );
}

#[test]
fn demo_in_f32_like_the_cortex_m4f() {
    check::<f32, 256, 256, 128>();
}

#[test]
fn demo_in_q32_32_like_the_cortex_m3() {
    check::<Fix, 256, 256, 128>();
}

#[test]
fn demo_in_q32_32_at_small_capacities() {
    check::<Fix, 8, 12, 32>();
}

#[test]
fn demo_in_the_scaled_format_like_the_cortex_m3() {
    check::<ScaledScalar, 256, 256, 128>();
}

#[test]
fn demo_in_the_scaled_format_at_small_capacities() {
    check::<ScaledScalar, 8, 12, 32>();
}

/// The micro:bit's scan-loop type (software f32) and capacities
/// (boards/qemu/src/number_types.rs, capacity.rs).
#[test]
fn demo_like_the_micro_bit() {
    check::<
        cortex_m0::Wide,
        { microbit::TRACKS },
        { microbit::MEASUREMENTS_PER_SCAN },
        { microbit::QUEUE_LEN },
    >();
}

/// One intruder tracked for 10 scans (closing at 100 m/s from 10 NM on
/// bearing 30°, exact replies), then a scan in which it does not reply and
/// another reply comes 30 m from its prediction (inside its gate), with
/// `stranger`'s identity (address, altitude ft); through the demo's
/// configuration in `S`. Returns that scan's counts.
fn dropout_scan<S: Scalar>(
    intruder: (Option<u32>, Option<f64>),
    stranger: (Option<u32>, Option<f64>),
) -> abtrack::wire::ScanCounts {
    use abtrack::scan::{MeasurementQueue, ScanLoop};
    use abtrack::wire::{MeasurementReport, ModeSAddress};
    let config = demo_config::demo_config::<S, _>().unwrap();
    let mut scan_loop: Box<ScanLoop<S, RangeAzimuthTrack<S>, 8, 12>> = Box::new(ScanLoop::new());
    let mut queue = Box::new(MeasurementQueue::<16>::new());
    let reply = |k: u32, extra_m: f64, (address, altitude): (Option<u32>, Option<f64>)| {
        let range = 10.0 * NM - 100.0 * f64::from(k) + extra_m;
        let r = MeasurementReport::polar_from_metres(
            k * 1000,
            1,
            range,
            std::f64::consts::FRAC_PI_6,
            altitude,
        )
        .unwrap();
        match address {
            Some(a) => r.with_mode_s(ModeSAddress::new(a).unwrap(), false),
            None => r,
        }
    };
    let mut last = None;
    for k in 0..11u32 {
        let r = if k < 10 {
            reply(k, 0.0, intruder)
        } else {
            reply(k, 30.0, stranger)
        };
        queue.push(r).unwrap();
        let tick = scan_loop.on_tick(&config, queue.as_mut(), |_| {}).unwrap();
        last = Some(tick.summary.counts);
    }
    let counts = last.unwrap();
    assert_eq!((counts.used, counts.confirmed_tracks), (1, 1));
    counts
}

/// Reply identity: a reply inside a track's gate updates it only if it is
/// its intruder's: the same Mode S address, or (Mode C) no address and an
/// altitude that correlates; otherwise the track coasts and the reply is
/// counted outside the gates (a first point for a track of its own).
#[test]
fn replies_go_only_to_their_own_tracks() {
    fn check<S: Scalar>() {
        let mode_s = |a: u32| (Some(a), Some(8300.0));
        let mode_c = |z: f64| (None, Some(z));
        for (intruder, stranger, updates) in [
            (mode_s(0xA00001), mode_s(0xA00001), true),
            (mode_s(0xA00001), mode_s(0xA00002), false),
            (mode_s(0xA00001), mode_c(8300.0), false),
            (mode_c(8300.0), mode_s(0xA00002), false),
            (mode_c(8300.0), mode_c(8300.0), true),
            (mode_c(8300.0), mode_c(8400.0), true),
            (mode_c(8300.0), mode_c(10300.0), false),
            (mode_c(8300.0), (None, None), true),
        ] {
            let c = dropout_scan::<S>(intruder, stranger);
            let case = format!("{}: {intruder:?} then {stranger:?}: {c}", S::NAME);
            if updates {
                assert_eq!((c.updated, c.coasted, c.outside_gates), (1, 0, 0), "{case}");
            } else {
                assert_eq!((c.updated, c.coasted, c.outside_gates), (0, 1, 1), "{case}");
            }
        }
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
    check::<ScaledScalar>();
}
