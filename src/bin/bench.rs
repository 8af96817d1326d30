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

use abtrack::filter::{Cartesian, Gains, KinematicFilter};
use abtrack::{Fix, Scalar};
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
        board::Native::NAME,
        UPDATES
    );
    let mut ok = true;
    ok &= bench_type::<f32>(&mut ticks, &calibration);
    ok &= bench_type::<Fix>(&mut ticks, &calibration);
    ok &= bench_type::<f64>(&mut ticks, &calibration);
    board::report_stack();
    ok
}

/// A noisy target going out and back (so the ring of measurements closes on
/// itself without a jump), converted to `S`.
fn ring<S: Scalar>(seed: u64, speed: f64) -> [S; RING] {
    let mut rng = Lcg::new(seed);
    let mut out = [S::ZERO; RING];
    for (k, z) in out.iter_mut().enumerate() {
        let leg = if k < RING / 2 { k } else { RING - k };
        *z = S::from_f64_lossy(5_000.0 + speed * leg as f64 + rng.noise(25.0));
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
