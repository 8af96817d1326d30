//! The scan loop's core on the host, fed with encoded frames as the firmware
//! is: bytes → `Intake` (decoder + spsc queue) → `ScanLoop::on_tick` →
//! report frames, decoded again and checked.

#![allow(clippy::needless_range_loop)]

use crate::scan::support;
use abtrack_firmware::capacity::{microbit, mps2};
use abtrack_firmware::demo_config;

use support::{crossing_truth, Lcg};

use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
use abtrack::scan::{
    AdvisoryLines, ClockConfig, Intake, MeasurementQueue, ScanConfig, ScanLoop, TickReport,
};
use abtrack::tcas::{Advisory, OwnAircraft};
use abtrack::track::{FixedGainTrack, Gate, TrackStatus, TrackerConfig};
use abtrack::wire::{
    Decoder, DecoderStats, Encoder, LoopCounters, MeasuredPosition, MeasurementReport, Message,
    ScanSummary, TrackReport, MAX_FRAME_LEN,
};
use abtrack::{Fix, Gains, Scalar};
use abtrack_host_tests::frames::{self, Faults};
use abtrack_host_tests::scenario;
use std::collections::{BTreeMap, BTreeSet};

type Loop<S, const N: usize, const M: usize> = ScanLoop<S, FixedGainTrack<S>, N, M>;
/// The demo's scan loop on the micro:bit (boards/qemu/src/main.rs).
type MicrobitLoop = ScanLoop<
    abtrack_firmware::number_types::cortex_m0::Wide,
    abtrack::track::RangeAzimuthTrack<abtrack_firmware::number_types::cortex_m0::Wide>,
    { microbit::TRACKS },
    { microbit::MEASUREMENTS_PER_SCAN },
>;

/// Numbers the frames of the test's sensor.
#[derive(Default)]
struct Sensor(Encoder);
impl Sensor {
    fn frame(&mut self, r: MeasurementReport) -> Vec<u8> {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = self.0.encode(&Message::Measurement(r), &mut buf).unwrap();
        buf[..n].to_vec()
    }
}

/// Everything the loop emitted, decoded back from the bytes.
#[derive(Default)]
struct Output {
    bytes: Vec<u8>,
    encoder: Encoder,
}

impl Output {
    fn sink(&mut self) -> impl FnMut(&Message) + '_ {
        |m: &Message| {
            let mut buf = [0u8; MAX_FRAME_LEN];
            let n = self.encoder.encode(m, &mut buf).unwrap();
            self.bytes.extend_from_slice(&buf[..n]);
        }
    }
    fn decode(&self) -> Vec<Message> {
        let (messages, stats) = frames::decode_all(&self.bytes);
        assert_eq!(
            stats.crc_errors + stats.bytes_skipped + stats.frames_lost,
            0
        );
        messages
    }
    fn tracks(&self) -> Vec<TrackReport> {
        self.decode()
            .into_iter()
            .filter_map(|m| match m {
                Message::Track(t) => Some(t),
                _ => None,
            })
            .collect()
    }
    fn scans(&self) -> Vec<ScanSummary> {
        self.decode()
            .into_iter()
            .filter_map(|m| match m {
                Message::Scan(s) => Some(s),
                _ => None,
            })
            .collect()
    }
}

/// Drives a loop like the firmware: all bytes of scan k are received, then
/// the scan runs.
struct Rig<S: Scalar, const N: usize, const M: usize> {
    intake: Box<Intake<64>>,
    scan_loop: Box<Loop<S, N, M>>,
    config: ScanConfig<S, Gains<S>>,
    out: Output,
    ticks: Vec<TickReport>,
}

impl<S: Scalar, const N: usize, const M: usize> Rig<S, N, M> {
    fn new(config: ScanConfig<S, Gains<S>>) -> Self {
        Rig {
            intake: Box::new(Intake::new()),
            scan_loop: Box::new(Loop::new()),
            config,
            out: Output::default(),
            ticks: Vec::new(),
        }
    }
    fn receive(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.intake.push(b);
        }
    }
    fn tick(&mut self) {
        let report = self
            .scan_loop
            .on_tick(&self.config, self.intake.as_mut(), self.out.sink())
            .unwrap();
        self.ticks.push(report);
    }
}

/// Runs the crossing through the loop in `S`; returns the rig's output and
/// the number of garbage bytes inserted.
fn run_crossing<S: Scalar>() -> (Output, Vec<TickReport>, DecoderStats, usize) {
    let mut rig: Rig<S, 8, 16> = Rig::new(demo_config::crossing_config::<S, _>().unwrap());
    let mut sensor = Sensor::default();
    let mut rng = Lcg(0x5CA1_AB1E);
    let mut garbage = 0;
    for k in 0..60u32 {
        let t = k as f64;
        let truth = crossing_truth(t);
        // The targets in random order, and two clutter points.
        let mut points: Vec<[f64; 2]> = truth
            .iter()
            .map(|p| [p[0] + 15.0 * rng.signed(), p[1] + 15.0 * rng.signed()])
            .collect();
        for _ in 0..2 {
            points.push([4500.0 * rng.signed(), 4500.0 * rng.signed()]);
        }
        if rng.below(2) == 0 {
            points.swap(0, 1);
        }
        let mut bytes = Vec::new();
        for p in points {
            // Garbage on the line before some frames, sync bytes included.
            if rng.below(4) == 0 {
                let g = [0x00, 0xAB, 0x13, 0xAB, 0xAB, 0x7E];
                let n = 1 + rng.below(g.len());
                bytes.extend_from_slice(&g[..n]);
                garbage += n;
            }
            let r =
                MeasurementReport::cartesian_from_metres(k * 1000, 1, p[0], p[1], None).unwrap();
            bytes.extend(sensor.frame(r));
        }
        rig.receive(&bytes);
        rig.tick();
    }
    let link = *rig.intake.decoder().stats();
    assert_eq!(rig.intake.counters().queue_full, 0);
    (rig.out, rig.ticks, link, garbage)
}

/// Distance (m) from a report to each target's truth at its time.
fn distances(report: &TrackReport) -> [f64; 2] {
    let truth = crossing_truth(report.time_ms as f64 / 1000.0);
    let (x, y) = (report.x_cm as f64 / 100.0, report.y_cm as f64 / 100.0);
    [
        (truth[0][0] - x).hypot(truth[0][1] - y),
        (truth[1][0] - x).hypot(truth[1][1] - y),
    ]
}

fn crossing_targets_keep_their_ids<S: Scalar>() {
    let (out, ticks, link, garbage) = run_crossing::<S>();
    // Garbage skipped and counted, every frame decoded: 4 per scan.
    assert_eq!(link.accepted, 240, "{link:?}");
    assert_eq!(link.frames_lost, 0);
    assert!(
        link.bytes_skipped as usize >= garbage,
        "{link:?} vs {garbage}"
    );
    let used: u32 = ticks.iter().map(|t| t.summary.counts.used as u32).sum();
    assert_eq!(used, 240);

    // The tracks that follow the targets: every report of the id within
    // 100 m of the same target.
    let reports = out.tracks();
    let mut by_id: BTreeMap<u32, Vec<TrackReport>> = BTreeMap::new();
    for r in &reports {
        by_id.entry(r.track_id).or_default().push(*r);
    }
    // An id follows a target when every one of its reports is within 100 m
    // of that target's truth (near the crossing, of both).
    let mut target_ids: [BTreeSet<u32>; 2] = [BTreeSet::new(), BTreeSet::new()];
    for (id, rs) in &by_id {
        for target in 0..2 {
            if rs.iter().all(|r| distances(r)[target] < 100.0) {
                target_ids[target].insert(*id);
            }
        }
    }
    for target in 0..2 {
        assert_eq!(
            target_ids[target].len(),
            1,
            "target {target}: ids {:?} ({} reports)",
            target_ids[target],
            reports.len()
        );
        let id = *target_ids[target].iter().next().unwrap();
        let rs = &by_id[&id];
        // Confirmed by t = 3 s (two-point start at 1 s, 2 of 3), reported in
        // every scan from then on, through the crossing at 30 s.
        assert!(rs[0].time_ms <= 3000, "first report at {}", rs[0].time_ms);
        assert_eq!(rs.len() as u32, 60 - rs[0].time_ms / 1000);
        // Closing on the own aircraft until the crossing: a traffic
        // advisory (non-altitude-reporting intruder: never a resolution
        // advisory), sensitivity level 5 at 8000 ft.
        for r in rs
            .iter()
            .filter(|r| r.time_ms >= 5000 && r.time_ms <= 25_000)
        {
            assert_eq!(r.advisory, Advisory::Traffic, "{r:?}");
            assert_eq!(r.sensitivity.map(|l| l.number()), Some(5));
            assert!(r.range_tau_ds.is_some());
            assert_eq!(r.altitude, None);
        }
        // 20 s after the crossing, 2.2 km away and opening: proximate only.
        let late = rs.iter().find(|r| r.time_ms == 50_000).unwrap();
        assert_eq!(late.advisory, Advisory::ProximateTraffic, "{late:?}");
        assert_eq!(late.range_tau_ds, None);
        assert!(rs.iter().all(|r| r.advisory != Advisory::Resolution));
    }
    // The scan summaries agree with the tracker's reports.
    let scans = out.scans();
    assert_eq!(scans.len(), 60);
    for (s, t) in scans.iter().zip(&ticks) {
        assert_eq!(*s, t.summary);
        assert_eq!(s.counts.updated as u32, t.scan.updated);
        assert_eq!(s.counts.tracks as u32, t.scan.tracks);
        // The per-measurement outcomes (counted from the association
        // codes) agree with the tracker's own counts.
        assert_eq!(s.counts.outside_gates as u32, t.scan.outside_gates, "{t:?}");
        assert_eq!(s.counts.started as u32, t.scan.started);
        assert_eq!(s.counts.not_assigned as u32, t.scan.not_assigned);
        let c = &s.counts;
        assert_eq!(
            c.used,
            c.updated
                + c.started
                + c.not_assigned
                + c.outside_gates
                + c.rejected
                + c.refused_table_full
        );
    }
    assert!(scans
        .iter()
        .any(|s| s.highest_advisory == Advisory::Traffic));
}

#[test]
fn crossing_targets_keep_their_ids_f64() {
    crossing_targets_keep_their_ids::<f64>();
}

#[test]
fn crossing_targets_keep_their_ids_f32() {
    crossing_targets_keep_their_ids::<f32>();
}

#[test]
fn crossing_targets_keep_their_ids_fixed() {
    crossing_targets_keep_their_ids::<Fix>();
}

#[test]
fn representations_report_the_same_tracks() {
    let ids = |out: &Output| -> Vec<(u32, u32, TrackStatus, Advisory)> {
        out.tracks()
            .iter()
            .map(|r| (r.time_ms, r.track_id, r.status, r.advisory))
            .collect()
    };
    let (a, ..) = run_crossing::<f64>();
    let (b, ..) = run_crossing::<f32>();
    let (c, ..) = run_crossing::<Fix>();
    assert_eq!(ids(&a), ids(&b));
    assert_eq!(ids(&a), ids(&c));
}

#[test]
fn queue_overflow_is_counted() {
    let mut intake: Intake<4> = Intake::new();
    let mut sensor = Sensor::default();
    let mut bytes = Vec::new();
    for k in 0..10 {
        bytes.extend(sensor.frame(
            MeasurementReport::cartesian_from_metres(0, 1, 100.0 * k as f64, 0.0, None).unwrap(),
        ));
    }
    let mut queued = 0;
    for &b in &bytes {
        queued += intake.push(b);
    }
    assert_eq!(queued, 4);
    let c = *intake.counters();
    assert_eq!((c.measurements, c.queue_full), (10, 6));
    assert_eq!(intake.decoder().stats().accepted, 10);
    assert_eq!(intake.free_slots(), 0);
    assert!(!intake.can_take_byte());

    // The four queued ones reach the scan, in order.
    let mut scan_loop: Box<Loop<f64, 4, 8>> = Box::new(Loop::new());
    let config = demo_config::crossing_config::<f64, _>().unwrap();
    let mut out = Output::default();
    let tick = scan_loop.on_tick(&config, &mut intake, out.sink()).unwrap();
    assert_eq!(tick.summary.counts.used, 4);
    assert_eq!(scan_loop.counters().used, 4);
    assert_eq!(intake.free_slots(), 4);
}

fn direct(reports: &[MeasurementReport]) -> Box<MeasurementQueue<64>> {
    let mut q = Box::new(MeasurementQueue::new());
    for r in reports {
        q.push(*r).unwrap();
    }
    q
}

fn at(t: u32, x: f64) -> MeasurementReport {
    MeasurementReport::cartesian_from_metres(t, 1, x, 0.0, None).unwrap()
}

/// The scan clock (abtrack::scan, "Time"): it locks at the first
/// measurement, later measurements wait, late ones and lone out-of-window
/// ones are counted, every measurement ends in exactly one scan or count.
#[test]
fn the_scan_clock_sorts_measurements_by_the_sensor_time() {
    let config = demo_config::crossing_config::<f32, _>().unwrap();
    let mut scan_loop: Box<Loop<f32, 4, 8>> = Box::new(Loop::new());
    let mut out = Output::default();
    let mut q = direct(&[
        at(1000, 0.0),
        at(1000, 10.0),
        at(1500, 20.0),
        at(2000, 30.0),
    ]);
    // Locked at 1000 ms: the two measurements of 1000 ms are this scan's;
    // 1500 ms belongs to the scan at 2000 ms, which is due.
    assert_eq!(
        scan_loop.collect(&config, q.as_mut()),
        abtrack::scan::Collected::ScanDue
    );
    assert_eq!(scan_loop.batch_len(), 2);
    let t = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
    assert_eq!((t.summary.time_ms, t.summary.counts.used), (1000, 2));
    // The scan at 2000 ms takes 1500 and 2000; the queue is empty: waiting.
    assert_eq!(
        scan_loop.collect(&config, q.as_mut()),
        abtrack::scan::Collected::Waiting
    );
    assert_eq!(scan_loop.batch_len(), 2);
    // A measurement of 1000 ms arriving now is late (its scan has run); one
    // of 500 ms is older than the late window (2 periods before this scan):
    // out of the window, held, then dropped when the next one does not
    // confirm a new time base.
    for r in [at(1000, 40.0), at(-500i32 as u32, 50.0), at(2000, 60.0)] {
        q.push(r).unwrap();
    }
    let t = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
    let c = t.summary.counts;
    assert_eq!(t.summary.time_ms, 2000);
    assert_eq!((c.used, c.late, c.out_of_window), (3, 1, 1));
    assert_eq!(t.summary.interval_ms, 1000);
    let lc = scan_loop.counters();
    assert_eq!(
        (lc.used, lc.late, lc.out_of_window, lc.clock_relocks),
        (5, 1, 1, 0)
    );
}

/// A silence shorter than the jump bound is a gap: one empty scan per
/// period, on schedule; the tracks coast and are deleted.
#[test]
fn a_gap_runs_empty_scans_on_schedule() {
    let config = demo_config::crossing_config::<f64, _>().unwrap();
    let mut scan_loop: Box<Loop<f64, 4, 8>> = Box::new(Loop::new());
    let mut out = Output::default();
    let mut q = direct(&[
        at(0, 0.0),
        at(1000, 100.0),
        at(2000, 200.0),
        at(3000, 300.0),
    ]);
    let mut times = Vec::new();
    for _ in 0..4 {
        times.push(
            scan_loop
                .on_tick(&config, q.as_mut(), out.sink())
                .unwrap()
                .summary
                .time_ms,
        );
    }
    // 12 s of silence, then the target again.
    q.push(at(15_000, 1500.0)).unwrap();
    while scan_loop.collect(&config, q.as_mut()) == abtrack::scan::Collected::ScanDue {
        let t = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
        times.push(t.summary.time_ms);
    }
    let t = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
    times.push(t.summary.time_ms);
    let expected: Vec<u32> = (0..=15).map(|k| k * 1000).collect();
    assert_eq!(times, expected);
    assert_eq!(scan_loop.counters().clock_relocks, 0);
    // The track (confirmed at 2 s) coasted and was deleted in the gap.
    assert_eq!(scan_loop.table().stats().tracks_deleted, 1);
}

/// 20 sensor scans from `start` ms, one target at 50 m/s and one clutter
/// point each, the sensor's clock stepped by `step` (wrapping) after the
/// tenth, through the scan loop as the firmware drives it: its counters,
/// its output and the measurements sent.
fn stepped_clock_run(start: u32, step: u32) -> (LoopCounters, Output, u32) {
    let config = demo_config::crossing_config::<Fix, _>().unwrap();
    let mut scan_loop: Box<Loop<Fix, 4, 8>> = Box::new(Loop::new());
    let mut out = Output::default();
    let mut q = Box::new(MeasurementQueue::<64>::new());
    let mut sent = 0;
    for k in 0..20u32 {
        let t = start + k * 1000;
        let t = if k >= 10 { t.wrapping_add(step) } else { t };
        q.push(at(t, 50.0 * k as f64)).unwrap();
        let clutter = MeasurementReport::cartesian_from_metres(
            t,
            1,
            -3000.0 + 100.0 * k as f64,
            4000.0,
            None,
        );
        q.push(clutter.unwrap()).unwrap();
        sent += 2;
        while scan_loop.collect(&config, q.as_mut()) == abtrack::scan::Collected::ScanDue {
            scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
        }
    }
    scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
    (*scan_loop.counters(), out, sent)
}

/// The clock findings on the scan core: a clock far from zero, a
/// jump past 2³¹ ms, a step back; each re-lock is counted, no measurement
/// is lost or used twice, and a target keeps its track across a step of
/// the sensor's clock.
#[test]
fn the_scan_clock_relocks_on_a_jump_and_keeps_the_track() {
    const FORTY_DAYS_MS: u32 = 40 * 86_400_000;
    for (name, step) in [
        ("+40 days", FORTY_DAYS_MS),
        ("-10 s", (-10_000i32) as u32),
        ("+31 s", 31_000),
        ("-1 h", (-3_600_000i32) as u32),
    ] {
        let start = 43_200_000u32; // noon
        let (c, out, sent) = stepped_clock_run(start, step);
        assert_eq!(c.clock_locks, 1, "{name}");
        assert_eq!(c.clock_relocks, 1, "{name}: {c:?}");
        assert_eq!(
            (c.late, c.out_of_window, c.invalid),
            (0, 0, 0),
            "{name}: {c:?}"
        );
        assert_eq!(c.used, sent, "{name}: {c:?}");
        // 20 scans: no empty scan before the first data, none across the
        // step.
        assert_eq!(c.scans, 20, "{name}: {c:?}");
        // One track follows the target through the step, reported at the
        // sensor's times.
        let tracks = out.tracks();
        let near: BTreeSet<u32> = tracks
            .iter()
            .filter(|t| (t.y_cm as f64).abs() < 10_000.0)
            .map(|t| t.track_id)
            .collect();
        assert_eq!(near.len(), 1, "{name}: {tracks:?}");
        let last = tracks.iter().rfind(|t| near.contains(&t.track_id)).unwrap();
        assert_eq!(last.time_ms, (start + 19_000).wrapping_add(step), "{name}");
        assert!(
            (last.x_cm as f64 / 100.0 - 950.0).abs() < 5.0,
            "{name}: {last:?}"
        );
    }
}

/// A step of the sensor's clock back by one to three periods cannot be told
/// from late reports until the reports after it arrive: the sensor scan
/// after the step falls in the scan being assembled (merged: the target's
/// track takes one of its two measurements, the other is counted as any
/// scan's are, here not assigned at one to two periods), and from two
/// periods back the one or two after it fall in the late window, dropped
/// and counted `late`. No re-lock, and every measurement is counted. A step
/// back by more (and forward by any amount,
/// [`the_scan_clock_relocks_on_a_jump_and_keeps_the_track`]) re-locks and
/// loses nothing.
#[test]
fn a_clock_step_back_of_one_to_three_periods_is_counted_not_relocked() {
    // (step, late, not assigned, re-locks): one target and one clutter
    // point a scan, 20 scans, the step after the tenth.
    for (step_ms, late, not_assigned, relocks) in [
        (-1_000i32, 0, 1, 0),
        (-1_500, 0, 1, 0),
        (-2_000, 2, 0, 0),
        (-2_500, 2, 0, 0),
        (-3_000, 4, 0, 0),
        (-3_500, 0, 0, 1),
    ] {
        let (c, _, sent) = stepped_clock_run(43_200_000, step_ms as u32);
        assert_eq!(
            (c.late, c.not_assigned, c.clock_relocks, c.out_of_window),
            (late, not_assigned, relocks, 0),
            "{step_ms}: {c:?}"
        );
        assert_eq!(c.used + c.late, sent, "{step_ms}: {c:?}");
    }
}

#[test]
fn out_of_range_measurements_are_refused_and_counted() {
    let reports = [
        MeasurementReport {
            time_ms: 0,
            sensor: 1,
            position: MeasuredPosition::Cartesian {
                x_cm: 50_000_000, // 500 km
                y_cm: 0,
            },
            altitude_ft: None,
            altitude_25ft: false,
            address: None,
        },
        MeasurementReport {
            time_ms: 0,
            sensor: 1,
            position: MeasuredPosition::Polar {
                range_cm: 40_000_001,
                azimuth_bam: 0,
            },
            altitude_ft: None,
            altitude_25ft: false,
            address: None,
        },
        MeasurementReport {
            time_ms: 0,
            sensor: 1,
            position: MeasuredPosition::Cartesian { x_cm: 0, y_cm: 0 },
            altitude_ft: Some(200_000),
            altitude_25ft: false,
            address: None,
        },
        MeasurementReport {
            time_ms: 0,
            sensor: 1,
            position: MeasuredPosition::Cartesian { x_cm: 100, y_cm: 0 },
            altitude_ft: Some(5_000),
            altitude_25ft: false,
            address: None,
        },
    ];
    // Through the wire they are refused by the decoder (outside the
    // envelope: lost, as the decoder counts refused frames before the first
    // accepted one) ...
    let mut intake: Intake<16> = Intake::new();
    let mut sensor = Sensor::default();
    for r in reports {
        for b in sensor.frame(r) {
            intake.push(b);
        }
    }
    let d = intake.decoder().stats();
    assert_eq!((d.accepted, d.out_of_envelope, d.frames_lost), (1, 3, 3));
    // ... and if they reach the loop another way, by the conversion.
    let mut q = direct(&reports);
    let mut scan_loop: Box<Loop<Fix, 4, 8>> = Box::new(Loop::new());
    let config = demo_config::crossing_config::<Fix, _>().unwrap();
    let mut out = Output::default();
    let t = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
    assert_eq!((t.summary.counts.used, t.summary.counts.invalid), (1, 3));
    assert_eq!(t.scan.measurements, 1);
    assert_eq!(scan_loop.counters().invalid, 3);
}

#[test]
fn scan_overflow_is_counted() {
    let mut q = direct(&(0..7).map(|k| at(0, 100.0 * k as f64)).collect::<Vec<_>>());
    let mut scan_loop: Box<Loop<f64, 4, 5>> = Box::new(Loop::new());
    let config = demo_config::crossing_config::<f64, _>().unwrap();
    let mut out = Output::default();
    let t = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
    assert_eq!(
        (t.summary.counts.used, t.summary.counts.over_capacity),
        (5, 2)
    );
    assert_eq!(t.scan.measurements, 5);
    assert!(q.is_empty());
    // Nearest to the own aircraft first: the five nearest were kept.
    let c = t.summary.counts;
    assert_eq!(c.used, c.outside_gates);
}

/// The demo's second input (`scripts/demo-input.sh FILE two-crossing`: the
/// `two-crossing` scenario, seed 1, a corrupted frame every 97 and garbage
/// before every 41st) through its Cartesian configuration and the
/// firmware's pacing, in the three number types: the two targets are
/// tracked under one id each from early on to the end, the clutter confirms
/// at most short-lived tracks, the faults are counted exactly, and the run
/// is clean.
fn demo_input_is_tracked<S: Scalar, const N: usize, const M: usize, const Q: usize>(
) -> Vec<(u32, u32)> {
    const SEED: u64 = 1;
    let faults = Faults {
        corrupt_every: Some(97),
        garbage_every: Some(41),
        seed: 0,
    };
    let reports = frames::scenario_reports("two-crossing", SEED, 1).unwrap();
    let encoded = frames::encode(&reports, faults);
    assert!(encoded.corrupted > 0 && encoded.garbage_bytes > 0);
    let run = scenario::generate("two-crossing", SEED).unwrap();

    let config = demo_config::crossing_config::<S, _>().unwrap();
    let fw =
        frames::run_like_the_firmware::<S, _, FixedGainTrack<S>, N, M, Q>(&encoded.bytes, &config);
    let h = fw.health;
    assert_eq!(
        h.decoder.accepted as usize,
        encoded.frames - encoded.corrupted
    );
    assert_eq!(h.decoder.crc_errors as usize, encoded.corrupted);
    assert_eq!(h.decoder.frames_lost as usize, encoded.corrupted);
    assert_eq!(
        h.decoder.bytes_skipped as usize,
        encoded.garbage_bytes + 32 * encoded.corrupted
    );
    assert_eq!(h.intake.queue_full, 0);
    // Every accepted frame but the end of input used.
    assert_eq!(h.scan.used + 1, h.decoder.accepted);
    assert!(fw.verdict.unwrap().is_clean());

    let (messages, stats) = frames::decode_all(&fw.output);
    assert_eq!(
        stats.frames_lost + stats.crc_errors + stats.bytes_skipped,
        0
    );
    let reports: Vec<TrackReport> = messages
        .iter()
        .filter_map(|m| match m {
            Message::Track(t) => Some(*t),
            _ => None,
        })
        .collect();
    let mut by_id: BTreeMap<u32, Vec<TrackReport>> = BTreeMap::new();
    for r in &reports {
        by_id.entry(r.track_id).or_default().push(*r);
    }
    // The targets within 150 m of a report's position at its time.
    let targets_near = |r: &TrackReport| -> BTreeSet<u32> {
        let Some(scan) = run
            .scans
            .iter()
            .find(|s| frames::time_ms(s.t).unwrap() == r.time_ms)
        else {
            return BTreeSet::new();
        };
        scan.truth
            .iter()
            .filter(|tr| (tr.x - r.x_cm as f64 / 100.0).hypot(tr.y - r.y_cm as f64 / 100.0) < 150.0)
            .map(|tr| tr.target)
            .collect()
    };
    let mut long_lived = Vec::new();
    for (id, rs) in &by_id {
        if rs.len() >= 10 {
            // Every long-lived track follows one target throughout (its
            // reports while updated; coasting after the input ended).
            let mut common = targets_near(&rs[0]);
            for r in rs.iter().filter(|r| r.time_ms <= 59_000) {
                common = common.intersection(&targets_near(r)).copied().collect();
            }
            assert_eq!(common.len(), 1, "track {id} follows {common:?}");
            long_lived.push((common.into_iter().next().unwrap(), *id));
        } else {
            // Clutter tracks: few and short.
            assert!(rs.len() <= 4, "track {id}: {} reports", rs.len());
        }
    }
    long_lived.sort();
    let targets: Vec<u32> = long_lived.iter().map(|(t, _)| *t).collect();
    assert_eq!(targets, vec![1, 2], "{long_lived:?}");
    for (_, id) in &long_lived {
        let rs = &by_id[id];
        assert!(
            rs[0].time_ms <= 5000,
            "track {id} confirmed at {}",
            rs[0].time_ms
        );
        assert!(rs.last().unwrap().time_ms >= 55_000);
    }
    long_lived
}

#[test]
fn demo_input_is_tracked_in_every_number_type() {
    // The firmware's capacities (boards/qemu/src/capacity.rs).
    use mps2::{MEASUREMENTS_PER_SCAN as M, QUEUE_LEN as Q, TRACKS as N};
    let f64_ids = demo_input_is_tracked::<f64, N, M, Q>();
    assert_eq!(demo_input_is_tracked::<f32, N, M, Q>(), f64_ids);
    assert_eq!(demo_input_is_tracked::<Fix, N, M, Q>(), f64_ids);
    // The micro:bit's tracks and queue, with room for the crossing's 20
    // measurements per scan (its demo takes 10 replies per scan: the TCAS
    // scenario has at most 6; tests/it/firmware/tcas_demo.rs).
    assert_eq!(
        demo_input_is_tracked::<Fix, { microbit::TRACKS }, 24, { microbit::QUEUE_LEN }>(),
        f64_ids
    );
}

/// A TCAS encounter (`tcas-converging`: range/bearing with Mode C altitude,
/// bearing σ 5°) through the loop with a configuration for that sensor: the
/// altitude tracker follows the intruder's reports and the threat logic
/// raises a resolution advisory before the closest approach (t = 100.8 s)
/// and clears it after.
fn run_tcas<S: Scalar>() -> Output {
    let v = |x: f64| S::try_from_f64(x).unwrap();
    let gains = Gains::alpha_beta_f64(0.5, 0.5 * 0.5 / 1.5).unwrap();
    // Li et al.'s wave gate sized from the sensor: range σ 15 m, bearing σ
    // 0.087 rad, 6 σ (with 4 σ the track is lost once near the closest
    // approach, where the bearing swings fastest, and restarted).
    let gate = Gate::wave(v(15.24), v(5f64.to_radians()), v(6.0)).unwrap();
    // Initiation: 300 m/s closure plus 2 × 3σ of cross-range noise at 14 NM.
    let tracker = TrackerConfig::new(gains, gate, v(300.0))
        .unwrap()
        .with_initiation_margin(v(14_000.0))
        .unwrap();
    let config = ScanConfig {
        tracker,
        own: OwnAircraft::over_sea_level(v(scenario::TCAS_OWN_ALTITUDE_FT), S::ZERO),
        altitude: AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeC).unwrap(),
        altitude_25ft: AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeS25).unwrap(),
        clock: ClockConfig::new(1000).unwrap(),
    };
    let reports = frames::scenario_reports("tcas-converging", 3, 2).unwrap();
    let mut rig: Rig<S, 8, 8> = Rig::new(config);
    let mut sensor = Sensor::default();
    for (k, r) in reports.iter().enumerate() {
        assert_eq!(r.time_ms, k as u32 * 1000);
        rig.receive(&sensor.frame(*r));
        rig.tick();
    }
    rig.out
}

fn tcas_encounter_raises_a_resolution_advisory<S: Scalar>() {
    let tracks = run_tcas::<S>().tracks();
    let ids: BTreeSet<u32> = tracks.iter().map(|t| t.track_id).collect();
    assert_eq!(ids.len(), 1, "{ids:?}");
    let ra: Vec<u32> = tracks
        .iter()
        .filter(|t| t.advisory == Advisory::Resolution)
        .map(|t| t.time_ms)
        .collect();
    assert!(!ra.is_empty());
    let first_ra = ra[0];
    assert!(
        (60_000..100_000).contains(&first_ra),
        "first RA at {first_ra} ms"
    );
    assert!(tracks
        .iter()
        .filter(|t| t.time_ms >= 120_000)
        .all(|t| t.advisory < Advisory::Traffic));
    // The tracked altitude: the truth climbs 5 ft/s (300 ft/min) from
    // 7500 ft; Mode C reports are quantised to 100 ft, one step every 20 s,
    // so the rate estimate swings around the truth from step to step (the
    // gains are Kalata's for σ_a = 0.1 g): its mean is checked, not each
    // value.
    let later: Vec<&TrackReport> = tracks.iter().filter(|t| t.time_ms >= 30_000).collect();
    let mut rate_sum = 0.0;
    for t in &later {
        let truth = 7500.0 + 5.0 * t.time_ms as f64 / 1000.0;
        let (alt, rate) = t.altitude.expect("altitude tracked");
        assert!((alt as f64 - truth).abs() < 100.0, "{t:?}");
        rate_sum += rate as f64;
        assert_eq!(t.sensitivity.map(|l| l.number()), Some(5));
    }
    let mean_rate = rate_sum / later.len() as f64;
    assert!(
        (mean_rate - 300.0).abs() < 60.0,
        "mean rate {mean_rate} ft/min"
    );
}

#[test]
fn tcas_encounter_raises_a_resolution_advisory_f64() {
    tcas_encounter_raises_a_resolution_advisory::<f64>();
}

#[test]
fn tcas_encounter_raises_a_resolution_advisory_f32() {
    tcas_encounter_raises_a_resolution_advisory::<f32>();
}

#[test]
fn tcas_encounter_raises_a_resolution_advisory_fixed() {
    tcas_encounter_raises_a_resolution_advisory::<Fix>();
}

/// An embedded-hal pin that records its level changes.
#[derive(Default)]
struct RecordingPin {
    high: Option<bool>,
    changes: Vec<bool>,
}
impl embedded_hal::digital::ErrorType for RecordingPin {
    type Error = core::convert::Infallible;
}
impl embedded_hal::digital::OutputPin for RecordingPin {
    fn set_low(&mut self) -> Result<(), Self::Error> {
        if self.high != Some(false) {
            self.changes.push(false);
        }
        self.high = Some(false);
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Self::Error> {
        if self.high != Some(true) {
            self.changes.push(true);
        }
        self.high = Some(true);
        Ok(())
    }
}

#[test]
fn advisory_lines_follow_the_highest_advisory() {
    let mut lines = AdvisoryLines::new(RecordingPin::default(), RecordingPin::default());
    let sequence = [
        Advisory::None,
        Advisory::ProximateTraffic,
        Advisory::Traffic,
        Advisory::Traffic,
        Advisory::Resolution,
        Advisory::Traffic,
        Advisory::None,
    ];
    let changed: Vec<bool> = sequence.iter().map(|a| lines.show(*a).unwrap()).collect();
    assert_eq!(changed, [true, false, true, false, true, true, true]);
    assert_eq!(lines.changes(), 4);
    let (ta, ra) = lines.release();
    assert_eq!(ta.changes, [false, true, false]);
    assert_eq!(ra.changes, [false, true, false]);
}

#[test]
fn print_memory_sizes() {
    // Host (x86-64) sizes; the firmware prints its own at start-up (heapless
    // lengths are usize, 4 bytes there).
    for (name, size) in [
        (
            "ScanLoop<f32, 16, 32>",
            std::mem::size_of::<Loop<f32, 16, 32>>(),
        ),
        (
            "ScanLoop<Fix, 16, 32>",
            std::mem::size_of::<Loop<Fix, 16, 32>>(),
        ),
        (
            "ScanLoop<Fix, 8, 24>",
            std::mem::size_of::<Loop<Fix, 8, 24>>(),
        ),
        (
            "ScanLoop<f32, RangeAzimuthTrack, micro:bit capacities> (the micro:bit's)",
            std::mem::size_of::<MicrobitLoop>(),
        ),
        ("Intake<128>", std::mem::size_of::<Intake<128>>()),
        ("Intake<32>", std::mem::size_of::<Intake<32>>()),
        (
            "MeasurementReport",
            std::mem::size_of::<MeasurementReport>(),
        ),
        ("Decoder", std::mem::size_of::<Decoder>()),
    ] {
        eprintln!("{name}: {size} bytes");
    }
    // The micro:bit's 16 KiB: the scan loop (32 tracks), the receiver and
    // the stack; scripts/stack.sh checks the stack's margin on the board
    // (docs/tcas.md, "RAM per intruder").
    assert!(std::mem::size_of::<MicrobitLoop>() < 12 * 1024);
}

/// Two confirmed tracks with the same nearest measurement (docs/firmware-
/// runtime.md, "Capacity"): X (1000, 0) and Y (1000, 60), whose nearest is
/// mX (28 m from X and 32 m from Y), and Z far away. With room for three of
/// the four, mX, Y's own mY (35 m off Y, its second nearest, protected
/// because its nearest is shared) and Z's mZ are kept, and a clutter return
/// 20 m from Z, nearer its track than mY is to Y, is dropped: every track is
/// updated. When only the nearest was protected, the clutter took mY's
/// place and Y coasted the scan. With room for four, all four are taken.
/// The same in every order of arrival.
#[test]
fn two_tracks_sharing_their_nearest_measurement_each_keep_one() {
    fn scan<const M: usize>(order: [usize; 4]) -> (u16, u16, u16) {
        let config = demo_config::crossing_config::<f64, _>().unwrap();
        let mut scan_loop: Box<Loop<f64, 8, M>> = Box::new(Loop::new());
        let mut q = Box::new(MeasurementQueue::<64>::new());
        let point = |t: u32, x: f64, y: f64| {
            MeasurementReport::cartesian_from_metres(t, 1, x, y, None).unwrap()
        };
        for k in 0..4u32 {
            for [x, y] in [[1000.0, 0.0], [1000.0, 60.0], [3000.0, 0.0]] {
                q.push(point(k * 1000, x, y)).unwrap();
            }
            scan_loop.on_tick(&config, q.as_mut(), |_| {}).unwrap();
        }
        let confirmed = scan_loop.table().tracks().filter(|t| t.is_confirmed());
        assert_eq!(confirmed.count(), 3);
        let last_scan = [
            [1000.0, 28.0],
            [1000.0, 95.0],
            [3000.0, 0.0],
            [3000.0, 20.0],
        ];
        for [x, y] in order.map(|i| last_scan[i]) {
            q.push(point(4000, x, y)).unwrap();
        }
        let tick = scan_loop.on_tick(&config, q.as_mut(), |_| {}).unwrap();
        let c = tick.summary.counts;
        (c.updated, c.over_capacity, tick.scan.coasted as u16)
    }
    for a in 0..4 {
        for b in (0..4).filter(|&b| b != a) {
            for c in (0..4).filter(|&c| c != a && c != b) {
                let order = [a, b, c, 6 - a - b - c];
                assert_eq!(scan::<4>(order), (3, 0, 0), "{order:?}");
                assert_eq!(scan::<3>(order), (3, 1, 0), "{order:?}");
            }
        }
    }
}

/// The capacity ranking forms no gate for a confirmed track the tracker
/// will end for its width (the design's rule 7): with room for one of two
/// returns, the confirmed track's own (3 km out) is not protected, and the
/// return nearer the own aircraft (500 m) takes the place. The track ends
/// (its gate is wider than the 1 m bound), and the kept return is the first
/// point the next scan starts a track from.
#[test]
fn a_track_ended_for_its_gate_width_protects_nothing() {
    let config = demo_config::crossing_config::<f64, _>().unwrap();
    let mut bounded = demo_config::crossing_config::<f64, _>().unwrap();
    bounded.tracker = bounded.tracker.with_max_gate_radius(1.0).unwrap();
    let mut scan_loop: Box<Loop<f64, 8, 1>> = Box::new(Loop::new());
    let mut q = Box::new(MeasurementQueue::<64>::new());
    let point =
        |t: u32, x: f64| MeasurementReport::cartesian_from_metres(t, 1, x, 0.0, None).unwrap();
    for k in 0..4u32 {
        q.push(point(k * 1000, 3000.0)).unwrap();
        scan_loop.on_tick(&config, q.as_mut(), |_| {}).unwrap();
    }
    let confirmed = scan_loop.table().tracks().filter(|t| t.is_confirmed());
    assert_eq!(confirmed.count(), 1);
    q.push(point(4000, 3000.0)).unwrap();
    q.push(point(4000, 500.0)).unwrap();
    let tick = scan_loop.on_tick(&bounded, q.as_mut(), |_| {}).unwrap();
    let c = tick.summary.counts;
    assert_eq!((c.used, c.over_capacity, c.updated), (1, 1, 0), "{c}");
    assert_eq!(scan_loop.table().tracks().count(), 0);
    q.push(point(5000, 510.0)).unwrap();
    scan_loop.on_tick(&bounded, q.as_mut(), |_| {}).unwrap();
    let started: Vec<[f64; 2]> = scan_loop.table().tracks().map(|t| t.position()).collect();
    assert_eq!(started.len(), 1, "{started:?}");
    assert!((started[0][0] - 510.0).abs() < 1.0, "{started:?}");
}

/// Capacity under clutter (abtrack::scan, "Capacity"): three confirmed
/// tracks 4 km out, then a scan with room for 8 of 53 returns: 40 clutter
/// returns within 500 m of the own aircraft, 10 more clutter returns 20 m
/// from track 0's prediction (closer than the other tracks' targets are to
/// theirs), and the three targets last (track 0's 3 m off, the others'
/// 40 m off). First come, first served would keep only clutter; by gate
/// distance alone track 0's clutter would take every slot; each confirmed
/// track's nearest measurement is kept.
#[test]
fn confirmed_tracks_are_never_starved() {
    fn run<S: Scalar>() {
        let config = demo_config::crossing_config::<S, _>().unwrap();
        let mut scan_loop: Box<Loop<S, 8, 8>> = Box::new(Loop::new());
        let mut out = Output::default();
        let truth = |k: u32, n: usize| -> [f64; 2] {
            let angle = n as f64 * 2.0;
            let r = 4000.0 - 50.0 * k as f64;
            [r * angle.cos(), r * angle.sin()]
        };
        let at_xy = |t: u32, p: [f64; 2]| {
            MeasurementReport::cartesian_from_metres(t, 1, p[0], p[1], None).unwrap()
        };
        let mut q = Box::new(MeasurementQueue::<128>::new());
        for k in 0..4 {
            for n in 0..3 {
                q.push(at_xy(k * 1000, truth(k, n))).unwrap();
            }
            scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
        }
        assert_eq!(
            scan_loop
                .table()
                .tracks()
                .filter(|t| t.is_confirmed())
                .count(),
            3
        );
        let mut rng = Lcg(7);
        let k = 4;
        let t = k * 1000;
        for _ in 0..40 {
            q.push(at_xy(t, [500.0 * rng.signed(), 350.0 * rng.signed()]))
                .unwrap();
        }
        let p0 = truth(k, 0);
        for _ in 0..10 {
            let angle = rng.signed() * std::f64::consts::PI;
            q.push(at_xy(
                t,
                [p0[0] + 20.0 * angle.cos(), p0[1] + 20.0 * angle.sin()],
            ))
            .unwrap();
        }
        q.push(at_xy(t, [p0[0] + 3.0, p0[1] - 2.0])).unwrap();
        for n in 1..3 {
            let p = truth(k, n);
            q.push(at_xy(t, [p[0] + 40.0, p[1]])).unwrap();
        }
        let before = out.tracks().len();
        let tick = scan_loop.on_tick(&config, q.as_mut(), out.sink()).unwrap();
        let c = tick.summary.counts;
        assert_eq!((c.used, c.over_capacity), (8, 45), "{c}");
        assert_eq!(c.updated, 3, "{c}");
        let tracks = &out.tracks()[before..];
        assert_eq!(tracks.len(), 3);
        for r in tracks {
            assert_eq!(r.status, TrackStatus::Confirmed);
            let d = (0..3)
                .map(|n| {
                    let p = truth(k, n);
                    (p[0] - r.x_cm as f64 / 100.0).hypot(p[1] - r.y_cm as f64 / 100.0)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(d < 45.0, "{r:?}: {d} m from its target");
        }
    }
    run::<f64>();
    run::<f32>();
    run::<Fix>();
}

/// What the tracker turns away is counted over the run as well as scan by
/// scan, and counts against the run's verdict: replies at range 0 pass the
/// frame's envelope and reach the micro:bit's range–azimuth tracker, whose
/// filter refuses them. The lifetime counts are the scan summaries' added
/// up.
#[test]
fn measurements_the_tracker_rejects_are_counted_over_the_run() {
    use abtrack_firmware::number_types::cortex_m0::Wide;
    let demo = frames::scenario_reports(frames::TCAS_DEMO, 1, 1).unwrap();
    let times: BTreeSet<u32> = demo.iter().map(|r| r.time_ms).collect();
    let mut reports = Vec::new();
    for t in times {
        reports.extend(demo.iter().filter(|r| r.time_ms == t).copied());
        reports.push(MeasurementReport {
            time_ms: t,
            sensor: 1,
            position: MeasuredPosition::Polar {
                range_cm: 0,
                azimuth_bam: 0,
            },
            altitude_ft: None,
            altitude_25ft: false,
            address: None,
        });
    }
    let encoded = frames::encode(&reports, Faults::default());
    let fw = frames::run_like_the_firmware::<
        Wide,
        _,
        abtrack::track::RangeAzimuthTrack<Wide>,
        { microbit::TRACKS },
        { microbit::MEASUREMENTS_PER_SCAN },
        { microbit::QUEUE_LEN },
    >(
        &encoded.bytes,
        &demo_config::demo_config::<Wide, _>().unwrap(),
    );
    let scans: Vec<ScanSummary> = frames::decode_all(&fw.output)
        .0
        .into_iter()
        .filter_map(|m| match m {
            Message::Scan(s) => Some(s),
            _ => None,
        })
        .collect();
    let added = |f: fn(&ScanSummary) -> u16| scans.iter().map(|s| u32::from(f(s))).sum::<u32>();
    let c = fw.health.scan;
    assert!(c.rejected > 0, "{c:?}");
    assert_eq!(c.rejected, added(|s| s.counts.rejected));
    assert_eq!(c.not_assigned, added(|s| s.counts.not_assigned));
    let verdict = fw.verdict.unwrap();
    let transport = fw.health.decoder.frames_lost
        + fw.health.intake.queue_full
        + c.late
        + c.out_of_window
        + c.over_capacity
        + c.invalid;
    assert_eq!(verdict.lost, transport + c.rejected);
}
