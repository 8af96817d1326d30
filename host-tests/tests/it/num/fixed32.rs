//! The fast fixed point (`abtrack::num::fixed32`, `Fixed32`) over raw bits:
//! arithmetic never wraps (checked against exact i128 / f64 arithmetic),
//! saturation is detected (sentinels, the hot path's guard), conversions
//! round as documented, and a refused filter update leaves the state
//! bit-identical.

use abtrack::filter::{Cartesian, FilterError, Gains, KinematicFilter, StepGains};
use abtrack::num::fixed32::{Acceleration, Gain, Interval, Length, Ratio, Speed};
use abtrack::num::{AddProduct, Numeric, Quantity, Real};
use abtrack::Fixed32;
use proptest::prelude::*;

type G = <Fixed32 as Numeric>::Guard;

/// A word that is not a sentinel.
fn word() -> impl Strategy<Value = i32> {
    (i32::MIN + 1)..i32::MAX
}

/// Exact `wide / 2^shift` rounded to nearest, ties toward +∞ (the
/// documented rounding).
fn round_shift(wide: i128, shift: u32) -> i128 {
    (wide + (1i128 << (shift - 1))) >> shift
}

fn fits(v: i128) -> bool {
    v > i128::from(i32::MIN) && v < i128::from(i32::MAX)
}

/// A normalised mantissa of either sign, the ends of its range included.
fn scaled_mantissa() -> impl Strategy<Value = i32> {
    prop_oneof![
        (1i32 << 30)..i32::MAX,
        (i32::MIN + 1)..=-(1i32 << 30),
        Just(1i32 << 30),
        Just(i32::MAX),
        Just(-(1i32 << 30)),
        Just(i32::MIN + 1),
    ]
}

/// A normalised scaled number with the given mantissa and exponent.
fn ratio_from(mantissa: i32, exponent: i32) -> Ratio {
    Ratio::from_wide(i64::from(mantissa), exponent)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4000))]

    /// Speed × Interval → Length: the exact product rounded to nearest, or a
    /// sentinel of the right sign when it does not fit; never a wrapped value.
    #[test]
    fn fixed_products_round_or_saturate(a in word(), b in word()) {
        let got = Speed::from_bits(a) * Interval::from_bits(b);
        let exact = round_shift(i128::from(a) * i128::from(b), 18 + 24 - 12);
        if fits(exact) {
            prop_assert_eq!(i128::from(got.to_bits()), exact);
        } else {
            prop_assert!(!got.is_valid());
            prop_assert_eq!(got.to_bits() > 0, exact > 0);
        }
    }

    /// The guarded form of the same product: x + v·T either equals the exact
    /// rounded sum or marks the guard.
    #[test]
    fn guarded_product_matches_or_flags(x in word(), a in word(), b in word()) {
        let mut g = G::default();
        let got = Length::from_bits(x).add_product(Speed::from_bits(a), Interval::from_bits(b), &mut g);
        let exact = i128::from(x) + round_shift(i128::from(a) * i128::from(b), 18 + 24 - 12);
        if fits(exact) {
            prop_assert!(g.passed());
            prop_assert_eq!(i128::from(got.to_bits()), exact);
        } else {
            prop_assert!(!g.passed() || !fits(i128::from(got.to_bits())));
            // A result that does not fit must never pass.
            prop_assert!(!g.passed());
        }
    }

    /// α·e with α a fixed-format gain (I4F28): exact rounding or the flag.
    #[test]
    fn guarded_gain_product(x in word(), alpha in word(), e in word()) {
        let mut g = G::default();
        let got = Length::from_bits(x).add_product(Gain::from_bits(alpha), Length::from_bits(e), &mut g);
        let exact = i128::from(x) + round_shift(i128::from(alpha) * i128::from(e), 28);
        prop_assert_eq!(g.passed(), fits(exact));
        if fits(exact) {
            prop_assert_eq!(i128::from(got.to_bits()), exact);
        }
    }

    /// (β/T)·e with β/T a scaled number: x + m·e·2^(e_m + 8) rounded, or the
    /// flag. Exponents cover tiny to absurd coefficients.
    #[test]
    fn guarded_scaled_product(
        v in word(),
        mantissa in (1i32 << 30)..i32::MAX,
        negative in any::<bool>(),
        exponent in -100i32..0,
        e in word(),
    ) {
        let m = if negative { -mantissa } else { mantissa };
        let rate = ratio_from(m, exponent);
        let rate: abtrack::num::fixed32::Rate = rate.cast();
        let mut g = G::default();
        let got = Speed::from_bits(v).add_product(rate, Length::from_bits(e), &mut g);
        // Speed bits = m·e·2^(exponent − 12 + 18).
        let shift = -(exponent + 6);
        let product = i128::from(rate.mantissa()) * i128::from(e);
        let term = if shift >= 1 {
            if shift > 62 { None } else { Some(round_shift(product, shift as u32)) }
        } else {
            None
        };
        match term {
            Some(t) => {
                let exact = i128::from(v) + t;
                prop_assert_eq!(g.passed(), fits(exact));
                if fits(exact) {
                    prop_assert_eq!(i128::from(got.to_bits()), exact);
                }
            }
            None if shift > 62 => {
                // |m·e| < 2⁶² shifted by more than 62: the exact term is
                // below one step; the result is within one step of v.
                if g.passed() {
                    prop_assert!((i128::from(got.to_bits()) - i128::from(v)).abs() <= 1);
                }
            }
            None => prop_assert!(!g.passed() || product == 0),
        }
    }

    /// Sums and differences of fixed words: exact, or a sentinel.
    #[test]
    fn sums_never_wrap(a in word(), b in word()) {
        let (x, y) = (Length::from_bits(a), Length::from_bits(b));
        for (got, exact) in [
            (x + y, i128::from(a) + i128::from(b)),
            (x - y, i128::from(a) - i128::from(b)),
        ] {
            if fits(exact) {
                prop_assert_eq!(i128::from(got.to_bits()), exact);
            } else {
                prop_assert!(!got.is_valid());
            }
        }
        let mut g = G::default();
        let d = x.sub_guarded(y, &mut g);
        let exact = i128::from(a) - i128::from(b);
        prop_assert_eq!(g.passed(), exact >= i128::from(i32::MIN) && exact <= i128::from(i32::MAX));
        if g.passed() {
            prop_assert_eq!(i128::from(d.to_bits()), exact);
        }
    }

    /// Sentinels are sticky through every operator.
    #[test]
    fn sentinels_are_sticky(a in word(), sign in any::<bool>()) {
        let s = if sign { Length::MAX } else { Length::MIN };
        let x = Length::from_bits(a);
        prop_assert!(!(s + x).is_valid());
        prop_assert!(!(x - s).is_valid());
        prop_assert!(!(-s).is_valid());
        prop_assert!(!(s / Interval::from_f64_lossy(1.0)).is_valid());
        prop_assert!(!(Ratio::ONE * s).is_valid());
        prop_assert!(!(s / x).is_valid());
        let t = if sign { Speed::MAX } else { Speed::MIN };
        prop_assert!(!(t * Interval::from_bits(a)).is_valid());
    }

    /// Length / Interval → Speed: rounded to nearest (ties away from zero),
    /// or a sentinel.
    #[test]
    fn division_rounds_or_saturates(a in word(), b in word()) {
        prop_assume!(b != 0);
        let got = Length::from_bits(a) / Interval::from_bits(b);
        let num = i128::from(a) << 30;
        let den = i128::from(b);
        let q = num / den;
        let r = num % den;
        let exact = if 2 * r.abs() >= den.abs() { q + num.signum() * den.signum() } else { q };
        if fits(exact) {
            prop_assert_eq!(i128::from(got.to_bits()), exact);
        } else {
            prop_assert!(!got.is_valid());
        }
    }

    /// Conversions from f64 round to nearest: within half a step, refused
    /// beyond the range.
    #[test]
    fn conversions_round_to_nearest(v in -600_000.0f64..600_000.0) {
        match Length::try_from_f64(v) {
            Ok(x) => {
                prop_assert!((x.to_f64() - v).abs() <= 0.5 / 4096.0);
            }
            Err(_) => prop_assert!(v.abs() >= 524_287.9),
        }
        let r = Ratio::from_f64_lossy(v);
        prop_assert!((r.to_f64() - v).abs() <= v.abs() * 2f64.powi(-31));
    }

    /// Scaled arithmetic: within one unit of the last place (2⁻³⁰ relative)
    /// of the exact result.
    #[test]
    fn scaled_ops_within_one_ulp(a in -1e6f64..1e6, b in -1e6f64..1e6) {
        prop_assume!(a != 0.0 && b != 0.0);
        let (x, y) = (Ratio::from_f64_lossy(a), Ratio::from_f64_lossy(b));
        let (xa, yb) = (x.to_f64(), y.to_f64());
        let tol = |exact: f64| exact.abs() * 2f64.powi(-30) * 1.000_001;
        let p = (x * y).to_f64();
        prop_assert!((p - xa * yb).abs() <= tol(xa * yb));
        let q = (x / y).to_f64();
        prop_assert!((q - xa / yb).abs() <= tol(xa / yb));
        let s = (x + y).to_f64();
        // The sum rounds once; its inputs are exact in f64.
        prop_assert!((s - (xa + yb)).abs() <= tol(xa + yb) + xa.abs().max(yb.abs()) * 2f64.powi(-61));
        let r = x.abs().sqrt().to_f64();
        prop_assert!((r - xa.abs().sqrt()).abs() <= tol(xa.abs().sqrt()));
        prop_assert_eq!(x < y, xa < yb);
        prop_assert_eq!(x == y, xa == yb);
    }

    /// The scaled primitives against exact arithmetic on normalised
    /// operands of any sign and scale: the product within half an ulp
    /// (exact i128), the quotient and the square root correctly rounded
    /// (f64's 53 bits leave 2⁻⁵² of slack), hypot within half an ulp plus
    /// 2⁻⁵⁰ (hypot3 too, and equal to hypot with a zero), the sum within
    /// half an ulp (plus 2⁻³⁰ of one).
    #[test]
    fn scaled_primitives_round_to_nearest(
        ma in scaled_mantissa(), ea in -50i32..34, mb in scaled_mantissa(), eb in -50i32..34,
    ) {
        let (x, y) = (ratio_from(ma, ea), ratio_from(mb, eb));
        let ulp = |r: Ratio| 2f64.powi(r.exponent());
        let p = x * y;
        // m·2^k against ma·mb, k = e_p − ea − eb ∈ {30, 31}.
        let k = p.exponent() - ea - eb;
        prop_assert!(k == 30 || k == 31);
        let error = (i128::from(p.mantissa()) << k) - i128::from(ma) * i128::from(mb);
        prop_assert!(error.abs() <= 1i128 << (k - 1));
        let (xf, yf) = (x.to_f64(), y.to_f64());
        let q = x / y;
        let exact = xf / yf;
        prop_assert!((q.to_f64() - exact).abs() <= 0.5 * ulp(q) + exact.abs() * 2f64.powi(-52));
        let r = x.abs().sqrt();
        let exact = xf.abs().sqrt();
        prop_assert!((r.to_f64() - exact).abs() <= 0.5 * ulp(r) + exact * 2f64.powi(-52));
        let h = x.hypot(y);
        let exact = xf.hypot(yf);
        prop_assert!((h.to_f64() - exact).abs() <= 0.5 * ulp(h) + exact * 2f64.powi(-50));
        // Three lengths: x, y and their product (another scale).
        let z = x * y;
        let h3 = x.hypot3(y, z);
        let exact = xf.hypot(yf).hypot(z.to_f64());
        prop_assert!((h3.to_f64() - exact).abs() <= 0.5 * ulp(h3) + exact * 2f64.powi(-50));
        prop_assert_eq!(x.hypot3(y, Ratio::ZERO), h);
        // Halving is exact.
        prop_assert_eq!(x.half().to_f64(), xf / 2.0);
        // The sum against the exact i128 sum, in units of 2^base (exponents
        // within 60 of each other keep every term below 2¹²²): within half
        // an ulp plus 2⁻³⁰ of one (the bit beyond the 31 guard bits when the
        // signs differ and the gap is 32).
        if (ea - eb).abs() <= 60 {
            let base = ea.min(eb) - 31;
            let units = |m: i32, e: i32| i128::from(m) << (e - base);
            let exact = units(ma, ea) + units(mb, eb);
            let s = x + y;
            if s.mantissa() == 0 {
                prop_assert_eq!(exact, 0);
            } else {
                prop_assert!(s.exponent() >= base);
                let ulp_units = 1i128 << (s.exponent() - base);
                let error = (units(s.mantissa(), s.exponent()) - exact).abs();
                prop_assert!(2 * error <= ulp_units + (ulp_units >> 29), "{} {}", error, ulp_units);
            }
        }
    }

    /// hypot: the integer square root of the exact sum of squares, to the
    /// nearest step.
    #[test]
    fn hypot_is_nearest_step(a in word(), b in word()) {
        let got = Fixed32::hypot(Length::from_bits(a), Length::from_bits(b));
        let sum = (i128::from(a) * i128::from(a) + i128::from(b) * i128::from(b)) as f64;
        let exact = sum.sqrt();
        if exact < f64::from(i32::MAX) - 1.0 {
            prop_assert!((f64::from(got.to_bits()) - exact).abs() <= 0.5 + 1e-6 * exact / 4e9);
        } else {
            prop_assert!(!got.is_valid());
        }
    }

    /// A refused update (saturation, bad measurement) leaves a 2-D filter
    /// bit-identical but for the saturation count of a saturated one.
    #[test]
    fn refused_update_leaves_state(
        x0 in -1e5f64..1e5, v in -1000.0f64..1000.0, big in 3e5f64..5e5, nan_axis in 0usize..2,
    ) {
        let gains = Gains::<Fixed32>::alpha_beta_f64(0.5, 0.3).unwrap();
        let dt = Interval::from_f64_lossy(1.0);
        let step = StepGains::new(&gains, dt).unwrap();
        let l = Length::from_f64_lossy;
        let mut f = Cartesian::<Fixed32, 2, 2>::new();
        f.update_step([l(x0), l(-x0)], &step).unwrap();
        f.update_step([l(x0 + v), l(-x0 - v)], &step).unwrap();
        let before = f;
        // A residual beyond the format (z far from the prediction): refused.
        let mut z = [l(x0 + 2.0 * v), l(-x0 - 2.0 * v)];
        z[nan_axis] = l(if x0 > 0.0 { -big } else { big });
        let result = f.update_step(z, &step);
        if result.is_err() {
            prop_assert_eq!(result, Err(FilterError::Saturated));
            prop_assert_eq!(f.saturations(), before.saturations() + 1);
            prop_assert_eq!(f.axes()[1], before.axes()[1]);
            prop_assert_eq!(f.axes()[0].position(), before.axes()[0].position());
            prop_assert_eq!(f.axes()[0].velocity(), before.axes()[0].velocity());
            prop_assert_eq!(f.axes()[0].last_innovation(), before.axes()[0].last_innovation());
        }
        // A sentinel measurement: refused, not counted.
        let mut z = [l(x0), l(-x0)];
        z[nan_axis] = Length::MAX;
        let snapshot = f;
        prop_assert_eq!(f.update_step(z, &step), Err(FilterError::InvalidMeasurement));
        prop_assert_eq!(f, snapshot);
    }
}

/// Zero is an exact scaled number whatever multiplies it, including in the
/// guarded hot path (an αβ schedule's γ = 0 on an αβγ filter).
#[test]
fn zero_gain_products_are_exact() {
    let zero = Ratio::ZERO;
    assert_eq!((zero * Length::from_f64_lossy(123.0)).to_bits(), 0);
    let mut g = G::default();
    let a = Acceleration::from_f64_lossy(1.5).add_product(
        zero.cast::<abtrack::num::scaled::unit::PerSecondSquared>(),
        Length::from_f64_lossy(-4000.0),
        &mut g,
    );
    assert!(g.passed());
    assert_eq!(a, Acceleration::from_f64_lossy(1.5));
    // An αβγ filter with αβ gains: the acceleration stays zero.
    let gains = Gains::<Fixed32>::alpha_beta_f64(0.5, 0.3).unwrap();
    let mut f = KinematicFilter::<Fixed32, 3>::new();
    for (i, z) in [0.0, 10.0, 21.0, 33.0].iter().enumerate() {
        let r = f.update(
            Length::from_f64_lossy(*z),
            Interval::from_f64_lossy(1.0),
            &gains,
        );
        assert!(r.is_ok(), "update {i}: {r:?}");
    }
    assert_eq!(f.acceleration(), Acceleration::ZERO);
}

/// Least-squares gains from integer ratios are within one unit of the last
/// place of the exact ratio.
#[test]
fn least_squares_gains_from_integers() {
    for n in [3u32, 4, 10, 100, 1000, 10_000, 1 << 20] {
        let a: Ratio = abtrack::gains::least_squares_alpha(n);
        let b: Ratio = abtrack::gains::least_squares_beta(n);
        let nf = f64::from(n);
        let ea = 2.0 * (2.0 * nf - 1.0) / (nf * (nf + 1.0));
        let eb = 6.0 / (nf * (nf + 1.0));
        assert!((a.to_f64() - ea).abs() <= ea * 2f64.powi(-30), "alpha({n})");
        assert!((b.to_f64() - eb).abs() <= eb * 2f64.powi(-30), "beta({n})");
    }
}

/// The per-interval gains are formed once with 2⁻³⁰ relative precision,
/// over the whole envelope of β/T (2.5·10⁻⁶ to 80 /s).
#[test]
fn step_gains_keep_relative_precision() {
    for (beta, dt) in [(5e-5, 20.0), (0.3, 1.0), (3.9, 0.05), (6e-8, 20.0)] {
        let gains = Gains::<Fixed32>::alpha_beta_f64(0.01, beta).unwrap();
        let t = Interval::from_f64_lossy(dt);
        let step = StepGains::new(&gains, t).unwrap();
        let exact = gains.beta().to_f64() / t.to_f64();
        let got = step.velocity_gain().to_f64();
        assert!(
            (got - exact).abs() <= exact * 2f64.powi(-29),
            "beta {beta} dt {dt}: {got} vs {exact}"
        );
    }
}

/// `seconds_from_ms`'s integer route gives the `f64` route's word (the
/// default method's, which it replaces) for every quantity's format, over
/// the table clock's whole range of intervals and beyond each format's
/// range (the sentinel).
#[test]
fn seconds_from_ms_matches_the_f64_route() {
    fn check<Q: Quantity + core::fmt::Debug>() {
        let via_f64 = |ms: u32| Q::from_f64_lossy(f64::from(ms) / 1000.0);
        let mut ms_values: Vec<u32> = (0..=100_000).collect();
        ms_values.extend((0..=32).map(|k| 1u32 << k).filter(|&m| m > 0));
        ms_values.extend([u32::MAX, u32::MAX - 1, 3_600_000, 86_400_000]);
        for ms in ms_values {
            assert_eq!(Q::seconds_from_ms(ms), via_f64(ms), "{ms} ms");
        }
    }
    check::<Interval>();
    check::<Length>();
    check::<Speed>();
    check::<Acceleration>();
    check::<Gain>();
}
