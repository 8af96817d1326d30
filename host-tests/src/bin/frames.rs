//! `frames`: writes measurement wire frames for the demo firmware's UART, and
//! decodes the report frames it sends back.
//!
//! ```text
//! frames encode (--scenario NAME [--seed N] | --csv FILE) [--sensor ID]
//!               [--corrupt-every K] [--garbage-every K] --out FILE
//! frames encode --fault KIND [--capacity M] [--fault-seed N] --out FILE
//! frames decode FILE [--messages | --scans-csv] [--check]
//! frames layout
//! frames --help
//! ```
//!
//! The frame format is documented in `abtrack::wire`.

use abtrack::wire::ScanCounts;
use abtrack_host_tests::frames::{self, Fault, Faults};
use abtrack_host_tests::scenario::{self, SCENARIO_NAMES};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "\
frames: abtrack wire frames for the demo firmware's UART (format: abtrack::wire)

USAGE:
    frames encode (--scenario NAME [--seed N] | --csv FILE) [--sensor ID]
                  [--corrupt-every K] [--garbage-every K] --out FILE
    frames encode --fault KIND [--capacity M] [--fault-seed N] --out FILE
    frames decode FILE [--messages | --scans-csv] [--check]
    frames layout
    frames --help

encode writes one measurement frame per measurement, in time order:
    --scenario NAME     tcas-demo (the demo's default input: four TCAS intruders,
                        Mode S and Mode C replies, false replies) or a
                        simulate scenario (two-crossing, tcas-converging, ...)
    --seed N            its seed (default 0)
    --csv FILE          or measurements from a CSV file: header t,x,y (s, m) or
                        t,range,azimuth[,alt] (s, m, rad clockwise from +y, ft;
                        empty alt = not reported); rows sharing t are one scan
    --sensor ID         sensor id in the frames, 0-255 (default 1)
    --corrupt-every K   flip one payload bit of every K-th frame (a CRC error)
    --garbage-every K   put 1-16 random bytes before every K-th frame
    --fault-seed N      seed of the injected faults (default 0)
    --out FILE          output file
  and prints what it wrote (frames, corrupted frames, garbage bytes, the
  largest number of measurements at one time) on stdout.
  Frames are numbered from 0 (the header's sequence number).

encode --fault writes the demo's input (tcas-demo, seed 1) with one fault
of the fault-injection tests: garbage, sync-garbage, crc-errors, truncated,
oversize, flood (10 x --capacity extra measurements at t = 30 s; default 64),
gap, backwards, far-clock, jump, out-of-range, clutter-storm, reversed,
garbage-only (see docs/firmware-runtime.md).

layout prints the frame format (every layout and counter list, from the
code's own tables) as Markdown: docs/firmware-runtime.md includes it.

decode reads a byte stream (e.g. the demo's UART output) and prints a
summary of the frames in it: scans, tracks, advisories, health counters;
--messages prints every message, one per line, instead; --scans-csv prints the
scan summaries as CSV (time_s, interval_ms, advisory, then every count). With --check the exit
status is 1 if the stream is not clean frames only (a CRC error, a skipped
or left-over byte, a gap in the sequence numbers): a firmware's report
output must be.
";

#[derive(Debug, PartialEq)]
enum Source {
    Scenario(String, u64),
    Csv(PathBuf),
    Fault(Fault, usize),
}

#[derive(Debug, PartialEq, Clone, Copy)]
enum Output {
    Summary,
    Messages,
    Csv,
}

#[derive(Debug, PartialEq)]
enum Command {
    Help,
    Layout,
    Encode {
        source: Source,
        sensor: u8,
        faults: Faults,
        out: PathBuf,
    },
    Decode {
        file: PathBuf,
        output: Output,
        check: bool,
    },
}

fn parse_number<T: std::str::FromStr>(name: &str, v: &str) -> Result<T, String> {
    v.parse::<T>()
        .map_err(|_| format!("{name}: '{v}' is not a valid number"))
}

fn parse(args: &[String]) -> Result<Command, String> {
    let Some(sub) = args.first() else {
        return Err("missing command: encode or decode (try --help)".into());
    };
    if sub == "-h" || sub == "--help" {
        return Ok(Command::Help);
    }
    if sub == "layout" {
        return match args.get(1) {
            None => Ok(Command::Layout),
            Some(a) => Err(format!("layout takes no argument ('{a}')")),
        };
    }
    let mut scenario_name = None;
    let mut seed = 0u64;
    let mut csv = None;
    let mut sensor = 1u8;
    let mut faults = Faults::default();
    let mut out = None;
    let mut file = None;
    let mut output = Output::Summary;
    let mut check = false;
    let mut fault = None;
    let mut capacity = 64usize;
    let mut it = args.iter().skip(1);
    while let Some(arg) = it.next() {
        let mut value = |name: &str| -> Result<String, String> {
            it.next()
                .cloned()
                .ok_or_else(|| format!("{name} needs a value"))
        };
        match arg.as_str() {
            "-h" | "--help" => return Ok(Command::Help),
            "--scenario" => scenario_name = Some(value(arg)?),
            "--seed" => seed = parse_number(arg, &value(arg)?)?,
            "--csv" => csv = Some(PathBuf::from(value(arg)?)),
            "--sensor" => sensor = parse_number(arg, &value(arg)?)?,
            "--corrupt-every" => faults.corrupt_every = Some(parse_number(arg, &value(arg)?)?),
            "--garbage-every" => faults.garbage_every = Some(parse_number(arg, &value(arg)?)?),
            "--fault-seed" => faults.seed = parse_number(arg, &value(arg)?)?,
            "--out" => out = Some(PathBuf::from(value(arg)?)),
            "--messages" => output = Output::Messages,
            "--scans-csv" => output = Output::Csv,
            "--fault" => {
                let name = value(arg)?;
                fault = Some(Fault::from_name(&name).ok_or_else(|| {
                    let known: Vec<&str> = Fault::ALL.iter().map(|f| f.name()).collect();
                    format!("unknown fault '{name}' (known: {})", known.join(", "))
                })?);
            }
            "--capacity" => capacity = parse_number(arg, &value(arg)?)?,
            "--check" => check = true,
            other if !other.starts_with('-') && file.is_none() => file = Some(PathBuf::from(other)),
            other => return Err(format!("unknown argument '{other}' (try --help)")),
        }
    }
    match sub.as_str() {
        "encode" => {
            let source = match (scenario_name, csv, fault) {
                (None, None, Some(fault)) => Source::Fault(fault, capacity),
                (Some(name), None, None) => {
                    if name != frames::TCAS_DEMO && scenario::info(&name).is_none() {
                        return Err(format!(
                            "unknown scenario '{name}' (known: {})",
                            SCENARIO_NAMES.join(", ")
                        ));
                    }
                    Source::Scenario(name, seed)
                }
                (None, Some(path), None) => Source::Csv(path),
                _ => {
                    return Err(
                        "encode needs one of --scenario NAME, --csv FILE or --fault KIND".into(),
                    )
                }
            };
            let out = out.ok_or("encode needs --out FILE")?;
            Ok(Command::Encode {
                source,
                sensor,
                faults,
                out,
            })
        }
        "decode" => Ok(Command::Decode {
            file: file.ok_or("decode needs a FILE")?,
            output,
            check,
        }),
        other => Err(format!(
            "unknown command '{other}': encode or decode (try --help)"
        )),
    }
}

fn run(command: Command) -> Result<(), String> {
    match command {
        Command::Help => print!("{USAGE}"),
        Command::Layout => print!("{}", frames::layout_markdown()),
        Command::Encode {
            source,
            sensor,
            faults,
            out,
        } => {
            let (encoded, what) = match &source {
                Source::Fault(fault, capacity) => {
                    let stream = frames::fault_stream(*fault, *capacity, faults.seed)?;
                    let encoded = frames::Encoded {
                        frames: stream.frames,
                        corrupted: stream.damaged,
                        garbage_bytes: stream.garbage_bytes,
                        max_per_scan: stream.scans.iter().map(|s| s.2).max().unwrap_or(0),
                        bytes: stream.bytes,
                    };
                    (
                        encoded,
                        format!("two-crossing seed 1 with fault {}", fault.name()),
                    )
                }
                Source::Scenario(name, seed) => (
                    frames::encode(&frames::scenario_reports(name, *seed, sensor)?, faults),
                    format!("{name} seed {seed}"),
                ),
                Source::Csv(path) => {
                    let text = std::fs::read_to_string(path)
                        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
                    let reports = frames::reports_from_csv(&text, sensor)
                        .map_err(|e| format!("{}: {e}", path.display()))?;
                    (frames::encode(&reports, faults), path.display().to_string())
                }
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
        Command::Decode {
            file,
            output,
            check,
        } => {
            let bytes =
                std::fs::read(&file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
            let text = match output {
                Output::Messages => frames::decode_all(&bytes)
                    .0
                    .iter()
                    .map(|m| frames::message_line(m) + "\n")
                    .collect(),
                Output::Csv => scans_csv(&frames::summarise(&bytes).scans),
                Output::Summary => frames::summarise(&bytes).to_text(),
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
fn scans_csv(scans: &[abtrack::wire::ScanSummary]) -> String {
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
    let args: Vec<String> = std::env::args().skip(1).collect();
    match parse(&args) {
        Ok(command) => match run(command) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("frames: error: {e}");
                ExitCode::from(1)
            }
        },
        Err(e) => {
            eprintln!("frames: error: {e}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &[&str]) -> Vec<String> {
        s.iter().map(|a| a.to_string()).collect()
    }

    #[test]
    fn parses_encode_and_decode() {
        assert_eq!(
            parse(&args(&[
                "encode",
                "--scenario",
                "two-crossing",
                "--seed",
                "3",
                "--corrupt-every",
                "40",
                "--out",
                "x.bin"
            ])),
            Ok(Command::Encode {
                source: Source::Scenario("two-crossing".into(), 3),
                sensor: 1,
                faults: Faults {
                    corrupt_every: Some(40),
                    garbage_every: None,
                    seed: 0
                },
                out: PathBuf::from("x.bin"),
            })
        );
        assert_eq!(
            parse(&args(&["decode", "r.bin", "--messages"])),
            Ok(Command::Decode {
                file: PathBuf::from("r.bin"),
                output: Output::Messages,
                check: false
            })
        );
    }

    #[test]
    fn refuses_bad_command_lines() {
        assert!(parse(&args(&[])).is_err());
        assert!(parse(&args(&["encode", "--out", "x"])).is_err());
        assert!(parse(&args(&["encode", "--scenario", "nope", "--out", "x"])).is_err());
        assert!(parse(&args(&["encode", "--scenario", "two-crossing"])).is_err());
        assert!(parse(&args(&["encode", "--sensor", "300"])).is_err());
        assert!(parse(&args(&["decode"])).is_err());
        assert!(parse(&args(&["frobnicate"])).is_err());
        assert_eq!(parse(&args(&["layout"])), Ok(Command::Layout));
        assert!(parse(&args(&["layout", "x"])).is_err());
        assert!(parse(&args(&["encode", "--fault", "nope", "--out", "x"])).is_err());
        assert!(parse(&args(&[
            "encode",
            "--fault",
            "gap",
            "--scenario",
            "two-crossing",
            "--out",
            "x"
        ]))
        .is_err());
    }
}
