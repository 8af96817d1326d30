//! Whether a run's input was used.

use crate::wire::Health;

/// Whether a run's input was used, from its last health counters: the rule
/// behind the demo firmware's exit status.
///
/// The sensor sent `sent = accepted frames + frames lost` (from the
/// sequence numbers, and the frames refused before the first accepted one:
/// [`crate::wire::Decoder`]); of those, `lost = frames lost + measurements not used`
/// (queue full, late, out of the window, over capacity, not representable,
/// rejected by the tracker). A run is **clean** when it used at least one
/// measurement and lost at most one in [`MAX_LOST_FRACTION_INVERSE`] of what
/// was sent, and no threat assessment failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RunVerdict {
    /// Frames the sensor sent: accepted plus lost ([`crate::wire::Decoder`]).
    pub sent: u32,
    /// Frames lost plus measurements not used (queue full, late, out of the
    /// window, over capacity, not representable, rejected by the tracker).
    pub lost: u32,
    /// Measurements used by the track table.
    pub used: u32,
    /// Threat assessments that failed.
    pub assessment_errors: u32,
}

/// A clean run loses at most 1 in this many of the frames sent.
pub const MAX_LOST_FRACTION_INVERSE: u32 = 10;

impl RunVerdict {
    /// The verdict from a run's last health counters.
    pub fn from_health(h: &Health) -> Self {
        let s = &h.scan;
        let lost = [
            h.decoder.frames_lost,
            h.intake.queue_full,
            s.late,
            s.out_of_window,
            s.over_capacity,
            s.invalid,
            s.rejected,
        ]
        .into_iter()
        .fold(0u32, |a, b| a.saturating_add(b));
        RunVerdict {
            sent: h.decoder.accepted.saturating_add(h.decoder.frames_lost),
            lost,
            used: s.used,
            assessment_errors: s.assessment_errors,
        }
    }

    /// More than one in [`MAX_LOST_FRACTION_INVERSE`] of the frames sent
    /// was not used.
    pub fn lost_too_much(&self) -> bool {
        u64::from(self.lost).saturating_mul(u64::from(MAX_LOST_FRACTION_INVERSE))
            > u64::from(self.sent)
    }

    /// Used at least one measurement, lost at most one in
    /// [`MAX_LOST_FRACTION_INVERSE`] and no assessment failed.
    pub fn is_clean(&self) -> bool {
        self.used > 0 && !self.lost_too_much() && self.assessment_errors == 0
    }
}
