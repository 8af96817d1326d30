//! The firmware's scan-loop state starts as all-zero bytes, so its
//! `static`s go to `.bss` (no flash copy, nothing copied at reset):
//! `Intake::new()` and `ScanLoop::new()` with the demo's types and
//! capacities (boards/qemu/src/main.rs, capacity.rs, number_types.rs).

use abtrack::scan::{Intake, ScanLoop};
use abtrack::track::RangeAzimuthTrack;
use abtrack_firmware::capacity::{microbit, mps2};
use abtrack_firmware::number_types::with_fpu;
use std::mem::size_of;

type M4fLoop = ScanLoop<
    with_fpu::TableScalar,
    RangeAzimuthTrack<with_fpu::TableScalar>,
    { mps2::TRACKS },
    { mps2::MEASUREMENTS_PER_SCAN },
>;

// Statics, as the firmware declares them: their bytes are what the
// compiler emits for the image (a value moved through the stack would
// carry whatever its padding and unused slots held there).
static MPS2_INTAKE: Intake<{ mps2::QUEUE_LEN }> = Intake::new();
static MICROBIT_INTAKE: Intake<{ microbit::QUEUE_LEN }> = Intake::new();
static M4F_SCAN_LOOP: M4fLoop = ScanLoop::new();

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

/// The M4F demo's scan loop (f32). Not yet the M3's and M0's: their
/// `ScaledScalar` zero has a non-zero exponent (docs/firmware-and-boards.md).
#[test]
fn demo_scan_loop_starts_all_zero_on_the_m4f() {
    assert_zero("ScanLoop on the mps2-an386 (M4F)", &M4F_SCAN_LOOP);
}
