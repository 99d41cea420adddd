"""The IR of a JSON protocol (the remote-driving messages): its parties, messages and fields."""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from canspec.spec.problems import Loc


@dataclass(frozen=True)
class JsonEnumValue:
    value: int | str
    name: str
    label_zh: str
    label: str
    loc: Loc | None = field(default=None, compare=False, hash=False)


@dataclass(frozen=True)
class JsonField:
    name: str  # identifier in bindings
    json_name: str  # key on the wire
    type: str  # the document's type name: U8, S16, U64, Float32, BOOL, ASCII ...
    json_type: str  # integer | number | boolean | string
    type_min: int | float | None
    type_max: int | float | None
    min: Fraction | None  # documented value range (None: the type's range)
    max: Fraction | None
    decimals: int | None
    unit: str
    enum: tuple[JsonEnumValue, ...]
    sentinels: tuple[JsonEnumValue, ...]
    min_length: int | None
    max_length: int | None
    zh: str
    desc: str
    desc_zh: str
    errata: tuple[str, ...]
    loc: Loc | None = field(default=None, compare=False, hash=False)  # the field's definition
    type_loc: Loc | None = field(default=None, compare=False, hash=False)  # its type's definition


@dataclass(frozen=True)
class JsonMessage:
    name: str
    zh: str
    desc: str
    cmd: int | None
    role: str | None  # "request" | "reply" | None
    reply_to: str | None
    sender: str
    receiver: str
    fields: tuple[JsonField, ...]
    examples: tuple[dict, ...]  # type: ignore[type-arg]
    loc: Loc | None = field(default=None, compare=False, hash=False)


@dataclass(frozen=True)
class JsonParty:
    name: str
    zh: str
    desc: str


@dataclass(frozen=True)
class JsonProtocol:
    name: str
    title: str
    title_zh: str
    version: str
    parties: tuple[JsonParty, ...]
    messages: tuple[JsonMessage, ...]
    errata: tuple[str, ...]
    loc: Loc | None = field(default=None, compare=False, hash=False)  # its `name`

    def message(self, name: str) -> JsonMessage:
        return next(m for m in self.messages if m.name == name)
