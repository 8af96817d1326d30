//! The firmware's scan-loop state starts as all-zero bytes, so its
//! `static`s go to `.bss` (no flash copy, nothing copied at reset):
//! `Intake::new()` and `ScanLoop::new()` with the demo's types and
//! capacities (boards/qemu/src/main.rs, capacity.rs, number_types.rs).

use abtrack::scan::{Intake, ScanLoop};
use abtrack::track::RangeAzimuthTrack;
use abtrack_firmware::capacity::{microbit, mps2};
use abtrack_firmware::number_types::with_fpu;
use std::mem::{size_of, MaybeUninit};

/// Offsets of the non-zero bytes of `make()`'s value, written into a zeroed
/// allocation (padding reads as the allocation's zeros or the constant's).
fn nonzero_offsets<T>(make: impl FnOnce() -> T) -> Vec<usize> {
    let mut slot: Box<MaybeUninit<T>> = Box::new_zeroed();
    slot.write(make());
    // SAFETY: the allocation is `size_of::<T>()` bytes, zeroed before the
    // write; bytes are read as `u8`, and the value is dropped afterwards.
    let bytes = unsafe { std::slice::from_raw_parts(slot.as_ptr().cast::<u8>(), size_of::<T>()) };
    let offsets = bytes
        .iter()
        .enumerate()
        .filter(|(_, b)| **b != 0)
        .map(|(i, _)| i)
        .collect();
    // SAFETY: initialised by the write above.
    drop(unsafe { slot.assume_init() });
    offsets
}

fn assert_zero<T>(name: &str, make: impl FnOnce() -> T) {
    let offsets = nonzero_offsets(make);
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
    assert_zero(
        "Intake<mps2::QUEUE_LEN>",
        Intake::<{ mps2::QUEUE_LEN }>::new,
    );
    assert_zero(
        "Intake<microbit::QUEUE_LEN>",
        Intake::<{ microbit::QUEUE_LEN }>::new,
    );
}

#[test]
fn the_check_sees_a_non_zero_byte() {
    // The helper itself: a value with one non-zero field is found.
    assert_eq!(nonzero_offsets(|| [0u8, 0, 7, 0]), vec![2]);
    assert_eq!(nonzero_offsets(|| Option::<bool>::None), vec![0]);
}

/// The M4F demo's scan loop (f32). Not yet the M3's and M0's: their
/// `ScaledScalar` zero has a non-zero exponent (docs/firmware-and-boards.md).
#[test]
fn demo_scan_loop_starts_all_zero_on_the_m4f() {
    type M4f = with_fpu::TableScalar;
    assert_zero("ScanLoop on the mps2-an386 (M4F)", || {
        ScanLoop::<M4f, RangeAzimuthTrack<M4f>, { mps2::TRACKS }, { mps2::MEASUREMENTS_PER_SCAN }>::new()
    });
}
