//! Wire frames on the host: a scenario or a CSV file of measurements as a
//! byte stream of `abtrack::wire` measurement frames (the demo firmware's UART
//! input), optionally with corrupted frames and garbage between frames to
//! exercise the receiver; and the reverse, a byte stream decoded into
//! messages with a summary; and the demo firmware's decisions on the host
//! ([`run_like_the_firmware`]). Used by the `frames` binary and the
//! scan-loop, fault-injection and determinism tests.

use crate::noise::{derive_seed, rng_from_seed, uniform_index};
use crate::scenario::{self, Measurement};
use abtrack::scan::{
    Collected, Intake, MeasurementSource, RunVerdict, ScanConfig, ScanLoop, TickReport,
};
use abtrack::tcas::Advisory;
use abtrack::track::FixedGainTrack;
use abtrack::wire::{
    Decoder, DecoderStats, Encoder, Health, MeasurementReport, Message, ScanSummary, TrackReport,
    CRC_LEN, HEADER_LEN, MAX_FRAME_LEN,
};
use abtrack::{Gains, Scalar};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Seconds to the millisecond clock of the frames (rounded; t ≥ 0).
pub fn time_ms(t_s: f64) -> Result<u32, String> {
    let ms = (t_s * 1000.0).round();
    if !(0.0..=u32::MAX as f64).contains(&ms) {
        return Err(format!(
            "time {t_s} s is outside the 32-bit millisecond clock"
        ));
    }
    Ok(ms as u32)
}

/// One scenario measurement as a wire report from sensor `sensor`.
pub fn report(m: &Measurement, sensor: u8) -> Result<MeasurementReport, String> {
    let converted = match *m {
        Measurement::Cartesian { t, x, y } => {
            MeasurementReport::cartesian_from_metres(time_ms(t)?, sensor, x, y, None)
        }
        Measurement::Polar {
            t,
            range,
            azimuth,
            alt_ft,
        } => MeasurementReport::polar_from_metres(time_ms(t)?, sensor, range, azimuth, alt_ft),
    };
    converted.map_err(|e| format!("measurement at t = {} s: {e}", m.t()))
}

/// Every measurement of a seeded scenario run, in time order (the scenario's
/// row order within a scan is kept: shuffled, unlabelled).
pub fn scenario_reports(
    name: &str,
    seed: u64,
    sensor: u8,
) -> Result<Vec<MeasurementReport>, String> {
    let run = scenario::generate(name, seed).map_err(|e| e.to_string())?;
    run.measurements().map(|m| report(m, sensor)).collect()
}

/// Reads measurements from CSV text: header `t,x,y` (Cartesian, metres) or
/// `t,range,azimuth` / `t,range,azimuth,alt` (metres, radians clockwise from
/// +y, feet; an empty `alt` is a non-reporting target), the formats the
/// `simulate` tool writes. Rows with the same `t` form one scan; `t` (s) must
/// not decrease.
pub fn reports_from_csv(text: &str, sensor: u8) -> Result<Vec<MeasurementReport>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_start_matches('\u{feff}').trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((_, header)) = lines.next() else {
        return Err("empty file: expected a header t,x,y or t,range,azimuth[,alt]".into());
    };
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    let polar = match columns.as_slice() {
        ["t", "x", "y"] => false,
        ["t", "range", "azimuth"] | ["t", "range", "azimuth", "alt"] => true,
        _ => {
            return Err(format!(
                "line 1: header '{header}': expected t,x,y or t,range,azimuth[,alt]"
            ))
        }
    };
    let mut out = Vec::new();
    let mut last_t = f64::NEG_INFINITY;
    for (line, row) in lines {
        let fields: Vec<&str> = row.split(',').map(str::trim).collect();
        if fields.len() != columns.len() {
            return Err(format!(
                "line {line}: {} fields, the header has {}",
                fields.len(),
                columns.len()
            ));
        }
        let number = |i: usize| -> Result<f64, String> {
            let f = fields.get(i).copied().unwrap_or("");
            match f.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(format!(
                    "line {line}, column {}: '{f}' is not a finite number",
                    i + 1
                )),
            }
        };
        let t = number(0)?;
        if t < last_t {
            return Err(format!(
                "line {line}: t = {t} is before the previous row's {last_t}"
            ));
        }
        last_t = t;
        let ms = time_ms(t).map_err(|e| format!("line {line}: {e}"))?;
        let converted = if polar {
            let alt = match fields.get(3) {
                Some(f) if !f.is_empty() => Some(number(3)?),
                _ => None,
            };
            MeasurementReport::polar_from_metres(ms, sensor, number(1)?, number(2)?, alt)
        } else {
            MeasurementReport::cartesian_from_metres(ms, sensor, number(1)?, number(2)?, None)
        };
        out.push(converted.map_err(|e| format!("line {line}: {e}"))?);
    }
    Ok(out)
}

/// Line faults to inject while encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Faults {
    /// Flip one payload bit of every k-th frame (a CRC error).
    pub corrupt_every: Option<usize>,
    /// Put 1–16 random bytes before every k-th frame.
    pub garbage_every: Option<usize>,
    /// Seed of the random garbage and of which bit is flipped.
    pub seed: u64,
}

/// An encoded stream and what is in it.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Encoded {
    pub bytes: Vec<u8>,
    /// Frames written (corrupted ones included).
    pub frames: usize,
    /// Frames written with a flipped bit.
    pub corrupted: usize,
    /// Garbage bytes written between frames.
    pub garbage_bytes: usize,
    /// The most measurements sharing one timestamp.
    pub max_per_scan: usize,
}

/// Encodes `reports` in order as frames, with the faults.
pub fn encode(reports: &[MeasurementReport], faults: Faults) -> Encoded {
    let mut rng = rng_from_seed(derive_seed(faults.seed, 0xF4A7));
    let mut out = Encoded::default();
    let mut per_time: BTreeMap<u32, usize> = BTreeMap::new();
    let mut frame = [0u8; MAX_FRAME_LEN];
    let mut encoder = Encoder::new();
    for (k, r) in reports.iter().enumerate() {
        *per_time.entry(r.time_ms).or_default() += 1;
        let n = k + 1;
        if faults.garbage_every.is_some_and(|g| g > 0 && n % g == 0) {
            let len = 1 + uniform_index(&mut rng, 16);
            for _ in 0..len {
                out.bytes.push(uniform_index(&mut rng, 256) as u8);
            }
            out.garbage_bytes += len;
        }
        let len = encoder
            .encode(&Message::Measurement(*r), &mut frame)
            .expect("a frame fits MAX_FRAME_LEN");
        let mut bytes = frame[..len].to_vec();
        if faults.corrupt_every.is_some_and(|c| c > 0 && n % c == 0) {
            // A payload bit: the header stays valid, so the decoder takes the
            // whole frame and fails its CRC.
            let bit = uniform_index(&mut rng, (len - HEADER_LEN - CRC_LEN) * 8);
            bytes[HEADER_LEN + bit / 8] ^= 1 << (bit % 8);
            out.corrupted += 1;
        }
        out.bytes.extend_from_slice(&bytes);
        out.frames += 1;
    }
    out.max_per_scan = per_time.values().copied().max().unwrap_or(0);
    out
}

/// Every message in a byte stream, and the decoder's counters.
pub fn decode_all(bytes: &[u8]) -> (Vec<Message>, DecoderStats) {
    let mut decoder = Decoder::new();
    let mut messages = Vec::new();
    for &b in bytes {
        let mut event = decoder.push(b);
        while let Some(result) = event {
            if let Ok(m) = result {
                messages.push(m);
            }
            event = decoder.poll();
        }
    }
    (messages, *decoder.stats())
}

/// One track's history in a report stream.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackHistory {
    pub id: u32,
    pub first_ms: u32,
    pub last_ms: u32,
    pub reports: usize,
    pub last: TrackReport,
    pub highest_advisory: Advisory,
}

/// What a report stream (the demo firmware's UART output) says.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReportSummary {
    pub scans: Vec<ScanSummary>,
    pub tracks: BTreeMap<u32, TrackHistory>,
    /// (scan time, new highest advisory) each time it changed.
    pub advisory_changes: Vec<(u32, Advisory)>,
    pub last_health: Option<Health>,
    pub measurements: usize,
    pub decoder: DecoderStats,
}

pub fn summarise(bytes: &[u8]) -> ReportSummary {
    let (messages, decoder) = decode_all(bytes);
    let mut s = ReportSummary {
        decoder,
        ..ReportSummary::default()
    };
    let mut shown = Advisory::None;
    for m in messages {
        match m {
            Message::Track(t) => {
                let h = s.tracks.entry(t.track_id).or_insert(TrackHistory {
                    id: t.track_id,
                    first_ms: t.time_ms,
                    last_ms: t.time_ms,
                    reports: 0,
                    last: t,
                    highest_advisory: Advisory::None,
                });
                h.last_ms = t.time_ms;
                h.reports += 1;
                h.last = t;
                h.highest_advisory = h.highest_advisory.max(t.advisory);
            }
            Message::Scan(scan) => {
                if scan.highest_advisory != shown {
                    shown = scan.highest_advisory;
                    s.advisory_changes.push((scan.time_ms, shown));
                }
                s.scans.push(scan);
            }
            Message::Health(h) => s.last_health = Some(h),
            Message::Measurement(_) => s.measurements += 1,
        }
    }
    s
}

fn seconds(ms: u32) -> f64 {
    ms as f64 / 1000.0
}

impl ReportSummary {
    /// The summary as text (what `frames decode` prints).
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let d = &self.decoder;
        let _ = writeln!(
            out,
            "{} frames decoded ({} CRC errors, {} bytes skipped, {} frames lost): {} scan summaries, {} track reports, {} measurements",
            d.accepted,
            d.crc_errors,
            d.bytes_skipped,
            d.frames_lost,
            self.scans.len(),
            self.tracks.values().map(|t| t.reports).sum::<usize>(),
            self.measurements
        );
        if let (Some(first), Some(last)) = (self.scans.first(), self.scans.last()) {
            let used: u32 = self.scans.iter().map(|s| s.counts.used as u32).sum();
            let started: u32 = self.scans.iter().map(|s| s.counts.started as u32).sum();
            let confirmed: u32 = self.scans.iter().map(|s| s.counts.confirmed as u32).sum();
            let deleted: u32 = self.scans.iter().map(|s| s.counts.deleted as u32).sum();
            let _ = writeln!(
                out,
                "{} scans, t = {} .. {} s: {used} measurements used; tracks started {started}, confirmed {confirmed}, deleted {deleted}; {} live at the end ({} confirmed)",
                self.scans.len(),
                seconds(first.time_ms),
                seconds(last.time_ms),
                last.counts.tracks,
                last.counts.confirmed_tracks
            );
        }
        for t in self.tracks.values() {
            let l = &t.last;
            let _ = writeln!(
                out,
                "track {}: reported t = {} .. {} s ({} reports), last {} at ({:.1}, {:.1}) m moving ({:.1}, {:.1}) m/s, worst advisory {}",
                t.id,
                seconds(t.first_ms),
                seconds(t.last_ms),
                t.reports,
                l.status.as_str(),
                l.x_cm as f64 / 100.0,
                l.y_cm as f64 / 100.0,
                l.vx_cm_per_s as f64 / 100.0,
                l.vy_cm_per_s as f64 / 100.0,
                t.highest_advisory.name()
            );
        }
        let changes: Vec<String> = self
            .advisory_changes
            .iter()
            .map(|(t, a)| format!("{} at t = {} s", a.name(), seconds(*t)))
            .collect();
        let _ = writeln!(
            out,
            "advisory changes: {}",
            if changes.is_empty() {
                "none".to_string()
            } else {
                changes.join(", ")
            }
        );
        if let Some(h) = &self.last_health {
            let _ = writeln!(out, "health (t = {} s):", seconds(h.time_ms));
            let _ = writeln!(out, "  receiver: {}", h.decoder);
            let _ = writeln!(out, "  intake: {}", h.intake);
            let _ = writeln!(out, "  scan loop: {}", h.scan);
        }
        out
    }
}

/// One message as a line of text (`frames decode --messages`).
pub fn message_line(m: &Message) -> String {
    match m {
        Message::Measurement(r) => {
            let alt = r
                .altitude_ft
                .map_or(String::new(), |a| format!(" alt {a} ft"));
            match r.position {
                abtrack::wire::MeasuredPosition::Cartesian { x_cm, y_cm } => format!(
                    "measurement t={} s sensor {} x={} m y={} m{alt}",
                    seconds(r.time_ms),
                    r.sensor,
                    x_cm as f64 / 100.0,
                    y_cm as f64 / 100.0
                ),
                abtrack::wire::MeasuredPosition::Polar {
                    range_cm,
                    azimuth_bam,
                } => format!(
                    "measurement t={} s sensor {} range={} m azimuth={:.3} deg{alt}",
                    seconds(r.time_ms),
                    r.sensor,
                    range_cm as f64 / 100.0,
                    azimuth_bam as f64 * 360.0 / 65536.0
                ),
            }
        }
        Message::Track(t) => format!(
            "track t={} s id {} {} x={} m y={} m vx={} m/s vy={} m/s alt={} advisory {} tau={}",
            seconds(t.time_ms),
            t.track_id,
            t.status.as_str(),
            t.x_cm as f64 / 100.0,
            t.y_cm as f64 / 100.0,
            t.vx_cm_per_s as f64 / 100.0,
            t.vy_cm_per_s as f64 / 100.0,
            t.altitude
                .map_or("-".to_string(), |(a, r)| format!("{a} ft {r} ft/min")),
            t.advisory.name(),
            t.range_tau_ds
                .map_or("-".to_string(), |d| format!("{} s", d as f64 / 10.0)),
        ),
        Message::Scan(s) => format!(
            "scan t={} s (interval {} ms), advisory {}: {}",
            seconds(s.time_ms),
            s.interval_ms,
            s.highest_advisory.name(),
            s.counts
        ),
        Message::Health(h) => format!(
            "health t={} s: receiver: {}; intake: {}; scan loop: {}",
            seconds(h.time_ms),
            h.decoder,
            h.intake,
            h.scan
        ),
    }
}

/// The demo firmware's decisions, on the host: the same scan-loop core fed
/// the same bytes in the same order, paced as `src/main.rs` paces it (a
/// scan runs once the input has moved past it; after the input, the line
/// goes idle, the rest is scanned, then three idle scans), with the same
/// capacities (`N` tracks, `M` measurements per scan, a queue of `Q`) and
/// number type. With flow control nothing depends on timing, so the report
/// frames are the firmware's, byte for byte.
pub fn run_like_the_firmware<S: Scalar, const N: usize, const M: usize, const Q: usize>(
    input: &[u8],
    config: &ScanConfig<S, Gains<S>>,
) -> FirmwareRun {
    /// `IDLE_SCANS` of src/main.rs.
    const IDLE_SCANS: u32 = 3;
    let mut intake: Box<Intake<Q>> = Box::new(Intake::new());
    let mut scan_loop: Box<ScanLoop<S, FixedGainTrack<S>, N, M>> = Box::new(ScanLoop::new());
    let mut run = FirmwareRun::default();
    let mut encoder = Encoder::new();
    let mut tick = |scan_loop: &mut ScanLoop<S, FixedGainTrack<S>, N, M>,
                    intake: &mut Intake<Q>,
                    run: &mut FirmwareRun| {
        let mut frame = [0u8; MAX_FRAME_LEN];
        let report = scan_loop
            .on_tick(config, intake, |m| {
                let n = encoder.encode(m, &mut frame).expect("a frame fits");
                run.output.extend_from_slice(&frame[..n]);
            })
            .expect("the loop's tracker clock always advances");
        run.ticks.push(report);
        report
    };
    for &b in input {
        // Flow control: the receiver reads a byte only with room for what
        // it may complete.
        while !intake.can_take_byte() {
            if scan_loop.collect(config, intake.as_mut()) == Collected::ScanDue {
                tick(&mut scan_loop, &mut intake, &mut run);
            }
        }
        intake.push(b);
        while scan_loop.collect(config, intake.as_mut()) == Collected::ScanDue {
            tick(&mut scan_loop, &mut intake, &mut run);
        }
    }
    intake.line_idle();
    let mut idle_scans = 0;
    while idle_scans < IDLE_SCANS {
        scan_loop.collect(config, intake.as_mut());
        let report = tick(&mut scan_loop, &mut intake, &mut run);
        if intake.queued() == 0 {
            scan_loop.finish();
        }
        if report.summary.counts.used == 0 && intake.queued() == 0 && scan_loop.held() == 0 {
            idle_scans += 1;
        } else {
            idle_scans = 0;
        }
    }
    let (decoder, intake_counters) = intake.receiver_counters();
    run.health = Health {
        time_ms: scan_loop.scan_time_ms(),
        decoder,
        intake: intake_counters,
        scan: *scan_loop.counters(),
    };
    run.verdict = Some(RunVerdict::from_health(&run.health));
    run
}

/// What [`run_like_the_firmware`] produced.
#[derive(Debug, Clone, Default)]
pub struct FirmwareRun {
    /// The report frames, as the firmware sends them on its UART.
    pub output: Vec<u8>,
    /// Every scan's result.
    pub ticks: Vec<TickReport>,
    /// The counters at the end (the firmware's summary).
    pub health: Health,
    pub verdict: Option<RunVerdict>,
}
