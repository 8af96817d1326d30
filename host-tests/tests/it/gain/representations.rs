//! Every schedule driving the αβ filter in f32, Q32.32 and the fast fixed
//! point (`Fixed32`) stays within the
//! representation bound of the same schedule in f64
//! ([`support::representation_bound`]), on the papers' scenarios, and
//! takes the same discrete decisions (the gains agree to rounding).

use super::support;

use abtrack::bank::BankOutcome;
use abtrack::bank::{BankConfig, CartesianBank};
use abtrack::{Fix, Fixed32, Numeric};
use support::{li_maneuver, liu_turn, representation_bound, run_scheduled, ALL_SCHEDULES};

/// Largest |coordinate| of the run: the scale of the rounding budget.
fn scale(meas: &[[f64; 2]]) -> f64 {
    meas.iter()
        .flat_map(|z| z.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Gains agree when they differ by less than any discrete choice would make
/// them: M3/M4 grid steps are ≥ 0.05, Liu's two branches and the TCAS
/// entries differ by ≥ 0.06, and a scan count off by one changes α by
/// 4/k² > 1e-3 up to k = 63 (the scenarios have ≤ 100 scans, and a later
/// count slip would show in the positions). Continuous gains may differ by
/// more than rounding the formula: Liu's residual α follows innovations
/// that differ by the representations' position error (mm at 17 km in f32,
/// moving α by ≈ 1e-5).
const GAIN_AGREEMENT: f64 = 1e-3;

/// Runs `spec` in `S` and in f64 and compares step by step. Returns the
/// largest position error seen, and its ratio to the bound.
fn compare<S: Numeric>(spec: &str, meas: &[[f64; 2]], dt: f64) -> (f64, f64) {
    let reference = run_scheduled::<f64>(spec, meas, dt);
    let other = run_scheduled::<S>(spec, meas, dt);
    let scale = scale(meas);
    let mut worst = (0.0f64, 0.0f64);
    for (k, (r, o)) in reference.iter().zip(&other).enumerate() {
        match (r.gains, o.gains) {
            (Some(gr), Some(go)) => {
                for axis in 0..2 {
                    let (ar, br) = gr[axis];
                    let (ao, bo) = go[axis];
                    assert!(
                        (ar - ao).abs() <= GAIN_AGREEMENT && (br - bo).abs() <= GAIN_AGREEMENT,
                        "{spec} in {}: gains differ at step {k} axis {axis}: f64 ({ar}, {br}) vs ({ao}, {bo})",
                        S::NAME
                    );
                }
            }
            (None, None) => {}
            _ => panic!(
                "{spec} in {}: gains present in one run only at step {k}",
                S::NAME
            ),
        }
        let bound = representation_bound(S::NAME, scale, k + 1);
        for axis in 0..2 {
            let err = (r.position[axis] - o.position[axis]).abs();
            assert!(
                err <= bound,
                "{spec} in {}: position error {err} > bound {bound} at step {k} axis {axis}",
                S::NAME
            );
            // The velocity correction is (β/T)·e with β < 2 (stability
            // triangle), so a position-sized error reaches the velocity
            // multiplied by at most 2/T.
            let verr = (r.velocity[axis] - o.velocity[axis]).abs();
            assert!(
                verr <= bound * 2.0 / dt,
                "{spec} in {}: velocity error {verr} > bound {} at step {k} axis {axis}",
                S::NAME,
                bound * 2.0 / dt
            );
            if err > worst.0 {
                worst.0 = err;
            }
            worst.1 = worst.1.max(err / bound);
        }
    }
    worst
}

fn scenarios() -> Vec<(&'static str, Vec<[f64; 2]>, f64)> {
    let mut v = Vec::new();
    for seed in [1, 2, 3] {
        let (_, m, dt) = liu_turn(seed);
        v.push(("liu-turn", m, dt));
        let (_, m, dt) = li_maneuver(seed);
        v.push(("li-maneuver", m, dt));
    }
    v
}

fn all_schedules<S: Numeric>() {
    for spec in ALL_SCHEDULES {
        for (name, meas, dt) in scenarios() {
            let (err, ratio) = compare::<S>(spec, &meas, dt);
            println!(
                "{:<50} {:<12} {:<5} max |Δx| = {err:.3e} m ({:.1}% of bound)",
                spec,
                name,
                S::NAME,
                100.0 * ratio
            );
        }
    }
}

#[test]
fn schedules_f32_within_bound_of_f64() {
    all_schedules::<f32>();
}

#[test]
fn schedules_q32_within_bound_of_f64() {
    all_schedules::<Fix>();
}

#[test]
fn schedules_fast_fixed_within_bound_of_f64() {
    all_schedules::<Fixed32>();
}

/// One bank step, per axis: the selected member, and every member's
/// position and |innovation|.
struct BankStep {
    selected: [usize; 2],
    positions: [[f64; 8]; 2],
    innovations: [[f64; 8]; 2],
}

fn run_bank<S: Numeric>(meas: &[[f64; 2]], dt: f64) -> Vec<BankStep> {
    use abtrack::num::Quantity;
    let mut bank = CartesianBank::<S, 8, 2>::from_config(&BankConfig::DEFAULT).unwrap();
    let dt = S::Interval::try_from_f64(dt).unwrap();
    meas.iter()
        .map(|z| {
            let z = z.map(|x| S::Length::try_from_f64(x).unwrap());
            let out = bank.update(z, dt).unwrap();
            let mut step = BankStep {
                selected: out.map(|o| match o {
                    BankOutcome::Filtered(s) => s.member,
                    _ => usize::MAX,
                }),
                positions: [[0.0; 8]; 2],
                innovations: [[0.0; 8]; 2],
            };
            for (axis, b) in bank.axes().iter().enumerate() {
                for k in 0..b.len() {
                    let m = b.member(k).unwrap();
                    step.positions[axis][k] = m.position().to_f64();
                    step.innovations[axis][k] = m
                        .last_innovation()
                        .map_or(0.0, |i| i.residual.to_f64().abs());
                }
            }
            step
        })
        .collect()
}

/// Every member of the bank stays within the bound of its f64 twin; the
/// selection may differ only where the two candidates' |innovations| are
/// closer in f64 than the rounding budget can tell apart (each innovation
/// is a measurement minus a member's prediction, both within the bound).
fn bank_within_bound<S: Numeric>() {
    for (name, meas, dt) in scenarios() {
        let reference = run_bank::<f64>(&meas, dt);
        let other = run_bank::<S>(&meas, dt);
        let scale = scale(&meas);
        let mut worst = 0.0f64;
        let mut near_ties = 0;
        for (k, (r, o)) in reference.iter().zip(&other).enumerate() {
            let bound = representation_bound(S::NAME, scale, k + 1);
            for axis in 0..2 {
                for m in 0..8 {
                    let err = (r.positions[axis][m] - o.positions[axis][m]).abs();
                    assert!(
                        err <= bound,
                        "bank member {m} on {name} in {}: {err} > {bound} at {k}",
                        S::NAME
                    );
                    worst = worst.max(err);
                }
                let (sr, so) = (r.selected[axis], o.selected[axis]);
                if sr != so {
                    let gap = (r.innovations[axis][sr] - r.innovations[axis][so]).abs();
                    assert!(
                        gap <= 2.0 * bound,
                        "bank on {name} in {}: selection {so} instead of {sr} at step {k} axis {axis}, \
                         f64 |innovation| gap {gap} > 2·bound {}",
                        S::NAME,
                        2.0 * bound
                    );
                    near_ties += 1;
                }
            }
        }
        println!(
            "bank:k=8 {name:<12} {:<5} max member |Δx| = {worst:.3e} m, {near_ties} near-tie selections",
            S::NAME
        );
    }
}

#[test]
fn bank_f32_within_bound_of_f64() {
    bank_within_bound::<f32>();
}

#[test]
fn bank_q32_within_bound_of_f64() {
    bank_within_bound::<Fix>();
}

#[test]
fn bank_fast_fixed_within_bound_of_f64() {
    bank_within_bound::<Fixed32>();
}
