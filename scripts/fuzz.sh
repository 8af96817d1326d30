#!/usr/bin/env bash
# Runs the fuzz targets (fuzz/fuzz_targets/, cargo-fuzz with libFuzzer) for a
# while each, starting from and adding to the committed corpora
# (fuzz/corpus/<target>/), and prints the executions per target.
#
#   scripts/fuzz.sh [--grow] [seconds per target] [target ...]
#
# Each target first runs every input of its committed corpus (libFuzzer
# reads the corpus before it mutates), then fuzzes until the time is up.
# Default: 20 s per target, every target. The test command does not fuzz: its host tests run the
# committed corpora through the same properties (fuzz/properties/,
# host-tests/tests/it/fuzz_corpora/).
# New inputs go to a temporary directory, so the committed corpus stays as
# it is; with --grow they are added to fuzz/corpus/<target>/ (for a long
# run; then minimise with `cd fuzz && cargo +nightly fuzz cmin <target>`
# before committing): `scripts/fuzz.sh --grow 600` (docs/safety.md).
# A failing property or a panic stops that target: libFuzzer writes the input
# to fuzz/artifacts/<target>/ and this script's exit status is 1. Reproduce
# with `cd fuzz && cargo +nightly fuzz run --release --sanitizer none <target> <artifact>`.
#
# Needs a nightly toolchain and cargo-fuzz; installs them when missing
# (rustup toolchain install nightly --profile minimal; cargo install
# cargo-fuzz --locked).
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

# No sanitizer: the fuzzed code (the library, which forbids unsafe code, the
# CSV reader, the demo's configuration and the targets) has no unsafe code,
# so AddressSanitizer would find nothing there that the overflow checks and
# debug assertions (fuzz/Cargo.toml) do not; without it the build takes a
# third less CPU time and the targets run faster.
fuzz_options=(--release --sanitizer none)

grow=
if [ "${1:-}" = --grow ]; then
    grow=1
    shift
fi
seconds=${1:-20}
[[ "$seconds" =~ ^[0-9]+$ ]] || die "seconds per target: '$seconds' is not a number"
shift || true

ensure_host_linker
ensure_cargo_fuzz

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    mapfile -t targets < <(cd fuzz && cargo +nightly fuzz list)
fi

status=0
summary=()
for target in "${targets[@]}"; do
    corpus="fuzz/corpus/$target"
    mkdir -p "$corpus"
    log=$(mktemp "${TMPDIR:-/tmp}/abtrack-fuzz.XXXXXX")
    # libFuzzer reads every corpus directory and writes new inputs to the
    # first one.
    corpora=("$PWD/$corpus")
    new_inputs=
    if [ -z "$grow" ]; then
        new_inputs=$(mktemp -d "${TMPDIR:-/tmp}/abtrack-fuzz-new.XXXXXX")
        corpora=("$new_inputs" "$PWD/$corpus")
    fi
    say "fuzz $target for ${seconds}s (corpus $corpus: $(find "$corpus" -type f | wc -l) inputs)"
    result=0
    (cd fuzz && cargo +nightly fuzz run "${fuzz_options[@]}" "$target" "${corpora[@]}" -- \
        -max_total_time="$seconds" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048) >"$log" 2>&1 || result=$?
    [ -z "$new_inputs" ] || rm -rf "$new_inputs"
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    if [ "$result" -eq 0 ]; then
        summary+=("$(printf '%-14s %12s executions in %ss, no failure' "$target" "${runs:-?}" "$seconds")")
    else
        status=1
        tail -n 40 "$log" >&2
        summary+=("$(printf '%-14s FAILED after %s executions: see above and fuzz/artifacts/%s/' "$target" "${runs:-?}" "$target")")
    fi
    rm -f "$log"
done
printf '%s\n' "${summary[@]}"
exit "$status"
