//! `replay --tracker`: the library's multi-target [`TrackTable`] over a
//! recording of scans (issue 5), in f64, f32 or Q32.32.
//!
//! # Input
//!
//! The `replay` CSV layouts ([`crate::csv_input`]), read with
//! [`TimeOrder::Scans`]: consecutive rows sharing a `t` are one scan, and a
//! time before the previous row's is refused naming its line. The layout is
//! chosen by the header:
//!
//! * `t,x,y` (m): the Cartesian tracker. `t,x` and `t,x,y,z` are refused
//!   (the table works in the x/y plane).
//! * `t,range,azimuth[,alt]` (m, rad clockwise from +y): the polar tracker.
//!   The `alt` column is read but not used: the table keeps no altitude.
//!
//! # Configuration
//!
//! With no option, the documented default design
//! ([`abtrack::track::defaults`]): [`default_cartesian`] (M2 least-squares
//! gains held at n_max = 9, uncertainty gate, 3-of-4 confirmation, deletion
//! after 4 / 2 misses, the nominal radar's 10 km square) for `t,x,y`, and
//! [`default_polar`] (He et al.'s filter with the nominal TCAS sensor's
//! noise, range/azimuth window, 3 of 4, 4 / 2, the 14 NM disc) for
//! `t,range,azimuth`. Options change one part and keep the rest:
//!
//! * `--schedule SPEC` (Cartesian only): any schedule of
//!   [`abtrack::gain::spec::SCHEDULES`] but `bank`, run as
//!   [`ScheduledTrack`] with [`ReplaySchedule`] (`AnySchedule`, windows of
//!   [`crate::replay::WINDOW_CAPACITY`]); the gate keeps the default's σ,
//!   threshold and a_max.
//! * `--capacity 16|64|256`: the table's N (a const generic, so a few sizes
//!   are compiled in); default [`DEFAULT_CAPACITY`]. Every table takes up to
//!   [`MAX_MEASUREMENTS`] measurements per scan; more are dropped and
//!   counted (association code `dropped`, see `--verbose`).
//! * `--confirm M/N`: M-of-N confirmation; the tentative deletion becomes
//!   N − M + 1 misses (rule 5 of the default design).
//! * `--delete K`: a confirmed track is deleted after K consecutive misses.
//!
//! # Time
//!
//! The table runs on a u32 millisecond clock. A scan at `t` seconds is given
//! `round((t − t₀)·1000)` ms, t₀ the first scan's time (so any start time
//! works, epoch seconds included), rounded half away from zero. Limits: a
//! scan more than 2³² − 1 ms (49.7 days) after the first is refused
//! ([`ReplayError::ScanTime`]), as are two scans that round to the same
//! millisecond and intervals over 2³¹ − 1 ms ([`ReplayError::Scan`]).
//!
//! # Output
//!
//! One row per live track per scan, in increasing id order:
//! `t,track_id,status,x,y,vx,vy` (`t` echoed as written, status
//! `tentative|confirmed|coasting`, position m and velocity m/s after the
//! scan). With `--own-alt FEET` the threat columns of `--filter
//! range-azimuth` follow ([`crate::replay::THREAT_COLUMNS`], written by the
//! same code), with the same assumptions (own aircraft at the origin, level
//! at FEET over sea-level terrain, zero own velocity) and no altitude per
//! track: every intruder counts as not reporting altitude, so advisories are
//! horizontal only, at most `ta`, `proximate` within 6 NM.
//!
//! The per-scan summary ([`TrackerReplay::scan_log`], printed by
//! `--verbose`) counts the association codes of the scan's measurements and
//! the table's confirmations, deletions and live tracks.

use std::fmt::Write as _;
use std::io::BufRead;

use abtrack::gain::spec::ScheduleSpec;
use abtrack::tcas::Intruder;
use abtrack::track::defaults::{
    default_cartesian, default_polar, DefaultCartesianTrack, DefaultPolarTrack,
};
use abtrack::track::{
    Association, Measurement, ScheduledTrack, TrackFilter, TrackTable, TrackerConfig,
};
use abtrack::{Fix, Scalar};

use crate::csv_input::{
    read_measurements_with, read_range_azimuth_with, sniff_format, CsvError, InputFormat, TimeOrder,
};
use crate::replay::{
    cell, own_aircraft, value, write_threat_cells, CsvValue, Failure, Numeric, ReplayError,
    ReplaySchedule, THREAT_COLUMNS,
};

/// The table capacities `--capacity` offers.
pub const CAPACITIES: [usize; 3] = [16, 64, 256];
/// N without `--capacity`.
pub const DEFAULT_CAPACITY: usize = 64;
/// M, the measurements per scan every table takes.
pub const MAX_MEASUREMENTS: usize = 256;

/// The output header.
pub fn tracker_header(threat: bool) -> String {
    let mut h = String::from("t,track_id,status,x,y,vx,vy");
    if threat {
        h.push(',');
        h.push_str(THREAT_COLUMNS);
    }
    h
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
    /// `--own-alt FEET`.
    pub own_altitude_ft: Option<f64>,
}

impl Default for TrackerOptions {
    fn default() -> Self {
        TrackerOptions {
            numeric: Numeric::F64,
            schedule: None,
            capacity: DEFAULT_CAPACITY,
            confirmation: None,
            delete_confirmed: None,
            own_altitude_ft: None,
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
}

/// One scan of the file in the table's number type.
struct ScanInput<'a, S> {
    /// Line of the scan's first row.
    line: usize,
    t_text: &'a str,
    t: f64,
    measurements: Vec<Measurement<S>>,
}

/// The file, parsed.
enum Data {
    Cartesian(crate::csv_input::Measurements),
    Polar(crate::csv_input::RangeAzimuthMeasurements),
}

/// Reads the whole input, picks the layout from its header and runs the
/// tracker: the output, or the first error (no partial output).
pub fn replay_tracker_reader<R: BufRead>(
    options: &TrackerOptions,
    mut input: R,
) -> Result<TrackerReplay, Failure> {
    let mut text = String::new();
    input
        .read_to_string(&mut text)
        .map_err(|e| Failure::Input(CsvError::Io(e.to_string())))?;
    let data = match sniff_format(&text) {
        Some(InputFormat::RangeAzimuth) => Data::Polar(
            read_range_azimuth_with(text.as_bytes(), TimeOrder::Scans).map_err(Failure::Input)?,
        ),
        // The Cartesian reader names a bad header (with a hint).
        _ => Data::Cartesian(
            read_measurements_with(text.as_bytes(), TimeOrder::Scans).map_err(Failure::Input)?,
        ),
    };
    with_large_stack(|| match options.numeric {
        Numeric::F64 => run_in::<f64>(options, &data),
        Numeric::F32 => run_in::<f32>(options, &data),
        Numeric::Fixed => run_in::<Fix>(options, &data),
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

fn run_in<S: CsvValue>(
    options: &TrackerOptions,
    data: &Data,
) -> Result<TrackerReplay, ReplayError> {
    let config_error = ReplayError::TrackerConfig;
    match data {
        Data::Cartesian(m) => {
            if m.dims != 2 {
                return Err(ReplayError::TrackerAxes { dims: m.dims });
            }
            let mut scans = Vec::new();
            for rows in m.scans() {
                let first = &rows[0];
                let mut measurements = Vec::with_capacity(rows.len());
                for r in rows {
                    measurements.push(Measurement::Cartesian {
                        x: value(r.z[0], r.line, 2, "x")?,
                        y: value(r.z[1], r.line, 3, "y")?,
                    });
                }
                scans.push(ScanInput {
                    line: first.line,
                    t_text: &first.t_text,
                    t: first.t,
                    measurements,
                });
            }
            let default = default_cartesian::<S>().map_err(config_error)?;
            match &options.schedule {
                None => {
                    let config = with_lifecycle(default, options)?;
                    by_capacity::<S, DefaultCartesianTrack<S>>(options, &config, &scans)
                }
                Some(spec) => {
                    let schedule =
                        ReplaySchedule::<S, 2>::from_spec(spec).map_err(ReplayError::Schedule)?;
                    let config = with_lifecycle(with_params(&default, schedule)?, options)?;
                    by_capacity::<S, ScheduledTrack<S, ReplaySchedule<S, 2>>>(
                        options, &config, &scans,
                    )
                }
            }
        }
        Data::Polar(m) => {
            if options.schedule.is_some() {
                return Err(ReplayError::TrackerScheduleNeedsCartesian);
            }
            let mut scans = Vec::new();
            for rows in m.scans() {
                let first = &rows[0];
                let mut measurements = Vec::with_capacity(rows.len());
                for r in rows {
                    measurements.push(Measurement::Polar {
                        range: value(r.range, r.line, 2, "range")?,
                        azimuth: value(r.azimuth, r.line, 3, "azimuth")?,
                    });
                }
                scans.push(ScanInput {
                    line: first.line,
                    t_text: &first.t_text,
                    t: first.t,
                    measurements,
                });
            }
            let config = with_lifecycle(default_polar::<S>().map_err(config_error)?, options)?;
            by_capacity::<S, DefaultPolarTrack<S>>(options, &config, &scans)
        }
    }
}

/// `config`'s gate, initiation, lifecycle and volume with other filter
/// parameters.
pub fn with_params<S: Scalar, P: Copy, Q: Copy>(
    config: &TrackerConfig<S, P>,
    params: Q,
) -> Result<TrackerConfig<S, Q>, ReplayError> {
    let (hits, window) = config.confirmation();
    let (confirmed, tentative) = config.deletion();
    let mut c = TrackerConfig::new(params, *config.gate(), config.max_speed())
        .and_then(|c| c.with_initiation_margin(config.initiation_margin()))
        .and_then(|c| c.with_confirmation(hits, window))
        .and_then(|c| c.with_deletion(confirmed, tentative))
        .map_err(ReplayError::TrackerConfig)?;
    if let Some(v) = config.volume() {
        c = c.with_volume(*v);
    }
    Ok(c)
}

/// `--confirm` and `--delete` applied to `config`.
pub fn with_lifecycle<S: Scalar, P: Copy>(
    config: TrackerConfig<S, P>,
    options: &TrackerOptions,
) -> Result<TrackerConfig<S, P>, ReplayError> {
    let mut config = config;
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

fn by_capacity<S: CsvValue, F: TrackFilter<S>>(
    options: &TrackerOptions,
    config: &TrackerConfig<S, F::Params>,
    scans: &[ScanInput<'_, S>],
) -> Result<TrackerReplay, ReplayError> {
    match options.capacity {
        16 => run_scans::<S, F, 16>(options, config, scans),
        64 => run_scans::<S, F, 64>(options, config, scans),
        _ => run_scans::<S, F, 256>(options, config, scans),
    }
}

/// The scan's time on the table's clock (see the module docs); `None`
/// beyond it.
pub fn scan_clock_ms(t: f64, first_t: f64) -> Option<u32> {
    let ms = ((t - first_t) * 1000.0).round();
    (ms >= 0.0 && ms <= f64::from(u32::MAX)).then_some(ms as u32)
}

/// The `--verbose` line of one scan.
fn log_scan(
    log: &mut String,
    t_text: &str,
    codes: &[Association],
    report: &abtrack::track::ScanReport,
) {
    let count = |f: fn(&Association) -> bool| codes.iter().filter(|c| f(c)).count();
    let _ = writeln!(
        log,
        "t={t_text} measurements={} updated={} started={} not-assigned={} outside-gates={} \
         rejected={} dropped={} | confirmed={} deleted={} tracks={}",
        codes.len(),
        count(|c| matches!(c, Association::Updated(_))),
        count(|c| matches!(c, Association::Started(_))),
        count(|c| matches!(c, Association::NotAssigned)),
        count(|c| matches!(c, Association::OutsideGates)),
        count(|c| matches!(c, Association::Rejected(_))),
        count(|c| matches!(c, Association::Dropped(_))),
        report.confirmed,
        report.deleted,
        report.tracks,
    );
}

fn run_scans<S: CsvValue, F: TrackFilter<S>, const N: usize>(
    options: &TrackerOptions,
    config: &TrackerConfig<S, F::Params>,
    scans: &[ScanInput<'_, S>],
) -> Result<TrackerReplay, ReplayError> {
    let own = own_aircraft::<S>(options.own_altitude_ft)?;
    let mut table: Box<TrackTable<S, F, N, MAX_MEASUREMENTS>> = Box::new(TrackTable::new());
    let mut csv = tracker_header(own.is_some());
    csv.push('\n');
    let mut scan_log = String::new();
    let first_t = scans.first().map_or(0.0, |s| s.t);
    let mut codes = Vec::new();
    for scan in scans {
        let now_ms = scan_clock_ms(scan.t, first_t).ok_or_else(|| ReplayError::ScanTime {
            line: scan.line,
            t: scan.t_text.to_string(),
        })?;
        codes.clear();
        codes.resize(scan.measurements.len(), Association::OutsideGates);
        let report = table
            .scan(config, now_ms, &scan.measurements, &mut codes)
            .map_err(|error| ReplayError::Scan {
                line: scan.line,
                t: scan.t_text.to_string(),
                error,
            })?;
        log_scan(&mut scan_log, scan.t_text, &codes, &report);
        let mut tracks: Vec<_> = table.tracks().collect();
        tracks.sort_by_key(|t| t.id());
        for track in tracks {
            let [x, y] = track.position();
            let [vx, vy] = track.velocity();
            let _ = write!(
                csv,
                "{},{},{}",
                scan.t_text,
                track.id(),
                track.status().as_str()
            );
            for v in [x, y, vx, vy] {
                cell(&mut csv, v);
            }
            if let Some(own) = &own {
                let intruder = Intruder {
                    relative_position_m: [x, y],
                    relative_velocity_m_per_s: [vx, vy],
                    altitude: None,
                };
                write_threat_cells(&mut csv, own, Some(&intruder), scan.line)?;
            }
            csv.push('\n');
        }
    }
    Ok(TrackerReplay { csv, scan_log })
}
