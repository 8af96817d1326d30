//! Sensitivity level selection and the TCAS II v7.1 table.

use abtrack::num::Quantity;
use abtrack::tcas::{sensitivity, OwnAircraft, SensitivityLevel, TcasError, SENSITIVITY_TABLE};
use abtrack::{Fix, Scalar};

/// SL, TA tau, RA tau, TA DMOD, RA DMOD, TA ZTHR, RA ZTHR, ALIM.
type PublishedRow = (
    u8,
    f64,
    Option<f64>,
    f64,
    Option<f64>,
    f64,
    Option<f64>,
    Option<f64>,
);

#[test]
fn table_is_the_published_tcas_ii_v7_1_table() {
    // own altitude → SL, TA tau, RA tau, TA DMOD, RA DMOD, TA ZTHR, RA ZTHR,
    // ALIM, copied from the TCAS II v7.1 table (– as None).
    #[rustfmt::skip]
    let published: [PublishedRow; 7] = [
        (2, 20.0, None, 0.30, None, 850.0, None, None),
        (3, 25.0, Some(15.0), 0.33, Some(0.20), 850.0, Some(600.0), Some(300.0)),
        (4, 30.0, Some(20.0), 0.48, Some(0.35), 850.0, Some(600.0), Some(300.0)),
        (5, 40.0, Some(25.0), 0.75, Some(0.55), 850.0, Some(600.0), Some(350.0)),
        (6, 45.0, Some(30.0), 1.00, Some(0.80), 850.0, Some(600.0), Some(400.0)),
        (7, 48.0, Some(35.0), 1.30, Some(1.10), 850.0, Some(700.0), Some(600.0)),
        (7, 48.0, Some(35.0), 1.30, Some(1.10), 1200.0, Some(800.0), Some(700.0)),
    ];
    for (row, want) in SENSITIVITY_TABLE.iter().zip(published) {
        assert_eq!(row.level.number(), want.0);
        assert_eq!(row.ta.tau_s, want.1);
        assert_eq!(row.ra.map(|r| r.tau_s), want.2);
        assert_eq!(row.ta.dmod_nm, want.3);
        assert_eq!(row.ra.map(|r| r.dmod_nm), want.4);
        assert_eq!(row.ta.zthr_ft, want.5);
        assert_eq!(row.ra.map(|r| r.zthr_ft), want.6);
        assert_eq!(row.alim_ft, want.7);
    }
}

fn level<S: Scalar>(pressure: f64, radio: Option<f64>) -> (u8, f64, Option<f64>) {
    let own = OwnAircraft {
        pressure_altitude_ft: S::from_f64_lossy(pressure),
        vertical_rate_ft_per_s: S::ZERO,
        radio_altitude_ft: radio.map(S::from_f64_lossy),
    };
    let p = sensitivity(&own).unwrap();
    (p.level.number(), p.ta.zthr_ft, p.alim_ft)
}

fn boundaries<S: Scalar>() {
    // Every band includes its lower bound: 1000 ft AGL is SL 3, 42 000 ft is
    // the high-altitude row.
    let sea = |h: f64| level::<S>(h, Some(h));
    assert_eq!(sea(0.0).0, 2);
    assert_eq!(sea(999.0).0, 2);
    assert_eq!(sea(999.9).0, 2);
    assert_eq!(sea(1000.0).0, 3);
    assert_eq!(sea(2349.0).0, 3);
    assert_eq!(sea(2350.0).0, 4);
    assert_eq!(sea(4999.0).0, 4);
    assert_eq!(sea(5000.0).0, 5);
    assert_eq!(sea(8000.0).0, 5);
    assert_eq!(sea(9999.0).0, 5);
    assert_eq!(sea(10000.0).0, 6);
    assert_eq!(sea(19999.0).0, 6);
    assert_eq!(sea(20000.0), (7, 850.0, Some(600.0)));
    assert_eq!(sea(41999.0), (7, 850.0, Some(600.0)));
    assert_eq!(sea(42000.0), (7, 1200.0, Some(700.0)));
    assert_eq!(sea(51000.0), (7, 1200.0, Some(700.0)));
    // Radio altitude governs the two AGL bands: over high terrain at 8000 ft
    // pressure altitude and 900 ft AGL the level is 2.
    assert_eq!(level::<S>(8000.0, Some(900.0)).0, 2);
    assert_eq!(level::<S>(8000.0, Some(1500.0)).0, 3);
    // Above 2350 ft AGL the pressure altitude decides.
    assert_eq!(level::<S>(8000.0, Some(3000.0)).0, 5);
    // Without a radio altitude the AGL bands are unavailable.
    assert_eq!(level::<S>(500.0, None).0, 4);
    assert_eq!(level::<S>(-300.0, None).0, 4);
}

#[test]
fn level_boundaries_in_all_types() {
    in_every_tcas_type!(boundaries);
}

#[test]
fn sl2_has_no_resolution_advisories() {
    let own = OwnAircraft::over_sea_level(500.0f64, 0.0);
    let p = sensitivity(&own).unwrap();
    assert_eq!(p.level, SensitivityLevel::Sl2);
    assert!(p.ra.is_none() && p.alim_ft.is_none());
}

#[test]
fn invalid_own_altitude_is_refused() {
    for bad in [f64::NAN, f64::INFINITY] {
        let own = OwnAircraft::over_sea_level(bad, 0.0);
        assert_eq!(sensitivity(&own), Err(TcasError::InvalidInput));
        let own = OwnAircraft {
            pressure_altitude_ft: 8000.0,
            vertical_rate_ft_per_s: 0.0,
            radio_altitude_ft: Some(bad),
        };
        assert_eq!(sensitivity(&own), Err(TcasError::InvalidInput));
    }
    let own = OwnAircraft::over_sea_level(Fix::MAX, Fix::ZERO);
    assert_eq!(sensitivity(&own), Err(TcasError::InvalidInput));
}
