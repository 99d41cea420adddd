"""A source message's multiplexing (DBC `M`/`mN`, SG_MUL_VAL_ ranges and nested multiplexers, as
cantools reads them) as the spec's `mux: {by, values}`, and which fields may share bits: only
fields never present in one frame (ir/mux.py decides, as the spec rules do).

What the spec cannot say is decided here with a warning: a message whose multiplexer is signed,
scaled or float, or that has two top-level multiplexers, is left out; a page's counter or checksum
role is dropped (those belong to every frame); a multiplexer value its bits cannot hold is dropped,
and the multiplexer's documented range is dropped when it leaves out values that select a page."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from canspec.ir import mux
from canspec.ir.bits import positions

NOT_MULTIPLEXABLE = ("counter", "checksum")


class Pages:
    def __init__(self, msg: Any, source_msg: str) -> None:
        self.msg = source_msg  # the message's name in the source, for the warnings
        self.by_name = {s.name: s for s in msg.signals}
        self.parent = {s.name: (s.multiplexer_signal, mux.ranges_of(s.multiplexer_ids)) for s in msg.signals if s.multiplexer_ids}
        self.chains = mux.conditions(self.parent)
        self.owners: dict[int, list[str]] = {}

    def refusal(self) -> str | None:
        """Why the message's multiplexing cannot be expressed, or None."""
        used = list(dict.fromkeys(by for by, _ in self.parent.values()))
        # cantools found no multiplexer (None) for a field with page values: SG_MUL_VAL_ names the
        # signal itself, names one whose SG_ line is not marked mN, or an `mNM` has no M above it.
        # Said first: None is no name to count or join as a root.
        if None in used:
            orphans = ", ".join(n for n, (by, _) in self.parent.items() if by is None)
            return f"signal {orphans} is multiplexed (mN) but has no multiplexer of the message to select it"
        roots = [name for name in used if name not in self.parent]
        if len(roots) > 1:
            return f"has {len(roots)} top-level multiplexers ({', '.join(roots)}; canspec multiplexes a message by one, nested ones under it)"
        for name in used:
            sig = self.by_name.get(name)
            if sig is None:
                return f"names a multiplexer {name} it does not have"
            if sig.is_float or sig.is_signed or sig.scale != 1 or sig.offset != 0:
                return f"multiplexer {name} is not an unsigned integer with factor 1 and offset 0 (a page is selected by the raw value)"
        return None

    def oddities(self) -> list[tuple[str, str]]:
        """(signal, warning) for a multiplexer flag the pages contradict: the pages decide, as cantools decodes."""
        used = {by for by, _ in self.parent.values()}
        out = [(n, f"signal {n} of {self.msg} is marked a multiplexer (M) but selects no page: taken as a plain field")
               for n, s in self.by_name.items() if s.is_multiplexer and n not in used]
        return out + [(n, f"signal {n} of {self.msg} selects pages but is not marked a multiplexer (M): taken as their multiplexer")
                      for n in sorted(used) if n in self.by_name and not self.by_name[n].is_multiplexer]

    def overlaps(self, sig: Any, bits: tuple[int, ...]) -> list[str]:
        """The fields already taken that own one of these bits in a frame `sig` can be in."""
        mine = self.chains.get(sig.name, {})
        return sorted({o for b in bits for o in self.owners.get(b, ()) if not mux.exclusive(mine, self.chains.get(o, {}))})

    def take(self, sig: Any) -> None:
        for b in positions(sig.start, sig.length, sig.byte_order):
            self.owners.setdefault(b, []).append(sig.name)

    def attach(self, fields: list[dict[str, Any]], spec_names: dict[str, str], warn: Callable[[str, str], None]) -> list[dict[str, Any]]:
        """`fields` (converted, in order; `spec_names`: source name → spec name) with their `mux:`; a
        field whose multiplexer was left out goes too, with a warning."""
        source_of = {v: k for k, v in spec_names.items()}
        kept = dict(zip((source_of[f["name"]] for f in fields), fields))
        while dropped := [n for n in kept if n in self.parent and self.parent[n][0] not in kept]:
            for name in dropped:
                warn(name, f"signal {name} of {self.msg}: its multiplexer {self.parent[name][0]} was left out: left out")
                del kept[name]
        for name in [n for n in kept if n in self.parent]:
            if not self._condition(name, kept, spec_names, warn):
                del kept[name]
        return list(kept.values())

    def _condition(self, name: str, kept: dict[str, dict[str, Any]], spec_names: dict[str, str], warn: Callable[[str, str], None]) -> bool:
        """Give the field its `mux:`; False when no value of its multiplexer selects it (left out, warned)."""
        field, (by, ranges) = kept[name], self.parent[name]
        top = (1 << self.by_name[by].length) - 1
        fitting = tuple((lo, min(hi, top)) for lo, hi in ranges if lo <= top)
        if not fitting:
            warn(name, f"signal {name} of {self.msg}: no multiplexer value that selects it fits {by}'s {self.by_name[by].length} bits: left out")
            return False
        if fitting != ranges:
            warn(name, f"signal {name} of {self.msg}: multiplexer values above {top} (what {by}'s {self.by_name[by].length} bits hold) dropped")
        for role_of in (name, by):  # a page's and a multiplexer's role
            if kept[role_of].get("role") in NOT_MULTIPLEXABLE:
                warn(role_of, f"{kept[role_of].pop('role')} signal {role_of} of {self.msg} is multiplexed or a multiplexer: role dropped "
                     "(counters and checksums belong to every frame and select no page)")
        rng = kept[by].get("range")
        if rng is not None and not (rng[0] <= fitting[0][0] and fitting[-1][1] <= rng[1]):
            warn(by, f"multiplexer {by} of {self.msg}: range [{rng[0]}|{rng[1]}] leaves out values that select a page: range dropped")
            del kept[by]["range"]
        field["mux"] = {"by": spec_names[by], "values": [lo if lo == hi else [lo, hi] for lo, hi in fitting]}
        return True
