"""Convert a vectors file in the shared JSON format into the line format the C runner reads
(C has no JSON parser in the standard library; this keeps the runner free of vendored code).

    C <frame_id> <kind> <hex data, `-` when empty> <message>
    R <signal> <raw int>
    P <signal> <physical, as written in the JSON> [<raw the double encode gives, `-` if it refuses>]
    E
    V <frame_id> <text as hex> <frame count> <hex frame>...

Given the spec, each physical value also carries what the shared rounding rule makes of that
double (ir/encoding.py's Python reference, with the range rules every encode applies): the C
double encode must give exactly that, on every case. Without it the runner expects the case's
raw value on physical-encodable cases.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "generator"))

from canspec import ir
from canspec.ir.encoding import to_raw_runtime


def number_text(value: object) -> str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"not a number: {value!r}")
    return repr(value)


def double_rule(sig: ir.Signal, x: float) -> int | None:
    """The raw value a double encode of `x` gives under the shared rules, or None if it refuses."""
    q = (x - float(sig.offset)) / float(sig.factor)
    if not sig.raw_type_min - 1 < q < sig.raw_type_max + 1:  # exact comparisons (float with int); NaN fails
        return None
    r = to_raw_runtime(x, float(sig.factor), float(sig.offset))
    if any(r == sp.raw for sp in sig.specials):
        return r
    if not float(sig.accept_min) <= x <= float(sig.accept_max) or not sig.raw_min <= r <= sig.raw_max:
        return None
    return r


def _physical_line(name: str, value: object, sig: ir.Signal | None) -> str:
    line = f"P {name} {number_text(value)}"
    if sig is None or sig.role != "data":
        return line
    r = double_rule(sig, float(value))  # type: ignore[arg-type]
    return f"{line} {'-' if r is None else r}"


def convert(doc: dict, can: ir.CanProtocol | None = None) -> str:  # type: ignore[type-arg]
    out = []
    for case in doc.get("cases", []):
        msg = can.message(case["message"]) if can is not None else None
        signals = {s.name: s for s in msg.data_signals} if msg is not None else {}
        out.append(f"C {int(case['frame_id'])} {case.get('kind', 'random')} {case['data'] or '-'} {case['message']}")
        for name, value in sorted(case.get("raw", {}).items()):
            out.append(f"R {name} {int(value)}")
        for name, value in sorted(case.get("physical", {}).items()):
            out.append(_physical_line(name, value, signals.get(name)))
        out.append("E")
    for mf in doc.get("multiframe", []):
        out.append(f"V {int(mf['frame_id'])} {mf['text'].encode('ascii').hex() or '-'} {len(mf['frames'])} {' '.join(mf['frames'])}")
    return "\n".join(out) + "\n"


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print("usage: vectors_to_lines.py VECTORS.json OUT.txt", file=sys.stderr)
        return 2
    try:
        with open(argv[1], encoding="utf-8") as fh:
            doc = json.load(fh)
        text = convert(doc)
    except (OSError, ValueError, KeyError, TypeError) as exc:
        print(f"vectors_to_lines: {argv[1]}: {exc}", file=sys.stderr)
        return 1
    with open(argv[2], "w", encoding="ascii") as fh:
        fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
