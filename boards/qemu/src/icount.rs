//! Instruction counts on the emulated core: SysTick as a free-running
//! down-counter of the core clock. QEMU does not model the cycle counter;
//! run with `-icount shift=0`, its virtual clock advances exactly 1 ns per
//! executed instruction, so SysTick counts instructions (one tick per 40 on
//! the mps2 boards' 25 MHz). The ratio is measured, not assumed: a loop of
//! a known number of instructions is timed first. These are instructions, not cycles.

use core::hint::black_box;

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;

/// SysTick's counter is 24 bits wide.
const SYSTICK_MASK: u32 = 0x00ff_ffff;

/// SysTick, free running, with the measured instructions per tick.
pub struct InstructionCounter {
    _syst: SYST,
    /// Instructions per tick, ×1000 (fixed point, no float needed).
    milli_instructions_per_tick: u32,
}

/// Executes exactly 2·n instructions (n ≥ 1): `subs` and `bne`, n times.
pub fn known_instructions(n: u32) {
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

impl InstructionCounter {
    /// Starts SysTick and calibrates it; `None` if it does not count (not
    /// run under `-icount`, or a board without SysTick).
    pub fn new(mut syst: SYST) -> Option<Self> {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(SYSTICK_MASK);
        syst.clear_current();
        syst.enable_counter();
        const LOOPS: u32 = 1_000_000;
        let start = SYST::get_current();
        known_instructions(black_box(LOOPS));
        let ticks = start.wrapping_sub(SYST::get_current()) & SYSTICK_MASK;
        if ticks == 0 {
            return None;
        }
        Some(InstructionCounter {
            _syst: syst,
            milli_instructions_per_tick: (2 * LOOPS as u64 * 1000 / ticks as u64) as u32,
        })
    }

    /// Instructions per SysTick tick, as measured.
    pub fn instructions_per_tick(&self) -> f32 {
        self.milli_instructions_per_tick as f32 / 1000.0
    }

    /// A reading of the counter.
    pub fn now(&self) -> u32 {
        SYST::get_current()
    }

    /// Instructions since the reading `start` (less than 2²⁴ ticks ago: 671
    /// million instructions on the mps2 boards).
    pub fn since(&self, start: u32) -> u32 {
        let ticks = start.wrapping_sub(SYST::get_current()) & SYSTICK_MASK;
        (ticks as u64 * self.milli_instructions_per_tick as u64 / 1000) as u32
    }
}
