//! The demo's scan-loop configurations, the own aircraft at the origin:
//!
//! * [`demo_config`], the firmware's: TCAS surveillance, the
//!   range–azimuth tracker of [`default_polar`] (σ_R = 15.24 m, σ_B = 5°,
//!   the 14 NM disc), altitude trackers for 100 ft and 25 ft reports, own
//!   aircraft level at 8000 ft;
//! * [`crossing_config`]: the αβ tracker tuned for the 20 m-class
//!   Cartesian radar of the multi-target scenarios (`two-crossing`,
//!   `parallel-200m`: σ = 20 m per axis, T = 1 s, targets up to ~150 m/s,
//!   clutter over a 10 km × 10 km square), for the host tests of the scan
//!   loop and (with a larger square) the soak.
//!
//! Depends on the abtrack library only, so it builds for the host too: the
//! firmware (demo and soak) uses it, and so do the host tests, which run
//! this exact configuration on the same inputs on the host.

use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::RangeAzimuthNoise;
use abtrack::scan::{ClockConfig, ScanConfig};
use abtrack::tcas::OwnAircraft;
use abtrack::track::defaults::default_polar;
use abtrack::track::{Gate, TrackerConfig, Volume};
use abtrack::{Gains, Numeric, Scalar};

/// The scan period, ms: the sensor's (one scan per second). The scan
/// clock's windows are `ClockConfig::new`'s: late up to one period after
/// the scan, a silence of up to 30 periods is a gap, a longer step a jump.
pub const SCAN_PERIOD_MS: u32 = 1000;

/// The own aircraft: level at 8000 ft over the sea (TCAS sensitivity level
/// 5: TA tau 40 s, DMOD 0.75 NM).
pub const OWN_ALTITUDE_FT: f64 = 8000.0;

/// αβ gains: α = 0.5 with the Benedict–Bordner β = α²/(2 − α) = 1/6
/// (Al-Wagih & Abdulla, method M1).
pub const ALPHA: f64 = 0.5;
pub const BETA: f64 = ALPHA * ALPHA / (2.0 - ALPHA);

/// Uncertainty gate: the sensor's σ (m), the χ² threshold G = 13.8 (99.9 %
/// for two degrees of freedom) and a manoeuvre allowance of 5 m/s².
pub const MEASUREMENT_SIGMA_M: f64 = 20.0;
pub const GATE_THRESHOLD: f64 = 13.8;
pub const MAX_ACCELERATION_M_PER_S2: f64 = 5.0;

/// Two-point initiation: targets up to 300 m/s, plus 100 m for the noise on
/// the two points (3σ√2 = 85 m).
pub const MAX_SPEED_M_PER_S: f64 = 300.0;
pub const INITIATION_MARGIN_M: f64 = 100.0;

/// The surveillance square, ±5 km around the own aircraft.
pub const SURVEILLANCE_HALF_WIDTH_M: f64 = 5000.0;

/// The firmware's configuration in the number type `S` (TCAS
/// surveillance); `Err` names what was refused.
pub fn demo_config<N: Numeric<Wide = S>, S: Scalar>(
) -> Result<ScanConfig<N, RangeAzimuthNoise<S>>, &'static str> {
    let s = |v: f64| S::try_from_f64(v).map_err(|_| "a constant is not representable");
    Ok(ScanConfig {
        // The scan loop keeps the previous scan's replies only, so its
        // identity rule starts no track from an earlier scan's first point.
        tracker: default_polar()
            .map_err(|_| "tracker configuration refused")?
            .keep_first_points_through_a_miss(false),
        own: OwnAircraft::over_sea_level(s(OWN_ALTITUDE_FT)?, S::ZERO),
        altitude: altitude_config(AltitudeQuantum::ModeC)?,
        altitude_25ft: altitude_config(AltitudeQuantum::ModeS25)?,
        clock: ClockConfig::new(SCAN_PERIOD_MS).map_err(|_| "scan period refused")?,
    })
}

fn altitude_config<S: Scalar>(
    quantum: AltitudeQuantum,
) -> Result<AltitudeTrackerConfig<S>, &'static str> {
    AltitudeTrackerConfig::default_for(quantum).map_err(|_| "altitude tracker refused")
}

/// The Cartesian configuration of the `two-crossing` scenario (±5 km).
pub fn crossing_config<N: Numeric<Wide = S>, S: Scalar>(
) -> Result<ScanConfig<N, Gains<S>>, &'static str> {
    config_for_square(SURVEILLANCE_HALF_WIDTH_M)
}

/// [`crossing_config`] with a surveillance square of ±`half_width_m`
/// (the soak's sky is ±16 km).
pub fn config_for_square<N: Numeric<Wide = S>, S: Scalar>(
    half_width_m: f64,
) -> Result<ScanConfig<N, Gains<S>>, &'static str> {
    let s = |v: f64| S::try_from_f64(v).map_err(|_| "a constant is not representable");
    let gains = Gains::alpha_beta_f64(ALPHA, BETA).map_err(|_| "gains refused")?;
    let gate = Gate::uncertainty(
        s(MEASUREMENT_SIGMA_M)?,
        s(GATE_THRESHOLD)?,
        s(MAX_ACCELERATION_M_PER_S2)?,
    )
    .map_err(|_| "gate refused")?;
    let half = s(half_width_m)?;
    let volume = Volume::new([-half, -half], [half, half]).map_err(|_| "volume refused")?;
    let margin = s(INITIATION_MARGIN_M)?;
    let tracker = TrackerConfig::new(gains, gate, s(MAX_SPEED_M_PER_S)?)
        .and_then(|c| c.with_initiation_margin(margin))
        .map_err(|_| "tracker configuration refused")?
        .with_volume(volume)
        // The scan loop keeps the previous scan's replies only, so its
        // identity rule starts no track from an earlier scan's first point.
        .keep_first_points_through_a_miss(false);
    let clock = ClockConfig::new(SCAN_PERIOD_MS).map_err(|_| "scan period refused")?;
    Ok(ScanConfig {
        tracker,
        own: OwnAircraft::over_sea_level(s(OWN_ALTITUDE_FT)?, S::ZERO),
        altitude: altitude_config(AltitudeQuantum::ModeC)?,
        altitude_25ft: altitude_config(AltitudeQuantum::ModeS25)?,
        clock,
    })
}
