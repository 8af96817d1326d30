//! The numeric labels of the output: which type a figure was measured in.

use abtrack::{Fix, Scalar};

/// A numeric type the abtrack operations run in, with its label in the
/// benchmark's output (the `numeric` column of bench/results.csv).
pub trait Numeric: Scalar {
    const LABEL: &'static str;
}

/// Hardware single precision where the core has an FPU (the hard-float ABI:
/// Cortex-M4F), software single precision elsewhere.
impl Numeric for f32 {
    #[cfg(target_abi = "eabihf")]
    const LABEL: &'static str = "f32";
    #[cfg(not(target_abi = "eabihf"))]
    const LABEL: &'static str = "f32soft";
}

/// Q32.32 ([`Fix`]).
impl Numeric for Fix {
    const LABEL: &'static str = "q32";
}

/// Software double precision on every core here.
impl Numeric for f64 {
    const LABEL: &'static str = "f64";
}
