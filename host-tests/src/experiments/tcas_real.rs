//! Group `tcas-real`: the TCAS encounter suite around recorded intruders
//! ([`crate::recorded_encounters`]: real ADS-B paths that turn, climb and
//! level off) exact and under a TCAS receiver's noise, in f64, f32 and
//! `Fixed32`, against the f64 reference of the rules on the true states;
//! the runs, conditions and tables are the randomized suite's
//! ([`super::tcas_random`]). Writes `results/tcas-real/`: the table by
//! level (`by_level.md`/`.csv`), the encounters by recorded path
//! (`encounters.md`), the encounters with false RAs, late RAs and the other
//! sense at onset at σB 5° and 25 ft (`false_ras.md`, `late_ras.md`,
//! `wrong_senses.md`), the same runs against the library's own run on
//! exact inputs (`by_level_against_exact_inputs.md`: the receiver's noise
//! alone) and `summary.md`.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::common::{write_file, Context, Table};
use rayon::prelude::*;

use super::tcas_random::{
    all_levels, by_level_table, late_ra_table, simulate_encounters, wrong_sense_table, RUNS,
};
use crate::encounters::ScanOutcome;
use crate::random_encounters::{
    exact_library_timeline, ra_onset, reference, trace_one, RandomEncounter, RunResult, CONDITIONS,
};
use crate::recorded_encounters::{suite, CPA_SPACING_S, MAX_GAP_S, MIN_CLOSURE_KT, OWN_SPEED_KT};
use crate::reference_tcas::level_for;

/// The group's name (`--only tcas-real`, `results/tcas-real/`).
pub const NAME: &str = "tcas-real";
/// The window before an RA onset over which the intruder's largest
/// acceleration is given, s.
pub const ACCELERATION_WINDOW_S: f64 = 10.0;
/// One line for `experiments --list`.
pub const ABOUT: &str =
    "TCAS: encounters around recorded ADS-B intruders, exact and noisy vs the v7.1 reference, f64/f32/Fixed32";

/// How many encounters each recorded path gave, by level.
fn encounters_table(encounters: &[RandomEncounter]) -> Table {
    let mut by_path: BTreeMap<&str, BTreeMap<u8, usize>> = BTreeMap::new();
    for e in encounters {
        if let Some(r) = e.encounter.recorded() {
            *by_path
                .entry(r.path.name.as_str())
                .or_default()
                .entry(e.level)
                .or_default() += 1;
        }
    }
    let mut table = Table::new(["recorded path", "SL3", "SL4", "SL5", "SL6", "SL7", "all"]);
    for (path, levels) in &by_path {
        let count = |l: u8| levels.get(&l).copied().unwrap_or(0);
        table.push([
            path.to_string(),
            count(3).to_string(),
            count(4).to_string(),
            count(5).to_string(),
            count(6).to_string(),
            count(7).to_string(),
            levels.values().sum::<usize>().to_string(),
        ]);
    }
    table
}

/// The least range of the run's true relative path (every 0.1 s), m.
fn closest_approach_m(e: &RandomEncounter) -> f64 {
    (0..e.encounter.scans * 10)
        .map(|i| {
            let s = e.encounter.relative(i as f64 / 10.0).s;
            s[0].hypot(s[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// The encounters with a false RA on exact inputs (`exact`, f64) or under
/// `noisy` (one condition, f64): the recorded path, the false RAs of each,
/// the drawn HMD and the path's actual closest approach against the
/// level's HMD threshold, and at the exact-input run's RA onset whether
/// the HMD filter had no miss distance (off for the cycles after a
/// detected manoeuvre, DO-185B `detect_maneuvers`, or no straight path
/// fits the range track) and the intruder's largest acceleration over the
/// [`ACCELERATION_WINDOW_S`] before.
fn false_ra_table(
    encounters: &[RandomEncounter],
    exact: &[Vec<RunResult>],
    noisy: &[Vec<RunResult>],
) -> Table {
    let mut table = Table::new([
        "encounter".to_string(),
        "level".into(),
        "recorded path".into(),
        "designed closest approach, recording time (s)".into(),
        "false RA on exact inputs".into(),
        format!("false RA runs, {}", CONDITIONS[1].name),
        "HMD / threshold".into(),
        "closest approach / threshold".into(),
        "no miss distance at the exact onset".into(),
        format!("intruder's largest acceleration, {ACCELERATION_WINDOW_S} s before the exact onset (m/s²)"),
    ]);
    let false_ras = |rs: &[RunResult]| rs.iter().filter(|r| r.ra && !r.reference_ra).count();
    for ((e, x), rs) in encounters.iter().zip(exact).zip(noisy) {
        let (on_exact, n) = (false_ras(x), false_ras(rs));
        let Some(recorded) = e.encounter.recorded().filter(|_| on_exact + n > 0) else {
            continue;
        };
        let threshold = level_for(e.encounter.own_altitude_ft)
            .ra
            .map_or(f64::NAN, |ra| ra.hmd_m);
        let onset = (on_exact > 0)
            .then(|| trace_one::<f64>(e, &CONDITIONS[0], 0).ok())
            .flatten()
            .and_then(|(outcomes, traces)| ra_onset(&outcomes).map(|(k, _)| (k, traces[k])));
        table.push([
            e.index.to_string(),
            format!("SL{}", e.level),
            recorded.path.name.clone(),
            format!("{:.0}", recorded.t_cpa),
            if on_exact > 0 { "yes" } else { "no" }.to_string(),
            format!("{n} of {}", rs.len()),
            format!("{:.2}", e.hmd_m / threshold),
            format!("{:.2}", closest_approach_m(e) / threshold),
            onset.map_or("–".into(), |(_, trace)| {
                if trace.filter_miss_distance_m.is_none() {
                    "yes".into()
                } else {
                    "no".into()
                }
            }),
            onset.map_or("–".into(), |(k, _)| {
                format!(
                    "{:.1}",
                    recorded.largest_acceleration_before(k, ACCELERATION_WINDOW_S)
                )
            }),
        ]);
    }
    table
}

pub fn run(ctx: &Context) -> Result<(), String> {
    let dir = ctx.group_dir(NAME)?;
    let seeds = ctx.runs(RUNS);
    let encounters = suite()?;
    let results = simulate_encounters(&encounters, seeds, reference);
    let table = by_level_table(&encounters, &results);
    table.write(&dir, "by_level")?;
    let baselines: Vec<Vec<ScanOutcome>> = encounters
        .par_iter()
        .map(|e| {
            exact_library_timeline(e)
                .ok_or_else(|| format!("encounter {}: the library refused exact inputs", e.index))
        })
        .collect::<Result<_, _>>()?;
    let against_exact = simulate_encounters(&encounters, seeds, |e| baselines[e.index].clone());
    let exact_table = by_level_table(&encounters, &against_exact);
    exact_table.write(&dir, "by_level_against_exact_inputs")?;
    encounters_table(&encounters).write(&dir, "encounters")?;
    false_ra_table(&encounters, &results[0][0], &results[1][0]).write(&dir, "false_ras")?;
    late_ra_table(&encounters, &results[1][0]).write(&dir, "late_ras")?;
    wrong_sense_table(&encounters, &results[0][0], &results[1][0]).write(&dir, "wrong_senses")?;

    let mut s = String::new();
    let _ = writeln!(s, "# TCAS encounters around recorded intruders\n");
    let _ = writeln!(
        s,
        "Generated by `cd host-tests && cargo run --release --bin experiments -- --only {NAME}`.\n"
    );
    let _ = writeln!(
        s,
        "{} encounters (`host-tests/src/recorded_encounters.rs`): the intruder flies a real \
         ADS-B path of `host-tests/data/real/` (the Paris scene's flights and the single \
         segments), its truth between samples the natural cubic spline and its altitude the \
         least-squares line through the reported altitudes; the own aircraft is level and \
         straight at {}-{} kt, passing the intruder's position at a closest approach taken \
         every {CPA_SPACING_S} s along the path with a horizontal miss of 0-1.5 NM and a \
         vertical miss of ±1200 ft (kept when the recording covers the run with no interval \
         over {MAX_GAP_S} s, the closure is at least {MIN_CLOSURE_KT} kt and the own altitude \
         is in SL 3-7's band). The conditions, runs ({seeds} noise seeds per encounter and \
         condition, range σ 15 m), types and definitions are the randomized suite's \
         (`results/tcas-random/`). Encounters by path and level: `encounters.md`.\n",
        encounters.len(),
        OWN_SPEED_KT.0,
        OWN_SPEED_KT.1,
    );
    let _ = writeln!(
        s,
        "## Against the reference on the true states, all levels\n\n\
         The f64 reference of the rules on the true states, as for the randomized suite \
         (its HMD filter on the straight path of the current true velocity). Table by level: \
         `by_level.md`; the encounters with false RAs on exact inputs or at {} (f64), with \
         the library's state at its RA onset on exact inputs: `false_ras.md`; late RAs and \
         the other sense at onset: `late_ras.md`, `wrong_senses.md`.\n\n{}",
        CONDITIONS[1].name,
        all_levels(&table).to_markdown()
    );
    let _ = writeln!(
        s,
        "## Against the library on exact inputs, all levels\n\n\
         The same runs compared with the library's own f64 run on exact ranges and bearings \
         with 25 ft altitudes: what the receiver's noise (and, for the 100 ft condition, the \
         coarser altitude) changes, apart from what the surveillance does on exact inputs. \
         Table by level: `by_level_against_exact_inputs.md`.\n\n{}",
        all_levels(&exact_table).to_markdown()
    );
    write_file(&dir.join("summary.md"), &s)
}
