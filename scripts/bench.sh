#!/usr/bin/env bash
# Instructions per filter update (αβ, αβγ, 2-D αβ; f32, fixed point, f64) on
# the three emulated cores. Builds and runs the benchmark firmware
# (src/bin/bench.rs) under QEMU with -icount shift=0; prints figures, not a
# test. The README's benchmark table comes from this.
#
#   scripts/bench.sh [target | board | core ...]   (default: all three)
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
ensure_qemu
ensure_defmt_print

for t in "${targets[@]}"; do
    cargo run --quiet --release --target "$t" --bin bench
done
