//! The numeric labels of the output: which number system a figure was
//! measured in.

use abtrack::{Fix, Fixed32, ScaledScalar};

/// The label of integer-only code (the wire decoder, the hand-written
/// integer scan): the same in every numeric type.
pub const INTEGER: &str = "int";

/// A number system the abtrack operations run in ([`abtrack::Numeric`]),
/// with its label in the benchmark's output (the `numeric` column of
/// bench/results.csv).
pub trait BenchNumber: abtrack::Numeric {
    const LABEL: &'static str;
}

/// Hardware single precision where the core has an FPU (the hard-float ABI:
/// Cortex-M4F), software single precision elsewhere.
impl BenchNumber for f32 {
    #[cfg(target_abi = "eabihf")]
    const LABEL: &'static str = "f32";
    #[cfg(not(target_abi = "eabihf"))]
    const LABEL: &'static str = "f32soft";
}

/// The fast fixed point ([`Fixed32`]): 32-bit words with a format per
/// quantity.
impl BenchNumber for Fixed32 {
    const LABEL: &'static str = "fixed";
}

/// The fast fixed point's wide format as one type for every quantity
/// ([`ScaledScalar`]): the type the code written for `Scalar` (the altitude
/// tracker, TCAS) runs in when named with `Fixed32` (the Cortex-M3's scan
/// loop), so its rows are the fast fixed point's (`fixed`); Fixed32 itself
/// has no implementation of them.
impl BenchNumber for ScaledScalar {
    const LABEL: &'static str = "fixed";
}

/// Q32.32 ([`Fix`]).
impl BenchNumber for Fix {
    const LABEL: &'static str = "q32";
}

/// Software double precision on every core here.
impl BenchNumber for f64 {
    const LABEL: &'static str = "f64";
}
