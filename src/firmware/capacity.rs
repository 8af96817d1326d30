//! The demo's capacities per board, declared once: the firmware (src/main.rs)
//! takes its board's, and the host model of the fault-injection tests
//! (host-tests/tests/fault_injection.rs) the same. RAM per table:
//! docs/track-table.md.

/// The mps2 boards (4 MiB of RAM): issue 9's 256 tracks and 256
/// measurements per scan.
pub mod mps2 {
    pub const TRACKS: usize = 256;
    pub const MEASUREMENTS_PER_SCAN: usize = 256;
    /// heapless queues hold one item less than their length.
    pub const QUEUE_LEN: usize = 128;
}

/// The micro:bit (16 KiB of RAM): the scenario has at most 20 measurements
/// per scan (2 targets + Poisson clutter).
pub mod microbit {
    pub const TRACKS: usize = 8;
    pub const MEASUREMENTS_PER_SCAN: usize = 24;
    pub const QUEUE_LEN: usize = 32;
}
