//! The library's other filters as [`TrackFilter`]s, so a
//! [`TrackTable`](super::TrackTable) can hold any of them, in any number
//! type:
//!
//! * [`ScheduledTrack`]: a 2-D αβ filter driven by any gain schedule
//!   ([`ScheduledFilter`] with a [`GainSchedule`]: M1–M4, Li, Liu, TCAS
//!   firmness, or [`AnySchedule`](crate::gain::AnySchedule) to choose at run
//!   time), plus the error covariance of each axis, propagated with the gains
//!   the schedule actually used.
//! * [`RangeAzimuthTrack`]: He, Peng, Ling & Quan's range–azimuth filter,
//!   gated by a window in range and azimuth sized from the filter's own
//!   along-range and cross-range covariances.
//!
//! Both are `Copy`, allocate nothing and never panic; everything they share
//! (the schedule as configured, the noise figures) is the table's
//! [`TrackFilter::Params`], stored once in the
//! [`TrackerConfig`](super::TrackerConfig).
//!
//! # Gates
//!
//! | adapter | [`Gate::Uncertainty`] | [`Gate::Wave`] |
//! |---|---|---|
//! | [`ScheduledTrack`] | circle, r = σ·√(G·(p + 1)) + ½·a_max·T², p the larger axis's predicted variance ratio | circle, r = κ·√α·√(Δρ² + ρ²Δθ²), α the larger per-axis gain the schedule would use next (Li et al. eqs. 11–12) |
//! | [`RangeAzimuthTrack`] | range/azimuth window, half-widths √G·√(P⁻₁₁ + σ²) + ½·a_max·T² in range (σ = σ_R) and across range (σ = R·σ_B) | range/azimuth window, half-widths κ·√α·Δρ in range and κ·√W1·ρΔθ across (eqs. 9–10 gains, λ = √gain per direction) |
//!
//! # Bytes per track
//!
//! In `docs/track-table.md` (asserted by
//! `host-tests/tests/it/track/static_construction.rs`). A schedule's constants sit in every
//! track's copy of it (a [`ScheduledFilter`] owns its schedule by value), and
//! `AnySchedule` is as large as its largest variant, so a table that only
//! ever runs one schedule should name that schedule's type. A
//! [`RangeAzimuthTrack`] keeps the filter's [`RangeAzimuthState`] only: its
//! noise figures are the table's configuration, not a copy in every track.

use super::gate::{hypot, Gate, GateRegion};
use super::model::{
    one_second, uncertainty_region, wave_radius, Measurement, Observation, PredictedState,
    ScanInterval, TrackFilter, Uncertainty, UpdateTerms,
};
use crate::filter::range_azimuth::{
    azimuth_of, CovarianceFactor, RangeAzimuthNoise, RangeAzimuthState,
};
use crate::filter::{FilterError, Gains, Phase, Prediction, UpdateKind, UpdateOutcome};
use crate::gain::{GainContext, GainSchedule, ScheduledError, ScheduledFilter};
use crate::num::{Numeric, Quantity, Real, Scalar};

/// What an update did, without its innovation; `None` for a skipped one
/// (the table never offers a track a measurement that close: it skips the
/// whole scan).
fn kind_of<N: Numeric>(outcome: &UpdateOutcome<N>) -> Option<UpdateKind> {
    match outcome {
        UpdateOutcome::FirstPoint | UpdateOutcome::Restarted => Some(UpdateKind::FirstPoint),
        UpdateOutcome::SecondPoint => Some(UpdateKind::SecondPoint),
        UpdateOutcome::Filtered(_) => Some(UpdateKind::Filtered),
        UpdateOutcome::Skipped => None,
    }
}

/// A scheduled update the table refused: the filter's own error, or, for a
/// schedule that produced no gains (a rounding failure its docs say does not
/// occur), [`FilterError::Saturated`] (the arithmetic left the stability
/// region).
fn filter_error(e: ScheduledError) -> FilterError {
    match e {
        ScheduledError::Filter(e) => e,
        ScheduledError::Schedule(_) => FilterError::Saturated,
    }
}

/// A 2-D αβ filter driven by gain schedule `G` ([`ScheduledFilter`]), with
/// the error covariance of each axis that sizes its gate.
///
/// `Params = G`: the schedule as configured. Every new track starts from a
/// copy of it ([`ScheduledFilter::new`]), so per-track schedule state
/// (counts, innovation windows) starts fresh.
///
/// # Covariance
///
/// Each axis keeps the [`ErrorVariance`](super::ErrorVariance) of its
/// (position, velocity) error in units of σ²: two-point initialisation
/// (Al-Wagih & Abdulla eqs. 9–10), then prediction over each interval and the
/// Joseph-form update with the gains *the schedule actually used* on that
/// axis. This is exact for white measurement noise and no process noise for
/// any gain sequence (M2's decreasing gains, Li's count cuts, Liu's
/// switches), and per axis because M3, M4 and Liu's residual accumulation
/// give each axis its own gains. The gate uses the larger of the two axes.
/// A manoeuvre is covered by the gate's ½·a_max·T² allowance, not by the
/// covariance.
///
/// # Gains the next update would use
///
/// [`Self::next_gains`] asks the schedule for the gains of a measurement
/// exactly at the prediction (zero innovation): the gains for Li's wave
/// gate. For schedules that ignore the current innovation (M1–M4, Li, TCAS)
/// those are the gains the update will use whatever the measurement; for
/// Liu's schedules that react to it (§2.1.2, 2.1.4, 2.1.5) they are the
/// non-manoeuvring gains, the smallest gate.
///
/// # Restarts
///
/// A schedule that requires a restart (TCAS firmness 0 after misses) gets no
/// gate: the track is not offered measurements it would restart on, and
/// coasts until the table deletes it for its misses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScheduledTrack<S: Numeric, G> {
    filter: ScheduledFilter<S, G, 2, 2>,
    uncertainty: [Uncertainty<S::Variance>; 2],
}

impl<S: Numeric, G: GainSchedule<S, 2>> ScheduledTrack<S, G> {
    /// The filter with its schedule.
    pub fn filter(&self) -> &ScheduledFilter<S, G, 2, 2> {
        &self.filter
    }

    /// The covariance bookkeeping of the x and y axes.
    pub fn uncertainty(&self) -> &[Uncertainty<S::Variance>; 2] {
        &self.uncertainty
    }

    fn restart_pending(&self) -> bool {
        let phase = self.filter.filter().phase();
        self.filter.schedule().restart_required(phase)
    }

    /// The per-axis gains the schedule would give a measurement exactly at
    /// `predicted`, `dt` after the last update or coast; `None` before
    /// filtering starts (two-point initialisation uses no gains), when a
    /// restart is pending or the schedule gives none.
    pub fn next_gains(
        &self,
        predicted: &PredictedState<S>,
        dt: S::Interval,
    ) -> Option<[Gains<S>; 2]> {
        if self.filter.filter().phase() != Phase::Tracking || self.restart_pending() {
            return None;
        }
        let [x, y] = predicted.position;
        let [vx, vy] = predicted.velocity;
        let prediction = |position, velocity| Prediction {
            position,
            velocity,
            acceleration: S::Acceleration::ZERO,
        };
        let predictions = [prediction(x, vx), prediction(y, vy)];
        let n = self.filter.measurements().saturating_add(1);
        let ctx = GainContext::new(n, dt, predicted.position, &predictions).ok()?;
        self.filter.schedule().gains(&ctx).ok()
    }

    /// The larger of the two axes' predicted position variance ratios from
    /// the covariance the gains imply for a constant-velocity target.
    fn uncertainty_variance_ratio(&self, step: &ScanInterval<S>) -> Option<S::Ratio> {
        let [ux, uy] = &self.uncertainty;
        let px = ux.predicted_variance_ratio(step.seconds())?;
        let py = uy.predicted_variance_ratio(step.seconds())?;
        Some(S::from_variance(px).max_of(S::from_variance(py)))
    }

    fn next_alpha(&self, predicted: &PredictedState<S>, dt: S::Interval) -> Option<S::Ratio> {
        let [gx, gy] = self.next_gains(predicted, dt)?;
        Some(gx.alpha().max_of(gy.alpha()))
    }
}

impl<S: Numeric, G: GainSchedule<S, 2>> TrackFilter<S> for ScheduledTrack<S, G> {
    type Params = G;
    type Step = ScanInterval<S>;
    type GateKept = ();
    const NOTHING_KEPT: () = ();

    fn step(_: &G, interval: &ScanInterval<S>) -> Result<ScanInterval<S>, FilterError> {
        Ok(*interval)
    }

    fn interval_of(step: &ScanInterval<S>) -> &ScanInterval<S> {
        step
    }

    fn empty(schedule: &G) -> Self {
        ScheduledTrack {
            filter: ScheduledFilter::new(*schedule),
            uncertainty: [Uncertainty::Empty; 2],
        }
    }

    fn update(
        &mut self,
        _: &G,
        z: &Observation<S>,
        step: &ScanInterval<S>,
    ) -> Result<(), FilterError> {
        let mut filter = self.filter;
        let update = match filter.update(z.xy(), step.interval()) {
            Ok(update) => update,
            Err(e) => {
                // A refused update changes the ScheduledFilter only by its
                // saturation count, which is kept.
                self.filter = filter;
                return Err(filter_error(e));
            }
        };
        if update.outcome.contains(&UpdateOutcome::Skipped) {
            // Nothing changed: refused as an interval outside the filter's.
            return Err(FilterError::InvalidInterval);
        }
        let mut uncertainty = self.uncertainty;
        for (i, (u, outcome)) in uncertainty
            .iter_mut()
            .zip(update.outcome.iter())
            .enumerate()
        {
            // Initialisation updates use no gains (and their bookkeeping
            // ignores them).
            let one = S::Ratio::ONE;
            let (alpha, beta) = update
                .gains
                .as_ref()
                .and_then(|g| g.get(i))
                .map_or((one, one), |g| (g.alpha(), g.beta()));
            let seconds = step.seconds();
            let velocity_gain = S::to_variance(beta) / seconds;
            *u = u
                .after_update(
                    kind_of(outcome).ok_or(FilterError::InvalidInterval)?,
                    &UpdateTerms::new(S::to_variance(alpha), velocity_gain),
                    seconds,
                )
                .ok_or(FilterError::Saturated)?;
        }
        self.filter = filter;
        self.uncertainty = uncertainty;
        Ok(())
    }

    fn coast(&mut self, _: &G, step: &ScanInterval<S>) -> Result<(), FilterError> {
        let mut filter = self.filter;
        filter.coast(step.interval())?;
        let [ux, uy] = self.uncertainty;
        let uncertainty = [
            ux.after_coast(step.seconds())
                .ok_or(FilterError::Saturated)?,
            uy.after_coast(step.seconds())
                .ok_or(FilterError::Saturated)?,
        ];
        self.filter = filter;
        self.uncertainty = uncertainty;
        Ok(())
    }

    fn predict(&self, _: &G, step: &ScanInterval<S>) -> Result<PredictedState<S>, FilterError> {
        let [px, py] = self.filter.filter().predict(step.interval())?;
        Ok(PredictedState {
            position: [px.position, py.position],
            velocity: [px.velocity, py.velocity],
        })
    }

    fn position(&self) -> [S::Length; 2] {
        self.filter.filter().position()
    }

    fn velocity(&self) -> [S::Speed; 2] {
        self.filter.filter().velocity()
    }

    /// The larger of the two axes' predicted position variance ratios: the
    /// schedule's own covariance when it carries one (`auto`), else the
    /// covariance the gains imply for a constant-velocity target.
    fn predicted_variance_ratio(&self, _: &G, step: &ScanInterval<S>) -> Option<S::Ratio> {
        if let Some([px, py]) = self
            .filter
            .schedule()
            .predicted_variance_ratios(step.interval())
        {
            return Some(px.max_of(py));
        }
        self.uncertainty_variance_ratio(step)
    }

    /// The larger per-axis α of [`Self::next_gains`] for a scan 1 s ahead
    /// (this signature has no interval); 1 (the widest wave gate) when the
    /// schedule gives none. The table does not call it: [`Self::gate_region`]
    /// uses the gains at the scan's own interval.
    fn gate_alpha(&self, schedule: &G) -> S::Ratio {
        one_second::<S>()
            .and_then(|second| {
                let p = self.predict(schedule, &second).ok()?;
                self.next_alpha(&p, second.interval())
            })
            .unwrap_or(S::Ratio::ONE)
    }

    fn gate_region(
        &self,
        _: &G,
        predicted: &PredictedState<S>,
        step: &ScanInterval<S>,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        if self.restart_pending() {
            return None;
        }
        let radius = match *gate {
            Gate::Uncertainty {
                measurement_sigma,
                threshold,
                max_acceleration,
            } => {
                // A schedule that carries its covariance has the manoeuvre
                // in p already: no allowance on top. (Asked once: it is the
                // largest part of the gate's cost for `auto`.)
                let carried = self
                    .filter
                    .schedule()
                    .predicted_variance_ratios(step.interval());
                let (p, allowance) = match carried {
                    Some([px, py]) => (px.max_of(py), S::Acceleration::ZERO),
                    None => (self.uncertainty_variance_ratio(step)?, max_acceleration),
                };
                return uncertainty_region(
                    predicted.position,
                    measurement_sigma,
                    threshold,
                    allowance,
                    p,
                    step,
                );
            }
            Gate::Wave {
                range_sigma,
                bearing_sigma,
                multiple,
            } => {
                let alpha = self.next_alpha(predicted, step.interval())?;
                wave_radius::<S>(
                    range_sigma,
                    bearing_sigma,
                    multiple,
                    alpha,
                    predicted.position,
                )
            }
        };
        GateRegion::circle(predicted.position, radius)
    }
}

/// √P⁻₁₁ of a direction's covariance predicted `dt` ahead: the length of the
/// first row of [Φ·L | Γ·√Q] = (a + T·b, T·c, T²·√Q/2) (He et al. eq. 8 in
/// the factor form of [`RangeAzimuthFilter`]), without squaring.
fn predicted_position_sigma<S: Scalar>(f: &CovarianceFactor<S>, dt: S, process_sigma: S) -> S {
    let half = S::from_f64_lossy(0.5);
    hypot(
        hypot(f.a + dt * f.b, dt * f.c),
        dt * dt * process_sigma * half,
    )
}

/// The position gain P⁻₁₁/(P⁻₁₁ + σ²) for predicted position standard
/// deviation `a` and measurement standard deviation `sigma` (He et al.
/// eq. 9 for α, eq. 10 for W1), with the ratio of the two kept ≤ 1 so that
/// nothing large is squared.
fn position_gain<S: Scalar>(a: S, sigma: S) -> S {
    if a <= sigma {
        let u = a / sigma;
        let u2 = u * u;
        u2 / (S::ONE + u2)
    } else {
        let w = sigma / a;
        S::ONE / (S::ONE + w * w)
    }
}

/// He, Peng, Ling & Quan's range–azimuth filter
/// ([`crate::filter::range_azimuth::RangeAzimuthFilter`]) in a track table:
/// the track holds its [`RangeAzimuthState`], `Params` is its
/// [`RangeAzimuthNoise`]. Named with a number
/// system `N`, it runs the filter and its table in `N::Wide` ([`Numeric::Wide`]).
///
/// Measurements: a polar measurement is used as (R, B); a Cartesian one is
/// converted to R = √(x² + y²), B = atan2(x, y). A range of 0 is refused by
/// the filter (the table codes it `Rejected(FilterRefused)` and the track
/// coasts).
///
/// # Gate: a window in range and azimuth
///
/// The filter's uncertainty differs along range (σ_R, tens of metres) and
/// across it (R·σ_B, hundreds of metres to kilometres at TCAS ranges with a
/// 5° bearing error): a circle large enough across range would be tens of
/// times too large along it, and would let neighbouring intruders at
/// different ranges into each other's gates. The gate is therefore
/// [`GateRegion::polar`]: ((R − R_p)/h_R)² + (R_p·ΔB/h_C)² ≤ 1 around the
/// predicted position (range R_p), with half-widths sized from the filter's
/// own predicted covariances P_R⁻ (along range) and P_C⁻ (across) (eq. 8):
///
/// * [`Gate::Uncertainty`] (threshold G, allowance a_max; its
///   `measurement_sigma` is not used — the filter's own σ_R and R_p·σ_B
///   are): h_R = √G·√(k²·P_R⁻₁₁ + σ_R²) + ½·a_max·T²,
///   h_C = √G·√(P_C⁻₁₁ + R_p²σ_B²) + ½·a_max·T², k ≥ 1 the range-coupling
///   factor below. The range (cross-range) difference has variance
///   P⁻₁₁ + σ² for that direction, so the normalised squared distance of a
///   true measurement is χ² with 2 degrees of freedom (the directions are
///   uncorrelated in the filter's model), as for the Cartesian gate.
/// * [`Gate::Wave`] (Δρ, Δθ, κ): Li et al.'s λ = √α per direction, with the
///   gains the update would use, α along range (eq. 9) and W1 across
///   (eq. 10): h_R = κ·√α·Δρ, h_C = κ·√W1·R_p·Δθ. Li et al.'s single circle
///   of radius κ·λ·√(Δρ² + ρ²Δθ²) is the special case of equal gains,
///   stretched to the window its two error terms describe. Both Δρ and Δθ
///   must be > 0 for this filter (a zero gives no region: the track coasts).
///
/// A first version used an ellipse in x, y aligned with the line of sight
/// (no arctangent per pair); on the `tcas-30` scenario it rejected most true
/// measurements of new tracks, because the circle of constant range bends
/// away from the tangent by v²/(2R) at lateral offset v — 300 m at 3 km off
/// the line of sight at 14 km, against a range half-width of 140 m — and
/// new tracks' lateral offsets are kilometres (their velocity comes from two
/// bearings 5° apart). The window has no such approximation.
///
/// # Range coupling: why the range half-width is widened by k
///
/// The filter takes its range residual along the *measured* bearing
/// (eq. 11, reading 1 of [`crate::filter::range_azimuth`]):
/// RESID_R = R − p_p·u(B). With the prediction's error e_a along and e_c
/// across the true line of sight and bearing noise n_B, to second order
/// RESID_R = n_R − e_a − e_c·n_B + R·n_B²/2: besides the range noise n_R
/// (variance σ_R²) the channel receives e_c·n_B (variance P_C⁻₁₁·σ_B²) and
/// R·n_B²/2 (mean square ¾·R²·σ_B⁴, a bias of R·σ_B²/2 and its spread).
/// With a 5° bearing error these dominate: at 7 km with P_C⁻₁₁ = (500 m)²
/// the effective range noise is 60 m, not the 15 m the filter's gains and
/// P_R assume, so its range state is several times less accurate than P_R
/// says. On `tcas-30` (host-tests, `multi-target` group) a track's
/// range-rate error reached 30–37 m/s while P_R claimed 3 m/s, and with
/// h_R from P_R alone (80 m) established tracks lost their own
/// measurements after a couple of misses (OSPA 1106 m, completeness 0.68
/// over 10 runs, against 635 m and 0.89 with k). The gate therefore
/// scales P_R⁻₁₁ by k² = (σ_R² + P_C⁻₁₁σ_B² + ¾R_p²σ_B⁴)/σ_R², the ratio
/// of the effective to the assumed range noise variance. Scaling all of
/// P_R (not only its measurement-noise part) is the conservative side. The
/// filter is not changed here; its owner has the finding.
///
/// Like the filter, the gate neglects the rotation of the line of sight
/// between the covariance's axes and the new prediction (the azimuth moves
/// by cross-range speed·T/R per scan).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RangeAzimuthTrack<N: Numeric> {
    state: RangeAzimuthState<N::Wide>,
}

impl<N: Numeric<Wide = S>, S: Scalar> RangeAzimuthTrack<N> {
    /// The state of the range–azimuth filter this track runs (He, Peng,
    /// Ling & Quan, eqs. 7–13); its noise is the table's configuration.
    pub fn state(&self) -> &RangeAzimuthState<S> {
        &self.state
    }

    /// (√P_R⁻₁₁, √P_C⁻₁₁, σ_R, R_p·σ_B) for a prediction `dt` ahead at
    /// predicted range `range`: the predicted position standard deviations
    /// along and across range and the measurement's.
    fn predicted_sigmas(&self, noise: &RangeAzimuthNoise<S>, dt: S, range: S) -> Option<[S; 4]> {
        if self.state.phase() != Phase::Tracking {
            return None;
        }
        let q = noise.process_sigma();
        let along = predicted_position_sigma(&self.state.range_covariance(), dt, q);
        let across = predicted_position_sigma(&self.state.cross_range_covariance(), dt, q);
        let sigmas = [
            along,
            across,
            noise.range_sigma(),
            noise.cross_range_sigma(range),
        ];
        sigmas
            .iter()
            .all(|s| s.is_valid() && *s >= S::ZERO)
            .then_some(sigmas)
    }

    /// k = √(σ_R² + P_C⁻₁₁·σ_B² + ¾·R_p²·σ_B⁴)/σ_R: how much larger the
    /// noise in the filter's range channel is than the σ_R it assumes (see
    /// "Range coupling" on [`RangeAzimuthTrack`]). `across` is √P_C⁻₁₁.
    fn range_coupling_scale(noise: &RangeAzimuthNoise<S>, across: S, range: S) -> S {
        let sigma_b = noise.bearing_sigma();
        let sigma_r = noise.range_sigma();
        // √(3/4) = 0.866…
        let second_order = range * sigma_b * sigma_b * S::from_f64_lossy(0.866_025_403_784_438_6);
        hypot(sigma_r, hypot(across * sigma_b, second_order)) / sigma_r
    }

    fn polar(z: &Observation<S>) -> (S, S) {
        match z.measurement() {
            Measurement::Polar { range, azimuth } => (range, azimuth),
            Measurement::Cartesian { x, y } => (hypot(x, y), azimuth_of(x, y)),
        }
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> TrackFilter<S> for RangeAzimuthTrack<N> {
    type Params = RangeAzimuthNoise<S>;
    type Step = ScanInterval<S>;
    type GateKept = ();
    const NOTHING_KEPT: () = ();

    fn step(
        _: &RangeAzimuthNoise<S>,
        interval: &ScanInterval<S>,
    ) -> Result<ScanInterval<S>, FilterError> {
        Ok(*interval)
    }

    fn interval_of(step: &ScanInterval<S>) -> &ScanInterval<S> {
        step
    }

    fn empty(_: &RangeAzimuthNoise<S>) -> Self {
        RangeAzimuthTrack {
            state: RangeAzimuthState::EMPTY,
        }
    }

    fn update(
        &mut self,
        noise: &RangeAzimuthNoise<S>,
        z: &Observation<S>,
        step: &ScanInterval<S>,
    ) -> Result<(), FilterError> {
        let dt = step.interval();
        let (range, azimuth) = Self::polar(z);
        // The filter leaves its state untouched on an error.
        self.state.update(noise, range, azimuth, dt).map(|_| ())
    }

    fn coast(
        &mut self,
        noise: &RangeAzimuthNoise<S>,
        step: &ScanInterval<S>,
    ) -> Result<(), FilterError> {
        self.state.coast(noise, step.interval())
    }

    fn predict(
        &self,
        _: &RangeAzimuthNoise<S>,
        step: &ScanInterval<S>,
    ) -> Result<PredictedState<S>, FilterError> {
        let p = self.state.predict(step.interval())?;
        Ok(PredictedState {
            position: p.position,
            velocity: p.velocity,
        })
    }

    fn position(&self) -> [S; 2] {
        self.state.position()
    }

    fn velocity(&self) -> [S; 2] {
        self.state.velocity()
    }

    /// The larger of P_R⁻₁₁/σ_R² and P_C⁻₁₁/(R_p σ_B)², each direction's
    /// predicted position variance in units of its own measurement variance
    /// (R_p the predicted range).
    fn predicted_variance_ratio(
        &self,
        noise: &RangeAzimuthNoise<S>,
        step: &ScanInterval<S>,
    ) -> Option<S> {
        let dt = step.interval();
        let p = self.predict(noise, step).ok()?;
        let range = hypot(p.position[0], p.position[1]);
        let [along, across, sigma_r, sigma_c] = self.predicted_sigmas(noise, dt, range)?;
        let ratio = (along / sigma_r).max_of(across / sigma_c);
        let r2 = ratio * ratio;
        r2.is_valid().then_some(r2)
    }

    /// The larger of α (eq. 9) and W1 (eq. 10) for an update 1 s ahead (this
    /// signature has no interval); 1 before filtering starts. The table does
    /// not call it: [`Self::gate_region`] uses the gains at the scan's own
    /// interval.
    fn gate_alpha(&self, noise: &RangeAzimuthNoise<S>) -> S {
        let Some(Ok(p)) = one_second::<S>().map(|second| self.predict(noise, &second)) else {
            return S::ONE;
        };
        let range = hypot(p.position[0], p.position[1]);
        match self.predicted_sigmas(noise, S::ONE, range) {
            Some([along, across, sigma_r, sigma_c]) => {
                position_gain(along, sigma_r).max_of(position_gain(across, sigma_c))
            }
            None => S::ONE,
        }
    }

    fn gate_region(
        &self,
        noise: &RangeAzimuthNoise<S>,
        predicted: &PredictedState<S>,
        step: &ScanInterval<S>,
        gate: &Gate<S>,
    ) -> Option<GateRegion<S>> {
        let dt = step.interval();
        let range = hypot(predicted.position[0], predicted.position[1]);
        let [along, across, sigma_r, sigma_c] = self.predicted_sigmas(noise, dt, range)?;
        let (half_along, half_across) = match *gate {
            Gate::Uncertainty {
                threshold,
                max_acceleration,
                ..
            } => {
                let k = threshold.sqrt();
                let allowance = S::from_f64_lossy(0.5) * max_acceleration * dt * dt;
                let scale = Self::range_coupling_scale(noise, across, range);
                (
                    k * hypot(along * scale, sigma_r) + allowance,
                    k * hypot(across, sigma_c) + allowance,
                )
            }
            Gate::Wave {
                range_sigma,
                bearing_sigma,
                multiple,
            } => (
                multiple * position_gain(along, sigma_r).sqrt() * range_sigma,
                multiple * position_gain(across, sigma_c).sqrt() * range * bearing_sigma,
            ),
        };
        GateRegion::polar(predicted.position, half_along, half_across)
    }
}
