//! `replay`: runs the library's filters, in f64, f32 or Q32.32 fixed point,
//! over a CSV recording, so that gains can be tuned on recorded data before
//! flashing. See `replay --help`, `abtrack_host_tests::replay` and
//! `docs/replay.md`.
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
//! The output is built in memory and written only when the whole file has run:
//! on any error stdout stays empty, the message (naming the line and column)
//! goes to stderr and the exit status is non-zero (1: input or refused row,
//! 2: arguments). `--tracker --verbose` prints one summary line per scan to
//! stderr after a successful run.

use std::io::{self, BufRead, BufReader, Read, Write};
use std::process::ExitCode;

use abtrack_host_tests::cli::{parse_replay_args, replay_usage, Command, Input};
use abtrack_host_tests::replay::replay_reader;
use abtrack_host_tests::replay_tracker::replay_tracker_reader;

/// Opens `input` and hands it to `run`: the input's name and `run`'s result,
/// or the exit code after reporting why it could not be opened.
fn with_input<T>(
    input: &Input,
    run: impl FnOnce(&mut dyn BufRead) -> T,
) -> Result<(String, T), ExitCode> {
    match input {
        Input::Stdin => {
            let mut text = String::new();
            match io::stdin().lock().read_to_string(&mut text) {
                Ok(_) => Ok(("<stdin>".to_string(), run(&mut text.as_bytes()))),
                Err(e) => {
                    eprintln!("replay: <stdin>: cannot read: {e}");
                    Err(ExitCode::FAILURE)
                }
            }
        }
        Input::Path(path) => match std::fs::File::open(path) {
            Ok(f) => Ok((path.display().to_string(), run(&mut BufReader::new(f)))),
            Err(e) => {
                eprintln!("replay: {}: {e}", path.display());
                Err(ExitCode::FAILURE)
            }
        },
    }
}

fn main() -> ExitCode {
    let command = match parse_replay_args(std::env::args().skip(1)) {
        Ok(Command::Help) => {
            print!("{}", replay_usage());
            return ExitCode::SUCCESS;
        }
        Ok(c) => c,
        Err(e) => {
            eprintln!("replay: {e}\n(replay --help lists the options)");
            return ExitCode::from(2);
        }
    };
    let outcome = match &command {
        Command::Replay { config, input } => with_input(input, |r| {
            replay_reader(config, r).map(|csv| (csv, String::new()))
        }),
        Command::Tracker { options, input, .. } => with_input(input, |r| {
            replay_tracker_reader(options, r).map(|o| (o.csv, o.scan_log))
        }),
        Command::Help => return ExitCode::SUCCESS,
    };
    let (name, result) = match outcome {
        Ok(o) => o,
        Err(code) => return code,
    };
    let (output, scan_log) = match result {
        Ok(o) => o,
        Err(e) => {
            eprintln!("replay: {name}: {e}");
            return ExitCode::FAILURE;
        }
    };
    if matches!(command, Command::Tracker { verbose: true, .. }) {
        eprint!("{scan_log}");
    }
    let mut stdout = io::stdout().lock();
    if let Err(e) = stdout
        .write_all(output.as_bytes())
        .and_then(|_| stdout.flush())
    {
        eprintln!("replay: cannot write the output: {e}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
