"""Literal syntax and number text per target (Python owns it; templates call these filters)."""

from __future__ import annotations

import json
from fractions import Fraction

from canspec.ir.encoding import decimal_text


def num(value: Fraction | int | None) -> str:
    """Exact decimal text: 0.02, -1080, 0.0015."""
    return "" if value is None else decimal_text(Fraction(value))


def c_double(value: Fraction | int) -> str:
    text = decimal_text(Fraction(value))
    return text if any(c in text for c in ".eE") else f"{text}.0"


def hex32(value: int) -> str:
    return f"0x{value:08X}"


def hex_byte(value: int) -> str:
    return f"0x{value:02X}"


def c_string(text: str) -> str:
    """A C/Rust/JSON-compatible double-quoted string literal (UTF-8 kept)."""
    return json.dumps(text, ensure_ascii=False)


def dbc_string(text: str) -> str:
    """DBC strings cannot escape quotes: replace them."""
    return '"' + text.replace("\\", "/").replace('"', "'") + '"'


FILTERS = {
    "num": num,
    "c_double": c_double,
    "hex32": hex32,
    "hex_byte": hex_byte,
    "c_string": c_string,
    "dbc_string": dbc_string,
}
