//! Al-Wagih & Abdulla's M5, parallel αβ tracking (Algorithm 3, Figure 4):
//! K fixed-gain αβ trackers run on every measurement and the prediction with
//! the lowest absolute innovation is taken.
//!
//! # Why this is not a gain schedule
//!
//! A [`crate::gain::GainSchedule`] chooses the gains of *one* filter and
//! keeps no filter state. M5 never changes any tracker's gains: it keeps K
//! complete filter states and chooses among their *outputs*. So it is an
//! estimator built from filters, beside [`crate::filter::Cartesian`], and it
//! uses the gain layer only for its members' gains (M1's β, eq. 23b).
//!
//! # Reading of Algorithm 3
//!
//! Step 1 prepares K trackers "with different α's and β's"; we space the α's
//! evenly on [min, max] ⊂ (0, 1] and give each β = α²/(2 − α) (eq. 23b), the
//! M1 relation, since the paper gives no values. Step 2 tracks with all K,
//! independently: no member is ever reset to another's state (the paper
//! describes none). Step 3 "at each time step, consider the prediction value
//! with the lowest absolute error as optimal one": among the members'
//! predictions x_p,k of measurement z, the one with the least |z − x_p,k|
//! (ties to the lowest index) is the bank's output for that step
//! ([`BankSelection`]), and that member's smoothed state is the bank's
//! estimate until the next measurement ([`ParallelBank::position`],
//! [`ParallelBank::predict`]).
//!
//! Note what step 3 implies, for whoever reads the paper's RMSE tables: the
//! selected "prediction" is chosen *after* seeing the measurement it
//! predicts, so it is not a one-step-ahead prediction in the causal sense;
//! with many members it tends to the measurement itself. The causal
//! alternative is [`ParallelBank::predict`] before the update (the member
//! that won the previous step); experiments should report both.
//!
//! Selection is per axis: [`CartesianBank`] runs one bank per axis (the
//! paper evaluates X and Y separately, Tables 1–2).
//!
//! Irregular intervals (real report times) bound every member's gains as
//! [`crate::gain::ScheduledFilter`] bounds a schedule's
//! ([`crate::gain::robust_gains`]); at a regular interval, as in the paper,
//! they are the members' own.

use core::fmt;

use crate::filter::{
    outcome as outcome_of, AlphaBeta, FilterError, Gains, IntervalSpan, Phase, Prediction,
    StepGains, UpdateOutcome,
};
use crate::gain::RecentIntervals;
use crate::gains::{
    beta_from_alpha, check_capacity, check_range, config_quantity, grid_point, ConfigError,
};
use crate::num::{Numeric, Quantity, Real};

/// Configuration of a bank (`bank:k=8,min=0.05,max=1`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BankConfig {
    /// K, the number of members, 1 ≤ k ≤ the type's capacity. Default 8.
    pub k: u16,
    /// The members' α, evenly spaced from `alpha_min` to `alpha_max`,
    /// 0 < min ≤ max ≤ 1 (eq. 23a); β from eq. (23b). Default 0.05 to 1.
    pub alpha_min: f64,
    /// The largest member α (see `alpha_min`).
    pub alpha_max: f64,
}

impl BankConfig {
    /// K = 8 members, α from 0.05 to 1.
    pub const DEFAULT: Self = BankConfig {
        k: 8,
        alpha_min: 0.05,
        alpha_max: 1.0,
    };

    /// Checks k ≥ 1 and 0 < `alpha_min` ≤ `alpha_max` ≤ 1 (distinct when k > 1).
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.k == 0 {
            return Err(ConfigError::OutOfRange { parameter: "k" });
        }
        check_range(self.alpha_min, 0.0, 1.0, false, "min")?;
        check_range(self.alpha_max, self.alpha_min, 1.0, true, "max")?;
        if self.k > 1 && self.alpha_max <= self.alpha_min {
            return Err(ConfigError::OutOfRange { parameter: "max" });
        }
        Ok(())
    }
}

/// Why a bank could not be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BankError {
    /// No members, or more than the capacity K.
    MemberCount,
}

impl fmt::Display for BankError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a bank needs between 1 and K members")
    }
}

impl core::error::Error for BankError {}

/// The member chosen for one measurement (Algorithm 3, step 3).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BankSelection<N: Numeric> {
    /// Index of the member with the least |innovation|.
    pub member: usize,
    /// Its prediction x_p of the measurement: the bank's output.
    pub predicted: N::Length,
    /// Its innovation z − x_p.
    pub residual: N::Length,
}

/// What a bank update did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BankOutcome<N: Numeric> {
    /// First measurement: every member took it as its position.
    FirstPoint,
    /// Second measurement: every member took its velocity from the difference.
    SecondPoint,
    /// A filtered update and the member selected for it (Algorithm 3, step 3).
    Filtered(BankSelection<N>),
    /// The interval was longer than
    /// [`MAX_INTERVAL_S`](crate::filter::MAX_INTERVAL_S): every member
    /// restarted, with this measurement as its first point.
    Restarted,
    /// Less than [`MIN_INTERVAL_S`](crate::filter::MIN_INTERVAL_S) after
    /// the previous measurement: not used, nothing changed.
    Skipped,
}

/// M5 on one axis: up to K fixed-gain αβ trackers (storage for K, `len`
/// in use).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ParallelBank<N: Numeric, const K: usize> {
    members: [AlphaBeta<N>; K],
    gains: [Gains<N>; K],
    len: usize,
    selected: usize,
    last: Option<BankSelection<N>>,
    saturations: u32,
    /// The intervals that bound the members' gains, as
    /// [`crate::gain::ScheduledFilter`] keeps them.
    intervals: RecentIntervals<N::Interval>,
}

impl<N: Numeric, const K: usize> ParallelBank<N, K> {
    /// A bank whose members have `gains` (1 ≤ len ≤ K).
    pub fn new(gains: &[Gains<N>]) -> Result<Self, BankError> {
        let first = *gains.first().ok_or(BankError::MemberCount)?;
        if gains.len() > K {
            return Err(BankError::MemberCount);
        }
        let mut all = [first; K];
        for (slot, g) in all.iter_mut().zip(gains) {
            *slot = *g;
        }
        Ok(ParallelBank {
            members: [AlphaBeta::new(); K],
            gains: all,
            len: gains.len(),
            selected: 0,
            last: None,
            saturations: 0,
            intervals: RecentIntervals::NONE,
        })
    }

    /// The bank a [`BankConfig`] describes.
    pub fn from_config(c: &BankConfig) -> Result<Self, ConfigError> {
        c.validate()?;
        check_capacity(c.k, K, "k")?;
        let k = usize::from(c.k);
        let lo: N::Ratio = config_quantity(c.alpha_min, "min")?;
        let hi: N::Ratio = config_quantity(c.alpha_max, "max")?;
        let mut gains = [Gains::alpha_beta(N::Ratio::ONE, N::Ratio::ONE)
            .map_err(|_| ConfigError::NotRepresentable { parameter: "min" })?;
            K];
        for (i, g) in gains.iter_mut().take(k).enumerate() {
            let a = grid_point(lo, hi, i, k);
            *g = Gains::alpha_beta(a, beta_from_alpha(a))
                .map_err(|_| ConfigError::NotRepresentable { parameter: "min" })?;
        }
        Self::new(gains.get(..k).unwrap_or(&[]))
            .map_err(|_| ConfigError::OutOfRange { parameter: "k" })
    }

    /// Members in use.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no member is in use (never, for a bank built by [`Self::new`]).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Member `i`'s filter state, `None` past [`Self::len`].
    pub fn member(&self, i: usize) -> Option<&AlphaBeta<N>> {
        self.members.get(..self.len)?.get(i)
    }

    /// Member `i`'s fixed gains, `None` past [`Self::len`].
    pub fn member_gains(&self, i: usize) -> Option<&Gains<N>> {
        self.gains.get(..self.len)?.get(i)
    }

    /// The member chosen at the last filtered update (0 before).
    pub fn selected(&self) -> usize {
        self.selected
    }

    /// The selection of the last filtered update, `None` before one.
    pub fn last_selection(&self) -> Option<BankSelection<N>> {
        self.last
    }

    /// How many measurements the members have seen (they all see the same).
    pub fn phase(&self) -> Phase {
        self.members.first().map_or(Phase::Empty, |m| m.phase())
    }

    /// The selected member's smoothed position.
    pub fn position(&self) -> N::Length {
        self.current().map_or(N::Length::ZERO, |m| m.position())
    }

    /// The selected member's smoothed velocity.
    pub fn velocity(&self) -> N::Speed {
        self.current().map_or(N::Speed::ZERO, |m| m.velocity())
    }

    /// Updates or coasts refused because a member's arithmetic saturated.
    pub fn saturations(&self) -> u32 {
        self.saturations
    }

    fn current(&self) -> Option<&AlphaBeta<N>> {
        self.members.get(self.selected)
    }

    /// The selected member's prediction `dt` ahead (causal: chosen at the
    /// previous measurement).
    pub fn predict(&self, dt: N::Interval) -> Result<Prediction<N>, FilterError> {
        self.current()
            .ok_or(FilterError::InvalidInterval)?
            .predict(dt)
    }

    /// Runs every member on `z` (all or none) and selects the member with the
    /// least |innovation| (Algorithm 3, steps 2–3). A measurement that is
    /// not a valid number is refused before the interval is looked at, as
    /// by [`AlphaBeta::update`].
    pub fn update(&mut self, z: N::Length, dt: N::Interval) -> Result<BankOutcome<N>, FilterError> {
        if !z.is_valid() {
            return Err(FilterError::InvalidMeasurement);
        }
        let mut next = *self;
        let restart = match self.interval_span(dt)? {
            IntervalSpan::TooShort => return Ok(BankOutcome::Skipped),
            IntervalSpan::TooLong => {
                next.restart();
                true
            }
            IntervalSpan::InRange => false,
        };
        match next
            .step_gains(dt)
            .and_then(|steps| next.update_step(z, &steps))
        {
            Ok(outcome) => {
                next.record_intervals(&outcome, dt);
                *self = next;
                Ok(if restart {
                    BankOutcome::Restarted
                } else {
                    outcome
                })
            }
            Err(e) => {
                self.saturations = next.saturations;
                Err(e)
            }
        }
    }

    /// The interval policy of the filters
    /// ([`KinematicFilter::interval_span`](crate::filter::KinematicFilter::interval_span);
    /// the first measurement takes any valid interval).
    fn interval_span(&self, dt: N::Interval) -> Result<IntervalSpan, FilterError> {
        match self.members.first() {
            Some(m) if m.phase() != Phase::Empty => m.interval_span(dt),
            _ => Ok(IntervalSpan::InRange),
        }
    }

    /// Every member back to its first point's wait (the counts kept).
    fn restart(&mut self) {
        for member in self.members.iter_mut() {
            member.restart();
        }
        self.selected = 0;
        self.last = None;
        self.intervals = RecentIntervals::NONE;
    }

    /// The intervals after an update `dt` after the previous one that gave
    /// `outcome`.
    fn record_intervals(&mut self, outcome: &BankOutcome<N>, dt: N::Interval) {
        match outcome {
            BankOutcome::FirstPoint | BankOutcome::Restarted => self.intervals.started(false, dt),
            BankOutcome::SecondPoint => self.intervals.started(true, dt),
            BankOutcome::Filtered(_) => self.intervals.filtered(dt),
            BankOutcome::Skipped => {}
        }
    }

    /// Every member's [`StepGains`] at `dt`, its gains bounded for an
    /// irregular interval ([`crate::gain::robust_gains`]), formed once per interval (a
    /// [`CartesianBank`] shares them between its axes); a saturated or
    /// unrepresentable gain is counted and refuses the update.
    fn step_gains(&mut self, dt: N::Interval) -> Result<[StepGains<N>; K], FilterError> {
        let bounded = self
            .intervals
            .bound(self.gains, dt)
            .map_err(|_| FilterError::Saturated);
        let formed = bounded.and_then(|gains| {
            gains
                .first()
                .map_or(Err(FilterError::InvalidInterval), |g| {
                    let first = StepGains::new(g, dt)?;
                    let mut steps = [first; K];
                    for (step, gains) in steps.iter_mut().zip(&gains).take(self.len).skip(1) {
                        *step = StepGains::new(gains, dt)?;
                    }
                    Ok(steps)
                })
        });
        if formed == Err(FilterError::Saturated) {
            self.saturations = self.saturations.saturating_add(1);
        }
        formed
    }

    /// [`Self::update`] with the members' step gains formed already.
    fn update_step(
        &mut self,
        z: N::Length,
        steps: &[StepGains<N>; K],
    ) -> Result<BankOutcome<N>, FilterError> {
        let mut next = self.members;
        let mut best: Option<(BankSelection<N>, N::Length)> = None;
        let mut outcome = BankOutcome::FirstPoint;
        let active = next.iter_mut().zip(steps).take(self.len);
        for (i, (member, step)) in active.enumerate() {
            let result = member
                .update_step(z, step)
                .map(|kind| outcome_of(kind, member.last_innovation()));
            match result {
                // `update_step` does not judge the interval: it neither
                // restarts nor skips.
                Ok(
                    UpdateOutcome::FirstPoint | UpdateOutcome::Restarted | UpdateOutcome::Skipped,
                ) => outcome = BankOutcome::FirstPoint,
                Ok(UpdateOutcome::SecondPoint) => outcome = BankOutcome::SecondPoint,
                Ok(UpdateOutcome::Filtered(inn)) => {
                    let size = inn.residual.abs();
                    if best.is_none_or(|(_, b)| size < b) {
                        best = Some((
                            BankSelection {
                                member: i,
                                predicted: inn.predicted,
                                residual: inn.residual,
                            },
                            size,
                        ));
                    }
                }
                Err(e) => {
                    if e == FilterError::Saturated {
                        self.saturations = self.saturations.saturating_add(1);
                    }
                    return Err(e);
                }
            }
        }
        self.members = next;
        if let Some((sel, _)) = best {
            self.selected = sel.member;
            self.last = Some(sel);
            outcome = BankOutcome::Filtered(sel);
        }
        Ok(outcome)
    }

    /// No measurement: every member coasts (all or none).
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        let mut next = self.members;
        for m in next.iter_mut().take(self.len) {
            if let Err(e) = m.coast(dt) {
                if e == FilterError::Saturated {
                    self.saturations = self.saturations.saturating_add(1);
                }
                return Err(e);
            }
        }
        self.members = next;
        Ok(())
    }
}

/// One [`ParallelBank`] per axis, updated all or none, each selecting its
/// own member.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CartesianBank<N: Numeric, const K: usize, const D: usize> {
    axes: [ParallelBank<N, K>; D],
}

impl<N: Numeric, const K: usize, const D: usize> CartesianBank<N, K, D> {
    /// Every axis with the same members.
    pub fn new(bank: ParallelBank<N, K>) -> Self {
        CartesianBank { axes: [bank; D] }
    }

    /// The bank a [`BankConfig`] describes, on every axis.
    pub fn from_config(c: &BankConfig) -> Result<Self, ConfigError> {
        Ok(Self::new(ParallelBank::from_config(c)?))
    }

    /// The per-axis banks.
    pub fn axes(&self) -> &[ParallelBank<N, K>; D] {
        &self.axes
    }

    /// The phase of the axes (all updated together, so all the same).
    pub fn phase(&self) -> Phase {
        self.axes.first().map_or(Phase::Empty, |a| a.phase())
    }

    /// Each axis's selected member's smoothed position.
    pub fn position(&self) -> [N::Length; D] {
        self.axes.map(|a| a.position())
    }

    /// Each axis's selected member's smoothed velocity.
    pub fn velocity(&self) -> [N::Speed; D] {
        self.axes.map(|a| a.velocity())
    }

    /// [`ParallelBank::update`] on every axis, all or none.
    pub fn update(
        &mut self,
        z: [N::Length; D],
        dt: N::Interval,
    ) -> Result<[BankOutcome<N>; D], FilterError> {
        // As the axes one after the other: the first axis's measurement,
        // then the interval, then the others' measurements.
        let invalid = |v: &N::Length| !v.is_valid();
        if z.first().is_some_and(invalid) {
            return Err(FilterError::InvalidMeasurement);
        }
        let span = match self.axes.first() {
            Some(axis) => axis.interval_span(dt)?,
            None => IntervalSpan::InRange,
        };
        let mut next = self.axes;
        match span {
            IntervalSpan::TooShort if z.iter().any(invalid) => {
                return Err(FilterError::InvalidMeasurement)
            }
            IntervalSpan::TooShort => return Ok([BankOutcome::Skipped; D]),
            IntervalSpan::TooLong => next.iter_mut().for_each(ParallelBank::restart),
            IntervalSpan::InRange => {}
        }
        let mut out = [BankOutcome::FirstPoint; D];
        // The first axis's measurement is checked before the interval, as
        // an axis's own update does; the members' step gains are formed
        // once for every axis (the axes share the members' gains).
        let first_invalid = z.first().is_some_and(|v| !v.is_valid());
        let steps = match next.first_mut() {
            Some(_) if first_invalid => Err(FilterError::InvalidMeasurement),
            Some(first) => first.step_gains(dt),
            None => return Ok(out),
        };
        for ((axis, o), z) in next.iter_mut().zip(out.iter_mut()).zip(z) {
            let result = match &steps {
                Ok(steps) if z.is_valid() => axis.update_step(z, steps),
                Ok(_) => Err(FilterError::InvalidMeasurement),
                Err(e) => Err(*e),
            };
            match result {
                Ok(r) => {
                    axis.record_intervals(&r, dt);
                    *o = r;
                }
                Err(e) => {
                    // Keep the saturation counts of the refused update.
                    for (mine, tried) in self.axes.iter_mut().zip(&next) {
                        mine.saturations = tried.saturations;
                    }
                    return Err(e);
                }
            }
        }
        self.axes = next;
        if span == IntervalSpan::TooLong {
            out = [BankOutcome::Restarted; D];
        }
        Ok(out)
    }

    /// [`ParallelBank::coast`] on every axis, all or none.
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        let mut next = self.axes;
        for axis in next.iter_mut() {
            if let Err(e) = axis.coast(dt) {
                for (mine, tried) in self.axes.iter_mut().zip(&next) {
                    mine.saturations = tried.saturations;
                }
                return Err(e);
            }
        }
        self.axes = next;
        Ok(())
    }
}
