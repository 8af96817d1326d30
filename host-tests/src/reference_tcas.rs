//! Independent f64 reference of the TCAS II v7.1 logic, written straight
//! from the public sources on *true* relative states (no trackers), for
//! the encounter suite's expected onset times, RA sense and clear of
//! conflict. Not the library's code: state vectors and squares in f64, the
//! tables copied again from the sources.
//!
//! Sources, per rule:
//! * modified tau τ_mod = (DMOD² − s·s)/(s·v) and the horizontal RA test:
//!   DAIDALUS `TCAS2D::tau_mod`, `horizontal_RA`; the 10 ft/s closure
//!   floor (`RDTHR`), the diverging test r·ṙ ≤ H1, `RMAX`: DO-185B
//!   `range_test` (ledieuke/tcas_simulator `detect.py`);
//! * the tau cap (`TAUCAP`: neither τ_mod nor the true tau rises while
//!   the intruder does not diverge, `MINTAU` = 0 when it does) and
//!   `TAURISE`: DO-185B `tau_calculation`, `range_test`;
//! * threats kept through one missed cycle and ended at the next after
//!   `TMIN` (4.5 s): DO-185B `set_up_working_list`;
//! * HMD filter: DAIDALUS `TCAS3D::cd2d_TCAS` (the straight path comes
//!   within HMD) for a new threat; DO-185B's 1.05·DMOD for more than four
//!   cycles for a continuing one;
//! * vertical tests: DO-185B `altitude_test` with the vertical miss distance
//!   (`vertical_miss_distance_calculation`), the level-own threshold
//!   (`set_detection_parameters`), `MAXZDINT`; the TA's: DAIDALUS
//!   `vertical_RA` with the TA table;
//! * TA hysteresis (`TARHYST`), minimum TA time (`MINTATIME`), the 15 500 ft
//!   cap (`ABOVNMC`), proximate traffic (`PROXR`, `PROXA`): DO-185B
//!   constants;
//! * tables: DAIDALUS `TCASTable.cpp` (TAU, DMOD, ZTHR, HMD), DO-185B
//!   `tcasConstant.py` (H1, TVVTT, TVPC, TVPE, ALIM by layer);
//! * resolution: the FAA booklet's two steps (sense by modelled separation
//!   at CPA, non-crossing preferred if it gives ALIM; then the weakest
//!   strength giving ALIM), DO-185B's manoeuvre model (`TV1` 5 s, `VACCEL`
//!   8 ft/s², `CLMRT` 1500 ft/min, projection at both taus capped at TVPE);
//!   CoC when no RA threat is left.
//!
//! Own altitude is the pressure altitude over sea-level terrain, so SL 2 and
//! 3 never arise in the suite (own altitudes 8000 and 20 000 ft); the
//! sensitivity level is taken from the booklet's bands.

const NM: f64 = 1852.0;
const FT: f64 = 0.3048;
const RDTHR_M_S: f64 = 10.0 * FT;
const RMAX_M: f64 = 12.0 * NM;
const ZDTHR_FT_S: f64 = -1.0;
const MAXZDINT_FT_S: f64 = 10000.0 / 60.0;
const OLEV_FT_S: f64 = 600.0 / 60.0;
const TARHYST_M: f64 = 0.2 * NM;
const MINTATIME_S: f64 = 8.0;
const ABOVNMC_FT: f64 = 15500.0;
const PROXR_M: f64 = 6.0 * NM;
const PROXA_FT: f64 = 1200.0;
const HMDMULT: f64 = 1.05;
/// DO-185B `TMIN_MDF` by sensitivity level (9999 at SL 3: never).
const TMIN_MDF: [u32; 8] = [0, 0, 0, 9999, 4, 4, 4, 4];
const MDF_TAU_LIMIT_S: f64 = 35.0;
/// DO-185B `TMIN`: a threat's second missed cycle ends it only after this.
const TMIN_S: f64 = 4.5;
/// DO-185B `taurise_thr` and `NAFRANGE`.
const TAURISE_CYCLES: u32 = 3;
const NAFRANGE_M: f64 = 1.7 * NM;
const TV1_S: f64 = 5.0;
const VACCEL_FT_S2: f64 = 8.0;
const CLMRT_FT_S: f64 = 1500.0 / 60.0;
const MAXDRATE_FT_S: f64 = 4400.0 / 60.0;
const CROSSTHR_FT: f64 = 100.0;

/// One level's thresholds, in SI/ft/s.
#[derive(Debug, Clone, Copy)]
pub struct Level {
    pub sl: u8,
    pub ta_tau: f64,
    pub ta_dmod_m: f64,
    pub ta_zthr_ft: f64,
    pub ta_h1: f64,
    /// RA: tau, DMOD (m), ZTHR (ft), H1 (m²/s), HMD (m), TVVTT, TVPC, TVPE, ALIM.
    pub ra: Option<RaLevel>,
}

#[derive(Debug, Clone, Copy)]
pub struct RaLevel {
    pub tau: f64,
    pub dmod_m: f64,
    pub zthr_ft: f64,
    pub h1: f64,
    pub hmd_m: f64,
    pub tvvtt: f64,
    pub tvpc: f64,
    pub tvpe: f64,
    pub alim_ft: f64,
}

/// The booklet's band for an own aircraft over sea-level terrain.
pub fn level_for(altitude_ft: f64) -> Level {
    // SL, TA tau, TA DMOD NM, TA H1 NM²/s.
    let (sl, ta_tau, ta_dmod, ta_h1) = if altitude_ft < 1000.0 {
        (2, 20.0, 0.30, 0.004)
    } else if altitude_ft < 2350.0 {
        (3, 25.0, 0.33, 0.004)
    } else if altitude_ft < 5000.0 {
        (4, 30.0, 0.48, 0.005)
    } else if altitude_ft < 10000.0 {
        (5, 40.0, 0.75, 0.006)
    } else if altitude_ft < 20000.0 {
        (6, 45.0, 1.0, 0.006)
    } else {
        (7, 48.0, 1.3, 0.006)
    };
    // ALIM, RA ZTHR, TA ZTHR by layer.
    let (alim, ra_zthr, ta_zthr) = if altitude_ft < 5000.0 {
        (300.0, 600.0, 850.0)
    } else if altitude_ft < 10000.0 {
        (350.0, 600.0, 850.0)
    } else if altitude_ft < 20000.0 {
        (400.0, 600.0, 850.0)
    } else if altitude_ft < 42000.0 {
        (600.0, 700.0, 850.0)
    } else {
        (700.0, 800.0, 1200.0)
    };
    // RA tau, DMOD NM, H1 NM²/s, HMD ft, TVVTT, TVPC, TVPE.
    let ra = match sl {
        3 => Some((15.0, 0.2, 0.002, 1215.0, 15.0, 35.0, 25.0)),
        4 => Some((20.0, 0.35, 0.00278, 2126.0, 18.0, 40.0, 30.0)),
        5 => Some((25.0, 0.55, 0.00278, 3342.0, 20.0, 40.0, 30.0)),
        6 => Some((30.0, 0.8, 0.00278, 4861.0, 22.0, 45.0, 35.0)),
        7 => Some((35.0, 1.1, 0.004, 6683.0, 25.0, 48.0, 40.0)),
        _ => None,
    };
    Level {
        sl,
        ta_tau,
        ta_dmod_m: ta_dmod * NM,
        ta_zthr_ft: ta_zthr,
        ta_h1: ta_h1 * NM * NM,
        ra: ra.map(|(tau, dmod, h1, hmd, tvvtt, tvpc, tvpe)| RaLevel {
            tau,
            dmod_m: dmod * NM,
            zthr_ft: ra_zthr,
            h1: h1 * NM * NM,
            hmd_m: hmd * FT,
            tvvtt,
            tvpc,
            tvpe,
            alim_ft: alim,
        }),
    }
}

/// The own aircraft's true state.
#[derive(Debug, Clone, Copy)]
pub struct Own {
    pub altitude_ft: f64,
    pub rate_ft_per_s: f64,
}

/// An intruder's true state relative to the own aircraft.
#[derive(Debug, Clone, Copy)]
pub struct Relative {
    /// Intruder minus own position, m.
    pub s: [f64; 2],
    /// Intruder minus own velocity, m/s.
    pub v: [f64; 2],
    /// Intruder altitude (ft) and rate (ft/s), if it reports altitude.
    pub altitude: Option<(f64, f64)>,
}

/// Advisory level of one intruder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Alert {
    None,
    Proximate,
    Ta,
    Ra,
}

/// RA sense, up or down.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sense {
    Up,
    Down,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// r, ṙ from the state vector (ṙ = 0 at r = 0).
pub fn range_and_rate(s: [f64; 2], v: [f64; 2]) -> (f64, f64) {
    let r = dot(s, s).sqrt();
    let rdot = if r > 0.0 { dot(s, v) / r } else { 0.0 };
    (r, rdot)
}

/// The range test: (r, ṙ, DMOD, TAU, H1, max range).
fn range_test(r: f64, rdot: f64, dmod: f64, tau: f64, h1: f64, rmax: f64) -> bool {
    if rdot > RDTHR_M_S {
        return r <= dmod && r * rdot <= h1;
    }
    if r > rmax {
        return false;
    }
    if r <= dmod {
        return true;
    }
    // τ_mod = (DMOD² − r²)/(r·ṙ) with ṙ floored at −RDTHR.
    let rdot_floored = rdot.min(-RDTHR_M_S);
    let tau_mod = (dmod * dmod - r * r) / (r * rdot_floored);
    tau_mod < tau
}

fn true_tau(r: f64, rdot: f64) -> f64 {
    r / (-rdot).max(RDTHR_M_S)
}

fn mod_tau(r: f64, rdot: f64, dmod: f64) -> f64 {
    if r <= dmod {
        0.0
    } else {
        (r * r - dmod * dmod) / (r * (-rdot).max(RDTHR_M_S))
    }
}

/// Straight-line miss distance |s × v|/|v| (r when v = 0).
pub fn line_miss(s: [f64; 2], v: [f64; 2]) -> f64 {
    let speed = dot(v, v).sqrt();
    if speed == 0.0 {
        dot(s, s).sqrt()
    } else {
        cross(s, v).abs() / speed
    }
}

/// One intruder's memory.
#[derive(Debug, Clone, Copy, Default)]
struct Memory {
    ta_since: Option<f64>,
    /// An RA threat: whether it missed the hit tests last cycle (DO-185B
    /// `KHIT` 1, else 3) and the time since it became one (`TCUR − TCMD`).
    threat: Option<(bool, f64)>,
    /// The capped τ_mod and true tau (`TAUR`, `TRTRU`), the last uncapped
    /// true tau (`TRTUN`) and the cycles it has not fallen (`TAURISE`).
    tau_cap: Option<(f64, f64)>,
    last_true_tau: f64,
    tau_rise: u32,
    hmd_count: u32,
}

/// The reference's active RA.
#[derive(Debug, Clone, Copy)]
pub struct Ra {
    pub sense: Sense,
    /// The strength chosen at onset: `false` negative (preventive or level
    /// off), `true` positive (climb or descend).
    pub positive: bool,
    pub crossing: bool,
}

/// One cycle's decision.
#[derive(Debug, Clone)]
pub struct Step {
    pub alerts: Vec<Alert>,
    pub ra: Option<Ra>,
    pub clear_of_conflict: bool,
}

/// The reference logic over several intruders.
#[derive(Debug, Clone)]
pub struct Reference {
    memory: Vec<Memory>,
    ra: Option<Ra>,
}

/// Own altitude at t s: hold `rate` for `delay`, then accelerate at VACCEL
/// to `goal` (DO-185B's projection written out piece by piece).
fn own_altitude_at(t: f64, z: f64, rate: f64, goal: f64, delay: f64) -> f64 {
    if t <= delay {
        return z + rate * t;
    }
    let z1 = z + rate * delay;
    let ramp = (goal - rate).abs() / VACCEL_FT_S2;
    let a = if goal >= rate {
        VACCEL_FT_S2
    } else {
        -VACCEL_FT_S2
    };
    let u = t - delay;
    if u <= ramp {
        z1 + rate * u + 0.5 * a * u * u
    } else {
        z1 + rate * ramp + 0.5 * a * ramp * ramp + goal * (u - ramp)
    }
}

/// A threat for the resolution step: intruder altitude and rate, both taus
/// (capped at TVPE).
#[derive(Debug, Clone, Copy)]
struct Threat {
    z: f64,
    zdot: f64,
    t1: f64,
    t2: f64,
}

fn separation(own: &Own, th: &Threat, sense: Sense, goal: f64) -> f64 {
    [th.t1, th.t2]
        .iter()
        .map(|&t| {
            let o = own_altitude_at(t, own.altitude_ft, own.rate_ft_per_s, goal, TV1_S);
            let i = th.z + th.zdot * t;
            match sense {
                Sense::Up => o - i,
                Sense::Down => i - o,
            }
        })
        .fold(f64::INFINITY, f64::min)
}

impl Reference {
    pub fn new(intruders: usize) -> Self {
        Reference {
            memory: vec![Memory::default(); intruders],
            ra: None,
        }
    }

    /// One cycle `dt` s after the previous one.
    pub fn step(&mut self, own: &Own, intruders: &[Relative], dt: f64) -> Step {
        let level = level_for(own.altitude_ft);
        let mut alerts = Vec::with_capacity(intruders.len());
        let mut threats = Vec::new();
        for (m, x) in self.memory.iter_mut().zip(intruders) {
            let (r, rdot) = range_and_rate(x.s, x.v);
            let vertical = x.altitude.map(|(z, zdot)| {
                let h = z - own.altitude_ft;
                let hdot = zdot - own.rate_ft_per_s;
                (z, zdot, h, hdot)
            });

            // TA.
            let had_ta = m.ta_since.is_some();
            let dmod_ta = level.ta_dmod_m + if had_ta { TARHYST_M } else { 0.0 };
            let ta_range = range_test(r, rdot, dmod_ta, level.ta_tau, level.ta_h1, f64::INFINITY);
            let ta_vertical = match vertical {
                Some((_, _, h, hdot)) => {
                    let a = h.abs();
                    let adot = if h < 0.0 { -hdot } else { hdot };
                    a < level.ta_zthr_ft || (adot < ZDTHR_FT_S && a / -adot < level.ta_tau)
                }
                None => own.altitude_ft < ABOVNMC_FT,
            };
            let ta_test = ta_range && ta_vertical;

            // RA.
            let continuing = m.threat.is_some();
            let mut ra_test = false;
            let mut threat = None;
            if let (Some(ra), Some((z, zdot, h, hdot))) = (level.ra, vertical) {
                // DO-185B `tau_calculation`, `range_test`: both taus never
                // rise while the intruder does not diverge (true states
                // are firm from the start), `MINTAU` = 0 when it does; a
                // new threat outside DMOD is no range hit once its true
                // tau has not fallen for `taurise_thr` cycles beyond
                // `NAFRANGE`.
                let diverging = rdot > RDTHR_M_S;
                let (taumod, tau_true) = if diverging {
                    m.tau_cap = None;
                    m.tau_rise = 0;
                    (0.0, 0.0)
                } else {
                    let t1 = mod_tau(r, rdot, ra.dmod_m);
                    let t3 = true_tau(r, rdot);
                    let capped = match m.tau_cap {
                        Some((c1, c3)) => {
                            if t3 < m.last_true_tau {
                                m.tau_rise = 0;
                            } else if r > NAFRANGE_M {
                                m.tau_rise += 1;
                            }
                            (t1.min(c1), t3.min(c3))
                        }
                        None => {
                            m.tau_rise = 0;
                            (t1, t3)
                        }
                    };
                    m.tau_cap = Some(capped);
                    m.last_true_tau = t3;
                    capped
                };
                let range_ok = if diverging {
                    range_test(r, rdot, ra.dmod_m, ra.tau, ra.h1, RMAX_M)
                } else {
                    r <= RMAX_M
                        && taumod < ra.tau
                        && (continuing || m.tau_rise < TAURISE_CYCLES || r < ra.dmod_m)
                };
                let hmd = line_miss(x.s, x.v);
                let exceeds = if continuing {
                    hmd > HMDMULT * ra.dmod_m
                } else {
                    hmd > ra.hmd_m
                };
                if taumod < MDF_TAU_LIMIT_S && exceeds {
                    m.hmd_count += 1;
                } else {
                    m.hmd_count = 0;
                }
                let filtered = if continuing {
                    TMIN_MDF
                        .get(usize::from(level.sl))
                        .is_some_and(|&n| m.hmd_count > n)
                } else {
                    m.hmd_count > 0
                };
                let vertical_ok = continuing || {
                    let vmd = if rdot > 0.0 {
                        h
                    } else {
                        let v1 = h + hdot * tau_true.min(ra.tvpc);
                        let v2 = h + hdot * taumod.min(ra.tvpc);
                        if v1 * v2 <= 0.0 {
                            0.0
                        } else if v1.abs() < v2.abs() {
                            v1
                        } else {
                            v2
                        }
                    };
                    let level_own = own.rate_ft_per_s.abs() <= OLEV_FT_S
                        || (own.rate_ft_per_s * zdot >= 0.0
                            && own.rate_ft_per_s.abs() < zdot.abs());
                    let tvthr = if level_own { ra.tvvtt } else { ra.tau };
                    let a = h.abs();
                    let adot = if h < 0.0 { -hdot } else { hdot };
                    zdot.abs() <= MAXZDINT_FT_S
                        && if a < ra.zthr_ft {
                            vmd.abs() < ra.zthr_ft
                        } else if adot >= ZDTHR_FT_S {
                            false
                        } else {
                            let tauv = a / -adot;
                            tauv < tvthr && (vmd.abs() < ra.zthr_ft || tauv < tau_true)
                        }
                };
                let hit = range_ok && !filtered && vertical_ok;
                let th = Threat {
                    z,
                    zdot,
                    t1: tau_true.min(ra.tvpe),
                    t2: taumod.min(ra.tvpe),
                };
                // DO-185B `set_up_working_list`: a hit makes or keeps a
                // threat; its first miss keeps it, the next ends it once
                // TMIN has passed since it became one.
                let age = m.threat.map_or(0.0, |(_, age)| age + dt);
                m.threat = match (hit, m.threat) {
                    (true, _) => Some((false, age)),
                    (false, Some((false, _))) => Some((true, age)),
                    (false, Some((true, _))) if age <= TMIN_S => Some((true, age)),
                    _ => None,
                };
                ra_test = m.threat.is_some();
                threat = m.threat.map(|_| th);
            }
            if threat.is_none() {
                m.threat = None;
            }
            threats.extend(threat);

            let keep_ta = m.ta_since.is_some_and(|t| t + dt < MINTATIME_S);
            let ta_now = ta_test || ra_test || keep_ta;
            m.ta_since = if ta_now {
                Some(m.ta_since.map_or(0.0, |t| t + dt))
            } else {
                None
            };
            let proximate = r <= PROXR_M && vertical.is_none_or(|(_, _, h, _)| h.abs() <= PROXA_FT);
            alerts.push(if ra_test {
                Alert::Ra
            } else if ta_now {
                Alert::Ta
            } else if proximate {
                Alert::Proximate
            } else {
                Alert::None
            });
        }

        let mut clear_of_conflict = false;
        match (&self.ra, threats.is_empty(), level.ra) {
            (Some(_), true, _) => {
                self.ra = None;
                clear_of_conflict = true;
            }
            (None, false, Some(ra_level)) => {
                let alim = ra_level.alim_ft;
                let climb = own.rate_ft_per_s.clamp(CLMRT_FT_S, MAXDRATE_FT_S);
                let descend = own.rate_ft_per_s.clamp(-MAXDRATE_FT_S, -CLMRT_FT_S);
                let worst = |sense: Sense, goal: f64| {
                    threats
                        .iter()
                        .map(|t| separation(own, t, sense, goal))
                        .fold(f64::INFINITY, f64::min)
                };
                let up = worst(Sense::Up, climb);
                let down = worst(Sense::Down, descend);
                let crosses = |sense: Sense| {
                    threats.iter().any(|t| {
                        let h = t.z - own.altitude_ft;
                        match sense {
                            Sense::Up => h >= CROSSTHR_FT,
                            Sense::Down => h <= -CROSSTHR_FT,
                        }
                    })
                };
                let mut sense = if up > down { Sense::Up } else { Sense::Down };
                let (other, other_sep) = match sense {
                    Sense::Up => (Sense::Down, down),
                    Sense::Down => (Sense::Up, up),
                };
                if crosses(sense) && !crosses(other) && other_sep >= alim {
                    sense = other;
                }
                let negative_goal = match sense {
                    Sense::Up => own.rate_ft_per_s.max(0.0),
                    Sense::Down => own.rate_ft_per_s.min(0.0),
                };
                let positive = worst(sense, negative_goal) < alim;
                self.ra = Some(Ra {
                    sense,
                    positive,
                    crossing: crosses(sense),
                });
            }
            _ => {}
        }
        Step {
            alerts,
            ra: self.ra,
            clear_of_conflict,
        }
    }
}
