"""The measurements of `make bench-c` (bench.py): instructions per pack+unpack pair from
callgrind, with the harness loop's own instructions subtracted in call mode, and the code size
of an object's symbols and of its .text."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path


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
    return sum(int(line.split()[1]) for line in out.splitlines() if line.startswith(".text"))


CALLGRIND_ITERS = 4096


def _callgrind(out: Path, inclusive: bool) -> dict[str, float]:
    """`lib:message` -> instructions per pair of its harness loop function (with everything it
    calls where `inclusive`, its own instructions alone where not)."""
    text = subprocess.run(["callgrind_annotate", f"--inclusive={'yes' if inclusive else 'no'}", "--threshold=100", str(out)],
                          check=True, capture_output=True, text=True).stdout
    ir: dict[str, float] = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+)\s.*\b(canspec|cantools)_run_(\w+)\b", line)
        if m:
            ir[f"{m.group(2)}:{m.group(3)}"] = int(m.group(1).replace(",", "")) / CALLGRIND_ITERS
    return ir


def _harness_loop(loop: dict[str, float], names: list[str], like_for_like: bool) -> tuple[dict[str, float], str]:
    """Per message the harness loop's own instructions (canspec's loop function: it runs nothing
    else), and how it is shared. Without the like-for-like checks cantools' loop is the same code:
    where it is not, the subtraction would be unfair and this says so."""
    own = {n: loop.get(f"canspec:{n}", 0.0) for n in names}
    if like_for_like:
        return own, "cantools' loop also holds the checks its user adds: counted on its side"
    differ = [n for n in names if loop.get(f"cantools:{n}") != own[n]]
    return own, (f"HARNESS LOOPS DIFFER on {differ}: the codec-only counts are not comparable" if differ
                 else "the same on both sides")


def instruction_counts(exe: Path, mode: str, names: list[str]) -> bool:
    """Instructions per pack+unpack pair, from callgrind: independent of load. In call mode, as on
    the ARM cores (bench_cross.py), the instructions of the codec alone: the harness loop (its
    indexing, call set-up and consumption of the results) is subtracted from both sides, and what a
    cantools user adds around the calls (the like-for-like checks) stays on cantools' side; the
    totals with the loop follow. In inline mode the codec is compiled into the loop, which is
    included. False where the counts could not be made."""
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        print(f"\n[{mode}] instruction counts: valgrind is needed (apt-get install valgrind; `make setup` installs it)")
        return False
    out = exe.with_suffix(".callgrind")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(exe), str(CALLGRIND_ITERS)],
                   check=True, capture_output=True)
    ir = _callgrind(out, inclusive=True)
    call = mode.startswith("call")
    loops, shared = _harness_loop(_callgrind(out, inclusive=False), names, mode != "call") if call else ({}, "")
    what = "inside the codec: the harness loop excluded, as on the ARM cores" if call else "loop included: the codec is inlined into it"
    print(f"\n[{mode}] {'message':<21} {'canspec Ir':>12} {'cantools Ir':>12} {'ratio':>8}   (instructions per pack+unpack pair, callgrind; {what})")
    ta = tb = tl = 0.0
    fewer = 0
    for n in names:
        harness = loops.get(n, 0.0)
        a, b = ir.get(f"canspec:{n}", 0) - harness, ir.get(f"cantools:{n}", 0) - harness
        ta, tb, tl = ta + a, tb + b, tl + harness
        fewer += a <= b
        print(f"{n:<28} {a:12.1f} {b:12.1f} {b / a if a else 0:7.2f}x")
    print(f"{'overall (sum)':<28} {ta:12.1f} {tb:12.1f} {tb / ta if ta else 0:7.2f}x")
    if call:
        print(f"{'with the harness loop':<28} {ta + tl:12.1f} {tb + tl:12.1f} {(tb + tl) / (ta + tl) if ta else 0:7.2f}x"
              f"   (the loop: {tl / len(names):.1f} per pair, {shared})")
    print(f"[{mode}] messages where canspec executes at most as many instructions: {fewer} of {len(names)}")
    return "DIFFER" not in shared
