#!/usr/bin/env bash
# The benchmark: instructions per call of every abtrack operation in every
# numeric type the core runs, beside the anchors (a minimal αβ update, a
# hand-written Kalman filter, minikalman), and the track table's scans, on
# the three emulated cores under QEMU -icount (instructions, not cycles).
# Builds and runs the benchmark firmware (boards/qemu/src/bin/bench/, feature
# bench-anchors) on each board, keeps each board's output in
# target/bench/<core>.log, and turns them into the report files with the
# host tool bench_report (host-tests/src/bench_report.rs). Before the
# runs, the images pass the test command's ELF checks (firmware-check: no
# call into core::panicking but minikalman's, the stack below the statics):
# the test command builds only the smoke image (feature bench-smoke).
#
#   scripts/bench.sh                  all three cores; writes bench/results.csv
#                                     and bench/BENCHMARKS.md (generated files:
#                                     never edit them, re-run this), and the
#                                     same two files for the mps2 images built
#                                     at opt-level 3 in bench/opt-level-3/
#   scripts/bench.sh m4f|m3|m0 ...    those cores only (target triples and
#                                     board names work too); writes the files
#                                     under target/bench/ instead (m4f and m3
#                                     also under target/bench/opt-level-3/),
#                                     since the committed ones cover all three
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh
root=$(pwd)

# The core label of each target in the benchmark's output.
core_for_target() {
    case "$1" in
        thumbv7em-none-eabihf) echo m4f ;;
        thumbv7m-none-eabi) echo m3 ;;
        thumbv6m-none-eabi) echo m0 ;;
        *) return 1 ;;
    esac
}

wanted=()
for arg in "$@"; do
    t=$(target_for "$arg") || die "unknown core, board or target '$arg'"
    wanted+=("$t")
done
# Always in the same order (the report's), whatever the order asked.
targets=()
for t in "${ABTRACK_TARGETS[@]}"; do
    if [ ${#wanted[@]} -eq 0 ] || printf '%s\n' "${wanted[@]}" | grep -qx "$t"; then
        targets+=("$t")
    fi
done
if [ ${#targets[@]} -eq ${#ABTRACK_TARGETS[@]} ]; then
    out_dir=bench
else
    out_dir=target/bench
fi

ensure_targets "${targets[@]}"
ensure_qemu
ensure_host_linker
ensure_defmt_print
ensure_llvm_tools

qemu_version=$(qemu-system-arm --version | head -n 1)
rustc_version=$(rustc --version)
# The ELF checker, built once here (in host-tests, as always): the checks
# below run with the opt-level 3 build's cargo environment too.
ABTRACK_FIRMWARE_CHECK=$(firmware_check_tool)
export ABTRACK_FIRMWARE_CHECK

# One benchmark: the images for the targets given, built (in one cargo
# invocation, so their link-time optimisations overlap) and checked as the
# test command checks its smoke images, run on their boards, and their logs
# turned into results.csv and BENCHMARKS.md in DIR. LABEL names the build in
# the messages; cargo's environment (the opt-level, the target directory)
# is the caller's.
#   measure LABEL DIR LOG_DIR TARGET...
measure() {
    local label=$1 dir=$2 log_dir=$3
    shift 3
    local elf_dir=${CARGO_TARGET_DIR:-target}
    local t core log elves=() target_args=() logs=()
    mkdir -p "$log_dir" "$dir"
    for t in "$@"; do
        target_args+=(--target "$t")
        elves+=("$elf_dir/$t/release/bench")
    done
    cargo build --quiet --release "${target_args[@]}" --bin bench --features bench-anchors
    local checks_log=$log_dir/elf-checks.log
    if check_panic_calls bench "${elves[@]}" >"$checks_log" 2>&1 &&
        check_stack_layout_of "${elves[@]}" >>"$checks_log" 2>&1; then
        say "benchmark images ($label): no call into core::panicking but minikalman's, the stack below the statics ($checks_log)"
    else
        tail -n 20 "$checks_log" >&2
        die "a benchmark image ($label) failed the ELF checks; the report is in $checks_log"
    fi
    for t in "$@"; do
        core=$(core_for_target "$t")
        log="$root/$log_dir/$core.log"
        say "benchmark ($label) on $(board_for_target "$t") ($core), output in ${log#"$root"/}"
        if ! cargo run --quiet --release --target "$t" --bin bench --features bench-anchors >"$log"; then
            tail -n 20 "$log" >&2
            die "the benchmark ($label) failed on $(board_for_target "$t"); its output is in $log"
        fi
        logs+=("$log")
    done
    # The host tool in its own target directory, built as always.
    (cd host-tests && env -u CARGO_TARGET_DIR -u CARGO_PROFILE_RELEASE_OPT_LEVEL \
        cargo run --quiet --release --bin bench_report -- \
        --qemu-version "$qemu_version" \
        --rustc-version "$rustc_version" \
        --csv "$root/$dir/results.csv" \
        --markdown "$root/$dir/BENCHMARKS.md" \
        "${logs[@]}")
}

# The firmware's own build: the release profile (opt-level "s").
measure 'opt-level "s"' "$out_dir" target/bench "${targets[@]}"

# The mps2 images again at opt-level 3, Rust's default for release builds:
# what a user of an anchor (minikalman) would build it with unless flash is
# short, and what abtrack costs where flash is not (docs/benchmarks.md). In
# their own target directory, so that neither build replaces the other.
# The micro:bit's image does not fit its 256 KiB of flash at opt-level 3.
wide_flash=()
for t in "${targets[@]}"; do
    [ "$t" = thumbv6m-none-eabi ] || wide_flash+=("$t")
done
if [ ${#wide_flash[@]} -gt 0 ]; then
    CARGO_PROFILE_RELEASE_OPT_LEVEL=3 CARGO_TARGET_DIR="$root/target/opt-level-3" \
        measure 'opt-level 3' "$out_dir/opt-level-3" target/bench/opt-level-3 "${wide_flash[@]}"
fi
