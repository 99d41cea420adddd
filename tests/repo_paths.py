"""Repository paths for the tests (a module of its own: several test folders have a conftest.py,
so `from conftest import ...` would be ambiguous)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "spec"
GENERATED = ROOT / "generated"
SOURCES = SPEC / "source"  # the source documents (OCR text), see spec/source/README.md
GATEWAY_DOC = SOURCES / "gateway_v2.0.5beta1.ocr.txt"
JSON_DOC = SOURCES / "remote_driving_json.ocr.txt"

# Test this checkout's generator even when another checkout is pip-installed in editable mode.
if str(ROOT / "generator") not in sys.path:
    sys.path.insert(0, str(ROOT / "generator"))

# The environment for running this checkout's `python -m canspec` in a subprocess.
CANSPEC_ENV = {**os.environ, "PYTHONPATH": str(ROOT / "generator")}
