"""Shared fixtures: the compiled shipped spec, the repository paths, the generated vectors."""

from __future__ import annotations

import atexit
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

# The checkout under test is the one these tests belong to, whatever canspec pip has installed
# (a second worktree, a CI copy): in this process and in every canspec subprocess.
_GENERATOR = str(Path(__file__).resolve().parents[1] / "generator")
sys.path[:0] = [str(Path(__file__).resolve().parent), _GENERATOR]
os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [_GENERATOR, os.environ.get("PYTHONPATH")]))
# Cargo builds here run once and are thrown away: incremental state and debug info would only
# fill the disk (about 10 GB over a full run with them, a fraction of that without).
os.environ.setdefault("CARGO_INCREMENTAL", "0")
os.environ.setdefault("CARGO_PROFILE_DEV_DEBUG", "0")
# The commands' compiled-spec cache goes to a folder of this run's own, never the user's home.
os.environ["CANSPEC_CACHE_DIR"] = tempfile.mkdtemp(prefix="canspec-test-cache-")
atexit.register(shutil.rmtree, os.environ["CANSPEC_CACHE_DIR"], True)
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
    """cantools reading the generated DBC, under the spec's signal names (dbc_names.py): the
    independent oracle of many tests."""
    from dbc_names import load_with_spec_names

    return load_with_spec_names(GENERATED / "dbc" / "kaiwo_gateway.dbc")


@pytest.fixture(scope="session")
def vectors():
    return json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))
