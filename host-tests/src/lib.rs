//! Host-side support for abtrack: what needs `std`.
//!
//! * [`reference`]: the independent `f64` reference filters, written straight
//!   from the papers.
//! * [`scenario`]: seeded measurement sequences.
//! * [`precision`]: runs a representation next to the reference and measures
//!   the deviation and the run's magnitudes; the documented runs.

pub mod precision;
pub mod reference;
pub mod scenario;
