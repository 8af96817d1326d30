//! Reader for recorded measurements: a CSV file with a header `t,x`,
//! `t,x,y` or `t,x,y,z` and one row per measurement (t in seconds, positions
//! in metres).
//!
//! A small hand parser rather than the `csv` crate: the files hold only
//! numbers (no quoting or embedded separators to handle), and every error must
//! name the line and column it is on, which is simplest when the parser counts
//! them itself.
//!
//! Accepted: a leading UTF-8 byte-order mark, `\r\n` line ends, spaces around
//! fields, blank lines (skipped). Refused, with the line (and column) named:
//! any other header, a row with the wrong number of fields, a field that is
//! not a finite number (NaN and infinities included), and a time that does not
//! increase.

use std::fmt;
use std::io::BufRead;

/// Axis names, in header order.
pub const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// One measurement row.
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

/// A parsed file.
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
}

/// Why a file could not be read. Lines and columns are 1-based.
#[derive(Debug, Clone, PartialEq)]
pub enum CsvError {
    Io(String),
    /// No header line at all.
    Empty,
    BadHeader {
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
    TimeNotIncreasing {
        line: usize,
        t: String,
        previous: String,
    },
}

impl fmt::Display for CsvError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CsvError::Io(e) => write!(f, "cannot read input: {e}"),
            CsvError::Empty => {
                write!(
                    f,
                    "line 1: empty input, expected a header t,x or t,x,y or t,x,y,z"
                )
            }
            CsvError::BadHeader { line, found } => write!(
                f,
                "line {line}: bad header \"{found}\", expected t,x or t,x,y or t,x,y,z"
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
            CsvError::TimeNotIncreasing { line, t, previous } => write!(
                f,
                "line {line}, column 1 (t): time {t} does not increase (previous row: {previous})"
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

fn parse_header(line: &str, line_no: usize) -> Result<usize, CsvError> {
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    let dims = fields.len().saturating_sub(1);
    let matches = (1..=3).contains(&dims)
        && fields[0] == "t"
        && fields[1..]
            .iter()
            .zip(AXIS_NAMES.iter())
            .all(|(f, n)| f == n);
    if matches {
        Ok(dims)
    } else {
        Err(CsvError::BadHeader {
            line: line_no,
            found: line.to_string(),
        })
    }
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

/// Reads a whole file. Stops at the first error.
pub fn read_measurements<R: BufRead>(input: R) -> Result<Measurements, CsvError> {
    let mut dims = None;
    let mut rows: Vec<Row> = Vec::new();
    for (index, line) in input.lines().enumerate() {
        let line_no = index + 1;
        let raw = line.map_err(|e| CsvError::Io(format!("line {line_no}: {e}")))?;
        let line = clean(&raw, index == 0);
        if line.trim().is_empty() {
            continue;
        }
        let d = match dims {
            None => {
                dims = Some(parse_header(line, line_no)?);
                continue;
            }
            Some(d) => d,
        };
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != d + 1 {
            return Err(CsvError::FieldCount {
                line: line_no,
                expected: d + 1,
                found: fields.len(),
            });
        }
        let t = parse_field(fields[0], line_no, 1, "t")?;
        let mut z = [0.0; 3];
        for (i, text) in fields[1..].iter().enumerate() {
            z[i] = parse_field(text, line_no, i + 2, AXIS_NAMES[i])?;
        }
        if let Some(prev) = rows.last() {
            if t <= prev.t {
                return Err(CsvError::TimeNotIncreasing {
                    line: line_no,
                    t: fields[0].to_string(),
                    previous: prev.t_text.clone(),
                });
            }
        }
        rows.push(Row {
            line: line_no,
            t_text: fields[0].to_string(),
            t,
            z,
        });
    }
    match dims {
        Some(dims) => Ok(Measurements { dims, rows }),
        None => Err(CsvError::Empty),
    }
}
