//! Each track's TCAS surveillance: reply identity, range and altitude
//! trackers, threat assessment and the RA.

use super::{BearingTrack, ScanConfig, ScanLoop};
use crate::count::increment;

use crate::filter::altitude::AltitudeQuantum;
use crate::num::{hypot, Numeric, Scalar};
use crate::tcas::detection::MAX_INTRUDER_RATE_FT_PER_S;
use crate::tcas::{Advisory, IntruderTrack, Reply, SensitivityLevel, ThreatGeometry};
use crate::track::{
    Association, FirstPoint, Measurement, PairRule, ScanReport, TrackFilter, TrackId,
};
use crate::wire::{LoopCounters, ModeSAddress, RaCode};

/// What a scan's reply carries besides its position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ReplyData<S> {
    pub(super) altitude_ft: Option<S>,
    pub(super) altitude_25ft: bool,
    pub(super) address: Option<ModeSAddress>,
}

/// This scan's assessment of one confirmed track (its range tau is the
/// range tracker's, recomputed for the report: not kept per intruder).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Assessed {
    pub(super) advisory: Advisory,
    pub(super) sensitivity: SensitivityLevel,
}

/// One track's TCAS surveillance: its intruder's Mode S address (kept for
/// the track's life), range and altitude trackers and threat state.
#[derive(Debug, Clone, Copy)]
pub(super) struct IntruderSlot<S: Scalar> {
    pub(super) track: TrackId,
    pub(super) address: Option<ModeSAddress>,
    pub(super) quantum: AltitudeQuantum,
    pub(super) tcas: IntruderTrack<S>,
    pub(super) updated: bool,
    pub(super) assessed: Option<Assessed>,
}

/// RA threats resolved together at most (the ones with the smallest
/// modified tau; more are counted, `ra_threats_over_capacity`).
pub const MAX_RA_THREATS: usize = 8;

/// Reply identity: a reply with a Mode S address
/// updates only the track of that address, and starts a track only if no
/// track has it, and only with the first of the previous scan's replies
/// with that address; a reply without one (Mode C) updates only a track
/// without an address whose altitude it correlates with, and starts one
/// only with a first point without an address whose altitude correlates.
/// A track deleted in the scan frees its address for the scan's starts
/// ([`PairRule::track_deleted`]).
pub(super) struct IdentityRule<'a, S: Scalar> {
    pub(super) intruders: &'a mut [IntruderSlot<S>],
    pub(super) replies: &'a [ReplyData<S>],
    pub(super) previous: &'a [ReplyData<S>],
    pub(super) dt: S,
}

impl<S: Scalar> IdentityRule<'_, S> {
    fn slot(&self, track: TrackId) -> Option<&IntruderSlot<S>> {
        self.intruders.iter().find(|s| s.track == track)
    }

    /// Previous-scan reply `p`, which has `address`, may start a track with
    /// it: no track has the address, and `p` is the first of the previous
    /// scan's replies with it. A track started in this scan has no slot
    /// until after the scan, and the table pairs each first point once, so
    /// that first reply is what keeps a second track from starting with the
    /// address in the same scan (from a copy of the reply, a reflection).
    fn may_start_with(&self, address: ModeSAddress, p: usize) -> bool {
        let first_with_address = self
            .previous
            .iter()
            .position(|r| r.address == Some(address));
        first_with_address == Some(p) && !self.intruders.iter().any(|s| s.address == Some(address))
    }
}

/// The update half of reply identity ([`IdentityRule`]): whether the track
/// whose TCAS slot is `slot` (none: a track without an address or an
/// altitude) may take `reply`, `dt` after its last scan. One definition for
/// the tracker's gating and the capacity ranking's gates.
pub(super) fn may_take<S: Scalar>(
    slot: Option<&IntruderSlot<S>>,
    reply: &ReplyData<S>,
    dt: S,
) -> bool {
    match (reply.address, slot.and_then(|s| s.address)) {
        (Some(a), Some(b)) => a == b,
        (None, None) => {
            let predicted = slot
                .and_then(|s| s.tcas.altitude_state().estimate())
                .map(|e| e.altitude_ft + e.vertical_rate_ft_per_s * dt);
            match (reply.altitude_ft, predicted, slot) {
                (Some(z), Some(p), Some(s)) => altitudes_correlate(z, p, s.quantum, dt),
                _ => true,
            }
        }
        _ => false,
    }
}

/// |a − b| within the altitude correlation window for `dt`: two
/// quanta plus the detection logic's 10 000 ft/min intruder-rate limit
/// (our choice: the public sources do not give DO-185B's window).
fn altitudes_correlate<S: Scalar>(a: S, b: S, quantum: AltitudeQuantum, dt: S) -> bool {
    // Each quantum's constant folds (no runtime `f64`).
    let two_quanta = match quantum {
        AltitudeQuantum::ModeC => S::from_f64_lossy(2.0 * AltitudeQuantum::ModeC.feet()),
        AltitudeQuantum::ModeS25 => S::from_f64_lossy(2.0 * AltitudeQuantum::ModeS25.feet()),
    };
    let window = two_quanta + S::from_f64_lossy(MAX_INTRUDER_RATE_FT_PER_S) * dt;
    (a - b).abs() <= window
}

impl<S: Scalar> PairRule for IdentityRule<'_, S> {
    fn may_update(&self, track: TrackId, k: usize) -> bool {
        self.replies
            .get(k)
            .is_some_and(|reply| may_take(self.slot(track), reply, self.dt))
    }

    /// A first point of an earlier scan has no reply kept with it (the loop
    /// keeps the previous scan's replies only), so it starts no track here.
    fn may_start(&self, first: FirstPoint, k: usize) -> bool {
        let FirstPoint::PreviousScan(p) = first else {
            return false;
        };
        let (Some(first), Some(second)) = (self.previous.get(p), self.replies.get(k)) else {
            return false;
        };
        if first.address != second.address {
            return false;
        }
        if second.address.is_some_and(|a| !self.may_start_with(a, p)) {
            return false;
        }
        match (first.altitude_ft, second.altitude_ft) {
            (Some(a), Some(b)) => altitudes_correlate(a, b, quantum_of(second), self.dt),
            _ => true,
        }
    }

    /// The deleted track's slot (dropped after the scan) no longer holds
    /// its address.
    fn track_deleted(&mut self, track: TrackId) {
        if let Some(s) = self.intruders.iter_mut().find(|s| s.track == track) {
            s.address = None;
        }
    }
}

fn quantum_of<S>(reply: &ReplyData<S>) -> AltitudeQuantum {
    if reply.altitude_25ft {
        AltitudeQuantum::ModeS25
    } else {
        AltitudeQuantum::ModeC
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
    /// Feeds each reply the tracker used to its track's range and altitude
    /// trackers (a started track gets its slot, its address and the
    /// altitude tracker of its reply's quantum); coasts the others; frees
    /// the slots of deleted tracks (a track updated and then deleted in the
    /// scan gets none).
    pub(super) fn update_intruders(
        &mut self,
        config: &ScanConfig<T, F::Params>,
        report: &ScanReport,
    ) {
        let table = &self.table;
        self.intruders.retain(|s| table.track(s.track).is_some());
        for s in self.intruders.iter_mut() {
            s.updated = false;
            s.assessed = None;
        }
        // The first scan has no interval, and no track yet.
        if report.interval_ms == 0 {
            return;
        }
        let dt = S::seconds_from_ms(report.interval_ms);
        if !dt.is_valid() {
            return;
        }
        let n = self.batch.len().min(M);
        let replies = self.batch.iter().zip(self.batch_replies.iter());
        for (code, (measurement, reply)) in self.codes.iter().take(n).zip(replies) {
            let (Association::Updated(id) | Association::Started(id)) = *code else {
                continue;
            };
            let index = match self.intruders.iter().position(|s| s.track == id) {
                Some(i) => Some(i),
                // Updated, then deleted in the same scan (it left the
                // volume): no slot for a dead track.
                None if self.table.track(id).is_none() => continue,
                None => {
                    // A track per slot at most, and a slot per track: there
                    // is room for every live track.
                    let slot = IntruderSlot {
                        track: id,
                        address: reply.address,
                        quantum: quantum_of(reply),
                        tcas: IntruderTrack::new(),
                        updated: false,
                        assessed: None,
                    };
                    let free = self.intruders.len();
                    self.intruders.push(slot).ok().map(|()| free)
                }
            };
            let range_m = match *measurement {
                Measurement::Polar { range, .. } => range,
                Measurement::Cartesian { x, y } => hypot(x, y),
            };
            if let Some(s) = index.and_then(|i| self.intruders.get_mut(i)) {
                let reply = Reply {
                    range_m,
                    altitude_ft: reply.altitude_ft,
                };
                let incredible = s.tcas.altitude_state().incredible_reports();
                if s.tcas
                    .scan(config.altitude_of(s.quantum), Some(reply), dt)
                    .is_err()
                {
                    increment(&mut self.counters.intruder_tracker_errors);
                }
                let counted = &mut self.counters.altitude_not_credible;
                *counted = counted.saturating_add(
                    s.tcas
                        .altitude_state()
                        .incredible_reports()
                        .saturating_sub(incredible),
                );
                s.updated = true;
            }
        }
        for s in self.intruders.iter_mut() {
            if !s.updated
                && s.tcas
                    .scan(config.altitude_of(s.quantum), None, dt)
                    .is_err()
            {
                increment(&mut self.counters.intruder_tracker_errors);
            }
        }
    }

    /// The TCAS cycle: the sensitivity level for the own
    /// aircraft, the threat logic of every confirmed track (advisories only
    /// from firm tracks: [`crate::tcas::ThreatState::assess`]), then the RA
    /// against the RA threats ([`CollisionAvoidance::resolve`]). Failures
    /// are counted (`assessment_errors`) and give no advisory.
    pub(super) fn assess_tracks(
        &mut self,
        config: &ScanConfig<T, F::Params>,
        report: &ScanReport,
    ) -> RaOutput {
        let none = RaOutput {
            advisory: None,
            clear_of_conflict: false,
        };
        if report.interval_ms == 0 {
            return none;
        }
        let dt = S::seconds_from_ms(report.interval_ms);
        if !dt.is_valid() {
            return none;
        }
        let Ok(cycle) = self.cas.begin_cycle(&config.own, false) else {
            increment(&mut self.counters.assessment_errors);
            return none;
        };
        let mut threats: heapless::Vec<ThreatGeometry<S>, MAX_RA_THREATS> = heapless::Vec::new();
        for track in self.table.tracks().filter(|t| t.is_confirmed()) {
            let Some(slot) = self.intruders.iter_mut().find(|s| s.track == track.id()) else {
                continue;
            };
            let status = match slot.tcas.assess(&cycle, track.filter().bearing_track(), dt) {
                Ok(status) => status,
                Err(_) => {
                    increment(&mut self.counters.assessment_errors);
                    continue;
                }
            };
            slot.assessed = Some(Assessed {
                advisory: status.map_or(Advisory::None, |s| s.advisory),
                sensitivity: cycle.params.level,
            });
            if let Some(g) = status.and_then(|s| s.geometry) {
                add_threat(&mut threats, g, &mut self.counters);
            }
        }
        match self.cas.resolve(&cycle, &threats, dt) {
            Ok(out) => RaOutput {
                advisory: out.advisory.map(|a| RaCode {
                    sense: a.sense,
                    strength: a.strength,
                }),
                clear_of_conflict: out.clear_of_conflict,
            },
            Err(_) => {
                increment(&mut self.counters.assessment_errors);
                none
            }
        }
    }
}

/// This scan's RA, as reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct RaOutput {
    pub(super) advisory: Option<RaCode>,
    pub(super) clear_of_conflict: bool,
}

/// Adds an RA threat; beyond [`MAX_RA_THREATS`] the one with the largest
/// modified tau is left out (counted).
fn add_threat<S: Scalar>(
    threats: &mut heapless::Vec<ThreatGeometry<S>, MAX_RA_THREATS>,
    threat: ThreatGeometry<S>,
    counters: &mut LoopCounters,
) {
    let Err(threat) = threats.push(threat) else {
        return;
    };
    increment(&mut counters.ra_threats_over_capacity);
    let latest = threats.iter_mut().reduce(|a, b| {
        if b.modified_tau_s > a.modified_tau_s {
            b
        } else {
            a
        }
    });
    if let Some(latest) = latest {
        if threat.modified_tau_s < latest.modified_tau_s {
            *latest = threat;
        }
    }
}
