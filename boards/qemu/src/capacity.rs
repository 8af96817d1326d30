//! The demo's capacities per board, declared once: the demo firmware
//! (boards/qemu/src/main.rs) takes its board's, and the host model of the fault-injection tests
//! (host-tests/tests/it/firmware/fault_injection.rs) the same. RAM per table:
//! docs/track-table.md.

/// The mps2 boards (4 MiB of RAM): 256 tracks and 256 measurements per
/// scan.
pub mod mps2 {
    pub const TRACKS: usize = 256;
    pub const MEASUREMENTS_PER_SCAN: usize = 256;
    /// The measurement queue holds `QUEUE_LEN` measurements.
    pub const QUEUE_LEN: usize = 128;
}

/// The micro:bit (16 KiB of RAM): the TCAS scenario has at most 6 replies
/// per scan (4 intruders, false replies), and a track there costs a
/// range–azimuth filter and an intruder's TCAS state (range and altitude
/// trackers, threat state) in software `f32` (`board::Wide`): 30 tracks
/// and 10 replies per scan leave the stack its 25 % margin
/// (scripts/stack.sh m0; the RAM budget is in docs/tcas.md).
pub mod microbit {
    pub const TRACKS: usize = 30;
    pub const MEASUREMENTS_PER_SCAN: usize = 10;
    pub const QUEUE_LEN: usize = 32;
}
