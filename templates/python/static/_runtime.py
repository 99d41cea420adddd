"""The slow paths of encode: the full physical → raw rule with its errors. The generated
per-message code handles in-range values inline and calls these only otherwise."""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping
from enum import IntEnum
from typing import NamedTuple, TypeVar

from ._rules import EXACT_LIMIT, TIE_EPSILON
from .errors import RangeError, RawRangeError

E = TypeVar("E")
T = TypeVar("T")
M = TypeVar("M", bound=IntEnum)


class SignalSpec(NamedTuple):
    """What the full rule needs to know about one signal."""

    message: str
    signal: str
    direct: bool  # factor 1, integer offset: integers convert exactly
    factor: float
    offset: float
    offset_int: int
    lo: float  # the documented physical range (nearest doubles)
    hi: float
    raw_min: int
    raw_max: int
    raw_type_min: int
    raw_type_max: int
    specials: frozenset[int]
    allowed: str
    float_bits: int = 0  # 32 or 64: an IEEE 754 field (raw = the bit pattern, lo/hi its range as doubles)
    nonfinite: bool = False  # a float field without a documented range: NaN and ±Inf encode too


_FLOATS = {32: struct.Struct("<f"), 64: struct.Struct("<d")}
unpack_f32, pack_f32 = _FLOATS[32].unpack, _FLOATS[32].pack
unpack_f64, pack_f64 = _FLOATS[64].unpack, _FLOATS[64].pack
# A float filling whole bytes, read straight from the frame: (data, first byte) → (value,)
unpack_f32_le, unpack_f32_be = struct.Struct("<f").unpack_from, struct.Struct(">f").unpack_from
unpack_f64_le, unpack_f64_be = struct.Struct("<d").unpack_from, struct.Struct(">d").unpack_from


def float_to_raw(value: object, s: SignalSpec) -> int:
    """A float field's bit pattern (float32 rounded to nearest), or RangeError / TypeError: a finite
    value must lie in [lo, hi] (beyond the largest float32 is out of range), NaN and ±Inf only
    where no range is documented."""
    if isinstance(value, float):
        x = value
    elif isinstance(value, int):
        try:
            x = float(value)
        except OverflowError:
            raise RangeError(s.message, s.signal, value, s.allowed) from None
    else:
        raise TypeError(f"{s.message}.{s.signal}: expected a number, got {type(value).__name__} {value!r}")
    if s.lo <= x <= s.hi if math.isfinite(x) else s.nonfinite:
        return int.from_bytes(_FLOATS[s.float_bits].pack(x), "little")
    raise RangeError(s.message, s.signal, value, s.allowed)


def physical_to_raw(value: object, s: SignalSpec) -> int:
    """The raw value a physical value encodes to, or RangeError / TypeError."""
    if s.float_bits:
        return float_to_raw(value, s)
    if isinstance(value, int):
        if s.direct:
            raw = int(value) - s.offset_int
            if raw in s.specials or (s.raw_min <= raw <= s.raw_max and s.lo <= value <= s.hi):
                return raw
            raise RangeError(s.message, s.signal, value, s.allowed)
        try:
            x = float(value)
        except OverflowError:
            raise RangeError(s.message, s.signal, value, s.allowed) from None
    elif isinstance(value, float):
        x = value
    else:
        raise TypeError(f"{s.message}.{s.signal}: expected a number, got {type(value).__name__} {value!r}")
    q = (x - s.offset) / s.factor
    if not math.isfinite(q):  # the raw checks below refuse every other value that does not fit
        raise RangeError(s.message, s.signal, value, s.allowed)
    a = abs(q)
    r = int(a) if a >= EXACT_LIMIT else math.floor((a + 0.5) + TIE_EPSILON)
    raw = -r if q < 0 else r
    # a double against the bounds as doubles, as C and the reference rule compare (an integer
    # bound beyond 2^53 is not exact in a double: its nearest double is the bound)
    if raw in s.specials or (float(s.lo) <= x <= float(s.hi) and s.raw_min <= raw <= s.raw_max):
        return raw
    raise RangeError(s.message, s.signal, value, s.allowed, (raw, s.raw_min, s.raw_max) if float(s.lo) <= x <= float(s.hi) else None)


def check_raw(value: object, s: SignalSpec) -> int:
    """A raw value that fits the field, as a plain int, or RawRangeError."""
    if isinstance(value, int) and not isinstance(value, bool) and s.raw_type_min <= value <= s.raw_type_max:
        return int(value)
    raise RawRangeError(s.message, s.signal, value, s.raw_type_min, s.raw_type_max)


def member(table: Mapping[int, E], raw: int) -> E | int:
    """The enum member for a raw value, or the raw value when the table has none."""
    return table.get(raw, raw)


def lookup(enum: type[M], bits: int) -> tuple[M | int, ...]:
    """Every raw value of a `bits`-wide field → its enum member, or the raw value when there is none."""
    members = {member.value: member for member in enum}
    return tuple(members.get(raw, raw) for raw in range(1 << bits))


def update(message: T, decoded: T, attrs: tuple[str, ...]) -> T:
    """`message` with the attributes `decoded` holds copied in; None (a page the frame does not hold) is skipped."""
    for name in attrs:
        value = getattr(decoded, name)
        if value is not None:
            setattr(message, name, value)
    return message
