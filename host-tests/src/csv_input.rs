//! Reader for recorded measurements, in one of two layouts chosen by the
//! filter ([`InputFormat`]):
//!
//! * Cartesian (`--filter ab|abg`): a header `t,x`, `t,x,y` or `t,x,y,z` and
//!   one row per measurement (t in seconds, positions in metres);
//! * range–azimuth (`--filter range-azimuth`): a header `t,range,azimuth` or
//!   `t,range,azimuth,alt`: slant range in metres (> 0), azimuth in radians
//!   clockwise from +y (x = R sin B, y = R cos B, any finite value), and the
//!   intruder's reported pressure altitude in feet, where an empty field means
//!   the reply carried no altitude.
//!
//! A small hand parser rather than the `csv` crate: the files hold only
//! numbers (no quoting or embedded separators to handle), and every error must
//! name the line and column it is on, which is simplest when the parser counts
//! them itself.
//!
//! Accepted: a leading UTF-8 byte-order mark, `\r\n` line ends, spaces around
//! fields, blank lines (skipped). Refused, with the line (and column) named:
//! any other header, a row with the wrong number of fields, a field that is
//! not a finite number (NaN and infinities included; only `alt` may be
//! empty), a range ≤ 0, and a time that does not increase.
//!
//! # Scans
//!
//! A single-target filter needs strictly increasing times. A multi-target
//! tracker reads *scans*: consecutive rows sharing a `t` (the format the
//! `simulate` binary writes for multi-target scenarios). The readers take a
//! [`TimeOrder`]; with [`TimeOrder::Scans`] equal times are accepted (only a
//! decrease is refused) and [`Measurements::scans`] /
//! [`RangeAzimuthMeasurements::scans`] group the rows.

use std::fmt;
use std::io::BufRead;

/// Axis names, in header order.
pub const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// Column names of the range–azimuth layout, in header order (`alt` optional).
pub const RANGE_AZIMUTH_COLUMNS: [&str; 3] = ["range", "azimuth", "alt"];

/// Which layout a filter reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputFormat {
    /// `t,x`, `t,x,y` or `t,x,y,z`.
    Cartesian,
    /// `t,range,azimuth` or `t,range,azimuth,alt`.
    RangeAzimuth,
}

impl InputFormat {
    /// The accepted headers, for messages.
    pub const fn headers(self) -> &'static str {
        match self {
            InputFormat::Cartesian => "t,x or t,x,y or t,x,y,z",
            InputFormat::RangeAzimuth => "t,range,azimuth or t,range,azimuth,alt",
        }
    }

    /// The filters that read this layout, for messages.
    pub const fn filters(self) -> &'static str {
        match self {
            InputFormat::Cartesian => "--filter ab or abg",
            InputFormat::RangeAzimuth => "--filter range-azimuth",
        }
    }

    /// The layout a header line looks like, if it is one of the accepted
    /// headers (used to suggest the right `--filter`).
    fn of_header(line: &str) -> Option<InputFormat> {
        if parse_cartesian_header(line, 1).is_ok() {
            Some(InputFormat::Cartesian)
        } else if parse_range_azimuth_header(line, 1).is_ok() {
            Some(InputFormat::RangeAzimuth)
        } else {
            None
        }
    }
}

/// Whether rows may share a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TimeOrder {
    /// Every row strictly after the previous one (single-target filters).
    #[default]
    Increasing,
    /// Rows sharing a `t` form one scan; times never decrease (trackers).
    Scans,
}

/// One Cartesian measurement row.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// 1-based line number in the file.
    pub line: usize,
    /// The time as written in the file (echoed unchanged in outputs).
    pub t_text: String,
    pub t: f64,
    /// One position per axis (`dims` of them are meaningful).
    pub z: [f64; 3],
}

/// A parsed Cartesian file.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurements {
    /// 1, 2 or 3.
    pub dims: usize,
    pub rows: Vec<Row>,
}

impl Measurements {
    /// The axis names of this file: `["x"]`, `["x", "y"]` or `["x", "y", "z"]`.
    pub fn axis_names(&self) -> &'static [&'static str] {
        &AXIS_NAMES[..self.dims.min(3)]
    }

    /// The rows grouped into scans (consecutive rows sharing a `t`).
    pub fn scans(&self) -> impl Iterator<Item = &[Row]> {
        self.rows.chunk_by(|a, b| a.t == b.t)
    }
}

/// One range–azimuth measurement row.
#[derive(Debug, Clone, PartialEq)]
pub struct RangeAzimuthRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// The time as written in the file (echoed unchanged in outputs).
    pub t_text: String,
    pub t: f64,
    /// Slant range, m (> 0).
    pub range: f64,
    /// Azimuth, rad, clockwise from +y.
    pub azimuth: f64,
    /// Reported pressure altitude, ft; `None` when the file has no `alt`
    /// column or this row's field is empty.
    pub alt: Option<f64>,
}

/// A parsed range–azimuth file.
#[derive(Debug, Clone, PartialEq)]
pub struct RangeAzimuthMeasurements {
    /// Whether the header has the `alt` column.
    pub has_alt: bool,
    pub rows: Vec<RangeAzimuthRow>,
}

impl RangeAzimuthMeasurements {
    /// The rows grouped into scans (consecutive rows sharing a `t`).
    pub fn scans(&self) -> impl Iterator<Item = &[RangeAzimuthRow]> {
        self.rows.chunk_by(|a, b| a.t == b.t)
    }
}

/// Why a file could not be read. Lines and columns are 1-based.
#[derive(Debug, Clone, PartialEq)]
pub enum CsvError {
    Io(String),
    /// No header line at all (Cartesian layout).
    Empty,
    /// Not a Cartesian header.
    BadHeader {
        line: usize,
        found: String,
    },
    /// No header line at all (range–azimuth layout).
    EmptyRangeAzimuth,
    /// Not a range–azimuth header.
    BadRangeAzimuthHeader {
        line: usize,
        found: String,
    },
    FieldCount {
        line: usize,
        expected: usize,
        found: usize,
    },
    NotANumber {
        line: usize,
        column: usize,
        name: &'static str,
        text: String,
    },
    NotFinite {
        line: usize,
        column: usize,
        name: &'static str,
        text: String,
    },
    /// A range ≤ 0.
    NotPositive {
        line: usize,
        column: usize,
        name: &'static str,
        text: String,
    },
    /// A time not after the previous row's ([`TimeOrder::Increasing`]).
    TimeNotIncreasing {
        line: usize,
        t: String,
        previous: String,
    },
    /// A time before the previous row's ([`TimeOrder::Scans`]).
    TimeDecreasing {
        line: usize,
        t: String,
        previous: String,
    },
}

/// " (this header is for --filter …)" when `found` is the other layout's.
fn header_hint(found: &str, expected: InputFormat) -> String {
    match InputFormat::of_header(found) {
        Some(other) if other != expected => {
            format!(" (this header is for {})", other.filters())
        }
        _ => String::new(),
    }
}

impl fmt::Display for CsvError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CsvError::Io(e) => write!(f, "cannot read input: {e}"),
            CsvError::Empty | CsvError::EmptyRangeAzimuth => {
                let format = if *self == CsvError::Empty {
                    InputFormat::Cartesian
                } else {
                    InputFormat::RangeAzimuth
                };
                write!(
                    f,
                    "line 1: empty input, expected a header {}",
                    format.headers()
                )
            }
            CsvError::BadHeader { line, found } => write!(
                f,
                "line {line}: bad header \"{found}\", expected {}{}",
                InputFormat::Cartesian.headers(),
                header_hint(found, InputFormat::Cartesian)
            ),
            CsvError::BadRangeAzimuthHeader { line, found } => write!(
                f,
                "line {line}: bad header \"{found}\", expected {}{}",
                InputFormat::RangeAzimuth.headers(),
                header_hint(found, InputFormat::RangeAzimuth)
            ),
            CsvError::FieldCount {
                line,
                expected,
                found,
            } => write!(f, "line {line}: {found} fields, expected {expected}"),
            CsvError::NotANumber {
                line,
                column,
                name,
                text,
            } => write!(
                f,
                "line {line}, column {column} ({name}): \"{text}\" is not a number"
            ),
            CsvError::NotFinite {
                line,
                column,
                name,
                text,
            } => write!(
                f,
                "line {line}, column {column} ({name}): \"{text}\" is not a finite number"
            ),
            CsvError::NotPositive {
                line,
                column,
                name,
                text,
            } => write!(
                f,
                "line {line}, column {column} ({name}): {text} is not > 0"
            ),
            CsvError::TimeNotIncreasing { line, t, previous } => write!(
                f,
                "line {line}, column 1 (t): time {t} does not increase (previous row: {previous})"
            ),
            CsvError::TimeDecreasing { line, t, previous } => write!(
                f,
                "line {line}, column 1 (t): time {t} is before the previous row's ({previous})"
            ),
        }
    }
}

impl std::error::Error for CsvError {}

/// Strips the line end and a byte-order mark (first line only).
fn clean(line: &str, first: bool) -> &str {
    let line = line.trim_end_matches(['\n', '\r']);
    if first {
        line.trim_start_matches('\u{feff}')
    } else {
        line
    }
}

/// One column after `t`: its name and whether an empty field is allowed
/// (read as "no value").
#[derive(Debug, Clone, Copy)]
struct Column {
    name: &'static str,
    optional: bool,
    positive: bool,
}

const fn column(name: &'static str) -> Column {
    Column {
        name,
        optional: false,
        positive: false,
    }
}

const CARTESIAN_COLUMNS: [Column; 3] = [column("x"), column("y"), column("z")];
const RANGE_AZIMUTH_LAYOUT: [Column; 3] = [
    Column {
        name: "range",
        optional: false,
        positive: true,
    },
    column("azimuth"),
    Column {
        name: "alt",
        optional: true,
        positive: false,
    },
];

/// The header's fields if it is `t` followed by the first `n` of `columns`
/// for some `n` in `counts`.
fn match_header(
    line: &str,
    columns: &'static [Column],
    counts: core::ops::RangeInclusive<usize>,
) -> Option<&'static [Column]> {
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    let n = fields.len().saturating_sub(1);
    let matches = counts.contains(&n)
        && fields.first() == Some(&"t")
        && fields[1..].iter().zip(columns).all(|(f, c)| *f == c.name);
    if matches {
        columns.get(..n)
    } else {
        None
    }
}

fn parse_cartesian_header(line: &str, line_no: usize) -> Result<&'static [Column], CsvError> {
    match_header(line, &CARTESIAN_COLUMNS, 1..=3).ok_or_else(|| CsvError::BadHeader {
        line: line_no,
        found: line.to_string(),
    })
}

fn parse_range_azimuth_header(line: &str, line_no: usize) -> Result<&'static [Column], CsvError> {
    match_header(line, &RANGE_AZIMUTH_LAYOUT, 2..=3).ok_or_else(|| {
        CsvError::BadRangeAzimuthHeader {
            line: line_no,
            found: line.to_string(),
        }
    })
}

fn parse_field(
    text: &str,
    line: usize,
    column: usize,
    name: &'static str,
) -> Result<f64, CsvError> {
    let v: f64 = text.parse().map_err(|_| CsvError::NotANumber {
        line,
        column,
        name,
        text: text.to_string(),
    })?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(CsvError::NotFinite {
            line,
            column,
            name,
            text: text.to_string(),
        })
    }
}

/// A data row before it is given its layout's type.
struct RawRow {
    line: usize,
    t_text: String,
    t: f64,
    /// One per header column after `t`; `None` only for an empty optional
    /// field.
    values: Vec<Option<f64>>,
}

/// Reads the header (with `parse_header`) and every row. Stops at the first
/// error.
fn read_table<R: BufRead>(
    input: R,
    parse_header: fn(&str, usize) -> Result<&'static [Column], CsvError>,
    empty: CsvError,
    times: TimeOrder,
) -> Result<(&'static [Column], Vec<RawRow>), CsvError> {
    let mut columns: Option<&'static [Column]> = None;
    let mut rows: Vec<RawRow> = Vec::new();
    for (index, line) in input.lines().enumerate() {
        let line_no = index + 1;
        let raw = line.map_err(|e| CsvError::Io(format!("line {line_no}: {e}")))?;
        let line = clean(&raw, index == 0);
        if line.trim().is_empty() {
            continue;
        }
        let cols = match columns {
            None => {
                columns = Some(parse_header(line, line_no)?);
                continue;
            }
            Some(c) => c,
        };
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != cols.len() + 1 {
            return Err(CsvError::FieldCount {
                line: line_no,
                expected: cols.len() + 1,
                found: fields.len(),
            });
        }
        let t = parse_field(fields[0], line_no, 1, "t")?;
        let mut values = Vec::with_capacity(cols.len());
        for (i, (text, col)) in fields[1..].iter().zip(cols).enumerate() {
            let column = i + 2;
            if col.optional && text.is_empty() {
                values.push(None);
                continue;
            }
            let v = parse_field(text, line_no, column, col.name)?;
            if col.positive && v <= 0.0 {
                return Err(CsvError::NotPositive {
                    line: line_no,
                    column,
                    name: col.name,
                    text: text.to_string(),
                });
            }
            values.push(Some(v));
        }
        if let Some(prev) = rows.last() {
            let refused = match times {
                TimeOrder::Increasing => (t <= prev.t).then(|| CsvError::TimeNotIncreasing {
                    line: line_no,
                    t: fields[0].to_string(),
                    previous: prev.t_text.clone(),
                }),
                TimeOrder::Scans => (t < prev.t).then(|| CsvError::TimeDecreasing {
                    line: line_no,
                    t: fields[0].to_string(),
                    previous: prev.t_text.clone(),
                }),
            };
            if let Some(e) = refused {
                return Err(e);
            }
        }
        rows.push(RawRow {
            line: line_no,
            t_text: fields[0].to_string(),
            t,
            values,
        });
    }
    match columns {
        Some(c) => Ok((c, rows)),
        None => Err(empty),
    }
}

/// Reads a whole Cartesian file with strictly increasing times. Stops at the
/// first error.
pub fn read_measurements<R: BufRead>(input: R) -> Result<Measurements, CsvError> {
    read_measurements_with(input, TimeOrder::Increasing)
}

/// [`read_measurements`] with a choice of [`TimeOrder`].
pub fn read_measurements_with<R: BufRead>(
    input: R,
    times: TimeOrder,
) -> Result<Measurements, CsvError> {
    let (columns, raw) = read_table(input, parse_cartesian_header, CsvError::Empty, times)?;
    let rows = raw
        .into_iter()
        .map(|r| {
            let mut z = [0.0; 3];
            for (zi, v) in z.iter_mut().zip(&r.values) {
                *zi = v.unwrap_or(0.0);
            }
            Row {
                line: r.line,
                t_text: r.t_text,
                t: r.t,
                z,
            }
        })
        .collect();
    Ok(Measurements {
        dims: columns.len(),
        rows,
    })
}

/// Reads a whole range–azimuth file with strictly increasing times. Stops at
/// the first error.
pub fn read_range_azimuth<R: BufRead>(input: R) -> Result<RangeAzimuthMeasurements, CsvError> {
    read_range_azimuth_with(input, TimeOrder::Increasing)
}

/// [`read_range_azimuth`] with a choice of [`TimeOrder`].
pub fn read_range_azimuth_with<R: BufRead>(
    input: R,
    times: TimeOrder,
) -> Result<RangeAzimuthMeasurements, CsvError> {
    let (columns, raw) = read_table(
        input,
        parse_range_azimuth_header,
        CsvError::EmptyRangeAzimuth,
        times,
    )?;
    let rows = raw
        .into_iter()
        .map(|r| {
            let value = |i: usize| r.values.get(i).copied().flatten();
            RangeAzimuthRow {
                line: r.line,
                t: r.t,
                range: value(0).unwrap_or(0.0),
                azimuth: value(1).unwrap_or(0.0),
                alt: value(2),
                t_text: r.t_text,
            }
        })
        .collect();
    Ok(RangeAzimuthMeasurements {
        has_alt: columns.len() == 3,
        rows,
    })
}
