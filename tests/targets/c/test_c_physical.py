"""The integer-only encode's range checks (physical.py): a term is left out only where earlier
checks already decide it. Each generated C condition is evaluated in Python for every input the
first check lets through (a small field's whole domain), against the unpruned definition:
out of range iff value < min, value > max, r < raw_min or r > raw_max, with r = (value - fo) / ff
rounded half away from zero by exact arithmetic here. The 32-bit rounding divides by a multiply
(divide.py): checked against integer division, in Python step for step as the C does it, and in
C itself with both ways of taking a product's high word."""

from __future__ import annotations

import dataclasses
import itertools
import re
import sys
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import pytest
from canspec.render.literals import C
from canspec.targets.c import divide, physical
from canspec.targets.c.names import CNames

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cbuild  # noqa: E402

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


def _exact_round(num: int, den: int) -> int:
    """num / den rounded half away from zero: the nearest integer of 2|num| / 2|den|, a tie
    (an odd multiple of a half) going up in magnitude."""
    mag = (2 * abs(num) + abs(den)) // (2 * abs(den))
    return mag if (num < 0) == (den < 0) else -mag


WORD = 2**32


def _magnitude(num: int, half: int) -> int:
    """`((num < 0) ? (0u - (uint32_t)num) : (uint32_t)num) + half` in uint32_t."""
    return ((-num if num < 0 else num) + half) % WORD


def _signed(num: int, r: int) -> int:
    return -r if num < 0 else r


def _c_div_round_mul(num: int, half: int, m: int, shift: int) -> int:
    """The C `div_round_mul`, step for step in 32-bit words: the product's low word, shifted."""
    return _signed(num, (_magnitude(num, half) * m % WORD) >> shift)


def _c_div_round_mulhi(num: int, half: int, m: int, shift: int) -> int:
    """The C `div_round_mulhi`: the product's high word, shifted."""
    return _signed(num, (_magnitude(num, half) * m >> 32) >> shift)


def _c_div_round_mulrem(num: int, d: int, m: int, shift: int) -> int:
    """The C `div_round_mulrem`: |num| / d by the high word, rounded by the remainder."""
    a = _magnitude(num, 0)
    q = (a * m >> 32) >> shift
    rem = (a - q * d) % WORD
    return _signed(num, q if rem < (d - rem) % WORD else q + 1)


WORD64 = 2**64


def _c_div_round_u64_mulhi(a: int, half: int, m: int, shift: int) -> int:
    """The C `div_round_u64_mulhi`: the high 64 bits of the 128-bit product, shifted."""
    return ((a + half) % WORD64 * m >> 64) >> shift


def _c_div_round_u64_mulrem(a: int, d: int, m: int, shift: int) -> int:
    """The C `div_round_u64_mulrem`: floor(a / d) by the 65-bit multiplier, rounded by the remainder."""
    hi = a * m >> 64
    q = (hi + ((a - hi) >> 1)) >> shift
    rem = (a - q * d) % WORD64
    return q if rem < (d - rem) % WORD64 else q + 1


def _signed64(fn):  # type: ignore[no-untyped-def]
    """The C `div_round64_*`: the unsigned function on |num|, the sign put back."""
    return lambda num, k, m, shift: _signed(num, fn((-num if num < 0 else num) % WORD64, k, m, shift))


C_FUNCTIONS = {"div_round_mul": _c_div_round_mul, "div_round_mulhi": _c_div_round_mulhi, "div_round_mulrem": _c_div_round_mulrem,
               "div_round_u64_mulhi": _c_div_round_u64_mulhi, "div_round_u64_mulrem": _c_div_round_u64_mulrem,
               "div_round64_mulhi": _signed64(_c_div_round_u64_mulhi), "div_round64_mulrem": _signed64(_c_div_round_u64_mulrem)}


def _py(cond: str) -> str:
    """A generated C condition or expression as Python (the literal forms the C target writes)."""
    out = re.sub(r"U?INT64_C\((-?(?:0x[0-9A-F]+|\d+))\)", r"\1", cond)
    out = re.sub(r"\(\(uint64_t\)(\w+) \+ (\d+)\)", rf"((\1 + \2) % {2**64})", out)  # wraps modulo 2^64
    out = out.replace("INT64_MIN", str(-(2**63))).replace("(int64_t)", "").replace("(uint64_t)", "")
    out = re.sub(r"\b(\d+|0x[0-9A-F]+)u\b", r"\1", out)
    out = out.replace("||", " or ").replace("&&", " and ").replace("!(", " not (")
    return re.sub(r"\bp_(div_round\w+)\(", r"\1(", out)


def _fn(cond: str):  # type: ignore[no-untyped-def]
    """A generated condition or expression as a Python function of value and r (False if empty)."""
    return eval(f"lambda value, r=None: {_py(cond) or False}", dict(C_FUNCTIONS))  # noqa: S307


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
        if outside(value):  # refused before the rounding: rightly, by the exact rule
            r = _exact_round(value - fo, ff)
            assert r not in specials and (value < fmin or value > fmax or r < sig.raw_min or r > sig.raw_max), (sig, fixed.outside, value)
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


# The 32-bit rounding divides by a multiply (divide.py): exact against integer division.

def _boundary_numerators(d: int, amax: int) -> set[int]:
    """0..300, the top 300, and around the multiples of d and the ties (k d + d / 2) near both."""
    out = set(range(min(amax, 300) + 1)) | set(range(max(amax - 300, 0), amax + 1))
    for k in (1, 2, 3, amax // d - 1, amax // d, amax // d + 1):
        for base in (k * d, k * d + d // 2, k * d + (d + 1) // 2):
            out |= {n for n in range(base - 2, base + 3) if 0 <= n <= amax}
    return out


def test_magic_quotient_is_exact_on_every_numerator():
    """floor(n / d) = (n × m) >> s on the whole range, exhaustively for small ranges and divisors."""
    for d in range(2, 70):
        for nmax in (d - 1, d, 257, 4099):
            mg = divide.magic(d, nmax)
            assert mg is not None and not mg.high, (d, nmax)  # small ranges: one 32-bit multiply
            assert all(mg.quotient(n) == n // d for n in range(nmax + 1)), mg
    mg = divide.magic(10, 655364)  # the steering angle: 0 .. 655364 exhaustively, the high form
    assert (mg.m, mg.shift, mg.high) == (0x1999999A, 0, True)
    assert all(mg.quotient(n) == n // 10 for n in range(655365))
    # the check is no rubber stamp: the next smaller constant is wrong inside that range
    worse = dataclasses.replace(mg, m=mg.m - 1)
    assert any(worse.quotient(n) != n // 10 for n in range(655365))


DIVISORS = (2, 3, 7, 10, 50, 150, 641, 1000, 65537, 1000003, 2**30 - 2, 2**30 + 1, 2**31 - 1, 2**31)


def test_rounding_plan_is_exact_up_to_int32_magnitudes():
    """Every divisor has a plan over |num| <= 2^31 (the proof in divide.rounding); the generated
    call, evaluated as the C computes it, rounds half away from zero at the ends, the multiples
    of d and every tie near them, for both signs."""
    forms = set()
    for d in DIVISORS:
        for amax in {2**31, 2**31 - 1, min(3 * d + 7, 2**31), 1000, 100000}:
            mg = divide.rounding(d, amax)
            forms.add("mulrem" if not mg.half else "mulhi" if mg.high else "mul")
            rounded = _fn(divide.call({k: f"p_div_round_{k}" for k in ("mul", "mulhi", "mulrem")}, "value", mg))
            for n in _boundary_numerators(d, amax):
                for num in {n, -n} - {2**31}:  # the numerator is an int32_t
                    assert rounded(num) == _exact_round(num, d), (mg, num)
    assert forms == {"mul", "mulhi", "mulrem"}
    with pytest.raises(ValueError):
        divide.rounding(10, 2**31 + 1)


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


RUNTIME_MAIN = r"""
#include <inttypes.h>
#include <stdio.h>
#include "kaiwo_gateway_common.h"
static const struct { int32_t num; uint32_t k; uint32_t m; uint32_t shift; int form; } cases[] = {
@CASES@
};
int main(void) {
    size_t i;
    for (i = 0u; i < sizeof cases / sizeof cases[0]; i++) {
        int32_t r = (cases[i].form == 0) ? kaiwo_gateway_div_round_mul(cases[i].num, cases[i].k, cases[i].m, cases[i].shift)
                  : (cases[i].form == 1) ? kaiwo_gateway_div_round_mulhi(cases[i].num, cases[i].k, cases[i].m, cases[i].shift)
                  : kaiwo_gateway_div_round_mulrem(cases[i].num, cases[i].k, cases[i].m, cases[i].shift);
        printf("%" PRId32 "\n", r);
    }
    return 0;
}
"""


@pytest.mark.parametrize("strategy", ["1", "0"])  # one 32 x 32 -> 64 multiply, or 16-bit halves
def test_runtime_division_functions_in_c(tmp_path, strategy):
    """The C runtime's functions on the plans above, compiled (gcc, strict) with the 64-bit
    product and with the 16-bit halves Thumb-1 cores use: the same exact results."""
    rows, want = [], []
    for d in DIVISORS:
        mg = divide.rounding(d, 2**31)
        form = 2 if not mg.half else 1 if mg.high else 0
        k = d if not mg.half else d // 2
        for n in sorted(_boundary_numerators(d, 2**31))[::7]:
            for num in {n, -n} - {2**31}:
                rows.append(f"    {{ {C.integer(num)}, {k}u, {mg.m}u, {mg.shift}u, {form} }},")
                want.append(_exact_round(num, d))
    src = tmp_path / "main.c"
    src.write_text(RUNTIME_MAIN.replace("@CASES@", "\n".join(rows)))
    exe = tmp_path / "div"
    cbuild.compile_c("gcc", [src], exe, ["-std=c99", "-O2", *cbuild.STRICT, f"-DKAIWO_GATEWAY_STRATEGY={strategy}"], [cbuild.HEADERS])
    proc = cbuild.run([str(exe)])
    assert proc.returncode == 0, proc.stderr
    assert [int(v) for v in proc.stdout.split()] == want


# The 64-bit rounding (numerators beyond 32 bits) divides by a multiply too: the high 64 bits of a
# 128-bit product, or the 65-bit multiplier and the remainder; no 64-bit division or product.

DIVISORS64 = (2, 3, 7, 10, 14, 70, 1022, 2**32 - 1, 2**32 + 1, 2**40 - 3, 2**61 - 1, 2**62 - 2, 2**62 + 3, 2**63 - 1, 2**63)
CALL64 = {"signed": {k: f"p_div_round64_{k}" for k in ("mul", "mulhi", "mulrem")},
          "unsigned": {k: f"p_div_round_u64_{k}" for k in ("mul", "mulhi", "mulrem")}}


def test_rounding64_plan_is_exact_up_to_64_bit_magnitudes():
    """Every divisor has a 64-bit plan, signed (|num| <= 2^63) and unsigned (up to 2^64 - 1): the
    generated call, as the C computes it, rounds half away from zero around the multiples of d,
    the ties and the ends."""
    forms = set()
    for d in DIVISORS64:
        for kind, top in (("signed", 2**63), ("unsigned", 2**64 - 1)):
            for amax in {top, top - 1, min(3 * d + 7, top), 10**6, (top // d) * d}:
                mg = divide.rounding64(d, amax)
                forms.add((kind, "mulrem" if not mg.half else "mulhi", mg.add))
                rounded = _fn(divide.call(CALL64[kind], "value", mg))
                for n in _boundary_numerators(d, amax):
                    for num in ({n, -n} - {2**63} if kind == "signed" else {n}):
                        assert rounded(num) == _exact_round(num, d), (mg, num)
    assert forms == {(k, "mulhi", False) for k in CALL64} | {(k, "mulrem", True) for k in CALL64}
    # the 65-bit multiplier where no 64-bit one is exact: every uint64_t, here 0 .. 2^16 and the top
    mg = divide.magic(7, 2**64 - 1, half=False, low=False, bits=64, add=True)
    assert mg is not None and divide.magic(7, 2**64 - 1, half=False, low=False, bits=64) is None
    assert all(mg.quotient(n) == n // 7 for n in itertools.chain(range(2**16), range(2**64 - 2**16, 2**64)))
    with pytest.raises(ValueError):
        divide.rounding64(10, 2**64)


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
    assert strain.decode_expr == "p_mul64((int64_t)raw, INT64_C(10))"
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


RUNTIME64_MAIN = r"""
#include <inttypes.h>
#include <stdio.h>
#include "kaiwo_gateway_common.h"
static const struct { int64_t num; uint64_t k; uint64_t m; uint32_t shift; int form; } cases[] = {
@CASES@
};
static const uint64_t words[] = { @WORDS@ };
int main(void) {
    size_t i, j;
    for (i = 0u; i < sizeof cases / sizeof cases[0]; i++) {
        const uint64_t a = (uint64_t)cases[i].num;
        switch (cases[i].form) {
        case 0: printf("%" PRId64 "\n", kaiwo_gateway_div_round64_mulhi(cases[i].num, cases[i].k, cases[i].m, cases[i].shift)); break;
        case 1: printf("%" PRId64 "\n", kaiwo_gateway_div_round64_mulrem(cases[i].num, cases[i].k, cases[i].m, cases[i].shift)); break;
        case 2: printf("%" PRIu64 "\n", kaiwo_gateway_div_round_u64_mulhi(a, cases[i].k, cases[i].m, cases[i].shift)); break;
        default: printf("%" PRIu64 "\n", kaiwo_gateway_div_round_u64_mulrem(a, cases[i].k, cases[i].m, cases[i].shift)); break;
        }
    }
    for (i = 0u; i < sizeof words / sizeof words[0]; i++) {
        for (j = 0u; j < sizeof words / sizeof words[0]; j++) {
            printf("%" PRIu64 " %" PRIu64 " %" PRId64 " %" PRIu64 "\n", kaiwo_gateway_mul_hi64(words[i], words[j]),
                   kaiwo_gateway_mul64_u(words[i], words[j]), kaiwo_gateway_mul64((int64_t)words[i], (int64_t)words[j]),
                   kaiwo_gateway_shr64(words[i], (uint32_t)(j % 64u)));
        }
    }
    return 0;
}
"""

WORDS = (0, 1, 2, 3, 0xFFFF, 0x10000, 0xFFFFFFFF, 2**32, 2**32 + 1, 0x123456789ABCDEF0, 2**63 - 1, 2**63, 2**63 + 1, 2**64 - 2, 2**64 - 1,
         0xFEDCBA9876543210, 0x00000001FFFFFFFF, 0xFFFFFFFF00000000)


def _int64(v: int) -> int:
    return v - 2**64 if v >= 2**63 else v


@pytest.mark.parametrize("strategy", ["1", "0"])
def test_runtime_64_bit_functions_in_c(tmp_path, strategy):
    """The C runtime's 64-bit division and product functions, compiled (gcc, strict) with the
    32 x 32 -> 64 product from one multiply and from 16-bit halves: the same exact results, the
    products and shifts checked on words at the ends of their halves."""
    rows, want = [], []
    for d in DIVISORS64:
        for kind, top in (("signed", 2**63), ("unsigned", 2**64 - 1)):
            mg = divide.rounding64(d, top)
            form = (0 if kind == "signed" else 2) + (not mg.half)
            for n in sorted(_boundary_numerators(d, top))[::23]:
                for num in ({n, -n} - {2**63} if kind == "signed" else {n}):
                    k = d if not mg.half else d // 2
                    rows.append(f"    {{ {C.integer(_int64(num), 64)}, UINT64_C({k}), UINT64_C({mg.m}), {mg.shift}u, {form} }},")
                    want.append(str(_exact_round(num, d)))
    for a in WORDS:
        for j, b in enumerate(WORDS):
            want.append(f"{a * b >> 64} {a * b % 2**64} {_int64(a * b % 2**64)} {a >> (j % 64)}")
    src = tmp_path / "main.c"
    src.write_text(RUNTIME64_MAIN.replace("@CASES@", "\n".join(rows)).replace("@WORDS@", ", ".join(f"UINT64_C({w})" for w in WORDS)))
    exe = tmp_path / "div64"
    cbuild.compile_c("gcc", [src], exe, ["-std=c99", "-O2", *cbuild.STRICT, f"-DKAIWO_GATEWAY_STRATEGY={strategy}"], [cbuild.HEADERS])
    proc = cbuild.run([str(exe)])
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines() == want


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
