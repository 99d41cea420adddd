"""JSON Schemas (draft 2020-12) of the JSON protocols, built as data: one per message, one
accepting any message of a protocol (`protocol.schema.json`), and one per receiving party
(`to_<party>.schema.json`) accepting what that party receives.

Decisions carried by every schema (and stated in its description):
- `additionalProperties: false`: the protocol is unversioned (the shipped one: erratum J01), so a receiver
  cannot tell a newer sender's field from a typo ("Spd"); unknown keys are rejected and a
  revision that adds a field must add it to the spec (and so to these schemas).
- Integer fields carry the range of their declared type (U8, S16, U64 limited to 2^53-1: J08).
- Precision notes ("2 decimal places") are annotations (`decimals`, see below), never
  `multipleOf`: 12.34 is not a multiple of 0.01 in binary floating point, and the document's
  precision is a formatting note for senders, not a rule receivers enforce.
- canspec's own annotations (a field's declared type, unit, decimals, errata, labels; a
  message's parties) are JSON text in the standard `$comment` keyword,
  `{"x-canspec": {...}}` (a root's also names the generator: `"generated"`), never a keyword
  of their own: validators in strict mode (ajv's default) refuse unknown keywords.
- Numbers in JSON are finite (erratum J11); a schema cannot say so, as JSON has no NaN: a
  reader must refuse NaN and Infinity itself (Python's `json.loads` accepts them).
"""

from __future__ import annotations

import json
from typing import Any

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.ir.json_fields import FieldRule, MessageModel, Plan, ProtocolModel
from canspec.render.environment import header_lines
from canspec.targets import Target
from canspec.targets.jsonschema.check import problems

DRAFT = "https://json-schema.org/draft/2020-12/schema"
ANNOTATION = "x-canspec"
ADDITIONAL_NOTE = (
    "Unknown keys are rejected (additionalProperties: false): the protocol carries no version, so a receiver cannot tell "
    "a newer sender's field from a misspelt one."
)
ADDITIONAL_NOTE_ZH = "不接受未定义的字段（additionalProperties: false）：协议没有版本号，接收方无法区分新字段和拼写错误。"
PRECISION_NOTE = "Precision is documented (decimals in the $comment annotation), not enforced: receivers accept any finite number in range."
PRECISION_NOTE_ZH = "有效小数位仅作说明（$comment 注解中的 decimals），不作校验。"


def schema_id(protocol: ir.JsonProtocol, name: str) -> str:
    return f"urn:canspec:json:{protocol.name}:{name}"


def _bilingual(en: str, zh: str) -> str:
    return "\n".join(t for t in (en.strip(), zh.strip()) if t)


def _field_description(r: FieldRule) -> str:
    """English facts, then (for a field with a Chinese name or description) the same in Chinese."""
    f = r.field
    facts, facts_zh = [f.type], [f.type]
    if f.unit:
        facts.append(f"unit {f.unit}")
        facts_zh.append(f"单位{f.unit}")
    if r.has_range:
        span = f"[{'' if r.lo is None else r.lo}, {'' if r.hi is None else r.hi}]"
        facts.append(f"range {span}")
        facts_zh.append(f"值范围为{span}")
    if f.decimals is not None:
        facts.append(f"{f.decimals} decimal places (documented, not enforced)")
        facts_zh.append(f"有效小数位{f.decimals}位（不作校验）")
    for s in r.sentinels:
        facts.append(f"{s.value}: {s.label.lower()}")
        facts_zh.append(f"{s.value}：{s.label_zh or s.label.lower()}")
    if r.enum is not None:
        facts.append("values " + ", ".join(f"{e.value} {e.label.lower()}" for e in r.enum.values))
        facts_zh.append("值为" + "、".join(f"{e.value}（{e.label_zh or e.label.lower()}）" for e in r.enum.values))
    en = (f.desc + " " if f.desc else "") + "(" + "; ".join(facts) + ")"
    if f.errata:
        en += " Errata: " + ", ".join(f.errata) + "."
    if not (f.zh or f.desc_zh):
        return en
    zh = "：".join(t for t in (f.zh, f.desc_zh) if t) + "；" + "；".join(facts_zh)
    return _bilingual(en, zh)


def _titled(name: str, zh: str) -> str:
    return f"{name}: {zh}" if zh else name


def _labels(v: ir.JsonEnumValue) -> dict[str, str]:
    return {"name": v.name, "en": v.label, **({"zh": v.label_zh} if v.label_zh else {})}


def _annotation(r: FieldRule) -> dict[str, Any]:
    f = r.field
    out: dict[str, Any] = {"type": f.type, "name": r.ident}
    if f.unit:
        out["unit"] = f.unit
    if f.decimals is not None:
        out["decimals"] = f.decimals
    if f.errata:
        out["errata"] = list(f.errata)
    if r.enum is not None:
        out["enum_type"] = r.enum.name
        out["enum"] = {str(e.value): _labels(e) for e in r.enum.values}
    if r.sentinels:
        out["sentinels"] = {str(s.value): _labels(s) for s in r.sentinels}
    return out


def field_schema(r: FieldRule) -> dict[str, Any]:
    f = r.field
    s: dict[str, Any] = {"title": _titled(r.key, f.zh), "description": _field_description(r), "$comment": annotation(_annotation(r))}
    s["type"] = r.kind
    if r.kind in ("integer", "number"):
        if r.type_lo is not None:
            s["minimum"] = r.type_lo
        if r.type_hi is not None:
            s["maximum"] = r.type_hi
    if r.kind == "string":
        if f.min_length is not None:
            s["minLength"] = f.min_length
        if f.max_length is not None:
            s["maxLength"] = f.max_length
    if r.const is not None:
        s["const"] = r.const
    elif r.enum is not None:
        s["enum"] = [e.value for e in r.enum.values]
    elif r.has_range:
        documented: dict[str, Any] = {"title": "documented range"}
        if r.lo is not None:
            documented["minimum"] = r.lo
        if r.hi is not None:
            documented["maximum"] = r.hi
        if r.sentinels:
            s["anyOf"] = [documented, *({"const": x.value, "title": x.name, "description": _bilingual(x.label, x.label_zh)} for x in r.sentinels)]
        else:  # one object: the tighter of the type's and the documented bound
            if "minimum" in documented:
                s["minimum"] = documented["minimum"] if r.type_lo is None else max(r.type_lo, documented["minimum"])
            if "maximum" in documented:
                s["maximum"] = documented["maximum"] if r.type_hi is None else min(r.type_hi, documented["maximum"])
    return s


def message_schema(pm: ProtocolModel, mm: MessageModel, generated: str | None = None) -> dict[str, Any]:
    m = mm.message
    role = f" ({m.role} of cmd {m.cmd})" if m.role else ""
    en = f"{m.desc} Sent by {m.sender} to {m.receiver}{role}.".strip()
    pair = next((p for p in pm.pairs if p.reply == m.name), None)
    if pair is not None:
        by = " and ".join(("cmd", *pair.echoed))
        echo = "".join(f" (the reply echoes the request's {k})" for k in pair.echoed)
        en += f" Answers {pair.request}: matched to it by {by}{echo}."
    decimals = any(r.field.decimals is not None for r in mm.rules)
    en += " " + ADDITIONAL_NOTE + (" " + PRECISION_NOTE if decimals else "")
    ann: dict[str, Any] = {"message": m.name, "from": m.sender, "to": m.receiver, "type_name": mm.type_name}
    if m.cmd is not None:
        ann.update({"cmd": m.cmd, "role": m.role})
    if m.reply_to:
        ann["reply_to"] = m.reply_to
    zh = f"{m.zh}（{m.sender} → {m.receiver}）。" + ADDITIONAL_NOTE_ZH + (PRECISION_NOTE_ZH if decimals else "") if m.zh else ""
    out = {
        "title": _titled(m.name, m.zh),
        "description": _bilingual(en, zh),
        "type": "object",
        "properties": {r.key: field_schema(r) for r in mm.rules},
        "required": [r.key for r in mm.rules],
        "additionalProperties": False,
        "$comment": annotation(ann, generated),
    }
    if m.examples:
        out["examples"] = [dict(e) for e in m.examples]
    return out


def annotation(ann: dict[str, Any], generated: str | None = None) -> str:
    """The `$comment` text carrying canspec's annotations (JSON; `generated`: a root's header)."""
    return json.dumps({**({"generated": generated} if generated else {}), ANNOTATION: ann}, ensure_ascii=False, sort_keys=True, separators=(",", ":"))


def _root(protocol: ir.JsonProtocol, name: str, body: dict[str, Any]) -> dict[str, Any]:
    return {"$schema": DRAFT, "$id": schema_id(protocol, name), **body}


def _has(key: str) -> dict[str, Any]:
    """The object has `key` (declared beside `required`, any value: strict validators such as ajv's
    strictRequired refuse a required key no `properties` of the same schema names)."""
    return {"properties": {key: {}}, "required": [key]}


def _any_of_keys(keys: tuple[str, ...]) -> dict[str, Any]:
    return _has(keys[0]) if len(keys) == 1 else {"anyOf": [_has(k) for k in keys]}


def _group_schema(group: tuple[jsonmodel.Branch, ...]) -> dict[str, Any]:
    """if <a marker of the first message> (or: valid as it, where no key tells) then it, else the rest of the group."""
    head, *rest = group
    ref = {"$ref": f"#/$defs/{head.message}"}
    if not rest:
        return ref
    return {"if": ref if head.tried else _any_of_keys(head.markers), "then": ref, "else": _group_schema(tuple(rest))}


def plan_schema(pm: ProtocolModel, p: Plan, generated: str | None = None) -> dict[str, Any]:
    defs = {name: message_schema(pm, pm.message(name)) for name in p.messages}
    who = "any message of the protocol" if p.receiver is None else f"a message sent to {p.receiver}"
    how = f"telling them apart as follows: {'; '.join(p.rules)}." if p.messages else "none: the protocol has no messages."
    title_zh = pm.protocol.title_zh
    zh = title_zh + ("：任意消息。" if p.receiver is None else f"：发给 {p.receiver} 的消息。") + ADDITIONAL_NOTE_ZH if title_zh else ""
    body: dict[str, Any] = {
        "title": f"{pm.protocol.name}: {who}",
        "description": _bilingual(f"Accepts {who}, {how} " + ADDITIONAL_NOTE, zh),
        "type": "object",
        "$comment": annotation({"protocol": pm.protocol.name, "version": pm.protocol.version, "receiver": p.receiver, "messages": list(p.messages)}, generated),
        "$defs": defs,
    }
    plain = _group_schema(p.plain) if p.plain else _has(jsonmodel.CMD_KEY)
    if p.commands:
        command = {
            "properties": {jsonmodel.CMD_KEY: {"enum": list(p.command_values), "description": "known commands"}},
            "allOf": [{"if": {"properties": {jsonmodel.CMD_KEY: {"const": c}}}, "then": _group_schema(g)} for c, g in p.commands],
        }
        body.update({"if": _has(jsonmodel.CMD_KEY), "then": command, "else": plain})
    elif p.plain:
        body.update(plain)
    else:
        body["not"] = {}  # no message: nothing is accepted
    return body


def build_schemas(spec: ir.Spec) -> dict[str, dict[str, Any]]:
    out: dict[str, dict[str, Any]] = {}
    generated = " ".join(header_lines(spec, "jsonschema"))
    for protocol in spec.json:
        pm = jsonmodel.model(protocol)
        for mm in pm.messages:
            out[f"{protocol.name}/{mm.name}.schema.json"] = _root(protocol, mm.name, message_schema(pm, mm, generated))
        for p in pm.plans:
            name = "protocol" if p.receiver is None else f"to_{p.receiver}"
            out[f"{protocol.name}/{name}.schema.json"] = _root(protocol, name, plan_schema(pm, p, generated))
    return out


def render_schemas(spec: ir.Spec) -> dict[str, bytes]:
    return {f"jsonschema/{rel}": (json.dumps(s, indent=2, sort_keys=True, ensure_ascii=False) + "\n").encode("utf-8") for rel, s in build_schemas(spec).items()}


TARGET = Target("jsonschema", "JSON Schemas (draft 2020-12) of the JSON protocol", "jsonschema/", render_schemas, order=40, check=problems)
