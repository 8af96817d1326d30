//! Shared by the gain tests: a seeded noise source, test scenarios, and
//! the error bound allowed between representations.

use abtrack::gain::spec::ScheduleSpec;
use abtrack::gain::{AnySchedule, GainContext, ScheduledFilter};
use abtrack::{Gains, Scalar};

/// Allowed |x_S − x_f64| for a filter run in representation `name` for
/// `steps` updates on positions of magnitude up to `scale` metres.
///
/// `src/budget.rs` (the project's error-budget function, written on another
/// branch) is not on main yet; this is our own budget, in one place:
///
/// * each update rounds at most 8 operations (predict 2, innovation 1,
///   position 2, velocity 3), each to within ε_S of the largest operand,
///   and the largest operand is at most `scale` (or 1 for gain-sized
///   operands): 8·ε_S·max(scale, 1) per update;
/// * the measurement's own conversion is one more rounding, counted in the 8;
/// * the filter is stable, so an error injected at one step is not
///   amplified; errors are budgeted to add up linearly over `steps`.
///
/// ε_f32 = 2⁻²⁴ (unit roundoff of round-to-nearest binary32),
/// ε_fixed = 2⁻³² (Q32.32's step; fixed-point rounding is absolute, so
/// measuring it against `scale` over-allows it, which we accept for one
/// formula). f64 itself (ε = 2⁻⁵³) is the reference and is neglected.
///
/// This bound holds only while the representations make the same discrete
/// choices (thresholds, argmins); the tests check those separately.
pub fn representation_bound(name: &str, scale: f64, steps: usize) -> f64 {
    let eps = match name {
        "f32" => 2f64.powi(-24),
        "q32" => 2f64.powi(-32),
        // The fast fixed point rounds positions to absolute steps of 2⁻¹²
        // m and its gains and rates to 2⁻³⁰ relative.
        "fixed" => 2f64.powi(-30) + 2f64.powi(-12) / scale.max(1.0),
        _ => 2f64.powi(-53),
    };
    8.0 * eps * scale.max(1.0) * steps as f64
}

/// xorshift64* with Box–Muller: reproducible Gaussian noise without a
/// dependency.
pub struct Noise(u64);

impl Noise {
    pub fn new(seed: u64) -> Self {
        Noise(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    pub fn gaussian(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

/// Liu, Wang & Yang's Table 1 scenario: start (533, 389) m, 150 m/s at
/// heading 45°, T = 2 s, 80 samples: 30 straight, 15 on a 9000 m radius
/// turn (left), then straight; Gaussian noise σ = 5 m per axis.
/// Returns (truth, measurements), T.
pub fn liu_turn(seed: u64) -> (Vec<[f64; 2]>, Vec<[f64; 2]>, f64) {
    let dt = 2.0;
    let speed = 150.0;
    let radius = 9000.0;
    let omega = speed / radius;
    let mut heading = std::f64::consts::FRAC_PI_4;
    let mut pos = [533.0, 389.0];
    let mut noise = Noise::new(seed);
    let mut truth = Vec::new();
    let mut meas = Vec::new();
    for k in 0..80 {
        if k > 0 {
            if (31..=45).contains(&k) {
                // Exact arc of the turn over one interval.
                let h1 = heading + omega * dt;
                pos[0] += radius * (h1.sin() - heading.sin());
                pos[1] -= radius * (h1.cos() - heading.cos());
                heading = h1;
            } else {
                pos[0] += speed * dt * heading.cos();
                pos[1] += speed * dt * heading.sin();
            }
        }
        truth.push(pos);
        meas.push([
            pos[0] + 5.0 * noise.gaussian(),
            pos[1] + 5.0 * noise.gaussian(),
        ]);
    }
    (truth, meas, dt)
}

/// Li et al.'s §5 scenario: 100 scans, T = 1 s, from (0, 0) m at (10, 5)
/// m/s, accelerations (2, 0) in scans 12–16, (0, 2) in 32–36, (0, −1.5) in
/// 53–73, (−1.5, 0) in 82–86; noise variance 1 per axis.
pub fn li_maneuver(seed: u64) -> (Vec<[f64; 2]>, Vec<[f64; 2]>, f64) {
    let dt = 1.0;
    let mut p = [0.0f64, 0.0];
    let mut v = [10.0f64, 5.0];
    let mut noise = Noise::new(seed);
    let mut truth = Vec::new();
    let mut meas = Vec::new();
    for k in 1..=100 {
        if k > 1 {
            let a = match k {
                12..=16 => [2.0, 0.0],
                32..=36 => [0.0, 2.0],
                53..=73 => [0.0, -1.5],
                82..=86 => [-1.5, 0.0],
                _ => [0.0, 0.0],
            };
            for i in 0..2 {
                p[i] += v[i] * dt + 0.5 * a[i] * dt * dt;
                v[i] += a[i] * dt;
            }
        }
        truth.push(p);
        meas.push([p[0] + noise.gaussian(), p[1] + noise.gaussian()]);
    }
    (truth, meas, dt)
}

/// Window capacity used by the tests' [`AnySchedule`].
pub const W: usize = 16;

pub type Track<N> = ScheduledFilter<N, AnySchedule<N, 2, W>, 2, 2>;

/// One step of a scheduled run, in f64 whatever the representation.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    pub position: [f64; 2],
    pub velocity: [f64; 2],
    /// (α, β) per axis, if the step was filtered.
    pub gains: Option<[(f64, f64); 2]>,
}

/// Runs `spec` on `meas` with an αβ filter in number system `N`.
pub fn run_scheduled<N: abtrack::Numeric>(spec: &str, meas: &[[f64; 2]], dt: f64) -> Vec<Step> {
    use abtrack::num::Quantity as Q;
    let spec = ScheduleSpec::parse(spec).expect("spec parses");
    let schedule = AnySchedule::<N, 2, W>::from_spec(&spec).expect("schedule builds");
    let mut track: Track<N> = ScheduledFilter::new(schedule);
    let dt_s = <N::Interval as Q>::try_from_f64(dt).unwrap();
    meas.iter()
        .map(|z| {
            let zs = z.map(|v| <N::Length as Q>::try_from_f64(v).unwrap());
            let u = track.update(zs, dt_s).expect("update accepted");
            Step {
                position: track.filter().position().map(Q::to_f64),
                velocity: track.filter().velocity().map(Q::to_f64),
                gains: u
                    .gains
                    .map(|g| g.map(|g| (Q::to_f64(g.alpha()), Q::to_f64(g.beta())))),
            }
        })
        .collect()
}

/// A context for driving a schedule directly: measurement n with the given
/// innovations, predictions at `predicted`, zero predicted velocity.
pub fn context<S: Scalar, const D: usize>(
    n: u32,
    dt: f64,
    predicted: [f64; D],
    innovation: [f64; D],
) -> GainContext<S, D> {
    let mut axes = [abtrack::gain::AxisObservation::<S>::default(); D];
    for i in 0..D {
        let p = S::try_from_f64(predicted[i]).unwrap();
        let e = S::try_from_f64(innovation[i]).unwrap();
        axes[i] = abtrack::gain::AxisObservation {
            measurement: p + e,
            predicted: p,
            predicted_velocity: S::ZERO,
            innovation: e,
        };
    }
    GainContext {
        n,
        dt: S::try_from_f64(dt).unwrap(),
        axes,
    }
}

/// (α, β, γ) in f64.
pub fn abg<N: abtrack::Numeric>(g: &Gains<N>) -> (f64, f64, f64) {
    use abtrack::num::Quantity as Q;
    (
        Q::to_f64(g.alpha()),
        Q::to_f64(g.beta()),
        Q::to_f64(g.gamma()),
    )
}

pub fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} (tolerance {tol})"
    );
}

/// Every spec the tests run, one per schedule (bank excluded).
pub const ALL_SCHEDULES: &[&str] = &[
    "fixed:alpha=0.6,beta=0.2",
    "m1:alpha=0.05",
    "m1:alpha=0.3",
    "least-squares",
    "m3",
    "m3:w=0.3,steps=0",
    "m4",
    "li-improved",
    "li-improved:r=2,range-error=5,bearing-error=0.002",
    "liu-count-adjusted",
    "liu-fixed",
    "liu-residual",
    "liu-adaptive",
    "tcas-firmness",
    "auto:sigma=5",
    "auto:range-sigma=5,bearing-sigma-deg=0.01",
];
