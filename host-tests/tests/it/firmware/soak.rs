//! The soak: a simulated operational day (86,400 scans at 1 Hz, 45
//! intruders, detection probability 0.9, 20 clutter returns per scan) on
//! the emulated board under `-icount shift=0` (boards/qemu/src/bin/soak/), checked
//! against the same day run in f64 on the host.
//!
//! Checks, hour by hour: nothing drifts (the RMS error, the instructions per
//! scan and the track breaks of every hour within bounds of the first
//! hour's), the table never fills with ghosts (at most 3 confirmed tracks
//! more than 200 m from every intruder at any scan, no candidate refused
//! for a full table), the intruders stay tracked (45 on average in every
//! hour after the first scans), the instructions per scan stay within
//! twice the first hour's mean (and those to receive a scan within twice
//! the first hour's most); and at the end, the board's confirmed
//! tracks are the f64 run's: the same ids, positions within 1 m (the
//! Cortex-M3's `ScaledScalar`) or 10 m (f32).
//!
//! Needs QEMU, so ignored by a plain `cargo test`. scripts/test.sh runs a
//! one-hour day (`ABTRACK_SOAK_SCANS=3600`); scripts/soak.sh runs the full
//! day and writes results/soak-<board>.md.

use abtrack_firmware::{demo_config, synth};

use abtrack::scan::{Intake, ScanLoop};
use abtrack::track::FixedGainTrack;
use abtrack::wire::{
    Encoder, MeasuredPosition, MeasurementReport, Message, TrackReport, MAX_FRAME_LEN,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn scans() -> u32 {
    std::env::var("ABTRACK_SOAK_SCANS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3600)
}

/// A confirmed track at the end: (x, y) m.
type EndState = BTreeMap<u32, [f64; 2]>;

/// The day in f64 on the host: the same sky, the same receive path and
/// scan loop, the capacities of boards/qemu/src/bin/soak/; the end state.
fn f64_day(scans: u32) -> EndState {
    let config = demo_config::config_for_square::<f64, _>(synth::SOAK_HALF_WIDTH_M).unwrap();
    let mut intake: Box<Intake<128>> = Box::new(Intake::new());
    let mut scan_loop: Box<ScanLoop<f64, FixedGainTrack<f64>, 64, 96>> = Box::new(ScanLoop::new());
    let mut encoder = Encoder::new();
    let mut measurements = [MeasurementReport {
        time_ms: 0,
        sensor: 0,
        position: MeasuredPosition::Cartesian { x_cm: 0, y_cm: 0 },
        altitude_ft: None,
        altitude_25ft: false,
        address: None,
    }; synth::SOAK_MAX_PER_SCAN];
    let mut last: Vec<TrackReport> = Vec::new();
    for k in 0..scans {
        let n = synth::soak_scan(k, &mut measurements);
        for m in &measurements[..n] {
            let mut frame = [0u8; MAX_FRAME_LEN];
            let len = encoder
                .encode(&Message::Measurement(*m), &mut frame)
                .unwrap();
            for &b in &frame[..len] {
                intake.push(b);
            }
        }
        last.clear();
        scan_loop
            .on_tick(&config, intake.as_mut(), |m| {
                if let Message::Track(t) = m {
                    last.push(*t);
                }
            })
            .unwrap();
    }
    last.iter()
        .map(|t| (t.track_id, [t.x_cm as f64 / 100.0, t.y_cm as f64 / 100.0]))
        .collect()
}

/// One "hour" line of the board's log.
#[derive(Debug, Clone, Copy, Default)]
struct Hour {
    scans: u32,
    receive_max: u32,
    scan_mean: u32,
    scan_max: u32,
    confirmed_max: u32,
    tracked_mean: f64,
    ghosts_max: u32,
    rms_error_m: f64,
    breaks: u32,
    refused_table_full: u32,
}

/// The numbers of a log line, in order.
fn numbers(line: &str) -> Vec<f64> {
    line.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter_map(|w| w.trim_end_matches('.').parse::<f64>().ok())
        .collect()
}

fn parse_hour(line: &str) -> Hour {
    // "hour H: S scans; ... receive mean A max B, scan mean C max D;
    // confirmed tracks mean E max F; intruders tracked mean G min H;
    // ghosts max I (J reports); rms error K m; track breaks L; tracks
    // started M, refused (table full) N"
    let n = numbers(line);
    assert_eq!(n.len(), 16, "{line}: {n:?}");
    Hour {
        scans: n[1] as u32,
        receive_max: n[3] as u32,
        scan_mean: n[4] as u32,
        scan_max: n[5] as u32,
        confirmed_max: n[7] as u32,
        tracked_mean: n[8],
        ghosts_max: n[10] as u32,
        rms_error_m: n[12],
        breaks: n[13] as u32,
        refused_table_full: n[15] as u32,
    }
}

fn parse_end_state(log: &str) -> EndState {
    log.lines()
        .filter(|l| l.starts_with("end track "))
        .map(|l| {
            let n = numbers(l);
            (n[0] as u32, [n[1] / 100.0, n[2] / 100.0])
        })
        .collect()
}

fn soak(target: &str, machine: &str, tolerance_m: f64) {
    let scans = scans();
    let status = Command::new("cargo")
        .current_dir(repo())
        .env("ABTRACK_SOAK_SCANS", scans.to_string())
        .args(["build", "--release", "--target", target, "--bin", "soak"])
        .status()
        .unwrap();
    assert!(status.success());
    let elf = repo().join("target").join(target).join("release/soak");
    let started = std::time::Instant::now();
    let out = Command::new(repo().join("scripts/qemu-run.sh"))
        .args([machine, elf.to_str().unwrap()])
        .env("ABTRACK_QEMU_ARGS", "-icount shift=0")
        .env("ABTRACK_QEMU_TIMEOUT", "7200")
        .output()
        .unwrap();
    let wall = started.elapsed();
    let log = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "soak on {machine}:\n{log}");
    let hours: Vec<Hour> = log
        .lines()
        .filter(|l| l.starts_with("hour "))
        .map(parse_hour)
        .collect();
    let day = log
        .lines()
        .find(|l| l.starts_with("day "))
        .map(parse_hour)
        .expect("a day line");
    assert_eq!(day.scans, scans);
    assert_eq!(hours.iter().map(|h| h.scans).sum::<u32>(), scans);

    let first = hours[0];
    let mut failures: Vec<String> = Vec::new();
    let mut check = |ok: bool, what: String| {
        if !ok {
            failures.push(what);
        }
    };
    for (i, h) in hours.iter().enumerate() {
        check(
            h.ghosts_max <= 3,
            format!("hour {i}: {} ghosts at once", h.ghosts_max),
        );
        check(h.refused_table_full == 0, format!("hour {i}: table full"));
        check(
            h.confirmed_max <= 48,
            format!("hour {i}: {} confirmed tracks", h.confirmed_max),
        );
        check(
            h.tracked_mean >= 44.0,
            format!("hour {i}: {} intruders tracked on average", h.tracked_mean),
        );
        check(
            h.scan_max <= 2 * first.scan_mean,
            format!(
                "hour {i}: {} instructions in a scan (first hour's mean {})",
                h.scan_max, first.scan_mean
            ),
        );
        check(
            h.receive_max <= 2 * first.receive_max,
            format!(
                "hour {i}: {} instructions to receive a scan (first hour's most {})",
                h.receive_max, first.receive_max
            ),
        );
        if i > 0 && h.scans == first.scans {
            check(
                (h.rms_error_m - first.rms_error_m).abs() <= 0.1 * first.rms_error_m,
                format!(
                    "hour {i}: rms error {} m (first hour {})",
                    h.rms_error_m, first.rms_error_m
                ),
            );
            check(
                (h.scan_mean as f64 - first.scan_mean as f64).abs() <= 0.1 * first.scan_mean as f64,
                format!(
                    "hour {i}: {} instructions per scan on average (first hour {})",
                    h.scan_mean, first.scan_mean
                ),
            );
            check(
                h.breaks <= 2 * first.breaks.max(1),
                format!(
                    "hour {i}: {} track breaks (first hour {})",
                    h.breaks, first.breaks
                ),
            );
        }
    }

    // The end state against the f64 day.
    let board_end = parse_end_state(&log);
    let reference = f64_day(scans);
    let ids_board: Vec<u32> = board_end.keys().copied().collect();
    let ids_f64: Vec<u32> = reference.keys().copied().collect();
    check(
        ids_board == ids_f64,
        format!("end state: ids {ids_board:?} on the board, {ids_f64:?} in f64"),
    );
    let worst = board_end
        .iter()
        .filter_map(|(id, p)| reference.get(id).map(|q| (p[0] - q[0]).hypot(p[1] - q[1])))
        .fold(0.0f64, f64::max);
    check(
        worst <= tolerance_m,
        format!("end state: a track {worst} m from the f64 run's"),
    );

    let board_name = if machine == "mps2-an385" { "m3" } else { "m4f" };
    let mut report = format!(
        "# Soak on {machine}\n\nGenerated by `scripts/soak.sh {board_name} {scans}` \
         (boards/qemu/src/bin/soak/ on the emulated board under `-icount shift=0`, checked by \
         host-tests/tests/it/firmware/soak.rs); do not edit. {scans} scans ({:.1} h of the sensor's \
         clock) took {:.0} s of wall time. Instructions, not cycles (QEMU counts \
         instructions).\n\n",
        scans as f64 / 3600.0,
        wall.as_secs_f64()
    );
    report += "```text\n";
    for l in log.lines().filter(|l| {
        [
            "abtrack soak",
            "hour ",
            "day ",
            "receiver",
            "intake",
            "scan loop",
            "stack",
        ]
        .iter()
        .any(|p| l.starts_with(p))
    }) {
        report += l;
        report += "\n";
    }
    report += "```\n\n";
    report += &format!(
        "End state: {} confirmed tracks on the board; the same ids as the f64 run on the host: {}; \
         largest position difference {:.3} m (tolerance {tolerance_m} m).\n\n\
         Checks (every hour): at most 3 ghosts at once, no candidate refused for a full table, \
         at most 48 confirmed tracks, at least 44 intruders tracked on average, no scan above \
         twice the first hour's mean instructions, no scan's reception above twice the first \
         hour's most; after the first hour: the RMS error and the \
         mean instructions per scan within 10 % of the first hour's, the track breaks at most \
         twice the first hour's. {}\n",
        board_end.len(),
        ids_board == ids_f64,
        worst,
        if failures.is_empty() {
            "All passed.".to_string()
        } else {
            format!("FAILED: {}", failures.join("; "))
        }
    );
    println!("{report}");
    if let Ok(path) = std::env::var("ABTRACK_SOAK_RESULTS") {
        std::fs::write(&path, &report).unwrap();
    }
    assert!(
        failures.is_empty(),
        "soak on {machine}:\n{}\n{report}",
        failures.join("\n")
    );
}

#[test]
#[ignore = "runs QEMU; scripts/test.sh and scripts/soak.sh run it"]
fn soak_mps2_an385() {
    soak("thumbv7m-none-eabi", "mps2-an385", 1.0);
}

#[test]
#[ignore = "runs QEMU; scripts/soak.sh runs it"]
fn soak_mps2_an386() {
    soak("thumbv7em-none-eabihf", "mps2-an386", 10.0);
}
