//! Anchors measured beside abtrack: the floor (the least a 2-D αβ update
//! can cost), in every number system, and a hand-written per-axis
//! constant-velocity Kalman filter in f32 (in Q32.32 it alone took 18 KiB of
//! the micro:bit's flash). `minikalman` is in [`crate::minikalman`].

use core::hint::black_box;

use abtrack::filter::StepGains;
use abtrack::num::{AddProduct, Quantity};
use abtrack::Scalar;

use crate::counter::Bench;
use crate::data::{at, PlaneRing};
use crate::numeric::BenchNumber;

/// Position error, m, beyond which an anchor counts as diverged: the inputs
/// have σ = 25 m of noise and a filter that follows them ends within a few σ
/// of the last one.
const DIVERGED_M: f64 = 150.0;

/// The 2-D anchors' target: the `ab2d_update` row's (σ = 25 m).
fn target<N: abtrack::Numeric>() -> PlaneRing<N> {
    PlaneRing::new(25.0)
}

/// Times `update` of `filter` on `target`, then checks that the anchor
/// followed it: its `position` must end within [`DIVERGED_M`] of the last
/// measurement it was given (call `CALLS − 1`).
fn per_anchor_call<N: abtrack::Numeric, F>(
    bench: &mut Bench,
    (numeric, operation): (&'static str, &'static str),
    target: &PlaneRing<N>,
    filter: &mut F,
    update: impl Fn(&mut F, [N::Length; 2]),
    position: impl Fn(&F) -> [N::Length; 2],
) {
    bench.per_call(
        numeric,
        operation,
        |k| update(filter, target.get(k)),
        |k| target.fetch(k),
    );
    let last = at(crate::CALLS - 1);
    let near = |e: N::Length, z: N::Length| libm::fabs(e.to_f64() - z.to_f64()) < DIVERGED_M;
    let [x, y] = position(filter);
    bench.check(
        near(x, target.xs[last]) && near(y, target.ys[last]),
        numeric,
        operation,
        "diverged",
    );
}

// ---------------------------------------------------------------------------
// The floor
// ---------------------------------------------------------------------------

/// The floor's constants, formed once: α, β/T and T, in the number
/// system's formats (the step gains' own: [`StepGains`]).
#[derive(Clone, Copy)]
struct FloorGains<N: abtrack::Numeric> {
    alpha: N::Gain,
    beta_over_interval: N::Rate,
    interval: N::Interval,
}

/// The floor: a 2-D αβ filter with nothing but its arithmetic (Al-Wagih &
/// Abdulla eqs. 4–8 with β/T precomputed): no input checks, no saturation
/// checks, no phases, nothing kept but position and velocity.
#[derive(Clone, Copy)]
struct FloorAlphaBeta<N: abtrack::Numeric> {
    x: N::Length,
    y: N::Length,
    vx: N::Speed,
    vy: N::Speed,
}

/// One axis: predict, residual, correct. The number system's fused
/// products (`q + a·b`, rounded once) are its cheapest arithmetic; the
/// guard they report to is never read, so its checks are compiled out.
#[inline(always)]
fn floor_axis<N: abtrack::Numeric>(
    position: &mut N::Length,
    velocity: &mut N::Speed,
    z: N::Length,
    g: &FloorGains<N>,
) {
    let mut unchecked = <N as abtrack::Numeric>::Guard::default();
    let guard = &mut unchecked;
    let predicted = position.add_product(*velocity, g.interval, guard);
    let residual = z.sub_guarded(predicted, guard);
    *position = predicted.add_product(g.alpha, residual, guard);
    *velocity = velocity.add_product(g.beta_over_interval, residual, guard);
}

/// The two axes written out and the measurement passed as two values (in
/// registers), so that nothing but the arithmetic and the state's loads and
/// stores is left.
#[inline(never)]
fn floor_update<N: abtrack::Numeric>(
    f: &mut FloorAlphaBeta<N>,
    zx: N::Length,
    zy: N::Length,
    g: &FloorGains<N>,
) {
    floor_axis(&mut f.x, &mut f.vx, zx, g);
    floor_axis(&mut f.y, &mut f.vy, zy, g);
}

/// `floor_ab2d_update`: the floor on the `ab2d_update` row's data and gains.
#[inline(never)]
pub fn floor<N: BenchNumber>(bench: &mut Bench) {
    const OPERATION: &str = "floor_ab2d_update";
    let numeric = N::LABEL;
    let interval = N::Interval::from_f64_lossy(1.0);
    let Some(step) =
        crate::filters::ab_gains::<N>().and_then(|g| StepGains::new(&g, interval).ok())
    else {
        bench.fail(numeric, OPERATION, "gains refused");
        return;
    };
    let constants = FloorGains::<N> {
        alpha: step.alpha(),
        beta_over_interval: step.velocity_gain(),
        interval,
    };
    let target = target::<N>();
    let mut filter = FloorAlphaBeta::<N> {
        x: target.xs[0],
        y: target.ys[0],
        vx: N::Speed::ZERO,
        vy: N::Speed::ZERO,
    };
    let constants = black_box(constants);
    per_anchor_call(
        bench,
        (numeric, OPERATION),
        &target,
        &mut filter,
        |f, [x, y]| floor_update(f, x, y, &constants),
        |f| [f.x, f.y],
    );
}

// ---------------------------------------------------------------------------
// A hand-written per-axis constant-velocity Kalman filter
// ---------------------------------------------------------------------------

/// Its constants, formed once: the interval T, the process noise of the
/// continuous white-noise acceleration model over T,
/// Q = q·[T³/3, T²/2; T²/2, T] (Bar-Shalom, Li & Kirubarajan, *Estimation
/// with Applications to Tracking and Navigation*, ch. 6), and the
/// measurement variance R.
#[derive(Clone, Copy)]
struct AxisKalmanModel<S> {
    interval: S,
    interval_squared: S,
    q_position: S,
    q_cross: S,
    q_velocity: S,
    measurement_variance: S,
}

/// One axis: state (x, v) and the symmetric covariance (p_xx, p_xv, p_vv).
#[derive(Clone, Copy)]
struct AxisKalman<S> {
    position: S,
    velocity: S,
    p_xx: S,
    p_xv: S,
    p_vv: S,
}

impl<S: Scalar> AxisKalman<S> {
    /// Predict P = F·P·Fᵀ + Q with F = [1, T; 0, 1], then the scalar update
    /// with H = [1, 0]: one division per axis.
    #[inline(always)]
    fn update(&mut self, z: S, m: &AxisKalmanModel<S>) {
        let t = m.interval;
        let x = self.position + t * self.velocity;
        let p_xx = self.p_xx + (t + t) * self.p_xv + m.interval_squared * self.p_vv + m.q_position;
        let p_xv = self.p_xv + t * self.p_vv + m.q_cross;
        let p_vv = self.p_vv + m.q_velocity;
        let innovation_variance = p_xx + m.measurement_variance;
        let k_x = p_xx / innovation_variance;
        let k_v = p_xv / innovation_variance;
        let residual = z - x;
        self.position = x + k_x * residual;
        self.velocity = self.velocity + k_v * residual;
        self.p_xx = (S::ONE - k_x) * p_xx;
        self.p_xv = (S::ONE - k_x) * p_xv;
        self.p_vv = p_vv - k_v * p_xv;
    }
}

/// Both axes, written out, the measurement in two scalars (as the floor).
#[inline(never)]
fn axis_kalman_update<S: Scalar>(
    x: &mut AxisKalman<S>,
    y: &mut AxisKalman<S>,
    zx: S,
    zy: S,
    m: &AxisKalmanModel<S>,
) {
    x.update(zx, m);
    y.update(zy, m);
}

/// `axis_kalman_cv2d_update`: two independent per-axis CV Kalman filters
/// (x and y), q = 1 m²/s³, σ = 25 m, on the `ab2d_update` row's data, as
/// a user would write them for `S`: f32, and the fast fixed point's
/// [`abtrack::ScaledScalar`] on every core (not Q32.32: it alone took
/// 18 KiB of the micro:bit's flash).
#[inline(never)]
pub fn axis_kalman<S>(bench: &mut Bench)
where
    S: Scalar + crate::numeric::BenchNumber,
{
    const OPERATION: &str = "axis_kalman_cv2d_update";
    let numeric = S::LABEL;
    let c = |v: f64| <S as abtrack::Quantity>::from_f64_lossy(v);
    let (t, q) = (1.0, 1.0);
    let model = black_box(AxisKalmanModel {
        interval: c(t),
        interval_squared: c(t * t),
        q_position: c(q * t * t * t / 3.0),
        q_cross: c(q * t * t / 2.0),
        q_velocity: c(q * t),
        measurement_variance: c(25.0 * 25.0),
    });
    let target = target::<S>();
    let start = |z: S| AxisKalman {
        position: z,
        velocity: <S as abtrack::Quantity>::ZERO,
        p_xx: c(625.0),
        p_xv: <S as abtrack::Quantity>::ZERO,
        p_vv: c(10_000.0),
    };
    let mut filter = [start(target.xs[0]), start(target.ys[0])];
    per_anchor_call(
        bench,
        (numeric, OPERATION),
        &target,
        &mut filter,
        |[x, y], [zx, zy]| axis_kalman_update(x, y, zx, zy, &model),
        |[x, y]| [x.position, y.position],
    );
}
