#!/usr/bin/env bash
# Runs every test of the project:
#   1. formatting (cargo fmt --check, root crate and host-tests),
#   2. host tests (cd host-tests && cargo test --release),
#   3. the library alone for the three thumb targets (no default features),
#      its dependency tree (no firmware crates) and `cargo publish --dry-run`,
#   4. the firmware (demo, self-test, benchmark) for the three targets,
#   5. the demo and the on-target self-tests (selftest, selftest-tracking)
#      under QEMU on the three boards
#      (mps2-an386 / Cortex-M4F, mps2-an385 / Cortex-M3, microbit / Cortex-M0).
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

# A library user's build (default features, any target) must not pull in
# the firmware's crates.
library_has_no_firmware_dependencies() {
    local deps firmware_crates
    deps=$(cargo tree -p abtrack -e normal,build --target all --prefix none --format '{p}') || return
    firmware_crates=$(grep -E '^(cortex-m|cortex-m-rt|defmt|defmt-semihosting|defmt-rtt|panic-probe|qemu-exit) ' <<<"$deps" | sort -u)
    if [ -n "$firmware_crates" ]; then
        echo "the library's default build depends on firmware crates:" >&2
        echo "$firmware_crates" >&2
        return 1
    fi
    echo "library dependencies: $(sed 's/ .*//' <<<"$deps" | sort -u | tr '\n' ' ')"
}

step "cargo fmt --check" cargo fmt --check
step "cargo fmt --check (host-tests)" in_host_tests cargo fmt --check
step "host tests (cargo test --release)" in_host_tests cargo test --release
for t in "${ABTRACK_TARGETS[@]}"; do
    step "library alone for $t" cargo build --release --lib --no-default-features --target "$t"
done
step "library: no firmware crates among its dependencies" library_has_no_firmware_dependencies
step "library: cargo publish --dry-run" cargo publish --quiet --dry-run -p abtrack --allow-dirty
for t in "${ABTRACK_TARGETS[@]}"; do
    step "firmware build for $t" cargo build --release --target "$t"
done
for t in "${ABTRACK_TARGETS[@]}"; do
    step "demo on $(board_for_target "$t")" cargo run --release --target "$t" --bin abtrack-firmware
done
# Two self-test images (together they do not fit the micro:bit's flash).
for t in "${ABTRACK_TARGETS[@]}"; do
    for bin in selftest selftest-tracking; do
        step "$bin on $(board_for_target "$t")" run_selftest "$t" "$bin"
    done
done

echo
echo "abtrack test summary:"
printf '  %s\n' "${results[@]}"
if [ "$failures" -ne 0 ]; then
    echo "$failures step(s) failed"
    exit 1
fi
echo "all ${#results[@]} steps passed"
