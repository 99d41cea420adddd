"""`make bench-c`: pack + unpack of every message, canspec's generated C vs the C that
`cantools generate_c_source` makes from the generated DBC. Same compiler (gcc -O2), same
harness (one translation unit per library: its code plus the identical loop), same frames
(the shared vectors). Prints ns/frame of both and the ratio per message and overall, plus
the code size of both libraries' pack+unpack functions."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import cbuild

FRAMES_PER_MESSAGE = 16
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
    return "{" + ", ".join(f"0x{hexdata[i:i + 2]}" for i in range(0, 16, 2)) + "}"


def harness(lib: str, include: str, names: list[str], frames: dict[str, list[str]], struct_kw: str, pack_args: str) -> str:
    out = [include, "#include <stdint.h>", "#include <stddef.h>", ""]
    for n in names:
        rows = ",\n    ".join(c_bytes(h) for h in frames[n])
        out.append(f"static const uint8_t F_{n}[{FRAMES_PER_MESSAGE}][8] = {{\n    {rows}\n}};")
        out.append(f"__attribute__((noinline)) uint64_t {lib}_run_{n}(long iters) {{")
        out.append(f"    {struct_kw}kaiwo_gateway_{n}_t s;")
        out.append("    uint8_t buf[8];")
        out.append("    uint64_t acc = 0;")
        out.append("    long i;")
        out.append("    for (i = 0; i < iters; i++) {")
        out.append(f"        acc += (uint64_t)kaiwo_gateway_{n}_unpack(&s, F_{n}[i & {FRAMES_PER_MESSAGE - 1}], 8);")
        # The decoded struct is consumed and the struct to send is produced elsewhere in a real
        # ECU: the barriers keep the compiler from fusing unpack into pack.
        out.append("        __asm__ volatile(\"\" : : \"r\"(&s) : \"memory\");")
        out.append(f"        acc += (uint64_t)kaiwo_gateway_{n}_pack({pack_args});")
        out.append("        __asm__ volatile(\"\" : : \"r\"(buf) : \"memory\");")
        out.append("        acc += buf[0] ^ buf[3] ^ buf[7];")
        out.append("    }")
        out.append("    return acc;")
        out.append("}")
    out.append(f"typedef uint64_t (*run_fn)(long);")
    out.append(f"const run_fn {lib}_runs[] = {{ {', '.join(f'{lib}_run_{n}' for n in names)} }};")
    return "\n".join(out) + "\n"


def sizes_wrapper(names: list[str]) -> str:
    """Out-of-line copies of canspec's pack/unpack so their code size can be measured."""
    out = ['#include "kaiwo_gateway.h"']
    for n in names:
        out.append(f"kaiwo_gateway_status_t x_{n}_pack(uint8_t *d, size_t z, const kaiwo_gateway_{n}_t *s) {{ return kaiwo_gateway_{n}_pack(d, z, s); }}")
        out.append(f"kaiwo_gateway_status_t x_{n}_unpack(kaiwo_gateway_{n}_t *s, const uint8_t *d, size_t z) {{ return kaiwo_gateway_{n}_unpack(s, d, z); }}")
    return "\n".join(out) + "\n"


MAIN = r"""
#include <stdint.h>
#include <stdio.h>
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
int main(void) {
    const long iters = %ITERS%;
    double tot_a = 0, tot_b = 0; int i, slower = 0;
    printf("%-28s %12s %12s %8s\n", "message", "canspec ns", "cantools ns", "ratio");
    for (i = 0; i < N_MSG; i++) {
        double a, b;
        best_pair(canspec_runs[i], cantools_runs[i], iters, &a, &b);
        tot_a += a; tot_b += b; slower += a > b;
        printf("%-28s %12.2f %12.2f %7.2fx\n", NAMES[i], a, b, b / a);
    }
    printf("%-28s %12.2f %12.2f %7.2fx\n", "overall (sum)", tot_a, tot_b, tot_b / tot_a);
    printf("messages where canspec is slower: %d of %d\n", slower, N_MSG);
    return 0;
}
"""


def symbol_bytes(obj: Path, pattern: str) -> int:
    out = subprocess.run(["nm", "-S", "--defined-only", str(obj)], capture_output=True, text=True, check=True).stdout
    total = 0
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in "tT" and re.search(pattern, parts[3]):
            total += int(parts[1], 16)
    return total


def text_size(obj: Path) -> int:
    out = subprocess.run(["size", "-A", str(obj)], capture_output=True, text=True, check=True).stdout
    return sum(int(l.split()[1]) for l in out.splitlines() if l.startswith(".text"))


def main(argv: list[str]) -> int:
    build = Path(argv[1]) if len(argv) > 1 else cbuild.ROOT / "build" / "c-bench"
    iters = int(argv[2]) if len(argv) > 2 else 100_000
    build.mkdir(parents=True, exist_ok=True)
    ct = build / "cantools"
    ct.mkdir(exist_ok=True)
    dbc = cbuild.ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"
    proc = cbuild.run([sys.executable, "-m", "cantools", "generate_c_source", str(dbc), "-o", str(ct)])
    if proc.returncode != 0:
        print(f"bench-c: cantools generate_c_source failed: {proc.stderr}", file=sys.stderr)
        return 1
    vectors = json.loads(cbuild.DEFAULT_VECTORS.read_text(encoding="utf-8"))
    names = list(dict.fromkeys(c["message"] for c in vectors["cases"]))
    header = (ct / "kaiwo_gateway.h").read_text()
    missing = [n for n in names if f"kaiwo_gateway_{n}_pack(" not in header]
    if missing:
        print(f"bench-c: cantools output lacks {missing}", file=sys.stderr)
        return 1
    frames = {n: frames_for(vectors["cases"], n) for n in names}
    (build / "bench_canspec.c").write_text(harness("canspec", '#include "kaiwo_gateway.h"', names, frames, "", "buf, 8, &s"))
    (build / "bench_cantools.c").write_text(harness("cantools", '#include "cantools/kaiwo_gateway.c"', names, frames, "struct ", "buf, &s, 8"))
    (build / "bench_main.c").write_text(MAIN.replace("%NAMES%", ", ".join(f'"{n}"' for n in names)).replace("%N%", str(len(names))).replace("%ITERS%", str(iters)).replace("%REPS%", str(REPS)))
    (build / "size_canspec.c").write_text(sizes_wrapper(names))
    inc = [f"-I{cbuild.HEADERS}", f"-I{build}", f"-I{ct}"]
    objs = []
    for src in ("bench_canspec.c", "bench_cantools.c", "bench_main.c"):
        obj = build / src.replace(".c", ".o")
        subprocess.run([CC, *CFLAGS, *inc, "-c", str(build / src), "-o", str(obj)], check=True)
        objs.append(str(obj))
    exe = build / "bench"
    subprocess.run([CC, *objs, "-o", str(exe)], check=True)
    size_a, size_b = build / "size_canspec.o", build / "size_cantools.o"
    subprocess.run([CC, *CFLAGS, *inc, "-c", str(build / "size_canspec.c"), "-o", str(size_a)], check=True)
    subprocess.run([CC, *CFLAGS, *inc, "-c", str(ct / "kaiwo_gateway.c"), "-o", str(size_b)], check=True)
    print(f"{CC} {' '.join(CFLAGS)}; {iters} pack+unpack pairs per message, interleaved, best of {REPS} runs (thread CPU time); ratio = cantools / canspec time")
    sys.stdout.flush()
    subprocess.run([str(exe)], check=True)
    pa, pb = symbol_bytes(size_a, r"_(pack|unpack)$"), symbol_bytes(size_b, r"_(pack|unpack)$")
    print(f"code size of pack+unpack of all messages: canspec {pa} bytes, cantools {pb} bytes")
    print(f".text of the object: canspec (pack+unpack wrappers) {text_size(size_a)} bytes, cantools (whole kaiwo_gateway.c) {text_size(size_b)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
