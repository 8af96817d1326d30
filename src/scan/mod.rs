//! The scan loop's hardware-independent core: what an interrupt-driven
//! tracker does with received bytes and timer ticks, with no interrupt,
//! peripheral or clock in it, so the firmware and the host tests run the same
//! code.
//!
//! ```text
//! receive interrupt:  byte ─▶ Intake::push ─▶ wire::Decoder ─▶ MeasurementQueue ─┐
//!                                                                                  │
//! main loop:  ScanLoop::collect ◀─ the scan clock sorts each measurement ◀─────────┘
//!               (this scan / a later one / late / out of the window)
//!               ─▶ the scan's batch, by priority when over capacity
//!             ScanLoop::on_tick: TrackTable::scan, altitude trackers,
//!               tcas::assess per confirmed track
//!               ─▶ TrackReport per confirmed track, ScanSummary, Health ─▶ callback
//! advisory outputs:   AdvisoryLines::show(highest) ─▶ embedded-hal OutputPin
//! ```
//!
//! * [`Intake`] is the producer half, run in the receive interrupt: bytes
//!   into the [`Decoder`](crate::wire::Decoder), measurements into a [`MeasurementQueue`] (a plain
//!   ring buffer with no panic path; the firmware shares it through a
//!   critical section, one short one per measurement). A full queue drops
//!   the measurement and counts it; it never blocks or panics.
//! * [`ScanLoop`] is the consumer half, run from the main loop. It owns the
//!   [`TrackTable`](crate::track::TrackTable), an altitude tracker per altitude-reporting track, the
//!   scan clock and the scan's batch; [`ScanConfig`] holds the tracker
//!   configuration, the own aircraft and the clock's bounds.
//!
//! The rules below are stated once here; `docs/firmware-runtime.md` gives
//! the reasons and the measured figures.
//!
//! # Time: the scan clock
//!
//! Measurements carry the sensor's millisecond clock (`u32`, wrapping). The
//! loop locks onto it at the first measurement: that measurement's time is
//! the first scan's time, and scans follow every `period_ms`
//! ([`ClockConfig`]) of the sensor's clock. For the scan being assembled,
//! at sensor time `N`, a measurement at time `t` (`d = t − N` in wrapping
//! arithmetic, as a signed 32-bit difference) is
//!
//! * **this scan's** if `−period < d ≤ 0`: it joins the batch;
//! * **a later scan's** if `0 < d ≤ jump`: it stays queued, and the scan
//!   runs (the input has moved past it): a silence of up to `jump` runs
//!   empty scans, one per period, in which the tracks coast;
//! * **late** if `−late_window ≤ d ≤ −period`: its scan has run; dropped
//!   and counted (`late`);
//! * **out of the window** otherwise. It is held until the next
//!   measurement: if that one is within one period of it, the sensor's
//!   clock jumped, and the loop **re-locks** (counted): the scan being
//!   assembled runs (if it has measurements), and the next scan is at the
//!   held measurement's time. If not, the held one is dropped and counted
//!   (`out_of_window`). So one wild time stamp never moves the clock, and a
//!   step of the sensor's clock forwards by any amount, or back by more
//!   than `late_window` + one period (past 2³¹ ms included), costs no
//!   measurement. A step back by one period to `late_window` + one period
//!   cannot be told from late reports and costs up to three sensor scans,
//!   all counted, without a re-lock: the scan after the step is merged into
//!   the scan being assembled (its measurements counted there as in any
//!   scan), and from two periods back the one or two after it are `late`.
//!
//! Every measurement is taken from the queue once and ends in exactly one
//! scan's batch or one drop count, so a clock stepping back never makes a
//! frame be processed twice.
//!
//! The tracker has its own time: it advances by exactly one period per scan
//! and never jumps, so [`TrackTable::scan`](crate::track::TrackTable::scan) always sees a one-period
//! interval, whatever the sensor's clock did; a re-lock takes a clock step
//! to be the sensor's, not the targets'. Reports carry the sensor's time of
//! their scan.
//!
//! # Capacity: who gets the scan's `M` slots
//!
//! When a scan has more measurements than `M`, the batch keeps the most
//! important ones, in this priority:
//!
//! 1. for each confirmed track, the measurement nearest its predicted
//!    position inside its gate among those it may take (reply identity:
//!    the tracker's own rule, the same Mode S address or a correlating
//!    Mode C altitude), and when that one is also another confirmed
//!    track's nearest, the second nearest too; these are never evicted, so
//!    a confirmed track is not starved by clutter, by other intruders'
//!    replies or by a neighbour a gate away (docs/firmware-runtime.md);
//! 2. other measurements inside a confirmed track's gate that it may take,
//!    by normalised gate distance;
//! 3. all others (tentative tracks' and candidates for new tracks), nearest
//!    to the own aircraft first: an unknown return's threat grows as it
//!    closes in;
//! 4. measurements the tracker would refuse (not finite).
//!
//! A newcomer replaces the least important unprotected entry only if it is
//! strictly more important (or is itself protected by 1 once counted);
//! among exact equals the later batch slot goes first. Gates are the
//! tracker's own ([`TrackFilter::gate_region`](crate::track::TrackFilter::gate_region)) for the next scan. The
//! others are dropped and counted (`over_capacity`).
//!
//! # Own aircraft
//!
//! Positions are relative to the own aircraft (the origin), as a TCAS
//! receiver measures them; so are the tracked velocities. Each confirmed
//! track is assessed against [`ScanConfig::own`] as an
//! [`Intruder`](crate::tcas::Intruder) with its tracked position and
//! velocity and, if it reported altitude, the estimate of its altitude
//! tracker ([`crate::filter::altitude`]); a track that never
//! reported altitude is a non-altitude-reporting intruder (traffic
//! advisories at most).

mod advisory;
mod clock;
mod intake;
mod scan_loop;
mod verdict;

pub use advisory::AdvisoryLines;
pub use clock::ClockConfig;
pub use intake::{Intake, MeasurementQueue, MeasurementSource};
pub use scan_loop::{BearingTrack, Collected, ScanConfig, ScanLoop, TickReport, MAX_RA_THREATS};
pub use verdict::{RunVerdict, MAX_LOST_FRACTION_INVERSE};
