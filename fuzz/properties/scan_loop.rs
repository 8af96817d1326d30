//! The TCAS scan loop (`abtrack::scan::ScanLoop`, the firmware's): arbitrary
//! replies and times through `on_tick` with the demo's configuration
//! (`demo_config::demo_config`: range–azimuth tracks, Mode S and Mode C
//! reply identity, the TCAS logic), in a small loop (8 tracks, 12 replies a
//! scan, a 16-reply queue) so that the table fills, scans overflow and
//! tracks are deleted and started again, in `f32` (the Cortex-M4F's type)
//! and the fast fixed point (`Fixed32`, the M3's).
//!
//! The input is a sequence of scans: each a time step (mostly a scan period,
//! sometimes zero, backwards or a long gap) and up to 20 replies, each from
//! one of four intruders moving in range and azimuth (with its own Mode S
//! address, another intruder's, or none, and an altitude or none) or any
//! position, time and altitude at all.
//!
//! Properties (beyond "never panics"):
//! - reply identity: no two live tracks hold one Mode S address, and a
//!   deleted track keeps none;
//! - counts add up: a scan summary's used replies equal the sum of the
//!   tracker's outcomes for them (updated, started, not assigned, outside
//!   the gates, outside the volume, rejected, refused with the table full),
//!   and its track counts are the table's.

use std::collections::BTreeSet;

use abtrack::num::fixed32::Fixed32;
use abtrack::scan::{MeasurementQueue, ScanConfig, ScanLoop};
use abtrack::track::RangeAzimuthTrack;
use abtrack::wire::{MeasuredPosition, MeasurementReport, Message, ModeSAddress};
use abtrack::{Numeric, Scalar};
use arbitrary::{Result, Unstructured};

use abtrack::filter::range_azimuth::RangeAzimuthNoise;
use abtrack_firmware::demo_config;

const TRACKS: usize = 8;
const PER_SCAN: usize = 12;
const QUEUE: usize = 16;
const MAX_REPLIES: usize = 20;
const INTRUDERS: usize = 4;
/// The intruders' own addresses (the first three; the fourth is Mode C).
const ADDRESSES: [u32; 3] = [0x4CA123, 0x3C6601, 0xABCDEF];

/// One scan of the input: its replies (the loop's clock follows their
/// times; it runs one scan per tick).
struct Scan {
    replies: Vec<MeasurementReport>,
}

fn address(u: &mut Unstructured, own: usize) -> Result<Option<ModeSAddress>> {
    Ok(match u.int_in_range(0u8..=7)? {
        // Another intruder's address, or none.
        0 => ModeSAddress::new(ADDRESSES[u.choose_index(ADDRESSES.len())?]),
        1 => None,
        _ => ADDRESSES.get(own).and_then(|&a| ModeSAddress::new(a)),
    })
}

fn scans(u: &mut Unstructured) -> Result<Vec<Scan>> {
    // Intruders: range (m), range rate (m/s), azimuth (rad), its rate
    // (rad/s), altitude (ft) and its rate (ft/s).
    let mut intruders = [[0.0f64; 6]; INTRUDERS];
    for i in &mut intruders {
        i[0] = f64::from(u.int_in_range(500i32..=30_000)?);
        i[1] = f64::from(u.int_in_range(-300i32..=100)?);
        i[2] = f64::from(u.int_in_range(0i32..=6283)?) / 1000.0;
        i[3] = f64::from(u.int_in_range(-20i32..=20)?) / 1000.0;
        i[4] = f64::from(u.int_in_range(-1000i32..=40_000)?);
        i[5] = f64::from(u.int_in_range(-100i32..=100)?);
    }
    let mut time_ms = 0u32;
    let mut scans = Vec::new();
    while !u.is_empty() && scans.len() < 64 {
        let step_ms = match u.int_in_range(0u8..=15)? {
            0 => 0,
            1 => u.arbitrary()?,
            2 => 0u32.wrapping_sub(u.int_in_range(1..=5000)?),
            3 => u.int_in_range(5000..=60_000)?,
            _ => 1000 + u.int_in_range(0..=40)?,
        };
        time_ms = time_ms.wrapping_add(step_ms);
        let dt = f64::from(step_ms.min(60_000)) / 1000.0;
        for i in &mut intruders {
            i[0] = (i[0] + i[1] * dt).max(0.0);
            i[2] += i[3] * dt;
            i[4] += i[5] * dt;
        }
        let n = u.int_in_range(0..=MAX_REPLIES)?;
        let mut replies = Vec::with_capacity(n);
        for _ in 0..n {
            let reply = if u.ratio(1u8, 6)? {
                MeasurementReport {
                    time_ms: time_ms.wrapping_add(u.int_in_range(0..=2000)?),
                    sensor: u.arbitrary()?,
                    position: if u.arbitrary()? {
                        MeasuredPosition::Polar {
                            range_cm: u.arbitrary()?,
                            azimuth_bam: u.arbitrary()?,
                        }
                    } else {
                        MeasuredPosition::Cartesian {
                            x_cm: u.arbitrary()?,
                            y_cm: u.arbitrary()?,
                        }
                    },
                    altitude_ft: u.arbitrary()?,
                    altitude_25ft: u.arbitrary()?,
                    address: ModeSAddress::new(u.int_in_range(0..=0xFF_FFFF)?),
                }
            } else {
                let k = u.choose_index(INTRUDERS)?;
                let i = intruders[k];
                let range = i[0] + f64::from(u.int_in_range(-30i32..=30)?);
                let azimuth = i[2] + f64::from(u.int_in_range(-90i32..=90)?) / 1000.0;
                let altitude = if u.ratio(1u8, 8)? {
                    None
                } else {
                    Some(i[4] + f64::from(u.int_in_range(-50i32..=50)?))
                };
                let Ok(r) = MeasurementReport::polar_from_metres(
                    time_ms,
                    1,
                    range.max(0.0),
                    azimuth,
                    altitude,
                ) else {
                    continue;
                };
                match address(u, k)? {
                    Some(a) => r.with_mode_s(a, u.arbitrary()?),
                    None => r,
                }
            };
            replies.push(reply);
        }
        scans.push(Scan { replies });
    }
    Ok(scans)
}

fn run<T: Numeric<Wide = S>, S: Scalar>(scans: &[Scan]) {
    let Ok(config): core::result::Result<ScanConfig<T, RangeAzimuthNoise<S>>, _> =
        demo_config::demo_config::<T, S>()
    else {
        panic!("the demo's configuration is refused");
    };
    let mut scan_loop: Box<ScanLoop<T, RangeAzimuthTrack<T>, TRACKS, PER_SCAN>> =
        Box::new(ScanLoop::new());
    let mut seen = BTreeSet::new();
    let mut queue = Box::new(MeasurementQueue::<QUEUE>::new());
    for scan in scans {
        for r in &scan.replies {
            // A full queue drops the reply, as the firmware's intake does.
            let _ = queue.push(*r);
        }
        let mut summaries = Vec::new();
        let tick = scan_loop.on_tick(&config, queue.as_mut(), |m| {
            if let Message::Scan(s) = m {
                summaries.push(*s);
            }
        });
        let Ok(tick) = tick else {
            assert!(summaries.is_empty(), "a refused tick emitted a summary");
            continue;
        };
        let c = tick.summary.counts;
        let outcomes = u32::from(c.updated)
            + u32::from(c.started)
            + u32::from(c.not_assigned)
            + u32::from(c.outside_gates)
            + u32::from(c.outside_volume)
            + u32::from(c.rejected)
            + u32::from(c.refused_table_full);
        assert_eq!(u32::from(c.used), outcomes, "used replies by outcome: {c}");
        let table = scan_loop.table();
        assert_eq!(usize::from(c.tracks), table.len(), "{c}");
        let live: Vec<_> = table.tracks().map(|t| t.id()).collect();
        let mut held = BTreeSet::new();
        for &id in &live {
            seen.insert(id);
            if let Some(a) = scan_loop.address(id) {
                assert!(held.insert(a), "two live tracks hold {a:?}");
            }
        }
        for id in seen.iter().filter(|id| !live.contains(id)) {
            assert_eq!(
                scan_loop.address(*id),
                None,
                "deleted track {id:?} holds an address"
            );
        }
    }
}

/// Runs the input's scans through the scan loop in `f32` and `Fixed32`.
pub fn check(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let Ok(scans) = scans(&mut u) else {
        return;
    };
    run::<f32, f32>(&scans);
    run::<Fixed32, <Fixed32 as Numeric>::Wide>(&scans);
}
