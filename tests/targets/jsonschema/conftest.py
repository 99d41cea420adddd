"""Fixtures of the JSON Schema tests: the shipped protocol's schemas and vector cases, shared with
the bindings' tests (../json_bindings/json_support.py holds the paths, helpers and these fixtures)."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "json_bindings"))
from json_support import cases, json_vectors, schemas  # noqa: E402, F401  (fixtures)
