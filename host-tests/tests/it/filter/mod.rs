//! The filters: against the independent f64 reference, their refusals of
//! bad input, the range–azimuth filter and the README's example.

mod bad_input;
mod f32_refusals;
mod gaps_restart;
mod range_azimuth;
mod readme_example;
mod reference;
