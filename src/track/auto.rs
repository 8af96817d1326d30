//! The default Cartesian track: [`AutoFilter`] (`auto` fused with its
//! filter, one covariance for both axes) in a track table.

use super::gate::{Gate, GateRegion};
use super::model::{
    one_second, uncertainty_region, wave_radius, Observation, PredictedState, ScanInterval,
    TrackFilter,
};
use crate::filter::auto::{AutoFilter, AutoInterval, AutoUpdate};
use crate::filter::FilterError;
use crate::gain::auto::AutoPrediction;
use crate::gain::AutoGains;
use crate::num::{Numeric, Quantity, Real};

/// A scan's interval as the default track uses it: the interval and
/// `auto`'s terms of it ([`AutoInterval`]), formed once per scan and used
/// by every track that coasted nothing since its last update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoStep<S: Numeric> {
    interval: ScanInterval<S>,
    terms: AutoInterval<S>,
}

/// `Params` is the `auto` schedule as configured ([`AutoGains`]; its σ
/// and manoeuvre bounds, [`AutoGains::shared_noise`]). The gate is the
/// filter's own covariance: [`Gate::Uncertainty`] with no manoeuvre
/// allowance on top (the manoeuvre is in p̃⁻ already: the gate's
/// `max_acceleration` is not used), [`Gate::Wave`] with the α the update
/// would use. p̃⁻ is in units of the schedule's σ², so the gate's
/// `measurement_sigma` must be that σ
/// ([`TrackerDesign`](super::defaults::TrackerDesign) builds both from the
/// sensor's one figure). A track with one point has no gate, as
/// the other Cartesian tracks. The gate's part of the predicted covariance
/// is the update's too ([`AutoPrediction`]).
impl<S: Numeric> TrackFilter<S> for AutoFilter<S, 2> {
    type Params = AutoGains<S, 2>;
    type Step = AutoStep<S>;
    type GateKept = AutoPrediction<S>;
    const NOTHING_KEPT: AutoPrediction<S> = AutoPrediction::NONE;

    fn step(_: &Self::Params, interval: &ScanInterval<S>) -> Result<AutoStep<S>, FilterError> {
        Ok(AutoStep {
            interval: *interval,
            terms: AutoInterval::new(interval.interval())?,
        })
    }

    fn interval_of(step: &AutoStep<S>) -> &ScanInterval<S> {
        &step.interval
    }

    fn empty(_: &Self::Params) -> Self {
        AutoFilter::new()
    }

    fn update(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        step: &AutoStep<S>,
    ) -> Result<(), FilterError> {
        // In place: an `Err` and a skip change nothing.
        skip_refused(self.update_step(params.shared_noise(), z.xy(), &step.terms))
    }

    fn update_after_gate(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        step: &AutoStep<S>,
        prediction: &AutoPrediction<S>,
    ) -> Result<(), FilterError> {
        skip_refused(self.update_predicted(params.shared_noise(), z.xy(), &step.terms, prediction))
    }

    fn coast(&mut self, _: &Self::Params, step: &AutoStep<S>) -> Result<(), FilterError> {
        AutoFilter::coast(self, step.interval.interval())
    }

    #[inline(always)]
    fn predict(
        &self,
        _: &Self::Params,
        step: &AutoStep<S>,
    ) -> Result<PredictedState<S>, FilterError> {
        Ok(PredictedState {
            position: self.predict_step(&step.terms)?,
            velocity: AutoFilter::velocity(self),
        })
    }

    fn position(&self) -> [S::Length; 2] {
        AutoFilter::position(self)
    }

    fn velocity(&self) -> [S::Speed; 2] {
        AutoFilter::velocity(self)
    }

    fn predicted_variance_ratio(&self, _: &Self::Params, step: &AutoStep<S>) -> Option<S::Ratio> {
        self.predicted_variance_ratio_step(&step.terms)
    }

    /// α for a scan 1 s ahead (this signature has no interval); the table
    /// does not call it: [`Self::gate_region`] uses the scan's own.
    fn gate_alpha(&self, _: &Self::Params) -> S::Ratio {
        one_second::<S>().map_or(<S::Ratio as Real>::ONE, |s| self.next_alpha(s.interval()))
    }

    #[inline(always)]
    fn gate_region(
        &self,
        params: &Self::Params,
        predicted: &PredictedState<S>,
        step: &AutoStep<S>,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        let mut kept = AutoPrediction::NONE;
        self.gate_region_keeping(params, predicted, step, gate, &mut kept)
    }

    #[inline(always)]
    fn gate_region_keeping(
        &self,
        _: &Self::Params,
        predicted: &PredictedState<S>,
        step: &AutoStep<S>,
        gate: &Gate<S>,
        kept: &mut AutoPrediction<S>,
    ) -> Option<GateRegion<S>> {
        let prediction = self.prediction_step(&step.terms)?;
        *kept = prediction;
        let p = prediction.predicted_variance_ratio();
        let radius = match *gate {
            Gate::Uncertainty {
                measurement_sigma,
                threshold,
                ..
            } => {
                return uncertainty_region(
                    predicted.position,
                    measurement_sigma,
                    threshold,
                    <S as Numeric>::Acceleration::ZERO,
                    p,
                    &step.interval,
                )
            }
            Gate::Wave {
                range_sigma,
                bearing_sigma,
                multiple,
            } => wave_radius::<S>(
                range_sigma,
                bearing_sigma,
                multiple,
                AutoFilter::<S, 2>::alpha_for(p),
                predicted.position,
            ),
        };
        GateRegion::circle(predicted.position, radius)
    }
}

/// An update's outcome as the table takes it: the table never offers a
/// measurement closer than the filters' shortest interval (it skips the
/// whole scan), so a skip is refused as an interval outside the filter's.
#[inline(always)]
fn skip_refused(update: Result<AutoUpdate, FilterError>) -> Result<(), FilterError> {
    match update? {
        AutoUpdate::Skipped => Err(FilterError::InvalidInterval),
        _ => Ok(()),
    }
}
