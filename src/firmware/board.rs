//! Board support shared by the firmware binaries (demo, self-test, benchmark):
//! which board and numeric type this build is for, the defmt transport, how
//! to leave QEMU with a status, and the fault handlers.
//!
//! Not part of the library: each binary includes it with `#[path]`. It is the
//! only place (with the binaries) that touches the hardware, per DESIGN.md.
//!
//! The target triple picks the board (see `.cargo/config.toml` and `build.rs`):
//! thumbv7em-none-eabihf → mps2-an386 (Cortex-M4F), thumbv7m-none-eabi →
//! mps2-an385 (Cortex-M3), thumbv6m-none-eabi → microbit (nRF51, Cortex-M0).

use core::cell::Cell;
use core::panic::PanicInfo;
use core::sync::atomic::{AtomicBool, Ordering};

// The critical-section implementation defmt-semihosting needs
// (cortex-m's `critical-section-single-core` feature).
use cortex_m as _;
use cortex_m_rt::{exception, ExceptionFrame};
// The defmt global logger: frames go out through semihosting SYS_WRITE to
// QEMU's stdout, where scripts/qemu-run.sh pipes them into defmt-print.
use defmt_semihosting as _;
use qemu_exit::QEMUExit;

/// The QEMU machine this build runs on (set by build.rs from the target).
pub const BOARD: &str = env!("ABTRACK_BOARD");

/// The core of [`BOARD`].
pub const CORE: &str = env!("ABTRACK_CORE");

/// The core's natural number system for the filters, the gain schedules
/// and the bank: `f32` where the core has a hardware FPU (the hard-float
/// ABI, thumbv7em-none-eabihf: Cortex-M4F), the fast fixed point
/// ([`abtrack::Fixed32`]) on cores without one (Cortex-M3, Cortex-M0),
/// where every float operation would be a software library call.
#[cfg(target_abi = "eabihf")]
#[allow(dead_code)] // the demo uses `TableScalar` until src/track is ported
pub type Native = f32;
/// See the hard-float definition.
#[cfg(not(target_abi = "eabihf"))]
#[allow(dead_code)] // the demo uses `TableScalar` until src/track is ported
pub type Native = abtrack::Fixed32;

/// The type of the code still written for `Scalar` (the track table, TCAS,
/// the altitude tracker, the demo) until it is ported to
/// [`abtrack::Numeric`]: `f32` with an FPU, Q32.32 without.
#[cfg(target_abi = "eabihf")]
#[allow(dead_code)] // the filter self-test uses `Native` only
pub type TableScalar = f32;
/// See the hard-float definition.
#[cfg(not(target_abi = "eabihf"))]
#[allow(dead_code)] // the filter self-test uses `Native` only
pub type TableScalar = abtrack::Fix;

/// Leaves QEMU through semihosting `SYS_EXIT_EXTENDED`: status 0 on success,
/// 1 on failure. Needs `-semihosting-config enable=on` (scripts/qemu-run.sh).
pub fn exit(success: bool) -> ! {
    let qemu = qemu_exit::AArch32::new();
    if success {
        qemu.exit_success()
    } else {
        qemu.exit_failure()
    }
}

/// Set by the first fault or panic, so that a fault raised while reporting one
/// (for example inside the logger) exits at once instead of recursing.
static FAILING: AtomicBool = AtomicBool::new(false);

/// True the first time it is called. A load and a store rather than a swap:
/// the Cortex-M0 has no atomic read-modify-write, and no interrupt handler
/// logs (the demo's handlers only count and queue).
fn first_failure() -> bool {
    let first = !FAILING.load(Ordering::Relaxed);
    FAILING.store(true, Ordering::Relaxed);
    first
}

/// A panic is a bug (the firmware is written so none is reachable from its
/// inputs): report where, and fail the run rather than hang.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    if first_failure() {
        match info.location() {
            Some(l) => defmt::error!("panic at {=str}:{=u32}", l.file(), l.line()),
            None => defmt::error!("panic"),
        }
    }
    exit(false)
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    if first_failure() {
        defmt::error!("hard fault at pc={=u32:#010x}", frame.pc());
    }
    exit(false)
}

/// The device-interrupt handler a binary installed, if any. Without a device
/// crate, cortex-m-rt sends every device interrupt to `DefaultHandler`;
/// binaries that enable one route it here. It returns false for an
/// interrupt it does not handle.
static INTERRUPT_HANDLER: cortex_m::interrupt::Mutex<Cell<Option<InterruptHandler>>> =
    cortex_m::interrupt::Mutex::new(Cell::new(None));

/// Takes the IRQ number; true if it handled the interrupt.
pub type InterruptHandler = fn(i16) -> bool;

/// Installs the handler of the binary's device interrupts (`irqn` = IRQ
/// number, exception number − 16). Install it before unmasking them.
#[allow(dead_code)] // the self-test and the benchmark use no interrupt
pub fn set_interrupt_handler(handler: InterruptHandler) {
    cortex_m::interrupt::free(|cs| INTERRUPT_HANDLER.borrow(cs).set(Some(handler)));
}

#[exception]
unsafe fn DefaultHandler(irqn: i16) {
    let handler = cortex_m::interrupt::free(|cs| INTERRUPT_HANDLER.borrow(cs).get());
    if handler.is_some_and(|h| h(irqn)) {
        return;
    }
    if first_failure() {
        defmt::error!("unexpected exception or interrupt {=i16}", irqn);
    }
    exit(false)
}

// Stack high-water mark. Static RAM is tiny (the filters live on the stack),
// so the stack is what decides whether a build fits a board's RAM. The
// binaries paint the free stack first thing and report how much of it was
// overwritten at the end.

/// What unused stack words hold.
const STACK_PAINT: u32 = 0x5ac4_5ac4;

extern "C" {
    /// End of static data = lowest stack address (cortex-m-rt's link.x).
    static _stack_end: u32;
    /// Initial stack pointer = end of RAM (cortex-m-rt's link.x).
    static _stack_start: u32;
}

fn stack_bounds() -> (usize, usize) {
    // Only the addresses of the linker symbols are taken (no read): safe.
    let bottom = core::ptr::addr_of!(_stack_end) as usize;
    let top = core::ptr::addr_of!(_stack_start) as usize;
    ((bottom + 3) & !3, top & !3)
}

/// Fills the unused stack (below the current frame, with a margin) with a
/// pattern. Call once, first thing in `main`.
pub fn paint_stack() {
    let (bottom, _) = stack_bounds();
    let sp = cortex_m::register::msp::read() as usize;
    let end = sp.saturating_sub(256) & !3;
    let mut p = bottom;
    while p < end {
        // SAFETY: [bottom, sp − 256) is RAM between the static data and the
        // live stack frames: nothing uses it yet.
        unsafe { (p as *mut u32).write_volatile(STACK_PAINT) };
        p += 4;
    }
}

/// (bytes of stack ever used since `paint_stack`, bytes available).
pub fn stack_usage() -> (u32, u32) {
    let (bottom, top) = stack_bounds();
    let mut p = bottom;
    // SAFETY: reads of RAM words between the static data and the stack top.
    while p < top && unsafe { (p as *const u32).read_volatile() } == STACK_PAINT {
        p += 4;
    }
    ((top - p) as u32, (top - bottom) as u32)
}

/// Logs the stack high-water mark.
#[allow(dead_code)] // the self-tests report per test instead
pub fn report_stack() {
    let (used, available) = stack_usage();
    defmt::println!(
        "stack: {=u32} of {=u32} bytes used (high-water mark)",
        used,
        available
    );
}
