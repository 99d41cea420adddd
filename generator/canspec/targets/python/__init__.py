"""Python bindings (`python/`): an installable, typed, stdlib-only package named after the
CAN protocol, formatted with ruff at generation time (render/formatters.py: in memory, so output is
deterministic for the pinned ruff version). Modules that depend on the spec are rendered from templates; the
rest (errors, the encode slow path, J1939 helpers, python-can glue) are plain source files
under templates/python/static/, copied with the generated header — and the receive monitor,
`monitor.py`, is canspec's own runtime/monitor.py, copied the same way."""

from __future__ import annotations

import importlib.resources
from collections.abc import Iterator

from canspec import ir
from canspec.render.environment import render, static_file, with_header
from canspec.render.formatters import ruff_format
from canspec.spec.problems import Problem, error
from canspec.targets import Target
from canspec.targets.python.model import PyPackage, build_package

MONITOR_SOURCE = "canspec.runtime.monitor"  # modules' source: copied from canspec's own package
LINE_LENGTH = 120
TARGET_NAME = "python"


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
        return with_header(spec, TARGET_NAME, "monitor.py", (importlib.resources.files("canspec.runtime") / "monitor.py").read_text(encoding="utf-8"))
    return static_file(spec, TARGET_NAME, f"python/{name}")


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
            text = ruff_format(text, rel, pkg.package, LINE_LENGTH)
        files[f"python/{rel}"] = text.encode("utf-8")
    return files


def problems(spec: ir.Spec) -> Iterator[Problem]:
    """Multi-frame text whose index, payload or key fields only some pages hold: the text assembler reads them from every frame."""
    for msg in spec.can.messages if spec.can is not None else ():
        for name in msg.text_fields_in_pages:
            yield error(f"multi-frame text of {msg.name!r} reads {name!r}, which only some pages hold; the Python text assembler reads it from every frame",
                        msg.signal(name).loc or msg.loc, "take the text's index, payload and keys from fields in every frame", "python-text-mux")


TARGET = Target(TARGET_NAME, "Python package (typed dataclasses, stdlib only; python-can optional)", "python/", render_python, order=30, cost=8,
                check=problems, formatters=("ruff",))
