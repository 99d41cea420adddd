"""Run the generated Python JSON bindings over a JSON-protocol vectors file and compare with
its expectations (own verdict, field and rule at fault, receiver's and whole-protocol reading,
round trip). Usage: python3 tests/targets/json_bindings/py_runner.py [--bindings DIR] VECTORS_JSON (DIR holds one
package folder per protocol, as generated/json/python does); ends with `N passed, N failed`."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]


def same(a: Any, b: Any) -> bool:
    """JSON equality: numbers by value (0 == 0.0), booleans never equal to numbers."""
    if isinstance(a, bool) or isinstance(b, bool):
        return type(a) is type(b) and a == b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return a == b
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    return type(a) is type(b) and a == b


def check(rd: Any, c: dict[str, Any]) -> list[str]:
    why = []
    try:
        msg = rd.MESSAGES[c["message"]].from_json(c["json"])
    except rd.ValidationError as e:
        if c["valid"]:
            why.append(f"rejected: {e}")
        elif (e.field, e.code) != (c["field"], c["rule"]):
            why.append(f"fault {e.field}/{e.code} (expected {c['field']}/{c['rule']})")
    else:
        if not c["valid"]:
            why.append("accepted")
        elif not same(msg.to_json(), c["json"]) or not same(json.loads(json.dumps(msg.to_json())), c["json"]):
            why.append(f"round trip gives {msg.to_json()}")
    for label, receiver in (("as_received", c["receiver"]), ("as_any", None)):
        try:
            got = rd.parse(c["json"], receiver).NAME
        except rd.ValidationError:
            got = None
        if got != c[label]:
            why.append(f"{label} {got} (expected {c[label]})")
    return why


def main(argv: list[str]) -> int:
    bindings = ROOT / "generated" / "json" / "python"
    if len(argv) == 3 and argv[0] == "--bindings":
        bindings, argv = Path(argv[1]), argv[2:]
    if len(argv) != 1:
        print("usage: py_runner.py [--bindings DIR] VECTORS_JSON", file=sys.stderr)
        return 2
    try:
        doc = json.loads(Path(argv[0]).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        print(f"py_runner: {argv[0]}: {exc}", file=sys.stderr)
        return 2
    total = failed = 0
    for proto in doc.get("protocols", []):
        sys.path.insert(0, str(bindings / proto["protocol"]))
        rd = __import__(proto["protocol"])
        for c in proto["cases"]:
            total += 1
            why = check(rd, c)
            if why:
                failed += 1
                print(f"MISMATCH {proto['protocol']} {c['id']}: {'; '.join(why)}", file=sys.stderr)
    print(f"python json vectors: {total} cases")
    print(f"{total - failed} passed, {failed} failed")
    return 1 if failed or not doc.get("protocols") else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
