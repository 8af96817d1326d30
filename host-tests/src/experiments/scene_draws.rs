//! The real scene drawn again: its truth measured with new seeds, in the dev
//! folder's two conditions and in the condition of the project's held-out
//! scene (not in the repository: P_D 0.7, 100 clutter plots a scan), as the
//! folder's README says its files were made. One draw
//! (the folder's, seed 7) says little about a difference of a few metres or
//! a few thousandths of coverage; the draws give the spread, and the third
//! condition checks that the design configured from the sensor's figures
//! holds at a clutter density the dev files do not have. Four more
//! conditions measure the same truth with other sensors' figures (a 12 s
//! scan; σ 150 m; 8 s, σ 100 m, P_D 0.8 and 50 clutter plots a scan; a
//! 12 s scan with 100 clutter plots), each configured from its own
//! figures, as a recording from another sensor would be.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use super::common::{min_max, write_file, Table};
use super::real_adsb::{
    score_tracks, stonesoup_tracks, Scene, SceneRun, OSPA_CUTOFF_M, PAIR_LIMIT_M,
    SCENE_HALF_WIDTH_M, SCENE_NUMERICS, SCENE_PERIOD_MS, SIGMA_M, STONESOUP_DIR, STONESOUP_LABEL,
};
use crate::metrics::{common_rmse, id_changes_after_far_updates, TruthPoint};
use crate::noise::{
    bernoulli, derive_seed, poisson, rng_from_seed, shuffle, standard_normal, uniform,
};
use crate::replay::Numeric;
use crate::replay_tracker::replay_tracker_reader;

/// The draws' conditions, named as their files and rows: first the
/// [`DEV_SENSOR_CONDITION_COUNT`] with the dev files' sensor (σ 50 m, a
/// scan every 4 s): the dev files' two and the held-out scene's (P_D 0.7,
/// 100 clutter plots a scan); then other sensors' figures. Each
/// condition's random stream is derived from its index here, so a
/// condition added at the end changes no earlier draw.
pub const CONDITIONS: [Scene; 7] = [
    Scene {
        name: "pd0.9_clutter20",
        detection_probability: 0.9,
        clutter_per_km2: 0.002,
        sigma_m: SIGMA_M,
        scan_period_ms: SCENE_PERIOD_MS,
    },
    Scene {
        name: "pd0.7_clutter60",
        detection_probability: 0.7,
        clutter_per_km2: 0.006,
        sigma_m: SIGMA_M,
        scan_period_ms: SCENE_PERIOD_MS,
    },
    Scene {
        name: "pd0.7_clutter100",
        detection_probability: 0.7,
        clutter_per_km2: 0.01,
        sigma_m: SIGMA_M,
        scan_period_ms: SCENE_PERIOD_MS,
    },
    Scene {
        name: "pd0.9_clutter20_T12s",
        detection_probability: 0.9,
        clutter_per_km2: 0.002,
        sigma_m: SIGMA_M,
        scan_period_ms: 3 * SCENE_PERIOD_MS,
    },
    Scene {
        name: "pd0.9_clutter20_sigma150m",
        detection_probability: 0.9,
        clutter_per_km2: 0.002,
        sigma_m: 150.0,
        scan_period_ms: SCENE_PERIOD_MS,
    },
    Scene {
        name: "pd0.8_clutter50_T8s_sigma100m",
        detection_probability: 0.8,
        clutter_per_km2: 0.005,
        sigma_m: 100.0,
        scan_period_ms: 2 * SCENE_PERIOD_MS,
    },
    Scene {
        name: "pd0.9_clutter100_T12s",
        detection_probability: 0.9,
        clutter_per_km2: 0.01,
        sigma_m: SIGMA_M,
        scan_period_ms: 3 * SCENE_PERIOD_MS,
    },
];

/// How many of [`CONDITIONS`], from the first, have the dev files' sensor
/// (σ 50 m, 4 s).
pub const DEV_SENSOR_CONDITION_COUNT: usize = 3;

/// The draws' seeds (the folder's files are seed 7).
pub const DRAW_SEEDS: [u64; 3] = [1, 2, 3];

/// The scene's last scan, ms.
const LAST_SCAN_MS: i64 = 1_200_000;

/// The mean number of clutter plots a scan of `condition` over the whole
/// square.
pub fn clutter_per_scan(condition: &Scene) -> f64 {
    let side_km = 2.0 * SCENE_HALF_WIDTH_M / 1000.0;
    condition.clutter_per_km2 * side_km * side_km
}

/// The measurement file (`t,x,y`) of one draw: each scan (every scan
/// period to 1200 s) detects each truth point with P_D and perturbs it by
/// N(0, σ²) per axis, adds Poisson(clutter) plots uniform over the square,
/// and lists the scan's plots in a random order (the folder's files list the
/// detections in the truth's order, then the clutter: a tracker must not
/// depend on that).
pub fn draw(truth: &BTreeMap<i64, Vec<TruthPoint>>, condition: &Scene, stream: u64) -> String {
    let mut rng = rng_from_seed(stream);
    let mut out = String::from("t,x,y\n");
    let sigma = condition.sigma_m;
    for t_ms in scan_times_ms(condition) {
        let mut plots: Vec<[f64; 2]> = Vec::new();
        for p in truth.get(&t_ms).map(Vec::as_slice).unwrap_or_default() {
            if bernoulli(&mut rng, condition.detection_probability) {
                plots.push([
                    p.x + sigma * standard_normal(&mut rng),
                    p.y + sigma * standard_normal(&mut rng),
                ]);
            }
        }
        for _ in 0..poisson(&mut rng, clutter_per_scan(condition)) {
            plots.push([
                uniform(&mut rng, -SCENE_HALF_WIDTH_M, SCENE_HALF_WIDTH_M),
                uniform(&mut rng, -SCENE_HALF_WIDTH_M, SCENE_HALF_WIDTH_M),
            ]);
        }
        shuffle(&mut rng, &mut plots);
        for [x, y] in plots {
            let _ = writeln!(out, "{:.3},{x:.2},{y:.2}", t_ms as f64 / 1000.0);
        }
    }
    out
}

/// The times (ms) of `condition`'s scans: every scan period from 0 to
/// 1200 s.
pub fn scan_times_ms(condition: &Scene) -> impl Iterator<Item = i64> {
    let period_ms = condition.scan_period_ms.max(1);
    (0..=LAST_SCAN_MS / period_ms).map(move |scan| scan * period_ms)
}

/// The truth of `condition`'s scans ([`scan_times_ms`]), keyed by their
/// times (a scan without a flight keeps its key, with no points): what a
/// draw of `condition` is scored against.
pub fn truth_at_scans(
    truth: &BTreeMap<i64, Vec<TruthPoint>>,
    condition: &Scene,
) -> BTreeMap<i64, Vec<TruthPoint>> {
    scan_times_ms(condition)
        .map(|t| (t, truth.get(&t).cloned().unwrap_or_default()))
        .collect()
}

/// The measurement file of condition `CONDITIONS[index]` drawn with `seed`.
pub fn measurements(truth: &BTreeMap<i64, Vec<TruthPoint>>, index: usize, seed: u64) -> String {
    draw(
        truth,
        &CONDITIONS[index],
        derive_seed(seed, 0x5ce0_0000 + index as u64),
    )
}

/// `replay --tracker` in `numeric`, configured for `condition`, on the
/// measurement file `text`, scored against `truth` at the condition's scans
/// (the design it printed in [`SceneRun::design`]).
pub fn track(
    truth: &BTreeMap<i64, Vec<TruthPoint>>,
    condition: &Scene,
    text: &str,
    numeric: Numeric,
    label: &str,
) -> Result<SceneRun, String> {
    let replay = replay_tracker_reader(&condition.options(numeric, None), text.as_bytes())
        .map_err(|e| format!("{} {label}: {e}", condition.name))?;
    score_tracks(
        label,
        &format!("replay --tracker output on the {} draw", condition.name),
        &replay.csv,
        &truth_at_scans(truth, condition),
        f64::NAN,
        replay.design.to_string(),
    )
}

/// One tracker's scores on one draw.
struct DrawScore {
    condition: usize,
    seed: u64,
    tracker: String,
    run: SceneRun,
}

/// The cell of a figure that does not apply.
const NOT_APPLICABLE: &str = "—";

/// [`id_changes_after_far_updates`] (farther than [`PAIR_LIMIT_M`]) of an
/// abtrack run; `None` for Stone Soup's, whose rows are all `confirmed`
/// (no update status).
fn far_update_id_changes(tracker: &str, run: &SceneRun) -> Option<usize> {
    (tracker != STONESOUP_LABEL)
        .then(|| id_changes_after_far_updates(&run.scans, &run.pairs, PAIR_LIMIT_M))
}

/// "mean (least–most)" of `values`, with `digits` decimals.
fn mean_and_range(values: &[f64], digits: usize) -> String {
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let (lo, hi) = min_max(values.iter().copied());
    format!("{mean:.digits$} ({lo:.digits$}–{hi:.digits$})")
}

/// Where `scripts/stonesoup_scene.py --draws` writes its tracks, under the
/// group's [`STONESOUP_DIR`]. They are the tracks of the draws the code made when the
/// script ran: a change to [`draw`] or to its random streams needs the
/// script run again (`on_the_scene_drawn_again_the_tracker_is_at_least_as_good_as_stone_soup`
/// compares with them).
pub const DRAWS_DIR: &str = "draws";

/// Where the drawn measurement files and the tracker's design for each
/// are written (`host-tests/target/scene-draws/`): inputs of
/// `scripts/stonesoup_scene.py --draws`, too large to keep in `results/`.
pub fn scratch_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("target/scene-draws")
}

/// The file name of one draw (without extension).
pub fn draw_name(condition: &Scene, seed: u64) -> String {
    format!("{}_seed{seed}", condition.name)
}

/// Stone Soup's tracks on one draw, scored against `truth`, if
/// `scripts/stonesoup_scene.py --draws` has written them under the
/// group's folder `dir`.
pub fn stonesoup_draw(
    dir: &Path,
    condition: &Scene,
    seed: u64,
    truth: &BTreeMap<i64, Vec<TruthPoint>>,
) -> Result<Option<SceneRun>, String> {
    let Some((path, csv_text)) = stonesoup_tracks(
        &dir.join(STONESOUP_DIR).join(DRAWS_DIR),
        &draw_name(condition, seed),
    ) else {
        return Ok(None);
    };
    score_tracks(
        STONESOUP_LABEL,
        &path,
        &csv_text,
        &truth_at_scans(truth, condition),
        f64::NAN,
        String::new(),
    )
    .map(Some)
}

/// Runs the draws, writes `scene_draws.csv`/`.md` into `dir` and the drawn
/// measurement files with the tracker's design into `scratch` (for Stone
/// Soup), and appends the section to `summary`. Stone Soup's tracks are
/// scored where its folder has them.
pub fn run(
    dir: &Path,
    scratch: &Path,
    truth: &BTreeMap<i64, Vec<TruthPoint>>,
    summary: &mut String,
) -> Result<(), String> {
    fs::create_dir_all(scratch).map_err(|e| format!("cannot create {}: {e}", scratch.display()))?;
    let mut scores: Vec<DrawScore> = Vec::new();
    let mut common = Table::new([
        "condition",
        "seed",
        "points both pair",
        "abtrack (f64) RMSE (m)",
        "Stone Soup RMSE (m)",
    ]);
    let mut designs: Vec<String> = Vec::new();
    for (c, condition) in CONDITIONS.iter().enumerate() {
        for &seed in &DRAW_SEEDS {
            let text = measurements(truth, c, seed);
            let name = draw_name(condition, seed);
            for (numeric, label) in SCENE_NUMERICS {
                let run = track(truth, condition, &text, numeric, label)?;
                if numeric == Numeric::F64 {
                    write_file(&scratch.join(format!("{name}.meas.csv")), &text)?;
                    write_file(&scratch.join(format!("{name}.design")), &run.design)?;
                    if seed == DRAW_SEEDS[0] {
                        designs.push(format!("{}:\n{}", condition.name, run.design));
                    }
                }
                scores.push(DrawScore {
                    condition: c,
                    seed,
                    tracker: label.to_string(),
                    run,
                });
            }
            if let Some(run) = stonesoup_draw(dir, condition, seed, truth)? {
                let ours = scores.iter().find(|s| {
                    s.condition == c && s.seed == seed && s.tracker == SCENE_NUMERICS[0].1
                });
                if let Some((a, b, n)) = ours.and_then(|o| common_rmse(&o.run.pairs, &run.pairs)) {
                    common.push([
                        condition.name.to_string(),
                        seed.to_string(),
                        n.to_string(),
                        format!("{a:.1}"),
                        format!("{b:.1}"),
                    ]);
                }
                scores.push(DrawScore {
                    condition: c,
                    seed,
                    tracker: STONESOUP_LABEL.to_string(),
                    run,
                });
            }
        }
    }

    let mut per_draw = Table::new([
        "condition",
        "seed",
        "tracker",
        "coverage",
        "continuity",
        "id changes",
        "of which after a far update",
        "RMSE (m)",
        "OSPA (m)",
        "false tracks",
        "reported tracks",
    ]);
    for s in &scores {
        per_draw.push([
            CONDITIONS[s.condition].name.to_string(),
            s.seed.to_string(),
            s.tracker.clone(),
            format!("{:.3}", s.run.coverage),
            format!("{:.3}", s.run.continuity),
            s.run.id_changes.to_string(),
            far_update_id_changes(&s.tracker, &s.run)
                .map_or(NOT_APPLICABLE.to_string(), |n| n.to_string()),
            format!("{:.1}", s.run.rmse),
            format!("{:.1}", s.run.ospa),
            s.run.false_tracks.to_string(),
            s.run.reported_tracks.to_string(),
        ]);
    }
    per_draw.write(dir, "scene_draws")?;

    // Per condition and tracker: the mean over the seeds, and the range.
    let mut means = Table::new([
        "condition",
        "tracker",
        "draws",
        "coverage",
        "id changes",
        "of which after a far update",
        "RMSE (m)",
        "OSPA (m)",
        "false tracks",
    ]);
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let mut trackers: Vec<&str> = SCENE_NUMERICS.iter().map(|(_, l)| *l).collect();
        trackers.push(STONESOUP_LABEL);
        for tracker in trackers {
            let runs: Vec<&SceneRun> = scores
                .iter()
                .filter(|s| s.condition == c && s.tracker == tracker)
                .map(|s| &s.run)
                .collect();
            if runs.is_empty() {
                continue;
            }
            let of = |f: &dyn Fn(&SceneRun) -> f64| runs.iter().map(|r| f(r)).collect::<Vec<f64>>();
            let far: Option<Vec<f64>> = runs
                .iter()
                .map(|r| far_update_id_changes(tracker, r).map(|n| n as f64))
                .collect();
            means.push([
                condition.name.to_string(),
                tracker.to_string(),
                runs.len().to_string(),
                mean_and_range(&of(&|r| r.coverage), 3),
                mean_and_range(&of(&|r| r.id_changes as f64), 1),
                far.map_or(NOT_APPLICABLE.to_string(), |v| mean_and_range(&v, 1)),
                mean_and_range(&of(&|r| r.rmse), 1),
                mean_and_range(&of(&|r| r.ospa), 1),
                mean_and_range(&of(&|r| r.false_tracks as f64), 1),
            ]);
        }
    }
    means.write(dir, "scene_draws_means")?;

    let _ = writeln!(
        summary,
        "## The scene drawn again\n\n\
         The scene's truth measured again as its README says the files were made (each truth \
         point detected with P_D and perturbed by N(0, σ²) m per axis, σ {SIGMA_M} m unless the \
         condition names another, Poisson clutter \
         uniform over the square; a scan's plots in random order, where the files list the \
         detections first), seeds {DRAW_SEEDS:?}, in the \
         dev files' two conditions and in the condition of the held-out scene the project is \
         checked on (not in the repository; P_D {}, {:.0} clutter plots a \
         scan, {} per km²), and with other sensors' figures on the same truth (the conditions \
         named with a scan period T or a σ: the truth at that period, perturbed by that σ), \
         each run as `replay --tracker` is configured from its condition's figures. \
         Scored as above (pairs beyond {PAIR_LIMIT_M} m dropped, OSPA c = {OSPA_CUTOFF_M} m). \
         \"After a far update\": identity changes where the old track was updated, after the \
         flight's last pairing with it and up to its first with the new one, to a position \
         more than {PAIR_LIMIT_M} m from the flight (it took a plot from elsewhere: clutter or \
         another aircraft's); abtrack's only, as Stone Soup's rows have no update status. \
         Mean over the draws (least–most); per draw: `scene_draws.md`. Stone Soup rows, when \
         present, score what `scripts/stonesoup_scene.py --draws` wrote into `{STONESOUP_DIR}/{DRAWS_DIR}/` \
         from the drawn files this group leaves in `host-tests/target/scene-draws/`.\n",
        CONDITIONS[2].detection_probability,
        clutter_per_scan(&CONDITIONS[2]),
        CONDITIONS[2].clutter_per_km2,
    );
    let _ = writeln!(summary, "```text\n{}```\n", designs.join(""));
    summary.push_str(&means.to_markdown());
    if !common.rows.is_empty() {
        common.write(dir, "scene_draws_common")?;
        summary.push_str(
            "\nRMSE over the (scan, flight) points both abtrack (f64) and Stone Soup pair, per \
             draw:\n\n",
        );
        summary.push_str(&common.to_markdown());
    }
    summary.push('\n');
    Ok(())
}
