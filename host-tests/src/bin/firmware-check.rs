//! Checks on release firmware ELFs (scripts/test.sh, docs/safety.md).
//!
//! ```text
//! firmware-check panics [--allow-crate <crate>=<reason>]... <elf>...
//!     Every branch into the panic machinery (core::panicking::*, panic_fmt,
//!     rust_begin_unwind) from any other function, with the source functions
//!     the call was inlined from, each marked as ours (abtrack's library or
//!     firmware) or a third-party crate's. Exit status 1 if any ELF has one
//!     of ours, one of a third-party crate not allowed, or defines a panic
//!     symbol with no call found, or if an allowed crate has no call in any
//!     ELF given (a stale allowance). --allow-crate names a third-party
//!     crate whose calls are reported but allowed, with the reason (printed
//!     with them); our own code cannot be allowed.
//! firmware-check layout --ram-origin <hex> <elf>...
//!     The flip-link layout: the stack runs from below the static data down
//!     to the bottom of RAM, nothing static below its top. Exit status 1 if
//!     not.
//! ```
//!
//! Uses llvm-objdump, llvm-symbolizer and llvm-nm (Debian's `llvm` package,
//! installed by scripts/setup.sh, or rustup's `llvm-tools`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use abtrack_host_tests::firmware_elf::{
    branches, callers_of, check_layout, crate_of, find_llvm_tool, frame_kind, is_rust_library,
    only_rust_library, owner_of, panic_calls, panic_symbols, parse_sections, parse_symbolizer,
    run_tool, Allowance, Branch, FrameKind, Owner, SourceFrame,
};

const USAGE: &str = "usage: firmware-check panics [--allow-crate <crate>=<reason>]... <elf>...\n       firmware-check layout --ram-origin <hex address> <elf>...";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("panics") => panics(&args[1..]),
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

/// True if no ELF has a panic path of ours or of a third-party crate not
/// allowed, and every allowance was used.
fn panics(args: &[String]) -> Result<bool, String> {
    let mut allowances: Vec<Allowance> = Vec::new();
    let mut elves: Vec<&String> = Vec::new();
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        if arg == "--allow-crate" {
            let value = rest.next().ok_or_else(|| USAGE.to_string())?;
            allowances.push(value.parse()?);
        } else if let Some(value) = arg.strip_prefix("--allow-crate=") {
            allowances.push(value.parse()?);
        } else {
            elves.push(arg);
        }
    }
    if elves.is_empty() {
        return Err(USAGE.to_string());
    }
    let objdump = tool("llvm-objdump")?;
    let symbolizer = tool("llvm-symbolizer")?;
    let nm = tool("llvm-nm")?;
    // Source paths are shown relative to the repository: the directory the
    // check runs in (scripts/test.sh runs it from the root).
    let root = std::env::current_dir()
        .map(|d| d.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut clean = true;
    let mut used = BTreeSet::new();
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
        if calls.is_empty() {
            clean = false;
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
        // Our crates: the library and this binary (its file name), and any
        // crate a frame in our sources belongs to.
        let binary = elf
            .file_name()
            .map(|n| n.to_string_lossy().replace('-', "_"))
            .unwrap_or_default();
        let mut own_crates = BTreeSet::from(["abtrack".to_string(), binary]);
        for (_, chain) in &frames {
            for frame in chain.iter().filter(|f| f.location.starts_with("src/")) {
                own_crates.insert(crate_of(&frame.function).to_string());
            }
        }
        if let Some(a) = allowances.iter().find(|a| own_crates.contains(&a.krate)) {
            return Err(format!(
                "--allow-crate {}: our own code ({}) cannot be allowed",
                a.krate,
                elf.display()
            ));
        }
        let mut own = BTreeSet::new();
        let mut own_count = 0usize;
        // Third-party crate(s) → (calls, functions).
        let mut third_party: BTreeMap<String, (usize, BTreeSet<String>)> = BTreeMap::new();
        let mut details = Vec::new();
        for call in &calls {
            let chain: &[SourceFrame] = frames
                .iter()
                .find(|(a, _)| *a == call.address)
                .map(|(_, f)| f.as_slice())
                .unwrap_or(&[]);
            let own_function = first_own_function(chain);
            // Code of core not inlined into ours or a dependency's: name
            // who calls it.
            let callers = if only_rust_library(chain) {
                outside_callers(&branches, &call.function)
            } else {
                Vec::new()
            };
            let owner = owner_of(&call.function, chain, &callers, &own_crates);
            let label = match &owner {
                Owner::Own => {
                    own_count += 1;
                    own.insert(own_function.unwrap_or(&call.function).to_string());
                    "ours".to_string()
                }
                Owner::ThirdParty(crates) => {
                    let names = crates.iter().cloned().collect::<Vec<_>>().join("+");
                    let entry = third_party.entry(names.clone()).or_default();
                    entry.0 += 1;
                    // The dependency's function with the check, and where
                    // it was inlined.
                    let checked = chain
                        .iter()
                        .find(|f| frame_kind(f) != FrameKind::RustLibrary)
                        .map_or(call.function.as_str(), |f| f.function.as_str());
                    entry.1.insert(if checked == call.function {
                        call.function.clone()
                    } else {
                        format!("{checked} (inlined into {})", call.function)
                    });
                    format!("third-party: {names}")
                }
            };
            details.push(format!(
                "  {:#010x} in {} -> {} [{label}]",
                call.address, call.function, call.target
            ));
            for (i, frame) in chain.iter().enumerate() {
                let arrow = if i == 0 { "at" } else { "inlined into" };
                details.push(format!(
                    "      {arrow} {} ({})",
                    frame.function, frame.location
                ));
            }
            if !callers.is_empty() {
                details.push(format!("      called from {}", callers.join(", ")));
            }
        }
        let third_count: usize = third_party.values().map(|(n, _)| n).sum();
        println!(
            "{}: {} call(s) into the panic machinery: {own_count} in our code, {third_count} in third-party crates",
            elf.display(),
            calls.len()
        );
        for line in details {
            println!("{line}");
        }
        if own_count > 0 {
            clean = false;
            println!(
                "  ours, not allowed: {own_count} call(s) in {}",
                own.into_iter().collect::<Vec<_>>().join(", ")
            );
        }
        for (names, (count, functions)) in third_party {
            let functions = functions.into_iter().collect::<Vec<_>>().join(", ");
            let reasons: Vec<&Allowance> = names
                .split('+')
                .filter_map(|n| allowances.iter().find(|a| a.krate == n))
                .collect();
            if reasons.len() == names.split('+').count() {
                used.extend(reasons.iter().map(|a| a.krate.clone()));
                let why: Vec<String> = reasons
                    .iter()
                    .map(|a| format!("{}: {}", a.krate, a.reason))
                    .collect();
                println!(
                    "  third-party {names}, allowed: {count} call(s) in {functions} ({})",
                    why.join("; ")
                );
            } else {
                clean = false;
                println!(
                    "  third-party {names}, not allowed: {count} call(s) in {functions} (remove them, or pass --allow-crate <crate>=<reason> with a documented reason)"
                );
            }
        }
    }
    for a in allowances.iter().filter(|a| !used.contains(&a.krate)) {
        clean = false;
        println!(
            "--allow-crate {}: no panic call of this crate in any ELF given; remove the allowance",
            a.krate
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
