//! Soak firmware: a simulated operational day on the emulated board, 86,400
//! scans at 1 Hz of 45 intruders (detection probability 0.9) and clutter,
//! through the demo's scan loop and configuration, timed in instructions
//! under `-icount shift=0`.
//!
//! The sky is generated on the board (`synth::soak_scan`: each scan from its
//! own seed, in f64, bit for bit what the host generates), encoded as
//! numbered wire frames and pushed byte by byte through the demo's receive
//! side (`scan::Intake`: decoder and queue), then scanned
//! (`ScanLoop::on_tick`). Every hour of the day it logs the instructions per
//! scan (receive and scan, mean and maximum), the confirmed tracks, the
//! intruders tracked within the accuracy budget (100 m), the ghosts
//! (confirmed tracks more than 200 m from every intruder), the track breaks
//! and the RMS error; at the end, every confirmed track, which
//! host-tests/tests/it/firmware/soak.rs compares with the same day run in f64 on the
//! host. `ABTRACK_SOAK_SCANS` (at build time) shortens the day.
//!
//! ```text
//! scripts/soak.sh [m4f|m3] [scans]
//! ```
#![no_std]
#![no_main]

use abtrack_firmware::board;

/// The micro:bit's 16 KiB of RAM cannot hold the soak's 64 tracks.
#[cfg(abtrack_board = "microbit")]
#[cortex_m_rt::entry]
fn main() -> ! {
    defmt::error!(
        "the soak needs 64 tracks, more than the {=str}'s RAM holds: run it on mps2-an385 or mps2-an386 (scripts/soak.sh)",
        board::BOARD
    );
    board::exit(false)
}

#[cfg(not(abtrack_board = "microbit"))]
mod day;
#[cfg(not(abtrack_board = "microbit"))]
use abtrack_firmware::{demo_config, icount, synth};
