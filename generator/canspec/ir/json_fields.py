"""The JSON protocol as every JSON target sees it: per-field validation rules (in the order
every binding checks them, with the rule texts all languages print), type names, enum types,
request/reply pairs, and the dispatch plan that tells the messages of a protocol apart.

Check order (every binding, the schemas' error fields and reference/jsonvalue.py): the value is
an object; every key is present (in document order); no other key (the least one in code-point
order); a command's `cmd`; then each other field in document order — its JSON type, its declared
type's range (or a string's length), then its documented values (enum, or range and sentinels).

Dispatch: a message whose `cmd` key carries its command number is a command; within one `cmd`,
and among the other messages, a message is recognised by a key only it has among those not yet
told apart (a reply by `res`, control by `tr`/`bk`/`st`/`vts`); messages that no key tells
apart (the same keys) are tried in document order — the first the object is valid as; the last
message of a group is its default. A receiver that knows the direction (it only ever receives
what is sent to it) needs fewer rules: plans exist for the whole protocol and for each
receiving party.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from fractions import Fraction

from canspec import ir
from canspec.ir.names import pascal, snake

CMD_KEY = "cmd"  # carries a command message's number
RESULT_KEY = "res"  # a reply's result
MATCH_KEY = "bn"  # a reply echoes its request's sequence number (对应服务器端请求的流水号) when both carry it
ERROR_CODES = ("object", "required", "unexpected", "type", "type_range", "enum", "range", "length", "cmd")
# The bindings' readers of JSON text refuse, besides: text that is not JSON (NaN and Infinity
# included), and a key given twice in an object.
TEXT_ERROR_CODES = ("json", "duplicate")
# Names the bindings define or import themselves (Python, Rust and its prelude, TypeScript): a
# message, enum or receiver type never takes one of them.
RESERVED_TYPE_NAMES = frozenset({
    "Any", "ClassVar", "NoReturn", "None", "True", "False", "ValidationError", "PendingRequests",
    "Message", "Request", "Reply", "ErrorCode", "Party", "Value", "Map", "Serialize", "Deserialize", "Serializer", "Deserializer", "Option", "Result",
    "Some", "Ok", "Err", "String", "Vec", "Box", "Self", "Clone", "Copy", "Debug", "Default", "Eq", "PartialEq", "Ord", "PartialOrd", "Hash", "Send",
    "Sync", "Sized", "Unpin", "Drop", "Fn", "FnMut", "FnOnce", "From", "Into", "TryFrom", "TryInto", "AsRef", "AsMut", "Iterator", "IntoIterator",
    "Extend", "FromIterator", "ToOwned", "ToString", "Protocol", "Version", "ReplyByCmd", "ReplyTo",
})


@dataclass(frozen=True)
class EnumType:
    name: str  # PascalCase type name
    json_type: str  # integer | string
    values: tuple[ir.JsonEnumValue, ...]


@dataclass(frozen=True)
class FieldRule:
    field: ir.JsonField
    key: str  # JSON key
    ident: str  # snake_case identifier in bindings (each language escapes its keywords)
    kind: str  # integer | number | boolean | string
    type_lo: int | float | None
    type_hi: int | float | None
    enum: EnumType | None
    const: int | None  # the `cmd` of a command message
    lo: int | float | None  # documented range (an integer field's: the integers within it)
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
        return self.kind in ("integer", "number") and (self.lo is not None or self.hi is not None)

    @property
    def length_rule(self) -> str:
        lo, hi, t = self.field.min_length, self.field.max_length, self.field.type
        if lo is not None and hi is not None:
            return f"must be {lo}..{hi} characters ({t})"
        if lo is not None or hi is not None:
            return f"must be {'at least' if hi is None else 'at most'} {hi if lo is None else lo} characters ({t})"
        return ""


@dataclass(frozen=True)
class MessageModel:
    message: ir.JsonMessage
    type_name: str  # PascalCase, unique in the protocol and never a name the bindings use themselves
    rules: tuple[FieldRule, ...]  # every JSON key, in document order

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

    @property
    def const_rule(self) -> FieldRule | None:
        """The `cmd` key of a command message (checked before the other fields)."""
        return next((r for r in self.rules if r.const is not None), None)

    def rule(self, key: str) -> FieldRule:
        return next(r for r in self.rules if r.key == key)


@dataclass(frozen=True)
class Branch:
    message: str
    markers: tuple[str, ...]  # any of these keys present selects it
    tried: bool = False  # no key tells it apart: selected when the object is valid as it


@dataclass(frozen=True)
class Plan:
    receiver: str | None  # None: any message of the protocol
    commands: tuple[tuple[int, tuple[Branch, ...]], ...]
    plain: tuple[Branch, ...]  # messages without `cmd`
    type_name: str  # the type of what the receiver receives (TypeScript `To<Receiver>`); "" for the whole protocol

    @property
    def command_values(self) -> tuple[int, ...]:
        return tuple(c for c, _ in self.commands)

    @property
    def messages(self) -> tuple[str, ...]:
        return tuple(b.message for _, g in self.commands for b in g) + tuple(b.message for b in self.plain)

    @property
    def command_rule(self) -> str:
        return f"must be one of {', '.join(str(c) for c in self.command_values)} (a known command)"

    @property
    def rules(self) -> tuple[str, ...]:
        """How this plan tells the messages apart, in words (schemas and binding docs)."""
        out = []
        plain_prefix = "without `cmd`, " if self.commands else ""
        if self.commands:
            listing = ", ".join(f"{c}: " + " / ".join(b.message for b in g) for c, g in self.commands)
            out.append(f"a message with `cmd` is the command of that number ({listing})")
            for c, g in self.commands:
                out += [f"with cmd {c}, {_branch_text(b)}, otherwise {g[-1].message}" for b in g[:-1]]
        out += [plain_prefix + _branch_text(b) for b in self.plain[:-1]]
        if self.plain:
            out.append(f"{plain_prefix}the message is {self.plain[-1].message}" + (" otherwise" if len(self.plain) > 1 else ""))
        return tuple(out)


def _branch_text(b: Branch) -> str:
    return f"a message valid as {b.message} is {b.message}" if b.tried else f"a message carrying {' or '.join(b.markers)} is {b.message}"


@dataclass(frozen=True)
class Pair:
    request: str
    reply: str
    cmd: int
    echoed: tuple[str, ...]  # reply keys copied from the request (bn)
    result: str | None  # the reply's result key (res), if it has one
    extra: tuple[str, ...]  # other reply keys the replier supplies (e.g. ro)


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

    @property
    def receiver_plans(self) -> tuple[Plan, ...]:
        return self.plans[1:]

    @property
    def replies_by_cmd(self) -> bool:
        """Each request carries its `cmd` and no two pairs share one: the cmd names the reply type."""
        cmds = [p.cmd for p in self.pairs]
        return len(set(cmds)) == len(cmds) and all(self.message(p.request).const_rule is not None for p in self.pairs)


def number(value: Fraction | float | None) -> int | float | None:
    """A bound as the JSON number a schema or binding carries: integral values as int."""
    if value is None:
        return None
    if isinstance(value, float):
        return int(value) if value.is_integer() and abs(value) < 2**63 else value
    f = Fraction(value)
    return f.numerator if f.denominator == 1 else float(f)


def literal(value: float | str) -> str:
    """JSON-ish text of a value, as rule texts show it (strings quoted and escaped as JSON writes them)."""
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    return repr(value)


def _interval(lo: float | None, hi: float | None) -> str:
    return f"[{'-inf' if lo is None else literal(lo)}, {'inf' if hi is None else literal(hi)}]"


def _allocate(base: str, suffix: str, taken: set[str]) -> str:
    """`base`, or `base` + `suffix` (+ a number) where that name is taken or reserved."""
    name, n = base, 1
    while name in taken or name in RESERVED_TYPE_NAMES:
        name = f"{base}{suffix}" + (str(n) if n > 1 else "")
        n += 1
    taken.add(name)
    return name


def _enum_types(protocol: ir.JsonProtocol, taken: set[str]) -> dict[tuple[str, str], EnumType]:
    """Enum type per (message, key): one type per distinct value set, named after the field, or
    after message and field where one field name carries different value sets."""
    sets: dict[str, set[tuple[object, ...]]] = {}
    for m in protocol.messages:
        for f in m.fields:
            if f.enum:
                sets.setdefault(f.name, set()).add(tuple(e.value for e in f.enum))
    out: dict[tuple[str, str], EnumType] = {}
    by_base: dict[tuple[str, tuple[object, ...]], EnumType] = {}
    for m in protocol.messages:
        for f in m.fields:
            if f.enum:
                base = pascal(f.name) if len(sets[f.name]) == 1 else pascal(f"{m.name}_{f.name}")
                values = tuple(e.value for e in f.enum)
                if (base, values) not in by_base:
                    kind = "string" if all(isinstance(e.value, str) for e in f.enum) else "integer"
                    by_base[(base, values)] = EnumType(_allocate(base, "Value", taken), kind, f.enum)
                out[(m.name, f.json_name)] = by_base[(base, values)]
    return out


def _rule(m: ir.JsonMessage, f: ir.JsonField, enum: EnumType | None) -> FieldRule:
    kind = f.json_type
    const = m.cmd if f.json_name == CMD_KEY and m.cmd is not None else None
    type_lo, type_hi = number(f.type_min), number(f.type_max)
    lo: int | float | None = number(f.min)
    hi: int | float | None = number(f.max)
    if kind == "integer":  # the integers within the documented range
        lo, hi = (None if f.min is None else math.ceil(f.min)), (None if f.max is None else math.floor(f.max))
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
    elif kind in ("integer", "number") and (lo is not None or hi is not None):
        value_rule = f"must be within {_interval(lo, hi)}"
        if f.sentinels:
            value_rule += " or " + ", ".join(f"{literal(s.value)} ({s.name})" for s in f.sentinels)
    else:
        value_rule = ""
    rule = FieldRule(
        field=f, key=f.json_name, ident=snake(f.name), kind=kind, type_lo=type_lo, type_hi=type_hi, enum=enum, const=const,
        lo=lo, hi=hi, sentinels=f.sentinels, type_rule=type_rule, type_range_rule=type_range_rule, value_rule=value_rule,
    )
    return rule if value_rule or kind != "string" else replace(rule, value_rule=rule.length_rule)


def _group(members: list[ir.JsonMessage]) -> tuple[Branch, ...]:
    """Order a group: round by round, the messages with a key no other remaining message has
    (document order); messages no key tells apart are tried; the last message is the default."""
    keys = {m.name: [f.json_name for f in m.fields] for m in members}
    remaining, branches = list(members), []
    while len(remaining) > 1:
        unique = {}
        for m in remaining:
            others = set().union(*(keys[o.name] for o in remaining if o is not m))
            unique[m.name] = tuple(k for k in keys[m.name] if k not in others)
        if not any(unique.values()):
            branches += [Branch(m.name, (), tried=True) for m in remaining[:-1]]
            remaining = remaining[-1:]
            break
        branches += [Branch(m.name, unique[m.name]) for m in remaining if unique[m.name]]
        remaining = [m for m in remaining if not unique[m.name]]
    last = remaining[0].name if remaining else branches.pop().message
    return (*branches, Branch(last, ()))


def is_command(m: ir.JsonMessage) -> bool:
    """A command as dispatch sees it: its number travels in the `cmd` key."""
    return m.cmd is not None and any(f.json_name == CMD_KEY for f in m.fields)


def plan(protocol: ir.JsonProtocol, receiver: str | None, type_name: str = "") -> Plan:
    members = [m for m in protocol.messages if receiver is None or m.receiver == receiver]
    cmds: dict[int, list[ir.JsonMessage]] = {}
    for m in members:
        if is_command(m):
            cmds.setdefault(int(m.cmd or 0), []).append(m)
    plain = [m for m in members if not is_command(m)]
    return Plan(receiver, tuple((c, _group(g)) for c, g in sorted(cmds.items())), _group(plain) if plain else (), type_name)


def _pairs(protocol: ir.JsonProtocol) -> tuple[Pair, ...]:
    out = []
    for rep in protocol.messages:
        if rep.role != "reply" or rep.reply_to is None:
            continue
        req_keys = {f.json_name for f in protocol.message(rep.reply_to).fields}
        rep_keys = [f.json_name for f in rep.fields]
        echoed = tuple(k for k in (MATCH_KEY,) if k in req_keys and k in rep_keys)
        result = RESULT_KEY if RESULT_KEY in rep_keys else None
        extra = tuple(k for k in rep_keys if k not in echoed and k != result and k != CMD_KEY)
        out.append(Pair(rep.reply_to, rep.name, int(rep.cmd or 0), echoed, result, extra))
    return tuple(out)


def model(protocol: ir.JsonProtocol) -> ProtocolModel:
    taken: set[str] = set()
    type_names = {m.name: _allocate(pascal(m.name), "Message", taken) for m in protocol.messages}
    enums = _enum_types(protocol, taken)
    messages = tuple(
        MessageModel(m, type_names[m.name], tuple(_rule(m, f, enums.get((m.name, f.json_name))) for f in m.fields)) for m in protocol.messages
    )
    unique_enums: dict[str, EnumType] = {}
    for e in enums.values():
        unique_enums.setdefault(e.name, e)
    receivers = sorted({m.receiver for m in protocol.messages})
    plans = (plan(protocol, None), *(plan(protocol, r, _allocate(pascal(f"to_{r}"), "Messages", taken)) for r in receivers))
    return ProtocolModel(protocol, messages, tuple(unique_enums.values()), plans, _pairs(protocol))
