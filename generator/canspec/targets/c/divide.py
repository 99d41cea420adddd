"""Division by a constant as a multiply, for the integer-only encode's rounding (32 and 64 bits).

Cortex-M0/M0+ have no divide instruction, so `a / d` there calls libgcc (`__aeabi_uidivmod`), and
no Cortex-M core divides 64-bit numbers (`__aeabi_uldivmod`). Every divisor of the fixed encode is
a constant per signal, and the generator knows the numerator's range, so it divides by
multiplying with a reciprocal instead (Granlund & Montgomery 1994; Hacker's Delight ch. 10):
floor(n / d) = (n × m) >> s for every n in [0, nmax], where m = ceil(2^s / d).

Why it is exact: m × d = 2^s + e with 0 <= e < d, so n × m / 2^s = n / d + n × e / (d × 2^s). The
added term is below 1/d wherever n × e < 2^s, and n / d is at most (d - 1) / d above its floor, so
the floor does not change. `magic` only returns (m, s) where nmax × e < 2^s: exact for the whole range.

Two forms, both in 32-bit integers: the low one where every product n × m fits 32 bits (one
32-bit multiply on any core), else the high one, s >= 32, which takes the high word of the 64-bit
product (`<prefix>_mul_hi32`: one UMULL where the core has it, 16-bit halves on Thumb-1 cores).

In 64-bit words (numerators beyond 32 bits) the same, with the high form only: the high 64 bits of
a 128-bit product (`<prefix>_mul_hi64`, four 32 x 32 -> 64 products). Where no 64-bit m is exact,
a 65-bit one m = 2^64 + m' is, on every n < 2^64: s = 64 + L for 2^(L-1) < d <= 2^L gives
m < 2^65 and e < d <= 2^L, so n × e < 2^s. Its top bit is n added back: (n × m) >> s is
(n + hi) >> (s - 64), hi = (n × m') >> 64 <= n, taken as (hi + ((n - hi) >> 1)) >> (s - 65) so
that no sum leaves the word (Hacker's Delight 10-8).
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec.render.literals import C


@dataclass(frozen=True)
class Magic:
    divisor: int
    nmax: int  # the largest numerator: exact on [0, nmax]
    m: int  # < 2^bits; in the add form the multiplier less 2^bits
    shift: int  # s; s - bits in the high form; s - bits - 1 in the add form
    high: bool  # (n × m) >> bits >> shift; else (n × m) >> shift, n × m < 2^bits
    half: bool  # the numerator is |num| + floor(d / 2); else |num|, rounded by the remainder
    bits: int = 32  # the word
    add: bool = False  # the 65-bit multiplier: (hi + ((n - hi) >> 1)) >> shift, hi = (n × m) >> 64

    def quotient(self, n: int) -> int:
        """floor(n / divisor) as the C computes it, in unsigned words of `bits` bits."""
        n %= 1 << self.bits
        product = n * self.m
        if not self.high:
            return (product % (1 << self.bits)) >> self.shift
        hi = product >> self.bits
        return (hi + ((n - hi) >> 1) if self.add else hi) >> self.shift

    @property
    def multiplier(self) -> int:
        return self.m + (1 << self.bits if self.add else 0)

    @property
    def total_shift(self) -> int:
        return self.shift + (self.bits if self.high else 0) + self.add


def _exact(d: int, nmax: int, m: int, s: int) -> bool:
    return nmax * (m * d - (1 << s)) < (1 << s)


def magic(d: int, nmax: int, half: bool = True, low: bool = True, bits: int = 32, add: bool = False) -> Magic | None:
    """The cheapest exact form of floor(n / d) on [0, nmax]: the low form with the smallest m
    (the smallest s), else the high form with the smallest s; None where neither exists (m
    would need bits + 1 bits). `add`: only the add form, m of bits + 1 bits."""
    word = 1 << bits
    if not (d > 1 and 0 <= nmax < word):
        raise ValueError(f"divisor {d}, numerators up to {nmax}: not a {bits}-bit division")
    s = 0
    while low and nmax * -(-(1 << s) // d) < word:  # low form: n × m within one word
        m = -(-(1 << s) // d)
        if _exact(d, nmax, m, s):
            return _checked(Magic(d, nmax, m, s, False, half, bits))
        s += 1
    for s in range(bits, 3 * bits):
        m = -(-(1 << s) // d)
        if m >= word << add:
            return None
        if (m >= word) == add and _exact(d, nmax, m, s):
            return _checked(Magic(d, nmax, m % word, s - bits - add, True, half, bits, add))
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


def rounding64(d: int, amax: int) -> Magic:
    """The 64-bit form of `rounding`, |num| <= amax < 2^64: floor((|num| + floor(d / 2)) / d) by
    the high 64 bits of one product where that is exact and the sum fits, else floor(|num| / d)
    by the 65-bit multiplier (exact on every uint64_t) and its remainder."""
    if not 0 <= amax < 2**64:
        raise ValueError(f"|num| up to {amax}: not a uint64_t")
    mg = magic(d, amax + d // 2, low=False, bits=64) if amax + d // 2 < 2**64 else None
    mg = mg or magic(d, amax, half=False, low=False, bits=64, add=True)
    if mg is None:
        raise AssertionError(f"no exact multiply for {amax} / {d}")
    return mg


def _checked(mg: Magic) -> Magic:
    """The proof's result, asserted where it is tightest: at nmax and at the largest numerator
    below it of each of the residues d - 1 and 0."""
    d, top = mg.divisor, mg.nmax
    for n in {0, top, top - top % d, top - (top + 1) % d, top - top % d - 1}:
        if 0 <= n <= top:
            assert mg.quotient(n) == n // d, (mg, n)
    return mg


def call(fn: dict[str, str], num: str, mg: Magic) -> str:
    """The C call that rounds num / d half away from zero; fn names the runtime's functions
    (`mul`, `mulhi`, `mulrem`)."""
    k, m = (mg.divisor, fn["mulrem"]) if not mg.half else (mg.divisor // 2, fn["mulhi" if mg.high else "mul"])
    return f"{m}({num}, {C.unsigned(k, mg.bits)}, {C.hex(mg.m, bits=mg.bits)}, {C.unsigned(mg.shift)})"


def note(mg: Magic) -> str:
    """The comment beside the call: the divisor, the constant, and the range it is exact on."""
    shift = f"({mg.bits} + {mg.total_shift - mg.bits})" if mg.high else f"{mg.shift}"
    num = f"(|num| + {mg.divisor // 2})" if mg.half else "|num|"
    return f"divide by {mg.divisor}: {num} * 0x{mg.multiplier:X} >> {shift}, exact up to {mg.nmax}"
