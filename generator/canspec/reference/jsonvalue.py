"""The reference reading of the JSON protocol: which rule a JSON value breaks first (the order
every binding checks in, ir/json_fields.py), which message a plan reads an object as, and a value
each field accepts. The shared vectors take their verdicts from here.

Numbers compare as doubles, as every binding and validator compares them (JSON has one number
type; Python's `jsonschema`, ajv, serde_json and TypeScript all read it as a double)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from canspec import ir
from canspec.ir.json_fields import CMD_KEY, Branch, Plan


@dataclass(frozen=True)
class Fault:
    key: str  # JSON key at fault ("" when the value is not an object)
    code: str  # one of json_fields.ERROR_CODES
    text: str


def _show(value: Any) -> str:
    return repr(value)


def _number_fault(field: ir.JsonField, value: Any) -> tuple[str, str] | None:
    """The type checks of an integer or number field: JSON type, integer-ness, the type's range."""
    name, what = field.json_name, "an integer" if field.json_type == "integer" else "a number"
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return "type", f"{name}: expected {what} ({field.type}), got {_show(value)}"
    if isinstance(value, float) and not math.isfinite(value):
        return "type", f"{name}: {_show(value)} is not a finite number"
    if field.json_type == "integer" and isinstance(value, float) and not value.is_integer():
        return "type", f"{name}: expected an integer ({field.type}), got {_show(value)}"
    if (field.type_min is not None and value < field.type_min) or (field.type_max is not None and value > field.type_max):
        return "type_range", f"{name}: {_show(value)} is outside the range of {field.type} [{field.type_min}, {field.type_max}]"
    return None


def _outside(field: ir.JsonField, value: float) -> bool:
    x = float(value)
    return (field.min is not None and x < float(field.min)) or (field.max is not None and x > float(field.max))


def type_fault(field: ir.JsonField, value: Any) -> tuple[str, str] | None:
    """(code, text) of the first type rule `value` breaks: JSON type, integer-ness, the declared
    type's range or a string's length."""
    name = field.json_name
    if field.json_type == "boolean":
        return None if isinstance(value, bool) else ("type", f"{name}: expected a boolean, got {_show(value)}")
    if field.json_type == "string":
        if not isinstance(value, str):
            return "type", f"{name}: expected a string, got {_show(value)}"
        if (field.min_length is not None and len(value) < field.min_length) or (field.max_length is not None and len(value) > field.max_length):
            return "length", f"{name}: {_show(value)} must be {field.min_length}..{field.max_length} characters ({field.type})"
        return None
    return _number_fault(field, value)


def field_fault(field: ir.JsonField, value: Any) -> tuple[str, str] | None:
    """(code, text) of the first rule `value` breaks as this field, or None."""
    fault = type_fault(field, value)
    if fault is not None:
        return fault
    name = field.json_name
    if field.enum:
        if value not in [e.value for e in field.enum]:
            return "enum", f"{name}: {_show(value)} is not one of {', '.join(repr(e.value) for e in field.enum)}"
        return None
    if field.json_type in ("integer", "number") and value not in [s.value for s in field.sentinels] and _outside(field, value):
        lo = "-inf" if field.min is None else format(float(field.min), "g")
        hi = "inf" if field.max is None else format(float(field.max), "g")
        return "range", f"{name}: {_show(value)} is outside [{lo}, {hi}]"
    return None


def message_faults(message: ir.JsonMessage, obj: Any) -> list[Fault]:
    """Every rule `obj` breaks as `message`, the one every binding reports first first."""
    if not isinstance(obj, dict):
        return [Fault("", "object", f"{message.name}: expected a JSON object, got {_show(obj)}")]
    fields = {f.json_name: f for f in message.fields}
    out = [Fault(k, "required", f"{k}: missing (required in {message.name})") for k in fields if k not in obj]
    out += [Fault(str(k), "unexpected", f"{k}: unexpected field in {message.name}") for k in sorted(obj) if k not in fields]
    if out:
        return out
    cmd = fields.get(CMD_KEY) if message.cmd is not None else None
    if cmd is not None:
        # A command's number: its JSON type and type range, then the number itself (not enum or range).
        fault = type_fault(cmd, obj[CMD_KEY])
        if fault is None and obj[CMD_KEY] != message.cmd:
            fault = "cmd", f"cmd: {message.name} carries cmd {message.cmd}, got {_show(obj[CMD_KEY])}"
        if fault is not None:
            out.append(Fault(CMD_KEY, *fault))
    for key, field in fields.items():
        fault = field_fault(field, obj[key]) if field is not cmd else None
        if fault is not None:
            out.append(Fault(key, *fault))
    return out


def message_problems(message: ir.JsonMessage, obj: Any) -> list[str]:
    return [f.text for f in message_faults(message, obj)]


def command_number(value: Any) -> int | None:
    """The command a `cmd` value names: an integer, possibly written as 3.0."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    if isinstance(value, float) and not value.is_integer():
        return None
    return int(value)


def select(protocol: ir.JsonProtocol, plan_: Plan, obj: Any) -> str | None:
    """The message `obj` is read as under `plan_` (None: not an object, or an unknown `cmd`).
    Every binding and schema implements exactly this."""
    if not isinstance(obj, dict):
        return None
    if plan_.commands and CMD_KEY in obj:
        n = command_number(obj[CMD_KEY])
        group = dict(plan_.commands).get(n) if n is not None else None
        return None if group is None else _pick(protocol, group, obj)
    return _pick(protocol, plan_.plain, obj) if plan_.plain else None


def _pick(protocol: ir.JsonProtocol, group: tuple[Branch, ...], obj: dict[str, Any]) -> str:
    for b in group[:-1]:
        if any(k in obj for k in b.markers) or (b.tried and not message_faults(protocol.message(b.message), obj)):
            return b.message
    return group[-1].message


def sample(field: ir.JsonField) -> tuple[Any, ...]:
    """A value the field accepts, as a 1-tuple; () when it accepts none."""
    candidates: list[Any]
    if field.json_type == "boolean":
        candidates = [False]
    elif field.enum:
        candidates = [e.value for e in field.enum]
    elif field.json_type == "string":
        candidates = ["x" * (field.min_length or 0)]
    else:
        bounds = [b for b in (field.min, field.max, field.type_min, field.type_max) if b is not None]
        candidates = [0, *(math.ceil(b) for b in bounds), *(math.floor(b) for b in bounds), *(s.value for s in field.sentinels)]
        if field.json_type == "number":
            candidates += [float(b) for b in bounds]
    return next(((v,) for v in candidates if field_fault(field, v) is None), ())
