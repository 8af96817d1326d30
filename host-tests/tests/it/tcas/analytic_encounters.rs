//! Analytic encounters through `abtrack::tcas::assess`, in f64, f32 and
//! Q32.32: when the traffic and resolution advisories start and stop, with
//! the boundaries solved by hand.

use abtrack::filter::altitude::{
    AltitudeEstimate, AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig,
};
use abtrack::filter::range_azimuth::{RangeAzimuthFilter, RangeAzimuthNoise};
use abtrack::tcas::{
    assess, Advisory, Intruder, OwnAircraft, SensitivityLevel, ThreatAssessment,
    METRES_PER_NAUTICAL_MILE, METRES_PER_SECOND_PER_KNOT,
};
use abtrack::{Fix, Scalar, ScaledScalar};

const NM: f64 = METRES_PER_NAUTICAL_MILE;
const KT: f64 = METRES_PER_SECOND_PER_KNOT;

/// Own aircraft level at `own_alt` ft; intruder at relative position `p` (m)
/// with relative velocity `v` (m/s), and altitude/vertical rate (ft, ft/s)
/// if it reports one.
fn assess_at<S: Scalar>(
    own_alt: f64,
    p: [f64; 2],
    v: [f64; 2],
    alt: Option<(f64, f64)>,
) -> ThreatAssessment<S> {
    let c = |x: f64| S::from_f64_lossy(x);
    let own = OwnAircraft::over_sea_level(c(own_alt), S::ZERO);
    let intruder = Intruder {
        relative_position_m: [c(p[0]), c(p[1])],
        relative_velocity_m_per_s: [c(v[0]), c(v[1])],
        altitude: alt.map(|(a, r)| AltitudeEstimate {
            altitude_ft: c(a),
            vertical_rate_ft_per_s: c(r),
        }),
    };
    assess(&own, &intruder).unwrap()
}

// Head-on at 600 kt closure, same altitude, own altitude 8000 ft (SL 5:
// TA tau 40 s, DMOD 0.75 NM; RA tau 25 s, DMOD 0.55 NM). With the closure
// c = 600 kt = 1/6 NM/s, τ_mod = (r² − DMOD²)/(r c) = TAU is the quadratic
// r² − TAU·c·r − DMOD² = 0, r = (TAU·c + √((TAU·c)² + 4 DMOD²))/2:
//   TA: TAU·c = 40/6 = 20/3 NM, (20/3)² + 4·0.5625 = 400/9 + 20.25/9
//       = 420.25/9, √ = 20.5/3; r = (20/3 + 20.5/3)/2 = 40.5/6 = 6.75 NM.
//   RA: TAU·c = 25/6 = 4.166 667 NM, (25/6)² + 4·0.3025 = 17.361 111 + 1.21
//       = 18.571 111, √ = 4.309 421; r = (4.166 667 + 4.309 421)/2
//       = 4.238 044 NM.
const TA_START_NM: f64 = 6.75;
const RA_START_NM: f64 = 4.238_044;

fn head_on<S: Scalar>(r: f64, alt: Option<(f64, f64)>) -> ThreatAssessment<S> {
    assess_at::<S>(8000.0, [0.0, r], [0.0, -600.0 * KT], alt)
}

fn head_on_boundaries<S: Scalar>() {
    let same = Some((8000.0, 0.0));
    let a = head_on::<S>(TA_START_NM * NM, same);
    assert_eq!(a.sensitivity, SensitivityLevel::Sl5);
    assert!(
        (a.ta_modified_tau_s.unwrap().to_f64() - 40.0).abs() < 1e-4,
        "{a:?}"
    );
    // One metre either side of each boundary (3.2 ms of closure).
    assert_eq!(
        head_on::<S>(TA_START_NM * NM + 1.0, same).advisory,
        Advisory::None
    );
    assert_eq!(
        head_on::<S>(TA_START_NM * NM - 1.0, same).advisory,
        Advisory::Traffic
    );
    let a = head_on::<S>(RA_START_NM * NM, same);
    assert!(
        (a.ra_modified_tau_s.unwrap().to_f64() - 25.0).abs() < 1e-4,
        "{a:?}"
    );
    assert_eq!(
        head_on::<S>(RA_START_NM * NM + 1.0, same).advisory,
        Advisory::Traffic
    );
    assert_eq!(
        head_on::<S>(RA_START_NM * NM - 1.0, same).advisory,
        Advisory::Resolution
    );
    // Stepping the encounter every 10 ms from 8 NM: the first TA and RA fall
    // within one step (3.09 m) inside the boundaries. (The 750th step lands
    // on 6.75 NM itself, where τ_mod = TAU exactly and rounding decides.)
    let step = 0.01;
    let closure = 600.0 * KT;
    let (mut first_ta, mut first_ra) = (None, None);
    for k in 0..20_000 {
        let r = 8.0 * NM - closure * step * k as f64;
        if r < 0.0 {
            break;
        }
        let adv = head_on::<S>(r, same).advisory;
        if adv >= Advisory::Traffic && first_ta.is_none() {
            first_ta = Some(r);
        }
        if adv == Advisory::Resolution && first_ra.is_none() {
            first_ra = Some(r);
        }
    }
    for (first, boundary) in [(first_ta, TA_START_NM * NM), (first_ra, RA_START_NM * NM)] {
        let first = first.unwrap();
        assert!(
            first <= boundary + 1e-6 && first >= boundary - closure * step - 1e-6,
            "{}: {first} vs {boundary}",
            S::NAME
        );
    }
    // Head-on: t_cpa = r/closure, d_cpa = 0.
    let cpa = head_on::<S>(6.0 * NM, same).closest_approach.unwrap();
    assert!((cpa.time_s.to_f64() - 6.0 * NM / closure).abs() < 1e-3);
    assert!(cpa.distance_m.to_f64().abs() < 1e-2);
}

#[test]
fn head_on_600_kt_at_8000_ft_alerts_at_6_75_and_4_238_nm() {
    in_every_tcas_type!(head_on_boundaries);
}

fn non_reporting<S: Scalar>() {
    // The same head-on without an altitude: the TA starts at the same range
    // (no vertical test), an RA never comes, down to 0.05 NM.
    assert_eq!(
        head_on::<S>(TA_START_NM * NM + 1.0, None).advisory,
        Advisory::None
    );
    assert_eq!(
        head_on::<S>(TA_START_NM * NM - 1.0, None).advisory,
        Advisory::Traffic
    );
    for r in [4.0, 2.0, 1.0, 0.5, 0.05] {
        let a = head_on::<S>(r * NM, None);
        assert_eq!(a.advisory, Advisory::Traffic, "{}: {r} NM", S::NAME);
        assert!(a.vertical.is_none());
    }
    // Within 6 NM but not closing: proximate (its altitude is unknown).
    let a = assess_at::<S>(8000.0, [0.0, 5.0 * NM], [0.0, 100.0], None);
    assert_eq!(a.advisory, Advisory::ProximateTraffic);
}

#[test]
fn non_reporting_intruder_raises_at_most_a_traffic_advisory() {
    in_every_tcas_type!(non_reporting);
}

// Crossing 1 NM abeam: from (−6 NM, 1 NM) at 360 kt = 0.1 NM/s east, same
// altitude, SL 5. With s = 6 − 0.1 t the along-track distance to CPA,
// r² = s² + 1, r ṙ = −0.1 s, so τ_mod = (s² + 1 − DMOD²)/(0.1 s):
//   TA (0.75 NM): s² − 4 s + 0.4375 = 0, s = 2 ± √3.5625 = 2 ± 1.887 459:
//       TA from s = 3.887 459 (t = 21.1254 s) to s = 0.112 541 (t = 58.8746 s).
//   RA (0.55 NM): the range test passes from s = 2.180 054 (t = 38.1995 s)
//       to s = 0.319 946 (t = 56.8005 s), but the miss distance, 1 NM =
//       6076 ft, exceeds SL 5's HMD threshold of 3342 ft (DAIDALUS
//       `RA_HMD`): the HMD filter removes it, so no RA (before,
//       this pass raised an RA).
// Near CPA the closure falls under 10 ft/s only for s < 0.0165 NM, where the
// floored τ_mod ≈ 0.56/0.001 646 = 340 s: no alert. After CPA the range
// opens from 1 NM, outside both DMODs: no alert, proximate until r > 6 NM.
// CPA: t = 60 s, d = 1 NM.
fn crossing<S: Scalar>() {
    let at = |t: f64| {
        assess_at::<S>(
            8000.0,
            [-6.0 * NM + 360.0 * KT * t, 1.0 * NM],
            [360.0 * KT, 0.0],
            Some((8000.0, 0.0)),
        )
    };
    let cpa = at(0.0).closest_approach.unwrap();
    assert!((cpa.time_s.to_f64() - 60.0).abs() < 1e-4, "{cpa:?}");
    assert!((cpa.distance_m.to_f64() - NM).abs() < 1e-3, "{cpa:?}");
    let step = 0.001;
    let mut ta = (None, None);
    let mut ra = (None, None);
    let mut last = Advisory::None;
    for k in 0..120_000 {
        let t = k as f64 * step;
        let adv = at(t).advisory;
        if adv >= Advisory::Traffic && last < Advisory::Traffic {
            assert!(ta.0.is_none(), "second TA at {t}");
            ta.0 = Some(t);
        }
        if adv < Advisory::Traffic && last >= Advisory::Traffic {
            ta.1 = Some(t);
        }
        if adv == Advisory::Resolution && last != Advisory::Resolution {
            assert!(ra.0.is_none(), "second RA at {t}");
            ra.0 = Some(t);
        }
        if adv != Advisory::Resolution && last == Advisory::Resolution {
            ra.1 = Some(t);
        }
        if t > 60.0 {
            assert!(
                adv <= Advisory::ProximateTraffic,
                "{}: {adv:?} after CPA at {t}",
                S::NAME
            );
        }
        last = adv;
    }
    let within = |got: Option<f64>, want: f64| {
        let got = got.unwrap();
        assert!(
            (got - want).abs() <= step + 1e-9,
            "{}: {got} vs {want}",
            S::NAME
        );
    };
    within(ta.0, 21.1254);
    within(ta.1, 58.8746);
    assert_eq!(ra, (None, None), "{}: RA despite the HMD filter", S::NAME);
    assert!(at(45.0).miss_distance_filtered, "{}", S::NAME);
    // Proximate until 6 NM opening: s = −√35 = −5.916 080, t = 119.1608 s.
    assert_eq!(at(119.15).advisory, Advisory::ProximateTraffic);
    assert_eq!(at(119.17).advisory, Advisory::None);
}

#[test]
fn crossing_with_one_nm_miss_has_the_analytic_timeline() {
    in_every_tcas_type!(crossing);
}

fn diverging<S: Scalar>() {
    // From 2 NM opening at 300 kt, same altitude: never a TA or RA;
    // proximate while within 6 NM (4 NM at 300 kt: 48 s).
    for k in 0..=600 {
        let t = k as f64 * 0.1;
        let a = assess_at::<S>(
            8000.0,
            [0.0, 2.0 * NM + 300.0 * KT * t],
            [0.0, 300.0 * KT],
            Some((8000.0, 0.0)),
        );
        assert!(a.range_tau_s.is_none() && a.ta_modified_tau_s.is_none());
        let expected = if t < 47.99 {
            Advisory::ProximateTraffic
        } else if t > 48.01 {
            Advisory::None
        } else {
            a.advisory
        };
        assert_eq!(a.advisory, expected, "{}: t = {t}", S::NAME);
    }
    // Within 10 ft/s (3.048 m/s) of zero the range rate counts as closing
    // at 10 ft/s (DO-185B `RDTHR`), opening or not: 50 m outside the TA DMOD
    // (1389 m), (1439 − 1389²/1439)/3.048 = 98.2627/3.048 = 32.2384 s < 40
    // is a TA at ṙ = −0.5 m/s and at +0.5 m/s; opening at 5 m/s (beyond
    // RDTHR) outside DMOD is not.
    let slow = |rate: f64| assess_at::<S>(8000.0, [0.0, 1439.0], [0.0, rate], Some((8000.0, 0.0)));
    let a = slow(-0.5);
    assert_eq!(a.advisory, Advisory::Traffic);
    assert!(
        (a.ta_modified_tau_s.unwrap().to_f64() - 32.2384).abs() < 1e-3,
        "{a:?}"
    );
    assert_eq!(slow(0.5).advisory, Advisory::Traffic);
    assert_eq!(slow(5.0).advisory, Advisory::ProximateTraffic);
    // The fault: "an RA at 0.5 NM while diverging at 250 m/s". Inside the RA
    // DMOD (0.55 NM) a diverging intruder stays a range hit only while
    // r·ṙ ≤ H1 = 0.00278 NM²/s = 9535 m²/s (DO-185B `H1TBL`, SL 5):
    // 926 m · 250 m/s = 231 500 m²/s is far beyond, so no RA; at 926 m
    // opening at 10 m/s (9260 m²/s ≤ 9535) it still is one.
    let opening =
        |rate: f64| assess_at::<S>(8000.0, [0.0, 0.5 * NM], [0.0, rate], Some((8000.0, 0.0)));
    assert_eq!(opening(250.0).advisory, Advisory::ProximateTraffic);
    assert_eq!(opening(10.0).advisory, Advisory::Resolution);
    assert_eq!(opening(10.5).advisory, Advisory::Traffic);
    // A diverging intruder's true range tau is MINTAU = 0 (DO-185B
    // `range_test`): the vertical test's "τ_v below the true tau" never
    // holds, and its miss distance is h itself. 700 ft above, descending
    // 40 ft/s toward own (τ_v = 17.5 s, below SL 5's level-own 20 s), the
    // range a hit (926 m opening at 10 m/s): |h| = 700 ≥ ZTHR 600, so no RA,
    // a TA.
    let above = assess_at::<S>(8000.0, [0.0, 0.5 * NM], [0.0, 10.0], Some((8700.0, -40.0)));
    assert_eq!(above.advisory, Advisory::Traffic, "{}: {above:?}", S::NAME);
}

#[test]
fn diverging_intruder_never_alerts() {
    in_every_tcas_type!(diverging);
}

fn vertical<S: Scalar>() {
    // Head-on at 3 NM: τ_mod = (3 − 0.3025/3)·6 = 17.395 s < 25 (RA) and
    // (3 − 0.5625/3)·6 = 16.875 s < 40 (TA); the true range tau is 18 s. The
    // horizontal tests pass; the vertical ones decide. Own level, so the RA
    // vertical threshold is SL 5's level-own TVVTT = 20 s (DO-185B), not 25.
    let at = |h: f64, hdot: f64| head_on::<S>(3.0 * NM, Some((8000.0 + h, hdot))).advisory;
    // 1000 ft above, level: outside both ZTHRs, not converging; within
    // ±1200 ft: proximate.
    assert_eq!(at(1000.0, 0.0), Advisory::ProximateTraffic);
    // 2000 ft above, level: nothing.
    assert_eq!(at(2000.0, 0.0), Advisory::None);
    // 1000 ft above descending 25 ft/s: τ_v = 40 s, not < 40 (TA); 26 ft/s:
    // 38.5 s, a TA; > 20 s, no RA.
    assert_eq!(at(1000.0, -25.0), Advisory::ProximateTraffic);
    assert_eq!(at(1000.0, -26.0), Advisory::Traffic);
    // 700 ft above descending 30 ft/s: τ_v = 23.3 s < 25 but not < 20: TA.
    assert_eq!(at(700.0, -30.0), Advisory::Traffic);
    // 650 ft above descending 40 ft/s: τ_v = 16.25 s < 20, and the vertical
    // miss at closest approach is 650 − 40·17.395 = −45.8 ft (at τ_mod) and
    // 650 − 40·18 = −70 ft (at τ): same sign, |−45.8| < ZTHR 600: RA.
    assert_eq!(at(650.0, -40.0), Advisory::Resolution);
    // 500 ft above, level: inside ZTHR and the miss stays 500 < 600: RA.
    assert_eq!(at(500.0, 0.0), Advisory::Resolution);
    // 500 ft above climbing away at 10 ft/s: the miss at τ_mod is
    // 500 + 10·17.395 = 674 ft ≥ 600: no RA, a TA (|h| < 850).
    assert_eq!(at(500.0, 10.0), Advisory::Traffic);
    // 600 ft below, descending away: |h| = 600 is not < ZTHR (DO-185B's
    // strict test) and it is diverging: TA only.
    assert_eq!(at(-600.0, -10.0), Advisory::Traffic);
    // 10 000 ft/min is the most an intruder's rate is believed for an RA
    // (DO-185B `MAXZDINT`): 300 ft above, 170 ft/s down, no RA.
    assert_eq!(at(300.0, -170.0), Advisory::Traffic);
}

#[test]
fn vertical_test_against_zthr_and_vertical_tau() {
    in_every_tcas_type!(vertical);
}

fn through_the_filters<S: Scalar>() -> f64 {
    // Noiseless head-on through the range–azimuth filter and the altitude
    // tracker, 1 s scans from 10 NM: the first TA comes at the first scan
    // inside 6.75 NM (one scan closes 308.67 m).
    let c = |x: f64| S::from_f64_lossy(x);
    let noise = RangeAzimuthNoise::<S>::paper_bearing_f64(225.0, 1.0).unwrap();
    let mut track = RangeAzimuthFilter::new(noise);
    let mut alt = AltitudeTracker::<S>::new(
        AltitudeTrackerConfig::<S>::default_for(AltitudeQuantum::ModeC).unwrap(),
    );
    let own = OwnAircraft::over_sea_level(c(8000.0), S::ZERO);
    let closure = 600.0 * KT;
    for k in 0..200 {
        let r = 10.0 * NM - closure * k as f64;
        track.update(c(r), c(0.0), S::ONE).unwrap();
        alt.scan(Some(c(8000.0)), S::ONE).unwrap();
        if k < 2 {
            continue;
        }
        let a = assess(&own, &Intruder::from_track(&track, alt.estimate())).unwrap();
        if a.advisory >= Advisory::Traffic {
            return r;
        }
    }
    panic!("no TA");
}

#[test]
fn tracks_from_the_filters_alert_on_the_first_scan_inside_the_boundary() {
    for r in [
        through_the_filters::<f64>(),
        through_the_filters::<f32>(),
        through_the_filters::<Fix>(),
        through_the_filters::<ScaledScalar>(),
    ] {
        assert!(
            r <= TA_START_NM * NM && r > TA_START_NM * NM - 600.0 * KT,
            "{r}"
        );
    }
}

/// The assessment's taus follow the threat logic's one definition of
/// diverging (DO-185B `RDTHR`, ṙ > 10 ft/s): an intruder opening slower
/// than that has the taus of a closure at the floor, as the public
/// `range_tau` and `modified_tau` give them; a faster one has none. At
/// 3 NM, 8000 ft (SL 5: TA DMOD 0.75 NM), abeam, opening at `rate`.
fn taus_of_a_slowly_opening_intruder<S: Scalar>() {
    let r = 3.0 * NM;
    for (rate, has_taus) in [(1.0, true), (3.0, true), (3.2, false), (20.0, false)] {
        let a = assess_at::<S>(8000.0, [r, 0.0], [rate, 0.0], Some((8000.0, 0.0)));
        let c = |x: f64| S::from_f64_lossy(x);
        let range_tau = abtrack::tcas::range_tau(c(r), c(rate)).unwrap();
        let ta_tau = abtrack::tcas::modified_tau(c(r), c(rate), c(0.75 * NM)).unwrap();
        assert_eq!(range_tau.is_some(), has_taus, "{}: {rate}", S::NAME);
        assert_eq!(a.range_tau_s.is_some(), has_taus, "{}: {rate}", S::NAME);
        assert_eq!(
            a.ta_modified_tau_s.is_some(),
            has_taus,
            "{}: {rate}",
            S::NAME
        );
        let near = |got: Option<S>, want: Option<S>| match (got, want) {
            (Some(g), Some(w)) => (g.to_f64() - w.to_f64()).abs() <= 1e-6 * w.to_f64().abs() + 1e-3,
            (g, w) => g.is_none() && w.is_none(),
        };
        assert!(near(a.range_tau_s, range_tau), "{}: {rate}", S::NAME);
        assert!(near(a.ta_modified_tau_s, ta_tau), "{}: {rate}", S::NAME);
    }
}

#[test]
fn a_slowly_opening_intruder_has_the_taus_of_the_closure_floor() {
    in_every_tcas_type!(taus_of_a_slowly_opening_intruder);
}
