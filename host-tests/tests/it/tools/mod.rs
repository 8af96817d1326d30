//! The host tools (replay, simulate, frames, bench_report, firmware-check,
//! the Monte Carlo runner) as a user runs them and on their library side.

mod bench_report;
mod firmware_check;
mod frames;
mod monte_carlo;
mod replay;
mod replay_filters;
mod replay_tracker;
mod shell;
mod simulate;
