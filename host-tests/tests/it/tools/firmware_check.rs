//! The firmware ELF checks' parsers (src/firmware_elf.rs), on text taken
//! from LLVM 14's tools run on the release firmware (thumbv7em, the demo as
//! it was when heapless's `% capacity` still panicked in `scan::Intake`).

use std::collections::BTreeSet;

use abtrack_host_tests::firmware_elf::{
    branches, callers_of, check_layout, crate_of, demangle, frame_kind, is_panic_symbol, owner_of,
    panic_calls, panic_symbols, parse_sections, parse_symbolizer, Allowance, FrameKind,
    LayoutError, Owner, PanicCall, SourceFrame,
};

const DISASSEMBLY: &str = "
target/thumbv7em-none-eabihf/release/abtrack-firmware:\tfile format elf32-littlearm

Disassembly of section .text:

00005c90 <_ZN7abtrack4scan6Intake13can_take_byte17hc56b57a7f8caa93fE>:
    5c90:      \tpush\t{r7, lr}
    5cb8:      \tcmp\tr1, #0
    5cba:      \tbeq\t0x5cc0 <_ZN7abtrack4scan6Intake13can_take_byte17hc56b57a7f8caa93fE+0x30> @ imm = #2
    5cbc:      \tbl\t0x69a8 <_RNvNtNtCs7ldSeZOOJos_4core9panicking11panic_const23panic_const_rem_by_zero> @ imm = #3304
    5cc0:      \tpop\t{r7, pc}

00005d00 <_ZN7abtrack4scan6Intake6handle17h9b07205840d91671E>:
    5d68:      \tcbz\tr0, 0x5d6e <_ZN7abtrack4scan6Intake6handle17h9b07205840d91671E+0x6e>
    5d6a:      \tb.w\t0x69a8 <_RNvNtNtCs7ldSeZOOJos_4core9panicking11panic_const23panic_const_rem_by_zero> @ imm = #3130
    5d6e:      \tbl\t0x5c90 <_ZN7abtrack4scan6Intake13can_take_byte17hc56b57a7f8caa93fE> @ imm = #-226
    5d72:      \tpop\t{r4, r6, r7, pc}
    5d74:      \tbmi\t0x69b6 <_RNvNtNtCs7ldSeZOOJos_4core9panicking11panic_const23panic_const_rem_by_zero+0xe> @ imm = #3134

0000698c <_RNvNtCs7ldSeZOOJos_4core9panicking9panic_fmt>:
    698c:      \tpush\t{r7, lr}
    6990:      \tbl\t0x6a00 <rust_begin_unwind> @ imm = #108

000069a8 <_RNvNtNtCs7ldSeZOOJos_4core9panicking11panic_const23panic_const_rem_by_zero>:
    69a8:      \tpush\t{r7, lr}
    69b8:      \tbl\t0x698c <_RNvNtCs7ldSeZOOJos_4core9panicking9panic_fmt> @ imm = #-48
";

#[test]
/// (The `bmi` into the middle of a panic function, after `handle`'s
/// return, is padding decoded as an instruction: not a call.)
fn finds_calls_and_tail_calls_into_the_panic_machinery_but_not_its_own() {
    let calls = panic_calls(&branches(DISASSEMBLY));
    assert_eq!(
        calls,
        vec![
            PanicCall {
                address: 0x5cbc,
                function: "abtrack::scan::Intake::can_take_byte".to_string(),
                target: "core::panicking::panic_const::panic_const_rem_by_zero".to_string(),
            },
            PanicCall {
                address: 0x5d6a,
                function: "abtrack::scan::Intake::handle".to_string(),
                target: "core::panicking::panic_const::panic_const_rem_by_zero".to_string(),
            },
        ]
    );
}

#[test]
fn a_clean_image_has_no_calls() {
    let clean = "
00000400 <main>:
     400:      \tbl\t0x500 <_ZN7abtrack4scan6Intake6handle17h9b07205840d91671E> @ imm = #252
     404:      \tb\t0x400 <main> @ imm = #-8
";
    assert!(panic_calls(&branches(clean)).is_empty());
}

#[test]
fn panic_symbols_are_recognised_demangled() {
    assert!(is_panic_symbol(&demangle(
        "_RNvNtCs7ldSeZOOJos_4core9panicking9panic_fmt"
    )));
    assert!(is_panic_symbol("rust_begin_unwind"));
    assert!(is_panic_symbol("core::panicking::panic_bounds_check"));
    assert!(!is_panic_symbol("abtrack::scan::Intake::handle"));
    // defmt's interned strings are symbols too; their text is not code.
    assert!(!is_panic_symbol(
        r#"{"package":"abtrack-firmware","tag":"defmt_error","data":"panic at {=str}:{=u32}"}"#
    ));
    let nm = "0000698c t _RNvNtCs7ldSeZOOJos_4core9panicking9panic_fmt
000069a8 t _RNvNtNtCs7ldSeZOOJos_4core9panicking11panic_const23panic_const_rem_by_zero
00000400 T main
00000008 N {\"package\":\"abtrack-firmware\",\"tag\":\"defmt_error\",\"data\":\"panic at {=str}:{=u32}\"}
";
    let symbols: Vec<String> = panic_symbols(nm).into_iter().collect();
    assert_eq!(
        symbols,
        vec![
            "core::panicking::panic_const::panic_const_rem_by_zero".to_string(),
            "core::panicking::panic_fmt".to_string()
        ]
    );
}

#[test]
fn symbolizer_output_gives_the_inlined_source_functions_innermost_first() {
    let output = "0x5cbc
_ZN8heapless4spsc23QueueInner$LT$T$C$S$GT$3len17h7625673ca4f42b8aE
/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/heapless-0.9.3/src/spsc.rs:205:9
_ZN7abtrack4scan6Intake10free_slots17hf3e08d863fb6a16aE
/work/wt/safety/src/scan.rs:102:63

0x5d6a
_ZN7abtrack4scan6Intake6handle17h9b07205840d91671E
/work/wt/safety/src/scan.rs:140:64

0x48bc
_ZN4core3cmp3Ord5clamp8do_panic7runtime17h0123456789abcdefE
/rustc/0123456789abcdef0123456789abcdef01234567/library/core/src/panic.rs:172:21

0x4aca
_ZN5bench4scan5Scene5start17h0123456789abcdefE
/work/wt/safety/boards/qemu/../../src/bin/bench/scan.rs:92:17

";
    let parsed = parse_symbolizer(output, "/work/wt/safety");
    assert_eq!(parsed.len(), 4);
    let (address, frames) = &parsed[0];
    assert_eq!(*address, 0x5cbc);
    assert_eq!(frames[0].function, "heapless::spsc::QueueInner<T,S>::len");
    assert_eq!(frames[0].location, "heapless-0.9.3/src/spsc.rs:205:9");
    assert_eq!(frames[1].function, "abtrack::scan::Intake::free_slots");
    assert_eq!(frames[1].location, "src/scan.rs:102:63");
    assert_eq!(parsed[1].0, 0x5d6a);
    assert_eq!(parsed[1].1[0].function, "abtrack::scan::Intake::handle");
    // Rust's own sources are not ours, though their path has a src/ too.
    assert_eq!(parsed[2].1[0].location, "core/src/panic.rs:172:21");
    // Sources named through a firmware package's directory are ours.
    assert_eq!(parsed[3].1[0].location, "src/bin/bench/scan.rs:92:17");
}

#[test]
fn callers_of_a_library_function_are_found() {
    let callers: Vec<String> = callers_of(
        &branches(DISASSEMBLY),
        "abtrack::scan::Intake::can_take_byte",
    )
    .into_iter()
    .collect();
    assert_eq!(callers, vec!["abtrack::scan::Intake::handle".to_string()]);
}

#[test]
fn mapping_symbols_inside_a_function_do_not_end_it() {
    let text = "
00000900 <_ZN8selftest16compare_schedule17h0123456789abcdefE>:
     9a8:      \ttbb\t[pc, r0]
     9aa:\t9b 01 15 01\t.word\t0x0115019b

000009b0 <$t>:
     9b0:      \tbl\t0x69a8 <_RNvNtNtCs7ldSeZOOJos_4core9panicking11panic_const23panic_const_rem_by_zero> @ imm = #3304
";
    let calls = panic_calls(&branches(text));
    assert_eq!(calls.len(), 1);
    assert_eq!(calls[0].function, "selftest::compare_schedule");
}

const SECTIONS_FLIPPED: &str = "
Sections:
Idx Name            Size     VMA      LMA      Type
  0                 00000000 00000000 00000000 
  1 .vector_table   00000400 00000000 00000000 DATA
  2 .text           00008220 00000400 00000400 TEXT
  3 .rodata         00000674 00008620 00008620 DATA
  4 .data           00004504 203fac68 00008c98 DATA
  5 .gnu.sgstubs    00000000 0000d1a0 0000d1a0 DATA
  6 .bss            00000e90 203ff16c 203ff16c BSS
  7 .uninit         00000000 203ffffc 203ffffc BSS
";

#[test]
fn the_flip_link_layout_passes() {
    let nm = "20000000 A _stack_end\n203fac68 A _stack_start\n";
    let sections = parse_sections(SECTIONS_FLIPPED);
    assert_eq!(sections.len(), 7, "the unnamed section 0 is skipped");
    let layout = check_layout(nm, &sections, 0x2000_0000).expect("flipped layout");
    assert_eq!(layout.stack_bottom, 0x2000_0000);
    assert_eq!(layout.stack_top, 0x203f_ac68);
    assert_eq!(layout.statics, Some((0x203f_ac68, 0x203f_fffc)));
}

#[test]
fn the_default_layout_with_the_stack_above_the_statics_fails() {
    // cortex-m-rt's own layout: statics at the bottom of RAM, the stack from
    // the end of RAM down into them.
    let sections = parse_sections(
        "
  4 .data           00004504 20000000 00008c98 DATA
  6 .bss            00000e90 20004504 20004504 BSS
",
    );
    let nm = "20005394 A _stack_end\n20400000 A _stack_start\n";
    assert_eq!(
        check_layout(nm, &sections, 0x2000_0000),
        Err(LayoutError::StackNotAtBottom {
            stack_bottom: 0x2000_5394,
            ram_origin: 0x2000_0000
        })
    );
    // Statics below the top of a stack that does reach the bottom of RAM.
    let nm = "20000000 A _stack_end\n20400000 A _stack_start\n";
    assert_eq!(
        check_layout(nm, &sections, 0x2000_0000),
        Err(LayoutError::StaticsBelowStackTop {
            lowest_static: 0x2000_0000,
            stack_top: 0x2040_0000
        })
    );
    assert_eq!(
        check_layout("", &sections, 0x2000_0000),
        Err(LayoutError::MissingSymbol("_stack_end"))
    );
}

#[test]
fn a_function_belongs_to_the_first_segment_of_its_path() {
    assert_eq!(
        crate_of("minikalman::matrix::traits::Matrix::mult"),
        "minikalman"
    );
    assert_eq!(
        crate_of("<core::num::dec2flt::decimal_seq::DecimalSeq>::left_shift"),
        "core"
    );
    assert_eq!(
        crate_of("<&mut heapless::spsc::Queue<T>>::push"),
        "heapless"
    );
    assert_eq!(crate_of("bench::minikalman::cv2d"), "bench");
}

fn own_crates() -> BTreeSet<String> {
    BTreeSet::from(["abtrack".to_string(), "bench".to_string()])
}

fn third_party(names: &[&str]) -> Owner {
    Owner::ThirdParty(names.iter().map(|n| n.to_string()).collect())
}

fn frame(function: &str, location: &str) -> SourceFrame {
    SourceFrame {
        function: function.to_string(),
        location: location.to_string(),
    }
}

#[test]
fn frames_are_ours_rust_s_or_a_registry_crate_s() {
    let kind = |l: &str| frame_kind(&frame("f", l));
    assert_eq!(kind("src/bin/bench/scan.rs:176:17"), FrameKind::Own);
    assert_eq!(kind("core/src/panic.rs:177:9"), FrameKind::RustLibrary);
    assert_eq!(kind("??:0:0"), FrameKind::RustLibrary);
    assert_eq!(
        kind("compiler_builtins-0.1.160/src/mem/mod.rs:1:1"),
        FrameKind::RustLibrary
    );
    assert_eq!(
        kind("minikalman-0.8.1/src/matrix/traits.rs:328:30"),
        FrameKind::Crate("minikalman".to_string())
    );
    assert_eq!(
        kind("defmt-semihosting-0.3.0/src/lib.rs:1:1"),
        FrameKind::Crate("defmt_semihosting".to_string())
    );
}

#[test]
/// The innermost frame outside core decides; with none, the function's
/// crate or, for core's own functions, their callers'.
fn calls_in_or_from_our_code_are_ours() {
    let own = own_crates();
    // A bounds check of core inlined into our source.
    let chain = [
        frame(
            "core::slice::index::get_unchecked",
            "core/src/slice/index.rs:1:1",
        ),
        frame("bench::scan::Scene::start", "src/bin/bench/scan.rs:176:17"),
    ];
    assert_eq!(
        owner_of("bench::scan::Scene::start", &chain, &[], &own),
        Owner::Own
    );
    // bench's own module named minikalman is not the crate minikalman.
    assert_eq!(
        owner_of("bench::minikalman::cv2d", &[], &[], &own),
        Owner::Own
    );
    assert_eq!(
        owner_of(
            "<core::num::dec2flt::decimal_seq::DecimalSeq>::left_shift",
            &[frame(
                "<core::num::dec2flt::decimal_seq::DecimalSeq>::left_shift",
                "core/src/num/dec2flt/decimal_seq.rs:136:19"
            )],
            &["abtrack::gain::spec::ScheduleSpec::parse".to_string()],
            &own
        ),
        Owner::Own
    );
    // A core function nobody outside core calls cannot be attributed.
    assert_eq!(
        owner_of("core::slice::index::slice_index_fail", &[], &[], &own),
        Owner::Own
    );
    // Called from ours and from a dependency: ours.
    assert_eq!(
        owner_of(
            "core::slice::index::slice_index_fail",
            &[],
            &["minikalman::f".to_string(), "bench::scan::g".to_string()],
            &own
        ),
        Owner::Own
    );
}

#[test]
fn checks_in_a_dependency_s_code_are_its_even_inlined_into_ours() {
    let own = own_crates();
    assert_eq!(
        owner_of("minikalman::matrix::traits::Matrix::mult", &[], &[], &own),
        third_party(&["minikalman"])
    );
    let chain = [
        frame(
            "minikalman::matrix::row_major::RowMajorSequentialDataMut::set_at",
            "minikalman-0.8.1/src/matrix/row_major.rs:71:9",
        ),
        frame(
            "bench::minikalman::cv2d",
            "src/bin/bench/minikalman.rs:112:39",
        ),
    ];
    assert_eq!(
        owner_of("bench::minikalman::cv2d", &chain, &[], &own),
        third_party(&["minikalman"])
    );
    assert_eq!(
        owner_of(
            "core::slice::index::slice_index_fail",
            &[],
            &["minikalman::f".to_string(), "heapless::g".to_string()],
            &own
        ),
        third_party(&["heapless", "minikalman"])
    );
}

#[test]
fn an_allowance_needs_a_crate_name_and_a_reason() {
    let a: Allowance = "minikalman=the anchor, third-party".parse().unwrap();
    assert_eq!(a.krate, "minikalman");
    assert_eq!(a.reason, "the anchor, third-party");
    for bad in [
        "minikalman",
        "minikalman=",
        "=why",
        "mini kalman=why",
        "core=why",
    ] {
        assert!(bad.parse::<Allowance>().is_err(), "{bad} accepted");
    }
}
