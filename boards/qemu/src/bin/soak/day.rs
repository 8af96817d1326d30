//! The soak's day (not built for the micro:bit).

use crate::board::{self, Native, Wide};
use crate::demo_config;
use crate::icount::InstructionCounter;
use crate::synth;
use crate::synth::{Orbit, SOAK_MAX_PER_SCAN, SOAK_TARGETS};
use abtrack::scan::{Intake, ScanLoop};
use abtrack::track::FixedGainTrack;
use abtrack::wire::{Encoder, MeasurementReport, Message, TrackReport, MAX_FRAME_LEN};
use abtrack::Numeric;

/// Scans of the day (86,400 = 24 h at 1 Hz), or `ABTRACK_SOAK_SCANS`.
const SCANS: u32 = match option_env!("ABTRACK_SOAK_SCANS") {
    Some(s) => parse_u32(s),
    None => 86_400,
};
/// Scans per report line: one hour.
const HOUR: u32 = 3600;
/// Capacities: the 45 intruders and room for clutter tracks.
const TRACKS: usize = 64;
const PER_SCAN: usize = 96;
const QUEUE: usize = 128;
/// An intruder is tracked when a confirmed track is this close (m).
const ACCURACY_M: f32 = 100.0;
/// A confirmed track farther than this from every intruder is a ghost (m).
const GHOST_M: f32 = 200.0;

const fn parse_u32(s: &str) -> u32 {
    let bytes = s.as_bytes();
    let mut value = 0u32;
    let mut i = 0;
    while i < bytes.len() {
        value = value * 10 + (bytes[i] - b'0') as u32;
        i += 1;
    }
    value
}

type SoakLoop = ScanLoop<Native, FixedGainTrack<Wide>, TRACKS, PER_SCAN>;

/// Figures over one hour (or the day).
#[derive(Clone, Copy, Default)]
struct Figures {
    scans: u32,
    receive_sum: u64,
    receive_max: u32,
    scan_sum: u64,
    scan_max: u32,
    confirmed_sum: u32,
    confirmed_max: u32,
    tracked_sum: u32,
    tracked_min: u32,
    ghost_reports: u32,
    ghosts_max: u32,
    squared_error_sum: f32,
    matched: u32,
    breaks: u32,
    started: u32,
    refused_table_full: u32,
}

impl Figures {
    fn log(&self, label: &str, index: u32) {
        let n = self.scans.max(1);
        defmt::println!(
            "{=str} {=u32}: {=u32} scans; instructions per scan: receive mean {=u32} max {=u32}, scan mean {=u32} max {=u32}; confirmed tracks mean {=f32} max {=u32}; intruders tracked mean {=f32} min {=u32}; ghosts max {=u32} ({=u32} reports); rms error {=f32} m; track breaks {=u32}; tracks started {=u32}, refused (table full) {=u32}",
            label,
            index,
            self.scans,
            (self.receive_sum / n as u64) as u32,
            self.receive_max,
            (self.scan_sum / n as u64) as u32,
            self.scan_max,
            self.confirmed_sum as f32 / n as f32,
            self.confirmed_max,
            self.tracked_sum as f32 / n as f32,
            self.tracked_min,
            self.ghosts_max,
            self.ghost_reports,
            libm::sqrtf(self.squared_error_sum / self.matched.max(1) as f32),
            self.breaks,
            self.started,
            self.refused_table_full
        );
    }

    fn add(&mut self, o: &Figures) {
        let tracked_min = if self.scans == 0 {
            o.tracked_min
        } else {
            self.tracked_min.min(o.tracked_min)
        };
        self.scans += o.scans;
        self.receive_sum += o.receive_sum;
        self.receive_max = self.receive_max.max(o.receive_max);
        self.scan_sum += o.scan_sum;
        self.scan_max = self.scan_max.max(o.scan_max);
        self.confirmed_sum += o.confirmed_sum;
        self.confirmed_max = self.confirmed_max.max(o.confirmed_max);
        self.tracked_sum += o.tracked_sum;
        self.tracked_min = tracked_min;
        self.ghost_reports += o.ghost_reports;
        self.ghosts_max = self.ghosts_max.max(o.ghosts_max);
        self.squared_error_sum += o.squared_error_sum;
        self.matched += o.matched;
        self.breaks += o.breaks;
        self.started += o.started;
        self.refused_table_full += o.refused_table_full;
    }
}

/// The track reports of one scan, checked against the truth after the
/// scan's timing.
struct Reports {
    tracks: heapless::Vec<TrackReport, TRACKS>,
    confirmed: u32,
    started: u32,
    refused_table_full: u32,
}

#[cortex_m_rt::entry]
fn main() -> ! {
    static mut SCAN_LOOP: SoakLoop = ScanLoop::new();
    static mut INTAKE: Intake<QUEUE> = Intake::new();
    static mut REPORTS: Reports = Reports {
        tracks: heapless::Vec::new(),
        confirmed: 0,
        started: 0,
        refused_table_full: 0,
    };

    board::paint_stack();
    let scan_loop: &mut SoakLoop = SCAN_LOOP;
    let intake: &mut Intake<QUEUE> = INTAKE;
    let reports: &mut Reports = REPORTS;
    let config = match demo_config::config_for_square::<Native, _>(synth::SOAK_HALF_WIDTH_M) {
        Ok(c) => c,
        Err(e) => {
            defmt::error!("configuration: {=str}", e);
            board::exit(false)
        }
    };
    let Some(core) = cortex_m::Peripherals::take() else {
        defmt::error!("core peripherals already taken");
        board::exit(false)
    };
    let Some(counter) = InstructionCounter::new(core.SYST) else {
        defmt::error!("SysTick does not count: run under -icount shift=0");
        board::exit(false)
    };
    defmt::println!(
        "abtrack soak on {=str} ({=str}), tracker in {=str}: {=u32} scans at 1 Hz, {=usize} intruders, Pd {=f32}, {=usize} clutter per scan over +-{=f32} km; capacity {=usize} tracks, {=usize} per scan; {=f32} instructions per SysTick tick (-icount shift=0)",
        board::BOARD,
        board::CORE,
        Wide::NAME,
        SCANS,
        SOAK_TARGETS,
        synth::SOAK_DETECTION_PROBABILITY as f32,
        synth::SOAK_CLUTTER_PER_SCAN,
        (synth::SOAK_HALF_WIDTH_M / 1000.0) as f32,
        TRACKS,
        PER_SCAN,
        counter.instructions_per_tick()
    );

    let mut encoder = Encoder::new();
    let mut measurements = [MeasurementReport {
        time_ms: 0,
        sensor: 0,
        position: abtrack::wire::MeasuredPosition::Cartesian { x_cm: 0, y_cm: 0 },
        altitude_ft: None,
        altitude_25ft: false,
        address: None,
    }; SOAK_MAX_PER_SCAN];
    let mut hour = Figures::default();
    let mut day = Figures::default();
    // The id of the track that last followed each intruder.
    let mut following = [0u32; SOAK_TARGETS];
    let mut ok = true;
    for k in 0..SCANS {
        let n = synth::soak_scan(k, &mut measurements);

        let start = counter.now();
        for m in measurements.iter().take(n) {
            let mut frame = [0u8; MAX_FRAME_LEN];
            if let Ok(len) = encoder.encode(&Message::Measurement(*m), &mut frame) {
                for &b in frame.iter().take(len) {
                    intake.push(b);
                }
            }
        }
        let receive = counter.since(start);

        reports.tracks.clear();
        let start = counter.now();
        let tick = scan_loop.on_tick(&config, intake, |message| {
            if let Message::Track(t) = message {
                let _ = reports.tracks.push(*t);
            }
            if let Message::Scan(s) = message {
                reports.confirmed = u32::from(s.counts.confirmed_tracks);
                reports.started = u32::from(s.counts.started);
                reports.refused_table_full = u32::from(s.counts.refused_table_full);
            }
        });
        let scan = counter.since(start);
        if tick.is_err() {
            defmt::error!("scan {=u32} refused", k);
            ok = false;
            break;
        }

        let f = check_against_truth(k, reports, &mut following);
        hour.add(&Figures {
            scans: 1,
            receive_sum: receive as u64,
            receive_max: receive,
            scan_sum: scan as u64,
            scan_max: scan,
            ..f
        });
        if (k + 1) % HOUR == 0 || k + 1 == SCANS {
            hour.log("hour", k / HOUR);
            day.add(&hour);
            hour = Figures::default();
        }
    }
    day.log("day", SCANS);
    defmt::println!("receiver: {}", intake.decoder().stats());
    defmt::println!("intake: {}", intake.counters());
    defmt::println!("scan loop: {}", scan_loop.counters());
    defmt::println!("track table: {}", scan_loop.table().stats());
    // The end state, for the comparison with the f64 run on the host.
    for t in reports.tracks.iter() {
        defmt::println!(
            "end track {=u32}: x {=i32} cm, y {=i32} cm, vx {=i32} cm/s, vy {=i32} cm/s",
            t.track_id,
            t.x_cm,
            t.y_cm,
            t.vx_cm_per_s,
            t.vy_cm_per_s
        );
    }
    board::report_stack();
    board::exit(ok)
}

/// The scan's figures against the truth: intruders tracked within the
/// budget, ghosts, errors, track breaks.
fn check_against_truth(k: u32, reports: &Reports, following: &mut [u32; SOAK_TARGETS]) -> Figures {
    let mut truth = [[0f32; 2]; SOAK_TARGETS];
    for (i, p) in truth.iter_mut().enumerate() {
        let s = Orbit::soak(i).at(f64::from(k));
        *p = [s.position[0] as f32, s.position[1] as f32];
    }
    let mut f = Figures {
        confirmed_sum: reports.confirmed,
        confirmed_max: reports.confirmed,
        started: reports.started,
        refused_table_full: reports.refused_table_full,
        ..Figures::default()
    };
    let mut tracked = 0u32;
    for (i, p) in truth.iter().enumerate() {
        let mut best: Option<(f32, u32)> = None;
        for t in reports.tracks.iter() {
            let dx = t.x_cm as f32 / 100.0 - p[0];
            let dy = t.y_cm as f32 / 100.0 - p[1];
            let d2 = dx * dx + dy * dy;
            if best.is_none_or(|(b, _)| d2 < b) {
                best = Some((d2, t.track_id));
            }
        }
        if let Some((d2, id)) = best.filter(|(d2, _)| *d2 < ACCURACY_M * ACCURACY_M) {
            tracked += 1;
            f.squared_error_sum += d2;
            f.matched += 1;
            if let Some(previous) = following.get_mut(i) {
                if *previous != 0 && *previous != id {
                    f.breaks += 1;
                }
                *previous = id;
            }
        }
    }
    let mut ghosts = 0u32;
    for t in reports.tracks.iter() {
        let near = truth.iter().any(|p| {
            let dx = t.x_cm as f32 / 100.0 - p[0];
            let dy = t.y_cm as f32 / 100.0 - p[1];
            dx * dx + dy * dy < GHOST_M * GHOST_M
        });
        if !near {
            ghosts += 1;
        }
    }
    f.tracked_sum = tracked;
    f.tracked_min = tracked;
    f.ghost_reports = ghosts;
    f.ghosts_max = ghosts;
    f
}
