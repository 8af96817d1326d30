#!/usr/bin/env bash
# Flash and RAM used by each release firmware build, per target.
#
#   scripts/sizes.sh                  the three emulated boards, every binary
#   scripts/sizes.sh --nrf52840-dk    the nRF52840-DK's demo (boards/nrf52840-dk)
#
# flash = .vector_table + .text + .rodata + .data (its initial values) +
#         .gnu.sgstubs; RAM = .data + .bss + .uninit (static data only: the
# stack takes the rest of RAM, below the statics: flip-link). Builds the
# firmware first.
# Needs an llvm-size: the rustup component llvm-tools (installed if missing),
# or llvm-size / arm-none-eabi-size on PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

find_size_tool() {
    local sysroot host
    sysroot=$(rustc --print sysroot)
    host=$(host_triple)
    local candidates=("$sysroot/lib/rustlib/$host/bin/llvm-size")
    local c
    for c in "${candidates[@]}"; do
        [ -x "$c" ] && {
            echo "$c"
            return
        }
    done
    for c in llvm-size $(compgen -c llvm-size- | sort -rV) arm-none-eabi-size; do
        command -v "$c" >/dev/null && {
            command -v "$c"
            return
        }
    done
    return 1
}

ensure_targets "${ABTRACK_TARGETS[@]}"
size_tool=$(find_size_tool) || {
    command -v rustup >/dev/null || die "no llvm-size found: install llvm (llvm-size) or binutils-arm-none-eabi, then re-run"
    say "rustup component add llvm-tools"
    rustup component add llvm-tools
    size_tool=$(find_size_tool) || die "llvm-tools installed but llvm-size not found"
}

# size_row <target> <board> <binary> <elf>
size_row() {
    "$size_tool" -A "$4" | awk -v t="$1" -v board="$2" -v b="$3" '
        $1 == ".vector_table" || $1 == ".text" || $1 == ".rodata" || $1 == ".gnu.sgstubs" { flash += $2 }
        $1 == ".data" { flash += $2; ram += $2 }
        $1 == ".bss" || $1 == ".uninit" { ram += $2 }
        END { printf "%-22s %-11s %-19s %10d %10d\n", t, board, b, flash, ram }'
}

printf '%-22s %-11s %-19s %10s %10s\n' target board binary "flash (B)" "RAM (B)"
if [ "${1:-}" = --nrf52840-dk ]; then
    # The real board's demo, built by its own package (boards/nrf52840-dk)
    # into the repository's target directory.
    (cd boards/nrf52840-dk && cargo build --quiet --release)
    size_row thumbv7em-none-eabihf nrf52840-dk abtrack-nrf52840-dk \
        target/thumbv7em-none-eabihf/release/abtrack-nrf52840-dk
    exit
fi
mapfile -t bins < <(firmware_bins)
for t in "${ABTRACK_TARGETS[@]}"; do
    cargo build --quiet --release --target "$t" --features bench-anchors
    for b in "${bins[@]}"; do
        size_row "$t" "$(board_for_target "$t")" "$b" "target/$t/release/$b"
    done
done
