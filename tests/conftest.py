"""Shared fixtures: the compiled shipped spec, the repository paths, the generated vectors."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from repo_paths import GENERATED, ROOT, SEEDS, SPEC  # noqa: E402,F401

from canspec.pipeline import compile_spec  # noqa: E402


@pytest.fixture(scope="session")
def spec():
    compiled = compile_spec(SPEC)
    assert compiled.spec is not None, "\n".join(p.format() for p in compiled.problems)
    return compiled.spec


@pytest.fixture(scope="session")
def can(spec):
    return spec.can


@pytest.fixture(scope="session")
def vectors():
    return json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))
