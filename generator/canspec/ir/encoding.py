"""Physical ↔ raw conversion rules every generated language shares.

`to_raw_exact` is the reference: exact rational arithmetic on the decimal the user meant.
`to_raw_runtime` is the same rule as the generated code computes it in IEEE doubles; tests
prove the two agree on every decimal value and tie of every signal in the spec.
"""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction

from canspec.ir import TIE_EPSILON


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
    """The generated code's rule, step for step (see ir.TIE_EPSILON)."""
    q = (physical - offset) / factor
    if q >= 0:
        return math.floor((q + 0.5) + TIE_EPSILON)
    return -math.floor((-q + 0.5) + TIE_EPSILON)


def to_physical(raw: int, factor: Fraction, offset: Fraction) -> Fraction:
    return raw * factor + offset


def decimal_text(value: Fraction | int) -> str:
    """Shortest exact decimal text of a value with a finite decimal expansion (0.02, -1080, 1e-3 → 0.001)."""
    value = Fraction(value)
    if value.denominator == 1:
        return str(value.numerator)
    # Every factor/offset in a spec comes from decimal text, so this terminates.
    d = Decimal(value.numerator) / Decimal(value.denominator)
    text = format(d.normalize(), "f")
    if Fraction(Decimal(text)) != value:
        raise ValueError(f"{value} has no finite decimal expansion")
    return text


def json_number(value: Fraction) -> int | float:
    """A vector/JSON number: int when integral, else the nearest double."""
    return value.numerator if value.denominator == 1 else float(value)
