"""The rounding divisions of the integer-only encode (divide.py): a division by a constant done
by a multiply, exact against integer division for every numerator the plan admits, in Python step
for step as the C does it, and in C itself with both ways of taking a product's high word (32-
and 64-bit forms)."""

from __future__ import annotations

import dataclasses
import itertools
import sys
from pathlib import Path

import pytest
from canspec.render.literals import C
from canspec.targets.c import divide

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cbuild  # noqa: E402
from division_model import c_function, exact_round  # noqa: E402


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
            rounded = c_function(divide.call({k: f"p_div_round_{k}" for k in ("mul", "mulhi", "mulrem")}, "value", mg))
            for n in _boundary_numerators(d, amax):
                for num in {n, -n} - {2**31}:  # the numerator is an int32_t
                    assert rounded(num) == exact_round(num, d), (mg, num)
    assert forms == {"mul", "mulhi", "mulrem"}
    with pytest.raises(ValueError):
        divide.rounding(10, 2**31 + 1)


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
                want.append(exact_round(num, d))
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
                rounded = c_function(divide.call(CALL64[kind], "value", mg))
                for n in _boundary_numerators(d, amax):
                    for num in ({n, -n} - {2**63} if kind == "signed" else {n}):
                        assert rounded(num) == exact_round(num, d), (mg, num)
    assert forms == {(k, "mulhi", False) for k in CALL64} | {(k, "mulrem", True) for k in CALL64}
    # the 65-bit multiplier where no 64-bit one is exact: every uint64_t, here 0 .. 2^16 and the top
    mg = divide.magic(7, 2**64 - 1, half=False, low=False, bits=64, add=True)
    assert mg is not None and divide.magic(7, 2**64 - 1, half=False, low=False, bits=64) is None
    assert all(mg.quotient(n) == n // 7 for n in itertools.chain(range(2**16), range(2**64 - 2**16, 2**64)))
    with pytest.raises(ValueError):
        divide.rounding64(10, 2**64)


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
                    want.append(str(exact_round(num, d)))
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
