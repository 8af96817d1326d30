//! `frames`: writes measurement wire frames for the demo firmware's UART, and
//! decodes the report frames it sends back (`frames --help`). The frame
//! format is documented in `abtrack::wire`.

use abtrack::wire::ScanCounts;
use abtrack_host_tests::csv_input::AngleUnit;
use abtrack_host_tests::frames::{self, Fault, Faults};
use abtrack_host_tests::scenario::SCENARIO_NAMES;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// abtrack wire frames for the demo firmware's UART (format: abtrack::wire).
#[derive(Debug, Parser)]
#[command(name = "frames", arg_required_else_help = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Write one measurement frame per measurement, in time order, and print
    /// what was written.
    #[command(
        long_about = "Write one measurement frame per measurement, in time order \
        (frames numbered from 0 in the header's sequence number, then an end-of-input \
        frame), and print what was written on stdout: frames, corrupted frames, garbage \
        bytes, the largest number of measurements at one time."
    )]
    Encode(EncodeArgs),
    /// Read a byte stream (e.g. the demo's UART output) and print a summary
    /// of the frames in it: scans, tracks, advisories, health counters.
    Decode(DecodeArgs),
    /// Print the frame format (every layout and counter list, from the code's
    /// own tables) as Markdown; docs/firmware-runtime.md includes it.
    Layout,
}

/// One source of measurements: `--scenario`, `--csv` or `--fault`.
#[derive(Debug, Args)]
#[group(required = true, multiple = false)]
struct Source {
    /// tcas-demo (the demo's default input: four TCAS intruders, Mode S and
    /// Mode C replies, false replies) or a simulate scenario.
    #[arg(long, value_name = "NAME", value_parser = scenario_name())]
    scenario: Option<String>,
    /// Measurements from a CSV file, columns matched by name (others
    /// ignored): t,x,y (s, m) or t,range,azimuth (s, m, clockwise from +y),
    /// either with an optional alt (ft; empty = not reported); rows sharing
    /// t are one scan.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// The demo's input (tcas-demo, seed 1) with one fault of the
    /// fault-injection tests (docs/firmware-runtime.md); flood adds 10 x
    /// --capacity extra measurements at t = 30 s.
    #[arg(long, value_name = "KIND", value_parser = fault_kind())]
    fault: Option<Fault>,
}

#[derive(Debug, Args)]
struct EncodeArgs {
    #[command(flatten)]
    source: Source,
    /// The scenario's seed.
    #[arg(long, value_name = "N", default_value_t = 0)]
    seed: u64,
    /// The unit of the CSV file's azimuth column (default: rad); never
    /// guessed.
    #[arg(long, value_enum, value_name = "UNIT", conflicts_with_all = ["scenario", "fault"])]
    azimuth_unit: Option<AngleUnit>,
    /// Sensor id in the frames.
    #[arg(long, value_name = "ID", default_value_t = 1)]
    sensor: u8,
    /// Flip one payload bit of every K-th frame (a CRC error).
    #[arg(long, value_name = "K")]
    corrupt_every: Option<usize>,
    /// Put 1-16 random bytes before every K-th frame.
    #[arg(long, value_name = "K")]
    garbage_every: Option<usize>,
    /// Seed of the injected faults.
    #[arg(long, value_name = "N", default_value_t = 0)]
    fault_seed: u64,
    /// The track capacity a --fault flood overwhelms.
    #[arg(long, value_name = "M", default_value_t = 64)]
    capacity: usize,
    /// The scans a --fault clutter-storm lasts, from the first (default:
    /// every scan of the input).
    #[arg(long, value_name = "N", default_value_t = frames::TCAS_DEMO_SCANS)]
    storm_scans: usize,
    /// Output file.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

#[derive(Debug, Args)]
struct DecodeArgs {
    /// The byte stream.
    file: PathBuf,
    /// Print every message, one per line, instead of the summary.
    #[arg(long, conflicts_with = "scans_csv")]
    messages: bool,
    /// Print the scan summaries as CSV (time_s, interval_ms, advisory, then
    /// every count) instead of the summary.
    #[arg(long)]
    scans_csv: bool,
    /// Exit status 1 if the stream is not clean frames only (a CRC error, a
    /// skipped or left-over byte, a gap in the sequence numbers): a
    /// firmware's report output must be.
    #[arg(long)]
    check: bool,
}

/// The scenario names: the demo's and the simulate tool's.
fn scenario_name() -> PossibleValuesParser {
    PossibleValuesParser::new(
        std::iter::once(frames::TCAS_DEMO).chain(SCENARIO_NAMES.iter().copied()),
    )
}

/// The fault names, parsed into a [`Fault`].
fn fault_kind() -> impl TypedValueParser<Value = Fault> {
    PossibleValuesParser::new(Fault::ALL.map(Fault::name))
        .map(|name| Fault::from_name(&name).expect("a possible value is a fault name"))
}

fn run(command: Command) -> Result<(), String> {
    match command {
        Command::Layout => print!("{}", frames::layout_markdown()),
        Command::Encode(EncodeArgs {
            source,
            seed,
            azimuth_unit,
            sensor,
            corrupt_every,
            garbage_every,
            fault_seed,
            capacity,
            storm_scans,
            out,
        }) => {
            let faults = Faults {
                corrupt_every,
                garbage_every,
                seed: fault_seed,
            };
            let (encoded, what) = match source {
                Source {
                    fault: Some(fault), ..
                } => {
                    let stream = frames::fault_stream(fault, capacity, storm_scans, faults.seed)?;
                    let encoded = frames::Encoded {
                        frames: stream.frames,
                        corrupted: stream.damaged,
                        garbage_bytes: stream.garbage_bytes,
                        max_per_scan: stream.scans.iter().map(|s| s.2).max().unwrap_or(0),
                        bytes: stream.bytes,
                    };
                    (
                        encoded,
                        format!(
                            "{} seed {} with fault {}",
                            frames::TCAS_DEMO,
                            frames::FAULT_INPUT_SEED,
                            fault.name()
                        ),
                    )
                }
                Source {
                    scenario: Some(name),
                    ..
                } => (
                    frames::encode(&frames::scenario_reports(&name, seed, sensor)?, faults),
                    format!("{name} seed {seed}"),
                ),
                Source {
                    csv: Some(path), ..
                } => {
                    let file = std::fs::File::open(&path)
                        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
                    let reports =
                        frames::reports_from_csv(file, sensor, azimuth_unit.unwrap_or_default())
                            .map_err(|e| format!("{}: {e}", path.display()))?;
                    (frames::encode(&reports, faults), path.display().to_string())
                }
                Source { .. } => unreachable!("clap requires one source"),
            };
            if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
                std::fs::create_dir_all(dir)
                    .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
            }
            std::fs::write(&out, &encoded.bytes)
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            println!(
                "{what}: {} frames ({} damaged), {} garbage bytes, {} bytes, at most {} measurements at one time -> {}",
                encoded.frames,
                encoded.corrupted,
                encoded.garbage_bytes,
                encoded.bytes.len(),
                encoded.max_per_scan,
                out.display()
            );
        }
        Command::Decode(DecodeArgs {
            file,
            messages,
            scans_csv,
            check,
        }) => {
            let bytes =
                std::fs::read(&file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
            let text = if messages {
                frames::decode_all(&bytes)
                    .0
                    .iter()
                    .map(|m| frames::message_line(m) + "\n")
                    .collect()
            } else if scans_csv {
                scans_table(&frames::summarise(&bytes).scans)
            } else {
                frames::summarise(&bytes).to_text()
            };
            // A closed pipe (`| head`) ends the output quietly.
            let mut out = std::io::stdout().lock();
            let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
            if check {
                let (messages, stats) = frames::decode_all(&bytes);
                let in_frames: usize = messages.iter().map(|m| m.buffer_len()).sum();
                if stats.crc_errors > 0
                    || stats.bytes_skipped > 0
                    || stats.frames_lost > 0
                    || stats.out_of_sequence > 0
                    || in_frames != bytes.len()
                {
                    return Err(format!(
                        "{}: not clean frames: {} CRC errors, {} bytes skipped, {} frames lost, {} out of sequence, {} of {} bytes in frames",
                        file.display(),
                        stats.crc_errors,
                        stats.bytes_skipped,
                        stats.frames_lost,
                        stats.out_of_sequence,
                        in_frames,
                        bytes.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The scan summaries as CSV: one column per count, named as in
/// [`ScanCounts::NAMES`].
fn scans_table(scans: &[abtrack::wire::ScanSummary]) -> String {
    let mut out = format!(
        "time_s,interval_ms,advisory,{}\n",
        ScanCounts::NAMES.join(",")
    );
    for s in scans {
        let counts: Vec<String> = s.counts.values().iter().map(u16::to_string).collect();
        out += &format!(
            "{},{},{},{}\n",
            s.time_ms as f64 / 1000.0,
            s.interval_ms,
            s.highest_advisory.name(),
            counts.join(",")
        );
    }
    out
}

fn main() -> ExitCode {
    // Usage errors exit with status 2 (clap), failures with 1.
    match run(Cli::parse().command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("frames: error: {e}");
            ExitCode::from(1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    fn parse(args: &[&str]) -> Result<Command, clap::Error> {
        Cli::try_parse_from(std::iter::once("frames").chain(args.iter().copied()))
            .map(|c| c.command)
    }

    #[test]
    fn command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn parses_encode_and_decode() {
        let Ok(Command::Encode(e)) = parse(&[
            "encode",
            "--scenario",
            "two-crossing",
            "--seed",
            "3",
            "--corrupt-every",
            "40",
            "--out",
            "x.bin",
        ]) else {
            panic!("encode not parsed")
        };
        assert_eq!(e.source.scenario.as_deref(), Some("two-crossing"));
        assert_eq!((e.seed, e.sensor, e.capacity, e.fault_seed), (3, 1, 64, 0));
        assert_eq!((e.corrupt_every, e.garbage_every), (Some(40), None));
        assert_eq!(e.out, PathBuf::from("x.bin"));
        let Ok(Command::Encode(e)) = parse(&[
            "encode",
            "--csv",
            "m.csv",
            "--azimuth-unit",
            "deg",
            "--out",
            "x.bin",
        ]) else {
            panic!("encode --csv not parsed")
        };
        assert_eq!(e.source.csv, Some(PathBuf::from("m.csv")));
        assert_eq!(e.azimuth_unit, Some(AngleUnit::Degrees));
        let Ok(Command::Encode(e)) = parse(&[
            "encode",
            "--fault",
            "flood",
            "--capacity",
            "24",
            "--fault-seed",
            "5",
            "--out",
            "x.bin",
        ]) else {
            panic!("encode --fault not parsed")
        };
        assert_eq!(e.source.fault, Some(Fault::Flood));
        assert_eq!((e.capacity, e.fault_seed), (24, 5));
        assert_eq!(e.storm_scans, frames::TCAS_DEMO_SCANS);
        let Ok(Command::Encode(e)) = parse(&[
            "encode",
            "--fault",
            "clutter-storm",
            "--storm-scans",
            "30",
            "--out",
            "x.bin",
        ]) else {
            panic!("encode --storm-scans not parsed")
        };
        assert_eq!(e.storm_scans, 30);
        let Ok(Command::Decode(d)) = parse(&["decode", "--check", "r.bin", "--messages"]) else {
            panic!("decode not parsed")
        };
        assert_eq!(d.file, PathBuf::from("r.bin"));
        assert!(d.messages && d.check && !d.scans_csv);
        assert!(matches!(parse(&["layout"]), Ok(Command::Layout)));
    }

    #[test]
    fn refuses_bad_command_lines() {
        for args in [
            &[][..],
            &["encode", "--out", "x"],
            &["encode", "--scenario", "nope", "--out", "x"],
            &["encode", "--scenario", "two-crossing"],
            &[
                "encode",
                "--scenario",
                "two-crossing",
                "--sensor",
                "300",
                "--out",
                "x",
            ],
            &[
                "encode",
                "--scenario",
                "two-crossing",
                "--azimuth-unit",
                "deg",
                "--out",
                "x",
            ],
            &["decode"],
            &["decode", "r.bin", "--messages", "--scans-csv"],
            &["frobnicate"],
            &["layout", "x"],
            &["encode", "--fault", "nope", "--out", "x"],
            &[
                "encode",
                "--fault",
                "gap",
                "--scenario",
                "two-crossing",
                "--out",
                "x",
            ],
        ] {
            let e = parse(args).map(|_| ()).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{args:?}: {e}");
        }
    }
}
