//! Gain design and the gain schedules: formulas, hand-computed sequences,
//! properties, representations, robustness, the bank and `auto`.

mod bank;
mod covariance;
mod design;
mod properties;
mod representations;
mod robustness;
mod sequences;
mod spec;
mod support;
