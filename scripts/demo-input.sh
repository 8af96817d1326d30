#!/usr/bin/env bash
# Writes the demo's UART input: by default the TCAS demo scenario
# (`tcas-demo`, seed 1: four intruders from 14 NM at 1 Hz, Mode S and Mode C
# replies with range, bearing and 100/25 ft altitude, false replies; see
# docs/tcas.md, "The demo"), or the scenario named as the second argument
# (e.g. `two-crossing`, the two crossing targets of the multi-target
# scenarios), as numbered abtrack wire frames ending with an end-of-input
# frame, with a corrupted frame every 97 and 1-16 garbage bytes before every
# 41st, so the receiver's resynchronisation and counters have something to
# do. host-tests/tests/it/firmware/tcas_demo.rs runs the same input through the same
# configuration on the host; `frames encode --fault KIND` writes the
# fault-injection inputs instead (docs/firmware-runtime.md).
#
#   scripts/demo-input.sh <output file> [scenario]
#
# Uses the `frames` tool of host-tests (built on first use).
set -euo pipefail
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
    echo "usage: $0 <output file> [scenario (default tcas-demo)]" >&2
    exit 2
fi
out=$1
scenario=${2:-tcas-demo}
case "$out" in
    /*) ;;
    *) out="$PWD/$out" ;;
esac
# shellcheck source=scripts/setup.sh
. "$(dirname "$0")/setup.sh"
cd "$(dirname "$0")/../host-tests"
cargo run --profile "$(host_profile)" --quiet --bin frames -- encode \
    --scenario "$scenario" --seed 1 --corrupt-every 97 --garbage-every 41 \
    --out "$out" >&2
