#!/usr/bin/env bash
# Fault injection on the three boards through the real UART path, and
# repeated runs of the demo compared byte for byte
# (host-tests/tests/it/firmware/fault_injection.rs); writes the outcome tables to
# results/fault-injection-<board>.md, with the whole clutter storm (an
# ABTRACK_CLUTTER_STORM_SCANS in the environment is ignored). scripts/test.sh
# runs the same tests without writing the tables, the clutter storm over 15
# scans.
#
#   scripts/fault-injection.sh [target | board | core ...]   (default: all three)
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

targets=()
for arg in "$@"; do
    targets+=("$(target_for "$arg")") || die "unknown target '$arg'"
done
[ ${#targets[@]} -gt 0 ] || targets=("${ABTRACK_TARGETS[@]}")

ensure_targets "${targets[@]}"
ensure_host_linker
ensure_qemu
ensure_defmt_print

mkdir -p results
for t in "${targets[@]}"; do
    b=$(board_for_target "$t")
    (
        cd host-tests
        env -u ABTRACK_CLUTTER_STORM_SCANS ABTRACK_FAULT_RESULTS="$PWD/../results" \
            cargo test --profile "$(host_profile)" --test it -- --ignored --test-threads=1 \
                "firmware::fault_injection::fault_injection_${b//-/_}" \
                "firmware::fault_injection::demo_runs_are_identical_${b//-/_}"
    )
    say "results/fault-injection-$b.md"
done
