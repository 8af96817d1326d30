//! `replay --tracker`: the library's multi-target [`TrackTable`] over a
//! recording of scans, in f64, f32, Q32.32 or the Cortex-M3 firmware's
//! fast fixed point ([`Fixed32`] for x/y input, its wide format
//! [`ScaledScalar`] for range/azimuth input and the threat columns),
//! configured from the sensor's figures by [`TrackerDesign`].
//!
//! # Input
//!
//! The `replay` CSV layouts ([`crate::csv_input`], [`read_recording`]),
//! read with [`TimeOrder::Scans`]: consecutive rows sharing a `t` are one
//! scan. The layout is chosen by the header: `x`, `y` columns (m) make the
//! Cartesian tracker, `range`, `azimuth` the polar one (a `z` column is
//! refused: the table works in the x/y plane; `alt` is checked but not
//! used: the table keeps no altitude).
//!
//! # Configuration
//!
//! [`SensorOptions`] give the sensor's figures; each figure not given is
//! the nominal sensor's ([`TrackerDesign::NOMINAL_RADAR`] for x/y input,
//! [`TrackerDesign::NOMINAL_TCAS`] for range/azimuth), except the coverage,
//! which is none unless `--region-m` gives one, and the scan period, which
//! is the median interval between the file's scans unless given. With no
//! coverage the design counts clutter over the disc reaching the farthest
//! measurement of the file. The design derives the filter, gate,
//! initiation, confirmation, deletion and volume
//! ([`TrackerDesign::cartesian_config`], [`TrackerDesign::polar_config`]);
//! `--schedule SPEC` (x/y input only, any schedule but `bank`) replaces the
//! filter ([`TrackerDesign::tracker_config`]), `--confirm M/N` and
//! `--delete K` the lifecycle, `--capacity 16|64|256` the table's N.
//!
//! # Time
//!
//! The table runs on a u32 millisecond clock: a scan at `t` seconds is
//! given `round((t − t₀)·1000)` ms, t₀ the first scan's time (so epoch
//! seconds work), at most 2³² − 1 ms after it ([`ReplayError::ScanTime`]).
//! Where the file skips scans (a gap g between two scans longer than 1.5
//! scan periods T), empty scans are run, as a sensor would report them: the
//! gap is cut into round(g/T) equal intervals, so tracks miss one scan per
//! period and the deletion rule counts scans, not rows. A track last
//! updated more than 20 s before a scan restarts there (the table ends it,
//! its target starts again by two-point initiation; counted on stderr); a
//! scan less than 0.05 s after the previous one (or in the same
//! millisecond) is skipped, its measurements counted, and writes no rows.
//!
//! # Output
//!
//! One row per live track per scan (the added empty scans included, their
//! `t` written from the clock), in increasing id order:
//! `t,track_id,status,x,y,vx,vy`. With `--own-alt FEET` the threat columns
//! of `--filter range-azimuth` follow ([`crate::replay::THREAT_COLUMNS`]),
//! under the same assumptions, with every track counted as not reporting
//! altitude (horizontal advisories only: at most `ta`).
//!
//! On stderr, always: the design used and the account of every measurement
//! not used, by reason ([`Unused`]); with `--verbose`, one line per scan
//! before it ([`TrackerReplay::scan_log`]).

use std::fmt::Write as _;
use std::io::Read;

use abtrack::envelope::{self, Limit};
use abtrack::gain::spec::ScheduleSpec;
use abtrack::tcas::Intruder;
use abtrack::track::defaults::{
    Coverage, DefaultCartesianTrack, DefaultPolarTrack, DerivedParameters, SensorAccuracy,
    TrackerDesign, MAX_CONFIRMATION_WINDOW, MAX_FALSE_CONFIRMATIONS_PER_SCAN,
    MAX_SPURIOUS_DELETIONS_PER_SCAN, MIN_TRUE_CONFIRMATION,
};
use abtrack::track::{
    Association, ConfigError, DropReason, Measurement, Observation, RejectReason, ScanReport,
    ScheduledTrack, TrackFilter, TrackTable, TrackerConfig,
};
use abtrack::{Fix, Fixed32, ScaledScalar};

use crate::csv_input::{read_recording, AngleUnit, ReadOptions, Recording, TimeOrder, Timed};
use crate::replay::{
    check_estimate, own_aircraft, value, write_threat_cells, CsvValue, Failure, Numeric,
    ReplayError, ReplaySchedule, FINITE, THREAT_COLUMNS,
};

/// The table capacities `--capacity` offers.
pub const CAPACITIES: [usize; 3] = [16, 64, 256];
/// N without `--capacity`.
pub const DEFAULT_CAPACITY: usize = 64;
/// M, the measurements per scan every table takes.
pub const MAX_MEASUREMENTS: usize = 4096;
/// A gap longer than this many scan periods gets empty scans (module docs).
pub const GAP_PERIODS: f64 = 1.5;

/// The output header.
pub fn tracker_header(threat: bool) -> String {
    let mut h = String::from("t,track_id,status,x,y,vx,vy");
    if threat {
        h.push(',');
        h.push_str(THREAT_COLUMNS);
    }
    h
}

/// The sensor's figures given on the command line; `None` takes the
/// default (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SensorOptions {
    /// `--region-m`: half-width of the square (x/y input) or radius of the
    /// disc (range/azimuth input) watched, m.
    pub region_m: Option<f64>,
    /// `--sigma-m`: Cartesian σ per axis, m.
    pub sigma_m: Option<f64>,
    /// `--range-sigma-m`: range σ, m.
    pub range_sigma_m: Option<f64>,
    /// `--bearing-sigma-deg`: bearing σ, degrees.
    pub bearing_sigma_deg: Option<f64>,
    /// `--scan-period-s`: T, s.
    pub scan_period_s: Option<f64>,
    /// `--pd`: detection probability.
    pub detection_probability: Option<f64>,
    /// `--clutter-per-km2`: false measurements per km² per scan.
    pub clutter_per_km2: Option<f64>,
    /// `--max-speed-mps`: v_max, m/s.
    pub max_speed_m_per_s: Option<f64>,
    /// `--max-accel-mps2`: a_max, the manoeuvre level, m/s².
    pub max_acceleration_m_per_s2: Option<f64>,
}

/// What `replay --tracker` runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackerOptions {
    pub numeric: Numeric,
    /// `--schedule` (Cartesian input only; never `bank`).
    pub schedule: Option<ScheduleSpec>,
    /// One of [`CAPACITIES`].
    pub capacity: usize,
    /// `--confirm M/N`.
    pub confirmation: Option<(u8, u8)>,
    /// `--delete K` (confirmed tracks).
    pub delete_confirmed: Option<u8>,
    /// Not `--no-first-point-wait`: a first point waits through one missed
    /// scan (`TrackerConfig::keep_first_points_through_a_miss`).
    pub first_points_through_a_miss: bool,
    /// `--own-alt FEET`.
    pub own_altitude_ft: Option<f64>,
    pub sensor: SensorOptions,
    /// `--azimuth-unit`.
    pub azimuth_unit: AngleUnit,
}

impl Default for TrackerOptions {
    fn default() -> Self {
        TrackerOptions {
            numeric: Numeric::F64,
            schedule: None,
            capacity: DEFAULT_CAPACITY,
            confirmation: None,
            delete_confirmed: None,
            first_points_through_a_miss: true,
            own_altitude_ft: None,
            sensor: SensorOptions::default(),
            azimuth_unit: AngleUnit::Radians,
        }
    }
}

/// A run's output.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerReplay {
    /// The CSV (stdout).
    pub csv: String,
    /// One summary line per scan (stderr with `--verbose`).
    pub scan_log: String,
    /// The design and the account of the measurements not used (stderr,
    /// always): [`TrackerReplay::report`].
    pub design: DesignUsed,
    pub unused: Unused,
    pub one_plot_scans: OnePlotScans,
}

impl TrackerReplay {
    /// The stderr report: the design, then every measurement not used by
    /// reason, then a note when the file looks like plots time-stamped one
    /// by one ([`OnePlotScans`]).
    pub fn report(&self) -> String {
        format!("{}{}{}", self.design, self.unused, self.one_plot_scans)
    }
}

/// Consecutive scans of one plot each, and those of them whose two plots
/// are farther apart than one target moves between them (v_max·Δt plus six
/// measurement σ): plots of different targets, time-stamped one by one,
/// which the tracker reads as scans of one plot each (docs/host-tools.md).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OnePlotScans {
    pub pairs: usize,
    pub apart: usize,
}

impl OnePlotScans {
    fn of(scans: &[FileScan<'_>], design: &TrackerDesign) -> Self {
        // The larger of a measurement's σ along and across its range.
        let sigma = |m: &Measurement<f64>| match (design.accuracy, *m) {
            (SensorAccuracy::Cartesian { sigma }, _) => sigma,
            (
                SensorAccuracy::Polar {
                    range_sigma,
                    bearing_sigma,
                },
                Measurement::Polar { range, .. },
            ) => range_sigma.max(range * bearing_sigma),
            (SensorAccuracy::Polar { range_sigma, .. }, _) => range_sigma,
        };
        let mut out = OnePlotScans::default();
        for pair in scans.windows(2) {
            let ([(_, a)], [(_, b)]) = (pair[0].rows.as_slice(), pair[1].rows.as_slice()) else {
                continue;
            };
            // Projected as the table projects them; a plot it refuses
            // makes no pair.
            let (Ok(oa), Ok(ob)) = (Observation::new(*a), Observation::new(*b)) else {
                continue;
            };
            out.pairs += 1;
            let ([xa, ya], [xb, yb]) = (oa.xy(), ob.xy());
            let reach = design.max_speed * (pair[1].t - pair[0].t) + 6.0 * sigma(a).max(sigma(b));
            if (xb - xa).hypot(yb - ya) > reach {
                out.apart += 1;
            }
        }
        out
    }

    /// At least 10 such pairs, most of them apart.
    pub fn look_stamped_one_by_one(&self) -> bool {
        self.pairs >= 10 && 2 * self.apart > self.pairs
    }
}

impl std::fmt::Display for OnePlotScans {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if !self.look_stamped_one_by_one() {
            return Ok(());
        }
        writeln!(
            f,
            "replay --tracker: note: in {} of {} pairs of consecutive one-row scans the two \
             plots are farther apart than a target moves between them (v_max·Δt + 6σ): the \
             plots look time-stamped one by one; the tracker takes the rows sharing a t as one \
             scan, so each plot is a scan of its own, which every other track misses \
             (docs/host-tools.md: give each plot its scan's time)",
            self.apart, self.pairs
        )
    }
}

/// The design a run used, and where its figures came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignUsed {
    pub design: TrackerDesign,
    pub derived: DerivedParameters,
    /// Where the scan period came from.
    pub period: PeriodSource,
    /// `--confirm M/N` replaced the designed confirmation rule.
    pub confirmation_given: bool,
}

/// Where a tracker replay's scan period came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PeriodSource {
    /// `--scan-period-s`, or the nominal period (a file of one scan).
    Given,
    /// The file's median scan interval.
    FileMedian,
    /// The file's median scan interval (this many s), outside the filters'
    /// interval range and clamped to it: a sparse or irregular file is
    /// run, not refused.
    FileMedianClamped(f64),
}

/// The sensor figures a design was derived from, as one line of text (no
/// newline).
fn design_figures(d: &TrackerDesign, period: PeriodSource) -> String {
    let accuracy = match d.accuracy {
        SensorAccuracy::Cartesian { sigma } => format!("σ {sigma} m per axis"),
        SensorAccuracy::Polar {
            range_sigma,
            bearing_sigma,
        } => format!(
            "range σ {range_sigma} m, bearing σ {:.4}°",
            bearing_sigma.to_degrees()
        ),
    };
    let coverage = match d.coverage {
        Coverage::None => format!(
            "no region (clutter counted over the disc to the farthest measurement, {:.1} km)",
            d.max_range / 1000.0
        ),
        Coverage::Square { half_width } => format!("square ±{half_width} m"),
        Coverage::Disc { radius } => format!("disc of {radius} m"),
    };
    format!(
        "sensor {accuracy}, T {} s{}, P_D {}, clutter {} per km², {coverage}, v_max {} m/s, \
         a_max {:.2} m/s²",
        d.scan_period,
        match period {
            PeriodSource::Given => String::new(),
            PeriodSource::FileMedian => " (median scan interval of the file)".to_string(),
            PeriodSource::FileMedianClamped(median) => format!(
                " (the file's median scan interval, {}, is outside the filters' {} ..= {} s: \
                 the nearest end is used; --scan-period-s sets it)",
                short(median),
                envelope::INTERVAL_S.min,
                envelope::INTERVAL_S.max
            ),
        },
        d.detection_probability,
        short(d.clutter_density * 1e6),
        d.max_speed,
        d.max_acceleration,
    )
}

impl std::fmt::Display for DesignUsed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.derived;
        writeln!(
            f,
            "replay --tracker: {}",
            design_figures(&self.design, self.period)
        )?;
        writeln!(
            f,
            "replay --tracker: design: gate G {:.2}, initiation within v_max·T + {:.0} m, \
             confirm {} of {}, delete after {} misses ({} tentative){}",
            p.gate_threshold,
            p.initiation_margin,
            p.confirmation.0,
            p.confirmation.1,
            p.deletion.0,
            p.deletion.1,
            p.max_gate_radius
                .map(|r| format!(" or a confirmed track's gate wider than {r:.0} m"))
                .unwrap_or_default()
        )?;
        if !p.confirmation_meets_bounds && !self.confirmation_given {
            // The fixes: with clutter, the clutter counted over the area
            // watched first (usually the default density over a file's
            // extent); without, only P_D is left.
            let area = self.design.clutter_area();
            let fixes = if self.design.clutter_density > 0.0 {
                "a recording without clutter takes --clutter-per-km2 0, and --region-m, --pd, \
                 --confirm and --delete set the figures and the rules"
            } else {
                "without clutter, P_D (--pd) is too low for it; --confirm and --delete set the \
                 rules"
            };
            writeln!(
                f,
                "replay --tracker: warning: no M-of-N within {} scans confirms a target with \
                 probability {} at no more than one false track per {} scans; {} of {} \
                 confirms one with probability {} at {} false tracks a scan (the clutter: {} \
                 false measurements a scan expected over the {} km² counted); {fixes}",
                MAX_CONFIRMATION_WINDOW,
                MIN_TRUE_CONFIRMATION,
                (1.0 / MAX_FALSE_CONFIRMATIONS_PER_SCAN).round(),
                p.confirmation.0,
                p.confirmation.1,
                three_significant(p.true_confirmation_probability),
                three_significant(p.false_confirmations_per_scan),
                three_significant(self.design.clutter_density * area),
                three_significant(area * 1e-6)
            )?;
        }
        Ok(())
    }
}

/// `v` with at most 6 decimals, trailing zeros dropped.
fn short(v: f64) -> String {
    let text = format!("{v:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// At most this many line numbers are listed per reason.
pub const LISTED_LINES: usize = 8;

/// Measurements of one reason: how many, and the first lines.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tally {
    pub count: usize,
    pub lines: Vec<usize>,
}

impl Tally {
    fn add(&mut self, line: usize) {
        self.count += 1;
        if self.lines.len() < LISTED_LINES {
            self.lines.push(line);
        }
    }

    fn lines_text(&self) -> String {
        if self.lines.is_empty() {
            return String::new();
        }
        let list: Vec<String> = self.lines.iter().map(usize::to_string).collect();
        let more = if self.count > self.lines.len() {
            ", …"
        } else {
            ""
        };
        format!(" (line {}{more})", list.join(", "))
    }
}

/// Every measurement of a run, accounted for.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Unused {
    pub measurements: usize,
    pub scans: usize,
    /// Empty scans run for gaps (module docs).
    pub empty_scans: usize,
    /// Scans of the file before the previous one, not run (their
    /// measurements are [`Self::out_of_order`]).
    pub out_of_order_scans: usize,
    /// Updated a track.
    pub updated: usize,
    /// Started a track (its second point) ...
    pub started: usize,
    /// Outside the coverage's volume: used by no track, starts none.
    pub outside_region: Tally,
    /// Inside the region but outside every gate (before subtracting those
    /// that became a new track's first point in the next scan).
    pub outside_gates: Tally,
    /// Inside a gate, but the assignment gave that track another one.
    pub not_assigned: Tally,
    /// More than `M` measurements in the scan.
    pub over_scan_capacity: Tally,
    /// Would have started a track, but the table was full.
    pub table_full: Tally,
    /// Refused: not a finite value.
    pub not_finite: Tally,
    /// Refused: a negative range.
    pub negative_range: Tally,
    /// Refused by the filter (its arithmetic saturated).
    pub filter_refused: Tally,
    /// Their scan came less than 0.05 s after the previous one (or in the
    /// same millisecond of the table's clock): the scan was skipped.
    pub too_close: Tally,
    /// Their scan's time was before the previous scan's (rows out of time
    /// order): the scan was skipped.
    pub out_of_order: Tally,
    /// Tracks restarted: ended by a scan more than 20 s after the previous
    /// one (their targets start again by two-point initiation).
    pub tracks_restarted: usize,
    /// Tentative tracks ended to make room for a new track (the table
    /// full; `abtrack::track::ScanReport::deleted_displaced`).
    pub tracks_displaced: usize,
    /// Confirmed tracks ended lost in clutter: their gate wider than the
    /// design's rule 7 allows
    /// (`abtrack::track::ScanReport::deleted_gate_too_wide`).
    pub tracks_lost_in_clutter: usize,
}

impl Unused {
    /// Measurements that were the first point of a new track: one per track
    /// started (each start takes one pending point of the previous scan,
    /// which was outside every gate and inside the region).
    pub fn first_points(&self) -> usize {
        self.started
    }

    /// Outside every gate and never a track's first point.
    pub fn outside_gates_unused(&self) -> usize {
        self.outside_gates.count.saturating_sub(self.first_points())
    }

    /// Measurements used: updates, and both points of every track started.
    pub fn used(&self) -> usize {
        self.updated + self.started + self.first_points()
    }

    /// Measurements not used, every reason summed.
    pub fn not_used(&self) -> usize {
        self.outside_region.count
            + self.outside_gates_unused()
            + self.not_assigned.count
            + self.over_scan_capacity.count
            + self.table_full.count
            + self.not_finite.count
            + self.negative_range.count
            + self.filter_refused.count
            + self.too_close.count
            + self.out_of_order.count
    }

    fn record(&mut self, code: Association, line: usize) {
        match code {
            Association::Updated(_) => self.updated += 1,
            Association::Started(_) => self.started += 1,
            Association::NotAssigned => self.not_assigned.add(line),
            Association::OutsideVolume => self.outside_region.add(line),
            Association::OutsideGates => self.outside_gates.add(line),
            Association::Rejected(RejectReason::NotFinite) => self.not_finite.add(line),
            Association::Rejected(RejectReason::NegativeRange) => self.negative_range.add(line),
            Association::Rejected(RejectReason::FilterRefused) => self.filter_refused.add(line),
            Association::Rejected(RejectReason::TooClose) => self.too_close.add(line),
            Association::Dropped(DropReason::ScanOverflow) => self.over_scan_capacity.add(line),
            Association::Dropped(DropReason::TableFull) => self.table_full.add(line),
        }
    }
}

/// `n` and `noun`, plural unless `n` is 1 ("1 scan", "2 scans").
fn counted(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

impl std::fmt::Display for Unused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = "replay --tracker:";
        writeln!(
            f,
            "{p} {} in {}{}{}: {} used, {} not used",
            counted(self.measurements, "measurement"),
            counted(self.scans, "scan"),
            if self.empty_scans > 0 {
                format!(
                    " (and {} run for gaps)",
                    counted(self.empty_scans, "empty scan")
                )
            } else {
                String::new()
            },
            if self.out_of_order_scans > 0 {
                format!(
                    " (and {} out of time order, not run)",
                    counted(self.out_of_order_scans, "scan")
                )
            } else {
                String::new()
            },
            self.used(),
            self.not_used()
        )?;
        writeln!(
            f,
            "{p}   outside the region: {}{}",
            self.outside_region.count,
            self.outside_region.lines_text()
        )?;
        writeln!(
            f,
            "{p}   outside every gate: {} (of {} outside every gate, {} became the first point \
             of a new track)",
            self.outside_gates_unused(),
            self.outside_gates.count,
            self.first_points()
        )?;
        writeln!(
            f,
            "{p}   inside a gate, the track took another measurement: {}{}",
            self.not_assigned.count,
            self.not_assigned.lines_text()
        )?;
        writeln!(
            f,
            "{p}   over capacity: {} more than {MAX_MEASUREMENTS} in a scan{}, {} table full{}",
            self.over_scan_capacity.count,
            self.over_scan_capacity.lines_text(),
            self.table_full.count,
            self.table_full.lines_text()
        )?;
        writeln!(
            f,
            "{p}   refused: {} not finite{}, {} negative range{}, {} refused by the filter{}",
            self.not_finite.count,
            self.not_finite.lines_text(),
            self.negative_range.count,
            self.negative_range.lines_text(),
            self.filter_refused.count,
            self.filter_refused.lines_text()
        )?;
        writeln!(
            f,
            "{p}   skipped: {} in scans less than {} s after the previous one{}, {} in scans \
             before the previous one (out of time order){}",
            self.too_close.count,
            abtrack::filter::MIN_INTERVAL_S,
            self.too_close.lines_text(),
            self.out_of_order.count,
            self.out_of_order.lines_text()
        )?;
        writeln!(
            f,
            "{p} tracks restarted: {} (by a scan more than {} s after the previous one; their \
             targets start again by two-point initiation)",
            self.tracks_restarted,
            abtrack::filter::MAX_INTERVAL_S
        )?;
        writeln!(
            f,
            "{p} tentative tracks displaced: {} (the table full, each ended for a new track; \
             {} candidates refused, no tentative track to displace)",
            self.tracks_displaced, self.table_full.count
        )?;
        writeln!(
            f,
            "{p} confirmed tracks lost in clutter: {} (each ended when its gate held more \
             expected clutter than the chance of its target's own: the design's rule 7)",
            self.tracks_lost_in_clutter
        )
    }
}

/// One scan in the table's number type.
struct ScanInput<'a, S: abtrack::Numeric> {
    /// Line of the scan's first row (0 for an added empty scan).
    line: usize,
    /// The time as written (or, for an added empty scan, from the clock).
    t_text: std::borrow::Cow<'a, str>,
    now_ms: u32,
    measurements: Vec<Measurement<S>>,
    lines: Vec<usize>,
}

/// A scan of the file, before conversion.
struct FileScan<'a> {
    line: usize,
    t_text: &'a str,
    t: f64,
    rows: Vec<(usize, Measurement<f64>)>,
}

/// A row of either layout as one measurement of a scan.
trait ScanRow: Timed {
    fn line(&self) -> usize;
    fn measurement(&self) -> Measurement<f64>;
}

impl ScanRow for crate::csv_input::Row {
    fn line(&self) -> usize {
        self.line
    }
    fn measurement(&self) -> Measurement<f64> {
        Measurement::Cartesian {
            x: self.z[0],
            y: self.z[1],
        }
    }
}

impl ScanRow for crate::csv_input::RangeAzimuthRow {
    fn line(&self) -> usize {
        self.line
    }
    fn measurement(&self) -> Measurement<f64> {
        Measurement::Polar {
            range: self.range,
            azimuth: self.azimuth,
        }
    }
}

/// A file's scans in time order, and the lines of the rows of the scans
/// out of it.
struct FileScans<'a> {
    scans: Vec<FileScan<'a>>,
    /// The rows of scans before the previous scan kept (skipped, counted).
    out_of_order: Vec<usize>,
    /// How many scans those rows made.
    out_of_order_scans: usize,
}

/// Scans of rows (consecutive rows sharing a `t`); a scan before the
/// previous one kept is set aside.
fn scans_of<'a, R: ScanRow + 'a>(scans: impl Iterator<Item = &'a [R]>) -> FileScans<'a> {
    let mut out = FileScans {
        scans: Vec::new(),
        out_of_order: Vec::new(),
        out_of_order_scans: 0,
    };
    for rows in scans {
        let Some(first) = rows.first() else { continue };
        let (t, t_text) = first.time();
        if out.scans.last().is_some_and(|s| t < s.t) {
            out.out_of_order.extend(rows.iter().map(ScanRow::line));
            out.out_of_order_scans += 1;
            continue;
        }
        out.scans.push(FileScan {
            line: first.line(),
            t_text,
            t,
            rows: rows.iter().map(|r| (r.line(), r.measurement())).collect(),
        });
    }
    out
}

fn file_scans(data: &Recording) -> Result<FileScans<'_>, ReplayError> {
    match data {
        Recording::Cartesian(m) if m.dims != 2 => Err(ReplayError::TrackerAxes { dims: m.dims }),
        Recording::Cartesian(m) => Ok(scans_of(m.scans())),
        Recording::RangeAzimuth(m) => Ok(scans_of(m.scans())),
    }
}

/// The median interval between consecutive scans, s (`None` for one scan).
pub fn median_scan_interval(times: &[f64]) -> Option<f64> {
    let mut intervals: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    if intervals.is_empty() {
        return None;
    }
    intervals.sort_by(f64::total_cmp);
    Some(intervals[intervals.len() / 2])
}

/// A positive length, m (σ, σ_R, `--region-m`).
const POSITIVE_LENGTH_M: Limit = Limit {
    min: f64::MIN_POSITIVE,
    max: envelope::MAX_POSITION_M,
};

impl SensorOptions {
    /// Each figure that can be given, by option, with the values it takes.
    fn figures(&self) -> [(&'static str, Option<f64>, Limit); 9] {
        [
            ("--region-m", self.region_m, POSITIVE_LENGTH_M),
            ("--sigma-m", self.sigma_m, POSITIVE_LENGTH_M),
            ("--range-sigma-m", self.range_sigma_m, POSITIVE_LENGTH_M),
            (
                "--bearing-sigma-deg",
                self.bearing_sigma_deg,
                Limit {
                    min: f64::MIN_POSITIVE,
                    max: 180.0,
                },
            ),
            ("--scan-period-s", self.scan_period_s, envelope::INTERVAL_S),
            (
                "--pd",
                self.detection_probability,
                Limit {
                    min: 1e-3,
                    max: 1.0,
                },
            ),
            (
                "--clutter-per-km2",
                self.clutter_per_km2,
                Limit { min: 0.0, max: 1e6 },
            ),
            (
                "--max-speed-mps",
                self.max_speed_m_per_s,
                Limit {
                    min: f64::MIN_POSITIVE,
                    max: envelope::VELOCITY_M_PER_S.max,
                },
            ),
            (
                "--max-accel-mps2",
                self.max_acceleration_m_per_s2,
                Limit {
                    min: f64::MIN_POSITIVE,
                    max: envelope::ACCELERATION_M_PER_S2.max,
                },
            ),
        ]
    }

    /// Every figure given inside the values it takes, and `--sigma-m` (a
    /// Cartesian sensor) not with the polar figures: all that can be
    /// checked before the file is read (the command line checks it when it
    /// is parsed; [`design_for`] again, for callers that build the options
    /// themselves).
    pub fn check(&self) -> Result<(), String> {
        for (name, value, limit) in self.figures() {
            if let Some(v) = value.filter(|&v| !(v.is_finite() && limit.contains(v))) {
                return Err(format!(
                    "{name} {v} is outside {} ..= {}",
                    limit.min, limit.max
                ));
            }
        }
        if self.sigma_m.is_some()
            && (self.range_sigma_m.is_some() || self.bearing_sigma_deg.is_some())
        {
            return Err(
                "--sigma-m (a Cartesian sensor) cannot be combined with --range-sigma-m \
                        or --bearing-sigma-deg (a polar one)"
                    .into(),
            );
        }
        Ok(())
    }
}

/// The design for `scans` of a file in the given layout (module docs):
/// the figures given ([`SensorOptions::check`]), the others the nominal
/// sensor's.
pub fn design_for(
    sensor: &SensorOptions,
    polar: bool,
    scan_times: &[f64],
    farthest_m: f64,
) -> Result<DesignUsed, ReplayError> {
    sensor.check().map_err(ReplayError::Design)?;
    let nominal = if polar {
        TrackerDesign::NOMINAL_TCAS
    } else {
        TrackerDesign::NOMINAL_RADAR
    };
    let accuracy = match (
        sensor.sigma_m,
        sensor.range_sigma_m,
        sensor.bearing_sigma_deg,
    ) {
        // Alone: `check` refuses it with the polar figures.
        (Some(sigma), _, _) => SensorAccuracy::Cartesian { sigma },
        (None, None, None) => nominal.accuracy,
        (None, r, b) => {
            let (r0, b0) = match TrackerDesign::NOMINAL_TCAS.accuracy {
                SensorAccuracy::Polar {
                    range_sigma,
                    bearing_sigma,
                } => (range_sigma, bearing_sigma.to_degrees()),
                SensorAccuracy::Cartesian { sigma } => (sigma, 5.0),
            };
            SensorAccuracy::Polar {
                range_sigma: r.unwrap_or(r0),
                bearing_sigma: b.unwrap_or(b0).to_radians(),
            }
        }
    };
    let median = median_scan_interval(scan_times);
    // A period given is checked; one taken from the file is brought into
    // the filters' range (a sparse or irregular file is run, not refused).
    let (scan_period, period) = match (sensor.scan_period_s, median) {
        (Some(given), _) => (given, PeriodSource::Given),
        (None, Some(m)) if envelope::INTERVAL_S.contains(m) => (m, PeriodSource::FileMedian),
        (None, Some(m)) => (
            m.clamp(envelope::INTERVAL_S.min, envelope::INTERVAL_S.max),
            PeriodSource::FileMedianClamped(m),
        ),
        (None, None) => (nominal.scan_period, PeriodSource::Given),
    };
    let coverage = match sensor.region_m {
        None => Coverage::None,
        Some(r) => {
            if polar {
                Coverage::Disc { radius: r }
            } else {
                Coverage::Square { half_width: r }
            }
        }
    };
    let design = TrackerDesign {
        accuracy,
        detection_probability: sensor
            .detection_probability
            .unwrap_or(nominal.detection_probability),
        clutter_density: sensor
            .clutter_per_km2
            .unwrap_or(nominal.clutter_density * 1e6)
            * 1e-6,
        coverage,
        // At least 1 m, so one measurement at the origin still has a disc.
        max_range: farthest_m.max(1.0),
        max_speed: sensor.max_speed_m_per_s.unwrap_or(nominal.max_speed),
        max_acceleration: sensor
            .max_acceleration_m_per_s2
            .unwrap_or(nominal.max_acceleration),
        scan_period,
    };
    let derived = design.derive().map_err(|e| {
        // Rule 5 is the one a figure in range can fail: so low a P_D that
        // no count of misses up to 255 keeps a true track's deletion rare.
        let reason = if e == ConfigError::Deletion {
            format!(
                "P_D {} is too low for design rule 5: no deletion after up to 255 misses keeps \
                 a true track from being deleted by missed detections more than once in {} \
                 scans",
                design.detection_probability,
                (1.0 / MAX_SPURIOUS_DELETIONS_PER_SCAN).round()
            )
        } else {
            e.to_string()
        };
        ReplayError::Design(format!(
            "no configuration meets the design rules for these figures: {reason} \
             ({}; the figures come from --sigma-m or --range-sigma-m/--bearing-sigma-deg, \
             --scan-period-s, --pd, --clutter-per-km2, --region-m, --max-speed-mps and \
             --max-accel-mps2)",
            design_figures(&design, period)
        ))
    })?;
    Ok(DesignUsed {
        design,
        derived,
        period,
        confirmation_given: false,
    })
}

/// `v` rounded to three significant digits, without an exponent (24300,
/// 100, 0.00251).
fn three_significant(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let scale = 10f64.powf(v.abs().log10().floor() - 2.0);
    let rounded = (v / scale).round() * scale;
    let decimals = (2.0 - rounded.abs().log10().floor()).max(0.0);
    format!("{rounded:.*}", decimals as usize)
}

/// Reads the whole input, picks the layout from its header and runs the
/// tracker: the output, or the first error (no partial output).
pub fn replay_tracker_reader<R: Read>(
    options: &TrackerOptions,
    input: R,
) -> Result<TrackerReplay, Failure> {
    let read = ReadOptions {
        times: TimeOrder::Scans,
        azimuth_unit: options.azimuth_unit,
    };
    let data = read_recording(input, read).map_err(Failure::Input)?;
    with_large_stack(|| match options.numeric {
        Numeric::F64 => run_in::<f64>(options, &data),
        Numeric::F32 => run_in::<f32>(options, &data),
        Numeric::Q32 => run_in::<Fix>(options, &data),
        Numeric::Fixed32 => run_fixed32(options, &data),
    })
    .map_err(Failure::Replay)
}

/// Stack for [`with_large_stack`]: `TrackTable::new` returns the table by
/// value, so it is built on the stack before it is boxed; the largest,
/// 256 `AnySchedule` tracks in f64, is 1.3 MB, more than a test thread's
/// 2 MB can hold twice.
pub const TABLE_STACK_BYTES: usize = 64 << 20;

/// Runs `f` on a thread with a [`TABLE_STACK_BYTES`] stack (see there).
pub fn with_large_stack<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    std::thread::scope(|s| {
        let worker = std::thread::Builder::new()
            .stack_size(TABLE_STACK_BYTES)
            .spawn_scoped(s, f)
            .expect("replay --tracker: cannot start the worker thread");
        worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// The file's scans on the table's clock, with empty scans added for gaps
/// (module docs), in `S`.
fn clocked_scans<'a, S: abtrack::Numeric>(
    scans: &'a [FileScan<'a>],
    period_s: f64,
) -> Result<(Vec<ScanInput<'a, S>>, usize), ReplayError> {
    let first_t = scans.first().map_or(0.0, |s| s.t);
    let mut out: Vec<ScanInput<'a, S>> = Vec::with_capacity(scans.len());
    let mut added = 0;
    let mut previous: Option<(f64, u32)> = None;
    for scan in scans {
        let now_ms = scan_clock_ms(scan.t, first_t).ok_or_else(|| ReplayError::ScanTime {
            line: scan.line,
            t: scan.t_text.to_string(),
        })?;
        if let Some((t0, ms0)) = previous {
            let gap = scan.t - t0;
            if gap > GAP_PERIODS * period_s {
                let parts = (gap / period_s).round() as u64;
                for k in 1..parts {
                    let ms =
                        ms0 + ((f64::from(now_ms - ms0) * k as f64) / parts as f64).round() as u32;
                    out.push(ScanInput {
                        line: 0,
                        t_text: clock_text(first_t, ms).into(),
                        now_ms: ms,
                        measurements: Vec::new(),
                        lines: Vec::new(),
                    });
                    added += 1;
                }
            }
        }
        let mut measurements = Vec::with_capacity(scan.rows.len());
        let mut lines = Vec::with_capacity(scan.rows.len());
        for &(line, m) in &scan.rows {
            measurements.push(match m {
                Measurement::Cartesian { x, y } => Measurement::Cartesian {
                    x: value(x, line, 2, "x")?,
                    y: value(y, line, 3, "y")?,
                },
                Measurement::Polar { range, azimuth } => Measurement::Polar {
                    range: value(range, line, 2, "range")?,
                    azimuth: value(azimuth, line, 3, "azimuth")?,
                },
            });
            lines.push(line);
        }
        out.push(ScanInput {
            line: scan.line,
            t_text: scan.t_text.into(),
            now_ms,
            measurements,
            lines,
        });
        previous = Some((scan.t, now_ms));
    }
    Ok((out, added))
}

/// An added scan's `t`: the first scan's time plus the clock, to the
/// millisecond.
fn clock_text(first_t: f64, ms: u32) -> String {
    let t = first_t + f64::from(ms) / 1000.0;
    let text = format!("{t:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A file's scans, ready for the table: the design and the clocked scans.
struct Prepared<'a, S: abtrack::Numeric> {
    design: DesignUsed,
    one_plot_scans: OnePlotScans,
    inputs: Vec<ScanInput<'a, S>>,
    added: usize,
    polar: bool,
    /// [`FileScans::out_of_order`].
    out_of_order: &'a [usize],
    /// [`FileScans::out_of_order_scans`].
    out_of_order_scans: usize,
}

fn prepare<'a, S: abtrack::Numeric>(
    options: &TrackerOptions,
    data: &'a Recording,
    file: &'a FileScans<'a>,
) -> Result<Prepared<'a, S>, ReplayError> {
    let scans = &file.scans;
    let polar = matches!(data, Recording::RangeAzimuth(_));
    let farthest = scans
        .iter()
        .flat_map(|s| s.rows.iter())
        .map(|(_, m)| match *m {
            Measurement::Cartesian { x, y } => x.hypot(y),
            Measurement::Polar { range, .. } => range,
        })
        .fold(0.0, f64::max);
    let first_t = scans.first().map_or(0.0, |s| s.t);
    if let Some(s) = scans.iter().find(|s| scan_clock_ms(s.t, first_t).is_none()) {
        return Err(ReplayError::ScanTime {
            line: s.line,
            t: s.t_text.to_string(),
        });
    }
    let times: Vec<f64> = scans.iter().map(|s| s.t).collect();
    let mut design = design_for(&options.sensor, polar, &times, farthest)?;
    design.confirmation_given = options.confirmation.is_some();
    let (inputs, added) = clocked_scans::<S>(scans, design.design.scan_period)?;
    Ok(Prepared {
        one_plot_scans: OnePlotScans::of(scans, &design.design),
        design,
        inputs,
        added,
        polar,
        out_of_order: &file.out_of_order,
        out_of_order_scans: file.out_of_order_scans,
    })
}

/// The threat columns of one track: position and velocity relative to the
/// own aircraft, and the row's line.
type ThreatCells<'a, S> = &'a dyn Fn(
    &mut String,
    [<S as abtrack::Numeric>::Length; 2],
    [<S as abtrack::Numeric>::Speed; 2],
    usize,
) -> Result<(), ReplayError>;

fn run_in<S: CsvValue + std::fmt::Display>(
    options: &TrackerOptions,
    data: &Recording,
) -> Result<TrackerReplay, ReplayError> {
    let file = file_scans(data)?;
    let prepared = prepare::<S>(options, data, &file)?;
    let own = own_aircraft::<S>(options.own_altitude_ft)?;
    let threat = own.map(|own| {
        move |out: &mut String, position: [S; 2], velocity: [S; 2], line: usize| {
            let intruder = Intruder {
                relative_position_m: position,
                relative_velocity_m_per_s: velocity,
                altitude: None,
            };
            write_threat_cells(out, &own, Some(&intruder), line)
        }
    });
    let threat: Option<ThreatCells<'_, S>> = threat.as_ref().map(|f| f as ThreatCells<'_, S>);
    if prepared.polar {
        if options.schedule.is_some() {
            return Err(ReplayError::TrackerScheduleNeedsCartesian);
        }
        let d = &prepared.design.design;
        let config = with_lifecycle(
            d.polar_config::<S>().map_err(ReplayError::TrackerConfig)?,
            options,
        )?;
        return by_capacity::<S, DefaultPolarTrack<S>>(options, &config, &prepared, threat);
    }
    run_cartesian(options, &prepared, threat)
}

/// [`run_in`] as the Cortex-M3 firmware runs it ([`Numeric::Fixed32`]):
/// x/y input without `--own-alt` in [`Fixed32`] (the scans' track table);
/// range/azimuth input or the threat columns in its wide format
/// [`ScaledScalar`] (the demo's range–azimuth tracks and TCAS logic).
fn run_fixed32(options: &TrackerOptions, data: &Recording) -> Result<TrackerReplay, ReplayError> {
    if options.own_altitude_ft.is_some() || matches!(data, Recording::RangeAzimuth(_)) {
        return run_in::<ScaledScalar>(options, data);
    }
    let file = file_scans(data)?;
    let prepared = prepare::<Fixed32>(options, data, &file)?;
    run_cartesian(options, &prepared, None)
}

/// The x/y table: the default filter, or `--schedule`'s.
fn run_cartesian<S: abtrack::Numeric<Length: std::fmt::Display, Speed: std::fmt::Display>>(
    options: &TrackerOptions,
    prepared: &Prepared<'_, S>,
    threat: Option<ThreatCells<'_, S>>,
) -> Result<TrackerReplay, ReplayError> {
    let config_error = ReplayError::TrackerConfig;
    let d = &prepared.design.design;
    match &options.schedule {
        None => {
            let config = with_lifecycle(d.cartesian_config::<S>().map_err(config_error)?, options)?;
            by_capacity::<S, DefaultCartesianTrack<S>>(options, &config, prepared, threat)
        }
        Some(spec) => {
            let schedule =
                ReplaySchedule::<S, 2>::from_spec(spec).map_err(ReplayError::Schedule)?;
            let config = with_lifecycle(
                d.tracker_config::<S, _>(schedule).map_err(config_error)?,
                options,
            )?;
            by_capacity::<S, ScheduledTrack<S, ReplaySchedule<S, 2>>>(
                options, &config, prepared, threat,
            )
        }
    }
}

/// `--confirm`, `--delete` and `--no-first-point-wait` applied to `config`.
pub fn with_lifecycle<S: abtrack::Numeric, P: Copy>(
    config: TrackerConfig<S, P>,
    options: &TrackerOptions,
) -> Result<TrackerConfig<S, P>, ReplayError> {
    let mut config = config.keep_first_points_through_a_miss(options.first_points_through_a_miss);
    if let Some((hits, window)) = options.confirmation {
        let (confirmed, _) = config.deletion();
        config = config
            .with_confirmation(hits, window)
            .and_then(|c| c.with_deletion(confirmed, window - hits + 1))
            .map_err(ReplayError::TrackerConfig)?;
    }
    if let Some(k) = options.delete_confirmed {
        let (_, tentative) = config.deletion();
        config = config
            .with_deletion(k, tentative)
            .map_err(ReplayError::TrackerConfig)?;
    }
    Ok(config)
}

fn by_capacity<
    S: abtrack::Numeric<Length: std::fmt::Display, Speed: std::fmt::Display>,
    F: TrackFilter<S>,
>(
    options: &TrackerOptions,
    config: &TrackerConfig<S, F::Params>,
    prepared: &Prepared<'_, S>,
    threat: Option<ThreatCells<'_, S>>,
) -> Result<TrackerReplay, ReplayError> {
    match options.capacity {
        16 => run_scans::<S, F, 16>(config, prepared, threat),
        64 => run_scans::<S, F, 64>(config, prepared, threat),
        _ => run_scans::<S, F, 256>(config, prepared, threat),
    }
}

/// The scan's time on the table's clock (see the module docs); `None`
/// beyond it.
pub fn scan_clock_ms(t: f64, first_t: f64) -> Option<u32> {
    let ms = ((t - first_t) * 1000.0).round();
    (ms >= 0.0 && ms <= f64::from(u32::MAX)).then_some(ms as u32)
}

/// The `--verbose` line of one scan.
fn log_scan(log: &mut String, t_text: &str, codes: &[Association], report: &ScanReport) {
    let count = |f: fn(&Association) -> bool| codes.iter().filter(|c| f(c)).count();
    let _ = writeln!(
        log,
        "t={t_text} measurements={} updated={} started={} not-assigned={} outside-gates={} \
         outside-volume={} rejected={} dropped={} | confirmed={} deleted={} displaced={} \
         restarted={} tracks={}",
        codes.len(),
        count(|c| matches!(c, Association::Updated(_))),
        count(|c| matches!(c, Association::Started(_))),
        count(|c| matches!(c, Association::NotAssigned)),
        count(|c| matches!(c, Association::OutsideGates)),
        count(|c| matches!(c, Association::OutsideVolume)),
        count(|c| matches!(c, Association::Rejected(_))),
        count(|c| matches!(c, Association::Dropped(_))),
        report.confirmed,
        report.deleted,
        report.deleted_displaced,
        report.restarted,
        report.tracks,
    );
}

fn run_scans<
    S: abtrack::Numeric<Length: std::fmt::Display, Speed: std::fmt::Display>,
    F: TrackFilter<S>,
    const N: usize,
>(
    config: &TrackerConfig<S, F::Params>,
    prepared: &Prepared<'_, S>,
    threat: Option<ThreatCells<'_, S>>,
) -> Result<TrackerReplay, ReplayError> {
    let (scans, design, added) = (&prepared.inputs, prepared.design, prepared.added);
    let mut table: Box<TrackTable<S, F, N, MAX_MEASUREMENTS>> = Box::new(TrackTable::new());
    let mut csv = tracker_header(threat.is_some());
    csv.push('\n');
    let mut scan_log = String::new();
    let mut unused = Unused {
        scans: scans.len() - added,
        empty_scans: added,
        out_of_order_scans: prepared.out_of_order_scans,
        ..Unused::default()
    };
    for &line in prepared.out_of_order {
        unused.measurements += 1;
        unused.out_of_order.add(line);
    }
    let mut codes = Vec::new();
    for scan in scans.iter() {
        if table.last_scan_ms() == Some(scan.now_ms) {
            // Rounds to the previous scan's millisecond: too close, as the
            // table skips any scan under 0.05 s.
            for &line in &scan.lines {
                unused.measurements += 1;
                unused.too_close.add(line);
            }
            continue;
        }
        codes.clear();
        codes.resize(scan.measurements.len(), Association::OutsideGates);
        let skipped_before = table.stats().scans_skipped;
        let report = table
            .scan(config, scan.now_ms, &scan.measurements, &mut codes)
            .map_err(|error| ReplayError::Scan {
                line: scan.line,
                t: scan.t_text.to_string(),
                error,
            })?;
        log_scan(&mut scan_log, &scan.t_text, &codes, &report);
        for (&code, &line) in codes.iter().zip(&scan.lines) {
            unused.measurements += 1;
            unused.record(code, line);
        }
        unused.tracks_restarted += report.restarted as usize;
        unused.tracks_displaced += report.deleted_displaced as usize;
        unused.tracks_lost_in_clutter += report.deleted_gate_too_wide as usize;
        if table.stats().scans_skipped != skipped_before {
            // Skipped: the tracks are as at the previous scan.
            continue;
        }
        let mut tracks: Vec<_> = table.tracks().collect();
        tracks.sort_by_key(|t| t.id());
        for track in tracks {
            let [x, y] = track.position();
            let [vx, vy] = track.velocity();
            // Positions inside the envelope; velocities finite only: young
            // tracks of a noisy bearing sensor legitimately exceed 1500 m/s
            // (5° at 25 km is 2 km across range), see docs/host-tools.md.
            let line = scan.line;
            check_estimate(line, "x", x, envelope::POSITION_M, "m")?;
            check_estimate(line, "y", y, envelope::POSITION_M, "m")?;
            check_estimate(line, "vx", vx, FINITE, "m/s")?;
            check_estimate(line, "vy", vy, FINITE, "m/s")?;
            let _ = write!(
                csv,
                "{},{},{}",
                scan.t_text,
                track.id(),
                track.status().as_str()
            );
            let _ = write!(csv, ",{x},{y},{vx},{vy}");
            if let Some(threat) = threat {
                threat(&mut csv, [x, y], [vx, vy], scan.line)?;
            }
            csv.push('\n');
        }
    }
    Ok(TrackerReplay {
        csv,
        scan_log,
        design,
        unused,
        one_plot_scans: prepared.one_plot_scans,
    })
}
