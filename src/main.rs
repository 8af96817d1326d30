//! abtrack demo firmware: an αβ and an αβγ filter track a synthetic target in
//! the plane, in the core's natural numeric type (`f32` on the Cortex-M4F,
//! Q32.32 fixed point on the Cortex-M3 and M0), and report every scan through
//! defmt: time, measurement, estimate and residual; then the RMS position
//! error of each filter against the truth.
//!
//! The scenario is deterministic: the target flies straight at constant
//! velocity, then turns at a constant rate; measurements are the truth plus
//! bounded pseudo-noise from a fixed seed. Run it with `scripts/demo.sh`
//! (or `cargo run --release --target <triple>`); it exits with status 0, or 1
//! if a filter refused an update it should have taken.
#![no_std]
#![no_main]

#[path = "firmware/board.rs"]
mod board;
#[path = "firmware/synth.rs"]
mod synth;

use abtrack::filter::{Cartesian, Gains, UpdateOutcome};
use abtrack::Scalar;
use board::Native;
use synth::{Lcg, TurningTarget};

/// Seconds between scans.
const SCAN_INTERVAL: f64 = 1.0;
const SCANS: u32 = 60;
/// Standard deviation of the measurement noise on each axis, metres.
const NOISE_SIGMA: f64 = 30.0;
const NOISE_SEED: u64 = 0x00ab_7ac4_2024;

/// 200 m/s eastwards from (−8 km, 12 km), then from t = 30 s a left turn at
/// 0.05 rad/s (2.9°/s, about a standard-rate turn).
const TARGET: TurningTarget = TurningTarget {
    start: [-8_000.0, 12_000.0],
    velocity: [200.0, 0.0],
    turn_start: 30.0,
    turn_rate: 0.05,
};

/// αβ gains: α = 0.5 with the Benedict–Bordner β = α²/(2 − α) = 1/6
/// (Al-Wagih & Abdulla, method M1).
const AB_ALPHA: f64 = 0.5;
const AB_BETA: f64 = AB_ALPHA * AB_ALPHA / (2.0 - AB_ALPHA);

/// αβγ gains: the critically damped (fading-memory) filter with θ = 0.7:
/// α = 1 − θ³, β = 1.5(1 − θ)²(1 + θ), and in Tenne & Singh's convention
/// (acceleration update γ/(2T²)·e, eq. 5) γ = 2(1 − θ)³.
const THETA: f64 = 0.7;
const ABG_ALPHA: f64 = 1.0 - THETA * THETA * THETA;
const ABG_BETA: f64 = 1.5 * (1.0 - THETA) * (1.0 - THETA) * (1.0 + THETA);
const ABG_GAMMA: f64 = 2.0 * (1.0 - THETA) * (1.0 - THETA) * (1.0 - THETA);

#[cortex_m_rt::entry]
fn main() -> ! {
    board::paint_stack();
    defmt::println!(
        "abtrack demo on {=str} ({=str}), filters in {=str}",
        board::BOARD,
        board::CORE,
        Native::NAME
    );
    let ok = run::<Native>();
    board::report_stack();
    board::exit(ok)
}

/// Running sum of squared position errors (metres²) over a set of scans.
#[derive(Default, Clone, Copy)]
struct SquaredError {
    sum: f64,
    count: u32,
}

impl SquaredError {
    fn add(&mut self, estimate: [f64; 2], truth: [f64; 2]) {
        let dx = estimate[0] - truth[0];
        let dy = estimate[1] - truth[1];
        self.sum += dx * dx + dy * dy;
        self.count += 1;
    }

    /// Root mean square distance, metres (0 when empty).
    fn rms(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            libm::sqrt(self.sum / self.count as f64)
        }
    }
}

/// The errors of one run, split at the start of the turn.
#[derive(Default, Clone, Copy)]
struct Errors {
    straight: SquaredError,
    turning: SquaredError,
    all: SquaredError,
}

impl Errors {
    fn add(&mut self, t: f64, estimate: [f64; 2], truth: [f64; 2]) {
        if t < TARGET.turn_start {
            self.straight.add(estimate, truth);
        } else {
            self.turning.add(estimate, truth);
        }
        self.all.add(estimate, truth);
    }
}

fn to_f64<S: Scalar>(v: [S; 2]) -> [f64; 2] {
    [v[0].to_f64(), v[1].to_f64()]
}

/// The residuals of a 2-D update, if it was a filtered one (not one of the
/// two initialisation points).
fn residuals<S: Scalar>(outcome: &[UpdateOutcome<S>; 2]) -> Option<[S; 2]> {
    match outcome {
        [UpdateOutcome::Filtered(x), UpdateOutcome::Filtered(y)] => Some([x.residual, y.residual]),
        _ => None,
    }
}

/// Runs the scenario in numeric type `S`; false if anything was refused.
fn run<S: Scalar + defmt::Format>() -> bool {
    let (ab_gains, abg_gains) = match (
        Gains::<S>::alpha_beta_f64(AB_ALPHA, AB_BETA),
        Gains::<S>::alpha_beta_gamma_f64(ABG_ALPHA, ABG_BETA, ABG_GAMMA),
    ) {
        (Ok(ab), Ok(abg)) => (ab, abg),
        (Err(e), _) | (_, Err(e)) => {
            defmt::error!("demo gains refused: {}", e);
            return false;
        }
    };
    let Ok(dt) = S::try_from_f64(SCAN_INTERVAL) else {
        defmt::error!("scan interval not representable");
        return false;
    };
    defmt::println!(
        "target: 200 m/s straight, left turn at 0.05 rad/s from t = 30 s; noise sigma {=f64} m; T = {=f64} s",
        NOISE_SIGMA,
        SCAN_INTERVAL
    );
    defmt::println!(
        "ab: alpha {} beta {} | abg: alpha {} beta {} gamma {}",
        ab_gains.alpha(),
        ab_gains.beta(),
        abg_gains.alpha(),
        abg_gains.beta(),
        abg_gains.gamma()
    );
    defmt::println!(
        "columns: t | measurement | estimate, residual (ab) | estimate, residual (abg)"
    );

    let mut ab: Cartesian<S, 2, 2> = Cartesian::new();
    let mut abg: Cartesian<S, 3, 2> = Cartesian::new();
    let mut noise = Lcg::new(NOISE_SEED);
    let mut measured = Errors::default();
    let mut ab_errors = Errors::default();
    let mut abg_errors = Errors::default();
    let mut refused = 0u32;

    for scan in 0..SCANS {
        let t = scan as f64 * SCAN_INTERVAL;
        let truth = TARGET.at(t).position;
        let z_f64 = [
            truth[0] + noise.noise(NOISE_SIGMA),
            truth[1] + noise.noise(NOISE_SIGMA),
        ];
        let z = match (S::try_from_f64(z_f64[0]), S::try_from_f64(z_f64[1])) {
            (Ok(x), Ok(y)) => [x, y],
            _ => {
                defmt::error!("t={=f64}: measurement not representable", t);
                refused += 1;
                continue;
            }
        };
        let ab_out = ab.update(z, dt, &ab_gains);
        let abg_out = abg.update(z, dt, &abg_gains);
        let (ab_out, abg_out) = match (ab_out, abg_out) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                defmt::error!("t={=f64}: update refused: {}", t, e);
                refused += 1;
                continue;
            }
        };
        let ab_x = ab.position();
        let abg_x = abg.position();
        match (residuals(&ab_out), residuals(&abg_out)) {
            (Some(ab_e), Some(abg_e)) => {
                defmt::println!(
                    "t={=f64} z=({}, {}) | ab x=({}, {}) e=({}, {}) | abg x=({}, {}) e=({}, {})",
                    t,
                    z[0],
                    z[1],
                    ab_x[0],
                    ab_x[1],
                    ab_e[0],
                    ab_e[1],
                    abg_x[0],
                    abg_x[1],
                    abg_e[0],
                    abg_e[1]
                );
                // Scored from the first filtered scan on: the two
                // initialisation scans only copy the measurement.
                measured.add(t, z_f64, truth);
                ab_errors.add(t, to_f64(ab_x), truth);
                abg_errors.add(t, to_f64(abg_x), truth);
            }
            _ => defmt::println!(
                "t={=f64} z=({}, {}) | initialising (two-point, Al-Wagih eqs. 9-10)",
                t,
                z[0],
                z[1]
            ),
        }
    }

    defmt::println!(
        "summary over {=u32} filtered scans, RMS position error vs truth (m):",
        ab_errors.all.count
    );
    for (name, e) in [
        ("measurements", measured),
        ("ab", ab_errors),
        ("abg", abg_errors),
    ] {
        // f32 for display only: a few significant digits are what matters.
        defmt::println!(
            "  {=str}: all {=f32}, straight {=f32}, turning {=f32}",
            name,
            e.all.rms() as f32,
            e.straight.rms() as f32,
            e.turning.rms() as f32
        );
    }
    if refused > 0 {
        defmt::error!("{=u32} scans refused", refused);
    }
    refused == 0
}
