"""`canspec decode` on the command line: candump logs decoded from the spec; garbage lines,
truncated frames, unknown IDs and bad checksums are reported at FILE:LINE, counted and never stop
the run; remote and error frames are counted as such; unreadable or wrong-format inputs exit 2
with one line. Values are checked against cantools reading the generated DBC."""

from __future__ import annotations

import csv
import io
import json
import os
import subprocess
import sys

import pytest
from canspec.logs import frames as fr
from canspec.logs.candump import DATA, ERROR, REMOTE, LineError, parse_line
from hypothesis import given, settings
from hypothesis import strategies as st
from repo_paths import CANSPEC_ENV

ENV = CANSPEC_ENV


def canspec_decode(*args, stdin=None):
    return subprocess.run([sys.executable, "-m", "canspec", "decode", *args], input=stdin, capture_output=True, text=True, env=ENV, check=False, timeout=120)


def sample_lines(vectors, n=200):
    cases = [c for c in vectors["cases"] if c["kind"] != "raw_only"][:n]
    return [f"({1700000000 + i / 100:.6f}) can0 {c['frame_id']:08X}#{c['data']}" for i, c in enumerate(cases)], cases


def test_json_output_agrees_with_cantools(tmp_path, vectors, db):
    lines, cases = sample_lines(vectors)
    log = tmp_path / "bus.log"
    log.write_text("\n".join(lines) + "\n")
    proc = canspec_decode("--format", "json", str(log))
    assert proc.returncode == 0, proc.stderr
    records = [json.loads(line) for line in proc.stdout.splitlines()]
    assert len(records) == len(cases)
    for record, case in zip(records, cases):
        theirs = db.decode_message(case["frame_id"], bytes.fromhex(case["data"]))
        assert record["message"] == case["message"] and record["checksum_ok"] is True and record["channel"] == "can0"
        for name, value in theirs.items():
            mine = record["signals"][name]
            if isinstance(mine, str):  # an enum or special-value name
                assert mine == str(value), (case, name)
            else:
                assert mine == pytest.approx(value, abs=1e-9), (case, name)
    assert f"{log}: {len(cases):,} lines, {len(cases):,} frames, {len(cases):,} decoded, 0 remote, 0 error frames" in proc.stderr


def test_text_output_has_enum_names_units_and_the_three_line_forms(vectors):
    m = "1803B0A0#" + next(
        c["data"] for c in vectors["cases"] if c["message"] == "autocar_speed_command" and c["kind"] == "enum" and c["note"] == "gear_cmd=drive"
    )
    log = f"(1.500000) can1 {m}\n{m}\n  can0  {m[:8]}   [8]  {' '.join(m[9:][i:i + 2] for i in range(0, 16, 2))}\n"
    proc = canspec_decode("-", stdin=log)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.splitlines()
    assert len(out) == 3
    assert out[0].startswith("(1.500000) can1 1803B0A0 autocar_speed_command: ")
    assert out[1].startswith("1803B0A0 autocar_speed_command: ") and out[2].startswith("can0 1803B0A0 autocar_speed_command: ")
    assert "gear_cmd=drive" in out[0] and "accel_cmd=" in out[0] and " m/s²" in out[0]
    assert len({line.split(" autocar_speed_command: ")[1] for line in out}) == 1


def test_problems_are_reported_counted_and_never_stop_the_run(vectors):
    good = next(c for c in vectors["cases"] if c["message"] == "autocar_eps_command" and c["kind"] == "random")
    bad_checksum = good["data"][:-2] + f"{int(good['data'][-2:], 16) ^ 0xFF:02X}"
    log = "\n".join([
        f"(0.1) can0 1801B0A0#{good['data']}",
        "this is garbage",
        "(0.2) can0 1801B0A0#0011",  # truncated
        "(0.3) can0 18FEEE00#0011223344556677",  # unknown ID
        f"(0.4) can0 1801B0A0#{bad_checksum}",
        "(0.5) can0 1801B0A0#ZZ",
        "(0.6 can0 1801B0A0#00",
        "1801B0A0#R",
        "7FF#00",
        "(0.9) can0 20000080#0000000000000000",  # an error frame (CAN_ERR_FLAG)
        "(abc) can0 1801B0A0#00",
        "",
        "# a comment",
        "(0.7) can0 1801B0A0#001122334455667788",  # too long
        f"(0.8) can0 1801B0A0#{good['data']}",
    ]) + "\n"
    proc = canspec_decode("-", stdin=log)
    assert proc.returncode == 0
    err = proc.stderr
    assert "<stdin>:2: error: malformed line" in err
    assert "<stdin>:3: error: autocar_eps_command (0x1801B0A0): 2 data bytes, expected 8" in err
    assert "<stdin>:4: error: unknown frame ID 18FEEE00" in err
    assert "<stdin>:5: warning: autocar_eps_command (0x1801B0A0): checksum mismatch" in err
    assert "<stdin>:6: error: malformed line: data 'ZZ'" in err
    assert "<stdin>:9: error: unknown frame ID 7FF" in err
    assert "<stdin>:11: error: malformed line: time stamp (abc) is not a number" in err
    assert "<stdin>:14: error: autocar_eps_command (0x1801B0A0): 9 data bytes" in err
    assert ":8:" not in err and ":10:" not in err and "Traceback" not in err  # remote and error frames are not problems
    summary = err.strip().splitlines()[-1]
    assert summary.startswith("canspec decode: <stdin>: 15 lines, 9 frames, 3 decoded, 1 remote, 1 error frames; "
                              "problems: 4 malformed, 2 unknown id, 2 wrong length, 1 checksum")
    out = proc.stdout.splitlines()
    assert len(out) == 3 and out[1].endswith("[checksum mismatch]") and not out[0].endswith("]")
    assert canspec_decode("--strict", "-", stdin=log).returncode == 1
    assert canspec_decode("--strict", "-", stdin=f"1801B0A0#{good['data']}\n").returncode == 0


def test_binary_garbage_and_limits(tmp_path):
    log = tmp_path / "junk.log"
    log.write_bytes(os.urandom(20000) + b"\n\xff\xfe(1) can0 1801B0A0#00\n" + b"1801B0A0#0000000000000000\n")
    proc = canspec_decode("--max-problems", "3", str(log))
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert f"canspec decode: {log}: binary data, not a candump text log" in proc.stderr
    proc = canspec_decode(
        "--max-problems", "3", "--input-format", "candump", "-", stdin=("garbage\n" * 50 + "(1) can0 1801B0A0#00\n1801B0A0#0000000000000000\n")
    )
    assert proc.returncode == 0 and "Traceback" not in proc.stderr
    assert sum(line.startswith("<stdin>:") for line in proc.stderr.splitlines()) == 4  # three problems and the note that more are not shown
    assert "more problems not shown (--max-problems 3)" in proc.stderr
    assert proc.stdout.count("autocar_eps_command") == 1
    proc = canspec_decode("--max-problems", "-1", str(log))
    assert proc.returncode == 2 and "argument --max-problems: -1 is not in 0..1000000000" in proc.stderr, proc.stderr


def test_csv_output(vectors, tmp_path):
    lines, cases = sample_lines(vectors, 30)
    proc = canspec_decode("--format", "csv", "-", stdin="\n".join(lines) + "\n")
    rows = list(csv.DictReader(io.StringIO(proc.stdout)))
    assert len(rows) == sum(len(c["raw"]) for c in cases)
    first = cases[0]
    mine = {r["signal"]: int(r["raw"]) for r in rows if r["timestamp"] == "1700000000.000000"}
    assert mine == first["raw"]


def test_unreadable_input_and_bad_spec_are_clear(tmp_path):
    proc = canspec_decode(str(tmp_path / "missing.log"))
    assert proc.returncode == 2 and f"canspec decode: {tmp_path / 'missing.log'}: cannot read: No such file or directory" in proc.stderr
    proc = canspec_decode(str(tmp_path))
    assert proc.returncode == 2 and "is a directory" in proc.stderr and "Traceback" not in proc.stderr
    bad = tmp_path / "bad.yaml"
    bad.write_text("schema_version: 1\nkind: can_protocol\nprotocol: [\n")
    proc = canspec_decode("--spec", str(bad), "-", stdin="")
    assert proc.returncode == 2 and "bad.yaml" in proc.stderr and "Traceback" not in proc.stderr


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet=st.sampled_from("0123456789ABCDEFabcdef#.()[] Rrcan\t-x"), max_size=60) | st.text(max_size=60))
def test_line_parser_raises_only_line_errors(line):
    try:
        frame = parse_line(line)
    except LineError:
        return
    if frame is not None:
        assert 0 <= frame.frame_id <= 0x1FFFFFFF and len(frame.data) <= 64


def test_compiled_text_decoder_equals_the_generic_codec(can, vectors, tmp_path):
    from canspec.pipeline import compile_spec
    from canspec.reference import codec

    decoders = {m.frame_id: (m, codec.text_decoder(m)) for m in can.messages}
    for case in vectors["cases"]:
        msg, decoder = decoders[case["frame_id"]]
        data = bytes.fromhex(case["data"])
        raw = codec.unpack(msg, data)
        assert raw == {s.name: case["raw"][s.name] for s in msg.data_signals}
        assert decoder(codec.frame_word(data)) == ", ".join(codec.signal_text(s, raw[s.name]) for s in msg.data_signals)
    # signed and wide fields take the inline paths; a label on a signed field
    spec = tmp_path / "s.yaml"
    spec.write_text(
        "schema_version: 1\nkind: can_protocol\nprotocol: {name: t, version: 1.0.0}\n"
        "bus: {bitrate: 500000, id_format: standard, addressing: none, byte_order: little_endian}\nnodes: [{name: A}]\n"
        "value_tables: {low: {-8: lowest}}\n"
        "messages:\n  - {name: m, id: 1, sender: A, receivers: ALL, dlc: 3, signals: [\n"
        "      {name: n, start: 0, len: 4, signed: true, values: low},\n"
        "      {name: t, start: 8, len: 16, signed: true, factor: 0.5, offset: -1, unit: '%'}]}\n",
        encoding="utf-8",
    )
    compiled = compile_spec(spec)
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    decoder = codec.text_decoder(compiled.spec.can.messages[0])
    assert decoder((0xFFFF << 8) | 0x8) == "n=lowest, t=-1.5 %"
    assert decoder((0x0003 << 8) | 0x7) == "n=7, t=0.5 %"


@pytest.mark.parametrize("line", ["-1#00", "0x1F#00", "1_0#00", "+7F#00", "123#0", "(1.0) can0", "(1.0 can0 123#00", "can0 123 [2] 00", "can0 123 [x] 00",
                                  "(abc) can0 123#00", "(1.2.3) can0 123#00", "(1.0) can0 123#00 junk", "40000000#00"])
def test_malformed_lines(line):
    with pytest.raises(LineError):
        parse_line(line)


def test_line_forms():
    assert parse_line("(1.5) vcan0 18FF0123#01.02") == (1.5, "vcan0", 0x18FF0123, True, b"\x01\x02", DATA, 0)
    assert parse_line("123#") == (None, None, 0x123, False, b"", DATA, 0)
    assert parse_line("  can0  1806A0B0   [2]  0A 0B") == (None, "can0", 0x1806A0B0, True, b"\x0a\x0b", DATA, 0)
    assert parse_line("(1.5)  can0  RX - -  123   [1]  0A  '.'") == (1.5, "can0", 0x123, False, b"\x0a", DATA, 0)
    assert parse_line("  can0  123   [2]  remote request") == (None, "can0", 0x123, False, b"", REMOTE, 0)
    assert parse_line("(2.0) can0 123#R2 R") == (2.0, "can0", 0x123, False, b"", REMOTE, 0)
    assert parse_line("  can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME")[4:] == (bytes([0, 4]) + bytes(6), ERROR, 0)


def test_can_fd_line_forms():
    """candump's CAN FD forms (lib.c): `ID##<flags digit><data>` (linux/can.h CANFD_BRS 1, CANFD_ESI 2),
    and the screen form's two-digit length, with -x's B (BRS) / E (ESI) marks."""
    fd, brs, esi = fr.FD, fr.BRS, fr.ESI
    assert parse_line("123##1112233") == (None, None, 0x123, False, bytes.fromhex("112233"), DATA, fd | brs)
    assert parse_line("(3.0) can1 1806A0B0##0" + "AB" * 64) == (3.0, "can1", 0x1806A0B0, True, bytes([0xAB] * 64), DATA, fd)
    assert parse_line("123##3" + "00" * 12)[4:] == (bytes(12), DATA, fd | brs | esi)
    assert parse_line("123##2")[4:] == (b"", DATA, fd | esi)
    assert parse_line("  can0  123  [12]  " + "01 " * 12)[4:] == (bytes([1] * 12), DATA, fd)
    assert parse_line("  can0  123  [08]  " + "01 " * 8)[4:] == (bytes([1] * 8), DATA, fd)  # an FD frame of 8 bytes
    assert parse_line("(1.5)  can0  RX B E  123  [16]  " + "02 " * 16)[4:] == (bytes([2] * 16), DATA, fd | brs | esi)
    assert parse_line("(1.5)  can0  RX B -  123  [64]  " + "02 " * 64)[4:] == (bytes([2] * 64), DATA, fd | brs)


@pytest.mark.parametrize("line", ["123##", "123##G00", "123##1" + "00" * 65, "123##1123"])
def test_malformed_can_fd_lines(line):
    with pytest.raises(LineError):
        parse_line(line)


def test_can_fd_lines_in_bulk():
    """FD lines amid classic ones: the bulk reader hands them to the line reader and keeps their bytes and flags."""
    from canspec.logs.candump_bulk import read_chunk

    text = "(1.0) can0 123#0102\n(2.0) can0 2B0##1" + "11" * 64 + "\n(3.0) can0 3C0##0" + "22" * 12 + "\n  can0  123   [8]  " + "03 " * 8 + "\n"
    batch, problems, count = read_chunk(text.encode(), 1)
    assert count == 4 and problems == []
    assert batch.dlc.tolist() == [2, 64, 12, 8] and batch.flags.tolist() == [0, fr.FD | fr.BRS, fr.FD, 0]
    assert [batch.frame_bytes(i) for i in range(4)] == [b"\x01\x02", bytes([0x11] * 64), bytes([0x22] * 12), bytes([3] * 8)]


def test_line_forms_blank():
    assert parse_line("   ") is None and parse_line("# comment") is None


def test_gen_and_check_do_not_import_the_logs_extra():
    code = ("import sys; from canspec import cli; cli.build_parser(); "
            "print(sorted(m for m in ('numpy', 'pyarrow', 'can', 'matplotlib', 'tqdm', 'asammdf') if m in sys.modules))")
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=ENV, check=True).stdout.strip() == "[]"


def test_bulk_text_equals_the_per_frame_text_decoder(can, vectors, tmp_path):
    """bulktext (a column of texts per signal) prints exactly what codec.text_decoder prints, on
    every vector case and on random frames of the mixed spec (64-bit, signed, labelled fields)."""
    import random

    import numpy as np
    from canspec.logs import bulktext
    from canspec.logs import frames as fr
    from canspec.logs.fields import MessageFrames
    from canspec.pipeline import compile_spec
    from canspec.reference import codec
    from repo_paths import ROOT

    mixed = compile_spec(ROOT / "tests" / "logs" / "specs" / "mixed.yaml").spec.can
    rng = random.Random(3)
    cases = [(can.by_id(c["frame_id"]), codec.frame_word(bytes.fromhex(c["data"]))) for c in vectors["cases"]]
    cases += [(m, rng.getrandbits(8 * m.dlc)) for m in mixed.messages for _ in range(300)]
    fd = compile_spec(ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml").spec.can  # Motorola, FD, floats
    cases += [(m, rng.getrandbits(8 * m.dlc)) for m in fd.messages for _ in range(300)]
    for msg in {m for m, _ in cases}:
        words = [w for m, w in cases if m is msg]
        payloads = [w.to_bytes(msg.dlc, "little") for w in words]
        data = fr.data_matrix(payloads)
        frames = MessageFrames(msg, np.array([w & (2**64 - 1) for w in words], dtype=np.uint64), None if data is None else data[:, : msg.dlc])
        assert bulktext.message_texts(frames, {}) == [codec.text_decoder(msg)(w) for w in words], msg.name


LINE_PIECES = st.sampled_from([
    "(1.5)", "(1700000000.000100)", "(abc)", "(1.2.3)", "(2023-11-14 22:13:20.123456)", "can0", "vcan12", "RX", "-", "123", "7FF", "800", "1806A0B0",
    "20000080", "3FFFFFFF", "[0]", "[2]", "[8]", "[12]", "[x]", "01", "0A", "ff", "0", "GG", "123#0102", "1806A0B0#R", "123#", "7FF##1" + "00" * 9,
    "7FF##0" + "00" * 64, "123##3", "[08]", "[64]", "B", "E", "ERRORFRAME", "remote", "request", "'..'", "R", "T", "#", ";"])


@settings(max_examples=400, deadline=None)
@given(st.lists(st.lists(LINE_PIECES, max_size=12).map(" ".join) | st.lists(LINE_PIECES, max_size=12).map("  ".join), min_size=1, max_size=30))
def test_bulk_reader_equals_the_line_reader(lines):
    """Every line the NumPy reader takes apart, it reads as candump.parse_line does; every other
    line it hands to parse_line — so the frames and problems are exactly the line reader's."""
    import math

    from canspec.logs.candump_bulk import read_chunk

    batch, problems, count = read_chunk(("\n".join(lines) + "\n").encode(), 1)
    assert count == len(lines)
    got = {int(i): row for i, *row in zip(batch.line, batch.timestamp.tolist(), batch.channel_names().tolist(), batch.frame_id.tolist(),
                                          batch.extended.tolist(), batch.kind.tolist(), batch.dlc.tolist(), batch.word.tolist(),
                                          [batch.frame_bytes(i) for i in range(len(batch))], batch.flags.tolist())}
    bad = {line for line, _ in problems}
    for i, line in enumerate(lines, 1):
        try:
            frame = parse_line(line)
        except LineError:
            assert i in bad and i not in got, line
            continue
        if frame is None:
            assert i not in got and i not in bad, line
            continue
        t, *rest = got[i]
        assert (None if math.isnan(t) else t, *rest) == (frame.timestamp, frame.channel or "", frame.frame_id, frame.extended, frame.kind,
                                                          len(frame.data), int.from_bytes(frame.data[:8], "little"), frame.data, frame.flags), line
