//! Each schedule's gain sequence against values computed by hand, in f64,
//! f32 and Q32.32. The tolerance per representation covers the rounding of
//! the handful of operations that produce one gain (not accumulation):
//! 1e-12 for f64, 1e-6 for f32 (≈ 16 ulp at 1), 1e-8 for fixed (≈ 40 steps
//! of 2⁻³²).

use super::support;

use abtrack::filter::Phase;
use abtrack::gain::al_wagih::{
    FixedAlphaConfig, LeastSquaresConfig, LinearCombinationConfig, MovingWindowConfig,
};
use abtrack::gain::li::LiImprovedConfig;
use abtrack::gain::liu::{
    AdaptiveSwitchConfig, ResidualAccumulationConfig, ScanCountAdjustedConfig,
};
use abtrack::gain::{
    AdaptiveSwitchGains, FirmnessGains, FixedGains, GainSchedule, LeastSquaresGains,
    LiImprovedGains, LinearCombinationGains, MovingWindowGains, ResidualAccumulationGains,
    ScanCountAdjustedGains, ScheduleError, ScheduledFilter, SwitchMode,
};
use abtrack::{Fix, Gains, Scalar};
use support::{abg, assert_close, context};

fn tol<S: Scalar>() -> f64 {
    match S::NAME {
        "f64" => 1e-12,
        "f32" => 1e-6,
        _ => 1e-8,
    }
}

fn check_ab<S: Scalar>(g: &Gains<S>, alpha: f64, beta: f64, what: &str) {
    let (a, b, _) = abg(g);
    assert_close(a, alpha, tol::<S>(), &format!("{} alpha {what}", S::NAME));
    assert_close(b, beta, tol::<S>(), &format!("{} beta {what}", S::NAME));
}

/// Gains of `schedule` for the context, then accept it.
fn step<S: Scalar, G: GainSchedule<S, D>, const D: usize>(
    schedule: &mut G,
    ctx: &abtrack::gain::GainContext<S, D>,
) -> [Gains<S>; D] {
    let g = schedule.gains(ctx).expect("gains");
    schedule.accepted(ctx, &g);
    g
}

macro_rules! for_all_representations {
    ($($name:ident => $body:ident;)*) => {
        $(
            mod $name {
                use super::*;
                #[test]
                fn f64() { $body::<f64>() }
                #[test]
                fn f32() { $body::<f32>() }
                #[test]
                fn fixed() { $body::<Fix>() }
            }
        )*
    };
}

for_all_representations! {
    m1 => m1_gains;
    least_squares => least_squares_sequence;
    least_squares_through_filter => least_squares_through_filter;
    m3_fixed_weight => m3_fixed_weight;
    m3_window_search => m3_window_search;
    m4_window_search => m4_window_search;
    li => li_sequence;
    li_bearing => li_bearing_error;
    liu_count_adjusted => liu_count_adjusted;
    liu_fixed => liu_fixed;
    liu_residual => liu_residual;
    liu_adaptive => liu_adaptive;
    tcas => tcas_firmness;
}

fn m1_gains<S: Scalar>() {
    // β = α²/(2 − α): 0.05² / 1.95 = 0.0025/1.95 = 0.00128205128…
    let m1 = FixedGains::<S>::from_m1_config(&FixedAlphaConfig { alpha: 0.05 }).unwrap();
    check_ab(&m1.fixed(), 0.05, 0.0025 / 1.95, "m1 0.05");
    // 0.3² / 1.7 = 0.09/1.7 = 0.0529411…
    let m1 = FixedGains::<S>::from_m1_config(&FixedAlphaConfig { alpha: 0.3 }).unwrap();
    check_ab(&m1.fixed(), 0.3, 0.09 / 1.7, "m1 0.3");
    // Eq. (23a) bounds α̃ to (0, 1].
    assert!(FixedGains::<S>::from_m1_config(&FixedAlphaConfig { alpha: 1.2 }).is_err());
    assert!(FixedGains::<S>::from_m1_config(&FixedAlphaConfig { alpha: 0.0 }).is_err());
}

fn least_squares_sequence<S: Scalar>() {
    let mut ls = LeastSquaresGains::new(&LeastSquaresConfig::DEFAULT).unwrap();
    // α(n) = 2(2n−1)/(n(n+1)), β(n) = 6/(n(n+1)):
    // n=3: 10/12 = 5/6, 6/12 = 1/2; n=4: 14/20 = 0.7, 6/20 = 0.3;
    // n=5: 18/30 = 0.6, 6/30 = 0.2; n=10: 38/110 = 0.3454…, 6/110 = 0.0545…
    let expected = [
        (3, 5.0 / 6.0, 0.5),
        (4, 0.7, 0.3),
        (5, 0.6, 0.2),
        (10, 38.0 / 110.0, 6.0 / 110.0),
        // n = 1000 = n_max: 3998/1 001 000, 6/1 001 000.
        (1000, 3998.0 / 1_001_000.0, 6.0 / 1_001_000.0),
        // Beyond n_max the gains stay at n_max's.
        (5000, 3998.0 / 1_001_000.0, 6.0 / 1_001_000.0),
        // A context with n < 3 (a handed-over track) is treated as n = 3.
        (1, 5.0 / 6.0, 0.5),
    ];
    for (n, a, b) in expected {
        let g = step::<S, _, 2>(&mut ls, &context(n, 1.0, [0.0; 2], [1.0; 2]));
        check_ab(&g[0], a, b, &format!("least squares n={n}"));
        assert_eq!(g[0], g[1], "same gains on both axes");
    }
}

fn least_squares_through_filter<S: Scalar>() {
    // Through ScheduledFilter: measurements 1 and 2 initialise (no gains),
    // the third is the first filtered update with n = 3 (α = 5/6, β = 1/2).
    let mut track: ScheduledFilter<S, LeastSquaresGains, 2, 2> =
        ScheduledFilter::new(LeastSquaresGains::default());
    let dt = S::ONE;
    let z = |x: f64| [S::from_f64_lossy(x), S::from_f64_lossy(2.0 * x)];
    assert!(track.update(z(0.0), dt).unwrap().gains.is_none());
    assert!(track.update(z(10.0), dt).unwrap().gains.is_none());
    let g3 = track.update(z(20.0), dt).unwrap().gains.unwrap();
    check_ab(&g3[0], 5.0 / 6.0, 0.5, "n=3");
    let g4 = track.update(z(30.0), dt).unwrap().gains.unwrap();
    check_ab(&g4[1], 0.7, 0.3, "n=4");
    assert_eq!(track.measurements(), 4);
    // A coast does not advance n: the next update is n = 5.
    track.coast(dt).unwrap();
    let g5 = track.update(z(50.0), dt).unwrap().gains.unwrap();
    check_ab(&g5[0], 0.6, 0.2, "n=5 after a coast");
}

fn m3_fixed_weight<S: Scalar>() {
    // α0 = 0.05: β̃ = 0.0025/1.95 = 0.00128205; w = 0.5:
    // n=3: α = 5/6, β = 0.5·0.00128205 + 0.5·0.5 = 0.25064103
    // n=4: α = 0.7,  β = 0.5·0.00128205 + 0.5·0.3 = 0.15064103
    let cfg = LinearCombinationConfig {
        w: 0.5,
        steps: 0,
        ..LinearCombinationConfig::DEFAULT
    };
    let mut m3 = LinearCombinationGains::<S, 2, 8>::new(&cfg).unwrap();
    let bt = 0.0025 / 1.95;
    let g = step(&mut m3, &context(3, 1.0, [0.0; 2], [3.0, -4.0]));
    check_ab(&g[0], 5.0 / 6.0, 0.5 * bt + 0.25, "m3 n=3");
    let g = step(&mut m3, &context(4, 1.0, [0.0; 2], [30.0, -40.0]));
    check_ab(&g[1], 0.7, 0.5 * bt + 0.15, "m3 n=4");
    // w = 1 is M1's β with M2's α; w = 0 is M2.
    for (w, n, b) in [(1.0, 3, bt), (0.0, 3, 0.5)] {
        let cfg = LinearCombinationConfig {
            w,
            steps: 0,
            ..LinearCombinationConfig::DEFAULT
        };
        let m3 = LinearCombinationGains::<S, 1, 8>::new(&cfg).unwrap();
        let g = m3.gains(&context(n, 1.0, [0.0], [1.0])).unwrap();
        check_ab(&g[0], 5.0 / 6.0, b, &format!("m3 w={w}"));
    }
}

fn m3_window_search<S: Scalar>() {
    // Two candidate weights (steps = 2: w ∈ {0, 1}), window L = 2,
    // α0 = 0.5 → β̃ = 0.25/1.5 = 1/6, initial w = 0.5.
    let cfg = LinearCombinationConfig {
        alpha0: 0.5,
        w: 0.5,
        steps: 2,
        window: 2,
        n_max: 1000,
    };
    let mut m3 = LinearCombinationGains::<S, 1, 4>::new(&cfg).unwrap();
    let ctx = |n, p: f64, v: f64, z: f64| {
        let mut c = context::<S, 1>(n, 1.0, [p], [z - p]);
        c.axes[0].predicted_velocity = S::from_f64_lossy(v);
        c
    };
    // n=3 (window not yet full): α = 5/6, β = 0.5·(1/6) + 0.5·0.5 = 1/3.
    let g = step(&mut m3, &ctx(3, 0.0, 0.0, 10.0));
    check_ab(&g[0], 5.0 / 6.0, 1.0 / 3.0, "m3 n=3");
    // n=4, still w = 0.5: α = 0.7, β = 0.5/6 + 0.5·0.3 = 0.2333…
    let g = step(&mut m3, &ctx(4, 18.0, 2.0, 20.0));
    check_ab(&g[0], 0.7, 0.5 / 6.0 + 0.15, "m3 n=4");
    // The window (n=3: x_p 0, v_p 0, e 10; n=4: z 20) is now full. Re-run
    // from x_p = 0, v_p = 0 with the n=3 gains α = 5/6:
    //   w=0: β = 1/2: x = 8.333, v = 5,     x_p(4) = 13.333, e = 6.667, e² = 44.4
    //   w=1: β = 1/6: x = 8.333, v = 1.667, x_p(4) = 10,     e = 10,    e² = 100
    // → w = 0: n=5 takes M2's gains α = 0.6, β = 0.2.
    assert_close(m3.weights()[0].to_f64(), 0.0, 0.0, "w after window 1");
    let g = step(&mut m3, &ctx(5, 0.0, 0.0, 21.0));
    check_ab(&g[0], 0.6, 0.2, "m3 n=5");
    // Window now (n=4: x_p 18, v_p 2, e 2; n=5: z 21). Re-run with the n=4
    // gains α = 0.7: x = 18 + 0.7·2 = 19.4,
    //   w=0: β = 0.3: v = 2.6,    x_p = 22.0,    e = −1,      e² = 1
    //   w=1: β = 1/6: v = 2.333,  x_p = 21.733,  e = −0.733,  e² = 0.538
    // → w = 1: n=6 takes α = 2·11/42 = 0.5238, β = β̃ = 1/6.
    assert_close(m3.weights()[0].to_f64(), 1.0, 0.0, "w after window 2");
    let g = m3.gains(&ctx(6, 0.0, 0.0, 0.0)).unwrap();
    check_ab(&g[0], 22.0 / 42.0, 1.0 / 6.0, "m3 n=6");
}

fn m4_window_search<S: Scalar>() {
    // Grid α ∈ {0.2, 0.8} (β = 0.04/1.8 = 0.0222, 0.64/1.2 = 0.5333),
    // window L = 2, α0 = 0.5 (β0 = 0.25/1.5 = 0.1667).
    let cfg = MovingWindowConfig {
        alpha0: 0.5,
        alpha_min: 0.2,
        alpha_max: 0.8,
        steps: 2,
        window: 2,
    };
    let mut m4 = MovingWindowGains::<S, 1, 4>::new(&cfg).unwrap();
    let ctx = |n, p: f64, v: f64, z: f64| {
        let mut c = context::<S, 1>(n, 1.0, [p], [z - p]);
        c.axes[0].predicted_velocity = S::from_f64_lossy(v);
        c
    };
    let b0 = 0.25 / 1.5;
    let g = step(&mut m4, &ctx(3, 0.0, 0.0, 10.0));
    check_ab(&g[0], 0.5, b0, "m4 first");
    let g = step(&mut m4, &ctx(4, 18.0, 2.0, 20.0));
    check_ab(&g[0], 0.5, b0, "m4 until the window fills");
    // Window (x_p 0, v_p 0, e 10; z 20):
    //   α=0.2: x = 2, v = 0.222, x_p = 2.222,  e = 17.78, e² = 316
    //   α=0.8: x = 8, v = 5.333, x_p = 13.333, e = 6.667, e² = 44.4 → 0.8
    let g = step(&mut m4, &ctx(5, 0.0, 0.0, 20.5));
    check_ab(&g[0], 0.8, 0.64 / 1.2, "m4 after window 1");
    // Window (x_p 18, v_p 2, e 2; z 20.5):
    //   α=0.2: x = 18.4, v = 2.0444, x_p = 20.444, e = 0.0556, e² = 0.0031
    //   α=0.8: x = 19.6, v = 3.0667, x_p = 22.667, e = −2.167, e² = 4.69 → 0.2
    let g = m4.gains(&ctx(6, 0.0, 0.0, 0.0)).unwrap();
    check_ab(&g[0], 0.2, 0.04 / 1.8, "m4 after window 2");
    // Reset returns to α0.
    m4.reset();
    let g = m4.gains(&ctx(3, 0.0, 0.0, 0.0)).unwrap();
    check_ab(&g[0], 0.5, b0, "m4 after reset");
}

fn li_sequence<S: Scalar>() {
    // R = 3, Δρ = 1 m, Δθ = 0: Δd = λ = √α(k).
    let mut li = LiImprovedGains::<S>::new(&LiImprovedConfig::DEFAULT).unwrap();
    // k = 3: α = 5/6, β = 2(1 − √(1 − 5/6))² = 2(1 − 0.408248)² = 0.700340
    // k = 4: α = 0.7, β = 2(1 − √0.3)² = 2(0.452277)² = 0.409110
    // k = 5: α = 0.6, β = 2(1 − √0.4)² = 2(0.367544)² = 0.270178
    let steady = |n| context::<S, 2>(n, 1.0, [100.0, 0.0], [0.3, 0.4]);
    // d = 0.5, r = 0.5/√α ≤ 0.56 ≤ 3: steady, k + 1 each time.
    for (n, a, b) in [
        (3, 5.0 / 6.0, 0.7003401714778815),
        (4, 0.7, 0.4091097699793354),
        (5, 0.6, 0.2701778718652965),
    ] {
        let g = step(&mut li, &steady(n));
        check_ab(&g[0], a, b, &format!("li k={n}"));
        assert_eq!(g[0], g[1]);
    }
    assert_eq!(li.count(), 6);
    // Up to k = 20: α = 78/420 = 0.185714, λ = 0.430946.
    for n in 6..20 {
        step(&mut li, &steady(n));
    }
    assert_eq!(li.count(), 20);
    assert_close(
        li.gate_scale().to_f64(),
        0.4309458036856673,
        tol::<S>(),
        "λ(20)",
    );
    // Innovation (1.8, 0): r = 1.8/0.430946 = 4.176859 > 3,
    // Δr = round((4.176859 − 3)·4.176859) = round(4.915576) = 5 → k = 15.
    let g = step(&mut li, &context(20, 1.0, [100.0, 0.0], [1.8, 0.0]));
    check_ab(&g[0], 78.0 / 420.0, 0.019060183461998458, "li k=20");
    assert_close(
        li.last_ratio().unwrap().to_f64(),
        4.176859328030314,
        1e3 * tol::<S>(),
        "r",
    );
    assert_eq!(li.count(), 15);
    // A large innovation drops the count to its floor 3, not below:
    // α(15) = 58/240, λ = 0.491596; d = 50 → r = 101.7, Δr = round(98.7·101.7) ≫ 12.
    step(&mut li, &context(21, 1.0, [100.0, 0.0], [30.0, 40.0]));
    assert_eq!(li.count(), 3);
    // r exactly 0 < R: +1.
    step(&mut li, &context(22, 1.0, [100.0, 0.0], [0.0, 0.0]));
    assert_eq!(li.count(), 4);
}

fn li_bearing_error<S: Scalar>() {
    // Δρ = 1 m, Δθ = 0.01 rad at predicted range ρ = ‖(300, 400)‖ = 500 m:
    // ρΔθ = 5 m, √(1 + 25) = 5.0990195; at k = 3, λ = √(5/6) = 0.9128709:
    // Δd = 4.6547467. Innovation (3, 4), d = 5: r = 1.0741697 ≤ 3 → k = 4.
    let cfg = LiImprovedConfig {
        bearing_error: 0.01,
        ..LiImprovedConfig::DEFAULT
    };
    let mut li = LiImprovedGains::<S>::new(&cfg).unwrap();
    assert_close(
        li.distance_error(S::from_f64_lossy(500.0)).to_f64(),
        0.9128709291752769 * 5.0990195135927845,
        1e2 * tol::<S>(),
        "Δd",
    );
    step(&mut li, &context(3, 1.0, [300.0, 400.0], [3.0, 4.0]));
    assert_close(
        li.last_ratio().unwrap().to_f64(),
        5.0 / (0.9128709291752769 * 5.0990195135927845),
        1e2 * tol::<S>(),
        "r",
    );
    assert_eq!(li.count(), 4);
    // Same innovation without the bearing term: Δd = λ(4) = √0.7 = 0.83666,
    // r = 5.976 > 3, Δr = round(2.976·5.976) = round(17.79) = 18 → floor 3.
    let mut li = LiImprovedGains::<S>::new(&LiImprovedConfig::DEFAULT).unwrap();
    step(&mut li, &context(3, 1.0, [300.0, 400.0], [0.0, 0.0]));
    step(&mut li, &context(4, 1.0, [300.0, 400.0], [3.0, 4.0]));
    assert_eq!(li.count(), 3);
}

fn liu_count_adjusted<S: Scalar>() {
    let mut s = ScanCountAdjustedGains::<S>::new(&ScanCountAdjustedConfig::DEFAULT).unwrap();
    // k starts at 2 (two initialisation scans); each filtered scan moves it
    // ±1 by its own innovation (70 m on either axis), within 3..=1000.
    let ls = |k: f64| {
        (
            2.0 * (2.0 * k - 1.0) / (k * (k + 1.0)),
            6.0 / (k * (k + 1.0)),
        )
    };
    let cases: [([f64; 2], f64); 8] = [
        ([1.0, 1.0], 3.0),    // 2 + 1
        ([80.0, 0.0], 3.0),   // 3 − 1 = 2 → floor 3
        ([1.0, -1.0], 4.0),   // 3 + 1
        ([10.0, 5.0], 5.0),   // 4 + 1
        ([-71.0, 0.0], 4.0),  // |−71| > 70: 5 − 1
        ([0.0, 70.5], 3.0),   // y over: 4 − 1
        ([70.0, -70.0], 4.0), // exactly 70 is not "greater": + 1
        ([0.0, 0.0], 5.0),
    ];
    for (n, (e, k)) in (3u32..).zip(cases) {
        let g = step(&mut s, &context(n, 2.0, [0.0; 2], e));
        let (a, b) = ls(k);
        check_ab(&g[0], a, b, &format!("liu 2.1.2 k={k}"));
        assert_eq!(s.count() as f64, k);
    }
}

fn liu_fixed<S: Scalar>() {
    let f = FixedGains::<S>::liu().unwrap();
    check_ab(&f.fixed(), 0.5, 0.3, "liu 2.1.3");
}

fn liu_residual<S: Scalar>() {
    let mut r =
        ResidualAccumulationGains::<S, 2, 4>::new(&ResidualAccumulationConfig::DEFAULT).unwrap();
    // σ_m² = 25, n = 3; s = mean((V/5)²) over the current and up to two past
    // innovations; α = s/(1 + s), β = α²/(2 − α).
    // x: V = 5, 10, 0, 0 → (V/5)² = 1, 4, 0, 0
    //   s = 1 → α = 1/2, β = 0.25/1.5 = 0.166667
    //   s = (1+4)/2 = 2.5 → α = 2.5/3.5 = 0.714286, β = 0.396825
    //   s = (1+4+0)/3 = 5/3 → α = 0.625, β = 0.390625/1.375 = 0.284091
    //   s = (4+0+0)/3 = 4/3 → α = 4/7 = 0.571429, β = 0.228571
    // y: V = 0, 5, 5, 15 → 0, 1, 1, 9
    //   s = 0 → α = 0, held at α_min = 0.01, β = 0.0001/1.99 = 5.0251e-5
    //   s = 1/2 → α = 1/3, β = (1/9)/(5/3) = 1/15
    //   s = 2/3 → α = 0.4, β = 0.16/1.6 = 0.1
    //   s = 11/3 → α = 11/14 = 0.785714, β = 0.508403
    let cases = [
        ([5.0, 0.0], (0.5, 0.25 / 1.5), (0.01, 0.0001 / 1.99)),
        (
            [10.0, 5.0],
            (2.5 / 3.5, 0.39682539682539686),
            (1.0 / 3.0, 1.0 / 15.0),
        ),
        ([0.0, 5.0], (0.625, 0.2840909090909091), (0.4, 0.1)),
        (
            [0.0, 15.0],
            (4.0 / 7.0, 0.22857142857142854),
            (11.0 / 14.0, 0.5084033613445378),
        ),
    ];
    for (n, (e, (ax, bx), (ay, by))) in (3u32..).zip(cases) {
        let g = step(&mut r, &context(n, 2.0, [0.0; 2], e));
        check_ab(&g[0], ax, bx, &format!("liu 2.1.4 x n={n}"));
        check_ab(&g[1], ay, by, &format!("liu 2.1.4 y n={n}"));
    }
}

fn liu_adaptive<S: Scalar>() {
    let mut a = AdaptiveSwitchGains::<S, 2, 4>::new(&AdaptiveSwitchConfig::DEFAULT).unwrap();
    // (10, 5): both ≤ 19 → fixed 0.5, 0.3.
    let g = step(&mut a, &context(3, 2.0, [0.0; 2], [10.0, 5.0]));
    check_ab(&g[0], 0.5, 0.3, "steady x");
    check_ab(&g[1], 0.5, 0.3, "steady y");
    assert_eq!(a.last_mode(), Some(SwitchMode::Steady));
    // (25, 0): x > 19 → residual gains on both axes, with the window of
    // every accepted innovation: x (10/5)² = 4 and (25/5)² = 25 → s = 14.5,
    // α = 14.5/15.5 = 0.935484, β = 0.822092; y 1 and 0 → s = 0.5,
    // α = 1/3, β = 1/15.
    let g = step(&mut a, &context(4, 2.0, [0.0; 2], [25.0, 0.0]));
    check_ab(&g[0], 14.5 / 15.5, 0.8220918866080156, "manoeuvre x");
    check_ab(&g[1], 1.0 / 3.0, 1.0 / 15.0, "manoeuvre y");
    assert_eq!(a.last_mode(), Some(SwitchMode::Manoeuvre));
    // (19, −19): both ≤ 19 (eqs. 12–15 use ≤) → fixed.
    let g = step(&mut a, &context(5, 2.0, [0.0; 2], [19.0, -19.0]));
    check_ab(&g[0], 0.5, 0.3, "at the limit");
    // (0, −19.5): y over. x window 25, 14.44, current 0 → s = 13.146667,
    // α = 0.929312, β = 0.806604; y 0, 14.44, current 15.21 → s = 9.883333,
    // α = 0.908116, β = 0.755278.
    let g = step(&mut a, &context(6, 2.0, [0.0; 2], [0.0, -19.5]));
    check_ab(
        &g[0],
        0.9293119698397738,
        0.8066035231179727,
        "manoeuvre 2 x",
    );
    check_ab(
        &g[1],
        0.9081163859111792,
        0.7552777234857352,
        "manoeuvre 2 y",
    );
}

fn tcas_firmness<S: Scalar>() {
    // Through ScheduledFilter with an αβγ filter.
    let mut track: ScheduledFilter<S, FirmnessGains, 3, 1> =
        ScheduledFilter::new(FirmnessGains::new());
    let dt = S::ONE;
    let z = |x: f64| [S::from_f64_lossy(x)];
    let firmness = |t: &ScheduledFilter<S, FirmnessGains, 3, 1>| t.schedule().firmness();
    let check_abg = |g: &Gains<S>, e: (f64, f64, f64), what: &str| {
        let (a, b, c) = abg(g);
        assert_close(a, e.0, tol::<S>(), what);
        assert_close(b, e.1, tol::<S>(), what);
        assert_close(c, e.2, tol::<S>(), what);
    };
    // Reports 1, 2: firmness 0 and 1 are two-point initialisation.
    assert!(track.update(z(1000.0), dt).unwrap().gains.is_none());
    assert_eq!(firmness(&track), 1);
    assert!(track.update(z(990.0), dt).unwrap().gains.is_none());
    assert_eq!(firmness(&track), 2);
    // Report 3 uses entry 2, report 4 entry 3, …, and firmness saturates at 8.
    let table = [
        (0.83, 0.5, 0.16),
        (0.7, 0.3, 0.07),
        (0.6, 0.2, 0.035),
        (0.46, 0.11, 0.013),
        (0.4, 0.1, 0.01),
        (0.4, 0.1, 0.01),
        (0.4, 0.1, 0.01),
        (0.4, 0.1, 0.01),
    ];
    let mut x = 980.0;
    for (i, e) in table.iter().enumerate() {
        let g = track.update(z(x), dt).unwrap().gains.unwrap();
        check_abg(&g[0], *e, &format!("entry {}", i + 2));
        x -= 10.0;
    }
    assert_eq!(firmness(&track), 8);
    // A miss lowers firmness: 8 → 7, and the next report uses entry 7.
    track.coast(dt).unwrap();
    assert_eq!(firmness(&track), 7);
    x -= 10.0;
    let g = track.update(z(x), dt).unwrap().gains.unwrap();
    check_abg(&g[0], (0.4, 0.1, 0.01), "entry 7");
    // Seven misses: 8 → 1; a report then uses entry 1 (α = β = 1, γ = 0).
    for _ in 0..7 {
        track.coast(dt).unwrap();
    }
    assert_eq!(firmness(&track), 1);
    let u = track.update(z(800.0), dt).unwrap();
    check_abg(
        &u.gains.unwrap()[0],
        (1.0, 1.0, 0.0),
        "entry 1 on a tracking filter",
    );
    assert!(!u.restarted);
    // Entry 1 puts the position on the report.
    assert_close(track.filter().position()[0].to_f64(), 800.0, 0.0, "α = 1");
    assert_eq!(firmness(&track), 2);
    // Two misses: firmness 0 → the next report restarts the track.
    track.coast(dt).unwrap();
    track.coast(dt).unwrap();
    assert_eq!(firmness(&track), 0);
    assert!(GainSchedule::<S, 1>::restart_required(
        track.schedule(),
        Phase::Tracking
    ));
    assert_eq!(
        GainSchedule::<S, 1>::gains(track.schedule(), &context(3, 1.0, [0.0], [0.0])),
        Err(ScheduleError::RestartRequired)
    );
    let u = track.update(z(700.0), dt).unwrap();
    assert!(u.restarted && u.gains.is_none());
    assert_eq!(track.filter().phase(), Phase::OnePoint);
    assert_eq!(track.measurements(), 1);
    assert_eq!(firmness(&track), 1);
}
