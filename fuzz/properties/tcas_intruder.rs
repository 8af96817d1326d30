//! One TCAS intruder through what the scan loop runs for it each scan, with
//! arbitrary replies, intervals and own aircraft: the bearing track
//! (`RangeAzimuthFilter::update` or `coast`), the range and altitude
//! trackers (`IntruderTrack::scan`), the threat logic
//! (`IntruderTrack::assess`) and the resolution
//! (`CollisionAvoidance::resolve`), in `f32` (the Cortex-M4F's and the
//! micro:bit's type) and `ScaledScalar` (the Cortex-M3's wide format).
//!
//! The input is the own aircraft's altitude and rate, then a sequence of
//! scans: each an interval (1 s, other valid ones, zero, negative, NaN,
//! huge) and a reply or none; a reply is either an intruder flying past
//! plus noise (so the trackers firm up and advisories arise) or any values
//! at all (NaN, infinities, huge, negative ranges), with or without an
//! altitude.
//!
//! Properties (beyond "never panics"):
//! - a refused bearing update or coast leaves the bearing track unchanged
//!   (its `Debug` text) but for its saturation count, which a refusal for
//!   saturation raises by one;
//! - the range tracker's and the altitude tracker's estimates, whenever
//!   they give one, are valid numbers, whatever was refused before: a bad
//!   reply is counted, it never corrupts a track;
//! - an RA from the resolution comes only in a cycle whose threat status
//!   is an RA.

use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::filter::FilterError;
use abtrack::tcas::{
    Advisory, CollisionAvoidance, IntruderTrack, OwnAircraft, Reply, ThreatGeometry,
    MAX_CLOSURE_SPEED_M_PER_S,
};
use abtrack::{Scalar, ScaledScalar};
use arbitrary::{Result, Unstructured};

const MAX_SCANS: usize = 200;

/// One scan of the input, in f64 (converted to each type).
struct Scan {
    dt: f64,
    /// Range (m), bearing (rad), altitude (ft).
    reply: Option<(f64, f64, Option<f64>)>,
}

/// The own aircraft and the scans.
struct Input {
    own_altitude_ft: f64,
    own_rate_ft_per_s: f64,
    quantum: AltitudeQuantum,
    scans: Vec<Scan>,
}

fn value(u: &mut Unstructured) -> Result<f64> {
    Ok(match u.int_in_range(0u8..=3)? {
        0 => f64::from_bits(u.arbitrary()?),
        1 => [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            0.0,
            -1.0,
        ][u.choose_index(7)?],
        _ => f64::from(u.int_in_range(-100_000_000i32..=100_000_000)?) / 1000.0,
    })
}

fn input(u: &mut Unstructured) -> Result<Input> {
    let own_altitude_ft = if u.ratio(1u8, 8)? {
        value(u)?
    } else {
        f64::from(u.int_in_range(0i32..=45_000)?)
    };
    let own_rate_ft_per_s = if u.ratio(1u8, 8)? {
        value(u)?
    } else {
        f64::from(u.int_in_range(-100i32..=100)?)
    };
    let quantum = if u.arbitrary()? {
        AltitudeQuantum::ModeS25
    } else {
        AltitudeQuantum::ModeC
    };
    // The intruder: relative position (m), velocity (m/s), altitude (ft)
    // and rate (ft/s), flown straight.
    let mut x = f64::from(u.int_in_range(-20_000i32..=20_000)?);
    let mut y = f64::from(u.int_in_range(2_000i32..=40_000)?);
    let vx = f64::from(u.int_in_range(-300i32..=300)?);
    let vy = -f64::from(u.int_in_range(0i32..=600)?);
    let mut z = own_altitude_ft + f64::from(u.int_in_range(-3000i32..=3000)?);
    let vz = f64::from(u.int_in_range(-60i32..=60)?);
    let mut scans = Vec::new();
    while !u.is_empty() && scans.len() < MAX_SCANS {
        let dt = match u.int_in_range(0u8..=15)? {
            0 => value(u)?,
            1 => f64::from(u.int_in_range(1u32..=30_000)?) / 1000.0,
            _ => 1.0,
        };
        if dt.is_finite() && dt > 0.0 {
            let step = dt.min(100.0);
            x += vx * step;
            y += vy * step;
            z += vz * step;
        }
        let reply = match u.int_in_range(0u8..=7)? {
            0 => None,
            1 => Some((
                value(u)?,
                value(u)?,
                if u.arbitrary()? {
                    Some(value(u)?)
                } else {
                    None
                },
            )),
            _ => {
                let noise = |u: &mut Unstructured, scale: f64| -> Result<f64> {
                    Ok(f64::from(u.int_in_range(-30i32..=30)?) * scale)
                };
                let range = (x * x + y * y).sqrt() + noise(u, 1.0)?;
                let bearing = x.atan2(y) + noise(u, 0.005)?;
                let altitude = if u.ratio(1u8, 8)? {
                    None
                } else {
                    let q = match quantum {
                        AltitudeQuantum::ModeS25 => 25.0,
                        AltitudeQuantum::ModeC => 100.0,
                    };
                    Some((z / q).round() * q)
                };
                Some((range, bearing, altitude))
            }
        };
        scans.push(Scan { dt, reply });
    }
    Ok(Input {
        own_altitude_ft,
        own_rate_ft_per_s,
        quantum,
        scans,
    })
}

fn run<S: Scalar + core::fmt::Debug>(input: &Input) {
    let c = |v: f64| S::from_f64_lossy(v);
    let altitude = AltitudeTrackerConfig::<S>::default_for(input.quantum)
        .expect("the default altitude configuration is valid");
    let noise = RangeAzimuthNoise::<S>::new_f64(15.0 * 15.0, 0.0873 * 0.0873, 1.0)
        .and_then(|n| n.with_speed_bound_f64(MAX_CLOSURE_SPEED_M_PER_S))
        .expect("the bearing track's noise is valid");
    let mut bearing = RangeAzimuthFilter::<S>::new(noise);
    let mut track = IntruderTrack::<S>::new();
    let mut cas = CollisionAvoidance::<S>::new();
    let own = OwnAircraft::over_sea_level(c(input.own_altitude_ft), c(input.own_rate_ft_per_s));
    for scan in &input.scans {
        let dt = c(scan.dt);
        let (before, saturations) = (without_count(&bearing), bearing.saturations());
        let bearing_result = match scan.reply {
            Some((range, azimuth, _)) => bearing.update(c(range), c(azimuth), dt).map(|_| ()),
            None => bearing.coast(dt),
        };
        if let Err(e) = bearing_result {
            assert_eq!(
                without_count(&bearing),
                before,
                "a refused bearing update ({e:?}) changed the track"
            );
            let counted = u32::from(e == FilterError::Saturated);
            // The count saturates at u16::MAX.
            let expected = saturations.saturating_add(counted).min(u32::from(u16::MAX));
            assert_eq!(bearing.saturations(), expected, "{e:?}");
        }
        let reply = scan.reply.map(|(range, _, altitude_ft)| Reply {
            range_m: c(range),
            altitude_ft: altitude_ft.map(c),
        });
        // A refused reply is counted by the caller; the trackers coast.
        let _ = track.scan(&altitude, reply, dt);
        if let Some(r) = track.range_tracker().estimate() {
            assert!(
                [
                    r.range_m,
                    r.range_rate_m_per_s,
                    r.range_acceleration_m_per_s2
                ]
                .iter()
                .all(|v| v.is_valid()),
                "the range tracker's estimate is not valid: {r:?}"
            );
        }
        if let Some(a) = track.altitude_state().estimate() {
            assert!(
                a.altitude_ft.is_valid() && a.vertical_rate_ft_per_s.is_valid(),
                "the altitude tracker's estimate is not valid: {a:?}"
            );
        }
        // An own aircraft the logic refuses ends the cycle here, as the
        // scan loop counts it and goes on.
        let Ok(cycle) = cas.begin_cycle(&own, false) else {
            continue;
        };
        let Ok(status) = track.assess(&cycle, Some(&bearing), dt) else {
            continue;
        };
        let threats: Vec<ThreatGeometry<S>> = status.and_then(|s| s.geometry).into_iter().collect();
        if let Ok(resolution) = cas.resolve(&cycle, &threats, dt) {
            if resolution.advisory.is_some() {
                assert_eq!(
                    status.map(|s| s.advisory),
                    Some(Advisory::Resolution),
                    "an RA without an RA threat"
                );
            }
        }
    }
}

/// The bearing track's `Debug` text without its saturation count.
fn without_count<S: Scalar + core::fmt::Debug>(bearing: &RangeAzimuthFilter<S>) -> String {
    let text = format!("{bearing:?}");
    match text.find("saturations:") {
        Some(at) => text[..at].to_string(),
        None => text,
    }
}

/// Runs the input in every type; panics on a failed property.
pub fn check(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let Ok(input) = input(&mut u) else { return };
    run::<f32>(&input);
    run::<ScaledScalar>(&input);
}
