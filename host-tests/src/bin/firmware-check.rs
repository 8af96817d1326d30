//! Checks on release firmware ELFs (scripts/test.sh, docs/safety.md;
//! `firmware-check --help`). Uses llvm-objdump, llvm-symbolizer and llvm-nm
//! (Debian's `llvm` package, installed by scripts/setup.sh, or rustup's
//! `llvm-tools`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use abtrack_host_tests::firmware_elf::{
    branches, callers_of, check_layout, crate_of, demangle, find_llvm_tool, frame_kind,
    is_own_source, is_rust_library, only_rust_library, owner_of, panic_calls, panic_symbols,
    parse_sections, parse_symbolizer, run_tool, section_size, Allowance, Branch, FrameKind, Owner,
    SourceFrame,
};

/// Checks on release firmware ELFs. Uses llvm-objdump, llvm-symbolizer and
/// llvm-nm (Debian's llvm package or rustup's llvm-tools).
#[derive(Debug, Parser)]
#[command(name = "firmware-check")]
struct Cli {
    #[command(subcommand)]
    check: Check,
}

#[derive(Debug, Subcommand)]
enum Check {
    /// Every branch into the panic machinery from any other function.
    #[command(
        long_about = "Every branch into the panic machinery (core::panicking::*, \
        panic_fmt, rust_begin_unwind) from any other function, with the source functions the \
        call was inlined from, each marked as ours (abtrack's library or firmware) or a \
        third-party crate's. Exit status 1 if any ELF has one of ours, one of a third-party \
        crate not allowed, or defines a panic symbol with no call found, or if an allowed crate \
        has no call in any ELF given (a stale allowance)."
    )]
    Panics {
        /// A third-party crate whose calls are reported but allowed, with the
        /// reason (printed with them); our own code cannot be allowed.
        #[arg(long = "allow-crate", value_name = "CRATE=REASON")]
        allowances: Vec<Allowance>,
        #[arg(value_name = "ELF", required = true)]
        elves: Vec<PathBuf>,
    },
    /// The flip-link layout: the stack runs from below the static data down
    /// to the bottom of RAM, nothing static below its top. Exit status 1 if
    /// not.
    Layout {
        /// The start of RAM, hexadecimal (0x optional).
        #[arg(long, value_name = "HEX", value_parser = hex_address)]
        ram_origin: u64,
        #[arg(value_name = "ELF", required = true)]
        elves: Vec<PathBuf>,
    },
    /// Initialised static data (`.data`), which costs its size in flash
    /// too and is copied at reset: each ELF's `.data` and `.bss`. Exit
    /// status 1 if any `.data` exceeds the limit.
    Data {
        /// The largest `.data` allowed, bytes.
        #[arg(long, value_name = "BYTES")]
        max_bytes: u64,
        #[arg(value_name = "ELF", required = true)]
        elves: Vec<PathBuf>,
    },
    /// Double-precision soft-float routines (f64 arithmetic, comparisons and
    /// conversions in software: `__aeabi_dadd`, `__muldf3`, ...), which an
    /// f32 image on a single-precision FPU should not need: each one
    /// defined, with the functions that call it. Exit status 1 if any ELF
    /// defines one.
    SoftDouble {
        #[arg(value_name = "ELF", required = true)]
        elves: Vec<PathBuf>,
    },
}

fn hex_address(text: &str) -> Result<u64, String> {
    u64::from_str_radix(text.trim_start_matches("0x"), 16).map_err(|e| e.to_string())
}

fn main() -> ExitCode {
    // Usage errors (clap) and failures to run the LLVM tools exit with
    // status 2, a failed check with 1.
    let result = match Cli::parse().check {
        Check::Panics { allowances, elves } => panics(&allowances, &elves),
        Check::Layout { ram_origin, elves } => layout(ram_origin, &elves),
        Check::Data { max_bytes, elves } => data(max_bytes, &elves),
        Check::SoftDouble { elves } => soft_double(&elves),
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
fn panics(allowances: &[Allowance], elves: &[PathBuf]) -> Result<bool, String> {
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
        // A branch can only reach a symbol the ELF defines: with no panic
        // symbol defined there is no call to look for, and the image is not
        // disassembled (most of this check's time).
        let symbols = panic_symbols(&run_tool(&nm, &["--defined-only", &elf_arg])?);
        if symbols.is_empty() {
            println!(
                "{}: no panic calls (no panic symbol defined)",
                elf.display()
            );
            continue;
        }
        let branches = branches(&run_tool(
            &objdump,
            &["-d", "--no-show-raw-insn", &elf_arg],
        )?);
        let calls = panic_calls(&branches);
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
        // Our crates: the library, the firmware's library and this binary
        // (its file name), and any crate a frame in our sources belongs to.
        let binary = elf
            .file_name()
            .map(|n| n.to_string_lossy().replace('-', "_"))
            .unwrap_or_default();
        let mut own_crates = BTreeSet::from([
            "abtrack".to_string(),
            "abtrack_firmware".to_string(),
            binary,
        ]);
        for (_, chain) in &frames {
            for frame in chain.iter().filter(|f| is_own_source(&f.location)) {
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
/// firmware): who to blame for the call.
fn first_own_function(chain: &[SourceFrame]) -> Option<&str> {
    chain
        .iter()
        .find(|f| is_own_source(&f.location))
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
fn layout(ram_origin: u64, elves: &[PathBuf]) -> Result<bool, String> {
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

/// True if no ELF's `.data` exceeds `max_bytes`.
fn data(max_bytes: u64, elves: &[PathBuf]) -> Result<bool, String> {
    let objdump = tool("llvm-objdump")?;
    let mut ok = true;
    for elf in elves {
        let elf_arg = elf.to_string_lossy();
        let sections = parse_sections(&run_tool(&objdump, &["-h", &elf_arg])?);
        let (data, bss) = (
            section_size(&sections, ".data"),
            section_size(&sections, ".bss"),
        );
        let verdict = if data <= max_bytes {
            "ok"
        } else {
            ok = false;
            "too large"
        };
        println!(
            "{}: .data {data} bytes (limit {max_bytes}: {verdict}), .bss {bss} bytes",
            elf.display()
        );
    }
    Ok(ok)
}

/// compiler-builtins' double-precision soft-float routines, by their ARM
/// EABI (RTABI §4.1.2) and libgcc names.
const SOFT_DOUBLE_ROUTINES: &[&str] = &[
    "__aeabi_dadd",
    "__aeabi_dsub",
    "__aeabi_drsub",
    "__aeabi_dmul",
    "__aeabi_ddiv",
    "__aeabi_dneg",
    "__aeabi_dcmpeq",
    "__aeabi_dcmplt",
    "__aeabi_dcmple",
    "__aeabi_dcmpge",
    "__aeabi_dcmpgt",
    "__aeabi_dcmpun",
    "__aeabi_cdcmpeq",
    "__aeabi_cdcmple",
    "__aeabi_cdrcmple",
    "__aeabi_d2f",
    "__aeabi_f2d",
    "__aeabi_d2iz",
    "__aeabi_d2uiz",
    "__aeabi_d2lz",
    "__aeabi_d2ulz",
    "__aeabi_i2d",
    "__aeabi_ui2d",
    "__aeabi_l2d",
    "__aeabi_ul2d",
    "__adddf3",
    "__subdf3",
    "__muldf3",
    "__divdf3",
    "__negdf2",
    "__eqdf2",
    "__nedf2",
    "__gedf2",
    "__gtdf2",
    "__ledf2",
    "__ltdf2",
    "__unorddf2",
    "__cmpdf2",
    "__extendsfdf2",
    "__truncdfsf2",
    "__fixdfsi",
    "__fixunsdfsi",
    "__fixdfdi",
    "__fixunsdfdi",
    "__floatsidf",
    "__floatunsidf",
    "__floatdidf",
    "__floatundidf",
    "__powidf2",
];

/// The routine `symbol` (demangled) is, if it is one of
/// [`SOFT_DOUBLE_ROUTINES`] (compiler-builtins defines each under its
/// module path too: `compiler_builtins::float::add::__adddf3`).
fn soft_double_routine(symbol: &str) -> Option<&'static str> {
    let last = symbol.rsplit("::").next().unwrap_or(symbol);
    SOFT_DOUBLE_ROUTINES.iter().copied().find(|r| *r == last)
}

/// True if no ELF defines a double-precision soft-float routine.
fn soft_double(elves: &[PathBuf]) -> Result<bool, String> {
    let objdump = tool("llvm-objdump")?;
    let nm = tool("llvm-nm")?;
    let mut clean = true;
    for elf in elves {
        let elf_arg = elf.to_string_lossy();
        let symbols = run_tool(&nm, &["--defined-only", &elf_arg])?;
        let defined: BTreeSet<String> = symbols
            .lines()
            .filter_map(|l| l.splitn(3, ' ').nth(2))
            .map(demangle)
            .filter(|name| soft_double_routine(name).is_some())
            .collect();
        if defined.is_empty() {
            println!("{}: no double-precision soft-float routine", elf.display());
            continue;
        }
        clean = false;
        let branches = branches(&run_tool(
            &objdump,
            &["-d", "--no-show-raw-insn", &elf_arg],
        )?);
        println!(
            "{}: {} double-precision soft-float routines",
            elf.display(),
            defined.len()
        );
        for routine in &defined {
            // Callers outside the soft-float routines themselves.
            let callers: Vec<String> = callers_of(&branches, routine)
                .into_iter()
                .filter(|f| soft_double_routine(f).is_none() && !f.starts_with("compiler_builtins"))
                .collect();
            println!("  {routine} <- {}", callers.join(", "));
        }
    }
    Ok(clean)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    fn parse(args: &[&str]) -> Result<Check, clap::Error> {
        Cli::try_parse_from(std::iter::once("firmware-check").chain(args.iter().copied()))
            .map(|c| c.check)
    }

    #[test]
    fn command_lines_of_scripts_parse() {
        Cli::command().debug_assert();
        // scripts/test.sh: the allowance as one `--allow-crate=...` word.
        let Ok(Check::Panics { allowances, elves }) = parse(&[
            "panics",
            "--allow-crate=minikalman=the benchmark's Kalman anchor",
            "a.elf",
            "b.elf",
        ]) else {
            panic!("panics not parsed")
        };
        assert_eq!(allowances.len(), 1);
        assert_eq!(allowances[0].krate, "minikalman");
        assert_eq!(elves.len(), 2);
        let Ok(Check::Panics { allowances, .. }) = parse(&[
            "panics",
            "--allow-crate",
            "x=why",
            "--allow-crate",
            "y=why",
            "a.elf",
        ]) else {
            panic!("two allowances not parsed")
        };
        assert_eq!(allowances.len(), 2);
        let Ok(Check::Layout { ram_origin, elves }) =
            parse(&["layout", "--ram-origin", "0x20000000", "a.elf"])
        else {
            panic!("layout not parsed")
        };
        assert_eq!((ram_origin, elves.len()), (0x2000_0000, 1));
        let Ok(Check::Data { max_bytes, elves }) =
            parse(&["data", "--max-bytes", "4096", "a.elf", "b.elf"])
        else {
            panic!("data not parsed")
        };
        assert_eq!((max_bytes, elves.len()), (4096, 2));
        let Ok(Check::SoftDouble { elves }) = parse(&["soft-double", "a.elf"]) else {
            panic!("soft-double not parsed")
        };
        assert_eq!(elves.len(), 1);
    }

    #[test]
    fn soft_double_routines_are_recognised_by_name() {
        assert_eq!(soft_double_routine("__aeabi_dmul"), Some("__aeabi_dmul"));
        assert_eq!(
            soft_double_routine("compiler_builtins::float::add::__adddf3"),
            Some("__adddf3")
        );
        // Single precision, integer and memory routines are not.
        for name in [
            "__aeabi_fmul",
            "__addsf3",
            "__aeabi_l2f",
            "__aeabi_memcpy",
            "__aeabi_uldivmod",
        ] {
            assert_eq!(soft_double_routine(name), None, "{name}");
        }
        assert_eq!(soft_double_routine("libm::math::sqrt::sqrtf"), None);
    }

    #[test]
    fn data_and_bss_sizes_are_read_from_the_section_headers() {
        let sections = parse_sections(
            "Idx Name            Size     VMA      LMA      Type
  0                 00000000 00000000 00000000
  1 .text           00008220 00000400 00000400 TEXT
  2 .data           00001004 203fac68 00008c98 DATA
  3 .bss            00000e90 203fbc6c 203fbc6c BSS
",
        );
        assert_eq!(section_size(&sections, ".data"), 0x1004);
        assert_eq!(section_size(&sections, ".bss"), 0xe90);
        assert_eq!(section_size(&sections, ".uninit"), 0, "no such section");
    }

    #[test]
    fn refuses_bad_command_lines() {
        for args in [
            &[][..],
            &["panics"],
            &["panics", "--allow-crate", "no-reason", "a.elf"],
            &["layout", "a.elf"],
            &["layout", "--ram-origin", "0xzz", "a.elf"],
            &["layout", "--ram-origin", "0x20000000"],
            &["data", "a.elf"],
            &["data", "--max-bytes", "4k", "a.elf"],
            &["data", "--max-bytes", "4096"],
            &["frobnicate"],
        ] {
            let e = parse(args).map(|_| ()).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{args:?}: {e}");
        }
    }
}
