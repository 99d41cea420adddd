"""What a sheet holds, independent of the XLSX library: columns (bilingual header, width, wrap)
and rows of plain cell values. The sheet builders (matrix.py, sheets.py, errata.py) decide every
value; workbook.py only lays them out."""

from __future__ import annotations

from dataclasses import dataclass

Cell = str | int | float | None


def joined(*texts: str) -> str:
    """Texts side by side (English and Chinese, a number and its unit), the empty ones left out."""
    return " ".join(t for t in texts if t)


@dataclass(frozen=True)
class Column:
    key: str  # stable name (tests, builders)
    zh: str  # header, Chinese line ("" for none)
    en: str  # header, English line
    width: float  # in Excel character widths
    wrap: bool = False  # multi-line text: wrapped, rows grow
    center: bool = False  # short flags (S/R) read down the column
    optional: bool = False  # left out when no row has a value (e.g. Chinese names of an English-only spec)

    @property
    def header(self) -> str:
        return f"{self.zh}\n{self.en}" if self.zh else self.en


@dataclass(frozen=True)
class Sheet:
    name: str  # tab name (at most 31 characters)
    columns: tuple[Column, ...]
    rows: tuple[tuple[Cell, ...], ...]
    freeze_cols: int = 0  # columns kept in view when scrolling right
    bands: tuple[int, ...] = ()  # per row: 0/1, alternate shading by group (the matrix: by message)

    def column(self, key: str) -> int:
        return next(i for i, c in enumerate(self.columns) if c.key == key)


def sheet(name: str, columns: list[Column], rows: list[list[Cell]], freeze: str | None = None, bands: list[int] | None = None) -> Sheet:
    """A sheet without its empty optional columns; `freeze` names the last column kept in view."""
    keep = [i for i, c in enumerate(columns) if not c.optional or any(r[i] not in (None, "") for r in rows)]
    cols = tuple(columns[i] for i in keep)
    freeze_cols = next((n + 1 for n, c in enumerate(cols) if c.key == freeze), 0)
    return Sheet(name, cols, tuple(tuple(r[i] for i in keep) for r in rows), freeze_cols, tuple(bands or ()))
