//! The accuracy and tracking metrics (src/metrics.rs): RMSE, confidence
//! intervals, OSPA, track continuity.

use abtrack_host_tests::metrics::*;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn student_t_quantiles() {
    // Table values and known quantiles beyond the table (to 4 digits).
    assert!(close(student_t_975(1), 12.7062, 1e-4));
    assert!(close(student_t_975(10), 2.2281, 1e-4));
    assert!(close(student_t_975(30), 2.0423, 1e-4));
    assert!(close(student_t_975(31), 2.0395, 1e-4));
    assert!(close(student_t_975(40), 2.0211, 1e-4));
    assert!(close(student_t_975(60), 2.0003, 1e-4));
    assert!(close(student_t_975(99), 1.9842, 1e-4));
    assert!(close(student_t_975(120), 1.9799, 1e-4));
    assert!(close(student_t_975(199), 1.9720, 1e-4));
    assert!(close(student_t_975(1_000_000), 1.96, 1e-4));
    assert!(student_t_975(0).is_infinite());
}

#[test]
fn mean_ci_by_hand() {
    // 1..5: mean 3, s² = (4+1+0+1+4)/4 = 2.5, s = 1.58114;
    // half-width = 2.776445·1.58114/√5 = 2.776445·0.707107 = 1.963243.
    let ci = mean_ci95(&[1.0, 2.0, 3.0, 4.0, 5.0]);
    assert_eq!(ci.mean, 3.0);
    assert!(close(ci.std_dev, 2.5f64.sqrt(), 1e-12));
    assert!(close(ci.half_width, 1.963243, 1e-6));
    assert!(close(ci.lower(), 1.036757, 1e-6));
    assert!(mean_ci95(&[2.0]).half_width.is_infinite());
    assert!(mean_ci95(&[]).mean.is_nan());
    // Paired: a − b = [1, 1, 1, 1]: mean 1, zero width.
    let d = paired_difference_ci95(&[2.0, 3.0, 4.0, 5.0], &[1.0, 2.0, 3.0, 4.0]).unwrap();
    assert_eq!((d.mean, d.half_width), (1.0, 0.0));
    assert!(paired_difference_ci95(&[1.0], &[]).is_none());
    let lo = mean_ci95(&[1.0, 1.1, 0.9]);
    let hi = mean_ci95(&[5.0, 5.1, 4.9]);
    assert!(lo.significantly_below(&hi) && !hi.significantly_below(&lo));
}

#[test]
fn rmse_by_hand() {
    // Position x errors 3, 4 → √((9+16)/2) = √12.5; y errors 0, 0;
    // velocity x 1, −1 → 1; y 2, 2 → 2. Distance RMSE √(12.5 + 0).
    let errs = vec![
        StateError::new([3.0, 0.0], [1.0, 2.0], [0.0, 0.0], [0.0, 0.0]),
        StateError::new([4.0, 0.0], [-1.0, 2.0], [0.0, 0.0], [0.0, 0.0]),
    ];
    let r = run_rmse(&errs);
    assert!(close(r.position[0], 12.5f64.sqrt(), 1e-12));
    assert_eq!(r.position[1], 0.0);
    assert_eq!(r.velocity, [1.0, 2.0]);
    assert!(close(r.velocity_distance, 5f64.sqrt(), 1e-12));
    // Two runs: per-run x RMSE √12.5 and 1 (errors [1, 1]).
    let runs = vec![
        errs.clone(),
        vec![StateError::new([1.0, 0.0], [0.0; 2], [0.0; 2], [0.0; 2]); 2],
    ];
    let s = monte_carlo_rmse(&runs);
    assert!(close(
        s.position[0].mean,
        (12.5f64.sqrt() + 1.0) / 2.0,
        1e-12
    ));
    assert_eq!(s.runs, 2);
    // Against time: scan 0 has x errors 3 and 1 → √((9+1)/2) = √5;
    // scan 1: 4 and 1 → √8.5.
    let t = rmse_against_time(&runs);
    assert!(close(t[0].position[0], 5f64.sqrt(), 1e-12));
    assert!(close(t[1].position[0], 8.5f64.sqrt(), 1e-12));
    // Ragged runs: scan 2 exists in one run only.
    let ragged = vec![
        vec![StateError::default(); 3],
        vec![StateError::default(); 2],
    ];
    assert_eq!(rmse_against_time(&ragged).len(), 3);
}

#[test]
fn ospa_by_hand() {
    // X = {(0,0), (10,0)}, Y = {(1,0), (10,2), (50,50)}, c = 20.
    // Optimal: (0,0)–(1,0): 1; (10,0)–(10,2): 2; one unmatched: c.
    // p = 2: √((1 + 4 + 400)/3) = √135 = 11.61895;
    //   localisation √(5/3) = 1.29099, cardinality √(400/3) = 11.54701.
    // p = 1: (1 + 2 + 20)/3 = 7.66667.
    let x = [[0.0, 0.0], [10.0, 0.0]];
    let y = [[1.0, 0.0], [10.0, 2.0], [50.0, 50.0]];
    let o = ospa(&x, &y, 20.0, 2.0).unwrap();
    assert!(close(o.distance, 135f64.sqrt(), 1e-12));
    assert!(close(o.localisation, (5.0f64 / 3.0).sqrt(), 1e-12));
    assert!(close(o.cardinality, (400.0f64 / 3.0).sqrt(), 1e-12));
    assert!(close(
        o.distance.powi(2),
        o.localisation.powi(2) + o.cardinality.powi(2),
        1e-9
    ));
    assert!(close(
        ospa(&x, &y, 20.0, 1.0).unwrap().distance,
        23.0 / 3.0,
        1e-12
    ));
    // Symmetric.
    assert_eq!(ospa(&y, &x, 20.0, 2.0).unwrap(), o);
    // Cut-off per pair: one point each, 100 m apart, c = 20 → 20.
    assert_eq!(
        ospa(&[[0.0, 0.0]], &[[100.0, 0.0]], 20.0, 1.0)
            .unwrap()
            .distance,
        20.0
    );
    // Empty cases.
    assert_eq!(ospa(&[], &[], 20.0, 2.0).unwrap().distance, 0.0);
    assert_eq!(ospa(&x, &[], 20.0, 2.0).unwrap().distance, 20.0);
}

#[test]
fn ospa_uses_the_optimal_not_the_greedy_assignment() {
    // On a line: x1 = 0, x2 = 2.1; y1 = 1, y2 = −2. Distances:
    // x1–y1 1, x1–y2 2, x2–y1 1.1, x2–y2 4.1. Greedy (closest pair first)
    // takes x1–y1 then x2–y2: 5.1. Optimal x1–y2 + x2–y1 = 3.1.
    // p = 1, c = 100: OSPA = 3.1/2 = 1.55.
    let o = ospa(
        &[[0.0, 0.0], [2.1, 0.0]],
        &[[1.0, 0.0], [-2.0, 0.0]],
        100.0,
        1.0,
    )
    .unwrap();
    assert!(close(o.distance, 1.55, 1e-12), "{o:?}");
}

#[test]
fn hungarian_matches_brute_force() {
    use abtrack_host_tests::noise::{rng_from_seed, uniform};
    fn brute(cost: &[Vec<f64>]) -> f64 {
        // rows ≤ cols: try every injective map.
        fn rec(cost: &[Vec<f64>], i: usize, used: &mut Vec<bool>) -> f64 {
            if i == cost.len() {
                return 0.0;
            }
            let mut best = f64::INFINITY;
            for j in 0..used.len() {
                if !used[j] {
                    used[j] = true;
                    best = best.min(cost[i][j] + rec(cost, i + 1, used));
                    used[j] = false;
                }
            }
            best
        }
        rec(cost, 0, &mut vec![false; cost[0].len()])
    }
    let mut rng = rng_from_seed(11);
    for trial in 0..300 {
        let rows = 1 + trial % 5;
        let cols = rows + (trial / 5) % 3;
        let cost: Vec<Vec<f64>> = (0..rows)
            .map(|_| {
                (0..cols)
                    .map(|_| uniform(&mut rng, 0.0, 10.0).floor())
                    .collect()
            })
            .collect();
        let a = assignment(&cost).unwrap();
        let total: f64 = a.iter().enumerate().map(|(i, j)| cost[i][j.unwrap()]).sum();
        assert!(close(total, brute(&cost), 1e-9), "trial {trial}: {cost:?}");
        let mut cols_used: Vec<usize> = a.iter().map(|j| j.unwrap()).collect();
        cols_used.sort();
        cols_used.dedup();
        assert_eq!(cols_used.len(), rows);
        // Transposed shape gives the same total.
        let t: Vec<Vec<f64>> = (0..cols)
            .map(|j| (0..rows).map(|i| cost[i][j]).collect())
            .collect();
        let at = assignment(&t).unwrap();
        let tt: f64 = at
            .iter()
            .enumerate()
            .filter_map(|(j, i)| i.map(|i| t[j][i]))
            .sum();
        assert!(close(tt, total, 1e-9));
        assert_eq!(at.iter().filter(|i| i.is_some()).count(), rows);
    }
    assert!(assignment(&[]).unwrap().is_empty());
}

/// A cost that is not finite is refused, naming it, in either shape (the
/// augmenting-path search never ended on a NaN), and so is a position that
/// is not finite wherever positions are paired, before any clipping at the
/// gate or cut-off could hide it.
#[test]
fn costs_and_positions_that_are_not_finite_are_refused() {
    let nan = vec![vec![1.0, 2.0], vec![3.0, f64::NAN]];
    let e = assignment(&nan).unwrap_err();
    assert_eq!((e.row, e.column), (1, 1));
    assert!(e.value.is_nan());
    assert!(e.to_string().contains("(row 1, column 1) is NaN"), "{e}");
    let tall = vec![vec![1.0], vec![f64::INFINITY], vec![2.0]];
    assert_eq!(
        assignment(&tall).unwrap_err(),
        NonFiniteCost {
            row: 1,
            column: 0,
            value: f64::INFINITY
        }
    );
    assert_eq!(finite_costs(&[vec![0.0, -1.0], vec![f64::MAX]]), Ok(()));
    // OSPA: a NaN position, and a cut-off whose cost overflows.
    assert!(ospa(&[[0.0, 0.0]], &[[f64::NAN, 0.0]], 20.0, 2.0).is_err());
    assert!(ospa(&[[0.0, 0.0]], &[[1.0, 0.0]], f64::INFINITY, 2.0).is_ok());
    assert!(ospa(&[[0.0, 0.0]], &[[1e300, 0.0]], 1e300, 2.0).is_err());
    // Track metrics under both costs, and the identity switches.
    let scans = vec![ScanReport {
        t: 0.0,
        truth: vec![TruthPoint {
            id: 1,
            x: 0.0,
            y: 0.0,
        }],
        tracks: vec![
            tp(7, TrackStatus::Confirmed, 5.0, 0.0),
            tp(8, TrackStatus::Confirmed, f64::NAN, 0.0),
        ],
    }];
    for cost in [PairingCost::Distance, PairingCost::ClippedAtGate] {
        let e = track_metrics_with(&scans, 500.0, cost).unwrap_err();
        assert_eq!((e.row, e.column), (0, 1), "{cost:?}");
    }
    assert!(abtrack_host_tests::tracking::identity_switches(&scans, 500.0).is_err());
    assert!(mean_ospa(&scans, 1000.0, 2.0).is_err());
}

/// The gate drops only the pairs farther apart than it: a track exactly
/// 500 m from its target is paired under either cost, one a metre farther
/// is not.
#[test]
fn a_pair_exactly_at_the_gate_is_paired() {
    let scan = |x: f64| ScanReport {
        t: 0.0,
        truth: vec![TruthPoint {
            id: 1,
            x: 0.0,
            y: 0.0,
        }],
        tracks: vec![tp(3, TrackStatus::Confirmed, x, 0.0)],
    };
    for cost in [PairingCost::Distance, PairingCost::ClippedAtGate] {
        let at = track_metrics_with(&[scan(500.0)], 500.0, cost).unwrap();
        assert_eq!(at.completeness, 1.0, "{cost:?}");
        assert_eq!(at.assigned_rmse, 500.0, "{cost:?}");
        assert!(at.never_paired.is_empty(), "{cost:?}");
        let beyond = track_metrics_with(&[scan(501.0)], 500.0, cost).unwrap();
        assert_eq!(beyond.completeness, 0.0, "{cost:?}");
        assert_eq!(beyond.never_paired.len(), 1, "{cost:?}");
    }
}

fn tp(id: u32, status: TrackStatus, x: f64, y: f64) -> TrackPoint {
    TrackPoint { id, status, x, y }
}

#[test]
fn track_metrics_by_hand() {
    use TrackStatus::*;
    // Targets A (id 1) along y = 0 and B (id 2) along y = 100, x = 10·t.
    // Gate 50 m.
    // t=0: only tentative tracks → nothing tracked.
    // t=1: track 7 (confirmed) on A; nothing on B.
    // t=2: 7 on A, 8 on B; track 9 (confirmed) at (500, 500): never
    //      paired.
    // t=3: ids swap: 8 on A, 7 on B; 9 coasting at (510, 500).
    // t=4: 8 on A; B's track 7 is 80 m off (outside the gate): B not
    //      tracked, track 7 unassigned this scan (but paired: it was
    //      assigned before).
    // t=5: 8 on A, 7 back on B; 9 gone.
    let truth = |t: f64| {
        vec![
            TruthPoint {
                id: 1,
                x: 10.0 * t,
                y: 0.0,
            },
            TruthPoint {
                id: 2,
                x: 10.0 * t,
                y: 100.0,
            },
        ]
    };
    let scans = vec![
        ScanReport {
            t: 0.0,
            truth: truth(0.0),
            tracks: vec![tp(7, Tentative, 0.0, 0.0), tp(8, Tentative, 0.0, 100.0)],
        },
        ScanReport {
            t: 1.0,
            truth: truth(1.0),
            tracks: vec![tp(7, Confirmed, 11.0, 0.0), tp(8, Tentative, 10.0, 100.0)],
        },
        ScanReport {
            t: 2.0,
            truth: truth(2.0),
            tracks: vec![
                tp(7, Confirmed, 20.0, 1.0),
                tp(8, Confirmed, 20.0, 99.0),
                tp(9, Confirmed, 500.0, 500.0),
            ],
        },
        ScanReport {
            t: 3.0,
            truth: truth(3.0),
            tracks: vec![
                tp(8, Confirmed, 30.0, 2.0),
                tp(7, Confirmed, 30.0, 98.0),
                tp(9, Coasting, 510.0, 500.0),
            ],
        },
        ScanReport {
            t: 4.0,
            truth: truth(4.0),
            tracks: vec![tp(8, Confirmed, 40.0, 0.0), tp(7, Coasting, 40.0, 180.0)],
        },
        ScanReport {
            t: 5.0,
            truth: truth(5.0),
            tracks: vec![tp(8, Confirmed, 50.0, 0.0), tp(7, Confirmed, 50.0, 100.0)],
        },
    ];
    let m = track_metrics(&scans, 50.0).unwrap();
    let a = &m.targets[0];
    let b = &m.targets[1];
    assert_eq!((a.target, b.target), (1, 2));
    // A: tracked at t = 1..5 (5 of 6); ids 7,7,8,8,8 → 1 change;
    // latency 1 s.
    assert_eq!((a.scans_present, a.scans_tracked, a.id_changes), (6, 5, 1));
    assert_eq!(a.track_ids, vec![7, 8]);
    assert_eq!(a.latency_to_confirm_s, Some(1.0));
    // B: tracked at t = 2, 3, 5 (3 of 6); ids 8, 7, 7 → 1 change;
    // latency 2 s.
    assert_eq!((b.scans_present, b.scans_tracked, b.id_changes), (6, 3, 1));
    assert_eq!(b.track_ids, vec![8, 7]);
    assert_eq!(b.latency_to_confirm_s, Some(2.0));
    assert!(close(b.completeness, 0.5, 1e-15));
    // Overall completeness (5 + 3)/12; 2 id changes.
    assert!(close(m.completeness, 8.0 / 12.0, 1e-15));
    assert_eq!(m.id_changes, 2);
    // One track never paired: 9, established at t = 2 and 3 → 2 scans, 1 s.
    assert_eq!(
        m.never_paired,
        vec![NeverPairedTrack {
            id: 9,
            first_t: 2.0,
            last_t: 3.0,
            scans: 2
        }]
    );
    assert_eq!(m.never_paired_time(), (2, Some(1.0)));
    // Unassigned established track-scans: 9 at t=2,3 and 7 at t=4.
    assert_eq!(m.unassigned_track_scans, 3);
    assert_eq!(m.established_tracks, 3);
    // Continuity: A tracked 5 of the 5 scans from t = 1, B 3 of the 4
    // from t = 2 → 8/9.
    assert_eq!(
        (
            a.scans_present_since_first_assignment,
            b.scans_present_since_first_assignment
        ),
        (5, 4)
    );
    assert!(close(m.continuity, 8.0 / 9.0, 1e-15));
    // Assigned pairs' distances: t=1: 1; t=2: 1, 1; t=3: 2, 2;
    // t=4: 0 (B's track is beyond the gate); t=5: 0, 0 → √(11/8).
    assert!(close(m.assigned_rmse, (11.0f64 / 8.0).sqrt(), 1e-12));
    // Only 9 is assigned in under half of its established scans (0 of
    // 2); 7 in 4 of 5, 8 in 4 of 4.
    assert_eq!(m.mostly_unassigned_tracks, vec![9]);

    // OSPA at t = 4 (c = 100, p = 1): truth (40,0), (40,100); established
    // tracks (40,0), (40,180): 0 + 80 → 40. At t = 0 no established
    // track: c = 100.
    let o = ospa_against_time(&scans, 100.0, 1.0).unwrap();
    assert!(close(o[4].1.distance, 40.0, 1e-12));
    assert_eq!(o[0].1.distance, 100.0);
}

#[test]
fn a_track_assigned_in_under_half_its_scans_is_counted_not_at_half() {
    use TrackStatus::*;
    // One target at the origin. Track 5 is on it at t = 0, then 600 m
    // away (beyond the 500 m gate) at t = 1 and 2: assigned in 1 of 3
    // scans, so mostly unassigned but not never paired. Track 6 appears
    // at t = 1 on the target (assigned) and is 600 m off at t = 2: 1 of
    // 2, exactly half, not counted. The target: id 5, then 6 → 1 change;
    // tracked at t = 0, 1, not 2 → continuity 2/3.
    let truth = vec![TruthPoint {
        id: 1,
        x: 0.0,
        y: 0.0,
    }];
    let scan = |t: f64, tracks: Vec<TrackPoint>| ScanReport {
        t,
        truth: truth.clone(),
        tracks,
    };
    let scans = vec![
        scan(0.0, vec![tp(5, Confirmed, 3.0, 4.0)]),
        scan(
            1.0,
            vec![tp(5, Coasting, 600.0, 0.0), tp(6, Confirmed, 0.0, 6.0)],
        ),
        scan(
            2.0,
            vec![tp(5, Coasting, 0.0, 600.0), tp(6, Coasting, -600.0, 0.0)],
        ),
    ];
    let m = track_metrics(&scans, 500.0).unwrap();
    assert_eq!(m.mostly_unassigned_tracks, vec![5]);
    assert!(m.never_paired.is_empty());
    assert_eq!(m.id_changes, 1);
    assert!(close(m.completeness, 2.0 / 3.0, 1e-15));
    assert!(close(m.continuity, 2.0 / 3.0, 1e-15));
    // Pairs at 5 m and 6 m: √((25 + 36)/2).
    assert!(close(m.assigned_rmse, 30.5f64.sqrt(), 1e-12));
    // No pair at all: NaN, as the continuity.
    let none = track_metrics(&scans[..1], 1.0).unwrap();
    assert!(none.assigned_rmse.is_nan() && none.continuity.is_nan());
}

#[test]
fn the_unclipped_pairing_lets_a_far_pair_displace_a_near_one() {
    use TrackStatus::*;
    // Targets A (0, 0) and B (300, 0); tracks 1 at (200, 0) and 2 at
    // (10 km, 0); gate 500 m. Σ d: A–1 + B–2 = 200 + 9700 < A–2 + B–1 =
    // 10000 + 100, so A gets track 1 (B–2 is dropped). Clipped:
    // A–1 + B–2 = 200 + 500 > A–2 + B–1 = 500 + 100, so B gets it.
    let scans = vec![ScanReport {
        t: 0.0,
        truth: vec![
            TruthPoint {
                id: 1,
                x: 0.0,
                y: 0.0,
            },
            TruthPoint {
                id: 2,
                x: 300.0,
                y: 0.0,
            },
        ],
        tracks: vec![
            tp(1, Confirmed, 200.0, 0.0),
            tp(2, Confirmed, 10_000.0, 0.0),
        ],
    }];
    let tracked =
        |m: &TrackMetrics| -> Vec<usize> { m.targets.iter().map(|t| t.scans_tracked).collect() };
    let distance = track_metrics_with(&scans, 500.0, PairingCost::Distance).unwrap();
    assert_eq!(tracked(&distance), vec![1, 0]);
    assert!(close(distance.assigned_rmse, 200.0, 1e-12));
    let clipped = track_metrics(&scans, 500.0).unwrap();
    assert_eq!(tracked(&clipped), vec![0, 1]);
    assert!(close(clipped.assigned_rmse, 100.0, 1e-12));
}

#[test]
fn mean_ospa_averages_every_scan() {
    use TrackStatus::*;
    // c = 1000, p = 2. t = 0: one target, no established track (a
    // tentative one does not count) → c. t = 1: a track 50 m off (3-4-5)
    // → 50. t = 2: nothing at all → 0. Mean (1000 + 50 + 0)/3 = 350.
    let target = TruthPoint {
        id: 1,
        x: 0.0,
        y: 0.0,
    };
    let scans = vec![
        ScanReport {
            t: 0.0,
            truth: vec![target],
            tracks: vec![tp(1, Tentative, 0.0, 0.0)],
        },
        ScanReport {
            t: 1.0,
            truth: vec![target],
            tracks: vec![tp(1, Confirmed, 30.0, 40.0)],
        },
        ScanReport {
            t: 2.0,
            truth: vec![],
            tracks: vec![],
        },
    ];
    assert!(close(mean_ospa(&scans, 1000.0, 2.0).unwrap(), 350.0, 1e-9));
}

#[test]
fn a_target_never_tracked_has_no_latency() {
    let scans = vec![ScanReport {
        t: 3.0,
        truth: vec![TruthPoint {
            id: 4,
            x: 0.0,
            y: 0.0,
        }],
        tracks: vec![],
    }];
    let m = track_metrics(&scans, 10.0).unwrap();
    assert_eq!(m.targets[0].latency_to_confirm_s, None);
    assert_eq!(m.completeness, 0.0);
    assert!(m.never_paired.is_empty());
    assert!(track_metrics(&[], 10.0).unwrap().completeness.is_nan());
    assert_eq!("coasting".parse::<TrackStatus>(), Ok(TrackStatus::Coasting));
    assert!("lost".parse::<TrackStatus>().is_err());
}

/// `common_rmse` pairs the two runs' points by scan and target and takes
/// each run's RMSE over those alone.
#[test]
fn common_rmse_takes_the_points_both_runs_paired() {
    use abtrack_host_tests::metrics::{common_rmse, PairedPoint};
    let p = |t: f64, target: u32, distance: f64| PairedPoint {
        t,
        target,
        track: 0,
        distance,
    };
    // Common: (4 s, 1) and (8 s, 2); each run has one point of its own.
    let a = [p(4.0, 1, 3.0), p(8.0, 2, 4.0), p(12.0, 1, 100.0)];
    let b = [p(4.0, 1, 6.0), p(8.0, 2, 8.0), p(4.0, 3, 50.0)];
    let (ra, rb, n) = common_rmse(&a, &b).unwrap();
    assert_eq!(n, 2);
    assert!((ra - (12.5f64).sqrt()).abs() < 1e-12, "{ra}");
    assert!((rb - (50.0f64).sqrt()).abs() < 1e-12, "{rb}");
    assert_eq!(common_rmse(&a[2..], &b[..2]), None);
}

/// `id_changes_after_far_updates` tells a track that took a far plot from
/// one that lost its target while it coasted.
#[test]
fn id_changes_after_far_updates_tells_a_far_update_from_a_coast() {
    let truth = |x: f64| vec![TruthPoint { id: 1, x, y: 0.0 }];
    // The target moves 100 m a scan; track 1 follows it for two scans, then
    // (scan 3) is `status` 800 m away while the target is unpaired, and
    // track 2 has it from scan 4.
    let scans_with = |status: TrackStatus| {
        vec![
            ScanReport {
                t: 4.0,
                truth: truth(0.0),
                tracks: vec![tp(1, TrackStatus::Confirmed, 10.0, 0.0)],
            },
            ScanReport {
                t: 8.0,
                truth: truth(100.0),
                tracks: vec![tp(1, TrackStatus::Confirmed, 110.0, 0.0)],
            },
            ScanReport {
                t: 12.0,
                truth: truth(200.0),
                tracks: vec![tp(1, status, 200.0, 800.0)],
            },
            ScanReport {
                t: 16.0,
                truth: truth(300.0),
                tracks: vec![
                    tp(1, TrackStatus::Coasting, 300.0, 900.0),
                    tp(2, TrackStatus::Confirmed, 310.0, 0.0),
                ],
            },
        ]
    };
    for (status, after_far_update) in [(TrackStatus::Confirmed, 1), (TrackStatus::Coasting, 0)] {
        let scans = scans_with(status);
        let m = track_metrics_with(&scans, 500.0, PairingCost::Distance).unwrap();
        assert_eq!(m.id_changes, 1, "{status:?}");
        assert_eq!(
            id_changes_after_far_updates(&scans, &m.pairs, 500.0),
            after_far_update,
            "{status:?}"
        );
        // Nothing is far within 1 km.
        assert_eq!(id_changes_after_far_updates(&scans, &m.pairs, 1000.0), 0);
    }
    // None counts: the old track coasts away while another track (3) is
    // updated far from the target in the window; or the old track is
    // updated far away and comes back to the target (no identity change).
    // A second target keeps its own track throughout.
    let with_second_target = |mut scans: Vec<ScanReport>| {
        for s in &mut scans {
            s.truth.push(TruthPoint {
                id: 2,
                x: 0.0,
                y: 5000.0,
            });
            s.tracks.push(tp(4, TrackStatus::Confirmed, 0.0, 5010.0));
        }
        scans
    };
    let mut other_track_far = with_second_target(scans_with(TrackStatus::Coasting));
    other_track_far[2]
        .tracks
        .push(tp(3, TrackStatus::Confirmed, 200.0, 900.0));
    let mut comes_back = with_second_target(scans_with(TrackStatus::Confirmed));
    comes_back[3].tracks[0] = tp(1, TrackStatus::Confirmed, 310.0, 0.0);
    comes_back[3].tracks.remove(1);
    for (scans, id_changes) in [(other_track_far, 1), (comes_back, 0)] {
        let m = track_metrics_with(&scans, 500.0, PairingCost::Distance).unwrap();
        assert_eq!(m.id_changes, id_changes);
        assert_eq!(id_changes_after_far_updates(&scans, &m.pairs, 500.0), 0);
    }
    // The window includes the scan of the change: the old track updated far
    // away at 16 s (having coasted at 12 s) counts.
    let mut at_the_change = scans_with(TrackStatus::Coasting);
    at_the_change[3].tracks[0] = tp(1, TrackStatus::Confirmed, 300.0, 900.0);
    let m = track_metrics_with(&at_the_change, 500.0, PairingCost::Distance).unwrap();
    assert_eq!(m.id_changes, 1);
    assert_eq!(
        id_changes_after_far_updates(&at_the_change, &m.pairs, 500.0),
        1
    );
}
