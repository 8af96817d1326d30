//! The firmware's number types per core, declared once: the board support
//! takes its core's (`board::Native`, `board::Wide`), and the host model of
//! the fault-injection tests (host-tests/tests/it/firmware/fault_injection.rs)
//! the same, so the two cannot drift apart. Each core has two:
//!
//! * `Native`: the filters, schedules, bank and stand-alone track tables
//!   (the self-test's filters, the benchmark's filter and scan rows).
//! * `Wide`: one type for every quantity, what the scan loop (its track
//!   table among them), TCAS and the altitude tracker compute in (a
//!   [`abtrack::Numeric`] that is its own wide format). The choice per core:
//!   docs/firmware-and-boards.md, "Number types".

/// The Cortex-M4F (a hardware FPU; the hard-float ABI,
/// thumbv7em-none-eabihf): `f32` throughout.
pub mod cortex_m4f {
    /// Filters, schedules, bank, stand-alone track tables.
    pub type Native = f32;
    /// Scan loop, TCAS, altitude tracker.
    pub type Wide = f32;
}

/// The Cortex-M3 (no FPU, where every float operation would be a software
/// library call; a 32×32→64 multiply, a leading-zero count and a divide in
/// hardware): the fast fixed point.
pub mod cortex_m3 {
    /// [`abtrack::Fixed32`], a 32-bit format per quantity.
    pub type Native = abtrack::Fixed32;
    /// [`abtrack::Fixed32`]'s wide format ([`abtrack::Numeric::Wide`]),
    /// [`abtrack::ScaledScalar`].
    pub type Wide = abtrack::ScaledScalar;
}

/// The Cortex-M0 (ARMv6-M: no FPU, and none of the instructions the
/// scaled format is built on, a 32×32→64 multiply, a leading-zero count, a
/// divide) with the micro:bit's 16 KiB of RAM.
pub mod cortex_m0 {
    /// [`abtrack::Fixed32`], a 32-bit format per quantity.
    pub type Native = abtrack::Fixed32;
    /// `f32` in software: half the scaled format's bytes, where RAM sets the
    /// micro:bit's intruder count.
    pub type Wide = f32;
}
