//! Helpers shared by the scan-loop tests (here and `firmware::runtime_findings`).

/// Deterministic pseudo-random numbers (64-bit LCG, Knuth's MMIX constants).
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 11
    }
    /// Uniform in [-1, 1).
    pub fn signed(&mut self) -> f64 {
        (self.next_u64() as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// Two targets on an X through the own aircraft at the origin, both at
/// 111.8 m/s: A from (−3000, −1500) m moving (100, 50) m/s, B from
/// (−3000, 1500) m moving (100, −50) m/s; they cross at the origin at
/// t = 30 s. Noise uniform ±15 m per axis.
pub fn crossing_truth(t: f64) -> [[f64; 2]; 2] {
    [
        [-3000.0 + 100.0 * t, -1500.0 + 50.0 * t],
        [-3000.0 + 100.0 * t, 1500.0 - 50.0 * t],
    ]
}
