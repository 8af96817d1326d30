//! The per-intruder TCAS state's bytes in the micro:bit's number type
//! (`number_types::cortex_m0::Wide`, software `f32`: every field 4-byte
//! aligned or less and no `usize`, so the host's sizes are the
//! Cortex-M0's; the demo prints its own at start-up). docs/tcas.md, "RAM
//! per intruder", has the table.

use abtrack::filter::altitude::AltitudeState;
use abtrack::scan::ScanLoop;
use abtrack::tcas::{IntruderTrack, RangeTracker, ThreatState};
use abtrack::track::{RangeAzimuthTrack, TrackSlot};
use abtrack_firmware::number_types::cortex_m0::Wide as S;
use std::mem::size_of;

type Loop<const N: usize> = ScanLoop<S, RangeAzimuthTrack<S>, N, 12>;

#[test]
fn per_intruder_state_fits_its_budget() {
    let parts = [
        ("range tracker", size_of::<RangeTracker<S>>(), 28),
        (
            "altitude tracker's state",
            size_of::<AltitudeState<S>>(),
            52,
        ),
        ("threat state", size_of::<ThreatState<S>>(), 28),
        ("intruder track", size_of::<IntruderTrack<S>>(), 108),
    ];
    for (name, size, budget) in parts {
        eprintln!("{name}: {size} B (budget {budget} B)");
    }
    // The scan loop's bytes per track: table slot, gate and TCAS slot
    // (heapless lengths are usize, but the difference of two capacities
    // holds none).
    let per_track = size_of::<Loop<9>>() - size_of::<Loop<8>>();
    eprintln!(
        "scan loop per track: {per_track} B, of which table slot {} B",
        size_of::<TrackSlot<S, RangeAzimuthTrack<S>>>()
    );
    for (name, size, budget) in parts {
        assert!(size <= budget, "{name}: {size} B > {budget} B");
    }
    // What sets the micro:bit's track count (docs/tcas.md, "RAM per
    // intruder").
    assert!(
        per_track <= 288,
        "scan loop per track: {per_track} B > 288 B"
    );
}
