"""Shared fixtures: the compiled shipped spec, the repository paths, the generated vectors."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from canspec.pipeline import compile_spec
from repo_paths import GENERATED, ROOT, SPEC  # noqa: F401


@pytest.fixture(scope="session")
def spec():
    compiled = compile_spec(SPEC)
    assert compiled.spec is not None, "\n".join(p.format() for p in compiled.problems)
    return compiled.spec


@pytest.fixture(scope="session")
def can(spec):
    return spec.can


@pytest.fixture(scope="session")
def db():
    """cantools reading the generated DBC: the independent oracle of many tests."""
    import cantools

    return cantools.database.load_file(str(GENERATED / "dbc" / "kaiwo_gateway.dbc"), encoding="utf-8", strict=True)


@pytest.fixture(scope="session")
def vectors():
    return json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))
