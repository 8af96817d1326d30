//! Group `tcas-random`: the randomized encounter suite
//! ([`crate::random_encounters`]) exact and under a TCAS receiver's noise,
//! in f64, f32 and `Fixed32` (the Cortex-M3's type, whose TCAS logic runs
//! in its wide format, `Numeric::Wide`), against the f64 reference
//! of the rules on the true states. Writes `results/tcas-random/`: the
//! table by level (`by_level.md`/`.csv`), false vs missed RAs by level
//! (`false_vs_missed.svg`), the distribution of RA onset delays
//! (`onset_delay.svg`), the encounters with false RAs (`false_ras.md`),
//! late RAs (`late_ras.md`; scan by scan, for the encounters late in
//! every seed, `late_ra_traces.md`) and the other sense at onset
//! (`wrong_senses.md`) at σB 5° and 25 ft,
//! the HMD filter's trade-off (`trade_off.md`, `trade_off.svg`) and
//! `summary.md`.

use std::fmt::Write as _;

use rayon::prelude::*;

use abtrack::tcas::detection::MISS_DISTANCE_CONFIDENCE;
use abtrack::{Fixed32, Numeric, Scalar};

use super::common::{plot, write_file, Context, PlotSpec, Series, Table};
use crate::encounters::ScanOutcome;
use crate::random_encounters::{
    ra_onset, reference, run_one, suite, trace_one, Condition, RandomEncounter, RunResult, Tally,
    CONDITIONS, LEVELS, PER_LEVEL,
};

/// The group's name (`--only tcas-random`, `results/tcas-random/`).
pub const NAME: &str = "tcas-random";
/// One line for `experiments --list`.
pub const ABOUT: &str =
    "TCAS: randomized encounters (SL 3-7) exact and noisy vs the v7.1 reference, f64/f32/Fixed32";
/// Documented noisy runs (seeds) per encounter and condition.
pub const RUNS: usize = 5;

/// The number types, in table order.
pub const TYPES: [&str; 3] = ["f64", "f32", "Fixed32"];

/// Every run of one encounter under one condition in one type.
fn runs_in<S: Scalar>(
    e: &RandomEncounter,
    condition: &Condition,
    seeds: usize,
    reference: &[ScanOutcome],
) -> Vec<RunResult> {
    let n = if condition.noisy { seeds } else { 1 };
    (0..n)
        .map(|run| run_one::<S>(e, condition, run, reference, None))
        .collect()
}

/// The results of the suite: `[condition][type][encounter]` → runs.
pub type SuiteResults = Vec<Vec<Vec<Vec<RunResult>>>>;

/// Runs the whole suite with `seeds` noisy runs per encounter.
pub fn simulate(seeds: usize) -> (Vec<RandomEncounter>, SuiteResults) {
    let encounters = suite();
    let results = simulate_encounters(&encounters, seeds, reference);
    (encounters, results)
}

/// Runs `encounters` under every condition in every type, with `seeds`
/// noisy runs each, each compared with the timeline `against` gives for
/// its encounter (the reference's, [`reference`]).
pub fn simulate_encounters(
    encounters: &[RandomEncounter],
    seeds: usize,
    against: impl Fn(&RandomEncounter) -> Vec<ScanOutcome> + Sync,
) -> SuiteResults {
    let per_encounter: Vec<Vec<Vec<Vec<RunResult>>>> = encounters
        .par_iter()
        .map(|e| {
            let reference = against(e);
            CONDITIONS
                .iter()
                .map(|c| {
                    vec![
                        runs_in::<f64>(e, c, seeds, &reference),
                        runs_in::<f32>(e, c, seeds, &reference),
                        runs_in::<<Fixed32 as Numeric>::Wide>(e, c, seeds, &reference),
                    ]
                })
                .collect()
        })
        .collect();
    // Transpose to [condition][type][encounter].
    (0..CONDITIONS.len())
        .map(|c| {
            (0..TYPES.len())
                .map(|t| per_encounter.iter().map(|e| e[c][t].clone()).collect())
                .collect()
        })
        .collect()
}

/// The tally of `runs` over the encounters whose level is `level` (`None`:
/// all).
pub fn tally(encounters: &[RandomEncounter], runs: &[Vec<RunResult>], level: Option<u8>) -> Tally {
    let mut t = Tally::default();
    for (e, rs) in encounters.iter().zip(runs) {
        if level.is_none_or(|l| l == e.level) {
            rs.iter().for_each(|r| t.add(e, r));
        }
    }
    t
}

fn pct(n: usize, d: usize) -> String {
    if d == 0 {
        "–".into()
    } else {
        format!("{:.1} %", 100.0 * n as f64 / d as f64)
    }
}

fn seconds(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{v:+.0}"))
}

/// The rows of a [`by_level_table`] over all levels.
pub fn all_levels(by_level: &Table) -> Table {
    let mut out = Table::new(by_level.headers.clone());
    by_level
        .rows
        .iter()
        .filter(|r| r[2] == "all")
        .for_each(|r| out.push(r.clone()));
    out
}

/// The table by condition, type and level.
pub fn by_level_table(encounters: &[RandomEncounter], results: &SuiteResults) -> Table {
    let mut table = Table::new([
        "condition",
        "type",
        "level",
        "runs",
        "refused",
        "reference RAs",
        "TA agree",
        "RA agree",
        "false RA",
        "missed RA",
        "onset delay median (s)",
        "onset delay p95 (s)",
        "wrong sense",
        "wrong sense: largest VMD magnitude (ft)",
        "RA in pieces",
        "RA reversed",
    ]);
    for (c, condition) in CONDITIONS.iter().enumerate() {
        for (t, type_name) in TYPES.iter().enumerate() {
            let levels = LEVELS.iter().map(|l| Some(l.0)).chain([None]);
            for level in levels {
                let s = tally(encounters, &results[c][t], level);
                let a = s.accepted();
                table.push([
                    condition.name.to_string(),
                    type_name.to_string(),
                    level.map_or("all".into(), |l| format!("SL{l}")),
                    s.runs.to_string(),
                    s.refused.to_string(),
                    s.reference_ra.to_string(),
                    pct(s.ta_agree, a),
                    pct(s.ra_agree, a),
                    pct(s.false_ra, a),
                    pct(s.missed_ra, a),
                    seconds(s.delay_quantile(0.5)),
                    seconds(s.delay_quantile(0.95)),
                    s.wrong_sense.to_string(),
                    s.wrong_sense_largest_vmd_ft
                        .map_or("–".into(), |v| format!("{v:.0}")),
                    s.in_pieces.to_string(),
                    s.reversed.to_string(),
                ]);
            }
        }
    }
    table
}

pub fn run(ctx: &Context) -> Result<(), String> {
    let dir = ctx.group_dir(NAME)?;
    let seeds = ctx.runs(RUNS);
    let (encounters, results) = simulate(seeds);
    let table = by_level_table(&encounters, &results);
    table.write(&dir, "by_level")?;

    // False vs missed RAs by level, f64, one series per condition.
    let fraction = |n: usize, d: usize| 100.0 * n as f64 / d.max(1) as f64;
    let series: Vec<Series> = CONDITIONS
        .iter()
        .enumerate()
        .map(|(c, condition)| {
            let points = LEVELS
                .iter()
                .map(|l| {
                    let s = tally(&encounters, &results[c][0], Some(l.0));
                    (
                        fraction(s.false_ra, s.accepted()),
                        fraction(s.missed_ra, s.accepted()),
                    )
                })
                .collect();
            Series::points(condition.name, points)
        })
        .collect();
    plot(
        &dir.join("false_vs_missed.svg"),
        &PlotSpec {
            title: "False vs missed RAs by level (SL 3-7), f64",
            x_label: "false RAs (% of runs)",
            y_label: "missed RAs (% of runs)",
            equal_aspect: false,
            y_max: None,
        },
        &series,
    )?;
    // RA onset delay: its distribution (sorted delays against the fraction
    // of runs), f64, per condition.
    let series: Vec<Series> = CONDITIONS
        .iter()
        .enumerate()
        .filter_map(|(c, condition)| {
            let mut d = tally(&encounters, &results[c][0], None).onset_delays_s;
            if d.is_empty() {
                return None;
            }
            d.sort_by(f64::total_cmp);
            let n = d.len() as f64;
            let points = d
                .iter()
                .enumerate()
                .map(|(k, &v)| (v, (k + 1) as f64 / n))
                .collect();
            Some(Series::line(condition.name, points))
        })
        .collect();
    plot(
        &dir.join("onset_delay.svg"),
        &PlotSpec {
            title: "RA onset delay against the reference (f64)",
            x_label: "onset delay (s)",
            y_label: "fraction of runs with both RAs",
            equal_aspect: false,
            y_max: None,
        },
        &series,
    )?;

    false_ra_table(&encounters, &results[1][0]).write(&dir, "false_ras")?;
    late_ra_table(&encounters, &results[1][0]).write(&dir, "late_ras")?;
    late_ra_trace_table(&encounters, &CONDITIONS[1], &results[1][0])?
        .write(&dir, "late_ra_traces")?;
    wrong_sense_table(&encounters, &results[0][0], &results[1][0]).write(&dir, "wrong_senses")?;
    let trade_off = trade_off_table(&encounters, seeds);
    trade_off.write(&dir, "trade_off")?;
    let point = |row: &Vec<String>, col: usize| row[col].trim_end_matches(" %").parse::<f64>();
    let mut series = Vec::new();
    let mut design = Vec::new();
    for condition in CONDITIONS.iter().filter(|c| c.noisy) {
        let rows: Vec<&Vec<String>> = trade_off
            .rows
            .iter()
            .filter(|r| r[0] == condition.name)
            .collect();
        let delay: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| Some((point(r, 2).ok()?, point(r, 5).ok()?)))
            .collect();
        let missed: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| Some((point(r, 2).ok()?, point(r, 3).ok()?)))
            .collect();
        design.extend(
            rows.iter()
                .filter(|r| r[1] == format!("{MISS_DISTANCE_CONFIDENCE}"))
                .filter_map(|r| Some((point(r, 2).ok()?, point(r, 5).ok()?))),
        );
        series.push(Series::line(
            format!("p95 onset delay (s), {}", condition.name),
            delay,
        ));
        series.push(Series::line(
            format!("missed RAs (%), {}", condition.name),
            missed,
        ));
    }
    series.push(Series::points(
        format!("the design, k = {MISS_DISTANCE_CONFIDENCE} (p95 delay)"),
        design,
    ));
    plot(
        &dir.join("trade_off.svg"),
        &PlotSpec {
            title: "HMD filter confidence k (f64): false RAs vs p95 onset delay and missed RAs",
            x_label: "false RAs (% of runs)",
            y_label: "p95 onset delay (s) / missed RAs (%)",
            equal_aspect: false,
            y_max: None,
        },
        &series,
    )?;

    let mut s = String::new();
    let _ = writeln!(s, "# Randomized TCAS encounters\n");
    let _ = writeln!(
        s,
        "Generated by `cd host-tests && cargo run --release --bin experiments -- --only {NAME}`.\n"
    );
    let _ = writeln!(
        s,
        "{} encounters ({PER_LEVEL} at each of SL 3-7; `host-tests/src/random_encounters.rs`), \
         exact and with {seeds} noise seeds per encounter and condition (range σ 15 m), through \
         the library in f64, f32 and `Fixed32` (its TCAS logic in its wide format), against the f64 reference of the rules \
         on the true states. Definitions in the module docs. Table by level: `by_level.md`; \
         plots: `false_vs_missed.svg`, `onset_delay.svg`; the HMD filter's confidence factor \
         k swept in `trade_off.md` and `trade_off.svg`; at σB 5° and 25 ft, the encounters \
         with false RAs in `false_ras.md`, those with an RA onset more than {LATE_ONSET_S} s \
         late in `late_ras.md` (scan by scan, for those late in every seed, in \
         `late_ra_traces.md`), and those with the other sense at onset, beside their \
         vertical miss against the 25 ft quantum, in `wrong_senses.md`.\n",
        encounters.len()
    );
    let _ = writeln!(s, "## All levels\n\n{}", all_levels(&table).to_markdown());
    let _ = writeln!(
        s,
        "## HMD filter confidence k (f64; the library's k = {MISS_DISTANCE_CONFIDENCE})\n\n{}",
        trade_off.to_markdown()
    );
    write_file(&dir.join("summary.md"), &s)
}

/// The new-threat confidence factors k the trade-off sweeps (an RA needs
/// the combined miss distance's bound m + kσ under the HMD threshold;
/// `abtrack::tcas::detection::MISS_DISTANCE_CONFIDENCE`): k > 0 asks for
/// confidence that the miss is small, k < 0 filters only when confident
/// that it is large.
pub const CONFIDENCES: [f64; 12] = [
    -1.0, -0.5, -0.25, 0.0, 0.25, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0,
];

/// An RA onset later than this after the reference's is late, s: the
/// randomized suite's p95 target with 25 ft reports.
pub const LATE_ONSET_S: f64 = 5.0;

/// False and missed RAs, the onset delay, RAs in pieces and wrong senses as
/// the HMD filter's confidence factor varies, for each noisy condition
/// (f64).
pub fn trade_off_table(encounters: &[RandomEncounter], seeds: usize) -> Table {
    let mut table = Table::new([
        "condition",
        "k (σ)",
        "false RA",
        "missed RA",
        "onset delay median (s)",
        "onset delay p95 (s)",
        "RA in pieces",
        "wrong sense",
    ]);
    let references: Vec<_> = encounters.par_iter().map(reference).collect();
    for condition in CONDITIONS.iter().filter(|c| c.noisy) {
        for k in CONFIDENCES {
            let runs: Vec<Vec<RunResult>> = encounters
                .par_iter()
                .zip(&references)
                .map(|(e, r)| {
                    (0..seeds)
                        .map(|run| run_one::<f64>(e, condition, run, r, Some(k)))
                        .collect()
                })
                .collect();
            let t = tally(encounters, &runs, None);
            let a = t.accepted();
            table.push([
                condition.name.to_string(),
                format!("{k}"),
                pct(t.false_ra, a),
                pct(t.missed_ra, a),
                seconds(t.delay_quantile(0.5)),
                seconds(t.delay_quantile(0.95)),
                t.in_pieces.to_string(),
                t.wrong_sense.to_string(),
            ]);
        }
    }
    table
}

/// The encounters with false RAs under `runs` (one condition and type):
/// how many of their runs, and the encounter's figures against the
/// level's HMD threshold.
pub fn false_ra_table(encounters: &[RandomEncounter], runs: &[Vec<RunResult>]) -> Table {
    let mut table = Table::new([
        "encounter",
        "level",
        "false RA runs",
        "HMD (m)",
        "HMD / threshold",
        "VMD (ft)",
        "closure (kt)",
        "intruder rate (ft/min)",
    ]);
    for (e, rs) in encounters.iter().zip(runs) {
        let n = rs.iter().filter(|r| r.ra && !r.reference_ra).count();
        if n == 0 {
            continue;
        }
        table.push([
            e.index.to_string(),
            format!("SL{}", e.level),
            n.to_string(),
            format!("{:.0}", e.hmd_m),
            format!("{:.2}", e.hmd_m / hmd_threshold_m(e)),
            format!("{:+.0}", e.vmd_ft),
            format!("{:.0}", e.closure_kt),
            format!("{:+.0}", e.intruder_rate_ft_per_min),
        ]);
    }
    table
}

/// The HMD threshold of the encounter's level, m (NaN at a level without
/// RAs).
fn hmd_threshold_m(e: &RandomEncounter) -> f64 {
    crate::reference_tcas::level_for(e.encounter.own_altitude_ft)
        .ra
        .map_or(f64::NAN, |ra| ra.hmd_m)
}

/// Whether a run's RA onset is more than [`LATE_ONSET_S`] after the
/// reference's.
fn is_late(r: &RunResult) -> bool {
    r.onset_delay_s.is_some_and(|d| d > LATE_ONSET_S)
}

/// The encounters with an RA onset more than [`LATE_ONSET_S`] after the
/// reference's under `runs` (one condition and type): how many of their
/// runs, the delays, and the encounter's figures against the level's HMD
/// threshold.
pub fn late_ra_table(encounters: &[RandomEncounter], runs: &[Vec<RunResult>]) -> Table {
    let mut table = Table::new([
        "encounter",
        "level",
        "late runs",
        "onset delays (s)",
        "HMD (m)",
        "HMD / threshold",
        "VMD (ft)",
        "closure (kt)",
    ]);
    for (e, rs) in encounters.iter().zip(runs) {
        let late = rs.iter().filter(|r| is_late(r)).count();
        if late == 0 {
            continue;
        }
        let delays: Vec<String> = rs.iter().map(|r| seconds(r.onset_delay_s)).collect();
        table.push([
            e.index.to_string(),
            format!("SL{}", e.level),
            format!("{late} of {}", rs.len()),
            delays.join(" "),
            format!("{:.0}", e.hmd_m),
            format!("{:.2}", e.hmd_m / hmd_threshold_m(e)),
            format!("{:+.0}", e.vmd_ft),
            format!("{:.0}", e.closure_kt),
        ]);
    }
    table
}

/// Scan by scan, the first seed of every encounter whose RA onset is more
/// than [`LATE_ONSET_S`] late in every run of `runs` (the f64 runs under
/// `condition`), from 2 s before the reference's onset to the run's: the
/// range tracker's ṙ and r̈ (r̈ beside the truth's), the bearing track's
/// miss distance, and the miss distance the HMD filter compared with the
/// level's threshold.
pub fn late_ra_trace_table(
    encounters: &[RandomEncounter],
    condition: &Condition,
    runs: &[Vec<RunResult>],
) -> Result<Table, String> {
    let mut table = Table::new([
        "encounter",
        "t (s)",
        "true range (m)",
        "ṙ (m/s)",
        "r̈ (m/s²)",
        "true r̈ (m/s²)",
        "bearing HMD (m)",
        "bearing HMD σ (m)",
        "filter HMD (m)",
        "HMD threshold (m)",
        "RA removed by the filter",
        "alert",
    ]);
    let cell = |v: Option<f64>, digits: usize| v.map_or("–".into(), |v| format!("{v:.digits$}"));
    for (e, rs) in encounters.iter().zip(runs) {
        if rs.is_empty() || !rs.iter().all(is_late) {
            continue;
        }
        let (outcomes, trace) = trace_one::<f64>(e, condition, 0)?;
        let (Some((expected, _)), Some((got, _))) = (ra_onset(&reference(e)), ra_onset(&outcomes))
        else {
            continue;
        };
        for (k, (t, o)) in trace
            .iter()
            .zip(&outcomes)
            .enumerate()
            .take(got + 1)
            .skip(expected.saturating_sub(2))
        {
            table.push([
                e.index.to_string(),
                k.to_string(),
                format!("{:.0}", t.true_range_m),
                cell(t.range_rate_m_per_s, 1),
                cell(t.range_acceleration_m_per_s2, 3),
                format!("{:.3}", t.true_range_acceleration_m_per_s2),
                cell(t.bearing_miss_distance_m, 0),
                cell(t.bearing_miss_distance_sigma_m, 0),
                cell(t.filter_miss_distance_m, 0),
                format!("{:.0}", hmd_threshold_m(e)),
                if t.miss_distance_filtered { "yes" } else { "" }.into(),
                format!("{:?}", o.alert),
            ]);
        }
    }
    Ok(table)
}

/// The encounters whose RA takes the other sense at onset under `noisy`
/// (one condition and type), beside the same encounter on exact inputs
/// (`exact`): how many runs, and the encounter's vertical miss against the
/// 25 ft altitude quantum.
pub fn wrong_sense_table(
    encounters: &[RandomEncounter],
    exact: &[Vec<RunResult>],
    noisy: &[Vec<RunResult>],
) -> Table {
    let mut table = Table::new([
        "encounter",
        "level",
        "wrong-sense runs",
        "wrong sense on exact inputs",
        "VMD (ft)",
        "VMD in 25 ft quanta",
        "intruder rate (ft/min)",
        "onset delays (s)",
    ]);
    for ((e, rs), exact_runs) in encounters.iter().zip(noisy).zip(exact) {
        let wrong: Vec<&RunResult> = rs.iter().filter(|r| r.wrong_sense).collect();
        if wrong.is_empty() {
            continue;
        }
        let delays: Vec<String> = wrong.iter().map(|r| seconds(r.onset_delay_s)).collect();
        table.push([
            e.index.to_string(),
            format!("SL{}", e.level),
            format!("{} of {}", wrong.len(), rs.len()),
            if exact_runs.iter().any(|r| r.wrong_sense) {
                "yes"
            } else {
                "no"
            }
            .to_string(),
            format!("{:+.0}", e.vmd_ft),
            format!("{:+.2}", e.vmd_ft / 25.0),
            format!("{:+.0}", e.intruder_rate_ft_per_min),
            delays.join(" "),
        ]);
    }
    table
}
