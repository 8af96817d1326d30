//! Wire frames on the host: a scenario or a CSV file of measurements as a
//! byte stream of `abtrack::wire` measurement frames (the demo firmware's UART
//! input), optionally with corrupted frames and garbage between frames to
//! exercise the receiver; and the reverse, a byte stream decoded into
//! messages with a summary; and the demo firmware's decisions on the host
//! ([`run_like_the_firmware`]). Used by the `frames` binary and the
//! scan-loop, fault-injection and determinism tests.

use crate::csv_input::{self, AngleUnit, ReadOptions, Recording, TimeOrder};
use crate::encounters::{demo_scenario, DemoReply};
use crate::noise::{derive_seed, rng_from_seed, uniform_index};
use crate::scenario::{self, Measurement};
use abtrack::filter::altitude::AltitudeQuantum;
use abtrack::scan::{
    BearingTrack, Collected, Intake, MeasurementSource, RunVerdict, ScanConfig, ScanLoop,
    TickReport,
};
use abtrack::tcas::Advisory;
use abtrack::track::TrackFilter;
use abtrack::wire::{
    Decoder, DecoderStats, Encoder, EndOfInput, Health, MeasurementReport, Message, ModeSAddress,
    ScanSummary, TrackReport, CRC_LEN, HEADER_LEN, MAX_FRAME_LEN,
};
use abtrack::{Numeric, Scalar};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Read;

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

/// The TCAS demo scenario ([`demo_scenario`]): the
/// firmware's default input.
pub const TCAS_DEMO: &str = "tcas-demo";
/// Its length, scans (1 s each): the threat's RA and clear of conflict, the
/// other intruders' closest approaches.
pub const TCAS_DEMO_SCANS: usize = 110;

/// One reply of the demo scenario as a polar wire report, with its Mode S
/// address and altitude quantum.
pub fn demo_report(r: &DemoReply, sensor: u8) -> Result<MeasurementReport, String> {
    let m = MeasurementReport::polar_from_metres(
        time_ms(r.time_s)?,
        sensor,
        r.range_m,
        r.bearing_rad,
        r.altitude_ft,
    )
    .map_err(|e| format!("reply at t = {} s: {e}", r.time_s))?;
    Ok(match r.mode_s_address {
        None => m,
        Some(a) => m.with_mode_s(
            ModeSAddress::new(a).ok_or_else(|| format!("address {a:#x} beyond 24 bits"))?,
            r.quantum == AltitudeQuantum::ModeS25,
        ),
    })
}

/// Every measurement of a seeded scenario run, in time order (the scenario's
/// row order within a scan is kept: shuffled, unlabelled); [`TCAS_DEMO`]
/// is the TCAS demo scenario.
pub fn scenario_reports(
    name: &str,
    seed: u64,
    sensor: u8,
) -> Result<Vec<MeasurementReport>, String> {
    if name == TCAS_DEMO {
        return demo_scenario(seed, TCAS_DEMO_SCANS)
            .iter()
            .map(|r| demo_report(r, sensor))
            .collect();
    }
    let run = scenario::generate(name, seed).map_err(|e| e.to_string())?;
    run.measurements().map(|m| report(m, sensor)).collect()
}

/// Reads measurements from a CSV recording with [`csv_input::read_recording`]
/// (header matched by name, extra columns ignored, errors naming the line and
/// column): `t,x,y` (metres) or `t,range,azimuth` (metres; azimuth clockwise
/// from +y in `azimuth_unit`), either with an optional `alt` (feet; empty =
/// not reported), the formats the `simulate` tool writes. Rows sharing `t`
/// form one scan ([`TimeOrder::Scans`]). The wire's Cartesian measurement is
/// two-dimensional, so a `z` column is refused rather than dropped.
pub fn reports_from_csv<R: Read>(
    input: R,
    sensor: u8,
    azimuth_unit: AngleUnit,
) -> Result<Vec<MeasurementReport>, String> {
    let options = ReadOptions {
        times: TimeOrder::Scans,
        azimuth_unit,
    };
    let at_line = |line: usize| move |e: String| format!("line {line}: {e}");
    match csv_input::read_recording(input, options).map_err(|e| e.to_string())? {
        Recording::Cartesian(m) => {
            if m.dims > 2 {
                return Err(
                    "line 1: the header has a z column, but the wire's Cartesian \
                            measurement is x, y only (remove the column)"
                        .into(),
                );
            }
            m.rows
                .iter()
                .map(|r| {
                    let [x, y, _] = r.z;
                    let ms = time_ms(r.t).map_err(at_line(r.line))?;
                    MeasurementReport::cartesian_from_metres(ms, sensor, x, y, r.alt)
                        .map_err(|e| at_line(r.line)(e.to_string()))
                })
                .collect()
        }
        Recording::RangeAzimuth(m) => m
            .rows
            .iter()
            .map(|r| {
                let ms = time_ms(r.t).map_err(at_line(r.line))?;
                MeasurementReport::polar_from_metres(ms, sensor, r.range, r.azimuth, r.alt)
                    .map_err(|e| at_line(r.line)(e.to_string()))
            })
            .collect(),
    }
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
    /// Frames written (corrupted ones and the end-of-input frame included).
    pub frames: usize,
    /// Frames written with a flipped bit.
    pub corrupted: usize,
    /// Garbage bytes written between frames.
    pub garbage_bytes: usize,
    /// The most measurements sharing one timestamp.
    pub max_per_scan: usize,
}

/// Encodes `reports` in order as numbered frames, with the faults, and an
/// end-of-input frame.
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
    // The end of the recording, so that a replay ends at once.
    let end = EndOfInput {
        time_ms: reports.last().map_or(0, |r| r.time_ms),
    };
    let len = encoder
        .encode(&Message::End(end), &mut frame)
        .expect("a frame fits MAX_FRAME_LEN");
    out.bytes.extend_from_slice(&frame[..len]);
    out.frames += 1;
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
    pub end: Option<EndOfInput>,
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
            Message::End(e) => s.end = Some(e),
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
            let _ = writeln!(out, "  track table: {}", h.table);
        }
        out
    }
}

/// One message as a line of text (`frames decode --messages`).
pub fn message_line(m: &Message) -> String {
    match m {
        Message::Measurement(r) => {
            let step = if r.altitude_25ft { " (25 ft steps)" } else { "" };
            let alt = r
                .altitude_ft
                .map_or(String::new(), |a| format!(" alt {a} ft{step}"));
            let alt = match r.address {
                Some(a) => format!("{alt} Mode S {:06X}", a.get()),
                None => alt,
            };
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
            "track t={} s id {} {} x={} m y={} m vx={} m/s vy={} m/s alt={} advisory {}{} tau={} address {}",
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
            t.ra.map_or(String::new(), |ra| format!(" ({})", ra.name())),
            t.range_tau_ds
                .map_or("-".to_string(), |d| format!("{} s", d as f64 / 10.0)),
            t.address
                .map_or("-".to_string(), |a| format!("{:06X}", a.get())),
        ),
        Message::Scan(s) => format!(
            "scan t={} s (interval {} ms), advisory {}{}{}: {}",
            seconds(s.time_ms),
            s.interval_ms,
            s.highest_advisory.name(),
            s.ra.map_or(String::new(), |ra| format!(" ({})", ra.name())),
            if s.clear_of_conflict {
                ", clear of conflict"
            } else {
                ""
            },
            s.counts
        ),
        Message::End(e) => format!("end of input t={} s", seconds(e.time_ms)),
        Message::Health(h) => format!(
            "health t={} s: receiver: {}; intake: {}; scan loop: {}; track table: {}",
            seconds(h.time_ms),
            h.decoder,
            h.intake,
            h.scan,
            h.table
        ),
    }
}

/// The demo firmware's decisions, on the host: the same scan-loop core fed
/// the same bytes in the same order, paced as `boards/qemu/src/main.rs` paces it (a
/// scan runs once the input has moved past it; after the input, the line
/// goes idle, the rest is scanned, then three idle scans), with the same
/// capacities (`N` tracks, `M` measurements per scan, a queue of `Q`) and
/// number type. The receiver reads in lock-step with the main loop (a byte
/// only once every queued measurement was taken) and stops at the
/// end-of-input frame, so nothing depends on timing: the report frames are
/// the firmware's, byte for byte.
pub fn run_like_the_firmware<
    T: Numeric<Wide = S>,
    S: Scalar,
    F: TrackFilter<S> + BearingTrack<S>,
    const N: usize,
    const M: usize,
    const Q: usize,
>(
    input: &[u8],
    config: &ScanConfig<T, F::Params>,
) -> FirmwareRun {
    /// `IDLE_SCANS` of boards/qemu/src/main.rs.
    const IDLE_SCANS: u32 = 3;
    let mut intake: Box<Intake<Q>> = Box::new(Intake::new());
    let mut scan_loop: Box<ScanLoop<T, F, N, M>> = Box::new(ScanLoop::new());
    let mut run = FirmwareRun::default();
    let mut encoder = Encoder::new();
    let mut tick =
        |scan_loop: &mut ScanLoop<T, F, N, M>, intake: &mut Intake<Q>, run: &mut FirmwareRun| {
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
    // Flow control in lock-step: the receiver reads the next byte only once
    // the main loop has taken every queued measurement (running a scan when
    // one is due).
    let mut drain =
        |scan_loop: &mut ScanLoop<T, F, N, M>, intake: &mut Intake<Q>, run: &mut FirmwareRun| {
            while intake.queued() > 0 {
                if scan_loop.collect(config, intake) == Collected::ScanDue {
                    tick(scan_loop, intake, run);
                }
            }
        };
    for &b in input {
        intake.push(b);
        drain(&mut scan_loop, &mut intake, &mut run);
        if intake.input_ended().is_some() {
            // The receiver reads nothing after the end-of-input frame.
            break;
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
    // As the last health frame sent.
    run.health = Health {
        time_ms: run.ticks.last().map_or(0, |t| t.summary.time_ms),
        decoder,
        intake: intake_counters,
        scan: *scan_loop.counters(),
        table: *scan_loop.table().stats(),
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

/// The frame format as Markdown, from the library's layout tables and
/// counter lists (`frames layout`; docs/firmware-runtime.md holds a copy,
/// checked by the frames tool's tests).
pub fn layout_markdown() -> String {
    use abtrack::track::TableStats;
    use abtrack::wire::{IntakeCounters, LoopCounters, ScanCounts, LAYOUTS};
    let mut out = String::new();
    for (name, kind, fields) in LAYOUTS {
        match kind {
            Some(k) => {
                out += &format!(
                    "**{name}** (type `0x{:02X}`, payload {} bytes, frame {} bytes)\n\n",
                    k.byte(),
                    k.payload_len(),
                    k.frame_len()
                )
            }
            None => {
                out += &format!(
                    "**{name}** ({HEADER_LEN} bytes; then the payload, then a {CRC_LEN}-byte CRC-32C of everything after the sync bytes)\n\n"
                )
            }
        }
        out += "| offset | bytes | field | holds |\n|---|---|---|---|\n";
        for (field, offset, width, doc) in fields {
            // Rustdoc links read as plain code here.
            let doc = doc.trim().replace("[`", "`").replace("`]", "`");
            let doc = doc.replace("`crate::scan`", "`abtrack::scan`");
            out += &format!("| {offset} | {width} | `{field}` | {doc} |\n");
        }
        out += "\n";
    }
    let lists: [(&str, &[&str], &[&str]); 5] = [
        (
            "`COUNTS` of the scan summary, u16 each, in order",
            &ScanCounts::NAMES,
            &ScanCounts::LABELS,
        ),
        (
            "`DECODER` of the health report, u32 each, in order",
            &DecoderStats::NAMES,
            &DecoderStats::LABELS,
        ),
        (
            "`INTAKE` of the health report, u32 each",
            &IntakeCounters::NAMES,
            &IntakeCounters::LABELS,
        ),
        (
            "`SCAN` of the health report, u32 each",
            &LoopCounters::NAMES,
            &LoopCounters::LABELS,
        ),
        (
            "`TABLE` of the health report, u32 each",
            &TableStats::NAMES,
            &TableStats::LABELS,
        ),
    ];
    for (title, names, labels) in lists {
        let items: Vec<String> = names
            .iter()
            .zip(labels)
            .map(|(n, l)| format!("`{n}` ({l})"))
            .collect();
        out += &format!("{title}: {}.\n\n", items.join(", "));
    }
    out
}

// ---------------------------------------------------------------------------
// Fault injection
// ---------------------------------------------------------------------------

/// A line or sensor fault, injected into the demo's input (the
/// [`TCAS_DEMO`] scenario, seed [`FAULT_INPUT_SEED`]) by [`fault_stream`]: the
/// fault-injection tests on the three boards, and `frames encode --fault`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fault {
    /// 8 KiB of random bytes first, then 1–64 random bytes before every
    /// 5th frame.
    Garbage,
    /// The same, drawn from the sync, type and length bytes.
    SyncGarbage,
    /// One payload bit flipped in every 20th frame (CRC errors).
    CrcErrors,
    /// Every 25th frame cut short by 2–20 bytes, mid-stream.
    Truncated,
    /// Every 25th frame with a length byte 8 too large and 8 more bytes.
    Oversize,
    /// Ten times the scan capacity of extra measurements in the scan at
    /// t = 30 s.
    Flood,
    /// The sensor silent for 10 s (the scans at t = 20 … 29 s missing).
    Gap,
    /// The sensor's clock steps back 10 s at t = 30 s.
    Backwards,
    /// The sensor's clock reads 12:00 (43.2e6 ms) at the start.
    FarClock,
    /// The sensor's clock jumps 40 days (past 2³¹ ms) at t = 30 s.
    Jump,
    /// After every 20th frame, a frame outside the envelope (x = 500 km,
    /// range 1000 km, altitude 200 000 ft in turn).
    OutOfRange,
    /// [`STORM_CLUTTER_PER_SCAN`] extra clutter measurements per scan,
    /// shuffled with the others, in the first scans ([`fault_stream`]'s
    /// `storm_scans`: every scan unless it says fewer).
    ClutterStorm,
    /// The scans in reverse time order.
    Reversed,
    /// 20 KiB of random bytes and no frame at all (not even the end of
    /// input: the firmware ends after 10 s of silence).
    GarbageOnly,
}

impl Fault {
    pub const ALL: [Fault; 14] = [
        Fault::Garbage,
        Fault::SyncGarbage,
        Fault::CrcErrors,
        Fault::Truncated,
        Fault::Oversize,
        Fault::Flood,
        Fault::Gap,
        Fault::Backwards,
        Fault::FarClock,
        Fault::Jump,
        Fault::OutOfRange,
        Fault::ClutterStorm,
        Fault::Reversed,
        Fault::GarbageOnly,
    ];

    pub const fn name(self) -> &'static str {
        match self {
            Fault::Garbage => "garbage",
            Fault::SyncGarbage => "sync-garbage",
            Fault::CrcErrors => "crc-errors",
            Fault::Truncated => "truncated",
            Fault::Oversize => "oversize",
            Fault::Flood => "flood",
            Fault::Gap => "gap",
            Fault::Backwards => "backwards",
            Fault::FarClock => "far-clock",
            Fault::Jump => "jump",
            Fault::OutOfRange => "out-of-range",
            Fault::ClutterStorm => "clutter-storm",
            Fault::Reversed => "reversed",
            Fault::GarbageOnly => "garbage-only",
        }
    }

    pub fn from_name(name: &str) -> Option<Fault> {
        Fault::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// The scan at which [`Fault::Flood`], [`Fault::Backwards`] and
/// [`Fault::Jump`] happen, and [`Fault::Gap`] ends.
pub const FAULT_SCAN: u32 = 30;
/// The seed of the demo input the faults are injected into (the demo's,
/// scripts/demo-input.sh).
pub const FAULT_INPUT_SEED: u64 = 1;
/// [`Fault::Gap`]: scans missing before [`FAULT_SCAN`].
pub const GAP_SCANS: u32 = 10;
/// [`Fault::ClutterStorm`]: clutter measurements added to each scan of
/// the storm.
pub const STORM_CLUTTER_PER_SCAN: usize = 200;
/// [`Fault::Backwards`]: the step, ms.
pub const BACKWARDS_MS: u32 = 10_000;
/// [`Fault::Jump`]: 40 days, ms (more than 2³¹).
pub const JUMP_MS: u32 = 40 * 86_400_000;
/// [`Fault::FarClock`]: 12:00, ms.
pub const FAR_CLOCK_MS: u32 = 43_200_000;

/// A faulty stream and what was put in it.
#[derive(Debug, Clone, Default)]
pub struct FaultStream {
    pub bytes: Vec<u8>,
    /// Numbered frames sent (damaged ones and the end-of-input frame
    /// included).
    pub frames: usize,
    /// Frames damaged or made up by the fault (corrupted, cut, oversize,
    /// out of range).
    pub damaged: usize,
    /// Random bytes put between frames.
    pub garbage_bytes: usize,
    /// Measurements added by the fault (flood, clutter storm).
    pub added: usize,
    /// Scan by scan, in sending order: (sensor time of the scan, scenario
    /// time in s, measurements sent).
    pub scans: Vec<(u32, f64, usize)>,
}

impl FaultStream {
    /// The scenario time (s) of a scan sent at sensor time `time_ms`.
    pub fn scenario_time(&self, time_ms: u32) -> Option<f64> {
        self.scans
            .iter()
            .find(|(t, _, _)| *t == time_ms)
            .map(|(_, s, _)| *s)
    }
}

/// The demo's input with `fault` injected; `capacity` is the board's
/// measurements per scan (for [`Fault::Flood`]); `storm_scans` the scans
/// [`Fault::ClutterStorm`] lasts, from the first ([`TCAS_DEMO_SCANS`] or
/// more: all of them).
pub fn fault_stream(
    fault: Fault,
    capacity: usize,
    storm_scans: usize,
    seed: u64,
) -> Result<FaultStream, String> {
    let mut rng = rng_from_seed(derive_seed(seed, 0xFA17));
    let mut out = FaultStream::default();
    if fault == Fault::GarbageOnly {
        out.bytes = (0..20 * 1024)
            .map(|_| uniform_index(&mut rng, 256) as u8)
            .collect();
        out.garbage_bytes = out.bytes.len();
        return Ok(out);
    }
    // The demo's input: scan k is the false reply before it (at k − 0.5 s)
    // and the interrogation cycle's replies (at k s).
    let mut scans: Vec<(u32, f64, Vec<MeasurementReport>)> = Vec::new();
    for reply in demo_scenario(FAULT_INPUT_SEED, TCAS_DEMO_SCANS) {
        let k = reply.time_s.ceil();
        let r = demo_report(&reply, 1)?;
        match scans.last_mut() {
            Some(scan) if scan.1 == k => scan.2.push(r),
            _ => scans.push((time_ms(k)?, k, vec![r])),
        }
    }
    let clutter = |rng: &mut crate::noise::SimRng, t: u32| {
        let mut u = || (uniform_index(rng, 1_000_001) as f64 / 1e6 - 0.5) * 10_000.0;
        MeasurementReport::cartesian_from_metres(t, 1, u(), u(), None).expect("inside ±5 km")
    };
    let shuffle = |rng: &mut crate::noise::SimRng, v: &mut Vec<MeasurementReport>| {
        for i in (1..v.len()).rev() {
            v.swap(i, uniform_index(rng, i + 1));
        }
    };
    let fault_ms = FAULT_SCAN * 1000;
    for (k, (t, _, reports)) in scans.iter_mut().enumerate() {
        let k_ms = *t;
        let shifted = match fault {
            Fault::Backwards if k_ms >= fault_ms => Some(t.wrapping_sub(BACKWARDS_MS)),
            Fault::Jump if k_ms >= fault_ms => Some(t.wrapping_add(JUMP_MS)),
            Fault::FarClock => Some(t.wrapping_add(FAR_CLOCK_MS)),
            _ => None,
        };
        if let Some(new) = shifted {
            *t = new;
            for r in reports.iter_mut() {
                r.time_ms = new;
            }
        }
        let extra = match fault {
            Fault::Flood if k_ms == fault_ms => 10 * capacity,
            Fault::ClutterStorm if k < storm_scans => STORM_CLUTTER_PER_SCAN,
            _ => 0,
        };
        if extra > 0 {
            for _ in 0..extra {
                reports.push(clutter(&mut rng, *t));
            }
            shuffle(&mut rng, reports);
            out.added += extra;
        }
    }
    match fault {
        Fault::Gap => {
            scans.retain(|(t, _, _)| !(fault_ms - GAP_SCANS * 1000..fault_ms).contains(t))
        }
        Fault::Reversed => scans.reverse(),
        _ => {}
    }

    let mut encoder = Encoder::new();
    let mut frame = [0u8; MAX_FRAME_LEN];
    let mut n = 0usize;
    if matches!(fault, Fault::Garbage | Fault::SyncGarbage) {
        let prefix = garbage(&mut rng, fault, 8 * 1024);
        out.garbage_bytes += prefix.len();
        out.bytes.extend(prefix);
    }
    for (t, scenario_t, reports) in &scans {
        out.scans.push((*t, *scenario_t, reports.len()));
        for r in reports {
            n += 1;
            if matches!(fault, Fault::Garbage | Fault::SyncGarbage) && n.is_multiple_of(5) {
                let len = 1 + uniform_index(&mut rng, 64);
                let g = garbage(&mut rng, fault, len);
                out.garbage_bytes += g.len();
                out.bytes.extend(g);
            }
            let len = encoder
                .encode(&Message::Measurement(*r), &mut frame)
                .expect("a frame fits");
            let mut bytes = frame[..len].to_vec();
            out.frames += 1;
            match fault {
                Fault::CrcErrors if n.is_multiple_of(20) => {
                    let bit = uniform_index(&mut rng, (len - HEADER_LEN - CRC_LEN) * 8);
                    bytes[HEADER_LEN + bit / 8] ^= 1 << (bit % 8);
                    out.damaged += 1;
                }
                Fault::Truncated if n.is_multiple_of(25) => {
                    let cut = 2 + uniform_index(&mut rng, 19);
                    bytes.truncate(len - cut);
                    out.damaged += 1;
                }
                Fault::Oversize if n.is_multiple_of(25) => {
                    bytes[3] = bytes[3].wrapping_add(8);
                    bytes.extend((0..8).map(|_| uniform_index(&mut rng, 256) as u8));
                    out.damaged += 1;
                }
                _ => {}
            }
            out.bytes.extend(bytes);
            if fault == Fault::OutOfRange && n.is_multiple_of(20) {
                let position = match (n / 20) % 3 {
                    0 => abtrack::wire::MeasuredPosition::Cartesian {
                        x_cm: 50_000_000,
                        y_cm: 0,
                    },
                    1 => abtrack::wire::MeasuredPosition::Polar {
                        range_cm: 100_000_000,
                        azimuth_bam: 0,
                    },
                    _ => abtrack::wire::MeasuredPosition::Cartesian { x_cm: 0, y_cm: 0 },
                };
                let bad = MeasurementReport {
                    time_ms: r.time_ms,
                    sensor: r.sensor,
                    position,
                    altitude_ft: ((n / 20) % 3 == 2).then_some(200_000),
                    altitude_25ft: false,
                    address: None,
                };
                let len = encoder
                    .encode(&Message::Measurement(bad), &mut frame)
                    .expect("a frame fits");
                out.bytes.extend_from_slice(&frame[..len]);
                out.frames += 1;
                out.damaged += 1;
            }
        }
    }
    let end = EndOfInput {
        time_ms: scans.last().map_or(0, |s| s.0),
    };
    let len = encoder
        .encode(&Message::End(end), &mut frame)
        .expect("a frame fits");
    out.bytes.extend_from_slice(&frame[..len]);
    out.frames += 1;
    Ok(out)
}

/// `len` garbage bytes: uniform, or from the bytes a frame header holds.
fn garbage(rng: &mut crate::noise::SimRng, fault: Fault, len: usize) -> Vec<u8> {
    const HEADERS: [u8; 10] = [0xAB, 0xCD, 0x01, 0x02, 0x81, 0x82, 0x84, 18, 16, 36];
    (0..len)
        .map(|_| {
            if fault == Fault::SyncGarbage {
                HEADERS[uniform_index(rng, HEADERS.len())]
            } else {
                uniform_index(rng, 256) as u8
            }
        })
        .collect()
}
