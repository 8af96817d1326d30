//! Sensitivity levels and their thresholds (FAA, "Introduction to TCAS II
//! Version 7.1", 2011, Table 3; DAIDALUS `TCASTable.cpp`), the altitude
//! layers that carry ALIM and ZTHR, and the level selection with the
//! hysteresis of DO-185B (transcribed in ledieuke/tcas_simulator
//! `tcasConstant.py`: `ZSL*`, `BOT`, `TOP`). See docs/tcas.md.

use super::detection::CONTINUING_HMD_CYCLES;
use super::{TcasError, METRES_PER_NAUTICAL_MILE};
use crate::num::Scalar;

/// TCAS II sensitivity level (2–7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SensitivityLevel {
    /// SL 2: TA only, below 1000 ft AGL (booklet Table 3).
    Sl2 = 2,
    /// SL 3: 1000–2350 ft AGL (booklet Table 3).
    Sl3 = 3,
    /// SL 4: 2350–5000 ft (booklet Table 3).
    Sl4 = 4,
    /// SL 5: 5000–10 000 ft (booklet Table 3).
    Sl5 = 5,
    /// SL 6: 10 000–20 000 ft (booklet Table 3).
    Sl6 = 6,
    /// SL 7: above 20 000 ft (booklet Table 3).
    Sl7 = 7,
}

impl SensitivityLevel {
    /// The level's number, 2–7.
    pub const fn number(self) -> u8 {
        self as u8
    }

    /// The level numbered `n` (2–7), if any.
    pub const fn from_number(n: u8) -> Option<Self> {
        match n {
            2 => Some(SensitivityLevel::Sl2),
            3 => Some(SensitivityLevel::Sl3),
            4 => Some(SensitivityLevel::Sl4),
            5 => Some(SensitivityLevel::Sl5),
            6 => Some(SensitivityLevel::Sl6),
            7 => Some(SensitivityLevel::Sl7),
            _ => None,
        }
    }

    /// The next level up (SL 7 stays).
    const fn up(self) -> Self {
        match self {
            SensitivityLevel::Sl2 => SensitivityLevel::Sl3,
            SensitivityLevel::Sl3 => SensitivityLevel::Sl4,
            SensitivityLevel::Sl4 => SensitivityLevel::Sl5,
            SensitivityLevel::Sl5 => SensitivityLevel::Sl6,
            SensitivityLevel::Sl6 | SensitivityLevel::Sl7 => SensitivityLevel::Sl7,
        }
    }

    /// The next level down (SL 2 stays).
    const fn down(self) -> Self {
        match self {
            SensitivityLevel::Sl2 | SensitivityLevel::Sl3 => SensitivityLevel::Sl2,
            SensitivityLevel::Sl4 => SensitivityLevel::Sl3,
            SensitivityLevel::Sl5 => SensitivityLevel::Sl4,
            SensitivityLevel::Sl6 => SensitivityLevel::Sl5,
            SensitivityLevel::Sl7 => SensitivityLevel::Sl6,
        }
    }
}

/// The altitude layer (by pressure altitude) that sets ALIM and the ZTHRs
/// (DO-185B `AL`, `ZT`, `ZT_TA` indexed by layer; FAA booklet Table 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeLayer {
    /// Below 2350 ft.
    Below2350Ft = 1,
    /// 2350–5000 ft.
    To5000Ft = 2,
    /// 5000–10 000 ft.
    To10000Ft = 3,
    /// 10 000–20 000 ft.
    To20000Ft = 4,
    /// 20 000–42 000 ft.
    To42000Ft = 5,
    /// Above 42 000 ft.
    Above42000Ft = 6,
}

impl AltitudeLayer {
    /// The layer's number, 1–6.
    pub const fn number(self) -> u8 {
        self as u8
    }

    /// The layer numbered `n` (1–6), if any.
    pub const fn from_number(n: u8) -> Option<Self> {
        match n {
            1 => Some(AltitudeLayer::Below2350Ft),
            2 => Some(AltitudeLayer::To5000Ft),
            3 => Some(AltitudeLayer::To10000Ft),
            4 => Some(AltitudeLayer::To20000Ft),
            5 => Some(AltitudeLayer::To42000Ft),
            6 => Some(AltitudeLayer::Above42000Ft),
            _ => None,
        }
    }
}

/// The thresholds of one alert type at one sensitivity level.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AlertThresholds {
    /// TAU, s: the modified-tau threshold of the range test and the
    /// vertical-tau threshold of the vertical test.
    pub tau_s: f64,
    /// DMOD, NM.
    pub dmod_nm: f64,
    /// ZTHR, ft.
    pub zthr_ft: f64,
    /// H1, NM²/s: a diverging intruder inside DMOD stays a range hit while
    /// r·ṙ ≤ H1 (DO-185B `H1TBL`, `H1TA_TBL`).
    pub h1_nm2_per_s: f64,
}

impl AlertThresholds {
    /// DMOD in metres.
    pub fn dmod_m(&self) -> f64 {
        self.dmod_nm * METRES_PER_NAUTICAL_MILE
    }

    /// H1 in m²/s.
    pub fn h1_m2_per_s(&self) -> f64 {
        self.h1_nm2_per_s * METRES_PER_NAUTICAL_MILE * METRES_PER_NAUTICAL_MILE
    }
}

/// The resolution-advisory limits beyond TAU, DMOD and ZTHR at one level.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ResolutionLimits {
    /// HMD threshold of the horizontal miss-distance filter, ft (DAIDALUS
    /// `RA_HMD`; DO-185B `HMDTHR`).
    pub hmd_ft: f64,
    /// Vertical-tau threshold while the own aircraft is level (DO-185B
    /// `TVVTT_TBL`), s.
    pub level_own_vertical_tau_s: f64,
    /// Longest tau used to project the vertical miss distance (DO-185B
    /// `TVPCTBL`), s.
    pub vmd_tau_limit_s: f64,
    /// Longest tau used to model the RA manoeuvre (DO-185B `TVPETBL`), s.
    pub model_tau_limit_s: f64,
    /// Cycles a continuing threat's HMD must exceed 1.05·DMOD, more than
    /// this, before the miss-distance filter ends its RA (DO-185B
    /// `TMIN_MDF`): 4 from SL 4 up; `None` at SL 3 (9999: never).
    pub continuing_hmd_cycles: Option<u8>,
}

impl ResolutionLimits {
    /// The HMD threshold in metres.
    pub fn hmd_m(&self) -> f64 {
        self.hmd_ft * super::METRES_PER_FOOT
    }
}

/// Everything the threat logic needs from the sensitivity level and the
/// altitude layer.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensitivityParameters {
    /// The sensitivity level (booklet Table 3).
    pub level: SensitivityLevel,
    /// The altitude layer that carries ALIM and ZTHR (booklet Table 3; DO-185B
    /// `BOT`/`TOP`).
    pub layer: AltitudeLayer,
    /// Traffic advisory thresholds.
    pub ta: AlertThresholds,
    /// Resolution advisory thresholds; `None` at SL 2 (TA only).
    pub ra: Option<AlertThresholds>,
    /// ALIM, ft: the vertical separation an RA aims for; `None` at SL 2.
    pub alim_ft: Option<f64>,
    /// The other RA limits; `None` at SL 2.
    pub resolution: Option<ResolutionLimits>,
}

/// One level's TA columns: tau (s), DMOD (NM), H1 (NM²/s).
const fn ta_columns(level: SensitivityLevel) -> (f64, f64, f64) {
    match level {
        SensitivityLevel::Sl2 => (20.0, 0.30, 0.004),
        SensitivityLevel::Sl3 => (25.0, 0.33, 0.004),
        SensitivityLevel::Sl4 => (30.0, 0.48, 0.005),
        SensitivityLevel::Sl5 => (40.0, 0.75, 0.006),
        SensitivityLevel::Sl6 => (45.0, 1.00, 0.006),
        SensitivityLevel::Sl7 => (48.0, 1.30, 0.006),
    }
}

/// One level's RA columns: tau (s), DMOD (NM), H1 (NM²/s), HMD (ft),
/// level-own vertical tau (s), VMD tau limit (s), model tau limit (s), the
/// continuing threat's HMD-filter cycles ([`ResolutionLimits`]).
type RaColumns = (f64, f64, f64, f64, f64, f64, f64, Option<u8>);

/// SL 2 has no RAs.
const fn ra_columns(level: SensitivityLevel) -> Option<RaColumns> {
    const MDF: Option<u8> = Some(CONTINUING_HMD_CYCLES);
    match level {
        SensitivityLevel::Sl2 => None,
        SensitivityLevel::Sl3 => Some((15.0, 0.20, 0.002, 1215.0, 15.0, 35.0, 25.0, None)),
        SensitivityLevel::Sl4 => Some((20.0, 0.35, 0.00278, 2126.0, 18.0, 40.0, 30.0, MDF)),
        SensitivityLevel::Sl5 => Some((25.0, 0.55, 0.00278, 3342.0, 20.0, 40.0, 30.0, MDF)),
        SensitivityLevel::Sl6 => Some((30.0, 0.80, 0.00278, 4861.0, 22.0, 45.0, 35.0, MDF)),
        SensitivityLevel::Sl7 => Some((35.0, 1.10, 0.004, 6683.0, 25.0, 48.0, 40.0, MDF)),
    }
}

/// One layer's ALIM, RA ZTHR, TA ZTHR (ft).
const fn layer_columns(layer: AltitudeLayer) -> (f64, f64, f64) {
    match layer {
        AltitudeLayer::Below2350Ft | AltitudeLayer::To5000Ft => (300.0, 600.0, 850.0),
        AltitudeLayer::To10000Ft => (350.0, 600.0, 850.0),
        AltitudeLayer::To20000Ft => (400.0, 600.0, 850.0),
        AltitudeLayer::To42000Ft => (600.0, 700.0, 850.0),
        AltitudeLayer::Above42000Ft => (700.0, 800.0, 1200.0),
    }
}

/// The parameters of a level in a layer (a `const fn` so
/// [`SENSITIVITY_TABLE`] is built from the same columns).
pub const fn parameters(level: SensitivityLevel, layer: AltitudeLayer) -> SensitivityParameters {
    let (ta_tau, ta_dmod, ta_h1) = ta_columns(level);
    let (alim, ra_zthr, ta_zthr) = layer_columns(layer);
    let ta = AlertThresholds {
        tau_s: ta_tau,
        dmod_nm: ta_dmod,
        zthr_ft: ta_zthr,
        h1_nm2_per_s: ta_h1,
    };
    match ra_columns(level) {
        None => SensitivityParameters {
            level,
            layer,
            ta,
            ra: None,
            alim_ft: None,
            resolution: None,
        },
        Some((tau, dmod, h1, hmd, level_tau, vmd_limit, model_limit, continuing_hmd_cycles)) => {
            SensitivityParameters {
                level,
                layer,
                ta,
                ra: Some(AlertThresholds {
                    tau_s: tau,
                    dmod_nm: dmod,
                    zthr_ft: ra_zthr,
                    h1_nm2_per_s: h1,
                }),
                alim_ft: Some(alim),
                resolution: Some(ResolutionLimits {
                    hmd_ft: hmd,
                    level_own_vertical_tau_s: level_tau,
                    vmd_tau_limit_s: vmd_limit,
                    model_tau_limit_s: model_limit,
                    continuing_hmd_cycles,
                }),
            }
        }
    }
}

/// The table of the FAA booklet (Table 3) for an own aircraft over terrain
/// at sea level, one row per band, in order:
///
/// | own altitude (ft) | SL | TA tau | RA tau | TA DMOD | RA DMOD | TA ZTHR | RA ZTHR | ALIM | HMD (ft) |
/// |---|---|---|---|---|---|---|---|---|---|
/// | < 1000 AGL | 2 | 20 | – | 0.30 | – | 850 | – | – | – |
/// | 1000–2350 AGL | 3 | 25 | 15 | 0.33 | 0.20 | 850 | 600 | 300 | 1215 |
/// | 2350–5000 | 4 | 30 | 20 | 0.48 | 0.35 | 850 | 600 | 300 | 2126 |
/// | 5000–10000 | 5 | 40 | 25 | 0.75 | 0.55 | 850 | 600 | 350 | 3342 |
/// | 10000–20000 | 6 | 45 | 30 | 1.00 | 0.80 | 850 | 600 | 400 | 4861 |
/// | 20000–42000 | 7 | 48 | 35 | 1.30 | 1.10 | 850 | 700 | 600 | 6683 |
/// | above 42000 | 7 | 48 | 35 | 1.30 | 1.10 | 1200 | 800 | 700 | 6683 |
///
/// (tau s, DMOD NM, ZTHR and ALIM ft; HMD from DAIDALUS `RA_HMD`).
pub const SENSITIVITY_TABLE: [SensitivityParameters; 7] = [
    parameters(SensitivityLevel::Sl2, AltitudeLayer::Below2350Ft),
    parameters(SensitivityLevel::Sl3, AltitudeLayer::Below2350Ft),
    parameters(SensitivityLevel::Sl4, AltitudeLayer::To5000Ft),
    parameters(SensitivityLevel::Sl5, AltitudeLayer::To10000Ft),
    parameters(SensitivityLevel::Sl6, AltitudeLayer::To20000Ft),
    parameters(SensitivityLevel::Sl7, AltitudeLayer::To42000Ft),
    parameters(SensitivityLevel::Sl7, AltitudeLayer::Above42000Ft),
];

/// Lower bounds of the table's bands, ft: radio altitude for the first two
/// (AGL), pressure altitude for the rest.
pub const SL3_RADIO_ALTITUDE_FT: f64 = 1000.0;
/// SL 4 from 2350 ft radio altitude (booklet Table 3).
pub const SL4_RADIO_ALTITUDE_FT: f64 = 2350.0;
/// SL 5 from 5000 ft pressure altitude (booklet Table 3).
pub const SL5_PRESSURE_ALTITUDE_FT: f64 = 5000.0;
/// SL 6 from 10 000 ft pressure altitude (booklet Table 3).
pub const SL6_PRESSURE_ALTITUDE_FT: f64 = 10000.0;
/// SL 7 from 20 000 ft pressure altitude (booklet Table 3).
pub const SL7_PRESSURE_ALTITUDE_FT: f64 = 20000.0;
/// The SL 7 layer above 42 000 ft pressure altitude, with its larger ZTHR
/// and ALIM (booklet Table 3).
pub const SL7_HIGH_PRESSURE_ALTITUDE_FT: f64 = 42000.0;

/// Level hysteresis (DO-185B `ZSL2TO3` … `ZSL7TO6`), ft: a level changes
/// only once the altitude is this far past the band boundary. Up-switches
/// first, then down-switches: (from, up at, down at). Radio altitude for
/// SL 2–4, pressure altitude above.
pub const LEVEL_UP_FT: [f64; 5] = [1100.0, 2550.0, 5500.0, 10500.0, 20500.0];
/// See [`LEVEL_UP_FT`]: the level below SL 3..=7 is taken at or below these.
pub const LEVEL_DOWN_FT: [f64; 5] = [900.0, 2150.0, 4500.0, 9500.0, 19500.0];
/// Layer hysteresis (DO-185B `TOP` for layers 1–5, `BOT` for layers 2–6), ft
/// of pressure altitude.
pub const LAYER_UP_FT: [f64; 5] = [2550.0, 5500.0, 10500.0, 20500.0, 42500.0];
/// See [`LAYER_UP_FT`].
pub const LAYER_DOWN_FT: [f64; 5] = [2150.0, 4500.0, 9500.0, 19500.0, 41500.0];

/// The own aircraft.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct OwnAircraft<S> {
    /// Pressure altitude, ft.
    pub pressure_altitude_ft: S,
    /// Vertical rate, ft/s (positive climbing).
    pub vertical_rate_ft_per_s: S,
    /// Radio (height above ground) altitude, ft; `None` when not available
    /// or above the radio altimeter's range.
    pub radio_altitude_ft: Option<S>,
}

impl<S: Scalar> OwnAircraft<S> {
    /// An own aircraft over terrain at sea level: the pressure altitude is
    /// also the height above ground (for tools given a single altitude).
    pub fn over_sea_level(altitude_ft: S, vertical_rate_ft_per_s: S) -> Self {
        OwnAircraft {
            pressure_altitude_ft: altitude_ft,
            vertical_rate_ft_per_s,
            radio_altitude_ft: Some(altitude_ft),
        }
    }

    pub(crate) fn is_valid(&self) -> bool {
        self.pressure_altitude_ft.is_valid()
            && self.vertical_rate_ft_per_s.is_valid()
            && self.radio_altitude_ft.is_none_or(|h| h.is_valid())
    }
}

// Inline, so that the bound (a constant at every call) is converted at
// compile time.
#[inline]
fn below<S: Scalar>(v: S, bound: f64) -> bool {
    v < S::from_f64_lossy(bound)
}

/// The band of the booklet table, without hysteresis: radio altitude
/// < 1000 ft → SL 2, < 2350 ft → SL 3; otherwise, by pressure altitude,
/// < 5000 → SL 4, < 10 000 → SL 5, < 20 000 → SL 6, else SL 7. Every band
/// includes its lower bound (as "< 1000 ft" puts 1000 ft in SL 3; DAIDALUS
/// puts the bound in the lower band). Without a radio altitude the two AGL
/// bands cannot be chosen and the lowest level is SL 4.
fn band_level<S: Scalar>(own: &OwnAircraft<S>) -> SensitivityLevel {
    match own.radio_altitude_ft {
        Some(h) if below(h, SL3_RADIO_ALTITUDE_FT) => SensitivityLevel::Sl2,
        Some(h) if below(h, SL4_RADIO_ALTITUDE_FT) => SensitivityLevel::Sl3,
        _ => {
            let p = own.pressure_altitude_ft;
            if below(p, SL5_PRESSURE_ALTITUDE_FT) {
                SensitivityLevel::Sl4
            } else if below(p, SL6_PRESSURE_ALTITUDE_FT) {
                SensitivityLevel::Sl5
            } else if below(p, SL7_PRESSURE_ALTITUDE_FT) {
                SensitivityLevel::Sl6
            } else {
                SensitivityLevel::Sl7
            }
        }
    }
}

/// The layer of the pressure altitude, without hysteresis.
fn band_layer<S: Scalar>(pressure_altitude_ft: S) -> AltitudeLayer {
    let p = pressure_altitude_ft;
    if below(p, SL4_RADIO_ALTITUDE_FT) {
        AltitudeLayer::Below2350Ft
    } else if below(p, SL5_PRESSURE_ALTITUDE_FT) {
        AltitudeLayer::To5000Ft
    } else if below(p, SL6_PRESSURE_ALTITUDE_FT) {
        AltitudeLayer::To10000Ft
    } else if below(p, SL7_PRESSURE_ALTITUDE_FT) {
        AltitudeLayer::To20000Ft
    } else if below(p, SL7_HIGH_PRESSURE_ALTITUDE_FT) {
        AltitudeLayer::To42000Ft
    } else {
        AltitudeLayer::Above42000Ft
    }
}

/// Selects the sensitivity level and layer from the own aircraft's
/// altitudes, without hysteresis (the booklet's bands; see
/// [`SensitivitySelector`] for the switching the logic uses).
pub fn sensitivity<S: Scalar>(own: &OwnAircraft<S>) -> Result<SensitivityParameters, TcasError> {
    if !own.is_valid() {
        return Err(TcasError::InvalidInput);
    }
    Ok(parameters(
        band_level(own),
        band_layer(own.pressure_altitude_ft),
    ))
}

/// Level and layer selection with DO-185B's hysteresis ([`LEVEL_UP_FT`],
/// [`LEVEL_DOWN_FT`], [`LAYER_UP_FT`], [`LAYER_DOWN_FT`]): the first call
/// takes the booklet band; later calls move a level (or layer) only when
/// the altitude is past the boundary by the hysteresis margin. SL 2 ↔ 3 ↔ 4
/// follow the radio altitude (SL 3 → 4 also happens when it is lost, by
/// pressure altitude), SL 4 ↔ 5 ↔ 6 ↔ 7 the pressure altitude (the booklet's
/// bands; DO-185B's `auto_sl4to7` keeps SL 4 while a radio altitude is
/// valid, which this reading does not).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensitivitySelector {
    /// The level and layer numbers selected last; 0 before the first call
    /// (all-zero bytes: a `static` holding it goes to `.bss`).
    current: (u8, u8),
}

impl SensitivitySelector {
    /// A selector with no level yet: the first call takes the booklet band.
    pub const fn new() -> Self {
        SensitivitySelector { current: (0, 0) }
    }

    /// The level and layer selected last, if any.
    pub fn current(&self) -> Option<(SensitivityLevel, AltitudeLayer)> {
        let (level, layer) = self.current;
        Some((
            SensitivityLevel::from_number(level)?,
            AltitudeLayer::from_number(layer)?,
        ))
    }

    /// This cycle's parameters.
    pub fn select<S: Scalar>(
        &mut self,
        own: &OwnAircraft<S>,
    ) -> Result<SensitivityParameters, TcasError> {
        if !own.is_valid() {
            return Err(TcasError::InvalidInput);
        }
        let (level, layer) = match self.current() {
            None => (band_level(own), band_layer(own.pressure_altitude_ft)),
            Some((level, layer)) => (
                next_level(level, own),
                next_layer(layer, own.pressure_altitude_ft),
            ),
        };
        self.current = (level.number(), layer.number());
        Ok(parameters(level, layer))
    }
}

/// Which altitude decides the boundary above `level` (SL 2 → 3 and 3 → 4:
/// radio; SL 3 → 4 falls back to pressure without a radio altitude).
fn deciding_altitude<S: Scalar>(level: SensitivityLevel, own: &OwnAircraft<S>) -> S {
    match (level, own.radio_altitude_ft) {
        (SensitivityLevel::Sl2 | SensitivityLevel::Sl3, Some(radio)) => radio,
        _ => own.pressure_altitude_ft,
    }
}

/// 0 for SL 2 … 5 for SL 7.
const fn level_index(level: SensitivityLevel) -> usize {
    match level {
        SensitivityLevel::Sl2 => 0,
        SensitivityLevel::Sl3 => 1,
        SensitivityLevel::Sl4 => 2,
        SensitivityLevel::Sl5 => 3,
        SensitivityLevel::Sl6 => 4,
        SensitivityLevel::Sl7 => 5,
    }
}

fn next_level<S: Scalar>(mut level: SensitivityLevel, own: &OwnAircraft<S>) -> SensitivityLevel {
    // At most five steps either way; each step is one band.
    for _ in 0..5 {
        let i = level_index(level);
        let up = LEVEL_UP_FT.get(i).copied();
        if let Some(up) = up {
            let h = deciding_altitude(level, own);
            // Without a radio altitude SL 2 cannot be held.
            let lost = level == SensitivityLevel::Sl2 && own.radio_altitude_ft.is_none();
            if lost || h >= S::from_f64_lossy(up) {
                level = level.up();
                continue;
            }
        }
        let down = i.checked_sub(1).and_then(|j| LEVEL_DOWN_FT.get(j)).copied();
        if let Some(down) = down {
            let below_level = level.down();
            let h = match (below_level, own.radio_altitude_ft) {
                // Down into SL 2 or 3 needs the radio altitude.
                (SensitivityLevel::Sl2 | SensitivityLevel::Sl3, None) => break,
                (SensitivityLevel::Sl2 | SensitivityLevel::Sl3, Some(radio)) => radio,
                _ => own.pressure_altitude_ft,
            };
            if h <= S::from_f64_lossy(down) {
                level = below_level;
                continue;
            }
        }
        break;
    }
    level
}

fn next_layer<S: Scalar>(layer: AltitudeLayer, pressure_altitude_ft: S) -> AltitudeLayer {
    let mut n = layer.number();
    for _ in 0..5 {
        let i = usize::from(n.saturating_sub(1));
        if let Some(&up) = LAYER_UP_FT.get(i) {
            if pressure_altitude_ft >= S::from_f64_lossy(up) {
                n = n.saturating_add(1);
                continue;
            }
        }
        let down = i.checked_sub(1).and_then(|j| LAYER_DOWN_FT.get(j)).copied();
        if let Some(down) = down {
            if pressure_altitude_ft <= S::from_f64_lossy(down) {
                n = n.saturating_sub(1);
                continue;
            }
        }
        break;
    }
    // n stays within 1..=6 (one step a pass from a valid layer).
    AltitudeLayer::from_number(n.clamp(1, 6)).unwrap_or(AltitudeLayer::Above42000Ft)
}
