//! The multi-target claims: the default tracker on the simulated multi-target
//! scenarios, in f64, f32 and Q32.32; the adapters' gates; bytes per track.
//!
//! Monte Carlo tests use the first `RUNS` runs of the `multi-target`
//! experiment group (`monte_carlo_seed(BASE_SEED, r)`), so the rates they
//! measure are the ones `results/multi-target/` reports for those runs. The
//! thresholds are below the measured rates by the margin stated on each
//! test; the measured rates are printed (`--nocapture`).

use std::collections::BTreeSet;

use abtrack::filter::range_azimuth::RangeAzimuthNoise;
use abtrack::gain::{FirmnessGains, FixedGains, LiImprovedGains};
use abtrack::track::defaults::{
    default_cartesian, default_polar, DefaultCartesianTrack, DerivedParameters, TrackerDesign,
};
use abtrack::track::{
    Association, DropReason, FixedGainTrack, Gate, GateRegion, Measurement, Observation,
    PolarWindow, PredictedState, RangeAzimuthTrack, ScanInterval, ScheduledTrack, TrackFilter,
    TrackTable, TrackerConfig,
};
use abtrack::{Fix, Gains, Scalar};
use abtrack_host_tests::experiments::multi_target::{BASE_SEED, PLANS};
use abtrack_host_tests::metrics::track_metrics;
use abtrack_host_tests::scenario::{self, ScenarioRun};
use abtrack_host_tests::tracking::{
    compare_decisions, design_for, identity_switches, run_table, to_measurement, TrackerRun,
};

/// Monte Carlo runs per scenario and number type in these tests.
const RUNS: usize = 100;

type Cart<S> = DefaultCartesianTrack<S>;

fn cutoff(name: &str) -> f64 {
    PLANS
        .iter()
        .find(|p| p.scenario == name)
        .map(|p| p.ospa_cutoff)
        .unwrap()
}

fn generate(name: &str, r: usize) -> ScenarioRun {
    scenario::generate(name, scenario::monte_carlo_seed(BASE_SEED, r as u64)).unwrap()
}

/// The default Cartesian tracker (the scenario's design) on one run.
fn run_cartesian<S: Scalar>(name: &str, r: usize) -> TrackerRun {
    let run = generate(name, r);
    let config = design_for(&run.info)
        .unwrap()
        .cartesian_config::<S>()
        .unwrap();
    run_table::<S, Cart<S>, 32, 64>(&run, &config).unwrap()
}

// ---------------------------------------------------------------------------
// Default design

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn nominal_designs_give_the_documented_parameters() {
    let radar: DerivedParameters = TrackerDesign::NOMINAL_RADAR.derive().unwrap();
    let tcas: DerivedParameters = TrackerDesign::NOMINAL_TCAS.derive().unwrap();
    println!("radar {radar:#?}\ntcas {tcas:#?}");
    for d in [&radar, &tcas] {
        // G = −2 ln(0.01·0.1) = 13.8155, P_G = 0.999.
        assert!(close(d.gate_threshold, 13.8155, 1e-4));
        assert!(close(d.gate_probability, 0.999, 1e-9));
        assert_eq!(d.confirmation, (3, 4));
        // P(≥ 2 hits in 3) at p = 0.9·0.999 = 0.8991:
        // 3p²(1 − p) + p³ = 0.97155.
        assert!(close(d.true_confirmation_probability, 0.97155, 1e-4));
        assert!(d.false_confirmations_per_scan <= 1e-3);
        // (1 − p)^4·p = 0.1009⁴·0.8991 = 9.32e-5 ≤ 1e-4 < 0.1009³·0.8991.
        assert_eq!(d.deletion, (4, 2));
        assert!(close(d.spurious_deletions_per_scan, 9.32e-5, 1e-6));
        // σ_w = g·tan 30°/2 = 5.6619/2 = 2.8309, Q = 8.0142.
        assert!(close(d.process_noise, 8.0142, 1e-3));
    }
    // Radar: Λ = 2.830/20 = 0.1415; α_K = 0.4116; α̂(8) = 0.4167 > α_K ≥
    // α̂(9) = 0.3778, so n_max = 9. Margin √(2·13.8155)·20 = 105.1 m.
    assert!(close(radar.tracking_index, 0.14151, 1e-4));
    assert!(close(radar.steady_state_alpha, 0.4116, 1e-3));
    assert_eq!(radar.least_squares_n_max, 9);
    assert!(close(radar.initiation_margin, 105.13, 0.01));
    // TCAS: σ_max = 25 928·0.0872665 = 2262.6 m; margin √27.631·2262.6 = 11 893 m.
    assert!(close(tcas.max_sigma, 2262.65, 0.01));
    assert!(close(tcas.initiation_margin, 11_893.4, 0.5));
    // Rule 7: √(P_D·P_G/(π·λ)) = √(0.8991/(π·10⁻⁷)) = 1691.7 m; TCAS,
    // λ = 3/(π·25 928²): 25 928·√(0.8991/3) = 14 194 m. No clutter, none.
    assert!(close(radar.max_gate_radius.unwrap(), 1691.72, 0.01));
    assert!(close(tcas.max_gate_radius.unwrap(), 14_194.2, 0.1));
    let clean = TrackerDesign {
        clutter_density: 0.0,
        ..TrackerDesign::NOMINAL_RADAR
    };
    assert_eq!(clean.derive().unwrap().max_gate_radius, None);
    assert_eq!(
        clean.cartesian_config::<f64>().unwrap().max_gate_radius(),
        None
    );

    // The scenarios' sensors are the nominal ones.
    for (name, nominal) in [
        ("two-crossing", TrackerDesign::NOMINAL_RADAR),
        ("parallel-200m", TrackerDesign::NOMINAL_RADAR),
        ("tcas-30", TrackerDesign::NOMINAL_TCAS),
    ] {
        let d = design_for(&scenario::info(name).unwrap()).unwrap();
        assert!(
            close(d.clutter_density, nominal.clutter_density, 1e-20),
            "{name}"
        );
        assert_eq!(
            TrackerDesign {
                clutter_density: nominal.clutter_density,
                ..d
            },
            nominal,
            "{name}"
        );
    }
    // dense: a larger square with less clutter per m², so 2 of 3 suffices.
    let dense = design_for(&scenario::info("dense").unwrap())
        .unwrap()
        .derive()
        .unwrap();
    assert_eq!(dense.confirmation, (2, 3));

    // The constructors build in every number type.
    default_cartesian::<f64>().unwrap();
    default_cartesian::<f32>().unwrap();
    default_cartesian::<Fix>().unwrap();
    default_polar::<f64>().unwrap();
    default_polar::<f32>().unwrap();
    default_polar::<Fix>().unwrap();
    let c = default_cartesian::<f64>().unwrap();
    assert_eq!(c.confirmation(), (3, 4));
    assert_eq!(c.deletion(), (4, 2));
    assert!(c.volume().is_some());
    assert!(close(c.max_gate_radius().unwrap(), 1691.72, 0.01));
    let p = default_polar::<f32>().unwrap();
    assert!(close(
        f64::from(p.max_gate_radius().unwrap()),
        14_194.2,
        0.1
    ));
}

#[test]
fn design_refuses_bad_figures() {
    let mut d = TrackerDesign::NOMINAL_RADAR;
    d.detection_probability = 0.0;
    assert!(d.derive().is_err());
    d.detection_probability = f64::NAN;
    assert!(d.derive().is_err());
    let mut d = TrackerDesign::NOMINAL_RADAR;
    d.max_speed = -1.0;
    assert!(d.derive().is_err());
    // The area clutter is counted over: the coverage's (the nominal
    // radar's 10 km square).
    assert_eq!(TrackerDesign::NOMINAL_RADAR.clutter_area(), 1e8);
}

/// Figures no rule up to 8 scans meets both bounds of (rule 4) for are not
/// refused: the design takes the rule meeting the false-track bound with
/// the highest true confirmation, or, when none meets it, the one with the
/// fewest false confirmations, and says so.
#[test]
fn design_takes_its_best_rule_when_none_meets_both_bounds() {
    use abtrack::track::defaults::MAX_FALSE_CONFIRMATIONS_PER_SCAN;
    for nominal in [TrackerDesign::NOMINAL_RADAR, TrackerDesign::NOMINAL_TCAS] {
        assert!(nominal.derive().unwrap().confirmation_meets_bounds);
    }
    // So low a P_D that no rule confirms a true target with probability
    // 0.95 (at most 7 hits after the first point), without clutter: every
    // rule meets the false-track bound, and 2 of 8 confirms most.
    let mut d = TrackerDesign::NOMINAL_RADAR;
    d.detection_probability = 0.3;
    d.clutter_density = 0.0;
    let p = d.derive().unwrap();
    assert!(!p.confirmation_meets_bounds);
    assert_eq!(p.confirmation, (2, 8));
    assert!(p.true_confirmation_probability > 0.9 && p.true_confirmation_probability < 0.95);
    assert_eq!(p.false_confirmations_per_scan, 0.0);
    // With the nominal clutter, a rule meeting the false-track bound exists
    // but confirms less; it is the one with the highest true confirmation
    // among those that meet it.
    d.clutter_density = TrackerDesign::NOMINAL_RADAR.clutter_density;
    let p = d.derive().unwrap();
    assert!(!p.confirmation_meets_bounds);
    assert!(p.false_confirmations_per_scan <= MAX_FALSE_CONFIRMATIONS_PER_SCAN);
    assert!(p.true_confirmation_probability < 0.95);
    // So much clutter that no rule keeps false confirmations below one per
    // 1000 scans: the rule with the fewest. At 3 per km² they are fewest
    // at 8 of 8; from 10 per km² every gate holds clutter, every rule
    // confirms as many false tracks, and the one confirming true targets
    // most, 2 of 8, is taken.
    for (clutter, rule) in [(3e-6, (8, 8)), (1e-5, (2, 8))] {
        let mut d = TrackerDesign::NOMINAL_RADAR;
        d.clutter_density = clutter;
        let p = d.derive().unwrap();
        assert!(!p.confirmation_meets_bounds, "{clutter}");
        assert!(p.false_confirmations_per_scan > MAX_FALSE_CONFIRMATIONS_PER_SCAN);
        assert_eq!(p.confirmation, rule, "{clutter}: {p:?}");
    }
}

// Bytes per track of every filter and number system: host-tests/tests/
// tests/it/track/static_construction.rs (bytes_per_track_of_every_filter).

// ---------------------------------------------------------------------------
// Adapters

/// With fixed gains the scheduled adapter is the fixed-gain track: same
/// covariance, same gates, same decisions on a cluttered two-target run at
/// regular intervals. First points kept through a miss start tracks over
/// two scans, an irregular interval sequence, which the scheduled adapter
/// bounds (`robust_gains`) and the fixed-gain track does not: there the
/// decisions differ, as asserted last.
#[test]
fn scheduled_fixed_gains_decide_as_fixed_gain_track() {
    fn both<S: Scalar>() {
        let run = generate("two-crossing", 3);
        let gains = Gains::<S>::alpha_beta_f64(0.5, 0.2).unwrap();
        let gate = Gate::uncertainty(
            S::from_f64_lossy(20.0),
            S::from_f64_lossy(13.8),
            S::from_f64_lossy(5.0),
        )
        .unwrap();
        let speed = S::from_f64_lossy(300.0);
        let fixed = TrackerConfig::new(gains, gate, speed).unwrap();
        let scheduled = TrackerConfig::new(FixedGains::new(gains), gate, speed).unwrap();
        let (regular_fixed, regular_scheduled) = (
            fixed.keep_first_points_through_a_miss(false),
            scheduled.keep_first_points_through_a_miss(false),
        );
        let a = run_table::<S, FixedGainTrack<S>, 32, 64>(&run, &regular_fixed).unwrap();
        let b = run_table::<S, ScheduledTrack<S, FixedGains<S>>, 32, 64>(&run, &regular_scheduled)
            .unwrap();
        assert_eq!(a.codes, b.codes, "{}", S::NAME);
        assert_eq!(a.reports, b.reports, "{}", S::NAME);
        assert!(a.reports.iter().map(|r| r.gated_pairs).sum::<u32>() > 100);
        let a = run_table::<S, FixedGainTrack<S>, 32, 64>(&run, &fixed).unwrap();
        let b = run_table::<S, ScheduledTrack<S, FixedGains<S>>, 32, 64>(&run, &scheduled).unwrap();
        assert_ne!(a.reports, b.reports, "{}", S::NAME);
    }
    both::<f64>();
    both::<f32>();
    both::<Fix>();
}

fn s<S: Scalar>(v: f64) -> S {
    S::try_from_f64(v).unwrap()
}

/// The range/azimuth window, by hand: prediction (0, 10 000) m,
/// half-widths 100 m in range and 2000 m across. A measurement at range
/// 10 050 m, azimuth 0.1 rad: ΔR = 50 → 0.5; ΔB = 0.1 rad and the azimuth
/// half-width is 2000/10 000 = 0.2 rad → 0.5; d² = 0.25 + 0.25 = 0.5, cost
/// round(0.5·65 534) = 32 767. The same point is 500 m (= 10 050·(1 − cos
/// 0.1) + 50) short of the tangent line's range, so an x, y ellipse along
/// the line of sight with a 100 m half-width would reject it.
#[test]
fn polar_window_cost_by_hand() {
    fn check<S: Scalar>(tolerance: u16) {
        let region =
            GateRegion::<S>::polar([s::<S>(0.0), s(10_000.0)], s(100.0), s(2000.0)).unwrap();
        let polar = Observation::new(Measurement::Polar {
            range: s::<S>(10_050.0),
            azimuth: s(0.1),
        })
        .unwrap();
        let c = region.cost(&polar).unwrap();
        assert!(c.abs_diff(32_767) <= tolerance, "{} {c}", S::NAME);
        // The same point given in x, y.
        let (sb, cb) = 0.1f64.sin_cos();
        let cart = Observation::new(Measurement::Cartesian {
            x: s::<S>(10_050.0 * sb),
            y: s(10_050.0 * cb),
        })
        .unwrap();
        let c = region.cost(&cart).unwrap();
        assert!(c.abs_diff(32_767) <= tolerance, "{} {c}", S::NAME);
        // Outside: 150 m long in range; 0.25 rad off in azimuth; behind
        // the sensor (azimuth 3 rad).
        for (range, azimuth) in [(10_150.0, 0.0), (10_000.0, 0.25), (10_000.0, 3.0)] {
            let o = Observation::new(Measurement::Polar {
                range: s::<S>(range),
                azimuth: s(azimuth),
            })
            .unwrap();
            assert_eq!(region.cost(&o), None, "{} {range} {azimuth}", S::NAME);
        }
        // Azimuth wraps: −0.12 rad and 2π − 0.12 rad are the same direction.
        let a = Observation::new(Measurement::Polar {
            range: s::<S>(10_000.0),
            azimuth: s(-0.12),
        })
        .unwrap();
        let b = Observation::new(Measurement::Polar {
            range: s::<S>(10_000.0),
            azimuth: s(std::f64::consts::TAU - 0.12),
        })
        .unwrap();
        let (ca, cb) = (region.cost(&a).unwrap(), region.cost(&b).unwrap());
        // (0.12/0.2)² = 0.36 → 0.36·65 534 = 23 592.24 → 23 592.
        assert!(
            ca.abs_diff(23_592) <= tolerance && cb.abs_diff(23_592) <= tolerance,
            "{} {ca} {cb}",
            S::NAME
        );
        // At the sensor: the circle of the larger half-width.
        let at_origin = GateRegion::<S>::polar([s::<S>(0.0), s(0.0)], s(100.0), s(2000.0)).unwrap();
        assert_eq!(at_origin.radius().to_f64(), 2000.0);
        assert!(GateRegion::<S>::polar([s::<S>(0.0), s(1.0)], s(0.0), s(2000.0)).is_none());
    }
    check::<f64>(0);
    check::<f32>(2);
    check::<Fix>(1);
}

/// A one-second step of the adapters (their step is the scan interval).
fn second() -> ScanInterval<f64> {
    ScanInterval::from_ms(1000).unwrap()
}

/// The range–azimuth adapter's window from the filter's public covariance
/// factors, recomputed in f64 here: h_R = √G·√(k²·P_R⁻₁₁ + σ_R²) + ½aT²,
/// h_C = √G·√(P_C⁻₁₁ + R_p²σ_B²) + ½aT², k² = (σ_R² + P_C⁻₁₁σ_B² +
/// ¾R_p²σ_B⁴)/σ_R², P⁻₁₁ = (a + Tb)² + (Tc)² + (T²√Q/2)².
#[test]
fn range_azimuth_window_from_its_covariances() {
    let noise = RangeAzimuthNoise::<f64>::new_f64(15.0 * 15.0, 0.05 * 0.05, 4.0).unwrap();
    let mut track = RangeAzimuthTrack::<f64>::empty(&noise);
    // A target at ~8 km, moving across the line of sight.
    for (k, (x, y)) in [
        (0.0, 8000.0),
        (110.0, 8010.0),
        (205.0, 7990.0),
        (300.0, 8000.0),
    ]
    .iter()
    .enumerate()
    {
        let r: f64 = f64::hypot(*x, *y);
        let b = x.atan2(*y);
        let z = Observation::new(Measurement::Polar {
            range: r,
            azimuth: b,
        })
        .unwrap();
        track
            .update(&noise, &z, &second())
            .unwrap_or_else(|e| panic!("{k}: {e}"));
    }
    let (g, a_max, dt) = (13.8, 5.0, 1.5);
    let gate = Gate::uncertainty(15.0, g, a_max).unwrap();
    let step = ScanInterval::from_ms(1500).unwrap();
    let p = track.predict(&noise, &step).unwrap();
    let region = track.gate_region(&noise, &p, &step, &gate).unwrap();
    let GateRegion::Polar(PolarWindow {
        range,
        half_range,
        inverse_half_azimuth,
        ..
    }) = region
    else {
        panic!("{region:?}")
    };
    let pred = |f: abtrack::filter::range_azimuth::CovarianceFactor<f64>| {
        (f.a + dt * f.b).powi(2) + (dt * f.c).powi(2) + (dt * dt * 2.0 / 2.0).powi(2)
    };
    let pr = pred(track.state().range_covariance());
    let pc = pred(track.state().cross_range_covariance());
    let rp = p.position[0].hypot(p.position[1]);
    let sb2 = 0.05f64 * 0.05;
    let k2 = (225.0 + pc * sb2 + 0.75 * rp * rp * sb2 * sb2) / 225.0;
    let allowance = 0.5 * a_max * dt * dt;
    let h_r = (g * (k2 * pr + 225.0)).sqrt() + allowance;
    let h_c = (g * (pc + rp * rp * sb2)).sqrt() + allowance;
    println!("P_R⁻ {pr:.1} P_C⁻ {pc:.1} k² {k2:.2} h_R {h_r:.2} h_C {h_c:.2}");
    assert!(k2 > 1.5, "the coupling matters here: k² = {k2}");
    assert!(close(range, rp, 1e-9));
    assert!(close(half_range, h_r, 1e-6), "{half_range} vs {h_r}");
    assert!(close(range / inverse_half_azimuth, h_c, 1e-6));
}

/// Li et al.'s wave gate on a scheduled track: r = κ·√α·√(Δρ² + ρ²Δθ²) with
/// the α the schedule gives next: a fresh Li schedule's count 3, α = 5/6
/// (eq. 4: 2·5/12).
#[test]
fn wave_gate_uses_the_next_scheduled_alpha() {
    let li = LiImprovedGains::<f64>::new(&abtrack::gain::li::LiImprovedConfig::DEFAULT).unwrap();
    let mut track = ScheduledTrack::empty(&li);
    for x in [1000.0, 1010.0] {
        let z = Observation::new(Measurement::Cartesian { x, y: 0.0 }).unwrap();
        track.update(&li, &z, &second()).unwrap();
    }
    let gate = Gate::wave(3.0, 0.002, 4.0).unwrap();
    let p: PredictedState<f64> = track.predict(&li, &second()).unwrap();
    assert_eq!(p.position, [1020.0, 0.0]);
    let region = track.gate_region(&li, &p, &second(), &gate).unwrap();
    let expected = 4.0 * (5.0f64 / 6.0).sqrt() * (9.0f64 + (1020.0f64 * 0.002).powi(2)).sqrt();
    assert!(
        close(region.radius(), expected, 1e-9),
        "{}",
        region.radius()
    );
    assert!(close(track.gate_alpha(&li), 5.0 / 6.0, 1e-12));
}

/// A TCAS firmness track whose firmness fell to 0 would restart on its next
/// measurement: it gets no gate (and coasts until deleted).
#[test]
fn firmness_restart_gets_no_gate() {
    let f = FirmnessGains::new();
    let mut track = ScheduledTrack::<f64, FirmnessGains>::empty(&f);
    for x in [0.0, 10.0] {
        let z = Observation::new(Measurement::Cartesian { x, y: 0.0 }).unwrap();
        track.update(&f, &z, &second()).unwrap();
    }
    let gate = Gate::uncertainty(5.0, 13.8, 5.0).unwrap();
    let p = track.predict(&f, &second()).unwrap();
    assert!(track.gate_region(&f, &p, &second(), &gate).is_some());
    // Firmness 2 after two points; two misses bring it to 0.
    track.coast(&f, &second()).unwrap();
    track.coast(&f, &second()).unwrap();
    let p = track.predict(&f, &second()).unwrap();
    assert!(track.gate_region(&f, &p, &second(), &gate).is_none());
}

// ---------------------------------------------------------------------------
// Monte Carlo claims

struct Rates {
    kept_whole_run: usize,
    kept_through_crossing: usize,
    /// Runs without a track never paired with a target.
    none_never_paired: usize,
    runs: usize,
}

fn rates<S: Scalar>(name: &str, window: Option<(f64, f64)>) -> Rates {
    let c = cutoff(name);
    let mut r = Rates {
        kept_whole_run: 0,
        kept_through_crossing: 0,
        none_never_paired: 0,
        runs: RUNS,
    };
    for run in 0..RUNS {
        let out = run_cartesian::<S>(name, run);
        let switches = identity_switches(&out.scans, c).unwrap();
        r.kept_whole_run += usize::from(switches.count() == 0);
        let (t0, t1) = window.unwrap_or((0.0, f64::INFINITY));
        r.kept_through_crossing += usize::from(switches.count_between(t0, t1) == 0);
        r.none_never_paired += usize::from(
            track_metrics(&out.scans, c)
                .unwrap()
                .never_paired
                .is_empty(),
        );
    }
    println!(
        "{name} {}: ids kept in {window:?} s {}/{RUNS}, over the whole run {}/{RUNS}; \
         no track never paired {}/{RUNS}",
        S::NAME,
        r.kept_through_crossing,
        r.kept_whole_run,
        r.none_never_paired
    );
    r
}

/// Crossing targets keep their ids through the crossing (no identity switch
/// in 20–40 s, the targets meeting at 30 s) in 100 of 100 runs in each
/// number type, and over the whole 60 s run in 98 of 100 (the other two
/// lose a track away from the crossing and re-acquire it under a new id).
/// Thresholds: each measured rate minus 10 points (90 % and 88 %), so that a
/// legitimate change of the tracker may move the rate a little, while a real
/// association fault (a swap at the crossing in more than 1 run in 10)
/// fails.
#[test]
fn crossing_targets_keep_ids_in_most_runs() {
    fn check<S: Scalar>() {
        let r = rates::<S>("two-crossing", Some((20.0, 40.0)));
        assert!(r.kept_through_crossing * 100 >= 90 * r.runs, "{}", S::NAME);
        assert!(r.kept_whole_run * 100 >= 88 * r.runs, "{}", S::NAME);
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// Parallel targets 200 m apart (10σ) keep their ids over the whole run in
/// 96 of 100 runs in each number type. In the other four a target gets a
/// second track id (never its neighbour's in these 100; once in the
/// experiment's 500 runs, run 247): twice its track is deleted after a run of
/// missed detections (4–5 in a row), twice a young track (confirmed on 4
/// points) coasting through missed detections lets its own measurement fall
/// outside its gate or takes a clutter point, and the target is
/// re-initiated. Threshold 86 % (measured
/// minus 10 points, as above).
#[test]
fn parallel_targets_keep_ids_in_most_runs() {
    fn check<S: Scalar>() {
        let r = rates::<S>("parallel-200m", None);
        assert!(r.kept_whole_run * 100 >= 86 * r.runs, "{}", S::NAME);
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// Clutter at the documented density (λ = 10⁻⁷ m⁻², 10 false measurements
/// per scan, over 60 scans of the two-target scenarios) creates no
/// confirmed false track (a track never paired with a target) in 100 of 100 runs of each (in each number type);
/// the design predicts 1.7·10⁻⁴ false confirmations per scan, 0.01 per run.
/// Threshold 90 % (measured minus 10 points).
#[test]
fn clutter_creates_no_confirmed_false_track_in_most_runs() {
    fn check<S: Scalar>() {
        for name in ["two-crossing", "parallel-200m"] {
            let r = rates::<S>(name, None);
            assert!(
                r.none_never_paired * 100 >= 90 * r.runs,
                "{name} {}",
                S::NAME
            );
        }
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// The `dense` scenario (64 targets) in a 32-track table: candidates are
/// refused and counted (codes `Dropped(TableFull)` = the report's count =
/// the lifetime counter), the table never holds more than 32 tracks, and no
/// confirmed track disappears except by a counted deletion.
#[test]
fn full_table_refuses_and_counts() {
    fn check<S: Scalar>() {
        let run = generate("dense", 0);
        let config = design_for(&run.info)
            .unwrap()
            .cartesian_config::<S>()
            .unwrap();
        let mut table: Box<TrackTable<S, Cart<S>, 32, 128>> = Box::new(TrackTable::new());
        let mut refused_total = 0u32;
        let mut confirmed_before: BTreeSet<u32> = BTreeSet::new();
        for scan in &run.scans {
            let m: Vec<Measurement<S>> = scan
                .measurements
                .iter()
                .map(|m| to_measurement(m).unwrap())
                .collect();
            let mut codes = vec![Association::OutsideGates; m.len()];
            let t_ms = (scan.t * 1000.0).round() as u32;
            let report = table.scan(&config, t_ms, &m, &mut codes).unwrap();
            let refused_codes = codes
                .iter()
                .filter(|c| **c == Association::Dropped(DropReason::TableFull))
                .count() as u32;
            assert_eq!(refused_codes, report.refused_table_full);
            refused_total += report.refused_table_full;
            assert!(table.len() <= 32);
            if report.refused_table_full > 0 {
                assert!(table.is_full());
            }
            let confirmed_now: BTreeSet<u32> = table
                .tracks()
                .filter(|t| t.is_confirmed())
                .map(|t| t.id().get())
                .collect();
            let vanished = confirmed_before.difference(&confirmed_now).count() as u32;
            assert!(
                vanished
                    <= report.deleted_misses
                        + report.deleted_left_volume
                        + report.deleted_gate_too_wide,
                "a confirmed track vanished without a counted deletion at t = {}",
                scan.t
            );
            confirmed_before = confirmed_now;
        }
        println!("{}: {refused_total} candidates refused", S::NAME);
        assert!(refused_total > 0);
        assert_eq!(table.stats().refused_table_full, refused_total);
        assert_eq!(table.len(), 32);
    }
    check::<f64>();
    check::<f32>();
    check::<Fix>();
}

/// f32 and Q32.32 make the same association decisions as f64 — every code
/// of every measurement, track ids included — on the first 100 runs of
/// two-crossing and parallel-200m and the first 20 of dense and tcas-30
/// (measured: 0 differing codes; the `multi-target` group counts them over
/// all its runs, see results/multi-target/decisions.md). Bound: 0.
#[test]
fn f32_and_fixed_decide_as_f64() {
    let mut compared = 0usize;
    for (name, runs) in [
        ("two-crossing", RUNS),
        ("parallel-200m", RUNS),
        ("dense", 20),
    ] {
        for r in 0..runs {
            let a = run_cartesian::<f64>(name, r);
            let b = run_cartesian::<f32>(name, r);
            let c = run_cartesian::<Fix>(name, r);
            let (d32, dfx) = (compare_decisions(&a, &b), compare_decisions(&a, &c));
            assert_eq!(d32.differing_codes, 0, "{name} run {r}: f32 {d32:?}");
            assert_eq!(dfx.differing_codes, 0, "{name} run {r}: fixed {dfx:?}");
            compared += d32.codes;
        }
    }
    for r in 0..20 {
        let run = generate("tcas-30", r);
        let design = design_for(&run.info).unwrap();
        let a = run_table::<f64, RangeAzimuthTrack<f64>, 64, 64>(
            &run,
            &design.polar_config::<f64>().unwrap(),
        )
        .unwrap();
        let b = run_table::<f32, RangeAzimuthTrack<f32>, 64, 64>(
            &run,
            &design.polar_config::<f32>().unwrap(),
        )
        .unwrap();
        let c = run_table::<Fix, RangeAzimuthTrack<Fix>, 64, 64>(
            &run,
            &design.polar_config::<Fix>().unwrap(),
        )
        .unwrap();
        let (d32, dfx) = (compare_decisions(&a, &b), compare_decisions(&a, &c));
        assert_eq!(d32.differing_codes, 0, "tcas-30 run {r}: f32 {d32:?}");
        assert_eq!(dfx.differing_codes, 0, "tcas-30 run {r}: fixed {dfx:?}");
        compared += d32.codes;
    }
    println!("{compared} codes compared per number type");
}
