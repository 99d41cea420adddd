"""Physical ↔ raw conversion rules every generated language shares.

`to_raw_exact` is the reference: exact rational arithmetic on the decimal the user meant —
round half away from zero. `to_raw_runtime` is the rule as every generated language computes
it, step for step in IEEE-754 doubles (see model.TIE_EPSILON / EXACT_LIMIT), so C, Python and
Rust give the same raw value for the same double input, for every field width up to 64 bits.

What the runtime rule guarantees (tested in tests/ir/test_encoding_rules.py), with q the exact
quotient (physical - offset) / factor of the decimal the user meant:
- Where (|physical| + |offset|) / |factor| < TIE_GUARANTEE (2^21), the result equals the exact
  rule on every tie and on every input at least 2·TIE_EPSILON (in raw steps) away from a tie:
  the double errors of the input, the subtraction and the division stay below
  3·2^-32 < TIE_EPSILON there. Every tie and every value of a field of up to 21 bits is covered
  unless its offset dwarfs its steps.
- Above that, up to 2^52, doubles cannot resolve every tie of the decimal the user meant (at
  2^32 their spacing is 2^-20): the result is the rounding of the double quotient itself (to
  nearest, half away from zero, TIE_EPSILON included), within 1 of the exact rule, and equal to
  it wherever q is further than TIE_EPSILON + 2^-50·|q| from a tie.
- From 2^52 up every double is an integer: raw = q. Raw values a double cannot hold (beyond
  2^53 in magnitude) are reached only through the raw-value APIs, never from a physical value.
"""

from __future__ import annotations

import math
import struct
import sys
from decimal import Decimal, localcontext
from fractions import Fraction
from functools import lru_cache

from canspec.ir.model import EXACT_LIMIT, TIE_EPSILON, runtime_quotient

TIE_GUARANTEE = 2**21  # see above: below this the runtime rule equals the exact one on ties


def exact(value: float | str | Decimal | Fraction) -> Fraction:
    """The decimal the value denotes: floats by their shortest repr (0.1 → 1/10)."""
    if isinstance(value, float):
        return Fraction(Decimal(repr(value)))
    if isinstance(value, (str, Decimal)):
        return Fraction(Decimal(value))
    return Fraction(value)


def round_half_away(q: Fraction) -> int:
    """Round to the nearest integer, ties away from zero."""
    n = math.floor(abs(q) + Fraction(1, 2))
    return n if q >= 0 else -n


def to_raw_exact(physical: float | str | Decimal | Fraction, factor: Fraction, offset: Fraction) -> int:
    return round_half_away((exact(physical) - offset) / factor)


def to_raw_runtime(physical: float, factor: float, offset: float) -> int:
    """The generated code's rule, step for step (see model.TIE_EPSILON, model.EXACT_LIMIT)."""
    return round_runtime(runtime_quotient(physical, factor, offset))


def round_runtime(q: float) -> int:
    """The runtime rule's rounding of the double quotient q: half away from zero, TIE_EPSILON
    included, below EXACT_LIMIT; q itself (an integer double) from there on."""
    a = abs(q)
    r = int(a) if a >= EXACT_LIMIT else math.floor((a + 0.5) + TIE_EPSILON)
    return -r if q < 0 else r


def to_physical_runtime(raw: int, factor: float, offset: float) -> float:
    """The generated decoders' rule, step for step: the raw value as a double, times factor, plus
    offset, each step rounded to a double (C, Python and Rust alike)."""
    return float(raw) * factor + offset


def covering_decimal(x: float, up: bool) -> Fraction:
    """The shortest decimal that reads back as the double x and lies at or above x's exact value
    (at or below where not `up`): a bound a literal can state, which keeps x inside in exact
    arithmetic (the reference codec) and in doubles (every target) alike."""
    exact_x = Fraction(x)
    for digits in range(17):
        d = Decimal(f"{x:.{digits}e}")
        step = Decimal(f"1e{d.adjusted() - digits}")
        for c in (d, d + step if up else d - step):
            if float(c) == x and (Fraction(c) >= exact_x if up else Fraction(c) <= exact_x):
                return Fraction(c)
    return exact_x


def fits_runtime(q: float, type_min: int, type_max: int) -> bool:
    """The runtime rule's field check: the double quotient q rounds (round_runtime) to a raw value
    the field's type holds. Every language rounds first and compares the raw value, so the decoded
    double of a raw at the type's end encodes back however far a double's step puts its quotient
    beyond the end (0x7FFFFFFF × 0.1 of a 32-bit field: q = 2147483647.0000002), while a value
    rounding one step beyond the field is refused. NaN and ±Inf fail."""
    if math.isnan(q) or math.isinf(q):
        return False
    return type_min <= round_runtime(q) <= type_max


def raw_range(length: int, signed: bool, factor: Fraction, offset: Fraction, documented: tuple[Fraction, Fraction] | None) -> tuple[int, int]:
    """The raw values a physical encode may produce: those of the field whose physical value lies
    in the documented range (exactly), or every value of the field without one. Empty (min > max)
    when none does — `canspec check` refuses that spec (rule range-empty)."""
    tmin, tmax = raw_type_range(length, signed)
    if documented is None:
        return tmin, tmax
    qa, qb = sorted(((documented[0] - offset) / factor, (documented[1] - offset) / factor))
    return max(tmin, math.ceil(qa)), min(tmax, math.floor(qb))


def raw_type_range(length: int, signed: bool) -> tuple[int, int]:
    """What the bits of a field can carry."""
    if signed:
        return -(1 << (length - 1)), (1 << (length - 1)) - 1
    return 0, (1 << length) - 1


def decimals(value: Fraction) -> int:
    """Decimal places of a value with a finite decimal expansion: max(a, b) for its denominator
    2^a 5^b (0.05 → 2, 2^-20 → 20)."""
    den, places = value.denominator, 0
    for p in (2, 5):
        n = 0
        while den % p == 0:
            den //= p
            n += 1
        places = max(places, n)
    if den != 1:
        raise ValueError(f"{value} is not a decimal number")
    return places


def decimal_scaling(factor: Fraction, offset: Fraction, bounds: tuple[Fraction, Fraction], half_steps: bool) -> tuple[int, int, int]:
    """An integer-only encode's units: (10^k, factor × 10^k, offset × 10^k) for the smallest 10^k
    that makes every physical value, both range bounds and (`half_steps`, a scaled signal's ties)
    every half step an integer."""
    parts = [factor, offset, *bounds] + ([factor / 2] if half_steps else [])
    scale = 10 ** max(decimals(v) for v in parts)
    return scale, int(factor * scale), int(offset * scale)


@lru_cache(maxsize=1 << 16)  # a spec repeats its factors, offsets and ranges: every literal of them comes here
def decimal_text(value: Fraction | int) -> str:
    """Shortest exact decimal text of a value with a finite decimal expansion (0.02, -1080, 1e-3 → 0.001)."""
    value = Fraction(value)
    if value.denominator == 1:
        return str(value.numerator)
    # Every factor/offset in a spec comes from decimal text, so this terminates; with denominator
    # 2^a·5^b it has at most digits(numerator) + max(a, b) significant digits: give the quotient room
    # for them (the default 28 digits round a 64-bit field's range under a fine factor).
    with localcontext() as ctx:
        ctx.prec = len(str(abs(value.numerator))) + value.denominator.bit_length()
        text = format((Decimal(value.numerator) / Decimal(value.denominator)).normalize(), "f")
    if Fraction(Decimal(text)) != value:
        raise ValueError(f"{value} has no finite decimal expansion")
    return text


# --- IEEE 754 fields ------------------------------------------------------------------------

FLOAT_FORMATS = {32: "f", 64: "d"}  # struct codes of binary32 / binary64
FLOAT_INF_BITS = {32: 0x7F800000, 64: 0x7FF0000000000000}  # +Inf; also the exponent field's mask
FLOAT_NAN_BITS = {32: 0x7FC00000, 64: 0x7FF8000000000000}  # the canonical quiet NaN every encoder writes
FLOAT_MAX = {32: Fraction(struct.unpack("<f", b"\xff\xff\x7f\x7f")[0]), 64: Fraction(sys.float_info.max)}


def float_of_bits(bits: int, length: int) -> float:
    """The float a field's bit pattern holds (NaN payloads, ±Inf and -0 as they are)."""
    return float(struct.unpack(f"<{FLOAT_FORMATS[length]}", bits.to_bytes(length // 8, "little"))[0])


def bits_of_float(value: float, length: int) -> int:
    """The bit pattern of a double stored in a field, rounded to nearest for binary32. A finite value
    beyond the format's largest (which would round to infinity, and is undefined behaviour in C) is
    the caller's to refuse; NaN becomes the format's quiet NaN with its sign."""
    if length == 32 and math.isfinite(value) and abs(Fraction(value)) > FLOAT_MAX[32]:
        raise OverflowError(f"{value!r} is beyond the largest float32")
    return int.from_bytes(struct.pack(f"<{FLOAT_FORMATS[length]}", value), "little")


def _ordered(bits: int, length: int) -> int:
    """A finite float's bit pattern as an integer that rises with its value (-0 and +0 both 0)."""
    sign = 1 << (length - 1)
    return -(bits & (sign - 1)) if bits & sign else bits


def _unordered(n: int, length: int) -> int:
    return (1 << (length - 1)) | -n if n < 0 else n


def float_inside(x: Fraction, length: int, up: bool) -> int:
    """The bit pattern of the format's float nearest to x at or above it (`up`) or at or below it:
    a range end a field can hold that keeps its value inside the range (0.1 has no float32; the
    float32 just above it lies inside [0.1, 1]). x is clipped to the format's finite range."""
    x = max(-FLOAT_MAX[length], min(FLOAT_MAX[length], x))
    n, step = _ordered(bits_of_float(float(x), length), length), 1 if up else -1
    while (Fraction(float_of_bits(_unordered(n, length), length)) - x) * step < 0:  # the double (and binary32) roundings may land outside
        n += step
    return _unordered(n, length)
