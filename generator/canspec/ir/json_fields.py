"""The JSON protocol as every JSON target sees it: per-field validation rules (in the order
every binding checks them, with the rule texts all languages print), enum types, and the
dispatch plan that tells the messages of a protocol apart.

Dispatch: a message carrying `cmd` is a command; within one `cmd`, and among the messages
without `cmd`, a message is recognised by a key only it has (a reply by `res`, control by
`tr`/`bk`/`st`/`vts`); the one message of a group without such a key is the default. A
receiver that knows the direction (it only ever receives what is sent to it) needs fewer
rules: plans exist for the whole protocol and for each receiving party.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.names import pascal, snake

# A reply answers the request with the same `cmd` and `bn` (对应服务器端请求的流水号).
MATCH_KEYS = ("cmd", "bn")
ERROR_CODES = ("object", "required", "unexpected", "type", "type_range", "enum", "range", "length", "cmd")


@dataclass(frozen=True)
class EnumType:
    name: str  # PascalCase type name
    json_type: str  # integer | string
    values: tuple[ir.JsonEnumValue, ...]


@dataclass(frozen=True)
class FieldRule:
    field: ir.JsonField
    key: str  # JSON key
    ident: str  # snake_case identifier in bindings
    kind: str  # integer | number | boolean | string
    type_lo: int | float | None
    type_hi: int | float | None
    enum: EnumType | None
    const: int | None  # the `cmd` of a command message
    lo: int | float | None  # documented range
    hi: int | float | None
    sentinels: tuple[ir.JsonEnumValue, ...]
    type_rule: str
    type_range_rule: str
    value_rule: str  # enum / documented range / const / length rule text ("" when none)

    @property
    def has_type_range(self) -> bool:
        return self.kind in ("integer", "number") and (self.type_lo is not None or self.type_hi is not None)

    @property
    def has_range(self) -> bool:
        return self.lo is not None or self.hi is not None


@dataclass(frozen=True)
class MessageModel:
    message: ir.JsonMessage
    type_name: str  # PascalCase
    rules: tuple[FieldRule, ...]  # every JSON key, in document order
    markers: tuple[str, ...]  # keys that select this message in the whole-protocol plan

    @property
    def name(self) -> str:
        return self.message.name

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(r.key for r in self.rules)

    @property
    def data_rules(self) -> tuple[FieldRule, ...]:
        """Fields other than the constant `cmd`."""
        return tuple(r for r in self.rules if r.const is None)

    def rule(self, key: str) -> FieldRule:
        return next(r for r in self.rules if r.key == key)


@dataclass(frozen=True)
class Branch:
    message: str
    markers: tuple[str, ...]  # any of these keys present selects it; () = the group's default


@dataclass(frozen=True)
class Plan:
    receiver: str | None  # None: any message of the protocol
    commands: tuple[tuple[int, tuple[Branch, ...]], ...]
    plain: tuple[Branch, ...]  # messages without `cmd`

    @property
    def command_values(self) -> tuple[int, ...]:
        return tuple(c for c, _ in self.commands)

    @property
    def messages(self) -> tuple[str, ...]:
        return tuple(b.message for _, g in self.commands for b in g) + tuple(b.message for b in self.plain)


@dataclass(frozen=True)
class Pair:
    request: str
    reply: str
    cmd: int
    echoed: tuple[str, ...]  # reply keys copied from the request (bn)
    extra: tuple[str, ...]  # reply keys the replier supplies besides res (e.g. ro)


@dataclass(frozen=True)
class ProtocolModel:
    protocol: ir.JsonProtocol
    messages: tuple[MessageModel, ...]
    enums: tuple[EnumType, ...]
    plans: tuple[Plan, ...]  # whole protocol first, then one per receiving party
    pairs: tuple[Pair, ...]

    def message(self, name: str) -> MessageModel:
        return next(m for m in self.messages if m.name == name)

    @property
    def any_plan(self) -> Plan:
        return self.plans[0]

    def plan_for(self, receiver: str | None) -> Plan:
        return next(p for p in self.plans if p.receiver == receiver)


def number(value: Fraction | float | None) -> int | float | None:
    """A bound as the JSON number a schema or binding carries: integral values as int."""
    if value is None:
        return None
    if isinstance(value, float):
        return int(value) if value.is_integer() and abs(value) < 2**63 else value
    f = Fraction(value)
    return f.numerator if f.denominator == 1 else float(f)


def literal(value: float | str) -> str:
    """JSON-ish text of a value, as rule texts show it (strings quoted)."""
    if isinstance(value, str):
        return '"' + value + '"'
    return repr(value)


def _interval(lo: float | None, hi: float | None) -> str:
    return f"[{'-inf' if lo is None else literal(lo)}, {'inf' if hi is None else literal(hi)}]"


def _enum_types(protocol: ir.JsonProtocol) -> dict[tuple[str, str], EnumType]:
    """Enum type per (message, field): one type per distinct value set, named after the field,
    or after message and field where one field name carries different value sets."""
    sets: dict[str, set[tuple[object, ...]]] = {}
    for m in protocol.messages:
        for f in m.fields:
            if f.enum:
                sets.setdefault(f.name, set()).add(tuple(e.value for e in f.enum))
    out: dict[tuple[str, str], EnumType] = {}
    for m in protocol.messages:
        for f in m.fields:
            if f.enum:
                name = pascal(f.name) if len(sets[f.name]) == 1 else pascal(f"{m.name}_{f.name}")
                kind = "string" if all(isinstance(e.value, str) for e in f.enum) else "integer"
                out[(m.name, f.json_name)] = EnumType(name, kind, f.enum)
    return out


def _rule(m: ir.JsonMessage, f: ir.JsonField, enum: EnumType | None) -> FieldRule:
    kind = f.json_type
    const = m.cmd if f.json_name == "cmd" and m.cmd is not None else None
    type_lo, type_hi = number(f.type_min), number(f.type_max)
    lo, hi = number(f.min), number(f.max)
    type_rule = {
        "integer": f"must be an integer ({f.type})",
        "number": f"must be a number ({f.type})",
        "boolean": f"must be true or false ({f.type})",
        "string": f"must be a string ({f.type})",
    }[kind]
    type_range_rule = f"must be within {_interval(type_lo, type_hi)} ({f.type})" if kind in ("integer", "number") else ""
    if const is not None:
        value_rule = f"must be {const} (the cmd of {m.name})"
    elif enum is not None:
        value_rule = "must be one of " + ", ".join(literal(e.value) for e in enum.values)
    elif lo is not None or hi is not None:
        value_rule = f"must be within {_interval(lo, hi)}"
        if f.sentinels:
            value_rule += " or " + ", ".join(f"{literal(s.value)} ({s.name})" for s in f.sentinels)
    elif kind == "string" and (f.min_length is not None or f.max_length is not None):
        value_rule = f"must be {f.min_length}..{f.max_length} characters ({f.type})"
    else:
        value_rule = ""
    return FieldRule(
        field=f, key=f.json_name, ident=snake(f.name), kind=kind, type_lo=type_lo, type_hi=type_hi, enum=enum, const=const,
        lo=lo, hi=hi, sentinels=f.sentinels, type_rule=type_rule, type_range_rule=type_range_rule, value_rule=value_rule,
    )


def _group(members: list[ir.JsonMessage]) -> tuple[Branch, ...]:
    """Order a group so that every message but the last is selected by a key only it has."""
    keys = {m.name: {f.json_name for f in m.fields} for m in members}
    unique = {}
    for m in members:
        others = set().union(*(keys[o.name] for o in members if o is not m)) if len(members) > 1 else set()
        unique[m.name] = tuple(f.json_name for f in m.fields if f.json_name not in others)
    ordered = sorted(members, key=lambda m: not unique[m.name])  # stable: document order otherwise
    if len(ordered) > 1 and not unique[ordered[-2].name]:
        raise ValueError(f"JSON messages {ordered[-2].name!r} and {ordered[-1].name!r} have no key that tells them apart")
    return tuple(Branch(m.name, unique[m.name] if i < len(ordered) - 1 else ()) for i, m in enumerate(ordered))


def plan(protocol: ir.JsonProtocol, receiver: str | None) -> Plan:
    members = [m for m in protocol.messages if receiver is None or m.receiver == receiver]
    cmds: dict[int, list[ir.JsonMessage]] = {}
    for m in members:
        if m.cmd is not None:
            cmds.setdefault(m.cmd, []).append(m)
    plain = [m for m in members if m.cmd is None]
    return Plan(receiver, tuple((c, _group(g)) for c, g in sorted(cmds.items())), _group(plain) if plain else ())


def _pairs(protocol: ir.JsonProtocol) -> tuple[Pair, ...]:
    out = []
    for rep in protocol.messages:
        if rep.role != "reply" or rep.reply_to is None:
            continue
        req = protocol.message(rep.reply_to)
        req_keys = {f.json_name for f in req.fields}
        rep_keys = [f.json_name for f in rep.fields]
        for key in MATCH_KEYS:
            if key not in req_keys or key not in rep_keys:
                raise ValueError(f"{req.name!r}/{rep.name!r}: a request and its reply both carry {key!r} (matching by {', '.join(MATCH_KEYS)})")
        extra = tuple(k for k in rep_keys if k not in MATCH_KEYS and k != "res")
        out.append(Pair(req.name, rep.name, int(rep.cmd or 0), tuple(k for k in MATCH_KEYS if k != "cmd"), extra))
    return tuple(out)


def model(protocol: ir.JsonProtocol) -> ProtocolModel:
    enums = _enum_types(protocol)
    whole = plan(protocol, None)
    markers = {b.message: b.markers for _, g in whole.commands for b in g} | {b.message: b.markers for b in whole.plain}
    messages = tuple(
        MessageModel(m, pascal(m.name), tuple(_rule(m, f, enums.get((m.name, f.json_name))) for f in m.fields), markers.get(m.name, ()))
        for m in protocol.messages
    )
    for mm in messages:
        idents = [r.ident for r in mm.rules]
        clash = sorted({i for i in idents if idents.count(i) > 1})
        if clash:
            raise ValueError(f"JSON message {mm.name!r}: fields share the binding identifier(s) {', '.join(clash)} (give each a distinct `name`)")
    unique_enums: dict[str, EnumType] = {}
    for e in enums.values():
        unique_enums.setdefault(e.name, e)
    receivers = sorted({m.receiver for m in protocol.messages})
    plans = (whole, *(plan(protocol, r) for r in receivers))
    return ProtocolModel(protocol, messages, tuple(unique_enums.values()), plans, _pairs(protocol))


def select(plan_: Plan, obj: object) -> str | None:
    """Reference dispatch: the message `obj` is read as under `plan_` (None: not an object or
    an unknown `cmd`). Every binding and schema implements exactly this."""
    if not isinstance(obj, dict):
        return None
    if plan_.commands and "cmd" in obj:
        cmd = obj["cmd"]
        if isinstance(cmd, bool) or not isinstance(cmd, (int, float)) or (isinstance(cmd, float) and not cmd.is_integer()):
            return None
        group = dict(plan_.commands).get(int(cmd))
        return None if group is None else _pick(group, obj)
    if not plan_.plain:
        return None
    return _pick(plan_.plain, obj)


def _pick(group: tuple[Branch, ...], obj: dict) -> str:  # type: ignore[type-arg]
    for b in group[:-1]:
        if any(k in obj for k in b.markers):
            return b.message
    return group[-1].message
