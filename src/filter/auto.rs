//! `auto` fused with its filter: the per-axis constant-velocity Kalman
//! filter of [`crate::gain::auto`] for a sensor with the same σ on every
//! axis, in one call per measurement and one covariance for all axes
//! (design and figures in `docs/auto.md`).
//!
//! With the same measurement variance on every axis, the axes' normalised
//! covariances p̃ = P/σ² follow the same recursion from the same two-point
//! start, so one 2×2 p̃ (three numbers), one manoeuvre level and one gain
//! pair serve them all; the manoeuvre level is matched on the mean of the
//! axes' ν²/S (Bar-Shalom, Li & Kirubarajan 2001 §5.4, §11.2.2). The update
//! is `covariance_step_or_restart` (one division, no libm) and then per axis
//! x = x_p + α·e, v = v + (β/T)·e (Al-Wagih & Abdulla eqs. 3–8). A sensor
//! whose σ differs per axis (range–bearing) is the schedule
//! [`crate::gain::AutoGains`] (one covariance per axis) with
//! [`crate::gain::ScheduledFilter`].

use crate::filter::{invalid_measurement, refusal, FilterError, IntervalSpan, Phase};
use crate::gain::auto::{
    capped_nis, covariance_step_or_restart, match_manoeuvre, mean_over_axes, predicted_part,
    two_point, AutoAxis, AutoPrediction, CovarianceTerms, SharedNoise,
};
use crate::num::{AddProduct, Numeric, Quantity, Real};

/// What [`AutoFilter::update`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AutoUpdate {
    /// First measurement: the position is the estimate.
    FirstPoint,
    /// Second: velocity from the difference (Al-Wagih eq. 9), the
    /// two-point covariance.
    SecondPoint,
    /// A Kalman update.
    Filtered,
    /// The interval was longer than [`crate::filter::MAX_INTERVAL_S`]: the
    /// estimate was dropped and this measurement is its first point.
    Restarted,
    /// Less than [`crate::filter::MIN_INTERVAL_S`] after the previous
    /// measurement: nothing changed.
    Skipped,
}

/// One update interval's terms for [`AutoFilter::update_step`]: the
/// interval T and `auto`'s terms of it alone (T³, 1.5T², 3T and the NIS
/// average's weight, [`crate::gain::auto`]), formed once for every filter
/// updated after that interval (a scan's tracks, a regular report rate), as
/// [`crate::filter::StepGains`] is for the fixed-gain filters. A filter that
/// coasted since its last update forms its own from the whole time since.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoInterval<N: Numeric> {
    interval: N::Interval,
    terms: CovarianceTerms<N::Ratio>,
}

impl<N: Numeric> AutoInterval<N> {
    /// The terms of `dt`; refuses an interval that is not a valid number
    /// or is ≤ 0 ([`FilterError::InvalidInterval`]). An interval outside
    /// the filters' range is accepted: the update applies the interval
    /// policy ([`AutoUpdate::Skipped`], [`AutoUpdate::Restarted`]).
    pub fn new(dt: N::Interval) -> Result<Self, FilterError> {
        crate::filter::check_interval(dt)?;
        Ok(AutoInterval {
            interval: dt,
            terms: CovarianceTerms::new(N::Ratio::ZERO, N::Ratio::from(dt)),
        })
    }

    /// T.
    pub fn interval(&self) -> N::Interval {
        self.interval
    }
}

/// A D-axis constant-velocity Kalman filter with one σ on every axis and
/// the manoeuvre level estimated online (module docs): the state per axis,
/// one normalised covariance, the time coasted and the phase. The
/// configuration ([`SharedNoise`]) is passed to every call, so it costs no
/// bytes per filter.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AutoFilter<N: Numeric, const D: usize> {
    position: [N::Length; D],
    velocity: [N::Speed; D],
    /// P/σ² after the last update, and the manoeuvre level.
    covariance: AutoAxis<N>,
    /// Time since the last update (coasts; while one point is known, the
    /// time since it), s. A coast that would take it out of the interval's
    /// format is not added.
    coasted: N::Interval,
    phase: Phase,
}

impl<N: Numeric, const D: usize> Default for AutoFilter<N, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Numeric, const D: usize> AutoFilter<N, D> {
    /// A filter that has seen no measurement.
    pub const fn new() -> Self {
        let one = N::Ratio::ONE;
        AutoFilter {
            position: [N::Length::ZERO; D],
            velocity: [N::Speed::ZERO; D],
            covariance: AutoAxis {
                position: one,
                cross: N::Ratio::ZERO,
                velocity: one,
                manoeuvre: one,
                nis: one,
            },
            coasted: N::Interval::ZERO,
            phase: Phase::Empty,
        }
    }

    /// Which stage of two-point initialisation the filter is in.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// Smoothed position per axis.
    pub fn position(&self) -> [N::Length; D] {
        self.position
    }

    /// Smoothed velocity per axis (zero before the second measurement).
    pub fn velocity(&self) -> [N::Speed; D] {
        self.velocity
    }

    /// The normalised covariance (P/σ²) and manoeuvre level after the last
    /// update.
    pub fn covariance(&self) -> &AutoAxis<N> {
        &self.covariance
    }

    /// The position predicted `dt` ahead per axis, without changing the
    /// filter.
    pub fn predict(&self, dt: N::Interval) -> Result<[N::Length; D], FilterError> {
        crate::filter::check_interval(dt)?;
        self.predict_over(dt)
    }

    /// [`Self::predict`] after `step`'s interval (checked when the step was
    /// formed: a track table's scan predicts every track after one).
    #[inline]
    pub fn predict_step(&self, step: &AutoInterval<N>) -> Result<[N::Length; D], FilterError> {
        self.predict_over(step.interval)
    }

    /// [`Self::predict`] after a valid `dt`.
    fn predict_over(&self, dt: N::Interval) -> Result<[N::Length; D], FilterError> {
        let mut guard = N::Guard::default();
        let mut out = self.position;
        for (x, v) in out.iter_mut().zip(&self.velocity) {
            *x = x.add_product(*v, dt, &mut guard);
            x.check_output(&mut guard);
        }
        if N::passed(&guard) {
            Ok(out)
        } else {
            Err(FilterError::Saturated)
        }
    }

    /// p̃⁻_xx for an update `dt` from now (the predicted position variance
    /// over σ²; the innovation variance over σ² is this plus 1); `None`
    /// before two measurements.
    pub fn predicted_variance_ratio(&self, dt: N::Interval) -> Option<N::Ratio> {
        self.prediction_over(dt, None)
            .map(|p| p.predicted_variance_ratio())
    }

    /// [`Self::predicted_variance_ratio`] for an update after `step`.
    #[inline]
    pub fn predicted_variance_ratio_step(&self, step: &AutoInterval<N>) -> Option<N::Ratio> {
        self.prediction_step(step)
            .map(|p| p.predicted_variance_ratio())
    }

    /// The predicted covariance's part for an update after `step`
    /// ([`AutoPrediction`]); `None` before two measurements or when p̃⁻_xx
    /// is not a valid number.
    #[inline]
    pub(crate) fn prediction_step(&self, step: &AutoInterval<N>) -> Option<AutoPrediction<N>> {
        self.prediction_over(step.interval, Some(&step.terms))
    }

    /// [`Self::prediction_step`] after `dt`, with the terms of `dt` alone
    /// formed once for many filters when given ([`Self::covariance_terms`]).
    #[inline]
    fn prediction_over(
        &self,
        dt: N::Interval,
        uncoasted: Option<&CovarianceTerms<N::Ratio>>,
    ) -> Option<AutoPrediction<N>> {
        if self.phase != Phase::Tracking {
            return None;
        }
        let part = predicted_part(&self.covariance, &self.covariance_terms(dt, uncoasted));
        part.predicted_variance_ratio().is_valid().then_some(part)
    }

    /// The covariance terms of an update `dt` from now: `uncoasted` (the
    /// terms of `dt` alone, `CovarianceTerms::new(0, dt)`, which a track
    /// table forms once per scan) when nothing was coasted, else formed
    /// here.
    #[inline(always)]
    fn covariance_terms(
        &self,
        dt: N::Interval,
        uncoasted: Option<&CovarianceTerms<N::Ratio>>,
    ) -> CovarianceTerms<N::Ratio> {
        match uncoasted {
            Some(terms) if self.coasted == N::Interval::ZERO => *terms,
            _ => CovarianceTerms::new(N::Ratio::from(self.coasted), N::Ratio::from(dt)),
        }
    }

    /// Incorporates measurement `z`, taken `dt` after the previous call
    /// that the filter took, under the interval policy of
    /// [`crate::filter`] (skipped when too short, changing nothing;
    /// restarted when too long, or, while one point is known, when the time
    /// since it is). An `Err` changes nothing.
    pub fn update(
        &mut self,
        noise: &SharedNoise<N>,
        z: [N::Length; D],
        dt: N::Interval,
    ) -> Result<AutoUpdate, FilterError> {
        self.update_over(noise, z, dt, None, None)
    }

    /// [`Self::update`] after `step`'s interval, its terms formed once for
    /// many updates ([`AutoInterval`]); the same results.
    pub fn update_step(
        &mut self,
        noise: &SharedNoise<N>,
        z: [N::Length; D],
        step: &AutoInterval<N>,
    ) -> Result<AutoUpdate, FilterError> {
        self.update_over(noise, z, step.interval, Some(&step.terms), None)
    }

    /// [`Self::update_step`] after `prediction`, which
    /// [`Self::prediction_step`] gave for this step with the filter as it
    /// is now (the track table's gate): the same results, the prediction not
    /// formed again.
    pub(crate) fn update_predicted(
        &mut self,
        noise: &SharedNoise<N>,
        z: [N::Length; D],
        step: &AutoInterval<N>,
        prediction: &AutoPrediction<N>,
    ) -> Result<AutoUpdate, FilterError> {
        self.update_over(noise, z, step.interval, Some(&step.terms), Some(prediction))
    }

    /// [`Self::update`], with the terms of `dt` alone formed once for many
    /// filters ([`Self::covariance_terms`]) and the prediction formed by a gate
    /// ([`Self::update_predicted`]).
    fn update_over(
        &mut self,
        noise: &SharedNoise<N>,
        z: [N::Length; D],
        dt: N::Interval,
        uncoasted: Option<&CovarianceTerms<N::Ratio>>,
        predicted: Option<&AutoPrediction<N>>,
    ) -> Result<AutoUpdate, FilterError> {
        let mut guard = N::Guard::default();
        for v in &z {
            v.check_input(&mut guard);
        }
        if !N::passed(&guard) {
            return Err(FilterError::InvalidMeasurement);
        }
        // A float's NaN or ∞ passes `check_input`: it reaches the outputs
        // of an update, whose refusal then names it (`refusal`); the paths
        // that store or skip `z` without arithmetic test it here.
        if self.phase == Phase::Empty {
            crate::filter::check_interval(dt)?;
            if invalid_measurement(&z) {
                return Err(FilterError::InvalidMeasurement);
            }
            self.start(z);
            return Ok(AutoUpdate::FirstPoint);
        }
        match IntervalSpan::of(dt)? {
            IntervalSpan::InRange => {}
            _ if invalid_measurement(&z) => return Err(FilterError::InvalidMeasurement),
            IntervalSpan::TooShort => return Ok(AutoUpdate::Skipped),
            IntervalSpan::TooLong => {
                self.start(z);
                return Ok(AutoUpdate::Restarted);
            }
        }
        let tau = self.coasted + dt;
        if self.phase == Phase::OnePoint {
            // Al-Wagih eq. 9 over the time since the first point, within
            // the filters' range.
            if IntervalSpan::of_second_point(self.coasted, dt) == Ok(IntervalSpan::TooLong) {
                if invalid_measurement(&z) {
                    return Err(FilterError::InvalidMeasurement);
                }
                self.start(z);
                return Ok(AutoUpdate::Restarted);
            }
            let mut velocity = self.velocity;
            for ((v, z), x) in velocity.iter_mut().zip(&z).zip(&self.position) {
                let difference = z.sub_guarded(*x, &mut guard);
                difference.check_output(&mut guard);
                *v = difference / tau;
                v.check_output(&mut guard);
            }
            if !N::passed(&guard) {
                return Err(refusal(&z));
            }
            self.position = z;
            self.velocity = velocity;
            self.covariance = two_point::<N>(N::Ratio::from(tau), noise.start_manoeuvre());
            self.coasted = N::Interval::ZERO;
            self.phase = Phase::Tracking;
            return Ok(AutoUpdate::SecondPoint);
        }
        // The gains depend on the covariance alone: formed first, so that
        // each axis is predicted, corrected and its ν²/S taken in one pass.
        let terms = self.covariance_terms(dt, uncoasted);
        let bounds = noise.bounds();
        let part = match predicted {
            Some(part) => *part,
            None => predicted_part(&self.covariance, &terms),
        };
        let step = covariance_step_or_restart(&self.covariance, &terms, &part, None, bounds);
        let (alpha, rate) = (N::gain(step.gains.alpha), N::Rate::from(step.gains.rate));
        let mut position = self.position;
        let mut velocity = self.velocity;
        let mut nis = N::Ratio::ZERO;
        // One guard for the whole update, tested once: an `Err` writes
        // nothing.
        for ((x, v), z) in position.iter_mut().zip(velocity.iter_mut()).zip(&z) {
            let p = x.add_product(*v, dt, &mut guard);
            let e = z.sub_guarded(p, &mut guard);
            if N::FUSED_PRODUCTS {
                // Not sticky: a prediction or residual that is a sentinel
                // would not show in the outputs. The sticky formats' outputs
                // carry every intermediate.
                p.check_output(&mut guard);
                e.check_output(&mut guard);
            }
            let nu = N::Ratio::from(e) * noise.inverse_sigma;
            nis = nis + capped_nis(nu, step.inverse, noise.nis_cap);
            *x = p.add_product(alpha, e, &mut guard);
            *v = v.add_product(rate, e, &mut guard);
            x.check_output(&mut guard);
            v.check_output(&mut guard);
        }
        if !N::passed(&guard) {
            return Err(refusal(&z));
        }
        let mut covariance = step.next;
        if step.matched {
            match_manoeuvre(&mut covariance, mean_over_axes::<_, D>(nis), &terms, bounds);
        }
        self.position = position;
        self.velocity = velocity;
        self.covariance = covariance;
        self.coasted = N::Interval::ZERO;
        Ok(AutoUpdate::Filtered)
    }

    /// No measurement for `dt`: the state moves to its prediction and the
    /// covariance's interval grows (coasting is exact: the covariance over
    /// T₁ then T₂ is that over T₁ + T₂). An `Err` changes nothing.
    pub fn coast(&mut self, dt: N::Interval) -> Result<(), FilterError> {
        crate::filter::check_interval(dt)?;
        if self.phase == Phase::Tracking {
            self.position = self.predict(dt)?;
        }
        let coasted = self.coasted + dt;
        if coasted.is_valid() {
            self.coasted = coasted;
        }
        Ok(())
    }

    /// The position gain α an update `dt` from now would use (before two
    /// measurements, 1).
    pub fn next_alpha(&self, dt: N::Interval) -> N::Ratio {
        self.predicted_variance_ratio(dt)
            .map_or(N::Ratio::ONE, Self::alpha_for)
    }

    /// The position gain α = p̃⁻_xx/(p̃⁻_xx + 1) for predicted variance ratio
    /// `p` (1 if that is not a valid number).
    pub(crate) fn alpha_for(p: N::Ratio) -> N::Ratio {
        let one = N::Ratio::ONE;
        let alpha = p / (p + one);
        if alpha.is_valid() {
            alpha
        } else {
            one
        }
    }

    /// `z` as the first point of a new estimate.
    fn start(&mut self, z: [N::Length; D]) {
        *self = AutoFilter {
            position: z,
            ..Self::new()
        };
        self.phase = Phase::OnePoint;
    }
}
