"""The YAML text of a drawn spec (strategy.py): block and flow style written by hand, so that every
scalar is quoted exactly where YAML needs it and the text is the same on every machine."""

from __future__ import annotations

import json
from decimal import Decimal
from typing import Any


class Hex(int):
    """An integer written in hex."""


_PLAIN_OK = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_")
_YAML_SPECIAL = {"true", "false", "True", "False", "TRUE", "FALSE", "null", "Null", "NULL", "~", "y", "n", "yes", "no", "on", "off"}


def _scalar(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, Hex):
        return f"0x{int(v):X}"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, Decimal):
        return dec_text(v)
    if isinstance(v, str):
        if v and set(v) <= _PLAIN_OK and v[0].isalpha() and v not in _YAML_SPECIAL:
            return v
        return json.dumps(v, ensure_ascii=False)
    raise TypeError(f"no YAML form for {v!r}")


def dec_text(d: Decimal) -> str:
    """Decimal → YAML number text the spec loader reads back exactly (a '.' marks a decimal;
    exponents need a sign in YAML 1.1)."""
    if d == d.to_integral_value() and abs(d) < Decimal("1e15"):
        return str(int(d))
    if abs(d) >= Decimal("1e15"):
        sign, digits, exp = d.normalize().as_tuple()
        mant = format(Decimal((0, digits, -(len(digits) - 1))), "f")
        return f"{'-' if sign else ''}{mant if '.' in mant else mant + '.0'}e+{exp + len(digits) - 1}"
    if abs(d) < Decimal("0.0001"):
        sign, digits, exp = d.as_tuple()
        mant = Decimal((0, digits, -(len(digits) - 1)))
        e = exp + len(digits) - 1
        m = format(mant, "f")
        if "." not in m:
            m += ".0"
        return f"{'-' if sign else ''}{m}e{'+' if e >= 0 else '-'}{abs(e)}"
    return format(d.normalize(), "f")


def flow(v: Any) -> str:
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_scalar(k)}: {flow(x)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(flow(x) for x in v) + "]"
    return _scalar(v)


def block(v: Any, indent: int = 0, flow_depth: int = 99) -> str:
    """Block-style YAML; mappings/lists deeper than `flow_depth` are written in flow style."""
    pad = " " * indent
    out = []
    if isinstance(v, dict):
        for k, x in v.items():
            key = _scalar(k)
            if isinstance(x, (dict, list)) and x and flow_depth > 0:
                out.append(f"{pad}{key}:\n{block(x, indent + 2, flow_depth - 1)}")
            else:
                out.append(f"{pad}{key}: {flow(x)}\n")
    elif isinstance(v, list):
        for x in v:
            if isinstance(x, dict) and x and flow_depth > 0:
                inner = block(x, indent + 2, flow_depth - 1)
                out.append(f"{pad}- {inner[indent + 2:]}")
            else:
                out.append(f"{pad}- {flow(x)}\n")
    return "".join(out)
