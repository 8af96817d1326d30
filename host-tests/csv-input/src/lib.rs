//! Reader for recorded measurements (the `csv` crate, rows deserialised by
//! header name with serde), in one of two layouts ([`InputFormat`]):
//!
//! * Cartesian (`--filter ab|abg`, `--tracker` on x/y data): columns `t` and
//!   `x`, optionally `y` and `z` (t in seconds, positions in metres);
//! * range–azimuth (`--filter range-azimuth`, `--tracker` on polar data):
//!   columns `t`, `range` (slant range, m, > 0) and `azimuth` (clockwise from
//!   +y: x = R sin B, y = R cos B; radians, or degrees with
//!   [`AngleUnit::Degrees`]).
//!
//! In both, an optional `alt` column holds the target's reported pressure
//! altitude in feet; an empty field, or `NaN` in any case (numpy's and
//! many exporters' missing value), means the reply carried none. The header
//! is matched by name: the columns may come in any order, and columns with
//! other names are ignored. Accepted: a UTF-8 byte-order mark, `\r\n` line
//! ends, spaces around fields, quoted fields, blank lines (also lines of
//! nothing but spaces or tabs).
//!
//! Refused, with the line (and column) named and at most a short prefix of
//! the field echoed: a header without the required columns, a row with
//! another number of fields than the header, a field that is not a number,
//! and a value outside [`abtrack::envelope`] (positions and ranges beyond
//! 400 km, altitudes outside −1000 … 126 700 ft, an azimuth beyond one turn,
//! a time stamp beyond 2³³ s). A radian azimuth beyond 2π is refused with
//! a message naming `--azimuth-unit deg`: the unit is never guessed.
//!
//! Timing is never a reason to refuse a file: gaps, jitter and rows out of
//! time order are the runners' business (an interval beyond the filters'
//! range restarts the estimate; a row too soon after, at or before the
//! last one used, or a scan before the previous one, is skipped and
//! counted, `docs/host-tools.md`).
//!
//! # Scans
//!
//! A single-target filter reads one report per row
//! ([`TimeOrder::Increasing`]); a row with the same time as the previous
//! one (a duplicate report) is read, and skipped by the runner. A
//! multi-target tracker reads *scans* ([`TimeOrder::Scans`]): consecutive
//! rows sharing a `t` are one scan ([`Measurements::scans`],
//! [`RangeAzimuthMeasurements::scans`] group the rows).

use std::fmt;
use std::io::Read;

use abtrack::envelope::{self, Limit};
use serde::Deserialize;

/// Axis names, in output order.
pub const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// The longest prefix of a bad field echoed in a message, in characters.
pub const ECHO_CHARS: usize = 24;

/// Which layout a file is read as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputFormat {
    /// Columns `t`, `x` and optionally `y`, `z`, `alt`.
    Cartesian,
    /// Columns `t`, `range`, `azimuth` and optionally `alt`.
    RangeAzimuth,
}

impl InputFormat {
    /// The columns this layout needs.
    pub const fn required(self) -> &'static [&'static str] {
        match self {
            InputFormat::Cartesian => &["t", "x"],
            InputFormat::RangeAzimuth => &["t", "range", "azimuth"],
        }
    }

    /// The columns this layout reads when present.
    pub const fn optional(self) -> &'static str {
        match self {
            InputFormat::Cartesian => "y, z (needs y), alt",
            InputFormat::RangeAzimuth => "alt",
        }
    }
}

/// The unit of the `azimuth` column (`--azimuth-unit rad|deg` with the
/// feature `clap`, which the host tools turn on).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum AngleUnit {
    /// Radians (the default).
    #[default]
    #[cfg_attr(feature = "clap", value(name = "rad"))]
    Radians,
    /// Degrees.
    #[cfg_attr(feature = "clap", value(name = "deg"))]
    Degrees,
}

/// Whether rows may share a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TimeOrder {
    /// One report per row (single-target filters; a row at or before the
    /// last one used, a duplicate or late report, is skipped by the
    /// runner).
    #[default]
    Increasing,
    /// Rows sharing a `t` form one scan (trackers; a scan before the
    /// previous one is skipped by the runner).
    Scans,
}

/// How to read a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReadOptions {
    pub times: TimeOrder,
    pub azimuth_unit: AngleUnit,
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
    /// The `alt` column (checked, not used by the Cartesian filters).
    pub alt: Option<f64>,
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
        AXIS_NAMES.get(..self.dims).unwrap_or(&AXIS_NAMES)
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
    /// Azimuth, rad, clockwise from +y (converted from degrees when the
    /// file is read with [`AngleUnit::Degrees`]).
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

/// A file in whichever layout its header has ([`read_recording`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Recording {
    Cartesian(Measurements),
    RangeAzimuth(RangeAzimuthMeasurements),
}

/// Why a value is refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Refusal {
    /// Not a number (or empty where a value is required).
    NotANumber,
    /// NaN or infinite.
    NotFinite,
    /// Outside the envelope (`limit`, in `unit`).
    OutOfEnvelope { limit: Limit, unit: &'static str },
    /// A radian azimuth beyond one turn: degrees without the option.
    LooksLikeDegrees,
    /// A range ≤ 0.
    NotPositive,
}

/// Why a file could not be read. Lines and columns are 1-based.
#[derive(Debug, Clone, PartialEq)]
pub enum CsvError {
    Io(String),
    /// Malformed CSV (e.g. invalid UTF-8, an unterminated quote).
    Malformed {
        line: usize,
        message: String,
    },
    /// No header line at all.
    Empty {
        format: Option<InputFormat>,
    },
    /// The header lacks columns the layout needs.
    MissingColumns {
        format: InputFormat,
        missing: Vec<&'static str>,
        found: String,
    },
    /// A column name appears twice.
    DuplicateColumn {
        name: String,
    },
    /// `read_recording`: neither layout's columns, or both.
    UnknownLayout {
        found: String,
        both: bool,
    },
    FieldCount {
        line: usize,
        expected: usize,
        found: usize,
    },
    /// A field refused; `text` is at most [`ECHO_CHARS`] of it.
    Field {
        line: usize,
        column: usize,
        name: &'static str,
        text: String,
        why: Refusal,
    },
}

/// At most [`ECHO_CHARS`] characters of `text`, with `…` when cut.
pub fn echo(text: &str) -> String {
    let mut chars = text.chars();
    let head: String = chars.by_ref().take(ECHO_CHARS).collect();
    if chars.next().is_some() {
        format!("{head}…")
    } else {
        head
    }
}

fn columns_text(names: &[&str]) -> String {
    names.join(", ")
}

impl fmt::Display for CsvError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let required = |format: InputFormat| {
            format!(
                "{} (optional: {})",
                columns_text(format.required()),
                format.optional()
            )
        };
        match self {
            CsvError::Io(e) => write!(f, "cannot read input: {e}"),
            CsvError::Malformed { line, message } => write!(f, "line {line}: {message}"),
            CsvError::Empty { format } => match format {
                Some(format) => write!(
                    f,
                    "line 1: empty input, expected a header with the columns {}",
                    required(*format)
                ),
                None => write!(
                    f,
                    "line 1: empty input, expected a header with the columns {} or {}",
                    required(InputFormat::Cartesian),
                    required(InputFormat::RangeAzimuth)
                ),
            },
            CsvError::MissingColumns {
                format,
                missing,
                found,
            } => {
                write!(
                    f,
                    "line 1: the header \"{found}\" has no column {}; this input needs the \
                     columns {} in any order, other columns are ignored",
                    columns_text(missing),
                    required(*format)
                )?;
                let other = match format {
                    InputFormat::Cartesian => InputFormat::RangeAzimuth,
                    InputFormat::RangeAzimuth => InputFormat::Cartesian,
                };
                if has_columns(found, other.required()) {
                    let filters = match other {
                        InputFormat::Cartesian => "--filter ab or abg",
                        InputFormat::RangeAzimuth => "--filter range-azimuth",
                    };
                    write!(f, " (this header is for {filters})")?;
                }
                Ok(())
            }
            CsvError::DuplicateColumn { name } => {
                write!(f, "line 1: the header has the column \"{name}\" twice")
            }
            CsvError::UnknownLayout { found, both } => {
                if *both {
                    write!(
                        f,
                        "line 1: the header \"{found}\" has both x, y and range, azimuth \
                         columns; keep one pair"
                    )
                } else {
                    write!(
                        f,
                        "line 1: the header \"{found}\" has neither t, x, y nor t, range, \
                         azimuth (columns in any order, other columns ignored)"
                    )
                }
            }
            CsvError::FieldCount {
                line,
                expected,
                found,
            } => write!(
                f,
                "line {line}: {found} fields, expected {expected} (one per header column)"
            ),
            CsvError::Field {
                line,
                column,
                name,
                text,
                why,
            } => {
                write!(f, "line {line}, column {column} ({name}): ")?;
                match why {
                    Refusal::NotANumber if text.is_empty() => write!(f, "empty, expected a number"),
                    Refusal::NotANumber => write!(f, "\"{text}\" is not a number"),
                    Refusal::NotFinite => write!(f, "\"{text}\" is not a finite number"),
                    Refusal::NotPositive => write!(f, "{text} is not > 0"),
                    Refusal::OutOfEnvelope { limit, unit } => write!(
                        f,
                        "{text} is outside the envelope {} ..= {} {unit}",
                        limit.min, limit.max
                    ),
                    Refusal::LooksLikeDegrees => write!(
                        f,
                        "{text} is beyond one turn in radians (2π); if the column is in \
                         degrees, say so with --azimuth-unit deg"
                    ),
                }
            }
        }
    }
}

impl std::error::Error for CsvError {}

/// Whether a header line holds every name of `names`.
fn has_columns(header: &str, names: &[&str]) -> bool {
    let fields: Vec<&str> = header.split(',').map(str::trim).collect();
    names.iter().all(|n| fields.contains(n))
}

/// A Cartesian row as serde reads it by header name.
#[derive(Debug, Deserialize)]
struct CartesianFields {
    t: Option<f64>,
    x: Option<f64>,
    y: Option<f64>,
    z: Option<f64>,
    alt: Option<f64>,
}

/// A range–azimuth row as serde reads it by header name.
#[derive(Debug, Deserialize)]
struct PolarFields {
    t: Option<f64>,
    range: Option<f64>,
    azimuth: Option<f64>,
    alt: Option<f64>,
}

/// The header, parsed: each known column's index.
struct Header {
    names: Vec<String>,
    record: csv::StringRecord,
    lines: Lines,
}

impl Header {
    fn index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
    fn has(&self, name: &str) -> bool {
        self.index(name).is_some()
    }
    fn text(&self) -> String {
        echo(&self.names.join(","))
    }
    /// The line a record starts on.
    fn line_of(&self, record: &csv::StringRecord) -> usize {
        record.position().map_or(0, |p| self.lines.line(p.byte()))
    }
}

/// The input's bytes and where its lines start. The `csv` crate's own line
/// count skips blank lines, so lines are counted here from a record's byte
/// offset.
struct Lines {
    starts: Vec<u64>,
    /// Whether each byte is a line end (a record's offset can point at the
    /// blank lines before it).
    line_end: Vec<bool>,
}

impl Lines {
    fn new(bytes: &[u8]) -> Self {
        let starts = std::iter::once(0)
            .chain(
                bytes
                    .iter()
                    .enumerate()
                    .filter(|(_, b)| **b == b'\n')
                    .map(|(i, _)| i as u64 + 1),
            )
            .collect();
        let line_end = bytes.iter().map(|b| matches!(b, b'\n' | b'\r')).collect();
        Lines { starts, line_end }
    }

    /// The 1-based line of the first byte at or after `offset` that is not
    /// a line end.
    fn line(&self, offset: u64) -> usize {
        let skipped = self
            .line_end
            .iter()
            .skip(offset as usize)
            .take_while(|end| **end)
            .count();
        let offset = offset + skipped as u64;
        self.starts.partition_point(|&s| s <= offset).max(1)
    }
}

/// Lines of nothing but spaces and tabs made blank (their bytes turned into
/// `\r`, at the same offsets: the line breaks stay where they were), so
/// that the reader skips them as it skips empty lines. (Inside a quoted
/// field such a line becomes `\r`s: only text columns, which are not read,
/// can hold one.)
fn blank_whitespace_lines(bytes: &mut [u8]) {
    for line in bytes.split_mut(|b| *b == b'\n') {
        if line.iter().any(|b| matches!(b, b' ' | b'\t'))
            && line.iter().all(|b| matches!(b, b' ' | b'\t' | b'\r'))
        {
            line.fill(b'\r');
        }
    }
}

type Reader = csv::Reader<std::io::Cursor<Vec<u8>>>;

/// A CSV reader over the whole input and its header.
fn open<R: Read>(mut input: R, format: Option<InputFormat>) -> Result<(Reader, Header), CsvError> {
    let mut bytes = Vec::new();
    input
        .read_to_end(&mut bytes)
        .map_err(|e| CsvError::Io(e.to_string()))?;
    blank_whitespace_lines(&mut bytes);
    let lines = Lines::new(&bytes);
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .has_headers(true)
        .from_reader(std::io::Cursor::new(bytes));
    let record = reader.headers().map_err(|e| csv_error(e, &lines))?.clone();
    let names: Vec<String> = record
        .iter()
        .map(|n| n.trim_start_matches('\u{feff}').trim().to_string())
        .collect();
    if names.iter().all(String::is_empty) {
        return Err(CsvError::Empty { format });
    }
    for (i, n) in names.iter().enumerate() {
        if !n.is_empty() && names.iter().skip(i + 1).any(|m| m == n) {
            return Err(CsvError::DuplicateColumn { name: echo(n) });
        }
    }
    // serde matches the cleaned names (a BOM is not part of the first one).
    let record = csv::StringRecord::from(names.clone());
    Ok((
        reader,
        Header {
            names,
            record,
            lines,
        },
    ))
}

fn csv_error(e: csv::Error, lines: &Lines) -> CsvError {
    let line = e.position().map_or(0, |p| lines.line(p.byte()));
    let message = e.to_string();
    match e.into_kind() {
        csv::ErrorKind::Io(e) => CsvError::Io(e.to_string()),
        csv::ErrorKind::UnequalLengths {
            pos,
            expected_len,
            len,
        } => CsvError::FieldCount {
            line: pos.map_or(line, |p| lines.line(p.byte())),
            expected: expected_len as usize,
            found: len as usize,
        },
        _ => CsvError::Malformed { line, message },
    }
}

/// Where a value is, for the checks.
struct Cell<'a> {
    line: usize,
    header: &'a Header,
    record: &'a csv::StringRecord,
}

impl Cell<'_> {
    fn refuse(&self, name: &'static str, why: Refusal) -> CsvError {
        let index = self.header.index(name).unwrap_or(0);
        CsvError::Field {
            line: self.line,
            column: index + 1,
            name,
            text: echo(self.record.get(index).unwrap_or("")),
            why,
        }
    }

    /// A required value, finite and inside `limit`.
    fn value(
        &self,
        name: &'static str,
        v: Option<f64>,
        limit: Limit,
        unit: &'static str,
    ) -> Result<f64, CsvError> {
        let v = v.ok_or_else(|| self.refuse(name, Refusal::NotANumber))?;
        if !v.is_finite() {
            return Err(self.refuse(name, Refusal::NotFinite));
        }
        if !limit.contains(v) {
            return Err(self.refuse(name, Refusal::OutOfEnvelope { limit, unit }));
        }
        Ok(v)
    }

    /// The row's `t` as written.
    fn t_text(&self) -> String {
        let index = self.header.index("t").unwrap_or(0);
        self.record.get(index).unwrap_or("").to_string()
    }

    /// `alt`, which may be empty or NaN (no altitude reported); an infinity
    /// is refused.
    fn altitude(&self, v: Option<f64>) -> Result<Option<f64>, CsvError> {
        match v {
            None => Ok(None),
            Some(v) if v.is_nan() => Ok(None),
            Some(v) => self
                .value("alt", Some(v), envelope::ALTITUDE_FT, "ft")
                .map(Some),
        }
    }
}

/// A serde error of one row, located.
fn field_error(
    e: csv::Error,
    line: usize,
    header: &Header,
    record: &csv::StringRecord,
) -> CsvError {
    if let csv::ErrorKind::Deserialize { err, .. } = e.kind() {
        if let Some(index) = err.field().map(|i| i as usize) {
            let name = header.names.get(index).map_or("?", String::as_str);
            let name = KNOWN_COLUMNS
                .iter()
                .find(|k| **k == name)
                .copied()
                .unwrap_or("?");
            return CsvError::Field {
                line,
                column: index + 1,
                name,
                text: echo(record.get(index).unwrap_or("")),
                why: Refusal::NotANumber,
            };
        }
    }
    csv_error(e, &header.lines)
}

const KNOWN_COLUMNS: [&str; 7] = ["t", "x", "y", "z", "range", "azimuth", "alt"];

/// A row's time (and as written), for the scans.
pub trait Timed {
    fn time(&self) -> (f64, &str);
}

impl Timed for Row {
    fn time(&self) -> (f64, &str) {
        (self.t, &self.t_text)
    }
}

impl Timed for RangeAzimuthRow {
    fn time(&self) -> (f64, &str) {
        (self.t, &self.t_text)
    }
}

/// Every record after the header: deserialised by column name into `F`,
/// checked and converted by `row`. Stops at the first error.
fn read_rows<F: serde::de::DeserializeOwned, T>(
    mut reader: Reader,
    header: &Header,
    row: impl Fn(&Cell<'_>, F) -> Result<T, CsvError>,
) -> Result<Vec<T>, CsvError> {
    let mut rows: Vec<T> = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| csv_error(e, &header.lines))?;
        let line = header.line_of(&record);
        let fields: F = record
            .deserialize(Some(&header.record))
            .map_err(|e| field_error(e, line, header, &record))?;
        let cell = Cell {
            line,
            header,
            record: &record,
        };
        rows.push(row(&cell, fields)?);
    }
    Ok(rows)
}

/// Reads a whole Cartesian file. Stops at the first error. (`_options`:
/// neither the time order, which only groups the rows, nor the azimuth
/// unit changes how Cartesian rows are read.)
pub fn read_measurements<R: Read>(
    input: R,
    _options: ReadOptions,
) -> Result<Measurements, CsvError> {
    let (reader, header) = open(input, Some(InputFormat::Cartesian))?;
    cartesian_rows(reader, header)
}

fn cartesian_rows(reader: Reader, header: Header) -> Result<Measurements, CsvError> {
    let missing: Vec<&'static str> = ["t", "x"]
        .into_iter()
        .chain(if header.has("z") { Some("y") } else { None })
        .filter(|n| !header.has(n))
        .collect();
    if !missing.is_empty() {
        return Err(CsvError::MissingColumns {
            format: InputFormat::Cartesian,
            missing,
            found: header.text(),
        });
    }
    let dims = 1 + usize::from(header.has("y")) + usize::from(header.has("z"));
    let rows = read_rows(reader, &header, |cell, fields: CartesianFields| {
        let t = cell.value("t", fields.t, envelope::TIME_S, "s")?;
        let mut z = [0.0; 3];
        for ((zi, name), v) in z
            .iter_mut()
            .zip(AXIS_NAMES)
            .zip([fields.x, fields.y, fields.z])
            .take(dims)
        {
            *zi = cell.value(name, v, envelope::POSITION_M, "m")?;
        }
        Ok(Row {
            line: cell.line,
            t_text: cell.t_text(),
            t,
            z,
            alt: cell.altitude(fields.alt)?,
        })
    })?;
    Ok(Measurements { dims, rows })
}

/// Reads a whole range–azimuth file. Stops at the first error.
pub fn read_range_azimuth<R: Read>(
    input: R,
    options: ReadOptions,
) -> Result<RangeAzimuthMeasurements, CsvError> {
    let (reader, header) = open(input, Some(InputFormat::RangeAzimuth))?;
    polar_rows(reader, header, options)
}

fn polar_rows(
    reader: Reader,
    header: Header,
    options: ReadOptions,
) -> Result<RangeAzimuthMeasurements, CsvError> {
    let missing: Vec<&'static str> = InputFormat::RangeAzimuth
        .required()
        .iter()
        .copied()
        .filter(|n| !header.has(n))
        .collect();
    if !missing.is_empty() {
        return Err(CsvError::MissingColumns {
            format: InputFormat::RangeAzimuth,
            missing,
            found: header.text(),
        });
    }
    let rows = read_rows(reader, &header, |cell, fields: PolarFields| {
        let t = cell.value("t", fields.t, envelope::TIME_S, "s")?;
        let range = cell.value("range", fields.range, envelope::RANGE_M, "m")?;
        if range <= 0.0 {
            return Err(cell.refuse("range", Refusal::NotPositive));
        }
        let azimuth = match options.azimuth_unit {
            AngleUnit::Radians => {
                let b = fields
                    .azimuth
                    .ok_or_else(|| cell.refuse("azimuth", Refusal::NotANumber))?;
                if b.is_finite() && !envelope::AZIMUTH_RAD.contains(b) {
                    return Err(cell.refuse("azimuth", Refusal::LooksLikeDegrees));
                }
                cell.value("azimuth", Some(b), envelope::AZIMUTH_RAD, "rad")?
            }
            AngleUnit::Degrees => cell
                .value("azimuth", fields.azimuth, envelope::AZIMUTH_DEG, "°")?
                .to_radians(),
        };
        Ok(RangeAzimuthRow {
            line: cell.line,
            t_text: cell.t_text(),
            t,
            range,
            azimuth,
            alt: cell.altitude(fields.alt)?,
        })
    })?;
    Ok(RangeAzimuthMeasurements {
        has_alt: header.has("alt"),
        rows,
    })
}

/// Reads a whole file in the layout its header has: `range` and `azimuth`
/// columns make it range–azimuth, `x` and `y` Cartesian (both pairs, or
/// neither, is refused).
pub fn read_recording<R: Read>(input: R, options: ReadOptions) -> Result<Recording, CsvError> {
    let (reader, header) = open(input, None)?;
    let polar = header.has("range") && header.has("azimuth");
    let cartesian = header.has("x") && header.has("y");
    match (cartesian, polar) {
        (true, false) => cartesian_rows(reader, header).map(Recording::Cartesian),
        (false, true) => polar_rows(reader, header, options).map(Recording::RangeAzimuth),
        (both, _) => Err(CsvError::UnknownLayout {
            found: header.text(),
            both,
        }),
    }
}
