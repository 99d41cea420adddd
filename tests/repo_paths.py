"""Repository paths for the tests (a module of its own: several test folders have a conftest.py,
so `from conftest import ...` would be ambiguous)."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "spec"
GENERATED = ROOT / "generated"
SEEDS = ROOT.parent / "shared" / "seeds"

# Test this checkout's generator even when another checkout is pip-installed in editable mode.
if str(ROOT / "generator") not in sys.path:
    sys.path.insert(0, str(ROOT / "generator"))
