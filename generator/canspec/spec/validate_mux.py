"""The rules of multiplexing (a signal's `mux: {by, values}`), and which fields of a message can be
present together (the overlap rule in validate.signal_shapes checks only those)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from fractions import Fraction

from canspec.ir import mux
from canspec.spec.problems import Problem, error
from canspec.spec.resolve import ResolvedCan
from canspec.spec.yamlsource import LocDict

NOT_MULTIPLEXABLE = ("counter", "checksum", "reserved")


def _parents(signals: list[LocDict]) -> dict[str, tuple[str, mux.Ranges]]:
    return {s["name"]: (s["mux"]["by"], mux.ranges_of(s["mux"]["values"])) for s in signals if "mux" in s}


def coexist(signals: list[LocDict]) -> Callable[[LocDict, LocDict], bool] | None:
    """Whether two fields of the message can be present in one frame; None for a message without
    multiplexing (every field is always present)."""
    parents = _parents(signals)
    if not parents:
        return None
    chains = mux.conditions(parents)
    return lambda a, b: not mux.exclusive(chains.get(a["name"], {}), chains.get(b["name"], {}))


def mux_rules(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        signals = list(msg["signals"])
        by_name = {s["name"]: s for s in signals}
        muxed = [s for s in signals if "mux" in s]
        for sig in muxed:
            yield from _one(msg, sig, by_name)
        yield from _cycles(msg, muxed)
        roots = [by_name[n] for n in dict.fromkeys(s["mux"]["by"] for s in muxed) if n in by_name and "mux" not in by_name[n]]
        for extra in roots[1:]:
            yield error(f"message {msg['name']!r} has two top-level multiplexers, {roots[0]['name']!r} and {extra['name']!r}", extra.loc_of("name"),
                        f"multiplex one by the other (give {extra['name']!r} a `mux:` of its own)", "mux-root")


def _one(msg: LocDict, sig: LocDict, by_name: dict[str, LocDict]) -> Iterator[Problem]:
    cond = sig["mux"]
    if sig["role"] in NOT_MULTIPLEXABLE:
        yield error(f"{sig['role']} field {sig['name']!r} of {msg['name']!r} is multiplexed", sig.loc_of("mux"),
                    "counters, checksums and reserved bits belong to every frame: remove `mux`", "mux-role")
    by = by_name.get(cond["by"])
    if by is None or by is sig:
        what = "itself" if by is sig else "no signal of the message"
        yield error(f"signal {sig['name']!r} is multiplexed by {cond['by']!r}, {what}", cond.loc_of("by"),
                    f"`by` names another signal of {msg['name']!r} (its multiplexer)", "mux-unknown")
        return
    if by["float"] or by["signed"] or by["role"] != "data" or by["factor"] != 1 or by["offset"] != 0:
        yield error(f"multiplexer {by['name']!r} of {sig['name']!r} is not an unsigned integer data field with factor 1 and offset 0",
                    cond.loc_of("by"), "a multiplexer's raw value selects the page: make it unsigned, not float, factor 1, offset 0", "mux-multiplexer")
        return
    if not 1 <= by["len"] <= 64:
        return  # reported by signal-length
    lo_max, hi_max = _raw_range(by)
    values = cond["values"]
    for i, value in enumerate(values):
        lo, hi = (value, value) if isinstance(value, int) else (value[0], value[1])
        if lo > hi or lo < lo_max or hi > hi_max:
            yield error(f"multiplexer value {lo if lo == hi else f'{lo}..{hi}'} of {sig['name']!r} is not a raw value {by['name']!r} can hold "
                        f"({lo_max}..{hi_max})", values.loc_of(i), "give single values or ranges [first, last] with first <= last within the multiplexer",
                        "mux-value-range")


def _raw_range(by: LocDict) -> tuple[int, int]:
    """The raw values the (unsigned, unscaled) multiplexer may hold: its bits, within its documented range."""
    lo, hi = 0, (1 << by["len"]) - 1
    rng = by.get("range")
    if rng is not None:
        try:
            lo, hi = max(lo, -(-Fraction(rng[0]) // 1)), min(hi, Fraction(rng[1]) // 1)
        except (ValueError, OverflowError):
            pass  # a non-finite range is reported by nonfinite
    return int(lo), int(hi)


def _cycles(msg: LocDict, muxed: list[LocDict]) -> Iterator[Problem]:
    parent = {s["name"]: s["mux"]["by"] for s in muxed}
    for sig in muxed:
        if parent[sig["name"]] == sig["name"]:
            continue  # multiplexed by itself: mux-unknown
        seen, at = [sig["name"]], parent[sig["name"]]
        while at in parent and at not in seen:
            seen.append(at)
            at = parent[at]
        if at == sig["name"]:
            loop = " → ".join([*seen, at])
            yield error(f"the multiplexers of {msg['name']!r} go round in a circle: {loop}", sig["mux"].loc_of("by"),
                        "one multiplexer of the chain must be present in every frame (no `mux`)", "mux-cycle")
