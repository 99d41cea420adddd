"""How a physical value becomes a raw value in the generated crate: the field's kind (its
physical type) and, for scaled fields, which `codec` function encodes it and the constants it
reads. Every path computes the shared rule (ir/encoding.py `to_raw_runtime`) step for step;
the shortcuts are taken only where this module proves they give its result.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import fits_runtime, to_raw_runtime
from canspec.render.literals import RUST

# Integer factors below this give the same raw value in exact integer arithmetic as the
# double rule (a non-tie quotient is at least 1/(2·factor) > TIE_EPSILON away from a tie).
MAX_INT_FACTOR = 500_000_000
# Quotients below this take the reciprocal path (its error budget: static/src/codec.rs).
RECIPROCAL_LIMIT = 2.0**17
ROUNDS_TO_ZERO = -0.25  # quotients above round to 0 or more, by either branch of the rule


def is_wide_unsigned(sig: ir.Signal) -> bool:
    """A 64-bit unsigned field: its raw values reach beyond `i64` (codec::ScaleU64)."""
    return not sig.signed and sig.length == 64


def scaled_int_type(sig: ir.Signal) -> str | None:
    """The integer type of a scaled signal whose physical values are all integers (integer
    factor and offset), holding every physical value and `raw × factor`; None if there is none."""
    if not sig.is_integer or sig.is_identity or not 0 < sig.factor < MAX_INT_FACTOR or sig.storage_bits > 32:
        return None
    # the physical values and the products raw × factor before the offset is added
    ends = [ir.to_physical(raw, sig.factor, offset) for raw in (sig.raw_type_min, sig.raw_type_max) for offset in (sig.offset, Fraction(0))]
    lo, hi = min(ends), max(ends)
    for bits in (8, 16, 32):
        if lo >= 0 and hi < 1 << bits:
            return f"u{bits}"
        if -(1 << (bits - 1)) <= lo and hi < 1 << (bits - 1):
            return f"i{bits}"
    return None


def kind_of(sig: ir.Signal) -> str:
    """"enum" (a value table), "int" (the raw value is the physical one), "scaled_int" (integer
    physical values in an integer type), "float" (scaled, in doubles) or "ieee" (an IEEE 754 field)."""
    if sig.is_float:
        return "ieee"
    if sig.decodes_to_enum:
        return "enum"
    if sig.is_identity:
        return "int"
    return "scaled_int" if scaled_int_type(sig) is not None else "float"


def has_range_consts(sig: ir.Signal) -> bool:
    """Scaled fields carry `_MIN`, `_MAX` and `_SCALE` constants (IEEE fields `_MIN` and `_MAX`)."""
    return kind_of(sig) in ("scaled_int", "float", "ieee")


def _double_key(x: float) -> int:
    """Doubles in order as integers (-0.0 and 0.0 share a key)."""
    bits = int(struct.unpack("<q", struct.pack("<d", x))[0])
    return bits if bits >= 0 else -(bits & 0x7FFF_FFFF_FFFF_FFFF)


def _double_of_key(key: int) -> float:
    bits = key if key >= 0 else (-key) | -0x8000_0000_0000_0000
    return float(struct.unpack("<d", struct.pack("<q", bits))[0])


def _first_true(pred: Callable[[float], bool], lo: float, hi: float) -> float | None:
    """The smallest double in [lo, hi] where the monotone (false…true) `pred` holds."""
    if pred(lo):
        return lo
    if not pred(hi):
        return None
    a, b = _double_key(lo), _double_key(hi)  # pred(a) false, pred(b) true
    while b - a > 1:
        mid = (a + b) // 2
        if pred(_double_of_key(mid)):
            b = mid
        else:
            a = mid
    return _double_of_key(b)


@dataclass(frozen=True)
class Shortcut:
    """Whether one range check on the physical value can replace the other checks of the
    shared rule, and what that check compares against."""

    suffices: bool
    q_min: float = 0.0  # the quotients the range gives
    q_max: float = 0.0
    pass_min: float | None = None  # float signals: the doubles every check passes
    pass_max: float | None = None


def documented_range_suffices(sig: ir.Signal, integer_path: bool) -> Shortcut:
    """Whether, for this signal, one range check [lo, hi] on the physical value can replace
    the other checks of the shared rule (q inside the field's raw range, raw inside [raw_min,
    raw_max]). Proof by monotonicity: q = (x - offset) / factor and the rounding are
    non-decreasing in x in IEEE arithmetic (factor > 0), and Python floats are the same doubles
    the generated code uses, so the doubles that pass form an interval, found exactly by
    bisection over the doubles. `integer_path`: the integer encode (whole physical values),
    whose range ends are the whole numbers inside the documented range. (Special values are
    checked by the full rule, which callers fall back to outside that range.)"""
    if sig.factor <= 0:
        return Shortcut(False)
    f, o = float(sig.factor), float(sig.offset)
    if integer_path:
        lo, hi = float(math.ceil(sig.check_min)), float(math.floor(sig.check_max))
        q_lo, q_hi = sig.runtime_quotient(lo), sig.runtime_quotient(hi)
        fits = fits_runtime(q_lo, sig.raw_type_min, sig.raw_type_max) and fits_runtime(q_hi, sig.raw_type_min, sig.raw_type_max)
        if not (fits and sig.raw_min <= to_raw_runtime(lo, f, o) and to_raw_runtime(hi, f, o) <= sig.raw_max):
            return Shortcut(False)
        return Shortcut(True, q_lo, q_hi)

    def high_enough(x: float) -> bool:
        return fits_runtime(sig.runtime_quotient(x), sig.raw_type_min, 1 << 64) and to_raw_runtime(x, f, o) >= sig.raw_min

    def low_enough(x: float) -> bool:
        return fits_runtime(sig.runtime_quotient(x), -(1 << 64), sig.raw_type_max) and to_raw_runtime(x, f, o) <= sig.raw_max

    lo, hi = float(sig.accept_min), float(sig.accept_max)
    first = _first_true(high_enough, lo, hi)
    last = _first_true(lambda x: not low_enough(x), lo, hi)
    if last is not None:
        last = _double_of_key(_double_key(last) - 1) if last > lo else None
    else:
        last = hi
    if first is None or last is None or first > last:
        return Shortcut(False)
    return Shortcut(True, sig.runtime_quotient(first), sig.runtime_quotient(last), first, last)


def _power_of_two(value: Fraction) -> bool:
    n, d = value.numerator, value.denominator
    return n > 0 and n & (n - 1) == 0 and d & (d - 1) == 0


@dataclass(frozen=True)
class Encoding:
    """The encode of one scaled field: `codec::{function}(value, &SCALE{, extra})`."""

    function: str
    scale_type: str  # "Scale" | "IntScale" | "ScaleU64"
    scale: dict[str, str]  # the scale's literals, by field
    extra: str  # further arguments after the scale: the specials slice or the reciprocal ("" for none)
    returns: str  # the raw type the function returns


def int_encoding(sig: ir.Signal) -> Encoding:
    short = documented_range_suffices(sig, integer_path=True)
    lo, hi = math.ceil(sig.check_min), math.floor(sig.check_max)
    scale = {"factor": RUST.integer(int(sig.factor)), "offset": RUST.integer(int(sig.offset)), "check_min": RUST.integer(lo), "check_max": RUST.integer(hi),
             **_raw_bounds(sig)}
    if not short.suffices:
        return Encoding("to_raw_int", "IntScale", scale, _specials(sig), "i64")
    if sig.specials:
        return Encoding("to_raw_int_documented_or_special", "IntScale", scale, _specials(sig), "i64")
    return Encoding("to_raw_int_documented", "IntScale", scale, "", "i64")


def float_encoding(sig: ir.Signal) -> Encoding:
    scale = {"factor": RUST.double(sig.factor), "offset": RUST.double(sig.offset)}
    scale.update(check_min=RUST.double(sig.accept_min), check_max=RUST.double(sig.accept_max))
    if is_wide_unsigned(sig):
        return Encoding("to_raw_u64", "ScaleU64", {**scale, "raw_min": RUST.integer(sig.raw_min), "raw_max": RUST.integer(sig.raw_max)}, _specials(sig), "u64")
    scale.update(_raw_bounds(sig))
    short = documented_range_suffices(sig, integer_path=False)
    if not short.suffices:
        return Encoding("to_raw", "Scale", scale, _specials(sig), "i64")
    # The doubles the full rule accepts (without specials): the shortcut's one range check,
    # and for the full rule the same answers (outside it another check fails anyway).
    assert short.pass_min is not None and short.pass_max is not None
    scale["check_min"], scale["check_max"] = RUST.double(short.pass_min), RUST.double(short.pass_max)
    if sig.specials:
        return Encoding("to_raw_documented_or_special", "Scale", scale, _specials(sig), "i64")
    # The unsigned paths compute floor((q + 0.5) + ε): round_half_away(q) for q below 2^52 that
    # is non-negative or rounds to 0 (the accepted range lets q reach −ε below a field's 0).
    if not (ROUNDS_TO_ZERO < short.q_min and short.q_max < ir.EXACT_LIMIT):
        return Encoding("to_raw_documented", "Scale", scale, "", "i64")
    # Quotients below 2^17 and a factor that is not a power of two (whose division the
    # compiler makes a multiplication already): the reciprocal path gives the same result.
    if short.q_max < RECIPROCAL_LIMIT and not _power_of_two(Fraction(sig.factor)):
        return Encoding("to_raw_documented_unsigned_recip", "Scale", scale, RUST.double(sig.reciprocal), "i64")
    return Encoding("to_raw_documented_unsigned", "Scale", scale, "", "i64")


def _raw_bounds(sig: ir.Signal) -> dict[str, str]:
    return {
        "raw_min": RUST.integer(sig.raw_min),
        "raw_max": RUST.integer(sig.raw_max),
        "type_min": RUST.integer(sig.raw_type_min),
        "type_max": RUST.integer(sig.raw_type_max),
    }


def _specials(sig: ir.Signal) -> str:
    return "&[" + ", ".join(RUST.integer(s.raw) for s in sig.specials) + "]"
