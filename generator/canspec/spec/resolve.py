"""Resolve references in the loaded documents: gather value tables, expand each message's
shared layout with its `override` / `remove` / `add`, and fill defaults. The result is
still plain data with locations, ready for the semantic rules in validate.py."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from canspec.ir.bits import LITTLE, positions
from canspec.spec.loader import Document, LoadedSpec
from canspec.spec.problems import Problem, error
from canspec.spec.yamlsource import LocDict, LocList

SIGNAL_DEFAULTS: dict[str, Any] = {"factor": 1, "offset": 0, "unit": "", "role": "data", "signed": False, "float": False, "desc": "", "desc_zh": ""}


@dataclass
class ResolvedCan:
    doc: Document
    value_tables: dict[str, LocDict] = field(default_factory=dict)
    messages: list[LocDict] = field(default_factory=list)  # each with a resolved `signals` list


@dataclass
class Resolved:
    can: ResolvedCan | None
    json: list[Document]
    changelog: Document | None
    problems: list[Problem]


def _copy(d: LocDict, **updates: Any) -> LocDict:
    out = LocDict(d)
    out.loc, out.key_locs, out.value_locs = d.loc, dict(d.key_locs), dict(d.value_locs)
    out.update(updates)
    return out


def _patched(base: LocDict, patch: LocDict) -> LocDict:
    """Signal `base` with the fields of `patch`; patched fields point at the patch."""
    out = _copy(base)
    for key, value in patch.items():
        out[key] = value
        out.key_locs[key] = patch.key_locs[key]
        out.value_locs[key] = patch.value_locs[key]
    return out


def _finish_signal(sig: LocDict, byte_order: str) -> LocDict:
    out = _copy(sig)
    for key, value in SIGNAL_DEFAULTS.items():
        out.setdefault(key, value)
    out.setdefault("byte_order", byte_order)
    if out["role"] == "reserved":
        out.setdefault("name", f"reserved_{out['start']}")
        out.setdefault("zh", "保留")
    return out


def _frame_order(sig: LocDict) -> tuple[int, int]:
    """Signals in frame order: by their lowest-numbered bit (an Intel field's start), then length."""
    start, length = sig["start"], sig["len"]
    if sig["byte_order"] == LITTLE or not (isinstance(start, int) and isinstance(length, int) and 0 <= start and 0 < length <= 64):
        return start, length
    return min(positions(start, length, sig["byte_order"])), length


def _expand_layout(msg: LocDict, layouts: LocDict, problems: list[Problem]) -> list[LocDict]:
    name = msg["layout"]
    if name not in layouts:
        known = ", ".join(sorted(layouts)) or "none defined"
        problems.append(error(f"message {msg['name']!r} uses unknown layout {name!r}", msg.loc_of("layout"), f"known layouts: {known}", "unknown-layout"))
        return []
    signals = [s for s in layouts[name]["signals"]]
    by_name = {s.get("name", f"reserved_{s['start']}"): i for i, s in enumerate(signals)}
    removed = set()
    removes: LocList = msg.get("remove", LocList())
    for i, victim in enumerate(removes):
        if victim not in by_name:
            problems.append(error(
                f"`remove` names {victim!r}, which layout {name!r} does not have", removes.loc_of(i), f"signals of {name!r}: {', '.join(by_name)}",
                "unknown-override"))
        removed.add(victim)
    overrides: LocDict = msg.get("override", LocDict())
    for target, patch in overrides.items():
        if target not in by_name:
            problems.append(error(
                f"`override` names {target!r}, which layout {name!r} does not have", overrides.key_locs[target],
                f"signals of {name!r}: {', '.join(by_name)}", "unknown-override"))
            continue
        signals[by_name[target]] = _patched(signals[by_name[target]], patch)
    kept = [s for s in signals if s.get("name", f"reserved_{s['start']}") not in removed]
    return kept + list(msg.get("add", []))


def resolve(spec: LoadedSpec) -> Resolved:
    problems: list[Problem] = []
    cans = spec.of_kind("can_protocol")
    for extra in cans[1:]:
        problems.append(error("a spec holds at most one CAN protocol", extra.data.loc, "split it into two specs", "one-can-protocol"))
    logs = spec.of_kind("changelog")
    for extra in logs[1:]:
        problems.append(error("a spec holds at most one changelog", extra.data.loc, None, "one-changelog"))
    can = None
    if cans:
        doc = cans[0]
        can = ResolvedCan(doc)
        table_sources = [d.data["value_tables"] for d in spec.of_kind("value_tables")]
        if "value_tables" in doc.data:
            table_sources.insert(0, doc.data["value_tables"])
        for source in table_sources:
            for tname, table in source.items():
                if tname in can.value_tables:
                    first = can.value_tables[tname].loc
                    problems.append(error(f"value table {tname!r} is defined twice (first at {first})", source.key_locs[tname], "rename one of them",
                                          "duplicate-value-table"))
                    continue
                can.value_tables[tname] = table
        layouts: LocDict = doc.data.get("layouts", LocDict())
        for msg in doc.data["messages"]:
            has_layout, has_signals = "layout" in msg, "signals" in msg
            if has_layout == has_signals:
                problems.append(error(
                    f"message {msg['name']!r} needs exactly one of `signals` or `layout`", msg.loc,
                    "list its signals, or name a shared layout and its differences", "signals-or-layout"))
                continue
            if not has_layout and any(k in msg for k in ("override", "remove", "add")):
                problems.append(error(f"message {msg['name']!r} uses override/remove/add without a `layout`", msg.loc, None, "signals-or-layout"))
            raw_signals = _expand_layout(msg, layouts, problems) if has_layout else list(msg["signals"])
            order = doc.data["bus"].get("byte_order", LITTLE)
            signals = LocList(sorted((_finish_signal(s, order) for s in raw_signals), key=_frame_order))
            signals.loc = msg.loc_of("signals") if has_signals else msg.loc_of("layout")
            signals.item_locs = [s.loc for s in signals]
            can.messages.append(_copy(msg, signals=signals))
    return Resolved(can, spec.of_kind("json_protocol"), logs[0] if logs else None, problems)


def label_pair(value: Any) -> tuple[str, str]:
    """A value's (identifier, Chinese label) from any of its written forms: `ident`, `[ident]`,
    `[ident, 中文]` (the label is optional: an English-only spec names values by identifier) or
    `{name: ident, zh: 中文, dbc: text}`."""
    if isinstance(value, str):
        return value, ""
    if isinstance(value, dict):
        return str(value["name"]), str(value.get("zh", ""))
    return str(value[0]), str(value[1]) if len(value) > 1 else ""



def label_dbc(value: Any) -> str:
    """The label a DBC writes for a value when it is not the identifier (`{…, dbc: text}`), else ""."""
    return str(value.get("dbc", "")) if isinstance(value, dict) else ""
