//! Al-Wagih & Abdulla's M5 (Algorithm 3): the bank runs every member on
//! every measurement and takes the prediction with the lowest |innovation|.

use super::support;
use abtrack::num::{Quantity, Real};

use abtrack::bank::{BankConfig, BankOutcome, CartesianBank, ParallelBank};
use abtrack::filter::{AlphaBeta, FilterError, Phase, UpdateOutcome};
use abtrack::gain::{next_reference, robust_gains, ConfigError};
use abtrack::{Fix, Gains, Scalar};
use proptest::prelude::*;
use support::assert_close;

fn two_member_bank<S: Scalar>() -> ParallelBank<S, 4> {
    // α = 0.2 (β = 0.04/1.8 = 0.0222) and α = 0.8 (β = 0.64/1.2 = 0.5333).
    let g = |a: f64| Gains::alpha_beta_f64(a, a * a / (2.0 - a)).unwrap();
    ParallelBank::new(&[g(0.2), g(0.8)]).unwrap()
}

fn selection<S: Scalar>(o: BankOutcome<S>) -> (usize, f64, f64) {
    match o {
        BankOutcome::Filtered(s) => (s.member, s.predicted.to_f64(), s.residual.to_f64()),
        other => panic!("expected a filtered update, got {other:?}"),
    }
}

fn hand_computed<S: Scalar>(tol: f64) {
    let mut bank = two_member_bank::<S>();
    let z = |x: f64| S::from_f64_lossy(x);
    let one = S::ONE;
    // z = 0, 10: two-point initialisation, x = 10, v = 10 in both members.
    assert_eq!(bank.update(z(0.0), one).unwrap(), BankOutcome::FirstPoint);
    assert_eq!(bank.update(z(10.0), one).unwrap(), BankOutcome::SecondPoint);
    // z = 25: both predict 20, e = 5: a tie, the first member wins.
    // Then m0: x = 20 + 0.2·5 = 21, v = 10 + 0.0222·5 = 10.1111;
    //      m1: x = 20 + 0.8·5 = 24, v = 10 + 0.5333·5 = 12.6667.
    let (m, p, e) = selection(bank.update(z(25.0), one).unwrap());
    assert_eq!(m, 0);
    assert_close(p, 20.0, tol, "tie prediction");
    assert_close(e, 5.0, tol, "tie residual");
    // z = 33: m0 predicts 31.1111 (e = 1.8889), m1 36.6667 (e = −3.6667):
    // m0 wins with the smaller |e|.
    let (m, p, e) = selection(bank.update(z(33.0), one).unwrap());
    assert_eq!((m, bank.selected()), (0, 0));
    assert_close(p, 31.11111111111111, tol, "z=33 prediction");
    assert_close(e, 1.8888888888888893, tol, "z=33 residual");
    // The bank's estimate is the selected member's: x = 31.4889.
    assert_close(
        bank.position().to_f64(),
        31.488888888888887,
        tol,
        "estimate",
    );
    // z = 45: m0 predicts 41.6420 (e = 3.3580), m1 44.4444 (e = 0.5556):
    // m1 wins, and |e| decides, not the sign.
    let (m, p, e) = selection(bank.update(z(45.0), one).unwrap());
    assert_eq!(m, 1);
    assert_close(p, 44.44444444444444, tol, "z=45 prediction");
    assert_close(e, 0.5555555555555571, tol, "z=45 residual");
    assert_close(
        bank.position().to_f64(),
        44.888888888888886,
        tol,
        "estimate",
    );
    assert_close(
        bank.velocity().to_f64(),
        11.007407407407406,
        tol,
        "velocity",
    );
    // Both members ran on every measurement.
    assert_close(
        bank.member(0).unwrap().position().to_f64(),
        42.31358024691358,
        tol,
        "member 0 kept tracking",
    );
}

#[test]
fn hand_computed_f64() {
    hand_computed::<f64>(1e-12);
}

#[test]
fn hand_computed_f32() {
    hand_computed::<f32>(1e-4);
}

#[test]
fn hand_computed_fixed() {
    hand_computed::<Fix>(1e-7);
}

#[test]
fn config_spaces_alphas_and_checks_capacity() {
    // k = 3 on [0.2, 0.8]: α = 0.2, 0.5, 0.8; β = α²/(2 − α).
    let bank = ParallelBank::<f64, 4>::from_config(&BankConfig {
        k: 3,
        alpha_min: 0.2,
        alpha_max: 0.8,
    })
    .unwrap();
    assert_eq!(bank.len(), 3);
    for (i, a) in [0.2, 0.5, 0.8].into_iter().enumerate() {
        let g = bank.member_gains(i).unwrap();
        assert_close(g.alpha(), a, 1e-15, "member alpha");
        assert_close(g.beta(), a * a / (2.0 - a), 1e-15, "member beta");
    }
    assert!(bank.member_gains(3).is_none());
    assert_eq!(
        ParallelBank::<f64, 4>::from_config(&BankConfig {
            k: 5,
            ..BankConfig::DEFAULT
        }),
        Err(ConfigError::ExceedsCapacity {
            parameter: "k",
            capacity: 4
        })
    );
    assert!(ParallelBank::<f64, 4>::from_config(&BankConfig {
        k: 0,
        ..BankConfig::DEFAULT
    })
    .is_err());
    assert!(ParallelBank::<f64, 4>::new(&[]).is_err());
}

#[test]
fn refused_update_changes_nothing() {
    let mut bank = two_member_bank::<f64>();
    bank.update(0.0, 1.0).unwrap();
    bank.update(10.0, 1.0).unwrap();
    let before = bank;
    assert_eq!(
        bank.update(f64::NAN, 1.0),
        Err(FilterError::InvalidMeasurement)
    );
    assert_eq!(bank.update(1.0, 0.0), Err(FilterError::InvalidInterval));
    assert_eq!(bank, before);
    // Saturation in fixed point is refused and counted.
    let mut fb = two_member_bank::<Fix>();
    fb.update(Fix::from_f64_lossy(0.0), Fix::ONE).unwrap();
    fb.update(Fix::from_f64_lossy(2.0e9), Fix::from_f64_lossy(0.5))
        .unwrap_err();
    assert_eq!(fb.saturations(), 1);
    assert_eq!(fb.phase(), Phase::OnePoint);
}

proptest! {
    /// The selected member is the one whose own αβ filter, run alone on the
    /// same data with its gains bounded for the irregular intervals as a
    /// schedule's are (`robust_gains`, after the previous interval and the
    /// reference `next_reference` keeps), has the least |innovation| (first
    /// on ties); the bank's estimate and causal prediction are that member's.
    #[test]
    fn selects_least_absolute_innovation(
        zs in prop::collection::vec(-1.0e4f64..1.0e4, 3..40),
        dts in prop::collection::vec(0.1f64..5.0, 40),
        alphas in prop::collection::vec(0.01f64..1.0, 1..8),
    ) {
        let gains: Vec<Gains<f64>> = alphas
            .iter()
            .map(|&a| Gains::alpha_beta_f64(a, a * a / (2.0 - a)).unwrap())
            .collect();
        let mut bank = ParallelBank::<f64, 8>::new(&gains).unwrap();
        let mut alone: Vec<AlphaBeta<f64>> = vec![AlphaBeta::new(); gains.len()];
        let (mut previous, mut reference) = (0.0, 0.0);
        for (z, dt) in zs.iter().zip(&dts) {
            let out = bank.update(*z, *dt).unwrap();
            let residuals: Vec<Option<f64>> = alone
                .iter_mut()
                .zip(&gains)
                .map(|(f, g)| {
                    let [bounded] = robust_gains([*g], *dt, previous, reference).unwrap();
                    match f.update(*z, *dt, &bounded).unwrap() {
                        UpdateOutcome::Filtered(i) => Some(i.residual),
                        _ => None,
                    }
                })
                .collect();
            (previous, reference) = match alone[0].phase() {
                Phase::Tracking if residuals[0].is_some() => (*dt, next_reference(reference, *dt)),
                Phase::Tracking => (*dt, *dt),
                _ => (0.0, 0.0),
            };
            if let BankOutcome::Filtered(sel) = out {
                let sizes: Vec<f64> = residuals.iter().map(|r| r.unwrap().abs()).collect();
                let least = sizes.iter().cloned().fold(f64::INFINITY, f64::min);
                let first = sizes.iter().position(|&s| s == least).unwrap();
                prop_assert_eq!(sel.member, first);
                prop_assert_eq!(sel.residual, residuals[first].unwrap());
                prop_assert_eq!(bank.position(), alone[first].position());
                prop_assert_eq!(bank.predict(1.0).unwrap(), alone[first].predict(1.0).unwrap());
            } else {
                prop_assert!(residuals.iter().all(|r| r.is_none()));
            }
        }
    }

    /// In 2-D each axis selects independently, and a coast advances every
    /// member.
    #[test]
    fn cartesian_bank_selects_per_axis(
        zs in prop::collection::vec((-1.0e3f64..1.0e3, -1.0e3f64..1.0e3), 3..20),
    ) {
        let mut bank = CartesianBank::<f64, 8, 2>::from_config(&BankConfig::DEFAULT).unwrap();
        let mut x = ParallelBank::<f64, 8>::from_config(&BankConfig::DEFAULT).unwrap();
        let mut y = x;
        for (zx, zy) in &zs {
            let out = bank.update([*zx, *zy], 1.0).unwrap();
            prop_assert_eq!(out[0], x.update(*zx, 1.0).unwrap());
            prop_assert_eq!(out[1], y.update(*zy, 1.0).unwrap());
        }
        bank.coast(1.0).unwrap();
        x.coast(1.0).unwrap();
        prop_assert_eq!(bank.position()[0], x.position());
    }
}

/// The Cartesian bank forms its members' step gains once per update for
/// every axis: each axis ends exactly as a `ParallelBank` updated alone,
/// refusals included (a bad measurement on either axis, a bad interval,
/// β/T saturating in fixed point); a refused update leaves every member as
/// it was and keeps the saturation counts the axes reached.
#[test]
fn cartesian_bank_equals_its_axes_updated_alone() {
    fn run<S: Scalar>(steps: &[([f64; 2], f64)]) -> u32 {
        let mut both = CartesianBank::<S, 4, 2>::new(two_member_bank::<S>());
        let mut alone = [two_member_bank::<S>(), two_member_bank::<S>()];
        for &(z, dt) in steps {
            let zs = z.map(S::from_f64_lossy);
            let dt = S::from_f64_lossy(dt);
            let got = both.update(zs, dt);
            // Alone, axis after axis: the first refusal is the Cartesian
            // one, and it undoes the axes updated before it.
            let mut tried = alone;
            let mut want = Ok([BankOutcome::FirstPoint; 2]);
            for (i, (axis, z)) in tried.iter_mut().zip(zs).enumerate() {
                match (axis.update(z, dt), want.as_mut()) {
                    (Ok(o), Ok(w)) => w[i] = o,
                    (Err(e), _) => {
                        want = Err(e);
                        break;
                    }
                    (Ok(_), Err(_)) => unreachable!(),
                }
            }
            assert_eq!(got, want, "{} {z:?}", S::NAME);
            for (i, (a, t)) in both.axes().iter().zip(&tried).enumerate() {
                let reference = if got.is_ok() { t } else { &alone[i] };
                assert_eq!(a.member(0), reference.member(0), "{} {z:?}", S::NAME);
                assert_eq!(a.member(1), reference.member(1), "{} {z:?}", S::NAME);
                assert_eq!(a.saturations(), t.saturations(), "{} {z:?}", S::NAME);
            }
            // Both now hold what the reference says (asserted above).
            alone = *both.axes();
        }
        both.axes().iter().map(|a| a.saturations()).sum()
    }
    let steps = [
        ([0.0, 5.0], 1.0),
        ([10.0, 3.0], 1.0),
        ([21.0, f64::NAN], 1.0),
        ([f64::NAN, 2.0], 1.0),
        ([19.0, 2.0], 0.0),
        ([30.0, -1.0], 1.5),
        ([41.0, -4.0], 0.5),
    ];
    assert_eq!(run::<f64>(&steps), 0);
    assert_eq!(run::<f32>(&steps), 0);
    assert_eq!(run::<Fix>(&steps), 0);
    // Fixed point: the prediction saturates (1.5·10⁹ m at 1.5·10⁹ m/s is
    // past Q32.32's 2³¹), counted once, on the first axis. (A tiny interval,
    // where β/T saturated, is now skipped before β/T is formed.)
    let saturations = run::<Fix>(&[([0.0, 5.0], 1.0), ([1.5e9, 3.0], 1.0), ([2.0e9, 4.0], 1.0)]);
    assert_eq!(saturations, 1);
}

/// A report 0.1 s after one at regular 1 s intervals, 150 m off (3σ at
/// σ 50 m): every member's gains are bounded as a schedule's are
/// (`robust_gains`: β scaled by 2·0.1/1), so the α = 1 member's velocity
/// moves by (0.2·β/0.1 s)·150 m = 300 m/s, not β·150/0.1 = 1,500 m/s; at
/// the regular interval the members keep their own gains.
#[test]
fn an_irregular_interval_bounds_every_members_gains() {
    fn run<S: Scalar>() {
        let mut bank = ParallelBank::<S, 8>::from_config(&BankConfig::DEFAULT).unwrap();
        let mut regular = [AlphaBeta::<S>::new(); 8];
        let one = S::ONE;
        for k in 0..10 {
            let z = S::from_f64_lossy(100.0 * k as f64);
            bank.update(z, one).unwrap();
            for (i, member) in regular.iter_mut().enumerate() {
                member
                    .update(z, one, bank.member_gains(i).unwrap())
                    .unwrap();
            }
        }
        for (i, member) in regular.iter().enumerate() {
            assert_eq!(bank.member(i), Some(member), "{} member {i}", S::NAME);
        }
        let z = S::from_f64_lossy(900.0 + 10.0 + 150.0);
        bank.update(z, S::from_f64_lossy(0.1)).unwrap();
        for i in 0..bank.len() {
            let v = bank.member(i).unwrap().velocity().to_f64();
            assert!(
                (v - 100.0).abs() <= 300.0 * 1.001,
                "{} member {i}: v = {v} m/s",
                S::NAME
            );
        }
        let last = bank.member(bank.len() - 1).unwrap().velocity().to_f64();
        assert!(
            last > 100.0 + 250.0,
            "{}: the α = 1 member moved {last}",
            S::NAME
        );
    }
    run::<f64>();
    run::<f32>();
    run::<Fix>();
}
