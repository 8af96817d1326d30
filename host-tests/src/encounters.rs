//! The TCAS encounter suite: straight-line encounters (the
//! intruder may change its vertical rate), flown open loop (the own
//! aircraft does not follow the RA), scanned once a second. Each is run
//! through the library — range tracker, altitude tracker, the He et al.
//! range–azimuth filter as bearing tracker, threat logic, resolution — on
//! exact inputs or with sensor noise, in f64, f32 or Q32.32, and through the
//! independent reference ([`crate::reference_tcas`]) on the true states,
//! which gives the expected timeline.
//!
//! Also the demo scenario ([`demo_scenario`]), the
//! firmware's default input (`frames encode --scenario tcas-demo`,
//! scripts/demo-input.sh).

use std::f64::consts::PI;

use abtrack::envelope::{POSITION_M, VELOCITY_M_PER_S};
use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::tcas::{
    Advisory, CollisionAvoidance, IntruderTrack, OwnAircraft, RaSense, Reply, ThreatGeometry,
    MAX_CLOSURE_SPEED_M_PER_S,
};
use abtrack::Scalar;

use crate::altitude_figures::{report, Profile, RateChange};
use crate::noise::{derive_seed, rng_from_seed, standard_normal, uniform, SimRng};
use crate::recorded_encounters::RecordedIntruder;
use crate::reference_tcas::{self, Alert, Own, Reference, Relative, Sense};

/// Metres per nautical mile, per knot.
pub const NM: f64 = 1852.0;
pub const KT: f64 = 1852.0 / 3600.0;

/// Range noise σ of the noisy runs, m (TCAS surveillance: ≈ 15 m).
pub const RANGE_SIGMA_M: f64 = 15.0;
/// Bearing noise σ of the noisy runs, rad (5°: "several degrees").
pub const BEARING_SIGMA_RAD: f64 = 5.0 * PI / 180.0;
/// Process noise of the bearing tracker, (m/s²)².
pub const BEARING_TRACKER_PROCESS_NOISE: f64 = 1.0;
/// An alert more than this from every scan at which the reference has it
/// is false, s.
pub const FALSE_ALERT_TOLERANCE_S: f64 = 3.0;

/// One encounter: the own aircraft level and straight, the intruder's path.
#[derive(Debug, Clone, Copy)]
pub struct Encounter {
    pub name: &'static str,
    pub description: &'static str,
    /// Own pressure altitude (level), ft.
    pub own_altitude_ft: f64,
    /// Own ground velocity, m/s.
    pub own_velocity: [f64; 2],
    pub intruder: IntruderPath,
    pub quantum: AltitudeQuantum,
    /// Scans (1 s each).
    pub scans: usize,
}

/// How the intruder moves.
#[derive(Debug, Clone, Copy)]
pub enum IntruderPath {
    /// A straight line at a constant ground velocity.
    Straight {
        /// Position relative to the own aircraft at t = 0, m.
        start: [f64; 2],
        /// Ground velocity, m/s.
        velocity: [f64; 2],
        /// Altitude profile; `None`: it does not report altitude.
        vertical: Option<RateChange>,
    },
    /// A recorded aircraft ([`crate::recorded_encounters`]).
    Recorded(RecordedIntruder),
}

const OWN_SPEED: f64 = 250.0 * KT;

fn level(altitude_ft: f64) -> Option<RateChange> {
    Some(RateChange {
        start_ft: altitude_ft,
        rate0: 0.0,
        rate1: 0.0,
        t_change: 0.0,
        accel: f64::INFINITY,
    })
}

/// Head-on from 14 NM at 500 kt closure (250 kt each), `offset` NM abeam.
fn head_on(
    name: &'static str,
    description: &'static str,
    offset_nm: f64,
    vertical: Option<RateChange>,
) -> Encounter {
    Encounter {
        name,
        description,
        own_altitude_ft: 8000.0,
        own_velocity: [0.0, OWN_SPEED],
        intruder: IntruderPath::Straight {
            start: [offset_nm * NM, 14.0 * NM],
            velocity: [0.0, -OWN_SPEED],
            vertical,
        },
        quantum: AltitudeQuantum::ModeC,
        scans: 160,
    }
}

/// The suite: own level at 8000 ft (SL 5) flying north at 250 kt unless
/// stated; Mode C altitude.
pub fn suite() -> Vec<Encounter> {
    let crossing_cpa_s = 120.0;
    vec![
        head_on(
            "head-on",
            "head-on from 14 NM, 500 kt closure, intruder level 200 ft above",
            0.0,
            level(8200.0),
        ),
        Encounter {
            name: "crossing",
            description: "90° crossing from the east at 250 kt, collision course (CPA at 120 s), intruder level 300 ft below",
            own_altitude_ft: 8000.0,
            own_velocity: [0.0, OWN_SPEED],
            intruder: IntruderPath::Straight {
                start: [OWN_SPEED * crossing_cpa_s, OWN_SPEED * crossing_cpa_s],
                velocity: [-OWN_SPEED, 0.0],
                vertical: level(7700.0),
            },
            quantum: AltitudeQuantum::ModeC,
            scans: 180,
        },
        Encounter {
            name: "overtaking",
            description: "overtaken from 3 NM behind by an intruder 100 kt faster, 0.1 NM abeam, level 300 ft above",
            own_altitude_ft: 8000.0,
            own_velocity: [0.0, OWN_SPEED],
            intruder: IntruderPath::Straight {
                start: [0.1 * NM, -3.0 * NM],
                velocity: [0.0, OWN_SPEED + 100.0 * KT],
                vertical: level(8300.0),
            },
            quantum: AltitudeQuantum::ModeC,
            scans: 200,
        },
        head_on(
            "offset-inside-hmd",
            "head-on, 0.4 NM abeam (741 m, inside SL 5's HMD of 3342 ft = 1019 m), level 200 ft above",
            0.4,
            level(8200.0),
        ),
        head_on(
            "offset-beyond-hmd",
            "head-on, 0.8 NM abeam (1482 m, beyond the HMD), level 200 ft above",
            0.8,
            level(8200.0),
        ),
        Encounter {
            intruder: IntruderPath::Straight {
                start: [1.2 * NM, 14.0 * NM],
                velocity: [0.0, -240.0 * KT],
                vertical: level(8000.0),
            },
            own_velocity: [0.0, 240.0 * KT],
            own_altitude_ft: 8000.0,
            ..head_on(
                "abeam-1.2nm",
                "beyond the HMD threshold: passing 1.2 NM abeam at 480 kt closure, co-altitude",
                1.2,
                level(8000.0),
            )
        },
        head_on(
            "level-1000ft",
            "head-on, level 1000 ft above",
            0.0,
            level(9000.0),
        ),
        head_on(
            "descending",
            "head-on 0.2 NM abeam, descending 1500 ft/min from 10 500 ft (co-altitude at CPA)",
            0.2,
            Some(RateChange {
                start_ft: 10500.0,
                rate0: -25.0,
                rate1: -25.0,
                t_change: 0.0,
                accel: f64::INFINITY,
            }),
        ),
        Encounter {
            name: "diverging",
            description: "1 NM ahead, same track, opening at 250 kt, co-altitude",
            own_altitude_ft: 8000.0,
            own_velocity: [0.0, OWN_SPEED],
            intruder: IntruderPath::Straight {
                start: [0.0, 1.0 * NM],
                velocity: [0.0, 2.0 * OWN_SPEED],
                vertical: level(8000.0),
            },
            quantum: AltitudeQuantum::ModeC,
            scans: 80,
        },
        head_on(
            "level-off",
            "head-on 0.2 NM abeam, climbing 2000 ft/min from 4800 ft, levelling 1000 ft below at t = 66 s",
            0.2,
            Some(RateChange {
                start_ft: 4800.0,
                rate0: 2000.0 / 60.0,
                rate1: 0.0,
                t_change: 66.0,
                accel: f64::INFINITY,
            }),
        ),
        head_on(
            "non-reporting",
            "head-on 0.2 NM abeam, no altitude reports",
            0.2,
            None,
        ),
        Encounter {
            own_altitude_ft: 20000.0,
            ..head_on(
                "non-reporting-high",
                "head-on 0.2 NM abeam, no altitude reports, own at 20 000 ft (above 15 500 ft)",
                0.2,
                None,
            )
        },
    ]
}

impl Encounter {
    /// The true relative state at t s.
    pub fn relative(&self, t: f64) -> Relative {
        match &self.intruder {
            IntruderPath::Straight {
                start,
                velocity,
                vertical,
            } => {
                let v = [
                    velocity[0] - self.own_velocity[0],
                    velocity[1] - self.own_velocity[1],
                ];
                Relative {
                    s: [start[0] + v[0] * t, start[1] + v[1] * t],
                    v,
                    altitude: vertical.map(|p| (p.altitude_ft(t), p.rate_ft_per_s(t))),
                }
            }
            IntruderPath::Recorded(recorded) => recorded.relative(t, self.own_velocity),
        }
    }

    /// The recorded intruder, if the intruder is one.
    pub fn recorded(&self) -> Option<&RecordedIntruder> {
        match &self.intruder {
            IntruderPath::Recorded(r) => Some(r),
            IntruderPath::Straight { .. } => None,
        }
    }

    pub fn own(&self) -> Own {
        Own {
            altitude_ft: self.own_altitude_ft,
            rate_ft_per_s: 0.0,
        }
    }
}

/// One scan's measurement of the intruder.
#[derive(Debug, Clone, Copy)]
pub struct Measurement {
    pub range_m: f64,
    /// Clockwise from north (+y), rad.
    pub bearing_rad: f64,
    /// Reported altitude, ft.
    pub altitude_ft: Option<f64>,
}

/// Sensor noise of a run.
#[derive(Debug, Clone, Copy)]
pub enum Noise {
    Exact,
    Seeded(u64),
}

/// The sensor of a run: its noise, which the bearing tracker is also
/// configured with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensor {
    /// Range σ, m.
    pub range_sigma_m: f64,
    /// Bearing σ, rad.
    pub bearing_sigma_rad: f64,
}

/// The suite's sensor: [`RANGE_SIGMA_M`], [`BEARING_SIGMA_RAD`].
pub const SENSOR: Sensor = Sensor {
    range_sigma_m: RANGE_SIGMA_M,
    bearing_sigma_rad: BEARING_SIGMA_RAD,
};

/// The measurements of an encounter, one per scan, by [`SENSOR`].
pub fn measurements(e: &Encounter, noise: Noise) -> Vec<Measurement> {
    measurements_by(e, noise, &SENSOR)
}

/// The measurements of an encounter, one per scan, with `sensor`'s noise.
pub fn measurements_by(e: &Encounter, noise: Noise, sensor: &Sensor) -> Vec<Measurement> {
    let mut rng: Option<SimRng> = match noise {
        Noise::Exact => None,
        Noise::Seeded(seed) => Some(rng_from_seed(seed)),
    };
    (0..e.scans)
        .map(|k| {
            let x = e.relative(k as f64);
            let r = x.s[0].hypot(x.s[1]);
            let b = x.s[0].atan2(x.s[1]);
            let (dr, db) = match rng.as_mut() {
                None => (0.0, 0.0),
                Some(g) => (
                    sensor.range_sigma_m * standard_normal(g),
                    sensor.bearing_sigma_rad * standard_normal(g),
                ),
            };
            Measurement {
                range_m: (r + dr).max(1.0),
                bearing_rad: b + db,
                altitude_ft: x.altitude.map(|(z, _)| report(z, e.quantum)),
            }
        })
        .collect()
}

/// One scan's outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanOutcome {
    pub alert: Alert,
    /// The RA sense in force.
    pub sense: Option<Sense>,
    pub clear_of_conflict: bool,
}

fn alert_of(a: Advisory) -> Alert {
    match a {
        Advisory::None => Alert::None,
        Advisory::ProximateTraffic => Alert::Proximate,
        Advisory::Traffic => Alert::Ta,
        Advisory::Resolution => Alert::Ra,
    }
}

/// Runs the library in `S` on the measurements, its bearing tracker
/// configured for [`SENSOR`]; `Err` for an input the library refused
/// (counted by the caller as a failure).
pub fn run_library<S: Scalar>(
    e: &Encounter,
    meas: &[Measurement],
) -> Result<Vec<ScanOutcome>, String> {
    run_library_for::<S>(e, meas, &SENSOR, None)
}

/// [`run_library`] with the bearing tracker configured for `sensor`. The
/// bearing track's estimate must stay within the numeric envelope
/// (positions, velocity components: [`abtrack::envelope`]), as `replay`
/// requires of every row it writes: a run whose track leaves it is refused.
/// `miss_distance_confidence` overrides the HMD filter's confidence factor
/// for the bearing-based miss distance (`Cycle::with_miss_distance_confidence`).
pub fn run_library_for<S: Scalar>(
    e: &Encounter,
    meas: &[Measurement],
    sensor: &Sensor,
    miss_distance_confidence: Option<f64>,
) -> Result<Vec<ScanOutcome>, String> {
    run_library_traced::<S>(e, meas, sensor, miss_distance_confidence, None)
}

/// What the library's surveillance held at one scan of a run, beside the
/// truth: the range tracker against the true range acceleration, the
/// bearing track's miss distance, and the miss distance the HMD filter
/// compared.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanTrace {
    /// True range, m.
    pub true_range_m: f64,
    /// True r̈ = (v² − ṙ²)/r of the straight relative path, m/s².
    pub true_range_acceleration_m_per_s2: f64,
    /// The range tracker's ṙ, m/s, and r̈, m/s² (`None` before it has a
    /// range rate).
    pub range_rate_m_per_s: Option<f64>,
    pub range_acceleration_m_per_s2: Option<f64>,
    /// The bearing track's miss distance and its σ, m.
    pub bearing_miss_distance_m: Option<f64>,
    pub bearing_miss_distance_sigma_m: Option<f64>,
    /// The miss distance the HMD filter compared (`None`: filter off), m.
    pub filter_miss_distance_m: Option<f64>,
    /// The filter removed the RA range hit.
    pub miss_distance_filtered: bool,
}

/// [`run_library_for`], pushing each scan's [`ScanTrace`] onto `trace`
/// when it is given.
pub fn run_library_traced<S: Scalar>(
    e: &Encounter,
    meas: &[Measurement],
    sensor: &Sensor,
    miss_distance_confidence: Option<f64>,
    mut trace: Option<&mut Vec<ScanTrace>>,
) -> Result<Vec<ScanOutcome>, String> {
    let c = |v: f64| S::from_f64_lossy(v);
    let one = S::ONE;
    let mut cas = CollisionAvoidance::<S>::new();
    let altitude = AltitudeTrackerConfig::<S>::default_for(e.quantum).map_err(|e| e.to_string())?;
    let mut track = IntruderTrack::<S>::new();
    let noise = RangeAzimuthNoise::<S>::new_f64(
        sensor.range_sigma_m * sensor.range_sigma_m,
        sensor.bearing_sigma_rad * sensor.bearing_sigma_rad,
        BEARING_TRACKER_PROCESS_NOISE,
    )
    .and_then(|n| n.with_speed_bound_f64(MAX_CLOSURE_SPEED_M_PER_S))
    .map_err(|e| e.to_string())?;
    let mut bearing = RangeAzimuthFilter::<S>::new(noise);
    let own = OwnAircraft::over_sea_level(c(e.own_altitude_ft), S::ZERO);
    let mut out = Vec::with_capacity(meas.len());
    for (k, m) in meas.iter().enumerate() {
        let mut cycle = cas
            .begin_cycle(&own, false)
            .map_err(|e| format!("scan {k}: {e}"))?;
        if let Some(sigmas) = miss_distance_confidence {
            cycle = cycle.with_miss_distance_confidence(c(sigmas));
        }
        track
            .scan(
                &altitude,
                Some(Reply {
                    range_m: c(m.range_m),
                    altitude_ft: m.altitude_ft.map(c),
                }),
                one,
            )
            .map_err(|e| format!("scan {k}: range/altitude refused: {e}"))?;
        bearing
            .update(c(m.range_m), c(m.bearing_rad), one)
            .map_err(|e| format!("scan {k}: bearing refused: {e}"))?;
        let inside = bearing
            .position()
            .iter()
            .all(|p| POSITION_M.contains(p.to_f64()))
            && bearing
                .velocity()
                .iter()
                .all(|v| VELOCITY_M_PER_S.contains(v.to_f64()));
        if !inside {
            return Err(format!(
                "scan {k}: the bearing track left the envelope (velocity {:?} m/s)",
                bearing.velocity().map(|v| v.to_f64())
            ));
        }
        let status = track
            .assess(&cycle, Some(&bearing), one)
            .map_err(|e| format!("scan {k}: {e}"))?;
        if let Some(trace) = trace.as_deref_mut() {
            // What `assess` saw: it moves only the threat state.
            let observation = track.observation(Some(&bearing));
            let truth = e.relative(k as f64);
            let (r, rate) = reference_tcas::range_and_rate(truth.s, truth.v);
            let speed_squared = truth.v[0] * truth.v[0] + truth.v[1] * truth.v[1];
            trace.push(ScanTrace {
                true_range_m: r,
                true_range_acceleration_m_per_s2: (speed_squared - rate * rate) / r,
                range_rate_m_per_s: observation.map(|o| o.range.range_rate_m_per_s.to_f64()),
                range_acceleration_m_per_s2: observation
                    .map(|o| o.range.range_acceleration_m_per_s2.to_f64()),
                bearing_miss_distance_m: observation
                    .and_then(|o| o.bearing_miss_distance_m)
                    .map(|v| v.to_f64()),
                bearing_miss_distance_sigma_m: observation
                    .and_then(|o| o.bearing_miss_distance_sigma_m)
                    .map(|v| v.to_f64()),
                filter_miss_distance_m: status.and_then(|s| s.miss_distance_m).map(|v| v.to_f64()),
                miss_distance_filtered: status.is_some_and(|s| s.miss_distance_filtered),
            });
        }
        let threats: Vec<ThreatGeometry<S>> = status.and_then(|s| s.geometry).into_iter().collect();
        let ra = cas
            .resolve(&cycle, &threats, one)
            .map_err(|e| format!("scan {k}: {e}"))?;
        out.push(ScanOutcome {
            alert: status.map_or(Alert::None, |s| alert_of(s.advisory)),
            sense: ra.advisory.map(|a| match a.sense {
                RaSense::Up => Sense::Up,
                RaSense::Down => Sense::Down,
            }),
            clear_of_conflict: ra.clear_of_conflict,
        });
    }
    Ok(out)
}

/// The reference's timeline on the true states.
pub fn run_reference(e: &Encounter) -> Vec<ScanOutcome> {
    let mut r = Reference::new(1);
    (0..e.scans)
        .map(|k| {
            let step = r.step(&e.own(), &[e.relative(k as f64)], 1.0);
            ScanOutcome {
                alert: step.alerts[0],
                sense: step.ra.map(|ra| ra.sense),
                clear_of_conflict: step.clear_of_conflict,
            }
        })
        .collect()
}

/// The events of a timeline.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Timeline {
    pub ta_onset_s: Option<f64>,
    pub ra_onset_s: Option<f64>,
    /// Sense at the RA onset.
    pub sense: Option<Sense>,
    pub clear_of_conflict_s: Option<f64>,
    /// Scans with a TA (or RA) and with an RA.
    pub ta_scans: usize,
    pub ra_scans: usize,
}

pub fn timeline(scans: &[ScanOutcome]) -> Timeline {
    let first = |f: &dyn Fn(&ScanOutcome) -> bool| scans.iter().position(f).map(|k| k as f64);
    let ra_onset = scans.iter().position(|s| s.alert == Alert::Ra);
    Timeline {
        ta_onset_s: first(&|s| s.alert >= Alert::Ta),
        ra_onset_s: ra_onset.map(|k| k as f64),
        sense: ra_onset.and_then(|k| scans[k].sense),
        clear_of_conflict_s: first(&|s| s.clear_of_conflict),
        ta_scans: scans.iter().filter(|s| s.alert >= Alert::Ta).count(),
        ra_scans: scans.iter().filter(|s| s.alert == Alert::Ra).count(),
    }
}

/// Whether the run starts an alert at `level` (a scan at `level` after one
/// below it) more than [`FALSE_ALERT_TOLERANCE_S`] from every scan at which
/// the reference has it. A late end of a true alert is not false: it is in
/// the clear-of-conflict delay.
pub fn has_false_alert(run: &[ScanOutcome], reference: &[ScanOutcome], level: Alert) -> bool {
    let tol = FALSE_ALERT_TOLERANCE_S as usize;
    run.iter().enumerate().any(|(k, s)| {
        let onset = s.alert >= level && (k == 0 || run[k - 1].alert < level);
        onset && {
            let lo = k.saturating_sub(tol);
            let hi = (k + tol).min(reference.len() - 1);
            !reference[lo..=hi].iter().any(|r| r.alert >= level)
        }
    })
}

/// Whether the run's RA ends (clear of conflict) at a scan from which the
/// reference keeps its RA for more than [`FALSE_ALERT_TOLERANCE_S`].
pub fn has_interrupted_ra(run: &[ScanOutcome], reference: &[ScanOutcome]) -> bool {
    let tol = FALSE_ALERT_TOLERANCE_S as usize;
    run.iter().enumerate().any(|(k, s)| {
        s.clear_of_conflict
            && reference
                .get(k..=k + tol)
                .is_some_and(|w| w.iter().all(|r| r.alert == Alert::Ra))
    })
}

/// Counts over the noisy runs of one encounter in one type.
#[derive(Debug, Clone, Default)]
pub struct NoiseCounts {
    pub runs: usize,
    pub missed_ta: usize,
    pub missed_ra: usize,
    pub false_ta: usize,
    pub false_ra: usize,
    pub wrong_sense: usize,
    /// Runs whose RA ended while the reference's RA went on for more than
    /// [`FALSE_ALERT_TOLERANCE_S`] (an RA dropped early, perhaps restarted).
    pub interrupted_ra: usize,
    pub refused: usize,
    /// Onset delays (run minus reference, s) of the runs that have both.
    pub ta_delays: Vec<f64>,
    pub ra_delays: Vec<f64>,
    pub coc_delays: Vec<f64>,
}

/// Base seed of the noisy runs.
pub const BASE_SEED: u64 = 0x0010_7CA5_E2C0_0010;

/// The seed of noisy run `run` of encounter `encounter_index`.
pub fn derive_run_seed(encounter_index: u64, run: u64) -> u64 {
    derive_seed(derive_seed(BASE_SEED, encounter_index), run)
}

/// `runs` noisy runs of `e` in `S` against the reference.
pub fn noisy_runs<S: Scalar>(e: &Encounter, encounter_index: u64, runs: usize) -> NoiseCounts {
    let reference = run_reference(e);
    let expected = timeline(&reference);
    let mut n = NoiseCounts {
        runs,
        ..NoiseCounts::default()
    };
    for run in 0..runs {
        let seed = derive_run_seed(encounter_index, run as u64);
        let meas = measurements(e, Noise::Seeded(seed));
        let Ok(out) = run_library::<S>(e, &meas) else {
            n.refused += 1;
            continue;
        };
        let got = timeline(&out);
        n.missed_ta += usize::from(expected.ta_onset_s.is_some() && got.ta_onset_s.is_none());
        n.missed_ra += usize::from(expected.ra_onset_s.is_some() && got.ra_onset_s.is_none());
        n.false_ta += usize::from(has_false_alert(&out, &reference, Alert::Ta));
        n.false_ra += usize::from(has_false_alert(&out, &reference, Alert::Ra));
        n.interrupted_ra += usize::from(has_interrupted_ra(&out, &reference));
        n.wrong_sense += usize::from(
            expected.sense.is_some() && got.sense.is_some() && expected.sense != got.sense,
        );
        if let (Some(a), Some(b)) = (got.ta_onset_s, expected.ta_onset_s) {
            n.ta_delays.push(a - b);
        }
        if let (Some(a), Some(b)) = (got.ra_onset_s, expected.ra_onset_s) {
            n.ra_delays.push(a - b);
        }
        if let (Some(a), Some(b)) = (got.clear_of_conflict_s, expected.clear_of_conflict_s) {
            n.coc_delays.push(a - b);
        }
    }
    n
}

/// One reply of the demo scenario.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemoReply {
    pub time_s: f64,
    pub range_m: f64,
    /// Clockwise from north, rad.
    pub bearing_rad: f64,
    /// Reported altitude, ft; `None` for Mode A / non-reporting.
    pub altitude_ft: Option<f64>,
    /// 100 ft or 25 ft steps.
    pub quantum: AltitudeQuantum,
    /// The 24-bit Mode S address; `None` for Mode C replies and false
    /// replies.
    pub mode_s_address: Option<u32>,
    /// Which intruder, `None` for a false reply.
    pub intruder: Option<usize>,
}

/// The demo's intruders, own level at 8000 ft flying
/// north at 250 kt, 1 Hz, from 14 NM:
/// 0. head-on 0.2 NM abeam, 300 ft above, Mode S 25 ft: proximate → TA →
///    RA (down) → clear of conflict;
/// 1. level 1000 ft above, crossing: no RA;
/// 2. not reporting altitude, converging: TA at most;
/// 3. passing 1 NM abeam co-altitude (beyond the HMD threshold): no RA;
///
/// Plus false replies (uniform in range 1–14 NM and bearing, 0.7 a second,
/// without altitude or address, half a second after the intruders' replies:
/// the next scan's).
pub fn demo_intruders() -> Vec<Encounter> {
    vec![
        Encounter {
            quantum: AltitudeQuantum::ModeS25,
            ..head_on(
                "demo-threat",
                "head-on 0.2 NM abeam, 300 ft above",
                0.2,
                level(8300.0),
            )
        },
        Encounter {
            own_velocity: [0.0, OWN_SPEED],
            intruder: IntruderPath::Straight {
                start: [9.0 * NM, 9.0 * NM],
                velocity: [-OWN_SPEED, 0.0],
                vertical: level(9000.0),
            },
            ..head_on(
                "demo-level-1000",
                "crossing, level 1000 ft above",
                0.0,
                level(9000.0),
            )
        },
        Encounter {
            intruder: IntruderPath::Straight {
                start: [-6.0 * NM, 11.0 * NM],
                velocity: [200.0 * KT, -150.0 * KT],
                vertical: None,
            },
            ..head_on(
                "demo-non-reporting",
                "converging from the north-west, no altitude",
                0.0,
                None,
            )
        },
        head_on(
            "demo-abeam",
            "head-on 1 NM abeam, co-altitude",
            1.0,
            level(8000.0),
        ),
    ]
}

/// The demo scenario's replies, in time order, with noise from `seed`
/// (range σ 15 m, bearing σ 5°, altitude quantised).
pub fn demo_scenario(seed: u64, scans: usize) -> Vec<DemoReply> {
    let mut rng = rng_from_seed(seed);
    let intruders = demo_intruders();
    let addresses = [Some(0x004C_A123), None, None, Some(0x003C_6601)];
    let mut replies = Vec::new();
    for k in 0..scans {
        let t = k as f64;
        for (i, e) in intruders.iter().enumerate() {
            let x = e.relative(t);
            let r = x.s[0].hypot(x.s[1]);
            replies.push(DemoReply {
                // One interrogation cycle: every reply at the scan's time.
                time_s: t,
                range_m: (r + RANGE_SIGMA_M * standard_normal(&mut rng)).max(1.0),
                bearing_rad: x.s[0].atan2(x.s[1]) + BEARING_SIGMA_RAD * standard_normal(&mut rng),
                altitude_ft: x.altitude.map(|(z, _)| report(z, e.quantum)),
                quantum: e.quantum,
                mode_s_address: addresses.get(i).copied().flatten(),
                intruder: Some(i),
            });
        }
        // (None after the last cycle: the input ends with its scan.)
        if uniform(&mut rng, 0.0, 1.0) < 0.7 && k + 1 < scans {
            replies.push(DemoReply {
                time_s: t + 0.5,
                range_m: uniform(&mut rng, 1.0, 14.0) * NM,
                bearing_rad: uniform(&mut rng, -PI, PI),
                altitude_ft: None,
                quantum: AltitudeQuantum::ModeC,
                mode_s_address: None,
                intruder: None,
            });
        }
    }
    replies
}

/// The reference's timeline of the demo's intruders (true states).
pub fn demo_reference(scans: usize) -> Vec<Vec<Alert>> {
    let intruders = demo_intruders();
    let mut r = Reference::new(intruders.len());
    let own = intruders[0].own();
    (0..scans)
        .map(|k| {
            let states: Vec<Relative> = intruders.iter().map(|e| e.relative(k as f64)).collect();
            r.step(&own, &states, 1.0).alerts
        })
        .collect()
}

/// The level of the reference's table for an own altitude (re-exported
/// for the experiment's notes).
pub fn reference_level(altitude_ft: f64) -> reference_tcas::Level {
    reference_tcas::level_for(altitude_ft)
}
