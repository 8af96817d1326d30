//! Counting instructions with SysTick under `-icount shift=0`, and the
//! benchmark's output lines.
//!
//! Every figure leaves the firmware as one line, read by the host tool
//! `bench_report` (host-tests/src/bench_report.rs, which documents the
//! format and refuses anything else):
//!
//! ```text
//! bench-meta,<core>,<key>,<value>
//! bench-figure,<core>,<numeric>,<operation>,<n>,<m>,<instructions>
//! bench-count,<core>,<numeric>,<operation>,<n>,<m>,<counter>,<value>
//! bench-omitted,<core>,<numeric>,<operation>,<reason>
//! bench-end,<core>,<figures>,<counts>
//! ```
//!
//! `n` and `m` (tracks, measurements per scan) are empty where they do not
//! apply; `instructions` has one decimal. The end line carries how many
//! figure and count lines came before it, so a run cut short is detected.

use core::hint::black_box;

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;

use crate::board;
use crate::CALLS;

/// SysTick's counter is 24 bits wide.
const SYSTICK_MAX: u32 = 0x00ff_ffff;

/// Why a row is not measured in a number system on this core (the
/// `reason` of a `bench-omitted` line; bench_report explains each).
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Omission {
    /// The image would not fit the board's flash with this row's code.
    Flash,
    /// The comparison image (feature `bench-microbit-scaled-tcas`) holds
    /// only the TCAS rows in `ScaledScalar`.
    Comparison,
}

impl Omission {
    fn reason(self) -> &'static str {
        match self {
            Omission::Flash => "flash",
            Omission::Comparison => "comparison",
        }
    }
}

/// Tracks and measurements per scan, for the scan rows.
#[derive(Clone, Copy)]
pub struct Size {
    pub n: usize,
    pub m: usize,
}

/// SysTick as a free-running down-counter of the core clock.
struct Ticks {
    syst: SYST,
}

impl Ticks {
    fn new(mut syst: SYST) -> Self {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(SYSTICK_MAX);
        syst.clear_current();
        syst.enable_counter();
        Ticks { syst }
    }

    /// Ticks taken by `work`, or `None` if the counter did not run or wrapped
    /// (the measurement would be meaningless).
    fn time(&mut self, work: impl FnOnce()) -> Option<u32> {
        self.syst.clear_current();
        // Writing the counter zeroes it; it reloads on the next tick. Wait
        // for that (boundedly: a counter that never runs must not hang us).
        let mut spins = 0u32;
        while SYST::get_current() == 0 {
            spins += 1;
            if spins > 100_000 {
                return None;
            }
        }
        let _ = self.syst.has_wrapped(); // reading clears COUNTFLAG
        let start = SYST::get_current();
        work();
        let end = SYST::get_current();
        if self.syst.has_wrapped() || end > start {
            return None;
        }
        Some(start - end)
    }
}

/// The core's label in the output: `m4f`, `m3`, `m0`.
fn core_label() -> &'static str {
    match board::BOARD {
        "mps2-an386" => "m4f",
        "mps2-an385" => "m3",
        "microbit" => "m0",
        other => other,
    }
}

/// The measuring instrument: the calibrated counter and the output lines.
pub struct Bench {
    ticks: Ticks,
    core: &'static str,
    instructions_per_tick: f64,
    figures: u32,
    counts: u32,
    failures: u32,
}

impl Bench {
    /// Starts SysTick and calibrates it on a loop of known length; `None`
    /// (and an error line) if it does not count.
    pub fn start(syst: SYST) -> Option<Self> {
        let mut ticks = Ticks::new(syst);
        const LOOPS: u32 = 1_000_000;
        let core = core_label();
        let instructions_per_tick =
            match ticks.time(|| crate::icount::known_instructions(black_box(LOOPS))) {
                Some(t) if t > 0 => (2 * LOOPS) as f64 / t as f64,
                _ => {
                    defmt::error!("SysTick does not count on this board; no figures");
                    return None;
                }
            };
        defmt::println!(
            "abtrack bench on {=str} ({=str}): instructions per call under QEMU -icount shift=0 (instructions, not cycles)",
            board::BOARD,
            board::CORE
        );
        defmt::println!("bench-meta,{=str},board,{=str}", core, board::BOARD);
        defmt::println!("bench-meta,{=str},core,{=str}", core, board::CORE);
        defmt::println!("bench-meta,{=str},opt_level,{=str}", core, board::OPT_LEVEL);
        defmt::println!(
            "bench-meta,{=str},instructions_per_tick,{=f32}",
            core,
            instructions_per_tick as f32
        );
        defmt::println!("bench-meta,{=str},calls,{=u32}", core, CALLS);
        defmt::println!(
            "bench-meta,{=str},scans,{=u32}",
            core,
            crate::scan::TIMED_SCANS
        );
        Some(Bench {
            ticks,
            core,
            instructions_per_tick,
            figures: 0,
            counts: 0,
            failures: 0,
        })
    }

    /// Ticks taken by `work` (see [`Ticks::time`]).
    pub fn time(&mut self, work: impl FnOnce()) -> Option<u32> {
        self.ticks.time(work)
    }

    /// Ticks to instructions.
    pub fn instructions(&self, ticks: u32) -> f64 {
        ticks as f64 * self.instructions_per_tick
    }

    /// Measures and reports instructions per call of `work(k)`, k = 0 ..
    /// [`CALLS`], net of the same loop over `baseline(k)` (what the loop
    /// costs without the measured call). False (and an error line) if the
    /// counter wrapped or the work cost less than its baseline.
    pub fn per_call(
        &mut self,
        numeric: &'static str,
        operation: &'static str,
        mut work: impl FnMut(u32),
        mut baseline: impl FnMut(u32),
    ) -> bool {
        let base = self.time(|| {
            for k in 0..CALLS {
                baseline(k);
            }
        });
        let total = self.time(|| {
            for k in 0..CALLS {
                work(k);
            }
        });
        match (total, base) {
            (Some(t), Some(b)) if t >= b => {
                let per_call = self.instructions(t - b) / CALLS as f64;
                self.figure(numeric, operation, None, per_call);
                true
            }
            _ => {
                self.fail(numeric, operation, "timing wrapped or below its baseline");
                false
            }
        }
    }

    /// [`Bench::per_call`] for a call that says whether it was accepted
    /// (`work` returns false for a refused update): a refusal fails the
    /// figure, which would otherwise time the refusal path.
    pub fn per_accepted_call(
        &mut self,
        numeric: &'static str,
        operation: &'static str,
        mut work: impl FnMut(u32) -> bool,
        baseline: impl FnMut(u32),
    ) {
        let mut refused = 0u32;
        self.per_call(
            numeric,
            operation,
            |k| refused += u32::from(!work(k)),
            baseline,
        );
        self.check(refused == 0, numeric, operation, "calls refused");
    }

    /// Reports one figure (instructions per call).
    pub fn figure(
        &mut self,
        numeric: &str,
        operation: &str,
        size: Option<Size>,
        instructions: f64,
    ) {
        // One decimal, rounded half up (the figure is never negative).
        let tenths = (instructions * 10.0 + 0.5) as u64;
        let (whole, tenth) = (tenths / 10, tenths % 10);
        let core = self.core;
        match size {
            Some(Size { n, m }) => defmt::println!(
                "bench-figure,{=str},{=str},{=str},{=usize},{=usize},{=u64}.{=u64}",
                core,
                numeric,
                operation,
                n,
                m,
                whole,
                tenth
            ),
            None => defmt::println!(
                "bench-figure,{=str},{=str},{=str},,,{=u64}.{=u64}",
                core,
                numeric,
                operation,
                whole,
                tenth
            ),
        }
        self.figures += 1;
    }

    /// Reports one count (events of a scan, cluster sizes).
    pub fn count(&mut self, numeric: &str, operation: &str, size: Size, counter: &str, value: u32) {
        defmt::println!(
            "bench-count,{=str},{=str},{=str},{=usize},{=usize},{=str},{=u32}",
            self.core,
            numeric,
            operation,
            size.n,
            size.m,
            counter,
            value
        );
        self.counts += 1;
    }

    /// Reports that `operations` are not measured in `numeric` here, and why.
    pub fn omitted_group(&mut self, numeric: &str, operations: &[&str], why: Omission) {
        for operation in operations {
            defmt::println!(
                "bench-omitted,{=str},{=str},{=str},{=str}",
                self.core,
                numeric,
                operation,
                why.reason()
            );
        }
    }

    /// Reports a failed measurement or check; the run then fails.
    pub fn fail(&mut self, numeric: &str, operation: &str, why: &str) {
        defmt::error!(
            "{=str} {=str} {=str}: {=str}",
            self.core,
            numeric,
            operation,
            why
        );
        self.failures += 1;
    }

    /// [`Bench::fail`] unless `ok`.
    pub fn check(&mut self, ok: bool, numeric: &str, operation: &str, why: &str) {
        if !ok {
            self.fail(numeric, operation, why);
        }
    }

    /// The stack high-water mark and the end line; true if nothing failed.
    pub fn finish(self) -> bool {
        let (stack_used, stack_available) = board::stack_usage();
        defmt::println!(
            "bench-meta,{=str},stack_bytes,{=u32}",
            self.core,
            stack_used
        );
        defmt::println!(
            "bench-meta,{=str},stack_available_bytes,{=u32}",
            self.core,
            stack_available
        );
        if self.failures > 0 {
            defmt::error!("{=u32} measurement(s) failed; no end line", self.failures);
            return false;
        }
        defmt::println!(
            "bench-end,{=str},{=u32},{=u32}",
            self.core,
            self.figures,
            self.counts
        );
        true
    }
}
