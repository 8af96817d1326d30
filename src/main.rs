//! abtrack demo firmware: the interrupt-driven scan loop.
//!
//! ```text
//! UART RX interrupt ─▶ scan::Intake (wire::Decoder) ─▶ spsc queue ─┐
//! SysTick ─▶ wakes main (WFI) ─▶ scan::ScanLoop::on_tick ◀────────┘
//!   tracker scan ─▶ TCAS assessment ─▶ defmt log lines
//!                                    ─▶ report frames on UART TX
//!                                    ─▶ advisory lines (OutputPin)
//! ```
//!
//! Measurement frames (`abtrack::wire`) arrive on the UART; the receive
//! interrupt decodes them and queues the measurements; every SysTick wakes
//! the main loop, which runs one scan per sensor period (1 s of the
//! recording's clock) on the queued measurements, logs the tracks, the
//! per-stage counts and the advisories through defmt, sends track, scan and
//! link reports back as frames on the UART, and drives the traffic and
//! resolution advisory lines. When the input has ended (the line idle for a
//! second) it runs a few more scans, prints a summary and leaves QEMU:
//! status 0, or 1 if no measurement arrived, a scan was refused or a report
//! could not be sent.
//!
//! The input is a recording, replayed faster than real time: SysTick fires
//! every 20 ms and each tick is one 1 s scan of the recording's clock (50×).
//! QEMU's UART delivers a file as fast as the firmware reads it, so two
//! things a live sensor link would not need keep the replay faithful: the
//! receive interrupt stops reading while the queue is nearly full (flow
//! control: QEMU holds the bytes back, as a sender would on a deasserted
//! RTS line), and a scan waits until the input has moved past its time (or
//! gone idle), so each scan gets exactly its measurements however fast the
//! host runs QEMU. See README.md, "The demo".
#![no_std]
#![no_main]

#[path = "firmware/board.rs"]
mod board;
#[path = "firmware/demo_config.rs"]
mod demo_config;
#[path = "firmware/io.rs"]
mod io;

use core::cell::RefCell;
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering::Relaxed};

use abtrack::scan::{AdvisoryLines, Intake, ScanLoop};
use abtrack::tcas::Advisory;
use abtrack::track::FixedGainTrack;
use abtrack::wire::{LinkStatus, MeasurementReport, Message, ScanSummary, TrackReport};
use abtrack::wire::{MAX_FRAMES_PER_BYTE, MAX_FRAME_LEN};
use abtrack::Scalar;
use board::TableScalar as Native;
use cortex_m::interrupt::{free, Mutex};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::NVIC;
use cortex_m_rt::exception;
use heapless::spsc::Queue;

/// Capacities. The micro:bit's 16 KiB of RAM set its own: the scenario
/// has at most 20 measurements per scan (2 targets + Poisson clutter).
#[cfg(not(abtrack_board = "microbit"))]
mod capacity {
    pub const TRACKS: usize = 32;
    pub const MEASUREMENTS_PER_SCAN: usize = 64;
    /// heapless queues hold one item less than their length.
    pub const QUEUE_LEN: usize = 128;
}
#[cfg(abtrack_board = "microbit")]
mod capacity {
    pub const TRACKS: usize = 8;
    pub const MEASUREMENTS_PER_SCAN: usize = 24;
    pub const QUEUE_LEN: usize = 32;
}
use capacity::{MEASUREMENTS_PER_SCAN, QUEUE_LEN, TRACKS};

type DemoLoop = ScanLoop<Native, FixedGainTrack<Native>, TRACKS, MEASUREMENTS_PER_SCAN>;
type MeasurementQueue = Queue<MeasurementReport, QUEUE_LEN>;

/// SysTick period (QEMU's virtual clock, real time without `-icount`).
const TICK_MS: u32 = 20;
/// No byte for this many ticks (1 s): the input has ended.
const IDLE_TICKS: u32 = 50;
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
/// The receive side: decoder and queue producer, owned by the receive
/// interrupt, read by the main loop for its counters.
static RX: Mutex<RefCell<Option<Intake<'static>>>> = Mutex::new(RefCell::new(None));

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
        let Ok(mut rx) = RX.borrow(cs).try_borrow_mut() else {
            return;
        };
        let Some(intake) = rx.as_mut() else {
            NVIC::mask(io::UartRxIrq);
            return;
        };
        loop {
            if io::uart_overrun() {
                intake.count_overrun();
            }
            if !intake.can_take_byte() {
                // Flow control: leave the byte in the UART; main resumes us.
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

/// Unmasks the receive interrupt again once the queue has room, and pends
/// it so that the byte left waiting in the UART is read.
fn resume_receiver() {
    if !RX_PAUSED.load(Relaxed) {
        return;
    }
    let room = free(|cs| {
        RX.borrow(cs)
            .try_borrow()
            .is_ok_and(|rx| rx.as_ref().is_some_and(|i| i.can_take_byte()))
    });
    if room {
        RX_PAUSED.store(false, Relaxed);
        // SAFETY: the handler and the intake are installed; unmasking is
        // not done inside a critical section.
        unsafe { NVIC::unmask(io::UartRxIrq) };
        NVIC::pend(io::UartRxIrq);
    }
}

fn link_status(time_ms: u32) -> LinkStatus {
    free(|cs| {
        RX.borrow(cs)
            .try_borrow()
            .ok()
            .and_then(|rx| rx.as_ref().map(|i| i.status(time_ms)))
            .unwrap_or_default()
    })
}

/// Sleeps until the next SysTick. Interrupts are off between the check and
/// the WFI, which still wakes on a pending interrupt, so no tick is missed.
fn wait_for_tick(seen: &mut u32) {
    loop {
        let now = TICKS.load(Relaxed);
        if now != *seen {
            *seen = now;
            return;
        }
        free(|_| {
            if TICKS.load(Relaxed) == *seen {
                cortex_m::asm::wfi();
            }
        });
    }
}

#[derive(Clone, Copy)]
struct TrackSeen {
    id: u32,
    first_ms: u32,
    last_ms: u32,
    reports: u32,
    worst: Advisory,
}

/// Where the scan loop's reports go: defmt lines, frames on UART TX, and a
/// record of the confirmed tracks for the summary.
///
/// On the wire a scan's track reports come first and its summary closes it;
/// the log prints the summary line first, so the track lines wait here.
struct Reporter {
    tracks_of_scan: heapless::Vec<TrackReport, TRACKS>,
    seen: heapless::Vec<TrackSeen, MAX_TRACKS_SEEN>,
    not_remembered: u32,
    frames_sent: u32,
    frames_not_sent: u32,
}

/// `ms` as seconds and milliseconds, for log lines.
fn secs(ms: u32) -> (u32, u32) {
    (ms / 1000, ms % 1000)
}

fn metres(cm: i32) -> f32 {
    cm as f32 / 100.0
}

impl Reporter {
    fn report(&mut self, message: &Message) {
        match message {
            Message::Track(t) => {
                self.remember(t);
                if self.tracks_of_scan.push(*t).is_err() {
                    log_track(t);
                }
            }
            Message::Scan(s) => {
                log_scan(s);
                for t in self.tracks_of_scan.iter() {
                    log_track(t);
                }
                self.tracks_of_scan.clear();
            }
            _ => {}
        }
        self.send(message);
    }

    fn send(&mut self, message: &Message) {
        let mut frame = [0u8; MAX_FRAME_LEN];
        let Ok(len) = message.emit(&mut frame) else {
            self.frames_not_sent += 1;
            return;
        };
        for &b in frame.iter().take(len) {
            if !io::uart_write(b) {
                self.frames_not_sent += 1;
                return;
            }
        }
        self.frames_sent += 1;
    }

    fn remember(&mut self, t: &TrackReport) {
        if let Some(s) = self.seen.iter_mut().find(|s| s.id == t.track_id) {
            s.last_ms = t.time_ms;
            s.reports += 1;
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
            self.not_remembered += 1;
        }
    }
}

fn log_scan(s: &ScanSummary) {
    let (sec, ms) = secs(s.time_ms);
    defmt::println!(
        "t={=u32}.{=u32:03} s | {=u16} meas ({=u16} invalid, {=u16} late, {=u16} dropped) | predicted {=u16}, gated {=u16}, assigned {=u16}, updated {=u16}, coasted {=u16} | started {=u16}, confirmed {=u16}, deleted {=u16} | {=u16} tracks, {=u16} confirmed | {=str}",
        sec,
        ms,
        s.measurements,
        s.invalid,
        s.late,
        s.dropped,
        s.predicted,
        s.gated_pairs,
        s.assigned,
        s.updated,
        s.coasted,
        s.started,
        s.confirmed,
        s.deleted,
        s.tracks,
        s.confirmed_tracks,
        s.highest_advisory.name()
    );
}

fn log_track(t: &TrackReport) {
    let (x, y) = (metres(t.x_cm), metres(t.y_cm));
    let (vx, vy) = (metres(t.vx_cm_per_s), metres(t.vy_cm_per_s));
    let (id, status, advisory) = (t.track_id, t.status.as_str(), t.advisory.name());
    match (t.altitude, t.range_tau_ds) {
        (None, None) => defmt::println!(
            "    track {=u32} {=str} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s {=str}",
            id,
            status,
            x,
            y,
            vx,
            vy,
            advisory
        ),
        (None, Some(tau)) => defmt::println!(
            "    track {=u32} {=str} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s {=str}, tau {=f32} s",
            id,
            status,
            x,
            y,
            vx,
            vy,
            advisory,
            tau as f32 / 10.0
        ),
        (Some((alt, rate)), None) => defmt::println!(
            "    track {=u32} {=str} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s {=i32} ft {=i16} ft/min {=str}",
            id,
            status,
            x,
            y,
            vx,
            vy,
            alt,
            rate,
            advisory
        ),
        (Some((alt, rate)), Some(tau)) => defmt::println!(
            "    track {=u32} {=str} ({=f32}, {=f32}) m ({=f32}, {=f32}) m/s {=i32} ft {=i16} ft/min {=str}, tau {=f32} s",
            id,
            status,
            x,
            y,
            vx,
            vy,
            alt,
            rate,
            advisory,
            tau as f32 / 10.0
        ),
    }
}

#[cortex_m_rt::entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` references, initialised
    // at compile time (no copy through the stack, no unsafe here).
    static mut QUEUE: MeasurementQueue = Queue::new();
    static mut SCAN_LOOP: DemoLoop = ScanLoop::new();

    board::paint_stack();
    defmt::println!(
        "abtrack scan-loop demo on {=str} ({=str}), tracker in {=str}",
        board::BOARD,
        board::CORE,
        Native::NAME
    );
    defmt::println!(
        "capacity: {=usize} tracks, {=usize} measurements per scan, queue of {=usize}; RAM: scan loop {=usize} B, queue {=usize} B, receiver {=usize} B",
        TRACKS,
        MEASUREMENTS_PER_SCAN,
        QUEUE_LEN - 1,
        core::mem::size_of::<DemoLoop>(),
        core::mem::size_of::<MeasurementQueue>(),
        core::mem::size_of::<Option<Intake<'static>>>()
    );
    defmt::println!(
        "input: wire frames on {=str}, receive IRQ {=u16}; SysTick every {=u32} ms = one {=u32} ms scan; advisory lines: {=str}",
        io::UART_NAME,
        io::UART_RX_IRQ,
        TICK_MS,
        demo_config::SCAN_PERIOD_MS,
        io::PINS_NAME
    );

    let config = match demo_config::demo_config::<Native>() {
        Ok(c) => c,
        Err(e) => {
            defmt::error!("configuration: {=str}", e);
            board::exit(false)
        }
    };
    let Some(mut core) = cortex_m::Peripherals::take() else {
        defmt::error!("core peripherals already taken");
        board::exit(false)
    };

    let (producer, mut consumer) = QUEUE.split();
    free(|cs| {
        if let Ok(mut rx) = RX.borrow(cs).try_borrow_mut() {
            *rx = Some(Intake::new(producer));
        }
    });
    let scan_loop: &mut DemoLoop = SCAN_LOOP;
    let mut lines = AdvisoryLines::new(io::AdvisoryPin::traffic(), io::AdvisoryPin::resolution());
    let mut reporter = Reporter {
        tracks_of_scan: heapless::Vec::new(),
        seen: heapless::Vec::new(),
        not_remembered: 0,
        frames_sent: 0,
        frames_not_sent: 0,
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

    let mut seen_ticks = TICKS.load(Relaxed);
    let mut now_ms = 0u32;
    let mut idle_scans = 0u32;
    let mut scan_errors = 0u32;
    let mut last_input_ms = None;
    loop {
        wait_for_tick(&mut seen_ticks);
        // Take this scan's measurements out of the queue as they come, so
        // that the receiver can go on.
        scan_loop.collect(&mut consumer, now_ms);
        resume_receiver();
        let idle = seen_ticks.wrapping_sub(LAST_RX_TICK.load(Relaxed)) >= IDLE_TICKS;
        // The queue head is after `now_ms` (collect stopped there): the
        // input has moved past this scan.
        let input_ahead = consumer.peek().is_some();
        if !(input_ahead || idle || scan_loop.batch_is_full()) {
            continue;
        }
        if idle {
            free(|cs| {
                if let Ok(mut rx) = RX.borrow(cs).try_borrow_mut() {
                    if let Some(intake) = rx.as_mut() {
                        intake.line_idle();
                    }
                }
            });
        }
        let had_input = scan_loop.batch_len() > 0 || !consumer.is_empty();
        match scan_loop.on_tick(&config, now_ms, &mut consumer, |m| reporter.report(m)) {
            Ok(tick) => {
                if tick.summary.measurements > 0 {
                    last_input_ms = Some(now_ms);
                }
                let before = (lines.pins().0.is_high(), lines.pins().1.is_high());
                if let Ok(true) = lines.show(tick.summary.highest_advisory) {
                    let (ta, ra) = (lines.pins().0.is_high(), lines.pins().1.is_high());
                    if (ta, ra) != before {
                        let (sec, ms) = secs(now_ms);
                        defmt::println!(
                            "advisory lines at t={=u32}.{=u32:03} s: TA {=bool}, RA {=bool}",
                            sec,
                            ms,
                            ta,
                            ra
                        );
                    }
                }
                reporter.send(&Message::Link(link_status(now_ms)));
            }
            Err(e) => {
                defmt::error!("scan at {=u32} ms refused: {}", now_ms, e);
                scan_errors += 1;
            }
        }
        now_ms = now_ms.wrapping_add(demo_config::SCAN_PERIOD_MS);
        if idle && !had_input && consumer.is_empty() {
            idle_scans += 1;
            if idle_scans >= IDLE_SCANS {
                break;
            }
        } else {
            idle_scans = 0;
        }
    }

    // Summary.
    let link = link_status(now_ms);
    let stats = *scan_loop.table().stats();
    let c = *scan_loop.counters();
    match last_input_ms {
        Some(t) => {
            let (sec, ms) = secs(t);
            defmt::println!(
                "input ended after the scan at t={=u32}.{=u32:03} s; {=u32} idle scans",
                sec,
                ms,
                IDLE_SCANS
            );
        }
        None => defmt::error!("no measurement arrived on the UART"),
    }
    defmt::println!(
        "summary: {=u32} scans; {=u32} measurements ({=u32} beyond 400 km, {=u32} bad altitude, {=u32} late, {=u32} over the scan capacity); tracks started {=u32}, confirmed {=u32}, deleted {=u32}, refused (table full) {=u32}",
        stats.scans,
        c.taken,
        c.position_out_of_range,
        c.altitude_out_of_range,
        c.late,
        c.dropped,
        stats.tracks_started,
        stats.tracks_confirmed,
        stats.tracks_deleted,
        stats.refused_table_full
    );
    defmt::println!(
        "confirmed tracks ({=usize}):",
        reporter.seen.len() + reporter.not_remembered as usize
    );
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
        "receiver: {=u32} frames, {=u32} CRC errors, {=u32} unknown type, {=u32} bad length, {=u32} bad field, {=u32} truncated, {=u32} bytes skipped; {=u32} queue full, {=u32} UART overruns; flow control paused it {=u32} times (keeps {=usize} slots free)",
        link.frames,
        link.crc_errors,
        link.unknown_type,
        link.bad_length,
        link.bad_field,
        link.truncated,
        link.bytes_skipped,
        link.queue_full,
        link.rx_overruns,
        RX_PAUSES.load(Relaxed),
        MAX_FRAMES_PER_BYTE
    );
    defmt::println!(
        "reports: {=u32} frames sent on the UART, {=u32} not sent; advisory lines changed {=u32} times, now TA {=bool}, RA {=bool}",
        reporter.frames_sent,
        reporter.frames_not_sent,
        lines.changes(),
        lines.pins().0.is_high(),
        lines.pins().1.is_high()
    );
    board::report_stack();
    let ok = scan_errors == 0
        && last_input_ms.is_some()
        && reporter.frames_not_sent == 0
        && c.assessment_errors == 0;
    board::exit(ok)
}
