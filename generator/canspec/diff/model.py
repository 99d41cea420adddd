"""The comparison model: what two revisions are compared on, independent of where they came
from. A field that a source cannot express (a DBC has no Chinese names) is None and is not
compared, so a DBC and a spec can be diffed without noise."""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.diff.attributes import Values, effective, protocol
from canspec.ir.bits import LITTLE, describe, positions
from canspec.ir.dbc_attributes import DbcAttributeDef
from canspec.ir.mux import Ranges
from canspec.spec.problems import Loc

# Value-table entries that only mark a raw value as unused ("保留") are not a meaning.
_RESERVED_LABELS = ("保留", "预留")


@dataclass(frozen=True)
class Entry:
    """One value-table entry or special value: identifier and (when known) the printed label."""

    name: str
    label: str | None


@dataclass(frozen=True)
class SignalModel:
    name: str
    start: int
    length: int
    signed: bool
    factor: Fraction
    offset: Fraction
    unit: str
    minimum: Fraction
    maximum: Fraction
    role: str  # data | counter | checksum
    values: dict[int, Entry] | None  # None: not an enumerated signal
    values_table: str | None  # the table's name (spec only): generated enum types are named after it
    specials: dict[int, Entry]
    zh: str | None
    desc: str | None
    loc: Loc | None = None
    byte_order: str = LITTLE  # little_endian (Intel: start is the LSB) | big_endian (Motorola: start is the MSB)
    is_float: bool = False  # an IEEE 754 field (the raw value is its bit pattern)
    mux: tuple[str, Ranges] | None = None  # multiplexed: its multiplexer and the raw values that select it (ir/mux.py)
    is_multiplexer: bool = False
    receivers: tuple[str, ...] | None = None  # the nodes that read it where not all its message's receivers do (a DBC's SG_ receivers)
    attributes: Values | None = None  # the source DBC's own attributes (diff/attributes.py); None: not compared
    documented: tuple[Fraction, Fraction] | None = None  # the range as the source states it (minimum/maximum: what the field carries of it)

    @property
    def positions(self) -> tuple[int, ...]:
        """The frame bits of value bits 0 (LSB) .. length - 1, in either byte order."""
        return positions(self.start, self.length, self.byte_order)

    @property
    def bits(self) -> frozenset[int]:
        return frozenset(self.positions)

    def span(self) -> str:
        if self.byte_order != LITTLE:
            return f"Motorola, start bit {self.start}: {describe(self.start, self.length, self.byte_order)}"
        end = self.start + self.length - 1
        return f"bit {self.start}" if self.length == 1 else f"bits {self.start}..{end}"


@dataclass(frozen=True)
class MessageModel:
    frame_id: int
    extended: bool
    name: str
    title: str | None
    zh: str | None
    dlc: int
    cycle_ms: int | None
    sender: str | None
    receivers: tuple[str, ...] | None
    signals: tuple[SignalModel, ...]  # data, counter and checksum signals; reserved bits are not signals
    checksum: tuple[str, int, tuple[int, ...]] | None  # (algorithm, byte, covered bytes), spec only
    multiframe: tuple[object, ...] | None
    loc: Loc | None = None
    fd: bool = False  # a CAN FD frame (FDF)
    brs: bool | None = False  # bit-rate switching of an FD frame; None: the source does not say
    desc: str | None = None  # None: the source's description is not compared (see diff/fromdb.py)
    attributes: Values | None = None  # the source DBC's own attributes (diff/attributes.py); None: not compared

    @property
    def used_bits(self) -> frozenset[int]:
        return frozenset(b for s in self.signals for b in s.bits)

    def signal(self, name: str) -> SignalModel | None:
        return next((s for s in self.signals if s.name == name), None)


@dataclass(frozen=True)
class NodeModel:
    """A node of the bus, by the name its DBC writes; what it does is its messages' senders and receivers."""

    name: str
    desc: str | None  # printed name, Chinese name and description; None: not compared (a database against a spec)
    loc: Loc | None = None


@dataclass(frozen=True)
class ProtocolModel:
    source: str  # what the user passed, for the report
    kind: str  # "spec" | "dbc"
    name: str
    version: str | None
    messages: tuple[MessageModel, ...]
    changelog: ir.Changelog | None = None  # the revision's own change record (spec only): what it declares
    bitrate: int | None = None  # the bus's (arbitration) bit rate; None: the source does not say (an import's assumption)
    data_bitrate: int | None = None  # the CAN FD data phase's; None: none, or not said
    attributes: Values | None = None  # the network's and nodes' own DBC attributes (diff/attributes.py); None: not compared
    nodes: tuple[NodeModel, ...] = ()

    def by_id(self, frame_id: int) -> MessageModel | None:
        return next((m for m in self.messages if m.frame_id == frame_id), None)

    def by_name(self, name: str) -> MessageModel | None:
        return next((m for m in self.messages if m.name == name), None)

    @property
    def label(self) -> str:
        return f"{self.name} {self.version}" if self.version else self.name


def meaningful_entries(entries: dict[int, Entry]) -> dict[int, Entry]:
    """Drop placeholder entries (`reserved_3: 保留`): a reserved raw value carries no meaning. A DBC's
    label is its own text (`RESERVED`) where a spec's name is lower case: one placeholder either way."""
    return {
        raw: e for raw, e in entries.items()
        if not (e.name.lower() == "reserved" or e.name.lower().startswith("reserved_") or (e.label or "").strip() in _RESERVED_LABELS)
    }


def _signal(sig: ir.Signal, defs: tuple[DbcAttributeDef, ...]) -> SignalModel:
    values = None
    if sig.value_table is not None:
        values = {e.raw: Entry(e.name, e.label_zh) for e in sig.value_table.entries}
    desc = " / ".join(t for t in (sig.desc, sig.desc_zh) if t)
    return SignalModel(
        name=sig.name, start=sig.start, length=sig.length, signed=sig.signed, factor=sig.factor, offset=sig.offset,
        # a float's range: the documented one, else every finite value (its raw range is a bit pattern's)
        unit=sig.unit, minimum=sig.check_min if sig.is_float else sig.phys_min, maximum=sig.check_max if sig.is_float else sig.phys_max,
        role=sig.role, values=values,
        values_table=sig.value_table.name if sig.value_table is not None else None,
        specials={s.raw: Entry(s.name, s.label_zh) for s in sig.specials}, zh=sig.zh, desc=desc, loc=sig.loc,
        byte_order=sig.byte_order, is_float=sig.is_float, mux=(sig.mux.by, sig.mux.ranges) if sig.mux is not None else None,
        is_multiplexer=sig.is_multiplexer, receivers=tuple(sorted(sig.receivers)) if sig.receivers is not None else None,
        attributes=effective(defs, "signal", sig.dbc_attributes),
        documented=(sig.doc_min, sig.doc_max) if sig.doc_min is not None and sig.doc_max is not None else None,
    )


def from_spec(spec: ir.Spec, source: str) -> ProtocolModel:
    messages = []
    defs = spec.can.dbc_attribute_defs if spec.can is not None else ()
    for msg in spec.can.messages if spec.can is not None else ():
        checksum = (msg.checksum.algorithm, msg.checksum.byte, msg.checksum.covers) if msg.checksum else None
        mf = msg.multiframe
        multiframe = (mf.index_signal, mf.payload_signal, mf.encoding, mf.text_length, mf.frames, mf.padding) if mf else None
        messages.append(
            MessageModel(
                frame_id=msg.frame_id, extended=msg.is_extended, name=msg.name, title=msg.title, zh=msg.zh, dlc=msg.dlc,
                cycle_ms=msg.cycle_ms, sender=msg.sender, receivers=tuple(sorted(msg.receivers)),
                signals=tuple(_signal(s, defs) for s in msg.signals if not s.is_reserved), checksum=checksum,
                multiframe=multiframe, loc=msg.loc, fd=msg.is_fd, brs=msg.brs, desc=msg.desc, attributes=effective(defs, "message", msg.dbc_attributes),
            )
        )
    name = spec.can.name if spec.can is not None else spec.name
    version = spec.can.version if spec.can is not None else spec.version
    bus = spec.can.bus if spec.can is not None else None
    rates = (bus.bitrate, bus.data_bitrate) if bus is not None else (None, None)
    attributes = protocol(spec.can) if spec.can is not None else None
    nodes = tuple(_node(n) for n in spec.can.nodes) if spec.can is not None else ()
    return ProtocolModel(source, "spec", name, version, tuple(messages), spec.changelog, *rates, attributes, nodes)


def _node(node: ir.Node) -> NodeModel:
    label = node.label if node.label != node.name else ""
    return NodeModel(node.dbc_name or node.name, " / ".join(t for t in (label, node.zh, node.desc) if t), node.loc)
