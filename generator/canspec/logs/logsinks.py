"""Where `canspec decode` puts decoded frames: text, JSON lines and CSV are written frame by frame
in log order (compiled per-message formatters); Parquet takes the bulk decoder's per-message
Arrow tables and writes one dataset per message, Hive-partitioned by source log:

    OUT/<message>/source=<log name>/part-0.parquet

so pandas, Polars, DuckDB and Spark read `OUT/<message>` as one table (with a `source` column)
and prune by source and, through row-group statistics, by time."""

from __future__ import annotations

import csv
import json
import math
import os
import re
from typing import IO, Any

import numpy as np

from canspec import ir
from canspec.logs.bulk import Decoder
from canspec.logs.bulktext import message_texts
from canspec.logs.fields import MessageFrames
from canspec.reference import codec


class FrameSink:
    """Per-frame outputs: one call per decoded chunk, frames in log order."""

    def __init__(self, decoder: Decoder, out: IO[str]) -> None:
        self.decoder, self.out = decoder, out

    def rows(self, batch: Any, decoded: Any) -> tuple[list[Any], ...]:
        """Per decoded frame: message key, data bytes, time, channel, checksum flag."""
        rows = np.flatnonzero(decoded.fits)
        ok = np.ones(len(batch), bool)
        ok[decoded.bad_checksum] = False
        dlc = batch.dlc[rows].tolist()
        payloads = [w.to_bytes(8, "little")[:n] for w, n in zip(batch.word[rows].tolist(), dlc)]
        for j in np.flatnonzero(batch.dlc[rows] > 8).tolist():  # CAN FD frames: their bytes
            payloads[j] = batch.data[rows[j], : dlc[j]].tobytes()
        return (decoded.key[rows].tolist(), payloads, batch.timestamp[rows].tolist(), batch.channel_names()[rows].tolist(), ok[rows].tolist())

    def close(self) -> None:
        self.out.flush()


class TextSink(FrameSink):
    """`(TIME) CHANNEL ID message: signal=value unit, ...` per frame. The lines of one message are
    made together (bulktext: a column of texts per signal), then put in log order."""

    def __init__(self, decoder: Decoder, out: IO[str]) -> None:
        super().__init__(decoder, out)
        self.messages = {lay.msg.name: (f" {lay.msg.id_text[2:]} {lay.msg.name}: ", lay.msg) for lay in decoder.layouts.values()}
        self.tables: dict[str, dict[str, np.ndarray]] = {}

    def __call__(self, source: str, batch: Any, decoded: Any) -> None:
        rows = np.flatnonzero(decoded.fits)
        if not len(rows):
            return
        lines = np.empty(len(rows), dtype=object)
        channels = batch.channel_names()
        one_channel = batch.channels[0] if len(batch.channels) == 1 and not (batch.channel < 0).any() else None
        for name, group in decoded.groups.items():
            head, msg = self.messages[name]
            texts = message_texts(MessageFrames.of(msg, batch, group), self.tables.setdefault(name, {}))
            lines[np.searchsorted(rows, group)] = _lines(head, texts, batch.timestamp[group], channels[group], one_channel)
        if len(decoded.bad_checksum):
            at = np.searchsorted(rows, decoded.bad_checksum)
            lines[at] = lines[at] + "  [checksum mismatch]"
        self.out.write("\n".join(lines.tolist()) + "\n")


def _lines(head: str, texts: list[str], time: np.ndarray, channel: np.ndarray, one_channel: str | None) -> list[str]:
    """One message's lines: `(TIME) CHANNEL` + head + fields, in one format call per line where
    every frame has a time stamp (the common case: no intermediate strings)."""
    if not np.isnan(time).any():
        if one_channel is not None:
            return list(map(("({:.6f}) " + (one_channel + head).replace("{", "{{").replace("}", "}}") + "{}").format, time.tolist(), texts))
        return list(map(("({:.6f}) {}" + head.replace("{", "{{").replace("}", "}}") + "{}").format, time.tolist(), channel.tolist(), texts))
    # no time stamps (or only some): the channel, when there is one, leads
    lead = [("" if t != t else f"({t:.6f}) ") + c for t, c in zip(time.tolist(), channel.tolist())]  # noqa: PLR0124 - NaN test
    return [lead_text + head + text if lead_text else head[1:] + text for lead_text, text in zip(lead, texts)]


NON_FINITE = {math.inf: "Infinity", -math.inf: "-Infinity"}  # as the vectors write them (JSON has no such numbers)


def json_value(sig: ir.Signal, raw: int) -> str | float | int:
    label = sig.label_of(raw)
    if label is not None:
        return label.name
    phys = codec.physical_number(sig, raw)
    if sig.is_float and not math.isfinite(phys):
        return NON_FINITE.get(phys, "NaN")
    return round(phys, sig.decimals) if sig.decimals else phys


def raw_values(msg: ir.Message, data: bytes) -> list[tuple[ir.Signal, int]]:
    """Each data signal the frame holds with its raw value (the reference codec's reading)."""
    if msg.is_multiplexed:
        return [(msg.signal(name), raw) for name, raw in codec.unpack(msg, data).items()]
    v = int.from_bytes(data, "little")
    big = int.from_bytes(data, "big") if msg.has_big_endian else None
    return [(s, codec.raw_value(s, v, big)) for s in msg.data_signals]


class JsonSink(FrameSink):
    def __call__(self, source: str, batch: Any, decoded: Any) -> None:
        parts = []
        for k, data, t, c, ok in zip(*self.rows(batch, decoded)):
            msg = self.decoder.layouts[k].msg
            record = {
                "timestamp": None if math.isnan(t) else t, "channel": c or None, "frame_id": msg.id_text[2:], "message": msg.name,
                "signals": {s.name: json_value(s, raw) for s, raw in raw_values(msg, data)}, "checksum_ok": ok,
            }
            parts.append(json.dumps(record, ensure_ascii=False) + "\n")
        self.out.write("".join(parts))


class CsvSink(FrameSink):
    """One row per signal value (long form), so every message fits one CSV stream."""

    def __init__(self, decoder: Decoder, out: IO[str]) -> None:
        super().__init__(decoder, out)
        self.csv = csv.writer(out, lineterminator="\n")
        self.csv.writerow(["timestamp", "channel", "frame_id", "message", "signal", "raw", "value", "unit", "checksum_ok"])

    def __call__(self, source: str, batch: Any, decoded: Any) -> None:
        for k, data, t, c, ok in zip(*self.rows(batch, decoded)):
            msg = self.decoder.layouts[k].msg
            ts = "" if math.isnan(t) else f"{t:.6f}"
            for s, raw in raw_values(msg, data):
                self.csv.writerow([ts, c, msg.id_text[2:], msg.name, s.name, raw, codec.value_text(s, raw), s.unit, int(ok)])


def partition_name(source: str, taken: set[str]) -> str:
    """A log's partition value: its file name without format extensions, made path-safe and unique."""
    base = "stdin" if source == "<stdin>" else os.path.basename(source)
    base = re.sub(r"(\.gz)?$", "", base, flags=re.IGNORECASE)
    base = re.sub(r"[^A-Za-z0-9._-]", "_", os.path.splitext(base)[0]) or "log"
    name, n = base, 1
    while name in taken:
        n += 1
        name = f"{base}-{n}"
    taken.add(name)
    return name


class ParquetSink:
    """Per (message, source) one Parquet file; a message's rows are gathered into row groups of
    up to ROW_GROUP_ROWS (fewer, larger row groups write faster and read better), all pending
    rows written once they hold PENDING_BYTES (memory stays bounded)."""

    ROW_GROUP_ROWS = 1 << 16
    PENDING_BYTES = 32 << 20

    def __init__(self, decoder: Decoder, out_dir: str) -> None:
        self.decoder, self.out_dir = decoder, out_dir
        self.writers: dict[tuple[str, str], Any] = {}
        self.pending: dict[tuple[str, str], list[Any]] = {}
        self.partitions: dict[str, str] = {}
        self.taken: set[str] = set()
        self.pending_bytes = 0  # of every pending table (kept as a sum: Table.nbytes walks the buffers)

    def __call__(self, source: str, batch: Any, decoded: Any) -> None:
        part = self.partitions.get(source) or self.partitions.setdefault(source, partition_name(source, self.taken))
        for name, table in decoded.tables.items():
            pending = self.pending.setdefault((name, part), [])
            pending.append(table)
            self.pending_bytes += table.nbytes
            if sum(t.num_rows for t in pending) >= self.ROW_GROUP_ROWS:
                self._flush((name, part))
        if self.pending_bytes >= self.PENDING_BYTES:
            for key in list(self.pending):
                self._flush(key)

    def _flush(self, key: tuple[str, str]) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        tables = self.pending.pop(key, [])
        if not tables:
            return
        self.pending_bytes -= sum(t.nbytes for t in tables)
        table = pa.concat_tables(tables).unify_dictionaries().combine_chunks()
        writer = self.writers.get(key)
        if writer is None:
            folder = os.path.join(self.out_dir, key[0], f"source={key[1]}")
            os.makedirs(folder, exist_ok=True)
            writer = self.writers[key] = pq.ParquetWriter(os.path.join(folder, "part-0.parquet"), table.schema, compression="zstd")
        writer.write_table(table, row_group_size=max(table.num_rows, 1))

    def close(self) -> None:
        for key in list(self.pending):
            self._flush(key)
        for writer in self.writers.values():
            writer.close()
