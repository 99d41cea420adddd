"""The Python bindings of a JSON protocol: a stdlib-only package of frozen dataclasses that
validate themselves. Type names, literals, check calls and signatures are computed here."""

from __future__ import annotations

from typing import Any

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.ir.json_fields import Branch, FieldRule, MessageModel, Pair, Plan, ProtocolModel
from canspec.render.environment import render
from canspec.render.literals import PYTHON
from canspec.targets.json_bindings import names, text

TYPING = ("Any", "ClassVar", "NoReturn")


def py_tuple(values: tuple[Any, ...]) -> str:
    """A tuple literal: (), ("a",), ("a", "b")."""
    items = [PYTHON.value(v) for v in values]
    return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"


def py_type(r: FieldRule) -> str:
    if r.enum is not None:
        return r.enum.name
    return {"integer": "int", "number": "float", "boolean": "bool", "string": "str"}[r.kind]


def param_type(r: FieldRule) -> str:
    """A parameter taking the field's value: an enum field takes the enum or its raw value."""
    if r.enum is not None:
        return f"{r.enum.name} | {'str' if r.enum.json_type == 'string' else 'int'}"
    return py_type(r)


def check(r: FieldRule, expr: str, indent: int = 8) -> str:
    """The call that type-checks `expr` for field `r` and returns its normalised value; its
    arguments go on their own line when the call would pass PY_LINE characters."""
    name = "self.NAME" if expr.startswith("self.") else "cls.NAME"
    args = [name, PYTHON.value(r.key), expr]
    if r.kind == "integer":
        fn, args = "_integer", [*args, PYTHON.value(r.type_lo), PYTHON.value(r.type_hi), PYTHON.value(r.type_rule), PYTHON.value(r.type_range_rule)]
    elif r.kind == "number":
        fn, args = "_number", [*args, PYTHON.value(r.type_lo), PYTHON.value(r.type_hi), PYTHON.value(r.type_rule), PYTHON.value(r.type_range_rule)]
    elif r.kind == "boolean":
        fn, args = "_boolean", [*args, PYTHON.value(r.type_rule)]
    else:
        f = r.field
        fn, args = "_string", [*args, PYTHON.value(f.min_length), PYTHON.value(f.max_length), PYTHON.value(r.type_rule), PYTHON.value(r.length_rule)]
    one_line = f"{fn}({', '.join(args)})"
    if indent + len("value = ") + len(one_line) <= text.PY_LINE:
        return one_line
    pad = " " * (indent + 4)
    return f"{fn}(\n" + "".join(f"{pad}{a},\n" for a in args) + " " * indent + ")"


def range_test(r: FieldRule) -> str:
    """The condition a value outside the documented range (and not a sentinel) meets."""
    bounds = " <= ".join([*([PYTHON.value(r.lo)] if r.lo is not None else []), "value", *([PYTHON.value(r.hi)] if r.hi is not None else [])])
    return f"not {bounds}" + "".join(f" and value != {PYTHON.value(s.value)}" for s in r.sentinels)


def to_json_expr(r: FieldRule) -> str:
    if r.const is not None:
        return "self.CMD"
    return f"self.{names.py_attr(r)}" + (".value" if r.enum is not None else "")


def reply_params(pm: ProtocolModel, pair: Pair) -> str:
    """The parameters of `reply` after self: the result (defaulting to its 0 value, "success"),
    then the reply's other fields by keyword."""
    reply = pm.message(pair.reply)
    out = []
    if pair.result is not None:
        r = reply.rule(pair.result)
        zero = next((e for e in r.enum.values if e.value == 0), None) if r.enum is not None else None
        out.append(f"{names.py_attr(r)}: {param_type(r)}" + (f" = {r.enum.name}.{names.member(zero)}" if r.enum is not None and zero else ""))
    if pair.extra:
        out += ["*", *(f"{names.py_attr(reply.rule(k))}: {param_type(reply.rule(k))}" for k in pair.extra)]
    return ", ".join(["self", *out])


def reply_args(pm: ProtocolModel, pair: Pair) -> str:
    """The reply's constructor arguments: the result, the keys echoed from the request, the rest."""
    request, reply = pm.message(pair.request), pm.message(pair.reply)
    out = []
    for k in reply.keys:
        r = reply.rule(k)
        if k in pair.echoed:
            out.append(f"{names.py_attr(r)}=self.{names.py_attr(request.rule(k))}")
        elif k == pair.result or k in pair.extra:  # an enum parameter may be the raw value: the dataclass field is the enum
            out.append(f"{names.py_attr(r)}={r.enum.name}({names.py_attr(r)})" if r.enum is not None else f"{names.py_attr(r)}={names.py_attr(r)}")
    return ", ".join(out)


def echo_test(pm: ProtocolModel, pair: Pair) -> str:
    request, reply = pm.message(pair.request), pm.message(pair.reply)
    return "".join(f" and reply.{names.py_attr(reply.rule(k))} == self.{names.py_attr(request.rule(k))}" for k in pair.echoed)


def match_key(pair: Pair, mm: MessageModel) -> str:
    """What a request shares with its reply: the request's name and the echoed keys' values."""
    items = [PYTHON.value(pair.request), *(f"self.{names.py_attr(mm.rule(k))}" for k in pair.echoed)]
    return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"


def self_attr(r: FieldRule) -> str:
    return f"self.{names.py_attr(r)}"


def item(key: str) -> str:
    return f"obj[{PYTHON.value(key)}]"


def enum_values(r: FieldRule) -> str:
    assert r.enum is not None
    return py_tuple(tuple(e.value for e in r.enum.values))


def field_line(r: FieldRule) -> str:
    """A field in its message's docstring."""
    return f'{names.py_attr(r)} ("{r.key}"): {text.field_doc(r)}'


def markers_test(b: Branch) -> str:
    return " or ".join(f"{PYTHON.value(k)} in obj" for k in b.markers)


def union(types: list[str]) -> str:
    return " | ".join(types) if types else "NoReturn"


def reader(plan: Plan) -> str:
    return "_read_any" if plan.receiver is None else f"_read_to_{plan.receiver}"


def exports(pm: ProtocolModel) -> list[str]:
    """The package's names, in isort's order (constants, classes, functions; each sorted)."""
    fixed = ["MESSAGES", "PROTOCOL", "RECEIVERS", "REPLY_OF", "VERSION", "Message", "ValidationError", "is_reply_to", "loads", "parse"]
    names = fixed + [e.name for e in pm.enums] + [mm.type_name for mm in pm.messages] + (["PendingRequests", "Reply", "Request"] if pm.pairs else [])
    return sorted(names, key=lambda n: (0 if n.isupper() and len(n) > 1 else 1 if n[0].isupper() else 2, n))


def typing_names(pm: ProtocolModel) -> tuple[str, ...]:
    unused = {"ClassVar"} if not pm.messages else {"NoReturn"}
    return tuple(n for n in TYPING if n not in unused)


def python_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    name = pm.protocol.name
    base = f"json/python/{name}"
    helpers = {
        "py_value": PYTHON.value,
        "py_tuple": py_tuple,
        "py_type": py_type,
        "check": check,
        "range_test": range_test,
        "to_json_expr": to_json_expr,
        "reply_params": reply_params,
        "reply_args": reply_args,
        "echo_test": echo_test,
        "match_key": match_key,
        "attr": names.py_attr,
        "member": names.member,
        "sentinel_const": names.sentinel_const,
        "wrap": text.py_wrap,
        "label": text.label,
        "self_attr": self_attr,
        "item": item,
        "enum_values": enum_values,
        "field_line": field_line,
        "markers_test": markers_test,
        "union": union,
        "reader": reader,
        "summary": text.summary,
        "echo_clause": text.echo_clause,
        "receives": text.receives,
        "without_receiver": text.without_receiver,
    }
    types = {
        "message_types": [mm.type_name for mm in pm.messages],
        "request_types": [pm.message(p.request).type_name for p in pm.pairs],
        "reply_types": [pm.message(p.reply).type_name for p in pm.pairs],
    }
    context = {"p": pm.protocol, "pm": pm, "codes": jsonmodel.ERROR_CODES + jsonmodel.TEXT_ERROR_CODES, "typing": typing_names(pm), **types, **helpers}
    files = {
        f"{base}/{name}/messages.py": render("json_python/messages.py.j2", spec, "json_python", **context),
        f"{base}/{name}/__init__.py": render("json_python/__init__.py.j2", spec, "json_python", p=pm.protocol, exports=exports(pm), py_string=PYTHON.string),
        f"{base}/{name}/py.typed": "",
        f"{base}/pyproject.toml": render("json_python/pyproject.toml.j2", spec, "json_python", p=pm.protocol),
    }
    return {path: body.encode() for path, body in files.items()}
