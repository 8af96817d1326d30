//! The benchmark report: turns the benchmark firmware's output lines
//! (boards/qemu/src/bin/bench/) into `bench/results.csv` and `bench/BENCHMARKS.md` (the
//! `bench_report` tool, run by `scripts/bench.sh`).
//!
//! # The lines
//!
//! The firmware writes one line per fact, fields separated by commas, no
//! field containing a comma or a space:
//!
//! ```text
//! bench-meta,<core>,<key>,<value>
//! bench-figure,<core>,<numeric>,<operation>,<n>,<m>,<instructions>
//! bench-count,<core>,<numeric>,<operation>,<n>,<m>,<counter>,<value>
//! bench-omitted,<core>,<numeric>,<operation>,<reason>
//! bench-end,<core>,<figures>,<counts>
//! ```
//!
//! * `core`, `numeric`, `key`, `counter`, `reason`: lower-case letters,
//!   digits and `_`;
//!   `operation` may also contain `/` (a scan's stage: `scan_crowded/gate`).
//! * `n`, `m`: tracks and measurements per scan, both positive integers or
//!   both empty (operations that are not a scan).
//! * `instructions`: a decimal with exactly one digit after the point.
//! * `bench-omitted`: an operation this image does not measure in a numeric
//!   type, and why ([`OMISSIONS`] explains each reason).
//! * `bench-end` closes a run and says how many figure and count lines came
//!   before it: a run cut short is refused.
//!
//! Every other line (the firmware's own messages, defmt-print's) is
//! ignored; a line that starts with `bench-` and does not match is refused
//! with its line number. One log holds one core's run.

use std::collections::BTreeMap;
use std::fmt;

/// The command that writes the report files (named in both).
pub const COMMAND: &str = "bash scripts/bench.sh";

/// The header of results.csv.
pub const CSV_HEADER: &str = "core,numeric,operation,n,m,instructions";

/// Instructions per call, in tenths (the lines carry one decimal).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Tenths(pub u64);

impl Tenths {
    pub fn value(self) -> f64 {
        self.0 as f64 / 10.0
    }
}

impl fmt::Display for Tenths {
    /// As in the lines: `1234.5`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{}", self.0 / 10, self.0 % 10)
    }
}

/// Tracks and measurements per scan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct ScanSize {
    pub n: u32,
    pub m: u32,
}

/// One `bench-figure` line.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub core: String,
    pub numeric: String,
    pub operation: String,
    pub size: Option<ScanSize>,
    pub instructions: Tenths,
}

/// One `bench-count` line.
#[derive(Debug, Clone, PartialEq)]
pub struct Count {
    pub core: String,
    pub numeric: String,
    pub operation: String,
    pub size: ScanSize,
    pub counter: String,
    pub value: u64,
}

/// One `bench-omitted` line: a row this image does not measure.
#[derive(Debug, Clone, PartialEq)]
pub struct Omitted {
    pub core: String,
    pub numeric: String,
    pub operation: String,
    pub reason: String,
}

/// A parsed line.
#[derive(Debug, Clone, PartialEq)]
pub enum Line {
    Meta {
        core: String,
        key: String,
        value: String,
    },
    Figure(Figure),
    Count(Count),
    Omitted(Omitted),
    End {
        core: String,
        figures: usize,
        counts: usize,
    },
}

/// Why a log was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReportError {
    /// A `bench-` line that does not match its format.
    Malformed { line: usize, why: String },
    /// A line about another core than the log's first.
    MixedCores {
        line: usize,
        expected: String,
        found: String,
    },
    /// The same figure, count or meta key twice.
    Duplicate { line: usize, what: String },
    /// A line after the end line.
    AfterEnd { line: usize },
    /// No end line: the run did not finish.
    NoEnd,
    /// The end line's counts differ from the lines seen.
    CountMismatch {
        figures_expected: usize,
        figures_seen: usize,
        counts_expected: usize,
        counts_seen: usize,
    },
    /// Two logs of the same core.
    CoreTwice(String),
    /// No log given.
    NoRuns,
}

impl fmt::Display for ReportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::Malformed { line, why } => write!(f, "line {line}: malformed: {why}"),
            ReportError::MixedCores {
                line,
                expected,
                found,
            } => write!(
                f,
                "line {line}: core '{found}' in the log of core '{expected}' (one core per log)"
            ),
            ReportError::Duplicate { line, what } => write!(f, "line {line}: {what} twice"),
            ReportError::AfterEnd { line } => write!(f, "line {line}: after the end line"),
            ReportError::NoEnd => f.write_str(
                "no bench-end line: the benchmark did not run to its end (see its log for the error)",
            ),
            ReportError::CountMismatch {
                figures_expected,
                figures_seen,
                counts_expected,
                counts_seen,
            } => write!(
                f,
                "the end line announces {figures_expected} figures and {counts_expected} counts, \
                 the log has {figures_seen} and {counts_seen}"
            ),
            ReportError::CoreTwice(c) => write!(f, "two logs of core '{c}'"),
            ReportError::NoRuns => f.write_str("no benchmark log given"),
        }
    }
}

impl std::error::Error for ReportError {}

fn is_name(s: &str, extra: &[char]) -> bool {
    !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_' || extra.contains(&c))
}

fn name(field: &str, what: &str) -> Result<String, String> {
    if is_name(field, &[]) {
        Ok(field.to_string())
    } else {
        Err(format!(
            "{what} '{field}' is not lower-case letters, digits and _"
        ))
    }
}

fn operation(field: &str) -> Result<String, String> {
    if is_name(field, &['/']) && !field.starts_with('/') && !field.ends_with('/') {
        Ok(field.to_string())
    } else {
        Err(format!(
            "operation '{field}' is not lower-case letters, digits, _ and /"
        ))
    }
}

fn positive(field: &str, what: &str) -> Result<u32, String> {
    match field.parse::<u32>() {
        Ok(v) if v > 0 && field.chars().all(|c| c.is_ascii_digit()) => Ok(v),
        _ => Err(format!("{what} '{field}' is not a positive integer")),
    }
}

fn unsigned(field: &str, what: &str) -> Result<u64, String> {
    if !field.is_empty() && field.chars().all(|c| c.is_ascii_digit()) {
        field
            .parse::<u64>()
            .map_err(|_| format!("{what} '{field}' is too large"))
    } else {
        Err(format!("{what} '{field}' is not an unsigned integer"))
    }
}

fn size(n: &str, m: &str) -> Result<Option<ScanSize>, String> {
    match (n.is_empty(), m.is_empty()) {
        (true, true) => Ok(None),
        (false, false) => Ok(Some(ScanSize {
            n: positive(n, "n")?,
            m: positive(m, "m")?,
        })),
        _ => Err(format!(
            "n '{n}' and m '{m}': both empty or both set (tracks, measurements per scan)"
        )),
    }
}

fn tenths(field: &str) -> Result<Tenths, String> {
    let bad = || format!("instructions '{field}' is not a decimal with one digit after the point");
    let (whole, tenth) = field.split_once('.').ok_or_else(bad)?;
    if tenth.len() != 1 {
        return Err(bad());
    }
    let whole = unsigned(whole, "instructions").map_err(|_| bad())?;
    let tenth = unsigned(tenth, "instructions").map_err(|_| bad())?;
    whole
        .checked_mul(10)
        .and_then(|w| w.checked_add(tenth))
        .map(Tenths)
        .ok_or_else(bad)
}

/// Parses one line: `Ok(None)` for a line that is not a benchmark line.
pub fn parse_line(line: &str) -> Result<Option<Line>, String> {
    let line = line.trim_end();
    if !line.starts_with("bench-") {
        return Ok(None);
    }
    let fields: Vec<&str> = line.split(',').collect();
    let expect = |n: usize| {
        if fields.len() == n {
            Ok(())
        } else {
            Err(format!(
                "{} has {} fields, not {n}",
                fields.first().copied().unwrap_or(""),
                fields.len()
            ))
        }
    };
    let f = |i: usize| fields.get(i).copied().unwrap_or("");
    let parsed = match f(0) {
        "bench-meta" => {
            expect(4)?;
            let value = f(3);
            if value.is_empty() {
                return Err("meta value is empty".into());
            }
            Line::Meta {
                core: name(f(1), "core")?,
                key: name(f(2), "key")?,
                value: value.to_string(),
            }
        }
        "bench-figure" => {
            expect(7)?;
            Line::Figure(Figure {
                core: name(f(1), "core")?,
                numeric: name(f(2), "numeric")?,
                operation: operation(f(3))?,
                size: size(f(4), f(5))?,
                instructions: tenths(f(6))?,
            })
        }
        "bench-count" => {
            expect(8)?;
            let Some(size) = size(f(4), f(5))? else {
                return Err("a count needs n and m".into());
            };
            Line::Count(Count {
                core: name(f(1), "core")?,
                numeric: name(f(2), "numeric")?,
                operation: operation(f(3))?,
                size,
                counter: name(f(6), "counter")?,
                value: unsigned(f(7), "value")?,
            })
        }
        "bench-omitted" => {
            expect(5)?;
            Line::Omitted(Omitted {
                core: name(f(1), "core")?,
                numeric: name(f(2), "numeric")?,
                operation: operation(f(3))?,
                reason: name(f(4), "reason")?,
            })
        }
        "bench-end" => {
            expect(4)?;
            Line::End {
                core: name(f(1), "core")?,
                figures: unsigned(f(2), "figures")? as usize,
                counts: unsigned(f(3), "counts")? as usize,
            }
        }
        other => return Err(format!("unknown line kind '{other}'")),
    };
    Ok(Some(parsed))
}

/// One core's complete run.
#[derive(Debug, Clone, PartialEq)]
pub struct CoreRun {
    pub core: String,
    /// `bench-meta` keys and values, in the order given.
    pub meta: Vec<(String, String)>,
    /// In the order given.
    pub figures: Vec<Figure>,
    pub counts: Vec<Count>,
    /// The rows not measured, in the order given.
    pub omitted: Vec<Omitted>,
}

impl CoreRun {
    pub fn meta(&self, key: &str) -> Option<&str> {
        self.meta
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The figure of (numeric, operation, size), if measured.
    pub fn figure(&self, numeric: &str, operation: &str, size: Option<ScanSize>) -> Option<Tenths> {
        self.figures
            .iter()
            .find(|f| f.numeric == numeric && f.operation == operation && f.size == size)
            .map(|f| f.instructions)
    }

    /// The count of (numeric, operation, size, counter), if reported.
    pub fn count(
        &self,
        numeric: &str,
        operation: &str,
        size: ScanSize,
        counter: &str,
    ) -> Option<u64> {
        self.counts
            .iter()
            .find(|c| {
                c.numeric == numeric
                    && c.operation == operation
                    && c.size == size
                    && c.counter == counter
            })
            .map(|c| c.value)
    }
}

/// Parses one core's log (see the module docs for what is refused).
pub fn parse_log(text: &str) -> Result<CoreRun, ReportError> {
    let mut core: Option<String> = None;
    let mut run = CoreRun {
        core: String::new(),
        meta: Vec::new(),
        figures: Vec::new(),
        counts: Vec::new(),
        omitted: Vec::new(),
    };
    let mut end: Option<(usize, usize)> = None;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let parsed = parse_line(raw).map_err(|why| ReportError::Malformed { line, why })?;
        let Some(parsed) = parsed else { continue };
        if end.is_some() {
            return Err(ReportError::AfterEnd { line });
        }
        let this_core = match &parsed {
            Line::Meta { core, .. } | Line::End { core, .. } => core,
            Line::Figure(f) => &f.core,
            Line::Count(c) => &c.core,
            Line::Omitted(o) => &o.core,
        };
        match &core {
            None => core = Some(this_core.clone()),
            Some(expected) if expected != this_core => {
                return Err(ReportError::MixedCores {
                    line,
                    expected: expected.clone(),
                    found: this_core.clone(),
                })
            }
            Some(_) => {}
        }
        match parsed {
            Line::Meta { key, value, .. } => {
                if run.meta(&key).is_some() {
                    return Err(ReportError::Duplicate {
                        line,
                        what: format!("meta '{key}'"),
                    });
                }
                run.meta.push((key, value));
            }
            Line::Figure(fig) => {
                let omitted = run
                    .omitted
                    .iter()
                    .any(|o| o.numeric == fig.numeric && o.operation == fig.operation);
                if omitted || run.figure(&fig.numeric, &fig.operation, fig.size).is_some() {
                    return Err(ReportError::Duplicate {
                        line,
                        what: format!("figure {} {}", fig.numeric, fig.operation),
                    });
                }
                run.figures.push(fig);
            }
            Line::Count(c) => {
                if run
                    .count(&c.numeric, &c.operation, c.size, &c.counter)
                    .is_some()
                {
                    return Err(ReportError::Duplicate {
                        line,
                        what: format!("count {} {} {}", c.numeric, c.operation, c.counter),
                    });
                }
                run.counts.push(c);
            }
            Line::Omitted(o) => {
                let twice = run
                    .omitted
                    .iter()
                    .any(|p| p.numeric == o.numeric && p.operation == o.operation);
                if twice || run.figure(&o.numeric, &o.operation, None).is_some() {
                    return Err(ReportError::Duplicate {
                        line,
                        what: format!("omitted or measured row {} {}", o.numeric, o.operation),
                    });
                }
                run.omitted.push(o);
            }
            Line::End {
                figures, counts, ..
            } => end = Some((figures, counts)),
        }
    }
    let Some((figures, counts)) = end else {
        return Err(ReportError::NoEnd);
    };
    if figures != run.figures.len() || counts != run.counts.len() {
        return Err(ReportError::CountMismatch {
            figures_expected: figures,
            figures_seen: run.figures.len(),
            counts_expected: counts,
            counts_seen: run.counts.len(),
        });
    }
    run.core = core.unwrap_or_default();
    Ok(run)
}

/// The runs of one benchmark, one per core, in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    pub runs: Vec<CoreRun>,
}

impl Report {
    pub fn new(runs: Vec<CoreRun>) -> Result<Self, ReportError> {
        if runs.is_empty() {
            return Err(ReportError::NoRuns);
        }
        for (i, r) in runs.iter().enumerate() {
            if runs.iter().skip(i + 1).any(|o| o.core == r.core) {
                return Err(ReportError::CoreTwice(r.core.clone()));
            }
        }
        Ok(Report { runs })
    }
}

/// `bench/results.csv`: a comment line saying it is generated, the header
/// [`CSV_HEADER`], then one row per figure in the order measured.
pub fn results_csv(report: &Report) -> String {
    let mut s = format!(
        "# Generated by `{COMMAND}` from the benchmark firmware's output; do not edit. \
         Instructions per call under QEMU -icount (instructions, not cycles); \
         n, m (tracks, measurements per scan) empty where they do not apply.\n"
    );
    s.push_str(CSV_HEADER);
    s.push('\n');
    for run in &report.runs {
        for f in &run.figures {
            let (n, m) = match f.size {
                Some(ScanSize { n, m }) => (n.to_string(), m.to_string()),
                None => (String::new(), String::new()),
            };
            s.push_str(&format!(
                "{},{},{},{},{},{}\n",
                f.core, f.numeric, f.operation, n, m, f.instructions
            ));
        }
    }
    s
}

// ---------------------------------------------------------------------------
// BENCHMARKS.md
// ---------------------------------------------------------------------------

/// The numeric labels, in the order the tables show them, with what they
/// mean. A label not listed here is shown after these, in the order it
/// first appears.
pub const NUMERICS: &[(&str, &str)] = &[
    ("f32", "single precision in hardware (the Cortex-M4F's FPU)"),
    (
        "f32soft",
        "single precision in software (cores without an FPU)",
    ),
    (
        "fixed",
        "abtrack's fast fixed point: `Fixed32` (a 32-bit format per quantity) for the \
         filters, the bank and the scans; its wide format `ScaledScalar` (31-bit mantissa \
         and exponent, every quantity) for the altitude tracker and TCAS",
    ),
    ("q32", "abtrack's Q32.32 fixed point (`Fix`)"),
    ("f64", "double precision, in software on every core here"),
    (
        "i16f16",
        "Q16.16 fixed point (`fixed::types::I16F16`), minikalman's fixed-point build",
    ),
    ("int", "integer-only code: the same in every numeric type"),
];

/// The operations, in the order the tables show them, with what one call
/// does. An operation not listed here is shown after these, in the order it
/// first appears, marked as not described.
pub const OPERATIONS: &[(&str, &str)] = &[
    (
        "ab1d_update",
        "αβ update, one axis (`KinematicFilter<_, 2>::update_step`, step gains formed once per interval)",
    ),
    (
        "abg1d_update",
        "αβγ update, one axis (`KinematicFilter<_, 3>::update_step`, step gains formed once per interval)",
    ),
    (
        "ab2d_update",
        "2-D αβ update, fixed gains (`Cartesian<_, 2, 2>::update_step`, step gains formed once per interval)",
    ),
    (
        "abg2d_update",
        "2-D αβγ update, fixed gains (`Cartesian<_, 3, 2>::update_step`, step gains formed once per interval)",
    ),
    (
        "ab2d_least_squares_update",
        "2-D αβ with Al-Wagih's least-squares gain schedule (`ScheduledFilter`)",
    ),
    (
        "ab2d_liu_adaptive_update",
        "2-D αβ with Liu's adaptive switch (`ScheduledFilter`)",
    ),
    (
        "auto2d_update",
        "2-D `auto`, fused with its filter (`filter::auto::AutoFilter::update_step`: one covariance for both axes, the interval's terms formed once per interval; docs/auto.md)",
    ),
    (
        "auto2d_update_per_call_interval",
        "the same, the interval's terms formed in every call (`AutoFilter::update`: reports that each come with their own interval)",
    ),
    (
        "range_azimuth_update",
        "He et al.'s range–azimuth filter, one polar measurement",
    ),
    (
        "altitude_update",
        "altitude tracker, one Mode C report (`AltitudeTracker::scan`)",
    ),
    (
        "tcas_assess",
        "TCAS threat assessment of one intruder, forming its cycle too (`tcas::assess`)",
    ),
    (
        "tcas_cycle",
        "TCAS cycle, once per scan: sensitivity level and every threshold in the number type (`tcas::stateless_cycle`)",
    ),
    (
        "tcas_assess_in_cycle",
        "TCAS threat assessment of one intruder in a cycle formed once per scan (`tcas::assess_in`)",
    ),
    (
        "tcas_intruder_scan",
        "TCAS, one tracked intruder's reply in a formed cycle: its bearing (range–azimuth) track, range and altitude trackers and its assessment with the miss-distance filter (`IntruderTrack::scan`, `assess`)",
    ),
    (
        "parse_byte",
        "wire decoder, one received byte (`wire::Decoder::push`)",
    ),
    (
        "floor_ab2d_update",
        "anchor, the floor: 2-D αβ with precomputed α, β/T and nothing else",
    ),
    (
        "axis_kalman_cv2d_update",
        "anchor: hand-written constant-velocity Kalman filter, two independent axes",
    ),
    (
        "kalman_cv2d_update",
        "anchor: minikalman 0.8 constant-velocity Kalman filter, 4 states, predict + correct",
    ),
    (
        "scan_separated",
        "track table, one whole scan: N targets 2 km apart, one measurement each",
    ),
    (
        "scan_crowded",
        "track table, one whole scan: clusters of 4–8 targets 12 m apart, gates overlapping",
    ),
    (
        "scan_default_separated",
        "track table with the default filter (auto), one whole scan: N targets 2 km apart",
    ),
    (
        "scan_default_crowded",
        "track table with the default filter (auto), one whole scan: clusters of 4–8 targets 12 m apart",
    ),
    (
        HAND_WRITTEN_SCAN,
        "anchor: a hand-written scan of the separated scene, each track in turn (the hand-written Kalman filter) taking the nearest measurement inside its gate, every measurement not yet taken tested",
    ),
    (
        INTEGER_SCAN,
        "anchor: the hand-written scan in integers, each track in turn (a fixed-gain αβ filter, the scan rows' gains in Q16) taking the nearest measurement inside a constant gate radius, every measurement not yet taken tested",
    ),
];

/// The hand-written scan anchor, and the table's scan it is set beside.
const HAND_WRITTEN_SCAN: &str = "axis_kalman_nn_scan_separated";
const DEFAULT_SCAN: &str = "scan_default_separated";
/// The hand-written integer scan anchor, and the table's fixed-gain scan it
/// is set beside (with `DEFAULT_SCAN`).
const INTEGER_SCAN: &str = "integer_ab_nn_scan_separated";
const FIXED_GAIN_SCAN: &str = "scan_separated";

/// Why a row is not measured (the `reason` of a `bench-omitted` line), with
/// what it means. An unknown reason is shown as not described.
pub const OMISSIONS: &[(&str, &str)] = &[
    (
        "flash",
        "the image would not fit the board's flash with this numeric type's code for \
         these operations as well (the micro:bit has 256 KiB); the firmware's own types \
         are kept",
    ),
    (
        "comparison",
        "the micro:bit's comparison image (feature bench-microbit-scaled-tcas) holds only \
         the TCAS rows in ScaledScalar",
    ),
];

/// The 2-D updates compared with the anchors.
const COMPARED: &[&str] = &[
    "ab2d_update",
    "abg2d_update",
    "ab2d_least_squares_update",
    "ab2d_liu_adaptive_update",
    "auto2d_update",
    "auto2d_update_per_call_interval",
    "axis_kalman_cv2d_update",
];
const FLOOR: &str = "floor_ab2d_update";
const MINIKALMAN: &str = "kalman_cv2d_update";
const MINIKALMAN_FIXED: &str = "i16f16";
/// The scan's stages, in order (operation `<scan>/<stage>`).
const STAGES: &[&str] = &[
    "intake", "index", "gate", "cluster", "assign", "update", "manage", "initiate",
];
/// The counts shown beside the scan figures.
const SCAN_COUNTS: &[&str] = &[
    "candidates",
    "gated_pairs",
    "solver_steps",
    "clusters",
    "largest_cluster",
];

fn is_f32(numeric: &str) -> bool {
    numeric == "f32" || numeric == "f32soft"
}

/// Items in the order of `known`, then the others in first-appearance order.
fn ordered<'a>(seen: impl Iterator<Item = &'a str>, known: &[(&str, &str)]) -> Vec<String> {
    let mut all: Vec<String> = Vec::new();
    for s in seen {
        if !all.iter().any(|a| a == s) {
            all.push(s.to_string());
        }
    }
    let rank = |s: &String| {
        known
            .iter()
            .position(|(k, _)| k == s)
            .unwrap_or(known.len())
    };
    // Stable: unknown ones keep their first-appearance order.
    all.sort_by_key(rank);
    all
}

/// `12,345` for large figures, one decimal below 100.
fn instructions(t: Tenths) -> String {
    let v = t.value();
    if v < 100.0 {
        return format!("{v:.1}");
    }
    thousands(v.round() as u64)
}

fn thousands(v: u64) -> String {
    let digits = v.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

fn ratio(a: Tenths, b: Tenths) -> String {
    if b.0 == 0 {
        return "—".into();
    }
    let r = a.value() / b.value();
    if r >= 10.0 {
        format!("{r:.1}")
    } else {
        format!("{r:.2}")
    }
}

fn core_title(run: &CoreRun) -> String {
    match (run.meta("core"), run.meta("board")) {
        (Some(c), Some(b)) => format!("{c} ({b}, `{}`)", run.core),
        _ => format!("`{}`", run.core),
    }
}

fn row(cells: &[String]) -> String {
    format!("| {} |\n", cells.join(" | "))
}

fn header(cells: &[&str]) -> String {
    let mut s = row(&cells.iter().map(|c| c.to_string()).collect::<Vec<_>>());
    s.push_str(&row(&vec!["---".to_string(); cells.len()]));
    s
}

/// Operations that are not a scan or a scan's stage.
fn per_call_operations(run: &CoreRun) -> Vec<String> {
    ordered(
        run.figures
            .iter()
            .filter(|f| f.size.is_none())
            .map(|f| f.operation.as_str()),
        OPERATIONS,
    )
}

fn numerics(run: &CoreRun) -> Vec<String> {
    ordered(run.figures.iter().map(|f| f.numeric.as_str()), NUMERICS)
}

/// `bench/BENCHMARKS.md`. `qemu_version` is `qemu-system-arm --version`'s
/// first line, `rustc_version` `rustc --version`'s. No date: the same
/// inputs give the same file.
pub fn benchmarks_md(report: &Report, qemu_version: &str, rustc_version: &str) -> String {
    let mut s = String::new();
    s.push_str("# Benchmarks: instructions per call on three emulated cores\n\n");
    s.push_str(&format!(
        "Generated by `{COMMAND}` (the benchmark firmware `boards/qemu/src/bin/bench/` run on each \
         board under QEMU, its output turned into this file and [`results.csv`](results.csv) \
         by the host tool `bench_report`); do not edit it, re-run the command. How the \
         figures are made and how to add a numeric type or an operation: \
         [`docs/benchmarks.md`](../docs/benchmarks.md).\n\n"
    ));
    s.push_str(
        "**These are instructions, not cycles.** QEMU does not model the cycle counter or \
         the pipeline; under `-icount shift=0` its clock advances one step per executed \
         instruction. On silicon, multiplies, divisions, loads, branches and flash wait \
         states take different numbers of cycles, so a ratio of instruction counts is \
         not a ratio of run times, least of all between cores.\n\n",
    );
    method(&mut s, report, qemu_version, rustc_version);
    for run in &report.runs {
        per_core(&mut s, run);
    }
    anchors(&mut s, report);
    scans(&mut s, report);
    hand_written_scan(&mut s, report);
    s
}

fn method(s: &mut String, report: &Report, qemu_version: &str, rustc_version: &str) {
    s.push_str("## Method\n\n");
    // The opt-level each image says it was built at (`s`, the release
    // profile's; `scripts/bench.sh` also builds the mps2 images at `3`).
    let mut levels: Vec<&str> = Vec::new();
    for run in &report.runs {
        let level = run.meta("opt_level").unwrap_or("not given");
        if !levels.contains(&level) {
            levels.push(level);
        }
    }
    let build = match levels.as_slice() {
        [level] => format!("at opt-level \"{level}\""),
        _ => format!(
            "at opt-level {} (per core in the table below)",
            levels
                .iter()
                .map(|l| format!("\"{l}\""))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    s.push_str(&format!(
        "- Emulator: `{qemu_version}`, run with `-icount shift=0` \
         (scripts/qemu-run.sh).\n- Compiler: `{rustc_version}`; the release profile \
         (fat LTO, one codegen unit) {build}.\n"
    ));
    s.push_str(
        "- Counting: SysTick on the core clock, calibrated at start-up on a loop of a \
         known number of instructions (instructions per tick below).\n\
         - A per-call figure is the average over the calls of a loop, each a call of a \
         non-inlined function that runs the operation once on the next input of a ring \
         of 64 (a noisy out-and-back trajectory), minus the same loop without the call; \
         it includes one call and return. Configuration the firmware would read at run \
         time (gains, interval) is opaque to the optimiser.\n\
         - A scan figure is the average of whole `TrackTable::scan` calls in steady \
         state (every target tracked, one measurement each), timed one by one; its \
         stages are timed inside the same scans (SysTick read as \
         `TrackTable::scan_with_probe` reports each stage's end: `intake`, `index` the \
         pre-gate's index, `gate` predict + pre-gate + exact gate, `cluster`, `assign`, \
         `update`, `manage`, `initiate` with the codes and counters); `rest` is the scan \
         minus the stages (the call, the probes).\n\
         - The figures are deterministic: the same code gives the same file.\n\n",
    );
    s.push_str(&header(&[
        "core",
        "board",
        "opt-level",
        "instructions per SysTick tick",
        "calls per figure",
        "scans per figure",
        "stack high-water (bytes)",
        "stack available (bytes)",
    ]));
    for run in &report.runs {
        let m = |k: &str| run.meta(k).unwrap_or("—").to_string();
        s.push_str(&row(&[
            format!("{} (`{}`)", m("core"), run.core),
            m("board"),
            m("opt_level"),
            m("instructions_per_tick"),
            m("calls"),
            m("scans"),
            m("stack_bytes"),
            m("stack_available_bytes"),
        ]));
    }
    s.push('\n');
    let numerics = report
        .runs
        .iter()
        .flat_map(|r| r.figures.iter().map(|f| f.numeric.as_str()));
    legend(
        s,
        "Numeric types (column `numeric` of results.csv):",
        ["label", "meaning"],
        ordered(numerics, NUMERICS),
        NUMERICS,
    );
    let operations = report
        .runs
        .iter()
        .flat_map(|r| r.figures.iter())
        .filter(|f| !f.operation.contains('/'))
        .map(|f| f.operation.as_str());
    legend(
        s,
        "Operations (column `operation`):",
        ["operation", "one call"],
        ordered(operations, OPERATIONS),
        OPERATIONS,
    );
}

/// A two-column table of the names used, each with its description from
/// `known`.
fn legend(
    s: &mut String,
    intro: &str,
    columns: [&str; 2],
    used: Vec<String>,
    known: &[(&str, &str)],
) {
    s.push_str(intro);
    s.push_str("\n\n");
    s.push_str(&header(&columns));
    for name in &used {
        let what = known
            .iter()
            .find(|(k, _)| k == name)
            .map_or("(not described)", |(_, v)| v);
        s.push_str(&row(&[format!("`{name}`"), what.to_string()]));
    }
    s.push('\n');
}

/// One core: every per-call figure, operations × numerics.
fn per_core(s: &mut String, run: &CoreRun) {
    s.push_str(&format!(
        "## {}: instructions per call\n\n",
        core_title(run)
    ));
    let numerics = numerics(run);
    let mut cols: Vec<&str> = vec!["operation"];
    cols.extend(numerics.iter().map(String::as_str));
    s.push_str(&header(&cols));
    for op in per_call_operations(run) {
        let mut cells = vec![format!("`{op}`")];
        for n in &numerics {
            cells.push(
                run.figure(n, &op, None)
                    .map_or("—".to_string(), instructions),
            );
        }
        s.push_str(&row(&cells));
    }
    s.push_str(
        "\n(— : not measured in this numeric type on this core; the rows the image \
         leaves out, and why, are listed below.)\n\n",
    );
    omitted(s, run);
}

/// The rows this core's image does not measure, grouped by numeric type and
/// reason.
fn omitted(s: &mut String, run: &CoreRun) {
    if run.omitted.is_empty() {
        return;
    }
    s.push_str(&format!("Not measured on {}:\n\n", core_title(run)));
    s.push_str(&header(&["numeric", "operations", "why"]));
    let mut groups: Vec<(&str, &str, Vec<&str>)> = Vec::new();
    for o in &run.omitted {
        match groups
            .iter_mut()
            .find(|(n, r, _)| *n == o.numeric && *r == o.reason)
        {
            Some((_, _, ops)) => ops.push(&o.operation),
            None => groups.push((&o.numeric, &o.reason, vec![&o.operation])),
        }
    }
    for (numeric, reason, ops) in groups {
        let why = OMISSIONS
            .iter()
            .find(|(k, _)| *k == reason)
            .map_or(format!("`{reason}` (not described)"), |(_, v)| {
                v.to_string()
            });
        let ops: Vec<String> = ops.iter().map(|o| format!("`{o}`")).collect();
        s.push_str(&row(&[format!("`{numeric}`"), ops.join(", "), why]));
    }
    s.push('\n');
}

/// The 2-D updates against the floor and minikalman, per core.
fn anchors(s: &mut String, report: &Report) {
    s.push_str("## Against the anchors\n\n");
    s.push_str(
        "Each 2-D update in each numeric type, as a multiple of the floor \
         (`floor_ab2d_update`) in the same type and in the core's f32, and how many times \
         fewer instructions it takes than minikalman's constant-velocity Kalman filter \
         (`kalman_cv2d_update`) in f32 and in I16F16 on the same core (above 1: cheaper \
         than minikalman).\n\n",
    );
    s.push_str(&header(&[
        "core",
        "numeric",
        "operation",
        "instructions",
        "× floor, same type",
        "× floor, f32",
        "minikalman f32 ÷ this",
        "minikalman I16F16 ÷ this",
    ]));
    for run in &report.runs {
        let numerics = numerics(run);
        let f32_label = numerics.iter().find(|n| is_f32(n));
        let f32_floor = f32_label.and_then(|n| run.figure(n, FLOOR, None));
        let kalman_f32 = f32_label.and_then(|n| run.figure(n, MINIKALMAN, None));
        let kalman_fixed = run.figure(MINIKALMAN_FIXED, MINIKALMAN, None);
        for op in COMPARED {
            for n in &numerics {
                let Some(t) = run.figure(n, op, None) else {
                    continue;
                };
                let floor = run.figure(n, FLOOR, None);
                let over = |base: Option<Tenths>| base.map_or("—".into(), |b| ratio(t, b));
                let under = |top: Option<Tenths>| top.map_or("—".into(), |k| ratio(k, t));
                s.push_str(&row(&[
                    format!("`{}`", run.core),
                    format!("`{n}`"),
                    format!("`{op}`"),
                    instructions(t),
                    over(floor),
                    over(f32_floor),
                    under(kalman_f32),
                    under(kalman_fixed),
                ]));
            }
        }
    }
    s.push('\n');
}

/// The scan rows: per core, numeric and scene, each size with its stages,
/// growth and counts; then every count.
fn scans(s: &mut String, report: &Report) {
    s.push_str("## Track-table scans\n\n");
    s.push_str(
        "Instructions per scan, N tracks and M measurements per scan. `growth` is the \
         scan's figure over the previous size's, and `exponent` the power of N that \
         growth corresponds to (1: linear, 2: quadratic). The counts (candidates of the \
         pre-gate, gated pairs, solver steps, clusters, tracks in the largest) are the \
         table's own, from the last scan timed.\n\n",
    );
    let mut columns = vec!["core", "numeric", "operation", "N × M", "scan"];
    columns.extend(STAGES.iter().copied());
    columns.extend(["rest", "growth", "exponent"]);
    columns.extend(SCAN_COUNTS.iter().copied());
    s.push_str(&header(&columns));
    for run in &report.runs {
        for n in numerics(run) {
            let scans = ordered(
                run.figures
                    .iter()
                    .filter(|f| f.numeric == n && f.size.is_some() && !f.operation.contains('/'))
                    .map(|f| f.operation.as_str()),
                OPERATIONS,
            );
            for op in scans {
                let mut sizes: Vec<ScanSize> = run
                    .figures
                    .iter()
                    .filter(|f| f.numeric == n && f.operation == op)
                    .filter_map(|f| f.size)
                    .collect();
                sizes.sort();
                let mut previous: Option<(ScanSize, Tenths)> = None;
                for size in sizes {
                    let Some(scan) = run.figure(&n, &op, Some(size)) else {
                        continue;
                    };
                    let stages: Vec<Option<Tenths>> = STAGES
                        .iter()
                        .map(|st| run.figure(&n, &format!("{op}/{st}"), Some(size)))
                        .collect();
                    let rest = stages
                        .iter()
                        .try_fold(0u64, |acc, st| st.map(|t| acc + t.0))
                        .map(|sum| {
                            let r = scan.0 as i64 - sum as i64;
                            if r >= 0 {
                                instructions(Tenths(r as u64))
                            } else {
                                format!("−{}", instructions(Tenths((-r) as u64)))
                            }
                        })
                        .unwrap_or_else(|| "—".into());
                    let (growth, exponent) = match previous {
                        Some((p, pt)) if p.n != size.n && pt.0 > 0 => {
                            let g = scan.value() / pt.value();
                            let e = g.ln() / (size.n as f64 / p.n as f64).ln();
                            (format!("{g:.2}"), format!("{e:.2}"))
                        }
                        _ => ("—".into(), "—".into()),
                    };
                    let count = |c: &str| {
                        run.count(&n, &op, size, c)
                            .map_or("—".to_string(), |v| v.to_string())
                    };
                    let mut cells = vec![
                        format!("`{}`", run.core),
                        format!("`{n}`"),
                        format!("`{op}`"),
                        format!("{} × {}", size.n, size.m),
                        instructions(scan),
                    ];
                    cells.extend(stages.iter().map(|st| st.map_or("—".into(), instructions)));
                    cells.push(rest);
                    cells.push(growth);
                    cells.push(exponent);
                    cells.extend(SCAN_COUNTS.iter().map(|c| count(c)));
                    s.push_str(&row(&cells));
                    previous = Some((size, scan));
                }
            }
        }
    }
    s.push('\n');
    scan_counts(s, report);
}

/// The table's scan with the default filter beside the hand-written scan,
/// per core and size: in each of the anchor's types, and in the table's
/// type of the same label (the fast fixed point: the anchor in its wide
/// format, the table in `Fixed32`).
fn hand_written_scan(s: &mut String, report: &Report) {
    s.push_str("## Against a hand-written scan\n\n");
    s.push_str(&format!(
        "`{HAND_WRITTEN_SCAN}` is the scan a user would write around the hand-written \
         Kalman filter (`axis_kalman_cv2d_update`) on the separated scene: each track in \
         turn predicted, every measurement not yet taken tested on the normalised \
         distance, the nearest inside the gate taken; no input checks, no assignment, no \
         track starts or deletions, no counts. Beside it, the track table's scan with its \
         default filter (`{DEFAULT_SCAN}`) at the same size, N tracks and M = N \
         measurements, in the anchor's type (for `fixed`, the table in `Fixed32` and the \
         anchor in `ScaledScalar`) and in the core's own (f32 on a core with an FPU, \
         else the fast fixed point, `fixed`). The table's figure includes its own \
         filter's updates (`auto2d_update` against `axis_kalman_cv2d_update`). A ratio \
         above 1: the table costs more.\n\n"
    ));
    s.push_str(&header(&[
        "core",
        "N × M",
        "numeric",
        "hand-written",
        "table, same label",
        "table ÷ hand-written",
        "table, the core's type",
        "its ÷ hand-written",
    ]));
    for run in &report.runs {
        let numerics = numerics(run);
        let own = own_type(&numerics);
        for n in &numerics {
            let mut sizes: Vec<ScanSize> = run
                .figures
                .iter()
                .filter(|f| f.numeric == *n && f.operation == HAND_WRITTEN_SCAN)
                .filter_map(|f| f.size)
                .collect();
            sizes.sort();
            for size in sizes {
                let Some(anchor) = run.figure(n, HAND_WRITTEN_SCAN, Some(size)) else {
                    continue;
                };
                let table = run.figure(n, DEFAULT_SCAN, Some(size));
                let table_own = run.figure(own, DEFAULT_SCAN, Some(size));
                let cell = |t: Option<Tenths>| t.map_or("—".into(), instructions);
                let over = |t: Option<Tenths>| t.map_or("—".into(), |t| ratio(t, anchor));
                s.push_str(&row(&[
                    format!("`{}`", run.core),
                    format!("{} × {}", size.n, size.m),
                    format!("`{n}`"),
                    instructions(anchor),
                    cell(table),
                    over(table),
                    format!("`{own}` {}", cell(table_own)),
                    over(table_own),
                ]));
            }
        }
    }
    s.push('\n');
    integer_scan(s, report);
}

/// The type a core's table runs in: f32 on a core with an FPU, else the
/// fast fixed point.
fn own_type(numerics: &[String]) -> &'static str {
    if numerics.iter().any(|n| n == "f32") {
        "f32"
    } else {
        "fixed"
    }
}

/// The table's scans in the core's own type beside the hand-written
/// integer scan, per core and size.
fn integer_scan(s: &mut String, report: &Report) {
    let mut rows = String::new();
    for run in &report.runs {
        let own = own_type(&numerics(run));
        let mut sizes: Vec<ScanSize> = run
            .figures
            .iter()
            .filter(|f| f.operation == INTEGER_SCAN)
            .filter_map(|f| f.size)
            .collect();
        sizes.sort();
        for size in sizes {
            let Some(anchor) = run.figures.iter().find_map(|f| {
                (f.operation == INTEGER_SCAN && f.size == Some(size)).then_some(f.instructions)
            }) else {
                continue;
            };
            let table = |operation: &str| run.figure(own, operation, Some(size));
            let cell = |t: Option<Tenths>| t.map_or("—".into(), instructions);
            let over = |t: Option<Tenths>| t.map_or("—".into(), |t| ratio(t, anchor));
            let (fixed_gains, default) = (table(FIXED_GAIN_SCAN), table(DEFAULT_SCAN));
            rows.push_str(&row(&[
                format!("`{}`", run.core),
                format!("{} × {}", size.n, size.m),
                instructions(anchor),
                format!("`{own}`"),
                cell(fixed_gains),
                over(fixed_gains),
                cell(default),
                over(default),
            ]));
        }
    }
    if rows.is_empty() {
        return;
    }
    s.push_str(&format!(
        "`{INTEGER_SCAN}` is that loop as it is written for a core without an FPU and a \
         sensor with a fixed scan period: coordinates in integers (1/16 m in an `i32`), \
         velocity per scan, the fixed-gain rows' α and β in Q16, a constant gate radius \
         (the table's fixed-gain gate in steady state) tested as a box and then on \
         dx² + dy², every product in a 32-bit word. Beside it, the table's scans in the \
         core's own type: with fixed gains (`{FIXED_GAIN_SCAN}`, the same gains) and with \
         its default filter (`{DEFAULT_SCAN}`). A ratio above 1: the table costs more.\n\n"
    ));
    s.push_str(&header(&[
        "core",
        "N × M",
        "hand-written, integer",
        "table's type",
        "table, fixed gains",
        "÷ integer",
        "table, default filter",
        "÷ integer",
    ]));
    s.push_str(&rows);
    s.push('\n');
}

/// Every count, one row per (core, numeric, scan, size).
fn scan_counts(s: &mut String, report: &Report) {
    let counters = {
        let mut all: Vec<&str> = Vec::new();
        for c in report.runs.iter().flat_map(|r| r.counts.iter()) {
            if !all.contains(&c.counter.as_str()) {
                all.push(&c.counter);
            }
        }
        all
    };
    if counters.is_empty() {
        return;
    }
    s.push_str("### Every count of the scan rows\n\n");
    s.push_str(
        "The table's `ScanReport` of the last scan timed, and the sizes of the clusters \
         (tracks joined by a gated measurement) of the scan after it, counted by the \
         benchmark: `clusters_of_1`, `clusters_of_2_3`, `clusters_of_4_8`, \
         `clusters_of_9_up`.\n\n",
    );
    let mut cols = vec!["core", "numeric", "operation", "N × M"];
    cols.extend(counters.iter().copied());
    s.push_str(&header(&cols));
    for run in &report.runs {
        let mut keys: BTreeMap<(usize, usize, ScanSize), (String, String)> = BTreeMap::new();
        let numerics = numerics(run);
        let ops = ordered(run.counts.iter().map(|c| c.operation.as_str()), OPERATIONS);
        for c in &run.counts {
            let ni = numerics
                .iter()
                .position(|n| *n == c.numeric)
                .unwrap_or(usize::MAX);
            let oi = ops
                .iter()
                .position(|o| *o == c.operation)
                .unwrap_or(usize::MAX);
            keys.entry((ni, oi, c.size))
                .or_insert_with(|| (c.numeric.clone(), c.operation.clone()));
        }
        for ((_, _, size), (n, op)) in keys {
            let mut cells = vec![
                format!("`{}`", run.core),
                format!("`{n}`"),
                format!("`{op}`"),
                format!("{} × {}", size.n, size.m),
            ];
            cells.extend(counters.iter().map(|c| {
                run.count(&n, &op, size, c)
                    .map_or("—".to_string(), |v| v.to_string())
            }));
            s.push_str(&row(&cells));
        }
    }
    s.push('\n');
}
