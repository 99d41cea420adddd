#!/usr/bin/env python3
"""Generation benchmark (issue 25, item 5): time and peak memory of `canspec gen` per target on
synthetic specs of 10, 100, 300 and 1,000 messages (tools/synth_spec.py, 12 signals per message),
plus the gcc -O2 compile time of the largest spec's C headers and the time of `canspec gen --check`
on an unchanged spec. Each target runs in its own process; its peak RSS comes from os.wait4, so
one target's memory never hides another's. The ms/msg column stays flat when growth is linear.
Goal: every target of the 1,000-message spec within 10 s and 500 MB. Then the largest DBC of the
opendbc corpus: `canspec import` and `canspec gen` of every target (goal: both within 5 s), and
each target alone.

  python3 bench/bench_gen.py [--sizes 10 100 300 1000] [--targets c rust] [--work build/bench-gen]
  python3 bench/bench_gen.py --corpus-only --runs 3    (make bench-corpus: the largest DBC alone)
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT / "generator"))
import synth_spec
from canspec.targets import target_names

SIGNALS_PER_MESSAGE = 12
GOAL_SECONDS, GOAL_MB = 10.0, 500.0


def _env(cache: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "generator") + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["CANSPEC_CACHE_DIR"] = str(cache)
    return env


def fresh_cache(work: Path) -> Path:
    """A cache that holds no compiled spec, formatted piece or gen record: every figure is of a spec's
    first run (the user's cache may hold it from an earlier run of this benchmark); an import and the
    gen after it share one, as a user's do. It keeps what depends on canspec alone (the compiled schema
    validator and templates), as every run after canspec's first has it."""
    cache = work / "cache"
    for entry in [*cache.glob("*.pickle"), *cache.glob("gen-*.json"), *cache.glob("format-*")]:
        entry.unlink()
    return cache


CORES = os.cpu_count() or 1


def measured(argv: list[str], cache: Path) -> tuple[float, float, int, float]:
    """Wall seconds, peak MB (this child alone, via wait4), exit code and CPU seconds (user + system, with the
    formatters it ran) of one command. CPU / cores is a floor on the wall time of that work on this machine."""
    start = time.perf_counter()
    proc = subprocess.Popen(argv, env=_env(cache), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    assert proc.stderr is not None
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    if proc.returncode not in (0, 1):
        raise SystemExit(f"bench-gen: {' '.join(argv)} failed ({proc.returncode}):\n{err.decode(errors='replace')}")
    return wall, usage.ru_maxrss / 1024.0, proc.returncode, usage.ru_utime + usage.ru_stime  # ru_maxrss is KiB on Linux


def canspec(*args: str | Path) -> list[str]:
    return [sys.executable, "-m", "canspec", *map(str, args)]


def compile_c(out: Path, work: Path) -> float:
    """Seconds gcc -O2 takes on a .c that includes every generated header."""
    headers = sorted((out / "c").rglob("*.h"))
    main = work / "include_all.c"
    main.write_text("".join(f'#include "{h.name}"\n' for h in headers) + "int main(void) { return 0; }\n", encoding="utf-8")
    dirs = sorted({str(h.parent) for h in headers})
    argv = ["gcc", "-O2", "-std=c99", *(f"-I{d}" for d in dirs), "-c", str(main), "-o", str(work / "include_all.o")]
    start = time.perf_counter()
    proc = subprocess.run(argv, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise SystemExit(f"bench-gen: gcc failed:\n{proc.stderr[-4000:]}")
    return time.perf_counter() - start


def largest_corpus_dbc(work: Path, targets: list[str], runs: int = 1) -> None:
    """Import and generate the largest opendbc DBC `runs` times; print the time and memory of each step
    (other processes on the machine make the wall time vary: the CPU s are the steadier figure)."""
    import opendbc

    largest = max(Path(opendbc.__file__).parent.rglob("*.dbc"), key=lambda p: p.stat().st_size)
    spec, out = work / "corpus-spec", work / "corpus-gen"
    print(f"\nlargest opendbc DBC, {largest.name} ({largest.stat().st_size // 1024} KB), goal: import and gen of every target within 5 s")
    for run in range(1, runs + 1):
        shutil.rmtree(spec, ignore_errors=True)
        shutil.rmtree(out, ignore_errors=True)
        cache = fresh_cache(work)
        imp_wall, imp_mb, _, imp_cpu = measured(canspec("import", largest, "-o", spec), cache)
        gen_wall, gen_mb, _, gen_cpu = measured(canspec("gen", "-q", spec, "-o", out, *(a for t in targets for a in ("-t", t))), cache)
        total = imp_wall + gen_wall
        print(f"  run {run} (empty compiled-spec cache: import fills it, gen reads it): import {imp_wall:.2f} s / {imp_mb:.0f} MB "
              f"({imp_cpu:.2f} CPU s, one process), gen {gen_wall:.2f} s / {gen_mb:.0f} MB "
              f"({gen_cpu:.2f} CPU s: no schedule on {CORES} cores beats {gen_cpu / CORES:.2f} s); together {total:.2f} s "
              f"({'ok' if total <= 5 else 'OVER'})", flush=True)
    edited_gen(spec, out, targets, cache)
    for target in targets:
        wall, mb, _, cpu = measured(canspec("gen", "-q", spec, "-o", work / f"corpus-{target}", "-t", target), fresh_cache(work))
        print(f"  {target:14} {wall:6.2f} s {mb:6.0f} MB {cpu:6.2f} CPU s", flush=True)


def edited_gen(spec: Path, out: Path, targets: list[str], cache: Path) -> None:
    """The gen after an edit of one signal (its range), with the cache the last gen left: the spec is
    compiled again, and only the formatted pieces that hold the edit are formatted again."""
    file = next(f for f in sorted(spec.glob("*.yaml")) if f.name != "canspec.yaml")
    text = file.read_text(encoding="utf-8")
    at = text.find("range: [0, 255]", len(text) // 2)
    if at < 0:
        return
    file.write_text(text[:at] + "range: [0, 254]" + text[at + len("range: [0, 255]") :], encoding="utf-8")
    wall, mb, _, cpu = measured(canspec("gen", "-q", spec, "-o", out, *(a for t in targets for a in ("-t", t))), cache)
    print(f"  gen after editing one signal's range, with the caches the last gen left: {wall:.2f} s / {mb:.0f} MB ({cpu:.2f} CPU s)", flush=True)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[10, 100, 300, 1000])
    ap.add_argument("--targets", nargs="+", default=target_names())
    ap.add_argument("--work", type=Path, default=ROOT / "build" / "bench-gen")
    ap.add_argument("--corpus-only", action="store_true", help="only the largest opendbc DBC's import and gen")
    ap.add_argument("--runs", type=int, default=1, help="import and gen of the largest opendbc DBC this many times")
    args = ap.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    if args.corpus_only:
        largest_corpus_dbc(args.work, args.targets, args.runs)
        return 0
    print(f"{'target':14} {'msgs':>5} | {'wall s':>7} {'ms/msg':>7} | {'peak MB':>8} {'KB/msg':>7} | {'CPU s':>6} {'floor':>6} | goal")
    over: list[str] = []
    for size in args.sizes:
        spec = args.work / f"m{size}"
        synth_spec.synthesize(spec, size, size * SIGNALS_PER_MESSAGE, seed=1)
        for target in args.targets:
            out = args.work / f"m{size}-{target}"
            shutil.rmtree(out, ignore_errors=True)
            wall, mb, _, cpu = measured(canspec("gen", "-q", spec, "-o", out, "-t", target), fresh_cache(args.work))
            ok = wall <= GOAL_SECONDS and mb <= GOAL_MB
            print(f"{target:14} {size:5} | {wall:7.2f} {1000 * wall / size:7.2f} | {mb:8.0f} {1024 * mb / size:7.0f} | {cpu:6.2f} {cpu / CORES:6.2f} | "
                  f"{'ok' if ok else 'OVER'}", flush=True)
            if not ok and size == max(args.sizes):
                over.append(target)
    largest = max(args.sizes)
    spec, out = args.work / f"m{largest}", args.work / f"m{largest}-all"
    shutil.rmtree(out, ignore_errors=True)
    chosen = [arg for t in args.targets for arg in ("-t", t)]
    cache = fresh_cache(args.work)
    wall, mb, _, cpu = measured(canspec("gen", "-q", spec, "-o", out, *chosen), cache)
    print(f"{'all targets':14} {largest:5} | {wall:7.2f} {1000 * wall / largest:7.2f} | {mb:8.0f} {1024 * mb / largest:7.0f} | {cpu:6.2f} {cpu / CORES:6.2f} |")
    print(f"floor = CPU s / {CORES} cores: the work a run did cannot finish sooner on this machine, however it is scheduled")
    check_wall, check_mb, rc, _ = measured(canspec("gen", "-q", spec, "-o", out, "--check", *chosen), cache)  # the record that gen left
    print(f"gen --check on the unchanged {largest}-message output: {check_wall:.2f} s, {check_mb:.0f} MB (exit {rc})")
    if "c" in args.targets:
        print(f"gcc -O2 of the {largest}-message C headers: {compile_c(args.work / f'm{largest}-c', args.work):.2f} s")
    print("over the goal (10 s, 500 MB) at", largest, "messages:", ", ".join(over) or "none")
    largest_corpus_dbc(args.work, args.targets, args.runs)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
