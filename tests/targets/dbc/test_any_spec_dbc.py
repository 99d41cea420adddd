"""The DBC of every valid fixture (tests/fixtures/valid/): it loads strictly in cantools and in
canmatrix, cantools agrees with every vector case, and it says what the spec says — J1939
attributes only on a J1939 bus, frame formats, send types and cycle times, station addresses only
for nodes with one, SigType, merged value labels, no Chinese where the spec has none."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from canspec.targets.dbc.naming import MAX_NAME
from dbc_support import attribute, can_fixtures, check_oracle, compiled, load_canmatrix, load_cantools, spec_names, vectors, write_dbc

FIXTURES = can_fixtures()
CJK = re.compile(r"[\u3000-\u9fff\uff00-\uffef]")


@pytest.fixture(scope="module", params=FIXTURES, ids=lambda p: p.stem)
def case(request, tmp_path_factory):
    spec = compiled(request.param)
    dbc = write_dbc(spec, tmp_path_factory.mktemp(request.param.stem))
    return spec, dbc, load_cantools(dbc)


def test_the_fixtures_cover_the_any_spec_features():
    specs = [compiled(p).can for p in FIXTURES]
    assert any(not c.bus.is_j1939 and c.has_standard for c in specs)
    assert any(m.dlc == 0 for c in specs for m in c.messages)
    assert any(s.length == 64 and s.signed for c in specs for m in c.messages for s in m.signals)
    assert any(c.has_multiframe for c in specs) and any(not m.is_cyclic for c in specs for m in c.messages)
    signals = [s for c in specs for m in c.messages for s in m.signals]
    assert any(s.is_big_endian for s in signals) and any(s.is_float and s.length == n for s in signals for n in (32, 64))
    fd = [m for c in specs for m in c.messages if m.is_fd]
    assert any(m.brs for m in fd) and any(not m.brs for m in fd) and any(m.dlc > 8 for m in fd)


def test_loads_in_canmatrix(case):
    spec, dbc, db = case
    matrix = load_canmatrix(dbc)
    assert len(matrix.frames) == len(db.messages) == len(spec.can.messages)
    for msg in spec.can.messages:
        frame = matrix.frame_by_name(msg.name)
        assert frame.arbitration_id.id == msg.frame_id and frame.arbitration_id.extended == msg.is_extended
        assert frame.size == msg.dlc and len(frame.signals) == len(msg.data_signals)


def test_cantools_agrees_with_every_vector(case):
    spec, _, db = case
    doc = vectors(spec)
    assert check_oracle(db, doc) == len(doc["cases"])  # every case checked (none for a spec without messages)


def test_messages_say_what_the_spec_says(case):
    spec, _, db = case
    can = spec.can
    assert (attribute(db, "ProtocolType") == "J1939") == can.bus.is_j1939
    # Vector's bus attributes: "CAN FD" once a frame is FD; the data-phase bitrate only when the spec gives one
    assert (attribute(db, "BusType"), db.buses[0].baudrate) == ("CAN FD" if can.has_fd else "CAN", can.bus.bitrate)
    assert attribute(db, "BaudrateCANFD") == can.bus.data_bitrate
    for msg in can.messages:
        m = db.get_message_by_name(msg.name)
        assert (m.frame_id, m.is_extended_frame, m.length, m.is_fd) == (msg.frame_id, msg.is_extended, msg.dlc, msg.is_fd)
        assert attribute(m, "VFrameFormat") == _vframe_format(can.bus.is_j1939, msg)
        # CANFD_BRS on every FD frame (0 or 1: tools differ on the default), never on a classic one
        assert attribute(m, "CANFD_BRS") == (int(msg.brs) if msg.is_fd else None)
        assert msg.is_fd or not msg.brs
        assert m.cycle_time == msg.cycle_ms
        own = next((d for d in can.dbc_attribute_defs if d.name == "GenMsgSendType"), None)  # a source's own, kept as it was
        if own is not None:
            assert m.send_type == dict(msg.dbc_attributes).get(own.name, own.default)
        else:
            assert m.send_type == (None if can.dbc_as_imported else "cyclic" if msg.cycle_ms else "noMsgSendType")
        assert sorted(spec_names(m).values()) == sorted(s.name for s in msg.data_signals)
    for node in db.nodes:
        sa = next(n.sa for n in can.nodes if n.name == node.name)
        assert attribute(node, "NmStationAddress") == sa  # none written for a node without one


def test_signals_say_what_the_spec_says(case):
    spec, _, db = case
    for msg in spec.can.messages:
        m = db.get_message_by_name(msg.name)
        for s in m.signals:
            sig = msg.signal(spec_names(m)[s.name])
            # the spec numbers a Motorola field's start as the DBC does (its MSB), so start is start in both orders
            assert (s.start, s.length, s.is_signed, s.byte_order) == (sig.start, sig.length, sig.signed, sig.byte_order)
            assert s.is_float == sig.is_float and (not sig.is_float or s.length in (32, 64))
            assert {int(k): str(v) for k, v in (s.choices or {}).items()} == {lb.raw: lb.name for lb in sig.labels}
            if msg.multiframe is not None and sig.name == msg.multiframe.payload_signal:
                assert attribute(s, "SigType") == 3  # ASCII
            if s.name != sig.name:
                assert len(s.name) <= MAX_NAME and s.name.endswith(msg.id_text[2:]) and attribute(s, "SpecSignalName") == sig.name


def _vframe_format(j1939: bool, msg) -> int:
    """Vector's VFrameFormat values: StandardCAN_FD 14 / ExtendedCAN_FD 15, J1939PG 3, ExtendedCAN 1 / StandardCAN 0."""
    if msg.is_fd:
        return 15 if msg.is_extended else 14
    return 3 if j1939 else int(msg.is_extended)


def test_no_chinese_where_the_spec_has_none_and_no_empty_comment_parts(case):
    spec, dbc, _ = case
    text = dbc.read_text(encoding="utf-8")
    has_zh = any(n.zh for n in spec.can.nodes) or any(m.zh or any(s.zh or s.desc_zh or any(lb.label_zh for lb in s.labels) for s in m.data_signals)
                                                       for m in spec.can.messages)
    assert bool(CJK.search(text)) == has_zh
    for comment in re.findall(r'^CM_ (?:BU_|BO_|SG_) .*?"(.*)";$', text, re.MULTILINE):
        assert comment and not comment.startswith(" | ") and not comment.endswith(" | ") and " |  | " not in comment
        assert "()" not in comment and "None" not in comment


def test_spec_and_its_dbc_do_not_differ(case, tmp_path):
    from canspec.diff.compare import compare
    from canspec.diff.inputs import load_model

    spec, dbc, _ = case
    source = next(str(p) for p in FIXTURES if compiled(p) is spec)
    assert [c for c in compare(load_model(source), load_model(str(dbc))) if c.cls != "docs"] == []
    assert [c for c in compare(load_model(str(dbc)), load_model(source)) if c.cls != "docs"] == []
    assert Path(source).is_file()
