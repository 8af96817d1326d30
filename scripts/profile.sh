#!/usr/bin/env bash
# Where one call of a firmware function spends its instructions: runs a
# release image under QEMU with its gdb server, steps one call of the
# function one instruction at a time (gdb-multiarch, scripts/profile.py) and
# prints the executed instructions per function, per innermost inlined
# function and per source line. Instructions, not cycles (QEMU models no
# pipeline); the total of a call matches the benchmark's row for it within
# the benchmark's own overhead (a few instructions a call).
#
#   scripts/profile.sh CORE BIN FUNCTION [--skip N] [--top N] [--instance TEXT]
#
#   CORE       m4f, m3 or m0 (or a target triple or board name)
#   BIN        a binary of boards/qemu, built first with
#              `cargo build --profile profiling --target <triple> --bin BIN`
#              (the release image's code with the full debug information)
#              (the benchmark: add `--features bench-anchors`, which this
#              script does for BIN = bench)
#   FUNCTION   0xADDRESS, or text of the function's demangled name that
#              matches one function (all matches are listed otherwise)
#   --skip N   let N calls run first (a warm table, a settled filter);
#              default 0
#   --top N    rows per table (default 20)
#   --instance TEXT
#              among FUNCTION's matches, the one that is, or inlines, the
#              function whose full generic name (debug information)
#              contains TEXT, e.g. for the benchmark's scan rows
#              `scripts/profile.sh m4f bench bench::scan::run_scan --skip 6
#               --instance 'scan_with_probe<f32, abtrack::filter::auto::AutoFilter<f32, 2>, 64, 64'`
#
# Needs gdb-multiarch (installed with apt-get when root; otherwise one line
# says so) besides what the firmware runs need. Slow: about 300 steps a
# second, so a 75,000-instruction scan takes four minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/setup.sh
. scripts/setup.sh

usage() { die "usage: scripts/profile.sh CORE BIN FUNCTION [--skip N] [--top N] [--instance TEXT]"; }
[ $# -ge 3 ] || usage
target=$(target_for "$1") || die "unknown core, board or target '$1'"
bin=$2
function=$3
shift 3
skip=0
top=20
instance=
while [ $# -gt 0 ]; do
    case "$1" in
        --skip) skip=${2:?}; shift 2 ;;
        --top) top=${2:?}; shift 2 ;;
        --instance) instance=${2:?}; shift 2 ;;
        *) usage ;;
    esac
done

ensure_targets "$target"
ensure_qemu
ensure_llvm_tools
if ! command -v gdb-multiarch >/dev/null; then
    install_packages_or_die "gdb-multiarch (a gdb for Arm)" gdb-multiarch
fi
tool() { if [ -n "${LLVM_TOOLS_DIR:-}" ]; then echo "$LLVM_TOOLS_DIR/$1"; else echo "$1"; fi; }
for t in llvm-nm llvm-symbolizer llvm-dwarfdump llvm-cxxfilt; do
    command -v "$(tool "$t")" >/dev/null ||
        die "$t not found: install Debian's llvm package (apt-get install llvm), then re-run"
done

features=()
[ "$bin" = bench ] && features=(--features bench-anchors)
cargo build --profile profiling --target "$target" --bin "$bin" "${features[@]}" >&2
elf=target/$target/profiling/$bin
board=$(board_for_target "$target")

# The function's address.
if [[ $function =~ ^0x[0-9a-fA-F]+$ ]]; then
    address=${function#0x}
else
    # Text symbols whose demangled name contains FUNCTION: "address mangled".
    matches=$(paste -d' ' \
        <("$(tool llvm-nm)" --defined-only "$elf" | awk '$2 ~ /^[tTwW]$/ {print $1, $3}') \
        <("$(tool llvm-nm)" --defined-only -C "$elf" | awk '$2 ~ /^[tTwW]$/ {$1 = ""; $2 = ""; print}') |
        awk -v f="$function" 'index($0, f) {print $1, $2}')
    [ -n "$matches" ] || die "no function's name contains '$function'"
    if [ -n "$instance" ]; then
        dwarf=$(mktemp "${TMPDIR:-/tmp}/abtrack-profile.XXXXXX")
        trap 'rm -f "$dwarf"' EXIT
        "$(tool llvm-dwarfdump)" --debug-info "$elf" >"$dwarf"
        # The linkage names of the functions whose full name contains TEXT.
        # (In a file, not an awk variable: a short TEXT can name thousands.)
        linkage=$(mktemp "${TMPDIR:-/tmp}/abtrack-profile-names.XXXXXX")
        trap 'rm -f "$dwarf" "$linkage"' EXIT
        awk -v f="$instance" '
            /DW_AT_linkage_name/ { match($0, /"[^"]*"/); last = substr($0, RSTART + 1, RLENGTH - 2) }
            /DW_AT_name/ && index($0, f) && last != "" { print last }' "$dwarf" | sort -u >"$linkage"
        [ -s "$linkage" ] || die "no function in the debug information is named with '$instance'"
        # The concrete functions (those with an address) that are, or inline, one of them.
        hosts=$(awk '
            FNR == NR { want[$0] = 1; next }
            /DW_TAG_subprogram/ { sub_pending = 1; next }
            sub_pending && /DW_AT_low_pc/ { match($0, /0x[0-9a-f]+/); pc = substr($0, RSTART, RLENGTH); sub_pending = 0; next }
            /DW_TAG_/ { sub_pending = 0 }
            /DW_AT_(linkage_name|abstract_origin|specification)/ && pc != "" {
                if (match($0, /"[^"]*"/) && (substr($0, RSTART + 1, RLENGTH - 2) in want)) print pc
            }' "$linkage" "$dwarf" | sort -u)
        matches=$(while read -r a m; do
            for h in $hosts; do
                if [ $((16#$a)) -eq $((h)) ]; then echo "$a $m"; fi
            done
        done <<<"$matches" | sort -u)
        [ -n "$matches" ] || die "no function named with '$function' is, or inlines, '$instance'"
    fi
    if [ "$(wc -l <<<"$matches")" -gt 1 ]; then
        echo "profile: '$function' matches several functions; name one by address or use --instance:" >&2
        while read -r a m; do echo "  0x$a $("$(tool llvm-cxxfilt)" "$m")" >&2; done <<<"$matches"
        exit 1
    fi
    address=$(cut -d' ' -f1 <<<"$matches")
fi

gdb_log=$(mktemp "${TMPDIR:-/tmp}/abtrack-profile-gdb.XXXXXX")
port=$((20000 + RANDOM % 20000))
qemu-system-arm -machine "$board" -display none -monitor none \
    -semihosting-config enable=on,target=native -serial none \
    -kernel "$elf" -gdb "tcp::$port" -S >/dev/null 2>&1 &
qemu_pid=$!
trap 'kill "$qemu_pid" 2>/dev/null || true; rm -f "${dwarf:-}" "${linkage:-}" "$gdb_log"' EXIT
PROFILE_ELF=$elf PROFILE_ADDRESS=$address PROFILE_SKIP=$skip PROFILE_TOP=$top PROFILE_PORT=$port \
    gdb-multiarch -q -batch -nx -ex "file $elf" -x scripts/profile.py >"$gdb_log" 2>&1 || true
if grep -q '^=== profile$' "$gdb_log"; then
    sed -n '/^=== profile$/,$p' "$gdb_log" | sed 1d
else
    echo "profile: no profile (gdb's last lines follow; is --skip more than the calls made?)" >&2
    tail -n 15 "$gdb_log" >&2
    exit 1
fi
