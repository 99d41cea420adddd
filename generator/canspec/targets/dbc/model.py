"""The DBC's view of the protocol: every name, number, comment and attribute value the template
writes, decided here (the template only lays the lines out)."""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir.ids import DBC_EXTENDED_FLAG
from canspec.render.environment import header_lines
from canspec.targets.dbc import attributes, comments, kept, naming

UNKNOWN_NODE = "Vector__XXX"  # a DBC's "no node": sender ALL, or no receiver


@dataclass(frozen=True)
class DbcSignal:
    name: str  # in the DBC
    spec_name: str | None  # the spec's name where the DBC renamed the signal (naming.py), else None
    sig: ir.Signal
    sig_type: int
    comment: str
    receivers: str  # its own (ir.Signal.receivers), else its message's
    kept: tuple[tuple[str, str], ...]  # the source's own attributes (kept.py)
    as_imported: bool  # ir.CanProtocol.dbc_as_imported

    @property
    def byte_order(self) -> int:
        """The DBC's @0 (Motorola) or @1 (Intel)."""
        return 0 if self.sig.is_big_endian else 1

    @property
    def mux_marker(self) -> str:
        """After the name: ` M` a multiplexer, ` mN` a field of the page N (its lowest value), ` mNM` both
        (extended multiplexing); SG_MUL_VAL_ gives every value where one number cannot (Dbc.mux_values)."""
        page = f" m{self.sig.mux.first}" if self.sig.mux is not None else ""
        return page + ("M" if page else " M") if self.sig.is_multiplexer else page

    @property
    def valtype(self) -> int:
        """SIG_VALTYPE_: 1 float32, 2 float64, 0 an integer."""
        return attributes.SIG_VALTYPES[self.sig.length] if self.sig.is_float else 0

    @property
    def bounds(self) -> tuple[object, object]:
        """[min|max]: the physical range the encoders accept. [0|0] is the DBC's "no range", so a float
        without a documented range writes it, and a field whose only allowed value is 0 writes its
        documented range instead."""
        sig = self.sig
        if self.as_imported and sig.doc_min is not None:  # the source's own [min|max], as it wrote it
            return sig.doc_min, sig.doc_max
        if sig.is_float:
            return (0, 0) if sig.doc_min is None else (sig.check_min, sig.check_max)
        if sig.phys_min == sig.phys_max == 0 and sig.doc_min is not None:
            return sig.doc_min, sig.doc_max
        return sig.phys_min, sig.phys_max


@dataclass(frozen=True)
class DbcMessage:
    msg: ir.Message
    dbc_id: int  # the frame ID, with bit 31 set for a 29-bit identifier
    sender: str
    senders: str  # BO_TX_BU_'s list where the spec gives further senders (ir.Message.dbc_senders), else ""
    receivers: str
    comment: str
    vframe_format: int
    send_type: int
    signals: tuple[DbcSignal, ...]
    kept: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class DbcNode:
    node: ir.Node
    comment: str
    kept: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class Dbc:
    can: ir.CanProtocol
    comment: str
    nodes: tuple[DbcNode, ...]
    messages: tuple[DbcMessage, ...]
    protocol_type: str  # "J1939" on a J1939 bus, else ""
    default_vframe_format: str
    kept_definitions: tuple[kept.KeptDefinition, ...]
    kept_values: tuple[tuple[str, str], ...]  # the network's
    own: frozenset[str]  # the replaceable attributes it writes itself (kept.own)

    @property
    def vframe_formats(self) -> tuple[str, ...]:
        return attributes.VFRAME_FORMATS_FD if self.can.has_fd else attributes.VFRAME_FORMATS

    @property
    def bus_type(self) -> str:
        return "CAN FD" if self.can.has_fd else "CAN"

    @property
    def floats(self) -> tuple[tuple[DbcMessage, DbcSignal], ...]:
        return tuple((m, s) for m in self.messages for s in m.signals if s.valtype)

    @property
    def mux_values(self) -> tuple[tuple[DbcMessage, DbcSignal, str, str], ...]:
        """SG_MUL_VAL_ lines (message, field, its multiplexer's DBC name, "lo-hi, lo-hi"): for every
        multiplexed field of a message with extended multiplexing or a page of more than one value,
        where a reader takes each field's values from these lines alone (as cantools writes them)."""
        out = []
        for m in self.messages:
            if not _needs_mux_values(m.msg):
                continue
            names = {s.sig.name: s.name for s in m.signals}
            for s in m.signals:
                if s.sig.mux is not None:
                    out.append((m, s, names[s.sig.mux.by], ", ".join(f"{lo}-{hi}" for lo, hi in s.sig.mux.ranges)))
        return tuple(out)

    @property
    def renamed(self) -> tuple[tuple[DbcMessage, DbcSignal], ...]:
        return tuple((m, s) for m in self.messages for s in m.signals if s.spec_name is not None)


def _needs_mux_values(msg: ir.Message) -> bool:
    return len(msg.multiplexers) > 1 or any(s.mux is not None and not s.mux.is_single for s in msg.signals)


def dbc_id(msg: ir.Message) -> int:
    return msg.frame_id | DBC_EXTENDED_FLAG if msg.is_extended else msg.frame_id


def _message(can: ir.CanProtocol, msg: ir.Message, names: dict[tuple[str, str], str]) -> DbcMessage:
    node = {n.name: n.dbc_name for n in can.nodes}
    receivers = ",".join(node.get(r, r) for r in msg.receivers) or UNKNOWN_NODE
    signals = []
    for sig in msg.data_signals:
        name = names[(msg.name, sig.name)]
        spec_name = sig.name if name != sig.dbc_name else None
        own = receivers if sig.receivers is None else ",".join(node.get(r, r) for r in sig.receivers) or UNKNOWN_NODE
        signals.append(DbcSignal(name, spec_name, sig, attributes.sig_type(msg, sig), comments.signal_comment(sig, spec_name, can.dbc_as_imported),
                                 own, kept.values(can, sig.dbc_attributes), can.dbc_as_imported))
    sender = UNKNOWN_NODE if msg.sender == "ALL" else node.get(msg.sender, msg.sender)
    return DbcMessage(
        msg=msg, dbc_id=dbc_id(msg), sender=sender, senders=",".join([sender, *(node.get(s, s) for s in msg.dbc_senders)]) if msg.dbc_senders else "",
        receivers=receivers, comment=comments.message_comment(msg, can.dbc_as_imported), vframe_format=attributes.vframe_format(can.bus, msg),
        send_type=attributes.send_type(msg), signals=tuple(signals), kept=kept.values(can, msg.dbc_attributes),
    )


def network_comment(spec: ir.Spec, messages: tuple[DbcMessage, ...]) -> str:
    text = " ".join(header_lines(spec, "dbc"))
    if any(s.spec_name is not None for m in messages for s in m.signals):
        text += (f". Signal names: a name the spec gives different definitions in different messages is written <name>_<frame ID> "
                 f"(at most {naming.MAX_NAME} characters) in each of them; attribute {naming.SPEC_NAME_ATTRIBUTE} holds the spec's name.")
    return text


def build(spec: ir.Spec, can: ir.CanProtocol) -> Dbc:
    names = naming.signal_names(can)
    messages = tuple(_message(can, msg, names) for msg in can.messages)
    if can.bus.is_j1939:
        default_vframe = "J1939PG"
    else:
        default_vframe = "ExtendedCAN" if can.bus.id_format == "extended" else "StandardCAN"
    return Dbc(
        can=can, comment=network_comment(spec, messages),
        nodes=tuple(DbcNode(n, comments.node_comment(n), kept.values(can, n.dbc_attributes)) for n in can.nodes),
        messages=messages, protocol_type="J1939" if can.bus.is_j1939 else "", default_vframe_format=default_vframe,
        kept_definitions=kept.definitions(can), kept_values=kept.network_values(can), own=kept.own(can),
    )
