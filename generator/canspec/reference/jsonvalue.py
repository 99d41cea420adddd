"""Check one JSON value against a JSON-protocol field of the IR: the rules every binding and
schema of the JSON protocol encode (type, integer range of the declared type, documented
range, enum, sentinel). Returns messages naming the field, the value and the rule."""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from canspec import ir


def field_problems(field: ir.JsonField, value: Any) -> list[str]:
    name = field.json_name
    jt = field.json_type
    if jt == "boolean":
        return [] if isinstance(value, bool) else [f"{name}: expected a boolean, got {value!r}"]
    if jt == "string":
        if not isinstance(value, str):
            return [f"{name}: expected a string, got {value!r}"]
        if field.min_length is not None and len(value) < field.min_length or field.max_length is not None and len(value) > field.max_length:
            return [f"{name}: {value!r} must be {field.min_length}..{field.max_length} characters ({field.type})"]
        if field.enum and value not in [e.value for e in field.enum]:
            return [f"{name}: {value!r} is not one of {', '.join(repr(e.value) for e in field.enum)}"]
        return []
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return [f"{name}: expected a {'integer' if jt == 'integer' else 'number'}, got {value!r}"]
    if jt == "integer" and not isinstance(value, int):
        if not (isinstance(value, float) and value.is_integer()):
            return [f"{name}: expected an integer ({field.type}), got {value!r}"]
    if isinstance(value, float) and not math.isfinite(value):
        return [f"{name}: {value!r} is not a finite number"]
    if field.type_min is not None and value < field.type_min or field.type_max is not None and value > field.type_max:
        return [f"{name}: {value!r} is outside the range of {field.type} [{field.type_min}, {field.type_max}]"]
    allowed = {e.value for e in field.enum} | {s.value for s in field.sentinels}
    if field.enum:
        return [] if value in allowed else [f"{name}: {value!r} is not one of {', '.join(repr(v) for v in sorted(allowed, key=str))}"]
    if value in {s.value for s in field.sentinels}:
        return []
    exact = Fraction(repr(value)) if isinstance(value, float) else Fraction(value)
    if field.min is not None and exact < field.min or field.max is not None and exact > field.max:
        return [f"{name}: {value!r} is outside [{_num(field.min)}, {_num(field.max)}]"]
    return []


def _num(f: Fraction | None) -> str:
    if f is None:
        return "-inf"
    return str(f.numerator) if f.denominator == 1 else str(float(f))


def message_problems(message: ir.JsonMessage, obj: Any) -> list[str]:
    if not isinstance(obj, dict):
        return [f"{message.name}: expected a JSON object, got {obj!r}"]
    out = []
    fields = {f.json_name: f for f in message.fields}
    for key in fields:
        if key not in obj:
            out.append(f"{key}: missing (required in {message.name})")
    for key, value in obj.items():
        if key not in fields:
            out.append(f"{key}: unexpected field in {message.name}")
        else:
            out.extend(field_problems(fields[key], value))
    if message.cmd is not None and obj.get("cmd") != message.cmd and "cmd" in fields:
        out.append(f"cmd: {message.name} carries cmd {message.cmd}, got {obj.get('cmd')!r}")
    return out
