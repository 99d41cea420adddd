"""What a spec keeps only for its DBC (ir/dbc_attributes.py, written by `canspec import`): the
source's own attribute definitions and values as `BA_DEF_` / `BA_DEF_DEF_` / `BA_` texts, and
whether canspec's own `GenMsgSendType` is written."""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir.dbc_attributes import REPLACEABLE, Attributes, AttributeValue, DbcAttributeDef
from canspec.render.literals import dbc_string


@dataclass(frozen=True)
class KeptDefinition:
    keyword: str  # "", "BU_", "BO_", "SG_"
    name: str
    type_text: str  # `INT 0 255`, `ENUM "a","b"`, `STRING`
    default: str | None  # the BA_DEF_DEF_ value as written


def number(value: AttributeValue | None) -> str:
    return repr(value) if isinstance(value, float) else str(value)


def value_text(d: DbcAttributeDef, value: AttributeValue) -> str:
    """A value as a BA_ line writes it: an ENUM's index, a STRING quoted, a number as is."""
    if d.type == "ENUM":
        return str(d.values.index(str(value)))
    return dbc_string(str(value)) if d.type == "STRING" else number(value)


def _type_text(d: DbcAttributeDef) -> str:
    if d.type == "ENUM":
        return "ENUM " + ",".join(dbc_string(v) for v in d.values)
    if d.type == "STRING":
        return "STRING "  # as Vector's tools write it: `STRING ;`
    return " ".join([d.type, number(d.minimum if d.minimum is not None else 0), number(d.maximum if d.maximum is not None else 0)])


def definitions(can: ir.CanProtocol) -> tuple[KeptDefinition, ...]:
    out = []
    for d in can.dbc_attribute_defs:
        default = None if d.default is None else dbc_string(str(d.default)) if d.type in ("STRING", "ENUM") else number(d.default)
        out.append(KeptDefinition(d.keyword, d.name, _type_text(d), default))
    return tuple(out)


def values(can: ir.CanProtocol, attributes: Attributes) -> tuple[tuple[str, str], ...]:
    """(name, value as written) of one object's kept attributes."""
    defs = {d.name: d for d in can.dbc_attribute_defs}
    return tuple((name, value_text(defs[name], v)) for name, v in attributes)


def network_values(can: ir.CanProtocol) -> tuple[tuple[str, str], ...]:
    return tuple((d.name, value_text(d, d.value)) for d in can.dbc_attribute_defs if d.object == "network" and d.value is not None)


def own(can: ir.CanProtocol) -> frozenset[str]:
    """Which of the replaceable attributes (ir.dbc_attributes.REPLACEABLE) the DBC target writes itself:
    those the spec does not define, and none as imported (a source without them keeps none)."""
    return frozenset() if can.dbc_as_imported else frozenset(REPLACEABLE) - {d.name for d in can.dbc_attribute_defs}
