"""The rules of what a spec keeps only for the DBC (written by `canspec import`): a source's own
attributes (`dbc_attributes`: each value needs a definition for its kind of object and must be one
the definition allows), further senders and per-signal receivers (known nodes)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from canspec.ir.dbc_attributes import COMPUTED
from canspec.spec.problems import Loc, Problem, error
from canspec.spec.resolve import ResolvedCan
from canspec.spec.yamlsource import LocDict


def refusal(d: dict[str, Any], value: Any) -> str | None:
    """Why the definition `d` refuses `value`, or None."""
    kind = d["type"]
    if kind == "STRING":
        return None if isinstance(value, str) else "a STRING attribute's value is a text"
    if kind == "ENUM":
        return None if value in d.get("values", []) else f"an ENUM attribute's value is one of {d.get('values', [])}"
    if isinstance(value, str | bool):
        return f"a {kind} attribute's value is a number"
    if kind in ("INT", "HEX") and value != int(value):
        return f"a {kind} attribute's value is an integer"
    lo, hi = d.get("min"), d.get("max")
    if lo is not None and hi is not None and (lo, hi) != (0, 0) and not lo <= value <= hi:  # a DBC's [0, 0]: no limit
        return f"the definition allows {lo} to {hi}"
    return None


def _values(obj: LocDict, kind: str, where: str, defs: LocDict) -> Iterator[Problem]:
    values = obj.get("dbc_attributes", LocDict())
    for name, value in values.items():
        d = defs.get(name)
        loc: Loc = values.loc_of(name)
        if d is None or d["object"] != kind:
            yield error(f"{where}: attribute {name!r} has no {kind} definition in `dbc_attributes`", loc,
                        f"define it at the top: dbc_attributes: {{{name}: {{object: {kind}, type: ...}}}}", "dbc-attribute")
        elif (why := refusal(d, value)) is not None:
            yield error(f"{where}: attribute {name!r} = {value!r}: {why}", loc, None, "dbc-attribute")


def _definitions(defs: LocDict) -> Iterator[Problem]:
    for name, d in defs.items():
        if name in COMPUTED:
            yield error(f"attribute {name!r} is written by canspec from the spec's own fields", defs.loc_of(name),
                        "remove it from `dbc_attributes` (its value comes from the bus, message or signal fields)", "dbc-attribute")
        for key in ("default", "value"):
            if key in d and (why := refusal(d, d[key])) is not None:
                yield error(f"attribute {name!r}: {key} {d[key]!r}: {why}", d.loc_of(key), None, "dbc-attribute")
        if "value" in d and d["object"] != "network":
            yield error(f"attribute {name!r}: only a network attribute has a `value` here", d.loc_of("value"),
                        "give a node's, message's or signal's value in its own `dbc_attributes`", "dbc-attribute")


def dbc_rules(can: ResolvedCan) -> Iterator[Problem]:
    data = can.doc.data
    defs = data.get("dbc_attributes", LocDict())
    yield from _definitions(defs)
    nodes = {n["name"] for n in data["nodes"]}
    for node in data["nodes"]:
        yield from _values(node, "node", f"node {node['name']!r}", defs)
    for msg in can.messages:
        yield from _values(msg, "message", f"message {msg['name']!r}", defs)
        senders = msg.get("dbc_senders", [])
        for i, name in enumerate(senders):
            if name not in nodes:
                yield error(f"sender {name!r} of message {msg['name']!r} is not a node", senders.loc_of(i), f"known nodes: {', '.join(sorted(nodes))}",
                            "unknown-node")
        for sig in msg["signals"]:
            where = f"signal {sig['name']!r} of {msg['name']!r}"
            yield from _values(sig, "signal", where, defs)
            receivers = sig.get("receivers", [])
            for i, name in enumerate(receivers):
                if name not in nodes:
                    yield error(f"receiver {name!r} of {where} is not a node", receivers.loc_of(i), f"known nodes: {', '.join(sorted(nodes))}",
                                "unknown-node")
