"""Word plans for the C target's pack/unpack: which struct fields move together, and how.

A classic CAN frame (DLC <= 8, Intel byte order) is one little-endian 64-bit word `v`; every
signal is the bit field [start, start+length) of it. The message struct holds the fields in
their narrowest C types. A *run* is a sequence of adjacent struct fields whose C storage
("slots", natural C alignment) spans at most 8 bytes: unpack computes the run's slot word —
each field's bits moved to its slot's position — and stores it field by field, which the
compiler merges into one word store; pack reads the slot word (one merged load), checks all
of the run's fields with one mask, and moves the fields back.

The moves are SWAR steps: every field travels by d = slot - start (minus a common base
shift); with g the GCD of the d and each d/g written in binary, step k moves the fields
whose d/g has bit k by g * 2^k, all at once: `x = (x | (x << s)) & mask` when no field's
copy can land on another field, else `x = (x & stay) | ((x << s) & moved)`. Runs are chosen
by dynamic programming over a small instruction-count model, so a field only joins a run
when moving it with others is cheaper than moving it alone.

A multiplication can replace all the steps: `x * (2^d1 + 2^d2 + ...)` adds a copy of `x`
moved by each distance at once, and is exact when no two of the copies' bits below bit 64
meet (a sum of distinct powers of two has no carries) and no field's copy lands in another
field's slot. Eight flags spread over eight bytes, or gathered back, take one multiply
instead of three SWAR steps.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import reduce
from math import gcd

WORD = 64
MAX_RUN_FIELDS = 8
_ALL = (1 << WORD) - 1


@dataclass(frozen=True)
class Field:
    """One struct field: its frame bits and its C storage."""

    name: str
    start: int  # first bit in the frame word
    length: int
    storage: int  # bits of its C type: 8 / 16 / 32 / 64
    signed: bool
    check: bool  # a raw value may not fit `length` bits: pack must range-check it


@dataclass(frozen=True)
class Step:
    """Unpack direction: fields in `movers` go up by `shift`. `before`/`after` are the bit
    masks of all fields of the run before and after the step; `stay` those that stay put."""

    shift: int
    movers: tuple[int, ...]  # indices into the run's fields
    before: int
    after: int
    stay: int
    simple: bool  # `x = (x | (x << shift)) & after` is exact
    simple_back: bool  # `x = (x | (x >> shift)) & before` is exact (pack direction)


@dataclass(frozen=True)
class Group:
    """Fields that travel by the same distance: slot word |= (v & frame) << shift."""

    shift: int  # negative: right shift
    frame: int  # mask of their bits in the frame word


@dataclass(frozen=True)
class Mul:
    """The SWAR part's moves as multiplications. Unpack: x = (x * up) & final. Pack:
    x = ((x * down) >> shift) & back (back 0: no copy survives that needs masking)."""

    up: int
    down: int
    shift: int
    back: int


@dataclass(frozen=True)
class Run:
    fields: tuple[Field, ...]
    slots: tuple[int, ...]  # bit offset of each field's slot in the run word
    base: int  # SWAR: unpack starts from v << base (negative: v >> -base)
    steps: tuple[Step, ...]
    first: int  # SWAR: mask of the fields right after the base shift
    final: int  # mask of the fields in their slots
    check: int  # pack: slot bits that must be 0 (fields wider than their bits)
    groups: tuple[Group, ...] = ()  # the other fields: one move per distinct distance
    swar: int = -1  # mask of the slots the SWAR steps fill (-1: all of `final`; 0: no steps)
    mul: Mul | None = None  # the SWAR part moves by multiplications (steps is then empty)

    @property
    def swar_mask(self) -> int:
        return self.final if self.swar < 0 else self.swar

    @property
    def cost(self) -> int:
        return run_cost(self)


def natural_offsets(storage: list[int]) -> list[int]:
    """Byte offsets of struct members of these sizes under natural alignment (what every C ABI
    this targets does for fixed-width integers)."""
    out, at = [], 0
    for size in storage:
        nbytes = size // 8
        at = (at + nbytes - 1) // nbytes * nbytes
        out.append(at)
        at += nbytes
    return out


def struct_size(storage: list[int]) -> int:
    """sizeof of a struct of these members under natural alignment."""
    if not storage:
        return 1
    offsets = natural_offsets(storage)
    align = max(storage) // 8
    end = offsets[-1] + storage[-1] // 8
    return (end + align - 1) // align * align


def _bits(pos: int, length: int) -> int:
    return ((1 << length) - 1) << pos


def _occupied(fields: tuple[Field, ...], pos: list[int]) -> int | None:
    """Mask of the fields at these positions, or None if one leaves the word or two overlap."""
    mask = 0
    for f, p in zip(fields, pos):
        if p < 0 or p + f.length > WORD:
            return None
        bits = _bits(p, f.length)
        if mask & bits:
            return None
        mask |= bits
    return mask


def _check_mask(fields: tuple[Field, ...], slots: tuple[int, ...]) -> int:
    """Pack: the slot bits above each checked field's width, which must be 0."""
    return sum(_bits(s + f.length, f.storage - f.length) for f, s in zip(fields, slots) if f.check)


def _plan(fields: tuple[Field, ...], slots: tuple[int, ...], descending: bool) -> Run | None:
    base = min(s - f.start for f, s in zip(fields, slots))
    pos = [f.start + base for f in fields]
    first = _occupied(fields, pos)
    if first is None:
        return None
    deltas = [s - p for s, p in zip(slots, pos)]
    g = reduce(gcd, deltas, 0)
    steps = []
    if g:
        bits = sorted({k for d in deltas for k in range((d // g).bit_length()) if (d // g) >> k & 1}, reverse=descending)
        for k in bits:
            shift = g << k
            movers = tuple(i for i, d in enumerate(deltas) if (d // g) >> k & 1)
            new = [p + shift if i in movers else p for i, p in enumerate(pos)]
            before, after = _occupied(fields, pos), _occupied(fields, new)
            if before is None or after is None:
                return None
            stay = sum(_bits(p, f.length) for i, (f, p) in enumerate(zip(fields, pos)) if i not in movers)
            moved_from = before & ~stay
            moved_to = after & ~stay
            # (x | x << s) & after: a stayer must not receive a shifted copy, a mover's slot
            # must be empty before. Backwards: (x | x >> s) & before, mirrored.
            simple = not ((before << shift) & _ALL & stay) and not (before & moved_to)
            simple_back = not ((after >> shift) & stay) and not (after & moved_from)
            steps.append(Step(shift, movers, before, after, stay, simple, simple_back))
            pos = new
    final = _occupied(fields, pos)
    if final is None or pos != list(slots):
        return None
    check = _check_mask(fields, slots)
    return Run(fields, slots, base, tuple(steps), first, final, check)


def _exact_product(fields: tuple[Field, ...], src: list[int], own: list[int], shifts: list[int], window: int) -> bool | None:
    """Whether multiplying the word holding these fields (at bit positions `src`) by the sum
    of 2^shift over `shifts` is exact: no two copies' bits below bit 64 meet (so no carries)
    and no field's copy by another field's shift lands on a field's own destination. Returns
    None if not exact, else whether any such stray copy lands at or above `window` (the result
    must then be masked)."""
    seen: set[int] = set()
    dest: set[int] = set()
    for f, p, d in zip(fields, src, own):
        dest.update(range(p + d, p + d + f.length))
    stray = False
    for f, p, d in zip(fields, src, own):
        for b in range(p, p + f.length):
            for s in shifts:
                t = b + s
                if t >= WORD:
                    continue
                if t in seen:
                    return None
                seen.add(t)
                if s != d and t >= window:
                    if t in dest:
                        return None
                    stray = True
    return stray


def _mul_plan(fields: tuple[Field, ...], slots: tuple[int, ...]) -> Run | None:
    """All fields moved by one multiplication each way, if that is exact."""
    base = min(s - f.start for f, s in zip(fields, slots))
    pos = [f.start + base for f in fields]
    first = _occupied(fields, pos)
    final = _occupied(fields, list(slots))
    if first is None or final is None:
        return None
    deltas = [s - p for s, p in zip(slots, pos)]
    shifts = sorted(set(deltas))
    top = shifts[-1]
    if len(shifts) < 2 or max(p + f.length for f, p in zip(fields, pos)) + top > WORD:
        return None
    if _exact_product(fields, pos, deltas, shifts, 0) is None:
        return None
    # Pack: every field goes up by top - d (to its frame position + top), then down by top.
    back = _exact_product(fields, list(slots), [top - d for d in deltas], [top - d for d in shifts], top)
    if back is None:
        return None
    mul = Mul(sum(1 << d for d in shifts), sum(1 << (top - d) for d in shifts), top, first if back else 0)
    check = _check_mask(fields, slots)
    return Run(fields, slots, base, (), first, final, check, mul=mul)


def _groups(fields: list[Field], slots: list[int]) -> tuple[Group, ...]:
    by_shift: dict[int, int] = {}
    for f, s in zip(fields, slots):
        by_shift[s - f.start] = by_shift.get(s - f.start, 0) | _bits(f.start, f.length)
    return tuple(Group(d, m) for d, m in sorted(by_shift.items()))


def _grouped(fields: tuple[Field, ...], slots: tuple[int, ...]) -> Run | None:
    """Plan that moves the fields of each distinct distance together (always possible)."""
    final = _occupied(fields, list(slots))
    if final is None:
        return None
    check = _check_mask(fields, slots)
    return Run(fields, slots, 0, (), 0, final, check, _groups(list(fields), list(slots)), 0)


def _hybrids(fields: tuple[Field, ...], slots: tuple[int, ...]) -> list[Run]:
    """SWAR steps for the fields whose distances form a regular pattern (distance = b + k*c),
    grouped moves for the rest."""
    final = _occupied(fields, list(slots))
    if final is None:
        return []
    check = _check_mask(fields, slots)
    deltas = [s - f.start for f, s in zip(fields, slots)]
    subsets = set()
    for b in deltas:
        for c in {d - b for d in deltas if d > b}:
            subset = tuple(i for i, d in enumerate(deltas) if d >= b and (d - b) % c == 0)
            if 2 <= len(subset) < len(fields):
                subsets.add(subset)
    out = []
    for subset in sorted(subsets):
        rest = [i for i in range(len(fields)) if i not in subset]
        sub_fields, sub_slots = tuple(fields[i] for i in subset), tuple(slots[i] for i in subset)
        parts = [_plan(sub_fields, sub_slots, descending) for descending in (True, False)] + [_mul_plan(sub_fields, sub_slots)]
        for part in parts:
            if part is None:
                continue
            groups = _groups([fields[i] for i in rest], [slots[i] for i in rest])
            out.append(Run(fields, slots, part.base, part.steps, part.first, final, check, groups, part.final, part.mul))
    return out


def _imm_cost(mask: int) -> int:
    """x86-64/ARM: a mask that is not a small immediate costs one more instruction."""
    return 0 if mask <= 0xFFFFFFFF else 1


def _mul_imm_cost(factor: int) -> int:
    """x86-64 imul takes a sign-extended 32-bit immediate; a wider factor is loaded first."""
    return 0 if factor <= 0x7FFFFFFF else 1


def run_cost(run: Run) -> int:
    """Rough instruction count of unpack + pack of the run (moves, masks, one merged access
    per run) — only used to compare plans of the same fields."""
    n = sum(2 * (3 + _imm_cost(g.frame)) - (2 if not g.shift else 0) for g in run.groups)
    if run.swar == 0:
        return n + 2 + (1 + _imm_cost(run.check) if run.check else 0)
    if run.groups:
        n += 4 + _imm_cost(run.swar_mask)  # combine both parts, both ways; isolate the SWAR part
    n += 2 + _imm_cost(run.first)  # base shift + mask
    if run.mul is not None:
        n += 2 + _mul_imm_cost(run.mul.up) + _imm_cost(run.swar_mask)  # multiply, mask
        n += 2 + _mul_imm_cost(run.mul.down) + (1 + _imm_cost(run.mul.back) if run.mul.back else 0)  # multiply, shift
    for st in run.steps:
        n += (3 if st.simple else 4) + _imm_cost(st.after)
        n += (3 if st.simple_back else 4) + _imm_cost(st.before)
    n += 2  # pack: shift back + OR into the frame
    n += 2  # merged store (unpack) and merged load (pack)
    if run.check:
        n += 1 + _imm_cost(run.check)
    return n


def plan_run(fields: tuple[Field, ...], offsets: tuple[int, ...]) -> Run | None:
    """The cheaper valid plan for these adjacent struct fields at these byte offsets, if any."""
    if any(f.signed for f in fields) and len(fields) > 1:
        return None  # signed fields need sign extension: moved alone
    slots = tuple(8 * (o - offsets[0]) for o in offsets)
    if slots[-1] + fields[-1].storage > WORD:
        return None
    plans = [p for p in (_plan(fields, slots, True), _plan(fields, slots, False)) if p is not None]
    if not any(f.signed for f in fields):
        plans += [p for p in (_mul_plan(fields, slots),) if p is not None]
    if not any(f.signed for f in fields):
        plans += [p for p in (_grouped(fields, slots),) if p is not None]
        plans += _hybrids(fields, slots)
    # a tie goes to the multiplication: one instruction of latency chain instead of several
    return min(plans, key=lambda p: (run_cost(p), p.mul is None)) if plans else None


def plan_runs(fields: list[Field], offsets: list[int]) -> tuple[Run, ...]:
    """Split these struct fields (at these byte offsets in the struct, in struct order) into
    runs: one per 8-byte block of the struct where possible — unpack then writes each block
    with one store and pack reads it with one load of the same size (a load that spans
    several smaller stores cannot be forwarded from them and stalls) — else runs of least
    total cost (dynamic programming)."""
    blocks: dict[int, list[int]] = {}
    for i, o in enumerate(offsets):
        blocks.setdefault(o // 8, []).append(i)
    out: list[Run] = []
    for idx in blocks.values():
        whole = plan_run(tuple(fields[i] for i in idx), tuple(offsets[i] for i in idx))
        out.extend((whole,) if whole is not None else _plan_dp([fields[i] for i in idx], [offsets[i] for i in idx]))
    return tuple(out)


def _plan_dp(fields: list[Field], offsets: list[int]) -> tuple[Run, ...]:
    """Runs of least total cost (dynamic programming)."""
    best: list[tuple[int, tuple[Run, ...]] | None] = [(0, ())] + [None] * len(fields)
    for end in range(1, len(fields) + 1):
        for begin in range(max(0, end - MAX_RUN_FIELDS), end):
            prev = best[begin]
            if prev is None:
                continue
            if offsets[begin] // 8 != offsets[end - 1] // 8:
                continue  # runs stay inside one 8-byte block of the struct
            run = plan_run(tuple(fields[begin:end]), tuple(offsets[begin:end]))
            if run is None:
                continue
            whole = (begin == 0 or offsets[begin - 1] // 8 != offsets[begin] // 8) and (
                end == len(fields) or offsets[end] // 8 != offsets[end - 1] // 8)
            # A run that fills its block is stored as one word. Otherwise compilers merge the
            # block's byte stores from several runs by shifting each byte into place.
            cand = (prev[0] + run.cost + (0 if whole else 2 * len(run.fields)), (*prev[1], run))
            cur = best[end]
            if cur is None or cand[0] < cur[0]:
                best[end] = cand
    result = best[len(fields)]
    if result is None:  # every single field is a valid run, so this cannot happen
        raise ValueError("no run plan")
    return result[1]


def unpack_run(run: Run, v: int) -> list[int]:
    """Execute the unpack plan on a frame word (what the C does): the fields' raw bit values.
    Used by the tests as an oracle check of the plans."""
    extra = 0
    for g in run.groups:
        extra |= (((v & g.frame) << g.shift) if g.shift >= 0 else ((v & g.frame) >> -g.shift)) & _ALL
    if run.swar == 0:
        return [(extra >> s) & ((1 << f.length) - 1) for f, s in zip(run.fields, run.slots)]
    x = ((v << run.base) if run.base >= 0 else (v >> -run.base)) & _ALL & run.first
    if run.mul is not None:
        x = (x * run.mul.up) & _ALL & run.swar_mask
    for st in run.steps:
        if st.simple:
            x = (x | (x << st.shift)) & _ALL & st.after
        else:
            x = (x & st.stay) | ((x << st.shift) & st.after & ~st.stay)
    x |= extra
    return [(x >> s) & ((1 << f.length) - 1) for f, s in zip(run.fields, run.slots)]


def pack_run(run: Run, values: list[int]) -> int:
    """Execute the pack plan: the frame bits of these field values (in range)."""
    x = sum(val << s for val, s in zip(values, run.slots))
    extra = 0
    for g in run.groups:
        extra |= (x >> g.shift) & g.frame if g.shift >= 0 else (x << -g.shift) & g.frame
    if run.swar == 0:
        return extra
    x &= run.swar_mask
    if run.mul is not None:
        x = ((x * run.mul.down) & _ALL) >> run.mul.shift
        if run.mul.back:
            x &= run.mul.back
    for st in reversed(run.steps):
        if st.simple_back:
            x = (x | (x >> st.shift)) & st.before
        else:
            x = (x & st.stay) | ((x >> st.shift) & st.before & ~st.stay)
    return (((x >> run.base) if run.base >= 0 else (x << -run.base)) & _ALL) | extra
