"""The DBC loads in cantools and canmatrix and carries the J1939 attributes, value tables,
receivers, units, ranges and comments."""

from __future__ import annotations

import canmatrix.formats
from repo_paths import GENERATED

DBC = GENERATED / "dbc" / "kaiwo_gateway.dbc"


def test_canmatrix_loads_without_errors():
    dbs = canmatrix.formats.loadp(str(DBC), dbcImportEncoding="utf-8")
    matrix = dbs[""]
    assert len(matrix.frames) == 25
    assert matrix.attributes["ProtocolType"] == "J1939"
    frame = matrix.frame_by_id(canmatrix.ArbitrationId(0x1813A0B0, extended=True))
    assert frame.attributes["GenMsgCycleTime"] == "100"


def test_j1939_attributes(db, can):
    attrs = db.dbc.attributes
    assert attrs["ProtocolType"].value == "J1939" and attrs["Baudrate"].value == 250000
    for node in db.nodes:
        assert node.dbc.attributes["NmStationAddress"].value == next(n.sa for n in can.nodes if n.name == node.name)
    for msg in can.messages:
        m = db.get_message_by_frame_id(msg.frame_id)
        assert m.dbc.attributes["VFrameFormat"].value == 3  # J1939PG
        assert m.dbc.attributes["GenMsgCycleTime"].value == msg.cycle_ms
        sig_types = {s.name: s.dbc.attributes["SigType"].value for s in m.signals}
        if msg.counter:
            assert sig_types[msg.counter.signal] == 11  # MessageCounter
        if msg.checksum:
            assert sig_types[msg.checksum.signal] == 12  # MessageChecksum


def test_signals_units_ranges_receivers(db):
    m = db.get_message_by_name("autocar_speed_command")
    accel = m.get_signal_by_name("accel_cmd")
    assert (accel.start, accel.length, accel.byte_order, accel.is_signed) == (0, 10, "little_endian", False)
    assert (accel.scale, accel.offset, accel.minimum, accel.maximum, accel.unit) == (0.02, -9, -9, 3.6, "m/s²")
    assert accel.receivers == ["Wire_Car_ECU"] and m.senders == ["AUTOCAR"]
    state = db.get_message_by_name("vehicle_state_1")
    assert set(state.receivers) == {"AUTOCAR", "R_GATE", "RC"}
    assert db.get_message_by_name("device_id").senders == []  # sent by ALL: Vector__XXX


def test_value_tables_and_comments(db, can):
    for msg in can.messages:
        m = db.get_message_by_frame_id(msg.frame_id)
        for sig in msg.data_signals:
            choices = {int(k): str(v) for k, v in (m.get_signal_by_name(sig.name).choices or {}).items()}
            expected = {e.raw: e.name for e in sig.value_table.entries} if sig.value_table else {}
            expected.update({s.raw: s.name for s in sig.specials if s.raw not in expected})
            assert choices == expected, (msg.name, sig.name)
    fault = db.get_message_by_name("vehicle_fault")
    assert "无法进入无人驾驶故障状态" in fault.get_signal_by_name("unmanned_entry_fault").comment
    assert "车辆故障状态" in fault.comment
