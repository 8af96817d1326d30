//! Tracker configuration: filter parameters, gate, initiation, confirmation,
//! deletion and surveillance volume.

use super::gate::{non_negative, ConfigError, Gate, GateRegion};
use crate::num::{Numeric, Quantity};

/// Axis-aligned surveillance region (m). Tracks whose position leaves it are
/// deleted; measurements outside it do not start tracks.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Volume<S: Numeric> {
    min: [S::Length; 2],
    max: [S::Length; 2],
}

impl<S: Numeric> Volume<S> {
    /// The box `min ..= max` on each axis; needs min < max.
    pub fn new(min: [S::Length; 2], max: [S::Length; 2]) -> Result<Self, ConfigError> {
        for (lo, hi) in min.iter().zip(max.iter()) {
            if !(lo.is_valid() && hi.is_valid()) {
                return Err(ConfigError::NotFinite);
            }
            if lo >= hi {
                return Err(ConfigError::EmptyVolume);
            }
        }
        Ok(Volume { min, max })
    }

    /// Lower corner (m).
    pub fn min(&self) -> [S::Length; 2] {
        self.min
    }
    /// Upper corner (m).
    pub fn max(&self) -> [S::Length; 2] {
        self.max
    }

    /// Inside or on the boundary (false for invalid coordinates).
    pub fn contains(&self, p: [S::Length; 2]) -> bool {
        p.iter()
            .zip(self.min.iter().zip(self.max.iter()))
            .all(|(v, (lo, hi))| v >= lo && v <= hi)
    }
}

/// Everything a [`TrackTable`](super::TrackTable) scan needs besides the
/// measurements. `P` is the filter's
/// [`TrackFilter::Params`](super::TrackFilter::Params) (for
/// [`FixedGainTrack`](super::FixedGainTrack): the `Gains`).
///
/// Defaults (from [`TrackerConfig::new`]):
/// * confirmation 2 of 3 (M-of-N over the first N scans of a tentative track,
///   the scan that started it counting as the first hit);
/// * deletion after 3 consecutive misses for a confirmed track, 2 for a
///   tentative one;
/// * a first point that finds no second point in the next scan waits one
///   more scan ([`Self::keep_first_points_through_a_miss`]);
/// * no initiation margin, no surveillance volume.
///
/// Kept outside the table and passed to every scan, so that the table itself
/// can be built by a `const fn` in a `static` (the checked constructors here
/// cannot be `const`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackerConfig<S: Numeric, P> {
    params: P,
    gate: Gate<S>,
    max_speed: S::Speed,
    initiation_margin: S::Length,
    confirm_hits: u8,
    confirm_window: u8,
    delete_confirmed_misses: u8,
    delete_tentative_misses: u8,
    first_points_through_a_miss: bool,
    volume: Option<Volume<S>>,
    max_gate_radius: Option<S::Length>,
}

impl<S: Numeric, P: Copy> TrackerConfig<S, P> {
    /// `params` for the filters, the gate rule, and the largest target speed
    /// (m/s) for two-point initiation: a measurement pairs with one of the
    /// previous scan only if they are at most `max_speed·T` apart.
    pub fn new(params: P, gate: Gate<S>, max_speed: S::Speed) -> Result<Self, ConfigError> {
        let gate = gate.validated()?;
        if !max_speed.is_valid() {
            return Err(ConfigError::NotFinite);
        }
        if max_speed <= S::Speed::ZERO {
            return Err(ConfigError::OutOfRange);
        }
        Ok(TrackerConfig {
            params,
            gate,
            max_speed,
            initiation_margin: S::Length::ZERO,
            confirm_hits: 2,
            confirm_window: 3,
            delete_confirmed_misses: 3,
            delete_tentative_misses: 2,
            first_points_through_a_miss: true,
            volume: None,
            max_gate_radius: None,
        })
    }

    /// Adds `margin` (m, ≥ 0) to the initiation radius `max_speed·T`, for
    /// measurement noise on the two points.
    pub fn with_initiation_margin(mut self, margin: S::Length) -> Result<Self, ConfigError> {
        self.initiation_margin = non_negative(margin)?;
        Ok(self)
    }

    /// Confirm a tentative track when `hits` of its first `window` scans had a
    /// measurement (1 ≤ hits ≤ window ≤ 32). A tentative track that can no
    /// longer reach `hits` within `window` scans is deleted.
    pub fn with_confirmation(mut self, hits: u8, window: u8) -> Result<Self, ConfigError> {
        if hits == 0 || hits > window || window > 32 {
            return Err(ConfigError::Confirmation);
        }
        self.confirm_hits = hits;
        self.confirm_window = window;
        Ok(self)
    }

    /// Delete a confirmed track after `confirmed` consecutive misses and a
    /// tentative one after `tentative` (both ≥ 1).
    pub fn with_deletion(mut self, confirmed: u8, tentative: u8) -> Result<Self, ConfigError> {
        if confirmed == 0 || tentative == 0 {
            return Err(ConfigError::Deletion);
        }
        self.delete_confirmed_misses = confirmed;
        self.delete_tentative_misses = tentative;
        Ok(self)
    }

    /// Whether an unused measurement that found no second point in the next
    /// scan is kept as a first point for one more scan (two-point
    /// initiation over both intervals, radius `max_speed·(T₁ + T₂)` plus the
    /// margin, after the previous scan's first points have paired), in the
    /// places above the previous scan's measurements (M less their number).
    /// Such a track's M-of-N window starts at the missed scan, so with the
    /// default 2 of 3 it must be seen in the next scan; with M-of-M it
    /// could never confirm, so the option has no effect then. On by default:
    /// without it, a target missed in the scan after its first detection
    /// starts a scan later (`docs/track-table.md`, "First points").
    pub fn keep_first_points_through_a_miss(mut self, keep: bool) -> Self {
        self.first_points_through_a_miss = keep;
        self
    }

    /// Delete tracks that leave `volume`; start none outside it.
    pub fn with_volume(mut self, volume: Volume<S>) -> Self {
        self.volume = Some(volume);
        self
    }

    /// Delete a confirmed track whose gate has grown larger than a circle
    /// of `radius` (m, > 0; for a range/azimuth window, larger in area):
    /// the design's rule 7 ([`TrackerDesign`](super::defaults::TrackerDesign)),
    /// past which a measurement in the gate is more likely clutter than the
    /// target. None by default.
    pub fn with_max_gate_radius(mut self, radius: S::Length) -> Result<Self, ConfigError> {
        if !radius.is_valid() {
            return Err(ConfigError::NotFinite);
        }
        if radius <= S::Length::ZERO {
            return Err(ConfigError::OutOfRange);
        }
        self.max_gate_radius = Some(radius);
        Ok(self)
    }

    /// The filters' parameters (for [`FixedGainTrack`](super::FixedGainTrack): the gains).
    pub fn params(&self) -> &P {
        &self.params
    }
    /// The gate rule.
    pub fn gate(&self) -> &Gate<S> {
        &self.gate
    }
    /// Largest target speed for two-point initiation (m/s).
    pub fn max_speed(&self) -> S::Speed {
        self.max_speed
    }
    /// Margin added to the initiation radius `max_speed·T` (m).
    pub fn initiation_margin(&self) -> S::Length {
        self.initiation_margin
    }
    /// (M, N) of M-of-N confirmation.
    pub fn confirmation(&self) -> (u8, u8) {
        (self.confirm_hits, self.confirm_window)
    }
    /// (confirmed, tentative) consecutive misses before deletion.
    pub fn deletion(&self) -> (u8, u8) {
        (self.delete_confirmed_misses, self.delete_tentative_misses)
    }
    /// Whether first points wait one missed scan
    /// ([`Self::keep_first_points_through_a_miss`]): set, and the
    /// confirmation leaves such a track a way to confirm (M ≤ N − 1, or
    /// M = 1; with M-of-M a window starting at the missed scan cannot).
    pub fn first_points_through_a_miss(&self) -> bool {
        self.first_points_through_a_miss
            && (self.confirm_hits <= 1 || self.confirm_hits < self.confirm_window)
    }
    /// The surveillance volume, if any.
    pub fn volume(&self) -> Option<&Volume<S>> {
        self.volume.as_ref()
    }
    /// The largest gate a confirmed track keeps
    /// ([`Self::with_max_gate_radius`]), if any.
    pub fn max_gate_radius(&self) -> Option<S::Length> {
        self.max_gate_radius
    }
    /// Whether a confirmed track with this gate is ended for it (the
    /// design's rule 7): its region is larger than the circle of
    /// [`Self::max_gate_radius`]; never without that bound.
    #[inline(always)]
    pub fn gate_too_wide(&self, region: &GateRegion<S>) -> bool {
        self.max_gate_radius
            .is_some_and(|radius| region.is_larger_than_circle(radius))
    }

    pub(crate) fn in_volume(&self, p: [S::Length; 2]) -> bool {
        self.volume.as_ref().is_none_or(|v| v.contains(p))
    }
}
