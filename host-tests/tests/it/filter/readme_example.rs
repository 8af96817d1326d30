//! The library example of docs/library.md ("A first look"), compiled and
//! run so the documentation cannot drift from the API;
//! `readme_shows_this_example` fails when that copy differs from this one.

use abtrack::filter::auto::{AutoFilter, AutoInterval, AutoUpdate};
use abtrack::filter::UpdateOutcome;
use abtrack::gain::{AnySchedule, AutoConfig, AutoGains, ScheduleSpec, ScheduledFilter};
use abtrack::{Cartesian, FilterError, Fix, GainError, Gains, Quantity};

#[test]
fn readme_example() -> Result<(), Box<dyn std::error::Error>> {
    // --- README example begins ---
    // Gains are checked against the stability triangle when they are made
    // (Al-Wagih & Abdulla eqs. 12-14): 2α + β < 4 fails here.
    assert_eq!(
        Gains::<Fix>::alpha_beta_f64(1.5, 1.2),
        Err(GainError::BetaTooLarge)
    );
    let gains = Gains::<Fix>::alpha_beta_f64(0.5, 0.3)?;

    // A 2-D αβ filter in Q32.32 fixed point (no FPU needed); 2 kinematic
    // states per axis, 2 axes. Two-point initialisation, then filtering.
    let mut filter: Cartesian<Fix, 2, 2> = Cartesian::new();
    let one_second = Fix::try_from_f64(1.0)?;
    for z in [[0.0, 0.0], [10.0, 5.0], [20.5, 9.8]] {
        let z = [Fix::try_from_f64(z[0])?, Fix::try_from_f64(z[1])?];
        if let [UpdateOutcome::Filtered(x), _] = filter.update(z, one_second, &gains)? {
            // Prediction 20 m, residual 0.5 m: x = 20 + 0.5·0.5, v = 10 + 0.3·0.5/1
            // (Al-Wagih & Abdulla eqs. 3-8).
            assert_eq!(x.predicted.to_f64(), 20.0);
            assert_eq!(x.residual.to_f64(), 0.5);
        }
    }
    assert_eq!(filter.position()[0].to_f64(), 20.25);
    // 0.3 is not exact in Q32.32: β was rounded to a multiple of 2⁻³².
    assert!((filter.velocity()[0].to_f64() - 10.15).abs() < 1e-9);

    // Bad input is refused and leaves the state untouched.
    let before = filter;
    let nan = Fix::from_f64_lossy(f64::NAN); // a saturation sentinel, like NaN
    assert_eq!(
        filter.update([nan, nan], one_second, &gains),
        Err(FilterError::InvalidMeasurement)
    );
    assert_eq!(filter, before);

    // A gain schedule from the same spec strings `replay --schedule` takes:
    // least squares, Al-Wagih & Abdulla eq. (24), in f32.
    let spec = ScheduleSpec::parse("least-squares").map_err(|e| format!("{e:?}"))?;
    let schedule = AnySchedule::<f32, 2, 8>::from_spec(&spec).map_err(|e| format!("{e:?}"))?;
    let mut scheduled = ScheduledFilter::<f32, _, 2, 2>::new(schedule);
    for (k, z) in [[0.0f32, 0.0], [10.0, 5.0], [20.5, 9.8]]
        .into_iter()
        .enumerate()
    {
        let update = scheduled.update(z, 1.0).map_err(|e| format!("{e:?}"))?;
        if k == 2 {
            // n = 3: α = 2(2n−1)/(n(n+1)) = 5/6, β = 6/(n(n+1)) = 1/2.
            let used = update.gains.ok_or("no gains on the third update")?;
            assert_eq!((used[0].alpha(), used[0].beta()), (5.0 / 6.0, 0.5));
        }
    }

    // The default track's filter, `auto`: a per-axis Kalman filter written
    // as αβ gains, configured from the sensor's σ alone, its manoeuvre level
    // estimated from the innovations (docs/auto.md). For a regular report
    // rate the interval's terms are formed once (`AutoInterval`).
    let auto_gains = AutoGains::<f32, 2>::new(&AutoConfig::cartesian(50.0))?;
    let noise = auto_gains.shared_noise();
    let four_seconds = AutoInterval::<f32>::new(4.0)?;
    let mut auto = AutoFilter::<f32, 2>::new();
    for k in 0..10u8 {
        let t = 4.0 * f32::from(k);
        auto.update_step(noise, [200.0 * t, -100.0 * t], &four_seconds)?;
    }
    assert_eq!(auto.velocity(), [200.0, -100.0]);
    // A report after more than 20 s starts the estimate again from it, and
    // one under 0.05 s after the last is skipped: neither refuses the input.
    assert_eq!(
        auto.update(noise, [9000.0, 0.0], 30.0)?,
        AutoUpdate::Restarted
    );
    assert_eq!(
        auto.update(noise, [9001.0, 0.0], 0.01)?,
        AutoUpdate::Skipped
    );
    // --- README example ends ---
    Ok(())
}

/// docs/library.md's ```rust block is this file's `use` lines and the body
/// between the markers (indented one level less): an edit there that is not
/// made here too fails the test command.
#[test]
fn readme_shows_this_example() {
    let readme = include_str!("../../../../docs/library.md");
    let this = include_str!("readme_example.rs");
    let shown = readme
        .split_once("```rust\n")
        .and_then(|(_, rest)| rest.split_once("```"))
        .map(|(block, _)| block)
        .expect("docs/library.md has a ```rust block");
    let uses: String = this
        .lines()
        .filter(|l| l.starts_with("use "))
        .map(|l| format!("{l}\n"))
        .collect();
    let body: String = this
        .split_once("// --- README example begins ---\n")
        .and_then(|(_, rest)| rest.split_once("    // --- README example ends ---"))
        .map(|(body, _)| body)
        .expect("markers in readme_example.rs")
        .lines()
        .map(|l| format!("{}\n", l.strip_prefix("    ").unwrap_or(l)))
        .collect();
    assert_eq!(shown, format!("{uses}\n{body}"));
}
