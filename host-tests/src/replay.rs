//! The runner behind the `replay` tool: the library's filters, in a chosen
//! representation, over recorded measurements ([`crate::csv_input`]), with the
//! output as CSV text.
//!
//! Output: a header, then one row per input row: `t` (echoed as written),
//! then for each axis `a` (`x`, `y`, `z`) the columns `a`, `va`, `res_a`, and
//! for αβγ also `aa`: the smoothed position and velocity after the update, the
//! residual z − x_p of the update (Al-Wagih eq. 4; empty on the two
//! initialisation rows, which have none, eqs. 9–10), and the smoothed
//! acceleration. Values are written in the representation's own shortest
//! exact form (`f32` values as `f32`, fixed point in decimal).
//!
//! The first row's interval is not used by the filter (two-point
//! initialisation takes the position only), so it is given as 1 s. Each later
//! interval is the difference of consecutive times, computed in `f64` and then
//! converted to the representation.
//!
//! Adding a filter kind: a variant of [`FilterKind`], its arm in [`run`], and
//! its option names in [`crate::cli`].

use std::fmt::{self, Write as _};

use abtrack::filter::{Cartesian, Gains, UpdateOutcome};
use abtrack::{FilterError, Fix, GainError, NumError, Scalar};

use crate::csv_input::Measurements;

/// Which filter to run, with its fixed gains.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FilterKind {
    /// αβ, Al-Wagih & Abdulla eqs. (3)–(10).
    AlphaBeta { alpha: f64, beta: f64 },
    /// αβγ, Tenne & Singh eqs. (1)–(5), γ in their γ/(2T²) convention.
    AlphaBetaGamma { alpha: f64, beta: f64, gamma: f64 },
}

impl FilterKind {
    /// The gains as `Gains<S>`, checked against the stability region.
    pub fn gains<S: Scalar>(&self) -> Result<Gains<S>, GainError> {
        match *self {
            FilterKind::AlphaBeta { alpha, beta } => Gains::alpha_beta_f64(alpha, beta),
            FilterKind::AlphaBetaGamma { alpha, beta, gamma } => {
                Gains::alpha_beta_gamma_f64(alpha, beta, gamma)
            }
        }
    }
}

/// The number representation the filter runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Numeric {
    #[default]
    F64,
    F32,
    /// Q32.32 ([`abtrack::Fix`]).
    Fixed,
}

impl Numeric {
    pub const NAMES: &'static str = "f64|f32|fixed";

    pub fn from_name(name: &str) -> Option<Numeric> {
        match name {
            "f64" => Some(Numeric::F64),
            "f32" => Some(Numeric::F32),
            "fixed" => Some(Numeric::Fixed),
            _ => None,
        }
    }
}

/// What to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplayConfig {
    pub filter: FilterKind,
    pub numeric: Numeric,
}

/// Why a replay stopped. Lines and columns are those of the input file.
#[derive(Debug, Clone, PartialEq)]
pub enum ReplayError {
    /// The gains are outside the stability region (or not representable).
    Gains(GainError),
    /// A value of the file does not fit the representation.
    Value {
        line: usize,
        column: usize,
        name: &'static str,
        error: NumError,
    },
    /// The filter refused a row (e.g. fixed-point saturation).
    Filter { line: usize, error: FilterError },
}

impl fmt::Display for ReplayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReplayError::Gains(e) => write!(f, "gains outside the stability region: {e}"),
            ReplayError::Value {
                line,
                column,
                name,
                error,
            } => write!(f, "line {line}, column {column} ({name}): {error}"),
            ReplayError::Filter { line, error } => {
                write!(f, "line {line}: the filter refused the row: {error}")
            }
        }
    }
}

impl std::error::Error for ReplayError {}

/// A [`Scalar`] that can be written to the output CSV.
pub trait CsvValue: Scalar {
    fn write_csv(self, out: &mut String);
}

impl CsvValue for f64 {
    fn write_csv(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

impl CsvValue for f32 {
    fn write_csv(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

impl CsvValue for Fix {
    fn write_csv(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

/// Runs the whole file and returns the output CSV, or the first error (no
/// partial output).
pub fn run(config: &ReplayConfig, data: &Measurements) -> Result<String, ReplayError> {
    match config.numeric {
        Numeric::F64 => run_in::<f64>(&config.filter, data),
        Numeric::F32 => run_in::<f32>(&config.filter, data),
        Numeric::Fixed => run_in::<Fix>(&config.filter, data),
    }
}

/// [`run`] in representation `S`.
pub fn run_in<S: CsvValue>(
    filter: &FilterKind,
    data: &Measurements,
) -> Result<String, ReplayError> {
    let gains = filter.gains::<S>().map_err(ReplayError::Gains)?;
    match (filter, data.dims) {
        (FilterKind::AlphaBeta { .. }, 1) => run_cartesian::<S, 2, 1>(&gains, data),
        (FilterKind::AlphaBeta { .. }, 2) => run_cartesian::<S, 2, 2>(&gains, data),
        (FilterKind::AlphaBeta { .. }, _) => run_cartesian::<S, 2, 3>(&gains, data),
        (FilterKind::AlphaBetaGamma { .. }, 1) => run_cartesian::<S, 3, 1>(&gains, data),
        (FilterKind::AlphaBetaGamma { .. }, 2) => run_cartesian::<S, 3, 2>(&gains, data),
        (FilterKind::AlphaBetaGamma { .. }, _) => run_cartesian::<S, 3, 3>(&gains, data),
    }
}

/// The output header for `dims` axes.
pub fn header(order: usize, dims: usize) -> String {
    let mut h = String::from("t");
    for a in crate::csv_input::AXIS_NAMES.iter().take(dims) {
        let _ = write!(h, ",{a},v{a},res_{a}");
        if order == 3 {
            let _ = write!(h, ",a{a}");
        }
    }
    h
}

fn run_cartesian<S: CsvValue, const ORDER: usize, const D: usize>(
    gains: &Gains<S>,
    data: &Measurements,
) -> Result<String, ReplayError> {
    let mut out = header(ORDER, D);
    out.push('\n');
    let mut tracker = Cartesian::<S, ORDER, D>::new();
    let mut previous_t: Option<f64> = None;
    for row in &data.rows {
        let dt = match previous_t {
            None => S::ONE,
            Some(p) => S::try_from_f64(row.t - p).map_err(|error| ReplayError::Value {
                line: row.line,
                column: 1,
                name: "t",
                error,
            })?,
        };
        let mut z = [S::ZERO; D];
        for (i, zi) in z.iter_mut().enumerate() {
            *zi = S::try_from_f64(row.z[i]).map_err(|error| ReplayError::Value {
                line: row.line,
                column: i + 2,
                name: crate::csv_input::AXIS_NAMES[i],
                error,
            })?;
        }
        let outcomes = tracker
            .update(z, dt, gains)
            .map_err(|error| ReplayError::Filter {
                line: row.line,
                error,
            })?;
        previous_t = Some(row.t);

        out.push_str(&row.t_text);
        for (axis, outcome) in tracker.axes().iter().zip(outcomes.iter()) {
            out.push(',');
            axis.position().write_csv(&mut out);
            out.push(',');
            axis.velocity().write_csv(&mut out);
            out.push(',');
            if let UpdateOutcome::Filtered(innovation) = outcome {
                innovation.residual.write_csv(&mut out);
            }
            if ORDER == 3 {
                out.push(',');
                axis.acceleration().write_csv(&mut out);
            }
        }
        out.push('\n');
    }
    Ok(out)
}
