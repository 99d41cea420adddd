"""Identifiers of the JSON bindings in each language, computed from the model's snake_case and
PascalCase names: keywords and the bindings' own member names escaped. Names that would still
coincide (two fields, values or parties spelt differently in the spec but alike in a binding)
are refused by `canspec check` (rule json-binding-name)."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from typing import TypeVar

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.ir.json_fields import FieldRule
from canspec.ir.names import pascal, rust_ident, upper_snake
from canspec.spec.problems import Loc, Problem, error

T = TypeVar("T")

# Python's keywords, fixed here (not `keyword.kwlist`) so that the output does not depend on the
# Python that generates it; soft keywords (match, case, type, _) are valid identifiers.
PY_KEYWORDS = frozenset({
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue", "def", "del", "elif", "else", "except", "finally",
    "for", "from", "global", "if", "import", "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while", "with",
    "yield",
})
# Attributes and parameters the Python message classes use themselves, and the builtins their
# class bodies annotate with (a field `int` would shadow the type in the annotations after it).
PY_MEMBERS = frozenset({"to_json", "from_json", "reply", "is_answered_by", "match_key", "self", "cls", "int", "float", "bool", "str"})
# Names the Rust `from_value` uses for the value and its map.
RUST_LOCALS = frozenset({"v", "obj"})


def py_attr(r: FieldRule) -> str:
    """The dataclass field (and constructor keyword) of a JSON field."""
    name = r.ident
    return f"{name}_" if name in PY_KEYWORDS or name in PY_MEMBERS else name


def rust_field(r: FieldRule) -> str:
    return rust_ident(r.ident)


def rust_local(r: FieldRule) -> str:
    """The local variable `from_value` reads a field into."""
    name = rust_field(r)
    return f"{name}_" if name in RUST_LOCALS else name


def rust_variant(name: str) -> str:
    """An enum variant: PascalCase, `Self` escaped."""
    out = pascal(name)
    return "Self_" if out == "Self" else out


def member(v: ir.JsonEnumValue) -> str:
    """A Python enum member."""
    return upper_snake(v.name)


def sentinel_const(r: FieldRule, s: ir.JsonEnumValue) -> str:
    """The class constant naming a sentinel (both languages)."""
    return upper_snake(f"{r.ident}_{s.name}")


def _clashes(items: list[tuple[str, T]]) -> Iterator[tuple[str, T]]:
    """(name, item) for each item whose name an earlier item took."""
    seen: set[str] = set()
    for name, item in items:
        if name in seen:
            yield name, item
        seen.add(name)


def problems(spec: ir.Spec) -> Iterator[Problem]:
    out: dict[tuple[object, str], Problem] = {}

    def refuse(what: str, name: str, loc: Loc | None, hint: str) -> None:
        p = error(f"{what} would share the name {name!r} in the generated bindings", loc, hint, "json-binding-name")
        out.setdefault((p.loc, p.message), p)

    for protocol in spec.json:
        if protocol.name in PY_KEYWORDS or protocol.name in sys.stdlib_module_names:
            p = error(
                f"JSON protocol {protocol.name!r} names its Python package, which would be a Python keyword or shadow the standard module",
                protocol.loc, "rename the protocol", "json-protocol-name",
            )
            out.setdefault((p.loc, p.message), p)
        pm = jsonmodel.model(protocol)
        for mm in pm.messages:
            for name, r in _clashes([(r.ident, r) for r in mm.rules]):
                refuse(f"two fields of {mm.name!r}", name, r.field.loc, "give one of them another `name`")
            consts = [(sentinel_const(r, s), s) for r in mm.rules for s in r.sentinels]
            for name, s in _clashes(consts):
                refuse(f"two sentinels of {mm.name!r}", name, s.loc, "rename one sentinel value")
        for e in pm.enums:
            for names in ([(member(v), v) for v in e.values], [(rust_variant(v.name), v) for v in e.values]):
                for name, v in _clashes(names):
                    refuse(f"two values of {e.name}", name, v.loc, "rename one of the values")
        for name, party in _clashes([(rust_variant(p.name), p) for p in protocol.parties]):
            refuse(f"party {party.name!r} and another party", name, protocol.loc, "rename one of the parties")
    yield from out.values()
