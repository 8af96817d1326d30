#!/usr/bin/env bash
# Runs a firmware ELF under QEMU and decodes its defmt log.
#
#   scripts/qemu-run.sh <qemu-board> <elf>
#
# This is the cargo runner (.cargo/config.toml), so `cargo run --release
# --target <triple> [--bin selftest|bench]` ends up here. The firmware logs
# defmt frames through semihosting to QEMU's stdout, which is piped into
# defmt-print; it leaves QEMU through semihosting SYS_EXIT_EXTENDED, and QEMU's
# exit status is this script's (pipefail), so a failing firmware fails the
# command.
#
# Environment:
#   ABTRACK_QEMU_TIMEOUT  seconds before QEMU is killed (default 600; status 124)
#   ABTRACK_QEMU_ARGS     extra QEMU arguments (word-split)
set -euo pipefail

if [ $# -lt 2 ]; then
    echo "usage: $0 <qemu-board> <elf>" >&2
    exit 2
fi
board=$1
elf=$2

# defmt-print from `cargo install` lives in cargo's bin directory, which a
# non-login shell may not have on PATH.
PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"
for tool in qemu-system-arm defmt-print; do
    if ! command -v "$tool" >/dev/null; then
        echo "qemu-run: $tool not found; run scripts/demo.sh or scripts/test.sh once to install it" >&2
        exit 127
    fi
done

qemu_args=(
    -machine "$board"
    -display none -monitor none -serial none
    # Semihosting carries the defmt log and the exit status.
    -semihosting-config enable=on,target=native
    -kernel "$elf"
)
# The benchmark counts instructions with a timer: make QEMU's virtual clock
# advance exactly 1 ns per instruction (see src/bin/bench.rs).
if [ "$(basename "$elf")" = bench ]; then
    qemu_args+=(-icount shift=0)
fi
if [ -n "${ABTRACK_QEMU_ARGS:-}" ]; then
    # shellcheck disable=SC2206 # word splitting wanted
    qemu_args+=($ABTRACK_QEMU_ARGS)
fi

timeout_s=${ABTRACK_QEMU_TIMEOUT:-600}
set +e
timeout "$timeout_s" qemu-system-arm "${qemu_args[@]}" </dev/null | defmt-print -e "$elf"
status=$?
set -e
if [ "$status" -eq 124 ]; then
    echo "qemu-run: $board did not finish within ${timeout_s}s (ABTRACK_QEMU_TIMEOUT); killed" >&2
elif [ "$status" -ne 0 ]; then
    echo "qemu-run: $(basename "$elf") on $board exited with status $status" >&2
fi
exit "$status"
