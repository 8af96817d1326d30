//! Stack-overflow check: recurses until the stack overflows, on purpose.
//!
//! With flip-link the stack sits below the static data and grows towards
//! the bottom of RAM, so the overflow runs off the bottom of RAM and faults;
//! the HardFault handler (boards/qemu/src/board.rs) moves the stack pointer back
//! to the top of the stack, reports the overflow, runs this image's hook and
//! leaves QEMU with status 1. The hook checks that every word of a static
//! guard block, filled with a known pattern at start-up, still holds it: the
//! overflow corrupted no static data.
//!
//! scripts/test.sh runs it on the three boards and expects exactly that: the
//! report, the guard intact, exit status 1; not QEMU's "Lockup" (status 134,
//! the handler's own stacking faulted) and not a normal exit.
#![no_std]
#![no_main]

use abtrack_firmware::board;

use core::hint::black_box;
use core::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// Guard words, in `.data` (initialised from flash), so they sit among the
/// statics just above the stack.
const GUARD_WORDS: usize = 256;
const GUARD: u32 = 0xc0de_5afe;
static GUARD_BLOCK: [AtomicU32; GUARD_WORDS] = [const { AtomicU32::new(GUARD) }; GUARD_WORDS];

/// Depth reached, updated on the way down (a static, so the report can give
/// it after the fault).
static DEPTH: AtomicU32 = AtomicU32::new(0);

/// Bytes of stack each level takes at least.
const FRAME_BYTES: usize = 512;

/// Called by the HardFault handler after its report.
fn check_statics() {
    let intact = GUARD_BLOCK
        .iter()
        .filter(|w| w.load(Relaxed) == GUARD)
        .count();
    defmt::println!(
        "recursion depth {=u32} ({=u32} B per level) when the stack ran out",
        DEPTH.load(Relaxed),
        FRAME_BYTES as u32
    );
    if intact == GUARD_WORDS {
        defmt::println!(
            "statics intact: {=usize} of {=usize} guard words hold their pattern",
            intact,
            GUARD_WORDS
        );
    } else {
        defmt::error!(
            "statics CORRUPTED: {=usize} of {=usize} guard words hold their pattern",
            intact,
            GUARD_WORDS
        );
    }
}

/// One level: a frame of [`FRAME_BYTES`] the optimiser cannot remove, then
/// the next level. `black_box` keeps the recursion (the condition is always
/// true at run time) and the buffer.
#[inline(never)]
fn dive(level: u32) -> u32 {
    let mut frame = [0u8; FRAME_BYTES];
    DEPTH.store(level, Relaxed);
    black_box(&mut frame);
    let below = if black_box(true) {
        dive(level.wrapping_add(1))
    } else {
        0
    };
    below.wrapping_add(u32::from(black_box(&frame).iter().fold(0u8, |a, b| a ^ b)))
}

#[cortex_m_rt::entry]
fn main() -> ! {
    board::set_fault_hook(check_statics);
    let (_, available) = board::stack_usage();
    defmt::println!(
        "abtrack stack-overflow check on {=str} ({=str}): {=u32} bytes of stack below the statics; recursing until it overflows",
        board::BOARD,
        board::CORE,
        available
    );
    let result = dive(0);
    // Not reached: the recursion does not end.
    defmt::error!("the recursion returned ({=u32}): no overflow fault", result);
    board::exit(false)
}
