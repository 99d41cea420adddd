"""The generated package's API against the spec's IR and the document: class constants,
enums, defaults, docstrings, helpers, and every error it documents."""

from __future__ import annotations

import dataclasses
import math

import pytest
from canspec.ir import j1939 as ref_j1939


def classes(gw):
    return {cls.NAME: cls for cls in gw.MESSAGES}


def attrs(cls):
    return dict(zip(cls.SIGNALS, (f.name for f in dataclasses.fields(cls))))


def test_every_message_is_a_slotted_dataclass_with_the_documents_constants(gw, can):
    by_name = classes(gw)
    assert len(by_name) == len(can.messages) == 25
    for msg in can.messages:
        cls = by_name[msg.name]
        assert dataclasses.is_dataclass(cls) and hasattr(cls, "__slots__")
        assert (cls.FRAME_ID, cls.DLC, cls.CYCLE_MS, cls.FINGERPRINT) == (msg.frame_id, msg.dlc, msg.cycle_ms, msg.fingerprint)
        fields = ref_j1939.decompose(msg.frame_id)  # independent of the IR's own j1939 block
        assert (cls.PRIORITY, cls.PGN, cls.SOURCE_ADDRESS, cls.DESTINATION_ADDRESS) == (fields.priority, fields.pgn, fields.sa, fields.da)
        assert cls.SIGNALS == tuple(s.name for s in msg.data_signals)  # reserved bits are not in the API
        assert gw.BY_ID[msg.frame_id] is cls
    # spot checks against the document (§2 message list)
    assert by_name["autocar_eps_command"].FRAME_ID == 0x1801B0A0 and by_name["autocar_eps_command"].CYCLE_MS == 20
    assert by_name["device_id"].FRAME_ID == 0x18FFAF00 and by_name["device_id"].DESTINATION_ADDRESS is None
    assert by_name["autocar_eps_command"].SOURCE_ADDRESS == 0xA0 and by_name["autocar_eps_command"].DESTINATION_ADDRESS == 0xB0


def test_value_tables_are_int_enums(gw, can):
    from enum import IntEnum

    for table in can.value_tables:
        enum = next(e for e in vars(gw.enums).values() if isinstance(e, type) and issubclass(e, IntEnum) and e.__doc__ == f"Value table `{table.name}`.")
        assert [(m.name.lower(), m.value) for m in enum] == [(e.name, e.raw) for e in table.entries]
    assert gw.Gear.__members__ and isinstance(gw.EpsState.decode(gw.EpsState().encode()).eps_ctrl_state, gw.EpsModeState)


def test_docstrings_carry_chinese_name_unit_and_range(gw):
    doc = gw.AutocarEpsCommand.__doc__
    assert "智能控制器 EPS 命令" in doc and "§3.1" in doc
    assert "steering_angle_cmd: 方向盘角度指令; unit deg; range [-1080, 1080]" in doc
    assert "max_angular_speed:" in doc and "0 = no_limit (不限制角速度)" in doc


def test_special_value_constants(gw):
    assert gw.FrontSensorDistance1.SENSOR_1_DISTANCE_NO_OBSTACLE == 0x3FF
    assert gw.DrivingState.MOTOR_SPEED_RATIO_INVALID == 0xFF + 1  # physical = raw 0xFF + offset 1
    # a special value outside the documented range encodes, and decodes back to the constant
    m = gw.FrontSensorDistance1(sensor_1_distance=gw.FrontSensorDistance1.SENSOR_1_DISTANCE_NO_OBSTACLE)
    assert gw.decode(m.FRAME_ID, m.encode()).sensor_1_distance == 0x3FF
    assert gw.FrontSensorDistance1.unpack_raw(m.encode())["sensor_1_distance"] == 0x3FF


def test_defaults_encode_and_decode_back(gw):
    for cls in gw.MESSAGES:
        m = cls()
        back = gw.decode(cls.FRAME_ID, gw.encode(m))
        for name in attrs(cls).values():
            if name != "checksum":
                assert getattr(back, name) == pytest.approx(getattr(m, name)), (cls.NAME, name)
    assert gw.AutocarEpsCommand().steering_angle_cmd == 0.0  # physical 0 where the range allows it


def test_checksum_filled_and_reserved_bits_zero(gw, can):
    for msg in can.messages:
        cls = gw.BY_ID[msg.frame_id]
        # a frame with every bit set: re-encoding the decoded message clears the reserved bits
        ones = bytearray(b"\xff" * msg.dlc)
        if msg.checksum is not None:
            x = 0
            for b in msg.checksum.covers:
                x ^= ones[b]
            ones[msg.checksum.byte] = x
        m = cls.decode(bytes(ones), verify_checksum=True)
        data = gw.encode_raw(msg.frame_id, cls.unpack_raw(bytes(ones)))
        frame = int.from_bytes(data, "little")
        for sig in msg.reserved_signals:
            assert (frame >> sig.start) & sig.mask == 0, (msg.name, sig.start)
        if msg.checksum is not None:
            x = 0
            for b in msg.checksum.covers:
                x ^= data[b]
            assert data[msg.checksum.byte] == x
            assert cls.checksum_ok(data) and gw.checksum_ok(msg.frame_id, data)
        del m


def test_encode_ignores_a_stale_checksum_attribute(gw):
    m = gw.AutocarEpsCommand(steering_angle_cmd=12.5, checksum=0x42)
    data = m.encode()
    assert data[7] == data[0] ^ data[1] ^ data[2] ^ data[3] ^ data[4] ^ data[5] ^ data[6]


def test_raw_level_access(gw):
    cls = gw.AutocarEpsCommand
    data = cls.pack_raw({"steering_angle_cmd": 10800 + 125, "counter": 7})
    assert cls.decode(data).steering_angle_cmd == pytest.approx(12.5)
    assert cls.unpack_raw(data)["steering_angle_cmd"] == 10925
    assert gw.decode_raw(cls.FRAME_ID, data) == cls.unpack_raw(data)
    assert gw.encode_raw(cls.FRAME_ID, cls.unpack_raw(data)) == data
    assert cls.from_raw({"counter": 7}).counter == 7
    assert cls(steering_angle_cmd=12.5, counter=7).to_raw()["steering_angle_cmd"] == 10925
    # raw level accepts what the documented range excludes (gear 3 is reserved)
    assert gw.AutocarSpeedCommand.unpack_raw(gw.AutocarSpeedCommand.pack_raw({"gear_cmd": 15}))["gear_cmd"] == 15


def test_counter_helpers(gw):
    assert gw.AutocarEpsCommand.COUNTER_MODULO == 256 and gw.AutocarControlCommand1.COUNTER_MODULO == 16
    assert gw.AutocarEpsCommand.next_counter(255) == 0 and gw.AutocarControlCommand1.next_counter(15) == 0
    m = gw.AutocarControlCommand1(counter=14)
    assert [m.advance_counter() for _ in range(3)] == [15, 0, 1]
    assert not hasattr(gw.VehicleState2, "COUNTER_MODULO")


def test_j1939_helpers_agree_with_the_reference(gw, can):
    for msg in can.messages:
        mine = gw.j1939.decompose(msg.frame_id)
        ref = ref_j1939.decompose(msg.frame_id)
        assert (mine.priority, mine.pgn, mine.sa, mine.da, mine.pf, mine.ps, mine.is_pdu2) == (
            ref.priority, ref.pgn, ref.sa, ref.da, ref.pf, ref.ps, ref.is_pdu2)
        assert gw.j1939.compose(mine.priority, mine.pgn, mine.sa, mine.da) == msg.frame_id == ref_j1939.compose(ref.priority, ref.pgn, ref.sa, ref.da)
    with pytest.raises(ValueError, match="29-bit"):
        gw.j1939.decompose(1 << 29)
    with pytest.raises(ValueError, match="priority"):
        gw.j1939.compose(8, 0xFF00, 0)
    with pytest.raises(ValueError, match="no destination"):
        gw.j1939.compose(6, 0xFFAF, 0, da=0x10)


def test_vin_split_join_and_assembler(gw, vectors):
    for entry in vectors["multiframe"]:
        frames = gw.split_device_id_text(entry["text"])
        assert [m.encode().hex().upper() for m in frames] == entry["frames"]
        decoded = [gw.decode(entry["frame_id"], bytes.fromhex(f)) for f in entry["frames"]]
        assert gw.join_device_id_text(reversed(decoded)) == entry["text"].rstrip("\0")
        asm = gw.DeviceIdTextAssembler()
        assert [asm.feed(m) for m in decoded] == [None, None, entry["text"].rstrip("\0")]
    short = gw.split_device_id_text("LK1")
    assert gw.join_device_id_text(short) == "LK1"
    with pytest.raises(ValueError, match="at most 17"):
        gw.split_device_id_text("X" * 18)
    with pytest.raises(ValueError, match="not ascii"):
        gw.split_device_id_text("车架号")
    with pytest.raises(ValueError, match=r"frame\(s\) \[1\] missing"):
        gw.join_device_id_text([short[0], short[2]])


# --- errors -----------------------------------------------------------------------------------


def test_unknown_frame_id(gw):
    for call in (lambda: gw.decode(0x123, bytes(8)), lambda: gw.decode_raw(0x18FFFFFF, bytes(8)),
                 lambda: gw.encode_raw(0x1, {}), lambda: gw.checksum_ok(0x1, bytes(8))):
        with pytest.raises(gw.UnknownFrameError, match="unknown frame ID 0x") as exc:
            call()
        assert isinstance(exc.value, gw.DecodeError) and isinstance(exc.value, ValueError)


@pytest.mark.parametrize("length", [0, 7, 9, 64])
def test_wrong_length(gw, length):
    with pytest.raises(gw.FrameLengthError, match=f"autocar_eps_command \\(0x1801B0A0\\): frame has {length} data bytes, expected 8") as exc:
        gw.decode(0x1801B0A0, bytes(length))
    assert (exc.value.expected, exc.value.actual) == (8, length)
    assert not gw.checksum_ok(0x1801B0A0, bytes(length))
    with pytest.raises(gw.FrameLengthError):
        gw.VehicleState2.unpack_raw(bytes(length))


def test_checksum_mismatch_and_non_raising_check(gw):
    good = gw.AutocarSpeedCommand(accel_cmd=1.0, counter=3).encode()
    bad = bytearray(good)
    bad[7] ^= 0x01
    assert gw.checksum_ok(0x1803B0A0, good) and not gw.checksum_ok(0x1803B0A0, bytes(bad))
    assert not gw.AutocarSpeedCommand.checksum_ok(bytes(bad))
    with pytest.raises(gw.ChecksumError, match="checksum mismatch: frame carries") as exc:
        gw.decode(0x1803B0A0, bytes(bad))
    assert exc.value.expected == good[7] and exc.value.actual == bad[7]
    assert not isinstance(exc.value, gw.FrameLengthError)
    assert gw.decode(0x1803B0A0, bytes(bad), verify_checksum=False).accel_cmd == pytest.approx(1.0)
    with pytest.raises(gw.ChecksumError):
        gw.decode_raw(0x1803B0A0, bytes(bad))
    assert gw.checksum_ok(0x1810A0B0, bytes(8))  # a message without checksum


@pytest.mark.parametrize(("field", "value", "allowed"), [
    ("steering_angle_cmd", 1080.1, "[-1080, 1080] deg"),
    ("steering_angle_cmd", -1080.06, "[-1080, 1080] deg"),
    ("steering_angle_cmd", math.nan, "[-1080, 1080] deg"),
    ("steering_angle_cmd", math.inf, "[-1080, 1080] deg"),
    ("steering_angle_cmd", 1e300, "[-1080, 1080] deg"),
    ("max_angular_speed", 514, "[0, 512] deg/s or 0 (no_limit)"),
    ("counter", 256, "[0, 255]"),
    ("counter", -1, "[0, 255]"),
    ("counter", 2**70, "[0, 255]"),
])
def test_range_error_names_message_signal_value_and_range(gw, field, value, allowed):
    m = gw.AutocarEpsCommand(**{field: value})
    with pytest.raises(gw.RangeError) as exc:
        gw.encode(m)
    assert str(exc.value) == f"autocar_eps_command.{field}: {value!r} is outside the allowed range {allowed}"
    assert (exc.value.message, exc.value.signal, exc.value.allowed) == ("autocar_eps_command", field, allowed)
    assert isinstance(exc.value, gw.EncodeError) and isinstance(exc.value, ValueError)


def test_enum_value_outside_the_documented_range(gw):
    with pytest.raises(gw.RangeError, match=r"autocar_speed_command.gear_cmd: 3 is outside the allowed range \[0, 2\]"):
        gw.AutocarSpeedCommand(gear_cmd=3).encode()
    assert gw.AutocarSpeedCommand(gear_cmd=gw.Gear(2)).encode()


def test_range_edges_round_and_never_clamp(gw):
    assert gw.AutocarEpsCommand(steering_angle_cmd=1080.0).to_raw()["steering_angle_cmd"] == 21600
    assert gw.AutocarEpsCommand(steering_angle_cmd=-1080.0).to_raw()["steering_angle_cmd"] == 0
    assert gw.AutocarEpsCommand(steering_angle_cmd=-8.95).to_raw()["steering_angle_cmd"] == 10711  # q = 10710.5: half away from zero
    assert gw.AutocarSpeedCommand(accel_cmd=3.6).to_raw()["accel_cmd"] == 630
    with pytest.raises(gw.RangeError):
        gw.AutocarSpeedCommand(accel_cmd=3.61).encode()
    # an integer signal given a float rounds by the same rule
    assert gw.AutocarEpsCommand(counter=2.5).to_raw()["counter"] == 3  # type: ignore[arg-type]
    assert gw.AutocarEpsCommand(counter=2.4999).to_raw()["counter"] == 2  # type: ignore[arg-type]


def test_wrong_types_are_type_errors(gw):
    with pytest.raises(TypeError, match="autocar_eps_command.steering_angle_cmd: expected a number, got str"):
        gw.AutocarEpsCommand(steering_angle_cmd="12").encode()  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="expected a number"):
        gw.AutocarEpsCommand(counter=None).encode()  # type: ignore[arg-type]


def test_raw_errors(gw):
    with pytest.raises(gw.RawRangeError, match=r"autocar_eps_command.counter: raw value 256 does not fit the field \(an integer in 0..255\)"):
        gw.AutocarEpsCommand.pack_raw({"counter": 256})
    with pytest.raises(gw.RawRangeError, match="raw value 1.5"):
        gw.AutocarEpsCommand.pack_raw({"counter": 1.5})  # type: ignore[typeddict-item]
    with pytest.raises(gw.UnknownSignalError, match="autocar_eps_command: no signal named 'speed'"):
        gw.encode_raw(0x1801B0A0, {"speed": 1})
