//! Running abtrack's track table over a simulated multi-target scenario:
//! the default tracker design for a scenario's sensor, one run in
//! any number type, and the association-decision comparison between number
//! types. Used by the `multi-target` experiment group and the
//! `claims::multi_target` tests.

use std::time::{Duration, Instant};

use abtrack::track::defaults::{Coverage, SensorAccuracy, TrackerDesign};
use abtrack::track::{
    Association, Measurement, ScanReport as TableScanReport, TableStats, TrackFilter,
    TrackStatus as TableStatus, TrackTable, TrackerConfig,
};
use abtrack::Scalar;

use crate::metrics::{ScanReport, TrackPoint, TrackStatus};
use crate::scenario::{self, MeasurementFrame, Region, ScenarioInfo, ScenarioRun, SensorNoise};

/// The default design ([`TrackerDesign`]) for a scenario's sensor: its noise,
/// P_D, clutter density and surveillance region, with the target envelope
/// (v_max, a_max) of the nominal sensor of the same kind
/// ([`TrackerDesign::NOMINAL_RADAR`] for Cartesian scenarios,
/// [`TrackerDesign::NOMINAL_TCAS`] for polar ones). For `two-crossing` and
/// `parallel-200m` this is exactly `NOMINAL_RADAR`, for `tcas-30` exactly
/// `NOMINAL_TCAS`; `dense` differs by its larger square and lower clutter
/// density. `None` for a scenario without a surveillance region, or with one
/// that is not a square or a disc centred on the sensor.
pub fn design_for(info: &ScenarioInfo) -> Option<TrackerDesign> {
    let accuracy = match info.noise {
        SensorNoise::Cartesian { x, y } => SensorAccuracy::Cartesian {
            sigma: ((x.sigma().powi(2) + y.sigma().powi(2)) / 2.0).sqrt(),
        },
        SensorNoise::Polar { range, azimuth } => SensorAccuracy::Polar {
            range_sigma: range.sigma(),
            bearing_sigma: azimuth.sigma(),
        },
    };
    let coverage = match info.surveillance? {
        Region::Rectangle {
            x_min,
            x_max,
            y_min,
            y_max,
        } if x_min == -x_max && y_min == -y_max && x_max == y_max => {
            Coverage::Square { half_width: x_max }
        }
        Region::Rectangle { .. } => return None,
        Region::Disc { radius } => Coverage::Disc { radius },
    };
    let nominal = match info.frame {
        MeasurementFrame::Cartesian => TrackerDesign::NOMINAL_RADAR,
        MeasurementFrame::Polar => TrackerDesign::NOMINAL_TCAS,
    };
    Some(TrackerDesign {
        accuracy,
        detection_probability: info.detection_probability,
        clutter_density: info.clutter.map_or(0.0, |c| c.density_per_m2()),
        coverage,
        max_range: coverage.max_range()?,
        scan_period: info.period_s,
        ..nominal
    })
}

/// Scan time in the table's millisecond clock.
pub fn scan_time_ms(t: f64) -> u32 {
    (t * 1000.0).round() as u32
}

/// A scenario measurement in the table's number type.
pub fn to_measurement<S: Scalar>(m: &scenario::Measurement) -> Result<Measurement<S>, String> {
    let c = |v: f64| S::try_from_f64(v).map_err(|e| format!("{v} not representable: {e:?}"));
    Ok(match *m {
        scenario::Measurement::Cartesian { x, y, .. } => {
            Measurement::Cartesian { x: c(x)?, y: c(y)? }
        }
        scenario::Measurement::Polar { range, azimuth, .. } => Measurement::Polar {
            range: c(range)?,
            azimuth: c(azimuth)?,
        },
    })
}

fn status(s: TableStatus) -> TrackStatus {
    match s {
        TableStatus::Tentative => TrackStatus::Tentative,
        TableStatus::Confirmed => TrackStatus::Confirmed,
        TableStatus::Coasting => TrackStatus::Coasting,
    }
}

/// Everything one run of the table produced.
#[derive(Debug, Clone)]
pub struct TrackerRun {
    /// Truth and every live track (all statuses) after each scan, for
    /// [`crate::metrics`].
    pub scans: Vec<ScanReport>,
    /// The association code of every measurement, scan by scan, in the
    /// scenario's row order.
    pub codes: Vec<Vec<Association>>,
    /// The table's per-stage counts of every scan.
    pub reports: Vec<TableScanReport>,
    pub stats: TableStats,
    /// Wall time spent inside `TrackTable::scan` (host).
    pub scan_time: Duration,
}

/// Runs a fresh `TrackTable<S, F, N, M>` over every scan of `run`.
pub fn run_table<S, F, const N: usize, const M: usize>(
    run: &ScenarioRun,
    config: &TrackerConfig<S, F::Params>,
) -> Result<TrackerRun, String>
where
    S: Scalar,
    F: TrackFilter<S>,
{
    let mut table: Box<TrackTable<S, F, N, M>> = Box::new(TrackTable::new());
    let mut out = TrackerRun {
        scans: Vec::with_capacity(run.scans.len()),
        codes: Vec::with_capacity(run.scans.len()),
        reports: Vec::with_capacity(run.scans.len()),
        stats: TableStats::default(),
        scan_time: Duration::ZERO,
    };
    let mut measurements: Vec<Measurement<S>> = Vec::new();
    for scan in &run.scans {
        measurements.clear();
        for m in &scan.measurements {
            measurements.push(to_measurement(m)?);
        }
        let mut codes = vec![Association::OutsideGates; measurements.len()];
        let start = Instant::now();
        let report = table
            .scan(config, scan_time_ms(scan.t), &measurements, &mut codes)
            .map_err(|e| format!("scan at t = {} s refused: {e}", scan.t))?;
        out.scan_time += start.elapsed();
        let tracks = table
            .tracks()
            .map(|t| {
                let [x, y] = t.position();
                TrackPoint {
                    id: t.id().get(),
                    status: status(t.status()),
                    x: x.to_f64(),
                    y: y.to_f64(),
                }
            })
            .collect();
        out.scans.push(ScanReport {
            t: scan.t,
            truth: scan.truth_points(),
            tracks,
        });
        out.codes.push(codes);
        out.reports.push(report);
    }
    out.stats = *table.stats();
    Ok(out)
}

/// What kind of decision a code records, without the track id (ids of two
/// runs are comparable only until their decisions first differ).
pub fn code_kind(c: &Association) -> &'static str {
    match c {
        Association::Updated(_) => "updated",
        Association::Started(_) => "started",
        Association::NotAssigned => "not-assigned",
        Association::OutsideGates => "outside-gates",
        Association::OutsideVolume => "outside-volume",
        Association::Rejected(_) => "rejected",
        Association::Dropped(_) => "dropped",
    }
}

/// How the association codes of one run in another number type compare
/// with the f64 run on the same measurements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DecisionDiff {
    /// Codes compared (every measurement of every scan).
    pub codes: usize,
    /// Codes that differ (track ids included).
    pub differing_codes: usize,
    /// Scans with at least one differing code.
    pub differing_scans: usize,
    /// Index of the first scan with a difference.
    pub first_scan: Option<usize>,
    /// Index (in that scan) of the first differing code.
    pub first_measurement: Option<usize>,
}

impl DecisionDiff {
    pub fn any(&self) -> bool {
        self.differing_codes > 0
    }
}

/// Compares two runs' codes scan by scan (`reference` is the f64 run).
pub fn compare_decisions(reference: &TrackerRun, other: &TrackerRun) -> DecisionDiff {
    let mut d = DecisionDiff::default();
    for (k, (a, b)) in reference.codes.iter().zip(&other.codes).enumerate() {
        d.codes += a.len().max(b.len());
        let mut scan_differs = a.len() != b.len();
        d.differing_codes += a.len().abs_diff(b.len());
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            if x != y {
                d.differing_codes += 1;
                if d.first_measurement.is_none() {
                    d.first_measurement = Some(i);
                    d.first_scan = Some(k);
                }
                scan_differs = true;
            }
        }
        if scan_differs {
            d.differing_scans += 1;
            if d.first_scan.is_none() {
                d.first_scan = Some(k);
            }
        }
    }
    d
}

/// Identity switches with continuity (the CLEAR-MOT rule of Bernardin &
/// Stiefelhagen, "Evaluating multiple object tracking performance: the
/// CLEAR MOT metrics", 2008, §2.1.1): at each scan a target keeps the
/// established track it corresponded to before if that track is still
/// established and within `gate` (m); only the remaining targets and tracks
/// are matched anew (optimal assignment minimising Σ min(d, gate), pairs
/// closer than `gate`), and a target matched to a track other than its
/// previous one is a switch.
///
/// Why besides [`crate::metrics::track_metrics`]'s id changes: that count
/// re-solves the whole assignment at every scan, so when two targets are
/// closer than the tracks' errors (the `two-crossing` targets coincide at
/// t = 30 s) the assignment flips between two correctly held tracks and
/// counts two changes per target although no track changed target. Here a
/// correspondence is only broken when its track is gone or has drifted
/// more than `gate` from the target.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct IdentitySwitches {
    /// (scan time, target) of every switch.
    pub switches: Vec<(f64, u32)>,
}

impl IdentitySwitches {
    pub fn count(&self) -> usize {
        self.switches.len()
    }
    /// Switches at times in `t0 ..= t1`.
    pub fn count_between(&self, t0: f64, t1: f64) -> usize {
        self.switches
            .iter()
            .filter(|(t, _)| *t >= t0 && *t <= t1)
            .count()
    }
}

/// See [`IdentitySwitches`]. A distance that is not finite (a position
/// that is not) is refused.
pub fn identity_switches(
    scans: &[ScanReport],
    gate: f64,
) -> Result<IdentitySwitches, crate::metrics::NonFiniteCost> {
    use std::collections::BTreeMap;
    let mut current: BTreeMap<u32, u32> = BTreeMap::new();
    let mut out = IdentitySwitches::default();
    for scan in scans {
        let est: Vec<&TrackPoint> = scan
            .tracks
            .iter()
            .filter(|t| t.status.is_established())
            .collect();
        let dist = |p: &crate::metrics::TruthPoint, t: &TrackPoint| (t.x - p.x).hypot(t.y - p.y);
        let mut track_used = vec![false; est.len()];
        let mut target_done = vec![false; scan.truth.len()];
        for (i, p) in scan.truth.iter().enumerate() {
            let Some(&id) = current.get(&p.id) else {
                continue;
            };
            if let Some(j) = est.iter().position(|t| t.id == id) {
                if !track_used[j] && dist(p, est[j]) < gate {
                    track_used[j] = true;
                    target_done[i] = true;
                }
            }
        }
        let rows: Vec<usize> = (0..scan.truth.len()).filter(|&i| !target_done[i]).collect();
        let cols: Vec<usize> = (0..est.len()).filter(|&j| !track_used[j]).collect();
        if rows.is_empty() || cols.is_empty() {
            continue;
        }
        let distance: Vec<Vec<f64>> = rows
            .iter()
            .map(|&i| cols.iter().map(|&j| dist(&scan.truth[i], est[j])).collect())
            .collect();
        crate::metrics::finite_costs(&distance)?;
        let cost: Vec<Vec<f64>> = distance
            .iter()
            .map(|row| row.iter().map(|d| d.min(gate)).collect())
            .collect();
        for (r, c) in crate::metrics::assignment(&cost)?.into_iter().enumerate() {
            let Some(c) = c else { continue };
            if cost[r][c] >= gate {
                continue;
            }
            let target = scan.truth[rows[r]].id;
            let id = est[cols[c]].id;
            if current.insert(target, id).is_some_and(|prev| prev != id) {
                out.switches.push((scan.t, target));
            }
        }
    }
    Ok(out)
}
