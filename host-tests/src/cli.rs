//! Command line of the `replay` tool ([`ReplayArgs`], clap derive).
//!
//! clap parses and checks each option; [`ReplayArgs::into_command`] then checks
//! which options the chosen mode takes (`--filter ab|abg|range-azimuth` or
//! `--tracker`) and builds the [`Command`] the runners take. Every refusal
//! is a clap error: a message, the usage line and exit status 2.

use std::path::PathBuf;

use abtrack::filter::altitude::AltitudeQuantum;
use abtrack::gain::auto::AutoConfig;
use abtrack::gain::spec::{ScheduleSpec, SensorScale, SpecError, SpecErrorKind, SCHEDULES};
use abtrack::gain::ConfigError;
use abtrack::track::defaults::BANK_30_ACCELERATION;
use clap::error::ErrorKind;
use clap::{CommandFactory, Parser, ValueEnum};

use crate::csv_input::AngleUnit;
use crate::replay::{
    FilterKind, Numeric, Order, RangeAzimuthOptions, ReplayBank, ReplayConfig, ReplayError,
    ReplaySchedule, BANK_CAPACITY, WINDOW_CAPACITY,
};
use crate::replay_tracker::{SensorOptions, TrackerOptions, CAPACITIES, MAX_MEASUREMENTS};

/// `--filter`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FilterName {
    /// αβ (Al-Wagih & Abdulla).
    #[value(name = "ab")]
    AlphaBeta,
    /// αβγ (Tenne & Singh).
    #[value(name = "abg")]
    AlphaBetaGamma,
    /// The range–azimuth projection filter (He, Peng, Ling & Quan).
    #[value(name = "range-azimuth")]
    RangeAzimuth,
    /// αβ with the self-tuning `auto` schedule, from the sensor's σ alone.
    #[value(name = "auto")]
    Auto,
}

/// `--alt-quantum`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum QuantumFeet {
    /// Mode C, 100 ft.
    #[value(name = "100")]
    ModeC,
    /// Mode S, 25 ft.
    #[value(name = "25")]
    ModeS,
}

/// A finite number (clap's `f64` parser also takes `nan` and `inf`).
fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!(
            "\"{}\" is not a finite number",
            crate::csv_input::echo(text)
        )),
    }
}

/// `M/N` with 1 ≤ M ≤ N ≤ 32.
fn confirmation(text: &str) -> Result<(u8, u8), String> {
    text.split_once('/')
        .and_then(|(m, n)| Some((m.trim().parse::<u8>().ok()?, n.trim().parse::<u8>().ok()?)))
        .filter(|&(m, n)| m >= 1 && m <= n && n <= 32)
        .ok_or_else(|| "expected M/N with 1 <= M <= N <= 32".to_string())
}

/// The schedule list of `--help`, generated from the library's
/// [`SCHEDULES`] table.
pub fn schedule_list() -> String {
    let mut s = String::new();
    for info in SCHEDULES {
        let names = info.names.join(" | ");
        s.push_str(&format!("  {names}\n"));
        s.push_str(&format!("      {}\n", info.summary));
        s.push_str(&format!("      parameters: {}\n", info.parameters));
    }
    s
}

/// The text after the options in `--help`.
fn after_help() -> String {
    format!(
        "Schedules (--schedule NAME[:key=value,...]; keys not given take the defaults shown):\n\
         {}\
         The schedule starts filtering at the third row (two-point initialisation uses no\n\
         gains). With --filter abg, schedules that give αβ gains (every one but tcas-firmness\n\
         and fixed with gamma) leave the acceleration at zero; with --filter ab the γ of\n\
         tcas-firmness is ignored. bank (M5) needs --filter ab. Windows (window, n) hold at\n\
         most {WINDOW_CAPACITY} entries and the bank at most {BANK_CAPACITY} members. With\n\
         --sigma-m, the defaults the papers tied to their own noise scale with the sensor.\n\
         --filter auto is --filter ab with the auto schedule: --sigma-m on x/y input, or\n\
         --range-sigma-m and --bearing-sigma-deg on range/azimuth input (x = R sin B,\n\
         y = R cos B).\n\
         \n\
         Input: CSV with a header; columns matched by name, in any order, others ignored.\n\
         \x20 ab, abg, tracker on x/y data: t (s), x [, y [, z]] (m) [, alt (ft)]\n\
         \x20 range-azimuth, tracker on polar data: t, range (m), azimuth [, alt]\n\
         \x20 azimuth clockwise from +y (x = R sin B, y = R cos B), in radians unless\n\
         \x20 --azimuth-unit deg; alt is the target's reported pressure altitude, empty when\n\
         \x20 the reply had none. Values outside the envelope (positions and ranges beyond\n\
         \x20 400 km, altitudes outside -1000..126700 ft, an azimuth beyond one turn, t beyond\n\
         \x20 2^33 s) are refused naming the line and column. With --tracker, rows sharing\n\
         \x20 a t are one scan. Timing is never refused: a report over 20 s after the last\n\
         \x20 one used restarts the estimate, one under 0.05 s (or at a repeated or earlier\n\
         \x20 time) is skipped; the last column, event, says which.\n\
         \n\
         Output (stdout, CSV, written only when the whole file has run; f32 in its shortest\n\
         form, fixed point in decimal, an undefined value empty; details: docs/host-tools.md):\n\
         \x20 ab, abg, auto  t, then per axis a: a, va, res_a (and aa for abg)\n\
         \x20 bank           t, then per axis a: a, va, res_a, member_a (the member selected)\n\
         \x20 range-azimuth  t,x,vx,res_x,y,vy,res_y,range,azimuth [,alt,alt_rate]\n\
         \x20 tracker        t,track_id,status,x,y,vx,vy (one row per live track per scan)\n\
         \x20 --own-alt adds tau,tau_mod,t_cpa,d_cpa,advisory,tau_mod_ra (TCAS II 7.1; the own\n\
         \x20 aircraft at the origin, level at FEET over sea-level terrain, own velocity zero).\n\
         An estimate outside the envelope (or not finite) stops the run with its line named,\n\
         but a two-point start that leaves the velocity envelope (jitter) starts again from\n\
         its row, once. Restarted and skipped rows are listed on stderr.\n\
         --tracker always reports on stderr the design used and every measurement not used,\n\
         by reason. Exit status: 0 success (also when stdout is closed early), 1 bad input or a\n\
         refused row, 2 bad arguments.\n",
        schedule_list()
    )
}

/// Runs the library's filters on recorded measurements, exactly as the
/// firmware computes them (f64, f32, the Cortex-M3/M0 fast fixed point, or Q32.32).
#[derive(Debug, Clone, Parser)]
#[command(
    name = "replay",
    version,
    allow_negative_numbers = true,
    group(clap::ArgGroup::new("mode").required(true).args(["filter", "tracker"])),
    after_long_help = after_help(),
    after_help = "Schedules, input and output formats: replay --help (long) and docs/host-tools.md."
)]
pub struct ReplayArgs {
    /// The single-target filter to run.
    #[arg(long, value_enum, help_heading = "Mode")]
    pub filter: Option<FilterName>,
    /// The multi-target track table, configured from the sensor's figures.
    #[arg(long, help_heading = "Mode")]
    pub tracker: bool,
    /// f64, f32, fixed32 (the Cortex-M3 firmware's fast fixed point: Fixed32, and ScaledScalar where it runs one; --tracker and --filter range-azimuth) or q32.32 (Fix).
    #[arg(long, value_enum, default_value = "f64")]
    pub numeric: Numeric,

    /// ab, abg, tracker (x/y input, not bank): the gain schedule, NAME[:key=value,...].
    #[arg(long, value_name = "SPEC", help_heading = "Gains")]
    pub schedule: Option<String>,
    /// ab, abg: fixed position gain α (0 < α < 2); shorthand for --schedule fixed:alpha=A,beta=B.
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "beta", help_heading = "Gains")]
    pub alpha: Option<f64>,
    /// ab, abg: fixed velocity gain β (β > 0, 2α + β < 4); the update uses β/T.
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "alpha", help_heading = "Gains")]
    pub beta: Option<f64>,
    /// abg: fixed acceleration gain γ, Tenne & Singh's γ/(2T²) (0 < γ < 4αβ/(2−α)).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "alpha", help_heading = "Gains")]
    pub gamma: Option<f64>,

    /// range-azimuth, tracker, auto: range noise σ_R, m (range-azimuth default 100, He et al.'s).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub range_sigma_m: Option<f64>,
    /// range-azimuth, tracker, auto: bearing noise σ_B, degrees (range-azimuth default about 5°).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub bearing_sigma_deg: Option<f64>,
    /// range-azimuth: bearing noise variance σ_B², rad² (He et al.'s unit; default 7.569e-3).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, conflicts_with = "bearing_sigma_deg", help_heading = "Sensor")]
    pub bearing_variance: Option<f64>,
    /// range-azimuth, tracker, auto: unit of the azimuth column (never guessed).
    #[arg(long, value_enum, default_value = "rad", help_heading = "Sensor")]
    pub azimuth_unit: AngleUnit,
    /// tracker, auto: Cartesian noise σ per axis, m (tracker default 20, or the polar sensor's
    /// figures); ab, abg: scales the schedule's paper-tied defaults to the sensor (noise
    /// levels, thresholds, α and count bounds: docs/auto.md).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub sigma_m: Option<f64>,
    /// tracker: the region watched, m: half-width of a square (x/y input) or radius of a
    /// disc (range/azimuth input) around the sensor. Default: none.
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub region_m: Option<f64>,
    /// tracker: scan period T, s (default: the median interval between the file's scans);
    /// ab, abg with --sigma-m: T of the scaled defaults (default 1 s).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub scan_period_s: Option<f64>,
    /// tracker: detection probability P_D (default 0.9).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub pd: Option<f64>,
    /// tracker: false measurements per km² per scan (default 0.1 for x/y, 0.00142 for polar).
    #[arg(long = "clutter-per-km2", value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub clutter_per_km2: Option<f64>,
    /// tracker: largest target speed, m/s (default 300 for x/y, 617 for polar).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub max_speed_mps: Option<f64>,
    /// tracker, and ab, abg with --sigma-m: manoeuvre level, the largest acceleration, m/s²
    /// (default g·tan 30° = 5.66).
    #[arg(long = "max-accel-mps2", value_parser = finite, allow_hyphen_values = true, help_heading = "Sensor")]
    pub max_accel_mps2: Option<f64>,

    /// range-azimuth: process noise Q, m²/s⁴ (≥ 0; default 1).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Range-azimuth filter")]
    pub process_noise: Option<f64>,
    /// range-azimuth: quantum of the alt reports: 100 ft (Mode C) or 25 ft (Mode S).
    #[arg(long, value_enum, help_heading = "Range-azimuth filter")]
    pub alt_quantum: Option<QuantumFeet>,
    /// range-azimuth, tracker: own pressure altitude, ft; adds the TCAS threat columns.
    #[arg(long = "own-alt", value_parser = finite, allow_hyphen_values = true, value_name = "FEET")]
    pub own_alt: Option<f64>,

    /// tracker: track table capacity N (16, 64 or 256; up to 4096 measurements per scan).
    #[arg(long, value_parser = ["16", "64", "256"], help_heading = "Tracker")]
    pub capacity: Option<String>,
    /// tracker: confirm a tentative track when M of its first N scans had a measurement
    /// (tentative deletion becomes N − M + 1 misses). Default: from the design.
    #[arg(long, value_name = "M/N", value_parser = confirmation, help_heading = "Tracker")]
    pub confirm: Option<(u8, u8)>,
    /// tracker: delete a confirmed track after K consecutive misses. Default: from the design.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u8).range(1..), help_heading = "Tracker")]
    pub delete: Option<u8>,
    /// tracker: pair first points with the next scan only (by default a first point that
    /// finds no second point waits one more scan).
    #[arg(long, help_heading = "Tracker")]
    pub no_first_point_wait: bool,
    /// tracker: one line of association counts per scan on stderr.
    #[arg(long, help_heading = "Tracker")]
    pub verbose: bool,

    /// The CSV recording; - reads standard input.
    pub input: PathBuf,
}

/// Where the measurements come from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    Stdin,
    Path(PathBuf),
}

/// A checked command line.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Replay {
        config: ReplayConfig,
        input: Input,
    },
    /// `--tracker`; `verbose`: print the per-scan summary to stderr.
    Tracker {
        options: TrackerOptions,
        input: Input,
        verbose: bool,
    },
}

/// A clap usage error (exit status 2) with `message`.
fn usage_error(kind: ErrorKind, message: impl std::fmt::Display) -> clap::Error {
    ReplayArgs::command().error(kind, message)
}

impl ReplayArgs {
    /// The options given, by name, besides the mode, `--numeric` and the
    /// input.
    fn given(&self) -> Vec<&'static str> {
        let options: [(&'static str, bool); 23] = [
            ("--schedule", self.schedule.is_some()),
            ("--alpha", self.alpha.is_some()),
            ("--beta", self.beta.is_some()),
            ("--gamma", self.gamma.is_some()),
            ("--range-sigma-m", self.range_sigma_m.is_some()),
            ("--bearing-sigma-deg", self.bearing_sigma_deg.is_some()),
            ("--bearing-variance", self.bearing_variance.is_some()),
            ("--azimuth-unit", self.azimuth_unit != AngleUnit::default()),
            ("--sigma-m", self.sigma_m.is_some()),
            ("--region-m", self.region_m.is_some()),
            ("--scan-period-s", self.scan_period_s.is_some()),
            ("--pd", self.pd.is_some()),
            ("--clutter-per-km2", self.clutter_per_km2.is_some()),
            ("--max-speed-mps", self.max_speed_mps.is_some()),
            ("--max-accel-mps2", self.max_accel_mps2.is_some()),
            ("--process-noise", self.process_noise.is_some()),
            ("--alt-quantum", self.alt_quantum.is_some()),
            ("--own-alt", self.own_alt.is_some()),
            ("--capacity", self.capacity.is_some()),
            ("--confirm", self.confirm.is_some()),
            ("--delete", self.delete.is_some()),
            ("--no-first-point-wait", self.no_first_point_wait),
            ("--verbose", self.verbose),
        ];
        options
            .into_iter()
            .filter(|(_, given)| *given)
            .map(|(name, _)| name)
            .collect()
    }

    /// Checks which options the mode takes and builds the [`Command`].
    pub fn into_command(self) -> Result<Command, clap::Error> {
        let input = if self.input.as_os_str() == "-" {
            Input::Stdin
        } else {
            Input::Path(self.input.clone())
        };
        let (mode, accepted): (&str, &[&str]) = match self.filter {
            None => (
                "--tracker",
                &[
                    "--schedule",
                    "--range-sigma-m",
                    "--bearing-sigma-deg",
                    "--azimuth-unit",
                    "--sigma-m",
                    "--region-m",
                    "--scan-period-s",
                    "--pd",
                    "--clutter-per-km2",
                    "--max-speed-mps",
                    "--max-accel-mps2",
                    "--own-alt",
                    "--capacity",
                    "--confirm",
                    "--delete",
                    "--no-first-point-wait",
                    "--verbose",
                ],
            ),
            Some(FilterName::AlphaBeta) => (
                "--filter ab",
                &[
                    "--schedule",
                    "--alpha",
                    "--beta",
                    "--sigma-m",
                    "--scan-period-s",
                    "--max-accel-mps2",
                ],
            ),
            Some(FilterName::AlphaBetaGamma) => (
                "--filter abg",
                &[
                    "--schedule",
                    "--alpha",
                    "--beta",
                    "--gamma",
                    "--sigma-m",
                    "--scan-period-s",
                    "--max-accel-mps2",
                ],
            ),
            Some(FilterName::Auto) => (
                "--filter auto",
                &[
                    "--sigma-m",
                    "--range-sigma-m",
                    "--bearing-sigma-deg",
                    "--azimuth-unit",
                ],
            ),
            Some(FilterName::RangeAzimuth) => (
                "--filter range-azimuth",
                &[
                    "--range-sigma-m",
                    "--bearing-sigma-deg",
                    "--bearing-variance",
                    "--azimuth-unit",
                    "--process-noise",
                    "--alt-quantum",
                    "--own-alt",
                ],
            ),
        };
        if let Some(option) = self.given().into_iter().find(|o| !accepted.contains(o)) {
            return Err(usage_error(
                ErrorKind::ArgumentConflict,
                format!("{option} does not apply to {mode}"),
            ));
        }
        let single_filter = matches!(
            self.filter,
            Some(FilterName::AlphaBeta | FilterName::AlphaBetaGamma | FilterName::Auto)
        );
        if single_filter && self.numeric == Numeric::Fixed32 {
            return Err(usage_error(
                ErrorKind::ArgumentConflict,
                ReplayError::Fixed32SingleFilter,
            ));
        }
        match self.filter {
            None => Ok(Command::Tracker {
                options: self.tracker_options()?,
                input,
                verbose: self.verbose,
            }),
            Some(FilterName::RangeAzimuth) => Ok(Command::Replay {
                config: ReplayConfig {
                    filter: FilterKind::RangeAzimuth(self.range_azimuth()?),
                    numeric: self.numeric,
                },
                input,
            }),
            Some(FilterName::Auto) => Ok(Command::Replay {
                config: ReplayConfig {
                    filter: self.auto()?,
                    numeric: self.numeric,
                },
                input,
            }),
            Some(name) => {
                let order = match name {
                    FilterName::AlphaBeta => Order::AlphaBeta,
                    _ => Order::AlphaBetaGamma,
                };
                Ok(Command::Replay {
                    config: ReplayConfig {
                        filter: self.kinematic(order)?,
                        numeric: self.numeric,
                    },
                    input,
                })
            }
        }
    }

    /// `--filter ab|abg`: a `--schedule`, or the `--alpha/--beta/--gamma`
    /// shorthand.
    fn kinematic(&self, order: Order) -> Result<FilterKind, clap::Error> {
        let Some(text) = &self.schedule else {
            let kind = match (order, self.alpha, self.beta, self.gamma) {
                (Order::AlphaBeta, Some(alpha), Some(beta), None) => {
                    FilterKind::AlphaBeta { alpha, beta }
                }
                (Order::AlphaBetaGamma, Some(alpha), Some(beta), Some(gamma)) => {
                    FilterKind::AlphaBetaGamma { alpha, beta, gamma }
                }
                _ => {
                    return Err(usage_error(
                        ErrorKind::MissingRequiredArgument,
                        match order {
                            Order::AlphaBeta => {
                                "--filter ab needs --schedule (or --alpha and --beta)"
                            }
                            Order::AlphaBetaGamma => {
                                "--filter abg needs --schedule (or --alpha, --beta and --gamma)"
                            }
                        },
                    ))
                }
            };
            if let Some(Err(e)) = kind.fixed_gains::<f64>() {
                return Err(usage_error(
                    ErrorKind::ValueValidation,
                    format!("gains outside the stability region: {e}"),
                ));
            }
            return Ok(kind);
        };
        if self.alpha.is_some() || self.beta.is_some() || self.gamma.is_some() {
            return Err(usage_error(
                ErrorKind::ArgumentConflict,
                "--schedule and --alpha/--beta/--gamma cannot be combined (--alpha/--beta/--gamma \
                 are shorthand for --schedule fixed:alpha=A,beta=B[,gamma=G])",
            ));
        }
        let spec = match self.sensor_scale()? {
            None => schedule_arg(text)?,
            Some(scale) => schedule_arg_scaled(text, &scale)?,
        };
        match (spec, order) {
            (ScheduleSpec::Bank(c), Order::AlphaBeta) => Ok(FilterKind::Bank(c)),
            (ScheduleSpec::Bank(_), Order::AlphaBetaGamma) => Err(usage_error(
                ErrorKind::ArgumentConflict,
                "--schedule bank: the M5 bank is made of αβ filters; use --filter ab",
            )),
            (ScheduleSpec::Fixed(c), Order::AlphaBeta) if c.gamma.is_some() => Err(usage_error(
                ErrorKind::ArgumentConflict,
                "gamma (in --schedule fixed) does not apply to --filter ab",
            )),
            _ => Ok(FilterKind::Scheduled { order, spec }),
        }
    }

    /// `--filter auto`: `--sigma-m` (x/y input), or `--range-sigma-m` with
    /// `--bearing-sigma-deg` (range/azimuth input).
    fn auto(&self) -> Result<FilterKind, clap::Error> {
        let config = match (self.sigma_m, self.range_sigma_m, self.bearing_sigma_deg) {
            (Some(sigma), None, None) => AutoConfig::cartesian(sigma),
            (None, Some(r), Some(b)) => AutoConfig::polar(r, b),
            _ => {
                return Err(usage_error(
                    ErrorKind::MissingRequiredArgument,
                    "--filter auto needs --sigma-m (x/y input), or --range-sigma-m and \
                     --bearing-sigma-deg (range/azimuth input)",
                ))
            }
        };
        let spec = ScheduleSpec::Auto(config);
        // Checked as the spec parser would, with the option named.
        schedule_arg(&spec.to_string()).map_err(|_| {
            usage_error(
                ErrorKind::ValueValidation,
                "--filter auto: the sensor σ must be > 0 (at most 10^6 m; the bearing σ at \
                 most 90°)",
            )
        })?;
        Ok(if config.sigma.is_some() {
            FilterKind::Scheduled {
                order: Order::AlphaBeta,
                spec,
            }
        } else {
            FilterKind::AutoPolar {
                config,
                azimuth_unit: self.azimuth_unit,
            }
        })
    }

    /// `--filter ab|abg --sigma-m S`: the figures that scale the schedules'
    /// paper-tied defaults ([`SensorScale`]); T from `--scan-period-s`
    /// (default 1 s), a_max from `--max-accel-mps2` (default g·tan 30°).
    fn sensor_scale(&self) -> Result<Option<SensorScale>, clap::Error> {
        let Some(sigma) = self.sigma_m else {
            if self.scan_period_s.is_some() || self.max_accel_mps2.is_some() {
                return Err(usage_error(
                    ErrorKind::MissingRequiredArgument,
                    "--scan-period-s and --max-accel-mps2 scale the schedule's defaults with \
                     --sigma-m; give --sigma-m",
                ));
            }
            return Ok(None);
        };
        let scale = SensorScale {
            sigma,
            period: self.scan_period_s.unwrap_or(1.0),
            max_acceleration: self.max_accel_mps2.unwrap_or(BANK_30_ACCELERATION),
        };
        for (option, v) in [
            ("--sigma-m", scale.sigma),
            ("--scan-period-s", scale.period),
            ("--max-accel-mps2", scale.max_acceleration),
        ] {
            if v <= 0.0 {
                return Err(usage_error(
                    ErrorKind::ValueValidation,
                    format!("{option}: {v} is out of range (must be > 0)"),
                ));
            }
        }
        let periods = abtrack::envelope::INTERVAL_S;
        if !periods.contains(scale.period) {
            return Err(usage_error(
                ErrorKind::ValueValidation,
                format!(
                    "--scan-period-s: {} is out of range (must be {}–{} s, the filters' \
                     intervals)",
                    scale.period, periods.min, periods.max
                ),
            ));
        }
        Ok(Some(scale))
    }

    /// `--filter range-azimuth`: noise settings, altitude quantum, own
    /// altitude, azimuth unit.
    fn range_azimuth(&self) -> Result<RangeAzimuthOptions, clap::Error> {
        let d = RangeAzimuthOptions::DEFAULT;
        let out_of_range = |option: &str, v: f64, requirement: &str| {
            usage_error(
                ErrorKind::ValueValidation,
                format!("{option}: {v} is out of range (must be {requirement})"),
            )
        };
        let range_sigma_m = self.range_sigma_m.unwrap_or(d.range_sigma_m);
        if range_sigma_m <= 0.0 {
            return Err(out_of_range("--range-sigma-m", range_sigma_m, "> 0"));
        }
        let bearing_variance_rad2 = match (self.bearing_variance, self.bearing_sigma_deg) {
            (Some(v), _) if v <= 0.0 => return Err(out_of_range("--bearing-variance", v, "> 0")),
            (Some(v), _) => v,
            (None, Some(deg)) if deg <= 0.0 => {
                return Err(out_of_range("--bearing-sigma-deg", deg, "> 0"))
            }
            (None, Some(deg)) => deg.to_radians().powi(2),
            (None, None) => d.bearing_variance_rad2,
        };
        let process_noise = self.process_noise.unwrap_or(d.process_noise);
        if process_noise < 0.0 {
            return Err(out_of_range("--process-noise", process_noise, ">= 0"));
        }
        let options = RangeAzimuthOptions {
            range_sigma_m,
            bearing_variance_rad2,
            process_noise,
            altitude_quantum: match self.alt_quantum {
                None => d.altitude_quantum,
                Some(QuantumFeet::ModeC) => AltitudeQuantum::ModeC,
                Some(QuantumFeet::ModeS) => AltitudeQuantum::ModeS25,
            },
            own_altitude_ft: self.own_alt,
            azimuth_unit: self.azimuth_unit,
        };
        // σ_R² and σ_B² must also be finite, representable variances.
        if options.noise::<f64>().is_err() {
            return Err(out_of_range(
                "--range-sigma-m",
                range_sigma_m,
                "> 0 with a finite square",
            ));
        }
        Ok(options)
    }

    /// `--tracker`.
    fn tracker_options(&self) -> Result<TrackerOptions, clap::Error> {
        let schedule = match &self.schedule {
            None => None,
            Some(text) => match schedule_arg(text)? {
                ScheduleSpec::Bank(_) => {
                    return Err(usage_error(
                        ErrorKind::ArgumentConflict,
                        "--schedule bank does not apply to --tracker",
                    ))
                }
                spec => Some(spec),
            },
        };
        let capacity = match &self.capacity {
            None => crate::replay_tracker::DEFAULT_CAPACITY,
            Some(text) => text
                .parse::<usize>()
                .ok()
                .filter(|n| CAPACITIES.contains(n))
                .ok_or_else(|| {
                    usage_error(
                        ErrorKind::InvalidValue,
                        format!("--capacity: {text} (16, 64 or 256; {MAX_MEASUREMENTS} measurements per scan)"),
                    )
                })?,
        };
        let options = TrackerOptions {
            numeric: self.numeric,
            schedule,
            capacity,
            confirmation: self.confirm,
            delete_confirmed: self.delete,
            first_points_through_a_miss: !self.no_first_point_wait,
            own_altitude_ft: self.own_alt,
            sensor: SensorOptions {
                region_m: self.region_m,
                sigma_m: self.sigma_m,
                range_sigma_m: self.range_sigma_m,
                bearing_sigma_deg: self.bearing_sigma_deg,
                scan_period_s: self.scan_period_s,
                detection_probability: self.pd,
                clutter_per_km2: self.clutter_per_km2,
                max_speed_m_per_s: self.max_speed_mps,
                max_acceleration_m_per_s2: self.max_accel_mps2,
            },
            azimuth_unit: self.azimuth_unit,
        };
        // The sensor's figures are arguments: refused here, before the
        // input is read (the file gives only the defaults' context).
        options
            .sensor
            .check()
            .map_err(|why| usage_error(ErrorKind::ValueValidation, why))?;
        Ok(options)
    }
}

/// A `--schedule` spec the library's parser (or the schedule's
/// construction) refused; `error.offset` is a byte offset in `text`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScheduleArgError {
    pub text: String,
    pub error: SpecError,
}

impl std::fmt::Display for ScheduleArgError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The spec, and a caret under the byte the parser points at.
        let column = self
            .text
            .get(..self.error.offset)
            .map_or(self.error.offset, |s| s.chars().count());
        write!(
            f,
            "--schedule: {}\n  {}\n  {}^",
            self.error,
            self.text,
            " ".repeat(column)
        )
    }
}

/// A `--schedule` spec, parsed and built once in `f64`: capacities are
/// checked when a schedule is built, not by the parser, so building it here
/// makes an oversized window or bank an argument error pointing at its key.
pub fn parse_schedule(text: &str) -> Result<ScheduleSpec, ScheduleArgError> {
    let spec_error = |error: SpecError| ScheduleArgError {
        text: text.to_string(),
        error,
    };
    let spec = ScheduleSpec::parse(text).map_err(spec_error)?;
    let built = match spec {
        ScheduleSpec::Bank(c) => ReplayBank::<f64, 1>::from_config(&c).map(|_| ()),
        _ => ReplaySchedule::<f64, 1>::from_spec(&spec).map(|_| ()),
    };
    built.map_err(|e| {
        spec_error(SpecError {
            kind: SpecErrorKind::Config(e),
            offset: parameter_offset(text, e),
        })
    })?;
    Ok(spec)
}

/// [`parse_schedule`] as a usage error.
fn schedule_arg(text: &str) -> Result<ScheduleSpec, clap::Error> {
    parse_schedule(text).map_err(|e| usage_error(ErrorKind::ValueValidation, e))
}

/// [`schedule_arg`] with the defaults scaled to the sensor
/// ([`ScheduleSpec::parse_scaled`]).
fn schedule_arg_scaled(text: &str, scale: &SensorScale) -> Result<ScheduleSpec, clap::Error> {
    let spec = ScheduleSpec::parse_scaled(text, scale).map_err(|error| {
        usage_error(
            ErrorKind::ValueValidation,
            ScheduleArgError {
                text: text.to_string(),
                error,
            },
        )
    })?;
    // Built once, as `parse_schedule` does, for the capacity checks.
    parse_schedule(&spec.to_string()).map_err(|e| usage_error(ErrorKind::ValueValidation, e))?;
    Ok(spec)
}

/// The byte offset of the `key=value` part that `error` is about in spec
/// `text` (0 if the key was not given).
fn parameter_offset(text: &str, error: ConfigError) -> usize {
    let parameter = match error {
        ConfigError::OutOfRange { parameter }
        | ConfigError::NotRepresentable { parameter }
        | ConfigError::ExceedsCapacity { parameter, .. } => parameter,
        ConfigError::NotASchedule => return 0,
    };
    let Some((name, params)) = text.split_once(':') else {
        return 0;
    };
    let mut offset = name.len() + 1;
    for part in params.split(',') {
        if part.split_once('=').is_some_and(|(k, _)| k == parameter) {
            return offset;
        }
        offset += part.len() + 1;
    }
    0
}
