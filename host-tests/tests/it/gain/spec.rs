//! The `--schedule NAME[:key=value,...]` spec strings.

use super::support;

use abtrack::bank::{BankConfig, CartesianBank};
use abtrack::gain::al_wagih::{
    FixedAlphaConfig, FixedConfig, LeastSquaresConfig, LinearCombinationConfig, MovingWindowConfig,
};
use abtrack::gain::li::LiImprovedConfig;
use abtrack::gain::liu::{
    AdaptiveSwitchConfig, ResidualAccumulationConfig, ScanCountAdjustedConfig,
};
use abtrack::gain::spec::{ScheduleSpec, SpecError, SpecErrorKind, SCHEDULES};
use abtrack::gain::{AnySchedule, ConfigError};
use proptest::prelude::*;

fn parse(s: &str) -> Result<ScheduleSpec, SpecError> {
    ScheduleSpec::parse(s)
}

#[test]
fn issue_examples_parse() {
    assert_eq!(
        parse("m1:alpha=0.05").unwrap(),
        ScheduleSpec::FixedAlpha(FixedAlphaConfig { alpha: 0.05 })
    );
    assert_eq!(
        parse("least-squares").unwrap(),
        ScheduleSpec::LeastSquares(LeastSquaresConfig::DEFAULT)
    );
    assert_eq!(
        parse("bank:k=8").unwrap(),
        ScheduleSpec::Bank(BankConfig {
            k: 8,
            ..BankConfig::DEFAULT
        })
    );
    assert_eq!(
        parse("liu-adaptive").unwrap(),
        ScheduleSpec::AdaptiveSwitch(AdaptiveSwitchConfig::DEFAULT)
    );
    assert_eq!(parse("tcas-firmness").unwrap(), ScheduleSpec::Firmness);
    assert_eq!(
        parse("m3").unwrap(),
        ScheduleSpec::LinearCombination(LinearCombinationConfig::DEFAULT)
    );
    assert_eq!(
        parse("m4").unwrap(),
        ScheduleSpec::MovingWindow(MovingWindowConfig::DEFAULT)
    );
    assert_eq!(
        parse("li-improved").unwrap(),
        ScheduleSpec::LiImproved(LiImprovedConfig::DEFAULT)
    );
    assert_eq!(
        parse("liu-count-adjusted").unwrap(),
        ScheduleSpec::ScanCountAdjusted(ScanCountAdjustedConfig::DEFAULT)
    );
    assert_eq!(
        parse("liu-residual").unwrap(),
        ScheduleSpec::ResidualAccumulation(ResidualAccumulationConfig::DEFAULT)
    );
}

#[test]
fn aliases_and_paper_defaults() {
    // Liu 2.1.1 is Al-Wagih's M2; Liu 2.1.3 is fixed 0.5 / 0.3.
    assert_eq!(parse("liu-count").unwrap(), parse("least-squares").unwrap());
    assert_eq!(parse("m2").unwrap(), parse("least-squares").unwrap());
    assert_eq!(parse("m5:k=4").unwrap(), parse("bank:k=4").unwrap());
    assert_eq!(
        parse("liu-fixed").unwrap(),
        ScheduleSpec::Fixed(FixedConfig::LIU)
    );
    assert_eq!(
        parse("liu-fixed").unwrap(),
        parse("fixed:alpha=0.5,beta=0.3").unwrap()
    );
    // The papers' values are the defaults.
    let ScheduleSpec::AdaptiveSwitch(c) = parse("liu-adaptive").unwrap() else {
        unreachable!()
    };
    assert_eq!((c.limit, c.alpha, c.beta), (19.0, 0.5, 0.3));
    assert_eq!((c.residual.n, c.residual.sigma_m2), (3, 25.0));
    let ScheduleSpec::ScanCountAdjusted(c) = parse("liu-count-adjusted").unwrap() else {
        unreachable!()
    };
    assert_eq!(c.threshold, 70.0);
}

#[test]
fn parameters_override_defaults() {
    let s = parse("m4:window=10,steps=19,min=0.05,max=0.95,alpha0=0.3").unwrap();
    assert_eq!(
        s,
        ScheduleSpec::MovingWindow(MovingWindowConfig {
            alpha0: 0.3,
            alpha_min: 0.05,
            alpha_max: 0.95,
            steps: 19,
            window: 10,
        })
    );
    let s = parse("fixed:alpha=0.83,beta=0.5,gamma=0.16").unwrap();
    assert_eq!(
        s,
        ScheduleSpec::Fixed(FixedConfig {
            alpha: 0.83,
            beta: 0.5,
            gamma: Some(0.16)
        })
    );
    let s = parse("li-improved:r=2.5,range-error=10,bearing-error=0.001,k-max=500").unwrap();
    assert_eq!(
        s,
        ScheduleSpec::LiImproved(LiImprovedConfig {
            max_ratio: 2.5,
            range_error: 10.0,
            bearing_error: 0.001,
            k_max: 500
        })
    );
}

fn kind(s: &str) -> (SpecErrorKind, usize) {
    let e = parse(s).unwrap_err();
    (e.kind, e.offset)
}

#[test]
fn errors_say_what_and_where() {
    assert_eq!(kind(""), (SpecErrorKind::Empty, 0));
    assert_eq!(kind(":alpha=1"), (SpecErrorKind::Empty, 0));
    assert_eq!(kind("m6"), (SpecErrorKind::UnknownSchedule, 0));
    assert_eq!(kind("M1"), (SpecErrorKind::UnknownSchedule, 0));
    assert_eq!(kind("m1:"), (SpecErrorKind::EmptyParameter, 3));
    assert_eq!(
        kind("m4:steps=3,,window=4"),
        (SpecErrorKind::EmptyParameter, 11)
    );
    assert_eq!(kind("m1:alpha"), (SpecErrorKind::MissingValue, 3));
    assert_eq!(kind("m1:beta=0.1"), (SpecErrorKind::UnknownParameter, 3));
    assert_eq!(
        kind("tcas-firmness:k=1"),
        (SpecErrorKind::UnknownParameter, 14)
    );
    assert_eq!(
        kind("m1:alpha=0.1,alpha=0.2"),
        (SpecErrorKind::DuplicateParameter, 13)
    );
    // The offset of a bad value is the value's.
    assert_eq!(kind("m1:alpha=x"), (SpecErrorKind::InvalidNumber, 9));
    assert_eq!(kind("bank:k=-1"), (SpecErrorKind::InvalidNumber, 7));
    assert_eq!(kind("bank:k=2.5"), (SpecErrorKind::InvalidNumber, 7));
    assert_eq!(
        kind("fixed:alpha=0.5"),
        (SpecErrorKind::MissingParameter { parameter: "beta" }, 15)
    );
    // Out-of-range values point at their key.
    assert_eq!(
        kind("m1:alpha=1.5"),
        (
            SpecErrorKind::Config(ConfigError::OutOfRange { parameter: "alpha" }),
            3
        )
    );
    assert_eq!(
        kind("m1:alpha=nan"),
        (
            SpecErrorKind::Config(ConfigError::OutOfRange { parameter: "alpha" }),
            3
        )
    );
    assert_eq!(
        kind("m4:min=0.5,max=0.2"),
        (
            SpecErrorKind::Config(ConfigError::OutOfRange { parameter: "max" }),
            11
        )
    );
    // Outside the stability triangle: 2·1.5 + 1.2 = 4.2 ≥ 4.
    assert_eq!(
        kind("fixed:alpha=1.5,beta=1.2"),
        (
            SpecErrorKind::Config(ConfigError::OutOfRange { parameter: "gains" }),
            0
        )
    );
    assert!(matches!(
        kind("liu-residual:n=0").0,
        SpecErrorKind::Config(_)
    ));
    assert!(matches!(
        kind("least-squares:n-max=2").0,
        SpecErrorKind::Config(_)
    ));
    // Display names the problem and the place.
    let msg = parse("m1:alpha=x").unwrap_err().to_string();
    assert!(
        msg.contains("not a valid number") && msg.contains("byte 9"),
        "{msg}"
    );
}

#[test]
fn capacities_are_checked_when_building() {
    let spec = parse("m4:window=20").unwrap();
    assert_eq!(
        AnySchedule::<f64, 2, 16>::from_spec(&spec),
        Err(ConfigError::ExceedsCapacity {
            parameter: "window",
            capacity: 16
        })
    );
    assert!(AnySchedule::<f64, 2, 32>::from_spec(&spec).is_ok());
    assert_eq!(
        AnySchedule::<f64, 2, 16>::from_spec(&parse("bank").unwrap()),
        Err(ConfigError::NotASchedule)
    );
    let ScheduleSpec::Bank(c) = parse("bank:k=8").unwrap() else {
        unreachable!()
    };
    assert!(CartesianBank::<f32, 8, 2>::from_config(&c).is_ok());
    assert!(CartesianBank::<f32, 4, 2>::from_config(&c).is_err());
}

#[test]
fn every_listed_name_parses_and_builds() {
    for info in SCHEDULES {
        for name in info.names {
            if *name == "fixed" {
                // The schedules without defaults.
                assert_eq!(
                    kind(name).0,
                    SpecErrorKind::MissingParameter { parameter: "alpha" }
                );
                continue;
            }
            if *name == "auto" {
                assert_eq!(
                    kind(name).0,
                    SpecErrorKind::MissingParameter { parameter: "sigma" }
                );
                continue;
            }
            let spec = parse(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            match spec {
                ScheduleSpec::Bank(c) => {
                    CartesianBank::<f64, 8, 2>::from_config(&c).unwrap();
                }
                _ => {
                    AnySchedule::<abtrack::Fix, 2, 16>::from_spec(&spec).unwrap();
                }
            }
        }
    }
    for spec in support::ALL_SCHEDULES {
        parse(spec).unwrap();
    }
}

#[test]
fn display_is_canonical() {
    assert_eq!(parse("m2").unwrap().to_string(), "least-squares:n-max=1000");
    assert_eq!(parse("m1").unwrap().to_string(), "m1:alpha=0.05");
    assert_eq!(
        parse("liu-fixed").unwrap().to_string(),
        "fixed:alpha=0.5,beta=0.3"
    );
    assert_eq!(parse("tcas-firmness").unwrap().to_string(), "tcas-firmness");
    assert_eq!(
        parse("liu-adaptive").unwrap().to_string(),
        "liu-adaptive:limit=19,alpha=0.5,beta=0.3,n=3,sigma-m2=25,alpha-min=0.01"
    );
}

proptest! {
    /// Display writes a spec that parses back to the same value.
    #[test]
    fn display_round_trips(
        name in prop::sample::select(
            SCHEDULES.iter().flat_map(|i| i.names.iter().copied()).filter(|n| *n != "fixed" && *n != "auto").collect::<Vec<_>>()
        ),
        alpha in 0.001f64..1.0,
        steps in 2u16..50,
        window in 2u16..16,
    ) {
        let spec = match parse(name).unwrap() {
            ScheduleSpec::FixedAlpha(_) => ScheduleSpec::FixedAlpha(FixedAlphaConfig { alpha }),
            ScheduleSpec::MovingWindow(c) => ScheduleSpec::MovingWindow(MovingWindowConfig { alpha0: alpha, steps, window, ..c }),
            ScheduleSpec::LinearCombination(c) => ScheduleSpec::LinearCombination(LinearCombinationConfig { w: alpha, steps, window, ..c }),
            ScheduleSpec::Bank(c) => ScheduleSpec::Bank(BankConfig { k: steps, alpha_min: alpha / 2.0, ..c }),
            other => other,
        };
        let text = spec.to_string();
        prop_assert_eq!(parse(&text).unwrap(), spec, "{}", text);
    }

    /// Arbitrary text never panics the parser.
    #[test]
    fn arbitrary_text_never_panics(s in "\\PC{0,40}") {
        let _ = parse(&s);
    }

    #[test]
    fn near_miss_text_never_panics(s in "(m[0-9]|bank|liu-[a-z]{0,9}|fixed)(:[a-z0-9=.,-]{0,30})?") {
        let _ = parse(&s);
    }
}
