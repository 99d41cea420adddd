"""The Python target on every valid fixture (tests/fixtures/valid/*.yaml with a CAN protocol), and on
the Python-target specs of tests/targets/python/specs/ (names other targets refuse, `canspec gen -t python`): each
generated package passes ruff check, ruff format and mypy --strict, imports (with its python-can
module), round-trips the spec's own vectors through the vector runner, and its example runs on
python-can's virtual bus. One ruff and one mypy run cover every package."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from canspec.pipeline import compile_spec
from canspec.render import formatters
from canspec.targets import python as target
from canspec.targets.vectors import render_vectors

from targets.python import pkgpath

VALID = pkgpath.ROOT / "tests" / "fixtures" / "valid"
PYTHON_ONLY = pkgpath.ROOT / "tests" / "targets" / "python" / "specs"
RUNNER = pkgpath.ROOT / "tests" / "targets" / "python" / "vector_runner.py"


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, check=False, **kw)


def _can_fixtures() -> list[Path]:
    out = []
    for path, targets in [*((p, None) for p in sorted(VALID.glob("*.yaml"))), *((p, ["python"]) for p in sorted(PYTHON_ONLY.glob("*.yaml")))]:
        compiled = compile_spec(path, targets)
        assert compiled.spec is not None, [p.format() for p in compiled.problems]
        if compiled.spec.can is not None:
            out.append(path)
    return out


FIXTURES = _can_fixtures()


@pytest.fixture(scope="module")
def packages(tmp_path_factory) -> dict[str, tuple[Path, Path]]:
    """Fixture name → (package directory, vectors file), generated once."""
    root = tmp_path_factory.mktemp("anyspec-python")
    out = {}
    for path in FIXTURES:
        spec = compile_spec(path, ["python"]).spec
        files = {**target.render_python(spec), **render_vectors(spec)}
        for rel, data in files.items():
            dest = root / path.stem / rel
            dest.parent.mkdir(parents=True, exist_ok=True)
            dest.write_bytes(data)
        (package,) = [p for p in (root / path.stem / "python").iterdir() if (p / "__init__.py").is_file()]
        out[path.stem] = (package, root / path.stem / "vectors" / "can.json")
    return out


def test_fixtures_cover_what_the_target_must_handle():
    names = {p.stem for p in FIXTURES}
    assert {"py_english_standard", "py_wide_and_keywords", "py_name_clashes", "py_no_messages", "py_special_at_field_edge", "py_value_tables"} <= names


def test_ruff_check_and_format(packages):
    ruff = formatters.FORMATTERS["ruff"].executable()
    dists = [str(pkg.parent) for pkg, _ in packages.values()]
    for dist in dists:  # each with its own pyproject.toml's [tool.ruff.lint] rules
        proc = run([ruff, "check", "--no-cache", "."], cwd=dist)
        assert proc.returncode == 0, dist + "\n" + proc.stdout + proc.stderr
    proc = run([ruff, "format", "--check", "--no-cache", "--isolated", f"--line-length={target.LINE_LENGTH}", *dists])
    assert proc.returncode == 0, proc.stdout + proc.stderr


def _distinct_name_groups(packages: dict[str, tuple[Path, Path]]) -> list[dict[str, Path]]:
    """Fixtures split into as few groups as keep package names apart (mypy sees one module per name)."""
    groups: list[dict[str, Path]] = []
    for stem, (pkg, _) in sorted(packages.items()):
        group = next((g for g in groups if pkg.name not in {p.name for p in g.values()}), None)
        if group is None:
            groups.append(group := {})
        group[stem] = pkg
    return groups


def test_mypy_strict(packages, tmp_path):
    """mypy --strict over every fixture's package and example, in one run per group of distinct
    package names (examples renamed apart: they share a module name)."""
    for i, group in enumerate(_distinct_name_groups(packages)):
        work = tmp_path / f"group{i}"
        work.mkdir()
        targets = [str(pkg) for pkg in group.values()]
        for stem, pkg in group.items():
            example = pkg.parent / "examples" / "virtual_bus.py"
            if example.is_file():
                targets.append(str(shutil.copy(example, work / f"example_{stem}.py")))
        env = {"MYPYPATH": ":".join(str(pkg.parent) for pkg in group.values()), "PATH": "/usr/bin:/bin"}
        proc = run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir=/dev/null", *targets], env=env, cwd=work)
        assert proc.returncode == 0 and "Success: no issues found" in proc.stdout, f"{sorted(group)}\n{proc.stdout}{proc.stderr}"


@pytest.mark.parametrize("stem", [p.stem for p in FIXTURES])
def test_imports_and_round_trips_its_vectors(packages, stem):
    pkg, vectors = packages[stem]
    # one interpreter: the package with its python-can module, then the runner (argv as on its command line)
    code = f"import {pkg.name}.bus, vector_runner, sys; sys.exit(vector_runner.main(sys.argv))"
    env = {"PYTHONPATH": f"{pkg.parent}:{RUNNER.parent}", "PATH": "/usr/bin:/bin"}
    proc = run([sys.executable, "-c", code, str(vectors), "--package", str(pkg)], env=env)
    assert proc.returncode == 0 and ", 0 mismatches" in proc.stdout, proc.stdout[-4000:] + proc.stderr[-2000:]


def test_english_only_spec_shows_no_empty_chinese(packages):
    pkg, _ = packages["py_english_standard"]
    for path in [*pkg.glob("*.py"), pkg.parent / "pyproject.toml"]:
        text = path.read_text(encoding="utf-8")
        # an empty Chinese name shows as "name ()" (not code such as `= ()`)
        assert not re.search(r"\w \(\)", text) and "— " not in text and "§" not in text, path.name


@pytest.mark.parametrize("stem", [p.stem for p in FIXTURES])
def test_example_runs_on_the_virtual_bus(packages, stem):
    pkg, _ = packages[stem]
    example = pkg.parent / "examples" / "virtual_bus.py"
    if not example.is_file():
        assert not (pkg / "messages.py").read_text(encoding="utf-8").count("@dataclass"), "a protocol with messages needs its example"
        return
    proc = run([sys.executable, str(example)], env={"PYTHONPATH": str(pkg.parent), "PATH": "/usr/bin:/bin"}, timeout=60)
    assert proc.returncode == 0 and len(proc.stdout.splitlines()) == 3, proc.stdout + proc.stderr
