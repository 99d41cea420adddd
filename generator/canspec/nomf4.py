"""python-can imports asammdf (with pandas and more: 2 s) from its MF4 module on `import can`, and
cantools imports python-can. canspec needs neither's MF4 support: its log readers read MF4 files
with asammdf directly (logread._mf4) and its importer reads DBC, ARXML, KCD and SYM. So these
modules are imported with asammdf hidden, as if absent (python-can's MF4 reader then says that
asammdf is missing; canspec never uses it)."""

from __future__ import annotations

import importlib
import sys
from types import ModuleType


def import_without_mf4(name: str) -> ModuleType:
    """The module `name` ("can", "cantools"); an ImportError when it is not installed."""
    if "can" in sys.modules or "asammdf" in sys.modules:  # python-can already imported, or asammdf's cost already paid
        return importlib.import_module(name)
    sys.modules["asammdf"] = None  # type: ignore[assignment]  # makes python-can's `import asammdf` fail fast
    try:
        return importlib.import_module(name)
    finally:
        del sys.modules["asammdf"]
