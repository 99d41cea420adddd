"""The shipped DBC loads in cantools and canmatrix and carries Vector's J1939 attributes (in the
J1939 template's enumerations), value tables, receivers, units, ranges and comments; signal names
the spec uses with different definitions are made unique, each naming its spec name."""

from __future__ import annotations


import canmatrix.formats
from dbc_support import attribute, spec_names
from repo_paths import GENERATED

DBC = GENERATED / "dbc" / "kaiwo_gateway.dbc"
# Vector's J1939 database template, as CANdb++ writes it (value order matters: BA_ stores the index).
J1939_SEND_TYPES = ["cyclic", "NotUsed", "NotUsed", "NotUsed", "NotUsed", "NotUsed", "NotUsed", "IfActive", "noMsgSendType"]


def test_canmatrix_loads_without_errors():
    dbs = canmatrix.formats.loadp(str(DBC), dbcImportEncoding="utf-8")
    matrix = dbs[""]
    assert len(matrix.frames) == 25
    assert matrix.attributes["ProtocolType"] == "J1939"
    frame = matrix.frame_by_id(canmatrix.ArbitrationId(0x1813A0B0, extended=True))
    assert frame.attributes["GenMsgCycleTime"] == "100"


def test_j1939_attributes(raw_db, can):
    attrs = raw_db.dbc.attributes
    assert attrs["ProtocolType"].value == "J1939" and attrs["Baudrate"].value == 250000
    assert raw_db.dbc.attribute_definitions["GenMsgSendType"].choices == J1939_SEND_TYPES
    for node in raw_db.nodes:
        assert attribute(node, "NmStationAddress") == next(n.sa for n in can.nodes if n.name == node.name)
    for msg in can.messages:
        m = raw_db.get_message_by_frame_id(msg.frame_id)
        assert attribute(m, "VFrameFormat") == 3  # J1939PG
        assert m.cycle_time == msg.cycle_ms and m.send_type == "cyclic"
        sig_types = {spec_names(m)[s.name]: attribute(s, "SigType") for s in m.signals}
        if msg.counter:
            assert sig_types[msg.counter.signal] == 11  # MessageCounter
        if msg.checksum:
            assert sig_types[msg.checksum.signal] == 12  # MessageChecksum
        if msg.multiframe:
            assert sig_types[msg.multiframe.payload_signal] == 3  # ASCII: the VIN characters


def test_signals_units_ranges_receivers(raw_db):
    m = raw_db.get_message_by_name("autocar_speed_command")
    accel = m.get_signal_by_name("accel_cmd")
    assert (accel.start, accel.length, accel.byte_order, accel.is_signed) == (0, 10, "little_endian", False)
    assert (accel.scale, accel.offset, accel.minimum, accel.maximum, accel.unit) == (0.02, -9, -9, 3.6, "m/s²")
    assert accel.receivers == ["Wire_Car_ECU"] and m.senders == ["AUTOCAR"]
    state = raw_db.get_message_by_name("vehicle_state_1")
    assert set(state.receivers) == {"AUTOCAR", "R_GATE", "RC"}
    assert raw_db.get_message_by_name("device_id").senders == []  # sent by ALL: Vector__XXX


def test_names_differing_definitions_apart(unique_db):
    """With `dbc_signal_names: unique`: the 4-bit counter of control command 1 and the 8-bit one of the EPS command, and the three
    drive-mode tables, each get a name of their own; a name with one definition stays."""
    c1 = unique_db.get_message_by_name("autocar_control_command_1")
    counter = c1.get_signal_by_name("counter_1805B0A0")
    assert counter.length == 4 and attribute(counter, "SpecSignalName") == "counter"
    assert "spec name: counter" in counter.comment
    assert unique_db.get_message_by_name("autocar_eps_command").get_signal_by_name("counter_1801B0A0").length == 8
    modes = {m: unique_db.get_message_by_name(m).get_signal_by_name(f"drive_mode_cmd_{i}").choices[1]
             for m, i in (("autocar_control_command_1", "1805B0A0"), ("rgate_control_command_1", "1805B0C0"))}
    assert modes == {"autocar_control_command_1": "autonomous", "rgate_control_command_1": "reserved_1"}
    assert unique_db.get_message_by_name("autocar_eps_command").get_signal_by_name("max_angular_speed") is not None
    definitions: dict[str, set[tuple[object, ...]]] = {}
    for m in unique_db.messages:
        for s in m.signals:
            assert len(s.name) <= 32
            definitions.setdefault(s.name, set()).add((s.length, s.is_signed, s.scale, s.offset, s.minimum, s.maximum, s.unit,
                                                       tuple((int(k), str(v)) for k, v in (s.choices or {}).items()), s.comment, tuple(s.receivers)))
    assert all(len(d) == 1 for d in definitions.values()), {n: d for n, d in definitions.items() if len(d) > 1}


def test_by_default_signals_keep_their_names(raw_db):
    c1 = raw_db.get_message_by_name("autocar_control_command_1")
    assert c1.get_signal_by_name("counter").length == 4
    assert raw_db.get_message_by_name("autocar_eps_command").get_signal_by_name("counter").length == 8
    assert not any("SpecSignalName" in (s.dbc.attributes if s.dbc else {}) for m in raw_db.messages for s in m.signals)


def test_value_tables_and_comments(raw_db, can):
    for msg in can.messages:
        m = raw_db.get_message_by_frame_id(msg.frame_id)
        for s in m.signals:
            sig = msg.signal(spec_names(m)[s.name])
            choices = {int(k): str(v) for k, v in (s.choices or {}).items()}
            expected = {e.raw: e.name for e in sig.value_table.entries} if sig.value_table else {}
            expected.update({sp.raw: sp.name for sp in sig.specials if sp.raw not in expected})
            assert choices == expected, (msg.name, sig.name)
    fault = raw_db.get_message_by_name("vehicle_fault")
    assert "无法进入无人驾驶故障状态" in fault.get_signal_by_name("unmanned_entry_fault").comment
    assert "车辆故障状态" in fault.comment
    assert "Signal names:" not in DBC.read_text(encoding="utf-8")  # per-message names: nothing renamed, nothing to say
