"""Division by a constant as a multiply, for the integer-only encode's 32-bit rounding.

Cortex-M0/M0+ have no divide instruction, so `a / d` there calls libgcc (`__aeabi_uidivmod`). Every
divisor of the fixed encode is a constant per signal, and the generator knows the numerator's
range, so it divides by multiplying with a reciprocal instead (Granlund & Montgomery 1994; Hacker's
Delight ch. 10): floor(n / d) = (n × m) >> s for every n in [0, nmax], where m = ceil(2^s / d).

Why it is exact: m × d = 2^s + e with 0 <= e < d, so n × m / 2^s = n / d + n × e / (d × 2^s). The
added term is below 1/d wherever n × e < 2^s, and n / d is at most (d - 1) / d above its floor, so
the floor does not change. `magic` only returns (m, s) where nmax × e < 2^s: exact for the whole range.

Two forms, both in 32-bit integers: the low one where every product n × m fits 32 bits (one
32-bit multiply on any core), else the high one, s >= 32, which takes the high word of the 64-bit
product (`<prefix>_mul_hi32`: one UMULL where the core has it, 16-bit halves on Thumb-1 cores).
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec.render.literals import c_hex, c_uint

WORD = 2**32


@dataclass(frozen=True)
class Magic:
    divisor: int
    nmax: int  # the largest numerator: exact on [0, nmax]
    m: int  # < 2^32
    shift: int  # s, or s - 32 in the high form
    high: bool  # (n × m) >> 32 >> shift; else (n × m) >> shift, n × m < 2^32
    half: bool  # the numerator is |num| + floor(d / 2); else |num|, rounded by the remainder

    def quotient(self, n: int) -> int:
        """floor(n / divisor) as the C computes it, in 32-bit unsigned words."""
        product = (n % WORD) * self.m
        return (product >> 32 if self.high else product % WORD) >> self.shift


def _exact(d: int, nmax: int, m: int, s: int) -> bool:
    return nmax * (m * d - (1 << s)) < (1 << s)


def magic(d: int, nmax: int, half: bool = True, low: bool = True) -> Magic | None:
    """The cheapest exact form of floor(n / d) on [0, nmax]: the low form with the smallest m
    (the smallest s), else the high form with the smallest s; None where neither exists (m
    would need 33 bits)."""
    if not (d > 1 and 0 <= nmax < WORD):
        raise ValueError(f"divisor {d}, numerators up to {nmax}: not a 32-bit division")
    s = 0
    while low and nmax * -(-(1 << s) // d) < WORD:  # low form: n × m within 32 bits
        m = -(-(1 << s) // d)
        if _exact(d, nmax, m, s):
            return _checked(Magic(d, nmax, m, s, False, half))
        s += 1
    for s in range(32, 96):
        m = -(-(1 << s) // d)
        if m >= WORD:
            return None
        if _exact(d, nmax, m, s):
            return _checked(Magic(d, nmax, m, s - 32, True, half))
    return None


def rounding(d: int, amax: int) -> Magic:
    """How the C rounds num / d half away from zero for |num| <= amax <= 2^31: floor((|num| +
    floor(d / 2)) / d), one multiply; where that has no exact form (d and amax both near 2^31),
    floor(|num| / d) and its remainder. That one always exists: for d not a power of two, with
    2^(L-1) < d < 2^L, s = 31 + L gives m < 2^32 and e × amax <= (2^L - 2) × 2^31 < 2^s."""
    if amax > 2**31:
        raise ValueError(f"|num| up to {amax}: not an int32_t")
    mg = magic(d, amax + d // 2) or magic(d, amax, half=False, low=False)
    if mg is None:  # a power of two has m = 1 in the low form
        raise AssertionError(f"no exact multiply for {amax} / {d}")
    return mg


def _checked(mg: Magic) -> Magic:
    """The proof's result, asserted where it is tightest: at nmax and at the largest numerator
    below it of each of the residues d - 1 and 0."""
    d, top = mg.divisor, mg.nmax
    for n in {0, top, top - top % d, top - (top + 1) % d}:
        if 0 <= n <= top:
            assert mg.quotient(n) == n // d, (mg, n)
    return mg


def call(fn: dict[str, str], num: str, mg: Magic) -> str:
    """The C call that rounds num / d half away from zero; fn names the runtime's functions
    (`mul`, `mulhi`, `mulrem`)."""
    if not mg.half:
        return f"{fn['mulrem']}({num}, {c_uint(mg.divisor)}, {c_hex(mg.m)}, {c_uint(mg.shift)})"
    return f"{fn['mulhi' if mg.high else 'mul']}({num}, {c_uint(mg.divisor // 2)}, {c_hex(mg.m)}, {c_uint(mg.shift)})"


def note(mg: Magic) -> str:
    """The comment beside the call: the divisor, the constant, and the range it is exact on."""
    shift = f"(32 + {mg.shift})" if mg.high else f"{mg.shift}"
    num = f"(|num| + {mg.divisor // 2})" if mg.half else "|num|"
    return f"divide by {mg.divisor}: {num} * 0x{mg.m:X} >> {shift}, exact up to {mg.nmax}"
