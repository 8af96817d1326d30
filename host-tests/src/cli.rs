//! Command-line arguments of the `replay` tool.
//!
//! Options are looked up in one table ([`REPLAY_OPTIONS`]) and collected as
//! text first, then interpreted per filter ([`filter_kind`]): adding an
//! option is a table row, its name in the filter's list of accepted options
//! ([`accepted_options`]) and the code that reads it; a new filter kind is
//! one arm of [`filter_kind`].
//!
//! A multi-target `--tracker` would be one more filter-independent row of
//! the table and a [`Command`] of its own, reading scans (rows sharing a
//! `t`, [`crate::csv_input::TimeOrder::Scans`]) instead of single-target
//! rows.
//!
//! Both `--name value` and `--name=value` are accepted; `-` as the input means
//! standard input.

use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;

use abtrack::filter::altitude::AltitudeQuantum;
use abtrack::gain::spec::{ScheduleSpec, SpecError, SpecErrorKind, SCHEDULES};
use abtrack::gain::ConfigError;
use abtrack::GainError;

use crate::replay::{
    FilterKind, Numeric, Order, RangeAzimuthOptions, ReplayBank, ReplayConfig, ReplaySchedule,
    BANK_CAPACITY, WINDOW_CAPACITY,
};

/// The options that take a value, with their help text.
pub const REPLAY_OPTIONS: &[(&str, &str)] = &[
    (
        "--filter",
        "ab | abg | range-azimuth: αβ (Al-Wagih & Abdulla), αβγ (Tenne & Singh), or the\n\
         range-azimuth projection filter (He, Peng, Ling & Quan)",
    ),
    (
        "--schedule",
        "ab, abg: NAME[:key=value,...], the gain schedule (list below)",
    ),
    (
        "--alpha",
        "ab, abg: fixed position gain α (0 < α < 2); --alpha A --beta B [--gamma G] is\n\
         shorthand for --schedule fixed:alpha=A,beta=B[,gamma=G]",
    ),
    (
        "--beta",
        "ab, abg: fixed velocity gain β (β > 0, 2α + β < 4); the update uses β/T",
    ),
    (
        "--gamma",
        "abg: fixed acceleration gain γ, Tenne & Singh's γ/(2T²) (0 < γ < 4αβ/(2−α))",
    ),
    (
        "--range-sigma",
        "range-azimuth: range noise σ_R in metres, > 0 (default 100, He et al.'s 100 m)",
    ),
    (
        "--bearing-variance",
        "range-azimuth: bearing noise variance σ_B² in rad², > 0; the cross-range variance\n\
         is R²·σ_B² (default 7.569e-3, He et al.'s value, about 5° RMS)",
    ),
    (
        "--process-noise",
        "range-azimuth: process noise Q in m²/s⁴, ≥ 0: the variance of the white\n\
         acceleration, along and across range (default 1)",
    ),
    (
        "--alt-quantum",
        "range-azimuth: quantum of the alt reports in feet, 100 (Mode C, default) or 25\n\
         (Mode S); sets the altitude tracker's gains",
    ),
    (
        "--own-alt",
        "range-azimuth: own pressure altitude in feet; adds the threat columns",
    ),
    ("--numeric", "f64 | f32 | fixed (Q32.32); default f64"),
];

/// The options each filter accepts (besides `--filter` and `--numeric`).
pub fn accepted_options(filter: &str) -> &'static [&'static str] {
    match filter {
        "ab" => &["--schedule", "--alpha", "--beta"],
        "abg" => &["--schedule", "--alpha", "--beta", "--gamma"],
        "range-azimuth" => &[
            "--range-sigma",
            "--bearing-variance",
            "--process-noise",
            "--alt-quantum",
            "--own-alt",
        ],
        _ => &[],
    }
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

/// The `--help` text.
pub fn replay_usage() -> String {
    let mut s = String::from(
        "replay: run the abtrack filters on recorded measurements, exactly as the firmware computes them.\n\
         \n\
         usage:\n  \
           replay --filter ab|abg --schedule NAME[:key=value,...] [--numeric N] <FILE | ->\n  \
           replay --filter ab|abg --alpha A --beta B [--gamma G] [--numeric N] <FILE | ->\n  \
           replay --filter range-azimuth [--range-sigma M] [--bearing-variance V] [--process-noise Q]\n         \
                  [--alt-quantum 100|25] [--own-alt FEET] [--numeric N] <FILE | ->\n\
         \n\
         options (--name value or --name=value; the filters an option applies to come first):\n",
    );
    let width = REPLAY_OPTIONS
        .iter()
        .map(|(n, _)| n.chars().count())
        .max()
        .unwrap_or(0);
    for (name, help) in REPLAY_OPTIONS {
        let indent = " ".repeat(width + 3);
        let help = help.replace('\n', &format!("\n{indent}"));
        s.push_str(&format!("  {name:<width$} {help}\n"));
    }
    s.push_str(&format!("  {:<width$} show this text\n", "-h, --help"));
    s.push_str(&format!(
        "\nschedules (--schedule NAME[:key=value,...]; keys not given take the defaults shown):\n\
         {}\
         \x20 The schedule starts filtering at the third row (two-point initialisation uses no\n\
         \x20 gains). With --filter abg, schedules that give αβ gains (every one but tcas-firmness\n\
         \x20 and fixed with gamma) leave the acceleration at zero; with --filter ab the γ of\n\
         \x20 tcas-firmness is ignored. bank (M5) needs --filter ab. Windows (window, n) hold at\n\
         \x20 most {WINDOW_CAPACITY} entries and the bank at most {BANK_CAPACITY} members.\n\
         \x20 A bad spec is refused with its byte position, e.g. `m1:beta=0.3`: unknown parameter\n\
         \x20 for this schedule (at byte 3).\n",
        schedule_list()
    ));
    s.push_str(
        "\ninput (CSV; `-` reads standard input; t in seconds, strictly increasing; blank lines,\n\
         spaces around fields, \\r\\n and a UTF-8 BOM are accepted):\n  \
           ab, abg        header t,x or t,x,y or t,x,y,z; positions in metres.\n  \
           range-azimuth  header t,range,azimuth or t,range,azimuth,alt; range in metres (> 0),\n                 \
                          azimuth in radians clockwise from +y (x = R sin B, y = R cos B; any\n                 \
                          finite value, it wraps), alt the intruder's reported pressure altitude\n                 \
                          in feet, an empty field meaning the reply carried none.\n\
         \n\
         output (stdout, CSV; f32 values in f32's shortest form, fixed point in decimal; an\n\
         undefined value is an empty cell):\n  \
           ab, abg        t, then per axis a (x, y, z): a, va, res_a and, for abg, aa: position,\n                 \
                          velocity (and acceleration) after the update, residual z − prediction\n                 \
                          (empty on the two initialisation rows).\n  \
           bank           per axis a, va, res_a, member_a: the output is that of the member whose\n                 \
                          prediction of this row had the least |z − prediction| (Al-Wagih &\n                 \
                          Abdulla Algorithm 3, ties to the lowest index): its position and\n                 \
                          velocity after the update, its residual, and its index (0-based, α\n                 \
                          evenly spaced from min to max, β = α²/(2 − α)).\n  \
           range-azimuth  t,x,vx,res_x,y,vy,res_y,range,azimuth: the relative position (m) and\n                 \
                          velocity (m/s), res_a = converted measurement (R sin B, R cos B) minus the\n                 \
                          prediction, and the estimate as range (m) and azimuth (rad, [0, 2π)).\n                 \
                          With an alt column: alt (ft), alt_rate (ft/s), the altitude tracker's\n                 \
                          estimate (empty while the intruder is not reporting: no report yet, or\n                 \
                          none for more than 6 s).\n                 \
                          With --own-alt: tau (range tau, s; empty when opening), tau_mod\n                 \
                          (modified tau with the TA DMOD, s; empty when opening outside DMOD),\n                 \
                          t_cpa (s), d_cpa (m), advisory (none|proximate|ta|ra) and tau_mod_ra\n                 \
                          (modified tau with the RA DMOD; also empty at SL 2), from abtrack::tcas\n                 \
                          (TCAS II 7.1: 10 ft/s closure floor, sensitivity level from FEET). All\n                 \
                          empty on the first row (no velocity yet).\n                 \
                          Assumed: the own aircraft is at the origin, level at FEET over terrain\n                 \
                          at sea level (radio altitude = FEET); range and azimuth are relative,\n                 \
                          so the track is the relative motion (own velocity zero). Without an alt\n                 \
                          column (or while the tracker has no altitude) the intruder counts as\n                 \
                          not reporting altitude: at most a TA, proximate within 6 NM.\n\
         The first row's interval is taken as 1 s (unused by two-point initialisation).\n\
         Nothing is written unless the whole file runs; errors name the line and column.\n\
         exit status: 0 success, 1 bad input file or refused row, 2 bad arguments.\n",
    );
    s
}

/// Where the measurements come from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    Stdin,
    Path(PathBuf),
}

/// A parsed command line.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Help,
    Replay { config: ReplayConfig, input: Input },
}

/// Why the arguments were refused.
#[derive(Debug, Clone, PartialEq)]
pub enum UsageError {
    UnknownOption(String),
    MissingValue(&'static str),
    Repeated(&'static str),
    Missing(&'static str),
    BadNumber {
        option: &'static str,
        text: String,
    },
    /// A number outside the option's range.
    OutOfRange {
        option: &'static str,
        text: String,
        requirement: &'static str,
    },
    UnknownFilter(String),
    UnknownNumeric(String),
    UnknownQuantum(String),
    /// An option that the chosen filter does not take.
    NotForFilter {
        option: &'static str,
        filter: String,
    },
    /// Two options that choose the same thing.
    Conflict {
        option: &'static str,
        with: &'static str,
    },
    /// A `--schedule` spec the library's parser (or the schedule's
    /// construction) refused; `offset` in `error` is a byte offset in `text`.
    Spec {
        text: String,
        error: SpecError,
    },
    /// `--schedule bank` with `--filter abg`.
    BankNeedsAlphaBeta,
    Gains(GainError),
    NoInput,
    ExtraInput(String),
}

impl fmt::Display for UsageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UsageError::UnknownOption(o) => write!(f, "unknown option {o}"),
            UsageError::MissingValue(o) => write!(f, "{o} needs a value"),
            UsageError::Repeated(o) => write!(f, "{o} given twice"),
            UsageError::Missing(o) => write!(f, "{o} is required"),
            UsageError::BadNumber { option, text } => {
                write!(f, "{option}: \"{text}\" is not a finite number")
            }
            UsageError::OutOfRange {
                option,
                text,
                requirement,
            } => write!(
                f,
                "{option}: {text} is out of range (must be {requirement})"
            ),
            UsageError::UnknownFilter(n) => {
                write!(f, "--filter: unknown filter \"{n}\" (ab|abg|range-azimuth)")
            }
            UsageError::UnknownNumeric(n) => {
                write!(f, "--numeric: unknown \"{n}\" ({})", Numeric::NAMES)
            }
            UsageError::UnknownQuantum(n) => {
                write!(f, "--alt-quantum: unknown \"{n}\" (100 or 25)")
            }
            UsageError::NotForFilter { option, filter } => {
                write!(f, "{option} does not apply to --filter {filter}")
            }
            UsageError::Conflict { option, with } => write!(
                f,
                "{option} and {with} cannot be combined (--alpha/--beta/--gamma are shorthand \
                 for --schedule fixed:alpha=A,beta=B[,gamma=G])"
            ),
            UsageError::Spec { text, error } => {
                // The spec, and a caret under the byte the parser points at.
                let column = text
                    .get(..error.offset)
                    .map_or(error.offset, |s| s.chars().count());
                write!(
                    f,
                    "--schedule: {error}\n  {text}\n  {}^",
                    " ".repeat(column)
                )
            }
            UsageError::BankNeedsAlphaBeta => write!(
                f,
                "--schedule bank: the M5 bank is made of αβ filters; use --filter ab"
            ),
            UsageError::Gains(e) => write!(f, "gains outside the stability region: {e}"),
            UsageError::NoInput => write!(f, "no input file (give a path, or - for stdin)"),
            UsageError::ExtraInput(p) => write!(f, "more than one input file ({p})"),
        }
    }
}

impl std::error::Error for UsageError {}

/// Option values as given, before interpretation.
#[derive(Debug, Default)]
struct RawOptions {
    values: BTreeMap<&'static str, String>,
}

impl RawOptions {
    fn take(&mut self, name: &'static str) -> Option<String> {
        self.values.remove(name)
    }

    fn number(&mut self, name: &'static str) -> Result<Option<f64>, UsageError> {
        match self.take(name) {
            None => Ok(None),
            Some(text) => match text.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(v)),
                _ => Err(UsageError::BadNumber { option: name, text }),
            },
        }
    }

    fn required_number(&mut self, name: &'static str) -> Result<f64, UsageError> {
        self.number(name)?.ok_or(UsageError::Missing(name))
    }

    /// A number checked by `ok`, or `default` when not given.
    fn number_in(
        &mut self,
        name: &'static str,
        default: f64,
        ok: fn(f64) -> bool,
        requirement: &'static str,
    ) -> Result<f64, UsageError> {
        let text = self.values.get(name).cloned().unwrap_or_default();
        match self.number(name)? {
            None => Ok(default),
            Some(v) if ok(v) => Ok(v),
            Some(_) => Err(UsageError::OutOfRange {
                option: name,
                text,
                requirement,
            }),
        }
    }
}

/// Parses the arguments after the program name.
pub fn parse_replay_args<I: IntoIterator<Item = String>>(args: I) -> Result<Command, UsageError> {
    let mut raw = RawOptions::default();
    let mut input: Option<Input> = None;
    let mut only_positional = false;
    let mut args = args.into_iter();
    while let Some(arg) = args.next() {
        let positional = only_positional || arg == "-" || !arg.starts_with('-');
        if positional {
            let this = if arg == "-" {
                Input::Stdin
            } else {
                Input::Path(PathBuf::from(&arg))
            };
            if input.replace(this).is_some() {
                return Err(UsageError::ExtraInput(arg));
            }
            continue;
        }
        if arg == "--" {
            only_positional = true;
            continue;
        }
        if arg == "-h" || arg == "--help" {
            return Ok(Command::Help);
        }
        let (name, inline) = match arg.split_once('=') {
            Some((n, v)) => (n.to_string(), Some(v.to_string())),
            None => (arg.clone(), None),
        };
        let Some(&(known, _)) = REPLAY_OPTIONS.iter().find(|(n, _)| *n == name) else {
            return Err(UsageError::UnknownOption(arg));
        };
        let value = match inline {
            Some(v) => v,
            None => args.next().ok_or(UsageError::MissingValue(known))?,
        };
        if raw.values.insert(known, value).is_some() {
            return Err(UsageError::Repeated(known));
        }
    }

    let numeric = match raw.take("--numeric") {
        None => Numeric::default(),
        Some(n) => Numeric::from_name(n.trim()).ok_or(UsageError::UnknownNumeric(n))?,
    };
    let filter = filter_kind(&mut raw)?;
    let input = input.ok_or(UsageError::NoInput)?;
    Ok(Command::Replay {
        config: ReplayConfig { filter, numeric },
        input,
    })
}

/// The filter and its settings, checked in `f64` (the chosen representation
/// checks again after rounding).
fn filter_kind(raw: &mut RawOptions) -> Result<FilterKind, UsageError> {
    let name = raw
        .take("--filter")
        .ok_or(UsageError::Missing("--filter"))?;
    let filter = name.trim();
    if !matches!(filter, "ab" | "abg" | "range-azimuth") {
        return Err(UsageError::UnknownFilter(name));
    }
    let accepted = accepted_options(filter);
    if let Some(&option) = raw.values.keys().find(|o| !accepted.contains(o)) {
        return Err(UsageError::NotForFilter {
            option,
            filter: name,
        });
    }
    match filter {
        "ab" => kinematic(raw, Order::AlphaBeta),
        "abg" => kinematic(raw, Order::AlphaBetaGamma),
        _ => range_azimuth(raw).map(FilterKind::RangeAzimuth),
    }
}

/// `--filter ab|abg`: a `--schedule`, or the `--alpha/--beta/--gamma`
/// shorthand.
fn kinematic(raw: &mut RawOptions, order: Order) -> Result<FilterKind, UsageError> {
    let Some(text) = raw.take("--schedule") else {
        let kind = match order {
            Order::AlphaBeta => {
                if raw.values.contains_key("--alpha") || raw.values.contains_key("--beta") {
                    FilterKind::AlphaBeta {
                        alpha: raw.required_number("--alpha")?,
                        beta: raw.required_number("--beta")?,
                    }
                } else {
                    return Err(UsageError::Missing("--schedule (or --alpha and --beta)"));
                }
            }
            Order::AlphaBetaGamma => {
                if ["--alpha", "--beta", "--gamma"]
                    .iter()
                    .any(|o| raw.values.contains_key(o))
                {
                    FilterKind::AlphaBetaGamma {
                        alpha: raw.required_number("--alpha")?,
                        beta: raw.required_number("--beta")?,
                        gamma: raw.required_number("--gamma")?,
                    }
                } else {
                    return Err(UsageError::Missing(
                        "--schedule (or --alpha, --beta and --gamma)",
                    ));
                }
            }
        };
        if let Some(gains) = kind.fixed_gains::<f64>() {
            gains.map_err(UsageError::Gains)?;
        }
        return Ok(kind);
    };
    if let Some(&with) = ["--alpha", "--beta", "--gamma"]
        .iter()
        .find(|o| raw.values.contains_key(*o))
    {
        return Err(UsageError::Conflict {
            option: "--schedule",
            with,
        });
    }
    let spec_error = |error: SpecError| UsageError::Spec {
        text: text.clone(),
        error,
    };
    let spec = ScheduleSpec::parse(&text).map_err(spec_error)?;
    // Capacities are checked when a schedule is built, not by the parser:
    // build it once here so that an oversized window or bank is an argument
    // error pointing at its key.
    let built = match spec {
        ScheduleSpec::Bank(c) => ReplayBank::<f64, 1>::from_config(&c).map(|_| ()),
        _ => ReplaySchedule::<f64, 1>::from_spec(&spec).map(|_| ()),
    };
    built.map_err(|e| {
        spec_error(SpecError {
            kind: SpecErrorKind::Config(e),
            offset: parameter_offset(&text, e),
        })
    })?;
    match (spec, order) {
        (ScheduleSpec::Bank(c), Order::AlphaBeta) => Ok(FilterKind::Bank(c)),
        (ScheduleSpec::Bank(_), Order::AlphaBetaGamma) => Err(UsageError::BankNeedsAlphaBeta),
        (ScheduleSpec::Fixed(c), Order::AlphaBeta) if c.gamma.is_some() => {
            Err(UsageError::NotForFilter {
                option: "gamma (in --schedule fixed)",
                filter: order.name().to_string(),
            })
        }
        _ => Ok(FilterKind::Scheduled { order, spec }),
    }
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

/// `--filter range-azimuth`: noise settings, altitude quantum, own altitude.
fn range_azimuth(raw: &mut RawOptions) -> Result<RangeAzimuthOptions, UsageError> {
    let d = RangeAzimuthOptions::DEFAULT;
    let positive = |v: f64| v > 0.0;
    let options = RangeAzimuthOptions {
        range_sigma_m: raw.number_in("--range-sigma", d.range_sigma_m, positive, "> 0")?,
        bearing_variance_rad2: raw.number_in(
            "--bearing-variance",
            d.bearing_variance_rad2,
            positive,
            "> 0",
        )?,
        process_noise: raw.number_in("--process-noise", d.process_noise, |v| v >= 0.0, ">= 0")?,
        altitude_quantum: match raw.take("--alt-quantum") {
            None => d.altitude_quantum,
            Some(q) => match q.trim() {
                "100" => AltitudeQuantum::ModeC,
                "25" => AltitudeQuantum::ModeS25,
                _ => return Err(UsageError::UnknownQuantum(q)),
            },
        },
        own_altitude_ft: raw.number("--own-alt")?,
    };
    // σ_R² must also be a finite, representable variance.
    if options.noise::<f64>().is_err() {
        return Err(UsageError::OutOfRange {
            option: "--range-sigma",
            text: options.range_sigma_m.to_string(),
            requirement: "> 0 with a finite square",
        });
    }
    Ok(options)
}
