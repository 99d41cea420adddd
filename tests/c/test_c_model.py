"""The C target's model (cmodel.py): literal syntax, fixed-point scales, pack plans and clear
errors for layouts the C target does not support. Expected values from the document."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import pytest
from canspec.generate import GenerationError, generate
from canspec.targets.c import model as cmodel


def test_decimals():
    assert cmodel.decimals(Fraction(3, 2000)) == 4  # 0.0015


def test_signal_plans(spec):
    model = cmodel.build_model(spec)
    eps = next(m for m in model.messages if m.msg.name == "autocar_eps_command")
    angle = next(s for s in eps.signals if s.sig.name == "steering_angle_cmd")
    # factor 0.1, offset -1080: fixed point in 1/100 deg so that the tie -1079.95 is expressible
    assert angle.scale_int == 100 and angle.fixed_factor == "10" and angle.fixed_offset == "(-108000)"
    assert angle.type == "uint16_t" and not angle.needs_check  # 16 bits in uint16_t
    assert eps.checksum_byte == 7 and eps.checksum_fold
    # the struct is one 8-byte word: fields at byte offsets 0, 1, 2, (pad), 4..5, 6
    assert [r.offset for r in eps.unpack_runs] == [0] and eps.unpack_runs[0].nbytes == 8
    assert "offsetof(kaiwo_gateway_autocar_eps_command_t, steering_angle_cmd) == 4u" in eps.layout_check
    # reserved bytes 5..6 stay 0: only the checksum byte is added to the packed data bits
    assert "0xFFFFFF" in eps.frame_word and eps.checksum_pack.endswith("<< 56)")
    cmd1 = next(m for m in model.messages if m.msg.name == "autocar_control_command_1")
    assert cmd1.counter is not None and cmd1.counter_mask == "0xFu"
    dev = next(m for m in model.messages if m.msg.name == "device_id")
    chars = next(s for s in dev.signals if s.sig.name == "id_chars")
    assert not chars.has_double and chars.fixed_type == "int64_t" and chars.scale_int == 1
    fs = next(m for m in model.messages if m.msg.name == "front_sensor_distance_1")
    dist = fs.signals[0]
    assert dist.needs_check and [sp.raw for sp in dist.specials] == [0x3FF]


def test_fault_code_mapping(spec):
    model = cmodel.build_model(spec)
    tables = {ft.enum.table: ft for ft in model.fault_tables}
    assert set(tables) == {"unmanned_entry_fault", "remote_entry_fault"}
    assert tables["unmanned_entry_fault"].timeout_const.endswith("MESSAGE_TIMEOUT")
    codes = {m.msg.name: dict(m.fault_xor_codes) for m in model.messages if m.fault_xor_codes}
    assert codes["autocar_eps_command"]["unmanned_entry_fault"].endswith("EPS_COMMAND_XOR_ERROR")
    assert codes["tele_speed_command"]["remote_entry_fault"].endswith("SPEED_COMMAND_XOR_ERROR")
    assert len(codes) == 6  # the three EPS and three speed commands carry the XOR checksum


def test_unsupported_layout_is_a_clear_generation_error(spec):
    can = spec.can
    big = dataclasses.replace(can.messages[0], dlc=64)
    bad = dataclasses.replace(spec, can=dataclasses.replace(can, messages=(big, *can.messages[1:])))
    with pytest.raises(GenerationError, match=r"target c: autocar_eps_command: DLC 64 > 8"):
        generate(bad, ["c"])


def test_trailing_byte_fields_are_copied_as_bytes(spec):
    """Whole-byte fields at the struct's end whose frame byte differs from their struct offset
    are copied byte by byte, when the planner's word cost says moving them costs more."""
    model = cmodel.build_model(spec)
    by = {m.msg.name: m for m in model.messages}
    cc2 = by["rgate_control_command_2"]  # ..., downhill_regen_speed (frame byte 1), counter (byte 7)
    assert [(b.field, b.byte) for b in cc2.byte_fields] == [("downhill_regen_speed", 1), ("counter", 7)]
    assert cc2.pack_byte_stores == cc2.byte_fields
    assert all(f.name not in ("downhill_regen_speed", "counter") for r in cc2.unpack_runs for f in r.run.fields)
    assert cc2.unpack_runs[-1].nbytes == 4  # the four sub-byte fields: one 4-byte store / load
    eps = by["autocar_eps_command"]  # the checksum (struct byte 6) lies inside the 8-byte word
    assert eps.byte_fields == ()  # access: a byte store there would stall pack's word load
    assert eps.unpack_runs[-1].nbytes == 8
    ds = by["driving_state"]  # its checksum moves with the two bytes before it: stays in the word
    assert ds.byte_fields == ()
