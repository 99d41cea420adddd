"""Run tests/targets/python/vector_runner.py against a generated CAN package (a fresh interpreter per
package: the runner imports the package under the shipped name).

    python3 tests/anyspec/py_vectors.py PYTHON_DIR PACKAGE VECTORS.json
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from anyspec import adapters


def main(argv: list[str]) -> int:
    pydir, package, vectors = Path(argv[1]), argv[2], Path(argv[3])
    runner = adapters.python_vector_runner(pydir, package)  # imports the package: an ImportError is a failure
    count, failures = runner.run(vectors)
    for f in failures[:40]:
        print(f)
    print(f"python vector runner: {count} cases, {len(failures)} mismatches ({package})")
    return 1 if failures or count == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
