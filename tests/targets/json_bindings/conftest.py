"""Fixtures of the JSON-protocol tests (paths and helpers: json_support.py)."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from json_support import (  # noqa: F401  (fixtures shared with ../jsonschema)
    CARGO_TARGET,
    HERE,
    NODE_MODULES,
    PROTOCOL,
    PY_BINDINGS,
    RUNNER,
    SCHEMAS,
    TS_DIR,
    VECTORS,
    cases,
    json_vectors,
    require_tool,
    run,
    schemas,
    ts_runners,
)


@pytest.fixture(scope="session")
def rd():
    """The generated Python bindings package."""
    sys.path.insert(0, str(PY_BINDINGS))
    try:
        import remote_driving
    finally:
        sys.path.remove(str(PY_BINDINGS))
    assert Path(remote_driving.__file__).resolve().is_relative_to(PY_BINDINGS)
    return remote_driving


@pytest.fixture(scope="session")
def ajv_results() -> dict[str, dict[str, Any]]:
    node = require_tool("node")
    if not (NODE_MODULES / "ajv").is_dir():
        pytest.fail(f"ajv is not installed in {NODE_MODULES}: run `make setup` (.ci/setup.d/60-json.sh)")
    env = {**os.environ, "NODE_PATH": str(NODE_MODULES)}
    proc = run([node, str(HERE / "node" / "ajv_check.cjs"), str(SCHEMAS), str(VECTORS)], "ajv", env=env)
    return {r["id"]: r for r in json.loads(proc.stdout)}


@pytest.fixture(scope="session")
def rust_runner() -> Path:
    cargo = require_tool("cargo")
    env = {**os.environ, "CARGO_TARGET_DIR": str(CARGO_TARGET)}
    run([cargo, "build", "--quiet", "--locked", "--manifest-path", str(RUNNER / "Cargo.toml")], "cargo build (JSON vectors runner)", env=env)
    return CARGO_TARGET / "debug" / "json-vectors-runner"


@pytest.fixture(scope="session")
def rust_results(rust_runner: Path) -> dict[str, dict[str, Any]]:
    proc = run([str(rust_runner), str(VECTORS)], "Rust JSON vectors runner")
    return {r["id"]: r for r in json.loads(proc.stdout)}


@pytest.fixture(scope="session")
def ts_runner(tmp_path_factory: pytest.TempPathFactory) -> list[str]:
    """The command running ts_runner.ts over the shipped protocol's generated TypeScript reader."""
    return ts_runners({PROTOCOL: (TS_DIR, PROTOCOL)}, tmp_path_factory.mktemp("ts_reader"))[PROTOCOL]


@pytest.fixture(scope="session")
def ts_results(ts_runner: list[str]) -> dict[str, dict[str, Any]]:
    proc = run([*ts_runner, str(VECTORS)], "TypeScript reader runner")
    return {r["id"]: r for r in json.loads(proc.stdout)}
