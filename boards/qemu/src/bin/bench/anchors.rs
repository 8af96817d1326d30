//! Anchors measured beside abtrack: the floor (the least a 2-D αβ update
//! can cost), in every number system; a hand-written per-axis
//! constant-velocity Kalman filter in f32 and the fast fixed point's wide
//! format (in Q32.32 it alone took 18 KiB of the micro:bit's flash); and the
//! nearest-neighbour scan a user would write around it, beside the track
//! table's scan. `minikalman` is in [`crate::minikalman`].

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

/// Whether an anchor's estimate `e` is within [`DIVERGED_M`] of `z`.
#[inline(never)]
fn near(e: f64, z: f64) -> bool {
    libm::fabs(e - z) < DIVERGED_M
}

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
    let [x, y] = position(filter);
    bench.check(
        near(x.to_f64(), target.xs[last].to_f64()) && near(y.to_f64(), target.ys[last].to_f64()),
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

impl<S: Scalar> AxisKalmanModel<S> {
    /// The constants for interval `t` (s), white-acceleration density `q`
    /// (m²/s³) and measurement σ `sigma` (m).
    fn new(t: f64, q: f64, sigma: f64) -> Self {
        let c = |v: f64| <S as abtrack::Quantity>::from_f64_lossy(v);
        AxisKalmanModel {
            interval: c(t),
            interval_squared: c(t * t),
            q_position: c(q * t * t * t / 3.0),
            q_cross: c(q * t * t / 2.0),
            q_velocity: c(q * t),
            measurement_variance: c(sigma * sigma),
        }
    }
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
    /// Predict: x + T·v and P = F·P·Fᵀ + Q with F = [1, T; 0, 1].
    #[inline(always)]
    fn predicted(&self, m: &AxisKalmanModel<S>) -> Self {
        let t = m.interval;
        AxisKalman {
            position: self.position + t * self.velocity,
            velocity: self.velocity,
            p_xx: self.p_xx + (t + t) * self.p_xv + m.interval_squared * self.p_vv + m.q_position,
            p_xv: self.p_xv + t * self.p_vv + m.q_cross,
            p_vv: self.p_vv + m.q_velocity,
        }
    }

    /// The scalar update of a predicted axis with H = [1, 0] and innovation
    /// variance `innovation_variance` (p_xx + R): one division per gain.
    #[inline(always)]
    fn correct(&mut self, z: S, innovation_variance: S) {
        let k_x = self.p_xx / innovation_variance;
        let k_v = self.p_xv / innovation_variance;
        let residual = z - self.position;
        self.position = self.position + k_x * residual;
        self.velocity = self.velocity + k_v * residual;
        self.p_vv = self.p_vv - k_v * self.p_xv;
        self.p_xv = (S::ONE - k_x) * self.p_xv;
        self.p_xx = (S::ONE - k_x) * self.p_xx;
    }

    /// Predict, then the update: one division per gain.
    #[inline(always)]
    fn update(&mut self, z: S, m: &AxisKalmanModel<S>) {
        let mut predicted = self.predicted(m);
        predicted.correct(z, predicted.p_xx + m.measurement_variance);
        *self = predicted;
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
    let model = black_box(AxisKalmanModel::new(1.0, 1.0, 25.0));
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

// ---------------------------------------------------------------------------
// A hand-written nearest-neighbour scan
// ---------------------------------------------------------------------------

/// The hand-written scan's row.
pub const NEAREST_NEIGHBOUR_SCAN: &str = "axis_kalman_nn_scan_separated";

/// `axis_kalman_nn_scan_separated`: the scan a user would write around the
/// hand-written Kalman filter above, on the track table's separated scene
/// (`scan_default_separated`'s measurements, gate σ and G): for each track
/// in turn, predict both axes, test every measurement not yet taken
/// (brute force) on the normalised distance squared dx²/S_x + dy²/S_y ≤ G
/// and update with the nearest, or coast. No measurement checks, no
/// assignment (the first track to reach a measurement takes it), no track
/// starts or deletions, no counts: what the table does beyond this is
/// what its figure costs beyond this row's.
#[cfg(not(abtrack_board = "microbit"))]
#[inline(never)]
pub fn nearest_neighbour_scan<S>(bench: &mut Bench)
where
    S: Scalar + crate::numeric::BenchNumber,
{
    nearest_neighbour_scene::<S>(bench, 16);
    #[cfg(not(feature = "bench-smoke"))]
    nearest_neighbour_scene::<S>(bench, 32);
    #[cfg(not(feature = "bench-smoke"))]
    nearest_neighbour_scene::<S>(bench, 64);
}

#[cfg(not(abtrack_board = "microbit"))]
/// One track of the hand-written scan: its x and y filters.
type AxisTrack<S> = [AxisKalman<S>; 2];

/// One scan of [`nearest_neighbour_scan`], on slices (one copy of the code for
/// every size): returns the number of tracks updated.
#[cfg(not(abtrack_board = "microbit"))]
#[inline(never)]
fn nearest_neighbour_step<S: Scalar>(
    tracks: &mut [AxisTrack<S>],
    z: &[[S; 2]],
    taken: &mut [bool],
    m: &AxisKalmanModel<S>,
    gate: S,
) -> usize {
    taken.fill(false);
    let mut updated = 0;
    for track in tracks.iter_mut() {
        // Axis by axis in loops: one copy of the filter's code (the
        // micro:bit's flash).
        let mut predicted = *track;
        let mut inverse = [S::ONE; 2];
        for (axis, i) in predicted.iter_mut().zip(inverse.iter_mut()) {
            *axis = axis.predicted(m);
            *i = S::ONE / (axis.p_xx + m.measurement_variance);
        }
        let [(px, ix), (py, iy)] = [
            (predicted[0].position, inverse[0]),
            (predicted[1].position, inverse[1]),
        ];
        let (mut nearest, mut least) = (None, gate);
        for (k, ([zx, zy], used)) in z.iter().zip(taken.iter()).enumerate() {
            if *used {
                continue;
            }
            let (dx, dy) = (*zx - px, *zy - py);
            let d2 = dx * dx * ix + dy * dy * iy;
            if d2 <= least {
                (nearest, least) = (Some(k), d2);
            }
        }
        if let Some(k) = nearest {
            if let (Some(zk), Some(used)) = (z.get(k), taken.get_mut(k)) {
                *used = true;
                for (axis, zi) in predicted.iter_mut().zip(zk) {
                    let innovation_variance = axis.p_xx + m.measurement_variance;
                    axis.correct(*zi, innovation_variance);
                }
                updated += 1;
            }
        }
        *track = predicted;
    }
    updated
}

/// The most tracks (and measurements) of [`nearest_neighbour_scene`].
#[cfg(not(abtrack_board = "microbit"))]
const NEAREST_NEIGHBOUR_CAPACITY: usize = 64;

/// The scene at `targets` tracks and measurements (at most
/// [`NEAREST_NEIGHBOUR_CAPACITY`]; one copy of the code for every size):
/// the tracks started from the scene's two noise-free first scans (the
/// two-point start: P = R·[1, 1/T; 1/T, 2/T²]), the next scans run as the
/// table's warm-up (timed, their times not counted), then
/// [`crate::scan::TIMED_SCANS`] scans timed one by one. Each scan must update
/// every track, and each track must end within [`DIVERGED_M`] of its own
/// target's last measurement (the targets are 2 km apart: a track led to
/// another target's measurements fails it).
#[cfg(not(abtrack_board = "microbit"))]
#[inline(never)]
fn nearest_neighbour_scene<S>(bench: &mut Bench, targets: usize)
where
    S: Scalar + crate::numeric::BenchNumber,
{
    use crate::scan::{Scene, GATE_SIGMA_M, GATE_THRESHOLD, TIMED_SCANS, WARM_UP_SCANS};
    const CAPACITY: usize = NEAREST_NEIGHBOUR_CAPACITY;
    let numeric = S::LABEL;
    // At most CAPACITY: in bounds (and the row says what was measured).
    let targets = targets.min(CAPACITY);
    let size = crate::counter::Size {
        n: targets,
        m: targets,
    };
    let c = |v: f64| <S as abtrack::Quantity>::from_f64_lossy(v);
    let zero = <S as abtrack::Quantity>::ZERO;
    let (t, r) = (1.0, GATE_SIGMA_M * GATE_SIGMA_M);
    let model = black_box(AxisKalmanModel::new(t, 1.0, GATE_SIGMA_M));
    let gate = black_box(c(GATE_THRESHOLD));
    let mut rng = crate::synth::Lcg::new(5);
    let mut z = [[zero; 2]; CAPACITY];
    let mut scan = |k: u32, z: &mut [[S; 2]; CAPACITY]| {
        for (i, zi) in z.iter_mut().take(targets).enumerate() {
            let (x, y) = Scene::Separated.position(k, i, targets, &mut rng);
            *zi = [c(x), c(y)];
        }
    };
    let axis = AxisKalman {
        position: zero,
        velocity: zero,
        p_xx: c(r),
        p_xv: c(r / t),
        p_vv: c(2.0 * r / (t * t)),
    };
    let mut tracks = [[axis; 2]; CAPACITY];
    let mut taken = [false; CAPACITY];
    let (tracks, taken) = (&mut tracks[..targets], &mut taken[..targets]);
    let (mut scan_ticks, mut empty_ticks) = (0u32, 0u32);
    // Scans 0 and 1 start the tracks (the velocity from their difference),
    // the warm-up's scans follow, then the timed ones (the warm-up's times
    // not counted); every scan after the start must time and update every
    // track.
    let mut every_track_updated = true;
    for k in 0..WARM_UP_SCANS + TIMED_SCANS {
        scan(k, &mut z);
        let measured = &z[..targets];
        if k < 2 {
            for (track, zi) in tracks.iter_mut().zip(measured) {
                for (a, zi) in track.iter_mut().zip(zi) {
                    a.velocity = (*zi - a.position) / c(t);
                    a.position = *zi;
                }
            }
            continue;
        }
        let mut updated = 0;
        let ticks = bench.time(|| {
            updated = black_box(nearest_neighbour_step(
                tracks,
                black_box(measured),
                taken,
                &model,
                gate,
            ));
        });
        let empty = bench.time(|| {
            black_box(black_box(measured));
        });
        every_track_updated &= updated == targets && ticks.is_some() && empty.is_some();
        if k >= WARM_UP_SCANS {
            scan_ticks += ticks.unwrap_or(0);
            empty_ticks += empty.unwrap_or(0);
        }
    }
    // Each track on its own target: within DIVERGED_M of the target's last
    // measurement.
    let on_own_target = tracks.iter().zip(&z).all(|(track, zi)| {
        track
            .iter()
            .zip(zi)
            .all(|(a, z)| near(a.position.to_f64(), z.to_f64()))
    });
    if !(every_track_updated && on_own_target) {
        bench.fail(
            numeric,
            NEAREST_NEIGHBOUR_SCAN,
            "a scan missed a track or its time, or a track left its target",
        );
        return;
    }
    let net = scan_ticks.saturating_sub(empty_ticks);
    let per_scan = bench.instructions(net) / TIMED_SCANS as f64;
    bench.figure(numeric, NEAREST_NEIGHBOUR_SCAN, Some(size), per_scan);
}
