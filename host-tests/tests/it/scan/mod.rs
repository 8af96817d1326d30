//! The scan loop's core on the host, fed with encoded frames as the
//! firmware is.

mod loop_on_host;
mod reply_identity;
pub(crate) mod support;
mod zero_state;
