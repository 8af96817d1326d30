//! Every TCAS component and the scan loop named with `Fixed32` (the
//! Cortex-M3 firmware's filter type): they compute in its wide format
//! (`Numeric::Wide`, `ScaledScalar`), so each output equals the one of the
//! same component named with `ScaledScalar` itself, bit for bit.

use abtrack::filter::altitude::{
    AltitudeEstimate, AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig,
};
use abtrack::filter::range_azimuth::RangeAzimuthNoise;
use abtrack::tcas::{
    CollisionAvoidance, IntruderTrack, OwnAircraft, RangeEstimate, RangeTracker, Reply,
    ResolutionOutput, ThreatStatus,
};
use abtrack::track::{Measurement, Observation, RangeAzimuthTrack, ScanInterval, TrackFilter};
use abtrack::{Fixed32, Numeric, Scalar, ScaledScalar};
use abtrack_firmware::capacity::microbit;
use abtrack_firmware::demo_config;
use abtrack_host_tests::frames::{self, Faults, TCAS_DEMO};

/// One scan's outputs of every component.
#[derive(Debug, PartialEq)]
struct ScanOutputs<S> {
    range: Option<RangeEstimate<S>>,
    altitude: Option<AltitudeEstimate<S>>,
    bearing_position: [S; 2],
    status: Option<ThreatStatus<S>>,
    resolution: ResolutionOutput<S>,
}

/// A head-on intruder 200 ft above, closing at 250 m/s from 15 km on a
/// bearing of 20°, one scan a second to the closest approach: the range
/// tracker, the altitude tracker and the range–azimuth track on their own,
/// and the intruder's track, the threat assessment and the resolution
/// advisory of one TCAS cycle per scan, each named with `N`.
fn head_on<N: Numeric<Wide = S>, S: Scalar>() -> Vec<ScanOutputs<S>> {
    let s = S::from_f64_lossy;
    let dt = S::ONE;
    let mut cas = CollisionAvoidance::<N>::new();
    let altitude_config = AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeC).unwrap();
    let mut intruder = IntruderTrack::<N>::new();
    let mut range_tracker = RangeTracker::<N>::new();
    let mut altitude_tracker = AltitudeTracker::<N>::new(altitude_config);
    let noise = RangeAzimuthNoise::new_f64(15.0 * 15.0, 0.087 * 0.087, 1.0)
        .and_then(|n| n.with_speed_bound_f64(600.0))
        .unwrap();
    let mut bearing = RangeAzimuthTrack::<N>::empty(&noise);
    let step = ScanInterval::from_ms(1000).unwrap();
    let own = OwnAircraft::over_sea_level(s(10_000.0), S::ZERO);
    let bearing_rad = 20f64.to_radians();
    (0..60)
        .map(|t| {
            let range_m = 15_000.0 - 250.0 * f64::from(t);
            let altitude_ft = Some(s(10_200.0));
            let cycle = cas.begin_cycle(&own, false).unwrap();
            let reply = Reply {
                range_m: s(range_m),
                altitude_ft,
            };
            intruder.scan(&altitude_config, Some(reply), dt).unwrap();
            range_tracker.update(s(range_m), dt).unwrap();
            altitude_tracker.scan(altitude_ft, dt).unwrap();
            let z = Observation::new(Measurement::Polar {
                range: s(range_m),
                azimuth: s(bearing_rad),
            })
            .unwrap();
            bearing.update(&noise, &z, &step).unwrap();
            let status = intruder.assess(&cycle, Some(bearing.state()), dt).unwrap();
            let threats: Vec<_> = status.and_then(|st| st.geometry).into_iter().collect();
            let resolution = cas.resolve(&cycle, &threats, dt).unwrap();
            ScanOutputs {
                range: range_tracker.estimate(),
                altitude: altitude_tracker.estimate(),
                bearing_position: bearing.position(),
                status,
                resolution,
            }
        })
        .collect()
}

#[test]
fn tcas_components_in_fixed32_equal_its_wide_format() {
    let fixed = head_on::<Fixed32, _>();
    let wide = head_on::<ScaledScalar, _>();
    assert_eq!(fixed, wide);
    // Not a vacuous comparison: the encounter ends in a resolution advisory.
    assert!(
        fixed.iter().any(|o| o.resolution.advisory.is_some()),
        "no resolution advisory"
    );
}

/// The firmware's demo input (no faults) through the scan loop with the
/// micro:bit's capacities, named with `N`: the report frames it sends.
fn demo_frames<N: Numeric<Wide = S>, S: Scalar>() -> frames::FirmwareRun {
    let reports = frames::scenario_reports(TCAS_DEMO, 1, 1).unwrap();
    let input = frames::encode(&reports, Faults::default()).bytes;
    let config = demo_config::demo_config::<N, _>().unwrap();
    frames::run_like_the_firmware::<
        N,
        _,
        RangeAzimuthTrack<N>,
        { microbit::TRACKS },
        { microbit::MEASUREMENTS_PER_SCAN },
        { microbit::QUEUE_LEN },
    >(&input, &config)
}

#[test]
fn scan_loop_in_fixed32_equals_its_wide_format() {
    let fixed = demo_frames::<Fixed32, _>();
    let wide = demo_frames::<ScaledScalar, _>();
    assert!(!fixed.output.is_empty());
    assert_eq!(fixed.output, wide.output);
    assert_eq!(fixed.ticks, wide.ticks);
    assert_eq!(fixed.health, wide.health);
}
