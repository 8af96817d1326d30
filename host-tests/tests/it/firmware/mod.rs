//! The firmware: its demo and scan loop on the host, the fuzzers' and runtime
//! findings, and (ignored by default: they need QEMU) fault injection and
//! the soak on the emulated boards.

mod fault_injection;
mod fuzz_findings;
mod runtime_findings;
mod soak;
mod tcas_demo;
