"""CAN FD logs in every format, written by the tools' own writers (python-can's candump, ASC, BLF
and TRC writers — TRC and BLF's CAN_FD_MESSAGE_64 taught FD records in logsynth — and asammdf
through python-can's MF4 writer; candump's screen forms as can-utils prints them), carrying
frames the reference codec packed for tests/fixtures/valid/motorola_fd_float.yaml (Motorola
fields crossing bytes, 12- and 64-byte frames, float32/64 in both orders, NaN, ±Inf, −0):
every frame read with its length, FD flag and BRS; every value as cantools decodes it with the
generated DBC; `canspec decode` text, JSON and CSV as the reference codec prints them."""

from __future__ import annotations

import csv
import io
import json
import math
import random
import struct
import subprocess
import sys
from pathlib import Path

import cantools
import numpy as np
import pytest
from canspec.logs import frames as fr
from canspec.logs.logread import read_log
from canspec.pipeline import compile_spec
from canspec.reference import codec

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import oracle
from canspec_cli import FIXTURES, canspec_env, run_canspec
from logsynth import T0, Frame, write

SPEC = FIXTURES / "valid" / "motorola_fd_float.yaml"
FORMATS = {"candump": "fd.log", "candump_default": "fd_default.log", "candump_x": "fd_x.log", "asc": "fd.asc", "blf": "fd.blf",
           "blf64": "fd64.blf", "trc": "fd.trc", "mf4": "fd.mf4"}
TIME_TOLERANCE = 1e-6  # every format keeps microseconds
SPECIAL_FLOATS = (math.nan, math.inf, -math.inf, -0.0, 0.0, 1.5, -3.25e-7, 3.4028234663852886e38, 5e-324)
N = 300


@pytest.fixture(scope="module")
def can():
    compiled = compile_spec(SPEC)
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    return compiled.spec.can


@pytest.fixture(scope="module")
def db(tmp_path_factory):
    out = tmp_path_factory.mktemp("dbc")
    result = run_canspec("gen", SPEC, "-t", "dbc", "-o", out)
    assert result.returncode == 0, result.stderr
    (path,) = out.rglob("*.dbc")
    return cantools.database.load_file(str(path), strict=True)


def random_raw(sig, rng):
    if sig.is_float and rng.random() < 0.3:  # special and extreme values, as bit patterns
        value = rng.choice(SPECIAL_FLOATS)
        return int.from_bytes(struct.pack("<f" if sig.length == 32 else "<d", value), "little") if sig.length == 64 or abs(value) < 3.5e38 else 0
    return rng.randint(sig.raw_type_min, sig.raw_type_max)


@pytest.fixture(scope="module")
def frames(can):
    """N frames cycling through the messages, every field random (checksums filled by the codec)."""
    rng = random.Random(2024)
    out = []
    for i in range(N):
        m = can.messages[i % len(can.messages)]
        data = codec.pack(m, {s.name: random_raw(s, rng) for s in m.data_signals})
        out.append(Frame(round(T0 + i * 0.001, 6), m.frame_id, m.is_extended, data, fd=m.is_fd, brs=m.brs))
    assert {len(f.data) for f in out} == {8, 12, 64} and {(f.fd, f.brs) for f in out} == {(False, False), (True, True), (True, False)}
    return out


@pytest.fixture(scope="module")
def logs(tmp_path_factory, frames):
    out = tmp_path_factory.mktemp("fdlogs")
    return {fmt: write(fmt, out / name, frames) for fmt, name in FORMATS.items()}


def test_the_writers_wrote_fd_records(logs):
    """The logs hold what the task names: candump `##`, ASC `CANFD`, BLF CAN_FD_MESSAGE / _64, TRC FD records."""
    assert "##1" in logs["candump"].read_text() and "##0" in logs["candump"].read_text()
    assert " CANFD " in logs["asc"].read_text()
    trc = logs["trc"].read_text().split()
    assert "FB" in trc and "FD" in trc
    assert b"LOBJ" in logs["blf"].read_bytes()
    assert "[64]" in logs["candump_default"].read_text() and "RX B -" in logs["candump_x"].read_text()


@pytest.mark.parametrize("fmt", list(FORMATS))
def test_fd_frames_read_with_length_and_flags(fmt, logs, frames):
    chunks = list(read_log(str(logs[fmt]), "blf" if fmt == "blf64" else None))
    assert not [p for c in chunks for p in c.problems]
    batch = fr.concat([c.batch for c in chunks])
    assert len(batch) == len(frames)
    assert [batch.frame_bytes(i) for i in range(len(batch))] == [f.data for f in frames]
    want_flags = [fr.FD * f.fd | fr.BRS * f.brs for f in frames]
    if fmt == "candump_default":  # the screen form without -x shows FD (two-digit length) but not BRS
        want_flags = [fr.FD * f.fd for f in frames]
    assert batch.flags.tolist() == want_flags
    assert np.array_equal(batch.frame_id, [f.frame_id for f in frames])


@pytest.mark.parametrize("fmt", list(FORMATS))
def test_fd_logs_decode_as_cantools_does(fmt, logs, frames, can, db):
    result = oracle.decode(logs[fmt], can.messages, "blf" if fmt == "blf64" else None)
    assert result.counts["decoded"] == len(frames) and result.counts["wrong_length"] == 0 and result.counts["malformed"] == 0
    names = {(m.frame_id, m.is_extended): m.name for m in can.messages}
    cmp = oracle.compare(result.tables, oracle.expected_by_message(frames, names), db, None if fmt == "candump_default" else TIME_TOLERANCE)
    assert cmp.rows == len(frames) and cmp.mismatches == []
    assert all(result.tables["wheel_speeds"].column("checksum_ok").to_pylist())


@pytest.mark.parametrize("fmt", list(FORMATS))
def test_brs_and_esi_in_every_format(fmt, tmp_path):
    """Every combination of BRS and ESI on FD frames of 0..64 bytes (ASC's BRS/ESI columns, TRC's FD/FB/FE/BI
    types, the candump flags digit and -x marks, BLF's and MF4's flag bits) read back as written."""
    sizes = (0, 5, 8, 12, 16, 20, 24, 32, 48, 64)
    frames = [Frame(round(T0 + i * 0.001, 6), 0x100 + i, i % 3 == 0, bytes(range(i, i + size)), fd=True, brs=bool(i & 1), esi=bool(i & 2))
              for i, size in enumerate(sizes * 2)]
    frames.append(Frame(round(T0 + 1, 6), 0x7FF, False, bytes(8)))  # and a classic frame
    path = write(fmt, tmp_path / FORMATS[fmt], frames)
    batch = fr.concat([c.batch for c in read_log(str(path), "blf" if fmt == "blf64" else None)])
    assert [batch.frame_bytes(i) for i in range(len(batch))] == [f.data for f in frames]
    screen = fmt == "candump_default"  # shows an FD frame's length with two digits, not its flags
    assert batch.flags.tolist() == [fr.FD * f.fd | (0 if screen else fr.BRS * f.brs | fr.ESI * f.esi) for f in frames]


def test_fd_frames_through_arrow(logs, can):
    """FD batches keep their bytes and flags through the Arrow form a distributed engine passes around."""
    from canspec.logs.bulk import Decoder, decode_arrow

    (chunk,) = list(read_log(str(logs["blf"])))
    record_batch = chunk.batch.to_arrow()
    assert record_batch.schema.names[-2:] == ["flags", "data"]
    back = fr.Batch.from_arrow(record_batch)
    assert [back.frame_bytes(i) for i in range(len(back))] == [chunk.batch.frame_bytes(i) for i in range(len(back))]
    assert back.flags.tolist() == chunk.batch.flags.tolist()
    direct = Decoder(can.messages).decode(chunk.batch).tables
    via_arrow = decode_arrow(can.messages, record_batch)
    assert sorted(direct) == sorted(via_arrow) == sorted(m.name for m in can.messages)
    for n in direct:  # repr: NaN values equal (Table.equals takes NaN != NaN)
        assert direct[n].schema == via_arrow[n].schema and repr(direct[n].to_pydict()) == repr(via_arrow[n].to_pydict()), n


def _json_number(value):
    if isinstance(value, float) and not math.isfinite(value):
        return "NaN" if math.isnan(value) else ("Infinity" if value > 0 else "-Infinity")
    return value


@pytest.mark.parametrize("fmt", ["blf", "asc"])
def test_decode_cli_text_json_csv_match_the_reference_codec(fmt, logs, frames, can):
    msg_of = {m.frame_id: m for m in can.messages}

    def run(*extra):
        args = [sys.executable, "-m", "canspec", "decode", "--spec", str(SPEC), str(logs[fmt]), *extra]
        return subprocess.run(args, capture_output=True, text=True, env=canspec_env(), check=True).stdout

    text = run().splitlines()
    want = [f"({f.timestamp:.6f}) {{}} {f.frame_id:03X} {msg_of[f.frame_id].name}: {codec.text_decoder(msg_of[f.frame_id])(codec.frame_word(f.data))}"
            for f in frames]
    channel = text[0].split()[1]
    assert text == [w.format(channel) for w in want]
    records = [json.loads(line) for line in run("--format", "json").splitlines()]
    assert len(records) == len(frames)
    for rec, f in zip(records, frames):
        m = msg_of[f.frame_id]
        raws = codec.unpack(m, f.data)
        expected = {s.name: (lb.name if (lb := s.label_of(raws[s.name])) else _json_number(codec.physical_number(s, raws[s.name])))
                    for s in m.data_signals}
        expected = {k: round(v, s.decimals) if s.decimals and not isinstance(v, str) else v for (k, v), s in zip(expected.items(), m.data_signals)}
        assert rec["message"] == m.name and rec["signals"] == expected and rec["checksum_ok"]
    rows = list(csv.DictReader(io.StringIO(run("--format", "csv"))))
    want_rows = [(m.name, s.name, str(raw), codec.value_text(s, raw)) for f in frames for m in [msg_of[f.frame_id]]
                 for s, raw in ((s, codec.unpack(m, f.data)[s.name]) for s in m.data_signals)]
    assert [(r["message"], r["signal"], r["raw"], r["value"]) for r in rows] == want_rows


def test_report_counts_fd_frames_and_wrong_lengths(tmp_path, can):
    """An FD message's frame with another length is reported as wrong_length; the others are counted."""
    m = next(m for m in can.messages if m.dlc == 64)
    good = codec.pack(m, {})
    lines = [f"({T0 + i * 0.05:.6f}) can0 {m.frame_id:03X}##1{good.hex()}" for i in range(5)]
    lines.append(f"({T0 + 0.3:.6f}) can0 {m.frame_id:03X}##1{good[:48].hex()}")
    log = tmp_path / "short.log"
    log.write_text("\n".join(lines) + "\n")
    result = run_canspec("decode", "--spec", SPEC, log, "--report", "--format", "json")
    report = json.loads(result.stdout)["inputs"][0]
    assert report["counts"]["decoded"] == 5 and report["counts"]["wrong_length"] == 1
    assert next(r for r in report["messages"] if r["message"] == m.name)["frames"] == 5
    assert f"{log}:6: error: {m.name} ({m.id_text}): 48 data bytes, expected 64" in result.stderr

