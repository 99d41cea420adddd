"""Multiplexing: a field present only while another field of its message, its multiplexer, holds
one of some raw values (a page). A multiplexer may itself be multiplexed (extended multiplexing).
The spec rules (spec/validate_mux.py) and the IR build share the value arithmetic here; targets
read the results (Signal.mux, Message.mux_groups, Message.present) and never recompute them."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

Ranges = tuple[tuple[int, int], ...]  # inclusive [first, last] runs of raw values, sorted, disjoint, not adjacent


def ranges_of(values: Iterable[int | Iterable[int]]) -> Ranges:
    """The spec's `values` (single values and [first, last] pairs) as merged runs."""
    runs = sorted((v, v) if isinstance(v, int) else tuple(v) for v in values)  # type: ignore[misc]
    merged: list[list[int]] = []
    for lo, hi in runs:
        if merged and lo <= merged[-1][1] + 1:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return tuple((lo, hi) for lo, hi in merged)


def ranges_text(ranges: Ranges) -> str:
    """`1, 4…6`: values as every target's text writes them, single values and inclusive runs."""
    return ", ".join(str(lo) if lo == hi else f"{lo}…{hi}" for lo, hi in ranges)


def holds(ranges: Ranges, value: int) -> bool:
    return any(lo <= value <= hi for lo, hi in ranges)


def disjoint(a: Ranges, b: Ranges) -> bool:
    return not any(alo <= bhi and blo <= ahi for alo, ahi in a for blo, bhi in b)


def exclusive(a: Mapping[str, Ranges], b: Mapping[str, Ranges]) -> bool:
    """Whether two fields with these presence conditions (multiplexer → values, along the whole
    chain of multiplexers) are never present together: some multiplexer needs disjoint values."""
    return any(name in b and disjoint(ranges, b[name]) for name, ranges in a.items())


def conditions(parent: Mapping[str, tuple[str, Ranges]]) -> dict[str, dict[str, Ranges]]:
    """Each multiplexed field's presence condition over its whole chain: field → {multiplexer →
    values}. `parent`: field → (its multiplexer, values). A chain that loops or names an unknown
    field stops there (the spec rules report it)."""
    out: dict[str, dict[str, Ranges]] = {}
    for name in parent:
        chain: dict[str, Ranges] = {}
        at = name
        while at in parent and parent[at][0] not in chain and parent[at][0] != name:
            by, ranges = parent[at]
            chain[by] = ranges
            at = by
        out[name] = chain
    return out


@dataclass(frozen=True)
class MuxCondition:
    """A multiplexed field is present while its multiplexer `by` (a field of the same message,
    itself present) holds a raw value in `ranges`."""

    by: str
    ranges: Ranges

    def holds(self, value: int) -> bool:
        return holds(self.ranges, value)

    @property
    def first(self) -> int:
        """The lowest value: the DBC's `mN`."""
        return self.ranges[0][0]

    @property
    def is_single(self) -> bool:
        return len(self.ranges) == 1 and self.ranges[0][0] == self.ranges[0][1]


@dataclass(frozen=True)
class MuxGroup:
    """One page of one multiplexer: the values of `multiplexer` for which the same fields it
    multiplexes are present (`signals`, by name, in frame order). Values no group holds select
    none of its fields."""

    multiplexer: str
    ranges: Ranges
    signals: tuple[str, ...]


def groups(multiplexer: str, children: list[tuple[str, Ranges]]) -> tuple[MuxGroup, ...]:
    """The pages of one multiplexer from its fields' conditions: its values cut where the set of
    present fields changes, runs with the same set merged, ordered by their first value."""
    cuts = sorted({lo for _, rs in children for lo, _ in rs} | {hi + 1 for _, rs in children for _, hi in rs})
    by_set: dict[tuple[str, ...], list[tuple[int, int]]] = {}
    for lo, nxt in itertools.pairwise(cuts):
        present = tuple(name for name, rs in children if holds(rs, lo))
        if present:
            by_set.setdefault(present, []).append((lo, nxt - 1))
    found = [MuxGroup(multiplexer, ranges_of(runs), names) for names, runs in by_set.items()]
    return tuple(sorted(found, key=lambda g: g.ranges[0]))
