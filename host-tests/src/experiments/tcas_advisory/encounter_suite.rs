//! The `tcas-advisory` group's first part: the encounter suite
//! ([`crate::encounters`]) on exact inputs and over seeds, in f64, f32 and
//! Q32.32 against the independent reference, and the altitude tracker's
//! figures ([`crate::altitude_figures`]).

use std::fmt::Write as _;
use std::path::Path;

use abtrack::filter::altitude::AltitudeQuantum;
use abtrack::{Fix, Scalar};

use super::super::common::Table;
use crate::altitude_figures::{level_off, ra_response, rate_change, steady_climb_rate_range};
use crate::encounters::{
    measurements, noisy_runs, run_library, run_reference, suite, timeline, Noise, NoiseCounts,
    Timeline, BEARING_SIGMA_RAD, FALSE_ALERT_TOLERANCE_S, RANGE_SIGMA_M,
};
use crate::reference_tcas::Sense;

/// Documented noisy runs per encounter and type.
pub const RUNS: usize = 100;

/// The range acceleration of the `offset-beyond-hmd` pass (exact ranges)
/// from the library's range tracker (straight-path prediction) and from a
/// parabolic-prediction tracker with the same firmness gains (abtrack's
/// αβγ filter, γ/(2T²), fed 2γ so the correction is DO-185B's γ/T²; r̈
/// held at zero until firmness 8, as DO-185B), against the truth, at the
/// scans nearest the listed ranges; with the HMD each implies.
fn range_acceleration_table() -> Result<Table, String> {
    use abtrack::filter::{AlphaBetaGamma, Gains};
    use abtrack::gain::tcas::{FIRMNESS_ALPHA, FIRMNESS_BETA, FIRMNESS_GAMMA};
    use abtrack::tcas::RangeTracker;
    let e = suite()
        .into_iter()
        .find(|e| e.name == "offset-beyond-hmd")
        .ok_or("offset-beyond-hmd missing")?;
    let meas = measurements(&e, Noise::Exact);
    let mut straight = RangeTracker::<f64>::new();
    let mut parabolic = AlphaBetaGamma::<f64>::new();
    let mut rows = Vec::new();
    for (k, m) in meas.iter().enumerate() {
        straight.update(m.range_m, 1.0).map_err(|e| e.to_string())?;
        let firmness = k.min(8);
        let g = if firmness == 8 {
            Gains::alpha_beta_gamma(FIRMNESS_ALPHA[8], FIRMNESS_BETA[8], 2.0 * FIRMNESS_GAMMA[8])
        } else {
            Gains::alpha_beta(
                FIRMNESS_ALPHA[firmness.max(1)],
                FIRMNESS_BETA[firmness.max(1)],
            )
        }
        .map_err(|e| e.to_string())?;
        parabolic
            .update(m.range_m, 1.0, &g)
            .map_err(|e| e.to_string())?;
        let x = e.relative(k as f64);
        let r = x.s[0].hypot(x.s[1]);
        let v2 = x.v[0] * x.v[0] + x.v[1] * x.v[1];
        let d = (x.s[0] * x.v[1] - x.s[1] * x.v[0]).abs() / v2.sqrt();
        let truth = v2 * d * d / (r * r * r);
        // Approaching only (the same ranges come again after the CPA).
        if x.s[0] * x.v[0] + x.s[1] * x.v[1] < 0.0 {
            rows.push((
                r,
                truth,
                straight.estimate(),
                parabolic.acceleration(),
                parabolic.velocity(),
            ));
        }
    }
    let hmd = |r: f64, rdot: f64, rdd: f64| {
        if rdd > 0.0 {
            format!("{:.0}", r * (r * rdd / (r * rdd + rdot * rdot)).sqrt())
        } else {
            "–".into()
        }
    };
    let mut t = Table::new([
        "range (m)",
        "true r̈ (m/s²)",
        "straight-path tracker r̈",
        "its HMD (m)",
        "parabolic tracker r̈",
        "its HMD (m)",
    ]);
    for target in [9000.0, 8000.0, 7000.0, 6300.0, 5000.0, 4000.0, 3000.0] {
        let Some(&(r, truth, est, acc, vel)) = rows
            .iter()
            .filter(|row| row.0 >= target)
            .min_by(|a, b| a.0.total_cmp(&b.0))
        else {
            continue;
        };
        let est = est.ok_or("no estimate")?;
        t.push([
            format!("{r:.0}"),
            format!("{truth:.3}"),
            format!("{:.3}", est.range_acceleration_m_per_s2),
            hmd(r, est.range_rate_m_per_s, est.range_acceleration_m_per_s2),
            format!("{acc:.3}"),
            hmd(r, vel, acc),
        ]);
    }
    Ok(t)
}

fn opt(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{v:.0}"))
}

fn sense(s: Option<Sense>) -> &'static str {
    match s {
        Some(Sense::Up) => "up",
        Some(Sense::Down) => "down",
        None => "–",
    }
}

fn events(t: &Timeline) -> [String; 4] {
    [
        opt(t.ta_onset_s),
        opt(t.ra_onset_s),
        sense(t.sense).into(),
        opt(t.clear_of_conflict_s),
    ]
}

/// Exact inputs: the reference's events and each type's.
fn exact_table() -> Result<(Table, usize), String> {
    let mut t = Table::new([
        "encounter",
        "expected TA (s)",
        "expected RA (s)",
        "expected sense",
        "expected CoC (s)",
        "f64 TA / RA / sense / CoC",
        "f32 TA / RA / sense / CoC",
        "Q32.32 TA / RA / sense / CoC",
    ]);
    let mut identical = 0;
    for e in suite() {
        let want = timeline(&run_reference(&e));
        let meas = measurements(&e, Noise::Exact);
        let runs = [
            timeline(&run_library::<f64>(&e, &meas)?),
            timeline(&run_library::<f32>(&e, &meas)?),
            timeline(&run_library::<Fix>(&e, &meas)?),
        ];
        let mut row: Vec<String> = vec![e.name.into()];
        row.extend(events(&want));
        for r in &runs {
            let [a, b, c, d] = events(r);
            row.push(format!("{a} / {b} / {c} / {d}"));
            identical += usize::from(events(r) == events(&want));
        }
        t.push(row);
    }
    Ok((t, identical))
}

fn range(v: &[f64]) -> String {
    if v.is_empty() {
        return "–".into();
    }
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    format!("{mean:+.2} ({lo:+.0}..{hi:+.0})")
}

fn noise_rows<S: Scalar>(t: &mut Table, runs: usize, totals: &mut NoiseCounts) {
    for (i, e) in suite().into_iter().enumerate() {
        let n = noisy_runs::<S>(&e, i as u64, runs);
        t.push([
            e.name.to_string(),
            S::NAME.to_string(),
            n.runs.to_string(),
            format!("{} / {}", n.missed_ta, n.missed_ra),
            format!("{} / {}", n.false_ta, n.false_ra),
            n.wrong_sense.to_string(),
            n.interrupted_ra.to_string(),
            range(&n.ta_delays),
            range(&n.ra_delays),
            range(&n.coc_delays),
        ]);
        totals.runs += n.runs;
        totals.missed_ta += n.missed_ta;
        totals.missed_ra += n.missed_ra;
        totals.false_ta += n.false_ta;
        totals.false_ra += n.false_ra;
        totals.wrong_sense += n.wrong_sense;
        totals.interrupted_ra += n.interrupted_ra;
        totals.refused += n.refused;
    }
}

/// The altitude tracker's figures, per quantum and type.
fn altitude_table() -> Table {
    let mut t = Table::new([
        "reports",
        "type",
        "300 ft/min climb read (ft/min, t ≥ 60 s)",
        "level-off from 2000 ft/min: rate 2 s after (ft/min, worst phase)",
        "level-off: within 300 ft/min after (s, phases)",
        "0.25 g RA response to 1500 ft/min: within 300 ft/min after (s, phases)",
    ]);
    fn row<S: Scalar>(t: &mut Table, q: AltitudeQuantum) {
        let (lo, hi) = steady_climb_rate_range::<S>(q, 300.0, 60, 240);
        let off = rate_change::<S>(q, level_off(), 2, 300.0, 120);
        let ra = rate_change::<S>(q, ra_response(), 2, 300.0, 120);
        let span = |v: &[Option<f64>]| {
            let v: Vec<f64> = v.iter().map(|s| s.unwrap_or(f64::NAN)).collect();
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            format!("{lo:.0}..{hi:.0}")
        };
        let at2 = off
            .at_probe_ft_per_min
            .iter()
            .fold(0.0f64, |m, r| m.max(r.abs()));
        t.push([
            format!("{} ft", q.feet()),
            S::NAME.to_string(),
            format!("{lo:.1}..{hi:.1}"),
            format!("{at2:.0}"),
            span(&off.settling_s),
            span(&ra.settling_s),
        ]);
    }
    for q in [AltitudeQuantum::ModeC, AltitudeQuantum::ModeS25] {
        row::<f64>(&mut t, q);
        row::<f32>(&mut t, q);
        row::<Fix>(&mut t, q);
    }
    t
}

/// Writes the tables and returns the summary section.
pub fn write(dir: &Path, runs: usize) -> Result<String, String> {
    let (exact, identical) = exact_table()?;
    exact.write(dir, "encounters_exact")?;
    let mut noise = Table::new([
        "encounter",
        "type",
        "runs",
        "missed TA / RA",
        "false TA / RA (runs)",
        "wrong sense",
        "RA interrupted",
        "TA onset − expected (s): mean (range)",
        "RA onset − expected (s)",
        "CoC − expected (s)",
    ]);
    let mut totals = NoiseCounts::default();
    noise_rows::<f64>(&mut noise, runs, &mut totals);
    noise_rows::<f32>(&mut noise, runs, &mut totals);
    noise_rows::<Fix>(&mut noise, runs, &mut totals);
    noise.write(dir, "encounters_noise")?;
    let altitude = altitude_table();
    altitude.write(dir, "altitude_tracker")?;
    let acceleration = range_acceleration_table()?;
    acceleration.write(dir, "range_acceleration")?;

    let encounters = suite().len();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# The TCAS II v7.1 logic on the encounter suite\n\n\
         {encounters} encounters (`host-tests/src/encounters.rs`; own level at 8000 ft, SL 5, unless stated; 1 s \
         scans; open loop — the own aircraft does not follow the RA): each through the library (range tracker, \
         altitude tracker, the range–azimuth filter as bearing tracker, threat detection, resolution) and through \
         the independent f64 reference (`host-tests/src/reference_tcas.rs`) on the true states, which gives the \
         expected events.\n"
    );
    let _ = writeln!(
        s,
        "## Exact inputs\n\nNoise-free range and bearing, altitude quantised to 100 ft. {identical} of {} \
         library timelines (encounters × f64, f32, Q32.32) have exactly the reference's TA onset, RA onset, \
         sense and clear of conflict; the others differ by the amounts in `encounters_exact.md` (the tests \
         allow one scan on onsets, two on clear of conflict).\n",
        3 * encounters
    );
    s.push_str(&exact.to_markdown());
    let _ = writeln!(
        s,
        "\n## With noise\n\nRange σ {RANGE_SIGMA_M} m, bearing σ {:.0}°, altitude quantised; {runs} seeds per \
         encounter and type. Missed: the reference has the alert, the run never does. False: the run starts the \
         alert more than {FALSE_ALERT_TOLERANCE_S} s from every scan at which the reference has it (a late end \
         of a true alert is in the CoC column instead). Over all {} runs: {} missed TAs, {} missed RAs, {} runs \
         with a false TA, {} with a false RA, {} with the wrong sense, {} with an RA dropped early (the reference's \
         RA going on for more than 3 s), {} refused.\n",
        BEARING_SIGMA_RAD.to_degrees(),
        totals.runs,
        totals.missed_ta,
        totals.missed_ra,
        totals.false_ta,
        totals.false_ra,
        totals.wrong_sense,
        totals.interrupted_ra,
        totals.refused,
    );
    s.push_str(&noise.to_markdown());
    let _ = writeln!(
        s,
        "\nThe false RAs are on the passes beyond the HMD threshold: the HMD filter needs the range \
         acceleration above DO-185B's noise-scaled threshold (≈ 0.7 m/s² with 15 m range noise); at 500 kt \
         with 0.8 NM offset the RA range test passes at r ≈ 6.3 km where r̈ ≈ 0.58 m/s², so many runs get an \
         RA that the continuing-threat filter drops once the range projection and the bearing track's lower \
         bound both put the miss beyond 1.05·DMOD (`tests/it/tcas/encounter_suite.rs` checks each is one RA, \
         ends within 20 s and before the closest approach). The 1.2 NM pass at 480 kt has r̈ ≈ 1.5 m/s² there and \
         few. The false TAs of `overtaking` are early onsets at 100 kt closure, where τ_mod is DMOD-dominated \
         and range noise moves it by seconds.\n"
    );
    let _ = writeln!(
        s,
        "## Range tracker: why the straight-path prediction\n\nThe `offset-beyond-hmd` pass (0.8 NM = 1482 m \
         abeam, 500 kt), exact ranges: the range acceleration and the miss distance it implies, from the \
         library's tracker and from a parabolic-prediction tracker with the same firmness gains and DO-185B's \
         γ/T² (`range_acceleration.md`). With the table's γ = 0.01 the parabolic r̈ lags the truth and the HMD \
         it implies is far below the true 1482 m, so the HMD filter (threshold 1019 m at SL 5) would not act.\n"
    );
    s.push_str(&acceleration.to_markdown());
    let _ = writeln!(
        s,
        "\n## Altitude tracker\n\nMode C (100 ft) and Mode S (25 ft) reports of the TCAS altitude profiles, over 20 \
         phases of the profile against the report grid (`host-tests/src/altitude_figures.rs`). Before (the \
         fixed-gain αβ tracker): a 300 ft/min climb read −40 to +908 ft/min, and 1562 ft/min 2 s after a \
         level-off from 2000 ft/min.\n"
    );
    s.push_str(&altitude.to_markdown());
    let _ = writeln!(
        s,
        "\nAt 2000 ft/min a 100 ft bin takes 3 s: 2 s after a level-off no transition can be overdue, so Mode C \
         reads the old rate in some phases (no tracker can know yet); the rate is within 300 ft/min of zero \
         once the missing transition is LATELEVEL overdue. 25 ft reports tell within a second.\n"
    );
    let _ = writeln!(
        s,
        "## Verdict\n\nOn exact inputs the trackers and logic give the published logic's timeline \
         within a scan in every type; with noise nothing is missed and no sense is wrong; false alerts are \
         limited to the two cases above, whose cause is measured, not tuned away.\n"
    );
    Ok(s)
}
