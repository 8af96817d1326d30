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
#                                     never edit them, re-run this)
#   scripts/bench.sh m4f|m3|m0 ...    those cores only (target triples and
#                                     board names work too); writes the two
#                                     files under target/bench/ instead, since
#                                     the committed ones cover all three
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

# The whole images, built first (the targets in one cargo invocation, so
# their link-time optimisations overlap) and checked as the test command
# checks its smoke images; the checks' reports in
# target/bench/elf-checks.log.
mkdir -p target/bench "$out_dir"
elves=() target_args=()
for t in "${targets[@]}"; do
    target_args+=(--target "$t")
    elves+=("target/$t/release/bench")
done
cargo build --quiet --release "${target_args[@]}" --bin bench --features bench-anchors
checks_log=target/bench/elf-checks.log
if check_panic_calls bench "${elves[@]}" >"$checks_log" 2>&1 &&
    check_stack_layout_of "${elves[@]}" >>"$checks_log" 2>&1; then
    say "benchmark images: no call into core::panicking but minikalman's, the stack below the statics ($checks_log)"
else
    tail -n 20 "$checks_log" >&2
    die "a benchmark image failed the ELF checks; the report is in $checks_log"
fi

logs=()
for t in "${targets[@]}"; do
    core=$(core_for_target "$t")
    log="$root/target/bench/$core.log"
    say "benchmark on $(board_for_target "$t") ($core), output in target/bench/$core.log"
    if ! cargo run --quiet --release --target "$t" --bin bench --features bench-anchors >"$log"; then
        tail -n 20 "$log" >&2
        die "the benchmark failed on $(board_for_target "$t"); its output is in $log"
    fi
    logs+=("$log")
done

qemu_version=$(qemu-system-arm --version | head -n 1)
rustc_version=$(rustc --version)
(cd host-tests && cargo run --quiet --release --bin bench_report -- \
    --qemu-version "$qemu_version" \
    --rustc-version "$rustc_version" \
    --csv "$root/$out_dir/results.csv" \
    --markdown "$root/$out_dir/BENCHMARKS.md" \
    "${logs[@]}")
