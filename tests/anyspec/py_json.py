"""Import a generated Python JSON-bindings package and check every case of its vectors file
with tests/targets/json_bindings/py_runner.py's `check` (own verdict, field at fault, dispatch, round trip).

    python3 tests/anyspec/py_json.py PACKAGE_DIR PACKAGE VECTORS_JSON
"""

from __future__ import annotations

import importlib
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from anyspec import adapters


def main(argv: list[str]) -> int:
    pkg_dir, package, vectors = Path(argv[1]), argv[2], Path(argv[3])
    sys.path.insert(0, str(pkg_dir))
    rd = importlib.import_module(package)
    check = adapters.json_case_check()
    doc = json.loads(vectors.read_text(encoding="utf-8"))
    (proto,) = [p for p in doc["protocols"] if p["protocol"] == package]
    bad = []
    for c in proto["cases"]:
        why = check(rd, c)
        if why:
            bad.append(f"MISMATCH {c['id']}: {'; '.join(why)}")
    for line in bad[:40]:
        print(line)
    print(f"python json bindings: {len(proto['cases'])} cases, {len(bad)} mismatches")
    return 1 if bad or not proto["cases"] else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
