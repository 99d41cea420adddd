"""Typed bindings of the JSON protocols from the same model as the schemas (`jsonmodel`):
Python (a stdlib-only package of frozen dataclasses), Rust (a serde crate, formatted by
rustfmt at generation time) and TypeScript declarations. Language facts (type names,
literals, check calls) are computed here; the templates only shape the text."""

from __future__ import annotations

import keyword
import textwrap
from typing import Any

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.ir.json_fields import FieldRule, MessageModel, ProtocolModel
from canspec.render.environment import render
from canspec.render.formatters import rustfmt
from canspec.render.literals import double_repr, py_string, rust_string, ts_value
from canspec.targets import Target

RUST_INTS = {"U8": "u8", "S8": "i8", "U16": "u16", "S16": "i16", "U32": "u32", "S32": "i32", "U64": "u64", "S64": "i64"}
PY_LINE = 100  # generated Python stays within this width


# --- shared ---------------------------------------------------------------------------------


def doc(r: FieldRule) -> str:
    """One line describing a field: meaning, type, unit, range, precision, sentinels, Chinese name."""
    f = r.field
    parts = [f.type]
    if f.unit:
        parts.append(f.unit)
    if r.has_range:
        parts.append(f"[{r.lo}, {r.hi}]")
    if f.decimals is not None:
        parts.append(f"{f.decimals} decimal{'' if f.decimals == 1 else 's'} (documented)")
    parts += [f"{s.value} = {s.name}" for s in r.sentinels]
    if r.enum is not None:
        parts.append("one of " + ", ".join(f"{e.value} ({e.name})" for e in r.enum.values))
    desc = f.desc.rstrip(".") + ". " if f.desc else ""
    return f"{desc}{', '.join(parts)}. {f.zh}"


# --- Python ----------------------------------------------------------------------------------


def pyrepr(value: Any) -> str:
    return py_string(value) if isinstance(value, str) else repr(value)


def wrap(text: str, indent: int, width: int = PY_LINE) -> str:
    """Text wrapped to `width`, continuation lines indented by `indent` spaces (docstrings)."""
    return ("\n" + " " * indent).join(textwrap.wrap(text, width - indent, break_long_words=False, break_on_hyphens=False))


def py_type(r: FieldRule) -> str:
    if r.enum is not None:
        return r.enum.name
    return {"integer": "int", "number": "float", "boolean": "bool", "string": "str"}[r.kind]


def py_check(mm: MessageModel, r: FieldRule, expr: str, indent: int = 8) -> str:
    """The call that type-checks `expr` for field `r` and returns its normalised value; its
    arguments go on their own line when the call would pass PY_LINE characters."""
    name = "self.NAME" if expr.startswith("self.") else "cls.NAME"
    args = [name, pyrepr(r.key), expr]
    if r.kind == "integer":
        fn, args = "_integer", [*args, repr(r.type_lo), repr(r.type_hi), pyrepr(r.type_rule), pyrepr(r.type_range_rule)]
    elif r.kind == "number":
        fn, args = "_number", [*args, repr(r.type_lo), repr(r.type_hi), pyrepr(r.type_rule), pyrepr(r.type_range_rule)]
    elif r.kind == "boolean":
        fn, args = "_boolean", [*args, pyrepr(r.type_rule)]
    else:
        f = r.field
        fn, args = "_string", [*args, repr(f.min_length), repr(f.max_length), pyrepr(r.type_rule), pyrepr(length_rule(r))]
    one_line = f"{fn}({', '.join(args)})"
    if indent + len("value = ") + len(one_line) <= PY_LINE:
        return one_line
    pad = " " * (indent + 4)
    return f"{fn}(\n" + "".join(f"{pad}{a},\n" for a in args) + " " * indent + ")"


def python_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    for mm in pm.messages:
        for r in mm.rules:
            if keyword.iskeyword(r.ident) or keyword.issoftkeyword(r.ident):
                raise ValueError(f"JSON field {mm.name}.{r.key}: identifier {r.ident!r} is a Python keyword (give the field another `name`)")
    base = f"json/python/{pm.protocol.name}"
    text = render("json_python/messages.py.j2", spec, "json_python", p=pm.protocol, pm=pm, codes=jsonmodel.ERROR_CODES,
                  pyrepr=pyrepr, py_type=py_type, check=py_check, doc=doc, wrap=wrap)
    init = render("json_python/__init__.py.j2", spec, "json_python", p=pm.protocol, pm=pm)
    pyproject = render("json_python/pyproject.toml.j2", spec, "json_python", p=pm.protocol)
    return {f"{base}/{pm.protocol.name}/messages.py": text.encode(), f"{base}/{pm.protocol.name}/__init__.py": init.encode(),
            f"{base}/{pm.protocol.name}/py.typed": b"", f"{base}/pyproject.toml": pyproject.encode()}


def render_bindings(spec: ir.Spec) -> dict[str, bytes]:
    out: dict[str, bytes] = {}
    for protocol in spec.json:
        pm = jsonmodel.model(protocol)
        out.update(python_files(spec, pm))
        out.update(rust_files(spec, pm))
        out.update(ts_files(spec, pm))
    return out


TARGET = Target("json_bindings", "typed bindings of the JSON protocol (Python, Rust, TypeScript)", "json/", render_bindings, order=41, cost=3)


# --- Rust ------------------------------------------------------------------------------------


def rs_lit(value: int | str) -> str:
    return rust_string(value) if isinstance(value, str) else str(value)


def rs_opt_f64(value: float | None) -> str:
    return "None" if value is None else f"Some({double_repr(value)})"


def rs_type(r: FieldRule) -> str:
    if r.enum is not None:
        return r.enum.name
    if r.kind == "integer":
        if r.field.type not in RUST_INTS:
            raise ValueError(f"JSON field {r.key!r}: no Rust integer type for {r.field.type!r}")
        return RUST_INTS[r.field.type]
    return {"number": "f64", "boolean": "bool", "string": "String"}[r.kind]


def length_rule(r: FieldRule) -> str:
    f = r.field
    return r.value_rule if r.enum is None and r.value_rule else f"must be {f.min_length}..{f.max_length} characters ({f.type})"


def rust_crate_name(protocol: ir.JsonProtocol) -> str:
    return protocol.name.replace("_", "-") + "-json"


def rust_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    base = f"json/rust/{pm.protocol.name}"
    receivers = [p.receiver for p in pm.plans if p.receiver]
    lib = render("json_rust/lib.rs.j2", spec, "json_rust", p=pm.protocol, pm=pm, codes=jsonmodel.ERROR_CODES, receivers=receivers,
                 rs_str=rust_string, rs_lit=rs_lit, rs_doc=rs_lit, rs_f64=double_repr, rs_opt_f64=rs_opt_f64, rs_type=rs_type, length_rule=length_rule, doc=doc)
    cargo = render("json_rust/Cargo.toml.j2", spec, "json_rust", p=pm.protocol, crate=rust_crate_name(pm.protocol))
    return {f"{base}/src/lib.rs": rustfmt(lib, f"{base}/src/lib.rs").encode(), f"{base}/Cargo.toml": cargo.encode()}


# --- TypeScript ------------------------------------------------------------------------------


def ts_type(r: FieldRule) -> str:
    if r.const is not None:
        return str(r.const)
    if r.enum is not None:
        return r.enum.name
    return {"integer": "number", "number": "number", "boolean": "boolean", "string": "string"}[r.kind]


def ts_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    text = render("json_ts/messages.d.ts.j2", spec, "json_ts", p=pm.protocol, pm=pm, ts_type=ts_type, ts_lit=ts_value, doc=doc)
    return {f"json/typescript/{pm.protocol.name}.d.ts": text.encode()}
