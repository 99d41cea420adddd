"""The declared Python API (canspec/__init__.py): every name it lists resolves, to the object the
internal module defines; `import canspec` loads none of the stages or the log decoder's optional
dependencies."""

from __future__ import annotations

import importlib
import subprocess
import sys

import canspec
import pytest
from repo_paths import CANSPEC_ENV, ROOT, SPEC


@pytest.mark.parametrize("name", sorted(set(canspec.__all__) - {"__version__", "ir"}))
def test_every_public_name_resolves_to_its_definition(name):
    value = getattr(canspec, name)
    assert value is getattr(importlib.import_module(canspec._EXPORTS[name]), name)
    assert value.__module__ == canspec._EXPORTS[name], "re-exported from where it is defined"


def test_unknown_names_are_attribute_errors():
    with pytest.raises(AttributeError, match="no attribute 'compile'"):
        canspec.compile  # noqa: B018


def test_import_is_cheap():
    code = "import sys, canspec; print(sorted(m for m in sys.modules if m.startswith(('canspec.', 'numpy', 'pyarrow', 'jinja2', 'yaml'))))"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=CANSPEC_ENV, check=True)
    assert proc.stdout.strip() == "[]"


def test_compile_and_generate_through_the_api():
    compiled = canspec.compile_spec(SPEC)
    assert compiled.spec is not None and not compiled.errors
    assert isinstance(compiled.spec, canspec.ir.Spec)
    assert "dbc" in canspec.target_names()
    (files,) = canspec.generate(compiled.spec, ["dbc"]).values()
    assert files["dbc/kaiwo_gateway.dbc"] == (ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc").read_bytes()


def test_bad_spec_gives_problems_not_an_exception(tmp_path):
    (tmp_path / "canspec.yaml").write_text("not: [a, spec\n", encoding="utf-8")
    compiled = canspec.compile_spec(tmp_path)
    assert compiled.spec is None and compiled.errors
    assert all(isinstance(p, canspec.Problem) for p in compiled.problems)
