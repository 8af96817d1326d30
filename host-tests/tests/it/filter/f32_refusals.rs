//! The `f32` refusal contract on the hot path, exactly: a non-finite
//! measurement or interval, or an interval ≤ 0, is refused and leaves the
//! state bit-identical; an update with a NaN or infinite result is refused
//! as `Saturated`, counted once, and leaves the state otherwise
//! bit-identical; an accepted update stores exactly the unguarded f32
//! arithmetic of Tenne & Singh eqs. (1)–(5) (Al-Wagih eqs. 3–8), with the
//! prediction and residual it corrected.
//!
//! The `f32` guard has two forms with one meaning (`abtrack::num::f32_check`):
//! an integer test of the IEEE 754 exponent field (the M0/M3, and this host)
//! and `check + 0·output` (the M4F's FPU). Both are checked here against
//! every class of value; the filter tests run the form this host selects.

use abtrack::filter::{Cartesian, Gains, KinematicFilter, Phase, StepGains, UpdateKind};
use abtrack::num::f32_check;
use abtrack::num::numeric::ScalarGuard;
use abtrack::num::Quantity;
use abtrack::FilterError;
use proptest::prelude::*;

/// Values of every IEEE 754 class and at every boundary: zeros, the
/// subnormal extremes, the normal extremes, infinities, quiet and
/// signalling NaNs of both signs.
fn special_values() -> Vec<f32> {
    let bits: [u32; 16] = [
        0x0000_0000, // +0
        0x8000_0000, // −0
        0x0000_0001, // smallest subnormal
        0x807F_FFFF, // −largest subnormal
        0x0080_0000, // MIN_POSITIVE
        0x3F80_0000, // 1
        0x7E00_0000, // 2¹²⁵
        0x7F7F_FFFF, // MAX
        0xFF7F_FFFF, // −MAX
        0x7F80_0000, // +∞
        0xFF80_0000, // −∞
        0x7FC0_0000, // quiet NaN
        0xFFC0_0000, // −quiet NaN
        0x7F80_0001, // signalling NaN
        0xFF80_0001, // −signalling NaN
        0x7FFF_FFFF, // NaN, every payload bit
    ];
    bits.iter().map(|&b| f32::from_bits(b)).collect()
}

/// Every exponent field, with the extreme and middle mantissas, both signs.
fn exponent_sweep() -> Vec<f32> {
    let mut out = Vec::new();
    for exponent in 0u32..=0xFF {
        for mantissa in [0, 1, 0x40_0000, 0x7F_FFFF] {
            for sign in [0, 0x8000_0000] {
                out.push(f32::from_bits(sign | exponent << 23 | mantissa));
            }
        }
    }
    out
}

/// One form of the guard: its fold and its final test.
type GuardForm = (fn(f32, f32) -> f32, fn(f32) -> bool);

/// Folds `values` from the guard's zero with one form and says whether it
/// passed.
fn passes(form: GuardForm, values: &[f32]) -> bool {
    let (fold, passed) = form;
    passed(values.iter().fold(0.0, |check, &v| fold(check, v)))
}

const BITS: GuardForm = (f32_check::fold_bits, f32_check::passed_bits);
const FPU: GuardForm = (f32_check::fold_fpu, f32_check::passed_fpu);

/// The guard the filters use (the form selected for this target).
fn guard_passes(values: &[f32]) -> bool {
    let mut guard = ScalarGuard::<f32>::default();
    for &v in values {
        v.check_output(&mut guard);
    }
    guard.passed()
}

#[test]
fn both_guard_forms_flag_exactly_the_non_finite_values() {
    let values: Vec<f32> = special_values()
        .into_iter()
        .chain(exponent_sweep())
        .collect();
    for &v in &values {
        for form in [BITS, FPU] {
            assert_eq!(
                passes(form, &[v]),
                v.is_finite(),
                "{v:e} ({:#010x})",
                v.to_bits()
            );
        }
        assert_eq!(guard_passes(&[v]), v.is_finite(), "{v:e}");
        // Several outputs: any non-finite one fails the check, wherever it
        // is, and finite ones after it do not clear it (sticky).
        for &w in &values {
            for form in [BITS, FPU] {
                let want = v.is_finite() && w.is_finite();
                assert_eq!(passes(form, &[v, w, 1.0, -2.5]), want, "{v:e}, {w:e}");
                assert_eq!(passes(form, &[1.0, w, v, f32::MAX]), want, "{w:e}, {v:e}");
            }
        }
    }
    assert!(passes(BITS, &[]) && passes(FPU, &[]) && guard_passes(&[]));
    // Finite outputs whose sum overflows are not refused: no result left the
    // range (the f64 guard's sum would refuse them).
    for form in [BITS, FPU] {
        assert!(passes(form, &[f32::MAX; 8]));
    }
}

#[test]
fn interval_test_is_finite_and_positive() {
    let values: Vec<f32> = special_values()
        .into_iter()
        .chain(exponent_sweep())
        .collect();
    for v in values {
        let want = v.is_finite() && v > 0.0;
        assert_eq!(Quantity::is_valid_and_positive(v), want, "{v:e}");
        assert_eq!(abtrack::Quantity::is_valid_and_positive(v), want, "{v:e}");
        let w = f64::from(v);
        assert_eq!(Quantity::is_valid_and_positive(w), w.is_finite() && w > 0.0);
    }
}

/// Every bit of a one-axis filter's state, and its saturation count.
type Snapshot = (Phase, [u32; 3], Option<[u32; 2]>, u32);

fn snapshot<const O: usize>(f: &KinematicFilter<f32, O>) -> Snapshot {
    (
        f.phase(),
        [
            f.position().to_bits(),
            f.velocity().to_bits(),
            f.acceleration().to_bits(),
        ],
        f.last_innovation()
            .map(|i| [i.predicted.to_bits(), i.residual.to_bits()]),
        f.saturations(),
    )
}

fn snapshots<const O: usize, const D: usize>(c: &Cartesian<f32, O, D>) -> Vec<Snapshot> {
    c.axes().iter().map(snapshot).collect()
}

/// One axis's filtered update in plain f32, written from the equations
/// (Tenne & Singh eqs. 1–5): the outputs (position, velocity, acceleration,
/// predicted, residual) as the filter must store them.
fn reference<const O: usize>(f: &KinematicFilter<f32, O>, z: f32, s: &StepGains<f32>) -> [f32; 5] {
    let t = s.interval();
    let (x, v, a) = (f.position(), f.velocity(), f.acceleration());
    let (predicted, predicted_velocity) = if O == 3 {
        (x + v * t + a * s.terms().half_squared(), v + a * t)
    } else {
        (x + v * t, v)
    };
    let residual = z - predicted;
    let position = predicted + s.alpha() * residual;
    let velocity = predicted_velocity + s.velocity_gain() * residual;
    let acceleration = if O == 3 {
        a + s.acceleration_gain() * residual
    } else {
        0.0
    };
    [position, velocity, acceleration, predicted, residual]
}

/// What the contract says an update of tracking `axes` with `z` does, and
/// the state it leaves, from the reference arithmetic alone.
fn expected<const O: usize, const D: usize>(
    axes: &[KinematicFilter<f32, O>; D],
    z: [f32; D],
    s: &StepGains<f32>,
) -> (Result<UpdateKind, FilterError>, Vec<Snapshot>) {
    let before: Vec<Snapshot> = axes.iter().map(snapshot).collect();
    if z.iter().any(|v| !v.is_finite()) {
        return (Err(FilterError::InvalidMeasurement), before);
    }
    let outputs: Vec<[f32; 5]> = axes
        .iter()
        .zip(z)
        .map(|(f, z)| reference(f, z, s))
        .collect();
    if outputs.iter().flatten().any(|v| !v.is_finite()) {
        let mut after = before;
        after[0].3 += 1;
        return (Err(FilterError::Saturated), after);
    }
    let after = outputs
        .iter()
        .zip(&before)
        .map(|([p, v, a, predicted, residual], b)| {
            (
                Phase::Tracking,
                [p.to_bits(), v.to_bits(), a.to_bits()],
                Some([predicted.to_bits(), residual.to_bits()]),
                b.3,
            )
        })
        .collect();
    (Ok(UpdateKind::Filtered), after)
}

/// Finite values from tiny to near the top of the range (so that some
/// updates overflow), most of them ordinary.
fn finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -1.0e6f32..1.0e6,
        1 => -3.4e38f32..3.4e38,
        1 => prop::sample::select(vec![
            0.0f32, -0.0, f32::MAX, -f32::MAX, 1.0e38, -1.0e38, f32::from_bits(1),
            f32::MIN_POSITIVE,
        ]),
    ]
}

/// A measurement: finite, or any bit pattern (NaN and ±∞ included).
fn measurement() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => finite(),
        1 => any::<u32>().prop_map(f32::from_bits),
        1 => prop::sample::select(vec![f32::NAN, f32::INFINITY, f32::NEG_INFINITY]),
    ]
}

fn step<const O: usize>(alpha: f64, beta: f64, gamma: f64, dt: f32) -> StepGains<f32> {
    let gains = if O == 3 {
        Gains::<f32>::alpha_beta_gamma_f64(alpha, beta, gamma)
    } else {
        Gains::<f32>::alpha_beta_f64(alpha, beta)
    };
    StepGains::new(&gains.expect("gains in the stability region"), dt).expect("valid interval")
}

fn check_update_step<const O: usize>(
    x: f32,
    v: f32,
    a: f32,
    z: f32,
    dt: f32,
) -> Result<(), TestCaseError> {
    let s = step::<O>(0.5, 0.25, 0.05, dt);
    let mut f = KinematicFilter::<f32, O>::from_state(x, v, a).expect("finite state");
    let (want, after) = expected(&[f], [z], &s);
    let got = f.update_step(z, &s);
    prop_assert_eq!(got, want);
    prop_assert_eq!(vec![snapshot(&f)], after);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4000))]

    /// Both guard forms over arbitrary words: pass exactly when every
    /// output is finite.
    #[test]
    fn guard_forms_agree_with_is_finite(words in prop::collection::vec(any::<u32>(), 0..10)) {
        let values: Vec<f32> = words.into_iter().map(f32::from_bits).collect();
        let want = values.iter().all(|v| v.is_finite());
        prop_assert_eq!(passes(BITS, &values), want);
        prop_assert_eq!(passes(FPU, &values), want);
        prop_assert_eq!(guard_passes(&values), want);
    }

    /// One axis, αβ and αβγ: the per-update path does exactly what the
    /// contract and the reference arithmetic say.
    #[test]
    fn one_axis_update_step_is_exact(
        x in finite(), v in finite(), a in finite(), z in measurement(),
        dt in prop::sample::select(vec![0.05f32, 1.0, 20.0]),
    ) {
        check_update_step::<2>(x, v, a, z, dt)?;
        check_update_step::<3>(x, v, a, z, dt)?;
    }

    /// Two axes through `update` (the interval checked, the step gains
    /// formed, both axes all or nothing): the same contract, and the
    /// saturation counted once, on the first axis.
    #[test]
    fn two_axis_update_is_exact(
        z0 in prop::array::uniform2(finite()),
        z1 in prop::array::uniform2(finite()),
        z in prop::array::uniform2(measurement()),
    ) {
        let dt = 1.0f32;
        let gains = Gains::<f32>::alpha_beta_f64(0.5, 0.25).expect("gains");
        let mut c = Cartesian::<f32, 2, 2>::new();
        c.update(z0, dt, &gains).expect("first point");
        // The second point may overflow (z₁ − z₀)/T: then it is refused and
        // counted, and nothing else is tested.
        if c.update(z1, dt, &gains).is_err() {
            prop_assert_eq!(c.saturations(), 1);
            prop_assert_eq!(c.phase(), Phase::OnePoint);
            return Ok(());
        }
        let s = StepGains::new(&gains, dt).expect("step gains");
        let (want, after) = expected(c.axes(), z, &s);
        let got = c.update(z, dt, &gains).map(|_| UpdateKind::Filtered);
        prop_assert_eq!(got, want);
        prop_assert_eq!(snapshots(&c), after);
    }

    /// Any interval word: refused as invalid exactly when it is not finite
    /// and > 0 (a subnormal is valid, and its β/T overflows: saturated);
    /// every refusal leaves the state bit-identical, only a saturation is
    /// counted; a bad measurement is reported first.
    #[test]
    fn any_interval_word(word in any::<u32>(), z_bad in any::<bool>()) {
        let dt = f32::from_bits(word);
        let gains = Gains::<f32>::alpha_beta_f64(0.5, 0.25).expect("gains");
        let mut c = Cartesian::<f32, 2, 2>::new();
        for z in [[1.0, 2.0], [3.0, 5.0], [5.5, 8.0]] {
            c.update(z, 1.0, &gains).expect("tracking");
        }
        let before = snapshots(&c);
        let z = if z_bad { [7.0, f32::NAN] } else { [7.0, 11.0] };
        let got = c.update(z, dt, &gains);
        if z_bad {
            prop_assert_eq!(got.err(), Some(FilterError::InvalidMeasurement));
        } else if !(dt.is_finite() && dt > 0.0) {
            prop_assert_eq!(got.err(), Some(FilterError::InvalidInterval));
        }
        match got {
            Ok(_) => prop_assert!(dt.is_finite() && dt > 0.0),
            Err(FilterError::Saturated) => {
                let mut want = before.clone();
                want[0].3 += 1;
                prop_assert_eq!(snapshots(&c), want);
            }
            Err(_) => prop_assert_eq!(snapshots(&c), before),
        }
        let mut d = c;
        let before = snapshots(&d);
        let coasted = d.coast(dt);
        if !(dt.is_finite() && dt > 0.0) {
            prop_assert_eq!(coasted, Err(FilterError::InvalidInterval));
            prop_assert_eq!(snapshots(&d), before);
        }
    }
}

/// The named cases, one by one: each bad measurement and interval, the
/// subnormal interval, and results that overflow in each output.
#[test]
fn named_refusals() {
    let gains = Gains::<f32>::alpha_beta_gamma_f64(0.5, 0.25, 0.05).expect("gains");
    let mut f = KinematicFilter::<f32, 3>::new();
    for z in [1.0, 2.5, 4.5] {
        f.update(z, 1.0, &gains).expect("tracking");
    }
    let before = snapshot(&f);
    for bad in [f32::NAN, -f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mut t = f;
        assert_eq!(
            t.update(bad, 1.0, &gains),
            Err(FilterError::InvalidMeasurement)
        );
        assert_eq!(
            t.update(bad, f32::NAN, &gains),
            Err(FilterError::InvalidMeasurement)
        );
        let s = StepGains::new(&gains, 1.0).expect("step");
        assert_eq!(t.update_step(bad, &s), Err(FilterError::InvalidMeasurement));
        assert_eq!(snapshot(&t), before);
    }
    let negative_subnormal = f32::from_bits(0x8000_0001);
    for bad in [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        -1.0,
        negative_subnormal,
        -f32::MAX,
    ] {
        let mut t = f;
        assert_eq!(
            t.update(6.0, bad, &gains),
            Err(FilterError::InvalidInterval),
            "{bad:e}"
        );
        assert_eq!(t.coast(bad), Err(FilterError::InvalidInterval), "{bad:e}");
        assert_eq!(t.predict(bad), Err(FilterError::InvalidInterval), "{bad:e}");
        assert_eq!(snapshot(&t), before);
    }
    // A positive subnormal interval is valid, but β/T overflows (and T²/2
    // underflows to zero): refused as saturated and counted; so is one
    // whose square overflows.
    for huge_gain in [f32::from_bits(1), f32::MAX] {
        let mut t = f;
        assert_eq!(
            t.update(6.0, huge_gain, &gains),
            Err(FilterError::Saturated)
        );
        assert_eq!(t.saturations(), 1);
        let mut want = before;
        want.3 = 1;
        assert_eq!(snapshot(&t), want);
    }

    // Results that overflow, from finite states and measurements:
    // (x, v, a, z, T).
    let cases: [(f32, f32, f32, f32, f32); 4] = [
        // The prediction x + T·v (and everything after it).
        (3.0e38, 1.0e37, 0.0, 3.0e38, 20.0),
        // The residual z − x_p.
        (-3.0e38, 0.0, 0.0, 3.0e38, 20.0),
        // The velocity v + (β/T)·e alone (β/T = 5, e = 10³⁷).
        (0.0, 3.0e38, 0.0, 2.5e37, 0.05),
        // The acceleration a + γ/(2T²)·e alone (γ/(2T²) = 10, e ≈ 10³⁷).
        (0.0, 0.0, 3.4e38, 1.0e37, 0.05),
    ];
    for (x, v, a, z, dt) in cases {
        let s = step::<3>(0.5, 0.25, 0.05, dt);
        let mut t = KinematicFilter::<f32, 3>::from_state(x, v, a).expect("finite");
        let before = snapshot(&t);
        let (want, after) = expected(&[t], [z], &s);
        assert_eq!(want, Err(FilterError::Saturated), "{x:e} {v:e} {a:e} {z:e}");
        assert_eq!(t.update_step(z, &s), want);
        assert_eq!(vec![snapshot(&t)], after);
        let mut unchanged = before;
        unchanged.3 = 1;
        assert_eq!(snapshot(&t), unchanged);
    }
    // The velocity and acceleration cases overflow in that output only.
    let only = |x: f32, v: f32, a: f32, z: f32, dt: f32| {
        let f = KinematicFilter::<f32, 3>::from_state(x, v, a).expect("finite");
        reference(&f, z, &step::<3>(0.5, 0.25, 0.05, dt)).map(f32::is_finite)
    };
    assert_eq!(
        only(0.0, 3.0e38, 0.0, 2.5e37, 0.05),
        [true, false, true, true, true]
    );
    assert_eq!(
        only(0.0, 0.0, 3.4e38, 1.0e37, 0.05),
        [true, true, false, true, true]
    );

    // An accepted update keeps its prediction and residual.
    let mut t = KinematicFilter::<f32, 2>::from_state(10.0, 2.0, 0.0).expect("finite");
    let s = step::<2>(0.5, 0.25, 0.0, 1.0);
    assert_eq!(t.update_step(13.0, &s), Ok(UpdateKind::Filtered));
    let innovation = t.last_innovation().expect("innovation");
    assert_eq!((innovation.predicted, innovation.residual), (12.0, 1.0));
    assert_eq!((t.position(), t.velocity()), (12.5, 2.25));
}
