"""The integer-only encode's range checks (physical.py): a term is left out only where earlier
checks already decide it. Each generated C condition is evaluated in Python for every input the
first check lets through (a small field's whole domain), against the unpruned definition:
out of range iff value < min, value > max, r < raw_min or r > raw_max, with r = (value - fo) / ff
rounded half away from zero by exact arithmetic here; the roundings' own divisions are
test_c_divide.py's."""

from __future__ import annotations

import itertools
import sys
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

from canspec.targets.c import physical
from canspec.targets.c.names import CNames

sys.path.insert(0, str(Path(__file__).resolve().parent))
from division_model import c_function, exact_round  # noqa: E402

NAMES = CNames("p", "P")


@dataclass(frozen=True)
class Special:
    raw: int


@dataclass(frozen=True)
class Sig:
    """The fields of ir.Signal that the fixed path reads."""

    length: int
    signed: bool
    factor: Fraction
    offset: Fraction
    check_min: Fraction
    check_max: Fraction
    raw_min: int
    raw_max: int
    specials: tuple[Special, ...] = ()

    @property
    def raw_type_min(self) -> int:
        return -(2 ** (self.length - 1)) if self.signed else 0

    @property
    def raw_type_max(self) -> int:
        return 2 ** (self.length - 1) - 1 if self.signed else 2**self.length - 1

    @property
    def is_identity(self) -> bool:
        return self.factor == 1 and self.offset == 0

    @property
    def storage_bits(self) -> int:
        return next(b for b in (8, 16, 32, 64) if self.length <= b)


TYPE_RANGES = {"int32_t": (-(2**31), 2**31 - 1), "int64_t": (-(2**63), 2**63 - 1), "uint64_t": (0, 2**64 - 1)}


def _inputs(sig: Sig, fixed: physical.CFixed) -> list[int]:
    """Every input of the value's C type around the first check's bounds: the field's whole
    (small) domain and beyond, or (a wide field) the inputs near its ends."""
    ends = [v * fixed.scale * sig.factor + sig.offset * fixed.scale for v in (sig.raw_type_min - 1, sig.raw_type_max + 1)]
    tlo, thi = TYPE_RANGES[fixed.type]
    lo, hi = max(int(min(ends)) - 3, tlo), min(int(max(ends)) + 3, thi)
    return list(range(lo, hi + 1)) if hi - lo < 4000 else list(range(lo, lo + 2000)) + list(range(hi - 2000, hi + 1))


def _check_agrees(sig: Sig) -> physical.CFixed:
    fixed = physical.fixed_path(NAMES, sig)
    assert fixed is not None, sig
    ff, fo, fmin, fmax = (int(v * fixed.scale) for v in (sig.factor, sig.offset, sig.check_min, sig.check_max))
    specials = {sp.raw for sp in sig.specials}
    outside, rounded, is_special, out_of_range = map(c_function, (fixed.outside, fixed.rounded, fixed.ranges.specials, fixed.ranges.outside))
    for value in _inputs(sig, fixed):
        if outside(value):  # refused before the rounding: rightly, by the exact rule
            r = exact_round(value - fo, ff)
            assert r not in specials and (value < fmin or value > fmax or r < sig.raw_min or r > sig.raw_max), (sig, fixed.outside, value)
            continue
        r = rounded(value)
        assert r == exact_round(value - fo, ff), (sig, value)
        assert bool(is_special(value, r)) == (r in specials)
        if r in specials:
            continue
        wanted = value < fmin or value > fmax or r < sig.raw_min or r > sig.raw_max
        assert bool(out_of_range(value, r)) == wanted, (sig, fixed.ranges.outside, value, r)
    return fixed


def test_exact_rounding_reference():
    assert [physical.round_half_away(Fraction(n, 2)) for n in range(-5, 6)] == [-3, -2, -2, -1, -1, 0, 1, 1, 2, 2, 3]
    assert [exact_round(n, 2) for n in range(-5, 6)] == [-3, -2, -2, -1, -1, 0, 1, 1, 2, 2, 3]
    assert [exact_round(n, -2) for n in (-3, -1, 1, 3)] == [2, 1, -1, -2]


def test_pruned_conditions_agree_with_the_full_ones_on_every_input():
    factors = [Fraction(1), Fraction(2), Fraction(1, 2), Fraction(1, 10), Fraction(3, 10), Fraction(-1), Fraction(-1, 4), Fraction(5)]
    offsets = [Fraction(0), Fraction(7), Fraction(-15, 2), Fraction(1, 4)]
    count = 0
    for length, signed, factor, offset in itertools.product((1, 3, 8), (False, True), factors, offsets):
        sig = Sig(length, signed, factor, offset, Fraction(0), Fraction(0), 0, 0)
        phys = sorted(v * factor + offset for v in (sig.raw_type_min, sig.raw_type_max))
        span = phys[1] - phys[0]
        # documented ranges: the encodable one, narrower ones (on a step and between steps), wider
        for cmin, cmax in ((phys[0], phys[1]), (phys[0] + span / 4, phys[1] - span / 5), (phys[0] - 1, phys[1] + 1),
                           (phys[0] + abs(factor) / 2, phys[1])):
            for rmin, rmax in ((sig.raw_type_min, sig.raw_type_max), (sig.raw_type_min + 1, sig.raw_type_max - 1)):
                for specials in ((), (Special(sig.raw_type_max),)):
                    _check_agrees(Sig(length, signed, factor, offset, cmin, cmax, rmin, rmax, specials))
                    count += 1
    assert count == 3 * 2 * 8 * 4 * 4 * 2 * 2


def test_wide_unsigned_fields_without_offset():
    top = 2**64 - 1
    fixed = _check_agrees(Sig(64, False, Fraction(1), Fraction(0), Fraction(0), Fraction(top), 0, top))
    assert fixed.type == "uint64_t" and fixed.outside == "" and fixed.ranges.outside == ""
    fixed = _check_agrees(Sig(63, False, Fraction(2), Fraction(0), Fraction(10), Fraction(2**63), 5, 2**62))
    # no special value: the accepted range is the first check, and r lies in the raw range then
    assert fixed.type == "uint64_t" and fixed.outside == "(value < UINT64_C(10)) || (value > UINT64_C(9223372036854775808))"
    assert fixed.ranges.outside == ""


def test_terms_earlier_checks_decide_are_left_out():
    # an unscaled 8-bit field over its whole range: the first check leaves nothing to compare
    byte = _check_agrees(Sig(8, False, Fraction(1), Fraction(0), Fraction(0), Fraction(255), 0, 255))
    assert (byte.outside, byte.ranges.outside) == ("(value <= (-1)) || (value >= 256)", "")
    # factor 0.1, offset -12.8, range [-12.8, 12.7]: the range, checked first, bounds the value
    # and r with it (one check instead of the raw type's window and then the range)
    torque = _check_agrees(Sig(8, False, Fraction(1, 10), Fraction(-128, 10), Fraction(-128, 10), Fraction(127, 10), 0, 255))
    assert torque.scale == 100 and torque.outside == "(value < (-1280)) || (value > 1270)" and torque.ranges.outside == ""
    # factor 2 over [0, 512] with a special value (a value outside the range may encode one, so the
    # range is checked after the rounding): 511 is let through and rounds (255.5) to 256, beyond
    # the raw range
    speed = _check_agrees(Sig(8, False, Fraction(2), Fraction(0), Fraction(0), Fraction(512), 0, 255, (Special(0),)))
    assert speed.ranges.outside == "(value < 0) || (r > INT64_C(255))" and speed.ranges.specials == "r == 0"


def test_fixed_encode_divides_by_a_multiply():
    """Fields whose 32-bit rounding takes each form, through the fixed path's checks."""
    # factor 0.1, offset -1080 on 16 bits, range checked first: |num| up to 216000, the high word
    # of the product
    angle = _check_agrees(Sig(16, False, Fraction(1, 10), Fraction(-1080), Fraction(-1080), Fraction(1080), 0, 21600))
    assert angle.outside == "(value < (-108000)) || (value > 108000)"
    assert angle.rounded == "p_div_round_mulhi(value + 108000, 5u, 0x1999999Au, 0u)"
    assert angle.note == "divide by 10: (|num| + 5) * 0x1999999A >> (32 + 0), exact up to 216005"
    # factor -0.25 on 8 signed bits: one 32-bit multiply
    neg = _check_agrees(Sig(8, True, Fraction(-1, 4), Fraction(1, 2), Fraction(-30), Fraction(30), -120, 127))
    assert neg.rounded == "p_div_round_mul(500 - value, 125u, 0x8313u, 23u)"
    # factor 2^30 - 2 on one bit with a special value (so the range is checked after the rounding,
    # and |num| reaches the raw type's window): |num| + d / 2 beyond what one multiply divides exactly
    huge = _check_agrees(Sig(1, False, Fraction(2**30 - 2), Fraction(0), Fraction(0), Fraction(2**30 - 2), 0, 1, (Special(1),)))
    assert huge.rounded == "p_div_round_mulrem(value, 1073741822u, 0x80000005u, 29u)"


def _wide(length: int, signed: bool, factor: Fraction) -> Sig:
    """A field over its whole raw range, the documented range the physical one."""
    tmin, tmax = (-(2 ** (length - 1)), 2 ** (length - 1) - 1) if signed else (0, 2**length - 1)
    ends = sorted((tmin * factor, tmax * factor))
    return Sig(length, signed, factor, Fraction(0), ends[0], ends[1], tmin, tmax)


def test_fixed_encode_divides_64_bit_values_by_a_multiply():
    """Fields whose rounding takes each 64-bit form, through the fixed path's checks; their decode
    multiplies through p_mul64 / p_mul64_u (no 64-bit product in C, __aeabi_lmul on Cortex-M0+)."""
    strain = _check_agrees(_wide(48, True, Fraction(1, 1000)))
    assert strain.rounded == "p_div_round64_mulhi((int64_t)value, UINT64_C(5), UINT64_C(0x199999999999999A), 0u)"
    assert strain.note == "divide by 10: (|num| + 5) * 0x199999999999999A >> (64 + 0), exact up to 1407374883553285"
    assert strain.decode_expr == "p_mul64((int64_t)field, INT64_C(10))"  # an int64_t argument times 10 can overflow: its 48 bits, sign-extended
    assert strain.decode_pre == ("const uint64_t bits = ((uint64_t)raw & UINT64_C(0xFFFFFFFFFFFF)) ^ UINT64_C(0x800000000000);",
                                 "const int64_t field = (int64_t)bits - INT64_C(140737488355328);")
    huge = _check_agrees(_wide(2, True, Fraction(2**62 - 2)))
    # an accepted range wider than INT64_MAX: one unsigned compare (cppcheck misjudges two)
    assert huge.outside == "((uint64_t)value + UINT64_C(9223372036854775804)) > UINT64_C(13835058055282163706)"
    assert huge.rounded == "p_div_round64_mulrem((int64_t)value, UINT64_C(4611686018427387902), UINT64_C(0x9), 61u)"
    assert huge.note == "divide by 4611686018427387902: |num| * 0x10000000000000009 >> (64 + 62), exact up to 9223372036854775804"
    sevens = _check_agrees(_wide(57, False, Fraction(7)))
    assert sevens.rounded == "p_div_round_u64_mulhi(value, UINT64_C(35), UINT64_C(0xEA0EA0EA0EA0EA1), 2u)"
    assert sevens.decode_expr == "p_mul64_u((uint64_t)raw, UINT64_C(70))"
    fourteens = _check_agrees(_wide(60, False, Fraction(14)))
    assert fourteens.rounded == "p_div_round_u64_mulrem(value, UINT64_C(14), UINT64_C(0x2492492492492493), 3u)"
    assert fourteens.note == "divide by 14: |num| * 0x12492492492492493 >> (64 + 4), exact up to 16140901064495857650"


WIDE_FIXED_POINT = Path(__file__).resolve().parent / "cross" / "wide_fixed_point.yaml"


def test_vector_runner_on_every_64_bit_form(tmp_path):
    """A spec whose integer path takes each 64-bit form (cross/wide_fixed_point.yaml): the vector
    runner agrees with its vectors with either product (STRATEGY 1 and 0) and under
    ASan/UBSan, its headers compile warning-free (speccheck.py)."""
    import speccheck

    assert speccheck.check_spec(WIDE_FIXED_POINT, tmp_path) == []
    text = next((tmp_path / "out" / "c").glob("*_messages.h")).read_text(encoding="utf-8")
    for fn in ("div_round64_mulhi", "div_round64_mulrem", "div_round_u64_mulhi", "div_round_u64_mulrem", "mul64", "mul64_u"):
        assert f"_{fn}(" in text, fn
