//! The multi-target scene's metrics for a `replay --tracker` output against
//! the scene's truth: coverage, continuity, id changes, RMSE, OSPA and false
//! tracks, as the real-data evaluation defines them.
//!
//! `cargo run --release --bin scene_metrics -- <truth.csv> <tracks.csv>`
//!
//! Reported tracks are those confirmed or coasting. Each scan, truth and
//! reported positions are paired by an optimal assignment on distance
//! ([`assignment`]), pairs over 500 m dropped. Coverage = paired truth
//! points / truth points; continuity = paired points / truth points after
//! the flight's first pairing; an id change is a change of the paired track
//! id between consecutive paired scans of one flight; a false track is one
//! paired in under half of its reported scans; OSPA (c = 1000 m, p = 2,
//! [`ospa`]) averaged over scans; RMSE over paired points.

use std::collections::{BTreeMap, HashMap};
use std::error::Error;

use abtrack_host_tests::metrics::{assignment, ospa};

const PAIR_LIMIT_M: f64 = 500.0;
const OSPA_CUTOFF_M: f64 = 1000.0;

type Scans = BTreeMap<i64, Vec<(String, [f64; 2])>>;

/// Rows of `path` by scan time (ms): (id, position); `keep` filters on the
/// row's third column (the status) when given.
fn read(path: &str, keep: Option<&[&str]>) -> Result<Scans, Box<dyn Error>> {
    let mut out = Scans::new();
    for line in std::fs::read_to_string(path)?.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (t, id) = (f[0].parse::<f64>()?, f[1].to_string());
        let (x, y) = match keep {
            Some(statuses) if !statuses.contains(&f[2]) => continue,
            Some(_) => (f[3].parse()?, f[4].parse()?),
            None => (f[2].parse()?, f[3].parse()?),
        };
        out.entry((t * 1000.0).round() as i64)
            .or_default()
            .push((id, [x, y]));
    }
    Ok(out)
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (truth, tracks) = match (args.get(1), args.get(2)) {
        (Some(a), Some(b)) => (read(a, None)?, read(b, Some(&["confirmed", "coasting"]))?),
        _ => return Err("usage: scene_metrics <truth.csv> <tracks.csv>".into()),
    };
    let empty = Vec::new();
    let (mut truth_points, mut paired, mut squared, mut ospa_sum) = (0usize, 0usize, 0.0, 0.0);
    let mut scans = 0usize;
    // Per flight: scan index of each pairing and the paired track.
    let mut flights: HashMap<String, Vec<(usize, Option<String>)>> = HashMap::new();
    // Per track: (reported scans, paired scans).
    let mut reported: HashMap<String, (usize, usize)> = HashMap::new();
    let times: std::collections::BTreeSet<i64> =
        truth.keys().chain(tracks.keys()).copied().collect();
    for (k, t) in times.iter().enumerate() {
        let truths = truth.get(t).unwrap_or(&empty);
        let tracked = tracks.get(t).unwrap_or(&empty);
        scans += 1;
        let xs: Vec<[f64; 2]> = truths.iter().map(|p| p.1).collect();
        let ys: Vec<[f64; 2]> = tracked.iter().map(|p| p.1).collect();
        ospa_sum += ospa(&xs, &ys, OSPA_CUTOFF_M, 2.0).distance;
        let cost: Vec<Vec<f64>> = xs
            .iter()
            .map(|a| {
                ys.iter()
                    .map(|b| (a[0] - b[0]).hypot(a[1] - b[1]))
                    .collect()
            })
            .collect();
        let pairs = if ys.is_empty() {
            vec![None; xs.len()]
        } else {
            assignment(&cost)
        };
        for (id, _) in tracked {
            reported.entry(id.clone()).or_default().0 += 1;
        }
        truth_points += truths.len();
        for (i, (flight, _)) in truths.iter().enumerate() {
            let j = pairs
                .get(i)
                .copied()
                .flatten()
                .filter(|&j| cost[i][j] <= PAIR_LIMIT_M);
            let track = j.map(|j| tracked[j].0.clone());
            if let Some(j) = j {
                paired += 1;
                squared += cost[i][j] * cost[i][j];
                reported.entry(tracked[j].0.clone()).or_default().1 += 1;
            }
            flights.entry(flight.clone()).or_default().push((k, track));
        }
    }
    let (mut after_first, mut paired_after, mut id_changes) = (0usize, 0usize, 0usize);
    for points in flights.values() {
        let Some(first) = points.iter().position(|p| p.1.is_some()) else {
            continue;
        };
        after_first += points.len() - first;
        let ids: Vec<&String> = points[first..]
            .iter()
            .filter_map(|p| p.1.as_ref())
            .collect();
        paired_after += ids.len();
        id_changes += ids.windows(2).filter(|w| w[0] != w[1]).count();
    }
    let false_tracks = reported.values().filter(|(r, p)| 2 * p < *r).count();
    println!(
        "coverage {:.3} continuity {:.3} id_changes {} rmse_m {:.1} ospa_m {:.1} false_tracks {}",
        paired as f64 / truth_points.max(1) as f64,
        paired_after as f64 / after_first.max(1) as f64,
        id_changes,
        (squared / paired.max(1) as f64).sqrt(),
        ospa_sum / scans.max(1) as f64,
        false_tracks
    );
    Ok(())
}
