//! The TCAS II v7.1 pieces one by one, with values worked out by hand: the
//! range tracker (γ convention, firmness, straight-path prediction), the
//! detection rules with memory (TA hysteresis, minimum TA time, firmness
//! gating, threats kept through a missed cycle, the tau cap on both taus,
//! the tau-rise count, the HMD filter for new and continuing threats, the intruder on
//! the ground, the 15 500 ft cap), the resolution logic (sense, crossing,
//! strength, strengthening, weakening, clear of conflict, two threats,
//! inhibits) and the sensitivity-level hysteresis; f64, f32 and Q32.32
//! where the arithmetic matters.

use abtrack::filter::altitude::AltitudeEstimate;
use abtrack::filter::Phase;
use abtrack::tcas::{
    Advisory, CollisionAvoidance, Cycle, IntruderObservation, LowAltitudeInhibits, OwnAircraft,
    RaSense, RaStrength, RangeEstimate, RangeTracker, ResolutionState, SensitivityLevel,
    SensitivitySelector, ThreatGeometry, ThreatState, METRES_PER_NAUTICAL_MILE,
};
use abtrack::{FilterError, Scalar};

const NM: f64 = METRES_PER_NAUTICAL_MILE;

fn c<S: Scalar>(v: f64) -> S {
    S::from_f64_lossy(v)
}

fn close<S: Scalar>(got: S, want: f64, tol: f64) -> bool {
    (got.to_f64() - want).abs() <= tol
}

// ---------------------------------------------------------------------------
// Range tracker
// ---------------------------------------------------------------------------

/// DO-185B's smoother corrects r̈ by γ·e/T² (not abtrack's γ/(2T²)): a
/// level range for 10 scans initialises the track (firmness 8, entry α 0.4,
/// β 0.1, γ 0.01), then one reply 100 m long gives r = 10 000 + 0.4·100,
/// ṙ = 0.1·100/1, r̈ = 0.01·100/1² = 1 m/s².
fn gamma_convention<S: Scalar>() {
    let mut t = RangeTracker::<S>::new();
    for _ in 0..10 {
        t.update(c(10_000.0), S::ONE).unwrap();
    }
    let e = t.estimate().unwrap();
    assert_eq!((e.firmness, e.initialised), (8, true));
    assert!(close(e.range_acceleration_m_per_s2, 0.0, 1e-9));
    t.update(c(10_100.0), S::ONE).unwrap();
    let e = t.estimate().unwrap();
    assert!(close(e.range_m, 10_040.0, 1e-3), "{}: {e:?}", S::NAME);
    assert!(
        close(e.range_rate_m_per_s, 10.0, 1e-4),
        "{}: {e:?}",
        S::NAME
    );
    assert!(
        close(e.range_acceleration_m_per_s2, 1.0, 1e-5),
        "{}: {e:?}",
        S::NAME
    );
}

#[test]
fn range_tracker_gamma_is_over_t_squared() {
    in_every_tcas_type!(gamma_convention);
}

/// Firmness +1 per reply (from 0 at the first), −1 per missed scan;
/// initialised at 8, no longer below 3, when r̈ is dropped; bad input is
/// refused and changes nothing.
#[test]
fn range_tracker_firmness() {
    let mut t = RangeTracker::<f64>::new();
    assert_eq!(t.phase(), Phase::Empty);
    assert!(t.estimate().is_none());
    let mut firmness = Vec::new();
    for k in 0..10 {
        t.update(20_000.0 - 200.0 * k as f64 + 2.0 * (k * k) as f64, 1.0)
            .unwrap();
        firmness.push(t.firmness());
    }
    assert_eq!(firmness, [0, 1, 2, 3, 4, 5, 6, 7, 8, 8]);
    assert!(t.estimate().unwrap().initialised);
    assert!(t.estimate().unwrap().range_acceleration_m_per_s2 != 0.0);
    for want in [7, 6, 5, 4, 3] {
        t.coast(1.0).unwrap();
        assert_eq!(t.firmness(), want);
        assert!(t.estimate().unwrap().initialised);
    }
    t.coast(1.0).unwrap();
    let e = t.estimate().unwrap();
    assert_eq!((e.firmness, e.initialised), (2, false));
    assert_eq!(e.range_acceleration_m_per_s2, 0.0);
    let before = t;
    assert_eq!(
        t.update(f64::NAN, 1.0),
        Err(FilterError::InvalidMeasurement)
    );
    assert_eq!(t.update(-1.0, 1.0), Err(FilterError::InvalidMeasurement));
    assert_eq!(t.update(1000.0, 0.0), Err(FilterError::InvalidInterval));
    assert_eq!(t.coast(-1.0), Err(FilterError::InvalidInterval));
    assert_eq!(t, before);
}

/// A reply either tracker refuses is no reply for the trackers that did
/// not take it: a negative range coasts the range and the altitude tracker
/// alike (so neither lags the other by a scan), and the error is returned
/// to be counted; a valid reply afterwards is taken as usual.
#[test]
fn a_refused_reply_coasts_both_trackers_in_step() {
    use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTrackerConfig};
    use abtrack::tcas::{IntruderTrack, Reply};
    let config = AltitudeTrackerConfig::default_for(AltitudeQuantum::ModeS25).unwrap();
    let reply = |k: f64| Reply {
        range_m: 20_000.0 - 200.0 * k,
        altitude_ft: Some(10_000.0 + 25.0 * k),
    };
    let mut t = IntruderTrack::<f64>::new();
    for k in 0..12 {
        t.scan(&config, Some(reply(f64::from(k))), 1.0).unwrap();
    }
    let mut missed = t;
    missed.scan(&config, None, 1.0).unwrap();
    let bad = Reply {
        range_m: -1.0,
        ..reply(12.0)
    };
    assert_eq!(
        t.scan(&config, Some(bad), 1.0),
        Err(FilterError::InvalidMeasurement)
    );
    assert_eq!(t, missed);
    let nan_altitude = Reply {
        altitude_ft: Some(f64::NAN),
        ..reply(13.0)
    };
    let mut missed_again = t;
    missed_again.scan(&config, None, 1.0).unwrap();
    assert_eq!(
        t.scan(&config, Some(nan_altitude), 1.0),
        Err(FilterError::InvalidMeasurement)
    );
    assert_eq!(t, missed_again);
    // In step: the next reply finds the range where the coasts put it.
    t.scan(&config, Some(reply(14.0)), 1.0).unwrap();
    let e = t.range_tracker().estimate().unwrap();
    assert!((e.range_m - reply(14.0).range_m).abs() < 1.0, "{e:?}");
    assert!((e.range_rate_m_per_s + 200.0).abs() < 1.0, "{e:?}");
}

/// On exact ranges of a straight pass (1 NM abeam, 250 m/s) the
/// straight-path prediction locks on: from 8 km in, the range rate is
/// within 0.5 m/s, and from 7 km (r̈ = v²d²/r³ = 0.62 m/s², above the
/// 0.457 m/s² threshold) the projected miss distance within 2 % of 1852 m —
/// in every type. Through the closest approach the range stays ≥ 0.
fn straight_pass<S: Scalar>() {
    let mut t = RangeTracker::<S>::new();
    let (d, v) = (NM, 250.0);
    for k in 0..140 {
        let y = 20_000.0 - v * k as f64;
        let r = d.hypot(y);
        t.update(c(r), S::ONE).unwrap();
        let e = t.estimate();
        if let Some(e) = e {
            assert!(e.range_m >= S::ZERO);
        }
        if r < 8000.0 && y > 0.0 {
            let e = e.unwrap();
            let rdot = -v * y / r;
            assert!(
                close(e.range_rate_m_per_s, rdot, 0.5),
                "{} k {k}: {e:?}",
                S::NAME
            );
            if r < 7000.0 {
                let hmd = e.miss_distance_m().unwrap().to_f64();
                assert!((hmd - d).abs() < 0.02 * d, "{} k {k}: hmd {hmd}", S::NAME);
            }
        }
    }
    assert_eq!(t.saturations(), 0);
}

#[test]
fn range_tracker_follows_a_straight_pass() {
    in_every_tcas_type!(straight_pass);
}

// ---------------------------------------------------------------------------
// Detection with memory
// ---------------------------------------------------------------------------

fn cycle_at<S: Scalar>(altitude_ft: f64) -> Cycle<S> {
    let own = OwnAircraft::over_sea_level(c(altitude_ft), S::ZERO);
    CollisionAvoidance::<S>::new()
        .begin_cycle(&own, false)
        .unwrap()
}

/// An observation with a firm, initialised range track and no acceleration
/// (HMD filter off).
fn observation<S: Scalar>(
    r: f64,
    rdot: f64,
    altitude: Option<(f64, f64)>,
) -> IntruderObservation<S> {
    IntruderObservation {
        range: RangeEstimate {
            range_m: c(r),
            range_rate_m_per_s: c(rdot),
            range_acceleration_m_per_s2: S::ZERO,
            firmness: 8,
            initialised: true,
            acceleration_threshold_m_per_s2: c(0.457),
            residual_sigma_m: S::ZERO,
        },
        bearing_miss_distance_m: None,
        bearing_miss_distance_sigma_m: None,
        altitude: altitude.map(|(z, zd)| AltitudeEstimate {
            altitude_ft: c(z),
            vertical_rate_ft_per_s: c(zd),
        }),
        altitude_firmness: 3,
    }
}

/// A refused assessment (an altitude estimate that is not a number)
/// changes nothing, the miss-distance filter's memory included: the
/// refused observation's range track would have shut the filter down (a
/// manoeuvre, r̈ below minus its threshold).
#[test]
fn a_refused_assessment_changes_nothing() {
    let cycle = cycle_at::<f64>(8000.0);
    let mut s = ThreatState::<f64>::new();
    for k in 0..6 {
        let r = 9000.0 - 150.0 * f64::from(k);
        s.assess(&cycle, &observation(r, -150.0, Some((8000.0, 0.0))), 1.0)
            .unwrap();
    }
    let before = s;
    let mut manoeuvring = observation::<f64>(8000.0, -150.0, Some((8000.0, f64::NAN)));
    manoeuvring.range.range_acceleration_m_per_s2 = -2.0;
    assert!(s.assess(&cycle, &manoeuvring, 1.0).is_err());
    assert_eq!(s, before);
}

/// TA range hysteresis (DO-185B `TARHYST` 0.2 NM): SL 5's TA DMOD is
/// 0.75 NM = 1389 m, H1 0.006 NM²/s = 20 579 m²/s. Opening at 5 m/s
/// (> 10 ft/s, diverging), a fresh intruder at 1450 m is no TA; one that
/// had a TA at 1300 m (1300·5 = 6500 ≤ H1) keeps it at 1450 m (DMOD +
/// 0.2 NM = 1759 m), and loses it past 1759 m once the 8 s minimum is over.
fn ta_hysteresis<S: Scalar>() {
    let cycle = cycle_at::<S>(8000.0);
    let one = S::ONE;
    let alt = Some((8000.0, 0.0));
    let mut fresh = ThreatState::<S>::new();
    let a = fresh
        .assess(&cycle, &observation(1450.0, 5.0, alt), one)
        .unwrap();
    assert_eq!(a.advisory, Advisory::ProximateTraffic, "{}", S::NAME);
    let mut s = ThreatState::<S>::new();
    let a = s
        .assess(&cycle, &observation(1300.0, 5.0, alt), one)
        .unwrap();
    assert_eq!(a.advisory, Advisory::Traffic);
    assert!(a.new_traffic);
    for k in 1..12 {
        let r = 1300.0 + 50.0 * k as f64;
        let a = s.assess(&cycle, &observation(r, 5.0, alt), one).unwrap();
        assert!(!a.new_traffic);
        let want = if r <= 0.95 * NM || k < 8 {
            Advisory::Traffic
        } else {
            Advisory::ProximateTraffic
        };
        assert_eq!(a.advisory, want, "{} k {k} r {r}", S::NAME);
    }
}

#[test]
fn traffic_advisory_range_hysteresis() {
    in_every_tcas_type!(ta_hysteresis);
}

/// Minimum TA time (DO-185B `MINTATIME` 8 s): a TA whose tests fail the
/// next scan is shown 8 scans in all, then dropped.
#[test]
fn traffic_advisory_lasts_at_least_8_s() {
    let cycle = cycle_at::<f64>(8000.0);
    let mut s = ThreatState::<f64>::new();
    // 700 ft above, level: a TA, no RA.
    let alt = Some((8700.0, 0.0));
    assert_eq!(
        s.assess(&cycle, &observation(3000.0, -200.0, alt), 1.0)
            .unwrap()
            .advisory,
        Advisory::Traffic
    );
    let mut held = 1;
    for _ in 0..12 {
        // 20 km away and opening: no test passes.
        let a = s
            .assess(&cycle, &observation(20_000.0, 100.0, alt), 1.0)
            .unwrap();
        if a.advisory == Advisory::Traffic {
            held += 1;
        }
    }
    assert_eq!(held, 8);
}

/// Advisories start only from firm tracks (before, a three-scan clutter
/// track raised a TA): range firmness 2 holds back a TA the tests give, 3
/// lets it through; vertical firmness 1 holds back an RA (a TA is shown), 2
/// lets it through; a continuing RA is not dropped when firmness falls.
#[test]
fn advisories_only_from_firm_tracks() {
    let cycle = cycle_at::<f64>(8000.0);
    let alt = Some((8100.0, 0.0));
    let mut o = observation::<f64>(3000.0, -250.0, alt);
    o.range.firmness = 2;
    let mut s = ThreatState::new();
    let a = s.assess(&cycle, &o, 1.0).unwrap();
    assert_eq!(a.advisory, Advisory::ProximateTraffic);
    assert!(a.held_by_firmness);
    o.range.firmness = 3;
    o.altitude_firmness = 1;
    let a = s.assess(&cycle, &o, 1.0).unwrap();
    assert_eq!(a.advisory, Advisory::Traffic);
    assert!(a.held_by_firmness);
    o.altitude_firmness = 2;
    let a = s.assess(&cycle, &o, 1.0).unwrap();
    assert_eq!(a.advisory, Advisory::Resolution);
    assert!(a.geometry.is_some());
    o.altitude_firmness = 0;
    o.range.firmness = 1;
    o.range.range_m = 2800.0;
    assert_eq!(
        s.assess(&cycle, &o, 1.0).unwrap().advisory,
        Advisory::Resolution
    );
}

/// DO-185B `KHIT` and `TMIN` at SL 5 (own level at 8000 ft): a co-altitude
/// intruder 3000 m out closing at 200 m/s (τ_mod 13.3 s < 25 s) is an RA
/// threat; opening at 200 m/s beyond DMOD it misses the range test. Its
/// first miss keeps the RA (KHIT 3 → 1); its next ends it only once more
/// than 4.5 s have passed since it became a threat: misses from the
/// second cycle on keep the RA until 5 s. A threat older than that, missing
/// one cycle between hits, keeps its RA through the miss and ends at the
/// second of two misses in a row (its TA, older than 8 s, ends with it).
fn threat_kept_through_one_miss<S: Scalar>() {
    let cycle = cycle_at::<S>(8000.0);
    let alt = Some((8000.0, 0.0));
    let (closing, opening) = (
        observation::<S>(3000.0, -200.0, alt),
        observation::<S>(3000.0, 200.0, alt),
    );
    let one = S::ONE;
    let mut s = ThreatState::<S>::new();
    let mut advisories = vec![s.assess(&cycle, &closing, one).unwrap().advisory];
    for _ in 0..6 {
        advisories.push(s.assess(&cycle, &opening, one).unwrap().advisory);
    }
    let ra = Advisory::Resolution;
    assert_eq!(advisories[..5], [ra; 5], "{}", S::NAME);
    assert_eq!(advisories[5..], [Advisory::Traffic; 2], "{}", S::NAME);

    let mut s = ThreatState::<S>::new();
    for _ in 0..10 {
        assert_eq!(s.assess(&cycle, &closing, one).unwrap().advisory, ra);
    }
    let pattern = [&opening, &closing, &opening, &opening];
    let advisories: Vec<_> = pattern
        .iter()
        .map(|o| s.assess(&cycle, o, one).unwrap())
        .collect();
    assert!(advisories[..3]
        .iter()
        .all(|a| a.advisory == ra && a.geometry.is_some()));
    // Its TA is older than 8 s and the opening intruder fails the TA
    // range test: proximate traffic.
    assert_eq!(
        advisories[3].advisory,
        Advisory::ProximateTraffic,
        "{}",
        S::NAME
    );
    assert!(!s.is_ra_threat());
}

#[test]
fn a_threat_is_kept_through_one_missed_cycle() {
    in_every_tcas_type!(threat_kept_through_one_miss);
}

/// `TMIN` is a bound the age must pass (DO-185B `TCUR − TCMD > TMIN`):
/// at 0.5 s cycles, exact in every type, the intruder of
/// [`threat_kept_through_one_miss`] missing from the cycle after its RA is
/// kept through the miss at 4.5 s and ends at 5.0 s. A kept threat also
/// skips the vertical test when it hits the range test again: the same
/// intruder, a threat for 6 s, 3000 ft above when it closes again after
/// one miss, keeps its RA (a new threat there gets no advisory at all, and
/// a second miss would end it), and its miss distance is held to the
/// continuing threshold.
fn threat_age_and_kept_threat_tests<S: Scalar>() {
    let cycle = cycle_at::<S>(8000.0);
    let alt = Some((8000.0, 0.0));
    let closing = observation::<S>(3000.0, -200.0, alt);
    let opening = observation::<S>(3000.0, 200.0, alt);
    let half = c::<S>(0.5);
    let mut s = ThreatState::<S>::new();
    assert_eq!(
        s.assess(&cycle, &closing, half).unwrap().advisory,
        Advisory::Resolution
    );
    let kept = (1..=12)
        .take_while(|_| s.assess(&cycle, &opening, half).unwrap().advisory == Advisory::Resolution)
        .count();
    assert_eq!(kept, 9, "{}: misses kept", S::NAME);

    let far_above = observation::<S>(3000.0, -200.0, Some((11_000.0, 0.0)));
    assert_eq!(
        ThreatState::<S>::new()
            .assess(&cycle, &far_above, S::ONE)
            .unwrap()
            .advisory,
        Advisory::None,
        "{}",
        S::NAME
    );
    // A threat for 6 s (past TMIN), then one miss: a second miss would
    // end it.
    let mut s = ThreatState::<S>::new();
    for o in [&closing; 6].into_iter().chain([&opening]) {
        assert_eq!(
            s.assess(&cycle, o, S::ONE).unwrap().advisory,
            Advisory::Resolution
        );
    }
    assert_eq!(
        s.assess(&cycle, &far_above, S::ONE).unwrap().advisory,
        Advisory::Resolution,
        "{}",
        S::NAME
    );
    // A kept threat's miss distance is held to the continuing threshold
    // (1.05·DMOD = 1069.5 m), not the new threat's (1018.6 m): r̈ = 1.8213
    // m/s² makes the range track's miss d = 1040 m, 1040.2 m linearised at
    // the new threshold (a new threat's RA filtered), 1040.4 m at the
    // continuing one (kept).
    let mut between = closing;
    between.range.range_acceleration_m_per_s2 = c(1.8213);
    let new = ThreatState::<S>::new()
        .assess(&cycle, &between, S::ONE)
        .unwrap();
    assert!(new.miss_distance_filtered, "{}", S::NAME);
    let mut s = ThreatState::<S>::new();
    for o in [&closing; 6].into_iter().chain([&opening]) {
        s.assess(&cycle, o, S::ONE).unwrap();
    }
    let kept = s.assess(&cycle, &between, S::ONE).unwrap();
    assert!(!kept.miss_distance_filtered, "{}", S::NAME);
    assert_eq!(kept.advisory, Advisory::Resolution, "{}", S::NAME);
}

#[test]
fn a_threat_ends_only_after_tmin_and_skips_the_vertical_test_while_kept() {
    in_every_tcas_type!(threat_age_and_kept_threat_tests);
}

/// The tau cap keeps lowering while the range track is not firm, once it
/// was (DO-185B `tau_calculation`: `TAUCAP` stays set), and the resolution
/// model takes the capped taus. SL 5 (TAU 25 s, TVPE 30 s), co-altitude,
/// r = 6000 m: firm at τ_mod 30.0 s (ṙ −194.2 m/s, true tau 30.9 s), no
/// RA; range firmness 2 at τ_mod 20.0 s (ṙ −291.4, 20.6 s): the RA held
/// back by firmness, the cap at 20.0 s; firm again at τ_mod 28.0 s (ṙ
/// −208.1, 28.8 s): under the cap τ_mod is 20.0 s, so the RA, with the
/// model's taus 20.0 s and 20.6 s. A cap kept from firm cycles alone would
/// hold 30.0 s, and τ_mod 28.0 s gives no RA.
fn cap_in_non_firm_cycles<S: Scalar>() {
    let cycle = cycle_at::<S>(8000.0);
    let alt = Some((8000.0, 0.0));
    let mut s = ThreatState::<S>::new();
    let a = s
        .assess(&cycle, &observation::<S>(6000.0, -194.2, alt), S::ONE)
        .unwrap();
    assert_eq!(a.advisory, Advisory::Traffic, "{}", S::NAME);
    let mut o = observation::<S>(6000.0, -291.4, alt);
    o.range.firmness = 2;
    let a = s.assess(&cycle, &o, S::ONE).unwrap();
    assert!(a.held_by_firmness && a.advisory != Advisory::Resolution);
    let a = s
        .assess(&cycle, &observation::<S>(6000.0, -208.1, alt), S::ONE)
        .unwrap();
    assert_eq!(a.advisory, Advisory::Resolution, "{}", S::NAME);
    let g = a.geometry.unwrap();
    assert!(close(g.modified_tau_s, 20.0, 0.01), "{}", S::NAME);
    assert!(close(g.range_tau_s, 6000.0 / 291.4, 0.01), "{}", S::NAME);
}

#[test]
fn the_tau_cap_runs_in_non_firm_cycles_and_feeds_the_model() {
    in_every_tcas_type!(cap_in_non_firm_cycles);
}

/// DO-185B `TAURISE` at SL 5 (own level at 8000 ft, DMOD 1018.6 m): a
/// co-altitude intruder at 5000 m whose closure falls 250, 240, 230, 220,
/// 210 m/s keeps τ_mod under 25 s (22.8 s at the fifth cycle), but its
/// true tau rises (20.0 → 23.8 s). The range track is firm from the first
/// cycle (the tau cap and the count run from there), the vertical track
/// only from cycle `firm_from`, which holds back the RA until then. At
/// the fourth cycle the count is 3 ≥ 3 beyond 1.7 NM (3148 m): a new
/// threat is no range hit, a TA; at the third it is 2, and the RA goes
/// through. With a falling true tau (the range closing at 250 m/s), or the
/// same rise inside 1.7 NM (3000 m, closure 150 → 130 m/s: τ_mod 20.4 s),
/// the fifth cycle gives the RA; and a threat since the first cycle keeps
/// its RA through a rise (the count holds back only new threats).
fn tau_rise<S: Scalar>() {
    let cycle = cycle_at::<S>(8000.0);
    let alt = Some((8000.0, 0.0));
    let run = |ranges: &[f64], rates: &[f64], firm_from: usize| {
        let mut s = ThreatState::<S>::new();
        let mut statuses = Vec::new();
        for (k, (r, rdot)) in ranges.iter().zip(rates).enumerate() {
            let mut o = observation::<S>(*r, *rdot, alt);
            o.altitude_firmness = if k < firm_from { 0 } else { 3 };
            statuses.push(s.assess(&cycle, &o, S::ONE).unwrap().advisory);
        }
        statuses
    };
    let closure_falls = [-250.0, -240.0, -230.0, -220.0, -210.0];
    let rising = run(&[5000.0; 5], &closure_falls, 3);
    assert_eq!(rising[3], Advisory::Traffic, "{}", S::NAME);
    let rising = run(&[5000.0; 5], &closure_falls, 2);
    assert_eq!(rising[2], Advisory::Resolution, "{}", S::NAME);
    let falling = run(&[5000.0, 4750.0, 4500.0, 4250.0, 4000.0], &[-250.0; 5], 4);
    assert_eq!(falling[4], Advisory::Resolution, "{}", S::NAME);
    let near = run(&[3000.0; 5], &[-150.0, -145.0, -140.0, -135.0, -130.0], 4);
    assert_eq!(near[4], Advisory::Resolution, "{}", S::NAME);
    // A threat from 6000 m closing at 250 m/s (τ_mod 23.3 s), then held at
    // 4750 m while its closure falls 240 → 200 m/s for five cycles (the
    // count reaching 5, τ_mod at most 22.7 s): an RA throughout, where a
    // count that stopped it too would end it after TMIN.
    let ranges = [
        6000.0, 5750.0, 5500.0, 5250.0, 5000.0, 4750.0, 4750.0, 4750.0, 4750.0, 4750.0, 4750.0,
    ];
    let rates = [
        -250.0, -250.0, -250.0, -250.0, -250.0, -250.0, -240.0, -230.0, -220.0, -210.0, -200.0,
    ];
    let threat = run(&ranges, &rates, 0);
    assert_eq!(threat, [Advisory::Resolution; 11], "{}", S::NAME);
}

#[test]
fn a_new_threat_whose_true_tau_keeps_rising_is_no_range_hit() {
    in_every_tcas_type!(tau_rise);
}

/// The tau cap holds the true tau too (DO-185B `TRTRU`), and the vertical
/// miss distance takes it: own level at 8000 ft (SL 5: ZTHR 600 ft, TVPC
/// 40 s, level-own τ_v threshold 20 s), an intruder 700 ft below climbing
/// at 40 ft/s (τ_v 17.5 s). Firm at 1100 m closing at 500 m/s (true tau
/// 2.2 s; far below then, 3000 ft, so no RA), then at 1050 m closing at
/// 20 m/s: the capped taus (2.2 s and 0.3 s) put the vertical miss at
/// −612 ft, beyond ZTHR, and τ_v is not under the capped true tau: no RA.
/// Uncapped (52.5 s, at most TVPC 40 s, and 3.1 s) the two projections
/// would straddle co-altitude (a miss of 0 ft) and give one.
fn true_tau_cap<S: Scalar>() {
    let cycle = cycle_at::<S>(8000.0);
    let mut s = ThreatState::<S>::new();
    let far = observation::<S>(1100.0, -500.0, Some((5000.0, 0.0)));
    assert_ne!(
        s.assess(&cycle, &far, S::ONE).unwrap().advisory,
        Advisory::Resolution
    );
    let near = observation::<S>(1050.0, -20.0, Some((7300.0, 40.0)));
    let a = s.assess(&cycle, &near, S::ONE).unwrap();
    assert_eq!(a.advisory, Advisory::Traffic, "{}", S::NAME);
    let mut fresh = ThreatState::<S>::new();
    let a = fresh.assess(&cycle, &near, S::ONE).unwrap();
    assert_eq!(a.advisory, Advisory::Resolution, "{}", S::NAME);
}

#[test]
fn the_vertical_tests_take_the_capped_true_tau() {
    in_every_tcas_type!(true_tau_cap);
}

/// The HMD filter (SL 5: HMD 3342 ft = 1018.6 m; continuing threats 1.05·
/// DMOD = 1069.5 m for more than 4 cycles; k = 0 for a new threat, 2 for
/// a continuing one; the bearing cross-check takes b + 2σ_b). r = 3000 m,
/// ṙ = −200 m/s and r̈ = 4.4444 m/s² project d² = 9·10⁶·13 333/53 333 =
/// 2.25·10⁶ m² (d = 1500 m); linearised at t = 1018.6 m, d²/(2t) + t/2 =
/// 1613.7 m, with σ = r²/(2tD)·√(a² + b² + 2ρab), D = x + ṙ²: a =
/// rṙ²σ(r̈)/D = 2250·σ(r̈) from r̈, b = −2xṙσ(ṙ)/D = 100·σ(ṙ) from ṙ,
/// σ(r̈) = 0.011 586·σ_resid, σ(ṙ) = 0.114 692·σ_resid, ρ = 0.959 645
/// (T = 1 s): σ = 3.0825·σ_resid (2.1593·σ_resid from r̈ alone).
fn with_hmd(bearing_hmd: f64, bearing_sigma: f64, residual_sigma: f64) -> IntruderObservation<f64> {
    let mut o = observation::<f64>(3000.0, -200.0, Some((8100.0, 0.0)));
    o.range.range_acceleration_m_per_s2 = 13_333.33 / 3000.0;
    o.range.residual_sigma_m = residual_sigma;
    o.bearing_miss_distance_m = Some(bearing_hmd);
    o.bearing_miss_distance_sigma_m = Some(bearing_sigma);
    o
}

/// DO-185B `TMIN_MDF`: the HMD filter ends a continuing RA after more than
/// 4 cycles over 1.05·DMOD from SL 4 up, never at SL 3 (9999). The
/// intruder of [`with_hmd`], 100 ft above a level own aircraft at 2000 ft
/// (SL 3: TAU 15 s, τ_mod 14.8 s) and at 8000 ft (SL 5): a bearing miss of
/// 100 ± 50 m against the range's 1500 m is a manoeuvre (the filter off for
/// 10 cycles), so the RA starts; then 1400 ± 50 m, well over 1.05·DMOD
/// (389 m at SL 3, 1069.5 m at SL 5) for 30 cycles.
#[test]
fn the_miss_distance_filter_never_ends_an_ra_at_sl3() {
    for (own_ft, ends) in [(2000.0, false), (8000.0, true)] {
        let cycle = cycle_at::<f64>(own_ft);
        let obs = |b: f64| {
            let mut o = with_hmd(b, 50.0, RESIDUAL_FOR_200_M);
            o.altitude = Some(AltitudeEstimate {
                altitude_ft: own_ft + 100.0,
                vertical_rate_ft_per_s: 0.0,
            });
            o
        };
        let mut s = ThreatState::new();
        let a = s.assess(&cycle, &obs(100.0), 1.0).unwrap();
        assert_eq!(a.advisory, Advisory::Resolution, "{own_ft} ft: {a:?}");
        let kept = (0..30)
            .take_while(|_| {
                s.assess(&cycle, &obs(1400.0), 1.0).unwrap().advisory == Advisory::Resolution
            })
            .count();
        assert_eq!(kept < 30, ends, "{own_ft} ft: the RA held {kept} cycles");
    }
}

/// σ_resid giving the range statistic σ 200 m at the new-threat threshold.
const RESIDUAL_FOR_200_M: f64 = 200.0 / 3.082_54;

#[test]
fn miss_distance_filter_new_and_continuing_threats() {
    let cycle = cycle_at::<f64>(8000.0);
    // Exact range track (no residual): the range statistic decides,
    // 1613.7 m > 1018.6 m, filtered, whatever b = 900 ± 100 m says.
    let mut s = ThreatState::new();
    let a = s.assess(&cycle, &with_hmd(900.0, 100.0, 0.0), 1.0).unwrap();
    assert!((a.miss_distance_m.unwrap() - 1613.7).abs() < 0.5, "{a:?}");
    assert_eq!(a.advisory, Advisory::Traffic);
    assert!(a.miss_distance_filtered);
    // Range 1613.7 ± 200, bearing 800 ± 200: equal weights, m = 1206.9 m:
    // filtered.
    let sigma = RESIDUAL_FOR_200_M;
    let a = s
        .assess(&cycle, &with_hmd(800.0, 200.0, sigma), 1.0)
        .unwrap();
    assert!((a.miss_distance_m.unwrap() - 1206.9).abs() < 0.5, "{a:?}");
    assert!(a.miss_distance_filtered);
    // Bearing 500 ± 300: the range HMD (1500 m) is more than twice b, but
    // not twice b + 2σ_b = 1100 m: within the bearing's noise, no
    // manoeuvre; m = 1271.0 m (weights 1/200², 1/300²): filtered.
    let a = s
        .assess(&cycle, &with_hmd(500.0, 300.0, sigma), 1.0)
        .unwrap();
    assert!((a.miss_distance_m.unwrap() - 1271.0).abs() < 0.5, "{a:?}");
    assert!(a.miss_distance_filtered);
    // Bearing 800 ± 50: weight of the range 50²/(200² + 50²) = 0.0588,
    // m = 847.9 m: an RA.
    let a = s
        .assess(&cycle, &with_hmd(800.0, 50.0, sigma), 1.0)
        .unwrap();
    assert!((a.miss_distance_m.unwrap() - 847.9).abs() < 0.5, "{a:?}");
    assert_eq!(a.advisory, Advisory::Resolution);
    // Continuing, at t = 1069.5 m (range statistic 1586.7 ± 190.5): with
    // b = 800 ± 50 the two are 786.7/197.0 = 3.99 σ apart, so the combined
    // σ (48.4 m) is scaled by 3.99 to 193.2 m and the lower bound
    // m − 2σ = 850.7 − 386.4 = 464.4 m keeps the RA; with b = 1400 ± 50
    // (0.95 σ apart: no scaling) it is 1412.0 − 96.7 = 1315.3 m, over
    // 1.05·DMOD: the filter removes the range hit on the fifth cycle, and
    // the threat, kept through that first miss, ends at the second
    // (DO-185B `KHIT` 3 → 1 → 0, long after `TMIN`).
    for _ in 0..8 {
        let a = s
            .assess(&cycle, &with_hmd(800.0, 50.0, sigma), 1.0)
            .unwrap();
        assert_eq!(a.advisory, Advisory::Resolution);
        assert!((a.miss_distance_m.unwrap() - 464.4).abs() < 0.5, "{a:?}");
    }
    let levels: Vec<_> = (0..6)
        .map(|_| {
            let a = s
                .assess(&cycle, &with_hmd(1400.0, 50.0, sigma), 1.0)
                .unwrap();
            assert!((a.miss_distance_m.unwrap() - 1315.3).abs() < 0.5, "{a:?}");
            a.advisory
        })
        .collect();
    assert_eq!(levels[..5], [Advisory::Resolution; 5]);
    assert_eq!(levels[5], Advisory::Traffic);
    // A range HMD (1500 m, r̈ over its threshold 0.457·σ_resid/10.67 m)
    // more than twice b + 2σ_b = 400 m is a manoeuvre: the filter is off
    // (10 cycles) and a new threat gets its RA.
    let mut s = ThreatState::new();
    let a = s
        .assess(&cycle, &with_hmd(300.0, 50.0, sigma), 1.0)
        .unwrap();
    assert_eq!(a.miss_distance_m, None);
    assert_eq!(a.advisory, Advisory::Resolution);
}

/// The σ of the firm range track's r̈ and ṙ per σ of its residual
/// (`ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA`, `RATE_SIGMA_PER_RESIDUAL_SIGMA`)
/// and the correlation of their errors (`RATE_ACCELERATION_ERROR_CORRELATION`,
/// with `RATE_ERROR_UNCORRELATED_SHARE` = √(1 − ρ²))
/// are the steady state of the firmness-8 gains on white range noise: the
/// error covariance P of x⁺ = (I − KH)F x + Kv solved by iteration,
/// residual variance HFPFᵀHᵀ + 1.
#[test]
fn rate_and_acceleration_sigmas_are_the_steady_state_of_the_firm_gains() {
    use abtrack::gain::tcas::{FIRMNESS_ALPHA, FIRMNESS_BETA, FIRMNESS_GAMMA, MAX_FIRMNESS};
    use abtrack::tcas::range_tracker::{
        ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA, RATE_ACCELERATION_ERROR_CORRELATION,
        RATE_ERROR_UNCORRELATED_SHARE, RATE_SIGMA_PER_RESIDUAL_SIGMA,
    };
    let i = usize::from(MAX_FIRMNESS);
    let (a, b, g) = (FIRMNESS_ALPHA[i], FIRMNESS_BETA[i], FIRMNESS_GAMMA[i]);
    let f = [[1.0, 1.0, 0.5], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0]];
    let k = [a, b, g];
    // A = (I − K H) F.
    let mut m = [[0.0; 3]; 3];
    for r in 0..3 {
        for col in 0..3 {
            m[r][col] = f[r][col] - k[r] * f[0][col];
        }
    }
    let mut p = [[0.0f64; 3]; 3];
    for _ in 0..5000 {
        let mut next = [[0.0; 3]; 3];
        for r in 0..3 {
            for col in 0..3 {
                let mut sum = k[r] * k[col];
                for u in 0..3 {
                    for v in 0..3 {
                        sum += m[r][u] * p[u][v] * m[col][v];
                    }
                }
                next[r][col] = sum;
            }
        }
        p = next;
    }
    let mut predicted = 0.0;
    for u in 0..3 {
        for v in 0..3 {
            predicted += f[0][u] * p[u][v] * f[0][v];
        }
    }
    let ratio = (p[2][2] / (predicted + 1.0)).sqrt();
    assert!(
        (ratio - ACCELERATION_SIGMA_PER_RESIDUAL_SIGMA).abs() < 1e-5,
        "{ratio}"
    );
    let rate = (p[1][1] / (predicted + 1.0)).sqrt();
    assert!(
        (rate - RATE_SIGMA_PER_RESIDUAL_SIGMA).abs() < 1e-5,
        "{rate}"
    );
    let correlation = p[1][2] / (p[1][1] * p[2][2]).sqrt();
    assert!(
        (correlation - RATE_ACCELERATION_ERROR_CORRELATION).abs() < 1e-5,
        "{correlation}"
    );
    let rho = RATE_ACCELERATION_ERROR_CORRELATION;
    assert!((RATE_ERROR_UNCORRELATED_SHARE - (1.0 - rho * rho).sqrt()).abs() < 1e-6);
}

/// An intruder less than 360 ft above the ground gets no advisory: own at
/// 1100 ft AGL (SL 3), intruder reporting 300 ft, closing at 1 km; at
/// 400 ft it gets a TA (700 ft below: inside the TA's 850 ft, outside the
/// RA's 600 ft).
#[test]
fn intruder_on_the_ground_gets_no_advisory() {
    let cycle = cycle_at::<f64>(1100.0);
    assert_eq!(cycle.params().level, SensitivityLevel::Sl3);
    let mut s = ThreatState::new();
    let a = s
        .assess(
            &cycle,
            &observation(1000.0, -100.0, Some((300.0, 0.0))),
            1.0,
        )
        .unwrap();
    assert!(a.advisory < Advisory::Traffic, "{a:?}");
    let a = s
        .assess(
            &cycle,
            &observation(1000.0, -100.0, Some((400.0, 0.0))),
            1.0,
        )
        .unwrap();
    assert_eq!(a.advisory, Advisory::Traffic);
}

/// Non-altitude-reporting intruders raise TAs only below 15 500 ft
/// (DO-185B `ABOVNMC`); never RAs.
#[test]
fn non_reporting_ta_ceiling() {
    for (own, want) in [
        (15_400.0, Advisory::Traffic),
        (15_600.0, Advisory::ProximateTraffic),
    ] {
        let cycle = cycle_at::<f64>(own);
        let mut s = ThreatState::new();
        let a = s
            .assess(&cycle, &observation(2000.0, -250.0, None), 1.0)
            .unwrap();
        assert_eq!(a.advisory, want, "{own}");
    }
}

// ---------------------------------------------------------------------------
// Resolution
// ---------------------------------------------------------------------------

fn threat<S: Scalar>(z: f64, zd: f64, tau: f64, tau_mod: f64) -> ThreatGeometry<S> {
    ThreatGeometry {
        intruder: AltitudeEstimate {
            altitude_ft: c(z),
            vertical_rate_ft_per_s: c(zd),
        },
        range_tau_s: c(tau),
        modified_tau_s: c(tau_mod),
    }
}

fn own_cycle<S: Scalar>(altitude_ft: f64, rate_ft_per_s: f64) -> Cycle<S> {
    let own = OwnAircraft::over_sea_level(c(altitude_ft), c(rate_ft_per_s));
    CollisionAvoidance::<S>::new()
        .begin_cycle(&own, false)
        .unwrap()
}

/// The head-on of the encounter suite at its RA onset (t = 76 s): intruder
/// level 200 ft above, τ = 24.80 s, τ_mod = 24.17 s (SL 5, ALIM 350 ft).
/// Own response: 5 s delay, 8 ft/s² for 3.125 s (39.06 ft), then 25 ft/s:
/// 39.06 + 25·(24.17 − 8.125) = 440.2 ft at τ_mod, 455.9 ft at τ. Up:
/// 440.2 − 200 = 240.2 ft; down: 200 + 440.2 = 640.2 ft: descend, which
/// does not cross. Strength: staying level leaves 200 ft < ALIM: positive.
fn head_on_sense<S: Scalar>() {
    let cycle = own_cycle::<S>(8000.0, 0.0);
    let mut r = ResolutionState::<S>::new();
    let out = r
        .resolve(&cycle, &[threat(8200.0, 0.0, 24.80, 24.17)], S::ONE)
        .unwrap();
    let ra = out.advisory.unwrap();
    assert_eq!(
        (ra.sense, ra.strength, ra.crossing, ra.corrective),
        (RaSense::Down, RaStrength::Positive, false, true),
        "{}",
        S::NAME
    );
    assert!(close(ra.goal_rate_ft_per_s, -25.0, 1e-5));
}

#[test]
fn sense_and_strength_of_the_head_on() {
    in_every_tcas_type!(head_on_sense);
}

/// A crossing RA: intruder 150 ft above, level; own climbing 3000 ft/min
/// (50 ft/s), τ = τ_mod = 15 s. Up keeps 50 ft/s: +750 ft, 600 ft above.
/// Down: 5 s at 50 ft/s (+250), then 8 ft/s² from 50 to −25 ft/s over
/// 9.375 s (+117.2) and 0.625 s at −25 (−15.6): +351.6 ft, 201.6 ft above
/// the intruder — no ALIM. The better sense crosses and the other does not
/// give ALIM: a crossing climb. Positive (goal 50 ft/s, a kept climb).
#[test]
fn crossing_climb_when_the_other_sense_cannot_give_alim() {
    let cycle = own_cycle::<f64>(8000.0, 50.0);
    let mut r = ResolutionState::new();
    let ra = r
        .resolve(&cycle, &[threat(8150.0, 0.0, 15.0, 15.0)], 1.0)
        .unwrap()
        .advisory
        .unwrap();
    assert_eq!((ra.sense, ra.crossing), (RaSense::Up, true));
    assert!((ra.goal_rate_ft_per_s - 50.0).abs() < 1e-9);
    assert!(!ra.corrective);
}

/// Preventive when staying level already gives ALIM: intruder 800 ft above
/// (τ 20 s): down, and level flight keeps 800 ≥ 350 ft: "don't climb".
/// It strengthens to a descend when the intruder starts down at 30 ft/s
/// (level: 800 − 30·20 = 200 ft < ALIM), and clears of conflict once no
/// threat is left.
#[test]
fn preventive_strengthens_then_clears() {
    let cycle = own_cycle::<f64>(8000.0, 0.0);
    let mut r = ResolutionState::new();
    let ra = r
        .resolve(&cycle, &[threat(8800.0, 0.0, 20.0, 20.0)], 1.0)
        .unwrap()
        .advisory
        .unwrap();
    assert_eq!(
        (ra.sense, ra.strength),
        (RaSense::Down, RaStrength::Preventive)
    );
    assert!(!ra.corrective);
    let ra = r
        .resolve(&cycle, &[threat(8800.0, -30.0, 19.0, 19.0)], 1.0)
        .unwrap()
        .advisory
        .unwrap();
    assert_eq!(
        (ra.sense, ra.strength),
        (RaSense::Down, RaStrength::Positive)
    );
    let out = r.resolve(&cycle, &[], 1.0).unwrap();
    assert!(out.advisory.is_none() && out.clear_of_conflict);
    let out = r.resolve(&cycle, &[], 1.0).unwrap();
    assert!(!out.clear_of_conflict);
}

/// Weakening (booklet: after the response has provided ALIM): a climb RA
/// 12 s old, own now 450 ft above an intruder level below, climbing
/// 25 ft/s, τ 8 s: levelling off (2.5 s delay) keeps ≥ 450 ft ≥ ALIM, so
/// it weakens to level-off. Before 10 s it does not.
#[test]
fn positive_ra_weakens_to_level_off_after_10_s() {
    let mut r = ResolutionState::new();
    let start = own_cycle::<f64>(8000.0, 0.0);
    let ra = r
        .resolve(&start, &[threat(8000.0 - 200.0, 0.0, 24.0, 24.0)], 1.0)
        .unwrap()
        .advisory
        .unwrap();
    assert_eq!((ra.sense, ra.strength), (RaSense::Up, RaStrength::Positive));
    let later = own_cycle::<f64>(8450.0, 25.0);
    let mut strengths = Vec::new();
    for k in 1..=12 {
        let tau = 24.0 - k as f64;
        let ra = r
            .resolve(&later, &[threat(8000.0, 0.0, tau, tau)], 1.0)
            .unwrap()
            .advisory
            .unwrap();
        strengths.push(ra.strength);
    }
    assert!(
        strengths[..9].iter().all(|&s| s == RaStrength::Positive),
        "{strengths:?}"
    );
    assert_eq!(strengths[9], RaStrength::LevelOff);
}

/// Sense reversal (booklet, "Sense Reversal"; DO-185B `reversal_check`):
/// an up RA against an intruder 300 ft below, level (τ 25 s: climb models
/// 761 ft above it, descend 161 ft below), then the intruder climbs at
/// 50 ft/s while the own aircraft stays level (it does not follow). At
/// k = 8 s the intruder is 100 ft (`CROSSTHR`) above own with τ = 17 s:
/// climbing at 1500 ft/min models 8386 − 8950 = −564 ft < ALIM, descending
/// after 2.5 s at 0.35 g models 8950 − 7665 = 1285 ft: the RA reverses to
/// a positive descend, once; at k = 7 (50 ft above) it does not.
fn reversal<S: Scalar>() {
    let cycle = own_cycle::<S>(8000.0, 0.0);
    let mut r = ResolutionState::<S>::new();
    let mut senses = Vec::new();
    for k in 0..20 {
        let tau = 25.0 - k as f64;
        let z = 7700.0 + if k == 0 { 0.0 } else { 50.0 * k as f64 };
        let zd = if k == 0 { 0.0 } else { 50.0 };
        let ra = r
            .resolve(&cycle, &[threat(z, zd, tau, tau)], S::ONE)
            .unwrap()
            .advisory
            .unwrap();
        senses.push((ra.sense, ra.reversed));
        if k == 8 {
            assert_eq!(ra.strength, RaStrength::Positive, "{}", S::NAME);
        }
    }
    assert!(
        senses[..8].iter().all(|&s| s == (RaSense::Up, false)),
        "{}: {senses:?}",
        S::NAME
    );
    assert!(
        senses[8..].iter().all(|&s| s == (RaSense::Down, true)),
        "{}: {senses:?}",
        S::NAME
    );
}

#[test]
fn sense_reverses_once_when_the_intruder_crosses() {
    in_every_tcas_type!(reversal);
}

/// No reversal within 4 s of closest approach (`MINRITIME`): the same
/// intruder already 200 ft above when τ reaches 4 s keeps the up RA.
#[test]
fn no_reversal_within_4_s() {
    let cycle = own_cycle::<f64>(8000.0, 0.0);
    let mut r = ResolutionState::new();
    let ra = r
        .resolve(&cycle, &[threat(7700.0, 0.0, 5.0, 5.0)], 1.0)
        .unwrap()
        .advisory
        .unwrap();
    assert_eq!(ra.sense, RaSense::Up);
    for tau in [4.0, 3.0, 2.0] {
        let ra = r
            .resolve(&cycle, &[threat(8200.0, 50.0, tau, tau)], 1.0)
            .unwrap()
            .advisory
            .unwrap();
        assert_eq!((ra.sense, ra.reversed), (RaSense::Up, false), "τ {tau}");
    }
}

/// Two threats, one 300 ft above and one 600 ft below, both at τ = 20 s:
/// one sense against both. Climb: +336 ft (39.06 + 25·11.875), 36 ft over
/// the upper, 936 ft over the lower: worst 36. Descend: 636 ft under the
/// upper, 264 ft below the lower intruder's altitude: worst −264. Up, and
/// positive (36 < ALIM).
#[test]
fn two_threats_one_sense() {
    let cycle = own_cycle::<f64>(8000.0, 0.0);
    let mut r = ResolutionState::new();
    let ra = r
        .resolve(
            &cycle,
            &[
                threat(8300.0, 0.0, 20.0, 20.0),
                threat(7400.0, 0.0, 20.0, 20.0),
            ],
            1.0,
        )
        .unwrap()
        .advisory
        .unwrap();
    assert_eq!(
        (ra.sense, ra.strength, ra.threats),
        (RaSense::Up, RaStrength::Positive, 2)
    );
}

/// Low-altitude inhibits (DO-185B `NODESLO/HI` 1000/1200 ft, `ZNOINCDESLO/HI`
/// 1450/1650 ft, `ZNO_AURALLO/HI` 400/600 ft): set below the low bound,
/// cleared above the high one.
#[test]
fn low_altitude_inhibits_with_hysteresis() {
    let mut i = LowAltitudeInhibits::new();
    let descend = |i: &mut LowAltitudeInhibits, h: f64| i.update(Some(h), false).descend;
    assert!(!descend(&mut i, 1300.0));
    assert!(!descend(&mut i, 1050.0));
    assert!(descend(&mut i, 990.0));
    assert!(descend(&mut i, 1150.0));
    assert!(!descend(&mut i, 1210.0));
    let x = i.update(Some(1400.0), false);
    assert!(x.increase_descent && !x.aural);
    let x = i.update(Some(350.0), true);
    assert!(x.aural && x.climb && x.descend);
    assert_eq!(i.update::<f64>(None, false), Default::default());
}

/// With descend RAs inhibited, an intruder above gets no descend: the down
/// sense only offers a level-off, so the RA climbs (crossing) when that is
/// the better separation.
#[test]
fn descend_inhibit_removes_descend_ras() {
    let own = OwnAircraft {
        pressure_altitude_ft: 1050.0,
        vertical_rate_ft_per_s: 0.0,
        radio_altitude_ft: Some(990.0),
    };
    let mut cas = CollisionAvoidance::<f64>::new();
    // 990 ft AGL is SL 2 (no RAs): use 1150 ft AGL (SL 3 from 1100 ft)
    // with the inhibit set on the way down (cleared only above 1200 ft).
    cas.begin_cycle(&own, false).unwrap();
    let own = OwnAircraft {
        radio_altitude_ft: Some(1150.0),
        ..own
    };
    let cycle = cas.begin_cycle(&own, false).unwrap();
    assert!(cycle.inhibits().descend);
    assert_eq!(cycle.params().level, SensitivityLevel::Sl3);
    let out = cas
        .resolve(&cycle, &[threat(1150.0, 0.0, 12.0, 12.0)], 1.0)
        .unwrap();
    let ra = out.advisory.unwrap();
    assert!(
        ra.sense == RaSense::Up || ra.strength <= RaStrength::LevelOff,
        "{ra:?}"
    );
}

// ---------------------------------------------------------------------------
// Sensitivity level hysteresis
// ---------------------------------------------------------------------------

/// Climbing through 5000 ft: SL 4 until 5500 ft (DO-185B `ZSL4TO5`), then
/// SL 5 until back under 4500 ft (`ZSL5TO4`); the ALIM layer likewise
/// (350 ft from 5500 ft, 300 ft again at 4500 ft).
#[test]
fn sensitivity_level_hysteresis() {
    let mut sel = SensitivitySelector::new();
    let at = |sel: &mut SensitivitySelector, h: f64| {
        let p = sel
            .select(&OwnAircraft::<f64>::over_sea_level(h, 0.0))
            .unwrap();
        (p.level.number(), p.alim_ft.unwrap())
    };
    assert_eq!(at(&mut sel, 4000.0), (4, 300.0));
    assert_eq!(at(&mut sel, 5200.0), (4, 300.0));
    assert_eq!(at(&mut sel, 5500.0), (5, 350.0));
    assert_eq!(at(&mut sel, 4600.0), (5, 350.0));
    assert_eq!(at(&mut sel, 4500.0), (4, 300.0));
    // A jump from 4500 to 25 000 ft moves up level by level in one call.
    assert_eq!(at(&mut sel, 25_000.0), (7, 600.0));
    // Radio altitude governs SL 2–3: 1050 ft AGL after 1200 is SL 3; down
    // to 900 is SL 2 (no ALIM).
    let mut sel = SensitivitySelector::new();
    let own = |h: f64| OwnAircraft::<f64>::over_sea_level(h, 0.0);
    assert_eq!(
        sel.select(&own(1200.0)).unwrap().level,
        SensitivityLevel::Sl3
    );
    assert_eq!(
        sel.select(&own(950.0)).unwrap().level,
        SensitivityLevel::Sl3
    );
    assert_eq!(
        sel.select(&own(900.0)).unwrap().level,
        SensitivityLevel::Sl2
    );
    assert_eq!(
        sel.select(&own(1050.0)).unwrap().level,
        SensitivityLevel::Sl2
    );
    assert_eq!(
        sel.select(&own(1100.0)).unwrap().level,
        SensitivityLevel::Sl3
    );
}
