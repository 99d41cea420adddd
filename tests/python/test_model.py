"""The Python target's model: the literals, expressions and decisions it computes from the IR."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import pytest
from canspec.targets.python import model as pm


def sig_of(can, message, signal):
    return can.message(message).signal(signal)


@pytest.mark.parametrize(("nbytes", "folds"), [(8, (32, 16, 8)), (7, (32, 16, 8)), (4, (16, 8)), (2, (8,)), (1, ()), (64, (256, 128, 64, 32, 16, 8))])
def test_xor_folds(nbytes, folds):
    assert pm._folds(nbytes) == folds
    value = int.from_bytes(bytes(range(1, nbytes + 1)), "little")
    c = value
    for f in folds:
        c ^= c >> f
    x = 0
    for b in range(1, nbytes + 1):
        x ^= b
    assert c & 0xFF == x


def test_number_literals():
    assert pm.num_lit(Fraction(1, 10), False) == "0.1" and pm.num_lit(Fraction(-1080), False) == "-1080.0"
    assert pm.num_lit(Fraction(5), True) == "5"
    with pytest.raises(ValueError):
        pm.num_lit(Fraction(1, 2), True)


def test_raw_expressions_extract_every_raw(can):
    sig = sig_of(can, "driving_state", "motor_speed")  # start 8, len 16
    expr = pm._raw_expr(sig, 64)
    assert expr == "(v >> 8) & 0xFFFF"
    for raw in (0, 1, 0x7FFF, 0xFFFF):
        assert eval(expr, {"v": raw << 8 | 0xFF | 0xFF << 24}) == raw
    top = sig_of(can, "autocar_eps_command", "checksum")
    assert pm._raw_expr(top, 64) == "v >> 56"  # nothing above it: no mask
    signed = dataclasses.replace(sig, signed=True, raw_type_min=-32768, raw_type_max=32767)
    sexpr = pm._raw_expr(signed, 64)
    for raw in (-32768, -1, 0, 1, 32767):
        assert eval(sexpr, {"v": (raw & 0xFFFF) << 8 | 0xAB | 0xCD << 24}) == raw


def test_physical_and_rounding_expressions(can):
    steer = sig_of(can, "autocar_eps_command", "steering_angle_cmd")
    assert pm._phys_expr(steer, "r", "float", None) == "r * 0.1 - 1080.0"
    assert pm._q_expr(steer, False, "x") == "(x + 1080.0) / 0.1"
    speed = sig_of(can, "driving_state", "motor_speed")
    assert pm._q_expr(speed, True, "m.motor_speed") == "m.motor_speed + 15000"
    ratio = sig_of(can, "driving_state", "motor_speed_ratio")
    assert pm._phys_expr(ratio, "(v >> 40) & 0xFF", "int", None) == "((v >> 40) & 0xFF) + 1"


def test_default_values_prefer_physical_zero(can):
    assert pm._default_raw(sig_of(can, "autocar_eps_command", "steering_angle_cmd")) == 10800
    assert pm._default_raw(sig_of(can, "driving_state", "motor_speed_ratio")) == 0  # range [1, 254]: raw 0 = physical 1
    assert pm._default_raw(sig_of(can, "autocar_speed_command", "accel_cmd")) == 450


def test_range_and_raw_checks(can):
    steer = sig_of(can, "autocar_eps_command", "steering_angle_cmd")
    assert not pm._raw_check(steer, False)  # both ends of [-1080, 1080] round inside 0..21600
    angular = sig_of(can, "autocar_eps_command", "max_angular_speed")  # documented up to 512, the bits reach 510
    assert pm._raw_check(angular, False)
    assert "[0, 512] deg/s or 0 (no_limit)" == pm._range_text(angular)


def test_only_intel_signals(can):
    msg = can.message("autocar_eps_command")
    sig = msg.signal("counter")
    seg = dataclasses.replace(sig.segments[0], byte=3)
    with pytest.raises(ValueError, match="only Intel"):
        pm._check_intel(msg, dataclasses.replace(sig, segments=(seg,)))


def test_unsupported_checksum_is_refused(can):
    msg = can.message("autocar_eps_command")
    odd = dataclasses.replace(msg, checksum=dataclasses.replace(msg.checksum, algorithm="crc8"))
    with pytest.raises(ValueError, match="checksum algorithm 'crc8' is not supported"):
        pm._message(odd, {t.name: t.name.title() for t in can.value_tables}, {})


def test_method_names_are_never_attribute_names(can):
    msg = can.message("autocar_eps_command")
    clash = dataclasses.replace(msg.signal("counter"), name="encode")
    assert pm._signal(msg, clash, 0, 64, {}, {}).attr == "encode_"


def test_package_model(spec):
    pkg = pm.build_package(spec)
    assert pkg.package == "kaiwo_gateway" and pkg.dist_name == "kaiwo-gateway" and pkg.version == "2.0.5"
    assert len(pkg.messages) == 25 and len(pkg.enums) == len(spec.can.value_tables)
    assert pkg.example.checksum is not None and pkg.example.counter is not None
    eps = next(m for m in pkg.messages if m.name == "autocar_eps_command")
    assert eps.checksum.whole_frame and eps.checksum.cover_mask == "0xFFFFFFFFFFFFFF"
