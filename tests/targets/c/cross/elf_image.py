"""What a linked Cortex-M image holds and executes, for `make bench-c-cross` (bench_cross.py):
function sizes, direct calls and prologue frames from arm-none-eabi-nm and -objdump, gcc's
-fstack-usage frames, and the instructions each harness function's callees execute under
`qemu-arm -singlestep -d exec,nochain`."""

from __future__ import annotations

import bisect
import re
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

LIBC = {"memcpy", "memset", "memmove", "memcmp", "strlen", "strcmp", "abort"}


def is_helper(name: str) -> bool:
    """A libgcc / soft-float / libc routine (not code of the library under test)."""
    return name.startswith("__") or name in LIBC


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
