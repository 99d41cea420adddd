"""The JSON protocol's IR (ir.JsonProtocol) from its loaded document: messages, their fields with
the bounds of their types, enums, sentinels and examples as plain JSON values."""

from __future__ import annotations

import math
from collections.abc import Callable
from decimal import Decimal
from fractions import Fraction
from typing import Any

from canspec import ir
from canspec.ir.names import humanize
from canspec.spec.resolve import label_pair
from canspec.spec.yamlsource import LocDict


def _enum(table: LocDict | None) -> tuple[ir.JsonEnumValue, ...]:
    if not table:
        return ()
    return tuple(ir.JsonEnumValue(v, ident, zh, humanize(ident), table.key_locs.get(v)) for v, (ident, zh) in ((v, label_pair(p)) for v, p in table.items()))


def _json_field(key: str, fdef: LocDict, types: LocDict) -> ir.JsonField:
    t = types[fdef["type"]]
    rng = fdef.get("range")

    def bound(v: Any, inward: Callable[[Fraction], int]) -> int | float | None:
        if v is None:
            return None
        return int(inward(Fraction(v))) if t["json"] == "integer" else float(v)  # an integer type's bounds: the integers within

    return ir.JsonField(
        name=fdef.get("name", key),  # a shared field may give its binding identifier
        json_name=fdef.get("json_name", key),
        type=fdef["type"],
        json_type=t["json"],
        type_min=bound(t.get("min"), math.ceil),
        type_max=bound(t.get("max"), math.floor),
        min=Fraction(rng[0]) if rng else None,
        max=Fraction(rng[1]) if rng else None,
        decimals=fdef.get("decimals"),
        unit=fdef.get("unit", ""),
        enum=_enum(fdef.get("enum")),
        sentinels=_enum(fdef.get("sentinel")),
        min_length=t.get("min_length"),
        max_length=t.get("max_length"),
        zh=fdef.get("zh", ""),
        desc=fdef.get("desc", ""),
        desc_zh=fdef.get("desc_zh", ""),
        errata=tuple(fdef.get("errata", ())),
        loc=fdef.loc,
        type_loc=types.loc_of(fdef["type"]),
    )


def plain(value: Any) -> Any:
    """LocDict/Decimal → plain JSON-able Python values (JSON examples, changelog changes)."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    if isinstance(value, Decimal):
        return float(value)
    return value


def build_json(doc: Any) -> ir.JsonProtocol:
    data = doc.data
    shared, types = data.get("fields", {}), data["types"]
    messages = []
    for m in data["messages"]:
        fields = []
        for ref in m["fields"]:
            if isinstance(ref, str):
                fields.append(_json_field(ref, shared[ref], types))
            else:
                fields.append(_json_field(ref["name"], ref, types))
        messages.append(
            ir.JsonMessage(
                name=m["name"], zh=m.get("zh", ""), desc=m.get("desc", ""), cmd=m.get("cmd"), role=m.get("role"), reply_to=m.get("reply_to"),
                sender=m["from"], receiver=m["to"], fields=tuple(fields), examples=tuple(plain(e) for e in m.get("examples", [])), loc=m.loc,
            )
        )
    p = data["protocol"]
    return ir.JsonProtocol(
        name=p["name"], title=p.get("title", p["name"]), title_zh=p.get("title_zh", ""), version=str(p["version"]),
        parties=tuple(ir.JsonParty(x["name"], x.get("zh", ""), x.get("desc", "")) for x in data["parties"]),
        messages=tuple(messages), errata=tuple(p.get("errata", ())), loc=p.loc_of("name"),
    )
