//! The benchmark's inputs: deterministic noisy trajectories (boards/qemu/src/synth.rs),
//! computed in f64 and converted to the number system under test.

use core::hint::black_box;

use abtrack::num::{Numeric, Quantity};

use crate::synth::Lcg;

/// Length of the input rings the calls cycle through.
pub const RING: usize = 64;

/// Position in the ring of call `k`.
pub fn at(k: u32) -> usize {
    k as usize % RING
}

/// A target going out and back at `speed` (m/s, one sample per second) from
/// 5 km, with noise of standard deviation `sigma` (m): the ring closes on
/// itself without a jump.
pub fn ring<L: Quantity>(seed: u64, speed: f64, sigma: f64) -> [L; RING] {
    let mut rng = Lcg::new(seed);
    core::array::from_fn(|k| {
        let leg = if k < RING / 2 { k } else { RING - k };
        L::from_f64_lossy(5_000.0 + speed * leg as f64 + rng.noise(sigma))
    })
}

/// The target of every 2-D row: x out and back at 180 m/s, y at −120 m/s,
/// from the same seeds whatever the row.
pub struct PlaneRing<N: Numeric> {
    pub xs: [N::Length; RING],
    pub ys: [N::Length; RING],
}

impl<N: Numeric> PlaneRing<N> {
    /// With noise of standard deviation `sigma` (m) on each axis.
    pub fn new(sigma: f64) -> Self {
        PlaneRing {
            xs: ring(1, 180.0, sigma),
            ys: ring(2, -120.0, sigma),
        }
    }

    /// The measurement of call `k`, opaque to the optimiser.
    pub fn get(&self, k: u32) -> [N::Length; 2] {
        [black_box(self.xs[at(k)]), black_box(self.ys[at(k)])]
    }

    /// A loop's baseline: the same fetch, without the call.
    pub fn fetch(&self, k: u32) {
        black_box(self.get(k));
    }
}
