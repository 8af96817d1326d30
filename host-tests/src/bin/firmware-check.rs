//! Checks on release firmware ELFs (scripts/test.sh, docs/safety.md).
//!
//! ```text
//! firmware-check panics <elf>...
//!     Every branch into the panic machinery (core::panicking::*, panic_fmt,
//!     rust_begin_unwind) from any other function, with the source functions
//!     the call was inlined from. Exit status 1 if any ELF has one, or
//!     defines a panic symbol at all.
//! firmware-check layout --ram-origin <hex> <elf>...
//!     The flip-link layout: the stack runs from below the static data down
//!     to the bottom of RAM, nothing static below its top. Exit status 1 if
//!     not.
//! ```
//!
//! Uses llvm-objdump, llvm-symbolizer and llvm-nm (Debian's `llvm` package,
//! installed by scripts/setup.sh, or rustup's `llvm-tools`).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use abtrack_host_tests::firmware_elf::{
    branches, callers_of, check_layout, find_llvm_tool, panic_calls, panic_symbols, parse_sections,
    parse_symbolizer, run_tool, Branch, SourceFrame,
};

const USAGE: &str = "usage: firmware-check panics <elf>...\n       firmware-check layout --ram-origin <hex address> <elf>...";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("panics") if args.len() > 1 => panics(&args[1..]),
        Some("layout") => layout(&args[1..]),
        Some("-h" | "--help") => {
            println!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        _ => Err(USAGE.to_string()),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("firmware-check: {e}");
            ExitCode::from(2)
        }
    }
}

fn tool(name: &str) -> Result<PathBuf, String> {
    find_llvm_tool(name).ok_or_else(|| {
        format!("{name} not found: install Debian's llvm package (apt-get install llvm) or rustup's llvm-tools (rustup component add llvm-tools)")
    })
}

/// True if no ELF has a panic path.
fn panics(elves: &[String]) -> Result<bool, String> {
    let objdump = tool("llvm-objdump")?;
    let symbolizer = tool("llvm-symbolizer")?;
    let nm = tool("llvm-nm")?;
    // Source paths are shown relative to the repository: the directory the
    // check runs in (scripts/test.sh runs it from the root).
    let root = std::env::current_dir()
        .map(|d| d.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut clean = true;
    for elf in elves {
        let elf = Path::new(elf);
        let elf_arg = elf.to_string_lossy();
        let branches = branches(&run_tool(
            &objdump,
            &["-d", "--no-show-raw-insn", &elf_arg],
        )?);
        let calls = panic_calls(&branches);
        let symbols = panic_symbols(&run_tool(&nm, &["--defined-only", &elf_arg])?);
        if calls.is_empty() && symbols.is_empty() {
            println!("{}: no panic calls", elf.display());
            continue;
        }
        clean = false;
        if calls.is_empty() {
            println!(
                "{}: defines panic symbols but no branch to them was found: {}",
                elf.display(),
                symbols.into_iter().collect::<Vec<_>>().join(", ")
            );
            continue;
        }
        let addresses: Vec<String> = calls.iter().map(|c| format!("{:#x}", c.address)).collect();
        let mut args = vec!["--inlining", "--no-demangle", "--print-address", "--obj"];
        let elf_str = elf.to_string_lossy();
        args.push(&elf_str);
        args.extend(addresses.iter().map(String::as_str));
        let symbolized = run_tool(&symbolizer, &args)?;
        let frames = parse_symbolizer(&symbolized, &root);
        println!(
            "{}: {} call(s) into the panic machinery",
            elf.display(),
            calls.len()
        );
        let mut containing = BTreeSet::new();
        for call in &calls {
            println!(
                "  {:#010x} in {} -> {}",
                call.address, call.function, call.target
            );
            let chain: &[SourceFrame] = frames
                .iter()
                .find(|(a, _)| *a == call.address)
                .map(|(_, f)| f.as_slice())
                .unwrap_or(&[]);
            for (i, frame) in chain.iter().enumerate() {
                let arrow = if i == 0 { "at" } else { "inlined into" };
                println!("      {arrow} {} ({})", frame.function, frame.location);
            }
            match first_own_function(chain) {
                Some(own) => {
                    containing.insert(own.to_string());
                }
                None => {
                    // Code of core or a dependency, not inlined into ours:
                    // name who calls it.
                    let callers = outside_callers(&branches, &call.function);
                    if !callers.is_empty() {
                        println!("      called from {}", callers.join(", "));
                    }
                    containing.insert(call.function.clone());
                }
            }
        }
        println!(
            "  functions containing them: {}",
            containing.into_iter().collect::<Vec<_>>().join(", ")
        );
    }
    Ok(clean)
}

/// The innermost frame in abtrack's own sources (the library or the
/// firmware, under the repository's src/): who to blame for the call.
fn first_own_function(chain: &[SourceFrame]) -> Option<&str> {
    chain
        .iter()
        .find(|f| f.location.starts_with("src/"))
        .map(|f| f.function.as_str())
}

/// Rust's own libraries, by symbol.
fn is_rust_library(function: &str) -> bool {
    ["core::", "alloc::", "compiler_builtins::"]
        .iter()
        .any(|p| function.contains(p))
}

/// The nearest callers of `function` outside Rust's own libraries, walking
/// up through callers that are in them (a few levels at most).
fn outside_callers(branches: &[Branch], function: &str) -> Vec<String> {
    let mut visited = BTreeSet::from([function.to_string()]);
    let mut frontier = vec![function.to_string()];
    let mut found = BTreeSet::new();
    for _ in 0..4 {
        let mut next = Vec::new();
        for f in &frontier {
            for caller in callers_of(branches, f) {
                if !visited.insert(caller.clone()) {
                    continue;
                }
                if is_rust_library(&caller) {
                    next.push(caller);
                } else {
                    found.insert(caller);
                }
            }
        }
        if !found.is_empty() || next.is_empty() {
            break;
        }
        frontier = next;
    }
    found.into_iter().collect()
}

/// True if every ELF has the protected layout.
fn layout(args: &[String]) -> Result<bool, String> {
    let [flag, origin, elves @ ..] = args else {
        return Err(USAGE.to_string());
    };
    if flag != "--ram-origin" || elves.is_empty() {
        return Err(USAGE.to_string());
    }
    let ram_origin = u64::from_str_radix(origin.trim_start_matches("0x"), 16)
        .map_err(|e| format!("--ram-origin {origin}: {e}"))?;
    let objdump = tool("llvm-objdump")?;
    let nm = tool("llvm-nm")?;
    let mut ok = true;
    for elf in elves {
        let elf = Path::new(elf);
        let elf_arg = elf.to_string_lossy();
        let sections = parse_sections(&run_tool(&objdump, &["-h", &elf_arg])?);
        let symbols = run_tool(&nm, &[&elf_arg])?;
        match check_layout(&symbols, &sections, ram_origin) {
            Ok(l) => {
                let statics = match l.statics {
                    Some((low, high)) => format!("statics {low:#010x}..{high:#010x}"),
                    None => "no statics".to_string(),
                };
                println!(
                    "{}: stack {:#010x}..{:#010x} ({} bytes) below the {statics}",
                    elf.display(),
                    l.stack_bottom,
                    l.stack_top,
                    l.stack_top - l.stack_bottom
                );
            }
            Err(e) => {
                ok = false;
                println!("{}: {e}", elf.display());
            }
        }
    }
    Ok(ok)
}
