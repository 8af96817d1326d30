//! Checks on the release firmware ELFs (the `firmware-check` tool,
//! docs/safety.md): no call into the panic machinery, and the flip-link
//! memory layout (stack below the static data).
//!
//! The ELFs are read through LLVM's tools (Debian's `llvm` package or
//! rustup's `llvm-tools`): `llvm-objdump -d` for the branches,
//! `llvm-symbolizer --inlining` for the source functions a call was inlined
//! from (the release profile keeps full debug information), `llvm-nm` for
//! the symbols. The parsers take the tools' text, so they are tested on
//! their own (tests/it/tools/firmware_check.rs).

use std::collections::BTreeSet;
use std::fmt;
use std::path::{Path, PathBuf};
use std::process::Command;

/// True for a symbol of the panic machinery: anything in `core::panicking`,
/// `panic_fmt`, and the panic handler's symbol `rust_begin_unwind`.
pub fn is_panic_symbol(symbol: &str) -> bool {
    symbol.contains("core::panicking::")
        || symbol.contains("panic_fmt")
        || symbol == "rust_begin_unwind"
}

/// A branch from outside the panic machinery into it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PanicCall {
    /// Address of the branch instruction.
    pub address: u64,
    /// The function (symbol) holding the branch.
    pub function: String,
    /// The panic symbol branched to.
    pub target: String,
}

/// A symbol name as Rust writes it: demangled, without the hash.
pub fn demangle(symbol: &str) -> String {
    format!("{:#}", rustc_demangle::demangle(symbol))
}

/// A branch (`bl`, `b`, `b.w`, conditional forms, `blx`) to a symbol's start,
/// from `llvm-objdump -d` output; names demangled.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Branch {
    pub address: u64,
    /// The function holding the branch.
    pub function: String,
    pub target: String,
}

/// Every branch to a symbol's start in `llvm-objdump -d` output (mangled
/// names), with the function it is in.
pub fn branches(disassembly: &str) -> Vec<Branch> {
    let mut found = Vec::new();
    let mut function: Option<String> = None;
    for line in disassembly.lines() {
        if let Some(name) = function_header(line) {
            // A mapping symbol ($t code, $d data) after a literal pool or
            // jump table continues the same function.
            if !is_mapping_symbol(name) {
                function = Some(demangle(name));
            }
            continue;
        }
        let (Some(current), Some((address, mnemonic, target))) = (&function, branch(line)) else {
            continue;
        };
        if mnemonic.starts_with('b') {
            found.push(Branch {
                address,
                function: current.clone(),
                target: demangle(target),
            });
        }
    }
    found
}

/// The panic calls among `branches`: every branch whose target is a panic
/// symbol, made from a function that is not one itself (the machinery
/// calling itself is not a new path).
pub fn panic_calls(branches: &[Branch]) -> Vec<PanicCall> {
    branches
        .iter()
        .filter(|b| !is_panic_symbol(&b.function) && is_panic_symbol(&b.target))
        .map(|b| PanicCall {
            address: b.address,
            function: b.function.clone(),
            target: b.target.clone(),
        })
        .collect()
}

/// Arm ELF mapping symbols (`$a`, `$t`, `$d`, `$x`, maybe with `.N`): they
/// mark code or data inside a function, not a function.
fn is_mapping_symbol(name: &str) -> bool {
    let base = name.split('.').next().unwrap_or(name);
    matches!(base, "$a" | "$t" | "$d" | "$x")
}

/// The functions that branch to `callee` (demangled, as [`PanicCall`]
/// names it).
pub fn callers_of(branches: &[Branch], callee: &str) -> BTreeSet<String> {
    branches
        .iter()
        .filter(|b| b.function != callee && b.target == callee)
        .map(|b| b.function.clone())
        .collect()
}

/// `00001234 <name>:` → `name`.
fn function_header(line: &str) -> Option<&str> {
    let (address, rest) = line.split_once(' ')?;
    if address.is_empty() || !address.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    rest.strip_prefix('<')?.strip_suffix(">:")
}

/// `    1240:      bl  0x1000 <name>` → (0x1240, "bl", "name"): an
/// instruction whose operand is a symbol's start. An operand inside a
/// function (`<name+0x4>`) is not a call: at best a branch within it, at
/// worst padding or data decoded as an instruction.
fn branch(line: &str) -> Option<(u64, &str, &str)> {
    let (address, rest) = line.trim_start().split_once(':')?;
    let address = u64::from_str_radix(address, 16).ok()?;
    let rest = rest.trim_start();
    let mnemonic = rest.split_whitespace().next()?;
    let open = rest.find('<')?;
    let close = rest.rfind('>')?;
    let symbol = rest.get(open + 1..close)?;
    if symbol.contains("+0x") {
        return None;
    }
    Some((address, mnemonic, symbol))
}

/// One source frame of a code address (`llvm-symbolizer --inlining`):
/// innermost first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceFrame {
    pub function: String,
    /// `file:line:column`; the path shortened (see [`parse_symbolizer`]).
    pub location: String,
}

/// Parses `llvm-symbolizer --inlining --no-demangle` output for several
/// addresses (given with `--print-address`, one block per address, blocks
/// separated by a blank line): address → frames, innermost first. Paths
/// under `root` (the repository) are made relative to it.
pub fn parse_symbolizer(output: &str, root: &str) -> Vec<(u64, Vec<SourceFrame>)> {
    let mut result = Vec::new();
    for block in output.split("\n\n") {
        let mut lines = block.lines().filter(|l| !l.trim().is_empty());
        let Some(first) = lines.next() else {
            continue;
        };
        let Some(address) = first
            .trim()
            .strip_prefix("0x")
            .and_then(|h| u64::from_str_radix(h, 16).ok())
        else {
            continue;
        };
        let rest: Vec<&str> = lines.collect();
        let frames = rest
            .chunks(2)
            .filter_map(|pair| match pair {
                [function, location] => Some(SourceFrame {
                    function: demangle(function.trim()),
                    location: shorten_path(location.trim(), root),
                }),
                _ => None,
            })
            .collect();
        result.push((address, frames));
    }
    result
}

/// A source path made short: relative to `root` (the repository) for our
/// own sources, from the crate directory for a registry crate
/// (`heapless-0.9.3/src/spsc.rs`), from the library directory for Rust's own
/// (`core/src/panic.rs`).
fn shorten_path(location: &str, root: &str) -> String {
    let root = root.trim_end_matches('/');
    if let Some(relative) = location
        .strip_prefix(root)
        .and_then(|r| r.strip_prefix('/'))
    {
        // A package may name sources outside its directory
        // (`boards/nrf52840-dk/../qemu/src/main.rs`): drop the detour.
        let mut parts: Vec<&str> = Vec::new();
        for part in relative.split('/') {
            match part {
                ".." => {
                    parts.pop();
                }
                "." => {}
                _ => parts.push(part),
            }
        }
        return parts.join("/");
    }
    if let Some((_, tail)) = location.split_once("/registry/src/") {
        // Drop the registry's index directory (`index.crates.io-…/`).
        return tail
            .split_once('/')
            .map_or(tail, |(_, rest)| rest)
            .to_string();
    }
    if let Some((_, tail)) = location.split_once("/library/") {
        return tail.to_string();
    }
    location.to_string()
}

/// The panic symbols defined in an ELF (`llvm-nm` output), demangled.
pub fn panic_symbols(nm_output: &str) -> BTreeSet<String> {
    nm_output
        .lines()
        .filter_map(|l| {
            let mut parts = l.splitn(3, ' ');
            let _address = parts.next()?;
            let _kind = parts.next()?;
            let name = demangle(parts.next()?);
            is_panic_symbol(&name).then_some(name)
        })
        .collect()
}

/// The symbols `llvm-nm` lists, by name: (address, name).
pub fn symbol_address(nm_output: &str, wanted: &str) -> Option<u64> {
    nm_output.lines().find_map(|l| {
        let mut parts = l.splitn(3, ' ');
        let address = parts.next()?;
        let _kind = parts.next()?;
        let name = parts.next()?;
        (name == wanted)
            .then(|| u64::from_str_radix(address, 16).ok())
            .flatten()
    })
}

/// A section of the ELF (`llvm-objdump -h` output): name, size, address,
/// and whether it occupies memory at run time.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    pub name: String,
    pub size: u64,
    pub address: u64,
}

/// The size of the section `name` (0 if the ELF has none; sizes of
/// sections of the same name add up).
pub fn section_size(sections: &[Section], name: &str) -> u64 {
    sections
        .iter()
        .filter(|s| s.name == name)
        .map(|s| s.size)
        .sum()
}

/// Parses `llvm-objdump -h` (`Idx Name Size VMA Type`).
pub fn parse_sections(headers: &str) -> Vec<Section> {
    headers
        .lines()
        .filter_map(|l| {
            let fields: Vec<&str> = l.split_whitespace().collect();
            // Section 0 has no name: four fields.
            let [index, name, size, address, _load_address, ..] = fields.as_slice() else {
                return None;
            };
            index.parse::<u32>().ok()?;
            Some(Section {
                name: name.to_string(),
                size: u64::from_str_radix(size, 16).ok()?,
                address: u64::from_str_radix(address, 16).ok()?,
            })
        })
        .collect()
}

/// The flip-link layout of one image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StackLayout {
    /// Lowest stack address (`_stack_end`): the bottom of RAM.
    pub stack_bottom: u64,
    /// Initial stack pointer (`_stack_start`).
    pub stack_top: u64,
    /// Lowest and highest address of the static data (.data, .bss, .uninit).
    pub statics: Option<(u64, u64)>,
}

/// Why a layout is not the protected one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LayoutError {
    MissingSymbol(&'static str),
    /// The stack does not grow towards the bottom of RAM.
    StackNotAtBottom {
        stack_bottom: u64,
        ram_origin: u64,
    },
    /// Some static data lies below the stack's top (the stack would run
    /// into it).
    StaticsBelowStackTop {
        lowest_static: u64,
        stack_top: u64,
    },
}

impl fmt::Display for LayoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LayoutError::MissingSymbol(s) => write!(f, "no symbol {s}"),
            LayoutError::StackNotAtBottom {
                stack_bottom,
                ram_origin,
            } => write!(
                f,
                "the stack's lowest address {stack_bottom:#010x} is not the bottom of RAM {ram_origin:#010x}"
            ),
            LayoutError::StaticsBelowStackTop {
                lowest_static,
                stack_top,
            } => write!(
                f,
                "static data at {lowest_static:#010x} lies below the stack's top {stack_top:#010x}: an overflow would run into it (not linked with flip-link?)"
            ),
        }
    }
}

/// Checks that the stack grows from below the statics to the bottom of RAM
/// (`ram_origin`), with nothing static below it.
pub fn check_layout(
    nm_output: &str,
    sections: &[Section],
    ram_origin: u64,
) -> Result<StackLayout, LayoutError> {
    let stack_bottom =
        symbol_address(nm_output, "_stack_end").ok_or(LayoutError::MissingSymbol("_stack_end"))?;
    let stack_top = symbol_address(nm_output, "_stack_start")
        .ok_or(LayoutError::MissingSymbol("_stack_start"))?;
    let statics: Vec<&Section> = sections
        .iter()
        .filter(|s| matches!(s.name.as_str(), ".data" | ".bss" | ".uninit") && s.size > 0)
        .collect();
    let low = statics.iter().map(|s| s.address).min();
    let high = statics.iter().map(|s| s.address + s.size).max();
    if stack_bottom != ram_origin {
        return Err(LayoutError::StackNotAtBottom {
            stack_bottom,
            ram_origin,
        });
    }
    if let Some(lowest_static) = low {
        if lowest_static < stack_top {
            return Err(LayoutError::StaticsBelowStackTop {
                lowest_static,
                stack_top,
            });
        }
    }
    Ok(StackLayout {
        stack_bottom,
        stack_top,
        statics: low.zip(high),
    })
}

/// An LLVM tool: from `$LLVM_TOOLS_DIR`, PATH (also versioned, e.g.
/// `llvm-objdump-14`), or rustup's `llvm-tools` component.
pub fn find_llvm_tool(name: &str) -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("LLVM_TOOLS_DIR") {
        let p = Path::new(&dir).join(name);
        if p.is_file() {
            return Some(p);
        }
    }
    let path = std::env::var_os("PATH")?;
    let mut versioned: Vec<(u32, PathBuf)> = Vec::new();
    for dir in std::env::split_paths(&path) {
        let exact = dir.join(name);
        if exact.is_file() {
            return Some(exact);
        }
        if let Ok(entries) = std::fs::read_dir(&dir) {
            for e in entries.flatten() {
                let file = e.file_name();
                let file = file.to_string_lossy();
                if let Some(v) = file
                    .strip_prefix(name)
                    .and_then(|r| r.strip_prefix('-'))
                    .and_then(|v| v.parse::<u32>().ok())
                {
                    versioned.push((v, e.path()));
                }
            }
        }
    }
    if let Some((_, p)) = versioned.into_iter().max_by_key(|(v, _)| *v) {
        return Some(p);
    }
    // rustup's llvm-tools: <sysroot>/lib/rustlib/<host>/bin/
    let sysroot = Command::new("rustc")
        .args(["--print", "sysroot"])
        .output()
        .ok()?;
    let sysroot = String::from_utf8(sysroot.stdout).ok()?;
    let rustlib = Path::new(sysroot.trim()).join("lib/rustlib");
    std::fs::read_dir(rustlib).ok()?.flatten().find_map(|e| {
        let p = e.path().join("bin").join(name);
        p.is_file().then_some(p)
    })
}

/// Runs a tool with `args` and returns its standard output, or a one-line
/// error.
pub fn run_tool(tool: &Path, args: &[&str]) -> Result<String, String> {
    let output = Command::new(tool)
        .args(args)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", tool.display()))?;
    if !output.status.success() {
        return Err(format!(
            "{} {} failed: {}",
            tool.display(),
            args.join(" "),
            String::from_utf8_lossy(&output.stderr).trim()
        ));
    }
    String::from_utf8(output.stdout).map_err(|e| format!("{}: {e}", tool.display()))
}

/// The crate a demangled function path belongs to: its first path segment,
/// through an impl's `<`, `&` or `mut ` (`<core::num::X>::f` → `core`).
pub fn crate_of(function: &str) -> &str {
    let path = function.trim_start_matches(['<', '&', '*', '[', '(']);
    let path = path.strip_prefix("mut ").unwrap_or(path);
    path.split("::").next().unwrap_or(path)
}

/// Rust's own libraries, by symbol (`core::`, `alloc::`,
/// `compiler_builtins::` anywhere in it, e.g. in an impl's type).
pub fn is_rust_library(function: &str) -> bool {
    ["core::", "alloc::", "compiler_builtins::"]
        .iter()
        .any(|p| function.contains(p))
}

/// Whose code a panic call is in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Owner {
    /// The library's or the firmware's own code: never allowed.
    Own,
    /// Code of these third-party crates (a function of Rust's own libraries
    /// is attributed to the crates of its nearest callers outside them).
    ThirdParty(BTreeSet<String>),
}

/// What a source frame's location says about whose code it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// Our sources ([`is_own_source`]).
    Own,
    /// Rust's own libraries (`core/`, `alloc/`, `std/`,
    /// `compiler_builtins-…/`), or no location.
    RustLibrary,
    /// A registry crate (`minikalman-0.8.1/src/…` → `minikalman`; `-` in
    /// the name as `_`, the way symbols spell it).
    Crate(String),
}

/// True for a location in our sources, as [`parse_symbolizer`] shortens
/// them: the library's (`src/`) or a firmware package's (`boards/`).
pub fn is_own_source(location: &str) -> bool {
    location.starts_with("src/") || location.starts_with("boards/")
}

pub fn frame_kind(frame: &SourceFrame) -> FrameKind {
    let location = frame.location.as_str();
    if is_own_source(location) {
        return FrameKind::Own;
    }
    let first = location.split('/').next().unwrap_or("");
    let versioned = first
        .rsplit_once('-')
        .filter(|(_, version)| version.starts_with(|c: char| c.is_ascii_digit()));
    match versioned {
        Some((name, _)) if name != "compiler_builtins" => FrameKind::Crate(name.replace('-', "_")),
        _ => FrameKind::RustLibrary,
    }
}

/// True if no frame of `chain` is outside Rust's own libraries: the call
/// is in a function of core (or alloc) not inlined into anything else, to
/// be attributed to that function's callers ([`owner_of`]).
pub fn only_rust_library(chain: &[SourceFrame]) -> bool {
    chain
        .iter()
        .all(|f| frame_kind(f) == FrameKind::RustLibrary)
}

/// Whose code the panic call in `function` is: the code that performs the
/// checked operation. That is the innermost frame of its inlining `chain`
/// (innermost first) outside Rust's own libraries: ours if in our sources,
/// else its crate's (a third-party function inlined into ours is still its
/// crate's code). With no such frame: the crate `function` is in, or for a
/// function of Rust's own libraries the crates of its nearest `callers`
/// outside them. `own_crates`: our crate names (`abtrack` and the
/// binary's). A call that cannot be attributed to a third-party crate is
/// ours.
pub fn owner_of(
    function: &str,
    chain: &[SourceFrame],
    callers: &[String],
    own_crates: &BTreeSet<String>,
) -> Owner {
    let third_party = |c: &str| {
        if own_crates.contains(c) || is_rust_library(&format!("{c}::")) {
            Owner::Own
        } else {
            Owner::ThirdParty(BTreeSet::from([c.to_string()]))
        }
    };
    match chain
        .iter()
        .map(frame_kind)
        .find(|k| *k != FrameKind::RustLibrary)
    {
        Some(FrameKind::Own) => return Owner::Own,
        Some(FrameKind::Crate(c)) => return third_party(&c),
        Some(FrameKind::RustLibrary) | None => {}
    }
    if !is_rust_library(function) {
        return third_party(crate_of(function));
    }
    let candidates: Vec<&str> = callers.iter().map(|c| crate_of(c)).collect();
    if candidates.is_empty()
        || candidates
            .iter()
            .any(|c| own_crates.contains(*c) || is_rust_library(&format!("{c}::")))
    {
        return Owner::Own;
    }
    Owner::ThirdParty(candidates.into_iter().map(str::to_string).collect())
}

/// A third-party crate allowed to keep panic calls, and why
/// (`--allow-crate <crate>=<reason>`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Allowance {
    pub krate: String,
    pub reason: String,
}

impl std::str::FromStr for Allowance {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let (krate, reason) = s
            .split_once('=')
            .ok_or_else(|| format!("--allow-crate {s}: expected <crate>=<reason>"))?;
        let (krate, reason) = (krate.trim(), reason.trim());
        if krate.is_empty()
            || !krate
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_')
        {
            return Err(format!(
                "--allow-crate {s}: the crate name as it appears in symbols (letters, digits, _)"
            ));
        }
        if reason.is_empty() {
            return Err(format!("--allow-crate {krate}: a reason is required"));
        }
        if is_rust_library(&format!("{krate}::")) {
            return Err(format!(
                "--allow-crate {krate}: Rust's own libraries are attributed to their callers"
            ));
        }
        Ok(Allowance {
            krate: krate.to_string(),
            reason: reason.to_string(),
        })
    }
}
