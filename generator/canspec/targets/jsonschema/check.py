"""What the JSON targets (schemas, bindings, vectors) cannot express, refused by `canspec check`
with the element's location: each rule below names the protocol feature a valid spec may hold
but no JSON target could give one meaning in every language."""

from __future__ import annotations

import math
from collections.abc import Iterator

from canspec import ir
from canspec.ir.json_fields import CMD_KEY, MATCH_KEY, is_command
from canspec.reference.jsonvalue import sample, type_fault
from canspec.spec.problems import Problem, error

EXACT_INTEGER = 2**53 - 1  # the largest integer every JSON parser reads exactly (I-JSON, RFC 7493)
# Keywords each JSON type gives a meaning to (`decimals` is a precision note on numbers).
MEANINGFUL = {
    "integer": {"range", "enum", "sentinel", "decimals"},
    "number": {"range", "sentinel", "decimals"},
    "boolean": set(),
    "string": {"enum"},
}


def _integer_range(field: ir.JsonField) -> Iterator[Problem]:
    if field.json_type != "integer":
        return
    lo, hi = field.type_min, field.type_max
    if lo is None or hi is None or lo < -EXACT_INTEGER or hi > EXACT_INTEGER:
        yield error(
            f"integer type {field.type!r} needs min and max within ±{EXACT_INTEGER} (2^53 - 1): "
            "beyond, JSON readers that hold numbers as doubles (JavaScript, ajv) cannot tell integers apart",
            field.type_loc, f"declare {field.type}: {{json: integer, min: ..., max: ...}} within ±{EXACT_INTEGER}, as the shipped U64 does (erratum J08)",
            "json-integer-range",
        )


def _used(field: ir.JsonField) -> set[str]:
    used = set()
    if field.min is not None:
        used.add("range")
    if field.enum:
        used.add("enum")
    if field.sentinels:
        used.add("sentinel")
    if field.decimals is not None:
        used.add("decimals")
    return used


def _field_shape(field: ir.JsonField) -> Iterator[Problem]:
    extra = sorted(_used(field) - MEANINGFUL[field.json_type])
    if extra:
        yield error(
            f"field {field.json_name!r} is a JSON {field.json_type} ({field.type}): {', '.join(f'`{k}`' for k in extra)} has no meaning for it",
            field.loc, "drop it, or give the field a type of another JSON kind", "json-field-shape",
        )
    elif field.enum and field.sentinels:
        yield error(f"field {field.json_name!r} has both `enum` and `sentinel`", field.loc, "list the special values in `enum`", "json-field-shape")


def _field_values(field: ir.JsonField) -> Iterator[Problem]:
    for what, values in (("enum", field.enum), ("sentinel", field.sentinels)):
        for v in values:
            fault = type_fault(field, v.value)
            if fault is not None:
                yield error(f"{what} value {v.value!r} of field {field.json_name!r} is never valid: {fault[1]}", v.loc or field.loc, None, "json-field-values")
    if field.min is not None and field.max is not None and field.json_type in ("integer", "number"):
        whole = field.json_type == "integer"
        if field.min > field.max or (whole and math.ceil(field.min) > math.floor(field.max)):
            yield error(f"field {field.json_name!r}: the range [{field.min}, {field.max}] holds no {field.json_type}", field.loc, None, "json-field-values")
            return
    if not sample(field):
        yield error(f"field {field.json_name!r} accepts no value: its range, enum or lengths exclude every {field.type}", field.loc, None, "json-field-values")


def _command_keys(protocol: ir.JsonProtocol) -> Iterator[Problem]:
    commands = any(is_command(m) for m in protocol.messages)
    for m in protocol.messages:
        cmd = next((f for f in m.fields if f.json_name == CMD_KEY), None)
        if cmd is None:
            continue
        if m.cmd is not None and (cmd.json_type != "integer" or type_fault(cmd, m.cmd) is not None):
            yield error(
                f"message {m.name!r}: its `cmd` key ({cmd.type}) cannot carry its command number {m.cmd}", cmd.loc,
                "give the cmd field an integer type whose range holds every command number", "json-command-key",
            )
        elif m.cmd is None and commands:
            yield error(
                f"message {m.name!r} carries a `cmd` key but declares no command number, while the protocol's commands are told apart by `cmd`",
                m.loc, "declare `cmd:` and `role:` on the message, or give the field another json_name", "json-command-key",
            )


def _shape(f: ir.JsonField) -> tuple[object, ...]:
    return (f.json_type, f.type_min, f.type_max, f.min, f.max, f.min_length, f.max_length, tuple(e.value for e in f.enum), tuple(s.value for s in f.sentinels))


def _reply_match(protocol: ir.JsonProtocol) -> Iterator[Problem]:
    answered: set[str] = set()
    for reply in protocol.messages:
        if reply.role != "reply" or reply.reply_to is None:
            continue
        if reply.reply_to in answered:
            yield error(
                f"reply {reply.name!r} answers {reply.reply_to!r}, which another reply answers already: the bindings pair each request with one reply",
                reply.loc, "give the request one reply message (results differ by `res`)", "json-reply-match",
            )
        answered.add(reply.reply_to)
        req = {f.json_name: f for f in protocol.message(reply.reply_to).fields}
        for f in reply.fields:
            if f.json_name == MATCH_KEY and MATCH_KEY in req and _shape(f) != _shape(req[MATCH_KEY]):
                yield error(
                    f"reply {reply.name!r} echoes its request's {MATCH_KEY!r}, but defines it unlike {reply.reply_to!r} does", f.loc,
                    f"give both messages' {MATCH_KEY!r} the same type, range and values", "json-reply-match",
                )


def _names(spec: ir.Spec) -> Iterator[Problem]:
    seen: set[str] = set()
    for p in spec.json:
        if p.name in seen:
            yield error(f"two JSON protocols are named {p.name!r}: their outputs would share one directory", p.loc, "rename one protocol", "json-protocol-name")
        seen.add(p.name)
        reserved = {"protocol": "the whole-protocol schema", **{f"to_{m.receiver}": f"the schema of what {m.receiver} receives" for m in p.messages}}
        for m in p.messages:
            if m.name in reserved:
                yield error(
                    f"message {m.name!r} would share its schema file ({m.name}.schema.json) with {reserved[m.name]}", m.loc, "rename the message",
                    "json-schema-file",
                )


def problems(spec: ir.Spec) -> Iterator[Problem]:
    out: dict[tuple[object, str], Problem] = {}
    for protocol in spec.json:
        fields = [f for m in protocol.messages for f in m.fields]
        for f in fields:
            for p in (*_integer_range(f), *_field_shape(f)):
                out.setdefault((p.loc, p.message), p)
        for f in fields:
            if not any(p.loc == f.loc for p in out.values()):  # a field of a refused shape has no values to speak of
                for p in _field_values(f):
                    out.setdefault((p.loc, p.message), p)
        for p in (*_command_keys(protocol), *_reply_match(protocol)):
            out.setdefault((p.loc, p.message), p)
    for p in _names(spec):
        out.setdefault((p.loc, p.message), p)
    yield from out.values()
