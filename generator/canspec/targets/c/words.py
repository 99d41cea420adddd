"""Word plans for the C target's pack/unpack: what a plan is, what it costs, and what it does
(`unpack_run` / `pack_run` execute one in Python); wordplans.py finds them.

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

WORD = 64
MAX_RUN_FIELDS = 8
ALL_BITS = (1 << WORD) - 1


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


def unpack_run(run: Run, v: int) -> list[int]:
    """Execute the unpack plan on a frame word (what the C does): the fields' raw bit values.
    Used by the tests as an oracle check of the plans."""
    extra = 0
    for g in run.groups:
        extra |= (((v & g.frame) << g.shift) if g.shift >= 0 else ((v & g.frame) >> -g.shift)) & ALL_BITS
    if run.swar == 0:
        return [(extra >> s) & ((1 << f.length) - 1) for f, s in zip(run.fields, run.slots)]
    x = ((v << run.base) if run.base >= 0 else (v >> -run.base)) & ALL_BITS & run.first
    if run.mul is not None:
        x = (x * run.mul.up) & ALL_BITS & run.swar_mask
    for st in run.steps:
        if st.simple:
            x = (x | (x << st.shift)) & ALL_BITS & st.after
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
        x = ((x * run.mul.down) & ALL_BITS) >> run.mul.shift
        if run.mul.back:
            x &= run.mul.back
    for st in reversed(run.steps):
        if st.simple_back:
            x = (x | (x >> st.shift)) & st.before
        else:
            x = (x & st.stay) | ((x >> st.shift) & st.before & ~st.stay)
    return (((x >> run.base) if run.base >= 0 else (x << -run.base)) & ALL_BITS) | extra
