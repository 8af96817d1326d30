//! Issue 11's firmware-runtime findings, each reproduced on the scan core
//! (the code the firmware runs), before the fixes.

#[path = "../../src/firmware/demo_config.rs"]
mod demo_config;

use abtrack::scan::{Intake, ScanLoop};
use abtrack::track::{FixedGainTrack, TrackTable};
use abtrack::wire::{crc16, Decoder, MeasuredPosition, MeasurementReport, Message, MAX_FRAME_LEN};
use heapless::spsc::Queue;

type Loop<const N: usize, const M: usize> = ScanLoop<f64, FixedGainTrack<f64>, N, M>;

fn frame(m: &Message) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = m.emit(&mut buf).unwrap();
    buf[..n].to_vec()
}

fn at(t: u32, x: f64, y: f64) -> MeasurementReport {
    MeasurementReport::cartesian_from_metres(t, 1, x, y, None).unwrap()
}

/// "ScanReport::outside_gates counts unused capacity slots (a scan with 0
/// measurements reports 8)".
#[test]
fn empty_scan_counts_nothing_outside_the_gates() {
    let config = demo_config::demo_config::<f64>().unwrap();
    let mut table: Box<TrackTable<f64, FixedGainTrack<f64>, 4, 8>> = Box::new(TrackTable::new());
    let mut codes = [abtrack::track::Association::OutsideGates; 8];
    let report = table.scan(&config.tracker, 0, &[], &mut codes).unwrap();
    assert_eq!(report.outside_gates, 0, "{report:?}");
}

/// "mid-stream truncated frames are counted as CRC errors".
#[test]
fn truncated_frame_mid_stream_is_counted_as_truncated() {
    let first = frame(&Message::Measurement(at(1000, 10.0, 20.0)));
    let second = frame(&Message::Measurement(at(1000, 30.0, 40.0)));
    let mut stream = first[..first.len() - 5].to_vec();
    stream.extend(&second);
    let mut d = Decoder::new();
    for &b in &stream {
        let mut e = d.push(b);
        while e.is_some() {
            e = d.poll();
        }
    }
    assert_eq!(
        (d.stats().truncated, d.stats().crc_errors),
        (1, 0),
        "{:?}",
        d.stats()
    );
}

/// "a sensor whose clock starts at 12:00 (43.2e6 ms) makes the M0 run
/// 30,000 empty scans before the first data": the scan clock starts at 0.
#[test]
fn sensor_clock_far_from_zero_is_used_by_the_first_scan() {
    let config = demo_config::demo_config::<f64>().unwrap();
    let mut queue: Queue<MeasurementReport, 16> = Queue::new();
    let (mut producer, mut consumer) = queue.split();
    producer.enqueue(at(43_200_000, 100.0, 0.0)).unwrap();
    let mut scan_loop: Box<Loop<4, 8>> = Box::new(Loop::new());
    // The firmware's first scan.
    let tick = scan_loop
        .on_tick(&config, 0, &mut consumer, |_| {})
        .unwrap();
    assert_eq!(tick.summary.measurements, 1, "{tick:?}");
}

/// "a +40-day jump wraps past 2³¹ ms and every later measurement is late".
#[test]
fn jump_past_2_31_ms_does_not_make_later_frames_late() {
    let config = demo_config::demo_config::<f64>().unwrap();
    let mut queue: Queue<MeasurementReport, 16> = Queue::new();
    let (mut producer, mut consumer) = queue.split();
    let mut scan_loop: Box<Loop<4, 8>> = Box::new(Loop::new());
    const FORTY_DAYS_MS: u32 = 40 * 86_400_000;
    let mut late = 0;
    for k in 0..10u32 {
        let t = if k < 5 {
            k * 1000
        } else {
            (k * 1000).wrapping_add(FORTY_DAYS_MS)
        };
        producer.enqueue(at(t, 100.0 * k as f64, 0.0)).unwrap();
        let tick = scan_loop
            .on_tick(&config, k * 1000, &mut consumer, |_| {})
            .unwrap();
        late += tick.summary.late;
    }
    assert_eq!(late, 0);
}

/// "a 5,000-frame flood in one scan is mostly labelled late rather than
/// over capacity": the firmware ran a scan as soon as its batch was full
/// (src/main.rs, `batch_is_full`), and the rest of the flood was late for
/// the next one. Paced here as the firmware paced it.
#[test]
fn flood_beyond_capacity_is_counted_as_over_capacity() {
    let config = demo_config::demo_config::<f64>().unwrap();
    let mut queue: Queue<MeasurementReport, 128> = Queue::new();
    let (producer, mut consumer) = queue.split();
    let mut intake = Intake::new(producer);
    let mut scan_loop: Box<Loop<32, 64>> = Box::new(Loop::new());
    let mut bytes = Vec::new();
    for k in 0..5000 {
        bytes.extend(frame(&Message::Measurement(at(
            0,
            (k % 100) as f64 * 50.0,
            (k / 100) as f64 * 50.0,
        ))));
    }
    bytes.extend(frame(&Message::Measurement(at(1000, 0.0, 0.0))));
    let mut now = 0;
    let (mut late, mut dropped) = (0u32, 0u32);
    for &b in &bytes {
        if !intake.can_take_byte() {
            scan_loop.collect(&mut consumer, now);
        }
        intake.push(b);
        scan_loop.collect(&mut consumer, now);
        let ahead = consumer.peek().is_some();
        if ahead || scan_loop.batch_is_full() {
            let t = scan_loop
                .on_tick(&config, now, &mut consumer, |_| {})
                .unwrap();
            late += t.summary.late as u32;
            dropped += t.summary.dropped as u32;
            now += 1000;
        }
    }
    let t = scan_loop
        .on_tick(&config, now, &mut consumer, |_| {})
        .unwrap();
    late += t.summary.late as u32;
    dropped += t.summary.dropped as u32;
    assert_eq!((late, dropped), (0, 5000 - 64));
}

/// "A fuzzer built a CRC-16 collision that made up a polar measurement at
/// 28,823 km and swallowed the real frame behind it, counting nothing."
/// Built here by hand: a polar header and 16 payload bytes, two of them
/// chosen so that the CRC-16 equals the real frame's sync bytes, which
/// follow.
#[test]
fn a_crc_collision_does_not_swallow_the_real_frame() {
    let real = Message::Measurement(at(2000, 1500.0, -700.0));
    let real_bytes = frame(&real);
    let mut fake = vec![0xAB, 0xCD, 0x02, 16];
    let mut payload = [0u8; 16];
    payload[6..10].copy_from_slice(&2_882_300_000u32.to_be_bytes()); // 28,823 km
    let target = u16::from_be_bytes([real_bytes[0], real_bytes[1]]);
    let mut found = false;
    'search: for a in 0..=255u8 {
        for b in 0..=255u8 {
            payload[0] = a;
            payload[1] = b;
            let mut covered = vec![0x02, 16];
            covered.extend_from_slice(&payload);
            if crc16(&covered) == target {
                found = true;
                break 'search;
            }
        }
    }
    assert!(found);
    fake.extend_from_slice(&payload);
    let mut stream = fake;
    stream.extend(&real_bytes);
    let mut d = Decoder::new();
    let mut messages = Vec::new();
    for &b in &stream {
        let mut e = d.push(b);
        while let Some(r) = e {
            if let Ok(m) = r {
                messages.push(m);
            }
            e = d.poll();
        }
    }
    let fake_decoded = messages.iter().any(|m| {
        matches!(m, Message::Measurement(r) if matches!(r.position, MeasuredPosition::Polar { range_cm, .. } if range_cm == 2_882_300_000))
    });
    assert!(
        !fake_decoded,
        "the made-up frame was accepted: {messages:?}"
    );
    assert!(
        messages.contains(&real),
        "the real frame was lost: {messages:?}"
    );
}

/// Deterministic pseudo-random numbers (64-bit LCG, Knuth's MMIX constants).
struct Lcg(u64);
impl Lcg {
    fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 11
    }
    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f64 {
        (self.next_u64() as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// The two targets of the crossing (scan_loop.rs): A from (−3000, −1500) m
/// moving (100, 50) m/s, B from (−3000, 1500) m moving (100, −50) m/s.
fn crossing_truth(t: f64) -> [[f64; 2]; 2] {
    [
        [-3000.0 + 100.0 * t, -1500.0 + 50.0 * t],
        [-3000.0 + 100.0 * t, 1500.0 - 50.0 * t],
    ]
}

/// The crossing with 200 clutter measurements per scan (uniform over the
/// ±5 km square) shuffled with the two targets, paced as the old firmware
/// paced it; returns, per target, the scans (of 60) in which a confirmed
/// track was reported within 150 m of it.
fn clutter_storm<const N: usize, const M: usize, const Q: usize>() -> [usize; 2] {
    let config = demo_config::demo_config::<f64>().unwrap();
    let mut queue: Queue<MeasurementReport, Q> = Queue::new();
    let (producer, mut consumer) = queue.split();
    let mut intake = Intake::new(producer);
    let mut scan_loop: Box<Loop<N, M>> = Box::new(Loop::new());
    let mut rng = Lcg(0xC1u64 << 32 | 0x77E4);
    let mut bytes = Vec::new();
    for k in 0..60u32 {
        let truth = crossing_truth(k as f64);
        let mut points: Vec<[f64; 2]> = truth
            .iter()
            .map(|p| [p[0] + 15.0 * rng.signed(), p[1] + 15.0 * rng.signed()])
            .collect();
        for _ in 0..200 {
            points.push([5000.0 * rng.signed(), 5000.0 * rng.signed()]);
        }
        for i in (1..points.len()).rev() {
            points.swap(i, rng.below(i + 1));
        }
        for p in points {
            bytes.extend(frame(&Message::Measurement(at(k * 1000, p[0], p[1]))));
        }
    }
    let mut tracked = [0usize; 2];
    let mut now = 0u32;
    let mut count = |out: &Message| {
        if let Message::Track(t) = out {
            let truth = crossing_truth(t.time_ms as f64 / 1000.0);
            let (x, y) = (t.x_cm as f64 / 100.0, t.y_cm as f64 / 100.0);
            for (n, p) in truth.iter().enumerate() {
                if (p[0] - x).hypot(p[1] - y) < 150.0 {
                    tracked[n] += 1;
                }
            }
        }
    };
    for &b in &bytes {
        if !intake.can_take_byte() {
            scan_loop.collect(&mut consumer, now);
        }
        intake.push(b);
        scan_loop.collect(&mut consumer, now);
        if consumer.peek().is_some() || scan_loop.batch_is_full() {
            scan_loop
                .on_tick(&config, now, &mut consumer, &mut count)
                .unwrap();
            now += 1000;
        }
    }
    scan_loop
        .on_tick(&config, now, &mut consumer, &mut count)
        .unwrap();
    tracked
}

/// "With 200 clutter measurements per scan shuffled with the targets, the
/// real targets are tracked in 15–19 of 60 scans on the mps2 boards and 0–1
/// on the micro:bit."
#[test]
fn targets_stay_tracked_in_a_clutter_storm() {
    let mps2 = clutter_storm::<32, 64, 128>();
    let microbit = clutter_storm::<8, 24, 32>();
    eprintln!("scans (of 60) with each target tracked: mps2 capacity {mps2:?}, micro:bit capacity {microbit:?}");
    assert!(
        mps2.iter().chain(&microbit).all(|&n| n >= 50),
        "{mps2:?} {microbit:?}"
    );
}
