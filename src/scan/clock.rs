//! The scan clock's period and windows.

use crate::track::ConfigError;

/// The scan clock's period and windows (see [`crate::scan`], "Time"), in
/// milliseconds of the sensor's clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ClockConfig {
    pub(super) period_ms: u32,
    pub(super) late_window_ms: u32,
    pub(super) jump_ms: u32,
}

impl ClockConfig {
    /// Late window, in periods, of [`ClockConfig::new`]: a measurement up
    /// to one period after its scan ran is late; an older one is out of
    /// the window.
    pub const LATE_PERIODS: u32 = 2;
    /// Jump bound, in periods, of [`ClockConfig::new`]: a silence of up to
    /// 30 periods is a gap (empty scans, the tracks coast and are deleted);
    /// a longer step is a jump of the sensor's clock (re-lock).
    pub const JUMP_PERIODS: u32 = 30;

    /// The scan period (inside the filters' 50 ms – 20 s,
    /// [`crate::filter::MIN_INTERVAL_MS`], [`crate::filter::MAX_INTERVAL_MS`])
    /// with the default windows.
    pub const fn new(period_ms: u32) -> Result<Self, ConfigError> {
        let (Some(late), Some(jump)) = (
            period_ms.checked_mul(Self::LATE_PERIODS),
            period_ms.checked_mul(Self::JUMP_PERIODS),
        ) else {
            return Err(ConfigError::OutOfRange);
        };
        Self::with_windows(period_ms, late, jump)
    }

    /// Explicit windows: a period inside the filters' 50 ms – 20 s (the
    /// tracker's interval), late window ≥ period, jump ≥ period, all below
    /// 2³¹ ms.
    pub const fn with_windows(
        period_ms: u32,
        late_window_ms: u32,
        jump_ms: u32,
    ) -> Result<Self, ConfigError> {
        let limit = i32::MAX as u32;
        if period_ms < crate::filter::MIN_INTERVAL_MS
            || period_ms > crate::filter::MAX_INTERVAL_MS
            || late_window_ms < period_ms
            || jump_ms < period_ms
            || late_window_ms > limit
            || jump_ms > limit
        {
            return Err(ConfigError::OutOfRange);
        }
        Ok(ClockConfig {
            period_ms,
            late_window_ms,
            jump_ms,
        })
    }

    /// The scan period, in ms.
    pub const fn period_ms(&self) -> u32 {
        self.period_ms
    }
    /// The late window, in ms: a measurement from a past scan up to this far
    /// back is counted late; older, out of the window.
    pub const fn late_window_ms(&self) -> u32 {
        self.late_window_ms
    }
    /// The jump bound, in ms: a measurement up to this far ahead starts a later
    /// scan; further ahead, it is out of the window (a clock jump candidate).
    pub const fn jump_ms(&self) -> u32 {
        self.jump_ms
    }
}
