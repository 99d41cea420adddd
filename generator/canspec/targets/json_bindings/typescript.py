"""The TypeScript declarations of a JSON protocol: interfaces of the JSON on the wire (keys as
sent), enum literal unions, and the request → reply type mapping."""

from __future__ import annotations

from canspec import ir
from canspec.ir.json_fields import FieldRule, Plan, ProtocolModel
from canspec.render.environment import render
from canspec.render.literals import ts_value
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


def ts_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    types = {
        "message_types": union([mm.type_name for mm in pm.messages]),
        "request_types": union([pm.message(p.request).type_name for p in pm.pairs]),
        "reply_types": union([pm.message(p.reply).type_name for p in pm.pairs]),
        "reply_to_doc": "it carries the same `cmd`" + "".join(f" and echoes `{k}`" for k in dict.fromkeys(k for p in pm.pairs for k in p.echoed)),
    }
    body = render("json_ts/messages.d.ts.j2", spec, "json_ts", p=pm.protocol, pm=pm, ts_type=ts_type, ts_lit=ts_value, doc=text.field_doc,
                  ts_doc=text.ts_doc, paren=text.paren, heading=text.heading, echo_clause=text.echo_clause, reply_chain=reply_chain(pm),
                  receiver_types=lambda plan: receiver_types(pm, plan), **types)
    return {f"json/typescript/{pm.protocol.name}.d.ts": body.encode()}
