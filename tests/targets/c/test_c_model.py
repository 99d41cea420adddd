"""The C target's model (model.py and the modules it uses): literal syntax, fixed-point scales
and types, pack plans, names. Expected values from the document and from exact arithmetic."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

from canspec.targets.c import model as cmodel
from canspec.targets.c import physical


def _by_name(model):
    return {m.msg.name: m for m in model.messages}


def test_fixed_scale_expresses_every_step_bound_and_tie():
    sig = dataclasses.make_dataclass("S", ["factor", "offset", "check_min", "check_max", "is_identity"])
    # factor 0.0015 (4 places), its half step 0.00075 (5 places)
    assert physical.fixed_scale(sig(Fraction(3, 2000), Fraction(0), Fraction(0), Fraction(1), False)) == 10**5
    # an identity field with a documented range of decimals
    assert physical.fixed_scale(sig(Fraction(1), Fraction(0), Fraction(1, 2), Fraction(10), True)) == 10
    # 2^-20 has 20 decimal places: counted exactly, not capped
    assert physical.fixed_scale(sig(Fraction(1, 2**20), Fraction(0), Fraction(0), Fraction(1), True)) == 10**20


def test_signal_plans(spec):
    by = _by_name(cmodel.build_model(spec))
    eps = by["autocar_eps_command"]
    angle = next(s for s in eps.signals if s.sig.name == "steering_angle_cmd")
    # factor 0.1, offset -1080: fixed point in 1/100 deg so that the tie -1079.95 is expressible
    assert angle.fixed.scale == 100 and angle.fixed.type == "int32_t"
    assert angle.fixed.decode_expr == "((int32_t)raw * 10) - 108000"
    # the first check is the document's range [-1080, 1080] deg (no special value to let through),
    # so |value + 108000| is at most 216000: divided by 10 as the high word of a 32-bit multiply,
    # no division (divide.py), and no check after it
    assert angle.fixed.outside == "(value < (-108000)) || (value > 108000)" and angle.fixed.ranges.outside == ""
    assert angle.fixed.rounded == "kaiwo_gateway_div_round_mulhi(value + 108000, 5u, 0x1999999Au, 0u)"
    assert angle.fixed.note == "divide by 10: (|num| + 5) * 0x1999999A >> (32 + 0), exact up to 216005"
    assert angle.type == "uint16_t" and not angle.needs_check  # 16 bits in uint16_t
    # the document's table: steering angle in bytes 3 (low) and 4 (high), bytes 5..6 reserved,
    # byte 7 the XOR of bytes 0..6
    pack = eps.codec.pack
    assert "dst[3] = (uint8_t)src->steering_angle_cmd;" in pack and "dst[4] = (uint8_t)(src->steering_angle_cmd >> 8u);" in pack
    assert "dst[5] = 0u;" in pack and "dst[6] = 0u;" in pack
    assert pack[-1] == "dst[7] = (uint8_t)(dst[0] ^ dst[1] ^ dst[2] ^ dst[3] ^ dst[4] ^ dst[5] ^ dst[6]);"
    assert "dst->steering_angle_cmd = (uint16_t)(b3 | (b4 << 8u));" in eps.codec.unpack
    # every byte read once, each folded into the XOR the checksum check needs
    assert [line for line in eps.codec.unpack if line.startswith("x ")] == [
        "x = b0;", "x ^= b1;", "x ^= b2;", "x ^= b3;", "x ^= b4;", "x ^= b7;", "x ^= src[5];", "x ^= src[6];"]
    cmd1 = by["autocar_control_command_1"]
    assert cmd1.counter is not None and cmd1.counter_mask == "0xFu"
    chars = next(s for s in by["device_id"].signals if s.sig.name == "id_chars")
    assert chars.double is None and chars.fixed.type == "int64_t" and chars.fixed.scale == 1  # 56 bits: not exact in a double
    dist = by["front_sensor_distance_1"].signals[0]
    assert dist.needs_check and [sp.raw for sp in dist.specials] == [0x3FF]


def test_double_decode_reads_the_macros_it_defines(spec):
    """The decode multiplies by the signal's `_FACTOR` macro and adds its `_OFFSET` macro (whose
    values are the document's 0.02 and -9: the accel_cmd row), never a second copy of them."""
    speed = _by_name(cmodel.build_model(spec))["autocar_speed_command"]
    accel = next(s for s in speed.signals if s.sig.name == "accel_cmd")
    assert (accel.factor, accel.offset) == ("0.02", "-9.0")
    assert accel.double.decode_pre == f"(double)raw * {accel.macro}_FACTOR"
    assert accel.double.decode_expr == f"scaled + {accel.macro}_OFFSET"



def test_double_encoders_share_descriptors_and_the_rounding(spec):
    """Every double encoder is a call into the runtime's shared steps with its descriptor; signals
    with the same scaling and range share one (named after the first, defined at file scope), one
    alone keeps its own in its encoder (MISRA C:2012 rule 8.9)."""
    model = cmodel.build_model(spec)
    by = _by_name(model)
    angles = [s for cm in model.messages for s in cm.signals if s.sig.name == "steering_angle_cmd"]
    first = "kaiwo_gateway_autocar_eps_command_steering_angle_cmd_phys"
    assert len(angles) > 1 and {s.double.phys_name for s in angles} == {first} and not any(s.double.phys_local for s in angles)
    assert [s.double.phys_defines for s in angles] == [True] + [False] * (len(angles) - 1)
    assert angles[0].double.phys == "{-1080.0, 0.1, -1080.0000000001, 1080.0000000001, true}"
    # the accepted range keeps r in the raw range: the runtime's uint16_t encoder does the rest
    assert angles[0].double.encode_tail == f"kaiwo_gateway_phys_encode_u16(value, &{first}, raw)" and not angles[0].double.encode_test
    torque = next(s for s in by["eps_state"].signals if s.sig.name == "steering_torque")
    assert torque.double.phys_local and torque.double.phys_name == "kaiwo_gateway_eps_state_steering_torque_phys"
    # factor 2 over [0, 512]: 511 rounds to 256, beyond the raw range; raw 0 is a special value
    speed = next(s for s in by["autocar_eps_command"].signals if s.sig.name == "max_angular_speed")
    name = "kaiwo_gateway_autocar_eps_command_max_angular_speed_phys"
    assert speed.double.special_test == f"kaiwo_gateway_phys_round(value, &{name}, &r) && (r == 0)"
    assert speed.double.encode_test == f"!kaiwo_gateway_phys_encode(value, &{name}, &r)" and speed.double.ranges.outside == "r > INT64_C(255)"
    assert not speed.double.window_test and model.has_phys_round
    assert model.phys_stores == (("kaiwo_gateway_phys_encode_u16", "uint16_t"), ("kaiwo_gateway_phys_encode_u8", "uint8_t"))

def test_j1939_facts_are_the_ids(spec):
    eps = _by_name(cmodel.build_model(spec))["autocar_eps_command"]  # 0x1801B0A0: priority 6, PF 0x01 (PDU1) to 0xB0 from 0xA0
    assert (eps.j1939.priority, eps.j1939.pgn, eps.j1939.sa, eps.j1939.da) == ("6u", "0x00100u", "0xA0u", "0xB0u")
    assert eps.frame_id == "0x1801B0A0u" and eps.cycle_ms == "20u"


def test_fault_code_mapping(spec):
    model = cmodel.build_model(spec)
    tables = {ft.enum.table: ft for ft in model.fault_tables}
    assert set(tables) == {"unmanned_entry_fault", "remote_entry_fault"}
    codes = {t: {index: step.code for step in ft.steps for index in step.messages} for t, ft in tables.items()}
    assert codes["unmanned_entry_fault"]["KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND"].endswith("EPS_COMMAND_XOR_ERROR")
    assert codes["remote_entry_fault"]["KAIWO_GATEWAY_MSG_TELE_SPEED_COMMAND"].endswith("SPEED_COMMAND_XOR_ERROR")
    assert len(codes["remote_entry_fault"]) == 6  # the three EPS and three speed commands carry the XOR checksum
    # reported lowest code first: the document's codes 5, 6 (EPS, speed command XOR error), 7 (timeout)
    steps = tables["remote_entry_fault"].steps
    assert [s.code.rsplit("_FAULT_", 1)[1] for s in steps] == ["EPS_COMMAND_XOR_ERROR", "SPEED_COMMAND_XOR_ERROR", "MESSAGE_TIMEOUT"]
    assert len(steps[0].messages) == 3 and steps[2].messages == ()


def test_sub_byte_fields_are_checked_then_placed(spec):
    """Fields narrower than their C type are checked per width before their byte is written
    (one compare per width); each byte is the OR of its fields' pieces, shift and mask in view."""
    cc2 = _by_name(cmodel.build_model(spec))["rgate_control_command_2"]
    pack = cc2.codec.pack
    assert pack[0].startswith("if (") and pack[0].endswith("{") and pack[1] == "return KAIWO_GATEWAY_ERR_RANGE;"
    assert any(line.startswith("dst[7] = ") and "src->counter" in line for line in pack)
    dist = _by_name(cmodel.build_model(spec))["front_sensor_distance_1"]  # 10-bit distances: sensor 2 at bits 10..19
    assert "dst->sensor_2_distance = (uint16_t)((b1 >> 2u) | ((b2 & 0xFu) << 6u));" in dist.codec.unpack
    assert "dst[1] = (uint8_t)((src->sensor_1_distance >> 8u) | ((uint32_t)src->sensor_2_distance << 2u));" in dist.codec.pack
