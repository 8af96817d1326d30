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
# The demo firmware (abtrack-firmware) reads measurement frames on its UART
# (mps2: CMSDK UART0; microbit: the nRF51 UART) and writes report frames back.
# Its serial port is a QEMU `pipe` chardev on two regular files in a temporary
# directory: `uart.in`, a copy of the input, which QEMU reads as fast as the
# firmware takes it; `uart.out`, which receives the transmitted bytes and is
# copied to the output file when QEMU exits. Semihosting (the defmt log and
# the exit status) stays on QEMU's stdout, so the two streams never mix.
# (QEMU 7.2's `file` chardev has no input side.)
#
# Environment:
#   ABTRACK_QEMU_TIMEOUT  seconds before QEMU is killed (default 600; status 124)
#   ABTRACK_QEMU_ARGS     extra QEMU arguments (word-split)
#   ABTRACK_UART_INPUT    the demo's UART input (wire frames); default: the
#                         TCAS scenario, written by scripts/demo-input.sh
#                         to target/demo/tcas-demo-seed1.bin
#   ABTRACK_UART_OUTPUT   where the demo's UART output goes (default
#                         target/demo/uart-<board>.out)
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

root=$(cd "$(dirname "$0")/.." && pwd)
qemu_args=(
    -machine "$board"
    -display none -monitor none
    # Semihosting carries the defmt log and the exit status.
    -semihosting-config enable=on,target=native
    -kernel "$elf"
)
uart_dir=
uart_output=
if [ "$(basename "$elf")" = abtrack-firmware ]; then
    if [ -n "${ABTRACK_UART_INPUT:-}" ]; then
        uart_input=$ABTRACK_UART_INPUT
        [ -f "$uart_input" ] || {
            echo "qemu-run: ABTRACK_UART_INPUT=$uart_input: no such file" >&2
            exit 2
        }
    else
        uart_input="$root/target/demo/tcas-demo-seed1.bin"
        mkdir -p "$(dirname "$uart_input")"
        "$root/scripts/demo-input.sh" "$uart_input"
    fi
    uart_output=${ABTRACK_UART_OUTPUT:-"$root/target/demo/uart-$board.out"}
    mkdir -p "$(dirname "$uart_output")"
    uart_dir=$(mktemp -d "${TMPDIR:-/tmp}/abtrack-uart.XXXXXX")
    trap 'rm -rf "$uart_dir"' EXIT
    cp "$uart_input" "$uart_dir/uart.in"
    : >"$uart_dir/uart.out"
    qemu_args+=(-chardev "pipe,id=uart0,path=$uart_dir/uart" -serial chardev:uart0)
    echo "qemu-run: UART input $uart_input ($(wc -c <"$uart_input") bytes), output -> $uart_output" >&2
else
    qemu_args+=(-serial none)
fi
# The benchmark counts instructions with a timer: make QEMU's virtual clock
# advance exactly 1 ns per instruction (see boards/qemu/src/bin/bench/).
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
if [ -n "$uart_dir" ]; then
    cp "$uart_dir/uart.out" "$uart_output"
fi
if [ "$status" -eq 124 ]; then
    echo "qemu-run: $board did not finish within ${timeout_s}s (ABTRACK_QEMU_TIMEOUT); killed" >&2
elif [ "$status" -ne 0 ]; then
    echo "qemu-run: $(basename "$elf") on $board exited with status $status" >&2
fi
exit "$status"
