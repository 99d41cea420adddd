"""Rust names of the generated crate, and the clashes `canspec check` refuses.

Spec names are lower_snake (`^[a-z][a-z0-9_]*$`); Rust wants snake_case values and PascalCase
types without doubled underscores, so `a__b` and `a_b` (or `x_1` and `x1` as types) become the
same Rust name. Keywords and the names the generated modules use unqualified are escaped
deterministically (`r#type`, `self_`, `Option_`), a value table named like a message gets `Value`
after its type name (`GearValue`); two spec names that still meet are refused
(rule `rust-name-clash`): renaming one of them is the user's choice, not the generator's.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from canspec import ir
from canspec.ir.names import pascal, rust_ident, snake, upper_snake
from canspec.spec.problems import Loc, Problem, error

OTHER_VARIANT = "_Other"  # catch-all of every value-table enum (as dbc-codegen names it)
# Type names the generated modules and tests use unqualified: the crate's own items and the
# Rust 2021 prelude (types, traits and variants). A message or table of that name gets a `_`.
RESERVED_TYPES = frozenset(
    {"Error", "Frame", "Messages", "Text", "Self"}
    | {"Option", "Some", "None", "Result", "Ok", "Err", "Vec", "String", "Box", "ToString", "ToOwned", "Clone", "Copy", "Send", "Sync", "Sized",
       "Unpin", "Drop", "Fn", "FnMut", "FnOnce", "Iterator", "IntoIterator", "DoubleEndedIterator", "ExactSizeIterator", "Extend", "FromIterator",
       "From", "Into", "TryFrom", "TryInto", "AsRef", "AsMut", "Default", "Eq", "PartialEq", "Ord", "PartialOrd"}
)


def type_name(name: str) -> str:
    """A spec name as a Rust type (message, value table, their companions)."""
    out = pascal(name)
    return f"{out}_" if out in RESERVED_TYPES else out


def enum_type_names(can: ir.CanProtocol, tables: Iterable[str]) -> dict[str, str]:
    """Each value table's enum type: its PascalCase name, with `Value` after it where a message
    type takes that name (a message and a table named alike, `gear`, are common on real buses)."""
    messages = {type_name(m.name) for m in can.messages}
    return {t: f"{type_name(t)}Value" if type_name(t) in messages else type_name(t) for t in tables}


def variant_name(name: str) -> str:
    out = pascal(name)
    return f"{out}_" if out == "Self" else out


@dataclass(frozen=True)
class FieldNames:
    """Every Rust name one signal gives its message type."""

    base: str  # snake_case
    field: str  # struct field and parameter (keywords escaped)
    getter: str
    raw_getter: str
    setter: str
    raw_setter: str
    store: str  # private: puts a raw value into the frame word
    const: str  # UPPER_SNAKE prefix of its associated constants
    load: str  # multiplexed messages, private: the field's bits in the frame, present or not
    has: str  # multiplexed fields: whether the field is present (its page is selected)

    def members(self, sig: ir.Signal, multiplexed: bool) -> tuple[str, ...]:
        """The methods of the message type; `multiplexed`: the message is."""
        mux = (self.load, *((self.has,) if sig.mux is not None else ())) if multiplexed else ()
        return (self.getter, self.raw_getter, self.setter, self.raw_setter, self.store, *mux)


# The methods every message type has (or may have): a signal of that name gets a getter with a `_`.
FIXED_METHODS = frozenset({"new", "from_raw", "from_values", "values", "encode", "decode", "checksum", "with_next_counter", "text_frames"})


def field_names(sig: ir.Signal) -> FieldNames:
    base = snake(sig.name)
    getter = f"{base}_" if base in FIXED_METHODS else rust_ident(base)
    return FieldNames(base, rust_ident(base), getter, rust_ident(f"{base}_raw"), f"set_{base}", f"set_{base}_raw", f"store_{base}", upper_snake(base),
                      f"load_{base}", f"has_{base}")


def stored_signals(msg: ir.Message) -> tuple[ir.Signal, ...]:
    """The signals a message type stores and offers accessors for (the checksum is computed)."""
    return tuple(s for s in msg.data_signals if s.role != "checksum")


def message_consts(msg: ir.Message) -> list[str]:
    """The associated constants of a message type that do not come from one signal."""
    names = ["NAME", "FRAME_ID", "IS_EXTENDED", "DLC", "FINGERPRINT", "ZERO", "FIELDS_MASK"]
    names += ["NAME_ZH"] if msg.zh else []
    names += ["CYCLE_TIME_MS"] if msg.is_cyclic else []
    names += ["PRIORITY", "PGN", "SOURCE_ADDRESS", "DESTINATION_ADDRESS"] if msg.j1939 else []
    names += ["COUNTER_BITS"] if msg.counter else []
    names += ["TEXT_LEN", "TEXT_FRAMES", "TEXT_BYTES_PER_FRAME", "TEXT_PADDING"] if msg.multiframe else []
    return names


def message_methods(msg: ir.Message) -> list[str]:
    names = ["new", "from_raw", "from_values", "values", "encode", "decode"]
    names += ["checksum"] if msg.checksum else []
    names += ["with_next_counter"] if msg.counter else []
    names += ["text_frames"] if msg.multiframe else []
    return names


def signal_consts(sig: ir.Signal, names: FieldNames, scaled: bool) -> list[str]:
    """`scaled`: the signal has a physical range of its own (`_MIN`, `_MAX`, `_SCALE`)."""
    out = [f"{names.const}_{suffix}" for suffix in ("MIN", "MAX", "SCALE")] if scaled else []
    return out + [special_const(names, s) for s in sig.specials]


def special_const(names: FieldNames, special: ir.SpecialValue) -> str:
    return upper_snake(f"{names.base}_{special.name}")


def _bare(name: str) -> str:
    return name.removeprefix("r#")


TYPE_HINT = "rename one of them in the spec (Rust type names drop underscores: `x_1` and `x1` are both `X1`)"
MEMBER_HINT = ("rename one of them in the spec (a signal `x` has the methods `x`, `x_raw`, `set_x`, `set_x_raw`, in a multiplexed message also `load_x` "
               "and `has_x`, and the constants `X_MIN`, `X_MAX`)")


def _clashes(entries: Iterable[tuple[str, str, Loc | None]], scope: str, hint: str) -> Iterator[Problem]:
    """One problem per item whose name is already taken in `scope`, at that item."""
    seen: dict[str, str] = {}
    reported: set[str] = set()
    for name, what, loc in entries:
        key = _bare(name)
        if key not in seen:
            seen[key] = what
        elif what not in reported:
            reported.add(what)
            yield error(f"{what} becomes the Rust name `{key}` in {scope}, which {seen[key]} already has", loc, hint, "rust-name-clash")


def problems(can: ir.CanProtocol, enum_users: dict[str, list[ir.Signal]], scaled: Callable[[ir.Signal], bool]) -> Iterator[Problem]:
    """Every Rust name clash of the crate. `enum_users`: the signals of each value table the
    crate makes an enum of; `scaled(sig)`: the field has range constants of its own."""
    types: list[tuple[str, str, Loc | None]] = [(n, f"the crate's own {n}", None) for n in ("Error", "Frame", "Messages", "Text")]
    enums = enum_type_names(can, enum_users)
    types += [(enums[table], f"value table {table!r}", users[0].loc) for table, users in enum_users.items()]
    types += [(type_name(msg.name), f"message {msg.name!r}", msg.loc) for msg in can.messages]
    for msg in can.messages:
        types.append((f"{pascal(msg.name)}Values", f"the values struct of message {msg.name!r}", msg.loc))
        if msg.multiframe:
            types.append((f"{pascal(msg.name)}Text", f"the text assembler of message {msg.name!r}", msg.loc))
    yield from _clashes(types, "the crate", TYPE_HINT)
    for table, users in enum_users.items():
        entries = users[0].value_table.entries if users[0].value_table else ()
        yield from _clashes(((variant_name(e.name), f"value {e.name!r}", e.loc) for e in entries), f"enum {enums[table]}", TYPE_HINT)
    for msg in can.messages:
        sigs = [(s, field_names(s)) for s in stored_signals(msg)]
        scope = f"type {type_name(msg.name)}"
        yield from _clashes([*((n, f"the method {n}", None) for n in message_methods(msg)),
                             *((m, f"signal {s.name!r}", s.loc) for s, names in sigs for m in names.members(s, msg.is_multiplexed))], scope, MEMBER_HINT)
        yield from _clashes([*((n, f"the constant {n}", None) for n in message_consts(msg)),
                             *((c, f"signal {s.name!r}", s.loc) for s, names in sigs for c in signal_consts(s, names, scaled(s)))], scope, MEMBER_HINT)
