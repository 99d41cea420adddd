"""Names for raw values: value tables, special values and the labels a field's raw values carry."""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from canspec.spec.problems import Loc


@dataclass(frozen=True)
class ValueEntry:
    raw: int
    name: str  # lower_snake identifier
    label_zh: str
    label: str  # English label derived from the identifier
    loc: Loc | None = field(default=None, compare=False, hash=False)
    dbc_text: str = ""  # the label the DBC writes where it is not `name` (a source's own text)


@dataclass(frozen=True)
class ValueTable:
    name: str
    entries: tuple[ValueEntry, ...]
    loc: Loc | None = field(default=None, compare=False, hash=False)

    def by_raw(self, raw: int) -> ValueEntry | None:
        return next((e for e in self.entries if e.raw == raw), None)


@dataclass(frozen=True)
class SpecialValue:
    raw: int
    name: str
    label_zh: str
    label: str
    physical: Fraction


@dataclass(frozen=True)
class Label:
    """A raw value with a name of its own: a value-table entry, or a special value (such as
    0x3FF "no obstacle") where the table has none for that raw value."""

    raw: int
    name: str
    label_zh: str
    label: str
    is_special: bool
    dbc_text: str = ""  # ValueEntry.dbc_text

    @property
    def dbc_label(self) -> str:
        return self.dbc_text or self.name
