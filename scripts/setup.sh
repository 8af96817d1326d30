# Shared set-up for the scripts in this directory (sourced, not run).
#
# Each `ensure_*` function checks for one prerequisite and installs it when it
# can (rustup targets and components, `cargo install defmt-print`, apt-get
# packages when running as root); otherwise it stops with one line saying what
# to install. Nothing here is needed by the library itself.

# The firmware targets and the QEMU board each one runs on.
ABTRACK_TARGETS=(thumbv7em-none-eabihf thumbv7m-none-eabi thumbv6m-none-eabi)

board_for_target() {
    case "$1" in
        thumbv7em-none-eabihf) echo mps2-an386 ;;
        thumbv7m-none-eabi) echo mps2-an385 ;;
        thumbv6m-none-eabi) echo microbit ;;
        *) return 1 ;;
    esac
}

# Accepts a target triple, a QEMU board name or a core name; prints the triple.
target_for() {
    case "$1" in
        thumbv7em-none-eabihf | mps2-an386 | m4f | M4F | cortex-m4f) echo thumbv7em-none-eabihf ;;
        thumbv7m-none-eabi | mps2-an385 | m3 | M3 | cortex-m3) echo thumbv7m-none-eabi ;;
        thumbv6m-none-eabi | microbit | m0 | M0 | cortex-m0) echo thumbv6m-none-eabi ;;
        *) return 1 ;;
    esac
}

say() { echo "[abtrack] $*" >&2; }
die() {
    echo "abtrack: $*" >&2
    exit 1
}

# cargo-installed tools (defmt-print) live here; a non-login shell may lack it.
CARGO_BIN_DIR="${CARGO_HOME:-$HOME/.cargo}/bin"
case ":$PATH:" in
    *":$CARGO_BIN_DIR:"*) ;;
    *) PATH="$PATH:$CARGO_BIN_DIR" ;;
esac
export PATH

is_root() { [ "$(id -u)" -eq 0 ]; }

# apt-get update runs at most once per script.
_apt_updated=
apt_install() {
    if [ -z "$_apt_updated" ]; then
        say "apt-get update"
        apt-get update -qq
        _apt_updated=1
    fi
    say "apt-get install $*"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@"
}

# Installs Debian packages if we are root on an apt system; otherwise stops
# with one line naming them. $1: what is missing (for the message).
install_packages_or_die() {
    local what=$1
    shift
    if is_root && command -v apt-get >/dev/null; then
        apt_install "$@"
    elif command -v apt-get >/dev/null; then
        die "$what is missing: run 'sudo apt-get install $*' (or run this script as root), then re-run"
    else
        die "$what is missing: install the package(s) '$*' with your system's package manager, then re-run"
    fi
}

# cargo and a rustc at least as new as the host tools' `rust-version`
# (host-tests/Cargo.toml; the demo and the tests build them; the library
# alone builds on the older workspace `rust-version`).
ensure_cargo() {
    command -v cargo >/dev/null && command -v rustc >/dev/null ||
        die "cargo/rustc not found: install Rust with rustup (https://rustup.rs), then re-run"
    local need have
    need=$(awk -F'"' '/^rust-version/ { print $2; exit }' "$(repo_root)/host-tests/Cargo.toml")
    have=$(rustc --version | awk '{ print $2 }')
    [ -z "$need" ] || [ "$(printf '%s\n%s\n' "$need" "$have" | sort -V | head -n 1)" = "$need" ] ||
        die "Rust $need or later is needed, this rustc is $have: run 'rustup update stable', then re-run"
}

# Rust targets, given as arguments (default: all three firmware targets),
# and the firmware's linker, flip-link: what a firmware build needs (every
# script that builds firmware calls this first).
ensure_targets() {
    ensure_cargo
    ensure_flip_link
    local wanted=("$@")
    [ ${#wanted[@]} -gt 0 ] || wanted=("${ABTRACK_TARGETS[@]}")
    local missing=() t
    for t in "${wanted[@]}"; do
        # The target's core library is what a build needs.
        if ! ls "$(rustc --print target-libdir --target "$t" 2>/dev/null)"/libcore-*.rlib >/dev/null 2>&1; then
            missing+=("$t")
        fi
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    command -v rustup >/dev/null ||
        die "Rust targets ${missing[*]} are missing and rustup is not installed: add them to your toolchain, then re-run"
    say "rustup target add ${missing[*]}"
    rustup target add "${missing[@]}"
}

# rustfmt and clippy, for `cargo fmt --check` and the library's clippy pass
# (rustup's minimal profile has neither).
ensure_rustfmt_and_clippy() {
    ensure_cargo
    local missing=()
    cargo fmt --version >/dev/null 2>&1 || missing+=(rustfmt)
    cargo clippy --version >/dev/null 2>&1 || missing+=(clippy)
    [ ${#missing[@]} -eq 0 ] && return 0
    command -v rustup >/dev/null ||
        die "${missing[*]} missing and rustup is not installed: install them for your toolchain, then re-run"
    say "rustup component add ${missing[*]}"
    rustup component add "${missing[@]}"
}

# A C compiler/linker: Rust links host programs (host-tests, defmt-print)
# with `cc`.
ensure_host_linker() {
    command -v cc >/dev/null && return 0
    install_packages_or_die "a C compiler (cc, needed to link host programs)" gcc libc6-dev
    command -v cc >/dev/null || die "gcc was installed but there is no 'cc' on PATH; fix that, then re-run"
}

# qemu-system-arm with the three boards.
ensure_qemu() {
    if ! command -v qemu-system-arm >/dev/null; then
        install_packages_or_die "qemu-system-arm" qemu-system-arm
    fi
    local machines
    machines=$(qemu-system-arm -machine help 2>/dev/null) ||
        die "qemu-system-arm does not run; reinstall it (apt-get install qemu-system-arm), then re-run"
    local board
    for board in mps2-an386 mps2-an385 microbit; do
        grep -q "^$board " <<<"$machines" ||
            die "qemu-system-arm ($(qemu-system-arm --version | head -n1)) has no '$board' board; install QEMU 6.0 or later, then re-run"
    done
}

# defmt-print that decodes the defmt wire format of defmt 1.x (version "4").
defmt_print_ok() {
    command -v defmt-print >/dev/null &&
        defmt-print --version 2>/dev/null | grep -Eq 'supported defmt versions:.*\b4\b'
}

ensure_defmt_print() {
    defmt_print_ok && return 0
    ensure_cargo
    ensure_host_linker
    say "cargo install defmt-print --locked (a few minutes, once)"
    cargo install defmt-print --version '^1' --locked ||
        die "installing defmt-print failed; install it with 'cargo install defmt-print --locked', then re-run"
    # An older defmt-print elsewhere on PATH must not shadow the new one.
    defmt_print_ok || PATH="$CARGO_BIN_DIR:$PATH"
    defmt_print_ok ||
        die "defmt-print was installed in $CARGO_BIN_DIR but does not run from there; put that directory first on PATH, then re-run"
}

# The repository's root (this file's directory's parent), absolute.
repo_root() { (cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd); }

# The firmware binaries, as declared in boards/qemu/Cargo.toml (the
# `name = ...` of each [[bin]]): one list, read where it is declared.
firmware_bins() {
    awk '/^\[\[bin\]\]/ { in_bin = 1; next }
         /^\[/ { in_bin = 0 }
         in_bin && $1 == "name" { gsub(/"/, "", $3); print $3 }' \
        "$(repo_root)/boards/qemu/Cargo.toml"
}

# flip-link, the firmware's linker (.cargo/config.toml): places the stack
# below the static data. 0.1.10 or later sets _stack_end, which cortex-m-rt
# 0.7.5's layout check needs.
ensure_flip_link() {
    command -v flip-link >/dev/null &&
        cargo install --list 2>/dev/null | grep -Eq '^flip-link v0\.1\.(1[0-9]|[2-9][0-9])' && return 0
    ensure_cargo
    ensure_host_linker
    say "cargo install flip-link --locked (the firmware's linker, once)"
    cargo install flip-link --version '^0.1.10' --locked ||
        die "installing flip-link failed; install it with 'cargo install flip-link --locked', then re-run"
}

# llvm-objdump, llvm-symbolizer, llvm-nm for the firmware checks
# (host-tests' firmware-check): Debian's llvm package, else rustup's
# llvm-tools component.
llvm_tools_ok() {
    local tool
    for tool in llvm-objdump llvm-symbolizer llvm-nm; do
        command -v "$tool" >/dev/null || compgen -c "$tool-" | grep -Eq "^$tool-[0-9]+$" || return 1
    done
}

ensure_llvm_tools() {
    llvm_tools_ok && return 0
    if is_root && command -v apt-get >/dev/null; then
        apt_install llvm
        llvm_tools_ok && return 0
    fi
    if command -v rustup >/dev/null; then
        say "rustup component add llvm-tools"
        rustup component add llvm-tools
        local dir
        dir="$(rustc --print sysroot)/lib/rustlib/$(host_triple)/bin"
        [ -x "$dir/llvm-objdump" ] && {
            export LLVM_TOOLS_DIR=$dir
            return 0
        }
    fi
    install_packages_or_die "llvm-objdump, llvm-symbolizer and llvm-nm" llvm
}

# The cargo profile of the scripts' host-tests builds (tools and tests):
# `release`, or the one ABTRACK_HOST_PROFILE names (the test command's
# `checks`, host-tests/Cargo.toml). Its output directory has its name.
host_profile() { echo "${ABTRACK_HOST_PROFILE:-release}"; }

# The host's target triple (host-tests/.cargo/config.toml builds for it
# explicitly, so its outputs are under target/<triple>/).
host_triple() { rustc -vV | sed -n 's/^host: //p'; }

# Where host-tests' build with host_profile puts its binaries and examples.
host_tests_out_dir() {
    echo "$(repo_root)/host-tests/target/$(host_triple)/$(host_profile)"
}

# Builds host-tests' firmware-check (the panic and stack-layout checks on
# the firmware ELFs) and prints its path; once it is in
# $ABTRACK_FIRMWARE_CHECK (the test command sets it after its builds), that
# path without a cargo call, so checks running beside other cargo commands
# never wait for a build lock.
firmware_check_tool() {
    if [ -n "${ABTRACK_FIRMWARE_CHECK:-}" ]; then
        echo "$ABTRACK_FIRMWARE_CHECK"
        return 0
    fi
    local root
    root=$(repo_root)
    (cd "$root/host-tests" && cargo build --profile "$(host_profile)" --quiet --bin firmware-check) >&2 || return
    (cd "$root/host-tests" && cargo metadata --format-version 1 --no-deps >/dev/null) || return
    echo "$(host_tests_out_dir)/firmware-check"
}

# Third-party crates allowed to keep panic calls, per image, each with its
# reason (firmware-check prints it with the calls; docs/safety.md). Our own
# code (the library and the firmware) can never be allowed, and an
# allowance no call uses fails the check. (scripts/test.sh checks every
# image; scripts/bench.sh the whole benchmark image it builds.)
#   bench: minikalman, the benchmark's Kalman anchor (feature bench-anchors,
#   only in this image): its Matrix::mult indexes; it is the third-party code
#   measured as published, not shipped in any other image.
panic_allowances_for() {
    case $1 in
    bench) echo "--allow-crate=minikalman=the benchmark's Kalman anchor (feature bench-anchors, only in the bench image), third-party code measured as published" ;;
    esac
}

# check_panic_calls <binary> <elf>...: no call into core::panicking in the
# ELFs of one binary (its targets), but those its allowances cover.
check_panic_calls() {
    local bin=$1 tool allow
    shift
    tool=$(firmware_check_tool) || return
    allow=$(panic_allowances_for "$bin")
    "$tool" panics ${allow:+"$allow"} "$@"
}

# check_stack_layout_of <elf>...: the stack below the static data
# (flip-link) in each ELF; RAM starts at 0x2000_0000 on every board
# (boards/*/memory.x).
check_stack_layout_of() {
    local tool
    tool=$(firmware_check_tool) || return
    "$tool" layout --ram-origin 0x20000000 "$@"
}

# A nightly toolchain and cargo-fuzz, for the fuzz targets (fuzz/,
# scripts/fuzz.sh): cargo-fuzz needs nightly's sanitizer flags; everything
# else builds with the stable toolchain.
ensure_cargo_fuzz() {
    ensure_cargo
    if ! rustup run nightly rustc --version >/dev/null 2>&1; then
        command -v rustup >/dev/null ||
            die "the fuzz targets need a nightly toolchain: install rustup, then 'rustup toolchain install nightly --profile minimal'"
        say "rustup toolchain install nightly --profile minimal (for cargo-fuzz)"
        rustup toolchain install nightly --profile minimal
    fi
    cargo fuzz --version >/dev/null 2>&1 && return 0
    ensure_host_linker
    say "cargo install cargo-fuzz --locked (a few minutes, once)"
    cargo install cargo-fuzz --locked ||
        die "installing cargo-fuzz failed; install it with 'cargo install cargo-fuzz --locked', then re-run"
}

# The minimum Rust version of the library and the firmware: `rust-version`
# of the root workspace's [workspace.package] (Cargo.toml), the one place it
# is declared.
msrv() {
    awk '/^\[workspace\.package\]/ { p = 1; next } /^\[/ { p = 0 }
         p && $1 == "rust-version" { gsub(/"/, "", $3); print $3; exit }' \
        "$(repo_root)/Cargo.toml"
}

# That toolchain with the M4F's target, for the test command's check of
# the library on it.
ensure_msrv_toolchain() {
    ensure_cargo
    local version
    version=$(msrv)
    [ -n "$version" ] || die "no rust-version in Cargo.toml's [workspace.package]"
    if ! rustup run "$version" rustc --version >/dev/null 2>&1; then
        command -v rustup >/dev/null ||
            die "the minimum Rust version $version is missing and rustup is not installed: install that toolchain, then re-run"
        say "rustup toolchain install $version --profile minimal (the minimum Rust version of the library and the firmware)"
        rustup toolchain install "$version" --profile minimal
    fi
    if ! ls "$(rustup run "$version" rustc --print target-libdir --target thumbv7em-none-eabihf 2>/dev/null)"/libcore-*.rlib >/dev/null 2>&1; then
        say "rustup target add --toolchain $version thumbv7em-none-eabihf"
        rustup target add --toolchain "$version" thumbv7em-none-eabihf
    fi
}
