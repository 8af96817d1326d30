//! Command-line arguments of the `replay` tool.
//!
//! Options are looked up in one table ([`REPLAY_OPTIONS`]) and collected as
//! text first, then interpreted: adding an option (a gain `--schedule`, a
//! `--tracker`, `--own-alt`) is a table row plus the code that reads it, and a
//! new filter kind (`range-azimuth`) is one arm of [`filter_kind`].
//! Both `--name value` and `--name=value` are accepted; `-` as the input means
//! standard input.

use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;

use abtrack::GainError;

use crate::replay::{FilterKind, Numeric, ReplayConfig};

/// The options that take a value, with their help text.
pub const REPLAY_OPTIONS: &[(&str, &str)] = &[
    (
        "--filter",
        "ab | abg: αβ (Al-Wagih & Abdulla) or αβγ (Tenne & Singh)",
    ),
    ("--alpha", "position gain α (0 < α < 2)"),
    (
        "--beta",
        "velocity gain β (β > 0, 2α + β < 4); the update uses β/T",
    ),
    (
        "--gamma",
        "acceleration gain γ for abg, Tenne & Singh's γ/(2T²) (0 < γ < 4αβ/(2−α))",
    ),
    ("--numeric", "f64 | f32 | fixed (Q32.32); default f64"),
];

/// The `--help` text.
pub fn replay_usage() -> String {
    let mut s = String::from(
        "replay: run the abtrack filters on recorded measurements, exactly as the firmware computes them.\n\
         \n\
         usage: replay --filter ab|abg --alpha A --beta B [--gamma G] [--numeric f64|f32|fixed] <FILE | ->\n\
         \n\
         options:\n",
    );
    for (name, help) in REPLAY_OPTIONS {
        s.push_str(&format!("  {name:<10} {help}\n"));
    }
    s.push_str(
        "  -h, --help show this text\n\
         \n\
         input: CSV with a header t,x or t,x,y or t,x,y,z; t in seconds (strictly increasing),\n\
         positions in metres; `-` reads standard input.\n\
         output (stdout): t, then per axis a: a, va, res_a (residual z - prediction, empty on the\n\
         two initialisation rows) and, for abg, aa. Nothing is written unless the whole file runs.\n\
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
    UnknownFilter(String),
    UnknownNumeric(String),
    /// An option that the chosen filter does not take.
    NotForFilter {
        option: &'static str,
        filter: String,
    },
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
            UsageError::UnknownFilter(n) => write!(f, "--filter: unknown filter \"{n}\" (ab|abg)"),
            UsageError::UnknownNumeric(n) => {
                write!(f, "--numeric: unknown \"{n}\" ({})", Numeric::NAMES)
            }
            UsageError::NotForFilter { option, filter } => {
                write!(f, "{option} does not apply to --filter {filter}")
            }
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

    let filter = filter_kind(&mut raw)?;
    let numeric = match raw.take("--numeric") {
        None => Numeric::default(),
        Some(n) => Numeric::from_name(n.trim()).ok_or(UsageError::UnknownNumeric(n))?,
    };
    let input = input.ok_or(UsageError::NoInput)?;
    Ok(Command::Replay {
        config: ReplayConfig { filter, numeric },
        input,
    })
}

/// The filter and its gains, checked against the stability region in `f64`
/// (the chosen representation checks again after rounding).
fn filter_kind(raw: &mut RawOptions) -> Result<FilterKind, UsageError> {
    let name = raw
        .take("--filter")
        .ok_or(UsageError::Missing("--filter"))?;
    let kind = match name.trim() {
        "ab" => {
            if raw.values.contains_key("--gamma") {
                return Err(UsageError::NotForFilter {
                    option: "--gamma",
                    filter: name,
                });
            }
            FilterKind::AlphaBeta {
                alpha: raw.required_number("--alpha")?,
                beta: raw.required_number("--beta")?,
            }
        }
        "abg" => FilterKind::AlphaBetaGamma {
            alpha: raw.required_number("--alpha")?,
            beta: raw.required_number("--beta")?,
            gamma: raw.required_number("--gamma")?,
        },
        _ => return Err(UsageError::UnknownFilter(name)),
    };
    kind.gains::<f64>().map_err(UsageError::Gains)?;
    Ok(kind)
}
