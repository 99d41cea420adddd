"""Whole log files → per-message Arrow tables: the unit of work a distributed engine maps over a
fleet's logs (Dask below; Spark's mapInArrow with bulk.decode_arrow, see README). The tables
are exactly those `canspec decode --format parquet` writes for the same file.

    from dask.distributed import Client
    futures = client.map(decode_file, [messages] * len(paths), paths)
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field

import pyarrow as pa

from canspec import ir
from canspec.logs.bulk import Decoder
from canspec.logs.logread import read_log


@dataclass
class FileResult:
    tables: dict[str, pa.Table] = field(default_factory=dict)
    counts: Counter[str] = field(default_factory=Counter)  # frames, decoded, remote, error, unknown, wrong_length, bad_checksum, malformed


def decode_file(messages: Iterable[ir.Message], path: str, fmt: str | None = None, raw: bool = False) -> FileResult:
    """Every frame of one log, decoded; raises logread.InputError when it cannot be read."""
    decoder = Decoder(messages, raw)
    parts: dict[str, list[pa.Table]] = {}
    result = FileResult()
    for chunk in read_log(path, fmt):
        decoded = decoder.decode(chunk.batch)
        for name, table in decoded.tables.items():
            parts.setdefault(name, []).append(table)
        result.counts.update(
            frames=len(chunk.batch), decoded=int(decoded.fits.sum()), remote=decoded.remote, error=decoded.error, malformed=len(chunk.problems),
            unknown=len(decoded.unknown), wrong_length=len(decoded.wrong_length), bad_checksum=len(decoded.bad_checksum),
        )
    result.tables = {name: pa.concat_tables(tables).unify_dictionaries().combine_chunks() for name, tables in parts.items()}
    return result
