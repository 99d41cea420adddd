"""Match two protocol models and list their differences, one `Change` each.

Messages are matched by frame ID, then by name (an ID change). Signals within a matched
message are matched by name, then by bit position (a rename), then by printed Chinese name
(a rename that also moved) — so a renamed or moved signal is reported as
such, not as a removal plus an addition. Reserved bits are not signals: a signal appearing in
bits that were reserved or unused is compatible."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from fractions import Fraction

from canspec.diff import attributes
from canspec.diff.classes import KINDS, LADDER
from canspec.diff.model import (
    Entry,
    MessageModel,
    ProtocolModel,
    SignalModel,
    meaningful_entries,
)
from canspec.ir.mux import ranges_text
from canspec.spec.problems import Loc

BUS = -1  # Change.frame_id of a change of the whole bus (its bit rates), which no message holds


def subject(frame_id: int) -> str:
    """The frame ID as printed, or `bus` for a change of the whole bus."""
    return "bus" if frame_id == BUS else f"0x{frame_id:08X}"


def declared_frame_id(message: int | str) -> int:
    """A changelog entry's `message` (a frame ID, or `bus` for a change of the whole bus) as Change.frame_id."""
    return BUS if message == "bus" else int(message)


@dataclass(frozen=True)
class Change:
    kind: str
    cls: str
    frame_id: int
    message: str
    signal: str | None
    detail: str
    old: object = None
    new: object = None
    loc: Loc | None = field(default=None, compare=False)  # where in the NEW spec (or old, if removed)
    position: int = field(default=-1, compare=False)  # start bit of the signal, for ordering

    @property
    def subject(self) -> str:
        return subject(self.frame_id)

    def as_json(self) -> dict:  # type: ignore[type-arg]
        return {
            "kind": self.kind, "class": self.cls, "frame_id": self.subject, "message": self.message,
            "signal": self.signal, "detail": self.detail, "old": _plain(self.old), "new": _plain(self.new),
        }


def _plain(value: object) -> object:
    if isinstance(value, Fraction):
        return int(value) if value.denominator == 1 else float(value)
    if isinstance(value, (tuple, list)):
        return [_plain(v) for v in value]
    return value


def num(value: Fraction | None) -> str:
    if value is None:
        return "-"
    if value.denominator == 1:
        return str(value.numerator)
    text = f"{float(value):.10g}"
    return text


class _Collector:
    def __init__(self) -> None:
        self.changes: list[Change] = []

    def add(self, kind: str, msg: MessageModel, sig: SignalModel | None, detail: str, old: object = None, new: object = None, cls: str | None = None) -> None:
        loc = (sig.loc if sig is not None else None) or msg.loc
        self.changes.append(
            Change(kind, cls or KINDS[kind], msg.frame_id, msg.name, sig.name if sig else None, detail, old, new, loc, sig.start if sig else -1)
        )


def _range(c: _Collector, msg: MessageModel, o: SignalModel, n: SignalModel) -> None:
    """The values a field carries of its range (narrowed: wire, widened: compatible), else the range as stated (docs)."""
    if (o.minimum, o.maximum) != (n.minimum, n.maximum):
        widened = n.minimum <= o.minimum and n.maximum >= o.maximum
        c.add(
            "signal_range_changed",
            msg,
            n,
            f"range [{num(o.minimum)}, {num(o.maximum)}] → [{num(n.minimum)}, {num(n.maximum)}]" + (" (widened)" if widened else ""),
            [o.minimum, o.maximum],
            [n.minimum, n.maximum],
            cls="compatible" if widened else "wire",
        )
    elif _beyond(o) and _beyond(n) and o.documented != n.documented:
        # the same values on the wire: only the stated range moved, beyond what the field carries on both sides (a side
        # that states just what the field carries may be a DBC canspec wrote, which states no more: not compared)
        assert o.documented is not None and n.documented is not None
        (olo, ohi), (nlo, nhi) = o.documented, n.documented
        carried = f"the field carries [{num(n.minimum)}, {num(n.maximum)}] of it either way"
        detail = f"documented range [{num(olo)}, {num(ohi)}] → [{num(nlo)}, {num(nhi)}] ({carried})"
        c.add("signal_range_changed", msg, n, detail, [olo, ohi], [nlo, nhi], cls="docs")


def _beyond(sig: SignalModel) -> bool:
    """The source states a range the field does not carry all of."""
    return sig.documented is not None and sig.documented != (sig.minimum, sig.maximum)


def _both(a: object, b: object) -> bool:
    return a is not None and b is not None


def _entries(c: _Collector, msg: MessageModel, sig: SignalModel, what: str, old: dict[int, Entry], new: dict[int, Entry]) -> None:
    kind = "value" if what == "value" else "special"
    for raw in sorted(set(old) | set(new)):
        o, n = old.get(raw), new.get(raw)
        if o is None and n is not None:
            c.add(f"{kind}_added", msg, sig, f"{what} {raw} = {n.name}" + (f" ({n.label})" if n.label else ""), None, n.name)
        elif n is None and o is not None:
            c.add(f"{kind}_removed", msg, sig, f"{what} {raw} = {o.name} removed", o.name, None)
        elif o is not None and n is not None:
            if _both(o.label, n.label) and o.label != n.label:
                c.add(
                    f"{kind}_relabelled",
                    msg,
                    sig,
                    f"{what} {raw}: {o.label} → {n.label}" + (f" ({o.name} → {n.name})" if o.name != n.name else ""),
                    o.label,
                    n.label,
                )
            elif o.name != n.name:
                c.add(f"{kind}_renamed", msg, sig, f"{what} {raw}: {o.name} → {n.name}", o.name, n.name)


def _signal_pair(c: _Collector, msg: MessageModel, o: SignalModel, n: SignalModel) -> None:
    if o.name != n.name:
        c.add("signal_renamed", msg, n, f"{o.name} → {n.name}", o.name, n.name)
    # The wire is the value bits' frame positions: a byte-aligned byte (or a single bit) is the same
    # field in either order, and a byte-order change is reported as that, its start bits with it.
    same_wire = o.positions == n.positions
    if o.byte_order != n.byte_order and not same_wire:
        c.add("signal_byte_order_changed", msg, n, f"byte order {_ORDER[o.byte_order]} → {_ORDER[n.byte_order]} (start bit {o.start} → {n.start})",
              o.byte_order, n.byte_order)
    elif o.start != n.start and not same_wire:
        c.add("signal_moved", msg, n, f"start bit {o.start} → {n.start}", o.start, n.start)
    if o.length != n.length:
        c.add("signal_resized", msg, n, f"length {o.length} → {n.length} bits", o.length, n.length)
    if (o.factor, o.offset) != (n.factor, n.offset):
        c.add(
            "signal_rescaled",
            msg,
            n,
            f"factor/offset {num(o.factor)}/{num(o.offset)} → {num(n.factor)}/{num(n.offset)}",
            [o.factor, o.offset],
            [n.factor, n.offset],
        )
    if o.signed != n.signed and o.is_float == n.is_float:  # integer ↔ float (a float's sign is its own): reported below
        c.add("signal_signedness_changed", msg, n, f"{'signed' if o.signed else 'unsigned'} → {'signed' if n.signed else 'unsigned'}", o.signed, n.signed)
    if o.is_float != n.is_float:
        c.add("signal_float_changed", msg, n, f"{_number_type(o)} → {_number_type(n)}", o.is_float, n.is_float)
    if (o.mux, o.is_multiplexer) != (n.mux, n.is_multiplexer):
        c.add("signal_mux_changed", msg, n, f"{_presence(o)} → {_presence(n)}", _presence(o), _presence(n))
    if o.unit != n.unit:
        c.add("signal_unit_changed", msg, n, f"unit {o.unit or '(none)'} → {n.unit or '(none)'}", o.unit, n.unit)
    if o.is_float == n.is_float:  # integer ↔ float: reported above
        _range(c, msg, o, n)
    if o.role != n.role:
        c.add("signal_role_changed", msg, n, f"role {o.role} → {n.role}", o.role, n.role)
    if _both(o.values_table, n.values_table) and o.values_table != n.values_table:
        c.add("signal_values_table_renamed", msg, n, f"value table {o.values_table} → {n.values_table}", o.values_table, n.values_table)
    if o.values is not None or n.values is not None:
        _entries(c, msg, n, "value", meaningful_entries(o.values or {}), meaningful_entries(n.values or {}))
    _entries(c, msg, n, "special", o.specials, n.specials)
    for name, a, b in attributes.changed(o.attributes or (), n.attributes or ()) if _both(o.attributes, n.attributes) else ():
        c.add("signal_attribute_changed", msg, n, attributes.text(name, a, b), a, b)
    if _both(o.zh, n.zh) and o.zh != n.zh:
        c.add("signal_label_changed", msg, n, f"name as printed {o.zh} → {n.zh}", o.zh, n.zh)
    if _both(o.desc, n.desc) and o.desc != n.desc:
        c.add("signal_description_changed", msg, n, "description changed", o.desc, n.desc)


def _receivers(c: _Collector, om: MessageModel, nm: MessageModel, o: SignalModel, n: SignalModel) -> None:
    """A signal's readers: its own list (a DBC's SG_ receivers), else its message's. Said only where a
    revision gives the signal a list of its own: the message's list alone is message_receivers_changed."""
    if o.receivers is None and n.receivers is None:
        return
    old = o.receivers if o.receivers is not None else om.receivers
    new = n.receivers if n.receivers is not None else nm.receivers
    if old is not None and new is not None and set(old) != set(new):
        c.add("signal_receivers_changed", nm, n, f"receivers {', '.join(old) or '(none)'} → {', '.join(new) or '(none)'}", old, new)


_ORDER = {"little_endian": "Intel (little-endian)", "big_endian": "Motorola (big-endian)"}


def _presence(sig: SignalModel) -> str:
    """`present while mode = 1, 4…6`, `in every frame`; `multiplexer, ...` for a multiplexer."""
    when = f"present while {sig.mux[0]} = {ranges_text(sig.mux[1])}" if sig.mux is not None else "in every frame"
    return f"multiplexer, {when}" if sig.is_multiplexer else when


def _number_type(sig: SignalModel) -> str:
    if sig.is_float:
        return f"IEEE float{sig.length}"
    return "signed integer" if sig.signed else "unsigned integer"


def _same_bits(o: SignalModel, n: SignalModel) -> bool:
    return (o.start, o.length) == (n.start, n.length) or o.positions == n.positions


def _page(sig: SignalModel) -> object:
    return (sig.mux[1] if sig.mux is not None else None, sig.is_multiplexer)


def _match_signals(old: MessageModel, new: MessageModel) -> tuple[list[tuple[SignalModel, SignalModel]], list[SignalModel], list[SignalModel]]:
    pairs: list[tuple[SignalModel, SignalModel]] = []
    left_old, left_new = list(old.signals), list(new.signals)

    def take(pred) -> None:  # type: ignore[no-untyped-def]
        for o in list(left_old):
            cands = [n for n in left_new if pred(o, n)]
            if len(cands) == 1:
                pairs.append((o, cands[0]))
                left_old.remove(o)
                left_new.remove(cands[0])

    take(lambda o, n: o.name == n.name)
    # Fields of different pages may share bits: the one of the same page first (its values; the
    # multiplexer's name may be what was renamed), then bits alone.
    take(lambda o, n: _same_bits(o, n) and _page(o) == _page(n))
    take(_same_bits)
    take(lambda o, n: bool(o.zh) and o.zh == n.zh)
    return pairs, left_old, left_new


def _message_pair(c: _Collector, o: MessageModel, n: MessageModel, both_specs: bool) -> None:
    if (o.frame_id, o.extended) != (n.frame_id, n.extended):
        c.add("message_id_changed", n, None, f"frame ID {_id(o)} → {_id(n)}", o.frame_id, n.frame_id)
    if o.name != n.name:
        c.add("message_renamed", n, None, f"{o.name} → {n.name}", o.name, n.name)
    if o.dlc != n.dlc:
        c.add("message_dlc_changed", n, None, f"DLC {o.dlc} → {n.dlc}", o.dlc, n.dlc)
    if o.fd != n.fd:
        c.add("message_fd_changed", n, None, f"frame format {_frame_format(o.fd)} → {_frame_format(n.fd)}", o.fd, n.fd)
    elif o.fd and _both(o.brs, n.brs) and o.brs != n.brs:
        c.add("message_brs_changed", n, None, f"bit-rate switching {'on' if o.brs else 'off'} → {'on' if n.brs else 'off'}", o.brs, n.brs)
    if o.cycle_ms != n.cycle_ms:  # None is a statement too: event-driven (a spec) or no GenMsgCycleTime (a DBC)
        c.add("message_cycle_changed", n, None, f"cycle {_cycle(o)} → {_cycle(n)}", o.cycle_ms, n.cycle_ms)
    if _both(o.sender, n.sender) and o.sender != n.sender:
        c.add("message_sender_changed", n, None, f"sender {o.sender} → {n.sender}", o.sender, n.sender)
    if _both(o.receivers, n.receivers) and o.receivers != n.receivers:
        c.add("message_receivers_changed", n, None, f"receivers {', '.join(o.receivers or ())} → {', '.join(n.receivers or ())}", o.receivers, n.receivers)
    if both_specs and o.checksum != n.checksum:
        c.add("message_checksum_changed", n, None, f"checksum {_checksum_text(o)} → {_checksum_text(n)}", None, None)
    if both_specs and o.multiframe != n.multiframe:
        c.add("message_multiframe_changed", n, None, "multi-frame text layout changed", _plain(o.multiframe), _plain(n.multiframe))
    for name, a, b in attributes.changed(o.attributes or (), n.attributes or ()) if _both(o.attributes, n.attributes) else ():
        c.add("message_attribute_changed", n, None, attributes.text(name, a, b), a, b)
    if _both(o.desc, n.desc) and o.desc != n.desc:
        c.add("message_description_changed", n, None, "description changed", o.desc, n.desc)
    for attr in ("title", "zh"):
        a, b = getattr(o, attr), getattr(n, attr)
        if _both(a, b) and a != b:
            c.add("message_title_changed", n, None, f"{'title' if attr == 'title' else 'name as printed'} {a} → {b}", a, b)
    pairs, removed, added = _match_signals(o, n)
    old_used = o.used_bits
    for sig in removed:
        c.add("signal_removed", n, sig, f"{sig.name} ({sig.span()}) removed", sig.name, None)
    for sig in added:
        free = not (sig.bits & old_used) and max(sig.bits) < o.dlc * 8
        where = "in formerly reserved bits" if free else "over bits that carried another signal"
        c.add("signal_added", n, sig, f"{sig.name} ({sig.span()}) added {where}", None, sig.name, cls="compatible" if free else "wire")
    # A page names its multiplexer: a renamed multiplexer is the same one (signal_renamed says it), not
    # another page for every field it selects.
    renamed = {a.name: b.name for a, b in pairs}
    for a, b in pairs:
        if a.mux is not None:
            a = replace(a, mux=(renamed.get(a.mux[0], a.mux[0]), a.mux[1]))
        _signal_pair(c, n, a, b)
        _receivers(c, o, n, a, b)


def _id(m: MessageModel) -> str:
    """With its format: 0x100 as an 11-bit and as a 29-bit ID are two frames."""
    return f"0x{m.frame_id:08X} (29-bit)" if m.extended else f"0x{m.frame_id:03X} (11-bit)"


def _cycle(m: MessageModel) -> str:
    return "event-driven" if m.cycle_ms is None else f"{m.cycle_ms} ms"


def _frame_format(fd: bool) -> str:
    return "CAN FD" if fd else "classic CAN"


def _checksum_text(m: MessageModel) -> str:
    if m.checksum is None:
        return "none"
    alg, byte, covers = m.checksum
    return f"{alg} of bytes {covers[0]}..{covers[-1]} in byte {byte}"


def _bus(c: _Collector, old: ProtocolModel, new: ProtocolModel) -> None:
    """Every node of a bus runs at its bit rates: another (arbitration or FD data phase) rate is a
    wire break for the whole bus. A rate a source does not state (None) is not compared. The
    network's and nodes' own attributes belong to no message either."""
    for what, a, b in (("bit rate", old.bitrate, new.bitrate), ("CAN FD data bit rate", old.data_bitrate, new.data_bitrate)):
        if _both(a, b) and a != b:
            detail = f"{what} {_rate(a)} → {_rate(b)}"
            c.changes.append(Change("bus_bitrate_changed", KINDS["bus_bitrate_changed"], BUS, "(bus)", None, detail, a, b))
    for name, a, b in attributes.changed(old.attributes or (), new.attributes or ()) if _both(old.attributes, new.attributes) else ():
        c.changes.append(Change("network_attribute_changed", KINDS["network_attribute_changed"], BUS, "(bus)", None, attributes.text(name, a, b), a, b))


def _nodes(c: _Collector, old: ProtocolModel, new: ProtocolModel) -> None:
    """Nodes by name (a rename reads as one removed and one added, as a DBC's BU_ line says no more);
    a description is compared where both sides state one."""
    a, b = {n.name: n for n in old.nodes}, {n.name: n for n in new.nodes}
    for name in sorted(set(a) | set(b)):
        o, n = a.get(name), b.get(name)
        if n is None:
            kind, detail, before, after = "node_removed", f"node {name} removed", name, None
        elif o is None:
            kind, detail, before, after = "node_added", f"node {name} added", None, name
        elif _both(o.desc, n.desc) and o.desc != n.desc:
            kind, detail, before, after = "node_description_changed", f"node {name}: description {o.desc!r} → {n.desc!r}", o.desc, n.desc
        else:
            continue
        c.changes.append(Change(kind, KINDS[kind], BUS, "(bus)", None, detail, before, after, (n or o).loc))


def _rate(rate: int | None) -> str:
    return "none" if rate is None else f"{rate / 1000:g} kbit/s"


def compare(old: ProtocolModel, new: ProtocolModel) -> list[Change]:
    c = _Collector()
    _bus(c, old, new)
    _nodes(c, old, new)
    both_specs = old.kind == new.kind == "spec"
    pairs: list[tuple[MessageModel, MessageModel]] = []
    left_old = list(old.messages)
    left_new = list(new.messages)
    for key in (lambda m: m.frame_id, lambda m: m.name):
        for o in list(left_old):
            n = next((x for x in left_new if key(x) == key(o)), None)
            if n is not None:
                pairs.append((o, n))
                left_old.remove(o)
                left_new.remove(n)
    for o in left_old:
        c.add("message_removed", o, None, f"{o.name} removed", o.name, None)
    for n in left_new:
        c.add("message_added", n, None, f"{n.name} added ({len(n.signals)} signals)", None, n.name)
    for o, n in pairs:
        _message_pair(c, o, n, both_specs)
    kind_order = list(KINDS)
    return sorted(c.changes, key=lambda ch: (ch.frame_id, ch.message, ch.position, ch.signal or "", kind_order.index(ch.kind), LADDER.index(ch.cls), ch.detail))
