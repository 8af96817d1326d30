//! One TCAS cycle per second against a head-on intruder, in the Cortex-M3
//! firmware's type `Fixed32` (the logic computes in its wide format,
//! `<Fixed32 as Numeric>::Wide`): the range tracker and the altitude tracker
//! (inside `IntruderTrack`, which takes the altitude tracker's configuration
//! at each scan), the bearing filter (`RangeAzimuthFilter`, a
//! separate track whose miss distance the threat logic cross-checks), the
//! threat assessment and the resolution advisory.
//!
//! Runs on the host (the repository's `.cargo/config.toml` picks a thumb
//! target, so name the host's):
//!
//! ```text
//! cargo run --release --example tcas_cycle --target x86_64-unknown-linux-gnu
//! ```
//!
//! It prints each change of advisory and exits with status 1 if no
//! resolution advisory was issued before the closest approach.

use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::tcas::{Advisory, CollisionAvoidance, IntruderTrack, OwnAircraft, Reply};
use abtrack::{Fixed32, Numeric, Quantity, Real};

/// The Cortex-M3's type (boards/qemu/src/number_types.rs,
/// `cortex_m3::Native`); `f32` on the Cortex-M4F.
type N = Fixed32;
/// Its one type for every quantity: the inputs and outputs of the logic.
type S = <N as Numeric>::Wide;

/// The sensor: range σ 15 m, bearing σ 5° (a TCAS directional antenna).
const RANGE_SIGMA_M: f64 = 15.0;
const BEARING_SIGMA_RAD: f64 = 5.0 * core::f64::consts::PI / 180.0;
/// The bearing filter's process noise, m²/s⁴, and the fastest closure it
/// initiates a track for, m/s.
const PROCESS_NOISE: f64 = 1.0;
const MAX_CLOSURE_M_PER_S: f64 = 600.0;

/// The encounter: own aircraft level at 10,000 ft; the intruder 15 km away
/// on a bearing of 20°, closing head-on at 250 m/s, level 200 ft above.
const OWN_ALTITUDE_FT: f64 = 10_000.0;
const INTRUDER_ALTITUDE_FT: f64 = 10_200.0;
const START_RANGE_M: f64 = 15_000.0;
const CLOSURE_M_PER_S: f64 = 250.0;
const BEARING_RAD: f64 = 20.0 * core::f64::consts::PI / 180.0;

fn main() {
    if let Err(e) = run() {
        eprintln!("tcas_cycle: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let s = S::from_f64_lossy;
    let dt = S::ONE;
    let mut cas = CollisionAvoidance::<N>::new();
    // 100 ft steps (Mode C); Mode S with the Q bit reports in 25 ft steps.
    let altitude =
        AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeC).map_err(|e| e.to_string())?;
    let mut intruder = IntruderTrack::<N>::new();
    let noise = RangeAzimuthNoise::<S>::new_f64(
        RANGE_SIGMA_M * RANGE_SIGMA_M,
        BEARING_SIGMA_RAD * BEARING_SIGMA_RAD,
        PROCESS_NOISE,
    )
    .and_then(|n| n.with_speed_bound_f64(MAX_CLOSURE_M_PER_S))
    .map_err(|e| e.to_string())?;
    // The bearing filter, a separate track, runs in the same wide type.
    let mut bearing_filter = RangeAzimuthFilter::<S>::new(noise);
    let own = OwnAircraft::over_sea_level(s(OWN_ALTITUDE_FT), S::ZERO);

    let mut shown = Advisory::None;
    let mut resolution_seen = false;
    let scans = (START_RANGE_M / CLOSURE_M_PER_S) as u32;
    for t in 0..scans {
        let range_m = START_RANGE_M - CLOSURE_M_PER_S * f64::from(t);
        // 1. The sensitivity level and inhibits for this cycle.
        let cycle = cas.begin_cycle(&own, false).map_err(|e| e.to_string())?;
        // 2. The intruder's reply: range and Mode C altitude.
        let reply = Reply {
            range_m: s(range_m),
            altitude_ft: Some(s(INTRUDER_ALTITUDE_FT)),
        };
        intruder
            .scan(&altitude, Some(reply), dt)
            .map_err(|e| e.to_string())?;
        // 3. The bearing track, from the same reply's range and azimuth.
        bearing_filter
            .update(s(range_m), s(BEARING_RAD), dt)
            .map_err(|e| e.to_string())?;
        // 4. The threat assessment (None until the range rate is known).
        let status = intruder
            .assess(&cycle, Some(&bearing_filter), dt)
            .map_err(|e| e.to_string())?;
        // 5. The resolution advisory against this cycle's RA threats.
        let threats: Vec<_> = status.and_then(|st| st.geometry).into_iter().collect();
        let ra = cas
            .resolve(&cycle, &threats, dt)
            .map_err(|e| e.to_string())?;

        let advisory = status.map_or(Advisory::None, |st| st.advisory);
        if advisory != shown {
            println!("t={t:2} s  range {range_m:6.0} m  advisory {advisory:?}");
            shown = advisory;
        }
        if let Some(a) = ra.advisory {
            if !resolution_seen {
                println!(
                    "t={t:2} s  resolution advisory: sense {}, goal {:+.0} ft/min",
                    a.sense.name(),
                    a.goal_rate_ft_per_s.to_f64() * 60.0
                );
            }
            resolution_seen = true;
        }
    }
    if !resolution_seen {
        return Err("no resolution advisory before the closest approach".into());
    }
    Ok(())
}
