//! The default Cartesian track: [`AutoFilter`] (`auto` fused with its
//! filter, one covariance for both axes) in a track table.

use super::gate::{Gate, GateRegion};
use super::model::{
    uncertainty_region, wave_radius, Observation, PredictedState, ScanInterval, TrackFilter,
};
use crate::filter::auto::{AutoFilter, AutoUpdate};
use crate::filter::FilterError;
use crate::gain::AutoGains;
use crate::num::{Numeric, Quantity, Real};

/// `Params` is the `auto` schedule as configured ([`AutoGains`]; its σ
/// and manoeuvre bounds, [`AutoGains::shared_noise`]). The gate is the
/// filter's own covariance: [`Gate::Uncertainty`] with no manoeuvre
/// allowance on top (the manoeuvre is in p̃⁻ already), [`Gate::Wave`] with
/// the α the update would use. A track with one point has no gate, as
/// the other Cartesian tracks.
impl<S: Numeric> TrackFilter<S> for AutoFilter<S, 2> {
    type Params = AutoGains<S, 2>;
    type Step = ScanInterval<S>;

    fn step(_: &Self::Params, interval: &ScanInterval<S>) -> Result<ScanInterval<S>, FilterError> {
        Ok(*interval)
    }

    fn interval_of(step: &ScanInterval<S>) -> &ScanInterval<S> {
        step
    }

    fn empty(_: &Self::Params) -> Self {
        AutoFilter::new()
    }

    fn update(
        &mut self,
        params: &Self::Params,
        z: &Observation<S>,
        step: &ScanInterval<S>,
    ) -> Result<(), FilterError> {
        let mut filter = *self;
        match filter.update(&params.shared_noise(), z.xy(), step.interval())? {
            // The table never offers a measurement that close (it skips the
            // whole scan): refused as an interval outside the filter's.
            AutoUpdate::Skipped => Err(FilterError::InvalidInterval),
            _ => {
                *self = filter;
                Ok(())
            }
        }
    }

    fn coast(&mut self, _: &Self::Params, step: &ScanInterval<S>) -> Result<(), FilterError> {
        AutoFilter::coast(self, step.interval())
    }

    fn predict(
        &self,
        _: &Self::Params,
        step: &ScanInterval<S>,
    ) -> Result<PredictedState<S>, FilterError> {
        Ok(PredictedState {
            position: AutoFilter::predict(self, step.interval())?,
            velocity: AutoFilter::velocity(self),
        })
    }

    fn position(&self) -> [S::Length; 2] {
        AutoFilter::position(self)
    }

    fn velocity(&self) -> [S::Speed; 2] {
        AutoFilter::velocity(self)
    }

    fn predicted_variance_ratio(
        &self,
        _: &Self::Params,
        step: &ScanInterval<S>,
    ) -> Option<S::Ratio> {
        AutoFilter::predicted_variance_ratio(self, step.interval())
    }

    /// α for a scan 1 s ahead (this signature has no interval); the table
    /// does not call it: [`Self::gate_region`] uses the scan's own.
    fn gate_alpha(&self, _: &Self::Params) -> S::Ratio {
        ScanInterval::<S>::from_ms(1000)
            .map_or(<S::Ratio as Real>::ONE, |s| self.next_alpha(s.interval()))
    }

    fn gate_region(
        &self,
        _: &Self::Params,
        predicted: &PredictedState<S>,
        step: &ScanInterval<S>,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        let p = AutoFilter::predicted_variance_ratio(self, step.interval())?;
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
                    step,
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
                self.next_alpha(step.interval()),
                predicted.position,
            ),
        };
        GateRegion::circle(predicted.position, radius)
    }
}
