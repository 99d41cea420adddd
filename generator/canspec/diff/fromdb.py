"""The comparison model of a database file, from the spec `canspec import` made of it. Names are
the file's own (a DBC's `WHEEL_SPEED_RL`, not the spec's `wheel_speed_rl`), except a signal
canspec renamed in a DBC it wrote, whose `SpecSignalName` gives the spec's name back, so a spec
and its own DBC compare equal. What a database cannot say (Chinese names, titles, descriptions,
checksum algorithms, multi-frame text, value labels as printed, receivers it leaves to
Vector__XXX) is None and not compared; its comments are compared with another database's only."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from canspec import ir
from canspec.diff.model import Entry, MessageModel, ProtocolModel, SignalModel, from_spec
from canspec.importer.signals import attribute
from canspec.targets.dbc.naming import SPEC_NAME_ATTRIBUTE


def _spec_named(db: Any) -> set[tuple[int, str]]:
    """(frame ID, DBC signal name) of the signals whose DBC carries the spec's name (the definition's
    default, "", says no name)."""
    return {(msg.frame_id, sig.name) for msg in db.messages for sig in msg.signals if attribute(sig, SPEC_NAME_ATTRIBUTE)}


def _signal(model: SignalModel, sig: ir.Signal, names: dict[str, str], comments: bool) -> SignalModel:
    values = None
    if sig.value_table is not None:
        values = {e.raw: Entry(e.dbc_text or e.name, None) for e in sig.value_table.entries}
    mux = (names[model.mux[0]], model.mux[1]) if model.mux is not None else None
    return replace(model, name=names[sig.name], values=values, values_table=None, zh=None, desc=model.desc if comments else None, loc=None, mux=mux,
                   attributes=model.attributes if comments else None)


def _message(model: MessageModel, msg: ir.Message, spec_named: set[tuple[int, str]], renamed: dict[str, str], comments: bool) -> MessageModel:
    own = {s.name: renamed.get(s.dbc_name, s.dbc_name) for s in msg.signals}
    names = {s.name: s.name if (msg.frame_id, s.dbc_name) in spec_named else own[s.name] for s in msg.signals}
    by_name = {s.name: s for s in msg.signals}
    # No receiver (Vector__XXX) is not said against a spec, whose DBC may leave it so; between two
    # databases it is what the file says: a message gaining its first reader is a receivers change.
    return replace(
        model, name=renamed.get(msg.dbc_name, msg.dbc_name), title=None, zh=None, checksum=None, multiframe=None, loc=None,
        receivers=model.receivers if comments else model.receivers or None, signals=tuple(_signal(m, by_name[m.name], names, comments) for m in model.signals),
        desc=model.desc if comments else None, attributes=model.attributes if comments else None,
    )


def from_database(spec: ir.Spec, loaded: Any, source: str, comments: bool = False) -> ProtocolModel:
    """`loaded`: the import's source (importer/load.py), for the names cantools read. `comments`:
    keep the database's comments as descriptions and its attributes, to compare with another
    database's (a spec's descriptions are not what its generated DBC comments say, and the DBC
    target adds attributes of its own, GenMsgSendType: against a spec they stay None)."""
    model = from_spec(spec, source)
    assert spec.can is not None
    spec_named = _spec_named(loaded.db)
    messages = tuple(_message(m, msg, spec_named, loaded.renamed, comments) for m, msg in zip(model.messages, spec.can.messages))
    version = spec.can.version if spec.can.version != "0.0.0" else None
    bitrate, data_bitrate = _stated(loaded.db, "Baudrate", "baudrate"), _stated(loaded.db, "BaudrateCANFD", "fd_baudrate")
    return replace(model, kind="dbc", messages=messages, version=version, changelog=None,
                   bitrate=model.bitrate if bitrate else None, data_bitrate=model.data_bitrate if data_bitrate else None,
                   attributes=model.attributes if comments else None,
                   nodes=tuple(replace(n, desc=n.desc if comments else None, loc=None) for n in model.nodes))


def _stated(db: Any, name: str, bus_field: str) -> bool:
    """Whether the file states a bus rate (as importer/tospec reads it): one the import assumed, with
    a warning, is not the file's and is not compared."""
    return bool(attribute(db, name) or any(getattr(b, bus_field, None) for b in db.buses))
