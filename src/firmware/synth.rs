//! Deterministic synthetic data for the firmware (demo, self-test, benchmark):
//! a tiny pseudo-random generator and target trajectories, in `f64` (the
//! truth is always computed in `f64`; the filters under test get it converted
//! to their own numeric type). No std, no heap, no panics.
//!
//! Included with `#[path]` by each firmware binary; not all of them use every
//! item.
#![allow(dead_code)]

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
        let (s, c) = libm::sincos(self.turn_rate * turning);
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
