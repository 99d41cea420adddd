"""Python models of the C runtime's rounding divisions (divide.py writes their constants): the
exact rule a rounding must give, and each C function step for step, in the widths the C uses.
`c_function` evaluates a generated C condition or expression with them. Shared by the tests of the
rounding plans (test_c_divide.py) and of the encode's range checks (test_c_physical.py)."""

from __future__ import annotations

import re


def exact_round(num: int, den: int) -> int:
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


def c_function(cond: str):  # type: ignore[no-untyped-def]
    """A generated condition or expression as a Python function of value and r (False if empty)."""
    return eval(f"lambda value, r=None: {_py(cond) or False}", dict(C_FUNCTIONS))  # noqa: S307
