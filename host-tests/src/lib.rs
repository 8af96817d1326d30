//! Host-side support for abtrack: what needs `std`.
//!
//! * [`reference`](mod@reference): the independent `f64` reference filters, written straight
//!   from the papers; [`reference_ra`] the same for He et al.'s range-azimuth
//!   filter; [`reference_tcas`] the TCAS II v7.1 logic on true states.
//! * [`encounters`]: the TCAS encounter suite and the demo scenario;
//!   [`altitude_figures`]: the altitude tracker's figures.
//! * [`trajectory`]: seeded random trajectories for the precision checks.
//! * [`scenario`], [`noise`]: the papers' scenarios and measurement noise.
//! * [`kalman`]: the Kalman-filter baselines; [`metrics`]: RMSE, confidence
//!   intervals, OSPA and track metrics.
//! * [`csv_input`], [`replay`], [`replay_tracker`], [`cli`]: the `replay`
//!   tool's CSV reader, runners and command line; [`output`]: stdout for the
//!   tools (a closed pipe ends them quietly).
//! * [`precision`]: runs a representation next to the reference and measures
//!   the deviation and the run's magnitudes; the documented runs.
//! * [`tracking`]: runs the track table over the multi-target scenarios for
//!   the metrics and experiments.
//! * [`experiments`]: the `experiments` tool's groups and output helpers.
//! * [`frames`]: wire frames for the demo firmware's UART (the `frames` tool).
//! * [`bench_report`]: the benchmark firmware's output to bench/results.csv
//!   and bench/BENCHMARKS.md (the `bench_report` tool).
//! * [`firmware_elf`]: checks on the release firmware ELFs (panic calls, stack
//!   layout; the `firmware-check` tool).

pub mod altitude_figures;
pub mod bench_report;
pub mod cli;
/// The CSV reader (its own package, `csv-input/`).
pub use abtrack_csv_input as csv_input;
pub mod encounters;
pub mod experiments;
pub mod firmware_elf;
pub mod frames;
pub mod kalman;
pub mod metrics;
pub mod noise;
pub mod output;
pub mod precision;
pub mod random_encounters;
pub mod recorded_encounters;
pub mod reference;
pub mod reference_ra;
pub mod reference_tcas;
pub mod replay;
pub mod replay_tracker;
pub mod scenario;
pub mod tracking;
pub mod trajectory;
