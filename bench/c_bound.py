"""How far any C codec could beat cantools on a spec: an estimate of the fewest x86-64 instructions
per pack+unpack pair (call mode: inside the codec) of each message, beside canspec's and cantools'
(+ the checks its user adds) counts from a `make bench-c*` output.

    python3 bench/c_bound.py SPEC BENCH_OUTPUT     (make bench-c-bound: the second benchmark spec)

Generous to the codec: only the operations every codec needs are counted, each at its cheapest —
the length check; a load per field, its shift or mask where its bits are not at a byte edge, a store
per field on unpack; a compare+branch for the first range-checked field and an OR for each further
one; the frame's stores (one 8-byte store, or for FD a zero fill of 16-byte stores plus a store per
field byte); the checksum fold; a multiplexed message at its smallest page. cantools / bound is then
the best ratio a codec could reach."""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "generator"))
from canspec.pipeline import compile_spec  # noqa: E402

CHECKSUM = 6  # the XOR fold of the loaded word, compare, branch (or fill)
ENTRY = 4  # cmp + jcc on the size, the status, ret


def frame_fields(m: Any) -> tuple[list[Any], int]:
    """The fields of one frame (of a multiplexed message: those of every frame and of its smallest
    page) and the page test's compare+branch."""
    every = [s for s in m.data_signals if s.mux is None]
    pages: dict[str, list[Any]] = {}
    for s in m.data_signals:
        if s.mux is not None:
            pages.setdefault(repr(s.mux), []).append(s)
    return every + (min(pages.values(), key=len) if pages else []), 2 if pages else 0


def _unpack_field(s: Any) -> int:
    whole = all(g.width == 8 for g in s.segments) and s.length == s.storage_bits and (not s.is_big_endian or s.length == 8)
    if whole:
        return 2  # a zero/sign-extending load, a store
    lo = min(s.segments, key=lambda g: g.value_shift)
    hi = max(s.segments, key=lambda g: g.value_shift)
    if s.signed:
        return 4  # load, shl + sar, store
    shift = lo.byte_shift != 0
    mask = not (hi.byte_shift + hi.width == 8 and shift) and not (lo.byte_shift == 0 and s.length == s.storage_bits)
    return 2 + shift + mask


def unpack_bound(m: Any) -> int:
    sigs, branch = frame_fields(m)
    if not sigs:
        return 3  # cmp, sbb, ret
    swap = 1 if any(s.is_big_endian and len(s.segments) > 1 for s in sigs) else 0  # one byte swap serves every Motorola field
    return ENTRY + branch + swap + (CHECKSUM if m.checksum is not None else 0) + sum(_unpack_field(s) for s in sigs)


def _placement(m: Any, sigs: list[Any]) -> int:
    """The cheaper of one frame word (shifts, ORs, a swap, one store) and bytes (a store per touched
    byte, a shift per segment off bit 0, ORs within a byte, the zero fill)."""
    if not sigs:
        return 2 if m.dlc > 8 else 1
    touched: dict[int, list[Any]] = {}
    for s in sigs:
        for g in s.segments:
            touched.setdefault(g.byte, []).append(g)
    stores = sum(1 + sum(1 for g in gs if g.byte_shift or g.value_shift) + len(gs) - 1 for gs in touched.values())
    if m.dlc - len(touched):
        stores += 1 + -(-m.dlc // 16) if m.dlc > 8 else 1  # pxor + 16-byte stores, or one zero store
    if m.dlc > 8:
        return stores
    swap = any(s.is_big_endian for s in sigs) and len(touched) > 1
    word = sum(1 for s in sigs if s.word_shift != 0) + len(sigs) - 1 + swap + 1
    return min(word, stores)


def pack_bound(m: Any) -> int:
    sigs, branch = frame_fields(m)
    sigs = [s for s in sigs if s.role != "checksum"]
    checked = [s for s in sigs if s.length < s.storage_bits]
    signed = sum(1 for s in checked if s.signed)  # masked to its bits
    ranges = 1 + len(checked) if checked else 0
    return ENTRY + branch + ranges + (CHECKSUM if m.checksum is not None else 0) + len(sigs) + signed + _placement(m, sigs)


def bench_counts(path: Path) -> dict[str, tuple[float, float]]:
    """message → (canspec, cantools + user) instructions, from the bench's call-mode like-for-like table."""
    out: dict[str, tuple[float, float]] = {}
    inside = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("[call, like for like") and "canspec Ir" in line:
            inside = True
        elif inside and line.startswith("["):
            break
        elif inside and (row := re.match(r"(\w+)\s+([\d.]+)\s+([\d.]+)\s+[\d.]+x", line)):
            out[row[1]] = (float(row[2]), float(row[3]))
    return out


def main() -> int:
    if len(sys.argv) != 3:
        raise SystemExit(__doc__.splitlines()[3].strip())
    compiled = compile_spec(Path(sys.argv[1]), ["c"])
    if compiled.spec is None or compiled.spec.can is None:
        raise SystemExit(f"{sys.argv[1]}: no CAN protocol")
    counts = bench_counts(Path(sys.argv[2]))
    if not counts:
        raise SystemExit(f"{sys.argv[2]}: no call-mode like-for-like table of make bench-c")
    total = [0.0, 0.0, 0.0]
    print(f"{'message':40} {'bound':>6} {'canspec':>8} {'cantools+user':>14} {'best ratio':>10}")
    for m in compiled.spec.can.messages:
        if m.name in counts:
            bound, (ours, theirs) = unpack_bound(m) + pack_bound(m), counts[m.name]
            total = [total[0] + bound, total[1] + ours, total[2] + theirs]
            print(f"{m.name:40} {bound:6d} {ours:8.0f} {theirs:14.0f} {theirs / bound:9.2f}x")
    print(f"{'overall':40} {total[0]:6.0f} {total[1]:8.0f} {total[2]:14.0f} {total[2] / total[0]:9.2f}x   (canspec: {total[2] / total[1]:.2f}x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
