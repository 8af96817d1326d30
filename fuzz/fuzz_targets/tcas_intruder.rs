//! One TCAS intruder's scans with arbitrary replies, intervals and own
//! aircraft: the properties in `fuzz/properties/tcas_intruder.rs`, which
//! the host tests also run on the committed corpus.
#![no_main]

#[path = "../properties/tcas_intruder.rs"]
mod property;

libfuzzer_sys::fuzz_target!(|data: &[u8]| property::check(data));
