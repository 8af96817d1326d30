//! Group `multi-target`: the default tracker of
//! `abtrack::track::defaults` on the four multi-target scenarios, over Monte
//! Carlo runs, in f64, f32 and Q32.32.
//!
//! Per scenario: OSPA (cut-off c, order p = 2), id changes per true target,
//! runs in which every target kept one track id, tracks never paired with
//! a target (count and duration), completeness, latency to confirm, table refusals; the tracks
//! over the truth of run 0 and the mean OSPA against time; and the number of
//! association decisions of the f32 and fixed-point trackers that differ
//! from f64 on the same measurements.
//!
//! Configurations: the Cartesian scenarios run
//! `AutoFilter<S, 2>` (`auto` fused, params `AutoGains<S, 2>`) with
//! `TrackerDesign::cartesian_config`, `tcas-30` runs `RangeAzimuthTrack<S>`
//! (polar measurements used as range and azimuth, gated by a window in
//! range and azimuth) with `TrackerDesign::polar_config`; the design is
//! [`design_for`] the scenario's sensor (see `abtrack::track::defaults`).

use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::mem::size_of;
use std::time::Instant;

use abtrack::filter::auto::AutoFilter;
use abtrack::gain::{AnySchedule, FirmnessGains, FixedGains, LeastSquaresGains, LiImprovedGains};
use abtrack::track::defaults::DerivedParameters;
use abtrack::track::{FixedGainTrack, RangeAzimuthTrack, ScheduledTrack, TrackSlot};
use abtrack::{Fix, Fixed32};

use super::common::{fmt_ci, plot, write_file, Context, PlotSpec, Series, Table};
use crate::metrics::{mean_ci95, ospa_against_time, track_metrics, MeanCi};
use crate::scenario::{self, MeasurementFrame, ScenarioInfo, ScenarioRun};
use crate::tracking::{
    code_kind, compare_decisions, design_for, identity_switches, run_table, DecisionDiff,
    TrackerRun,
};

pub const NAME: &str = "multi-target";
pub const ABOUT: &str =
    "default tracker on two-crossing, parallel-200m, tcas-30, dense (f64/f32/fixed)";

/// Base seed of the group's Monte Carlo runs (run r uses
/// `monte_carlo_seed(BASE_SEED, r)`).
pub const BASE_SEED: u64 = 0x155E_0005;

/// OSPA order p.
pub const OSPA_ORDER: f64 = 2.0;

/// One scenario of the group.
#[derive(Debug, Clone, Copy)]
pub struct Plan {
    /// Row label (the scenario name, or the name and the variant).
    pub label: &'static str,
    pub scenario: &'static str,
    /// For a polar scenario: convert the measurements to x, y and run the
    /// default Cartesian tracker (σ = σ_max) instead of the range–azimuth
    /// filter, for comparison.
    pub cartesian_converted: bool,
    /// Documented Monte Carlo runs.
    pub runs: usize,
    /// OSPA cut-off c (m), also the track-to-truth assignment gate of the
    /// track metrics.
    pub ospa_cutoff: f64,
    /// Time window (s) around the crossing in which id changes are counted
    /// separately.
    pub crossing_window: Option<(f64, f64)>,
    /// Table capacity N (tracks) and M (measurements per scan), for the
    /// record; the types are fixed in [`run_types`].
    pub capacity: (usize, usize),
}

impl Plan {
    /// File-name stem of the plan's plots.
    pub fn slug(&self) -> String {
        if self.cartesian_converted {
            format!("{}-xy", self.scenario)
        } else {
            self.scenario.to_string()
        }
    }
}

/// The scenarios, runs and cut-offs. c = 100 m for the Cartesian scenarios
/// (5σ of the 20 m sensor: a track further off than that is as bad as a
/// missing one); c = 1852 m (1 NM) for `tcas-30`, whose bearing error alone
/// is 280–1600 m across range at 2–10 NM.
pub const PLANS: &[Plan] = &[
    Plan {
        label: "two-crossing",
        scenario: "two-crossing",
        cartesian_converted: false,
        runs: 500,
        ospa_cutoff: 100.0,
        crossing_window: Some((20.0, 40.0)),
        capacity: (32, 64),
    },
    Plan {
        label: "parallel-200m",
        scenario: "parallel-200m",
        cartesian_converted: false,
        runs: 500,
        ospa_cutoff: 100.0,
        crossing_window: None,
        capacity: (32, 64),
    },
    Plan {
        label: "tcas-30",
        scenario: "tcas-30",
        cartesian_converted: false,
        runs: 200,
        ospa_cutoff: 1852.0,
        crossing_window: None,
        capacity: (64, 64),
    },
    Plan {
        label: "tcas-30 (x, y)",
        scenario: "tcas-30",
        cartesian_converted: true,
        runs: 200,
        ospa_cutoff: 1852.0,
        crossing_window: None,
        capacity: (64, 64),
    },
    Plan {
        label: "dense",
        scenario: "dense",
        cartesian_converted: false,
        runs: 200,
        ospa_cutoff: 100.0,
        crossing_window: None,
        capacity: (64, 128),
    },
];

/// Runs the scenario in f64, f32 and Q32.32 (`Fix`) with the default design, the table
/// capacity of its [`Plan`].
pub fn run_types(
    plan: &Plan,
    info: &ScenarioInfo,
    run: &ScenarioRun,
) -> Result<[TrackerRun; 3], String> {
    let design = design_for(info).ok_or("scenario has no surveillance region")?;
    let e = |e| format!("{}: configuration refused: {e}", info.name);
    macro_rules! three {
        ($filter:ident, $config:ident, $n:literal, $m:literal) => {{
            let c64 = design.$config::<f64>().map_err(e)?;
            let c32 = design.$config::<f32>().map_err(e)?;
            let cfx = design.$config::<Fix>().map_err(e)?;
            [
                run_table::<f64, $filter<f64>, $n, $m>(run, &c64)?,
                run_table::<f32, $filter<f32>, $n, $m>(run, &c32)?,
                run_table::<Fix, $filter<Fix>, $n, $m>(run, &cfx)?,
            ]
        }};
    }
    type Cart<S> = abtrack::track::defaults::DefaultCartesianTrack<S>;
    Ok(match (info.frame, plan.capacity) {
        (MeasurementFrame::Polar, (64, 64)) if plan.cartesian_converted => {
            three!(Cart, cartesian_config, 64, 64)
        }
        (MeasurementFrame::Polar, (64, 64)) => three!(RangeAzimuthTrack, polar_config, 64, 64),
        (MeasurementFrame::Cartesian, (32, 64)) => three!(Cart, cartesian_config, 32, 64),
        (MeasurementFrame::Cartesian, (64, 128)) => three!(Cart, cartesian_config, 64, 128),
        other => return Err(format!("{}: no table type for {other:?}", info.name)),
    })
}

/// The numbers of one run in one number type.
#[derive(Debug, Clone, Default)]
pub struct RunFigures {
    pub ospa: f64,
    pub ospa_localisation: f64,
    pub ospa_cardinality: f64,
    /// Id changes as `metrics::track_metrics` counts them (per-scan
    /// assignment).
    pub id_changes: usize,
    /// Identity switches with continuity ([`identity_switches`]).
    pub id_switches: usize,
    pub targets: usize,
    /// No identity switch over the whole run.
    pub ids_kept: bool,
    /// No identity switch inside the crossing window.
    pub ids_kept_in_window: Option<bool>,
    /// Established tracks never paired with a target.
    pub never_paired: usize,
    /// Durations (s) of the tracks never paired.
    pub never_paired_durations: Vec<f64>,
    pub completeness: f64,
    /// Mean latency to confirm over the targets that were tracked (s).
    pub latency: Option<f64>,
    /// Targets never tracked.
    pub never_tracked: usize,
    pub refused_table_full: u32,
    pub dropped_overflow: u32,
    pub scans: usize,
    pub scan_seconds: f64,
}

/// Computes [`RunFigures`] from a run's output.
pub fn figures(plan: &Plan, out: &TrackerRun) -> Result<RunFigures, String> {
    let c = plan.ospa_cutoff;
    let refused = |e: crate::metrics::NonFiniteCost| format!("{}: {e}", plan.label);
    let ospa = ospa_against_time(&out.scans, c, OSPA_ORDER).map_err(refused)?;
    let n = ospa.len().max(1) as f64;
    let m = track_metrics(&out.scans, c).map_err(refused)?;
    let switches = identity_switches(&out.scans, c).map_err(refused)?;
    let window = plan
        .crossing_window
        .map(|(t0, t1)| switches.count_between(t0, t1) == 0);
    let latencies: Vec<f64> = m
        .targets
        .iter()
        .filter_map(|t| t.latency_to_confirm_s)
        .collect();
    Ok(RunFigures {
        ospa: ospa.iter().map(|(_, o)| o.distance).sum::<f64>() / n,
        ospa_localisation: ospa.iter().map(|(_, o)| o.localisation).sum::<f64>() / n,
        ospa_cardinality: ospa.iter().map(|(_, o)| o.cardinality).sum::<f64>() / n,
        id_changes: m.id_changes,
        id_switches: switches.count(),
        targets: m.targets.len(),
        ids_kept: switches.count() == 0,
        ids_kept_in_window: window,
        never_paired: m.never_paired.len(),
        never_paired_durations: m.never_paired.iter().map(|f| f.duration_s()).collect(),
        completeness: m.completeness,
        latency: (!latencies.is_empty())
            .then(|| latencies.iter().sum::<f64>() / latencies.len() as f64),
        never_tracked: m.targets.iter().filter(|t| t.scans_tracked == 0).count(),
        refused_table_full: out.stats.refused_table_full,
        dropped_overflow: out.stats.dropped_overflow,
        scans: out.scans.len(),
        scan_seconds: out.scan_time.as_secs_f64(),
    })
}

/// One Monte Carlo run: figures per number type, decision comparisons with
/// f64, and the f64 OSPA series.
#[derive(Debug, Clone)]
pub struct RunResult {
    pub figures: [RunFigures; 3],
    /// f32 vs f64, Q32.32 vs f64.
    pub diffs: [DecisionDiff; 2],
    /// "f64 kind → other kind" of the first differing code, per type.
    pub first_diff: [Option<String>; 2],
    /// (t, distance, localisation, cardinality) per scan, f64.
    pub ospa_series: Vec<(f64, f64, f64, f64)>,
}

fn first_diff_label(a: &TrackerRun, b: &TrackerRun, d: &DecisionDiff) -> Option<String> {
    let (k, i) = (d.first_scan?, d.first_measurement?);
    let x = a.codes.get(k)?.get(i)?;
    let y = b.codes.get(k)?.get(i)?;
    Some(format!("{} -> {}", code_kind(x), code_kind(y)))
}

/// Runs one seed of a scenario in the three types.
pub fn one_run(
    plan: &Plan,
    info: &ScenarioInfo,
    seed: u64,
) -> Result<(RunResult, TrackerRun), String> {
    let run = scenario::generate(plan.scenario, seed).map_err(|e| e.to_string())?;
    let [r64, r32, rfx] = run_types(plan, info, &run)?;
    let d32 = compare_decisions(&r64, &r32);
    let dfx = compare_decisions(&r64, &rfx);
    let result = RunResult {
        figures: [
            figures(plan, &r64)?,
            figures(plan, &r32)?,
            figures(plan, &rfx)?,
        ],
        first_diff: [
            first_diff_label(&r64, &r32, &d32),
            first_diff_label(&r64, &rfx, &dfx),
        ],
        diffs: [d32, dfx],
        ospa_series: ospa_against_time(&r64.scans, plan.ospa_cutoff, OSPA_ORDER)
            .map_err(|e| format!("{}: {e}", plan.label))?
            .into_iter()
            .map(|(t, o)| (t, o.distance, o.localisation, o.cardinality))
            .collect(),
    };
    Ok((result, r64))
}

/// Runs `runs` seeds, spread over the cores by rayon; returns the results
/// in run order and the f64 output of run 0.
pub fn monte_carlo(
    plan: &Plan,
    info: &ScenarioInfo,
    runs: usize,
) -> Result<(Vec<RunResult>, TrackerRun), String> {
    // Only run 0's full output is kept (the others' would fill memory).
    let outcomes = (0..runs)
        .into_par_iter()
        .map(|r| {
            one_run(plan, info, scenario::monte_carlo_seed(BASE_SEED, r as u64))
                .map(|(res, out)| (res, (r == 0).then_some(out)))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut first = None;
    let mut results = Vec::with_capacity(runs);
    for (res, out) in outcomes {
        first = first.or(out);
        results.push(res);
    }
    Ok((results, first.ok_or("run 0 missing")?))
}

const TYPES: [&str; 3] = ["f64", "f32", "q32"];

fn ci_of(results: &[RunResult], t: usize, f: impl Fn(&RunFigures) -> f64) -> MeanCi {
    let v: Vec<f64> = results.iter().map(|r| f(&r.figures[t])).collect();
    mean_ci95(&v)
}

/// Wilson 95 % interval of a proportion k/n, as "p (lo–hi)" in percent.
pub fn proportion(k: usize, n: usize) -> String {
    if n == 0 {
        return "n/a".into();
    }
    let z = 1.959_964f64;
    let nf = n as f64;
    let p = k as f64 / nf;
    let denom = 1.0 + z * z / nf;
    let centre = (p + z * z / (2.0 * nf)) / denom;
    let half = z * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt() / denom;
    format!(
        "{:.1} % ({:.1}–{:.1})",
        100.0 * p,
        100.0 * (centre - half).max(0.0),
        100.0 * (centre + half).min(1.0)
    )
}

/// Aggregated figures of one scenario in one number type.
struct Aggregate {
    row: Vec<String>,
}

fn aggregate(plan: &Plan, results: &[RunResult], t: usize) -> Aggregate {
    let n = results.len();
    let ospa = ci_of(results, t, |f| f.ospa);
    let loc = ci_of(results, t, |f| f.ospa_localisation);
    let card = ci_of(results, t, |f| f.ospa_cardinality);
    let idc = ci_of(results, t, |f| {
        f.id_changes as f64 / f.targets.max(1) as f64
    });
    let ids = ci_of(results, t, |f| {
        f.id_switches as f64 / f.targets.max(1) as f64
    });
    let kept = results.iter().filter(|r| r.figures[t].ids_kept).count();
    let window = plan.crossing_window.map(|_| {
        results
            .iter()
            .filter(|r| r.figures[t].ids_kept_in_window == Some(true))
            .count()
    });
    let never_paired = ci_of(results, t, |f| f.never_paired as f64);
    let none_never_paired = results
        .iter()
        .filter(|r| r.figures[t].never_paired == 0)
        .count();
    let durations: Vec<f64> = results
        .iter()
        .flat_map(|r| r.figures[t].never_paired_durations.iter().copied())
        .collect();
    let completeness = ci_of(results, t, |f| f.completeness);
    let latencies: Vec<f64> = results
        .iter()
        .filter_map(|r| r.figures[t].latency)
        .collect();
    let latency = mean_ci95(&latencies);
    let never: usize = results.iter().map(|r| r.figures[t].never_tracked).sum();
    let refused = ci_of(results, t, |f| f64::from(f.refused_table_full));
    let us_per_scan = 1e6
        * results
            .iter()
            .map(|r| r.figures[t].scan_seconds)
            .sum::<f64>()
        / results
            .iter()
            .map(|r| r.figures[t].scans)
            .sum::<usize>()
            .max(1) as f64;
    let duration = match durations.len() {
        0 => "–".to_string(),
        1 => format!("{:.1} (1 track)", durations[0]),
        n => format!("{} ({n} tracks)", fmt_ci(&mean_ci95(&durations), 1)),
    };
    Aggregate {
        row: vec![
            plan.label.to_string(),
            TYPES[t].to_string(),
            n.to_string(),
            fmt_ci(&ospa, 1),
            fmt_ci(&loc, 1),
            fmt_ci(&card, 1),
            fmt_ci(&ids, 3),
            fmt_ci(&idc, 3),
            proportion(kept, n),
            window.map_or("–".into(), |w| proportion(w, n)),
            fmt_ci(&never_paired, 2),
            proportion(none_never_paired, n),
            duration,
            fmt_ci(&completeness, 3),
            if latencies.is_empty() {
                "–".into()
            } else {
                fmt_ci(&latency, 2)
            },
            never.to_string(),
            fmt_ci(&refused, 1),
            format!("{us_per_scan:.0}"),
        ],
    }
}

const METRIC_HEADERS: [&str; 18] = [
    "scenario",
    "type",
    "runs",
    "OSPA (m)",
    "OSPA loc. (m)",
    "OSPA card. (m)",
    "id switches / target (continuity)",
    "id changes / target (per-scan assignment)",
    "runs without id switch (95 % CI)",
    "runs without id switch in the crossing window",
    "tracks never paired / run",
    "runs without a track never paired",
    "duration of tracks never paired (s, pooled)",
    "completeness",
    "latency to confirm (s)",
    "targets never tracked (all runs)",
    "table-full refusals / run",
    "host µs / scan",
];

fn design_rows(table: &mut Table, scenario: &str, d: &DerivedParameters, plan: &Plan) {
    table.push([
        scenario.to_string(),
        format!("{:.2} ({:.4})", d.gate_threshold, d.gate_probability),
        format!("{:.3}", d.tracking_index),
        format!("{:.3}", d.steady_state_alpha),
        d.least_squares_n_max.to_string(),
        format!("{:.2}", d.process_noise),
        format!("{:.0}", d.initiation_margin),
        format!("{} of {}", d.confirmation.0, d.confirmation.1),
        format!("{:.4}", d.true_confirmation_probability),
        format!("{:.3}", d.false_starts_per_scan),
        format!("{:.2e}", d.false_gate_hit_probability),
        format!("{:.2e}", d.false_confirmations_per_scan),
        format!("{}, {}", d.deletion.0, d.deletion.1),
        format!("{:.2e}", d.spurious_deletions_per_scan),
        format!("N = {}, M = {}", plan.capacity.0, plan.capacity.1),
    ]);
}

fn bytes_table() -> Table {
    let mut t = Table::new([
        "filter F (the table's slot, TrackSlot<S, F>)",
        "f64",
        "f32",
        "q32 (Q32.32)",
        "fixed (Fixed32)",
    ]);
    // The track type for each number system S.
    macro_rules! row {
        ($label:expr, $track:ident<S $(, $extra:ty)?>) => {
            t.push([
                $label.to_string(),
                size_of::<TrackSlot<f64, $track<f64 $(, $extra)?>>>().to_string(),
                size_of::<TrackSlot<f32, $track<f32 $(, $extra)?>>>().to_string(),
                size_of::<TrackSlot<Fix, $track<Fix $(, $extra)?>>>().to_string(),
                size_of::<TrackSlot<Fixed32, $track<Fixed32 $(, $extra)?>>>().to_string(),
            ]);
        };
    }
    row!(
        "FixedGainTrack (fixed gains, for comparison)",
        FixedGainTrack<S>
    );
    row!("ScheduledTrack<S, LeastSquaresGains> (M2)", ScheduledTrack<S, LeastSquaresGains>);
    row!(
        "AutoFilter<S, 2>, auto fused (default Cartesian)",
        AutoTrack<S>
    );
    row!("ScheduledTrack<S, FixedGains<S>> (M1)", FixedGainsTrack<S>);
    row!("ScheduledTrack<S, LiImprovedGains<S>>", LiTrack<S>);
    row!("ScheduledTrack<S, FirmnessGains> (TCAS)", ScheduledTrack<S, FirmnessGains>);
    row!(
        "ScheduledTrack<S, AnySchedule<S, 2, 8>> (any schedule)",
        AnyScheduleTrack<S>
    );
    row!("RangeAzimuthTrack (default polar)", RangeAzimuthTrack<S>);
    t
}

/// Track types whose other parameters name the number system too, as one
/// parameter for `row!`.
type AutoTrack<S> = AutoFilter<S, 2>;
type FixedGainsTrack<S> = ScheduledTrack<S, FixedGains<S>>;
type LiTrack<S> = ScheduledTrack<S, LiImprovedGains<S>>;
type AnyScheduleTrack<S> = ScheduledTrack<S, AnySchedule<S, 2, 8>>;

/// The group's entry point.
pub fn run(ctx: &Context) -> Result<(), String> {
    let dir = ctx.group_dir(NAME)?;
    let started = Instant::now();
    let mut metrics = Table::new(METRIC_HEADERS);
    let mut decisions = Table::new([
        "scenario",
        "type",
        "runs",
        "codes compared",
        "codes differing",
        "scans differing",
        "runs with any difference",
        "first differences (f64 -> other: runs)",
    ]);
    let mut design = Table::new([
        "scenario",
        "G (P_G)",
        "Λ",
        "α_K",
        "M2 n_max",
        "Q (m²/s⁴)",
        "initiation margin (m)",
        "M of N",
        "P(confirm true)",
        "false starts / scan",
        "q (clutter in first gate)",
        "false confirmations / scan",
        "delete after (confirmed, tentative)",
        "spurious deletions / scan",
        "table",
    ]);
    let mut summary_lines = Vec::new();
    let mut timing = Vec::new();
    for plan in PLANS {
        let info = scenario::info(plan.scenario).ok_or("unknown scenario")?;
        let d = design_for(&info)
            .ok_or("no design")?
            .derive()
            .map_err(|e| format!("{}: {e}", plan.scenario))?;
        design_rows(&mut design, plan.label, &d, plan);
        let runs = ctx.runs(plan.runs);
        let t0 = Instant::now();
        let (results, first) = monte_carlo(plan, &info, runs)?;
        timing.push((plan.label, runs, t0.elapsed().as_secs_f64()));
        for t in 0..3 {
            metrics.push(aggregate(plan, &results, t).row);
        }
        for (i, ty) in ["f32", "q32"].iter().enumerate() {
            let total = |f: fn(&DecisionDiff) -> usize| -> usize {
                results.iter().map(|r| f(&r.diffs[i])).sum()
            };
            let mut kinds: BTreeMap<String, usize> = BTreeMap::new();
            for r in &results {
                if let Some(k) = &r.first_diff[i] {
                    *kinds.entry(k.clone()).or_default() += 1;
                }
            }
            let kinds = if kinds.is_empty() {
                "–".to_string()
            } else {
                kinds
                    .iter()
                    .map(|(k, n)| format!("{k}: {n}"))
                    .collect::<Vec<_>>()
                    .join("; ")
            };
            decisions.push([
                plan.label.to_string(),
                ty.to_string(),
                results.len().to_string(),
                total(|d| d.codes).to_string(),
                total(|d| d.differing_codes).to_string(),
                total(|d| d.differing_scans).to_string(),
                results
                    .iter()
                    .filter(|r| r.diffs[i].any())
                    .count()
                    .to_string(),
                kinds,
            ]);
        }
        plots(&dir, plan, &info, &results, &first)?;
        summary_lines.push(scenario_summary(plan, &results));
    }
    metrics.write(&dir, "metrics")?;
    decisions.write(&dir, "decisions")?;
    design.write(&dir, "design")?;
    let bytes = bytes_table();
    bytes.write(&dir, "bytes_per_track")?;

    let mut s = String::new();
    let _ = writeln!(s, "# multi-target\n");
    let _ = writeln!(
        s,
        "Regenerate: `cd host-tests && cargo run --release --bin experiments -- --only {NAME}`.\n"
    );
    let _ = writeln!(
        s,
        "Default tracker (`abtrack::track::defaults`, derived from each scenario's sensor \
         figures; nothing tuned to these results): Cartesian scenarios \
         `AutoFilter<S, 2>` (`auto` fused) with the uncertainty gate; `tcas-30` \
         `RangeAzimuthTrack<S>` on the polar measurements with the range/azimuth window gate. \
         Base seed {BASE_SEED:#x}; OSPA order p = {OSPA_ORDER}, cut-off c per scenario below \
         (also the track-to-truth gate of the track metrics). Intervals are 95 % (Student t \
         for means, Wilson for proportions). Identity switches follow the CLEAR-MOT continuity \
         rule (`tracking::identity_switches`); the per-scan-assignment id changes of \
         `metrics::track_metrics` are listed too. Discussion: docs/experiments.md, \"Many targets\".\n"
    );
    for l in &summary_lines {
        let _ = writeln!(s, "{l}");
    }
    let _ = writeln!(
        s,
        "\n## Derived design per scenario\n\n{}",
        design.to_markdown()
    );
    let _ = writeln!(s, "## Metrics\n\n{}", metrics.to_markdown());
    let _ = writeln!(
        s,
        "## Association decisions of f32 and Q32.32 against f64\n\n{}",
        decisions.to_markdown()
    );
    let _ = writeln!(s, "## Bytes per track slot\n\n{}", bytes.to_markdown());
    let _ = writeln!(s, "## Runtime (this host, 2 threads)\n");
    for (name, runs, secs) in &timing {
        let _ = writeln!(s, "- {name}: {runs} runs × 3 number types in {secs:.1} s");
    }
    let _ = writeln!(s, "- whole group: {:.1} s", started.elapsed().as_secs_f64());
    write_file(&dir.join("summary.md"), &s)
}

fn scenario_summary(plan: &Plan, results: &[RunResult]) -> String {
    let n = results.len();
    fn f(r: &RunResult) -> &RunFigures {
        &r.figures[0]
    }
    let ospa = mean_ci95(&results.iter().map(|r| f(r).ospa).collect::<Vec<_>>());
    let kept = results.iter().filter(|r| f(r).ids_kept).count();
    let none_never_paired = results.iter().filter(|r| f(r).never_paired == 0).count();
    format!(
        "- **{}** (c = {} m, {} runs, f64): OSPA {} m; no identity switch in {} of the runs; \
         no track never paired with a target in {}.",
        plan.label,
        plan.ospa_cutoff,
        n,
        fmt_ci(&ospa, 1),
        proportion(kept, n),
        proportion(none_never_paired, n)
    )
}

fn plots(
    dir: &std::path::Path,
    plan: &Plan,
    info: &ScenarioInfo,
    results: &[RunResult],
    first: &TrackerRun,
) -> Result<(), String> {
    // Tracks over truth, run 0.
    let many = info.targets > 4;
    let mut series = Vec::new();
    if many {
        let truth: Vec<(f64, f64)> = first
            .scans
            .iter()
            .flat_map(|s| s.truth.iter().map(|p| (p.x, p.y)))
            .collect();
        series.push(Series::points("truth (all targets)", truth));
        let tracks: Vec<(f64, f64)> = first
            .scans
            .iter()
            .flat_map(|s| {
                s.tracks
                    .iter()
                    .filter(|t| t.status.is_established())
                    .map(|t| (t.x, t.y))
            })
            .collect();
        series.push(Series::points("established tracks", tracks));
    } else {
        let mut by_target: BTreeMap<u32, Vec<(f64, f64)>> = BTreeMap::new();
        for s in &first.scans {
            for p in &s.truth {
                by_target.entry(p.id).or_default().push((p.x, p.y));
            }
        }
        for (id, pts) in by_target {
            series.push(Series::line(format!("truth {id}"), pts));
        }
        let mut by_track: BTreeMap<u32, Vec<(f64, f64)>> = BTreeMap::new();
        for s in &first.scans {
            for t in s.tracks.iter().filter(|t| t.status.is_established()) {
                by_track.entry(t.id).or_default().push((t.x, t.y));
            }
        }
        for (id, pts) in by_track {
            series.push(Series::points(format!("track {id}"), pts));
        }
    }
    let title = format!("{}: established tracks over truth (run 0, f64)", plan.label);
    plot(
        &dir.join(format!("tracks_{}.svg", plan.slug())),
        &PlotSpec {
            title: &title,
            x_label: "x (m)",
            y_label: "y (m)",
            equal_aspect: true,
            y_max: None,
        },
        &series,
    )?;

    // Mean OSPA against time.
    let scans = results.first().map_or(0, |r| r.ospa_series.len());
    let mean_at = |k: usize, part: fn(&(f64, f64, f64, f64)) -> f64| -> (f64, f64) {
        let t = results[0].ospa_series[k].0;
        let v = results
            .iter()
            .filter_map(|r| r.ospa_series.get(k).map(part))
            .sum::<f64>()
            / results.len() as f64;
        (t, v)
    };
    let series = vec![
        Series::line("OSPA", (0..scans).map(|k| mean_at(k, |o| o.1)).collect()),
        Series::line(
            "localisation part",
            (0..scans).map(|k| mean_at(k, |o| o.2)).collect(),
        ),
        Series::line(
            "cardinality part",
            (0..scans).map(|k| mean_at(k, |o| o.3)).collect(),
        ),
    ];
    let title = format!(
        "{}: mean OSPA over {} runs (c = {} m, p = 2, f64)",
        plan.label,
        results.len(),
        plan.ospa_cutoff
    );
    plot(
        &dir.join(format!("ospa_{}.svg", plan.slug())),
        &PlotSpec {
            title: &title,
            x_label: "t (s)",
            y_label: "OSPA (m)",
            equal_aspect: false,
            y_max: None,
        },
        &series,
    )
}
