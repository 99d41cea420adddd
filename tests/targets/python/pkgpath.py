"""Where the generated Python package lives; importing this module makes it importable."""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
# CANSPEC_PYTHON_PACKAGE points the tests at another rendering of the package (see test_quality.py).
PACKAGE_DIR = Path(os.environ.get("CANSPEC_PYTHON_PACKAGE", ROOT / "generated" / "python"))
DBC = ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"
DEFAULT_VECTORS = ROOT / "generated" / "vectors" / "can.json"

if str(PACKAGE_DIR) not in sys.path:
    sys.path.insert(0, str(PACKAGE_DIR))
