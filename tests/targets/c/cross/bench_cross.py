"""`make bench-c-cross`: canspec's generated C against `cantools generate_c_source` on the
generated DBC, on the exact Cortex-M0+ and Cortex-M4 cores (arm-none-eabi-gcc), per core and
optimisation level: dynamic instructions of pack + unpack per message, code size, stack, and the
libgcc / libc helpers the code calls. x86-64 stays in tests/targets/c/bench.py (callgrind).

Dynamic instructions: every library is compiled into its own translation units with the core's
flags plus -ffunction-sections -fno-ipa-icf (canspec's static inline pack/unpack behind extern
wrappers, as bench.py's call mode; cantools' .c as it ships; "cantools+user" (like for like):
extern wrappers in the user's translation unit that add what canspec does and cantools does not
-- check the XOR checksum before cantools' unpack and fill it after its pack, byte-wise, on the
messages that carry one, and refuse a field that does not fit its bits before cantools' pack,
which would drop the excess bits silently (range_checks: the same compares as canspec's)). A harness function per (library,
message, pack|unpack) calls the function on the same 16 frames per message (bench.py's
frames_for: the shared vectors, cycled). The ELF runs once under
`qemu-arm -singlestep -d exec,nochain`, which logs every executed instruction's address; an
instruction is counted for a harness function when it executes while that harness function is
active (entered and not yet returned to main) but lies outside the harness function's own code:
i.e. exactly the instructions of the called functions and of everything they call (helpers
included), without the harness's loop and call set-up. The harness then checks that all three
libraries returned 0 and packed the input frames back byte for byte (same work on both sides).

Size: nm sizes of the functions in question plus the static helpers of the same object that they
call (the call graph from the linked disassembly), and the read-only data they read where it is
not in their literal pools (canspec's double encoders' `_phys` descriptors); libgcc / libc
helpers are listed by name.
The physical-value API is measured on a translation unit that takes the address of each
canspec function (so each is emitted once, out of line): the double path against cantools'
default `_encode`/`_decode`, the integer path against what `--no-floating-point-numbers` leaves.
Stack: gcc -fstack-usage frames, and the deepest call path (frames added along the call graph;
functions without a .su entry, i.e. libgcc/libc, estimated from their push/sub sp prologue).

    python3 tests/targets/c/cross/bench_cross.py [--headers DIR] [--dbc FILE] [--vectors FILE] [--spec SPEC]
        [--configs cortex-m0plus:-Os,cortex-m4:-Os,...] [--build DIR] [-j N]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))
import cbuild  # noqa: E402
import cross  # noqa: E402
from bench import FRAMES_PER_MESSAGE, c_bytes, frames_for, range_checks  # noqa: E402
from fixed_user import fixed_user_source  # noqa: E402

ROOT = cbuild.ROOT
DEFAULT_CONFIGS = "cortex-m0plus:-Os,cortex-m0plus:-O2,cortex-m4:-Os,cortex-m4:-O2"
COMMON = ["-std=gnu99", "-ffunction-sections", "-fno-ipa-icf", "-fstack-usage"]
LIBS = ("canspec", "cantools", "cantools_xor")
PHASES = ("unpack", "pack")
LIBC = {"memcpy", "memset", "memmove", "memcmp", "strlen", "strcmp", "abort"}


def is_helper(name: str) -> bool:
    """A libgcc / soft-float / libc routine (not code of the library under test)."""
    return name.startswith("__") or name in LIBC


@dataclass
class Inputs:
    headers: Path
    dbc: Path
    vectors: Path
    spec: Path
    prefix: str = ""
    db: str = ""
    names: list[str] = field(default_factory=list)
    frames: dict[str, list[str]] = field(default_factory=dict)
    xor: dict[str, tuple[int, tuple[int, ...]]] = field(default_factory=dict)
    ranges: dict[str, str] = field(default_factory=dict)  # message → a cantools user's range check
    c_base: dict[str, str] = field(default_factory=dict)  # message → its C name in canspec's headers (a spec `c_name`)
    functions: list[str] = field(default_factory=list)  # every static inline function of the headers


def checksum_layout(spec: Path) -> tuple[dict[str, tuple[int, tuple[int, ...]]], dict[str, str]]:
    """message → (checksum byte, bytes it covers), and message → its C name, from the spec the
    headers came from."""
    sys.path.insert(0, str(ROOT / "generator"))
    from canspec.pipeline import compile_spec
    from canspec.targets.c.names import CNames

    compiled = compile_spec(spec, ["c", "dbc"])  # only the targets benchmarked check the spec
    if compiled.spec is None or compiled.spec.can is None:
        raise ValueError(f"{spec}: the spec does not compile")
    can = compiled.spec.can
    names = CNames.of(can)
    return ({m.name: (m.checksum.byte, tuple(m.checksum.covers)) for m in can.messages if m.checksum is not None},
            {m.name: names.message(m.name) for m in can.messages})


def header_functions(headers: Path) -> list[str]:
    out: list[str] = []
    for h in sorted(headers.glob("*.h")):
        out += re.findall(r"\bstatic\s+inline\s+[\w\s\*]*?\b(\w+)\s*\(", h.read_text(encoding="utf-8"))
    return list(dict.fromkeys(out))


# --- sources ------------------------------------------------------------------------------


def src_canspec_wrappers(inp: Inputs) -> str:
    """Extern copies of canspec's static inline pack/unpack (bench.py's call mode)."""
    p = inp.prefix
    out = [f'#include "{p}.h"']
    for n in inp.names:
        c = f"{p}_{inp.c_base[n]}"
        out.append(f"{p}_status_t x_{n}_pack(uint8_t *d, size_t z, const {c}_t *s);")
        out.append(f"{p}_status_t x_{n}_pack(uint8_t *d, size_t z, const {c}_t *s) {{ return {c}_pack(d, z, s); }}")
        out.append(f"{p}_status_t x_{n}_unpack({c}_t *s, const uint8_t *d, size_t z);")
        out.append(f"{p}_status_t x_{n}_unpack({c}_t *s, const uint8_t *d, size_t z) {{ return {c}_unpack(s, d, z); }}")
    return "\n".join(out) + "\n"


def src_cantools_xor(inp: Inputs, stem: str = "cx", with_ranges: bool = True) -> str:
    """What a cantools user adds for canspec's guarantees: on a checksum message, verify before
    unpack and fill after pack; on a message with fields narrower than their C type, refuse an
    out-of-range field before pack (range_checks). `with_ranges=False`: the XOR alone (the
    issue's "cantools (+XOR)" size)."""
    ranges = inp.ranges if with_ranges else {}
    out = [f'#include "{inp.db}.h"']
    for n in inp.names:
        t = f"struct {inp.db}_{n}_t"
        if n in inp.xor:
            byte, covers = inp.xor[n]
            out.append(f"int {stem}_{n}_unpack({t} *s, const uint8_t *d, size_t z);")
            out.append(f"int {stem}_{n}_unpack({t} *s, const uint8_t *d, size_t z) {{")
            # Byte-wise (bench.py's 64-bit word fold is an x86 choice: no unaligned word loads on M0+).
            out.append(f"    if (z < 8u || (uint8_t)({' ^ '.join(f'd[{b}]' for b in (*covers, byte))}) != 0u) return -2;")
            out.append(f"    return {inp.db}_{n}_unpack(s, d, z);")
            out.append("}")
        if n in inp.xor or n in ranges:
            out.append(f"int {stem}_{n}_pack(uint8_t *d, const {t} *s, size_t z);")
            out.append(f"int {stem}_{n}_pack(uint8_t *d, const {t} *s, size_t z) {{")
            out.append("    int st;")
            if n in ranges:
                out.append(f"    if ({ranges[n]}) return -3;")
            out.append(f"    st = {inp.db}_{n}_pack(d, s, z);")
            if n in inp.xor:
                byte, covers = inp.xor[n]
                out.append(f"    if (st >= 0) d[{byte}] = (uint8_t)({' ^ '.join(f'd[{b}]' for b in covers)});")
            out.append("    return st;")
            out.append("}")
    return "\n".join(out) + "\n"


def flen(inp: Inputs, name: str) -> int:
    """The message's frame length in bytes (its vectors' data: up to 64 on CAN FD)."""
    return len(inp.frames[name][0]) // 2


def src_harness(inp: Inputs, lib: str) -> str:
    """run_<lib>_<msg>_<phase>(): the 16 frames through one function; results kept for main."""
    if lib == "canspec":
        out = [f'#include "{inp.prefix}.h"']
        typ = lambda n: f"{inp.prefix}_{inp.c_base[n]}_t"  # noqa: E731
        for n in inp.names:
            out.append(f"{inp.prefix}_status_t x_{n}_pack(uint8_t *d, size_t z, const {typ(n)} *s);")
            out.append(f"{inp.prefix}_status_t x_{n}_unpack({typ(n)} *s, const uint8_t *d, size_t z);")
        call_u = lambda n: f"x_{n}_unpack(&S_{n}[i], F_{n}[i], {flen(inp, n)})"  # noqa: E731
        call_p = lambda n: f"x_{n}_pack(O_{n}[i], {flen(inp, n)}, &S_{n}[i])"  # noqa: E731
    else:
        out = [f'#include "{inp.db}.h"']
        typ = lambda n: f"struct {inp.db}_{n}_t"  # noqa: E731
        fn = (lambda n: f"cx_{n}") if lib == "cantools_xor" else (lambda n: f"{inp.db}_{n}")  # noqa: E731
        for n in inp.names:
            if lib == "cantools_xor" and n in inp.xor:
                out.append(f"int cx_{n}_unpack({typ(n)} *s, const uint8_t *d, size_t z);")
            if lib == "cantools_xor" and (n in inp.xor or n in inp.ranges):
                out.append(f"int cx_{n}_pack(uint8_t *d, const {typ(n)} *s, size_t z);")
        call_u = lambda n: f"{fn(n) if n in inp.xor else f'{inp.db}_{n}'}_unpack(&S_{n}[i], F_{n}[i], {flen(inp, n)})"  # noqa: E731
        call_p = lambda n: f"{fn(n) if n in inp.xor or n in inp.ranges else f'{inp.db}_{n}'}_pack(O_{n}[i], &S_{n}[i], {flen(inp, n)})"  # noqa: E731
    out += ["#include <stdint.h>", "#include <stddef.h>", f"#define NF {FRAMES_PER_MESSAGE}"]
    runs = []
    for n in inp.names:
        rows = ",\n    ".join(c_bytes(h) for h in inp.frames[n])
        out.append(f"static const uint8_t F_{n}[NF][{flen(inp, n)}] = {{\n    {rows}\n}};")
        out.append(f"static {typ(n)} S_{n}[NF];")
        out.append(f"static uint8_t O_{n}[NF][{flen(inp, n)}];")
        for phase, call in (("unpack", call_u), ("pack", call_p)):
            out.append(f"__attribute__((noinline)) void run_{lib}_{n}_{phase}(int *st) {{")
            out.append("    int i;")
            # cantools' pack returns the size on success: the same 0 for the check in main.
            norm = "r < 0 ? r : 0" if lib != "canspec" and phase == "pack" else "r"
            out.append(f"    for (i = 0; i < NF; i++) {{ const int r = (int){call(n)}; st[i] = {norm}; }}")
            out.append("}")
            runs.append(f"run_{lib}_{n}_{phase}")
        out.append(f"const uint8_t *out_{lib}_{n}(void) {{ return &O_{n}[0][0]; }}")
    out.append("typedef void (*run_fn)(int *);")
    out.append(f"const run_fn runs_{lib}[] = {{ {', '.join(runs)} }};")
    out.append("typedef const uint8_t *(*out_fn)(void);")
    out.append(f"const out_fn outs_{lib}[] = {{ {', '.join(f'out_{lib}_{n}' for n in inp.names)} }};")
    return "\n".join(out) + "\n"


def src_main(inp: Inputs) -> str:
    """Runs every harness function once, then checks: status 0 and the frames packed back, on
    every library (the same work on both sides)."""
    frames = []
    for n in inp.names:
        frames.append("{" + ", ".join(c_bytes(h) for h in inp.frames[n]) + "}")
    out = ["#include <stdio.h>", "#include <stdint.h>", "#include <string.h>",
           "typedef void (*run_fn)(int *);", "typedef const uint8_t *(*out_fn)(void);",
           f"#define NM {len(inp.names)}", f"#define NF {FRAMES_PER_MESSAGE}"]
    for lib in LIBS:
        out.append(f"extern const run_fn runs_{lib}[];")
        out.append(f"extern const out_fn outs_{lib}[];")
    out.append(f"static const char *const NAMES[NM] = {{ {', '.join(json.dumps(n) for n in inp.names)} }};")
    out.append(f"static const size_t LEN[NM] = {{ {', '.join(str(flen(inp, n)) for n in inp.names)} }};")
    out.append("static const uint8_t FRAMES[NM][NF][64] = {\n" + ",\n".join(frames) + "\n};")
    out.append(f"static const char *const LIB_NAMES[3] = {{ {', '.join(json.dumps(lib) for lib in LIBS)} }};")
    out.append(f"static const run_fn *const RUNS[3] = {{ {', '.join(f'runs_{lib}' for lib in LIBS)} }};")
    out.append(f"static const out_fn *const OUTS[3] = {{ {', '.join(f'outs_{lib}' for lib in LIBS)} }};")
    out.append(r"""
int main(void) {
    static int st[3][NM][2][NF];
    int lib, m, p, f, bad = 0;
    for (lib = 0; lib < 3; lib++)
        for (m = 0; m < NM; m++)
            for (p = 0; p < 2; p++) RUNS[lib][2 * m + p](st[lib][m][p]);
    for (lib = 0; lib < 3; lib++)
        for (m = 0; m < NM; m++) {
            const uint8_t *o = OUTS[lib][m]();
            for (f = 0; f < NF; f++) {
                if (st[lib][m][0][f] != 0 || st[lib][m][1][f] != 0 || memcmp(o + LEN[m] * f, FRAMES[m][f], LEN[m]) != 0) {
                    printf("bench: %s %s frame %d: unpack %d pack %d, packed bytes %s\n", LIB_NAMES[lib], NAMES[m], f,
                           st[lib][m][0][f], st[lib][m][1][f], memcmp(o + LEN[m] * f, FRAMES[m][f], LEN[m]) ? "differ" : "agree");
                    bad++;
                }
            }
        }
    printf("bench: %d mismatches\n", bad);
    return bad != 0;
}
""")
    return "\n".join(out) + "\n"


def src_api(inp: Inputs, patterns: dict[str, str]) -> str:
    """Takes the address of every header function matching one of `patterns`, so each is
    emitted once, out of line, with its own ABI (for size and stack)."""
    wanted = [f for f in inp.functions if any(re.fullmatch(p, f) for p in patterns.values())]
    out = [f'#include "{inp.prefix}.h"', "typedef void (*any_fn)(void);", "const any_fn canspec_api[] = {"]
    out += [f"    (any_fn){f}," for f in wanted]
    out.append("};")
    return "\n".join(out) + "\n"


STUB_MAIN = "int main(void);\nint main(void) { return 0; }\n"
STUB_MAIN_API = "typedef void (*any_fn)(void);\nextern const any_fn canspec_api[];\nint main(void);\nint main(void) { return canspec_api[0] != 0; }\n"


# --- analysis -----------------------------------------------------------------------------


@dataclass
class Image:
    """A linked ELF: function sizes, direct call edges, own stack frames."""
    sizes: dict[str, int] = field(default_factory=dict)
    data: dict[str, int] = field(default_factory=dict)  # read-only and initialised data objects
    calls: dict[str, set[str]] = field(default_factory=dict)
    indirect: set[str] = field(default_factory=set)
    frames: dict[str, int] = field(default_factory=dict)  # from the prologue (push, sub sp)


_FN = re.compile(r"^([0-9a-f]+) <([^>]+)>:$")
_INSN = re.compile(r"^\s*[0-9a-f]+:\s+(\S+)\s+(.*)$")
_TARGET = re.compile(r"\b[0-9a-f]+ <([^>+]+)(\+0x[0-9a-f]+)?>")


def load_image(elf: Path) -> Image:
    img = Image()
    nm = subprocess.run(["arm-none-eabi-nm", "-S", "--defined-only", str(elf)], capture_output=True, text=True, check=True).stdout
    for line in nm.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in "tTwW":
            img.sizes[parts[3]] = max(img.sizes.get(parts[3], 0), int(parts[1], 16))
        elif len(parts) == 4 and parts[2] in "rRdD":
            img.data[parts[3]] = int(parts[1], 16)
    dis = subprocess.run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", str(elf)], capture_output=True, text=True, check=True).stdout
    cur = None
    count = 0
    for line in dis.splitlines():
        m = _FN.match(line)
        if m:
            cur, count = m.group(2), 0
            img.calls.setdefault(cur, set())
            img.frames[cur] = 0
            continue
        m = _INSN.match(line)
        if not m or cur is None:
            continue
        op, args = m.group(1), m.group(2)
        count += 1
        if count <= 8:  # the prologue
            if op in ("push", "push.w", "stmdb", "vpush") and "{" in args:
                regs = args[args.index("{") + 1: args.index("}")]
                n = 0
                for r in regs.split(","):
                    r = r.strip()
                    if "-" in r:
                        a, b = r.split("-")
                        n += int(b.strip()[1:]) - int(a.strip()[1:]) + 1
                    elif r:
                        n += 1
                img.frames[cur] += n * (8 if op == "vpush" and args.strip().startswith("{d") else 4)
            sub = re.match(r"(sub|subw|sub\.w)\s*$", op)
            if sub and re.match(r"sp, (sp, )?#(\d+)", args):
                img.frames[cur] += int(re.match(r"sp, (sp, )?#(\d+)", args).group(2))
        if op.startswith(("bl", "b")) and not op.startswith(("bic", "bfi", "bfc")):
            t = _TARGET.search(args)
            if t and t.group(1) != cur and (op.startswith("bl") or t.group(2) is None):
                img.calls[cur].add(t.group(1))
            elif op.startswith("blx") and not t:
                img.indirect.add(cur)
    return img


def closure(img: Image, roots: list[str]) -> tuple[set[str], set[str]]:
    """(functions of the library reached from roots, the libgcc/libc helpers they call)."""
    seen: set[str] = set()
    todo = list(roots)
    while todo:
        f = todo.pop()
        if f in seen:
            continue
        seen.add(f)
        todo += sorted(img.calls.get(f, ()))
    own = {f for f in seen if not is_helper(f)}
    # The helpers the library's own code calls (not what those helpers call in turn).
    return own, {c for f in own for c in img.calls.get(f, ()) if is_helper(c)}


def group_size(img: Image, roots: list[str]) -> tuple[int, set[str]]:
    own, helpers = closure(img, roots)
    return sum(img.sizes.get(f, 0) for f in own), helpers


def stack_usage(su: Path) -> dict[str, int]:
    """function → frame bytes, from one object's gcc -fstack-usage file."""
    out: dict[str, int] = {}
    if su.exists():
        for line in su.read_text().splitlines():
            parts = line.split("\t")
            if len(parts) >= 2:
                out[parts[0].rsplit(":", 1)[-1]] = int(parts[1])
    return out


def deepest(img: Image, su: dict[str, int], root: str, memo: dict[str, tuple[int, list[str]]] | None = None,
            stack: tuple[str, ...] = ()) -> tuple[int, list[str]]:
    """Largest sum of frames along a call path from root (recursion cut off)."""
    memo = {} if memo is None else memo
    if root in memo:
        return memo[root]
    own = su.get(root, img.frames.get(root, 0))
    best: tuple[int, list[str]] = (0, [])
    for callee in sorted(img.calls.get(root, ())):
        if callee in stack:
            continue
        d = deepest(img, su, callee, memo, (*stack, root))
        if d[0] > best[0]:
            best = d
    memo[root] = (own + best[0], [root, *best[1]])
    return memo[root]


# --- build and measure --------------------------------------------------------------------


@dataclass
class ConfigResult:
    core: str
    opt: str
    counts: dict[tuple[str, str, str], float] = field(default_factory=dict)  # (lib, msg, phase) → instr per call
    traced_helpers: dict[str, set[str]] = field(default_factory=dict)  # lib → helpers executed
    check: str = ""
    sizes: dict[str, tuple[int, set[str]]] = field(default_factory=dict)
    stack: dict[str, tuple[int, list[str]]] = field(default_factory=dict)
    frame: dict[str, tuple[int, str]] = field(default_factory=dict)
    seconds: float = 0.0
    error: str = ""


def compile_obj(core: str, opt: str, src: Path, obj: Path, inc: list[Path]) -> None:
    cmd = [cross.ARM_CC, *cross.ARM_CORES[core], opt, *COMMON, *[f"-I{p}" for p in inc], "-c", str(src), "-o", str(obj)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}\n{proc.stderr[-4000:]}")


def link(core: str, objs: list[Path], exe: Path, shim_dir: Path) -> None:
    target = cross.Target(f"bench-{core}", cross.ARM_CC, cross.ARM_CORES[core], ("qemu-arm",), bare_metal=True)
    cmd = [cross.ARM_CC, *cross.ARM_CORES[core], *map(str, objs), "-o", str(exe), *cross.link_flags(target, shim_dir)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}\n{proc.stderr[-4000:]}")


_TRACE = re.compile(r"^Trace \d+: \S+ \[[0-9a-f]+/([0-9a-f]+)/[0-9a-f]+/[0-9a-f]+\] ?(\S*)")


def trace_counts(exe: Path, run_names: set[str]) -> tuple[dict[str, int], dict[str, set[str]], str]:
    """Instructions executed inside each harness function's callees (see the module doc)."""
    nm = subprocess.run(["arm-none-eabi-nm", "-S", "--defined-only", str(exe)], capture_output=True, text=True, check=True).stdout
    ranges: list[tuple[int, int, str]] = []
    for line in nm.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in "tT" and (parts[3] in run_names or parts[3] == "main"):
            lo = int(parts[0], 16) & ~1
            ranges.append((lo, lo + int(parts[1], 16), parts[3]))
    ranges.sort()
    starts = [r[0] for r in ranges]
    import bisect

    def owner(pc: int) -> str | None:
        i = bisect.bisect_right(starts, pc) - 1
        return ranges[i][2] if i >= 0 and pc < ranges[i][1] else None

    counts: dict[str, int] = {}
    seen: dict[str, set[str]] = {}
    cur: str | None = None
    cache: dict[int, str | None] = {}
    log = exe.with_suffix(".out")
    with open(log, "w", encoding="utf-8") as stdout:
        proc = subprocess.Popen(["qemu-arm", "-singlestep", "-d", "exec,nochain", str(exe)], stdout=stdout,
                                stderr=subprocess.PIPE, text=True, bufsize=1 << 20)
    assert proc.stderr is not None
    other = []
    for line in proc.stderr:
        m = _TRACE.match(line)
        if not m:
            other.append(line)
            continue
        pc = int(m.group(1), 16)
        if pc not in cache:
            cache[pc] = owner(pc)
        o = cache[pc]
        if o is not None:
            cur = None if o == "main" else o
        elif cur is not None:
            counts[cur] = counts.get(cur, 0) + 1
            seen.setdefault(cur, set()).add(m.group(2))
    proc.wait()
    out = log.read_text(encoding="utf-8")
    if proc.returncode != 0 or not counts:
        raise RuntimeError(f"traced bench exited {proc.returncode}: {out[-2000:]}{''.join(other[-20:])}")
    return counts, seen, out.strip().splitlines()[-1] if out.strip() else ""


def measure(inp: Inputs, build: Path, ct: Path, ct_nofp: Path, core: str, opt: str) -> ConfigResult:
    res = ConfigResult(core, opt)
    t0 = time.monotonic()
    out = build / f"{core}{opt}"
    out.mkdir(parents=True, exist_ok=True)
    for su in out.glob("*.su"):
        su.unlink()
    # The two libraries' umbrella headers may share a name: each translation unit sees one.
    inc = {"canspec": [inp.headers], "cantools": [ct]}
    p = re.escape(inp.prefix)
    msgs = "|".join(map(re.escape, inp.names))  # cantools' names: the spec's
    cmsgs = "|".join(re.escape(inp.c_base[n]) for n in inp.names)  # canspec's
    api = {
        "double": rf"{p}_({cmsgs})_\w+_(encode|decode)",
        "fixed": rf"{p}_({cmsgs})_\w+_(encode|decode)_fixed",
        "monitor": rf"{p}_monitor_(on_frame|check)",
    }
    try:
        objs = {}
        for name in (
            "canspec_wrappers", "cantools_xor", "cantools_xoronly", "harness_canspec", "harness_cantools", "harness_cantools_xor", "bench_main", "canspec_api",
            "stub_main", "stub_main_api"):
            compile_obj(core, opt, build / f"{name}.c", out / f"{name}.o", inc["cantools" if "cantools" in name else "canspec"])
            objs[name] = out / f"{name}.o"
        compile_obj(core, opt, ct / f"{inp.db}.c", out / "cantools.o", [ct])
        compile_obj(core, opt, ct_nofp / f"{inp.db}.c", out / "cantools_nofp.o", [ct_nofp])
        compile_obj(core, opt, build / "cantools_fixed_user.c", out / "cantools_fixed_user.o", [ct_nofp])
        # The dynamic count.
        bench = out / "bench.elf"
        link(core, [objs["bench_main"], objs["harness_canspec"], objs["harness_cantools"], objs["harness_cantools_xor"],
                    objs["canspec_wrappers"], objs["cantools_xor"], out / "cantools.o"], bench, build)
        run_names = {f"run_{lib}_{n}_{ph}" for lib in LIBS for n in inp.names for ph in PHASES}
        counts, seen, res.check = trace_counts(bench, run_names)
        for lib in LIBS:
            helpers: set[str] = set()
            for n in inp.names:
                for ph in PHASES:
                    key = f"run_{lib}_{n}_{ph}"
                    res.counts[(lib, n, ph)] = counts.get(key, 0) / FRAMES_PER_MESSAGE
                    helpers |= {s for s in seen.get(key, ()) if is_helper(s)}
            res.traced_helpers[lib] = helpers
        # Sizes, helpers and stack from single-library images.
        images = {}
        for name, objs_ in {"canspec": [objs["canspec_wrappers"], objs["stub_main"]],
                            "cantools": [out / "cantools.o", objs["stub_main"]],
                            "cantools_xor": [out / "cantools.o", objs["cantools_xor"], objs["stub_main"]],
                            "cantools_xoronly": [out / "cantools.o", objs["cantools_xoronly"], objs["stub_main"]],
                            "cantools_nofp": [out / "cantools_nofp.o", objs["stub_main"]],
                            "cantools_fixed_user": [out / "cantools_nofp.o", out / "cantools_fixed_user.o", objs["stub_main"]],
                            "api": [objs["canspec_api"], objs["stub_main_api"]]}.items():
            link(core, objs_, out / f"size_{name}.elf", build)
            images[name] = load_image(out / f"size_{name}.elf")
        db = re.escape(inp.db)
        groups = {
            "canspec pack+unpack": ("canspec", [f"x_{n}_{ph}" for n in inp.names for ph in PHASES]),
            "cantools pack+unpack": ("cantools", [f"{inp.db}_{n}_{ph}" for n in inp.names for ph in PHASES]),
            "cantools+XOR pack+unpack": (
                "cantools_xoronly",
                [f"cxo_{n}_{ph}" if f"cxo_{n}_{ph}" in images["cantools_xoronly"].sizes else f"{inp.db}_{n}_{ph}" for n in inp.names for ph in PHASES]),
            # like for like: the user's XOR and range-check wrappers with the cantools functions they call
            "cantools+user pack+unpack": (
                "cantools_xor",
                [f"cx_{n}_{ph}" if f"cx_{n}_{ph}" in images["cantools_xor"].sizes else f"{inp.db}_{n}_{ph}" for n in inp.names for ph in PHASES]),
            "canspec double encode+decode": ("api", [f for f in images["api"].sizes if re.fullmatch(api["double"], f)]),
            "cantools double encode+decode": ("cantools", [f for f in images["cantools"].sizes if re.fullmatch(rf"{db}_({msgs})_\w+_(encode|decode)", f)]),
            "cantools is_in_range+is_in_phys_range": (
                "cantools", [f for f in images["cantools"].sizes if re.fullmatch(rf"{db}_({msgs})_\w+_is_in_(phys_)?range", f)]),
            "canspec integer encode+decode_fixed": ("api", [f for f in images["api"].sizes if re.fullmatch(api["fixed"], f)]),
            "cantools --no-floating-point-numbers is_in_range": (
                "cantools_nofp", [f for f in images["cantools_nofp"].sizes if re.fullmatch(rf"{db}_({msgs})_\w+_is_in_range", f)]),
            # like for like: cantools converts nothing without floats; the user's conversion around its is_in_range (fixed_user.py)
            "cantools+user integer (conversion + is_in_range)": (
                "cantools_fixed_user", [f for f in images["cantools_fixed_user"].sizes if re.fullmatch(r"ux_\w+_(en|de)code_fixed", f)]),
            "cantools --no-floating-point-numbers is_in_phys_range (double)": (
                "cantools_nofp", [f for f in images["cantools_nofp"].sizes if re.fullmatch(rf"{db}_({msgs})_\w+_is_in_phys_range", f)]),
            "canspec monitor on_frame+check": ("api", [f for f in images["api"].sizes if re.fullmatch(api["monitor"], f)]),
        }
        # read-only data a group's functions read, by name: the double encoders' descriptors
        # (file scope, or `<name>.<n>` where GCC names an encoder's own)
        data = {"canspec double encode+decode": rf"{p}_({cmsgs})_\w+_phys(\.\d+)?"}
        for label, (img, roots) in groups.items():
            res.sizes[label] = group_size(images[img], roots) if roots else (0, set())
            if label in data:
                extra = sum(n for name, n in images[img].data.items() if re.fullmatch(data[label], name))
                res.sizes[label] = (res.sizes[label][0] + extra, res.sizes[label][1])
        for label, img, obj, roots in (("canspec pack/unpack", "canspec", "canspec_wrappers", groups["canspec pack+unpack"][1]),
                                       ("cantools pack/unpack", "cantools", "cantools", groups["cantools pack+unpack"][1]),
                                       ("canspec monitor", "api", "canspec_api", groups["canspec monitor on_frame+check"][1])):
            su = stack_usage(out / f"{obj}.su")
            frames = [(su.get(f, images[img].frames.get(f, 0)), f) for f in roots]
            res.frame[label] = max(frames) if frames else (0, "-")
            paths = [deepest(images[img], su, f) for f in roots]
            res.stack[label] = max(paths, key=lambda d: d[0]) if paths else (0, [])
    except (RuntimeError, subprocess.CalledProcessError, OSError) as exc:
        res.error = str(exc)
    res.seconds = time.monotonic() - t0
    return res


def write_sources(inp: Inputs, build: Path) -> tuple[Path, Path]:
    build.mkdir(parents=True, exist_ok=True)
    ct, ct_nofp = build / "cantools", build / "cantools-nofp"
    for d, extra in ((ct, []), (ct_nofp, ["--no-floating-point-numbers"])):
        d.mkdir(exist_ok=True)
        proc = subprocess.run([sys.executable, "-m", "cantools", "generate_c_source", *extra, str(inp.dbc), "-o", str(d)],
                              capture_output=True, text=True, check=False)
        if proc.returncode != 0:
            raise RuntimeError(f"cantools generate_c_source failed: {proc.stderr[-2000:]}")
    header = (ct / f"{inp.db}.h").read_text()
    missing = [n for n in inp.names if f"{inp.db}_{n}_pack(" not in header]
    if missing and len(missing) * 4 > len(inp.names):
        raise RuntimeError(f"cantools output lacks {missing}")
    if missing:  # an imported DBC name cantools' C spells otherwise (NEW_MSG_15B → new_msg_15_b): left out, said so
        print(f"bench-c-cross: left out (cantools' C name differs from the spec's): {', '.join(missing)}")
        inp.names = [n for n in inp.names if n not in missing]
    p = re.escape(inp.prefix)
    cmsgs = "|".join(re.escape(inp.c_base[n]) for n in inp.names)
    sources = {
        "canspec_wrappers.c": src_canspec_wrappers(inp),
        "cantools_xor.c": src_cantools_xor(inp),
        "cantools_xoronly.c": src_cantools_xor(inp, "cxo", with_ranges=False),
        "harness_canspec.c": src_harness(inp, "canspec"),
        "harness_cantools.c": src_harness(inp, "cantools"),
        "harness_cantools_xor.c": src_harness(inp, "cantools_xor"),
        "bench_main.c": src_main(inp),
        "canspec_api.c": src_api(inp, {"api": rf"{p}_({cmsgs})_\w+_(encode|decode)(_fixed)?", "monitor": rf"{p}_monitor_(on_frame|check)"}),
        "stub_main.c": STUB_MAIN,
        "stub_main_api.c": STUB_MAIN_API,
        "cantools_fixed_user.c": fixed_user_source(inp.spec, inp.dbc)[0],
    }
    for name, text in sources.items():
        (build / name).write_text(text)
    return ct, ct_nofp


def load_inputs(headers: Path, dbc: Path, vectors: Path, spec: Path) -> Inputs:
    inp = Inputs(headers, dbc, vectors, spec)
    inp.prefix = cross.header_prefix(headers)
    inp.db = dbc.stem
    doc = json.loads(vectors.read_text(encoding="utf-8"))
    inp.names = list(dict.fromkeys(c["message"] for c in doc["cases"]))
    inp.frames = {n: frames_for(doc["cases"], n) for n in inp.names}
    inp.xor, inp.c_base = checksum_layout(spec)
    inp.ranges = range_checks(spec, dbc)
    inp.functions = header_functions(headers)
    return inp


# --- report -------------------------------------------------------------------------------


def report(inp: Inputs, results: list[ConfigResult]) -> str:
    out: list[str] = []
    sizes_by_core: dict[str, dict[str, ConfigResult]] = {}
    for r in results:
        sizes_by_core.setdefault(r.core, {})[r.opt] = r
        out.append(f"\n[{r.core} {r.opt}] dynamic instructions per pack+unpack pair (qemu-arm -singlestep trace, "
                   f"{FRAMES_PER_MESSAGE} frames per message; ratio = other / canspec)")
        if r.error:
            out.append(f"FAILED: {r.error}")
            continue
        out.append(f"{'message':<28} {'canspec':>8} {'(unpack':>8} {'pack)':>6} {'cantools':>9} {'ratio':>6} {'cantools+user':>13} {'ratio':>6}")
        tot = {lib: 0.0 for lib in LIBS}
        worst: tuple[float, str] = (1e9, "-")
        for n in inp.names:
            v = {lib: r.counts[(lib, n, "unpack")] + r.counts[(lib, n, "pack")] for lib in LIBS}
            for lib in LIBS:
                tot[lib] += v[lib]
            rx = v["cantools_xor"] / v["canspec"] if v["canspec"] else 0.0
            worst = min(worst, (rx, n))
            out.append(f"{n:<28} {v['canspec']:8.1f} {r.counts[('canspec', n, 'unpack')]:8.1f} {r.counts[('canspec', n, 'pack')]:6.1f} "
                       f"{v['cantools']:9.1f} {v['cantools'] / v['canspec'] if v['canspec'] else 0:5.2f}x "
                       f"{v['cantools_xor']:13.1f} {rx:5.2f}x" + ("  *" if n in inp.xor else ""))
        out.append(f"{'overall (sum)':<28} {tot['canspec']:8.1f} {'':>8} {'':>6} {tot['cantools']:9.1f} {tot['cantools'] / tot['canspec']:5.2f}x "
                   f"{tot['cantools_xor']:13.1f} {tot['cantools_xor'] / tot['canspec']:5.2f}x")
        fewer = sum(r.counts[("canspec", n, "unpack")] + r.counts[("canspec", n, "pack")]
                    <= r.counts[("cantools_xor", n, "unpack")] + r.counts[("cantools_xor", n, "pack")] for n in inp.names)
        out.append(
            f"worst message (like for like): {worst[1]} {worst[0]:.2f}x; "
            f"canspec executes at most as many instructions as cantools+user on {fewer} of {len(inp.names)}"
            "  (* = XOR checksum message; cantools+user = cantools + the XOR fill/check + the field range check a user adds for canspec's guarantees; "
            f"{r.check})")
        for lib in LIBS:
            out.append(f"helpers executed by {lib}: {', '.join(sorted(r.traced_helpers[lib])) or 'none'}")
    for core, by_opt in sizes_by_core.items():
        opts = list(by_opt)
        out.append(f"\n[{core}] code size, bytes (-ffunction-sections -fno-ipa-icf: the functions + the static helpers they call; "
                   "libgcc/libc helpers named, not counted)")
        labels = next((list(r.sizes) for r in by_opt.values() if r.sizes), [])
        out.append(f"{'':<62}" + "".join(f"{o:>8}" for o in opts) + "  helpers called")
        for label in labels:
            row = [by_opt[o].sizes.get(label, (0, set())) for o in opts]
            helpers = sorted(set().union(*(h for _, h in row)))
            out.append(f"{label:<62}" + "".join(f"{s:>8}" for s, _ in row) + f"  {', '.join(helpers) or '-'}")
        out.append("stack, bytes (-fstack-usage; deepest path adds frames along the call graph)")
        for o in opts:
            r = by_opt[o]
            for label in r.frame:
                fr, fn = r.frame[label]
                depth, path = r.stack[label]
                out.append(f"  {o:<4} {label:<22} largest frame {fr:>4} ({fn}); deepest path {depth:>4}: {' > '.join(path)}")
    out.append("\nhelper-free (no libgcc/soft-float/libc call from pack/unpack and the integer path, by call graph):")
    for r in results:
        if r.error:
            continue
        found = sorted(r.sizes["canspec pack+unpack"][1] | r.sizes["canspec integer encode+decode_fixed"][1])
        out.append(f"  {r.core} {r.opt}: {'yes' if not found else 'NO: ' + ', '.join(found)}")
    return "\n".join(out)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description="canspec C vs cantools on Cortex-M0+/M4 under qemu-arm")
    ap.add_argument("--headers", type=Path, default=cbuild.HEADERS)
    ap.add_argument("--dbc", type=Path, default=ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc")
    ap.add_argument("--vectors", type=Path, default=cbuild.DEFAULT_VECTORS)
    ap.add_argument("--spec", type=Path, default=ROOT / "spec", help="the spec the headers came from (checksum layout)")
    ap.add_argument("--configs", default=DEFAULT_CONFIGS, help="core:opt,... with core in " + ", ".join(cross.ARM_CORES))
    ap.add_argument("--build", type=Path, default=ROOT / "build" / "c-bench-cross")
    ap.add_argument("-j", "--jobs", type=int, default=None)
    args = ap.parse_args(argv[1:])
    missing = [t for t in (cross.ARM_CC, "qemu-arm", "arm-none-eabi-nm", "arm-none-eabi-objdump") if not cross.shutil.which(t)]
    if missing:
        print(f"bench-c-cross: missing {', '.join(missing)} (make setup)", file=sys.stderr)
        return 1
    try:
        configs = [tuple(c.split(":", 1)) for c in args.configs.split(",") if c]
        for core, _ in configs:
            if core not in cross.ARM_CORES:
                raise ValueError(f"unknown core {core}")
        inp = load_inputs(args.headers, args.dbc, args.vectors, args.spec)
        ct, ct_nofp = write_sources(inp, args.build)
    except (ValueError, RuntimeError, OSError) as exc:
        print(f"bench-c-cross: {exc}", file=sys.stderr)
        return 1
    t0 = time.monotonic()
    with ThreadPoolExecutor(max_workers=args.jobs or os.cpu_count() or 2) as pool:
        results = list(pool.map(lambda c: measure(inp, args.build, ct, ct_nofp, c[0], c[1]), configs))
    print(f"{cross.ARM_CC} {' '.join(COMMON)}; cantools {inp.db}.c from {args.dbc.name}; {time.monotonic() - t0:.0f} s")
    print(report(inp, results))
    return 1 if any(r.error or not r.check.startswith("bench: 0 mismatches") for r in results) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
