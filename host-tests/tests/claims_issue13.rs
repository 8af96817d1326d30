//! The claims of issue 13's experiments, checked on reduced runs (the full
//! runs: `cd host-tests && cargo run --release --bin experiments -- --only
//! tenne-singh,he-tcas,liu,alwagih`; their numbers are in the groups'
//! `summary.md`).
//!
//! Seeded, so deterministic; the asserted differences are many half-widths
//! of their 95 % intervals from zero at these run counts.

use abtrack_host_tests::experiments::monte_carlo::Verdict;
use abtrack_host_tests::experiments::tenne_singh::{self, Figure2Curve};

/// Monte Carlo runs of the simulated worked example here (the committed
/// results use 200).
const TENNE_SINGH_RUNS: usize = 40;

#[test]
fn tenne_singh_closed_forms_optimiser_and_simulation() {
    let out = tenne_singh::evaluate(TENNE_SINGH_RUNS).unwrap();
    // Fig. 2: every closed form (where the optimum is interior) is the
    // optimiser's optimum.
    for curve in Figure2Curve::ALL {
        let points: Vec<_> = out.figure2.iter().filter(|p| p.curve == curve).collect();
        let with_closed = points.iter().filter(|p| p.closed.is_some()).count();
        assert!(with_closed + 1 >= points.len(), "{curve:?}: {with_closed}");
        for p in points {
            if let Some(d) = p.deviation() {
                assert!(d < 1e-5, "{curve:?} at κ = {}: {d}", p.kappa);
            }
        }
    }
    // The αβγ acceleration optimum: closed form = optimiser; on eq. 34's
    // surface; eq. 35's surface is always worse.
    for r in &out.abc {
        assert!((r.closed.3 - r.numeric.3).abs() <= 1e-9 * r.closed.3);
        assert!(r.on_eq34 <= r.closed.3 * (1.0 + 1e-9));
        assert!(r.on_eq35 > r.closed.3 * (1.0 + 1e-5), "κ = {}", r.kappa);
    }
    // Fig. 1: the interior optimum falls with κ; γ vanishes by κ = 10.
    let interior: Vec<_> = out
        .figure1
        .iter()
        .filter(|r| r.region() == "interior")
        .collect();
    assert!(interior.len() >= 15);
    assert!(interior
        .windows(2)
        .all(|w| w[1].alpha_beta.0 < w[0].alpha_beta.0 && w[1].alpha_beta.1 < w[0].alpha_beta.1));
    assert!(out
        .figure1
        .iter()
        .filter(|r| r.kappa >= 10.0)
        .all(|r| r.alpha_beta_gamma.2 < 1e-9));
    // The worked example, simulated: every prediction within two 95 %
    // half-widths of its simulated mean (at 40 runs a half-width is ≈ 1 %;
    // the committed 200 runs are within 1 %), and every perturbed gain
    // costs more than the optimum (paired 95 % intervals).
    assert_eq!(out.examples.len(), 2);
    for ex in &out.examples {
        for (c, s) in ex.candidates.iter().zip(&ex.simulated) {
            assert!(
                (c.predicted - s.mean).abs() <= 2.0 * s.half_width,
                "κ = {}, {}: predicted {} simulated {s:?}",
                ex.kappa,
                c.label,
                c.predicted
            );
        }
        for (c, d) in ex.candidates.iter().zip(&ex.excess) {
            if let Some(d) = d {
                assert!(d.lower() > 0.0, "κ = {}, {}: {d:?}", ex.kappa, c.label);
            }
        }
        // Benedict–Bordner's best is among the beaten.
        assert!(ex
            .candidates
            .iter()
            .any(|c| c.label.starts_with("Benedict")));
    }
    // The verdicts the summary reports (T8–T9 judge the simulation at the
    // committed run count, see above).
    let verdicts: Vec<(String, Verdict)> = tenne_singh::claims(&out)
        .into_iter()
        .map(|c| (c.id, c.verdict))
        .collect();
    let expected = [
        ("T1", Verdict::Reproduced),
        ("T2", Verdict::Reproduced),
        ("T3", Verdict::Reproduced),
        ("T4", Verdict::Reproduced),
        ("T5", Verdict::Partly),
        ("T6", Verdict::Partly),
        ("T7", Verdict::Partly),
    ];
    for (id, v) in expected {
        assert!(
            verdicts.contains(&(id.to_string(), v)),
            "{id}: {verdicts:?}"
        );
    }
}
