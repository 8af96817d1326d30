#!/usr/bin/env bash
# The soak: a simulated operational day (86,400 scans at 1 Hz, 45 intruders,
# detection probability 0.9, 20 clutter returns per scan) through the demo's
# scan loop on an emulated board under -icount shift=0 (boards/qemu/src/bin/soak/),
# checked hour by hour and against the same day run in f64 on the host
# (host-tests/tests/it/firmware/soak.rs). Writes the figures to results/soak-<board>.md.
#
#   scripts/soak.sh [m3 | m4f] [scans]     (default: m3, 86400)
#
# A simulated day takes a few minutes of wall time on either board (the
# results file records it; a loaded machine takes longer).
# The micro:bit's 16 KiB of RAM cannot hold 45 tracks. scripts/test.sh runs
# a one-hour day (3,600 scans) on the Cortex-M3.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

target=$(target_for "${1:-m3}") || die "unknown target '$1'; use m3 or m4f"
board=$(board_for_target "$target")
case "$board" in
    mps2-an385 | mps2-an386) ;;
    *) die "the soak needs 45 tracks: mps2-an385 (m3) or mps2-an386 (m4f), not $board" ;;
esac
scans=${2:-86400}
[[ "$scans" =~ ^[0-9]+$ ]] && [ "$scans" -gt 0 ] || die "scans must be a positive number: $scans"

ensure_targets "$target"
ensure_host_linker
ensure_qemu
ensure_defmt_print

mkdir -p results
results="$PWD/results/soak-$board.md"
say "soak on $board ($target): $scans scans -> $results"
(
    cd host-tests
    ABTRACK_SOAK_SCANS=$scans ABTRACK_SOAK_RESULTS="$results" \
        cargo test --profile "$(host_profile)" --test it -- --ignored --nocapture "firmware::soak::soak_${board//-/_}"
)
