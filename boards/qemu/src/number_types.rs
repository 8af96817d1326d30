//! The firmware's number types per core, declared once: the board support
//! takes its core's (`board::Native`, `board::TableScalar`), and the host
//! model of the fault-injection tests (host-tests/tests/it/firmware/fault_injection.rs)
//! the same, so the two cannot drift apart.

/// A core with a hardware FPU (the hard-float ABI, thumbv7em-none-eabihf:
/// Cortex-M4F): `f32` throughout.
pub mod with_fpu {
    /// The filters, the gain schedules and the bank.
    pub type Native = f32;
    /// The code written for `Scalar` (scan loop, track table, TCAS, altitude
    /// tracker, demo).
    pub type TableScalar = f32;
}

/// A core without one (Cortex-M3, Cortex-M0), where every float operation
/// would be a software library call: the fast fixed point.
pub mod without_fpu {
    /// [`abtrack::Fixed32`]: a 32-bit format per quantity.
    pub type Native = abtrack::Fixed32;
    /// Its wide format [`abtrack::ScaledScalar`] (31-bit mantissa and
    /// exponent, 32-bit integer code), whose range holds the TCAS logic's
    /// taus and products in one type.
    pub type TableScalar = abtrack::ScaledScalar;
}
