//! The Monte Carlo runner on rayon: the results of a seed are the same, bit
//! for bit, whatever the number of threads (each run depends only on its
//! own seed, and the indexed collect keeps run order).

use abtrack_host_tests::experiments::monte_carlo::{run, Experiment, Method};

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
