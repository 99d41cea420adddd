"""A loaded source (cantools' database) as a canspec spec: plain data, in the spec's own syntax,
with a warning for every decision a source did not make for us."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from canspec.diff.dbcimport import written_numbers
from canspec.importer.attributes import kept_definitions, kept_values
from canspec.importer.load import Loaded
from canspec.importer.names import Namer, identifier
from canspec.ir.bits import positions
from canspec.ir.encoding import raw_range
from canspec.ir.fd import FD_LENGTHS
from canspec.ir.ids import DBC_EXTENDED_FLAG

DEFAULT_BITRATE = 500_000
DEFAULT_DATA_BITRATE = 2_000_000
NO_NODE = "Vector__XXX"
SIG_TYPE_ROLES = {"MessageCounter": "counter", "MessageChecksum": "checksum"}


@dataclass
class Report:
    warnings: list[tuple[str, int | None, str]] = field(default_factory=list)  # (source, line, text)

    def warn(self, source: str, line: int | None, text: str) -> None:
        self.warnings.append((source, line, text))


def _attr(obj: Any, name: str) -> Any:
    attrs = getattr(getattr(obj, "dbc", None), "attributes", None) or {}
    return getattr(attrs.get(name), "value", None)


def _lines(text: str | None) -> dict[tuple[int, str], int]:
    """(BO_ ID as written, signal name or '') → 1-based line of its BO_ / SG_ line."""
    out: dict[tuple[int, str], int] = {}
    frame = None
    for i, line in enumerate((text or "").split("\n"), 1):
        words = line.split()
        if len(words) >= 3 and words[0] == "BO_" and words[1].isdigit():
            frame = int(words[1])
            out[(frame, "")] = i
        elif frame is not None and len(words) >= 2 and words[0] == "SG_":
            out[(frame, words[1])] = i
    return out


def _number(value: Fraction) -> int | Fraction:
    return value.numerator if value.denominator == 1 else value


def _bus(loaded: Loaded, report: Report) -> dict[str, Any]:
    db = loaded.db
    rate = _attr(db, "Baudrate") or next((b.baudrate for b in db.buses if getattr(b, "baudrate", None)), None)
    if not rate:
        rate = DEFAULT_BITRATE
        report.warn(loaded.source, None, f"no bit rate given: {rate // 1000} kbit/s assumed")
    extended = Counter(bool(m.is_extended_frame) for m in db.messages)
    orders = Counter(s.byte_order for m in db.messages for s in m.signals)
    bus: dict[str, Any] = {
        "bitrate": int(rate),
        "id_format": "extended" if extended[True] > extended[False] else "standard",
        "addressing": "none",
        "byte_order": "big_endian" if orders["big_endian"] > orders["little_endian"] else "little_endian",
    }
    data_rate = _attr(db, "BaudrateCANFD") or next((b.fd_baudrate for b in db.buses if getattr(b, "fd_baudrate", None)), None)
    if data_rate:
        bus["data_bitrate"] = int(data_rate)
    elif any(m.is_fd and _brs(m) for m in db.messages):
        bus["data_bitrate"] = DEFAULT_DATA_BITRATE
        report.warn(loaded.source, None, f"CAN FD frames switch bit rate but no data bit rate is given: {DEFAULT_DATA_BITRATE // 1000} kbit/s assumed")
    return bus


def _brs(msg: Any) -> bool:
    value = _attr(msg, "CANFD_BRS")
    return True if value is None else str(value) in ("1", "True")


def build_spec(loaded: Loaded, report: Report) -> dict[str, Any]:
    db = loaded.db
    bus = _bus(loaded, report)
    kept = kept_definitions(loaded, lambda text: report.warn(loaded.source, None, text))
    nodes = _nodes(loaded, report, kept)
    spec: dict[str, Any] = {"schema_version": 1, "kind": "can_protocol", "protocol": _protocol(loaded), "bus": bus, "nodes": list(nodes.values())}
    tables: dict[str, dict[int, str]] = {}
    messages, names = [], Namer()
    written, lines = written_numbers(loaded.text or ""), _lines(loaded.text)
    for msg in sorted(db.messages, key=lambda m: (m.frame_id, m.name)):
        converted = _message(loaded, msg, bus, names, tables, written, lines, report, kept)
        if converted is not None:
            messages.append(_node_names(converted, nodes))
    if tables:
        spec["value_tables"] = tables
    if kept:
        spec["dbc_attributes"] = kept
    spec["messages"] = messages
    return spec


def _node_names(msg: dict[str, Any], nodes: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """The source's node names in a converted message as the spec's; a signal's receivers only where
    they are not its message's."""
    msg["sender"] = nodes[msg["sender"]]["name"] if msg["sender"] != "ALL" else "ALL"
    msg["receivers"] = sorted({nodes[r]["name"] for r in msg["receivers"]} - {msg["sender"]})
    if "dbc_senders" in msg:
        msg["dbc_senders"] = [nodes[s]["name"] for s in msg["dbc_senders"]]
    for sig in msg["signals"]:
        own = sorted(nodes[r]["name"] for r in sig.pop("receivers"))
        if own != msg["receivers"]:
            sig["receivers"] = own
            if "dbc_attributes" in sig:  # keep the attributes last on the line
                sig["dbc_attributes"] = sig.pop("dbc_attributes")
    return msg


NODE_NAME = __import__("re").compile(r"^[A-Za-z][A-Za-z0-9_]*$")


def _nodes(loaded: Loaded, report: Report, kept: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Source node name → the spec's node: BU_'s nodes, then those only senders and receivers name."""
    db, out, taken = loaded.db, {}, set()

    def add(name: str, comment: str | None) -> None:
        ident = name if NODE_NAME.match(name) and name != "ALL" else "N" + __import__("re").sub(r"\W", "_", name)
        while ident in taken:
            ident += "_"
        taken.add(ident)
        out[name] = {"name": ident, **({"dbc_name": name} if ident != name else {}), **({"desc": str(comment)} if comment else {})}

    for node in db.nodes:
        if node.name != NO_NODE and node.name not in out:
            add(node.name, node.comment)
            if values := kept_values(node, kept, lambda text: report.warn(loaded.source, None, text), f"node {node.name}"):
                out[node.name]["dbc_attributes"] = values
    used = sorted({s for m in db.messages for s in m.senders} | {r for m in db.messages for sig in m.signals for r in sig.receivers})
    for name in used:
        if name != NO_NODE and name not in out:
            report.warn(loaded.source, None, f"node {name} sends or receives but is not declared in BU_: added")
            add(name, None)
    return out


def _protocol(loaded: Loaded) -> dict[str, Any]:
    from pathlib import PurePath

    version = (getattr(loaded.db, "version", None) or "").strip()
    name = identifier(PurePath(loaded.source).stem, "imported")
    if " " in version:  # canspec writes VERSION "<protocol> <version>"
        name, version = identifier(version.rsplit(" ", 1)[0], name), version.rsplit(" ", 1)[1]
    parts = version.split(".")
    if not (len(parts) == 3 and all(p.isdigit() for p in parts)):
        version = "0.0.0"
    return {"name": name, "version": version, "title": PurePath(loaded.source).name, "dbc_as_imported": True}


def _message(loaded: Loaded, msg: Any, bus: dict[str, Any], names: Namer, tables: dict[str, dict[int, str]],
             written: dict[tuple[int, str], tuple[Fraction, Fraction, Fraction, Fraction]], lines: dict[tuple[int, str], int],
             report: Report, kept: dict[str, dict[str, Any]]) -> dict[str, Any] | None:
    dbc_id = msg.frame_id | DBC_EXTENDED_FLAG if msg.is_extended_frame else msg.frame_id
    line = lines.get((dbc_id, ""))
    source_name = loaded.renamed.get(msg.name, msg.name)
    if msg.is_multiplexed():
        report.warn(loaded.source, line, f"message {source_name} is multiplexed: left out (canspec import does not read multiplexing yet)")
        return None
    if msg.length not in FD_LENGTHS:
        report.warn(loaded.source, line, f"message {source_name} has {msg.length} bytes, not a CAN frame length: left out")
        return None
    name = names.name(source_name, f"message_{msg.frame_id:x}")
    out: dict[str, Any] = {"name": name}
    if name != source_name:
        out["dbc_name"] = source_name
    out["id"] = msg.frame_id
    if bool(msg.is_extended_frame) != (bus["id_format"] == "extended"):
        out["extended"] = bool(msg.is_extended_frame)
    senders = [s for s in msg.senders if s != NO_NODE]
    out["sender"] = senders[0] if senders else "ALL"
    if len(senders) > 1:  # BO_TX_BU_: the DBC keeps them all, the other targets know the first
        out["dbc_senders"] = senders[1:]
    receivers = sorted({r for s in msg.signals for r in s.receivers if r != NO_NODE} - {out["sender"]})
    out["receivers"] = receivers
    if msg.cycle_time:
        out["cycle_ms"] = int(msg.cycle_time)
    out["dlc"] = msg.length
    if msg.length > 8 and not msg.is_fd:
        report.warn(loaded.source, line, f"message {source_name} has {msg.length} bytes but no CAN FD frame format: taken as CAN FD")
    if msg.is_fd or msg.length > 8:
        out["fd"] = True
        if not _brs(msg):
            out["brs"] = False
    if msg.comment:
        out["desc"] = str(msg.comment)
    out["signals"] = _signals(loaded, msg, bus["byte_order"], dbc_id, source_name, name, tables, written, lines, report, kept)
    if not out["signals"] and msg.length:
        out["layout_undefined"] = True
    if values := kept_values(msg, kept, lambda text: report.warn(loaded.source, line, text), f"message {source_name}"):
        out["dbc_attributes"] = values
    return out


def _signals(loaded: Loaded, msg: Any, default_order: str, dbc_id: int, source_msg: str, msg_name: str, tables: dict[str, dict[int, str]],
             written: dict[tuple[int, str], tuple[Fraction, Fraction, Fraction, Fraction]], lines: dict[tuple[int, str], int],
             report: Report, kept: dict[str, dict[str, Any]]) -> list[dict[str, Any]]:
    out, names, owners = [], Namer(), {}
    for sig in msg.signals:  # in the file's order: the first of two overlapping signals stays
        source_name = loaded.renamed.get(sig.name, sig.name)
        line = lines.get((dbc_id, sig.name))
        if not 1 <= sig.length <= 64:
            report.warn(loaded.source, line, f"signal {source_name} of {source_msg} is {sig.length} bits long: left out (a field has 1 to 64 bits)")
            continue
        bits = positions(sig.start, sig.length, sig.byte_order)
        if any(b >= 8 * msg.length for b in bits):
            report.warn(loaded.source, line, f"signal {source_name} of {source_msg} leaves its {msg.length}-byte frame: left out")
            continue
        clash = sorted({owners[b] for b in bits if b in owners})
        if clash:
            report.warn(loaded.source, line, f"signal {source_name} of {source_msg} overlaps {', '.join(clash)}: left out (a field owns its bits)")
            continue
        owners.update((b, source_name) for b in bits)
        converted = _signal(loaded, sig, default_order, names, written.get((dbc_id, sig.name)), f"{msg_name}_", tables, line, report)
        converted["receivers"] = [r for r in sig.receivers if r != NO_NODE]  # the spec's names and whether to keep them: _node_names
        if values := kept_values(sig, kept, lambda text, at=line: report.warn(loaded.source, at, text), f"signal {sig.name} of {source_msg}"):
            converted["dbc_attributes"] = values
        out.append(converted)
    return out


def _signal(loaded: Loaded, sig: Any, default_order: str, names: Namer, numbers: tuple[Fraction, Fraction, Fraction, Fraction] | None, table_prefix: str,
            tables: dict[str, dict[int, str]], line: int | None, report: Report) -> dict[str, Any]:
    source_name = loaded.renamed.get(sig.name, sig.name)
    name = names.name(source_name, "signal")
    out: dict[str, Any] = {"name": name}
    if name != source_name:
        out["dbc_name"] = source_name
    out["start"], out["len"] = sig.start, sig.length
    if sig.byte_order != default_order:
        out["byte_order"] = sig.byte_order
    if sig.is_float:
        out["float"] = True
    elif sig.is_signed:
        out["signed"] = True
    factor, offset, lo, hi = numbers if numbers is not None else (
        Fraction(str(sig.scale)), Fraction(str(sig.offset)), Fraction(str(sig.minimum or 0)), Fraction(str(sig.maximum or 0)))
    if not sig.is_float:
        if factor != 1:
            out["factor"] = _number(factor)
        if offset != 0:
            out["offset"] = _number(offset)
    elif factor != 1 or offset != 0:
        report.warn(loaded.source, line, f"float signal {source_name} is scaled ({factor}, {offset}): scaling dropped (a float field holds its value)")
    if not (lo == hi == 0):
        lo, hi = min(lo, hi), max(lo, hi)
        if not sig.is_float and factor and raw_range(sig.length, bool(sig.is_signed), factor, offset, (lo, hi))[0] > \
                raw_range(sig.length, bool(sig.is_signed), factor, offset, (lo, hi))[1]:
            report.warn(loaded.source, line, f"signal {source_name}: range [{_number(lo)}|{_number(hi)}] holds no value of the field: dropped")
        else:
            out["range"] = [_number(lo), _number(hi)]
    if sig.unit:
        out["unit"] = str(sig.unit)
    if sig.comment:
        out["desc"] = str(sig.comment)
    choices = _choices(loaded, sig, source_name, line, report)
    if choices:
        table, labels = f"{table_prefix}{name}", Namer()
        tables[table] = {raw: _label(labels.name(text, f"value_{raw}"), text) for raw, text in choices}
        out["values"] = table
    role = SIG_TYPE_ROLES.get(str(_sig_type(loaded, sig)))
    if role is not None:
        out["role"] = role
    return out


def _label(ident: str, text: str) -> str | dict[str, str]:
    """A value label: the identifier, with the source's own text where that differs."""
    return ident if ident == text else {"name": ident, "dbc": text}


def _sig_type(loaded: Loaded, sig: Any) -> Any:
    value = _attr(sig, "SigType")
    definitions = getattr(getattr(loaded.db, "dbc", None), "attribute_definitions", None) or {}
    choices = getattr(definitions.get("SigType"), "choices", None)
    return choices[value] if isinstance(value, int) and choices and 0 <= value < len(choices) else value


def _choices(loaded: Loaded, sig: Any, source_name: str, line: int | None, report: Report) -> list[tuple[int, str]]:
    """The value table's entries that fit the field; the others dropped with a warning."""
    if sig.choices and sig.is_float:
        report.warn(loaded.source, line, f"float signal {source_name} has value labels: dropped (a float field has no value table)")
    if not sig.choices or sig.is_float:
        return []
    lo, hi = (-(1 << (sig.length - 1)), (1 << (sig.length - 1)) - 1) if sig.is_signed else (0, (1 << sig.length) - 1)
    kept = []
    for raw, value in sorted(sig.choices.items()):
        if lo <= int(raw) <= hi:
            kept.append((int(raw), str(getattr(value, "name", value))))
        else:
            report.warn(loaded.source, line, f"value {raw} of signal {source_name} does not fit its {sig.length} bits: dropped")
    return kept
