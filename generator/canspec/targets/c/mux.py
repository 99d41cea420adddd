"""Pack and unpack of a multiplexed message (ir/mux.py), in every form codec.py and codec64.py write.

The struct holds every field of every page; the multiplexers' values in it say which pages a frame
holds. Fields of different pages may share bits, so no one set of byte pieces serves every frame:

- pack branches on the multiplexers (top-level first, then the multiplexers a page holds) down to
  one set of present fields, and packs that set as a plain message (codec.py / codec64.py, each
  leaf in its own block with its own locals; a multiplexer whose branch holds only values of its
  bits is not checked again: MISRA C:2012 rule 14.3). The other pages' fields are neither checked
  nor written. A multiplexer value no page holds leaves only the fields of every frame. Where
  the pages of a message's one multiplexer lay out their fields alike (a bank of cells), the byte
  forms pick a pointer per field by page and pack once (_shared_pages);
- unpack writes the fields of every frame (and checks the checksum over the whole frame), then
  branches on the multiplexer values just written and writes the selected page's fields the same
  way. Every other field of *dst keeps its value (cantools #193 wipes them).

`<field>_is_present()` asks the same conditions of a struct (CPresence).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, replace

from canspec import ir
from canspec.ir.mux import Ranges, ranges_of
from canspec.render.literals import C
from canspec.targets.c.codec import CCodec, build_codec, unpack_parts
from canspec.targets.c.codec64 import build_codec64, unpack_parts64, word_order
from canspec.targets.c.signals import CSignal


@dataclass(frozen=True)
class CPresence:
    """`fn(const T *m)`: whether field `s` is present in a frame holding m's multiplexer values."""

    s: CSignal
    fn: str
    test: str  # over `m->`
    where: str  # the condition as the spec says it, for the comment


def _literal(s: CSignal, value: int) -> str:
    bits = s.sig.storage_bits
    return C.integer(value, bits) if s.sig.signed else C.unsigned(value, bits)


def holds(s: CSignal, ranges: Ranges, access: str, excluded: Ranges = ()) -> str:
    """C condition: the multiplexer `s` (read as `access` + field) holds one of `ranges`, where it
    is known to hold none of `excluded` (the earlier branches' values); "" when every other value
    of its type does. A bound is left out where every value beyond it is excluded or beyond its
    type (gcc -Wtype-limits; MISRA C:2012 rule 14.3: cppcheck knows what the earlier branches
    excluded). Not parenthesised as a whole (an `if` adds them; clang -Wparentheses-equality)."""
    field, bits = f"{access}{s.field}", s.sig.storage_bits
    low, high = (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1) if s.sig.signed else (0, 2**bits - 1)
    gone = ranges_of([*excluded, *ranges])  # what no other value is: these and the excluded ones

    def beyond(lo: int, hi: int) -> bool:  # every value of [lo, hi] excluded (or none there)
        return lo > hi or any(a <= lo and hi <= b for a, b in gone)

    terms = []
    for lo, hi in ranges:
        ends = [f"({field} >= {_literal(s, lo)})"] if not beyond(low, lo - 1) else []
        ends += [f"({field} <= {_literal(s, hi)})"] if not beyond(hi + 1, high) else []
        if lo == hi and ends:
            ends = [f"({field} == {_literal(s, lo)})"]
        if not ends:
            return ""
        terms.append(ends[0][1:-1] if len(ends) == 1 else " && ".join(ends))
    return terms[0] if len(terms) == 1 else " || ".join(f"({t})" for t in terms)


Step = Callable[[tuple[CSignal, ...], tuple[CSignal, ...]], list[str]]  # (fields present, fields a branch adds) -> statements


def _branches(msg: ir.Message, sigs: tuple[CSignal, ...], present: frozenset[str], decided: frozenset[str], access: str, step: Step,
              refuse: tuple[str, ...] = ()) -> list[str]:
    """The statements for the frames whose fields include `present`: an if / else if / else on
    the first multiplexer among them not decided yet, each branch starting with what `step` writes
    for the fields its page adds; at the bottom (every multiplexer decided) what `step` writes for
    no added field. The fields `step` gets are those of `sigs`, a multiplexer inside one of its
    pages' branches marked as known to fit its bits. `refuse` (pack): the else of a multiplexer whose
    pages hold every value its bits carry, reached only by a value that does not fit them."""
    def of(names: frozenset[str] | tuple[str, ...]) -> tuple[CSignal, ...]:
        return tuple(s for s in sigs if s.sig.name in names)

    by = next((s for s in sigs if s.sig.is_multiplexer and s.sig.name in present and s.sig.name not in decided), None)
    if by is None:
        return step(of(present), ())
    inside = tuple(replace(s, range_known=True) if s is by else s for s in sigs)
    out: list[str] = []
    excluded: Ranges = ()
    for group in (g for g in msg.mux_groups if g.multiplexer == by.sig.name):
        test = holds(by, group.ranges, access, excluded)
        excluded = ranges_of([*excluded, *group.ranges])
        inner = [*step(of(present), of(group.signals)), *_branches(msg, inside, present | set(group.signals), decided | {by.sig.name}, access, step, refuse)]
        if not test:  # every value left: the last branch
            return [*out, "} else {", *inner, "}"] if out else ["{", *inner, "}"]
        out += [f"{'} else if' if out else 'if'} ({test}) {{", *inner]
    if refuse and _fills_bits(by, excluded):  # its range check there would always fail (MISRA C:2012 rule 14.3)
        return [*out, "} else {", *refuse, "}"]
    rest = _branches(msg, sigs, present, decided | {by.sig.name}, access, step, refuse)
    return [*out, "} else {", *(rest or ["/* no page: the fields of every frame only */"]), "}"]


def _fills_bits(by: CSignal, ranges: Ranges) -> bool:
    """The pages' values `ranges` hold every value the multiplexer's bits carry."""
    return any(lo <= by.sig.raw_type_min and by.sig.raw_type_max <= hi for lo, hi in ranges_of(list(ranges)))


def _every_frame(sigs: tuple[CSignal, ...]) -> frozenset[str]:
    return frozenset(s.sig.name for s in sigs if s.sig.mux is None)


def _layout(page: tuple[CSignal, ...]) -> tuple[object, ...]:
    return tuple((s.sig.segments, s.sig.storage_bits, s.sig.signed, s.length, s.type, s.sig.role, s.checked) for s in page)


def _shared_pages(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, ok: str, words: bool) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
    """(locals, statements): the byte form's pack of a message whose one multiplexer's pages all
    lay out their fields alike (same bits, types and checks, none a float or a multiplexer) and
    take no branch below it: the page picks a pointer per field (`page_f<i>`), then one pack
    serves every page, with the fields read through them (a value no page holds packs the fields
    of every frame and returns `ok`); None for any other message."""
    muxes = [s for s in sigs if s.sig.is_multiplexer]
    if len(muxes) != 1 or muxes[0].sig.mux is not None:
        return None
    by = muxes[0]
    groups = [g for g in msg.mux_groups if g.multiplexer == by.sig.name]
    pages = [tuple(s for s in sigs if s.sig.name in g.signals) for g in groups]
    if len(pages) < 2 or not pages[0] or any(s.sig.is_multiplexer or s.float is not None for p in pages for s in p):
        return None
    if len({_layout(p) for p in pages}) != 1:
        return None
    tests: list[str] = []
    excluded: Ranges = ()
    for g in groups:
        tests.append(holds(by, g.ranges, "src->", excluded))
        excluded = ranges_of([*excluded, *g.ranges])
    if not all(tests[:-1]):
        return None
    inside = tuple(replace(s, range_known=True) if s is by else s for s in sigs)
    first = {s.sig.name for s in pages[0]}
    present = tuple(s for s in inside if s.sig.mux is None or s.sig.name in first)
    body = list(build_codec(msg, present, err, words).pack)
    for i, s in enumerate(pages[0]):
        pattern = re.compile(rf"src->{re.escape(s.field)}(?!\w)")
        body = [pattern.sub(f"(*page_f{i})", line) for line in body]
    locals_ = tuple(f"const {s.type} *page_f{i};" for i, s in enumerate(pages[0]))
    pick: list[str] = []
    for k, (test, page) in enumerate(zip(tests, pages)):
        pick.append(f"if ({test}) {{" if k == 0 else f"}} else if ({test}) {{" if test else "} else {")
        pick += [f"page_f{i} = &src->{s.field};" for i, s in enumerate(page)]
    if tests[-1] and _fills_bits(by, excluded):  # a value beyond the multiplexer's bits
        pick += ["} else {", f"return {err};"]
    elif tests[-1]:  # values no page holds: the fields of every frame, and done
        rest = tuple(s for s in sigs if s.sig.mux is None)  # the multiplexer checked: no page's value
        pick += ["} else {", *build_codec(msg, rest, err, words).pack, f"return {ok};"]
    return locals_, (*pick, "}", *body)


def _pack(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, wide: bool, words: bool = False) -> tuple[str, ...]:
    def leaf(present: tuple[CSignal, ...], added: tuple[CSignal, ...]) -> list[str]:
        if added:  # a branch: its leaves pack
            return []
        codec = build_codec(msg, present, err, words)
        form = (build_codec64(msg, present, err, codec) or codec) if wide else codec
        return [*form.pack_locals, *form.pack]

    return tuple(_branches(msg, sigs, _every_frame(sigs), frozenset(), "src->", leaf, (f"return {err};",)))


def _unpack(msg: ir.Message, sigs: tuple[CSignal, ...], wide: bool) -> tuple[tuple[str, ...], tuple[str, ...]]:
    declared: list[str] = []

    def part(fields: tuple[CSignal, ...], checksum: bool) -> list[str]:
        found = unpack_parts64(fields, msg.dlc, checksum, word_order(fields)) if wide and fields else None
        locals_, body = found or unpack_parts(fields, msg.dlc, checksum)
        declared.extend(line for line in locals_ if line not in declared)
        return list(body)

    every = tuple(s for s in sigs if s.sig.mux is None)
    body = [*part(every, msg.checksum is not None), *_branches(msg, sigs, _every_frame(sigs), frozenset(), "dst->", lambda _, added: part(added, False))]
    return tuple(declared), tuple(body)


def build_mux_codecs(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, ok: str) -> tuple[CCodec, CCodec | None]:
    """The byte form (every core) and the form of <PREFIX>_STRATEGY 3 (None where there is none)."""
    byte_locals, byte_unpack = _unpack(msg, sigs, False)
    shared = _shared_pages(msg, sigs, err, ok, False) if msg.dlc else None
    pack_locals, pack = shared or ((), _pack(msg, sigs, err, False))
    bytewise = CCodec(pack, byte_locals, byte_unpack, pack_locals)
    if not msg.dlc or not msg.is_classic_length:
        return bytewise, None
    word_locals, word_unpack = _unpack(msg, sigs, True)
    return bytewise, CCodec(_pack(msg, sigs, err, True), word_locals, word_unpack)


def presence(msg: ir.Message, sigs: tuple[CSignal, ...]) -> tuple[CPresence, ...]:
    """The presence test of each field some multiplexer selects."""
    by_name = {s.sig.name: s for s in sigs}
    out = []
    for s in sigs:
        chain = msg.mux_chain(s.sig)
        if not chain:
            continue
        tests = [t for c in chain if (t := holds(by_name[c.by], c.ranges, "m->"))]
        where = " and ".join(f"{c.by} in {_ranges_text(c.ranges)}" for c in chain)
        test = tests[0] if len(tests) == 1 else " && ".join(f"({t})" for t in tests)
        out.append(CPresence(s, f"{s.fn}_is_present", test or "true", where))
    return tuple(out)


def _ranges_text(ranges: Ranges) -> str:
    return "{" + ", ".join(str(lo) if lo == hi else f"{lo}..{hi}" for lo, hi in ranges) + "}"


def mux_words(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec, ok: str) -> CCodec | None:
    """The pack of <PREFIX>_STRATEGY 2 (codec.word_zeros in each leaf), None where it is the byte form's."""
    shared = _shared_pages(msg, sigs, err, ok, True) if msg.dlc else None
    locals_, pack = shared or ((), _pack(msg, sigs, err, False, words=True) if msg.dlc else ())
    return None if (locals_, pack) == (bytewise.pack_locals, bytewise.pack) else replace(bytewise, pack=pack, pack_locals=locals_)
