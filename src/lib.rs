//! abtrack: αβ / αβγ target tracking for Cortex-M, without a heap.
//!
//! The layers, each using only those above it:
//!
//! | module | what it owns |
//! |---|---|
//! | [`num`] | the number systems ([`num::Numeric`]): `f64`, `f32`, Q32.32 and the fast fixed point |
//! | [`gains`] | the gains (α, β, γ), their stability region and the papers' gain formulas |
//! | [`filter`] | single-target αβ / αβγ filters, one axis and composed into 2-D/3-D |
//! | [`budget`] | the error budget: bound on the deviation of an f32 / fixed-point run from f64 |
//! | [`design`] | closed-form analysis: stability, noise ratio, steady-state and transient errors |
//! | [`envelope`] | the limits every value is checked against where it enters |
//! | [`track`] | the fixed-capacity multi-target track table: gating, assignment, lifecycle |
//! | [`tcas`] | threat measures and advisory levels |
//! | [`wire`] | the serial frame codec: measurement frames in, report frames out (sans-IO) |
//! | [`scan`] | the scan loop's core: received bytes and timer ticks to tracks, advisories and reports |
//!
//! The specification is five papers, cited in the doc comments by author and
//! equation number (see docs/papers.md).
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_debug_implementations)]
// Every public item is documented; keep it so.
#![deny(missing_docs)]

pub mod bank;
pub mod budget;
#[macro_use]
mod count;
pub mod design;
pub mod envelope;
pub mod filter;
pub mod gain;
pub mod gains;
pub mod num;
pub mod scan;
pub mod tcas;
pub mod track;
pub mod wire;

pub use filter::{AlphaBeta, AlphaBetaGamma, Cartesian, FilterError, GainError, Gains};
pub use num::{AddProduct, Fix, Fixed32, NumError, Numeric, Quantity, Real, Scalar, ScaledScalar};
