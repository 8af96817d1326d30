//! Gaps and timing never refuse a recording: an interval beyond the
//! filters' range (20 s) restarts the estimate, one below it (0.05 s) is
//! skipped and leaves the state as it was, in every layer (filter,
//! scheduled filter, M5 bank, track table, scan loop, replay) and every
//! number system (f64, f32, Q32.32, the fast fixed point).

use abtrack::bank::{BankConfig, BankOutcome, CartesianBank};
use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
use abtrack::filter::auto::{AutoFilter, AutoUpdate};
use abtrack::filter::{
    Cartesian, FilterError, IntervalSpan, Phase, UpdateOutcome, MAX_INTERVAL_S, MIN_INTERVAL_S,
};
use abtrack::gain::{
    AutoConfig, AutoGains, FixedGains, LeastSquaresGains, ScheduledError, ScheduledFilter,
};
use abtrack::num::fixed32::Fixed32;
use abtrack::num::{Numeric, Quantity};
use abtrack::scan::{ClockConfig, MeasurementQueue, ScanConfig, ScanLoop};
use abtrack::tcas::OwnAircraft;
use abtrack::track::{
    Association, FixedGainTrack, Gate, Measurement, RejectReason, TrackTable, TrackerConfig,
};
use abtrack::wire::{MeasurementReport, Message};
use abtrack::{Fix, Gains};
use abtrack_host_tests::replay::{replay_events, Replayed};
use abtrack_host_tests::replay_tracker::{replay_tracker_reader, TrackerReplay};

fn q<Q: Quantity>(v: f64) -> Q {
    Q::try_from_f64(v).unwrap()
}

#[test]
fn the_range_is_the_envelope() {
    assert_eq!((MIN_INTERVAL_S, MAX_INTERVAL_S), (0.05, 20.0));
    assert_eq!(IntervalSpan::of(0.049), Ok(IntervalSpan::TooShort));
    assert_eq!(IntervalSpan::of(0.05), Ok(IntervalSpan::InRange));
    assert_eq!(IntervalSpan::of(20.0), Ok(IntervalSpan::InRange));
    assert_eq!(IntervalSpan::of(20.001), Ok(IntervalSpan::TooLong));
    // Malformed intervals stay errors.
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            IntervalSpan::of(dt),
            Err(FilterError::InvalidInterval),
            "{dt}"
        );
    }
}

/// A 2-D αβ track with fixed gains (a [`ScheduledFilter`], what holds a
/// track; the bare [`Cartesian`] filter computes the equations for any
/// interval > 0) on a straight line at (10, −5) m/s: a report 10 ms after
/// the last is skipped with the state bit-identical; one 30 s later
/// restarts (first point of a new estimate), and the next two-point
/// initialisation takes its velocity from the new points only.
fn gap_and_close_report<N: Numeric>() {
    let gains = Gains::<N>::alpha_beta_f64(0.5, 0.2).unwrap();
    let mut f = ScheduledFilter::<N, _, 2, 2>::new(FixedGains::new(gains));
    let z = |x: f64, y: f64| [q::<N::Length>(x), q::<N::Length>(y)];
    let one: N::Interval = q(1.0);
    for k in 0..4 {
        let t = f64::from(k);
        f.update(z(10.0 * t, -5.0 * t), one).unwrap();
    }
    let before = f;
    let out = f.update(z(31.0, -15.5), q(0.01)).unwrap();
    assert_eq!(out.outcome, [UpdateOutcome::Skipped; 2], "{}", N::NAME);
    assert_eq!(f, before, "{}", N::NAME);
    // Malformed intervals are refused, the state untouched.
    assert_eq!(
        f.update(z(31.0, -15.5), N::Interval::ZERO),
        Err(ScheduledError::Filter(FilterError::InvalidInterval))
    );
    assert_eq!(f, before);
    // The bare filter extrapolates over 30 s as its equations say.
    let mut bare: Cartesian<N, 2, 2> = *f.filter();
    assert!(matches!(
        bare.update(z(340.0, -170.0), q(30.0), &gains).unwrap(),
        [UpdateOutcome::Filtered(_), UpdateOutcome::Filtered(_)]
    ));
    // 30 s of silence, the target reappears elsewhere.
    let out = f.update(z(1000.0, 2000.0), q(30.0)).unwrap();
    assert_eq!(out.outcome, [UpdateOutcome::Restarted; 2], "{}", N::NAME);
    assert!(out.restarted);
    assert_eq!(f.filter().phase(), Phase::OnePoint);
    let [x, y] = f.filter().position();
    assert!((x.to_f64() - 1000.0).abs() < 1e-3 && (y.to_f64() - 2000.0).abs() < 1e-3);
    let out = f.update(z(1020.0, 1990.0), q(2.0)).unwrap();
    assert_eq!(out.outcome, [UpdateOutcome::SecondPoint; 2]);
    let [vx, vy] = f.filter().velocity();
    assert!((vx.to_f64() - 10.0).abs() < 1e-3 && (vy.to_f64() + 5.0).abs() < 1e-3);
    assert!(matches!(
        f.update(z(1030.0, 1985.0), one).unwrap().outcome,
        [UpdateOutcome::Filtered(_), UpdateOutcome::Filtered(_)]
    ));
}

#[test]
fn a_gap_restarts_a_track_and_a_close_report_is_skipped() {
    gap_and_close_report::<f64>();
    gap_and_close_report::<f32>();
    gap_and_close_report::<Fix>();
    gap_and_close_report::<Fixed32>();
}

/// The schedule restarts with the filter: after a gap the least-squares
/// count starts again (n = 3 gives α̂ = 5/6, β̂ = 1/2, Al-Wagih eq. 24).
fn schedule_restarts<N: Numeric>() {
    let mut track = ScheduledFilter::<N, _, 2, 1>::new(LeastSquaresGains::default());
    let one: N::Interval = q(1.0);
    for k in 0..10 {
        track.update([q(10.0 * f64::from(k))], one).unwrap();
    }
    assert_eq!(track.measurements(), 10);
    let before = track;
    let skipped = track.update([q(95.0)], q(0.02)).unwrap();
    assert_eq!(skipped.outcome, [UpdateOutcome::Skipped]);
    assert!(!skipped.restarted && skipped.gains.is_none());
    assert_eq!(track, before, "{}", N::NAME);
    let restarted = track.update([q(500.0)], q(25.0)).unwrap();
    assert!(restarted.restarted, "{}", N::NAME);
    assert_eq!(restarted.outcome, [UpdateOutcome::Restarted]);
    assert_eq!(track.measurements(), 1);
    track.update([q(510.0)], one).unwrap();
    let third = track.update([q(520.0)], one).unwrap();
    let g = third.gains.unwrap()[0];
    assert!((g.alpha().to_f64() - 5.0 / 6.0).abs() < 1e-6, "{}", N::NAME);
    assert!((g.beta().to_f64() - 0.5).abs() < 1e-6, "{}", N::NAME);
}

#[test]
fn a_scheduled_filter_restarts_its_schedule_on_a_gap() {
    schedule_restarts::<f64>();
    schedule_restarts::<f32>();
    schedule_restarts::<Fix>();
    schedule_restarts::<Fixed32>();
}

#[test]
fn the_m5_bank_restarts_and_skips_the_same_way() {
    let mut bank = CartesianBank::<f64, 8, 2>::from_config(&BankConfig::DEFAULT).unwrap();
    for k in 0..5 {
        let t = f64::from(k);
        bank.update([10.0 * t, 0.0], 1.0).unwrap();
    }
    let before = bank;
    assert_eq!(
        bank.update([41.0, 0.0], 0.001).unwrap(),
        [BankOutcome::Skipped; 2]
    );
    assert_eq!(bank, before);
    assert_eq!(
        bank.update([900.0, 0.0], 21.0).unwrap(),
        [BankOutcome::Restarted; 2]
    );
    assert_eq!(bank.phase(), Phase::OnePoint);
    assert_eq!(bank.position(), [900.0, 0.0]);
}

/// A track holding one point, coasted past the filters' longest interval
/// (and, in the fast fixed point, past its interval type's 128 s), restarts
/// from its next report, which becomes the new first point, in each layer
/// that holds a track: the scheduled filter (its saturation count kept
/// through the restart), the fused default filter and the M5 bank.
fn one_point_coasted_past_the_range<N: Numeric>() {
    let z = |x: f64| [q::<N::Length>(x), q::<N::Length>(0.0)];
    let ten: N::Interval = q(10.0);
    let one: N::Interval = q(1.0);
    for coasts in [3, 13] {
        let gains = Gains::<N>::alpha_beta_f64(0.5, 0.2).unwrap();
        let mut scheduled = ScheduledFilter::<N, _, 2, 2>::new(FixedGains::new(gains));
        let mut auto = AutoFilter::<N, 2>::new();
        let noise = AutoGains::<N, 2>::new(&AutoConfig::cartesian(50.0)).unwrap();
        let noise = noise.shared_noise();
        let mut bank = CartesianBank::<N, 8, 2>::from_config(&BankConfig::DEFAULT).unwrap();
        scheduled.update(z(0.0), one).unwrap();
        auto.update(noise, z(0.0), one).unwrap();
        bank.update(z(0.0), one).unwrap();
        for _ in 0..coasts {
            // The fast fixed point refuses a coast beyond its 128 s (counted).
            let _ = scheduled.coast(ten);
            auto.coast(ten).unwrap();
            let _ = bank.coast(ten);
        }
        let saturations = scheduled.filter().saturations();
        let out = scheduled.update(z(5000.0), one).unwrap();
        assert_eq!(
            out.outcome,
            [UpdateOutcome::Restarted; 2],
            "{} {coasts}",
            N::NAME
        );
        assert_eq!(scheduled.filter().phase(), Phase::OnePoint);
        assert_eq!(scheduled.filter().saturations(), saturations, "{}", N::NAME);
        assert_eq!(
            auto.update(noise, z(5000.0), one),
            Ok(AutoUpdate::Restarted),
            "{} {coasts}",
            N::NAME
        );
        assert_eq!(auto.phase(), Phase::OnePoint);
        assert_eq!(
            bank.update(z(5000.0), one).unwrap(),
            [BankOutcome::Restarted; 2]
        );
        // The next report is the second point: velocity over its own 2 s.
        scheduled.update(z(5020.0), q(2.0)).unwrap();
        auto.update(noise, z(5020.0), q(2.0)).unwrap();
        bank.update(z(5020.0), q(2.0)).unwrap();
        let velocities = [
            scheduled.filter().velocity()[0].to_f64(),
            auto.velocity()[0].to_f64(),
            bank.velocity()[0].to_f64(),
        ];
        for v in velocities {
            assert!(
                (v - 10.0).abs() < 1e-3,
                "{} {coasts}: {velocities:?}",
                N::NAME
            );
        }
    }
}

#[test]
fn a_first_point_coasted_past_the_range_restarts() {
    one_point_coasted_past_the_range::<f64>();
    one_point_coasted_past_the_range::<f32>();
    one_point_coasted_past_the_range::<Fix>();
    one_point_coasted_past_the_range::<Fixed32>();
}

/// The fused default filter refuses a measurement that is not a valid
/// number (NaN, or a value that left the fixed formats) on every path, its
/// state unchanged: the first point, the second, a report too soon, after a
/// gap or after a first point coasted past the range, and a filtered update.
fn invalid_measurement_refused<N: Numeric>() {
    let noise = AutoGains::<N, 2>::new(&AutoConfig::cartesian(50.0)).unwrap();
    let noise = noise.shared_noise();
    let z = |x: f64| [q::<N::Length>(x), q::<N::Length>(0.0)];
    let invalid = [f64::NAN, 1.0e30]
        .map(N::Length::from_f64_lossy)
        .into_iter()
        .find(|v| !v.is_valid())
        .expect("an invalid length");
    let bad = [invalid, q::<N::Length>(0.0)];
    let one: N::Interval = q(1.0);
    let mut auto = AutoFilter::<N, 2>::new();
    let check = |auto: &mut AutoFilter<N, 2>, dt: N::Interval, what: &str| {
        let before = *auto;
        assert_eq!(
            auto.update(noise, bad, dt),
            Err(FilterError::InvalidMeasurement),
            "{} {what}",
            N::NAME
        );
        assert_eq!(*auto, before, "{} {what}", N::NAME);
    };
    check(&mut auto, one, "first point");
    auto.update(noise, z(0.0), one).unwrap();
    check(&mut auto, one, "second point");
    check(&mut auto, q(0.01), "too soon");
    check(&mut auto, q(30.0), "after a gap");
    let mut coasted = auto;
    for _ in 0..3 {
        coasted.coast(q(10.0)).unwrap();
    }
    check(
        &mut coasted,
        one,
        "after a first point coasted past the range",
    );
    auto.update(noise, z(10.0), one).unwrap();
    auto.update(noise, z(20.0), one).unwrap();
    check(&mut auto, one, "filtered");
}

#[test]
fn the_default_filter_refuses_an_invalid_measurement_on_every_path() {
    invalid_measurement_refused::<f64>();
    invalid_measurement_refused::<f32>();
    invalid_measurement_refused::<Fix>();
    invalid_measurement_refused::<Fixed32>();
}

// ------------------------------------------------------------ track table

type Table<S> = TrackTable<S, FixedGainTrack<S>, 8, 8>;

/// σ 5 m, G 13.8, a_max 5 m/s², v_max 300 m/s; confirmed tracks deleted
/// only after 255 misses, so a coasting track outlives the filters' range.
fn long_coast_config<S: Numeric>() -> TrackerConfig<S, Gains<S>> {
    let gains = Gains::alpha_beta_f64(0.5, 0.2).unwrap();
    let gate = Gate::uncertainty(q(5.0), q(13.8), q(5.0)).unwrap();
    TrackerConfig::new(gains, gate, q(300.0))
        .unwrap()
        .with_deletion(255, 2)
        .unwrap()
}

fn cart<S: Numeric>(x: f64, y: f64) -> Measurement<S> {
    Measurement::Cartesian { x: q(x), y: q(y) }
}

/// A target seen every 4 s, then unseen: the confirmed track coasts (the
/// time since its last update grows by 4 s a scan, past the filters' 20 s,
/// each step being one scan's 4 s) and keeps its id: the target's next
/// report updates it. Under a deletion rule of K misses it is deleted at
/// the K-th, never restarted.
fn coasting_track_keeps_its_id<S: Numeric>() {
    let config = long_coast_config::<S>();
    let mut table = Box::new(Table::<S>::new());
    let mut codes = [Association::NotAssigned; 1];
    let position = |t: f64| cart::<S>(1000.0 + 50.0 * t, 2000.0);
    for k in 0..4u32 {
        let t = f64::from(k) * 4.0;
        table
            .scan(&config, k * 4000, &[position(t)], &mut codes)
            .unwrap();
    }
    assert!(table.tracks().all(|t| t.is_confirmed()));
    let first = table.tracks().next().unwrap().id();
    // Last update at 12 s. Coasts at 16, 20, 24, 28, 32 s (20 s since).
    for k in 4..9u32 {
        let r = table.scan(&config, k * 4000, &[], &mut codes).unwrap();
        assert_eq!((r.restarted, r.coasted), (0, 1), "{} at {k}", S::NAME);
    }
    // 36 s: 24 s since the last update, beyond the filters' 20 s.
    let r = table
        .scan(&config, 36_000, &[position(36.0)], &mut codes)
        .unwrap();
    assert_eq!((r.restarted, r.updated, r.tracks), (0, 1, 1), "{}", S::NAME);
    assert_eq!(codes[0], Association::Updated(first), "{}", S::NAME);
    let [vx, _] = table.track(first).unwrap().velocity();
    assert!((vx.to_f64() - 50.0).abs() < 0.01, "{}", S::NAME);
    // Deleted at its 8th miss (68 s, 32 s after its last update).
    let config = long_coast_config::<S>().with_deletion(8, 2).unwrap();
    for k in 10..17u32 {
        let r = table.scan(&config, k * 4000, &[], &mut codes).unwrap();
        assert_eq!(
            (r.restarted, r.deleted, r.tracks),
            (0, 0, 1),
            "{} at {k}",
            S::NAME
        );
    }
    let r = table.scan(&config, 68_000, &[], &mut codes).unwrap();
    assert_eq!(
        (r.restarted, r.deleted_misses, r.tracks),
        (0, 1, 0),
        "{}",
        S::NAME
    );
    assert_eq!(table.stats().tracks_restarted, 0);
}

#[test]
fn a_coasting_track_keeps_its_id_past_the_longest_interval() {
    coasting_track_keeps_its_id::<f64>();
    coasting_track_keeps_its_id::<f32>();
    coasting_track_keeps_its_id::<Fix>();
    coasting_track_keeps_its_id::<Fixed32>();
}

/// A scan interval beyond 20 s restarts every track and drops the previous
/// scan's first points; the scan's measurements are the new first points.
#[test]
fn a_scan_after_a_long_silence_restarts_every_track() {
    let config = long_coast_config::<f64>();
    let mut table = Box::new(Table::<f64>::new());
    let mut codes = [Association::NotAssigned; 3];
    let scan = |k: f64| {
        [
            cart(50.0 * k, 0.0),
            cart(0.0, 5000.0 + 40.0 * k),
            cart(-9000.0 * k, 9000.0),
        ]
    };
    for k in 0..3u32 {
        table
            .scan(&config, k * 1000, &scan(f64::from(k)), &mut codes)
            .unwrap();
    }
    assert_eq!(table.len(), 2);
    assert!(table.pending() >= 1);
    let r = table
        .scan(&config, 60_000, &scan(60.0), &mut codes)
        .unwrap();
    assert_eq!((r.restarted, r.tracks, r.interval_ms), (2, 0, 58_000));
    assert!(codes.iter().all(|c| *c == Association::OutsideGates));
    assert_eq!(table.pending(), 3);
    table
        .scan(&config, 61_000, &scan(61.0), &mut codes)
        .unwrap();
    assert_eq!(
        codes
            .iter()
            .filter(|c| matches!(c, Association::Started(_)))
            .count(),
        2
    );
}

/// A scan less than 0.05 s after the previous one is skipped: every
/// measurement is coded and counted, the tracks and the scan time are
/// unchanged; the next scan's interval is from the last accepted one.
fn close_scan_is_skipped<S: Numeric>() {
    let config = long_coast_config::<S>();
    let mut table = Box::new(Table::<S>::new());
    let mut codes = [Association::NotAssigned; 2];
    for k in 0..3u32 {
        let t = f64::from(k);
        table
            .scan(&config, k * 1000, &[cart(100.0 * t, 0.0)], &mut codes[..1])
            .unwrap();
    }
    let tracks: Vec<_> = table.tracks().copied().collect();
    let stats = *table.stats();
    let r = table
        .scan(
            &config,
            2040,
            &[cart(204.0, 0.0), cart(7.0, 7.0)],
            &mut codes,
        )
        .unwrap();
    assert_eq!(
        (r.too_close, r.updated, r.coasted),
        (2, 0, 0),
        "{}",
        S::NAME
    );
    assert_eq!(codes, [Association::Rejected(RejectReason::TooClose); 2]);
    assert_eq!(table.tracks().copied().collect::<Vec<_>>(), tracks);
    assert_eq!(table.last_scan_ms(), Some(2000));
    assert_eq!(table.stats().scans_skipped, stats.scans_skipped + 1);
    assert_eq!(table.stats().scans, stats.scans);
    let r = table
        .scan(&config, 3000, &[cart(300.0, 0.0)], &mut codes[..1])
        .unwrap();
    assert_eq!((r.interval_ms, r.updated), (1000, 1));
}

#[test]
fn a_scan_too_close_to_the_previous_is_skipped() {
    close_scan_is_skipped::<f64>();
    close_scan_is_skipped::<f32>();
    close_scan_is_skipped::<Fix>();
    close_scan_is_skipped::<Fixed32>();
}

// ------------------------------------------------------------- scan loop

/// The scan loop runs one period per scan, so every step is in the
/// filters' range: a track coasting 25 s keeps its id and the target's
/// next report updates it; nothing restarts or is deleted.
#[test]
fn the_scan_loop_keeps_a_coasting_track_past_the_longest_interval() {
    let v = |x: f64| <f64 as Quantity>::try_from_f64(x).unwrap();
    let config = ScanConfig {
        tracker: long_coast_config::<f64>(),
        own: OwnAircraft::over_sea_level(v(5000.0), 0.0),
        altitude: AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeC).unwrap(),
        altitude_25ft: AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeS25).unwrap(),
        clock: ClockConfig::new(1000).unwrap(),
    };
    let at = |t: u32| {
        MeasurementReport::cartesian_from_metres(t, 1, 1000.0 + 0.05 * f64::from(t), 0.0, None)
            .unwrap()
    };
    let mut queue = Box::new(MeasurementQueue::<64>::new());
    for t in [0, 1000, 2000, 3000, 28_000] {
        queue.push(at(t)).unwrap();
    }
    let mut scan_loop: Box<ScanLoop<f64, FixedGainTrack<f64>, 4, 8>> = Box::new(ScanLoop::new());
    let mut summaries = Vec::new();
    let mut health = Vec::new();
    for _ in 0..30 {
        scan_loop
            .on_tick(&config, queue.as_mut(), |m| match m {
                Message::Scan(s) => summaries.push(*s),
                Message::Health(h) => health.push(*h),
                _ => {}
            })
            .unwrap();
    }
    // Last update at 3 s; the report at 28 s updates the same track.
    let updated_late: Vec<u32> = summaries
        .iter()
        .filter(|s| s.time_ms > 3000 && s.counts.updated > 0)
        .map(|s| s.time_ms)
        .collect();
    assert_eq!(updated_late.len(), 1, "{updated_late:?}");
    assert!(updated_late[0] >= 28_000, "{updated_late:?}");
    let stats = scan_loop.table().stats();
    assert_eq!(
        (
            stats.tracks_started,
            stats.tracks_restarted,
            stats.tracks_deleted
        ),
        (1, 0, 0)
    );
    assert_eq!(health.last().unwrap().table, *stats);
    assert_eq!(scan_loop.table().len(), 1);
}

// ------------------------------------------------------------------ replay

/// A recording with the timing of real ADS-B coverage: a repeated time, a
/// report 20 ms after the last, and holes of 26 and 60 s (a glider's).
const GAPPY: &str = "t,x,y\n\
0,0,0\n1,10,-5\n2,20,-10\n2,20.5,-10\n2.02,20.2,-10.1\n3,30,-15\n4,40,-20\n\
30,300,-150\n31,310,-155\n32,320,-160\n33,330,-165\n\
93,930,-465\n94,940,-470\n95,950,-475\n96,960,-480\n";

/// Report-time jitter at a start: the first two reports 0.1 s apart and
/// 200 m apart, a two-point velocity of 2,000 m/s, beyond the 1,500 m/s
/// envelope. With σ 50 m that velocity's σ is 50·√2/0.1 = 707 m/s, so `auto`
/// (which carries it) keeps the start; the next report brings the estimate
/// back inside the envelope.
#[test]
fn a_jittered_start_within_its_own_uncertainty_is_not_refused() {
    for numeric in ["f64", "f32", "q32.32"] {
        let run = replay("--filter auto --sigma-m 50", numeric, JITTERED_START);
        let rows: Vec<&str> = run.csv.lines().collect();
        assert_eq!(rows.len(), 6, "{numeric}");
        assert!((vx(rows[2]) - 2000.0).abs() < 1.0, "{numeric}: {}", rows[2]);
        assert!(vx(rows[3]).abs() < 1500.0, "{numeric}: {}", rows[3]);
        assert!(vx(rows[5]).abs() < 100.0, "{numeric}: {}", rows[5]);
        assert!(run.events.is_empty(), "{numeric}: {:?}", run.events);
    }
}

/// A file whose first two reports are 0.1 s and 200 m apart, then a slow
/// straight track ([`a_jittered_start_within_its_own_uncertainty_is_not_refused`]).
const JITTERED_START: &str = "t,x,y\n0.45,0,0\n0.55,200,-10\n2,210,-15\n3,220,-20\n4,230,-25\n";

/// One of each kind of x/y filter `replay` runs: `auto` (with σ 5 m, whose
/// covariance allows little), a count schedule, fixed αβ and αβγ gains, a
/// context schedule and the bank.
const CARTESIAN_FILTERS: [&str; 6] = [
    "--filter auto --sigma-m 5",
    "--filter ab --schedule least-squares",
    "--filter ab --alpha 0.5 --beta 0.2",
    "--filter abg --alpha 0.5 --beta 0.2 --gamma 0.02",
    "--filter abg --schedule tcas-firmness",
    "--filter ab --schedule bank",
];

/// The number systems of `replay`'s x/y filters.
const REPLAY_NUMERICS: [&str; 3] = ["f64", "f32", "q32.32"];

/// The `vx` cell of a Cartesian output row (`t,x,vx,…`).
fn vx(row: &str) -> f64 {
    row.split(',').nth(2).unwrap().parse().unwrap()
}

/// The same jittered start for the filters that carry no covariance (and
/// for `auto` with σ 5 m, whose velocity σ of 71 m/s puts it beyond three
/// of them): the start is dropped and the estimate starts again from its
/// row, marked `restarted` and listed on stderr; the run goes on.
#[test]
fn a_start_outside_the_velocity_envelope_starts_again_from_its_row() {
    for filter in CARTESIAN_FILTERS {
        for numeric in REPLAY_NUMERICS {
            let run = replay(filter, numeric, JITTERED_START);
            let rows: Vec<&str> = run.csv.lines().collect();
            assert_eq!(rows.len(), 6, "{filter} {numeric}");
            // The row that completed the start is the new estimate's first
            // point: its position, no velocity.
            assert!(
                rows[2].starts_with("0.55,200,0,"),
                "{filter} {numeric}: {}",
                rows[2]
            );
            assert!(
                rows[2].ends_with(",restarted"),
                "{filter} {numeric}: {}",
                rows[2]
            );
            assert!(
                (vx(rows[3]) - 10.0 / 1.45).abs() < 0.01,
                "{filter} {numeric}: {}",
                rows[3]
            );
            assert_eq!(run.events.restarted_starts, ["0.55"], "{filter} {numeric}");
            assert!(run.events.restarted.is_empty(), "{filter} {numeric}");
            assert!(
                run.events.to_string().starts_with(
                    "replay: 1 restarted: the two-point start ending there left the velocity envelope"
                ),
                "{}",
                run.events
            );
        }
    }
}

/// The range–azimuth filter gets the same policy: for a sensor of σ_R 15 m
/// and σ_B 0.5° (a cross-range σ of 195 m at 22 km, a two-point velocity σ
/// of 2.8 km/s over 0.1 s), a start 5 km out of place over 0.1 s (50 km/s)
/// starts again from its row, in every number system, the firmware's
/// included.
#[test]
fn a_polar_start_outside_the_velocity_envelope_starts_again_from_its_row() {
    let mut text = String::from("t,range,azimuth\n");
    for (t, x) in [
        (0.45, -5000.0),
        (0.55, 0.0),
        (2.0, 10.0),
        (3.0, 20.0),
        (4.0, 30.0),
    ] {
        let (x, y) = (20_000.0 + x, 10_000.0);
        text.push_str(&format!("{t},{},{}\n", f64::hypot(x, y), f64::atan2(x, y)));
    }
    for numeric in ["f64", "f32", "q32.32", "fixed32"] {
        let sensor = "--filter range-azimuth --range-sigma-m 15 --bearing-sigma-deg 0.5";
        let run = replay(sensor, numeric, &text);
        let rows: Vec<&str> = run.csv.lines().collect();
        assert_eq!(rows.len(), 6, "{numeric}");
        assert!(rows[2].ends_with(",restarted"), "{numeric}: {}", rows[2]);
        assert_eq!(vx(rows[2]), 0.0, "{numeric}: {}", rows[2]);
        assert!(
            (vx(rows[3]) - 10.0 / 1.45).abs() < 1.0,
            "{numeric}: {}",
            rows[3]
        );
        assert_eq!(run.events.restarted_starts, ["0.55"], "{numeric}");
    }
}

/// Reports that keep moving faster than the envelope are not jitter: the
/// start from the restarted row leaves it too, and the run stops there.
#[test]
fn reports_faster_than_the_envelope_stop_at_the_second_start() {
    let text = "t,x,y\n0,0,0\n1,2000,0\n2,4000,0\n3,6000,0\n";
    for filter in [
        "--filter auto --sigma-m 50",
        "--filter ab --alpha 0.5 --beta 0.2",
        "--filter ab --schedule bank",
    ] {
        let e = replay_failure(filter, "f64", text);
        assert!(
            e.starts_with("line 4: after this row the estimate vx = 2.000000e3 m/s"),
            "{filter}: {e}"
        );
    }
    // A gap's restart begins a new estimate and clears the mark: after the
    // gaps at 60 s (right after the first restart) and 130 s, a fast start
    // restarts again rather than stopping the run.
    let text = "t,x,y\n0,0,0\n0.1,200,0\n60,800,0\n60.1,1000,0\n61,1010,0\n62,1020,0\n\
                130,1700,0\n130.1,1900,0\n131,1910,0\n";
    let run = replay("--filter ab --alpha 0.5 --beta 0.2", "f64", text);
    assert_eq!(run.events.restarted_starts, ["0.1", "60.1", "130.1"]);
    assert_eq!(run.events.restarted, ["60", "130"]);
}

/// The same jittered start seen by a range–azimuth sensor 22 km away: the
/// filter's velocity σ (the larger of along and across range) allows it in
/// every number system, the firmware's included.
#[test]
fn a_jittered_polar_start_within_its_own_uncertainty_is_not_refused() {
    let mut text = String::from("t,range,azimuth\n");
    for (t, x, y) in [
        (0.45, 0.0, 0.0),
        (0.55, 200.0, -10.0),
        (2.0, 210.0, -15.0),
        (3.0, 220.0, -20.0),
        (4.0, 230.0, -25.0),
    ] {
        let (x, y) = (20_000.0 + x, 10_000.0 + y);
        text.push_str(&format!("{t},{},{}\n", f64::hypot(x, y), f64::atan2(x, y)));
    }
    for numeric in ["f64", "f32", "q32.32", "fixed32"] {
        let run = replay("--filter range-azimuth", numeric, &text);
        let rows: Vec<&str> = run.csv.lines().collect();
        assert_eq!(rows.len(), 6, "{numeric}");
        assert!(vx(rows[2]).abs() > 1500.0, "{numeric}: {}", rows[2]);
        assert!(vx(rows[3]).abs() < 1500.0, "{numeric}: {}", rows[3]);
    }
}

fn replay_failure(filter: &str, numeric: &str, text: &str) -> String {
    match replay_events(&replay_config(filter, numeric), text.as_bytes()) {
        Err(abtrack_host_tests::replay::Failure::Replay(e)) => e.to_string(),
        other => panic!("{filter}: expected a refusal, got {other:?}"),
    }
}

fn replay(filter: &str, numeric: &str, text: &str) -> Replayed {
    replay_events(&replay_config(filter, numeric), text.as_bytes()).unwrap()
}

/// The configuration `replay FILTER --numeric NUMERIC -` parses to.
fn replay_config(filter: &str, numeric: &str) -> abtrack_host_tests::replay::ReplayConfig {
    use abtrack_host_tests::cli::{Command, ReplayArgs};
    use clap::Parser;
    let args: Vec<String> = ["replay"]
        .into_iter()
        .chain(filter.split_whitespace())
        .chain(["--numeric", numeric, "-"])
        .map(String::from)
        .collect();
    let Command::Replay { config, .. } = ReplayArgs::parse_from(args).into_command().unwrap()
    else {
        panic!("not a replay command");
    };
    config
}

fn events(csv: &str) -> Vec<(String, String)> {
    csv.lines()
        .skip(1)
        .filter_map(|l| {
            let (t, event) = (l.split(',').next()?, l.rsplit(',').next()?);
            (!event.is_empty()).then(|| (t.to_string(), event.to_string()))
        })
        .collect()
}

/// Reports exactly 0.05 s apart (a 20 Hz sensor) and exactly 20 s apart,
/// in decimal times whose `f64` differences fall either side of the range's
/// ends (0.15 − 0.1 = 0.04999999999999999, 40.7 − 20.7 =
/// 20.000000000000004): intervals are read to the microsecond, so none is
/// skipped or restarted; a time less than half a microsecond after the
/// last is a repeated time.
const RANGE_ENDS: &str = "t,x,y\n\
0,0,0\n0.05,1,0\n0.1,2,0\n0.15,3,0\n0.2,4,0\n0.25,5,0\n0.3,6,0\n\
20.3,406,0\n20.7,414,0\n40.7,814,0\n41.3,826,0\n41.3000004,826,0\n42.3,846,0\n";

#[test]
fn intervals_at_the_ends_of_the_range_are_inside_it_in_every_number_system() {
    for filter in CARTESIAN_FILTERS {
        for numeric in REPLAY_NUMERICS {
            let run = replay(filter, numeric, RANGE_ENDS);
            assert_eq!(run.csv.lines().count(), 14, "{filter} {numeric}");
            assert_eq!(
                events(&run.csv),
                [("41.3000004".to_string(), "skipped".to_string())],
                "{filter} {numeric}"
            );
            assert!(run.events.restarted.is_empty(), "{filter} {numeric}");
            assert_eq!(run.events.skipped, ["41.3000004"], "{filter} {numeric}");
            assert_eq!(run.events.duplicates, 1, "{filter} {numeric}");
        }
    }
    // The range–azimuth filter's runner takes the same intervals: the same
    // positions as range and azimuth from a sensor 20 km south and 10 km
    // west.
    let mut polar = String::from("t,range,azimuth\n");
    for row in RANGE_ENDS.lines().skip(1) {
        let v: Vec<f64> = row.split(',').map(|c| c.parse().unwrap()).collect();
        let (x, y) = (10_000.0 + v[1], 20_000.0 + v[2]);
        let t = row.split(',').next().unwrap();
        polar.push_str(&format!("{t},{},{}\n", f64::hypot(x, y), f64::atan2(x, y)));
    }
    for numeric in ["f64", "f32", "q32.32", "fixed32"] {
        let run = replay("--filter range-azimuth", numeric, &polar);
        assert_eq!(
            events(&run.csv),
            [("41.3000004".to_string(), "skipped".to_string())],
            "range-azimuth {numeric}"
        );
    }
    // A time less than half a microsecond before the last is a repeated
    // time too, not a late one.
    let run = replay(
        "--filter ab --alpha 0.5 --beta 0.2",
        "f64",
        "t,x\n0,0\n1,10\n0.9999996,10\n2,20\n",
    );
    assert_eq!((run.events.duplicates, run.events.late), (1, 0));
}

#[test]
fn replay_runs_through_gaps_and_jitter_in_every_number_system() {
    let want: Vec<(String, String)> = [
        ("2", "skipped"),
        ("2.02", "skipped"),
        ("30", "restarted"),
        ("93", "restarted"),
    ]
    .map(|(t, e)| (t.to_string(), e.to_string()))
    .to_vec();
    for filter in CARTESIAN_FILTERS {
        for numeric in REPLAY_NUMERICS {
            let run = replay(filter, numeric, GAPPY);
            assert_eq!(run.csv.lines().count(), 16, "{filter} {numeric}");
            assert_eq!(events(&run.csv), want, "{filter} {numeric}");
            assert_eq!(run.events.restarted, ["30", "93"], "{filter} {numeric}");
            assert_eq!(run.events.skipped, ["2", "2.02"]);
            assert_eq!(run.events.duplicates, 1);
            let text = run.events.to_string();
            assert!(text.contains("replay: 2 restarted"), "{text}");
            assert!(text.contains("replay: 2 skipped"), "{text}");
        }
    }
    // A skipped row repeats the estimate; the restarted one is its report.
    let run = replay("--filter ab --schedule least-squares", "f64", GAPPY);
    let rows: Vec<&str> = run.csv.lines().collect();
    let x = |row: &str| row.split(',').nth(1).unwrap().to_string();
    assert_eq!(x(rows[4]), x(rows[3]));
    assert_eq!(x(rows[8]), "300");
    // A report out of time order (merged feeds deliver them) is skipped like
    // a duplicate, in every filter, and counted apart; the file was refused
    // before.
    let back = "t,x\n0,0\n1,10\n2,20\n1.5,15\n3,30\n";
    for filter in [
        "--filter ab --schedule least-squares",
        "--filter auto --sigma-m 5",
        "--filter ab --schedule bank",
    ] {
        let run = replay(filter, "f64", back);
        assert_eq!(run.events.skipped, ["1.5"], "{filter}");
        assert_eq!((run.events.late, run.events.duplicates), (1, 0), "{filter}");
        assert!(
            run.csv.lines().nth(4).unwrap().ends_with(",skipped"),
            "{filter}"
        );
        assert!(
            run.events
                .to_string()
                .contains("1 before it (out of order)"),
            "{}",
            run.events
        );
    }
}

/// The skipped rows are counted by reason, one clause each, and a file
/// whose rows were mostly skipped is warned about: a first row at 500 s
/// and the rest from 0 s leaves 19 of 20 rows out of time order. With one
/// row of each reason among many, no warning.
#[test]
fn skipped_rows_are_counted_by_reason_and_a_mostly_skipped_file_is_warned_about() {
    let mut late = String::from("t,x\n500,0\n");
    for k in 0..19 {
        late.push_str(&format!("{},{k}\n", 10 * k));
    }
    let run = replay("--filter auto --sigma-m 50", "f64", &late);
    assert_eq!((run.events.rows, run.events.late), (20, 19));
    assert_eq!(
        run.events.to_string(),
        "replay: 19 skipped (t = 0, 10, 20, 30, 40, 50, 60, 70, …): 0 less than 0.05 s after \
         the last report used, 0 at its time (duplicates), 19 before it (out of order)\n\
         replay: warning: 19 of the 20 rows were skipped, most of the file (rows out of time \
         order are skipped: sort the file by t)\n"
    );
    let mixed = "t,x\n0,0\n1,10\n1,11\n1.01,12\n0.5,5\n2,20\n3,30\n4,40\n";
    let run = replay("--filter auto --sigma-m 50", "f64", mixed);
    assert_eq!(run.events.too_close(), 1);
    assert_eq!(
        run.events.to_string(),
        "replay: 3 skipped (t = 1, 1.01, 0.5): 1 less than 0.05 s after the last report used, \
         1 at its time (duplicates), 1 before it (out of order)\n"
    );
}

/// A range–azimuth report out of time order is skipped and counted too.
#[test]
fn range_azimuth_replay_skips_a_report_out_of_order() {
    let text = "t,range,azimuth\n0,5000,0.5\n1,4990,0.5\n2,4980,0.5\n1.5,4985,0.5\n3,4970,0.5\n";
    let run = replay("--filter range-azimuth", "f64", text);
    assert_eq!(run.events.skipped, ["1.5"]);
    assert_eq!(run.events.late, 1);
    assert!(run.csv.lines().nth(4).unwrap().ends_with(",skipped"));
}

#[test]
fn range_azimuth_replay_restarts_and_skips_too() {
    let text = "t,range,azimuth\n0,5000,0.5\n1,4990,0.5\n1,4991,0.5\n2,4980,0.5\n\
                40,4600,0.52\n41,4590,0.52\n42,4580,0.52\n";
    for numeric in ["f64", "f32", "q32.32"] {
        let run = replay("--filter range-azimuth", numeric, text);
        assert_eq!(run.events.restarted, ["40"], "{numeric}");
        assert_eq!(run.events.skipped, ["1"], "{numeric}");
        assert!(run.csv.lines().next().unwrap().ends_with(",event"));
    }
}

/// The range–azimuth replay's altitude: an altitude report the altitude
/// tracker finds not credible (a level intruder's 8,000 ft reported once as
/// 3,000) is listed on stderr with its time, not dropped unseen; a 45 s
/// hole in the replies starts a new altitude track, without a climb across
/// the hole.
#[test]
fn range_azimuth_replay_lists_incredible_altitudes_and_restarts_after_a_hole() {
    let mut text = String::from("t,range,azimuth,alt\n");
    for k in 0..10 {
        let alt = if k == 5 { 3000 } else { 8000 };
        text += &format!("{k},{},0.5,{alt}\n", 9000 - 100 * k);
    }
    for k in 55..60 {
        text += &format!("{k},{},0.5,12000\n", 9000 - 100 * k);
    }
    for numeric in ["f64", "f32", "q32.32"] {
        let run = replay("--filter range-azimuth", numeric, &text);
        assert_eq!(run.events.altitude_not_credible, ["5"], "{numeric}");
        assert!(
            run.events
                .to_string()
                .contains("1 altitude reports not credible"),
            "{}",
            run.events
        );
        let header: Vec<&str> = run.csv.lines().next().unwrap().split(',').collect();
        let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let (alt, rate) = (column("alt"), column("alt_rate"));
        let after_hole: Vec<&str> = run.csv.lines().nth(11).unwrap().split(',').collect();
        assert_eq!(after_hole[0], "55");
        assert_eq!(
            after_hole[alt].parse::<f64>().unwrap(),
            12000.0,
            "{numeric}"
        );
        assert_eq!(after_hole[rate].parse::<f64>().unwrap(), 0.0, "{numeric}");
    }
}

/// The tracker reads the same recording, without clutter: through the
/// 26 s hole the track coasts past 20 s and keeps its id (deletion after
/// 30 misses); the 60 s hole outlives it (deleted, never restarted) and
/// the target starts a new track; the repeated time is one scan, the 20 ms
/// scan is skipped. With replay's default clutter (0.1 per km²) a
/// coasting track's gate outgrows the design's rule 7 in each hole, before
/// its 30 misses: it is ended, counted, and the target starts a new track.
#[test]
fn tracker_replay_coasts_through_gaps_and_skips() {
    use abtrack_host_tests::cli::{Command, ReplayArgs};
    use clap::Parser;
    for (numeric, clutter) in ["f64", "f32", "q32.32"]
        .into_iter()
        .flat_map(|n| [(n, "0"), (n, "0.1")])
    {
        let args = [
            "replay",
            "--tracker",
            "--sigma-m",
            "5",
            "--scan-period-s",
            "1",
            "--delete",
            "30",
            "--clutter-per-km2",
            clutter,
            "--numeric",
            numeric,
            "-",
        ];
        let Command::Tracker { options, .. } = ReplayArgs::parse_from(args).into_command().unwrap()
        else {
            panic!()
        };
        let run: TrackerReplay = replay_tracker_reader(&options, GAPPY.as_bytes()).unwrap();
        assert_eq!(run.unused.too_close.count, 1, "{numeric}");
        assert_eq!(run.unused.too_close.lines, [6]);
        assert_eq!(run.unused.tracks_restarted, 0, "{numeric}");
        let report = run.report();
        assert!(report.contains("tracks restarted: 0"), "{report}");
        let id_at = |t: &str| -> Vec<String> {
            run.csv
                .lines()
                .filter(|l| l.split(',').next() == Some(t))
                .map(|l| l.split(',').nth(1).unwrap().to_string())
                .collect()
        };
        assert_eq!(id_at("4").len(), 1, "{numeric}");
        if clutter == "0" {
            // One track before the 26 s hole and after it, under one id.
            assert_eq!(id_at("30"), id_at("4"), "{numeric}");
            assert_eq!(run.unused.tracks_lost_in_clutter, 0, "{numeric}");
        } else {
            assert_ne!(id_at("30"), id_at("4"), "{numeric}");
            assert_eq!(run.unused.tracks_lost_in_clutter, 2, "{numeric}: {report}");
            assert!(
                report.contains("confirmed tracks lost in clutter: 2"),
                "{report}"
            );
        }
        // The target is tracked again after the 60 s hole, under a new id.
        assert_eq!(id_at("96").len(), 1, "{numeric}");
        assert_ne!(id_at("96"), id_at("4"), "{numeric}");
    }
}
