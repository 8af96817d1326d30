#!/usr/bin/env bash
# The main job: the scan-loop demo firmware under qemu-system-arm. Measurement
# frames go in on the board's UART, the firmware tracks, assesses and logs
# through defmt (decoded on the terminal), and sends report frames back on
# the UART; those are decoded on the host at the end.
#
#   scripts/demo.sh [target | board | core] [frames file]
#
# Default: thumbv7em-none-eabihf on mps2-an386 (Cortex-M4F, f32). Also:
# thumbv7m-none-eabi / mps2-an385 / m3 (Cortex-M3, fixed point) and
# thumbv6m-none-eabi / microbit / m0 (Cortex-M0, fixed point).
# Input: the given frames file, or by default the TCAS scenario written by
# scripts/demo-input.sh (the second input, the two crossing targets:
# `scripts/demo-input.sh FILE two-crossing`, then `scripts/demo.sh T FILE`;
# make your own with the `frames` tool: docs/firmware-runtime.md). Installs what is missing (the
# Rust target, qemu-system-arm when root, defmt-print). The exit status is
# the firmware's: 0 for a clean run (docs/firmware-runtime.md, "Exit status
# and health"), or 1 if the report frames on the UART are not clean frames.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

target=$(target_for "${1:-thumbv7em-none-eabihf}") ||
    die "unknown target '$1'; use one of: ${ABTRACK_TARGETS[*]} (or mps2-an386, mps2-an385, microbit)"
board=$(board_for_target "$target")
if [ $# -ge 2 ]; then
    [ -f "$2" ] || die "no such frames file: $2"
    export ABTRACK_UART_INPUT=$2
fi
export ABTRACK_UART_OUTPUT="$PWD/target/demo/uart-$board.out"

ensure_targets "$target"
ensure_host_linker
ensure_qemu
ensure_defmt_print

say "demo firmware on $board ($target)"
status=0
cargo run --release --target "$target" --bin abtrack-firmware || status=$?
if [ -s "$ABTRACK_UART_OUTPUT" ]; then
    say "the firmware's UART output ($ABTRACK_UART_OUTPUT), decoded on the host:"
    if ! (cd host-tests && cargo run --profile "$(host_profile)" --quiet --bin frames -- decode --check "$ABTRACK_UART_OUTPUT") &&
        [ "$status" -eq 0 ]; then
        status=1
    fi
fi
exit "$status"
