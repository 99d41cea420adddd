"""The communication matrix read back with openpyxl and pandas: every signal of a spec is there with
exactly the IR's values, the node columns say who sends and who receives, and the companion sheets
list every value table, node, change item and erratum — for the shipped spec, every valid fixture
and hand-written edge specs (English-only, 11-bit IDs, event-driven, no J1939, DLC 0, 64-bit
fields, negative scaling, a formula-like text)."""

from __future__ import annotations

import math
import re
import struct
from fractions import Fraction
from pathlib import Path

import pytest
from canspec import ir
from canspec.pipeline import compile_spec
from canspec.targets.xlsx import render_xlsx
from repo_paths import ROOT
from xlsx_support import MATRIX, Book, raw_value, read, same_number, value_lines

VALID = ROOT / "tests" / "fixtures" / "valid"

EDGE = """\
schema_version: 1
kind: can_protocol
protocol: {name: edge_bus, version: 0.3.1}
bus: {bitrate: 500000, id_format: standard, addressing: none, byte_order: little_endian}
nodes:
  - {name: BODY}
  - {name: GATEWAY}
  - {name: TESTER}
value_tables:
  state: {-2: fault, 0: idle, 1: run}
messages:
  - {name: wide, id: 0x123, sender: BODY, receivers: [GATEWAY, TESTER],
     signals: [{name: big_unsigned, start: 0, len: 64, factor: 0.001, unit: mJ}]}
  - {name: wide_signed, id: 0x124, sender: GATEWAY, receivers: ALL, cycle_ms: 10,
     signals: [{name: big_signed, start: 0, len: 64, signed: true, factor: 0.5, offset: -3, desc: "=SUM(A1) is text, not a formula"}]}
  - {name: empty, id: 0x7FF, dlc: 0, sender: TESTER, receivers: [BODY], signals: []}
  - name: mixed
    id: 0x1ABCDE12
    extended: true
    dlc: 3
    sender: BODY
    receivers: [BODY, GATEWAY]
    cycle_ms: 0
    signals:
      - {name: st, start: 0, len: 3, signed: true, values: state, range: [-2, 1]}
      - {name: temp, start: 3, len: 10, signed: true, factor: -0.25, offset: 20, unit: °C, special: {-512: invalid}}
      - {name: tiny, start: 13, len: 1}
"""


def compiled(path: Path) -> ir.Spec:
    result = compile_spec(path)
    assert result.spec is not None, "\n".join(p.format() for p in result.problems)
    return result.spec


def workbook(spec: ir.Spec) -> Book:
    files = render_xlsx(spec)
    assert list(files) == [f"xlsx/{spec.can.name}.xlsx"]
    return read(next(iter(files.values())))


def expected_rows(can: ir.CanProtocol) -> list[tuple[ir.Message, ir.Signal | None]]:
    return [(m, s) for m in can.messages for s in (m.data_signals or (None,))]


def check_message(row: dict, msg: ir.Message, can: ir.CanProtocol) -> None:
    assert row["Message name"] == msg.name
    assert int(row["Message ID"], 16) == msg.frame_id and len(row["Message ID"]) == (10 if msg.is_extended else 5)
    assert row["Frame format"] == ("Extended" if msg.is_extended else "Standard") + (" FD" if msg.is_fd else "")
    assert ("BRS" in row) == can.has_fd  # the column only on a bus with FD frames
    if can.has_fd:
        assert row["BRS"] == (("Yes" if msg.brs else "No") if msg.is_fd else None)
    assert (row["Send type"], row["Cycle time (ms)"]) == (("Cycle", msg.cycle_ms) if msg.cycle_ms else ("Event", None))
    assert row["DLC (bytes)"] == msg.dlc
    sender = next((n.label for n in can.nodes if n.name == msg.sender), msg.sender)
    assert row["Sender"] == sender
    if can.bus.is_j1939:
        assert int(row["PGN"], 16) == msg.j1939.pgn
    for node in can.nodes:
        flags = set((row[node.label] or "").split("/")) - {""}
        assert flags == {f for f, on in (("S", node.name == msg.sender), ("R", node.name in msg.receivers)) if on}, (msg.name, node.name)


def check_signal(row: dict, msg: ir.Message, sig: ir.Signal) -> None:
    assert row["Signal name"] == sig.name
    assert (row["Start bit"], row["Start byte"], row["Length (bits)"]) == (sig.start, sig.start // 8, sig.length)
    assert row["Byte order"] == {"little_endian": "Intel", "big_endian": "Motorola"}[sig.byte_order]  # the signal's, not the bus's
    if sig.is_float:
        check_float(row, msg, sig)
    else:
        assert row["Signedness"] == ("Signed" if sig.signed else "Unsigned")
        for key, value in (("Factor", sig.factor), ("Offset", sig.offset), ("Physical min", sig.phys_min), ("Physical max", sig.phys_max)):
            assert same_number(row[key], value), (msg.name, sig.name, key, row[key], value)
        assert (raw_value(sig, row["Raw min (hex)"]), raw_value(sig, row["Raw max (hex)"])) == (sig.raw_min, sig.raw_max)
        assert sig.phys_min == min(sig.physical(sig.raw_min), sig.physical(sig.raw_max))  # the pair is consistent
    assert row["Initial value (hex)"].startswith("0x0 (")
    assert (row["Unit"] or "") == sig.unit
    assert (row["Description"] or "") == "\n".join(t for t in (sig.desc, sig.desc_zh) if t)
    for key, special in (("Value table", False), ("Invalid / special values", True)):
        got = value_lines(sig, row[key])
        want = [(lb.raw, " ".join(t for t in (lb.label, lb.label_zh) if t)) for lb in sig.labels if lb.is_special == special]
        assert got == want, (msg.name, sig.name, key)
    if "Signal name (Chinese)" in row:
        assert (row["Signal name (Chinese)"] or "") == sig.zh


def _floats_between(a: Fraction, b: Fraction, fmt: str) -> list[Fraction]:
    """The format's floats nearest each of a and b (by struct's rounding): a float strictly between
    the raw end and its bound would be one of them."""
    return [Fraction(struct.unpack(fmt, struct.pack(fmt, float(x)))[0]) for x in (a, b)]


def check_float(row: dict, msg: ir.Message, sig: ir.Signal) -> None:
    """An IEEE field: its type named; the documented range, else the format's largest finite values; raw
    limits the bit patterns of those values (struct, the oracle, reads them back)."""
    assert row["Signedness"] == f"Float{sig.length} (IEEE 754)" and (row["Factor"], row["Offset"]) == (1, 0)
    largest = Fraction(struct.unpack(">f" if sig.length == 32 else ">d", bytes.fromhex("7F7FFFFF" if sig.length == 32 else "7FEFFFFFFFFFFFFF"))[0])
    want = (sig.doc_min, sig.doc_max) if sig.doc_min is not None else (-largest, largest)
    for key, raw_key, value in (("Physical min", "Raw min (hex)", want[0]), ("Physical max", "Raw max (hex)", want[1])):
        cell = row[key]
        assert (Fraction(float(cell)) == value) if isinstance(cell, str) else same_number(cell, value), (msg.name, sig.name, key, cell)
        # the raw end: the format's float nearest the bound on the range's side (the bound itself where it is one)
        fmt, up = (">f" if sig.length == 32 else ">d"), key == "Physical min"
        got = Fraction(struct.unpack(fmt, int(row[raw_key], 16).to_bytes(sig.length // 8, "big"))[0])
        assert (got >= value) if up else (got <= value), (msg.name, sig.name, raw_key)
        assert got == Fraction(struct.unpack(fmt, struct.pack(fmt, float(got)))[0])  # a float of the format
        assert not any(value <= f <= got if up else got <= f <= value for f in _floats_between(got, value, fmt) if f != got), (msg.name, sig.name)
    assert ("NaN and ±Inf allowed" in (row["Notes"] or "")) == (sig.doc_min is None)


def check_matrix(spec: ir.Spec, book: Book) -> None:
    can = spec.can
    rows = book.rows(MATRIX)
    want = expected_rows(can)
    assert [(r["Message name"], r["Signal name"]) for r in rows] == [(m.name, s.name if s else None) for m, s in want]
    for row, (msg, sig) in zip(rows, want):
        check_message(row, msg, can)
        if sig is not None:
            check_signal(row, msg, sig)
        else:
            assert all(row[k] is None for k in ("Signal name", "Start bit", "Factor", "Raw min (hex)"))
    # Chinese-name columns exist exactly when the spec names something in Chinese.
    headers = {h.split("\n")[-1] for h in book.headers(MATRIX)}
    assert ("Signal name (Chinese)" in headers) == any(s.zh for m in can.messages for s in m.data_signals)
    assert ("Message name (Chinese)" in headers) == any(m.zh for m in can.messages)
    assert ("PGN" in headers) == can.bus.is_j1939
    # pandas reads the same sheet: one row per signal, node columns counting senders and receivers.
    df = book.frames[MATRIX]
    df.columns = [c.split("\n")[-1] for c in df.columns]
    assert len(df) == len(want)
    assert df.groupby("Message name", sort=False).size().to_dict() == {m.name: len(m.data_signals) or 1 for m in can.messages}
    signals = df["Signal name"].dropna().tolist()
    assert signals == [s.name for m in can.messages for s in m.data_signals]
    for node in can.nodes:
        col = df[node.label].fillna("")
        assert col.str.contains("S").sum() == sum(len(m.data_signals) or 1 for m in can.messages if m.sender == node.name)
        assert col.str.contains("R").sum() == sum(len(m.data_signals) or 1 for m in can.messages if node.name in m.receivers)


def check_companions(spec: ir.Spec, book: Book) -> None:
    can = spec.can
    tables = book.rows("值表 Value tables") if can.value_tables else []
    assert [(r["Value table"], r["Raw value"], r["Identifier"]) for r in tables] == [(vt.name, e.raw, e.name) for vt in can.value_tables for e in vt.entries]
    nodes = book.rows("节点 Nodes")
    assert [r["Node"] for r in nodes] == [n.name for n in can.nodes]
    if spec.changelog is not None:
        items = book.rows("修订历史 History")
        assert len(items) == sum(len(v.items) or 1 for v in spec.changelog.versions)
        assert {r["Version"] for r in items} == {f"V{v.version}" for v in spec.changelog.versions}
    else:
        assert "修订历史 History" not in book.wb.sheetnames
    about = {r["Item"]: r["Value"] for r in book.rows("说明 About")}
    assert about["规范哈希 Spec sha256"] == spec.sha256 and spec.version in about["规范 Spec"]
    assert ("排列格式 Byte order" in about, "浮点 Float" in about, "CAN FD" in about) == (can.has_big_endian, can.has_float, can.has_fd)


def edge_spec(tmp_path: Path) -> ir.Spec:
    path = tmp_path / "edge.yaml"
    path.write_text(EDGE, encoding="utf-8")
    return compiled(path)


def test_shipped_spec(spec):
    book = workbook(spec)
    check_matrix(spec, book)
    check_companions(spec, book)
    assert book.wb.sheetnames == ["通信矩阵 Matrix", "值表 Value tables", "节点 Nodes", "修订历史 History", "勘误 Errata", "说明 About"]
    # Every erratum of spec/ERRATA.md has its row; where the spec cites one, the row says where.
    described = re.findall(r"^\| ([A-Z]+\d+) \|", (ROOT / "spec" / "ERRATA.md").read_text(encoding="utf-8"), re.MULTILINE)
    errata = {r["Erratum"]: r for r in book.rows("勘误 Errata")}
    assert described and list(errata)[: len(described)] == described
    assert "0x1801B0A0 autocar_eps_command.max_angular_speed" in errata["E10"]["Cited by"].splitlines()
    assert errata["E10"]["Section"] == "CAN protocol (D)" and "8 bits × 2 encode at most 510" in errata["E10"]["Resolution"]


@pytest.mark.parametrize("path", sorted(VALID.glob("*.yaml")), ids=lambda p: p.stem)
def test_every_valid_fixture(path):
    spec = compiled(path)
    if spec.can is None:
        assert render_xlsx(spec) == {}  # no CAN protocol, no matrix
        return
    book = workbook(spec)
    check_matrix(spec, book)
    check_companions(spec, book)


def test_edge_spec(tmp_path):
    spec = edge_spec(tmp_path)
    book = workbook(spec)
    check_matrix(spec, book)
    check_companions(spec, book)
    rows = {(r["Message name"], r["Signal name"]): r for r in book.rows(MATRIX)}
    # 64-bit fields: exact hex and exact physical text where a double would round.
    assert rows[("wide", "big_unsigned")]["Raw max (hex)"] == "0xFFFFFFFFFFFFFFFF"
    assert rows[("wide", "big_unsigned")]["Physical max"] == "18446744073709551.615"
    assert rows[("wide_signed", "big_signed")]["Raw min (hex)"] == "0x8000000000000000 (-9223372036854775808)"
    assert rows[("mixed", "temp")]["Invalid / special values"] == "0x200 (-512): Invalid"
    assert (rows[("mixed", "temp")]["Physical min"], rows[("mixed", "temp")]["Physical max"]) == (-107.75, 148)
    assert rows[("empty", None)]["DLC (bytes)"] == 0 and rows[("empty", None)]["Send type"] == "Event"
    assert rows[("mixed", "st")]["BODY"] == "S/R"  # a sender that also lists itself as a receiver
    cell = next(c for c in book.wb[MATRIX]["I"] if c.value and str(c.value).startswith("=SUM"))
    assert cell.data_type == "s"  # text stays text: no formula injection
    assert not any(isinstance(v, float) and math.isnan(v) for r in rows.values() for v in r.values())
    assert "Chinese" not in " ".join(book.headers("值表 Value tables") + book.headers("节点 Nodes"))


def decimal(value: object) -> Fraction:
    """The decimal a cell or DBC number stands for (a float by its shortest repr, text exactly)."""
    return Fraction(repr(value)) if isinstance(value, float) else Fraction(str(value))


def test_shipped_matrix_agrees_with_the_dbc(spec, db):
    """cantools reading the generated DBC, the independent oracle: same IDs, cycle times, senders and
    receivers, and per signal the same bits, scaling, range, unit and value table."""
    book = workbook(spec)
    label_to_node = {r["Label"]: r["Node"] for r in book.rows("节点 Nodes")}
    for row in book.rows(MATRIX):
        m = db.get_message_by_frame_id(int(row["Message ID"], 16))
        assert (m.name, m.is_extended_frame, m.length, m.cycle_time) == (
            row["Message name"], row["Frame format"] == "Extended", row["DLC (bytes)"], row["Cycle time (ms)"])
        senders = {label_to_node[k] for k, v in row.items() if k in label_to_node and "S" in (v or "")}
        receivers = {label_to_node[k] for k, v in row.items() if k in label_to_node and "R" in (v or "")}
        assert set(m.senders) == senders
        if row["Signal name"] is None:
            assert m.signals == []
            continue
        s = m.get_signal_by_name(row["Signal name"])
        assert (s.start, s.length, s.is_signed, s.byte_order) == (row["Start bit"], row["Length (bits)"], row["Signedness"] == "Signed", "little_endian")
        dbc = [decimal(v) for v in (s.scale, s.offset, s.minimum, s.maximum)]
        assert dbc == [decimal(row[k]) for k in ("Factor", "Offset", "Physical min", "Physical max")], s.name
        assert (s.unit or "") == (row["Unit"] or "") and set(s.receivers) == receivers
        named = [line.split(":")[0] for key in ("Value table", "Invalid / special values") for line in (row[key] or "").splitlines()]
        assert sorted(int(raw, 16) for raw in named) == sorted(int(raw) for raw in (s.choices or {})), s.name  # VAL_: table + specials


def test_fd_matrix_agrees_with_its_dbc(tmp_path):
    """The Motorola / FD / float fixture: cantools reading the DBC generated from the same spec gives
    each row's byte order, start bit, length, float flag, FD flag and BRS (the DBC's CANFD_BRS)."""
    import cantools
    from canspec.targets import registry

    spec = compiled(VALID / "motorola_fd_float.yaml")
    (_, dbc_text), = registry()["dbc"].render(spec).items()
    db = cantools.database.load_string(dbc_text.decode("utf-8"), database_format="dbc", strict=True)
    rows = workbook(spec).rows(MATRIX)
    orders = {"little_endian": "Intel", "big_endian": "Motorola"}
    for row in rows:
        m = db.get_message_by_name(row["Message name"])
        brs = m.dbc.attributes.get("CANFD_BRS")
        assert row["Frame format"].endswith(" FD") == m.is_fd and row["BRS"] == (("Yes" if brs.value else "No") if m.is_fd else None)
        s = m.get_signal_by_name(row["Signal name"])
        assert (orders[s.byte_order], s.start, s.start // 8, s.length) == (row["Byte order"], row["Start bit"], row["Start byte"], row["Length (bits)"])
        assert s.is_float == row["Signedness"].startswith("Float")
    assert {r["Byte order"] for r in rows} == {"Intel", "Motorola"} and {r["BRS"] for r in rows} == {None, "Yes", "No"}
    about = {r["Item"]: r["Value"] for r in workbook(spec).rows("说明 About")}
    assert "Motorola: the start bit is its most significant bit" in about["排列格式 Byte order"] and "CAN FD" in about
