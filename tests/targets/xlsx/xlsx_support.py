"""Reading the communication matrix back, independently of the generator: openpyxl for exact cell
values and formatting, pandas for a second reading of the same sheets. Cell texts are parsed here
with their own rules (hex bit patterns, value lines), never with the target's formatting helpers."""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import openpyxl
import pandas as pd
from canspec import ir

MATRIX = "通信矩阵 Matrix"
RAW = re.compile(r"^0x([0-9A-F]+)(?: \((-\d+)\))?$")
LINE = re.compile(r"^0x([0-9A-F]+)(?: \((-\d+)\))?: (.+)$")


@dataclass
class Book:
    data: bytes
    wb: Any  # openpyxl Workbook
    frames: dict[str, pd.DataFrame]

    def rows(self, sheet: str) -> list[dict[str, Any]]:
        """Data rows keyed by the header's English line."""
        ws = self.wb[sheet]
        values = list(ws.iter_rows(values_only=True))
        keys = [english(h) for h in values[0]]
        return [dict(zip(keys, r)) for r in values[1:]]

    def headers(self, sheet: str) -> list[str]:
        return [c.value for c in self.wb[sheet][1]]


def english(header: str) -> str:
    return header.split("\n")[-1]


def read(data: bytes) -> Book:
    wb = openpyxl.load_workbook(io.BytesIO(data))
    frames = pd.read_excel(io.BytesIO(data), sheet_name=None, engine="openpyxl")
    return Book(data, wb, frames)


def raw_value(sig: ir.Signal, text: str) -> int:
    """`0x200 (-512)` → -512: the hex digits are the field's bits; the value in parentheses must be
    their two's complement reading."""
    m = RAW.match(text)
    assert m, f"not a raw hex cell: {text!r}"
    bits = int(m.group(1), 16)
    assert bits < 1 << sig.length, text
    value = bits - (1 << sig.length) if sig.signed and bits >> (sig.length - 1) else bits
    assert (m.group(2) is not None) == (value < 0), f"{text!r}: a negative value (and only one) names itself"
    if m.group(2) is not None:
        assert int(m.group(2)) == value, text
    return value


def value_lines(sig: ir.Signal, text: str | None) -> list[tuple[int, str]]:
    out = []
    for line in (text or "").splitlines():
        m = LINE.match(line)
        assert m, f"not a value line: {line!r}"
        out.append((raw_value(sig, f"0x{m.group(1)}" + (f" ({m.group(2)})" if m.group(2) else "")), m.group(3)))
    return out


def same_number(cell: Any, value: Fraction | int) -> bool:
    """A number cell equal to the exact value as Excel shows it (15 digits), or its exact decimal text."""
    if isinstance(cell, str):
        return Fraction(cell) == value and len(cell.lstrip("-").replace(".", "").strip("0")) > 15
    if isinstance(cell, bool) or not isinstance(cell, (int, float)):
        return False
    return cell == float(value) and Fraction(f"{cell:.15g}") == value
