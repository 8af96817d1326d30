//! The TCAS scan loop with arbitrary replies and times: the properties in
//! `fuzz/properties/scan_loop.rs`, which the host tests also run on the
//! committed corpus.
#![no_main]

#[path = "../properties/scan_loop.rs"]
mod property;

libfuzzer_sys::fuzz_target!(|data: &[u8]| property::check(data));
