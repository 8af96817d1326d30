//! Firmware link set-up: picks the board's memory layout from the target
//! triple and passes the linker scripts to the firmware binaries only, so the
//! library still builds for any target (host-tests builds it for the host).
//!
//! | target                | board (QEMU) | memory layout                                  |
//! |-----------------------|--------------|------------------------------------------------|
//! | thumbv7em-none-eabihf | mps2-an386   | `memory.x`                                     |
//! | thumbv7m-none-eabi    | mps2-an385   | `memory.x`                                     |
//! | thumbv6m-none-eabi    | microbit     | `memory.x` narrowed by `boards/microbit/nrf51.x` |
//!
//! Why the micro:bit layout is a narrowing script rather than a second
//! `memory.x`: rust-lld resolves cortex-m-rt's `INCLUDE memory.x` in its
//! working directory (the crate root) before the search path, so the
//! top-level file is always the one read; see `boards/microbit/nrf51.x`.

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// A board the firmware runs on.
struct Board {
    /// QEMU machine name.
    qemu_machine: &'static str,
    core: &'static str,
    /// Linker script narrowing `memory.x` to this board, relative to the
    /// crate root.
    narrowing_script: Option<&'static str>,
}

fn board_for(target: &str) -> Option<Board> {
    if target == "thumbv7em-none-eabihf" {
        Some(Board {
            qemu_machine: "mps2-an386",
            core: "Cortex-M4F",
            narrowing_script: None,
        })
    } else if target == "thumbv7m-none-eabi" {
        Some(Board {
            qemu_machine: "mps2-an385",
            core: "Cortex-M3",
            narrowing_script: None,
        })
    } else if target == "thumbv6m-none-eabi" {
        Some(Board {
            qemu_machine: "microbit",
            core: "Cortex-M0",
            narrowing_script: Some("boards/microbit/nrf51.x"),
        })
    } else {
        None
    }
}

fn main() -> ExitCode {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=boards/microbit/nrf51.x");
    // `cfg(abtrack_board = "...")` picks the board's peripherals in the
    // firmware (src/firmware/io.rs).
    println!(
        "cargo::rustc-check-cfg=cfg(abtrack_board, values(\"mps2-an386\", \"mps2-an385\", \"microbit\"))"
    );

    let target = env::var("TARGET").unwrap_or_default();
    let is_bare_metal_arm = target.starts_with("thumbv")
        && (target.ends_with("-none-eabi") || target.ends_with("-none-eabihf"));
    // Without the firmware binaries there is nothing to link: the library is
    // an rlib and builds for any target.
    if env::var_os("CARGO_FEATURE_FIRMWARE").is_none() || !is_bare_metal_arm {
        return ExitCode::SUCCESS;
    }

    let Some(board) = board_for(&target) else {
        eprintln!(
            "abtrack firmware: no board for target {target}; supported: \
             thumbv7em-none-eabihf, thumbv7m-none-eabi, thumbv6m-none-eabi \
             (or build the library alone with --no-default-features)"
        );
        return ExitCode::FAILURE;
    };

    let (Some(manifest_dir), Some(out_dir)) =
        (env::var_os("CARGO_MANIFEST_DIR"), env::var_os("OUT_DIR"))
    else {
        eprintln!("abtrack firmware: CARGO_MANIFEST_DIR or OUT_DIR not set (not run by cargo?)");
        return ExitCode::FAILURE;
    };
    let manifest_dir = Path::new(&manifest_dir);
    let out_dir = PathBuf::from(out_dir);
    // The usual cortex-m-rt set-up: memory.x on the linker search path, so it
    // is found even when the linker runs elsewhere (e.g. a workspace root).
    let memory_x = manifest_dir.join("memory.x");
    if let Err(e) = fs::copy(&memory_x, out_dir.join("memory.x")) {
        eprintln!("abtrack firmware: cannot copy {}: {e}", memory_x.display());
        return ExitCode::FAILURE;
    }
    println!("cargo:rustc-link-search={}", out_dir.display());
    if let Some(script) = board.narrowing_script {
        println!(
            "cargo:rustc-link-arg-bins=-T{}",
            manifest_dir.join(script).display()
        );
    }
    // Flash starts at 0x0 on every board: no page-alignment padding.
    println!("cargo:rustc-link-arg-bins=--nmagic");
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
    // Read by src/firmware/board.rs (`env!`), for the firmware's reports.
    println!("cargo:rustc-env=ABTRACK_BOARD={}", board.qemu_machine);
    println!("cargo:rustc-env=ABTRACK_CORE={}", board.core);
    println!("cargo:rustc-cfg=abtrack_board=\"{}\"", board.qemu_machine);
    ExitCode::SUCCESS
}
