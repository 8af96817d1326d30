#!/usr/bin/env bash
# Flash and RAM used by each release firmware build, per target.
#
#   scripts/sizes.sh
#
# flash = .vector_table + .text + .rodata + .data (its initial values) +
#         .gnu.sgstubs; RAM = .data + .bss + .uninit (static data only: the
# stack comes on top, from the end of RAM down). Builds the firmware first.
# Needs an llvm-size: the rustup component llvm-tools (installed if missing),
# or llvm-size / arm-none-eabi-size on PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

find_size_tool() {
    local sysroot host
    sysroot=$(rustc --print sysroot)
    host=$(rustc -vV | sed -n 's/^host: //p')
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

mapfile -t bins < <(firmware_bins)
printf '%-22s %-11s %-17s %10s %10s\n' target board binary "flash (B)" "RAM (B)"
for t in "${ABTRACK_TARGETS[@]}"; do
    cargo build --quiet --release --target "$t"
    for b in "${bins[@]}"; do
        elf="target/$t/release/$b"
        "$size_tool" -A "$elf" | awk -v t="$t" -v board="$(board_for_target "$t")" -v b="$b" '
            $1 == ".vector_table" || $1 == ".text" || $1 == ".rodata" || $1 == ".gnu.sgstubs" { flash += $2 }
            $1 == ".data" { flash += $2; ram += $2 }
            $1 == ".bss" || $1 == ".uninit" { ram += $2 }
            END { printf "%-22s %-11s %-17s %10d %10d\n", t, board, b, flash, ram }'
    done
done
