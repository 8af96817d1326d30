//! Firmware link set-up, shared by the firmware packages (`boards/qemu`, the
//! three emulated boards, and `boards/nrf52840-dk`, the real one): picks the
//! board from the package, its features and the target triple, puts that
//! board's memory layout on the linker search path as `memory.x`, and passes
//! the linker scripts.
//!
//! | package | target | board | memory layout |
//! |---|---|---|---|
//! | abtrack-firmware | thumbv7em-none-eabihf | mps2-an386 (QEMU) | `boards/mps2/memory.x` |
//! | abtrack-firmware | thumbv7m-none-eabi | mps2-an385 (QEMU) | `boards/mps2/memory.x` |
//! | abtrack-firmware | thumbv6m-none-eabi | microbit (QEMU) | `boards/microbit/memory.x` |
//! | abtrack-firmware, feature `nrf52840-dk` | thumbv7em-none-eabihf | nrf52840-dk | `boards/nrf52840-dk/memory.x` |
//! | abtrack-nrf52840-dk | thumbv7em-none-eabihf | nrf52840-dk | `boards/nrf52840-dk/memory.x` |
//!
//! For a target with an operating system (the host, where host-tests and
//! fuzz build abtrack-firmware's hardware-free modules) there is no board:
//! no `abtrack_board` cfg, no link set-up.
//!
//! The layout goes on the search path as `abtrack-board-memory.x`: rust-lld
//! reads cortex-m-rt's `INCLUDE memory.x` from the directory it runs in (the
//! workspace root) before the search path, so the repository's top-level
//! `memory.x` is always the one read, and it includes the board's file.
//! (`boards/nrf52840-dk` is its own workspace; its `memory.x` is read the
//! same way, from its directory.)

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// A board the firmware runs on.
struct Board {
    /// The board's name: the QEMU machine for the emulated ones.
    name: &'static str,
    core: &'static str,
    /// Directory under `boards/` holding its `memory.x`.
    layout_dir: &'static str,
}

/// Every board name, for `cfg(abtrack_board = "...")`.
const BOARD_NAMES: [&str; 4] = ["mps2-an386", "mps2-an385", "microbit", "nrf52840-dk"];

fn board_for(package: &str, target: &str, nrf52840_dk: bool) -> Option<Board> {
    let board = |name, core, layout_dir| {
        Some(Board {
            name,
            core,
            layout_dir,
        })
    };
    match (package, target) {
        ("abtrack-firmware", "thumbv7em-none-eabihf") if nrf52840_dk => {
            board("nrf52840-dk", "Cortex-M4F", "nrf52840-dk")
        }
        ("abtrack-firmware", "thumbv7em-none-eabihf") => board("mps2-an386", "Cortex-M4F", "mps2"),
        ("abtrack-firmware", "thumbv7m-none-eabi") => board("mps2-an385", "Cortex-M3", "mps2"),
        ("abtrack-firmware", "thumbv6m-none-eabi") => board("microbit", "Cortex-M0", "microbit"),
        ("abtrack-nrf52840-dk", "thumbv7em-none-eabihf") => {
            board("nrf52840-dk", "Cortex-M4F", "nrf52840-dk")
        }
        _ => None,
    }
}

fn main() -> ExitCode {
    println!("cargo:rerun-if-changed=../build.rs");
    // `cfg(abtrack_board = "...")` picks the board's peripherals in the
    // firmware (boards/qemu/src/io.rs, boards/qemu/src/board.rs).
    let names: Vec<String> = BOARD_NAMES.iter().map(|n| format!("\"{n}\"")).collect();
    println!(
        "cargo::rustc-check-cfg=cfg(abtrack_board, values({}))",
        names.join(", ")
    );

    let target = env::var("TARGET").unwrap_or_default();
    let package = env::var("CARGO_PKG_NAME").unwrap_or_default();
    if env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os != "none") {
        // The host: only the library's hardware-free modules build.
        return ExitCode::SUCCESS;
    }
    let nrf52840_dk = env::var_os("CARGO_FEATURE_NRF52840_DK").is_some();
    let Some(board) = board_for(&package, &target, nrf52840_dk) else {
        eprintln!(
            "{package}: no board for target {target}; abtrack-firmware builds for \
             thumbv7em-none-eabihf, thumbv7m-none-eabi and thumbv6m-none-eabi, \
             abtrack-nrf52840-dk for thumbv7em-none-eabihf (the library alone: \
             cargo build -p abtrack)"
        );
        return ExitCode::FAILURE;
    };

    let (Some(manifest_dir), Some(out_dir)) =
        (env::var_os("CARGO_MANIFEST_DIR"), env::var_os("OUT_DIR"))
    else {
        eprintln!("{package}: CARGO_MANIFEST_DIR or OUT_DIR not set (not run by cargo?)");
        return ExitCode::FAILURE;
    };
    // Every firmware package sits in a directory under boards/.
    let boards_dir = Path::new(&manifest_dir).join("..");
    let out_dir = PathBuf::from(out_dir);
    let memory_x = boards_dir.join(board.layout_dir).join("memory.x");
    println!("cargo:rerun-if-changed={}", memory_x.display());
    for name in ["abtrack-board-memory.x", "memory.x"] {
        if let Err(e) = fs::copy(&memory_x, out_dir.join(name)) {
            eprintln!("{package}: cannot copy {}: {e}", memory_x.display());
            return ExitCode::FAILURE;
        }
    }
    println!("cargo:rustc-link-search={}", out_dir.display());
    // Flash starts at 0x0 on every board: no page-alignment padding. The
    // binaries are images, and so are abtrack-firmware's examples (cargo
    // refuses the examples' instruction for a package without one).
    let kinds: &[&str] = if package == "abtrack-firmware" {
        &["bins", "examples"]
    } else {
        &["bins"]
    };
    for kind in kinds {
        println!("cargo:rustc-link-arg-{kind}=--nmagic");
        println!("cargo:rustc-link-arg-{kind}=-Tlink.x");
        println!("cargo:rustc-link-arg-{kind}=-Tdefmt.x");
    }
    // Read by boards/qemu/src/board.rs (`env!`), for the firmware's reports.
    println!("cargo:rustc-env=ABTRACK_BOARD={}", board.name);
    println!("cargo:rustc-env=ABTRACK_CORE={}", board.core);
    // The profile's opt-level, which the benchmark prints beside its figures
    // (`s` for the release profile; `scripts/bench.sh` also measures `3`).
    let opt_level = env::var("OPT_LEVEL").unwrap_or_default();
    println!("cargo:rustc-env=ABTRACK_OPT_LEVEL={opt_level}");
    println!("cargo:rustc-cfg=abtrack_board=\"{}\"", board.name);
    ExitCode::SUCCESS
}
