"""The bulk decoder: a pure function from a batch of frames (frames.Batch, or its Arrow form) to
one Arrow table per message. All frames of one ID are decoded at once — NumPy shifts and masks
over the column of 64-bit frame words (byte gathers for CAN FD frames: fields.py), with the IR's
word_mask/word_shift/sign_bit, the checksum's cover_mask and the reference codec's physical
formula — so it maps over log files in Dask or Spark (see README) and gives the same tables as
a single process.

A message's table: `timestamp` (float64 s), `channel` (dictionary string), per data signal its
physical value (float64; null in the frames of a multiplexed message that hold another page),
`<signal>_label` (dictionary string, null where the raw value has no
label) for signals with labels, `<signal>_raw` when asked (the field's storage type:
uint64/int64 for wide fields, so raw values above 2^53 stay exact), and `checksum_ok` (bool)
for messages with a checksum. A derived column whose name a signal already has gets a leading
underscore. Frames with a bad checksum stay in the table, flagged."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from canspec import ir
from canspec.logs import frames as fr
from canspec.logs.candump import DATA, ERROR, REMOTE
from canspec.logs.fields import MessageFrames, float_column

if TYPE_CHECKING:  # pyarrow is imported where tables are made: the text output needs none
    import pyarrow as pa

def message_key(frame_id: int, extended: bool) -> int:
    return frame_id << 1 | int(extended)


@dataclass(frozen=True)
class Layout:
    """The columns of one message's table, decided once from the IR."""

    msg: ir.Message
    raw: bool
    names: dict[str, str]  # role key ("timestamp", "s:<sig>", "l:<sig>", "r:<sig>", "checksum_ok") → column name

    @classmethod
    def of(cls, msg: ir.Message, raw: bool = False) -> Layout:
        taken = {s.name for s in msg.data_signals}
        names: dict[str, str] = {}

        def add(key: str, wanted: str) -> None:
            while wanted in taken:
                wanted = "_" + wanted
            taken.add(wanted)
            names[key] = wanted

        add("timestamp", "timestamp")
        add("channel", "channel")
        for s in msg.data_signals:
            names[f"s:{s.name}"] = s.name
            if s.labels:
                add(f"l:{s.name}", f"{s.name}_label")
            if raw:
                add(f"r:{s.name}", f"{s.name}_raw")
        if msg.checksum is not None:
            add("checksum_ok", "checksum_ok")
        return cls(msg, raw, names)

    def schema(self) -> pa.Schema:
        import pyarrow as pa

        n = self.names
        cols = [pa.field(n["timestamp"], pa.float64()), pa.field(n["channel"], pa.dictionary(pa.int32(), pa.string()))]
        for s in self.msg.data_signals:
            unit = {b"unit": s.unit.encode()} if s.unit else None
            cols.append(pa.field(s.name, pa.float64(), metadata=unit))
            if s.labels:
                cols.append(pa.field(n[f"l:{s.name}"], pa.dictionary(pa.int32(), pa.string())))
            if self.raw:
                cols.append(pa.field(n[f"r:{s.name}"], raw_type(s)))
        if self.msg.checksum is not None:
            cols.append(pa.field(n["checksum_ok"], pa.bool_()))
        meta = {b"message": self.msg.name.encode(), b"frame_id": self.msg.id_text.encode()}
        return pa.schema(cols, metadata=meta)

    def plain_schema(self) -> pa.Schema:
        """The schema with dictionary columns as plain strings (what Spark's mapInArrow takes)."""
        import pyarrow as pa

        schema = self.schema()
        return pa.schema([pa.field(f.name, pa.string()) if pa.types.is_dictionary(f.type) else f for f in schema], metadata=schema.metadata)


def raw_type(sig: ir.Signal) -> pa.DataType:
    import pyarrow as pa

    return getattr(pa, f"{'int' if sig.signed else 'uint'}{sig.storage_bits}")()


def physical_column(sig: ir.Signal, raw: np.ndarray) -> np.ndarray:
    """The physical values as float64, as float(codec.physical_number) gives them: integer
    scaling exactly (int64 where it cannot overflow, else Python ints) and rounded once;
    otherwise raw × factor + offset in doubles; a float field's bit patterns as the floats they hold."""
    if sig.is_float:
        return float_column(sig, raw)
    if not sig.is_integer:
        return ir.to_physical(raw.astype(np.float64), float(sig.factor), float(sig.offset))
    factor, offset = int(sig.factor), int(sig.offset)
    if factor == 1 and offset == 0:
        return raw.astype(np.float64)
    if sig.length + abs(factor).bit_length() < 62 and abs(offset) < 2**62:
        return ir.to_physical(raw.astype(np.int64), factor, offset).astype(np.float64)
    return np.array([float(ir.to_physical(r, factor, offset)) for r in raw.tolist()], dtype=np.float64)


def label_column(sig: ir.Signal, raw: np.ndarray, absent: np.ndarray | None = None) -> pa.DictionaryArray:
    import pyarrow as pa

    labels = sorted(sig.labels, key=lambda lb: lb.raw)
    keys = np.array([lb.raw for lb in labels], dtype=raw.dtype)
    at = np.minimum(np.searchsorted(keys, raw), len(keys) - 1)
    miss = keys[at] != raw
    if absent is not None:
        miss |= absent
    return pa.DictionaryArray.from_arrays(pa.array(at.astype(np.int32), mask=miss), pa.array([lb.name for lb in labels], pa.string()))


def message_table(layout: Layout, batch: fr.Batch) -> pa.Table:
    """The table of frames that all carry layout.msg with the right length."""
    import pyarrow as pa

    frames = MessageFrames.of(layout.msg, batch)
    channel = pa.DictionaryArray.from_arrays(pa.array(batch.channel, mask=batch.channel < 0), pa.array(batch.channels, pa.string()))
    cols: list[pa.Array] = [pa.array(batch.timestamp), channel]
    for s in layout.msg.data_signals:
        raw, present = frames.raw(s), frames.present(s)
        absent = None if present is None else ~present  # null where the frame holds another page
        cols.append(pa.array(physical_column(s, raw), mask=absent))
        if s.labels:
            cols.append(label_column(s, raw, absent))
        if layout.raw:
            cols.append(pa.array(raw.astype(f"{'int' if s.signed else 'uint'}{s.storage_bits}"), mask=absent))
    if layout.msg.checksum is not None:
        cols.append(pa.array(frames.checksum_ok()))
    return pa.Table.from_arrays(cols, schema=layout.schema())


@dataclass
class Decoded:
    """One batch decoded: per message the indices of its frames in the batch (and its table when
    asked); as indices into the batch, the frames that were not decoded or failed the checksum."""

    key: np.ndarray  # per frame: frame_id << 1 | extended
    fits: np.ndarray  # per frame: a data frame of a known message with its length
    groups: dict[str, np.ndarray] = field(default_factory=dict)
    tables: dict[str, pa.Table] = field(default_factory=dict)
    unknown: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    wrong_length: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    bad_checksum: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    remote: int = 0
    error: int = 0


class Decoder:
    """Decodes batches for one protocol: the IR's messages keyed by (frame_id, is_extended)."""

    def __init__(self, messages: Iterable[ir.Message], raw: bool = False) -> None:
        self.layouts = {message_key(m.frame_id, m.is_extended): Layout.of(m, raw) for m in messages}
        self.keys = np.array(sorted(self.layouts), dtype=np.int64)
        self.dlcs = np.array([self.layouts[k].msg.dlc for k in sorted(self.layouts)], dtype=np.int64)

    def layout(self, name: str) -> Layout:
        return next(lay for lay in self.layouts.values() if lay.msg.name == name)

    def decode(self, batch: fr.Batch, tables: bool = True) -> Decoded:
        key = (batch.frame_id.astype(np.int64) << 1) | batch.extended
        data = batch.kind == DATA
        if len(self.keys):
            at = np.minimum(np.searchsorted(self.keys, key), len(self.keys) - 1)
            known = data & (self.keys[at] == key)
            fits = known & (self.dlcs[at] == batch.dlc)
        else:
            known = fits = np.zeros(len(batch), bool)
        out = Decoded(key, fits, remote=int(np.sum(batch.kind == REMOTE)), error=int(np.sum(batch.kind == ERROR)))
        out.unknown = np.flatnonzero(data & ~known)
        out.wrong_length = np.flatnonzero(known & ~fits)
        rows = np.flatnonzero(fits)
        order = rows[np.argsort(key[rows], kind="stable")]
        bad = []
        for group in np.split(order, np.flatnonzero(np.diff(key[order])) + 1) if len(order) else []:
            layout = self.layouts[int(key[group[0]])]
            out.groups[layout.msg.name] = group
            if tables:
                out.tables[layout.msg.name] = message_table(layout, batch.take(group))
            if layout.msg.checksum is not None:
                bad.append(group[~MessageFrames.of(layout.msg, batch, group).checksum_ok()])
        out.bad_checksum = np.sort(np.concatenate(bad)) if bad else out.bad_checksum
        return out


def decode_arrow(messages: Iterable[ir.Message], record_batch: pa.RecordBatch, raw: bool = False) -> dict[str, pa.Table]:
    """The pure function for distributed engines: Arrow frame columns → per-message tables."""
    return Decoder(messages, raw).decode(fr.Batch.from_arrow(record_batch)).tables
