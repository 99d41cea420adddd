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
import itertools
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


def _beyond(r: FieldRule, bound: float, sign: int) -> int | float | None:
    """A value just outside a type bound: one step for integers and small bounds; 3% for huge
    float bounds (±3.4e38), where one decimal step vanishes in the double; None when only
    infinity lies beyond."""
    if r.kind == "number" and abs(bound) > 1e15:
        beyond = float(bound) * 1.03
        return beyond if abs(beyond) != float("inf") else None
    return _num(Fraction(bound) + sign * _step(r))


def _in_type(r: FieldRule, v: Fraction) -> bool:
    return (r.type_lo is None or v >= Fraction(r.type_lo)) and (r.type_hi is None or v <= Fraction(r.type_hi))


def _free(taken: set[str], *candidates: str) -> str:
    """The first candidate key that is not taken (then the first with underscores appended)."""
    return next((c for c in candidates if c not in taken), None) or _free(taken, *(c + "_" for c in candidates))


def _bounds(r: FieldRule) -> tuple[Any, Any]:
    """The documented range within the type's."""
    lo = r.type_lo if r.lo is None else (r.lo if r.type_lo is None else max(r.lo, r.type_lo))
    hi = r.type_hi if r.hi is None else (r.hi if r.type_hi is None else min(r.hi, r.type_hi))
    return lo, hi


def valid_values(r: FieldRule) -> list[tuple[Any, str, str]]:
    """(value, kind, note) for one field."""
    key = r.key
    if r.const is not None:
        return []
    if r.kind == "boolean":
        return [(True, "boundary", f"{key}=true"), (False, "boundary", f"{key}=false")]
    if r.enum is not None:
        return [(e.value, "enum", f"{key}={e.name}") for e in r.enum.values]
    if r.kind == "string":
        f = r.field
        return [("x" * n, "boundary", f"{key} of {n} character(s)") for n in dict.fromkeys((f.min_length or 0, f.max_length)) if n is not None]
    out: list[tuple[Any, str, str]] = []
    lo, hi = _bounds(r)
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


def _enum_outsiders(values: list[int]) -> list[int]:
    """Integers next to an enum's values: below, above, and the first two missing between them."""
    gaps = [v for a, b in itertools.pairwise(values) for v in range(a + 1, min(b, a + 3))][:2]
    return sorted({values[0] - 1, values[-1] + 1, *gaps})


def _number_invalid(r: FieldRule, pm: ProtocolModel) -> list[tuple[Any, str, str]]:
    key, out = r.key, list[tuple[Any, str, str]]()
    for bound, sign, what in ((r.type_lo, -1, "below"), (r.type_hi, 1, "above")):
        beyond = None if bound is None else _beyond(r, bound, sign)
        if beyond is not None:
            out.append((beyond, "type_range", f"{key} {what} its {r.field.type} range"))
    if r.const is not None:
        known = pm.any_plan.command_values
        for c in (0, max(known) + 1):
            if c != r.const and _in_type(r, Fraction(c)):
                out.append((c, "cmd", f"cmd {c}: no such command" if c not in known else f"cmd {c}: another command's"))
    elif r.enum is not None:
        for v in _enum_outsiders(sorted(int(e.value) for e in r.enum.values)):
            if _in_type(r, Fraction(v)):
                out.append((v, "enum", f"{key}={v}: not a documented value"))
    elif r.has_range:
        sentinels = {s.value for s in r.sentinels}
        for bound, sign in ((r.lo, -1), (r.hi, 1)):
            if bound is None:
                continue
            x = Fraction(bound) + sign * _step(r)
            while x in sentinels:
                x += sign * _step(r)
            if _in_type(r, x):
                out.append((_num(x) if r.kind == "integer" else float(x), "range", f"{key}={float(x)!r}: outside the documented range"))
    return out


def _string_invalid(r: FieldRule, pm: ProtocolModel) -> list[tuple[Any, str, str]]:
    key, f, out = r.key, r.field, []
    if f.max_length is not None:
        out.append(("N" * (f.max_length + 1), "length", f"{key} longer than {f.max_length} character(s)"))
    if f.min_length:
        out.append(("", "length", f"{key} empty"))
    if r.enum is not None:
        values = [e.value for e in r.enum.values]
        elsewhere: dict[Any, list[str]] = {}
        for mm in pm.messages:
            for rr in mm.rules:
                if rr.enum is not None and rr.key == key:
                    for e in rr.enum.values:
                        elsewhere.setdefault(e.value, []).append(mm.name)
        for v in sorted(set(elsewhere) - set(values)) + [v for v in ("X", "n") if v not in values]:
            if jsonvalue.type_fault(f, v) is None:
                owners = f" (only {', '.join(elsewhere[v])} has it)" if v in elsewhere else ""
                out.append((v, "enum", f"{key}={v!r}: not a value of this message{owners}"))
    return out


def invalid_values(r: FieldRule, pm: ProtocolModel) -> list[tuple[Any, str, str]]:
    """(value, rule, note) for one field."""
    wrong_types: dict[str, list[Any]] = {"integer": ["1", 1.5, None], "number": ["1", None, True], "boolean": [1, "true", None], "string": [1, None]}
    wrong_type = wrong_types[r.kind]
    out: list[tuple[Any, str, str]] = [(w, "type", f"{r.key} as {json.dumps(w)}") for w in wrong_type]
    if r.kind in ("integer", "number"):
        out += _number_invalid(r, pm)
    if r.kind == "string":
        out += _string_invalid(r, pm)
    return out


class _Cases:
    def __init__(self, pm: ProtocolModel):
        self.pm = pm
        self.cases: list[dict[str, Any]] = []
        self.plans = {p.receiver: p for p in pm.plans}

    def add(self, mm: MessageModel, obj: Any, kind: str, note: str, field: str | None = None, rule: str | None = None) -> None:
        """One case; the reference checker must find exactly the fault intended (`field`, `rule`) first."""
        m, protocol = mm.message, self.pm.protocol
        faults = jsonvalue.message_faults(m, obj)
        got = (faults[0].key, faults[0].code) if faults else None
        if got != (None if rule is None else (field, rule)):
            raise AssertionError(
                f"{m.name} {note}: expected {rule and (field, rule) or 'valid'}, the reference checker says {[f.text for f in faults] or 'valid'}"
            )
        case: dict[str, Any] = {"id": f"{m.name}/{kind}/{len(self.cases)}", "message": m.name, "receiver": m.receiver, "valid": not faults,
                                "kind": kind, "note": note, "json": obj}
        for label, receiver in (("as_received", m.receiver), ("as_any", None)):
            chosen = jsonvalue.select(protocol, self.plans[receiver], obj)
            ok = chosen is not None and not jsonvalue.message_faults(protocol.message(chosen), obj)
            case[label] = chosen if ok else None
        if not faults and (case["as_received"] is None or case["as_any"] is None):  # messages with the same keys: read as the first that fits
            raise AssertionError(f"{m.name} {note}: a valid message is rejected by a reader ({case['as_received']} / {case['as_any']})")
        if faults:
            case["field"] = field
            case["rule"] = rule
        self.cases.append(case)


def _base(mm: MessageModel) -> dict[str, Any]:
    """The message's first example, or one made of a value each field accepts."""
    if mm.message.examples:
        return dict(mm.message.examples[0])
    return {r.key: r.const if r.const is not None else jsonvalue.sample(r.field)[0] for r in mm.rules}


def _message_cases(c: _Cases, mm: MessageModel) -> None:
    m = mm.message
    base = _base(mm)
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
        if m.role == "reply" and r.key != jsonmodel.RESULT_KEY:
            note = f"reply without its request's {r.key}" if r.key in (jsonmodel.CMD_KEY, jsonmodel.MATCH_KEY) else f"reply without {r.key}"
        c.add(mm, missing, "missing", note, r.key, "required")
        for value, rule, vnote in invalid_values(r, c.pm):
            c.add(mm, {**base, r.key: value}, "invalid", vnote, r.key, rule)
    extra = _free(set(base), "extra")
    c.add(mm, {**base, extra: 1}, "extra", "unknown key", extra, "unexpected")
    cased = _free(set(base) | {extra}, "Extra", "X")
    c.add(mm, {**base, cased: 1}, "extra", "unknown key differing from a field only by case", cased, "unexpected")


def protocol_cases(pm: ProtocolModel) -> list[dict[str, Any]]:
    c = _Cases(pm)
    for mm in pm.messages:
        _message_cases(c, mm)
    not_objects: tuple[Any, ...] = ([], "text", None, 1) if pm.messages else ()
    for value in not_objects:
        c.add(pm.messages[0], copy.deepcopy(value), "not_object", f"{json.dumps(value)} is not a JSON object", "", "object")
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
