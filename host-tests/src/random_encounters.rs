//! The randomized TCAS encounter suite: seeded straight-line encounters
//! spread over sensitivity levels 3–7, horizontal miss 0–1.5 NM, vertical
//! miss ±1200 ft, closure 100–1000 kt and intruder vertical rates
//! ±3000 ft/min, the own aircraft level over sea-level terrain. Each is run
//! through the library ([`crate::encounters::run_library_for`]: range
//! tracker, altitude tracker, bearing tracker, threat logic, resolution) on
//! exact or noisy measurements, in f64, f32 or the firmware's `Fixed32` (its
//! TCAS logic in its wide format),
//! and compared with the independent f64 reference of the rules
//! ([`crate::reference_tcas`]) on the true states.
//!
//! # Definitions (per run, against the reference's timeline)
//!
//! * refused: the library refused an input or the bearing track left the
//!   numeric envelope (as `replay` refuses such a row);
//! * false RA: the run has an RA, the reference none; missed RA: the
//!   reference has one, the run none; the same for TAs (an RA counts as a
//!   TA); agreement: the run has a TA (RA) exactly when the reference has;
//! * onset delay: the run's first RA scan minus the reference's, s;
//! * wrong sense: both have an RA and the senses at onset differ (the
//!   tables also give the largest |VMD| of those runs' encounters);
//! * RA in pieces: the run's RA starts more than once;
//! * RA reversed: the run's RA changes sense while in force (a sense
//!   reversal; the reference has none: the own aircraft does not follow
//!   the RA, and the reference does not model reversals).

use abtrack::filter::altitude::AltitudeQuantum;
use abtrack::Scalar;

use crate::altitude_figures::RateChange;
use crate::encounters::{
    measurements_by, run_library_for, run_library_traced, run_reference, Encounter, IntruderPath,
    Measurement, Noise, ScanOutcome, ScanTrace, Sensor, KT, NM,
};
use crate::noise::{derive_seed, rng_from_seed, uniform};
use crate::reference_tcas::{level_for, Alert, Sense};

/// Base seed of the encounters.
pub const BASE_SEED: u64 = 0x0019_7CA5_0A4D_0019;
/// Base seed of the measurement noise.
pub const NOISE_SEED: u64 = 0x0019_7CA5_0015_E019;
/// Encounters per sensitivity level.
pub const PER_LEVEL: usize = 60;
/// The levels and the own altitudes drawn for each, ft (inside the
/// booklet's band, away from its edges and from the low-altitude inhibits
/// of descend RAs, below 1100 ft, and increase-descend, below 1450 ft).
pub const LEVELS: [(u8, f64, f64); 5] = [
    (3, 1700.0, 2250.0),
    (4, 2600.0, 4800.0),
    (5, 5200.0, 9800.0),
    (6, 10500.0, 19500.0),
    (7, 20500.0, 40000.0),
];
/// Horizontal miss distance, NM.
pub const HMD_NM: (f64, f64) = (0.0, 1.5);
/// Vertical miss distance (intruder minus own at closest approach), ft.
pub const VMD_FT: (f64, f64) = (-1200.0, 1200.0);
/// Closure speed, kt.
pub const CLOSURE_KT: (f64, f64) = (100.0, 1000.0);
/// Intruder vertical rate, ft/min.
pub const INTRUDER_RATE_FT_PER_MIN: (f64, f64) = (-3000.0, 3000.0);
/// The intruder stays at least this high over the run (the logic treats
/// an intruder below 360 ft over the terrain as on the ground), ft.
pub const LOWEST_INTRUDER_FT: f64 = 1000.0;
/// The run ends this long after closest approach, s.
pub const AFTER_CPA_S: f64 = 40.0;

/// One drawn encounter and the figures it was drawn from.
#[derive(Debug, Clone, Copy)]
pub struct RandomEncounter {
    pub index: usize,
    pub level: u8,
    pub hmd_m: f64,
    pub vmd_ft: f64,
    pub closure_kt: f64,
    pub intruder_rate_ft_per_min: f64,
    pub encounter: Encounter,
}

/// Encounter `index` (level `LEVELS[index / PER_LEVEL]`), from its seed.
/// The approach direction is uniform; the intruder starts where the range
/// tau is the level's TA tau + 30 s (and at least 6 NM out), so every
/// track is firm before any alert can arise.
pub fn encounter(index: usize) -> RandomEncounter {
    let (level, lo, hi) = LEVELS[(index / PER_LEVEL).min(LEVELS.len() - 1)];
    let mut rng = rng_from_seed(derive_seed(BASE_SEED, index as u64));
    let own_ft = uniform(&mut rng, lo, hi);
    let hmd_m = uniform(&mut rng, HMD_NM.0, HMD_NM.1) * NM;
    let vmd_ft = uniform(&mut rng, VMD_FT.0, VMD_FT.1);
    let closure_kt = uniform(&mut rng, CLOSURE_KT.0, CLOSURE_KT.1);
    let heading = uniform(&mut rng, 0.0, std::f64::consts::TAU);
    let side = if uniform(&mut rng, 0.0, 1.0) < 0.5 {
        -1.0
    } else {
        1.0
    };
    let speed = closure_kt * KT;
    let ta_tau = level_for(own_ft).ta_tau;
    let start_range = (speed * (ta_tau + 30.0)).max(6.0 * NM).max(hmd_m);
    let t_cpa = (start_range * start_range - hmd_m * hmd_m).sqrt() / speed;
    let scans = (t_cpa + AFTER_CPA_S).ceil() as usize;
    // The intruder's rate: drawn again (from the same stream) while its
    // path would take it below LOWEST_INTRUDER_FT; the zero rate always fits.
    let mut rate = 0.0;
    for _ in 0..8 {
        let r = uniform(
            &mut rng,
            INTRUDER_RATE_FT_PER_MIN.0,
            INTRUDER_RATE_FT_PER_MIN.1,
        );
        let at = |t: f64| own_ft + vmd_ft + r / 60.0 * (t - t_cpa);
        if at(0.0).min(at(scans as f64)) >= LOWEST_INTRUDER_FT {
            rate = r;
            break;
        }
    }
    let (u, n) = (
        [heading.sin(), heading.cos()],
        [heading.cos() * side, -heading.sin() * side],
    );
    let v = [u[0] * speed, u[1] * speed];
    // s(t) = hmd·n + v·(t − t_cpa).
    let start = [hmd_m * n[0] - v[0] * t_cpa, hmd_m * n[1] - v[1] * t_cpa];
    RandomEncounter {
        index,
        level,
        hmd_m,
        vmd_ft,
        closure_kt,
        intruder_rate_ft_per_min: rate,
        encounter: Encounter {
            name: "random",
            description: "randomized straight-line encounter",
            own_altitude_ft: own_ft,
            own_velocity: [0.0, 0.0],
            intruder: IntruderPath::Straight {
                start,
                velocity: v,
                vertical: Some(RateChange {
                    start_ft: own_ft + vmd_ft - rate / 60.0 * t_cpa,
                    rate0: rate / 60.0,
                    rate1: rate / 60.0,
                    t_change: 0.0,
                    accel: f64::INFINITY,
                }),
            },
            quantum: AltitudeQuantum::ModeS25,
            scans,
        },
    }
}

/// The whole suite: [`PER_LEVEL`] encounters at each of the [`LEVELS`].
pub fn suite() -> Vec<RandomEncounter> {
    (0..PER_LEVEL * LEVELS.len()).map(encounter).collect()
}

/// A measurement configuration of the suite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Condition {
    pub name: &'static str,
    /// `None`: exact ranges and bearings (the tracker is configured with
    /// [`Self::sensor`]'s figures all the same).
    pub noisy: bool,
    pub sensor: Sensor,
    pub quantum: AltitudeQuantum,
}

const DEG: f64 = std::f64::consts::PI / 180.0;

/// Range σ of every condition, m.
pub const RANGE_SIGMA_M: f64 = 15.0;

/// The conditions: exact; range σ 15 m with bearing σ 5° or 10° and 25 ft
/// altitude; bearing σ 5° with 100 ft altitude.
pub const CONDITIONS: [Condition; 4] = [
    Condition {
        name: "exact, 25 ft",
        noisy: false,
        sensor: Sensor {
            range_sigma_m: RANGE_SIGMA_M,
            bearing_sigma_rad: 5.0 * DEG,
        },
        quantum: AltitudeQuantum::ModeS25,
    },
    Condition {
        name: "σB 5°, 25 ft",
        noisy: true,
        sensor: Sensor {
            range_sigma_m: RANGE_SIGMA_M,
            bearing_sigma_rad: 5.0 * DEG,
        },
        quantum: AltitudeQuantum::ModeS25,
    },
    Condition {
        name: "σB 10°, 25 ft",
        noisy: true,
        sensor: Sensor {
            range_sigma_m: RANGE_SIGMA_M,
            bearing_sigma_rad: 10.0 * DEG,
        },
        quantum: AltitudeQuantum::ModeS25,
    },
    Condition {
        name: "σB 5°, 100 ft",
        noisy: true,
        sensor: Sensor {
            range_sigma_m: RANGE_SIGMA_M,
            bearing_sigma_rad: 5.0 * DEG,
        },
        quantum: AltitudeQuantum::ModeC,
    },
];

/// What one run gave against the reference.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RunResult {
    pub refused: bool,
    pub reference_ta: bool,
    pub reference_ra: bool,
    pub ta: bool,
    pub ra: bool,
    /// Run minus reference RA onset, s (both have an RA).
    pub onset_delay_s: Option<f64>,
    pub wrong_sense: bool,
    /// How many times the run's RA starts.
    pub ra_pieces: usize,
    /// The run's RA changes sense while in force.
    pub reversed: bool,
}

/// The scan of a timeline's first RA and its sense.
pub fn ra_onset(scans: &[ScanOutcome]) -> Option<(usize, Option<Sense>)> {
    scans
        .iter()
        .position(|s| s.alert == Alert::Ra)
        .map(|k| (k, scans[k].sense))
}

/// Compares a run with the reference's timeline.
pub fn compare(run: &[ScanOutcome], reference: &[ScanOutcome]) -> RunResult {
    let any = |s: &[ScanOutcome], a: Alert| s.iter().any(|o| o.alert >= a);
    let (got, expected) = (ra_onset(run), ra_onset(reference));
    let ra_pieces = run
        .iter()
        .enumerate()
        .filter(|(k, s)| s.alert == Alert::Ra && (*k == 0 || run[k - 1].alert != Alert::Ra))
        .count();
    RunResult {
        refused: false,
        reference_ta: any(reference, Alert::Ta),
        reference_ra: expected.is_some(),
        ta: any(run, Alert::Ta),
        ra: got.is_some(),
        onset_delay_s: match (got, expected) {
            (Some((a, _)), Some((b, _))) => Some(a as f64 - b as f64),
            _ => None,
        },
        wrong_sense: matches!((got, expected), (Some((_, a)), Some((_, b))) if a != b),
        ra_pieces,
        reversed: run
            .windows(2)
            .any(|w| matches!((w[0].sense, w[1].sense), (Some(a), Some(b)) if a != b)),
    }
}

/// Seed of noisy run `run` of encounter `index`.
pub fn run_seed(index: usize, run: usize) -> u64 {
    derive_seed(derive_seed(NOISE_SEED, index as u64), run as u64)
}

/// Run `run` of `e` under `condition` in `S` (the exact condition ignores
/// `run`), against the reference's timeline `reference`; the HMD filter's
/// confidence factor for the bearing-based miss distance is the library's
/// unless `miss_distance_confidence` is given.
pub fn run_one<S: Scalar>(
    e: &RandomEncounter,
    condition: &Condition,
    run: usize,
    reference: &[ScanOutcome],
    miss_distance_confidence: Option<f64>,
) -> RunResult {
    let (encounter, meas) = run_inputs(e, condition, run);
    match run_library_for::<S>(
        &encounter,
        &meas,
        &condition.sensor,
        miss_distance_confidence,
    ) {
        Ok(out) => compare(&out, reference),
        Err(_) => RunResult {
            refused: true,
            reference_ta: reference.iter().any(|o| o.alert >= Alert::Ta),
            reference_ra: reference.iter().any(|o| o.alert == Alert::Ra),
            ..RunResult::default()
        },
    }
}

/// The encounter as run under `condition` (its altitude quantum) and the
/// measurements of run `run`.
fn run_inputs(
    e: &RandomEncounter,
    condition: &Condition,
    run: usize,
) -> (Encounter, Vec<Measurement>) {
    let encounter = Encounter {
        quantum: condition.quantum,
        ..e.encounter
    };
    let noise = if condition.noisy {
        Noise::Seeded(run_seed(e.index, run))
    } else {
        Noise::Exact
    };
    let meas = measurements_by(&encounter, noise, &condition.sensor);
    (encounter, meas)
}

/// Run `run` of `e` under `condition` in `S` with the library's HMD filter,
/// scan by scan: the outcomes and the [`ScanTrace`]s.
pub fn trace_one<S: Scalar>(
    e: &RandomEncounter,
    condition: &Condition,
    run: usize,
) -> Result<(Vec<ScanOutcome>, Vec<ScanTrace>), String> {
    let (encounter, meas) = run_inputs(e, condition, run);
    let mut trace = Vec::with_capacity(meas.len());
    run_library_traced::<S>(&encounter, &meas, &condition.sensor, None, Some(&mut trace))
        .map(|outcomes| (outcomes, trace))
}

/// The reference's timeline of an encounter.
pub fn reference(e: &RandomEncounter) -> Vec<ScanOutcome> {
    run_reference(&e.encounter)
}

/// The library's own timeline of an encounter in f64 on exact ranges and
/// bearings with 25 ft altitudes (the first of [`CONDITIONS`]): the
/// baseline against which the receiver's noise alone is measured (`None`
/// should the library refuse the run).
pub fn exact_library_timeline(e: &RandomEncounter) -> Option<Vec<ScanOutcome>> {
    trace_one::<f64>(e, &CONDITIONS[0], 0)
        .ok()
        .map(|(outcomes, _)| outcomes)
}

/// Counts over a set of runs.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    pub runs: usize,
    pub refused: usize,
    pub reference_ra: usize,
    pub false_ra: usize,
    pub missed_ra: usize,
    pub false_ta: usize,
    pub missed_ta: usize,
    pub ta_agree: usize,
    pub ra_agree: usize,
    pub wrong_sense: usize,
    /// The largest |VMD| (the encounter's, at closest approach) of the
    /// wrong-sense runs, ft: how near a tie the two senses were.
    pub wrong_sense_largest_vmd_ft: Option<f64>,
    pub in_pieces: usize,
    pub reversed: usize,
    pub onset_delays_s: Vec<f64>,
}

impl Tally {
    /// Adds run `r` of encounter `e`.
    pub fn add(&mut self, e: &RandomEncounter, r: &RunResult) {
        self.runs += 1;
        self.reference_ra += usize::from(r.reference_ra);
        if r.refused {
            self.refused += 1;
            return;
        }
        self.false_ra += usize::from(r.ra && !r.reference_ra);
        self.missed_ra += usize::from(!r.ra && r.reference_ra);
        self.false_ta += usize::from(r.ta && !r.reference_ta);
        self.missed_ta += usize::from(!r.ta && r.reference_ta);
        self.ta_agree += usize::from(r.ta == r.reference_ta);
        self.ra_agree += usize::from(r.ra == r.reference_ra);
        self.wrong_sense += usize::from(r.wrong_sense);
        if r.wrong_sense {
            let vmd = e.vmd_ft.abs();
            self.wrong_sense_largest_vmd_ft =
                Some(self.wrong_sense_largest_vmd_ft.map_or(vmd, |v| v.max(vmd)));
        }
        self.in_pieces += usize::from(r.ra_pieces > 1);
        self.reversed += usize::from(r.reversed);
        self.onset_delays_s.extend(r.onset_delay_s);
    }

    /// Runs that went through.
    pub fn accepted(&self) -> usize {
        self.runs - self.refused
    }

    /// The `q` quantile of the onset delays (nearest rank), s.
    pub fn delay_quantile(&self, q: f64) -> Option<f64> {
        let mut d = self.onset_delays_s.clone();
        if d.is_empty() {
            return None;
        }
        d.sort_by(f64::total_cmp);
        let k = ((q * d.len() as f64).ceil() as usize).clamp(1, d.len()) - 1;
        Some(d[k])
    }
}
