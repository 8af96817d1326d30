//! Host-side support for abtrack: what needs `std`.
//!
//! * [`reference`]: the independent `f64` reference filters, written straight
//!   from the papers.
//! * [`scenario`]: seeded measurement sequences.
//! * [`csv_input`], [`replay`], [`cli`]: the `replay` tool's CSV reader,
//!   runner and command line.
//! * [`precision`]: runs a representation next to the reference and measures
//!   the deviation and the run's magnitudes; the documented runs.

pub mod cli;
pub mod csv_input;
pub mod precision;
pub mod reference;
pub mod replay;
pub mod scenario;
