//! Who gets the scan's `M` slots when it has more measurements (the
//! [`crate::scan`] docs, "Capacity").

use super::intruders::{may_take, IntruderSlot, ReplyData};
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

/// The gate for the next scan of the track of one TCAS slot (the loop's
/// `intruders`, same order), if the track is confirmed, and its best
/// measurement so far.
#[derive(Debug, Clone, Copy)]
pub(super) struct TrackGate<S: Numeric> {
    /// `None`: the track is tentative (or its gate could not be formed).
    /// As large as the region alone (the option is in the enum's tag).
    region: Option<GateRegion<S>>,
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

impl<S: Scalar> TrackGate<S> {
    fn new(region: Option<GateRegion<S>>) -> Self {
        TrackGate {
            region,
            champion_index: NO_CHAMPION,
            champion_cost: 0,
        }
    }

    /// The gate cost of a measurement at `observation` with `reply`, if it
    /// is inside the gate and the track (of TCAS slot `intruder`) may take
    /// it: reply identity, the tracker's own rule ([`may_take`]), `dt` after
    /// the last scan.
    fn cost(
        &self,
        intruder: &IntruderSlot<S>,
        observation: &Observation<S>,
        reply: &ReplyData<S>,
        dt: S,
    ) -> Option<u16> {
        let cost = self.region.as_ref()?.cost(observation)?;
        may_take(Some(intruder), reply, dt).then_some(cost)
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
    /// `dt`: the scan period, in seconds.
    pub(super) fn rank_batch(&mut self, config: &ScanConfig<T, F::Params>, dt: S) {
        self.prepare_gates(config);
        self.ranked = true;
        for i in 0..self.batch.len() {
            let (Some(measurement), Some(reply)) = (
                self.batch.get(i).copied(),
                self.batch_replies.get(i).copied(),
            ) else {
                continue;
            };
            let observation = Observation::new(measurement).ok();
            let priority = self.priority(observation.as_ref(), &reply, dt);
            if let Some(slot) = self.batch_priorities.get_mut(i) {
                *slot = priority;
            }
            if let Some(o) = observation {
                self.crown(i, &o, &reply, dt);
            }
        }
    }

    /// The priority of a measurement against the gates of the next scan
    /// (`dt` away) whose tracks may take its reply.
    pub(super) fn priority(
        &self,
        observation: Option<&Observation<S>>,
        reply: &ReplyData<S>,
        dt: S,
    ) -> Priority<S> {
        let Some(o) = observation else {
            return Priority {
                class: CLASS_REFUSED,
                gate_cost: 0,
                range: S::ZERO,
            };
        };
        let best = self
            .gates
            .iter()
            .zip(self.intruders.iter())
            .filter_map(|(g, intruder)| g.cost(intruder, o, reply, dt))
            .min();
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
        reply: &ReplyData<S>,
        dt: S,
    ) -> Option<usize> {
        // Champion places the new measurement would take from each entry,
        // and whether it would hold one.
        let mut dethroned = [0u8; M];
        let mut crowned = false;
        if let Some(o) = observation {
            for (gate, intruder) in self.gates.iter().zip(self.intruders.iter()) {
                let Some(cost) = gate.cost(intruder, o, reply, dt) else {
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
    /// whose gate it is nearest to so far among the entries the track may
    /// take.
    pub(super) fn crown(
        &mut self,
        index: usize,
        observation: &Observation<S>,
        reply: &ReplyData<S>,
        dt: S,
    ) {
        for (gate, intruder) in self.gates.iter_mut().zip(self.intruders.iter()) {
            let Some(cost) = gate.cost(intruder, observation, reply, dt) else {
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

    /// A gate per TCAS slot, in the slots' order: its track's for the scan
    /// being assembled (one period after the last) if the track is
    /// confirmed. Every live track has a slot between scans.
    fn prepare_gates(&mut self, config: &ScanConfig<T, F::Params>) {
        self.gates.clear();
        let params = config.tracker.params();
        let Some(step) = ScanInterval::from_ms(config.clock.period_ms)
            .and_then(|interval| F::step(params, &interval).ok())
        else {
            return;
        };
        for intruder in self.intruders.iter() {
            let confirmed = self
                .table
                .track(intruder.track)
                .filter(|t| t.is_confirmed());
            let region = confirmed.and_then(|track| {
                let predicted = track.filter().predict(params, &step).ok()?;
                track
                    .filter()
                    .gate_region(params, &predicted, &step, config.tracker.gate())
            });
            if self.gates.push(TrackGate::new(region)).is_err() {
                break;
            }
        }
    }
}
