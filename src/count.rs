//! Saturating counters: every count the library keeps stops at its type's
//! maximum instead of wrapping.

/// Adds one to `counter`, saturating.
pub(crate) fn increment(counter: &mut u32) {
    *counter = counter.saturating_add(1);
}

/// Adds one to a 16-bit `counter` (a wire frame's), saturating.
pub(crate) fn increment16(counter: &mut u16) {
    *counter = counter.saturating_add(1);
}

/// `n` as a `u32`, saturated.
pub(crate) fn sat_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// `n` as a `u16`, saturated.
pub(crate) fn sat_u16(n: u32) -> u16 {
    u16::try_from(n).unwrap_or(u16::MAX)
}
