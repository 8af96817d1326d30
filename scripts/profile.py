# GDB script of scripts/profile.sh (run inside gdb-multiarch, whose Python
# this is): steps one call of a firmware function under QEMU one instruction
# at a time and counts the instructions it executes, per function, per
# inlined function and per source line (the innermost frame of the debug
# information in the project's own source).
#
# Parameters come from the environment (scripts/profile.sh sets them):
#   PROFILE_ELF      the firmware image
#   PROFILE_ADDRESS  the function's entry address (hex)
#   PROFILE_SKIP     calls to let run before the one counted
#   PROFILE_TOP      rows per table
#   PROFILE_PORT     QEMU's gdb port
import bisect
import collections
import os
import subprocess
import time

import gdb

elf = os.environ["PROFILE_ELF"]
entry = int(os.environ["PROFILE_ADDRESS"], 16)
skip = int(os.environ.get("PROFILE_SKIP", "0"))
top = int(os.environ.get("PROFILE_TOP", "20"))
port = os.environ.get("PROFILE_PORT", "1234")
# A bound on one call, so that a function that never returns ends the run.
LIMIT = 5_000_000

gdb.execute("set pagination off")
gdb.execute("set confirm off")
# QEMU was just started in the background: wait for its gdb server.
for attempt in range(50):
    try:
        gdb.execute("target remote :" + port)
        break
    except gdb.error:
        if attempt == 49:
            raise
        time.sleep(0.2)
gdb.execute("break *0x%x" % entry)
for _ in range(skip + 1):
    gdb.execute("continue", to_string=True)
# The call ends when the caller's return address is reached with the stack
# back at (or above) its level at entry (a recursive call does not end it).
ret = int(gdb.parse_and_eval("$lr")) & ~1
sp = int(gdb.parse_and_eval("$sp"))
gdb.execute("delete")
counts = collections.Counter()
steps = 0
while steps < LIMIT:
    pc = int(gdb.parse_and_eval("$pc"))
    if pc == ret and int(gdb.parse_and_eval("$sp")) >= sp:
        break
    counts[pc] += 1
    steps += 1
    gdb.execute("stepi", to_string=True)
gdb.execute("kill")


def tool(name):
    directory = os.environ.get("LLVM_TOOLS_DIR")
    return os.path.join(directory, name) if directory else name


# Each address's function: the symbol table's text symbols.
symbols = []
for line in subprocess.run(
    [tool("llvm-nm"), "-n", "-C", "--defined-only", elf],
    capture_output=True, text=True, check=True,
).stdout.splitlines():
    parts = line.split(None, 2)
    if len(parts) == 3 and parts[1] in "tTwW":
        symbols.append((int(parts[0], 16), parts[2]))
starts = [a for a, _ in symbols]


def function_of(address):
    i = bisect.bisect_right(starts, address) - 1
    return symbols[i][1] if i >= 0 else "?"


# Each address's innermost inlined function and source line.
addresses = sorted(counts)
frames = subprocess.run(
    [tool("llvm-symbolizer"), "--obj", elf, "--inlining", "-C", "--relativenames"],
    input="".join("0x%x\n" % a for a in addresses),
    capture_output=True, text=True, check=True,
).stdout.split("\n\n")
# The innermost frame in the project's own source (the standard library's
# inlined operators and iterators count towards the code that used them).
innermost = {}
for address, block in zip(addresses, frames):
    lines = block.strip("\n").split("\n")
    pairs = list(zip(lines[0::2], lines[1::2])) or [("?", "?")]
    own = [p for p in pairs if not p[1].startswith("/")]
    innermost[address] = (own or pairs)[0]


# The escapes of Rust's legacy mangling that LLVM's demangler leaves.
ESCAPES = [("$LT$", "<"), ("$GT$", ">"), ("$C$", ","), ("$u20$", " "), ("$RF$", "&"),
           ("$BP$", "*"), ("$u7b$", "{"), ("$u7d$", "}"), ("$u5b$", "["), ("$u5d$", "]"),
           ("$u3b$", ";"), ("$u27$", "'"), ("$LP$", "("), ("$RP$", ")"), ("..", "::")]


def short(name, width=110):
    # Drop the hash suffix of a demangled Rust name, undo the escapes.
    head, _, tail = name.rpartition("::h")
    if head and len(tail) == 16:
        name = head
    for escape, text in ESCAPES:
        name = name.replace(escape, text)
    if name.startswith("_<") or name.startswith("_$"):
        name = name[1:]
    return name if len(name) <= width else "…" + name[-(width - 1):]


def table(title, totals):
    print(title)
    for name, n in totals.most_common(top):
        print("%9d %5.1f %%  %s" % (n, 100.0 * n / steps, short(name)))
    rest = len(totals) - top
    if rest > 0:
        print("%9s          (%d more)" % ("", rest))


by_function = collections.Counter()
by_inlined = collections.Counter()
by_line = collections.Counter()
for address, n in counts.items():
    by_function[function_of(address)] += n
    name, line = innermost[address]
    by_inlined[name] += n
    by_line[short(name, 60) + " @ " + line] += n
print("=== profile")
print("profile: %s at 0x%x, call %d: %d instructions" % (short(function_of(entry)), entry, skip + 1, steps))
table("per function (its own instructions; callees apart):", by_function)
table("per innermost inlined function of the project's source:", by_inlined)
table("per source line (the same frames):", by_line)
