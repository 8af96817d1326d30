//! The firmware's support library, shared by its binaries (the demo,
//! `selftest`, `selftest-tracking`, `soak`, `bench`, `stack-overflow`), by
//! the nRF52840-DK package and, for its hardware-free parts, by the host
//! tests and the fuzz targets:
//!
//! * on every target: the demo's scan-loop configurations
//!   ([`demo_config`]), its capacities per board ([`capacity`]), the number
//!   types per core ([`number_types`]), the synthetic data generator
//!   ([`synth`]) and the self-tests' error propagation bound
//!   ([`propagation`]);
//! * on the boards only (`target_os = "none"`): board support (`board`:
//!   the board and core of this build, the defmt transport, exit, fault
//!   handlers, stack high-water mark), the demo's peripherals (`io`), the
//!   instruction counter under QEMU's `-icount` (`icount`) and the
//!   self-tests' harness (`selftest_support`).
//!
//! The target triple (and the `nrf52840-dk` feature) picks the board:
//! boards/build.rs sets `cfg(abtrack_board = "...")`.
#![no_std]

pub mod capacity;
pub mod demo_config;
pub mod number_types;
pub mod propagation;
pub mod synth;

#[cfg(target_os = "none")]
pub mod board;
#[cfg(target_os = "none")]
pub mod icount;
#[cfg(target_os = "none")]
pub mod io;
#[cfg(target_os = "none")]
#[macro_use]
pub mod selftest_support;
