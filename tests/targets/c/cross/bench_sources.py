"""The C sources of `make bench-c-cross` (bench_cross.py): canspec's extern wrappers, what a
cantools user adds for canspec's guarantees (XOR checksum, range checks), one harness function per
(library, message, pack|unpack) over the shared vectors' frames, and the checking main; and the
inputs they are written from (the spec's checksum layout and C names, the headers' functions)."""

from __future__ import annotations

import json
import re
import subprocess
import sys
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
LIBS = ("canspec", "cantools", "cantools_xor")
PHASES = ("unpack", "pack")


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
