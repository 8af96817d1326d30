//! Li, Zhao, Liang & Zhang §5: the improved αβ filter against the standard
//! one on the manoeuvring target (their Figures 2–4 and the running-time
//! comparison), with the Kalman yardsticks.
//!
//! The standard filter Li et al. compare against is the one of their §2:
//! α and β from the scan count, eqs. (4)–(5) (`least-squares`, the same
//! gains as Al-Wagih & Abdulla's M2). The improved filter is
//! `li-improved` with its documented defaults (R = 3, Δρ = 1 m, Δθ = 0:
//! the paper gives no R and its noise is Cartesian, see
//! `abtrack::gain::li`). The scenario module reads eq. (11) for Cartesian
//! noise as Δd = λ·σ√2 instead; that reading is run as a second variant,
//! and a small grid of R and Δρ is reported as a sensitivity table (never
//! used for the verdicts).

use std::time::Instant;

use super::common::{fmt_ci, write_file, Context, Series, Table};
use super::monte_carlo::{
    self, claims_markdown, claims_table, compare, manoeuvring_scans, plot_against_time,
    plot_tracks, rmse_table, Claim, Comparison, Estimator, Experiment, Method, Metric, Scheduled,
    Segment, ALL_SCANS, FIRST_FILTERED,
};
use crate::scenario::{self, monte_carlo_seed};

pub const GROUP: &str = "li";
pub const SCENARIO: &str = "li-maneuver";
pub const BASE_SEED: u64 = 0x11_3001;

pub const STANDARD: &str = "standard αβ";
pub const IMPROVED: &str = "improved αβ";
pub const IMPROVED_SQRT2: &str = "improved (Δd = λσ√2)";
pub const KF_CV: &str = "Kalman CV";
pub const KF_CA: &str = "Kalman CA";

pub const STANDARD_SPEC: &str = "least-squares";
pub const IMPROVED_SPEC: &str = "li-improved";
/// Δρ = σ√2 with Δθ = 0: the same Δd as `SensorNoise::range_bearing_errors`
/// gives for the scenario's Cartesian σ = 1 m (Δρ = σ, ρΔθ = σ).
pub const IMPROVED_SQRT2_SPEC: &str = "li-improved:range-error=1.4142135623730951";

pub fn methods(info: &scenario::ScenarioInfo) -> Result<Vec<Method>, String> {
    Ok(vec![
        Method::schedule::<f64>(STANDARD, STANDARD_SPEC)?,
        Method::schedule::<f64>(IMPROVED, IMPROVED_SPEC)?,
        Method::schedule::<f64>(IMPROVED_SQRT2, IMPROVED_SQRT2_SPEC)?,
        Method::kalman_cv(KF_CV, info)?,
        Method::kalman_ca(KF_CA, info)?,
    ])
}

/// The sensitivity grid: R × Δρ.
const SENSITIVITY_R: [f64; 3] = [2.0, 3.0, 5.0];
const SENSITIVITY_RANGE_ERROR: [(f64, &str); 2] = [(1.0, "1"), (std::f64::consts::SQRT_2, "√2")];

fn sensitivity_methods() -> Result<Vec<Method>, String> {
    let mut out = vec![Method::schedule::<f64>(STANDARD, STANDARD_SPEC)?];
    for r in SENSITIVITY_R {
        for (dr, name) in SENSITIVITY_RANGE_ERROR {
            out.push(Method::schedule::<f64>(
                &format!("improved R={r}, Δρ={name}"),
                &format!("li-improved:r={r},range-error={dr}"),
            )?);
        }
    }
    Ok(out)
}

pub fn evaluate(runs: Option<usize>) -> Result<Experiment, String> {
    let info = scenario::info(SCENARIO).ok_or("li-maneuver missing")?;
    let n = runs.unwrap_or(info.monte_carlo_runs);
    monte_carlo::run(SCENARIO, BASE_SEED, n, &methods(&info)?)
}

/// The scans at which the truth accelerated during the preceding period
/// (scans 13–17, 33–37, 54–74, 83–87 counted from 1), and the others.
pub struct Segments {
    manoeuvring: Vec<bool>,
    first_manoeuvre: usize,
}

impl Segments {
    pub fn new(exp: &Experiment) -> Self {
        let manoeuvring = manoeuvring_scans(&exp.truth);
        let first_manoeuvre = manoeuvring
            .iter()
            .position(|&m| m)
            .unwrap_or(manoeuvring.len());
        Segments {
            manoeuvring,
            first_manoeuvre,
        }
    }
    pub fn is_manoeuvring(&self, k: usize) -> bool {
        self.manoeuvring.get(k).copied().unwrap_or(false)
    }
    /// Before the first manoeuvre (scans 3–12 counted from 1): straight
    /// flight with no lag left over from an earlier manoeuvre, where the
    /// standard gains are the least-squares line fit.
    pub fn before_first(&self, k: usize) -> bool {
        k < self.first_manoeuvre
    }
}

pub fn claims(exp: &Experiment) -> Result<Vec<Claim>, String> {
    let seg = Segments::new(exp);
    let man = |k: usize| seg.is_manoeuvring(k);
    let steady = |k: usize| !seg.is_manoeuvring(k);
    let manoeuvring = Segment {
        name: "manoeuvring",
        contains: &man,
    };
    let non_manoeuvring = Segment {
        name: "non-manoeuvring",
        contains: &steady,
    };
    let first = |k: usize| seg.before_first(k);
    let before_first = Segment {
        name: "before the first manoeuvre",
        contains: &first,
    };
    let cmp = |metric: Metric, segment: Segment<'_>| -> Result<Comparison, String> {
        compare(exp, "", IMPROVED, STANDARD, metric, segment)
    };
    let line = |c: &[Comparison]| -> String {
        c.iter()
            .map(|c| {
                format!(
                    "{} ({}): improved {:.2} vs standard {:.2}, diff {}",
                    c.metric.name(),
                    c.segment,
                    c.better_rmse.mean,
                    c.worse_rmse.mean,
                    fmt_ci(&c.difference, 2)
                )
            })
            .collect::<Vec<_>>()
            .join("; ")
            + "."
    };
    let mut claims = Vec::new();

    let l1 = vec![
        cmp(Metric::VelocityX, ALL_SCANS)?,
        cmp(Metric::VelocityY, ALL_SCANS)?,
    ];
    let ours = line(&l1);
    let tally = Claim::judged("", "", "", l1.clone(), String::new(), String::new()).tally();
    claims.push(Claim::judged(
        "L1",
        "§5, Figure 3",
        "\"the velocity estimates are more accurate in the proposed α-β filter from the 3rd scan\"",
        l1,
        ours,
        format!(
            "{tally}. The standard gains fall as 6/(k(k+1)), so after the first manoeuvre its \
             velocity error decays only over tens of scans; the improved count drops when d/Δd \
             exceeds R and the velocity recovers within a few scans."
        ),
    ));

    let l2 = vec![
        cmp(Metric::VelocityX, manoeuvring)?,
        cmp(Metric::VelocityY, manoeuvring)?,
    ];
    let ours = line(&l2);
    let tally = Claim::judged("", "", "", l2.clone(), String::new(), String::new()).tally();
    claims.push(Claim::judged(
        "L2",
        "§5, Figure 3",
        "\"it represents the change of x and y velocities rapidly when the motion dynamics are \
         switching\"",
        l2,
        ours,
        format!("{tally}, scored over the manoeuvring scans only."),
    ));

    let l3 = vec![
        cmp(Metric::PositionX, manoeuvring)?,
        cmp(Metric::PositionY, manoeuvring)?,
        cmp(Metric::PositionX, non_manoeuvring)?,
        cmp(Metric::PositionY, non_manoeuvring)?,
        cmp(Metric::PositionX, before_first)?,
        cmp(Metric::PositionY, before_first)?,
    ];
    let ours = line(&l3);
    let tally = Claim::judged("", "", "", l3.clone(), String::new(), String::new()).tally();
    claims.push(Claim::judged(
        "L3",
        "§5, Figure 4",
        "the standard filter's position error grows when the target manoeuvres; the proposed \
         filter \"achieves better performance whether the target is maneuvering or \
         non-maneuvering\"",
        l3,
        ours,
        format!(
            "{tally}. \"Non-manoeuvring\" scans include the standard filter's long recovery \
             after each manoeuvre, where its lag persists; before the first manoeuvre the \
             standard gains are the least-squares line fit, optimal for straight flight, while \
             the improved count keeps falling back towards k = 3 (α ≈ 0.5–0.83, `alpha.svg`), \
             so it smooths less."
        ),
    ));

    // Running time: a descriptive claim, judged by the measured ratio.
    let (standard_s, improved_s) = running_time(exp)?;
    let ratio = improved_s / standard_s;
    // Two parts: the improved filter costs more, and by an amount like the
    // paper's 15 % (within a factor of two: 7.5–30 %).
    let overhead = ratio - 1.0;
    let verdict =
        monte_carlo::Verdict::of_parts(&[overhead > 0.0, (0.075..=0.30).contains(&overhead)]);
    claims.push(Claim {
        id: "L4".into(),
        source: "§5, running time".into(),
        claim: "the proposed filter costs 15.21 % more time than the standard one (2.386 s vs \
                2.071 s for 100 runs): \"slightly more computational expense\""
            .into(),
        comparisons: Vec::new(),
        ours: format!(
            "{:.2} ms vs {:.2} ms for {} runs × {} scans (best of {TIMING_REPEATS} interleaved \
             samples, release build, f64, one core): {:+.0} %.",
            improved_s * 1e3,
            standard_s * 1e3,
            exp.runs(),
            exp.truth.len(),
            (ratio - 1.0) * 100.0
        ),
        verdict,
        reason: "Two parts: costlier (yes/no) and by an amount like the paper's (7.5–30 %). \
                 Timing depends on the machine, its load and the implementation (the paper \
                 does not say what its times include); on our shared two-core machine repeated \
                 runs gave between about +35 % and +100 %, always above the paper's 15 %, so the \
                 tests do not assert it. The extra work per scan is two norms, two square \
                 roots and a division (eqs. 10–13) on top of an update of a few \
                 multiply-adds."
            .into(),
    });
    Ok(claims)
}

const TIMING_REPEATS: usize = 40;
/// Passes over the data per timed sample (≈ 10 ms per sample), so the
/// clock's resolution and one-off stalls matter less.
const TIMING_PASSES: usize = 10;

/// Wall time of the standard and the improved filter over every run's
/// measurements (f64): per filter, the best of `TIMING_REPEATS` samples,
/// the two filters' samples interleaved so that both see the same machine
/// load; returned per pass over the data.
pub fn running_time(exp: &Experiment) -> Result<(f64, f64), String> {
    let data: Vec<Vec<[f64; 2]>> = (0..exp.runs())
        .map(|r| {
            let run = scenario::generate(SCENARIO, monte_carlo_seed(exp.base_seed, r as u64))
                .map_err(|e| e.to_string())?;
            Ok(run
                .scans
                .iter()
                .filter_map(|s| s.measurements.first().map(|m| m.position()))
                .collect())
        })
        .collect::<Result<_, String>>()?;
    let dt = exp.info.period_s;
    let sample = |spec: &str| -> Result<f64, String> {
        let start = Instant::now();
        let mut sink = 0.0;
        for _ in 0..TIMING_PASSES {
            for run in &data {
                let mut f = Scheduled::<f64>::from_spec(spec)?;
                for z in run {
                    sink += f.step(*z, dt)?.position[0];
                }
            }
        }
        std::hint::black_box(sink);
        Ok(start.elapsed().as_secs_f64() / TIMING_PASSES as f64)
    };
    let mut best = (f64::INFINITY, f64::INFINITY);
    for _ in 0..TIMING_REPEATS {
        best.0 = best.0.min(sample(STANDARD_SPEC)?);
        best.1 = best.1.min(sample(IMPROVED_SPEC)?);
    }
    Ok(best)
}

const METRICS: [Metric; 4] = [
    Metric::PositionX,
    Metric::PositionY,
    Metric::VelocityX,
    Metric::VelocityY,
];

pub fn run(ctx: &Context) -> Result<(), String> {
    let info = scenario::info(SCENARIO).ok_or("li-maneuver missing")?;
    let exp = evaluate(Some(ctx.runs(info.monte_carlo_runs)))?;
    let dir = ctx.group_dir(GROUP)?;
    let seg = Segments::new(&exp);
    let man = |k: usize| seg.is_manoeuvring(k);
    let steady = |k: usize| !seg.is_manoeuvring(k);
    let all: Vec<_> = exp.methods.iter().collect();
    rmse_table(&all, &METRICS, ALL_SCANS, 3).write(&dir, "rmse")?;
    rmse_table(
        &all,
        &METRICS,
        Segment {
            name: "manoeuvring",
            contains: &man,
        },
        3,
    )
    .write(&dir, "rmse_manoeuvring")?;
    rmse_table(
        &all,
        &METRICS,
        Segment {
            name: "non-manoeuvring",
            contains: &steady,
        },
        3,
    )
    .write(&dir, "rmse_non_manoeuvring")?;

    // Sensitivity of the improved filter to the unstated R and Δd.
    let sens = monte_carlo::run(SCENARIO, BASE_SEED, exp.runs(), &sensitivity_methods()?)?;
    let mut t = Table::new([
        "method",
        "position distance, all (m)",
        "position distance, manoeuvring (m)",
        "position distance, non-manoeuvring (m)",
        "velocity distance, all (m/s)",
        "configuration",
    ]);
    for m in &sens.methods {
        let s = |metric: Metric, contains: &dyn Fn(usize) -> bool| {
            fmt_ci(&m.summary(metric, Segment { name: "", contains }), 3)
        };
        t.push([
            m.label.clone(),
            s(Metric::PositionDistance, &|_| true),
            s(Metric::PositionDistance, &man),
            s(Metric::PositionDistance, &steady),
            s(Metric::VelocityDistance, &|_| true),
            m.detail.clone(),
        ]);
    }
    t.write(&dir, "sensitivity")?;

    let shown: Vec<_> = [STANDARD, IMPROVED, KF_CV]
        .iter()
        .map(|l| exp.method(l))
        .collect::<Result<_, _>>()?;
    plot_tracks(
        &dir.join("track.svg"),
        &exp,
        &shown,
        "Li et al. Fig. 2: target trajectory and estimates (run 0)",
        false,
    )?;
    let curves: Vec<_> = [STANDARD, IMPROVED, IMPROVED_SQRT2, KF_CV, KF_CA]
        .iter()
        .map(|l| exp.method(l))
        .collect::<Result<_, _>>()?;
    for (metric, file, title, cap) in [
        (
            Metric::VelocityX,
            "rmse_velocity_x.svg",
            "Li et al. Fig. 3: RMSE of x velocity (clipped at 6 m/s)",
            Some(6.0),
        ),
        (
            Metric::VelocityY,
            "rmse_velocity_y.svg",
            "Li et al. Fig. 3: RMSE of y velocity (clipped at 6 m/s)",
            Some(6.0),
        ),
        (
            Metric::PositionX,
            "rmse_position_x.svg",
            "Li et al. Fig. 4: RMSE of x position (clipped at 6 m)",
            Some(6.0),
        ),
        (
            Metric::PositionY,
            "rmse_position_y.svg",
            "Li et al. Fig. 4: RMSE of y position (clipped at 6 m)",
            Some(6.0),
        ),
    ] {
        plot_against_time(&dir.join(file), &exp, &curves, metric, title, cap)?;
    }
    // The mechanism: α of the standard and the improved filter in run 0.
    let alpha = |label: &str| -> Result<Series, String> {
        let m = exp.method(label)?;
        let run = m.runs.first().ok_or("no runs")?;
        Ok(Series::line(
            label,
            run.iter()
                .enumerate()
                .skip(FIRST_FILTERED)
                .filter_map(|(k, s)| s.output.gains.map(|g| (exp.time(k), g[0].0)))
                .collect(),
        ))
    };
    super::common::plot(
        &dir.join("alpha.svg"),
        &super::common::PlotSpec {
            title: "Li et al.: α of the standard and the improved filter (run 0)",
            x_label: "time (s)",
            y_label: "α",
            equal_aspect: false,
            y_max: None,
        },
        &[alpha(STANDARD)?, alpha(IMPROVED)?],
    )?;

    let claims = claims(&exp)?;
    claims_table(&claims).write(&dir, "claims")?;
    write_file(&dir.join("summary.md"), &summary(&exp, &claims)?)?;
    Ok(())
}

fn summary(exp: &Experiment, claims: &[Claim]) -> Result<String, String> {
    let seg = Segments::new(exp);
    let man = |k: usize| seg.is_manoeuvring(k);
    let manoeuvring = Segment {
        name: "manoeuvring",
        contains: &man,
    };
    let mut s = String::new();
    s.push_str("# Li, Zhao, Liang & Zhang (001): improved vs standard αβ filter\n\n");
    s.push_str(&format!(
        "Scenario `li-maneuver` (§5: 100 scans, T = 1 s, (10, 5) m/s from (0, 0), accelerations \
         in scans 12–16, 32–36, 53–73, 82–86, noise σ = 1 m per axis), {} Monte Carlo runs, base \
         seed {:#x}. Standard = `{STANDARD_SPEC}` (eqs. 4–5, the filter of §2); improved = \
         `{IMPROVED_SPEC}` with its documented defaults (R = 3, Δρ = 1 m, Δθ = 0; the paper \
         gives no R). Scored from the third scan. Manoeuvring scans: those whose preceding \
         period had a non-zero acceleration ({} of {} scored scans).\n\n",
        exp.runs(),
        exp.base_seed,
        (FIRST_FILTERED..exp.truth.len())
            .filter(|&k| seg.is_manoeuvring(k))
            .count(),
        exp.truth.len() - FIRST_FILTERED
    ));
    s.push_str(
        "Regenerate: `cd host-tests && cargo run --release --bin experiments -- --only li`\n\n",
    );
    s.push_str("## Headline (RMSE, mean ± 95 % CI over runs)\n\n");
    s.push_str("| method | position x / y (m), all | velocity x / y (m/s), all | position x / y (m), manoeuvring |\n|---|---|---|---|\n");
    for m in &exp.methods {
        let c = |metric, seg| fmt_ci(&m.summary(metric, seg), 3);
        s.push_str(&format!(
            "| {} | {} / {} | {} / {} | {} / {} |\n",
            m.label,
            c(Metric::PositionX, ALL_SCANS),
            c(Metric::PositionY, ALL_SCANS),
            c(Metric::VelocityX, ALL_SCANS),
            c(Metric::VelocityY, ALL_SCANS),
            c(Metric::PositionX, manoeuvring),
            c(Metric::PositionY, manoeuvring),
        ));
    }
    s.push_str("\n## Claims\n\n");
    s.push_str(&claims_markdown(claims));
    s.push_str(NOTES);
    s.push_str(
        "\n## Files\n\n\
         - `rmse.md`, `rmse_manoeuvring.md`, `rmse_non_manoeuvring.md` (+ `.csv`): per-axis \
         position and velocity RMSE, mean ± 95 % CI\n\
         - `claims.md`: the paired comparisons behind the verdicts\n\
         - `sensitivity.md`: the improved filter for R ∈ {2, 3, 5} × Δρ ∈ {1, √2} m (not used \
         for the verdicts)\n\
         - `track.svg` (Figure 2), `rmse_velocity_{x,y}.svg` (Figure 3), \
         `rmse_position_{x,y}.svg` (Figure 4), `alpha.svg` (the gains in run 0)\n",
    );
    Ok(s)
}

const NOTES: &str = "\n## Readings and comparability\n\n\
The paper shows its results only as curves (Figures 2–4), without numbers, so only the \
direction and the shape can be compared. Its r_k is read as two quantities (the ratio d/Δd of \
the scan and an effective scan count it drives; see `abtrack::gain::li`). \"The covariance of \
noise is 1\" is read as σ = 1 m per axis. R, Δρ and Δθ are not given: we use the schedule's \
documented defaults, and `sensitivity.md` shows how the result moves with them.\n";
