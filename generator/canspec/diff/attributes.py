"""A source DBC's own attributes (the spec's `dbc_attributes`, ir/dbc_attributes.py) as diff compares
them: each object's effective values — its BA_ value, else its definition's BA_DEF_DEF_ default — so a
changed default is a change of every object that has no value of its own. canspec interprets none of
them; it carries them, and tools and gateways act on them (GenMsgSendType, GenSigStartValue): a change
is compatible, not docs. The attributes canspec computes from the spec (bit rates, frame format, cycle
time, signal type) are compared as those fields, not here."""

from __future__ import annotations

from canspec.ir.dbc_attributes import Attributes, AttributeValue, DbcAttributeDef
from canspec.ir.protocol_model import CanProtocol

Values = tuple[tuple[str, AttributeValue], ...]  # (name, effective value), by name


def effective(defs: tuple[DbcAttributeDef, ...], obj: str, own: Attributes) -> Values:
    """An object's (`network`, `node`, `message`, `signal`) values: its own, else the defaults."""
    values = {d.name: d.default for d in defs if d.object == obj and d.default is not None}
    values.update(dict(own))
    return tuple(sorted(values.items()))


def protocol(can: CanProtocol) -> Values:
    """The network's values and its nodes' (`NodeLayer of ECU2`), one list: what no message holds."""
    network = effective(can.dbc_attribute_defs, "network", tuple((d.name, d.value) for d in can.dbc_attribute_defs if d.value is not None))
    nodes = [(f"{name} of node {n.dbc_name or n.name}", v) for n in can.nodes for name, v in effective(can.dbc_attribute_defs, "node", n.dbc_attributes)]
    return network + tuple(sorted(nodes))


def changed(old: Values, new: Values) -> list[tuple[str, AttributeValue | None, AttributeValue | None]]:
    """(name, old value, new value) of each attribute whose value differs (None: it has none)."""
    a, b = dict(old), dict(new)
    return [(name, a.get(name), b.get(name)) for name in sorted(set(a) | set(b)) if a.get(name) != b.get(name)]


def text(name: str, old: AttributeValue | None, new: AttributeValue | None) -> str:
    return f"attribute {name} {_value(old)} → {_value(new)}"


def _value(v: AttributeValue | None) -> str:
    return "(none)" if v is None else repr(v) if isinstance(v, str) else f"{v:g}" if isinstance(v, float) else str(v)
