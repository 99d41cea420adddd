"""The rules on a signal's numbers: a documented range the field can encode, and physical values
that stay within a double (validate.py runs them in its order of rules)."""

from __future__ import annotations

from collections.abc import Iterator
from decimal import Decimal
from fractions import Fraction

from canspec.ir.encoding import FLOAT_MAX, raw_range, raw_type_range
from canspec.ir.model import to_physical
from canspec.spec.finite import finite
from canspec.spec.problems import Problem, error, warning
from canspec.spec.resolve import ResolvedCan


def range_rules(can: ResolvedCan) -> Iterator[Problem]:
    yield from _ranges(can)
    yield from _physical_doubles(can)


def _ranges(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        for sig in msg["signals"]:
            rng = sig.get("range")
            if rng is None or not 1 <= sig["len"] <= 64 or not finite(sig["factor"]) or sig["factor"] == 0 or not finite(sig["offset"]):
                continue
            if not all(finite(v) for v in rng):
                yield error(f"signal {sig['name']!r}: range must be finite numbers within the range of a double", sig.loc_of("range"), None, "nonfinite")
                continue
            lo, hi = Fraction(rng[0]), Fraction(rng[1])
            if lo > hi:
                yield error(
                    f"signal {sig['name']!r}: range [{rng[0]}, {rng[1]}] has min > max", sig.loc_of("range"), "write the range as [min, max]", "range-order"
                )
                continue
            if sig["float"]:
                if sig["len"] in FLOAT_MAX and max(abs(lo), abs(hi)) > FLOAT_MAX[sig["len"]]:
                    yield error(f"signal {sig['name']!r}: range [{rng[0]}, {rng[1]}] exceeds the largest float{sig['len']}", sig.loc_of("range"),
                                "give a range within the float's finite values, or none (then NaN and ±Inf pass too)", "range-empty")
                continue
            tmin, tmax = raw_type_range(sig["len"], sig["signed"])
            factor, offset = Fraction(sig["factor"]), Fraction(sig["offset"])
            ends = sorted([to_physical(tmin, factor, offset), to_physical(tmax, factor, offset)])
            if hi < ends[0] or lo > ends[1] or _no_raw_in(lo, hi, factor, offset, sig["len"], sig["signed"]):
                yield error(
                    f"signal {sig['name']!r}: no value of the {sig['len']}-bit field lies in the documented range [{rng[0]}, {rng[1]}] "
                    f"(it encodes [{_num(ends[0])}, {_num(ends[1])}] in steps of {sig['factor']})",
                    sig.loc_of("range"), "check offset, factor, length and range against the document", "range-empty")
            elif lo < ends[0] or hi > ends[1]:
                yield warning(
                    f"signal {sig['name']!r}: documented range [{rng[0]}, {rng[1]}] exceeds what {sig['len']} bits × {sig['factor']} + {sig['offset']} "
                    f"can encode [{_num(ends[0])}, {_num(ends[1])}]",
                    sig.loc_of("range"), "encoders accept only the encodable part; record the erratum if the document is wrong", "range-unreachable")


def _physical_doubles(can: ResolvedCan) -> Iterator[Problem]:
    """Every physical value a field may carry is a double: each target computes them in doubles."""
    for msg in can.messages:
        for sig in msg["signals"]:
            if not 1 <= sig["len"] <= 64 or not finite(sig["factor"]) or sig["factor"] == 0 or not finite(sig["offset"]) or sig["float"]:
                continue
            factor, offset = Fraction(sig["factor"]), Fraction(sig["offset"])
            rng = sig.get("range")
            documented = (Fraction(rng[0]), Fraction(rng[1])) if rng is not None and all(finite(v) for v in rng) else None
            raw_min, raw_max = raw_range(sig["len"], sig["signed"], factor, offset, documented)
            for raw, where in ((raw_min, "factor"), (raw_max, "factor"), *((r, "special") for r in sig.get("special", {}))):
                physical = to_physical(raw, factor, offset)
                if raw_min <= raw_max and not finite(physical):
                    about = format(Decimal(physical.numerator) / Decimal(physical.denominator), ".4g")
                    yield error(f"signal {sig['name']!r}: raw {raw} is the physical value {about}, beyond the range of a double",
                                sig.loc_of(where), "give the signal a documented `range`, or a smaller factor or offset", "physical-range")
                    break


def _no_raw_in(lo: Fraction, hi: Fraction, factor: Fraction, offset: Fraction, length: int, signed: bool) -> bool:
    """True when no raw value of the field maps into [lo, hi] (the IR's raw range would be empty)."""
    raw_min, raw_max = raw_range(length, signed, factor, offset, (lo, hi))
    return raw_min > raw_max


def _num(f: Fraction) -> str:
    return str(f.numerator) if f.denominator == 1 else str(float(f))
