//! The host tools (replay, simulate, frames, bench_report, firmware-check,
//! the Monte Carlo runner) as a user runs them and on their library side
//! (scenarios, noise, metrics, the reference Kalman filters, tables).

mod bench_report;
mod firmware_check;
mod frames;
mod kalman;
mod metrics;
mod monte_carlo;
mod noise;
mod replay;
mod replay_filters;
mod replay_tracker;
mod scenario;
mod shell;
mod simulate;
mod tables;

use std::path::PathBuf;
use std::process::Command as Process;

/// The replay binary, as a user runs it.
fn replay_binary() -> Process {
    Process::new(env!("CARGO_BIN_EXE_replay"))
}

/// Writes `contents` to a file named `name` (unique among the tools'
/// tests) in cargo's temporary directory for this process.
fn temp_file(name: &str, contents: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("replay-{}-{name}", std::process::id()));
    std::fs::write(&path, contents).unwrap();
    path
}
