//! Anchors measured beside abtrack: the floor (the least a 2-D αβ update
//! can cost), in every number system; a hand-written per-axis
//! constant-velocity Kalman filter in f32 and the fast fixed point's wide
//! format (in Q32.32 it alone took 18 KiB of the micro:bit's flash); and the
//! nearest-neighbour scans a user would write, around that filter and in
//! integers around a fixed-gain αβ filter, beside the track table's scans.
//! `minikalman` is in [`crate::minikalman`].

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
// Hand-written nearest-neighbour scans
// ---------------------------------------------------------------------------

/// The hand-written scan around the hand-written Kalman filter.
pub const NEAREST_NEIGHBOUR_SCAN: &str = "axis_kalman_nn_scan_separated";
/// The hand-written scan in integers around a fixed-gain αβ filter.
pub const INTEGER_SCAN: &str = "integer_ab_nn_scan_separated";

/// A scan a user would write instead of the track table, on the table's
/// separated scene: for each track in turn, predict, test every measurement
/// not yet taken (brute force) and update with the nearest inside the gate,
/// or coast. No measurement checks, no assignment (the first track to reach
/// a measurement takes it), no track starts or deletions, no counts: what
/// the table does beyond this is what its figure costs beyond this row's.
trait HandWrittenScan {
    /// The row.
    const OPERATION: &'static str;
    /// One measurement, as the scan takes it.
    type Measurement: Copy;
    /// One track.
    type Track: Copy;
    /// The scene's measurement at (`x`, `y`), m.
    fn measurement(&self, x: f64, y: f64) -> Self::Measurement;
    /// A track started from two noise-free measurements one scan apart.
    fn start(&self, first: Self::Measurement, second: Self::Measurement) -> Self::Track;
    /// One scan (the timed call): returns the number of tracks updated.
    fn scan(
        &self,
        tracks: &mut [Self::Track],
        z: &[Self::Measurement],
        taken: &mut [bool],
    ) -> usize;
    /// A track's position, m.
    fn position(&self, track: &Self::Track) -> [f64; 2];
    /// A measurement's position, m.
    fn measured(&self, z: &Self::Measurement) -> [f64; 2];
}

/// The most tracks (and measurements) of [`hand_written_scene`].
const HAND_WRITTEN_CAPACITY: usize = 64;

/// `scan` at 16, 32 and 64 tracks and measurements (the test command's
/// smoke image: 16).
fn hand_written_sizes<H: HandWrittenScan>(bench: &mut Bench, numeric: &'static str, scan: &H) {
    hand_written_scene(bench, numeric, scan, 16);
    #[cfg(not(feature = "bench-smoke"))]
    hand_written_scene(bench, numeric, scan, 32);
    #[cfg(not(feature = "bench-smoke"))]
    hand_written_scene(bench, numeric, scan, 64);
}

/// The scene at `targets` tracks and measurements (at most
/// [`HAND_WRITTEN_CAPACITY`]): the tracks started from the scene's two
/// noise-free first scans, the next scans run as the table's warm-up
/// (timed, their times not counted), then [`crate::scan::TIMED_SCANS`]
/// scans timed one by one. Each scan must update every track, and each
/// track must end within [`DIVERGED_M`] of its own target's last
/// measurement (the targets are 2 km apart: a track led to another
/// target's measurements fails it).
#[inline(never)]
fn hand_written_scene<H: HandWrittenScan>(
    bench: &mut Bench,
    numeric: &'static str,
    h: &H,
    targets: usize,
) {
    use crate::scan::{Scene, TIMED_SCANS, WARM_UP_SCANS};
    const CAPACITY: usize = HAND_WRITTEN_CAPACITY;
    // At most CAPACITY: in bounds (and the row says what was measured).
    let targets = targets.min(CAPACITY);
    let size = crate::counter::Size {
        n: targets,
        m: targets,
    };
    let mut rng = crate::synth::Lcg::new(5);
    let origin = h.measurement(0.0, 0.0);
    let mut z = [origin; CAPACITY];
    let mut scan = |k: u32, z: &mut [H::Measurement; CAPACITY]| {
        for (i, zi) in z.iter_mut().take(targets).enumerate() {
            let (x, y) = Scene::Separated.position(k, i, targets, &mut rng);
            *zi = h.measurement(x, y);
        }
    };
    let mut first = [origin; CAPACITY];
    scan(0, &mut first);
    scan(1, &mut z);
    let mut tracks = [h.start(origin, origin); CAPACITY];
    for ((track, a), b) in tracks.iter_mut().zip(&first).zip(&z) {
        *track = h.start(*a, *b);
    }
    let mut taken = [false; CAPACITY];
    let (tracks, taken) = (&mut tracks[..targets], &mut taken[..targets]);
    let (mut scan_ticks, mut empty_ticks) = (0u32, 0u32);
    // The warm-up's times are not counted; every scan after the start must
    // time and update every track.
    let mut every_track_updated = true;
    for k in 2..WARM_UP_SCANS + TIMED_SCANS {
        scan(k, &mut z);
        let measured = &z[..targets];
        let mut updated = 0;
        let ticks = bench.time(|| {
            updated = black_box(h.scan(tracks, black_box(measured), taken));
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
        let ([x, y], [zx, zy]) = (h.position(track), h.measured(zi));
        near(x, zx) && near(y, zy)
    });
    if !(every_track_updated && on_own_target) {
        bench.fail(
            numeric,
            H::OPERATION,
            "a scan missed a track or its time, or a track left its target",
        );
        return;
    }
    let net = scan_ticks.saturating_sub(empty_ticks);
    let per_scan = bench.instructions(net) / TIMED_SCANS as f64;
    bench.figure(numeric, H::OPERATION, Some(size), per_scan);
}

#[cfg(not(abtrack_board = "microbit"))]
/// The hand-written Kalman filter's scan ([`HandWrittenScan`]) in `S`, on
/// the table's gate σ and G: the normalised distance squared
/// dx²/S_x + dy²/S_y ≤ G.
struct KalmanScan<S> {
    model: AxisKalmanModel<S>,
    gate: S,
}

#[cfg(not(abtrack_board = "microbit"))]
/// One track of [`KalmanScan`]: its x and y filters.
type AxisTrack<S> = [AxisKalman<S>; 2];

#[cfg(not(abtrack_board = "microbit"))]
impl<S: Scalar> HandWrittenScan for KalmanScan<S> {
    const OPERATION: &'static str = NEAREST_NEIGHBOUR_SCAN;
    type Measurement = [S; 2];
    type Track = AxisTrack<S>;
    fn measurement(&self, x: f64, y: f64) -> [S; 2] {
        [S::from_f64_lossy(x), S::from_f64_lossy(y)]
    }
    /// The two-point start: P = R·[1, 1/T; 1/T, 2/T²].
    fn start(&self, first: [S; 2], second: [S; 2]) -> AxisTrack<S> {
        let m = &self.model;
        let (t, r) = (m.interval, m.measurement_variance);
        let axis = |a: S, b: S| AxisKalman {
            position: b,
            velocity: (b - a) / t,
            p_xx: r,
            p_xv: r / t,
            p_vv: (r + r) / m.interval_squared,
        };
        [axis(first[0], second[0]), axis(first[1], second[1])]
    }
    fn scan(&self, tracks: &mut [AxisTrack<S>], z: &[[S; 2]], taken: &mut [bool]) -> usize {
        kalman_scan(tracks, z, taken, &self.model, self.gate)
    }
    fn position(&self, track: &AxisTrack<S>) -> [f64; 2] {
        [track[0].position.to_f64(), track[1].position.to_f64()]
    }
    fn measured(&self, z: &[S; 2]) -> [f64; 2] {
        [z[0].to_f64(), z[1].to_f64()]
    }
}

/// `axis_kalman_nn_scan_separated`: [`KalmanScan`] in `S` (σ and G of
/// the table's separated scene, q = 1 m²/s³, T = 1 s).
#[cfg(not(abtrack_board = "microbit"))]
#[inline(never)]
pub fn nearest_neighbour_scan<S>(bench: &mut Bench)
where
    S: Scalar + crate::numeric::BenchNumber,
{
    use crate::scan::{GATE_SIGMA_M, GATE_THRESHOLD};
    let scan = KalmanScan {
        model: black_box(AxisKalmanModel::new(1.0, 1.0, GATE_SIGMA_M)),
        gate: black_box(S::from_f64_lossy(GATE_THRESHOLD)),
    };
    hand_written_sizes(bench, S::LABEL, &scan);
}

#[cfg(not(abtrack_board = "microbit"))]
/// One scan of [`KalmanScan`], on slices (one copy of the code for every
/// size): returns the number of tracks updated.
#[inline(never)]
fn kalman_scan<S: Scalar>(
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

/// Units of the integer scan's coordinates per metre: 1/16 m in an `i32`
/// (±134,000 km).
const INTEGER_UNITS_PER_M: f64 = 16.0;
/// Fraction bits of the integer scan's gains (Q16).
const GAIN_FRACTION_BITS: u32 = 16;

/// The scan a firmware engineer writes for a core without an FPU and a
/// sensor with a fixed scan period ([`HandWrittenScan`]): coordinates in
/// integer units, velocity in units per scan, the table's fixed gains α and
/// β in Q16, a constant gate radius r (the table's fixed-gain gate in steady
/// state) tested as a box |dx|, |dy| ≤ r, then dx² + dy² ≤ r², all in 32-bit
/// words.
struct IntegerScan {
    alpha: i32,
    beta: i32,
    radius: u32,
    radius_squared: u32,
}

/// One track of [`IntegerScan`]: position in units, velocity in units per
/// scan.
#[derive(Clone, Copy)]
struct IntegerTrack {
    x: i32,
    y: i32,
    vx: i32,
    vy: i32,
}

impl IntegerScan {
    /// For gains α, β, the sensor's σ (m), the gate's G and a_max (m/s²)
    /// and the scan period T (s): r = σ·√(G·(1 + p⁻)) + ½·a_max·T², the
    /// track table's fixed-gain radius, with p⁻ the αβ filter's steady-state
    /// predicted variance over σ², (2α² + αβ + 2β)/(α(4 − β − 2α)) (Tenne &
    /// Singh eq. 13).
    fn new(alpha: f64, beta: f64, sigma: f64, threshold: f64, a_max: f64, t: f64) -> Self {
        let predicted = (2.0 * alpha * alpha + alpha * beta + 2.0 * beta)
            / (alpha * (4.0 - beta - 2.0 * alpha));
        let radius_m = sigma * libm::sqrt(threshold * (1.0 + predicted)) + 0.5 * a_max * t * t;
        let radius = libm::ceil(radius_m * INTEGER_UNITS_PER_M) as u32;
        let q16 = |g: f64| libm::round(g * f64::from(1u32 << GAIN_FRACTION_BITS)) as i32;
        IntegerScan {
            alpha: q16(alpha),
            beta: q16(beta),
            radius,
            radius_squared: radius.saturating_mul(radius),
        }
    }
}

impl HandWrittenScan for IntegerScan {
    const OPERATION: &'static str = INTEGER_SCAN;
    type Measurement = [i32; 2];
    type Track = IntegerTrack;
    fn measurement(&self, x: f64, y: f64) -> [i32; 2] {
        let unit = |v: f64| libm::round(v * INTEGER_UNITS_PER_M) as i32;
        [unit(x), unit(y)]
    }
    fn start(&self, first: [i32; 2], second: [i32; 2]) -> IntegerTrack {
        IntegerTrack {
            x: second[0],
            y: second[1],
            vx: second[0].wrapping_sub(first[0]),
            vy: second[1].wrapping_sub(first[1]),
        }
    }
    fn scan(&self, tracks: &mut [IntegerTrack], z: &[[i32; 2]], taken: &mut [bool]) -> usize {
        integer_nearest_neighbour(tracks, z, taken, self)
    }
    fn position(&self, track: &IntegerTrack) -> [f64; 2] {
        [
            f64::from(track.x) / INTEGER_UNITS_PER_M,
            f64::from(track.y) / INTEGER_UNITS_PER_M,
        ]
    }
    fn measured(&self, z: &[i32; 2]) -> [f64; 2] {
        [
            f64::from(z[0]) / INTEGER_UNITS_PER_M,
            f64::from(z[1]) / INTEGER_UNITS_PER_M,
        ]
    }
}

/// `integer_ab_nn_scan_separated`: [`IntegerScan`] with the table's
/// fixed-gain rows' gains and gate (`scan_separated`), T = 1 s, on every
/// board.
#[inline(never)]
pub fn integer_scan(bench: &mut Bench) {
    use crate::scan::{FIXED_GAINS, GATE_MAX_ACCELERATION_M_PER_S2, GATE_SIGMA_M, GATE_THRESHOLD};
    let scan = black_box(IntegerScan::new(
        FIXED_GAINS.0,
        FIXED_GAINS.1,
        GATE_SIGMA_M,
        GATE_THRESHOLD,
        GATE_MAX_ACCELERATION_M_PER_S2,
        1.0,
    ));
    hand_written_sizes(bench, crate::numeric::INTEGER, &scan);
}

/// The correction g·e in units, rounded (half up), for a gain `g` in Q16
/// (≤ 1) and a residual inside the gate (|e| ≤ r < 2¹⁵ units): the
/// product stays below 2³¹.
#[inline(always)]
fn q16_times(g: i32, e: i32) -> i32 {
    g.wrapping_mul(e)
        .wrapping_add(1 << (GAIN_FRACTION_BITS - 1))
        >> GAIN_FRACTION_BITS
}

/// One scan of [`IntegerScan`], on slices (one copy of the code for every
/// size): returns the number of tracks updated.
#[inline(never)]
fn integer_nearest_neighbour(
    tracks: &mut [IntegerTrack],
    z: &[[i32; 2]],
    taken: &mut [bool],
    s: &IntegerScan,
) -> usize {
    taken.fill(false);
    let mut updated = 0;
    for track in tracks.iter_mut() {
        let (px, py) = (
            track.x.wrapping_add(track.vx),
            track.y.wrapping_add(track.vy),
        );
        let (mut nearest, mut least) = (None, s.radius_squared);
        for (k, ([zx, zy], used)) in z.iter().zip(taken.iter()).enumerate() {
            if *used {
                continue;
            }
            let (dx, dy) = (zx.wrapping_sub(px), zy.wrapping_sub(py));
            if dx.unsigned_abs() > s.radius || dy.unsigned_abs() > s.radius {
                continue;
            }
            // |dx|, |dy| ≤ r < 2¹⁵: no overflow.
            let d2 = (dx.wrapping_mul(dx) as u32).wrapping_add(dy.wrapping_mul(dy) as u32);
            if d2 <= least {
                (nearest, least) = (Some((k, dx, dy)), d2);
            }
        }
        (track.x, track.y) = (px, py);
        if let Some((k, ex, ey)) = nearest {
            if let Some(used) = taken.get_mut(k) {
                *used = true;
                track.x = px.wrapping_add(q16_times(s.alpha, ex));
                track.y = py.wrapping_add(q16_times(s.alpha, ey));
                track.vx = track.vx.wrapping_add(q16_times(s.beta, ex));
                track.vy = track.vy.wrapping_add(q16_times(s.beta, ey));
                updated += 1;
            }
        }
    }
    updated
}
