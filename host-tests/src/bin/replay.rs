//! `replay`: runs the library's filters, in f64, f32 or Q32.32 fixed point,
//! over a CSV recording, so that gains can be tuned on recorded data before
//! flashing. See `replay --help`, `abtrack_host_tests::replay` and
//! `results/README-replay.md`.
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
//! 2: arguments).

use std::io::{self, BufReader, Read, Write};
use std::process::ExitCode;

use abtrack_host_tests::cli::{parse_replay_args, replay_usage, Command, Input};
use abtrack_host_tests::replay::replay_reader;

fn main() -> ExitCode {
    let (config, input) = match parse_replay_args(std::env::args().skip(1)) {
        Ok(Command::Help) => {
            print!("{}", replay_usage());
            return ExitCode::SUCCESS;
        }
        Ok(Command::Replay { config, input }) => (config, input),
        Err(e) => {
            eprintln!("replay: {e}\n(replay --help lists the options)");
            return ExitCode::from(2);
        }
    };
    let (name, result) = match &input {
        Input::Stdin => {
            let mut text = String::new();
            let result = match io::stdin().lock().read_to_string(&mut text) {
                Ok(_) => replay_reader(&config, text.as_bytes()),
                Err(e) => {
                    eprintln!("replay: <stdin>: cannot read: {e}");
                    return ExitCode::FAILURE;
                }
            };
            ("<stdin>".to_string(), result)
        }
        Input::Path(path) => match std::fs::File::open(path) {
            Ok(f) => (
                path.display().to_string(),
                replay_reader(&config, BufReader::new(f)),
            ),
            Err(e) => {
                eprintln!("replay: {}: {e}", path.display());
                return ExitCode::FAILURE;
            }
        },
    };
    let output = match result {
        Ok(o) => o,
        Err(e) => {
            eprintln!("replay: {name}: {e}");
            return ExitCode::FAILURE;
        }
    };
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
