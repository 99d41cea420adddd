"""The integer-only encode's range checks (physical.py): a term is left out only where earlier
checks already decide it. Each generated C condition is evaluated in Python for every input the
first check lets through (a small field's whole domain), against the unpruned definition:
out of range iff value < min, value > max, r < raw_min or r > raw_max, with r = (value - fo) / ff
rounded half away from zero by exact arithmetic here."""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass
from fractions import Fraction

from canspec.targets.c import physical
from canspec.targets.c.names import CNames

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


def _c_div_round(num: int, den: int) -> int:
    """The C helpers `div_round` / `div_round_u`, step for step (unsigned magnitude, remainder)."""
    a = -num if num < 0 else num
    q, rem = a // den, a % den
    q = q + 1 if rem >= den - rem else q
    return -q if num < 0 else q


def _exact_round(num: int, den: int) -> int:
    """num / den rounded half away from zero: the nearest integer of 2|num| / 2|den|, a tie
    (an odd multiple of a half) going up in magnitude."""
    mag = (2 * abs(num) + abs(den)) // (2 * abs(den))
    return mag if (num < 0) == (den < 0) else -mag


def _py(cond: str) -> str:
    """A generated C condition or expression as Python (the literal forms the C target writes)."""
    out = re.sub(r"U?INT64_C\((-?\d+)\)", r"\1", cond)
    out = out.replace("INT64_MIN", str(-(2**63))).replace("(int64_t)", "").replace("(uint64_t)", "")
    out = re.sub(r"\b(\d+)u\b", r"\1", out)
    out = out.replace("||", " or ").replace("&&", " and ").replace("!(", " not (")
    return out.replace("p_div_round_u(", "div_round(").replace("p_div_round32(", "div_round(").replace("p_div_round(", "div_round(")


def _fn(cond: str):  # type: ignore[no-untyped-def]
    """A generated condition or expression as a Python function of value and r (False if empty)."""
    return eval(f"lambda value, r=None: {_py(cond) or False}", {"div_round": _c_div_round})  # noqa: S307


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
    outside, rounded, is_special, out_of_range = map(_fn, (fixed.outside, fixed.rounded, fixed.ranges.specials, fixed.ranges.outside))
    for value in _inputs(sig, fixed):
        if outside(value):
            continue
        r = rounded(value)
        assert r == _exact_round(value - fo, ff), (sig, value)
        assert bool(is_special(value, r)) == (r in specials)
        if r in specials:
            continue
        wanted = value < fmin or value > fmax or r < sig.raw_min or r > sig.raw_max
        assert bool(out_of_range(value, r)) == wanted, (sig, fixed.ranges.outside, value, r)
    return fixed


def test_exact_rounding_reference():
    assert [physical.round_half_away(Fraction(n, 2)) for n in range(-5, 6)] == [-3, -2, -2, -1, -1, 0, 1, 1, 2, 2, 3]
    assert [_exact_round(n, 2) for n in range(-5, 6)] == [-3, -2, -2, -1, -1, 0, 1, 1, 2, 2, 3]
    assert [_exact_round(n, -2) for n in (-3, -1, 1, 3)] == [2, 1, -1, -2]
    assert [_c_div_round(n, 4) for n in (-6, -5, -2, -1, 1, 2, 6)] == [-2, -1, -1, 0, 0, 1, 2]


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
    assert fixed.type == "uint64_t" and fixed.ranges.outside == "(value < UINT64_C(10)) || (value > UINT64_C(9223372036854775808))"


def test_terms_earlier_checks_decide_are_left_out():
    # an unscaled 8-bit field over its whole range: the first check leaves nothing to compare
    byte = _check_agrees(Sig(8, False, Fraction(1), Fraction(0), Fraction(0), Fraction(255), 0, 255))
    assert (byte.outside, byte.ranges.outside) == ("(value <= (-1)) || (value >= 256)", "")
    # factor 0.1, offset -12.8, range [-12.8, 12.7]: the range bounds the value, and r with it
    torque = _check_agrees(Sig(8, False, Fraction(1, 10), Fraction(-128, 10), Fraction(-128, 10), Fraction(127, 10), 0, 255))
    assert torque.scale == 100 and torque.ranges.outside == "(value < (-1280)) || (value > 1270)"
    # factor 2 over [0, 512]: 511 is let through and rounds (255.5) to 256, beyond the raw range
    speed = _check_agrees(Sig(8, False, Fraction(2), Fraction(0), Fraction(0), Fraction(512), 0, 255, (Special(0),)))
    assert speed.ranges.outside == "(value < 0) || (r > INT64_C(255))" and speed.ranges.specials == "r == 0"
