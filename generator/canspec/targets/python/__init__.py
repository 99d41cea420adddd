"""Python bindings (`python/`): an installable, typed, stdlib-only package named after the
CAN protocol, formatted with ruff at generation time (in memory, so output is deterministic
for a pinned ruff version)."""

from __future__ import annotations

import subprocess

from canspec import ir
from canspec.render.environment import render
from canspec.targets import Target
from canspec.targets.python.model import build_package

# The formatter's version is part of the output: CI installs exactly this one (.ci/setup.d/40-python.sh).
RUFF_VERSION = "0.17.6"
LINE_LENGTH = 120
TARGET_NAME = "python"

# template → path inside the package directory ("{pkg}" is the import name)
MODULES = {
    "__init__.py": "python/__init__.py.j2",
    "errors.py": "python/errors.py.j2",
    "_runtime.py": "python/_runtime.py.j2",
    "enums.py": "python/enums.py.j2",
    "messages.py": "python/messages.py.j2",
    "j1939.py": "python/j1939.py.j2",
    "multiframe.py": "python/multiframe.py.j2",
    "bus.py": "python/bus.py.j2",
}


def ruff_binary() -> str:
    try:
        from ruff.__main__ import find_ruff_bin  # type: ignore[import-not-found,import-untyped,unused-ignore]
    except ImportError:
        raise RuntimeError(f"the python target formats its output with ruff: pip install ruff=={RUFF_VERSION}") from None
    return str(find_ruff_bin())


def ruff_format(source: str, filename: str) -> str:
    """The source as `ruff format` writes it, with this target's settings and no config files."""
    cmd = [ruff_binary(), "format", "--isolated", f"--line-length={LINE_LENGTH}", "--target-version=py310", f"--stdin-filename={filename}", "-"]
    proc = subprocess.run(cmd, input=source.encode("utf-8"), capture_output=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"ruff format failed on {filename}: {proc.stderr.decode('utf-8', 'replace').strip()}")
    return proc.stdout.decode("utf-8")


def render_sources(spec: ir.Spec) -> dict[str, str]:
    """Unformatted sources, relative to the distribution directory."""
    pkg = build_package(spec)
    ctx = {"pkg": pkg, "tie_epsilon": ir.TIE_EPSILON_TEXT, "sha256": spec.sha256, "line_length": LINE_LENGTH}
    out = {f"{pkg.package}/{name}": render(tpl, spec, TARGET_NAME, **ctx) for name, tpl in MODULES.items()}
    out[f"{pkg.package}/py.typed"] = render("python/py.typed.j2", spec, TARGET_NAME, **ctx)
    out["examples/virtual_bus.py"] = render("python/example_virtual_bus.py.j2", spec, TARGET_NAME, **ctx)
    out["pyproject.toml"] = render("python/pyproject.toml.j2", spec, TARGET_NAME, **ctx)
    return out


def render_python(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    files = {}
    for rel, text in render_sources(spec).items():
        if rel.endswith(".py"):
            text = ruff_format(text, rel)
        files[f"python/{rel}"] = text.encode("utf-8")
    return files


TARGET = Target(TARGET_NAME, "Python package (typed dataclasses, stdlib only; python-can optional)", "python/", render_python, order=30, cost=8)
