"""The shared physical↔raw rules: the exact reference (Fractions) and the runtime rule the
generated code uses (IEEE doubles + tie epsilon) agree on every decimal value and every tie of
every signal of the spec. Expected values of the worked examples come from the document (§1.2)."""

from __future__ import annotations

from fractions import Fraction

import pytest
from canspec.ir.encoding import decimal_text, round_half_away, to_raw_exact, to_raw_runtime
from canspec.reference import codec


def test_document_worked_examples():
    # §1.2: factor 0.1 A/bit, offset -100 A, 500 A → raw 6000 = 0x1770
    assert to_raw_exact("500", Fraction("0.1"), Fraction(-100)) == 0x1770
    assert to_raw_runtime(500.0, 0.1, -100.0) == 0x1770
    # §1.2: factor 1 °C/bit, offset -40 °C, raw 70 → 30 °C
    assert 70 * 1 + (-40) == 30


@pytest.mark.parametrize("q,expected", [(Fraction(1, 2), 1), (Fraction(-1, 2), -1), (Fraction(3, 2), 2), (Fraction(-5, 2), -3), (Fraction(49, 100), 0), (Fraction(-51, 100), -1), (0, 0)])
def test_round_half_away_from_zero(q, expected):
    assert round_half_away(Fraction(q)) == expected


def test_decimal_factor_ties_round_away_in_doubles():
    # (−8.99 − (−9)) / 0.02 = 0.5 exactly, but 0.49999999999998934 in doubles: the epsilon fixes it.
    assert to_raw_exact("-8.99", Fraction("0.02"), Fraction(-9)) == 1
    assert to_raw_runtime(-8.99, 0.02, -9.0) == 1
    assert round((-8.99 + 9) / 0.02) == 0  # what naive double rounding (cantools) gets


def test_exact_and_runtime_rules_agree_on_every_signal(can):
    """Every raw step's decimal value and every tie between steps, for every scaled signal."""
    checked = 0
    for msg in can.messages:
        for sig in msg.data_signals:
            if sig.is_identity:
                continue
            f, o = float(sig.factor), float(sig.offset)
            span = range(sig.raw_min, sig.raw_max + 1)
            for raw in [*span[:: max(1, len(span) // 4000)], sig.raw_max]:
                value = raw * sig.factor + sig.offset
                tie = value + sig.factor / 2
                for x in (value, tie):
                    text = decimal_text(x)
                    assert to_raw_runtime(float(text), f, o) == to_raw_exact(text, sig.factor, sig.offset), (msg.name, sig.name, text)
                    checked += 1
    assert checked > 50_000


def test_range_rules(can):
    accel = can.message("autocar_speed_command").signal("accel_cmd")
    assert (accel.raw_min, accel.raw_max) == (0, 630)  # [-9, 3.6] with 0.02: (3.6 + 9) / 0.02
    assert codec.to_raw(accel, 3.6) == 630
    assert codec.to_raw(accel, -9) == 0
    with pytest.raises(codec.CodecError):
        codec.to_raw(accel, 3.61)
    with pytest.raises(codec.CodecError):
        codec.to_raw(accel, 3.605)  # rounds to 3.6 but lies outside the documented range
    with pytest.raises(codec.CodecError):
        codec.to_raw(accel, float("nan"))
    speed = can.message("autocar_eps_command").signal("max_angular_speed")
    assert speed.raw_max == 255 and speed.doc_max == 512  # E10: documented 512, encodable 510
    with pytest.raises(codec.CodecError):
        codec.to_raw(speed, 512)
    distance = can.message("front_sensor_distance_1").signal("sensor_1_distance")
    assert codec.to_raw(distance, 1023) == 0x3FF  # special value "no obstacle" outside [0, 500]
    with pytest.raises(codec.CodecError):
        codec.to_raw(distance, 501)


def test_reserved_bits_are_zero_and_checksum_is_xor(can):
    msg = can.message("autocar_eps_command")
    data = codec.pack(msg, {"eps_ctrl_mode": 0x20, "counter": 7, "max_angular_speed": 10, "steering_angle_cmd": 10800})
    assert data[5] == data[6] == 0  # reserved bits 40..55
    assert data[7] == data[0] ^ data[1] ^ data[2] ^ data[3] ^ data[4] ^ data[5] ^ data[6]
    assert data.hex() == "20070a302a0000" + format(0x20 ^ 0x07 ^ 0x0A ^ 0x30 ^ 0x2A, "02x")


def test_every_decoded_value_re_encodes(can):
    """raw → physical in doubles → raw is the identity on every physical-encodable raw value,
    although 252 × 0.05 − 9 is 3.6000000000000014 in doubles (the accept tolerance)."""
    accel = can.message("driving_state").signal("current_accel")
    assert 252 * 0.05 - 9 > 3.6 and codec.to_raw(accel, 252 * 0.05 - 9) == 252
    checked = 0
    for msg in can.messages:
        for sig in msg.data_signals:
            f, o = float(sig.factor), float(sig.offset)
            if sig.length > 53:  # wider raw values are not exact in doubles; bindings keep them integer
                continue
            span = range(sig.raw_min, sig.raw_max + 1)
            for raw in [*span[:: max(1, len(span) // 2000)], sig.raw_max]:
                assert codec.to_raw(sig, raw * f + o) == raw, (msg.name, sig.name, raw)
                checked += 1
    assert checked > 20_000
