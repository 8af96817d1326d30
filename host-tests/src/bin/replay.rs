//! `replay`: runs the library's filters, in f64, f32, the Cortex-M3/M0 fast fixed point or Q32.32,
//! over a CSV recording, so that gains can be tuned on recorded data before
//! flashing. See `replay --help` and `docs/host-tools.md`.
//!
//! From the repository root (the root `.cargo/config.toml` selects a thumb
//! target, and cargo reads configuration from the current directory, not from
//! the manifest's, so the host target must be named):
//!
//! ```text
//! cargo run --release --manifest-path host-tests/Cargo.toml --target host-tuple \
//!     --bin replay -- --filter ab --schedule least-squares --numeric f64 data.csv
//! ```
//!
//! or, inside `host-tests/`, `cargo run --release --bin replay -- ...`.
//!
//! Gaps and jitter never stop a run: the rows where the estimate restarted
//! (more than 20 s after the last report used, or a two-point start that
//! left the velocity envelope) or that were skipped (less than 0.05 s after
//! it) are marked in the `event` column and listed on stderr.
//!
//! The output is built in memory and written only when the whole file has run:
//! on any error stdout stays empty, the message (naming the line and column)
//! goes to stderr and the exit status is non-zero (1: input or refused row,
//! 2: arguments). A closed stdout (`replay … | head`) ends it quietly with
//! status 0.

use std::io::{self, Read};
use std::process::ExitCode;

use abtrack_host_tests::cli::{Command, Input, ReplayArgs};
use abtrack_host_tests::output::write_stdout;
use abtrack_host_tests::replay::replay_events;
use abtrack_host_tests::replay_tracker::replay_tracker_reader;
use clap::Parser;

/// The input's bytes and its name for messages.
fn read_input(input: &Input) -> Result<(String, Vec<u8>), String> {
    match input {
        Input::Stdin => {
            let mut bytes = Vec::new();
            io::stdin()
                .lock()
                .read_to_end(&mut bytes)
                .map_err(|e| format!("<stdin>: cannot read: {e}"))?;
            Ok(("<stdin>".to_string(), bytes))
        }
        Input::Path(path) => std::fs::read(path)
            .map(|bytes| (path.display().to_string(), bytes))
            .map_err(|e| format!("{}: {e}", path.display())),
    }
}

fn main() -> ExitCode {
    let command = ReplayArgs::parse()
        .into_command()
        .unwrap_or_else(|e| e.exit());
    let input = match &command {
        Command::Replay { input, .. } | Command::Tracker { input, .. } => input,
    };
    let (name, bytes) = match read_input(input) {
        Ok(x) => x,
        Err(e) => {
            eprintln!("replay: {e}");
            return ExitCode::FAILURE;
        }
    };
    let output = match &command {
        Command::Replay { config, .. } => replay_events(config, bytes.as_slice()).map(|run| {
            eprint!("{}", run.events);
            run.csv
        }),
        Command::Tracker {
            options, verbose, ..
        } => replay_tracker_reader(options, bytes.as_slice()).map(|run| {
            if *verbose {
                eprint!("{}", run.scan_log);
            }
            eprint!("{}", run.report());
            run.csv
        }),
    };
    match output {
        Ok(csv) => write_stdout("replay", csv.as_bytes()),
        Err(e) => {
            eprintln!("replay: {name}: {e}");
            ExitCode::FAILURE
        }
    }
}
