//! `auto` on the real single-aircraft segments: per segment, the position
//! RMSE of `auto:sigma=S` (f64, f32 and the fast fixed point), of a
//! constant-velocity Kalman filter with one q for the whole set (each q of a
//! grid; the best by median is marked) and of the raw measurements, at the
//! real report times and on a 4 s grid, noise N(0, S²) per axis, seeds 1–3.
//!
//! `cargo run --release --bin real_segments -- <dir of t,x,y[,alt_ft] CSVs> [S]`
//!
//! A report more than 20 s after the previous one restarts every filter (a
//! two-point start). The 4 s grid interpolates the truth linearly between
//! reports no more than 20 s apart; grid times inside longer holes are
//! omitted. The RMSE is √(mean(e_x² + e_y²)) over every report of the
//! segment, the two start points included (each estimate is then the
//! measurement).

use std::error::Error;
use std::path::Path;

use abtrack::gain::{AutoConfig, AutoGains, ScheduledFilter};
use abtrack::num::fixed32::Fixed32;
use abtrack::{Numeric, Quantity};
use abtrack_host_tests::kalman::{isotropic, Kalman, ProcessNoise};
use abtrack_host_tests::noise::{rng_from_seed, standard_normal};

/// The longest interval a track is carried over, s.
const RESTART_GAP_S: f64 = 20.0;
const SEEDS: [u64; 3] = [1, 2, 3];
const GRID_S: f64 = 4.0;
const KF_Q: [f64; 9] = [3.0, 10.0, 20.0, 30.0, 50.0, 70.0, 100.0, 200.0, 300.0];

type Point = (f64, [f64; 2]);

fn load(path: &Path) -> Result<Vec<Point>, Box<dyn Error>> {
    let text = std::fs::read_to_string(path)?;
    let mut out = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (t, x, y) = (f[0].parse()?, f[1].parse()?, f[2].parse()?);
        out.push((t, [x, y]));
    }
    Ok(out)
}

fn grid(points: &[Point]) -> Vec<Point> {
    let mut out = Vec::new();
    let (t0, t_end) = (points[0].0, points[points.len() - 1].0);
    let mut j = 0;
    let mut k = 0u32;
    loop {
        let t = t0 + GRID_S * f64::from(k);
        if t > t_end {
            return out;
        }
        while j + 1 < points.len() && points[j + 1].0 < t {
            j += 1;
        }
        if j + 1 < points.len() {
            let ((ta, a), (tb, b)) = (points[j], points[j + 1]);
            if tb - ta <= RESTART_GAP_S {
                let f = (t - ta) / (tb - ta);
                out.push((t, [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]));
            }
        } else if points[j].0 == t {
            out.push(points[j]);
        }
        k += 1;
    }
}

fn measurements(points: &[Point], sigma: f64, seed: u64) -> Vec<Point> {
    let mut rng = rng_from_seed(seed);
    points
        .iter()
        .map(|&(t, [x, y])| {
            let ex = sigma * standard_normal(&mut rng);
            let ey = sigma * standard_normal(&mut rng);
            (t, [x + ex, y + ey])
        })
        .collect()
}

/// Estimates at every measurement, restarting after gaps over 20 s.
fn run(
    meas: &[Point],
    mut start: impl FnMut(),
    mut step: impl FnMut([f64; 2], f64) -> [f64; 2],
) -> Vec<[f64; 2]> {
    let mut last: Option<f64> = None;
    meas.iter()
        .map(|&(t, z)| {
            let dt = match last {
                Some(l) if t - l <= RESTART_GAP_S => t - l,
                _ => {
                    start();
                    1.0
                }
            };
            last = Some(t);
            step(z, dt)
        })
        .collect()
}

fn auto<N: Numeric>(meas: &[Point], sigma: f64) -> Vec<[f64; 2]> {
    let schedule = AutoGains::<N, 2>::new(&AutoConfig::cartesian(sigma)).expect("auto");
    let fresh = ScheduledFilter::<N, _, 2, 2>::new(schedule);
    let track = std::cell::Cell::new(fresh);
    run(
        meas,
        || track.set(fresh),
        |z, dt| {
            let mut f = track.get();
            let zq = z.map(N::Length::from_f64_lossy);
            let out = match f.update(zq, N::Interval::from_f64_lossy(dt)) {
                Ok(_) => f.filter().position().map(Quantity::to_f64),
                // Refused (never seen on this data): the raw measurement.
                Err(_) => z,
            };
            track.set(f);
            out
        },
    )
}

fn kalman(meas: &[Point], sigma: f64, q: f64) -> Vec<[f64; 2]> {
    let fresh = Kalman::<4>::new(
        ProcessNoise::ContinuousWhiteAcceleration {
            spectral_density: q,
        },
        isotropic(sigma),
    )
    .expect("kf");
    let kf = std::cell::RefCell::new(fresh.clone());
    run(
        meas,
        || *kf.borrow_mut() = fresh.clone(),
        |z, dt| {
            let mut k = kf.borrow_mut();
            k.update(z, dt).expect("kf update");
            k.position()
        },
    )
}

fn rmse(estimates: &[[f64; 2]], truth: &[Point]) -> f64 {
    let sum: f64 = estimates
        .iter()
        .zip(truth)
        .map(|(e, (_, p))| (e[0] - p[0]).powi(2) + (e[1] - p[1]).powi(2))
        .sum();
    (sum / truth.len() as f64).sqrt()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().collect();
    let dir = args.get(1).ok_or("usage: real_segments <dir> [sigma]")?;
    let sigma: f64 = args.get(2).map_or(Ok(50.0), |s| s.parse())?;
    let mut paths: Vec<_> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    paths.sort();
    let methods = ["raw", "auto f64", "auto f32", "auto fixed"];
    for timing in ["real report times", "4 s grid"] {
        // rows[segment] = [raw, auto f64, f32, fixed, kf q...]
        let mut rows: Vec<(String, Vec<f64>)> = Vec::new();
        for path in &paths {
            let points = load(path)?;
            let truth = if timing == "4 s grid" {
                grid(&points)
            } else {
                points
            };
            let mut row = vec![0.0; methods.len() + KF_Q.len()];
            for seed in SEEDS {
                let meas = measurements(&truth, sigma, seed);
                let raw: Vec<[f64; 2]> = meas.iter().map(|m| m.1).collect();
                let mut r = vec![
                    rmse(&raw, &truth),
                    rmse(&auto::<f64>(&meas, sigma), &truth),
                    rmse(&auto::<f32>(&meas, sigma), &truth),
                    rmse(&auto::<Fixed32>(&meas, sigma), &truth),
                ];
                r.extend(KF_Q.iter().map(|&q| rmse(&kalman(&meas, sigma, q), &truth)));
                for (acc, v) in row.iter_mut().zip(r) {
                    *acc += v / SEEDS.len() as f64;
                }
            }
            let name = path
                .file_stem()
                .map_or(String::new(), |s| s.to_string_lossy().into());
            rows.push((name, row));
        }
        let medians: Vec<f64> = (0..methods.len() + KF_Q.len())
            .map(|i| median(rows.iter().map(|r| r.1[i]).collect()))
            .collect();
        let kf_medians = &medians[methods.len()..];
        let best = (0..KF_Q.len())
            .min_by(|&a, &b| kf_medians[a].total_cmp(&kf_medians[b]))
            .unwrap_or(0);
        let best_col = methods.len() + best;
        println!("## {timing}, σ {sigma} m, seeds 1-3 (mean RMSE per segment, m)\n");
        println!(
            "| segment | raw | auto f64 | auto f32 | auto fixed | KF q={} | auto/raw |",
            KF_Q[best]
        );
        println!("|---|---|---|---|---|---|---|");
        for (name, r) in &rows {
            println!(
                "| {name} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.3} |",
                r[0],
                r[1],
                r[2],
                r[3],
                r[best_col],
                r[1] / r[0]
            );
        }
        println!(
            "| **median** | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | |",
            medians[0], medians[1], medians[2], medians[3], medians[best_col]
        );
        let worst = rows.iter().map(|(_, r)| r[1] / r[0]).fold(0.0, f64::max);
        println!(
            "\nauto f64 median / best one-q KF median (q = {} of {:?}): {:.3}; worst segment auto/raw: {:.3}",
            KF_Q[best],
            KF_Q,
            medians[1] / medians[best_col],
            worst
        );
        let grid: Vec<String> = KF_Q
            .iter()
            .zip(kf_medians)
            .map(|(q, m)| format!("q={q}: {m:.1}"))
            .collect();
        println!("KF medians: {}\n", grid.join(", "));
    }
    Ok(())
}
