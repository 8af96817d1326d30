//! `frames`: writes measurement wire frames for the demo firmware's UART, and
//! decodes the report frames it sends back.
//!
//! ```text
//! frames encode (--scenario NAME [--seed N] | --csv FILE) [--sensor ID]
//!               [--corrupt-every K] [--garbage-every K] --out FILE
//! frames decode FILE [--messages] [--check]
//! frames --help
//! ```
//!
//! The frame format is documented in `abtrack::wire`.

use abtrack_host_tests::frames::{self, Faults};
use abtrack_host_tests::scenario::{self, SCENARIO_NAMES};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "\
frames: abtrack wire frames for the demo firmware's UART (format: abtrack::wire)

USAGE:
    frames encode (--scenario NAME [--seed N] | --csv FILE) [--sensor ID]
                  [--corrupt-every K] [--garbage-every K] --out FILE
    frames decode FILE [--messages] [--check]
    frames --help

encode writes one measurement frame per measurement, in time order:
    --scenario NAME     a simulate scenario (two-crossing, tcas-converging, ...)
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

decode reads a byte stream (e.g. the demo's UART output) and prints a
summary of the frames in it: scans, tracks, advisories, receiver counters;
--messages prints every message, one per line, instead. With --check the exit
status is 1 if the stream is not clean frames only (a CRC error, a skipped
or left-over byte, a gap in the sequence numbers): a firmware's report
output must be.
";

#[derive(Debug, PartialEq)]
enum Source {
    Scenario(String, u64),
    Csv(PathBuf),
}

#[derive(Debug, PartialEq)]
enum Command {
    Help,
    Encode {
        source: Source,
        sensor: u8,
        faults: Faults,
        out: PathBuf,
    },
    Decode {
        file: PathBuf,
        messages: bool,
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
    let mut scenario_name = None;
    let mut seed = 0u64;
    let mut csv = None;
    let mut sensor = 1u8;
    let mut faults = Faults::default();
    let mut out = None;
    let mut file = None;
    let mut messages = false;
    let mut check = false;
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
            "--messages" => messages = true,
            "--check" => check = true,
            other if !other.starts_with('-') && file.is_none() => file = Some(PathBuf::from(other)),
            other => return Err(format!("unknown argument '{other}' (try --help)")),
        }
    }
    match sub.as_str() {
        "encode" => {
            let source = match (scenario_name, csv) {
                (Some(name), None) => {
                    if scenario::info(&name).is_none() {
                        return Err(format!(
                            "unknown scenario '{name}' (known: {})",
                            SCENARIO_NAMES.join(", ")
                        ));
                    }
                    Source::Scenario(name, seed)
                }
                (None, Some(path)) => Source::Csv(path),
                _ => return Err("encode needs one of --scenario NAME or --csv FILE".into()),
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
            messages,
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
        Command::Encode {
            source,
            sensor,
            faults,
            out,
        } => {
            let (reports, what) = match &source {
                Source::Scenario(name, seed) => (
                    frames::scenario_reports(name, *seed, sensor)?,
                    format!("{name} seed {seed}"),
                ),
                Source::Csv(path) => {
                    let text = std::fs::read_to_string(path)
                        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
                    (
                        frames::reports_from_csv(&text, sensor)
                            .map_err(|e| format!("{}: {e}", path.display()))?,
                        path.display().to_string(),
                    )
                }
            };
            let encoded = frames::encode(&reports, faults);
            if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
                std::fs::create_dir_all(dir)
                    .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
            }
            std::fs::write(&out, &encoded.bytes)
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            println!(
                "{what}: {} frames ({} corrupted), {} garbage bytes, {} bytes, at most {} measurements at one time -> {}",
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
            messages,
            check,
        } => {
            let bytes =
                std::fs::read(&file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
            let text = if messages {
                frames::decode_all(&bytes)
                    .0
                    .iter()
                    .map(|m| frames::message_line(m) + "\n")
                    .collect()
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
                messages: true,
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
    }
}
