//! Benchmark firmware: instructions per filter update (αβ, αβγ, and a 2-D
//! Cartesian αβ) in f32, Q32.32 fixed point and f64, on the emulated core.
//! Prints figures; it is not a test (scripts/bench.sh runs it on the three
//! boards).
//!
//! # How it counts
//!
//! QEMU does not model the DWT cycle counter (it reads 0), and its timing is
//! not cycle-accurate anyway. Run with `-icount shift=0` (scripts/qemu-run.sh
//! adds it for this binary), QEMU's virtual clock advances exactly 1 ns per
//! executed instruction, so any timer clocked from it counts instructions:
//! SysTick on the core clock gives one tick per 40 instructions on the mps2
//! boards (25 MHz). The firmware does not assume the ratio: it first times a
//! loop of a known number of instructions (a two-instruction `subs`/`bne`
//! loop in assembly) and scales every measurement by what it found.
//! On the micro:bit (nRF51) QEMU 7.2 also models SysTick on the 16 MHz
//! core clock, so the same code runs there.
//!
//! Each figure is the average over [`UPDATES`] updates on a deterministic
//! noisy trajectory, each a call of a non-inlined function that runs the
//! update, minus the same loop without the call (fetching the measurement,
//! `black_box`): so it includes one call and return. These are instruction counts, not cycles: on
//! real silicon multiplies, divides, loads and branches take different numbers
//! of cycles (and flash wait states add more).
#![no_std]
#![no_main]

#[path = "../firmware/board.rs"]
mod board;
#[path = "../firmware/synth.rs"]
mod synth;

use core::hint::black_box;

use abtrack::filter::altitude::AltitudeEstimate;
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::filter::{Cartesian, Gains, KinematicFilter};
use abtrack::gain::al_wagih::LeastSquaresConfig;
use abtrack::gain::liu::{AdaptiveSwitchConfig, SwitchMode};
use abtrack::gain::{AdaptiveSwitchGains, GainSchedule, LeastSquaresGains, ScheduledFilter};
use abtrack::tcas::{assess, Advisory, Intruder, OwnAircraft};
use abtrack::track::assign::{AssignmentSolver, FORBIDDEN};
use abtrack::track::{
    Association, FixedGainTrack, Gate, Measurement, Observation, TrackFilter, TrackTable,
    TrackerConfig,
};
use abtrack::{Fix, Scalar};
use board::Native;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use synth::Lcg;

/// Updates averaged per figure.
const UPDATES: u32 = 4096;
/// Length of the measurement ring the updates cycle through.
const RING: usize = 64;
/// SysTick's counter is 24 bits wide.
const SYSTICK_MAX: u32 = 0x00ff_ffff;

#[cortex_m_rt::entry]
fn main() -> ! {
    board::paint_stack();
    let ok = match cortex_m::Peripherals::take() {
        Some(p) => run(p.SYST),
        None => {
            defmt::error!("core peripherals already taken");
            false
        }
    };
    board::exit(ok)
}

/// SysTick as a free-running down-counter of the core clock.
struct Ticks {
    syst: SYST,
}

impl Ticks {
    fn new(mut syst: SYST) -> Self {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(SYSTICK_MAX);
        syst.clear_current();
        syst.enable_counter();
        Ticks { syst }
    }

    /// Ticks taken by `work`, or `None` if the counter did not run or wrapped
    /// (the measurement would be meaningless).
    fn time(&mut self, work: impl FnOnce()) -> Option<u32> {
        self.syst.clear_current();
        // Writing the counter zeroes it; it reloads on the next tick. Wait
        // for that (boundedly: a counter that never runs must not hang us).
        let mut spins = 0u32;
        while SYST::get_current() == 0 {
            spins += 1;
            if spins > 100_000 {
                return None;
            }
        }
        let _ = self.syst.has_wrapped(); // reading clears COUNTFLAG
        let start = SYST::get_current();
        work();
        let end = SYST::get_current();
        if self.syst.has_wrapped() || end > start {
            return None;
        }
        Some(start - end)
    }
}

/// Executes exactly 2·n instructions (n ≥ 1): `subs` and `bne`, n times.
fn known_instructions(n: u32) {
    // SAFETY: register-only arithmetic on r0, declared clobbered; no memory
    // access, no stack use.
    unsafe {
        core::arch::asm!(
            "2:",
            "subs r0, #1",
            "bne 2b",
            inout("r0") n => _,
            options(nomem, nostack),
        );
    }
}

/// Instructions per SysTick tick, measured.
struct Calibration {
    instructions: u32,
    ticks: u32,
}

impl Calibration {
    fn instructions_per_tick(&self) -> f64 {
        self.instructions as f64 / self.ticks as f64
    }
}

fn run(syst: SYST) -> bool {
    let mut ticks = Ticks::new(syst);
    const LOOPS: u32 = 1_000_000;
    let calibration = match ticks.time(|| known_instructions(black_box(LOOPS))) {
        Some(t) if t > 0 => Calibration {
            instructions: 2 * LOOPS,
            ticks: t,
        },
        _ => {
            defmt::error!("SysTick does not count on this board; no figures");
            return false;
        }
    };
    defmt::println!(
        "abtrack bench on {=str} ({=str}): {=u32} instructions took {=u32} SysTick ticks ({=f32} instructions/tick; run under -icount shift=0)",
        board::BOARD,
        board::CORE,
        calibration.instructions,
        calibration.ticks,
        calibration.instructions_per_tick() as f32
    );
    defmt::println!(
        "instructions per update (this core's natural type: {=str}), average of {=u32} updates, loop overhead subtracted:",
        Native::NAME,
        UPDATES
    );
    let mut ok = true;
    ok &= bench_type::<f32>(&mut ticks, &calibration);
    ok &= bench_type::<Fix>(&mut ticks, &calibration);
    ok &= bench_type::<f64>(&mut ticks, &calibration);
    defmt::println!(
        "instructions per call, natural type ({=str}) and f64:",
        Native::NAME
    );
    ok &= bench_system::<Native>(&mut ticks, &calibration);
    ok &= bench_system::<f64>(&mut ticks, &calibration);
    ok &= bench_table::<Native, 8, 8>(&mut ticks, &calibration);
    ok &= bench_table::<f64, 8, 8>(&mut ticks, &calibration);
    ok &= bench_table::<Native, 16, 16>(&mut ticks, &calibration);
    ok &= bench_table::<f64, 16, 16>(&mut ticks, &calibration);
    board::report_stack();
    ok
}

/// A noisy target going out and back (so the ring of measurements closes on
/// itself without a jump), converted to `S`.
fn ring<S: Scalar>(seed: u64, speed: f64) -> [S; RING] {
    ring_with_noise(seed, speed, 25.0)
}

/// [`ring`] with noise of standard deviation `sigma` (m).
fn ring_with_noise<S: Scalar>(seed: u64, speed: f64, sigma: f64) -> [S; RING] {
    let mut rng = Lcg::new(seed);
    let mut out = [S::ZERO; RING];
    for (k, z) in out.iter_mut().enumerate() {
        let leg = if k < RING / 2 { k } else { RING - k };
        *z = S::from_f64_lossy(5_000.0 + speed * leg as f64 + rng.noise(sigma));
    }
    out
}

/// One update behind a call the compiler may not inline, so that every figure
/// includes the same call overhead whatever the inliner decides for the
/// filter's own code (left to itself it inlines some instantiations into the
/// loop and not others).
#[inline(never)]
fn update_one_axis<S: Scalar, const ORDER: usize>(
    filter: &mut KinematicFilter<S, ORDER>,
    z: S,
    dt: S,
    gains: &Gains<S>,
) -> bool {
    filter.update(z, dt, gains).is_ok()
}

/// As [`update_one_axis`], for the 2-D filter.
#[inline(never)]
fn update_plane<S: Scalar>(
    filter: &mut Cartesian<S, 2, 2>,
    z: [S; 2],
    dt: S,
    gains: &Gains<S>,
) -> bool {
    filter.update(z, dt, gains).is_ok()
}

/// The three figures for one numeric type; false if an update was refused.
#[inline(never)]
fn bench_type<S: Scalar>(ticks: &mut Ticks, calibration: &Calibration) -> bool {
    let (Ok(ab_gains), Ok(abg_gains)) = (
        Gains::<S>::alpha_beta_f64(0.5, 0.5 * 0.5 / 1.5),
        Gains::<S>::alpha_beta_gamma_f64(0.657, 0.2295, 0.054),
    ) else {
        defmt::error!("{=str}: gains refused", S::NAME);
        return false;
    };
    let dt = S::from_f64_lossy(1.0);
    let xs = ring::<S>(1, 180.0);
    let ys = ring::<S>(2, -120.0);
    let mut refused = 0u32;

    let baseline = ticks.time(|| {
        for z in xs.iter().cycle().take(UPDATES as usize) {
            black_box(black_box(*z));
        }
    });
    let baseline_2d = ticks.time(|| {
        for (x, y) in xs.iter().zip(ys.iter()).cycle().take(UPDATES as usize) {
            black_box([black_box(*x), black_box(*y)]);
        }
    });

    let mut ab = KinematicFilter::<S, 2>::new();
    let ab_ticks = ticks.time(|| {
        let (gains, dt) = (black_box(ab_gains), black_box(dt));
        for z in xs.iter().cycle().take(UPDATES as usize) {
            if !update_one_axis(&mut ab, black_box(*z), dt, &gains) {
                refused += 1;
            }
        }
    });
    let mut abg = KinematicFilter::<S, 3>::new();
    let abg_ticks = ticks.time(|| {
        let (gains, dt) = (black_box(abg_gains), black_box(dt));
        for z in xs.iter().cycle().take(UPDATES as usize) {
            if !update_one_axis(&mut abg, black_box(*z), dt, &gains) {
                refused += 1;
            }
        }
    });
    let mut plane: Cartesian<S, 2, 2> = Cartesian::new();
    let plane_ticks = ticks.time(|| {
        let (gains, dt) = (black_box(ab_gains), black_box(dt));
        for (x, y) in xs.iter().zip(ys.iter()).cycle().take(UPDATES as usize) {
            if !update_plane(&mut plane, [black_box(*x), black_box(*y)], dt, &gains) {
                refused += 1;
            }
        }
    });

    let per_update = |work: Option<u32>, base: Option<u32>| -> Option<f32> {
        let (w, b) = (work?, base?);
        let net = w.checked_sub(b)? as f64 * calibration.instructions_per_tick();
        Some((net / UPDATES as f64) as f32)
    };
    match (
        per_update(ab_ticks, baseline),
        per_update(abg_ticks, baseline),
        per_update(plane_ticks, baseline_2d),
    ) {
        (Some(ab), Some(abg), Some(plane)) => {
            defmt::println!(
                "  {=str}: ab {=f32}, abg {=f32}, 2-D ab {=f32}",
                S::NAME,
                ab,
                abg,
                plane
            );
        }
        _ => {
            defmt::error!("{=str}: a measurement overflowed or did not run", S::NAME);
            return false;
        }
    }
    if refused > 0 {
        defmt::error!("{=str}: {=u32} updates refused", S::NAME, refused);
    }
    refused == 0
}

// ---------------------------------------------------------------------------
// Beyond the bare filter: schedules, range–azimuth, TCAS, the track table
// ---------------------------------------------------------------------------

/// Ticks of a loop of `calls` iterations of `work`, minus those of the same
/// loop around `baseline` (what the loop costs without the measured call),
/// in instructions per call.
fn instructions_per_call(
    ticks: &mut Ticks,
    calibration: &Calibration,
    calls: u32,
    mut work: impl FnMut(u32),
    mut baseline: impl FnMut(u32),
) -> Option<f32> {
    let base = ticks.time(|| {
        for k in 0..calls {
            baseline(k);
        }
    })?;
    let w = ticks.time(|| {
        for k in 0..calls {
            work(k);
        }
    })?;
    let net = w.checked_sub(base)? as f64 * calibration.instructions_per_tick();
    Some((net / calls as f64) as f32)
}

#[inline(never)]
fn update_scheduled<S: Scalar, G: GainSchedule<S, 2>>(
    filter: &mut ScheduledFilter<S, G, 2, 2>,
    z: [S; 2],
    dt: S,
) -> bool {
    filter.update(z, dt).is_ok()
}

#[inline(never)]
fn update_range_azimuth<S: Scalar>(
    filter: &mut RangeAzimuthFilter<S>,
    range: S,
    azimuth: S,
    dt: S,
) -> bool {
    filter.update(range, azimuth, dt).is_ok()
}

#[inline(never)]
fn assess_one<S: Scalar>(own: &OwnAircraft<S>, intruder: &Intruder<S>) -> Option<Advisory> {
    assess(own, intruder).ok().map(|a| a.advisory)
}

/// Scheduled 2-D αβ (least squares, Liu's adaptive switch), one
/// range–azimuth update, and one TCAS assessment, in `S`.
#[inline(never)] // its rings would otherwise sit in `run`'s frame
fn bench_system<S: Scalar>(ticks: &mut Ticks, calibration: &Calibration) -> bool {
    let dt = S::from_f64_lossy(1.0);
    // Liu, Wang & Yang's σ = 5 m: Liu's switch (19 m) sees steady stretches
    // and the turnarounds of the out-and-back track.
    let xs = ring_with_noise::<S>(1, 180.0, 5.0);
    let ys = ring_with_noise::<S>(2, -120.0, 5.0);
    let mut refused = 0u32;
    let at = |k: u32| (k as usize) % RING;
    let plane_baseline = |k: u32| {
        black_box([black_box(xs[at(k)]), black_box(ys[at(k)])]);
    };

    let (Ok(ls), Ok(liu)) = (
        LeastSquaresGains::new(&LeastSquaresConfig::DEFAULT),
        AdaptiveSwitchGains::<S, 2, 8>::new(&AdaptiveSwitchConfig::DEFAULT),
    ) else {
        defmt::error!("{=str}: schedule configuration refused", S::NAME);
        return false;
    };
    let mut ls_track: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(ls);
    let least_squares = instructions_per_call(
        ticks,
        calibration,
        UPDATES,
        |k| {
            let z = [black_box(xs[at(k)]), black_box(ys[at(k)])];
            if !update_scheduled(&mut ls_track, z, black_box(dt)) {
                refused += 1;
            }
        },
        plane_baseline,
    );
    let mut liu_track: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(liu);
    let mut residual_branch = 0u32;
    let adaptive = instructions_per_call(
        ticks,
        calibration,
        UPDATES,
        |k| {
            let z = [black_box(xs[at(k)]), black_box(ys[at(k)])];
            if !update_scheduled(&mut liu_track, z, black_box(dt)) {
                refused += 1;
            }
        },
        plane_baseline,
    );
    // Which branch the adaptive runs took (after the timing, same data).
    let mut probe: ScheduledFilter<S, _, 2, 2> = ScheduledFilter::new(liu);
    for k in 0..UPDATES {
        let _ = probe.update([xs[at(k)], ys[at(k)]], dt);
        if probe.schedule().last_mode() == Some(SwitchMode::Manoeuvre) {
            residual_branch += 1;
        }
    }

    // Range–azimuth: a target 20 km out going out and back at 150 m/s along
    // the line of sight while the azimuth drifts, 15 m and 0.01 rad of noise.
    let mut rng = Lcg::new(3);
    let mut polar = [(S::ZERO, S::ZERO); RING];
    for (k, p) in polar.iter_mut().enumerate() {
        let leg = if k < RING / 2 { k } else { RING - k } as f64;
        *p = (
            S::from_f64_lossy(20_000.0 + 150.0 * leg + rng.noise(15.0)),
            S::from_f64_lossy(0.5 + 0.002 * leg + rng.noise(0.01)),
        );
    }
    let Ok(noise) = RangeAzimuthNoise::<S>::paper_bearing_f64(225.0, 1.0) else {
        defmt::error!("{=str}: noise refused", S::NAME);
        return false;
    };
    let mut ra = RangeAzimuthFilter::new(noise);
    let range_azimuth = instructions_per_call(
        ticks,
        calibration,
        UPDATES,
        |k| {
            let (r, b) = polar[at(k)];
            if !update_range_azimuth(&mut ra, black_box(r), black_box(b), black_box(dt)) {
                refused += 1;
            }
        },
        |k| {
            let (r, b) = polar[at(k)];
            black_box((black_box(r), black_box(b)));
        },
    );

    // TCAS: intruders within ±6 NM on each axis, ±300 m/s, ±1000 ft and
    // ±30 ft/s of the own aircraft, level at 8000 ft (SL 5): a mix of none,
    // proximate, TA and RA.
    let own = OwnAircraft::over_sea_level(S::from_f64_lossy(8000.0), S::ZERO);
    let mut intruders = [Intruder {
        relative_position_m: [S::ZERO; 2],
        relative_velocity_m_per_s: [S::ZERO; 2],
        altitude: None,
    }; RING];
    let mut rng = Lcg::new(4);
    for i in intruders.iter_mut() {
        let c = |v: f64| S::from_f64_lossy(v);
        *i = Intruder {
            relative_position_m: [
                c(rng.uniform(-11_112.0, 11_112.0)),
                c(rng.uniform(-11_112.0, 11_112.0)),
            ],
            relative_velocity_m_per_s: [
                c(rng.uniform(-300.0, 300.0)),
                c(rng.uniform(-300.0, 300.0)),
            ],
            altitude: Some(AltitudeEstimate {
                altitude_ft: c(8000.0 + rng.uniform(-1000.0, 1000.0)),
                vertical_rate_ft_per_s: c(rng.uniform(-30.0, 30.0)),
            }),
        };
    }
    let mut alerts = 0u32;
    let tcas = instructions_per_call(
        ticks,
        calibration,
        UPDATES,
        |k| match assess_one(black_box(&own), black_box(&intruders[at(k)])) {
            Some(a) if a >= Advisory::Traffic => alerts += 1,
            Some(_) => {}
            None => refused += 1,
        },
        |k| {
            black_box(black_box(&intruders[at(k)]));
        },
    );
    match (least_squares, adaptive, range_azimuth, tcas) {
        (Some(ls), Some(liu), Some(ra), Some(tcas)) => defmt::println!(
            "  {=str}: scheduled 2-D ab least-squares {=f32}, liu-adaptive {=f32} ({=u32} of {=u32} updates on the manoeuvre branch); range-azimuth update {=f32}; tcas assess {=f32} per intruder ({=u32} of {=u32} TA/RA)",
            S::NAME,
            ls,
            liu,
            residual_branch,
            UPDATES,
            ra,
            tcas,
            alerts,
            UPDATES
        ),
        _ => {
            defmt::error!("{=str}: a measurement overflowed or did not run", S::NAME);
            return false;
        }
    }
    if refused > 0 {
        defmt::error!("{=str}: {=u32} calls refused", S::NAME, refused);
    }
    refused == 0
}

/// Scans timed per figure.
const SCANS: u32 = 16;

type BenchTable<S, const N: usize, const M: usize> = TrackTable<S, FixedGainTrack<S>, N, M>;

/// `N` targets 2 km apart on a grid, flying in parallel at 100 m/s; one
/// measurement each per scan (±2 m of noise), so in steady state every
/// track has exactly its own measurement in its gate.
fn grid_scan<S: Scalar, const M: usize>(k: u32, rng: &mut Lcg) -> [Measurement<S>; M] {
    let t = k as f64;
    let side = 1 + libm::sqrt(M as f64) as usize;
    core::array::from_fn(|i| {
        let (col, row) = ((i % side) as f64, (i / side) as f64);
        Measurement::Cartesian {
            x: S::from_f64_lossy(2000.0 * col + 100.0 * t + rng.uniform(-2.0, 2.0)),
            y: S::from_f64_lossy(2000.0 * row + rng.uniform(-2.0, 2.0)),
        }
    })
}

#[inline(never)]
fn run_scan<S: Scalar, const N: usize, const M: usize>(
    table: &mut BenchTable<S, N, M>,
    config: &TrackerConfig<S, Gains<S>>,
    now_ms: u32,
    measurements: &[Measurement<S>; M],
    codes: &mut [Association; M],
) -> bool {
    table.scan(config, now_ms, measurements, codes).is_ok()
}

/// The track table in steady state, `N` confirmed tracks and `M`
/// measurements per scan: the whole `scan`, and its stages timed apart by
/// calling the same library functions the scan calls (the track filters'
/// `predict`, `gate_region` and `GateRegion::cost`, the assignment solver,
/// the filters' `update`) on a copy of the table's tracks. The scan's other
/// work (intake, bookkeeping, lifecycle, initiation) is the difference.
#[inline(never)]
fn bench_table<S: Scalar, const N: usize, const M: usize>(
    ticks: &mut Ticks,
    calibration: &Calibration,
) -> bool {
    let (Ok(gains), Ok(gate)) = (
        Gains::<S>::alpha_beta_f64(0.5, 0.2),
        Gate::uncertainty(
            S::from_f64_lossy(5.0),
            S::from_f64_lossy(13.8),
            S::from_f64_lossy(5.0),
        ),
    ) else {
        defmt::error!("{=str}: tracker configuration refused", S::NAME);
        return false;
    };
    let Ok(config) = TrackerConfig::new(gains, gate, S::from_f64_lossy(300.0)) else {
        defmt::error!("{=str}: tracker configuration refused", S::NAME);
        return false;
    };
    // A constant, copied into place: `new()` would build the table in its
    // own frame and copy it here, twice the table on the stack.
    let mut table = const { BenchTable::<S, N, M>::new() };
    let mut rng = Lcg::new(5);
    let mut codes = [Association::OutsideGates; M];
    // Warm-up: initiation and confirmation of every track.
    let mut k = 0u32;
    while k < 5 {
        let m = grid_scan::<S, M>(k, &mut rng);
        if !run_scan(&mut table, &config, 1000 * k, &m, &mut codes) {
            defmt::error!("{=str}: warm-up scan refused", S::NAME);
            return false;
        }
        k += 1;
    }
    if table.len() != N.min(M) {
        defmt::error!(
            "{=str}: {=usize} tracks after warm-up",
            S::NAME,
            table.len()
        );
        return false;
    }
    // Whole scans, timed one by one (the measurements made outside).
    let mut scan_ticks = 0u32;
    let mut empty_ticks = 0u32;
    for _ in 0..SCANS {
        let m = grid_scan::<S, M>(k, &mut rng);
        let now = 1000 * k;
        let (Some(t), Some(e)) = (
            ticks.time(|| {
                black_box(run_scan(
                    &mut table,
                    &config,
                    now,
                    black_box(&m),
                    &mut codes,
                ));
            }),
            ticks.time(|| {
                black_box(black_box(&m));
            }),
        ) else {
            defmt::error!("{=str}: scan timing failed", S::NAME);
            return false;
        };
        scan_ticks += t;
        empty_ticks += e;
        k += 1;
    }
    let per = |t: u32, e: u32, n: u32| -> f32 {
        (t.saturating_sub(e) as f64 * calibration.instructions_per_tick() / n as f64) as f32
    };
    let scan = per(scan_ticks, empty_ticks, SCANS);

    // The stages on the table's tracks, at the next scan (predict and gate
    // read them in place; update works on a copy of each track, made inside
    // the timed loop: 84 to 160 bytes a track).
    let dt = S::from_f64_lossy(1.0);
    let m = grid_scan::<S, M>(k, &mut rng);
    let observations: [Option<Observation<S>>; M] = m.map(|x| Observation::new(x).ok());
    let mut predicted = [None; N];
    let predict = ticks.time(|| {
        for (p, t) in predicted.iter_mut().zip(black_box(&table).tracks()) {
            *p = t.filter().predict(&gains, dt).ok();
        }
        black_box(&predicted);
    });
    let mut cost = [[FORBIDDEN; M]; N];
    let gate_ticks = ticks.time(|| {
        let tracks = black_box(&table).tracks();
        for ((row, t), p) in cost.iter_mut().zip(tracks).zip(predicted.iter()) {
            let f = t.filter();
            let Some(region) = p.and_then(|p| f.gate_region(&gains, &p, dt, config.gate())) else {
                continue;
            };
            for (c, o) in row.iter_mut().zip(black_box(&observations).iter()) {
                if let Some(o) = o {
                    *c = region.cost(o).unwrap_or(FORBIDDEN);
                }
            }
        }
        black_box(&cost);
    });
    let gated = cost.iter().flatten().filter(|c| **c != FORBIDDEN).count();
    let mut solver = const { AssignmentSolver::<N, M>::new() };
    let mut solution = None;
    let assign = ticks.time(|| {
        let c = black_box(&cost);
        solution = solver
            .solve(N, M, |r, col| {
                c.get(r)
                    .and_then(|row| row.get(col))
                    .copied()
                    .unwrap_or(FORBIDDEN)
            })
            .ok();
    });
    let mut assigned = [None; N];
    for (r, a) in assigned.iter_mut().enumerate() {
        *a = solver.col_for_row(r);
    }
    let mut accepted = 0usize;
    let update = ticks.time(|| {
        for (t, a) in black_box(&table).tracks().zip(assigned.iter()) {
            if let Some(Some(o)) = a.and_then(|c| observations.get(c)) {
                let mut f = *t.filter();
                if f.update(&gains, o, dt).is_ok() {
                    accepted += 1;
                }
                black_box(&f);
            }
        }
    });
    let empty = ticks.time(|| {
        black_box(&table);
    });
    if accepted != N.min(M) {
        defmt::error!("{=str}: {=usize} stage updates accepted", S::NAME, accepted);
        return false;
    }
    match (predict, gate_ticks, assign, update, empty, solution) {
        (Some(p), Some(g), Some(a), Some(u), Some(e), Some(s)) => defmt::println!(
            "  {=str} track table {=usize} x {=usize}: scan {=f32} per scan; stages: predict {=f32}, gate {=f32} ({=usize} gated pairs), assign {=f32} ({=u32} assigned, {=u32} solver steps), update {=f32}",
            S::NAME,
            N,
            M,
            scan,
            per(p, e, 1),
            per(g, e, 1),
            gated,
            per(a, e, 1),
            s.assigned,
            s.steps,
            per(u, e, 1)
        ),
        _ => {
            defmt::error!("{=str}: stage timing failed", S::NAME);
            return false;
        }
    }
    true
}
