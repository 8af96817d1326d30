#!/usr/bin/env bash
# Writes the demo's default UART input: the `two-crossing` scenario (seed 1)
# as numbered abtrack wire frames ending with an end-of-input frame, with a
# corrupted frame every 97 and 1-16 garbage bytes before every 41st, so the
# receiver's resynchronisation and counters have something to do.
# host-tests/tests/scan_loop.rs runs the same input through the same
# configuration on the host; `frames encode --fault KIND` writes it with one
# of the fault-injection faults instead (docs/firmware-runtime.md).
#
#   scripts/demo-input.sh <output file>
#
# Uses the `frames` tool of host-tests (built on first use).
set -euo pipefail
if [ $# -ne 1 ]; then
    echo "usage: $0 <output file>" >&2
    exit 2
fi
out=$1
case "$out" in
    /*) ;;
    *) out="$PWD/$out" ;;
esac
cd "$(dirname "$0")/../host-tests"
PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"
cargo run --release --quiet --bin frames -- encode \
    --scenario two-crossing --seed 1 --corrupt-every 97 --garbage-every 41 \
    --out "$out" >&2
