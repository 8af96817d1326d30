//! A whole tracker scan with arbitrary measurements and times: the
//! properties in `fuzz/properties/tracker_scan.rs`, which the host tests
//! also run on the committed corpus.
#![no_main]

#[path = "../properties/tracker_scan.rs"]
mod property;

libfuzzer_sys::fuzz_target!(|data: &[u8]| property::check(data));
