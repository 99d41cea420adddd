"""Paths, helpers and the shipped protocol's fixtures of the JSON-protocol tests (other fixtures are in
conftest.py): the shared vectors, the generated schemas, the Python bindings, and the results of the validators from other ecosystems (ajv via node, the Rust
bindings via cargo). Tools come from `.ci/setup.d/60-json.sh` (`make setup`)."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest
from py_runner import same  # noqa: F401  (re-exported: one JSON equality for runner and tests)

ROOT = Path(__file__).resolve().parents[3]
HERE = Path(__file__).resolve().parent
GENERATED = ROOT / "generated"
SCHEMAS = GENERATED / "jsonschema"
VECTORS = GENERATED / "vectors" / "json.json"
PROTOCOL = "remote_driving"
PY_BINDINGS = GENERATED / "json" / "python" / PROTOCOL
RUST_CRATE = GENERATED / "json" / "rust" / PROTOCOL
TS_DECL = GENERATED / "json" / "typescript" / f"{PROTOCOL}.d.ts"
TS_DIR = GENERATED / "json" / "typescript"
BUILD = ROOT / "build"
NODE_MODULES = BUILD / "json-node" / "node_modules"
CARGO_TARGET = BUILD / "json-rust"
RUNNER = HERE / "rust_runner"
SEED = ROOT / "spec" / "source" / "remote_driving_json.ocr.txt"  # the source document (spec/source/README.md)
TOOL_TIMEOUT_S = 900


def run(cmd: list[str], what: str, **kw: Any) -> subprocess.CompletedProcess[str]:
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=TOOL_TIMEOUT_S, check=False, **kw)
    if proc.returncode != 0:
        pytest.fail(f"{what} failed ({' '.join(cmd)}):\n{proc.stdout[-4000:]}\n{proc.stderr[-4000:]}")
    return proc


def require_tool(name: str) -> str:
    exe = shutil.which(name)
    if exe is None:
        pytest.fail(f"{name} is not installed: run `make setup` (.ci/setup.d/60-json.sh)")
    return exe


def fields_at_fault(v: Any, instance: Any) -> set[str]:
    """The JSON keys a jsonschema validator's errors point at ("" for the value itself)."""
    out = set()
    for e in v.iter_errors(instance):
        if e.validator == "required" and isinstance(instance, dict):
            out |= {k for k in e.validator_value if k not in instance}
        elif e.validator == "additionalProperties" and isinstance(instance, dict):
            out |= {k for k in instance if k not in e.schema.get("properties", {})}
        else:
            out.add(str(e.absolute_path[0]) if e.absolute_path else "")
    return out


def ts_runners(units: dict[str, tuple[Path, str]], root: Path) -> dict[str, list[str]]:
    """unit → (generated json/typescript dir, protocol): each unit's TypeScript (declarations,
    reader, runtime) copied with ts_runner.ts (importing that protocol's reader) into its own
    folder, all compiled in one `tsc --strict` program to CommonJS. Returns unit → node command."""
    node = require_tool("node")
    tsc = NODE_MODULES / "typescript" / "bin" / "tsc"
    assert tsc.is_file(), f"typescript is not installed in {NODE_MODULES}: run `make setup`"
    runner = (HERE / "ts_runner.ts").read_text(encoding="utf-8")
    sources = []
    for unit, (ts_dir, protocol) in units.items():
        folder = root / "src" / unit
        folder.mkdir(parents=True)
        for f in [ts_dir / f"{protocol}.d.ts", ts_dir / f"{protocol}.reader.ts", ts_dir / "canspec-json.ts"]:
            shutil.copy(f, folder / f.name)
        (folder / "ts_runner.ts").write_text(runner.replace(PROTOCOL, protocol), encoding="utf-8")
        sources += sorted(folder.glob("*.ts"))
    opts = ["--strict", "--noUnusedLocals", "--noUnusedParameters", "--target", "es2020", "--module", "commonjs"]
    run([node, str(tsc), *opts, "--rootDir", str(root / "src"), "--outDir", str(root / "js"), *map(str, sources)], "tsc --strict (TypeScript readers)")
    return {unit: [node, str(root / "js" / unit / "ts_runner.js")] for unit in units}


# Fixtures of the shipped protocol, used by both JSON test folders (their conftest.py import them).
@pytest.fixture(scope="session")
def json_vectors() -> dict[str, Any]:
    return json.loads(VECTORS.read_text(encoding="utf-8"))


@pytest.fixture(scope="session")
def cases(json_vectors: dict[str, Any]) -> list[dict[str, Any]]:
    (proto,) = [p for p in json_vectors["protocols"] if p["protocol"] == PROTOCOL]
    return proto["cases"]


@pytest.fixture(scope="session")
def schemas() -> dict[str, dict[str, Any]]:
    return {p.name.removesuffix(".schema.json"): json.loads(p.read_text(encoding="utf-8")) for p in sorted((SCHEMAS / PROTOCOL).glob("*.schema.json"))}
