"""The C vector runner (tests/targets/c/runner.c) built for other machines and run under emulation:
x86-64 (native), big-endian 32-bit PowerPC (powerpc-linux-gnu-gcc, qemu-ppc), and the exact
Cortex-M0+ and Cortex-M4 cores (arm-none-eabi-gcc -mcpu=... -mthumb with newlib; run as Linux
processes by user-mode qemu-arm through arm_linux_shim.c, which implements newlib's system layer
with Linux system calls, so the runner reads the vectors file by its path as on a host).

Each target is built once per compile-time strategy of the headers (`--strategies`, default
$CANSPEC_C_STRATEGIES or DEFAULT_STRATEGIES) plus once with nothing defined, and each build also
compiles the headers alone with the strict warning flags for that target (32-bit size_t, ...).

    python3 tests/targets/c/cross/cross.py [--headers DIR] [--spec SPEC] [--vectors FILE]
        [--targets x86-64,ppc,...] [--strategies 'MACRO=0,1/le;...'] [--build DIR] [-j N]

Prints one line per (target, strategy): cases, multi-frame texts, mismatches; exits 1 on any
mismatch, failed build or missing tool. Standard library only (plus the repository's
tests/targets/c helpers, which read the spec to map vector signal names to struct fields and to work out
what each encode and fixed-point decode must give)."""

from __future__ import annotations

import argparse
import itertools
import os
import re
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
import cbuild  # noqa: E402

ROOT = cbuild.ROOT
SHIM = HERE / "arm_linux_shim.c"
PPC_SYSROOT = "/usr/powerpc-linux-gnu"

# The compile-time strategies the current headers offer: MACRO=value,value[;MACRO=...]. A value
# marked /le is a little-endian-only fast path (not built for big-endian targets). The C rewrite
# changes this list; CANSPEC_C_STRATEGIES overrides it without editing this file.
DEFAULT_STRATEGIES = "KAIWO_GATEWAY_STRATEGY=0,1,2,3"

# The exact cores: flags shared by the runner builds and the benchmarks. Cortex-M4 without the
# FPU's float ABI (the headers compute in double, which the M4F's single-precision FPU does not do).
ARM_CORES = {
    "cortex-m0plus": ("-mcpu=cortex-m0plus", "-mthumb"),
    "cortex-m4": ("-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=soft"),
}
ARM_CC = "arm-none-eabi-gcc"


@dataclass(frozen=True)
class Target:
    name: str
    cc: str
    flags: tuple[str, ...]
    emulator: tuple[str, ...] = ()
    little_endian: bool = True
    bare_metal: bool = False  # newlib + arm_linux_shim.c

    def tools(self) -> list[str]:
        return [self.cc, *self.emulator[:1]]

    def missing(self) -> list[str]:
        return [t for t in self.tools() if shutil.which(t) is None]


TARGETS = {
    t.name: t
    for t in (
        Target("x86-64", "gcc", ("-O2",)),
        Target("ppc", "powerpc-linux-gnu-gcc", ("-O2",), ("qemu-ppc", "-L", PPC_SYSROOT), little_endian=False),
        Target("cortex-m0plus", ARM_CC, (*ARM_CORES["cortex-m0plus"], "-Os"), ("qemu-arm",), bare_metal=True),
        Target("cortex-m4", ARM_CC, (*ARM_CORES["cortex-m4"], "-Os"), ("qemu-arm",), bare_metal=True),
        Target("cortex-m4-O2", ARM_CC, (*ARM_CORES["cortex-m4"], "-O2"), ("qemu-arm",), bare_metal=True),
    )
}


@dataclass(frozen=True)
class Strategy:
    defines: tuple[tuple[str, str], ...] = ()
    little_endian_only: bool = False

    @property
    def name(self) -> str:
        return ",".join(f"{m}={v}" for m, v in self.defines) or "default"

    def flags(self) -> list[str]:
        return [f"-D{m}={v}" for m, v in self.defines]


def parse_strategies(text: str) -> list[Strategy]:
    """'A=0,1/le;B=x,y' → the build with nothing defined, then every combination of the values."""
    axes: list[list[tuple[str, str, bool]]] = []
    for part in filter(None, (p.strip() for p in text.split(";"))):
        macro, _, values = part.partition("=")
        if not re.fullmatch(r"[A-Za-z_]\w*", macro.strip()) or not values.strip():
            raise ValueError(f"strategy {part!r}: expected MACRO=value[,value...]")
        axis = []
        for v in values.split(","):
            value, _, flag = v.strip().partition("/")
            if flag not in ("", "le"):
                raise ValueError(f"strategy {part!r}: unknown marker /{flag} (only /le)")
            axis.append((macro.strip(), value, flag == "le"))
        axes.append(axis)
    out = [Strategy()]
    for combo in itertools.product(*axes):
        out.append(Strategy(tuple((m, v) for m, v, _ in combo), any(le for _, _, le in combo)))
    return out


def strategies_from_env() -> list[Strategy]:
    return parse_strategies(os.environ.get("CANSPEC_C_STRATEGIES", DEFAULT_STRATEGIES))


def applicable(target: Target, strategies: list[Strategy]) -> list[Strategy]:
    return [s for s in strategies if target.little_endian or not s.little_endian_only]


_GUARD = re.compile(r"_H(_INCLUDED)?$")


def config_macros(headers: Path) -> set[str]:
    """The macros that choose code in the headers: the identifiers tested by #if/#elif/#ifdef,
    minus include guards, compiler-predefined names (__...) and the `defined` operator.
    #ifndef X / #define X value pairs (tunable values, e.g. a default timeout) are not choices."""
    found: set[str] = set()
    for h in sorted(headers.glob("*.h")):
        for m in re.finditer(r"^\s*#\s*(if|elif|ifdef)\b(.*(?:\\\n.*)*)", h.read_text(encoding="utf-8"), re.MULTILINE):
            for ident in re.findall(r"[A-Za-z_]\w*", re.sub(r"/\*.*?\*/", " ", m.group(2))):  # not a comment's words
                if ident == "defined" or ident.startswith("__") or _GUARD.search(ident):
                    continue
                found.add(ident)
    return found


def header_prefix(headers: Path) -> str:
    """`foo` for headers foo.h + foo_common.h + ...: the umbrella header that includes the others."""
    commons = sorted(headers.glob("*_common.h"))
    if len(commons) != 1:
        raise ValueError(f"{headers}: expected exactly one *_common.h")
    return commons[0].name[: -len("_common.h")]


@dataclass
class Result:
    target: str
    strategy: str
    ok: bool = False
    cases: int = 0
    texts: int = 0
    mismatches: int = -1
    build_s: float = 0.0
    run_s: float = 0.0
    error: str = ""
    output: str = field(default="", repr=False)


def run(cmd: list[str], timeout: float = 600) -> subprocess.CompletedProcess:  # type: ignore[type-arg]
    return subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=timeout)


def shim_object(target: Target, build: Path) -> Path:
    """arm_linux_shim.c compiled for the target's core (r7 is free: no frame pointer)."""
    obj = build / f"shim-{target.name}.o"
    if not obj.exists():
        tmp = obj.with_suffix(f".{os.getpid()}.{id(target)}.o")
        proc = run([target.cc, *target.flags, "-O2", "-fomit-frame-pointer", "-c", str(SHIM), "-o", str(tmp)])
        if proc.returncode != 0:
            raise RuntimeError(f"shim build failed:\n{proc.stderr[-4000:]}")
        tmp.replace(obj)
    return obj


def link_flags(target: Target, build: Path) -> list[str]:
    """What a program for the target needs at link time (after its sources)."""
    if target.bare_metal:
        return [str(shim_object(target, build)), "-nostartfiles", "-lm"]
    return ["-lm"]


def command(target: Target, exe: Path, *args: str) -> list[str]:
    return [*target.emulator, str(exe), *args]


def prepare(build: Path, spec: Path, vectors: Path) -> Path:
    """runner_tables.h (from the spec) and the line form of the vectors, once for every build."""
    build.mkdir(parents=True, exist_ok=True)
    (build / "runner_tables.h").write_text(cbuild.tables(str(spec)), encoding="utf-8")
    return cbuild.vectors_lines(vectors, build, cbuild.spec_can(spec))


def check_one(target: Target, strategy: Strategy, build: Path, headers: Path, lines: Path, prefix: str) -> Result:
    res = Result(target.name, strategy.name)
    missing = target.missing()
    if missing:
        res.error = f"missing tools: {', '.join(missing)} (make setup)"
        return res
    out = build / target.name / re.sub(r"[^\w.=-]+", "_", strategy.name)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.monotonic()
    try:
        # The headers alone, strict, for this target's int/size_t/long widths.
        strict_src = out / "strict.c"
        strict_src.write_text(f'#include "{prefix}.h"\nint canspec_strict_probe(void);\nint canspec_strict_probe(void) {{ return 0; }}\n')
        proc = run([target.cc, *target.flags, "-std=c99", *cbuild.STRICT, *strategy.flags(), f"-I{headers}", "-fsyntax-only", str(strict_src)])
        if proc.returncode != 0:
            res.error = f"headers not warning-free for {target.name}:\n{proc.stderr[-4000:]}"
            return res
        exe = out / ("runner.elf" if target.bare_metal else "runner")
        proc = run(
            [
                target.cc,
                *target.flags,
                "-std=c99",
                *cbuild.STRICT,
                *strategy.flags(),
                f"-I{headers}",
                f"-I{build}",
                str(cbuild.HERE / "runner.c"),
                "-o",
                str(exe),
                *link_flags(target, build),
            ]
        )
        if proc.returncode != 0:
            res.error = f"runner build failed:\n{proc.stderr[-4000:]}"
            return res
    except (RuntimeError, subprocess.TimeoutExpired) as exc:
        res.error = str(exc)
        return res
    res.build_s = time.monotonic() - t0
    t0 = time.monotonic()
    try:
        proc = run(command(target, exe, str(lines)), timeout=300)
    except subprocess.TimeoutExpired:
        res.error = "runner timed out"
        return res
    res.run_s = time.monotonic() - t0
    res.output = proc.stdout + proc.stderr[-4000:]
    m = cbuild.CASES_RE.search(proc.stdout)
    if not m:
        res.error = f"runner exit {proc.returncode}, no summary line:\n{res.output[-2000:]}"
        return res
    res.cases, res.texts, res.mismatches = int(m.group(1)), int(m.group(2)), int(m.group(3))
    res.ok = proc.returncode == 0 and res.mismatches == 0
    if not res.ok:
        res.error = f"runner exit {proc.returncode}:\n{proc.stderr[-3000:]}"
    return res


def check_all(
    targets: list[Target],
    strategies: list[Strategy],
    build: Path,
    headers: Path = cbuild.HEADERS,
    spec: Path = ROOT / "spec",
    vectors: Path = cbuild.DEFAULT_VECTORS,
    jobs: int | None = None,
) -> list[Result]:
    lines = prepare(build, spec, vectors)
    prefix = header_prefix(headers)
    for t in targets:  # once, before the parallel builds
        if t.bare_metal and not t.missing():
            shim_object(t, build)
    work = [(t, s) for t in targets for s in applicable(t, strategies)]
    with ThreadPoolExecutor(max_workers=jobs or os.cpu_count() or 2) as pool:
        return list(pool.map(lambda ts: check_one(ts[0], ts[1], build, headers, lines, prefix), work))


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--headers", type=Path, default=cbuild.HEADERS)
    ap.add_argument("--spec", type=Path, default=ROOT / "spec", help="the spec the headers were generated from (maps vector signal names to C fields)")
    ap.add_argument("--vectors", type=Path, default=cbuild.DEFAULT_VECTORS)
    ap.add_argument("--targets", default=",".join(TARGETS), help=f"comma-separated, of {', '.join(TARGETS)}")
    ap.add_argument("--strategies", default=os.environ.get("CANSPEC_C_STRATEGIES", DEFAULT_STRATEGIES))
    ap.add_argument("--build", type=Path, default=ROOT / "build" / "c-cross")
    ap.add_argument("-j", "--jobs", type=int, default=None)
    args = ap.parse_args(argv[1:])
    try:
        targets = [TARGETS[n] for n in args.targets.split(",") if n]
        strategies = parse_strategies(args.strategies)
    except (KeyError, ValueError) as exc:
        print(f"cross: {exc}", file=sys.stderr)
        return 2
    uncovered = config_macros(args.headers) - {m for s in strategies for m, _ in s.defines}
    if uncovered:
        print(f"cross: note: the headers test {sorted(uncovered)} but --strategies does not vary them", file=sys.stderr)
    t0 = time.monotonic()
    results = check_all(targets, strategies, args.build, args.headers, args.spec, args.vectors, args.jobs)
    print(f"{'target':<15} {'strategy':<32} {'cases':>6} {'texts':>6} {'mismatches':>10} {'build s':>8} {'run s':>6}")
    for r in results:
        print(
            f"{r.target:<15} {r.strategy:<32} {r.cases:>6} {r.texts:>6} {r.mismatches if r.mismatches >= 0 else '-':>10} {r.build_s:>8.1f} {r.run_s:>6.2f}"
            + ("" if r.ok else "  FAILED")
        )
    for r in results:
        if not r.ok:
            print(f"\n{r.target} {r.strategy}: {r.error}", file=sys.stderr)
    bad = sum(not r.ok for r in results)
    print(f"cross: {len(results) - bad} passed, {bad} failed ({time.monotonic() - t0:.0f} s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
