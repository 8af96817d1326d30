//! The TCAS II logic: threat measures, sensitivity levels, detection and
//! resolution, the altitude tracker and the encounters.

mod altitude;
mod analytic_encounters;
mod encounter_suite;
mod logic;
mod one_type;
mod sensitivity;
mod state_size;
mod threat;
