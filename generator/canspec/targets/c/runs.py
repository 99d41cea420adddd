"""C text of the word plans (words.py): the statements that move a run of struct fields between
the frame word and their slots, and the choice of trailing fields copied as bytes instead.

Unpack: `var` = the run's slot word from the frame word `v`, then stored field by field (the
compiler merges the stores), or as one little-endian word on the word path. Pack: the reverse,
and `placed` is the run's bits in the frame word."""

from __future__ import annotations

from dataclasses import dataclass

from canspec.render.literals import c_hex, c_uint
from canspec.targets.c import wordplans
from canspec.targets.c import words as cwords
from canspec.targets.c.signals import CSignal

IMM32 = 0x7FFFFFFF  # x86-64 and/or/test take sign-extended 32-bit immediates: wider masks cost a load
BYTE_COPY_COST = 4  # a byte load and store, both ways
TOP = (1 << cwords.WORD) - 1


@dataclass(frozen=True)
class CRun:
    """C text of one run (see words.Run): the local `var` holds its slot word."""

    run: cwords.Run
    var: str
    unpack_init: str  # value of `var` from the frame word `v`
    unpack_steps: tuple[str, ...]  # statements moving the fields into their slots
    stores: tuple[tuple[str, str], ...]  # (field, value from `var`)
    pack_init: str  # value of `var` from the struct fields (one merged load)
    pack_steps: tuple[str, ...]  # statements moving the fields back to their frame bits
    placed: str  # `var` shifted to its frame bits
    offset: int  # little-endian word path: the run's bytes in the struct
    nbytes: int  # (up to the next run: includes padding, never another run's field)
    size: str  # nbytes as a C literal
    pad_mask: str  # pack: mask clearing padding bytes read with the fields ("" if none)
    extra: str  # pack: a second local for the fields moved by groups beside SWAR steps ("" if none)
    le_value: str  # unpack, word path: the slot word as stored (a signed field sign-extended)


def m(mask: int) -> str:
    return c_hex(mask, 64)


def byte_of(word: str, b: int) -> str:
    return f"(uint8_t){word}" if b == 0 else f"(uint8_t)({word} >> {8 * b})"


def shifted(expr: str, shift: int) -> str:
    """expr << shift (negative: >>), as C text."""
    if shift == 0:
        return expr
    return f"({expr} << {shift})" if shift > 0 else f"({expr} >> {-shift})"


def move(word: str, mask: int, shift: int) -> str:
    """C text of (word & mask) moved by `shift` bits (negative: right). A contiguous mask that
    starts or ends at a word edge, before or after the move, and is too wide for an immediate
    either side, is cut out by two shifts instead (no mask constant)."""
    moved = ((mask << shift) if shift >= 0 else (mask >> -shift)) & TOP
    lo = (mask & -mask).bit_length() - 1
    n = mask.bit_length() - lo
    dest = lo + shift
    if mask == ((1 << n) - 1) << lo and mask > IMM32 and moved > IMM32:
        if lo + n == 64 or dest + n == 64:  # nothing above it before, or nothing left above after
            return shifted(f"({word} >> {lo})" if lo else word, dest)
        if lo == 0 or dest == 0:  # nothing below it before, or nothing left below after
            return shifted(f"({word} << {64 - n - lo})" if 64 - n - lo else word, dest - (64 - n))
    return shifted(f"({word} & {m(mask)})", shift)


def fields_of(sigs: list[CSignal] | tuple[CSignal, ...]) -> list[cwords.Field]:
    return [cwords.Field(s.field, s.start, s.length, s.sig.storage_bits, s.sig.signed, s.needs_check) for s in sigs]


def plan(sigs: list[CSignal] | tuple[CSignal, ...], offsets: dict[str, int], size: int, letter: str, drop: int) -> tuple[CRun, ...]:
    """The runs of these struct fields (at these byte offsets; the struct part is `size` bytes),
    locals named `letter`0, 1, ...; `drop`: frame bits pack leaves out (the checksum byte)."""
    fields = fields_of(sigs)
    by_field = {s.field: s for s in sigs}
    runs = wordplans.plan_runs(fields, [offsets[f.name] for f in fields])
    starts = [offsets[r.fields[0].name] for r in runs] + [size]
    return tuple(_crun(run, f"{letter}{i}", by_field, starts[i], min(8, starts[i + 1] - starts[i]), drop) for i, run in enumerate(runs))


def _sign_extended(var: str, length: int) -> str:
    """int64_t of the `length`-bit two's complement value in the low bits of `var`."""
    if length == 64:
        return f"(int64_t){var}"
    sign = m(1 << (length - 1))
    return f"(int64_t)({var} ^ {sign}) - (int64_t){sign}"


def _field_moves(run: cwords.Run, var: str, by_field: dict[str, CSignal]) -> tuple[list[tuple[str, str]], list[str]]:
    """Per field: its value from the slot word (unpack) and its slot bits from the struct (pack)."""
    stores, loads = [], []
    for f, slot in zip(run.fields, run.slots):
        s = by_field[f.name]
        if f.signed:  # alone in its run, at slot 0
            stores.append((f.name, f"({s.type})({_sign_extended(var, f.length)})"))
            loads.append(f"(uint64_t)src->{f.name}" if f.length == 64 else f"((uint64_t)(int64_t)src->{f.name} & {m((1 << f.length) - 1)})")
        else:
            stores.append((f.name, f"({s.type}){var}" if slot == 0 else f"({s.type})({var} >> {slot})"))
            loads.append(shifted(f"(uint64_t)src->{f.name}", slot))
    return stores, loads


def _crun(run: cwords.Run, var: str, by_field: dict[str, CSignal], offset: int, nbytes: int, drop: int) -> CRun:
    storage = sum(((1 << f.storage) - 1) << s for f, s in zip(run.fields, run.slots))
    # group moves mask their fields; SWAR steps need zeros around them
    pad = "" if run.groups or storage == (1 << (8 * nbytes)) - 1 else f"{var} &= {m(storage)};"
    le_value = var
    signed = next((f for f in run.fields if f.signed), None)
    if signed is not None:  # alone in its run: the struct holds it sign-extended to its type
        pad = "" if signed.length == 64 else f"{var} &= {m((1 << signed.length) - 1)};"
        le_value = var if signed.length == 64 else f"(uint64_t)({_sign_extended(var, signed.length)})"
    stores, loads = _field_moves(run, var, by_field)
    moves = [move("v", g.frame, g.shift) for g in run.groups]
    kept = [g for g in (cwords.Group(g.shift, g.frame & ~drop) for g in run.groups) if g.frame]
    backs = [move(var, ((g.frame << g.shift) if g.shift >= 0 else (g.frame >> -g.shift)) & TOP, -g.shift) for g in kept]
    common = {"run": run, "var": var, "stores": tuple(stores), "pack_init": " | ".join(loads), "le_value": le_value, "offset": offset, "nbytes": nbytes, "size": c_uint(nbytes)}
    if run.swar == 0:
        return CRun(unpack_init=" | ".join(moves), unpack_steps=(), pack_steps=(), placed=" | ".join(backs) or "0u", extra="", pad_mask=pad, **common)  # type: ignore[arg-type]
    ups, downs, extra, placed = _swar_steps(run, var, moves, backs, pad)
    # the padding mask is in the steps
    return CRun(unpack_init=_swar_init(run), unpack_steps=ups, pack_steps=downs, placed=placed, extra=extra, pad_mask="", **common)  # type: ignore[arg-type]


def _swar_init(run: cwords.Run) -> str:
    init = shifted("v", run.base)
    remaining = cwords.WORD - max(0, -run.base)
    needed = run.first != (((1 << remaining) - 1) << max(0, run.base)) & TOP
    return f"{init} & {m(run.first)}" if needed else init


def _swar_steps(run: cwords.Run, var: str, moves: list[str], backs: list[str], pad: str) -> tuple[tuple[str, ...], tuple[str, ...], str, str]:
    """SWAR part: (unpack statements, pack statements, the second local, the run's frame bits)."""
    ups, downs = [], []
    if run.mul is not None:
        ups.append(f"{var} = ({var} * {m(run.mul.up)}) & {m(run.swar_mask)};")
    for st in run.steps:
        if st.simple:
            ups.append(f"{var} = ({var} | ({var} << {st.shift})) & {m(st.after)};")
        else:
            ups.append(f"{var} = ({var} & {m(st.stay)}) | (({var} << {st.shift}) & {m(st.after & ~st.stay)});")
    extra = ""
    placed = shifted(var, -run.base)
    if run.groups:  # the other fields move by groups, from the frame word / before the steps
        ups.append(f"{var} |= {' | '.join(moves)};")
        if backs:
            extra = f"{var}g"
            downs.append(f"{extra} = {' | '.join(backs)};")
            placed = f"{placed} | {extra}"
        downs.append(f"{var} &= {m(run.swar_mask)};")
    elif pad:
        downs.append(pad)
    # Like the steps, the multiplication needs only the fields' bits in the word: the padding
    # mask clears the bytes between fields and the range check the bits above each one.
    if run.mul is not None:
        back = f" & {m(run.mul.back)}" if run.mul.back else ""
        downs.append(f"{var} = (({var} * {m(run.mul.down)}) >> {run.mul.shift}){back};")
    for st in reversed(run.steps):
        if st.simple_back:
            downs.append(f"{var} = ({var} | ({var} >> {st.shift})) & {m(st.before)};")
        else:
            downs.append(f"{var} = ({var} & {m(st.stay)}) | (({var} >> {st.shift}) & {m(st.before & ~st.stay)});")
    return tuple(ups), tuple(downs), extra, placed


def peeled(sigs: tuple[CSignal, ...], offsets: dict[str, int], size: int, checksum: str | None) -> tuple[CSignal, ...]:
    """The struct's trailing whole-byte fields (8 unsigned bits on a byte boundary in a uint8_t)
    whose frame byte is not their struct offset: copying such a byte costs less than moving it
    within the word. With a checksum only the checksum byte itself (pack needs the whole word
    for the XOR). At least one field stays in the word runs."""
    out: list[CSignal] = []
    kept = list(sigs)
    for s in reversed(sigs[1:]):
        whole = s.length == 8 and s.start % 8 == 0 and s.sig.storage_bits == 8 and not s.sig.signed
        if not whole or s.start // 8 == offsets[s.field] or (checksum is not None and s.sig.name != checksum):
            break
        if _words_cost(kept[:-1], offsets) + BYTE_COPY_COST >= _words_cost(kept, offsets):
            break  # it moves (almost) for free with the others
        out.append(kept.pop())
    # The runs' word access must not cover a peeled byte: pack's load would then span unpack's
    # word store and its byte store, which a CPU cannot forward (a stall of ~10 cycles).
    while out and run_end(sigs[: len(sigs) - len(out)], offsets, size) > offsets[out[-1].field]:
        out.pop()
    return tuple(reversed(out))


def _words_cost(sigs: list[CSignal], offsets: dict[str, int]) -> int:
    """The word planner's cost estimate of these struct fields' runs."""
    fields = fields_of(sigs)
    return sum(r.cost for r in wordplans.plan_runs(fields, [offsets[f.name] for f in fields]))


def run_end(sigs: tuple[CSignal, ...], offsets: dict[str, int], size: int) -> int:
    """Where the word runs of these (leading) struct fields end: their last byte, rounded up to
    a whole 2-, 4- or 8-byte access when that stays inside the struct (the bytes past the fields
    are padding or peeled fields, written afterwards)."""
    last = sigs[-1]
    start = offsets[last.field] // 8 * 8  # the runs stay inside 8-byte blocks
    ext = offsets[last.field] + last.sig.storage_bits // 8 - start
    n = 1
    while n < ext:
        n *= 2
    return start + n if start + n <= size else start + ext
