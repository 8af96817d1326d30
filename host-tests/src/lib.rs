//! Host-side support for abtrack: what needs `std`.

pub mod experiments;
pub mod kalman;
pub mod metrics;
pub mod noise;
pub mod reference_ra;
pub mod scenario;
pub mod tracking;
