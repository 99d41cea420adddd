"""Shared JSON-protocol test vectors (`vectors/json.json`): every document example, boundary
values, every enum and sentinel value, and invalid messages (wrong type, missing field, out of
range, unknown enum value, extra field, unknown cmd, wrong res, replies without their request's
fields), each naming the field at fault and the rule broken.

Each case states three verdicts: `valid` (against its own message), `as_received` (what the
receiver's schema/binding reads it as — the message name, or null when rejected) and `as_any`
(the same for the whole-protocol schema, which cannot use the direction: a reply without `res`
is a well-formed request there). The verdicts are computed here by the reference checker
(`jsonvalue`) and the reference dispatch (`jsonmodel.select`), and every validator and binding
must reproduce them.
"""

from __future__ import annotations

import copy
import json
from decimal import ROUND_DOWN, Decimal
from fractions import Fraction
from typing import Any

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.ir.json_fields import FieldRule, MessageModel, ProtocolModel
from canspec.reference import jsonvalue
from canspec.targets import Target

VECTOR_FORMAT = 1
PRECISION_SAMPLE = Decimal("12.3456789")


def _step(r: FieldRule) -> Fraction:
    return Fraction(1) if r.kind == "integer" else Fraction(1, 10 ** (r.field.decimals if r.field.decimals is not None else 2))


def _num(value: Fraction | float) -> int | float:
    out = jsonmodel.number(value if isinstance(value, (int, float)) else Fraction(value))
    assert out is not None
    return out


def _beyond(r: FieldRule, bound: float, sign: int) -> int | float:
    """A value just outside a type bound: one step for integers and small bounds; 3% for huge
    float bounds (±3.4e38), where one decimal step vanishes in the double."""
    if r.kind == "number" and abs(bound) > 1e15:
        return float(bound) * 1.03
    return _num(Fraction(bound) + sign * _step(r))


def _in_type(r: FieldRule, v: Fraction) -> bool:
    return (r.type_lo is None or v >= Fraction(r.type_lo)) and (r.type_hi is None or v <= Fraction(r.type_hi))


def valid_values(r: FieldRule) -> list[tuple[Any, str, str]]:
    """(value, kind, note) for one field."""
    key = r.key
    if r.const is not None:
        return []
    if r.kind == "boolean":
        return [(True, "boundary", f"{key}=true"), (False, "boundary", f"{key}=false")]
    if r.enum is not None:
        return [(e.value, "enum", f"{key}={e.name}") for e in r.enum.values]
    out: list[tuple[Any, str, str]] = []
    lo = r.lo if r.lo is not None else r.type_lo
    hi = r.hi if r.hi is not None else r.type_hi
    for v, what in ((lo, "minimum"), (hi, "maximum")):
        if v is not None:
            out.append((v, "boundary", f"{key} {what} {v}"))
    for s in r.sentinels:
        out.append((s.value, "sentinel", f"{key}={s.name}"))
    if r.kind == "number" and r.field.decimals is not None:
        q = Decimal(1).scaleb(-r.field.decimals)
        for sign in (1, -1):
            text = (sign * PRECISION_SAMPLE).quantize(q, rounding=ROUND_DOWN)
            if (lo is None or Fraction(text) >= Fraction(lo)) and (hi is None or Fraction(text) <= Fraction(hi)):
                out.append((float(text), "precision", f"{key}={text}: {r.field.decimals} decimal places, not a binary multiple of {q}"))
    return out


def invalid_values(r: FieldRule, pm: ProtocolModel) -> list[tuple[Any, str, str]]:
    """(value, rule, note) for one field."""
    key = r.key
    out: list[tuple[Any, str, str]] = []
    wrong_type = {"integer": ["1", 1.5, None], "number": ["1", None, True], "boolean": [1, "true", None], "string": [1, None]}[r.kind]
    out += [(w, "type", f"{key} as {json.dumps(w)}") for w in wrong_type]
    if r.kind in ("integer", "number"):
        step = _step(r)
        for bound, sign, what in ((r.type_lo, -1, "below"), (r.type_hi, 1, "above")):
            if bound is not None:
                out.append((_beyond(r, bound, sign), "type_range", f"{key} {what} its {r.field.type} range"))
        if r.const is not None:
            for c in (0, max(pm.any_plan.command_values) + 1):
                out.append((c, "cmd", f"cmd {c}: no such command"))
        elif r.enum is not None:
            values = sorted(int(e.value) for e in r.enum.values)
            gaps = [v for v in range(values[0], values[-1]) if v not in values][:2]
            for v in sorted({values[0] - 1, values[-1] + 1, *gaps}):
                if _in_type(r, Fraction(v)):
                    out.append((v, "enum", f"{key}={v}: not a documented value"))
        elif r.has_range:
            sentinels = {s.value for s in r.sentinels}
            for bound, sign in ((r.lo, -1), (r.hi, 1)):
                if bound is None:
                    continue
                v = Fraction(bound) + sign * step
                while v in sentinels:
                    v += sign * step
                if _in_type(r, v):
                    out.append((_num(v) if r.kind == "integer" else float(v), "range", f"{key}={float(v)!r}: outside the documented range"))
    if r.kind == "string":
        if r.field.max_length is not None:
            out.append(("N" * (r.field.max_length + 1), "length", f"{key} longer than {r.field.max_length} character(s)"))
        if r.field.min_length:
            out.append(("", "length", f"{key} empty"))
        if r.enum is not None:
            values = [e.value for e in r.enum.values]
            others = {e.value for mm in pm.messages for rr in mm.rules if rr.enum is not None and rr.key == key for e in rr.enum.values} - set(values)
            for v in sorted(others) + [v for v in ("X", "n") if v not in values]:
                out.append((v, "enum", f"{key}={v!r}: not a value of this message" + (" (J04: only status reports '-')" if v == "-" else "")))
    return out


class _Cases:
    def __init__(self, pm: ProtocolModel):
        self.pm = pm
        self.cases: list[dict[str, Any]] = []
        self.plans = {p.receiver: p for p in pm.plans}

    def add(self, mm: MessageModel, obj: Any, kind: str, note: str, field: str | None = None, rule: str | None = None) -> None:
        m = mm.message
        problems = jsonvalue.message_problems(m, obj)
        valid = not problems
        if valid != (rule is None):
            raise AssertionError(f"{m.name} {note}: expected {'valid' if rule is None else rule}, the reference checker says {problems or 'valid'}")
        if field and not any(p.startswith(f"{field}:") for p in problems):
            raise AssertionError(f"{m.name} {note}: fault expected in {field}, the reference checker says {problems}")
        case: dict[str, Any] = {"id": f"{m.name}/{kind}/{len(self.cases)}", "message": m.name, "receiver": m.receiver, "valid": valid,
                                "kind": kind, "note": note, "json": obj}
        for label, receiver in (("as_received", m.receiver), ("as_any", None)):
            chosen = jsonmodel.select(self.plans[receiver], obj)
            ok = chosen is not None and not jsonvalue.message_problems(self.pm.protocol.message(chosen), obj)
            case[label] = chosen if ok else None
        if valid and (case["as_received"] != m.name or case["as_any"] != m.name):
            raise AssertionError(f"{m.name} {note}: a valid message is read as {case['as_received']} / {case['as_any']}")
        if not valid:
            case["field"] = field
            case["rule"] = rule
        self.cases.append(case)


def protocol_cases(pm: ProtocolModel) -> list[dict[str, Any]]:
    c = _Cases(pm)
    for mm in pm.messages:
        m = mm.message
        base = dict(m.examples[0])
        for i, ex in enumerate(m.examples):
            c.add(mm, dict(ex), "example", f"document example {i + 1}")
        for r in mm.rules:
            for value, kind, note in valid_values(r):
                c.add(mm, {**base, r.key: value}, kind, note)
            if r.kind == "integer" and isinstance(base[r.key], int):
                # JSON has one number type: 9120.0 is the integer 9120 (JSON Schema's rule, and every binding's).
                c.add(mm, {**base, r.key: float(base[r.key])}, "integral_float", f"{r.key} written as {float(base[r.key])!r}")
        for r in mm.rules:
            missing = {k: v for k, v in base.items() if k != r.key}
            note = f"{r.key} missing"
            if m.role == "reply" and r.key != "res":
                note = f"reply without its request's {r.key}" if r.key in ("cmd", "bn") else f"reply without {r.key}"
            c.add(mm, missing, "missing", note, r.key, "required")
            for value, rule, vnote in invalid_values(r, pm):
                c.add(mm, {**base, r.key: value}, "invalid", vnote, r.key, rule)
        c.add(mm, {**base, "extra": 1}, "extra", "unknown key", "extra", "unexpected")
        case_key = {"Extra": 1} if "extra" not in base else {"X": 1}
        c.add(mm, {**base, **case_key}, "extra", "unknown key differing from a field only by case", next(iter(case_key)), "unexpected")
    first = pm.messages[0]
    for value in ([], "text", None, 1):
        c.add(first, copy.deepcopy(value), "not_object", f"{json.dumps(value)} is not a JSON object", "", "object")
    return c.cases


def build_vectors(spec: ir.Spec) -> dict[str, Any]:
    protocols = []
    for protocol in spec.json:
        pm = jsonmodel.model(protocol)
        protocols.append({"protocol": protocol.name, "version": protocol.version, "cases": protocol_cases(pm)})
    return {
        "format": VECTOR_FORMAT,
        "spec": spec.name,
        "sha256": spec.sha256,
        "generated_by": f"canspec {spec.generator_version}",
        "rules": {
            "valid": "verdict against the case's own message schema / binding",
            "as_received": "message the receiver's schema (to_<receiver>) / binding reads the case as; null: rejected",
            "as_any": "message the whole-protocol schema / binding reads the case as; null: rejected",
            "field": "JSON key at fault (\"\": the value is not an object)",
            "rule": "one of " + ", ".join(jsonmodel.ERROR_CODES),
            "numbers": "JSON numbers compare by value: 0 and 0.0 are the same number",
        },
        "protocols": protocols,
    }


def render_vectors(spec: ir.Spec) -> dict[str, bytes]:
    if not spec.json:
        return {}
    text = json.dumps(build_vectors(spec), indent=1, sort_keys=True, ensure_ascii=False) + "\n"
    return {"vectors/json.json": text.encode("utf-8")}


TARGET = Target("json_vectors", "shared JSON-protocol test vectors", "vectors/", render_vectors, order=21)
