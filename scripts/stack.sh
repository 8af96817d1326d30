#!/usr/bin/env bash
# Stack high-water marks of the demo firmware on the three emulated boards,
# for its default input and for each fault input, and of the HardFault
# handler after a stack overflow; fails if any run leaves less than 25 %
# margin (bytes available >= 1.25 x bytes used).
#
#   scripts/stack.sh [--all] [target | board | core ...]   (default: all three)
#
# The demo paints its stack at start and prints `stack: N of M bytes used`
# at the end (boards/qemu/src/board.rs): N counts from the top of the stack to
# the deepest word written, M is the whole stack, from below the static data
# (flip-link) to the bottom of RAM. The fault inputs are written to
# target/stack-inputs/ with the frames tool:
#
#   tcas-demo      the demo's default input (scripts/demo-input.sh)
#   two-crossing   its second input (scripts/demo-input.sh FILE two-crossing)
#   empty          no input at all
#   corrupt        the two-crossing input with every frame's CRC wrong and
#                  1-16 garbage bytes before each
#   flood          2,000 measurements in one scan (capacity: 256, 12 on the micro:bit)
#   replayed       the two-crossing input twice in a row: time goes back at
#                  the join
#   truncated      the first half of the two-crossing input, cut inside a frame
#
# plus every *.bin file in $ABTRACK_STACK_INPUTS (a directory), if set.
# `--all` also reports the self-tests' and the benchmark's deepest test.
# docs/safety.md has the figures.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

all=
targets=()
for arg in "$@"; do
    case "$arg" in
        --all) all=1 ;;
        *) targets+=("$(target_for "$arg")") || die "unknown target '$arg'" ;;
    esac
done
[ ${#targets[@]} -gt 0 ] || targets=("${ABTRACK_TARGETS[@]}")

ensure_targets "${targets[@]}"
ensure_host_linker
ensure_qemu
ensure_defmt_print

MIN_MARGIN_PERCENT=25
inputs_dir="$PWD/target/stack-inputs"
mkdir -p "$inputs_dir"

frames() { (cd host-tests && cargo run --profile "$(host_profile)" --quiet --bin frames -- "$@"); }

# The fault inputs (rewritten each run: they are cheap).
scripts/demo-input.sh "$inputs_dir/tcas-demo.bin" >/dev/null 2>&1
scripts/demo-input.sh "$inputs_dir/two-crossing.bin" two-crossing >/dev/null 2>&1
: >"$inputs_dir/empty.bin"
frames encode --scenario two-crossing --seed 1 --corrupt-every 1 --garbage-every 1 \
    --out "$inputs_dir/corrupt.bin" >/dev/null
{
    echo "t,x,y"
    for i in $(seq 0 1999); do
        echo "1,$((i * 37 % 9000 - 4500)),$((i * 53 % 9000 - 4500))"
    done
} >"$inputs_dir/flood.csv"
frames encode --csv "$inputs_dir/flood.csv" --out "$inputs_dir/flood.bin" >/dev/null
cat "$inputs_dir/two-crossing.bin" "$inputs_dir/two-crossing.bin" >"$inputs_dir/replayed.bin"
size=$(wc -c <"$inputs_dir/two-crossing.bin")
head -c $((size / 2 + 3)) "$inputs_dir/two-crossing.bin" >"$inputs_dir/truncated.bin"

inputs=(tcas-demo two-crossing empty corrupt flood replayed truncated)
input_files=()
for name in "${inputs[@]}"; do
    input_files+=("$inputs_dir/$name.bin")
done
if [ -n "${ABTRACK_STACK_INPUTS:-}" ]; then
    for f in "$ABTRACK_STACK_INPUTS"/*.bin; do
        [ -f "$f" ] || continue
        inputs+=("$(basename "$f" .bin)")
        input_files+=("$f")
    done
fi

failures=0
# report <target> <what> <log>: prints the figures from the log's `stack:`
# line (or the HardFault handler's) and checks the margin.
report() {
    local target=$1 what=$2 log=$3 used available
    read -r used available < <(sed -n 's/.*stack: \([0-9]*\) of \([0-9]*\) bytes used.*/\1 \2/p' "$log" | tail -n 1) || true
    if [ -z "${used:-}" ]; then
        # The benchmark reports in its CSV lines.
        used=$(sed -n 's/.*bench-meta,.*,stack_bytes,\([0-9]*\).*/\1/p' "$log" | tail -n 1)
        available=$(sed -n 's/.*bench-meta,.*,stack_available_bytes,\([0-9]*\).*/\1/p' "$log" | tail -n 1)
    fi
    if [ -z "${used:-}" ]; then
        printf '%-22s %-11s %-34s %s\n' "$target" "$(board_for_target "$target")" "$what" "no stack line in the output"
        failures=$((failures + 1))
        return
    fi
    local margin=$(((available - used) * 100 / used)) verdict=ok
    if [ "$margin" -lt "$MIN_MARGIN_PERCENT" ]; then
        verdict="LESS THAN ${MIN_MARGIN_PERCENT} %"
        failures=$((failures + 1))
    fi
    printf '%-22s %-11s %-34s %10d %12d %9d %%  %s\n' "$target" "$(board_for_target "$target")" "$what" "$used" "$available" "$margin" "$verdict"
}

log_dir=$(mktemp -d "${TMPDIR:-/tmp}/abtrack-stack.XXXXXX")
trap 'rm -rf "$log_dir"' EXIT

# run <log> <target> <bin> [env...]: one image under QEMU (the target's
# runner, scripts/qemu-run.sh), its output in <log>; the exit status does
# not matter here (the stack figure does).
run() {
    local log=$1 target=$2 bin=$3
    shift 3
    env "$@" scripts/qemu-run.sh "$(board_for_target "$target")" \
        "target/$target/release/$bin" >"$log" 2>&1 || true
}

# Every run of a target at once, then the reports in order: a run mostly
# waits (the demo ends an input without its end frame after 10 s of
# silence), and its figures depend only on its input.
printf '%-22s %-11s %-34s %10s %12s %11s\n' target board "run (input)" "used (B)" "stack (B)" margin
for t in "${targets[@]}"; do
    cargo build --quiet --release --target "$t" --bin abtrack-firmware --bin stack-overflow
    [ -z "$all" ] || cargo build --quiet --release --target "$t" --bin selftest --bin selftest-tracking
    [ -z "$all" ] || cargo build --quiet --release --target "$t" --features bench-anchors --bin bench
    for i in "${!inputs[@]}"; do
        run "$log_dir/$t-demo-$i" "$t" abtrack-firmware \
            ABTRACK_UART_INPUT="${input_files[$i]}" ABTRACK_UART_OUTPUT=/dev/null &
    done
    run "$log_dir/$t-overflow" "$t" stack-overflow &
    if [ -n "$all" ]; then
        for bin in selftest selftest-tracking bench; do
            run "$log_dir/$t-$bin" "$t" "$bin" &
        done
    fi
    wait
    for i in "${!inputs[@]}"; do
        report "$t" "demo (${inputs[$i]})" "$log_dir/$t-demo-$i"
    done
    # The HardFault handler after an overflow: its own high-water mark on
    # the stack it resets to, out of the whole stack.
    log=$log_dir/$t-overflow
    used=$(sed -n 's/.*hard fault handler: \([0-9]*\) bytes of stack used.*/\1/p' "$log")
    available=$(sed -n 's/.*: \([0-9]*\) bytes of stack below the statics.*/\1/p' "$log")
    printf 'stack: %s of %s bytes used\n' "${used:-}" "${available:-}" >"$log"
    if [ -n "$used" ] && [ -n "$available" ]; then
        report "$t" "hard-fault handler (overflow)" "$log"
    else
        report "$t" "hard-fault handler (overflow)" /dev/null
    fi
    if [ -n "$all" ]; then
        for bin in selftest selftest-tracking bench; do
            report "$t" "$bin (deepest)" "$log_dir/$t-$bin"
        done
    fi
done
if [ "$failures" -ne 0 ]; then
    echo "$failures run(s) without a stack figure or with less than ${MIN_MARGIN_PERCENT} % margin" >&2
    exit 1
fi
