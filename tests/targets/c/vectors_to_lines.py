"""Convert a vectors file in the shared JSON format into the line format the C runner reads
(C has no JSON parser in the standard library; this keeps the runner free of vendored code).

    C <frame_id> <kind> <hex data, `-` when empty> <message>
    R <signal> <raw int>
    P <signal> <physical, as written in the JSON> [<double> [<fixed> <agrees> <fixed in> <fixed raw>]]
    E
    V <frame_id> <text as hex> <frame count> <hex frame>...

A data signal's physical value carries, from the spec's IR, what every encode and decode of
it must give, so that the runner (which must build for 32-bit cores too) compares integers of
at most 64 bits and does no wide arithmetic:
- <double>: the raw value the shared rounding rule gives for that double (ir/encoding.py's
  Python reference, with the range rules every encode applies), `-` where the rule refuses it;
- where the C headers have the fixed-point path (physical × 10^k in integers):
  <fixed> = raw × factor × 10^k + offset × 10^k exactly, what decode_fixed(raw) gives;
  <agrees> = 1 if the physical text is that value (checked where a double holds it to the
  digit), else 0; <fixed in> <fixed raw> = an encode_fixed input and the raw value it must
  give, `- -` when there is no fixed encode check.
"""

from __future__ import annotations

import json
import sys
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "generator"))

from canspec import ir
from canspec.ir.encoding import to_raw_runtime
from canspec.pipeline import compile_spec
from canspec.reference.codec import CodecError, float_raw
from canspec.targets.c.names import CNames
from canspec.targets.c.physical import fixed_path

# Kinds whose physical values a physical encode must refuse (raw_only) or that do not survive
# doubles (beyond_double) or the encode (nan_payload: a NaN encodes to the canonical one): decode and raw pack only.
NOT_ENCODABLE = ("raw_only", "beyond_double", "nan_payload")
# A float field's physical value that is no JSON number (the vectors' format), as C's strtod reads it.
FLOAT_WORDS = {"NaN": "NaN", "Infinity": "Infinity", "-Infinity": "-Infinity"}
# The vectors write the shortest text of the nearest double: it is the exact value only up to
# this many significant digits.
DOUBLE_DIGITS = 15


def number_text(value: object) -> str:
    if isinstance(value, str) and value in FLOAT_WORDS:
        return FLOAT_WORDS[value]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"not a number: {value!r}")
    return repr(value)


def int64_text(value: int) -> str:
    """An integer the runner reads into 64 bits (two's complement, or unsigned up to 2^64 - 1)."""
    if not -(2**63) <= value < 2**64:
        raise ValueError(f"{value} does not fit 64 bits")
    return str(value)


def double_rule(sig: ir.Signal, x: float) -> int | None:
    """The raw value a double encode of `x` gives under the shared rules, or None if it refuses (a
    float field: the reference codec's bit pattern)."""
    if sig.is_float:
        try:
            return float_raw(sig, x)
        except CodecError:
            return None
    q = (x - float(sig.offset)) / float(sig.factor)
    if not sig.raw_type_min - 1 < q < sig.raw_type_max + 1:  # exact comparisons (float with int); NaN fails
        return None
    r = to_raw_runtime(x, float(sig.factor), float(sig.offset))
    if any(r == sp.raw for sp in sig.specials):
        return r
    if not float(sig.accept_min) <= x <= float(sig.accept_max) or not sig.raw_min <= r <= sig.raw_max:
        return None
    return r


def div_round(num: int, den: int) -> int:
    """num / den rounded half away from zero, exactly: the fixed encode's rounding."""
    r = (2 * abs(num) + abs(den)) // (2 * abs(den))
    return r if (num < 0) == (den < 0) else -r


def significant_digits(value: int) -> int:
    return len(str(abs(value)).rstrip("0"))


def fixed_encode(kind: str, raw: int, scaled: Fraction, ff: int, fo: int) -> str:
    """The fixed encode check: its input and the raw value it must give. The exact scaled
    physical value of the case's raw value, or a tie as written with its exact rounding when the
    text is exactly halfway between two steps (a tie of a wide field may be written as a nearby
    double, which is not one). `- -`: no check."""
    if kind in NOT_ENCODABLE:
        return "- -"
    if kind != "tie":
        return f"{int64_text(raw * ff + fo)} {int64_text(raw)}"
    if scaled.denominator != 1 or (2 * (int(scaled) - fo)) % (2 * abs(ff)) != abs(ff):
        return "- -"
    return f"{int64_text(int(scaled))} {int64_text(div_round(int(scaled) - fo, ff))}"


def fixed_fields(sig: ir.Signal, scale: int, kind: str, raw: int, text: str) -> str:
    """<fixed> <agrees> <fixed in> <fixed raw> of one physical value (see the module docstring)."""
    ff, fo = int(sig.factor * scale), int(sig.offset * scale)
    want, scaled = raw * ff + fo, Fraction(text) * scale
    # a tie or a decoded double is, by design, not the exact value: nothing to compare
    agrees = kind in ("tie", "decoded") or significant_digits(want) > DOUBLE_DIGITS or scaled == want
    return f"{int64_text(want)} {int(agrees)} {fixed_encode(kind, raw, scaled, ff, fo)}"


def physical_line(data: dict[str, tuple[ir.Signal, int | None]], case: dict, name: str) -> str:  # type: ignore[type-arg]
    text = number_text(case["physical"][name])
    line = f"P {name} {text}"
    if name not in data:  # a counter or checksum: its physical value is its raw value
        return line
    sig, scale = data[name]
    # a decoded case's value is what a decoder returns for its raw value: it must encode back to it
    r = int(case["raw"][name]) if case.get("kind") == "decoded" else double_rule(sig, float(text))
    line += f" {'-' if r is None else int64_text(r)}"
    if scale is None:
        return line
    return f"{line} {fixed_fields(sig, scale, case.get('kind', 'random'), int(case['raw'][name]), text)}"


def data_signals(can: ir.CanProtocol) -> dict[str, dict[str, tuple[ir.Signal, int | None]]]:
    """Per message, its data signals with the scale of their C fixed-point path (None: no such path)."""
    names = CNames.of(can)
    out: dict[str, dict[str, tuple[ir.Signal, int | None]]] = {}
    for msg in can.messages:
        paths = {s.name: (s, None if s.is_float else fixed_path(names, s)) for s in msg.signals if s.role == "data"}
        out[msg.name] = {n: (s, None if f is None else f.scale) for n, (s, f) in paths.items()}
    return out


def convert(doc: dict, can: ir.CanProtocol) -> str:  # type: ignore[type-arg]
    signals = data_signals(can)
    out = []
    for case in doc.get("cases", []):
        out.append(f"C {int(case['frame_id'])} {case.get('kind', 'random')} {case['data'] or '-'} {case['message']}")
        for name, value in sorted(case.get("raw", {}).items()):
            out.append(f"R {name} {int(value)}")
        for name in sorted(case.get("physical", {})):
            out.append(physical_line(signals[case["message"]], case, name))
        out.append("E")
    for mf in doc.get("multiframe", []):
        out.append(f"V {int(mf['frame_id'])} {mf['text'].encode('ascii').hex() or '-'} {len(mf['frames'])} {' '.join(mf['frames'])}")
    return "\n".join(out) + "\n"


def main(argv: list[str]) -> int:
    if len(argv) != 4:
        print("usage: vectors_to_lines.py SPEC VECTORS.json OUT.txt", file=sys.stderr)
        return 2
    try:
        spec = compile_spec(argv[1]).spec
        if spec is None or spec.can is None:
            raise ValueError(f"{argv[1]}: no CAN protocol (canspec check tells why)")
        with open(argv[2], encoding="utf-8") as fh:
            doc = json.load(fh)
        text = convert(doc, spec.can)
    except (OSError, ValueError, KeyError, TypeError) as exc:
        print(f"vectors_to_lines: {argv[2]}: {exc}", file=sys.stderr)
        return 1
    with open(argv[3], "w", encoding="ascii") as fh:
        fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
