//! The firmware's number type per core, declared once: the board support
//! takes its core's (`board::Native`), and the host model of the
//! fault-injection tests (host-tests/tests/it/firmware/fault_injection.rs)
//! the same, so the two cannot drift apart.

/// A core with a hardware FPU (the hard-float ABI, thumbv7em-none-eabihf:
/// Cortex-M4F): `f32` throughout.
pub mod with_fpu {
    /// Every component: filters, schedules, bank, track table, scan loop,
    /// TCAS, altitude tracker.
    pub type Native = f32;
}

/// A core without one (Cortex-M3, Cortex-M0), where every float operation
/// would be a software library call: the fast fixed point.
pub mod without_fpu {
    /// [`abtrack::Fixed32`], a 32-bit format per quantity, for every
    /// component; the scan loop, TCAS and the altitude tracker run in its
    /// wide format ([`abtrack::Numeric::Wide`]).
    pub type Native = abtrack::Fixed32;
}
