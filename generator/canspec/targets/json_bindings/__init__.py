"""Typed bindings of the JSON protocols, from the same model as the schemas (ir/json_fields.py):
Python (python.py: a stdlib-only package of frozen dataclasses), Rust (rust.py: a serde crate)
and TypeScript declarations (typescript.py). Identifiers per language: names.py; doc text:
text.py. The templates only shape the text."""

from __future__ import annotations

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.targets import Target
from canspec.targets.json_bindings.names import problems
from canspec.targets.json_bindings.python import python_files
from canspec.targets.json_bindings.rust import rust_files
from canspec.targets.json_bindings.typescript import ts_files


def render_bindings(spec: ir.Spec) -> dict[str, bytes]:
    out: dict[str, bytes] = {}
    for protocol in spec.json:
        pm = jsonmodel.model(protocol)
        out.update(python_files(spec, pm))
        out.update(rust_files(spec, pm))
        out.update(ts_files(spec, pm))
    return out


TARGET = Target("json_bindings", "typed bindings of the JSON protocol (Python, Rust, TypeScript)", "json/", render_bindings, order=41, cost=3, check=problems,
                formatters=("rustfmt",))
