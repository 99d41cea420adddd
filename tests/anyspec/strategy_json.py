"""The JSON protocol of a drawn spec (strategy.py)."""

from __future__ import annotations

from decimal import Decimal
from typing import TYPE_CHECKING, Any

from anyspec.pools import (
    JSON_FIELD_WORDS,
    JSON_PROTOCOL_NAMES,
    KEYWORDS,
    PARTIES,
    UNITS,
    VALUE_IDENTS,
    _Names,
)
from anyspec.yamltext import _scalar, block, flow

if TYPE_CHECKING:
    from anyspec.strategy import Builder


class JsonBuilder:
    """A JSON protocol that satisfies the documented dispatch model (canspec/jsonmodel.py):
    commands are told apart by `cmd` (a reply by `res`), other messages by a key only they have."""

    TYPES: dict[str, dict[str, Any]] = {
        "U8": {"json": "integer", "min": 0, "max": 255},
        "S8": {"json": "integer", "min": -128, "max": 127},
        "U16": {"json": "integer", "min": 0, "max": 65535},
        "S16": {"json": "integer", "min": -32768, "max": 32767},
        "U32": {"json": "integer", "min": 0, "max": 4294967295},
        "U64": {"json": "integer", "min": 0, "max": 9007199254740991},
        "Float32": {"json": "number", "min": Decimal("-3.4028234663852886e+38"), "max": Decimal("3.4028234663852886e+38")},
        "Float64": {"json": "number"},
        "BOOL": {"json": "boolean"},
        "ASCII": {"json": "string", "min_length": 1, "max_length": 1},
        "TEXT": {"json": "string", "min_length": 0, "max_length": 16},
    }

    def __init__(self, b: Builder, can_name: str) -> None:
        self.b = b
        self.can_name = can_name
        self.types_used: dict[str, dict[str, Any]] = {}

    def type(self, name: str) -> str:
        self.types_used[name] = self.TYPES[name]
        return name

    def render(self) -> str:
        b = self.b
        name = b.pick(JSON_PROTOCOL_NAMES)
        parties = self.parties()
        shared: dict[str, Any] = {
            "ts": {"type": self.type("U64"), "unit": "ms", "zh": "时间戳"},
            "bn": {"type": self.type("U64"), "zh": "流水号"},
        }
        messages: list[dict[str, Any]] = []
        msg_names = _Names()
        self.plain_messages(parties, messages, msg_names)
        self.command_messages(parties, shared, messages, msg_names)
        doc: dict[str, Any] = {"schema_version": 1, "kind": "json_protocol", "protocol": {"name": name, "version": f"1.{b.ch.integer(0, 3)}.0"}}
        doc["parties"] = [{"name": p, **({"zh": b.zh()} if b.p(0.5) else {})} for p in parties]
        doc["types"] = self.types_used
        doc["fields"] = shared
        doc["messages"] = messages
        self.shared = shared
        return _text(doc)

    def parties(self) -> list[str]:
        """Two parties, sometimes three."""
        b = self.b
        parties = [b.pick(PARTIES)]
        others = [p for p in PARTIES if p != parties[0]]
        parties.append(b.pick(others))
        if b.p(0.2):
            parties.append(b.pick([p for p in PARTIES if p not in parties]))
        return parties

    def plain_messages(self, parties: list[str], messages: list[dict[str, Any]], msg_names: _Names) -> None:
        """One to three messages told apart by a marker field, not by a command number."""
        b = self.b
        markers = _Names(["ts", "bn", "cmd", "res"])
        plain = 1 + b.ch.integer(0, 2)
        for _ in range(plain):
            frm, to = self.direction(parties)
            fields: list[Any] = []
            if b.p(0.6):
                fields.append("ts")
            if b.p(0.4):
                fields.append("bn")
            keys = _Names(["ts", "bn"])
            marker = self.field(markers, keys)
            fields.append(marker)
            for _ in range(b.ch.integer(0, 2)):
                fields.append(self.field(markers, keys))
            messages.append(self.message(msg_names, frm, to, fields, None))

    def command_messages(self, parties: list[str], shared: dict[str, Any], messages: list[dict[str, Any]], msg_names: _Names) -> None:
        """Up to two commands: a request, mostly with its reply (cmd, res and the request's bn)."""
        b = self.b
        ncmd = b.ch.integer(0, 2)
        if ncmd:
            shared["cmd"] = {"type": self.type("U16"), "zh": "消息类型"}
            shared["res"] = {"type": self.type("S8"), "zh": "结果", "enum": {0: ["ok", "成功"], -1: ["failed", "失败"]}}
            if b.p(0.5):
                shared["reply_bn"] = {"name": "bn", "json_name": "bn", "type": "U64", "zh": "请求流水号"}
        for c in range(ncmd):
            cmd = c + 1 if b.p(0.7) else b.ch.integer(1, 65535)
            if any(m.get("cmd") == cmd for m in messages):
                cmd = max(m.get("cmd", 0) for m in messages) + 1
            frm, to = self.direction(parties)
            keys = _Names(["cmd", "bn", "res"])
            extra = [self.field(_Names(["ts", "bn", "cmd", "res"]), keys)] if b.p(0.4) else []
            req = self.message(msg_names, frm, to, ["cmd", "bn", *extra], cmd, "request")
            messages.append(req)
            if b.p(0.85):
                bn = "reply_bn" if "reply_bn" in shared else "bn"
                rextra = [self.field(_Names(["ts", "bn", "cmd", "res"]), _Names(["cmd", "bn", "res"]))] if b.p(0.3) else []
                rep = self.message(msg_names, to, frm, ["cmd", "res", bn, *rextra], cmd, "reply", req["name"])
                messages.append(rep)

    def direction(self, parties: list[str]) -> tuple[str, str]:
        frm = self.b.pick(parties)
        to = self.b.pick([p for p in parties if p != frm])
        return frm, to

    def field(self, markers: _Names, keys: _Names) -> dict[str, Any]:
        """An inline field whose JSON key is new to the protocol (`markers`) and message (`keys`)."""
        b = self.b
        pool = JSON_FIELD_WORDS
        while True:
            base = b.pick(pool) if not b.p(0.1) else b.pick(KEYWORDS)
            key = markers.take(base)
            if keys.free(key):
                keys.take(key)
                break
        f: dict[str, Any] = {"name": key}
        kind = b.pick(("U8", "Float32", "BOOL", "S16", "ASCII", "Float64", "U64", "TEXT", "S8", "U32"))
        f["type"] = self.type(kind)
        t = self.TYPES[kind]
        f["zh"] = b.zh()
        if b.p(0.3):
            f["unit"] = b.pick(UNITS)
        if t["json"] == "integer":
            lo, hi = t["min"], t["max"]
            if b.p(0.25):
                n = 1 + b.ch.integer(0, 3)
                vals = sorted({lo + i if b.p(0.5) else max(lo, min(hi, i * 3 - 1)) for i in range(n)})
                idents = _Names()
                f["enum"] = {v: [b.ident(VALUE_IDENTS, idents, 0.1), b.zh()] for v in vals}
            elif b.p(0.5):
                rlo = max(lo, 0) + b.ch.integer(0, 10)
                rhi = rlo + b.ch.integer(0, 100)
                rhi = min(rhi, hi)
                f["range"] = [rlo, rhi]
                if lo < rlo and b.p(0.4):
                    f["sentinel"] = {rlo - 1: ["unknown", "未知"]}
        elif t["json"] == "number":
            if b.p(0.5):
                f["range"] = [Decimal(b.pick(("0", "-100", "-180", "-0.5"))), Decimal(b.pick(("100", "180", "0.5", "1000")))]
            if b.p(0.4):
                f["decimals"] = b.ch.integer(0, 6)
        elif t["json"] == "string" and kind == "ASCII" and b.p(0.5):
            letters = sorted({b.pick("NDRP-xyz") for _ in range(1 + b.ch.integer(0, 3))})
            idents = _Names()
            f["enum"] = {c: [b.ident(VALUE_IDENTS, idents, 0.1), b.zh()] for c in letters}
        if b.p(0.2):
            f["desc"] = b.text()
        if b.p(0.15) and key[0].islower():
            f["json_name"] = key
            f["name"] = key + "_value" if b.p(0.5) else key
        return f

    def message(self, names: _Names, frm: str, to: str, fields: list[Any], cmd: int | None, role: str | None = None,
                reply_to: str | None = None) -> dict[str, Any]:
        b = self.b
        m: dict[str, Any] = {"name": b.ident(("control", "status", "report", "ping", "query", "notice"), names, 0.05, ("request", "reply", "msg"))}
        if cmd is not None:
            m["cmd"] = cmd
            m["role"] = role
            if reply_to:
                m["reply_to"] = reply_to
        m["zh"] = b.zh()
        if b.p(0.3):
            m["desc"] = b.text()
        m["from"], m["to"] = frm, to
        m["fields"] = fields
        if b.p(0.7):
            m["examples"] = [self.example(fields, cmd) for _ in range(1 + b.ch.integer(0, 1))]
        return m

    def example(self, fields: list[Any], cmd: int | None) -> dict[str, Any]:
        shared = {
            "ts": {"type": "U64"}, "bn": {"type": "U64"}, "cmd": {"type": "U16"},
            "res": {"type": "S8", "enum": {0: 1, -1: 1}}, "reply_bn": {"type": "U64", "json_name": "bn"},
        }
        out: dict[str, Any] = {}
        for ref in fields:
            f = shared[ref] if isinstance(ref, str) else ref
            key = f.get("json_name", ref if isinstance(ref, str) else ref["name"])
            out[key] = cmd if key == "cmd" else self.value(f)
        return out

    def value(self, f: dict[str, Any]) -> Any:
        b = self.b
        t = self.TYPES[f["type"]]
        if "enum" in f:
            return b.pick(list(f["enum"]))
        if "sentinel" in f and b.p(0.3):
            return b.pick(list(f["sentinel"]))
        if t["json"] == "boolean":
            return b.p(0.5)
        if t["json"] == "string":
            return "x" * b.ch.integer(t["min_length"], min(t["max_length"], 4))
        if "range" in f:
            lo, hi = f["range"]
        else:
            lo, hi = max(t.get("min", -1000), -1000), min(t.get("max", 1000), 1000)
        if t["json"] == "integer":
            return b.ch.integer(int(lo), int(min(hi, lo + 1000)))
        v = Decimal(lo) + Decimal(b.ch.integer(0, 1000)) / 100
        return min(v, Decimal(hi))


def _text(doc: dict[str, Any]) -> str:
    """The document as YAML, one flow mapping per party, type, field and message key."""
    out = block({k: doc[k] for k in ("schema_version", "kind", "protocol")}, 0, 0)
    out += "parties:\n" + "".join(f"  - {flow(p)}\n" for p in doc["parties"])
    out += "types:\n" + "".join(f"  {k}: {flow(v)}\n" for k, v in doc["types"].items())
    out += "fields:\n" + "".join(f"  {k}: {flow(v)}\n" for k, v in doc["fields"].items())
    out += "messages:\n"
    for m in doc["messages"]:
        out += "  - " + "\n    ".join(f"{_scalar(k)}: {flow(v)}" for k, v in m.items()) + "\n"
    return out
