"""The TypeScript bindings of a JSON protocol: declarations (interfaces of the JSON on the wire,
keys as sent; enum literal unions; the request → reply type mapping), and a reader of JSON text
(`<protocol>.reader.ts`: the protocol's rules as tables, checked by `canspec-json.ts`, a real
source file copied with the generated header)."""

from __future__ import annotations

import textwrap

from canspec import ir
from canspec.ir.json_fields import Branch, FieldRule, Plan, ProtocolModel
from canspec.render.environment import render, static_file
from canspec.render.literals import TYPESCRIPT
from canspec.targets.json_bindings import text


def ts_type(r: FieldRule) -> str:
    if r.const is not None:
        return str(r.const)
    if r.enum is not None:
        return r.enum.name
    return {"integer": "number", "number": "number", "boolean": "boolean", "string": "string"}[r.kind]


def union(types: list[str]) -> str:
    return " | ".join(types) if types else "never"


def reply_chain(pm: ProtocolModel) -> list[tuple[str, str]]:
    """(request type, reply type), requests with more keys first: a request type that holds
    another's keys would also match the other's `extends` test."""
    pairs = sorted(pm.pairs, key=lambda p: -len(pm.message(p.request).keys))
    return [(pm.message(p.request).type_name, pm.message(p.reply).type_name) for p in pairs]


def receiver_types(pm: ProtocolModel, plan: Plan) -> str:
    return union([pm.message(name).type_name for name in plan.messages])


def ts_list(values: tuple[float | str, ...] | list[str]) -> str:
    return "[" + ", ".join(TYPESCRIPT.value(v) for v in values) + "]"


def field_props(r: FieldRule) -> list[str]:
    """A field's rules as the properties of canspec-json.ts `Field` (absent where the rule is)."""
    props = [f"key: {TYPESCRIPT.value(r.key)}", f"kind: {TYPESCRIPT.value(r.kind)}"]
    if r.type_lo is not None:
        props.append(f"typeLo: {TYPESCRIPT.value(r.type_lo)}")
    if r.type_hi is not None:
        props.append(f"typeHi: {TYPESCRIPT.value(r.type_hi)}")
    props.append(f"typeRule: {TYPESCRIPT.value(r.type_rule)}")
    if r.has_type_range:
        props.append(f"typeRangeRule: {TYPESCRIPT.value(r.type_range_rule)}")
    if r.kind == "string":
        f = r.field
        props += [*([f"minLength: {f.min_length}"] if f.min_length is not None else []), *([f"maxLength: {f.max_length}"] if f.max_length is not None else [])]
        if r.length_rule:
            props.append(f"lengthRule: {TYPESCRIPT.value(r.length_rule)}")
    if r.enum is not None:
        props.append(f"values: {ts_list(tuple(e.value for e in r.enum.values))}")
    elif r.has_range:
        props += [*([f"lo: {TYPESCRIPT.value(r.lo)}"] if r.lo is not None else []), *([f"hi: {TYPESCRIPT.value(r.hi)}"] if r.hi is not None else [])]
        if r.sentinels:
            props.append(f"sentinels: {ts_list(tuple(s.value for s in r.sentinels))}")
    if r.value_rule:
        props.append(f"valueRule: {TYPESCRIPT.value(r.value_rule)}")
    return props


def branch(b: Branch) -> str:
    return f"{{ message: {TYPESCRIPT.value(b.message)}, markers: {ts_list(b.markers)}, tried: {'true' if b.tried else 'false'} }}"


def plan_const(plan: Plan) -> str:
    """The plan's constant: ANY, or the receiver's type name (unique in the protocol)."""
    return "ANY" if plan.receiver is None else plan.type_name


def plan_doc(plan: Plan) -> str:
    rules = "; ".join(plan.rules) or "none: the protocol has no messages"
    whom = "any party" if plan.receiver is None else plan.receiver
    lines = textwrap.wrap(text.ts_doc(f"What {whom} receives: {rules}."), 96, break_long_words=False, break_on_hyphens=False)
    return "/**\n" + "".join(f" * {line}\n" for line in lines) + " */"


def read_union(pm: ProtocolModel) -> str:
    """`Read`: one `{ name, value }` per message, a line each."""
    if not pm.messages:
        return " never"
    return "".join(f"\n  | {{ readonly name: {TYPESCRIPT.value(mm.name)}; readonly value: T.{mm.type_name} }}" for mm in pm.messages)


def ts_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    types = {
        "message_types": union([mm.type_name for mm in pm.messages]),
        "request_types": union([pm.message(p.request).type_name for p in pm.pairs]),
        "reply_types": union([pm.message(p.reply).type_name for p in pm.pairs]),
        "reply_to_doc": "it carries the same `cmd`" + "".join(f" and echoes `{k}`" for k in dict.fromkeys(k for p in pm.pairs for k in p.echoed)),
    }
    body = render("json_ts/messages.d.ts.j2", spec, "json_ts", p=pm.protocol, pm=pm, ts_type=ts_type, ts_lit=TYPESCRIPT.value, doc=text.field_doc,
                  ts_doc=text.ts_doc, paren=text.paren, heading=text.heading, echo_clause=text.echo_clause, reply_chain=reply_chain(pm),
                  receiver_types=lambda plan: receiver_types(pm, plan), **types)
    reader = render("json_ts/reader.ts.j2", spec, "json_ts", p=pm.protocol, pm=pm, ts_lit=TYPESCRIPT.value, ts_list=ts_list, field_props=field_props,
                    branch=branch, plan_const=plan_const, plan_doc=plan_doc, read_union=read_union(pm), receivers=[plan.receiver for plan in pm.receiver_plans])
    return {
        f"json/typescript/{pm.protocol.name}.d.ts": body.encode(),
        f"json/typescript/{pm.protocol.name}.reader.ts": reader.encode(),
        "json/typescript/canspec-json.ts": static_file(spec, "json_ts", "json_ts/canspec-json.ts").encode(),
    }
