//! The CSV reader on arbitrary bytes: the properties in
//! `fuzz/properties/csv_recording.rs`, which the host tests also run on the
//! committed corpus.
#![no_main]

#[path = "../properties/csv_recording.rs"]
mod property;

libfuzzer_sys::fuzz_target!(|data: &[u8]| property::check(data));
