"""Python bindings (`python/`): an installable, typed, stdlib-only package named after the
CAN protocol, formatted with ruff at generation time (in memory, so output is deterministic
for a pinned ruff version). Modules that depend on the spec are rendered from templates; the
rest (errors, the encode slow path, J1939 helpers, python-can glue) are plain source files
under templates/python/static/, copied with the generated header — and the receive monitor,
`monitor.py`, is canspec's own runtime/monitor.py, copied the same way."""

from __future__ import annotations

import importlib.resources
import subprocess

from canspec import ir, resources
from canspec.render.environment import header_lines, render
from canspec.targets import Target
from canspec.targets.python.model import PyPackage, build_package

# The formatter's version is part of the output: CI installs exactly this one (.ci/setup.d/40-python.sh).
RUFF_VERSION = "0.17.6"
MONITOR_SOURCE = "canspec.runtime.monitor"  # modules' source: copied from canspec's own package
LINE_LENGTH = 120
TARGET_NAME = "python"


def ruff_binary() -> str:
    try:
        from ruff.__main__ import find_ruff_bin  # type: ignore[import-not-found,import-untyped,unused-ignore]
    except ImportError:
        raise RuntimeError(f"the python target formats its output with ruff: pip install ruff=={RUFF_VERSION}") from None
    return str(find_ruff_bin())


def _ruff(args: list[str], source: str, filename: str) -> str:
    cmd = [ruff_binary(), *args, "--isolated", f"--line-length={LINE_LENGTH}", "--target-version=py310", f"--stdin-filename={filename}", "-"]
    proc = subprocess.run(cmd, input=source.encode("utf-8"), capture_output=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"ruff {args[0]} failed on {filename}: {proc.stderr.decode('utf-8', 'replace').strip()}")
    return proc.stdout.decode("utf-8")


def ruff_format(source: str, filename: str, package: str) -> str:
    """The source as ruff writes it, with this target's settings and no config files: imports
    sorted (isort's order of names, which the templates do not reproduce), then formatted."""
    isort = ["check", "--select=I", "--fix", "--exit-zero", "--quiet", "--config", f"lint.isort.known-first-party = [{package!r}]"]
    return _ruff(["format"], _ruff(isort, source, filename), filename)


def _modules(pkg: PyPackage) -> dict[str, str]:
    """Package module → its template (`.j2`) or static source, for this spec."""
    modules = {"__init__.py": "__init__.py.j2", "_rules.py": "_rules.py.j2", "messages.py": "messages.py.j2", "supervision.py": "supervision.py.j2"}
    modules.update({"errors.py": "static/errors.py", "_runtime.py": "static/_runtime.py", "bus.py": "static/bus.py", "monitor.py": MONITOR_SOURCE})
    if pkg.enums:
        modules["enums.py"] = "enums.py.j2"
    if pkg.is_j1939:
        modules["j1939.py"] = "static/j1939.py"
    if pkg.has_multiframe:
        modules["multiframe.py"] = "multiframe.py.j2"
    return modules


def static_source(spec: ir.Spec, name: str) -> str:
    """A static source file as shipped: the generated header, then the file verbatim."""
    if name == MONITOR_SOURCE:  # canspec's own receive monitor, the one implementation of it
        text = (importlib.resources.files("canspec.runtime") / "monitor.py").read_text(encoding="utf-8")
    else:
        text = (resources.templates_dir() / "python" / name).read_text(encoding="utf-8")
    return "".join(f"# {line}\n" for line in header_lines(spec, TARGET_NAME)) + "\n" + text


def render_sources(spec: ir.Spec, pkg: PyPackage) -> dict[str, str]:
    """Unformatted sources, relative to the distribution directory."""
    ctx = {"pkg": pkg, "tie_epsilon": ir.TIE_EPSILON_TEXT, "exact_limit": ir.EXACT_LIMIT_TEXT, "sha256": spec.sha256, "line_length": LINE_LENGTH}

    def source(name: str) -> str:
        return render(f"python/{name}", spec, TARGET_NAME, **ctx) if name.endswith(".j2") else static_source(spec, name)

    out = {f"{pkg.package}/{module}": source(name) for module, name in _modules(pkg).items()}
    out[f"{pkg.package}/py.typed"] = static_source(spec, "static/py.typed")
    if pkg.example is not None:
        out["examples/virtual_bus.py"] = source("example_virtual_bus.py.j2")
    out["pyproject.toml"] = source("pyproject.toml.j2")
    return out


def render_python(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    files = {}
    pkg = build_package(spec)
    for rel, text in render_sources(spec, pkg).items():
        if rel.endswith(".py"):
            text = ruff_format(text, rel, pkg.package)
        files[f"python/{rel}"] = text.encode("utf-8")
    return files


TARGET = Target(TARGET_NAME, "Python package (typed dataclasses, stdlib only; python-can optional)", "python/", render_python, order=30, cost=8)
