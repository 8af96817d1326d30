//! The number types and their functions: `Fix` (Q32.32), the fast fixed point,
//! `ScaledScalar`, CORDIC, sine, hypot, the error budget and the wide products.

mod cordic;
mod error_budget;
mod f32_integer_paths;
mod fix;
mod fixed32;
mod fixed_variance;
mod hypot3;
mod scaled_scalar;
mod sine;
mod two;
mod wide;
