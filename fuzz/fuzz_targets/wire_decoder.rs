//! The wire frame decoder on arbitrary bytes: the properties in
//! `fuzz/properties/wire_decoder.rs`, which the host tests also run on the
//! committed corpus.
#![no_main]

#[path = "../properties/wire_decoder.rs"]
mod property;

libfuzzer_sys::fuzz_target!(|data: &[u8]| property::check(data));
