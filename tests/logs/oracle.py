"""Decode a log file in-process with the bulk decoder, and compare its tables with cantools (the
independent oracle) decoding the frames that were written into the log."""

from __future__ import annotations

import math
import struct
from collections import defaultdict
from dataclasses import dataclass, field

import pyarrow as pa
from canspec.logs import fleet
from logsynth import Frame


@dataclass
class Comparison:
    rows: int = 0
    mismatches: list[str] = field(default_factory=list)


def expected_by_message(frames: list[Frame], names: dict[tuple[int, bool], str]) -> dict[str, list[Frame]]:
    out: dict[str, list[Frame]] = defaultdict(list)
    for f in frames:
        name = names.get((f.frame_id, f.extended))
        if f.kind == "data" and name is not None:
            out[name].append(f)
    return out


def _same_physical(mine: float, theirs: object) -> bool:
    return mine == float(theirs) or (math.isnan(mine) and math.isnan(float(theirs)))  # type: ignore[arg-type]


def _float_bits(value: float, length: int) -> int:
    """The IEEE 754 bit pattern cantools' float value came from (its raw value is the float itself)."""
    return int.from_bytes(struct.pack("<f" if length == 32 else "<d", value), "little")


def compare(tables: dict[str, pa.Table], expected: dict[str, list[Frame]], db, timestamps: float | None) -> Comparison:  # type: ignore[no-untyped-def]
    """Every row against cantools: raw values exactly, physical values exactly (both compute
    raw × scale + offset in doubles), labels as cantools' choice names, time stamps within
    `timestamps` seconds (None: the format keeps none)."""
    result = Comparison()
    assert set(tables) == {n for n, fs in expected.items() if fs}, (sorted(tables), sorted(expected))
    for name, frames in expected.items():
        cm = db.get_message_by_name(name)
        rows = tables[name].to_pylist()
        time_column = tables[name].column_names[0]  # "timestamp", or "_timestamp" when a signal has that name
        assert len(rows) == len(frames), (name, len(rows), len(frames))
        for row, f in zip(rows, frames):
            result.rows += 1
            raw = cm.decode(f.data, decode_choices=False, scaling=False)
            phys = cm.decode(f.data, decode_choices=False)
            named = cm.decode(f.data)
            for sig, value in raw.items():
                problems = []
                cs = cm.get_signal_by_name(sig)
                if cs.is_float:
                    value = _float_bits(value, cs.length)
                if row[f"{sig}_raw"] != value:
                    problems.append(f"raw {row[f'{sig}_raw']} != {value}")
                if not _same_physical(row[sig], phys[sig]):
                    problems.append(f"physical {row[sig]!r} != {phys[sig]!r}")
                label = row.get(f"{sig}_label")
                theirs = str(named[sig]) if not isinstance(named[sig], (int, float)) else None
                if label != theirs:
                    problems.append(f"label {label!r} != {theirs!r}")
                if problems:
                    result.mismatches.append(f"{name}.{sig} at {f.timestamp}: {'; '.join(problems)}")
            if timestamps is not None and abs(row[time_column] - f.timestamp) > timestamps:
                result.mismatches.append(f"{name} time {row[time_column]} != {f.timestamp}")
    return result


def decode(path, messages, fmt=None):  # type: ignore[no-untyped-def]
    return fleet.decode_file(messages, str(path), fmt, raw=True)
