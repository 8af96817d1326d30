//! Who gets the scan's `M` slots when it has more measurements (the
//! [`crate::scan`] docs, "Capacity").

use super::intruders::{may_take, IntruderSlot, ReplyData};
use super::{BearingTrack, ScanConfig, ScanLoop};

use crate::num::{hypot, Numeric, Scalar};
use crate::track::{GateRegion, Measurement, Observation, ScanInterval, TrackFilter};

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
/// `intruders`, same order), if the track is confirmed, and the batch
/// indices of the two nearest measurements in it so far ([`NO_ENTRY`] for
/// none): 4 bytes, where an `Option<usize>` takes 8 (32-bit cores) or 16,
/// in a record kept per track. Their gate costs are formed again when a
/// measurement in the gate is compared with them, rather than kept.
#[derive(Debug, Clone, Copy)]
pub(super) struct TrackGate<S: Numeric> {
    /// `None`: the track is tentative (or its gate could not be formed).
    /// As large as the region alone (the option is in the enum's tag).
    region: Option<GateRegion<S>>,
    nearest: u16,
    second: u16,
}

/// No measurement: not a batch index (a batch holds fewer than 65,535
/// measurements, the track table's capacity check).
const NO_ENTRY: u16 = u16::MAX;

/// `index` as a [`TrackGate`] entry.
fn entry(index: Option<usize>) -> u16 {
    index
        .and_then(|i| u16::try_from(i).ok())
        .unwrap_or(NO_ENTRY)
}

impl<S: Scalar> TrackGate<S> {
    fn new(region: Option<GateRegion<S>>) -> Self {
        TrackGate {
            region,
            nearest: NO_ENTRY,
            second: NO_ENTRY,
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

    /// The batch indices of the nearest measurement and the second nearest.
    fn nearest_two(&self) -> [Option<usize>; 2] {
        [self.nearest, self.second].map(|e| (e != NO_ENTRY).then_some(usize::from(e)))
    }

    /// [`Self::nearest_two`] once a measurement at batch index `index` and
    /// gate cost `cost` (if inside) is counted; `cost_of` gives an entry's
    /// gate cost. Ties keep the entries already there.
    fn nearest_two_with(
        &self,
        index: usize,
        cost: Option<u16>,
        cost_of: impl Fn(usize) -> Option<u16>,
    ) -> [Option<usize>; 2] {
        let [nearest, second] = self.nearest_two();
        let Some(cost) = cost else {
            return [nearest, second];
        };
        let beats = |e: Option<usize>| e.is_none_or(|e| cost_of(e).is_none_or(|c| cost < c));
        if beats(nearest) {
            [Some(index), nearest]
        } else if beats(second) {
            [nearest, Some(index)]
        } else {
            [nearest, second]
        }
    }

    fn set_nearest_two(&mut self, [nearest, second]: [Option<usize>; 2]) {
        self.nearest = entry(nearest);
        self.second = entry(second);
    }

    /// The entry at `index` left the batch. The third nearest is not
    /// kept: a gate that loses one of its two has one until the next
    /// measurement in it.
    fn remove(&mut self, index: usize) {
        let [nearest, second] = self.nearest_two();
        if nearest == Some(index) {
            self.nearest = entry(second);
            self.second = NO_ENTRY;
        } else if second == Some(index) {
            self.second = NO_ENTRY;
        }
    }
}

/// The gate cost in `gate` (of TCAS slot `intruder`) of the batch entry at
/// `index` ([`TrackGate::cost`]).
fn entry_cost<S: Scalar>(
    batch: &[Measurement<S>],
    replies: &[ReplyData<S>],
    gate: &TrackGate<S>,
    intruder: &IntruderSlot<S>,
    index: usize,
    dt: S,
) -> Option<u16> {
    let observation = Observation::new(*batch.get(index)?).ok()?;
    gate.cost(intruder, &observation, replies.get(index)?, dt)
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
    /// the priority of every entry and the nearest two in each gate (in
    /// arrival order). Only a scan with more than `M` measurements pays for this.
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
    /// important unprotected one, if the new one is more important or is
    /// protected itself. Protected, once the new one is counted (it may
    /// take a place from another): each confirmed track's nearest
    /// measurement, and the second nearest of a track whose nearest is
    /// also another's ([`crate::scan`], "Capacity").
    pub(super) fn evictable(
        &self,
        priority: &Priority<S>,
        observation: Option<&Observation<S>>,
        reply: &ReplyData<S>,
        dt: S,
    ) -> Option<usize> {
        // The newcomer's index: past every batch entry.
        let newcomer = M;
        let (batch, replies) = (&self.batch[..], &self.batch_replies[..]);
        let nearest_two = |gate: &TrackGate<S>, intruder: &IntruderSlot<S>| {
            let cost = observation.and_then(|o| gate.cost(intruder, o, reply, dt));
            gate.nearest_two_with(newcomer, cost, |i| {
                entry_cost(batch, replies, gate, intruder, i, dt)
            })
        };
        // In how many gates each entry (the newcomer last) is the nearest.
        let mut nearest_in = [0u8; M];
        let mut newcomer_nearest_in = 0u8;
        let mut count = |counts: &mut [u8; M], i: usize| match counts.get_mut(i) {
            Some(c) => *c = c.saturating_add(1),
            None => newcomer_nearest_in = newcomer_nearest_in.saturating_add(1),
        };
        for (gate, intruder) in self.gates.iter().zip(self.intruders.iter()) {
            if let [Some(i), _] = nearest_two(gate, intruder) {
                count(&mut nearest_in, i);
            }
        }
        let shared = |i: usize| nearest_in.get(i).map_or(newcomer_nearest_in, |c| *c) >= 2;
        // The second nearest of a gate whose nearest is shared: protected
        // too. Formed only when some nearest is shared.
        let mut second_kept = [false; M];
        let mut newcomer_kept = newcomer_nearest_in > 0;
        if newcomer_nearest_in >= 2 || nearest_in.iter().any(|c| *c >= 2) {
            for (gate, intruder) in self.gates.iter().zip(self.intruders.iter()) {
                if let [Some(n), Some(s)] = nearest_two(gate, intruder) {
                    if shared(n) {
                        match second_kept.get_mut(s) {
                            Some(k) => *k = true,
                            None => newcomer_kept = true,
                        }
                    }
                }
            }
        }
        // The least important unprotected entry (the last of equals).
        let mut worst: Option<(usize, &Priority<S>)> = None;
        for (i, (p, (&nearest, &second))) in self
            .batch_priorities
            .iter()
            .zip(nearest_in.iter().zip(second_kept.iter()))
            .enumerate()
        {
            if nearest > 0 || second {
                continue;
            }
            if worst.is_none_or(|(_, w)| !w.is_worse_than(p)) {
                worst = Some((i, p));
            }
        }
        let (w, worst_priority) = worst?;
        // Ties keep the measurement already in the batch.
        if newcomer_kept || worst_priority.is_worse_than(priority) {
            Some(w)
        } else {
            None
        }
    }

    /// Takes a batch entry out of the gates (it is being replaced).
    pub(super) fn release(&mut self, index: usize) {
        for gate in self.gates.iter_mut() {
            gate.remove(index);
        }
    }

    /// Counts the entry at `index` in every confirmed track's gate that
    /// holds it and whose track may take it, among the two nearest so far.
    pub(super) fn crown(
        &mut self,
        index: usize,
        observation: &Observation<S>,
        reply: &ReplyData<S>,
        dt: S,
    ) {
        let (batch, replies) = (&self.batch[..], &self.batch_replies[..]);
        for (gate, intruder) in self.gates.iter_mut().zip(self.intruders.iter()) {
            let Some(cost) = gate.cost(intruder, observation, reply, dt) else {
                continue;
            };
            let seen: &TrackGate<S> = gate;
            let next = seen.nearest_two_with(index, Some(cost), |i| {
                entry_cost(batch, replies, seen, intruder, i, dt)
            });
            gate.set_nearest_two(next);
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
            // A gate the tracker would end the track for (the design's
            // rule 7) gates nothing there, and none here.
            let region = confirmed
                .and_then(|track| {
                    let predicted = track.filter().predict(params, &step).ok()?;
                    track
                        .filter()
                        .gate_region(params, &predicted, &step, config.tracker.gate())
                })
                .filter(|region| !config.tracker.gate_too_wide(region));
            if self.gates.push(TrackGate::new(region)).is_err() {
                break;
            }
        }
    }
}
