"""Multiplexing in the Python bindings: the statements that depend on which pages a frame holds.

Fields are grouped by their chain of multiplexers (ir.Message.mux_chain): the fields of every frame
first, then each page, a multiplexer's page before the pages it selects. A page's statements run
under the whole chain's condition, so a nested multiplexer's value only counts while its own page
is present. Decode sets the other pages' fields to None; `update` (a decode copied onto an existing
message, None skipped) leaves them alone; encode and pack neither check nor write them.
"""

from __future__ import annotations

from collections.abc import Callable

from canspec import ir
from canspec.targets.python.fields import PySignal

IND = "    "
Chain = tuple[ir.MuxCondition, ...]


def holds(cond: ir.MuxCondition, var: str) -> str:
    """`var` (a multiplexer's raw value) is one of the condition's values."""
    singles = [str(lo) for lo, hi in cond.ranges if lo == hi]
    # several single values are one membership test (ruff PLR1714 refuses `k == 2 or k == 4`)
    parts = [f"{var} == {singles[0]}" if len(singles) == 1 else f"{var} in {{{', '.join(singles)}}}"] if singles else []
    parts += [f"{lo} <= {var} <= {hi}" for lo, hi in cond.ranges if lo != hi]
    return parts[0] if len(parts) == 1 else "(" + " or ".join(parts) + ")"


def presence(chain: Chain, var_of: Callable[[str], str]) -> str:
    """The condition of a whole chain, each multiplexer's raw value named by `var_of`."""
    return " and ".join(holds(c, var_of(c.by)) for c in chain)


def grouped(signals: tuple[PySignal, ...]) -> list[tuple[Chain, list[PySignal]]]:
    """Signals by chain, in frame order within each: every frame's first, then shallower pages before deeper ones."""
    groups: dict[Chain, list[PySignal]] = {}
    for s in signals:
        groups.setdefault(s.chain, []).append(s)
    return sorted(groups.items(), key=lambda item: len(item[0]))


def under(chain: Chain, var_of: Callable[[str], str], lines: list[str]) -> list[str]:
    """`lines` as they are for the fields of every frame, else under the chain's condition."""
    if not chain:
        return lines
    return [f"if {presence(chain, var_of)}:", *(IND + line for line in lines)]


def is_multiplexed(signals: tuple[PySignal, ...]) -> bool:
    return any(s.chain for s in signals)


def decode(signals: tuple[PySignal, ...]) -> tuple[str, ...]:
    """Decode's assignments to `m`: a multiplexer through its raw local, the other pages' fields None."""
    by_name = {s.name: s for s in signals}
    lines: list[str] = []
    for chain, group in grouped(signals):
        body = [line for s in group for line in _assign(s)]
        lines += under(chain, lambda n: by_name[n].key_var, body)
        if chain:
            lines += ["else:", IND + " = ".join([*(f"m.{s.attr}" for s in group), "None"])]
    return tuple(lines)


def _assign(s: PySignal) -> list[str]:
    if s.key_var:
        return [f"{s.key_var} = {s.raw_expr}", f"m.{s.attr} = {s.phys_from_key}"]
    return [f"m.{s.attr} = {s.phys_expr}"]


def unpack(signals: tuple[PySignal, ...], raw_class: str) -> tuple[str, ...]:
    """Unpack's raw dict of a multiplexed message: the fields the frame holds."""
    groups = grouped(signals)
    first = groups[0][1] if not groups[0][0] else []
    lines = [f"raw: {raw_class} = {{", *(f'{IND}"{s.name}": {s.raw_expr},' for s in first), "}"]
    for chain, group in groups:
        if chain:
            lines += under(chain, _raw_key, [f'raw["{s.name}"] = {s.raw_expr}' for s in group])
    return (*lines, "return raw")


def _raw_key(name: str) -> str:
    return f'raw["{name}"]'


def present(signals: tuple[PySignal, ...]) -> tuple[str, ...]:
    """The body of `_present_<message>(m)`: the spec names of the fields its multiplexer values select, in frame order."""
    by_name = {s.name: s for s in signals}

    def key(name: str) -> str:
        return by_name[name].key_var

    lines = []
    for s in sorted((s for s in signals if s.key_var), key=lambda s: len(s.chain)):  # a multiplexer's raw, parents first
        value = f"_to_raw(m.{s.attr}, {s.descriptor})"  # 0 while its own page is absent: every condition names the whole chain
        lines.append(f"{s.key_var} = {value} if {presence(s.chain, key)} else 0" if s.chain else f"{s.key_var} = {value}")
    pairs = ", ".join(f'("{s.name}", {presence(s.chain, key) if s.chain else "True"})' for s in signals)
    return (*lines, f"return tuple(name for name, on in ({pairs}) if on)")
