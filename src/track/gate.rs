//! Validation regions (gates): which measurements may belong to a track, and
//! how far inside the gate each one lies.
//!
//! A gate is built once per track and scan ([`GateRegion`]) from the track's
//! prediction and the configured [`Gate`] rule, then tested against every
//! measurement. The test returns a normalised cost in `0 ..= MAX_COST`
//! (0 = at the predicted position, `MAX_COST` = on the gate's edge), the
//! currency of the assignment solver. Normalising by the gate size makes the
//! cost the squared distance in units of the track's own uncertainty, the
//! statistical distance of global nearest neighbour, rather than metres
//! (which would favour the tracks with the smallest gates).
//!
//! Two shapes exist: a circle in x, y (isotropic Cartesian uncertainty, the
//! αβ filters) and a window in range and azimuth around the predicted polar
//! position ([`GateRegion::polar`], for the range–azimuth filter of He et
//! al., whose uncertainty differs along and across range). A filter chooses
//! its region in [`TrackFilter::gate_region`](super::TrackFilter::gate_region).

use super::numeric::quantise_unit;
use super::{Measurement, Observation};
use crate::num::{Numeric, Quantity, Scalar};

/// The rule that sizes each track's gate.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Gate<S: Numeric> {
    /// A circle around the predicted position whose radius follows the
    /// filter's predicted uncertainty:
    ///
    /// r = σ·√(G·(p + 1)) + ½·a_max·T²
    ///
    /// * σ: measurement noise standard deviation per axis (m).
    /// * p: predicted position error variance of the filter in units of σ²
    ///   ([`TrackFilter::predicted_variance_ratio`](super::TrackFilter::predicted_variance_ratio));
    ///   the innovation z − x_p then has variance σ²(p + 1) per axis, because
    ///   the new measurement's noise is independent of the prediction error.
    /// * G: gate threshold on the squared normalised distance, which is χ²
    ///   with 2 degrees of freedom for a target that moves as the filter
    ///   assumes, so a true measurement falls outside with probability
    ///   e^(−G/2): G = 9.21 keeps 99 %, G = 13.8 keeps 99.9 %.
    /// * a_max: manoeuvre allowance (m/s²). The αβ model has no process
    ///   noise, so an accelerating target drifts from the prediction by up to
    ///   ½·a·T² over the interval T; the gate is widened by that much.
    ///
    /// A tentative track's circle is held to the gate a track formed from
    /// two points would have without process noise (the design's rule 4,
    /// [`defaults`](super::defaults)).
    Uncertainty {
        /// σ, the measurement noise standard deviation per axis (m).
        measurement_sigma: S::Length,
        /// G, the threshold on the squared normalised distance (χ², 2 degrees of freedom).
        threshold: S::Ratio,
        /// a_max, the manoeuvre allowance (m/s²).
        max_acceleration: S::Acceleration,
    },
    /// The wave gate of Li, Zhao, Liang & Zhang: a circle around the
    /// predicted position of radius
    ///
    /// r = κ·λ·√(Δρ² + ρ²Δθ²),  λ = √α  (eqs. 11–12)
    ///
    /// * Δρ, Δθ: the radar's range error (m) and bearing error (rad).
    /// * ρ: range of the predicted position from the sensor at the origin.
    /// * α: the position gain the track's next update will use
    ///   ([`TrackFilter::gate_alpha`](super::TrackFilter::gate_alpha)).
    /// * κ: multiple of the distance error Δd (eq. 11) accepted.
    ///
    /// Reading of the paper: its Fig. 1 draws the gate as a box
    /// Δx × Δy scaled by λ, but the quantities it then tests are the
    /// Euclidean distance d (eq. 10) against Δd (eq. 11) through the ratio
    /// r_k = d/Δd (eq. 13), which it lets grow up to a limit R. We take the
    /// consistent reading: a circular gate d ≤ κ·Δd, with κ playing the role
    /// of R. The paper gives no value for R; κ is the caller's choice.
    Wave {
        /// Δρ, the radar's range error (m).
        range_sigma: S::Length,
        /// Δθ, the radar's bearing error (rad).
        bearing_sigma: S::Ratio,
        /// κ, the multiple of the distance error Δd (eq. 11) accepted.
        multiple: S::Ratio,
    },
}

/// Why a configuration value was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ConfigError {
    /// A value is NaN, infinite or not representable.
    NotFinite,
    /// A value that must be > 0 (or ≥ 0 for allowances) is not.
    OutOfRange,
    /// M-of-N confirmation needs 1 ≤ M ≤ N ≤ 32.
    Confirmation,
    /// Deletion thresholds must be ≥ 1.
    Deletion,
    /// The surveillance volume's minimum is not below its maximum.
    EmptyVolume,
}

impl core::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            ConfigError::NotFinite => "configuration value is not a finite number",
            ConfigError::OutOfRange => "configuration value is out of range",
            ConfigError::Confirmation => "M-of-N confirmation needs 1 <= M <= N <= 32",
            ConfigError::Deletion => "deletion thresholds must be at least 1 miss",
            ConfigError::EmptyVolume => "surveillance volume minimum must be below its maximum",
        })
    }
}

impl core::error::Error for ConfigError {}

fn positive<Q: Quantity>(v: Q) -> Result<Q, ConfigError> {
    if !v.is_valid() {
        Err(ConfigError::NotFinite)
    } else if v <= Q::ZERO {
        Err(ConfigError::OutOfRange)
    } else {
        Ok(v)
    }
}

pub(super) fn non_negative<Q: Quantity>(v: Q) -> Result<Q, ConfigError> {
    if !v.is_valid() {
        Err(ConfigError::NotFinite)
    } else if v < Q::ZERO {
        Err(ConfigError::OutOfRange)
    } else {
        Ok(v)
    }
}

impl<S: Numeric> Gate<S> {
    /// [`Gate::Uncertainty`], checked: σ > 0, G > 0, a_max ≥ 0.
    pub fn uncertainty(
        measurement_sigma: S::Length,
        threshold: S::Ratio,
        max_acceleration: S::Acceleration,
    ) -> Result<Self, ConfigError> {
        Ok(Gate::Uncertainty {
            measurement_sigma: positive(measurement_sigma)?,
            threshold: positive(threshold)?,
            max_acceleration: non_negative(max_acceleration)?,
        })
    }

    /// [`Gate::Wave`], checked: Δρ ≥ 0, Δθ ≥ 0, not both 0, κ > 0.
    pub fn wave(
        range_sigma: S::Length,
        bearing_sigma: S::Ratio,
        multiple: S::Ratio,
    ) -> Result<Self, ConfigError> {
        let range_sigma = non_negative(range_sigma)?;
        let bearing_sigma = non_negative(bearing_sigma)?;
        if range_sigma == S::Length::ZERO && bearing_sigma == S::Ratio::ZERO {
            return Err(ConfigError::OutOfRange);
        }
        Ok(Gate::Wave {
            range_sigma,
            bearing_sigma,
            multiple: positive(multiple)?,
        })
    }

    /// Re-checks a gate built directly from the enum's public fields.
    pub fn validated(self) -> Result<Self, ConfigError> {
        match self {
            Gate::Uncertainty {
                measurement_sigma,
                threshold,
                max_acceleration,
            } => Self::uncertainty(measurement_sigma, threshold, max_acceleration),
            Gate::Wave {
                range_sigma,
                bearing_sigma,
                multiple,
            } => Self::wave(range_sigma, bearing_sigma, multiple),
        }
    }
}

pub use crate::num::hypot;

/// An axis-aligned box in x, y (m), boundaries included.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BoundingBox<S: Numeric> {
    /// Lower corner (x, y) (m).
    pub min: [S::Length; 2],
    /// Upper corner (x, y) (m).
    pub max: [S::Length; 2],
}

impl<S: Numeric> BoundingBox<S> {
    /// Inside or on the boundary.
    pub fn contains(&self, p: [S::Length; 2]) -> bool {
        p[0] >= self.min[0] && p[0] <= self.max[0] && p[1] >= self.min[1] && p[1] <= self.max[1]
    }
}

/// One track's validation region for one scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GateRegion<S: Numeric> {
    /// Points within the radius of `center` (Cartesian, metres).
    Circle {
        /// The predicted position (m).
        center: [S::Length; 2],
        /// A half-width at least the radius (m): the radius itself, or,
        /// for a circle formed from its squared radius
        /// ([`GateRegion::scaled_circle`]), a bound the number system forms
        /// without a square root ([`Numeric::scaled_circle`]).
        reach: S::Length,
        /// What the number system keeps to test a point without a division
        /// (1/r² for floats, 1/r for Q32.32).
        scale: S::CircleScale,
    },
    /// A window in range and azimuth ([`GateRegion::polar`]), in the
    /// number system's polar scalar.
    Polar(PolarWindow<S::Polar>),
}

/// A window in range and azimuth around a predicted position at distance
/// `range` from the sensor, in direction `unit` ([`GateRegion::polar`]).
/// Its cost is the normalised squared distance
/// (ΔR/half_range)² + (ΔB·inverse_half_azimuth)², as for the circle.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PolarWindow<S> {
    /// R_p, the predicted position's distance from the sensor (m).
    pub range: S,
    /// The unit vector from the sensor towards the predicted position.
    pub unit: [S; 2],
    /// Half-width of the window in range (m).
    pub half_range: S,
    /// 1 / `half_range` (m⁻¹).
    pub inverse_half_range: S,
    /// R_p / half_cross: 1 over the azimuth half-width (rad⁻¹).
    pub inverse_half_azimuth: S,
}

impl<S: Numeric> GateRegion<S> {
    /// A circle; `None` if the radius is not a valid number > 0 or the
    /// number system cannot prepare its test.
    pub fn circle(center: [S::Length; 2], radius: S::Length) -> Option<Self> {
        if !(radius.is_valid()
            && radius > S::Length::ZERO
            && center[0].is_valid()
            && center[1].is_valid())
        {
            return None;
        }
        Some(GateRegion::Circle {
            center,
            reach: radius,
            scale: S::circle_scale(radius)?,
        })
    }

    /// The circle of radius σ·√`factor` around `center` (σ = `sigma`), its
    /// test formed from the squared radius σ²·`factor` (no square root in
    /// floats); `None` if σ is not > 0, the centre is not valid, or the
    /// number system cannot form the circle (the radius or its square is
    /// not a valid number > 0).
    pub fn scaled_circle(
        center: [S::Length; 2],
        sigma: S::Length,
        factor: S::Ratio,
    ) -> Option<Self> {
        if !(sigma > S::Length::ZERO && center[0].is_valid() && center[1].is_valid()) {
            return None;
        }
        let (reach, scale) = S::scaled_circle(sigma, factor)?;
        Some(GateRegion::Circle {
            center,
            reach,
            scale,
        })
    }

    /// Whether the region is larger than a circle of `radius` (m): wider
    /// for a circle (its exact radius formed only when its reach, a bound
    /// on it, is wider), larger in area for a range/azimuth window
    /// (half_range·R_p > radius²·inverse_half_azimuth, its area
    /// π·half_range·half_cross against π·radius²). In a format of absolute
    /// precision (Q32.32) both products could leave it at long range: there
    /// the half-range is divided by the radius first, comparing
    /// (half_range/radius)·R_p with radius·inverse_half_azimuth, whose left
    /// side stays small and whose right side, saturated, is rightly not
    /// exceeded.
    pub fn is_larger_than_circle(&self, radius: S::Length) -> bool {
        match self {
            GateRegion::Circle { reach, scale, .. } => {
                *reach > radius && S::circle_radius(*reach, *scale) > radius
            }
            GateRegion::Polar(w) => {
                let r = S::length_to_polar(radius);
                if <S::Polar as Quantity>::RELATIVE_PRECISION {
                    w.half_range * w.range > r * r * w.inverse_half_azimuth
                } else {
                    w.half_range / r * w.range > r * w.inverse_half_azimuth
                }
            }
        }
    }

    /// This region held to the circle of `radius` around its centre: a
    /// wider circle gives that circle (if it can be formed); a
    /// range/azimuth window is kept as it is.
    pub fn limited_to(self, radius: S::Length) -> Self {
        match self {
            GateRegion::Circle { center, .. } if self.is_larger_than_circle(radius) => {
                Self::circle(center, radius).unwrap_or(self)
            }
            _ => self,
        }
    }

    /// A range/azimuth window around the predicted position `center` (from
    /// a sensor at the origin): measurements whose range R and azimuth B
    /// satisfy ((R − R_p)/`half_range`)² + (R_p·ΔB/`half_cross`)² ≤ 1, with
    /// R_p = |center|, ΔB the angle between the measurement's and the
    /// prediction's directions (in [−π, π]) and `half_cross` in metres of
    /// arc at R_p (the cross-range half-width).
    ///
    /// Why not an ellipse in x, y aligned with the line of sight: the circle
    /// of constant range bends away from the tangent by v²/(2R) at a lateral
    /// offset v, and with a 5° bearing error the gate's lateral half-width
    /// (several σ_B·R) makes that bend (hundreds of metres at 14 km) many
    /// times the range half-width (a few σ_R, tens of metres): a Cartesian
    /// ellipse rejects true measurements well off the line of sight. The
    /// window is exact for any angular width.
    ///
    /// At R_p = 0 there is no direction: the circle of the larger
    /// half-width. `None` if a half-width is not a valid number > 0 or
    /// its inverse is not representable.
    pub fn polar(
        center: [S::Length; 2],
        half_range: S::Length,
        half_cross: S::Length,
    ) -> Option<Self> {
        let to = S::length_to_polar;
        match PolarWindow::new(
            [to(center[0]), to(center[1])],
            to(half_range),
            to(half_cross),
        )? {
            Ok(window) => Some(GateRegion::Polar(window)),
            Err(radius) => Self::circle(center, S::length_from_polar(radius)),
        }
    }

    /// An axis-aligned box that contains every observation [`Self::cost`]
    /// accepts: the spatial pre-gate looks up the measurements inside it and
    /// tests only those exactly.
    ///
    /// * Circle: the centre ± ρ·(1 + 2⁻⁴), ρ its reach (≥ r). The exact
    ///   test accepts z when the rounded z − c is ≤ ρ; one rounding errs by
    ///   less than 2⁻²³ of the result in f32 (fixed point subtracts
    ///   exactly), so z − c < ρ·(1 + 2⁻⁴) and, rounding being monotone, z
    ///   lies inside the rounded bounds.
    /// * Range/azimuth window: a point at range R and angle ΔB ≤ h_C/R_p
    ///   from the prediction (half-widths h_R along and h_C across range,
    ///   predicted range R_p) lies within √(h_R² + R·R_p·ΔB²) ≤
    ///   h_R + h_C·(1 + h_R/R_p) of it; the box is the centre ± twice that
    ///   plus (R_p + h_R)/256, room for the rounding of the projection, the
    ///   square roots and the arctangent (in the polar scalar, converted).
    pub fn bounds(&self) -> BoundingBox<S> {
        match *self {
            GateRegion::Circle { center, reach, .. } => {
                let (min, max) = S::circle_bounds(center, reach);
                BoundingBox { min, max }
            }
            GateRegion::Polar(window) => {
                let (min, max) = window.bounds();
                let from = S::length_from_polar;
                BoundingBox {
                    min: [from(min[0]), from(min[1])],
                    max: [from(max[0]), from(max[1])],
                }
            }
        }
    }

    /// Radius of a circular region; for a range/azimuth window, its range
    /// half-width.
    pub fn radius(&self) -> S::Length {
        match *self {
            GateRegion::Circle { reach, scale, .. } => S::circle_radius(reach, scale),
            GateRegion::Polar(window) => S::length_from_polar(window.half_range),
        }
    }

    /// The normalised cost `(d/r)²·MAX_COST` (circle) or
    /// `((ΔR/half_range)² + (ΔB/ΔB_max)²)·MAX_COST` (range/azimuth window),
    /// rounded, if the observation lies inside the region; `None` if
    /// outside.
    pub fn cost(&self, observation: &Observation<S>) -> Option<u16> {
        match *self {
            GateRegion::Circle {
                center,
                reach,
                scale,
            } => S::circle_cost_at(observation.xy(), center, reach, scale),
            GateRegion::Polar(window) => {
                let z = observation.xy().map(S::length_to_polar);
                let measured_range = match observation.measurement() {
                    Measurement::Polar { range, .. } => S::length_to_polar(range),
                    Measurement::Cartesian { .. } => hypot(z[0], z[1]),
                };
                window.cost(z, measured_range)
            }
        }
    }
}

impl<S: Scalar> PolarWindow<S> {
    /// The window, or `Err(radius)` for a circle of that radius when the
    /// centre is at the sensor (no direction); `None` if not representable.
    #[inline(never)]
    fn new(center: [S; 2], half_range: S, half_cross: S) -> Option<Result<Self, S>> {
        let range = hypot(center[0], center[1]);
        if !range.is_valid() {
            return None;
        }
        if range == S::ZERO {
            return Some(Err(half_range.max_of(half_cross)));
        }
        let valid = |v: S| v.is_valid() && v > S::ZERO;
        if !(valid(half_range) && valid(half_cross)) {
            return None;
        }
        let inverse_half_range = S::ONE / half_range;
        // 1/ΔB_max = R_p / half_cross (rad⁻¹).
        let inverse_half_azimuth = range / half_cross;
        if !(valid(inverse_half_range) && valid(inverse_half_azimuth)) {
            return None;
        }
        Some(Ok(PolarWindow {
            range,
            unit: [center[0] / range, center[1] / range],
            half_range,
            inverse_half_range,
            inverse_half_azimuth,
        }))
    }

    /// (min, max) corners of the box of [`GateRegion::bounds`].
    // Not inlined: the circle is the hot path, and a copy of the window's
    // arithmetic at each call site costs flash for nothing.
    #[inline(never)]
    fn bounds(&self) -> ([S; 2], [S; 2]) {
        let half_cross = self.range / self.inverse_half_azimuth;
        let spread = self.half_range + half_cross * (S::ONE + self.half_range / self.range);
        let rounding = (self.range + self.half_range) * S::from_f64_lossy(1.0 / 256.0);
        let half = spread + spread + rounding;
        let center = [self.unit[0] * self.range, self.unit[1] * self.range];
        (
            [center[0] - half, center[1] - half],
            [center[0] + half, center[1] + half],
        )
    }

    /// The cost of a measurement at `z` whose range from the sensor is
    /// `measured_range` (its own for a polar measurement).
    ///
    /// Each offset is first compared with its half-width, so the squares are
    /// of numbers ≤ 1 and cannot saturate in fixed point.
    #[inline(never)]
    fn cost(&self, z: [S; 2], measured_range: S) -> Option<u16> {
        // The range test first: it is cheap and rejects most pairs.
        let dr = measured_range - self.range;
        // `!(a <= b)` is also true for NaN.
        if !(dr.abs() <= self.half_range && measured_range != S::ZERO) {
            return None;
        }
        // Angle between the directions, from unit vectors (no product of
        // two positions is formed, so Q32.32 cannot overflow) and one
        // arctangent: exact for any width.
        let unit = self.unit;
        let m = [z[0] / measured_range, z[1] / measured_range];
        let cross = unit[0] * m[1] - unit[1] * m[0];
        let dot = unit[0] * m[0] + unit[1] * m[1];
        let db = cross.atan2(dot);
        let nr = dr * self.inverse_half_range;
        let nb = db * self.inverse_half_azimuth;
        if !(nb.abs() <= S::ONE && nr.abs() <= S::ONE) {
            return None;
        }
        let d2 = nr * nr + nb * nb;
        if !(d2.is_valid() && d2 <= S::ONE) {
            return None;
        }
        Some(quantise_unit(d2))
    }
}
