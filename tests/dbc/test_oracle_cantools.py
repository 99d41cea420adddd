"""The independent oracle: cantools reads the generated DBC and must agree with every vector
case on raw values and bytes (decode and encode), and on physical values."""

from __future__ import annotations

import math

from repo_paths import GENERATED

DBC = GENERATED / "dbc" / "kaiwo_gateway.dbc"


def test_dbc_matches_spec_shape(db, can):
    assert len(db.messages) == len(can.messages) == 25
    for msg in can.messages:
        m = db.get_message_by_frame_id(msg.frame_id)
        assert m.is_extended_frame and m.length == msg.dlc and m.cycle_time == msg.cycle_ms
        assert {s.name for s in m.signals} == {s.name for s in msg.data_signals}


def test_every_case_agrees_with_cantools(db, vectors):
    checked = 0
    for case in vectors["cases"]:
        data = bytes.fromhex(case["data"])
        raw = db.decode_message(case["frame_id"], data, decode_choices=False, scaling=False)
        assert raw == case["raw"], case
        encoded = db.encode_message(case["frame_id"], case["raw"], scaling=False, strict=False)
        assert encoded == data, case
        phys = db.decode_message(case["frame_id"], data, decode_choices=False, scaling=True)
        msg = db.get_message_by_frame_id(case["frame_id"])
        for sig in msg.signals:
            expected = case["physical"][sig.name]
            tolerance = abs(sig.scale) / 2 * (1 + 1e-9) if case["kind"] == "tie" else 1e-9 * max(1.0, abs(expected))
            assert math.isclose(phys[sig.name], expected, abs_tol=tolerance), (case, sig.name)
        checked += 1
    print(f"cantools oracle: {checked} cases agree")
    assert checked == len(vectors["cases"]) >= 25 * 50


def test_cantools_physical_encode_agrees_off_ties(db, vectors):
    """cantools rounds with Python's round() on doubles; away from ties it must agree with us."""
    checked = 0
    for case in vectors["cases"]:
        if case["kind"] in ("tie", "raw_only", "special"):
            continue
        encoded = db.encode_message(case["frame_id"], case["physical"], scaling=True, strict=False)
        assert encoded == bytes.fromhex(case["data"]), case
        checked += 1
    assert checked > 1000
