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


@pytest.mark.parametrize(
    "q,expected",
    [(Fraction(1, 2), 1), (Fraction(-1, 2), -1), (Fraction(3, 2), 2), (Fraction(-5, 2), -3), (Fraction(49, 100), 0), (Fraction(-51, 100), -1), (0, 0)])
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


# --- what the runtime rule guarantees, for any signal (ir/encoding.py) --------------------------

from decimal import Decimal  # noqa: E402

from canspec.ir.encoding import TIE_GUARANTEE  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

FACTORS = st.builds(lambda m, e: Fraction(m) * Fraction(10) ** e, st.integers(-999, 999).filter(bool), st.integers(-6, 3))
OFFSETS = st.builds(lambda m, e: Fraction(m) * Fraction(10) ** e, st.integers(-(10**6), 10**6), st.integers(-3, 3))


def _decimal_float(value: Fraction) -> tuple[str, float]:
    text = decimal_text(value)
    return text, float(Decimal(text))


@settings(max_examples=3000, deadline=None)
@given(
    FACTORS, OFFSETS, st.integers(-(2**40), 2**40), st.sampled_from([Fraction(1, 2), Fraction(0), Fraction(333, 1000), Fraction(-1, 4), Fraction(499, 1000)])
)
def test_runtime_equals_exact_within_the_guarantee(factor, offset, k, frac):
    q = k + frac  # the exact quotient: a tie, a step, or well away from a tie
    physical = q * factor + offset
    if (abs(physical) + abs(offset)) / abs(factor) >= TIE_GUARANTEE:
        return
    text, x = _decimal_float(physical)
    assert to_raw_runtime(x, float(factor), float(offset)) == to_raw_exact(text, factor, offset), (text, factor, offset)


@settings(max_examples=3000, deadline=None)
@given(FACTORS, OFFSETS, st.integers(-(2**62), 2**62), st.sampled_from([Fraction(1, 2), Fraction(0), Fraction(-1, 2), Fraction(142857, 10**6)]))
def test_runtime_is_within_one_of_exact_everywhere(factor, offset, k, frac):
    q = k + frac
    physical = q * factor + offset
    text, x = _decimal_float(physical)
    f, o = float(factor), float(offset)
    got = to_raw_runtime(x, f, o)
    assert abs(got - to_raw_exact(text, factor, offset)) <= 1 + abs(q) * Fraction(2) ** -50 + abs(Fraction(o) / Fraction(f)) * Fraction(2) ** -50
    qd = (x - o) / f
    if abs(qd) >= 2**52:  # every double is an integer there: taken as is, never rounded to even
        assert got == int(qd)


def test_half_is_not_rounded_to_even_near_the_exact_limit():
    # 2^52 - 0.5 is a double; adding 0.5 and flooring gives 2^52 (away from zero), and 2^52 + 1
    # is taken as it is (q + 0.5 would round to even: 2^52 + 2).
    assert to_raw_runtime(2**52 - 0.5, 1.0, 0.0) == 2**52
    assert to_raw_runtime(2**52 + 1.0, 1.0, 0.0) == 2**52 + 1
    assert to_raw_runtime(-(2**52) - 1.0, 1.0, 0.0) == -(2**52) - 1
    # a 32-bit field scaled by 0.1: this tie lies beyond the guarantee, and the rule is the
    # rounding of the double quotient (4294966294.4999995 → ...94), within one of the exact 95
    assert to_raw_exact("429496629.45", Fraction(1, 10), Fraction(0)) == 4294966295
    assert to_raw_runtime(429496629.45, 0.1, 0.0) in (4294966294, 4294966295)


def test_decimal_text_of_values_longer_than_the_decimal_context():
    """A wide field's range widened by the tie epsilon has more than 28 significant digits."""
    assert decimal_text(Fraction(-9223372036854775832600000001, 2000000000)) == "-4611686018427387916.3000000005"
    assert decimal_text(Fraction(1, 2**50)) == "0.00000000000000088817841970012523233890533447265625"
    with pytest.raises(ValueError):
        decimal_text(Fraction(1, 3))
