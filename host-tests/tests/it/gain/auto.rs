//! The `auto` schedule (`abtrack::gain::auto`): its spec, an independent f64
//! transcription of its rules, the figures its docs state (false-alarm rates),
//! its response to a manoeuvre, its gains' region, and its runs in the
//! firmware's number types.

use super::support;

use abtrack::gain::auto::{AutoAxis, AutoConfig, AutoGains, DETECTION_LEVEL};
use abtrack::gain::spec::{ScheduleSpec, SpecErrorKind};
use abtrack::gain::{AnySchedule, ConfigError, GainSchedule, LeastSquaresGains, ScheduledFilter};
use abtrack::gains::li_beta;
use abtrack::num::{Numeric, Quantity};
use abtrack::{Fix, Fixed32};
use proptest::prelude::*;
use support::Noise;

type AutoTrack<N> = ScheduledFilter<N, AutoGains<N, 2>, 2, 2>;

fn track<N: Numeric>(config: &AutoConfig) -> AutoTrack<N> {
    ScheduledFilter::new(AutoGains::new(config).expect("auto builds"))
}

fn length<N: Numeric>(v: f64) -> N::Length {
    N::Length::try_from_f64(v).expect("length in range")
}

fn interval<N: Numeric>(v: f64) -> N::Interval {
    N::Interval::try_from_f64(v).expect("interval in range")
}

/// One accepted update: the gains (α, β per axis) and the state after it.
struct Stepped {
    gains: Option<[(f64, f64); 2]>,
    axes: [AutoAxis<f64>; 2],
}

fn step(t: &mut AutoTrack<f64>, z: [f64; 2], dt: f64) -> Stepped {
    let u = t.update(z, dt).expect("update accepted");
    Stepped {
        gains: u.gains.map(|g| g.map(|g| (g.alpha(), g.beta()))),
        axes: *t.schedule().axes(),
    }
}

// ------------------------------------------------------------------ spec

#[test]
fn spec_needs_the_sensor_and_prints_canonically() {
    let e = ScheduleSpec::parse("auto").unwrap_err();
    assert_eq!(
        e.kind,
        SpecErrorKind::MissingParameter { parameter: "sigma" }
    );
    let e = ScheduleSpec::parse("auto:n-max=50").unwrap_err();
    assert_eq!(
        e.kind,
        SpecErrorKind::MissingParameter { parameter: "sigma" }
    );

    let s = ScheduleSpec::parse("auto:sigma=20").unwrap();
    assert_eq!(s, ScheduleSpec::Auto(AutoConfig::cartesian(20.0)));
    assert_eq!(s.to_string(), "auto:sigma=20,n-max=1000");
    let p = ScheduleSpec::parse("auto:range-sigma=15.24,bearing-sigma-deg=5,n-max=300").unwrap();
    assert_eq!(
        p.to_string(),
        "auto:range-sigma=15.24,bearing-sigma-deg=5,n-max=300"
    );
    for text in [s.to_string(), p.to_string()] {
        assert_eq!(ScheduleSpec::parse(&text).unwrap().to_string(), text);
    }

    // Both forms, half a polar sensor, out-of-range values.
    let refused = |text: &str, parameter: &'static str| {
        let e = ScheduleSpec::parse(text).unwrap_err();
        assert_eq!(
            e.kind,
            SpecErrorKind::Config(ConfigError::OutOfRange { parameter }),
            "{text}"
        );
    };
    refused("auto:sigma=5,range-sigma=5,bearing-sigma-deg=1", "sigma");
    refused("auto:range-sigma=5", "bearing-sigma-deg");
    refused("auto:bearing-sigma-deg=5", "range-sigma");
    refused("auto:sigma=0", "sigma");
    refused("auto:sigma=-3", "sigma");
    refused("auto:sigma=inf", "sigma");
    refused(
        "auto:range-sigma=5,bearing-sigma-deg=91",
        "bearing-sigma-deg",
    );
    refused("auto:sigma=5,n-max=2", "n-max");
    // Builds in every representation the firmware uses.
    for text in [
        "auto:sigma=0.01",
        "auto:sigma=1e6",
        "auto:range-sigma=1,bearing-sigma-deg=0.01",
    ] {
        let spec = ScheduleSpec::parse(text).unwrap();
        AnySchedule::<f32, 2, 8>::from_spec(&spec).unwrap();
        AnySchedule::<Fix, 2, 8>::from_spec(&spec).unwrap();
        AnySchedule::<Fixed32, 2, 8>::from_spec(&spec).unwrap();
    }
}

// ------------------------------------------------------ the reference

/// The rules of `docs/auto.md`, written out again in plain f64 for one
/// axis of a Cartesian sensor.
#[derive(Clone, Copy)]
struct Reference {
    sigma: f64,
    n_max: f64,
    count: f64,
    fast: f64,
    slow: f64,
    ceiling: f64,
}

fn ls(n: f64) -> (f64, f64) {
    (
        2.0 * (2.0 * n - 1.0) / (n * (n + 1.0)),
        6.0 / (n * (n + 1.0)),
    )
}

impl Reference {
    fn new(sigma: f64) -> Self {
        Reference {
            sigma,
            n_max: 1000.0,
            count: 3.0,
            fast: 1.0,
            slow: 1.0,
            ceiling: 1000.0,
        }
    }

    /// The gains for innovation `e` with span² `h2`, and the state after.
    fn update(&mut self, e: f64, h2: f64) -> (f64, f64) {
        let (alpha, _) = ls(self.count);
        let nu = e / self.sigma;
        let nis = nu * nu * (1.0 - alpha) / (1.0 - alpha + alpha * h2);
        let fast = 0.5 * (self.fast + nis);
        let slow = self.slow + (nis - self.slow) / 16.0;
        if slow <= 2.0 {
            self.slow = slow;
            self.ceiling = (self.ceiling * (1.0 + 1.0 / 64.0)).min(self.n_max);
        } else {
            self.slow = 1.0;
            self.ceiling = (self.ceiling.min(self.count) / 2.0).max(3.0);
        }
        let mut n = self.count;
        if fast <= 7.0 {
            self.fast = fast;
        } else {
            self.fast = 1.0;
            let a = 1.0 - (1.0 - alpha) * 7.0 / fast;
            let b = 4.0 - a;
            let root = ((b * b - 8.0 * a).sqrt() + b) / (2.0 * a);
            n = n.min(root).max(3.0);
        }
        self.count = (n + 1.0).min(self.ceiling).min(self.n_max).max(3.0);
        ls(n)
    }
}

/// Straight flight with two manoeuvres and a stretch of misses.
fn manoeuvring(seed: u64, sigma: f64) -> Vec<Option<[f64; 2]>> {
    let mut noise = Noise::new(seed);
    let (mut p, mut v) = ([0.0f64, 0.0], [40.0f64, -10.0]);
    (0..300)
        .map(|k| {
            let a = match k {
                80..=95 => [0.0, 6.0],
                170..=230 => [-2.0, 1.0],
                _ => [0.0, 0.0],
            };
            for i in 0..2 {
                p[i] += v[i] + 0.5 * a[i];
                v[i] += a[i];
            }
            let seen = !(120..124).contains(&k) && noise.uniform() > 0.05;
            seen.then(|| {
                [
                    p[0] + sigma * noise.gaussian(),
                    p[1] + sigma * noise.gaussian(),
                ]
            })
        })
        .collect()
}

#[test]
fn matches_an_independent_transcription() {
    for seed in 1..=20 {
        let sigma = 7.0;
        let mut t = track::<f64>(&AutoConfig::cartesian(sigma));
        let mut reference = [Reference::new(sigma); 2];
        let mut misses = 0u32;
        let mut cuts = 0;
        for z in manoeuvring(seed, sigma) {
            let Some(z) = z else {
                t.coast(1.0).unwrap();
                misses += 1;
                continue;
            };
            let before = t.filter().predict(1.0).ok();
            let s = step(&mut t, z, 1.0);
            if let (Some(g), Some(p)) = (s.gains, before) {
                let h = f64::from(misses + 1);
                let h2 = if h > 1.0 { h * h } else { 1.0 };
                for axis in 0..2 {
                    let (a, b) = reference[axis].update(z[axis] - p[axis].position, h2);
                    assert!((g[axis].0 - a).abs() <= 1e-12 * a, "seed {seed} α");
                    assert!((g[axis].1 - b).abs() <= 1e-12 * b, "seed {seed} β");
                    let got = s.axes[axis].count;
                    assert!((got - reference[axis].count).abs() <= 1e-9 * got, "count");
                    if reference[axis].fast == 1.0 {
                        cuts += 1;
                    }
                }
            }
            misses = 0;
        }
        assert!(cuts > 0, "seed {seed}: the manoeuvres were never detected");
    }
}

/// Without noise on a straight line every NIS is zero: auto is the
/// least-squares schedule (the same gains to rounding).
#[test]
fn a_straight_noise_free_line_gets_the_least_squares_gains() {
    let mut auto = track::<f64>(&AutoConfig::cartesian(10.0));
    let mut ls: ScheduledFilter<f64, LeastSquaresGains, 2, 2> =
        ScheduledFilter::new(LeastSquaresGains::default());
    for k in 0..1500 {
        let z = [100.0 + 30.0 * k as f64, -50.0 + 4.0 * k as f64];
        let a = step(&mut auto, z, 2.0);
        let l = ls.update(z, 2.0).unwrap();
        match (a.gains, l.gains) {
            (Some(ga), Some(gl)) => {
                for axis in 0..2 {
                    let (la, lb) = (gl[axis].alpha(), gl[axis].beta());
                    assert!((ga[axis].0 - la).abs() <= 1e-12 * la, "k {k}");
                    assert!((ga[axis].1 - lb).abs() <= 1e-12 * lb, "k {k}");
                }
            }
            (None, None) => {}
            _ => panic!("k {k}: one filtered and the other not"),
        }
    }
}

// ---------------------------------------------------- stated figures

/// Fraction of axis-updates on which the fast test cuts the count (the fast
/// average is then exactly 1), on a straight line with white noise of the
/// configured σ: docs/auto.md states about 4·10⁻⁴ (P(m > 7) for the fading
/// average m of χ²₁ variables with weight ½). Also the slow test's rate.
#[test]
fn false_alarm_rates_on_a_straight_line() {
    let sigma = 25.0;
    let (mut cuts, mut halvings, mut n) = (0u64, 0u64, 0u64);
    for seed in 0..40 {
        let mut noise = Noise::new(1000 + seed);
        let mut t = track::<f64>(&AutoConfig::cartesian(sigma));
        let mut previous_ceiling = [f64::INFINITY; 2];
        for k in 0..2500 {
            let z = [
                20.0 * k as f64 + sigma * noise.gaussian(),
                -7.0 * k as f64 + sigma * noise.gaussian(),
            ];
            let s = step(&mut t, z, 1.0);
            if s.gains.is_none() {
                continue;
            }
            for axis in 0..2 {
                n += 1;
                if s.axes[axis].fast == 1.0 {
                    cuts += 1;
                }
                if s.axes[axis].ceiling < previous_ceiling[axis] {
                    halvings += 1;
                }
                previous_ceiling[axis] = s.axes[axis].ceiling;
            }
        }
    }
    let cut_rate = cuts as f64 / n as f64;
    let halving_rate = halvings as f64 / n as f64;
    println!("fast-test cut rate {cut_rate:.2e}, slow-test rate {halving_rate:.2e} over {n}");
    assert!(
        (2.5e-4..6e-4).contains(&cut_rate),
        "fast-test false alarms {cut_rate:.2e} per axis-update"
    );
    assert!(
        halving_rate < 1e-3,
        "slow-test false alarms {halving_rate:.2e}"
    );
}

/// The fast statistic alone: P(m > 7) for m_k = (m_{k−1} + χ²₁)/2.
#[test]
fn the_fast_threshold_is_the_stated_quantile() {
    let mut noise = Noise::new(7);
    let mut m = 1.0;
    let (mut over, total) = (0u64, 4_000_000u64);
    for _ in 0..total {
        let g = noise.gaussian();
        m = 0.5 * (m + g * g);
        if m > DETECTION_LEVEL as f64 {
            over += 1;
        }
    }
    let p = over as f64 / total as f64;
    assert!((3.3e-4..4.5e-4).contains(&p), "P(m > 7) = {p:.2e}");
}

// ------------------------------------------------------------ response

/// A 3 m/s² acceleration on x after 60 straight scans (σ = 1 m): within
/// three updates of its start α on x is above 0.5; y, still straight, keeps
/// its small gains.
#[test]
fn a_manoeuvre_raises_the_gains_of_its_axis_within_three_updates() {
    for seed in 0..30 {
        let mut noise = Noise::new(seed);
        let mut t = track::<f64>(&AutoConfig::cartesian(1.0));
        let (mut x, mut vx) = (0.0f64, 50.0f64);
        let mut raised_at = None;
        for k in 0..80 {
            let a = if k >= 60 { 3.0 } else { 0.0 };
            x += vx + 0.5 * a;
            vx += a;
            let z = [x + noise.gaussian(), 10.0 * k as f64 + noise.gaussian()];
            let s = step(&mut t, z, 1.0);
            if let Some(g) = s.gains {
                if k >= 60 && raised_at.is_none() && g[0].0 > 0.5 {
                    raised_at = Some(k - 60);
                }
                if k >= 60 {
                    assert!(g[1].0 < 0.1, "seed {seed} k {k}: y gains {:?}", g[1]);
                }
            }
        }
        let r = raised_at.unwrap_or(usize::MAX);
        assert!(r <= 2, "seed {seed}: α on x above 0.5 only {r} updates in");
    }
}

/// After the manoeuvre the count grows back: 100 straight scans later α is
/// below 0.1 again.
#[test]
fn the_count_grows_back_after_a_manoeuvre() {
    let mut noise = Noise::new(3);
    let mut t = track::<f64>(&AutoConfig::cartesian(2.0));
    let (mut x, mut vx) = (0.0f64, 20.0f64);
    let mut last = None;
    for k in 0..260 {
        let a = if (50..60).contains(&k) { 4.0 } else { 0.0 };
        x += vx + 0.5 * a;
        vx += a;
        let s = step(
            &mut t,
            [x + 2.0 * noise.gaussian(), 2.0 * noise.gaussian()],
            1.0,
        );
        last = s.gains;
    }
    let g = last.unwrap();
    assert!(g[0].0 < 0.1, "α on x {} 200 scans after", g[0].0);
}

// ------------------------------------------------------------- region

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Whatever the innovations (outliers, overflows), every pair lies in
    /// the stability triangle and at or below Kalata's β for its α.
    #[test]
    fn every_gain_is_stable_and_damped(
        seed in 0u64..1000,
        sigma in 0.1f64..500.0,
        outlier in 1.0f64..1e5,
    ) {
        let mut noise = Noise::new(seed);
        let mut t = track::<f64>(&AutoConfig::cartesian(sigma));
        for k in 0..200 {
            let jump = if noise.uniform() < 0.05 { outlier } else { 0.0 };
            let z = [
                3.0 * k as f64 + sigma * noise.gaussian() + jump,
                sigma * noise.gaussian() - jump,
            ];
            let dt = if noise.uniform() < 0.2 { 0.05 + 5.0 * noise.uniform() } else { 1.0 };
            let Ok(u) = t.update(z, dt) else { continue };
            if let Some(g) = u.gains {
                for g in g {
                    let (a, b) = (g.alpha(), g.beta());
                    prop_assert!(a > 0.0 && a <= 5.0 / 6.0 + 1e-12 && b > 0.0 && 2.0 * a + b < 4.0);
                    prop_assert!(b <= li_beta(a) * (1.0 + 1e-9), "β {b} above Kalata's for α {a}");
                }
            }
        }
    }
}

// --------------------------------------------- firmware number types

fn run_in<N: Numeric>(config: &AutoConfig, data: &[Option<[f64; 2]>]) -> Vec<[f64; 2]> {
    let mut t = track::<N>(config);
    let mut out = Vec::new();
    for z in data {
        match z {
            None => t.coast(interval::<N>(1.0)).unwrap(),
            Some(z) => {
                t.update([length::<N>(z[0]), length::<N>(z[1])], interval::<N>(1.0))
                    .unwrap();
                out.push(t.filter().position().map(|v| v.to_f64()));
            }
        }
    }
    out
}

/// f32, Q32.32 and the fast fixed point follow f64 on the manoeuvring
/// track (σ = 7 m): the same cuts, positions within a few centimetres.
#[test]
fn runs_in_the_firmware_types() {
    let config = AutoConfig::cartesian(7.0);
    for seed in 1..=5 {
        let data = manoeuvring(seed, 7.0);
        let reference = run_in::<f64>(&config, &data);
        for (name, got, tolerance) in [
            ("f32", run_in::<f32>(&config, &data), 0.05),
            ("q32", run_in::<Fix>(&config, &data), 1e-3),
            ("fixed32", run_in::<Fixed32>(&config, &data), 0.05),
        ] {
            let worst = got
                .iter()
                .zip(&reference)
                .flat_map(|(g, r)| [(g[0] - r[0]).abs(), (g[1] - r[1]).abs()])
                .fold(0.0f64, f64::max);
            assert!(worst <= tolerance, "{name} seed {seed}: deviates {worst} m");
        }
    }
}

// ---------------------------------------------------------------- polar

/// A range–bearing sensor: σ along each axis follows the position, so the
/// fast test's false-alarm rate on a straight line stays near the
/// Cartesian one at any range and bearing.
#[test]
fn a_polar_sensor_calibrates_at_every_range() {
    let (range_sigma, bearing_sigma) = (15.0, 0.5f64.to_radians());
    let config = AutoConfig::polar(range_sigma, 0.5);
    let (mut cuts, mut n) = (0u64, 0u64);
    for seed in 0..40 {
        let mut noise = Noise::new(50 + seed);
        let mut t = track::<f64>(&config);
        let start = [3000.0 + 500.0 * seed as f64, 40_000.0 - 900.0 * seed as f64];
        for k in 0..1500 {
            let p = [start[0] - 20.0 * k as f64, start[1] + 5.0 * k as f64];
            let r = p[0].hypot(p[1]) + range_sigma * noise.gaussian();
            let b = p[0].atan2(p[1]) + bearing_sigma * noise.gaussian();
            let s = step(&mut t, [r * b.sin(), r * b.cos()], 1.0);
            if s.gains.is_some() {
                for axis in 0..2 {
                    n += 1;
                    cuts += u64::from(s.axes[axis].fast == 1.0);
                }
            }
        }
    }
    let rate = cuts as f64 / n as f64;
    assert!(
        rate < 1.5e-3,
        "polar false alarms {rate:.2e} per axis-update"
    );
}

/// The schedule state machine alone: a miss widens the expected innovation
/// (h = 2), so the same innovation gives a smaller NIS.
#[test]
fn a_miss_widens_the_expected_innovation() {
    use support::context;
    let mut plain = AutoGains::<f64, 1>::new(&AutoConfig::cartesian(1.0)).unwrap();
    let mut missed = plain;
    GainSchedule::<f64, 1>::missed(&mut missed);
    let ctx = context::<f64, 1>(3, 1.0, [0.0], [2.0]);
    let used = plain.gains(&ctx).unwrap();
    plain.accepted(&ctx, &used);
    let used = missed.gains(&ctx).unwrap();
    missed.accepted(&ctx, &used);
    assert!(missed.axes()[0].fast < plain.axes()[0].fast);
}

// ---------------------------------------------------------------- replay

mod replay_cli {
    use abtrack::gain::auto::AutoConfig;
    use abtrack::gain::spec::ScheduleSpec;
    use abtrack::gain::{AnySchedule, ScheduledFilter};
    use abtrack_host_tests::cli::{Command, ReplayArgs};
    use abtrack_host_tests::replay::{replay_reader, FilterKind, Order};
    use clap::Parser;

    use super::support::Noise;

    fn command(line: &str) -> Result<Command, clap::Error> {
        ReplayArgs::try_parse_from(std::iter::once("replay").chain(line.split_whitespace()))?
            .into_command()
    }

    fn run(line: &str, input: &str) -> String {
        match command(&format!("{line} -")) {
            Ok(Command::Replay { config, .. }) => {
                replay_reader(&config, input.as_bytes()).unwrap_or_else(|e| panic!("{line}: {e}"))
            }
            other => panic!("{line}: {other:?}"),
        }
    }

    fn flight(seed: u64) -> (String, Vec<[f64; 2]>, String) {
        let mut noise = Noise::new(seed);
        let mut xy = String::from("t,x,y\n");
        let mut polar = String::from("t,range,azimuth\n");
        let mut z = Vec::new();
        for k in 0..60 {
            let p = [8000.0 - 150.0 * k as f64, 3000.0 + 60.0 * k as f64];
            let m = [
                p[0] + 20.0 * noise.gaussian(),
                p[1] + 20.0 * noise.gaussian(),
            ];
            xy.push_str(&format!("{k},{},{}\n", m[0], m[1]));
            z.push(m);
            polar.push_str(&format!("{k},{},{}\n", m[0].hypot(m[1]), m[0].atan2(m[1])));
        }
        (xy, z, polar)
    }

    /// `replay --filter auto --sigma-m S` is `--filter ab --schedule
    /// auto:sigma=S`, and matches the library run.
    #[test]
    fn filter_auto_runs_the_schedule_with_the_sensor_sigma() {
        let (xy, z, _) = flight(1);
        let out = run("--filter auto --sigma-m 20", &xy);
        assert_eq!(out, run("--filter ab --schedule auto:sigma=20", &xy));
        let spec = ScheduleSpec::Auto(AutoConfig::cartesian(20.0));
        let mut t: ScheduledFilter<f64, AnySchedule<f64, 2, 64>, 2, 2> =
            ScheduledFilter::new(AnySchedule::from_spec(&spec).unwrap());
        let last = out.lines().last().unwrap().to_string();
        for z in &z {
            t.update(*z, 1.0).unwrap();
        }
        let x: f64 = last.split(',').nth(1).unwrap().parse().unwrap();
        assert_eq!(x, t.filter().position()[0]);
        assert!(matches!(
            command("--filter auto --sigma-m 20 -"),
            Ok(Command::Replay { config, .. })
                if matches!(config.filter, FilterKind::Scheduled { order: Order::AlphaBeta, .. })
        ));
    }

    /// Polar input: range and bearing σ, the azimuth unit as given.
    #[test]
    fn filter_auto_takes_a_polar_sensor() {
        let (xy, _, polar) = flight(2);
        let out = run(
            "--filter auto --range-sigma-m 20 --bearing-sigma-deg 0.1",
            &polar,
        );
        assert_eq!(out.lines().next(), Some("t,x,vx,res_x,y,vy,res_y,event"));
        assert_eq!(out.lines().count(), xy.lines().count());
        let deg: String = polar
            .lines()
            .enumerate()
            .map(|(i, l)| {
                if i == 0 {
                    format!("{l}\n")
                } else {
                    let f: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
                    format!("{},{},{}\n", f[0], f[1], f[2].to_degrees())
                }
            })
            .collect();
        let out_deg = run(
            "--filter auto --range-sigma-m 20 --bearing-sigma-deg 0.1 --azimuth-unit deg",
            &deg,
        );
        let last = |s: &str| -> Vec<f64> {
            s.lines()
                .last()
                .unwrap()
                .split(',')
                .map(|v| v.parse().unwrap_or(0.0))
                .collect()
        };
        let (a, b) = (last(&out), last(&out_deg));
        assert!((a[1] - b[1]).abs() < 1e-6 && (a[4] - b[4]).abs() < 1e-6);
    }

    #[test]
    fn filter_auto_needs_the_sensor() {
        for line in [
            "--filter auto -",
            "--filter auto --range-sigma-m 20 -",
            "--filter auto --sigma-m 20 --range-sigma-m 20 --bearing-sigma-deg 1 -",
            "--filter auto --sigma-m 0 -",
            "--filter auto --sigma-m 20 --schedule m2 -",
            "--filter ab --schedule m2 --scan-period-s 2 -",
        ] {
            let e = command(line).expect_err(line);
            assert_eq!(e.exit_code(), 2, "{line}");
        }
    }

    /// `--sigma-m` with `--filter ab` scales the schedule's defaults.
    #[test]
    fn sigma_scales_the_schedule_defaults() {
        let (xy, _, _) = flight(3);
        let scaled = run("--filter ab --schedule m2 --sigma-m 50", &xy);
        let scale = abtrack::gain::spec::SensorScale {
            sigma: 50.0,
            period: 1.0,
            max_acceleration: abtrack::track::defaults::BANK_30_ACCELERATION,
        };
        let n = scale.least_squares_n_max().unwrap();
        assert!(n < 60, "the cap binds within the file");
        assert_eq!(
            scaled,
            run(
                &format!("--filter ab --schedule least-squares:n-max={n}"),
                &xy
            )
        );
        assert_ne!(scaled, run("--filter ab --schedule m2", &xy));
    }

    /// `--tracker --schedule auto:sigma=S` drives the track table.
    #[test]
    fn the_tracker_takes_auto() {
        let run = abtrack_host_tests::scenario::generate("two-crossing", 5).unwrap();
        let csv = run.measurements_csv();
        let Ok(Command::Tracker { options, .. }) =
            command("--tracker --schedule auto:sigma=20 --sigma-m 20 -")
        else {
            panic!("tracker command refused");
        };
        let out =
            abtrack_host_tests::replay_tracker::replay_tracker_reader(&options, csv.as_bytes())
                .unwrap();
        assert!(out.csv.lines().count() > 60, "no tracks reported");
    }
}
