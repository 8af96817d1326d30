//! The host tests, one binary with a module per capability (a single link
//! instead of one per file). Run a capability or one test by its path:
//!
//! ```text
//! cd host-tests && cargo test --release --test it tcas::
//! cd host-tests && cargo test --release --test it firmware::soak -- --ignored
//! ```

mod claims;
mod filter;
mod firmware;
mod gain;
mod num;
mod scan;
mod tcas;
mod tools;
mod track;
mod wire;
