//! Every fuzz target's committed corpus (`fuzz/corpus/<target>/`) run
//! through the target's properties (`fuzz/properties/`, the same source the
//! cargo-fuzz targets wrap): each input that once found a new path must
//! still pass. The fuzzing itself is `scripts/fuzz.sh` (nightly,
//! cargo-fuzz). The fuzz profile turns on overflow checks (and debug
//! assertions, which the library does not use); the `checks` profile turns
//! them on for the library, the CSV reader and the firmware's host modules
//! (host-tests/Cargo.toml), not for the properties themselves, whose
//! arithmetic is wrapping or in i128.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

#[path = "../../../../fuzz/properties/csv_recording.rs"]
mod csv_recording;
#[path = "../../../../fuzz/properties/fixed_point.rs"]
mod fixed_point;
#[path = "../../../../fuzz/properties/scan_loop.rs"]
mod scan_loop;
#[path = "../../../../fuzz/properties/tcas_intruder.rs"]
mod tcas_intruder;
#[path = "../../../../fuzz/properties/tracker_scan.rs"]
mod tracker_scan;
#[path = "../../../../fuzz/properties/wire_decoder.rs"]
mod wire_decoder;

fn corpus(target: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/corpus")
        .join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

/// Runs `check` on every input of the target's corpus, the inputs spread
/// over the cores; fails naming each input whose check panicked.
fn replay(target: &str, check: fn(&[u8])) {
    let files = corpus(target);
    assert!(!files.is_empty(), "fuzz/corpus/{target}/ is empty");
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = files.len().div_ceil(threads);
    let failed: Vec<String> = std::thread::scope(|s| {
        let workers: Vec<_> = files
            .chunks(chunk)
            .map(|inputs| {
                s.spawn(move || {
                    inputs
                        .iter()
                        .filter(|path| {
                            let data = std::fs::read(path).unwrap();
                            catch_unwind(AssertUnwindSafe(|| check(&data))).is_err()
                        })
                        .map(|path| path.display().to_string())
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap())
            .collect()
    });
    assert!(
        failed.is_empty(),
        "{} of {} inputs of fuzz/corpus/{target}/ fail (reproduce with \
         `cd fuzz && cargo +nightly fuzz run --release --sanitizer none {target} <input>`): {failed:?}",
        failed.len(),
        files.len()
    );
}

#[test]
fn csv_recording_corpus() {
    replay("csv_recording", csv_recording::check);
}

#[test]
fn fixed_point_corpus() {
    replay("fixed_point", fixed_point::check);
}

#[test]
fn scan_loop_corpus() {
    replay("scan_loop", scan_loop::check);
}

#[test]
fn tcas_intruder_corpus() {
    replay("tcas_intruder", tcas_intruder::check);
}

#[test]
fn tracker_scan_corpus() {
    replay("tracker_scan", tracker_scan::check);
}

#[test]
fn wire_decoder_corpus() {
    replay("wire_decoder", wire_decoder::check);
}
