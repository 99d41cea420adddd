"""Value tables as Rust enums: one per table a signal uses, with a catch-all variant for the raw
values the table leaves undefined (unless it defines every value of the enum's type)."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from canspec import ir
from canspec.render.literals import RUST
from canspec.spec.problems import Problem, error
from canspec.targets.rust import docs
from canspec.targets.rust.bits import type_bounds
from canspec.targets.rust.naming import OTHER_VARIANT, variant_name

REPR_TYPES = ("u8", "i8", "u16", "i16", "u32", "i32", "u64", "i64")


@dataclass(frozen=True)
class RustVariant:
    name: str
    raw: str
    doc: str


@dataclass(frozen=True)
class RustEnum:
    name: str
    table: str
    repr: str  # the narrowest integer type holding every raw value of every signal using it
    variants: tuple[RustVariant, ...]
    other: str | None  # the catch-all variant; None when the table defines every value of `repr`
    other_tag: str  # discriminant of the catch-all: the first raw value the table leaves free
    halves: bool = False  # `raw()` as two halves (see raw_halves)


def enum_users(can: ir.CanProtocol) -> dict[str, list[ir.Signal]]:
    """The signals that decode to each value table's enum, by table name (sorted)."""
    users: dict[str, list[ir.Signal]] = {}
    for msg in can.messages:
        for s in msg.data_signals:
            if s.value_table is not None and s.decodes_to_enum and s.role != "checksum":
                users.setdefault(s.value_table.name, []).append(s)
    return dict(sorted(users.items()))


def repr_type(signals: list[ir.Signal]) -> str | None:
    """The narrowest Rust integer holding the raw values of all these fields; None if none does
    (a 64-bit unsigned field and a signed one)."""
    lo = min(s.raw_type_min for s in signals)
    hi = max(s.raw_type_max for s in signals)
    return next((t for t in REPR_TYPES if type_bounds(t)[0] <= lo and hi <= type_bounds(t)[1]), None)


def problems(users: dict[str, list[ir.Signal]]) -> Iterator[Problem]:
    for table, signals in users.items():
        if repr_type(signals) is None:
            wide = next(s for s in signals if not s.signed)
            signed = next(s for s in signals if s.signed)
            yield error(
                f"value table {table!r} is used by the 64-bit unsigned field {wide.name!r} and the signed field {signed.name!r}: "
                "no Rust integer type holds the raw values of both",
                signed.loc,
                "give the signed field a value table of its own",
                "rust-value-table-width",
            )


def raw_halves(table: ir.ValueTable, signals: list[ir.Signal]) -> bool:
    """Whether `raw()` is written as two halves (table value or 0) | (payload or 0) rather than
    one match: true when the fields' bits can carry two or more values the table leaves out.
    A getter's `from_raw(x).raw()` is then a switch whose default covers several values, and
    LLVM folds the one match back to `x` only in the i8 it matched in, not once the result is
    widened (`raw() as u64`: a compare and a select per read); the halves fold. With at most one
    value left out the switch covers every value the bits carry and the one match folds, where
    the halves leave LLVM a compare with the catch-all (2-bit fields of 3 values)."""
    lo = min(s.raw_type_min for s in signals)
    hi = max(s.raw_type_max for s in signals)
    named = {e.raw for e in table.entries if lo <= e.raw <= hi}
    return hi - lo + 1 - len(named) >= 2


def build_enum(table: ir.ValueTable, signals: list[ir.Signal], name: str) -> RustEnum:
    repr_ = repr_type(signals)
    assert repr_ is not None, "refused by `canspec check` (rust-value-table-width)"
    variants = tuple(RustVariant(variant_name(e.name), RUST.integer(e.raw), docs.variant_doc(e)) for e in table.entries)
    used = {e.raw for e in table.entries}
    lo, hi = type_bounds(repr_)
    free = next((v for v in range(hi + 1) if v not in used), None) if len(used) <= hi - lo else None
    if free is None and len(used) <= hi - lo:
        free = next(v for v in range(-1, lo - 1, -1) if v not in used)
    return RustEnum(name, table.name, repr_, variants, OTHER_VARIANT if free is not None else None, RUST.integer(free) if free is not None else "",
                    free is not None and raw_halves(table, signals))

