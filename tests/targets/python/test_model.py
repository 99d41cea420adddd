"""The Python target's view model: the literals, expressions, statements and names it computes
from the IR (checked by evaluating them, or against the IR and the reference rule)."""

from __future__ import annotations

import dataclasses
import math
import random
from fractions import Fraction

import pytest
from canspec import ir
from canspec.ir.encoding import to_raw_runtime
from canspec.render.literals import PYTHON
from canspec.targets.python import code, fields, naming
from canspec.targets.python import model as pm


def sig_of(can, message, signal):
    return can.message(message).signal(signal)


@pytest.mark.parametrize(("nbytes", "folds"), [(8, (32, 16, 8)), (7, (32, 16, 8)), (4, (16, 8)), (3, (16, 8)), (2, (8,)), (1, ())])
def test_xor_folds(nbytes, folds):
    assert code.xor_folds(nbytes) == folds
    value = int.from_bytes(bytes(range(1, nbytes + 1)), "little")
    c = value
    for f in folds:
        c ^= c >> f
    x = 0
    for b in range(1, nbytes + 1):
        x ^= b
    assert c & 0xFF == x


def test_number_literals():
    """The Python target's numbers: an int where the quantity is integral, else a float literal."""
    assert PYTHON.number(Fraction(5), True) == "5" and PYTHON.number(Fraction(1, 10), False) == "0.1" and PYTHON.number(Fraction(-1080), False) == "-1080.0"
    with pytest.raises(ValueError):
        PYTHON.number(Fraction(1, 2), True)


def test_raw_expressions_extract_every_raw(can):
    sig = sig_of(can, "driving_state", "motor_speed")  # start 8, len 16
    classic, fd = fields.raw_expr(sig, 64), fields.raw_expr(sig, 72)
    assert classic == fd == "d1 | d2 << 8"  # from the frame's bytes, in a classic or an FD frame (a struct unpacks those)
    for raw in (0, 1, 0x7FFF, 0xFFFF):
        frame = (raw << 8 | 0xFF | 0xFF << 24).to_bytes(9, "little")
        assert eval(classic, {f"d{i}": b for i, b in enumerate(frame)}) == raw
    wide_fd = dataclasses.replace(sig, length=40, word_mask=2**40 - 1)  # wider than MAX_BYTE_SPAN bytes: a slice of its own
    assert fields.raw_expr(wide_fd, 128) == '_from_bytes(data[1:6], "little")'
    for raw in (0, 1, 2**40 - 1, 0x123456789A):
        frame = (raw << 8 | 0xFF | 0xFF << 48).to_bytes(16, "little")
        assert eval(fields.raw_expr(wide_fd, 128), {"data": frame, "_from_bytes": int.from_bytes}) == raw
    wide = _wide(can, False, Fraction(1))
    assert fields.raw_expr(wide, 64) == "v" and fields.raw_expr(dataclasses.replace(wide, length=40, word_mask=2**40 - 1), 64) == "v & 0xFFFFFFFFFF"
    top = sig_of(can, "autocar_eps_command", "checksum")
    assert fields.raw_expr(top, 64) == "d7"  # a classic frame's byte, read alone
    door = sig_of(can, "autocar_control_command_1", "door_cmd")  # start 2, len 2: within byte 0
    assert fields.raw_expr(door, 64) == "(d0 >> 2) & 0x3"
    assert [eval(fields.raw_expr(door, 64), {"d0": raw << 2 | 0b11110011}) for raw in range(4)] == [0, 1, 2, 3]
    signed = dataclasses.replace(sig, signed=True, sign_bit=0x8000, raw_type_min=-32768, raw_type_max=32767)
    sexpr = fields.raw_expr(signed, 72)
    for raw in (-32768, -1, 0, 1, 32767):
        frame = ((raw & 0xFFFF) << 8 | 0xAB | 0xCD << 24).to_bytes(9, "little")
        assert eval(sexpr, {f"d{i}": b for i, b in enumerate(frame)}) == raw


def test_physical_and_quotient_expressions(can):
    steer = sig_of(can, "autocar_eps_command", "steering_angle_cmd")
    assert fields.phys_expr(steer, "r", "float") == "r * 0.1 - 1080.0"
    assert fields.q_expr(steer, False, "x") == "(x + 1080.0) / 0.1"
    speed = sig_of(can, "driving_state", "motor_speed")
    assert fields.q_expr(speed, True, "m.motor_speed") == "m.motor_speed + 15000"
    ratio = sig_of(can, "driving_state", "motor_speed_ratio")
    assert fields.phys_expr(ratio, "(v >> 40) & 0xFF", "int") == "((v >> 40) & 0xFF) + 1"


def test_default_values_prefer_physical_zero(can):
    assert fields.default_raw(sig_of(can, "autocar_eps_command", "steering_angle_cmd")) == 10800
    assert fields.default_raw(sig_of(can, "driving_state", "motor_speed_ratio")) == 0  # range [1, 254]: raw 0 = physical 1
    assert fields.default_raw(sig_of(can, "autocar_speed_command", "accel_cmd")) == 450


def test_range_and_raw_checks(can):
    steer = sig_of(can, "autocar_eps_command", "steering_angle_cmd")
    assert not fields.raw_check(steer, False)  # both ends of [-1080, 1080] round inside 0..21600
    assert not fields.exact_branch(steer)
    angular = sig_of(can, "autocar_eps_command", "max_angular_speed")  # documented up to 512, the bits reach 510
    assert fields.raw_check(angular, False)
    assert "[0, 512] deg/s or 0 (no_limit)" == fields.range_text(angular)


def _wide(can, signed, factor, offset=Fraction(0)):
    """A 64-bit field of the given scaling, its ranges as the IR computes them."""
    base = sig_of(can, "autocar_eps_command", "steering_angle_cmd")
    tmin, tmax = (-(2**63), 2**63 - 1) if signed else (0, 2**64 - 1)
    lo, hi = sorted((tmin * factor + offset, tmax * factor + offset))
    return dataclasses.replace(base, length=64, start=0, word_shift=0, word_mask=2**64 - 1, signed=signed,
                               sign_bit=2**63 if signed else 0, factor=factor, offset=offset,
                               raw_type_min=tmin, raw_type_max=tmax, raw_min=tmin, raw_max=tmax, phys_min=lo, phys_max=hi, check_min=lo, check_max=hi,
                               accept_min=lo, accept_max=hi, doc_min=None, doc_max=None, specials=(), value_table=None)


def _run_encode(sig, x):
    """The inline encode statements of a one-signal message, run on `x`; the slow path stubbed out."""
    ns = fields.Namespace()
    ctx = fields.SignalContext("m", 0, 64, fields.Namespace(), fields.Namespace(), ns, None, {}, None)
    py = fields.build_signal(sig, ctx)
    frame = code.Frame("m", "0x1", 8, (py,), None)
    src = "def enc(m):\n" + "".join(f"    {line}\n" for line in code.encode(frame, "slow"))
    env = {"_to_raw": lambda *_: "slow", "slow": lambda raw: raw, "int": int, "abs": abs}
    exec(src, env)  # noqa: S102
    got = env["enc"](type("M", (), {py.attr: x})())
    return got if isinstance(got, dict) else int.from_bytes(got, "little")


WIDE_SCALINGS = [
    (False, Fraction(1, 10), Fraction(0)), (True, Fraction(1, 10), Fraction(-5, 2)), (True, Fraction(-3), Fraction(0)), (False, Fraction(2), Fraction(7))]


@pytest.mark.parametrize(("signed", "factor", "offset"), WIDE_SCALINGS)
def test_inline_rounding_is_the_shared_rule_also_beyond_2_to_the_52(can, signed, factor, offset):
    """The fast path of encode gives the reference rule's raw (ir/encoding.to_raw_runtime) on every
    double, including quotients at and beyond 2^52 where q + 0.5 would round to even."""
    sig = _wide(can, signed, factor, offset)
    assert fields.exact_branch(sig)
    rng = random.Random(7)
    limit = float(ir.EXACT_LIMIT)
    qs = [0.0, 0.5, 2.5, limit - 1.5, limit - 0.5, limit, limit + 1, limit + 3, 2 * limit + 2, 2**60 + 2**9, 2**63 - 2**12]
    qs += [rng.uniform(0, 2**63) for _ in range(200)] + [math.ldexp(rng.random(), rng.randint(0, 63)) for _ in range(200)]
    for q in qs:
        for sign in (1, -1) if signed or factor < 0 else (1,):
            x = (sign * q) * float(factor) + float(offset)
            want = to_raw_runtime(x, float(factor), float(offset))
            if not (float(sig.accept_min) <= x <= float(sig.accept_max) and sig.raw_min <= want <= sig.raw_max):
                continue  # the slow path's business
            got = _run_encode(sig, x)
            assert isinstance(got, int) and got - (1 << 64 if signed and got >> 63 else 0) == want, (q, x, got)


def test_names_never_clash_and_never_shadow():
    ns = naming.Namespace({"Message"})
    assert [ns.take(n) for n in ("Engine2", "Engine2", "Message", "class", "match", "type")] == ["Engine2", "Engine2_", "Message_", "class_", "match_", "type_"]
    assert naming.package_name("platform") == "platform_" and naming.package_name("can") == "can_" and naming.package_name("kaiwo_gateway") == "kaiwo_gateway"
    assert "type" in naming.KEYWORDS and "int" in fields.ATTRIBUTE_RESERVED and "encode" in fields.ATTRIBUTE_RESERVED


def test_package_model(spec):
    pkg = pm.build_package(spec)
    assert pkg.package == "kaiwo_gateway" and pkg.dist_name == "kaiwo-gateway" and pkg.version == "2.0.5"
    assert len(pkg.messages) == 25 and len(pkg.enums) == len(spec.can.value_tables)
    assert pkg.example.checksum is not None and pkg.example.counter is not None
    assert pkg.modules == ("enums", "errors", "j1939", "messages", "monitor", "multiframe", "supervision") and pkg.is_j1939
    eps = next(m for m in pkg.messages if m.name == "autocar_eps_command")
    assert eps.id_lit == "0x1801B0A0" and eps.is_extended and eps.checksum.shift == 56 and eps.checksum.folds == (32, 16, 8)
