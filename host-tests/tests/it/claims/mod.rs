//! The papers' and experiments' claims, asserted on reduced seeded Monte
//! Carlo runs (the full runs: the `experiments` tool).

mod auto;
mod gain_schedules;
mod multi_target;
mod paper_readings;
mod range_azimuth_and_advisories;
mod real_data;
mod tcas_random;
mod tcas_real;
