//! Resolution advisories: the sense (up or down, preferring not to cross the
//! intruder's altitude when the other sense gives ALIM), the strength
//! (preventive, level-off, climb/descend, increase), strengthening,
//! weakening, one sense reversal, clear of conflict, and one defined
//! behaviour against several threats. Sources: FAA, "Introduction to TCAS II Version 7.1" (sense and
//! strength selection, weakening, v7.1's level-off RA); DO-185B as
//! transcribed in ledieuke/tcas_simulator `detect.py` (`model_sep`,
//! `project_vertical_given_zdgoal`, `model_maneuvers`) and
//! `tcasConstant.py` (the constants below) and `resolution.py` (the
//! reversal conditions); FlightGear `tcas.cxx` (`determineRAsense`).
//! Coordination with another TCAS aircraft and DO-185B's multi-threat
//! composite RAs are not modelled (docs/tcas.md).

use super::detection::{Cycle, ThreatGeometry};
use super::held::Held;
use super::measures::all_valid;
use super::TcasError;
use crate::filter::altitude::OutOfLine;
use crate::num::Scalar;

/// Pilot response delay to an initial RA, s (DO-185B `TV1`).
pub const INITIAL_DELAY_S: f64 = 5.0;
/// Pilot response delay to a change of RA, s (DO-185B `QUIKREAC`).
pub const CHANGE_DELAY_S: f64 = 2.5;
/// Vertical acceleration of the response, ft/s² (DO-185B `VACCEL`, 0.25 g).
pub const RESPONSE_ACCELERATION_FT_PER_S2: f64 = 8.0;
/// Vertical acceleration of an increase-rate response, ft/s² (DO-185B
/// `RACCEL`, 0.35 g).
pub const INCREASE_ACCELERATION_FT_PER_S2: f64 = 11.2;
/// Climb or descend RA rate, ft/s (DO-185B `CLMRT`, 1500 ft/min).
pub const RA_RATE_FT_PER_S: f64 = 1500.0 / 60.0;
/// Increase-rate RA rate, ft/s (DO-185B `INC_CLMRATE`, 2500 ft/min).
pub const INCREASE_RATE_FT_PER_S: f64 = 2500.0 / 60.0;
/// Highest own rate the model keeps, ft/s (DO-185B `MAXDRATE`, 4400 ft/min).
pub const MAX_MODEL_RATE_FT_PER_S: f64 = 4400.0 / 60.0;
/// An intruder this far above (below) own makes an up (down) RA a crossing
/// one, ft (DO-185B `CROSSTHR`).
pub const CROSSING_THRESHOLD_FT: f64 = 100.0;
/// An RA is not weakened before this age, s (DO-185B `NOWEAK`).
pub const NO_WEAKENING_S: f64 = 10.0;
/// A reversed RA is not weakened before this time after the reversal, s
/// (DO-185B `TRVSNOWEAK`).
pub const REVERSAL_NO_WEAKENING_S: f64 = 5.0;
/// No sense reversal within this range tau of closest approach, s
/// (DO-185B `MINRITIME`, "inhibit reversals and increases").
pub const MIN_REVERSAL_TAU_S: f64 = 4.0;
/// Within this range tau a threat must be [`REVERSAL_CLOSE_ALTITUDE_FT`]
/// on the RA's side of the own aircraft for a reversal, beyond it
/// [`CROSSING_THRESHOLD_FT`], s (DO-185B `MINRVSTIME`).
pub const REVERSAL_CLOSE_TAU_S: f64 = 10.0;
/// See [`REVERSAL_CLOSE_TAU_S`], ft (DO-185B `AVEVALT`).
pub const REVERSAL_CLOSE_ALTITUDE_FT: f64 = 200.0;
/// The reversed sense must model this much more separation than the
/// current one, ft (DO-185B `NOZCROSS`).
pub const REVERSAL_MARGIN_FT: f64 = 100.0;
/// An own rate this far on the wrong side of the goal makes the RA
/// corrective, ft/s (DO-185B `HYSTERCOR`, 300 ft/min).
pub const CORRECTIVE_HYSTERESIS_FT_PER_S: f64 = 300.0 / 60.0;
/// Descend RAs are inhibited below this radio altitude and allowed again
/// above the next, ft (DO-185B `NODESLO`, `NODESHI`; booklet 1100 ± 100).
pub const DESCEND_INHIBIT_FT: (f64, f64) = (1000.0, 1200.0);
/// Increase-descent RAs likewise (DO-185B `ZNOINCDESLO`, `ZNOINCDESHI`;
/// booklet 1450 ft).
pub const INCREASE_DESCENT_INHIBIT_FT: (f64, f64) = (1450.0, 1650.0);
/// Aural annunciations likewise (DO-185B `ZNO_AURALLO`, `ZNO_AURALHI`;
/// booklet 500 ± 100).
pub const AURAL_INHIBIT_FT: (f64, f64) = (400.0, 600.0);

// Not inlined: each call site would otherwise carry the f64-to-S
// conversion (soft-float on the M0), which costs flash.
#[inline(never)]
fn c<S: Scalar>(v: f64) -> S {
    S::from_f64_lossy(v)
}

/// Up (climb side) or down.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RaSense {
    /// Upward sense: climb, or don't descend (booklet, "RA Sense Selection").
    Up,
    /// Downward sense: descend, or don't climb (booklet, "RA Sense Selection").
    Down,
}

impl RaSense {
    /// The lower-case name (`"up"`, `"down"`).
    pub const fn name(self) -> &'static str {
        match self {
            RaSense::Up => "up",
            RaSense::Down => "down",
        }
    }

    fn other(self) -> Self {
        match self {
            RaSense::Up => RaSense::Down,
            RaSense::Down => RaSense::Up,
        }
    }
}

/// RA strength, weakest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RaStrength {
    /// Don't descend / don't climb while the own rate already complies
    /// ("monitor vertical speed").
    Preventive,
    /// Level off: the own rate is to go to zero (v7.1's replacement of
    /// "adjust vertical speed", also the weakened positive RA).
    LevelOff,
    /// Climb or descend at 1500 ft/min (or keep a steeper rate).
    Positive,
    /// Increase climb or descent to 2500 ft/min.
    Increase,
}

impl RaStrength {
    /// The lower-case name (`"preventive"`, `"level-off"`, …).
    pub const fn name(self) -> &'static str {
        match self {
            RaStrength::Preventive => "preventive",
            RaStrength::LevelOff => "level-off",
            RaStrength::Positive => "positive",
            RaStrength::Increase => "increase",
        }
    }
}

/// This cycle's resolution advisory.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ResolutionAdvisory<S> {
    /// The sense selected: the one with the larger modelled separation
    /// (booklet; FlightGear `determineRAsense`).
    pub sense: RaSense,
    /// The strength: the weakest that models ALIM (booklet, v7.1).
    pub strength: RaStrength,
    /// The RA took the own aircraft through a threat's altitude.
    pub crossing: bool,
    /// The rate the RA asks for, ft/s (a floor for up, a ceiling for down).
    pub goal_rate_ft_per_s: S,
    /// The own rate does not satisfy the RA yet.
    pub corrective: bool,
    /// Threats resolved together.
    pub threats: u8,
    /// Time since the RA started, s.
    pub age_s: S,
    /// The sense was reversed in this encounter (at most once).
    pub reversed: bool,
}

/// What the resolution logic decided this cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ResolutionOutput<S> {
    /// The active RA, if any.
    pub advisory: Option<ResolutionAdvisory<S>>,
    /// The last RA ended this cycle ("clear of conflict").
    pub clear_of_conflict: bool,
}

/// The low-altitude and performance inhibits of one cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Inhibits {
    /// Climb RAs inhibited (aircraft performance; an input).
    pub climb: bool,
    /// Descend RAs inhibited (low altitude).
    pub descend: bool,
    /// Increase-descent RAs inhibited (low altitude).
    pub increase_descent: bool,
    /// Aural annunciations inhibited (low altitude).
    pub aural: bool,
}

/// The inhibits' hysteresis on the radio altitude: each is set below its
/// low bound and cleared above its high bound; without a radio altitude
/// (above the altimeter's range) none is set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LowAltitudeInhibits {
    current: Held<Inhibits>,
}

fn hysteresis<S: Scalar>(was: Option<bool>, radio_ft: Option<S>, (low, high): (f64, f64)) -> bool {
    match (radio_ft, was) {
        (None, _) => false,
        (Some(h), None) => h < c(low),
        (Some(h), Some(true)) => h <= c(high),
        (Some(h), Some(false)) => h < c(low),
    }
}

impl Default for LowAltitudeInhibits {
    fn default() -> Self {
        Self::new()
    }
}

impl LowAltitudeInhibits {
    /// No inhibit set yet: the first radio altitude decides each one.
    pub const fn new() -> Self {
        LowAltitudeInhibits {
            current: Held::unset(Inhibits {
                climb: false,
                descend: false,
                increase_descent: false,
                aural: false,
            }),
        }
    }

    /// This cycle's inhibits for a radio altitude (ft) and the climb
    /// inhibit input.
    pub fn update<S: Scalar>(&mut self, radio_altitude_ft: Option<S>, climb: bool) -> Inhibits {
        let was = self.current.get();
        let next = Inhibits {
            climb,
            descend: hysteresis(
                was.map(|w| w.descend),
                radio_altitude_ft,
                DESCEND_INHIBIT_FT,
            ),
            increase_descent: hysteresis(
                was.map(|w| w.increase_descent),
                radio_altitude_ft,
                INCREASE_DESCENT_INHIBIT_FT,
            ),
            aural: hysteresis(was.map(|w| w.aural), radio_altitude_ft, AURAL_INHIBIT_FT),
        };
        self.current.put(next);
        next
    }
}

/// The own aircraft's altitude `t` s ahead when it holds its rate for
/// `delay` s and then accelerates at `accel` to `goal` (DO-185B
/// `project_vertical_given_zdgoal`).
fn project_own<S: Scalar>(t: S, z: S, rate: S, goal: S, delay: S, accel: S) -> S {
    let to_goal = (goal - rate).abs().over(accel);
    let accelerating = (t - delay).max_of(S::ZERO).min_of(to_goal);
    let at_goal = (t - delay - to_goal).max_of(S::ZERO);
    let signed_accel = if goal >= rate { accel } else { -accel };
    z + rate.times(delay.min_of(t))
        + (rate + c::<S>(0.5).times(signed_accel).times(accelerating)).times(accelerating)
        + goal.times(at_goal)
}

/// A modelled manoeuvre of the own aircraft.
#[derive(Debug, Clone, Copy)]
struct Manoeuvre<S> {
    goal: S,
    delay: S,
    accel: S,
}

/// The separation in the sense's direction (own above the intruder for
/// up) at the threat's range tau and modified tau, the smaller (DO-185B
/// `model_sep`).
fn modelled_separation<S: Scalar>(
    own_altitude: S,
    own_rate: S,
    sense: RaSense,
    m: Manoeuvre<S>,
    threat: &ThreatGeometry<S>,
) -> S {
    let at = |t: S| {
        let own = project_own(t, own_altitude, own_rate, m.goal, m.delay, m.accel);
        let intruder =
            threat.intruder.altitude_ft + threat.intruder.vertical_rate_ft_per_s.times(t);
        match sense {
            RaSense::Up => own - intruder,
            RaSense::Down => intruder - own,
        }
    };
    at(threat.range_tau_s).min_of(at(threat.modified_tau_s))
}

/// The goal rate of a strength in a sense for the current own rate.
fn goal_rate<S: Scalar>(sense: RaSense, strength: RaStrength, own_rate: S) -> S {
    let up = match strength {
        RaStrength::Preventive => match sense {
            RaSense::Up => own_rate.max_of(S::ZERO),
            RaSense::Down => -(own_rate.min_of(S::ZERO)),
        },
        RaStrength::LevelOff => S::ZERO,
        RaStrength::Positive => {
            let own_up = match sense {
                RaSense::Up => own_rate,
                RaSense::Down => -own_rate,
            };
            own_up
                .min_of(c(MAX_MODEL_RATE_FT_PER_S))
                .max_of(c(RA_RATE_FT_PER_S))
        }
        RaStrength::Increase => c(INCREASE_RATE_FT_PER_S),
    };
    match sense {
        RaSense::Up => up,
        RaSense::Down => -up,
    }
}

/// The negative RA that fits the own rate: preventive if it already
/// complies, level-off if it does not.
fn negative_strength<S: Scalar>(sense: RaSense, own_rate: S) -> RaStrength {
    let complies = match sense {
        RaSense::Up => own_rate >= S::ZERO,
        RaSense::Down => own_rate <= S::ZERO,
    };
    if complies {
        RaStrength::Preventive
    } else {
        RaStrength::LevelOff
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct ActiveRa<S> {
    sense: RaSense,
    strength: RaStrength,
    crossing: bool,
    age_s: S,
    strength_age_s: S,
    reversed: bool,
}

/// The resolution logic's memory: the active RA, if any.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ResolutionState<S> {
    active: Held<ActiveRa<S>>,
}

impl<S: Scalar> Default for ResolutionState<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// The smallest modelled separation over the threats (+∞-like `None` with
/// no threats).
fn worst<S: Scalar>(
    cycle: &Cycle<S>,
    threats: &[ThreatGeometry<S>],
    sense: RaSense,
    m: Manoeuvre<S>,
) -> Option<S> {
    threats
        .iter()
        .map(|t| {
            modelled_separation(
                cycle.own.pressure_altitude_ft,
                cycle.own.vertical_rate_ft_per_s,
                sense,
                m,
                t,
            )
        })
        .reduce(|a, b| a.min_of(b))
}

fn crosses<S: Scalar>(cycle: &Cycle<S>, threats: &[ThreatGeometry<S>], sense: RaSense) -> bool {
    let threshold = c::<S>(CROSSING_THRESHOLD_FT);
    threats.iter().any(|t| {
        let h = t.intruder.altitude_ft - cycle.own.pressure_altitude_ft;
        match sense {
            RaSense::Up => h >= threshold,
            RaSense::Down => h <= -threshold,
        }
    })
}

impl<S: Scalar> ResolutionState<S> {
    /// No active RA.
    pub const fn new() -> Self {
        ResolutionState {
            active: Held::unset(ActiveRa {
                sense: RaSense::Up,
                strength: RaStrength::Preventive,
                crossing: false,
                age_s: S::ZERO,
                strength_age_s: S::ZERO,
                reversed: false,
            }),
        }
    }

    /// Whether an RA is in force.
    pub fn is_active(&self) -> bool {
        self.active.get().is_some()
    }

    fn allowed(cycle: &Cycle<S>, sense: RaSense, strength: RaStrength) -> bool {
        let i = &cycle.inhibits;
        match (sense, strength) {
            (_, RaStrength::Preventive | RaStrength::LevelOff) => true,
            (RaSense::Up, _) => !i.climb,
            (RaSense::Down, RaStrength::Positive) => !i.descend,
            (RaSense::Down, RaStrength::Increase) => !i.descend && !i.increase_descent,
        }
    }

    fn manoeuvre(
        &self,
        cycle: &Cycle<S>,
        sense: RaSense,
        strength: RaStrength,
        delay: f64,
    ) -> Manoeuvre<S> {
        let accel = if strength == RaStrength::Increase {
            INCREASE_ACCELERATION_FT_PER_S2
        } else {
            RESPONSE_ACCELERATION_FT_PER_S2
        };
        Manoeuvre {
            goal: goal_rate(sense, strength, cycle.own.vertical_rate_ft_per_s),
            delay: c(delay),
            accel: c(accel),
        }
    }

    /// The weakest allowed RA in `sense` that models ALIM against every
    /// threat; the strongest allowed one when none does.
    fn weakest_sufficient(
        &self,
        cycle: &Cycle<S>,
        threats: &[ThreatGeometry<S>],
        sense: RaSense,
        alim: S,
        delay: f64,
    ) -> RaStrength {
        let own_rate = cycle.own.vertical_rate_ft_per_s;
        let mut best = negative_strength(sense, own_rate);
        for strength in [negative_strength(sense, own_rate), RaStrength::Positive] {
            if !Self::allowed(cycle, sense, strength) {
                continue;
            }
            best = strength;
            let m = self.manoeuvre(cycle, sense, strength, delay);
            if worst(cycle, threats, sense, m).is_some_and(|s| s >= alim) {
                return strength;
            }
        }
        best
    }

    /// Whether the active RA `a` is to be reversed this cycle, after
    /// DO-185B `reversal_check`/`reversal_proj_check`/`reversal_modeling`
    /// for an intruder without TCAS (booklet, "Sense Reversal": when the
    /// threat manoeuvres so that the current sense no longer provides
    /// adequate separation), reduced to: no reversal yet in this encounter
    /// (DO-185B `rev_geom`); every threat's range tau above 4 s
    /// (`MINRITIME`); a threat on the RA's side of the own aircraft by
    /// 100 ft (`CROSSTHR`), or by 200 ft (`AVEVALT`) within 10 s
    /// (`MINRVSTIME`); the current sense, climbing or descending at
    /// 1500 ft/min after what remains of the 5 s delay, models less than
    /// ALIM; the reversed sense, after 2.5 s (`QUIKREAC`) at 0.35 g
    /// (`RACCEL`), models a positive separation and 100 ft (`NOZCROSS`)
    /// more than the current one; and a positive RA in the reversed sense
    /// is not inhibited.
    fn reversal_due(
        &self,
        cycle: &Cycle<S>,
        threats: &[ThreatGeometry<S>],
        a: &ActiveRa<S>,
        alim: S,
    ) -> bool {
        let reversed = a.sense.other();
        if !Self::allowed(cycle, reversed, RaStrength::Positive) {
            return false;
        }
        let own = cycle.own.pressure_altitude_ft;
        let min_tau = c::<S>(MIN_REVERSAL_TAU_S);
        let close_tau = c::<S>(REVERSAL_CLOSE_TAU_S);
        let on_ra_side = |t: &ThreatGeometry<S>| {
            let h = t.intruder.altitude_ft - own;
            let h = if a.sense == RaSense::Up { h } else { -h };
            let threshold = if t.range_tau_s <= close_tau {
                REVERSAL_CLOSE_ALTITUDE_FT
            } else {
                CROSSING_THRESHOLD_FT
            };
            h >= c(threshold)
        };
        if threats.iter().any(|t| t.range_tau_s <= min_tau) || !threats.iter().any(on_ra_side) {
            return false;
        }
        let remaining = (c::<S>(INITIAL_DELAY_S) - a.age_s).max_of(S::ZERO);
        let nominal = Manoeuvre {
            goal: goal_rate(
                a.sense,
                RaStrength::Positive,
                cycle.own.vertical_rate_ft_per_s,
            ),
            delay: remaining,
            accel: c(RESPONSE_ACCELERATION_FT_PER_S2),
        };
        let reversal = Manoeuvre {
            goal: goal_rate(
                reversed,
                RaStrength::Positive,
                cycle.own.vertical_rate_ft_per_s,
            ),
            delay: remaining.max_of(c(CHANGE_DELAY_S)),
            accel: c(INCREASE_ACCELERATION_FT_PER_S2),
        };
        match (
            worst(cycle, threats, a.sense, nominal),
            worst(cycle, threats, reversed, reversal),
        ) {
            (Some(current), Some(other)) => {
                current < alim && other > S::ZERO && other > current + c(REVERSAL_MARGIN_FT)
            }
            _ => false,
        }
    }

    /// One cycle: `threats` are this cycle's RA threats ([`ThreatGeometry`]
    /// of every intruder whose status is an RA), `dt` s after the previous
    /// cycle.
    ///
    /// * New RA: the sense with the larger modelled separation at the
    ///   threats' taus (own: 5 s delay, 0.25 g to 1500 ft/min or its own
    ///   steeper rate), unless it crosses a threat's altitude and the other
    ///   sense gives ALIM; then the weakest strength that gives ALIM.
    /// * Several threats: one sense against all, each compared by its
    ///   smallest separation over the threats; the strength must give ALIM
    ///   against all.
    /// * Continuing RA: the sense is kept; it strengthens (negative →
    ///   positive → increase after 5 s) when the modelled separation with a
    ///   2.5 s delay falls below ALIM, and weakens to level-off after 10 s
    ///   when the own aircraft is already ALIM clear of every threat and
    ///   levelling off keeps it so (5 s after a reversal).
    /// * Sense reversal, at most once: the conditions of `reversal_due` (DO-185B, docs/tcas.md);
    ///   the reversed RA is positive.
    /// * No threat left: the RA ends and `clear_of_conflict` is set once.
    pub fn resolve(
        &mut self,
        cycle: &Cycle<S>,
        threats: &[ThreatGeometry<S>],
        dt: S,
    ) -> Result<ResolutionOutput<S>, TcasError> {
        all_valid(&[
            cycle.own.pressure_altitude_ft,
            cycle.own.vertical_rate_ft_per_s,
            dt,
        ])?;
        let Some(alim_ft) = cycle.params.alim_ft else {
            let ended = self.active.take().is_some();
            return Ok(ResolutionOutput {
                advisory: None,
                clear_of_conflict: ended,
            });
        };
        if threats.is_empty() {
            let ended = self.active.take().is_some();
            return Ok(ResolutionOutput {
                advisory: None,
                clear_of_conflict: ended,
            });
        }
        let alim = c::<S>(alim_ft);
        let own_rate = cycle.own.vertical_rate_ft_per_s;
        let active = match self.active.get() {
            None => {
                let up = self.manoeuvre(cycle, RaSense::Up, RaStrength::Positive, INITIAL_DELAY_S);
                let up = if Self::allowed(cycle, RaSense::Up, RaStrength::Positive) {
                    up
                } else {
                    self.manoeuvre(cycle, RaSense::Up, RaStrength::LevelOff, INITIAL_DELAY_S)
                };
                let down =
                    self.manoeuvre(cycle, RaSense::Down, RaStrength::Positive, INITIAL_DELAY_S);
                let down = if Self::allowed(cycle, RaSense::Down, RaStrength::Positive) {
                    down
                } else {
                    self.manoeuvre(cycle, RaSense::Down, RaStrength::LevelOff, INITIAL_DELAY_S)
                };
                let (Some(sep_up), Some(sep_down)) = (
                    worst(cycle, threats, RaSense::Up, up),
                    worst(cycle, threats, RaSense::Down, down),
                ) else {
                    return Err(TcasError::InvalidInput);
                };
                let mut sense = if sep_up > sep_down {
                    RaSense::Up
                } else {
                    RaSense::Down
                };
                let other_sep = if sense == RaSense::Up {
                    sep_down
                } else {
                    sep_up
                };
                if crosses(cycle, threats, sense)
                    && !crosses(cycle, threats, sense.other())
                    && other_sep >= alim
                {
                    sense = sense.other();
                }
                let strength =
                    self.weakest_sufficient(cycle, threats, sense, alim, INITIAL_DELAY_S);
                ActiveRa {
                    sense,
                    strength,
                    crossing: crosses(cycle, threats, sense),
                    age_s: S::ZERO,
                    strength_age_s: S::ZERO,
                    reversed: false,
                }
            }
            Some(mut a) if !a.reversed && self.reversal_due(cycle, threats, &a, alim) => {
                a.age_s = a.age_s + dt;
                a.sense = a.sense.other();
                a.strength = RaStrength::Positive;
                a.strength_age_s = S::ZERO;
                a.crossing = crosses(cycle, threats, a.sense);
                a.reversed = true;
                a
            }
            Some(mut a) => {
                a.age_s = a.age_s + dt;
                a.strength_age_s = a.strength_age_s + dt;
                let current = self.manoeuvre(cycle, a.sense, a.strength, CHANGE_DELAY_S);
                let separation = worst(cycle, threats, a.sense, current);
                let short = separation.is_some_and(|s| s < alim);
                let next = match a.strength {
                    RaStrength::Preventive | RaStrength::LevelOff if short => RaStrength::Positive,
                    RaStrength::Positive if short && a.strength_age_s >= c(INITIAL_DELAY_S) => {
                        RaStrength::Increase
                    }
                    s => s,
                };
                let next = if next != a.strength && Self::allowed(cycle, a.sense, next) {
                    next
                } else {
                    a.strength
                };
                let weakening_allowed = if a.reversed {
                    a.strength_age_s >= c(REVERSAL_NO_WEAKENING_S)
                } else {
                    a.age_s >= c(NO_WEAKENING_S)
                };
                let next = if next == a.strength
                    && a.strength >= RaStrength::Positive
                    && weakening_allowed
                {
                    let level =
                        self.manoeuvre(cycle, a.sense, RaStrength::LevelOff, CHANGE_DELAY_S);
                    let clear_now = threats.iter().all(|t| {
                        let h = cycle.own.pressure_altitude_ft - t.intruder.altitude_ft;
                        let h = if a.sense == RaSense::Up { h } else { -h };
                        h >= alim
                    });
                    let stays_clear =
                        worst(cycle, threats, a.sense, level).is_some_and(|s| s >= alim);
                    if clear_now && stays_clear {
                        RaStrength::LevelOff
                    } else {
                        next
                    }
                } else {
                    next
                };
                if next != a.strength {
                    a.strength = next;
                    a.strength_age_s = S::ZERO;
                }
                a
            }
        };
        self.active.put(active);
        let goal = goal_rate(active.sense, active.strength, own_rate);
        let hysteresis = c::<S>(CORRECTIVE_HYSTERESIS_FT_PER_S);
        let corrective = match active.sense {
            RaSense::Up => own_rate < goal - hysteresis,
            RaSense::Down => own_rate > goal + hysteresis,
        };
        Ok(ResolutionOutput {
            advisory: Some(ResolutionAdvisory {
                sense: active.sense,
                strength: active.strength,
                crossing: active.crossing,
                goal_rate_ft_per_s: goal,
                corrective,
                threats: u8::try_from(threats.len()).unwrap_or(u8::MAX),
                age_s: active.age_s,
                reversed: active.reversed,
            }),
            clear_of_conflict: false,
        })
    }
}
