#!/usr/bin/env bash
# Runs every test of the project:
#   1. formatting (cargo fmt --check, root crate and host-tests),
#   2. host tests (cd host-tests && cargo test --release),
#   3. the library alone for the three thumb targets (no firmware feature),
#   4. the firmware (demo, self-tests) for the three targets (the benchmark,
#      which needs the feature bench-anchors, is built by step 7),
#   5. the demo and the on-target self-tests (selftest, selftest-tracking)
#      under QEMU on the three boards
#      (mps2-an386 / Cortex-M4F, mps2-an385 / Cortex-M3, microbit / Cortex-M0),
#   6. fault injection and repeated demo runs on the three boards, and a
#      one-hour soak on the Cortex-M3 (docs/firmware-runtime.md),
#   7. a smoke run of the benchmark image on each board: it must run to its
#      end and print a well-formed report (nothing about speed is checked;
#      scripts/bench.sh measures).
#
#   scripts/test.sh
#
# Installs what is missing (Rust targets, rustfmt, qemu-system-arm and a C
# compiler when root, defmt-print). Every step runs even if an earlier one
# failed; the summary lists them and the exit status is non-zero if any
# failed. `.ci/run` calls this.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

ensure_targets "${ABTRACK_TARGETS[@]}"
ensure_rustfmt
ensure_host_linker
ensure_qemu
ensure_defmt_print

results=()
failures=0
log_dir=$(mktemp -d "${TMPDIR:-/tmp}/abtrack-test.XXXXXX")
trap 'rm -rf "$log_dir"' EXIT

# step <name> <command...>: runs one step, records PASS/FAIL.
step() {
    local name=$1
    shift
    say "== $name"
    local status=0
    "$@" || status=$?
    if [ "$status" -eq 0 ]; then
        results+=("PASS  $name")
    else
        results+=("FAIL  $name (exit status $status)")
        failures=$((failures + 1))
    fi
}

in_host_tests() { (cd host-tests && "$@"); }

# The self-test's own verdict is its exit status (through QEMU and the
# pipe); its last line must also be the summary with no failures, so a run
# that stopped early cannot pass.
run_selftest() {
    local target=$1 bin=$2 log="$log_dir/$2-$1.log"
    cargo run --release --target "$target" --bin "$bin" | tee "$log" || return
    tail -n 1 "$log" | grep -Eq '^[0-9]+ passed, 0 failed$' || {
        echo "$bin on $target: no '<N> passed, 0 failed' line at the end" >&2
        return 1
    }
}

step "cargo fmt --check" cargo fmt --check
step "cargo fmt --check (host-tests)" in_host_tests cargo fmt --check
step "host tests (cargo test --release)" in_host_tests cargo test --release
for t in "${ABTRACK_TARGETS[@]}"; do
    step "library alone for $t" cargo build --release --lib --no-default-features --target "$t"
done
for t in "${ABTRACK_TARGETS[@]}"; do
    step "firmware build for $t" cargo build --release --target "$t"
done
for t in "${ABTRACK_TARGETS[@]}"; do
    step "demo on $(board_for_target "$t")" cargo run --release --target "$t" --bin abtrack-firmware
done
# Fault injection through each board's UART (every fault of
# host-tests/src/frames.rs `Fault`), and three runs of the demo compared byte
# for byte, with each other and with the same core run on the host
# (host-tests/tests/fault_injection.rs; about 30 s per board).
for t in "${ABTRACK_TARGETS[@]}"; do
    b=$(board_for_target "$t")
    step "fault injection and repeated runs on $b" in_host_tests \
        cargo test --release --test fault_injection -- --ignored --test-threads=1 "${b//-/_}"
done
# The soak, shortened to one hour of scans (scripts/soak.sh runs the day).
step "soak, one hour, on mps2-an385" in_host_tests env ABTRACK_SOAK_SCANS=3600 \
    cargo test --release --test soak -- --ignored soak_mps2_an385
# Two self-test images (together they do not fit the micro:bit's flash).
for t in "${ABTRACK_TARGETS[@]}"; do
    for bin in selftest selftest-tracking; do
        step "$bin on $(board_for_target "$t")" run_selftest "$t" "$bin"
    done
done

# The benchmark image (its own feature: the minikalman anchor) must run to
# its end and print a complete, well-formed report: bench_report --check
# refuses a malformed line, a missing end line or a line count that differs
# from the end line's. The figures themselves are not checked.
run_bench_smoke() {
    local target=$1 log="$log_dir/bench-$1.log"
    cargo run --release --target "$target" --bin bench --features bench-anchors >"$log" || {
        tail -n 20 "$log" >&2
        return 1
    }
    in_host_tests cargo run --quiet --release --bin bench_report -- --check "$log"
}
for t in "${ABTRACK_TARGETS[@]}"; do
    step "benchmark smoke run on $(board_for_target "$t")" run_bench_smoke "$t"
done

echo
echo "abtrack test summary:"
printf '  %s\n' "${results[@]}"
if [ "$failures" -ne 0 ]; then
    echo "$failures step(s) failed"
    exit 1
fi
echo "all ${#results[@]} steps passed"
