"""The vector cases of IEEE 754 fields (`float: true`) and their values in JSON.

A float field's raw value is its bit pattern and its physical value the float those bits hold,
written as a JSON number (-0 as -0.0) or, where JSON has none, as "NaN", "Infinity", "-Infinity".
Cases: the range ends (the format's largest finite values without a range), +0 and -0, the
smallest subnormals, the quiet NaN, NaNs with other payloads, ±Inf, and random finite values (a
float32's are float32 values, so the double in the file is exact). A case is physical-encodable
when the physical value, read back from the file, encodes to its raw value under the shared rule
(reference/codec.float_raw): NaN/±Inf with a documented range are refused (raw_only); a NaN with
another payload encodes to the quiet NaN (nan_payload: decode gives NaN, raw pack gives the data).
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import bits_of_float, float_inside, float_of_bits
from canspec.reference import codec

# A quiet NaN with a payload and the sign set. No signalling NaN: a binary32 one does not survive a
# double (the conversion quiets it), and the oracle (cantools) encodes a float field from a double.
NAN_PAYLOADS = {32: (0xFFC00000 | 0x15A5A5,), 64: (0xFFF8000000000000 | 0x123456789AB,)}


def json_value(x: float) -> float | str:
    """A float as the vectors hold it: a number, or the name of a value JSON has no number for."""
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "Infinity" if x > 0 else "-Infinity"
    return x


def read_value(v: float | str) -> float:
    """A physical value as a runner reads it back from the file."""
    return float(v)  # float("NaN"), float("Infinity"), float("-Infinity") and numbers alike


def encodes_to(sig: ir.Signal, raw: int) -> str | None:
    """None when the field's physical value (as the file holds it) encodes back to `raw`; else the
    kind of case it makes: raw_only (the encode refuses it) or nan_payload (it encodes to the quiet NaN)."""
    x = read_value(json_value(float_of_bits(raw, sig.length)))
    try:
        back = codec.float_raw(sig, x)
    except codec.CodecError:
        return "raw_only"
    return None if back == raw else "nan_payload"


def edge_cases(sig: ir.Signal) -> list[tuple[int, str, str]]:
    """(raw, kind, note) for the field's range ends and the format's special values."""
    n = sig.length
    sign = 1 << (n - 1)
    out = [
        (float_inside(sig.check_min, n, up=True), "min", f"{sig.name} lowest"),
        (float_inside(sig.check_max, n, up=False), "max", f"{sig.name} highest"),
    ]
    specials = {
        "+0": 0, "-0": sign, "smallest subnormal": 1, "-smallest subnormal": sign | 1, "NaN": bits_of_float(math.nan, n),
        "+Inf": bits_of_float(math.inf, n), "-Inf": bits_of_float(-math.inf, n),
    }
    out += [(raw, "float_special", f"{sig.name}={what}") for what, raw in specials.items()]
    out += [(raw, "nan_payload", f"{sig.name}=NaN payload 0x{raw:X}") for raw in NAN_PAYLOADS[n]]
    return out


def random_raw(sig: ir.Signal, rng: random.Random) -> int:
    """A random finite value of the field: any bit pattern of a finite float without a range (every
    magnitude), else a value spread evenly over the range, rounded into it."""
    n = sig.length
    if sig.doc_min is None and rng.random() < 0.5:
        while True:
            raw = rng.getrandbits(n)
            if math.isfinite(float_of_bits(raw, n)):
                return raw
    lo, hi = float(sig.check_min), float(sig.check_max)
    x = Fraction(lo + (hi - lo) * rng.random() if math.isfinite(hi - lo) else rng.uniform(lo / 2, hi / 2) * 2)
    raw = float_inside(x, n, up=True)
    return raw if Fraction(float_of_bits(raw, n)) <= sig.check_max else float_inside(x, n, up=False)
