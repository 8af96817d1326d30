//! Deterministic synthetic data for the firmware (self-test, benchmark, soak):
//! a tiny pseudo-random generator and target trajectories, in `f64` (the
//! truth is always computed in `f64`; the filters under test get it converted
//! to their own numeric type). No std, no heap, no panics.

/// Knuth's MMIX linear congruential generator (multiplier
/// 6364136223846793005, increment 1442695040888963407, modulus 2⁶⁴), output
/// the high 32 bits (the low bits of a power-of-two LCG are weak). Plenty for
/// test trajectories and pseudo-noise; not for statistics.
#[derive(Debug, Clone, Copy)]
pub struct Lcg {
    state: u64,
}

impl Lcg {
    pub const fn new(seed: u64) -> Self {
        Lcg { state: seed }
    }

    pub fn next_u32(&mut self) -> u32 {
        self.state = self
            .state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.state >> 32) as u32
    }

    /// Uniform in [0, 1), 32 bits of resolution.
    pub fn unit(&mut self) -> f64 {
        self.next_u32() as f64 * (1.0 / 4_294_967_296.0)
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform choice of an index below `n` (0 for `n == 0`).
    pub fn index(&mut self, n: usize) -> usize {
        if n == 0 {
            return 0;
        }
        // Multiply-shift: unbiased enough for small n, and no division.
        ((self.next_u32() as u64 * n as u64) >> 32) as usize
    }

    /// Zero-mean noise of standard deviation `sigma`, bell-shaped and bounded:
    /// the Irwin–Hall sum of four uniforms (variance 4/12), rescaled. Never
    /// beyond ±2√3·σ ≈ ±3.46σ, so test bounds stay deterministic.
    pub fn noise(&mut self, sigma: f64) -> f64 {
        let sum = self.unit() + self.unit() + self.unit() + self.unit();
        // (sum − 2) has variance 1/3; × √3 gives variance 1.
        (sum - 2.0) * 1.732_050_807_568_877_2 * sigma
    }
}

/// Position and velocity of a point target in the plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneState {
    pub position: [f64; 2],
    pub velocity: [f64; 2],
}

/// The demo's target: constant velocity until `turn_start`, then a
/// coordinated turn (constant speed, constant turn rate `turn_rate` rad/s,
/// counter-clockwise for a positive rate). Closed form, so there is no
/// integration error in the truth.
#[derive(Debug, Clone, Copy)]
pub struct TurningTarget {
    pub start: [f64; 2],
    pub velocity: [f64; 2],
    pub turn_start: f64,
    pub turn_rate: f64,
}

impl TurningTarget {
    /// The true state at time `t` (seconds from the start).
    pub fn at(&self, t: f64) -> PlaneState {
        let [vx, vy] = self.velocity;
        let straight = t.min(self.turn_start);
        let mut position = [self.start[0] + vx * straight, self.start[1] + vy * straight];
        let turning = t - straight;
        if turning <= 0.0 || self.turn_rate == 0.0 {
            return PlaneState {
                position,
                velocity: self.velocity,
            };
        }
        let (s, c) = <f64 as abtrack::Numeric>::sin_cos(self.turn_rate * turning);
        // ∫₀^τ R(ωu)·v du = (1/ω)·[[sin ωτ, −(1−cos ωτ)], [1−cos ωτ, sin ωτ]]·v
        let w = self.turn_rate;
        position[0] += (s * vx - (1.0 - c) * vy) / w;
        position[1] += ((1.0 - c) * vx + s * vy) / w;
        PlaneState {
            position,
            velocity: [c * vx - s * vy, s * vx + c * vy],
        }
    }
}

// ---------------------------------------------------------------------------
// The soak's sky: 45 intruders on circular orbits, clutter, Pd 0.9
// ---------------------------------------------------------------------------

/// Intruders of the soak.
pub const SOAK_TARGETS: usize = 45;
/// Half-width of the surveillance square, m.
pub const SOAK_HALF_WIDTH_M: f64 = 16_000.0;
/// False measurements per scan, uniform over the square (0.02 per km²).
pub const SOAK_CLUTTER_PER_SCAN: usize = 20;
/// Detection probability of each intruder in each scan.
pub const SOAK_DETECTION_PROBABILITY: f64 = 0.9;
/// Measurement noise per axis, m (the demo sensor's).
pub const SOAK_SIGMA_M: f64 = 20.0;
/// The most measurements a soak scan has.
pub const SOAK_MAX_PER_SCAN: usize = SOAK_TARGETS + SOAK_CLUTTER_PER_SCAN;

/// A target flying a circle at constant speed for ever (a holding pattern):
/// it stays in the surveillance square for the whole day.
#[derive(Debug, Clone, Copy)]
pub struct Orbit {
    pub centre: [f64; 2],
    pub radius: f64,
    pub speed: f64,
    /// Angle at t = 0, rad.
    pub phase: f64,
    /// +1 counter-clockwise, −1 clockwise.
    pub direction: f64,
}

impl Orbit {
    /// Intruder `i` of the soak: centres on a 9 × 5 grid 3.5 km apart,
    /// radii 1.0–1.4 km, speeds 30–50 m/s (centripetal acceleration at most
    /// 1.8 m/s²), phases and directions spread.
    pub fn soak(i: usize) -> Self {
        let column = (i % 9) as f64 - 4.0;
        let row = (i / 9) as f64 - 2.0;
        Orbit {
            centre: [3500.0 * column, 3500.0 * row],
            radius: 1000.0 + 100.0 * (i % 5) as f64,
            speed: 30.0 + 5.0 * ((i / 5) % 5) as f64,
            phase: 0.7 * i as f64,
            direction: if i.is_multiple_of(2) { 1.0 } else { -1.0 },
        }
    }

    /// The true state at time `t` (s).
    pub fn at(&self, t: f64) -> PlaneState {
        let omega = self.direction * self.speed / self.radius;
        let (s, c) = <f64 as abtrack::Numeric>::sin_cos(self.phase + omega * t);
        PlaneState {
            position: [
                self.centre[0] + self.radius * c,
                self.centre[1] + self.radius * s,
            ],
            velocity: [-self.radius * omega * s, self.radius * omega * c],
        }
    }
}

/// The measurements of soak scan `k` (time `k` s, sensor clock `k`·1000
/// ms) into `out`, shuffled; returns how many. Each intruder is detected
/// with [`SOAK_DETECTION_PROBABILITY`] and measured with noise of
/// [`SOAK_SIGMA_M`] per axis; [`SOAK_CLUTTER_PER_SCAN`] false measurements
/// are uniform over the square. Each scan has its own generator (seeded
/// from `k`), so any scan can be generated alone, on the board or on the
/// host, bit for bit the same (f64 and libm on both).
pub fn soak_scan(k: u32, out: &mut [abtrack::wire::MeasurementReport; SOAK_MAX_PER_SCAN]) -> usize {
    let mut rng =
        Lcg::new(0x50AC_0000_0000_0000 ^ u64::from(k).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let t = f64::from(k);
    let time_ms = k.wrapping_mul(1000);
    let mut n = 0;
    let mut put =
        |x: f64, y: f64, out: &mut [abtrack::wire::MeasurementReport; SOAK_MAX_PER_SCAN]| {
            // Inside ±16 km: the conversion cannot fail.
            if let (Ok(m), Some(slot)) = (
                abtrack::wire::MeasurementReport::cartesian_from_metres(time_ms, 1, x, y, None),
                out.get_mut(n),
            ) {
                *slot = m;
                n += 1;
            }
        };
    for i in 0..SOAK_TARGETS {
        let truth = Orbit::soak(i).at(t);
        let detected = rng.unit() < SOAK_DETECTION_PROBABILITY;
        let (nx, ny) = (rng.noise(SOAK_SIGMA_M), rng.noise(SOAK_SIGMA_M));
        if detected {
            put(truth.position[0] + nx, truth.position[1] + ny, out);
        }
    }
    for _ in 0..SOAK_CLUTTER_PER_SCAN {
        let x = rng.uniform(-SOAK_HALF_WIDTH_M, SOAK_HALF_WIDTH_M);
        let y = rng.uniform(-SOAK_HALF_WIDTH_M, SOAK_HALF_WIDTH_M);
        put(x, y, out);
    }
    // Fisher–Yates: the sensor does not sort its reports.
    let mut i = n;
    while i > 1 {
        let j = rng.index(i);
        i -= 1;
        if j < i && i < out.len() {
            out.swap(i, j);
        }
    }
    n
}
