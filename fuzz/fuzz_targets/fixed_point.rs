//! Q32.32 fixed point on arbitrary raw words: the properties in
//! `fuzz/properties/fixed_point.rs`, which the host tests also run on the
//! committed corpus.
#![no_main]

#[path = "../properties/fixed_point.rs"]
mod property;

libfuzzer_sys::fuzz_target!(|words: property::Words| property::check_words(words));
