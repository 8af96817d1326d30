//! Altitude tracker for TCAS intruders on quantised reports (100 ft Mode C,
//! 25 ft Mode S): altitude, vertical rate, vertical firmness 0–3 and rate
//! bounds, after the bin-crossing tracker of RTCA DO-185B as transcribed in
//! ledieuke/tcas_simulator `tracking.py` (`one_hundred_ft_tracking` and the
//! functions it calls; constants from `tcasConstant.py`).
//!
//! A quantised report changes only when the altitude crosses a bin
//! boundary (report ± q/2), so the rate comes from the times between those
//! transitions (the bin time), averaged over up to [`MAX_BINS`] bins; a
//! transition that does not come when due first slows the rate and then
//! declares the track level; the estimate is always kept inside the
//! reported bin. DO-185B tracks 25 ft reports with a separate αβ tracker;
//! this one runs the same bin logic with q = 25 ft (one mechanism; the
//! figures are in docs/tcas.md).
//!
//! Units are feet and seconds: the reports and every vertical threshold
//! they feed are in feet.

use core::cmp::Ordering;

use crate::filter::{check_interval, FilterError};
use crate::num::{Numeric, Scalar};

/// `a·b` and `a/b` out of line, for logic that runs once a second per
/// intruder: Q32.32's 64×64-bit product and quotient, inlined at every use,
/// would otherwise cost the Cortex-M0's flash (measured: the altitude
/// tracker alone took 49 KiB in Q32.32 with the operators inlined). Used by
/// this tracker and by `crate::tcas`.
pub(crate) trait OutOfLine: Scalar {
    #[inline(never)]
    fn times(self, other: Self) -> Self {
        self * other
    }
    #[inline(never)]
    fn over(self, other: Self) -> Self {
        self / other
    }
}

impl<S: Scalar> OutOfLine for S {}

/// Default nominal scan interval T, s (TCAS surveillance updates once a
/// second; DO-185B `DT`).
pub const DEFAULT_INTERVAL_S: f64 = 1.0;
/// Default longest coast before an intruder counts as non-reporting, s.
pub const DEFAULT_MAX_COAST_S: f64 = 6.0;
/// Seconds per minute, for the ft/min figures of DO-185B.
const S_PER_MIN: f64 = 60.0;

/// Overdue time after which a trend's rate starts to slow, s (`LATESLACK`).
pub const LATE_SLACK_S: f64 = 0.5;
/// Overdue time after which a trend is declared level, s (`LATELEVEL`).
pub const LATE_LEVEL_S: f64 = 4.5;
/// Overdue time that restores firmness 2 on a slowing trend, s (`OVERDUE`).
pub const OVERDUE_S: f64 = 3.5;
/// Time without a transition after which a new, guessed or oscillating
/// track is level, s (`TGOLEV`).
pub const GO_LEVEL_S: f64 = 20.5;
/// Bin occupancy times that raise a new or guessed track's firmness to 1,
/// 2, 3, s (`GUESDU1..3`).
pub const OCCUPANCY_FIRMNESS_S: [f64; 3] = [4.5, 9.5, 14.5];
/// Time after which an oscillating track is firm, s (`GUESDU2`).
pub const OSCILLATION_FIRM_S: f64 = 9.5;
/// Rate assumed after a single transition from level, ft/s (`GUESRATE`,
/// 480 ft/min).
pub const GUESS_RATE_FT_PER_S: f64 = 480.0 / S_PER_MIN;
/// Decay of a guessed rate per scan without a transition (`ZDDECAY`).
pub const GUESS_DECAY: f64 = 0.9;
/// A gap between reports this long makes a multi-bin change a rate
/// measurement, s (`LONGCOAST`).
pub const LONG_COAST_S: f64 = 3.5;
/// Most likely rate after a transition, ft/s (`ZDLIKELY`, 3000 ft/min).
pub const LIKELY_RATE_FT_PER_S: f64 = 3000.0 / S_PER_MIN;
/// Steepest rate bound, ft/s (`ZDLARGE`, 12 000 ft/min).
pub const LARGE_RATE_FT_PER_S: f64 = 12000.0 / S_PER_MIN;
/// Time to a reasonable rate estimate, s (`TINITZD`).
pub const RATE_SETTLING_S: f64 = 5.5;
/// Shortest first bin time of a mature track, s (`TBINMIN`).
pub const MIN_FIRST_BIN_S: f64 = 2.0;
/// Shortest time for a trend to be reliable, s (`TTRENDMIN`).
pub const MIN_TREND_S: f64 = 2.5;
/// Transition earlier or later than expected by more than this restarts
/// the averaging, s (`EARLYLATE`).
pub const EARLY_LATE_S: f64 = 1.5;
/// Accumulated lateness that shortens the averaging, s (`SLITEOFF`).
pub const SLIGHTLY_OFF_S: f64 = 1.35;
/// Decay of the accumulated lateness per transition (`RESIDIMIN`).
pub const LATENESS_MEMORY: f64 = 0.8;
/// Decay of the accumulated lateness after a shortening (`RESIDECAY`).
pub const LATENESS_DECAY: f64 = 0.5;
/// Most bins averaged into the rate (`MAXBINS`).
pub const MAX_BINS: u8 = 8;
/// Longest time averaged into the rate, s (`MAXZDTIME`).
pub const MAX_RATE_TIME_S: f64 = 17.0;
/// Bins assumed when switching back from αβ smoothing (`NBINSNL`).
pub const BINS_AFTER_ALPHA_BETA: u8 = 5;
/// Bin times that switch to αβ smoothing (below `TBINLO` per bin observed,
/// `TBINHI` estimated) and back, s.
pub const ALPHA_BETA_BELOW_S: f64 = 0.9;
/// See [`ALPHA_BETA_BELOW_S`].
pub const BIN_OCCUPANCY_ABOVE_S: f64 = 1.1;
/// αβ gains when transitions come every scan (`ALPHAZ[1]`, `BETAZ[1]`).
pub const ALPHA_BETA_GAINS: (f64, f64) = (0.5, 0.167);
/// A reversal this early in the bin (fraction of the bin time) is taken as
/// jitter at the boundary and ignored (`ZRJIT`).
pub const REVERSAL_JITTER: f64 = 0.24;
/// Margin of the rate bounds for possible acceleration (`ZDFRACC`).
pub const RATE_BOUND_MARGIN: f64 = 1.3;
/// Shortest time over which a prediction error corrects the rate, s
/// (`DELZDT`).
pub const MIN_CORRECTION_TIME_S: f64 = 4.0;
/// Prediction error that lowers a trend's firmness to 1, ft (`DELZTHR`).
pub const PREDICTION_ERROR_FT: f64 = 20.0;
/// Ratios of observed to expected bin time that keep firmness 3, 2, 1
/// (`LO3..HI1`).
pub const BIN_RATIO_FIRMNESS: [(f64, f64); 3] = [(0.8, 1.25), (0.667, 1.5), (0.0, 2.0)];
/// Lateness that gives firmness 3, at least 2, s (`OUT3`, `OUT2`).
pub const LATENESS_FIRMNESS_S: (f64, f64) = (0.55, 1.1);
/// Bin times that give at least firmness 1, 2, s (`SLACKEN1`, `SLACKEN2`).
pub const SLOW_BIN_FIRMNESS_S: (f64, f64) = (3.5, 6.5);
/// Credibility of a report (`credible`): within q + this rate error ·Δt
/// (ft/s, `CREDZDERR`) + this acceleration/2 ·Δt² (ft/s², `CREDACCDIV`) of
/// the prediction; while the rate is settling, within this rate ·Δt
/// (`CREDINIT`, ft/s).
pub const CREDIBLE_RATE_ERROR_FT_PER_S: f64 = 30.0;
/// See [`CREDIBLE_RATE_ERROR_FT_PER_S`].
pub const CREDIBLE_HALF_ACCELERATION_FT_PER_S2: f64 = 20.0;
/// See [`CREDIBLE_RATE_ERROR_FT_PER_S`].
pub const CREDIBLE_INITIAL_RATE_FT_PER_S: f64 = 200.0;
/// Largest vertical firmness.
pub const MAX_VERTICAL_FIRMNESS: u8 = 3;

/// The altitude quantum of the transponder's reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeQuantum {
    /// Mode C (Gillham code): 100 ft.
    ModeC,
    /// Mode S with 25 ft reporting (Q bit set).
    ModeS25,
}

impl AltitudeQuantum {
    /// The quantum q in feet.
    pub const fn feet(self) -> f64 {
        match self {
            AltitudeQuantum::ModeC => 100.0,
            AltitudeQuantum::ModeS25 => 25.0,
        }
    }

    /// Residual of the αβ smoothing that costs firmness, ft (`DZTHR_100`,
    /// `DZTHR_25`).
    const fn residual_threshold_ft(self) -> f64 {
        match self {
            AltitudeQuantum::ModeC => 60.0,
            AltitudeQuantum::ModeS25 => 22.5,
        }
    }
}

/// Why an altitude-tracker configuration was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeConfigError {
    /// The nominal interval is not a finite number > 0, or not representable.
    IntervalNotPositive,
    /// The longest coast is not a finite number ≥ 0, or not representable.
    InvalidCoast,
}

impl core::fmt::Display for AltitudeConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            AltitudeConfigError::IntervalNotPositive => {
                "nominal interval must be a finite number > 0 s"
            }
            AltitudeConfigError::InvalidCoast => "longest coast must be a finite number >= 0 s",
        })
    }
}

impl core::error::Error for AltitudeConfigError {}

/// Configuration of an [`AltitudeTracker`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeTrackerConfig<S> {
    quantum: AltitudeQuantum,
    interval: S,
    max_coast: S,
    /// `max_coast` + `interval`: the longest time from one report to the
    /// next that the track survives, coasted scan by scan.
    longest_gap: S,
}

impl<S: Scalar> AltitudeTrackerConfig<S> {
    /// Reports quantised to `quantum`, a nominal scan interval `interval_s`
    /// (> 0; DO-185B's `DT`, used for the half-scan uncertainty of a
    /// transition time), coasting through up to `max_coast_s` (≥ 0) seconds
    /// of missing reports.
    pub fn new(
        quantum: AltitudeQuantum,
        interval_s: f64,
        max_coast_s: f64,
    ) -> Result<Self, AltitudeConfigError> {
        if !(interval_s.is_finite() && interval_s > 0.0) {
            return Err(AltitudeConfigError::IntervalNotPositive);
        }
        if !(max_coast_s.is_finite() && max_coast_s >= 0.0) {
            return Err(AltitudeConfigError::InvalidCoast);
        }
        Ok(AltitudeTrackerConfig {
            quantum,
            interval: S::try_from_f64(interval_s)
                .map_err(|_| AltitudeConfigError::IntervalNotPositive)?,
            max_coast: S::try_from_f64(max_coast_s)
                .map_err(|_| AltitudeConfigError::InvalidCoast)?,
            longest_gap: S::try_from_f64(max_coast_s + interval_s)
                .map_err(|_| AltitudeConfigError::InvalidCoast)?,
        })
    }

    /// The documented defaults for a quantum: T = 1 s, coast up to 6 s.
    pub fn default_for(quantum: AltitudeQuantum) -> Result<Self, AltitudeConfigError> {
        Self::new(quantum, DEFAULT_INTERVAL_S, DEFAULT_MAX_COAST_S)
    }

    /// The altitude reports' quantum (Mode C 100 ft or Mode S 25 ft).
    pub fn quantum(&self) -> AltitudeQuantum {
        self.quantum
    }
    /// Nominal scan interval, s.
    pub fn interval(&self) -> S {
        self.interval
    }
    /// Longest coast through missing reports, s.
    pub fn max_coast(&self) -> S {
        self.max_coast
    }

    /// The quantum q, ft.
    #[inline(always)]
    fn q(&self) -> S {
        self.of_quantum(|q| q)
    }

    /// q/2, ft: half a bin (a report stands for report ± q/2, DO-185B);
    /// exact in every format, so the same as `q·0.5`.
    #[inline(always)]
    fn half_q(&self) -> S {
        self.of_quantum(|q| q / 2.0)
    }

    /// q/3, ft (the estimate after an oscillation: `oscil_track_init`),
    /// rounded once in f64 and once to S: for q = 100 and 25 ft the same
    /// value as `q ÷ 3` in S in every format (no tie near either rounding).
    #[inline(always)]
    fn third_q(&self) -> S {
        self.of_quantum(|q| q / 3.0)
    }

    /// `f(q)` as S: both quanta's constants, folded at compile time, then
    /// the configuration's (a match over the two conversions is merged by LLVM
    /// into one conversion at run time of the chosen f64; in Q32.32, whose
    /// conversion does not fold, this converts both).
    #[inline(always)]
    fn of_quantum(&self, f: impl Fn(f64) -> f64) -> S {
        self.per_quantum(|quantum| f(quantum.feet()))
    }

    /// Residual of the αβ smoothing that costs firmness, ft, as S.
    #[inline(always)]
    fn residual_threshold(&self) -> S {
        self.per_quantum(AltitudeQuantum::residual_threshold_ft)
    }

    /// `f(quantum)` as S for the configured quantum (see `of_quantum`).
    #[inline(always)]
    fn per_quantum(&self, f: impl Fn(AltitudeQuantum) -> f64) -> S {
        let mode_c = c::<S>(f(AltitudeQuantum::ModeC));
        let mode_s25 = c::<S>(f(AltitudeQuantum::ModeS25));
        match self.quantum {
            AltitudeQuantum::ModeC => mode_c,
            AltitudeQuantum::ModeS25 => mode_s25,
        }
    }
}

/// Altitude and vertical rate of an intruder.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeEstimate<S> {
    /// Pressure altitude, ft.
    pub altitude_ft: S,
    /// Vertical rate, ft/s (positive climbing).
    pub vertical_rate_ft_per_s: S,
}

/// Bounds on the intruder's vertical rate, ft/s (DO-185B `ZDINNER`,
/// `ZDOUTER`, sorted).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RateBounds<S> {
    /// The lower bound, ft/s.
    pub lowest_ft_per_s: S,
    /// The upper bound, ft/s.
    pub highest_ft_per_s: S,
}

/// Whether and how well the intruder's altitude is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AltitudeStatus {
    /// No altitude: never reported, or reports stopped for longer than the
    /// configured coast.
    NotReporting,
    /// One report: altitude known, vertical rate taken as zero.
    OneReport,
    /// Two or more reports.
    Tracking,
}

/// What the reports have shown so far (DO-185B `CLASS`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum VerticalClass {
    /// No transition since the track started.
    New,
    /// No transition for a long time, or a trend that stopped: rate zero.
    Level,
    /// One transition: the rate is a guess.
    Guess,
    /// Transitions back and forth across one boundary: rate zero.
    Oscillating,
    /// Transitions in one direction: the rate is measured.
    Trend,
}

/// Quantisation-aware altitude tracker (see the module docs), computing in
/// `N::Wide` ([`Numeric::Wide`]): its configuration and its
/// [`AltitudeState`], which it dereferences to for reading.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeTracker<N: Numeric> {
    config: AltitudeTrackerConfig<N::Wide>,
    state: AltitudeState<N>,
}

/// The state of an [`AltitudeTracker`] without its configuration: what a
/// scan loop keeps per intruder, the configuration being the system's
/// ([`crate::tcas::IntruderTrack`]). Its [`Self::scan`] takes the
/// configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AltitudeState<N: Numeric> {
    /// Reports since the track (re)started, saturating at 2.
    reports: u8,
    altitude_ft: N::Wide,
    rate_ft_per_s: N::Wide,
    /// The last report taken (DO-185B `ZSAVE`), ft.
    report_ft: N::Wide,
    class: VerticalClass,
    /// −1, 0 or +1: the direction of the last transition.
    direction: i8,
    since_start_s: N::Wide,
    since_transition_s: N::Wide,
    /// Time since the last report, s.
    coasted_s: N::Wide,
    /// Smoothed time per bin, s (`TBIN`).
    bin_time_s: N::Wide,
    /// Bins averaged into the rate (`BINSTHISZD`).
    bins_in_rate: u8,
    /// Accumulated lateness of the transitions, s (`RESID`).
    lateness_s: N::Wide,
    alpha_beta: bool,
    firmness: u8,
    bounds: RateBounds<N::Wide>,
    /// Saturating counts. The reports refused as not credible are a u32:
    /// the scan loop's lifetime count sums their increase, which a u16 would
    /// stop at 65,535 (the micro:bit's state is 52 bytes either way,
    /// docs/tcas.md "RAM per intruder"); the saturations a u16, widened by
    /// their getter.
    incredible_reports: u32,
    saturations: u16,
}

// Always inlined: every argument is a constant, so the conversion folds at
// compile time into a literal of S where it inlines, as in the fast fixed
// point and f32 (a call per constant per scan otherwise: ~50 integer
// instructions, or a soft-float call). Q32.32's conversion is out of line
// in the library and stays a call.
#[inline(always)]
fn c<S: Scalar>(v: f64) -> S {
    S::from_f64_lossy(v)
}

/// `v` in the direction of a transition (`sign` > 0: up, otherwise down).
#[inline(always)]
fn toward<S: Scalar>(sign: i8, v: S) -> S {
    if sign > 0 {
        v
    } else {
        -v
    }
}

/// A value known only at run time as S, out of line (the conversion is
/// soft-float or ~50 integer instructions: one copy, for flash).
#[inline(never)]
fn convert<S: Scalar>(v: f64) -> S {
    S::from_f64_lossy(v)
}

/// A count (bins) as S: 1..=[`MAX_BINS`], the counts averaged into the rate
/// (`BINSTHISZD`), from constants (the same values: small integers are
/// exact in every format), others converted.
#[inline(always)]
fn count<S: Scalar>(n: u8) -> S {
    match n {
        1 => S::ONE,
        2 => c(2.0),
        3 => c(3.0),
        4 => c(4.0),
        5 => c(5.0),
        6 => c(6.0),
        7 => c(7.0),
        8 => c(8.0),
        _ => convert(f64::from(n)),
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> Default for AltitudeState<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> AltitudeState<N> {
    /// No altitude yet (status `NotReporting`).
    pub fn new() -> Self {
        AltitudeState {
            reports: 0,
            altitude_ft: S::ZERO,
            rate_ft_per_s: S::ZERO,
            report_ft: S::ZERO,
            class: VerticalClass::New,
            direction: 0,
            since_start_s: S::ZERO,
            since_transition_s: S::ZERO,
            coasted_s: S::ZERO,
            bin_time_s: S::ZERO,
            bins_in_rate: 1,
            lateness_s: S::ZERO,
            alpha_beta: false,
            firmness: 0,
            bounds: RateBounds {
                lowest_ft_per_s: S::ZERO,
                highest_ft_per_s: S::ZERO,
            },
            incredible_reports: 0,
            saturations: 0,
        }
    }

    /// Whether and how well the altitude is known (from the report count).
    pub fn status(&self) -> AltitudeStatus {
        match self.reports {
            0 => AltitudeStatus::NotReporting,
            1 => AltitudeStatus::OneReport,
            _ => AltitudeStatus::Tracking,
        }
    }

    /// The current estimate; `None` for a non-reporting intruder.
    pub fn estimate(&self) -> Option<AltitudeEstimate<S>> {
        (self.reports > 0).then_some(AltitudeEstimate {
            altitude_ft: self.altitude_ft,
            vertical_rate_ft_per_s: self.rate_ft_per_s,
        })
    }

    /// Vertical firmness 0–3 (DO-185B `CASFIRM`): how much the rate can be
    /// trusted; the threat logic needs 2 for a new RA.
    pub fn firmness(&self) -> u8 {
        self.firmness
    }

    /// What the reports have shown so far.
    pub fn class(&self) -> VerticalClass {
        self.class
    }

    /// The rate bounds; `None` for a non-reporting intruder.
    pub fn rate_bounds(&self) -> Option<RateBounds<S>> {
        (self.reports > 0).then_some(self.bounds)
    }

    /// Time since the last altitude report, s (zero right after one).
    pub fn since_last_report(&self) -> S {
        self.coasted_s
    }

    /// Reports refused as not credible (a jump the track cannot have made);
    /// each was coasted through instead.
    pub fn incredible_reports(&self) -> u32 {
        self.incredible_reports
    }

    /// Scans discarded because their arithmetic saturated.
    pub fn saturations(&self) -> u32 {
        u32::from(self.saturations)
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> AltitudeTracker<N> {
    /// A tracker with no altitude yet (status `NotReporting`).
    pub fn new(config: AltitudeTrackerConfig<S>) -> Self {
        AltitudeTracker {
            config,
            state: AltitudeState::new(),
        }
    }

    /// The configuration the tracker was built with.
    pub fn config(&self) -> &AltitudeTrackerConfig<S> {
        &self.config
    }

    /// [`AltitudeState::scan`] with this tracker's configuration.
    pub fn scan(&mut self, altitude_ft: Option<S>, dt: S) -> Result<AltitudeStatus, FilterError> {
        self.state.scan(&self.config, altitude_ft, dt)
    }
}

impl<N: Numeric<Wide = S>, S: Scalar> AltitudeState<N> {
    /// One surveillance scan, `dt` seconds after the previous one:
    /// `Some(altitude_ft)` if the reply carried an altitude, `None` if it did
    /// not. A missing or incredible altitude coasts the track; after more
    /// than `max_coast` seconds without one the tracker forgets the altitude
    /// and becomes `NotReporting` (DO-185B's coast limit), also when the gap
    /// comes as one long `dt`: the report after it starts a new track.
    /// Invalid input is refused with the filter's error and changes
    /// nothing; so is a scan whose arithmetic saturates (counted). `config`
    /// is the tracker's configuration, the same at every scan of a track.
    pub fn scan(
        &mut self,
        config: &AltitudeTrackerConfig<S>,
        altitude_ft: Option<S>,
        dt: S,
    ) -> Result<AltitudeStatus, FilterError> {
        if altitude_ft.is_some_and(|z| !z.is_valid()) {
            return Err(FilterError::InvalidMeasurement);
        }
        check_interval(dt)?;
        let mut next = *self;
        // The time since the last report. A report after a gap the track
        // would not have coasted through scan by scan (more than
        // `max_coast` before this scan's nominal interval, whether the gap
        // came as coasts, as one long `dt` or as both) starts the track
        // again: the coasts would have forgotten it.
        let elapsed = self.coasted_s + dt;
        match altitude_ft {
            Some(z) if self.reports == 0 || elapsed > config.longest_gap => next.start(z),
            Some(z) => {
                // The change of report, once for the test and the update.
                let change = z - self.report_ft;
                if self.credible(config, change, dt, elapsed) {
                    next.take(config, z, change, dt);
                } else {
                    next.incredible_reports = next.incredible_reports.saturating_add(1);
                    next.coast(config, dt);
                }
            }
            None => next.coast(config, dt),
        }
        if !next.is_valid() {
            self.saturations = self.saturations.saturating_add(1);
            return Err(FilterError::Saturated);
        }
        *self = next;
        Ok(self.status())
    }

    fn is_valid(&self) -> bool {
        [
            self.altitude_ft,
            self.rate_ft_per_s,
            self.since_start_s,
            self.since_transition_s,
            self.coasted_s,
            self.bin_time_s,
            self.lateness_s,
            self.bounds.lowest_ft_per_s,
            self.bounds.highest_ft_per_s,
        ]
        .iter()
        .all(|v| v.is_valid())
    }

    /// Forgets the track (status `NotReporting`); the counts stay.
    fn forget(&mut self) {
        *self = AltitudeState {
            incredible_reports: self.incredible_reports,
            saturations: self.saturations,
            ..AltitudeState::new()
        };
    }

    fn start(&mut self, z: S) {
        self.forget();
        self.reports = 1;
        self.altitude_ft = z;
        self.report_ft = z;
        self.bounds = RateBounds {
            lowest_ft_per_s: -c::<S>(LARGE_RATE_FT_PER_S),
            highest_ft_per_s: c(LARGE_RATE_FT_PER_S),
        };
    }

    /// DO-185B `credible`: the report is within what the track could have
    /// done since the last report (`change`: the report minus the last;
    /// `elapsed`: the time since it, coasts included).
    fn credible(&self, config: &AltitudeTrackerConfig<S>, change: S, dt: S, elapsed: S) -> bool {
        if change == S::ZERO {
            return true;
        }
        if self.since_start_s + dt < c(RATE_SETTLING_S) {
            return change.abs() <= c::<S>(CREDIBLE_INITIAL_RATE_FT_PER_S).times(elapsed);
        }
        let predicted_change = self.rate_ft_per_s.times(elapsed);
        (change - predicted_change).abs()
            <= config.q()
                + c::<S>(CREDIBLE_RATE_ERROR_FT_PER_S).times(elapsed)
                + c::<S>(CREDIBLE_HALF_ACCELERATION_FT_PER_S2)
                    .times(elapsed)
                    .times(elapsed)
    }

    fn coast(&mut self, config: &AltitudeTrackerConfig<S>, dt: S) {
        if self.reports == 0 {
            return;
        }
        let coasted = self.coasted_s + dt;
        if !coasted.is_valid() || coasted > config.max_coast {
            self.forget();
            return;
        }
        self.coasted_s = coasted;
        self.since_start_s = self.since_start_s + dt;
        self.since_transition_s = self.since_transition_s + dt;
        self.altitude_ft = self.altitude_ft + self.rate_ft_per_s.times(dt);
        self.firmness = self.firmness.saturating_sub(1);
    }

    /// A credible report `z`, `change` from the last, `dt` after the
    /// previous scan.
    fn take(&mut self, config: &AltitudeTrackerConfig<S>, z: S, change: S, dt: S) {
        self.reports = 2;
        self.since_start_s = self.since_start_s + dt;
        self.since_transition_s = self.since_transition_s + dt;
        let coasted = self.coasted_s;
        self.coasted_s = S::ZERO;
        // The reported bin, z ± q/2, once for the no-transition test and
        // the clamp.
        let half = config.half_q();
        let bin = (z - half, z + half);
        let keep_report = if change == S::ZERO {
            self.no_transition(config, z, dt, bin);
            true
        } else {
            self.transition(config, z, change, dt, coasted + dt)
        };
        if keep_report {
            self.report_ft = z;
        }
        self.clamp_to_bin(bin);
    }

    /// The estimate stays inside the reported bin (its lower and upper
    /// edges).
    fn clamp_to_bin(&mut self, (low, high): (S, S)) {
        self.altitude_ft = self.altitude_ft.max_of(low).min_of(high);
    }

    fn signed(&self, v: S) -> S {
        match self.direction {
            d if d < 0 => -v,
            0 => S::ZERO,
            _ => v,
        }
    }

    fn set_bounds(&mut self, a: S, b: S) {
        self.bounds = RateBounds {
            lowest_ft_per_s: a.min_of(b),
            highest_ft_per_s: a.max_of(b),
        };
    }

    fn occupancy_firmness(&mut self) {
        let [t1, t2, t3] = OCCUPANCY_FIRMNESS_S;
        for (firmness, t) in [(1u8, c::<S>(t1)), (2, c(t2)), (3, c(t3))] {
            if self.since_transition_s > t {
                self.firmness = self.firmness.max(firmness);
            }
        }
    }

    fn go_level(&mut self, config: &AltitudeTrackerConfig<S>, z: S) {
        self.altitude_ft = z;
        self.rate_ft_per_s = S::ZERO;
        self.class = VerticalClass::Level;
        self.firmness = MAX_VERTICAL_FIRMNESS;
        let outer = self.signed(
            config
                .q()
                .over(self.since_transition_s.max_of(config.interval)),
        );
        self.set_bounds(S::ZERO, outer);
    }

    /// DO-185B `no_transition_update` and `no_transition_firmness`.
    /// `bin`: the reported bin's lower and upper edges, z ∓ q/2.
    fn no_transition(&mut self, config: &AltitudeTrackerConfig<S>, z: S, dt: S, bin: (S, S)) {
        let q = config.q();
        let t = config.interval;
        let since = self.since_transition_s;
        match self.class {
            VerticalClass::New | VerticalClass::Guess | VerticalClass::Oscillating
                if since > c(GO_LEVEL_S) =>
            {
                self.go_level(config, z)
            }
            VerticalClass::Level => self.go_level(config, z),
            VerticalClass::New => {
                self.altitude_ft = z;
                self.rate_ft_per_s = S::ZERO;
                let bound = q.over(self.since_start_s);
                self.set_bounds(-bound, bound);
                self.occupancy_firmness();
            }
            VerticalClass::Oscillating => {
                self.rate_ft_per_s = S::ZERO;
                self.set_bounds(S::ZERO, S::ZERO);
                if since > c(OSCILLATION_FIRM_S) {
                    self.firmness = MAX_VERTICAL_FIRMNESS;
                }
            }
            VerticalClass::Guess => {
                self.rate_ft_per_s = self.rate_ft_per_s.times(c(GUESS_DECAY));
                self.altitude_ft = self.altitude_ft + self.rate_ft_per_s.times(dt);
                let outer = if self.since_start_s > c(RATE_SETTLING_S) {
                    q.over(since).min_of(c(LIKELY_RATE_FT_PER_S))
                } else {
                    q.over(since)
                };
                let outer = self.signed(outer);
                self.set_bounds(S::ZERO, outer);
                self.occupancy_firmness();
            }
            VerticalClass::Trend => {
                let overdue = since - self.bin_time_s;
                let late_level = c::<S>(LATE_LEVEL_S);
                if overdue > late_level {
                    self.go_level(config, z);
                } else if overdue > c(LATE_SLACK_S) {
                    // No transition when due: the rate that would just have
                    // missed it, tapering to zero at LATELEVEL.
                    let half_t = t.times(c(0.5));
                    let taper = (late_level + half_t - overdue).over(late_level + half_t);
                    self.rate_ft_per_s = self.signed(q.over(since + t).times(taper));
                    self.bins_in_rate = self.bins_in_rate.saturating_sub(1).max(1);
                    self.altitude_ft = z + self.signed(config.half_q());
                    self.set_bounds(S::ZERO, self.signed(q.over(since)));
                    self.firmness = if overdue > c(OVERDUE_S) {
                        self.firmness.saturating_add(1).min(2)
                    } else {
                        1
                    };
                } else {
                    let predicted = self.altitude_ft + self.rate_ft_per_s.times(dt);
                    let (low, high) = bin;
                    if predicted > high || predicted < low {
                        // Ahead of the reports: hold the estimate at the bin
                        // edge and take the difference out of the rate.
                        self.altitude_ft = z + self.signed(config.half_q());
                        let error = self.altitude_ft - predicted;
                        self.rate_ft_per_s =
                            self.rate_ft_per_s + error.over(since.max_of(c(MIN_CORRECTION_TIME_S)));
                        self.bins_in_rate = self.bins_in_rate.saturating_sub(1).max(1);
                        if error.abs() > c(PREDICTION_ERROR_FT) {
                            self.firmness = 1;
                        }
                    } else {
                        self.altitude_ft = predicted;
                    }
                }
            }
        }
    }

    /// A change of report by `change`; false when the transition is taken
    /// as jitter and the previous report stays the reference.
    fn transition(
        &mut self,
        config: &AltitudeTrackerConfig<S>,
        z: S,
        change: S,
        dt: S,
        since_report: S,
    ) -> bool {
        let q = config.q();
        let sign: i8 = if change > S::ZERO { 1 } else { -1 };
        let bins = bins_of(change.abs().over(q));
        let bins_s = count::<S>(bins);
        let time_per_bin = self.since_transition_s.over(bins_s);
        let same_direction = self.direction == sign;
        let mut keep = true;
        match self.class {
            VerticalClass::New | VerticalClass::Level => {
                self.start_guess(config, z, change, sign, since_report)
            }
            VerticalClass::Guess if same_direction => {
                self.start_trend(config, z, change, sign, time_per_bin)
            }
            VerticalClass::Guess => self.start_oscillation(config, z, sign),
            VerticalClass::Oscillating if same_direction => {
                self.start_trend(config, z, change, sign, time_per_bin)
            }
            VerticalClass::Oscillating => {
                self.altitude_ft = z - toward(sign, config.third_q());
                self.firmness = MAX_VERTICAL_FIRMNESS;
            }
            VerticalClass::Trend if same_direction => {
                self.continue_trend(config, z, change, bins, time_per_bin, dt)
            }
            VerticalClass::Trend if bins > 1 => {
                self.start_guess(config, z, change, sign, since_report)
            }
            VerticalClass::Trend => {
                if self.bin_time_s > S::ZERO
                    && time_per_bin <= c::<S>(REVERSAL_JITTER).times(self.bin_time_s)
                {
                    // Right after a transition: jitter at the boundary.
                    self.altitude_ft = self.altitude_ft + self.rate_ft_per_s.times(dt);
                    self.firmness = 0;
                    keep = false;
                } else {
                    self.start_oscillation(config, z, sign);
                }
            }
        }
        if keep {
            self.direction = sign;
            self.since_transition_s = S::ZERO;
        }
        keep
    }

    /// The altitude a new rate starts from: the report's bin edge half a
    /// quantum back against `sign`, moved on by half a scan at the rate
    /// (DO-185B `guess_track_init`, `trend_track_init`).
    fn mid_bin_altitude(&self, config: &AltitudeTrackerConfig<S>, z: S, sign: i8) -> S {
        z - toward(sign, config.half_q()) + self.rate_ft_per_s.times(config.interval).times(c(0.5))
    }

    /// DO-185B `guess_track_init`.
    fn start_guess(
        &mut self,
        config: &AltitudeTrackerConfig<S>,
        z: S,
        change: S,
        sign: i8,
        since_report: S,
    ) {
        let q = config.q();
        let qs = toward(sign, q);
        // After a long gap over several bins the change itself is a rate.
        self.rate_ft_per_s = if since_report > c(LONG_COAST_S) && change.abs() > q {
            (change - qs).over(since_report)
        } else {
            toward(sign, c(GUESS_RATE_FT_PER_S))
        };
        let outer = if self.since_start_s < c(RATE_SETTLING_S) {
            (change + qs).over(self.since_start_s)
        } else {
            toward(sign, c(LIKELY_RATE_FT_PER_S))
        };
        self.set_bounds(S::ZERO, outer);
        self.altitude_ft = self.mid_bin_altitude(config, z, sign);
        self.firmness = 0;
        self.class = VerticalClass::Guess;
    }

    /// DO-185B `oscil_track_init`.
    fn start_oscillation(&mut self, config: &AltitudeTrackerConfig<S>, z: S, sign: i8) {
        self.altitude_ft = z - toward(sign, config.third_q());
        self.rate_ft_per_s = S::ZERO;
        self.firmness = 2;
        self.set_bounds(S::ZERO, S::ZERO);
        self.class = VerticalClass::Oscillating;
    }

    /// DO-185B `trend_track_init`: the second transition in one direction.
    fn start_trend(
        &mut self,
        config: &AltitudeTrackerConfig<S>,
        z: S,
        change: S,
        sign: i8,
        time_per_bin: S,
    ) {
        let qs = toward(sign, config.q());
        let t = config.interval;
        let since = self.since_transition_s;
        self.alpha_beta = false;
        self.bin_time_s = if self.since_start_s < c(RATE_SETTLING_S) {
            time_per_bin
        } else {
            time_per_bin.max_of(c(MIN_FIRST_BIN_S))
        };
        self.rate_ft_per_s = qs.over(self.bin_time_s);
        self.altitude_ft = if self.bin_time_s > S::ONE {
            self.mid_bin_altitude(config, z, sign)
        } else {
            z
        };
        self.lateness_s = S::ZERO;
        self.bins_in_rate = 1;
        if since > c(MIN_TREND_S) {
            self.firmness = 2;
            let outer_time = (since - t).max_of(t);
            self.set_bounds(
                change.over(since + t),
                c::<S>(RATE_BOUND_MARGIN).times(change).over(outer_time),
            );
        } else {
            self.firmness = 1;
            self.set_bounds(
                change.over(c::<S>(MIN_TREND_S) + t),
                (change + qs).over(since),
            );
        }
        self.class = VerticalClass::Trend;
    }

    /// DO-185B `smoothing_method_selection`, `expected_transition`,
    /// `alpha_beta_smoothing`, `transition_set_casfirm`,
    /// `transition_set_rate_limits`: another transition along the trend.
    fn continue_trend(
        &mut self,
        config: &AltitudeTrackerConfig<S>,
        z: S,
        change: S,
        bins: u8,
        time_per_bin: S,
        dt: S,
    ) {
        let q = config.q();
        let t = config.interval;
        let sign_q = self.signed(q);
        let since = self.since_transition_s;
        let bins_s = count::<S>(bins);
        let previous_bin_time = self.bin_time_s;
        if self.alpha_beta {
            if self.bin_time_s > c(ALPHA_BETA_BELOW_S) && time_per_bin > c(BIN_OCCUPANCY_ABOVE_S) {
                self.alpha_beta = false;
                self.lateness_s = S::ZERO;
                self.bins_in_rate = BINS_AFTER_ALPHA_BETA;
            }
        } else if self.bin_time_s < c(BIN_OCCUPANCY_ABOVE_S) && time_per_bin < c(ALPHA_BETA_BELOW_S)
        {
            self.alpha_beta = true;
            self.firmness = self.firmness.min(1);
        }
        if self.alpha_beta {
            let (alpha, beta) = ALPHA_BETA_GAINS;
            let previous = self.altitude_ft;
            let predicted = previous + self.rate_ft_per_s.times(dt);
            let residual = z - predicted;
            self.altitude_ft = predicted + c::<S>(alpha).times(residual);
            self.rate_ft_per_s = self.rate_ft_per_s + c::<S>(beta).times(residual).over(dt);
            let after = z - (previous + self.rate_ft_per_s.times(dt));
            if after.abs() >= config.residual_threshold() {
                self.firmness = self.firmness.saturating_sub(2);
                self.bins_in_rate = self.bins_in_rate.saturating_sub(1).max(3);
            } else {
                self.firmness = self.firmness.saturating_add(1).min(MAX_VERTICAL_FIRMNESS);
                self.bins_in_rate = self.bins_in_rate.saturating_add(bins).min(MAX_BINS);
            }
            if self.rate_ft_per_s != S::ZERO {
                self.bin_time_s = q.over(self.rate_ft_per_s).abs();
            }
            // Bounds: the measured rate ± half a bin per averaged bin.
            let n = count::<S>(self.bins_in_rate.max(1));
            let half = c::<S>(0.5);
            self.set_bounds(
                self.rate_ft_per_s.times(n - half).over(n),
                self.rate_ft_per_s.times(n + half).over(n),
            );
            return;
        }
        // Bin occupancy: average the time per bin.
        let late = since - previous_bin_time.times(bins_s);
        let restart_bins = if time_per_bin > c(MIN_TREND_S) {
            bins
        } else {
            bins.saturating_add(1)
        };
        if late.abs() > c(EARLY_LATE_S) {
            self.bins_in_rate = restart_bins;
            self.lateness_s = S::ZERO;
        } else {
            self.lateness_s = c::<S>(LATENESS_MEMORY).times(self.lateness_s) + late;
            if self.lateness_s.abs() <= c(SLIGHTLY_OFF_S) {
                let max_time = c::<S>(MAX_RATE_TIME_S);
                // 2·t ≥ MAXZDTIME, as t ≥ MAXZDTIME/2: doubling is exact.
                if time_per_bin >= c(MAX_RATE_TIME_S / 2.0) {
                    self.bins_in_rate = 1;
                } else {
                    // The most bins whose time fits in MAXZDTIME.
                    let mut most = 1u8;
                    let counts: [(u8, S); MAX_BINS as usize - 1] = [
                        (2, c(2.0)),
                        (3, c(3.0)),
                        (4, c(4.0)),
                        (5, c(5.0)),
                        (6, c(6.0)),
                        (7, c(7.0)),
                        (8, c(8.0)),
                    ];
                    for (n, n_s) in counts {
                        if n_s.times(time_per_bin) <= max_time {
                            most = n;
                        }
                    }
                    self.bins_in_rate = self.bins_in_rate.saturating_add(bins).min(most);
                }
            } else {
                self.bins_in_rate = restart_bins;
                self.lateness_s = self.lateness_s.times(c(LATENESS_DECAY));
            }
        }
        let weight = bins_s.over(count::<S>(self.bins_in_rate.max(1)));
        self.bin_time_s = previous_bin_time
            + weight
                .min_of(S::ONE)
                .times(time_per_bin - previous_bin_time);
        self.rate_ft_per_s = sign_q.over(self.bin_time_s);
        self.altitude_ft = self.altitude_ft + self.rate_ft_per_s.times(dt);
        // Firmness from how regular the bin crossings are.
        let ratio = time_per_bin.over(previous_bin_time);
        let [(lo3, hi3), (lo2, hi2), (lo1, hi1)] = BIN_RATIO_FIRMNESS;
        let ranges: [(u8, S, S); 3] = [
            (3, c(lo3), c(hi3)),
            (2, c(lo2), c(hi2)),
            (1, c(lo1), c(hi1)),
        ];
        self.firmness = ranges
            .iter()
            .find(|&&(_, lo, hi)| ratio >= lo && ratio <= hi)
            .map_or(0, |&(firmness, _, _)| firmness);
        let (out3, out2) = LATENESS_FIRMNESS_S;
        if late.abs() < c(out3) {
            self.firmness = MAX_VERTICAL_FIRMNESS;
        } else if late.abs() < c(out2) {
            self.firmness = self.firmness.max(2);
        }
        let (slow1, slow2) = SLOW_BIN_FIRMNESS_S;
        if time_per_bin > c(slow2) {
            self.firmness = self.firmness.max(2);
        } else if time_per_bin > c(slow1) {
            self.firmness = self.firmness.max(1);
        }
        if self.since_start_s < c(RATE_SETTLING_S) {
            self.firmness = 1;
        }
        // Rate bounds: ± one scan of timing over the averaged bins when the
        // crossings are regular; wider otherwise.
        if self.firmness == MAX_VERTICAL_FIRMNESS || late.abs() < c(out2) {
            let span = count::<S>(self.bins_in_rate).times(since);
            self.set_bounds(
                self.rate_ft_per_s.times(span - t).over(span),
                self.rate_ft_per_s.times(span + t).over(span),
            );
        } else if ratio < S::ONE {
            self.set_bounds(
                sign_q.over(previous_bin_time),
                c::<S>(RATE_BOUND_MARGIN)
                    .times(change)
                    .over((since - t).max_of(t)),
            );
        } else {
            let outer = q
                .over(time_per_bin)
                .max_of(self.bounds.highest_ft_per_s.abs());
            self.set_bounds(S::ZERO, self.signed(outer));
        }
    }
}

impl<N: Numeric> core::ops::Deref for AltitudeTracker<N> {
    type Target = AltitudeState<N>;

    fn deref(&self) -> &AltitudeState<N> {
        &self.state
    }
}

/// Whole bins in a change of `ratio` quanta (reports are whole quanta, so
/// the ratio is an integer up to rounding), at least 1, saturating.
fn bins_of<S: Scalar>(ratio: S) -> u8 {
    // The usual one-bin change (and NaN) without the f64 rounding: below
    // 1.5, or not comparable, rounds to at most 1 (1.5 is exact in every
    // format, and `to_f64` is exact).
    if !matches!(
        ratio.partial_cmp(&c(1.5)),
        Some(Ordering::Greater | Ordering::Equal)
    ) {
        return 1;
    }
    let r = libm::round(ratio.to_f64());
    if r >= 255.0 {
        u8::MAX
    } else if r >= 1.0 {
        // 1 ≤ r < 255 after the checks, so the cast is exact.
        r as u8
    } else {
        1
    }
}
