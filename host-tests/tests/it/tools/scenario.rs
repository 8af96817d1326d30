//! The simulated scenarios (src/scenario.rs): trajectories, detection,
//! clutter and the papers' scenario definitions.

use abtrack_host_tests::scenario::*;
use std::f64::consts::{FRAC_PI_4, PI, TAU};

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn every_listed_scenario_generates() {
    for name in SCENARIO_NAMES {
        let run = generate(name, 1).unwrap();
        assert_eq!(run.info.name, *name);
        assert_eq!(run.scans.len(), run.info.scans);
        assert!(run.measurements().count() > 0);
    }
    assert_eq!(scenarios().len(), SCENARIO_NAMES.len());
    assert!(matches!(
        generate("nope", 1),
        Err(ScenarioError::Unknown(_))
    ));
}

#[test]
fn li_maneuver_final_state_matches_the_hand_integration() {
    // x: vx = 10 on [0,11) → 110; a = 2 on [11,16): 10·5 + ½·2·25 = 75 → 185,
    // vx = 20; [16,81): 20·65 = 1300 → 1485; a = −1.5 on [81,86):
    // 20·5 − ½·1.5·25 = 81.25 → 1566.25, vx = 12.5; [86,99]: 12.5·13 =
    // 162.5 → 1728.75.
    // y: vy = 5 on [0,31) → 155; a = 2 on [31,36): 5·5 + 25 = 50 → 205,
    // vy = 15; [36,52): 15·16 = 240 → 445; a = −1.5 on [52,73) (21 s):
    // 15·21 − ½·1.5·441 = −15.75 → 429.25, vy = −16.5; [73,99]:
    // −16.5·26 = −429 → 0.25.
    let truth = truth("li-maneuver").unwrap();
    assert_eq!(truth.len(), 100);
    let first = truth[0][0];
    assert_eq!(
        (first.t, first.x, first.y, first.vx, first.vy),
        (0.0, 0.0, 0.0, 10.0, 5.0)
    );
    let last = truth[99][0];
    assert_eq!(last.t, 99.0);
    assert!(close(last.x, 1728.75, 1e-9), "{last:?}");
    assert!(close(last.y, 0.25, 1e-9), "{last:?}");
    assert!(close(last.vx, 12.5, 1e-12) && close(last.vy, -16.5, 1e-12));
    // Scan 12 (index 11) still has the initial velocity; scan 17 (index
    // 16) has completed the first manoeuvre.
    assert_eq!(truth[11][0].vx, 10.0);
    assert_eq!(truth[12][0].vx, 12.0);
    assert_eq!(truth[16][0].vx, 20.0);
}

#[test]
fn liu_turn_has_the_stated_radius_speed_and_timing() {
    let truth = truth("liu-turn").unwrap();
    assert_eq!(truth.len(), 80);
    let s0 = truth[0][0];
    assert_eq!((s0.x, s0.y), (533.0, 389.0));
    assert!(close(s0.vx, 150.0 / 2f64.sqrt(), 1e-9) && close(s0.vy, s0.vx, 1e-12));
    // Turn centre: R to the left of the velocity at the turn's start
    // (sample 30, t = 60 s).
    let s30 = truth[30][0];
    assert_eq!(s30.t, 60.0);
    assert!(close(s30.x, 533.0 + 60.0 * s0.vx, 1e-9));
    let speed = s30.vx.hypot(s30.vy);
    let centre = [
        s30.x - 9000.0 * s30.vy / speed,
        s30.y + 9000.0 * s30.vx / speed,
    ];
    for s in &truth[30..=45] {
        let r = (s[0].x - centre[0]).hypot(s[0].y - centre[1]);
        assert!(close(r, 9000.0, 1e-6), "radius {r} at t={}", s[0].t);
    }
    for s in &truth {
        assert!(close(s[0].vx.hypot(s[0].vy), 150.0, 1e-9));
    }
    // Heading after the turn: 45° + 0.5 rad (counter-clockwise from +x).
    let s45 = truth[45][0];
    let heading = s45.vy.atan2(s45.vx);
    assert!(close(heading, FRAC_PI_4 + 0.5, 1e-12), "{heading}");
    // Straight afterwards.
    let s79 = truth[79][0];
    assert!(close(s79.vx, s45.vx, 1e-9) && close(s79.vy, s45.vy, 1e-9));
    assert!(close(s79.x, s45.x + 68.0 * s45.vx, 1e-6));
}

#[test]
fn he_tcas_geometry() {
    let truth = truth("he-tcas").unwrap();
    assert_eq!(truth.len(), 500);
    let s0 = truth[0][0];
    assert!(close(s0.range(), 280_000.0, 1e-6));
    assert!(close(s0.azimuth().to_degrees(), 30.0, 1e-9));
    // Own faster by 200 km/h = 55.556 m/s, closing along −y.
    assert!(close(s0.vy, -200.0 / 3.6, 1e-9) && s0.vx == 0.0);
    // ṙ = vy·cos B = −55.556·0.866 = −48.11 m/s.
    assert!(close(
        s0.range_rate().unwrap(),
        -200.0 / 3.6 * 0.75f64.sqrt(),
        1e-9
    ));
    let s = truth[499][0];
    // y = 242487.1 − 55.556·499 = 214764.9; R = √(140000² + y²) = 256366.8.
    let y = 280_000.0 * 0.75f64.sqrt() - 200.0 / 3.6 * 499.0;
    assert!(close(s.range(), 140_000f64.hypot(y), 1e-6));
    assert!(s.azimuth().to_degrees() > 33.0 && s.azimuth().to_degrees() < 33.2);
}

#[test]
fn tcas_converging_cpa_tau_and_altitudes() {
    let run = generate("tcas-converging", 3).unwrap();
    let s0 = run.scans[0].truth[0];
    assert!(close(s0.range(), 14.0 * NAUTICAL_MILE, 1e-6));
    // Closure 500 kt = 257.22 m/s; tau = r/ṙ ≈ y0/v for a small offset:
    // 25926.5 / 257.22 = 100.79 s (r·r/(y·v) = 100.80).
    let tau = s0.tau().unwrap();
    assert!(close(tau, 100.8, 0.05), "tau {tau}");
    let (t_cpa, d_cpa) = closest_approach(s0.x, s0.y, s0.vx, s0.vy);
    assert!(close(d_cpa, 0.2 * NAUTICAL_MILE, 1e-6));
    assert!(close(t_cpa, 100.79, 0.01), "t_cpa {t_cpa}");
    // The sampled truth's minimum range is within one second of CPA.
    let min = run
        .scans
        .iter()
        .map(|s| s.truth[0].range())
        .fold(f64::INFINITY, f64::min);
    // Nearest sample 0.21 s from CPA at 257.2 m/s closure.
    let d = 0.2 * NAUTICAL_MILE;
    assert!((d..d + 0.21 * 257.3).contains(&min), "{min}");
    // Past CPA the range opens: no tau.
    assert!(run.scans[120].truth[0].tau().is_none());
    // Altitude: 7500 + 5·t; reports are multiples of 100 within 50 ft.
    for s in &run.scans {
        let truth_alt = s.truth[0].alt_ft.unwrap();
        assert!(close(truth_alt, 7500.0 + 5.0 * s.t, 1e-9));
        match s.measurements[0] {
            Measurement::Polar {
                alt_ft: Some(a), ..
            } => {
                assert_eq!(a % 100.0, 0.0);
                assert!((a - truth_alt).abs() <= 50.0);
            }
            other => panic!("expected a polar report with altitude, got {other:?}"),
        }
    }
    assert_eq!(run.info.own_altitude_ft, Some(8000.0));
}

#[test]
fn li_noise_has_unit_variance_per_axis() {
    let mut sum = [0.0; 2];
    let mut sum2 = [0.0; 2];
    let mut n = 0.0;
    for seed in 0..100 {
        let run = generate("li-maneuver", seed).unwrap();
        for s in &run.scans {
            let m = s.measurements[0].position();
            let e = [m[0] - s.truth[0].x, m[1] - s.truth[0].y];
            for a in 0..2 {
                sum[a] += e[a];
                sum2[a] += e[a] * e[a];
            }
            n += 1.0;
        }
    }
    for a in 0..2 {
        // n = 10000: mean s.e. 0.01, variance s.e. 0.014.
        assert!((sum[a] / n).abs() < 0.05);
        assert!(close(sum2[a] / n, 1.0, 0.07), "axis {a}: {}", sum2[a] / n);
    }
}

#[test]
fn polar_noise_has_the_stated_range_and_azimuth_sigma() {
    let mut sr = 0.0;
    let mut sb = 0.0;
    let mut n = 0.0;
    for seed in 0..20 {
        let run = generate("he-tcas", seed).unwrap();
        for s in &run.scans {
            if let Measurement::Polar {
                range,
                azimuth,
                alt_ft,
                ..
            } = s.measurements[0]
            {
                assert!(alt_ft.is_none());
                assert!((0.0..TAU).contains(&azimuth));
                let db = (azimuth - s.truth[0].azimuth() + PI).rem_euclid(TAU) - PI;
                sr += (range - s.truth[0].range()).powi(2);
                sb += db * db;
                n += 1.0;
            }
        }
    }
    // n = 10000: relative s.e. of a variance √(2/n) = 1.4 %.
    assert!(close(sr / n, 100.0 * 100.0, 10000.0 * 0.07), "{}", sr / n);
    assert!(
        close(sb / n, HE_AZIMUTH_VARIANCE, HE_AZIMUTH_VARIANCE * 0.07),
        "{}",
        sb / n
    );
}

#[test]
fn coloured_scenario_has_correlated_errors_white_does_not() {
    let lag1 = |name: &str| {
        let mut num = 0.0;
        let mut den = 0.0;
        for seed in 0..20 {
            let run = generate(name, seed).unwrap();
            let e: Vec<f64> = run
                .scans
                .iter()
                .map(|s| s.measurements[0].position()[0] - s.truth[0].x)
                .collect();
            num += e.windows(2).map(|w| w[0] * w[1]).sum::<f64>();
            den += e.iter().map(|x| x * x).sum::<f64>();
        }
        num / den
    };
    let white = lag1("alwagih-cv");
    let coloured = lag1("alwagih-cv-coloured");
    // 3000 samples: s.e. ≈ 0.02 (white), ≈ 0.01·√(1+ρ²)... allow 0.06.
    assert!(white.abs() < 0.06, "white lag-1 {white}");
    assert!(close(coloured, 0.8, 0.06), "coloured lag-1 {coloured}");
}

#[test]
fn multi_target_detection_rate_and_clutter_density() {
    let mut detected = 0usize;
    let mut present = 0usize;
    let mut clutter = 0usize;
    let runs = 20;
    for seed in 0..runs {
        let run = generate("two-crossing", seed).unwrap();
        for s in &run.scans {
            present += s.truth.len();
            assert_eq!(s.measurements.len(), s.origins.len());
            for (m, o) in s.measurements.iter().zip(&s.origins) {
                assert_eq!(m.t(), s.t);
                match o {
                    Some(_) => detected += 1,
                    None => clutter += 1,
                }
            }
        }
    }
    let pd = detected as f64 / present as f64;
    // 2400 opportunities: s.e. √(0.09/2400) = 0.006.
    assert!(close(pd, 0.9, 0.025), "Pd {pd}");
    let per_scan = clutter as f64 / (runs as f64 * 60.0);
    // 1200 Poisson(10) scans: s.e. 0.09.
    assert!(close(per_scan, 10.0, 0.4), "clutter/scan {per_scan}");
    let info = info("two-crossing").unwrap();
    assert!(close(info.clutter.unwrap().density_per_m2(), 1e-7, 1e-20));
}

#[test]
fn multi_target_rows_are_shuffled() {
    // If rows kept truth order, clutter would always come last.
    let run = generate("two-crossing", 9).unwrap();
    let clutter_not_last = run.scans.iter().any(|s| {
        s.origins
            .iter()
            .position(|o| o.is_none())
            .is_some_and(|first_clutter| s.origins[first_clutter..].iter().any(|o| o.is_some()))
    });
    assert!(clutter_not_last);
}

#[test]
fn crossing_and_parallel_geometry() {
    let c = truth("two-crossing").unwrap();
    let at30 = &c[30];
    let run = generate("two-crossing", 0).unwrap();
    let points = run.scans[30].truth_points();
    assert_eq!(points.iter().map(|p| p.id).collect::<Vec<_>>(), vec![1, 2]);
    assert!(points.iter().all(|p| p.x.abs() < 1e-9 && p.y.abs() < 1e-9));
    assert_eq!(at30.len(), 2);
    for s in at30 {
        assert!(close(s.x, 0.0, 1e-9) && close(s.y, 0.0, 1e-9));
    }
    let p = truth("parallel-200m").unwrap();
    for scan in &p {
        assert_eq!(scan.len(), 2);
        assert!(close(scan[1].y - scan[0].y, 200.0, 1e-12));
        assert!(close(scan[1].x, scan[0].x, 1e-12));
    }
}

#[test]
fn dense_fills_the_table_and_tcas30_has_thirty_intruders() {
    let d = truth("dense").unwrap();
    for scan in &d {
        assert_eq!(
            scan.len(),
            DENSE_TABLE_CAPACITY,
            "every target stays inside"
        );
    }
    let t = truth("tcas-30").unwrap();
    assert_eq!(t[0].len(), 30);
    for s in &t[0] {
        assert!(s.range() <= 10.0 * NAUTICAL_MILE + 1e-6 && s.alt_ft.is_some());
    }
    // Mode C: intruders 29 and 30 never report altitude, the others do.
    let run = generate("tcas-30", 5).unwrap();
    for s in &run.scans {
        for (m, o) in s.measurements.iter().zip(&s.origins) {
            if let (Measurement::Polar { alt_ft, .. }, Some(id)) = (m, o) {
                assert_eq!(alt_ft.is_none(), *id >= 29, "intruder {id}");
            }
        }
    }
}

#[test]
fn same_seed_same_run_different_seed_different() {
    for name in SCENARIO_NAMES {
        let a = generate(name, 42).unwrap();
        let b = generate(name, 42).unwrap();
        let c = generate(name, 43).unwrap();
        assert_eq!(a.measurements_csv(), b.measurements_csv());
        assert_eq!(a.truth_csv(), b.truth_csv());
        assert_ne!(a.measurements_csv(), c.measurements_csv());
        assert_eq!(
            a.truth_csv(),
            c.truth_csv(),
            "truth does not depend on the seed"
        );
    }
}

#[test]
fn csv_headers() {
    let h = |n: &str| {
        let run = generate(n, 0).unwrap();
        let m = run.measurements_csv();
        let t = run.truth_csv();
        (
            m.lines().next().unwrap().to_string(),
            t.lines().next().unwrap().to_string(),
        )
    };
    assert_eq!(h("li-maneuver"), ("t,x,y".into(), "t,x,y,vx,vy".into()));
    assert_eq!(
        h("he-tcas"),
        (
            "t,range,azimuth".into(),
            "t,x,y,vx,vy,range,azimuth,range_rate,tau".into()
        )
    );
    assert_eq!(
        h("tcas-converging"),
        (
            "t,range,azimuth,alt".into(),
            "t,x,y,vx,vy,range,azimuth,range_rate,tau,alt,own_alt".into()
        )
    );
    assert_eq!(
        h("two-crossing"),
        ("t,x,y".into(), "t,target,x,y,vx,vy".into())
    );
    assert_eq!(
        h("tcas-30"),
        (
            "t,range,azimuth,alt".into(),
            "t,target,x,y,vx,vy,range,azimuth,range_rate,tau,alt,own_alt".into()
        )
    );
}

#[test]
fn csv_rows_round_trip_and_have_the_header_width() {
    let run = generate("tcas-30", 2).unwrap();
    let csv = run.measurements_csv();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), run.measurements().count());
    for (line, m) in rows.iter().zip(run.measurements()) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 4);
        if let Measurement::Polar {
            t,
            range,
            azimuth,
            alt_ft,
        } = *m
        {
            assert_eq!(f[0].parse::<f64>().unwrap(), t);
            assert_eq!(f[1].parse::<f64>().unwrap(), range);
            assert_eq!(f[2].parse::<f64>().unwrap(), azimuth);
            assert_eq!(f[3].parse::<f64>().ok(), alt_ft);
        }
    }
    let truth = run.truth_csv();
    for line in truth.lines().skip(1) {
        assert_eq!(line.split(',').count(), 12);
    }
    // Scans are in time order.
    let times: Vec<f64> = rows
        .iter()
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]));
}

#[test]
fn li_distance_error_terms() {
    let info = info("li-maneuver").unwrap();
    let (dr, dtheta) = info.noise.range_bearing_errors(500.0).unwrap();
    // Δd/λ = √(Δρ² + ρ²Δθ²) = √(1 + 1) = √2.
    assert!(close(
        (dr * dr + (500.0 * dtheta).powi(2)).sqrt(),
        2f64.sqrt(),
        1e-12
    ));
    let he = info_he();
    assert_eq!(
        he.noise.range_bearing_errors(1.0),
        Some((100.0, HE_AZIMUTH_VARIANCE.sqrt()))
    );
    assert_eq!(info.noise.range_bearing_errors(0.0), None);
}

fn info_he() -> ScenarioInfo {
    info("he-tcas").unwrap()
}

#[test]
fn wrap_and_mode_c() {
    assert_eq!(wrap_two_pi(-1e-300), 0.0);
    assert!(close(wrap_two_pi(-0.1), TAU - 0.1, 1e-15));
    assert!(close(wrap_two_pi(TAU + 0.1), 0.1, 1e-15));
    assert_eq!(mode_c(8049.9), 8000.0);
    assert_eq!(mode_c(8050.1), 8100.0);
    assert_eq!(range_tau(0.0, 1000.0, 0.0, 10.0), None);
    assert_eq!(range_tau(0.0, 1000.0, 0.0, -10.0), Some(100.0));
}
