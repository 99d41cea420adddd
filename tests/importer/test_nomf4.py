"""cantools and python-can are imported without asammdf (canspec/nomf4.py): python-can's MF4 module
imports it (with pandas: 2 s of every `canspec import`), and canspec reads MF4 with asammdf itself."""

from __future__ import annotations

import subprocess
import sys

import pytest

PROBE = """
import sys
from canspec.nomf4 import import_without_mf4
import_without_mf4({module!r})
print(" ".join(sorted(m for m in ("asammdf", "pandas") if m in sys.modules)) or "none")
"""


@pytest.mark.parametrize("module", ["cantools", "can"])
def test_imported_without_asammdf(module: str) -> None:
    pytest.importorskip(module)
    proc = subprocess.run([sys.executable, "-c", PROBE.format(module=module)], capture_output=True, text=True, check=True, timeout=120)
    assert proc.stdout.split() == ["none"]


def test_asammdf_stays_importable_afterwards() -> None:
    pytest.importorskip("asammdf")
    code = "from canspec.nomf4 import import_without_mf4; import_without_mf4('cantools'); import asammdf; print(asammdf.__name__)"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120)
    assert proc.stdout.split() == ["asammdf"]
