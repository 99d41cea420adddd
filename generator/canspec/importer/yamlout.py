"""The imported spec as YAML in the shipped spec's style: one line per signal and per node,
blocks for messages and value tables, IDs in hex, numbers as exact decimals. Written by hand
rather than by a YAML library so that the layout is the one a reviewer reads in the shipped spec."""

from __future__ import annotations

import json
import re
from fractions import Fraction
from typing import Any

from canspec.ir.encoding import decimal_text

_PLAIN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")  # fullmatch: "$" would also match before a final newline
_CONTROL = re.compile("[\x7f-\x9f]")
_YAML_WORDS = {"y", "n", "yes", "no", "true", "false", "on", "off", "null"}


def scalar(value: Any, key: str = "") -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return f"0x{value:X}" if key == "id" else str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, Fraction):
        return decimal_text(value)
    if isinstance(value, list):
        return "[" + ", ".join(scalar(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {scalar(v, k)}" for k, v in value.items()) + "}"
    text = str(value)
    if _PLAIN.fullmatch(text) and text.lower() not in _YAML_WORDS:
        return text
    return _CONTROL.sub(lambda m: f"\\u{ord(m.group()):04x}", json.dumps(text, ensure_ascii=False))  # YAML refuses DEL and C1 raw


def dump_with_lines(spec: dict[str, Any], header: list[str]) -> tuple[str, dict[int, tuple[int, ...]]]:
    """The text, and each message's and signal's 1-based line: (message index,) or (message, signal index)."""
    out = [f"# {line}" for line in header]
    where: dict[int, tuple[int, ...]] = {}
    for key in ("schema_version", "kind", "protocol", "bus"):
        out.append(f"{key}: {scalar(spec[key])}")
    out.append("nodes:" + ("" if spec["nodes"] else " []"))
    out += [f"  - {scalar(n)}" for n in spec["nodes"]]
    if spec.get("value_tables"):
        out.append("value_tables:")
        for name, table in spec["value_tables"].items():
            out.append(f"  {name}:")
            out += [f"    {raw}: {scalar(label)}" for raw, label in table.items()]
    if spec.get("dbc_attributes"):
        out.append("dbc_attributes:")
        out += [f"  {name}: {scalar(d)}" for name, d in spec["dbc_attributes"].items()]
    out.append("messages:" + ("" if spec["messages"] else " []"))
    for mi, msg in enumerate(spec["messages"]):
        first = True
        for key, value in msg.items():
            if key == "signals":
                out.append("    signals:" + ("" if value else " []"))
                for si, sig in enumerate(value):
                    out.append(f"      - {scalar(sig)}")
                    where[len(out)] = (mi, si)
                continue
            out.append(f"  {'- ' if first else '  '}{key}: {scalar(value, key)}")
            if first:
                where[len(out)] = (mi,)
            first = False
    return "\n".join(out) + "\n", where
