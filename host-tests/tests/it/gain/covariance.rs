//! `auto` (`abtrack::gain::auto`): a per-axis Kalman filter written as αβ
//! gains. Agreement with the independent reference (`RefKalmanAxis`,
//! written from the equations in metres) to rounding in f64 and within a
//! bound in f32 and the fast fixed point; stability for intervals 0.05–20 s
//! with coasts; the manoeuvre level follows a manoeuvre; the gate's variance
//! grows while coasting.

use abtrack::gain::auto::{AutoConfig, AutoGains, Q_MAX, Q_MIN, Q_START};
use abtrack::gain::{GainSchedule, ScheduledFilter};
use abtrack::num::fixed32::Fixed32;
use abtrack::{Numeric, Quantity};
use abtrack_host_tests::noise::{rng_from_seed, standard_normal, uniform};
use abtrack_host_tests::reference::RefKalmanAxis;

type Track<N> = ScheduledFilter<N, AutoGains<N, 2>, 2, 2>;

fn track<N: Numeric>(sigma: f64) -> Track<N> {
    ScheduledFilter::new(AutoGains::new(&AutoConfig::cartesian(sigma)).expect("auto builds"))
}

/// A target turning at `accel` m/s² between 40 % and 60 % of the run,
/// measured with σ noise at random intervals in [lo, hi] s; every 7th
/// report missed (a coast). Items: (dt, Some(z) or None for a coast).
fn events(
    seed: u64,
    n: usize,
    sigma: f64,
    lo: f64,
    hi: f64,
    accel: f64,
) -> Vec<(f64, Option<[f64; 2]>)> {
    let mut rng = rng_from_seed(seed);
    let (mut p, mut v): ([f64; 2], [f64; 2]) = ([1000.0, -2000.0], [120.0, 40.0]);
    (0..n)
        .map(|k| {
            let dt = uniform(&mut rng, lo, hi);
            let turning = k > 2 * n / 5 && k < 3 * n / 5;
            let a = if turning {
                let speed = v[0].hypot(v[1]);
                [-accel * v[1] / speed, accel * v[0] / speed]
            } else {
                [0.0, 0.0]
            };
            for i in 0..2 {
                p[i] += v[i] * dt + 0.5 * a[i] * dt * dt;
                v[i] += a[i] * dt;
            }
            let z = [0, 1].map(|i| p[i] + sigma * standard_normal(&mut rng));
            (dt, (k % 7 != 6 || k < 3).then_some(z))
        })
        .collect()
}

fn reference(sigma: f64) -> RefKalmanAxis {
    RefKalmanAxis::new(sigma, (Q_MIN as f64, Q_START as f64, Q_MAX as f64))
}

/// Runs the library in `N` and the reference side by side; returns the
/// largest position difference (m) and checks the gains agree as well.
fn compare<N: Numeric>(seed: u64, sigma: f64, lo: f64, hi: f64, gain_tol: f64) -> f64 {
    let mut lib = track::<N>(sigma);
    let mut refs = [reference(sigma), reference(sigma)];
    let mut worst: f64 = 0.0;
    for (dt, z) in events(seed, 400, sigma, lo, hi, 20.0) {
        let dtq = N::Interval::from_f64_lossy(dt);
        match z {
            None => {
                lib.coast(dtq).expect("coast");
                refs.iter_mut().for_each(|r| r.coast(dt));
            }
            Some(z) => {
                let out = lib
                    .update(z.map(N::Length::from_f64_lossy), dtq)
                    .expect("update accepted");
                for (i, r) in refs.iter_mut().enumerate() {
                    let expected = r.update(z[i], dt);
                    if let (Some((a, b)), Some(g)) = (expected, out.gains) {
                        let (ga, gb) = (g[i].alpha().to_f64(), g[i].beta().to_f64());
                        assert!((ga - a).abs() <= gain_tol, "α {ga} vs {a}");
                        assert!((gb - b).abs() <= gain_tol * (1.0 + b), "β {gb} vs {b}");
                    }
                }
                let pos = lib.filter().position();
                for (i, r) in refs.iter().enumerate() {
                    worst = worst.max((pos[i].to_f64() - r.x).abs());
                }
            }
        }
    }
    worst
}

#[test]
fn f64_agrees_with_the_reference_to_rounding() {
    for seed in 1..=5 {
        let d = compare::<f64>(seed, 50.0, 0.5, 6.0, 1e-9);
        assert!(d < 1e-6, "seed {seed}: {d} m");
    }
}

#[test]
fn f32_and_fixed_stay_within_a_bound_of_the_reference() {
    for seed in 1..=3 {
        let d32 = compare::<f32>(seed, 50.0, 0.5, 6.0, 1e-3);
        assert!(d32 < 0.5, "f32 seed {seed}: {d32} m");
        let dfx = compare::<Fixed32>(seed, 50.0, 0.5, 6.0, 1e-3);
        assert!(dfx < 0.5, "fixed seed {seed}: {dfx} m");
    }
}

/// Intervals anywhere in 0.05–20 s (the envelope), coasts included: every
/// update is accepted (the gains lie inside the stability triangle, which
/// `Gains` enforces) and the error stays within a few σ of the truth's
/// noise-free filter, in every number system.
fn stays_stable<N: Numeric>() {
    let sigma = 30.0;
    for seed in 1..=4 {
        let mut lib = track::<N>(sigma);
        let mut rng = rng_from_seed(100 + seed);
        let (mut p, v) = ([0.0f64, 0.0], [150.0f64, -60.0]);
        let mut worst: f64 = 0.0;
        for k in 0..1500 {
            let dt = if k % 3 == 0 {
                uniform(&mut rng, 0.05, 0.3)
            } else {
                uniform(&mut rng, 0.05, 20.0)
            };
            for i in 0..2 {
                p[i] += v[i] * dt;
            }
            let dtq = N::Interval::from_f64_lossy(dt);
            if k % 11 == 10 {
                lib.coast(dtq).expect("coast");
                continue;
            }
            let z = [0, 1].map(|i| p[i] + sigma * standard_normal(&mut rng));
            lib.update(z.map(N::Length::from_f64_lossy), dtq)
                .expect("update accepted");
            if k > 10 {
                let e = lib.filter().position();
                worst = worst.max((e[0].to_f64() - p[0]).hypot(e[1].to_f64() - p[1]));
            }
            if p[0].abs() > 2.0e5 {
                p = [0.0, 0.0];
                lib = track::<N>(sigma);
            }
        }
        assert!(worst < 8.0 * sigma, "{}: worst error {worst} m", N::NAME);
    }
}

#[test]
fn stable_for_every_interval_in_every_number_system() {
    stays_stable::<f64>();
    stays_stable::<f32>();
    stays_stable::<Fixed32>();
}

#[test]
fn the_manoeuvre_level_rises_in_a_turn_and_falls_after() {
    let sigma = 50.0;
    let mut lib = track::<f64>(sigma);
    let n = 500;
    let q_of = |t: &Track<f64>| {
        t.schedule()
            .axes()
            .iter()
            .map(|a| a.manoeuvre * 3.0 * sigma * sigma)
            .fold(0.0, f64::max)
    };
    let (mut before, mut during, mut after) = (0.0f64, 0.0f64, f64::MAX);
    for (k, (dt, z)) in events(9, n, sigma, 1.0, 1.0, 25.0).into_iter().enumerate() {
        match z {
            None => lib.coast(dt).unwrap(),
            Some(z) => {
                lib.update(z, dt).unwrap();
            }
        }
        let q = q_of(&lib);
        if k == 2 * n / 5 {
            before = q;
        }
        if k > 2 * n / 5 && k < 3 * n / 5 {
            during = during.max(q);
        }
        if k == n - 1 {
            after = q;
        }
    }
    assert!(before < 2.0 * Q_MIN as f64, "straight: q {before}");
    assert!(during > 20.0 * before, "turn: q {during} vs {before}");
    assert!(after < during / 10.0, "after: q {after} vs {during}");
}

#[test]
fn coasting_grows_the_gate_variance() {
    let mut lib = track::<f64>(50.0);
    for z in [0.0, 100.0, 200.0, 300.0] {
        lib.update([z, 0.0], 1.0).unwrap();
    }
    let before = lib.schedule().predicted_variance_ratios(1.0).unwrap();
    lib.coast(1.0).unwrap();
    lib.coast(1.0).unwrap();
    let after = lib.schedule().predicted_variance_ratios(1.0).unwrap();
    for i in 0..2 {
        assert!(after[i] > 2.0 * before[i], "{:?} vs {:?}", after, before);
    }
}

/// The fused filter (`AutoFilter`, one covariance for every axis) and the
/// schedule in a `ScheduledFilter` are one mechanism: on one axis, where
/// the shared covariance is that axis's, they give the same estimates to
/// rounding over irregular intervals, coasts and a manoeuvre.
#[test]
fn the_fused_filter_is_the_schedule_on_one_axis() {
    use abtrack::filter::auto::{AutoFilter, AutoUpdate};
    let sigma = 50.0;
    let gains = AutoGains::<f64, 1>::new(&AutoConfig::cartesian(sigma)).expect("auto builds");
    let mut scheduled: ScheduledFilter<f64, AutoGains<f64, 1>, 2, 1> = ScheduledFilter::new(gains);
    let mut fused = AutoFilter::<f64, 1>::new();
    let mut filtered = 0;
    for (dt, z) in events(11, 400, sigma, 0.5, 6.0, 20.0) {
        match z {
            Some([x, _]) => {
                scheduled.update([x], dt).expect("scheduled update");
                let outcome = fused
                    .update(gains.shared_noise(), [x], dt)
                    .expect("fused update");
                filtered += usize::from(outcome == AutoUpdate::Filtered);
            }
            None => {
                scheduled.coast(dt).expect("scheduled coast");
                fused.coast(dt).expect("fused coast");
            }
        }
        let (a, b) = (scheduled.filter().position()[0], fused.position()[0]);
        assert!(
            (a - b).abs() <= 1e-6 * (1.0 + a.abs()),
            "position {a} vs {b}"
        );
        let (a, b) = (scheduled.filter().velocity()[0], fused.velocity()[0]);
        assert!(
            (a - b).abs() <= 1e-6 * (1.0 + a.abs()),
            "velocity {a} vs {b}"
        );
    }
    assert!(filtered > 300, "{filtered} filtered updates");
}

/// `AutoFilter::update_step` with the interval's terms formed once
/// (`AutoInterval`, as a track table forms them per scan) is `update`
/// forming them in the call: the same outcome and the same filter, bit for
/// bit, over irregular intervals, coasts, intervals under the shortest and
/// over the longest, in every number system; the gate's variance likewise.
fn interval_formed_once_is_update<N: Numeric>() {
    use abtrack::filter::auto::{AutoFilter, AutoInterval};
    let sigma = 50.0;
    let gains = AutoGains::<N, 2>::new(&AutoConfig::cartesian(sigma)).expect("auto builds");
    let noise = gains.shared_noise();
    let (mut per_call, mut once) = (AutoFilter::<N, 2>::new(), AutoFilter::<N, 2>::new());
    let mut events = events(5, 300, sigma, 0.5, 6.0, 20.0);
    // An interval under the shortest (skipped) and one over the longest
    // (restarted), each with a measurement.
    events.insert(100, (0.01, Some([5000.0, 5000.0])));
    events.insert(200, (25.0, Some([9000.0, 9000.0])));
    let mut outcomes = std::collections::BTreeSet::new();
    for (dt, z) in events {
        let dt = N::Interval::from_f64_lossy(dt);
        let step = AutoInterval::<N>::new(dt).expect("a positive interval");
        assert_eq!(
            per_call.predicted_variance_ratio(dt),
            once.predicted_variance_ratio_step(&step)
        );
        assert_eq!(per_call.predict(dt), once.predict_step(&step));
        match z {
            Some(z) => {
                let z = z.map(N::Length::from_f64_lossy);
                let a = per_call.update(noise, z, dt);
                let b = once.update_step(noise, z, &step);
                assert_eq!(a, b);
                outcomes.insert(format!("{a:?}"));
            }
            None => {
                per_call.coast(dt).expect("coast");
                once.coast(dt).expect("coast");
            }
        }
        assert_eq!(per_call, once);
    }
    assert_eq!(outcomes.len(), 5, "every outcome taken: {outcomes:?}");
    for dt in [0.0, -1.0, f64::NAN] {
        assert_eq!(
            AutoInterval::<N>::new(N::Interval::from_f64_lossy(dt)),
            Err(abtrack::FilterError::InvalidInterval),
            "{dt}"
        );
    }
}

#[test]
fn an_interval_formed_once_gives_what_each_update_forms() {
    interval_formed_once_is_update::<f64>();
    interval_formed_once_is_update::<f32>();
    interval_formed_once_is_update::<Fixed32>();
    interval_formed_once_is_update::<abtrack::Fix>();
    interval_formed_once_is_update::<abtrack::ScaledScalar>();
}

/// The default track's update after its gate (`TrackFilter::update_after_gate`
/// with the prediction `gate_region_keeping` kept, as the track
/// table runs it) is its plain `update`: the same outcome and the same
/// filter, bit for bit, and the same region as `gate_region`, over
/// irregular intervals, coasts, intervals under the shortest and over the
/// longest, with the uncertainty gate and the wave gate, in every number
/// system.
fn update_after_gate_is_update<N: Numeric>(gate: abtrack::track::Gate<N>) {
    use abtrack::filter::auto::AutoFilter;
    use abtrack::track::{Measurement, Observation, ScanInterval, TrackFilter};
    let sigma = 50.0;
    let gains = AutoGains::<N, 2>::new(&AutoConfig::cartesian(sigma)).expect("auto builds");
    let empty = <AutoFilter<N, 2> as TrackFilter<N>>::empty(&gains);
    let (mut plain, mut after_gate) = (empty, empty);
    let mut events = events(6, 300, sigma, 0.5, 6.0, 20.0);
    events.insert(100, (0.01, Some([5000.0, 5000.0])));
    events.insert(200, (25.0, Some([9000.0, 9000.0])));
    let (mut kept, mut outcomes) = (0, std::collections::BTreeSet::new());
    for (dt, z) in events {
        // Whole milliseconds, as a scan's interval; at least 1.
        let ms = ((dt * 1000.0).round() as u32).max(1);
        let interval = ScanInterval::<N>::from_ms(ms).expect("an interval");
        let step = <AutoFilter<N, 2> as TrackFilter<N>>::step(&gains, &interval).expect("a step");
        let predicted = TrackFilter::predict(&plain, &gains, &step);
        assert_eq!(predicted, TrackFilter::predict(&after_gate, &gains, &step));
        let with_prediction = predicted.ok().and_then(|p| {
            let mut kept = <AutoFilter<N, 2> as TrackFilter<N>>::NOTHING_KEPT;
            let region = after_gate.gate_region_keeping(&gains, &p, &step, &gate, &mut kept);
            assert_eq!(region, plain.gate_region(&gains, &p, &step, &gate));
            region.map(|region| (region, kept))
        });
        match z {
            Some([x, y]) => {
                let measurement = Measurement::Cartesian {
                    x: N::Length::from_f64_lossy(x),
                    y: N::Length::from_f64_lossy(y),
                };
                let o = Observation::new(measurement).expect("a valid measurement");
                let a = TrackFilter::update(&mut plain, &gains, &o, &step);
                let b = match &with_prediction {
                    Some((_, prediction)) => {
                        kept += 1;
                        after_gate.update_after_gate(&gains, &o, &step, prediction)
                    }
                    None => TrackFilter::update(&mut after_gate, &gains, &o, &step),
                };
                assert_eq!(a, b);
                outcomes.insert(format!("{a:?}"));
            }
            None => {
                TrackFilter::coast(&mut plain, &gains, &step).expect("coast");
                TrackFilter::coast(&mut after_gate, &gains, &step).expect("coast");
            }
        }
        assert_eq!(plain, after_gate);
    }
    assert!(kept > 200, "{kept} updates after a gate");
    // Updated, and the too-short interval refused (the table skips such a
    // scan whole).
    for taken in ["Ok(())", "Err(InvalidInterval)"] {
        assert!(outcomes.contains(taken), "{outcomes:?}");
    }
}

#[test]
fn the_default_track_updated_after_its_gate_is_updated_as_without() {
    use abtrack::track::Gate;
    fn both<N: Numeric>() {
        let sigma = N::Length::from_f64_lossy(50.0);
        let threshold = N::Ratio::from_f64_lossy(13.8);
        update_after_gate_is_update::<N>(
            Gate::uncertainty(sigma, threshold, <N as Numeric>::Acceleration::ZERO)
                .expect("a gate"),
        );
        let bearing = N::Ratio::from_f64_lossy(0.01);
        update_after_gate_is_update::<N>(
            Gate::wave(sigma, bearing, N::Ratio::from_f64_lossy(3.0)).expect("a gate"),
        );
    }
    both::<f64>();
    both::<f32>();
    both::<Fixed32>();
    both::<abtrack::Fix>();
    both::<abtrack::ScaledScalar>();
}

/// A sensor figure the number system cannot hold is refused under its own
/// name: a polar sensor's tiny σ_R is named as range-sigma (its 1/σ_R and
/// bounds are formed first), not as the bearing ratio it also spoils.
#[test]
fn an_unrepresentable_sensor_figure_is_named() {
    use abtrack::gain::ConfigError;
    use abtrack::Fix;
    assert_eq!(
        AutoGains::<Fix, 2>::new(&AutoConfig::polar(1e-10, 90.0)),
        Err(ConfigError::NotRepresentable {
            parameter: "range-sigma"
        })
    );
    assert_eq!(
        AutoGains::<Fix, 2>::new(&AutoConfig::cartesian(1e-10)),
        Err(ConfigError::NotRepresentable { parameter: "sigma" })
    );
    assert!(AutoGains::<Fix, 2>::new(&AutoConfig::polar(15.0, 5.0)).is_ok());
}
