#!/usr/bin/env bash
# Runs every test of the project:
#   1. formatting (cargo fmt --check, root crate and host-tests),
#   2. host tests (cd host-tests && cargo test --profile checks, the
#      release profile at opt-level 1 without LTO; the integration tests
#      are one binary, host-tests/tests/it/; among them each fuzz target's
#      committed corpus run through its properties, fuzz/properties/),
#      then, with the same build, the
#      library's doc examples (cargo test -p abtrack --doc) and its
#      examples/ (built; examples/tcas_cycle.rs run); in lanes beside it:
#      the library's documentation with no rustdoc warning (cargo doc, as
#      docs.rs builds it) and the library and the firmware on their minimum
#      Rust version,
#   3. (in a lane beside step 2) the library alone (without features and
#      with `defmt`) for the M4F and the M0 (with and without 32-bit
#      atomics, the only target property that changes which of its code
#      compiles) in a clippy pass with its no-panic lints, its dependency tree (no
#      firmware crates), and the package as crates.io gets it
#      (`cargo publish --dry-run --no-verify`, then the unpacked package
#      checked: the verification build without its code generation, which
#      the firmware build does for the three targets),
#   4. the firmware (every binary of boards/qemu, the benchmark's smoke
#      image: feature bench-smoke, the anchors and each filter's scan rows
#      at its smallest and largest table size; the example
#      static_track_table) for the three
#      targets, then the nRF52840-DK build of the demo (in the same target
#      directory: it reuses the M4F's crates.io dependencies);
#   then the runs and checks, in lanes side by side (a QEMU run mostly
#   waits): the ELF checks (no call into core::panicking in any release
#      ELF; the stack below the static data (flip-link); each demo image's
#      .data under 4 KiB; no double-precision soft-float routine in the M4F
#      example),
#   5. the firmware images under QEMU on the three boards
#      (mps2-an386 / Cortex-M4F, mps2-an385 / Cortex-M3, microbit / Cortex-M0):
#      a deliberate stack overflow ends in a clean HardFault report; stack
#      high-water marks with 25 % margin (scripts/stack.sh); the demo; the
#      on-target self-tests (selftest, selftest-tracking); a smoke run of the
#      benchmark's smoke image, which must run to its end and print a
#      well-formed report (nothing about speed is checked; scripts/bench.sh
#      builds, checks and runs the whole image, and measures);
#      the static track table example on the mps2-an386,
#   6. fault injection (the clutter storm over 15 of the input's 110 scans;
#      scripts/fault-injection.sh runs it whole) and repeated demo runs on
#      the three boards (one lane each), a one-hour soak on the Cortex-M3
#      (docs/firmware-and-boards.md).
#
# The fuzzing itself (nightly, cargo-fuzz) is scripts/fuzz.sh: its build
# alone took a tenth of this command's CPU time.
#
#   scripts/test.sh
#
# Installs what is missing (Rust targets, rustfmt and clippy, the
# minimum-version toolchain, qemu-system-arm, a C compiler and llvm when
# root, defmt-print, flip-link). Every step runs
# even if an earlier one failed; the summary lists them with their wall
# and CPU times (and when each started), and the whole command's; the exit
# status is non-zero if any failed. `.ci/run` calls this.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

ensure_targets "${ABTRACK_TARGETS[@]}"
ensure_rustfmt_and_clippy
ensure_host_linker
ensure_qemu
ensure_defmt_print
ensure_llvm_tools
ensure_msrv_toolchain

# The host tests and tools build with host-tests' `checks` profile (the
# release profile at opt-level 1 without LTO: host-tests/Cargo.toml); every
# script below builds them through host_profile (scripts/setup.sh).
export ABTRACK_HOST_PROFILE=checks

log_dir=$(mktemp -d "${TMPDIR:-/tmp}/abtrack-test.XXXXXX")
results_file=$log_dir/results
: >"$results_file"

# children_cpu_s: the CPU time (user + system, whole seconds) of this
# shell's finished child processes and theirs, from bash's `times` (run in
# this shell: a command substitution would report its own subshell's), in
# $children_cpu_s.
children_cpu_s() {
    local f="$log_dir/times.$BASHPID" user sys total=0 t seconds
    times >"$f"
    # Two lines, "<user> <system>" each as "<m>m<s.sss>s" (the locale's
    # decimal separator): the shell's own, then its children's.
    { read -r _ _ && read -r user sys; } <"$f"
    for t in "$user" "$sys"; do
        t=${t%s}
        seconds=${t#*m}
        total=$((total + ${t%%m*} * 60 + 10#${seconds%%[.,]*}))
    done
    children_cpu_s=$total
}

trap 'rm -rf "$log_dir"' EXIT

# step <name> <command...>: runs one step, records PASS/FAIL, its wall
# time, when it started (seconds since the script started; the lanes share
# the clock) and the CPU time its processes used, in $step_results inside a
# parallel lane, else in the summary.
step() {
    local name=$1
    shift
    say "== $name"
    local status=0 start=$SECONDS cpu_before
    children_cpu_s
    cpu_before=$children_cpu_s
    "$@" || status=$?
    local took=$((SECONDS - start))
    children_cpu_s
    local times="${took} s, from +${start} s, $((children_cpu_s - cpu_before)) CPU-s"
    if [ "$status" -eq 0 ]; then
        echo "PASS  $name ($times)" >>"${step_results:-$results_file}"
    else
        echo "FAIL  $name (exit status $status, $times)" >>"${step_results:-$results_file}"
    fi
}

# in_parallel <lane>...: runs each lane (a function that runs steps one
# after another) in the background, its output in a log; when all have
# ended, prints each lane's output and adds its steps to the summary, in
# lane order. The lanes share no build directory lock while they run: the
# builds they need are made before.
in_parallel() {
    local lane i=0 pids=()
    for lane in "$@"; do
        say "== running in parallel: $lane (its output follows when the lanes end)"
        (
            step_results="$log_dir/lane-$i.results"
            : >"$step_results"
            "$lane"
        ) >"$log_dir/lane-$i.log" 2>&1 &
        pids+=("$!")
        i=$((i + 1))
    done
    local pid
    for pid in "${pids[@]}"; do
        wait "$pid" || true
    done
    local j
    for ((j = 0; j < i; j++)); do
        cat "$log_dir/lane-$j.log"
        cat "$log_dir/lane-$j.results" >>"$results_file"
    done
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

# Every release firmware ELF of the three targets.
firmware_elves() {
    local t b
    for t in "${ABTRACK_TARGETS[@]}"; do
        for b in $(firmware_bins); do
            echo "target/$t/release/$b"
        done
    done
}

# Each image with its own allowances (none but the benchmark's); the images
# side by side (each check is one llvm-objdump at a time), their reports in
# order.
check_no_panic_calls() {
    local status=0 b t pids=() bins=()
    for b in $(firmware_bins); do
        local elves=()
        for t in "${ABTRACK_TARGETS[@]}"; do
            elves+=("target/$t/release/$b")
        done
        check_panic_calls "$b" "${elves[@]}" >"$log_dir/panics-$b.log" 2>&1 &
        pids+=("$!")
        bins+=("$b")
    done
    local i
    for i in "${!pids[@]}"; do
        wait "${pids[$i]}" || status=1
        cat "$log_dir/panics-${bins[$i]}.log"
    done
    return "$status"
}

# Every release ELF of the three emulated boards and the nRF52840-DK's.
check_stack_layout() {
    # shellcheck disable=SC2046
    check_stack_layout_of $(firmware_elves) "$nrf52840_dk_elf"
}

# Each demo image's initialised statics (.data, copied from flash at reset)
# under 4 KiB on the three boards: the scan loop's and the intake's state,
# and every number type's zero, start as zero bytes, in .bss.
check_demo_data() {
    local tool t elves=()
    tool=$(firmware_check_tool) || return
    for t in "${ABTRACK_TARGETS[@]}"; do
        elves+=("target/$t/release/abtrack-firmware")
    done
    "$tool" data --max-bytes 4095 "${elves[@]}"
}

# The M4F example image (f32 on a single-precision FPU) links no
# double-precision soft-float routine (__aeabi_dadd, __muldf3, ...):
# firmware-check lists any, with its callers.
check_example_soft_double() {
    local tool
    tool=$(firmware_check_tool) || return
    "$tool" soft-double target/thumbv7em-none-eabihf/release/examples/static_track_table
}

# The deliberate overflow (boards/qemu/src/bin/stack_overflow.rs) must end in the
# HardFault handler's report with the statics intact and exit status 1; not
# in QEMU's "Lockup" abort (134), a hang (124) or a normal exit.
run_stack_overflow() {
    local target=$1 log="$log_dir/stack-overflow-$1.log" status=0
    cargo run --release --target "$target" --bin stack-overflow 2>&1 | tee "$log" || status=$?
    if [ "$status" -ne 1 ]; then
        echo "stack-overflow on $target: exit status $status, expected 1 (the HardFault handler's)" >&2
        return 1
    fi
    local expected
    for expected in 'hard fault: stack overflow' 'statics intact: 256 of 256' \
        'hard fault handler: [0-9]* bytes of stack used'; do
        grep -q "$expected" "$log" || {
            echo "stack-overflow on $target: no '$expected' in the output" >&2
            return 1
        }
    done
    if grep -qi 'lockup' "$log"; then
        echo "stack-overflow on $target: QEMU reports a lockup" >&2
        return 1
    fi
}

# The real board's build (nothing can run it here): its own workspace and
# .cargo/config.toml, the repository's target directory (after the M4F
# firmware's build, whose crates.io dependencies it reuses); prints its
# sizes. Its stack layout is checked with the other images' (elf_checks).
nrf52840_dk_elf=target/thumbv7em-none-eabihf/release/abtrack-nrf52840-dk
build_nrf52840_dk() {
    (cd boards/nrf52840-dk && cargo build --release) || return
    bash scripts/sizes.sh --nrf52840-dk
}

# The host tests (their build is mostly one crate after another, its
# library, then the test binary, and leaves a core idle that the other
# lanes' builds take); then, with that build of the library and its
# dependencies, the library's doc examples and its examples/ (built, and
# examples/tcas_cycle.rs run). The `checks` profile turns on overflow
# checks in the library, the CSV reader and the firmware's host modules, as
# the fuzz targets' profile does (host-tests/Cargo.toml); the library has no
# debug assertion.
host_tests_steps() {
    step "cargo fmt --check (host-tests)" in_host_tests cargo fmt --check
    step "host tests (cargo test --profile checks)" in_host_tests cargo test --profile "$(host_profile)"
    step "library doc examples (cargo test -p abtrack --doc)" \
        in_host_tests cargo test --profile "$(host_profile)" -p abtrack --doc
    step "library examples/ built, and examples/tcas_cycle.rs run on the host" run_library_examples
}

# The library's examples/, built in host-tests' workspace (the library is
# one of its dependencies), and examples/tcas_cycle.rs run.
run_library_examples() {
    in_host_tests cargo build --profile "$(host_profile)" -p abtrack --examples &&
        "$(host_tests_out_dir)/examples/tcas_cycle"
}

target_args=("${ABTRACK_TARGETS[@]/#/--target=}")
# The library's targets for clippy and the package check: one with 32-bit
# atomics and one without, the only target property that changes which of
# its code compiles (`cfg(target_has_atomic = "32")`, src/num/fixed32.rs);
# the Cortex-M3 compiles the M4F's sources (the firmware build compiles the
# library for all three).
library_targets=(thumbv7em-none-eabihf thumbv6m-none-eabi)
library_target_args=("${library_targets[@]/#/--target=}")

# The package as crates.io gets it: `cargo publish --dry-run --no-verify`
# makes it without its verification build (a build of the packaged
# sources); instead, every file the library's compilation read (its
# dep-info from the clippy passes: sources, include_str! files) must be in the
# package. The packaged sources are then the ones clippy checked and the
# firmware build compiles for the three targets.
check_package() {
    cargo publish --quiet --dry-run --no-verify -p abtrack --allow-dirty || return
    local listed dep_info missing=0 f t root=$PWD
    listed=$(cargo package --quiet --list -p abtrack --allow-dirty) || return
    for t in "${library_targets[@]}"; do
        dep_info=$(ls -t target/"$t"/debug/deps/abtrack-*.d 2>/dev/null | head -n 1)
        [ -n "$dep_info" ] || {
            echo "no dep-info of the library for $t (the clippy step makes it)" >&2
            return 1
        }
        # "<output>: <source> <source> ...", one line per output.
        for f in $(sed -n '1s/^[^:]*: *//p' "$dep_info"); do
            case "$f" in
                "$root"/target/* | target/*) continue ;;
                "$root"/*) f=${f#"$root"/} ;;
                /*) continue ;;
            esac
            grep -qxF "$f" <<<"$listed" || {
                echo "$f is read by the library's build for $t but is not in the package" >&2
                missing=1
            }
        done
    done
    [ "$missing" -eq 0 ] && echo "the package ($(wc -l <<<"$listed") files) holds every file the library's build reads"
}

# Every image as the runs below use it: the binaries without features (the
# soak image shortened to one hour of scans, ABTRACK_SOAK_SCANS, read at
# build time: scripts/soak.sh runs the day), the benchmark with its anchors
# and its scan rows at each filter's smallest and largest size (feature
# bench-smoke: scripts/bench.sh builds, checks and runs the whole image), so
# each is built once; the three targets in one cargo
# invocation (it keeps both cores busy through the single-threaded link-time
# optimisation of each image).
build_firmware() {
    env ABTRACK_SOAK_SCANS=3600 cargo build --release "${target_args[@]}" &&
        cargo build --release "${target_args[@]}" --features bench-smoke --bin bench &&
        cargo build --release --target thumbv7em-none-eabihf -p abtrack-firmware --example static_track_table
}

# The firmware's binaries and examples on the minimum Rust version, for the
# M4F: the check compiles the whole library too (its one feature, defmt,
# only adds derives), so a separate check of the library alone would
# repeat it.
check_on_msrv() {
    cargo "+$(msrv)" check -p abtrack-firmware --bins --examples \
        --target thumbv7em-none-eabihf --target-dir target/msrv
}

# The library's clippy pass, without features and with `defmt` (the
# firmware's: its Format impls are code too).
clippy_library() {
    cargo clippy -p abtrack --lib --no-default-features "${library_target_args[@]}" -- -D warnings &&
        cargo clippy -p abtrack --lib --no-default-features --features defmt \
            "${library_target_args[@]}" -- -D warnings
}

# The library alone (without features and with `defmt`) for the M4F and
# the M0 (library_targets), in a clippy pass with its no-panic lints (Cargo.toml
# [lints.clippy], .clippy.toml): indexing, unwrap/expect, panic! and integer
# arithmetic are errors, and so is every other clippy warning
# (docs/safety.md). Its code generation for the three targets is the
# firmware build's. Every image is built here, the nRF52840-DK's last (it
# reuses the M4F build's crates.io dependencies), so that no later lane
# holds the build directory's lock for a link while the others run.
library_and_firmware_steps() {
    step "cargo fmt --check" cargo fmt --check
    step "library alone for the M4F and the M0, without and with its defmt feature: clippy, no panic paths (indexing, unwrap, arithmetic)" \
        clippy_library
    step "library: no firmware crates among its dependencies" library_has_no_firmware_dependencies
    step "library: the crates.io package (cargo publish --dry-run --no-verify; every file the build reads packaged)" check_package
    step "firmware build for the three targets (and the example static_track_table)" build_firmware
    step "nRF52840-DK demo build (boards/nrf52840-dk: defmt-rtt, probe-rs runner, flip-link) and its sizes" build_nrf52840_dk
}

# The library's host-side checks, each in its own target directory (under
# target/) so that no lane waits for another's build lock: the
# documentation docs.rs builds (all features, the host target) with no
# rustdoc warning (broken intra-doc links among them); the library and the
# firmware on their minimum Rust version (Cargo.toml `rust-version`).
library_on_the_host() {
    step "library: cargo doc, no warnings" in_host_tests env RUSTDOCFLAGS="-D warnings" \
        cargo doc --manifest-path ../Cargo.toml -p abtrack --lib --no-deps --all-features \
        --target-dir ../target/doc-check
    step "library and firmware on their minimum Rust version $(msrv) (cargo +$(msrv) check of the firmware, which compiles the library)" \
        check_on_msrv
}

# The builds, and the checks that need no firmware image and no host tool,
# from the start: three lanes (the machine's
# cores stay busy while one lane waits for a single-threaded link).
in_parallel host_tests_steps library_and_firmware_steps library_on_the_host

# firmware-check, built by the host tests' step: its path, found once, for
# the checks in the lanes below.
ABTRACK_FIRMWARE_CHECK=$(firmware_check_tool) || ABTRACK_FIRMWARE_CHECK=

# Lane 7 of the runs below: the ELF checks (firmware-check at the path
# found above: no cargo call, so no wait for a build lock held by another
# lane).
elf_checks() {
    step "firmware: no call into core::panicking in any release ELF" check_no_panic_calls
    step "firmware: stack below the static data in every release ELF, the nRF52840-DK's too (flip-link)" check_stack_layout
    step "firmware: each demo image's .data under 4 KiB (three boards)" check_demo_data
    step "firmware: no double-precision soft-float routine in the M4F example image" check_example_soft_double
}

# The benchmark image (feature bench-smoke: the minikalman anchor, each
# filter's scan rows at its smallest and largest table size) must run to
# its end and print a complete, well-formed report: bench_report --check
# refuses a malformed line, a missing end line or a line count that differs
# from the end line's. The figures themselves are not checked.
run_bench_smoke() {
    local target=$1 log="$log_dir/bench-$1.log"
    cargo run --release --target "$target" --bin bench --features bench-smoke >"$log" || {
        tail -n 20 "$log" >&2
        return 1
    }
    in_host_tests cargo run --quiet --profile "$(host_profile)" --bin bench_report -- --check "$log"
}

# The runs, in lanes side by side once the builds above are made (QEMU
# runs one core each and mostly waits: for its input, or for the demo's
# 10 s of silence after an input without its end frame). Lane 1: the
# firmware images of the root workspace on the three boards.
emulated_images() {
    local t bin
    for t in "${ABTRACK_TARGETS[@]}"; do
        step "stack overflow faults cleanly on $(board_for_target "$t")" run_stack_overflow "$t"
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
    for t in "${ABTRACK_TARGETS[@]}"; do
        step "benchmark smoke run on $(board_for_target "$t")" run_bench_smoke "$t"
    done
    step "example static_track_table on mps2-an386" run_static_track_table
}

# The example's last line is its verdict; its exit status too.
run_static_track_table() {
    local log="$log_dir/static_track_table.log"
    cargo run --release --target thumbv7em-none-eabihf -p abtrack-firmware \
        --example static_track_table | tee "$log" || return
    grep -q '^static track table: 3 confirmed tracks, all within 1 m' "$log" || {
        echo "static_track_table: no '3 confirmed tracks, all within 1 m' line" >&2
        return 1
    }
}

# Lane 2: the stack high-water marks (scripts/stack.sh runs each target's
# inputs side by side).
stack_marks() {
    step "stack high-water marks, demo and fault inputs (>= 25 % margin)" bash scripts/stack.sh
}

# Lanes 3-5: the host-tests runs of the firmware, one board each (fault
# injection through the board's UART, every fault of host-tests/src/frames.rs
# `Fault` side by side, and three runs of the demo compared byte for byte,
# with each other and with the same core run on the host:
# host-tests/tests/it/firmware/fault_injection.rs). The clutter storm lasts
# the input's first 15 scans of 110 (ABTRACK_CLUTTER_STORM_SCANS): the whole
# storm, 720 KB through the mps2 boards' one-byte UART, took about 70 s of
# CPU per board; scripts/fault-injection.sh runs it whole.
clutter_storm_scans=15
fault_injection_on() {
    local b=$1
    step "fault injection (the clutter storm over $clutter_storm_scans scans) and repeated runs on $b" in_host_tests \
        env ABTRACK_CLUTTER_STORM_SCANS="$clutter_storm_scans" cargo test --profile "$(host_profile)" --test it -- --ignored --test-threads=2 \
        "firmware::fault_injection::fault_injection_${b//-/_}" \
        "firmware::fault_injection::demo_runs_are_identical_${b//-/_}"
}
fault_injection_mps2_an386() { fault_injection_on mps2-an386; }
fault_injection_mps2_an385() { fault_injection_on mps2-an385; }
fault_injection_microbit() { fault_injection_on microbit; }

# Lane 6: the soak shortened to one hour of scans (scripts/soak.sh runs the
# day; its image is built above).
soak() {
    step "soak, one hour, on mps2-an385" in_host_tests env ABTRACK_SOAK_SCANS=3600 \
        cargo test --profile "$(host_profile)" --test it -- --ignored firmware::soak::soak_mps2_an385
}

in_parallel emulated_images stack_marks fault_injection_mps2_an386 fault_injection_mps2_an385 \
    fault_injection_microbit soak elf_checks

# The whole command's CPU time: every lane's.
children_cpu_s

echo
echo "abtrack test summary:"
sed 's/^/  /' "$results_file"
echo "  whole command: $SECONDS s, $children_cpu_s CPU-s (user + system; the lanes side by side; installs included)"
failures=$(grep -c '^FAIL' "$results_file" || true)
steps=$(wc -l <"$results_file")
if [ "$failures" -ne 0 ]; then
    echo "$failures step(s) failed"
    exit 1
fi
echo "all $steps steps passed"
