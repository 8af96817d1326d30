//! The Monte Carlo runner on rayon: the results of a seed are the same, bit
//! for bit, whatever the number of threads (each run depends only on its
//! own seed, and the indexed collect keeps run order).

use abtrack::bank::BankConfig;
use abtrack_host_tests::experiments::monte_carlo::*;
use abtrack_host_tests::metrics::StateError;

fn bits(e: &Experiment) -> Vec<u64> {
    let mut out = Vec::new();
    for m in &e.methods {
        for run in &m.runs {
            for step in run {
                let o = &step.output;
                out.extend(o.position.iter().chain(&o.velocity).map(|v| v.to_bits()));
                out.extend(step.error.position.iter().map(|v| v.to_bits()));
                if let Some(p) = step.prediction_error {
                    out.extend(p.iter().map(|v| v.to_bits()));
                }
            }
        }
    }
    out
}

fn experiment(threads: usize) -> Experiment {
    let methods = vec![
        Method::schedule::<f64>("M2", "least-squares").unwrap(),
        Method::schedule::<f32>("Liu 2.1.5", "liu-adaptive").unwrap(),
    ];
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| run("liu-turn", 0x5eed, 24, &methods))
        .unwrap()
}

#[test]
fn results_are_bit_identical_on_one_and_on_four_threads() {
    let one = experiment(1);
    let four = experiment(4);
    assert_eq!(one.methods[0].runs.len(), 24);
    let (a, b) = (bits(&one), bits(&four));
    assert!(a.len() > 24 * 2 * 70 * 6, "{}", a.len());
    assert!(a == b, "results differ between 1 and 4 threads");
    // And the runs differ from each other (the seeds are used).
    assert_ne!(
        one.methods[0].runs[0][10].output.position,
        one.methods[0].runs[1][10].output.position
    );
}

// The runner's own records and statistics.

fn step(ex: f64, px: Option<f64>) -> StepRecord {
    StepRecord {
        error: StateError {
            position: [ex, 0.0],
            velocity: [0.0, 2.0 * ex],
        },
        prediction_error: px.map(|p| [p, 0.0]),
        output: Output {
            predicted: None,
            position: [0.0; 2],
            velocity: [0.0; 2],
            gains: None,
            innovation: None,
            steady: None,
        },
    }
}

#[test]
fn per_run_rmse_skips_initialisation_and_honours_segments() {
    // Scans 0 and 1 initialise (never scored); scans 2, 3 have errors 3, 4:
    // √((9 + 16)/2) = √12.5. Velocity errors are twice as large.
    let m = MethodResult {
        label: "m".into(),
        detail: String::new(),
        runs: vec![vec![
            step(100.0, None),
            step(100.0, None),
            step(3.0, Some(1.0)),
            step(4.0, Some(7.0)),
        ]],
    };
    let r = m.per_run(Metric::PositionX, ALL_SCANS);
    assert!((r[0] - 12.5f64.sqrt()).abs() < 1e-12);
    assert!((m.per_run(Metric::VelocityY, ALL_SCANS)[0] - 2.0 * 12.5f64.sqrt()).abs() < 1e-12);
    // √((1 + 49)/2) = 5.
    assert!((m.per_run(Metric::PredictionX, ALL_SCANS)[0] - 5.0).abs() < 1e-12);
    let last = Segment {
        name: "last",
        contains: &|k| k == 3,
    };
    assert_eq!(m.per_run(Metric::PositionX, last)[0], 4.0);
    let none = Segment {
        name: "none",
        contains: &|_| false,
    };
    assert!(m.per_run(Metric::PositionX, none)[0].is_nan());
    assert_eq!(m.against_time(Metric::PositionX), vec![(2, 3.0), (3, 4.0)]);
}

#[test]
fn verdict_of_parts() {
    assert_eq!(Verdict::of_parts(&[true, true]), Verdict::Reproduced);
    assert_eq!(Verdict::of_parts(&[true, false]), Verdict::Partly);
    assert_eq!(Verdict::of_parts(&[false, false]), Verdict::NotReproduced);
    assert_eq!(Verdict::of_parts(&[]), Verdict::NotReproduced);
}

/// The printed M5 readout takes, per axis, the member with the least
/// |innovation|, so its |innovation| is never above the causal one's
/// (the member chosen at the previous scan), and both readouts run the
/// same bank.
#[test]
fn bank_readouts_differ_only_in_the_member_read() {
    let mut paper = Bank::new(&BankConfig::DEFAULT, BankReadout::Paper).unwrap();
    let mut causal = Bank::new(&BankConfig::DEFAULT, BankReadout::Causal).unwrap();
    let mut strictly_better = 0;
    for k in 0..60 {
        let t = k as f64;
        // A weave the fixed members follow differently.
        let z = [
            10.0 * t + 30.0 * (0.3 * t).sin(),
            -5.0 * t + 20.0 * (0.2 * t).cos(),
        ];
        let p = paper.step(z, 1.0).unwrap();
        let c = causal.step(z, 1.0).unwrap();
        assert_eq!(p.predicted.is_some(), k >= 2);
        if let (Some(ep), Some(ec)) = (p.innovation, c.innovation) {
            for axis in 0..2 {
                assert!(ep[axis].abs() <= ec[axis].abs() + 1e-12, "scan {k}");
                if ep[axis].abs() < ec[axis].abs() - 1e-9 {
                    strictly_better += 1;
                }
            }
        }
    }
    assert!(strictly_better > 0, "the readouts never differed");
}
