"""The JSON targets of every valid spec fixture holding a JSON protocol, generated into one
directory and checked in batches: one ajv run, one ruff and one mypy run over every Python
package, one cargo workspace (shared target dir, offline) for every Rust crate and its vector
runner, one tsc program for every TypeScript declaration and reader, and one for the readers'
vector runners (used by test_json_fixtures.py)."""

from __future__ import annotations

import json
import os
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from canspec.generation import generate
from canspec.pipeline import compile_spec
from json_support import BUILD, HERE, NODE_MODULES, ROOT, require_tool, run, ts_runners

VALID = ROOT / "tests" / "fixtures" / "valid"
JSON_TARGETS = ["jsonschema", "json_bindings", "json_vectors"]
CARGO_TARGET = BUILD / "json-fixtures-rust"  # shared by runs: only changed crates rebuild
RUN_RS = HERE / "rust_runner" / "src" / "run.rs"
# ruff's default rules (the packages declare no configuration) for their Python, plus W: trailing
# whitespace is where an empty Chinese label would show.
RUFF_ARGS = ["--no-cache", "--isolated", "--target-version", "py310", "--extend-select", "W"]
RUNNER_LOCK = HERE / "rust_runner" / "Cargo.lock"  # pins serde / serde_json to the versions the shipped crate uses


@dataclass(frozen=True)
class Output:
    fixture: str  # file stem
    out: Path  # the generated tree
    protocols: tuple[str, ...]

    @property
    def vectors(self) -> Path:
        return self.out / "vectors" / "json.json"

    @property
    def cases(self) -> dict[str, list[dict[str, Any]]]:
        doc = json.loads(self.vectors.read_text(encoding="utf-8"))
        return {p["protocol"]: p["cases"] for p in doc["protocols"]}

    def schema(self, protocol: str, name: str) -> dict[str, Any]:
        return json.loads((self.out / "jsonschema" / protocol / f"{name}.schema.json").read_text(encoding="utf-8"))

    def unit(self, protocol: str) -> str:
        """A name unique in the batch (fixtures may share protocol names)."""
        return f"{self.fixture}_{protocol}"


def generate_one(path: Path, out: Path) -> Output | None:
    """The JSON targets of the spec at `path` under `out` (None: the spec has no JSON protocol)."""
    compiled = compile_spec(path)
    assert compiled.spec is not None, "\n".join(p.format() for p in compiled.problems)
    if not compiled.spec.json:
        return None
    for files in generate(compiled.spec, JSON_TARGETS).values():
        for rel, body in files.items():
            (out / rel).parent.mkdir(parents=True, exist_ok=True)
            (out / rel).write_bytes(body)
    return Output(out.name, out, tuple(p.name for p in compiled.spec.json))


def generate_all(root: Path) -> list[Output]:
    """Every valid fixture's (tests/fixtures/valid/*.yaml) that holds a JSON protocol."""
    outputs = (generate_one(path, root / path.stem) for path in sorted(VALID.glob("*.yaml")))
    return [o for o in outputs if o is not None]


def ajv(outputs: list[Output]) -> dict[tuple[str, str, str], dict[str, Any]]:
    """(fixture, protocol, case id) → ajv's verdicts."""
    node = require_tool("node")
    args = [str(a) for o in outputs for a in (o.out / "jsonschema", o.vectors)]
    proc = run([node, str(HERE / "node" / "ajv_check.cjs"), *args], "ajv", env={**os.environ, "NODE_PATH": str(NODE_MODULES)})
    return {(outputs[r["input"]].fixture, r["protocol"], r["id"]): r for r in json.loads(proc.stdout)}


def python_runner(o: Output) -> str:
    proc = run(
        [sys.executable, str(HERE / "py_runner.py"), "--bindings", str(o.out / "json" / "python"), str(o.vectors)], f"Python vector runner ({o.fixture})"
    )
    return proc.stdout


def python_lint(outputs: list[Output], root: Path) -> None:
    """ruff over every package; mypy --strict over copies named uniquely (one mypy program)."""
    ruff = require_tool("ruff")
    packages = [o.out / "json" / "python" / p / p for o in outputs for p in o.protocols]
    run([ruff, "check", *RUFF_ARGS, *map(str, packages)], "ruff check")
    copies = root / "mypy"
    for o in outputs:
        for p in o.protocols:
            shutil.copytree(o.out / "json" / "python" / p / p, copies / o.unit(p), dirs_exist_ok=True)
    args = [a for o in outputs for p in o.protocols for a in ("-p", o.unit(p))]
    run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir=/dev/null", *args], "mypy --strict", cwd=copies,
        env={**os.environ, "MYPYPATH": str(copies)})


def rust_workspace(outputs: list[Output], root: Path) -> dict[str, Path]:
    """Every crate (renamed uniquely, its own [workspace] table dropped) and a vector runner for
    each, in one workspace; clippy -D warnings over all of it. Returns unit → runner binary."""
    cargo = require_tool("cargo")
    ws, members, runners = root / "rust", [], {}
    for o in outputs:
        for p in o.protocols:
            unit = o.unit(p)
            crate, lib = ws / "crates" / unit, f"{unit}_json"
            shutil.copytree(o.out / "json" / "rust" / p, crate, dirs_exist_ok=True)
            manifest = (crate / "Cargo.toml").read_text(encoding="utf-8")
            name = next(line for line in manifest.splitlines() if line.startswith("name = "))
            (crate / "Cargo.toml").write_text(manifest.replace(name, f'name = "{lib}"').replace("\n[workspace]\n", "\n"), encoding="utf-8")
            runner = ws / "runners" / unit
            (runner / "src").mkdir(parents=True, exist_ok=True)
            (runner / "Cargo.toml").write_text(
                f'[package]\nname = "run_{unit}"\nversion = "0.1.0"\nedition = "2021"\npublish = false\n\n'
                f'[dependencies]\n{lib} = {{ path = "../../crates/{unit}" }}\nserde_json = "1"\n', encoding="utf-8")
            (runner / "src" / "main.rs").write_text(f'//! Vector runner of {unit}.\n\nuse {lib} as bindings;\n\ninclude!("{RUN_RS}");\n', encoding="utf-8")
            members += [f"crates/{unit}", f"runners/{unit}"]
            runners[unit] = CARGO_TARGET / "debug" / f"run_{unit}"
    (ws / "Cargo.toml").write_text('[workspace]\nresolver = "2"\nmembers = [' + ", ".join(f'"{m}"' for m in members) + "]\n", encoding="utf-8")
    shutil.copy(RUNNER_LOCK, ws / "Cargo.lock")
    env = {**os.environ, "CARGO_TARGET_DIR": str(CARGO_TARGET)}
    manifest = ["--manifest-path", str(ws / "Cargo.toml"), "--offline", "--quiet"]
    run([cargo, "clippy", *manifest, "--workspace", "--all-targets", "--", "-D", "warnings"], "cargo clippy (JSON fixture crates)", env=env)
    run([cargo, "build", *manifest, "--workspace"], "cargo build (JSON fixture runners)", env=env)
    return runners


def typescript(outputs: list[Output], root: Path) -> None:
    """Every declaration file, and each protocol's valid cases typed as their message, in one
    `tsc --strict` program."""
    node = require_tool("node")
    tsc = NODE_MODULES / "typescript" / "bin" / "tsc"
    assert tsc.is_file(), f"typescript is not installed in {NODE_MODULES}: run `make setup`"
    sources = []
    for o in outputs:
        for p, cases in o.cases.items():
            decl = o.out / "json" / "typescript" / f"{p}.d.ts"
            types = {c["message"]: json.loads(o.schema(p, c["message"])["$comment"])["x-canspec"]["type_name"] for c in cases}
            lines = [f'import type * as rd from "{os.path.relpath(decl.with_suffix("").with_suffix(""), root / "ts")}";\n', "export {};\n"]
            lines += [f"const c{i}: rd.{types[c['message']]} = {json.dumps(c['json'], ensure_ascii=False)};\n" for i, c in enumerate(cases) if c["valid"]]
            lines.append("const any: rd.Message[] = [];\nvoid any;\n")
            src = root / "ts" / f"{o.unit(p)}.ts"
            src.parent.mkdir(parents=True, exist_ok=True)
            src.write_text("".join(lines), encoding="utf-8")
            sources += [decl, decl.with_name(f"{p}.reader.ts"), src]
    opts = ["--noEmit", "--strict", "--noUnusedLocals", "false", "--target", "es2020", "--module", "es2020", "--moduleResolution", "node"]
    run([node, str(tsc), *opts, *map(str, sources)], "tsc --strict (JSON fixture declarations and readers)")


def typescript_readers(outputs: list[Output], root: Path) -> dict[str, list[str]]:
    """unit → the command running ts_runner.ts over that protocol's TypeScript reader."""
    return ts_runners({o.unit(p): (o.out / "json" / "typescript", p) for o in outputs for p in o.protocols}, root)
