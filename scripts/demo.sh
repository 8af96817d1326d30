#!/usr/bin/env bash
# The main job: the demo firmware (αβ and αβγ filters tracking a synthetic
# target) under qemu-system-arm, its defmt log decoded on the terminal.
#
#   scripts/demo.sh [target | board | core]
#
# Default: thumbv7em-none-eabihf on mps2-an386 (Cortex-M4F, f32). Also:
# thumbv7m-none-eabi / mps2-an385 / m3 (Cortex-M3, fixed point) and
# thumbv6m-none-eabi / microbit / m0 (Cortex-M0, fixed point).
# Installs what is missing (the Rust target, qemu-system-arm when root,
# defmt-print). The exit status is the firmware's.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

target=$(target_for "${1:-thumbv7em-none-eabihf}") ||
    die "unknown target '$1'; use one of: ${ABTRACK_TARGETS[*]} (or mps2-an386, mps2-an385, microbit)"

ensure_targets "$target"
ensure_qemu
ensure_defmt_print

say "demo firmware on $(board_for_target "$target") ($target)"
cargo run --release --target "$target" --bin abtrack-firmware
