"""IEEE 754 fields in the generated crate: an `f32`/`f64` physical value whose raw value is its bit
pattern (`from_bits`/`to_bits`). The encode rule is the reference codec's (`float_raw`): a finite
value must lie in the accepted range, NaN and ±Inf pass only without a documented range, NaN is
sent as the format's quiet NaN with its sign. The range check compares in the field's own type,
so its bounds are the floats of that type that the exact range holds (`_inner`)."""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir

FORMATS = {32: "f", 64: "d"}
INTEGER = {32: "I", 64: "Q"}
QUIET_NANS = {32: (0x7FC0_0000, 0xFFC0_0000), 64: (0x7FF8_0000_0000_0000, 0xFFF8_0000_0000_0000)}  # what encoding NaN sends


@dataclass(frozen=True)
class IeeeEncoding:
    """`ieee::f{bits}_bits(value, MIN, MAX, ranged)`: the range's float bounds as literals."""

    function: str
    min_lit: str
    max_lit: str
    ranged: str  # "true": a documented range (NaN and ±Inf refused)


def _float(bits: int, length: int) -> float:
    return float(struct.unpack(f"<{FORMATS[length]}", struct.pack(f"<{INTEGER[length]}", bits))[0])


def bits_of(x: float, length: int) -> int:
    return int(struct.unpack(f"<{INTEGER[length]}", struct.pack(f"<{FORMATS[length]}", x))[0])


def _step(x: float, length: int, up: bool) -> float:
    """The next float of the format above (below) the finite `x`."""
    if x == 0:
        return _float(1, length) if up else -_float(1, length)
    bits = bits_of(x, length)
    return _float(bits + 1 if (x > 0) == up else bits - 1, length)


def _inner(bound: Fraction, length: int, up: bool) -> float:
    """The float of the format nearest `bound` on its inner side: the smallest one at least
    `bound` (up) or the largest at most `bound`."""
    x = _float(bits_of(float(bound), length), length) if length == 32 else float(bound)
    while (Fraction(x) < bound) if up else (Fraction(x) > bound):
        x = _step(x, length, up)
    return x


def literal(x: float, length: int) -> str:
    """The shortest decimal that reads back as the float `x` of the format (clippy refuses digits
    beyond the type's precision)."""
    if x == float(ir.encoding.FLOAT_MAX[length]):
        return f"f{length}::MAX"
    if x == -float(ir.encoding.FLOAT_MAX[length]):
        return f"f{length}::MIN"
    if length == 32:  # the double of the shortest decimal that reads back as the float32
        x = next(d for p in range(1, 10) if _float(bits_of(d := float(f"{x:.{p}g}"), 32), 32) == x)
    return repr(x).replace("e+", "e")


def literal_value(sig: ir.Signal, up: bool) -> float:
    """The range's lower (up) or upper bound as a float of the field's format."""
    return _inner(sig.accept_min if up else sig.accept_max, sig.length, up)


def ieee_encoding(sig: ir.Signal) -> IeeeEncoding:
    lo, hi = literal_value(sig, up=True), literal_value(sig, up=False)
    assert math.isfinite(lo) and math.isfinite(hi) and lo <= hi, sig.name
    ranged = sig.doc_min is not None
    return IeeeEncoding(f"f{sig.length}_bits", literal(lo, sig.length), literal(hi, sig.length), "true" if ranged else "false")
