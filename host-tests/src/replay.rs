//! The runner behind the `replay` tool: the library's filters, in a chosen
//! representation, over recorded measurements ([`crate::csv_input`]), with the
//! output as CSV text.
//!
//! # Cartesian filters (`--filter ab|abg`)
//!
//! Output: a header, then one row per input row: `t` (echoed as written),
//! then for each axis `a` (`x`, `y`, `z`) the columns `a`, `va`, `res_a`, and
//! for αβγ also `aa`: the smoothed position and velocity after the update, the
//! residual z − x_p of the update (Al-Wagih eq. 4; empty on the two
//! initialisation rows, which have none, eqs. 9–10), and the smoothed
//! acceleration. Values are written in the representation's own shortest
//! exact form (`f32` values as `f32`, fixed point in decimal).
//!
//! The gains are fixed ([`FilterKind::AlphaBeta`],
//! [`FilterKind::AlphaBetaGamma`]: `--alpha/--beta/--gamma`, run by
//! [`Cartesian`] directly), scheduled ([`FilterKind::Scheduled`]: any
//! `--schedule` spec of [`abtrack::gain::spec::SCHEDULES`], run by
//! [`ScheduledFilter`] with [`AnySchedule`]), or the M5 bank
//! ([`FilterKind::Bank`], run by [`CartesianBank`]).
//!
//! The bank's output per axis is that of the member selected at the row
//! (Al-Wagih & Abdulla Algorithm 3 step 3, as [`abtrack::bank`] reads it):
//! the member whose prediction of this row's measurement had the least
//! |z − x_p| (ties to the lowest index). `a`, `va` are that member's smoothed
//! position and velocity after the update, `res_a` its innovation, and an
//! extra column `member_a` its index i (0-based; α_i evenly spaced from `min`
//! to `max`, β_i = α_i²/(2 − α_i)). On the two initialisation rows all
//! members hold the same state; `res_a` and `member_a` are empty.
//!
//! # Range–azimuth filter (`--filter range-azimuth`)
//!
//! He, Peng, Ling & Quan's filter ([`RangeAzimuthFilter`]) on `t,range,azimuth`
//! rows. Output: `t,x,vx,res_x,y,vy,res_y,range,azimuth`, then `alt,alt_rate`
//! when the input has an `alt` column, then
//! `tau,tau_mod,t_cpa,d_cpa,advisory,tau_mod_ra,ra_sense,ra_strength,clear_of_conflict`
//! with an own altitude. See
//! [`range_azimuth_header`] for each column's meaning.
//!
//! # Intervals
//!
//! The first row's interval is not used by the filters (two-point
//! initialisation takes the position only), so it is given as 1 s. Each later
//! interval is the time since the last report used, computed in `f64`,
//! rounded to whole microseconds ([`interval_s`]) and then
//! converted to the representation: decimal report times whose difference
//! is exactly 0.05 s or 20 s are then not put on either side of the
//! filters' range by binary rounding (0.15 − 0.1 is 0.04999999999999999 in
//! `f64`; below 2³² s, where an `f64` holds a microsecond); times less
//! than half a microsecond apart are a repeated time.
//!
//! Timing never stops a run: the filters' interval policy
//! ([`abtrack::filter::IntervalSpan`]) restarts the estimate at a report
//! more than 20 s after the last one used, and skips a report less than
//! 0.05 s after it (a repeated time, a duplicate report, and a time before
//! it, a report out of order, are skipped the same way), leaving the
//! estimate as it was; a two-point start that leaves the velocity envelope
//! starts again from its row ([`StartCheck`]). Every output has a last
//! column `event`: `restarted`, `skipped` or empty; the rows of both are
//! listed on stderr ([`TimingEvents`]). The range–azimuth filter gets the
//! same policy from the runner.
//!
//! Adding a filter kind: a variant of [`FilterKind`], its arm in [`run_in`]
//! (or its own runner, as range–azimuth), and its options in [`crate::cli`].

use std::fmt::{self, Write as _};
use std::io::Read;

use abtrack::bank::{BankConfig, BankOutcome, CartesianBank};
use abtrack::filter::altitude::{AltitudeQuantum, AltitudeTracker, AltitudeTrackerConfig};
use abtrack::filter::range_azimuth::{
    CovarianceFactor, NoiseError, RangeAzimuthFilter, RangeAzimuthNoise, RangeAzimuthOutcome,
    PAPER_BEARING_VARIANCE,
};
use abtrack::filter::{Cartesian, Gains, IntervalSpan, Phase, UpdateOutcome};
use abtrack::gain::auto::AutoConfig;
use abtrack::gain::spec::ScheduleSpec;
use abtrack::gain::{
    AnySchedule, ConfigError, FixedGains, GainSchedule, ScheduleError, ScheduledError,
    ScheduledFilter,
};
use abtrack::tcas::{
    assess, CollisionAvoidance, Intruder, OwnAircraft, ResolutionAdvisory, TcasError, ThreatState,
};
use abtrack::track::{ConfigError as TrackConfigError, ScanError};
use abtrack::{FilterError, Fix, GainError, NumError, Quantity, Scalar, ScaledScalar};

use abtrack::envelope::{self, Limit};

use crate::csv_input::{
    read_measurements, read_range_azimuth, AngleUnit, CsvError, InputFormat, Measurements,
    RangeAzimuthMeasurements, ReadOptions, Row, TimeOrder, AXIS_NAMES,
};

/// Capacity of the windows of `m3`, `m4`, `liu-residual` and `liu-adaptive`
/// (their `window` / `n` parameter).
pub const WINDOW_CAPACITY: usize = 64;
/// Capacity of the M5 bank (its `k` parameter).
pub const BANK_CAPACITY: usize = 64;

/// The schedule type `replay` runs.
pub type ReplaySchedule<S, const D: usize> = AnySchedule<S, D, WINDOW_CAPACITY>;
/// The bank type `replay` runs.
pub type ReplayBank<S, const D: usize> = CartesianBank<S, BANK_CAPACITY, D>;

/// αβ or αβγ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// αβ (ORDER 2).
    AlphaBeta,
    /// αβγ (ORDER 3).
    AlphaBetaGamma,
}

impl Order {
    /// The filter's ORDER: 2 or 3.
    pub const fn value(self) -> usize {
        match self {
            Order::AlphaBeta => 2,
            Order::AlphaBetaGamma => 3,
        }
    }

    /// The `--filter` name.
    pub const fn name(self) -> &'static str {
        match self {
            Order::AlphaBeta => "ab",
            Order::AlphaBetaGamma => "abg",
        }
    }
}

/// Settings of the range–azimuth run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RangeAzimuthOptions {
    /// σ_R, m (`--range-sigma`): the along-range measurement standard
    /// deviation, σ_R² in He et al. eq. (9) (reading 3 of
    /// [`abtrack::filter::range_azimuth`]).
    pub range_sigma_m: f64,
    /// σ_B², rad² (`--bearing-variance`): VAR = R²·σ_B² (eq. 10).
    pub bearing_variance_rad2: f64,
    /// Q, m²/s⁴ (`--process-noise`): the white acceleration's variance
    /// (eqs. 1, 7–8), the same along and across range.
    pub process_noise: f64,
    /// The `alt` column's quantum (`--alt-quantum`): sets the altitude
    /// tracker's gains ([`abtrack::filter::altitude`]).
    pub altitude_quantum: AltitudeQuantum,
    /// The own aircraft's pressure altitude, ft (`--own-alt`): enables the
    /// threat columns.
    pub own_altitude_ft: Option<f64>,
    /// The unit of the `azimuth` column (`--azimuth-unit`).
    pub azimuth_unit: AngleUnit,
}

impl RangeAzimuthOptions {
    /// He et al.'s range noise ("Navr = 100 m", §4).
    pub const DEFAULT_RANGE_SIGMA_M: f64 = 100.0;
    /// He et al.'s σ_B² (VAR = R²·7.569·10⁻³, about 5° RMS).
    pub const DEFAULT_BEARING_VARIANCE_RAD2: f64 = PAPER_BEARING_VARIANCE;
    /// The paper gives no Q; 1 m²/s⁴ (σ_a = 1 m/s², 0.1 g) lets the track
    /// follow gentle manoeuvres without giving up the smoothing.
    pub const DEFAULT_PROCESS_NOISE: f64 = 1.0;

    pub const DEFAULT: Self = RangeAzimuthOptions {
        range_sigma_m: Self::DEFAULT_RANGE_SIGMA_M,
        bearing_variance_rad2: Self::DEFAULT_BEARING_VARIANCE_RAD2,
        process_noise: Self::DEFAULT_PROCESS_NOISE,
        altitude_quantum: AltitudeQuantum::ModeC,
        own_altitude_ft: None,
        azimuth_unit: AngleUnit::Radians,
    };

    /// The measurement and process noise in representation `S`.
    pub fn noise<S: Scalar>(&self) -> Result<RangeAzimuthNoise<S>, NoiseError> {
        RangeAzimuthNoise::new_f64(
            self.range_sigma_m * self.range_sigma_m,
            self.bearing_variance_rad2,
            self.process_noise,
        )
    }
}

impl Default for RangeAzimuthOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Which filter to run, with its gains.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FilterKind {
    /// αβ with fixed gains, Al-Wagih & Abdulla eqs. (3)–(10)
    /// (`--alpha/--beta`).
    AlphaBeta { alpha: f64, beta: f64 },
    /// αβγ with fixed gains, Tenne & Singh eqs. (1)–(5), γ in their γ/(2T²)
    /// convention (`--alpha/--beta/--gamma`).
    AlphaBetaGamma { alpha: f64, beta: f64, gamma: f64 },
    /// αβ or αβγ driven by a gain schedule (`--schedule`; any spec but
    /// `bank`).
    Scheduled { order: Order, spec: ScheduleSpec },
    /// Al-Wagih & Abdulla's M5 bank of αβ filters (`--schedule bank`).
    Bank(BankConfig),
    /// He et al.'s range–azimuth projection filter.
    RangeAzimuth(RangeAzimuthOptions),
    /// `auto` (`--filter auto`) on `t,range,azimuth` rows, converted to
    /// x = R sin B, y = R cos B (a polar sensor's σ_R and σ_B in `config`);
    /// on `t,x,y` rows `--filter auto` is [`FilterKind::Scheduled`].
    AutoPolar {
        config: AutoConfig,
        azimuth_unit: AngleUnit,
    },
}

impl FilterKind {
    /// The fixed gains as `Gains<S>`, checked against the stability region;
    /// `None` for the kinds whose gains are not fixed.
    pub fn fixed_gains<S: Scalar>(&self) -> Option<Result<Gains<S>, GainError>> {
        match *self {
            FilterKind::AlphaBeta { alpha, beta } => Some(Gains::alpha_beta_f64(alpha, beta)),
            FilterKind::AlphaBetaGamma { alpha, beta, gamma } => {
                Some(Gains::alpha_beta_gamma_f64(alpha, beta, gamma))
            }
            _ => None,
        }
    }

    /// The input layout this filter reads.
    pub fn input_format(&self) -> InputFormat {
        match self {
            FilterKind::RangeAzimuth(_) | FilterKind::AutoPolar { .. } => InputFormat::RangeAzimuth,
            _ => InputFormat::Cartesian,
        }
    }
}

/// The number representation the filter runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Numeric {
    #[default]
    #[value(name = "f64")]
    F64,
    #[value(name = "f32")]
    F32,
    // The values' doc comments are `--help` text (clap): plain words, no
    // doc links.
    /// The Cortex-M3's fast fixed point as its firmware runs it
    /// (abtrack_firmware::number_types::cortex_m3): Fixed32 for the x/y
    /// track table, its wide format ScaledScalar for the code written for a
    /// Scalar (the range–azimuth filter and tracks, the altitude tracker,
    /// the TCAS columns). Not the single x/y filters.
    #[value(name = "fixed32")]
    Fixed32,
    /// Q32.32 (abtrack::Fix), which no firmware runs.
    #[value(name = "q32.32")]
    Q32,
}

impl Numeric {
    pub const NAMES: &'static str = "f64|f32|fixed32|q32.32";

    pub fn from_name(name: &str) -> Option<Numeric> {
        match name {
            "f64" => Some(Numeric::F64),
            "f32" => Some(Numeric::F32),
            "fixed32" => Some(Numeric::Fixed32),
            "q32.32" => Some(Numeric::Q32),
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
    /// The schedule or bank cannot be built in this representation.
    Schedule(ConfigError),
    /// The range–azimuth noise settings are not representable.
    Noise(NoiseError),
    /// The altitude tracker's gains cannot be built in this representation.
    AltitudeGains(abtrack::filter::altitude::AltitudeConfigError),
    /// The own altitude is not representable.
    OwnAltitude(NumError),
    /// A value of the file does not fit the representation.
    Value {
        line: usize,
        column: usize,
        name: &'static str,
        error: NumError,
    },
    /// The filter refused a row (e.g. fixed-point saturation).
    Filter { line: usize, error: FilterError },
    /// The schedule gave no gains for a row.
    ScheduledGains { line: usize, error: ScheduleError },
    /// The altitude tracker refused the row's `alt` (column 4).
    Altitude { line: usize, error: FilterError },
    /// The threat assessment failed (e.g. fixed-point saturation).
    Threat { line: usize, error: TcasError },
    /// The data are in the other layout (a caller error: the binary reads
    /// the layout the filter needs).
    WrongLayout { expected: InputFormat },
    /// `--tracker` on a Cartesian file with other than two axes (the table
    /// tracks in the x/y plane).
    TrackerAxes { dims: usize },
    /// `--tracker`: the configuration (`--confirm`, `--delete`, or the
    /// default design in this representation) was refused.
    TrackerConfig(TrackConfigError),
    /// `--tracker --schedule` on a `t,range,azimuth` file: the polar
    /// tracker is He et al.'s filter, which takes no schedule.
    TrackerScheduleNeedsCartesian,
    /// `--tracker`: a scan time beyond the table's u32 millisecond clock
    /// (more than 2³² − 1 ms after the first scan).
    ScanTime { line: usize, t: String },
    /// `--tracker`: the table refused the scan starting on `line` (e.g. two
    /// scan times that round to the same millisecond).
    Scan {
        line: usize,
        t: String,
        error: ScanError,
    },
    /// An estimate left the envelope (or is not finite) after the row on
    /// `line`: the run stops there rather than print it.
    Estimate {
        line: usize,
        name: &'static str,
        value: f64,
        limit: Limit,
        unit: &'static str,
    },
    /// `--tracker`: the sensor figures were refused.
    Design(String),
    /// `--numeric fixed32` with a single x/y filter (`--filter ab|abg`):
    /// the firmware's Fixed32 filters are not modelled by replay.
    Fixed32SingleFilter,
}

impl fmt::Display for ReplayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReplayError::Gains(e) => write!(f, "gains outside the stability region: {e}"),
            ReplayError::Schedule(e) => write!(f, "schedule: {e}"),
            ReplayError::Noise(e) => write!(f, "range-azimuth noise settings: {e}"),
            ReplayError::AltitudeGains(e) => write!(f, "altitude tracker gains: {e}"),
            ReplayError::OwnAltitude(e) => write!(f, "--own-alt: {e}"),
            ReplayError::Value {
                line,
                column,
                name,
                error,
            } => write!(f, "line {line}, column {column} ({name}): {error}"),
            ReplayError::Filter { line, error } => {
                write!(f, "line {line}: the filter refused the row: {error}")
            }
            ReplayError::ScheduledGains { line, error } => {
                write!(f, "line {line}: the schedule gave no gains: {error}")
            }
            ReplayError::Altitude { line, error } => write!(
                f,
                "line {line}, column 4 (alt): the altitude tracker refused the report: {error}"
            ),
            ReplayError::Threat { line, error } => {
                write!(f, "line {line}: threat assessment failed: {error}")
            }
            ReplayError::WrongLayout { expected } => write!(
                f,
                "this filter reads a file with the columns {}",
                expected.required().join(", ")
            ),
            ReplayError::TrackerAxes { dims } => write!(
                f,
                "line 1: --tracker reads t,x,y or t,range,azimuth[,alt]; this file has {dims} \
                 axis column(s) (the track table works in the x/y plane)"
            ),
            ReplayError::TrackerConfig(e) => write!(f, "tracker configuration refused: {e}"),
            ReplayError::TrackerScheduleNeedsCartesian => write!(
                f,
                "--schedule applies to t,x,y input only (the polar tracker is He et al.'s \
                 range-azimuth filter, which takes no schedule)"
            ),
            ReplayError::ScanTime { line, t } => write!(
                f,
                "line {line}, column 1 (t): time {t} is more than 2^32 - 1 ms (49.7 days) after \
                 the first scan, beyond the track table's u32 millisecond clock"
            ),
            ReplayError::Scan { line, t, error } => {
                write!(
                    f,
                    "line {line}: the track table refused the scan at t = {t}: {error}"
                )
            }
            ReplayError::Estimate {
                line,
                name,
                value,
                limit,
                unit,
            } => write!(
                f,
                "line {line}: after this row the estimate {name} = {value:.6e} {unit} is outside \
                 the envelope {} ..= {} {unit} (the filter diverged, or the data are outside \
                 what it is specified for); nothing is written",
                limit.min, limit.max
            ),
            ReplayError::Design(e) => write!(f, "tracker design: {e}"),
            ReplayError::Fixed32SingleFilter => write!(
                f,
                "--numeric fixed32 runs --tracker and --filter range-azimuth (as the Cortex-M3 \
                 firmware does), not the single x/y filters --filter ab|abg|auto"
            ),
        }
    }
}

impl std::error::Error for ReplayError {}

/// Why [`replay_reader`] produced no output: the input could not be read, or
/// the run stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    Input(CsvError),
    Replay(ReplayError),
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Input(e) => fmt::Display::fmt(e, f),
            Failure::Replay(e) => fmt::Display::fmt(e, f),
        }
    }
}

impl std::error::Error for Failure {}

/// What the timing policy did to one row (module docs, "Intervals").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowEvent {
    /// Used as usual.
    Used,
    /// More than 20 s after the last report used: the estimate restarted.
    Restarted,
    /// The start this row completed left the velocity envelope (beyond its
    /// allowance): the estimate started again from this row ([`StartCheck`]).
    RestartedStart,
    /// Less than 0.05 s after the last report used: skipped.
    Skipped,
    /// The same time as the last report used (to the microsecond): skipped.
    Duplicate,
    /// Before the last report used (out of order): skipped.
    Late,
}

impl RowEvent {
    /// The `event` column's text.
    pub const fn name(self) -> &'static str {
        match self {
            RowEvent::Used => "",
            RowEvent::Restarted | RowEvent::RestartedStart => "restarted",
            RowEvent::Skipped | RowEvent::Duplicate | RowEvent::Late => "skipped",
        }
    }

    fn of<N: abtrack::Numeric>(outcome: Option<&UpdateOutcome<N>>) -> Self {
        match outcome {
            Some(UpdateOutcome::Restarted) => RowEvent::Restarted,
            Some(UpdateOutcome::Skipped) => RowEvent::Skipped,
            _ => RowEvent::Used,
        }
    }

    /// Whether the row was used (its time is the next interval's start).
    fn used(self) -> bool {
        matches!(
            self,
            RowEvent::Used | RowEvent::Restarted | RowEvent::RestartedStart
        )
    }
}

/// The rows the timing policy did not use as usual, and the altitude
/// reports the altitude tracker did not take, by their `t` as written
/// (stderr, when any).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TimingEvents {
    /// Rows where the estimate restarted (a gap).
    pub restarted: Vec<String>,
    /// Rows where a start left the velocity envelope and the estimate
    /// started again ([`StartCheck`]).
    pub restarted_starts: Vec<String>,
    /// Rows skipped (duplicates included).
    pub skipped: Vec<String>,
    /// Of the skipped, rows repeating the last used report's time.
    pub duplicates: usize,
    /// Of the skipped, rows before the last used report's time (out of
    /// order).
    pub late: usize,
    /// Rows whose altitude report the altitude tracker found not credible
    /// (DO-185B; it coasted instead): the range–azimuth replay's.
    pub altitude_not_credible: Vec<String>,
    /// Data rows run (every row of the file, used or not).
    pub rows: usize,
}

impl TimingEvents {
    fn record(&mut self, event: RowEvent, t_text: &str) {
        self.rows += 1;
        match event {
            RowEvent::Used => {}
            RowEvent::Restarted => self.restarted.push(t_text.to_string()),
            RowEvent::RestartedStart => self.restarted_starts.push(t_text.to_string()),
            RowEvent::Skipped => self.skipped.push(t_text.to_string()),
            RowEvent::Duplicate => {
                self.skipped.push(t_text.to_string());
                self.duplicates += 1;
            }
            RowEvent::Late => {
                self.skipped.push(t_text.to_string());
                self.late += 1;
            }
        }
    }

    /// Of the skipped, rows less than [`abtrack::filter::MIN_INTERVAL_S`]
    /// after the last used report (neither at its time nor before it).
    pub fn too_close(&self) -> usize {
        self.skipped.len() - self.duplicates - self.late
    }

    /// No row restarted or skipped, and every altitude report taken.
    pub fn is_empty(&self) -> bool {
        self.restarted.is_empty()
            && self.restarted_starts.is_empty()
            && self.skipped.is_empty()
            && self.altitude_not_credible.is_empty()
    }
}

/// At most this many times are listed per event on stderr.
pub const LISTED_TIMES: usize = 8;

fn times_text(times: &[String]) -> String {
    let shown: Vec<&str> = times
        .iter()
        .take(LISTED_TIMES)
        .map(String::as_str)
        .collect();
    let more = if times.len() > LISTED_TIMES {
        ", …"
    } else {
        ""
    };
    format!("t = {}{more}", shown.join(", "))
}

impl fmt::Display for TimingEvents {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.rows == 0 {
            writeln!(f, "replay: no data rows (the input has its header only)")?;
        }
        if !self.restarted.is_empty() {
            writeln!(
                f,
                "replay: {} restarted: more than {} s after the last report used, the estimate \
                 started again there ({})",
                self.restarted.len(),
                abtrack::filter::MAX_INTERVAL_S,
                times_text(&self.restarted)
            )?;
        }
        if !self.restarted_starts.is_empty() {
            writeln!(
                f,
                "replay: {} restarted: the two-point start ending there left the velocity \
                 envelope (reports close together for their noise), the estimate started again \
                 there ({})",
                self.restarted_starts.len(),
                times_text(&self.restarted_starts)
            )?;
        }
        if !self.skipped.is_empty() {
            writeln!(
                f,
                "replay: {} skipped ({}): {} less than {} s after the last report used, {} at \
                 its time (duplicates), {} before it (out of order)",
                self.skipped.len(),
                times_text(&self.skipped),
                self.too_close(),
                abtrack::filter::MIN_INTERVAL_S,
                self.duplicates,
                self.late,
            )?;
            if 2 * self.skipped.len() > self.rows {
                writeln!(
                    f,
                    "replay: warning: {} of the {} rows were skipped, most of the file{}",
                    self.skipped.len(),
                    self.rows,
                    if self.late > 0 {
                        " (rows out of time order are skipped: sort the file by t)"
                    } else {
                        ""
                    }
                )?;
            }
        }
        if !self.altitude_not_credible.is_empty() {
            writeln!(
                f,
                "replay: {} altitude reports not credible (DO-185B): the altitude coasted there \
                 ({})",
                self.altitude_not_credible.len(),
                times_text(&self.altitude_not_credible)
            )?;
        }
        Ok(())
    }
}

/// A run's output CSV and its timing events.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Replayed {
    pub csv: String,
    pub events: TimingEvents,
}

/// A [`Scalar`] that can be written to the output CSV.
pub trait CsvValue: Scalar + std::fmt::Display {
    fn write_csv(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

impl<S: Scalar + std::fmt::Display> CsvValue for S {}

/// Any finite value (estimates with no envelope of their own).
pub const FINITE: Limit = Limit::symmetric(f64::MAX);

/// `Err` unless the estimate `value` (a quantity of the representation) is
/// inside `limit`.
pub(crate) fn check_estimate<Q: Quantity>(
    line: usize,
    name: &'static str,
    value: Q,
    limit: Limit,
    unit: &'static str,
) -> Result<(), ReplayError> {
    let v = value.to_f64();
    if value.is_valid() && limit.contains(v) {
        Ok(())
    } else {
        Err(ReplayError::Estimate {
            line,
            name,
            value: v,
            limit,
            unit,
        })
    }
}

/// Position, velocity (and acceleration) estimates of the `D` axes of a
/// Cartesian filter after the row on `line`.
fn check_kinematics<S: Scalar>(
    line: usize,
    axes: impl IntoIterator<Item = (S, S, Option<S>)>,
) -> Result<(), ReplayError> {
    check_kinematics_within(line, axes, [0.0; 3])
}

/// Estimates an envelope check does not refuse for their own uncertainty:
/// a velocity beyond [`envelope::VELOCITY_M_PER_S`] by at most this many
/// of its σ (a start over a short, jittered interval, whose velocity the
/// filter knows to be that uncertain) is not a diverged filter.
pub const VELOCITY_SIGMAS_ALLOWED: f64 = 3.0;

/// [`check_kinematics`], each axis's velocity envelope widened by
/// `velocity_allowance` (m/s).
fn check_kinematics_within<S: Scalar>(
    line: usize,
    axes: impl IntoIterator<Item = (S, S, Option<S>)>,
    velocity_allowance: [f64; 3],
) -> Result<(), ReplayError> {
    const VELOCITY: [&str; 3] = ["vx", "vy", "vz"];
    const ACCELERATION: [&str; 3] = ["ax", "ay", "az"];
    for ((((x, v, a), names), (vn, an)), allowance) in axes
        .into_iter()
        .zip(AXIS_NAMES)
        .zip(VELOCITY.into_iter().zip(ACCELERATION))
        .zip(velocity_allowance)
    {
        let velocity_limit = Limit::symmetric(envelope::VELOCITY_M_PER_S.max + allowance);
        check_estimate(line, names, x, envelope::POSITION_M, "m")?;
        check_estimate(line, vn, v, velocity_limit, "m/s")?;
        if let Some(a) = a {
            check_estimate(line, an, a, envelope::ACCELERATION_M_PER_S2, "m/s²")?;
        }
    }
    Ok(())
}

/// The envelope check of a start: a two-point velocity is the difference of
/// two noisy reports over their interval, and jitter can bring two reports
/// close enough for it to leave the velocity envelope (beyond the filter's
/// own allowance). Such a start drops the estimate and starts again from
/// its row, once: if the start that follows leaves the envelope too, the
/// reports keep implying a speed beyond it (data that fast, or an outlier
/// row) and the run stops there.
#[derive(Debug, Default)]
struct StartCheck {
    /// The estimate began at a start that left the envelope (a gap's
    /// restart begins a new one).
    restarted: bool,
}

impl StartCheck {
    /// `check`, the envelope check after a row with `event`, at a row
    /// completing a two-point start (`start`) or not: `Ok(true)` when the
    /// estimate is to start again from this row, the check's error when it
    /// stops the run.
    fn restart(
        &mut self,
        check: Result<(), ReplayError>,
        start: bool,
        event: RowEvent,
    ) -> Result<bool, ReplayError> {
        if event == RowEvent::Restarted {
            self.restarted = false;
        }
        match check {
            Err(ReplayError::Estimate { unit: "m/s", .. }) if start && !self.restarted => {
                self.restarted = true;
                Ok(true)
            }
            other => other.map(|()| false),
        }
    }
}

/// `,value`.
pub(crate) fn cell<S: CsvValue>(out: &mut String, v: S) {
    out.push(',');
    v.write_csv(out);
}

/// `,value` or `,` (an undefined value is an empty cell).
fn optional_cell<S: CsvValue>(out: &mut String, v: Option<S>) {
    out.push(',');
    if let Some(v) = v {
        v.write_csv(out);
    }
}

/// Reads the layout `config`'s filter needs from `input` and runs it: the
/// whole output CSV, or the first error (no partial output).
pub fn replay_reader<R: Read>(config: &ReplayConfig, input: R) -> Result<String, Failure> {
    replay_events(config, input).map(|r| r.csv)
}

/// [`replay_reader`] with the run's timing events.
pub fn replay_events<R: Read>(config: &ReplayConfig, input: R) -> Result<Replayed, Failure> {
    match config.filter {
        FilterKind::RangeAzimuth(options) => {
            let read = ReadOptions {
                times: TimeOrder::Increasing,
                azimuth_unit: options.azimuth_unit,
            };
            let data = read_range_azimuth(input, read).map_err(Failure::Input)?;
            replay_range_azimuth(&options, config.numeric, &data).map_err(Failure::Replay)
        }
        FilterKind::AutoPolar {
            config: auto,
            azimuth_unit,
        } => {
            let read = ReadOptions {
                times: TimeOrder::Increasing,
                azimuth_unit,
            };
            let data = read_range_azimuth(input, read).map_err(Failure::Input)?;
            let converted = Measurements {
                dims: 2,
                rows: data
                    .rows
                    .iter()
                    .map(|r| {
                        let (s, c) = r.azimuth.sin_cos();
                        Row {
                            line: r.line,
                            t_text: r.t_text.clone(),
                            t: r.t,
                            z: [r.range * s, r.range * c, 0.0],
                            alt: r.alt,
                        }
                    })
                    .collect(),
            };
            let filter = FilterKind::Scheduled {
                order: Order::AlphaBeta,
                spec: ScheduleSpec::Auto(auto),
            };
            let config = ReplayConfig {
                filter,
                numeric: config.numeric,
            };
            replay(&config, &converted).map_err(Failure::Replay)
        }
        _ => {
            let data = read_measurements(input, ReadOptions::default()).map_err(Failure::Input)?;
            replay(config, &data).map_err(Failure::Replay)
        }
    }
}

/// Runs a Cartesian file and returns the output CSV, or the first error (no
/// partial output).
pub fn run(config: &ReplayConfig, data: &Measurements) -> Result<String, ReplayError> {
    replay(config, data).map(|r| r.csv)
}

/// [`run`] with the timing events.
pub fn replay(config: &ReplayConfig, data: &Measurements) -> Result<Replayed, ReplayError> {
    match config.numeric {
        Numeric::F64 => replay_in::<f64>(&config.filter, data),
        Numeric::F32 => replay_in::<f32>(&config.filter, data),
        Numeric::Q32 => replay_in::<Fix>(&config.filter, data),
        Numeric::Fixed32 => Err(ReplayError::Fixed32SingleFilter),
    }
}

/// [`run`] in representation `S`.
pub fn run_in<S: CsvValue>(
    filter: &FilterKind,
    data: &Measurements,
) -> Result<String, ReplayError> {
    replay_in::<S>(filter, data).map(|r| r.csv)
}

/// [`replay`] in representation `S`.
pub fn replay_in<S: CsvValue>(
    filter: &FilterKind,
    data: &Measurements,
) -> Result<Replayed, ReplayError> {
    match filter {
        FilterKind::AlphaBeta { .. } | FilterKind::AlphaBetaGamma { .. } => {
            let gains = filter
                .fixed_gains::<S>()
                .unwrap_or(Err(GainError::NotFinite))
                .map_err(ReplayError::Gains)?;
            let order = if matches!(filter, FilterKind::AlphaBeta { .. }) {
                Order::AlphaBeta
            } else {
                Order::AlphaBetaGamma
            };
            match (order, data.dims) {
                (Order::AlphaBeta, 1) => run_cartesian::<S, 2, 1>(&gains, data),
                (Order::AlphaBeta, 2) => run_cartesian::<S, 2, 2>(&gains, data),
                (Order::AlphaBeta, _) => run_cartesian::<S, 2, 3>(&gains, data),
                (Order::AlphaBetaGamma, 1) => run_cartesian::<S, 3, 1>(&gains, data),
                (Order::AlphaBetaGamma, 2) => run_cartesian::<S, 3, 2>(&gains, data),
                (Order::AlphaBetaGamma, _) => run_cartesian::<S, 3, 3>(&gains, data),
            }
        }
        FilterKind::Scheduled { order, spec } => match (order, data.dims) {
            (Order::AlphaBeta, 1) => run_scheduled::<S, 2, 1>(spec, data),
            (Order::AlphaBeta, 2) => run_scheduled::<S, 2, 2>(spec, data),
            (Order::AlphaBeta, _) => run_scheduled::<S, 2, 3>(spec, data),
            (Order::AlphaBetaGamma, 1) => run_scheduled::<S, 3, 1>(spec, data),
            (Order::AlphaBetaGamma, 2) => run_scheduled::<S, 3, 2>(spec, data),
            (Order::AlphaBetaGamma, _) => run_scheduled::<S, 3, 3>(spec, data),
        },
        FilterKind::Bank(config) => match data.dims {
            1 => run_bank::<S, 1>(config, data),
            2 => run_bank::<S, 2>(config, data),
            _ => run_bank::<S, 3>(config, data),
        },
        FilterKind::RangeAzimuth(_) | FilterKind::AutoPolar { .. } => {
            Err(ReplayError::WrongLayout {
                expected: InputFormat::RangeAzimuth,
            })
        }
    }
}

/// The output header of a Cartesian filter of `order` (2 or 3) on `dims`
/// axes.
pub fn header(order: usize, dims: usize) -> String {
    let mut h = String::from("t");
    for a in AXIS_NAMES.iter().take(dims) {
        let _ = write!(h, ",{a},v{a},res_{a}");
        if order == 3 {
            let _ = write!(h, ",a{a}");
        }
    }
    h.push_str(",event");
    h
}

/// The output header of the M5 bank on `dims` axes.
pub fn bank_header(dims: usize) -> String {
    let mut h = String::from("t");
    for a in AXIS_NAMES.iter().take(dims) {
        let _ = write!(h, ",{a},v{a},res_{a},member_{a}");
    }
    h.push_str(",event");
    h
}

/// Report times are read to the microsecond (module docs, "Intervals").
const MICROSECONDS_PER_SECOND: f64 = 1e6;

/// `t − previous`, s, rounded to the microsecond (module docs,
/// "Intervals"). Both factors are exact, so a whole number of microseconds
/// over 10⁶ is the `f64` nearest the decimal interval: 0.15 − 0.1 gives the
/// literal 0.05.
pub fn interval_s(previous: f64, t: f64) -> f64 {
    ((t - previous) * MICROSECONDS_PER_SECOND).round() / MICROSECONDS_PER_SECOND
}

/// The interval since the last report used (1 s for the first row, see the
/// module docs) in `S` ([`interval_s`]); `Err` with the row's event for a
/// repeated time (a duplicate report, or one less than half a microsecond
/// before or after) or an earlier one (late), both skipped.
fn interval<S: Scalar>(
    previous_t: Option<f64>,
    t: f64,
    line: usize,
) -> Result<Result<S, RowEvent>, ReplayError> {
    let Some(p) = previous_t else {
        return Ok(Ok(S::ONE));
    };
    let dt = interval_s(p, t);
    if dt == 0.0 {
        return Ok(Err(RowEvent::Duplicate));
    }
    if dt < 0.0 {
        return Ok(Err(RowEvent::Late));
    }
    S::try_from_f64(dt)
        .map(Ok)
        .map_err(|error| ReplayError::Value {
            line,
            column: 1,
            name: "t",
            error,
        })
}

/// A value of the file in `S`, or an error naming where it is.
pub(crate) fn value<Q: Quantity>(
    v: f64,
    line: usize,
    column: usize,
    name: &'static str,
) -> Result<Q, ReplayError> {
    Q::try_from_f64(v).map_err(|error| ReplayError::Value {
        line,
        column,
        name,
        error,
    })
}

/// The row's positions in `S`.
fn positions<S: Scalar, const D: usize>(row: &Row) -> Result<[S; D], ReplayError> {
    let mut z = [S::ZERO; D];
    for (i, (zi, name)) in z.iter_mut().zip(AXIS_NAMES).enumerate() {
        *zi = value(row.z[i], row.line, i + 2, name)?;
    }
    Ok(z)
}

/// Per axis: position, velocity, residual (empty before filtering) and, for
/// αβγ, acceleration.
fn write_kinematic_row<S: CsvValue, const ORDER: usize, const D: usize>(
    out: &mut String,
    t_text: &str,
    filter: &Cartesian<S, ORDER, D>,
    outcomes: &[UpdateOutcome<S>; D],
    event: RowEvent,
) {
    out.push_str(t_text);
    for (axis, outcome) in filter.axes().iter().zip(outcomes) {
        cell(out, axis.position());
        cell(out, axis.velocity());
        optional_cell(
            out,
            match outcome {
                UpdateOutcome::Filtered(innovation) => Some(innovation.residual),
                _ => None,
            },
        );
        if ORDER == 3 {
            cell(out, axis.acceleration());
        }
    }
    out.push(',');
    out.push_str(event.name());
    out.push('\n');
}

/// [`check_kinematics`] of a Cartesian filter.
fn check_filter<S: Scalar, const ORDER: usize, const D: usize>(
    line: usize,
    filter: &Cartesian<S, ORDER, D>,
    velocity_allowance: [f64; 3],
) -> Result<(), ReplayError> {
    check_kinematics_within(
        line,
        filter.axes().iter().map(|a| {
            (
                a.position(),
                a.velocity(),
                (ORDER == 3).then(|| a.acceleration()),
            )
        }),
        velocity_allowance,
    )
}

/// Fixed gains, run by [`ScheduledFilter`] so that real timing gets the
/// same bounds as every schedule ([`abtrack::gain::robust_gains`]).
fn run_cartesian<S: CsvValue, const ORDER: usize, const D: usize>(
    gains: &Gains<S>,
    data: &Measurements,
) -> Result<Replayed, ReplayError> {
    run_schedule::<S, _, ORDER, D>(FixedGains::new(*gains), data, |_| [0.0; 3])
}

fn run_scheduled<S: CsvValue, const ORDER: usize, const D: usize>(
    spec: &ScheduleSpec,
    data: &Measurements,
) -> Result<Replayed, ReplayError> {
    let schedule = ReplaySchedule::<S, D>::from_spec(spec).map_err(ReplayError::Schedule)?;
    let sigma = match spec {
        // The covariance is normalised by σ, or by σ_R for a polar sensor.
        ScheduleSpec::Auto(c) => c.sigma.or(c.range_sigma),
        _ => None,
    };
    run_schedule::<S, _, ORDER, D>(schedule, data, |s| velocity_allowance(s, sigma))
}

/// `auto`'s allowance on each axis's velocity envelope:
/// [`VELOCITY_SIGMAS_ALLOWED`] of the velocity's σ, σ·√(P_vv/σ²) from the
/// schedule's normalised covariance (σ the reference it is normalised by;
/// none for the other schedules, which carry no covariance).
fn velocity_allowance<S: Scalar, const D: usize>(
    schedule: &ReplaySchedule<S, D>,
    sigma: Option<f64>,
) -> [f64; 3] {
    let mut out = [0.0; 3];
    if let (ReplaySchedule::Auto(auto), Some(sigma)) = (schedule, sigma) {
        for (o, axis) in out.iter_mut().zip(auto.axes()) {
            let variance_ratio = axis.velocity.to_f64();
            if variance_ratio.is_finite() && variance_ratio > 0.0 {
                *o = VELOCITY_SIGMAS_ALLOWED * sigma * variance_ratio.sqrt();
            }
        }
    }
    out
}

/// The range–azimuth filter's allowance on each axis's velocity envelope:
/// [`VELOCITY_SIGMAS_ALLOWED`] of the larger of its along- and cross-range
/// velocity σ (√(L₂₁² + L₂₂²) of each covariance factor), which bounds
/// either Cartesian axis's.
fn range_azimuth_velocity_allowance<S: Scalar>(filter: &RangeAzimuthFilter<S>) -> f64 {
    let sigma = |f: CovarianceFactor<S>| f.b.to_f64().hypot(f.c.to_f64());
    let larger = sigma(filter.range_covariance()).max(sigma(filter.cross_range_covariance()));
    if larger.is_finite() {
        VELOCITY_SIGMAS_ALLOWED * larger
    } else {
        0.0
    }
}

fn run_schedule<S: CsvValue, G: GainSchedule<S, D>, const ORDER: usize, const D: usize>(
    schedule: G,
    data: &Measurements,
    velocity_allowance: impl Fn(&G) -> [f64; 3],
) -> Result<Replayed, ReplayError> {
    let mut track = ScheduledFilter::<S, _, ORDER, D>::new(schedule);
    let mut out = header(ORDER, D);
    out.push('\n');
    let mut events = TimingEvents::default();
    let mut previous_t: Option<f64> = None;
    let mut starts = StartCheck::default();
    for row in &data.rows {
        let dt = match interval::<S>(previous_t, row.t, row.line)? {
            Ok(dt) => dt,
            Err(event) => {
                events.record(event, &row.t_text);
                let skipped = [UpdateOutcome::Skipped; D];
                write_kinematic_row(&mut out, &row.t_text, track.filter(), &skipped, event);
                continue;
            }
        };
        let z = positions::<S, D>(row)?;
        let refused = |e| match e {
            ScheduledError::Filter(error) => ReplayError::Filter {
                line: row.line,
                error,
            },
            ScheduledError::Schedule(error) => ReplayError::ScheduledGains {
                line: row.line,
                error,
            },
        };
        let mut outcome = track.update(z, dt).map_err(refused)?.outcome;
        let mut event = RowEvent::of(outcome.first());
        let check = check_filter(
            row.line,
            track.filter(),
            velocity_allowance(track.schedule()),
        );
        let start = matches!(outcome.first(), Some(UpdateOutcome::SecondPoint));
        if starts.restart(check, start, event)? {
            track = ScheduledFilter::new(schedule);
            outcome = track.update(z, dt).map_err(refused)?.outcome;
            event = RowEvent::RestartedStart;
        }
        if event.used() {
            previous_t = Some(row.t);
        }
        events.record(event, &row.t_text);
        write_kinematic_row(&mut out, &row.t_text, track.filter(), &outcome, event);
    }
    Ok(Replayed { csv: out, events })
}

fn run_bank<S: CsvValue, const D: usize>(
    config: &BankConfig,
    data: &Measurements,
) -> Result<Replayed, ReplayError> {
    let fresh = ReplayBank::<S, D>::from_config(config).map_err(ReplayError::Schedule)?;
    let mut bank = fresh;
    let mut out = bank_header(D);
    out.push('\n');
    let mut events = TimingEvents::default();
    let mut previous_t: Option<f64> = None;
    let mut starts = StartCheck::default();
    for row in &data.rows {
        let refused = |error| ReplayError::Filter {
            line: row.line,
            error,
        };
        let (mut outcomes, mut event, z_dt) = match interval::<S>(previous_t, row.t, row.line)? {
            Err(event) => ([BankOutcome::Skipped; D], event, None),
            Ok(dt) => {
                let z = positions::<S, D>(row)?;
                let outcomes = bank.update(z, dt).map_err(refused)?;
                let event = match outcomes.first() {
                    Some(BankOutcome::Restarted) => RowEvent::Restarted,
                    Some(BankOutcome::Skipped) => RowEvent::Skipped,
                    _ => RowEvent::Used,
                };
                (outcomes, event, Some((z, dt)))
            }
        };
        let check = check_kinematics(
            row.line,
            bank.axes()
                .iter()
                .map(|a| (a.position(), a.velocity(), None)),
        );
        let start = matches!(outcomes.first(), Some(BankOutcome::SecondPoint));
        if let (true, Some((z, dt))) = (starts.restart(check, start, event)?, z_dt) {
            bank = fresh;
            outcomes = bank.update(z, dt).map_err(refused)?;
            event = RowEvent::RestartedStart;
        }
        if event.used() {
            previous_t = Some(row.t);
        }
        events.record(event, &row.t_text);
        out.push_str(&row.t_text);
        for (axis, outcome) in bank.axes().iter().zip(&outcomes) {
            cell(&mut out, axis.position());
            cell(&mut out, axis.velocity());
            match outcome {
                BankOutcome::Filtered(selection) => {
                    cell(&mut out, selection.residual);
                    let _ = write!(out, ",{}", selection.member);
                }
                _ => out.push_str(",,"),
            }
        }
        out.push(',');
        out.push_str(event.name());
        out.push('\n');
    }
    Ok(Replayed { csv: out, events })
}

/// The range–azimuth filter's position and velocity against the envelope,
/// its velocity's allowance included.
fn check_range_azimuth<S: Scalar>(
    line: usize,
    filter: &RangeAzimuthFilter<S>,
) -> Result<(), ReplayError> {
    let (position, velocity) = (filter.position(), filter.velocity());
    let allowance = range_azimuth_velocity_allowance(filter);
    check_kinematics_within(
        line,
        [
            (position[0], velocity[0], None),
            (position[1], velocity[1], None),
        ],
        [allowance, allowance, 0.0],
    )
}

/// The output header of the range–azimuth filter: with `has_alt` (the input
/// has an `alt` column) and `threat` (an own altitude was given).
///
/// * `x,vx,res_x,y,vy,res_y`: the estimated relative position (m) and
///   velocity (m/s) in the sensor's x/y frame (x = R sin B, y = R cos B), and
///   the residual of the update on each axis, z − x_p with the measurement
///   converted as z = (R sin B, R cos B) and x_p the filter's prediction:
///   the vector He et al.'s range and cross-range residuals (eq. 11) are the
///   components of, RESID_R·(sin B, cos B) − RESID_CR·(cos B, −sin B).
///   Empty on the two initialisation rows.
/// * `range` (m), `azimuth` (rad in [0, 2π)): the estimate re-synthesised as
///   range and azimuth.
/// * `alt` (ft), `alt_rate` (ft/s): the altitude tracker's estimate of the
///   intruder; empty while it is not reporting (no report yet, or none for
///   more than 6 s).
/// * `tau` (range tau, s), `tau_mod` (modified tau with the TA DMOD, s),
///   `t_cpa` (s from now), `d_cpa` (m), `advisory` (none, proximate, ta,
///   ra), `tau_mod_ra` (modified tau with the RA DMOD, s) from
///   [`abtrack::tcas::assess`]. Empty where undefined: `tau` when the
///   intruder is diverging (ṙ > 10 ft/s, DO-185B `RDTHR`), `tau_mod` and
///   `tau_mod_ra` when it is diverging outside the DMOD, `tau_mod_ra` at SL 2 (no RAs), `t_cpa`/`d_cpa` when the time is
///   beyond the representation, and every threat column on the first row
///   (no velocity yet).
/// * `ra_sense` (up, down), `ra_strength` (preventive, level-off,
///   positive, increase), `clear_of_conflict` (1 on the row the RA ends):
///   the RA in force after this row, from the logic with memory
///   ([`abtrack::tcas::ThreatState::assess_intruder`] and
///   [`abtrack::tcas::CollisionAvoidance::resolve`]: TA hysteresis, the
///   continuing threat, strengthening, weakening, sense reversal). A sense
///   reversal shows as a change of `ra_sense` within one RA. A row not
///   used (skipped) repeats the RA in force. `advisory` stays the
///   stateless assessment of the row.
pub fn range_azimuth_header(has_alt: bool, threat: bool) -> String {
    let mut h = String::from("t,x,vx,res_x,y,vy,res_y,range,azimuth");
    if has_alt {
        h.push_str(",alt,alt_rate");
    }
    if threat {
        h.push(',');
        h.push_str(THREAT_COLUMNS);
        h.push(',');
        h.push_str(RA_COLUMNS);
    }
    h.push_str(",event");
    h
}

/// The RA columns of `--filter range-azimuth --own-alt`; see
/// [`range_azimuth_header`].
pub const RA_COLUMNS: &str = "ra_sense,ra_strength,clear_of_conflict";

/// The collision-avoidance logic with memory behind [`RA_COLUMNS`]: the
/// system's state and the one intruder's threat state.
#[derive(Debug, Clone, Copy)]
struct RaMemory<S: Scalar> {
    cas: CollisionAvoidance<S>,
    threat: ThreatState<S>,
    in_force: Option<ResolutionAdvisory<S>>,
}

impl<S: CsvValue> RaMemory<S> {
    fn new() -> Self {
        RaMemory {
            cas: CollisionAvoidance::new(),
            threat: ThreatState::new(),
            in_force: None,
        }
    }

    /// One used row `dt` s after the previous: the cells of
    /// [`RA_COLUMNS`], each preceded by a comma. Without an intruder state
    /// (no velocity yet) the intruder is not a threat.
    fn update(
        &mut self,
        out: &mut String,
        own: &OwnAircraft<S>,
        intruder: Option<&Intruder<S>>,
        dt: S,
        line: usize,
    ) -> Result<(), ReplayError> {
        let threat_error = |error| ReplayError::Threat { line, error };
        let cycle = self.cas.begin_cycle(own, false).map_err(threat_error)?;
        let geometry = match intruder {
            Some(i) => {
                self.threat
                    .assess_intruder(&cycle, i, dt)
                    .map_err(threat_error)?
                    .geometry
            }
            None => None,
        };
        let threats: Vec<_> = geometry.into_iter().collect();
        let output = self
            .cas
            .resolve(&cycle, &threats, dt)
            .map_err(threat_error)?;
        self.in_force = output.advisory;
        self.write(out, output.clear_of_conflict);
        Ok(())
    }

    /// The RA in force, each cell preceded by a comma.
    fn write(&self, out: &mut String, clear_of_conflict: bool) {
        out.push(',');
        if let Some(ra) = self.in_force {
            out.push_str(ra.sense.name());
            out.push(',');
            out.push_str(ra.strength.name());
        } else {
            out.push(',');
        }
        out.push(',');
        if clear_of_conflict {
            out.push('1');
        }
    }
}

/// The threat columns (`--own-alt`), shared by `--filter range-azimuth` and
/// `--tracker`; see [`range_azimuth_header`] for their meaning.
pub const THREAT_COLUMNS: &str = "tau,tau_mod,t_cpa,d_cpa,advisory,tau_mod_ra";

/// The own aircraft of `--own-alt` in `S`: at the origin, level at `feet`
/// over terrain at sea level (see [`run_range_azimuth_in`]); `None` without
/// an own altitude.
pub(crate) fn own_aircraft<S: Scalar>(
    feet: Option<f64>,
) -> Result<Option<OwnAircraft<S>>, ReplayError> {
    match feet {
        None => Ok(None),
        Some(feet) => {
            let feet = S::try_from_f64(feet).map_err(ReplayError::OwnAltitude)?;
            Ok(Some(OwnAircraft::over_sea_level(feet, S::ZERO)))
        }
    }
}

/// The cells of [`THREAT_COLUMNS`] for `intruder` seen from `own`
/// ([`abtrack::tcas::assess`]), each preceded by a comma; all empty when
/// there is no intruder state yet (no velocity). `line` names the input line
/// in an error.
pub(crate) fn write_threat_cells<S: CsvValue>(
    out: &mut String,
    own: &OwnAircraft<S>,
    intruder: Option<&Intruder<S>>,
    line: usize,
) -> Result<(), ReplayError> {
    let Some(intruder) = intruder else {
        out.push_str(",,,,,,");
        return Ok(());
    };
    let a = assess(own, intruder).map_err(|error| ReplayError::Threat { line, error })?;
    optional_cell(out, a.range_tau_s);
    optional_cell(out, a.ta_modified_tau_s);
    optional_cell(out, a.closest_approach.map(|c| c.time_s));
    optional_cell(out, a.closest_approach.map(|c| c.distance_m));
    out.push(',');
    out.push_str(a.advisory.name());
    optional_cell(out, a.ra_modified_tau_s);
    Ok(())
}

/// Runs a range–azimuth file and returns the output CSV, or the first error
/// (no partial output).
pub fn run_range_azimuth(
    options: &RangeAzimuthOptions,
    numeric: Numeric,
    data: &RangeAzimuthMeasurements,
) -> Result<String, ReplayError> {
    replay_range_azimuth(options, numeric, data).map(|r| r.csv)
}

/// [`run_range_azimuth`] with the timing events.
pub fn replay_range_azimuth(
    options: &RangeAzimuthOptions,
    numeric: Numeric,
    data: &RangeAzimuthMeasurements,
) -> Result<Replayed, ReplayError> {
    match numeric {
        Numeric::F64 => replay_range_azimuth_in::<f64>(options, data),
        Numeric::F32 => replay_range_azimuth_in::<f32>(options, data),
        Numeric::Q32 => replay_range_azimuth_in::<Fix>(options, data),
        Numeric::Fixed32 => replay_range_azimuth_in::<ScaledScalar>(options, data),
    }
}

/// [`run_range_azimuth`] in representation `S`.
///
/// The own aircraft (`--own-alt`) is at the origin of the x/y frame, level
/// at the given pressure altitude, over terrain at sea level (so its radio
/// altitude is the same number, which selects SL 2 and 3 below 2350 ft). The
/// filter's state is the intruder *relative* to it, so the own velocity is
/// implicitly zero: the range rate, taus and CPA are those of the relative
/// motion. Without an `alt` column, or while the altitude tracker has no
/// altitude, the intruder counts as not reporting altitude: at most a
/// traffic advisory (TCAS never issues RAs against such intruders).
pub fn run_range_azimuth_in<S: CsvValue>(
    options: &RangeAzimuthOptions,
    data: &RangeAzimuthMeasurements,
) -> Result<String, ReplayError> {
    replay_range_azimuth_in::<S>(options, data).map(|r| r.csv)
}

/// [`run_range_azimuth_in`] with the timing events. He et al.'s filter
/// takes the filters' interval policy from here ([`IntervalSpan`] on the
/// time since the last report used): a new filter after a longer interval,
/// the row skipped after a shorter one.
pub fn replay_range_azimuth_in<S: CsvValue>(
    options: &RangeAzimuthOptions,
    data: &RangeAzimuthMeasurements,
) -> Result<Replayed, ReplayError> {
    let noise = options.noise::<S>().map_err(ReplayError::Noise)?;
    // A new estimate and, with it, no RA in force.
    let fresh = || (RangeAzimuthFilter::new(noise), RaMemory::<S>::new());
    let (mut filter, mut ra_memory) = fresh();
    let altitude_config = AltitudeTrackerConfig::<S>::default_for(options.altitude_quantum)
        .map_err(ReplayError::AltitudeGains)?;
    let mut altitude = AltitudeTracker::<S>::new(altitude_config);
    let own = own_aircraft::<S>(options.own_altitude_ft)?;
    let mut out = range_azimuth_header(data.has_alt, own.is_some());
    out.push('\n');
    let mut events = TimingEvents::default();
    let mut previous_t: Option<f64> = None;
    let mut starts = StartCheck::default();
    for row in &data.rows {
        let line = row.line;
        let refused = |error| ReplayError::Filter { line, error };
        let range: S = value(row.range, line, 2, "range")?;
        let azimuth: S = value(row.azimuth, line, 3, "azimuth")?;
        let report = match row.alt {
            Some(a) => Some(value::<S>(a, line, 4, "alt")?),
            None => None,
        };
        let interval = interval::<S>(previous_t, row.t, line)?;
        let mut event = match (interval, previous_t) {
            (Err(event), _) => event,
            (Ok(_), None) => RowEvent::Used,
            (Ok(_), Some(p)) => match IntervalSpan::of(interval_s(p, row.t)) {
                Ok(IntervalSpan::TooShort) => RowEvent::Skipped,
                Ok(IntervalSpan::TooLong) if filter.phase() != Phase::Empty => RowEvent::Restarted,
                _ => RowEvent::Used,
            },
        };
        let mut outcome = RangeAzimuthOutcome::FirstPoint;
        let mut used_dt = None;
        if let (true, Ok(dt)) = (event.used(), interval) {
            used_dt = Some(dt);
            if event == RowEvent::Restarted {
                (filter, ra_memory) = fresh();
            }
            outcome = filter.update(range, azimuth, dt).map_err(refused)?;
            if data.has_alt {
                let incredible = altitude.incredible_reports();
                altitude
                    .scan(report, dt)
                    .map_err(|error| ReplayError::Altitude { line, error })?;
                if altitude.incredible_reports() > incredible {
                    events.altitude_not_credible.push(row.t_text.clone());
                }
            }
            previous_t = Some(row.t);
        }
        let check = check_range_azimuth(line, &filter);
        let start = matches!(outcome, RangeAzimuthOutcome::SecondPoint);
        if let (true, Some(dt)) = (starts.restart(check, start, event)?, used_dt) {
            (filter, ra_memory) = fresh();
            outcome = filter.update(range, azimuth, dt).map_err(refused)?;
            event = RowEvent::RestartedStart;
        }
        events.record(event, &row.t_text);
        let position = filter.position();
        let velocity = filter.velocity();
        check_estimate(line, "range", filter.range(), envelope::RANGE_M, "m")?;
        let estimate = altitude.estimate();
        if let Some(e) = estimate {
            check_estimate(line, "alt", e.altitude_ft, FINITE, "ft")?;
            check_estimate(line, "alt_rate", e.vertical_rate_ft_per_s, FINITE, "ft/s")?;
        }

        out.push_str(&row.t_text);
        let residual = match outcome {
            RangeAzimuthOutcome::Filtered(innovation) if event.used() => {
                // The same products the filter formed for its measurement.
                let (sin_b, cos_b) = S::sin_cos(azimuth);
                let measured = [range * sin_b, range * cos_b];
                Some([
                    measured[0] - innovation.predicted[0],
                    measured[1] - innovation.predicted[1],
                ])
            }
            _ => None,
        };
        for axis in 0..2 {
            cell(&mut out, position[axis]);
            cell(&mut out, velocity[axis]);
            optional_cell(&mut out, residual.map(|r| r[axis]));
        }
        cell(&mut out, filter.range());
        cell(&mut out, filter.azimuth());
        if data.has_alt {
            optional_cell(&mut out, estimate.map(|e| e.altitude_ft));
            optional_cell(&mut out, estimate.map(|e| e.vertical_rate_ft_per_s));
        }
        if let Some(own) = own {
            let intruder = (filter.phase() == Phase::Tracking)
                .then(|| Intruder::from_track(&filter, estimate));
            write_threat_cells(&mut out, &own, intruder.as_ref(), line)?;
            match used_dt {
                Some(dt) => ra_memory.update(&mut out, &own, intruder.as_ref(), dt, line)?,
                None => ra_memory.write(&mut out, false),
            }
        }
        out.push(',');
        out.push_str(event.name());
        out.push('\n');
    }
    Ok(Replayed { csv: out, events })
}
