"""Every log format, the same frames: every frame decoded, and every value as cantools (reading
the generated DBC, or a hand-written one for a spec of our own) decodes it — 0 mismatches."""

from __future__ import annotations

import random
import sys
from pathlib import Path

import cantools
import pytest
from canspec.pipeline import compile_spec
from canspec.reference import codec

sys.path.insert(0, str(Path(__file__).resolve().parent))
import oracle
from logsynth import FORMATS, HAS_SPECIAL_FRAMES, T0, Frame, frames_from_cases, vector_cases, write

FRAMES = 20000
SPECIALS_EVERY = 997  # a remote or an error frame now and then
TIME_TOLERANCE = {"asc": 1e-6, "trc": 1e-6}  # the formats' own resolution (µs)
MIXED = Path(__file__).resolve().parent / "specs"


@pytest.fixture(scope="module")
def shipped_frames(vectors):
    return frames_from_cases(vector_cases(vectors), FRAMES, SPECIALS_EVERY)


@pytest.fixture(scope="module")
def shipped_logs(tmp_path_factory, shipped_frames):
    out = tmp_path_factory.mktemp("logs")
    return {fmt: write(fmt, out / name, shipped_frames) for fmt, name in FORMATS.items()}


@pytest.mark.parametrize("fmt", list(FORMATS))
def test_every_format_agrees_with_cantools(fmt, shipped_logs, shipped_frames, can, db):
    names = {(m.frame_id, m.is_extended): m.name for m in can.messages}
    result = oracle.decode(shipped_logs[fmt], can.messages)
    data = [f for f in shipped_frames if f.kind == "data"]
    assert result.counts["decoded"] == len(data) and result.counts["unknown"] == 0 and result.counts["malformed"] == 0
    if fmt in HAS_SPECIAL_FRAMES:
        assert result.counts["remote"] == sum(f.kind == "remote" for f in shipped_frames) > 0
        assert result.counts["error"] == sum(f.kind == "error" for f in shipped_frames) > 0
    timestamps = None if fmt == "candump_default" else TIME_TOLERANCE.get(fmt, 1e-6)
    cmp = oracle.compare(result.tables, oracle.expected_by_message(shipped_frames, names), db, timestamps)
    print(f"{fmt}: {cmp.rows} frames compared, {len(cmp.mismatches)} mismatches")
    assert cmp.rows == len(data) and cmp.mismatches == []
    assert all(all(t.column("checksum_ok").to_pylist()) for t in result.tables.values() if "checksum_ok" in t.column_names)


def mixed_frames(msgs, n, seed=7):
    """Random frames of every message of the mixed spec (high bits set in wide fields), a valid
    checksum on half of them, and a 29-bit frame carrying an 11-bit message's ID number."""
    rng = random.Random(seed)
    frames = []
    for i in range(n):
        m = msgs[i % len(msgs)]
        data = bytearray(rng.getrandbits(8) for _ in range(m.dlc))
        if m.checksum is not None and i % 2:
            data[m.checksum.byte] = codec.xor_checksum(m, codec.frame_word(data))
        frames.append(Frame(T0 + i * 0.001, m.frame_id, m.is_extended, bytes(data)))
    frames.append(Frame(T0 + n * 0.001, msgs[0].frame_id, True, bytes(8)))
    return frames


@pytest.mark.parametrize("fmt", ["candump", "candump_x", "asc", "blf", "trc", "mf4"])
def test_any_spec_standard_and_extended_ids_wide_fields(fmt, tmp_path):
    compiled = compile_spec(MIXED / "mixed.yaml")
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    msgs = compiled.spec.can.messages
    assert {m.is_extended for m in msgs} == {True, False} and any(m.dlc == 0 for m in msgs)
    db = cantools.database.load_file(str(MIXED / "mixed.dbc"), strict=True)
    frames = mixed_frames(msgs, 600)
    result = oracle.decode(write(fmt, tmp_path / FORMATS[fmt], frames), msgs)
    names = {(m.frame_id, m.is_extended): m.name for m in msgs}
    assert result.counts["unknown"] == 1 and result.counts["decoded"] == 600
    cmp = oracle.compare(result.tables, oracle.expected_by_message(frames, names), db, TIME_TOLERANCE.get(fmt, 1e-6))
    assert cmp.rows == 600 and cmp.mismatches == []
    big = result.tables["ext_wide"].column("u64_raw")
    assert str(big.type) == "uint64" and max(big.to_pylist()) > 2**63  # exact above 2^53
    assert str(result.tables["ext_signed64"].column("s64_raw").type) == "int64"
    std = result.tables["std_cyclic"]
    expected_ok = [i % 2 == 1 or codec.checksum_ok(msgs[0], f.data) for i, f in enumerate(frames[:-1]) if f.frame_id == msgs[0].frame_id and not f.extended]
    assert std.column("checksum_ok").to_pylist() == expected_ok
    # a signal named like a derived column: the derived one gives way
    assert result.tables["short_std"].column_names[:3] == ["_timestamp", "channel", "flag"]
    assert result.tables["empty"].num_rows == 120 and result.tables["empty"].column_names == ["timestamp", "channel"]
