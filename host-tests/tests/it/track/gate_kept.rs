//! What a track's gate keeps for its update (`TrackFilter::GateKept`): a
//! table of default tracks, whose update takes the predicted covariance
//! terms their gate formed, gives scan for scan what the same table gives
//! when its tracks keep nothing and form everything again: the same
//! reports, association codes and tracks, bit for bit, through manoeuvres,
//! missed detections, clutter, scans too close to the previous one, gaps
//! that restart tracks, a full table and overflowing scans, in every number
//! system.

use super::support::Lcg;
use abtrack::filter::auto::AutoFilter;
use abtrack::gain::AutoGains;
use abtrack::num::fixed32::Fixed32;
use abtrack::num::{Numeric, Quantity};
use abtrack::track::defaults::default_cartesian;
use abtrack::track::{
    Association, Gate, GateRegion, Measurement, Observation, PredictedState, ScanInterval,
    TrackFilter, TrackTable,
};
use abtrack::{FilterError, Fix, ScaledScalar};

/// The default track keeping nothing from its gate: each method is the
/// default track's, the update the one that forms everything again.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Recomputing<S: Numeric>(AutoFilter<S, 2>);

type Default<S> = AutoFilter<S, 2>;

impl<S: Numeric> TrackFilter<S> for Recomputing<S> {
    type Params = AutoGains<S, 2>;
    type Step = <Default<S> as TrackFilter<S>>::Step;
    type GateKept = ();
    const NOTHING_KEPT: () = ();

    fn step(params: &Self::Params, interval: &ScanInterval<S>) -> Result<Self::Step, FilterError> {
        <Default<S> as TrackFilter<S>>::step(params, interval)
    }
    fn empty(params: &Self::Params) -> Self {
        Recomputing(<Default<S> as TrackFilter<S>>::empty(params))
    }
    fn update(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        step: &Self::Step,
    ) -> Result<(), FilterError> {
        TrackFilter::update(&mut self.0, params, z, step)
    }
    fn coast(&mut self, params: &Self::Params, step: &Self::Step) -> Result<(), FilterError> {
        TrackFilter::coast(&mut self.0, params, step)
    }
    fn predict(
        &self,
        params: &Self::Params,
        step: &Self::Step,
    ) -> Result<PredictedState<S>, FilterError> {
        TrackFilter::predict(&self.0, params, step)
    }
    fn position(&self) -> [S::Length; 2] {
        TrackFilter::position(&self.0)
    }
    fn velocity(&self) -> [S::Speed; 2] {
        TrackFilter::velocity(&self.0)
    }
    fn predicted_variance_ratio(
        &self,
        params: &Self::Params,
        step: &Self::Step,
    ) -> Option<S::Ratio> {
        TrackFilter::predicted_variance_ratio(&self.0, params, step)
    }
    fn gate_alpha(&self, params: &Self::Params) -> S::Ratio {
        TrackFilter::gate_alpha(&self.0, params)
    }
    fn interval_of(step: &Self::Step) -> &ScanInterval<S> {
        <Default<S> as TrackFilter<S>>::interval_of(step)
    }
    fn gate_region(
        &self,
        params: &Self::Params,
        predicted: &PredictedState<S>,
        step: &Self::Step,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        TrackFilter::gate_region(&self.0, params, predicted, step, gate)
    }
}

const TRACKS: usize = 12;
const PER_SCAN: usize = 10;
const TARGETS: usize = 10;

/// The scans: (interval in ms, measurements x, y in m). Targets in the
/// nominal radar's ±5 km square, turning now and then, seen with P_D 0.85
/// and σ 20 m, three clutter plots a scan; mostly 1 s scans, some 5 ms
/// (too close: the table skips the scan), some 2 s, some 25 s (gaps).
fn scans(seed: u64, count: usize) -> Vec<(u32, Vec<[f64; 2]>)> {
    let mut rng = Lcg(seed);
    let mut targets: Vec<[f64; 4]> = (0..TARGETS)
        .map(|_| {
            let heading = rng.next_signed() * std::f64::consts::PI;
            let speed = 150.0 + 100.0 * rng.next_signed();
            [
                4000.0 * rng.next_signed(),
                4000.0 * rng.next_signed(),
                speed * heading.cos(),
                speed * heading.sin(),
            ]
        })
        .collect();
    (0..count)
        .map(|k| {
            let draw = rng.next_signed();
            let ms = if draw < -0.9 {
                5
            } else if draw < -0.85 {
                25_000
            } else if draw < -0.7 {
                2_000
            } else {
                1_000
            };
            let dt = f64::from(ms) / 1000.0;
            let mut plots = Vec::new();
            for t in &mut targets {
                // A turn of up to 3 g in a third of the scans.
                let turn = if k % 3 == 0 {
                    30.0 * rng.next_signed()
                } else {
                    0.0
                };
                let speed = t[2].hypot(t[3]).max(1.0);
                let (ax, ay) = (-turn * t[3] / speed, turn * t[2] / speed);
                t[0] += t[2] * dt;
                t[1] += t[3] * dt;
                t[2] += ax * dt;
                t[3] += ay * dt;
                // Back into the square from the other side.
                for c in &mut t[..2] {
                    if c.abs() > 5000.0 {
                        *c = -c.signum() * 4500.0;
                    }
                }
                if rng.next_signed() < 0.7 {
                    plots.push([
                        t[0] + 20.0 * 1.7 * rng.next_signed(),
                        t[1] + 20.0 * 1.7 * rng.next_signed(),
                    ]);
                }
            }
            for _ in 0..3 {
                plots.push([5000.0 * rng.next_signed(), 5000.0 * rng.next_signed()]);
            }
            (ms, plots)
        })
        .collect()
}

fn same_as_recomputing<S: Numeric>(seed: u64) {
    let config = default_cartesian::<S>().expect("the nominal radar's design is valid");
    let mut kept: Box<TrackTable<S, Default<S>, TRACKS, PER_SCAN>> = Box::new(TrackTable::new());
    let mut formed: Box<TrackTable<S, Recomputing<S>, TRACKS, PER_SCAN>> =
        Box::new(TrackTable::new());
    let (mut now_ms, mut updated, mut overflowed) = (0u32, 0u32, 0u32);
    for (ms, plots) in scans(seed, 400) {
        now_ms += ms;
        let measurements: Vec<Measurement<S>> = plots
            .iter()
            .map(|&[x, y]| Measurement::Cartesian {
                x: S::Length::from_f64_lossy(x),
                y: S::Length::from_f64_lossy(y),
            })
            .collect();
        let mut codes_kept = vec![Association::OutsideGates; measurements.len()];
        let mut codes_formed = codes_kept.clone();
        let a = kept.scan(&config, now_ms, &measurements, &mut codes_kept);
        let b = formed.scan(&config, now_ms, &measurements, &mut codes_formed);
        assert_eq!(a, b, "{} at {now_ms} ms", S::NAME);
        assert_eq!(codes_kept, codes_formed, "{} at {now_ms} ms", S::NAME);
        let tracks_kept: Vec<_> = kept.tracks().map(|t| (t.id(), *t.filter())).collect();
        let tracks_formed: Vec<_> = formed.tracks().map(|t| (t.id(), t.filter().0)).collect();
        assert_eq!(tracks_kept, tracks_formed, "{} at {now_ms} ms", S::NAME);
        if let Ok(report) = a {
            updated += report.updated;
            overflowed += report.dropped_overflow;
        }
    }
    let stats = kept.stats();
    assert!(updated > 500, "{}: {updated} updates", S::NAME);
    assert!(overflowed > 0, "{}: no scan overflowed", S::NAME);
    assert!(stats.scans_skipped > 10, "{}: {stats:?}", S::NAME);
    assert!(stats.tracks_restarted > 0, "{}: {stats:?}", S::NAME);
}

#[test]
fn a_track_updated_with_what_its_gate_kept_is_the_track_that_forms_it_again() {
    for seed in [1, 2] {
        same_as_recomputing::<f64>(seed);
        same_as_recomputing::<f32>(seed);
        same_as_recomputing::<Fixed32>(seed);
        same_as_recomputing::<Fix>(seed);
        same_as_recomputing::<ScaledScalar>(seed);
    }
}
