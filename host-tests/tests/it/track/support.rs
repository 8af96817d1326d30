//! Shared helpers of the track tests.

use abtrack::num::{Numeric, Quantity};
use abtrack::track::{
    FixedGainTrack, Gate, GateRegion, Measurement, Observation, PredictedState, ScanInterval,
    TrackFilter, TrackerConfig,
};
use abtrack::{FilterError, Gains, Scalar};

pub type Config<S> = TrackerConfig<S, Gains<S>>;
pub type Table<S, const N: usize, const M: usize> =
    abtrack::track::TrackTable<S, FixedGainTrack<S>, N, M>;

pub fn s<S: Scalar>(v: f64) -> S {
    S::try_from_f64(v).unwrap()
}

/// A quantity of any number system (a length, a ratio, ...).
pub fn q<Q: Quantity>(v: f64) -> Q {
    Q::try_from_f64(v).unwrap()
}

pub fn cart<S: Numeric>(x: f64, y: f64) -> Measurement<S> {
    Measurement::Cartesian { x: q(x), y: q(y) }
}

/// α = 0.5, β = 0.2 (inside Al-Wagih's triangle: 2α + β = 1.2 < 4);
/// uncertainty gate σ = 5 m, G = 13.8 (99.9 %), a_max = 5 m/s²;
/// v_max = 300 m/s; defaults otherwise (2 of 3, delete after 3 / 2 misses).
pub fn default_config<S: Numeric>() -> Config<S> {
    let gains = Gains::alpha_beta_f64(0.5, 0.2).unwrap();
    let gate = Gate::uncertainty(q(5.0), q(13.8), q(5.0)).unwrap();
    TrackerConfig::new(gains, gate, q(300.0)).unwrap()
}

/// Deterministic pseudo-random numbers (64-bit LCG, Knuth's MMIX constants).
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in [-1, 1).
    pub fn next_signed(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// A stationary track for the tests that need a filter of their own: it
/// takes its position from its measurements and gates a circle of the
/// configured radius around it (none when the radius is `None`); with
/// `refuse_after: Some(n)` it refuses every update once it holds n points
/// (2: every update after the two initiation points; 1: the second
/// initiation point), as a saturating update would.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parked {
    points: u8,
    position: [f64; 2],
}

/// [`Parked`]'s configuration.
#[derive(Debug, Clone, Copy)]
pub struct ParkedParams {
    pub gate_radius: Option<f64>,
    pub refuse_after: Option<u8>,
}

impl TrackFilter<f64> for Parked {
    type Params = ParkedParams;
    type Step = ScanInterval<f64>;
    type GateKept = ();
    const NOTHING_KEPT: () = ();
    fn step(_: &ParkedParams, i: &ScanInterval<f64>) -> Result<ScanInterval<f64>, FilterError> {
        Ok(*i)
    }
    fn interval_of(step: &ScanInterval<f64>) -> &ScanInterval<f64> {
        step
    }
    fn empty(_: &ParkedParams) -> Self {
        Parked {
            points: 0,
            position: [0.0; 2],
        }
    }
    fn update(
        &mut self,
        params: &ParkedParams,
        z: &Observation<f64>,
        _: &ScanInterval<f64>,
    ) -> Result<(), FilterError> {
        if params.refuse_after.is_some_and(|n| self.points >= n) {
            return Err(FilterError::Saturated);
        }
        self.points = self.points.saturating_add(1);
        self.position = z.xy();
        Ok(())
    }
    fn coast(&mut self, _: &ParkedParams, _: &ScanInterval<f64>) -> Result<(), FilterError> {
        Ok(())
    }
    fn predict(
        &self,
        _: &ParkedParams,
        _: &ScanInterval<f64>,
    ) -> Result<PredictedState<f64>, FilterError> {
        Ok(PredictedState {
            position: self.position,
            velocity: [0.0; 2],
        })
    }
    fn position(&self) -> [f64; 2] {
        self.position
    }
    fn velocity(&self) -> [f64; 2] {
        [0.0; 2]
    }
    fn predicted_variance_ratio(&self, _: &ParkedParams, _: &ScanInterval<f64>) -> Option<f64> {
        Some(0.0)
    }
    fn gate_alpha(&self, _: &ParkedParams) -> f64 {
        1.0
    }
    fn gate_region(
        &self,
        params: &ParkedParams,
        _: &PredictedState<f64>,
        _: &ScanInterval<f64>,
        _: &Gate<f64>,
    ) -> Option<GateRegion<f64>> {
        GateRegion::circle(self.position, params.gate_radius?)
    }
}

/// A configuration of [`Parked`] tracks: confirmed at their start, deleted
/// after 255 misses.
pub fn parked_config(params: ParkedParams) -> TrackerConfig<f64, ParkedParams> {
    TrackerConfig::new(params, Gate::uncertainty(5.0, 13.8, 5.0).unwrap(), 300.0)
        .unwrap()
        .with_confirmation(1, 1)
        .unwrap()
        .with_deletion(255, 255)
        .unwrap()
}
