//! The host tests, one binary with a module per capability (a single link
//! instead of one per file). Run a capability or one test by its path:
//!
//! ```text
//! cd host-tests && cargo test --release --test it tcas::
//! cd host-tests && cargo test --release --test it firmware::soak -- --ignored
//! ```
//!
//! proptest keeps the seeds of past failures where its default persistence
//! puts them for a test crate rooted at this main.rs:
//! `tests/proptest-regressions/<group>/<file>.txt`.

mod claims;
mod filter;
mod firmware;
mod fuzz_corpora;
mod gain;
mod num;
mod scan;
mod tcas;
mod tools;
mod track;
mod wire;
