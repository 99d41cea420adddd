"""What the JSON protocol page's cells say."""

from __future__ import annotations

import json
from typing import Any

from canspec import ir
from canspec.render.literals import num
from canspec.targets.docs.cells import cell
from canspec.targets.docs.lang import Lang


def json_range(field: ir.JsonField) -> str:
    if field.json_type == "string":
        if field.min_length is not None or field.max_length is not None:
            shortest, longest = field.min_length, field.max_length
            return f"length {shortest if shortest is not None else 0} … {longest if longest is not None else '∞'}"
        return ""
    if field.min is not None or field.max is not None:
        lo = num(field.min) if field.min is not None else _type_bound(field.type_min)
        hi = num(field.max) if field.max is not None else _type_bound(field.type_max)
        return f"{lo} … {hi}"
    if field.type_min is not None and field.type_max is not None:
        return f"{_type_bound(field.type_min)} … {_type_bound(field.type_max)} (type)"
    return ""


def _type_bound(value: float | None) -> str:
    if value is None:
        return "—"
    return repr(value) if isinstance(value, float) else str(value)


def _enum_text(e: ir.JsonEnumValue, lang: Lang) -> str:
    return f"`{json.dumps(e.value, ensure_ascii=False)}` = " + " ".join(t for t in (lang.only_zh(e.label_zh), e.label) if t)


def json_values(field: ir.JsonField, lang: Lang) -> str:
    parts = [_enum_text(e, lang) for e in field.enum]
    parts += [f"{_enum_text(e, lang)} ({lang.en_zh('sentinel', '哨兵值')})" for e in field.sentinels]
    return "<br>".join(cell(p) for p in parts)


def json_example(example: dict[str, Any]) -> str:
    return json.dumps(example, ensure_ascii=False)


def json_pairs(proto: ir.JsonProtocol) -> list[tuple[ir.JsonMessage, ir.JsonMessage]]:
    return [(proto.message(m.reply_to), m) for m in proto.messages if m.reply_to is not None]


def party_label(proto: ir.JsonProtocol, name: str, lang: Lang) -> str:
    party = next((p for p in proto.parties if p.name == name), None)
    return f"{party.zh} {name}" if party is not None and lang.zh and party.zh else name
