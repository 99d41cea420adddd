"""The search for word plans (words.py says what a plan is): per run of adjacent struct fields,
the SWAR steps, the multiplications, the grouped moves and their mixes that move every field
exactly, and the cheapest split of a struct into runs."""

from __future__ import annotations

from functools import reduce
from math import gcd

from canspec.targets.c.words import ALL_BITS, MAX_RUN_FIELDS, WORD, Field, Group, Mul, Run, Step, run_cost


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
            simple = not ((before << shift) & ALL_BITS & stay) and not (before & moved_to)
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
