//! Benchmark firmware: instructions per call of abtrack's operations in every
//! numeric type the core runs, beside anchors (a minimal αβ update, a
//! hand-written Kalman filter and a hand-written scan around it,
//! `minikalman`), on the emulated core.
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

// The calibration loop (`icount::known_instructions`); the bench times with
// its own `counter::Ticks`, not `icount::InstructionCounter`.
use abtrack_firmware::{board, icount, synth};

mod anchors;
mod counter;
mod data;
mod decoder;
mod filters;
mod minikalman;
mod numeric;
mod scan;

use core::any::TypeId;

use abtrack::{Fix, Fixed32, Scalar, ScaledScalar};
use counter::Bench;
use numeric::BenchNumber;

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
    // One line per number system. A new one: implement `BenchNumber` for it
    // (boards/qemu/src/bin/bench/numeric.rs) and add its line here.
    bench_numeric::<f32>(bench);
    bench_numeric::<Fixed32>(bench);
    bench_numeric::<Fix>(bench);
    bench_numeric::<f64>(bench);
    // The operations written for `Scalar`; in the fast fixed point they
    // run in its wide format, `ScaledScalar`.
    bench_scalar::<f32>(bench);
    bench_scalar::<ScaledScalar>(bench);
    bench_scalar::<Fix>(bench);
    bench_scalar::<f64>(bench);
    // Anchors: the hand-written Kalman filter in f32 and the fast fixed
    // point, the hand-written integer scan, and minikalman (f32, with its
    // I16F16 build).
    anchors::axis_kalman::<f32>(bench);
    anchors::axis_kalman::<ScaledScalar>(bench);
    anchors::integer_scan(bench);
    // The scan a user would write around that filter, where the flash
    // holds it (not the micro:bit's): in f32 (software f32 on the M3) and
    // in the fast fixed point's wide format.
    #[cfg(not(abtrack_board = "microbit"))]
    {
        anchors::nearest_neighbour_scan::<f32>(bench);
        anchors::nearest_neighbour_scan::<ScaledScalar>(bench);
    }
    #[cfg(abtrack_board = "microbit")]
    for label in [f32::LABEL, ScaledScalar::LABEL] {
        bench.omitted_group(label, &[anchors::NEAREST_NEIGHBOUR_SCAN], Omission::Flash);
    }
    minikalman::run(bench);
    // Integer-only code, the same in every numeric.
    decoder::parse_byte(bench);
}

/// The rows of one kind, left out of an image together.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Group {
    /// The filters, the schedules, range–azimuth and the floor
    /// ([`filters::run`], [`anchors::floor`]).
    Filters,
    /// The altitude tracker and the TCAS assessment.
    Tcas,
    /// The track table's scans.
    Scans,
}

impl Group {
    /// The operations of the group (the rows an omission leaves empty).
    fn operations(self) -> &'static [&'static str] {
        match self {
            Group::Filters => &[
                "ab1d_update",
                "abg1d_update",
                "ab2d_update",
                "abg2d_update",
                "ab2d_least_squares_update",
                "ab2d_liu_adaptive_update",
                "auto2d_update",
                "auto2d_update_per_call_interval",
                "range_azimuth_update",
                "floor_ab2d_update",
            ],
            Group::Tcas => &[
                "altitude_update",
                "tcas_assess",
                "tcas_cycle",
                "tcas_assess_in_cycle",
                "tcas_intruder_scan",
            ],
            Group::Scans => &[
                "scan_separated",
                "scan_crowded",
                "scan_default_separated",
                "scan_default_crowded",
            ],
        }
    }
}

use counter::Omission;

/// Every operation that runs in any number system, in `N`.
#[inline(never)]
fn bench_numeric<N: BenchNumber>(bench: &mut Bench) {
    if let Some(why) = omitted::<N>(Group::Filters) {
        bench.omitted_group(N::LABEL, Group::Filters.operations(), why);
        if let Some(why) = omitted::<N>(Group::Scans) {
            bench.omitted_group(N::LABEL, Group::Scans.operations(), why);
        }
        return;
    }
    filters::run::<N>(bench);
    anchors::floor::<N>(bench);
    match omitted::<N>(Group::Scans) {
        Some(why) => bench.omitted_group(N::LABEL, Group::Scans.operations(), why),
        None => scan::sizes::<N>(bench),
    }
}

/// The operations written for [`Scalar`] only, in `S`.
#[inline(never)]
fn bench_scalar<S: BenchNumber + Scalar>(bench: &mut Bench) {
    match omitted::<S>(Group::Tcas) {
        Some(why) => bench.omitted_group(S::LABEL, Group::Tcas.operations(), why),
        None => filters::run_scalar::<S>(bench),
    }
}

/// Why this image leaves out `group` in `N`, if it does. The mps2 boards
/// hold every row. The micro:bit's 256 KiB of flash do not: it keeps the
/// filter rows in soft f32, the fast fixed point (its firmware's type) and
/// f64, but not in Q32.32 (whose inlined 64-bit products alone would take
/// the image past 256 KiB), the TCAS rows in the type its firmware runs
/// them in ([`board::Wide`]: software `f32`), and the scans in the fast
/// fixed point only. With the feature `bench-microbit-scaled-tcas` it holds,
/// of abtrack's rows, only the TCAS rows in `ScaledScalar`, for the
/// comparison of the two types (the anchors and `parse_byte` still run).
/// Decided at compile time, so the code left out is not linked.
fn omitted<N: BenchNumber>(group: Group) -> Option<Omission> {
    if !cfg!(abtrack_board = "microbit") {
        return None;
    }
    let is = |t: TypeId| TypeId::of::<N>() == t;
    if cfg!(feature = "bench-microbit-scaled-tcas") {
        let kept = group == Group::Tcas && is(TypeId::of::<ScaledScalar>());
        return (!kept).then_some(Omission::Comparison);
    }
    let kept = match group {
        Group::Filters => !is(TypeId::of::<Fix>()),
        Group::Tcas => is(TypeId::of::<board::Wide>()),
        Group::Scans => is(TypeId::of::<Fixed32>()),
    };
    (!kept).then_some(Omission::Flash)
}
