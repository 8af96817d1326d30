//! Who gets the scan's `M` slots when it has more measurements (the
//! [`crate::scan`] docs, "Capacity").

use super::{BearingTrack, ScanConfig, ScanLoop};

use crate::num::{hypot, Numeric, Scalar};
use crate::track::{GateRegion, Observation, ScanInterval, TrackFilter};

/// A batch entry's claim on a slot; smaller is more important ([`crate::scan`],
/// "Capacity").
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Priority<S> {
    pub(super) class: u8,
    pub(super) gate_cost: u16,
    pub(super) range: S,
}

const CLASS_CONFIRMED_GATE: u8 = 0;
pub(super) const CLASS_OTHER: u8 = 1;
const CLASS_REFUSED: u8 = 2;

impl<S: Scalar> Priority<S> {
    /// Strictly less important than `other`.
    fn is_worse_than(&self, other: &Self) -> bool {
        (self.class, self.gate_cost) > (other.class, other.gate_cost)
            || ((self.class, self.gate_cost) == (other.class, other.gate_cost)
                && self.range > other.range)
    }
}

/// A confirmed track's gate for the next scan, and its best measurement so
/// far.
#[derive(Debug, Clone, Copy)]
pub(super) struct TrackGate<S: Numeric> {
    region: GateRegion<S>,
    /// The batch index of the nearest measurement in the gate,
    /// [`NO_CHAMPION`] for none, and its gate cost: 4 bytes, where an
    /// `Option<(usize, u16)>` takes 12 (32-bit cores) or 16, in a record kept
    /// per track. A batch index is below the track table's measurement
    /// capacity, which its capacity check keeps under `NO_CHAMPION`.
    champion_index: u16,
    champion_cost: u16,
}

/// No measurement in the gate yet: not a batch index (a batch holds fewer
/// than 65,535 measurements, the track table's capacity check).
const NO_CHAMPION: u16 = u16::MAX;

impl<S: Numeric> TrackGate<S> {
    fn new(region: GateRegion<S>) -> Self {
        TrackGate {
            region,
            champion_index: NO_CHAMPION,
            champion_cost: 0,
        }
    }

    /// (batch index, gate cost) of the nearest measurement in the gate.
    fn champion(&self) -> Option<(usize, u16)> {
        (self.champion_index != NO_CHAMPION)
            .then_some((usize::from(self.champion_index), self.champion_cost))
    }

    fn set_champion(&mut self, index: usize, cost: u16) {
        self.champion_index = u16::try_from(index).unwrap_or(NO_CHAMPION);
        self.champion_cost = cost;
    }

    fn clear_champion(&mut self) {
        self.champion_index = NO_CHAMPION;
    }
}

impl<
        T: Numeric<Wide = S>,
        S: Scalar,
        F: TrackFilter<S> + BearingTrack<S>,
        const N: usize,
        const M: usize,
    > ScanLoop<T, F, N, M>
{
    /// The batch has just overflowed: the gates of the confirmed tracks,
    /// and the priority and champion places of every entry (in arrival
    /// order). Only a scan with more than `M` measurements pays for this.
    pub(super) fn rank_batch(&mut self, config: &ScanConfig<T, F::Params>) {
        self.prepare_gates(config);
        self.ranked = true;
        for i in 0..self.batch.len() {
            let observation = self.batch.get(i).and_then(|m| Observation::new(*m).ok());
            let priority = self.priority(observation.as_ref());
            if let Some(slot) = self.batch_priorities.get_mut(i) {
                *slot = priority;
            }
            if let Some(o) = observation {
                self.crown(i, &o);
            }
        }
    }

    /// The priority of a measurement against the gates of the next scan.
    pub(super) fn priority(&self, observation: Option<&Observation<S>>) -> Priority<S> {
        let Some(o) = observation else {
            return Priority {
                class: CLASS_REFUSED,
                gate_cost: 0,
                range: S::ZERO,
            };
        };
        let best = self.gates.iter().filter_map(|g| g.region.cost(o)).min();
        // Positions are relative to the own aircraft.
        let [x, y] = o.xy();
        let range = hypot(x, y);
        match best {
            Some(gate_cost) => Priority {
                class: CLASS_CONFIRMED_GATE,
                gate_cost,
                range,
            },
            None => Priority {
                class: CLASS_OTHER,
                gate_cost: 0,
                range,
            },
        }
    }

    /// Which batch entry a new measurement replaces, if any: the least
    /// important one that is no confirmed track's nearest measurement once
    /// the new one is counted (it may take that place from another), if the
    /// new one is more important or takes such a place itself.
    pub(super) fn evictable(
        &self,
        priority: &Priority<S>,
        observation: Option<&Observation<S>>,
    ) -> Option<usize> {
        // Champion places the new measurement would take from each entry,
        // and whether it would hold one.
        let mut dethroned = [0u8; M];
        let mut crowned = false;
        if let Some(o) = observation {
            for gate in self.gates.iter() {
                let Some(cost) = gate.region.cost(o) else {
                    continue;
                };
                match gate.champion() {
                    Some((i, c)) if cost < c => {
                        crowned = true;
                        if let Some(d) = dethroned.get_mut(i) {
                            *d = d.saturating_add(1);
                        }
                    }
                    None => crowned = true,
                    _ => {}
                }
            }
        }
        // The least important unprotected entry (the last of equals).
        let mut worst: Option<(usize, &Priority<S>)> = None;
        for (i, (p, (&places, &taken))) in self
            .batch_priorities
            .iter()
            .zip(self.batch_champions.iter().zip(dethroned.iter()))
            .enumerate()
        {
            if places > taken {
                continue;
            }
            if worst.is_none_or(|(_, w)| !w.is_worse_than(p)) {
                worst = Some((i, p));
            }
        }
        let (w, worst_priority) = worst?;
        // Ties keep the measurement already in the batch.
        if crowned || worst_priority.is_worse_than(priority) {
            Some(w)
        } else {
            None
        }
    }

    /// Clears a batch entry's champion places (it is being replaced).
    pub(super) fn release(&mut self, index: usize) {
        for gate in self.gates.iter_mut() {
            if gate.champion().is_some_and(|(i, _)| i == index) {
                gate.clear_champion();
            }
        }
        if let Some(c) = self.batch_champions.get_mut(index) {
            *c = 0;
        }
    }

    /// Makes the entry at `index` the champion of every confirmed track
    /// whose gate it is nearest to so far.
    pub(super) fn crown(&mut self, index: usize, observation: &Observation<S>) {
        for gate in self.gates.iter_mut() {
            let Some(cost) = gate.region.cost(observation) else {
                continue;
            };
            let previous = match gate.champion() {
                Some((_, c)) if cost >= c => continue,
                previous => previous,
            };
            if let Some((p, _)) = previous {
                if let Some(count) = self.batch_champions.get_mut(p) {
                    *count = count.saturating_sub(1);
                }
            }
            gate.set_champion(index, cost);
            if let Some(count) = self.batch_champions.get_mut(index) {
                *count = count.saturating_add(1);
            }
        }
    }

    /// The gates of the confirmed tracks for the scan being assembled (one
    /// period after the last).
    fn prepare_gates(&mut self, config: &ScanConfig<T, F::Params>) {
        self.gates.clear();
        let params = config.tracker.params();
        let Some(step) = ScanInterval::from_ms(config.clock.period_ms)
            .and_then(|interval| F::step(params, &interval).ok())
        else {
            return;
        };
        let confirmed = self.table.tracks().filter(|t| t.is_confirmed());
        for track in confirmed {
            let region = track.filter().predict(params, &step).ok().and_then(|p| {
                track
                    .filter()
                    .gate_region(params, &p, &step, config.tracker.gate())
            });
            if let Some(region) = region {
                if self.gates.push(TrackGate::new(region)).is_err() {
                    break;
                }
            }
        }
    }
}
