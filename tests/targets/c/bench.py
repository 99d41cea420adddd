"""`make bench-c`: pack + unpack of every message, canspec's generated C vs the C that
`cantools generate_c_source` makes from the generated DBC. Same compiler (gcc -O2), same
harness loop, same 16 frames per message (the shared vectors, cycled so branches see varied
data identically for both), every output consumed (status codes, packed bytes; the struct
passes through a compiler barrier between unpack and pack). Each frame reaches the codec
through a pointer the compiler cannot trace back to the frame table, as a frame from a CAN
driver's buffer does: otherwise, inlined, the compiler would know the bytes are constant and
apart from the struct, and reuse loads across iterations as no receive path lets it.

Two modes, both reported:
- call: how firmware uses a codec from its own translation units. cantools' .c is compiled
  alone as it ships; canspec's static inline functions are compiled alone behind extern
  wrapper functions; the harness calls both through the same non-inlined call boundary.
- inline: each library's code in the harness's translation unit, the compiler free to
  inline what it chooses (it inlines canspec's static inline functions; cantools' extern
  functions are its choice).
Wall time is thread CPU time, best of interleaved A/B runs (the machine is shared); beside
it the load-independent instruction count per pack+unpack pair from valgrind's callgrind: in
call mode the codec's own (the harness loop subtracted from both sides, as bench_cross.py
counts on the ARM cores), in inline mode with the loop it is compiled into. Also prints the
code size of both libraries.

Like for like: canspec's pack fills the XOR checksum byte and its unpack verifies it; the
cantools code does neither. A second pair of runs gives the cantools loop of each message
that carries a checksum the check a user would add around it (verify before unpack with the
word fold canspec uses, fill after pack byte by byte), so the codecs are compared doing the
same work, per message and overall."""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import cbuild
from bench_counts import instruction_counts, symbol_bytes, text_size

sys.path.insert(0, str(cbuild.ROOT / "generator"))
from canspec.pipeline import compile_spec
from canspec.targets.c.names import CNames
from canspec.targets.dbc.naming import signal_names

FRAMES_PER_MESSAGE = 16
PREFIX = "kaiwo_gateway"  # the protocol's C prefix and cantools' file stem (main: from --dbc)
INPUT = argparse.Namespace()  # main's options: spec, headers, dbc, vectors
REPS = 61
CFLAGS = ["-std=gnu99", "-O2"]
CC = os.environ.get("BENCH_CC", "gcc")


def frames_for(cases: list[dict], name: str) -> list[str]:  # type: ignore[type-arg]
    picked = [c["data"] for c in cases if c["message"] == name and c.get("kind") != "raw_only"][:FRAMES_PER_MESSAGE]
    picked = picked or ["00" * 8]
    while len(picked) < FRAMES_PER_MESSAGE:
        picked += picked[: FRAMES_PER_MESSAGE - len(picked)]
    return picked


def c_bytes(hexdata: str) -> str:
    return "{" + ", ".join(f"0x{hexdata[i:i + 2]}" for i in range(0, len(hexdata), 2)) + "}"


XOR_HELPERS = """#include <string.h>
/* The XOR of the frame bytes in `mask` (0xFF per byte): one word load and a fold. */
static inline uint8_t bench_xor(const uint8_t *p, uint64_t mask) {
    uint64_t w;
    memcpy(&w, p, 8);
    w &= mask;
    w ^= w >> 32;
    w ^= w >> 16;
    return (uint8_t)(w ^ (w >> 8));
}
"""


def byte_mask(indices: tuple[int, ...]) -> str:
    return f"UINT64_C(0x{sum(0xFF << (8 * b) for b in indices):016X})"


def range_checks(spec: Path, dbc: Path, access: str = "s->") -> dict[str, str]:
    """message → the condition a cantools user adds to refuse a field that does not fit its bits
    (cantools' pack silently drops the excess bits; canspec's refuses with ERR_RANGE): the same
    form as canspec's, one compare per width of the unsigned fields narrower than their type."""
    from cantools.database.can.c_source import camel_to_snake_case

    can = compile_spec(spec, ["c", "dbc"]).spec.can  # type: ignore[union-attr]  # only the benchmarked targets check the spec
    dbc_names = signal_names(can)  # the DBC target's own naming: the signal names cantools' C is generated from
    out = {}
    for m in can.messages:
        members = {spec: camel_to_snake_case(dbc_name) for (msg, spec), dbc_name in dbc_names.items() if msg == m.name}
        groups: dict[tuple[int, int], list[str]] = {}
        terms = []
        for s in m.data_signals:
            if s.role == "checksum" or s.length == s.storage_bits:
                continue
            field = f"{access}{members[s.name]}"
            if s.signed:
                terms += [f"({field} < {s.raw_type_min})", f"({field} > {s.raw_type_max})"]
            else:
                groups.setdefault((s.length, s.storage_bits), []).append(field)
        terms = [f"(({' | '.join(f)}) > {(1 << n) - 1}u)" for (n, _), f in sorted(groups.items())] + terms
        if terms:
            out[m.name] = " || ".join(terms)
    return out


def harness(lib: str, include: str, names: list[str], frames: dict[str, list[str]], struct_kw: str, pack_args: str,
            fn: str = "", xor: dict[str, tuple[int, tuple[int, ...]]] | None = None, ranges: dict[str, str] | None = None,
            c_base: dict[str, str] | None = None) -> str:
    """`c_base`: canspec's C name of each message (a spec `c_name`), where it is not the spec's; `xor`: for each
    message that carries a checksum, (checksum byte, covered bytes): the loop verifies it before unpack and fills it after pack; `ranges`: the check before pack
    that a field fits its bits (for a library that does neither)."""
    out = [include, "#include <stdint.h>", "#include <stddef.h>", XOR_HELPERS if xor else ""]
    fn = fn or f"{PREFIX}_"
    for n in names:
        cb = (c_base or {}).get(n, n)
        size = len(frames[n][0]) // 2  # the frame's length (up to 64 bytes on CAN FD); buffers at least 8
        rows = ",\n    ".join(c_bytes(h) for h in frames[n])
        out.append(f"static const uint8_t F_{n}[{FRAMES_PER_MESSAGE}][{max(size, 8)}] = {{\n    {rows}\n}};")
        out.append(f"__attribute__((noinline)) uint64_t {lib}_run_{n}(long iters) {{")
        out.append(f"    {struct_kw}{PREFIX}_{cb}_t s;")
        out.append(f"    uint8_t buf[{max(size, 8)}];")
        out.append("    uint64_t acc = 0;")
        out.append("    long i;")
        out.append("    const uint8_t *f;")
        out.append("    for (i = 0; i < iters; i++) {")
        out.append(f"        f = F_{n}[i & {FRAMES_PER_MESSAGE - 1}];")
        out.append("        __asm__(\"\" : \"+r\"(f)); /* a frame from a driver's buffer: origin unknown */")
        if xor and n in xor:
            byte, covers = xor[n]
            out.append(f"        if (bench_xor(f, {byte_mask((*covers, byte))}) != 0u) {{")
            out.append("            acc += 1000u;")
            out.append("        } else {")
            out.append(f"            acc += (uint64_t){fn}{cb}_unpack(&s, f, {size});")
            out.append("        }")
        else:
            out.append(f"        acc += (uint64_t){fn}{cb}_unpack(&s, f, {size});")
        # The decoded struct is consumed and the struct to send is produced elsewhere in a real
        # ECU: the barriers keep the compiler from fusing unpack into pack.
        out.append("        __asm__ volatile(\"\" : : \"r\"(&s) : \"memory\");")
        if ranges and n in ranges:
            out.append(f"        if ({ranges[n]}) {{")
            out.append("            acc += 1000u;")
            out.append("        } else {")
            out.append(f"            acc += (uint64_t){fn}{cb}_pack({pack_args.format(size=size)});")
            out.append("        }")
        else:
            out.append(f"        acc += (uint64_t){fn}{cb}_pack({pack_args.format(size=size)});")
        if xor and n in xor:
            byte, covers = xor[n]
            # Byte-wise: a word load right after cantools' byte stores would stall on store
            # forwarding and charge cantools for the harness's choice.
            out.append(f"        buf[{byte}] = (uint8_t)({' ^ '.join(f'buf[{b}]' for b in covers)});")
        out.append("        __asm__ volatile(\"\" : : \"r\"(buf) : \"memory\");")
        out.append("        acc += buf[0] ^ buf[3] ^ buf[7];")
        out.append("    }")
        out.append("    return acc;")
        out.append("}")
    out.append("typedef uint64_t (*run_fn)(long);")
    out.append(f"const run_fn {lib}_runs[] = {{ {', '.join(f'{lib}_run_{n}' for n in names)} }};")
    return "\n".join(out) + "\n"


def wrappers(names: list[str], define: bool, c_base: dict[str, str]) -> str:
    """Extern copies of canspec's pack/unpack (their own translation unit: the call mode, and
    the code size), or just their declarations (the call-mode harness)."""
    p = PREFIX
    out = [f'#include "{p}.h"']
    for cb in (c_base.get(n, n) for n in names):
        pack = f"{p}_status_t x_{cb}_pack(uint8_t *d, size_t z, const {p}_{cb}_t *s)"
        unpack = f"{p}_status_t x_{cb}_unpack({p}_{cb}_t *s, const uint8_t *d, size_t z)"
        if define:
            out.append(f"{pack} {{ return {p}_{cb}_pack(d, z, s); }}")
            out.append(f"{unpack} {{ return {p}_{cb}_unpack(s, d, z); }}")
        else:
            out += [f"{pack};", f"{unpack};"]
    return "\n".join(out) + "\n"


MAIN = r"""
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
typedef uint64_t (*run_fn)(long);
extern const run_fn canspec_runs[];
extern const run_fn cantools_runs[];
static const char *NAMES[] = {%NAMES%};
#define N_MSG %N%
static volatile uint64_t sink;
static double now_ns(void) { struct timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return (double)t.tv_sec * 1e9 + (double)t.tv_nsec; }
static double time_ns(run_fn f, long iters) { double t0 = now_ns(); sink += f(iters); return (now_ns() - t0) / (double)iters; }
/* Interleaved A/B runs (both see the same machine state); the minimum of each filters out
 * interference from other processes. */
static void best_pair(run_fn a, run_fn b, long iters, double *ba, double *bb) {
    int r;
    *ba = *bb = 1e30;
    sink += a(iters / 10) + b(iters / 10);
    for (r = 0; r < %REPS%; r++) {
        double ta = time_ns(a, iters), tb = time_ns(b, iters);
        if (ta < *ba) *ba = ta;
        if (tb < *bb) *bb = tb;
    }
}
static void table(const char *mode, const run_fn *a_runs, const run_fn *b_runs, long iters) {
    double tot_a = 0, tot_b = 0; int i, slower = 0;
    printf("\n[%s] %-21s %12s %12s %8s\n", mode, "message", "canspec ns", "cantools ns", "ratio");
    for (i = 0; i < N_MSG; i++) {
        double a, b;
        best_pair(a_runs[i], b_runs[i], iters, &a, &b);
        tot_a += a; tot_b += b; slower += a > b;
        printf("%-28s %12.2f %12.2f %7.2fx\n", NAMES[i], a, b, b / a);
    }
    printf("%-28s %12.2f %12.2f %7.2fx\n", "overall (sum)", tot_a, tot_b, tot_b / tot_a);
    printf("[%s] messages where canspec is slower: %d of %d\n", mode, slower, N_MSG);
}
int main(int argc, char **argv) {
    const long iters = %ITERS%;
    int i;
    if (argc > 1) { /* one pass of every loop (for callgrind's instruction counts) */
        long n = atol(argv[1]);
        for (i = 0; i < N_MSG; i++)
            sink += canspec_runs[i](n) + cantools_runs[i](n);
        return 0;
    }
    table(MODE, canspec_runs, cantools_runs, iters);
    return 0;
}
"""


XMODE = "like for like (cantools + the XOR check + the field range check)"


def _sources(names: list[str], frames: dict[str, list[str]], xor: dict[str, tuple[int, tuple[int, ...]]], iters: int, ranges: dict[str, str],
             c_base: dict[str, str]) -> dict[str, str]:
    main_c = (MAIN.replace("%NAMES%", ", ".join(f'"{n}"' for n in names)).replace("%N%", str(len(names)))
              .replace("%ITERS%", str(iters)).replace("%REPS%", str(REPS)))
    return {
        "bench_canspec.c": harness("canspec", f'#include "{PREFIX}.h"', names, frames, "", "buf, {size}, &s", c_base=c_base),
        "bench_cantools.c": harness("cantools", f'#include "cantools/{PREFIX}.c"', names, frames, "struct ", "buf, &s, {size}"),
        "call_canspec.c": harness("canspec", wrappers(names, False, c_base), names, frames, "", "buf, {size}, &s", fn="x_", c_base=c_base),
        "call_cantools.c": harness("cantools", f'#include "cantools/{PREFIX}.h"', names, frames, "struct ", "buf, &s, {size}"),
        "size_canspec.c": wrappers(names, True, c_base),
        "bench_main.c": main_c,
        # Like for like: cantools with the check a user adds where a message has one (canspec's
        # side of these runs is the same code as above).
        "xbench_cantools.c": harness("cantools", f'#include "cantools/{PREFIX}.c"', names, frames, "struct ", "buf, &s, {size}", xor=xor, ranges=ranges),
        "xcall_cantools.c": harness("cantools", f'#include "cantools/{PREFIX}.h"', names, frames, "struct ", "buf, &s, {size}", xor=xor, ranges=ranges),
    }


def _objects(build: Path, ct: Path) -> tuple[dict[str, list[str]], str, str]:
    """Per mode the objects of its benchmark executable; the two size objects."""
    inc = [f"-I{INPUT.headers}", f"-I{build}", f"-I{ct}"]

    def compile_(src: Path, obj: str, *extra: str) -> str:
        subprocess.run([CC, *CFLAGS, *extra, *inc, "-c", str(src), "-o", str(build / obj)], check=True)
        return str(build / obj)

    size_a = compile_(build / "size_canspec.c", "size_canspec.o")
    size_b = compile_(ct / f"{PREFIX}.c", "size_cantools.o")
    call_a, inline_a = compile_(build / "call_canspec.c", "call_canspec.o"), compile_(build / "bench_canspec.c", "bench_canspec.o")
    exes = {
        "call": [call_a, compile_(build / "call_cantools.c", "call_cantools.o"),
                 size_a, size_b, compile_(build / "bench_main.c", "main_call.o", '-DMODE="call"')],
        "inline": [inline_a, compile_(build / "bench_cantools.c", "bench_cantools.o"),
                   compile_(build / "bench_main.c", "main_inline.o", '-DMODE="inline"')],
        f"call, {XMODE}": [call_a, compile_(build / "xcall_cantools.c", "xcall_cantools.o"),
                           size_a, size_b, compile_(build / "bench_main.c", "xmain_call.o", f'-DMODE="call, {XMODE}"')],
        f"inline, {XMODE}": [inline_a, compile_(build / "xbench_cantools.c", "xbench_cantools.o"),
                             compile_(build / "bench_main.c", "xmain_inline.o", f'-DMODE="inline, {XMODE}"')],
    }
    return exes, size_a, size_b


def _inputs(ct: Path) -> tuple[list[str], dict[str, list[str]], dict[str, tuple[int, tuple[int, ...]]], dict[str, str]] | str:
    """Messages, their frames and checksum bytes; or what is wrong."""
    dbc = INPUT.dbc
    proc = cbuild.run([sys.executable, "-m", "cantools", "generate_c_source", str(dbc), "-o", str(ct)])
    if proc.returncode != 0:
        return f"cantools generate_c_source failed: {proc.stderr}"
    vectors = json.loads(INPUT.vectors.read_text(encoding="utf-8"))
    names = list(dict.fromkeys(c["message"] for c in vectors["cases"]))
    header = (ct / f"{PREFIX}.h").read_text()
    missing = [n for n in names if f"{PREFIX}_{n}_pack(" not in header]
    if missing and len(missing) * 4 > len(names):
        return f"cantools output lacks {missing}"
    if missing:  # an imported DBC name cantools' C spells otherwise (NEW_MSG_15B → new_msg_15_b): left out, said so
        print(f"bench-c: left out (cantools' C name differs from the spec's): {', '.join(missing)}")
        names = [n for n in names if n not in missing]
    compiled = compile_spec(INPUT.spec, ["c", "dbc"])
    if compiled.spec is None or compiled.spec.can is None:
        return "the spec does not compile"
    xor = {m.name: (m.checksum.byte, m.checksum.covers) for m in compiled.spec.can.messages if m.checksum is not None}
    c_base = {m.name: CNames.of(compiled.spec.can).message(m.name) for m in compiled.spec.can.messages}
    return names, {n: frames_for(vectors["cases"], n) for n in names}, xor, c_base


def parse_args(argv: list[str]) -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("build", type=Path, nargs="?", default=cbuild.ROOT / "build" / "c-bench")
    ap.add_argument("iters", type=int, nargs="?", default=100_000)
    ap.add_argument("--spec", type=Path, default=cbuild.ROOT / "spec", help="another spec (the second benchmark spec: bench/spec2.py)")
    ap.add_argument("--headers", type=Path, default=cbuild.HEADERS, help="its generated C headers")
    ap.add_argument("--dbc", type=Path, default=cbuild.ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc", help="its generated DBC")
    ap.add_argument("--vectors", type=Path, default=cbuild.DEFAULT_VECTORS, help="its vectors")
    return ap.parse_args(argv[1:])


def main(argv: list[str]) -> int:
    global INPUT, PREFIX
    INPUT = parse_args(argv)
    PREFIX = INPUT.dbc.stem  # cantools' file stem; canspec's headers carry the same protocol name
    if not (INPUT.headers / f"{PREFIX}.h").is_file():
        print(f"bench-c: {INPUT.headers}/{PREFIX}.h missing (the DBC's stem names the headers)", file=sys.stderr)
        return 1
    build, iters = INPUT.build, INPUT.iters
    build.mkdir(parents=True, exist_ok=True)
    ct = build / "cantools"
    ct.mkdir(parents=True, exist_ok=True)
    inputs = _inputs(ct)
    if isinstance(inputs, str):
        print(f"bench-c: {inputs}", file=sys.stderr)
        return 1
    names, frames, xor, c_base = inputs
    ranges = range_checks(INPUT.spec, INPUT.dbc, access="s.")
    for name, text in _sources(names, frames, xor, iters, ranges, c_base).items():
        (build / name).write_text(text)
    exes, size_a, size_b = _objects(build, ct)
    print(
        f"{CC} {' '.join(CFLAGS)}; {iters} pack+unpack pairs per message, interleaved, best of {REPS} runs (thread CPU time); ratio = cantools / canspec time"
    )
    for i, objs in enumerate(exes.values()):
        exe = build / f"bench_{i}"
        subprocess.run([CC, *objs, "-o", str(exe)], check=True)
        sys.stdout.flush()
        subprocess.run([str(exe)], check=True)
    counted = [instruction_counts(build / f"bench_{i}", mode, names) for i, mode in enumerate(exes)]
    pa, pb = symbol_bytes(Path(size_a), r"_(pack|unpack)$"), symbol_bytes(Path(size_b), r"_(pack|unpack)$")
    print(f"\ncode size of pack+unpack of all messages: canspec {pa} bytes, cantools {pb} bytes")
    print(
        f".text of the object: canspec (pack+unpack wrappers) {text_size(Path(size_a))} bytes, cantools (whole {PREFIX}.c) {text_size(Path(size_b))} bytes"
    )
    return 0 if all(counted) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
