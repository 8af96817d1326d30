//! The benchmark's inputs: deterministic noisy trajectories (src/firmware/synth.rs),
//! computed in f64 and converted to the type under test.

use abtrack::Scalar;

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
pub fn ring<S: Scalar>(seed: u64, speed: f64, sigma: f64) -> [S; RING] {
    let mut rng = Lcg::new(seed);
    core::array::from_fn(|k| {
        let leg = if k < RING / 2 { k } else { RING - k };
        S::from_f64_lossy(5_000.0 + speed * leg as f64 + rng.noise(sigma))
    })
}
