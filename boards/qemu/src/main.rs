//! abtrack demo firmware: the interrupt-driven scan loop.
//!
//! ```text
//! UART RX interrupt ─▶ scan::Intake (wire::Decoder, measurement queue) ─┐
//! SysTick ─▶ wakes main (WFI) ─▶ receive ─▶ scan::ScanLoop::collect ◀────┘
//!   ─▶ ScanLoop::on_tick: tracker scan, TCAS assessment
//!        ─▶ defmt log lines, report frames on UART TX, advisory lines
//! ```
//!
//! Measurement frames (`abtrack::wire`) arrive on the UART; the receive
//! interrupt decodes them and queues the measurements; every SysTick wakes
//! the main loop (and so does a measurement waiting in the queue), which
//! runs one function per stage: [`receive`] takes the
//! queued measurements into the scan being assembled (the scan clock of
//! `abtrack::scan` sorts them by the sensor's time), [`scan`] runs the scan
//! once the input has moved past it, [`show_advisories`] drives the advisory
//! lines, [`input_has_ended`] and [`run_is_over`] notice the end of the
//! input and of the run, and [`summarise`] and [`verdict`] end the run. The reports go out through [`Reporter`].
//!
//! The input is a recording, replayed faster than real time: a scan runs as
//! soon as the input has moved past its time (a measurement of a later scan
//! is at the head of the queue) or the input has ended (its end-of-input
//! frame arrived, or, without one, no byte for 10 s; SysTick, every 20 ms,
//! times that silence). QEMU's UART delivers a file as
//! fast as the firmware reads it, so the receive interrupt stops reading
//! as soon as it has queued a measurement (flow control: QEMU holds the
//! bytes back, as a sender would on a deasserted RTS line) and the main loop
//! resumes it once it has taken the measurement. So everything the firmware
//! does, the receiver's counters included, depends only on the bytes and
//! never on how fast the host runs QEMU: every run sends the same report
//! frames and logs the same lines but the stack high-water mark
//! (`demo_runs_are_identical_*` in host-tests/tests/it/firmware/fault_injection.rs
//! compares runs byte for byte, and with the same core run on the host).
//!
//! After the input ends it scans what is left, runs three idle scans,
//! prints a summary and
//! leaves QEMU with status 0 when the run was clean
//! (`abtrack::scan::RunVerdict`: something was used, at most one in ten
//! frames the sensor sent was lost or not used, no threat assessment
//! failed), and every scan ran and every report was sent; 1 otherwise. See
//! docs/firmware-runtime.md.
#![no_std]
#![no_main]

use abtrack_firmware::{board, demo_config, io};
// The real board (boards/nrf52840-dk): defmt over RTT and probe-rs's panic
// handler.
#[cfg(abtrack_board = "nrf52840-dk")]
use defmt_rtt as _;
#[cfg(abtrack_board = "nrf52840-dk")]
use panic_probe as _;

use core::cell::RefCell;
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering::Relaxed};

use abtrack::scan::{
    AdvisoryLines, Collected, Intake, MeasurementSource, RunVerdict, ScanConfig, ScanLoop,
};
use abtrack::tcas::Advisory;
use abtrack::track::RangeAzimuthTrack;
use abtrack::wire::{
    DecoderStats, Encoder, EndOfInput, Health, IntakeCounters, MeasurementReport, Message,
    ScanSummary, TrackReport, MAX_FRAMES_PER_BYTE, MAX_FRAME_LEN,
};

use abtrack::Numeric;
use board::Wide;
use cortex_m::interrupt::{free, Mutex};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::NVIC;
use cortex_m_rt::exception;

// Every board's capacities; this build uses its own board's.
#[cfg(abtrack_board = "microbit")]
use abtrack_firmware::capacity::microbit as capacity;
#[cfg(not(abtrack_board = "microbit"))]
use abtrack_firmware::capacity::mps2 as capacity;
use capacity::{MEASUREMENTS_PER_SCAN, QUEUE_LEN, TRACKS};

type DemoLoop = ScanLoop<Wide, RangeAzimuthTrack<Wide>, TRACKS, MEASUREMENTS_PER_SCAN>;
type DemoConfig = ScanConfig<Wide, abtrack::filter::range_azimuth::RangeAzimuthNoise<Wide>>;
type DemoIntake = Intake<QUEUE_LEN>;

/// SysTick period (QEMU's virtual clock, real time without `-icount`).
const TICK_MS: u32 = 20;
/// No byte for this many ticks (10 s) and no end-of-input frame: the input
/// has ended anyway (a recording without its end frame, a silent sensor).
/// Long, because a loaded host can stall QEMU's input for a second or more.
const SILENT_TICKS: u32 = 500;
/// Scans run after the input ended, before the summary.
const IDLE_SCANS: u32 = 3;
/// Confirmed tracks remembered for the summary.
const MAX_TRACKS_SEEN: usize = 32;

static TICKS: AtomicU32 = AtomicU32::new(0);
static LAST_RX_TICK: AtomicU32 = AtomicU32::new(0);
/// Set by the receive interrupt when it stopped reading (queue nearly
/// full), cleared by the main loop when it resumes it.
static RX_PAUSED: AtomicBool = AtomicBool::new(false);
static RX_PAUSES: AtomicU32 = AtomicU32::new(0);
/// Set when the receiver stopped for good: the end-of-input frame arrived,
/// or the line stayed silent.
static RX_ENDED: AtomicBool = AtomicBool::new(false);
/// The receive side: decoder and measurement queue, filled by the receive
/// interrupt, emptied by the main loop one measurement per critical
/// section.
static RX: Mutex<RefCell<DemoIntake>> = Mutex::new(RefCell::new(Intake::new()));

#[exception]
fn SysTick() {
    // The only writer: a load and a store (the Cortex-M0 has no atomic
    // read-modify-write).
    TICKS.store(TICKS.load(Relaxed).wrapping_add(1), Relaxed);
}

/// The UART receive interrupt (installed into board.rs's DefaultHandler).
fn on_interrupt(irqn: i16) -> bool {
    if irqn != io::UART_RX_IRQ as i16 {
        return false;
    }
    free(|cs| {
        // `try_`: no borrow is ever held across an interrupt, and this way no
        // panic path exists for one.
        let Ok(mut intake) = RX.borrow(cs).try_borrow_mut() else {
            return;
        };
        loop {
            if io::uart_overrun() {
                intake.count_overrun();
            }
            if intake.input_ended().is_some() {
                // The recording is over: read nothing after its end.
                NVIC::mask(io::UartRxIrq);
                RX_ENDED.store(true, Relaxed);
                break;
            }
            if intake.queued() > 0 || !intake.can_take_byte() {
                // Flow control, in lock-step with the main loop: leave the
                // byte in the UART until main has taken the measurement
                // queued (main resumes us). What has been received when a
                // scan runs then depends only on the bytes, not on timing.
                NVIC::mask(io::UartRxIrq);
                RX_PAUSED.store(true, Relaxed);
                RX_PAUSES.store(RX_PAUSES.load(Relaxed).wrapping_add(1), Relaxed);
                break;
            }
            let Some(byte) = io::uart_read() else { break };
            intake.push(byte);
            LAST_RX_TICK.store(TICKS.load(Relaxed), Relaxed);
        }
    });
    true
}

/// The main loop's access to the receive side: one short critical section
/// per call.
struct SharedIntake;

impl SharedIntake {
    fn with<R>(f: impl FnOnce(&mut DemoIntake) -> R) -> Option<R> {
        free(|cs| {
            RX.borrow(cs)
                .try_borrow_mut()
                .ok()
                .map(|mut intake| f(&mut intake))
        })
    }
}

impl MeasurementSource for SharedIntake {
    fn peek(&mut self) -> Option<MeasurementReport> {
        Self::with(|i| i.peek()).flatten()
    }
    fn pop(&mut self) -> Option<MeasurementReport> {
        Self::with(|i| i.pop()).flatten()
    }
    fn receiver_counters(&mut self) -> (DecoderStats, IntakeCounters) {
        Self::with(|i| i.receiver_counters()).unwrap_or_default()
    }
}

/// Unmasks the receive interrupt again once the queue is empty, and pends
/// it so that the byte left waiting in the UART is read. True if it did.
fn resume_receiver() -> bool {
    if !RX_PAUSED.load(Relaxed) || RX_ENDED.load(Relaxed) {
        return false;
    }
    if SharedIntake::with(|i| i.queued() == 0 && i.can_take_byte()) != Some(true) {
        return false;
    }
    RX_PAUSED.store(false, Relaxed);
    // SAFETY: the handler and the intake are installed; unmasking is not
    // done inside a critical section.
    unsafe { NVIC::unmask(io::UartRxIrq) };
    NVIC::pend(io::UartRxIrq);
    true
}

/// Whether the main loop has something to do: the receiver paused with a
/// measurement queued, or it stopped.
fn receiver_waits() -> bool {
    RX_PAUSED.load(Relaxed) || RX_ENDED.load(Relaxed)
}

/// Sleeps until the next SysTick or until the receiver waits for the main
/// loop. Interrupts are off between the check and the WFI, which still
/// wakes on a pending interrupt, so no event is missed.
fn wait_for_event(seen: &mut u32) {
    loop {
        let now = TICKS.load(Relaxed);
        if now != *seen || receiver_waits() {
            *seen = now;
            return;
        }
        free(|_| {
            if TICKS.load(Relaxed) == *seen && !receiver_waits() {
                cortex_m::asm::wfi();
            }
        });
    }
}

// ---------------------------------------------------------------------------
// Reports
// ---------------------------------------------------------------------------

#[derive(Clone, Copy)]
struct TrackSeen {
    id: u32,
    first_ms: u32,
    last_ms: u32,
    reports: u32,
    worst: Advisory,
}

/// Where the scan loop's reports go: frames on UART TX (numbered by an
/// [`Encoder`]), defmt lines, and a record of the confirmed tracks for the
/// summary.
///
/// The log keeps the wire's order: a scan's track lines, each with the
/// scan's time, then its summary line (no buffer of a scan's track reports:
/// on the micro:bit that was 44 bytes a track).
struct Reporter {
    encoder: Encoder,
    seen: heapless::Vec<TrackSeen, MAX_TRACKS_SEEN>,
    /// Reports of confirmed tracks beyond the first [`MAX_TRACKS_SEEN`]
    /// (not listed: a count of reports, not of tracks).
    reports_not_listed: u32,
    frames_sent: u32,
    frames_not_sent: u32,
    /// The last health report sent.
    health: Health,
}

/// `ms` as seconds and milliseconds, for log lines.
fn secs(ms: u32) -> (u32, u32) {
    (ms / 1000, ms % 1000)
}

fn metres(cm: i32) -> f32 {
    cm as f32 / 100.0
}

impl Reporter {
    const fn new() -> Self {
        Reporter {
            encoder: Encoder::new(),
            seen: heapless::Vec::new(),
            reports_not_listed: 0,
            frames_sent: 0,
            frames_not_sent: 0,
            health: Health {
                time_ms: 0,
                decoder: DecoderStats::new(),
                intake: IntakeCounters::new(),
                scan: abtrack::wire::LoopCounters::new(),
                table: abtrack::track::TableStats::new(),
            },
        }
    }

    fn report(&mut self, message: &Message) {
        match message {
            Message::Track(t) => {
                self.remember(t);
                log_track(t);
            }
            Message::Scan(s) => log_scan(s),
            Message::Health(h) => self.health = *h,
            Message::Measurement(_) | Message::End(_) => {}
        }
        self.send(message);
    }

    fn send(&mut self, message: &Message) {
        let mut frame = [0u8; MAX_FRAME_LEN];
        let Ok(len) = self.encoder.encode(message, &mut frame) else {
            self.frames_not_sent = self.frames_not_sent.saturating_add(1);
            return;
        };
        for &b in frame.iter().take(len) {
            if !io::uart_write(b) {
                self.frames_not_sent = self.frames_not_sent.saturating_add(1);
                return;
            }
        }
        self.frames_sent = self.frames_sent.saturating_add(1);
    }

    fn remember(&mut self, t: &TrackReport) {
        if let Some(s) = self.seen.iter_mut().find(|s| s.id == t.track_id) {
            s.last_ms = t.time_ms;
            s.reports = s.reports.saturating_add(1);
            s.worst = s.worst.max(t.advisory);
            return;
        }
        let new = TrackSeen {
            id: t.track_id,
            first_ms: t.time_ms,
            last_ms: t.time_ms,
            reports: 1,
            worst: t.advisory,
        };
        if self.seen.push(new).is_err() {
            self.reports_not_listed = self.reports_not_listed.saturating_add(1);
        }
    }
}

fn log_scan(s: &ScanSummary) {
    let (sec, ms) = secs(s.time_ms);
    let ra = s.ra.map_or("", |ra| ra.name());
    let coc = if s.clear_of_conflict {
        ", CLEAR OF CONFLICT"
    } else {
        ""
    };
    defmt::println!(
        "t={=u32}.{=u32:03} s | {} | {=str} {=str}{=str}",
        sec,
        ms,
        s.counts,
        s.highest_advisory.name(),
        ra,
        coc
    );
}

/// One track: id, status, Mode S address (or "Mode C"), position and
/// velocity, altitude, advisory with the RA's sense and strength, tau.
fn log_track(t: &TrackReport) {
    let (x, y) = (metres(t.x_cm), metres(t.y_cm));
    let (vx, vy) = (metres(t.vx_cm_per_s), metres(t.vy_cm_per_s));
    let (id, status, advisory) = (t.track_id, t.status.as_str(), t.advisory.name());
    let ra = t.ra.map_or("", |ra| ra.name());
    // 0 never is a Mode S address the demo uses; "Mode C" says it is absent.
    let (address, mode) = match t.address {
        Some(a) => (a.get(), "Mode S"),
        None => (0, "Mode C"),
    };
    let alt = t.altitude;
    let tau = t.range_tau_ds.map(|d| f32::from(d) / 10.0);
    let (sec, ms) = secs(t.time_ms);
    match (alt, tau) {
        (Some((alt, rate)), Some(tau)) => defmt::println!(
            "t={=u32}.{=u32:03} s   track {=u32} {=str} {=str} {=u32:06x} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s {=i32} ft {=i16} ft/min | {=str} {=str} | tau {=f32} s",
            sec, ms, id, status, mode, address, x, y, vx, vy, alt, rate, advisory, ra, tau
        ),
        (Some((alt, rate)), None) => defmt::println!(
            "t={=u32}.{=u32:03} s   track {=u32} {=str} {=str} {=u32:06x} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s {=i32} ft {=i16} ft/min | {=str} {=str} | no tau",
            sec, ms, id, status, mode, address, x, y, vx, vy, alt, rate, advisory, ra
        ),
        (None, Some(tau)) => defmt::println!(
            "t={=u32}.{=u32:03} s   track {=u32} {=str} {=str} {=u32:06x} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s no altitude | {=str} {=str} | tau {=f32} s",
            sec, ms, id, status, mode, address, x, y, vx, vy, advisory, ra, tau
        ),
        (None, None) => defmt::println!(
            "t={=u32}.{=u32:03} s   track {=u32} {=str} {=str} {=u32:06x} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s no altitude | {=str} {=str} | no tau",
            sec, ms, id, status, mode, address, x, y, vx, vy, advisory, ra
        ),
    }
}

// ---------------------------------------------------------------------------
// Stages
// ---------------------------------------------------------------------------

/// The run's state between stages.
struct Run {
    seen_ticks: u32,
    /// The input has ended (end-of-input frame, or silence).
    ended: bool,
    /// The end-of-input frame, if that is how it ended.
    end_frame: Option<EndOfInput>,
    idle_scans: u32,
    scan_errors: u32,
    /// Sensor time of the last scan that used a measurement.
    last_input_ms: Option<u32>,
}

/// Banner and configuration; a configuration the number type refuses ends
/// the run.
fn start() -> DemoConfig {
    defmt::println!(
        "abtrack scan-loop demo on {=str} ({=str}), tracker in {=str}",
        board::BOARD,
        board::CORE,
        Wide::NAME
    );
    defmt::println!(
        "capacity: {=usize} tracks, {=usize} measurements per scan, queue of {=usize}; RAM: scan loop {=usize} B, receiver {=usize} B",
        TRACKS,
        MEASUREMENTS_PER_SCAN,
        QUEUE_LEN,
        core::mem::size_of::<DemoLoop>(),
        core::mem::size_of::<DemoIntake>()
    );
    {
        use abtrack::filter::altitude::AltitudeState;
        use abtrack::tcas::{IntruderTrack, RangeTracker, ThreatState};
        use core::mem::size_of;
        // One track more, for the loop's bytes per track.
        type LoopWithOneMore =
            ScanLoop<Wide, RangeAzimuthTrack<Wide>, { TRACKS + 1 }, MEASUREMENTS_PER_SCAN>;
        defmt::println!(
            "RAM per track: {=usize} B in the scan loop, of which table slot {=usize} B, TCAS intruder {=usize} B (range tracker {=usize}, altitude state {=usize}, threat state {=usize})",
            size_of::<LoopWithOneMore>() - size_of::<DemoLoop>(),
            size_of::<abtrack::track::TrackSlot<Wide, RangeAzimuthTrack<Wide>>>(),
            size_of::<IntruderTrack<Wide>>(),
            size_of::<RangeTracker<Wide>>(),
            size_of::<AltitudeState<Wide>>(),
            size_of::<ThreatState<Wide>>()
        );
    }
    defmt::println!(
        "input: wire frames on {=str}, receive IRQ {=u16}; SysTick every {=u32} ms; a scan every {=u32} ms of the sensor's clock; advisory lines: {=str}",
        io::UART_NAME,
        io::UART_RX_IRQ,
        TICK_MS,
        demo_config::SCAN_PERIOD_MS,
        io::PINS_NAME
    );
    match demo_config::demo_config::<Wide, _>() {
        Ok(c) => c,
        Err(e) => {
            defmt::error!("configuration: {=str}", e);
            board::exit(false)
        }
    }
}

/// The UART with its receive interrupt, and SysTick.
fn start_peripherals() {
    let Some(mut core) = cortex_m::Peripherals::take() else {
        defmt::error!("core peripherals already taken");
        board::exit(false)
    };
    io::uart_init();
    board::set_interrupt_handler(on_interrupt);
    // SAFETY: the handler and the intake are installed; not in a critical
    // section.
    unsafe { NVIC::unmask(io::UartRxIrq) };
    let syst = &mut core.SYST;
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(io::CORE_CLOCK_HZ / 1000 * TICK_MS - 1);
    syst.clear_current();
    syst.enable_counter();
    syst.enable_interrupt();
}

/// Takes the queued measurements into the scan being assembled, resuming
/// the paused receiver as room appears, until the queue is empty or the
/// scan is due (the input has moved past it). True if it is due.
fn receive(config: &DemoConfig, scan_loop: &mut DemoLoop) -> bool {
    loop {
        let collected = scan_loop.collect(config, &mut SharedIntake);
        // A resumed receiver reads at once (its interrupt is pending): take
        // what it queued before deciding.
        let resumed = resume_receiver();
        if collected == Collected::ScanDue {
            return true;
        }
        if !resumed {
            return false;
        }
    }
}

/// Whether the input has ended: the end-of-input frame arrived, or the line
/// stayed silent for [`SILENT_TICKS`]. The first time, the receiver stops
/// for good and its decoder abandons a partial frame.
fn input_has_ended(run: &mut Run) -> bool {
    if run.ended {
        return true;
    }
    // The last byte's tick first: the tick read after it is never earlier,
    // so the difference cannot wrap.
    let last_rx = LAST_RX_TICK.load(Relaxed);
    let silent = TICKS.load(Relaxed).wrapping_sub(last_rx) >= SILENT_TICKS;
    if !(RX_ENDED.load(Relaxed) || silent) {
        return false;
    }
    NVIC::mask(io::UartRxIrq);
    RX_ENDED.store(true, Relaxed);
    run.ended = true;
    run.end_frame = SharedIntake::with(|i| {
        i.line_idle();
        i.input_ended()
    })
    .flatten();
    true
}

/// One scan and its reports; returns the scan's summary.
fn scan(
    config: &DemoConfig,
    scan_loop: &mut DemoLoop,
    reporter: &mut Reporter,
    run: &mut Run,
) -> Option<ScanSummary> {
    match scan_loop.on_tick(config, &mut SharedIntake, |m| reporter.report(m)) {
        Ok(tick) => {
            if tick.summary.counts.used > 0 {
                run.last_input_ms = Some(tick.summary.time_ms);
            }
            Some(tick.summary)
        }
        Err(e) => {
            defmt::error!("scan refused: {}", e);
            run.scan_errors = run.scan_errors.saturating_add(1);
            None
        }
    }
}

/// Drives the advisory lines (the board's TA and RA outputs) for the
/// scan's most severe advisory; logs a change, with the RA's sense, and the
/// clear of conflict.
fn show_advisories(lines: &mut AdvisoryLines<io::AdvisoryPin>, summary: &ScanSummary) {
    let before = (lines.pins().0.is_high(), lines.pins().1.is_high());
    let (sec, ms) = secs(summary.time_ms);
    if let Ok(true) = lines.show(summary.highest_advisory) {
        let (ta, ra) = (lines.pins().0.is_high(), lines.pins().1.is_high());
        if (ta, ra) != before {
            defmt::println!(
                "advisory lines at t={=u32}.{=u32:03} s: TA {=bool}, RA {=bool} {=str}",
                sec,
                ms,
                ta,
                ra,
                summary.ra.map_or("", |r| r.name())
            );
        }
    }
    if summary.clear_of_conflict {
        defmt::println!("clear of conflict at t={=u32}.{=u32:03} s", sec, ms);
    }
}

/// After the input ended and everything received was scanned, counts the
/// idle scans; true after [`IDLE_SCANS`] of them.
fn run_is_over(used: u16, scan_loop: &mut DemoLoop, run: &mut Run) -> bool {
    let queued = SharedIntake::with(|i| i.queued()).unwrap_or(0);
    if !run.ended {
        return false;
    }
    if queued == 0 {
        // Nothing more can arrive to confirm a held out-of-window
        // measurement.
        scan_loop.finish();
    }
    if used == 0 && queued == 0 && scan_loop.held() == 0 {
        run.idle_scans = run.idle_scans.saturating_add(1);
    } else {
        run.idle_scans = 0;
    }
    run.idle_scans >= IDLE_SCANS
}

/// The end-of-run summary: the lifetime counters, the confirmed tracks,
/// the reports sent. Only the stack high-water mark can differ from run to
/// run (a SysTick exception landing at the deepest point of a scan).
fn summarise(
    scan_loop: &DemoLoop,
    reporter: &Reporter,
    lines: &AdvisoryLines<io::AdvisoryPin>,
    run: &Run,
) -> Health {
    let (decoder, intake) = SharedIntake.receiver_counters();
    let health = Health {
        time_ms: scan_loop.scan_time_ms(),
        decoder,
        intake,
        scan: *scan_loop.counters(),
        table: *scan_loop.table().stats(),
    };
    match run.end_frame {
        Some(e) => {
            let (sec, ms) = secs(e.time_ms);
            defmt::println!(
                "input ended: end-of-input frame (sensor clock t={=u32}.{=u32:03} s)",
                sec,
                ms
            );
        }
        None => defmt::println!(
            "input ended: no byte for {=u32} s and no end-of-input frame",
            SILENT_TICKS * TICK_MS / 1000
        ),
    }
    match run.last_input_ms {
        Some(t) => {
            let (sec, ms) = secs(t);
            defmt::println!(
                "last measurements used in the scan at t={=u32}.{=u32:03} s; {=u32} idle scans after the input",
                sec,
                ms,
                IDLE_SCANS
            );
        }
        None => defmt::error!("no measurement was used"),
    }
    defmt::println!("receiver: {}", health.decoder);
    defmt::println!("intake: {}", health.intake);
    defmt::println!("scan loop: {}", health.scan);
    defmt::println!("track table: {}", health.table);
    if reporter.reports_not_listed == 0 {
        defmt::println!("confirmed tracks ({=usize}):", reporter.seen.len());
    } else {
        defmt::println!(
            "confirmed tracks (the first {=usize}; {=u32} reports of later ones not listed):",
            reporter.seen.len(),
            reporter.reports_not_listed
        );
    }
    for s in reporter.seen.iter() {
        let (a, am) = secs(s.first_ms);
        let (b, bm) = secs(s.last_ms);
        defmt::println!(
            "    id {=u32}: reported t={=u32}.{=u32:03}..{=u32}.{=u32:03} s ({=u32} scans), worst advisory {=str}",
            s.id,
            a,
            am,
            b,
            bm,
            s.reports,
            s.worst.name()
        );
    }
    defmt::println!(
        "reports: {=u32} frames sent on the UART, {=u32} not sent; advisory lines changed {=u32} times, now TA {=bool}, RA {=bool}",
        reporter.frames_sent,
        reporter.frames_not_sent,
        lines.changes(),
        lines.pins().0.is_high(),
        lines.pins().1.is_high()
    );
    defmt::println!(
        "flow control paused the receiver {=u32} times (it keeps {=usize} queue slots free)",
        RX_PAUSES.load(Relaxed),
        MAX_FRAMES_PER_BYTE
    );
    board::report_stack();
    health
}

/// The exit status: the run's input verdict, and every scan ran and every
/// report was sent.
fn verdict(health: &Health, reporter: &Reporter, run: &Run) -> bool {
    let v = RunVerdict::from_health(health);
    let clean = v.is_clean() && run.scan_errors == 0 && reporter.frames_not_sent == 0;
    defmt::println!(
        "verdict: {=str}: the sensor sent {=u32} frames, {=u32} lost or not used (at most 1 in {=u32} allowed), {=u32} measurements used; {=u32} scans refused, {=u32} reports not sent, {=u32} assessment errors",
        if clean { "clean" } else { "NOT CLEAN" },
        v.sent,
        v.lost,
        abtrack::scan::MAX_LOST_FRACTION_INVERSE,
        v.used,
        run.scan_errors,
        reporter.frames_not_sent,
        v.assessment_errors
    );
    clean
}

#[cortex_m_rt::entry]
fn main() -> ! {
    // cortex-m-rt turns this into a `&'static mut`, initialised at compile
    // time (no copy through the stack, no unsafe here).
    static mut SCAN_LOOP: DemoLoop = ScanLoop::new();
    static mut REPORTER: Reporter = Reporter::new();

    board::paint_stack();
    let config = start();
    let scan_loop: &mut DemoLoop = SCAN_LOOP;
    let reporter: &mut Reporter = REPORTER;
    let mut lines = AdvisoryLines::new(io::AdvisoryPin::traffic(), io::AdvisoryPin::resolution());
    start_peripherals();

    let mut run = Run {
        seen_ticks: TICKS.load(Relaxed),
        ended: false,
        end_frame: None,
        idle_scans: 0,
        scan_errors: 0,
        last_input_ms: None,
    };
    loop {
        wait_for_event(&mut run.seen_ticks);
        let mut due = receive(&config, scan_loop);
        let ended = input_has_ended(&mut run);
        if ended {
            due |= receive(&config, scan_loop);
        }
        if !(due || ended) {
            continue;
        }
        let used = match scan(&config, scan_loop, reporter, &mut run) {
            Some(summary) => {
                show_advisories(&mut lines, &summary);
                summary.counts.used
            }
            None => 0,
        };
        if run_is_over(used, scan_loop, &mut run) {
            break;
        }
    }
    let health = summarise(scan_loop, reporter, &lines, &run);
    board::exit(verdict(&health, reporter, &run))
}
