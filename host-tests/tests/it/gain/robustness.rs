//! Robust gains on real timing: each finding of "Defaults
//! tuned to the papers' noise levels misbehave on real data" as a test that
//! fails on the code before the fix, and the bounds of
//! `abtrack::gain::robust_gains` on any accepted input.

use super::support;

use abtrack::filter::{Cartesian, Gains, UpdateOutcome};
use abtrack::gain::spec::{ScheduleSpec, SensorScale};
use abtrack::gain::{
    next_reference, robust_gains, AnySchedule, FixedGains, GainSchedule, ScheduledFilter,
    MIN_INTERVAL_S,
};
use abtrack::gains::li_beta;
use abtrack::track::defaults::BANK_30_ACCELERATION;
use proptest::prelude::*;
use support::{Noise, ALL_SCHEDULES, W};

type Track<G> = ScheduledFilter<f64, G, 2, 2>;

fn any_track(spec: &str) -> Track<AnySchedule<f64, 2, W>> {
    let spec = ScheduleSpec::parse(spec).unwrap();
    ScheduledFilter::new(AnySchedule::from_spec(&spec).unwrap())
}

/// A constant-velocity target seen with white noise at the given report
/// times: the largest |position error| over the reports from `from` on,
/// or infinity once an update is refused or the error passes 10¹².
fn worst_error<G: GainSchedule<f64, 2>>(
    track: &mut Track<G>,
    times: &[f64],
    sigma: f64,
    seed: u64,
    from: usize,
) -> f64 {
    let mut noise = Noise::new(seed);
    let velocity = [120.0, -45.0];
    let mut worst = 0.0f64;
    let mut previous = None;
    for (k, &t) in times.iter().enumerate() {
        let truth = [velocity[0] * t, velocity[1] * t];
        let z = [
            truth[0] + sigma * noise.gaussian(),
            truth[1] + sigma * noise.gaussian(),
        ];
        let dt = previous.map_or(1.0, |p| t - p);
        previous = Some(t);
        if track.update(z, dt).is_err() {
            return f64::INFINITY;
        }
        let p = track.filter().position();
        let e = (p[0] - truth[0]).hypot(p[1] - truth[1]);
        // Not below 1e12, or not a number.
        if e.partial_cmp(&1e12) != Some(std::cmp::Ordering::Less) {
            return f64::INFINITY;
        }
        if k >= from {
            worst = worst.max(e);
        }
    }
    worst
}

/// Report times every second.
fn uniform(n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64).collect()
}

/// Report times of a real receiver: intervals of 0.5 to 5 s with jitter
/// (ADS-B positions arrive irregularly, often two in a second, sometimes
/// none for several).
fn irregular(n: usize, seed: u64) -> Vec<f64> {
    let mut noise = Noise::new(seed);
    let mut t = 0.0;
    (0..n)
        .map(|k| {
            if k > 0 {
                let base =
                    [0.5, 0.5, 1.0, 1.0, 1.0, 2.0, 5.0][(noise.uniform() * 7.0) as usize % 7];
                t += base * (0.8 + 0.4 * noise.uniform());
            }
            t
        })
        .collect()
}

// ------------------------------------------------------------------ m3

/// Finding: "`m3` with alpha0 ≥ 0.2 diverges to 1e23 m on uniform 1 s
/// data". α̂(n) falls to 0.004 while β̃ = α₀²/(2 − α₀) stays (0.022 for
/// α₀ = 0.2): poles within 0.2 % of the unit circle, pumped by the weight
/// search. β_LC is now held at Kalata's β for α̂(n).
#[test]
fn m3_with_a_large_alpha0_stays_near_the_truth_on_uniform_data() {
    for alpha0 in ["0.2", "0.5", "1"] {
        for seed in 1..=3 {
            let mut t = any_track(&format!("m3:alpha0={alpha0}"));
            let worst = worst_error(&mut t, &uniform(2000), 20.0, seed, 20);
            assert!(worst < 100.0, "m3 α₀ = {alpha0}, seed {seed}: {worst} m");
        }
    }
}

/// Every M3 pair lies at or below Kalata's β for its α.
#[test]
fn m3_gains_are_damped() {
    let mut t = any_track("m3:alpha0=1");
    let mut noise = Noise::new(9);
    for k in 0..1500 {
        let z = [
            3.0 * k as f64 + 20.0 * noise.gaussian(),
            20.0 * noise.gaussian(),
        ];
        if let Some(g) = t.update(z, 1.0).unwrap().gains {
            for g in g {
                assert!(
                    g.beta() <= li_beta(g.alpha()) * (1.0 + 1e-12),
                    "k {k}: {g:?}"
                );
            }
        }
    }
}

// --------------------------------------------------- irregular timing

/// Finding: "fixed gains that pass the stability check (α 0.002, β 0.1667)
/// diverge to 834 km on real, irregular report times". The same gains on
/// the same reports: without bounds (`Cartesian::update`) the error grows
/// past 10⁶ m; through `ScheduledFilter` it settles and does not grow.
#[test]
fn underdamped_fixed_gains_stay_bounded_on_irregular_report_times() {
    let gains = Gains::<f64>::alpha_beta(0.002, 0.1667).unwrap();
    let times = irregular(6000, 4);
    // Unbounded, for the record of what the finding was.
    let mut raw: Cartesian<f64, 2, 2> = Cartesian::new();
    let mut noise = Noise::new(11);
    let mut raw_worst = 0.0f64;
    let mut previous = None;
    for &t in &times {
        let truth = [120.0 * t, -45.0 * t];
        let z = [
            truth[0] + 20.0 * noise.gaussian(),
            truth[1] + 20.0 * noise.gaussian(),
        ];
        let dt = previous.map_or(1.0, |p: f64| t - p);
        previous = Some(t);
        if raw.update(z, dt, &gains).is_err() {
            raw_worst = f64::INFINITY;
            break;
        }
        let p = raw.position();
        raw_worst = raw_worst.max((p[0] - truth[0]).hypot(p[1] - truth[1]));
    }
    assert!(
        raw_worst > 1e6,
        "the unbounded filter did not diverge: {raw_worst}"
    );

    let mut bounded: Track<FixedGains<f64>> = ScheduledFilter::new(FixedGains::new(gains));
    let first_half = worst_error(&mut bounded, &times[..3000], 20.0, 11, 0);
    let mut bounded: Track<FixedGains<f64>> = ScheduledFilter::new(FixedGains::new(gains));
    let second_half = worst_error(&mut bounded, &times, 20.0, 11, 3000);
    assert!(first_half.is_finite() && first_half < 1e5, "{first_half}");
    assert!(
        second_half <= first_half,
        "the error grows: {first_half} m, then {second_half} m"
    );
}

/// Every schedule, on intervals drawn anywhere in the envelope (0.05 to
/// 20 s, log-uniform, each different from the last): after the start-up
/// transient the error stays bounded. The bound, 1000σ (10 km), separates
/// a bounded filter from a diverging one (those grow past 10¹² m within
/// the run): a velocity error of a few tens of m/s over a 20 s interval is
/// already several hundred metres, and slow gains take many updates to
/// remove it.
#[test]
fn every_schedule_stays_bounded_on_intervals_across_the_envelope() {
    let mut noise = Noise::new(21);
    let mut t = 0.0;
    let times: Vec<f64> = (0..1500)
        .map(|k| {
            if k == 1 {
                t += 1.0;
            } else if k > 1 {
                t += (0.05f64.ln() + (20.0f64 / 0.05).ln() * noise.uniform()).exp();
            }
            t
        })
        .collect();
    for spec in ALL_SCHEDULES {
        for seed in 1..=3 {
            let mut track = any_track(spec);
            let worst = worst_error(&mut track, &times, 10.0, seed, 500);
            assert!(worst < 1e4, "{spec}, seed {seed}: {worst} m");
        }
    }
}

/// 1200 report times: 0, 1 s, then `pattern`'s intervals repeated.
fn repeating(pattern: &[f64]) -> Vec<f64> {
    let mut t = 0.0;
    (0..1200)
        .map(|k| {
            if k == 1 {
                t += 1.0;
            } else if k > 1 {
                t += pattern[k % pattern.len()];
            }
            t
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Any repeating pattern of accepted intervals (from 0.06 s: summed in
    /// f64, 0.05 s steps can come out a hair below the minimum and be
    /// refused): every schedule but M4 stays within the bound above. M4
    /// switches its gains in a way no interval bound can hold (the two
    /// tests below).
    #[test]
    fn any_interval_sequence_keeps_every_schedule_but_m4_bounded(
        seed in 0u64..10_000,
        pattern in proptest::collection::vec(0.06f64..20.0, 2..8),
    ) {
        let times = repeating(&pattern);
        for spec in ALL_SCHEDULES.iter().filter(|spec| **spec != "m4") {
            let mut track = any_track(spec);
            let worst = worst_error(&mut track, &times, 10.0, seed, 600);
            prop_assert!(worst < 1e4, "{} with intervals {:?}: {} m", spec, pattern, worst);
        }
    }
}

/// Why M4 is outside the search above: Al-Wagih's Algorithm 2 picks α
/// anew after every update, and an αβ filter whose gains switch is not
/// stable under every switching, even at equal intervals and with each
/// pair stable on its own (shown here on M4's pairs in a chosen order; the
/// next test is M4 itself on report times where its search switches so). M4's own pairs (β = α²/(2 − α), eq. 23b) in the
/// periodic order α = 1, 0.1, 0.1 at 1 s: the error matrix of the cycle
/// has spectral radius 1.705, while each pair's own is below 1; on
/// noiseless reports of a constant-velocity target with one 100 m outlier
/// the switched filter's error passes 1000 km, either pair held removes it.
#[test]
fn m4_gain_pairs_switched_periodically_diverge_at_equal_intervals() {
    let beta = |alpha: f64| alpha * alpha / (2.0 - alpha);
    // The spectral radius of the product of the error matrices
    // [[1 − α, (1 − α)T], [−β/T, 1 − β]] (T = 1 s) of a cycle.
    let radius = |cycle: &[f64]| {
        let mut m = [[1.0, 0.0], [0.0, 1.0]];
        for &alpha in cycle {
            let b = beta(alpha);
            let step = [[1.0 - alpha, 1.0 - alpha], [-b, 1.0 - b]];
            m = [
                [
                    step[0][0] * m[0][0] + step[0][1] * m[1][0],
                    step[0][0] * m[0][1] + step[0][1] * m[1][1],
                ],
                [
                    step[1][0] * m[0][0] + step[1][1] * m[1][0],
                    step[1][0] * m[0][1] + step[1][1] * m[1][1],
                ],
            ];
        }
        let (trace, det) = (m[0][0] + m[1][1], m[0][0] * m[1][1] - m[0][1] * m[1][0]);
        let discriminant = trace * trace / 4.0 - det;
        if discriminant >= 0.0 {
            (trace / 2.0).abs() + discriminant.sqrt()
        } else {
            det.sqrt()
        }
    };
    let switched = [1.0, 0.1, 0.1];
    assert!(
        (radius(&switched) - 1.705).abs() < 5e-4,
        "{}",
        radius(&switched)
    );
    assert!(radius(&[1.0]) < 1.0 && radius(&[0.1]) < 1.0);

    let final_error = |cycle: &[f64]| {
        let mut filter: Cartesian<f64, 2, 1> = Cartesian::new();
        let mut error = 0.0;
        for k in 0..92usize {
            let truth = 80.0 * k as f64;
            let z = if k == 5 { truth + 100.0 } else { truth };
            let alpha = cycle[k % cycle.len()];
            let gains = Gains::<f64>::alpha_beta(alpha, beta(alpha)).unwrap();
            filter.update([z], 1.0, &gains).unwrap();
            error = (filter.position()[0] - truth).abs();
        }
        error
    };
    let diverged = final_error(&switched);
    assert!(diverged > 1e6, "switched pairs: {diverged} m");
    for alpha in [1.0, 0.1] {
        let held = final_error(&[alpha]);
        assert!(held < 1.0, "α = {alpha} held: {held} m");
    }
}

/// A case the search above found (seed 1637) before M4 was taken out of
/// it: on the repeating intervals 15.87 s, 0.125 s, 2.66 s, M4's error
/// passes the 10 km bound while every other schedule stays within it. Kept as the
/// record of a limitation of the published method (docs/auto.md): the
/// assertion fails, and the docs must change, if M4 is ever bounded here.
#[test]
fn m4_leaves_the_bound_on_a_long_short_medium_pattern_and_the_others_do_not() {
    let pattern = [15.870185795895068, 0.12461074173788983, 2.66273256798735];
    let times = repeating(&pattern);
    for spec in ALL_SCHEDULES {
        let worst = worst_error(&mut any_track(spec), &times, 10.0, 1637, 600);
        if *spec == "m4" {
            assert!(worst > 1e4, "m4: {worst} m");
        } else {
            assert!(worst < 1e4, "{spec}: {worst} m");
        }
    }
}

/// Equal intervals (every experiment of the papers) leave the gains as the
/// schedule gave them; a changed interval bounds them as documented.
#[test]
fn robust_gains_leave_equal_intervals_alone_and_bound_the_others() {
    let g = [
        Gains::<f64>::alpha_beta(0.002, 0.1667).unwrap(),
        Gains::<f64>::alpha_beta_gamma(0.6, 0.5, 0.05).unwrap(),
    ];
    assert_eq!(robust_gains(g, 2.0, 2.0, 2.0).unwrap(), g);
    assert_eq!(robust_gains(g, 2.0, 0.0, 0.0).unwrap(), g);
    // A changed interval holds β at Kalata's β for α (γ in proportion).
    let kalata = li_beta(0.6);
    let longer = robust_gains(g, 4.0, 2.0, 2.0).unwrap();
    assert!((longer[1].beta() - kalata).abs() < 1e-15);
    assert!((longer[1].gamma() - 0.05 * kalata / 0.5).abs() < 1e-15);
    assert!((longer[0].beta() - li_beta(0.002)).abs() < 1e-15);
    // Equal to the previous interval but shorter than half the reference:
    // the same bounds, and β, γ scaled by 2T/reference (γ twice).
    let shorter = robust_gains(g, 0.5, 0.5, 2.0).unwrap();
    assert!((shorter[1].beta() - kalata / 2.0).abs() < 1e-15);
    assert!((shorter[1].gamma() - 0.05 * (kalata / 2.0 / 0.5) / 2.0).abs() < 1e-15);
    assert!((shorter[0].beta() - li_beta(0.002) / 2.0).abs() < 1e-15);
    // Half the reference (the scan after a missed one): bounds only.
    let after_miss = robust_gains(g, 1.0, 2.0, 2.0).unwrap();
    assert!((after_miss[1].beta() - kalata).abs() < 1e-15);
    // Gains already below the bounds pass a longer interval unchanged; α
    // above 1 is held at 1.
    let damped = [Gains::<f64>::alpha_beta(0.5, 0.1).unwrap(); 2];
    assert_eq!(robust_gains(damped, 4.0, 2.0, 2.0).unwrap(), damped);
    let over = [Gains::<f64>::alpha_beta(1.5, 0.9).unwrap(); 1];
    let held = robust_gains(over, 4.0, 2.0, 2.0).unwrap();
    assert_eq!((held[0].alpha(), held[0].beta()), (1.0, 0.9));
    // The reference: the longest recent interval, relaxing by a quarter.
    assert_eq!(next_reference(2.0, 4.0), 4.0);
    assert_eq!(next_reference(2.0, 1.0), 1.75);
}

// ------------------------------------------------ near-coincident reports

/// Finding: "two reports 1 ms apart make `m2` print values around 1e190".
/// The library skips a measurement less than 0.05 s after the previous
/// one, in initialisation and in tracking, and changes nothing.
#[test]
fn near_coincident_reports_are_skipped_and_change_nothing() {
    assert_eq!(MIN_INTERVAL_S, 0.05);
    let mut t = any_track("least-squares");
    t.update([0.0, 0.0], 1.0).unwrap();
    let before = t;
    let skipped = t.update([1.0, 1.0], 0.001).unwrap();
    assert_eq!(skipped.outcome, [UpdateOutcome::Skipped; 2]);
    assert_eq!(t, before);
    t.update([10.0, 5.0], 1.0).unwrap();
    t.update([20.0, 10.0], 1.0).unwrap();
    let before = t;
    let skipped = t.update([20.01, 10.0], 0.049).unwrap();
    assert_eq!(skipped.outcome, [UpdateOutcome::Skipped; 2]);
    assert_eq!(t, before);
    assert!(matches!(
        t.update([20.5, 10.25], 0.05).unwrap().outcome,
        [UpdateOutcome::Filtered(_), UpdateOutcome::Filtered(_)]
    ));
}

/// Reports 60 ms apart (just above the shortest accepted) in pairs, one pair a
/// second: `m2` stays within 10σ of the truth (the velocity correction of
/// the short interval is bounded by the previous interval's).
#[test]
fn close_pairs_of_reports_keep_m2_near_the_truth() {
    // Two reports a second apart start the track (the two-point velocity
    // of a 60 ms baseline is another matter: σ√2/0.06 s), then the pairs.
    let times: Vec<f64> = (0..2000)
        .map(|k| match k {
            0 | 1 => k as f64,
            _ => (k / 2 + 1) as f64 + if k % 2 == 1 { 0.06 } else { 0.0 },
        })
        .collect();
    for seed in 1..=3 {
        let mut t = any_track("least-squares");
        let worst = worst_error(&mut t, &times, 20.0, seed, 10);
        assert!(worst < 200.0, "seed {seed}: {worst} m");
    }
}

// --------------------------------------------------- defaults and σ

fn scale(sigma: f64) -> SensorScale {
    SensorScale {
        sigma,
        period: 1.0,
        max_acceleration: BANK_30_ACCELERATION,
    }
}

/// The defaults tied to the papers' noise follow the sensor; keys given
/// keep their values.
#[test]
fn defaults_scale_with_the_sensor() {
    let s = scale(50.0);
    let alpha = s.steady_state_alpha().unwrap();
    let n_max = s.least_squares_n_max().unwrap();
    assert!(abtrack::gains::least_squares_alpha::<f64>(n_max) <= alpha);
    assert!(abtrack::gains::least_squares_alpha::<f64>(n_max - 1) > alpha);
    let parsed = |text: &str| ScheduleSpec::parse_scaled(text, &s).unwrap().to_string();
    assert_eq!(parsed("m2"), format!("least-squares:n-max={n_max}"));
    assert_eq!(parsed("m1"), format!("m1:alpha={alpha}"));
    assert_eq!(parsed("m1:alpha=0.3"), "m1:alpha=0.3");
    assert!(parsed("li-improved").contains("range-error=50,"));
    assert!(parsed("li-improved").ends_with(&format!(",k-max={n_max}")));
    assert_eq!(
        parsed("liu-count-adjusted"),
        format!("liu-count-adjusted:threshold=700,k-max={n_max}")
    );
    assert_eq!(
        parsed("liu-count-adjusted:k-max=1000"),
        "liu-count-adjusted:threshold=700,k-max=1000"
    );
    assert_eq!(
        parsed("liu-residual"),
        "liu-residual:n=3,sigma-m2=2500,alpha-min=0.01"
    );
    assert!(parsed("liu-adaptive").starts_with("liu-adaptive:limit=190,"));
    assert_eq!(parsed("auto"), "auto:sigma=50");
    // Without a sensor the papers' defaults stay (the experiments use them).
    assert_eq!(
        ScheduleSpec::parse("m2").unwrap().to_string(),
        "least-squares:n-max=1000"
    );
}

/// A turning aircraft seen by a 50 m sensor every second: 200 m/s, a
/// 3°/s turn (10.5 m/s²) for 60 s between straight legs.
fn turning_flight(seed: u64) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let mut noise = Noise::new(seed);
    let (mut p, mut heading) = ([0.0f64, 0.0], 0.0f64);
    let (speed, rate) = (200.0, 3f64.to_radians());
    let mut truth = Vec::new();
    let mut meas = Vec::new();
    for k in 0..240 {
        if (80..140).contains(&k) {
            heading += rate;
        }
        p = [p[0] + speed * heading.cos(), p[1] + speed * heading.sin()];
        truth.push(p);
        meas.push([
            p[0] + 50.0 * noise.gaussian(),
            p[1] + 50.0 * noise.gaussian(),
        ]);
    }
    (truth, meas)
}

fn worst_on_turn(spec: &ScheduleSpec, seed: u64) -> f64 {
    let (truth, meas) = turning_flight(seed);
    let mut t: Track<AnySchedule<f64, 2, W>> =
        ScheduledFilter::new(AnySchedule::from_spec(spec).unwrap());
    let mut worst = 0.0f64;
    for (z, p) in meas.iter().zip(&truth) {
        t.update(*z, 1.0).unwrap();
        let e = t.filter().position();
        worst = worst.max((e[0] - p[0]).hypot(e[1] - p[1]));
    }
    worst
}

/// Finding: "`m2`/`least-squares` with n-max 1000 and `m1`/`m3` with
/// α 0.05 lag by kilometres in a turn". With the defaults scaled to the
/// sensor (σ = 50 m, T = 1 s, a_max = g·tan 30°) they stay within 8σ; with
/// the papers' defaults they lag by more than a kilometre.
#[test]
fn scaled_defaults_follow_a_turn() {
    for name in ["m2", "m1", "m3"] {
        let paper = ScheduleSpec::parse(name).unwrap();
        let scaled = ScheduleSpec::parse_scaled(name, &scale(50.0)).unwrap();
        lags_then_follows_the_turn(&paper, &scaled);
    }
}

/// `lagging` lags by more than a kilometre on the turning flight (seeds
/// 1–3) and `following` by less than 400 m.
fn lags_then_follows_the_turn(lagging: &ScheduleSpec, following: &ScheduleSpec) {
    for seed in 1..=3 {
        let lag = worst_on_turn(lagging, seed);
        assert!(lag > 1000.0, "{lagging} lags only {lag} m");
        let lag = worst_on_turn(following, seed);
        assert!(lag < 400.0, "{following} lags {lag} m");
    }
}

/// Finding: "`liu-count-adjusted` scaled to a 50 m sensor is 15–17× the
/// Kalman filter on real flights": its threshold (14σ = 700 m) scaled but
/// its count bound left at 1000, the count grows while the innovations stay
/// under the threshold, and its gains (eq. 5) fall far below the sensor's
/// steady-state α, so it lags by kilometres in a turn. Scaled as the
/// least-squares count bound (k-max = n-max, the first n with α̂(n) ≤ α_K)
/// it follows the turn as `m2` does.
#[test]
fn a_scaled_count_bound_keeps_liu_count_adjusted_in_a_turn() {
    let k_max_1000 =
        ScheduleSpec::parse_scaled("liu-count-adjusted:k-max=1000", &scale(50.0)).unwrap();
    let scaled = ScheduleSpec::parse_scaled("liu-count-adjusted", &scale(50.0)).unwrap();
    lags_then_follows_the_turn(&k_max_1000, &scaled);
}

/// RMSE of the filtered position over a run.
fn rmse(spec: &ScheduleSpec, truth: &[[f64; 2]], meas: &[[f64; 2]]) -> f64 {
    let mut t: Track<AnySchedule<f64, 2, W>> =
        ScheduledFilter::new(AnySchedule::from_spec(spec).unwrap());
    let mut sum = 0.0;
    for (z, p) in meas.iter().zip(truth) {
        t.update(*z, 1.0).unwrap();
        let e = t.filter().position();
        sum += (e[0] - p[0]).powi(2) + (e[1] - p[1]).powi(2);
    }
    (sum / truth.len() as f64).sqrt()
}

/// Li's Δρ = 1 m and Liu's σ_m² = 25 m² on a 50 m sensor take every
/// innovation for a manoeuvre (Li cuts its count to 3, Liu's α goes to
/// ~1), so they hardly smooth; scaled to σ they remove at least a tenth of
/// the error on the turning flight. Not much more: with σ_m² = σ², Liu's
/// α = s/(s + 1) from three squared innovations is about 0.6, and Li's ratio
/// test compares the innovation with √α·Δρ, below the innovation's σ even
/// with Δρ = σ, so it still cuts its count every few scans (measured, sums
/// over the five runs: li-improved 254 m against 301 m, liu-residual 276 m
/// against 343 m).
#[test]
fn scaled_noise_levels_smooth_a_noisier_sensor() {
    for (name, at_most) in [
        ("li-improved", 0.9),
        ("liu-residual", 0.9),
        ("liu-adaptive", 0.9),
    ] {
        let (mut paper, mut scaled) = (0.0, 0.0);
        for seed in 1..=5 {
            let (truth, meas) = turning_flight(seed);
            paper += rmse(&ScheduleSpec::parse(name).unwrap(), &truth, &meas);
            scaled += rmse(
                &ScheduleSpec::parse_scaled(name, &scale(50.0)).unwrap(),
                &truth,
                &meas,
            );
        }
        println!("{name}: {scaled} (scaled) vs {paper} (paper)");
        assert!(
            scaled < at_most * paper,
            "{name}: RMSE {scaled} (scaled) vs {paper} (paper defaults), sums over 5 runs"
        );
    }
}

/// A schedule's gains through the context path alone: `G` with every
/// method forwarded but `count_gains` (the trait's default, `None`).
#[derive(Clone, Copy)]
struct ThroughContext<G>(G);

impl<N: abtrack::Numeric, const D: usize, G: GainSchedule<N, D>> GainSchedule<N, D>
    for ThroughContext<G>
{
    fn gains(
        &self,
        ctx: &abtrack::gain::GainContext<N, D>,
    ) -> Result<[Gains<N>; D], abtrack::gain::ScheduleError> {
        self.0.gains(ctx)
    }
    fn accepted(&mut self, ctx: &abtrack::gain::GainContext<N, D>, used: &[Gains<N>; D]) {
        self.0.accepted(ctx, used)
    }
    fn initialised(&mut self, n: u32, dt: N::Interval) {
        self.0.initialised(n, dt)
    }
    fn missed(&mut self, dt: N::Interval) {
        self.0.missed(dt)
    }
    fn gains_follow_interval(&self) -> bool {
        self.0.gains_follow_interval()
    }
    fn predicted_variance_ratios(&self, dt: N::Interval) -> Option<[N::Ratio; D]> {
        self.0.predicted_variance_ratios(dt)
    }
    fn restart_required(&self, phase: abtrack::filter::Phase) -> bool {
        self.0.restart_required(phase)
    }
    fn reset(&mut self) {
        self.0.reset()
    }
}

/// A report of the count-path comparison: an interval and a position, or
/// (`None`) a pair of positions at ± the largest length of the number type,
/// whose innovation overflows it.
type Report = (f64, Option<[f64; 2]>);

/// What [`count_path_matches_context_path`] saw: filtered updates, and
/// updates refused as saturated.
#[derive(Default)]
struct PathCounts {
    filtered: usize,
    saturated: usize,
}

/// Feeds the same reports to `G` (`count_gains`) and to `G` through the
/// context path: every result (outcomes, gains, errors) and every state
/// after it are the same, bit for bit (compared in their `Debug` form,
/// which tells −0 from +0).
fn count_path_matches_context_path<N, G, const ORDER: usize>(
    schedule: G,
    reports: &[Report],
    largest: f64,
) -> PathCounts
where
    N: abtrack::Numeric,
    G: GainSchedule<N, 2> + core::fmt::Debug,
{
    use abtrack::gain::ScheduledError;
    use abtrack::num::Quantity;
    assert!(schedule.count_gains(3).is_some(), "not a count schedule");
    let mut counted = ScheduledFilter::<N, G, ORDER, 2>::new(schedule);
    let mut through =
        ScheduledFilter::<N, ThroughContext<G>, ORDER, 2>::new(ThroughContext(schedule));
    let mut counts = PathCounts::default();
    for (k, &(dt, z)) in reports.iter().enumerate() {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        let z = z.unwrap_or([sign * largest, -sign * largest]);
        let z = z.map(N::Length::from_f64_lossy);
        let dt = N::Interval::from_f64_lossy(dt);
        let (a, b) = (counted.update(z, dt), through.update(z, dt));
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "report {k}");
        assert_eq!(
            format!("{:?}", counted.filter()),
            format!("{:?}", through.filter()),
            "report {k}"
        );
        assert_eq!(counted.measurements(), through.measurements(), "report {k}");
        assert_eq!(
            format!("{:?}", counted.schedule()),
            format!("{:?}", through.schedule().0),
            "report {k}"
        );
        match a {
            Ok(u) if u.gains.is_some() => counts.filtered += 1,
            Err(ScheduledError::Filter(abtrack::filter::FilterError::Saturated)) => {
                counts.saturated += 1
            }
            _ => {}
        }
    }
    counts
}

/// The largest length each number type takes, about: ± it in the two axes
/// overflows an innovation. Not f64's: its guard sums the outputs, exact
/// only below `f64::MAX`/8 (`Scalar::accumulate_check`), so the two paths,
/// which check different sets of outputs, may refuse differently above
/// that; f64 takes a length far below it, and never saturates here.
const LARGEST_F64: f64 = 1.0e300;
const LARGEST_F32: f64 = 3.0e38;
const LARGEST_FIXED32: f64 = 5.0e5;

/// Every count schedule, in every number type, on `reports`: M2 (also
/// as `AnySchedule` from its spec), M1 αβ and M1 αβγ (an order-3 filter);
/// the f64 runs are the first and the fifth.
fn every_count_schedule(reports: &[Report]) -> [PathCounts; 8] {
    use abtrack::Fixed32;
    let ls = abtrack::gain::LeastSquaresGains::default();
    let spec = ScheduleSpec::parse("least-squares").unwrap();
    let any = AnySchedule::<f32, 2, W>::from_spec(&spec).unwrap();
    fn m1<N: abtrack::Numeric>() -> FixedGains<N> {
        FixedGains::new(Gains::alpha_beta_f64(0.6, 0.3).unwrap())
    }
    fn m1_gamma<N: abtrack::Numeric>() -> FixedGains<N> {
        FixedGains::new(Gains::alpha_beta_gamma_f64(0.7, 0.4, 0.05).unwrap())
    }
    [
        count_path_matches_context_path::<f64, _, 2>(ls, reports, LARGEST_F64),
        count_path_matches_context_path::<f32, _, 2>(ls, reports, LARGEST_F32),
        count_path_matches_context_path::<Fixed32, _, 2>(ls, reports, LARGEST_FIXED32),
        count_path_matches_context_path::<f32, _, 2>(any, reports, LARGEST_F32),
        count_path_matches_context_path::<f64, _, 2>(m1::<f64>(), reports, LARGEST_F64),
        count_path_matches_context_path::<Fixed32, _, 2>(m1::<Fixed32>(), reports, LARGEST_FIXED32),
        count_path_matches_context_path::<f32, _, 3>(m1_gamma::<f32>(), reports, LARGEST_F32),
        count_path_matches_context_path::<Fixed32, _, 3>(
            m1_gamma::<Fixed32>(),
            reports,
            LARGEST_FIXED32,
        ),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// M1's and M2's gains skip the context (`GainSchedule::count_gains`)
    /// and give what the context path gives, on irregular intervals, skips,
    /// gaps, invalid and overflowing measurements, in every number type.
    #[test]
    fn count_gains_give_what_the_context_path_gives(
        reports in proptest::collection::vec(
            (
                prop_oneof![
                    8 => 0.06f64..8.0,
                    1 => Just(1.0),
                    1 => 0.0f64..0.05,
                    1 => 20.5f64..40.0,
                    1 => Just(f64::NAN),
                ],
                prop_oneof![
                    12 => (-2.0e4f64..2.0e4, -2.0e4f64..2.0e4).prop_map(|(x, y)| Some([x, y])),
                    1 => Just(Some([f64::NAN, 0.0])),
                    1 => Just(None),
                ],
            ),
            1..40,
        ),
    ) {
        every_count_schedule(&reports);
    }
}

/// The comparison above is not vacuous: on a fixed sequence (regular and
/// irregular intervals, then reports at ± the largest length, the second
/// of which overflows its innovation at the latest) every schedule and
/// number type filters updates, and every one but f64 (whose reports stay
/// far inside its range) refuses one as saturated on both paths.
#[test]
fn count_gains_comparison_filters_and_refuses() {
    let mut reports: Vec<Report> = (0..12)
        .map(|k| {
            let t = f64::from(k);
            (
                if k % 3 == 0 { 2.5 } else { 1.0 },
                Some([100.0 * t, -40.0 * t]),
            )
        })
        .collect();
    reports.extend([(1.0, None), (1.0, None), (1.0, Some([1300.0, -520.0]))]);
    for (i, counts) in every_count_schedule(&reports).iter().enumerate() {
        assert!(
            counts.filtered >= 8,
            "schedule {i}: {} filtered",
            counts.filtered
        );
        let f64_run = i == 0 || i == 4;
        assert!(
            f64_run || counts.saturated >= 1,
            "schedule {i}: no saturated update"
        );
    }
}
