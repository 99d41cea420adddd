"""A loaded source (cantools' database) as a canspec spec: plain data, in the spec's own syntax,
with a warning for every decision a source did not make for us."""

from __future__ import annotations

import math
import re
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

from canspec.importer.attributes import kept_definitions, kept_values
from canspec.importer.dbctext import Numbers, written_numbers
from canspec.importer.load import Loaded
from canspec.importer.names import Namer, identifier
from canspec.importer.signals import NO_NODE, Where, attribute, convert_signals
from canspec.ir.fd import FD_LENGTHS
from canspec.ir.ids import DBC_EXTENDED_FLAG

DEFAULT_BITRATE = 500_000
DEFAULT_DATA_BITRATE = 2_000_000


@dataclass
class Report:
    warnings: list[tuple[str, int | None, str]] = field(default_factory=list)  # (source, line, text)

    def warn(self, source: str, line: int | None, text: str) -> None:
        self.warnings.append((source, line, text))


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


def _bus(loaded: Loaded, report: Report) -> dict[str, Any]:
    db = loaded.db
    rate = attribute(db, "Baudrate") or next((b.baudrate for b in db.buses if getattr(b, "baudrate", None)), None)
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
    data_rate = attribute(db, "BaudrateCANFD") or next((b.fd_baudrate for b in db.buses if getattr(b, "fd_baudrate", None)), None)
    if data_rate:
        bus["data_bitrate"] = int(data_rate)
    elif any(m.is_fd and _brs(m, db) for m in db.messages):
        bus["data_bitrate"] = DEFAULT_DATA_BITRATE
        report.warn(loaded.source, None, f"CAN FD frames switch bit rate but no data bit rate is given: {DEFAULT_DATA_BITRATE // 1000} kbit/s assumed")
    _bus_type(loaded, report)
    return bus


def _bus_type(loaded: Loaded, report: Report) -> None:
    """The DBC target writes BusType from the frames ("CAN FD" when a message is an FD frame): a file
    whose BusType says otherwise loses it, and says so (`canspec diff` reads files through here)."""
    stated = str(attribute(loaded.db, "BusType") or "").strip()
    written = "CAN FD" if any(m.is_fd for m in loaded.db.messages) else "CAN"
    if stated in ("CAN", "CAN FD") and stated != written:
        report.warn(loaded.source, None, f'BusType is "{stated}", but {"a" if written == "CAN FD" else "no"} message is a CAN FD frame: '
                                         f'the spec keeps the frames, and its DBC says "{written}"')


def _brs(msg: Any, db: Any) -> bool:
    value = attribute(msg, "CANFD_BRS", db)
    return True if value is None else str(value) in ("1", "True")


def build_spec(loaded: Loaded, report: Report) -> dict[str, Any]:
    db = loaded.db
    bus = _bus(loaded, report)
    kept = kept_definitions(loaded, lambda text: report.warn(loaded.source, None, text))
    nodes = _nodes(loaded, report, kept)
    spec: dict[str, Any] = {"schema_version": 1, "kind": "can_protocol", "protocol": _protocol(loaded), "bus": bus, "nodes": list(nodes.values())}
    tables: dict[str, dict[int, Any]] = {}
    messages, names = [], Namer(tuple(loaded.renamed.get(m.name, m.name) for m in db.messages))
    written, lines = written_numbers(loaded.text or ""), _lines(loaded.text)
    seen: dict[tuple[int, bool], str] = {}
    for msg in sorted(db.messages, key=lambda m: (m.frame_id, m.name)):
        key, name = (msg.frame_id, bool(msg.is_extended_frame)), loaded.renamed.get(msg.name, msg.name)
        if key in seen:  # a KCD or ARXML file of several buses: a spec is one bus
            report.warn(loaded.source, None, f"message {name} has the frame ID 0x{msg.frame_id:X} of {seen[key]} (another bus of the file?): left out "
                        "(a spec is one bus: import each bus into a spec of its own)")
            continue
        seen[key] = name
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


NODE_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")  # fullmatch: "$" would also match before a final newline


def _nodes(loaded: Loaded, report: Report, kept: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Source node name → the spec's node: BU_'s nodes, then those only senders and receivers name."""
    db, out, taken = loaded.db, {}, set()
    spellings = Namer(tuple(n.name for n in db.nodes))

    def add(name: str, comment: str | None) -> None:
        ident = name if NODE_NAME.fullmatch(name) and name != "ALL" else "N" + re.sub(r"\W", "_", name)
        while ident in taken:
            ident += "_"
        taken.add(ident)
        spelt = spellings.dbc(name, lambda text: report.warn(loaded.source, None, text))
        out[name] = {"name": ident, **({"dbc_name": spelt} if ident != spelt else {}), **({"desc": str(comment)} if comment else {})}

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


def _message(loaded: Loaded, msg: Any, bus: dict[str, Any], names: Namer, tables: dict[str, dict[int, Any]],
             written: dict[tuple[int, str], Numbers], lines: dict[tuple[int, str], int],
             report: Report, kept: dict[str, dict[str, Any]]) -> dict[str, Any] | None:
    dbc_id = msg.frame_id | DBC_EXTENDED_FLAG if msg.is_extended_frame else msg.frame_id
    line = lines.get((dbc_id, ""))
    source_name = loaded.renamed.get(msg.name, msg.name)
    if msg.length not in FD_LENGTHS:
        report.warn(loaded.source, line, f"message {source_name} has {msg.length} bytes, not a CAN frame length: left out")
        return None
    name = names.name(source_name, f"message_{msg.frame_id:x}")
    out: dict[str, Any] = {"name": name}
    if name != source_name:
        out["dbc_name"] = names.dbc(source_name, lambda text: report.warn(loaded.source, line, text))
    out["id"] = msg.frame_id
    if bool(msg.is_extended_frame) != (bus["id_format"] == "extended"):
        out["extended"] = bool(msg.is_extended_frame)
    senders = [s for s in msg.senders if s != NO_NODE]
    out["sender"] = senders[0] if senders else "ALL"
    if len(senders) > 1:  # BO_TX_BU_: the DBC keeps them all, the other targets know the first
        out["dbc_senders"] = senders[1:]
    receivers = sorted({r for s in msg.signals for r in s.receivers if r != NO_NODE} - {out["sender"]})
    out["receivers"] = receivers
    if (cycle := _cycle_ms(loaded, msg, dbc_id, source_name, line, report)) is not None:
        out["cycle_ms"] = cycle
    out["dlc"] = msg.length
    if msg.length > 8 and not msg.is_fd:
        report.warn(loaded.source, line, f"message {source_name} has {msg.length} bytes but no CAN FD frame format: taken as CAN FD")
    if msg.is_fd or msg.length > 8:
        out["fd"] = True
        if not _brs(msg, loaded.db):
            out["brs"] = False
    if msg.comment:
        out["desc"] = str(msg.comment)
    where = Where(loaded, dbc_id, source_name, name, lines, lambda at, text: report.warn(loaded.source, at, text))
    signals = convert_signals(where, msg, bus["byte_order"], tables, written, kept)
    if signals is None:
        return None
    out["signals"] = signals
    if not out["signals"] and msg.length:
        out["layout_undefined"] = True
    if values := kept_values(msg, kept, lambda text: report.warn(loaded.source, line, text), f"message {source_name}"):
        out["dbc_attributes"] = values
    return out


def _cycle_ms(loaded: Loaded, msg: Any, dbc_id: int, name: str, line: int | None, report: Report) -> int | None:
    """GenMsgCycleTime as a number of ms; a definition of another type (STRING: "fast") can hold
    text, which is no cycle time: warned at its BA_ line and left out (the attribute is canspec's
    to compute from cycle_ms, so it is not kept either)."""
    value = msg.cycle_time
    if not value:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if math.isfinite(number):
        return int(number)  # out of range is `canspec check`'s to say, in the written spec
    at = re.compile(rf'^\s*BA_\s+"GenMsgCycleTime"\s+BO_\s+{dbc_id}\s')
    ba = next((i for i, text in enumerate((loaded.text or "").split("\n"), 1) if at.match(text)), line)
    report.warn(loaded.source, ba, f"GenMsgCycleTime of message {name} is {value!r}, not a number of milliseconds: "
                "message taken without a cycle time (set cycle_ms in the spec)")
    return None
