"""The C view of an IEEE 754 float field (ir.Signal.is_float): a `float` (binary32) or `double`
(binary64) in the message struct, whose bit pattern pack and unpack move as a uint32_t / uint64_t.

No undefined behaviour and no type punning the standard does not define: the bit pattern is copied
between the integer and the float object with memcpy, through `<prefix>_copy_bits` (its pointers
are `void *`: memcpy's are then of one type, MISRA C:2012 rule 21.15), never through a union or a
pointer cast; every bit pattern is a value of the float type (NaN payloads included). Decode
widens the float to a double (exact). Encode takes a double: a finite value must lie in the
accepted range, rounded inward to doubles here so that the C compare decides exactly as the
reference codec's exact one; float32 narrows it with a cast (rounding to nearest), which is
defined because the range never exceeds the largest float32 (beyond it the conversion is
undefined behaviour, so such a value is a range error). NaN and ±Inf pass only where no range is
documented, written as the format's bit patterns (a NaN as the canonical quiet NaN, as every
canspec language encodes it) without a floating-point conversion. Whether a value is finite is
read from its binary64 bit pattern, not by comparing it with the largest double: static analysers
(cppcheck) take such a compare for one whose outcome is known (MISRA C:2012 rule 14.3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import FLOAT_INF_BITS, FLOAT_MAX, FLOAT_NAN_BITS
from canspec.render.literals import C
from canspec.targets.c.names import CNames

# (C type, bit-pattern type, +Inf, quiet NaN) per field length; -Inf is +Inf with the sign bit
FORMATS = {32: ("float", "uint32_t", FLOAT_INF_BITS[32], FLOAT_NAN_BITS[32]), 64: ("double", "uint64_t", FLOAT_INF_BITS[64], FLOAT_NAN_BITS[64])}


@dataclass(frozen=True)
class CFloat:
    type: str  # float / double: the struct field's type
    bits_type: str  # uint32_t / uint64_t: its bit pattern's
    local: str  # pack's and unpack's local holding the bit pattern
    copy_fn: str  # <prefix>_copy_bits
    narrows: bool  # float32: encode converts the double to float
    check_min: str  # the _MIN / _MAX macros: the documented range, else the format's finite one
    check_max: str
    low: str  # encode's compare bounds: the accepted range as the doubles inside it (a float64 without a
    high: str  # range compares with none: every finite value passes)
    specials: bool  # NaN and ±Inf encode (no documented range)
    inf: str  # the bit patterns NaN and ±Inf encode to
    neg_inf: str
    nan: str
    exponent64: str  # a double's exponent bits (all set: ±Inf or NaN) and fraction bits (then set: NaN)
    fraction64: str


def shortest(value: float) -> str:
    """The shortest C double literal that reads back as `value` (3.4028234663852886e38)."""
    text = repr(value).replace("e+", "e")
    return text if any(ch in text for ch in ".e") else f"{text}.0"


def inward(bound: Fraction, up: bool) -> float:
    """The double nearest `bound` on the range's side of it: the smallest double at or above it
    (`up`, a lower bound) or the largest at or below it (an upper bound)."""
    x = float(bound)
    if up and Fraction(x) < bound:
        return math.nextafter(x, math.inf)
    if not up and Fraction(x) > bound:
        return math.nextafter(x, -math.inf)
    return x


def float_path(names: CNames, sig: ir.Signal, field: str) -> CFloat:
    ctype, bits_type, inf, nan = FORMATS[sig.length]
    bits = sig.length
    largest = FLOAT_MAX[bits]
    low = inward(max(sig.accept_min, -largest), up=True)
    high = inward(min(sig.accept_max, largest), up=False)
    specials = sig.doc_min is None
    return CFloat(
        type=ctype,
        bits_type=bits_type,
        local=f"fb_{field}",
        copy_fn=names.fn("copy_bits"),
        narrows=bits == 32,
        check_min=shortest(float(sig.check_min)),
        check_max=shortest(float(sig.check_max)),
        low=shortest(low),
        high=shortest(high),
        specials=specials,
        inf=C.hex(inf, bits=bits),
        neg_inf=C.hex(inf | 1 << (bits - 1), bits=bits),
        nan=C.hex(nan, bits=bits),
        exponent64=C.hex(FLOAT_INF_BITS[64], bits=64),
        fraction64=C.hex((1 << 52) - 1, bits=64),
    )
