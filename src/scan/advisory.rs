//! The advisory level on two discrete outputs.

use embedded_hal::digital::OutputPin;

use crate::tcas::Advisory;

/// Two discrete outputs for the advisory level, as a TCAS processor drives
/// its display and aural-warning lines: the traffic line is high while any
/// intruder has a traffic or a resolution advisory, the resolution line
/// while any has a resolution advisory. The pins are embedded-hal 1.0
/// [`OutputPin`]s: the board behind them is the caller's.
#[derive(Debug)]
pub struct AdvisoryLines<P> {
    traffic: P,
    resolution: P,
    shown: Option<Advisory>,
    changes: u32,
}

impl<P: OutputPin> AdvisoryLines<P> {
    /// Takes the pins; they are first driven by [`AdvisoryLines::show`].
    pub fn new(traffic: P, resolution: P) -> Self {
        AdvisoryLines {
            traffic,
            resolution,
            shown: None,
            changes: 0,
        }
    }

    /// Drives the lines for the most severe advisory of a scan; true if the
    /// lines changed. The first call always drives both.
    pub fn show(&mut self, highest: Advisory) -> Result<bool, P::Error> {
        let traffic = highest >= Advisory::Traffic;
        let resolution = highest >= Advisory::Resolution;
        let before = self
            .shown
            .map(|a| (a >= Advisory::Traffic, a >= Advisory::Resolution));
        if before == Some((traffic, resolution)) {
            self.shown = Some(highest);
            return Ok(false);
        }
        set(&mut self.traffic, traffic)?;
        set(&mut self.resolution, resolution)?;
        if before.is_some() {
            self.changes = self.changes.saturating_add(1);
        }
        self.shown = Some(highest);
        Ok(true)
    }

    /// Times the lines changed after the first [`show`](Self::show).
    pub fn changes(&self) -> u32 {
        self.changes
    }

    /// (traffic, resolution) pins, e.g. to read them back.
    pub fn pins(&self) -> (&P, &P) {
        (&self.traffic, &self.resolution)
    }

    /// Gives the (traffic, resolution) pins back.
    pub fn release(self) -> (P, P) {
        (self.traffic, self.resolution)
    }
}

fn set<P: OutputPin>(pin: &mut P, high: bool) -> Result<(), P::Error> {
    if high {
        pin.set_high()
    } else {
        pin.set_low()
    }
}
