//! The TCAS II logic: threat measures, sensitivity levels, detection and
//! resolution, the altitude tracker and the encounters.

/// Runs a test body generic over the scalar in each type the TCAS code is
/// checked in: `f64`, `f32`, Q32.32 and the Cortex-M3's `ScaledScalar`.
macro_rules! in_every_tcas_type {
    ($body:ident) => {
        $body::<f64>();
        $body::<f32>();
        $body::<abtrack::Fix>();
        $body::<abtrack::ScaledScalar>();
    };
}

mod altitude;
mod analytic_encounters;
mod encounter_suite;
mod logic;
mod one_type;
mod sensitivity;
mod state_size;
mod threat;
