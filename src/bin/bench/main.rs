//! Benchmark firmware: instructions per call of abtrack's operations in every
//! numeric type the core runs, beside anchors (a minimal αβ update, a
//! hand-written Kalman filter, `minikalman`), on the emulated core.
//! Prints figures, one machine-readable line each; it is not a test
//! (scripts/bench.sh runs it on the three boards and turns the lines into
//! bench/results.csv and bench/BENCHMARKS.md; docs/benchmarks.md has the
//! line format and how to add a numeric or an operation).
//!
//! # How it counts
//!
//! QEMU does not model the DWT cycle counter (it reads 0), and its timing is
//! not cycle-accurate anyway. Run with `-icount shift=0` (scripts/qemu-run.sh
//! adds it for this binary), QEMU's virtual clock advances exactly 1 ns per
//! executed instruction, so any timer clocked from it counts instructions:
//! SysTick on the core clock gives one tick per 40 instructions on the mps2
//! boards (25 MHz), 62.5 on the micro:bit (16 MHz). The firmware does not
//! assume the ratio: it first times a loop of a known number of instructions
//! ([`counter::Calibration`]) and scales every measurement by what it found.
//!
//! Each per-call figure is the average over [`CALLS`] calls, each of a
//! non-inlined function that runs the operation once, minus the same loop
//! without the call (fetching the input, `black_box`): so it includes one
//! call and return. These are instruction counts, not cycles: on real
//! silicon multiplies, divides, loads and branches take different numbers of
//! cycles (and flash wait states add more).
#![no_std]
#![no_main]

#[path = "../../firmware/board.rs"]
mod board;
#[path = "../../firmware/synth.rs"]
mod synth;

mod anchors;
mod counter;
mod data;
mod decoder;
mod filters;
mod minikalman;
mod numeric;
mod scan;

use abtrack::Fix;
use counter::Bench;
use numeric::Numeric;

/// Calls averaged per per-call figure.
pub const CALLS: u32 = 4096;

#[cortex_m_rt::entry]
fn main() -> ! {
    board::paint_stack();
    let ok = match cortex_m::Peripherals::take() {
        Some(p) => match Bench::start(p.SYST) {
            Some(mut bench) => {
                run(&mut bench);
                bench.finish()
            }
            None => false,
        },
        None => {
            defmt::error!("core peripherals already taken");
            false
        }
    };
    board::exit(ok)
}

fn run(bench: &mut Bench) {
    // One line per numeric type. A new one: implement `Numeric` for it
    // (src/bin/bench/numeric.rs) and add its line here.
    bench_numeric::<f32>(bench);
    bench_numeric::<Fix>(bench);
    bench_numeric::<f64>(bench);
    // Anchors in f32 only: the hand-written Kalman filter, and minikalman
    // (with its I16F16 build).
    anchors::axis_kalman::<f32>(bench);
    minikalman::run(bench);
    // Integer-only code, the same in every numeric.
    decoder::parse_byte(bench);
}

/// Every operation that runs in `S`.
#[inline(never)]
fn bench_numeric<S: Numeric>(bench: &mut Bench) {
    filters::run::<S>(bench);
    anchors::floor::<S>(bench);
    if scans_fit::<S>() {
        // The track table at N tracks = M measurements per scan, one line
        // per size (each a table type of its own, with its own code).
        scan::run::<S, 8, 8>(bench);
        scan::run::<S, 16, 16>(bench);
    }
}

/// Whether this image holds the scan rows in `S`: every board holds them
/// in its natural type ([`board::Native`]); the micro:bit's 256 KiB of
/// flash holds no other (each type's table code for two sizes is about
/// 35 KiB there). Decided at compile time, so the code left out is not
/// linked.
fn scans_fit<S: Numeric>() -> bool {
    !cfg!(abtrack_board = "microbit")
        || core::any::TypeId::of::<S>() == core::any::TypeId::of::<board::TableScalar>()
}
