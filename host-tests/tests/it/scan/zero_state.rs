//! The firmware's scan-loop state starts as all-zero bytes, so its
//! `static`s go to `.bss` (no flash copy, nothing copied at reset):
//! `Intake::new()` and `ScanLoop::new()` with the demo's types and
//! capacities on the three boards (boards/qemu/src/main.rs, capacity.rs,
//! number_types.rs), and the zero of every number type.

use abtrack::scan::{Intake, ScanLoop};
use abtrack::track::RangeAzimuthTrack;
use abtrack::{Fix, Quantity, ScaledScalar};
use abtrack_firmware::capacity::{microbit, mps2};
use abtrack_firmware::number_types::{cortex_m0, cortex_m3, cortex_m4f};
use std::mem::size_of;

type M4fLoop = ScanLoop<
    cortex_m4f::Wide,
    RangeAzimuthTrack<cortex_m4f::Wide>,
    { mps2::TRACKS },
    { mps2::MEASUREMENTS_PER_SCAN },
>;

// Statics, as the firmware declares them: their bytes are what the
// compiler emits for the image (a value moved through the stack would
// carry whatever its padding and unused slots held there).
static MPS2_INTAKE: Intake<{ mps2::QUEUE_LEN }> = Intake::new();
static MICROBIT_INTAKE: Intake<{ microbit::QUEUE_LEN }> = Intake::new();
static M4F_SCAN_LOOP: M4fLoop = ScanLoop::new();

/// The Cortex-M3's (mps2-an385) demo loop, in the fast fixed point's wide
/// format, and the Cortex-M0's (micro:bit), in software f32.
type M3Loop = ScanLoop<
    cortex_m3::Wide,
    RangeAzimuthTrack<cortex_m3::Wide>,
    { mps2::TRACKS },
    { mps2::MEASUREMENTS_PER_SCAN },
>;
type M0Loop = ScanLoop<
    cortex_m0::Wide,
    RangeAzimuthTrack<cortex_m0::Wide>,
    { microbit::TRACKS },
    { microbit::MEASUREMENTS_PER_SCAN },
>;
static M3_SCAN_LOOP: M3Loop = ScanLoop::new();
static M0_SCAN_LOOP: M0Loop = ScanLoop::new();

/// Offsets of the non-zero bytes of a value.
fn nonzero_offsets<T>(value: &T) -> Vec<usize> {
    // SAFETY: `value` is a live reference to `size_of::<T>()` bytes, read as
    // `u8` (a static's padding and unused slots are emitted as zeros).
    let bytes =
        unsafe { std::slice::from_raw_parts((value as *const T).cast::<u8>(), size_of::<T>()) };
    bytes
        .iter()
        .enumerate()
        .filter(|(_, b)| **b != 0)
        .map(|(i, _)| i)
        .collect()
}

fn assert_zero<T>(name: &str, value: &T) {
    let offsets = nonzero_offsets(value);
    assert!(
        offsets.is_empty(),
        "{name}: {} of {} bytes non-zero, first at offsets {:?}",
        offsets.len(),
        size_of::<T>(),
        &offsets[..offsets.len().min(8)]
    );
}

#[test]
fn intake_starts_all_zero() {
    assert_zero("Intake<mps2::QUEUE_LEN>", &MPS2_INTAKE);
    assert_zero("Intake<microbit::QUEUE_LEN>", &MICROBIT_INTAKE);
}

#[test]
fn the_check_sees_a_non_zero_byte() {
    // The helper itself: a value with one non-zero field is found.
    static SEVEN: [u8; 4] = [0, 0, 7, 0];
    static NONE: Option<bool> = None;
    assert_eq!(nonzero_offsets(&SEVEN), vec![2]);
    assert_eq!(nonzero_offsets(&NONE), vec![0]);
}

/// The demo's scan loop on each board: f32 on the M4F and M0, the fast
/// fixed point's wide format (`ScaledScalar`, whose zero stores its
/// exponent biased) on the M3.
#[test]
fn demo_scan_loop_starts_all_zero_on_every_board() {
    assert_zero("ScanLoop on the mps2-an386 (M4F)", &M4F_SCAN_LOOP);
    assert_zero("ScanLoop on the mps2-an385 (M3)", &M3_SCAN_LOOP);
    assert_zero("ScanLoop on the micro:bit (M0)", &M0_SCAN_LOOP);
}

/// Zero (and `Default`) of every number type is all-zero bytes, the
/// fast fixed point's formats among them.
#[test]
fn every_number_types_zero_is_zero_bytes() {
    static SCALED_ZERO: ScaledScalar = <ScaledScalar as abtrack::Quantity>::ZERO;
    static RATIO_ZERO: abtrack::num::fixed32::Ratio =
        <abtrack::num::fixed32::Ratio as Quantity>::ZERO;
    static LENGTH_ZERO: abtrack::num::fixed32::Length =
        <abtrack::num::fixed32::Length as Quantity>::ZERO;
    static FIX_ZERO: Fix = <Fix as abtrack::Quantity>::ZERO;
    static F32_ZERO: f32 = 0.0;
    assert_zero("ScaledScalar::ZERO", &SCALED_ZERO);
    assert_zero("fixed32::Ratio::ZERO", &RATIO_ZERO);
    assert_zero("fixed32::Length::ZERO", &LENGTH_ZERO);
    assert_zero("Fix::ZERO", &FIX_ZERO);
    assert_zero("f32 zero", &F32_ZERO);
    assert_zero("ScaledScalar::default()", &ScaledScalar::default());
    assert_zero(
        "fixed32::Ratio::default()",
        &abtrack::num::fixed32::Ratio::default(),
    );
    // The zero still behaves as the smallest exponent: a product with it
    // is zero, a sum with it the other operand.
    let x = <ScaledScalar as abtrack::Quantity>::from_f64_lossy(3.5);
    assert_eq!(x * SCALED_ZERO, SCALED_ZERO);
    assert_eq!(x + SCALED_ZERO, x);
    assert_eq!(
        SCALED_ZERO.to_ratio().exponent(),
        abtrack::num::scaled::EXPONENT_MIN
    );
}
