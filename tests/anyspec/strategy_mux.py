"""Multiplexed messages for strategy.py: a top-level multiplexer, fields of every frame, pages
selected by single values and ranges (disjoint), fields of different pages laid out over the
same bits (they may overlap), and now and then a page holding a multiplexer of its own
(extended multiplexing). Each page is laid out by `Builder.signals` in the bits the frame's
always-present fields leave free, so byte orders, floats and FD lengths mix in as elsewhere.
Smaller choices: one page of one value, no nesting."""

from __future__ import annotations

from typing import Any

from anyspec.pools import _Names, frame_bits, seq_bit
from anyspec.strategy import Builder

SELECTOR_LENGTHS = (4, 2, 8, 3, 1, 6, 5)


def used_bits(b: Builder, sigs: list[dict[str, Any]]) -> set[int]:
    return {x for s in sigs for x in frame_bits(s["start"], s["len"], s.get("byte_order", b.order))}


def _first_run(bits: int, occ: set[int], order: str) -> tuple[int, int] | None:
    """The first free place in this order's run of bits and the free run from there, or None."""
    first = next((k for k in range(bits) if seq_bit(k, order) not in occ), None)
    if first is None:
        return None
    run = 0
    while first + run < bits and seq_bit(first + run, order) not in occ:
        run += 1
    return seq_bit(first, order), run


def signals(b: Builder, dlc: int) -> list[dict[str, Any]]:
    """A multiplexed message's fields (at least the multiplexer and one page)."""
    bits, names = 8 * dlc, _Names()
    sel = _multiplexer(b, bits, set(), names)
    assert sel is not None  # an empty frame is never multiplexed
    out = [sel]
    if b.p(0.6):  # fields of every frame (counters and checksums too)
        out += b.signals(dlc, used_bits(b, out), names, first_needed=False)
    occ = used_bits(b, out)
    for values in page_values(b, (1 << sel["len"]) - 1):
        out += page(b, dlc, occ, names, sel["name"], values, nested=True)
    return out


def _multiplexer(b: Builder, bits: int, occ: set[int], names: _Names) -> dict[str, Any] | None:
    """An unsigned integer field with factor 1 and offset 0, sometimes with a value table."""
    order = b.field_order()
    found = _first_run(bits, occ, order)
    if found is None:
        return None
    start, run = found
    length = min(run, b.pick(SELECTOR_LENGTHS))
    s: dict[str, Any] = {"name": b.ident(("mode", "page", "selector", "mux_id", "channel"), names, 0.05)}
    b.sig_zh(s)
    s.update({"start": start, "len": length})
    b.orient(s, order)
    if length <= 8 and b.p(0.3):
        s["values"] = b.table_for(0, (1 << length) - 1)
    return s


def page_values(b: Builder, top: int) -> list[list[Any]]:
    """1–3 pages' selector values (single values and inclusive ranges), disjoint between pages."""
    free = set(range(min(top, 255) + 1))
    pages: list[list[Any]] = []
    for _ in range(1 + (b.ch.integer(0, 2) if b.p(0.6) else 0)):
        vals: list[Any] = []
        for _ in range(1 + (1 if b.p(0.3) else 0)):
            if not free:
                break
            at = b.ch.integer(0, min(top, 255))
            v = min(free, key=lambda x: (x - at) % (min(top, 255) + 1))  # the first free value from `at` on
            hi = v
            if b.p(0.3):
                while hi + 1 in free and hi - v < 7:
                    hi += 1
                hi = v + b.ch.integer(0, hi - v)
            free -= set(range(v, hi + 1))
            vals.append(v if hi == v else [v, hi])
        if vals:
            pages.append(vals)
    return pages


def page(b: Builder, dlc: int, occ: set[int], names: _Names, by: str, values: list[Any], nested: bool) -> list[dict[str, Any]]:
    """One page's fields, multiplexed by `by`: laid out afresh in the bits `occ` leaves free, so
    they may overlap another page's; on the top level sometimes a multiplexer with pages of its own."""
    out: list[dict[str, Any]] = []
    sub = _multiplexer(b, 8 * dlc, occ, names) if nested and b.p(0.4) else None
    if sub is not None:
        out.append(sub)
    fields = b.signals(dlc, occ | used_bits(b, out), names, counter=False, checksum=False, first_needed=False)
    out += [s for s in fields if s.get("role") != "reserved"]  # reserved bits belong to every frame
    for s in out:
        s["mux"] = {"by": by, "values": [list(v) if isinstance(v, list) else v for v in values]}
    if sub is not None:
        inner = occ | used_bits(b, out)
        for sub_values in page_values(b, (1 << sub["len"]) - 1):
            out += page(b, dlc, inner, names, sub["name"], sub_values, nested=False)
    return out
