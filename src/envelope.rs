//! The numeric envelope: the largest values the filters are specified for
//! (the fixed-point format of [`crate::num`] is sized for them) and the
//! values a sensor may report. One set of limits for the wire edge, the
//! firmware and the host tools; a value outside is refused where it enters,
//! except an interval: outside [`INTERVAL_S`] a report restarts the estimate
//! or is skipped ([`crate::filter::IntervalSpan`]).
//!
//! The figures are those of the numeric specification (see
//! `docs/numerics.md`): positions ±400 km, velocities ±1500 m/s,
//! accelerations ±200 m/s², intervals 0.05–20 s; altitudes are Mode C's
//! −1000 … 126 700 ft (ICAO Annex 10 Vol. IV).

/// A closed interval `min ..= max` of accepted values.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Limit {
    /// Smallest accepted value (the quantity's unit: m, m/s, m/s², s or ft).
    pub min: f64,
    /// Largest accepted value (same unit as `min`).
    pub max: f64,
}

impl Limit {
    /// `-bound ..= bound`.
    pub const fn symmetric(bound: f64) -> Self {
        Limit {
            min: -bound,
            max: bound,
        }
    }

    /// Inside or on the boundary; false for NaN.
    pub fn contains(&self, value: f64) -> bool {
        value >= self.min && value <= self.max
    }
}

/// Largest |x|, |y| (and |z|) of a position or range, m.
pub const MAX_POSITION_M: f64 = 400_000.0;
/// A Cartesian coordinate, m.
pub const POSITION_M: Limit = Limit::symmetric(MAX_POSITION_M);
/// A slant range, m: positive, at most [`MAX_POSITION_M`].
pub const RANGE_M: Limit = Limit {
    min: 0.0,
    max: MAX_POSITION_M,
};
/// A velocity component, m/s.
pub const VELOCITY_M_PER_S: Limit = Limit::symmetric(1500.0);
/// An acceleration component, m/s².
pub const ACCELERATION_M_PER_S2: Limit = Limit::symmetric(200.0);
/// The interval between two updates of one filter, s.
pub const INTERVAL_S: Limit = Limit {
    min: 0.05,
    max: 20.0,
};
/// A reported pressure altitude, ft (Mode C).
pub const ALTITUDE_FT: Limit = Limit {
    min: -1000.0,
    max: 126_700.0,
};
/// An azimuth in radians: one turn either way (a larger magnitude is not a
/// bearing in radians; in degrees it would be up to 360).
pub const AZIMUTH_RAD: Limit = Limit::symmetric(core::f64::consts::TAU);
/// An azimuth in degrees: one turn either way.
pub const AZIMUTH_DEG: Limit = Limit::symmetric(360.0);
/// A time stamp in seconds (host tools, which read times as `f64`): up to
/// 2³³ s (272 years, so epoch seconds fit), where an `f64` still resolves
/// 2⁻¹⁹ s ≈ 1.9 µs, far below the shortest interval and the track table's
/// millisecond clock.
pub const TIME_S: Limit = Limit::symmetric(8_589_934_592.0);
