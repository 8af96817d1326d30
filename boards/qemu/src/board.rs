//! Board support shared by the firmware binaries (demo, self-tests,
//! benchmark, stack-overflow check): which board and numeric type this build
//! is for, the defmt transport, how to stop with a status, and the fault
//! handlers.
//!
//! Not part of the abtrack library: with the binaries and [`crate::io`], the
//! only code that touches the hardware.
//!
//! The package and the target triple pick the board (boards/build.rs):
//! thumbv7em-none-eabihf → mps2-an386 (Cortex-M4F), thumbv7m-none-eabi →
//! mps2-an385 (Cortex-M3), thumbv6m-none-eabi → microbit (nRF51, Cortex-M0),
//! all three under QEMU; the package `abtrack-nrf52840-dk` → the nRF52840-DK.
//!
//! Nothing here can panic (the release ELFs are checked for calls into
//! `core::panicking`, docs/safety.md): the emulated boards log through a
//! semihosting defmt transport of our own, because defmt-semihosting's
//! re-entrancy guards and `write_all` panic. The nRF52840-DK uses the
//! ecosystem's defmt-rtt and panic-probe, as a probe-rs user expects.
//!
//! The stack sits below the static data (flip-link, `.cargo/config.toml`),
//! so an overflow runs off the bottom of RAM and faults; the HardFault
//! handler moves the stack pointer back to the top of the stack before it
//! runs any code that pushes, so it can report even then.

use core::cell::Cell;
use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_rt::exception;

#[cfg(not(abtrack_board = "nrf52840-dk"))]
use core::cell::UnsafeCell;
#[cfg(not(abtrack_board = "nrf52840-dk"))]
use core::panic::PanicInfo;

/// The board this build runs on (set by boards/build.rs from the package and
/// target): the QEMU machine name for the emulated boards.
pub const BOARD: &str = env!("ABTRACK_BOARD");

/// The core of [`BOARD`].
pub const CORE: &str = env!("ABTRACK_CORE");

/// The opt-level this image was built at (set by boards/build.rs from
/// cargo's profile): `s` for the release profile.
pub const OPT_LEVEL: &str = env!("ABTRACK_OPT_LEVEL");

#[cfg(target_abi = "eabihf")]
use crate::number_types::cortex_m4f as core_types;

#[cfg(all(not(target_abi = "eabihf"), target_has_atomic = "32"))]
use crate::number_types::cortex_m3 as core_types;

// ARMv6-M (Cortex-M0), recognised on stable Rust by its lack of 32-bit
// atomics.
#[cfg(all(not(target_abi = "eabihf"), not(target_has_atomic = "32")))]
use crate::number_types::cortex_m0 as core_types;

/// The core's number type for the filters, schedules, bank and stand-alone
/// track tables: `f32` where the core has a hardware FPU (Cortex-M4F), the
/// fast fixed point ([`abtrack::Fixed32`]) on cores without one (Cortex-M3,
/// Cortex-M0), where every float operation would be a software library
/// call ([`crate::number_types`]).
pub type Native = core_types::Native;

/// The core's one type for every quantity, what the scan loop (its track
/// table among them), TCAS and the altitude tracker compute in: `f32` on
/// the Cortex-M4F, `Fixed32`'s wide format on the Cortex-M3, software
/// `f32` on the Cortex-M0 ([`crate::number_types`]).
pub type Wide = core_types::Wide;

// ---------------------------------------------------------------------------
// Semihosting: the log on the emulated boards, and the exit status
// ---------------------------------------------------------------------------

/// Arm semihosting calls (Arm "Semihosting for AArch32 and AArch64", 2.0:
/// `BKPT 0xAB`, operation in r0, parameter block in r1). QEMU services them
/// with `-semihosting-config enable=on` (scripts/qemu-run.sh); so does
/// probe-rs for the exit calls.
mod semihosting {
    const SYS_OPEN: u32 = 0x01;
    const SYS_WRITE: u32 = 0x05;
    const SYS_EXIT_EXTENDED: u32 = 0x20;
    /// `ADP_Stopped_ApplicationExit`: a normal exit, with the status given.
    const APPLICATION_EXIT: u32 = 0x2_0026;
    /// SYS_OPEN mode 4 = "w".
    const MODE_WRITE: u32 = 4;

    /// One semihosting call; its result (r0).
    fn call(operation: u32, parameters: &[u32]) -> u32 {
        let result: u32;
        // SAFETY: BKPT 0xAB is the semihosting trap: the debugger or QEMU
        // reads the parameter block (live for the call) and writes r0 only.
        // Without a debugger it is a fault, handled by HardFault. Not
        // `nomem`: the host reads the memory the block points to.
        unsafe {
            core::arch::asm!(
                "bkpt #0xab",
                inout("r0") operation => result,
                in("r1") parameters.as_ptr(),
                options(nostack, preserves_flags),
            );
        }
        result
    }

    /// Opens the host console for writing (the special file `:tt`); its
    /// handle, or None (the call returns −1 on failure).
    #[cfg_attr(abtrack_board = "nrf52840-dk", allow(dead_code))] // only the emulated boards log through semihosting
    pub fn open_console() -> Option<u32> {
        const NAME: &[u8; 4] = b":tt\0";
        let handle = call(SYS_OPEN, &[NAME.as_ptr() as u32, MODE_WRITE, 3]);
        (handle != u32::MAX).then_some(handle)
    }

    /// Writes `bytes` to `handle`; false if the host did not take them all.
    #[cfg_attr(abtrack_board = "nrf52840-dk", allow(dead_code))]
    pub fn write(handle: u32, bytes: &[u8]) -> bool {
        // SYS_WRITE returns the number of bytes *not* written.
        let not_written = call(
            SYS_WRITE,
            &[handle, bytes.as_ptr() as u32, bytes.len() as u32],
        );
        not_written == 0
    }

    /// Ends the run with `status` (QEMU's exit status).
    pub fn exit(status: u32) -> ! {
        call(SYS_EXIT_EXTENDED, &[APPLICATION_EXIT, status]);
        // Only reached if nothing serviced the call.
        loop {
            cortex_m::asm::wfi();
        }
    }
}

/// Ends the run: status 0 on success, 1 on failure. Under QEMU (or a probe-rs
/// session) through semihosting `SYS_EXIT_EXTENDED`; on a real board with no
/// debugger attached it sleeps instead (a semihosting call would fault).
pub fn exit(success: bool) -> ! {
    let status = if success { 0 } else { 1 };
    if debugger_can_serve_semihosting() {
        semihosting::exit(status)
    }
    loop {
        cortex_m::asm::wfi();
    }
}

/// QEMU always serves semihosting. On the nRF52840 (ARMv7-M) the core says
/// whether a debugger is attached: DHCSR.C_DEBUGEN (ARMv7-M ARM, C1.6.3).
fn debugger_can_serve_semihosting() -> bool {
    #[cfg(abtrack_board = "nrf52840-dk")]
    {
        const DHCSR: *const u32 = 0xE000_EDF0 as *const u32;
        // SAFETY: DHCSR is an architectural register of the core, readable
        // by privileged software on ARMv7-M; reading it has no effect.
        unsafe { DHCSR.read_volatile() & 1 != 0 }
    }
    #[cfg(not(abtrack_board = "nrf52840-dk"))]
    {
        true
    }
}

/// The defmt transport of the emulated boards: defmt's rzCOBS frames written
/// to the host console with semihosting `SYS_WRITE`, buffered so that a
/// frame costs a few traps rather than one per byte.
///
/// It cannot panic. The log is taken with interrupts off, so the only way to
/// re-enter it is a fault raised while a frame is being written; the fault
/// report then closes the broken frame with a delimiter (defmt-print skips
/// it) and starts its own.
#[cfg(not(abtrack_board = "nrf52840-dk"))]
mod log {
    use super::{semihosting, UnsafeCell};

    const BUFFER_LEN: usize = 128;

    struct State {
        /// A frame is being written.
        taken: bool,
        /// Interrupts were enabled before `acquire` (restore them after).
        interrupts_were_enabled: bool,
        encoder: defmt::Encoder,
        out: Output,
    }

    /// Encoded bytes on their way to the host console.
    struct Output {
        /// Opening the console has been tried (a flag beside the handle,
        /// so that the initial state is all-zero bytes: `.bss`).
        opened: bool,
        /// The result of opening it.
        console: Option<u32>,
        buffer: [u8; BUFFER_LEN],
        buffered: usize,
    }

    impl Output {
        fn flush(&mut self) {
            if !self.opened {
                self.opened = true;
                self.console = semihosting::open_console();
            }
            if let (Some(handle), Some(bytes)) = (self.console, self.buffer.get(..self.buffered)) {
                // A console that refuses bytes loses them: nothing else to do.
                let _ = semihosting::write(handle, bytes);
            }
            self.buffered = 0;
        }

        fn put(&mut self, bytes: &[u8]) {
            for &b in bytes {
                if self.buffered >= BUFFER_LEN {
                    self.flush();
                }
                if let Some(slot) = self.buffer.get_mut(self.buffered) {
                    *slot = b;
                    self.buffered += 1;
                }
            }
        }
    }

    /// The log's state; touched only with interrupts off (see `Sync`).
    struct Shared(UnsafeCell<State>);

    // SAFETY: every access goes through `state()`, called only with
    // interrupts off, on one core: in `acquire` after disabling them, and
    // between `acquire` and `release`. The one way in besides, a fault
    // handler logging while a frame is open, is handled in `acquire`.
    unsafe impl Sync for Shared {}

    static LOG: Shared = Shared(UnsafeCell::new(State {
        taken: false,
        interrupts_were_enabled: false,
        encoder: defmt::Encoder::new(),
        out: Output {
            opened: false,
            console: None,
            buffer: [0; BUFFER_LEN],
            buffered: 0,
        },
    }));

    /// SAFETY: interrupts must be off, and no other reference to the state
    /// in use (defmt's calls never nest; a fault handler's do not return).
    #[allow(clippy::mut_from_ref)]
    unsafe fn state() -> &'static mut State {
        unsafe { &mut *LOG.0.get() }
    }

    #[defmt::global_logger]
    struct Logger;

    // SAFETY: `acquire` disables interrupts before touching the state, and
    // `release` restores them; defmt calls write/flush/release only between
    // acquire and release.
    unsafe impl defmt::Logger for Logger {
        fn acquire() {
            // PRIMASK "active" = exceptions of configurable priority are taken.
            let enabled = cortex_m::register::primask::read().is_active();
            cortex_m::interrupt::disable();
            // SAFETY: interrupts are off.
            let s = unsafe { state() };
            if s.taken {
                // A fault handler logging over an open frame: end that frame
                // (defmt-print drops it as malformed) and start afresh.
                s.out.put(&[0]);
                s.encoder = defmt::Encoder::new();
            }
            s.taken = true;
            s.interrupts_were_enabled = enabled;
            s.encoder.start_frame(|b| s.out.put(b));
        }

        unsafe fn flush() {
            // SAFETY: between acquire and release: interrupts are off.
            unsafe { state() }.out.flush();
        }

        unsafe fn release() {
            // SAFETY: between acquire and release: interrupts are off.
            let s = unsafe { state() };
            s.encoder.end_frame(|b| s.out.put(b));
            s.out.flush();
            s.taken = false;
            if s.interrupts_were_enabled {
                // SAFETY: they were enabled when this frame began.
                unsafe { cortex_m::interrupt::enable() };
            }
        }

        unsafe fn write(bytes: &[u8]) {
            // SAFETY: between acquire and release: interrupts are off.
            let s = unsafe { state() };
            s.encoder.write(bytes, |b| s.out.put(b));
        }
    }
}

// ---------------------------------------------------------------------------
// Panics and faults
// ---------------------------------------------------------------------------

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

/// A panic is a bug (the firmware is written so none is reachable, and the
/// release ELFs are checked for panic calls): report where, and fail the run
/// rather than hang. (The nRF52840-DK uses panic-probe's handler.)
#[cfg(not(abtrack_board = "nrf52840-dk"))]
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

/// The HardFault vector. A naked function: when the stack has overflowed,
/// the stack pointer is below RAM and any push faults again, which in a
/// HardFault handler is a lockup (QEMU aborts with "Lockup", status 134).
/// So, before anything is pushed, it takes the stack pointer of the faulting
/// context (MSP or PSP, EXC_RETURN bit 2) as the argument and sets MSP to the
/// top of the stack (`_stack_start`); [`hard_fault`] then runs on a valid
/// stack. Nothing returns, so what was on the stack is not needed.
///
/// Replaces cortex-m-rt's `#[exception] HardFault` trampoline (which would
/// call the handler on the faulting stack); the vector table refers to the
/// symbol `HardFault`.
#[unsafe(naked)]
#[unsafe(no_mangle)]
unsafe extern "C" fn HardFault() -> ! {
    core::arch::naked_asm!(
        "mov r0, lr",
        "movs r1, #4",
        "tst r0, r1",
        "bne 1f",
        "mrs r0, msp",
        "b 2f",
        "1:",
        "mrs r0, psp",
        "2:",
        "ldr r1, 3f",
        "mov sp, r1",
        "bl {report}",
        // Not reached: `hard_fault` never returns.
        "udf #0",
        ".p2align 2",
        "3:",
        ".word {stack_top}",
        report = sym hard_fault,
        stack_top = sym _stack_start,
    )
}

/// How much stack the HardFault report is given, painted before it runs so
/// that its own high-water mark can be printed.
const FAULT_STACK_PAINTED: usize = 2048;

/// The HardFault report, on a fresh stack (see [`HardFault`]). `frame` is
/// the faulting context's stack pointer: the exception frame is there unless
/// the stack had overflowed, in which case it is below the stack's bottom.
extern "C" fn hard_fault(frame: u32) -> ! {
    let (bottom, top) = stack_bounds();
    // Paint the stack below this frame, for the report's own high-water mark.
    let sp = cortex_m::register::msp::read() as usize;
    let painted_from = sp.saturating_sub(FAULT_STACK_PAINTED).max(bottom);
    paint(painted_from, sp.saturating_sub(64) & !3);
    if first_failure() {
        report_fault(frame as usize, bottom, top);
        let used = top.saturating_sub(first_unpainted_word(painted_from, top));
        defmt::error!(
            "hard fault handler: {=usize} bytes of stack used (high-water mark, on the reset stack)",
            used
        );
    }
    exit(false)
}

/// The report proper, out of line so that its frame is measured.
#[inline(never)]
fn report_fault(frame: usize, bottom: usize, top: usize) {
    const FRAME_LEN: usize = 32;
    if frame < bottom || frame > top {
        defmt::error!(
            "hard fault: stack overflow (stack pointer {=usize:#010x} is outside the stack {=usize:#010x}..{=usize:#010x}, which lies below the statics)",
            frame,
            bottom,
            top
        );
    } else if frame.saturating_add(FRAME_LEN) <= top && frame.is_multiple_of(4) {
        // SAFETY: the exception frame's eight words lie within the stack
        // (checked above); the sixth is the stacked PC (ARMv7-M ARM B1.5.6).
        let pc = unsafe { ((frame + 24) as *const u32).read_volatile() };
        defmt::error!(
            "hard fault at pc={=u32:#010x} (stack pointer {=usize:#010x})",
            pc,
            frame
        );
    } else {
        defmt::error!(
            "hard fault (stack pointer {=usize:#010x}, no readable exception frame)",
            frame
        );
    }
    if let Some(hook) = cortex_m::interrupt::free(|cs| FAULT_HOOK.borrow(cs).get()) {
        hook();
    }
}

/// A binary's own check to run after a hard fault has been reported (the
/// stack-overflow image checks its statics); called once, then the run
/// fails.
static FAULT_HOOK: Installed<fn()> = cortex_m::interrupt::Mutex::new(Cell::new(None));

/// A function a binary installs into board.rs (read in handlers).
type Installed<F> = cortex_m::interrupt::Mutex<Cell<Option<F>>>;

/// Installs the hook [`hard_fault`] calls after its report.
pub fn set_fault_hook(hook: fn()) {
    cortex_m::interrupt::free(|cs| FAULT_HOOK.borrow(cs).set(Some(hook)));
}

/// The device-interrupt handler a binary installed, if any. Without a device
/// crate, cortex-m-rt sends every device interrupt to `DefaultHandler`;
/// binaries that enable one route it here. It returns false for an
/// interrupt it does not handle.
static INTERRUPT_HANDLER: Installed<InterruptHandler> =
    cortex_m::interrupt::Mutex::new(Cell::new(None));

/// Takes the IRQ number; true if it handled the interrupt.
pub type InterruptHandler = fn(i16) -> bool;

/// Installs the handler of the binary's device interrupts (`irqn` = IRQ
/// number, exception number − 16). Install it before unmasking them.
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

// ---------------------------------------------------------------------------
// Stack high-water mark
// ---------------------------------------------------------------------------

// Static RAM is small (the filters live on the stack), so the stack is what
// decides whether a build fits a board's RAM. The binaries paint the free
// stack first thing and report how much of it was overwritten at the end.

/// What unused stack words hold.
const STACK_PAINT: u32 = 0x5ac4_5ac4;

extern "C" {
    /// Lowest stack address: the bottom of RAM (flip-link sets it; without
    /// flip-link cortex-m-rt's link.x puts it at the end of the statics).
    static _stack_end: u32;
    /// Initial stack pointer: just below the statics (flip-link), or the end
    /// of RAM (cortex-m-rt's default).
    static _stack_start: u32;
}

/// (lowest stack address, initial stack pointer), word-aligned.
fn stack_bounds() -> (usize, usize) {
    // Only the addresses of the linker symbols are taken (no read): safe.
    let bottom = core::ptr::addr_of!(_stack_end) as usize;
    let top = core::ptr::addr_of!(_stack_start) as usize;
    ((bottom + 3) & !3, top & !3)
}

/// Fills the words of `[from, to)` with the paint.
fn paint(from: usize, to: usize) {
    let mut p = from;
    while p < to {
        // SAFETY: callers pass stack memory below the live frames.
        unsafe { (p as *mut u32).write_volatile(STACK_PAINT) };
        p += 4;
    }
}

/// The lowest word of `[from, to)` that no longer holds the paint.
fn first_unpainted_word(from: usize, to: usize) -> usize {
    let mut p = from;
    // SAFETY: reads of RAM words between the stack's bottom and its top.
    while p < to && unsafe { (p as *const u32).read_volatile() } == STACK_PAINT {
        p += 4;
    }
    p
}

/// Fills the unused stack (below the current frame, with a margin) with a
/// pattern. Call once, first thing in `main`.
pub fn paint_stack() {
    let (bottom, _) = stack_bounds();
    let sp = cortex_m::register::msp::read() as usize;
    // [bottom, sp − 256) is RAM below the live stack frames: nothing uses it.
    paint(bottom, sp.saturating_sub(256) & !3);
}

/// (bytes of stack ever used since `paint_stack`, bytes available).
pub fn stack_usage() -> (u32, u32) {
    let (bottom, top) = stack_bounds();
    let used = top - first_unpainted_word(bottom, top);
    (used as u32, (top - bottom) as u32)
}

/// Logs the stack high-water mark.
pub fn report_stack() {
    let (used, available) = stack_usage();
    defmt::println!(
        "stack: {=u32} of {=u32} bytes used (high-water mark)",
        used,
        available
    );
}
