"""Convert a vectors file in the shared JSON format into the line format the C runner reads
(C has no JSON parser in the standard library; this keeps the runner free of vendored code).

    C <frame_id> <kind> <hex data> <message>
    R <signal> <raw int>
    P <signal> <physical, as written in the JSON>
    E
    V <frame_id> <text as hex> <frame count> <hex frame>...
"""

from __future__ import annotations

import json
import sys


def number_text(value: object) -> str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"not a number: {value!r}")
    return repr(value)


def convert(doc: dict) -> str:  # type: ignore[type-arg]
    out = []
    for case in doc.get("cases", []):
        out.append(f"C {int(case['frame_id'])} {case.get('kind', 'random')} {case['data']} {case['message']}")
        for name, value in sorted(case.get("raw", {}).items()):
            out.append(f"R {name} {int(value)}")
        for name, value in sorted(case.get("physical", {}).items()):
            out.append(f"P {name} {number_text(value)}")
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
