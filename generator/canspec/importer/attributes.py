"""A source's own DBC attributes, kept as they were (the spec's `dbc_attributes`): the definitions
canspec does not compute from the spec's fields, and every object's values of them. ENUM values are
kept by their text (a DBC stores the index)."""

from __future__ import annotations

import re
from typing import Any

from canspec.importer.load import Loaded
from canspec.ir.dbc_attributes import COMPUTED
from canspec.spec.validate_dbc import refusal

KINDS = {None: "network", "BU_": "node", "BO_": "message", "SG_": "signal"}
NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")  # fullmatch: "$" would also match before a final newline


def _number(value: Any) -> int | float:
    number = float(value)
    return int(number) if number.is_integer() and abs(number) < 2**63 else number


def kept_definitions(loaded: Loaded, warn: Any) -> dict[str, dict[str, Any]]:
    """name → the spec's definition; a network attribute's value in it."""
    dbc = getattr(loaded.db, "dbc", None)
    out: dict[str, dict[str, Any]] = {}
    for name, d in (getattr(dbc, "attribute_definitions", None) or {}).items():
        if name in COMPUTED:
            continue
        if d.kind not in KINDS or not NAME.fullmatch(name):
            warn(f"attribute {name} of {d.kind} objects: left out (canspec keeps network, node, message and signal attributes named as identifiers)")
            continue
        spec: dict[str, Any] = {"object": KINDS[d.kind], "type": d.type_name}
        if d.type_name in ("INT", "HEX", "FLOAT"):
            spec |= {"min": _number(d.minimum or 0), "max": _number(d.maximum or 0)}
        if d.type_name == "ENUM":
            spec["values"] = [str(c) for c in d.choices]
        if d.default_value is not None:
            default = _value(d, d.default_value, default=True)
            why = refusal(spec, default)
            if why is None:
                spec["default"] = default
            else:
                warn(f"attribute {name}: default {default!r} is refused by its definition ({why}): left out")
        out[name] = spec
    for name, attribute in (getattr(dbc, "attributes", None) or {}).items():
        if name in out:
            out[name] |= kept_values_of({name: attribute}, out, warn, "the network", key="value")
    return out


def _value(d: Any, value: Any, default: bool = False) -> Any:
    if d.type_name == "ENUM":  # a BA_ line holds the index, BA_DEF_DEF_ the text
        return str(value) if default or isinstance(value, str) else str(d.choices[int(value)])
    return str(value) if d.type_name == "STRING" else _number(value)


def kept_values(obj: Any, kept: dict[str, dict[str, Any]], warn: Any, where: str) -> dict[str, Any]:
    """An object's values of the kept attributes, in the source's order."""
    return kept_values_of(getattr(getattr(obj, "dbc", None), "attributes", None) or {}, kept, warn, where)


def kept_values_of(attributes: dict[str, Any], kept: dict[str, dict[str, Any]], warn: Any, where: str, key: str = "") -> dict[str, Any]:
    out = {}
    for name, a in attributes.items():
        if name not in kept:
            continue
        value = _value(a.definition, a.value)
        why = refusal(kept[name], value)
        if why is None:
            out[key or name] = value
        else:
            warn(f"attribute {name} of {where} = {value!r} is refused by its definition ({why}): left out")
    return out
